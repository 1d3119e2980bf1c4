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
