"""
Tests for :mod:`skinrender.model.factors`: the normalisations of Eqs. 5–8 are a table of functions with one
dispatcher, each function gives its illuminants' factors (WP, a pair's, gives none), the quadratures' weights.
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.methods import describe
from skinrender.model.factors import (NORMALISATIONS, QUADRATURES, illuminant_factors, normalisation_factor,
                                      uses_whites)
from skinrender.spectra import WavelengthGrid


def test_each_normalisation_is_a_described_function():
    """The table maps the names the command line offers to functions whose descriptions are the paper's."""
    assert list(NORMALISATIONS) == ["none", "560nm", "euclidean", "white"]
    assert [describe(f)[:6] for f in NORMALISATIONS.values()] == ["Eq. 5:", "Eq. 6:", "Eq. 7:", "Eq. 8:"]


def test_the_dispatcher_gives_each_illuminant_its_factor():
    """Eq. 5: 1; Eq. 6: 100 / SPD(560 nm), so 100 at 560 nm once applied; Eq. 7: a unit norm on the grid; Eq. 8
    (WP) is no illuminant's: ``None``."""
    from skinrender.model.illuminant import illuminant

    grid = WavelengthGrid(400, 700, 10)
    assert illuminant_factors([2856, 6500], "none", grid).tolist() == [1.0, 1.0]
    light = illuminant(2856)
    assert light.spd(np.array([560.0]))[0] * illuminant_factors(2856, "560nm", grid) == pytest.approx(100.0)
    assert np.linalg.norm(light.spd(grid.wavelengths)) * illuminant_factors(2856, "euclidean", grid) == \
        pytest.approx(1.0)
    assert illuminant_factors(2856, "white", grid) is None
    assert uses_whites("white") and not uses_whites("none")


def test_names_outside_the_table_are_refused_by_the_dispatcher():
    with pytest.raises(SkinrenderError, match="normalization must be one of none, 560nm, euclidean, white"):
        illuminant_factors(2856, "max")
    with pytest.raises(SkinrenderError, match=r"white has no per-illuminant factor\), got 'white'"):
        normalisation_factor(2856, "white")


def test_quadrature_weights():
    grid = WavelengthGrid(400, 440, 10)
    assert QUADRATURES["sum"](grid).tolist() == [1.0] * 5
    assert QUADRATURES["trapezoid"](grid).tolist() == [0.5, 1.0, 1.0, 1.0, 0.5]
