"""
``skinrender validate`` on a chart (:mod:`skinrender.cli.chart_validation`): the exit status says the verdict
(0 pass, 1 fail, 3 inconclusive), the text has headed columns with full patch names, the JSON one document with the
contract's keys and the verdict's; ``--spp auto`` says what it chose and why; bad tolerances and flags that go
elsewhere are refused naming the flag.
"""

from __future__ import annotations

import json

import pytest

from .refusal import assert_refused, run

pytest.importorskip("mitsuba")

CAM = "gbell:9@450,540,610"
LIGHTS = ["--prevailing", "3300", "--calibration", "4800"]


@pytest.mark.parametrize("extra, verdict, status", [
    (["--spp", "256", "--tolerance", "0.05"], "pass", 0),
    (["--spp", "4", "--tolerance", "0.002"], "inconclusive", 3),
])
def test_exit_status_says_the_verdict(small_chart, extra, verdict, status, capsys):
    code, out, err = run(["validate", small_chart, "--camera", CAM, *LIGHTS, *extra, "--json"], capsys)
    document = json.loads(out)
    assert code == status == document["exit_status"], err
    assert document["verdict"] == verdict and document["passed"] is (verdict == "pass")
    assert set(document["checks"]) == {"equivalence", "difference"}
    assert document["checks"]["equivalence"]["tolerance"] == float(extra[-1])
    row = document["patches"][0]
    assert {"name", "rendered", "analytic", "rel_error", "tolerance", "error", "bound", "shown"} <= set(row)
    if verdict == "inconclusive":
        assert document["spp_needed"] > 4


def test_30_kelvin_at_4_spp_does_not_pass(capsys):
    """The issue's case: at 30 K the pixels are so skewed that their means are no longer normal: the verdict says
    so instead of passing (exit status 3)."""
    code, out, err = run(["validate", "macbeth", "--camera", CAM, "--prevailing", "30", "--calibration", "5900",
                          "--spp", "4", "--tolerance", "0.002", "--json"], capsys)
    document = json.loads(out)
    assert code == 3 and document["verdict"] == "inconclusive" and not document["passed"]
    assert "too skewed" in document["checks"]["equivalence"]["reason"]


def test_a_shown_bias_fails_with_exit_status_1(small_chart, capsys):
    """The impulse at the grid's end under 1000 K: the render's known bias (~1e-4, Planck changing ~9 % per nm)
    is shown beyond a 3e-5 tolerance."""
    code, out, err = run(["validate", small_chart, "--camera", "impulse@400,550,700", "--prevailing", "1000",
                          "--calibration", "25000", "--spp", "64", "--tolerance", "0.00003", "--json"], capsys)
    document = json.loads(out)
    assert code == 1 and document["verdict"] == "fail" and document["spp_needed"] is None
    assert document["checks"]["difference"]["verdict"] == "fail"


def test_text_has_headed_columns_and_full_names(capsys):
    code, out, err = run(["validate", "macbeth", "--camera", CAM, *LIGHTS, "--spp", "16", "--tolerance", "0.05"],
                         capsys)
    assert code == 0, err
    header = next(line for line in out.splitlines() if line.startswith("patch"))
    assert header.split() == ["patch", "channel", "analytic", "rendered", "error", "bound", "tolerance", "shown"]
    assert "neutral 3.5 (1.05 D)" in out and "purplish blue" in out  # full names, not cut at 28 characters
    assert "equivalence: PASS" in out and "difference:" in out and "verdict: PASS (exit status 0)" in out


def test_spp_auto_says_what_it_chose_and_why(small_chart, capsys):
    code, out, err = run(["validate", small_chart, "--camera", CAM, *LIGHTS, "--spp", "auto", "--tolerance", "0.01",
                          "--json"], capsys)
    document = json.loads(out)
    choice = document["spp_auto"]
    assert [p["spp"] for p in choice["pilots"]] == [16, 64] and choice["spp"] == document["spp"]
    assert "pilots at 16 and 64 spp" in choice["why"] and document["spp_requested"] == "auto"
    assert code == document["exit_status"]


@pytest.mark.parametrize("extra, names", [
    (["--tolerance", "0"], "--tolerance"),
    (["--tolerance", "1"], "--tolerance"),
    (["--tolerance", "-0.01"], "--tolerance"),
    (["--tolerance", "1%"], "--tolerance"),
    (["--spp", "auto"], ("--spp auto", "--tolerance")),
    (["--spp", "many"], "--spp"),
    (["--gamut", "--imager", "sony-imx174"], ("--gamut", "--imager")),
    # issue 36: an OverflowError as "internal error" (its bounds' ratios overflowed)
    (["--tolerance", "5e-324"], ("--tolerance", "float32's resolution")),
    (["--tolerance", "1e400"], "--tolerance"),
    # issue 36: each was accepted and had no effect
    (["--imager", "sony-imx174", "--knee"], ("--knee", "linear codes")),
    (["--gamut", "--normalization", "none"], ("--gamut", "--normalization none")),
    (["--gamut", "--knee"], ("--gamut", "--knee")),
])
def test_bad_input_refused(extra, names, capsys):
    assert_refused(["validate", "macbeth", "--camera", CAM, *LIGHTS, *extra], names, capsys)


@pytest.mark.parametrize("extra, name", [(["--tolerance", "0.01"], "--tolerance"),
                                         (["--spp", "auto", "--tolerance", "0.01"], "--spp auto")])
