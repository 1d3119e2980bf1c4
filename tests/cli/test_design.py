"""Bad inputs to ``search`` and ``design`` (:mod:`skinrender.cli.design`) are refused cleanly, before any work."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from .refusal import assert_refused, bad_files, run  # noqa: F401  (fixture)

SEARCH = ["search", "--sensor", "9", "--quiet", "--workers", "1"]
DESIGN = ["design", "--evaluations", "3"]


@pytest.mark.parametrize("extra, names", [
    (["--positions", "400:700:70"], ("positions", "not START")),
    (["--positions", "400:690:50"], ("positions", "not START")),
    (["--positions", "400:inf:10"], "positions"),
    (["--positions", "400:700:inf"], "positions"),
    (["--positions", "400:700:0"], "positions"),
    (["--positions", "700:400:10"], "positions"),
    (["--positions", "400:700:0.01"], ("positions", "triplets")),
    (["--positions", "400:410:10"], "positions"),
    (["--positions", "x"], "positions"),
    (["--positions", "400:700:1", "--max-triplets", "1000"], ("max_triplets", "--max-triplets")),
    (["--tie-tolerance", "-1"], "--tie-tolerance"),
    (["--tie-tolerance", "nan"], "--tie-tolerance"),
    (["--workers", "0"], "--workers"),
    (["--workers", "1000"], "--workers"),
    (["--max-triplets", "0"], "--max-triplets"),
    (["--max-triplets", "-5"], "--max-triplets"),
    (["--sensor", "0"], "sensor"),
    (["--sensor", "-3"], "sensor"),
    (["--sensor", "nan"], "sensor"),
    (["--slope", "0"], "--slope"),
    (["--slope", "nan"], "--slope"),
    (["--illuminants", "20,3300"], ("--illuminants", "20K", "no light")),
    (["--illuminants", "auto"], ("--illuminants", "auto")),
    (["--illuminants", "3000,3300,3000"], ("--illuminants", "distinct", "3000 K")),
    (["--imager", "sony-imx174", "--noise-samples", "0"], "--noise-samples"),
    (["--imager", "sony-imx174", "--noise-seed", "-1"], "--noise-seed"),
    (["--imager", "sony-imx174", "--noise-calibration", "3000"], ("--noise-calibration", "3300")),
    # the default calibration, 3300 K, is not among these: the flag is asked for, not the nearest light taken
    (["--imager", "sony-imx174", "--illuminants", "2000,6500"], ("--noise-calibration", "default 3300")),
    # the noise flags without --imager would be ignored
    (["--noise-seed", "3"], ("--noise-seed", "--imager")),
    (["--noise-calibration", "3300"], ("--noise-calibration", "--imager")),
    (["--grid", "380:780:5"], ("--skin", "extrapolation")),
    (["--illuminants", "2000,,x"], "--illuminants"),
    (["--sensor", "1", "--positions", "400.5:650.5:50"], ("--positions", "400.5")),
    (["--positions", "300:800:100"], ("--positions", "leave the integration grid")),  # it blamed --illuminants
    (["--positions", "0.4:0.7:0.05"], ("--positions", "in nm")),
    (["--skin", "skn"], ("--skin", "skn")),
    (["--munsell", ""], "--munsell"),
    (["--method", "quick"], "--method"),
    (["--grid", "400:700:0"], "--grid"),
    (["--dask", ""], "--dask"),
])
def test_search_refuses(extra, names, capsys):
    argv = list(SEARCH)
    if "--sensor" in extra:
        argv = ["search", "--quiet", "--workers", "1"]
    if "--workers" in extra:
        argv = ["search", "--sensor", "9", "--quiet"]
    assert_refused(argv + (["--positions", "400:700:50"] if "--positions" not in extra else []) + extra, names, capsys)


@pytest.mark.parametrize("key", ["binary.csv", "latin1.csv", "refl_nan.csv"])
def test_search_refuses_bad_sets(key, bad_files, capsys):
    assert_refused(SEARCH + ["--positions", "400:700:50", "--skin", bad_files[key]], "--skin", capsys)


@pytest.mark.parametrize("target", ["folder", "empty", "parent_file", "suffix", "unwritable"])
def test_search_checks_the_csv_path_before_searching(target, bad_files, tmp_path, capsys):
    if target == "unwritable" and not Path("/proc/self").is_dir():
        pytest.skip("needs Linux's /proc, a place no one can create files in")
    path = {"folder": tmp_path, "empty": "", "parent_file": bad_files["a_file"] / "x.csv",
            "suffix": tmp_path / "out.txt", "unwritable": "/proc/skinrender/x.csv"}[target]
    assert_refused(SEARCH + ["--positions", "400:700:50", "--csv", path], "--csv", capsys, output=tmp_path)


def test_search_extrapolates_named_sets_when_told(capsys):
    # the skin set is measured over 390–730 nm: a 380–780 nm grid needs --extrapolation, which named sets take too
    status, out, err = run(SEARCH + ["--positions", "400:700:100", "--grid", "380:780:5", "--extrapolation", "constant",
                                     "--json"], capsys)
    assert status == 0, err
    document = json.loads(out)
    assert document["triplets"] == 4
    # said, not silent: the set and the ranges (the helper's survey found notes: [])
    assert document["notes"] == ["--skin skin: measured over 390–730 nm, extrapolated ('constant') to the grid "
                                 "380–780 nm"]


@pytest.mark.parametrize("extra, expected", [
    ([], []),
    (["--sensor", "1", "--slope", "3"], ["--slope 3 does not apply"]),
    # two wavelength samples: every one-calibration cloud is flat
    (["--grid", "400:700:300"], ["every one-calibration skin gamut has zero volume",
                                 "every one-calibration Munsell gamut has zero volume"]),
    (["--imager", "sony-imx174", "--exposure", "10"], ["no triplet keeps a noisy TPR ≥ 0.9"]),
    (["--imager", "sony-imx174", "--illuminance", "500"], []),  # the auto exposure reaches its target
    (["--imager", "sony-icx418", "--illuminance", "5"], ["auto exposure capped at the longest exposure",
                                                         "no triplet keeps a noisy TPR ≥ 0.9"]),
])
def test_search_notes_what_its_tables_do_not_show(extra, expected, capsys):
    argv = [a for a in SEARCH if a != "9" and a != "--sensor"] + (["--sensor", "9"] if "--sensor" not in extra else [])
    status, out, err = run(argv + ["--positions", "400:700:100", *extra, "--json"], capsys)
    assert status == 0, err
    notes = json.loads(out)["notes"]
    assert len(notes) == len(expected) and all(n.startswith(e) for n, e in zip(notes, expected)), notes


def test_search_writes_its_csv_where_told(tmp_path, capsys):
    status, out, _ = run(SEARCH + ["--positions", "400:700:100", "--csv", tmp_path / "new" / "s.csv", "--json"], capsys)
    assert status == 0 and json.loads(out)["triplets"] == 4 and (tmp_path / "new" / "s.csv").is_file()


@pytest.mark.parametrize("extra, names", [
    (["--evaluations", "0"], "--evaluations"),
    (["--evaluations", "-1"], "--evaluations"),
    (["--sensor", "-3"], "--sensor"),
    (["--sensor", "0"], "--sensor"),
    (["--slope", "0"], "--slope"),
    (["--slope", "-2"], "--slope"),
    (["--starts", "550,550,550"], "--starts"),
    (["--starts", "300,540,800"], "--starts"),
    (["--starts", "nan,540,610"], "--starts"),
    (["--starts", "450,540"], "--starts"),
    (["--starts", ""], "--starts"),
    (["--starts", "450,540,610;"], "--starts"),  # an empty start is refused, not dropped
    (["--starts", "450,540,610;;420,550,680"], "--starts"),
    (["--objective", "beauty"], "--objective"),
    (["--munsell", "nosuch"], "--munsell"),
    (["--imager", "sony-imx174", "--noise-calibration", "3000"], "--noise-calibration"),
    (["--imager", "sony-imx174", "--noise-samples", "1001"], "--noise-samples"),
])
def test_design_refuses(extra, names, capsys):
    assert_refused(DESIGN + extra, names, capsys)


@pytest.mark.skipif(not hasattr(__import__("signal"), "SIGINT") or __import__("os").name != "posix", reason="POSIX")
def test_ctrl_c_stops_a_search_with_one_line_and_no_worker_left(tmp_path):
    """Ctrl-C during a parallel search: exit 130, one line, no traceback from the parent or its workers. The
    interrupt follows the search's own progress line (it slept 5 s before); 35 990 triplets cannot finish first."""
    from .refusal import interrupt_after

    status, out, err = interrupt_after(["search", "--sensor", "9", "--positions", "400:700:5", "--workers", "2"],
                                       "sensor 9: ")
    assert status == 130, err[-800:]
    assert err.strip().splitlines()[-1] == "skinrender search: interrupted"
    assert "Traceback" not in err and out == ""


