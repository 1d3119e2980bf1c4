"""
Face sweeps
===========

The face (:func:`skinrender.rendering.face.render_face`) rendered for every
combination of cameras × (prevailing, calibration) light pairs × skins ×
levels of physics, each scored as the ladder scores a level
(:mod:`skinrender.studies.face.ladder`): the scored skin pixels' NCC mean and
spread, the share of them inside the camera's analytic skin locus (TPR) and
that of the scored prop pixels (FPR), and the detection verdict (Eq. 4's rates
against the rendered ones, the renderer's noise separated); each combination
rendered as replicates, as the ladder renders a level. The renders run on every core (a
process pool) or a Dask cluster, as the Stage 3 search does
(:mod:`skinrender.design.search`).

-   :func:`face_sweep`, :class:`FaceSweep`: the sweep, its JSON document and CSV.
-   :func:`score_rendering`: one face render scored (the ladder's scoring).
-   :func:`sweep_tasks`: the combinations, in the order of the result.

Determinism: every render uses the same seed, the Mitsuba variant chosen
once in the calling process and one drjit thread
(:mod:`~skinrender.studies.face.workers`, which runs the renders), so the
numbers (all but ``seconds``) are the same with one worker, several or a
Dask cluster (tested). A script that asks for several workers needs the
``if __name__ == "__main__":`` guard (workers are spawned).

Units: temperatures K, times s, image sides pixels, NCC and rates fractions.
"""

from __future__ import annotations

import csv
import io
import itertools
import math
import os
import time
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path

import numpy as np

from ...errors import SkinrenderError
from ...execution import check_workers, dask_name
from ...evaluation.locus import skin_locus
from ...files import write_output
from ...model.camera import camera
from ...model.chromaticity import ncc
from ...evaluation.detection_verdict import DETECTION_TOLERANCE, check_tolerance
from ...rendering.face import planckian_temperature
from ...rendering.face.detection import face_detection
from ...rendering.face.effects import PHYSICS_REGISTRY, physics_level
from ...rendering.face.limits import REPLICATES
from ...rendering.face.request import face_request
from ...rendering.face.shift import skin_set_name
from ...rendering.face.validation import mean_rendering, render_replicates, replicated_of
from ...rendering.face.effects.direct import SAMPLES_PER_S_DIRECT
from ...rendering.face.effects.direct import SECONDS_PER_RENDER as SECONDS_PER_RENDER_DIRECT
from ...rendering.face.scene import load_face_scene, skin_reflectance_of
from ...rendering.bands import BANDS_DEFAULT, bands_text, check_bands, parse_bands, projection
from ...rendering.renderer import SAMPLES_MAX
from ...rendering.scene import PIXELS_MAX
from ...rendering.settings import check_seed, seed_at
from ...rendering.validation import analytic_reference
from ...rendering.variants import choose_variant
from ...spectra import GRID_DEFAULT, WavelengthGrid
from ...workload import check_work, duration_text
from .workers import RenderRun, run_renders
from .ladder import score_rendering

__all__ = ["REPLICATES_SWEEP", "RENDERS_MAX", "SWEEP_SAMPLES_MAX", "SECONDS_PER_RENDER", "SAMPLES_PER_S", "CSV_COLUMNS",
           "FaceSweep", "face_sweep", "sweep_tasks", "spectral_tasks", "estimate_seconds"]

REPLICATES_SWEEP = REPLICATES
"""Replicates each combination is rendered as (independent seeds, ``⌈spp / K⌉`` spp each): their mean is scored,
their spread separates the renderer's noise from the physics in the detection verdict."""

RENDERS_MAX = 5000
"""Most renders a sweep may ask for unless ``max_renders`` is raised (a guard against a slip of the flags)."""

SWEEP_SAMPLES_MAX = 10**11
"""Most samples (renders × pixels × spp) a sweep may ask for unless ``max_samples`` is raised (about 15 h on 2
cores at :data:`SAMPLES_PER_S`)."""

