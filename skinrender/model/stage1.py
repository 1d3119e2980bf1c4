"""
Illuminant sets and Stage 1
===========================

The paper's Stage 1: the chromaticity track of Planckian illuminants seen by a
camera (Eq. 1 on a white object, then Eq. 2), the measure of Eq. 3 along it,
and the selection of illuminants equally spaced in that measure.

-   :func:`illuminant_track`: NCC and measure over a temperature range.
-   :func:`select_illuminants`, :func:`illuminant_selection`: Stage 1.
-   :func:`illuminant_set`: the ``--illuminants`` spec (paper list, ``auto``,
    comma-separated kelvin).

References
----------
-   :cite:`Martinkauppi2006` : the paper, Stage 1 and Fig. 2.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..constants import TEMPERATURES_PAPER
from ..errors import SkinrenderError
from ..hints import ArrayLike, NDArrayFloat
from ..methods import RangeWords, range_steps
from ..spectra import GRID_DEFAULT, WavelengthGrid, as_grid, float_array
from .camera import Camera, camera
from .illuminant import illuminant
from .chromaticity import measure, ncc
from .response import response_raw

__all__ = [
    "ILLUMINANTS_MAX",
    "IlluminantTrack",
    "illuminant_track",
    "IlluminantSelection",
    "illuminant_selection",
    "select_illuminants",
    "illuminant_set",
    "temperature_range",
]


CANDIDATES_MAX = 100_001
"""Most Stage 1 candidate temperatures (2000–10000 K every 0.08 K)."""


_CANDIDATES_WORDS = RangeWords(
    lambda r: f"temperature range end {r.end:g} K must be above its start {r.start:g} K",
    lambda r: (f"temperature range {r.start:g}–{r.end:g} K every {r.step:g} K has {r.values:.3g} candidates, more "
               f"than {CANDIDATES_MAX}; use a larger step"),
    lambda r: f"temperature range {r.start:g}–{r.end:g} K is not a whole number of {r.step:g} K steps",
)


def temperature_range(start: float = 2000.0, end: float = 10000.0, step: float = 100.0) -> NDArrayFloat:
    """Temperatures ``start, start + step, …, end`` in K (``end`` included)."""
    for name, value in (("start", start), ("end", end), ("step", step)):
        if value is None or isinstance(value, (bool, str)) or not (np.ndim(value) == 0 and np.isfinite(value)
                                                                   and value > 0):
            raise SkinrenderError(f"{name} (temperature) must be a finite number of kelvin > 0, got {value!r}",
                                  role=name)
    return start + step * np.arange(range_steps(start, end, step, CANDIDATES_MAX, _CANDIDATES_WORDS, role="end") + 1)


@dataclass(frozen=True)
class IlluminantTrack:
    """Planckian track of a camera: temperatures (K), NCC ``(n, 3)`` and measure ``(n,)``."""

    temperatures: NDArrayFloat
    chromaticities: NDArrayFloat
    measures: NDArrayFloat
    pair: str


def illuminant_track(
    camera_: Camera | str,
    temperatures: ArrayLike | None = None,
    grid: WavelengthGrid = GRID_DEFAULT,
    pair: str = "gb",
) -> IlluminantTrack:
    """
    The NCC chromaticities of a white object under Planckian light (Fig. 2).

    Parameters
    ----------
    camera_
        Camera or spec.
    temperatures
        Colour temperatures, K (default 2000–10000 K every 100 K).
    grid
        Integration grid.
    pair
        Chromaticity pair of the measure (Eq. 3); the paper uses ``gb``
        because it grows with colour temperature.

    Returns
    -------
    :class:`IlluminantTrack`

    Notes
    -----
    Eq. 1 with the raw SPD (Eq. 5) and ``o(λ) = 1``; any normalisation would
    cancel in Eq. 2.
    """

    grid = as_grid(grid)
    temperatures = temperature_range() if temperatures is None else float_array(temperatures, "temperatures")
    white = np.ones((1, grid.size))
    rgb = response_raw(camera(camera_), white, temperatures, "none", grid)[..., 0, :]
    chromaticities = ncc(rgb)
    return IlluminantTrack(temperatures, chromaticities, measure(chromaticities, pair), pair)


@dataclass(frozen=True)
class IlluminantSelection:
    """
    Stage 1 result.

    Attributes
    ----------
    temperatures
        Selected temperatures, K, ascending.
    measures
        Their measures (Eq. 3).
    targets
        The equally spaced measure values they were chosen for.
    track
        The full candidate track.
    monotonic
        Whether the measure grows strictly with temperature over the range
        (the premise of the method; ``False`` is reported, not hidden).
    """

    temperatures: NDArrayFloat
    measures: NDArrayFloat
    targets: NDArrayFloat
    track: IlluminantTrack
    monotonic: bool


def illuminant_selection(
    camera_: Camera | str,
    count: int = 10,
    start: float = 2000.0,
    end: float = 10000.0,
    step: float = 100.0,
    grid: WavelengthGrid = GRID_DEFAULT,
    pair: str = "gb",
) -> IlluminantSelection:
    """
    Stage 1: ``count`` temperatures equally spaced in the measure of Eq. 3.

    Parameters
    ----------
    camera_
        Camera or spec.
    count
        How many illuminants (≥ 2); the first and last are the range ends.
    start, end, step
        Candidate temperatures, K (the paper: 2000–10000 K every 100 K).
    grid
        Integration grid.
    pair
        Chromaticity pair of the measure.

    Returns
    -------
    :class:`IlluminantSelection`

    Notes
    -----
    The targets are ``count`` values equally spaced between the measures at
    ``start`` and ``end``; each is matched to the candidate whose measure is
    nearest (ties to the lower temperature). When two targets would fall on
    the same candidate (a short range or a coarse step), or the measure does
    not change with temperature (coincident sensors), the selection is
    refused with the reason rather than returning fewer than ``count``.
    """

    if not (isinstance(count, (int, np.integer)) or (isinstance(count, float) and count.is_integer())) or count < 2:
        raise SkinrenderError(f"count must be an integer ≥ 2, got {count!r}", role="count")
    candidates = temperature_range(start, end, step)
    if count > candidates.size:
        raise SkinrenderError(f"count {int(count)} is more than the {candidates.size} candidate temperatures "
                              f"({start:g}–{end:g} K every {step:g} K)", role="count")
    track = illuminant_track(camera_, candidates, grid, pair)
    m = track.measures
    if not np.all(np.isfinite(m)) or abs(m[-1] - m[0]) <= 1e-12 * max(1.0, abs(m[0])):
        raise SkinrenderError(f"the Stage 1 measure (NCC {pair}) does not change from {start:g} K to {end:g} K for "
                              f"this camera (coincident sensors?): no temperatures can be spaced in it", role="camera")
    targets = np.linspace(m[0], m[-1], int(count))
    index = np.argmin(np.abs(m[None, :] - targets[:, None]), axis=1)
    if np.unique(index).size < index.size:
        raise SkinrenderError(f"only {np.unique(index).size} distinct temperatures of the {int(count)} asked for: "
                              f"candidates every {step:g} K are too coarse for this range; use a smaller step or count")
    return IlluminantSelection(
        track.temperatures[index], m[index], targets, track, bool(np.all(np.diff(m) > 0))
    )


def select_illuminants(camera_: Camera | str, count: int = 10, **kwargs) -> NDArrayFloat:
    """
    Stage 1 temperatures (K) for a camera; see :func:`illuminant_selection`.

    Examples
    --------
    >>> select_illuminants("Nikon 5100 (NPL)", count=3)  # doctest: +ELLIPSIS
    array([  2000., ...,  10000.])
    """

    return illuminant_selection(camera_, count, **kwargs).temperatures


def illuminant_set(spec: str | ArrayLike | None = None, camera_: Camera | str | None = None) -> NDArrayFloat:
    """
    Temperatures (K) from an ``--illuminants`` spec.

    Parameters
    ----------
    spec
        ``None`` or ``paper``: the paper's ten (2000 … 10000 K); ``auto``: Stage 1
        for ``camera_``; a comma-separated list of kelvin (``2000,3300K,A``) or
        a sequence of numbers.
    camera_
        Needed for ``auto``.
    """

    if spec is None or (isinstance(spec, str) and spec.strip().lower() == "paper"):
        return np.array(TEMPERATURES_PAPER)
    if isinstance(spec, str):
        text = spec.strip()
        if text.lower() == "auto":
            if camera_ is None:
                raise SkinrenderError("--illuminants auto needs a camera (--camera)", flag="--illuminants",
                                      role="illuminants")
            return select_illuminants(camera_)

        parts = text.split(",")
        if not all(part.strip() for part in parts):
            raise SkinrenderError(f"illuminants must be comma-separated kelvin (e.g. 2000,3300,A), none empty, "
                                  f"got {spec!r}", role="illuminants")
        try:
            items = [illuminant(part) for part in parts]
        except SkinrenderError as error:
            raise error.reworded(role="illuminants") from None
        if any(item.temperature is None for item in items):
            raise SkinrenderError(
                f"illuminants must be 'paper', 'auto' or comma-separated kelvin (e.g. 2000,3300,A), got {spec!r}",
                role="illuminants")
        return _distinct(np.array([item.temperature for item in items]))
    if isinstance(spec, dict) or np.ndim(spec) > 1:
        raise SkinrenderError(f"illuminants must be text or a 1-D sequence of kelvin, got {spec!r}"[:200],
                              role="illuminants")
    values = float_array(spec, "illuminants").ravel()
    if values.size == 0 or not np.all(np.isfinite(values) & (values > 0)):
        raise SkinrenderError(f"illuminants must be kelvin > 0, got {values.tolist()}", role="illuminants")
    return _distinct(values)


ILLUMINANTS_MAX = 100
"""Most illuminants in a set (the paper's has 10): each is a prevailing light and a calibration, so a gamut or
search does work and holds memory growing with the count squared (1000 illuminants ran a machine of 24 GiB out of
memory in ``gamut --all-calibrations``)."""


def _distinct(temperatures: NDArrayFloat) -> NDArrayFloat:
    """
    ``temperatures`` (K), refused when one repeats (each would be a prevailing light and a calibration twice) or
    when there are more than :data:`ILLUMINANTS_MAX`.
    """
    if temperatures.size > ILLUMINANTS_MAX:
        raise SkinrenderError(f"illuminants: at most {ILLUMINANTS_MAX} (each is a prevailing light and a calibration: "
                              f"the work grows with the count squared, {(temperatures.size / 10) ** 2:.3g}× the "
                              f"paper's 10), got {temperatures.size}")
    values, counts = np.unique(temperatures, return_counts=True)
    if np.any(counts > 1):
        repeated = ", ".join(f"{v:g} K" for v in values[counts > 1])
        raise SkinrenderError(f"illuminants must be distinct temperatures, got {repeated} more than once")
    return temperatures
