"""
Eq. 4's error on a face, against a detection budget
===================================================

``eq4_shift``, the check of every level of physics: how far the skin's mean
NCC (r, g) moves from Eq. 4's, tested for *equivalence* against the
detection budget of :mod:`skinrender.evaluation.budget` (a stated fraction
of the distance from Eq. 4's skin chromaticity to the boundary of the
camera's skin locus): ``pass`` when the shift is shown within the budget
(its upper confidence bound below it), ``fail`` when shown beyond it (its
lower bound above it), ``inconclusive`` otherwise, ``not_applicable`` where
no budget is defined (a degenerate locus, a skin on its boundary).

-   :func:`face_budget`: the budget of a face's skin, and the locus detection
    uses (a skin set, ``skin`` unless told, under the paper's ten Planckians,
    white balanced to the calibration); the budget is measured against that
    locus without the tested skin (a leave-one-out hull), so it is defined
    for every skin.
-   :func:`eq4_shift`: the check.
-   :func:`scored_skin`, :func:`budget_rates`: the pixels it measures, and
    what a shift of the budget does to their detection.

The shift
---------
The pixels are the interior skin pixels the detection scores (the
replicates' mean has its brightest channel at
:data:`~skinrender.evaluation.detection.SCORED_MIN_OUTPUT` or more), every
pixel weighing the same, as in the detection rates. Their mean NCC is a mean
of ratios, biased by ``O(1/K)`` of each pixel's relative variance: the
jackknife's bias correction removes that term, and its standard error (over
the ``K`` replicates, Student's t with ``K − 1`` degrees of freedom) is that
of the shift's Euclidean length (the delta method: valid once the shift is
resolved; an unresolved shift's length is biased upwards, which only delays
a pass). α is :data:`~skinrender.evaluation.verdict.ALPHA_EQUIVALENCE`: the
shift's bounds hold at 95 % confidence. Through an image sensor the rounding
to codes is left out of the bound: the tested pixels are dithered, their
mean error below 0.003 DN (:data:`~skinrender.rendering.face.effects.noise.DITHER_SIGMA_DN`).

Units: NCC fractions; images in Eq. 4 output units.

References
----------
-   :cite:`Efron1982` : see :mod:`skinrender.rendering.face.limits` (the
    jackknife's bias correction and standard error).
-   :cite:`Schuirmann1987` : see :mod:`skinrender.evaluation.verdict` (two
    one-sided tests).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...evaluation.budget import BUDGET_FRACTION, DetectionBudget, detection_budget, rates_shifted
from ...evaluation.detection import SCORED_MIN_OUTPUT
from ...evaluation.locus import SkinLocus, skin_locus
from ...evaluation.verdict import ALPHA_EQUIVALENCE, equivalence
from ...hints import NDArrayFloat
from ...model.camera import Camera
from ...spectra import GRID_DEFAULT, WavelengthGrid
from .labels import LABEL_SKIN, interior
from .limits import PIXELS_MIN, LimitCheck, deviation_ratio, critical_t, jackknife, rg

__all__ = ["SKIN_SET_DEFAULT", "skin_set_name", "face_budget", "scored_skin", "eq4_shift", "budget_rates"]


SKIN_SET_DEFAULT = "skin"
"""The reflectance set a face's skin locus is built from unless told: the 30 Vrhel skins."""


def skin_set_name(skin_set) -> str:
    """
    How a row names the set its locus was built from: the set's name, or ``N spectra`` for an array.

    >>> skin_set_name("skin-tones"), skin_set_name(np.ones((3, 301)))
    ('skin-tones', '3 spectra')
    """
    if isinstance(skin_set, str):
        return skin_set
    name = getattr(skin_set, "name", None)
    return str(name) if name is not None else f"{np.asarray(skin_set).reshape(-1, np.shape(skin_set)[-1]).shape[0]} spectra"