SECONDS_PER_RENDER = SECONDS_PER_RENDER_DIRECT
"""Fixed cost of one face render on one core, s: the estimates' base
(:data:`skinrender.rendering.face.effects.direct.SECONDS_PER_RENDER`)."""

SAMPLES_PER_S = SAMPLES_PER_S_DIRECT
"""Samples per second of the face on one core (one drjit thread), the estimates' rate (see
:data:`SECONDS_PER_RENDER`) at every level but those whose effects are slower (a level's own rate:
:attr:`~skinrender.rendering.face.effects.Level.samples_per_s`, e.g. ``subsurface-volume``'s)."""

CSV_COLUMNS = ("camera", "prevailing_K", "calibration_K", "skin", "level", "seconds", "spp",
               "skin_ncc_mean_r", "skin_ncc_mean_g", "skin_ncc_mean_b", "skin_ncc_std_r", "skin_ncc_std_g",
               "skin_ncc_std_b", "tpr", "fpr", "skin_pixels", "prop_pixels",
               "skin_ncc_analytic_r", "skin_ncc_analytic_g", "skin_ncc_analytic_b", "skin_set",
               "detection_verdict", "detection_tpr", "detection_fpr", "tpr_eq4", "fpr_eq4", "tpr_change",
               "fpr_change")
"""Columns of :meth:`FaceSweep.to_csv`; an empty cell where a value is ``None``."""


