"""
The registry of effects, and levels as their compositions
=========================================================

:data:`PHYSICS_EFFECTS` is the one table of effects (name → :class:`~.base.Effect`),
in the order they apply: the base, ``direct``, first. A level of physics is
the base alone (``direct``) or the base with effects joined by ``+``
(``interreflection+sheen``): a :class:`Level`, which applies its effects in
the table's order, whatever order they were named in. The renderer, the
validation, the ladder, the face sweep, the face bench and the command line
all read this table; nothing else lists the levels.

-   :data:`PHYSICS_EFFECTS`, :data:`PHYSICS_BASE`: the registry.
-   :data:`PHYSICS`: name → description (read from the registry);
    :data:`EFFECTS`: the names that add to the base.
-   :data:`EFFECTS_DEFAULT`, :data:`LEVELS_EACH`, :data:`LEVELS_LADDER`: the
    effects of the default levels (all but the volumetric reference,
    ``subsurface-volume``), the base and each of them alone (``bench render
    --scene``), and then all together (``ladder``, ``face-sweep``).
-   :func:`parse_physics`: a spec's effects as names (a tuple);
    :func:`physics_level`: a spec as a :class:`Level`.
-   :func:`active_lights`: the lights a level adds to a scene.

Adding an effect is one module beside the others (see ``docs/effects.md``)
and its line in :data:`PHYSICS_EFFECTS`.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass

from ....errors import SkinrenderError
from ....methods import validate_method
from ...variants import choose_variant
from ..scene import FaceScene, Light
from .base import Effect, Frame, Measured, Setup
from .direct import DIRECT
from .interreflection import INTERREFLECTION
from .mixed import MIXED
from .noise import NOISE
from .sheen import SHEEN
from .subsurface import SUBSURFACE_VOLUME
from .subsurface_table import SUBSURFACE

__all__ = ["PHYSICS_EFFECTS", "PHYSICS_BASE", "PHYSICS", "EFFECTS", "EFFECTS_DEFAULT", "LEVELS_EACH", "LEVELS_LADDER", "Level",
           "parse_physics", "physics_level", "active_lights"]

PHYSICS_EFFECTS: dict[str, Effect] = {effect.name: effect for effect in (
    DIRECT,
    INTERREFLECTION,
    SHEEN,
    SUBSURFACE,
    SUBSURFACE_VOLUME,
    MIXED,
    NOISE,
)}
"""The effects of physics, name → :class:`~.base.Effect`, in the order a level applies them (and names them:
``interreflection+sheen+mixed+noise``). The first is the base."""

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


@dataclass(frozen=True)
class Level:
    """
    A level of physics: the base and the effects added to it, applied in the registry's order.

    Attributes
    ----------
    effects
        The :class:`~.base.Effect` objects, the base first.
    """

    effects: tuple[Effect, ...]

    @property
    def names(self) -> tuple[str, ...]:
        """The effects added to the base, in the registry's order (``()`` for ``direct``)."""
        return tuple(effect.name for effect in self.effects[1:])

    @property
    def name(self) -> str:
        """``direct``, or the added effects joined by ``+``."""
        return "+".join(self.names) or self.effects[0].name

    def __contains__(self, name: object) -> bool:
        return any(effect.name == name for effect in self.effects)

    @property
    def document_key(self) -> tuple[str, ...]:
        """The added effects that change the Mitsuba document (not those acting after the render only)."""
        return tuple(effect.name for effect in self.effects[1:] if effect.changes_document)

    def _fold(self, part: str, value, *arguments):
        for effect in self.effects:
            function = getattr(effect, part)
            if function is not None:
                value = function(value, *arguments)
        return value

    def lights(self, scene: FaceScene) -> dict[str, Light]:
        """The lights a render of ``scene`` at this level adds, ``{name: Light}``; none: a one-line error."""
        lights = self._fold("lights", {}, scene)
        if not lights:
            raise SkinrenderError(f"face scene {scene.source or scene.name} has no light")
        return lights

    @staticmethod
    def setup(scene: FaceScene, camera, grid, lights: Mapping[str, Light], **after) -> Setup:
        """What the effects read (:class:`~.base.Setup`); ``after``: ``calibration``, ``seed``, ``imager``,
        ``exposure`` for ``post``."""
        return Setup(scene, camera, grid, lights, **after)

    @property
    def samples_per_s(self) -> float:
        """Samples per second of a face render at this level on one core: its slowest effect's rate."""
        return min(effect.samples_per_s for effect in self.effects if effect.samples_per_s is not None)

    def seconds(self, samples: float) -> float:
        """Seconds ``samples`` (pixels × spp) of one skin take at this level on one core (:attr:`samples_per_s`,
        and :attr:`setup_seconds` once)."""
        return float(samples) / self.samples_per_s + self.setup_seconds

    @property
    def setup_seconds(self) -> float:
        """One-off seconds on one core before the first render of a skin at this level (its effects'
        :attr:`~.base.Effect.setup_seconds`)."""
        return float(sum(effect.setup_seconds for effect in self.effects))

    @property
    def scene_scale(self) -> float:
        """Scene units per metre of its Mitsuba document (:attr:`~.base.Effect.scene_scale`)."""
        return max(effect.scene_scale for effect in self.effects)

    def choose_variant(self, requested: str | None = None) -> str:
        """The Mitsuba variant: the first effect's that chooses one (:attr:`~.base.Effect.variant`), else
        :func:`~skinrender.rendering.variants.choose_variant`'s."""
        for effect in self.effects:
            if effect.variant is not None:
                return effect.variant(requested)
        return choose_variant(requested)

    def integrator(self, setup: Setup) -> dict:
        """The Mitsuba integrator."""
        return self._fold("integrator", None, setup)

    def skin(self, reflectance, setup: Setup) -> dict:
        """The skin's shape properties (``{"bsdf": …}``) for its reflectance on ``setup.grid``."""
        return self._fold("skin", {}, reflectance, setup)

    def prop(self, reflectance, setup: Setup) -> dict:
        """A prop's shape properties for its reflectance."""
        return self._fold("prop", {}, reflectance, setup)

    def post(self, frame: Frame, setup: Setup) -> Frame:
        """The frame after every effect's post-processing."""
        return self._fold("post", frame, setup)

    def measure(self, images, first, imager=None) -> Measured:
        """The replicate images as the checks see them (:class:`~.base.Measured`)."""
        measured = Measured(images)
        for effect in self.effects:
            if effect.limits.measure is not None:
                measured = effect.limits.measure(measured, first, imager)
        return measured

    @property
    def check(self):
        """The analytic limit tested at this level (``(Replicates) → LimitCheck``), or ``None`` where none holds."""
        if any(not effect.limits.holds for effect in self.effects):
            return None
        checks = [effect.limits.check for effect in self.effects if effect.limits.check is not None]
        return checks[-1] if checks else None

    @property
    def why(self) -> str:
        """Why the level's check is what it is, or why there is none (``eq4_shift``'s reason)."""
        broken = [effect for effect in self.effects if not effect.limits.holds]
        deciding = broken[:1] or [effect for effect in self.effects if effect.limits.check is not None][-1:]
        return deciding[0].limits.why if deciding else "no analytic limit at this level"


