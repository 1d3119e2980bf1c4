"""
The physics ladder
==================

The face rendered at each level of physics
(:data:`skinrender.rendering.face.PHYSICS`), and what each level does to skin
detection: the skin pixels' NCC against Eq. 4's, and the true- and
false-positive rates of the camera's analytic skin locus on the rendered
pixels.

-   :func:`ladder`, :class:`Ladder`: the study; :meth:`Ladder.figure` draws it
    (renders, label masks, detected masks, NCC over the locus).
-   :data:`LEVELS_DEFAULT`: ``direct``, each effect alone, then all together.

Scoring: a pixel is scored when its brightest channel reaches
:data:`SCORED_MIN_OUTPUT` (too dark a pixel has no chromaticity worth the
name: the paper's Table 1 keeps 10–245); ``tpr`` is the share of scored skin
pixels (label 1) whose NCC (r, g) lies in the locus
(:func:`skinrender.evaluation.locus.skin_locus` of the ``skin`` set, one white
balancing at the calibration light), ``fpr`` that of the scored prop pixels;
the background is left out. Each is ``None`` when no pixel of its kind is
scored, with its reason in the level's ``undefined`` (``{key: reason}``).

Units: temperatures K, times s, NCC and rates fractions.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import SkinrenderError
from ..evaluation.detection import SCORED_MIN_OUTPUT
from ..evaluation.locus import skin_locus
from ..hints import NDArrayFloat
from ..model.camera import camera
from ..model.chromaticity import ncc
from ..rendering.face import planckian_temperature, render_face
from ..rendering.face.effects import LEVELS_LADDER, parse_physics, physics_level
from ..rendering.face.labels import LABEL_SKIN
from ..rendering.face.scene import load_face_scene, skin_reflectance_of
from ..rendering.validation import analytic_reference
from ..spectra import GRID_DEFAULT, WavelengthGrid
from ..workload import duration_text

__all__ = ["LEVELS_DEFAULT", "SCORED_MIN_OUTPUT", "Ladder", "ladder", "score_rendering", "score_frame"]

LEVELS_DEFAULT = LEVELS_LADDER
"""The levels of :func:`ladder`: the analytic model's world, each effect alone, then all of them (read from the
registry of effects, :data:`skinrender.rendering.face.effects.LEVELS_LADDER`)."""


@dataclass(frozen=True)
class Ladder:
    """
    The ladder's result.

    Attributes
    ----------
    levels
        One dict per level: ``name``, ``seconds``, ``spp``,
        ``skin_ncc_mean`` and ``skin_ncc_std`` (``[r, g, b]`` over the scored
        skin pixels), ``tpr``, ``fpr``, ``skin_pixels`` and ``prop_pixels``
        (scored), ``undefined`` (``{key: reason}`` for each ``None``),
        ``variant``, and ``imager``/``exposure_s`` with ``noise``.
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

    def document(self) -> dict:
        """The JSON document (``levels`` and the settings)."""
        return {"camera": self.camera, "scene": self.scene, "skin": self.skin,
                "prevailing_K": self.prevailing, "calibration_K": self.calibration, "size": list(self.size),
                "skin_ncc_analytic": self.skin_ncc_analytic, "locus_area": self.locus_area,
                "levels": self.levels}

    def figure(self, path) -> Path:
        """
        Draw the ladder to a PNG (:func:`skinrender.studies.figures.figure_ladder`): per level the render,
        the label mask, the detected mask and the scored skin and prop pixels' NCC (r, g) over the locus.

        Returns
        -------
        Path
            ``path``.
        """
        from .figures import figure_ladder

        rows = []
        for row, frame in zip(self.levels, self.frames):
            labels, scored = frame["labels"], frame["scored"]
            rows.append({**{k: row[k] for k in ("name", "tpr", "fpr", "seconds", "spp")},
                         "image": frame["image"], "labels": labels, "detected": frame["detected"],
                         "skin_rg": frame["ncc"][scored & (labels == LABEL_SKIN), :2],
                         "prop_rg": frame["ncc"][scored & (labels > LABEL_SKIN), :2]})
        title = (f"The face ({self.skin}) through {self.camera}, {self.prevailing:g} K balanced to "
                 f"{self.calibration:g} K, {self.size[0]}×{self.size[1]} px\n(renders: the balanced camera RGB shown as "
                 "sRGB; TPR, FPR and NCC over scored pixels, brightest channel ≥ "
                 f"{SCORED_MIN_OUTPUT:g})")
        return figure_ladder(rows, self.locus_polygon, np.asarray(self.skin_ncc_analytic), title, path,
                             self.label_names)


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


