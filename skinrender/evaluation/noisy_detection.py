"""
Noisy detection
===============

The skin-locus criterion through an image sensor: the locus is drawn from the
noise-free Eq. 4 chromaticities, and the skin and non-skin pixels it is scored
on are noisy frames of an :class:`~skinrender.model.imager.Imager` at a stated
illuminance and exposure.

-   :class:`ImagedWhites`: the whites, exposures and white-balance gains of
    every (prevailing, calibration) pair through an imager (steps 1–3 below),
    formed once for any number of reflectance sets.
-   :class:`PixelElectrons`, :func:`pixel_electrons`: the expected electrons
    and white-balance gains of a reflectance set (steps 1–3 below).
-   :class:`NoisyDetection`, :func:`noisy_detection`: seeded Monte Carlo
    true- and false-positive rates with their binomial standard errors, the
    noise-free rates beside them, and the skin's NCC noise by the delta method.

The chain, for each (prevailing p, calibration c) pair of the illuminant set
and each reflectance ρ:

1.  the chart's irradiance E_p (W·m⁻²·nm⁻¹) is the Planckian of temperature p
    at ``illuminance_lux`` (:func:`~skinrender.model.exposure.irradiance_planck`);
    a patch's radiance is ρ E_p / π (W·m⁻²·sr⁻¹·nm⁻¹);
2.  the camera curves weight energy, as in Eq. 1, so a channel's quantum
    efficiency is proportional to x_k(λ) / λ (peak ``qe_peak``): the white's
    electron rate (e⁻/s) is :func:`~skinrender.model.exposure.electrons_mean`,
    and a patch's is the white's times the Eq. 1 ratio
    ``response_raw(ρ) / response_raw(white)`` (:mod:`skinrender.model.response`);
3.  the exposure (s) is given, or ``auto``: the white under the calibration
    light c at 0.7 of the full well (:func:`~skinrender.model.exposure.auto_exposure`);
4.  a noisy frame (:func:`~skinrender.model.noise.simulate_dn`), less the black
    level and clipped at 0 DN (as a raw pipeline does), is white-balanced by the Eq. 4 gain of the noise-free whites under
    p and c (:func:`~skinrender.model.response.gain`), and its NCC (r, g) is
    classified by the locus; a pixel with every channel at or below the black
    level is not skin.

Without noise, dark current and clipping, step 4 gives exactly the Eq. 4
chromaticities, so the noisy rates tend to the noise-free ones as the
collected charge grows (more light at a fixed exposure, on a well that does
not fill). With ``auto`` exposure the charge is fixed by the full well, not by
the illuminance: the illuminance then only changes the dark current's share.

Units: wavelength nm, temperature K, illuminance lx, exposure s, charge e⁻,
output DN; rates are fractions in [0, 1].

References
----------
-   :cite:`EMVA1288` : the linear camera model of
    :mod:`skinrender.model.noise`.
-   :cite:`Martinkauppi2006` : Eqs. 1, 2 and 4 (docs/references.md).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import SkinrenderError
from ..hints import ArrayLike, NDArrayFloat
from ..model.camera import Camera
from ..model.chromaticity import ncc
from ..model.exposure import (AUTO_EXPOSURE_FRACTION, AUTO_EXPOSURE_MAX_S, Imaging, auto_exposure,
                              auto_exposure_note, electrons_mean, imaging, irradiance_planck)
from ..model.illuminant import illuminants_array
from ..model.imager import Imager, checked_array
from ..model.noise import (clipping_counts, clipping_note, ncc_covariance, random_generator, simulate_dn_clipped,
                           statistics_dn)
from ..model.response import gain, response_raw, spds_on
from ..spectra import GRID_DEFAULT, WavelengthGrid
from .locus import SkinLocus, false_positive_rate, locus_points, skin_locus

__all__ = ["AUTO_EXPOSURE_FRACTION", "NCC_LINEAR_MAX", "SECONDS_PER_NOISY_PIXEL", "NoisyDetection", "ImagedWhites",
           "PixelElectrons", "noisy_detection", "pixel_electrons"]

@dataclass(frozen=True)
class NoisyDetection:
    """
    Skin detection rates on noisy pixels.

    Attributes
    ----------
    tpr, fpr
        Shares of noisy skin and non-skin pixels inside the skin locus, in [0, 1].
    tpr_se, fpr_se
        Their binomial standard errors, sqrt(p (1 − p) / n) over the n pixels
        drawn (an upper bound on the Monte Carlo error: the pixels of one
        reflectance and pair share their mean).
    samples
        Noisy pixels drawn per (reflectance, prevailing, calibration).
    exposure_s
        Exposure, s, per calibration illuminant (in the order of ``calibrations_K``).
    illuminance_lux
        The chart's illuminance, lx.
    imager
        The imager's name.
    tpr_noise_free, fpr_noise_free
        The same shares for the noise-free Eq. 4 chromaticities.
    calibrations_K
        The calibration illuminants, K.
    skin_ncc_std
        Root mean square over the skin pixels of the NCC (r, g, b) standard
        deviations by the delta method (:func:`~skinrender.model.noise.ncc_covariance`), unitless,
        over the pixels where that first-order propagation holds (:data:`NCC_LINEAR_MAX`); NaN where none does.
    undefined
        Why a value is ``None`` or NaN (``tpr``/``fpr``: every noisy pixel black, no chromaticity;
        ``skin_ncc_std``: no skin pixel bright enough for the delta method).
    black_share
        Shares of the noisy skin and non-skin pixels with no chromaticity (every channel at or below the black
        level): counted as not detected.
    clipping
        :func:`~skinrender.model.noise.clipping_counts` of the noisy skin and non-skin pixels (``skin``,
        ``nonskin``): clipped at the full well or the ADC range.
    notes
        What was capped or clipped: the ``auto`` exposure stopped by its longest exposure, clipped pixels.
    """

    tpr: float
    fpr: float
    tpr_se: float
    fpr_se: float
    samples: int
    exposure_s: tuple[float, ...]
    illuminance_lux: float
    imager: str
    tpr_noise_free: float
    fpr_noise_free: float
    calibrations_K: tuple[float, ...]
    skin_ncc_std: tuple[float, float, float]
    undefined: dict = field(default_factory=dict)
    black_share: tuple[float, float] = (0.0, 0.0)
    clipping: dict = field(default_factory=dict)
    notes: tuple[str, ...] = ()


def _reflectance_array(values: ArrayLike, name: str, grid: WavelengthGrid) -> NDArrayFloat:
    out = checked_array(values, name, "(reflectance, fraction)", grid=grid)
    if out.ndim != 2 or out.shape[0] == 0:
        raise SkinrenderError(f"{name} must be an array (samples, {grid.size}) on the grid {grid}, got {out.shape}")
    return out


def _temperatures(values: ArrayLike, name: str) -> NDArrayFloat:
    out = checked_array(values, name, "K").ravel()
    if out.size == 0 or np.any(out <= 0):
        raise SkinrenderError(f"{name} must be temperatures > 0 K, got {values!r}")
    return out


def _rates(hits: int, total: int) -> tuple[float, float]:
    """The share of hits and its binomial standard error sqrt(p (1 − p) / n)."""
    share = hits / total
    return share, math.sqrt(share * (1.0 - share) / total)


@dataclass(frozen=True)
class PixelElectrons:
    """
    The noise-free pixels of a reflectance set through an imager.

    Attributes
    ----------
    electrons
        Expected electrons (photo plus dark), e⁻, shape ``(P, C, n, 3)`` for
        P prevailing and C calibration illuminants and n reflectances.
    gains
        The Eq. 4 gain of each (p, c) pair, output units per DN above the black level, shape ``(P, C, 1, 3)``.
    exposure_s
        Exposure, s, per calibration illuminant, shape ``(C,)``.
    notes
        A note where the ``auto`` exposure's longest exposure kept a white from its target (else empty).
    """

    electrons: NDArrayFloat
    gains: NDArrayFloat
    exposure_s: NDArrayFloat
    notes: tuple[str, ...] = ()


def _white_rates(im: Imager, cam: Camera, temperatures: NDArrayFloat, lux: float, grid: WavelengthGrid):
    """The white's electron rate per channel, e⁻/s (dark current included), and its Eq. 1 raw response."""
    irradiance = irradiance_planck(temperatures, lux, grid)  # W·m⁻²·nm⁻¹
    x = cam.sensitivities(grid)
    rate = electrons_mean(im, x / grid.wavelengths, irradiance / math.pi, 1.0, grid)  # QE ∝ x / λ
    raw = spds_on(illuminants_array(temperatures)[0], grid) @ x.T * grid.step  # Eq. 1 of the white
    return rate, raw


