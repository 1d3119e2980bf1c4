"""Tests for :mod:`skinrender.rendering.face.scene`: face scenes; bad ones refused naming file and field."""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.rendering.face.scene import (MESH_HEAD, ROOT_FACE_SCENES, FaceScene, list_face_scenes,
                                             load_face_scene, skin_reflectance_of)
from skinrender.rendering.scene import list_scenes
from skinrender.spectra import GRID_DEFAULT

BUNDLED = (ROOT_FACE_SCENES / "face.toml").read_text(encoding="utf-8")


GOOD_OBJ = "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n"
GOOD_PLY = ("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n0.1 0 0\n0 0.1 0\n3 0 1 2\n")


def write(tmp_path, text: str, name: str = "scene.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


class TestLoadFaceScene:
    def test_the_bundled_face(self):
        scene = load_face_scene("face")
        assert isinstance(scene, FaceScene) and scene.mesh == MESH_HEAD
        assert (scene.camera.width, scene.camera.height) == (256, 256)
        assert scene.key.temperature == 2856 and scene.fill.temperature == 6500
        assert scene.environment.position is None
        assert [p.shape for p in scene.props] == ["rectangle", "rectangle", "cube", "rectangle"]
        assert list_face_scenes() == ["face"]
        assert "face" not in list_scenes(), "face scenes are not charts"

    def test_a_copy_by_path_is_the_same_scene(self, tmp_path):
        from dataclasses import replace

        path = write(tmp_path, BUNDLED)
        assert replace(load_face_scene(path), source="") == replace(load_face_scene("face"), source="")
        assert load_face_scene(load_face_scene("face")) == load_face_scene("face")

    def test_smooth_shading_and_an_ambient_sky_by_default(self, tmp_path):
        """The bundled face: smooth shading normals, and a sky of the key's spectrum at a fifth of its lux. A scene
        without the fields: smooth, and no ambient sky."""
        scene = load_face_scene("face")
        assert scene.mesh_smooth is True and scene.ambient == 0.2
        sky = scene.ambient_light
        assert sky.position is None and sky.temperature == scene.key.temperature
        assert sky.illuminance == pytest.approx(0.2 * scene.key.illuminance)
        text = BUNDLED.replace("smooth = true", "").replace("ambient = 0.2", "")
        bare = load_face_scene(write(tmp_path, text))
        assert bare.mesh_smooth is True and bare.ambient == 0.0 and bare.ambient_light is None

    def test_resized(self):
        scene = load_face_scene("face").resized(32, 24)
        assert (scene.camera.width, scene.camera.height, scene.camera.fov) == (32, 24, 36.0)

    def test_a_user_mesh_relative_to_the_file(self, tmp_path):
        (tmp_path / "ball.ply").write_text(GOOD_PLY)
        path = write(tmp_path, BUNDLED.replace('file = "head"', 'file = "ball.ply"'))
        assert load_face_scene(path).mesh == str((tmp_path / "ball.ply").resolve())

    def test_optional_lights_and_props(self, tmp_path):
        text = BUNDLED.split("[fill]")[0]
        scene = load_face_scene(write(tmp_path, text))
        assert scene.fill is None and scene.environment is None and scene.props == ()


REPLACEMENTS = [
    ("fov = 36.0", "fov = 180.0", "fov"),
    ("fov = 36.0", "fov = -1", "fov"),
    ("fov = 36.0", 'fov = "wide"', "fov"),
    ("width = 256", "width = 0", "width"),
    ("width = 256", "width = 2.5", "width"),
    ("height = 256", "height = 100000", "height"),
    ("position = [0.0, -0.03, 0.75]", "position = [0.0, -0.03]", "position"),
    ("position = [0.0, -0.03, 0.75]", "position = [0.0, -0.04, 0.0]", "position"),
    ("up = [0.0, 1.0, 0.0]", "up = [0.0, -0.02, -1.5]", "up"),
    ('file = "head"', 'file = "head.stl"', "file"),
    ('file = "head"', 'file = "missing.obj"', "file"),
    ("scale = 1.0", "scale = 0", "scale"),
    ("smooth = true", 'smooth = "yes"', "smooth"),
    ("ambient = 0.2", "ambient = -0.1", "ambient"),
    ("ambient = 0.2", 'ambient = "some"', "ambient"),
    ("[fill]", "[fill]\nambient = 0.2", "ambient"),
    ("temperature = 2856", "temperature = 0", "temperature"),
    ("illuminance = 1000", "illuminance = -5", "illuminance"),
    ('skin = "skin:089 skin -- caucasian (light)"', 'skin = "skin:nobody"', "skin"),
    ('skin = "skin:089 skin -- caucasian (light)"', 'skin = "skin-model:melanin=x"', "skin"),
    ('reflectance = "munsell:5YR 7/4"', 'reflectance = "munsell:5YR 99/99"', "reflectance"),
    ('shape = "cube"', 'shape = "sphere"', "shape"),
    ("size = [0.07, 0.07, 0.07]", "size = [0.07, 0.07]", "size"),
    ("size = [0.06, 0.06]", "size = [0.06, -0.06]", "size"),
    ("rotate = [0.0, 20.0, 0.0]", "rotate = [0.0, nan, 0.0]", "rotate"),
    ('name = "121 wood -- oak"', 'name = "skin"', "prop names"),
    ('name = "121 wood -- oak"', 'name = "Munsell 5YR 7/4"', "prop names"),
    ("[key]", "[keys]", "keys"),
    ("scale = 1.0", "scale = 1.0\ncolour = 1", "colour"),
    ("[environment]", "[environment]\nposition = [0, 1, 0]", "position"),
]


class TestRefusals:
    @pytest.mark.parametrize("old, new, field", REPLACEMENTS)
    def test_a_bad_field_is_named_with_the_file(self, tmp_path, old, new, field):
        assert old in BUNDLED
        path = write(tmp_path, BUNDLED.replace(old, new, 1))
        with pytest.raises(SkinrenderError) as error:
            load_face_scene(path)
        message = str(error.value)
        assert str(path) in message and field in message, message
        assert "\n" not in message

    @pytest.mark.parametrize("cut, field", [("[camera]", "camera"), ("[mesh]", "mesh"), ("[key]", "key")])
    def test_a_missing_table_is_named(self, tmp_path, cut, field):
        start = BUNDLED.index(cut)
        end = BUNDLED.index("\n[", start + 1)
        path = write(tmp_path, BUNDLED[:start] + BUNDLED[end:])
        with pytest.raises(SkinrenderError, match=f"{field}"):
            load_face_scene(path)

    def test_missing_field(self, tmp_path):
        text = "\n".join(line for line in BUNDLED.splitlines() if not line.startswith("fov ="))
        path = write(tmp_path, text)
        with pytest.raises(SkinrenderError, match="missing field 'fov'"):
            load_face_scene(path)

    @pytest.mark.parametrize("spec, match", [
        ("", "empty"), ("nowhere", "unknown face scene"), ("missing.toml", "does not exist"),
    ])
    def test_bad_names(self, spec, match):
        with pytest.raises(SkinrenderError, match=match):
            load_face_scene(spec)

    def test_a_bundled_name_wins_over_a_folder_of_that_name_here(self, tmp_path, monkeypatch):
        """``face`` is the bundled scene even where the working folder holds a folder or file named ``face``."""
        monkeypatch.chdir(tmp_path)
        (tmp_path / "face").mkdir()
        assert load_face_scene("face").name == "face"
        with pytest.raises(SkinrenderError, match="folder"):
            load_face_scene(str(tmp_path / "face"))

    def test_a_folder_and_bad_toml(self, tmp_path):
        with pytest.raises(SkinrenderError, match="folder"):
            load_face_scene(tmp_path)
        with pytest.raises(SkinrenderError, match="not valid TOML"):
            load_face_scene(write(tmp_path, "fov = ="))


class TestSkinReflectanceOf:
    def test_sets_and_indices(self):
        by_name = skin_reflectance_of("skin:089 skin -- caucasian (light)")
        assert by_name.shape == (GRID_DEFAULT.size,) and np.all((by_name > 0) & (by_name < 1))
        assert skin_reflectance_of("macbeth:#1").shape == by_name.shape

    def test_skin_model_parameters(self):
        pytest.importorskip("skinoptics")
        light = skin_reflectance_of("skin-model:melanin=0.02")
        dark = skin_reflectance_of("skin-model:melanin=0.3,blood=0.02")
        assert np.all(dark <= light) and dark.mean() < 0.5 * light.mean()
        in_vivo = skin_reflectance_of("skin-model:melanin=0.3,blood=0.02,melanin_law=exponential")
        assert in_vivo[-1] > dark[-1]  # the exponential law: in vivo melanin has fallen further in the red

    @pytest.mark.parametrize("spec, match", [
        ("skin-model:melanin=-0.1", "melanin"), ("skin-model:melanin=inf", "melanin"),
        ("skin-model:hair=1", "hair"), ("skin-model:melanin=0.1,melanin=0.3", "melanin is given twice"), ("skin:#999", "index"), ("nothing", "reflectance"),
    ])
    def test_bad_specs(self, spec, match):
        with pytest.raises(SkinrenderError, match=match):
            skin_reflectance_of(spec)

    @pytest.mark.parametrize("spec, match", [
        ("skin-model:melanin=5", r"skin-model:melanin=5.*melanin must be in \[0, 1\]"),
        ("skin-model:oxygenation=7,blood=3", "must be in"),
        ("skin-model:oxygenation=7", r"oxygenation must be in \[0, 1\]"),
        ("skin-model:scattering=0", "scattering must be in"),
        ("skin-model:n=0.5", r"n must be in \[1, 3\]"),
        ("skin-model:melanin_law=gaussian", "melanin_law must be one of power, exponential, got 'gaussian'"),  # (scattering=1e-300, refused by Kubelka–Munk's 0/0,
        # is a clear medium to adding-doubling: its Fresnel reflection, finite)
    ])
    def test_skin_model_parameters_out_of_range_refused_without_warnings(self, spec, match):
        import warnings

        pytest.importorskip("skinoptics")
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # a numpy RuntimeWarning would leak to the command line's stderr
            with pytest.raises(SkinrenderError, match=match):
                skin_reflectance_of(spec)


BINARY_PLY_HEADER = ("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                     "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n").encode()


class TestMeshFiles:
    """A user's mesh Mitsuba could not render is refused while the scene loads (an internal error mid-render before)."""

    @pytest.mark.parametrize("name, content, match", [
        ("empty.obj", b"", "is empty; expected a Wavefront OBJ"),
        ("blank.obj", b"\n  \n", "is empty"),
        ("binary.obj", bytes(range(256)) * 8, "is binary; expected a Wavefront OBJ"),
        ("nofaces.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\n", "has 3 vertices but no face"),
        ("edge.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "line 4: bad 'f' line"),
        ("negative.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n", "line 4: bad 'f' line"),
        ("beyond.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "faces indexing v 9 of 3"),
        ("normals.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n", "faces indexing vn 1 of 0"),
        ("text.obj", b"v 0 zero 0\nf 1 2 3\n", "line 1: bad 'v' line"),
        ("badheader.ply", b"ply\nformat nonsense 1.0\nelement vertex 3\nend_header\n", "no valid PLY header"),
        ("noheader.ply", b"ply\nformat ascii 1.0\nelement vertex 3\n", "no valid PLY header"),
        ("notply.ply", b"solid cube\n", "no valid PLY header"),
        ("nofaces.ply", b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n0\n0\n0\n",
         "has 3 vertices and 0 faces"),
        ("short.ply", GOOD_PLY.rsplit("\n", 3)[0].encode(), "cut short: .*\\(4 lines at least\\), it holds 2"),
        ("short_binary.ply", BINARY_PLY_HEADER + bytes(20), "cut short: .*\\(49 bytes at least\\), it holds 20"),
    ])
    def test_a_bad_mesh_is_refused_naming_the_file_and_field(self, tmp_path, name, content, match):
        (tmp_path / name).write_bytes(content)
        path = write(tmp_path, BUNDLED.replace('file = "head"', f'file = "{name}"'))
        with pytest.raises(SkinrenderError, match=match) as caught:
            load_face_scene(path)
        message = str(caught.value)
        assert message.startswith(f"{path}: [mesh]: field 'file': mesh {tmp_path / name}") and "\n" not in message

    @pytest.mark.parametrize("kind, match", [("pipe", "a named pipe, not a regular file"),
                                             ("device", "a device, not a regular file"),
                                             ("big", "is larger than a mesh")])
    def test_a_mesh_that_is_no_regular_file_is_refused_unread(self, tmp_path, kind, match):
        """A named pipe would block the check and Mitsuba; /dev/zero would be read without end."""
        import os

        from skinrender.files import MESH_BYTES_MAX

        mesh = tmp_path / "head.obj"
        if kind == "pipe":
            os.mkfifo(mesh)
        elif kind == "device":
            mesh.symlink_to("/dev/zero")
        else:
            with open(mesh, "wb") as handle:
                handle.truncate(MESH_BYTES_MAX + 1)
        path = write(tmp_path, BUNDLED.replace('file = "head"', 'file = "head.obj"'))
        with pytest.raises(SkinrenderError, match=match) as caught:
            load_face_scene(path)
        assert str(caught.value).startswith(f"{path}: [mesh]: field 'file': mesh {mesh}: ")

    @pytest.mark.parametrize("name, content", [
        ("tri.obj", GOOD_OBJ.encode()),
        ("quad.obj", b"# a quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1 4/1\n"),
        ("tri.ply", GOOD_PLY.encode()),
        ("tri_binary.ply", BINARY_PLY_HEADER + bytes(36) + bytes([3]) + bytes(12)),
    ])
    def test_a_good_mesh_loads(self, tmp_path, name, content):
        (tmp_path / name).write_bytes(content)
        path = write(tmp_path, BUNDLED.replace('file = "head"', f'file = "{name}"'))
        assert load_face_scene(path).mesh == str((tmp_path / name).resolve())

    def test_mitsuba_renders_what_the_check_passes(self, tmp_path):
        """The meshes the check passes are ones Mitsuba's plugins load with faces (the check is not too strict)."""
        pytest.importorskip("mitsuba")
        from skinrender.rendering.variants import choose_variant, mitsuba

        mi = mitsuba(choose_variant())
        for name, content in (("tri.obj", GOOD_OBJ), ("tri.ply", GOOD_PLY)):
            (tmp_path / name).write_text(content)
            path = write(tmp_path, BUNDLED.replace('file = "head"', f'file = "{name}"'))
            shape = mi.load_dict({"type": name[-3:], "filename": load_face_scene(path).mesh, "face_normals": True})
            assert shape.face_count() == 1
