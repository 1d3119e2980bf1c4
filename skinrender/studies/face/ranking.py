"""
Would Eq. 4 still choose the same camera?
=========================================

The paper's method chooses a camera by Eq. 4. This study asks whether that
choice survives the physics Eq. 4 leaves out. Candidate cameras (the top
triplets of the Stage 3 search, :func:`search_candidates`, and any named) are
scored twice on the same face scenes — skin tones × light pairs, at each level
of physics:

-   ``score_eq4``: Youden's J = TPR − FPR of the camera's analytic skin locus
    on the chromaticities Eq. 4 gives each pixel's material, averaged over the
    scenes;
-   ``score_rendered``: the same J on the rendered pixels with the renderer's
    Monte Carlo noise separated (:func:`~skinrender.rendering.face.detection.detection_rates`);

and ranked both ways. Per level: Kendall's τ (τ-b, ties counted) between the
two scores with its 95 % interval, the overlap of the two top-``k`` sets, and
whether Eq. 4's best camera is still the best (``same_best``: true, false, or
null when the samples cannot tell). The intervals come from half-samples of
the replicates (the delete-K/2 jackknife, the same halves for every camera and
scene): a bootstrap with replacement would count a replicate twice, and the
noise separation reads a repeated replicate as less noise.

Every candidate's rendered image comes from one function,
:func:`candidate_renders`: one spectral render per scene, level and seed, seen
through every camera (their differences estimated with common random numbers).

-   :func:`rank`, :class:`Ranking`: the study; :func:`search_candidates`.
-   :data:`LEVELS_RANK`, :data:`TOP_OVERLAP`, :data:`HALVES_RANK`.

Units: rates and scores fractions; temperatures K; times s.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from functools import partial

import numpy as np

from ...errors import SkinrenderError
from ...evaluation.locus import skin_locus
from ...execution import dask_name
from ...model.camera import camera
from ...rendering.face import planckian_temperature
from ...rendering.face.detection import detection_rates
from ...rendering.face.effects import PHYSICS_REGISTRY, Level
from ...rendering.face.limits import REPLICATES
from ...rendering.face.scene import load_face_scene
from ...rendering.face.shift import skin_set_name
from ...rendering.bands import BANDS_DEFAULT, parse_bands, projection
from ...rendering.face.request import face_request
from ...rendering.face.validation import render_replicates, replicated_of
from ...rendering.settings import seed_at
from ...rendering.variants import choose_variant
from ...spectra import GRID_DEFAULT
from .workers import RenderRun, run_renders

__all__ = ["LEVELS_RANK", "TOP_OVERLAP", "HALVES_RANK", "Ranking", "rank", "search_candidates", "candidate_renders",
           "triplet_camera", "rank_tasks"]

LEVELS_RANK = ("direct", "interreflection", "sheen", "mixed", "noise")
"""The levels of a ranking unless named: the base and the fast effects (subsurface renders far slower)."""

TOP_OVERLAP = 3
"""``k`` of ``top_k_overlap``: the share of Eq. 4's best ``k`` cameras that are among the rendered best ``k``."""

HALVES_RANK = 24
"""Half-samples of the replicates behind τ's interval and ``same_best``."""

Z_95 = 1.959963984540054
"""The two-sided 95 % normal quantile."""


def triplet_camera(sensor: float, peaks, slope: float = 2.0) -> str:
    """
    The camera spec of a Stage 3 triplet: ``impulse@…`` for sensor 1, ``gbell:N@…`` (``gbell:N,b=B@…`` for a
    slope other than 2).

    >>> triplet_camera(9, [450.0, 540.0, 610.0]), triplet_camera(1, [450, 540, 610])
    ('gbell:9@450,540,610', 'impulse@450,540,610')
    """
    where = ",".join(f"{float(p):g}" for p in peaks)
    if float(sensor) == 1:
        return f"impulse@{where}"
    return f"gbell:{float(sensor):g}{'' if float(slope) == 2 else f',b={float(slope):g}'}@{where}"


