"""
Tests for :mod:`skinrender.cli.face_sweep`: ``face-sweep`` prints one JSON document (also with worker
processes, whose Mitsuba must not write on stdout), writes its CSV whole, refuses bad input with one line naming
the flag before any render, and stops at once on Ctrl-C.
"""

from __future__ import annotations

import csv
import json
import os
import signal

import pytest

from .refusal import assert_refused, interrupt_after, run

pytest.importorskip("mitsuba")

CAM = "gbell:9@450,540,610"
TINY = ["--size", "16", "--spp", "2", "--levels", "direct", "--skin", "skin-model:melanin=0.02"]
SWEEP = ["face-sweep", "--camera", CAM, "--lights", "2856/5900", *TINY]


def test_json_and_csv_in_this_process(tmp_path, capsys):
    target = tmp_path / "out" / "sweep.csv"
    status, out, err = run([*SWEEP, "--lights", "H/5900", "--camera", "Nikon 5100 (NPL)", "--workers", "1",
                            "--csv", target, "--json"], capsys)
    assert status == 0, err
    document = json.loads(out)
    rows = document["combinations"]
    assert document["renders"] == 4 and document["csv"] == str(target) and document["workers"] == 1
    assert [(r["camera"], r["prevailing_K"]) for r in rows] == [(CAM, 2856), (CAM, 2300), ("Nikon 5100 (NPL)", 2856),
                                                               ("Nikon 5100 (NPL)", 2300)]
    assert all(r["calibration_K"] == 5900 and r["level"] == "direct" and r["spp"] >= 2 for r in rows)
    with open(target, encoding="utf-8", newline="") as handle:
        lines = list(csv.reader(handle))
    assert [line[0] for line in lines[1:]] == [r["camera"] for r in rows]


def test_text_table(capsys):
    status, out, err = run([*SWEEP, "--workers", "1"], capsys)
    assert status == 0, err
    # 12 replicates of ⌈2 / 12⌉ spp: 12 spp in all; the detection verdict beside the rates
    assert "skin-model:melanin=0.02" in out and "2856/5900" in out and "1 render of 16×16 px at 12 spp" in out and "(1 worker, " in out
    assert "detection" in out and "the skin skin locus" in out


def test_workers_keep_stdout_to_the_json(capfd):
    """Two worker processes: stdout holds exactly the one JSON document (Mitsuba's log goes to stderr). Run in this
    process with ``capfd``: the spawned workers inherit its file descriptor 1, so whatever they write on stdout
    lands in the captured output as it did in a child's pipe (a worker printing on stdout fails this test); what is
    tested is the workers' stdout, not this process's start (``test_ctrl_c_stops_a_sweep_with_one_line`` runs one)."""
    from skinrender.cli import main

    status = main([str(a) for a in [*SWEEP, "--skin", "skin-model:melanin=0.4", "--spp", "3", "--workers", "2",
                                    "--json"]])
    out, err = capfd.readouterr()
    assert status == 0, err[-800:]
    document = json.loads(out)
    assert document["workers"] == 2 and [r["skin"] for r in document["combinations"]] == [
        "skin-model:melanin=0.02", "skin-model:melanin=0.4"]


@pytest.mark.parametrize("extra, names", [
    (["--lights", "2856"], "--lights"),
    (["--lights", "2856/x"], "--lights"),
    (["--lights", "2856/5900/1"], "--lights"),
    (["--lights", "2856/nosuch.csv"], "--lights"),
    (["--camera", "gbell:9@450"], "--camera"),
    (["--skin", "skin:nobody"], "--skin"),
    (["--skin", " "], "--skin"),
    (["--levels", "glossy"], "--levels"),
    (["--levels", ","], "--levels"),
    (["--levels", "direct,,sheen"], "--levels"),
    (["--levels", "sheen+mixed,mixed+sheen"], "--levels"),
    (["--size", "0"], "--size"),
    (["--size", "x"], "--size"),
    (["--spp", "0"], "--spp"),
    (["--seed", "-1"], "--seed"),
    (["--workers", "0"], "--workers"),
    (["--variant", "rgb"], "--variant"),
    (["--illuminance", "-1"], "--illuminance"),
    (["--imager", "nosuch"], "--imager"),
    (["--scene", "nosuch"], "--scene"),
    (["--max-renders", "0"], "--max-renders"),
    (["--lights", "2300/5900", "--max-renders", "1"], "--max-renders"),
    (["--max-samples", "100"], "--max-samples"),
    (["--max-samples", "nan"], "--max-samples"),
    (["--dask", " "], "--dask"),
    (["--imager", "sony-icx418"], ("--imager", "--levels", "noise")),
    (["--illuminance", "200"], ("--illuminance", "--levels")),
    (["--lights", "2856/5900,"], "--lights"),
    (["--lights", "2856/5900,2856/5900"], ("--lights", "2856/5900 K")),
    (["--lights", "2856/5900,A/5900"], ("--lights", "2856/5900 K")),
    (["--camera", CAM], ("--camera", "more than once")),
    (["--skin", "skin-model:melanin=0.02"], ("--skin", "more than once")),
])
def test_refusals(extra, names, capsys):
    assert_refused([*SWEEP, *extra], names, capsys)


