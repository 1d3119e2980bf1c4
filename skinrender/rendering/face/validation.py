"""
Validating face renders
=======================

A face rendered at a level of physics, checked against the analytic limits
that hold at that level (:mod:`skinrender.rendering.face.limits`), and told
how far its skin moves from Eq. 4 where none holds.

-   :func:`validate_face`, :class:`FaceValidation`: the checks of one face scene.
-   :func:`validate_face_request`: the same of a
    :class:`~skinrender.rendering.face.request.FaceRequest`.
-   :func:`render_replicates_request` (of a request), :func:`render_replicates`,
    :class:`Replicated`: the replicate renders a validation (and the ladder) measures; :func:`mean_rendering`, their mean
    as one render; :func:`shift_against`, their ``eq4_shift`` against the
    detection budget.
-   :data:`LIMITS_SCENE_FREE`: the limits that hold whatever the level.

What holds where
----------------
Each effect states its limits (:class:`~skinrender.rendering.face.effects.base.Limits`):
the check it makes the level's test, or that it breaks every limit, and why;
a level composes them (:attr:`~skinrender.rendering.face.effects.levels.Level.check`,
``.why``, ``.measure``). With today's effects:

======================  ====================================================
level (effects)         checks
======================  ====================================================
``direct``              ``shading_cancels``
``sheen``               ``dichromatic_plane``
``noise`` (+ above)     the same, on the frames' mean, dark signal removed,
                        clipped pixels left out, quantisation bounded
``interreflection``,    none of the exact limits
``mixed``
every level             ``eq4_shift`` (Eq. 4's error against the detection
                        budget, :mod:`~skinrender.rendering.face.shift`),
                        ``white_furnace`` (the scene's mesh, its camera),
                        ``closed_sphere`` (the skin's reflectance)
======================  ====================================================

Each check is a verdict (:class:`~skinrender.evaluation.verdict.Verdict`:
``pass``, ``fail``, ``inconclusive``, ``not_applicable``); the validation's
is their combination (:func:`~skinrender.evaluation.verdict.combine`), and
the command line's exit status :data:`~skinrender.evaluation.verdict.EXIT_STATUS`'s.

The requested ``spp`` is split over :data:`~skinrender.rendering.face.limits.REPLICATES`
renders with seeds ``seed, seed + 1, …`` (mod 2³²), each at ``⌈spp / K⌉`` but at
least :data:`~skinrender.rendering.face.limits.SPP_REPLICATE_MIN`; their
spread is each statistic's noise. Two validations are independent when their
seeds are ``K`` or more apart. Through an image sensor (``noise``) each
replicate is a frame of its own (the sensor's stream is seeded from the
render's seed), so the spread holds the sensor's noise too; the sensor is
linear in the mean except for its dark signal (subtracted: dark current ×
exposure), the clipping at 0 and at saturation (pixels with a clipped
replicate are left out) and the rounding to codes (pixels whose modelled
noise is below :data:`~skinrender.rendering.face.effects.noise.DITHER_SIGMA_DN` are left out; elsewhere the mean
error is bounded by :func:`~skinrender.rendering.face.limits.rounding_bias`
at each pixel's modelled σ and may be used up by a deviation, and the
standard error is taken no smaller than the EMVA 1288 model's,
``√((σ² + 1/12 DN²) / K)``, since twelve frames may read one code). A dim scene
through a coarse sensor may so leave too few pixels to test: the check then
reports ``passed`` None with the count.

Units: temperatures K, times s, images in Eq. 4 output units.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace

import numpy as np

from ...errors import SkinrenderError
from ...evaluation.detection_verdict import check_tolerance
from ...evaluation.verdict import EXIT_STATUS, Verdict, combine, samples_needed
from ...methods import method_of
from ...model.chromaticity import ncc
from ...spectra import GRID_DEFAULT
from ..validation import analytic_reference
from ..settings import seed_at
from .detection import detection_check
from .effects import Level, Measured, Replicates
from .limit_scenes import FURNACE_SIZE, FURNACE_SPP, LIMITS_SCENE_FREE, SPHERE_SIZE, SPHERE_SPP  # noqa: F401
from .limits import REPLICATES, SPP_REPLICATE_MIN, LimitCheck
from .render import FaceRendering, balanced_frame, render_face_request
from .request import FaceRequest, face_request
from .scene import skin_reflectance_of
from .shift import budget_rates, eq4_shift, face_budget, skin_set_name

__all__ = ["LIMITS_SCENE_FREE", "FURNACE_SIZE", "FURNACE_SPP", "SPHERE_SIZE", "SPHERE_SPP", "RENDER_OPTIONS",
           "FaceValidation", "Replicated", "replicated_of", "render_replicates", "render_replicates_request", "mean_rendering",
           "shift_against", "validate_face", "validate_face_request"]

RENDER_OPTIONS = ("skin", "size", "sampler", "variant", "grid", "channels", "imager", "exposure", "illuminance",
                  "translate_mm")
""":func:`validate_face`'s keywords that go to each replicate's :func:`~skinrender.rendering.face.render_face`."""


@dataclass(frozen=True)
class Replicated:
    """
    Replicate renders of a face at one level, as the checks see them.

    Attributes
    ----------
    renders
        The :class:`~skinrender.rendering.face.render.FaceRendering` of each seed.
    level
        The :class:`~skinrender.rendering.face.effects.Level`.
    measured
        The replicate images after the level's ``measure`` (a sensor's dark signal removed, its usable pixels,
        bias bound and standard-error floor): :class:`~skinrender.rendering.face.effects.Measured`.
    expected
        Eq. 4's NCC of the skin, ``[r, g, b]``.
    seconds
        Wall time of the renders, s.
    grid
        The wavelength grid, nm.
    options
        The effects' options they were rendered with, by effect name (the request's).
    """

    renders: list
    level: Level
    measured: Measured
    expected: np.ndarray
    seconds: float
    grid: object = GRID_DEFAULT
    options: Mapping = field(default_factory=dict)

    @property
    def first(self) -> FaceRendering:
        """The first replicate (scene, camera, labels, lights)."""
        return self.renders[0]

    def replicates(self) -> Replicates:
        """What a level's check reads (:class:`~skinrender.rendering.face.effects.Replicates`)."""
        m, first = self.measured, self.first
        return Replicates(m.images, first.labels, self.expected, first, self.level.lights(first.scene), m.usable,
                          m.bias, m.floor)