@dataclass(frozen=True)
class ImagedWhites:
    """
    The white of every (prevailing, calibration) pair through an imager (steps 1–3 above), formed once: what
    every reflectance set's pixels are formed from (:meth:`pixels`). Build it with :meth:`of`.

    Attributes
    ----------
    camera, setting
        The camera; the imager, illuminance (lx) and exposure (:class:`~skinrender.model.exposure.Imaging`).
    prevailing, calibrations, grid
        Illuminants, K, shapes ``(P,)`` and ``(C,)``; the wavelength grid, nm.
    rates, raw
        The white's electron rate under each prevailing light, e⁻/s (dark current included), and its Eq. 1 raw
        response, shapes ``(P, 3)``.
    gains, exposure_s, notes
        As :class:`PixelElectrons`.
    """

    camera: Camera
    setting: Imaging
    prevailing: NDArrayFloat
    calibrations: NDArrayFloat
    grid: WavelengthGrid
    rates: NDArrayFloat
    raw: NDArrayFloat
    gains: NDArrayFloat
    exposure_s: NDArrayFloat
    notes: tuple[str, ...] = ()

    @classmethod
    def of(cls, cam: Camera, prevailing: ArrayLike, calibrations: ArrayLike, setting: Imaging,
           grid: WavelengthGrid = GRID_DEFAULT) -> ImagedWhites:
        """The whites of ``cam`` under every pair of ``prevailing`` and ``calibrations`` (K), through ``setting``."""
        prevailing = _temperatures(prevailing, "prevailing")
        calibrations = _temperatures(calibrations, "calibrations")
        im, lux, auto = setting.imager, setting.illuminance_lux, setting.exposure == "auto"
        white_p, raw_white_p = _white_rates(im, cam, prevailing, lux, grid)  # (P, 3)
        white_c, _ = _white_rates(im, cam, calibrations, lux, grid)  # (C, 3)
        exposures = (np.atleast_1d(auto_exposure(im, white_c, AUTO_EXPOSURE_FRACTION, AUTO_EXPOSURE_MAX_S)) if auto
                     else np.full(calibrations.size, float(setting.exposure)))  # (C,)
        capped = auto_exposure_note(im, white_c, AUTO_EXPOSURE_FRACTION, AUTO_EXPOSURE_MAX_S) if auto else None
        # the Eq. 4 gain from the noise-free whites (DN above black) of each (p, c) pair, exposed for c
        t = exposures[None, :, None]
        gains = gain(im.gain_dn_per_e * white_p[:, None, :] * t, im.gain_dn_per_e * white_c[None, :, :] * t)
        return cls(cam, setting, prevailing, calibrations, grid, white_p, raw_white_p, gains[:, :, None, :],
                   exposures, (capped,) if capped else ())

    def pixels(self, reflectance: ArrayLike, name: str = "reflectance") -> PixelElectrons:
        """The expected electrons of reflectances on the grid (``(n, grid.size)``, fractions; ``name`` in errors)."""
        reflectance = _reflectance_array(reflectance, name, self.grid)
        dark = self.setting.imager.dark_current_e_per_s
        ratio = response_raw(self.camera, reflectance, self.prevailing, "none", self.grid) / self.raw[:, None, :]
        photo = ratio * (self.rates - dark)[:, None, :]  # e⁻/s, Eq. 1 ratio × the white's, (P, n, 3)
        electrons = (photo[:, None] + dark) * self.exposure_s[None, :, None, None]
        return PixelElectrons(electrons, self.gains, self.exposure_s, self.notes)


