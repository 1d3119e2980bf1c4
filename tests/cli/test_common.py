"""Tests for :mod:`skinrender.cli.common`: what every command shares (here: how a document is printed)."""

from __future__ import annotations

import argparse
import math
import os

import pytest

from skinrender.cli.common import coverage_hint, emit
from skinrender.errors import SkinrenderError


def test_a_document_that_cannot_be_json_prints_nothing_not_half(capsys):
    args = argparse.Namespace(json=True)
    with pytest.raises(ValueError, match="JSON"):
        emit(args, {"first": list(range(2000)), "last": math.inf}, "text")
    assert capsys.readouterr().out == ""


def test_a_document_prints_whole(capsys):
    emit(argparse.Namespace(json=True), {"a": [1, 2]}, "text")
    emit(argparse.Namespace(json=False), {"a": [1, 2]}, "as text\n\n")
    assert capsys.readouterr().out == '{\n  "a": [\n    1,\n    2\n  ]\n}\nas text\n'


def coverage_error():
    """The refusal of spectra that do not cover the grid, as :func:`skinrender.spectra.resample` raises it."""
    from skinrender.spectra import WavelengthGrid, resample

    with pytest.raises(SkinrenderError) as caught:
        resample([420.0, 680.0], [[0.5, 0.5]], WavelengthGrid(400, 700, 1), source="c.csv")
    return caught.value


@pytest.mark.parametrize("flags, advice", [
    ({"grid": "400:700:1", "extrapolation": "refuse"},
     "choose a --grid inside the data or an --extrapolation ('zero' or 'constant')"),
    ({"grid": "400:700:1", "extrapolation": "constant"},
     "choose a --grid inside the data (--extrapolation constant applies to CSV files, not to these spectra)"),
    ({"grid": "400:700:1"}, "choose a --grid inside the data"),
    ({}, "this command integrates over that grid: give spectra that cover it"),
])
def test_coverage_advice_names_only_the_flags_the_command_has(flags, advice):
    """The advice is chosen by the error's ``cause`` field, not by matching its words; an --extrapolation given
    that did not apply is not advised again (seen: ``response --grid 300:900:1 --extrapolation constant``)."""
    error = coverage_error()
    assert error.cause == "coverage" and str(error).endswith(error.hint)  # the library's own words keep the hint
    line = coverage_hint(error, argparse.Namespace(**flags))
    assert line == "c.csv: measured over 420–680 nm, which does not cover the grid 400–700 nm; " + advice


def test_other_messages_keep_their_words():
    error = SkinrenderError("--seed must be an integer")
    assert coverage_hint(error, argparse.Namespace(grid="400:700:1")) == "--seed must be an integer"


CAM = "gbell:9@450,540,610"
LIGHTS = ["--prevailing", "A", "--calibration", "H"]
LONG = "n" * 300


@pytest.fixture(scope="module")
def odd_inputs(tmp_path_factory) -> dict:
    """Inputs that are not regular files of a sensible size: a named pipe, a device behind a link, a folder, an
    oversized (sparse) file and a name too long, each as a .csv and as a .toml."""
    folder = tmp_path_factory.mktemp("odd")
    paths = {}
    for suffix in (".csv", ".toml"):
        os.mkfifo(folder / f"pipe{suffix}")
        (folder / f"zero{suffix}").symlink_to("/dev/zero")
        (folder / f"folder{suffix}").mkdir()
        with open(folder / f"big{suffix}", "wb") as handle:
            handle.truncate(100_000_000)
        for kind, reason in (("pipe", "a named pipe"), ("zero", "a device"), ("folder", "a folder"),
                             ("big", "is larger than"), ("long", "the name is too long")):
            paths[kind + suffix] = (folder / (LONG + suffix if kind == "long" else f"{kind}{suffix}"), reason)
    return paths


INPUTS = {
    "--camera": (["response", "--reflectances", "skin", *LIGHTS], ".csv"),
    "--reflectances": (["response", "--camera", CAM, *LIGHTS], ".csv"),
    "--prevailing": (["response", "--camera", CAM, "--reflectances", "skin", "--calibration", "A"], ".csv"),
    "--skin": (["gamut", "--camera", CAM, "--ratio", "--all-calibrations"], ".csv"),
    "SCENE": (["render", "--camera", CAM, *LIGHTS], ".toml"),
    "--scene": (["ladder", "--camera", CAM, *LIGHTS], ".toml"),
    "--imager": (["score", "--camera", CAM, "--illuminance", "500"], ".toml"),
}
"""Every kind of input file, each given where a command reads it: the argv without it and its suffix."""


@pytest.mark.parametrize("kind", ["pipe", "zero", "folder", "big", "long"])
@pytest.mark.parametrize("name", list(INPUTS))
def test_an_input_that_is_no_regular_file_is_refused_naming_its_flag(name, kind, odd_inputs, capsys):
    """Seen: a named pipe blocked forever, a link to /dev/zero was read to 12.8 GB, a name too long was an
    internal error: each is now refused at once, one line naming the flag and what the file is."""
    from .refusal import assert_refused

    argv, suffix = INPUTS[name]
    path, reason = odd_inputs[kind + suffix]
    argv = [*argv[:1], str(path), *argv[1:]] if name == "SCENE" else [*argv, name, str(path)]
    line = assert_refused(argv, name, capsys)
    assert reason in line and len(line) < 400


OUTPUTS = {
    "render": (["render", "macbeth", "--camera", CAM, *LIGHTS, "-o"], ".exr"),
    "detect": (["detect", "macbeth", "--camera", CAM, *LIGHTS, "-o"], ".png"),
    "render --figure": (["render", "macbeth", "--camera", CAM, *LIGHTS, "--figure"], ".png"),
    "locus": (["locus", "--camera", CAM, "--plot"], ".png"),
    "ptc": (["ptc", "--camera", CAM, "--imager", "sony-imx174", "--plot"], ".png"),
    "search": (["search", "--sensor", "9", "--positions", "400:700:50", "--csv"], ".csv"),
    "ladder": (["ladder", "--camera", CAM, *LIGHTS, "--plot"], ".png"),
    "face-sweep": (["face-sweep", "--camera", CAM, "--csv"], ".csv"),
    "bench": (["bench", "render", "--plot"], ".png"),
    "reproduce": (["reproduce", "-o"], ""),
}
"""Every output flag: the argv up to the flag, and the suffix its file takes."""


@pytest.mark.parametrize("case", ["long", "long folder", "dangling"])
@pytest.mark.parametrize("command", list(OUTPUTS))
def test_an_output_that_cannot_be_written_is_refused_before_the_work(command, case, tmp_path, capsys):
    """Seen: a name too long for -o, --camera … and a dangling-link -o were internal errors after the work."""
    from .refusal import assert_refused

    argv, suffix = OUTPUTS[command]
    if case == "dangling":
        path = tmp_path / f"link{suffix}"
        path.symlink_to(tmp_path / "gone" / f"x{suffix}")
    else:
        path = tmp_path / (f"{LONG}{suffix}" if case == "long" else f"{LONG}/x{suffix}")
    line = assert_refused([*argv, path], argv[-1], capsys, output=tmp_path)
    assert ("the name is too long" if case != "dangling" else "a symbolic link to nothing") in line
