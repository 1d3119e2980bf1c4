"""
Calibration of the detection verdict
====================================

The face's detection verdict (:func:`~skinrender.rendering.face.detection.face_detection`)
says whether Eq. 4 predicts the skin locus's rates within a tolerance. Where
Eq. 4 holds exactly (``direct``, and levels whose analytic check is the
base's) every ``fail`` is a false alarm, at any spp: the renderer's noise must
be separated from the physics however large it is. This study measures that:
``seeds`` independent runs (each renders its replicates, seeds ``S … S + K − 1``;
runs ``K`` apart) of the detection verdict alone — no other check, and no
floor on the spp per replicate, so that it runs at the ladder's sizes (64 px,
16 spp: 12 replicates of 2 spp) — with the failures, the Clopper–Pearson 95 %
interval of their rate and the nominal α.

-   :func:`detection_calibration`: the study (``skinrender bench calibration
    --scene face --checks detection``).
-   :func:`estimate_detection_seconds`: its time.

Units: seconds s, spp samples per pixel, rates fractions, temperatures K.

References
----------
-   :cite:`Clopper1934` : see :mod:`skinrender.evaluation.verdict`.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from ...errors import SkinrenderError
from ...evaluation.detection_verdict import DETECTION_TOLERANCE, check_tolerance
from ...evaluation.locus import skin_locus
from ...evaluation.verdict import binomial_interval
from ...model.camera import camera
from ...rendering.face import planckian_temperature
from ...rendering.face.detection import face_detection
from ...rendering.face.effects import PHYSICS_BASE, PHYSICS_EFFECTS, PHYSICS_REGISTRY, physics_level
from ...rendering.face.limits import REPLICATES
from ...rendering.face.scene import load_face_scene
from ...rendering.face.shift import skin_set_name
from ...rendering.face.validation import render_replicates
from ...rendering.settings import seed_at
from .bench import machine

__all__ = ["detection_calibration", "estimate_detection_seconds"]

SECONDS_DETECTION = 0.5
"""The detection statistics of one run, s (half-samples and their separations; measured 0.2–1 on 2 cores)."""


def estimate_detection_seconds(seeds: int, pixels: int, spp: int, level: str | None = None) -> float:
    """
    Wall time of ``seeds`` runs of the detection verdict on a face of ``pixels`` pixels at ``spp`` (split over the
    replicates), s, on one core.

    >>> round(estimate_detection_seconds(40, 64 * 64, 16))  # measured: 33 s (2 cores, load 8)
    96
    """
    from ..face.sweep import estimate_seconds

    each = max(1, -(-int(spp) // REPLICATES))
    levels = None if level is None else [level] * REPLICATES
    return seeds * (estimate_seconds(REPLICATES, pixels, each, 1, levels) + SECONDS_DETECTION)


def _eq4_exact(level) -> bool:
    check = physics_level(level).check
    return check is not None and check is PHYSICS_EFFECTS[PHYSICS_BASE].limits.check


def detection_calibration(level: str = PHYSICS_BASE, seeds: int = 40, camera_="gbell:9@450,540,610",
                          scene="face", prevailing=2856.0, calibration=5900.0, spp: int = 16, size: int | None = 64,
                          skin: str | None = None, skin_set="skin", tolerance: float = DETECTION_TOLERANCE,
                          first_seed: int = 0, imaging: dict | None = None, variant: str | None = None,
                          progress: Callable[[str], None] | None = None) -> dict:
    """
    ``seeds`` independent detection verdicts of the face at ``level`` (see the module).

    Parameters
    ----------
    level
        A level of physics; its fails are false alarms only where Eq. 4 holds exactly: levels whose analytic
        check is the base's (``direct``) and that add no sensor (a sensor's noise changes detection: physics
        Eq. 4 leaves out).
    seeds
        Independent runs, ≥ 1 (seeds ``first_seed + j · K``).
    spp
        Samples per pixel of a run in all, split over the :data:`~skinrender.rendering.face.limits.REPLICATES`
        replicates (each ``⌈spp / K⌉``).
    size
        Image side, pixels (``None``: the scene's).
    skin, skin_set, tolerance
        The face's skin (``None``: the scene's), the set of the locus, the verdict's tolerance.
    imaging
        ``{imager_, exposure, illuminance_lux}`` for a level with ``noise``, or ``None``.

    Returns
    -------
    dict
        As :func:`~skinrender.studies.benchmarks.face_calibration.face_calibration`'s: ``checks`` (one row,
        ``detection``: ``failures``, ``trials``, ``rate``, ``interval``, ``nominal_alpha``, ``nominal``,
        ``consistent``, ``outcomes``), ``runs`` (per seed its outcome, changes and bounds), the settings.
    """
    if isinstance(seeds, bool) or not isinstance(seeds, int) or seeds < 1:
        raise SkinrenderError(f"seeds must be an integer ≥ 1, got {seeds!r}")
    tolerance = check_tolerance(tolerance, "tolerance")
    effects = physics_level(level)
    cam, face = camera(camera_), load_face_scene(scene)
    p, c = planckian_temperature(prevailing, "prevailing"), planckian_temperature(calibration, "calibration")
    locus = skin_locus(cam, skin_set, calibration=c)
    imaging = imaging or {}
    sensor = PHYSICS_REGISTRY.options_for(effects, {"imager": imaging.get("imager_"),
                                                    "exposure": imaging.get("exposure"),
                                                    "illuminance": imaging.get("illuminance_lux")})
    each = max(1, -(-int(spp) // REPLICATES))
    begun, runs, verdicts = time.perf_counter(), [], []
    for j in range(seeds):
        seed = seed_at(first_seed, j * REPLICATES)
        start = time.perf_counter()
        replicated = render_replicates(cam, face, p, c, skin, effects, each,
                                       [seed_at(seed, k) for k in range(REPLICATES)], size, variant=variant,
                                       **sensor)
        document, verdict = face_detection(replicated, locus, tolerance, seed=seed)
        verdicts.append(verdict)
        runs.append({"seed": seed, "seconds": time.perf_counter() - start, "outcome": verdict.outcome,
                     **{key: document[key] for key in ("tpr_change", "fpr_change", "tpr_change_bound",
                                                       "fpr_change_bound", "mc_floor")}})
        if progress is not None:
            progress(f"seed {seed}: {verdict.outcome} (ΔTPR {document['tpr_change']}, ΔFPR {document['fpr_change']})")
    outcomes = [v.outcome for v in verdicts]
    failures, trials = outcomes.count("fail"), len(outcomes)
    low, high = binomial_interval(failures, trials)
    alpha = verdicts[0].alpha
    exact = _eq4_exact(effects) and not any(effect.post is not None for effect in effects.effects)
    row = {"name": "detection", "nominal_alpha": alpha if exact else None, "nominal": "at most" if exact else None,
           "failures": failures, "trials": trials, "seeds": trials, "rate": failures / trials, "interval": [low, high],
           "consistent": (low <= alpha) if exact else None,
           "outcomes": {o: outcomes.count(o) for o in sorted(set(outcomes))}, "test": verdicts[0].test}
    if not exact:
        row["undefined"] = ("Eq. 4 does not hold exactly at this level: a fail is a finding (the rates changed), not "
                            "a false alarm")
    elif not any(o in ("pass", "fail") for o in outcomes):  # no false alarm, but no test either: nothing shown
        row["consistent"] = None
        row["undefined"] = "no run was decided (every one inconclusive: too few pixels or samples): nothing is tested"
    return {"machine": machine(), "level": effects.name, "scene": face.name, "camera": cam.name, "prevailing_K": p,
            "calibration_K": c, "spp_requested": int(spp), "spp": each * REPLICATES, "size": size,
            "skin": skin or face.skin, "skin_set": skin_set_name(skin_set), "detection_tolerance": tolerance,
            "seeds": seeds, "first_seed": first_seed, "seed_step": REPLICATES, "checks": [row], "runs": runs,
            "tests": {"detection": row["test"]}, "imager": imaging.get("imager_") and str(imaging.get("imager_")),
            "illuminance_lux": imaging.get("illuminance_lux"), "elapsed_s": time.perf_counter() - begun}
