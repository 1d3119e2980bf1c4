"""
Validation of renders recorded through an image sensor
======================================================

A noisy render's patches (:func:`~skinrender.rendering.imaging.render_imaged`)
against the analytic sensor model (:mod:`skinrender.model.noise`) and Eq. 4:

-   **mean** (difference test): each patch channel's pixel mean against the
    analytic mean, DN; its standard error from the model's sensor variance
    plus the render's own Monte Carlo variance.
-   **variance** (difference test): the sensor's temporal variance against the
    model's. The render's Monte Carlo variance is removed as
    :data:`MC_VARIANCE` says (by default with a second frame of the same
    render, as EMVA 1288 measures a camera: half the variance of the two
    frames' difference holds the sensor's noise alone).
-   **equivalence**: each patch channel's mean, in output units, shown within
    the relative tolerance (:mod:`skinrender.rendering.agreement`).

Where the noise spans a few codes (σ < 4 DN and a small lattice) the mean and
variance tests are exact on the code lattice (:func:`exact_p_values`), the
pixel's law the mixture of the patch pixels' code laws (the render's spread
included); elsewhere the mean takes a z-test and the variance a scaled χ²
whose degrees of freedom match its law's fourth moment (Satterthwaite). Every
mean and variance test runs at the Šidák level of a family-wise false-alarm
rate :data:`ALPHA_FAMILY`, measured by ``skinrender bench calibration``.

The verdict combines the equivalence of the means (they have a tolerance)
with the variance tests (the noise model has none: a difference test is all
there is); the mean's difference test is reported beside it. A patch channel
that saturates (:mod:`~skinrender.rendering.saturation`) is left out of every
test, and the verdict is then at best inconclusive, naming it.

-   :data:`ALPHA_FAMILY`, :data:`MC_VARIANCE`, :class:`ImagedValidation`,
    :func:`validate_imaged`.

Units: DN and DN² unless said; output units (255 for white at p = c) for
the equivalence.

References
----------
-   :cite:`EMVA1288` : two frames per exposure for the temporal variance (docs/references.md).
-   :cite:`Satterthwaite1946` : F. E. Satterthwaite (1946). An approximate distribution of estimates of
    variance components. Biometrics Bulletin 2(6), 110–114.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ..evaluation.verdict import ALPHA_EQUIVALENCE, Verdict, combine
from ..hints import NDArrayFloat
from ..methods import method_of, takes
from ..model.imager import Imager, imager
from ..model.noise import code_probabilities, simulate_dn_clipped, statistics_dn
from ..spectra import GRID_DEFAULT, WavelengthGrid
from .agreement import TOLERANCE_DEFAULT, agreement, check_tolerance
from .code_laws import difference_law, exact_p_values, mixture, normal_sf, p_variance, spread_of_variance
from .imaging import ImagedRendering, electrons_per_radiance, predicted_electrons, predicted_patches
from .renderer import channel_names
from .saturation import saturated_values, saturation_verdict

__all__ = ["ALPHA_FAMILY", "MC_VARIANCE", "PatchChannel", "mc_frames", "mc_pixels", "mc_none", "ImagedValidation", "validate_imaged"]

ALPHA_FAMILY = 0.01
"""Family-wise false-alarm rate of the mean and variance tests: each of the m tests (patch × channel × mean and
variance) runs at the Šidák level ``1 − (1 − α)^(1/m)``, as Mitsuba's render tests do."""

