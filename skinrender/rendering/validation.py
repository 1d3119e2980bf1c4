"""
Render validation against the analytic model
============================================

-   :func:`analytic_reference`: Eq. 4 as the renderer integrates it — the spectra linearly interpolated between
    grid samples, Planck evaluated exactly, integrated on a refined grid (the paper's Σ differs from this by a
    quadrature term that :func:`quadrature_difference` reports).
-   :func:`validate`, :class:`Validation`: every patch's rendered mean against the reference
    (:func:`validate_rendering`: the check of a render): shown within a relative tolerance (equivalence, the
    verdict) and no difference detected (a calibrated difference test), both from the measured noise
    (:mod:`skinrender.rendering.agreement`); :meth:`Validation.document`: the JSON ``validate`` prints
    (:mod:`.chart_document`).
-   :func:`validate_gamut`: gamut volumes of a rendered chart against the analytic ones, with the same two verdicts.

The standard error of a patch channel (:func:`~skinrender.rendering.patch_errors.error_law`) is the patch's
standard error together with the white references' errors carried through the white balance and WP (Eq. 8),
linearised with their channel covariances; a value whose error is too skewed for the normal law is held to
distribution-free (Cantelli, Chebyshev) bounds instead. The pixels of a patch are independent (a box filter), so
the standard errors have ``pixels − 1`` degrees of freedom (Student t). The difference test allows a float32 floor
(:func:`float32_floor`) beyond the noise. At p = c the whites are one render and WP is exactly 1. Renders of p
and c use different seeds, so their noise is independent.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..constants import CONSTANT_OUTPUT_SCALE, TEMPERATURES_PAPER
from ..errors import SkinrenderError
from ..evaluation.gamut import gamut
from ..evaluation.verdict import ALPHA_DIFFERENCE, ALPHA_EQUIVALENCE, Verdict
from ..hints import NDArrayFloat
from ..model.camera import Camera, camera
from ..model.response import gain, response
from ..spectra import GRID_DEFAULT, WavelengthGrid, planck
from .agreement import TOLERANCE_DEFAULT, agreement, check_tolerance, tolerance_scale
from .balance import Eq4Options, Rendering, patch_statistics, render_balanced
from .patch_errors import SKEW_MAX, error_law
from .renderer import chart_renderer
from .request import chart_request
from .scene import ChartScene, load_chart_scene
from .settings import RenderSettings, seed_at
from .spp_choice import square_spp

__all__ = ["FLOAT32_FLOOR", "REFINE", "analytic_reference", "quadrature_difference", "Validation", "validate",
           "validate_rendering", "white_level", "validate_gamut"]

FLOAT32_FLOOR = 2e-6
"""Relative floor for float32 accumulation in the renderer (≈ 16 ulp)."""

EPS_FLOAT32 = 2.0**-24
"""float32 unit round-off. Mitsuba evaluates spectra at float32 wavelengths:
a curve of feature width w (nm) at λ (nm) is then known to ~ε λ / w relative,
which for the impulse's 2 nm triangle (w = Δλ) reaches ~4e-5 at 700 nm."""

REFINE = 10
"""The reference integrates on a grid this many times finer than the sensor grid."""


def analytic_reference(
    cam: Camera | str,
    reflectance: NDArrayFloat,
    prevailing: float,
    calibration: float,
    normalization: str = "white",
    knee: bool = False,
    grid: WavelengthGrid = GRID_DEFAULT,
    refine: int = REFINE,
    scale: float = CONSTANT_OUTPUT_SCALE,
    bands: WavelengthGrid | None = None,
) -> NDArrayFloat:
    """
    Eq. 4 of the integral the renderer estimates.

    Sensor curves and reflectances (given on ``grid``) are linearly
    interpolated onto a grid ``refine`` times finer, Planck is evaluated there,
    and the products are integrated with the trapezoid rule. Shape
    ``reflectance.shape[:-1] + (3,)``, output units. ``bands``: the camera as a spectral render of those bands
    sees it (:mod:`~skinrender.rendering.bands`: its curves at the bands, linearly interpolated, 0 beyond them).
    """

    cam = camera(cam)
    fine = WavelengthGrid(grid.start, grid.end, grid.step / refine)
    lam, coarse = fine.wavelengths, grid.wavelengths
    on = grid if bands is None else bands
    x = np.array([np.interp(lam, on.wavelengths, curve, left=None if bands is None else 0.0,
                            right=None if bands is None else 0.0)
                  for curve in cam.sensitivities(on)])
    o = np.asarray(reflectance, dtype=np.float64)
    o_fine = np.apply_along_axis(lambda row: np.interp(lam, coarse, row), -1, o.reshape(-1, coarse.size))
    weights = np.full(lam.size, fine.step)
    weights[[0, -1]] *= 0.5
    spd_p, spd_c = planck(lam, prevailing) * weights, planck(lam, calibration) * weights
    signal = (o_fine * spd_p) @ x.T
    white_p, white_c = spd_p @ x.T, spd_c @ x.T
    out = Eq4Options(normalization, knee, grid, scale).apply(signal, white_p, white_c, prevailing, calibration)
    return out.reshape(*o.shape[:-1], 3)


