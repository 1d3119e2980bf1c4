"""
Detection verdicts: is Eq. 4 right about the detection rates?
=============================================================

Eq. 4 is used to build a skin locus and to choose a camera; what it must get
right is therefore the locus's true- and false-positive rates. Given the rates
of a render with its Monte Carlo noise removed (``tpr``, ``fpr``; see
:mod:`skinrender.evaluation.noise_separation`), Eq. 4's prediction of the same
rates for the same pixels (``tpr_eq4``, ``fpr_eq4``) and the first's values on
half-samples of the independent replicates (the delete-K/2 jackknife), the changes ``tpr − tpr_eq4`` and
``fpr − fpr_eq4`` are held to a tolerance by an equivalence test
(:func:`~skinrender.evaluation.verdict.equivalence`, simultaneous over the
defined rates at α :data:`~skinrender.evaluation.verdict.ALPHA_EQUIVALENCE`):
``pass`` when both are shown within it, ``fail`` when one is shown beyond it,
``inconclusive`` otherwise. A rate with no pixel to score is ``None`` with its
reason, and is not tested.

The rates as rendered are kept (``tpr_rendered``, ``fpr_rendered``), and what
the noise alone did to them: ``mc_floor`` (``{tpr, fpr}``, rendered − noise
removed). So ``rendered = eq4 + change + mc_floor``, each term measured.

-   :data:`DETECTION_TOLERANCE`, :data:`HALVES_DETECTION`, :data:`DETECTION_KEYS`.
-   :func:`check_tolerance`: a tolerance in (0, 1), or a one-line error.
-   :func:`detection_verdict`: the document and the verdict.
-   :func:`finding`, :func:`findings_text`: a finding in words.

Units: rates fractions.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..errors import SkinrenderError
from .verdict import ALPHA_EQUIVALENCE, Verdict, equivalence

__all__ = ["PIXELS_MIN", "DETECTION_TOLERANCE", "HALVES_DETECTION", "DETECTION_KEYS", "check_tolerance",
           "detection_verdict", "finding", "findings_text"]

DETECTION_TOLERANCE = 0.02
"""How far, as a fraction, Eq. 4 may be off in TPR and in FPR unless told (``--detection-tolerance``)."""

HALVES_DETECTION = 24
"""Half-samples of the replicates (the delete-K/2 jackknife) behind a detection verdict's standard errors."""

DETECTION_KEYS = ("tpr", "fpr", "tpr_eq4", "fpr_eq4", "tpr_change", "fpr_change", "tpr_change_bound",
                  "fpr_change_bound", "tolerance", "verdict", "mc_floor")
"""The keys every ``detection`` document has (more follow them)."""

RATES = ("tpr", "fpr")

PIXELS_MIN = 10
"""Fewer tested pixels than this and a check has nothing to judge (too small an image, too little light): a rate
of one pixel is 0 or 1, its resampled standard error 0. Such a rate is left out of the detection test, as one of
no pixel (inconclusive where neither rate is judged); ``rendering.face.limits`` and ``eq4_shift`` hold their
checks inconclusive below it."""


def check_tolerance(value, flag: str = "tolerance") -> float:
    """
    A detection tolerance: a fraction in (0, 1) (``None``: :data:`DETECTION_TOLERANCE`), or a one-line
    :class:`~skinrender.errors.SkinrenderError` naming ``flag``.

    >>> check_tolerance("0.05", "--detection-tolerance"), check_tolerance(None)
    (0.05, 0.02)
    """
    if value is None:
        return DETECTION_TOLERANCE
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = float("nan")
    if isinstance(value, bool) or not 0 < number < 1:
        raise SkinrenderError(f"{flag}: a rate as a fraction in (0, 1) (e.g. 0.02 for two percentage points), got "
                              f"{value!r}", flag=flag if flag.startswith("--") else None,
                              role=None if flag.startswith("--") else flag)
    return number


