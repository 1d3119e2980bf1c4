"""
Tests for :mod:`skinrender.rendering.request`: a chart's request is one frozen, checked object, built the same way
through every front door (Python, the command line, the pytest plugin), every bound checked before any render
(issue 35 item 1, issue 36's late refusals).
"""

from __future__ import annotations

import dataclasses

import pytest

import skinrender as sr
from skinrender.cli import main
from skinrender.errors import SkinrenderError
from skinrender.rendering.request import ChartRequest, chart_request
from skinrender.rendering.settings import SEED_MAX

CAM = "gbell:9@450,540,610"


@pytest.fixture
def no_render(monkeypatch):
    """Every chart renderer (Lambertian, slabs, sensor) replaced by one that fails the test: what is refused must be
    refused before any render."""
    import skinrender.rendering.chart_effects as effects

    def rendered(*args, **kwargs):
        raise AssertionError("rendered before the refusal")

    for name in ("_Lambertian", "_Slabs"):
        monkeypatch.setattr(effects, name, rendered)
    import skinrender.rendering.imaging as imaging

    monkeypatch.setattr(imaging, "render_imaged_request", rendered)


def test_a_request_holds_objects_and_is_frozen():
    request = chart_request("macbeth", CAM, "A", 5900, spp=16, seed=3)
    assert isinstance(request, ChartRequest) and request.camera.name == sr.camera(CAM).name
    assert (request.prevailing, request.calibration, request.level.name) == (2856.0, 5900.0, "direct")
    assert request.settings == sr.RenderSettings(spp=16, seed=3) and dict(request.options) == {}
    with pytest.raises(dataclasses.FrozenInstanceError):
        request.prevailing = 3000.0  # type: ignore[misc]
    with pytest.raises(TypeError):
        request.options["noise"] = None  # type: ignore[index]
    assert dataclasses.replace(request, knee=True).knee is True  # a changed copy is checked again


def test_an_imager_adds_the_sensor_with_its_options():
    """The chart + imager composed below the command line: the request's level gains the sensor, its options
    checked there (the illuminance a chart's default unless given)."""
    request = chart_request("macbeth", CAM, "A", "A", imager="sony-imx174", exposure="0.01")
    assert request.level.name == "noise" and request.options["noise"].exposure == 0.01
    assert request.options["noise"].imager.name == "sony-imx174" and request.options["noise"].illuminance is None


@pytest.mark.parametrize("kwargs, role, words", [
    ({"seed": 2**32 - 1}, "seed", f"at most {SEED_MAX}"),
    ({"seed": -1}, "seed", "seed must be an integer"),
    ({"spp": 0}, "spp", "spp must be a positive integer"),
    ({"spp": 2**21}, "spp", "at most 1048576"),
    ({"physics": "sheen"}, "physics",
     "physics (of a chart) must be one of direct, subsurface, subsurface-volume, got 'sheen'"),
    ({"physics": "noise"}, "physics", "must be one of direct, subsurface, subsurface-volume"),  # the sensor comes with an imager
    ({"illuminance": 300}, "illuminance", "it goes with imager"),
    ({"exposure": "auto"}, "exposure", "it goes with imager"),
    ({"imager": "sony-imx174", "exposure": -1}, "exposure", "exposure must be auto or a finite number of seconds"),
    ({"imager": "sony-imx174", "illuminance": float("nan")}, "illuminance", "illuminance must be a finite number"),
    ({"imager": "nosuch"}, "imager", "nosuch"),
    ({"normalization": "whiter"}, "normalization", "normalization must be one of"),
    ({"knee": "yes"}, "knee", "knee must be True or False"),
    ({"camera": "nosuch"}, "camera", "camera"),
    ({"prevailing": "x"}, "prevailing", "prevailing"),
    ({"calibration": True}, "calibration", "calibration"),
    ({"scene": "nosuch"}, "scene", "unknown scene 'nosuch'"),
])
def test_every_bound_is_checked_where_the_request_is_built(kwargs, role, words, no_render):
    arguments = {"scene": "macbeth", "camera": CAM, "prevailing": 2856, "calibration": 5900, **kwargs}
    scene, camera, p, c = (arguments.pop(name) for name in ("scene", "camera", "prevailing", "calibration"))
    with pytest.raises(SkinrenderError) as error:
        chart_request(scene, camera, p, c, **arguments)
    assert words in str(error.value) and error.value.role == role, (error.value.role, str(error.value))


