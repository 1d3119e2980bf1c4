"""
Sensor bank
===========

The Stage 3 search's single sensors: every sensor position's responses to a
reflectance set under every illuminant, computed once per search and
gathered per triplet.

-   :func:`positions_grid`: sensor peak positions from ``START:END:STEP`` (nm).
-   :func:`triplets`: the ascending triplets of distinct positions.
-   :class:`SensorBank`, :func:`sensor_bank`: the single-sensor responses,
    with each triplet's Eq. 4 gains (:func:`skinrender.model.response.gain`)
    and prevailing clouds.
-   :data:`SENSORS_PAPER`: the paper's sensors 1, 3, …, 15.

Units: wavelength in nm, temperature in K; responses as Eq. 1 sums (radiance
times unitless sensitivities and reflectances, times nm).

References
----------
-   :cite:`Martinkauppi2006` : the paper, Stage 3 (docs/references.md).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from ..constants import CONSTANT_OUTPUT_SCALE, SENSOR_RULE, TEMPERATURES_PAPER
from ..errors import SkinrenderError
from ..hints import ArrayLike, NDArrayFloat
from ..methods import RangeWords, parse_range, range_steps, validate_method
from ..model.camera import sensor_curves
from ..model.illuminant import illuminants_array
from ..model.response import NORMALISATIONS, gain, illuminant_factors, spds_on
from ..spectra import GRID_DEFAULT, WavelengthGrid, float_array

__all__ = ["SENSORS_PAPER", "POSITIONS_MAX", "positions_grid", "triplets", "SensorBank", "sensor_bank"]

SENSORS_PAPER = (1, 3, 5, 7, 9, 11, 13, 15)
"""The paper's sensors: 1 is the impulse, N ≥ 3 a gbell of FWHM N·10 nm."""


POSITIONS_MAX = 3001
"""Most sensor positions of a search (every 0.1 nm over 400–700 nm; 4.5e9 triplets)."""


_POSITIONS_WORDS = RangeWords(
    lambda r: f"positions {r.text!r}: need END > START and STEP > 0 (nm)",
    lambda r: (f"positions {r.text!r}: {r.values:.3g} positions, more than {POSITIONS_MAX} ({r.values ** 3 / 6:.3g} "
               "triplets); use a larger step"),
    lambda r: (f"positions {r.text!r}: {r.end:g} nm is not START + a whole number of {r.step:g} nm steps (the end "
               "is included, never dropped)"),
)


def positions_grid(spec: str | ArrayLike = "400:700:10") -> NDArrayFloat:
    """Sensor peak positions in nm from ``start:end:step`` (end included) or a sequence."""
    if isinstance(spec, str):
        start, end, step = parse_range(spec, "positions")
        values = start + step * np.arange(range_steps(start, end, step, POSITIONS_MAX, _POSITIONS_WORDS, spec) + 1)
    else:
        values = np.asarray(spec, dtype=np.float64).ravel()
    if values.size < 3 or not np.all(np.isfinite(values)) or np.any(np.diff(values) <= 0):
        raise SkinrenderError("positions must be at least three increasing wavelengths in nm")
    return values


def triplets(count: int) -> np.ndarray:
    """Index triplets ``(i, j, k)``, ``i < j < k``, of ``count`` positions, lexicographic; shape ``(T, 3)``."""
    return np.array(list(itertools.combinations(range(count), 3)), dtype=np.intp).reshape(-1, 3)


