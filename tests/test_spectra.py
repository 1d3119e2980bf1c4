"""Tests for :mod:`skinrender.spectra`."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from skinrender.constants import CONSTANT_C, CONSTANT_H, CONSTANT_K_B, TOLERANCE_RELATIVE_TESTS
from skinrender.errors import SkinrenderError
from skinrender.spectra import (
    GRID_DEFAULT,
    WavelengthGrid,
    gbell,
    impulse,
    planck,
    resample,
)


class TestWavelengthGrid:
    def test_default(self):
        assert GRID_DEFAULT.size == 301
        assert GRID_DEFAULT.wavelengths[0] == 400 and GRID_DEFAULT.wavelengths[-1] == 700

    def test_parse(self):
        assert WavelengthGrid.parse("400:700:5") == WavelengthGrid(400, 700, 5)
        assert WavelengthGrid.parse("400:700:5").size == 61

    @pytest.mark.parametrize("text", ["400:700", "a:b:c", "400:700:7", "700:400:1", "400:700:0", "0:700:1"])
    def test_bad(self, text):
        with pytest.raises(SkinrenderError, match="grid"):
            WavelengthGrid.parse(text)

    def test_index_of(self):
        assert GRID_DEFAULT.index_of(450) == 50
        with pytest.raises(SkinrenderError, match="not a sample"):
            WavelengthGrid(400, 700, 10).index_of(455)


class TestPlanck:
    def test_against_colour_science(self):
        """colour's ``planck_law`` takes metres and returns W·sr⁻¹·m⁻²·m⁻¹; with the
        same CODATA constants (c1 = 2πhc², c2 = hc/k) it must equal ours × 1e9."""
        colour = pytest.importorskip("colour")
        wavelengths = np.linspace(360, 830, 48)
        for temperature in (1000.0, 2856.0, 6500.0, 25000.0):
            theirs = colour.colorimetry.planck_law(
                wavelengths * 1e-9, temperature,
                c1=2 * np.pi * CONSTANT_H * CONSTANT_C**2, c2=CONSTANT_H * CONSTANT_C / CONSTANT_K_B,
            )
            np.testing.assert_allclose(planck(wavelengths, temperature) * 1e9, theirs, rtol=1e-12)

    def test_against_colour_science_default_constants(self):
        """colour's default c2 = 0.014388 m·K is CODATA's 0.0143877688 rounded: 1.6e-5
        relative, which moves the exponent by at most 1e-4 relative over 400–700 nm."""
        colour = pytest.importorskip("colour")
        wavelengths = np.arange(400.0, 701.0, 10.0)
        theirs = colour.colorimetry.planck_law(wavelengths * 1e-9, 5000.0)
        np.testing.assert_allclose(planck(wavelengths, 5000.0) * 1e9, theirs, rtol=2e-4)

    def test_hand_value(self):
        """λ = 500 nm, T = 5000 K: x = hc/(λkT) = 5.7551075…, L = 2hc²/λ⁵/(eˣ − 1) per nm."""
        x = CONSTANT_H * CONSTANT_C / (500e-9 * CONSTANT_K_B * 5000)
        expected = 2 * CONSTANT_H * CONSTANT_C**2 / (500e-9) ** 5 / (np.exp(x) - 1) * 1e-9
        assert x == pytest.approx(5.7551075, rel=1e-7)  # 0.0143877688 m·K / 0.0025 m·K
        assert planck(500, 5000) == pytest.approx(expected, rel=TOLERANCE_RELATIVE_TESTS)

    @pytest.mark.parametrize("temperature", [2000.0, 3000.0, 5000.0, 7000.0])
    def test_wien_displacement(self, temperature):
        """The peak of L(λ) lies at λ_max = b / T, b = 2.897771955e6 nm·K."""
        wavelengths = np.arange(300.0, 2000.0, 0.01)
        peak = wavelengths[np.argmax(planck(wavelengths, temperature))]
        assert peak == pytest.approx(2.897771955e6 / temperature, abs=0.01)

    @pytest.mark.parametrize("temperature", [300.0, 1000.0, 50000.0, 1e6])
    def test_extremes_finite(self, temperature):
        wavelengths = np.arange(300.0, 1001.0, 1.0)
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            values = planck(wavelengths, temperature)
        assert np.all(np.isfinite(values)) and np.all(values >= 0)
        if temperature >= 1000:
            assert np.all(values > 0)

    def test_300K_tiny_but_ordered(self):
        """At 300 K the visible radiance is ~1e-45 yet still grows with λ (Wien side)."""
        values = planck(np.arange(400.0, 701.0, 50.0), 300.0)
        assert np.all(np.diff(values) > 0)

    def test_high_temperature_no_loss(self):
        """At 1e6 K, x ≈ 0.03: expm1 keeps the Rayleigh–Jeans limit 2ckT/λ⁴ to O(x)."""
        rayleigh_jeans = 2 * CONSTANT_C * CONSTANT_K_B * 1e6 / (500e-9) ** 4 * 1e-9
        x = CONSTANT_H * CONSTANT_C / (500e-9 * CONSTANT_K_B * 1e6)
        assert planck(500, 1e6) == pytest.approx(rayleigh_jeans * x / np.expm1(x), rel=1e-12)

    @pytest.mark.parametrize("temperature", [0.0, -5.0, np.nan, np.inf])
    def test_bad_temperature(self, temperature):
        with pytest.raises(SkinrenderError, match="temperature"):
            planck(500, temperature)

    def test_n_dimensional(self):
        t = np.array([2000.0, 3000.0])[:, None, None]
        w = np.array([[450.0, 550.0, 650.0]])
        assert planck(w, t).shape == (2, 1, 3)


class TestGbell:
    def test_shape(self):
        """Peak 1 at c, 1/2 at c ± a for any slope, so FWHM = 2a."""
        for slope in (0.5, 1, 2, 4):
            values = gbell([540, 540 - 45, 540 + 45], 540, 90, slope)
            np.testing.assert_allclose(values, [1, 0.5, 0.5], atol=1e-15)

    def test_hand_value(self):
        """λ − c = 2a, b = 2: 1 / (1 + 2⁴) = 1/17."""
        assert gbell(540 + 90, 540, 90, 2) == pytest.approx(1 / 17)

    def test_bad(self):
        with pytest.raises(SkinrenderError, match="fwhm"):
            gbell(500, 500, 0)
        with pytest.raises(SkinrenderError, match="slope"):
            gbell(500, 500, 30, -1)


class TestImpulse:
    def test_unit_area(self):
        grid = WavelengthGrid(400, 700, 5)
        values = impulse(grid, 550)
        assert values.sum() * grid.step == pytest.approx(1.0)
        assert np.count_nonzero(values) == 1 and values[30] > 0

    def test_off_grid(self):
        with pytest.raises(SkinrenderError, match="not a sample"):
            impulse(WavelengthGrid(400, 700, 10), 455)


class TestResample:
    def test_linear_exact(self):
        """Linear interpolation reproduces a linear function exactly."""
        x = np.array([380.0, 500.0, 780.0])
        y = 0.001 * x
        np.testing.assert_allclose(resample(x, y, GRID_DEFAULT), 0.001 * GRID_DEFAULT.wavelengths, rtol=1e-12)

    def test_refuse(self):
        with pytest.raises(SkinrenderError, match="does not cover"):
            resample([420.0, 700.0], [1.0, 1.0], GRID_DEFAULT, source="mine.csv")

    def test_zero_and_constant(self):
        x, y = np.array([420.0, 680.0]), np.array([0.5, 0.5])
        zero = resample(x, y, GRID_DEFAULT, "zero")
        constant = resample(x, y, GRID_DEFAULT, "constant")
        assert zero[0] == 0 and zero[-1] == 0 and zero[100] == 0.5
        np.testing.assert_array_equal(constant, 0.5)

    @pytest.mark.parametrize("extrapolation", ["refuse", "zero", "constant"])
    @pytest.mark.parametrize("x, says", [([0.4, 0.55, 0.7], "in µm"), ([750.0, 900.0], "at all")])
    def test_data_beside_the_grid_is_refused_whatever_the_extrapolation(self, x, says, extrapolation):
        """No rule makes data of a spectrum that misses the grid entirely (zero would give silent zeros)."""
        with pytest.raises(SkinrenderError, match=f"does not overlap the grid .*{says}"):
            resample(x, np.full(len(x), 0.5), GRID_DEFAULT, extrapolation, source="mine.csv")

    def test_n_dimensional(self, rng):
        x = np.linspace(380, 780, 81)
        y = rng.random((2, 3, 81))
        out = resample(x, y, GRID_DEFAULT)
        assert out.shape == (2, 3, 301)
        np.testing.assert_allclose(out[1, 2], resample(x, y[1, 2], GRID_DEFAULT))
