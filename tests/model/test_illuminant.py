"""Tests for :mod:`skinrender.illuminant`."""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.model.illuminant import illuminant, illuminants_array
from skinrender.spectra import planck


class TestIlluminant:
    @pytest.mark.parametrize("spec, kelvin", [(3300, 3300), ("3300", 3300), ("3300K", 3300), (" 2856k ", 2856),
                                              ("A", 2856), ("h", 2300), ("Horizon", 2300)])
    def test_specs(self, spec, kelvin):
        assert illuminant(spec).temperature == kelvin

    def test_planck_spd(self):
        np.testing.assert_allclose(illuminant("A").spd([500.0, 600.0]), planck([500.0, 600.0], 2856))

    @pytest.mark.parametrize("spec", [0, -300, "0K", "-5", "nan", "warm", "inf"])
    def test_bad(self, spec):
        with pytest.raises(SkinrenderError, match="kelvin|not understood"):
            illuminant(spec)

    def test_csv(self, tmp_path):
        path = tmp_path / "lamp.csv"
        path.write_text("nm,spd\n380,1\n780,3\n")
        lamp = illuminant(str(path))
        assert lamp.temperature is None
        assert lamp.spd([580.0])[0] == pytest.approx(2.0)
        with pytest.raises(SkinrenderError, match="does not cover"):
            lamp.spd([300.0])

    def test_array(self):
        items, shape = illuminants_array(np.array([[2000.0], [3000.0]]))
        assert shape == (2, 1) and [i.temperature for i in items] == [2000, 3000]
        assert illuminants_array("A")[1] == ()
