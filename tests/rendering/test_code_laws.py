"""
Tests for :mod:`skinrender.rendering.code_laws`: the exact p-values of a patch's pixel mean and sample variance on
the code lattice match a brute-force enumeration, are calibrated under their law, and tell a patch of one likely
code from one of an unlikely code.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from skinrender.rendering.code_laws import exact_p_values


def _brute_force_p_values(pmf, codes):
    """Every outcome of n pixels enumerated: the two-sided p-values of Σ d and of the sample variance."""
    import itertools

    n, support = len(codes), np.arange(len(pmf))
    sums, variances, weights = [], [], []
    for outcome in itertools.product(support, repeat=n):
        draws = np.array(outcome, dtype=float)
        sums.append(draws.sum())
        variances.append(draws.var(ddof=1))
        weights.append(np.prod(pmf[list(outcome)]))
    sums, variances, weights = map(np.array, (sums, variances, weights))
    seen_sum, seen_var = codes.sum(), codes.var(ddof=1)
    tails = lambda value, seen: min(1.0, 2 * min(weights[value <= seen + 1e-12].sum(),  # noqa: E731
                                                 weights[value >= seen - 1e-12].sum()))
    return tails(sums, seen_sum), tails(variances, seen_var)


@pytest.mark.parametrize("codes", [[1, 1, 1, 1], [0, 1, 1, 2], [2, 2, 2, 1], [0, 0, 0, 0], [0, 2, 2, 0]])
def test_exact_p_values_match_enumeration(codes):
    pmf = np.array([0.05, 0.8, 0.15])
    exact = exact_p_values(pmf, 0.0, np.array(codes, dtype=float))
    np.testing.assert_allclose(exact, _brute_force_p_values(pmf, np.array(codes)), rtol=1e-9, atol=1e-12)


def test_a_patch_of_one_likely_code_is_consistent_and_of_an_unlikely_code_is_not():
    """σ = 0.12 DN about 9.0 DN: P(9) = 0.9999; 144 pixels all reading 9 happen with probability 0.98."""
    pmf = np.array([3e-5, 1 - 6e-5, 3e-5])  # codes 8, 9, 10
    p_mean, p_variance = exact_p_values(pmf, 8.0, np.full(144, 9.0))
    assert p_mean == 1.0 and p_variance == 1.0
    p_mean, p_variance = exact_p_values(pmf, 8.0, np.full(144, 10.0))  # every pixel on a 3e-5 code: (3e-5)^144
    assert p_mean < 1e-12 and p_variance == 1.0  # the mean rejects (FFT round-off ~1e-14); one code has no spread


def test_exact_p_values_are_calibrated_under_the_model():
    """Patches drawn from the law itself: rejections at level 0.05 happen at most 5 % of the time (+3 σ)."""
    pmf, rng = np.array([0.02, 0.9, 0.08]), np.random.default_rng(11)
    draws = rng.choice(3, size=(1000, 60), p=pmf).astype(float)
    p_values = np.array([exact_p_values(pmf, 0.0, codes) for codes in draws])
    bound = 0.05 + 3 * math.sqrt(0.05 * 0.95 / 1000)
    assert np.all(np.mean(p_values < 0.05, axis=0) <= bound), np.mean(p_values < 0.05, axis=0)
