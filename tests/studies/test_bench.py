"""Tests for :mod:`skinrender.bench`: the analytic benchmark's two routes agree (no timing asserted)."""

from __future__ import annotations

from skinrender.studies.bench import bench_analytic
from skinrender.constants import TOLERANCE_RELATIVE_TESTS


def test_bench_analytic_routes_agree():
    result = bench_analytic(repeat=1)
    assert result["responses"] == 1269 * 100
    assert result["max_rel_difference"] < TOLERANCE_RELATIVE_TESTS
    assert {"machine", "elapsed_s", "responses_per_s", "colour_responses_per_s", "speedup"} <= set(result)


def test_bench_search_keys_and_agreement():
    from skinrender.studies.bench import bench_search

    result = bench_search(sensor=9, sample=3, steps=(100.0, 75.0), full_steps=(100.0,), workers=1)
    assert {"naive_ms_per_triplet", "fast_ms_per_triplet", "speedup", "full_search_s", "growth", "machine"} <= set(result)
    assert result["hull_kernel"] in ("quickhull", "qhull")
    assert result["max_rel_difference"] < 1e-9
    assert [g["triplets"] for g in result["growth"]] == [4, 10]