@dataclass(frozen=True)
class ImagedValidation:
    """
    A noisy render's patches against the analytic sensor model, per patch and channel.

    ``rendered_mean``/``predicted_mean`` (DN), ``rendered_std``/``predicted_std`` (DN; predicted: the sensor's and
    the render's variances together), ``sensor_std`` (the model's, DN) and ``render_std`` (the render's Monte
    Carlo spread as the sensor sees it, DN), the z statistic of the mean, the p-values of the mean and variance
    tests, the Šidák ``level``, which tests were ``exact``; ``difference`` (every mean and variance test),
    ``checks`` (``mean``, ``variance``, ``equivalence``), ``verdict`` (equivalence and variance combined),
    the equivalence's ``upper`` bounds and ``tolerance`` (output units), ``spp_needed``; ``spp_auto``: with
    ``spp="auto"``, how the spp was chosen (:meth:`~skinrender.rendering.kinds.ChartKind.choose_spp`).
    """

    imaged: ImagedRendering
    rendered_mean: NDArrayFloat
    predicted_mean: NDArrayFloat
    rendered_std: NDArrayFloat
    predicted_std: NDArrayFloat
    z: NDArrayFloat
    p_mean: NDArrayFloat
    p_variance: NDArrayFloat
    level: float
    exact: NDArrayFloat | None = None
    sensor_std: NDArrayFloat | None = None
    render_std: NDArrayFloat | None = None
    difference: Verdict | None = None
    checks: dict = field(default_factory=dict)
    verdict: Verdict | None = None
    upper: NDArrayFloat | None = None
    tolerance: NDArrayFloat | None = None
    spp_needed: int | None = None
    mc_variance: str = "frames"
    spp_reason: str = ""
    saturated: NDArrayFloat | None = None
    saturation: Verdict | None = None
    spp_auto: dict | None = None

    @property
    def rendering(self):
        """The render the sensor recorded (its Eq. 4 image, raw passes and seconds), as a chart validation has it."""
        return self.imaged.rendering

    @property
    def passed(self) -> bool:
        """The verdict is a pass (means shown within the tolerance, no variance test rejects)."""
        return self.verdict is not None and self.verdict.outcome == "pass"

    @property
    def bound(self) -> float | None:
        """The smallest relative tolerance the means would pass at."""
        return self.checks["equivalence"].bound if "equivalence" in self.checks else None

    def patches(self) -> list[dict]:
        """Per patch, in output units (DN above black × the Eq. 4 gain): CONTRACT.md's rows, and the verdicts'."""
        gains, names = self.imaged.gains, [p.name for p in self.imaged.rendering.scene.patches]
        black = self.imaged.imager.black_level_dn
        rows = []
        for i, name in enumerate(names):
            error = (self.rendered_mean[i] - self.predicted_mean[i]) * gains
            rows.append({
                "name": name,
                "rendered": ((self.rendered_mean[i] - black) * gains).tolist(),
                "analytic": ((self.predicted_mean[i] - black) * gains).tolist(),
                "rendered_std": (self.rendered_std[i] * gains).tolist(),
                "predicted_std": (self.predicted_std[i] * gains).tolist(),
                "sensor_std": (self.sensor_std[i] * gains).tolist(),
                "render_std": (self.render_std[i] * gains).tolist(),
                "error": error.tolist(), "bound": _or_none(self.upper[i]), "tolerance": _or_none(self.tolerance[i]),
                "z_mean": self.z[i].tolist(), "p_mean": self.p_mean[i].tolist(),
                "p_variance": self.p_variance[i].tolist(),
                "test": ["exact" if self.exact is not None and self.exact[i, k] else "normal" for k in range(3)],
                "saturated": [bool(self.saturated is not None and self.saturated[i, k]) for k in range(3)],
                "passed": bool(np.all(self.upper[i] <= self.tolerance[i]) and np.all(self.p_variance[i] >= self.level)),
            })
        return rows


def _or_none(values: NDArrayFloat) -> list:
    """JSON values: ``None`` where not tested (a saturated patch channel: NaN)."""
    return [None if np.isnan(v) else float(v) for v in values]


def _model_electrons(imaged: ImagedRendering, model: Imager, grid: WavelengthGrid) -> NDArrayFloat:
    """Each pixel's expected electrons, e⁻, under ``model`` (its quantum efficiency and dark current) from the
    render's radiance, as :func:`~skinrender.rendering.imaging.render_imaged` computes them for its own imager."""
    if model == imaged.imager:
        return imaged.electrons
    r = imaged.rendering
    rate = electrons_per_radiance(model, r.camera, r.prevailing, imaged.illuminance_lux, grid)
    return (r.raw[0].radiance * rate + model.dark_current_e_per_s) * imaged.exposure_s


def _verdict(name: str, p_values: NDArrayFloat, level: float, alpha: float, tests: int, what: str) -> Verdict:
    """A difference verdict of p-values at the Šidák ``level`` (statistic: the smallest p-value)."""
    if p_values.size == 0:
        return Verdict(name, "not_applicable", alpha, what, reason="every patch channel saturates: nothing to test")
    smallest = float(np.min(p_values))
    rejected = int(np.sum(p_values < level))
    test = (f"{what}: every p-value ≥ {level:.3g}, the Šidák level of {tests} tests at family-wise α = {alpha:g} "
            "(exact on the code lattice where the noise spans a few codes, else z-test and scaled chi-square)")
    if rejected:
        return Verdict(name, "fail", alpha, test, smallest, level,
                       reason=f"{rejected} test{'s' * (rejected > 1)} reject (smallest p {smallest:.2g})",
                       details={"rejected": rejected, "tests": int(p_values.size)})
    return Verdict(name, "pass", alpha, test, smallest, level, reason="no difference detected",
                   details={"rejected": 0, "tests": int(p_values.size)})


