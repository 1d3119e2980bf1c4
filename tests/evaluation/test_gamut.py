"""Tests for :mod:`skinrender.gamut`: hand-computable shapes, degenerate clouds, the paper's cases."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

import skinrender as sr
from skinrender.errors import SkinrenderError
from skinrender.evaluation.gamut import gamut, gamut_all_calibrations, gamut_calibration, gamut_volume

CUBE = np.array(list(itertools.product([0.0, 1.0], repeat=3)))


class TestGamutVolume:
    def test_unit_cube(self):
        assert gamut_volume(CUBE) == pytest.approx(1.0, rel=1e-12)

    def test_tetrahedron(self):
        """Corner tetrahedron of edge 2: volume 2³/6."""
        points = np.array([[0, 0, 0], [2, 0, 0], [0, 2, 0], [0, 0, 2.0]])
        assert gamut_volume(points) == pytest.approx(8 / 6, rel=1e-12)

    def test_interior_points_ignored(self, rng):
        points = np.vstack([CUBE, rng.random((500, 3))])
        assert gamut_volume(points) == pytest.approx(1.0, rel=1e-12)

    def test_scaled_cloud(self, rng):
        """A diagonal scaling (sx, sy, sz) multiplies the volume by sx·sy·sz (Eq. 4's white balance)."""
        points = rng.random((200, 3))
        scale = np.array([2.0, 0.5, 7.0])
        assert gamut_volume(points * scale) == pytest.approx(gamut_volume(points) * 7.0, rel=1e-10)

    def test_n_dimensional(self, rng):
        points = rng.random((4, 50, 3))
        assert gamut_volume(points) == pytest.approx(gamut_volume(points.reshape(-1, 3)))


class TestDegenerate:
    @pytest.mark.parametrize(
        "points",
        [
            np.zeros((0, 3)),
            np.array([[0, 0, 0], [1, 1, 1], [2, 0, 1.0]]),  # three points
            np.array([[1, 2, 3]] * 10, dtype=float),  # coincident
            np.outer(np.linspace(0, 1, 20), [1.0, 2.0, 3.0]),  # collinear
            np.column_stack([np.random.default_rng(0).random((30, 2)), np.zeros(30)]),  # coplanar
        ],
        ids=["empty", "three", "coincident", "collinear", "coplanar"],
    )
    def test_zero_and_flagged(self, points):
        result = gamut(points)
        assert result.volume == 0.0 and result.degenerate

    def test_coincident_sensors(self):
        """Three sensors at one peak give R = G = B for every sample: a line, volume 0, no Qhull error."""
        result = gamut_calibration("gbell:9@550,550,550", "munsell", 3300)
        assert result.volume == 0.0 and result.degenerate and result.points == 12690

    def test_nan_is_an_error(self):
        with pytest.raises(SkinrenderError, match="NaN or inf"):
            gamut(np.array([[0, 0, np.nan], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]]))

    def test_bad_shape(self):
        with pytest.raises(SkinrenderError, match="three channels"):
            gamut(np.zeros((5, 2)))


class TestCases:
    def test_calibration_case_is_union_over_prevailing(self):
        t = np.array(sr.TEMPERATURES_PAPER)
        rgb = sr.response("gbell:9@450,540,610", "skin", t, 3300)
        assert gamut_calibration("gbell:9@450,540,610", "skin", 3300).volume == pytest.approx(gamut_volume(rgb))
        assert gamut_calibration("gbell:9@450,540,610", "skin", 3300).points == 10 * 30

    def test_all_calibrations_contains_each_case(self):
        cam = "gbell:7@440,550,600"
        whole = gamut_all_calibrations(cam, "macbeth").volume
        for c in sr.TEMPERATURES_PAPER:
            assert gamut_calibration(cam, "macbeth", c).volume <= whole * (1 + 1e-12)

    def test_skin_gamut_smaller_than_munsell(self):
        for case in (gamut_calibration("Nikon 5100 (NPL)", "skin", 3300), gamut_calibration("Nikon 5100 (NPL)", "munsell", 3300)):
            assert case.volume > 0
        ratio = gamut_calibration("Nikon 5100 (NPL)", "skin", 3300).volume / gamut_calibration(
            "Nikon 5100 (NPL)", "munsell", 3300).volume
        assert 0 < ratio < 1


def test_an_illuminant_set_as_text_as_the_cli_takes_it():
    """``illuminants="paper" | "auto" | "2000,3300,A"`` as ``--illuminants`` (they raised a bare ValueError)."""
    from skinrender.model.stage1 import select_illuminants

    cam = "gbell:9@450,540,610"
    assert gamut_calibration(cam, "macbeth", 3300, "paper").volume == gamut_calibration(cam, "macbeth", 3300).volume
    auto = gamut_calibration(cam, "macbeth", 3300, select_illuminants(cam)).volume
    assert gamut_calibration(cam, "macbeth", 3300, "auto").volume == auto
    listed = gamut_all_calibrations(cam, "macbeth", "2000,3300,A").volume
    assert listed == gamut_all_calibrations(cam, "macbeth", [2000.0, 3300.0, 2856.0]).volume
    with pytest.raises(SkinrenderError) as error:
        gamut_calibration(cam, "macbeth", 3300, "2000,,3300")
    assert error.value.role == "illuminants" and str(error.value).startswith("illuminants")


def test_one_illuminant_for_all_calibrations_is_its_one_pair():
    """A single temperature (a bare IndexError before) is the set of one: the canonical case."""
    cam = "gbell:9@450,540,610"
    one = gamut_calibration(cam, "macbeth", 3300, [3300]).volume
    assert gamut_all_calibrations(cam, "macbeth", 3300).volume == one