@dataclass(frozen=True)
class SensorBank:
    """
    Single-sensor responses of one reflectance set.

    Attributes
    ----------
    positions
        Sensor peaks, nm, shape ``(J,)``.
    temperatures
        Illuminants, K, shape ``(P,)``; they serve as prevailing and calibration.
    signal
        ``Σ_λ I_p(λ) x_j(λ) o_i(λ)``, shape ``(P, J, N)``.
    white
        ``Σ_λ I_p(λ) x_j(λ)``, shape ``(P, J)``.
    factor
        Normalisation factor ``F_p`` (Eqs. 5–7), shape ``(P,)``; ``None`` for ``white``.
    """

    positions: NDArrayFloat
    temperatures: NDArrayFloat
    signal: NDArrayFloat
    white: NDArrayFloat
    factor: NDArrayFloat | None
    scale: float = CONSTANT_OUTPUT_SCALE
    knee: bool = False
    diagonal: bool = False
    """True for the impulse: each prevailing cloud is a per-channel scaling of
    every other (``I_p(λ_k) o_i(λ_k)``), so all share one vertex set."""
    normalization: str = "white"
    """The Eq. 10 factor of the gains: ``white`` (WP) or the normalisation of ``factor``."""

    def gains(self, triplet: ArrayLike) -> NDArrayFloat:
        """Eq. 4 gains ``v · F_pq / W_qk`` for one index triplet (channels R, G, B), shape ``(P, Q, 3)``."""
        index = np.asarray(triplet)[::-1]  # R is the longest peak
        white = self.white[:, index]
        if self.factor is None:  # WP (Eq. 8)
            return gain(white[:, None, :], white[None, :, :], scale=self.scale)
        return gain(white[:, None, :], white[None, :, :], self.normalization, self.factor[:, None],
                    self.factor[None, :], self.scale)

    def clouds(self, triplet: ArrayLike) -> NDArrayFloat:
        """Prevailing clouds ``C_p`` (channels R, G, B), shape ``(P, N, 3)``."""
        index = np.asarray(triplet)[::-1]
        return np.ascontiguousarray(self.signal[:, index, :].transpose(0, 2, 1))


def sensor_bank(
    sensor: float,
    reflectance: NDArrayFloat,
    positions: ArrayLike = positions_grid(),
    illuminants: ArrayLike = TEMPERATURES_PAPER,
    slope: float = 2.0,
    normalization: str = "white",
    knee: bool = False,
    grid: WavelengthGrid = GRID_DEFAULT,
) -> SensorBank:
    """
    Single-sensor responses at every position, computed once for a search.

    Parameters
    ----------
    sensor
        The paper's sensor number: 1 (impulse, a unit-area delta on the grid
        sample of its peak) or any other N > 0 (gbell, FWHM = N·10 nm).
    reflectance
        Reflectances on ``grid``, shape ``(N, grid.size)``, fractions.
    positions
        Sensor peaks, nm.
    illuminants
        Prevailing and calibration illuminants (K, ``A``, ``H`` …).
    slope
        gbell slope *b*.
    normalization
        ``white`` (Eq. 8, the paper's Stage 3) or ``none``/``560nm``/``euclidean``.
    knee
        Apply Eq. 11 (forces the straightforward method).
    grid
        Integration grid, nm.
    """

    validate_method(normalization, NORMALISATIONS, "normalization")
    number = float_array(sensor, "sensor")
    if number.ndim != 0 or not (np.isfinite(number) and number > 0):
        raise SkinrenderError(f"sensor must be {SENSOR_RULE}, got {sensor!r}", role="sensor")
    positions = float_array(positions, "positions")
    if positions.min() < grid.start or positions.max() > grid.end:
        raise SkinrenderError(
            f"positions {positions.min():g}–{positions.max():g} nm leave the integration grid {grid}"
        )
    items, _ = illuminants_array(illuminants)
    spd = spds_on(items, grid)  # (P, W)
    x = sensor_curves(positions, grid, None if sensor == 1 else float(sensor) * 10.0, slope)
    o = float_array(reflectance, "reflectance")
    if o.ndim != 2 or o.shape[-1] != grid.size:
        raise SkinrenderError(f"reflectance must be an array (samples, {grid.size}) on the grid {grid}, got shape "
                              f"{o.shape}", role="reflectance")
    signal = np.einsum("iw,pjw->pji", o, spd[:, None, :] * x[None, :, :], optimize=True)
    white = spd @ x.T
    for item, row in zip(items, white):
        if not np.all(np.isfinite(row) & (row > 1e-300)):
            raise SkinrenderError(f"illuminant {item} gives no light in the sensors' range ({grid}) at every position: "
                                  "every response would be 0/0", role="illuminants")
    factor = illuminant_factors(items, normalization, grid)  # None: WP (Eq. 8), the pair's
    temperatures = np.array([item.temperature if item.temperature is not None else np.nan for item in items])
    return SensorBank(positions, temperatures, signal, white, factor, knee=knee, diagonal=sensor == 1,
                      normalization=normalization)
