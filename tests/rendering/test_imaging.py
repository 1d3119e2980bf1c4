"""
Tests for :mod:`skinrender.rendering.imaging`: renders recorded through an image sensor agree with the
analytic sensor model patch by patch (mean: z-test; variance: χ² test; Šidák-corrected), a model whose read
noise or gain is off by 20 % is rejected, and the same seed gives the same image.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from skinrender.model.camera import camera
from skinrender.model.imager import imager
from skinrender.rendering.imaging import render_imaged, validate_imaged
from skinrender.rendering.scene import load_scene
from skinrender.rendering.validation import analytic_reference
from skinrender.spectra import GRID_DEFAULT

pytest.importorskip("mitsuba")

CAM = camera("gbell:9@450,540,610")
CHART = load_scene("macbeth")
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
    return load_scene(path)


@pytest.fixture(scope="module")
def dim(greys):
    """A 0.2 ms exposure at 500 lx: a few to a few hundred electrons, where read noise counts."""
    return render_imaged(greys, CAM, 2856.0, 2300.0, "sony-imx174", 500.0, exposure=2e-4, spp=64, seed=4)


@pytest.fixture(scope="module")
def dim_ratio(greys):
    return analytic_reference(CAM, greys.reflectances(GRID_DEFAULT), 2856.0, 2856.0) / 255.0


@pytest.mark.parametrize("frame, ratio", [("bright", None), ("dim", "dim_ratio")])
def test_correct_model_passes(frame, ratio, request):
    validation = validate_imaged(request.getfixturevalue(frame), RATIO if ratio is None else request.getfixturevalue(ratio))
    assert validation.passed, (np.abs(validation.z).max(), validation.p_variance.min(), validation.level)


def test_gain_off_by_20_percent_fails(bright):
    wrong = dataclasses.replace(imager("sony-imx174"), gain_dn_per_e=imager("sony-imx174").gain_dn_per_e * 1.2)
    assert not validate_imaged(bright, RATIO, model=wrong).passed


@pytest.mark.parametrize("factor", [0.8, 1.2])
def test_read_noise_off_by_20_percent_fails(dim, dim_ratio, factor):
    model = imager("sony-imx174")
    wrong = dataclasses.replace(model, read_noise_e=model.read_noise_e * factor)
    assert not validate_imaged(dim, dim_ratio, model=wrong).passed


def test_same_seed_same_image_other_seed_other_image(bright):
    again = render_imaged(CHART, CAM, 2856.0, 2300.0, "sony-imx174", 500.0, spp=256, seed=3)
    other = render_imaged(CHART, CAM, 2856.0, 2300.0, "sony-imx174", 500.0, spp=256, seed=5)
    assert np.array_equal(again.dn, bright.dn) and not np.array_equal(other.dn, bright.dn)


def test_json_rows_carry_the_standard_deviations(bright):
    row = validate_imaged(bright, RATIO).patches()[0]
    assert len(row["rendered_std"]) == 3 and all(s > 0 for s in row["predicted_std"])


# Sub-DN noise: the 8-bit CCD preset (0.006 DN/e⁻) at 500 lx gives σ ≈ 0.1–0.6 DN, one to three codes per patch.

def _brute_force_p_values(pmf, codes):
    """Every outcome of n pixels enumerated: the two-sided p-values of Σ d and of the sample variance."""
    import itertools

    n, support = len(codes), np.arange(len(pmf))
    sums, variances, weights = [], [], []
    for outcome in itertools.product(support, repeat=n):
        draws = np.array(outcome, dtype=float)
        sums.append(draws.sum())
        variances.append(draws.var(ddof=1))
        weights.append(np.prod(pmf[list(outcome)]))
    sums, variances, weights = map(np.array, (sums, variances, weights))
    seen_sum, seen_var = codes.sum(), codes.var(ddof=1)
    tails = lambda value, seen: min(1.0, 2 * min(weights[value <= seen + 1e-12].sum(),  # noqa: E731
                                                 weights[value >= seen - 1e-12].sum()))
    return tails(sums, seen_sum), tails(variances, seen_var)


@pytest.mark.parametrize("codes", [[1, 1, 1, 1], [0, 1, 1, 2], [2, 2, 2, 1], [0, 0, 0, 0], [0, 2, 2, 0]])
def test_exact_p_values_match_enumeration(codes):
    from skinrender.rendering.imaging import _exact_p_values

    pmf = np.array([0.05, 0.8, 0.15])
    exact = _exact_p_values(pmf, 0.0, np.array(codes, dtype=float))
    np.testing.assert_allclose(exact, _brute_force_p_values(pmf, np.array(codes)), rtol=1e-9, atol=1e-12)


def test_a_patch_of_one_likely_code_is_consistent_and_of_an_unlikely_code_is_not():
    """σ = 0.12 DN about 9.0 DN: P(9) = 0.9999; 144 pixels all reading 9 happen with probability 0.98."""
    from skinrender.rendering.imaging import _exact_p_values

    pmf = np.array([3e-5, 1 - 6e-5, 3e-5])  # codes 8, 9, 10
    p_mean, p_variance = _exact_p_values(pmf, 8.0, np.full(144, 9.0))
    assert p_mean == 1.0 and p_variance == 1.0
    p_mean, p_variance = _exact_p_values(pmf, 8.0, np.full(144, 10.0))  # every pixel on a 3e-5 code: (3e-5)^144
    assert p_mean < 1e-12 and p_variance == 1.0  # the mean rejects (FFT round-off ~1e-14); one code has no spread


def test_exact_p_values_are_calibrated_under_the_model():
    """Patches drawn from the law itself: rejections at level 0.05 happen at most 5 % of the time (+3 σ)."""
    from skinrender.rendering.imaging import _exact_p_values

    pmf, rng = np.array([0.02, 0.9, 0.08]), np.random.default_rng(11)
    draws = rng.choice(3, size=(1000, 60), p=pmf).astype(float)
    p_values = np.array([_exact_p_values(pmf, 0.0, codes) for codes in draws])
    bound = 0.05 + 3 * math.sqrt(0.05 * 0.95 / 1000)
    assert np.all(np.mean(p_values < 0.05, axis=0) <= bound), np.mean(p_values < 0.05, axis=0)


@pytest.fixture(scope="module")
def sub_dn():
    """The 8-bit CCD at 500 lx, auto exposure (capped at 1/30 s): every channel's noise under 1 DN."""
    cam = camera("gbell:3@450,550,650")
    ratio = analytic_reference(cam, CHART.reflectances(GRID_DEFAULT), 3300.0, 3300.0) / 255.0
    return render_imaged(CHART, cam, 3300.0, 3300.0, "sony-icx418", 500.0, spp=256, seed=0), ratio


