"""
Tests for :mod:`skinrender.methods`: the method tables' one validator, ``START:END:STEP`` parsing, and the one
check of every range (wavelength grids, sensor positions, Stage 1's candidate temperatures), each kind wording
its refusals as it always has.
"""

from __future__ import annotations

import pytest

from skinrender.design.bank import positions_grid
from skinrender.errors import SkinrenderError
from skinrender.methods import RangeWords, parse_range, range_steps, validate_method
from skinrender.model.stage1 import temperature_range
from skinrender.spectra import WavelengthGrid

WORDS = RangeWords(lambda r: f"order {r.text}", lambda r: f"count {r.values:g}", lambda r: f"whole {r.end:g}")


@pytest.mark.parametrize("start, end, step, expected", [(400, 700, 10, 30), (2000, 10000, 100, 80), (1, 2, 1, 1),
                                                        (400, 700, 0.1, 3000)])
def test_steps_count_the_end_in(start, end, step, expected):
    assert range_steps(start, end, step, 3001, WORDS) == expected


@pytest.mark.parametrize("start, end, step, message", [
    (700, 400, 10, "order x"), (400, 400, 10, "order x"), (400, 700, 0, "order x"), (400, 700, -1, "order x"),
    (400, 700, 0.01, "count 30001"), (400, 700, 7, "whole 700"), (400, 690, 50, "whole 690"),
])
def test_each_refusal_is_worded_by_its_kind(start, end, step, message):
    with pytest.raises(SkinrenderError, match=f"^{message}$"):
        range_steps(start, end, step, 3001, WORDS, "x")


@pytest.mark.parametrize("make, message", [
    (lambda: WavelengthGrid(400, 700, 7), "grid 400–700 nm is not a whole number of 7 nm steps"),
    (lambda: WavelengthGrid.parse("400:700:7"), "grid 400.0–700.0 nm is not a whole number of 7.0 nm steps"),
    (lambda: WavelengthGrid(400, 300, 1), "grid end (300 nm) must be above grid start (400 nm): a grid needs two "
                                          "samples"),
    (lambda: WavelengthGrid(1, 1e6, 1), "grid 1:1e+06:1 nm has 1e+06 samples, more than 100001 (every spectrum "
                                        "would need 8 MB); use a larger step"),
    (lambda: positions_grid("400:700:70"), "positions '400:700:70': 700 nm is not START + a whole number of 70 nm "
                                           "steps (the end is included, never dropped)"),
    (lambda: positions_grid("700:400:10"), "positions '700:400:10': need END > START and STEP > 0 (nm)"),
    (lambda: positions_grid("400:700:0.01"), "positions '400:700:0.01': 3e+04 positions, more than 3001 (4.5e+12 "
                                             "triplets); use a larger step"),
    (lambda: temperature_range(2000, 10000, 7), "temperature range 2000–10000 K is not a whole number of 7 K steps"),
    (lambda: temperature_range(5000, 2000, 10), "temperature range end 2000 K must be above its start 5000 K"),
    (lambda: temperature_range(2000, 10000, 0.01), "temperature range 2000–10000 K every 0.01 K has 8e+05 "
                                                   "candidates, more than 100001; use a larger step"),
])
def test_the_ranges_word_their_refusals_as_before(make, message):
    with pytest.raises(SkinrenderError) as error:
        make()
    assert str(error.value) == message


def test_parse_range_and_validate_method():
    assert parse_range("400:700:5nm", "grid") == (400.0, 700.0, 5.0)
    with pytest.raises(SkinrenderError, match=r"^grid must be START:END:STEP in nm \(e.g. 400:700:10\), got '400:7'"):
        parse_range("400:7", "grid")
    with pytest.raises(SkinrenderError) as error:
        validate_method("x", {"a": 1}, "method", role="method")
    assert error.value.role == "method" and str(error.value) == "method must be one of a, got 'x'"


def test_every_method_table_maps_names_to_described_functions():
    """Each family's table holds functions (colour-science's ``*_METHODS``), each with a one-line description for
    the command line's help; its dispatcher refuses a name outside it, naming the choices."""
    from skinrender.design.optimise import OBJECTIVES
    from skinrender.design.search import SEARCH_METHODS
    from skinrender.evaluation.locus import BOUNDARIES
    from skinrender.methods import describe, method_of
    from skinrender.model.factors import NORMALISATIONS, QUADRATURES
    from skinrender.rendering.face.validation import LIMITS_SCENE_FREE
    from skinrender.rendering.renderer import EMITTERS
    from skinrender.rendering.sensor_validation import MC_VARIANCE
    from skinrender.rendering.settings import CHANNEL_GROUPINGS, SAMPLERS
    from skinrender.spectra import EXTRAPOLATIONS

    tables = [EXTRAPOLATIONS, NORMALISATIONS, QUADRATURES, BOUNDARIES, SEARCH_METHODS, OBJECTIVES, SAMPLERS,
              CHANNEL_GROUPINGS, EMITTERS, MC_VARIANCE, LIMITS_SCENE_FREE]
    for table in tables:
        assert all(callable(function) and describe(function) and "\n" not in describe(function)
                   for function in table.values()), table
        first = next(iter(table))
        assert method_of(first, table, "method") is table[first]
        with pytest.raises(SkinrenderError, match=f"method must be one of {', '.join(table)}, got 'nothing'"):
            method_of("nothing", table, "method")


def test_takes_tells_the_methods_that_take_an_option():
    """Only the detection objective takes noisy pixels; only the frames variance method a second frame."""
    from skinrender.design.optimise import OBJECTIVES
    from skinrender.methods import takes
    from skinrender.rendering.sensor_validation import MC_VARIANCE

    assert [name for name, f in OBJECTIVES.items() if takes(f, "noisy")] == ["detection"]
    assert [name for name, f in MC_VARIANCE.items() if takes(f, "other")] == ["frames"]