def render_replicates_request(request: FaceRequest, seeds) -> Replicated:
    """
    The face of ``request`` rendered once per seed of ``seeds`` (derived from the request's, any 32-bit
    integers), measured as its level's checks see it.
    """
    start = time.perf_counter()
    renders = [render_face_request(request, seed) for seed in seeds]
    return replicated_of(renders, request, time.perf_counter() - start)


def replicated_of(renders: list, request, seconds: float = 0.0) -> Replicated:
    """Replicate renders of one camera (e.g. seen through a spectral render per seed) of ``request`` (its level,
    grid and options), measured as the level's checks see them; ``seconds``: the time they took."""
    first, grid, level = renders[0], request.grid, request.level
    images = np.array([r.image for r in renders], dtype=np.float64)
    rho = skin_reflectance_of(first.skin, grid, "skin")
    expected = ncc(analytic_reference(first.camera, rho[None], first.prevailing, first.calibration, grid=grid))[0]
    measured = level.measure(images, first, request.options)  # through a sensor: dark signal, clipping, codes
    return Replicated(renders, level, measured, expected, seconds, grid, request.options)


def render_replicates(camera_, scene, prevailing, calibration, skin, level: Level, spp: int, seeds, size=None,
                      grid=GRID_DEFAULT, **options) -> Replicated:
    """
    The face rendered once per seed of ``seeds`` at ``spp`` each (arguments as
    :func:`~skinrender.rendering.face.render_face`; ``options``: its ``sampler``, ``variant``, ``channels``,
    ``imager``, ``exposure``, ``illuminance``), measured as the level's checks see it
    (:func:`render_replicates_request` of their :func:`~skinrender.rendering.face.request.face_request`).
    """
    request = face_request(scene, camera_, prevailing, calibration, skin=skin, physics=level, size=size, spp=spp,
                           grid=grid, **options)
    return render_replicates_request(request, seeds)


