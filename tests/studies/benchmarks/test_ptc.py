"""
Tests for :mod:`skinrender.studies.benchmarks.ptc`: the photon transfer measured from rendered pixels recovers the
imager's stated conversion gain, read noise and full well, as EMVA 1288 would from a real camera.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from skinrender.cli import main
from skinrender.model.camera import camera
from skinrender.studies.benchmarks.ptc import photon_transfer

pytest.importorskip("mitsuba")

TOLERANCE_GAIN = 0.05
"""Relative: each point's temporal variance from 64 × 64 pixel differences is known to √(2/4095) ≈ 2.2 %; the
slope over ~10 points to ~1 %, so 5 % is ~4 σ."""

SATURATION_BAND = (0.85, 1.0)
"""EMVA's saturation capacity is the mean at the largest variance: below the full well (partly saturated pixels
already lose variance) by at most one exposure step (1.3/11 of the fill) here."""


@pytest.fixture(scope="module")
def imx174():
    return photon_transfer(camera("gbell:9@450,540,610"), "sony-imx174", points=12, spp=16, seed=1)


def test_gain_and_read_noise_recovered(imx174):
    stated = imx174["stated"]
    np.testing.assert_allclose(imx174["gain_dn_per_e"], stated["gain_dn_per_e"], rtol=TOLERANCE_GAIN)
    np.testing.assert_allclose(imx174["read_noise_e"], stated["read_noise_e"], rtol=TOLERANCE_GAIN)


def test_saturation_capacity_is_near_the_full_well(imx174):
    ratio = np.array(imx174["full_well_e"]) / imx174["stated"]["full_well_e"]
    assert np.all((ratio >= SATURATION_BAND[0]) & (ratio <= SATURATION_BAND[1])), ratio


def test_the_curve_starts_at_zero_and_is_linear(imx174):
    first = imx174["points"][0]
    assert first["exposure_s"] == 0 and np.allclose(first["mean_dn"], 0, atol=0.05)
    assert max(imx174["linearity_error"]) < 1.0  # percent: the model is linear below the well


def test_quantisation_hides_a_small_read_noise():
    """The 8-bit CCD preset: 20 e⁻ at 0.006 DN/e⁻ is 0.12 DN, under the ADC step: undefined, with the reason."""
    result = photon_transfer(camera("gbell:9@450,540,610"), "sony-icx418", points=16, spp=4)
    assert result["read_noise_e"] == [None, None, None] and "quantisation" in result["undefined"]["read_noise_e"]


def test_ptc_command_json_and_plot(tmp_path, capsys):
    status = main(["ptc", "--camera", "gbell:9@450,540,610", "--imager", "sony-imx174", "--points", "8", "--spp",
                   "4", "--plot", str(tmp_path / "ptc.png"), "--json"])
    document = json.loads(capsys.readouterr().out)
    assert status == 0 and (tmp_path / "ptc.png").is_file()
    assert {"points", "gain_dn_per_e", "read_noise_e", "full_well_e", "linearity_error", "stated"} <= set(document)
    assert set(document["points"][1]) >= {"exposure_s", "mean_dn", "variance_dn"}
    assert {"standard_error", "z", "checks", "verdict", "passed", "exit_status", "information_only"} <= set(document)
    assert document["verdict"] == "pass" and document["exit_status"] == 0 and document["checks"]["fits"]["alpha"] == 0.01
    assert len(document["standard_error"]["gain_dn_per_e"]) == 3 and len(document["z"]["read_noise_e"]) == 3


@pytest.mark.parametrize(("lux", "kelvin"), [(1e-3, 5900.0), (1e-9, 5900.0)])
def test_light_the_dark_current_outruns_is_refused_naming_the_illuminance(lux, kelvin, capsys):
    # dimmer than 10x the dark current, the series would be dark frames: refused before any number is made
    status = main(["ptc", "--camera", "gbell:9@450,540,610", "--imager", "sony-imx174", "--spp", "1",
                   "--illuminance", str(lux), "--temperature", str(kelvin), "--json"])
    out, err = capsys.readouterr()
    lines = [line for line in err.splitlines() if line.strip() and not line.startswith("rendering")]
    assert status == 2 and out == "" and len(lines) == 1, err
    assert "--illuminance" in lines[0] and "dark current" in lines[0]


def test_a_light_the_camera_does_not_see_is_refused_naming_the_temperature(capsys):
    status = main(["ptc", "--camera", "gbell:9@450,540,610", "--imager", "sony-imx174", "--temperature", "10", "--json"])
    out, err = capsys.readouterr()
    assert status == 2 and out == "" and err.strip().splitlines()[-1].startswith("skinrender ptc: error: --temperature")


@pytest.fixture(scope="module")
def imx174_dim():
    """1 lx: the series runs to ~29 s, where the dark current (10 e⁻/s) adds ~290 e⁻² of shot noise to 6.83² e⁻²."""
    return photon_transfer(camera("gbell:9@450,540,610"), "sony-imx174", illuminance_lux=1.0, points=12, spp=4,
                           seed=2)


def test_read_noise_leaves_out_the_dark_currents_shot_noise(imx174_dim):
    stated, gain = imx174_dim["stated"], np.array(imx174_dim["gain_dn_per_e"])
    last = imx174_dim["points"][-1]
    dark_e2 = (np.array(last["dark_variance_dn"]) - 1 / 12) / gain**2  # e⁻²: read noise² + dark electrons
    assert np.all(dark_e2 > 2 * stated["read_noise_e"] ** 2), dark_e2  # the dark noise grew with the exposure …
    np.testing.assert_allclose(imx174_dim["read_noise_e"], stated["read_noise_e"], rtol=TOLERANCE_GAIN)  # … not it


def test_dark_current_measured_from_the_dark_frames(imx174_dim):
    """The dark mean's slope over 12 exposures (each mean to ~0.01 DN of 4096 pixel pairs) over the gain."""
    np.testing.assert_allclose(imx174_dim["dark_current_e_per_s"], imx174_dim["stated"]["dark_current_e_per_s"],
                               rtol=TOLERANCE_GAIN)


