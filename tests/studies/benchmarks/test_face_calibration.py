"""
Tests for :mod:`skinrender.studies.benchmarks.face_calibration`: independent validations (seeds a validation's replicates
apart), per check the failures, trials, Clopper–Pearson interval and nominal α; eq4_shift's failures counted as
false alarms only where Eq. 4 holds; the chart bench's run shape.
"""

from __future__ import annotations

import pytest

from skinrender.errors import SkinrenderError
from skinrender.evaluation.verdict import Verdict, binomial_interval
from skinrender.studies.benchmarks.face_calibration import SEED_STEP, face_calibration, face_run

pytest.importorskip("mitsuba")

CAMERA = "gbell:9@450,540,610"


def test_per_check_rates_over_independent_seeds():
    result = face_calibration("direct", seeds=2, camera_=CAMERA, spp=192, size=24, first_seed=5, limits=("sphere",))
    assert [run["seed"] for run in result["runs"]] == [5, 5 + SEED_STEP] and SEED_STEP == 12
    rows = {row["name"]: row for row in result["checks"]}
    assert set(rows) == {"shading_cancels", "detection", "eq4_shift", "closed_sphere"}
    for row in rows.values():
        assert row["trials"] == 2 and sum(row["outcomes"].values()) == 2 and row["test"]
        assert row["interval"] == pytest.approx(list(binomial_interval(row["failures"], 2)))
        assert row["rate"] == row["failures"] / 2
    assert rows["shading_cancels"]["nominal"] == "equal to" and rows["shading_cancels"]["nominal_alpha"] == 0.01
    assert rows["eq4_shift"]["nominal"] == "at most" and rows["eq4_shift"]["nominal_alpha"] == 0.05
    assert rows["detection"]["nominal"] == "at most" and rows["detection"]["nominal_alpha"] == 0.05
    assert result["level"] == "direct" and result["seed_step"] == SEED_STEP and result["machine"]["cpu_count"]


def test_where_eq4_does_not_hold_its_failures_are_findings():
    result = face_calibration("mixed", seeds=1, camera_=CAMERA, spp=192, size=24, limits=())
    assert [row["name"] for row in result["checks"]] == ["detection", "eq4_shift"]
    for row in result["checks"]:
        assert row["nominal"] is None and row["consistent"] is None and "finding" in row["undefined"]


def test_one_run_as_the_chart_bench_runs_one():
    out = face_run("face", CAMERA, 2856, 5900, 192, 0, level="sheen", size=24, limits=())
    assert set(out) == {"checks", "bound", "seconds", "spp"} and out["spp"] == 192
    assert list(out["checks"]) == ["dichromatic_plane", "detection", "eq4_shift"]
    assert all(isinstance(v, Verdict) for v in out["checks"].values()) and out["bound"] > 0
    with pytest.raises(SkinrenderError, match="tolerance"):
        face_run("face", CAMERA, 2856, 5900, 12, 0, tolerance=0.01)


@pytest.mark.parametrize("kwargs, match", [({"seeds": 0}, "seeds"), ({"level": "glossy"}, "physics")])
def test_refusals(kwargs, match):
    with pytest.raises(SkinrenderError, match=match):
        face_calibration(**{"seeds": 1, "size": 4, "spp": 12, **kwargs})
