"""
Tests for :mod:`skinrender.model.noise`: the analytic DN statistics against
seeded Monte Carlo frames (dark, mid-range, filling and full wells, ADC
clipping), the dark frame of a photon-transfer measurement, NCC noise
propagation, and every bad input.

Statistical checks are z-tests against the sampling error of the Monte Carlo
estimate, with a family-wise false-alarm rate fixed below (Šidák correction
over the file's comparisons); every frame is drawn from a fixed seed, so a
failure is reproducible.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.stats import multivariate_normal, norm

from skinrender.errors import SkinrenderError
from skinrender.model.imager import imager
from skinrender.model.noise import (
    _bivariate_normal_cdf,
    ncc_covariance,
    random_generator,
    signal_dn,
    simulate_dn,
    statistics_dn,
)

from .test_imager import make_imager

N_SAMPLES = 200_000
"""Monte Carlo pixels per condition: the standard error of a mean is σ/447."""

ALPHA_FAMILY = 1e-3
"""Allowed probability that any statistical comparison in this file fails by chance."""

N_COMPARISONS = 60
"""Upper bound on the number of z-tests in this file (28 analytic-vs-MC, 6 noise, 9 NCC, 6 dark, …)."""

Z_TOLERANCE = float(norm.isf((1.0 - (1.0 - ALPHA_FAMILY) ** (1.0 / N_COMPARISONS)) / 2.0))
"""Two-sided z bound per comparison, Šidák-corrected: about 4.3."""

TOLERANCE_ANALYTIC = 1e-9
"""Absolute tolerance, DN or DN², for analytic identities far from the clipping bounds, where the
neglected normal tails are below 1e-15."""

TOLERANCE_SHEPPARD = 1e-6
"""Absolute tolerance, DN², on the quantisation variance 1/12 DN² of a normal of σ ≥ 1 DN rounded to
codes: Sheppard's correction is off by terms of order exp(−2π²σ²) < 3e-9."""


def z_mean(samples: np.ndarray, mean: float, variance: float) -> float:
    """z of the sample mean against an analytic mean and variance."""
    if variance == 0:
        return 0.0 if np.all(samples == mean) else math.inf
    return float((samples.mean() - mean) / math.sqrt(variance / samples.size))


def z_variance(samples: np.ndarray, variance: float) -> float:
    """z of the sample variance, its standard error sqrt((m4 − s⁴)/N) from the samples.

    Below 1 DN² the spread of codes is mostly unit jumps off one code, rare enough that a sample
    may hold none; m4 is then floored at the analytic variance, the m4 of unit jumps (d⁴ = d²).
    """
    s2 = samples.var(ddof=1)
    m4 = np.mean((samples - samples.mean()) ** 4)
    m4 = max(m4, variance) if variance < 1 else m4
    error = math.sqrt(max(m4 - s2**2, 0.0) / samples.size)
    if error == 0:
        return 0.0 if s2 == variance else math.inf
    return float((s2 - variance) / error)


