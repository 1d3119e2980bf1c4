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
-   :func:`electron_rates`, :func:`measure`: its two halves, the render and the sensor's measurement (with each
    fit's standard error).
-   :func:`ptc_calibration`: the false-alarm rate of its verdict
    (:mod:`~skinrender.studies.benchmarks.ptc_verdict`) over sensor seeds of one render.

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

import time
from collections.abc import Callable

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

__all__ = ["GREY_CHART", "PTC_SETTINGS", "electron_rates", "measure", "photon_transfer", "ptc_calibration"]

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

DITHER_MIN_DN = 0.6
"""Points whose light frames' temporal noise (quantisation removed) is below this, DN, are left out of the gain's fit:
rounding a narrower noise to codes does not add 1/12 DN² but a share that swings with the mean's fraction of a code,
by up to 0.0079 DN² at 0.5 DN, 0.0013 at 0.6 and 1.3e-4 at 0.7 (the rounded normal's variance, computed). The 8-bit
sony-icx418's first points (0.29 DN at 14 DN) biased its gain by up to 4 standard errors (184 of 200 seeds failed
the fits' test at α 0.01 before this cut)."""


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


def _half_variance(difference: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """
    Half the variance of a two-frame difference ``(H, W, 3)`` per channel, DN² (the temporal variance of one frame),
    and its sampling variance, DN⁴, from the pixels' own fourth moment (any law):
    Var(s²) = (m₄ − (n − 3)/(n − 1) s⁴)/n.
    """
    x = difference.reshape(-1, difference.shape[-1]).astype(np.float64)
    n = x.shape[0]
    centred = x - x.mean(axis=0)
    m2 = np.sum(centred**2, axis=0) / (n - 1)
    m4 = np.mean(centred**4, axis=0)
    return 0.5 * m2, 0.25 * np.maximum(m4 - (n - 3) / (n - 1) * m2**2, 0.0) / n


def _line(x: np.ndarray, y: np.ndarray) -> tuple[float, float, np.ndarray, np.ndarray]:
    """
    The unweighted least-squares line through ``(x, y)`` (EMVA 1288's fit): slope, intercept and their weights
    (``slope = w_s·y``, ``intercept = w_i·y``), whose sampling variances are ``w_s²·v`` and ``w_i²·v`` for the
    points' independent sampling variances ``v`` (x taken as exact: each a mean of thousands of pixels).
    """
    centred = x - x.mean()
    w_slope = centred / np.sum(centred**2)
    w_intercept = 1.0 / x.size - x.mean() * w_slope
    return float(w_slope @ y), float(w_intercept @ y), w_slope, w_intercept


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


def electron_rates(camera_: Camera, im: Imager, temperature: float, illuminance_lux: float,
                   settings: RenderSettings, grid: WavelengthGrid = GRID_DEFAULT) -> tuple[np.ndarray, int]:
    """
    The grey chart rendered once: its photo-electron rate per pixel and channel, e⁻/s ``(H, W, 3)``, and the spp
    used. Refuses a light whose brightest channel does not outrun the dark current :data:`DARK_SHARE_MAX` times.
    """
    raw = render_raw(GREY_CHART, camera_, temperature, settings, grid)
    rate = raw.radiance * electrons_per_radiance(im, camera_, temperature, illuminance_lux, grid)  # e⁻/s per pixel
    brightest = float(rate.mean(axis=(0, 1)).max())  # e⁻/s
    if not brightest > DARK_SHARE_MAX * im.dark_current_e_per_s:
        raise SkinrenderError(
            f"--illuminance: {illuminance_lux:g} lx at {temperature:g} K gives the brightest channel {brightest:.3g} "
            f"e⁻/s, not above {DARK_SHARE_MAX:g}× the dark current ({im.dark_current_e_per_s:g} e⁻/s): the dark "
            "current would fill the well before the light does, and no transfer curve can be measured; raise the "
            "illuminance", flag="--illuminance")
    return rate, raw.spp


def _series(im: Imager, rate: np.ndarray, seed: int, exposures: np.ndarray) -> tuple[list, dict]:
    """The exposure series' rows (JSON) and, as ``(points, 3)`` arrays, each point's statistics and their sampling
    variances: ``mean`` (DN), ``variance``, ``variance_var``, ``light_variance`` (the light frames' own, DN²),
    ``dark_variance``, ``dark_variance_var``, ``dark_mean``,
    ``dark_mean_var``."""
    rows, stats = [], {key: [] for key in ("mean", "variance", "variance_var", "light_variance", "dark_variance",
                                           "dark_variance_var", "dark_mean", "dark_mean_var")}
    pixels = rate.shape[0] * rate.shape[1]
    for index, t in enumerate(exposures):
        dark = _frames(im, np.full(rate.shape, im.dark_current_e_per_s * t), seed, 2 * index)
        light = _frames(im, (rate + im.dark_current_e_per_s) * t, seed, 2 * index + 1)
        dark_sum = 0.5 * (dark[0] + dark[1])
        dark_mean = dark_sum.mean(axis=(0, 1))
        mean = 0.5 * (light[0] + light[1]).mean(axis=(0, 1)) - dark_mean
        light_variance, light_var = _half_variance(light[0] - light[1])
        dark_variance, dark_var = _half_variance(dark[0] - dark[1])
        variance = light_variance - dark_variance
        for key, value in (("mean", mean), ("variance", variance), ("variance_var", light_var + dark_var),
                           ("light_variance", light_variance),
                           ("dark_variance", dark_variance), ("dark_variance_var", dark_var),
                           ("dark_mean", dark_mean), ("dark_mean_var", dark_sum.reshape(-1, 3).var(axis=0, ddof=1)
                                                      / pixels)):
            stats[key].append(value)
        rows.append({"exposure_s": float(t), "mean_dn": mean.tolist(), "variance_dn": variance.tolist(),
                     "dark_variance_dn": dark_variance.tolist(),
                     "snr": np.divide(mean, np.sqrt(light_variance), out=np.zeros(3),
                                      where=light_variance > 0).tolist()})
    return rows, {key: np.array(value) for key, value in stats.items()}


def measure(im: Imager, rate: np.ndarray, seed: int, points: int = 24) -> dict:
    """
    The EMVA 1288 measurement of ``im`` recording the electron ``rate`` (e⁻/s ``(H, W, 3)``, from
    :func:`electron_rates`) with sensor-noise ``seed``: :func:`photon_transfer`'s keys but the render's, each fit with
    its ``standard_error`` (the sampling one, propagated from every point's own: see the module's Notes) and the
    fits' ``correlation`` per channel (``gain_read_noise``, ``gain_dark_current``, ``read_noise_dark_current``: the
    read noise divides by the gain and shares its dark variances, the dark current divides by it; delta method).
    """
    fill = im.full_well_e / float(rate.mean(axis=(0, 1)).max())
    exposures = np.linspace(0.0, 1.3 * fill, points)
    rows, s = _series(im, rate, seed, exposures)
    means, variances = s["mean"], s["variance"]
    saturated = np.argmax(variances, axis=0)
    gain, gain_var, full_well, linearity, covariance = np.zeros(3), np.zeros(3), [], [], np.zeros(3)
    dark_var, intercept_var, dark_current, dark_current_var = np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3)
    for k in range(3):
        top = means[saturated[k], k]
        fit = ((means[:, k] > 0) & (means[:, k] <= LINEAR_RANGE * top)
               & (s["light_variance"][:, k] >= DITHER_MIN_DN**2 + 1.0 / 12.0))
        if fit.sum() < 2:
            raise SkinrenderError(f"photon transfer: too few exposures between a temporal noise of {DITHER_MIN_DN} DN "
                                  f"and {LINEAR_RANGE:.0%} of saturation to fit the gain; use more points (24 suit both presets)")
        gain[k], _, w_gain, _ = _line(means[fit, k], variances[fit, k])
        gain_var[k] = w_gain**2 @ s["variance_var"][fit, k]
        full_well.append(float(top / gain[k]))
        band = (means[:, k] >= 0.05 * top) & (means[:, k] <= 0.95 * top)
        line = np.sum(means[band, k] * exposures[band]) / np.sum(exposures[band] ** 2)
        linearity.append(float(np.max(np.abs(means[band, k] - line * exposures[band]) / (line * exposures[band]))
                               * 100.0))
        # the dark variance's intercept at t = 0 (read noise and quantisation, no dark current) …
        _, dark_var[k], _, w_intercept = _line(exposures, s["dark_variance"][:, k])
        intercept_var[k] = w_intercept**2 @ s["dark_variance_var"][:, k]
        # … shares the dark variances the gain's points subtract: Cov(intercept, K) = −Σ w_i w_s Var(dark variance)
        covariance[k] = -np.sum(w_intercept[fit] * w_gain * s["dark_variance_var"][fit, k])
        # … and the dark mean's slope over K: the dark current (EMVA 1288's dark current measurement)
        slope, _, w_slope, _ = _line(exposures, s["dark_mean"][:, k])
        dark_current[k] = slope / gain[k]
        dark_current_var[k] = (w_slope**2 @ s["dark_mean_var"][:, k] + dark_current[k] ** 2 * gain_var[k]) / gain[k] ** 2
    dark_std = np.sqrt(np.maximum(dark_var, 0.0))  # DN: the temporal dark noise at t = 0
    excess = np.maximum(dark_var - 1.0 / 12.0, 0.0)  # quantisation removed
    read_noise = np.sqrt(excess) / gain
    with np.errstate(divide="ignore", invalid="ignore"):  # ln RN = ½ ln(intercept − 1/12) − ln K (delta method)
        read_noise_se = read_noise * np.sqrt(np.maximum(
            intercept_var / (4 * excess**2) + gain_var / gain**2 - covariance / (excess * gain), 0.0))
    measurable = dark_std >= DARK_NOISE_MIN_DN
    dark_current_se = np.sqrt(dark_current_var)
    with np.errstate(divide="ignore", invalid="ignore"):  # the fits share data: their correlations (delta method)
        cov_rn_k = read_noise * (covariance / (2 * excess) - gain_var / gain)
        cov_dc_k = -dark_current * gain_var / gain
        cov_rn_dc = read_noise * dark_current / gain * (gain_var / gain - covariance / (2 * excess))
        gain_se = np.sqrt(gain_var)
        correlation = {"gain_read_noise": cov_rn_k / (read_noise_se * gain_se),
                       "gain_dark_current": cov_dc_k / (dark_current_se * gain_se),
                       "read_noise_dark_current": cov_rn_dc / (read_noise_se * dark_current_se)}
    current, why = _dark_current(dark_current, dark_current_se, measurable, dark_std, float(exposures[-1]))
    undefined = {} if measurable.all() else {
        "read_noise_e": f"the dark noise ({dark_std.min():.2g} DN) is below {DARK_NOISE_MIN_DN} DN: quantisation "
                        "hides the read noise (EMVA 1288)"}
    if why is not None:
        undefined["dark_current_e_per_s"] = why
    kept = lambda values, ok: [float(v) if o else None for v, o in zip(values, ok)]  # noqa: E731
    return {
        "seed": int(seed), "points": rows,
        "gain_dn_per_e": gain.tolist(),
        "read_noise_e": kept(read_noise, measurable),
        "undefined": undefined,
        "dark_current_e_per_s": current,
        "full_well_e": full_well,
        "linearity_error": linearity,
        "stated": {"gain_dn_per_e": im.gain_dn_per_e, "read_noise_e": im.read_noise_e, "full_well_e": im.full_well_e,
                   "dark_current_e_per_s": im.dark_current_e_per_s},
        "correlation": {key: [float(v) if np.isfinite(v) else None for v in np.clip(value, -1.0, 1.0)]
                        for key, value in correlation.items()},
        "standard_error": {"gain_dn_per_e": np.sqrt(gain_var).tolist(),
                           "read_noise_e": kept(read_noise_se, measurable),
                           "dark_current_e_per_s": kept(dark_current_se, [c is not None for c in current])},
    }


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
    per channel, ``stated`` (the imager's own figures), ``standard_error`` (of the first three) and the verdict's
    keys (:func:`~skinrender.studies.benchmarks.ptc_verdict.ptc_verdict`: ``z``, ``checks``, ``verdict``, ``passed``,
    ``exit_status``, ``information_only``). ``settings``: the render's, and its seed the sensor noise's (or its
    fields ``spp``, ``seed`` … as ``options``).
    """

    from .ptc_verdict import ptc_verdict

    im = imager(imager_)
    if not (isinstance(points, (int, np.integer)) and 4 <= points <= 1000):
        raise SkinrenderError(f"points must be an integer in [4, 1000] exposures, got {points!r}")
    settings = RenderSettings.of(settings, **options)
    rate, spp = electron_rates(camera_, im, temperature, illuminance_lux, settings, grid)
    result = {"camera": camera_.name, "imager": im.name, "temperature_K": float(temperature),
              "illuminance_lux": float(illuminance_lux), "spp": spp, **measure(im, rate, settings.seed, points)}
    return {**result, **ptc_verdict(result)}


def ptc_calibration(camera_, imager_, temperature: float = 5900.0, illuminance_lux: float = 500.0, seeds: int = 40,
                    first_seed: int = 0, points: int = 24, spp: int = 64, alpha: float = 0.01,
                    progress: Callable[[str], None] | None = None) -> dict:
    """
    ``seeds`` photon-transfer measurements of a correct imager (the sensor noise's seeds ``first_seed``,
    ``first_seed + 1``, …; the grey chart rendered once at ``spp`` with seed ``first_seed``): every failure of the
    fits' test is a false alarm. Per check (``fits``, the family; each tested figure, its share of it) the observed
    rate with its Clopper–Pearson 95 % interval against the nominal α, and per figure and channel the mean and
    standard deviation of z (0 and 1 where the standard errors are right).

    Returns
    -------
    dict
        ``machine``, ``scene`` (``ptc``), ``camera``, ``imager``, ``illuminance_lux``, ``prevailing_K`` (the light,
        K), ``calibration_K`` (``None``), ``spp``, ``points``, ``seeds``, ``first_seed``, ``seed_step`` (1),
        ``checks`` (``[{name, nominal_alpha, nominal, failures, seeds, rate, interval, consistent, outcomes}]``),
        ``z`` (``{figure: {mean, sd, values}}``, per channel), ``tests``, ``runs`` (``[{seed, verdict, statistic,
        worst}]``), ``elapsed_s``.
    """
    from .bench import machine
    from .ptc_verdict import TESTED, false_alarm_rows, ptc_verdict

    begun = time.perf_counter()
    im = imager(imager_)
    rate, used = electron_rates(camera_, im, temperature, illuminance_lux, RenderSettings(spp=spp, seed=first_seed))
    runs, test = [], ""
    for seed in range(first_seed, first_seed + seeds):
        verdict = ptc_verdict(measure(im, rate, seed, points), alpha)
        check = verdict["checks"]["fits"]
        test = check["test"]
        runs.append({"seed": seed, "verdict": verdict["verdict"], "statistic": check["statistic"],
                     "threshold": check["threshold"], "worst": check.get("worst_figure"), "tested": check["tested"],
                     "z": verdict["z"]})
        if progress is not None:
            progress(f"seed {seed}: {verdict['verdict']}, largest |z| {check['statistic']:.3g}"
                     + (f" ({check['worst_figure']})" if verdict["verdict"] == "fail" else ""))
    z = {}
    for figure in TESTED:
        values = np.array([[np.nan if v is None else v for v in run["z"][figure]] for run in runs])
        tested = ~np.isnan(values)
        if tested.any():
            with np.errstate(invalid="ignore", divide="ignore"):
                z[figure] = {"mean": [float(np.nanmean(c)) if t.any() else None for c, t in zip(values.T, tested.T)],
                             "sd": [float(np.nanstd(c, ddof=1)) if t.sum() > 1 else None
                                    for c, t in zip(values.T, tested.T)],
                             "values": tested.sum(axis=0).tolist()}
    return {"machine": machine(), "scene": "ptc", "camera": camera_.name, "imager": im.name,
            "illuminance_lux": float(illuminance_lux), "prevailing_K": float(temperature), "calibration_K": None,
            "spp": used, "points": points, "seeds": seeds, "first_seed": first_seed, "seed_step": 1, "alpha": alpha,
            "checks": false_alarm_rows(runs, alpha), "z": z, "tests": {"fits": test},
            "runs": [{key: run[key] for key in ("seed", "verdict", "statistic", "worst")} for run in runs],
            "elapsed_s": time.perf_counter() - begun}