def test_the_face_refuses_the_chart_flags(extra, name, capsys):
    assert_refused(["validate", "face", "--camera", CAM, *LIGHTS, *extra], name, capsys)


def test_help_documents_the_exit_statuses_and_the_default(capsys):
    code, out, _ = run(["validate", "--help"], capsys)
    assert code == 0 and "0 pass, 1 fail, 3 inconclusive" in out and "default 0.01" in out


def test_gamut_verdict_joins_the_patches(small_chart, capsys):
    code, out, err = run(["validate", small_chart, "--camera", CAM, *LIGHTS, "--spp", "64", "--tolerance", "0.05",
                          "--gamut", "--json"], capsys)
    document = json.loads(out)
    gamut = document["gamut"]
    assert len(gamut["bound"]) == len(gamut["illuminants_K"]) + 1 and gamut["verdict"]["tolerance"] == 0.05
    parts = {document["checks"]["equivalence"]["verdict"], gamut["verdict"]["verdict"]}
    expected = next(outcome for outcome in ("fail", "inconclusive", "pass") if outcome in parts)
    assert document["verdict"] == expected and code == document["exit_status"]
    assert "gamut equivalence:" in run(["validate", small_chart, "--camera", CAM, *LIGHTS, "--spp", "64",
                                        "--tolerance", "0.05", "--gamut"], capsys)[1]


def test_gamut_keeps_the_csv_cameras_extrapolation(small_chart, tmp_path, capsys):
    """Issue 26: ``--gamut`` with a CSV camera measured over 420–680 nm and ``--extrapolation zero`` renders the
    chart and its gamut through the one camera parsed from the flags (the gamut step parsed ``--camera`` again
    without ``--extrapolation`` and refused the camera after the chart had rendered)."""
    import numpy as np

    from skinrender.model.camera import camera
    from skinrender.spectra import WavelengthGrid

    wavelengths = np.arange(420.0, 681.0, 5.0)
    curves = camera(CAM).sensitivities(WavelengthGrid(420, 680, 5))
    path = tmp_path / "short.csv"
    np.savetxt(path, np.column_stack([wavelengths, curves.T]), delimiter=",", header="wavelength_nm,R,G,B",
               comments="", fmt="%.6g")
    code, out, err = run(["validate", small_chart, "--camera", path, "--extrapolation", "zero", *LIGHTS, "--spp",
                          "16", "--tolerance", "0.05", "--gamut", "--json"], capsys)
    assert code in (0, 1, 3), err
    document = json.loads(out)
    assert document["camera"] == str(path) and document["gamut"]["camera"] == str(path)
    assert len(document["gamut"]["rendered"]) == len(document["gamut"]["illuminants_K"]) + 1


def test_the_dark_floor_follows_the_rendered_white(capsys):
    """Issue 36: at --normalization none the white is ~3.5 output units, but the dark floor stayed REL × 2.55, so
    the black patch's blue could err by 480 % and the run passed where --normalization white is inconclusive. The
    floor is now 1 % of the white's brightest channel as rendered; the header says what that white is."""
    argv = ["validate", "macbeth", "--camera", CAM, "--prevailing", "A", "--calibration", "5900", "--spp", "4",
            "--tolerance", "0.06"]
    code, out, err = run([*argv, "--normalization", "none", "--json"], capsys)
    document = json.loads(out)
    assert 3 < document["white_level"] < 4 and document["dark_floor_output"] == pytest.approx(
        0.06 * 0.01 * document["white_level"])
    assert document["verdict"] != "pass" and code == document["exit_status"] != 0
    code, out, err = run(argv, capsys)
    assert "output units (a perfect white's brightest channel: 3.49" not in out
    assert "a perfect white's brightest channel: 410.7" in out  # white normalisation at A / 5900 K


def test_the_dropped_sigmas_key_is_back_with_its_deprecation(small_chart, capsys):
    """Issue 36: validate --json had dropped 'sigmas' (the tolerance in standard errors, 5, before the verdicts)
    without a deprecation. It is back: the equivalence's critical value, with a note of what to read instead."""
    code, out, err = run(["validate", small_chart, "--camera", CAM, *LIGHTS, "--spp", "4", "--json"], capsys)
    document = json.loads(out)
    assert document["sigmas"] == document["checks"]["equivalence"]["critical"] > 2
    assert "deprecated" in document["deprecated"]["sigmas"] and "checks.equivalence.critical" in document[
        "deprecated"]["sigmas"]


def test_spp_auto_is_held_to_the_spp_limit(tmp_path, capsys):
    """Issue 36: --spp auto --tolerance 1e-9 picked 2.4 M spp on a small chart (one pass could hold that many),
    beyond --spp's own limit of 1 048 576, and rendered for 89 s. Refused after the pilots, naming --tolerance."""
    chart = tmp_path / "two.toml"
    chart.write_text("columns = 2\npatch_px = 4\ngap_px = 1\nborder_px = 1\n[[patch]]\nreflectance = 'grey:0.5'\n")
    # 30 K: the pilots' bounds barely fall (the render is extremely heavy-tailed), so the spp projected is vast; the
    # refusal follows the pilots (it is their projection), after their progress line
    code, out, err = run(["validate", chart, "--camera", CAM, "--prevailing", "30", "--calibration", "5900", "--spp",
                          "auto", "--tolerance", "1e-4", "--json"], capsys)
    assert code == 2 and out == "" and "Traceback" not in err
    assert err.splitlines()[-1].startswith("skinrender validate: error: --tolerance 0.0001: about ")
    assert "more than 1048576 a render may take" in err
