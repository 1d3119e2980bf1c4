"""
Skin loci from rendered faces
=============================

The analytic skin locus is the convex hull of a skin set's Eq. 4
chromaticities over the illuminant pairs. Here the same locus is built from
rendered faces — skin tones from light to very dark (the skin model's melanin),
each under the illuminant pairs, at a level of physics — and set beside the
analytic one: both areas, their overlap (intersection over union) and how far
the rendered locus's centre moves.

-   :func:`face_locus`: the comparison, a dict.
-   :func:`convex_intersection_area`: the area shared by two convex polygons.

Units: chromaticities NCC (r, g), unitless; areas in (r, g) units².

References
----------
-   :cite:`Storring2001`, :cite:`Soriano2003` (docs/references.md).
"""

from __future__ import annotations

from functools import partial

import numpy as np
from scipy.spatial import QhullError

from ...evaluation.detection import SCORED_MIN_OUTPUT
from ...evaluation.locus import hull_locus
from ...hints import ArrayLike, NDArrayFloat
from ...model.camera import Camera
from ...model.chromaticity import ncc
from ...model.response import response
from ...rendering.face import render_face
from ...rendering.face.scene import skin_reflectance_of
from ...rendering.variants import choose_variant
from ...spectra import GRID_DEFAULT
from .workers import run_renders

__all__ = ["SKIN_TONES", "face_locus", "convex_intersection_area"]

SKIN_TONES = tuple(f"skin-model:melanin={m:g}" for m in (0.02, 0.08, 0.2, 0.4))
"""Light to very dark skin: the skin model at four melanin volume fractions."""


def _area(polygon: NDArrayFloat) -> float:
    x, y = polygon[:, 0], polygon[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def convex_intersection_area(a: NDArrayFloat, b: NDArrayFloat) -> float:
    """
    The area common to two convex polygons (vertices counter-clockwise, ``(n, 2)``), by Sutherland–Hodgman
    clipping of ``a`` by each edge of ``b``.

    Examples
    --------
    >>> square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float)
    >>> convex_intersection_area(square, square + 0.5)
    0.25
    """
    output = [tuple(p) for p in a]
    for start, end in zip(b, np.roll(b, -1, axis=0)):
        edge = end - start
        inside = lambda p: edge[0] * (p[1] - start[1]) - edge[1] * (p[0] - start[0]) >= 0  # noqa: E731
        points, output = output, []
        for current, previous in zip(points, points[-1:] + points[:-1]):
            if inside(current):
                if not inside(previous):
                    output.append(_crossing(previous, current, start, end))
                output.append(current)
            elif inside(previous):
                output.append(_crossing(previous, current, start, end))
        if not output:
            return 0.0
    return _area(np.array(output)) if len(output) >= 3 else 0.0


def _crossing(p, q, a, b) -> tuple[float, float]:
    """Where the segment p–q crosses the line a–b."""
    d1, d2 = np.subtract(q, p), np.subtract(b, a)
    t = ((a[0] - p[0]) * d2[1] - (a[1] - p[1]) * d2[0]) / (d1[0] * d2[1] - d1[1] * d2[0])
    return p[0] + t * d1[0], p[1] + t * d1[1]


def _lit_skin(task: tuple, camera_: Camera, physics: str, spp: int, seed: int, size: int,
              variant: str) -> tuple[NDArrayFloat, float]:
    """The NCC (r, g) of one face's lit skin pixels, ``task = (skin, prevailing K, calibration K)``, and its s."""
    skin, p, c = task
    face = render_face(camera_, "face", p, c, skin, physics, spp, seed, size, variant=variant)
    lit = (face.labels == 1) & (face.image.max(axis=-1) >= SCORED_MIN_OUTPUT)
    return ncc(np.maximum(face.image[lit].astype(np.float64), 0.0))[:, :2], face.seconds


def face_locus(camera_: Camera, pairs: ArrayLike = ((2300.0, 5900.0), (2856.0, 5900.0), (5900.0, 5900.0),
                                                     (10000.0, 5900.0)),
               skins: tuple[str, ...] = SKIN_TONES, physics: str = "direct", size: int = 64, spp: int = 16,
               seed: int = 0, workers: int = 1, dask=None, progress=None) -> dict:
    """
    The skin locus of rendered faces beside the analytic one of the same skins and illuminant pairs.

    ``pairs``: (prevailing, calibration) in K. Each face is rendered at ``size`` pixels; its lit skin pixels
    (brightest channel ≥ the ladder's :data:`~skinrender.evaluation.detection.SCORED_MIN_OUTPUT`) give NCC (r, g).
    The analytic points are Eq. 4 of the same skin reflectances under the same pairs. The faces render in this
    process (``workers = 1``), in ``workers`` processes or on a Dask cluster (``dask``: an address or a
    ``distributed.Client``), with the same numbers (:func:`skinrender.studies.face.workers.run_renders`);
    ``progress``: a stream for a progress bar, or ``None``.

    Returns
    -------
    dict
        ``rendered_area``, ``analytic_area``, ``overlap_iou``, ``analytic_covered`` (the share of the analytic
        locus inside the rendered one), ``centre_shift`` (r, g), both ``polygon``\\ s,
        ``pixels`` (scored skin pixels), ``seconds``.
    """
    pairs = np.asarray(pairs, dtype=np.float64).reshape(-1, 2)
    tasks = [(skin, float(p), float(c)) for skin in skins for p, c in pairs]
    analytic = [ncc(response(camera_, skin_reflectance_of(skin, GRID_DEFAULT)[None, :], p, c))[:, :2]
                for skin, p, c in tasks]
    variant = choose_variant(None)
    done = run_renders(partial(_lit_skin, camera_=camera_, physics=physics, spp=spp, seed=seed, size=size,
                               variant=variant), tasks, variant, workers, dask, progress, "face locus")
    rendered, seconds = [points for points, _ in done], sum(s for _, s in done)
    cloud, model = np.concatenate(rendered), np.concatenate(analytic)
    mine, theirs = hull_locus(cloud, pairs[:, 0], None), hull_locus(model, pairs[:, 0], None)
    if mine is None or theirs is None:
        raise QhullError("a locus without area: too few lit skin pixels or coincident sensors")
    shared = convex_intersection_area(mine.polygon, theirs.polygon)
    return {
        "camera": camera_.name, "physics": physics, "skins": list(skins), "pairs_K": pairs.tolist(),
        "rendered_area": mine.area, "analytic_area": theirs.area,
        "overlap_iou": shared / (mine.area + theirs.area - shared),
        "analytic_covered": shared / theirs.area,
        # each (skin, pair) weighs alike, as in the analytic cloud (dark skins have fewer lit pixels)
        "centre_shift": (np.mean([part.mean(axis=0) for part in rendered], axis=0) - model.mean(axis=0)).tolist(),
        "rendered_polygon": mine.polygon.tolist(), "analytic_polygon": theirs.polygon.tolist(),
        "pixels": int(len(cloud)), "seconds": seconds, "spp": spp, "size": size,
    }


