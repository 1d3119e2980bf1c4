"""
Validating face renders
=======================

A face rendered at a level of physics, checked against the analytic limits
that hold at that level (:mod:`skinrender.rendering.face.limits`), and told
how far its skin moves from Eq. 4 where none holds.

-   :func:`validate_face`, :class:`FaceValidation`: the checks of one face scene.
-   :data:`LIMITS_SCENE_FREE`: the limits that hold whatever the level.

What holds where
----------------
Each effect states its limits (:class:`~skinrender.rendering.face.effects.base.Limits`):
the check it makes the level's test, or that it breaks every limit, and why;
a level composes them (:attr:`~skinrender.rendering.face.effects.levels.Level.check`,
``.why``, ``.measure``). With today's effects:

======================  ====================================================
level (effects)         checks
======================  ====================================================
``direct``              ``shading_cancels``
``sheen``               ``dichromatic_plane``
``noise`` (+ above)     the same, on the frames' mean, dark signal removed,
                        clipped pixels left out, quantisation bounded
``interreflection``,    none: ``eq4_shift`` only (information)
``mixed``
every level             ``white_furnace`` (the scene's mesh, its camera),
                        ``closed_sphere`` (the skin's reflectance), and
                        ``eq4_shift``
======================  ====================================================

The requested ``spp`` is split over :data:`~skinrender.rendering.face.limits.REPLICATES`
renders with seeds ``seed, seed + 1, …`` (mod 2³²), each at ``⌈spp / K⌉``; their
spread is each statistic's noise. Through an image sensor (``noise``) each
replicate is a frame of its own (the sensor's stream is seeded from the
render's seed), so the spread holds the sensor's noise too; the sensor is
linear in the mean except for its dark signal (subtracted: dark current ×
exposure), the clipping at 0 and at saturation (pixels with a clipped
replicate are left out) and the rounding to codes (pixels whose modelled
noise is below :data:`~skinrender.rendering.face.effects.noise.DITHER_SIGMA_DN` are left out; elsewhere the mean
error is bounded by :func:`~skinrender.rendering.face.limits.rounding_bias`
at each pixel's modelled σ and may be used up by a deviation, and the
standard error is taken no smaller than the EMVA 1288 model's,
``√((σ² + 1/12 DN²) / K)``, since twelve frames may read one code). A dim scene
through a coarse sensor may so leave too few pixels to test: the check then
reports ``passed`` None with the count.

Units: temperatures K, times s, images in Eq. 4 output units.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np

from ...errors import SkinrenderError
from ...model.chromaticity import ncc
from ...spectra import GRID_DEFAULT
from ..validation import analytic_reference
from .effects import Level, Replicates, physics_level
from .limit_scenes import furnace_radiance, sphere_channels
from .limits import REPLICATES, LimitCheck, check_furnace, check_sphere, eq4_shift
from .render import FaceRendering, render_face
from .scene import skin_reflectance_of

__all__ = ["LIMITS_SCENE_FREE", "FURNACE_SIZE", "FURNACE_SPP", "SPHERE_SIZE", "SPHERE_SPP", "FaceValidation",
           "validate_face"]

LIMITS_SCENE_FREE = {
    "furnace": "white furnace: the scene's mesh, reflectance 1, every bounce, in a uniform sky",
    "sphere": "closed Lambertian sphere of the skin's reflectance seen from inside, every bounce and one",
}
"""The limits that hold whatever the level, name → meaning; run small beside the level's own."""

FURNACE_SIZE = 32
"""Image side of the white furnace, pixels (~300 head pixels in the bundled scene)."""

FURNACE_SPP = 16
"""Samples per pixel of each white-furnace replicate."""

SPHERE_SIZE = 16
"""Image side of the closed sphere, pixels (their mean is tested)."""

SPHERE_SPP = 16
"""Samples per pixel of each closed-sphere replicate."""


@dataclass(frozen=True)
class FaceValidation:
    """
    A face render checked against its level's analytic limits.

    Attributes
    ----------
    rendering
        The first replicate (scene, camera, physics, labels, lights).
    checks
        :class:`~skinrender.rendering.face.limits.LimitCheck` rows.
    spp, spp_requested
        Samples per pixel of all replicates together, and as asked.
    replicates, seed
        How many renders, the first's seed.
    seconds
        Wall time of everything, s.
    """

    rendering: FaceRendering
    checks: list
    spp: int
    spp_requested: int
    replicates: int
    seed: int
    seconds: float
    info: dict = field(default_factory=dict)

    @property
    def passed(self) -> bool | None:
        """
        False when a check that applies fails; else None when one that applies is undecided (its ``reason``
        says why) or none applies; True only when every check that applies passed.
        """
        verdicts = [c.passed for c in self.checks if c.applies]
        if False in verdicts:
            return False
        return None if not verdicts or None in verdicts else True

    def document(self) -> dict:
        """The JSON document of ``skinrender validate face``."""
        r = self.rendering
        return {"scene": r.scene.name, "camera": r.camera.name, "physics": r.physics, "skin": r.skin,
                "prevailing_K": r.prevailing, "calibration_K": r.calibration, "spp": self.spp,
                "spp_requested": self.spp_requested, "replicates": self.replicates, "seed": self.seed,
                "sampler": r.sampler, "variant": r.variant, "elapsed_s": self.seconds,
                "size": [r.scene.camera.width, r.scene.camera.height], "labels": r.label_names, **self.info,
                "checks": [c.document() for c in self.checks], "passed": self.passed}


