"""
``skinrender bench calibration`` and ``bench validate`` (:mod:`skinrender.cli.calibration`): one JSON document with
the rates and their intervals, the plot written whole; refusals name the flag (a seeds count over the cap with its
estimate, a face's bench validate, a chart's --level, the other benchmarks' flags); a face's calibration (each check's
rate, eq4_shift's without a null where Eq. 4 does not hold); Ctrl-C exits 130 and leaves nothing behind.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time

import pytest

from .refusal import assert_refused, run

pytest.importorskip("mitsuba")


def test_calibration_document_and_plot(small_chart, tmp_path, capsys):
    plot = tmp_path / "rates.png"
    status, out, err = run(["bench", "calibration", "--scene", small_chart, "--seeds", "3", "--spp", "4", "--plot", plot,
                            "--json"], capsys)
    assert status == 0, err[-500:]
    document = json.loads(out)
    names = [row["name"] for row in document["checks"]]
    assert names == ["difference", "equivalence"] and document["seeds"] == 3 and document["spp"] == 4
    row = document["checks"][0]
    assert row["nominal_alpha"] == 0.01 and len(row["interval"]) == 2 and row["seeds"] == 3
    assert document["plot"] == str(plot) and plot.stat().st_size > 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rates.png"]  # no temporary file left


def test_calibration_through_a_sensor_reports_each_check(small_chart, capsys):
    status, out, err = run(["bench", "calibration", "--scene", small_chart, "--seeds", "2", "--spp", "4", "--imager",
                            "sony-imx174", "--mc-variance", "pixels", "--json"], capsys)
    assert status == 0, err[-500:]
    document = json.loads(out)
    assert [row["name"] for row in document["checks"]] == ["mean", "variance", "equivalence", "difference"]
    assert document["mc_variance"] == "pixels" and document["imager"] == "sony-imx174"


def test_a_faces_calibration_per_check(tmp_path, capsys):
    """``--scene`` a face ``--level sheen``: the face's checks, seeds 12 apart, eq4_shift's failures findings (no
    null). The face is the bundled one at 32 × 32 px (its own 256 × 256 takes 60 times the samples; nothing
    asserted here depends on the size)."""
    from skinrender.rendering.face.scene import ROOT_FACE_SCENES

    bundled = (ROOT_FACE_SCENES / "face.toml").read_text(encoding="utf-8")
    assert "width = 256" in bundled and "height = 256" in bundled
    scene = tmp_path / "small_face.toml"
    scene.write_text(bundled.replace("width = 256", "width = 32").replace("height = 256", "height = 32"))
    plot = tmp_path / "face.png"
    status, out, err = run(["bench", "calibration", "--scene", scene, "--level", "sheen", "--seeds", "2", "--spp",
                            "192", "--plot", plot, "--json"], capsys)
    assert status == 0, err[-500:]
    document = json.loads(out)
    rows = {row["name"]: row for row in document["checks"]}
    assert list(rows) == ["dichromatic_plane", "detection", "eq4_shift", "white_furnace", "closed_sphere"]
    assert [r["seed"] for r in document["runs"]] == [0, 12] and document["level"] == "sheen"
    assert rows["dichromatic_plane"]["nominal_alpha"] == 0.01 and rows["dichromatic_plane"]["seeds"] == 2
    assert rows["eq4_shift"]["nominal"] is None and rows["eq4_shift"]["consistent"] is None
    assert rows["detection"]["nominal"] is None  # sheen changes the rates: a fail there is a finding
    assert plot.stat().st_size > 0 and document["estimate_s"] > 0


def test_the_detection_verdicts_false_alarms_at_any_spp(capsys):
    """``--checks detection``: the detection verdict alone at the ladder's sizes (no floor per replicate: 12 × 1
    spp here), its failures false alarms at direct (at most α). Three seeds at 24 px: the shape, not the rate
    (docs/face-verdicts.md measures 40 seeds)."""
    status, out, err = run(["bench", "calibration", "--scene", "face", "--checks", "detection", "--seeds", "3",
                            "--spp", "12", "--size", "24", "--skin", "skin-model:melanin=0.3", "--skin-set",
                            "skin-tones", "--json"], capsys)
    assert status == 0, err[-500:]
    document = json.loads(out)
    (row,) = document["checks"]
    assert row["name"] == "detection" and row["nominal"] == "at most" and row["trials"] == 3
    assert row["failures"] == 0 and document["spp"] == 12 and document["size"] == 24
    assert document["skin_set"] == "skin-tones" and [r["seed"] for r in document["runs"]] == [0, 12, 24]


@pytest.mark.parametrize("argv, flag", [
    (["--checks", "detection", "--skin-set", "nothing-such"], "--skin-set"),
    (["--checks", "detection", "--detection-tolerance", "2"], "--detection-tolerance"),
    (["--skin", "skin-model:melanin=0.3"], "--skin"),
])
def test_the_detection_calibrations_flags_are_refused_by_name(argv, flag, capsys):
    status, out, err = run(["bench", "calibration", "--scene", "face", "--seeds", "1", *argv], capsys)
    assert status == 2 and out == "" and flag in err


def test_ptc_calibration_rates_and_z(capsys):
    """``--scene ptc``: the photon transfer's fits over a few sensor seeds of one render, the family's row and each
    tested figure's, and z's mean and spread per channel."""
    status, out, err = run(["bench", "calibration", "--scene", "ptc", "--imager", "sony-imx174", "--seeds", "3",
                            "--spp", "1", "--json"], capsys)
    assert status == 0, err[-500:]
    document = json.loads(out)
    names = [row["name"] for row in document["checks"]]
    assert names == ["fits", "gain_dn_per_e", "read_noise_e", "dark_current_e_per_s"]
    assert document["checks"][0]["nominal_alpha"] == 0.01 and document["checks"][0]["seeds"] == 3
    assert [run_["seed"] for run_ in document["runs"]] == [0, 1, 2] and document["seed_step"] == 1
    assert set(document["z"]) == {"gain_dn_per_e", "read_noise_e", "dark_current_e_per_s"}
    assert len(document["z"]["gain_dn_per_e"]["sd"]) == 3 and "Šidák" in document["tests"]["fits"]


def test_validate_rows_in_text(small_chart, capsys):
    status, out, err = run(["bench", "validate", "--scene", small_chart, "--seeds", "2", "--spp-list", "4,16"], capsys)
    assert status == 0, err[-500:]
    header = next(line for line in out.splitlines() if line.startswith("spp"))
    assert header.split()[:4] == ["spp", "used", "s", "per"] and "2 seeds per spp" in out
    assert "the bound falls as spp^-" in out


@pytest.mark.parametrize("argv, names", [
    (["calibration", "--seeds", "100000"], ("--seeds", "estimated", "--max-minutes")),
    (["calibration", "--seeds", "50", "--max-minutes", "0.01"], ("--seeds", "--max-minutes")),
    (["calibration", "--seeds", "0"], "--seeds"),
    (["calibration", "--spp", "0"], "--spp"),
    (["calibration", "--level", "direct"], ("--level", "face")),
    (["validate", "--scene", "face"], ("--scene", "bench calibration --scene face")),
    (["calibration", "--scene", "face", "--level", "glossy"], "--level"),
    (["calibration", "--scene", "face", "--imager", "sony-icx418", "--mc-variance", "frames"], "--mc-variance"),
    (["calibration", "--scene", "face", "--seeds", "100000"], ("--seeds", "--max-minutes")),
    (["calibration", "--mc-variance", "frames"], ("--mc-variance", "--imager")),
    (["calibration", "--illuminance", "200"], ("--illuminance", "--imager")),
    (["calibration", "--plot", "rates.txt"], "--plot"),
    (["calibration", "--camera", "nope"], "--camera"),
    (["calibration", "--prevailing", "x"], "--prevailing"),
    (["calibration", "--seed", "-1"], "--seed"),
    (["validate", "--spp", "16"], ("--spp", "'bench calibration'")),
    (["validate", "--plot", "x.png"], "--plot"),
    (["validate", "--spp-list", "4,4"], "--spp-list"),
    (["validate", "--level", "direct"], "--level"),
    (["calibration", "--repeat", "2"], "--repeat"),
    (["calibration", "--size", "16"], "--size"),
    (["analytic", "--seeds", "3"], "--seeds"),
    (["render", "--imager", "sony-imx174"], "--imager"),
    (["calibration", "--scene", "ptc"], ("--imager", "ptc")),
    (["calibration", "--scene", "ptc", "--imager", "sony-imx174", "--calibration", "4800"], ("--calibration", "ptc")),
    (["calibration", "--scene", "ptc", "--imager", "sony-imx174", "--level", "direct"], "--level"),
    (["calibration", "--scene", "ptc", "--imager", "nope"], "--imager"),
    (["calibration", "--scene", "ptc", "--imager", "sony-imx174", "--seeds", "100000"], ("--seeds", "--max-minutes")),
    (["validate", "--scene", "ptc"], ("--scene", "bench calibration --scene ptc")),
])
def test_refusals_name_the_flag(argv, names, tmp_path, capsys):
    assert_refused(["bench", *argv], names, capsys, output=tmp_path)


def test_render_bench_checks_its_camera_first(capsys):
    assert_refused(["bench", "render", "--quick", "--camera", "gbell:9@450,540"], "--camera", capsys)


@pytest.mark.skipif(not hasattr(signal, "SIGINT") or os.name != "posix", reason="POSIX")
def test_ctrl_c_exits_130_and_leaves_nothing(tmp_path):
    plot = tmp_path / "rates.png"
    argv = [sys.executable, "-c", "import sys; from skinrender.cli import main; sys.exit(main())", "bench",
            "calibration", "--seeds", "5000", "--spp", "64", "--max-minutes", "10000", "--plot", str(plot), "--json"]
    child = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    deadline = time.monotonic() + 120
    while "seed 0:" not in (line := child.stderr.readline()) and time.monotonic() < deadline:
        assert line, "the bench ended before it could be interrupted"
    child.send_signal(signal.SIGINT)
    out, err = child.communicate(timeout=60)
    assert child.returncode == 130, err[-800:]
    assert err.strip().splitlines()[-1] == "skinrender bench: interrupted" and out == ""
    assert list(tmp_path.iterdir()) == []
