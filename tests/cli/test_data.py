"""``cameras`` and ``datasets`` (:mod:`skinrender.cli.data`): one JSON document, and clean refusals."""

from __future__ import annotations

import json

import pytest

from .refusal import assert_refused, run


@pytest.mark.parametrize("command, key", [("cameras", "cameras"), ("datasets", "datasets")])
def test_lists_are_one_json_document(command, key, capsys):
    status, out, _ = run([command, "--json"], capsys)
    assert status == 0 and len(json.loads(out)[key]) >= 4


@pytest.mark.parametrize("argv, names", [
    (["cameras", "extra"], "unrecognized arguments"),
    (["datasets", "--count"], "unrecognized arguments"),
    (["nosuchcommand"], "invalid choice"),
])
def test_unknown_arguments_are_one_line(argv, names, capsys):
    assert_refused(argv, names, capsys)
