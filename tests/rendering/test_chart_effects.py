"""
Tests for :mod:`skinrender.rendering.chart_effects`: a chart's physics is a registry of the same effects and
levels as the face's; its sensor comes with an imager and is not named in a spec.
"""

from __future__ import annotations

import pytest

from skinrender.errors import SkinrenderError
from skinrender.rendering.chart_effects import CHART_EFFECTS, CHART_REGISTRY
from skinrender.rendering.physics import Effect, Level


def test_every_effect_renders_a_chart_and_the_named_ones_are_the_specs():
    assert next(iter(CHART_EFFECTS)) == CHART_REGISTRY.base.name == "direct"
    for name, effect in CHART_EFFECTS.items():
        assert isinstance(effect, Effect) and effect.name == name and callable(effect.chart)
        assert effect.description.strip() and "\n" not in effect.description
    unnamed = [name for name, effect in CHART_EFFECTS.items() if not effect.named]
    assert unnamed and all(CHART_EFFECTS[name].added_by for name in unnamed)  # reached through their options
    for name in unnamed:
        with pytest.raises(SkinrenderError, match=r"physics \(of a chart\) must be one of"):
            CHART_REGISTRY.level(name)


def test_a_level_renders_with_its_last_chart_part_and_says_what_it_refuses():
    for name in CHART_REGISTRY.named:
        level = CHART_REGISTRY.level(name)
        assert isinstance(level, Level) and level.chart is CHART_EFFECTS[name].chart
    base = CHART_REGISTRY.level("direct")
    assert base.refused("gamut") is None and base.refused("spp_auto") is None
    for effect in CHART_EFFECTS.values():
        for option, why in effect.refuses.items():
            assert option in ("gamut", "spp_auto") and why.strip()
