"""
The ladder's and the effects table's text: per level the detection rates as
rendered, with the renderer's noise separated and as Eq. 4 predicts them, the
detection verdict, and the NCC shift against the budget as a diagnostic; then
the finding in words and what the last line, the verdict, means.

Units: rates fractions; NCC fractions; times s.
"""

from __future__ import annotations

from .common import table

__all__ = ["ladder_text", "effects_text", "verdict_text", "shown"]

_WITHIN = {True: "yes", False: "NO", None: "—"}

VERDICT_MEANING = {
    "pass": "Eq. 4 predicts the detection rates within the tolerance at every level",
    "fail": ("a finding, not an error of the run: Eq. 4 is shown to mispredict the detection rates at a level of "
             "physics (the finding line says where and by how much)"),
    "inconclusive": "the samples cannot tell at some level: raise --spp or --size",
    "not_applicable": "no level had pixels to score",
}
"""What the ladder's verdict line means, per outcome."""


def shown(value, digits: str = ".4f") -> str:
    """A number, or ``—`` for ``None``."""
    return "—" if value is None else format(value, digits)


def _detection_cells(detection: dict) -> list[str]:
    def pair(key):
        return f"{shown(detection[key], '.3f')} ({shown(detection[key + '_eq4'], '.3f')})"

    return [shown(detection.get("tpr_rendered"), ".3f"), shown(detection.get("fpr_rendered"), ".3f"), pair("tpr"),
            pair("fpr"), shown(detection["tpr_change"], "+.3f"), shown(detection["fpr_change"], "+.3f"),
            detection["verdict"]]


DETECTION_HEADER = ["TPR seen", "FPR seen", "TPR (Eq. 4)", "FPR (Eq. 4)", "ΔTPR", "ΔFPR", "detection"]


def ladder_text(result, document: dict) -> str:
    """The ladder's table, its legend and its finding."""
    rows = [[row["name"], f"{row['seconds']:.2f}", row["spp"], *_detection_cells(row["detection"]),
             shown(row["eq4_shift"], ".3g"), _WITHIN[row["within_budget"]]] for row in document["levels"]]
    budget = document["budget"]
    return (f"the face ({result.skin}) through {result.camera}, {result.prevailing:g} K balanced to "
            f"{result.calibration:g} K, {result.size[0]}×{result.size[1]} px; the {document['skin_set']} skin "
            f"locus; Eq. 4's skin NCC {' '.join(f'{v:.4f}' for v in result.skin_ncc_analytic)}; detection budget "
            f"{shown(budget['budget'])} ({budget['reason']}):\n"
            + table(rows, ["level", "s", "spp", *DETECTION_HEADER, "shift", "within"])
            + "\n(seen: the rates as rendered, the renderer's noise in them; TPR, FPR: that noise separated, Eq. 4's "
            f"in brackets; detection: the changes held to ±{document['detection_tolerance']:g}; shift, within: the "
            "skin's NCC shift from Eq. 4 against the budget, a diagnostic)"
            + f"\nfinding: {document['finding']}")


def effects_text(result, document: dict) -> str:
    """The effects table: per skin and level the detection rates and verdict, and the shift."""
    rows = [[row["tone"], row["level"], *_detection_cells(row["detection"]), shown(row["eq4_shift"], ".3g"),
             shown(row["budget"], ".3g"), _WITHIN[row["within_budget"]], f"{row['seconds']:.1f}"]
            for row in document["rows"]]
    return (f"what each effect does to skin detection: {result.camera}, {result.prevailing:g} K balanced to "
            f"{result.calibration:g} K, {result.size[0]}×{result.size[1]} px, {result.spp} spp per level, the "
            f"{document['skin_set']} skin locus\n"
            + table(rows, ["skin", "level", *DETECTION_HEADER, "shift", "budget", "within", "s"])
            + f"\nfinding: {document['finding']}")


def verdict_text(document: dict) -> str:
    """The last line: the verdict, its exit status, and what it means."""
    outcome = document["verdict"]
    return (f"verdict: {outcome.upper().replace('_', ' ')} (exit status {document['exit_status']}): "
            f"{VERDICT_MEANING[outcome]}")
