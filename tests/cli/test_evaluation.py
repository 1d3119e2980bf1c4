"""Bad inputs to ``locus`` (:mod:`skinrender.cli.evaluation`) are refused cleanly; coincident sensors are degenerate."""

from __future__ import annotations

import json

import pytest

from .refusal import assert_refused, bad_files, run  # noqa: F401  (fixture)

LOCUS = ["locus", "--camera", "gbell:9@450,540,610"]


@pytest.mark.parametrize("extra, names", [
    (["--calibration", ""], "--calibration"),
    (["--calibration", "nan"], "--calibration"),
    (["--illuminants", "20,3300"], ("--illuminants", "20K", "no light")),
    (["--illuminants", "x"], "--illuminants"),
    (["--boundary", "circle"], "--boundary"),
    (["--skin", "nosuch"], "--skin"),
    (["--nonskin", ","], "--nonskin"),
    (["--nonskin", "munsell,nosuch"], ("--nonskin", "nosuch")),
])
def test_locus_refuses(extra, names, capsys):
    assert_refused(LOCUS + extra, names, capsys)


@pytest.mark.parametrize("target", ["folder", "suffix", "parent_file", "empty"])
def test_locus_checks_the_plot_path_first(target, bad_files, tmp_path, capsys):
    path = {"folder": tmp_path, "suffix": tmp_path / "p.txt", "parent_file": bad_files["a_file"] / "p.png",
            "empty": ""}[target]
    assert_refused(LOCUS + ["--plot", path], "--plot", capsys, output=tmp_path)


@pytest.mark.parametrize("boundary", ["hull", "quadratic"])
def test_coincident_sensors_give_a_degenerate_locus(boundary, capsys):
    """Degenerate is not an error: zero area, flagged with the reason, nothing inside."""
    status, out, err = run(["locus", "--camera", "gbell:9@550,550,550", "--boundary", boundary, "--json"], capsys)
    document = json.loads(out)
    assert status == 0, err
    assert document["area"] == 0.0 and "coincident" in document["degenerate"]
    assert set(document["false_positive_rate"].values()) == {0.0}
