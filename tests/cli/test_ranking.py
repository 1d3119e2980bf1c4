"""Tests for :mod:`skinrender.cli.ranking`: every flag refused by name before the search or a render; one small run."""

from __future__ import annotations

import json

import pytest

from .refusal import assert_refused, run

pytest.importorskip("mitsuba")

CAM = "gbell:9@450,540,610"
SMALL = ["--lights", "2856/5900", "--skin", "skin-model:melanin=0.02", "--levels", "direct", "--size", "48",
         "--workers", "1", "--quiet"]


@pytest.mark.parametrize("argv, names", [
    (["--top", "600"], ("--top", "560 triplets")),                       # beyond the 20 nm grid's triplets
    (["--top", "1"], ("--top", "two or more candidates")),
    (["--top", "0", "--camera", CAM], ("--top", "two or more candidates")),
    (["--top", "-1"], "--top"),
    (["--levels", "glossy"], "--levels"),
    (["--levels", ""], "--levels"),
    (["--skin-set", ""], "--skin-set"),
    (["--skin-set", "nothing-such"], "--skin-set"),
    (["--camera", "Sony 755"], "--camera"),
    (["--camera", CAM, "--camera", CAM], "--camera"),
    (["--lights", "2856"], "--lights"),
    (["--positions", "400:700"], "--positions"),
    (["--sensor", "0"], "--sensor"),
    (["--spp", "0"], "--spp"),
    (["--imager", "sony-icx418", "--levels", "direct"], "--imager"),
    (["--plot", "rank.txt"], "--plot"),
    (["--max-minutes", "0.01"], ("--top", "estimated", "--max-minutes")),
])
def test_refusals_name_the_flag(argv, names, capsys, tmp_path):
    assert_refused(["rank", *argv], names, capsys, output=tmp_path)


def test_two_cameras_at_direct(capsys, tmp_path):
    """No search (``--top 0``): two named cameras, ranked alike at direct; the answer line per level."""
    plot = tmp_path / "rank.png"
    status, out, err = run(["rank", "--top", "0", "--camera", CAM, "--camera", "Nikon 5100 (NPL)", *SMALL,
                            "--spp", "16", "--plot", str(plot), "--json"], capsys)
    assert status == 0, err[-500:]
    document = json.loads(out)
    (level,) = document["levels"]
    assert [c["camera"] for c in level["candidates"]] == [CAM, "Nikon 5100 (NPL)"]
    assert all(c["rank_eq4"] == c["rank_rendered"] for c in level["candidates"])
    assert document["candidates_from"]["top"] == 0 and document["plot"] == str(plot) and plot.stat().st_size > 0
    status, out, err = run(["rank", "--top", "0", "--camera", CAM, "--camera", "Nikon 5100 (NPL)", *SMALL,
                            "--spp", "16"], capsys)
    assert "would Eq. 4 still choose the same camera?" in out and "direct: " in out.splitlines()[-1]
