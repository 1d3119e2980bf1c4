"""
Tests for :mod:`skinrender.rendering.kinds`: a chart and a face are two objects of one protocol (issue 35 item 2),
the one place a scene is told to be one or the other; ``skinrender.render("macbeth", imager=…)`` works.
"""

from __future__ import annotations

import inspect

import numpy as np
import pytest

import skinrender as sr
from skinrender.rendering.kinds import CHART, FACE, SCENE_KINDS, SceneKind, scene_kind

CAM = "gbell:9@450,540,610"

PROTOCOL = [name for name, value in vars(SceneKind).items() if inspect.isfunction(value) and not name.startswith("_")]
"""The methods of the protocol."""


def test_both_kinds_implement_the_protocol():
    assert {"render", "validate", "estimate_seconds", "figure", "request", "load", "owns"} <= set(PROTOCOL)
    for kind in SCENE_KINDS.values():
        for name in PROTOCOL:
            assert callable(getattr(kind, name)), (kind, name)
        assert kind.registry.base.name == "direct" and kind.name in SCENE_KINDS
        assert {"physics", "spp", "seed"} <= set(kind.render_options) <= set(kind.validate_options)


def test_the_kind_of_a_scene_or_a_spec(small_chart, tmp_path):
    face_toml = tmp_path / "f.toml"
    face_toml.write_text("[camera]\n[mesh]\n")
    assert [scene_kind(s) for s in ("macbeth", str(small_chart), "face", str(face_toml), "nosuch")] == [
        CHART, CHART, FACE, FACE, CHART]  # anything else: the chart loader says what is wrong
    assert scene_kind(sr.load_scene("face")) is FACE and scene_kind(sr.load_scene("macbeth")) is CHART


def test_a_face_toml_is_parsed_once(tmp_path, monkeypatch):
    """Issue 35: a face TOML was parsed twice (to tell its kind, then to load it)."""
    import tomllib

    path = tmp_path / "face.toml"
    path.write_text(open(sr.load_scene("face").source, encoding="utf-8").read())
    calls = []
    loads = tomllib.loads
    monkeypatch.setattr(tomllib, "loads", lambda *a, **k: calls.append(1) or loads(*a, **k))
    scene = sr.load_scene(str(path))
    assert scene_kind(scene) is FACE and len(calls) == 1


def test_estimates_follow_the_level(small_chart):
    """A slower level's estimate is longer; a subsurface-volume chart's counts its skin patches only; the fast
    subsurface adds its one-off table."""
    fast = FACE.request("face", CAM, None, None, size=64, spp=64)
    slow = FACE.request("face", CAM, None, None, size=64, spp=64, physics="subsurface-volume")
    assert FACE.estimate_seconds(slow) > 10 * FACE.estimate_seconds(fast) > 0
    assert FACE.estimate_seconds(fast, renders=4, cores=2) == pytest.approx(2 * FACE.estimate_seconds(fast))
    table = FACE.request("face", CAM, None, None, size=64, spp=64, physics="subsurface")
    assert FACE.estimate_seconds(fast) < FACE.estimate_seconds(table) < 2 * FACE.estimate_seconds(fast) + 5
    for physics, what_says in (("subsurface-volume", "30 skin patches of skin_patches as media"),
                               ("subsurface", "30 skin patches' tables and 30 fits")):
        slabs = CHART.request("skin_patches", CAM, 2856, 2856, physics=physics, spp=16)
        seconds, what = CHART.workload(slabs)
        assert seconds == pytest.approx(CHART.estimate_seconds(slabs)) and what_says in what


def test_a_chart_through_an_imager_from_python():
    """Issue 35: ``sr.render("macbeth", imager=…)`` was refused (chart + imager was composed in the command line
    only); it is the sensor's render (:func:`~skinrender.rendering.imaging.render_imaged`), and validates."""
    pytest.importorskip("mitsuba")
    from skinrender.rendering.imaging import render_imaged

    kwargs = {"spp": 4, "seed": 2, "illuminance": 300.0}
    result = sr.render("macbeth", CAM, 2856, 5900, imager="sony-imx174", **kwargs)
    same = render_imaged("macbeth", sr.camera(CAM), 2856, 5900, "sony-imx174", 300.0, spp=4, seed=2)
    assert np.array_equal(result.image, same.rendering.image)
    assert result.info["imager"] == "sony-imx174" and result.info["illuminance_lux"] == 300.0
    checked = sr.validate("macbeth", CAM, 2856, 5900, imager="sony-imx174", tolerance=0.5, **kwargs)
    assert checked.verdict.outcome in ("pass", "fail", "inconclusive") and "variance" in checked.checks


def test_the_figure_of_each_kind(tmp_path):
    pytest.importorskip("mitsuba")
    chart = sr.render("macbeth", CAM, 2856, 2856, spp=1)
    assert CHART.figure(chart, tmp_path / "c.png").stat().st_size > 0
