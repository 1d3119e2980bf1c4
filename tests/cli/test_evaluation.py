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
    (["--nonskin", "munsell,,macbeth"], ("--nonskin", "empty")),
    (["--nonskin", "macbeth,macbeth"], ("--nonskin", "macbeth")),
    (["--munsell", "nosuch"], ("--munsell", "nosuch")),
    (["--munsell", "munsell-nickerson", "--nonskin", "macbeth"], ("--munsell", "not used")),
    (["--munsell", "macbeth"], ("--munsell macbeth is already in --nonskin",)),
    (["--skin", "SHORT_CSV"], ("--skin", "does not cover", "give spectra that cover it")),
    (["--munsell", "SHORT_CSV"], ("--munsell", "does not cover")),
    (["--camera", "SHORT_CAMERA"], ("--camera", "does not cover", "give spectra that cover it")),
])
def test_locus_refuses(extra, names, capsys, tmp_path):
    """``SHORT_*``: CSVs over 420–680 nm (locus has no --grid or --extrapolation: the advice says so)."""
    wavelengths = range(420, 681, 5)
    short = {"SHORT_CSV": "\n".join(f"{w},0.5,0.3" for w in wavelengths),
             "SHORT_CAMERA": "\n".join(f"{w},0.2,0.5,0.9" for w in wavelengths)}
    for name, text in short.items():
        (tmp_path / f"{name}.csv").write_text(text)
    extra = [str(tmp_path / f"{a}.csv") if a in short else a for a in extra]
    line = assert_refused(LOCUS + extra, names, capsys)
    assert "--grid" not in line and "--extrapolation" not in line


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


def test_locus_takes_the_munsell_set(capsys):
    """``--munsell`` (docs/contract.md: commands with skin and Munsell sets take both) replaces the 'munsell' item."""
    argv = LOCUS + ["--nonskin", "munsell,macbeth", "--json"]
    status, out, err = run(argv, capsys)
    default = json.loads(out)
    status_n, out_n, err_n = run(argv + ["--munsell", "munsell-nickerson"], capsys)
    nickerson = json.loads(out_n)
    assert status == status_n == 0, err + err_n
    assert default["munsell"] == "munsell" and nickerson["munsell"] == "munsell-nickerson"
    assert list(nickerson["false_positive_rate"]) == ["munsell", "macbeth"]  # keyed by the --nonskin items
    assert nickerson["false_positive_rate"]["macbeth"] == default["false_positive_rate"]["macbeth"]
    assert nickerson["polygon"] == default["polygon"]  # the locus is the skin set's alone
    assert nickerson["false_positive_rate"]["munsell"] != default["false_positive_rate"]["munsell"]


def test_the_nonskin_help_says_a_set_named_twice_is_refused(capsys):
    """Seen: the help said duplicates were "counted once" while they are refused."""
    from skinrender.cli import build_parser

    commands = next(a for a in build_parser()._actions if a.dest == "command").choices
    assert "a set named twice is refused" in " ".join(commands["locus"].format_help().split())
    assert_refused(["locus", "--camera", "gbell:9@450,540,610", "--nonskin", "macbeth,macbeth"], "--nonskin", capsys)


def test_the_locus_names_its_skin_set(capsys):
    """``--skin-set`` (``--skin`` its old spelling, still taken): the document says which set built the locus; the
    all-tones set's locus is larger than the Vrhel skins'."""
    import json

    from .refusal import assert_refused, run

    areas = {}
    for argv in (["--skin-set", "skin-tones"], ["--skin", "skin"], []):
        status, out, err = run(["locus", "--camera", "gbell:9@450,540,610", "--calibration", "5900", *argv, "--json"],
                               capsys)
        document = json.loads(out)
        areas[document["skin_set"]] = document["area"]
    assert set(areas) == {"skin", "skin-tones"} and areas["skin-tones"] > areas["skin"]
    for argv, name in ((["--skin-set", ""], "--skin-set"), (["--skin-set", "skin", "--skin", "skin"], "--skin")):
        assert_refused(["locus", "--camera", "gbell:9@450,540,610", *argv], name, capsys)


def test_a_bundled_set_off_the_grid_is_not_told_to_extrapolate(capsys):
    """``gamut``'s --extrapolation applies to CSV files: for the bundled skin set (390–730 nm) on 380–780 nm the
    advice was '--extrapolation', which the command then refused; ``search`` takes it for bundled sets (and says so
    in its notes), so there the advice stands."""
    gamut = ["gamut", "--camera", "gbell:9@450,540,610", "--calibration", "2856", "--reflectances", "skin",
             "--grid", "380:780:5"]
    line = assert_refused(gamut, ("--reflectances", "does not cover", "a bundled set is not extrapolated"), capsys)
    assert "--extrapolation" not in line
    search = ["search", "--sensor", "9", "--positions", "400:700:100", "--grid", "380:780:5"]
    assert "--extrapolation ('zero' or 'constant')" in assert_refused(search, ("--skin", "does not cover"), capsys)


def test_a_users_file_not_named_csv_is_still_told_to_extrapolate(tmp_path, capsys):
    """Only a bundled set is kept from the --extrapolation advice: a user's narrow.txt takes --extrapolation (the
    review found it told 'a bundled set is not extrapolated', going by the .csv suffix)."""
    narrow = tmp_path / "narrow.txt"
    narrow.write_text("wavelength,a\n450,0.3\n550,0.35\n650,0.5\n")
    gamut = ["gamut", "--camera", "gbell:9@450,540,610", "--calibration", "2856", "--reflectances", str(narrow)]
    line = assert_refused(gamut, ("--reflectances", "does not cover"), capsys)
    assert "--extrapolation ('zero' or 'constant')" in line and "bundled" not in line
