"""
Tests for :mod:`skinrender.rendering.chart_effects`: a chart's physics is a registry of the same effects and
levels as the face's; its sensor comes with an imager and is not named in a spec.
"""

from __future__ import annotations

import pytest

from skinrender.errors import SkinrenderError
from skinrender.rendering.chart_effects import CHART_EFFECTS, CHART_REGISTRY
from skinrender.rendering.physics import Effect, Level


def test_the_named_effects_are_the_specs_and_each_has_its_source():
    """A named effect is a spec of ``--physics`` and supplies the source of the raw renders; an unnamed one (the
    sensor) is reached through its options, which a request holds (:attr:`Request.sensor`)."""
    assert next(iter(CHART_EFFECTS)) == CHART_REGISTRY.base.name == "direct"
    for name, effect in CHART_EFFECTS.items():
        assert isinstance(effect, Effect) and effect.name == name
        assert effect.description.strip() and "\n" not in effect.description
        assert callable(effect.chart) if effect.named else effect.chart is None
    unnamed = [name for name, effect in CHART_EFFECTS.items() if not effect.named]
    assert unnamed and all(CHART_EFFECTS[name].added_by and CHART_EFFECTS[name].options for name in unnamed)
    for name in unnamed:
        with pytest.raises(SkinrenderError, match=r"physics \(of a chart\) must be one of"):
            CHART_REGISTRY.level(name)


def test_a_level_renders_from_its_last_source_and_says_what_it_refuses():
    for name in CHART_REGISTRY.named:
        level = CHART_REGISTRY.level(name)
        assert isinstance(level, Level) and level.chart is CHART_EFFECTS[name].chart
    base = CHART_REGISTRY.level("direct")
    assert base.refused("gamut") is None and base.refused("spp_auto") is None
    for effect in CHART_EFFECTS.values():
        for option, why in effect.refuses.items():
            assert option in ("gamut", "spp_auto") and why.strip()
