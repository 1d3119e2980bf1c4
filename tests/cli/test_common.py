"""Tests for :mod:`skinrender.cli.common`: what every command shares (here: how a document is printed)."""

from __future__ import annotations

import argparse
import math

import pytest

from skinrender.cli.common import emit


def test_a_document_that_cannot_be_json_prints_nothing_not_half(capsys):
    args = argparse.Namespace(json=True)
    with pytest.raises(ValueError, match="JSON"):
        emit(args, {"first": list(range(2000)), "last": math.inf}, "text")
    assert capsys.readouterr().out == ""


def test_a_document_prints_whole(capsys):
    emit(argparse.Namespace(json=True), {"a": [1, 2]}, "text")
    emit(argparse.Namespace(json=False), {"a": [1, 2]}, "as text\n\n")
    assert capsys.readouterr().out == '{\n  "a": [\n    1,\n    2\n  ]\n}\nas text\n'