def test_quantised_dark_frames_give_no_dark_current():
    result = photon_transfer(camera("gbell:9@450,540,610"), "sony-icx418", points=16, spp=4)
    assert result["dark_current_e_per_s"] == [None, None, None]
    assert "dither" in result["undefined"]["dark_current_e_per_s"]


@pytest.mark.parametrize("lux", [1e4, 1e12])
def test_a_dark_current_the_series_cannot_resolve_is_undefined(lux):
    """Seen: at 1e4 lx and above the fit gave −4.5 and −17.2 e⁻/s (up to −2e9 at 1e12 lx) for a stated 10, exit 0.
    Bright light means short exposures: too little dark charge to measure; undefined, saying why."""
    result = photon_transfer(camera("gbell:9@450,540,610"), "sony-imx174", illuminance_lux=lux, points=8, spp=1)
    assert result["dark_current_e_per_s"] == [None, None, None]
    assert "not resolved" in result["undefined"]["dark_current_e_per_s"]
    np.testing.assert_allclose(result["gain_dn_per_e"], result["stated"]["gain_dn_per_e"], rtol=2 * TOLERANCE_GAIN)


def test_a_reported_dark_current_is_positive_and_resolved():
    """Where the series is long enough (100 lx: ~0.3 s), each channel's dark current is reported, > 0 and
    within 4 standard errors (≤ 20 % each) of the stated figure; the standard errors (propagated from each dark
    mean's own) were calibrated on 400 seeds at 500 lx: z = (fit − stated)/SE had sd 0.97, 0.97, 1.01."""
    result = photon_transfer(camera("gbell:9@450,540,610"), "sony-imx174", illuminance_lux=100, points=24, spp=1)
    current = np.array(result["dark_current_e_per_s"], dtype=float)
    stated = result["stated"]["dark_current_e_per_s"]
    assert "dark_current_e_per_s" not in result["undefined"]
    assert np.all(np.abs(current - stated) <= 4 * 0.2 * current)


def test_the_ptc_text_shows_every_figure_of_the_json(capsys):
    """The dark current was in the JSON only; every per-channel figure is a column, undefined ones say why."""
    status = main(["ptc", "--camera", "gbell:9@450,540,610", "--imager", "sony-imx174", "--points", "8", "--spp",
                   "1", "--illuminance", "1e4"])
    out = capsys.readouterr().out
    assert status == 0
    for column in ("gain DN/e⁻", "read noise e⁻", "dark current e⁻/s", "full well e⁻", "linearity %"):
        assert column in out
    header = next(line for line in out.splitlines() if line.startswith("figure"))
    assert header.split() == ["figure", "channel", "fit", "stated", "SE", "z"]
    assert "test: difference" in out and "information only, full_well_e" in out and "verdict: PASS (exit status 0)" in out
    assert "dark_current_e_per_s undefined: not resolved" in out
