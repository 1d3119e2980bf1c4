"""Bad inputs to ``illuminants``, ``response`` and ``gamut`` (:mod:`skinrender.cli.model`) are refused cleanly."""

from __future__ import annotations

import json

import pytest

from .refusal import assert_refused, bad_files, run  # noqa: F401  (fixture)

CAM = "gbell:9@450,540,610"
RESPONSE = ["response", "--camera", CAM, "--reflectances", "macbeth"]
ILLUMINANTS = ["illuminants", "--camera", CAM]
GAMUT = ["gamut", "--camera", CAM, "--reflectances", "macbeth"]


@pytest.mark.parametrize("argv, names", [
    (ILLUMINANTS[:2] + ["Sony 755"], ("--camera", "Sony 755")),
    (ILLUMINANTS[:2] + [""], "--camera"),
    (ILLUMINANTS[:2] + ["gbell:0@450,540,610"], ("--camera", "N must be > 0")),
    (ILLUMINANTS[:2] + ["gbell:9@450,540"], ("--camera", "three peak")),
    (ILLUMINANTS[:2] + ["gbell:9,b=-1@450,540,610"], ("--camera", "slope")),
    (ILLUMINANTS[:2] + ["gbell:9@-5,1,2"], "--camera"),
    (ILLUMINANTS[:2] + ["gbell:1e308@450,540,610"], "--camera"),
    (ILLUMINANTS[:2] + ["impulse@401.5,500,600"], "--camera"),
    (ILLUMINANTS[:2] + ["impulse@399,500,600"], "--camera"),
    (ILLUMINANTS[:2] + ["gbell:9@550,550,550"], "does not change"),
    (ILLUMINANTS + ["--count", "1000"], "count"),
    (ILLUMINANTS + ["--count", "81"], "distinct temperatures"),
    (ILLUMINANTS + ["--count", "1"], "count"),
    (ILLUMINANTS + ["--step", "3000"], "step"),
    (ILLUMINANTS + ["--step", "1e-6"], "candidates"),
    (ILLUMINANTS + ["--step", "0"], "step"),
    (ILLUMINANTS + ["--step", "nan"], "step"),
    (ILLUMINANTS + ["--range", "5000", "5000"], "range"),
    (ILLUMINANTS + ["--range", "10000", "2000"], "range"),
    (ILLUMINANTS + ["--range", "20", "10000", "--step", "20"], ("20K", "no light")),
    (ILLUMINANTS + ["--range", "2000", "1e9"], "candidates"),
    (ILLUMINANTS + ["--grid", "400:700:1e-6"], ("--grid", "samples")),
    (ILLUMINANTS + ["--grid", "400:400:1"], ("--grid", "two samples")),
    (ILLUMINANTS + ["--grid", "700:400:1"], "--grid"),
    (ILLUMINANTS + ["--grid", "400:700"], "--grid"),
    (ILLUMINANTS + ["--grid", "400:700:7"], "--grid"),
    (ILLUMINANTS + ["--grid", "a:b:c"], "--grid"),
    (ILLUMINANTS + ["--count", "x"], "--count"),
    (ILLUMINANTS + ["--count", "0"], "--count"),
    (ILLUMINANTS + ["--step", "0"], "--step"),
    (ILLUMINANTS + ["--range", "10000", "2000"], ("--range", "above its start")),
    (ILLUMINANTS + ["--pair", "xx"], ("--pair", "two of r, g, b")),
    (ILLUMINANTS + ["--extrapolation", "nearest"], "--extrapolation"),
])
def test_illuminants_refuses(argv, names, capsys):
    assert_refused(argv, names, capsys)


