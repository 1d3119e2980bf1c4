"""
Tests for :mod:`skinrender.datasets.adding_doubling`: the quadrature, the Fresnel boundary, the stack's
reflectance against Prahl's own adding-doubling (iadpython) for single finite and semi-infinite layers and for
two layers, slab by slab, and its angular reflectance (a BRDF table) against iadpython's matrix, single scattering,
energy conservation and the diffuse reflectance.
"""

from __future__ import annotations

import copy

import numpy as np
import pytest

from skinrender.datasets.adding_doubling import (Slab, angular_reflectance, fresnel_reflectance, quadrature,
                                                 stack_reflectance)
from skinrender.errors import SkinrenderError

TOLERANCE_IADPYTHON = 1e-8
"""The same formulation, quadrature and starting layer as iadpython: agreement to round-off (measured ~1e-10; the
semi-infinite layers stop doubling on slightly different criteria)."""


def iad_two_layers_matrices(top: tuple, bottom: tuple, thickness_top: float, g: float, n: float,
                            quad_pts: int = 16) -> tuple:
    """iadpython's sample and reflection matrix (from air, boundary included) of a layer ``(mu_a, mu_s)`` over a
    semi-infinite one, and the stack's transmission matrix."""
    iad = pytest.importorskip("iadpython")
    sample = iad.Sample(a=0.5, b=1, g=g, n=n, n_above=1, n_below=1, quad_pts=quad_pts)
    sample.update_quadrature()
    matrices = []
    for (mu_a, mu_s), thickness in ((top, thickness_top), (bottom, np.inf)):
        layer = copy.deepcopy(sample)
        layer.a, layer.b = mu_s / (mu_a + mu_s), (mu_a + mu_s) * thickness
        matrices.append(iad.simple_layer_matrices(layer))
    (r1, t1), (r2, t2) = matrices
    r02, r20, t02, t20 = iad.add_layers(sample, r1, r1, t1, t1, r2, r2, t2, t2)
    b01, b10, c01, c10 = iad.boundary_matrices(sample, top=True)
    return sample, iad.add_layers(sample, b01, b10, c01, c10, r02, r20, t02, t20)[0], t02


def iad_two_layers(top: tuple, bottom: tuple, thickness_top: float, g: float, n: float, quad_pts: int = 16) -> float:
    """iadpython's total reflectance (UR1) of a layer ``(mu_a, mu_s)`` over a semi-infinite one, under air."""
    sample, total, t02 = iad_two_layers_matrices(top, bottom, thickness_top, g, n, quad_pts)
    return float(sample.UX1_and_UXU(total, t02)[0])


class TestQuadrature:
    @pytest.mark.parametrize("quad_pts, n", [(4, 1.0), (8, 1.0), (8, 1.4), (16, 1.4), (16, 1.33)])
    def test_integrates_polynomials_exactly(self, quad_pts, n):
        """Gauss and Radau halves are each exact to degree quad_pts - 2 on their intervals: so is the sum on [0, 1]."""
        nu, twonuw = quadrature(quad_pts, n)
        weights = twonuw / (2 * nu)
        for k in range(quad_pts - 1):
            assert weights @ nu**k == pytest.approx(1 / (k + 1), rel=1e-12)
        assert nu[-1] == 1.0 and np.all(np.diff(nu) > 0)

    def test_critical_angle_splits_the_points(self):
        nu, _ = quadrature(16, 1.4)
        assert np.sum(nu < np.sqrt(1 - 1 / 1.4**2)) == 8

    def test_against_iadpython(self):
        iad = pytest.importorskip("iadpython")
        sample = iad.Sample(a=0.5, b=1, g=0.8, n=1.4, quad_pts=16)
        sample.update_quadrature()
        nu, twonuw = quadrature(16, 1.4)
        np.testing.assert_allclose(nu, sample.nu, atol=1e-12)
        np.testing.assert_allclose(twonuw, sample.twonuw, atol=1e-11)

    def test_odd_point_counts_are_refused(self):
        with pytest.raises(SkinrenderError, match="even"):
            quadrature(7, 1.4)