def search_candidates(top: int, sensor: float, positions="400:700:10", slope: float = 2.0, workers=None, dask=None,
                      skin="skin", munsell="munsell", progress=None) -> list[str]:
    """
    The ``top`` triplets of the Stage 3 search (:func:`skinrender.design.search.search`) by its detection
    criterion, Eq. 4's: the smallest false-positive rate of the Munsell set inside the skin locus, averaged over
    the calibrations (``search --detection``; a triplet without a rate last), as camera specs
    (:func:`triplet_camera`). ``top`` beyond the number of triplets is refused. (The paper's gamut ratio favours
    triplets crowded in the blue, whose loci take every prop on the face: no detector.)
    """
    from ...datasets import reflectances
    from ...design.bank import positions_grid
    from ...design.search import search

    grid_positions = positions_grid(positions)
    count = len(grid_positions) * (len(grid_positions) - 1) * (len(grid_positions) - 2) // 6
    if not 1 <= int(top) <= count:
        raise SkinrenderError(f"top: {top} is not between 1 and the {count} triplets of positions {positions!r}")
    result = search(sensor, reflectances(skin).on(GRID_DEFAULT), reflectances(munsell).on(GRID_DEFAULT), positions,
                    slope=slope, workers=workers, dask=dask, progress=progress, label=f"sensor {sensor:g}",
                    detection=True)
    fpr = result.fpr_table[:, -1]
    order = np.lexsort((np.arange(len(fpr)), np.where(np.isfinite(fpr), fpr, np.inf)))
    return [triplet_camera(sensor, result.triplets[t], slope) for t in order[:int(top)]]


def candidate_renders(cameras, scene, prevailing: float, calibration: float, skin, level: Level, spp: int, seeds,
                      size, variant=None, grid=GRID_DEFAULT, sensor=None, bands=BANDS_DEFAULT) -> list:
    """
    Every candidate's replicates of one scene, the one place a ranking gets its images: a
    :class:`~skinrender.rendering.face.validation.Replicated` per camera of ``cameras`` (their order), each
    replicate at ``spp`` per seed of ``seeds``: one spectral render per seed with ``bands`` as its film, seen
    through every camera (:mod:`~skinrender.rendering.face.spectral_face`: the cameras share its light paths), or,
    ``bands=None``, one render per camera and seed. ``sensor``: the sensor's keywords (``imager``,
    ``illuminance``) for a level with ``noise``; dropped at the others.
    """
    options = PHYSICS_REGISTRY.options_for(level, dict(sensor or {}))
    if bands is None:
        return [render_replicates(cam, scene, prevailing, calibration, skin, level, spp, seeds, size, grid=grid,
                                  variant=variant, **options) for cam in cameras]
    from ...rendering.face.spectral_face import render_face_spectral_request

    request = face_request(scene, None, prevailing, None, skin=skin, physics=level, size=size, spp=spp,
                           seed=seeds[0], variant=variant, grid=grid, bands=parse_bands(bands), **options)
    images = [render_face_spectral_request(request, seed) for seed in seeds]
    return [replicated_of([image.through(cam, calibration) for image in images], request) for cam in cameras]


def rank_tasks(lights, skins, levels) -> list[tuple]:
    """
    One task per scene and level: ``(prevailing K, calibration K, skin, level)``, levels outermost.

    >>> rank_tasks([(2856.0, 5900.0)], ["a", "b"], ["direct"])
    [(2856.0, 5900.0, 'a', 'direct'), (2856.0, 5900.0, 'b', 'direct')]
    """
    return [(p, c, skin, level) for level in levels for p, c in lights for skin in skins]


@dataclass(frozen=True)
class _Settings:
    cameras: tuple
    scene: object
    size: int
    spp: int
    seed: int
    variant: str
    skin_set: object
    imager: str | None
    illuminance: float | None
    halves: int
    bands: object = BANDS_DEFAULT


