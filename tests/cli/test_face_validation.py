"""
``skinrender validate`` on a face scene (:mod:`skinrender.cli.face_validation`): one JSON document with a
row per check (each a verdict with its test and α), exit 0 pass, 1 fail, 3 inconclusive, and bad input refused
(exit 2, one line naming the flag) before anything renders.
"""

from __future__ import annotations

import argparse
import json

import pytest

from skinrender.cli.face_validation import command_validate_face, limits_of
from skinrender.cli.inputs import scene_of
from skinrender.errors import SkinrenderError
from skinrender.rendering.face.limits import LimitCheck

from .refusal import assert_refused, run

pytest.importorskip("mitsuba")

CAM = "gbell:9@450,540,610"
BASE = ["validate", "face", "--camera", CAM, "--prevailing", "A", "--calibration", "5900", "--size", "32",
        "--spp", "48"]
KEYS = {"scene", "camera", "physics", "skin", "prevailing_K", "calibration_K", "spp", "spp_requested", "seed",
        "variant", "elapsed_s", "checks", "passed", "verdict", "exit_status", "budget", "spp_per_replicate"}
ROW = {"name", "applies", "passed", "statistic", "tolerance", "pixels", "reason", "verdict", "alpha", "test", "bound"}


def test_direct_document(capsys):
    status, out, err = run([*BASE, "--seed", "3", "--json"], capsys)
    assert status in (0, None), err[-500:]
    document = json.loads(out)
    assert set(document) >= KEYS
    assert document["physics"] == "direct" and document["seed"] == 3 and document["spp_requested"] == 48
    assert document["spp"] >= 48 and document["checks"][0]["passed"] is True and document["replicates"] == 12
    names = [row["name"] for row in document["checks"]]
    assert names == ["shading_cancels", "detection", "eq4_shift", "white_furnace", "closed_sphere"]
    assert all(set(row) >= ROW for row in document["checks"])
    detection, shift = document["checks"][1], document["checks"][2]
    assert detection["applies"] is True and detection["verdict"] == "pass" and detection["tolerance"] == 0.02
    assert document["detection"]["verdict"] == "pass" and document["detection"]["tpr_change"] == 0
    assert document["skin_set"] == "skin"
    # the NCC budget is a diagnostic: reported, outside the verdict
    assert shift["applies"] is False and shift["verdict"] == "pass" and shift["within_budget"] is True
    assert shift["tolerance"] == document["budget"]["budget"] and shift["alpha"] == 0.05
    assert shift["bound"] < shift["tolerance"] and "equivalence" in shift["test"]
    assert {row["verdict"] for row in document["checks"]} == {"pass"} and document["passed"] is True
    assert document["verdict"] == "pass" and document["exit_status"] == 0


def test_text_names_each_test_and_the_verdict(capsys):
    status, out, err = run([*BASE, "--limits", "none"], capsys)
    assert status in (0, None), err[-500:]
    assert "verdict" in out.splitlines()[1] and "test: difference, two parts" in out and "test: equivalence" in out
    assert "verdict: PASS (exit status 0)" in out


def test_interreflection_is_held_to_the_budget_and_the_sensor_is_named(capsys):
    """No exact limit holds at interreflection: eq4_shift against the budget is its only check; with --imager the
    level gains noise. At 16 px through the 8-bit sensor few skin pixels are scored: the exit status follows the
    verdict."""
    args = argparse.Namespace(scene="face", camera=CAM, prevailing="A", calibration="A", quality="standard", spp=24,
                              sampler=None, seed=0, variant=None, channels="auto", imager="sony-icx418",
                              illuminance=300.0, exposure="auto", normalization="white", knee=False,
                              grid="400:700:1", extrapolation="refuse", gamut=False, physics="interreflection",
                              skin=None, size="16", limits="none", json=True, detection_tolerance=None,
                              skin_set=None)
    try:
        command_validate_face(args, scene_of(args))
        status = 0
    except SystemExit as exit_:
        status = exit_.code
    document = json.loads(capsys.readouterr().out)
    assert document["physics"] == "interreflection+noise" and document["imager"] == "sony-icx418"
    assert document["illuminance_lux"] == 300.0
    assert [row["name"] for row in document["checks"]] == ["detection", "eq4_shift"]
    assert status == document["exit_status"] == {"pass": 0, "fail": 1, "inconclusive": 3}[document["verdict"]]


