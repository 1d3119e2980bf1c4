"""
Tests for :mod:`skinrender.evaluation.detection`: only pixels with a colour are scored, and a chart with no
scored skin or non-skin pixel has undefined rates (``None`` and the reason), never 0.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

import skinrender as sr
from skinrender.evaluation.detection import detect, scored_pixels
from skinrender.evaluation.locus import skin_locus
from skinrender.rendering.scene import ChartScene, Patch

CAMERA = "gbell:9@450,540,610"


def chart_rendering(scale: float, noise: float = 0.0):
    """Two skin patches and a blue one, Eq. 4 at 3300 K times ``scale`` (0: black), plus ``noise`` (output units)."""
    patches = (Patch("s1", "skin:#0", True), Patch("s2", "skin:#9", True), Patch("blue", "macbeth:blue", False),
               Patch("white reference", "perfect", False))
    chart = ChartScene("synthetic", "", 4, 6, 1, 1, patches)
    width, height = chart.size
    image = np.zeros((height, width, 3))
    rgb = sr.response(CAMERA, chart.reflectances(sr.GRID_DEFAULT), 3300, 3300) * scale
    for i in range(len(patches)):
        x0, y0, x1, y1 = chart.patch_box(i)
        image[y0:y1, x0:x1] = rgb[i]
    image += noise * np.random.default_rng(0).standard_normal(image.shape)
    return SimpleNamespace(scene=chart, image=image)


@pytest.fixture(scope="module")
def locus():
    return skin_locus(CAMERA, "skin", calibration=3300.0)


def test_a_black_chart_has_undefined_rates_not_zero(locus):
    """Seen by a user: a black render gave fpr 0.0 (black's achromatic point is outside the locus)."""
    result = detect(chart_rendering(0.0), locus)
    assert result.tpr is None and result.fpr is None
    assert "no scored skin pixel in its 2 skin patches" in result.undefined["tpr"]
    assert "no scored non-skin pixel in its 1 non-skin patch " in result.undefined["fpr"]
    assert all(p["detected_fraction"] is None and p["scored_pixels"] == 0 and "no scored pixel" in p["undefined"]
               for p in result.per_patch)
    assert not result.mask.any()


def test_a_dim_chart_below_the_threshold_is_undefined_and_says_the_threshold(locus):
    dim = chart_rendering(0.02)  # the brightest channel of each patch below 10 output units, above 0
    assert 0 < dim.image.max() < 10
    assert detect(dim, locus).tpr == 1.0  # without a threshold every lit pixel is scored
    result = detect(dim, locus, scored_min=10.0)
    assert result.tpr is None and result.fpr is None and "≥ 10" in result.undefined["fpr"]


def test_a_lit_chart_is_scored_as_before(locus):
    result = detect(chart_rendering(1.0), locus, scored_min=10.0)
    assert result.tpr == 1.0 and result.fpr == 0.0 and result.undefined == {}
    assert [p["detected_fraction"] for p in result.per_patch] == [1.0, 1.0, 0.0]
    assert all(p["scored_pixels"] == p["pixels"] > 0 for p in result.per_patch)


def test_negative_noise_on_black_is_no_light(locus):
    """A sensor's read noise around a black level: negative pixels have no light; the rest count."""
    noisy = chart_rendering(0.0, noise=1.0)
    scored = scored_pixels(noisy.image)
    assert scored.sum() == np.any(noisy.image > 0, axis=-1).sum() and 0 < scored.mean() < 1
    result = detect(noisy, locus)
    assert sum(p["scored_pixels"] for p in result.per_patch) < sum(p["pixels"] for p in result.per_patch)
    assert not (result.mask & ~scored).any()


@pytest.mark.parametrize("rendering, locus_given, scored_min, name", [
    ("chart", None, 0.0, "locus"), (None, "locus", 0.0, "rendering"), ("chart", "locus", -1.0, "scored_min"),
    ("chart", "locus", float("nan"), "scored_min"), ("chart", "locus", "1", "scored_min"),
    ("chart", "a string", 0.0, "locus"),
])
def test_a_bad_argument_names_itself(locus, rendering, locus_given, scored_min, name):
    """Issue 36: ``sr.detect(r, None)`` raised a bare AttributeError."""
    chart = chart_rendering(1.0) if rendering == "chart" else rendering
    given = locus if locus_given == "locus" else locus_given
    with pytest.raises(sr.SkinrenderError, match=f"^{name}") as error:
        sr.detect(chart, given, scored_min)
    assert error.value.role == name
