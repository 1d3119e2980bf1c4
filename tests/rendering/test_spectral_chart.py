"""
Tests for :mod:`skinrender.rendering.spectral_chart`: a chart rendered once with the bands, seen through a
camera, is the result a render of that camera returns (Eq. 4-balanced, its white's noise carried), its
calibration white computed exactly where p ≠ c; bad requests are refused before anything renders.
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.model.camera import camera
from skinrender.rendering.balance import Rendering
from skinrender.rendering.bands import BANDS_DEFAULT, projection
from skinrender.rendering.scene import load_chart_scene
from skinrender.rendering.spectral_chart import calibration_white, chart_through, render_chart_spectral
from skinrender.rendering.validation import analytic_reference
from skinrender.spectra import GRID_DEFAULT, planck

pytest.importorskip("mitsuba")

CAM = "gbell:9@450,540,610"


@pytest.fixture(scope="module")
def image():
    """The Macbeth chart at 2856 K, 16 spp: enough for a patch mean within ~1 % of Eq. 4 (its bound ~0.5 %)."""
    return render_chart_spectral("macbeth", 2856, spp=16, seed=3)


def test_the_render_holds_a_channel_per_band(image):
    assert image.kind == "chart" and image.image.shape == (82, 98, BANDS_DEFAULT.size)
    assert image.image.dtype == np.float32 and image.spp == 16 and image.seed == 3
    assert image.channels[0] == "400nm" and image.channels[-1] == "700nm"
    assert np.all(np.isfinite(image.radiance)) and image.radiance.min() >= 0


def test_seen_through_a_camera_it_is_a_balanced_rendering(image):
    """White reads 255 at p = c (WP = 1, one render), and every patch is near Eq. 4 (2 %: 16 spp's noise)."""
    result = image.through(CAM)
    assert isinstance(result, Rendering) and result.calibration == 2856.0
    assert result.info["white_calibration"] == "rendered"
    assert np.allclose(result.patches.mean[-1], 255.0, rtol=1e-6)
    chart = load_chart_scene("macbeth")
    reference = analytic_reference(camera(CAM), chart.reflectances(GRID_DEFAULT), 2856, 2856)
    lit = reference > 0.05 * 255
    assert np.max(np.abs(result.patches.mean - reference)[lit] / reference[lit]) < 0.02


def test_the_calibration_white_is_computed_where_p_differs_from_c(image):
    """At p ≠ c the white under the calibration light is exact: its relative error is 0, and it equals the white
    of the bands' integral of Planck (the Eq. 4 white of the camera as the bands see it)."""
    result = chart_through(image, CAM, 5900)
    assert result.info["white_calibration"] == "analytic" and np.all(result.white_relative_error[1] == 0)
    matrix = projection(camera(CAM), BANDS_DEFAULT, GRID_DEFAULT)
    white = calibration_white(image.scene, matrix, BANDS_DEFAULT, GRID_DEFAULT, 5900)
    fine = np.arange(4000, 7001) / 10.0
    curves = np.array([np.interp(fine, BANDS_DEFAULT.wavelengths, row) for row in matrix])
    weights = np.full(fine.size, 0.1)
    weights[[0, -1]] = 0.05
    expected = (planck(fine, 5900) * weights) @ curves.T  # the perfect white's ∫ E s_k as the bands see s_k
    assert np.allclose(white / white[0], expected / expected[0], rtol=1e-9)  # up to its (cancelling) scale


def test_two_cameras_share_the_render(image):
    a, b = image.through(CAM, 5900), image.through("Nikon 5100 (NPL)", 5900)
    assert a.raw[0].seed == b.raw[0].seed == 3 and a.camera.name != b.camera.name
    assert not np.allclose(a.image, b.image)


def test_requests_a_spectral_chart_cannot_take_are_refused():
    with pytest.raises(SkinrenderError, match="physics"):
        render_chart_spectral("macbeth", 2856, physics="subsurface", spp=4)
    with pytest.raises(SkinrenderError, match="channels"):
        render_chart_spectral("macbeth", 2856, channels="separate", spp=4)
    with pytest.raises(SkinrenderError, match="reach beyond"):
        render_chart_spectral("macbeth", 2856, bands="380:700:5", spp=4)


def test_a_camera_the_bands_do_not_cover_is_refused_at_through(image):
    narrow = render_chart_spectral("macbeth", 2856, bands="450:650:5", spp=4)
    with pytest.raises(SkinrenderError, match="outside the bands 450–650 nm"):
        narrow.through(CAM)
