"""
Calibration of the verdicts
===========================

How often a check fails where its null holds, measured over independent seeds
(``skinrender bench calibration``), and what a validation costs and shows as
the samples per pixel grow (``skinrender bench validate``).

-   :data:`CALIBRATION_PATHS`, :func:`calibration_path`: the validate paths a
    calibration runs, by kind of scene (``chart``, ``face``: the face's is
    :func:`skinrender.studies.benchmarks.face_calibration.face_run`, whose validations
    are :data:`~skinrender.studies.benchmarks.face_calibration.SEED_STEP` seeds apart;
    its calibration, :func:`~skinrender.studies.benchmarks.face_calibration.face_calibration`).
-   :func:`estimate_seconds`: the time a run of validations takes (the
    command line refuses one above ``--max-minutes``, :mod:`skinrender.workload`).
-   :func:`bench_calibration`: per check, the observed false-alarm rate with
    its Clopper–Pearson 95 % interval against the nominal α.
-   :func:`bench_validate`: per spp, the seconds, the bound (the smallest
    tolerance that would pass) and the observed false-alarm rate.

A chart's renderer is unbiased (its analytic reference is what it
integrates), so every difference test's failure there is a false alarm, and
an equivalence ``fail`` (some value shown beyond the tolerance) is a false
fail whenever the true errors are within the tolerance.

Units: seconds s, spp samples per pixel, rates fractions, temperatures K.

References
----------
-   :cite:`Clopper1934` : see :mod:`skinrender.evaluation.verdict`.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence

import numpy as np

from ...errors import SkinrenderError
from ...evaluation.verdict import ALPHA_DIFFERENCE, ALPHA_EQUIVALENCE, binomial_interval
from .bench import machine

__all__ = ["CALIBRATION_PATHS", "CHART_SAMPLES_PER_S", "CHART_SECONDS_PER_RENDER", "calibration_path",
           "estimate_seconds", "renders_of", "bench_calibration", "bench_validate"]

CHART_SAMPLES_PER_S = 2.8e6
"""Samples per second of a chart render (fitted with :data:`CHART_SECONDS_PER_RENDER` to the Macbeth chart through
gbell:9, one pass, at 16–1024 spp: 0.11–3.0 s per render, 2-core AMD EPYC VM, llvm_ad_spectral)."""

CHART_SECONDS_PER_RENDER = 0.065
"""Fixed cost of one chart render (the fit of :data:`CHART_SAMPLES_PER_S`), s."""

SENSOR_SECONDS = 0.2
"""A validation through an image sensor beside its render (the second frame and the tests), s (measured 0.07–0.2)."""

STARTUP_SECONDS = 5.0
"""The first render's kernel compilation, s (measured 1.5–6)."""


def _chart_run(scene, camera_, prevailing: float, calibration: float, spp: int, seed: int, imaging: dict | None,
               mc_variance: str, tolerance: float | None, level: str | None, grid=None) -> dict:
    """One validation of a chart (through a sensor with ``imaging``): its checks' verdicts, bound and seconds."""
    from ...rendering.validation import analytic_reference, validate
    from ...spectra import GRID_DEFAULT

    grid = GRID_DEFAULT if grid is None else grid
    settings = {} if tolerance is None else {"tolerance": tolerance}
    if imaging is None:
        result = validate(scene, camera_, prevailing, calibration, grid=grid, spp=spp, seed=seed, **settings)
        return {"checks": {"difference": result.difference, "equivalence": result.verdict}, "bound": result.bound,
                "seconds": result.rendering.seconds, "spp": result.rendering.raw[0].spp}
    from ...model.camera import camera
    from ...rendering.imaging import render_imaged
    from ...rendering.sensor_validation import validate_imaged

    start = time.perf_counter()
    imaged = render_imaged(scene, camera(camera_), prevailing, calibration, **imaging, spp=spp, seed=seed, grid=grid)
    ratio = analytic_reference(imaged.rendering.camera, imaged.rendering.scene.reflectances(grid), prevailing,
                               prevailing, grid=grid) / 255.0
    result = validate_imaged(imaged, ratio, grid=grid, mc_variance=mc_variance, **settings)
    return {"checks": {**result.checks, "difference": result.difference}, "bound": result.bound,
            "seconds": time.perf_counter() - start, "spp": imaged.rendering.raw[0].spp}


def _face_run(*arguments, **options) -> dict:
    """One ``validate face`` (:func:`skinrender.studies.benchmarks.face_calibration.face_run`)."""
    from .face_calibration import face_run

    return face_run(*arguments, **options)


_face_run.seed_step = 12  # each validation renders its seed and the next 11 (face_calibration.SEED_STEP)
_chart_run.levels = False  # it renders direct light only: it takes no level of physics