def detection_verdict(rendered: Sequence, separated: Sequence, eq4: Sequence, samples: Sequence,
                      tolerance: float = DETECTION_TOLERANCE, alpha: float = ALPHA_EQUIVALENCE,
                      pixels: dict | None = None, name: str = "detection",
                      variance_factor: float = 1.0) -> tuple[dict, Verdict]:
    """
    The ``detection`` document and verdict of one render.

    Parameters
    ----------
    rendered, separated, eq4
        ``(tpr, fpr)`` as rendered, with the Monte Carlo noise removed, and as Eq. 4 predicts; ``None`` where
        no pixel of the kind was scored.
    samples
        ``(tpr, fpr)`` of ``separated`` on resamples of the replicates (two or more).
    variance_factor
        The standard error's square is this times the samples' variance: ``(K − k) / k`` for half-samples of
        ``k`` of ``K`` replicates (the delete-``(K − k)`` jackknife), 1 for a bootstrap.
    tolerance
        The change allowed, a fraction in (0, 1).
    pixels
        ``{"skin": n, "prop": n}`` scored (reported); a rate of fewer than :data:`PIXELS_MIN` is undefined, with
        the reason.

    Returns
    -------
    (dict, Verdict)
        :data:`DETECTION_KEYS` and ``tpr_rendered``, ``fpr_rendered``, ``tpr_change_se``, ``fpr_change_se``,
        ``alpha``, ``resamples``, ``pixels``, ``reason``, ``test``, ``undefined`` (``{key: reason}``).

    Examples
    --------
    >>> doc, v = detection_verdict((0.8, 0.2), (1.0, 0.10), (1.0, 0.11), [(1.0, 0.100), (1.0, 0.101)] * 6)
    >>> v.outcome, doc["tpr_change"], round(doc["fpr_change"], 3), round(doc["mc_floor"]["tpr"], 3)
    ('pass', 0.0, -0.01, -0.2)
    """
    tolerance = check_tolerance(tolerance)
    draws = np.array([[np.nan if v is None else v for v in sample] for sample in samples], dtype=np.float64)
    if draws.ndim != 2 or draws.shape[0] < 2:
        raise SkinrenderError(f"samples: the rates with each of two or more replicates left out, got {len(samples)}")
    variance = float(variance_factor) * np.var(draws, axis=0, ddof=1)
    document, errors, ses, undefined, few = {}, [], [], {}, []
    for j, key in enumerate(RATES):
        value, predicted, raw = separated[j], eq4[j], rendered[j]
        kind = "skin" if key == "tpr" else "prop"
        count = (pixels or {}).get(kind)
        too_few = value is not None and predicted is not None and count is not None and count < PIXELS_MIN
        if value is None or predicted is None or too_few:
            reason = (f"only {count} scored {kind} pixels, fewer than {PIXELS_MIN}: too few for a rate" if too_few
                      else f"no scored {kind} pixel (one material, brightest channel ≥ 10)")
            few += [reason] if too_few else []
            undefined.update({name_: reason for name_ in (key, f"{key}_eq4", f"{key}_change", f"{key}_change_bound",
                                                          f"{key}_change_se", f"{key}_rendered")})
            document.update({key: None, f"{key}_eq4": None, f"{key}_change": None, f"{key}_change_se": None,
                             f"{key}_rendered": None})
            continue
        change = float(value) - float(predicted)
        se = float(np.sqrt(variance[j])) if np.isfinite(variance[j]) else float("nan")
        document.update({key: float(value), f"{key}_eq4": float(predicted), f"{key}_change": change,
                         f"{key}_change_se": se, f"{key}_rendered": float(raw)})
        errors.append(change)
        ses.append(se)
    if few and not errors:  # pixels there, too few to judge either rate: undecided (exit 3), never not applicable
        verdict = Verdict(name, "inconclusive", alpha, "equivalence of the rates' changes with the tolerance (not "
                          "run)", reason="; ".join(few))
        uppers = iter([])
    elif errors and np.all(np.isfinite(ses)):  # the rates with pixels enough; one too few is left out, as one none
        verdict, bounds = equivalence(errors, ses, tolerance, alpha, name=name)
        uppers = iter(np.atleast_1d(bounds["upper"]).tolist())
    else:
        why = ("; ".join(dict.fromkeys(undefined[key] for key in RATES if key in undefined))
               or "no scored skin or prop pixel") if not errors else "a resample had no pixel to score"
        verdict = Verdict(name, "not_applicable" if not errors else "inconclusive", alpha,
                          "equivalence of the rates' changes with the tolerance (not run)", reason=why)
        uppers = iter([None] * len(errors))
    for key in RATES:
        document[f"{key}_change_bound"] = None if document[key] is None else next(uppers)
    floor = {key: (None if document[key] is None else document[f"{key}_rendered"] - document[key]) for key in RATES}
    document.update({"tolerance": tolerance, "verdict": verdict.outcome, "mc_floor": floor, "alpha": alpha,
                     "resamples": int(draws.shape[0]), "pixels": dict(pixels or {}), "reason": verdict.reason,
                     "test": verdict.test, "undefined": undefined})
    ordered = {key: document[key] for key in DETECTION_KEYS}
    ordered.update({key: value for key, value in document.items() if key not in ordered})
    return ordered, verdict


def findings_text(levels, tolerance: float = DETECTION_TOLERANCE) -> str:
    """
    The findings of several levels in one line: where Eq. 4 mispredicts detection (:func:`finding`), where the
    samples could not tell, or that it predicts it everywhere; ``levels`` are ``(name, detection document)``.

    >>> findings_text([("direct", {"verdict": "pass"}), ("mixed", {"verdict": "fail", "tpr_change": 0.0,
    ...                 "fpr_change": 0.41, "tolerance": 0.02})])
    'Eq. 4 mispredicts detection (by more than 0.02) at: mixed (FPR +0.41); it holds at: direct'
    """
    levels = list(levels)
    wrong = [finding(name, document) for name, document in levels if document.get("verdict") == "fail"]
    held = [name for name, document in levels if document.get("verdict") == "pass"]
    open_ = [name for name, document in levels if document.get("verdict") == "inconclusive"]
    parts = []
    if wrong:
        parts.append(f"Eq. 4 mispredicts detection (by more than {tolerance:g}) at: {', '.join(wrong)}")
    if held:
        parts.append(("it holds at: " if wrong else f"Eq. 4 predicts detection within {tolerance:g} at: ")
                     + ", ".join(held))
    if open_:
        parts.append("undecided (more samples needed) at: " + ", ".join(open_))
    return "; ".join(parts) if parts else "no level had pixels to score"


def finding(level: str, document: dict) -> str | None:
    """
    A level's detection finding in words, or ``None`` where Eq. 4 is not shown wrong: ``"mixed (FPR +0.41)"``
    (the changes shown beyond the tolerance, signed, as fractions).

    >>> finding("mixed", {"verdict": "fail", "tpr_change": -0.004, "fpr_change": 0.41, "tolerance": 0.02,
    ...                   "tpr_change_bound": 0.01, "fpr_change_bound": 0.45})
    'mixed (FPR +0.41)'
    """
    if document.get("verdict") != "fail":
        return None
    parts = [f"{key.upper()} {document[f'{key}_change']:+.2f}" for key in RATES
             if document.get(f"{key}_change") is not None and abs(document[f"{key}_change"]) > document["tolerance"]]
    return f"{level} ({', '.join(parts)})" if parts else level
