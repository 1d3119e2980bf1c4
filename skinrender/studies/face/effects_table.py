"""
What each effect does to skin detection, and what it costs
==========================================================

For light, medium and dark skin, the face at the base level and with each
effect alone (:data:`~skinrender.rendering.face.effects.LEVELS_EACH`, read
from the registry: a new effect gets its row), each a :func:`~skinrender.studies.face.ladder.ladder`
level: whether Eq. 4 still predicts the skin locus's true- and false-positive
rates there (each row's ``detection``, the table's verdict), how far the
effect moves the skin's mean NCC from Eq. 4 (``eq4_shift``, with its 95 %
upper bound) against the detection budget (a diagnostic), how it changes the
rates from ``direct``'s, what a shift of the budget would do to them, and the
seconds the level took. ``skinrender ladder
--effects`` prints it (``--plot``: :func:`skinrender.studies.face.effect_figures.figure_effects`).

-   :data:`SKIN_TONES`: the default skins (the skin model at three melanin
    fractions).
-   :func:`effects_table`, :class:`EffectsTable`: the study.

Units: NCC fractions; rates fractions; seconds s; temperatures K.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path

from ...errors import SkinrenderError
from ...evaluation.budget import BUDGET_FRACTION
from ...evaluation.detection_verdict import DETECTION_TOLERANCE
from ...rendering.face.shift import SKIN_SET_DEFAULT
from ...rendering.face.effects import LEVELS_EACH, PHYSICS_REGISTRY
from .detection_study import DetectionStudy
from .ladder import REPLICATES_LADDER, ladder

__all__ = ["SKIN_TONES", "ROW_KEYS", "EffectsTable", "effects_table"]

SKIN_TONES = {
    "light": "skin-model:melanin=0.02",
    "medium": "skin-model:melanin=0.13",
    "dark": "skin-model:melanin=0.3",
}
"""The skins of the table, tone → skin spec: the skin model at melanin volume fractions 0.02, 0.13 and 0.3 (issue
22's light, medium and dark), its other parameters at their defaults."""

ROW_KEYS = ("skin_set", "detection", "seconds", "spp", "eq4_shift", "eq4_shift_bound", "eq4_verdict", "budget", "within_budget", "tpr", "fpr",
            "tpr_change", "fpr_change", "budget_tpr_change", "budget_fpr_change", "skin_pixels", "prop_pixels")
"""The ladder's keys each row of the table carries (beside ``tone``, ``skin``, ``level`` and ``undefined``)."""


@dataclass(frozen=True)
class EffectsTable(DetectionStudy):
    """
    The table: ``rows`` (one per skin tone and level: ``tone``, ``skin``, ``level``, the :data:`ROW_KEYS` and
    ``undefined``), ``skins`` (per tone its ``skin``, Eq. 4's NCC and the detection ``budget``), the settings,
    and every level's ``eq4_shift`` verdict (``verdicts``, not in the document).
    """

    camera: str
    prevailing: float
    calibration: float
    size: tuple
    spp: int
    levels: tuple
    skins: list
    rows: list

    VERDICT_NAME = "effects table"

    def detection_rows(self) -> list[tuple[str, dict]]:
        """Each skin's and level's detection document, named by both (the table's :attr:`finding`)."""
        return [(f"{row['tone']} {row['level']}", row["detection"]) for row in self.rows]

    def document(self) -> dict:
        """The JSON document."""
        return {"camera": self.camera, "prevailing_K": self.prevailing, "calibration_K": self.calibration,
                "size": list(self.size), "spp": self.spp, "levels": list(self.levels), "skins": self.skins,
                "skin_set": self.skin_set, "detection_tolerance": self.detection_tolerance, "rows": self.rows,
                "finding": self.finding, **self.verdict.summary()}

    def figure(self, path) -> Path:
        """Draw the table (:func:`skinrender.studies.face.effect_figures.figure_effects`) to a PNG; returns ``path``."""
        from .effect_figures import figure_effects

        title = (f"What each effect does to skin detection: {self.camera}, {self.prevailing:g} K balanced to "
                 f"{self.calibration:g} K, {self.size[0]}×{self.size[1]} px, {self.spp} spp per level")
        return figure_effects(self.rows, title, path)


def effects_table(camera_, prevailing, calibration, skins: Mapping[str, str] | None = None,
                  levels: Sequence[str] = LEVELS_EACH, spp: int = 64, size: int | None = 64, seed: int = 0,
                  scene="face", variant: str | None = None, imager: str | None = None,
                  illuminance: float | None = None, replicates: int = REPLICATES_LADDER,
                  budget_fraction: float = BUDGET_FRACTION,
                  progress: Callable[[str], None] | None = None, skin_set=SKIN_SET_DEFAULT,
                  detection_tolerance: float = DETECTION_TOLERANCE) -> EffectsTable:
    """
    The ladder (:func:`~skinrender.studies.face.ladder.ladder`) at ``levels`` for each skin of ``skins``
    (tone → skin spec; default :data:`SKIN_TONES`), gathered per tone and level.

    ``levels`` must hold ``direct``: the rates' changes are from it. The other arguments are the ladder's
    (``skin_set``: the set the locus is built from; ``detection_tolerance``: each row's detection verdict).
    """
    skins = dict(SKIN_TONES if skins is None else skins)
    if not skins:
        raise SkinrenderError("skins: name at least one skin")
    levels = tuple(PHYSICS_REGISTRY.level(level) for level in levels)  # each spec parsed once, here
    base = PHYSICS_REGISTRY.base.name
    if all(level.names for level in levels):
        raise SkinrenderError(f"levels: the table compares each effect with {base!r}; add it, got "
                              f"{','.join(level.name for level in levels)!r}")
    rows, described, verdicts, result = [], [], [], None
    for tone, skin in skins.items():
        if progress is not None:
            progress(f"{tone} skin ({skin}) …")
        result = ladder(camera_, prevailing, calibration, skin, levels, spp, seed, size, scene, variant,
                        imager=imager, illuminance=illuminance, progress=progress, replicates=replicates,
                        budget_fraction=budget_fraction, skin_set=skin_set, detection_tolerance=detection_tolerance)
        described.append({"tone": tone, "skin": skin, "skin_ncc_analytic": result.skin_ncc_analytic,
                          "budget": result.budget})
        for row in result.levels:
            rows.append({"tone": tone, "skin": skin, "level": row["name"], **{key: row[key] for key in ROW_KEYS},
                         "undefined": row["undefined"]})
        verdicts.extend(replace(verdict, name=f"{tone} skin, {verdict.name}") for verdict in result.verdicts)
    return EffectsTable(result.camera, result.prevailing, result.calibration, result.size, int(spp),
                        tuple(level.name for level in levels), described, rows, verdicts=verdicts,
                        skin_set=result.skin_set, detection_tolerance=result.detection_tolerance)
