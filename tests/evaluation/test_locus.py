"""Tests for :mod:`skinrender.locus`: the skin locus contains its training points, detection rates are right."""

from __future__ import annotations

import numpy as np
import pytest

import skinrender as sr
from skinrender.errors import SkinrenderError
from skinrender.evaluation.detection import Detection, detect
from skinrender.evaluation.locus import false_positive_rate, locus_points, skin_locus

CAMERA = "gbell:9@450,540,610"


@pytest.mark.parametrize("boundary", ["hull", "quadratic"])
@pytest.mark.parametrize("calibration", [None, 5900.0])
def test_locus_contains_every_training_chromaticity(boundary, calibration):
    locus = skin_locus(CAMERA, "skin", calibration=calibration, boundary=boundary)
    points = locus_points(CAMERA, "skin", calibration=calibration)
    assert np.all(locus.contains(points))
    assert locus.area > 0


def test_quadratic_is_tighter_than_nothing_and_one_balancing_is_smaller():
    several = skin_locus(CAMERA, "skin")
    one = skin_locus(CAMERA, "skin", calibration=3300.0)
    assert one.area < several.area  # one white balancing: a narrower locus (Martinkauppi)


def test_false_positive_rate_is_a_fraction_and_can_be_zero_or_one():
    locus = skin_locus(CAMERA, "skin")
    rate = false_positive_rate(locus, CAMERA, "munsell")
    assert 0 < rate < 1
    assert false_positive_rate(locus, CAMERA, "skin") == 1.0
    blue = np.zeros((3, sr.GRID_DEFAULT.size))
    blue[:, :60] = 0.8
    blue[:, 60:] = 0.02
    one = skin_locus(CAMERA, "skin", calibration=5900.0)
    assert false_positive_rate(one, CAMERA, blue) == 0.0  # one white balancing: blue never looks like skin


def test_detection_rates_on_a_synthetic_chart():
    """Known labels: skin patches and one blue patch, rendered analytically into a fake image."""
    from types import SimpleNamespace

    from skinrender.rendering.scene import ChartScene, Patch

    patches = (Patch("s1", "skin:#0", True), Patch("s2", "skin:#9", True), Patch("blue", "macbeth:blue", False),
               Patch("white reference", "perfect", False))
    chart = ChartScene("synthetic", "", 4, 6, 1, 1, patches)
    width, height = chart.size
    image = np.zeros((height, width, 3))
    rgb = sr.response(CAMERA, chart.reflectances(sr.GRID_DEFAULT), 3300, 3300)
    for i in range(len(patches)):
        x0, y0, x1, y1 = chart.patch_box(i)
        image[y0:y1, x0:x1] = rgb[i]
    rendering = SimpleNamespace(scene=chart, image=image)
    result = detect(rendering, skin_locus(CAMERA, "skin", calibration=3300.0))
    assert isinstance(result, Detection)
    assert result.tpr == 1.0 and result.fpr == 0.0
    assert [p["detected_fraction"] for p in result.per_patch] == [1.0, 1.0, 0.0]


def test_bad_boundary():
    with pytest.raises(SkinrenderError, match="boundary"):
        skin_locus(CAMERA, boundary="circle")


def test_a_locus_takes_its_lights_as_text_as_the_cli_does():
    """``calibration="A"`` and ``illuminants="2000,3300,5900"`` as ``locus --calibration A --illuminants …`` (a bare
    ValueError, or "illuminants must be numbers", before)."""
    by_name = skin_locus(CAMERA, calibration="A", illuminants="2000,3300,5900")
    by_number = skin_locus(CAMERA, calibration=2856, illuminants=[2000, 3300, 5900])
    assert by_name.calibration == 2856.0 and np.array_equal(by_name.polygon, by_number.polygon)
    assert by_name.illuminants.tolist() == [2000.0, 3300.0, 5900.0]
    for calibration in ("nosuch", -5):
        with pytest.raises(SkinrenderError) as error:
            skin_locus(CAMERA, calibration=calibration)
        assert error.value.role == "calibration" and str(error.value).startswith("calibration")
