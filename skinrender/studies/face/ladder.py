"""
The physics ladder
==================

The face rendered at each level of physics
(:data:`skinrender.rendering.face.PHYSICS`), and what each level does to skin
detection: the true- and false-positive rates of the camera's analytic skin
locus on the rendered pixels, and whether Eq. 4 predicts them — each level's
``detection`` verdict (:mod:`skinrender.rendering.face.detection`: the rates
with the renderer's noise separated against Eq. 4's, within
``detection_tolerance``), which is the ladder's verdict — and, as diagnostics,
the skin pixels' NCC against Eq. 4's with the detection budget
(:mod:`skinrender.rendering.face.shift`: ``eq4_shift``, ``budget``,
``within_budget``) and how far each level moves the rates from ``direct``'s.

-   :func:`ladder`, :class:`Ladder`: the study; :meth:`Ladder.figure` draws it
    (renders, label masks, detected masks, NCC over the locus with the budget).
-   :data:`LEVELS_DEFAULT`: ``direct``, each effect alone, then all together.
-   :data:`REPLICATES_LADDER`: each level is rendered as this many replicates
    (independent seeds) of ``⌈spp / K⌉`` spp: their spread is ``eq4_shift``'s
    noise, and their mean (one frame of their mean radiance through a sensor)
    is what is scored, as one render at ``spp``.

Scoring: a pixel is scored when its brightest channel reaches
:data:`SCORED_MIN_OUTPUT` (too dark a pixel has no chromaticity worth the
name: the paper's Table 1 keeps 10–245); ``tpr`` is the share of scored skin
pixels (label 1) whose NCC (r, g) lies in the locus
(:func:`skinrender.evaluation.locus.skin_locus` of the ``skin`` set, one white
balancing at the calibration light), ``fpr`` that of the scored prop pixels;
the background is left out. Each is ``None`` when no pixel of its kind is
scored, with its reason in the level's ``undefined`` (``{key: reason}``). The
locus is that of the ``skin_set`` (default ``skin``, the Vrhel skins; each row
says which in ``skin_set``).

Units: temperatures K, times s, NCC and rates fractions.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ...errors import SkinrenderError
from ...evaluation.budget import BUDGET_FRACTION
from ...evaluation.detection import SCORED_MIN_OUTPUT
from ...hints import NDArrayFloat
from ...model.camera import camera
from ...model.chromaticity import ncc
from ...rendering.face import planckian_temperature
from ...rendering.face.effects import LEVELS_LADDER, PHYSICS_REGISTRY, Level
from ...rendering.face.labels import LABEL_SKIN
from ...rendering.face.limits import REPLICATES
from ...rendering.face.scene import load_face_scene, skin_reflectance_of
from ...evaluation.detection_verdict import DETECTION_TOLERANCE, check_tolerance
from ...rendering.face.detection import face_detection
from ...rendering.face.shift import SKIN_SET_DEFAULT, face_budget, skin_set_name
from ...rendering.settings import seed_at
from ...rendering.face.request import face_request
from ...rendering.bands import BANDS_DEFAULT, parse_bands, projection
from ...rendering.face.validation import mean_rendering, render_replicates_request, replicated_of, shift_against
from ...rendering.validation import analytic_reference
from ...spectra import GRID_DEFAULT, WavelengthGrid
from ...workload import duration_text
from .detection_study import DetectionStudy

__all__ = ["LEVELS_DEFAULT", "REPLICATES_LADDER", "SCORED_MIN_OUTPUT", "Ladder", "ladder", "ladders",
           "score_rendering", "score_frame"]

LEVELS_DEFAULT = LEVELS_LADDER
"""The levels of :func:`ladder`: the analytic model's world, each effect alone, then all of them (read from the
registry of effects, :data:`skinrender.rendering.face.effects.LEVELS_LADDER`)."""

REPLICATES_LADDER = REPLICATES
"""Replicates per level (:data:`~skinrender.rendering.face.limits.REPLICATES`, as ``validate face``)."""


@dataclass(frozen=True)
class Ladder(DetectionStudy):
    """
    The ladder's result.

    Attributes
    ----------
    levels
        One dict per level: ``name``, ``seconds``, ``spp``,
        ``skin_ncc_mean`` and ``skin_ncc_std`` (``[r, g, b]`` over the scored
        skin pixels), ``tpr``, ``fpr``, ``skin_pixels`` and ``prop_pixels``
        (scored), ``eq4_shift`` (the skin's mean NCC from Eq. 4's,
        Euclidean), ``eq4_shift_bound`` (its 95 % upper bound),
        ``eq4_verdict``, ``budget`` (the detection budget, NCC),
        ``within_budget`` (true, false or null), ``tpr_change`` and
        ``fpr_change`` (from ``direct``'s, when ``direct`` is a level),
        ``budget_tpr_change`` and ``budget_fpr_change`` (what a shift of the
        budget towards the locus's boundary does to this level's pixels),
        ``replicates``, ``spp_per_replicate``, ``undefined`` (``{key:
        reason}`` for each ``None``), ``variant``, and
        ``imager``/``exposure_s`` with ``noise``.
    budget
        The detection budget (:meth:`~skinrender.evaluation.budget.DetectionBudget.document`).
    skin_ncc_analytic
        Eq. 4's NCC of the skin (prevailing = the key light, white balanced to
        the calibration), ``[r, g, b]``.
    frames
        One dict of arrays per level (not in :meth:`document`): ``image``
        ``(h, w, 3)`` output units, ``labels`` ``(h, w)`` ints, ``scored``
        and ``detected`` ``(h, w)`` bools (detected: scored and inside the
        locus), ``ncc`` ``(h, w, 3)``.
    locus_polygon
        The analytic skin locus, ``(K, 2)`` NCC (r, g).
    label_names
        ``{name: label}`` of the face scene.
    """

    camera: str
    scene: str
    skin: str
    prevailing: float
    calibration: float
    size: tuple[int, int]
    skin_ncc_analytic: list
    locus_area: float
    levels: list = field(default_factory=list)
    frames: list = field(default_factory=list, repr=False, compare=False)
    locus_polygon: NDArrayFloat | None = field(default=None, repr=False, compare=False)
    label_names: dict = field(default_factory=dict)
    budget: dict = field(default_factory=dict)

    VERDICT_NAME = "ladder"

    def detection_rows(self) -> list[tuple[str, dict]]:
        """Each level's name and detection document (the ladder's :attr:`finding`)."""
        return [(row["name"], row["detection"]) for row in self.levels]

    def document(self) -> dict:
        """The JSON document (``levels``, the budget, the verdict and the settings)."""
        return {"camera": self.camera, "scene": self.scene, "skin": self.skin, "skin_set": self.skin_set,
                "prevailing_K": self.prevailing, "calibration_K": self.calibration, "size": list(self.size),
                "skin_ncc_analytic": self.skin_ncc_analytic, "locus_area": self.locus_area, "budget": self.budget,
                "detection_tolerance": self.detection_tolerance, "levels": self.levels, "finding": self.finding,
                **self.verdict.summary()}

    def figure(self, path) -> Path:
        """
        Draw the ladder to a PNG (:func:`skinrender.studies.figures.figure_ladder`): per level the render,
        the label mask, the detected mask and the scored skin and prop pixels' NCC (r, g) over the locus.

        Returns
        -------
        Path
            ``path``.
        """
        from ..figures import figure_ladder

        rows = []
        for row, frame in zip(self.levels, self.frames):
            labels, scored = frame["labels"], frame["scored"]
            rows.append({**{k: row.get(k) for k in ("name", "tpr", "fpr", "seconds", "spp", "eq4_shift", "budget",
                                                   "within_budget", "tpr_change", "fpr_change", "eq4_ncc_mean")},
                         "image": frame["image"], "labels": labels, "detected": frame["detected"],
                         "skin_rg": frame["ncc"][scored & (labels == LABEL_SKIN), :2],
                         "prop_rg": frame["ncc"][scored & (labels > LABEL_SKIN), :2]})
        title = (f"The face ({self.skin}) through {self.camera}, {self.prevailing:g} K balanced to "
                 f"{self.calibration:g} K, {self.size[0]}×{self.size[1]} px\n(renders: the balanced camera RGB shown as "
                 "sRGB; TPR, FPR and NCC over scored pixels, brightest channel ≥ "
                 f"{SCORED_MIN_OUTPUT:g})")
        return figure_ladder(rows, self.locus_polygon, np.asarray(self.skin_ncc_analytic), title, path,
                             self.label_names, self.budget.get("budget"))


def _rate(hits: np.ndarray) -> float | None:
    return float(hits.mean()) if hits.size else None


def score_frame(result, locus, clip_negative: bool = False) -> tuple[dict, dict]:
    """
    :func:`score_rendering`'s scores, and the frame the figures draw: ``image``, ``labels``, ``scored``,
    ``inside`` (every pixel's NCC in the locus), ``detected`` (scored and inside) and ``ncc``.

    ``clip_negative``: the NCC of the image with negative channels (noise around a dark level) set to 0,
    as ``skinrender detect`` classifies a face; the ladder keeps them.
    """
    image = result.image.astype(np.float64)
    scored = image.max(axis=-1) >= SCORED_MIN_OUTPUT
    chromaticity = ncc(np.maximum(image, 0.0) if clip_negative else image)
    inside = locus.contains(chromaticity[..., :2])
    skin_pixels = scored & (result.labels == LABEL_SKIN)
    prop_pixels = scored & (result.labels > LABEL_SKIN)
    values = chromaticity[skin_pixels]
    undefined = {}
    if not skin_pixels.any():
        reason = f"no scored skin pixel (brightest channel ≥ {SCORED_MIN_OUTPUT:g})"
        undefined.update({key: reason for key in ("skin_ncc_mean", "skin_ncc_std", "tpr")})
    if not prop_pixels.any():
        undefined["fpr"] = f"no scored prop pixel (brightest channel ≥ {SCORED_MIN_OUTPUT:g})"
    scores = {
        "skin_ncc_mean": values.mean(axis=0).tolist() if values.size else None,
        "skin_ncc_std": values.std(axis=0).tolist() if values.size else None,
        "tpr": _rate(inside[skin_pixels]),
        "fpr": _rate(inside[prop_pixels]),
        "skin_pixels": int(skin_pixels.sum()),
        "prop_pixels": int(prop_pixels.sum()),
        "undefined": undefined,
    }
    frame = {"image": result.image, "labels": result.labels, "scored": scored, "inside": inside,
             "detected": scored & inside, "ncc": chromaticity}
    return scores, frame


def score_rendering(result, locus) -> dict:
    """
    Score one face render as the ladder scores a level.

    A pixel is scored when its brightest channel reaches :data:`SCORED_MIN_OUTPUT`; ``tpr`` is the share of
    scored skin pixels whose NCC (r, g) lies in ``locus``, ``fpr`` that of the scored prop pixels (the
    background is left out).

    Parameters
    ----------
    result
        A :class:`~skinrender.rendering.face.FaceRendering`.
    locus
        A :class:`~skinrender.evaluation.locus.SkinLocus` (its ``contains``).

    Returns
    -------
    dict
        ``skin_ncc_mean``, ``skin_ncc_std`` (``[r, g, b]`` or ``None`` without a scored skin pixel), ``tpr``,
        ``fpr`` (fractions or ``None``), ``skin_pixels``, ``prop_pixels`` (scored counts), ``undefined``
        (``{key: reason}`` for each ``None``, e.g. ``{"tpr": "no scored skin pixel (brightest channel ≥ 10)"}``).
    """
    return score_frame(result, locus)[0]


def _level_row(level: Level, replicated, mean, scores: dict, shift, rates: dict | None) -> dict:
    """One level's row: its scores, ``eq4_shift`` against the budget, and what the budget does to its pixels."""
    undefined = dict(scores.pop("undefined"))
    within = shift.details.get("within_budget")
    if within is None:
        undefined["within_budget"] = f"{shift.outcome.replace('_', ' ')}: {shift.reason}"
    if shift.statistic is None:
        undefined["eq4_shift"] = shift.reason
    if rates is None:
        undefined.update({key: "no detection budget" for key in ("budget_tpr_change", "budget_fpr_change")})
    row = {"name": level.name, "seconds": replicated.seconds,
           "spp": mean.spp, "replicates": len(replicated.renders), "spp_per_replicate": replicated.first.spp,
           **scores, "eq4_shift": shift.statistic, "eq4_shift_bound": shift.bound, "eq4_verdict": shift.outcome,
           "eq4_ncc_mean": shift.details.get("ncc_mean"), "budget": shift.tolerance, "within_budget": within,
           "budget_tpr_change": None if rates is None else rates["tpr_change"],
           "budget_fpr_change": None if rates is None else rates["fpr_change"], "undefined": undefined,
           "variant": mean.variant}
    row.update({k: v for k, v in mean.info.items() if k in ("imager", "illuminance_lux", "exposure_s")})
    return row


def _changes(rows: list[dict]) -> None:
    """Each row's ``tpr_change`` and ``fpr_change`` from the ``direct`` row's (``None`` with a reason without one)."""
    base = next((row for row in rows if row["name"] == PHYSICS_REGISTRY.base.name), None)
    for row in rows:
        for key in ("tpr", "fpr"):
            if base is None or base[key] is None or row[key] is None:
                row[f"{key}_change"] = None
                row["undefined"][f"{key}_change"] = ("no direct level to compare with" if base is None else
                                                     f"no {key.upper()} at this level or at direct")
            else:
                row[f"{key}_change"] = row[key] - base[key]


def ladder(
    camera_,
    prevailing,
    calibration,
    skin: str | None = None,
    levels: Sequence[str | Level] = LEVELS_DEFAULT,
    spp: int = 64,
    seed: int = 0,
    size: int | None = 128,
    scene="face",
    variant: str | None = None,
    grid: WavelengthGrid = GRID_DEFAULT,
    imager: str | None = None,
    illuminance: float | None = None,
    progress: Callable[[str], None] | None = None,
    replicates: int = REPLICATES_LADDER,
    budget_fraction: float = BUDGET_FRACTION,
    skin_set=SKIN_SET_DEFAULT,
    detection_tolerance: float = DETECTION_TOLERANCE,
    translate_mm=None,
) -> Ladder:
    """
    Render the face at each level of physics, score skin detection there and test Eq. 4's error.

    Parameters
    ----------
    camera_
        Camera or spec.
    prevailing, calibration
        The key light's temperature and the white balance's (kelvin, ``A``, ``H``).
    skin
        The skin spec (``SET:SAMPLE``, ``SET:#N``, ``skin-model:…``); ``None``: the scene's.
    levels
        Physics levels (:data:`skinrender.rendering.face.PHYSICS`, effects joined by ``+``), or
        :class:`~skinrender.rendering.face.effects.Level` objects.
    spp
        Samples per pixel of a level in all, split over ``replicates`` renders (each ``⌈spp / K⌉``).
    seed, variant, grid
        As :func:`skinrender.rendering.face.render_face`; the replicates' seeds are ``seed, seed + 1, …``, the
        same at every level.
    size
        Image side, pixels (``None``: the scene's).
    scene
        A face scene name or path.
    imager, illuminance
        The image sensor of ``noise`` (default :data:`skinrender.rendering.face.IMAGER_DEFAULT`) and the
        key light's illuminance, lx (``None``: the scene's): the options of the levels with ``noise`` (the others
        are rendered without them).
    progress
        Called with a line before each level (e.g. to print it on stderr).
    replicates
        Renders per level, ≥ 3.
    budget_fraction
        The share of the margin to the locus's boundary Eq. 4's error may use
        (:data:`~skinrender.evaluation.budget.BUDGET_FRACTION`).
    skin_set
        The reflectance set the skin locus is built from (a name such as ``skin`` or ``skin-tones``, a
        :class:`~skinrender.datasets.SpectralSet` or spectra on ``grid``).
    detection_tolerance
        How far Eq. 4 may be off in TPR and in FPR (fractions in (0, 1)): each level's ``detection`` verdict
        (:func:`~skinrender.rendering.face.detection.face_detection`).
    translate_mm
        ``(x, y, z)`` mm: the whole scene moved that far from the origin (``None``: where it is); a scene beyond
        float32's useful range at any of the levels is refused before anything renders
        (:func:`~skinrender.rendering.face.request.face_request`).

    Returns
    -------
    :class:`Ladder`
    """

    return ladders([camera_], prevailing, calibration, skin, levels, spp, seed, size, scene, variant, grid, imager,
                   illuminance, progress, replicates, budget_fraction, bands=None, skin_set=skin_set,
                   detection_tolerance=detection_tolerance, translate_mm=translate_mm)[0]


def ladders(cameras, prevailing, calibration, skin: str | None = None, levels: Sequence[str] = LEVELS_DEFAULT,
            spp: int = 64, seed: int = 0, size: int | None = 128, scene="face", variant: str | None = None,
            grid: WavelengthGrid = GRID_DEFAULT, imager: str | None = None, illuminance: float | None = None,
            progress: Callable[[str], None] | None = None, replicates: int = REPLICATES_LADDER,
            budget_fraction: float = BUDGET_FRACTION, bands=BANDS_DEFAULT, skin_set=SKIN_SET_DEFAULT,
            detection_tolerance: float = DETECTION_TOLERANCE, translate_mm=None) -> list:
    """
    :func:`ladder` for every camera of ``cameras`` (arguments as there): each level's replicates rendered once
    spectrally with ``bands`` (``START:END:STEP`` nm; one render per seed, seen through every camera:
    :mod:`~skinrender.rendering.face.spectral_face`), or, with ``bands=None``, once per camera. A spectral
    level's seconds are shared equally by the cameras (each adds its own projections). One :class:`Ladder` per
    camera, in their order. ``translate_mm``: as :func:`ladder`.
    """
    cams = [camera(c) for c in cameras]
    if not cams:
        raise SkinrenderError("cameras: name at least one camera")
    p, c = planckian_temperature(prevailing, "prevailing"), planckian_temperature(calibration, "calibration")
    face = load_face_scene(scene)
    skin = face.skin if skin is None else str(skin).strip()
    rho = skin_reflectance_of(skin, grid, "skin")
    levels = [PHYSICS_REGISTRY.level(level) for level in levels]  # each spec parsed once, here
    if not levels:
        raise SkinrenderError("levels: name at least one level of physics")
    if isinstance(replicates, bool) or not isinstance(replicates, int) or replicates < 3:
        raise SkinrenderError(f"replicates must be an integer ≥ 3, got {replicates!r}")
    if bands is not None:
        bands = parse_bands(bands)
        for cam in cams:
            projection(cam, bands, grid)
    each = max(1, -(-int(spp) // replicates))
    sensor = {"imager": imager, "illuminance": illuminance}
    ways = [None] if bands is not None else cams  # a spectral request per level, or one per camera and level
    requests = {(way and way.name, level.name): face_request(
        face, way, p, None if way is None else c, skin=skin, physics=level, size=size, spp=each, seed=seed,
        variant=variant, grid=grid, bands=None if way is not None else bands, translate_mm=translate_mm,
        **PHYSICS_REGISTRY.options_for(level, sensor)) for way in ways for level in levels}  # checked first
    seconds = sum(request.level.seconds(request.pixels * each * replicates) for request in requests.values())
    if progress is not None and seconds > 60:  # subsurface-volume: minutes (the command line refuses beyond --max-minutes)
        progress(f"the {len(levels)} levels should take about {duration_text(seconds)} on one core")
    detection_tolerance = check_tolerance(detection_tolerance, "detection_tolerance")
    set_name = skin_set_name(skin_set)
    studied = []
    for cam in cams:
        analytic = ncc(analytic_reference(cam, rho[None], p, c, grid=grid))[0]
        studied.append((cam, analytic, *face_budget(cam, analytic, c, budget_fraction, grid, skin_set, rho)))
    seeds = [seed_at(seed, k) for k in range(replicates)]
    rows, frames, verdicts = [[] for _ in cams], [[] for _ in cams], [[] for _ in cams]
    means = [None] * len(cams)
    for level in levels:
        if progress is not None:
            how = "" if bands is None else f", spectral ({bands.size} bands) for {len(cams)} cameras"
            progress(f"rendering the face: {level.name} ({replicates} × {each} spp{how}) …")
        for index, replicated in enumerate(_replicated(cams, requests, level, seeds, c, bands is not None)):
            _, _, budget, locus = studied[index]
            mean = means[index] = mean_rendering(replicated)
            scores, frame = score_frame(mean, locus)
            shift = shift_against(replicated, budget, locus, mean.image)
            rows[index].append(_level_row(level, replicated, mean, scores, shift, shift.details["budget_rates"]))
            detection, verdict = face_detection(replicated, locus, detection_tolerance, seed=seed, mean=mean)
            rows[index][-1].update({"skin_set": set_name, "detection": detection})
            frames[index].append(frame)
            verdicts[index].append(replace(verdict, name=f"detection at {rows[index][-1]['name']}"))
    out = []
    for (cam, analytic, budget, locus), mine, drawn, checked, mean in zip(studied, rows, frames, verdicts, means):
        _changes(mine)
        shape = (mean.scene.camera.width, mean.scene.camera.height)
        out.append(Ladder(cam.name, face.name, skin, p, c, shape, analytic.tolist(), float(locus.area), mine, drawn,
                          np.asarray(locus.polygon), dict(mean.label_names), budget.document(), verdicts=checked,
                          skin_set=set_name, detection_tolerance=detection_tolerance))
    return out


def _replicated(cams, requests: dict, level, seeds, calibration: float, spectral: bool) -> list:
    """One level's replicates for each camera: rendered per camera, or once per seed spectrally and seen through
    each camera (the renders' seconds shared equally)."""
    if not spectral:
        return [render_replicates_request(requests[(cam.name, level.name)], seeds) for cam in cams]
    from ...rendering.face.spectral_face import render_face_spectral_request

    request = requests[(None, level.name)]
    start = time.perf_counter()
    images = [render_face_spectral_request(request, seed) for seed in seeds]
    share = (time.perf_counter() - start) / len(cams)
    out = []
    for cam in cams:
        begin = time.perf_counter()
        renders = [image.through(cam, calibration) for image in images]
        out.append(replicated_of(renders, request, share + time.perf_counter() - begin))
    return out
