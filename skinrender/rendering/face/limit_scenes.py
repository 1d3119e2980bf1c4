"""
Scenes of the scene-free limits
===============================

The renders of the limits that hold whatever the level, and their checks: a
face scene's mesh as a white furnace, and a closed emitting Lambertian sphere
seen from inside.

-   :func:`furnace_radiance`, :data:`FURNACE_SKY`: the white furnace;
    :func:`check_furnace`, its check.
-   :func:`sphere_channels`: the closed sphere (its emission:
    :func:`~skinrender.rendering.face.limits.sphere_emission`);
    :func:`check_sphere`, its check.

The checks are difference tests as
:mod:`~skinrender.rendering.face.limits` describes: the furnace per pixel
and on the head's mean (two parts, each at
:data:`~skinrender.rendering.face.limits.ALPHA_PART`), the sphere on its
four NCC values at :data:`~skinrender.rendering.face.limits.ALPHA`.

The white furnace is rendered with flat shading (each triangle's own
normal) whatever the scene asks: interpolated shading normals are not energy
conserving :cite:`Veach1996`, so the limit holds for the geometry only;
``smooth=True`` renders the scene's smooth shading, whose loss it measures
(the head's mean 0.35 % below the sky's radiance, ``docs/face-verdicts.md``).

Units: radiance in the specfilm's units (W·m⁻²·sr⁻¹ times the sensitivity's
unit), wavelengths nm, temperatures K, illuminance lx.

References
----------
-   :cite:`Veach1996` : E. Veach (1996). Non-symmetric scattering in light
    transport algorithms. Rendering Techniques '96, 81–90 (shading normals).
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from ...hints import NDArrayFloat
from ...model.camera import Camera, camera
from ...spectra import GRID_DEFAULT
from ..validation import FLOAT32_FLOOR
from .document import channel_groups, channel_integral, film_dict, light_irradiance
from .labels import LABEL_SKIN
from .limits import ALPHA, LimitCheck, deviation_ratio, critical_t, jackknife, rg, sphere_emission, two_part
from .scene import FaceScene, Light, load_face_scene, skin_reflectance_of

if TYPE_CHECKING:
    from ..physics import Level

__all__ = ["FURNACE_SKY", "REPLICATES_DEFAULT", "FURNACE_SIZE", "FURNACE_SPP", "SPHERE_SIZE", "SPHERE_SPP",
           "furnace_radiance", "sphere_channels", "check_furnace", "check_sphere", "limit_furnace", "limit_sphere",
           "LIMITS_SCENE_FREE"]

FURNACE_SKY = Light(temperature=5000.0, illuminance=500.0)
"""The white furnace's uniform environment: a 5000 K Planckian, 500 lx on a surface open to it."""

REPLICATES_DEFAULT = 12
"""Seeds rendered unless named (:data:`skinrender.rendering.face.limits.REPLICATES`)."""

FURNACE_SIZE = 32
"""Image side of the white furnace, pixels (~300 head pixels in the bundled scene)."""

FURNACE_SPP = 16
"""Samples per pixel of each white-furnace replicate."""

SPHERE_SIZE = 16
"""Image side of the closed sphere, pixels (their mean is tested)."""

SPHERE_SPP = 16
"""Samples per pixel of each closed-sphere replicate."""


def furnace_radiance(cam: Camera | str, scene: FaceScene | str = "face", seeds=range(REPLICATES_DEFAULT),
                     size: int = 32,
                     spp: int = 16, physics: str | Level = "interreflection", variant: str | None = None,
                     sky: Light = FURNACE_SKY, smooth: bool = False) -> tuple[NDArrayFloat, NDArrayFloat, NDArrayFloat]:
    """
    The white furnace rendered: the scene's mesh alone, reflectance 1, inside a uniform sky, flat shading
    (``smooth``: the interpolated shading normals, which lose energy).

    Returns
    -------
    tuple
        ``(radiance, labels, expected)``: the replicates' radiance ``(K, size,
        size, 3)`` and the label image (specfilm units), and ``∫ (E / π) x_k dλ``,
        the sky's radiance through the camera, ``(3,)``.
    """
    from .render import render_face_request
    from .request import face_request

    furnace = replace(load_face_scene(scene), props=(), key=None, fill=None, environment=sky,
                      mesh_smooth=bool(smooth))
    request = face_request(furnace, cam, skin="perfect", physics=physics, size=size, spp=spp, variant=variant)
    renders = [render_face_request(request, int(s)) for s in seeds]
    lam, irradiance = light_irradiance(sky, GRID_DEFAULT)
    expected = channel_integral(camera(cam), GRID_DEFAULT, lam, irradiance / np.pi)
    return np.array([r.radiance for r in renders]), renders[0].labels, expected


