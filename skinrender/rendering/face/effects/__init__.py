"""
Effects of physics
==================

Each effect a face render can add (interreflection, a sheen coat, mixed
lights, sensor noise) is one module here, with one
:class:`~skinrender.rendering.face.effects.base.Effect` that supplies what it
changes: the integrator, the skin's and props' materials, the lights, the
post-processing after the render, and its analytic limits. A level of physics
is a composition of them (:class:`Level`); :data:`PHYSICS_REGISTRY` (its table
:data:`PHYSICS_EFFECTS`) is the one registry every part of skinrender reads.
A module here that defines ``EFFECT`` is registered by being here; an effect
owns its options (``options``: a dataclass, e.g. ``noise``'s
:class:`~skinrender.rendering.sensor.NoiseOptions`).

-   :mod:`~skinrender.rendering.face.effects.base`: what an effect supplies.
-   :mod:`~skinrender.rendering.face.effects.levels`: the registry, levels,
    :func:`parse_physics`, :func:`physics_level`, :func:`register` (the
    classes: :mod:`skinrender.rendering.physics`).
-   :mod:`~skinrender.rendering.face.effects.direct` (the base),
    :mod:`~skinrender.rendering.face.effects.interreflection`,
    :mod:`~skinrender.rendering.face.effects.sheen`,
    :mod:`~skinrender.rendering.face.effects.subsurface_table` (``subsurface``),
    :mod:`~skinrender.rendering.face.effects.subsurface` (``subsurface-volume``),
    :mod:`~skinrender.rendering.face.effects.mixed`,
    :mod:`~skinrender.rendering.face.effects.noise`: the effects.

How to add one: ``docs/effects.md``.
"""

from __future__ import annotations

from .base import Effect, Frame, Limits, Measured, Replicates, Setup
from .levels import (EFFECTS, EFFECTS_DEFAULT, LEVELS_EACH, LEVELS_LADDER, PHYSICS, PHYSICS_BASE, PHYSICS_EFFECTS,
                     PHYSICS_REGISTRY, Level, Registry, active_lights, levels_each, levels_ladder, parse_physics,
                     physics_level, register)

__all__ = ["Effect", "Limits", "Setup", "Frame", "Replicates", "Measured", "PHYSICS_EFFECTS", "PHYSICS_BASE",
           "PHYSICS", "EFFECTS", "EFFECTS_DEFAULT", "LEVELS_EACH", "LEVELS_LADDER", "PHYSICS_REGISTRY", "Level", "Registry", "register",
           "levels_each", "levels_ladder", "parse_physics", "physics_level", "active_lights"]
