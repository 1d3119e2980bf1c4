"""
Detection rates of a face, against Eq. 4's
==========================================

What a camera designer uses Eq. 4 for: the skin locus's true- and
false-positive rates. For a face rendered as replicates at a level of physics
(:func:`~skinrender.rendering.face.validation.render_replicates`), each pixel
that sees one material is classified by the camera's analytic skin locus three
ways:

-   as rendered (the replicates' mean, through the level's sensor if it has
    one): ``tpr_rendered``, ``fpr_rendered``;
-   with the renderer's Monte Carlo noise removed
    (:func:`~skinrender.evaluation.noise_separation.separate_noise`, the
    noise measured from the replicates' radiance, before any sensor, so that a
    sensor's noise counts as physics): ``tpr``, ``fpr``;
-   at the chromaticity Eq. 4 gives the pixel's material under the key light,
    white balanced as the render: ``tpr_eq4``, ``fpr_eq4``.

Their differences are tested against a tolerance
(:func:`~skinrender.evaluation.detection_verdict.detection_verdict`), the
standard errors from half-samples of the replicates (the delete-``K/2``
jackknife, which holds for statistics as discontinuous as a classification,
where the delete-one jackknife overstates it threefold here), each half through
a sensor frame of its own (one frame is one draw of the sensor's noise). ``tpr`` is over skin (label 1), ``fpr``
over the props (labels 2…); the background is left out, and so are pixels
next to another material (their colour mixes two; Eq. 4 gives one) and pixels
too dark to score (the brightest channel of the mean below
:data:`~skinrender.evaluation.detection.SCORED_MIN_OUTPUT`).

-   :func:`detection_rates`, :class:`DetectionRates`: the rates and their half-samples;
-   :func:`face_detection`: the rates, the changes and the verdict;
    :func:`detection_check`, the same as a row of ``validate face``.
-   :func:`material_chromaticities`: Eq. 4's NCC (r, g) of each label.
-   :func:`one_material`: the pixels that see one material.

Units: NCC fractions; rates fractions; radiance in the specfilm's units.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...constants import CONSTANT_OUTPUT_SCALE
from ...errors import SkinrenderError
from ...evaluation.detection import SCORED_MIN_OUTPUT
from ...evaluation.detection_verdict import DETECTION_KEYS, DETECTION_TOLERANCE, HALVES_DETECTION, detection_verdict
from ...evaluation.locus import SkinLocus
from ...evaluation.noise_separation import SPREAD_Z, replicate_noise, rg_of, separate_noise
from ...evaluation.verdict import ALPHA_EQUIVALENCE, Verdict
from ...hints import NDArrayFloat
from ...model.response import gain
from ..validation import analytic_reference
from .labels import LABEL_SKIN
from .limits import LimitCheck
from .render import balanced_frame, white_references
from .scene import skin_reflectance_of

__all__ = ["DetectionRates", "detection_rates", "face_detection", "detection_check", "material_chromaticities", "one_material"]


def one_material(labels: NDArrayFloat) -> NDArrayFloat:
    """
    The labelled pixels (label ≥ 1) none of whose eight neighbours has another label ≥ 1: a pixel beside the
    (black) background sees one material and the dark, which leaves its chromaticity alone.

    >>> labels = np.array([[0, 1, 1, 2], [0, 1, 1, 2], [0, 0, 0, 0]])
    >>> one_material(labels).astype(int).tolist()
    [[0, 1, 0, 0], [0, 1, 0, 0], [0, 0, 0, 0]]
    """
    labels = np.asarray(labels)
    padded = np.pad(labels, 1, constant_values=0)
    height, width = labels.shape
    alone = labels >= 1
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            other = padded[1 + dy:1 + dy + height, 1 + dx:1 + dx + width]
            alone &= (other == 0) | (other == labels)
    return alone


def material_chromaticities(first, grid) -> NDArrayFloat:
    """Eq. 4's NCC (r, g) of each label's material, ``(labels, 2)`` (row 0, the background, is 1/3): the skin
    and the props under the key light, white balanced to the calibration (the render's ``first`` replicate)."""
    scene = first.scene
    specs = [first.skin, *(prop.reflectance for prop in scene.props)]
    rho = np.array([skin_reflectance_of(spec, grid, "skin" if k == 0 else f"prop {k}") for k, spec in enumerate(specs)])
    rgb = analytic_reference(first.camera, rho, first.prevailing, first.calibration, grid=grid)
    return np.vstack([np.full((1, 2), 1.0 / 3.0), rg_of(rgb)])


def _rates(inside: NDArrayFloat, skin: NDArrayFloat) -> tuple[float | None, float | None]:
    props = ~skin
    return (float(inside[skin].mean()) if skin.any() else None, float(inside[props].mean()) if props.any() else None)


def _frame(replicated, radiance: NDArrayFloat, seed: int) -> NDArrayFloat:
    """One frame (balanced, output units) of the pixels' ``radiance`` ``(n, 3)`` through the level's sensor (with
    the replicates' options)."""
    image, _, _ = balanced_frame(replicated.first, replicated.level, radiance[:, None, :], replicated.grid, seed,
                                 replicated.options)
    return image[:, 0, :]


@dataclass(frozen=True)
class DetectionRates:
    """
    The rates of one render's replicates, each ``(tpr, fpr)`` (``None`` where no pixel of the kind is scored):
    ``rendered`` (as rendered), ``separated`` (the renderer's noise removed), ``eq4`` (Eq. 4's), ``samples``
    (``separated`` on each half-sample of the replicates, in the order the seed draws them: two renders of
    the same level and seed draw the same halves), ``variance_factor`` (the half-samples' variance times this is
    the squared standard error), ``pixels`` (``{"skin", "prop"}`` scored) and the materials' ``spreads``.
    """

    rendered: tuple
    separated: tuple
    eq4: tuple
    samples: list
    variance_factor: float
    pixels: dict
    spreads: dict = field(default_factory=dict, repr=False)


def detection_rates(replicated, locus: SkinLocus, halves: int = HALVES_DETECTION, seed: int = 0, mean=None,
                    z: float = SPREAD_Z) -> DetectionRates:
    """The rates :func:`face_detection` tests (arguments as there)."""
    first, level = replicated.first, replicated.level
    if mean is None:
        radiance_mean = np.mean([r.radiance for r in replicated.renders], axis=0)
        image = balanced_frame(first, level, radiance_mean, replicated.grid, first.seed, replicated.options)[0]
        image = image.astype(np.float32).astype(np.float64)  # as mean_rendering gives it
    else:
        image = np.asarray(mean.image, dtype=np.float64)
    labels = first.labels
    tested = one_material(labels) & (image.max(axis=-1) >= SCORED_MIN_OUTPUT)
    materials = labels[tested]
    skin = materials == LABEL_SKIN
    balance = gain(*white_references(first.scene, first.camera, first.calibration, replicated.grid),
                   scale=CONSTANT_OUTPUT_SCALE)
    radiance = np.array([r.radiance[tested] for r in replicated.renders], dtype=np.float64)  # (K, n, 3)
    expected = material_chromaticities(first, replicated.grid)[materials]
    post = any(effect.post is not None for effect in level.effects)

    def separated_rates(sample: NDArrayFloat, chromaticity: NDArrayFloat):
        bias, covariance = replicate_noise(sample * balance)
        separated, spreads = separate_noise(chromaticity, covariance, materials, z, bias=bias)
        return _rates(locus.contains(separated), skin), spreads

    rendered_rg = rg_of(image[tested])
    point, spreads = separated_rates(radiance, rendered_rg)
    k = radiance.shape[0]
    if k < 2:
        raise SkinrenderError(f"replicates: the renderer's noise is measured from two or more, got {k}")
    kept = k - k // 2  # each half-sample keeps this many replicates: the delete-(k // 2) jackknife
    rng = np.random.default_rng([int(seed) % 2**32, 0xD37EC7])
    samples = []
    for _ in range(int(halves)):
        sample = radiance[np.sort(rng.permutation(k)[:kept])]
        chromaticity = (rg_of(_frame(replicated, sample.mean(axis=0), int(rng.integers(0, 2**32)))) if post
                        else rg_of(sample.mean(axis=0) * balance))  # through a sensor: a frame of its own
        samples.append(separated_rates(sample, chromaticity)[0])
    return DetectionRates(_rates(locus.contains(rendered_rg), skin), point, _rates(locus.contains(expected), skin),
                          samples, (k - kept) / kept, {"skin": int(skin.sum()), "prop": int((~skin).sum())}, spreads)


def face_detection(replicated, locus: SkinLocus, tolerance: float = DETECTION_TOLERANCE,
                   halves: int = HALVES_DETECTION, seed: int = 0, mean=None, alpha: float = ALPHA_EQUIVALENCE,
                   z: float = SPREAD_Z) -> tuple[dict, Verdict]:
    """
    The detection rates of a face's replicates as rendered, with their Monte Carlo noise removed and as Eq. 4
    predicts them, and whether Eq. 4 is shown right within ``tolerance`` (see the module).

    Parameters
    ----------
    replicated
        The replicate renders of one level (:func:`~skinrender.rendering.face.validation.render_replicates`).
    locus
        The camera's analytic skin locus (its ``contains`` classifies).
    tolerance
        The change in TPR and in FPR Eq. 4 may be off by, fractions in (0, 1).
    halves
        Half-samples of the replicates whose spread gives the standard errors (≥ 2).
    seed
        The seed of the half-samples (which replicates, and their sensor frames).
    mean
        The replicates' mean as one render (:func:`~skinrender.rendering.face.validation.mean_rendering`;
        ``None``: made here).
    alpha, z
        The equivalence test's α (simultaneous over the two rates) and the spread test's
        (:data:`~skinrender.evaluation.noise_separation.SPREAD_Z`).

    Returns
    -------
    (dict, Verdict)
        The ``detection`` document (:func:`~skinrender.evaluation.detection_verdict.detection_verdict`) and
        its verdict.
    """
    rates = detection_rates(replicated, locus, halves, seed, mean, z)
    document, verdict = detection_verdict(rates.rendered, rates.separated, rates.eq4, rates.samples, tolerance,
                                          alpha=alpha, pixels=rates.pixels, variance_factor=rates.variance_factor)
    document["spread"] = {int(group): {"pixels": s.pixels, "physics_kept": list(s.kept), "separated": s.separated}
                          for group, s in rates.spreads.items()}
    return document, verdict


def detection_check(replicated, locus: SkinLocus, tolerance: float = DETECTION_TOLERANCE,
                    **options) -> tuple[dict, LimitCheck]:
    """
    :func:`face_detection` as a row of ``validate face``'s checks (``detection``): ``statistic`` the larger
    upper bound of the changes over the tolerance, ``tolerance`` the tolerance, ``bound`` the larger upper
    bound; and its document. ``options``: :func:`face_detection`'s.
    """
    document, verdict = face_detection(replicated, locus, tolerance, **options)
    pixels = sum(document["pixels"].values())
    bounds = [document[f"{key}_change_bound"] for key in ("tpr", "fpr") if document[f"{key}_change_bound"] is not None]
    said = ", ".join(f"{key.upper()} {document[key]:.3f} against Eq. 4's {document[key + '_eq4']:.3f}"
                     for key in ("tpr", "fpr") if document[key] is not None)
    row = LimitCheck("detection", True, verdict.passed, verdict.statistic, tolerance, pixels,
                     f"the skin locus's rates with the renderer's noise separated: {said or 'none scored'}; "
                     f"{verdict.reason}", {key: document[key] for key in DETECTION_KEYS if key != "verdict"},
                     outcome=verdict.outcome, alpha=verdict.alpha, test=verdict.test,
                     bound=max(bounds) if bounds else None)
    return document, row