@dataclass(frozen=True)
class _Settings:
    """What every render of a sweep shares (sent to each worker once per task; small)."""

    scene: object
    size: int
    spp: int
    seed: int
    variant: str
    grid: WavelengthGrid
    imager: str | None
    illuminance: float | None
    skin_set: object = "skin"
    tolerance: float = DETECTION_TOLERANCE

    @property
    def seeds(self) -> list[int]:
        """The replicates' seeds: ``seed, seed + 1, …`` (mod 2³²)."""
        return [seed_at(self.seed, k) for k in range(REPLICATES_SWEEP)]

    @property
    def each(self) -> int:
        """A replicate's spp: ``⌈spp / K⌉``."""
        return -(-self.spp // REPLICATES_SWEEP)


def _scored(replicated, cam, p: float, c: float, skin: str, settings: _Settings, start: float) -> dict:
    """One combination's row from its replicates: their mean scored as the ladder scores a level, and its
    detection verdict (``start``: when its work began, ``perf_counter``)."""
    grid = settings.grid
    result = mean_rendering(replicated)
    locus = skin_locus(cam, settings.skin_set, calibration=c, grid=grid)
    rho = skin_reflectance_of(skin, grid, "skin")
    analytic = ncc(analytic_reference(cam, rho[None], p, c, grid=grid))[0]
    detection, _ = face_detection(replicated, locus, settings.tolerance, seed=settings.seed, mean=result)
    row = {"camera": cam.name, "prevailing_K": p, "calibration_K": c, "skin": skin,
           "level": result.physics, "seconds": 0.0, "spp": result.spp, "replicates": len(replicated.renders),
           "spp_per_replicate": replicated.first.spp, **score_rendering(result, locus),
           "skin_ncc_analytic": analytic.tolist(), "variant": result.variant,
           "skin_set": skin_set_name(settings.skin_set), "detection": detection}
    row.update({k: v for k, v in result.info.items() if k in ("imager", "illuminance_lux", "exposure_s")})
    row["seconds"] = time.perf_counter() - start
    return row


def _render_task(task: tuple, settings: _Settings) -> dict:
    """One combination ``(camera, prevailing K, calibration K, skin, level)`` rendered as :data:`REPLICATES_SWEEP`
    replicates and scored."""
    cam, p, c, skin, level = task
    start = time.perf_counter()
    sensor = PHYSICS_REGISTRY.options_for(level, {"imager": settings.imager, "illuminance": settings.illuminance})
    replicated = render_replicates(cam, settings.scene, p, c, skin, level, settings.each, settings.seeds,
                                   settings.size, grid=settings.grid, variant=settings.variant, **sensor)
    return _scored(replicated, cam, p, c, skin, settings, start)


def _spectral_task(task: tuple, settings: _Settings, bands: WavelengthGrid) -> list[dict]:
    """
    One spectral render per replicate ``(prevailing K, skin, level, cameras, calibrations K)`` seen through every
    camera at every calibration: their rows, the renders' seconds shared equally among them (each adds its own
    projections and scoring).
    """
    from ...rendering.face.spectral_face import render_face_spectral_request

    p, skin, level, cams, calibrations = task
    sensor = PHYSICS_REGISTRY.options_for(level, {"imager": settings.imager, "illuminance": settings.illuminance})
    request = face_request(settings.scene, None, p, None, skin=skin, physics=level, size=settings.size,
                           spp=settings.each, seed=settings.seed, variant=settings.variant, grid=settings.grid,
                           bands=bands, **sensor)
    begun = time.perf_counter()
    images = [render_face_spectral_request(request, seed) for seed in settings.seeds]  # one per replicate
    share = (time.perf_counter() - begun) / (len(cams) * len(calibrations))
    rows = []
    for cam in cams:
        for c in calibrations:
            start = time.perf_counter() - share
            replicated = replicated_of([image.through(cam, c) for image in images], request)
            rows.append(_scored(replicated, cam, p, c, skin, settings, start))
    return rows


def spectral_tasks(cameras, lights, skins, levels) -> list[tuple]:
    """
    The spectral renders of a sweep: one per prevailing light, skin and level, each with every camera and the
    calibrations paired with that light.

    Examples
    --------
    >>> [t[:3] + (t[4],) for t in spectral_tasks(["a", "b"], [(2856.0, 5900.0), (2856.0, 2856.0)], ["s"],
    ...                                           ["direct"])]
    [(2856.0, 's', 'direct', [5900.0, 2856.0])]
    """
    prevailing = list(dict.fromkeys(p for p, _ in lights))
    return [(p, skin, level, list(cameras), [c for q, c in lights if q == p])
            for p, skin, level in itertools.product(prevailing, skins, levels)]


def sweep_tasks(cameras, lights, skins, levels) -> list[tuple]:
    """
    Every combination, cameras outermost, then light pairs, skins, levels.

    Examples
    --------
    >>> [t[1:] for t in sweep_tasks(["cam"], [(2856.0, 5900.0)], ["a", "b"], ["direct"])]
    [(2856.0, 5900.0, 'a', 'direct'), (2856.0, 5900.0, 'b', 'direct')]
    """
    return [(cam, p, c, skin, level) for cam, (p, c), skin, level in itertools.product(cameras, lights, skins, levels)]


def estimate_seconds(renders: int, pixels: int, spp: int, cores: int = 2, levels=None, bands=None,
                     skins: int = 1) -> float:
    """
    Wall time of ``renders`` face renders of ``pixels`` pixels at ``spp`` on ``cores`` cores, s (from
    :data:`SECONDS_PER_RENDER` and :data:`SAMPLES_PER_S`, per core; a worker's start, a few seconds, aside);
    ``levels``, one per render, each render at its level's rate
    (:attr:`~skinrender.rendering.face.effects.Level.samples_per_s`: ``subsurface-volume`` is far slower) and
    each distinct level's one-off work once per skin of the ``skins``
    (:attr:`~skinrender.rendering.face.effects.Level.setup_seconds`: ``subsurface``'s table); ``bands``:
    spectral renders of those bands (each sample costs more: :data:`~skinrender.rendering.bands.BAND_COST`).

    Examples
    --------
    >>> round(estimate_seconds(54, 128 * 128, 64, cores=1))  # measured: docs/speed.md
    71
    """
    rates = [SAMPLES_PER_S] * renders if levels is None else [physics_level(level).samples_per_s for level in levels]
    factor = 1.0
    if bands is not None:
        from ...rendering.bands import BAND_COST

        factor = 1.0 + BAND_COST[0] * bands.size ** BAND_COST[1]
    setup = 0.0 if levels is None else sum(physics_level(level).setup_seconds for level in set(levels)) * skins
    return (sum(SECONDS_PER_RENDER + factor * pixels * spp / rate for rate in rates) + setup) / max(1, cores)


@dataclass(frozen=True)
class FaceSweep(RenderRun):
    """
    The sweep's result: a row per combination of camera, light pair, skin and level, and how its renders ran
    (:class:`~skinrender.studies.face.workers.RenderRun`'s keyword fields: size, spp, seed, variant, workers,
    ``elapsed_s``, ``dask``).

    Attributes
    ----------
    combinations
        One dict per combination, in :func:`sweep_tasks` order: ``camera``, ``prevailing_K``,
        ``calibration_K``, ``skin``, ``level``, ``seconds``, ``spp``, ``skin_ncc_mean``, ``skin_ncc_std``
        (``[r, g, b]``), ``tpr``, ``fpr``, ``skin_pixels``, ``prop_pixels``, ``skin_ncc_analytic`` (Eq. 4's
        NCC of the skin, ``[r, g, b]``), ``undefined`` (``{key: reason}`` for each ``None``, as the ladder's;
        in the JSON, not the CSV), ``variant``, and ``imager``/``exposure_s`` with ``noise``.
    elapsed_s
        Wall time of the renders, s.
    """

    scene: object
    combinations: list = field(default_factory=list)
    spectral: dict | None = None

    def document(self) -> dict:
        """The JSON document (``combinations`` and the settings; ``spectral``: the bands and the spectral renders
        made, or ``null`` for one render per combination)."""
        return {"scene": self.scene, "size": self.size, "spp": self.spp, "seed": self.seed,
                "variant": self.variant, "workers": self.workers, "dask": self.dask, "elapsed_s": self.elapsed_s,
                "renders": len(self.combinations), "spectral": self.spectral, "combinations": self.combinations}

    def to_csv(self, path, flag: str | None = None) -> Path:
        """Every combination as a CSV row (:data:`CSV_COLUMNS`), written whole or not at all (``flag``: the
        option that named ``path``, for the message when it cannot be written)."""
        handle = io.StringIO(newline="")
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(CSV_COLUMNS)
        for row in self.combinations:
            triples = [v for key in ("skin_ncc_mean", "skin_ncc_std")
                       for v in (row[key] if row[key] is not None else [None] * 3)]
            found = row.get("detection") or {}
            cells = [row["camera"], row["prevailing_K"], row["calibration_K"], row["skin"], row["level"],
                     row["seconds"], row["spp"], *triples, row["tpr"], row["fpr"], row["skin_pixels"],
                     row["prop_pixels"], *row["skin_ncc_analytic"], row.get("skin_set"),
                     *(found.get(key) for key in ("verdict", "tpr", "fpr", "tpr_eq4", "fpr_eq4", "tpr_change",
                                                   "fpr_change"))]
            writer.writerow(["" if v is None else f"{v:.17g}" if isinstance(v, float) else v for v in cells])
        return write_output(path, handle.getvalue(), flag)


def _check_size(renders: int, size: int, spp: int, max_renders: int, max_samples: float, cores: int,
                levels=None, bands=None, skins: int = 1, max_minutes: float | None = None) -> None:
    """Refuse a sweep too large (``levels``: each render's level; a slower level's samples count at its cost;
    ``bands``: spectral renders, each sample at the bands' cost; ``skins``: how many; ``max_minutes``: the cap of
    its estimated time, ``None`` none)."""
    pixels = size * size
    if pixels > PIXELS_MAX:
        raise SkinrenderError(f"size {size} pixels gives {pixels} pixels per image, more than {PIXELS_MAX}",
                              role="size")
    if spp * pixels > SAMPLES_MAX:
        raise SkinrenderError(f"spp {spp} × {pixels} pixels is more than {SAMPLES_MAX:.3g} samples per render; at "
                              f"most {SAMPLES_MAX // pixels} spp at this size", role="spp")
    each = -(-spp // REPLICATES_SWEEP)  # every combination is rendered as replicates of ⌈spp / K⌉
    seconds = estimate_seconds(renders * REPLICATES_SWEEP, pixels, each, cores,
                               None if levels is None else [level for level in levels for _ in range(REPLICATES_SWEEP)],
                               bands, skins)
    on = f"on {cores} core{'s' * (cores > 1)}"
    about = f"about {duration_text(seconds)} {on}"
    if renders > max_renders:
        raise SkinrenderError(f"{renders} renders is more than max_renders = {max_renders} ({about}); raise "
                              "the limit (--max-renders) or sweep fewer combinations", role="max_renders")
    costs = [1.0] * renders if levels is None else [SAMPLES_PER_S / physics_level(level).samples_per_s
                                                     for level in levels]
    weighted = sum(costs) * pixels * spp
    if weighted > max_samples:
        slower = [] if levels is None else sorted({physics_level(level).name for level, cost in zip(levels, costs)
                                                   if cost > 1})
        counted = (f" (at {', '.join(slower)} a sample counts as {max(costs):.3g} at the base's rate, its cost)"
                   if slower else "")
        raise SkinrenderError(f"{renders} renders × {pixels} pixels × {spp} spp = {weighted:.3g} samples{counted} "
                              f"is more than max_samples = {max_samples:.3g} ({about}); raise "
                              "the limit (--max-samples) or lower the size or spp", role="max_samples")
    if max_minutes is not None:
        if isinstance(max_minutes, bool) or not (isinstance(max_minutes, (int, float)) and math.isfinite(max_minutes)
                                                 and max_minutes > 0):
            raise SkinrenderError(f"max_minutes must be a finite number of minutes > 0, got {max_minutes!r}",
                                  role="max_minutes")
        try:
            check_work(seconds, "--max-minutes", f"{renders} renders of {pixels} pixels at {spp} spp {on}",
                       max_minutes, fewer="lower --size or --spp, or sweep fewer combinations")
        except SkinrenderError as error:
            raise error.reworded(role="max_minutes") from None


def face_sweep(
    cameras,
    lights,
    skins,
    levels,
    size: int = 64,
    spp: int = 32,
    seed: int = 0,
    scene="face",
    variant: str | None = None,
    grid: WavelengthGrid = GRID_DEFAULT,
    imager: str | None = None,
    illuminance: float | None = None,
    workers: int | None = None,
    dask=None,
    progress=None,
    max_renders: int = RENDERS_MAX,
    max_samples: float = SWEEP_SAMPLES_MAX,
    max_minutes: float | None = None,
    spectral: bool | None = None,
    bands: WavelengthGrid | str = BANDS_DEFAULT,
    skin_set="skin",
    detection_tolerance: float = DETECTION_TOLERANCE,
) -> FaceSweep:
    """
    Render and score the face for every camera × light pair × skin × level.

    Parameters
    ----------
    cameras
        Cameras or specs.
    lights
        (prevailing, calibration) pairs: kelvin, ``A`` or ``H`` (Planckian lights).
    skins
        Skin specs (``SET:SAMPLE``, ``SET:#N``, ``skin-model:melanin=…``).
    levels
        Physics levels (:data:`skinrender.rendering.face.PHYSICS`, effects joined by ``+``).
    size
        Image side, pixels.
    spp, seed, variant, grid
        As :func:`skinrender.rendering.face.render_face`; every render uses ``seed``; the variant is chosen
        once here (``None``: the fastest that works) and used by every worker.
    scene
        A face scene name or path.
    imager, illuminance
        The ``noise`` level's image sensor and the key light's illuminance, lx (as :func:`ladder`).
    workers
        Processes; ``None``: every core. 1 renders in this process.
    dask
        A Dask scheduler address (``tcp://host:8786``) or a ``distributed.Client``: the renders run there.
    progress
        A stream (``sys.stderr``) for a progress bar (shown on a terminal only), or ``None``.
    max_renders, max_samples, max_minutes
        Refuse a sweep of more renders, or more samples (renders × pixels × spp), than these, or estimated to take
        longer than ``max_minutes`` (``None``: no cap of time; the command line's default is an hour); the
        message carries the estimate.
    spectral, bands
        Render once per prevailing light, skin and level with ``bands`` (``START:END:STEP`` nm) as the film and
        see every camera and calibration through it (:mod:`~skinrender.rendering.face.spectral_face`), rather
        than once per combination; ``None``: spectral for more than one camera. A spectral render's seconds are
        shared equally by the rows it serves.
    skin_set
        The reflectance set of every combination's skin locus (``skin``: the Vrhel skins; a name, a set or
        spectra); each row says which (``skin_set``).
    detection_tolerance
        How far Eq. 4 may be off in TPR and FPR, fractions in (0, 1): each row's ``detection`` verdict
        (:func:`~skinrender.rendering.face.detection.face_detection`). Every combination is rendered as
        :data:`REPLICATES_SWEEP` replicates of ``⌈spp / K⌉`` spp (seeds ``seed, seed + 1, …``), scored on their mean.

    Returns
    -------
    :class:`FaceSweep`
    """
    cams = [camera(c) for c in cameras]
    pairs = [(planckian_temperature(p, "prevailing"), planckian_temperature(c, "calibration")) for p, c in lights]
    skins = [str(s).strip() for s in skins]
    levels = [PHYSICS_REGISTRY.level(level) for level in levels]  # each spec parsed once, here
    for name, values in (("cameras", cams), ("lights", pairs), ("skins", skins), ("levels", levels)):
        if not values:
            raise SkinrenderError(f"{name}: name at least one")
    for skin in skins:
        skin_reflectance_of(skin, grid, "skin")
    for name, value, low in (("size", size, 1), ("spp", spp, 1)):  # size in pixels
        if not (isinstance(value, (int, np.integer)) and not isinstance(value, bool) and low <= value < 2**32):
            raise SkinrenderError(f"{name} must be an integer in [{low}, 2^32), got {value!r}", role=name)
    check_seed(seed)  # the bound of every front door
    workers = check_workers(workers, "workers")
    tasks = sweep_tasks(cams, pairs, skins, levels)
    spectral = len(cams) > 1 if spectral is None else bool(spectral)
    cores = min(workers, os.cpu_count() or 1) if dask is None else os.cpu_count() or 1
    if spectral:
        bands = parse_bands(bands)
        check_bands(bands, grid, "the face's lights and reflectances")
        for cam in cams:  # every camera checked against the bands before any render
            projection(cam, bands, grid)
        renders = spectral_tasks(cams, pairs, skins, levels)
        _check_size(len(renders), int(size), int(spp), max_renders, max_samples, cores, [t[2] for t in renders],
                    bands, len(set(skins)), max_minutes)
    else:
        _check_size(len(tasks), int(size), int(spp), max_renders, max_samples, cores, [t[-1] for t in tasks],
                    skins=len(set(skins)), max_minutes=max_minutes)
    face = load_face_scene(scene)
    settings = _Settings(scene, int(size), int(spp), int(seed), choose_variant(variant), grid, imager, illuminance,
                         skin_set, check_tolerance(detection_tolerance, "detection_tolerance"))
    start = time.perf_counter()
    about = None
    if spectral:
        found = run_renders(partial(_spectral_task, settings=settings, bands=bands), renders, settings.variant,
                            int(workers), dask, progress, "face sweep (spectral)")
        by_key = {(row["camera"], row["prevailing_K"], row["calibration_K"], row["skin"], row["level"]): row
                  for rows in found for row in rows}
        rows = [by_key[(cam.name, p, c, skin, level.name)] for cam, p, c, skin, level in tasks]
        about = {"bands_nm": bands_text(bands), "bands": bands.size, "basis": "hat", "renders": len(renders)}
    else:
        rows = run_renders(partial(_render_task, settings=settings), tasks, settings.variant, int(workers), dask,
                           progress, "face sweep")
    return FaceSweep(face.name, rows, about, size=int(size), spp=int(spp), seed=int(seed), variant=settings.variant,
                     workers=1 if dask is not None else int(workers), elapsed_s=time.perf_counter() - start,
                     dask=dask_name(dask))
