"""
Tests for :mod:`skinrender.rendering.settings`: the render settings are one checked, frozen object; the chart
renderers take it whole or its fields one by one, with the same result.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.rendering.settings import QUALITY_PRESETS, RenderSettings


def test_defaults_and_presets():
    assert RenderSettings() == RenderSettings(256, 0, "multijitter", None, "auto")
    for name, preset in QUALITY_PRESETS.items():
        settings = RenderSettings.preset(name, seed=4)
        assert (settings.spp, settings.sampler, settings.seed) == (preset["spp"], preset["sampler"], 4)


def test_frozen_and_hashable():
    settings = RenderSettings(spp=16)
    with pytest.raises(dataclasses.FrozenInstanceError):
        settings.spp = 32  # type: ignore[misc]
    assert hash(settings) == hash(RenderSettings(spp=16)) and {settings: 1}[RenderSettings(spp=16)] == 1


@pytest.mark.parametrize("fields, role, words", [
    ({"spp": 0}, "spp", "spp must be a positive integer"),
    ({"spp": 2.5}, "spp", "spp must be a positive integer"),
    ({"spp": True}, "spp", "spp must be a positive integer"),
    ({"seed": -1}, "seed", "seed must be an integer in [0, 2^32)"),
    ({"seed": 2**32}, "seed", "seed must be an integer in [0, 2^32)"),
    ({"sampler": "sobol"}, "sampler", "sampler must be one of independent, stratified, multijitter"),
    ({"channels": "two"}, "channels", "channels must be one of auto, together, separate"),
    ({"variant": 3}, "variant", "variant must be a Mitsuba variant's name"),
])
def test_bad_settings_are_refused_with_their_role(fields, role, words):
    with pytest.raises(SkinrenderError) as error:
        RenderSettings(**fields)
    assert str(error.value).startswith(words) and error.value.role == role


def test_of_replaces_fields_and_refuses_others():
    base = RenderSettings(spp=16, seed=2)
    assert RenderSettings.of(None) == RenderSettings()
    assert RenderSettings.of(base) is base
    assert RenderSettings.of(base, seed=5) == RenderSettings(spp=16, seed=5)
    assert RenderSettings.of(spp=np.int64(8)).spp == 8 and type(RenderSettings.of(spp=np.int64(8)).spp) is int
    with pytest.raises(SkinrenderError, match="^emitter: not a render setting; the settings: spp, seed, sampler"):
        RenderSettings.of(base, emitter="blackbody")
    with pytest.raises(SkinrenderError, match="^settings must be a RenderSettings"):
        RenderSettings.of({"spp": 4})  # type: ignore[arg-type]


def test_key_leaves_the_seed_out():
    assert RenderSettings(spp=16, seed=1).key == RenderSettings(spp=16, seed=9).key
    assert RenderSettings(spp=16).key != RenderSettings(spp=16, sampler="independent").key


def test_a_render_with_settings_equals_one_with_its_fields():
    pytest.importorskip("mitsuba")
    from skinrender.rendering.balance import render

    settings = RenderSettings(spp=4, seed=3, sampler="independent")
    whole = render("macbeth", "gbell:9@450,540,610", 2856, 2300, settings=settings)
    fields = render("macbeth", "gbell:9@450,540,610", 2856, 2300, spp=4, seed=3, sampler="independent")
    assert np.array_equal(whole.image, fields.image) and whole.raw[1].seed == 4  # the calibration takes seed + 1
