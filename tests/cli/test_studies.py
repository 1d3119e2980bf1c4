"""
``skinrender bench render --scene`` (:mod:`skinrender.cli.studies`): the face bench's document, and its flags
refused (exit 2, one line naming the flag) before anything renders.
"""

from __future__ import annotations

import json

import pytest

from .refusal import assert_refused, run


def test_face_bench_document(capsys):
    pytest.importorskip("mitsuba")
    status, out, err = run(["bench", "render", "--scene", "face", "--size", "16", "--spp-list", "1,4",
                            "--reference-spp", "16", "--levels", "direct", "--json"], capsys)
    assert status in (0, None), err[-500:]
    document = json.loads(out)
    assert [(r["level"], r["spp"]) for r in document["curve"]] == [("direct", 1), ("direct", 4)]
    assert document["size"] == [16, 16] and document["reference_spp"] == 16
    assert set(document["presets"]["direct"]) >= {"draft", "standard", "reference"}


@pytest.mark.parametrize("argv, names", [
    (["render", "--scene", "macbeth"], "--scene"),
    (["render", "--scene", "nowhere.toml"], "--scene"),
    (["search", "--scene", "face"], "--scene"),
    (["render", "--size", "64"], "--size"),
    (["render", "--spp-list", "4"], "--spp-list"),
    (["render", "--scene", "face", "--size", "0"], "--size"),
    (["render", "--scene", "face", "--size", "64,32"], "--size"),
    (["render", "--scene", "face", "--spp-list", "4,x"], "--spp-list"),
    (["render", "--scene", "face", "--reference-spp", "0"], "--reference-spp"),
    (["render", "--scene", "face", "--size", "2000", "--reference-spp", "1000"], "--reference-spp"),
    (["render", "--scene", "face", "--levels", "direct,glossy"], "--levels"),
    (["render", "--scene", "face", "--levels", ","], "--levels"),
    (["render", "--scene", "face", "--plot", "curve.png"], "--plot"),
])
def test_face_bench_refusals(argv, names, capsys):
    assert_refused(["bench", *argv], names, capsys)
