"""
Calibration of the face's verdicts
==================================

How often each check of ``validate face`` fails where its null holds,
measured over independent seeds: per check the observed failures, the
trials, the Clopper–Pearson 95 % interval of the rate
(:func:`~skinrender.evaluation.verdict.binomial_interval`) and the nominal
α. A difference test (``shading_cancels``, ``dichromatic_plane``,
``white_furnace``, ``closed_sphere``) should fail at its α: the interval
should hold it. ``eq4_shift`` and ``detection``, equivalence tests, should
fail at most at their α where Eq. 4 holds (levels whose check is the base's:
``direct``; for ``eq4_shift`` also ``noise``, whose sensor leaves the mean
where Eq. 4 puts it but changes the detection rates); where an effect moves
skin from Eq. 4 (``sheen``, ``interreflection``, ``mixed``) their failures are
findings, not false alarms, and their rows say so. The detection verdict alone,
at any spp (no floor per replicate), is
:mod:`~skinrender.studies.benchmarks.detection_calibration`'s.

-   :func:`face_calibration`: the study.
-   :func:`face_run`: one validation, as the chart's calibration runs one
    (``run(scene, camera, prevailing, calibration, spp, seed, imaging,
    mc_variance, tolerance, level)`` → ``{checks, bound, seconds, spp}``), for
    ``skinrender bench calibration --scene face`` to register.
-   :data:`SEED_STEP`: the seeds of two independent validations are this far
    apart (each renders ``seed … seed + K − 1``).
-   :func:`estimate_face_seconds`: the time a run of validations takes.

``skinrender bench calibration --scene face [--level L]`` runs
:func:`face_calibration` (:mod:`skinrender.cli.calibration`).

Units: seconds s, spp samples per pixel, rates fractions, temperatures K.

References
----------
-   :cite:`Clopper1934` : see :mod:`skinrender.evaluation.verdict`.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from ...errors import SkinrenderError
from ...evaluation.verdict import binomial_interval
from ...rendering.face.effects import PHYSICS_BASE, PHYSICS_EFFECTS, physics_level
from ...rendering.face.limits import REPLICATES
from ...rendering.face.validation import LIMITS_SCENE_FREE, validate_face
from ...rendering.settings import seed_at
from .bench import machine

__all__ = ["SEED_STEP", "SECONDS_LIMITS", "face_run", "face_calibration", "estimate_face_seconds"]

SEED_STEP = REPLICATES
"""Seeds between two independent validations: each renders its seed and the next ``K − 1``."""

SECONDS_LIMITS = 3.0
"""The white furnace and the closed sphere of one validation, s (measured 1.5–5 on 2 cores)."""


def estimate_face_seconds(seeds: int, pixels: int, spp: int, level: str | None = None) -> float:
    """
    Wall time of ``seeds`` validations of a face of ``pixels`` pixels at ``spp`` (split over the replicates, each at
    least :data:`~skinrender.rendering.face.limits.SPP_REPLICATE_MIN`), s: the replicates
    (:func:`skinrender.studies.face.sweep.estimate_seconds` on one core, at ``level``'s rate: ``subsurface-volume`` is far
    slower; ``None``: the base's) and the scene-free limits.

    >>> round(estimate_face_seconds(10, 256 * 256, 256))  # measured: 68–140 s (6.8–14 s a validation, 2 cores)
    240
    """
    from ...rendering.face.limits import SPP_REPLICATE_MIN
    from ..face.sweep import estimate_seconds

    each = max(SPP_REPLICATE_MIN, -(-int(spp) // REPLICATES))
    levels = None if level is None else [level] * REPLICATES
    return seeds * (estimate_seconds(REPLICATES, pixels, each, 1, levels) + SECONDS_LIMITS)


def _eq4_exact(level) -> bool:
    """Whether Eq. 4 holds exactly at ``level``: its check is the base's (nothing in it moves skin from Eq. 4)."""
    check = physics_level(level).check  # a Level passes as it is
    return check is not None and check is PHYSICS_EFFECTS[PHYSICS_BASE].limits.check


def face_run(scene, camera_, prevailing, calibration, spp, seed, imaging=None, mc_variance=None, tolerance=None,
             level=None, size=None, limits=tuple(LIMITS_SCENE_FREE), variant=None) -> dict:
    """
    One ``validate face`` (seeds ``seed … seed + K − 1``): ``{checks: {name: Verdict}, bound, seconds, spp}``
    (``bound``: ``eq4_shift``'s upper confidence bound of the shift, NCC). ``imaging``: ``{imager_, exposure,
    illuminance_lux}`` or ``None``; ``mc_variance`` and ``tolerance`` (the chart's) are refused for a face.
    """
    if tolerance is not None:
        raise SkinrenderError("--tolerance is the chart's; the face's eq4_shift is held to its detection budget")
    imaging = imaging or {}
    result = validate_face(camera_, scene, prevailing, calibration, physics=level or PHYSICS_BASE, spp=spp,
                           seed=seed, size=size, variant=variant, imager=imaging.get("imager_"),
                           exposure=imaging.get("exposure"), illuminance=imaging.get("illuminance_lux"),
                           limits=limits)
    shift = next(c for c in result.checks if c.name == "eq4_shift")
    return {"checks": {c.name: c.verdict for c in result.checks}, "bound": shift.bound, "seconds": result.seconds,
            "spp": result.spp}


def face_calibration(level: str = PHYSICS_BASE, seeds: int = 10, camera_="gbell:9@450,540,610", scene="face",
                     prevailing=2856.0, calibration=5900.0, spp: int = 256, size: int | None = None,
                     first_seed: int = 0, imaging: dict | None = None, limits=tuple(LIMITS_SCENE_FREE),
                     variant: str | None = None, progress: Callable[[str], None] | None = None) -> dict:
    """
    ``seeds`` independent validations of the face at ``level`` (seeds ``first_seed + j ·`` :data:`SEED_STEP`);
    per check the observed false-alarm rate against its nominal α.

    Parameters
    ----------
    level
        A level of physics (``direct``, ``sheen+noise``, …).
    seeds
        Independent validations, ≥ 1.
    camera_, scene, prevailing, calibration, spp, size, imaging, limits, variant
        As :func:`skinrender.rendering.face.validate_face` (temperatures K; ``imaging``: :func:`face_run`'s).
    first_seed
        The first validation's seed.
    progress
        Called with a line after each validation.

    Returns
    -------
    dict
        ``machine``, the settings, ``checks``: per check ``{name, nominal_alpha, nominal ("equal to" for a
        difference test, "at most" for eq4_shift where Eq. 4 holds, None where its null does not hold), failures,
        trials (and ``seeds``, the same, as the chart's calibration names it), rate, interval (95 %), consistent (α inside the interval, or below its top for "at most"; None
        without a null), outcomes ({outcome: count}), test}``, ``runs`` (``[{seed, seconds, outcomes,
        statistics}]``), ``tests`` (each check's test in words) and ``elapsed_s``.
    """
    if isinstance(seeds, bool) or not isinstance(seeds, int) or seeds < 1:
        raise SkinrenderError(f"seeds must be an integer ≥ 1, got {seeds!r}")
    level = physics_level(level)  # the spec parsed once, here
    begun = time.perf_counter()
    runs, verdicts = [], {}
    for j in range(seeds):
        seed = seed_at(first_seed, j * SEED_STEP)
        out = face_run(scene, camera_, prevailing, calibration, spp, seed, imaging, level=level, size=size,
                       limits=limits, variant=variant)
        for name, verdict in out["checks"].items():
            verdicts.setdefault(name, []).append(verdict)
        runs.append({"seed": seed, "seconds": out["seconds"], "spp": out["spp"],
                     "outcomes": {name: v.outcome for name, v in out["checks"].items()},
                     "statistics": {name: v.statistic for name, v in out["checks"].items()}})
        if progress is not None:
            failed = [name for name, v in out["checks"].items() if v.outcome == "fail"]
            progress(f"seed {seed}: {out['seconds']:.1f} s" + (f", failed: {', '.join(failed)}" if failed else ""))
    rows = []
    for name, found in verdicts.items():
        outcomes = [v.outcome for v in found]
        failures, trials = outcomes.count("fail"), len(outcomes)
        low, high = binomial_interval(failures, trials)
        alpha = found[0].alpha
        if name not in ("eq4_shift", "detection"):
            nominal, consistent = "equal to", low <= alpha <= high
        elif _eq4_exact(level) and (name == "eq4_shift" or not any(e.post is not None for e in level.effects)):
            nominal, consistent = "at most", low <= alpha
        else:
            nominal, consistent = None, None
        if nominal and not any(o in ("pass", "fail") for o in outcomes):  # no false alarm, but no test either
            consistent = None
        rows.append({"name": name, "nominal_alpha": alpha if nominal else None, "nominal": nominal,
                     "failures": failures, "trials": trials, "seeds": trials, "rate": failures / trials, "interval": [low, high],
                     "consistent": consistent, "outcomes": {o: outcomes.count(o) for o in sorted(set(outcomes))},
                     "test": found[0].test,
                     **({} if nominal else {"undefined": "Eq. 4 does not hold at this level: a fail is a finding "
                                                         "(a shift beyond the budget, rates changed), not a false "
                                                         "alarm"}),
                     **({"undefined": "no run was decided (every one inconclusive): nothing is tested"}
                        if nominal and consistent is None else {})})
    return {"machine": machine(), "level": level.name, "scene": getattr(scene, "name", str(scene)),
            "camera": getattr(camera_, "name", str(camera_)), "prevailing_K": prevailing,
            "calibration_K": calibration, "spp_requested": spp, "spp": runs[0]["spp"], "size": size,
            "seeds": seeds, "first_seed": first_seed, "seed_step": SEED_STEP, "checks": rows, "runs": runs,
            "tests": {row["name"]: row["test"] for row in rows},
            "imager": None if not imaging else getattr(imaging.get("imager_"), "name", imaging.get("imager_")),
            "illuminance_lux": None if not imaging else imaging.get("illuminance_lux"),
            "elapsed_s": time.perf_counter() - begun}
