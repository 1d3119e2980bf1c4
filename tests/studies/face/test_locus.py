"""Tests for :mod:`skinrender.studies.face.locus`: polygon overlap, and rendered faces' locus beside the analytic."""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.model.camera import camera
from skinrender.studies.face.locus import convex_intersection_area, face_locus

pytest.importorskip("mitsuba")

SQUARE = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float)


@pytest.mark.parametrize("shift, expected", [((0.5, 0.5), 0.25), ((0.0, 0.0), 1.0), ((2.0, 0.0), 0.0),
                                             ((0.25, 0.0), 0.75)])
def test_intersection_of_squares(shift, expected):
    assert convex_intersection_area(SQUARE, SQUARE + shift) == pytest.approx(expected, abs=1e-12)


def test_triangle_inside_square():
    triangle = np.array([[0.1, 0.1], [0.9, 0.1], [0.1, 0.9]])
    assert convex_intersection_area(SQUARE, triangle) == pytest.approx(0.32, abs=1e-12)


def test_direct_faces_overlap_the_analytic_locus():
    """At the direct level shading cancels in NCC: the rendered skin's locus lies over the analytic one and their
    centres agree (each skin and light weighing alike); render noise only widens it."""
    result = face_locus(camera("gbell:9@450,540,610"), pairs=((2856.0, 5900.0), (5900.0, 5900.0)),
                        skins=("skin-model:melanin=0.02", "skin-model:melanin=0.2"), size=32, spp=64)
    assert result["analytic_covered"] > 0.9 and result["rendered_area"] >= 0.9 * result["analytic_area"]
    assert np.all(np.abs(result["centre_shift"]) < 5e-3)


def test_workers_give_the_same_locus():
    """The faces rendered in two worker processes give the locus rendered in this process, to the last bit."""
    arguments = {"camera_": camera("gbell:9@450,540,610"), "pairs": ((2856.0, 5900.0), (2300.0, 5900.0)),
                 "skins": ("skin-model:melanin=0.02", "skin-model:melanin=0.4"), "size": 48, "spp": 32, "seed": 1}
    one, two = face_locus(**arguments, workers=1), face_locus(**arguments, workers=2)
    for result in (one, two):
        del result["seconds"]
    assert one == two and one["pixels"] > 0
