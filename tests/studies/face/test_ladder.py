"""Tests for :mod:`skinrender.studies.face.ladder`: the face at two levels of physics, tiny."""

from __future__ import annotations

import json

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.studies.face.ladder import ladder, ladders

pytest.importorskip("mitsuba")

CAMERA = "gbell:9@450,540,610"


class TestLadder:
    def test_two_levels(self):
        result = ladder(CAMERA, "A", 5900, levels=("direct", "mixed"), spp=96, size=32)
        document = json.loads(json.dumps(result.document(), allow_nan=False))
        assert [row["name"] for row in document["levels"]] == ["direct", "mixed"]
        assert document["size"] == [32, 32] and document["prevailing_K"] == 2856
        for row in document["levels"]:
            assert set(row) >= {"name", "seconds", "spp", "skin_ncc_mean", "skin_ncc_std", "tpr", "fpr", "eq4_shift",
                                "budget", "within_budget", "tpr_change", "fpr_change", "budget_tpr_change"}
            assert row["spp"] == 96 and row["replicates"] == 12 and row["spp_per_replicate"] == 8
            assert row["seconds"] > 0 and row["budget"] == document["budget"]["budget"] > 0
            assert row["skin_pixels"] > 0 and row["prop_pixels"] > 0
            assert abs(sum(row["skin_ncc_mean"]) - 1) < 1e-9 and 0 <= row["tpr"] <= 1 and 0 <= row["fpr"] <= 1
        direct, mixed = document["levels"]
        # direct light keeps the skin's NCC at Eq. 4's; the bluer window and sky pull it off, beyond the budget
        analytic = np.array(document["skin_ncc_analytic"])
        assert np.abs(np.array(direct["skin_ncc_mean"]) - analytic).max() < 3 * max(direct["skin_ncc_std"])
        assert mixed["skin_ncc_mean"][2] > direct["skin_ncc_mean"][2] + max(direct["skin_ncc_std"])
        assert direct["within_budget"] is True and mixed["within_budget"] is False
        assert direct["tpr_change"] == 0 and mixed["fpr_change"] == mixed["fpr"] - direct["fpr"]
        # the verdict is the detection's: Eq. 4 right at direct, the props let in under two lights
        assert direct["detection"]["verdict"] == "pass" and direct["detection"]["tpr_change"] == 0
        assert mixed["detection"]["verdict"] == "fail" and mixed["detection"]["fpr_change"] > 0.2
        assert all(row["skin_set"] == "skin" for row in document["levels"]) and document["skin_set"] == "skin"
        assert document["finding"].startswith("Eq. 4 mispredicts detection (by more than 0.02) at: mixed (FPR +")
        assert document["verdict"] == "fail" and document["exit_status"] == 1

    def test_frames_carry_the_masks_and_draw(self, tmp_path):
        """The arrays behind the figure: per level the image and masks, the counts those of the JSON rows."""
        result = ladder(CAMERA, "A", 5900, levels=("direct", "sheen"), spp=12, size=20)
        assert "frames" not in result.document() and len(result.frames) == 2
        for row, frame in zip(result.levels, result.frames):
            labels, scored, detected = frame["labels"], frame["scored"], frame["detected"]
            assert frame["image"].shape == (20, 20, 3) and labels.shape == scored.shape == detected.shape == (20, 20)
            assert int((scored & (labels == 1)).sum()) == row["skin_pixels"]
            assert int((scored & (labels > 1)).sum()) == row["prop_pixels"]
            assert not (detected & ~scored).any()  # only scored pixels are detected
            assert detected[scored & (labels == 1)].mean() == pytest.approx(row["tpr"])
        assert result.locus_polygon.shape[1] == 2 and result.label_names["skin"] == 1
        path = result.figure(tmp_path / "ladder.png")
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"

    def test_a_none_comes_with_its_reason(self):
        """At 2 px no skin pixel is scored: each None score has its reason in the level's ``undefined``."""
        result = ladder(CAMERA, "A", 5900, levels=("direct",), spp=12, size=2)
        for row in json.loads(json.dumps(result.document(), allow_nan=False))["levels"]:
            keys = ("skin_ncc_mean", "skin_ncc_std", "tpr", "fpr", "eq4_shift", "within_budget", "tpr_change",
                    "fpr_change")
            nones = {key for key in keys if row[key] is None}
            assert nones and set(row["undefined"]) == nones
            if "tpr" in nones:
                assert row["undefined"]["tpr"] == "no scored skin pixel (brightest channel ≥ 10)"
            detection = row["detection"]  # no pixel to score: the rates are None with their reason, never 0
            assert detection["tpr"] is None and "no scored skin pixel" in detection["undefined"]["tpr"]

    @pytest.mark.parametrize("kwargs, match", [
        ({"levels": ()}, "levels"), ({"levels": ("glossy",)}, "physics"), ({"prevailing": "x"}, "illuminant"),
        ({"skin": "skin:nobody"}, "skin"), ({"replicates": 2}, "replicates"),
        ({"detection_tolerance": 1.0}, "detection_tolerance"), ({"detection_tolerance": 0}, "detection_tolerance"),
    ])
    def test_refusals(self, kwargs, match):
        arguments = {"camera_": CAMERA, "prevailing": 2856, "calibration": 5900, "size": 8, "spp": 1,
                     **kwargs}
        with pytest.raises(SkinrenderError, match=match):
            ladder(**arguments)


def test_score_rendering_gives_a_reason_for_each_none():
    """The scoring the sweep shares: a dark render scores no pixel, and says why for each None."""
    from types import SimpleNamespace

    from skinrender.studies.face.ladder import score_rendering

    labels = np.array([[0, 1], [1, 2]])
    locus = SimpleNamespace(contains=lambda rg: np.ones(rg.shape[:-1], bool))
    dark = score_rendering(SimpleNamespace(image=np.full((2, 2, 3), 5.0), labels=labels), locus)
    assert dark["tpr"] is None and dark["fpr"] is None and dark["skin_ncc_mean"] is None
    assert set(dark["undefined"]) == {"skin_ncc_mean", "skin_ncc_std", "tpr", "fpr"}
    assert "no scored prop pixel" in dark["undefined"]["fpr"]
    lit = score_rendering(SimpleNamespace(image=np.full((2, 2, 3), 50.0), labels=labels), locus)
    assert lit["tpr"] == 1.0 and lit["undefined"] == {}


def test_ladders_see_every_camera_through_one_render_per_replicate():
    """Two cameras, one level: a ladder each, spectral (50 nm bands) or one render per camera (``bands=None``);
    each camera's analytic NCC and budget its own; the spectral level's seconds shared."""
    cams = [CAMERA, "Nikon 5100 (NPL)"]
    spectral = ladders(cams, "A", 5900, levels=("direct",), spp=12, size=16, bands="400:700:50")
    direct = ladders(cams, "A", 5900, levels=("direct",), spp=12, size=16, bands=None)
    assert [r.camera for r in spectral] == [r.camera for r in direct] == cams
    for s, d in zip(spectral, direct):
        assert s.skin_ncc_analytic == d.skin_ncc_analytic and s.budget == d.budget
        assert s.levels[0]["spp"] == d.levels[0]["spp"] == 12 and s.levels[0]["replicates"] == 12
    assert spectral[0].skin_ncc_analytic != spectral[1].skin_ncc_analytic
    with pytest.raises(SkinrenderError, match="outside the bands"):
        ladders(cams, "A", 5900, levels=("direct",), spp=12, size=16, bands="450:650:10")

