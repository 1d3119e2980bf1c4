"""
Tests for :mod:`skinrender.rendering.sensor_validation`: renders recorded through an image sensor agree with the
analytic sensor model patch by patch (mean: z-test; variance: scaled χ²; exact on the code lattice where the noise
spans a few codes; Šidák-corrected), the render's own Monte Carlo variance is part of the prediction (simulated and
on real renders: without it most seeds fail at 16 spp), a model whose read noise or gain is off is rejected, and the
means' equivalence gives the three outcomes.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from skinrender.evaluation.verdict import binomial_interval
from skinrender.model.camera import camera
from skinrender.model.imager import imager
from skinrender.model.noise import simulate_dn, statistics_dn
from skinrender.rendering.imaging import render_imaged
from skinrender.rendering.scene import load_chart_scene
from skinrender.rendering.sensor_validation import MC_VARIANCE, _channel_tests, validate_imaged
from skinrender.rendering.validation import analytic_reference
from skinrender.spectra import GRID_DEFAULT

pytest.importorskip("mitsuba")

CAM = camera("gbell:9@450,540,610")
CHART = load_chart_scene("macbeth")
RATIO = analytic_reference(CAM, CHART.reflectances(GRID_DEFAULT), 2856.0, 2856.0) / 255.0
"""Each patch's render value over a perfect white's (Eq. 4 at p = c, over v = 255)."""


@pytest.fixture(scope="module")
def bright():
    """Office light, auto exposure: shot noise dominates."""
    return render_imaged(CHART, CAM, 2856.0, 2300.0, "sony-imx174", 500.0, spp=256, seed=3)


@pytest.fixture(scope="module")
def greys(tmp_path_factory):
    """Three large grey patches (60 × 60 inner pixels each): a variance known to ~2.4 % per patch."""
    path = tmp_path_factory.mktemp("scene") / "greys.toml"
    path.write_text("columns = 2\npatch_px = 64\nborder_px = 2\n" + "".join(
        f"[[patch]]\nname = 'grey {g}'\nreflectance = 'grey:{g}'\n" for g in (0.05, 0.2, 0.8)))
    return load_chart_scene(path)


@pytest.fixture(scope="module")
def dim(greys):
    """A 0.2 ms exposure at 500 lx: a few to a few hundred electrons, where read noise counts."""
    return render_imaged(greys, CAM, 2856.0, 2300.0, "sony-imx174", 500.0, exposure=2e-4, spp=64, seed=4)


@pytest.fixture(scope="module")
def dim_ratio(greys):
    return analytic_reference(CAM, greys.reflectances(GRID_DEFAULT), 2856.0, 2856.0) / 255.0


class TestModelChecks:
    @pytest.mark.parametrize("frame, ratio", [("bright", None), ("dim", "dim_ratio")])
    def test_correct_model_detects_no_difference(self, frame, ratio, request):
        validation = validate_imaged(request.getfixturevalue(frame),
                                     RATIO if ratio is None else request.getfixturevalue(ratio))
        assert validation.difference.outcome == "pass", (np.abs(validation.z).max(), validation.p_variance.min())

    def test_gain_off_by_20_percent_fails(self, bright):
        wrong = dataclasses.replace(imager("sony-imx174"), gain_dn_per_e=imager("sony-imx174").gain_dn_per_e * 1.2)
        validation = validate_imaged(bright, RATIO, model=wrong)
        assert validation.difference.outcome == "fail" and validation.verdict.outcome == "fail"

    @pytest.mark.parametrize("factor", [0.8, 1.2])
    def test_read_noise_off_by_20_percent_fails(self, dim, dim_ratio, factor):
        model = imager("sony-imx174")
        wrong = dataclasses.replace(model, read_noise_e=model.read_noise_e * factor)
        validation = validate_imaged(dim, dim_ratio, model=wrong)
        assert validation.checks["variance"].outcome == "fail" and validation.verdict.outcome == "fail"

    def test_json_rows_carry_the_standard_deviations_and_bounds(self, bright):
        row = validate_imaged(bright, RATIO).patches()[0]
        assert len(row["rendered_std"]) == 3 and all(s > 0 for s in row["predicted_std"])
        assert all(p >= s for p, s in zip(row["predicted_std"], row["sensor_std"]))  # the render's part added
        assert {"error", "bound", "tolerance", "render_std"} <= set(row)


class TestEquivalence:
    def test_three_outcomes(self, bright):
        """Bright light: the means are known to ~0.3 %: a 5 % tolerance passes, 0.1 % cannot be shown (the
        sensor's noise alone keeps the bound above it, so no spp is named), and a 20 % gain error fails."""
        loose = validate_imaged(bright, RATIO, tolerance=0.05)
        assert loose.verdict.outcome == "pass" and loose.bound < 0.05
        tight = validate_imaged(bright, RATIO, tolerance=0.001)
        assert tight.checks["equivalence"].outcome == "inconclusive" and tight.spp_needed is None
        assert "sensor" in tight.spp_reason
        wrong = dataclasses.replace(imager("sony-imx174"), gain_dn_per_e=imager("sony-imx174").gain_dn_per_e * 1.2)
        assert validate_imaged(bright, RATIO, model=wrong, tolerance=0.05).checks["equivalence"].outcome == "fail"

    def test_bad_tolerance_refused(self, bright):
        from skinrender.errors import SkinrenderError

        with pytest.raises(SkinrenderError, match="tolerance"):
            validate_imaged(bright, RATIO, tolerance=1.5)


def _simulated_rates(method: str, trials: int, rng, share: float = 0.3, pixels: int = 144, excess: float = 0.0):
    """Rejections at level 0.05 of one patch channel's mean and variance tests, ``trials`` times: the sensor's
    noise plus a render spread whose variance is ``share`` of it (pixels' electrons vary as a render's would);
    ``excess``: extra sensor variance the model does not know, as a share of its own."""
    model = imager("sony-imx174")
    expected = 4000.0  # e⁻: σ ≈ 7.8 DN, the normal regime
    _, sensor = statistics_dn(model, [expected])
    spread_e = math.sqrt(share * sensor[0]) / model.gain_dn_per_e  # e⁻ whose DN variance is share × the sensor's
    mean, variance = (float(v[0]) for v in statistics_dn(model, [expected]))
    rejected = np.zeros(2)
    for _ in range(trials):
        electrons = expected + rng.normal(0.0, spread_e, pixels)
        extra = np.sqrt(excess * sensor[0])
        codes, other = (simulate_dn(model, electrons, rng) + np.rint(rng.normal(0.0, extra, pixels)) for _ in "ab")
        means, variances = statistics_dn(model, electrons)
        _, p_mean, p_variance, _, _ = _channel_tests(codes, other, electrons, means, variances, mean, variance,
                                                     expected, model, MC_VARIANCE[method])
        rejected += [p_mean < 0.05, p_variance < 0.05]
    return rejected / trials


@pytest.mark.parametrize("method", ["frames", "pixels"])
def test_the_render_variance_correction_is_calibrated_on_simulated_pixels(method, rng):
    """With the render's spread a third of the sensor's variance, the corrected tests reject at their level (5 %,
    inside the binomial 99.9 % interval of 400 trials); left out, the variance test rejects far more often."""
    trials = 400
    for rate in _simulated_rates(method, trials, rng):
        lo, hi = binomial_interval(int(round(rate * trials)), trials, 0.999)
        assert lo <= 0.05 <= hi, rate
    assert _simulated_rates("none", trials, rng)[1] > 0.2


def test_two_frames_see_a_wrong_noise_model_more_often(rng):
    """A sensor 25 % noisier than its model: the second frame's variance test (no render noise in it) rejects more
    often than the one that subtracts the render's pixel variance (whose cross term widens its law)."""
    frames = _simulated_rates("frames", 300, rng, share=0.3, excess=0.25)[1]
    pixels = _simulated_rates("pixels", 300, rng, share=0.3, excess=0.25)[1]
    assert frames > pixels + 0.05, (frames, pixels)


def test_at_16_spp_the_render_variance_decides_the_false_alarms(greys, dim_ratio):
    """Real renders at 16 spp, where the render's variance is several times the sensor's at 500 lx: over 12 seeds
    the corrected tests raise at most 2 false alarms (α = 0.01: expected 0.12), without the correction most fail."""
    ratio = analytic_reference(CAM, greys.reflectances(GRID_DEFAULT), 2856.0, 2856.0) / 255.0
    failures = {"frames": 0, "none": 0}
    for seed in range(12):
        imaged = render_imaged(greys, CAM, 2856.0, 2300.0, "sony-imx174", 500.0, spp=16, seed=100 + seed)
        for method in failures:
            failures[method] += validate_imaged(imaged, ratio, mc_variance=method).difference.outcome == "fail"
    assert failures["frames"] <= 2 and failures["none"] >= 8, failures


# Sub-DN noise: the 8-bit CCD preset (0.006 DN/e⁻) at 500 lx gives σ ≈ 0.1–0.6 DN, one to three codes per patch.

@pytest.fixture(scope="module")
def sub_dn():
    """The 8-bit CCD at 500 lx, auto exposure (capped at 1/30 s): every channel's noise under 1 DN."""
    cam = camera("gbell:3@450,550,650")
    ratio = analytic_reference(cam, CHART.reflectances(GRID_DEFAULT), 3300.0, 3300.0) / 255.0
    return render_imaged(CHART, cam, 3300.0, 3300.0, "sony-icx418", 500.0, spp=256, seed=0), ratio


def test_sub_dn_noise_correct_model_detects_no_difference(sub_dn):
    imaged, ratio = sub_dn
    validation = validate_imaged(imaged, ratio)
    assert validation.predicted_std.max() < 1.0 and validation.exact.mean() > 0.5  # the lattice regime
    assert np.any(validation.rendered_std == 0)  # patches of one code, as the bug report had them
    assert validation.difference.outcome == "pass", (validation.p_mean.min(), validation.p_variance.min())


@pytest.mark.parametrize("field, factor", [("gain_dn_per_e", 1.1), ("read_noise_e", 3.0)])
def test_sub_dn_noise_wrong_model_fails(sub_dn, field, factor):
    imaged, ratio = sub_dn
    model = imager("sony-icx418")
    wrong = dataclasses.replace(model, **{field: getattr(model, field) * factor})
    assert validate_imaged(imaged, ratio, model=wrong).difference.outcome == "fail"
