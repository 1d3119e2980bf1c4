"""Tests for :mod:`skinrender.bench`: the benchmarks' routes agree and their arguments are checked (no timing asserted)."""

from __future__ import annotations

import pytest

from skinrender.cli import main
from skinrender.constants import TOLERANCE_RELATIVE_TESTS
from skinrender.errors import SkinrenderError
from skinrender.studies.benchmarks.bench import bench_analytic, bench_search, bench_sweep


def test_bench_analytic_routes_agree():
    result = bench_analytic(repeat=1)
    assert result["responses"] == 1269 * 100
    assert result["max_rel_difference"] < TOLERANCE_RELATIVE_TESTS
    assert {"machine", "elapsed_s", "responses_per_s", "colour_responses_per_s", "speedup"} <= set(result)


def test_bench_search_keys_and_agreement():
    result = bench_search(sensor=9, sample=3, steps=(100.0, 75.0), full_steps=(100.0,), workers=1,
                          sweep_positions="400:700:100", sweep_slopes=(3.0,))
    assert {"naive_ms_per_triplet", "fast_ms_per_triplet", "speedup", "full_search_s", "growth", "machine"} <= set(result)
    assert result["hull_kernel"] in ("quickhull", "qhull")
    assert result["max_rel_difference"] < 1e-9
    assert [g["triplets"] for g in result["growth"]] == [4, 10]
    assert result["sweep_s_per_setting"] > 0 and result["sweep_s_per_setting_10nm_estimate"] > 0


def test_bench_sweep_one_row_per_setting():
    result = bench_sweep("400:700:100", sensors=[1, 9], workers=1, candidates={"slope": [3.0], "skin": ["skin-model"]})
    assert [row["setting"] for row in result["settings"]] == ["default", "slope=3", "skin=skin-model"]
    assert result["triplets"] == 4 and result["s_per_setting"] > 0


@pytest.mark.parametrize(("call", "flag"), [
    (lambda: bench_analytic(repeat=0), "--repeat"),
    (lambda: bench_search(sample=0), "--sample"),
    (lambda: bench_search(workers=0), "--workers"),
    (lambda: bench_sweep(workers=0), "--workers"),
])
def test_bad_arguments_are_refused_before_timing(call, flag):
    with pytest.raises(SkinrenderError, match=f"^{flag}"):
        call()


def test_command_line_refusal(capsys):
    assert main(["bench", "analytic", "--repeat", "0"]) == 2
    err = capsys.readouterr().err
    assert "--repeat" in err and err.count("\n") == 1


def test_bench_render_elapsed_is_the_whole_run_not_the_curve_sum():
    pytest.importorskip("mitsuba")
    from skinrender.rendering.variants import choose_variant
    from skinrender.studies.benchmarks.bench import bench_render

    result = bench_render(variants=(choose_variant(),), spps=(4,), samplers=("multijitter",), all_pairs=False)
    assert result["curve_s"] == pytest.approx(sum(row["seconds"] for row in result["curve"]))
    assert result["elapsed_s"] > result["curve_s"]  # the warm-up render alone is outside the curve's timings
