"""
The spectral render's trade, measured
=====================================

``skinrender bench render --spectral --cameras N[,N…]``: a face sweep
(:func:`skinrender.studies.face.sweep.face_sweep`: 2 light pairs × 2 skins ×
2 levels at 64 px, 16 spp) over N cameras, rendered once per light, skin and
level with the bands as its film (:mod:`skinrender.rendering.face.spectral_face`)
against one render per camera, timed whole with one worker (every spectral
sweep first, then every direct one, each way after a warm-up of its own: a
process renders one way, as a command does: loading the other way's scenes
would change the kernels a render compiles); and the error each way, so that
the speed is compared at equal error.

-   **Cameras**: :func:`bench_cameras`: gbell 9 (FWHM 90 nm) triplets at
    450, 540, 610 nm shifted together by up to ±30 nm (every 1 nm at 61).
-   **Error**: per channel, the RMS over scored skin pixels of a render's
    difference from a reference (a direct render at ``reference_spp``, another
    seed) over the reference's mean there, relative; measured on the first
    light pair, skin and level for :data:`ERROR_CAMERAS` cameras (a
    render's error does not depend on how many cameras share it). ``error`` is
    the broad channel's (:data:`BROAD_CHANNEL`, G: the 540 nm gbell 9).
-   **Speedup at equal error**: the timed ratio ``direct_s / spectral_s``,
    divided by ``(error_spectral / error_direct)²`` where the spectral render is
    the noisier (it would need that many times the spp, taking the error to
    fall as 1/√spp), never raised where it is the less noisy (``speedup_timed``
    is the plain ratio).
-   **The narrow-channel penalty**: the bands' hats sum to 1, so ``specfilm``
    samples wavelengths uniformly, where a direct render samples them in
    proportion to the camera's own curves (narrow channels even one pass each):
    the error of :data:`NARROW_CAMERA` each way, and ``penalty``, the variance
    ratio ``(error_spectral / error_direct)²`` per channel (the spp factor a
    spectral render needs to match).
-   **Common random numbers**: two cameras seen through one spectral render
    share its light paths; the variance of their difference over seeds
    (Macbeth patch means) against that of two independent direct renders.

-   **The basis error** (:func:`basis_errors`): a camera not given on the
    band grid, seen through the bands, against its own curves: Eq. 4 exactly,
    no render.

-   :func:`bench_spectral`, :func:`bench_cameras`, :func:`channel_errors`,
    :func:`camera_difference`, :func:`basis_errors`, :func:`estimate_bench_seconds`.

Units: seconds s; errors relative (fractions); temperatures K; sizes pixels.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np

from ...errors import SkinrenderError
from ...evaluation.detection import SCORED_MIN_OUTPUT
from ...rendering.face.labels import LABEL_SKIN
from ...spectra import GRID_DEFAULT
from ..face.sweep import estimate_seconds, face_sweep

__all__ = ["CAMERA_COUNTS", "LIGHTS_SPECTRAL", "SKINS_SPECTRAL", "LEVELS_SPECTRAL", "SIZE_SPECTRAL", "SPP_SPECTRAL",
           "REFERENCE_SPP_SPECTRAL", "ERROR_CAMERAS", "NARROW_CAMERA", "BROAD_CHANNEL", "CRN_CAMERAS", "CRN_SEEDS",
           "BASIS_CAMERAS", "BASIS_STEPS", "bench_cameras", "channel_errors", "camera_difference", "basis_errors",
           "estimate_bench_seconds", "bench_spectral"]

CAMERA_COUNTS = (1, 5, 20, 61)
"""The camera counts of the bench's rows."""

LIGHTS_SPECTRAL = ((2856.0, 5900.0), (2300.0, 5900.0))
"""The sweep's (prevailing, calibration) pairs, K."""

SKINS_SPECTRAL = ("skin-model:melanin=0.02", "skin-model:melanin=0.2")
"""The sweep's skins."""

LEVELS_SPECTRAL = ("direct", "sheen")
"""The sweep's levels of physics."""

SIZE_SPECTRAL = 64
"""Image side, pixels."""

SPP_SPECTRAL = 16
"""Samples per pixel of both ways."""

