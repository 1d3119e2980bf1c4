"""
Tests for :mod:`skinrender.studies.face.ranking`: at ``direct`` Eq. 4 and the rendered faces rank the cameras alike
(the renderer's noise separated, the scores are Eq. 4's); the search's candidates; the summaries on scores whose
answer is known. Renders at 48 px, 12 replicates of 2 spp, one scene: the smallest at which every camera's props
keep enough pixels to be scored.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.studies.face.ranking import _level_from_scenes, _level_summary, rank, search_candidates, triplet_camera

CAMERAS = ["gbell:9@450,540,610", "gbell:9@560,570,590", "Nikon 5100 (NPL)"]


@pytest.fixture(scope="module")
def ranking():
    pytest.importorskip("mitsuba")
    return rank(CAMERAS, [(2856, 5900)], ["skin-model:melanin=0.02"], ["direct"], size=48, spp=16, workers=1)


def test_at_direct_the_rankings_agree(ranking, tmp_path):
    document = json.loads(json.dumps(ranking.document(), allow_nan=False))
    (level,) = document["levels"]
    assert level["level"] == "direct" and [c["camera"] for c in level["candidates"]] == CAMERAS
    for candidate in level["candidates"]:
        assert set(candidate) == {"camera", "score_eq4", "score_rendered", "score_bound", "rank_eq4", "rank_rendered"}
        assert candidate["score_rendered"] == pytest.approx(candidate["score_eq4"], abs=1e-12)
        assert candidate["rank_eq4"] == candidate["rank_rendered"]
    assert level["top_k_overlap"] == 1.0 and level["top_k"] == 3
    assert level["kendall_tau"] is None or level["kendall_tau"] >= 0.95
    assert document["skin_set"] == "skin" and document["replicates"] == 12 and document["spp"] == 24
    path = ranking.figure(tmp_path / "rank.png")
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_the_summary_on_known_scores():
    """Scores in the same order: τ 1; reversed: τ −1, another best; half-samples that disagree half the time:
    same_best null, with its reason; half-samples that lean towards Eq. 4's order while the whole sample reverses
    it: another best (their spread is about the whole sample's scores)."""
    names = ["a", "b", "c", "d"]
    eq4 = np.array([0.9, 0.8, 0.7, 0.6])
    same = _level_summary("x", names, eq4, eq4 + 0.01, np.tile(eq4, (24, 1)), 1.0, {})
    assert same["kendall_tau"] == 1.0 and same["kendall_tau_interval"] == [1.0, 1.0] and same["same_best"] is True
    flipped = _level_summary("x", names, eq4, eq4[::-1], np.tile(eq4[::-1], (24, 1)), 1.0, {})
    assert flipped["kendall_tau"] == -1.0 and flipped["same_best"] is False and flipped["best_rendered"] == "d"
    halves = np.array([eq4 if k % 2 else eq4[[1, 0, 2, 3]] for k in range(24)])
    mixed = _level_summary("x", names, eq4, halves.mean(axis=0), halves, 1.0, {})
    assert mixed["same_best"] is None and "cannot tell" in mixed["undefined"]["same_best"]
    leaning = _level_summary("x", names, eq4, eq4[::-1], np.tile(eq4, (24, 1)) + np.arange(24)[:, None] * 1e-4,
                             1.0, {})
    assert leaning["same_best"] is False and leaning["same_best_share"] == 0.0  # the halves' spread, not their lean
    tied = _level_summary("x", names, np.full(4, 0.5), eq4, np.tile(eq4, (24, 1)), 1.0, {})
    assert tied["kendall_tau"] is None and "every candidate scores the same" in tied["undefined"]["kendall_tau"]


def test_cameras_are_averaged_over_the_scenes_scored_for_every_camera():
    """A scene that one camera could not score is left out for every camera (else each camera's mean covers other
    scenes); a level with no such scene has null scores and answers with the reason (a NaN would rank first and make
    the JSON invalid)."""
    def scene(scores):
        return {"scores": [{"eq4": e, "rendered": r, "halves": [r] * 4, "factor": 1.0} for e, r in scores]}

    names = ["a", "b"]
    level = _level_from_scenes("x", names, [scene([(0.9, 0.9), (0.5, 0.5)]), scene([(0.1, 0.1), (None, None)])])
    assert [c["score_eq4"] for c in level["candidates"]] == [0.9, 0.5]  # the second scene left out for both
    assert level["best_rendered"] == "a" and "1 of 2 scenes" in level["undefined"]["scenes"]
    json.dumps(level, allow_nan=False)
    none = _level_from_scenes("x", names, [scene([(0.9, 0.9), (None, None)])])
    assert none["kendall_tau"] is None and none["same_best"] is None and none["best_rendered"] is None
    assert all(c["rank_eq4"] is None for c in none["candidates"]) and "every camera" in none["undefined"]["level"]
    json.dumps(none, allow_nan=False)


def test_the_searchs_candidates():
    """Positions 500, 550, 600 nm hold one triplet; asking for two is refused, naming top."""
    assert search_candidates(1, 9.0, "500:600:50", workers=1) == ["gbell:9@500,550,600"]
    with pytest.raises(SkinrenderError, match="top: 2 is not between 1 and the 1 triplets"):
        search_candidates(2, 9.0, "500:600:50", workers=1)
    assert triplet_camera(5, [400, 500, 600], slope=3) == "gbell:5,b=3@400,500,600"


def test_one_candidate_is_no_ranking():
    with pytest.raises(SkinrenderError, match="two or more candidates"):
        rank(CAMERAS[:1], [(2856, 5900)], ["skin-model:melanin=0.02"], ["direct"])
