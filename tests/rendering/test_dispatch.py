"""
Tests for :mod:`skinrender.rendering.dispatch`: ``skinrender.render`` renders charts and faces alike, each as
its own renderer does, and refuses an option of the other kind of scene.
"""

from __future__ import annotations

import numpy as np
import pytest

import skinrender as sr
from skinrender.rendering.balance import Rendering
from skinrender.rendering.balance import render as render_chart
from skinrender.rendering.face import FaceRendering, load_face_scene, render_face

pytest.importorskip("mitsuba")

CAMERA = "gbell:9@450,540,610"


def test_a_face_from_python_as_from_its_renderer():
    """The issue's call: ``sr.render("face", camera=…, physics=…)`` (it failed with "unknown scene 'face'")."""
    result = sr.render("face", camera=CAMERA, prevailing=2856, calibration=5900, physics="sheen", spp=4, size=16,
                       seed=2)
    assert isinstance(result, FaceRendering) and result.physics == "sheen" and result.image.shape == (16, 16, 3)
    same = render_face(CAMERA, "face", 2856, 5900, physics="sheen", spp=4, size=16, seed=2)
    assert np.array_equal(result.image, same.image) and np.array_equal(result.labels, same.labels)


def test_a_face_scene_object_and_the_scenes_own_lights():
    scene = load_face_scene("face")
    result = sr.render(scene, CAMERA, spp=1, size=8)
    assert result.prevailing == result.calibration == scene.key.temperature


def test_a_chart_as_before_positionally_and_by_name():
    result = sr.render("macbeth", CAMERA, 2856, 2300, spp=4)
    assert isinstance(result, Rendering)
    same = render_chart("macbeth", CAMERA, 2856, 2300, spp=4)
    assert np.array_equal(result.image, same.image)
    named = sr.render(scene="macbeth", camera_=CAMERA, prevailing=2856, calibration=2300, spp=4)
    assert np.array_equal(named.image, same.image)


@pytest.mark.parametrize("kwargs, message", [
    ({"scene": "macbeth", "skin": "skin:#0"}, "render: skin is not an option of a chart scene; its options: "
                                               "normalization, knee, spp"),
    ({"scene": "macbeth", "physics": "sheen"}, "physics (of a chart) must be one of direct, subsurface, got 'sheen'"),
    ({"scene": "face", "normalization": "white", "knee": True}, "render: knee, normalization are not options of a "
                                                                 "face scene; its options: skin, physics"),
    ({"scene": "macbeth", "prevailing": None}, "prevailing: a chart render needs the prevailing light"),
    ({"scene": "macbeth", "camera": None}, "camera: name the camera"),
    ({"scene": "macbeth", "camera_": CAMERA}, "render: give the camera once"),
    ({"scene": "nothing"}, "unknown scene 'nothing'; bundled scenes: face_chart, macbeth, skin_patches (charts), "
                           "face (faces)"),
])
def test_refusals(kwargs, message):
    arguments = {"camera": CAMERA, "prevailing": 2856, "calibration": 2856, **kwargs}
    with pytest.raises(sr.SkinrenderError) as error:
        sr.render(**arguments)
    assert str(error.value).startswith(message)