def test_a_failing_check_exits_1_with_its_document(capsys, monkeypatch):
    import skinrender.cli.face_validation as cli
    import skinrender.rendering.face.effects.direct as module  # the base level's check

    failed = LimitCheck("shading_cancels", True, False, 9.0, 7.0, 100, "forced")
    monkeypatch.setattr(module, "check_shading", lambda *a, **k: failed)
    monkeypatch.setattr(cli, "limits_of", lambda text: ())  # the scene-free limits: not needed here
    status, out, _ = run([*BASE, "--size", "12", "--spp", "12", "--json"], capsys)
    assert status == 1
    document = json.loads(out)
    assert document["passed"] is False and document["checks"][0]["passed"] is False


def test_limits_are_parsed():
    assert limits_of("furnace, sphere,furnace") == ("furnace", "sphere")
    with pytest.raises(SkinrenderError, match="--limits"):
        limits_of("moon")


@pytest.mark.parametrize("extra, names", [
    (["--physics", "glossy"], "--physics"),
    (["--skin", "skin:nobody"], "--skin"),
    (["--size", "0"], "--size"),
    (["--size", "x"], "--size"),
    (["--knee"], "--knee"),
    (["--gamut"], "--gamut"),
    (["--normalization", "none"], "--normalization"),
    (["--grid", "400:700:5"], "--grid"),
    (["--prevailing", "nonsense"], "--prevailing"),
    (["--calibration", "20"], "--calibration"),
    (["--camera", "Sony 755"], "--camera"),
    (["--imager", "nope"], "--imager"),
    (["--imager", "sony-icx418", "--illuminance", "-3"], "--illuminance"),
    (["--spp", "0"], "--spp"),
    (["--seed", "-1"], "--seed"),
    (["--variant", "llvm_ad_rgb"], "--variant"),
])
def test_bad_input_is_refused(extra, names, capsys):
    assert_refused([*BASE, *extra], names, capsys)


@pytest.mark.parametrize("argv, names", [
    ([*BASE, "--limits", "moon"], "--limits"),
    (["validate", "macbeth", "--camera", CAM, "--prevailing", "A", "--calibration", "A", "--limits", "none"],
     "--limits"),
    (["validate", "macbeth", "--camera", CAM, "--prevailing", "A", "--calibration", "A", "--physics", "sheen"],
     "--physics"),
])
def test_limits_flag_is_checked_and_face_only(argv, names, capsys):
    """``--limits`` names the scene-free limits of a face; a chart refuses it (and the other face options)."""
    assert_refused(argv, names, capsys)


def test_an_undecided_limit_is_inconclusive_exit_3(capsys):
    """A limit that applies but has too few pixels to decide: inconclusive with the reason, exit status 3."""
    status, out, err = run(["validate", "face", "--camera", CAM, "--prevailing", "A", "--calibration", "5900",
                            "--size", "4", "--spp", "12", "--limits", "none", "--json"], capsys)
    document = json.loads(out)
    assert status == 3 and document["passed"] is None and document["verdict"] == "inconclusive"
    assert document["checks"][0]["applies"] and document["checks"][0]["verdict"] == "inconclusive"
    assert document["undefined"]["passed"].startswith("INCONCLUSIVE: shading_cancels")


def test_an_undecided_main_check_is_not_passed_by_the_scene_free_limits(capsys):
    """Seen by a user: at 2 px ``shading_cancels`` had no lit skin pixel, yet the sphere's pass made the verdict
    true. Now inconclusive with the undecided check's reason (exit 3), text INCONCLUSIVE."""
    argv = ["validate", "face", "--camera", CAM, "--prevailing", "3300", "--calibration", "3300", "--size", "2",
            "--spp", "3", "--limits", "sphere"]
    status, out, err = run([*argv, "--json"], capsys)
    document = json.loads(out)
    assert status == 3, err[-500:]
    assert [row["verdict"] for row in document["checks"] if row["name"] in ("shading_cancels", "closed_sphere")] == [
        "inconclusive", "pass"]
    assert document["passed"] is None
    assert document["undefined"]["passed"].startswith("INCONCLUSIVE: shading_cancels: only 0 skin pixels")
    status, out, err = run(argv, capsys)
    assert status == 3 and "verdict: INCONCLUSIVE (exit status 3)" in out and "PASS (" not in out


def test_its_replicates_are_capped_by_their_estimated_time(capsys):
    """Issue 25: validate face had only the one-pass sample cap, no estimate against --max-minutes."""
    status, out, err = run([*BASE, "--size", "256", "--spp", "4096", "--max-minutes", "1", "--json"], capsys)
    assert status == 2 and out == ""
    line = err.strip().splitlines()[-1]
    assert line.startswith("skinrender validate: error: --spp: 12 renders of 65536 pixels at 342 spp would take about")
    assert "--max-minutes" in line