@dataclass(frozen=True)
class PatchChannel:
    """One patch channel as a variance method (:data:`MC_VARIANCE`) sees it: its frame's ``codes`` (DN), each
    pixel's expected ``electrons`` and code ``means`` (DN); the analytic patch's ``mean`` and ``variance`` (DN,
    DN²) at ``expected`` electrons; the codes' ``sample_var`` and the ``sensor``'s own variance (DN²); ``own``,
    the sensor's law at the analytic electrons (``(first code, probabilities or None)``)."""

    codes: NDArrayFloat
    electrons: NDArrayFloat
    means: NDArrayFloat
    model: Imager
    mean: float
    variance: float
    expected: float
    sample_var: float
    sensor: float
    own: tuple

    @property
    def n(self) -> int:
        """The pixels."""
        return int(self.codes.size)

    def mixed(self) -> tuple:
        """The pixels' law: the sensor's mixed over the render's spread, centred on the analytic electrons."""
        return mixture(*code_probabilities(self.model, self.electrons - self.electrons.mean() + self.expected))


def mc_frames(channel: PatchChannel, other: NDArrayFloat):
    """a second sensor frame of the same render: the variance test on half the variance of the frames'
    difference (the render's noise cancels); the mean's standard error adds the render's pixel variance (default)

    ``(mc, test)``: the render's variance (DN²) and the variance test, ``test() → (law, p_variance, replaced)``
    (``replaced``: an exact law's p-value replaces it); ``other``: the second frame's codes."""
    def test() -> tuple:
        difference = channel.codes - other
        laws = code_probabilities(channel.model, channel.electrons)[1]
        found = None
        if not np.any(np.isnan(laws)):
            first_d, law_d = difference_law(laws)
            found = exact_p_values(law_d, first_d, difference)
        else:
            first_d, law_d = 0.0, None
        if found is not None:
            return channel.mixed(), found[1], False
        var_d = 2 * channel.sensor
        dof = 2 * var_d**2 / spread_of_variance(law_d, first_d, 0.0, var_d, channel.n)
        return channel.mixed(), p_variance(dof * np.var(difference, ddof=1) / var_d, dof), False

    return float(np.var(channel.means, ddof=1)), test


def mc_pixels(channel: PatchChannel):
    """the render's own pixel variance subtracted from the frame's, the test's degrees of freedom reduced
    for the cross term the two share

    ``(mc, test)`` as :func:`mc_frames`: S² − mc estimates the sensor's variance; the cross term widens its law."""
    mc = float(np.var(channel.means, ddof=1))

    def test() -> tuple:
        own, sensor, n = channel.own, channel.sensor, channel.n
        spread = spread_of_variance(own[1], own[0], channel.mean, sensor, n) + 4 * mc * sensor / (n - 1)
        dof = 2 * sensor**2 / spread
        return channel.mixed(), p_variance(dof * (channel.sample_var - mc) / sensor, dof), True

    return mc, test


def mc_none(channel: PatchChannel):
    """left out (the model's sensor variance alone; too many false alarms at a few tens of spp)

    ``(mc, test)`` as :func:`mc_frames`, the render's variance 0."""
    def test() -> tuple:
        own, variance = channel.own, channel.variance
        dof = 2 * variance**2 / spread_of_variance(own[1], own[0], channel.mean, variance, channel.n)
        return (own if own[1] is not None else None), p_variance(dof * channel.sample_var / variance, dof), True

    return 0.0, test


MC_VARIANCE = {"frames": mc_frames, "pixels": mc_pixels, "none": mc_none}
"""How the render's own Monte Carlo variance enters the noisy predictions, name → the function ``(channel[,
other]) → (mc, test)`` (:func:`mc_frames`: one that takes ``other`` is given a second frame of the same render);
:func:`validate_imaged` dispatches."""


