"""
The noise-aware detection criterion for sensor triplets
=======================================================

The Stage 3 search and the continuous design reward sensors that separate
skin chromaticities from everything else. Without noise both drive the three
sensors together (the chromatic signal shrinks, but nothing pays for it). With
an image sensor at a stated light level, a triplet is judged on noisy pixels:

1.  each sensor position's electron rate for a white under the lit chart
    (:func:`skinrender.model.exposure.electrons_mean` with the QE shape
    x(λ)/λ, since the curves weight energy), computed once per bank;
2.  a patch's electrons are the white's times its Eq. 1 ratio (the bank's
    signal over its white), for an exposure fixed or ``auto`` (the
    calibration white's brightest channel at 0.7 of the full well);
3.  ``samples`` noisy frames per (patch, prevailing light), seeded by the
    triplet, through :func:`skinrender.model.noise.simulate_dn`; black level
    subtracted (a pixel with nothing above black is no light), the Eq. 4 gain
    from the noise-free whites;
4.  the skin locus is the hull of the noise-free skin chromaticities under the
    same balance; TPR is the share of noisy skin pixels inside it, FPR that of
    noisy non-skin pixels.

-   :class:`NoisySetting`: imager, illuminance (lx), exposure (an
    :class:`~skinrender.model.exposure.Imaging`), calibration (K), samples and seed.
-   :func:`bank_rates`: step 1 for a bank.
-   :func:`triplet_noisy_rates`: (TPR, FPR) of one triplet.
-   :data:`TPR_MIN`: the TPR a triplet must keep to be ranked by its FPR.

Units: illuminance lx, exposure s, rates are fractions in [0, 1].

References
----------
-   :cite:`EMVA1288`, :cite:`Martinkauppi2006` (docs/references.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import SkinrenderError
from ..evaluation.locus import hull_locus
from ..hints import ArrayLike, NDArrayFloat
from ..model.camera import sensor_curves
from ..model.chromaticity import ncc
from ..model.exposure import (AUTO_EXPOSURE_FRACTION, AUTO_EXPOSURE_MAX_S, Imaging, auto_exposure,
                              auto_exposure_note, electrons_mean, imaging, irradiance_planck)
from ..model.imager import Imager
from ..model.noise import simulate_dn
from ..model.response import gain
from ..spectra import GRID_DEFAULT, WavelengthGrid
from .bank import SensorBank

__all__ = ["TPR_MIN", "SECONDS_PER_NOISY_SAMPLE", "NOISE_SAMPLES_MAX", "NOISE_SEED_MAX",
           "NOISE_CALIBRATION_K", "AUTO_EXPOSURE_FRACTION", "NoisySetting", "noisy_setting", "bank_rates",
           "calibration_index", "exposure_capped", "triplet_noisy_rates"]

SECONDS_PER_NOISY_SAMPLE = 0.022
"""What each noise sample adds to one triplet of a noisy search, s on one core: the estimates' rate, from
``search --imager`` over 286 triplets with 4 and 40 noise samples (docs/speed.md, "The rates behind the
estimates")."""

NOISE_SAMPLES_MAX = 1000
"""Most noisy frames per pixel (``--noise-samples``)."""

NOISE_SEED_MAX = 2**32 - 1
"""Largest noise seed (``--noise-seed``): numpy's seeds are 32-bit here."""

NOISE_CALIBRATION_K = 3300.0
"""The white balance of the noisy criterion when none is given (K), when it is one of the illuminants."""

TPR_MIN = 0.9
"""A triplet is ranked by its noisy FPR only while at least this share of noisy skin pixels stays in the
locus: otherwise noise that pushes every pixel out of the locus would look like a perfect detector."""


@dataclass(frozen=True)
class NoisySetting(Imaging):
    """What the noisy criterion is computed for: the :class:`~skinrender.model.exposure.Imaging` (imager,
    illuminance in lx, exposure in s or ``auto``), the calibration light (K, one of the bank's illuminants),
    noisy samples per pixel and the seed."""

    calibration: float = 3300.0
    samples: int = 4
    seed: int = 0


def noisy_setting(imager_: Imager | str, illuminance_lux: float, exposure: float | str = "auto",
                  calibration: float = 3300.0, samples: int = 4, seed: int = 0) -> NoisySetting:
    """A checked :class:`NoisySetting` (one-line errors naming the argument; the imaging's checks are
    :func:`~skinrender.model.exposure.imaging`'s)."""
    setting = imaging(imager_, illuminance_lux, exposure)
    if not (isinstance(samples, (int, np.integer)) and 1 <= samples <= NOISE_SAMPLES_MAX):
        raise SkinrenderError(f"noise samples must be an integer in [1, {NOISE_SAMPLES_MAX}], got {samples!r}")
    if not (isinstance(seed, (int, np.integer)) and 0 <= seed <= NOISE_SEED_MAX):
        raise SkinrenderError(f"seed must be an integer in [0, 2^32), got {seed!r}")
    return NoisySetting(setting.imager, setting.illuminance_lux, setting.exposure, float(calibration), int(samples),
                        int(seed))


def bank_rates(bank: SensorBank, setting: NoisySetting, sensor: float, slope: float = 2.0,
               grid: WavelengthGrid = GRID_DEFAULT) -> NDArrayFloat:
    """
    Photo-electron rate of a white, e⁻/s, for every (illuminant, position) of ``bank``, shape ``(P, J)``:
    each position's sensor (the paper's ``sensor``: 1 impulse, else gbell FWHM sensor·10 nm) as a QE shape
    x(λ)/λ peaking at the imager's QE.
    """
    curves = sensor_curves(bank.positions, grid, None if sensor == 1 else float(sensor) * 10.0, slope)
    curves = curves / grid.wavelengths
    padded = np.vstack([curves, np.repeat(curves[-1:], (-len(curves)) % 3, axis=0)])  # whole triplets
    rates = np.empty((bank.temperatures.size, len(curves)))
    for p, temperature in enumerate(bank.temperatures):
        white = irradiance_planck(temperature, setting.illuminance_lux, grid) / math.pi
        per_group = [electrons_mean(setting.imager, padded[g:g + 3], white, 1.0, grid) for g in range(0, len(padded), 3)]
        rates[p] = np.concatenate(per_group)[: len(curves)] - setting.imager.dark_current_e_per_s
    return rates


def _frames(setting: NoisySetting, bank: SensorBank, rates: NDArrayFloat, index: np.ndarray, exposure: float,
            generator: np.random.Generator) -> NDArrayFloat:
    """Noisy DN above black, ``(samples, P, N, 3)``, of a bank's patches through the triplet ``index`` (R, G, B)."""
    im = setting.imager
    ratio = bank.signal[:, index, :].transpose(0, 2, 1) / bank.white[:, None, index]  # Eq. 1 over the white
    electrons = (ratio * rates[:, None, index] + im.dark_current_e_per_s) * exposure
    frames = simulate_dn(im, np.broadcast_to(electrons, (setting.samples, *electrons.shape)), generator)
    return np.maximum(frames - im.black_level_dn, 0.0)


def calibration_index(temperatures: ArrayLike, calibration: float) -> int:
    """
    The index of the calibration light ``calibration`` (K) among ``temperatures`` (K); one of them exactly,
    else a one-line error (no nearest one is taken in its place).

    >>> calibration_index([2000.0, 3300.0, 6500.0], 3300)
    1
    """
    where = np.flatnonzero(np.asarray(temperatures, dtype=np.float64) == float(calibration))
    if where.size == 0:
        listed = ", ".join(f"{t:g}" for t in np.asarray(temperatures, dtype=np.float64))
        raise SkinrenderError(f"noise calibration must be one of the illuminants ({listed} K), got {calibration!r}")
    return int(where[0])


def exposure_capped(setting: NoisySetting, rates_skin: NDArrayFloat, temperatures: ArrayLike,
                    index: NDArrayFloat) -> str | None:
    """
    With an ``auto`` exposure: a note where it stops at :data:`AUTO_EXPOSURE_MAX_S` (a video frame) before the
    calibration white reaches :data:`AUTO_EXPOSURE_FRACTION` of the well, for how many of the triplets ``index``
    (``(T, 3)`` positions, ascending); ``None`` where it never does or the exposure is fixed.
    """
    if setting.exposure != "auto":
        return None
    q = calibration_index(temperatures, setting.calibration)
    whites = rates_skin[q][np.asarray(index)[:, ::-1]] + setting.imager.dark_current_e_per_s  # (T, 3): R, G, B
    return auto_exposure_note(setting.imager, whites, AUTO_EXPOSURE_FRACTION, AUTO_EXPOSURE_MAX_S)


def triplet_noisy_rates(skin: SensorBank, nonskin: SensorBank, rates_skin: NDArrayFloat,
                        rates_nonskin: NDArrayFloat, triplet: ArrayLike, setting: NoisySetting,
                        stream: int = 0) -> tuple[float, float]:
    """
    (TPR, FPR) of one triplet (index triplet into the banks' positions) on noisy pixels; NaN, NaN where the
    noise-free skin locus has no area. ``stream`` (the triplet's number) makes each triplet's noise its own and
    reproducible.
    """
    index = np.asarray(triplet)[::-1]  # R is the longest peak
    q = calibration_index(skin.temperatures, setting.calibration)
    im = setting.imager
    white_c = rates_skin[q, index]
    exposure = (float(auto_exposure(im, white_c + im.dark_current_e_per_s, AUTO_EXPOSURE_FRACTION,
                                         AUTO_EXPOSURE_MAX_S))
                if setting.exposure == "auto" else float(setting.exposure))
    gains = gain(rates_skin[:, index] * exposure * im.gain_dn_per_e, white_c * exposure * im.gain_dn_per_e)  # (P, 3)
    clean = skin.signal[:, index, :].transpose(0, 2, 1) / skin.white[:, None, index] * rates_skin[:, None, index]
    locus = hull_locus(ncc(clean * gains[:, None, :]).reshape(-1, 3)[:, :2], skin.temperatures, skin.temperatures[q])
    if locus is None:
        return float("nan"), float("nan")
    generator = np.random.default_rng([setting.seed, stream])
    shares = []
    for bank, rates in ((skin, rates_skin), (nonskin, rates_nonskin)):
        balanced = _frames(setting, bank, rates, index, exposure, generator) * gains[None, :, None, :]
        shares.append(float(np.mean(locus.contains(ncc(balanced)[..., :2]))))
    return shares[0], shares[1]
