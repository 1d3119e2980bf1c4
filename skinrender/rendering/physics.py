"""
Effects of physics and levels
=============================

What every scene kind's physics is made of: an :class:`Effect` (one effect of
physics: what it changes in a render, its analytic limits, its options), a
:class:`Level` (the base and the effects added to it, applied in their
registry's order) and a registry (:class:`~skinrender.rendering.registry.Registry`: a scene
kind's table of effects and the one parser of a physics spec into a level). The face's registry is
:data:`skinrender.rendering.face.effects.PHYSICS_REGISTRY` (its effects one
module each, :mod:`skinrender.rendering.face.effects`, where the parts an
effect supplies are described); a chart's is
:data:`skinrender.rendering.chart_effects.CHART_REGISTRY`.

A physics spec becomes a :class:`Level` once, where a request is built
(:mod:`skinrender.rendering.request`): below it, functions take the level,
never the spec.

-   :class:`Effect`, :class:`Limits`: an effect and its analytic limits.
-   :class:`Level`: a composition of effects.
-   :class:`~skinrender.rendering.effect_inputs.Setup`, ``Frame``, ``Replicates``, ``Measured``: what an
    effect's functions read and return (:mod:`skinrender.rendering.effect_inputs`, importable here).
-   :data:`SAMPLES_PER_S_DIRECT`, :data:`SECONDS_PER_RENDER`: the base's
    rate and a render's fixed cost, the estimates'.

A scene kind's table of effects and its parser are a
:class:`~skinrender.rendering.registry.Registry`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from ..errors import SkinrenderError
from .effect_inputs import Frame, Measured, Replicates, Setup  # noqa: F401 (their home before)
from .variants import choose_variant

if TYPE_CHECKING:
    from .face.scene import FaceScene, Light

__all__ = ["SAMPLES_PER_S_DIRECT", "SECONDS_PER_RENDER", "Setup", "Frame", "Replicates", "Measured", "Effect",
           "Limits", "Level"]


SAMPLES_PER_S_DIRECT = 9e5
"""Samples per second of a render at the base level on one core (one drjit thread), the estimates' rate for every
level that costs no more: fitted with :data:`SECONDS_PER_RENDER` to two measured sweeps of the face (the
measurements and their commands: docs/speed.md, "The rates behind the estimates")."""

SECONDS_PER_RENDER = 0.15
"""Fixed cost of one face render on one core (scene, cached kernels, labels, scoring), s: the estimates' base;
fitted with :data:`SAMPLES_PER_S_DIRECT` to two measured sweeps of 54 renders (direct, sheen, all effects) with one
worker at 64 px, 32 spp and 128 px, 64 spp (the measurements and their commands: docs/speed.md, "The rates
behind the estimates")."""


@dataclass(frozen=True)
class Limits:
    """
    An effect's analytic limits.

    Attributes
    ----------
    check
        ``(replicates: Replicates) → LimitCheck``: the test of a level this effect is in (a later
        effect's check replaces an earlier one's: ``sheen``'s dichromatic plane replaces ``direct``'s
        shading), or ``None``.
    holds
        ``False`` when no analytic limit holds with the effect (``interreflection``, ``mixed``): a level
        with it has no check, only ``eq4_shift``.
    why
        Why the level's check is what it is (or why there is none): ``eq4_shift``'s reason. A level
        takes it from its first effect that breaks the limits, else from the effect whose check it runs.
    measure
        ``(measured: Measured, first, options) → Measured``: how the replicate images become the values
        checked (a sensor's dark signal, clipping and quantisation; ``options``: the effect's own,
        :attr:`Effect.options`), or ``None``.
    """

    check: Callable | None = None
    holds: bool = True
    why: str | None = None
    measure: Callable | None = None


@dataclass(frozen=True)
class Effect:
    """
    One effect of physics (:mod:`skinrender.rendering.face.effects.base` describes what each part does).

    Attributes
    ----------
    name
        What a user types (``--physics NAME``), a key of the registry.
    description
        One line: what the effect renders (the CLI's help shows it).
    short
        A few words for lists in prose (``mixed light``); default the name.
    integrator, skin, prop, lights, post
        What it changes, or ``None``.
    limits
        Its analytic limits.
    samples_per_s
        Samples per second of a face render with this effect on one core, measured: the estimates' rate
        (``None``: it costs no more than the base). A level runs at the slowest of its effects' rates.
    scene_scale
        Scene units per metre of the Mitsuba document (1: metres). Mitsuba starts a ray leaving a surface
        ``(1 + max|p|) · 8.9e-5`` scene units off it: in metres, ~0.1 mm at the face; in millimetres (1000),
        ~0.01 mm. A level writes its document at the largest of its effects' scales.
    variant
        ``(requested) → variant``: the Mitsuba variant the effect renders best with (``requested``: the one the
        user named, or ``None``), or ``None`` to leave the choice to
        :func:`~skinrender.rendering.variants.choose_variant`.
    order
        Its place in its registry (the base lowest): a level applies its effects, and names them, in this order.
        An effect module in ``skinrender/rendering/face/effects/`` defines ``EFFECT`` and is registered by
        being there (:mod:`~skinrender.rendering.face.effects.levels`).
    options
        The frozen dataclass of the effect's options (its fields with their defaults and units, bounds checked in
        its ``__post_init__``), or ``None``: a request holds one per effect of its level, by effect name.
    added_by
        The options whose presence adds the effect to a level (``noise``: ``imager``, an imager records the
        render); any other option of an effect the level lacks is refused.
    named
        Whether a user names it in a physics spec (a chart's sensor comes with ``imager`` only).
    sampler
        The sampler a level with it renders with unless one is asked for (``None``: the settings').
    scene, refuse, chart
        See :mod:`skinrender.rendering.face.effects.base`.
    estimate
        ``(request, cores) → (seconds, what)``: one render on ``cores`` cores and what it is in words, where
        pixels × spp / :attr:`samples_per_s` does not give it (a subsurface chart: its skin patches, or its tables), or
        ``None``.
    prepare
        ``(request) → None``: work done once the request's time is accepted, before any render, that may still
        refuse it (a subsurface chart fits its skin patches' layers: one that is not skin is refused), or ``None``.
    refuses
        What a validation at a level with it does not take, option → why (a subsurface chart's ``gamut`` and
        ``spp_auto``).
    setup_seconds
        One-off seconds on one core before a process's first render of a skin with it (the fast ``subsurface``'s
        table), measured: the estimates add it once per level and skin.
    excludes, by_default
        Effects it does not combine with (two transports of one skin); whether the default levels (``ladder``,
        ``face-sweep``, the face bench) hold it (``False``: ``subsurface-volume``, which a user names).
    """

    name: str
    description: str
    short: str = ""
    integrator: Callable | None = None
    skin: Callable | None = None
    prop: Callable | None = None
    lights: Callable | None = None
    post: Callable | None = None
    limits: Limits = field(default_factory=Limits)
    samples_per_s: float | None = None
    scene_scale: float = 1.0
    variant: Callable | None = None
    order: float = 0.0
    options: type | None = None
    added_by: tuple[str, ...] = ()
    named: bool = True
    sampler: str | None = None
    scene: Callable | None = None
    refuse: Callable | None = None
    chart: Callable | None = None
    estimate: Callable | None = None
    prepare: Callable | None = None
    refuses: Mapping[str, str] = field(default_factory=dict, compare=False, hash=False)
    setup_seconds: float = 0.0
    excludes: tuple[str, ...] = ()
    by_default: bool = True

    def __repr__(self) -> str:
        return f"Effect({self.name!r})"

    @property
    def changes_document(self) -> bool:
        """Whether it changes the Mitsuba document (else it acts after rendering only)."""
        return any(part is not None for part in (self.integrator, self.skin, self.prop, self.lights)) or \
            self.scene_scale != 1.0

    def option_names(self) -> tuple[str, ...]:
        """The names of its options (the fields of :attr:`options`; ``()`` without)."""
        from dataclasses import fields

        return () if self.options is None else tuple(f.name for f in fields(self.options))




@dataclass(frozen=True)
class Level:
    """
    A level of physics: the base and the effects added to it, applied in the registry's order.

    Attributes
    ----------
    effects
        The :class:`Effect` objects, the base first.
    """

    effects: tuple[Effect, ...]

    def __repr__(self) -> str:
        return f"Level({self.name!r})"

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
        """What the effects read (:class:`Setup`); ``after``: ``calibration``, ``seed``, ``options`` (effect
        name → its options) for ``post``."""
        return Setup(scene, camera, grid, lights, **after)

    def _last(self, part: str):
        """The last of its effects' ``part`` that is not ``None`` (or ``None``)."""
        found = [getattr(effect, part) for effect in self.effects if getattr(effect, part) is not None]
        return found[-1] if found else None

    @property
    def options(self) -> dict[str, type]:
        """Effect name → its options' dataclass, for the effects of the level that have options."""
        return {effect.name: effect.options for effect in self.effects if effect.options is not None}

    def default_options(self, given: Mapping[str, object] | None = None) -> dict[str, object]:
        """
        Every effect's options, by effect name: those ``given`` (each an instance of its effect's
        :attr:`Effect.options`, refused otherwise, naming the effect), the defaults for the others.
        An option of an effect outside the level is refused.
        """
        given = dict(given or {})
        outside = sorted(set(given) - set(self.options))
        if outside:
            raise SkinrenderError(f"options: {', '.join(outside)} {'is not an effect' if len(outside) == 1 else 'are not effects'}"
                                  f" with options at level {self.name!r}", role="options")
        for name, value in given.items():
            if not isinstance(value, self.options[name]):
                raise SkinrenderError(f"options: {name}'s options must be a {self.options[name].__name__}, got "
                                      f"{value!r}", role="options")
        return {name: given[name] if name in given else kind() for name, kind in self.options.items()}

    @property
    def sampler(self) -> str | None:
        """The sampler the level renders with unless one is asked for (its last effect's that names one)."""
        return self._last("sampler")

    @property
    def chart(self):
        """The source of a chart's raw renders at this level (its last effect's ``chart`` part:
        ``(request) → source``), or ``None``."""
        return self._last("chart")

    def refused(self, option: str) -> tuple[Effect, str] | None:
        """``(effect, why)`` of the first of its effects that refuses a validation's ``option``
        (:attr:`Effect.refuses`), or ``None``."""
        return next(((effect, effect.refuses[option]) for effect in self.effects if option in effect.refuses), None)

    @property
    def estimate(self):
        """``(request, cores) → (seconds, what)`` of one render where an effect says (its last such), else ``None``."""
        return self._last("estimate")

    def refuse(self, request) -> None:
        """Refuse, before any work, what does not go with the level's effects (each effect's ``refuse``)."""
        for effect in self.effects:
            if effect.refuse is not None:
                effect.refuse(request)

    def prepare(self, request) -> None:
        """What its effects do before any render, once the request's time is accepted (each effect's ``prepare``)."""
        for effect in self.effects:
            if effect.prepare is not None:
                effect.prepare(request)

    def scene(self, scene, options: Mapping[str, object]):
        """The scene as the render sees it: each effect's ``scene`` part with its options."""
        for effect in self.effects:
            if effect.scene is not None:
                scene = effect.scene(scene, options.get(effect.name))
        return scene

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
        """One-off seconds on one core before a skin's first render (its effects' :attr:`Effect.setup_seconds`)."""
        return float(sum(effect.setup_seconds for effect in self.effects))

    @property
    def scene_scale(self) -> float:
        """Scene units per metre of its Mitsuba document (:attr:`Effect.scene_scale`)."""
        return max(effect.scene_scale for effect in self.effects)

    def choose_variant(self, requested: str | None = None) -> str:
        """The Mitsuba variant: the first effect's that chooses one (:attr:`Effect.variant`), else
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

    def measure(self, images, first, options: Mapping[str, object] | None = None) -> Measured:
        """The replicate images as the checks see them (:class:`Measured`); ``options``: effect name →
        its options (the defaults where missing)."""
        options = self.default_options() if options is None else options
        measured = Measured(images)
        for effect in self.effects:
            if effect.limits.measure is not None:
                measured = effect.limits.measure(measured, first, options.get(effect.name))
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
