"""
A scene kind's registry of effects
==================================

:class:`Registry`: a scene kind's effects of physics (name →
:class:`~skinrender.rendering.physics.Effect`, the base first) and the one
parser of a physics spec (``direct``, ``interreflection+sheen``) into a
:class:`~skinrender.rendering.physics.Level`; it also hands each effect its
options (:meth:`Registry.with_options`: an ``imager`` adds ``noise``, the one
place that rule is written) and adds effects (:meth:`Registry.register`).
The face's is :data:`skinrender.rendering.face.effects.PHYSICS_REGISTRY`, a
chart's :data:`skinrender.rendering.chart_effects.CHART_REGISTRY`; a spec
becomes a level only here, where a request is built.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from ..errors import SkinrenderError
from ..methods import validate_method
from .physics import Effect, Level

__all__ = ["Registry"]


class Registry:
    """
    A scene kind's effects of physics, name → :class:`Effect`, in the order a level applies them, the base
    first; the one parser of a physics spec into a :class:`Level`.

    Parameters
    ----------
    effects
        The table, read live (an effect added to it is a level at once).
    what
        How a refusal names a spec: ``physics ({spec!r})`` (the face's), ``physics (of a chart)``.
    """

    def __init__(self, effects: dict[str, Effect], what: str = "physics ({spec!r})"):
        self.effects, self.what = effects, what

    def __repr__(self) -> str:
        return f"Registry({', '.join(self.effects)})"

    @property
    def base(self) -> Effect:
        """The effect every level starts from (the table's first)."""
        return next(iter(self.effects.values()))

    @property
    def named(self) -> dict[str, Effect]:
        """The effects a user may name in a spec (:attr:`Effect.named`), in order."""
        return {name: effect for name, effect in self.effects.items() if effect.named}

    @property
    def by_default(self) -> dict[str, Effect]:
        """The named effects of the default levels (:attr:`Effect.by_default`: all but a reference a user names,
        ``subsurface-volume``), in order."""
        return {name: effect for name, effect in self.named.items() if effect.by_default}

    def register(self, effect: Effect) -> Effect:
        """Add ``effect`` in the place of its :attr:`Effect.order` (after the base); a name taken is refused."""
        if not isinstance(effect, Effect) or effect.name in self.effects:
            raise SkinrenderError(f"register: an effect of a new name, got {getattr(effect, 'name', effect)!r}")
        items = sorted([*self.effects.values(), effect], key=lambda e: (e is not self.base, e.order))
        self.effects.clear()
        self.effects.update({e.name: e for e in items})
        return effect

    def names(self, spec: str) -> tuple[str, ...]:
        """The effects of a spec, in the registry's order (``()`` for the base); a bad spec refused, its role
        ``physics``."""
        text = str(spec).strip()
        parts = [part.strip() for part in text.split("+")]
        base = self.base.name
        for part in parts:
            validate_method(part, self.named, self.what.format(spec=text), role="physics")
        if base in parts and len(parts) > 1:
            raise SkinrenderError(f"physics: {base!r} is the base and combines with nothing, got {text!r}",
                                  role="physics")
        twice = sorted({part for part in parts if parts.count(part) > 1})
        if twice:
            raise SkinrenderError(f"physics: {', '.join(twice)} named twice in {text!r}; name each effect once",
                                  role="physics")
        for part in parts:
            clash = [other for other in self.effects[part].excludes if other in parts]
            if clash:
                raise SkinrenderError(f"physics: {part!r} and {clash[0]!r} are two transports of the same skin and "
                                      f"do not combine, got {text!r}; name one", role="physics")
        return tuple(name for name in self.effects if name in parts and name != base)

    def level(self, spec: str | Sequence[str] | Level) -> Level:
        """A :class:`Level` from a spec, a sequence of effect names (``()``: the base) or a level of this registry
        (returned as it is)."""
        if isinstance(spec, Level):
            alien = [effect.name for effect in spec.effects if self.effects.get(effect.name) != effect]
            if alien:
                raise SkinrenderError(f"physics: {', '.join(alien)} {'is' if len(alien) == 1 else 'are'} not of "
                                      f"this scene's effects ({', '.join(self.named)})", role="physics")
            return spec
        if not isinstance(spec, str):
            spec = "+".join(spec) or self.base.name
        return self._level(self.names(spec))

    def _level(self, names) -> Level:
        return Level((self.base, *(self.effects[name] for name in self.effects if name in names
                                   and name != self.base.name)))

    def options_for(self, level: Level, given: Mapping[str, object]) -> dict[str, object]:
        """
        The keywords of ``given`` that an effect of ``level`` owns, the others dropped: a study over several levels
        (the ladder, a sweep) hands its sensor's options to the levels with the sensor only (where they would
        otherwise add it, :meth:`with_options`).
        """
        owned = {option for effect in level.effects for option in effect.option_names()}
        return {key: value for key, value in given.items() if key in owned}

    def with_options(self, level: Level, given: Mapping[str, object]) -> tuple[Level, dict[str, object]]:
        """
        The level and its effects' options from flat keywords ``given`` (``imager=…``, ``exposure=…``): each
        keyword goes to the effect of this registry whose :attr:`Effect.options` has it (made and checked
        there); an effect the level lacks is added where the keyword is in its :attr:`Effect.added_by`
        (an imager adds ``noise``: the one place that rule is written), and any other keyword of it is refused,
        naming it. ``given``'s ``None`` values count as not given. Returns ``(level, {effect name: options})``.
        """
        given = {key: value for key, value in given.items() if value is not None}
        owners = {option: effect for effect in self.effects.values() for option in effect.option_names()}
        unknown = sorted(set(given) - set(owners))
        if unknown:
            raise SkinrenderError(f"{', '.join(unknown)}: not an effect's option; the options: "
                                  f"{', '.join(owners) or 'none'}", role=unknown[0])
        names = set(level.names)
        options = {}
        for effect in self.effects.values():
            mine = {key: value for key, value in given.items() if owners[key] is effect}
            if not mine:
                continue
            options[effect.name] = effect.options(**mine)  # each value checked, its role its name
            if effect.name not in names and effect is not self.base:
                adding = [key for key in mine if key in effect.added_by]
                if not adding:
                    key = sorted(mine)[0]
                    ways = [f"a level with {effect.name}"] * effect.named + (
                        [f"{' or '.join(effect.added_by)}, which adds it"] if effect.added_by else [])
                    raise SkinrenderError(f"{key} is an option of the {effect.short or effect.name} ({effect.name}): "
                                          f"it goes with {' or with '.join(ways)}", role=key)
                names.add(effect.name)
        level = self._level(names)
        return level, level.default_options(options)
