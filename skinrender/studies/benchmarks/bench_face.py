"""
Face render benchmark
=====================

Error against spp and time of the face render at each level of physics
(``skinrender bench render --scene face``); measured here, never asserted in
unit tests.

-   :func:`bench_face`: the curve and the presets per level.
-   :func:`fit_error`, :func:`spp_for`, :func:`presets_of`: the error model and the spp it asks for.
-   :data:`LEVELS_BENCH`, :data:`SPPS_BENCH`, :data:`PRESET_THRESHOLDS`.

What is measured
----------------
For each level, spp and a seed, the face is rendered (after a warm-up render
at the same spp, so that loading the scene and compiling the kernels are left
out, as the chart bench does) and compared with a reference render of the
same level at ``reference_spp`` with another seed. Over the skin pixels
scored in the reference (label 1, brightest channel ≥
:data:`~skinrender.evaluation.detection.SCORED_MIN_OUTPUT`):

-   ``skin_ncc_rms``: the RMS per pixel of the NCC (r, g) difference
    (Euclidean), what pixel-wise detection sees;
-   ``skin_ncc_error``: the Euclidean difference of the mean NCC (r, g), what
    the ladder's mean sees.

Both include the reference's own noise. The per-pixel squared error is fitted
as ``e² = a (1/spp + 1/reference_spp) + b``: ``a`` the Monte Carlo variance
at one spp, ``b`` the floor that spp does not lower (the sensor's noise at
``noise``, twice: the render's frame and the reference's). The preset of a
level (:func:`presets_of`) is the smallest measured spp whose error, the
reference's terms (``a / reference_spp`` and half the floor) taken off,
reaches :data:`PRESET_THRESHOLDS`, else the smallest power of two the fit
asks for, or ``None`` where the floor is above it; ``floor`` is ``√(b / 2)``,
one frame's share of the floor, and ``spp_at_floor`` the smallest power of
two whose Monte Carlo error is half of it (``a / spp ≤ b / 8``): more spp
buys nothing a sensor would show.

Units: time s, NCC fractions, temperatures K.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence

import numpy as np

from ...errors import SkinrenderError
from ...model.camera import camera
from ...model.chromaticity import ncc
from ...rendering.face.effects import LEVELS_EACH, physics_level
from .bench import at_least_one, machine

__all__ = ["LEVELS_BENCH", "SPPS_BENCH", "SIZE_BENCH", "PRESET_THRESHOLDS", "fit_error", "spp_for", "presets_of",
           "bench_face"]

LEVELS_BENCH = tuple(level for level in LEVELS_EACH
                     if physics_level(level).samples_per_s >= physics_level("direct").samples_per_s)
"""The levels timed unless named: the analytic model's world and each effect alone (read from the registry of
effects, :data:`skinrender.rendering.face.effects.LEVELS_EACH`) but those slower per sample than the base
(``subsurface-volume``, not a default level either: its reference alone would take ~40 min on one core at
:data:`SIZE_BENCH`): name them (``--levels subsurface-volume``), at a smaller size."""

SPPS_BENCH = (4, 16, 64, 256)
"""Samples per pixel of the curve."""

SIZE_BENCH = 256
"""Image side, pixels (the issue's 256 × 256)."""

PRESET_THRESHOLDS = {"draft": 1e-2, "standard": 3e-3, "reference": 1e-3}
"""RMS per-pixel skin NCC error each preset reaches: ``draft`` at the paper's Table 1 scale (|ΔNCC| ~ 0.01
between render and model), ``standard`` below a tenth of the skin locus's NCC width (~0.03), ``reference``
ten times below ``draft``."""


def fit_error(spps: Sequence[int], errors: Sequence[float], reference_spp: int) -> tuple[float, float]:
    """
    ``(a, b)``, both ≥ 0, of ``e² = a (1/spp + 1/reference_spp) + b``, least squares in relative terms
    (each point's residual divided by its ``e²``, so that the low-spp points do not outweigh the rest).

    Examples
    --------
    >>> e = [np.sqrt(2 * (1 / s + 1 / 256) + 1e-4) for s in (4, 16, 64)]
    >>> a, b = fit_error([4, 16, 64], e, 256)
    >>> round(a, 6), round(b, 8)
    (2.0, 0.0001)
    """
    x = 1.0 / np.asarray(spps, dtype=np.float64) + 1.0 / reference_spp
    y = np.asarray(errors, dtype=np.float64) ** 2
    w = 1.0 / np.maximum(y, np.finfo(float).tiny)
    if x.size == 1:
        return float(y[0] / x[0]), 0.0
    a, b = np.linalg.lstsq(np.stack([x * w, w], axis=1), y * w, rcond=None)[0]
    if b <= 1e-9 * y.min():  # no floor (one below 1e-9 of the smallest e² is rounding): the Monte Carlo term alone
        return float(np.sum(x * w * w * y) / np.sum((x * w) ** 2)), 0.0
    if a < 0:  # no decrease: a floor alone
        return 0.0, float(np.sum(w * w * y) / np.sum(w * w))
    return float(a), float(b)


def spp_for(threshold: float, a: float, b: float) -> int | None:
    """
    The smallest power of two spp with ``√(a / spp + b) ≤ threshold``; ``None`` when the floor ``b`` is above it.

    Examples
    --------
    >>> spp_for(0.01, 0.0256, 0.0), spp_for(0.01, 0.0256, 2e-4)
    (256, None)
    """
    room = threshold**2 - b
    if room <= 0:
        return None
    return 1 << max(0, math.ceil(math.log2(max(a / room, 1.0))))


def presets_of(spps: Sequence[int], errors: Sequence[float], reference_spp: int) -> dict:
    """
    The spp of each of :data:`PRESET_THRESHOLDS` from a level's curve (``spps`` ascending, RMS ``errors``).

    The error model (:func:`fit_error`) is fitted to the upper half of the
    curve (at least two points), where the sampler's stratification no longer
    speeds convergence beyond ``1/√spp``. A preset is the smallest measured
    spp whose own error (the reference's terms taken off) reaches the
    threshold, else the model's :func:`spp_for` (named in ``extrapolated``).

    Returns
    -------
    dict
        ``draft``, ``standard``, ``reference`` (spp or ``None``), ``extrapolated``
        (names), ``a``, ``b``, ``floor`` (``√(b / 2)``), ``spp_at_floor`` and
        ``undefined`` (``{key: reason}`` for each ``None``).
    """
    upper = max(2, math.ceil(len(spps) / 2)) if len(spps) > 1 else 1
    a, b = fit_error(spps[-upper:], errors[-upper:], reference_spp)
    own = np.asarray(errors, dtype=np.float64) ** 2 - a / reference_spp - b / 2
    floor = math.sqrt(b / 2)
    out: dict = {"extrapolated": []}
    undefined = {}
    for name, threshold in PRESET_THRESHOLDS.items():
        reached = [spp for spp, e2 in zip(spps, own) if e2 <= threshold**2]
        out[name] = reached[0] if reached else spp_for(threshold, a, b / 2)
        if not reached and out[name] is not None:
            out["extrapolated"].append(name)
        if out[name] is None:
            undefined[name] = (f"the error's floor {floor:.2g} (what more spp does not lower, e.g. the sensor's "
                               f"noise) is above the threshold {threshold:g}")
    at_floor = None if b <= 0 else 1 << max(0, math.ceil(math.log2(max(8 * a / b, 1.0))))
    if at_floor is None:
        undefined["spp_at_floor"] = "no floor in the fit: the error keeps falling with spp over the curve"
    return {**out, "a": a, "b": b, "floor": floor, "spp_at_floor": at_floor, "undefined": undefined}


def _scored_skin(rendering) -> np.ndarray:
    from ...evaluation.detection import SCORED_MIN_OUTPUT

    return (rendering.labels == 1) & (rendering.image.max(axis=-1) >= SCORED_MIN_OUTPUT)


def bench_face(
    camera_spec: str = "gbell:9@450,540,610",
    levels: Sequence[str] = LEVELS_BENCH,
    spps: Sequence[int] = SPPS_BENCH,
    size: int = SIZE_BENCH,
    reference_spp: int | None = None,
    seed: int = 1,
    scene: str = "face",
    prevailing: float = 2856.0,
    calibration: float = 2856.0,
    variant: str | None = None,
    progress: Callable[[str], None] | None = None,
) -> dict:
    """
    Error of the face's skin NCC against spp and time, per level of physics.

    Parameters
    ----------
    camera_spec
        Camera spec.
    levels
        Levels of physics (``direct``, ``interreflection`` …, effects joined by ``+``).
    spps
        Samples per pixel of the curve, each ≥ 1.
    size
        Image side, pixels.
    reference_spp
        The reference render's spp; default 4 × the largest of ``spps``.
    seed
        The timed renders' seed (the warm-up uses ``seed + 1``, the reference ``seed + 2``).
    scene, prevailing, calibration, variant
        As :func:`skinrender.rendering.face.render_face` (temperatures K).

    Returns
    -------
    dict
        ``machine``, ``camera``, ``scene``, ``size``, ``reference_spp``,
        ``curve`` (``[{level, spp, seconds, skin_ncc_error, skin_ncc_rms,
        pixels, variant, undefined}]``), ``presets`` (``{level: {draft, standard,
        reference, a, b, floor, spp_at_floor, reference_seconds, undefined}}``,
        spp or ``None``; ``undefined``: ``{key: reason}`` for each ``None``),
        ``thresholds``, ``elapsed_s`` (everything, s).
    """

    from ...rendering.face import render_face
    from ...rendering.face.scene import load_face_scene
    from ...rendering.settings import seed_at

    say = progress or (lambda line: None)
    start = time.perf_counter()
    spps = [at_least_one(s, "--spp-list") for s in spps]
    if not spps:
        raise SkinrenderError("--spp-list: name at least one spp", flag="--spp-list")
    size = at_least_one(size, "--size")
    if len(set(spps)) < len(spps):
        raise SkinrenderError(f"--spp-list: each spp once, got {list(spps)}", flag="--spp-list")
    reference_spp = at_least_one(reference_spp or 4 * max(spps), "--reference-spp")
    if reference_spp <= max(spps):
        raise SkinrenderError(f"--reference-spp must be more than the largest of --spp-list ({max(spps)}), got "
                              f"{reference_spp}", flag="--reference-spp")
    labels = [level if isinstance(level, str) else level.name for level in levels]  # the rows' names, as given
    if not labels:
        raise SkinrenderError("--levels: name at least one level of physics", flag="--levels")
    try:
        levels = [physics_level(level) for level in levels]  # each spec parsed once, here
    except SkinrenderError as error:
        raise SkinrenderError(f"--levels: {error}", flag="--levels") from None
    cam = camera(camera_spec)
    face = load_face_scene(scene)
    from ...workload import check_work

    for label, level in zip(labels, levels):  # a level too long is refused before anything renders
        check_work(level.seconds(size * size * reference_spp), "--levels",
                   f"{label}'s reference ({size}×{size} px at {reference_spp} spp)",
                   fewer="a smaller --size or --reference-spp")
    curve, presets = [], {}
    from ...evaluation.detection import SCORED_MIN_OUTPUT

    none_scored = f"no scored skin pixel in the reference (brightest channel ≥ {SCORED_MIN_OUTPUT:g})"
    for label, level in zip(labels, levels):
        say(f"{label}: reference at {reference_spp} spp …")
        ref = render_face(cam, face, prevailing, calibration, physics=level, spp=reference_spp, seed=seed_at(seed, 2),
                          size=size, variant=variant)
        scored = _scored_skin(ref)
        ref_ncc = ncc(ref.image.astype(np.float64))[..., :2][scored]
        rms = []
        for spp in sorted(spps):
            say(f"{label}: {spp} spp …")
            render_face(cam, face, prevailing, calibration, physics=level, spp=spp, seed=seed_at(seed, 1), size=size,
                        variant=variant)  # warm-up: the scene loaded, the kernels compiled
            timed = render_face(cam, face, prevailing, calibration, physics=level, spp=spp, seed=seed, size=size,
                                variant=variant)
            rg = ncc(np.maximum(timed.image.astype(np.float64), 0.0))[..., :2][scored]
            rg = np.nan_to_num(rg, nan=1.0 / 3.0)  # a pixel black at low spp: the neutral point
            difference = rg - ref_ncc
            row = {"level": label, "spp": timed.spp, "seconds": timed.seconds,
                   "skin_ncc_error": float(np.hypot(*difference.mean(axis=0))) if scored.any() else None,
                   "skin_ncc_rms": float(np.sqrt(np.mean(np.sum(difference**2, axis=-1)))) if scored.any()
                   else None, "pixels": int(scored.sum()), "variant": timed.variant,
                   "undefined": {} if scored.any() else {key: none_scored for key in ("skin_ncc_error",
                                                                                       "skin_ncc_rms")}}
            curve.append(row)
            rms.append(row["skin_ncc_rms"])
        if None in rms:
            presets[label] = {**{name: None for name in PRESET_THRESHOLDS}, "floor": None, "spp_at_floor": None,
                              "undefined": {key: none_scored for key in (*PRESET_THRESHOLDS, "floor",
                                                                          "spp_at_floor")}}
            continue
        presets[label] = {**presets_of(sorted(spps), rms, reference_spp), "reference_seconds": ref.seconds}
    return {"machine": machine(), "camera": cam.name, "scene": face.name, "size": [size, size],
            "reference_spp": reference_spp, "prevailing_K": float(prevailing), "calibration_K": float(calibration),
            "curve": curve, "presets": presets, "thresholds": dict(PRESET_THRESHOLDS),
            "elapsed_s": time.perf_counter() - start}
