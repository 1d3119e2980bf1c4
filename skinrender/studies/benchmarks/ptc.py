"""
Photon transfer
===============

The simulated camera measured the way EMVA 1288 measures a real one: a flat
grey chart rendered once, recorded through the image sensor over an exposure
series, two frames per exposure and a dark frame pair; from the pixels alone,
the photon transfer curve (dark-subtracted mean against temporal variance) and
what it gives — conversion gain, read noise, saturation capacity, linearity
error, signal-to-noise ratio — beside the values the imager states.

-   :func:`photon_transfer`: the measurement, a dict with CONTRACT.md's keys.

Units: exposure s, means DN, variances DN², gain DN/e⁻, noise and capacity e⁻,
linearity error in percent.

Notes
-----
As EMVA 1288 prescribes, the temporal variance is half the variance of the
difference of two frames of the same exposure, which cancels every
fixed pattern — here the render's own Monte Carlo noise, identical in both
frames. The gain is the slope of variance against mean over the points below
70 % of saturation (the linear range; quantisation, 1/12 DN², is removed
first). The dark frames' temporal variance grows with the exposure,
σ_y.dark² = K² (σ_r² + μ_I t) + 1/12 DN², by the dark current's shot noise: the
read noise is the intercept at t = 0 of a line fitted to it over the series,
less quantisation, divided by the gain, and the dark current μ_I (e⁻/s) the
slope of the dark mean against the exposure divided by the gain (EMVA 1288's
dark current measurement);
the saturation capacity the mean at the largest variance divided by the gain,
and the linearity error the largest deviation of the mean from a line through
the origin fitted between 5 % and 95 % of saturation, in percent of the fitted
value.

References
----------
-   :cite:`EMVA1288` : EMVA Standard 1288, release 4.0 (docs/references.md).
"""

from __future__ import annotations

import numpy as np

from ...errors import SkinrenderError
from ...model.camera import Camera
from ...model.imager import Imager, imager
from ...model.noise import simulate_dn
from ...rendering.imaging import electrons_per_radiance
from ...rendering.renderer import render_raw
from ...rendering.scene import ChartScene, Patch
from ...rendering.settings import RenderSettings
from ...spectra import GRID_DEFAULT, WavelengthGrid

__all__ = ["GREY_CHART", "PTC_SETTINGS", "photon_transfer"]

GREY_CHART = ChartScene(name="ptc grey", description="one flat grey patch (reflectance 0.5) for photon transfer",
                        columns=1, patch_px=64, gap_px=0, border_px=0,
                        patches=(Patch("grey 0.5", "grey:0.5", False),), source="skinrender.studies.benchmarks.ptc")
"""The flat chart: 64 × 64 pixels of a grey of reflectance 0.5."""

PTC_SETTINGS = RenderSettings(spp=64)
"""The render of the grey chart unless given: 64 spp, seed 0."""

DARK_NOISE_MIN_DN = 0.5
"""Below this temporal dark noise, DN, the ADC's quantisation hides the read noise: it is reported as undefined
(EMVA 1288 release 4.0 asks for σ_dark ≥ 0.5 DN)."""

LINEAR_RANGE = 0.7
"""Points whose mean is below this share of the saturated mean fit the gain."""


DARK_SHARE_MAX = 10.0
"""The brightest channel's photo-electron rate must exceed the dark current this many times: dimmer, the dark
current fills the well first (a curve of dark frames, not of light)."""


def _frames(im: Imager, electrons: np.ndarray, seed: int, index: int) -> tuple[np.ndarray, np.ndarray]:
    generator = np.random.default_rng([seed, index])
    return simulate_dn(im, electrons, generator), simulate_dn(im, electrons, generator)


DARK_CURRENT_PRECISION = 0.2
"""The dark current is reported only where its fit's standard error is at most this share of it (five standard
errors above zero): a series of short exposures (bright light) holds too little dark charge to measure it (at
1e4 lx the imx174's series gave −4.5 and −17.2 e⁻/s for a stated 10)."""


