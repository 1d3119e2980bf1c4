"""
Subsurface scattering, volumetric: the reference
================================================

Level ``subsurface-volume`` (until issue 34 it was named ``subsurface``,
which is now the fast transport of
:mod:`~skinrender.rendering.face.effects.subsurface_table`). The skin as a participating medium inside a rough dielectric boundary
(Mitsuba 3 has no BSSRDF), path traced by ``volpathmis``: light enters the
skin, scatters under it and leaves it elsewhere.

-   :data:`SUBSURFACE_VOLUME`: the effect; :data:`SUBSURFACE_ALPHA`,
    :data:`SCENE_SCALE_SUBSURFACE`, :data:`SAMPLES_PER_S_SUBSURFACE`.
-   :func:`face_medium`: the one medium the face renders for a skin spec.

The medium
----------
The skin model's two layers of the face's skin
(:func:`~skinrender.rendering.subsurface.skin_media_of`: its ``skin-model:``
parameters, or the model fitted to a measured reflectance and refused when it
does not fit) become **one effective semi-infinite medium**
(:func:`~skinrender.rendering.subsurface.effective_layer`): the dermis'
scattering, ``g`` and ``n``, and the absorption per wavelength that gives the
same adding-doubling reflectance for collimated normal incidence as the two
layers. Why not the two layers, the epidermis inside an offset surface 0.1 mm
under the skin: Mitsuba starts a ray leaving a surface ``(1 + max|p|) ·
8.9e-5`` scene units off it (float32), which at the face, ~0.1 m from the
origin, is ~0.1 mm in metres and ~0.01 mm in millimetres: a ray entering the
skin would skip a tenth of the epidermis (and an offset surface 0.1 mm inside
a scanned mesh intersects itself). What the single medium misses: the
epidermis filters the light twice near the surface where the effective medium
spreads the absorption with depth, so under other light than collimated at
normal incidence the two differ (diffuse incidence: by up to 0.007, 0.012
and 0.006 in reflectance, 1.3, 3.8 and 3.9 % relative, at melanin 0.02, 0.1
and 0.3, measured with adding-doubling, ``docs/subsurface.md``).

The document is written in millimetres (:data:`SCENE_SCALE_SUBSURFACE`) for
the same reason; even so the skipped ~0.01 mm leaves a measured bias: a flat
slab of the effective medium 100 mm from the origin renders 6.0, 6.9 and
8.4 % (melanin 0.02) and 13, 15 and 16 % (melanin 0.3) darker than
adding-doubling gives (R, G, B), against agreement within the noise (≈ 1–2 %)
at the origin, where the chart's slabs are (``docs/subsurface.md``). The bias
grows towards blue, so it moves the skin's NCC too: Eq. 4's channels of the
bundled face's skin (gbell 9 @ 450, 540, 610, 2856 K balanced to 5900 K)
scaled by the melanin-0.02 factors move its NCC by 0.0034, most of its
detection budget (0.0042). The face's ``eq4_shift`` at this level holds this
artefact beside the physics.

The boundary is a rough dielectric (GGX, :data:`SUBSURFACE_ALPHA`, the skin
model's ``n``): the key and fill lights are points, which a smooth dielectric
would never let into the medium. It is the skin's surface, so with ``sheen``
(placed before it in the registry) this boundary replaces the coat: its
Fresnel reflection is the highlight. The integrator path traces every bounce
(:data:`~skinrender.rendering.subsurface.INTEGRATOR_SUBSURFACE`): light from
the props reaches the face too, as with ``interreflection``.

Its limits
----------
None holds: light leaving the skin has travelled under it along paths whose
length and depth depend on where it entered and in which direction, so its
spectrum changes with the angles of incidence and view, and the shading no
longer cancels in NCC (a prototype slab's NCC at 60° incidence minus at 0°:
Δr −0.020, Δg +0.010, z ≈ 4). The flat slab against adding-doubling is the
check of this physics (``validate CHART --physics subsurface-volume``,
:mod:`skinrender.rendering.subsurface_chart`).

Cost
----
Light scatters hundreds of times in skin before it leaves: a face render at
this level costs ~:data:`SAMPLES_PER_S_SUBSURFACE` samples per second on one
core, against ~9e5 without it, so the default levels (``ladder``,
``face-sweep``, the face bench) leave it out (:attr:`~skinrender.rendering.face.effects.base.Effect.by_default`):
name it (``--levels subsurface-volume``). :attr:`~skinrender.rendering.face.effects.base.Effect.samples_per_s`
gives the estimates this rate.
"""