def quadrature_difference(
    cam: Camera | str, reflectance: NDArrayFloat, prevailing: float, calibration: float,
    normalization: str = "white", grid: WavelengthGrid = GRID_DEFAULT, exact: NDArrayFloat | None = None,
) -> float:
    """
    Largest relative difference between the paper's Σ (Eq. 4 on ``grid``) and
    :func:`analytic_reference` (pass it as ``exact`` when already computed, without the knee).
    """
    paper = response(cam, reflectance, prevailing, calibration, normalization, False, grid)
    if exact is None:
        exact = analytic_reference(cam, reflectance, prevailing, calibration, normalization, False, grid)
    return float(np.max(np.abs(paper - exact) / np.maximum(np.abs(exact), 1e-300)))


@dataclass(frozen=True)
class Validation:
    """
    Rendered patches against the analytic reference, with their verdicts.

    Attributes
    ----------
    rendered, analytic
        Per patch and channel, output units.
    sigma
        Each patch channel's standard error (module docstring), output units.
    floor
        The float32 floor of each patch channel, output units (the difference test's allowance).
    tolerance
        The allowed ``|rendered − analytic|`` per patch and channel, output units: ``tolerance_relative ×
        max(|analytic|, DARK_LEVEL × white_level)`` (:mod:`~skinrender.rendering.agreement`).
    tolerance_relative
        The relative tolerance asked for.
    verdict
        The equivalence verdict: ``pass`` only when every patch channel is shown within its tolerance at
        family-wise 95 % confidence; ``bound`` the smallest relative tolerance that would pass.
    difference
        The difference test (no difference beyond the noise, family-wise α = 0.01): information beside the
        verdict, and the check whose false-alarm rate ``skinrender bench calibration`` measures.
    upper
        The upper confidence bound of each ``|rendered − analytic|``, output units.
    spp_needed
        The samples per pixel at which the verdict is expected to pass (``None`` after a fail).
    skewness
        The skewness of each patch channel's error (:func:`~skinrender.rendering.patch_errors.error_law`): beyond
        :data:`~skinrender.rendering.patch_errors.SKEW_MAX` its normal law is not trusted and the value is held to
        distribution-free bounds (:func:`~skinrender.rendering.agreement.agreement`).
    white_level
        A perfect white's brightest channel in this render's output units (Eq. 4 of a reflectance of 1 under
        the prevailing light, with the render's normalisation and knee): 255 at p = c with ``white``, ~3.5 with
        ``none`` (:func:`white_level`). A channel below ``DARK_LEVEL`` of it is dark.
    spp_auto
        With ``spp="auto"``: how the spp was chosen (:meth:`~skinrender.rendering.kinds.ChartKind.choose_spp`).
    """

    rendering: Rendering
    rendered: NDArrayFloat
    analytic: NDArrayFloat
    sigma: NDArrayFloat
    floor: NDArrayFloat
    quadrature: float
    tolerance: NDArrayFloat
    tolerance_relative: float
    verdict: Verdict
    difference: Verdict
    upper: NDArrayFloat
    spp_needed: int | None
    skewness: NDArrayFloat | None = None
    white_level: float = CONSTANT_OUTPUT_SCALE
    spp_auto: dict | None = None

    @property
    def error(self) -> NDArrayFloat:
        """``rendered − analytic``, output units."""
        return self.rendered - self.analytic

    @property
    def rel_error(self) -> NDArrayFloat:
        """``|rendered − analytic| / analytic`` (absolute difference where analytic is 0)."""
        difference = np.abs(self.rendered - self.analytic)
        return np.where(self.analytic != 0, difference / np.where(self.analytic != 0, np.abs(self.analytic), 1), difference)

    @property
    def z(self) -> NDArrayFloat:
        """Difference in standard errors (0 where the standard error is 0: a black patch renders exactly 0)."""
        difference = self.rendered - self.analytic
        return np.divide(difference, self.sigma, out=np.zeros_like(difference), where=self.sigma > 0)

    @property
    def bound(self) -> float | None:
        """The smallest relative tolerance that would pass (:attr:`verdict`'s bound)."""
        return self.verdict.bound

    def document(self, spp_requested=None) -> dict:
        """The JSON document ``validate CHART --json`` prints (:func:`~.chart_document.chart_document`)."""
        from .chart_document import chart_document
        return chart_document(self, spp_requested)

    @property
    def passed(self) -> bool:
        """The verdict is a pass: every patch channel shown within its tolerance."""
        return self.verdict.outcome == "pass"

    def worst(self) -> list[dict]:
        """The worst patch per channel (largest ``|z|``)."""
        names = self.rendering.camera.channels
        out = []
        for k, channel in enumerate(names):
            i = int(np.argmax(np.abs(self.z[:, k])))
            out.append({"channel": channel, "patch": self.rendering.scene.patches[i].name,
                        "z": float(self.z[i, k]), "rel_error": float(self.rel_error[i, k])})
        return out

    def patches(self) -> list[dict]:
        """
        CONTRACT.md's per-patch rows, extended: per channel the ``error`` (output units), its upper confidence
        bound ``bound`` (output units), ``relative_bound``, ``sigma`` and ``z``; ``tolerance`` is the allowed
        ``|error|``, output units; ``shown`` says per channel ``within``, ``outside`` or ``undecided``.
        """
        rows = []
        scale = tolerance_scale(self.analytic, self.white_level)
        for i, patch in enumerate(self.rendering.scene.patches):
            within = self.upper[i] <= self.tolerance[i]
            lower = np.abs(self.error[i]) - (self.upper[i] - np.abs(self.error[i]))
            outside = lower > self.tolerance[i]
            rows.append({
                "name": patch.name, "rendered": self.rendered[i].tolist(), "analytic": self.analytic[i].tolist(),
                "rel_error": self.rel_error[i].tolist(), "tolerance": self.tolerance[i].tolist(),
                "error": self.error[i].tolist(), "bound": self.upper[i].tolist(),
                "relative_bound": (self.upper[i] / scale[i]).tolist(),
                "sigma": self.sigma[i].tolist(),
                "z": self.z[i].tolist(),
                "skewness": (np.zeros(3) if self.skewness is None else self.skewness[i]).tolist(),
                "shown": ["within" if w else "outside" if o else "undecided" for w, o in zip(within, outside)],
                "passed": bool(np.all(within)),
            })
        return rows


