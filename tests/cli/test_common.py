"""Tests for :mod:`skinrender.cli.common`: what every command shares (here: how a document is printed)."""

from __future__ import annotations

import argparse
import math

import pytest

from skinrender.cli.common import coverage_hint, emit


def test_a_document_that_cannot_be_json_prints_nothing_not_half(capsys):
    args = argparse.Namespace(json=True)
    with pytest.raises(ValueError, match="JSON"):
        emit(args, {"first": list(range(2000)), "last": math.inf}, "text")
    assert capsys.readouterr().out == ""


def test_a_document_prints_whole(capsys):
    emit(argparse.Namespace(json=True), {"a": [1, 2]}, "text")
    emit(argparse.Namespace(json=False), {"a": [1, 2]}, "as text\n\n")
    assert capsys.readouterr().out == '{\n  "a": [\n    1,\n    2\n  ]\n}\nas text\n'


COVERAGE = ("c.csv: measured over 420–680 nm, which does not cover the grid 400–700 nm; choose a grid inside the "
            "data or state an extrapolation ('zero' or 'constant')")


@pytest.mark.parametrize("flags, advice", [
    ({"grid": "400:700:1", "extrapolation": "refuse"}, "choose a --grid inside the data or an --extrapolation"),
    ({"grid": "400:700:1"}, "choose a --grid inside the data"),
    ({}, "this command integrates over that grid"),
])
def test_coverage_advice_names_only_the_flags_the_command_has(flags, advice):
    line = coverage_hint(COVERAGE, argparse.Namespace(**flags))
    assert line.startswith("c.csv: measured over 420–680 nm") and line.endswith(advice + (
        " ('zero' or 'constant')" if "extrapolation" in flags else "" if "grid" in flags else ": give spectra that cover it"))
    for name in ("--grid", "--extrapolation"):
        assert (name in line) == (name.lstrip("-") in flags)


def test_other_messages_keep_their_words():
    assert coverage_hint("--seed must be an integer", argparse.Namespace()) == "--seed must be an integer"
