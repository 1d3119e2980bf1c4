"""Tests for :mod:`skinrender.design`: the optimiser improves its objective from a poor start."""

from __future__ import annotations

import numpy as np
import pytest

import skinrender as sr
from skinrender.design.optimise import objective, optimise_camera
from skinrender.errors import SkinrenderError


@pytest.fixture(scope="module")
def sets():
    return sr.reflectances("skin").on(sr.GRID_DEFAULT), sr.reflectances("munsell").on(sr.GRID_DEFAULT)


@pytest.mark.parametrize("kind", ["detection", "ratio"])
def test_improves_from_a_poor_start(sets, kind):
    design = optimise_camera(kind, *sets, starts=[(420.0, 550.0, 680.0)], max_evaluations=40)
    start = design.starts[0]
    assert design.value < start["start_value"]
    assert design.value == pytest.approx(objective(kind, design.peaks, design.fwhm, *sets, design.slope))
    assert np.all(np.diff(design.peaks) > 0) and 400 <= design.peaks[0] and design.peaks[-1] <= 700


def test_objective_matches_the_search(sets):
    from skinrender.design.search import search

    result = search(9, *sets, "400:700:100", workers=1, detection=True)  # 400, 500, 600, 700 nm
    t = 1  # 400 500 700
    assert objective("ratio", result.triplets[t], 90.0, *sets) == pytest.approx(result.ratio[t, -1], rel=1e-12)
    assert objective("detection", result.triplets[t], 90.0, *sets) == pytest.approx(result.fpr[t, 0], rel=1e-12)


def test_out_of_bounds_is_infinite_and_bad_kind_refused(sets):
    assert objective("ratio", [390, 500, 600], 90.0, *sets) == np.inf
    with pytest.raises(SkinrenderError, match="objective"):
        objective("beauty", [450, 500, 600], 90.0, *sets)
