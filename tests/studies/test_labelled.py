"""
Tests for :mod:`skinrender.studies.labelled`: the figures of renders, registered for ``.figure()`` when
``skinrender`` is imported, as ``render --figure`` draws them.
"""

from __future__ import annotations

import pytest

import skinrender as sr
from skinrender.rendering.outputs import FIGURE_DRAWERS
from skinrender.studies.labelled import chart_figure, face_figure

CAMERA = "gbell:9@450,540,610"


def test_registered_by_importing_skinrender():
    assert FIGURE_DRAWERS["chart"] is chart_figure and FIGURE_DRAWERS["face"] is face_figure


def test_figures_of_a_chart_and_a_face(tmp_path):
    pytest.importorskip("mitsuba")
    from PIL import Image

    from skinrender.evaluation.detection import detect

    chart = sr.render("macbeth", CAMERA, 2856, 2856, spp=2)
    plain = chart.figure(tmp_path / "chart.png")
    detection = detect(chart, sr.skin_locus(CAMERA, "skin", calibration=2856))
    detected = chart_figure(chart, tmp_path / "detected.png", detection, "TPR —")
    face = sr.render("face", camera=CAMERA, prevailing=2856, calibration=2856, spp=1, size=12)
    drawn = face_figure(face, tmp_path / "face.png", mask=face.labels == 1, title="a title")
    for path in (plain, detected, drawn):
        with Image.open(path) as image:
            assert image.format == "PNG" and min(image.size) > 100
    with Image.open(plain) as one, Image.open(detected) as two:
        assert two.size[1] > one.size[1]  # the detection's mask is a second panel below the render
