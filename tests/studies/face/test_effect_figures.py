"""Tests for :mod:`skinrender.studies.face.effect_figures`: the effects table drawn from rows, ``None`` values left out."""

from __future__ import annotations

import pytest

from skinrender.studies.face.effect_figures import figure_effects

pytest.importorskip("matplotlib")


def test_rows_with_gaps_draw(tmp_path):
    rows = [{"tone": tone, "level": level, "eq4_shift": shift, "eq4_shift_bound": None if shift is None else 2 * shift,
             "budget": 0.002, "tpr_change": 0.0 if level == "direct" else -0.1, "fpr_change": None, "seconds": 1.5}
            for tone in ("light", "dark") for level, shift in (("direct", 1e-5), ("noise", None), ("mixed", 0.09))]
    path = figure_effects(rows, "a title", tmp_path / "deep" / "effects.png")
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
