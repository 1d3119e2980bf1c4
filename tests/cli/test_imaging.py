"""
Tests for :mod:`skinrender.cli.imaging`: ``skinrender imagers`` and
``skinrender score`` through :func:`skinrender.cli.main`, their ``--json``
documents (docs/contract.md keys), and a one-line error (exit status 2) for every
bad number (:func:`tests.cli.refusal.assert_refused`).
"""

from __future__ import annotations

import json

import pytest

from skinrender.cli import main

from .refusal import assert_refused

CAMERA = "gbell:9@450,540,610"
FAST = ("--illuminants", "2500,4000,6500", "--munsell", "macbeth")
"""Three illuminants and the 24 Macbeth patches as the non-skin set keep each command well under a second."""


def run_json(capsys, *argv) -> dict:
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


class TestImagers:
    def test01_json(self, capsys):
        document = run_json(capsys, "imagers")
        rows = {row["name"]: row for row in document["imagers"]}
        assert {"sony-imx174", "sony-icx418"} <= set(rows)
        for row in rows.values():
            assert set(row) >= {"name", "source", "pixel_um", "full_well_e", "read_noise_e", "gain_dn_per_e", "bits"}
        assert rows["sony-imx174"]["full_well_e"] == 32691.0 and rows["sony-icx418"]["bits"] == 8

    def test02_text_table(self, capsys):
        assert main(["imagers"]) == 0
        out = capsys.readouterr().out
        assert "full well e⁻" in out and "sony-icx418" in out


class TestScore:
    def test01_noise_free_criteria(self, capsys):
        document = run_json(capsys, "score", "--camera", CAMERA, *FAST)
        assert 0 < document["ratio_all"] < 1 and 0 <= document["fpr"] <= 1
        assert document["illuminants_K"] == [2500.0, 4000.0, 6500.0] and "noisy" not in document

    def test02_noisy(self, capsys):
        document = run_json(capsys, "score", "--camera", CAMERA, *FAST, "--imager", "sony-imx174",
                            "--illuminance", "500", "--samples", "4", "--seed", "3")
        noisy = document["noisy"]
        assert set(noisy) >= {"illuminance_lux", "exposure_s", "tpr", "fpr", "tpr_se", "fpr_se", "samples", "imager"}
        assert noisy["imager"] == "sony-imx174" and noisy["illuminance_lux"] == 500.0 and noisy["samples"] == 4
        assert len(noisy["exposure_s"]) == 3 and all(0 < t < 1 for t in noisy["exposure_s"])
        assert 0 < noisy["tpr"] <= 1 and 0 <= noisy["fpr"] <= 1 and noisy["tpr_se"] > 0
        assert noisy["fpr_noise_free"] == pytest.approx(document["fpr"])
        again = run_json(capsys, "score", "--camera", CAMERA, *FAST, "--imager", "sony-imx174",
                         "--illuminance", "500", "--samples", "4", "--seed", "3")
        assert again == document  # seeded

    def test03_fixed_exposure_and_text(self, capsys):
        document = run_json(capsys, "score", "--camera", CAMERA, *FAST, "--imager", "sony-icx418",
                            "--illuminance", "1000", "--exposure", "0.002", "--samples", "2")
        assert document["noisy"]["exposure_s"] == [0.002] * 3
        assert main(["score", "--camera", CAMERA, *FAST, "--imager", "sony-icx418", "--illuminance", "1000",
                     "--samples", "2"]) == 0
        out = capsys.readouterr().out
        assert "TPR" in out and "FPR" in out and "1000 lx" in out

    @pytest.mark.parametrize(
        ("flags", "named"),
        [(("--illuminance", "0"), "--illuminance"), (("--illuminance", "-5"), "--illuminance"),
         (("--illuminance", "nan"), "--illuminance"), (("--illuminance", "inf"), "--illuminance"),
         (("--illuminance", "bright"), "--illuminance"),
         (("--illuminance", "500", "--exposure", "0"), "--exposure"),
         (("--illuminance", "500", "--exposure", "-0.01"), "--exposure"),
         (("--illuminance", "500", "--exposure", "NaN"), "--exposure"),
         (("--illuminance", "500", "--exposure", "soon"), "--exposure"),
         (("--illuminance", "500", "--samples", "0"), "--samples"),
         (("--illuminance", "500", "--samples", "2.5"), "--samples"),
         (("--illuminance", "500", "--seed", "-1"), "--seed"),
         (("--illuminance", "500", "--seed", "4294967296"), "--seed"),
         (("--illuminance", "500", "--seed", "1.5"), "--seed"),
         ((), "--illuminance")],
    )
    def test04_bad_numbers(self, capsys, flags, named):
        assert_refused(["score", "--camera", CAMERA, *FAST, "--imager", "sony-imx174", *flags], named, capsys)

    def test05_bad_imager_and_orphan_flags(self, capsys):
        assert_refused(["score", "--camera", CAMERA, "--imager", "no-such-imager", "--illuminance", "500"],
                       ("--imager", "sony-imx174"), capsys)
        assert_refused(["score", "--camera", CAMERA, "--illuminance", "500"], ("--illuminance", "--imager"), capsys)
        assert_refused(["score", "--camera", CAMERA, "--seed", "1"], ("--seed", "--imager"), capsys)


def test_score_black_frame_json_gives_null_with_reasons(capsys):
    document = run_json(capsys, "score", "--camera", CAMERA, *FAST, "--imager", "sony-icx418", "--illuminance",
                        "0.001", "--exposure", "1e-6", "--samples", "2")
    noisy = document["noisy"]
    assert noisy["tpr"] is None and noisy["skin_ncc_std"] == [None, None, None]
    assert {"tpr", "skin_ncc_std"} <= set(noisy["undefined"]) and noisy["black_share"]["skin"] == 1.0


def test_score_json_notes_the_capped_exposure_and_clipping(capsys):
    auto = run_json(capsys, "score", "--camera", CAMERA, *FAST, "--imager", "sony-icx418", "--illuminance", "500",
                    "--samples", "2")["noisy"]
    assert any("capped" in note for note in auto["notes"])
    long = run_json(capsys, "score", "--camera", CAMERA, *FAST, "--imager", "sony-icx418", "--illuminance", "500",
                    "--exposure", "1", "--samples", "2")["noisy"]
    assert max(long["clipping"]["skin"]["well_full"]) > 0 and any("full well" in note for note in long["notes"])


def test_score_samples_are_capped_by_their_estimated_time(capsys):
    """Seen: ``score --samples 100000000`` ran on without an estimate (1000 samples take ~44 s)."""
    line = assert_refused(["score", "--camera", CAMERA, "--imager", "sony-imx174", "--illuminance", "500",
                           "--samples", "100000000"], ("--samples", "--max-minutes"), capsys)
    assert "would take about" in line and "days" in line
    assert_refused(["score", "--camera", CAMERA, "--max-minutes", "5"], ("--max-minutes", "--imager"), capsys)


def test_ptc_points_are_refused_before_the_render(capsys):
    assert_refused(["ptc", "--camera", CAMERA, "--imager", "sony-imx174", "--points", "1000000"], "--points", capsys)
