"""
``skinrender bench`` and ``reproduce`` (:mod:`skinrender.cli.studies`): the face bench's document, and the
flags of the benchmarks and of ``reproduce`` refused (exit 2, one line naming the flag) before any work.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from .refusal import assert_refused, run


def test_face_bench_document(capsys):
    pytest.importorskip("mitsuba")
    status, out, err = run(["bench", "render", "--scene", "face", "--size", "16", "--spp-list", "1,4",
                            "--reference-spp", "16", "--levels", "direct", "--json"], capsys)
    assert status in (0, None), err[-500:]
    document = json.loads(out)
    assert [(r["level"], r["spp"]) for r in document["curve"]] == [("direct", 1), ("direct", 4)]
    assert document["size"] == [16, 16] and document["reference_spp"] == 16
    assert set(document["presets"]["direct"]) >= {"draft", "standard", "reference"}


@pytest.mark.parametrize("argv, names", [
    (["render", "--scene", "macbeth"], "--scene"),
    (["render", "--scene", "nowhere.toml"], "--scene"),
    (["search", "--scene", "face"], "--scene"),
    (["render", "--size", "64"], "--size"),
    (["render", "--spp-list", "4"], "--spp-list"),
    (["render", "--scene", "face", "--size", "0"], "--size"),
    (["render", "--scene", "face", "--size", "64,32"], "--size"),
    (["render", "--scene", "face", "--spp-list", "4,x"], "--spp-list"),
    (["render", "--scene", "face", "--reference-spp", "0"], "--reference-spp"),
    (["render", "--scene", "face", "--size", "2000", "--reference-spp", "1000"], "--reference-spp"),
    (["render", "--scene", "face", "--levels", "direct,glossy"], "--levels"),
    (["render", "--scene", "face", "--levels", ","], "--levels"),
    (["render", "--scene", "face", "--levels", "direct,,sheen"], "--levels"),
    (["render", "--scene", "face", "--levels", "direct,direct"], "--levels"),
    (["render", "--scene", "face", "--plot", "curve.png"], "--plot"),
    # an empty --levels is refused, not read as the default levels
    (["render", "--scene", "face", "--quick", "--levels", ""], "--levels"),
    # the flags of the other benchmarks are refused with --scene
    (["render", "--scene", "face", "--repeat", "3"], "--repeat"),
    (["render", "--scene", "face", "--sensor", "9"], "--sensor"),
    (["render", "--scene", "face", "--workers", "2"], "--workers"),
    (["render", "--scene", "face", "--positions", "400:700:20"], "--positions"),
    (["render", "--scene", "face", "--sample", "5"], "--sample"),
    # … and each benchmark's flags by the others
    (["analytic", "--sensor", "9"], "--sensor"),
    (["search", "--repeat", "2"], "--repeat"),
    (["sweep", "--quick"], "--quick"),
    (["analytic", "--plot", "curve.png"], "--plot"),
    # the reference converges further than the curve; each spp once
    (["render", "--scene", "face", "--quick", "--size", "16", "--levels", "direct", "--spp-list", "4,16",
      "--reference-spp", "8"], "--reference-spp"),
    (["render", "--scene", "face", "--size", "16", "--spp-list", "4,16", "--reference-spp", "16"],
     "--reference-spp"),
    (["render", "--scene", "face", "--size", "16", "--spp-list", "4,4"], "--spp-list"),
])
def test_face_bench_refusals(argv, names, capsys):
    assert_refused(["bench", *argv], names, capsys)


def test_face_bench_text_shows_no_none_and_the_json_gives_reasons(monkeypatch, capsys):
    """A preset the floor makes unreachable prints "—" (never ``None``), its reason in a note and the JSON."""
    pytest.importorskip("mitsuba")
    import skinrender.studies.benchmarks.bench_face as bench_face_module
    from skinrender.studies.benchmarks.bench_face import PRESET_THRESHOLDS, presets_of

    spps, reference = [4, 16], 64
    noise = presets_of(spps, [0.03, 0.025], reference)  # a floor above the draft threshold
    curve = [4, 16, 64, 256]
    direct = presets_of(curve, list(0.1 * (1 / np.array(curve) + 1 / 4096) ** 0.5), 4096)  # no floor
    assert noise["draft"] is None and direct["spp_at_floor"] is None
    result = {"scene": "face", "camera": "gbell", "size": [16, 16], "reference_spp": reference, "elapsed_s": 1.0,
              "thresholds": dict(PRESET_THRESHOLDS), "presets": {"noise": noise, "direct": direct},
              "curve": [{"level": "noise", "spp": 4, "seconds": 0.1, "skin_ncc_error": None, "skin_ncc_rms": None}]}
    monkeypatch.setattr(bench_face_module, "bench_face", lambda **kwargs: result)
    argv = ["bench", "render", "--scene", "face", "--size", "16", "--spp-list", "4,16", "--reference-spp", "64",
            "--levels", "direct,noise"]
    status, out, err = run(argv, capsys)
    assert status in (0, None), err[-500:]
    assert "None" not in out and "—" in out
    assert "noise draft: the error's floor" in out and "above the threshold 0.01" in out
    status, out, err = run([*argv, "--json"], capsys)
    document = json.loads(out)
    for presets in document["presets"].values():
        for key in ("draft", "standard", "reference", "spp_at_floor"):
            assert (presets[key] is None) == (key in presets["undefined"]), (key, presets)


@pytest.mark.parametrize("argv, names", [
    # checked before any timing starts
    (["render", "--plot", "curve.txt"], ("--plot", ".png")),
    (["render", "--quick", "--plot", "{file}/curve.png"], ("--plot", "is a file")),
    (["render", "--plot", "{folder}"], ("--plot", "is a folder")),
    (["search", "--workers", "100"], "--workers"),
    (["search", "--workers", "0"], "--workers"),
    (["sweep", "--workers", "100"], "--workers"),
    (["sweep", "--positions", "700:400:10"], "--positions"),
])
def test_chart_bench_refusals(argv, names, tmp_path, capsys):
    (tmp_path / "file").write_text("x")
    argv = [a.format(file=tmp_path / "file", folder=tmp_path) for a in argv]
    assert_refused(["bench", *argv], names, capsys)


@pytest.mark.parametrize("argv, names", [
    (["--sweep-combine", "2"], ("--sweep-combine", "--sweep")),
    (["--sweep-values", "2"], ("--sweep-values", "--sweep")),
    (["--sweep-positions", "400:700:100"], ("--sweep-positions", "--sweep")),
    # the sweep takes one of the two position flags, and its errors name the one given
    (["--sweep", "--positions", "400:700:50", "--sweep-positions", "400:700:100"], ("--positions", "--sweep-positions")),
    (["--sweep", "--sweep-positions", "700:400:10"], "--sweep-positions"),
    (["--sweep", "--sweep-positions", "300:700:100"], ("--sweep-positions", "--grid")),
    (["--workers", "1000"], "--workers"),
    (["--sweep", "--workers", "1000"], "--workers"),
    (["--illuminants", "3000,3300,3000"], ("--illuminants", "distinct")),
    (["--illuminants", "20,3300"], ("--illuminants", "no light")),
    (["--dask", "nonsense"], "--dask"),
])
def test_reproduce_refusals(argv, names, tmp_path, capsys):
    output = tmp_path / "out"
    small = [] if "--sweep-positions" in argv else ["--positions", "400:700:100", "--no-figures"]
    assert_refused(["reproduce", "-o", output, "--sensors", "3", "--quiet", *small, *argv], names, capsys)
    assert not output.exists()


@pytest.mark.parametrize("argv, names", [
    (["--spp", "0"], "--spp"),
    (["--seed", "4294967295"], ("--seed", "4294967294")),
    (["--camera", "nope"], "--camera"),
])
def test_table1_refusals_name_the_flag(argv, names, capsys):
    assert_refused(["table1", *argv], names, capsys)


def test_quick_search_bench_times_the_20nm_search_and_estimates_the_rest(capsys):
    status, out, err = run(["bench", "search", "--quick", "--sample", "2", "--workers", "1", "--json"], capsys)
    assert status in (0, None), err[-500:]
    document = json.loads(out)
    assert document["growth"][0]["measured"] == "full"
    assert all(g["measured"].startswith("estimated from 2 triplets") for g in document["growth"][1:])
    assert document["full_search_s"] is None and document["sweep_s_per_setting"] is None
    assert np.isfinite(document["fast_ms_per_triplet"]) and document["max_rel_difference"] < 1e-9


def test_face_bench_marks_extrapolated_presets(monkeypatch, capsys):
    """A preset the curve did not reach is the error model's extrapolation: starred, with a footnote."""
    pytest.importorskip("mitsuba")
    import skinrender.studies.benchmarks.bench_face as bench_face_module
    from skinrender.studies.benchmarks.bench_face import PRESET_THRESHOLDS, presets_of

    curve = [4, 16]
    presets = presets_of(curve, list(0.1 * (1 / np.array(curve)) ** 0.5), 4096)
    assert presets["extrapolated"]  # the reference threshold lies beyond 16 spp
    seen = {}
    result = {"scene": "face", "camera": "impulse@450,550,650", "size": [16, 16], "reference_spp": 64,
              "elapsed_s": 1.0, "thresholds": dict(PRESET_THRESHOLDS), "presets": {"direct": presets},
              "curve": [{"level": "direct", "spp": 4, "seconds": 0.1, "skin_ncc_error": 0.01, "skin_ncc_rms": 0.01}]}
    monkeypatch.setattr(bench_face_module, "bench_face", lambda **kwargs: seen.update(kwargs) or result)
    status, out, err = run(["bench", "render", "--scene", "face", "--size", "16", "--spp-list", "4,16",
                            "--levels", "direct", "--camera", "impulse@450,550,650"], capsys)
    assert status in (0, None), err[-500:]
    assert seen["camera_spec"] == "impulse@450,550,650"
    assert f"{presets[presets['extrapolated'][0]]}*" in out and "* extrapolated beyond the measured spp" in out