def parse_physics(spec: str) -> tuple[str, ...]:
    """
    The effects of a physics spec, in the registry's order (``()`` for ``direct``).

    Examples
    --------
    >>> parse_physics("sheen+interreflection")
    ('interreflection', 'sheen')
    >>> parse_physics("direct")
    ()
    """

    text = str(spec).strip()
    parts = [part.strip() for part in text.split("+")]
    for part in parts:
        validate_method(part, PHYSICS_EFFECTS, f"physics ({text!r})")
    if PHYSICS_BASE in parts and len(parts) > 1:
        raise SkinrenderError(f"physics: {PHYSICS_BASE!r} is the base and combines with nothing, got {text!r}")
    twice = sorted({part for part in parts if parts.count(part) > 1})
    if twice:
        raise SkinrenderError(f"physics: {', '.join(twice)} named twice in {text!r}; name each effect once")
    for part in parts:
        clash = [other for other in PHYSICS_EFFECTS[part].excludes if other in parts]
        if clash:
            raise SkinrenderError(f"physics: {part!r} and {clash[0]!r} are two transports of the same skin and do "
                                  f"not combine, got {text!r}; name one")
    return tuple(name for name in PHYSICS_EFFECTS if name in parts and name != PHYSICS_BASE)


def physics_level(spec: str | Sequence[str] | Level) -> Level:
    """
    A level of physics from a spec (``direct``, ``sheen+noise``), a sequence of effect names (``()`` is
    ``direct``) or a :class:`Level` (returned as it is).

    Examples
    --------
    >>> level = physics_level("noise+sheen")
    >>> level.name, "sheen" in level, [effect.name for effect in level.effects]
    ('sheen+noise', True, ['direct', 'sheen', 'noise'])
    """

    if isinstance(spec, Level):
        return spec
    if not isinstance(spec, str):
        spec = "+".join(spec) or PHYSICS_BASE
    names = parse_physics(spec)
    return Level((PHYSICS_EFFECTS[PHYSICS_BASE], *(PHYSICS_EFFECTS[name] for name in names)))


def active_lights(scene: FaceScene, effects: str | Sequence[str] | Level) -> dict[str, Light]:
    """
    The lights of a render: ``key`` and its ``ambient`` sky (or, in a scene without a key, the ``environment``);
    with ``mixed`` ``key``, ``fill`` and ``environment`` instead (:meth:`Level.lights`).
    """
    return physics_level(effects).lights(scene)
