"""
Subsurface scattering, volumetric: the reference
================================================

Level ``subsurface-volume`` (until issue 34 it was named ``subsurface``,
which is now the fast transport of
:mod:`~skinrender.rendering.face.effects.subsurface_table`). The skin as the
skin model's two layers under a rough dielectric boundary (Mitsuba 3 has no
BSSRDF), path traced by the project's own integrator
(:mod:`~skinrender.rendering.skin_integrator`): light enters the skin,
scatters under it and leaves it elsewhere.

-   :data:`SUBSURFACE_VOLUME`: the effect; :data:`SUBSURFACE_ALPHA`,
    :data:`SCENE_SCALE_SUBSURFACE`, :data:`SAMPLES_PER_S_SUBSURFACE`.
-   :func:`face_media`: the layers the face renders for a skin spec.

The layers
----------
The skin model's two layers of the face's skin
(:func:`~skinrender.rendering.subsurface.skin_media_of`: its ``skin-model:``
parameters, or the model fitted to a measured reflectance and refused when it
does not fit): the epidermis (``epidermis_mm``, 0.1 mm by default) over the
dermis, semi-infinite under the scan's surface. No offset mesh: the
integrator tracks a path's depth below the skin along the normal where it
last touched the surface, and the epidermis is what lies within
``epidermis_mm`` of it (locally flat layers); a scattering within
:data:`~skinrender.rendering.skin_integrator.REANCHOR_DEPTH_MM` of the
epidermis measures its depth again, to the surface straight above it. The
condition: where the skin curves with radius ``R``, the boundary between the
layers drifts by ``l² / 2R`` over a straight path of length ``l`` from where
the depth was last measured, so the layers are right where that is small
against the epidermis for the flights that cross it, a few mean free paths
(~0.02–0.1 mm): ``R ≫ 0.05 mm`` — every surface of the scan. Measured on
spheres of skin against the same spheres with an offset sphere as the
layers' boundary: within 1 % at a radius of 2 mm, where depth from the last
contact alone was 22 % off (``docs/subsurface.md``).

Every free flight is sampled from the true point the path is at, so the
render does not depend on where the face is: the face translated by 100 mm
renders as at its place (``docs/subsurface.md``), where ``volpathmis``, whose
rays started ~0.01 mm inside the skin, had rendered a slab up to 5 % (light
skin) and 16 % (dark) dark 100–200 mm away.
The document is written in millimetres (:data:`SCENE_SCALE_SUBSURFACE`),
where Mitsuba's ray offsets, which only the intersection queries now see, are
smallest.

The boundary is a rough dielectric (GGX, :data:`SUBSURFACE_ALPHA`, the skin
model's ``n``): the key and fill lights are points, which a smooth dielectric
would never let into the skin. It is the skin's surface, so with ``sheen``
(placed before it in the registry) this boundary replaces the coat: its
Fresnel reflection is the highlight. The integrator path traces every bounce,
so light from the props reaches the face too, as with ``interreflection``,
and it hides the skies from the camera as the base level does (the background
black).

Its limits
----------
None holds: light leaving the skin has travelled under it along paths whose
length and depth depend on where it entered and in which direction, so its
spectrum changes with the angles of incidence and view, and the shading no
longer cancels in NCC. The flat slab against adding-doubling is the check of
this physics (``validate CHART --physics subsurface-volume``,
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
from ...subsurface import check_truncation, integrator_dict, medium_dict, skin_media_of, subsurface_variant
from .base import Effect, Limits, Setup

__all__ = ["EFFECT", "SUBSURFACE_VOLUME", "SUBSURFACE_ALPHA", "SCENE_SCALE_SUBSURFACE", "SAMPLES_PER_S_SUBSURFACE", "face_media"]

SUBSURFACE_ALPHA = 0.35
"""GGX roughness α of the skin's boundary, as ``sheen``'s coat (Weyrich et al. 2006 fit 0.3–0.45 to faces)."""

SCENE_SCALE_SUBSURFACE = 1000.0
"""The face's Mitsuba document in millimetres (scene units per metre)."""

SAMPLES_PER_S_SUBSURFACE = 30000.0
"""Samples per second of the face (the ``face`` scene) at this level on one core, the estimates' rate: 3.4–3.5 × 10⁴
per CPU second at 64 px × 64 spp and 128 px × 16 spp (``docs/subsurface.md``)."""


def face_media(spec: str, grid: WavelengthGrid):
    """
    The skin model's layers the face renders for a skin spec (a
    :class:`~skinrender.rendering.subsurface.SkinMedia`), refused where a walk cut at the depth cap could carry
    light (:func:`~skinrender.rendering.subsurface.check_truncation`). Cached per spec and grid.
    """
    return _face_media(str(spec).strip(), grid)


@lru_cache(maxsize=32)
def _face_media(spec: str, grid: WavelengthGrid):
    media = skin_media_of(spec, grid, "skin")
    check_truncation(media, "skin")
    return media


def _integrator(integrator: dict | None, setup: Setup) -> dict:
    """The skin's integrator, the base's choice of hiding the skies from the camera kept."""
    media = face_media(setup.skin or setup.scene.skin, setup.grid)
    hidden = bool((integrator or {}).get("hide_emitters"))
    return integrator_dict(media.layers, setup.grid, 1000.0 / SCENE_SCALE_SUBSURFACE, hide_emitters=hidden,
                           boundary_alpha=SUBSURFACE_ALPHA)


def _skin(material: dict, reflectance, setup: Setup) -> dict:
    """The rough boundary; the epidermis as its interior, which marks the shape as skin to the integrator."""
    epidermis, dermis = face_media(setup.skin or setup.scene.skin, setup.grid).layers
    boundary = {"type": "roughdielectric", "distribution": "ggx", "alpha": SUBSURFACE_ALPHA,
                "int_ior": float(dermis.n), "ext_ior": 1.0}
    return {**material, "bsdf": boundary,
            "interior": medium_dict(epidermis, setup.grid, 1000.0 / SCENE_SCALE_SUBSURFACE)}


SUBSURFACE_VOLUME = Effect(
    "subsurface-volume",
    "the volumetric reference: the skin as the skin model's two layers under a rough dielectric boundary, path "
    "traced (the project's skinvolpath; minutes): light scatters under the skin and leaves it elsewhere",
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