def face_budget(cam: Camera, expected: NDArrayFloat, calibration: float, fraction: float = BUDGET_FRACTION,
                grid: WavelengthGrid = GRID_DEFAULT, skin_set=SKIN_SET_DEFAULT,
                skin: NDArrayFloat | None = None) -> tuple[DetectionBudget, SkinLocus]:
    """
    The detection budget of Eq. 4's skin NCC ``expected`` (``[r, g, …]``) for camera ``cam`` white balanced to
    ``calibration`` (K), and the skin locus detection uses (``skin_set`` under the paper's ten Planckians).

    The budget is measured against the locus of the set *without the tested skin* (``skin``, its reflectance
    on ``grid``; the spectra of the set equal to it left out): a skin of the set would otherwise sit on or
    just inside the hull it helps to span, its budget 0 (undefined, at a hull vertex) or small by
    construction. Left out, it has a margin like any other skin's, so the budget is defined for every skin.
    """
    locus = skin_locus(cam, skin_set, calibration=calibration, grid=grid)
    trimmed = locus
    if skin is not None:
        from ...datasets import SpectralSet, reflectances

        spectra = (reflectances(skin_set).on(grid) if isinstance(skin_set, (str, SpectralSet))
                   else np.asarray(skin_set, dtype=np.float64).reshape(-1, grid.size))
        same = np.all(np.isclose(spectra, np.asarray(skin, dtype=np.float64)[None], rtol=1e-6, atol=1e-9), axis=1)
        if same.any() and not same.all():
            trimmed = skin_locus(cam, spectra[~same], calibration=calibration, grid=grid)
    budget = detection_budget(trimmed, np.asarray(expected, dtype=np.float64)[:2], fraction)
    if trimmed is not locus and budget.budget is not None:
        budget = replace(budget, reason=budget.reason + " (the locus without the tested skin, which is in the set)")
    return budget, locus


def scored_skin(mean: NDArrayFloat, labels: NDArrayFloat, usable: NDArrayFloat | None = None) -> NDArrayFloat:
    """The interior skin pixels (``usable`` ones) whose mean image ``(h, w, 3)`` has its brightest channel at
    :data:`~skinrender.evaluation.detection.SCORED_MIN_OUTPUT` or more: those detection scores."""
    skin = interior(labels, LABEL_SKIN) & (np.asarray(mean).max(axis=-1) >= SCORED_MIN_OUTPUT)
    return skin if usable is None else skin & usable


def _not_run(pixels: int, why: str, budget: DetectionBudget | None) -> LimitCheck:
    return LimitCheck("eq4_shift", True, None, None, None if budget is None else budget.budget, pixels,
                      f"{why}; only {pixels} scored skin pixels (interior, brightest channel ≥ {SCORED_MIN_OUTPUT:g}, "
                      "usable through a sensor): no shift measured", {"within_budget": None}, outcome="inconclusive", alpha=ALPHA_EQUIVALENCE,
                      test="equivalence against the detection budget (not run)")


