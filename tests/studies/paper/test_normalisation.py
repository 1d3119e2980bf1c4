"""Tests for :mod:`skinrender.studies.paper.normalisation`: the data of Figs. 3–7."""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.constants import TEMPERATURES_PAPER
from skinrender.evaluation.gamut import gamut
from skinrender.model.camera import camera
from skinrender.model.response import response
from skinrender.datasets import reflectances
from skinrender.errors import SkinrenderError
from skinrender.spectra import WavelengthGrid
from skinrender.studies.paper.normalisation import (Stage2, stage2_cases, stage2_gamut_panels, stage2_observation,
                                                    stage2_pairs)

GRID = WavelengthGrid(400, 700, 10)


def test_pairs_equal_qhull_volumes():
    """The compiled hull gives the volumes of :func:`skinrender.gamut` (Qhull) to 1e-12."""
    t = np.array(TEMPERATURES_PAPER[:3])
    volumes = stage2_pairs("Kodak DCS-200", "macbeth", "560nm", True, t, GRID)
    points = response(camera("Kodak DCS-200"), reflectances("macbeth").on(GRID), t[:, None], t[None, :], "560nm",
                      True, GRID)
    expected = np.array([[gamut(points[p, q]).volume for q in range(3)] for p in range(3)])
    np.testing.assert_allclose(volumes, expected, rtol=1e-12)


def test_observation_counts_the_diagonal():
    volumes = np.array([[3.0, 1.0, 1.0], [1.0, 1.0, 5.0], [1.0, 2.0, 1.0]])
    seen = stage2_observation(volumes)
    assert seen["argmax_prevailing"] == [0, 2, 1] and seen["on_calibration"] == 1 and seen["total"] == 3


def test_panels_of_a_short_illuminant_set():
    panels = stage2_gamut_panels("Kodak DCS-200", "macbeth", [2000.0, 5000.0], GRID)
    assert len(panels) == 2 and panels[0]["label"] == "prevailing 5000 K, calibration 5000 K"


def test_cases_take_the_setting_whole_or_by_keyword():
    """Fig. 7's volumes are the same from a whole :class:`Stage2` and from its fields by keyword."""
    t = [2000.0, 5000.0]
    whole = stage2_cases(Stage2("Kodak DCS-200", munsell="macbeth", illuminants=t, grid=GRID))
    named = stage2_cases("Kodak DCS-200", munsell="macbeth", illuminants=t, grid=GRID)
    assert all(np.array_equal(whole[key], named[key]) for key in ("skin", "munsell", "ratio", "temperatures"))
    assert whole["skin"].shape == (2,) and np.all(whole["munsell"] > 0)
    with pytest.raises(SkinrenderError, match="munsel: not a Stage 2 setting"):
        stage2_cases("Kodak DCS-200", munsel="macbeth")
