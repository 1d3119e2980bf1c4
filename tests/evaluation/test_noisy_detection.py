"""
Tests for :mod:`skinrender.evaluation.noisy_detection`: the noise-free chain
gives the Eq. 4 chromaticities, the automatic exposure, the noisy rates tend
to the noise-free ones as the collected charge grows, seeding, and every bad
input.

The convergence check needs no statistical tolerance: a pixel can change
class only if its noise moves it across the locus boundary, so the noisy and
noise-free rates differ by at most the share of points within 8 NCC standard
deviations (delta method) of the boundary; as the light grows, that band
shrinks to the hull's own vertices (training points on the boundary, which
noise of any size pushes out about half the time).
"""

from __future__ import annotations

import math

import numpy as np

from skinrender.model.exposure import AUTO_EXPOSURE_MAX_S, imaging
import pytest

from skinrender.datasets import reflectances
from skinrender.errors import SkinrenderError
from skinrender.evaluation.locus import locus_points, skin_locus
from skinrender.evaluation.noisy_detection import (
    AUTO_EXPOSURE_FRACTION,
    NoisyDetection,
    noisy_detection,
    pixel_electrons,
)
from skinrender.model.camera import camera
from skinrender.model.chromaticity import ncc
from skinrender.model.imager import Imager, imager
from skinrender.model.noise import ncc_covariance, statistics_dn
from skinrender.model.response import response

CAMERA = camera("gbell:9@450,540,610")
ILLUMINANTS = np.array([2500.0, 4000.0, 6500.0])
"""Three of the paper's range, K: nine (prevailing, calibration) pairs keep the tests fast."""

N_SIGMA_BAND = 8.0
"""Half-width of the boundary band in NCC standard deviations: a normal tail beyond 8 σ is < 1e-15."""

BIG_WELL = Imager(name="big-well", source="tests: a well that never fills", pixel_um=5.0, f_number=2.8,
                  transmittance=0.9, qe_peak=0.6, full_well_e=1e13, read_noise_e=5.0, dark_current_e_per_s=0.0,
                  gain_dn_per_e=4e-4, bits=32, black_level_dn=100.0)
"""An imager whose shot noise can be made as small as wanted: K μ_sat + b = 4e9 DN < 2³² − 1."""


@pytest.fixture(scope="module")
def sets() -> tuple[np.ndarray, np.ndarray]:
    """Skin (30) and every tenth Munsell chip (127), on the default grid."""
    return reflectances("skin").on(), reflectances("munsell").on()[::10]


def band_share(locus, points: np.ndarray, delta: float) -> float:
    """Share of (r, g) points whose class can change under a displacement smaller than ``delta``.

    With the hull counter-clockwise, d_e = cross(edge, p − start) / |edge| is the signed distance to
    edge e's line (positive inside): an inside point with min_e d_e > δ and an outside point with
    max_e (−d_e) > δ keep their class.
    """
    start = locus.polygon
    edge = np.roll(start, -1, axis=0) - start
    offset = points[:, None, :] - start[None, :, :]
    distance = (edge[None, :, 0] * offset[..., 1] - edge[None, :, 1] * offset[..., 0]) / np.hypot(*edge.T)[None]
    inside = np.all(distance >= 0, axis=1)
    near = np.where(inside, distance.min(axis=1) <= delta, (-distance).max(axis=1) <= delta)
    return float(np.mean(near))


def ncc_std_max(im: Imager, pixels) -> float:
    """The largest NCC standard deviation (delta method) over the pixels."""
    mean, variance = statistics_dn(im, pixels.electrons)
    gains = np.broadcast_to(pixels.gains, mean.shape)
    covariance = ncc_covariance(mean - im.black_level_dn, variance, gains)
    return float(np.sqrt(np.diagonal(covariance, axis1=-2, axis2=-1).max()))


class TestPixelElectrons:
    def test01_noise_free_chain_is_eq4(self, sets):
        """Without noise or dark current, gain · K · μ has the Eq. 4 chromaticities of every pair."""
        skin, _ = sets
        pixels = pixel_electrons(CAMERA, skin, ILLUMINANTS, ILLUMINANTS, imaging(BIG_WELL, 500.0))
        assert pixels.electrons.shape == (3, 3, 30, 3) and pixels.gains.shape == (3, 3, 1, 3)
        chain = ncc(pixels.gains * BIG_WELL.gain_dn_per_e * pixels.electrons)
        eq4 = ncc(response(CAMERA, skin, ILLUMINANTS[:, None], ILLUMINANTS[None, :]))
        np.testing.assert_allclose(chain, eq4, rtol=1e-12, atol=1e-14)

    def test02_auto_exposure_puts_the_white_at_the_fraction(self):
        im = imager("sony-icx418")
        white = np.ones((1, CAMERA.sensitivities().shape[1]))
        bright = imaging(im, 5000.0)  # under a frame time
        pixels = pixel_electrons(CAMERA, white, ILLUMINANTS, ILLUMINANTS, bright)
        diagonal = pixels.electrons[np.arange(3), np.arange(3), 0]  # p = c: the calibration white
        assert np.all(pixels.exposure_s < AUTO_EXPOSURE_MAX_S)
        np.testing.assert_allclose(diagonal.max(axis=-1), AUTO_EXPOSURE_FRACTION * im.full_well_e, rtol=1e-12)
        dim = pixel_electrons(CAMERA, white, ILLUMINANTS, ILLUMINANTS, imaging(im, 5.0))  # dim: the frame time caps it
        np.testing.assert_array_equal(dim.exposure_s, AUTO_EXPOSURE_MAX_S)
        fixed = pixel_electrons(CAMERA, white, ILLUMINANTS, ILLUMINANTS, imaging(im, 400.0, 0.01))
        np.testing.assert_array_equal(fixed.exposure_s, 0.01)
        doubled = pixel_electrons(CAMERA, white, ILLUMINANTS, ILLUMINANTS, imaging(im, 800.0, 0.01))
        dark = im.dark_current_e_per_s * 0.01  # e⁻: photo-electrons double with the light, dark ones do not
        np.testing.assert_allclose(doubled.electrons - dark, 2 * (fixed.electrons - dark), rtol=1e-12)