from __future__ import annotations

from functools import lru_cache

from ....spectra import WavelengthGrid
from ...subsurface import (INTEGRATOR_SUBSURFACE, check_truncation, effective_layer, medium_dict, skin_media_of,
                           subsurface_variant)
from .base import Effect, Limits, Setup

__all__ = ["EFFECT", "SUBSURFACE_VOLUME", "SUBSURFACE_ALPHA", "SCENE_SCALE_SUBSURFACE", "SAMPLES_PER_S_SUBSURFACE", "face_medium"]

SUBSURFACE_ALPHA = 0.35
"""GGX roughness α of the skin's boundary, as ``sheen``'s coat (Weyrich et al. 2006 fit 0.3–0.45 to faces)."""

SCENE_SCALE_SUBSURFACE = 1000.0
"""The face's Mitsuba document in millimetres (scene units per metre)."""

SAMPLES_PER_S_SUBSURFACE = 1200.0
"""Samples per second of the face (the ``face`` scene) at this level on one core, measured
(``docs/subsurface.md``): the estimates' rate."""


def face_medium(spec: str, grid: WavelengthGrid):
    """
    The one medium the face renders for a skin spec (module docstring): the
    :func:`~skinrender.rendering.subsurface.effective_layer` of its layers, and the
    :class:`~skinrender.rendering.subsurface.SkinMedia` they come from. Cached per spec and grid.
    """
    return _face_medium(str(spec).strip(), grid)


@lru_cache(maxsize=32)
def _face_medium(spec: str, grid: WavelengthGrid):
    media = skin_media_of(spec, grid, "skin")
    check_truncation(media, "skin")
    return effective_layer(media.layers), media


def _integrator(integrator: dict | None, setup: Setup) -> dict:
    return dict(INTEGRATOR_SUBSURFACE)


def _skin(material: dict, reflectance, setup: Setup) -> dict:
    layer, _ = face_medium(setup.skin or setup.scene.skin, setup.grid)
    boundary = {"type": "roughdielectric", "distribution": "ggx", "alpha": SUBSURFACE_ALPHA,
                "int_ior": float(layer.n), "ext_ior": 1.0}
    return {**material, "bsdf": boundary, "interior": medium_dict(layer, setup.grid, 1000.0 / SCENE_SCALE_SUBSURFACE)}


SUBSURFACE_VOLUME = Effect(
    "subsurface-volume",
    "the volumetric reference: the skin as the skin model's layers (one effective medium) under a rough dielectric "
    "boundary, path traced (volpathmis; minutes): light scatters under the skin and leaves it elsewhere",
    short="volumetric subsurface scattering", excludes=("subsurface",), by_default=False,
    integrator=_integrator, skin=_skin,
    limits=Limits(holds=False, why="light leaves the skin after paths under it whose length depends on the angles "
                                   "of incidence and view, so the skin's colour changes with the geometry and the "
                                   "shading no longer cancels: no analytic limit on the face (the flat slab is "
                                   "checked against adding-doubling: validate a chart with --physics subsurface-volume)"),
    samples_per_s=SAMPLES_PER_S_SUBSURFACE, scene_scale=SCENE_SCALE_SUBSURFACE, variant=subsurface_variant,
    order=35,
)
"""The skin as a medium (module docstring)."""

EFFECT = SUBSURFACE_VOLUME
"""This module's effect (the registry takes it: :mod:`.levels`)."""
