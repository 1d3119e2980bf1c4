"""
A face study judged by detection verdicts
=========================================

What the ladder (:class:`~skinrender.studies.face.ladder.Ladder`) and the effects table
(:class:`~skinrender.studies.face.effects_table.EffectsTable`) share, :class:`DetectionStudy`: their checks'
verdicts (combined into the study's verdict), the skin set the locus was built from, the detection tolerance, and
the finding in words (:func:`~skinrender.evaluation.detection_verdict.findings_text`) over the rows a study says
carry a detection verdict.

Units: rates fractions.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ...evaluation.detection_verdict import DETECTION_TOLERANCE, findings_text
from ...evaluation.verdict import Combined
from ...rendering.face.shift import SKIN_SET_DEFAULT

__all__ = ["DetectionStudy"]


@dataclass(frozen=True, kw_only=True)
class DetectionStudy(Combined):
    """
    A face study with a detection verdict per row; its fields are keywords, after the study's own.

    Attributes
    ----------
    verdicts
        Its checks' verdicts (not in a document), combined into :attr:`verdict`.
    skin_set
        The name of the reflectance set the skin locus was built from.
    detection_tolerance
        The change in TPR and in FPR Eq. 4 may be off by, a fraction in (0, 1).
    """

    verdicts: list = field(default_factory=list, repr=False, compare=False)
    skin_set: str = SKIN_SET_DEFAULT
    detection_tolerance: float = DETECTION_TOLERANCE

    def detection_rows(self) -> list[tuple[str, dict]]:
        """``(where, detection document)`` for each row with a detection verdict: what :attr:`finding` reads."""
        raise NotImplementedError(f"{type(self).__name__} names its rows with a detection verdict")

    @property
    def finding(self) -> str:
        """Where Eq. 4 mispredicts detection, where it holds and where the samples cannot tell, in words."""
        return findings_text(self.detection_rows(), self.detection_tolerance)