def validate_face(
    camera_,
    scene="face",
    prevailing=None,
    calibration=None,
    skin: str | None = None,
    physics: str | Level = "direct",
    spp: int = 256,
    seed: int = 0,
    size=None,
    sampler: str = "multijitter",
    variant: str | None = None,
    channels: str = "auto",
    imager=None,
    exposure="auto",
    illuminance: float | None = None,
    replicates: int = REPLICATES,
    limits=tuple(LIMITS_SCENE_FREE),
    progress: Callable[[str], None] | None = None,
) -> FaceValidation:
    """
    Render a face scene ``replicates`` times and check the analytic limits of its level.

    Parameters
    ----------
    camera_, scene, prevailing, calibration, skin, physics, sampler, variant, channels, imager, exposure, illuminance
        As :func:`skinrender.rendering.face.render_face` (temperatures K,
        illuminance lx, exposure s or ``auto``).
    spp
        Samples per pixel in all, split over the replicates (each ``⌈spp / replicates⌉``).
    seed
        The first replicate's seed; the others follow.
    size
        Image side, pixels; ``None``: the scene's.
    replicates
        Renders, ≥ 3 (the jackknife's t has ``replicates − 1`` degrees of freedom).
    limits
        Which of :data:`LIMITS_SCENE_FREE` to run beside the level's own.
    progress
        Called with a line of text before each stage.

    Returns
    -------
    :class:`FaceValidation`
    """

    start = time.perf_counter()
    say = progress or (lambda line: None)
    level = physics_level(physics)
    if isinstance(replicates, bool) or not isinstance(replicates, (int, np.integer)) or replicates < 3:
        raise SkinrenderError(f"replicates must be an integer ≥ 3, got {replicates!r}")
    unknown = [name for name in limits if name not in LIMITS_SCENE_FREE]
    if unknown:
        raise SkinrenderError(f"limits: unknown {', '.join(map(repr, unknown))}; known: "
                              + ", ".join(LIMITS_SCENE_FREE))
    if isinstance(spp, bool) or not isinstance(spp, (int, np.integer)) or spp < 1:
        raise SkinrenderError(f"spp must be a positive integer, got {spp!r}")
    each = max(1, math.ceil(int(spp) / replicates))
    seeds = [(int(seed) + k) % 2**32 for k in range(replicates)]
    say(f"rendering the face ({level.name}) {replicates} times at {each} spp …")
    renders = [render_face(camera_, scene, prevailing, calibration, skin, level, each, s, size, sampler, variant,
                           channels=channels, imager=imager, exposure=exposure, illuminance=illuminance)
               for s in seeds]
    first = renders[0]
    cam, labels = first.camera, first.labels
    images = np.array([r.image for r in renders], dtype=np.float64)
    rho = skin_reflectance_of(first.skin, GRID_DEFAULT, "skin")
    expected = ncc(analytic_reference(cam, rho[None], first.prevailing, first.calibration))[0]
    measured = level.measure(images, first, imager)  # through a sensor: its dark signal, clipping, codes
    images, usable = measured.images, measured.usable
    checks: list[LimitCheck] = []
    check = level.check  # the level's analytic limit (the last effect's that has one), or none
    if check is not None:
        checks.append(check(Replicates(images, labels, expected, first, level.lights(first.scene), usable,
                                       measured.bias, measured.floor)))
    if measured.excluded:  # say which pixels the measurement left out, and why a check may have none
        row = checks[0] if checks else None
        if row is not None and row.passed is None:
            checks[0] = replace(row, reason=f"{row.reason}; {measured.note}")
        checks = [replace(c, details={**c.details, **measured.excluded}) for c in checks]
    checks.append(eq4_shift(images, labels, expected, level.why, usable))
    if "furnace" in limits:
        say(f"white furnace ({FURNACE_SIZE}² px, {replicates} × {FURNACE_SPP} spp) …")
        checks.append(check_furnace(*furnace_radiance(cam, first.scene, seeds, FURNACE_SIZE, FURNACE_SPP,
                                                      variant=variant)))
    if "sphere" in limits:
        say(f"closed sphere ({SPHERE_SIZE}² px, {replicates} × {SPHERE_SPP} spp, two depths) …")
        every = sphere_channels(cam, rho, -1, seeds, SPHERE_SPP, SPHERE_SIZE, variant)
        one = sphere_channels(cam, rho, 2, seeds, SPHERE_SPP, SPHERE_SIZE, variant)
        checks.append(check_sphere(cam, rho, every, one))
    info = {key: value for key, value in first.info.items() if key != "lights"}
    info["lights"] = first.info.get("lights", {})
    return FaceValidation(first, checks, int(sum(r.spp for r in renders)), int(spp), int(replicates), int(seed),
                          time.perf_counter() - start, info)
