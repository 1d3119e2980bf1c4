"""
Interreflection
===============

Every bounce: path tracing with Russian roulette (unbiased), so light reaches
the skin from the props and from the face itself.

-   :data:`INTERREFLECTION`: the effect; :data:`RUSSIAN_ROULETTE_DEPTH`.

No analytic limit holds: light bounced off other surfaces is no longer the
light's spectrum, so the shading no longer cancels in NCC.
"""

from __future__ import annotations

from .base import Effect, Limits, Setup

__all__ = ["EFFECT", "INTERREFLECTION", "RUSSIAN_ROULETTE_DEPTH"]

RUSSIAN_ROULETTE_DEPTH = 5
"""Path depth from which Russian roulette ends paths (Mitsuba's default; unbiased)."""


def _integrator(integrator: dict | None, setup: Setup) -> dict:
    """Path tracing, the base's choice of hiding the sky from the camera kept."""
    hidden = {"hide_emitters": True} if (integrator or {}).get("hide_emitters") else {}
    return {"type": "path", "max_depth": -1, "rr_depth": RUSSIAN_ROULETTE_DEPTH, **hidden}


INTERREFLECTION = Effect(
    "interreflection",
    "every bounce (path tracing, Russian roulette: unbiased): light from the props and from the face onto itself",
    integrator=_integrator,
    order=10,
    limits=Limits(holds=False, why="light reaches the skin from other surfaces (props, the face itself) and is "
                                   "no longer the light's spectrum: no analytic limit at this level"),
)

EFFECT = INTERREFLECTION
"""This module's effect (the registry takes it: :mod:`.levels`)."""
