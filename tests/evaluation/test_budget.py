"""
Tests for :mod:`skinrender.evaluation.budget`: the signed distance to a locus's boundary, the detection budget
(half of it by default), and what a shift does to detection rates.
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.evaluation.budget import (BUDGET_FRACTION, DetectionBudget, boundary_distance, detection_budget,
                                          rates_shifted)
from skinrender.evaluation.locus import SkinLocus, hull_locus, skin_locus
from skinrender.model.chromaticity import ncc
from skinrender.model.response import response
from skinrender.spectra import GRID_DEFAULT

SQUARE = hull_locus(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]), np.array([5000.0]), None)


class TestBoundaryDistance:
    @pytest.mark.parametrize("point, distance, nearest", [
        ([0.5, 0.8], 0.2, [0.5, 1.0]),
        ([0.1, 0.5], 0.1, [0.0, 0.5]),
        ([1.5, 0.5], -0.5, [1.0, 0.5]),
        ([2.0, 2.0], -np.sqrt(2), [1.0, 1.0]),
    ])
    def test_signed_distance_and_nearest_point(self, point, distance, nearest):
        d, foot = boundary_distance(SQUARE, point)
        assert d == pytest.approx(distance) and foot == pytest.approx(nearest)

    def test_a_degenerate_locus_has_no_boundary(self):
        flat = SkinLocus(np.array([[0.0, 0.0], [1.0, 1.0]]), 0.0, "hull", np.array([5000.0]), None,
                         degenerate="on a line")
        with pytest.raises(SkinrenderError, match="no boundary"):
            boundary_distance(flat, [0.5, 0.5])
        budget = detection_budget(flat, [0.5, 0.5])
        assert budget.budget is None and "degenerate" in budget.reason and budget.inside is None


class TestDetectionBudget:
    def test_a_fraction_of_the_margin_towards_the_nearest_boundary(self):
        budget = detection_budget(SQUARE, [0.5, 0.8])
        assert budget.fraction == BUDGET_FRACTION == 0.5 and budget.budget == pytest.approx(0.1)
        assert budget.inside and budget.direction == pytest.approx((0.0, 1.0))
        assert detection_budget(SQUARE, [0.5, 0.8], fraction=0.25).budget == pytest.approx(0.05)
        document = budget.document()
        assert set(document) == {"budget", "fraction", "margin", "inside", "point", "nearest", "direction", "reason"}

    def test_outside_the_margin_is_the_distance_in(self):
        budget = detection_budget(SQUARE, [1.5, 0.5])
        assert budget.inside is False and budget.budget == pytest.approx(0.25)
        assert budget.direction == pytest.approx((-1.0, 0.0)) and "outside" in budget.reason

    def test_on_the_boundary_there_is_no_budget(self):
        budget = detection_budget(SQUARE, [1.0, 0.5])
        assert budget.budget is None and "boundary" in budget.reason

    @pytest.mark.parametrize("fraction", [0.0, -0.5, 1.5, "half"])
    def test_a_bad_fraction_is_refused(self, fraction):
        with pytest.raises(SkinrenderError, match="fraction"):
            detection_budget(SQUARE, [0.5, 0.5], fraction)

    def test_a_camera_skin_within_twice_its_budget_stays_on_its_side(self):
        """Eq. 4's light skin through gbell 9 @450,540,610 at 2856 K balanced to 5900 K: a shift of twice the budget
        (the whole margin) less a hair keeps it inside the locus, a hair more carries it out."""
        cam = "gbell:9@450,540,610"
        locus = skin_locus(cam, "skin", calibration=5900)
        from skinrender.datasets import reflectances

        skin = reflectances("skin")
        rho = skin.on(GRID_DEFAULT)[list(skin.names).index("089 skin -- caucasian (light)")]
        point = ncc(response(cam, rho[None], 2856, 5900))[0, :2]
        budget = detection_budget(locus, point)
        assert isinstance(budget, DetectionBudget) and budget.inside and 0 < budget.budget < 0.05
        step = np.asarray(budget.direction)
        assert locus.contains((point + (2 * budget.budget - 1e-6) * step)[None])[0]
        assert not locus.contains((point + (2 * budget.budget + 1e-6) * step)[None])[0]


class TestRatesShifted:
    def test_rates_before_and_after(self):
        out = rates_shifted(SQUARE, [[0.5, 0.5], [0.5, 0.95]], [[0.5, 1.05], [1.5, 1.5]], [0.0, -0.1])
        assert (out["tpr"], out["tpr_shifted"], out["tpr_change"]) == (1.0, 1.0, 0.0)
        assert (out["fpr"], out["fpr_shifted"], out["fpr_change"]) == (0.0, 0.5, 0.5)

    def test_no_points_no_rate(self):
        out = rates_shifted(SQUARE, np.zeros((0, 2)), [[0.5, 0.5]], [0.1, 0.0])
        assert out["tpr"] is None and out["tpr_change"] is None and out["fpr"] == 1.0
