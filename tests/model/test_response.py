"""Tests for :mod:`skinrender.camera`: Eqs. 1–11 against values worked out by hand."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import skinrender as sr
from skinrender.model.camera import camera
from skinrender.model.chromaticity import measure, ncc
from skinrender.model.response import knee, normalisation_factor, response, response_raw, white_coefficient
from skinrender.constants import CONSTANT_KNEE_FACTOR, TEMPERATURES_PAPER, TOLERANCE_ABSOLUTE_TESTS
from skinrender.errors import SkinrenderError
from skinrender.spectra import GRID_DEFAULT, WavelengthGrid, planck

CAMERAS = ["gbell:9@450,540,610", "gbell:3,b=1@420,550,560", "impulse@450,540,610", "Nikon 5100 (NPL)", "Kodak DCS-200"]
WHITE = np.ones((1, GRID_DEFAULT.size))


class TestCamera:
    def test_gbell_spec(self):
        cam = camera("gbell:9@450,540,610")
        assert cam.kind == "gbell" and cam.fwhm == 90 and cam.slope == 2
        assert cam.peaks == (610, 540, 450)  # R, G, B: longest first

    def test_order_does_not_matter(self):
        a = camera("gbell:5,b=3@610,450,540").sensitivities()
        b = camera("gbell:5,b=3@450,540,610").sensitivities()
        np.testing.assert_array_equal(a, b)

    def test_gbell_sensitivities(self):
        """Sensor 9 at 540 nm: value 1 at 540, 1/2 at 540 ± 45 nm."""
        s = camera("gbell:9@450,540,610").sensitivities()
        assert s[1, 140] == 1 and s[1, 95] == pytest.approx(0.5) and s[1, 185] == pytest.approx(0.5)

    def test_measured_case_insensitive(self):
        assert camera("nikon 5100 (npl)").measured.name == "Nikon 5100 (NPL)"

    def test_unknown_lists_known(self):
        with pytest.raises(SkinrenderError, match=r"unknown camera 'Sony XYZ'; known: 'Nikon 5100 \(NPL\)'.*Kodak"):
            camera("Sony XYZ")

    @pytest.mark.parametrize("spec", ["gbell:9@450,540", "gbell:x@1,2,3", "gbell:0@450,540,610", "impulse@a,b,c",
                                      "gbell:9,b=-1@450,540,610", "gbell9@450"])
    def test_malformed(self, spec):
        with pytest.raises(SkinrenderError, match="camera"):
            camera(spec)

    def test_impulse_off_grid(self):
        with pytest.raises(SkinrenderError, match="not a sample"):
            camera("impulse@455,540,610").sensitivities(WavelengthGrid(400, 700, 10))

    def test_csv_camera_not_covering_grid(self, tmp_path):
        path = tmp_path / "cam.csv"
        path.write_text("nm,R,G,B\n420,1,1,1\n680,1,1,1\n")
        cam = camera(str(path))
        with pytest.raises(SkinrenderError, match="does not cover"):
            cam.sensitivities()
        assert camera(str(path), extrapolation="zero").sensitivities()[0, 0] == 0


class TestResponseRaw:
    def test_impulse_hand_value(self):
        """Eq. 1 with unit-area impulses at 610/540/450 nm and o = 0.5: X_k = 0.5 · L(p_k, T)."""
        o = np.full((1, GRID_DEFAULT.size), 0.5)
        rgb = response_raw("impulse@450,540,610", o, 3300)
        np.testing.assert_allclose(rgb[0], 0.5 * planck([610, 540, 450], 3300), rtol=1e-12)

    def test_560nm_normalisation(self):
        """Eq. 6: I_1 = 100 · SPD / SPD(560), so an impulse at 560 nm sees exactly 100 · o."""
        rgb = response_raw("impulse@450,560,610", WHITE * 0.25, 7500, "560nm")
        assert rgb[0, 1] == pytest.approx(25.0, rel=1e-12)

    def test_euclidean_normalisation(self):
        """Eq. 7: I_2 = SPD / ||SPD||₂ over the grid samples."""
        spd = planck(GRID_DEFAULT.wavelengths, 4800)
        assert normalisation_factor(4800, "euclidean") == pytest.approx(1 / np.sqrt(np.sum(spd**2)))
        rgb = response_raw("impulse@450,540,610", WHITE, 4800, "euclidean")
        np.testing.assert_allclose(rgb[0], planck([610, 540, 450], 4800) / np.sqrt(np.sum(spd**2)), rtol=1e-12)

    def test_flat_spectrum_furnace(self):
        """A flat SPD of 1 through a camera on the grid gives Σ S_c(λ) Δλ per channel."""
        from skinrender.model.illuminant import Illuminant

        flat = Illuminant("flat", None, (380.0, 780.0), (1.0, 1.0))
        cam = camera("gbell:9@450,540,610")
        rgb = response_raw(cam, WHITE, flat)
        np.testing.assert_allclose(rgb[0], cam.sensitivities().sum(axis=1) * GRID_DEFAULT.step, rtol=1e-12)

    def test_shapes(self, rng):
        o = rng.random((2, 4, GRID_DEFAULT.size))
        assert response_raw("Kodak DCS-200", o, [2000, 3000, 4000]).shape == (3, 2, 4, 3)
        assert response_raw("Kodak DCS-200", o, 2000).shape == (2, 4, 3)


class TestResponse:
    @pytest.mark.parametrize("spec", CAMERAS)
    @pytest.mark.parametrize("normalization", sr.NORMALISATIONS)
    def test_white_at_p_equals_c_is_v(self, spec, normalization):
        """Eq. 4 at p = c: a white object gives v = 255 in every channel, whatever the normalisation."""
        for t in (2000, 5900, 10000):
            np.testing.assert_allclose(response(spec, WHITE, t, t, normalization), 255, atol=1e-10)

    def test_grey_scales(self):
        """Linearity: a grey of 0.2 at p = c gives 51 = 0.2 · 255."""
        np.testing.assert_allclose(response("Nikon 5100 (NPL)", WHITE * 0.2, "A", "A"), 51, atol=1e-10)

    def test_impulse_hand_value(self):
        """Impulses: X_k = v · WP · L(p_k, Tp) / L(p_k, Tc) for a white object."""
        peaks = np.array([610.0, 540.0, 450.0])
        ratio = planck(peaks, 2300) / planck(peaks, 2856)
        wp = 3 / ratio.sum()
        np.testing.assert_allclose(response("impulse@450,540,610", WHITE, "H", "A")[0], 255 * wp * ratio, rtol=1e-12)
        np.testing.assert_allclose(
            response("impulse@450,540,610", WHITE, "H", "A", "none")[0], 255 * ratio, rtol=1e-12
        )

    def test_eq10_factors(self, rng):
        """Eq. 10: normalisation n multiplies the unnormalised Eq. 4 by F_pn / F_cn."""
        o = rng.random((5, GRID_DEFAULT.size))
        cam = "gbell:7@460,530,620"
        base = response(cam, o, 2000, 7500, "none")
        f560 = planck(560, 7500) / planck(560, 2000)  # (100/SPD_p(560)) / (100/SPD_c(560))
        np.testing.assert_allclose(response(cam, o, 2000, 7500, "560nm"), base * f560, rtol=1e-12)
        norm = np.linalg.norm
        feuc = norm(planck(GRID_DEFAULT.wavelengths, 7500)) / norm(planck(GRID_DEFAULT.wavelengths, 2000))
        np.testing.assert_allclose(response(cam, o, 2000, 7500, "euclidean"), base * feuc, rtol=1e-12)
        wp = white_coefficient(cam, 2000, 7500)
        np.testing.assert_allclose(response(cam, o, 2000, 7500, "white"), base * wp, rtol=1e-12)

    def test_white_coefficient_is_one_at_p_equals_c(self):
        t = np.array(TEMPERATURES_PAPER)
        np.testing.assert_allclose(np.diag(white_coefficient("Nikon 5100 (NPL)", t[:, None], t[None, :])), 1, atol=1e-14)

    def test_white_response_sums_to_3v(self):
        """With WP (Eq. 8, scaled), a white object's channels sum to 3v for every (p, c)."""
        t = np.array(TEMPERATURES_PAPER)
        rgb = response("Canon EOS 5D Mark II", WHITE, t[:, None], t[None, :])
        np.testing.assert_allclose(rgb.sum(axis=-1), 3 * 255, rtol=1e-12)

    def test_all_pairs_equal_single_calls(self):
        t = np.array([2000.0, 3300.0, 10000.0])
        all_pairs = response("Kodak DCS-200", "macbeth", t[:, None], t[None, :])
        assert all_pairs.shape == (3, 3, 24, 3)
        for i, p in enumerate(t):
            for j, c in enumerate(t):
                np.testing.assert_allclose(all_pairs[i, j], response("Kodak DCS-200", "macbeth", p, c), rtol=1e-13)

    def test_n_dimensional(self, rng):
        o = rng.random((6, GRID_DEFAULT.size))
        flat = response("gbell:9@450,540,610", o, 2800, 5900)
        np.testing.assert_allclose(response("gbell:9@450,540,610", o.reshape(2, 3, -1), 2800, 5900), flat.reshape(2, 3, 3))

    def test_against_colour_science(self):
        """Eq. 4 at p = c equals colour's ``training_data_sds_to_RGB`` on the ColorChecker, up to a
        per-channel scale: colour multiplies by 1/white (scaled so the smallest multiplier is 1),
        Eq. 4 by v/white, so the ratio is one constant for all patches and channels."""
        colour = pytest.importorskip("colour")
        from colour.characterisation import RGB_CameraSensitivities, training_data_sds_to_RGB

        grid = GRID_DEFAULT
        cam = camera("Nikon 5100 (NPL)")
        macbeth = sr.reflectances("macbeth")
        training = colour.MultiSpectralDistributions(macbeth.on(grid).T, grid.wavelengths)
        sensitivities = RGB_CameraSensitivities(cam.sensitivities(grid).T, grid.wavelengths)
        for t in (2300.0, 2856.0, 6500.0):
            sd = colour.SpectralDistribution(planck(grid.wavelengths, t), grid.wavelengths)
            theirs, _ = training_data_sds_to_RGB(training, sensitivities, sd)
            ours = response(cam, macbeth, t, t)
            ratio = ours / theirs
            np.testing.assert_allclose(ratio, ratio[0, 0], rtol=1e-12)

    @pytest.mark.parametrize("t", [300.0, 1000.0, 25000.0, 50000.0])
    def test_extreme_temperatures_finite(self, t):
        rgb = response("gbell:9@450,540,610", "macbeth", t, 5900)
        assert np.all(np.isfinite(rgb)) and np.all(rgb >= 0)

    def test_knee_applied(self):
        """10000 K seen with a 2000 K calibration: blue far above 255 before the knee, 255 after;
        red below the knee point and untouched."""
        linear = response("gbell:9@450,540,610", WHITE, 10000, 2000, "560nm")
        kneed = response("gbell:9@450,540,610", WHITE, 10000, 2000, "560nm", knee=True)
        np.testing.assert_array_equal(kneed, knee(linear))
        assert linear[0, 2] > 1110 and kneed[0, 2] == 255
        assert linear[0, 0] < 244 and kneed[0, 0] == linear[0, 0]

    def test_bad_normalization(self):
        with pytest.raises(SkinrenderError, match="normalization must be one of none, 560nm, euclidean, white"):
            response("Kodak DCS-200", WHITE, 3000, 3000, "max")

    def test_bad_temperature(self):
        with pytest.raises(SkinrenderError, match=r"kelvin in \(0, "):
            response("Kodak DCS-200", WHITE, -100, 3000)

    def test_bad_array(self):
        with pytest.raises(SkinrenderError, match="301 samples"):
            response("Kodak DCS-200", np.ones((2, 30)), 3000, 3000)

    @settings(max_examples=40, deadline=None)
    @given(
        st.floats(1000, 30000), st.floats(1000, 30000),
        st.sampled_from(["none", "560nm", "euclidean"]), st.sampled_from(["none", "560nm", "euclidean", "white"]),
    )
    def test_normalisation_cancels_in_ncc(self, tp, tc, n1, n2):
        """Property: every normalisation is a factor common to the channels, so NCC is unchanged."""
        o = np.linspace(0.1, 0.9, GRID_DEFAULT.size)[None, :]
        a = ncc(response("gbell:9@450,540,610", o, tp, tc, n1))
        b = ncc(response("gbell:9@450,540,610", o, tp, tc, n2))
        np.testing.assert_allclose(a, b, atol=1e-12)