def _scene_task(task: tuple, settings: _Settings) -> dict:
    """One scene at one level through every candidate: per camera its J as Eq. 4 gives it, separated, and on each
    half-sample."""
    p, c, skin, level = task
    start = time.perf_counter()
    seeds = [seed_at(settings.seed, k) for k in range(REPLICATES)]
    each = -(-settings.spp // REPLICATES)
    renders = candidate_renders(settings.cameras, settings.scene, p, c, skin, level, each, seeds, settings.size,
                                settings.variant, sensor={"imager": settings.imager, "illuminance": settings.illuminance},
                                bands=settings.bands)
    scores = []
    for cam, replicated in zip(settings.cameras, renders):
        locus = skin_locus(cam, settings.skin_set, calibration=c)
        rates = detection_rates(replicated, locus, settings.halves, settings.seed)
        youden = lambda pair: None if None in pair else pair[0] - pair[1]  # noqa: E731
        scores.append({"eq4": youden(rates.eq4), "rendered": youden(rates.separated),
                       "halves": [youden(sample) for sample in rates.samples], "factor": rates.variance_factor,
                       "spp": int(sum(r.spp for r in replicated.renders))})
    return {"task": task, "scores": scores, "seconds": time.perf_counter() - start}


def _ranks(values: np.ndarray) -> list[int]:
    """1 for the highest score; ties share the better rank."""
    return [int(1 + np.sum(values > v + 1e-12)) for v in values]


def _kendall(a: np.ndarray, b: np.ndarray) -> float | None:
    from scipy.stats import kendalltau

    if len(a) < 2 or np.ptp(a) == 0 or np.ptp(b) == 0:
        return None
    tau = kendalltau(a, b).statistic
    return None if not np.isfinite(tau) else float(tau)


def _level_from_scenes(level: str, names: list[str], mine: list[dict]) -> dict:
    """One level's summary from its scenes' scores (each a :func:`_scene_task`'s result): every camera averaged
    over the scenes scored for every camera (``null`` scores with the reason where there are none)."""
    eq4 = np.array([[np.nan if s["eq4"] is None else s["eq4"] for s in d["scores"]] for d in mine])
    rendered = np.array([[np.nan if s["rendered"] is None else s["rendered"] for s in d["scores"]] for d in mine])
    halves = np.array([[[np.nan if v is None else v for v in s["halves"]] for s in d["scores"]] for d in mine])
    undefined = {}
    complete = ~(np.isnan(eq4).any(axis=1) | np.isnan(rendered).any(axis=1) | np.isnan(halves).any(axis=(1, 2)))
    if not complete.all():  # every camera averaged over the same scenes, or the ranks compare unlike samples
        undefined["scenes"] = (f"{int((~complete).sum())} of {len(complete)} scenes had no scored skin or prop "
                               "pixel for some camera: left out for every camera")
    if not complete.any():
        return _level_unscored(level, names, undefined)
    return _level_summary(level, names, eq4[complete].mean(axis=0), rendered[complete].mean(axis=0),
                          halves[complete].mean(axis=0).T, mine[0]["scores"][0]["factor"], undefined)


def _level_unscored(level: str, names: list[str], undefined: dict) -> dict:
    """A level where no scene was scored for every camera: its scores, ranks and answers ``null``, with the reason."""
    candidates = [{"camera": name, "score_eq4": None, "score_rendered": None, "score_bound": None, "rank_eq4": None,
                   "rank_rendered": None} for name in names]
    reason = "no scene had scored skin and prop pixels for every camera"
    return {"level": level, "candidates": candidates, "undefined": {**undefined, "level": reason},
            "kendall_tau": None, "kendall_tau_interval": None, "top_k": min(TOP_OVERLAP, len(names)),
            "top_k_overlap": None, "same_best_share": None, "best_eq4": [], "best_rendered": None, "same_best": None}


def _level_summary(level: str, names: list[str], eq4: np.ndarray, rendered: np.ndarray, halves: np.ndarray,
                   factor: float, undefined: dict) -> dict:
    """One level's candidates, τ and its interval, the top-k overlap and same_best."""
    se = np.sqrt(factor * np.var(halves, axis=0, ddof=1))
    # The half-samples' spread about the whole sample's scores (the delete-d jackknife's resampling): a half
    # keeps half the replicates, so its noise separation finds less physics and its scores lean towards Eq. 4's;
    # taken as they are, they would call Eq. 4's best the rendered best where the whole sample ranks it low.
    halves = rendered + np.sqrt(factor) * (halves - halves.mean(axis=0))
    rank_eq4, rank_rendered = _ranks(eq4), _ranks(rendered)
    candidates = [{"camera": name, "score_eq4": float(e), "score_rendered": float(r),
                   "score_bound": float(abs(r - e) + Z_95 * s), "rank_eq4": a, "rank_rendered": b}
                  for name, e, r, s, a, b in zip(names, eq4, rendered, se, rank_eq4, rank_rendered)]
    out = {"level": level, "candidates": candidates, "undefined": dict(undefined)}
    tau = _kendall(eq4, rendered)
    out["kendall_tau"] = tau
    if tau is None:
        out["kendall_tau_interval"] = None
        out["undefined"]["kendall_tau"] = ("the scores do not order the cameras: every candidate scores the same "
                                           "(Eq. 4's or the rendered)" if len(names) > 1 else "one candidate")
    else:
        taus = np.array([t for t in (_kendall(eq4, h) for h in halves) if t is not None])
        if len(taus) < 2:
            out["kendall_tau_interval"] = None
            out["undefined"]["kendall_tau_interval"] = "the half-samples' scores do not order the cameras"
        else:
            spread = Z_95 * np.std(taus, ddof=1)  # the halves carry the factor already (above)
            out["kendall_tau_interval"] = [max(-1.0, tau - spread), min(1.0, tau + spread)]
    k = min(TOP_OVERLAP, len(names))
    top_eq4 = set(np.argsort(-eq4, kind="stable")[:k].tolist())
    top_rendered = set(np.argsort(-rendered, kind="stable")[:k].tolist())
    out.update({"top_k": k, "top_k_overlap": len(top_eq4 & top_rendered) / k})
    best = set(np.flatnonzero(eq4 >= eq4.max() - 1e-12).tolist())
    share = float(np.mean([int(np.argmax(h)) in best for h in halves]))
    out["same_best_share"] = share
    out["best_eq4"] = [names[i] for i in sorted(best)]
    out["best_rendered"] = names[int(np.argmax(rendered))]
    if share >= 0.95:
        out["same_best"] = True
    elif share <= 0.05:
        out["same_best"] = False
    else:
        out["same_best"] = None
        out["undefined"]["same_best"] = (f"Eq. 4's best camera is the rendered best in {share:.0%} of the half-samples: "
                                         "the samples cannot tell (raise --spp or --size)")
    return out


@dataclass(frozen=True)
class Ranking(RenderRun):
    """
    The ranking: ``levels`` (per level ``level``, ``candidates`` ``[{camera, score_eq4, score_rendered, score_bound,
    rank_eq4, rank_rendered}]``, ``kendall_tau``, ``kendall_tau_interval``, ``top_k``, ``top_k_overlap``,
    ``same_best``, ``same_best_share``, ``best_eq4``, ``best_rendered``, ``undefined``), the candidates, lights and
    skins, and how its renders ran (:class:`~skinrender.studies.face.workers.RenderRun`'s keyword fields).
    """

    cameras: list
    lights: list
    skins: list
    skin_set: str
    levels: list = field(default_factory=list)
    candidates_from: dict | None = None

    def document(self) -> dict:
        """The JSON document."""
        return {"cameras": self.cameras, "candidates_from": self.candidates_from, "lights_K": self.lights,
                "skins": self.skins, "skin_set": self.skin_set, "score": "Youden's J = TPR - FPR, mean over the scenes",
                "size": self.size, "spp": self.spp, "replicates": REPLICATES, "seed": self.seed,
                "variant": self.variant, "workers": self.workers, "dask": self.dask, "elapsed_s": self.elapsed_s,
                "levels": self.levels}

    def figure(self, path):
        """Rank against rank per level (:func:`skinrender.studies.face.ranking_figure.figure_rank`) to a PNG."""
        from .ranking_figure import figure_rank

        return figure_rank(self.levels, f"Would Eq. 4 still choose the same camera? {len(self.cameras)} candidates, "
                           f"{len(self.lights)} light pairs × {len(self.skins)} skins, {self.size} px, {self.spp} spp, "
                           f"the {self.skin_set} locus", path)


def rank(cameras, lights, skins, levels=LEVELS_RANK, size: int = 64, spp: int = 16, seed: int = 0, scene="face",
         skin_set="skin", variant: str | None = None, imager: str | None = None, illuminance: float | None = None,
         workers: int | None = None, dask=None, progress=None, halves: int = HALVES_RANK,
         candidates_from: dict | None = None, bands=BANDS_DEFAULT) -> Ranking:
    """
    Rank ``cameras`` by Eq. 4 and by the rendered face at each level (see the module).

    Parameters
    ----------
    cameras
        Cameras or specs, two or more.
    lights
        (prevailing, calibration) pairs, K.
    skins
        Skin specs (the face's).
    levels
        Levels of physics (:data:`LEVELS_RANK` unless named).
    size, spp, seed
        Image side (pixels); samples per pixel of a scene in all, over
        :data:`~skinrender.rendering.face.limits.REPLICATES` replicates (seeds ``seed …``).
    skin_set
        The reflectance set of every camera's locus.
    imager, illuminance
        The ``noise`` level's sensor and the key light's lux.
    workers, dask, progress
        As :func:`skinrender.studies.face.sweep.face_sweep` (one task per scene and level).
    halves
        Half-samples of the replicates for τ's interval and ``same_best``.
    candidates_from
        How the candidates were chosen (reported).
    bands
        The film of the one spectral render per scene, level and replicate every candidate is seen through
        (``START:END:STEP`` nm, default 400:700:5); ``None``: one render per candidate.

    Returns
    -------
    :class:`Ranking`
    """
    cams = [camera(c) for c in cameras]
    if len(cams) < 2:
        raise SkinrenderError(f"cameras: a ranking needs two or more candidates, got {len(cams)}")
    pairs = [(planckian_temperature(p, "prevailing"), planckian_temperature(c, "calibration")) for p, c in lights]
    skins = [str(s).strip() for s in skins]
    levels = [PHYSICS_REGISTRY.level(level) for level in levels]  # each spec parsed once, here
    for name, values in (("lights", pairs), ("skins", skins), ("levels", levels)):
        if not values:
            raise SkinrenderError(f"{name}: name at least one")
    from ...execution import check_workers

    workers = check_workers(workers, "workers")
    if bands is not None:
        bands = parse_bands(bands)
        for cam in cams:  # every camera checked against the bands before any render
            projection(cam, bands, GRID_DEFAULT)
    settings = _Settings(tuple(cams), load_face_scene(scene), int(size), int(spp), int(seed), choose_variant(variant),
                         skin_set, imager, illuminance, int(halves), bands)
    start = time.perf_counter()
    done = run_renders(partial(_scene_task, settings=settings), rank_tasks(pairs, skins, levels), settings.variant,
                       int(workers), dask, progress, "rank")
    names = [cam.name for cam in cams]
    summaries = [_level_from_scenes(level.name, names, [d for d in done if d["task"][3].name == level.name])
                 for level in levels]
    spp_used = done[0]["scores"][0]["spp"]
    return Ranking(names, [list(pair) for pair in pairs], skins, skin_set_name(skin_set), summaries, candidates_from,
                   size=int(size), spp=spp_used, seed=int(seed), variant=settings.variant,
                   workers=1 if dask is not None else int(workers), elapsed_s=time.perf_counter() - start,
                   dask=dask_name(dask))
