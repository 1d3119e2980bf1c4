"""Tests for :mod:`skinrender.cli.common`: what every command shares (here: how a document is printed)."""

from __future__ import annotations

import argparse
import math

import pytest

from skinrender.cli.common import coverage_hint, emit
from skinrender.errors import SkinrenderError


def test_a_document_that_cannot_be_json_prints_nothing_not_half(capsys):
    args = argparse.Namespace(json=True)
    with pytest.raises(ValueError, match="JSON"):
        emit(args, {"first": list(range(2000)), "last": math.inf}, "text")
    assert capsys.readouterr().out == ""


def test_a_document_prints_whole(capsys):
    emit(argparse.Namespace(json=True), {"a": [1, 2]}, "text")
    emit(argparse.Namespace(json=False), {"a": [1, 2]}, "as text\n\n")
    assert capsys.readouterr().out == '{\n  "a": [\n    1,\n    2\n  ]\n}\nas text\n'


def coverage_error():
    """The refusal of spectra that do not cover the grid, as :func:`skinrender.spectra.resample` raises it."""
    from skinrender.spectra import WavelengthGrid, resample

    with pytest.raises(SkinrenderError) as caught:
        resample([420.0, 680.0], [[0.5, 0.5]], WavelengthGrid(400, 700, 1), source="c.csv")
    return caught.value


@pytest.mark.parametrize("flags, advice", [
    ({"grid": "400:700:1", "extrapolation": "refuse"},
     "choose a --grid inside the data or an --extrapolation ('zero' or 'constant')"),
    ({"grid": "400:700:1", "extrapolation": "constant"},
     "choose a --grid inside the data (--extrapolation constant applies to CSV files, not to these spectra)"),
    ({"grid": "400:700:1"}, "choose a --grid inside the data"),
    ({}, "this command integrates over that grid: give spectra that cover it"),
])
def test_coverage_advice_names_only_the_flags_the_command_has(flags, advice):
    """The advice is chosen by the error's ``cause`` field, not by matching its words; an --extrapolation given
    that did not apply is not advised again (seen: ``response --grid 300:900:1 --extrapolation constant``)."""
    error = coverage_error()
    assert error.cause == "coverage" and str(error).endswith(error.hint)  # the library's own words keep the hint
    line = coverage_hint(error, argparse.Namespace(**flags))
    assert line == "c.csv: measured over 420–680 nm, which does not cover the grid 400–700 nm; " + advice


def test_other_messages_keep_their_words():
    error = SkinrenderError("--seed must be an integer")
    assert coverage_hint(error, argparse.Namespace(grid="400:700:1")) == "--seed must be an integer"
