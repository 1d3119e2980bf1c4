"""
Subsurface scattering, fast: the slab's angular reflectance as a BSDF
=====================================================================

The skin as what the skin model's layers reflect, read from a table rather
than path traced through them: adding-doubling gives, per wavelength, how
much of the light arriving from each direction a flat, laterally infinite
slab of the layers returns into each other direction
(:class:`~skinrender.rendering.slab_table.SlabTable`, from the skin spec's
layers as :func:`~skinrender.rendering.subsurface.skin_media_of` gives them:
its ``skin-model:`` parameters or the model fitted to a measured skin), and
the :mod:`~skinrender.rendering.slab_bsdf` plugin renders it as the skin's
BSDF. Level ``subsurface``; the volumetric reference is
``subsurface-volume`` (:mod:`~skinrender.rendering.face.effects.subsurface`).

-   :data:`SUBSURFACE` (this module's ``EFFECT``): the effect; :data:`SETUP_SECONDS_TABLE`.

What it keeps and what it leaves out
------------------------------------
It is exact in the polar angles of incidence and exit for a flat slab
(to adding-doubling's quadrature and the table's interpolation,
``docs/subsurface.md``): the skin's colour changes with the angles as the
layers make it, light under the skin is absorbed by the epidermis on the
way in and out, and the boundary's Fresnel reflection is the highlight.
What it leaves out is **lateral transport**: light leaves the skin where it
entered, so it does not bleed across shadow edges or out of thin, curved
places (the nose, the ears' rims) as in the volumetric reference; and the
azimuth (adding-doubling averages over it). The surface reflection is GGX of
roughness :data:`~skinrender.rendering.face.effects.subsurface.SUBSURFACE_ALPHA`
(as the volumetric level's boundary and ``sheen``'s coat), so that the key
and fill, point lights, make highlights; the light under it is the smooth
boundary's table. With ``sheen`` this surface replaces the coat.

It changes the skin only: the integrator is the level's own (direct light at
``subsurface``; every bounce with ``interreflection``), so a level pays for
the transport it asks for and nothing more: per sample what ``direct`` costs,
and once per skin its table (:data:`SETUP_SECONDS_TABLE`).

Its limits
----------
None holds on the face: the table's colour depends on the angles, so the
shading no longer cancels in NCC. Its check is the flat patch under a uniform
sky, which reflects adding-doubling's ``UR1`` exactly (``validate CHART
--physics subsurface``, :mod:`skinrender.rendering.slab_chart`).

References
----------
-   :cite:`Prahl1995` : S. A. Prahl (1995). The adding-doubling method.
"""

from __future__ import annotations

from ...slab_bsdf import slab_bsdf_dict
from ...slab_table import slab_table
from .base import Effect, Limits, Setup, twosided
from .subsurface import SUBSURFACE_ALPHA

__all__ = ["EFFECT", "SUBSURFACE", "SETUP_SECONDS_TABLE"]

SETUP_SECONDS_TABLE = 2.5
"""One-off seconds on one core before a process's first render of a skin at this level: the fit of the skin model
to a measured skin (the face's own, ~1.3 s), the skin's table (~0.6 s) and the plugin's kernel, measured
(``tools/measure_fast_subsurface.py setup``, ``docs/subsurface.md``). Per sample the level costs what ``direct``
does (the same measurement), so it takes the base's rate."""


def _skin(material: dict, reflectance, setup: Setup) -> dict:
    table = slab_table(setup.skin or setup.scene.skin, setup.grid, "skin")
    return {**material, "bsdf": twosided(slab_bsdf_dict(table, SUBSURFACE_ALPHA))}


SUBSURFACE = Effect(
    "subsurface",
    "the skin as the skin model's layers, fast: a flat slab's angular reflectance from adding-doubling as the "
    "skin's BSDF (exact in angle for a flat slab; no light travels sideways under the skin)",
    short="subsurface scattering",
    skin=_skin,
    limits=Limits(holds=False, why="the slab's reflectance depends on the angles of incidence and view, so the "
                                   "skin's colour changes with the geometry and the shading no longer cancels: no "
                                   "analytic limit on the face (the flat patch under a uniform sky is checked "
                                   "against adding-doubling: validate a chart with --physics subsurface)"),
    setup_seconds=SETUP_SECONDS_TABLE, order=30,
)
"""The skin as the slab's table (module docstring)."""

EFFECT = SUBSURFACE
"""This module's effect (the registry takes it: :mod:`.levels`)."""