def float32_floor(cam: Camera, grid: WavelengthGrid) -> NDArrayFloat:
    """Relative floor per channel: :data:`FLOAT32_FLOOR`, or ε λ_max / w for narrow curves (w = feature width)."""
    if cam.kind == "impulse":
        width = grid.step
    elif cam.kind == "gbell":
        width = cam.fwhm / 2
    else:
        return np.full(3, FLOAT32_FLOOR)
    return np.full(3, max(FLOAT32_FLOOR, EPS_FLOAT32 * grid.end / width))


def validate(
    scene: ChartScene | str,
    camera_: Camera | str,
    prevailing,
    calibration,
    *,
    grid: WavelengthGrid = GRID_DEFAULT,
    rendering: Rendering | None = None,
    tolerance: float = TOLERANCE_DEFAULT,
    alpha: float = ALPHA_EQUIVALENCE,
    alpha_difference: float = ALPHA_DIFFERENCE,
    allowance: NDArrayFloat | float = 0.0,
    **render_options,
) -> Validation:
    """
    Render a chart (or take ``rendering``) and check every patch against the analytic reference.

    Parameters
    ----------
    scene, camera_, prevailing, calibration, grid
        As :func:`skinrender.rendering.balance.render` (temperatures K, grid nm); the rest by keyword.
    rendering
        A render to check instead (with its own normalisation and knee).
    tolerance
        Relative tolerance in (0, 1) on each lit channel (dark channels: an absolute floor,
        :data:`~skinrender.rendering.agreement.DARK_LEVEL`); default
        :data:`~skinrender.rendering.agreement.TOLERANCE_DEFAULT`.
    alpha, alpha_difference
        Family-wise error rates of the equivalence verdict (its bounds hold together at ``1 − alpha``) and
        of the difference test (its false-alarm rate).
    allowance
        A known systematic ``|rendered − analytic|`` (output units, per patch and channel, or one value) the
        difference test allows beside the float32 floor: a spectral render's basis error
        (:func:`~skinrender.rendering.spectral_validation.validate_spectral`). The equivalence verdict allows
        nothing: the tolerance holds the whole error.
    render_options
        To :func:`skinrender.rendering.balance.render`: ``normalization``, ``knee`` (Eq. 4's), ``settings``
        (a :class:`~skinrender.rendering.settings.RenderSettings`) or its fields ``spp``, ``seed``, ``sampler``,
        ``variant``, ``channels``; ``cache``, ``emitter``.

    Returns
    -------
    :class:`Validation`
        ``.verdict`` (pass / fail / inconclusive), ``.bound``, ``.spp_needed``, ``.difference``.

    Examples
    --------
    >>> v = validate("macbeth", "gbell:9@450,540,610", 2856, 2300, spp=16, seed=1,
    ...              tolerance=0.002)  # doctest: +SKIP
    >>> v.verdict.outcome, v.spp_needed  # doctest: +SKIP
    ('inconclusive', 118)
    """

    tolerance = check_tolerance(tolerance, "tolerance")
    if rendering is not None:
        return validate_rendering(rendering, tolerance, alpha, alpha_difference, grid, allowance)
    cache = render_options.pop("cache", None)
    request = chart_request(scene, camera_, prevailing, calibration, grid=grid, **render_options)
    if request.sensor is not None:
        raise SkinrenderError("imager: this checks the radiance's render; through an image sensor: "
                              "skinrender.validate with imager=", role="imager")
    rendering = render_balanced(request, request.level.chart(request), cache)
    return validate_rendering(rendering, tolerance, alpha, alpha_difference, grid)