def mean_rendering(replicated: Replicated, imager=None, exposure=None) -> FaceRendering:
    """
    The replicates as one render of all their samples: the mean radiance, through the level's ``post`` (one
    frame through a sensor, the first seed's, with the replicates' own options; ``imager`` and ``exposure`` are
    deprecated: they replace the sensor's where given) and Eq. 4's gain; what one render at the replicates'
    total spp would give.
    """
    renders, first = replicated.renders, replicated.first
    options = dict(replicated.options)
    if imager is not None or exposure is not None:  # deprecated: the sensor's options of the replicates replaced
        from ..sensor import NoiseOptions

        for name, noise in options.items():
            if isinstance(noise, NoiseOptions):
                options[name] = NoiseOptions(imager if imager is not None else noise.imager, noise.illuminance,
                                             exposure if exposure is not None else noise.exposure)
    radiance = np.mean([r.radiance for r in renders], axis=0)
    image, frame, applied = balanced_frame(first, replicated.level, radiance, replicated.grid, first.seed, options)
    return replace(first, image=image.astype(np.float32), radiance=radiance, gain=applied,
                   spp=int(sum(r.spp for r in renders)), spp_requested=int(sum(r.spp_requested for r in renders)),
                   seconds=replicated.seconds, info=frame.info)


def shift_against(replicated: Replicated, budget, locus, mean=None) -> LimitCheck:
    """
    ``eq4_shift`` of the replicates against the detection ``budget``
    (:func:`~skinrender.rendering.face.shift.eq4_shift`), with ``budget_rates`` (what a shift of the budget does
    to the pixels of ``mean``, an image ``(h, w, 3)``; ``None``: the replicates' mean) in its details and, where
    a sensor left too few pixels to decide, which it left out in its reason.
    """
    measured, first = replicated.measured, replicated.first
    shift = eq4_shift(measured.images, first.labels, replicated.expected, replicated.level.why, budget,
                      measured.usable)
    mean = measured.images.mean(axis=0) if mean is None else mean
    reason = f"{shift.reason}; {measured.note}" if shift.outcome == "inconclusive" and measured.note else shift.reason
    return replace(shift, reason=reason, details={**shift.details, "budget_rates": budget_rates(mean, first.labels,
                                                                                                locus, budget)})


@dataclass(frozen=True)
class FaceValidation:
    """
    A face render checked against its level's analytic limits and Eq. 4's detection budget.

    Attributes
    ----------
    rendering
        The first replicate (scene, camera, physics, labels, lights).
    checks
        :class:`~skinrender.rendering.face.limits.LimitCheck` rows (each a verdict).
    spp, spp_requested
        Samples per pixel of all replicates together, and as asked.
    replicates, seed
        How many renders, the first's seed.
    seconds
        Wall time of everything, s.
    info
        Further JSON-ready keys (the lights, the sensor's settings, ``budget``, ``spp_per_replicate``).
    """

    rendering: FaceRendering
    checks: list
    spp: int
    spp_requested: int
    replicates: int
    seed: int
    seconds: float
    info: dict = field(default_factory=dict)

    @property
    def verdict(self) -> Verdict:
        """The verdicts of the checks that apply combined (a diagnostic row, ``eq4_shift``, decides nothing):
        ``fail`` if one failed, else ``inconclusive`` if one was, else ``pass`` if one passed, else
        ``not_applicable``."""
        return combine([c.verdict for c in self.checks if c.applies], "validate face")

    @property
    def passed(self) -> bool | None:
        """True when the verdict is ``pass``, False for ``fail``, else None (inconclusive or nothing tested)."""
        return self.verdict.passed

    def _shift(self) -> LimitCheck | None:
        return next((c for c in self.checks if c.name == "eq4_shift"), None)

    @property
    def bound(self) -> float | None:
        """``eq4_shift``'s upper confidence bound on Eq. 4's error (NCC): the smallest detection budget that would
        pass; ``None`` where no shift was measured."""
        shift = self._shift()
        return None if shift is None else shift.bound

    @property
    def spp_needed(self) -> int | None:
        """
        Samples per pixel in all (over the replicates) at which ``eq4_shift`` is expected to pass: its standard
        error shrinking as 1/√spp, the measured shift taken as it is
        (:func:`~skinrender.evaluation.verdict.samples_needed`), at least
        :data:`~skinrender.rendering.face.limits.SPP_REPLICATE_MIN` per replicate. ``None`` when no count can pass (the shift is at
        or beyond its budget) or nothing was measured or budgeted.
        """
        shift = self._shift()
        if shift is None or shift.statistic is None or shift.tolerance is None:
            return None
        se = shift.details.get("shift_length_se")
        if se is None:
            return None
        needed = samples_needed(self.spp, [shift.statistic], [se], shift.tolerance, shift.alpha,
                                dof=self.replicates - 1)
        return None if needed is None else max(needed, SPP_REPLICATE_MIN * self.replicates)

    def document(self) -> dict:
        """The JSON document of ``skinrender validate face``."""
        r, verdict = self.rendering, self.verdict
        return {"scene": r.scene.name, "camera": r.camera.name, "physics": r.physics, "skin": r.skin,
                "prevailing_K": r.prevailing, "calibration_K": r.calibration, "spp": self.spp,
                "spp_requested": self.spp_requested, "replicates": self.replicates, "seed": self.seed,
                "sampler": r.sampler, "variant": r.variant, "elapsed_s": self.seconds,
                "size": [r.scene.camera.width, r.scene.camera.height], "labels": r.label_names, **self.info,
                "checks": [c.document() for c in self.checks], "bound": self.bound, "spp_needed": self.spp_needed,
                "passed": self.passed, "verdict": verdict.outcome,
                "exit_status": EXIT_STATUS[verdict.outcome]}


