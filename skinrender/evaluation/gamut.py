"""
Gamut volumes
=============

The evaluator that analytic and rendered responses both feed: the convex-hull
volume of a cloud of RGB responses (Qhull, as Matlab's ``convhulln``), safe for
degenerate clouds, and the paper's two gamut cases.

-   :class:`Gamut`, :func:`gamut`: volume, point count and a ``degenerate`` flag.
-   :func:`gamut_volume`: the volume alone, 0.0 for a degenerate cloud.
-   :func:`to_unit_box`, :func:`is_flat`: the scale-free frame and flatness
    test that :mod:`~skinrender.evaluation.hull` shares.
-   :func:`gamut_calibration`: one calibration case (the union over the
    prevailing illuminants for one calibration illuminant).
-   :func:`gamut_all_calibrations`: the union over every (prevailing,
    calibration) pair.

Volumes are in output units cubed (Eq. 4 responses, v = 255).

References
----------
-   :cite:`Barber1996` : Barber, C. B., Dobkin, D. P., & Huhdanpaa, H. (1996).
    The Quickhull algorithm for convex hulls. ACM TOMS, 22(4), 469–483.
-   :cite:`Martinkauppi2006` : the paper, Stages 2 and 3; NOTES.md "Gamuts".
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..constants import TEMPERATURES_PAPER
from ..errors import SkinrenderError
from ..hints import ArrayLike, NDArrayFloat
from ..model.camera import Camera
from ..model.response import response
from ..spectra import GRID_DEFAULT, WavelengthGrid, float_array

__all__ = [
    "illuminant_temperatures",
    "TOLERANCE_GAMUT_FLATNESS",
    "COORDINATE_MAX",
    "Gamut",
    "gamut",
    "gamut_volume",
    "gamut_hull",
    "is_flat",
    "to_unit_box",
    "gamut_calibration",
    "gamut_all_calibrations",
]

COORDINATE_MAX = 1e100
"""Largest coordinate of a gamut point (output units are ~1–1e4); beyond, volumes overflow float64."""

TOLERANCE_GAMUT_FLATNESS = 1e-10
"""A cloud whose smallest principal extent is below this fraction of its
largest is flat (coplanar, collinear or coincident): its volume is 0 and it is
flagged degenerate rather than handed to Qhull, which fails or returns round-off
noise on such input. 1e-10 is far above float64 round-off on responses of
order 1–1000 and far below any real gamut's aspect ratio."""


@dataclass(frozen=True)
class Gamut:
    """A gamut: ``volume`` (output units³), ``points`` (count) and ``degenerate``."""

    volume: float
    points: int
    degenerate: bool


def gamut(points: ArrayLike) -> Gamut:
    """
    The convex-hull gamut of a cloud of responses.

    Parameters
    ----------
    points
        Responses with channels on the last axis, shape ``(..., 3)``, output units.

    Returns
    -------
    :class:`Gamut`
        Volume 0.0 and ``degenerate=True`` for fewer than four distinct points
        or a flat cloud (coplanar, collinear, coincident), never an exception.

    Raises
    ------
    SkinrenderError
        For NaN or infinite coordinates, or a last axis other than 3.

    Examples
    --------
    >>> gamut(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])).volume  # doctest: +ELLIPSIS
    0.1666...
    """

    return gamut_hull(points)[0]


def gamut_hull(points: ArrayLike) -> tuple[Gamut, np.ndarray]:
    """
    :func:`gamut` and the indices of the hull's vertices in the flattened cloud.

    For a degenerate cloud the indices are every point's (none can be ruled out).
    """

    cloud = float_array(points, "points")
    if cloud.shape[-1:] != (3,):
        raise SkinrenderError(f"points (gamut) must have three channels on the last axis, got shape {cloud.shape}",
                              role="points")
    cloud = cloud.reshape(-1, 3)
    if not np.all(np.isfinite(cloud)):
        raise SkinrenderError("gamut points contain NaN or inf")
    count = cloud.shape[0]
    every = np.arange(count)
    if count < 4:
        return Gamut(0.0, count, True), every
    if np.max(np.abs(cloud)) > COORDINATE_MAX:
        raise SkinrenderError(f"gamut points beyond ±{COORDINATE_MAX:g}: their volume would overflow float64")
    boxed = to_unit_box(cloud)
    if boxed is None:
        return Gamut(0.0, count, True), every
    unit, scale = boxed
    if is_flat(unit):
        return Gamut(0.0, count, True), every
    from scipy.spatial import ConvexHull, QhullError  # here: a heavy import most commands never use

    try:
        hull = ConvexHull(unit)
    except QhullError:
        return Gamut(0.0, count, True), every
    return Gamut(float(hull.volume * np.prod(scale)), count, False), hull.vertices


