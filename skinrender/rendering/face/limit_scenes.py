"""
Scenes of the scene-free limits
===============================

The renders that :func:`~skinrender.rendering.face.limits.check_furnace` and
:func:`~skinrender.rendering.face.limits.check_sphere` check: a face scene's
mesh as a white furnace, and a closed emitting Lambertian sphere seen from
inside.

-   :func:`furnace_radiance`, :data:`FURNACE_SKY`: the white furnace.
-   :func:`sphere_channels`: the closed sphere (its emission:
    :func:`~skinrender.rendering.face.limits.sphere_emission`).

Units: radiance in the specfilm's units (W·m⁻²·sr⁻¹ times the sensitivity's
unit), wavelengths nm, temperatures K, illuminance lx.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...hints import NDArrayFloat
from ...model.camera import Camera, camera
from ...spectra import GRID_DEFAULT
from .document import channel_groups, channel_integral, film_dict, light_irradiance
from .limits import sphere_emission
from .scene import FaceScene, Light, load_face_scene

__all__ = ["FURNACE_SKY", "REPLICATES_DEFAULT", "furnace_radiance", "sphere_channels"]

FURNACE_SKY = Light(temperature=5000.0, illuminance=500.0)
"""The white furnace's uniform environment: a 5000 K Planckian, 500 lx on a surface open to it."""

REPLICATES_DEFAULT = 12
"""Seeds rendered unless named (:data:`skinrender.rendering.face.limits.REPLICATES`)."""


def furnace_radiance(cam: Camera | str, scene: FaceScene | str = "face", seeds=range(REPLICATES_DEFAULT),
                     size: int = 32,
                     spp: int = 16, physics: str = "interreflection", variant: str | None = None,
                     sky: Light = FURNACE_SKY) -> tuple[NDArrayFloat, NDArrayFloat, NDArrayFloat]:
    """
    The white furnace rendered: the scene's mesh alone, reflectance 1, inside a uniform sky.

    Returns
    -------
    tuple
        ``(radiance, labels, expected)``: the replicates' radiance ``(K, size,
        size, 3)`` and the label image (specfilm units), and ``∫ (E / π) x_k dλ``,
        the sky's radiance through the camera, ``(3,)``.
    """
    from .render import render_face

    furnace = replace(load_face_scene(scene), props=(), key=None, fill=None, environment=sky)
    renders = [render_face(cam, furnace, skin="perfect", physics=physics, size=size, spp=spp, seed=int(s),
                           variant=variant) for s in seeds]
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
    from ..renderer import _spectrum
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
                       "emitter": {"type": "area", "radiance": _spectrum(lam, emission)},
                       "bsdf": {"type": "diffuse", "reflectance": _spectrum(GRID_DEFAULT.wavelengths, rho)}},
        })
        for row, seed in enumerate(seeds):
            image = np.array(mi.render(scene, seed=int(seed)), dtype=np.float64)
            out[row, list(group)] = image.reshape(-1, len(group)).mean(axis=0)
    return out