def validate_face(
    camera_,
    scene="face",
    prevailing=None,
    calibration=None,
    *,
    physics: str | Level = "direct",
    spp: int = 256,
    seed: int = 0,
    replicates: int = REPLICATES,
    limits=tuple(LIMITS_SCENE_FREE),
    progress: Callable[[str], None] | None = None,
    budget_fraction: float | None = None,
    skin_set="skin",
    detection_tolerance: float | None = None,
    **render_options,
) -> FaceValidation:
    """
    Render a face scene ``replicates`` times and check the analytic limits of its level and Eq. 4's error.

    Parameters
    ----------
    camera_, scene, prevailing, calibration, physics
        As :func:`skinrender.rendering.face.render_face` (temperatures K); the rest by keyword.
    spp
        Samples per pixel in all, split over the replicates (each ``⌈spp / replicates⌉``, at least
        :data:`~skinrender.rendering.face.limits.SPP_REPLICATE_MIN`).
    seed
        The first replicate's seed; the others follow.
    size
        Image side, pixels; ``None``: the scene's.
    replicates
        Renders, ≥ 3 (Student's t has ``replicates − 1`` degrees of freedom).
    limits
        Which of :data:`LIMITS_SCENE_FREE` to run beside the level's own.
    progress
        Called with a line of text before each stage.
    budget_fraction
        The share of the margin to the locus's boundary Eq. 4's error may use (``eq4_shift``, a diagnostic).
    skin_set, detection_tolerance
        The locus's skin set (``skin``) and the ``detection`` check's tolerance in TPR and FPR (0.02).
    **render_options
        The render's own, to each replicate's :func:`skinrender.rendering.face.render_face`: ``skin``,
        ``size`` (image side, pixels; ``None``: the scene's), ``sampler``, ``variant``, ``channels``, ``grid``
        (nm), ``imager``, ``exposure`` (s or ``auto``), ``illuminance`` (lx), ``translate_mm`` (x, y, z mm).

    Returns
    -------
    :class:`FaceValidation`

    Raises
    ------
    SkinrenderError
        A bad argument, named; a render option ``render_face`` does not take.
    """

    if isinstance(replicates, bool) or not isinstance(replicates, (int, np.integer)) or replicates < 3:
        raise SkinrenderError(f"replicates must be an integer ≥ 3, got {replicates!r}", role="replicates")
    if isinstance(limits, str):  # "furnace,sphere" as the command line gives it, not its letters one by one
        limits = [name.strip() for name in limits.split(",") if name.strip()] if limits.strip() != "none" else []
    unknown = [name for name in limits if name not in LIMITS_SCENE_FREE]
    if unknown:
        raise SkinrenderError(f"limits: unknown {', '.join(map(repr, unknown))}; known: "
                              + ", ".join(LIMITS_SCENE_FREE), role="limits")
    if isinstance(spp, bool) or not isinstance(spp, (int, np.integer)) or spp < 1:
        raise SkinrenderError(f"spp must be a positive integer, got {spp!r}", role="spp")
    unknown = sorted(set(render_options) - set(RENDER_OPTIONS))
    if unknown:
        raise SkinrenderError(f"{', '.join(unknown)}: not an option of a face's render; its options: "
                              + ", ".join(RENDER_OPTIONS))
    each = max(SPP_REPLICATE_MIN, math.ceil(int(spp) / replicates))
    request = face_request(scene, camera_, prevailing, calibration, physics=physics, spp=each, seed=seed,
                           **render_options)
    return validate_face_request(request, spp, replicates, limits, progress, budget_fraction, skin_set,
                                 detection_tolerance)