@pytest.mark.parametrize("argv, names", [(["--tolerance", "0"], "--tolerance"), (["--tolerance", "2"], "--tolerance"),
                                         (["--tolerance", "x"], "--tolerance"),
                                         # issue 36: an internal error (the bounds overflowed to infinity)
                                         (["--tolerance", "1e-320"], ("--tolerance", "float32"))])
def test_table1_tolerance_refused(argv, names, capsys):
    assert_refused(["table1", *argv], names, capsys)


def test_table1_exit_status_says_its_verdict(capsys):
    pytest.importorskip("mitsuba")
    status, out, err = run(["table1", "--spp", "16", "--tolerance", "0.0001", "--json"], capsys)
    document = json.loads(out)
    assert document["verdict"]["verdict"] in ("inconclusive", "fail") and status == document["exit_status"] != 0
    assert document["difference_eq1"]["verdict"] == "fail"  # Eq. 1 with WP differs, as the paper's Table 1 shows


@pytest.mark.parametrize("argv, names", [
    (["bench", "analytic", "--repeat", "1000000"], ("--repeat", "days", "--max-minutes")),
    (["bench", "search", "--sample", "100000"], ("--sample", "--max-minutes")),
    (["bench", "render", "--max-minutes", "5"], ("--max-minutes", "fixed amount of work")),
    (["bench", "render", "--scene", "face", "--spp-list", "64,256,1024", "--size", "256", "--max-minutes", "1"],
     ("--spp-list", "levels × (4096 + 2 × 1344) spp × 65536 pixels", "--max-minutes")),
    (["table1", "--spp", "1048576"], ("--spp", "at most 267232 spp")),
])
def test_work_and_its_flag_are_named(argv, names, capsys):
    """Seen: ``bench analytic --repeat 1000000`` ran on without an estimate; ``table1 --spp 1048576`` was blamed on
    --camera."""
    assert_refused(argv, names, capsys)


