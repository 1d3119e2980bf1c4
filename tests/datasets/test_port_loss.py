"""
Tests for :mod:`skinrender.datasets.port_loss`: the kept fraction of Farrell et al.'s diffusion model against a
direct numerical integral of its radial reflectance, its limits, and a reflectance read through a port.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from skinrender.datasets.port_loss import check_port, kept_fraction, through_port
from skinrender.errors import SkinrenderError

G, N = 0.8, 1.4


def farrell_radial(r, mu_a, mu_s):
    """Farrell, Patterson & Wilson 1992: the diffuse reflectance at distance r of a pencil beam, mm⁻², from the
    source at z0 and its image at −(z0 + 2 zb), written out as the paper gives it (not the module's closed form)."""
    transport = mu_a + mu_s * (1 - G)
    effective = np.sqrt(3 * mu_a * transport)
    r_eff = -1.440 / N**2 + 0.710 / N + 0.668 + 0.0636 * N
    z0 = 1 / transport
    zb = 2 * (1 + r_eff) / (1 - r_eff) / (3 * transport)
    total = 0.0
    for z in (z0, z0 + 2 * zb):
        rho = np.sqrt(z * z + r * r)
        total += z * (effective + 1 / rho) * np.exp(-effective * rho) / rho**2
    return total / (4 * np.pi)


@pytest.mark.parametrize("mu_a, mu_s, radius", [(0.01, 20.0, 2.5), (0.05, 15.0, 1.0), (0.3, 30.0, 0.5),
                                                (0.005, 10.0, 4.0)])
def test_kept_fraction_is_the_integral_of_the_radial_reflectance(mu_a, mu_s, radius):
    def ring(r):
        return 2 * np.pi * r * farrell_radial(r, mu_a, mu_s)

    inside = quad(ring, 0, radius, limit=200)[0]
    total = inside + quad(ring, radius, np.inf, limit=200)[0]
    assert kept_fraction(mu_a, mu_s, radius, G, N) == pytest.approx(inside / total, rel=1e-6)


def test_kept_fraction_grows_from_0_to_1_with_the_radius_and_falls_with_less_absorption():
    radii = np.array([0.0, 0.5, 1.0, 2.5, 5.0, 20.0, 1e4])
    kept = kept_fraction(0.01, 20.0, radii[:, None], G, N)[:, 0]
    assert kept[0] == 0.0 and kept[-1] == pytest.approx(1.0, abs=1e-9) and np.all(np.diff(kept) > 0)
    # the less the skin absorbs, the farther light spreads: a port keeps less of it
    absorption = np.array([0.3, 0.1, 0.03, 0.01, 0.003])
    assert np.all(np.diff(kept_fraction(absorption, 20.0, 2.5, G, N)) < 0)


def test_through_port_keeps_the_specular_part_and_none_is_the_reflectance_itself():
    reflectance = np.array([0.1, 0.3, 0.5])
    assert np.array_equal(through_port(reflectance, 0.028, 0.01, 20.0, None, G, N), reflectance)
    seen = through_port(reflectance, 0.028, 0.01, 20.0, 5.0, G, N)
    kept = kept_fraction(0.01, 20.0, 2.5, G, N)
    np.testing.assert_allclose(seen, 0.028 + (reflectance - 0.028) * kept, rtol=1e-12)
    assert np.all(seen < reflectance)


@pytest.mark.parametrize("port", [0, -1, float("nan"), float("inf"), "x", "", True, [5]])
def test_check_port_refuses_what_is_no_diameter(port):
    with pytest.raises(SkinrenderError, match="port_mm") as error:
        check_port(port)
    assert error.value.role == "port_mm"
    assert check_port(None) is None and check_port("5") == 5.0


@pytest.mark.parametrize("arguments, role", [
    ((0.5, 0.03, 0.01, 20.0, -1.0, 0.8, 1.4), "port_mm"),  # was read as +1 mm
    ((0.5, 0.03, 0.01, 20.0, True, 0.8, 1.4), "port_mm"),  # was read as 1 mm
    ((0.5, 0.03, 0.01, 20.0, float("nan"), 0.8, 1.4), "port_mm"),  # was NaN
    ((-0.5, 0.03, 0.01, 20.0, 5.0, 0.8, 1.4), "reflectance"),
])
def test_through_port_checks_its_port_and_reflectance(arguments, role):
    with pytest.raises(SkinrenderError) as error:
        through_port(*arguments)
    assert error.value.role == role


@pytest.mark.parametrize("arguments, role", [
    ((0.01, 20.0, -1.0, 0.8, 1.4), "radius_mm"),  # was 0.60
    ((-1.0, 20.0, 1.0, 0.8, 1.4), "mu_a"),  # was NaN
    ((0.0, 0.0, 1.0, 0.8, 1.4), "mu_a"),  # no transport length: was NaN
    ((0.01, 20.0, 1.0, 1.0, 1.4), "g"),
    ((0.01, 20.0, 1.0, 0.8, 0.0), "n"),  # was a bare ZeroDivisionError
])
def test_kept_fraction_checks_the_medium(arguments, role):
    with pytest.raises(SkinrenderError) as error:
        kept_fraction(*arguments)
    assert error.value.role == role