def to_unit_box(cloud: NDArrayFloat) -> tuple[NDArrayFloat, NDArrayFloat] | None:
    """
    ``cloud`` ``(n, 3)`` centred and each axis scaled to [-1, 1], and the scales (output units): flatness and
    Qhull alike are then scale-free, and the hull's volume is the unit one times the scales' product.
    ``None`` where an axis has no extent (or is not finite).

    Examples
    --------
    >>> unit, scale = to_unit_box(np.array([[0.0, 0.0, 0.0], [2.0, 4.0, 8.0]]))
    >>> unit[1].tolist(), scale.tolist()
    ([1.0, 1.0, 1.0], [1.0, 2.0, 4.0])
    """
    centred = cloud - cloud.mean(axis=0)
    scale = np.max(np.abs(centred), axis=0)
    if not np.all(scale > 0):
        return None
    return centred / scale, scale


def is_flat(points: NDArrayFloat) -> bool:
    """
    Whether a cloud ``(n, 3)`` is flat (coplanar, collinear or coincident): its
    smallest principal extent is at most :data:`TOLERANCE_GAMUT_FLATNESS` of
    its largest (or it has no extent at all).
    """
    extents = np.linalg.svd(points - points.mean(axis=0), compute_uv=False)
    return bool(extents[0] == 0 or extents[-1] <= TOLERANCE_GAMUT_FLATNESS * extents[0])


def gamut_volume(points: ArrayLike) -> float:
    """The convex-hull volume of ``points`` (output units³); 0.0 for a degenerate cloud."""
    return gamut(points).volume


def gamut_calibration(
    camera_: Camera | str,
    reflectance,
    calibration: float | str,
    illuminants: ArrayLike = TEMPERATURES_PAPER,
    normalization: str = "white",
    knee: bool = False,
    grid: WavelengthGrid = GRID_DEFAULT,
) -> Gamut:
    """
    One calibration case: the hull of the responses under every prevailing
    illuminant of the set, all white-balanced to ``calibration`` (K).

    With the paper's ten illuminants that is one canonical case (p = c) and nine
    uncanonical ones.
    """

    prevailing = illuminant_temperatures(illuminants, camera_)
    return gamut(response(camera_, reflectance, prevailing, calibration, normalization, knee, grid))


def gamut_all_calibrations(
    camera_: Camera | str,
    reflectance,
    illuminants: ArrayLike = TEMPERATURES_PAPER,
    normalization: str = "white",
    knee: bool = False,
    grid: WavelengthGrid = GRID_DEFAULT,
) -> Gamut:
    """All calibrations: the hull of the union over every (prevailing, calibration) pair of the set."""
    t = np.atleast_1d(illuminant_temperatures(illuminants, camera_))
    return gamut(response(camera_, reflectance, t[:, None], t[None, :], normalization, knee, grid))


def illuminant_temperatures(illuminants, camera_=None) -> NDArrayFloat:
    """
    An illuminant set's temperatures, K: its text as ``--illuminants`` takes it (``paper``, ``auto`` for
    ``camera_``, ``2000,3300,A``; :func:`~skinrender.model.stage1.illuminant_set`), or numbers as they are; a
    refusal names ``illuminants``.
    """
    if isinstance(illuminants, str):
        from ..model.stage1 import illuminant_set

        try:
            return illuminant_set(illuminants, camera_)
        except SkinrenderError as error:
            if error.message.startswith("--illuminants auto"):  # the CLI's words: a caller here passes no flag
                named = ("illuminants: 'auto' (Stage 1) needs a camera; give kelvin (2000,3300,A) or 'paper'"
                         if camera_ is None else f"illuminants: {error.message}")
            else:
                named = error.message if error.message.startswith("illuminants") else f"illuminants: {error.message}"
            raise error.reworded(named, role="illuminants", flag=None) from None
    temperatures = float_array(illuminants, "illuminants")
    if temperatures.size == 0 or not np.all(np.isfinite(temperatures) & (temperatures > 0)):
        raise SkinrenderError(f"illuminants must be kelvin > 0, got {temperatures.tolist()}", role="illuminants")
    return temperatures