def _dark_fit(exposures: np.ndarray, variances: np.ndarray, means: np.ndarray,
              gains: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """
    The dark frames over the series: the temporal variance's intercept at t = 0, DN², the dark current, e⁻/s,
    and its standard error, e⁻/s.

    σ_y.dark²(t) = σ_0² + K² μ_I t and μ_y.dark(t) = μ_y.dark(0) + K μ_I t, per channel: straight lines in the
    exposure t (s); the intercept σ_0² = K² σ_r² + 1/12 DN² holds the read noise alone, the slope of the mean over
    K the dark current μ_I, its standard error the least-squares one (residual variance over n − 2 degrees of
    freedom). ``variances``, ``means``: ``(points, 3)``, DN² and DN; ``gains``: K, DN/e⁻, ``(3,)``.
    """
    variance_line = np.polyfit(exposures, variances, 1)  # (2, 3): slope, intercept
    slope, intercept = np.polyfit(exposures, means, 1)
    residuals = means - (np.outer(exposures, slope) + intercept)
    spread = np.sum((exposures - exposures.mean()) ** 2)
    error = np.sqrt(np.sum(residuals**2, axis=0) / max(exposures.size - 2, 1) / spread)
    return variance_line[1], slope / gains, error / np.abs(gains)


def _dark_current(current: np.ndarray, error: np.ndarray, measurable: np.ndarray, dark_std: np.ndarray,
                  longest_s: float) -> tuple[list, str | None]:
    """The dark currents reported (``None`` where not well conditioned) and why any is not, or ``None``."""
    if not measurable.all():
        return [None] * 3, (f"the dark noise ({dark_std.min():.2g} DN) is below {DARK_NOISE_MIN_DN} DN: the dark "
                            "frames' codes do not follow their mean (no dither), so their slope is not the dark current")
    resolved = (current > 0) & (error <= DARK_CURRENT_PRECISION * current)
    if resolved.all():
        return [float(v) for v in current], None
    fits = ", ".join(f"{c:.3g} ± {e:.2g}" for c, e in zip(current, error))
    return [float(v) if ok else None for v, ok in zip(current, resolved)], (
        f"not resolved by this series: its longest exposure ({longest_s * 1e3:.3g} ms) holds too little dark charge "
        f"against the dark frames' noise (fits R, G, B {fits} e⁻/s; reported where positive with a standard error "
        f"≤ {DARK_CURRENT_PRECISION:.0%} of it); lower --illuminance for longer exposures")


def photon_transfer(
    camera_: Camera,
    imager_: Imager | str,
    temperature: float = 5900.0,
    illuminance_lux: float = 500.0,
    points: int = 24,
    settings: RenderSettings = PTC_SETTINGS,
    grid: WavelengthGrid = GRID_DEFAULT,
    **options,
) -> dict:
    """
    Measure the photon transfer of ``camera_`` recorded by ``imager_`` under a Planckian light (K, lx).

    ``points`` exposures are spaced evenly from 0 to 1.3 × the exposure that fills the brightest channel's
    well (so the series passes saturation). Returns ``points`` (``[{exposure_s, mean_dn, variance_dn, snr,
    dark_variance_dn}]``, dark-subtracted, per channel R, G, B; ``dark_variance_dn`` the dark frames' temporal
    variance at that exposure, DN², read noise plus the dark current's shot noise plus quantisation),
    ``gain_dn_per_e``, ``read_noise_e`` (the dark variance's intercept at t = 0: no dark current),
    ``dark_current_e_per_s`` (measured from the dark means), ``full_well_e``, ``linearity_error`` (percent), each
    per channel, and ``stated`` (the imager's own figures). ``settings``: the render's, and its seed the
    sensor noise's (or its fields ``spp``, ``seed`` … as ``options``).
    """

    im = imager(imager_)
    if not (isinstance(points, (int, np.integer)) and 4 <= points <= 1000):
        raise SkinrenderError(f"points must be an integer in [4, 1000] exposures, got {points!r}")
    settings = RenderSettings.of(settings, **options)
    seed = settings.seed
    raw = render_raw(GREY_CHART, camera_, temperature, settings, grid)
    rate = raw.radiance * electrons_per_radiance(im, camera_, temperature, illuminance_lux, grid)  # e⁻/s per pixel
    brightest = float(rate.mean(axis=(0, 1)).max())  # e⁻/s
    if not brightest > DARK_SHARE_MAX * im.dark_current_e_per_s:
        raise SkinrenderError(
            f"--illuminance: {illuminance_lux:g} lx at {temperature:g} K gives the brightest channel {brightest:.3g} "
            f"e⁻/s, not above {DARK_SHARE_MAX:g}× the dark current ({im.dark_current_e_per_s:g} e⁻/s): the dark "
            "current would fill the well before the light does, and no transfer curve can be measured; raise the "
            "illuminance", flag="--illuminance")
    fill = im.full_well_e / brightest
    exposures = np.linspace(0.0, 1.3 * fill, points)
    rows, dark_noise, dark_means = [], [], []
    for index, t in enumerate(exposures):
        dark = _frames(im, np.full(rate.shape, im.dark_current_e_per_s * t), seed, 2 * index)
        light = _frames(im, (rate + im.dark_current_e_per_s) * t, seed, 2 * index + 1)
        dark_mean = 0.5 * (dark[0] + dark[1]).mean(axis=(0, 1))
        mean = 0.5 * (light[0] + light[1]).mean(axis=(0, 1)) - dark_mean
        variance = 0.5 * (light[0] - light[1]).var(axis=(0, 1), ddof=1) - 0.5 * (dark[0] - dark[1]).var(
            axis=(0, 1), ddof=1)
        dark_noise.append(0.5 * (dark[0] - dark[1]).var(axis=(0, 1), ddof=1))
        dark_means.append(dark_mean)
        rows.append({"exposure_s": float(t), "mean_dn": mean.tolist(), "variance_dn": variance.tolist(),
                     "dark_variance_dn": dark_noise[-1].tolist(),
                     "snr": np.divide(mean, np.sqrt(variance + dark_noise[-1]), out=np.zeros(3),
                                      where=variance + dark_noise[-1] > 0).tolist()})
    means = np.array([r["mean_dn"] for r in rows])  # (points, 3)
    variances = np.array([r["variance_dn"] for r in rows])
    saturated = np.argmax(variances, axis=0)
    gain_k, full_well, linearity = [], [], []
    for k in range(3):
        top = means[saturated[k], k]
        fit = (means[:, k] > 0) & (means[:, k] <= LINEAR_RANGE * top)
        if fit.sum() < 2:
            raise SkinrenderError("photon transfer: too few exposures below saturation; use more points")
        slope = float(np.polyfit(means[fit, k], variances[fit, k], 1)[0])
        gain_k.append(slope)
        full_well.append(float(top / slope))
        band = (means[:, k] >= 0.05 * top) & (means[:, k] <= 0.95 * top)
        line = np.sum(means[band, k] * exposures[band]) / np.sum(exposures[band] ** 2)
        linearity.append(float(np.max(np.abs(means[band, k] - line * exposures[band]) / (line * exposures[band]))
                               * 100.0))
    dark_intercept, dark_current, dark_error = _dark_fit(exposures, np.array(dark_noise), np.array(dark_means),
                                                         np.array(gain_k))
    dark_std = np.sqrt(np.maximum(dark_intercept, 0.0))  # DN: the temporal dark noise at t = 0
    read_noise = np.sqrt(np.maximum(dark_intercept - 1.0 / 12.0, 0.0)) / np.array(gain_k)  # quantisation removed
    measurable = dark_std >= DARK_NOISE_MIN_DN
    current, why = _dark_current(dark_current, dark_error, measurable, dark_std, float(exposures[-1]))
    undefined = {} if measurable.all() else {
        "read_noise_e": f"the dark noise ({dark_std.min():.2g} DN) is below {DARK_NOISE_MIN_DN} DN: quantisation "
                        "hides the read noise (EMVA 1288)"}
    if why is not None:
        undefined["dark_current_e_per_s"] = why
    return {
        "camera": camera_.name, "imager": im.name, "temperature_K": float(temperature),
        "illuminance_lux": float(illuminance_lux), "spp": raw.spp, "seed": int(seed), "points": rows,
        "gain_dn_per_e": gain_k,
        "read_noise_e": [float(v) if ok else None for v, ok in zip(read_noise, measurable)],
        "undefined": undefined,
        "dark_current_e_per_s": current,
        "full_well_e": full_well,
        "linearity_error": linearity,
        "stated": {"gain_dn_per_e": im.gain_dn_per_e, "read_noise_e": im.read_noise_e, "full_well_e": im.full_well_e,
                   "dark_current_e_per_s": im.dark_current_e_per_s},
    }