class TestFresnelReflectance:
    def test_normal_incidence_and_total_internal_reflection(self):
        assert fresnel_reflectance(1.0, 1.5) == pytest.approx(0.04)
        assert fresnel_reflectance(0.5, 1.4) == 1.0  # beyond the critical angle (cos 0.70)
        assert fresnel_reflectance(1.0, 1.0) == 0.0

    def test_rises_towards_the_critical_angle(self):
        nu = np.linspace(0.72, 1.0, 20)
        assert np.all(np.diff(fresnel_reflectance(nu, 1.4)) < 0)


class TestStackReflectance:
    def test_single_finite_layers_against_iadpython(self, rng):
        iad = pytest.importorskip("iadpython")
        for _ in range(6):
            mu_a, mu_s, g, d = rng.uniform(0.01, 2), rng.uniform(0.1, 30), rng.uniform(0, 0.95), rng.uniform(0.01, 2)
            n = float(rng.choice([1.0, 1.4]))
            mine = stack_reflectance([Slab(np.array([mu_a]), np.array([mu_s]), g, d)], n=n)[0]
            theirs = iad.Sample(a=mu_s / (mu_a + mu_s), b=(mu_a + mu_s) * d, g=g, n=n, quad_pts=16).rt()[0]
            assert mine == pytest.approx(theirs, abs=TOLERANCE_IADPYTHON)

    def test_diffuse_incidence_against_iadpython(self, rng):
        iad = pytest.importorskip("iadpython")
        for n, thickness in ((1.4, 0.5), (1.4, None), (1.0, 1.0)):
            mu_a, mu_s, g = rng.uniform(0.05, 1), rng.uniform(2, 20), rng.uniform(0.5, 0.9)
            mine = stack_reflectance([Slab(np.array([mu_a]), np.array([mu_s]), g, thickness)], n=n, diffuse=True)[0]
            b = np.inf if thickness is None else (mu_a + mu_s) * thickness
            theirs = iad.Sample(a=mu_s / (mu_a + mu_s), b=b, g=g, n=n, quad_pts=16).rt()[2]
            assert mine == pytest.approx(theirs, abs=TOLERANCE_IADPYTHON)

    def test_semi_infinite_layers_against_iadpython(self, rng):
        iad = pytest.importorskip("iadpython")
        for _ in range(4):
            mu_a, mu_s, g = rng.uniform(0.005, 2), rng.uniform(0.5, 30), rng.uniform(0, 0.9)
            mine = stack_reflectance([Slab(np.array([mu_a]), np.array([mu_s]), g, None)], n=1.4)[0]
            theirs = iad.Sample(a=mu_s / (mu_a + mu_s), b=np.inf, g=g, n=1.4, quad_pts=16).rt()[0]
            assert mine == pytest.approx(theirs, abs=TOLERANCE_IADPYTHON)

    def test_two_layers_against_iadpython(self, rng):
        for _ in range(4):
            top, bottom = (rng.uniform(0.1, 5), rng.uniform(5, 40)), (rng.uniform(0.01, 1), rng.uniform(5, 40))
            thickness, g = rng.uniform(0.05, 0.2), rng.uniform(0.6, 0.9)
            mine = stack_reflectance([Slab(np.array([top[0]]), np.array([top[1]]), g, thickness),
                                      Slab(np.array([bottom[0]]), np.array([bottom[1]]), g, None)], n=1.4)[0]
            assert mine == pytest.approx(iad_two_layers(top, bottom, thickness, g, 1.4), abs=TOLERANCE_IADPYTHON)

    def test_a_clear_half_space_reflects_the_fresnel_term(self):
        r = stack_reflectance([Slab(np.zeros(3), np.zeros(3), 0.5, None)], n=1.5)
        np.testing.assert_allclose(r, 0.04, atol=1e-12)

    def test_n_dimensional(self, rng):
        """Coefficients (2, 3, L) give reflectances (2, 3, L), each row as computed alone."""
        mu_a = rng.uniform(0.01, 1, size=(2, 3, 5))
        mu_s = rng.uniform(5, 30, size=(2, 3, 5))
        stacked = stack_reflectance([Slab(mu_a, mu_s, 0.8, 0.1), Slab(mu_a / 2, mu_s, 0.8, None)])
        assert stacked.shape == (2, 3, 5)
        alone = stack_reflectance([Slab(mu_a[1, 2], mu_s[1, 2], 0.8, 0.1),
                                   Slab(mu_a[1, 2] / 2, mu_s[1, 2], 0.8, None)])
        np.testing.assert_allclose(stacked[1, 2], alone, atol=1e-13)

    def test_more_absorption_reflects_less(self):
        mu_a = np.array([0.01, 0.1, 1.0, 10.0])
        r = stack_reflectance([Slab(mu_a, np.full(4, 20.0), 0.8, None)])
        assert np.all(np.diff(r) < 0) and r[-1] > 0.0277

    @pytest.mark.parametrize("slabs, match", [
        ([Slab(np.array([-1.0]), np.array([1.0]), 0.5, None)], "mu_a and mu_s"),
        ([Slab(np.array([1.0]), np.array([np.nan]), 0.5, None)], "mu_a and mu_s"),
        ([Slab(np.array([1.0]), np.array([1.0]), 1.0, None)], "g must be"),
        ([Slab(np.array([1.0]), np.array([1.0]), 0.5, 0.0)], "thickness"),
        ([Slab(np.array([1.0]), np.array([1.0]), 0.5, None), Slab(np.array([1.0]), np.array([1.0]), 0.5, None)],
         "only the last layer"),
        ([], "at least one layer"),
    ])
    def test_bad_layers_are_refused(self, slabs, match):
        with pytest.raises(SkinrenderError, match=match):
            stack_reflectance(slabs)

    def test_an_index_below_one_is_refused(self):
        with pytest.raises(SkinrenderError, match="n must be"):
            stack_reflectance([Slab(np.array([1.0]), np.array([1.0]), 0.5, None)], n=0.9)


