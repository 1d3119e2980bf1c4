"""
Tests for :mod:`skinrender.model.imager`: photon counts by hand, photometry, the analytic DN
statistics against seeded Monte Carlo frames, NCC noise propagation, presets and every bad input.

Statistical checks are z-tests against the sampling error of the Monte Carlo estimate, with a
family-wise false-alarm rate fixed below (Šidák correction over the file's comparisons); every
frame is drawn from a fixed seed, so a failure is reproducible.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.stats import norm

from skinrender.constants import CONSTANT_C, CONSTANT_H
from skinrender.errors import SkinrenderError
from skinrender.model.imager import (
    CONSTANT_K_M,
    ROOT_RESOURCES_IMAGERS,
    Imager,
    auto_exposure,
    electrons_mean,
    illuminance_lux,
    imager,
    irradiance_planck,
    list_imagers,
    ncc_covariance,
    radiance_lambertian,
    signal_dn,
    simulate_dn,
    statistics_dn,
)
from skinrender.spectra import WavelengthGrid

N_SAMPLES = 200_000
"""Monte Carlo pixels per condition: the standard error of a mean is σ/447."""

ALPHA_FAMILY = 1e-3
"""Allowed probability that any statistical comparison in this file fails by chance."""

N_COMPARISONS = 60
"""Upper bound on the number of z-tests in this file (24 analytic-vs-MC, 6 noise, 9 NCC, …)."""

Z_TOLERANCE = float(norm.isf((1.0 - (1.0 - ALPHA_FAMILY) ** (1.0 / N_COMPARISONS)) / 2.0))
"""Two-sided z bound per comparison, Šidák-corrected: about 4.3."""

TOLERANCE_RELATIVE_HAND = 1e-12
"""Relative tolerance for closed-form arithmetic done two ways in float64 (a few roundings)."""

TOLERANCE_ANALYTIC = 1e-9
"""Absolute tolerance, DN or DN², for analytic identities far from the clipping bounds, where the
neglected normal tails are below 1e-15."""

GRID_555 = WavelengthGrid(555.0, 555.0, 1.0)
GRID = WavelengthGrid(400.0, 700.0, 10.0)


def make_imager(**changes) -> Imager:
    """A test imager whose saturated code K·μ_sat + b = 0.2 · 20000 + 10 = 4010 is an exact integer."""
    values = {
        "name": "test", "source": "tests", "pixel_um": 5.0, "f_number": 2.8, "transmittance": 0.9,
        "qe_peak": 0.5, "full_well_e": 20000.0, "read_noise_e": 5.0, "dark_current_e_per_s": 0.0,
        "gain_dn_per_e": 0.2, "bits": 12, "black_level_dn": 10.0,
    }
    return Imager(**(values | changes))


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


# --- electrons ------------------------------------------------------------------------------


class TestElectronsMean:
    def test01_hand_computation(self):
        """555 nm, 1 nm band, L = 0.01 W·m⁻²·sr⁻¹·nm⁻¹, f/2.8, τ 0.9, 5 µm, QE 0.5, 10 ms.

        E_s = π τ L / (4 N²); photons = E_s A λ / (h c) · Δλ · t; electrons = QE · photons.
        """
        im = make_imager(dark_current_e_per_s=0.0)
        sensor_irradiance = math.pi * 0.9 * 0.01 / (4 * 2.8**2)  # W·m⁻²·nm⁻¹
        photons = sensor_irradiance * (5e-6) ** 2 / (CONSTANT_H * CONSTANT_C / 555e-9) * 1.0 * 0.01
        expected = 0.5 * photons
        got = electrons_mean(im, np.ones((3, 1)), [0.01], 0.01, GRID_555)
        np.testing.assert_allclose(got, [expected] * 3, rtol=TOLERANCE_RELATIVE_HAND, atol=0)
        np.testing.assert_allclose(expected, 314.87819838729547, rtol=TOLERANCE_RELATIVE_HAND)

    def test02_dark_current_and_linearity(self):
        im = make_imager(dark_current_e_per_s=50.0)
        sens = np.vstack([np.linspace(0.1, 1, GRID.size), np.ones(GRID.size), np.linspace(1, 0.1, GRID.size)])
        dark = electrons_mean(im, sens, np.zeros(GRID.size), 0.2, GRID)
        np.testing.assert_allclose(dark, [10.0, 10.0, 10.0], rtol=TOLERANCE_RELATIVE_HAND)
        one = electrons_mean(im, sens, np.full(GRID.size, 1e-3), 0.1, GRID)
        two = electrons_mean(im, 7.0 * sens, np.full(GRID.size, 2e-3), 0.1, GRID)  # any scale
        np.testing.assert_allclose(two - 5.0, 2 * (one - 5.0), rtol=TOLERANCE_RELATIVE_HAND)
        half_n = electrons_mean(make_imager(f_number=1.4), sens, np.full(GRID.size, 1e-3), 0.1, GRID)
        np.testing.assert_allclose(half_n, 4 * (one - 5.0), rtol=TOLERANCE_RELATIVE_HAND)  # no dark there

    def test03_flat_spectrum_sum(self):
        """Per channel: t Σ QE_k(λ) π τ L A λ / (4 N² h c) Δλ, written out."""
        im = make_imager()
        sens = np.vstack([np.linspace(0.1, 1, GRID.size), np.ones(GRID.size), np.linspace(1, 0.1, GRID.size)])
        lam = GRID.wavelengths * 1e-9
        photons = math.pi * 0.9 * 2e-3 / (4 * 2.8**2) * (5e-6) ** 2 * lam / (CONSTANT_H * CONSTANT_C)
        expected = [0.5 * np.sum(row / row.max() * photons) * 10.0 * 0.05 for row in sens]
        got = electrons_mean(im, sens, np.full(GRID.size, 2e-3), 0.05, GRID)
        np.testing.assert_allclose(got, expected, rtol=TOLERANCE_RELATIVE_HAND)

    def test04_n_dimensional(self):
        im = make_imager()
        radiance = np.random.default_rng(1).uniform(0, 1e-3, (2, 4, GRID.size))
        out = electrons_mean(im, np.ones((3, GRID.size)), radiance, np.array([[0.01], [0.02]]), GRID)
        assert out.shape == (2, 4, 3)
        single = electrons_mean(im, np.ones((3, GRID.size)), radiance[1, 2], 0.02, GRID)
        np.testing.assert_allclose(out[1, 2], single, rtol=TOLERANCE_RELATIVE_HAND)


class TestAutoExposure:
    def test01_brightest_channel_at_fraction(self):
        im = make_imager(dark_current_e_per_s=20.0)
        sens = np.vstack([np.ones(GRID.size), 2 * np.ones(GRID.size), np.linspace(0, 1, GRID.size)])
        white = np.full(GRID.size, 1e-3)
        rate = electrons_mean(im, sens, white, 1.0, GRID)
        t = auto_exposure(im, rate, fraction=0.7)
        assert isinstance(t, float)
        np.testing.assert_allclose(electrons_mean(im, sens, white, t, GRID).max(), 0.7 * 20000.0, rtol=1e-12)
        np.testing.assert_allclose(auto_exposure(im, [[100, 200, 50], [10, 5, 1]]), [70.0, 1400.0])


# --- photometry -----------------------------------------------------------------------------


class TestPhotometry:
    def test01_flat_spectrum(self):
        from colour.colorimetry import SDS_LEFS_PHOTOPIC

        grid = WavelengthGrid(400, 700, 1)
        v = SDS_LEFS_PHOTOPIC["CIE 1924 Photopic Standard Observer"][grid.wavelengths]
        expected = CONSTANT_K_M * np.sum(v) * 1.0
        np.testing.assert_allclose(illuminance_lux(np.ones(grid.size), grid), expected, rtol=1e-12)

    def test02_planck_at_500_lux(self):
        grid = WavelengthGrid(380, 780, 5)
        spd = irradiance_planck([2000.0, 2856.0, 6500.0], 500.0, grid)
        assert spd.shape == (3, grid.size)
        np.testing.assert_allclose(illuminance_lux(spd, grid), 500.0, rtol=1e-12)
        assert irradiance_planck(3000.0, 0.0, "400:700:10").max() == 0.0

    def test03_lambertian(self):
        e = irradiance_planck(2856.0, 1000.0, GRID)
        np.testing.assert_allclose(radiance_lambertian(0.5, e), 0.5 * e / math.pi, rtol=1e-15)

    def test04_grid_without_photopic_weight(self):
        with pytest.raises(SkinrenderError, match="photopic"):
            irradiance_planck(3000.0, 500.0, WavelengthGrid(900, 1000, 10))


# --- analytic statistics --------------------------------------------------------------------


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
        im = make_imager()
        mean, var = statistics_dn(im, [1e5, 1e9, 1e30])
        np.testing.assert_array_equal(mean, 20000.0 * 0.2 + 10.0)
        np.testing.assert_array_equal(var, 0.0)
        adc = make_imager(gain_dn_per_e=0.25)  # 0.25 · 20000 + 10 > 4095: the ADC clips first
        assert signal_dn(adc, 1e6) == 4095.0
        assert signal_dn(im, 0.0) > 10.0  # the read noise clipped at 0 e⁻ lifts the dark level

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


# --- Monte Carlo ----------------------------------------------------------------------------


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
    @pytest.mark.parametrize("level", ["dark", "low", "mid", "near", "full", "over"])
    def test03_analytic_against_monte_carlo(self, preset, level):
        """Mean and variance at dark, low, mid, just below, at and above saturation."""
        im = imager(preset)
        fw = im.full_well_e
        mu = {"dark": 0.0, "low": 50.0, "mid": 0.4 * fw, "near": fw - 2 * math.sqrt(fw),
              "full": fw, "over": 1.5 * fw}[level]
        mean, var = statistics_dn(im, mu)
        frame = simulate_dn(im, np.full(N_SAMPLES, mu), 4242)
        assert abs(z_mean(frame, float(mean), float(var))) < Z_TOLERANCE
        assert abs(z_variance(frame, float(var))) < Z_TOLERANCE

    def test04_saturated_pixel(self):
        im = make_imager()
        frame = simulate_dn(im, np.full(1000, 3 * 20000.0), 5)
        np.testing.assert_array_equal(frame, 20000.0 * 0.2 + 10.0)

    def test05_seeded_and_shaped(self):
        im = make_imager()
        mu = np.full((2, 5, 3), 800.0)
        first, second = simulate_dn(im, mu, 7), simulate_dn(im, mu, 7)
        np.testing.assert_array_equal(first, second)
        assert first.shape == (2, 5, 3)
        np.testing.assert_array_equal(simulate_dn(im, mu, np.random.default_rng(7)), first)
        assert not np.array_equal(simulate_dn(im, mu, 8), first)
        assert np.all(first == np.rint(first))


# --- NCC ------------------------------------------------------------------------------------


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


# --- presets and bad input ------------------------------------------------------------------


class TestPresets:
    def test01_list_and_load(self):
        rows = list_imagers()
        assert {row["name"] for row in rows} >= {"sony-imx174", "sony-icx418"}
        for row in rows:
            assert set(row) == {"name", "source", "pixel_um", "full_well_e", "read_noise_e", "gain_dn_per_e",
                                "bits"}
            item = imager(row["name"].upper())
            assert item.source.strip() and item.name == row["name"]
            assert item.gain_dn_per_e * item.full_well_e + item.black_level_dn <= item.max_dn
        assert imager("sony-imx174").full_well_e == 32691.0
        assert imager("Sony-ICX418").bits == 8

    def test02_found_beside_the_package_and_by_path(self):
        assert ROOT_RESOURCES_IMAGERS.is_dir()
        assert ROOT_RESOURCES_IMAGERS.parent.parent.name == "datasets"
        path = ROOT_RESOURCES_IMAGERS / "sony-imx174.toml"
        assert imager(path) == imager(str(path)) == imager("sony-imx174")
        assert imager(imager("sony-imx174")) is imager("sony-imx174")


GOOD_TOML = """name = "mine"
source = "a test"
pixel_um = 4.0
f_number = 2.0
transmittance = 0.9
qe_peak = 0.6
full_well_e = 10000.0
read_noise_e = 3.0
dark_current_e_per_s = 1.0
gain_dn_per_e = 0.4
bits = 12
black_level_dn = 8.0
"""


class TestBadInput:
    @pytest.mark.parametrize(
        ("field", "value"),
        [("name", ""), ("source", 3), ("pixel_um", 0.0), ("pixel_um", "5"), ("pixel_um", math.nan),
         ("f_number", 0.0), ("f_number", -2.8), ("transmittance", 0.0), ("transmittance", 1.2),
         ("qe_peak", 0.0), ("qe_peak", 1.01), ("full_well_e", 0.0), ("full_well_e", -1.0),
         ("full_well_e", math.inf), ("read_noise_e", -0.1), ("dark_current_e_per_s", -1.0),
         ("gain_dn_per_e", 0.0), ("bits", 12.5), ("bits", 0), ("bits", 33), ("bits", True),
         ("bits", "12"), ("black_level_dn", -1.0), ("black_level_dn", 4096.0), ("pixel_um", True)],
    )
    def test01_each_imager_field(self, field, value):
        with pytest.raises(SkinrenderError, match=field):
            make_imager(**{field: value})

    @pytest.mark.parametrize(
        ("edit", "field"),
        [(lambda t: t + "colour = 1\n", "colour"),
         (lambda t: t.replace("read_noise_e = 3.0\n", ""), "read_noise_e"),
         (lambda t: t.replace("pixel_um = 4.0", 'pixel_um = "four"'), "pixel_um"),
         (lambda t: t.replace("bits = 12", "bits = 12.5"), "bits"),
         (lambda t: t.replace("read_noise_e = 3.0", "read_noise_e = -3.0"), "read_noise_e"),
         (lambda t: t.replace("qe_peak = 0.6", "qe_peak = "), "TOML")],
    )
    def test02_bad_toml_files(self, tmp_path: Path, edit, field):
        path = tmp_path / "bad_imager.toml"
        path.write_text(edit(GOOD_TOML), encoding="utf-8")
        with pytest.raises(SkinrenderError) as caught:
            imager(path)
        assert "bad_imager.toml" in str(caught.value) and field in str(caught.value)

    def test03_good_toml_and_unknown_presets(self, tmp_path: Path):
        path = tmp_path / "mine.toml"
        path.write_text(GOOD_TOML, encoding="utf-8")
        assert imager(path).gain_dn_per_e == 0.4
        for spec in ("no-such-imager", tmp_path / "missing.toml"):
            with pytest.raises(SkinrenderError, match="sony-imx174"):
                imager(spec)
        with pytest.raises(SkinrenderError, match="imager"):
            imager(42)

    @pytest.mark.parametrize("seed", [-1, 2**32, 1.5, True, None, "7", np.float64(3.0)])
    def test04_bad_seed(self, seed):
        with pytest.raises(SkinrenderError, match="rng_or_seed"):
            simulate_dn(make_imager(), [100.0], seed)

    def test05_bad_arrays(self):
        im, ones, flat = make_imager(), np.ones((3, GRID.size)), np.ones(GRID.size)
        cases = [
            (lambda: electrons_mean(im, np.ones((2, GRID.size)), flat, 0.1, GRID), "sensitivities"),
            (lambda: electrons_mean(im, ones * [[1], [0], [1]], flat, 0.1, GRID), "sensitivities"),
            (lambda: electrons_mean(im, ones, np.ones(GRID.size - 1), 0.1, GRID), "radiance"),
            (lambda: electrons_mean(im, ones, -np.ones(GRID.size), 0.1, GRID), "radiance"),
            (lambda: electrons_mean(im, ones, np.ones(GRID.size), -0.1, GRID), "exposure_s"),
            (lambda: electrons_mean(im, ones, np.ones(GRID.size), 0.1, (400, 700, 10)), "grid"),
            (lambda: statistics_dn(im, [-1.0]), "electrons_mean"),
            (lambda: simulate_dn(im, [math.nan], 1), "electrons_mean"),
            (lambda: auto_exposure(im, [1.0, 2.0, 3.0], fraction=0.0), "fraction"),
            (lambda: auto_exposure(im, [0.0, 0.0, 0.0]), "white_electrons_per_s"),
            (lambda: auto_exposure(im, [1.0, 2.0]), "white_electrons_per_s"),
            (lambda: illuminance_lux(np.ones(5), GRID), "spd"),
            (lambda: irradiance_planck(3000.0, -1.0, GRID), "lux"),
            (lambda: ncc_covariance([1.0, 2.0, 3.0], [1.0, 1.0, 1.0], [1.0, 0.0, 1.0]), "gains"),
            (lambda: ncc_covariance([1.0, -2.0, 0.5], [1.0, 1.0, 1.0], [1.0, 1.0, 1.0]), "mean"),
            (lambda: ncc_covariance([1.0, 2.0, 3.0], np.ones((2, 2)), [1.0, 1.0, 1.0]), "cov_or_var"),
            (lambda: ncc_covariance([1.0, 2.0, 3.0], [1.0, -1.0, 1.0], [1.0, 1.0, 1.0]), "cov_or_var"),
        ]
        for call, name in cases:
            with pytest.raises(SkinrenderError, match=name):
                call()
