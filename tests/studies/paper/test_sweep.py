"""Tests for :mod:`skinrender.studies.paper.sweep`: one row per setting, files written, refusals leave nothing."""

from __future__ import annotations

import csv
import os

import pytest

from skinrender.errors import SkinrenderError
from skinrender.studies.paper.sweep import SWEEP_GRIDS, SWEEP_SLOPES, reproduce_sweep, sweep, sweep_candidates

CANDIDATES = {"slope": [2.0, 3.0], "skin": ["skin", "skin-model"], "munsell": ["munsell", "munsell-nickerson"]}


@pytest.fixture(scope="module")
def tiny():
    """Two sensors on a 50 nm grid, three unknowns, two of them combined."""
    return sweep([1, 9], "400:700:50", combine=2, candidates=CANDIDATES, workers=2)


class TestSweep:
    def test_one_row_per_setting(self, tiny):
        settings = [row["setting"] for row in tiny["sweep"]]
        assert settings[:4] == ["default", "slope=3", "skin=skin-model", "munsell=munsell-nickerson"]
        assert len(settings) == len(set(settings))
        combined = [row for row in tiny["sweep"] if "+" in row["unknown"]]
        assert len(tiny["combined"]) == 2 and 1 <= len(combined) <= 4
        assert len(settings) == 4 + len(combined)
        for row in tiny["sweep"]:
            assert {"setting", "exact", "within_step", "total", "matches_by_table", "tables"} <= set(row)
            assert row["total"] == 12 and 0 <= row["exact"] <= row["within_step"] <= 12

    def test_shared_volumes_are_computed_once(self, tiny):
        """Default 4 banks; slope 3 changes the gbell's two (not the impulse's); each set change one per sensor."""
        assert tiny["volumes_computed"] >= 4 + 2 + 2 + 2

    def test_candidates_follow_the_issue(self, tmp_path):
        values, notes, _ = sweep_candidates(tmp_path, shared=tmp_path / "absent")
        assert values["slope"] == list(SWEEP_SLOPES) and values["grid"] == list(SWEEP_GRIDS)
        assert values["skin"] == ["skin", "skin-model"] and values["munsell"] == ["munsell", "munsell-nickerson"]
        assert values["illuminants"][0] == ("paper", None) and len(values["illuminants"]) == 5
        assert len(notes) == 2  # NIST and the DXC-930 absent, both said


class TestReproduceSweep:
    def test_writes_csv_and_markdown(self, tmp_path):
        out = tmp_path / "sweep"
        result = reproduce_sweep(out, [9], "400:700:100", candidates={"slope": [3.0]}, combine=0, workers=1)
        assert sorted(os.listdir(out)) == ["reproduce.json", "sweep.csv", "sweep.md"]
        with open(out / "sweep.csv", encoding="utf-8") as handle:
            rows = list(csv.DictReader(handle))
        assert [r["setting"] for r in rows] == ["default", "slope=3"] == [r["setting"] for r in result["sweep"]]
        assert "slope=3" in (out / "sweep.md").read_text(encoding="utf-8")

    @pytest.mark.parametrize(("argument", "value", "flag"), [
        ("sensors", "1,x", "--sensors"), ("positions", "400:900:10", "--positions"), ("workers", 0, "--workers"),
        ("workers", 1000, "--workers"), ("combine", 6, "--sweep-combine"), ("combine", -1, "--sweep-combine"),
        ("values_per_unknown", 0, "--sweep-values"),
    ])
    def test_refusals_leave_no_folder(self, tmp_path, argument, value, flag):
        options = {"sensors": [9], "positions": "400:700:100", "workers": 1, argument: value}
        with pytest.raises(SkinrenderError, match=flag):
            reproduce_sweep(tmp_path / "out", options.pop("sensors"), options.pop("positions"), **options)
        assert os.listdir(tmp_path) == []