class TestStatisticsDn:
    def test01_linear_far_from_bounds(self):
        """Mean K μ + b, variance K² (μ + σ_r²) + 1/12 (shot, read in quadrature, quantisation)."""
        im = make_imager()
        mu = np.array([2000.0, 9000.0, 15000.0])
        mean, var = statistics_dn(im, mu)
        np.testing.assert_allclose(mean, 0.2 * mu + 10.0, atol=TOLERANCE_ANALYTIC)
        np.testing.assert_allclose(var, 0.04 * (mu + 25.0) + 1 / 12, atol=TOLERANCE_ANALYTIC)

    def test02_read_noise_in_quadrature_and_quantisation(self):
        mu = 5000.0
        v0 = statistics_dn(make_imager(read_noise_e=0.0), mu)[1]
        v30 = statistics_dn(make_imager(read_noise_e=30.0), mu)[1]
        np.testing.assert_allclose(v30 - v0, 0.04 * 30.0**2, atol=TOLERANCE_ANALYTIC)
        np.testing.assert_allclose(v0 - 0.04 * mu, 1 / 12, atol=TOLERANCE_ANALYTIC)

    def test03_saturation(self):
        """A full well reads K μ_sat + b; the read noise after the well stays unless the ADC clips."""
        im = make_imager(read_noise_e=0.0)
        mean, var = statistics_dn(im, [1e5, 1e9, 1e30])
        np.testing.assert_array_equal(mean, 20000.0 * 0.2 + 10.0)
        np.testing.assert_array_equal(var, 0.0)
        mean, var = statistics_dn(make_imager(), [1e5, 1e9, 1e30])  # σ_r = 5 e⁻ → 1 DN on the full well
        np.testing.assert_allclose(mean, 20000.0 * 0.2 + 10.0, atol=TOLERANCE_ANALYTIC)
        np.testing.assert_allclose(var, 0.04 * 25.0 + 1 / 12, atol=TOLERANCE_SHEPPARD)
        adc = make_imager(gain_dn_per_e=0.25)  # 0.25 · 20000 + 10 > 4095: the ADC clips first
        assert signal_dn(adc, 1e6) == 4095.0
        assert statistics_dn(adc, 1e6)[1] == 0.0
        # the draft clipped the charge at 0 e⁻ after the read noise, lifting the dark level above 10 DN;
        # the read noise now rides on the black level
        np.testing.assert_allclose(signal_dn(make_imager(), 0.0), 10.0, atol=TOLERANCE_ANALYTIC)

    def test04_exact_and_closed_forms_meet(self):
        """Just below and above σ = 4 DN the two evaluations agree (remainder < 1e-5 DN)."""
        im = make_imager(read_noise_e=0.0, full_well_e=1e6, gain_dn_per_e=0.01, bits=16)
        mu = (4.0 / 0.01) ** 2 * np.array([1 - 1e-9, 1 + 1e-9])
        mean, var = statistics_dn(im, mu)
        np.testing.assert_allclose(mean[0], mean[1], atol=1e-5)
        np.testing.assert_allclose(var[0], var[1], atol=1e-5)

    def test05_n_dimensional(self):
        mu = np.linspace(0, 3e4, 24).reshape(2, 4, 3)
        mean, var = statistics_dn("sony-imx174", mu)
        assert mean.shape == var.shape == (2, 4, 3)
        np.testing.assert_allclose(mean[1, 2], statistics_dn("sony-imx174", mu[1, 2])[0])

    @pytest.mark.parametrize("preset", ["sony-imx174", "sony-icx418"])
    def test06_filling_well_meets_the_normal_cases(self, preset):
        """At μ_sat ∓ 8 √μ the well-filling sum and the two normal cases agree (tails < 1e-15)."""
        im = imager(preset)
        fw = im.full_well_e
        for root in (math.sqrt(fw) * (1 - 1e-3), math.sqrt(fw) * (1 + 1e-3)):  # μ = fw ∓ 8 √μ on either side
            for sign in (-1.0, 1.0):
                mu = fw + sign * 8.0 * root
                mu = np.array([mu * (1 - 1e-9), mu * (1 + 1e-9)])
                mean, var = statistics_dn(im, mu)
                np.testing.assert_allclose(mean[0], mean[1], atol=1e-6)
                np.testing.assert_allclose(var[0], var[1], atol=1e-5)

    def test07_bivariate_normal_cdf(self):
        """The Owen's T formula against scipy's integration, signs and zeros included."""
        h = np.array([-1.5, 0.0, 0.7, 2.0, -0.3, 1.0])
        k = np.array([0.4, -1.2, 0.0, 2.5, -0.8, -1e-3])
        rho = np.array([0.5, 0.9, 0.99, 0.2, 0.999, 0.7])
        got = _bivariate_normal_cdf(h, k, rho, np.sqrt(1 - rho**2))
        expected = [multivariate_normal([0, 0], [[1, r], [r, 1]]).cdf([a, b]) for a, b, r in zip(h, k, rho)]
        np.testing.assert_allclose(got, expected, atol=1e-7)