REFERENCE_SPP_SPECTRAL = 256
"""Samples per pixel of the error's reference renders."""

ERROR_CAMERAS = 3
"""Cameras of a row whose error is measured."""

NARROW_CAMERA = "gbell:3@450,540,610"
"""The narrow camera of the penalty: gbell 3, FWHM 30 nm."""

BROAD_CHANNEL = 1
"""The broad channel the rows' ``error`` is of: G (gbell 9 at 540 nm, FWHM 90 nm)."""

CRN_CAMERAS = ("gbell:9@450,540,610", "gbell:9@460,550,620")
"""The two cameras whose difference common random numbers are measured on."""

CRN_SEEDS = 12
"""Seeds of the common random numbers' variance."""


def bench_cameras(count: int) -> list[str]:
    """
    ``count`` gbell 9 cameras, their peaks 450, 540, 610 nm shifted together by offsets spread over ±30 nm.

    >>> bench_cameras(3)
    ['gbell:9@420,510,580', 'gbell:9@450,540,610', 'gbell:9@480,570,640']
    """
    offsets = [0] if count == 1 else sorted({int(round(d)) for d in np.linspace(-30, 30, count)})
    if len(offsets) != count:
        raise SkinrenderError(f"cameras: at most 61 cameras (one per 1 nm offset), got {count}")
    return [f"gbell:9@{450 + d},{540 + d},{610 + d}" for d in offsets]


def channel_errors(image, reference, labels) -> np.ndarray:
    """
    Per channel, the RMS of ``image − reference`` over the skin pixels the reference scores (brightest channel ≥
    :data:`~skinrender.evaluation.detection.SCORED_MIN_OUTPUT`), over the reference's mean there: ``(3,)``,
    relative.
    """
    reference = np.asarray(reference, dtype=np.float64)
    skin = (labels == LABEL_SKIN) & (reference.max(axis=-1) >= SCORED_MIN_OUTPUT)
    difference = np.asarray(image, dtype=np.float64)[skin] - reference[skin]
    return np.sqrt(np.mean(difference**2, axis=0)) / reference[skin].mean(axis=0)


def _errors(cameras, spp: int, reference_spp: int, seed: int, size: int) -> dict:
    """Each camera's channel errors, spectral and direct, on the sweep's first light pair, skin and level."""
    from ...rendering.dispatch import render

    (p, c), skin, level = LIGHTS_SPECTRAL[0], SKINS_SPECTRAL[0], LEVELS_SPECTRAL[0]
    common = {"skin": skin, "physics": level, "size": size}
    spectral = render("face", prevailing=p, spectral=True, spp=spp, seed=seed, **common)
    out = {"spectral": [], "direct": []}
    for cam in cameras:
        reference = render("face", cam, p, c, spp=reference_spp, seed=seed + 1, **common)
        direct = render("face", cam, p, c, spp=spp, seed=seed, **common)
        out["spectral"].append(channel_errors(spectral.through(cam, c).image, reference.image, reference.labels))
        out["direct"].append(channel_errors(direct.image, reference.image, reference.labels))
    return {key: np.array(value) for key, value in out.items()}


def camera_difference(cameras=CRN_CAMERAS, seeds: int = CRN_SEEDS, spp: int = SPP_SPECTRAL, seed: int = 0) -> dict:
    """
    The variance over ``seeds`` of the difference of two cameras' balanced Macbeth patch means (2856 K balanced
    to 5900 K, ``spp``): seen through one spectral render per seed, against two independent direct renders
    per seed. ``variance_ratio``: direct over spectral, per patch channel (the white, exact at its own
    balance, left out), summarised by its median, least and largest.
    """
    from ...rendering.dispatch import render
    from ...rendering.spectral_chart import render_chart_spectral

    a, b = cameras
    spectral, direct = [], []
    for k in range(seeds):
        base = seed + 8 * k  # every render its own seeds: a direct render takes seed and seed + 1
        image = render_chart_spectral("macbeth", 2856, spp=spp, seed=base)
        spectral.append(image.through(a, 5900).patches.mean - image.through(b, 5900).patches.mean)
        first = render("macbeth", a, 2856, 5900, spp=spp, seed=base + 2)
        second = render("macbeth", b, 2856, 5900, spp=spp, seed=base + 4)
        direct.append(first.patches.mean - second.patches.mean)
    var_s = np.var(np.array(spectral)[:, :-1], axis=0, ddof=1)
    var_d = np.var(np.array(direct)[:, :-1], axis=0, ddof=1)
    ratio = var_d / np.maximum(var_s, 1e-300)
    return {"cameras": list(cameras), "seeds": seeds, "spp": spp, "scene": "macbeth", "prevailing_K": 2856.0,
            "calibration_K": 5900.0, "variance_spectral_median": float(np.median(var_s)),
            "variance_direct_median": float(np.median(var_d)), "variance_ratio_median": float(np.median(ratio)),
            "variance_ratio_min": float(ratio.min()), "variance_ratio_max": float(ratio.max())}


