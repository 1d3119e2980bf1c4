"""
Tests for :mod:`skinrender.rendering.imaging`: renders recorded through an image sensor agree with the
analytic sensor model patch by patch (mean: z-test; variance: χ² test; Šidák-corrected), a model whose read
noise or gain is off by 20 % is rejected, and the same seed gives the same image.
"""

from __future__ import annotations

import dataclasses

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