def validate_face_request(request: FaceRequest, spp: int | None = None, replicates: int = REPLICATES,
                          limits=tuple(LIMITS_SCENE_FREE), progress: Callable[[str], None] | None = None,
                          budget_fraction: float | None = None, skin_set="skin",
                          detection_tolerance: float | None = None) -> FaceValidation:
    """
    :func:`validate_face` of a :class:`~skinrender.rendering.face.request.FaceRequest`: ``replicates`` renders at
    its spp (each replicate's) with seeds ``seed, seed + 1, …`` (mod 2³²); ``spp``: the total asked (default the
    replicates'); the rest as :func:`validate_face`.
    """
    from ...evaluation.budget import BUDGET_FRACTION

    start = time.perf_counter()
    say = progress or (lambda line: None)
    level, each = request.level, request.settings.spp
    spp = each * replicates if spp is None else int(spp)
    seeds = [seed_at(request.settings.seed, k) for k in range(replicates)]
    variant = request.settings.variant
    # the checks' arguments before any render, as the CLI's flags are
    tolerance = check_tolerance(detection_tolerance, "detection_tolerance")  # None: the default
    if isinstance(skin_set, str):
        from ...datasets import reflectances

        try:
            reflectances(skin_set)
        except SkinrenderError as error:
            raise error.reworded(f"skin_set: {error.message}", role="skin_set") from None
    for name in limits:  # each checked (:data:`LIMITS_SCENE_FREE`), in the table's order
        method_of(name, LIMITS_SCENE_FREE, "limits")
    say(f"rendering the face ({level.name}) {replicates} times at {each} spp …")
    replicated = render_replicates_request(request, seeds)
    first, measured = replicated.first, replicated.measured
    checks: list[LimitCheck] = []
    check = level.check  # the level's analytic limit (the last effect's that has one), or none
    if check is not None:
        checks.append(check(replicated.replicates()))
    if measured.excluded:  # say which pixels the measurement left out, and why a check may have none
        row = checks[0] if checks else None
        if row is not None and row.outcome == "inconclusive":
            checks[0] = replace(row, reason=f"{row.reason}; {measured.note}")
        checks = [replace(c, details={**c.details, **measured.excluded}) for c in checks]
    fraction = BUDGET_FRACTION if budget_fraction is None else budget_fraction
    budget, locus = face_budget(first.camera, replicated.expected, first.calibration, fraction, replicated.grid,
                                skin_set, skin_reflectance_of(first.skin, replicated.grid, "skin"))
    detection, check_row = detection_check(replicated, locus, tolerance, seed=request.settings.seed)
    checks += [check_row, replace(shift_against(replicated, budget, locus), applies=False)]  # eq4_shift: a diagnostic
    checks += [limit(first, seeds, variant, say) for name, limit in LIMITS_SCENE_FREE.items() if name in limits]
    info = {key: value for key, value in first.info.items() if key != "lights"}
    info["lights"] = first.info.get("lights", {})
    info["spp_per_replicate"] = int(first.spp)
    if each > math.ceil(int(spp) / replicates):
        info["spp_note"] = (f"each replicate rendered at {each} spp, the least a replicate takes "
                            f"(SPP_REPLICATE_MIN); {spp} spp over {replicates} would give fewer")
    info.update(budget=budget.document(), detection=detection, skin_set=skin_set_name(skin_set))
    renders = replicated.renders
    return FaceValidation(first, checks, int(sum(r.spp for r in renders)), int(spp), int(replicates),
                          int(request.settings.seed), time.perf_counter() - start, info)
