"""
Property-based tests of the public Python API (``import skinrender as sr``): for any generated arrays,
temperatures and specs, each function returns finite numbers or raises :class:`SkinrenderError` — never NaN,
never another exception.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import skinrender as sr

SETTINGS = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
floats = st.floats(allow_nan=True, allow_infinity=True, width=64)
temperatures = st.one_of(floats, st.sampled_from([0.0, -0.0, 1e-300, 20.0, 35.0, 1e306, 2856.0, 1e12, 1e13]),
                         st.booleans())
grid = sr.GRID_DEFAULT


def finite_or_refused(function, *args, **kwargs):
    """Call; the result must be all finite numbers, or the call a SkinrenderError."""
    try:
        value = function(*args, **kwargs)
    except sr.SkinrenderError:
        return None
    array = np.asarray(getattr(value, "volume", value), dtype=np.float64)
    assert np.all(np.isfinite(array)), f"{function.__name__} gave {array}"
    return value


@SETTINGS
@given(wavelength=floats, temperature=temperatures)
def test_planck(wavelength, temperature):
    value = finite_or_refused(sr.planck, wavelength, temperature)
    if value is not None:
        assert float(value) >= 0


@SETTINGS
@given(p=temperatures, c=temperatures, normalization=st.sampled_from(list(sr.NORMALISATIONS)), knee=st.booleans())
def test_response_to_any_lights(p, c, normalization, knee):
    finite_or_refused(sr.response, "gbell:9@450,540,610", np.full((2, grid.size), 0.5), p, c, normalization, knee)


@SETTINGS
@given(reflectance=hnp.arrays(np.float64, (3, grid.size), elements=floats))
def test_response_to_any_reflectance_array(reflectance):
    value = finite_or_refused(sr.response, "gbell:9@450,540,610", reflectance, 2856, 2300)
    if value is not None:
        assert np.all((reflectance >= 0) & (reflectance <= 1.5)), "reflectances outside [0, 1.5] must be refused"


@SETTINGS
@given(spec=st.one_of(st.text(max_size=30), st.builds(lambda n, b, p: f"gbell:{n},b={b}@{p[0]},{p[1]},{p[2]}",
                                                          floats, floats, st.tuples(floats, floats, floats))))
def test_camera_specs(spec):
    try:
        cam = sr.camera(spec)
        curves = cam.sensitivities(grid)
    except sr.SkinrenderError:
        return
    assert np.all(np.isfinite(curves))


@SETTINGS
@given(points=hnp.arrays(np.float64, st.tuples(st.integers(0, 12), st.just(3)), elements=floats),
       scale=st.sampled_from([1.0, 1e-80, 1e80]))
def test_gamut_volume(points, scale):
    with np.errstate(over="ignore"):  # scaling a generated cloud may itself overflow to inf: refused then
        cloud = points * scale
    value = finite_or_refused(sr.gamut_volume, cloud)
    if value is not None:
        assert value >= 0


def test_a_scaled_tetrahedron_is_not_degenerate():
    """Flatness is relative: a tetrahedron of any size has its volume, scaled by s³."""
    tetrahedron = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    for scale in (1e-30, 1.0, 1e30):
        assert sr.gamut_volume(tetrahedron * scale) == pytest.approx(scale**3 / 6, rel=1e-9)


@SETTINGS
@given(rgb=hnp.arrays(np.float64, (4, 3), elements=floats))
def test_ncc_and_knee(rgb):
    finite_or_refused(sr.ncc, rgb)
    finite_or_refused(sr.knee, rgb)


@SETTINGS
@given(values=st.lists(temperatures, max_size=4))
def test_illuminant_sets(values):
    finite_or_refused(sr.gamut_calibration, "gbell:9@450,540,610", np.full((5, grid.size), 0.4) *
                      np.linspace(0.5, 1, 5)[:, None] * np.linspace(0.5, 1, grid.size), 3300, values)


CAMERA = sr.camera("gbell:9@450,540,610")

BAD_ARGUMENTS = {
    # issue 36: each raised a bare ValueError, TypeError, IndexError or AttributeError, or was accepted
    "response grid": (lambda: sr.response(CAMERA, sr.reflectances("macbeth"), 2856, 2300, grid="x"), "grid"),
    "response knee": (lambda: sr.response(CAMERA, sr.reflectances("macbeth"), 2856, 2300, knee="yes"), "knee"),
    "gamut_volume text": (lambda: sr.gamut_volume("x"), "points"),
    "ncc text": (lambda: sr.ncc("x"), "rgb"),
    "measure None": (lambda: sr.measure(None), "chromaticity"),
    "skin_locus illuminants": (lambda: sr.skin_locus(CAMERA, illuminants="x"), "illuminants"),
    "WavelengthGrid text": (lambda: sr.WavelengthGrid("a", "b", "c"), "grid start"),
    "planck wavelength": (lambda: sr.planck("x", 3000), "wavelength"),
    "planck temperature": (lambda: sr.planck([500.0], "x"), "temperature"),
    "gbell None": (lambda: sr.gbell(None, 450, 90), "wavelength"),
    "impulse grid": (lambda: sr.impulse("x", 450), "grid"),
    "resample None": (lambda: sr.resample(None, None, None), "wavelengths"),
    "knee text": (lambda: sr.knee("x"), "x must be numbers"),
    "gain None": (lambda: sr.gain(None, None), "white_p"),
    "search sensor": (lambda: sr.search(None, None, None), "sensor"),
    "search shapes": (lambda: sr.search(9, sr.reflectances("macbeth").values, sr.reflectances("macbeth").values,
                                        positions="400:700:100"), "reflectance"),
}


@pytest.mark.parametrize("name", list(BAD_ARGUMENTS))
def test_a_bad_argument_is_a_skinrender_error_naming_it(name):
    call, named = BAD_ARGUMENTS[name]
    with pytest.raises(sr.SkinrenderError, match=named):
        call()