def test_subsurface_refuses_before_any_render(no_render):
    """Issue 36: ``sr.render(chart, seed=2**32-1, physics="subsurface")`` rendered 30 s, then refused "4294967296";
    a chart without a skin patch and a sensor on the slabs are refused alike, naming the argument."""
    with pytest.raises(SkinrenderError) as error:
        sr.render("skin_patches", CAM, 2856, 5900, seed=2**32 - 1, physics="subsurface", spp=1)
    assert error.value.role == "seed" and str(SEED_MAX) in str(error.value)
    with pytest.raises(SkinrenderError, match="macbeth has none") as error:
        sr.render("macbeth", CAM, 2856, 5900, physics="subsurface", spp=1)
    assert error.value.role == "physics"
    with pytest.raises(SkinrenderError, match="without an image sensor") as error:
        sr.render("skin_patches", CAM, 2856, 5900, physics="subsurface", spp=1, imager="sony-imx174")
    assert error.value.role == "imager"


def test_the_subsurface_volume_level_brings_its_sampler_unless_one_is_named():
    """The volumetric chart's sampler (SAMPLER_SUBSURFACE, calibrated there); the fast one keeps the chart's."""
    chart = sr.load_scene("skin_patches")
    assert chart_request(chart, CAM, 2856, 2856, physics="subsurface-volume").settings.sampler == "independent"
    named = chart_request(chart, CAM, 2856, 2856, physics="subsurface-volume", sampler="multijitter")
    assert named.settings.sampler == "multijitter"
    given = chart_request(chart, CAM, 2856, 2856, physics="subsurface-volume", settings=sr.RenderSettings())
    assert given.settings.sampler == "multijitter"  # a whole settings object is taken as it is
    assert chart_request("macbeth", CAM, 2856, 2856).settings.sampler == "multijitter"
    assert chart_request(chart, CAM, 2856, 2856, physics="subsurface").settings.sampler == "multijitter"


@pytest.mark.parametrize("seed, refused", [(SEED_MAX, False), (SEED_MAX + 1, True)])
def test_python_and_the_command_line_draw_the_seed_line_in_one_place(seed, refused, tmp_path, capsys, no_render):
    """Issue 36: ``sr.render("macbeth", seed=2**32-1, prevailing=2856, calibration=5900)`` is refused exactly as the
    command line refuses ``--seed 4294967295``, and the largest seed both take is the same (the calibration render
    takes seed + 1 mod 2³²: it fits)."""
    from skinrender.cli import build_parser
    from skinrender.cli.common import settings_of
    from skinrender.cli.inputs import chart_request_of, scene_of

    argv = ["render", "macbeth", "--camera", CAM, "--prevailing", "2856", "--calibration", "5900", "--seed",
            str(seed), "--spp", "1", "-o", str(tmp_path / "r.exr")]
    if not refused:  # both build the request: the command line's converters and Python's
        args = build_parser().parse_args(argv)
        cli = chart_request_of(args, scene_of(args), settings_of(args))
        assert cli.settings.seed == chart_request("macbeth", CAM, 2856, 5900, seed=seed, spp=1).settings.seed == seed
        return
    with pytest.raises(SkinrenderError) as python:
        sr.render("macbeth", CAM, 2856, 5900, seed=seed, spp=1)
    assert main([*argv, "--json"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and "--seed" in err and str(SEED_MAX) in err
    assert python.value.role == "seed" and str(SEED_MAX) in str(python.value)
