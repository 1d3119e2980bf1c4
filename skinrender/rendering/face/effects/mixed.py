"""
Mixed light
===========

The second light (``[fill]``) and the uniform environment beside the key
light, each at its own temperature.

-   :data:`MIXED`: the effect.

No analytic limit holds: lights of different temperatures mix by each
pixel's geometry.
"""

from __future__ import annotations

from ....errors import SkinrenderError
from .base import Effect, Limits

__all__ = ["EFFECT", "MIXED"]


def _lights(lights: dict, scene) -> dict:
    """Every light of the scene: at least two of key, fill and environment, else a one-line error."""
    found = {name: getattr(scene, name) for name in ("key", "fill", "environment") if getattr(scene, name)}
    if len(found) < 2:
        raise SkinrenderError(f"physics 'mixed' needs a [fill] light or an [environment] beside the key "
                              f"light ({scene.source or scene.name})")
    return found


MIXED = Effect(
    "mixed",
    "the second light and the environment beside the key light, each at its own temperature",
    short="mixed light", lights=_lights,
    limits=Limits(holds=False, why="lights of different temperatures mix by each pixel's geometry: no analytic "
                                   "limit at this level"),
    order=40,
)

EFFECT = MIXED
"""This module's effect (the registry takes it: :mod:`.levels`)."""