def _channel_tests(codes: NDArrayFloat, other: NDArrayFloat | None, electrons: NDArrayFloat, means: NDArrayFloat,
                   variances: NDArrayFloat, mean: float, variance: float, expected: float, model: Imager,
                   method) -> tuple[float, float, float, bool, float]:
    """
    One patch channel's tests: ``(z, p_mean, p_variance, exact, mc)``.

    ``codes``: the frame's n codes, DN; ``other``: the second frame's (a method that takes it); ``electrons``,
    ``means``, ``variances``: each pixel's expected electrons (e⁻) and its code mean and variance under the model
    (DN, DN²); ``mean``, ``variance``: the analytic patch's (DN, DN²) at ``expected`` electrons; ``method``: one of
    :data:`MC_VARIANCE`' functions; ``mc``: the render's Monte Carlo variance as the sensor sees it, DN² (the
    variance of the pixels' code means).
    """
    n = codes.size
    sample_var = float(np.var(codes, ddof=1))
    first, own = code_probabilities(model, np.full(1, expected))  # the sensor's own law at the analytic electrons
    own = (float(first[0]), own[0]) if np.all(np.isfinite(own)) else (0.0, None)
    channel = PatchChannel(codes, electrons, means, model, mean, variance, expected, sample_var,
                           float(np.mean(variances)), own)
    mc, test = method(channel, **({"other": other} if takes(method, "other") else {}))
    total = variance + mc
    if total <= 0:  # a clipped, noiseless patch: it must equal its prediction exactly
        return 0.0, float(abs(codes.mean() - mean) < 1e-9), float(sample_var < 1e-9), False, mc
    z = (codes.mean() - mean) / np.sqrt(total / n)
    p_mean = float(2 * normal_sf(abs(z)))
    law, p_var, replaced = test()
    exact = False
    if law is not None:
        found = exact_p_values(law[1], law[0], codes)
        if found is not None:
            exact, p_mean = True, found[0]
            if replaced:
                p_var = found[1]
    return float(z), p_mean, p_var, exact, mc