class TestSimulateDn:
    def test01_shot_noise_variance_equals_mean(self):
        """K = 1 DN/e⁻, no read noise: DN − b is the Poisson count, variance = mean (e⁻).

        (N − 1) s²/μ is close to χ²(N − 1); its z uses Var(s²) = μ²(2/(N − 1) + 1/(μ N)).
        """
        im = make_imager(read_noise_e=0.0, gain_dn_per_e=1.0, full_well_e=1e6, bits=24, black_level_dn=100.0)
        for mu in (20.0, 1000.0):
            counts = simulate_dn(im, np.full(N_SAMPLES, mu), 20240601) - 100.0
            assert abs(z_mean(counts, mu, mu)) < Z_TOLERANCE
            z = (counts.var(ddof=1) - mu) / (mu * math.sqrt(2 / (N_SAMPLES - 1) + 1 / (mu * N_SAMPLES)))
            assert abs(z) < Z_TOLERANCE

    def test02_read_noise_and_quantisation(self):
        im = make_imager(read_noise_e=40.0)
        frame = simulate_dn(im, np.full(N_SAMPLES, 5000.0), 99)
        assert abs(z_mean(frame, 1010.0, 0.04 * (5000.0 + 1600.0) + 1 / 12)) < Z_TOLERANCE
        assert abs(z_variance(frame, 0.04 * (5000.0 + 1600.0) + 1 / 12)) < Z_TOLERANCE

    @pytest.mark.parametrize("preset", ["sony-imx174", "sony-icx418"])
    @pytest.mark.parametrize("level", ["dark", "low", "mid", "near", "full", "beyond", "over"])
    def test03_analytic_against_monte_carlo(self, preset, level):
        """Mean and variance at dark, low, mid, just below, at, just above and far above saturation."""
        im = imager(preset)
        fw = im.full_well_e
        mu = {"dark": 0.0, "low": 50.0, "mid": 0.4 * fw, "near": fw - 2 * math.sqrt(fw),
              "full": fw, "beyond": fw + 3 * math.sqrt(fw), "over": 1.5 * fw}[level]
        mean, var = statistics_dn(im, mu)
        frame = simulate_dn(im, np.full(N_SAMPLES, mu), 4242)
        assert abs(z_mean(frame, float(mean), float(var))) < Z_TOLERANCE
        assert abs(z_variance(frame, float(var))) < Z_TOLERANCE

    def test04_saturated_pixel(self):
        """Without read noise a full well sits on one code; the ADC's last code holds whatever it clips."""
        frame = simulate_dn(make_imager(read_noise_e=0.0), np.full(1000, 3 * 20000.0), 5)
        np.testing.assert_array_equal(frame, 20000.0 * 0.2 + 10.0)
        frame = simulate_dn(make_imager(gain_dn_per_e=0.25), np.full(1000, 3 * 20000.0), 5)
        np.testing.assert_array_equal(frame, 4095.0)
        frame = simulate_dn(make_imager(), np.full(N_SAMPLES, 3 * 20000.0), 5)  # read noise after the well
        assert abs(z_mean(frame, 4010.0, 0.04 * 25.0 + 1 / 12)) < Z_TOLERANCE
        assert abs(z_variance(frame, 0.04 * 25.0 + 1 / 12)) < Z_TOLERANCE

    def test05_seeded_and_shaped(self):
        im = make_imager()
        mu = np.full((2, 5, 3), 800.0)
        first, second = simulate_dn(im, mu, 7), simulate_dn(im, mu, 7)
        np.testing.assert_array_equal(first, second)
        assert first.shape == (2, 5, 3)
        np.testing.assert_array_equal(simulate_dn(im, mu, np.random.default_rng(7)), first)
        assert not np.array_equal(simulate_dn(im, mu, 8), first)
        assert np.all(first == np.rint(first))
        assert random_generator(7).random() == np.random.default_rng(7).random()