def validate_rendering(rendering: Rendering, tolerance: float = TOLERANCE_DEFAULT, alpha: float = ALPHA_EQUIVALENCE,
                       alpha_difference: float = ALPHA_DIFFERENCE, grid: WavelengthGrid = GRID_DEFAULT,
                       allowance: NDArrayFloat | float = 0.0) -> Validation:
    """A chart's render checked patch by patch against the analytic reference (:func:`validate`'s check;
    ``allowance`` as there)."""
    tolerance = check_tolerance(tolerance, "tolerance")
    chart = rendering.scene
    reflectance = rendering.info.get("reflectances")  # subsurface: a skin patch's slab (its adding-doubling R)
    reflectance = chart.reflectances(grid) if reflectance is None else reflectance
    r = rendering
    reference = analytic_reference(r.camera, reflectance, r.prevailing, r.calibration, r.normalization, r.knee, grid)
    quadrature = quadrature_difference(r.camera, reflectance, r.prevailing, r.calibration, r.normalization, grid,
                                       exact=None if r.knee else reference)
    sigma, skewness = error_law(rendering, reference)
    floor = float32_floor(rendering.camera, grid)[None, :] * np.abs(reference) + np.abs(allowance)
    dof = float(np.min(rendering.patches.count) - 1)
    level = white_level(r.camera, r.prevailing, r.calibration, r.normalization, r.knee, grid)
    out = agreement(rendering.patches.mean, reference, sigma, tolerance, r.raw[0].spp, dof, floor, alpha,
                    alpha_difference, skewness=skewness, skew_max=SKEW_MAX, scale=level)
    needed = None if out["spp_needed"] is None else square_spp(out["spp_needed"], r.raw[0].sampler)
    return Validation(rendering, rendering.patches.mean, reference, sigma, floor, quadrature, out["tolerance"],
                      tolerance, out["equivalence"], out["difference"], out["upper"], needed, skewness, level)


def white_level(cam: Camera | str, prevailing: float, calibration: float, normalization: str = "white",
                knee: bool = False, grid: WavelengthGrid = GRID_DEFAULT) -> float:
    """
    A perfect white's brightest channel in Eq. 4's output units under ``prevailing`` (K), balanced to
    ``calibration`` (K) with ``normalization`` (and the knee): what a validation's dark floor is a fraction of
    (:data:`~skinrender.rendering.agreement.DARK_LEVEL`). 255 at p = c with the white normalisation; with
    ``none`` (Eq. 5) the raw response, a few output units: a floor of 1 % of 255 there allowed a dark channel
    an error of several times its value.

    >>> round(white_level("gbell:9@450,540,610", 2856, 2856), 6)
    255.0
    >>> round(white_level("gbell:9@450,540,610", 2856, 5900, "none"), 2)
    3.5
    """
    white = np.ones((1, grid.wavelengths.size))
    return float(np.max(analytic_reference(cam, white, prevailing, calibration, normalization, knee, grid)))


