"""
Tests for :mod:`skinrender.cli.inputs`: a command parses each input once (issue 26) — the scene is loaded once
(charts and faces alike), ``--grid`` parsed once and ``--camera`` once — and everything below the command line
takes the objects. The loaders are counted wherever a module holds them (every binding in every loaded
``skinrender`` module is replaced by a counting one), so a second parse anywhere below is caught.
"""

from __future__ import annotations

import sys
from collections import Counter
from pathlib import Path

import pytest

from skinrender.cli.inputs import ChartInputs, chart_inputs, chart_only, scene_of
from skinrender.errors import SkinrenderError
from skinrender.model import camera as camera_module
from skinrender.rendering import scene as chart_scene_module
from skinrender.rendering.face import scene as face_scene_module
from skinrender.spectra import WavelengthGrid

from .refusal import run

pytest.importorskip("mitsuba")

CAM = "gbell:9@450,540,610"


@pytest.fixture
def parses(monkeypatch) -> Counter:
    """How often each input was parsed from its text: ``scene`` (a chart or face scene loaded from a spec),
    ``camera`` (a camera made from a spec) and ``grid`` (``START:END:STEP`` parsed)."""
    counts: Counter = Counter()

    def counting(kind: str, original):
        def wrapper(spec, *args, **kwargs):
            if isinstance(spec, (str, Path)):  # an object passed on is no parse
                counts[kind] += 1
            return original(spec, *args, **kwargs)
        return wrapper

    for kind, module, name in (("scene", chart_scene_module, "load_chart_scene"),
                               ("scene", face_scene_module, "load_face_scene"),
                               ("camera", camera_module, "camera")):
        original = getattr(module, name)
        wrapper = counting(kind, original)
        for loaded in [m for n, m in sys.modules.items() if n == "skinrender" or n.startswith("skinrender.")]:
            for attribute, value in list(vars(loaded).items()):
                if value is original:
                    monkeypatch.setattr(loaded, attribute, wrapper)
    parse = WavelengthGrid.parse.__func__

    def parse_counted(cls, text):
        counts["grid"] += 1
        return parse(cls, text)

    monkeypatch.setattr(WavelengthGrid, "parse", classmethod(parse_counted))
    return counts


LIGHTS = ["--camera", CAM, "--prevailing", "3300", "--calibration", "4800"]


@pytest.mark.parametrize("command, grids", [
    (["render", "{chart}", *LIGHTS, "--spp", "4", "--grid", "400:700:2", "-o", "{tmp}/r.exr"], 1),
    (["render", "{chart}", *LIGHTS, "--spp", "4", "--imager", "sony-imx174", "-o", "{tmp}/r.exr"], 1),
    (["validate", "{chart}", *LIGHTS, "--spp", "4", "--tolerance", "0.5", "--gamut"], 1),
    (["validate", "{chart}", *LIGHTS, "--spp", "auto", "--tolerance", "0.5"], 1),
    (["detect", "{chart}", *LIGHTS, "--spp", "4", "-o", "{tmp}/d.png"], 0),  # detect has no --grid
    # a face renders on the default grid: its --grid is checked as given, never parsed
    (["render", "face", *LIGHTS, "--spp", "1", "--size", "8", "-o", "{tmp}/f.exr"], 0),
    (["detect", "face", *LIGHTS, "--spp", "1", "--size", "8", "-o", "{tmp}/f.png"], 0),
    (["ladder", *LIGHTS, "--spp", "1", "--size", "8", "--levels", "direct"], 0),
])
def test_each_input_is_parsed_once_per_command(command, grids, small_chart, tmp_path, parses, capsys):
    argv = [part.format(chart=small_chart, tmp=tmp_path) for part in command]
    status, out, err = run([*argv, "--json"], capsys)
    assert status in (0, 1, 3), err[-800:]
    assert parses == {"scene": 1, "camera": 1, **({"grid": grids} if grids else {})}, " ".join(argv)


def test_scene_of_loads_charts_and_faces(small_chart):
    from argparse import Namespace

    from skinrender.rendering.face.scene import FaceScene
    from skinrender.rendering.scene import ChartScene

    assert isinstance(scene_of(Namespace(scene=str(small_chart))), ChartScene)
    assert isinstance(scene_of(Namespace(scene="face")), FaceScene)
    with pytest.raises(SkinrenderError, match="^SCENE: unknown scene 'nowhere'; bundled scenes: .*face"):
        scene_of(Namespace(scene="nowhere"))


def test_chart_inputs_are_objects_with_the_flags_named(small_chart, tmp_path):
    """The camera keeps its --extrapolation; the lights are kelvin; a refusal names its flag."""
    from argparse import Namespace

    import numpy as np

    from skinrender.rendering.scene import load_chart_scene

    chart = load_chart_scene(small_chart)
    wavelengths = np.arange(420.0, 681.0, 5.0)
    path = tmp_path / "short.csv"
    np.savetxt(path, np.column_stack([wavelengths, np.ones((wavelengths.size, 3))]), delimiter=",",
               header="wavelength_nm,R,G,B", comments="")
    args = Namespace(camera=str(path), extrapolation="zero", prevailing="A", calibration="3300", grid="400:700:5",
                     normalization="white", knee=False)
    inputs = chart_inputs(args, chart)
    assert isinstance(inputs, ChartInputs) and inputs.scene is chart
    assert inputs.camera.extrapolation == "zero" and (inputs.prevailing, inputs.calibration) == (2856, 3300)
    assert inputs.grid == WavelengthGrid(400, 700, 5) and inputs.keywords()["camera_"] is inputs.camera
    light = tmp_path / "light.csv"
    np.savetxt(light, np.column_stack([wavelengths, np.ones(wavelengths.size)]), delimiter=",",
               header="wavelength_nm,light", comments="")
    with pytest.raises(SkinrenderError, match="^--calibration: rendering needs a Planckian") as error:
        chart_inputs(Namespace(**{**vars(args), "calibration": str(light)}), chart)
    assert error.value.flag == "--calibration"


def test_chart_only_refuses_the_face_flags_naming_them():
    from argparse import Namespace

    with pytest.raises(SkinrenderError, match="^--physics, --size: go with a face scene") as error:
        chart_only(Namespace(physics="sheen", skin=None, size="8"))
    assert error.value.flag == "--physics"
    chart_only(Namespace(physics="direct", skin="skin:#1", size=None), skin=False)  # detect's --skin: the locus's


@pytest.mark.parametrize("command, expected", [
    (["illuminants", "--camera", CAM, "--count", "4", "--grid", "400:700:5"], {"camera": 1, "grid": 1}),
    (["response", "--camera", CAM, "--reflectances", "macbeth", "--prevailing", "2856", "--calibration", "2300",
      "--grid", "400:700:5"], {"camera": 1, "grid": 1}),
    (["gamut", "--camera", CAM, "--reflectances", "skin", "--all-calibrations", "--grid", "400:700:5"],
     {"camera": 1, "grid": 1}),
    (["locus", "--camera", CAM], {"camera": 1}),
    (["search", "--sensor", "9", "--positions", "400:700:100", "--workers", "1", "--quiet"], {"grid": 1}),
])
def test_the_analytic_commands_parse_each_input_once(command, expected, parses, capsys):
    status, out, err = run([*command, "--json"], capsys)
    assert status == 0, err[-800:]
    assert parses == expected, " ".join(command)
