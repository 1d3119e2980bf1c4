"""
Tests for :mod:`skinrender.rendering.registry`: a scene kind's effects, the one parser of a physics spec into a
level, the effects' options handed in by effect name (an imager adds noise: the one place that rule is written),
and an effect registered from outside the package.
"""

from __future__ import annotations

import pytest

from skinrender.errors import SkinrenderError
from skinrender.rendering.chart_effects import CHART_REGISTRY
from skinrender.rendering.face.effects import PHYSICS_EFFECTS, PHYSICS_REGISTRY
from skinrender.rendering.physics import Effect
from skinrender.rendering.registry import Registry
from skinrender.rendering.sensor import NoiseOptions

SENSOR = [name for name, effect in PHYSICS_EFFECTS.items() if "imager" in effect.added_by]
"""The face effects an imager adds (read from the registry: today the sensor, ``noise``)."""


def test_specs_become_levels_in_the_registrys_order():
    for registry in (PHYSICS_REGISTRY, CHART_REGISTRY):
        named = list(registry.by_default)  # (the effects a spec may name together: no two transports of one skin)
        assert registry.level(registry.base.name).names == () and registry.level(()).name == registry.base.name
        spec = "+".join(reversed(named[1:]))
        assert registry.level(spec).names == tuple(named[1:])  # the registry's order, whatever the spec's
        level = registry.level(spec)
        assert registry.level(level) is level  # a level of the registry passes as it is
    with pytest.raises(SkinrenderError, match="not of this scene's effects") as error:
        CHART_REGISTRY.level(PHYSICS_REGISTRY.level("sheen"))
    assert error.value.role == "physics"


def test_two_transports_of_one_skin_do_not_combine():
    """``subsurface`` and ``subsurface-volume`` exclude each other, on a chart and on the face, whichever is named
    first; each is a level alone, and the volumetric one is not a default level."""
    for registry in (PHYSICS_REGISTRY, CHART_REGISTRY):
        for spec in ("subsurface+subsurface-volume", "subsurface-volume+subsurface"):
            with pytest.raises(SkinrenderError, match="two transports of the same skin") as error:
                registry.level(spec)
            assert error.value.role == "physics"
        assert registry.level("subsurface-volume").names == ("subsurface-volume",)
        assert "subsurface" in registry.by_default and "subsurface-volume" not in registry.by_default


def test_options_go_to_their_effect_and_an_imager_adds_the_sensor():
    level, options = PHYSICS_REGISTRY.with_options(PHYSICS_REGISTRY.level("sheen"), {"imager": "sony-icx418",
                                                                                      "exposure": None})
    assert list(level.names) == ["sheen", *SENSOR] and isinstance(options[SENSOR[0]], NoiseOptions)
    plain, none = PHYSICS_REGISTRY.with_options(PHYSICS_REGISTRY.level("sheen"), {"imager": None})
    assert plain.name == "sheen" and none == {}  # None is not given
    with pytest.raises(SkinrenderError, match="exposure is an option of") as error:
        PHYSICS_REGISTRY.with_options(PHYSICS_REGISTRY.level("direct"), {"exposure": 0.01})
    assert error.value.role == "exposure"
    with pytest.raises(SkinrenderError, match="blur: not an effect's option") as error:
        PHYSICS_REGISTRY.with_options(PHYSICS_REGISTRY.level("direct"), {"blur": 1})
    assert error.value.role == "blur"


def test_a_study_hands_the_sensor_only_to_the_levels_with_it():
    given = {"imager": "sony-icx418", "illuminance": 100.0}
    assert PHYSICS_REGISTRY.options_for(PHYSICS_REGISTRY.level("sheen"), given) == {}
    assert PHYSICS_REGISTRY.options_for(PHYSICS_REGISTRY.level("+".join(SENSOR)), given) == given


def test_register_places_an_effect_by_its_order_and_refuses_a_name_taken():
    base = Effect("base", "the base", order=0)
    registry = Registry({"base": base}, "toy physics ({spec!r})")
    late, early = Effect("late", "late", order=20), Effect("early", "early", order=10)
    assert registry.register(late) is late and registry.register(early) is early
    assert list(registry.effects) == ["base", "early", "late"] and registry.level("late+early").name == "early+late"
    with pytest.raises(SkinrenderError, match="register"):
        registry.register(Effect("late", "again", order=30))
    with pytest.raises(SkinrenderError, match=r"toy physics \('nope'\) must be one of base, early, late"):
        registry.level("nope")
