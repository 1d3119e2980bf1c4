"""
Tests for :mod:`skinrender.design.inputs`: a search's and a design's sets by name and illuminants as text, as the
CLI takes them, and their refusals naming the argument.
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.datasets import reflectances
from skinrender.design.inputs import design_inputs
from skinrender.design.optimise import optimise_camera
from skinrender.design.search import search
from skinrender.errors import SkinrenderError
from skinrender.spectra import GRID_DEFAULT, WavelengthGrid


def test_names_are_resampled_onto_the_grid_and_arrays_pass_as_they_are():
    grid = WavelengthGrid(400, 700, 10)
    skin, munsell, temperatures = design_inputs("skin", "munsell", "2000,3300,A", grid)
    assert np.array_equal(skin, reflectances("skin").on(grid)) and munsell.shape[-1] == grid.size
    assert temperatures.tolist() == [2000.0, 3300.0, 2856.0]
    values = np.full((2, grid.size), 0.3)
    assert design_inputs(values, values, [2856.0], grid)[0] is values


def test_sets_by_name_and_illuminants_as_text_as_the_cli_takes_them():
    """``search(9, "skin", "munsell", illuminants="paper")`` as ``search --skin skin --munsell munsell`` (they were
    refused: "reflectance must be numbers"); a noisy setting of the wrong type is refused naming it (a bare
    AttributeError before)."""
    from skinrender.datasets import reflectances

    by_name = search(9, "skin", "munsell", positions="450:650:50", illuminants="paper", workers=1)
    arrays = search(9, reflectances("skin").on(GRID_DEFAULT), reflectances("munsell").on(GRID_DEFAULT),
                    positions="450:650:50", workers=1)
    assert np.array_equal(by_name.skin, arrays.skin) and np.array_equal(by_name.munsell, arrays.munsell)
    for keywords, role in (({"noisy": "x"}, "noisy"), ({"illuminants": "2000,,3300"}, "illuminants"),
                           ({"skin": "nosuch"}, "skin")):
        arguments = {"skin": "skin", "munsell": "munsell", "positions": "450:650:50", "workers": 1, **keywords}
        with pytest.raises(SkinrenderError) as error:
            search(9, **arguments)
        assert error.value.role == role


@pytest.mark.parametrize("illuminants", ["auto", [2000, "x"], [2000, -1], []])
def test_bad_illuminants_are_refused_in_the_callers_words(illuminants):
    """A search has no camera for Stage 1's ``auto`` (the refusal named the CLI's ``--camera`` before); a list with
    text or a non-positive kelvin was a bare ValueError or named no argument."""
    with pytest.raises(SkinrenderError) as error:
        search(9, "skin", "munsell", positions="450:650:50", workers=1, illuminants=illuminants)
    assert error.value.role == "illuminants" and "--" not in str(error.value)


def test_a_design_takes_them_too():
    design = optimise_camera("ratio", "skin", "munsell", starts=((450.0, 540.0, 610.0),), max_evaluations=3,
                             illuminants="2000,3300,5900")
    assert design.peaks.shape == (3,)


def test_a_search_takes_its_grid_as_text():
    """``grid="400:700:10"`` as ``--grid`` (a bare AttributeError before)."""
    text = search(9, "skin", "munsell", grid="400:700:10", positions="450:650:50", workers=1)
    grid = search(9, "skin", "munsell", grid=WavelengthGrid(400, 700, 10), positions="450:650:50", workers=1)
    assert np.array_equal(text.skin, grid.skin)
