"""
The registry of effects, and levels as their compositions
=========================================================

:class:`Registry` is a table of effects (name → :class:`~.base.Effect`) in the
order they apply, the base first, and the one parser of a physics spec
(``direct``, ``interreflection+sheen``) into a :class:`Level`, which applies
its effects in the table's order, whatever order they were named in. Each
scene kind has one (:data:`PHYSICS_REGISTRY`, the face's; a chart's is
:data:`skinrender.rendering.chart_effects.CHART_REGISTRY`), and a spec becomes a
:class:`Level` once, where a request is built
(:mod:`skinrender.rendering.request`): below it, functions take the level.

The face's effects are the modules of this package: each that defines
``EFFECT`` is registered by being here, in the order of its
:attr:`~.base.Effect.order` (a new effect is one module and its test module;
``docs/effects.md``). :func:`register` adds one from elsewhere (a test, a
user's plugin).

-   :class:`Registry`, :data:`PHYSICS_REGISTRY`, :data:`PHYSICS_EFFECTS` (its
    table), :data:`PHYSICS_BASE`, :func:`register`.
-   :data:`PHYSICS`: name → description (read from the registry);
    :data:`EFFECTS`: the names that add to the base.
-   :data:`EFFECTS_DEFAULT`, :data:`LEVELS_EACH`, :data:`LEVELS_LADDER`: the
    effects of the default levels (every effect but the volumetric reference,
    ``subsurface-volume``: :attr:`~.base.Effect.by_default`), the base and each
    of them alone (``bench render --scene``), and then all together
    (``ladder``, ``face-sweep``), as registered at import; :func:`levels_each`,
    :func:`levels_ladder`: the same read from the registry when called.
-   :func:`parse_physics`: a spec's effects as names (a tuple);
    :func:`physics_level`: a spec as a :class:`Level`.
-   :func:`active_lights`: the lights a level adds to a scene.
"""

from __future__ import annotations

import importlib
import pkgutil
import sys
from collections.abc import Iterator, Mapping, Sequence

from ...physics import Effect, Level
from ...registry import Registry
from ..scene import FaceScene, Light

__all__ = ["Registry", "PHYSICS_REGISTRY", "PHYSICS_EFFECTS", "PHYSICS_BASE", "PHYSICS", "EFFECTS", "EFFECTS_DEFAULT",
           "LEVELS_EACH",
           "LEVELS_LADDER", "Level", "register", "levels_each", "levels_ladder", "parse_physics", "physics_level",
           "active_lights"]


def _discovered() -> dict[str, Effect]:
    """The ``EFFECT`` of every module of this package, in the order of their :attr:`~.base.Effect.order`."""
    package = sys.modules[__package__]
    found = []
    for info in pkgutil.iter_modules(package.__path__):
        if info.name not in ("base", "levels"):
            effect = getattr(importlib.import_module(f"{__package__}.{info.name}"), "EFFECT", None)
            if isinstance(effect, Effect):
                found.append(effect)
    found.sort(key=lambda effect: (effect.order, effect.name))
    names = [effect.name for effect in found]
    twice = sorted({name for name in names if names.count(name) > 1})
    if twice:
        raise RuntimeError(f"effects registered twice: {', '.join(twice)}")
    return {effect.name: effect for effect in found}


PHYSICS_EFFECTS: dict[str, Effect] = _discovered()
"""The face's effects of physics, name → :class:`~.base.Effect`, in the order a level applies them (and names
them: ``interreflection+sheen+mixed+noise``). The first is the base. Read live by :data:`PHYSICS_REGISTRY`: an
effect added to it (:func:`register`, or a test's ``monkeypatch.setitem``) is a level at once."""

PHYSICS_BASE = next(iter(PHYSICS_EFFECTS))
"""The base every level starts from: ``direct``."""


class _Descriptions(Mapping):
    """name → one-line description of every registered effect, read from :data:`PHYSICS_EFFECTS` when asked."""

    def __getitem__(self, name: str) -> str:
        return PHYSICS_EFFECTS[name].description

    def __iter__(self) -> Iterator[str]:
        return iter(PHYSICS_EFFECTS)

    def __len__(self) -> int:
        return len(PHYSICS_EFFECTS)

    def __repr__(self) -> str:
        return repr(dict(self))


PHYSICS: Mapping[str, str] = _Descriptions()
"""Levels of physics, name → meaning (the registry's descriptions). ``direct`` is the base; the others each
add one effect to it and combine with ``+`` (``interreflection+sheen+mixed``)."""

EFFECTS = tuple(name for name in PHYSICS_EFFECTS if name != PHYSICS_BASE)
"""The effects that add to ``direct``, in ladder order."""

EFFECTS_DEFAULT = tuple(name for name in EFFECTS if PHYSICS_EFFECTS[name].by_default)
"""The effects of the default levels (:attr:`~.base.Effect.by_default`: all but ``subsurface-volume``, the
volumetric reference, which a user names)."""

LEVELS_EACH = (PHYSICS_BASE, *EFFECTS_DEFAULT)
"""The base and each default effect alone (the face bench's and the effects table's levels)."""

LEVELS_LADDER = (*LEVELS_EACH, "+".join(EFFECTS_DEFAULT))
"""The base, each default effect alone, then all of them (the ladder's and the face sweep's levels)."""

PHYSICS_REGISTRY = Registry(PHYSICS_EFFECTS)
"""The face's registry of effects (its table: :data:`PHYSICS_EFFECTS`)."""


def register(effect: Effect) -> Effect:
    """Register a face effect from outside this package (a test, a plugin): :meth:`Registry.register`."""
    return PHYSICS_REGISTRY.register(effect)


def levels_each(registry: Registry = PHYSICS_REGISTRY) -> tuple[str, ...]:
    """The base and each named effect of the default levels alone (:meth:`Registry.by_default`), as registered
    now."""
    return tuple(registry.by_default)


def levels_ladder(registry: Registry = PHYSICS_REGISTRY) -> tuple[str, ...]:
    """The base, each named effect of the default levels alone, then all of them together, as registered now (the
    ladder's)."""
    each = levels_each(registry)
    return (*each, "+".join(each[1:])) if len(each) > 2 else each


def parse_physics(spec: str) -> tuple[str, ...]:
    """
    The effects of a face's physics spec, in the registry's order (``()`` for ``direct``):
    :meth:`Registry.names` of :data:`PHYSICS_REGISTRY`.

    Examples
    --------
    >>> parse_physics("sheen+interreflection")
    ('interreflection', 'sheen')
    >>> parse_physics("direct")
    ()
    """
    return PHYSICS_REGISTRY.names(spec)


def physics_level(spec: str | Sequence[str] | Level) -> Level:
    """
    A face's level of physics from a spec (``direct``, ``sheen+noise``), a sequence of effect names (``()`` is
    ``direct``) or a :class:`Level` (returned as it is): :meth:`Registry.level` of :data:`PHYSICS_REGISTRY`.

    Examples
    --------
    >>> level = physics_level("noise+sheen")
    >>> level.name, "sheen" in level, [effect.name for effect in level.effects]
    ('sheen+noise', True, ['direct', 'sheen', 'noise'])
    """
    if isinstance(spec, Level):
        return spec
    return PHYSICS_REGISTRY.level(spec)


def active_lights(scene: FaceScene, effects: str | Sequence[str] | Level) -> dict[str, Light]:
    """
    The lights of a render: ``key`` and its ambient sky (or, in a scene without a key, the ``environment``);
    with ``mixed`` ``key``, ``fill`` and ``environment`` instead (:meth:`Level.lights`).
    """
    return physics_level(effects).lights(scene)