CALIBRATION_PATHS: dict[str, Callable[..., dict]] = {"chart": _chart_run, "face": _face_run}
"""The validate path a calibration runs, by kind of scene (``chart``, ``face``): ``run(scene, camera, prevailing,
calibration, spp, seed, imaging, mc_variance, tolerance, level)`` → ``{checks: {name: Verdict}, bound, seconds,
spp}``; a run's ``seed_step`` (2 unless it says) is how far apart two independent runs' seeds are, and its
``levels`` (true unless it says) whether it takes a level of physics."""


def calibration_path(kind: str, level: str | None = None) -> Callable[..., dict]:
    """The run of a kind of scene (:data:`CALIBRATION_PATHS`); ``level`` (a face's level of physics) is refused for
    a chart, and a kind with no run registered with a one-line reason naming ``--scene``."""
    if kind not in CALIBRATION_PATHS:
        raise SkinrenderError(f"--scene: no calibration of a {kind} scene's checks is registered; known: "
                              f"{', '.join(CALIBRATION_PATHS)}", flag="--scene")
    if level is not None and not getattr(CALIBRATION_PATHS[kind], "levels", True):
        raise SkinrenderError(f"--level {level}: levels of physics go with a face scene; a chart has none (its "
                              "renders are direct lighting only)", flag="--level")
    return CALIBRATION_PATHS[kind]


def estimate_seconds(runs: int, pixels: int, spp: int, renders: int = 2, passes: int = 1,
                     sensor: bool = False) -> float:
    """
    Wall time of ``runs`` chart validations, s: each ``renders`` renders (2 where prevailing ≠ calibration) of
    ``passes`` passes of ``pixels`` × ``spp`` samples, plus a sensor's validation, plus the first compilation.

    >>> round(estimate_seconds(40, 98 * 82, 16))  # the Macbeth chart, 40 seeds at 16 spp
    14
    """
    per_render = CHART_SECONDS_PER_RENDER + pixels * spp * passes / CHART_SAMPLES_PER_S
    per_run = renders * per_render + (SENSOR_SECONDS if sensor else 0.0)
    return STARTUP_SECONDS + runs * per_run


def _rates(runs: list[dict], nominal: dict) -> list[dict]:
    """Per check: failures, rate, its 95 % Clopper–Pearson interval and whether the nominal α is consistent."""
    rows = []
    for name, (alpha, kind) in nominal.items():
        outcomes = [run["outcomes"][name] for run in runs if name in run["outcomes"]]
        if not outcomes:
            continue
        failures, trials = sum(o == "fail" for o in outcomes), len(outcomes)
        lo, hi = binomial_interval(failures, trials)
        consistent = lo <= alpha <= hi if kind == "equal" else lo <= alpha
        rows.append({"name": name, "nominal_alpha": alpha, "nominal": "equal to" if kind == "equal" else "at most",
                     "failures": failures, "seeds": trials, "rate": failures / trials, "interval": [lo, hi],
                     "consistent": bool(consistent),
                     "outcomes": {o: outcomes.count(o) for o in sorted(set(outcomes))}})
    return rows


def _nominal(checks: dict) -> dict:
    """Each check's nominal false-alarm rate and whether the observed rate should equal it or stay below it."""
    out = {}
    for name, verdict in checks.items():
        if name == "equivalence":
            out[name] = (verdict.alpha, "at most")
        elif name in ("mean", "variance"):  # half of the sensor family, each test at the family's Šidák level
            tests = verdict.details.get("tests")
            out[name] = (1 - (1 - verdict.threshold) ** tests if tests else verdict.alpha, "equal")
        else:
            out[name] = (verdict.alpha, "equal")
    return out