@pytest.mark.parametrize("prevailing, names", [
    ("", "--prevailing"), ("   ", "--prevailing"), ("0", "--prevailing"), ("-0", "--prevailing"),
    ("-5", "--prevailing"), ("nan", "--prevailing"), ("inf", "--prevailing"), ("3300KK", "--prevailing"),
    ("1e306", "--prevailing"), ("20", ("prevailing", "no light")), ("1e-300", ("prevailing", "no light")),
])
def test_response_refuses_bad_prevailing(prevailing, names, capsys):
    assert_refused(RESPONSE + ["--prevailing", prevailing, "--calibration", "H"], names, capsys)


@pytest.mark.parametrize("extra, names", [
    (["--prevailing", "A", "--calibration", "20"], ("calibration", "no light")),
    (["--prevailing", "35", "--calibration", "H", "--normalization", "560nm"], ("--prevailing", "35K", "no light")),
    (["--prevailing", "A", "--calibration", "H", "--normalization", "loud"], "--normalization"),
    (["--prevailing", "A", "--calibration", "H", "--grid", "400:700:0.0001"], "--grid"),
    (["--prevailing", "A"], "--calibration"),
    # peaks outside the grid: each channel saw only a curve's tail (every sample came out grey, silently)
    (["--prevailing", "A", "--calibration", "H", "--camera", "gbell:9@0.45,0.54,0.61"], ("--camera", "not µm")),
    (["--prevailing", "A", "--calibration", "H", "--camera", "gbell:9@100,540,610"], ("--camera", "100 nm lies")),
    (["--prevailing", "A", "--calibration", "H", "--camera", "impulse@300,540,610"], ("--camera", "outside the grid")),
    (["--prevailing", "A", "--calibration", "H", "--reflectances", "UM"], ("--reflectances", "in µm")),
])
def test_response_refuses(extra, names, capsys, tmp_path):
    microns = tmp_path / "um.csv"  # wavelengths in µm: no extrapolation makes data of them
    microns.write_text("\n".join(f"{w / 1000},0.5" for w in range(400, 701, 10)))
    extra = [str(microns) if a == "UM" else a for a in extra] + ["--extrapolation", "zero"]
    assert_refused(RESPONSE + extra, names, capsys)


@pytest.mark.parametrize("key, names", [
    ("binary.csv", "not a UTF-8"), ("latin1.csv", "not a UTF-8"), ("header_only.csv", "no data rows"),
    ("refl_negative.csv", "reflectance"), ("refl_unsorted.csv", "increasing"),
])
def test_response_refuses_bad_reflectance_files(key, names, bad_files, capsys):
    argv = ["response", "--camera", CAM, "--reflectances", bad_files[key], "--prevailing", "A", "--calibration", "H"]
    assert_refused(argv, ("--reflectances", names), capsys)


@pytest.mark.parametrize("key, names", [
    ("binary.csv", "not a UTF-8"), ("camera_two.csv", "column"), ("camera_zero.csv", "zero"),
])
def test_bad_camera_files(key, names, bad_files, capsys):
    assert_refused(RESPONSE[:1] + ["--camera", bad_files[key], "--reflectances", "macbeth", "--prevailing", "A",
                                   "--calibration", "H"], names, capsys)


@pytest.mark.parametrize("key", ["zero_spd.csv", "binary.csv"])
def test_bad_illuminant_files(key, bad_files, capsys):
    assert_refused(RESPONSE + ["--prevailing", bad_files[key], "--calibration", "H"], "prevailing", capsys)


@pytest.mark.parametrize("extra, names", [
    (["--all-calibrations", "--illuminants", "2000,x"], "--illuminants"),
    (["--all-calibrations", "--illuminants", "20,3300"], ("--illuminants", "20K", "no light")),
    (["--all-calibrations", "--illuminants", ""], "--illuminants"),
    (["--calibration", "nan"], "--calibration"),
    (["--calibration", "3300", "--ratio"], "--ratio"),
    (["--calibration", "3300", "--munsell", "macbeth"], ("--munsell", "--ratio")),  # it was ignored
    (["--calibration", "3300", "--skin", "macbeth"], ("--skin", "--ratio")),
    (["--calibration", "3300", "--reflectances", "nope"], ("--reflectances", "nope")),
    (["--calibration", "3300", "--reflectances", "SHORT"], ("--reflectances", "does not cover")),
])
def test_gamut_refuses(extra, names, capsys, tmp_path):
    short = tmp_path / "short.csv"
    short.write_text("\n".join(f"{w},0.5" for w in range(420, 601, 10)))
    extra = [str(short) if a == "SHORT" else a for a in extra]
    assert_refused(GAMUT + extra, names, capsys)


