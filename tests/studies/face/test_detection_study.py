"""Tests of skinrender.studies.face.detection_study: the ladder's and the effects table's shared part."""

from dataclasses import dataclass

import pytest

from skinrender.evaluation.verdict import Verdict
from skinrender.studies.face.detection_study import DetectionStudy


@dataclass(frozen=True)
class Rows(DetectionStudy):
    """A study of named rows, each with its detection document (a study's own field before the shared ones)."""

    rows: list

    VERDICT_NAME = "rows"

    def detection_rows(self) -> list[tuple[str, dict]]:
        return [(row["name"], row["detection"]) for row in self.rows]


def test_the_finding_reads_the_rows_a_study_names_at_its_tolerance():
    """The finding names the row where Eq. 4 is off beyond the tolerance, and where it holds; the verdict combines
    the verdicts given (one failed: fail); the shared fields are keywords after the study's own."""
    rows = [{"name": "direct", "detection": {"verdict": "pass"}},
            {"name": "mixed", "detection": {"verdict": "fail", "tpr_change": 0.0, "fpr_change": 0.41,
                                            "tolerance": 0.05}}]
    verdicts = [Verdict("detection at direct", "pass", 0.05, "within"),
                Verdict("detection at mixed", "fail", 0.05, "beyond")]
    study = Rows(rows, verdicts=verdicts, skin_set="skin-tones", detection_tolerance=0.05)
    assert study.finding == ("Eq. 4 mispredicts detection (by more than 0.05) at: mixed (FPR +0.41); it holds at: "
                             "direct")
    assert study.verdict.outcome == "fail"
    assert Rows([]).skin_set == "skin" and Rows([]).finding == "no level had pixels to score"
    with pytest.raises(TypeError):
        Rows(rows, verdicts)  # the shared fields are keywords only


def test_a_study_that_names_no_rows_says_so():
    with pytest.raises(NotImplementedError, match="names its rows"):
        DetectionStudy().finding