BASIS_CAMERAS = ("gbell:9@450,540,610", "gbell:3@450,540,610", "gbell:1@450,540,610", "impulse@450,550,650",
                 "Nikon 5100 (NPL)", "Sigma SDMerill (NPL)")
"""Cameras whose basis error is stated: gbell 9, 3, 1 (FWHM 90, 30, 10 nm) given every 1 nm, the impulse, and
measured cameras given every 5 and 10 nm."""

BASIS_STEPS = (2.5, 5.0, 10.0)
"""Band steps (nm) of the basis error."""


def basis_errors(cameras=BASIS_CAMERAS, steps=BASIS_STEPS, lights=((2856.0, 5900.0), (2300.0, 2300.0))) -> list:
    """
    What the bands do to a camera not given on their grid, exactly (no render): the largest relative difference
    over the Macbeth chart (a channel darker than 1 % of white against 1 % of white) between Eq. 4 of the camera
    as the bands see it (its curves at the bands, linearly interpolated) and Eq. 4 of its curves on the 1 nm
    grid, for each band step (400–700 nm) and light pair; one row per camera and step.
    """
    from ...model.camera import camera
    from ...rendering.agreement import tolerance_scale
    from ...rendering.scene import load_chart_scene
    from ...rendering.validation import analytic_reference
    from ...spectra import WavelengthGrid

    reflectance = load_chart_scene("macbeth").reflectances(GRID_DEFAULT)
    rows = []
    for spec in cameras:
        cam = camera(spec)
        for step in steps:
            bands, worst = WavelengthGrid(400.0, 700.0, step), 0.0
            for p, c in lights:
                exact = analytic_reference(cam, reflectance, p, c)
                seen = analytic_reference(cam, reflectance, p, c, bands=bands)
                worst = max(worst, float(np.max(np.abs(seen - exact) / tolerance_scale(exact))))
            rows.append({"camera": cam.name, "bands_nm": f"400:700:{step:g}", "max_rel_error": worst})
    return rows


def estimate_bench_seconds(counts, size: int = SIZE_SPECTRAL, spp: int = SPP_SPECTRAL,
                           reference_spp: int = REFERENCE_SPP_SPECTRAL) -> float:
    """The bench's time on one core, s: the sweeps both ways, the error renders and the seeds of the common random
    numbers (:func:`~skinrender.studies.face.sweep.estimate_seconds`)."""
    from ...rendering.bands import BANDS_DEFAULT

    combos = len(LIGHTS_SPECTRAL) * len(SKINS_SPECTRAL) * len(LEVELS_SPECTRAL)
    pixels = size * size
    cameras = ERROR_CAMERAS + 1
    direct = sum(counts) * combos + 2 * cameras + 2 * CRN_SEEDS
    spectral = len(set(LIGHTS_SPECTRAL)) * len(SKINS_SPECTRAL) * len(LEVELS_SPECTRAL) * len(counts) + 1 + CRN_SEEDS
    return (estimate_seconds(direct, pixels, spp, 1) + estimate_seconds(spectral, pixels, spp, 1, bands=BANDS_DEFAULT)
            + estimate_seconds(cameras, pixels, reference_spp, 1))