def test_the_face_bench_estimates_each_level_at_its_own_rate():
    """A subsurface-volume level in the face bench is estimated at its own (far slower) rate, as render and ladder do."""
    import argparse
    import re

    from skinrender.cli.studies import check_face_bench_work
    from skinrender.errors import SkinrenderError

    def minutes(levels):
        with pytest.raises(SkinrenderError) as error:
            check_face_bench_work(argparse.Namespace(max_minutes=0.001), levels, 128 * 128, [16, 64], 256)
        value, unit = re.search(r"about ([\d.]+) (s|min|h)", str(error.value)).groups()
        return float(value) * {"s": 1 / 60, "min": 1, "h": 60}[unit]

    assert minutes(["direct", "subsurface-volume"]) > 10 * minutes(["direct", "sheen"])


def test_reproduce_on_a_full_disk_leaves_no_folder_and_names_o(tmp_path, capsys, monkeypatch):
    """A file of the reproduce folder cannot be written: the folder (made in a temporary beside it) is removed,
    and the one line names -o and the reason, exit 1 (the machine's error)."""
    from .refusal import full_disk

    full_disk(monkeypatch, after=2)
    target = tmp_path / "out"
    status, out, err = run(["reproduce", "-o", target, "--sensors", "9", "--positions", "400:700:50", "--no-figures",
                            "--quiet", "--json"], capsys)
    assert status == 1 and out == "" and list(tmp_path.iterdir()) == []
    assert err.strip().splitlines()[-1] == (f"skinrender reproduce: error: -o {target}: cannot be written (no space "
                                            "left on the device (the disk is full)); nothing was left there")


@pytest.mark.parametrize("argv, name", [
    (["reproduce", "-o", "{out}", "--positions", "400:700:1"], "--positions"),
    (["reproduce", "-o", "{out}", "--sweep", "--sweep-positions", "400:700:1"], "--sweep-positions"),
    (["bench", "sweep", "--positions", "400:700:1"], "--positions"),
])
def test_searches_of_the_studies_are_capped_by_their_estimated_time(argv, name, tmp_path, capsys):
    """1 nm positions ran the paper's eight searches (4.5 million triplets each) for hours, unannounced."""
    line = assert_refused([a.format(out=tmp_path / "out") for a in argv], (name, "--max-minutes"), capsys,
                          output=tmp_path)
    assert "4499950 triplets" in line and "would take about" in line
