"""
Skin locus
==========

The skin locus of a camera (Störring et al.; Martinkauppi & Soriano): the
region of NCC (r, g) that skin occupies under a set of illuminants, with one
white balancing (one calibration illuminant) or with several.

-   :func:`locus_points`: NCC (r, g) of a reflectance set over the illuminant
    set (one calibration, or every pair).
-   :class:`SkinLocus`, :func:`skin_locus`: the locus as a polygon — the convex
    hull, or the tighter two-quadratic boundary of Soriano et al. (2003)
    (upper and lower quadratics g(r) fitted to the cloud's per-bin extremes
    and offset so that every training point lies inside), with its area.
-   :meth:`SkinLocus.contains`: the classifier.
-   :func:`false_positive_rate`: the share of a non-skin set's chromaticities
    inside the locus.
-   :func:`hull_locus`: the convex-hull locus of a cloud of chromaticities.

References
----------
-   :cite:`Storring2001` : Störring, M., Andersen, H. J., & Granum, E. (2001).
    Physics-based modelling of human skin colour under mixed illuminants.
    Robotics and Autonomous Systems, 35(3–4), 131–142.
-   :cite:`Soriano2003` : Soriano, M., Martinkauppi, B., Huovinen, S., &
    Laaksonen, M. (2003). Adaptive skin color modeling using the skin locus for
    selecting training pixels. Pattern Recognition, 36(3), 681–690.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..constants import TEMPERATURES_PAPER
from ..errors import SkinrenderError
from ..hints import ArrayLike, NDArrayFloat
from ..methods import method_of
from ..model.camera import Camera
from ..model.chromaticity import ncc
from ..model.response import response
from ..spectra import GRID_DEFAULT, WavelengthGrid
from .gamut import illuminant_temperatures

__all__ = ["BOUNDARIES", "boundary_hull", "boundary_quadratic", "locus_points", "SkinLocus", "skin_locus", "false_positive_rate", "hull_locus"]

def boundary_hull(points: NDArrayFloat, hull: SkinLocus) -> SkinLocus:
    """the convex hull of the training chromaticities (default)

    The convex hull of the (r, g) ``points``: ``hull`` as it is."""
    return hull


def boundary_quadratic(points: NDArrayFloat, hull: SkinLocus) -> SkinLocus:
    """two quadratics g(r) (Soriano et al. 2003)

    Two quadratics in r fitted to the g extremes of the (r, g) ``points`` (tighter on the curved skin locus; it
    contains every training point), the lights of ``hull`` kept."""
    polygon, quadratics = _quadratic_polygon(points)
    return SkinLocus(polygon, _polygon_area(polygon), "quadratic", hull.illuminants, hull.calibration, quadratics)


BOUNDARIES = {"hull": boundary_hull, "quadratic": boundary_quadratic}
"""Locus boundaries, name → the function ``(points, hull) → SkinLocus`` of the training chromaticities and their
convex-hull locus; :func:`skin_locus` dispatches."""

QUADRATIC_BINS = 24
"""r bins whose g extremes the two quadratics are fitted to."""


def locus_points(
    cam: Camera | str,
    reflectance,
    illuminants: ArrayLike = TEMPERATURES_PAPER,
    calibration: float | str | None = None,
    grid: WavelengthGrid = GRID_DEFAULT,
    role: str = "reflectance",
) -> NDArrayFloat:
    """
    NCC (r, g) of ``reflectance`` under every illuminant of the set (a refusal of it has the role ``role``).

    ``calibration`` (K) fixes one white balancing (every prevailing light
    balanced to it); ``None`` takes every (prevailing, calibration) pair of
    the set. Shape ``(n, 2)``.
    """

    t = illuminant_temperatures(illuminants, cam)
    if t.ndim != 1:
        raise SkinrenderError(f"illuminants must be a list of kelvin, got {illuminants!r}", role="illuminants")
    try:
        if calibration is None:
            rgb = response(cam, reflectance, t[:, None], t[None, :], grid=grid)
        else:
            rgb = response(cam, reflectance, t, calibration_kelvin(calibration), grid=grid)
    except SkinrenderError as error:  # the caller's argument: skin_locus' skin, a false-positive rate's nonskin
        raise (error.reworded(role=role) if error.role == "reflectance" else error) from None
    return ncc(rgb).reshape(-1, 3)[:, :2]


def calibration_kelvin(calibration) -> float:
    """
    A locus' one white balancing as a temperature, K: a number, or a Planckian light as ``--calibration`` takes
    it (``3300``, ``"3300K"``, ``"A"``); a measured light or anything else is refused naming ``calibration``.

    >>> calibration_kelvin("A"), calibration_kelvin(5900)
    (2856.0, 5900.0)
    """
    from ..model.illuminant import illuminant

    try:
        kelvin = illuminant(calibration).temperature
    except SkinrenderError as error:
        raise error.reworded(f"calibration: {error.message}", role="calibration") from None
    if kelvin is None:
        raise SkinrenderError(f"calibration: a locus balances to a Planckian light (kelvin or A), got {calibration!r}",
                              role="calibration")
    return float(kelvin)


@dataclass(frozen=True)
class SkinLocus:
    """
    A skin locus in NCC (r, g).

    Attributes
    ----------
    polygon
        Boundary vertices ``(m, 2)``, counter-clockwise.
    area
        Area in (r, g) units².
    boundary
        ``hull`` or ``quadratic``.
    illuminants
        The illuminant set, K; ``calibration`` the one white balancing or ``None``.
    """

    polygon: NDArrayFloat
    area: float
    boundary: str
    illuminants: NDArrayFloat
    calibration: float | None
    quadratics: tuple | None = None
    """For ``quadratic``: (upper, lower) polynomial coefficients in r and the r range."""
    degenerate: str | None = None
    """Why the locus has no area (skin chromaticities on a line or a point, e.g. coincident sensors), or ``None``.
    A degenerate locus contains nothing: detection with it finds no skin."""

    def contains(self, rg: ArrayLike, tolerance: float = 1e-9) -> NDArrayFloat:
        """Whether each (r, g) lies in the locus (boundary included); shape ``rg.shape[:-1]``."""
        points = np.asarray(rg, dtype=np.float64)
        flat = points.reshape(-1, 2)
        if self.degenerate is not None:
            return np.zeros(points.shape[:-1], dtype=bool)
        if self.quadratics is not None:
            upper, lower, (r_min, r_max) = self.quadratics
            r, g = flat[:, 0], flat[:, 1]
            inside = ((r >= r_min - tolerance) & (r <= r_max + tolerance)
                      & (g <= np.polyval(upper, r) + tolerance) & (g >= np.polyval(lower, r) - tolerance))
        else:
            # convex, counter-clockwise: inside (or within tolerance of) every edge's half-plane
            start = self.polygon
            edge = np.roll(start, -1, axis=0) - start
            # p is inside an edge's half-plane when cross(edge, p − start) ≥ −tolerance·|edge|;
            # test edge by edge, keeping only the points still inside (most leave after a few edges)
            bound = edge[:, 0] * start[:, 1] - edge[:, 1] * start[:, 0] - tolerance * np.hypot(edge[:, 0], edge[:, 1])
            candidates = np.arange(len(flat))
            x, y = flat[:, 0], flat[:, 1]
            for (ex, ey), limit in zip(edge, bound):
                candidates = candidates[ex * y[candidates] - ey * x[candidates] >= limit]
            inside = np.zeros(len(flat), dtype=bool)
            inside[candidates] = True
        return inside.reshape(points.shape[:-1])


def _polygon_area(polygon: NDArrayFloat) -> float:
    x, y = polygon[:, 0], polygon[:, 1]
    return float(0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def _quadratic_polygon(points: NDArrayFloat, samples: int = 64) -> NDArrayFloat:
    r, g = points[:, 0], points[:, 1]
    edges = np.linspace(r.min(), r.max(), QUADRATIC_BINS + 1)
    which = np.clip(np.digitize(r, edges) - 1, 0, QUADRATIC_BINS - 1)
    upper, lower = [], []
    for b in range(QUADRATIC_BINS):
        members = which == b
        if members.any():
            upper.append((r[members][np.argmax(g[members])], g[members].max()))
            lower.append((r[members][np.argmin(g[members])], g[members].min()))
    upper, lower = np.array(upper), np.array(lower)
    if len(upper) < 3:
        raise SkinrenderError("quadratic locus needs chromaticities spread over at least three r bins")
    fit_upper = np.polyfit(upper[:, 0], upper[:, 1], 2)
    fit_lower = np.polyfit(lower[:, 0], lower[:, 1], 2)
    # offset so that every training point lies between the two curves
    fit_upper[-1] += max(0.0, float(np.max(g - np.polyval(fit_upper, r))))
    fit_lower[-1] -= max(0.0, float(np.max(np.polyval(fit_lower, r) - g)))
    rr = np.linspace(r.min(), r.max(), samples)
    top, bottom = np.polyval(fit_upper, rr), np.polyval(fit_lower, rr)
    polygon = np.vstack([np.column_stack([rr, bottom]), np.column_stack([rr[::-1], top[::-1]])])
    return polygon, (fit_upper, fit_lower, (float(r.min()), float(r.max())))


def skin_locus(
    cam: Camera | str,
    skin="skin",
    illuminants: ArrayLike = TEMPERATURES_PAPER,
    calibration: float | str | None = None,
    boundary: str = "hull",
    grid: WavelengthGrid = GRID_DEFAULT,
) -> SkinLocus:
    """
    The skin locus of a camera.

    Parameters
    ----------
    cam
        Camera or spec.
    skin
        Skin reflectance set (name, CSV, :class:`SpectralSet` or array on ``grid``).
    illuminants
        Illuminant set, K (the paper's ten by default), or its text as ``--illuminants`` takes it (``paper``,
        ``auto``, ``2000,3300,A``).
    calibration
        One white balancing at this temperature (K, or a Planckian light's name such as ``A``), or ``None`` for
        every calibration of the set (the locus for several white balancings).
    boundary
        ``hull`` (convex hull, default) or ``quadratic`` (two quadratics in r,
        tighter on the curved skin locus; it contains every training point).
    """

    shaped = method_of(boundary, BOUNDARIES, "boundary")
    illuminants = illuminant_temperatures(illuminants, cam)  # once: 'auto' runs Stage 1
    calibration = None if calibration is None else calibration_kelvin(calibration)
    points = locus_points(cam, skin, illuminants, calibration, grid, role="skin")
    if points.shape[0] == 0:  # degenerate is not an error: an empty skin set's locus contains nothing
        return SkinLocus(np.empty((0, 2)), 0.0, boundary, illuminants, calibration,
                         degenerate="the skin set is empty: no chromaticities to bound")
    locus = hull_locus(points, illuminants, calibration)
    if locus is None:  # degenerate is not an error: a locus of no area, which contains nothing
        return SkinLocus(np.unique(points.round(12), axis=0), 0.0, boundary, illuminants, calibration,
                         degenerate="the skin chromaticities lie on a line or a point (coincident sensors?)")
    return shaped(points, locus)


def hull_locus(points: NDArrayFloat, illuminants: NDArrayFloat, calibration: float | None) -> SkinLocus | None:
    """The convex-hull locus of (r, g) ``points`` (vertices counter-clockwise), ``None`` if it has no area."""
    from scipy.spatial import ConvexHull, QhullError  # here: a heavy import most commands never use

    try:
        hull = ConvexHull(points)
    except QhullError:
        return None
    polygon = points[hull.vertices]  # scipy gives 2-D hull vertices counter-clockwise
    return SkinLocus(polygon, _polygon_area(polygon), "hull", illuminants, calibration)


def false_positive_rate(locus: SkinLocus, cam: Camera | str, nonskin, grid: WavelengthGrid = GRID_DEFAULT) -> float:
    """Share of a non-skin set's chromaticities (same illuminants and white balancing) inside the locus."""
    points = locus_points(cam, nonskin, locus.illuminants, locus.calibration, grid)
    return float(np.mean(locus.contains(points)))