def _row(count: int, spectral_s: float, direct_s: float, error_s: float, error_d: float) -> dict:
    timed = direct_s / spectral_s
    ratio = error_s / error_d
    return {"cameras": count, "spectral_s": spectral_s, "direct_s": direct_s,
            "speedup": timed / max(1.0, ratio**2), "speedup_timed": timed, "error_spectral": error_s,
            "error_direct": error_d, "error_ratio": ratio}


def bench_spectral(counts=CAMERA_COUNTS, size: int = SIZE_SPECTRAL, spp: int = SPP_SPECTRAL,
                   reference_spp: int = REFERENCE_SPP_SPECTRAL, seed: int = 0,
                   progress: Callable[[str], None] | None = None) -> dict:
    """
    The spectral render's trade for each camera count of ``counts`` (module docstring).

    Returns
    -------
    dict
        ``rows`` (one per count: ``cameras``, ``spectral_s``, ``direct_s``, ``speedup`` — at equal error —,
        ``speedup_timed``, ``error_spectral``, ``error_direct``, ``error_ratio``), ``narrow`` (``camera``,
        per channel ``error_spectral``, ``error_direct``, ``penalty``), ``errors`` (the broad cameras' per
        channel), ``common_random_numbers`` (:func:`camera_difference`), ``basis`` (:func:`basis_errors`), the
        sweep's settings and ``machine``.
    """
    from .bench import machine

    say = progress or (lambda line: None)
    counts = [int(n) for n in counts]
    lights, skins, levels = list(LIGHTS_SPECTRAL), list(SKINS_SPECTRAL), list(LEVELS_SPECTRAL)
    start = time.perf_counter()
    timing = {True: {}, False: {}}
    for spectral in (True, False):  # one way at a time, as one command renders: the other's scenes stay unloaded
        way = "spectral" if spectral else "one render per camera"
        say(f"warming up ({way}: its kernels compiled once) …")
        face_sweep(bench_cameras(2), lights, skins, levels, size, spp, seed, workers=1, spectral=spectral)
        for count in counts:
            say(f"{count} camera{'s' * (count > 1)}, {way} …")
            sweep = face_sweep(bench_cameras(count), lights, skins, levels, size, spp, seed, workers=1,
                               spectral=spectral)
            timing[spectral][count] = sweep.elapsed_s
    say(f"errors: {ERROR_CAMERAS} cameras and {NARROW_CAMERA} against {reference_spp}-spp references …")
    broad = _errors(bench_cameras(5)[1:1 + ERROR_CAMERAS], spp, reference_spp, seed, size)
    narrow = _errors([NARROW_CAMERA], spp, reference_spp, seed, size)
    error_s = float(np.sqrt(np.mean(broad["spectral"][:, BROAD_CHANNEL] ** 2)))
    error_d = float(np.sqrt(np.mean(broad["direct"][:, BROAD_CHANNEL] ** 2)))
    rows = [_row(count, timing[True][count], timing[False][count], error_s, error_d) for count in counts]
    say(f"common random numbers: {CRN_SEEDS} seeds of the Macbeth chart …")
    crn = camera_difference(seed=seed)
    narrow_s, narrow_d = narrow["spectral"][0], narrow["direct"][0]
    return {"rows": rows, "narrow": {"camera": NARROW_CAMERA, "error_spectral": narrow_s.tolist(),
                                     "error_direct": narrow_d.tolist(), "penalty": ((narrow_s / narrow_d) ** 2).tolist()},
            "errors": {"cameras": bench_cameras(5)[1:1 + ERROR_CAMERAS], "spectral": broad["spectral"].tolist(),
                       "direct": broad["direct"].tolist(), "channel": "RGB"[BROAD_CHANNEL]},
            "common_random_numbers": crn, "basis": basis_errors(), "scene": "face", "lights_K": [list(pair) for pair in lights],
            "skins": skins, "levels": levels, "size": size, "spp": spp, "reference_spp": reference_spp,
            "bands_nm": "400:700:5", "workers": 1, "seed": seed, "elapsed_s": time.perf_counter() - start,
            "grid_nm": f"{GRID_DEFAULT.start:g}:{GRID_DEFAULT.end:g}:{GRID_DEFAULT.step:g}", "machine": machine()}