def iad_two_layers_brdf(top: tuple, bottom: tuple, thickness_top: float, g: float, n: float,
                        quad_pts: int = 16) -> np.ndarray:
    """iadpython's reflection matrix of a layer over a semi-infinite one under air, as a BRDF on the nodes that
    leave into air: (total − the boundary's Fresnel term) / (π n²) (angular_reflectance's docstring)."""
    sample, total, _ = iad_two_layers_matrices(top, bottom, thickness_top, g, n, quad_pts)
    above = sample.nu > np.sqrt(1 - 1 / n**2)
    body = total - np.diag(fresnel_reflectance(sample.nu, n) / sample.twonuw)
    return body[above][:, above] / (np.pi * n**2)


class TestAngularReflectance:
    def test_two_layers_against_iadpython(self, rng):
        """The whole matrix, not only UR1's column, is iadpython's: every pair of angles."""
        for _ in range(3):
            top, bottom = (rng.uniform(0.1, 5), rng.uniform(5, 40)), (rng.uniform(0.01, 1), rng.uniform(5, 40))
            thickness, g = rng.uniform(0.05, 0.2), rng.uniform(0.6, 0.9)
            mine = angular_reflectance([Slab(np.array([top[0]]), np.array([top[1]]), g, thickness),
                                        Slab(np.array([bottom[0]]), np.array([bottom[1]]), g, None)], n=1.4)
            theirs = iad_two_layers_brdf(top, bottom, thickness, g, 1.4)
            np.testing.assert_allclose(mine.brdf[0], theirs, rtol=1e-7, atol=1e-12)

    def test_single_scattering(self):
        """
        An independent check of the BRDF's units and angles: a thin slab (τ 0.5) scattering isotropically with
        albedo ω 0.002, no boundary (n 1), reflects almost only light scattered once. A beam of irradiance E at μ_i
        carries E/μ_i across its own section; at optical depth t a layer dt scatters ω (E/μ_i) e^(−t/μ_i) dt/4π per
        sr, attenuated by e^(−t/μ_o) on the way out, and spread over dt/μ_o of the surface:

            L_o = ω E / (4π μ_i μ_o) ∫₀^τ e^(−t(1/μ_i + 1/μ_o)) dt,  f = L_o / E = ω (1 − e^(−τ(1/μ_i + 1/μ_o))) / (4π (μ_i + μ_o)).

        Light scattered twice adds a fraction of order ω: agreement within 0.2 %.
        """
        albedo, tau = 0.002, 0.5
        table = angular_reflectance([Slab(np.array([1 - albedo]), np.array([albedo]), 0.0, tau)], n=1.0)
        mo, mi = np.meshgrid(table.mu, table.mu, indexing="ij")
        once = albedo * (1 - np.exp(-tau * (1 / mo + 1 / mi))) / (4 * np.pi * (mo + mi))
        np.testing.assert_allclose(table.brdf[0], once, rtol=2e-3)
        np.testing.assert_allclose(table.specular, 0.0, atol=1e-15)

    def test_reciprocity_and_ur1(self, rng):
        """f(μ_o, μ_i) = f(μ_i, μ_o) (both ends in air), and the albedo at normal incidence is UR1."""
        mu_a, mu_s = rng.uniform(0.01, 1, size=4), rng.uniform(5, 30, size=4)
        slabs = [Slab(mu_a * 5, mu_s, 0.8, 0.1), Slab(mu_a, mu_s, 0.8, None)]
        table = angular_reflectance(slabs, n=1.4, quad_pts=16)
        assert table.brdf.shape == (4, 8, 8) and table.mu[-1] == 1.0 and np.all(np.diff(table.mu) > 0)
        np.testing.assert_allclose(table.brdf, np.swapaxes(table.brdf, -1, -2), rtol=1e-10)
        np.testing.assert_allclose(table.albedo()[:, -1], stack_reflectance(slabs, n=1.4), atol=1e-13)
        np.testing.assert_allclose(table.specular, fresnel_reflectance(np.sqrt(1 - (1 - table.mu**2) / 1.4**2), 1.4))

    def test_weights_integrate_in_air(self):
        """The air weights are a quadrature of ∫₀¹ 2μ dμ: exact for μ^(2k) (a polynomial in the nodes' ν inside:
        μ² = 1 − n²(1 − ν²))."""
        table = angular_reflectance([Slab(np.array([0.1]), np.array([10.0]), 0.8, None)], n=1.4, quad_pts=16)
        for k in range(5):
            assert table.weights @ table.mu ** (2 * k) == pytest.approx(1 / (k + 1), rel=1e-12)

    def test_no_absorption_returns_every_angle_s_light(self):
        """A semi-infinite slab that does not absorb reflects all the light that arrives, from any angle: its
        directional-hemispherical reflectance (the body's flux plus Fresnel) is 1 at every node."""
        table = angular_reflectance([Slab(np.array([0.0]), np.array([5.0]), 0.8, None)], n=1.4)
        np.testing.assert_allclose(table.albedo(), 1.0, atol=5e-6)

    def test_diffuse_reflectance(self, rng):
        """Under diffuse light the table's reflectance, weighted over incidence, is adding-doubling's URU."""
        mu_a, mu_s = rng.uniform(0.01, 1, size=3), rng.uniform(5, 30, size=3)
        slabs = [Slab(mu_a, mu_s, 0.8, None)]
        table = angular_reflectance(slabs, n=1.4)
        np.testing.assert_allclose(table.albedo() @ table.weights, stack_reflectance(slabs, n=1.4, diffuse=True),
                                   atol=1e-12)
