"""Verdicts: the outcomes, the equivalence and difference tests and their error rates on simulated data."""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.evaluation.verdict import (EXIT_STATUS, OUTCOMES, Verdict, binomial_interval, combine, critical_z,
                                           difference, equivalence, samples_needed, sidak)


class TestVerdict:
    def test_outcomes_have_exit_statuses(self):
        assert set(EXIT_STATUS) == set(OUTCOMES)
        assert EXIT_STATUS["pass"] == 0 and EXIT_STATUS["fail"] == 1 and EXIT_STATUS["inconclusive"] == 3

    def test_unknown_outcome_refused(self):
        with pytest.raises(SkinrenderError, match="outcome"):
            Verdict("x", "maybe", 0.01, "z")

    def test_document_has_the_verdict(self):
        document = Verdict("x", "inconclusive", 0.05, "TOST", reason="few samples", details={"spp": 4}).document()
        assert document["verdict"] == "inconclusive" and document["passed"] is None and document["spp"] == 4


class TestCombine:
    @pytest.mark.parametrize("outcomes, expected", [
        (["pass", "pass"], "pass"), (["pass", "fail", "inconclusive"], "fail"),
        (["pass", "inconclusive"], "inconclusive"), (["not_applicable", "pass"], "pass"),
        (["not_applicable"], "not_applicable"),
    ])
    def test_worst_wins(self, outcomes, expected):
        assert combine([Verdict(str(i), o, 0.01, "t", reason="r") for i, o in enumerate(outcomes)]).outcome == expected


class TestSidak:
    def test_one_test_is_alpha(self):
        assert sidak(0.05, 1) == pytest.approx(0.05)

    def test_family_rate_is_alpha(self):
        assert 1 - (1 - sidak(0.01, 72)) ** 72 == pytest.approx(0.01)

    @pytest.mark.parametrize("alpha", [0, 1, -0.1, 2, float("nan")])
    def test_bad_alpha_refused(self, alpha):
        with pytest.raises(SkinrenderError, match="alpha"):
            sidak(alpha, 3)

    def test_student_wider_than_normal(self):
        assert critical_z(0.01, 10, dof=11) > critical_z(0.01, 10)


class TestEquivalence:
    def test_pass_fail_inconclusive(self):
        assert equivalence([0.0, 0.01], 0.001, 0.1)[0].outcome == "pass"
        assert equivalence([0.0, 0.5], 0.001, 0.1)[0].outcome == "fail"
        assert equivalence([0.0, 0.09], 0.01, 0.1)[0].outcome == "inconclusive"

    def test_noise_never_passes(self):
        """A correct but very noisy measurement is inconclusive, never a pass."""
        verdict, _ = equivalence(np.zeros(30), 10.0, 0.1)
        assert verdict.outcome == "inconclusive"

    def test_bound_is_the_smallest_passing_tolerance(self, rng):
        error, se = rng.normal(0, 0.01, 20), np.full(20, 0.01)
        verdict, _ = equivalence(error, se, 1.0)
        assert equivalence(error, se, verdict.bound * 1.001)[0].outcome == "pass"
        assert equivalence(error, se, verdict.bound * 0.999)[0].outcome != "pass"

    def test_relative_bound(self):
        verdict, rows = equivalence([1.0], [0.0], 5.0, scale=[100.0])
        assert verdict.bound == pytest.approx(0.01) and rows["upper"][0] == pytest.approx(1.0)

    def test_false_pass_rate_at_the_tolerance_is_at_most_alpha(self, rng):
        """Errors exactly at the tolerance (the null of equivalence): a pass in at most α of draws."""
        trials, values, alpha = 4000, 5, 0.05
        truth = np.full(values, 0.1)
        passes = sum(equivalence(truth + rng.normal(0, 0.02, values), 0.02, 0.1, alpha)[0].outcome == "pass"
                     for _ in range(trials))
        assert passes / trials <= binomial_interval(int(alpha * trials), trials)[1]

    def test_bad_inputs_refused(self):
        with pytest.raises(SkinrenderError, match="tolerances"):
            equivalence([0.0], [0.1], 0.0)
        with pytest.raises(SkinrenderError, match="finite"):
            equivalence([np.nan], [0.1], 0.1)


class TestDifference:
    def test_false_alarm_rate_is_alpha(self, rng):
        """Under the null, the family-wise rate of a Šidák z test is α (binomial 99.9 % interval)."""
        trials, values, alpha = 4000, 24, 0.05
        failures = sum(difference(rng.normal(0, 1, values), 1.0, alpha).outcome == "fail" for _ in range(trials))
        lo, hi = binomial_interval(failures, trials, 0.999)
        assert lo <= alpha <= hi

    def test_exact_zero_passes_and_exact_deviation_fails(self):
        assert difference([0.0], [0.0]).outcome == "pass"
        assert difference([1e-9], [0.0]).outcome == "fail"

    def test_per_value_dof_false_alarm_rate_is_alpha(self, rng):
        """Each value a Student t of its own degrees of freedom (3 to normal): the rate is α; the smallest dof
        for all (the conservative alternative) would fall far below it."""
        trials, alpha = 4000, 0.05
        dof = np.array([3.0, 5.0, 10.0, 30.0, np.inf] * 4)
        draws = [rng.standard_t(np.where(np.isinf(dof), 1e9, dof)) for _ in range(trials)]
        failures = sum(difference(t, 1.0, alpha, dof=dof).outcome == "fail" for t in draws)
        lo, hi = binomial_interval(failures, trials, 0.999)
        assert lo <= alpha <= hi
        conservative = sum(difference(t, 1.0, alpha, dof=3.0).outcome == "fail" for t in draws)
        assert conservative < 0.5 * failures

    def test_per_value_dof_reports_the_worst_against_its_own_critical_value(self):
        verdict = difference([4.0, 3.5], [1.0, 1.0], dof=[3.0, np.inf])
        assert verdict.outcome == "fail" and verdict.details["worst"] == 1 and verdict.statistic == 3.5
        with pytest.raises(SkinrenderError, match="degrees of freedom"):
            difference([1.0], [1.0], dof=[0.0])


class TestSamplesNeeded:
    def test_scales_as_inverse_square(self):
        assert samples_needed(100, [0.0], [0.04], 0.1) == pytest.approx(4 * samples_needed(100, [0.0], [0.02], 0.1),
                                                                        rel=0.01)

    def test_passes_at_the_estimate(self):
        n0, se0 = 16, np.array([0.05, 0.08])
        n = samples_needed(n0, [0.0, 0.0], se0, 0.1)
        assert equivalence([0.0, 0.0], se0 * np.sqrt(n0 / n), 0.1)[0].outcome == "pass"


class TestBinomialInterval:
    def test_contains_the_rate(self):
        lo, hi = binomial_interval(10, 100)
        assert lo < 0.1 < hi

    def test_edges(self):
        assert binomial_interval(0, 40)[0] == 0.0 and binomial_interval(40, 40)[1] == 1.0

    def test_bad_counts_refused(self):
        with pytest.raises(SkinrenderError):
            binomial_interval(5, 3)
