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
    ({"scene": "macbeth", "physics": "sheen"}, "physics (of a chart) must be one of direct, subsurface, "
                                               "subsurface-volume, got 'sheen'"),
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


def test_validate_a_face_from_python_with_its_verdict_bound_and_spp_needed():
    """Issue 23 item 4: ``sr.validate`` of a face returns the verdict, the bound and the spp it takes."""
    from skinrender.rendering.face.validation import FaceValidation, validate_face

    result = sr.validate("face", CAMERA, 2856, 2856, physics="direct", spp=48, size=16, seed=3, limits=())
    assert isinstance(result, FaceValidation)
    assert [c.name for c in result.checks] == ["shading_cancels", "detection", "eq4_shift"]
    shift = result.checks[-1]  # the NCC budget's diagnostic: the bound and spp_needed are still its
    assert result.bound == shift.bound and result.bound >= shift.statistic
    document = result.document()
    assert document["bound"] == result.bound and document["spp_needed"] == result.spp_needed
    assert shift.outcome == "pass" and result.spp_needed is not None  # a direct face: Eq. 4 holds
    assert 16 * result.replicates <= result.spp_needed <= result.spp  # shown within at the spp it had
    same = validate_face(CAMERA, "face", 2856, 2856, physics="direct", spp=48, size=16, seed=3, limits=())
    assert same.bound == result.bound


def test_validate_a_face_takes_the_clis_skin_set_and_detection_tolerance():
    """``validate face --skin-set … --detection-tolerance …`` from Python (they were "not an option of a face
    scene", though :func:`validate_face` takes both)."""
    result = sr.validate("face", CAMERA, 2856, 2856, physics="direct", spp=8, size=8, skin_set="skin-tones",
                         detection_tolerance=0.05)
    document = result.document()
    assert document["skin_set"] == "skin-tones" and document["detection"]["tolerance"] == 0.05
    for keywords, role in (({"skin_set": "nosuch"}, "skin_set"), ({"detection_tolerance": 2.0}, "detection_tolerance"),
                           ({"limits": ("nosuch",)}, "limits")):  # refused before any render, naming the argument
        with pytest.raises(sr.SkinrenderError) as error:
            sr.validate("face", CAMERA, 2856, 2856, physics="direct", spp=48, size=16, **keywords)
        assert error.value.role == role and str(error.value).startswith(role)


def test_a_grid_as_text_as_the_cli_takes_it():
    """``grid="400:700:5"`` as ``--grid 400:700:5`` (it was refused, and with ``spectral=True`` it raised a bare
    AttributeError)."""
    text = sr.render("macbeth", CAMERA, 5900, 2856, spp=4, grid="400:700:5")
    grid = sr.render("macbeth", CAMERA, 5900, 2856, spp=4, grid=sr.WavelengthGrid(400, 700, 5))
    assert np.array_equal(text.image, grid.image)
    spectral = sr.render("macbeth", None, 5900, spp=4, grid="400:700:5", spectral=True)
    assert spectral.grid == sr.WavelengthGrid(400, 700, 5)
    for spectral in (False, True):
        with pytest.raises(sr.SkinrenderError) as error:
            sr.render("macbeth", None if spectral else CAMERA, 5900, None if spectral else 2856, spp=4,
                      grid="400:700", spectral=spectral)
        assert error.value.role == "grid" and str(error.value).startswith("grid must be START:END:STEP")


def test_the_knee_through_an_image_sensor_as_render_imager_knee_applies_it():
    """``knee=True`` with an ``imager``: the knee on the sensor's Eq. 4 image, as ``render --imager --knee`` (Python
    dropped it silently); a validation through a sensor refuses it, as ``validate --imager --knee`` does."""
    from skinrender.model.response import knee

    plain = sr.render("macbeth", CAMERA, 5900, 2856, spp=4, imager="sony-imx174")
    kneed = sr.render("macbeth", CAMERA, 5900, 2856, spp=4, imager="sony-imx174", knee=True)
    assert kneed.knee and not plain.knee and plain.image.max() > 255
    np.testing.assert_array_equal(kneed.image, knee(plain.image).astype(np.float32))
    with pytest.raises(sr.SkinrenderError) as error:
        sr.validate("macbeth", CAMERA, 5900, 2856, spp=4, imager="sony-imx174", knee=True)
    assert error.value.role == "knee"


def test_quality_as_the_cli_takes_it():
    """``quality="draft"`` as ``--quality draft``: the preset's spp unless spp is given; not with settings."""
    assert sr.render("macbeth", CAMERA, 5900, 2856, quality="draft").raw[0].spp == 16
    assert sr.render("macbeth", CAMERA, 5900, 2856, quality="draft", spp=8).raw[0].spp == 8
    assert sr.render("face", CAMERA, 2856, 2856, quality="draft", size=8).spp == 16
    for keywords in ({"quality": "best"}, {"quality": "draft", "settings": sr.RenderSettings(spp=4)}):
        with pytest.raises(sr.SkinrenderError) as error:
            sr.render("macbeth", CAMERA, 5900, 2856, **keywords)
        assert error.value.role == "quality"


def test_validate_a_chart_from_python_as_before():
    from skinrender.rendering.validation import Validation
    from skinrender.rendering.validation import validate as validate_chart

    result = sr.validate("macbeth", CAMERA, 2856, 2300, spp=4, seed=1, tolerance=0.002)
    assert isinstance(result, Validation) and result.verdict.outcome != "pass"
    same = validate_chart("macbeth", CAMERA, 2856, 2300, spp=4, seed=1, tolerance=0.002)
    assert result.bound == same.bound and result.spp_needed == same.spp_needed > 4


