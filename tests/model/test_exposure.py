"""
Tests for :mod:`skinrender.model.exposure`: photon counts by hand, photometry
against V(λ), the automatic exposure and every bad input.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from skinrender.constants import CONSTANT_C, CONSTANT_H
from skinrender.errors import SkinrenderError
from skinrender.model.exposure import (
    CONSTANT_K_M,
    auto_exposure,
    electrons_mean,
    illuminance_lux,
    irradiance_planck,
    photopic_efficiency,
    radiance_lambertian,
)
from skinrender.spectra import WavelengthGrid

from .test_imager import make_imager

TOLERANCE_RELATIVE_HAND = 1e-12
"""Relative tolerance for closed-form arithmetic done two ways in float64 (a few roundings)."""

GRID_555 = WavelengthGrid(555.0, 556.0, 1.0)
"""A 1 nm band at 555 nm: the radiance is 0 at 556 nm (a grid needs two samples)."""
GRID = WavelengthGrid(400.0, 700.0, 10.0)


class TestElectronsMean:
    def test01_hand_computation(self):
        """555 nm, 1 nm band, L = 0.01 W·m⁻²·sr⁻¹·nm⁻¹, f/2.8, τ 0.9, 5 µm, QE 0.5, 10 ms.

        E_s = π τ L / (4 N²); photons = E_s A λ / (h c) · Δλ · t; electrons = QE · photons.
        """
        im = make_imager(dark_current_e_per_s=0.0)
        sensor_irradiance = math.pi * 0.9 * 0.01 / (4 * 2.8**2)  # W·m⁻²·nm⁻¹
        photons = sensor_irradiance * (5e-6) ** 2 / (CONSTANT_H * CONSTANT_C / 555e-9) * 1.0 * 0.01
        expected = 0.5 * photons
        got = electrons_mean(im, np.ones((3, 2)), [0.01, 0.0], 0.01, GRID_555)
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


class TestPhotometry:
    def test01_flat_spectrum(self):
        from colour.colorimetry import SDS_LEFS_PHOTOPIC

        grid = WavelengthGrid(400, 700, 1)
        v = SDS_LEFS_PHOTOPIC["CIE 1924 Photopic Standard Observer"][grid.wavelengths]
        expected = CONSTANT_K_M * np.sum(v) * 1.0
        np.testing.assert_allclose(illuminance_lux(np.ones(grid.size), grid), expected, rtol=1e-12)
        np.testing.assert_allclose(photopic_efficiency(grid), v, rtol=1e-12)

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


class TestBadInput:
    def test01_bad_arrays(self):
        im, ones, flat = make_imager(), np.ones((3, GRID.size)), np.ones(GRID.size)
        cases = [
            (lambda: electrons_mean(im, np.ones((2, GRID.size)), flat, 0.1, GRID), "sensitivities"),
            (lambda: electrons_mean(im, ones * [[1], [0], [1]], flat, 0.1, GRID), "sensitivities"),
            (lambda: electrons_mean(im, ones, np.ones(GRID.size - 1), 0.1, GRID), "radiance"),
            (lambda: electrons_mean(im, ones, -np.ones(GRID.size), 0.1, GRID), "radiance"),
            (lambda: electrons_mean(im, ones, np.ones(GRID.size), -0.1, GRID), "exposure_s"),
            (lambda: electrons_mean(im, ones, np.ones(GRID.size), 0.1, (400, 700, 10)), "grid"),
            (lambda: auto_exposure(im, [1.0, 2.0, 3.0], fraction=0.0), "fraction"),
            (lambda: auto_exposure(im, [0.0, 0.0, 0.0]), "white_electrons_per_s"),
            (lambda: auto_exposure(im, [1.0, 2.0]), "white_electrons_per_s"),
            (lambda: illuminance_lux(np.ones(5), GRID), "spd"),
            (lambda: irradiance_planck(3000.0, -1.0, GRID), "lux"),
            (lambda: irradiance_planck(3000.0, math.nan, GRID), "lux"),
            (lambda: radiance_lambertian(-0.1, 1.0), "reflectance"),
        ]
        for call, name in cases:
            with pytest.raises(SkinrenderError, match=name):
                call()


def test_auto_exposure_note_says_where_the_cap_binds():
    from skinrender.model.exposure import auto_exposure_note

    im = make_imager()
    rate = np.array([[1e3, 2e3, 5e2], [1e8, 2e8, 5e7]])  # e⁻/s: a dim white (capped) and a bright one
    note = auto_exposure_note(im, rate, 0.7, 0.01)
    reached = 2e3 * 0.01 / im.full_well_e
    assert note is not None and f"{reached:.3g} of the full well" in note and "1 of 2" in note and "0.7" in note
    assert auto_exposure_note(im, rate[1:], 0.7, 0.01) is None