def sphere_channels(cam: Camera | str, rho: NDArrayFloat, depth: int, seeds=range(REPLICATES_DEFAULT),
                    spp: int = 16,
                    size: int = 16, variant: str | None = None) -> NDArrayFloat:
    """
    Mean channels of a closed emitting Lambertian sphere of reflectance ``rho`` (on the default grid),
    rendered from its centre to path depth ``depth`` (−1: every bounce); one row per seed, specfilm units.
    """
    from ..renderer import mitsuba_spectrum
    from ..variants import choose_variant, mitsuba

    mi = mitsuba(choose_variant(variant))
    cam = camera(cam)
    lam, emission = sphere_emission()
    seeds = list(seeds)
    out = np.zeros((len(seeds), 3))
    for group in channel_groups(cam, GRID_DEFAULT):
        scene = mi.load_dict({
            "type": "scene", "integrator": {"type": "path", "max_depth": int(depth)},
            "sensor": {"type": "perspective", "fov": 60,
                       "sampler": {"type": "independent", "sample_count": int(spp)},
                       "film": film_dict(cam, GRID_DEFAULT, group, size, size)},
            "sphere": {"type": "sphere", "radius": 1.0, "flip_normals": True,
                       "emitter": {"type": "area", "radiance": mitsuba_spectrum(lam, emission)},
                       "bsdf": {"type": "diffuse", "reflectance": mitsuba_spectrum(GRID_DEFAULT.wavelengths, rho)}},
        })
        for row, seed in enumerate(seeds):
            image = np.array(mi.render(scene, seed=int(seed)), dtype=np.float64)
            out[row, list(group)] = image.reshape(-1, len(group)).mean(axis=0)
    return out


def check_furnace(radiance: NDArrayFloat, labels: NDArrayFloat, expected: NDArrayFloat) -> LimitCheck:
    """
    White furnace: a head of reflectance 1 (both sides) in a uniform sky of radiance ``L`` returns ``L``.

    The radiance leaving every surface is ``L`` (the fixed point of
    ``L_o = ∫ ρ/π L_i cos`` with ``ρ = 1`` and ``L_i = L`` from every
    direction), so with every bounce every pixel, the concavities included,
    reads ``∫ L x_k dλ``. Tested per pixel and channel, and on the head's mean.
    """
    radiance = np.asarray(radiance, dtype=np.float64)
    k = radiance.shape[0]
    head = labels == LABEL_SKIN
    mean = radiance.mean(axis=0)
    error = radiance.std(axis=0, ddof=1) / np.sqrt(k)
    t_pixel = deviation_ratio(np.abs(mean - expected), np.hypot(error, FLOAT32_FLOOR * expected))
    pooled = radiance[:, head].mean(axis=1) if head.any() else radiance.reshape(k, -1, 3).mean(axis=1)
    pooled_error = pooled.std(axis=0, ddof=1) / np.sqrt(k)
    t_pooled = deviation_ratio(np.abs(pooled.mean(axis=0) - expected), np.hypot(pooled_error, FLOAT32_FLOOR * expected))
    outcome, statistic, test, details = two_part("white_furnace", t_pixel, t_pooled, k,
                                                 "each pixel's channels against the sky's",
                                                 "the head's mean channels")
    return LimitCheck("white_furnace", True, outcome == "pass", statistic, 1.0, int(mean.shape[0] * mean.shape[1]),
                      "every pixel of a white head (reflectance 1, every bounce, flat shading) in a uniform sky "
                      f"against the sky's radiance; the head covers {int(head.sum())} pixels",
                      {**details, "head_rel_error": (pooled.mean(axis=0) / expected - 1).tolist()},
                      outcome=outcome, test=test)


