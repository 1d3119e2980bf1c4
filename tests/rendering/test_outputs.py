"""
Tests for :mod:`skinrender.rendering.outputs`: a render's ``.save()`` and ``.figure()`` — the paths checked
before anything is written, the EXR read back, and figures drawn by the drawer the studies layer registers.
"""

from __future__ import annotations

import importlib

import numpy as np
import pytest

import skinrender as sr
from skinrender.rendering import outputs
from skinrender.rendering.exr import read_exr
from skinrender.rendering.outputs import output_paths
from skinrender.rendering.renderer import channel_names

CAMERA = "gbell:9@450,540,610"


class TestOutputPaths:
    def test_defaults_and_choices(self, tmp_path):
        exr = tmp_path / "a.exr"
        assert output_paths(exr) == (exr, tmp_path / "a.png", None)
        assert output_paths(exr, False, tmp_path / "f.png") == (exr, None, tmp_path / "f.png")
        assert output_paths(exr, tmp_path / "p.png")[1] == tmp_path / "p.png"

    @pytest.mark.parametrize("args, name", [
        (("a.png",), "exr"), (("a.exr", "a.jpg"), "png"), (("a.exr", True, "f.svg"), "figure"),
        (("a.exr", True, "a.png"), "figure"),
    ])
    def test_refused_naming_the_argument(self, tmp_path, args, name):
        with pytest.raises(sr.SkinrenderError, match=f"^{name}: "):
            output_paths(*(tmp_path / a if isinstance(a, str) else a for a in args))
        assert list(tmp_path.iterdir()) == []

    @pytest.mark.parametrize("args, name", [
        (("",), "exr"), ((None,), "exr"), ((3,), "exr"), (("a.exr", ""), "png"), (("a.exr", 1), "png"),
        (("a.exr", True, ""), "figure"), (("a.exr", True, b"f.png"), "figure"),
    ])
    def test_empty_and_non_paths_are_refused_by_name(self, args, name):
        """Issue 36: ``sr.render(...).save("")`` raised a bare ValueError (Path('') is '.', which has no suffix to
        replace)."""
        with pytest.raises(sr.SkinrenderError, match=f"^{name}: expected ") as error:
            output_paths(*args)
        assert error.value.role == name

    def test_a_folder_is_no_file(self, tmp_path):
        (tmp_path / "x.exr").mkdir()
        with pytest.raises(sr.SkinrenderError, match="exr"):
            output_paths(tmp_path / "x.exr")


def test_without_a_registered_drawer_a_figure_says_who_draws(monkeypatch, tmp_path):
    importlib.import_module(outputs.FIGURE_MODULE)  # imported already: its drawers are not registered again
    monkeypatch.setattr(outputs, "FIGURE_DRAWERS", {})
    with pytest.raises(sr.SkinrenderError, match="skinrender.studies.labelled"):
        outputs.draw_figure("face", None, tmp_path / "f.png")


def test_a_face_saves_itself(tmp_path):
    pytest.importorskip("mitsuba")
    face = sr.render("face", camera=CAMERA, prevailing=2856, calibration=5900, spp=2, size=12)
    paths = face.save(tmp_path / "out" / "face.exr", figure=tmp_path / "out" / "figure.png")
    assert paths == {"exr": tmp_path / "out" / "face.exr", "png": tmp_path / "out" / "face.png",
                     "figure": tmp_path / "out" / "figure.png"}
    stack = read_exr(paths["exr"], (*face.channels, "label"))
    assert np.array_equal(stack[..., :3], face.image) and np.array_equal(stack[..., 3], face.labels)
    assert all(path.stat().st_size > 0 for path in paths.values())
    assert face.figure(tmp_path / "again.png") == tmp_path / "again.png"


def test_a_chart_saves_itself(tmp_path):
    pytest.importorskip("mitsuba")
    chart = sr.render("macbeth", CAMERA, 2856, 2300, spp=2)
    paths = chart.save(tmp_path / "chart.exr", png=False)
    assert paths == {"exr": tmp_path / "chart.exr", "png": None, "figure": None}
    assert sorted(p.name for p in tmp_path.iterdir()) == ["chart.exr"]
    assert np.array_equal(read_exr(paths["exr"], channel_names(chart.camera)), chart.image)
    with pytest.raises(sr.SkinrenderError, match="figure"):
        chart.figure(tmp_path / "chart.jpg")
