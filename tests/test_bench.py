"""Tests for :mod:`skinrender.bench`: the analytic benchmark's two routes agree (no timing asserted)."""

from __future__ import annotations

from skinrender.bench import bench_analytic
from skinrender.constants import TOLERANCE_RELATIVE_TESTS


def test_bench_analytic_routes_agree():
    result = bench_analytic(repeat=1)
    assert result["responses"] == 1269 * 100
    assert result["max_rel_difference"] < TOLERANCE_RELATIVE_TESTS
    assert {"machine", "elapsed_s", "responses_per_s", "colour_responses_per_s", "speedup"} <= set(result)