def ladder(
    camera_,
    prevailing,
    calibration,
    skin: str | None = None,
    levels: Sequence[str] = LEVELS_DEFAULT,
    spp: int = 64,
    seed: int = 0,
    size: int | None = 128,
    scene="face",
    variant: str | None = None,
    grid: WavelengthGrid = GRID_DEFAULT,
    imager: str | None = None,
    illuminance: float | None = None,
    progress: Callable[[str], None] | None = None,
) -> Ladder:
    """
    Render the face at each level of physics and score skin detection there.

    Parameters
    ----------
    camera_
        Camera or spec.
    prevailing, calibration
        The key light's temperature and the white balance's (kelvin, ``A``, ``H``).
    skin
        The skin spec (``SET:SAMPLE``, ``SET:#N``, ``skin-model:…``); ``None``: the scene's.
    levels
        Physics levels (:data:`skinrender.rendering.face.PHYSICS`, effects joined by ``+``).
    spp, seed, variant, grid
        As :func:`skinrender.rendering.face.render_face`; every level uses the same seed.
    size
        Image side, pixels (``None``: the scene's).
    scene
        A face scene name or path.
    imager, illuminance
        The image sensor of ``noise`` (default :data:`skinrender.rendering.face.IMAGER_DEFAULT`) and the
        key light's illuminance, lx (``None``: the scene's; only ``noise`` sees it).
    progress
        Called with a line before each level (e.g. to print it on stderr).

    Returns
    -------
    :class:`Ladder`
    """

    cam = camera(camera_)
    p, c = planckian_temperature(prevailing, "prevailing"), planckian_temperature(calibration, "calibration")
    face = load_face_scene(scene)
    skin = face.skin if skin is None else str(skin).strip()
    rho = skin_reflectance_of(skin, grid, "skin")
    levels = list(levels)
    if not levels:
        raise SkinrenderError("levels: name at least one level of physics")
    for level in levels:
        parse_physics(level)
    side = (face.camera.width, face.camera.height) if size is None else (size, size)
    seconds = sum(physics_level(level).seconds(side[0] * side[1] * spp) for level in levels)
    if progress is not None and seconds > 60:  # subsurface: minutes (the command line refuses beyond --max-minutes)
        progress(f"the {len(levels)} levels should take about {duration_text(seconds)} on one core")
    locus = skin_locus(cam, "skin", calibration=c, grid=grid)
    analytic = ncc(analytic_reference(cam, rho[None], p, c, grid=grid))[0]
    rows, frames, shape = [], [], None
    for level in levels:
        if progress is not None:
            progress(f"rendering the face: {level} …")
        start = time.perf_counter()
        result = render_face(cam, face, p, c, skin, level, spp, seed, size, variant=variant, grid=grid,
                             imager=imager, illuminance=illuminance)
        scores, frame = score_frame(result, locus)
        row = {"name": result.physics if level != "direct" else "direct", "seconds": time.perf_counter() - start,
               "spp": result.spp, **scores, "variant": result.variant}
        row.update({k: v for k, v in result.info.items() if k in ("imager", "illuminance_lux", "exposure_s")})
        rows.append(row)
        frames.append(frame)
        shape = (result.scene.camera.width, result.scene.camera.height)
    return Ladder(cam.name, face.name, skin, p, c, shape, analytic.tolist(), float(locus.area), rows, frames,
                  np.asarray(locus.polygon), dict(result.label_names))