def pixel_electrons(
    cam: Camera,
    reflectance: ArrayLike,
    prevailing: ArrayLike,
    calibrations: ArrayLike,
    setting: Imaging,
    grid: WavelengthGrid = GRID_DEFAULT,
) -> PixelElectrons:
    """
    Expected electrons and white-balance gains of every (prevailing, calibration) pair (steps 1–3 above).

    Parameters
    ----------
    cam
        The camera.
    reflectance
        Reflectances on ``grid``, shape ``(n, grid.size)``, fractions.
    prevailing, calibrations
        Illuminants, K (Planckian): every pair of the two.
    setting
        The imager, the chart's illuminance (lx > 0) and the exposure (s > 0, or ``auto``):
        :func:`~skinrender.model.exposure.imaging`.
    grid
        The wavelength grid, nm.

    Returns
    -------
    :class:`PixelElectrons`

    Examples
    --------
    >>> from skinrender.model.camera import camera
    >>> pixels = pixel_electrons(camera("gbell:9@450,540,610"), np.ones((1, 301)), [3300.0], [3300.0],
    ...                          imaging("sony-imx174", 500.0))
    >>> print(f"{pixels.electrons.max() / 32691:.3f} of the full well in {pixels.exposure_s[0] * 1e3:.2f} ms")
    0.700 of the full well in 12.12 ms
    """

    reflectance = _reflectance_array(reflectance, "reflectance", grid)
    return ImagedWhites.of(cam, prevailing, calibrations, setting, grid).pixels(reflectance)


