"""
Tests for :mod:`skinrender.rendering.skin_sampling`: Henyey–Greenstein's density and sampling, the direction a
boundary refracts towards a light, the lengths of a segment in each layer, a medium's ``g``.
"""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("mitsuba")

from skinrender.rendering import skin_sampling as s  # noqa: E402
from skinrender.rendering.variants import choose_variant, mitsuba  # noqa: E402


@pytest.fixture(scope="module")
def mi():
    module = mitsuba(choose_variant(None))
    s.bind(module)
    return module


def test_hg_density_integrates_to_one_and_sampling_follows_it(mi):
    """∫ p dω = 1 (a quadrature in cos θ); 20 000 samples of g = 0.8 have the mean cosine g (±4 SE) and the
    density returned for each is hg_pdf of its angle."""
    for g in (0.0, 0.5, 0.8, 0.95, -0.3):
        mu = np.linspace(-1, 1, 200_001)
        density = np.array(s.hg_pdf(mi.Float(g), mi.Float(mu)))
        assert 2 * np.pi * np.trapezoid(density, mu) == pytest.approx(1, abs=2e-4)
    rng = np.random.default_rng(1)
    u = mi.Point2f(rng.random(20_000), rng.random(20_000))
    axis = mi.Vector3f(0.0, 0.6, 0.8)
    w, pdf = s.hg_sample(mi.Float(0.8), axis, u)
    cosines = np.array(w.y) * 0.6 + np.array(w.z) * 0.8
    assert abs(cosines.mean() - 0.8) < 4 * cosines.std() / np.sqrt(cosines.size)
    np.testing.assert_allclose(np.array(pdf), np.array(s.hg_pdf(mi.Float(0.8), mi.Float(cosines))), rtol=1e-3)


def test_inside_direction_refracts_to_the_light(mi):
    """Snell's law: the inside direction's tangential part is the light's over η, both on the same side; a light
    below the surface is flagged."""
    normal = mi.Vector3f(0.0, 0.0, 1.0)
    light = mi.Vector3f(float(np.sin(0.7)), 0.0, float(np.cos(0.7)))
    inside, above = s.inside_direction(light, normal, 1.4)
    assert bool(above[0]) and float(inside.x[0]) == pytest.approx(np.sin(0.7) / 1.4, rel=1e-6)
    assert float(inside.z[0]) == pytest.approx(np.sqrt(1 - (np.sin(0.7) / 1.4) ** 2), rel=1e-6)
    _, above = s.inside_direction(mi.Vector3f(0.0, 0.6, -0.8), normal, 1.4)
    assert not bool(above[0])


@pytest.mark.parametrize("z, rate, in_epi, expected", [
    (0.0, 0.5, True, (0.2, 0.8)),    # down from the surface: 0.1 mm of epidermis is 0.2 along a 60° path
    (0.05, -0.5, True, (1.0, 0.0)),  # up, staying in the epidermis
    (0.3, -0.5, False, (0.4, 0.6)),  # up from 0.3 mm in the dermis: 0.2 mm of dermis, then epidermis
    (0.3, 0.5, False, (1.0, 0.0)),   # down, staying in the dermis
])
def test_layer_lengths(mi, z, rate, in_epi, expected):
    first, second = s.layer_lengths(mi.Float(z), mi.Float(rate), mi.Float(1.0), mi.Bool(in_epi), 0.1)
    assert (float(first[0]), float(second[0])) == pytest.approx(expected, abs=1e-6)
    first, _ = s.layer_lengths(mi.Float(z), mi.Float(rate), mi.Float(1.0), mi.Bool(in_epi), 0.0)
    assert float(first[0]) == pytest.approx(1.0)  # one layer: all of it


def test_phase_g(mi):
    medium = mi.load_dict({"type": "homogeneous", "sigma_t": 1.0, "albedo": 0.5, "phase": {"type": "hg", "g": 0.7}})
    assert s.phase_g(medium) == pytest.approx(0.7)


def test_a_wavelength_outside_the_medium_is_clear_not_a_nan(mi):
    """The media are spectra on the render's grid: a wavelength a float32 step outside reads 0 extinction, whose
    albedo 0 / 0 was a NaN pixel; its extinction is 1e-12 (clear), its albedo 0 (it carries nothing)."""
    from skinrender.datasets.skin_model import SkinParameters, skin_layers
    from skinrender.rendering.subsurface import medium_dict
    from skinrender.spectra import GRID_DEFAULT

    layer = skin_layers(GRID_DEFAULT.wavelengths, SkinParameters())[1]
    medium = mi.load_dict(medium_dict(layer, GRID_DEFAULT))
    lam = dr_wavelengths(mi, [500.0, float(GRID_DEFAULT.wavelengths[-1]) + 5.0, 550.0, 600.0])
    sigma_s, sigma_t = (np.array(v).ravel() for v in s.coefficients(medium, lam))
    assert sigma_t[1] == pytest.approx(1e-12) and sigma_s[1] == 0 and np.all(sigma_t[[0, 2, 3]] > 1)
    albedo = sigma_s / sigma_t
    assert albedo[1] == 0 and np.all((albedo[[0, 2, 3]] > 0.5) & (albedo[[0, 2, 3]] < 1))


def dr_wavelengths(mi, values):
    """One lane's four wavelengths, nm."""
    return mi.UnpolarizedSpectrum(*[mi.Float([v]) for v in values])
