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
first), the read noise the dark frames' temporal noise divided by the gain,
the saturation capacity the mean at the largest variance divided by the gain,
and the linearity error the largest deviation of the mean from a line through
the origin fitted between 5 % and 95 % of saturation, in percent of the fitted
value.

References
----------
-   [EMVA1288]_ : EMVA Standard 1288, release 4.0 (docs/references.md).
"""

from __future__ import annotations

import numpy as np

from ..errors import SkinrenderError
from ..model.camera import Camera
from ..model.imager import Imager, imager
from ..model.noise import simulate_dn
from ..rendering.imaging import electrons_per_radiance
from ..rendering.renderer import render_raw
from ..rendering.scene import ChartScene, Patch
from ..spectra import GRID_DEFAULT, WavelengthGrid

__all__ = ["GREY_CHART", "photon_transfer"]

GREY_CHART = ChartScene(name="ptc grey", description="one flat grey patch (reflectance 0.5) for photon transfer",
                        columns=1, patch_px=64, gap_px=0, border_px=0,
                        patches=(Patch("grey 0.5", "grey:0.5", False),), source="skinrender.studies.ptc")
"""The flat chart: 64 × 64 pixels of a grey of reflectance 0.5."""

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


def photon_transfer(
    camera_: Camera,
    imager_: Imager | str,
    temperature: float = 5900.0,
    illuminance_lux: float = 500.0,
    points: int = 24,
    spp: int = 64,
    seed: int = 0,
    grid: WavelengthGrid = GRID_DEFAULT,
    **render_options,
) -> dict:
    """
    Measure the photon transfer of ``camera_`` recorded by ``imager_`` under a Planckian light (K, lx).

    ``points`` exposures are spaced evenly from 0 to 1.3 × the exposure that fills the brightest channel's
    well (so the series passes saturation). Returns ``points`` (``[{exposure_s, mean_dn, variance_dn, snr}]``,
    dark-subtracted, per channel R, G, B), ``gain_dn_per_e``, ``read_noise_e``, ``full_well_e``,
    ``linearity_error`` (percent), each per channel, and ``stated`` (the imager's own figures).
    """

    im = imager(imager_)
    if not (isinstance(points, (int, np.integer)) and 4 <= points <= 1000):
        raise SkinrenderError(f"points must be an integer in [4, 1000] exposures, got {points!r}")
    raw = render_raw(GREY_CHART, camera_, temperature, spp, seed, grid=grid, **render_options)
    rate = raw.radiance * electrons_per_radiance(im, camera_, temperature, illuminance_lux, grid)  # e⁻/s per pixel
    brightest = float(rate.mean(axis=(0, 1)).max())  # e⁻/s
    if not brightest > DARK_SHARE_MAX * im.dark_current_e_per_s:
        raise SkinrenderError(
            f"--illuminance: {illuminance_lux:g} lx at {temperature:g} K gives the brightest channel {brightest:.3g} "
            f"e⁻/s, not above {DARK_SHARE_MAX:g}× the dark current ({im.dark_current_e_per_s:g} e⁻/s): the dark "
            "current would fill the well before the light does, and no transfer curve can be measured; raise the "
            "illuminance")
    fill = im.full_well_e / brightest
    exposures = np.linspace(0.0, 1.3 * fill, points)
    rows, dark_noise = [], []
    for index, t in enumerate(exposures):
        dark = _frames(im, np.full(rate.shape, im.dark_current_e_per_s * t), seed, 2 * index)
        light = _frames(im, (rate + im.dark_current_e_per_s) * t, seed, 2 * index + 1)
        dark_mean = 0.5 * (dark[0] + dark[1]).mean(axis=(0, 1))
        mean = 0.5 * (light[0] + light[1]).mean(axis=(0, 1)) - dark_mean
        variance = 0.5 * (light[0] - light[1]).var(axis=(0, 1), ddof=1) - 0.5 * (dark[0] - dark[1]).var(
            axis=(0, 1), ddof=1)
        dark_noise.append(0.5 * (dark[0] - dark[1]).var(axis=(0, 1), ddof=1))
        rows.append({"exposure_s": float(t), "mean_dn": mean.tolist(), "variance_dn": variance.tolist(),
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
    dark_std = np.sqrt(np.mean(dark_noise, axis=0))
    read_noise = np.sqrt(np.maximum(dark_std**2 - 1.0 / 12.0, 0.0)) / np.array(gain_k)  # quantisation removed
    measurable = dark_std >= DARK_NOISE_MIN_DN
    return {
        "camera": camera_.name, "imager": im.name, "temperature_K": float(temperature),
        "illuminance_lux": float(illuminance_lux), "spp": raw.spp, "seed": int(seed), "points": rows,
        "gain_dn_per_e": gain_k,
        "read_noise_e": [float(v) if ok else None for v, ok in zip(read_noise, measurable)],
        "undefined": ({} if measurable.all() else {"read_noise_e": f"the dark noise ({dark_std.min():.2g} DN) is "
                      f"below {DARK_NOISE_MIN_DN} DN: quantisation hides the read noise (EMVA 1288)"}),
        "full_well_e": full_well,
        "linearity_error": linearity,
        "stated": {"gain_dn_per_e": im.gain_dn_per_e, "read_noise_e": im.read_noise_e, "full_well_e": im.full_well_e},
    }
