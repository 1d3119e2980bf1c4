"""
Tests for :mod:`skinrender.rendering.face.limits`: the statistics on synthetic replicates (a correct
image passes, a wrong one fails), and the controls that must fail on renders: each limit applied
where it does not hold, or against a wrong analytic value.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats

from skinrender.model.chromaticity import ncc
from skinrender.rendering.face.labels import LABEL_SKIN
from skinrender.rendering.face.limit_scenes import furnace_radiance, sphere_channels
from skinrender.rendering.face.limits import (
    ALPHA,
    LINEAR,
    PIXELS_MIN,
    LimitCheck,
    check_dichromatic,
    check_furnace,
    check_shading,
    check_sphere,
    critical_t,
    eq4_shift,
    jackknife,
    rounding_bias,
)

CAMERA = "gbell:9@450,540,610"
SKIN = "skin:089 skin -- caucasian (light)"
COLOUR = np.array([120.0, 60.0, 30.0])
"""A synthetic skin's channels at full shading, output units."""


def synthetic(rng, colour=COLOUR, k: int = 12, side: int = 24, noise: float = 0.002) -> tuple[np.ndarray, ...]:
    """``k`` replicates of a square of skin of ``colour`` under varying shading, relative noise ``noise``."""
    labels = np.zeros((side, side), dtype=np.int32)
    labels[2:-2, 2:-2] = LABEL_SKIN
    shading = np.linspace(0.1, 1.0, side * side).reshape(side, side, 1)
    clean = shading * colour * (labels[..., None] == LABEL_SKIN)
    images = clean * (1 + noise * rng.standard_normal((k, side, side, 3)))
    return images, labels


class TestCriticalT:
    def test_sidak_matches_the_family_wise_rate(self):
        t = critical_t(100, 12, 0.01)
        each = 2 * stats.t.sf(t, 11)
        assert np.isclose(1 - (1 - each) ** 100, 0.01)

    def test_grows_with_the_tests(self):
        assert critical_t(10) < critical_t(1000) < critical_t(100_000)


class TestJackknife:
    def test_the_mean_has_the_standard_error(self, rng):
        samples = rng.standard_normal((12, 5))
        value, error = jackknife(samples, lambda m: m)
        assert np.allclose(value, samples.mean(axis=0))
        assert np.allclose(error, samples.std(axis=0, ddof=1) / np.sqrt(12))


class TestRoundingBias:
    @pytest.mark.parametrize("sigma", [0.15, 0.25, 0.4])
    def test_bounds_the_monte_carlo_mean_error(self, sigma, rng):
        offsets = np.linspace(0, 1, 21)
        values = offsets[:, None] + sigma * rng.standard_normal((21, 400_000))
        error = np.abs(np.rint(values).mean(axis=1) - offsets)
        assert np.all(error <= rounding_bias(sigma) + 4 * sigma / np.sqrt(400_000))
        assert error.max() > 0.5 * rounding_bias(sigma)  # and the bound is not loose

    def test_never_more_than_half_a_code(self):
        assert rounding_bias(0.0) == 0.5 and rounding_bias(2.0) < 1e-30


class TestCheckShading:
    def test_a_shaded_single_colour_passes(self, rng):
        images, labels = synthetic(rng)
        check = check_shading(images, labels, ncc(COLOUR))
        assert isinstance(check, LimitCheck) and check.passed and check.applies
        assert check.pixels == 20 * 20 - 2 * 20 - 2 * 18  # the interior of the square
        assert check.details["shading_range"] > 3
        assert set(check.document()) >= {"name", "applies", "passed", "statistic", "tolerance", "pixels",
                                          "reason"}

    def test_control_a_colour_off_by_a_tenth_of_a_percent_fails(self, rng):
        images, labels = synthetic(rng)
        check = check_shading(images, labels, ncc(COLOUR * [1.001, 1.0, 1.0]))
        assert check.passed is False and check.statistic > check.tolerance

    def test_control_colour_varying_with_shading_fails(self, rng):
        """A pixel whose colour depends on its brightness (a highlight, a bounce) is not Eq. 4's."""
        images, labels = synthetic(rng)
        images = images + 0.05 * images.sum(axis=-1, keepdims=True) ** 2 / 255
        assert check_shading(images, labels, ncc(COLOUR)).passed is False

    def test_a_bias_within_the_sensors_bound_passes(self, rng):
        images, labels = synthetic(rng, noise=0.0005)
        shifted = images + 0.02 * (labels[..., None] == LABEL_SKIN)
        assert check_shading(shifted, labels, ncc(COLOUR)).passed is False
        bias = np.full(labels.shape + (3,), 0.02)
        assert check_shading(shifted, labels, ncc(COLOUR), bias=bias).passed

    def test_identical_frames_take_the_sensors_standard_error(self, rng):
        """Twelve frames that read one code have no spread; the sensor's model gives their error."""
        images, labels = synthetic(rng, k=1, noise=0.0)
        images = np.repeat(np.rint(images), 12, axis=0)  # each pixel one code, up to half a code off
        assert check_shading(images, labels, ncc(COLOUR)).passed is False
        floor = np.full(labels.shape + (3,), (0.5**2 + 1 / 12) / 12)  # σ = 0.5 DN a frame and the codes
        assert check_shading(images, labels, ncc(COLOUR), bias=np.zeros_like(floor), floor=floor).passed

    def test_too_few_lit_pixels_is_not_a_failure(self, rng):
        images, labels = synthetic(rng, noise=5 * LINEAR)  # relative SE 5 LINEAR / √12 > LINEAR
        check = check_shading(images, labels, ncc(COLOUR))
        assert check.pixels < PIXELS_MIN and check.passed is None and "lit" in check.reason


