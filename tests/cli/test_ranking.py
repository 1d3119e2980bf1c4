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
    (["--seed", "-3"], "--seed"),                                         # issue 36's second round of bad inputs
    (["--lights", "2856/0"], "--lights"),
    (["--size", "0"], "--size"),
    (["--top", "1e9"], "--top"),
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


def test_a_camera_the_search_also_found_leaves_too_few_and_is_named(capsys, tmp_path, monkeypatch):
    """Only the search tells that a ``--camera`` is one of its triplets: with ``--top 1`` that leaves one candidate,
    refused naming --camera before any render (the search stubbed: its best triplet is the camera given)."""
    import skinrender.studies.face.ranking as ranking

    monkeypatch.setattr(ranking, "search_candidates", lambda *args, **kwargs: [CAM])
    monkeypatch.setattr(ranking, "rank", lambda *args, **kwargs: pytest.fail("rendered"))
    status, out, err = run(["rank", "--top", "1", "--camera", CAM, *SMALL, "--json"], capsys)
    last = err.strip().splitlines()[-1]  # after the estimate's line: the search ran
    assert status == 2 and out == "" and "Traceback" not in err
    assert "--camera" in last and "search's own triplet" in last and "--top 1" in last