class TestDarkFrame:
    """The dark frame of a photon-transfer measurement: read noise on the black level, unclipped."""

    def test01_dark_std_is_read_noise_and_quantisation(self):
        """Black level 20 DN = 10 σ above 0 DN, σ = K σ_r = 0.2 · 10 = 2 DN: std² = K² σ_r² + 1/12 DN².

        The draft clipped the charge at 0 e⁻ after the read noise, which read ~0.58 σ_r here.
        """
        im = make_imager(read_noise_e=10.0, black_level_dn=20.0)
        expected = 0.04 * 100.0 + 1 / 12
        mean, var = statistics_dn(im, 0.0)
        np.testing.assert_allclose([mean, var], [20.0, expected], atol=TOLERANCE_SHEPPARD)
        frame = simulate_dn(im, np.zeros(N_SAMPLES), 1288)
        assert abs(z_mean(frame, 20.0, expected)) < Z_TOLERANCE
        assert abs(z_variance(frame, expected)) < Z_TOLERANCE
        assert frame.std() > 0.95 * 2.0  # not the ~0.58 σ_r of a frame clipped at 0 e⁻

    def test02_presets_dark_frames(self):
        """Each preset's dark frame: mean the black level, variance K² σ_r² + quantisation (analytic = MC)."""
        for number, row in enumerate(("sony-imx174", "sony-icx418")):
            im = imager(row)
            mean, var = statistics_dn(im, 0.0)
            np.testing.assert_allclose(mean, im.black_level_dn, atol=TOLERANCE_ANALYTIC)
            frame = simulate_dn(im, np.zeros(N_SAMPLES), 100 + number)
            assert abs(z_variance(frame, float(var))) < Z_TOLERANCE

    def test03_black_level_zero_clips_at_the_adc(self):
        """With b = 0 DN the ADC clips half the dark frame at 0 DN: the analytic censoring still holds."""
        im = make_imager(read_noise_e=10.0, black_level_dn=0.0)
        mean, var = statistics_dn(im, 0.0)
        assert 0.7 < mean < 0.9  # E[max(round(N(0, 2²)), 0)] ≈ σ/√(2π) = 0.80 DN
        frame = simulate_dn(im, np.zeros(N_SAMPLES), 77)
        assert abs(z_mean(frame, float(mean), float(var))) < Z_TOLERANCE
        assert abs(z_variance(frame, float(var))) < Z_TOLERANCE


class TestNccCovariance:
    def test01_hand_values(self):
        """Equal means x, variance v, gains 1: c = 1/3, J = (I − 1/3)/(3x), Σ_c = v (I − 1/3)/(9x²)."""
        cov = ncc_covariance([100.0] * 3, [100.0] * 3, [1.0] * 3)
        expected = 100.0 * (np.eye(3) - 1 / 3) / (9 * 100.0**2)
        np.testing.assert_allclose(cov, expected, rtol=1e-12)
        np.testing.assert_allclose(cov.sum(axis=-1), 0.0, atol=1e-18)

    def test02_covariance_input_and_shapes(self):
        mean = np.array([[200.0, 300.0, 100.0], [50.0, 60.0, 70.0]])
        var = np.array([[20.0, 30.0, 10.0], [5.0, 6.0, 7.0]])
        gains = np.array([1.5, 1.0, 2.5])
        from_var = ncc_covariance(mean, var, gains)
        from_cov = ncc_covariance(mean, var[..., None] * np.eye(3), gains)
        assert from_var.shape == (2, 3, 3)
        np.testing.assert_allclose(from_var, from_cov, rtol=1e-14)
        np.testing.assert_allclose(from_var[1], ncc_covariance(mean[1], var[1], gains), rtol=1e-14)

    def test03_against_monte_carlo(self):
        """NCC of white-balanced simulated pixels vs the delta method; SE² = (V_i V_j + C_ij²)/N."""
        im = imager("sony-imx174")
        mu = np.array([6000.0, 12000.0, 3000.0])
        gains = np.array([1.2, 0.6, 2.0])
        mean, var = statistics_dn(im, mu)
        predicted = ncc_covariance(mean - im.black_level_dn, var, gains)
        frame = simulate_dn(im, np.broadcast_to(mu, (N_SAMPLES, 3)), 31337) - im.black_level_dn
        balanced = frame * gains
        ncc = balanced / balanced.sum(axis=-1, keepdims=True)
        sample = np.cov(ncc, rowvar=False)
        diag = np.diag(predicted)
        error = np.sqrt((np.outer(diag, diag) + predicted**2) / N_SAMPLES)
        assert np.all(np.abs(sample - predicted) < Z_TOLERANCE * error)


