"""Tests for :mod:`skinrender.studies.paper.unknowns`: a setting of the paper's unknowns, checked and computed."""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.constants import TEMPERATURES_PAPER
from skinrender.design.search import search
from skinrender.errors import SkinrenderError
from skinrender.studies.paper.unknowns import (SETTING_DEFAULT, Setting, check_camera, check_positions, check_sensors,
                                         resolve_setting, setting_tables, with_unknown)
from skinrender.studies.paper.volumes import VolumeCache


class TestResolveSetting:
    def test_default(self):
        resolved = resolve_setting(SETTING_DEFAULT)
        assert str(resolved.grid) == "400:700:1 nm"
        np.testing.assert_array_equal(resolved.temperatures, TEMPERATURES_PAPER)
        assert resolved.skin.shape == (30, 301) and resolved.munsell.shape == (1269, 301)

    @pytest.mark.parametrize(("change", "flag"), [
        ({"slope": 0.0}, "--slope"), ({"slope": float("nan")}, "--slope"), ({"slope": "2"}, "--slope"),
        ({"grid": "400:700"}, "--grid"), ({"grid": "380:780:1"}, "--skin"),
        ({"skin": "nope"}, "--skin"), ({"munsell": "nope.csv"}, "--munsell"),
        ({"illuminants": "2000,x"}, "--illuminants"),
        ({"illuminants": "auto", "stage1_camera": "Sony 755"}, "--stage1-camera"),
        ({"extrapolation": "linear"}, "--extrapolation"),
    ])
    def test_refusals_name_the_flag(self, change, flag):
        with pytest.raises(SkinrenderError, match=f"^{flag}"):
            resolve_setting(Setting(**change))

    def test_wide_grid_with_extrapolation(self):
        resolved = resolve_setting(with_unknown(SETTING_DEFAULT, "grid", "380:780:5"))
        assert resolved.setting.extrapolation == "constant" and resolved.skin.shape == (30, 81)

    def test_auto_illuminants(self):
        resolved = resolve_setting(Setting(illuminants="auto", stage1_camera="Kodak DCS-200"))
        assert resolved.temperatures.size == 10 and resolved.temperatures[0] == 2000


class TestChecks:
    def test_sensors(self):
        assert check_sensors("1,3,15") == [1.0, 3.0, 15.0]
        for bad in ("", "1,,3", "0", "1,1", "a"):
            with pytest.raises(SkinrenderError, match="--sensors"):
                check_sensors(bad)

    def test_positions_inside_the_grid(self):
        grid = resolve_setting(SETTING_DEFAULT).grid
        assert check_positions("400:700:100", grid).tolist() == [400, 500, 600, 700]
        with pytest.raises(SkinrenderError, match="--positions"):
            check_positions("380:700:10", grid)

    def test_camera(self):
        grid = resolve_setting(SETTING_DEFAULT).grid
        with pytest.raises(SkinrenderError, match="^--camera"):
            check_camera("Sony 755", grid)


class TestLabel:
    def test_labels(self):
        assert SETTING_DEFAULT.label() == "default"
        assert Setting(slope=3.0).label() == "slope=3"
        assert Setting(illuminants="auto", stage1_camera="Kodak DCS-200").label() == \
            "illuminants=auto (Kodak DCS-200)"
        assert with_unknown(SETTING_DEFAULT, "grid", "380:780:1").label() == "grid=380:780:1, extrapolation=constant"

    def test_stage1_camera_alone_changes_nothing(self):
        assert Setting(stage1_camera="Kodak DCS-200").label() == "default"


class TestSettingTables:
    def test_tables_equal_the_search(self):
        resolved = resolve_setting(SETTING_DEFAULT)
        where = check_positions("400:700:50", resolved.grid)
        cache = VolumeCache()
        out = setting_tables(resolved, [9], where, cache, workers=1)
        reference = search(9, resolved.skin, resolved.munsell, where, workers=1)
        np.testing.assert_array_equal(out["results"][9.0].munsell, reference.munsell)
        assert set(out["matches"]) >= {"exact", "within_step", "total", "by_table"}
        assert out["matches"]["total"] == 6 and cache.computed == 2
        skin_only = resolve_setting(with_unknown(SETTING_DEFAULT, "skin", "skin-model"))
        setting_tables(skin_only, [9], where, cache, workers=1)
        assert cache.computed == 3  # the Munsell volumes were reused