class TestEq4Shift:
    def test_reports_the_shift_as_information(self, rng):
        images, labels = synthetic(rng, colour=COLOUR * [1.1, 1.0, 1.0])
        row = eq4_shift(images, labels, ncc(COLOUR), "why")
        assert row.applies is False and row.passed is None and "why" in row.reason
        expected = ncc(COLOUR)[:2] - ncc(COLOUR * [1.1, 1.0, 1.0])[:2]
        assert np.isclose(row.statistic, np.hypot(*expected), rtol=1e-3)
        assert row.details["share_outside"] == 1.0


class TestCheckDichromatic:
    def test_mixes_of_body_and_light_pass_and_others_fail(self, rng):
        body, light = COLOUR, np.array([80.0, 80.0, 80.0])
        images, labels = synthetic(rng)
        spec = np.linspace(0, 1, labels.size).reshape(labels.shape + (1,)) ** 4 * light
        mixed = images + spec * (labels[..., None] == LABEL_SKIN)
        check = check_dichromatic(mixed, labels, body, light)
        assert check.passed and check.details["highlights"]
        # control: a third colour in the mix leaves the plane
        assert check_dichromatic(mixed + spec * [0.0, 0.0, 0.05], labels, body, light).passed is False


@pytest.fixture(scope="module")
def renders():
    """Replicate face renders (48 px, 12 × 16 spp) at the given physics."""
    pytest.importorskip("mitsuba")
    from skinrender.rendering.face import render_face

    def replicates(**kwargs):
        out = [render_face(CAMERA, seed=k, size=48, spp=16, skin=SKIN, **kwargs) for k in range(12)]
        return out, np.array([r.image for r in out], dtype=np.float64)

    return replicates


class TestControlsOnRenders:
    """Each limit where it does not hold, or against a wrong value: the check must fail."""

    def test_shading_does_not_cancel_under_sheen(self, renders):
        from skinrender.rendering.face.scene import skin_reflectance_of
        from skinrender.rendering.validation import analytic_reference

        out, images = renders(physics="sheen", prevailing=2856, calibration=2856)
        expected = ncc(analytic_reference(CAMERA, skin_reflectance_of(SKIN)[None], 2856, 2856))[0]
        check = check_shading(images, out[0].labels, expected)
        assert check.passed is False, check

    def test_sheen_is_not_in_the_plane_of_another_light(self, renders):
        from skinrender.rendering.face.scene import Light
        from skinrender.rendering.face.effects.sheen import dichromatic_colours

        out, images = renders(physics="sheen", prevailing=2856, calibration=2856)
        check = check_dichromatic(images, out[0].labels, *dichromatic_colours(out[0], Light(6500.0, 1000.0)))
        assert check.passed is False, check

    def test_one_bounce_is_no_white_furnace(self):
        pytest.importorskip("mitsuba")
        radiance, labels, expected = furnace_radiance(CAMERA, "face", range(12), size=32, spp=16, physics="direct")
        check = check_furnace(radiance, labels, expected)
        assert check.passed is False, check

    def test_one_bounce_is_not_the_closed_form_of_every_bounce(self):
        pytest.importorskip("mitsuba")
        from skinrender.rendering.face.scene import skin_reflectance_of

        rho = skin_reflectance_of(SKIN)
        one = sphere_channels(CAMERA, rho, 2)
        assert check_sphere(CAMERA, rho, one, one).passed is False


def test_alpha_is_a_probability():
    assert 0 < ALPHA < 0.05
