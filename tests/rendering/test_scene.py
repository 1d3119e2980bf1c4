"""Tests for :mod:`skinrender.scene`: the bundled charts and clear errors for bad scene files."""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.rendering.scene import list_scenes, load_chart_scene
from skinrender.spectra import GRID_DEFAULT

GOOD = """
name = "mine"
columns = 2
patch_px = 6
gap_px = 1
border_px = 1
[[patch]]
reflectance = "macbeth:dark skin"
skin = false
[[patch]]
name = "half grey"
reflectance = "grey:0.5"
"""


def test_bundled_scenes():
    assert list_scenes() == ["face_chart", "macbeth", "skin_patches"]
    macbeth = load_chart_scene("macbeth")
    assert len(macbeth.patches) == 25 and macbeth.patches[-1].name == "white reference"
    assert macbeth.size == (98, 82)
    face = load_chart_scene("face_chart")
    skin = [p for p in face.patches if p.skin]
    assert 10 <= len(skin) < len(face.patches) - 10  # skin beside as many confusers
    values = face.reflectances(GRID_DEFAULT)
    assert np.all((values >= 0) & (values <= 1))
    means = values[[i for i, p in enumerate(face.patches) if p.skin]].mean(axis=1)
    assert means.max() / means.min() > 5  # light to very dark skin


def test_patch_boxes_do_not_overlap():
    scene = load_chart_scene("skin_patches")
    mask = np.zeros(scene.size[::-1], dtype=int)
    for i in range(len(scene.patches)):
        x0, y0, x1, y1 = scene.patch_box(i)
        mask[y0:y1, x0:x1] += 1
    assert mask.max() == 1


def test_user_scene(tmp_path):
    path = tmp_path / "mine.toml"
    path.write_text(GOOD)
    scene = load_chart_scene(str(path))
    assert [p.name for p in scene.patches] == ["dark skin", "half grey", "white reference"]
    np.testing.assert_allclose(scene.reflectances(GRID_DEFAULT)[1], 0.5)


@pytest.mark.parametrize(
    "change, message",
    [
        (("columns = 2", "columns = 0"), "'columns' must be ≥ 1"),
        (("columns = 2", "columns = \"two\""), "'columns' must be an integer"),
        (("columns = 2\n", ""), "missing field 'columns'"),
        (("grey:0.5", "grey:1.5"), "grey reflectance"),
        (("macbeth:dark skin", "macbeth:no such"), "no sample 'no such'"),
        (("macbeth:dark skin", "nosuchset:1"), "nosuchset"),
        (("skin = false", "skin = 3"), "'skin' must be true or false"),
        (("border_px = 1", "border_px = 3"), "border_px"),
        (("name = \"mine\"", "colour = \"red\""), "unknown field"),
        (("[[patch]]", "[[patches]]"), "unknown field"),
    ],
)
def test_bad_scene_names_the_field(tmp_path, change, message):
    path = tmp_path / "bad.toml"
    path.write_text(GOOD.replace(*change, 1))
    with pytest.raises(SkinrenderError, match=message) as error:
        load_chart_scene(str(path))
    assert str(path) in str(error.value)


def test_unknown_scene_lists_the_known():
    with pytest.raises(SkinrenderError, match="face_chart, macbeth, skin_patches"):
        load_chart_scene("nope")


def test_not_toml(tmp_path):
    path = tmp_path / "x.toml"
    path.write_text("columns = = 2")
    with pytest.raises(SkinrenderError, match="not valid TOML"):
        load_chart_scene(str(path))


def test_a_bundled_name_wins_over_a_file_of_that_name_here(tmp_path, monkeypatch):
    """``macbeth`` is the bundled chart even where the working folder holds a file named ``macbeth``."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "macbeth").write_text("not a scene")
    assert load_chart_scene("macbeth").name == "macbeth"
    with pytest.raises(SkinrenderError, match="unknown scene"):
        load_chart_scene("nowhere")
