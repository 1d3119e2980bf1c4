"""
Tests for :mod:`skinrender.rendering.face.effects.sheen`: the coat's internal reflectance measured from the
plugin, and the body reflectance the dichromatic check uses (ρ / (1 − R ρ) with the coat's internal scattering).
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.rendering.face.effects.sheen import (SHEEN_ALPHA, SHEEN_IOR, SHEEN_NONLINEAR,
                                                     coat_body_reflectance, coat_internal_reflectance)

pytest.importorskip("mitsuba")


def diffuse_lobe(rho: float, nonlinear: bool) -> float:
    """The roughplastic's diffuse lobe at one geometry for a uniform base ``rho`` (the specular lobe subtracted)."""
    from skinrender.rendering.variants import choose_variant, mitsuba

    mi = mitsuba(choose_variant(None))
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(0.28, 0.0, float(np.sqrt(1 - 0.28**2)))
    si.wavelengths = mi.Spectrum(610.0)
    wo = mi.Vector3f(0.1, -0.6, float(np.sqrt(1 - 0.37)))
    values = []
    for r in (rho, 0.0):
        bsdf = mi.load_dict({"type": "roughplastic", "distribution": "ggx", "alpha": SHEEN_ALPHA, "int_ior": SHEEN_IOR,
                             "ext_ior": 1.0, "nonlinear": nonlinear, "diffuse_reflectance": {"type": "uniform",
                                                                                             "value": r}})
        values.append(float(np.asarray(bsdf.eval(mi.BSDFContext(), si, wo)).ravel()[0]))
    return values[0] - values[1]


def test_the_internal_reflectance_predicts_the_plugin_at_another_geometry_and_base():
    """R was measured at one geometry from ρ 0.2 and 0.8; at another geometry, ρ 0.35 against 0.65 obeys
    ρ / (1 − R ρ) with it, and without the coat's internal scattering the lobe is linear in ρ."""
    r = coat_internal_reflectance()
    assert 0.2 < r < 0.5
    ratio = diffuse_lobe(0.65, True) / diffuse_lobe(0.35, True)
    assert ratio == pytest.approx((0.65 / (1 - r * 0.65)) / (0.35 / (1 - r * 0.35)), rel=1e-5)
    assert diffuse_lobe(0.65, False) / diffuse_lobe(0.35, False) == pytest.approx(0.65 / 0.35, rel=1e-5)


def test_the_body_reflectance_saturates_with_the_coats_scattering():
    rho = np.array([0.1, 0.3, 0.6])
    assert SHEEN_NONLINEAR
    body = coat_body_reflectance(rho)
    assert body == pytest.approx(rho / (1 - coat_internal_reflectance() * rho))
    assert np.all(np.diff(body / rho) > 0)  # the redder (brighter) the more it gains: the colour saturates
    assert np.array_equal(coat_body_reflectance(rho, nonlinear=False), rho)