class TestNoisyDetection:
    def test01_tends_to_noise_free_as_the_light_grows(self, sets):
        """Fixed exposure, a well that never fills: at each illuminance the rates differ from the
        noise-free ones by at most the boundary band, which shrinks as the charge grows: the false-positive
        rate reaches the noise-free one, the true-positive rate comes within the share of hull vertices."""
        skin, nonskin = sets
        white = np.ones((1, skin.shape[1]))
        lux_max = 1e6
        rate = pixel_electrons(CAMERA, white, ILLUMINANTS, ILLUMINANTS, imaging(BIG_WELL, lux_max, 1.0))
        exposure = 0.5 * BIG_WELL.full_well_e / rate.electrons.max()  # s: the brightest white at half the well
        locus = skin_locus(CAMERA, skin, ILLUMINANTS)
        free_skin, free_other = locus_points(CAMERA, skin, ILLUMINANTS), locus_points(CAMERA, nonskin, ILLUMINANTS)
        results, bands = [], []
        for lux in (1e-2, 1.0, 1e2, 1e4, lux_max):
            result = noisy_detection(CAMERA, skin, nonskin, ILLUMINANTS, BIG_WELL, lux, exposure, samples=8,
                                     seed=11, locus=locus)
            setting = imaging(BIG_WELL, lux, exposure)
            sigma = max(ncc_std_max(BIG_WELL, pixel_electrons(CAMERA, data, ILLUMINANTS, ILLUMINANTS, setting))
                        for data in (skin, nonskin))
            band = (band_share(locus, free_skin, N_SIGMA_BAND * sigma),
                    band_share(locus, free_other, N_SIGMA_BAND * sigma))
            assert abs(result.tpr - result.tpr_noise_free) <= band[0]
            assert abs(result.fpr - result.fpr_noise_free) <= band[1]
            results.append(result)
            bands.append(band)
        assert [sum(band) for band in bands] == sorted((sum(band) for band in bands), reverse=True)
        # at the most light only the hull's own vertices (training points on the boundary) can still flip
        assert bands[-1] == (band_share(locus, free_skin, 1e-12), 0.0)
        assert results[-1].fpr == results[-1].fpr_noise_free
        assert results[-1].tpr_noise_free - results[-1].tpr <= bands[-1][0] <= 0.05
        assert results[0].tpr < results[-1].tpr - 0.2  # little light, much noise: skin pixels leave the locus
        assert result.tpr_noise_free == 1.0  # the hull holds its training points

    def test02_a_real_imager_loses_skin_pixels(self, sets):
        skin, nonskin = sets
        result = noisy_detection(CAMERA, skin, nonskin, ILLUMINANTS, "sony-icx418", 500.0, samples=8, seed=3)
        assert isinstance(result, NoisyDetection)
        assert result.tpr < result.tpr_noise_free - 5 * result.tpr_se
        assert result.imager == "sony-icx418" and result.illuminance_lux == 500.0 and result.samples == 8
        assert result.calibrations_K == tuple(ILLUMINANTS) and len(result.exposure_s) == 3
        assert all(0 < value < 0.05 for value in result.skin_ncc_std)

    def test03_little_light_pixels_at_the_black_level(self, sets):
        """At 5 lx for 1 ms the dark channels sink into the read noise around the black level: they are
        clipped at 0 DN above black (a pixel with nothing above black is not skin), never an error."""
        skin, nonskin = sets
        result = noisy_detection(CAMERA, skin, nonskin, ILLUMINANTS, "sony-imx174", 5.0, 0.001, samples=2)
        assert result.tpr < 0.5 * result.tpr_noise_free
        assert 0 <= result.fpr <= 1

    def test04_binomial_errors_and_seeding(self, sets):
        skin, nonskin = sets
        first = noisy_detection(CAMERA, skin, nonskin, ILLUMINANTS, "sony-imx174", 300.0, samples=4, seed=5)
        assert first == noisy_detection(CAMERA, skin, nonskin, ILLUMINANTS, "sony-imx174", 300.0, samples=4,
                                        seed=np.random.default_rng(5))
        other = noisy_detection(CAMERA, skin, nonskin, ILLUMINANTS, "sony-imx174", 300.0, samples=4, seed=6)
        assert (other.tpr, other.fpr) != (first.tpr, first.fpr)
        pixels_skin, pixels_other = 4 * 9 * len(skin), 4 * 9 * len(nonskin)
        assert first.tpr_se == pytest.approx(math.sqrt(first.tpr * (1 - first.tpr) / pixels_skin), rel=1e-12)
        assert first.fpr_se == pytest.approx(math.sqrt(first.fpr * (1 - first.fpr) / pixels_other), rel=1e-12)

    def test05_one_calibration(self, sets):
        skin, nonskin = sets
        result = noisy_detection(CAMERA, skin, nonskin, ILLUMINANTS, "sony-imx174", 500.0, samples=2,
                                 calibration=4000.0)
        assert result.calibrations_K == (4000.0,) and len(result.exposure_s) == 1
        assert result.fpr_se > 0

    @pytest.mark.parametrize(
        ("change", "name"),
        [({"illuminance_lux": 0.0}, "illuminance_lux"), ({"illuminance_lux": -5.0}, "illuminance_lux"),
         ({"illuminance_lux": math.nan}, "illuminance_lux"), ({"illuminance_lux": math.inf}, "illuminance_lux"),
         ({"exposure": 0.0}, "exposure"), ({"exposure": math.nan}, "exposure"), ({"exposure": "fast"}, "exposure"),
         ({"samples": 0}, "samples"), ({"samples": 2.5}, "samples"), ({"samples": True}, "samples"),
         ({"seed": -1}, "seed"), ({"seed": 2**32}, "seed"), ({"seed": 1.5}, "seed"),
         ({"skin": np.ones((2, 10))}, "skin"), ({"nonskin": -np.ones((2, 301))}, "nonskin"),
         ({"illuminants": [-3000.0]}, "illuminants"), ({"imager_": "no-such-imager"}, "imager")],
    )
    def test06_bad_input(self, sets, change, name):
        skin, nonskin = sets
        arguments = {"cam": CAMERA, "skin": skin, "nonskin": nonskin, "illuminants": ILLUMINANTS,
                     "imager_": "sony-imx174", "illuminance_lux": 500.0, "samples": 1} | change
        with pytest.raises(SkinrenderError, match=name):
            noisy_detection(**arguments)