def test_csv_refused_before_any_render(tmp_path, capsys):
    (tmp_path / "folder.csv").mkdir()
    assert_refused([*SWEEP, "--csv", tmp_path / "folder.csv"], "--csv", capsys, tmp_path)
    assert_refused([*SWEEP, "--csv", tmp_path / "sweep.txt"], "--csv", capsys, tmp_path)
    assert_refused([*SWEEP, "--csv", tmp_path / "sweep.csv", "--skin", "skin:nobody"], "--skin", capsys, tmp_path)


def test_unreachable_dask(capsys, monkeypatch):
    """Refused in one line naming --dask (waiting 1 s for the scheduler rather than the default 10 s: the refusal is
    the same)."""
    import skinrender.execution as execution

    monkeypatch.setattr(execution, "DASK_TIMEOUT_S", 1.0)
    line = assert_refused([*SWEEP, "--dask", "tcp://127.0.0.1:9"], "--dask", capsys)
    assert "within 1 s" in line


@pytest.mark.skipif(not hasattr(signal, "SIGINT") or os.name != "posix", reason="POSIX")
def test_ctrl_c_stops_a_sweep_with_one_line(tmp_path):
    """Ctrl-C during a parallel sweep: exit 130, one line, nothing on stdout, no CSV. The interrupt follows the
    sweep's own progress line; the sweep (direct only: subsurface's cost would refuse it; 256 px at 1024 spp) cannot
    finish first on any machine."""
    target = tmp_path / "sweep.csv"
    argv = ["face-sweep", "--camera", CAM, "--lights", "2300/5900,2856/5900,5900/5900,10000/5900", "--size", "256",
            "--spp", "1024", "--levels", "direct", "--workers", "2", "--csv", str(target), "--json"]
    status, out, err = interrupt_after(argv, "face sweep: ")
    assert status == 130, err[-800:]
    assert err.strip().splitlines()[-1] == "skinrender face-sweep: interrupted"
    assert "Traceback" not in err and out == ""
    assert list(tmp_path.iterdir()) == []


@pytest.mark.skipif(not hasattr(signal, "SIGINT") or os.name != "posix", reason="POSIX")
@pytest.mark.parametrize("name, extra, marker", [
    ("face-sweep", ["--lights", "2856/5900", "--skin", "skin-model:melanin=0.02", "--workers", "1"], "face sweep: "),
    ("ladder", ["--prevailing", "A", "--calibration", "H"], "rendering the face"),
])
def test_ctrl_c_stops_an_in_process_render_at_once(name, extra, marker):
    """Seen by a user: Ctrl-C inside Mitsuba's native render (one process) gave an internal error ~20 s later.
    The interrupt follows the command's own progress line (it slept 8 s before, assuming a 30 s render, and
    failed on a faster machine where the render finished first)."""
    argv = [name, "--camera", CAM, *extra, "--levels", "direct", "--size", "160", "--spp", "2048", "--json"]
    status, out, err = interrupt_after(argv, marker)
    assert status == 130, err[-800:]  # it was 1, an internal error from drjit
    assert err.strip().splitlines()[-1] == f"skinrender {name}: interrupted" and out == ""


def test_rounded_spp_is_said_once_and_the_json_reports_the_count_used(capsys):
    """Seen: Mitsuba's "Sample count rounded up" warnings reached the terminal (54 in the README's example) while
    the JSON reported the requested spp."""
    status, out, err = run([*SWEEP, "--spp", "84", "--workers", "1", "--json"], capsys)  # 12 replicates of 7 spp
    document = json.loads(out)
    assert status == 0 and document["spp"] == 96 and document["spp_requested"] == 84
    assert "WARN" not in err and err.count("rounded") == 1


def test_a_full_disk_leaves_no_csv(tmp_path, capsys, monkeypatch):
    from .refusal import full_disk

    full_disk(monkeypatch)
    status, out, err = run([*SWEEP, "--workers", "1", "--csv", tmp_path / "s.csv", "--json"], capsys)
    assert status == 1 and out == "" and list(tmp_path.iterdir()) == []
    assert f"error: --csv {tmp_path / 's.csv'}: cannot be written (no space left" in err


def test_the_sensors_flags_reach_the_noise_level(capsys):
    """--illuminance and --imager go to the noise level's sensor (after the front door, noise_sensor returns both:
    the sweep had taken the pair for the lux and refused every --illuminance)."""
    status, out, err = run([*SWEEP, "--levels", "noise", "--illuminance", "500", "--imager", "sony-imx174",
                            "--workers", "1", "--json"], capsys)
    assert status == 0, err[-500:]
    row = json.loads(out)["combinations"][0]
    assert row["illuminance_lux"] == 500 and row["imager"] == "sony-imx174"


def test_a_sweep_estimated_beyond_max_minutes_is_refused_with_its_estimate(capsys):
    """A subsurface-volume sweep at 512 px and 2048 spp (about 10 h) started without a word: face-sweep had no
    --max-minutes (an hour by default, as ladder's)."""
    from .refusal import assert_refused

    line = assert_refused(["face-sweep", "--camera", "gbell:9@450,540,610", "--lights", "2856/5900", "--levels",
                           "subsurface-volume", "--size", "512", "--spp", "2048"],
                          ("--max-minutes", "would take about", "more than the cap of 60 min"), capsys)
    assert " h (estimated)" in line