SECONDS_PER_NOISY_PIXEL = 8e-7
"""Time of one noisy pixel (draw, white balance, NCC, locus test), s: ``score --imager`` took 0.10 s per sample of
1299 reflectances × 100 illuminant pairs (4 vs 64 samples, 2-core AMD EPYC VM shared with other jobs)."""

NCC_LINEAR_MAX = 0.1
"""The delta method's NCC spread holds where the white-balanced channel sum's relative noise σ_S / S is at most
this: the neglected terms are of order (σ_S / S)², 1 %. Darker pixels (a black frame: S ≈ 0) are left out."""


@dataclass(frozen=True)
class _Draws:
    """The noisy pixels of one reflectance set: in the locus, black (no chromaticity), drawn; clipping counts."""

    hits: int
    black: int
    total: int
    clipping: dict


def _defined_rates(draws: _Draws, name: str, undefined: dict) -> tuple[float | None, float | None]:
    """The share of hits and its standard error, or ``None`` (reason in ``undefined``) where every pixel is black."""
    if draws.black == draws.total:
        undefined[name] = (f"every one of the {draws.total} noisy pixels is black (no channel above the black level): "
                           "no chromaticity to classify; raise the illuminance or the exposure")
        return None, None
    return _rates(draws.hits, draws.total)


def _skin_ncc_spread(im: Imager, pixels: PixelElectrons, undefined: dict) -> NDArrayFloat:
    """RMS NCC (r, g, b) std of the skin pixels by the delta method where it holds (:data:`NCC_LINEAR_MAX`)."""
    mean, variance = statistics_dn(im, pixels.electrons)
    signal = mean - im.black_level_dn
    gains = np.broadcast_to(pixels.gains, signal.shape)
    total = (signal * gains).sum(axis=-1)
    usable = (total > 0) & (np.sqrt((variance * gains**2).sum(axis=-1)) <= NCC_LINEAR_MAX * total)
    if not usable.any():
        undefined["skin_ncc_std"] = (f"no skin pixel's white-balanced channel sum is {1 / NCC_LINEAR_MAX:g}× its "
                                     "noise: the first-order (delta-method) NCC spread does not hold")
        return np.full(3, math.nan)
    covariance = ncc_covariance(signal[usable], variance[usable], gains[usable])
    return np.sqrt(np.mean(np.diagonal(covariance, axis1=-2, axis2=-1), axis=0))