def check_sphere(cam: Camera | str, rho: NDArrayFloat, every: NDArrayFloat, one: NDArrayFloat) -> LimitCheck:
    """
    Closed sphere: interreflection's closed form, and how it saturates colour.

    A closed Lambertian sphere of reflectance ρ(λ) emitting E(λ) uniformly,
    seen from inside: by symmetry the radiance is the same everywhere and
    ``L = E + (ρ/π) ∫ L cos θ dω = E + ρ L``, so ``L = E / (1 − ρ)`` with every
    bounce (``every``: :func:`sphere_channels` at depth −1), ``E (1 + ρ)`` with
    one (``one``: depth 2). Both rendered NCCs (r, g) are tested against these
    (four values, Šidák at :data:`~skinrender.rendering.face.limits.ALPHA` with
    the saturation's test); and the higher terms ρⁿ being ever more coloured,
    every bounce must move the chromaticity further from the light's than one
    bounce does (``saturation_t``, one-sided, must exceed the critical value).
    """
    cam = camera(cam)
    lam, emission = sphere_emission()
    rho_fine = np.interp(lam, GRID_DEFAULT.wavelengths, rho)
    light = rg(channel_integral(cam, GRID_DEFAULT, lam, emission))
    k = np.asarray(every).shape[0]
    critical = critical_t(2 * 2 + 1, k)
    worst, distances = 0.0, []
    for samples, radiance in ((every, emission / (1 - rho_fine)), (one, emission * (1 + rho_fine))):
        expected = rg(channel_integral(cam, GRID_DEFAULT, lam, radiance))
        value, se = jackknife(samples, rg)
        worst = max(worst, float((np.abs(value - expected) / np.hypot(se, FLOAT32_FLOOR)).max()))
        distances.append(jackknife(samples, lambda m: np.linalg.norm(rg(m) - light, axis=-1)))
    (far, se_far), (near, se_near) = distances
    saturation_t = float((far - near) / np.hypot(se_far, se_near))
    passed = worst <= critical and saturation_t > critical
    test = (f"difference: max |t| ≤ {critical:.3g} over the 4 NCC values, and the saturation's t above it; Student t, "
            f"{k - 1} dof, Šidák over 5 at α {ALPHA:g}")
    return LimitCheck("closed_sphere", True, passed, worst / critical, 1.0, 0,
                      "the NCC (r, g) of a closed emitting sphere of the skin's reflectance, every bounce "
                      "(E / (1 − ρ)) and one (E (1 + ρ)); every bounce must saturate the colour more",
                      {"worst_t": worst, "critical": critical, "saturation_t": saturation_t,
                       "distance_from_light": [float(far), float(near)]}, outcome="pass" if passed else "fail",
                      test=test)


def limit_furnace(first, seeds, variant: str | None = None, say=lambda line: None) -> LimitCheck:
    """white furnace: the scene's mesh, reflectance 1, every bounce, in a uniform sky

    The check of the scene (and camera) of a validation's ``first`` render (a
    :class:`~skinrender.rendering.face.render.FaceRendering`), ``seeds`` one per replicate, small
    (:data:`FURNACE_SIZE`, :data:`FURNACE_SPP`); ``say``: a progress line."""
    from .effects import PHYSICS_REGISTRY, Level
    from .effects.interreflection import INTERREFLECTION

    say(f"white furnace ({FURNACE_SIZE}² px, {len(seeds)} × {FURNACE_SPP} spp) …")
    every_bounce = Level((PHYSICS_REGISTRY.base, INTERREFLECTION))
    return check_furnace(*furnace_radiance(first.camera, first.scene, seeds, FURNACE_SIZE, FURNACE_SPP, every_bounce,
                                           variant=variant))


def limit_sphere(first, seeds, variant: str | None = None, say=lambda line: None) -> LimitCheck:
    """closed Lambertian sphere of the skin's reflectance seen from inside, every bounce and one

    The check of the skin of a validation's ``first`` render, as :func:`limit_furnace` (:data:`SPHERE_SIZE`,
    :data:`SPHERE_SPP`)."""
    say(f"closed sphere ({SPHERE_SIZE}² px, {len(seeds)} × {SPHERE_SPP} spp, two depths) …")
    rho = skin_reflectance_of(first.skin, GRID_DEFAULT, "skin")
    every = sphere_channels(first.camera, rho, -1, seeds, SPHERE_SPP, SPHERE_SIZE, variant)
    one = sphere_channels(first.camera, rho, 2, seeds, SPHERE_SPP, SPHERE_SIZE, variant)
    return check_sphere(first.camera, rho, every, one)


LIMITS_SCENE_FREE = {"furnace": limit_furnace, "sphere": limit_sphere}
"""The limits that hold whatever the level, name → the function ``(first, seeds, variant, say) → LimitCheck`` of
a validation's first render; run small beside the level's own
(:func:`~skinrender.rendering.face.validation.validate_face_request` dispatches)."""
