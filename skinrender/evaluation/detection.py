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

from dataclasses import dataclass, field

import numpy as np

from ..hints import NDArrayFloat
from ..model.chromaticity import ncc
from .locus import SkinLocus

__all__ = ["Detection", "detect"]


@dataclass(frozen=True)
class Detection:
    """
    Detection on a rendered chart: per-pixel ``mask``, per-patch rates,
    ``tpr`` and ``fpr`` (fractions), each ``None`` where it is undefined (a
    chart without skin, or without non-skin patches), with the reason in
    ``undefined`` (``{"tpr": reason}``).
    """

    mask: NDArrayFloat
    per_patch: list
    tpr: float | None
    fpr: float | None
    undefined: dict = field(default_factory=dict)


def detect(rendering, locus: SkinLocus) -> Detection:
    """
    Classify every pixel of a rendered chart by the skin locus.

    ``tpr`` is the share of skin patches' pixels inside the locus, ``fpr``
    that of the other patches' pixels (the white reference and the black gaps
    are left out).
    """

    chart = rendering.scene
    # a sensor's read noise can leave a dark pixel below its black level: nothing above black is no light
    rg = ncc(np.maximum(rendering.image.astype(np.float64), 0.0))[..., :2]
    mask = locus.contains(rg)
    per_patch, skin_hits, skin_total, other_hits, other_total = [], 0, 0, 0, 0
    for i, patch in enumerate(chart.patches[:-1]):
        rows, columns = chart.patch_pixels(i)
        hits = mask[rows, columns]
        per_patch.append({"name": patch.name, "is_skin": patch.skin, "detected_fraction": float(hits.mean())})
        if patch.skin:
            skin_hits, skin_total = skin_hits + hits.sum(), skin_total + hits.size
        else:
            other_hits, other_total = other_hits + hits.sum(), other_total + hits.size
    undefined = {}
    if not skin_total:
        undefined["tpr"] = "the chart has no skin patch"
    if not other_total:
        undefined["fpr"] = "the chart has no non-skin patch"
    tpr = float(skin_hits / skin_total) if skin_total else None
    fpr = float(other_hits / other_total) if other_total else None
    return Detection(mask, per_patch, tpr, fpr, undefined)
