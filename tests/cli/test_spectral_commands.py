"""
Tests for :mod:`skinrender.cli.spectral_commands`: ``render SCENE --spectral`` writes the bands' EXR (one JSON
document, the header's settings), ``sr.read_spectral`` reads it back, and bad requests are refused in one line
naming the flag, nothing written; ``bench render --spectral`` refuses what does not go with it.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import skinrender as sr

from .refusal import assert_refused, run

pytest.importorskip("mitsuba")


def test_render_a_chart_spectrally(tmp_path, capsys):
    target = tmp_path / "bands.exr"
    status, out, err = run(["render", "macbeth", "--spectral", "--prevailing", "A", "--spp", "2", "--bands",
                            "400:700:20", "-o", target, "--json"], capsys)
    assert status == 0, err
    document = json.loads(out)
    assert document["bands_nm"] == "400:700:20" and document["bands"] == 16 and document["basis"] == "hat"
    assert document["channels"][:2] == ["400nm", "420nm"] and document["prevailing_K"] == 2856.0
    assert document["memory_estimate_bytes"] > 0 and document["image"] == str(target)
    image = sr.read_spectral(target)
    assert image.bands.step == 20 and image.image.shape[-1] == 16
    assert np.all(np.isfinite(image.through("Nikon 5100 (NPL)", 5900).image))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bands.exr"]  # no preview: no camera to show


def test_render_a_face_spectrally_with_its_label_channel(tmp_path, capsys):
    target = tmp_path / "face.exr"
    status, out, err = run(["render", "face", "--spectral", "--prevailing", "2856", "--spp", "1", "--size", "8",
                            "--physics", "sheen", "--bands", "400:700:50", "-o", target], capsys)
    assert status == 0, err
    assert "7 bands" in out and "read_spectral" in out
    image = sr.read_spectral(target)
    assert image.physics == "sheen" and image.labels.shape == (8, 8) and (image.labels == 1).any()


@pytest.mark.parametrize("extra, names", [
    (["--camera", "gbell:9@450,540,610"], "--camera"),
    (["--calibration", "5900"], "--calibration"),
    (["--knee"], "--knee"),
    (["--bands", "380:700:5"], ("--bands", "380–700 nm")),
    (["--bands", "400:700:0.1"], "--bands"),
    (["--physics", "subsurface"], "--physics"),
    (["--imager", "sony-icx418"], "--imager"),
])
def test_bad_spectral_renders_are_refused(tmp_path, capsys, extra, names):
    assert_refused(["render", "macbeth", "--spectral", "--prevailing", "2856", "--spp", "1", "-o",
                    tmp_path / "x.exr", *extra], names, capsys, tmp_path)


def test_render_without_spectral_still_needs_camera_and_calibration(tmp_path, capsys):
    assert_refused(["render", "macbeth", "--prevailing", "2856", "-o", tmp_path / "x.exr"],
                   ("--camera", "--calibration", "--spectral"), capsys, tmp_path)
    assert_refused(["render", "macbeth", "--camera", "gbell:9@450,540,610", "--prevailing", "2856",
                    "--calibration", "2856", "--bands", "400:700:5", "-o", tmp_path / "x.exr"], "--bands", capsys,
                   tmp_path)


@pytest.mark.parametrize("extra, name", [(["--scene", "face"], "--scene"), (["--quick"], "--quick"),
                                         (["--cameras", "0"], "--cameras"), (["--cameras", "5,5"], "--cameras"),
                                         (["--cameras", "62"], "--cameras")])
def test_bench_spectral_refusals(capsys, extra, name):
    assert_refused(["bench", "render", "--spectral", *extra], name, capsys)


def test_cameras_goes_with_the_spectral_bench(capsys):
    assert_refused(["bench", "render", "--cameras", "5"], ("--cameras", "--spectral"), capsys)