def test_a_noisy_design_says_what_its_value_stands_for(capsys):
    """``design --imager``: the best camera's noisy TPR and FPR; where no start keeps TPR ≥ 0.9 the value is a
    penalty (1 + 0.9 − TPR), said in a note, and a capped auto exposure is noted (both were silent)."""
    status, out, err = run(["design", "--starts", "450,540,610", "--evaluations", "2", "--imager", "sony-icx418",
                            "--json"], capsys)
    document = json.loads(out)
    assert status == 0, err
    tpr = document["noisy"]["tpr"]
    assert 0.0 <= tpr <= 1.0 and 0.0 <= document["noisy"]["fpr"] <= 1.0
    if tpr < 0.9:
        assert document["value"] == pytest.approx(1.0 + 0.9 - tpr)
        assert any("penalty" in note for note in document["notes"])
    else:
        assert document["value"] == pytest.approx(document["noisy"]["fpr"])
    assert any(note.startswith("auto exposure capped") for note in document["notes"])  # icx418 at 500 lx: 0.49


def test_a_full_disk_leaves_no_partial_csv(tmp_path, capsys, monkeypatch):
    """Seen: ``search --csv`` on a full disk left ``*.partial`` and named no argument."""
    from .refusal import full_disk

    full_disk(monkeypatch)
    status, out, err = run([*SEARCH, "--positions", "400:700:50", "--csv", tmp_path / "rows.csv", "--json"], capsys)
    assert status == 1 and out == "" and list(tmp_path.iterdir()) == []
    assert err.strip() == (f"skinrender search: error: --csv {tmp_path / 'rows.csv'}: cannot be written (no space "
                           "left on the device (the disk is full)); nothing was written")


@pytest.mark.parametrize("extra, names", [
    (["--evaluations", "100000"], ("--evaluations", "13 h", "--max-minutes")),
    (["--evaluations", "400", "--max-minutes", "1"], ("--evaluations", "--max-minutes")),
    (["--max-minutes", "0"], "--max-minutes"),
])
def test_design_work_is_capped_by_its_estimated_time(extra, names, capsys):
    assert_refused(["design", *extra], names, capsys)


def test_search_and_reproduce_take_one_sensor_rule(capsys):
    """Seen: reproduce said a gbell sensor needs N > 1, search N > 0; the model takes any N > 0."""
    from skinrender.constants import SENSOR_RULE

    for argv, name in ((["search", "--sensor", "-1"], "--sensor"),
                       (["reproduce", "-o", "unused", "--sensors", "1,-1"], "--sensors")):
        assert SENSOR_RULE in assert_refused(argv, name, capsys)


def test_a_noisy_search_is_capped_by_its_estimated_time(capsys):
    """--noise-samples 1000 on the 10 nm grid was ~14 h with no estimate."""
    assert_refused(["search", "--sensor", "9", "--imager", "sony-imx174", "--noise-samples", "1000"],
                   ("--noise-samples", "--max-minutes"), capsys)
