"""
Accuracy budgets in detection terms
===================================

How far the analytic model (Eq. 4) may be off before the error matters for
skin detection by a skin locus (:mod:`skinrender.evaluation.locus`).

The detection budget of a skin chromaticity ``p`` (Eq. 4's NCC (r, g) of the
skin under the prevailing light, white balanced to the calibration) is

``budget = BUDGET_FRACTION · |d|``,

``d`` the signed distance from ``p`` to the locus's boundary (positive inside).
A shift of the skin's chromaticity within the budget cannot carry ``p``
across the boundary, on whichever side it lies: it cannot change whether Eq.
4's skin is detected, and it uses at most that fraction of the margin that
keeps the skin's pixels inside (or outside). The budget follows the camera,
the lights and the skin: a skin near the boundary has a small budget (no
error is harmless there), one deep inside a large one. What a shift of the
budget does to the detection rates is measured on pixels with
:func:`rates_shifted` (the pixels moved towards the nearest boundary point).

-   :data:`BUDGET_FRACTION`: the stated fraction.
-   :func:`boundary_distance`: the signed distance to a locus's boundary and
    the nearest boundary point.
-   :class:`DetectionBudget`, :func:`detection_budget`: the budget of a skin
    chromaticity.
-   :func:`rates_shifted`: TPR and FPR of chromaticities, and after a shift.

Units: NCC (r, g) fractions; rates fractions.

References
----------
-   :cite:`Storring2001` : see :mod:`skinrender.evaluation.locus` (the skin
    locus).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import SkinrenderError
from ..hints import ArrayLike, NDArrayFloat
from .locus import SkinLocus

__all__ = ["BUDGET_FRACTION", "boundary_distance", "DetectionBudget", "detection_budget", "rates_shifted"]

BUDGET_FRACTION = 0.5
"""The share of the distance from Eq. 4's skin chromaticity to the skin locus's boundary that an error of Eq. 4 may
use: half the margin (a shift within it leaves the skin's chromaticity on its side of the boundary with at least half
of the margin to spare)."""


def boundary_distance(locus: SkinLocus, point: ArrayLike) -> tuple[float, NDArrayFloat]:
    """
    The signed distance from an NCC (r, g) ``point`` to the boundary of ``locus`` (positive inside, negative
    outside) and the nearest point of the boundary.

    Examples
    --------
    >>> from skinrender.evaluation.locus import hull_locus
    >>> square = hull_locus(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]), np.array([5000.0]), None)
    >>> distance, nearest = boundary_distance(square, [0.5, 0.8])
    >>> round(distance, 6), nearest.round(6).tolist()
    (0.2, [0.5, 1.0])
    >>> round(boundary_distance(square, [1.5, 0.5])[0], 6)
    -0.5
    """
    p = np.asarray(point, dtype=np.float64).reshape(2)
    if locus.degenerate is not None:
        raise SkinrenderError(f"the skin locus has no boundary: {locus.degenerate}")
    start = np.asarray(locus.polygon, dtype=np.float64)
    edge = np.roll(start, -1, axis=0) - start
    length2 = np.maximum(np.sum(edge**2, axis=1), np.finfo(float).tiny)
    along = np.clip(np.sum((p - start) * edge, axis=1) / length2, 0.0, 1.0)
    foot = start + along[:, None] * edge
    gaps = np.linalg.norm(p - foot, axis=1)
    nearest = int(np.argmin(gaps))
    sign = 1.0 if bool(locus.contains(p[None])[0]) else -1.0
    return sign * float(gaps[nearest]), foot[nearest]


@dataclass(frozen=True)
class DetectionBudget:
    """
    The detection budget of a skin chromaticity.

    Attributes
    ----------
    budget
        The NCC (r, g) shift Eq. 4 may be off by (Euclidean), ``fraction · |margin|``; ``None`` when undefined.
    fraction
        The share of the margin (:data:`BUDGET_FRACTION` unless stated).
    margin
        The signed distance from ``point`` to the locus's boundary (positive inside); ``None`` without a boundary.
    point, nearest
        The skin chromaticity (Eq. 4's (r, g)) and the nearest boundary point.
    direction
        The unit vector from ``point`` to ``nearest``: the shift that changes detection soonest.
    reason
        Why the budget is undefined (``None`` when defined), or what it is, in words.
    """

    budget: float | None
    fraction: float
    margin: float | None
    point: tuple
    nearest: tuple | None
    direction: tuple | None
    reason: str

    @property
    def inside(self) -> bool | None:
        """Whether Eq. 4's skin lies inside the locus (``None`` without a boundary)."""
        return None if self.margin is None else self.margin > 0

    def document(self) -> dict:
        """The JSON form: every attribute and ``inside``."""
        return {"budget": self.budget, "fraction": self.fraction, "margin": self.margin, "inside": self.inside,
                "point": list(self.point), "nearest": None if self.nearest is None else list(self.nearest),
                "direction": None if self.direction is None else list(self.direction), "reason": self.reason}


def detection_budget(locus: SkinLocus, point: ArrayLike, fraction: float = BUDGET_FRACTION) -> DetectionBudget:
    """
    The budget of Eq. 4's error at skin chromaticity ``point`` (NCC (r, g)): ``fraction`` of its distance to the
    boundary of ``locus``. Undefined (``budget`` None, with the reason) when the locus is degenerate or the point
    lies on its boundary.

    Examples
    --------
    >>> from skinrender.evaluation.locus import hull_locus
    >>> square = hull_locus(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]), np.array([5000.0]), None)
    >>> b = detection_budget(square, [0.5, 0.8])
    >>> round(b.budget, 6), b.inside, [round(v, 6) for v in b.direction]
    (0.1, True, [0.0, 1.0])
    """
    if not (isinstance(fraction, (int, float, np.floating)) and 0 < fraction <= 1):
        raise SkinrenderError(f"budget fraction must be in (0, 1], got {fraction!r}")
    p = tuple(float(v) for v in np.asarray(point, dtype=np.float64).reshape(-1)[:2])
    if locus.degenerate is not None:
        return DetectionBudget(None, float(fraction), None, p, None, None,
                               f"no budget: the skin locus is degenerate ({locus.degenerate})")
    margin, nearest = boundary_distance(locus, p)
    if margin == 0:
        return DetectionBudget(None, float(fraction), 0.0, p, tuple(nearest.tolist()), None,
                               "no budget: Eq. 4's skin lies on the locus's boundary (any error may change detection)")
    step = nearest - np.asarray(p)
    direction = tuple((step / np.linalg.norm(step)).tolist())
    side = "inside" if margin > 0 else "outside"
    return DetectionBudget(float(fraction) * abs(margin), float(fraction), float(margin), p,
                           tuple(nearest.tolist()), direction,
                           f"{fraction:g} of the distance ({abs(margin):.3g} in NCC) from Eq. 4's skin ({side} the "
                           "locus) to the locus's boundary")


def rates_shifted(locus: SkinLocus, skin_rg: ArrayLike, prop_rg: ArrayLike, shift: ArrayLike) -> dict:
    """
    The TPR (share of ``skin_rg`` inside ``locus``) and FPR (share of ``prop_rg`` inside), and both again with every
    chromaticity moved by ``shift`` (an NCC (r, g) vector): what an error of Eq. 4 by ``shift`` does to detection
    with a locus built from Eq. 4.

    Returns
    -------
    dict
        ``tpr``, ``fpr``, ``tpr_shifted``, ``fpr_shifted``, ``tpr_change``, ``fpr_change`` (fractions; ``None``
        where there are no points of the kind).

    Examples
    --------
    >>> from skinrender.evaluation.locus import hull_locus
    >>> square = hull_locus(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]), np.array([5000.0]), None)
    >>> out = rates_shifted(square, [[0.5, 0.5], [0.5, 0.95]], [[0.5, 1.05]], [0.0, 0.1])
    >>> out["tpr"], out["tpr_shifted"], out["fpr"], out["fpr_shifted"]
    (1.0, 0.5, 0.0, 0.0)
    """
    shift = np.asarray(shift, dtype=np.float64).reshape(2)
    out = {}
    for key, points in (("tpr", skin_rg), ("fpr", prop_rg)):
        points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        if points.size == 0:
            out.update({key: None, f"{key}_shifted": None, f"{key}_change": None})
            continue
        before = float(np.mean(locus.contains(points)))
        after = float(np.mean(locus.contains(points + shift)))
        out.update({key: before, f"{key}_shifted": after, f"{key}_change": after - before})
    return out