def test_a_ratio_over_a_degenerate_munsell_gamut_is_null_with_the_reason(capsys):
    status, out, err = run(["gamut", "--camera", "impulse@450,450,450", "--ratio", "--all-calibrations", "--json"],
                           capsys)
    document = json.loads(out)
    assert status == 0, err
    assert document["ratio"] is None and "zero volume" in document["undefined"]["ratio"]


def test_coincident_sensors_give_a_zero_volume_not_an_error(capsys):
    """Degenerate is not an error: the volume is 0, flagged."""
    status, out, err = run(["gamut", "--camera", "gbell:9@550,550,550", "--reflectances", "skin",
                            "--calibration", "3300", "--json"], capsys)
    document = json.loads(out)
    assert status == 0 and document["volume"] == 0.0 and document["degenerate"] is True


@pytest.fixture
def underflowing_camera(tmp_path):
    path = tmp_path / "tiny.csv"
    path.write_text("nm,R,G,B\n400,1e-320,1e-320,1e-320\n700,1e-320,1e-320,1e-320\n")
    return path


@pytest.mark.parametrize("argv, name", [
    (["illuminants", "--camera", CAM, "--range", "1", "1e9", "--step", "1e5"], "--range"),
    (["illuminants", "--camera", "gbell:9@550,550,550"], "--camera"),
    (["illuminants", "--count", "1000"], "--count"),
])
def test_stage1_refusals_name_the_argument_at_fault(argv, name, capsys):
    """Seen: a range starting at 1 K and coincident sensors were blamed on --count."""
    argv = argv if "--camera" in argv else [*argv, "--camera", CAM]
    assert assert_refused(argv, name, capsys).startswith(f"skinrender illuminants: error: {name}: ")


@pytest.mark.parametrize("command", [["illuminants"], ["response", "--reflectances", "skin", "--prevailing", "A",
                                                       "--calibration", "A"]])
def test_a_camera_whose_responses_underflow_is_blamed_on_the_camera(command, underflowing_camera, capsys):
    """Seen: a camera CSV of 1e-320 values was blamed on --count (its responses to every light underflow)."""
    line = assert_refused([*command, "--camera", underflowing_camera], "--camera", capsys)
    assert line.startswith(f"skinrender {command[0]}: error: --camera: ") and "too small" in line


def test_an_extrapolation_that_does_not_apply_is_not_advised(capsys):
    """Seen: with a bundled set, ``--extrapolation constant`` was refused with the advice to give --extrapolation."""
    line = assert_refused(["response", "--camera", CAM, "--reflectances", "skin", "--prevailing", "A",
                           "--calibration", "A", "--grid", "300:900:1", "--extrapolation", "constant"],
                          "--reflectances", capsys)
    assert line.endswith("choose a --grid inside the data (--extrapolation constant applies to CSV files, not to "
                         "these spectra)")


def test_both_spellings_of_the_normalisation_are_refused_together(capsys):
    """Seen: ``--normalisation none --normalization white``: the last won silently."""
    argv = ["response", "--camera", CAM, "--reflectances", "skin", "--prevailing", "A", "--calibration", "A",
            "--normalisation", "none", "--normalization", "white"]
    assert_refused(argv, ("--normalization", "--normalisation"), capsys)
    status, out, _ = run([*argv[:-2], "--json"], capsys)
    assert status == 0 and json.loads(out)["normalization"] == "none"
