"""
The base level: direct
======================

Lambertian skin and props under the key light and its ambient sky (a uniform
environment of the key's own spectrum, the scene's ``[key] ambient`` share of
its illuminance: no pure-black shadow), or, in a scene without a key light,
the uniform environment; direct lighting only: the analytic model's world,
shading aside. Every level starts from it.

-   :data:`DIRECT`: the effect; its rate
    :data:`~skinrender.rendering.physics.SAMPLES_PER_S_DIRECT`.

Its limit: under light of one Planckian spectrum with direct light only a
skin pixel's radiance is ``ρ(λ) E(λ) G``, the shading ``G`` (the key's and
the sky's shares included) independent of λ, so its NCC is Eq. 4's
(:func:`~skinrender.rendering.face.limits.check_shading`).
"""

from __future__ import annotations

from ...physics import SAMPLES_PER_S_DIRECT, SECONDS_PER_RENDER
from ..limits import check_shading
from .base import Effect, Limits, Replicates, Setup, spectrum, twosided

__all__ = ["EFFECT", "DIRECT", "SAMPLES_PER_S_DIRECT", "SECONDS_PER_RENDER"]
"""(:data:`SAMPLES_PER_S_DIRECT` and :data:`SECONDS_PER_RENDER`, the base's rate and a render's fixed cost, are
:mod:`skinrender.rendering.physics`'s, here for the code that read them here.)"""


def _integrator(integrator: dict | None, setup: Setup) -> dict:
    """
    One light sample per hit; a BSDF sample only where it can meet a light (the environment). In a lamp-lit
    scene (one with a key light) the sky lights the face but is hidden from the camera: the background stays
    black, and the silhouette's pixels are skin and black, not skin and sky (which would pull their NCC towards
    the light's colour). A scene lit by its environment alone (the white furnace) sees it.
    """
    points = all(light.position is not None for light in setup.lights.values())
    hidden = {"hide_emitters": True} if setup.scene.key is not None and not points else {}
    return {"type": "direct", "emitter_samples": 1, "bsdf_samples": 0 if points else 1, **hidden}


def _lambertian(material: dict, reflectance, setup: Setup) -> dict:
    return {"bsdf": twosided({"type": "diffuse", "reflectance": spectrum(setup.grid, reflectance)})}


def _lights(lights: dict, scene) -> dict:
    """The key light and its ambient sky, or in a scene without a key the environment; none: ``{}`` (refused by
    the level)."""
    if scene.key is not None:
        ambient = scene.ambient_light
        return {"key": scene.key} if ambient is None else {"key": scene.key, "ambient": ambient}
    if scene.environment is not None:
        return {"environment": scene.environment}
    return {}


def _check(replicates: Replicates):
    r = replicates
    return check_shading(r.images, r.labels, r.expected, r.usable, r.bias, r.floor)


DIRECT = Effect(
    "direct",
    "Lambertian skin and props under the key light and its ambient sky of the same spectrum, direct lighting only "
    "(Mitsuba's direct integrator): the analytic model's world, shading aside",
    integrator=_integrator, skin=_lambertian, prop=_lambertian, lights=_lights,
    limits=Limits(check=_check, why="the shading check is the test at this level"),
    samples_per_s=SAMPLES_PER_S_DIRECT,
    order=0,
)
"""The base of every level."""

EFFECT = DIRECT
"""This module's effect (the registry takes it: :mod:`.levels`)."""