def test_black_frames_give_undefined_rates_and_spread_with_reasons():
    """1 mlx for 1 µs: no electron reaches any pixel; nothing has a chromaticity."""
    skin, chips = reflectances("skin").on(), reflectances("munsell").on()[::40]
    result = noisy_detection(CAMERA, skin, chips, ILLUMINANTS, "sony-icx418", 1e-3, exposure=1e-6, samples=2)
    assert result.tpr is None and result.tpr_se is None and "black" in result.undefined["tpr"]
    assert result.black_share[0] == 1.0
    assert all(math.isnan(v) for v in result.skin_ncc_std) and "delta" in result.undefined["skin_ncc_std"]


def test_skin_ncc_std_stays_a_chromaticity_spread_in_dim_light():
    """Dim but not black: every std reported lies in [0, 1] (an NCC coordinate does), never the blow-up of S ≈ 0."""
    skin, chips = reflectances("skin").on(), reflectances("munsell").on()[::40]
    result = noisy_detection(CAMERA, skin, chips, ILLUMINANTS, "sony-imx174", 5.0, exposure=1e-4, samples=2)
    spread = np.array(result.skin_ncc_std)
    assert np.all(np.isnan(spread) | ((spread >= 0) & (spread <= 1))), spread


def test_long_exposure_reports_the_clipped_pixels():
    skin, chips = reflectances("skin").on(), reflectances("munsell").on()[::40]
    result = noisy_detection(CAMERA, skin, chips, ILLUMINANTS, "sony-icx418", 500.0, exposure=1.0, samples=2)
    full = np.array(result.clipping["skin"]["well_full_share"])
    assert np.all(full > 0.3) and any(note.startswith("skin pixels clipped") for note in result.notes)
    assert result.clipping["skin"]["pixels"] == 2 * len(skin) * len(ILLUMINANTS) ** 2


def test_capped_auto_exposure_is_noted():
    electrons = pixel_electrons(CAMERA, np.ones((1, 301)), [3300.0], [3300.0], imaging("sony-icx418", 500.0))
    assert electrons.exposure_s[0] == AUTO_EXPOSURE_MAX_S and "not the 0.7 target" in electrons.notes[0]
    reached = electrons.electrons.max() / imager("sony-icx418").full_well_e
    assert f"{reached:.3g} of the full well" in electrons.notes[0]
    assert pixel_electrons(CAMERA, np.ones((1, 301)), [3300.0], [3300.0], imaging("sony-imx174", 500.0)).notes == ()