class TestBadInput:
    @pytest.mark.parametrize("seed", [-1, 2**32, 1.5, True, None, "7", np.float64(3.0)])
    def test01_bad_seed(self, seed):
        with pytest.raises(SkinrenderError, match="rng_or_seed"):
            simulate_dn(make_imager(), [100.0], seed)
        with pytest.raises(SkinrenderError, match="--seed"):
            random_generator(seed, "--seed")

    def test02_bad_arrays(self):
        im = make_imager()
        cases = [
            (lambda: statistics_dn(im, [-1.0]), "electrons_mean"),
            (lambda: simulate_dn(im, [math.nan], 1), "electrons_mean"),
            (lambda: ncc_covariance([1.0, 2.0, 3.0], [1.0, 1.0, 1.0], [1.0, 0.0, 1.0]), "gains"),
            (lambda: ncc_covariance([1.0, -2.0, 0.5], [1.0, 1.0, 1.0], [1.0, 1.0, 1.0]), "mean"),
            (lambda: ncc_covariance([1.0, 2.0, 3.0], np.ones((2, 2)), [1.0, 1.0, 1.0]), "cov_or_var"),
            (lambda: ncc_covariance([1.0, 2.0, 3.0], [1.0, -1.0, 1.0], [1.0, 1.0, 1.0]), "cov_or_var"),
        ]
        for call, name in cases:
            with pytest.raises(SkinrenderError, match=name):
                call()


def test_simulate_dn_clipped_is_simulate_dn_with_its_clipping():
    from skinrender.model.noise import clipping_counts, simulate_dn_clipped

    im = imager("sony-icx418")  # well 40 000 e⁻ → 248 DN, under the 8-bit maximum 255
    electrons = np.array([[1e3, 5e4, 1e6]] * 1000)
    dn, full, clipped = simulate_dn_clipped(im, electrons, 5)
    assert np.array_equal(dn, simulate_dn(im, electrons, 5))
    assert full[:, 1:].all() and not full[:, 0].any() and not clipped.any()
    counts = clipping_counts(full, clipped)
    assert counts["well_full"] == [0, 1000, 1000] and counts["well_full_share"] == [0.0, 1.0, 1.0]
    high = dataclasses.replace(im, black_level_dn=250.0)  # the well now lies past the ADC range
    assert simulate_dn_clipped(high, electrons, 5)[2][:, 1:].all()


@pytest.mark.parametrize("electrons", [0.0, 37.0, 1e3, 2e4])
def test_code_probabilities_carry_statistics_dn_moments(electrons):
    from skinrender.model.noise import code_probabilities

    im = imager("sony-icx418")
    first, pmf = code_probabilities(im, [electrons])
    codes = first[0] + np.arange(pmf.shape[1])
    mean, variance = statistics_dn(im, electrons)
    assert pmf.sum() == pytest.approx(1.0, abs=1e-12)
    assert np.sum(pmf[0] * codes) == pytest.approx(mean, abs=1e-9)
    assert np.sum(pmf[0] * (codes - mean) ** 2) == pytest.approx(variance, abs=1e-9)


def test_code_probabilities_none_where_noise_is_wide():
    from skinrender.model.noise import code_probabilities

    first, pmf = code_probabilities("sony-imx174", [1e4])  # σ ≈ 12 DN: the closed form, no code law
    assert np.isnan(first[0]) and np.isnan(pmf).all()
