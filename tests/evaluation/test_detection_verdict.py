"""Tests for :mod:`skinrender.evaluation.detection_verdict`: the changes held to a tolerance, undefined rates, words."""

from __future__ import annotations

import pytest

from skinrender.errors import SkinrenderError
from skinrender.evaluation.detection_verdict import (DETECTION_KEYS, check_tolerance, detection_verdict, finding,
                                                     findings_text)

STEADY = [(1.0, 0.10)] * 12
"""Half-samples that agree: a standard error of 0."""


def test_the_decomposition_and_the_keys():
    """rendered = Eq. 4 + change + mc_floor, term by term; the issue's keys first."""
    document, verdict = detection_verdict((0.81, 0.19), (1.0, 0.10), (1.0, 0.10), STEADY)
    assert list(document)[:len(DETECTION_KEYS)] == list(DETECTION_KEYS)
    for key in ("tpr", "fpr"):
        assert document[f"{key}_rendered"] == pytest.approx(document[f"{key}_eq4"] + document[f"{key}_change"]
                                                            + document["mc_floor"][key])
    assert verdict.outcome == document["verdict"] == "pass" and document["tolerance"] == 0.02


@pytest.mark.parametrize("separated, samples, outcome", [
    ((0.90, 0.10), STEADY, "fail"),                                      # TPR 10 points below Eq. 4's, shown
    ((1.0, 0.115), [(1.0, 0.10), (1.0, 0.13)] * 6, "inconclusive"),      # 1.5 points, ± 1.5: cannot tell
    ((1.0, 0.105), [(1.0, 0.104), (1.0, 0.106)] * 6, "pass"),           # half a point, shown within 2
])
def test_the_verdict_follows_the_intervals(separated, samples, outcome):
    document, verdict = detection_verdict((0.9, 0.2), separated, (1.0, 0.10), samples, 0.02)
    assert verdict.outcome == outcome
    bound = max(document["tpr_change_bound"], document["fpr_change_bound"])
    assert (bound <= 0.02) == (outcome == "pass")


def test_a_rate_without_pixels_is_none_with_its_reason():
    """No scored skin pixel: TPR and its change are None with the reason (never 0), and only FPR is tested."""
    document, verdict = detection_verdict((None, 0.2), (None, 0.10), (None, 0.10), [(None, 0.10)] * 12)
    assert document["tpr"] is None and document["tpr_change"] is None and document["mc_floor"]["tpr"] is None
    assert "no scored skin pixel" in document["undefined"]["tpr"] and verdict.outcome == "pass"
    document, verdict = detection_verdict((None, None), (None, None), (None, None), [(None, None)] * 12)
    assert verdict.outcome == "not_applicable"


@pytest.mark.parametrize("value", [0, 1, -0.1, 2, "x", True, float("nan")])
def test_a_tolerance_outside_the_unit_interval_is_refused(value):
    with pytest.raises(SkinrenderError, match="--detection-tolerance: a rate as a fraction in"):
        check_tolerance(value, "--detection-tolerance")


def test_findings_in_words():
    mixed = {"verdict": "fail", "tpr_change": -0.004, "fpr_change": 0.41, "tolerance": 0.02}
    noise = {"verdict": "fail", "tpr_change": -0.11, "fpr_change": 0.05, "tolerance": 0.02}
    assert finding("noise", noise) == "noise (TPR -0.11, FPR +0.05)" and finding("direct", {"verdict": "pass"}) is None
    text = findings_text([("direct", {"verdict": "pass"}), ("mixed", mixed), ("sheen", {"verdict": "inconclusive"})])
    assert text == ("Eq. 4 mispredicts detection (by more than 0.02) at: mixed (FPR +0.41); it holds at: direct; "
                    "undecided (more samples needed) at: sheen")


def test_a_rate_of_too_few_pixels_is_undefined_not_a_finding():
    """``ladder --size 1``: one skin pixel, classified alike in every replicate (standard error 0), made a finding
    "Eq. 4 mispredicts detection … TPR −1.00" and exit 1; eq4_shift said the same pixels were too few."""
    from skinrender.evaluation.detection_verdict import PIXELS_MIN

    one = detection_verdict((0.0, None), (0.0, None), (1.0, None), [(0.0, None)] * 12, pixels={"skin": 1, "prop": 0})
    document, verdict = one
    assert verdict.outcome == "inconclusive" and document["tpr"] is None  # exit 3: undecided, never a pass
    assert f"only 1 scored skin pixels, fewer than {PIXELS_MIN}" in document["undefined"]["tpr"]
    enough = detection_verdict((0.0, None), (0.0, None), (1.0, None), [(0.0, None), (0.1, None)] * 6,
                               pixels={"skin": PIXELS_MIN, "prop": 0})
    assert enough[1].outcome == "fail" and enough[0]["tpr_change"] == -1.0


def test_a_rate_of_too_few_pixels_is_left_out_as_one_of_none():
    """One rate too few to judge, the other fine: the fine one is tested (a clear fail is a fail), as when the
    other had no pixel at all (the review: 5 prop pixels made it inconclusive where 0 gave the TPR's verdict)."""
    samples = [(0.5, 0.1), (0.5001, 0.1)] * 6
    verdicts = [detection_verdict((0.5, 0.1), (0.5, fpr), (1.0, fpr), samples, pixels={"skin": 100, "prop": prop})
                for prop, fpr in ((0, None), (5, 0.1))]
    assert [v.outcome for _, v in verdicts] == ["fail", "fail"]
    assert verdicts[1][0]["tpr_change_bound"] is not None and "only 5 scored prop" in verdicts[1][0]["undefined"]["fpr"]