def validate_gamut(
    scene: ChartScene | str,
    camera_: Camera | str,
    illuminants=None,
    settings: RenderSettings | None = None,
    draws: int = 64,
    grid: WavelengthGrid = GRID_DEFAULT,
    tolerance: float = TOLERANCE_DEFAULT,
    alpha: float = ALPHA_EQUIVALENCE,
    alpha_difference: float = ALPHA_DIFFERENCE,
    **options,
) -> dict:
    """
    Gamut volumes of a chart's rendered patches against the analytic ones.

    The chart is rendered once per illuminant of the set (``settings``, a
    :class:`~skinrender.rendering.settings.RenderSettings`, or its fields
    ``spp``, ``seed`` … as ``options``; seed ``seed + i`` mod 2³²);
    Eq. 4 (white normalisation) for every (prevailing, calibration) pair is
    applied to the rendered patch means (white reference left out of the
    cloud), and the one-calibration-case and all-calibration volumes are
    compared with the same volumes of :func:`analytic_reference`. The noise of
    a volume σ_V is estimated by redrawing every patch mean ``draws`` times
    from its measured standard error (Student t with ``draws − 1`` degrees of
    freedom). The verdict is the equivalence of the volumes within the
    relative ``tolerance`` (family-wise ``1 − alpha``); the difference test
    (``|V_render − V_analytic| / σ_V``, Šidák at ``alpha_difference``) is
    reported beside it.

    Returns
    -------
    dict
        ``illuminants_K``, ``rendered``, ``analytic``, ``sigma`` (each: the
        ``Q`` one-calibration volumes then the all-calibration volume,
        output units³), ``rel_difference``, ``bound`` (relative, per volume),
        ``verdict`` and ``difference`` (verdict documents), ``passed`` (the
        verdict is a pass), ``spp_needed``, ``seconds``.
    """

    tolerance = check_tolerance(tolerance, "tolerance")
    if isinstance(draws, bool) or not isinstance(draws, (int, np.integer)) or not 2 <= draws <= 100_000:
        raise SkinrenderError(f"draws must be an integer in [2, 100000] (redraws of the patch means), got {draws!r}",
                              role="draws")
    settings = RenderSettings.of(settings, **options)
    seed = settings.seed
    chart = load_chart_scene(scene)
    cam = camera(camera_)
    temperatures = np.asarray(TEMPERATURES_PAPER if illuminants is None else illuminants, dtype=np.float64)
    renderer = chart_renderer(chart, cam, settings, grid)
    means, errors, seconds = [], [], 0.0
    for i, t in enumerate(temperatures):
        raw = renderer.raw(float(t), seed_at(seed, i))
        stats = patch_statistics(raw.radiance, chart)
        means.append(stats.mean)
        errors.append(stats.standard_error)
        seconds += raw.seconds
    means, errors = np.array(means), np.array(errors)  # (P, patches, 3)

    def volumes(m: NDArrayFloat) -> NDArrayFloat:
        white = m[:, -1, :]
        points = m[:, None, :-1, :] * gain(white[:, None, :], white[None, :, :])[:, :, None, :]
        return np.array([gamut(points[:, q]).volume for q in range(len(temperatures))] + [gamut(points).volume])

    rendered = volumes(means)
    generator = np.random.default_rng(seed)
    sigma = np.std([volumes(means + generator.normal(size=means.shape) * errors) for _ in range(draws)], axis=0, ddof=1)
    reflectance = chart.reflectances(grid)[:-1]
    analytic_points = np.array([[analytic_reference(cam, reflectance, p, q, grid=grid) for q in temperatures]
                                for p in temperatures])
    analytic = np.array([gamut(analytic_points[:, q]).volume for q in range(len(temperatures))]
                        + [gamut(analytic_points).volume])
    # volumes are no output values: their tolerance is relative throughout (scale 0: no dark floor)
    out = agreement(rendered, analytic, sigma, tolerance, renderer.spp, draws - 1, 0.0, alpha, alpha_difference,
                    "gamut volumes", scale=0.0)
    return {
        "scene": chart.name,
        "camera": cam.name,
        "illuminants_K": temperatures.tolist(),
        "rendered": rendered.tolist(),
        "analytic": analytic.tolist(),
        "sigma": sigma.tolist(),
        "rel_difference": (np.abs(rendered - analytic) / analytic).tolist(),
        "bound": out["relative_bound"].tolist(),
        "verdict": out["equivalence"].document(),
        "difference": out["difference"].document(),
        "passed": out["equivalence"].outcome == "pass",
        "spp_needed": out["spp_needed"],
        "spp": renderer.spp,
        "seconds": seconds,
    }