class TestLinearity:
    @settings(max_examples=40, deadline=None)
    @given(st.floats(0, 0.75), st.floats(0, 0.75), st.integers(0, 2**32 - 1), st.floats(1500, 20000))
    def test_eq1_linear_in_reflectance(self, a, b, seed, t):
        """Property: Eq. 1 is linear in o, X(a·o1 + b·o2) = a·X(o1) + b·X(o2) (combinations kept within the
        reflectances the API accepts, [0, 1.5])."""
        rng = np.random.default_rng(seed)
        o1, o2 = rng.random((2, 1, GRID_DEFAULT.size))
        left = response_raw("Nikon 5100 (NPL)", a * o1 + b * o2, t, "euclidean")
        right = a * response_raw("Nikon 5100 (NPL)", o1, t, "euclidean") + b * response_raw(
            "Nikon 5100 (NPL)", o2, t, "euclidean"
        )
        scale = np.abs(response_raw("Nikon 5100 (NPL)", np.ones_like(o1), t, "euclidean")).max() * (a + b + 1)
        np.testing.assert_allclose(left, right, atol=1e-12 * scale)


class TestKnee:
    def test_hand_values(self):
        """Below 244 identity; above, 244(1 − a) + aX; 255 past the end of the slope."""
        a = CONSTANT_KNEE_FACTOR
        np.testing.assert_allclose(knee([0, 100, 244]), [0, 100, 244])
        assert knee(500) == pytest.approx(244 * (1 - a) + a * 500)
        assert knee(500) == pytest.approx(247.2512)
        assert knee(2000) == 255 and knee(1e9) == 255

    def test_continuous(self):
        """Continuous at the knee point 244 and at the end of the slope (1110.14, printed 1109)."""
        eps = 1e-9
        end = 244 + 11 / CONSTANT_KNEE_FACTOR
        assert abs(knee(244 + eps) - knee(244 - eps)) < 1e-8
        assert abs(knee(end + eps) - knee(end - eps)) < 1e-8
        assert abs(knee(1109 + eps) - knee(1109 - eps)) < 1e-8
        assert knee(1109) == pytest.approx(255, abs=0.015)  # the paper's rounded end

    def test_monotone(self):
        x = np.linspace(-10, 3000, 30001)
        assert np.all(np.diff(knee(x)) >= 0)

    def test_n_dimensional(self):
        x = np.array([100.0, 500.0, 2000.0, 244.0, 1109.0, 50.0])
        np.testing.assert_allclose(knee(x.reshape(2, 3, 1)).ravel(), knee(x))