def eq4_shift(images: NDArrayFloat, labels: NDArrayFloat, expected: NDArrayFloat, why: str,
              budget: DetectionBudget | None, usable: NDArrayFloat | None = None,
              alpha: float = ALPHA_EQUIVALENCE) -> LimitCheck:
    """
    How far skin moves from Eq. 4, against the detection ``budget`` (an equivalence test; see the module).

    Parameters
    ----------
    images
        ``(K, height, width, 3)`` balanced replicate images, output units.
    labels
        ``(height, width)`` label image.
    expected
        Eq. 4's NCC of the skin, ``[r, g, b]``.
    why
        What Eq. 4 meets at this level (the level's reason, :attr:`~skinrender.rendering.face.effects.Level.why`).
    budget
        :func:`face_budget`'s; ``None`` or an undefined budget: ``not_applicable``.
    usable
        Pixels a sensor left linear; ``None``: all.

    Returns
    -------
    :class:`~skinrender.rendering.face.limits.LimitCheck`
        ``statistic`` the shift (Euclidean, NCC), ``tolerance`` the budget, ``bound`` the shift's upper
        confidence bound; details ``shift`` (r, g), ``shift_se``, ``shift_length_se`` (the shift's standard
        error), ``ncc_mean``, ``ncc_expected``,
        ``within_budget`` (true, false or null), ``budget`` (:meth:`DetectionBudget.document`), and
        ``share_outside``: the share of the pixels whose own NCC differs from Eq. 4's beyond their noise
        (Šidák over the pixels at :data:`~skinrender.rendering.face.limits.ALPHA`).
    """
    images = np.asarray(images, dtype=np.float64)
    expected = np.asarray(expected, dtype=np.float64)[:2]
    k = images.shape[0]
    pixels_of = scored_skin(images.mean(axis=0), labels, usable)
    pixels = int(pixels_of.sum())
    if pixels < PIXELS_MIN:
        return _not_run(pixels, why, budget)
    samples = images[:, pixels_of]
    total = samples.sum(axis=0)
    full = rg(total / k).mean(axis=0)
    leave_out = np.array([rg((total - s) / (k - 1)).mean(axis=0) for s in samples])
    value = k * full - (k - 1) * leave_out.mean(axis=0)  # the jackknife's bias correction
    shift = value - expected
    spread = lambda v: np.sqrt((k - 1) / k * np.sum((v - v.mean(axis=0)) ** 2, axis=0))  # noqa: E731
    shift_se = spread(leave_out)
    length, length_se = float(np.hypot(*shift)), float(spread(np.linalg.norm(leave_out - expected, axis=-1)))
    per_pixel, per_pixel_se = jackknife(samples, rg)
    outside = np.any(deviation_ratio(np.abs(per_pixel - expected), per_pixel_se) > critical_t(per_pixel.size, k), axis=-1)
    tolerance = None if budget is None else budget.budget
    details = {"shift": shift.tolist(), "shift_se": shift_se.tolist(), "ncc_mean": value.tolist(),
               "ncc_expected": expected.tolist(), "share_outside": float(outside.mean()),
               "shift_length_se": length_se, "budget": None if budget is None else budget.document()}
    if tolerance is None:
        verdict, _ = equivalence([length], [length_se], 1.0, alpha, dof=k - 1, name="eq4_shift", scale=1.0)
        because = "no detection budget" if budget is None else budget.reason
        return LimitCheck("eq4_shift", True, None, length, None, pixels,
                          f"{why}; not tested: {because} (shift {length:.3g}, at most {verdict.bound:.3g} at "
                          f"{100 * (1 - alpha):g} %)", {**details, "within_budget": None},
                          outcome="not_applicable", alpha=alpha, test=verdict.test, bound=verdict.bound)
    verdict, _ = equivalence([length], [length_se], tolerance, alpha, dof=k - 1, name="eq4_shift", scale=1.0)
    within = {"pass": True, "fail": False}.get(verdict.outcome)
    said = {"pass": "within", "fail": "beyond"}.get(verdict.outcome, "neither shown within nor beyond")
    return LimitCheck("eq4_shift", True, within, length, tolerance, pixels,
                      f"{why}; the skin's mean NCC is {length:.3g} from Eq. 4's (at most {verdict.bound:.3g}), "
                      f"{said} the detection budget {tolerance:.3g}", {**details, "within_budget": within},
                      outcome=verdict.outcome, alpha=alpha, test=verdict.test, bound=verdict.bound)


def budget_rates(mean: NDArrayFloat, labels: NDArrayFloat, locus: SkinLocus,
                 budget: DetectionBudget | None) -> dict | None:
    """
    What an error of Eq. 4 by the budget does to detection: :func:`~skinrender.evaluation.budget.rates_shifted`
    of the scored skin pixels (label :data:`~skinrender.rendering.face.labels.LABEL_SKIN`) and prop pixels
    (labels above it) of the mean image ``(h, w, 3)``, every chromaticity moved by the budget towards the
    locus's nearest boundary point; ``None`` without a budget.
    """
    if budget is None or budget.budget is None:
        return None
    mean = np.asarray(mean, dtype=np.float64)
    scored = mean.max(axis=-1) >= SCORED_MIN_OUTPUT
    chromaticity = rg(mean)
    return rates_shifted(locus, chromaticity[scored & (labels == LABEL_SKIN)],
                         chromaticity[scored & (labels > LABEL_SKIN)],
                         budget.budget * np.asarray(budget.direction))