def test_validate_a_chart_with_spp_auto_from_python_as_the_cli_does(capsys):
    """``spp="auto"`` with a tolerance: the pilots and the spp chosen, as ``validate --spp auto`` (it was refused:
    "spp must be a positive integer")."""
    import json

    from skinrender.cli import main

    result = sr.validate("macbeth", CAMERA, 2856, 2300, spp="auto", tolerance=0.05, seed=3)
    choice = result.spp_auto
    assert [p["spp"] for p in choice["pilots"]] == [16, 64] and "pilots at 16 and 64 spp" in choice["why"]
    assert result.rendering.raw[0].spp == choice["spp"] and result.verdict.outcome in ("pass", "inconclusive")
    capsys.readouterr()
    status = main(["validate", "macbeth", "--camera", CAMERA, "--prevailing", "2856", "--calibration", "2300",
                   "--spp", "auto", "--tolerance", "0.05", "--seed", "3", "--json"])
    cli = json.loads(capsys.readouterr().out)
    def timeless(chosen):  # the pilots' seconds are wall times
        return {**chosen, "pilots": [{k: v for k, v in p.items() if k != "seconds"} for p in chosen["pilots"]]}

    assert timeless(cli["spp_auto"]) == timeless(choice) and cli["verdict"] == result.verdict.outcome
    assert status == cli["exit_status"]
    assert sr.validate("macbeth", CAMERA, 2856, 2300, spp=12, tolerance=0.05).spp_auto is None


@pytest.mark.parametrize("kwargs, message, role", [
    ({"scene": "macbeth", "spp": "auto"}, "spp='auto' renders at the smallest spp expected to pass tolerance",
     "tolerance"),
    ({"scene": "face", "spp": "auto"}, "spp='auto' goes with a chart's validation", "spp"),
    ({"scene": "macbeth", "spp": "auto", "tolerance": 1e-7}, "tolerance 1e-07: about", "tolerance"),
])
def test_spp_auto_refusals_name_their_argument(kwargs, message, role):
    arguments = {"camera": CAMERA, "prevailing": 2856, "calibration": 2856, **kwargs}
    with pytest.raises(sr.SkinrenderError) as error:
        sr.validate(**arguments)
    assert str(error.value).startswith(message) and error.value.role == role


@pytest.mark.parametrize("kwargs, message", [
    ({"scene": "face", "tolerance": 0.1}, "validate: tolerance is not an option of a face scene; its options: skin"),
    ({"scene": "macbeth", "skin": "skin:#0"}, "validate: skin is not an option of a chart scene"),
    ({"scene": "macbeth", "physics": "sheen"}, "physics (of a chart) must be one of direct, subsurface, "
                                               "subsurface-volume, got 'sheen'"),
    ({"scene": "macbeth", "calibration": None}, "calibration: a chart validation needs the calibration light"),
    ({"scene": "macbeth", "camera": None}, "camera: name the camera"),
])
def test_validate_refusals(kwargs, message):
    arguments = {"camera": CAMERA, "prevailing": 2856, "calibration": 2856, **kwargs}
    with pytest.raises(sr.SkinrenderError) as error:
        sr.validate(**arguments)
    assert str(error.value).startswith(message)


def test_a_spectral_render_of_a_chart_and_a_face():
    """``spectral=True``: no camera, no calibration; a ``SpectralImage`` that any camera sees through."""
    chart = sr.render("macbeth", prevailing=2856, spectral=True, spp=2, bands="400:700:50")
    assert isinstance(chart, sr.SpectralImage) and chart.kind == "chart" and chart.image.shape[-1] == 7
    face = sr.render("face", prevailing=2856, spectral=True, spp=1, size=8, bands="400:700:50", physics="sheen")
    assert face.kind == "face" and face.physics == "sheen"
    assert isinstance(face.through(CAMERA, 5900), FaceRendering)


@pytest.mark.parametrize("call, message", [
    (dict(camera=CAMERA), "camera: a spectral render takes no camera"),
    (dict(calibration=5900), "calibration: a spectral render takes no calibration"),
    (dict(normalization="none"), "normalization is not an option of a chart scene"),
    (dict(prevailing=None), "prevailing: a chart"),
])
def test_a_spectral_render_refuses_what_it_does_not_take(call, message):
    with pytest.raises(sr.SkinrenderError, match=message):
        sr.render("macbeth", **{"prevailing": 2856, "spp": 1, **call}, spectral=True)


def test_render_cameras_takes_its_grid_as_text():
    faces = sr.render_cameras("macbeth", [CAMERA], 5900, 2856, spp=2, grid="400:700:5")
    same = sr.render_cameras("macbeth", [CAMERA], 5900, 2856, spp=2, grid=sr.WavelengthGrid(400, 700, 5))
    assert np.array_equal(faces[0].image, same[0].image)


def test_render_cameras_renders_once_for_every_camera():
    """One spectral render: each camera's result, in order, sharing the render's seed and spp."""
    results = sr.render_cameras("macbeth", [CAMERA, "Nikon 5100 (NPL)"], 2856, 5900, spp=2, bands="400:700:10")
    assert [r.camera.name for r in results] == [CAMERA, "Nikon 5100 (NPL)"]
    assert all(isinstance(r, Rendering) and r.calibration == 5900 and r.raw[0].seed == 0 for r in results)
    with pytest.raises(sr.SkinrenderError, match="outside the bands"):
        sr.render_cameras("macbeth", [CAMERA], 2856, bands="450:650:10", spp=1)
    with pytest.raises(sr.SkinrenderError, match="at least one"):
        sr.render_cameras("macbeth", [], 2856)
