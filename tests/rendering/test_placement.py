"""
Tests for :mod:`skinrender.rendering.placement`: a translation parsed and checked, float32's useful range and its
refusal naming the scene.
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.rendering.placement import (FLOAT32_SHARE, check_float32_range, float32_limit_mm, float32_spacing,
                                            translation)


@pytest.mark.parametrize("value, expected", [("100,0,0", (100.0, 0.0, 0.0)), (" -5, 2.5 ,1e2", (-5.0, 2.5, 100.0)),
                                             ((1, 2, 3), (1.0, 2.0, 3.0))])
def test_translation(value, expected):
    assert translation(value) == expected


@pytest.mark.parametrize("value", ["100,0", "1,2,3,4", "a,b,c", "nan,0,0", "inf,0,0", "", (1, 2)])
def test_a_bad_translation_is_refused_naming_it(value):
    with pytest.raises(SkinrenderError, match="--translate-mm must be three finite numbers of mm") as raised:
        translation(value)
    assert raised.value.flag == "--translate-mm"


def test_the_limit_is_where_the_spacing_reaches_the_share():
    """Below the limit float32 positions are at most FLOAT32_SHARE of the length apart, at it they are more."""
    for length in (0.0113, 0.0167, 1.9):
        limit = float32_limit_mm(length)
        assert float32_spacing(np.nextafter(np.float32(limit), np.float32(0))) <= FLOAT32_SHARE * length
        assert float32_spacing(limit) > FLOAT32_SHARE * length


def test_beyond_float32s_useful_range_is_refused_naming_the_scene():
    assert check_float32_range("face.toml", 300.0, 0.0113, "the skin's mean free path") == 2.0**-15
    with pytest.raises(SkinrenderError, match="face.toml: it reaches 3000 mm from the origin, where float32 "
                                              "positions are 0.00024 mm apart, more than 0.01 of the skin's mean "
                                              "free path .*up to 1024 mm") as raised:
        check_float32_range("face.toml", 3000.0, 0.0113, "the skin's mean free path")
    assert raised.value.flag == "--translate-mm"


def test_the_documents_unit_is_taken_into_account():
    """In metres (unit 1000 mm) the spacing at 0.3 m is float32's there, times 1000 mm."""
    assert check_float32_range("x", 300.0, 1.9, "a pixel", unit_mm=1000.0) == pytest.approx(
        float(np.spacing(np.float32(0.3))) * 1000)


def test_the_spawn_offset_grows_with_the_distance_and_is_refused_past_its_limit():
    from skinrender.rendering.placement import RAY_EPSILON, SPAWN_OFFSET_MAX_MM, check_spawn_offset, spawn_offset_mm

    assert spawn_offset_mm(0.0, 1000.0) == pytest.approx(RAY_EPSILON * 1000.0)  # a face at the origin: ~0.09 mm
    assert spawn_offset_mm(300.0, 1.0) == pytest.approx(301 * RAY_EPSILON)  # the same in a mm document
    assert check_spawn_offset("face", 5000.0, 1000.0) < SPAWN_OFFSET_MAX_MM
    with pytest.raises(SkinrenderError, match=r"face: it reaches 2e\+04 mm .* keep it within 1\.0\d*e\+04 mm"):
        check_spawn_offset("face", 20_000.0, 1000.0)