def validate_imaged(imaged: ImagedRendering, reference_ratio: NDArrayFloat, model: Imager | str | None = None,
                    alpha: float = ALPHA_FAMILY, grid: WavelengthGrid = GRID_DEFAULT,
                    tolerance: float = TOLERANCE_DEFAULT, alpha_equivalence: float = ALPHA_EQUIVALENCE,
                    mc_variance: str = "frames") -> ImagedValidation:
    """
    Check every patch's pixel mean and variance against the analytic model of ``model`` (default: the imager
    that recorded it), and the means within ``tolerance`` of Eq. 4 (module docstring).

    Parameters
    ----------
    imaged
        The render through the sensor.
    reference_ratio
        Each patch's render value over a perfect white's, ``(patches, 3)`` (the Eq. 4 reference at p = c over 255).
    model
        The imager whose model is tested (an imager, preset name or TOML path).
    alpha
        Family-wise false-alarm rate of the mean and variance tests together.
    tolerance, alpha_equivalence
        Relative tolerance in (0, 1) of the means and the family-wise error rate of their equivalence.
    mc_variance
        How the render's Monte Carlo variance enters (:data:`MC_VARIANCE`).
    """

    method = method_of(mc_variance, MC_VARIANCE, "mc_variance")
    tolerance = check_tolerance(tolerance)
    recording = imaged.imager
    model_im = recording if model is None else imager(model)
    second = None
    if takes(method, "other"):  # the same render, the sensor's noise drawn again (another stream of the seed)
        second = simulate_dn_clipped(recording, imaged.electrons, np.random.default_rng([imaged.seed, 0x5EED, 1]))[0]
    imaged = replace(imaged, imager=model_im)
    mean, variance = predicted_patches(imaged, reference_ratio, grid)
    expected = predicted_electrons(imaged, reference_ratio, grid)
    electrons = _model_electrons(imaged, model_im, grid)
    pixel_mean, pixel_variance = statistics_dn(model_im, electrons)
    scene = imaged.rendering.scene
    rendered_mean, rendered_var, mc, count = (np.zeros(mean.shape) for _ in range(4))
    z, p_mean, p_var = (np.zeros(mean.shape) for _ in range(3))
    exact = np.zeros(mean.shape, dtype=bool)
    for i in range(mean.shape[0]):
        rows, columns = scene.patch_pixels(i)
        codes = imaged.dn[rows, columns].reshape(-1, 3)
        count[i] = len(codes)
        rendered_mean[i], rendered_var[i] = codes.mean(axis=0), codes.var(axis=0, ddof=1)
        for k in range(3):
            z[i, k], p_mean[i, k], p_var[i, k], exact[i, k], mc[i, k] = _channel_tests(
                codes[:, k], None if second is None else second[rows, columns, k].ravel(),
                electrons[rows, columns, k].ravel(), pixel_mean[rows, columns, k].ravel(),
                pixel_variance[rows, columns, k].ravel(), mean[i, k], variance[i, k], expected[i, k], model_im,
                method)
    # a patch channel at the sensor's ceiling is no evidence about Eq. 4: left out of every test (saturation.py)
    pixels = [electrons[scene.patch_pixels(i)].reshape(-1, 3) for i in range(mean.shape[0])]
    saturated = saturated_values(model_im, pixels, expected)
    tested = ~saturated
    tests = 2 * int(tested.sum())
    level = 1.0 - (1.0 - alpha) ** (1.0 / max(tests, 1))
    checks = {"mean": _verdict("mean", p_mean[tested], level, alpha, tests, "each patch channel's pixel mean, DN"),
              "variance": _verdict("variance", p_var[tested], level, alpha, tests,
                                   "each patch channel's temporal pixel variance, DN²")}
    difference_all = _verdict("difference", np.concatenate([p_mean[tested], p_var[tested]]), level, alpha, tests,
                              "every patch channel's pixel mean and variance")
    gains, black = imaged.gains, model_im.black_level_dn
    # the dark floor is a fraction of the white this render shows (a perfect white's brightest channel, output units)
    white_dn = (predicted_electrons(imaged, np.ones((1, 3)), grid)[0]
                - model_im.dark_current_e_per_s * imaged.exposure_s) * model_im.gain_dn_per_e
    spp = imaged.rendering.raw[0].spp
    upper, allowed = np.full(mean.shape, np.nan), np.full(mean.shape, np.nan)
    if tested.any():
        out = agreement(((rendered_mean - black) * gains)[tested], ((mean - black) * gains)[tested],
                        (np.sqrt((variance + mc) / count) * gains)[tested], tolerance, spp, None, 0.0,
                        alpha_equivalence, alpha, "patch channel means through the sensor",
                        scale=float(np.max(white_dn * gains)))
        upper[tested], allowed[tested] = out["upper"], out["tolerance"]
        needed, reason = _spp_needed(out, spp, variance[tested], mc[tested])
        checks["equivalence"] = replace(out["equivalence"],
                                        details={**out["equivalence"].details, "spp_needed": needed})
    else:
        needed, reason = None, "every patch channel saturates: nothing to test"
        checks["equivalence"] = Verdict("equivalence", "not_applicable", alpha_equivalence,
                                        "patch channel means through the sensor", tolerance=tolerance, reason=reason)
    r = imaged.rendering
    brightest = float(max(np.max(p) for p in pixels + [expected]))
    saturation = saturation_verdict(saturated, [p.name for p in scene.patches], channel_names(r.camera), model_im,
                                    brightest, imaged.exposure_s, imaged.illuminance_lux, imaged.exposure_auto)
    verdict = combine([checks["equivalence"], checks["variance"], saturation], "validation")
    return ImagedValidation(imaged, rendered_mean, mean, np.sqrt(rendered_var), np.sqrt(variance + mc), z, p_mean,
                            p_var, level, exact, np.sqrt(variance), np.sqrt(mc), difference_all, checks, verdict,
                            upper, allowed, needed, mc_variance, reason, saturated, saturation)


def _spp_needed(out: dict, spp: int, sensor: NDArrayFloat, mc: NDArrayFloat) -> tuple[int | None, str]:
    """
    The spp at which the means' equivalence is expected to pass, and why none where there is none.

    Each bound ``|error| + c·SE`` is taken to scale with its standard error, whose square is the sensor's
    variance (which more spp leaves as it is) plus the render's (falling as 1/spp), over the pixels: at N spp
    ``(s + m · spp / N) ≤ (s + m) (tolerance / bound)²`` for every value. None after a fail, or where the
    sensor's variance alone keeps some bound above its tolerance.
    """
    verdict = out["equivalence"]
    if verdict.outcome not in ("pass", "inconclusive"):
        return None, f"the equivalence is {verdict.outcome.replace('_', ' ')}: more samples do not change it"
    room = (sensor + mc) * (out["tolerance"] / np.maximum(out["upper"], 1e-300)) ** 2 - sensor
    if np.any(room <= 0):
        return None, ("the sensor's noise alone keeps a bound above its tolerance: more spp cannot pass; more light "
                      "(--illuminance), a longer exposure or larger patches can")
    return max(1, int(np.ceil(np.max(mc * spp / room)))), ""
