"""
Skin detection
==============

Classify an image's pixels by a skin locus and score the result against the
known regions of a chart: true-positive rate over skin, false-positive rate
over everything else. The image can come from either road (a rendering, or
any ``(height, width, 3)`` array with its regions): this module never knows
which fed it.

-   :class:`Detection`, :func:`detect`.

Units: the image in output units (Eq. 4); rates are fractions in [0, 1].
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import SkinrenderError
from ..hints import NDArrayFloat
from ..model.chromaticity import ncc
from .locus import SkinLocus

__all__ = ["SCORED_MIN_OUTPUT", "Detection", "detect", "scored_pixels"]

SCORED_MIN_OUTPUT = 10.0
"""A pixel is scored when its brightest channel reaches this (output units; the paper's lower bound): the
threshold of ``detect`` on charts and faces, the ladder and the face loci."""


@dataclass(frozen=True)
class Detection:
    """
    Detection on a rendered chart: per-pixel ``mask``, per-patch rates,
    ``tpr`` and ``fpr`` (fractions), each ``None`` where it is undefined (a
    chart without skin or without non-skin patches, or none of their pixels
    scored: too dark to have a chromaticity), with the reason in
    ``undefined`` (``{"tpr": reason}``).
    """

    mask: NDArrayFloat
    per_patch: list
    tpr: float | None
    fpr: float | None
    undefined: dict = field(default_factory=dict)


def scored_pixels(image: NDArrayFloat, scored_min: float = 0.0) -> NDArrayFloat:
    """
    The pixels whose colour can be classified: light in some channel (negative noise counted as none), the
    brightest channel at least ``scored_min`` (output units). A black pixel has no chromaticity (Eq. 2 is 0/0).

    >>> scored_pixels(np.array([[[0.0, 0.0, 0.0], [0.0, 5.0, 1.0], [-1.0, 20.0, 3.0]]]), 10.0).tolist()
    [[False, False, True]]
    """
    brightest = np.max(np.maximum(np.asarray(image, dtype=np.float64), 0.0), axis=-1)
    return (brightest > 0) & (brightest >= scored_min)


def _unscored(scored_min: float) -> str:
    return "brightest channel > 0" + (f" and ≥ {scored_min:g}" if scored_min > 0 else "")


def _why_undefined(kind: str, patches: int, scored_min: float) -> str:
    if not patches:
        return f"the chart has no {kind} patch"
    return f"no scored {kind} pixel in its {patches} {kind} patch{'es' if patches > 1 else ''} ({_unscored(scored_min)})"


def detect(rendering, locus: SkinLocus, scored_min: float = 0.0) -> Detection:
    """
    Classify every pixel of a rendered chart by the skin locus.

    ``tpr`` is the share of skin patches' scored pixels inside the locus,
    ``fpr`` that of the other patches' scored pixels (the white reference and
    the black gaps are left out). A pixel is scored when it has light and its
    brightest channel reaches ``scored_min`` (output units; ``skinrender
    detect`` uses :data:`SCORED_MIN_OUTPUT`, as on faces):
    a pixel too dark has no chromaticity to classify, so a chart with nothing
    scored has undefined rates (``None`` and the reason), not 0. Each patch's
    row counts its ``pixels`` and ``scored_pixels``; its ``detected_fraction``
    is ``None`` (with ``undefined``) when none is scored.

    A bad argument (not a chart render, not a :class:`SkinLocus`, a ``scored_min`` that is not a finite number
    ≥ 0) raises a one-line :class:`SkinrenderError` naming it.
    """

    if not (hasattr(rendering, "image") and hasattr(getattr(rendering, "scene", None), "patch_pixels")):
        raise SkinrenderError(f"rendering: expected a chart render (skinrender.render(chart, …)), got "
                              f"{type(rendering).__name__}", role="rendering")
    if not isinstance(locus, SkinLocus):
        raise SkinrenderError(f"locus: expected a SkinLocus (skinrender.skin_locus(camera, …)), got "
                              f"{type(locus).__name__}", role="locus")
    if isinstance(scored_min, bool) or not isinstance(scored_min, (int, float, np.integer, np.floating)) or not (
            math.isfinite(scored_min) and scored_min >= 0):
        raise SkinrenderError(f"scored_min must be a finite number ≥ 0 (output units), got {scored_min!r}",
                              role="scored_min")
    chart = rendering.scene
    # a sensor's read noise can leave a dark pixel below its black level: nothing above black is no light
    image = np.maximum(rendering.image.astype(np.float64), 0.0)
    scored = scored_pixels(image, scored_min)
    mask = locus.contains(ncc(image)[..., :2]) & scored
    per_patch, counts = [], {True: [0, 0, 0], False: [0, 0, 0]}  # is_skin -> [hits, scored, patches]
    for i, patch in enumerate(chart.patches[:-1]):
        rows, columns = chart.patch_pixels(i)
        seen = scored[rows, columns]
        hits = int(mask[rows, columns].sum())
        row = {"name": patch.name, "is_skin": patch.skin,
               "detected_fraction": hits / int(seen.sum()) if seen.any() else None,
               "pixels": int(seen.size), "scored_pixels": int(seen.sum())}
        if not seen.any():
            row["undefined"] = f"no scored pixel ({_unscored(scored_min)})"
        per_patch.append(row)
        tally = counts[bool(patch.skin)]
        tally[0], tally[1], tally[2] = tally[0] + hits, tally[1] + int(seen.sum()), tally[2] + 1
    rates, undefined = {}, {}
    for key, kind, (hits, total, patches) in (("tpr", "skin", counts[True]), ("fpr", "non-skin", counts[False])):
        rates[key] = hits / total if total else None
        if not total:
            undefined[key] = _why_undefined(kind, patches, scored_min)
    return Detection(mask, per_patch, rates["tpr"], rates["fpr"], undefined)
