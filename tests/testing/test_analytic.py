"""Tests for :mod:`skinrender.testing.analytic`: a render shown within a tolerance of Eq. 4 passes; a failed or
inconclusive verdict raises, the latter with the spp needed."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from skinrender.evaluation.verdict import Verdict
from skinrender.testing import assert_matches_analytic

CAMERA = "gbell:9@450,540,610"


def fake_validate(outcome: str, bound: float | None = 0.004, spp_needed: int | None = 2900):
    def validate(scene, camera, prevailing, calibration, spp, seed, tolerance):
        verdict = Verdict("equivalence", outcome, 0.05, "TOST", reason=f"{outcome} for the test")
        return SimpleNamespace(verdict=verdict, bound=bound, spp_needed=spp_needed, scene=scene, spp=spp,
                               tolerance=tolerance)
    return validate


@pytest.mark.parametrize("outcome, bound, needed, match", [
    ("fail", 0.03, None, r"macbeth through gbell:9@450,540,610 at 4 spp \(seed 0\): not within tolerance 0.002 of "
                         r"Eq. 4 \(fail\): fail for the test; the bound reached is 0.03"),
    ("inconclusive", 0.004, 2900, r"not shown within tolerance 0.002 of Eq. 4, inconclusive: inconclusive for the "
                                  r"test; the bound reached is 0.004; about 2900 spp would decide"),
    ("inconclusive", None, None, r"inconclusive for the test; no spp can show it"),
])
def test_anything_but_pass_raises(monkeypatch, outcome, bound, needed, match):
    monkeypatch.setattr("skinrender.rendering.validation.validate", fake_validate(outcome, bound, needed))
    with pytest.raises(AssertionError, match=match):
        assert_matches_analytic("macbeth", camera=CAMERA, prevailing="A", calibration=5000, spp=4, tolerance=0.002)


def test_pass_returns_the_validation(monkeypatch):
    monkeypatch.setattr("skinrender.rendering.validation.validate", fake_validate("pass"))
    result = assert_matches_analytic("macbeth", camera=CAMERA, prevailing="A", calibration=5000, spp=64,
                                     tolerance=0.01)
    assert result.verdict.outcome == "pass" and result.tolerance == 0.01


def test_passes_at_1024_spp_within_one_percent():
    pytest.importorskip("mitsuba")
    result = assert_matches_analytic("macbeth", camera=CAMERA, prevailing="A", calibration=5000, spp=1024,
                                     tolerance=0.01)
    assert result.verdict.outcome == "pass"


def test_raises_at_4_spp_within_two_per_mille():
    pytest.importorskip("mitsuba")
    with pytest.raises(AssertionError, match="tolerance 0.002"):
        assert_matches_analytic("macbeth", camera=CAMERA, prevailing="A", calibration=5000, spp=4, tolerance=0.002)
