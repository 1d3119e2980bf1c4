"""
Tests for :mod:`skinrender.rendering.imaging`: renders recorded through an image sensor are seeded (the same seed,
the same image), and what an ``auto`` exposure capped and the well clipped is reported. Their validation against
the sensor model is tests/rendering/test_sensor_validation.py.
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.model.camera import camera
from skinrender.rendering.imaging import predicted_electrons, predicted_patches, render_imaged
from skinrender.rendering.scene import load_chart_scene
from skinrender.rendering.validation import analytic_reference
from skinrender.spectra import GRID_DEFAULT

pytest.importorskip("mitsuba")

CAM = camera("gbell:9@450,540,610")
CHART = load_chart_scene("macbeth")


@pytest.fixture(scope="module")
def small():
    return render_imaged(CHART, CAM, 2856.0, 2300.0, "sony-imx174", 500.0, spp=16, seed=3)


def test_same_seed_same_image_other_seed_other_image(small):
    again = render_imaged(CHART, CAM, 2856.0, 2300.0, "sony-imx174", 500.0, spp=16, seed=3)
    other = render_imaged(CHART, CAM, 2856.0, 2300.0, "sony-imx174", 500.0, spp=16, seed=5)
    assert np.array_equal(again.dn, small.dn) and not np.array_equal(other.dn, small.dn)


def test_predicted_patches_are_the_model_at_the_predicted_electrons(small):
    from skinrender.model.noise import statistics_dn

    ratio = analytic_reference(CAM, CHART.reflectances(GRID_DEFAULT), 2856.0, 2856.0) / 255.0
    electrons = predicted_electrons(small, ratio)
    mean, variance = predicted_patches(small, ratio)
    np.testing.assert_allclose((mean, variance), statistics_dn(small.imager, electrons))
    white = CHART.white_index
    assert electrons[white].max() < small.imager.full_well_e  # auto exposure: the white below the well


def test_capped_auto_exposure_and_clipping_are_reported():
    cam = camera("gbell:3@450,550,650")
    dim = render_imaged(CHART, cam, 3300.0, 3300.0, "sony-icx418", 500.0, spp=4, seed=0)
    assert dim.exposure_s == pytest.approx(1 / 30) and "capped" in dim.notes[0]
    assert dim.clipping["well_full"] == [0, 0, 0] and dim.rendering.info["notes"] == list(dim.notes)
    long = render_imaged(CHART, CAM, 2856.0, 2856.0, "sony-icx418", 500.0, exposure=1.0, spp=4, seed=1)
    full = np.count_nonzero(long.dn.reshape(-1, 3) >= long.imager.black_level_dn
                            + long.imager.gain_dn_per_e * long.imager.full_well_e - 1, axis=0)
    assert 0 < long.clipping["well_full"][0] <= full[0] and any("full well" in note for note in long.notes)


def test_a_chart_through_an_imager_renders_as_its_reference(render_regression):
    """Regression, on the package's pytest plugin: the face chart recorded by the paper's class of 3-CCD camera
    at 300 lx (Monte Carlo and sensor noise together in each patch's standard error)."""
    render_regression.check("face_chart", camera="Kodak DCS-200", prevailing="A", calibration=5900,
                            imager="sony-icx418", illuminance=300.0, basename="face_chart_icx418")