def bench_calibration(run: Callable[..., dict], scene, camera_, prevailing: float, calibration: float, spp: int,
                      seeds: int, first_seed: int = 0, imaging: dict | None = None, mc_variance: str = "frames",
                      tolerance: float | None = None, level: str | None = None,
                      progress: Callable[[str], None] | None = None) -> dict:
    """
    ``seeds`` independent validations (seeds ``first_seed``, ``first_seed + 2``, …: each uses its seed and the
    next; a run's ``seed_step`` apart where it says, the face's 12) where the null holds; per check the observed
    false-alarm rate against its nominal α (a face's: :func:`~skinrender.studies.benchmarks.face_calibration.face_calibration`,
    which knows where Eq. 4's null holds).

    Returns
    -------
    dict
        ``machine``, the settings, ``checks`` (``[{name, nominal_alpha, nominal, failures, seeds, rate,
        interval, consistent, outcomes}]``), ``runs`` (``[{seed, seconds, outcomes, statistics}]``),
        ``tests`` (each check's test in words), ``elapsed_s``.
    """
    begun = time.perf_counter()
    runs, nominal, tests = [], {}, {}
    step = getattr(run, "seed_step", 2)
    for j in range(seeds):
        seed = first_seed + step * j
        out = run(scene, camera_, prevailing, calibration, spp, seed, imaging, mc_variance, tolerance, level)
        nominal = nominal or _nominal(out["checks"])
        tests = tests or {name: v.test for name, v in out["checks"].items()}
        runs.append({"seed": seed, "seconds": out["seconds"], "spp": out["spp"], "bound": out["bound"],
                     "outcomes": {name: v.outcome for name, v in out["checks"].items()},
                     "statistics": {name: v.statistic for name, v in out["checks"].items()}})
        if progress is not None:
            failed = [name for name, v in out["checks"].items() if v.outcome == "fail"]
            progress(f"seed {seed}: {out['seconds']:.2f} s" + (f", failed: {', '.join(failed)}" if failed else ""))
    return {"machine": machine(), "scene": getattr(scene, "name", str(scene)), "camera": getattr(camera_, "name",
                                                                                                 str(camera_)),
            "prevailing_K": prevailing, "calibration_K": calibration, "spp_requested": spp,
            "spp": runs[0]["spp"] if runs else None, "seeds": seeds, "first_seed": first_seed,
            "imager": None if imaging is None else imaging["imager_"].name,
            "illuminance_lux": None if imaging is None else imaging["illuminance_lux"],
            "mc_variance": None if imaging is None else mc_variance, "level": level,
            "checks": _rates(runs, nominal), "tests": tests, "runs": runs,
            "elapsed_s": time.perf_counter() - begun}


def bench_validate(run: Callable[..., dict], scene, camera_, prevailing: float, calibration: float,
                   spps: Sequence[int], seeds: int = 5, first_seed: int = 0, imaging: dict | None = None,
                   mc_variance: str = "frames", progress: Callable[[str], None] | None = None) -> dict:
    """
    Per spp of ``spps``, ``seeds`` validations: the median seconds of one (the first at each spp loads the scene),
    the median bound (the smallest relative
    tolerance that would pass) and the observed false-alarm rate of the difference test (every failure is a false
    alarm: the null holds), with its Clopper–Pearson 95 % interval.

    Returns
    -------
    dict
        ``machine``, the settings, ``rows`` (``[{spp, spp_used, seconds, bound, bounds, false_alarms, seeds,
        false_alarm_rate, interval}]``), ``bound_exponent`` (``a`` of a least-squares fit ``bound ∝ spp^-a``
        over the rows; ½ for independent samples), ``alpha``, ``elapsed_s``.
    """
    begun = time.perf_counter()
    rows = []
    for spp in spps:
        outs = [run(scene, camera_, prevailing, calibration, spp, first_seed + 2 * j, imaging, mc_variance, None, None)
                for j in range(seeds)]
        failures = sum(out["checks"]["difference"].outcome == "fail" for out in outs)
        bounds = [out["bound"] for out in outs]
        lo, hi = binomial_interval(failures, seeds)
        rows.append({"spp": int(spp), "spp_used": outs[0]["spp"],
                     "seconds": float(np.median([out["seconds"] for out in outs])),
                     "bound": float(np.median(bounds)), "bounds": bounds, "false_alarms": failures, "seeds": seeds,
                     "false_alarm_rate": failures / seeds, "interval": [lo, hi]})
        if progress is not None:
            progress(f"{spp} spp: {rows[-1]['seconds']:.2f} s, bound {rows[-1]['bound']:.3g}, "
                     f"{failures}/{seeds} false alarms")
    exponent = None
    if len(rows) >= 2:
        used = np.log([row["spp_used"] for row in rows])
        exponent = float(-np.polyfit(used, np.log([row["bound"] for row in rows]), 1)[0])
    return {"machine": machine(), "scene": getattr(scene, "name", str(scene)),
            "camera": getattr(camera_, "name", str(camera_)), "prevailing_K": prevailing, "calibration_K": calibration,
            "imager": None if imaging is None else imaging["imager_"].name,
            "illuminance_lux": None if imaging is None else imaging["illuminance_lux"],
            "seeds": seeds, "first_seed": first_seed, "alpha": ALPHA_DIFFERENCE, "alpha_bound": ALPHA_EQUIVALENCE,
            "rows": rows, "bound_exponent": exponent, "elapsed_s": time.perf_counter() - begun}


def renders_of(prevailing: float, calibration: float) -> int:
    """Renders per chart validation: one at p = c, else two."""
    return 1 if math.isclose(prevailing, calibration) else 2
