"""Tests for :mod:`skinrender.studies.face.effects_table`: per skin and level the ladder's shift, budget, rate changes and
seconds, tiny; refusals."""

from __future__ import annotations

import json

import pytest

from skinrender.errors import SkinrenderError
from skinrender.rendering.face.effects import LEVELS_EACH
from skinrender.studies.face.effects_table import ROW_KEYS, SKIN_TONES, effects_table

pytest.importorskip("mitsuba")

CAMERA = "gbell:9@450,540,610"


def test_rows_per_skin_and_level(tmp_path):
    table = effects_table(CAMERA, 2856, 5900, skins={"light": SKIN_TONES["light"], "dark": SKIN_TONES["dark"]},
                          levels=("direct", "mixed"), spp=48, size=24)
    document = json.loads(json.dumps(table.document(), allow_nan=False))
    assert [(row["tone"], row["level"]) for row in document["rows"]] == [
        ("light", "direct"), ("light", "mixed"), ("dark", "direct"), ("dark", "mixed")]
    for row in document["rows"]:
        assert set(row) >= {"tone", "skin", "level", "undefined", *ROW_KEYS} and row["seconds"] > 0
        if row["level"] == "direct":
            assert row["tpr_change"] in (0, None) and row["fpr_change"] in (0, None)
    assert [skin["tone"] for skin in document["skins"]] == ["light", "dark"]
    assert all(skin["budget"]["fraction"] == 0.5 for skin in document["skins"])
    mixed = [row for row in document["rows"] if row["level"] == "mixed"]
    assert all(row["fpr_change"] > 0.1 for row in mixed), "the window and the sky let props in"
    assert document["verdict"] == "fail" and document["exit_status"] == 1
    assert table.figure(tmp_path / "effects.png").read_bytes()[:4] == b"\x89PNG"


def test_defaults_and_refusals():
    assert list(SKIN_TONES) == ["light", "medium", "dark"] and "direct" in LEVELS_EACH
    with pytest.raises(SkinrenderError, match="direct"):
        effects_table(CAMERA, 2856, 5900, levels=("sheen",), spp=1, size=4)
    with pytest.raises(SkinrenderError, match="skins"):
        effects_table(CAMERA, 2856, 5900, skins={}, spp=1, size=4)
