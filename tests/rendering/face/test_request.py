"""
Tests for :mod:`skinrender.rendering.face.request`: a face's request is built once, as every door builds it; the
scene it holds is the one rendered; the sensor's options are the ``noise`` effect's, refused without it.
"""

from __future__ import annotations

import pytest

import skinrender as sr
from skinrender.errors import SkinrenderError
from skinrender.rendering.face.request import SPP_FACE_DEFAULT, FaceRequest, face_request
from skinrender.rendering.face.scene import load_face_scene
from skinrender.rendering.settings import SEED_MAX

CAM = "gbell:9@450,540,610"


def test_the_scene_is_the_one_rendered():
    """Resized, its key light at ``prevailing`` and every light scaled to the sensor's illuminance; the calibration
    the prevailing light where not given; the spp a face's default."""
    scene = load_face_scene("face")
    request = face_request("face", CAM, 3300, physics="noise", size=(20, 10), illuminance=2 * scene.key.illuminance)
    assert isinstance(request, FaceRequest) and request.pixels == 200 and request.settings.spp == SPP_FACE_DEFAULT
    assert request.scene.key.temperature == request.prevailing == request.calibration == 3300.0
    assert request.scene.key.illuminance == pytest.approx(2 * scene.key.illuminance)
    assert request.skin == scene.skin and request.level.name == "noise"
    kept = face_request(scene, CAM)
    assert kept.scene is scene and kept.prevailing == scene.key.temperature  # nothing to change: the same scene


def test_an_imager_adds_noise_to_any_level():
    request = face_request("face", CAM, physics="sheen", imager="sony-imx174", size=8)
    assert request.level.name == "sheen+noise" and request.options["noise"].imager.name == "sony-imx174"
    assert face_request("face", CAM, physics="noise", size=8).options["noise"].imager is None  # the default's


@pytest.mark.parametrize("kwargs, role", [
    ({"exposure": -1}, "exposure"),  # issue 36: sr.render("face", …, exposure=-1) was accepted
    ({"physics": "noise", "exposure": -1}, "exposure"),
    ({"exposure": "auto"}, "exposure"),  # nothing would see it without the sensor
    ({"illuminance": 300}, "illuminance"),
    ({"physics": "noise", "illuminance": 0}, "illuminance"),
    ({"seed": SEED_MAX + 1}, "seed"),
    ({"spp": 1 << 20, "size": 64}, "spp"),  # more samples than one pass holds
    ({"size": 0}, "size"),
    ({"size": 2.5}, "size"),
    ({"skin": "skin-model:hair=1"}, "skin"),
    ({"physics": "glossy"}, "physics"),
    ({"physics": "subsurface+subsurface"}, "physics"),
    ({"camera": None}, "camera"),
    ({"prevailing": "nosuch.csv"}, "prevailing"),
])
def test_refusals_name_the_argument(kwargs, role):
    arguments = {"camera": CAM, "size": 8, **kwargs}
    with pytest.raises(SkinrenderError) as error:
        face_request("face", **arguments)
    assert error.value.role == role, (error.value.role, str(error.value))
    with pytest.raises(SkinrenderError) as python:  # the public door says the same
        sr.render("face", **arguments)
    assert python.value.role == role


def test_a_level_whose_lights_the_scene_lacks_is_refused_before_rendering():
    from dataclasses import replace

    lone = replace(load_face_scene("face"), fill=None, environment=None)
    with pytest.raises(SkinrenderError, match="mixed"):
        face_request(lone, CAM, physics="mixed", size=8)