def noisy_detection(
    cam: Camera,
    skin: ArrayLike,
    nonskin: ArrayLike,
    illuminants: ArrayLike,
    imager_: str | Path | Imager,
    illuminance_lux: float,
    exposure: float | str = "auto",
    samples: int = 16,
    seed: int | np.random.Generator = 0,
    calibration: float | None = None,
    grid: WavelengthGrid = GRID_DEFAULT,
    locus: SkinLocus | None = None,
) -> NoisyDetection:
    """
    True- and false-positive rates of the skin locus on noisy pixels of an imager.

    Parameters
    ----------
    cam
        The camera (:func:`skinrender.model.camera.camera`): its curves are the spectral channels.
    skin, nonskin
        Reflectances on ``grid``, shape ``(n, grid.size)``, fractions.
    illuminants
        The illuminant set, K (Planckian).
    imager_
        An :class:`~skinrender.model.imager.Imager`, a preset name or a TOML path.
    illuminance_lux
        The chart's illuminance, lx > 0, under every illuminant.
    exposure
        Exposure, s > 0, or ``auto`` (the white under the calibration light
        at :data:`AUTO_EXPOSURE_FRACTION` of the full well).
    samples
        Noisy pixels per (reflectance, prevailing, calibration), ≥ 1.
    seed
        An integer seed in [0, 2³²) or a numpy Generator.
    calibration
        One white balancing at this temperature, K, or ``None`` for every
        calibration of the set (as :func:`~skinrender.evaluation.locus.skin_locus`).
    grid
        The wavelength grid, nm.
    locus
        The noise-free skin locus if already drawn (convex hull of ``skin``
        over the same illuminants and calibration); drawn here otherwise.

    Returns
    -------
    :class:`NoisyDetection`

    Raises
    ------
    SkinrenderError
        Naming the argument: a non-positive or NaN illuminance or exposure, a
        bad ``samples`` or ``seed``, reflectances off the grid.

    Examples
    --------
    >>> from skinrender.datasets import reflectances
    >>> from skinrender.model.camera import camera
    >>> skin, chips = reflectances("skin").on(), reflectances("munsell").on()[::10]
    >>> result = noisy_detection(camera("gbell:9@450,540,610"), skin, chips, [2500.0, 4000.0, 6500.0],
    ...                          "sony-imx174", 500.0, samples=4, seed=1)
    >>> print(f"TPR {result.tpr:.3f} (noise-free {result.tpr_noise_free:.3f}), {len(result.exposure_s)} exposures")
    TPR 0.9... (noise-free 1.000), 3 exposures
    """

    setting = imaging(imager_, illuminance_lux, exposure)
    im = setting.imager
    skin = _reflectance_array(skin, "skin", grid)
    nonskin = _reflectance_array(nonskin, "nonskin", grid)
    prevailing = _temperatures(illuminants, "illuminants")
    calibrations = prevailing if calibration is None else _temperatures(calibration, "calibration")
    if isinstance(samples, bool) or not isinstance(samples, numbers.Integral) or samples < 1:
        raise SkinrenderError(f"samples must be an integer ≥ 1, got {samples!r}")
    rng = random_generator(seed, "seed")

    if locus is None:
        locus = skin_locus(cam, skin, prevailing, calibration, "hull", grid)
    tpr_free = float(np.mean(locus.contains(locus_points(cam, skin, prevailing, calibration, grid))))
    fpr_free = false_positive_rate(locus, cam, nonskin, grid)

    def inside(pixels: PixelElectrons) -> _Draws:
        hits = black = 0
        full = clipped = np.zeros(pixels.electrons.shape, int)  # draws clipped, per pixel and channel
        for _ in range(samples):
            dn, well_full, adc_clipped = simulate_dn_clipped(im, pixels.electrons, rng)
            full, clipped = full + well_full, clipped + adc_clipped
            balanced = np.maximum(dn - im.black_level_dn, 0.0) * pixels.gains  # DN above black × gain
            positive = balanced.sum(axis=-1) > 0  # a black pixel has no chromaticity
            black += int(np.count_nonzero(~positive))
            hits += int(np.count_nonzero(locus.contains(ncc(balanced)[..., :2]) & positive))
        total = samples * int(np.prod(pixels.electrons.shape[:-1]))
        return _Draws(hits, black, total, clipping_counts(full, clipped, total))  # every draw counted

    whites = ImagedWhites.of(cam, prevailing, calibrations, setting, grid)  # formed once, for both sets
    on_skin = whites.pixels(skin, "skin")
    skin_draws = inside(on_skin)
    nonskin_draws = inside(whites.pixels(nonskin, "nonskin"))
    undefined: dict = {}
    (tpr, tpr_se), (fpr, fpr_se) = (_defined_rates(draws, name, undefined)
                                    for draws, name in ((skin_draws, "tpr"), (nonskin_draws, "fpr")))
    exposures = on_skin.exposure_s
    spread = _skin_ncc_spread(im, on_skin, undefined)
    clipped = ((name, clipping_note(draws.clipping)) for name, draws in (("skin", skin_draws), ("nonskin", nonskin_draws)))
    notes = on_skin.notes + tuple(f"{name} pixels {note}" for name, note in clipped if note)
    return NoisyDetection(
        tpr=tpr, fpr=fpr, tpr_se=tpr_se, fpr_se=fpr_se, samples=int(samples),
        exposure_s=tuple(float(value) for value in exposures), illuminance_lux=setting.illuminance_lux,
        imager=im.name, tpr_noise_free=tpr_free, fpr_noise_free=fpr_free,
        calibrations_K=tuple(float(value) for value in calibrations),
        skin_ncc_std=tuple(float(value) for value in spread), undefined=undefined,
        black_share=(skin_draws.black / skin_draws.total, nonskin_draws.black / nonskin_draws.total),
        clipping={"skin": skin_draws.clipping, "nonskin": nonskin_draws.clipping}, notes=notes,
    )