def test_sub_dn_noise_correct_model_passes(sub_dn):
    imaged, ratio = sub_dn
    validation = validate_imaged(imaged, ratio)
    assert validation.predicted_std.max() < 1.0 and validation.exact.mean() > 0.5  # the lattice regime
    assert np.any(validation.rendered_std == 0)  # patches of one code, as the bug report had them
    assert validation.passed, (validation.p_mean.min(), validation.p_variance.min(), validation.level)


@pytest.mark.parametrize("field, factor", [("gain_dn_per_e", 1.1), ("read_noise_e", 3.0)])
def test_sub_dn_noise_wrong_model_fails(sub_dn, field, factor):
    imaged, ratio = sub_dn
    model = imager("sony-icx418")
    assert not validate_imaged(imaged, ratio, model=dataclasses.replace(model, **{field: getattr(model, field) * factor})).passed


def test_capped_auto_exposure_and_clipping_are_reported(sub_dn):
    imaged, _ = sub_dn
    assert imaged.exposure_s == pytest.approx(1 / 30) and "capped" in imaged.notes[0]
    assert imaged.clipping["well_full"] == [0, 0, 0] and imaged.rendering.info["notes"] == list(imaged.notes)
    long = render_imaged(CHART, CAM, 2856.0, 2856.0, "sony-icx418", 500.0, exposure=1.0, spp=4, seed=1)
    full = np.count_nonzero(long.dn.reshape(-1, 3) >= long.imager.black_level_dn
                            + long.imager.gain_dn_per_e * long.imager.full_well_e - 1, axis=0)
    assert 0 < long.clipping["well_full"][0] <= full[0] and any("full well" in note for note in long.notes)


def test_a_chart_through_an_imager_renders_as_its_reference(render_regression):
    """Regression, on the package's pytest plugin: the face chart recorded by the paper's class of 3-CCD camera
    at 300 lx (Monte Carlo and sensor noise together in each patch's standard error)."""
    render_regression.check("face_chart", camera="Kodak DCS-200", prevailing="A", calibration=5900,
                            imager="sony-icx418", illuminance=300.0, basename="face_chart_icx418")
