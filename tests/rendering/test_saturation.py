"""
Tests for :mod:`skinrender.rendering.saturation`: a patch channel at the sensor's ceiling is left out of the sensor
validation's tests and makes its verdict inconclusive, naming it and an exposure that would not saturate — never a
pass (a chart saturated throughout matched its saturated prediction and passed) and never a fail from the clipped
values alone.

One render of two small grey patches at 4 spp serves every test: the frames are drawn again from its electrons at
longer exposures (the charge scales with the exposure), so no further render is needed.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from skinrender.model.camera import camera
from skinrender.model.imager import imager
from skinrender.model.noise import simulate_dn_clipped
from skinrender.rendering.imaging import render_imaged
from skinrender.rendering.saturation import saturated_values, unsaturated_exposure
from skinrender.rendering.scene import load_chart_scene
from skinrender.rendering.sensor_validation import validate_imaged
from skinrender.rendering.validation import analytic_reference
from skinrender.spectra import GRID_DEFAULT

pytest.importorskip("mitsuba")

CAM = camera("gbell:9@450,540,610")
IMX = imager("sony-imx174")


@pytest.fixture(scope="module")
def chart(tmp_path_factory):
    """A bright (0.8) and a dark (0.05) grey, 16 × 16 pixels each."""
    path = tmp_path_factory.mktemp("scene") / "two.toml"
    path.write_text("columns = 2\npatch_px = 16\nborder_px = 1\n" + "".join(
        f"[[patch]]\nname = 'grey {g}'\nreflectance = 'grey:{g}'\n" for g in (0.8, 0.05)))
    return load_chart_scene(path)


@pytest.fixture(scope="module")
def imaged(chart):
    """1 ms at 500 lx: the bright grey at ~7 % of the full well, nothing saturates."""
    return render_imaged(chart, CAM, 2856.0, 2856.0, IMX, 500.0, exposure=1e-3, spp=4, seed=5)


@pytest.fixture(scope="module")
def ratio(chart):
    return analytic_reference(CAM, chart.reflectances(GRID_DEFAULT), 2856.0, 2856.0) / 255.0


def _exposed(imaged, factor: float):
    """The same render recorded ``factor`` × longer (its charge scaled, the frame drawn again)."""
    electrons = imaged.electrons * factor
    dn = simulate_dn_clipped(imaged.imager, electrons, np.random.default_rng([imaged.seed, 0x5EED]))[0]
    return dataclasses.replace(imaged, electrons=electrons, dn=dn, exposure_s=imaged.exposure_s * factor)


def test_nothing_saturates_at_a_short_exposure(imaged, ratio):
    result = validate_imaged(imaged, ratio)
    assert result.saturation.outcome == "not_applicable"
    assert not result.saturated.any()


def test_a_chart_saturated_throughout_is_inconclusive_not_a_pass(imaged, ratio):
    """At 10 000 × the exposure every channel of both greys (and the white) sits at the full well: before, each matched its saturated
    prediction and the chart passed."""
    result = validate_imaged(_exposed(imaged, 1e4), ratio)
    assert result.saturated.all()
    assert result.verdict.outcome == "inconclusive"
    assert "saturate" in result.verdict.reason and "--exposure" in result.saturation.reason
    assert result.checks["equivalence"].outcome == "not_applicable"
    assert all(row["bound"] == [None] * 3 and row["saturated"] == [True] * 3 for row in result.patches())


def test_a_partly_saturated_chart_tests_the_rest_and_names_a_safe_exposure(imaged, ratio):
    """At 16 × the bright grey and the white fill the well, the dark grey does not: only it is tested; the exposure
    the saturation check names saturates nothing."""
    result = validate_imaged(_exposed(imaged, 16.0), ratio)
    assert result.saturated[0].any() and not result.saturated[1].any()
    assert result.verdict.outcome == "inconclusive"
    assert result.checks["variance"].details["tests"] == int((~result.saturated).sum())
    safe = result.saturation.details["exposure_max_s"]
    again = validate_imaged(_exposed(imaged, safe / imaged.exposure_s), ratio)
    assert again.saturation.outcome == "not_applicable"


def test_a_wrong_model_still_fails_on_the_unsaturated_patches(imaged, ratio):
    """Saturation never hides a difference elsewhere: a gain 20 % off fails on the dark grey alone."""
    wrong = dataclasses.replace(IMX, gain_dn_per_e=IMX.gain_dn_per_e * 1.2)
    result = validate_imaged(_exposed(imaged, 16.0), ratio, model=wrong)
    assert result.saturation.outcome == "inconclusive"
    assert result.verdict.outcome == "fail"


def test_the_safe_exposure_keeps_the_brightest_pixel_five_sigma_below_the_well():
    t = unsaturated_exposure(IMX, 4e4, 0.02)
    charge = 4e4 * t / 0.02
    assert charge + 5 * np.sqrt(charge + IMX.read_noise_e**2) <= IMX.full_well_e
    assert not saturated_values(IMX, [np.array([[charge] * 3])], np.array([[charge] * 3])).any()
    assert saturated_values(IMX, [np.array([[charge * 1.01] * 3])], np.array([[0.0] * 3])).all()


def test_spp_auto_on_a_saturated_chart_is_refused_in_one_line(imaged, ratio):
    """Every patch channel saturated: no bound, no spp to choose; refused naming --tolerance and the reason (its
    message had formatted the missing bound: a TypeError)."""
    from skinrender.errors import SkinrenderError
    from skinrender.rendering.spp_choice import spp_for_tolerance

    with pytest.raises(SkinrenderError, match="--tolerance 0.05: no spp .* saturates.* has no bound"):
        spp_for_tolerance(lambda spp, seed: validate_imaged(_exposed(imaged, 1e4), ratio), 0.05)