class TestNcc:
    def test_hand_value(self):
        np.testing.assert_allclose(ncc([30.0, 50.0, 20.0]), [0.3, 0.5, 0.2])

    def test_black_is_achromatic(self):
        np.testing.assert_allclose(ncc([0.0, 0.0, 0.0]), [1 / 3, 1 / 3, 1 / 3])

    def test_bad_shape(self):
        with pytest.raises(SkinrenderError, match="three channels"):
            ncc([1.0, 2.0])

    @settings(max_examples=60, deadline=None)
    @given(st.lists(st.floats(1e-6, 1e6), min_size=3, max_size=3), st.floats(1e-6, 1e6))
    def test_sums_to_one_and_scale_invariant(self, rgb, k):
        """Property: NCC sums to 1 and is invariant to a common scale k."""
        rgb = np.array(rgb)
        assert ncc(rgb).sum() == pytest.approx(1.0, abs=1e-12)
        np.testing.assert_allclose(ncc(k * rgb), ncc(rgb), atol=1e-12)

    def test_n_dimensional(self, rng):
        rgb = rng.random((4, 5, 3))
        np.testing.assert_allclose(ncc(rgb).sum(axis=-1), 1, atol=TOLERANCE_ABSOLUTE_TESTS)


class TestMeasure:
    def test_hand_value(self):
        """sqrt(0.3² + 0.4²) = 0.5 for the (g, b) pair."""
        assert measure([0.3, 0.3, 0.4]) == pytest.approx(0.5)
        assert measure([0.6, 0.8, 0.0], "rg") == pytest.approx(1.0)

    def test_bad_pair(self):
        with pytest.raises(SkinrenderError, match="pair"):
            measure([0.3, 0.3, 0.4], "gg")
