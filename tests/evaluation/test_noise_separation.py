"""
Tests for :mod:`skinrender.evaluation.noise_separation`: on synthetic pixels whose physics and noise are known, the
separation keeps the physics' spread and removes the noise's, and the jackknife's bias and covariance are those of
a mean's chromaticity.
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.evaluation.noise_separation import GROUP_PIXELS_MIN, replicate_noise, rg_of, separate_noise


def noisy(centre, physics_sd, noise_sd, n, seed):
    """``n`` pixels: a physics spread (isotropic, ``physics_sd``) around ``centre``, seen through heteroscedastic
    Gaussian noise (each pixel's sd between ½ and 1½ × ``noise_sd``); their chromaticities and covariances."""
    rng = np.random.default_rng(seed)
    truth = np.asarray(centre) + physics_sd * rng.standard_normal((n, 2))
    scale = noise_sd * rng.uniform(0.5, 1.5, n)
    seen = truth + scale[:, None] * rng.standard_normal((n, 2))
    return truth, seen, scale[:, None, None] ** 2 * np.eye(2)


def test_noise_alone_goes_back_to_the_materials_chromaticity():
    """No physics spread (the analytic model's world): 30 seeds, every pixel goes to its material's mean, which is
    within 4 standard errors of the truth; no direction's excess passes the test (z = 5, one-sided)."""
    for seed in range(30):
        _, seen, covariance = noisy([0.6, 0.3], 0.0, 0.004, 900, seed)
        separated, spreads = separate_noise(seen, covariance, np.ones(900, int))
        assert np.allclose(separated, separated[0]) and not any(spreads[1].kept)
        assert np.abs(separated[0] - [0.6, 0.3]).max() < 4 * 0.004 / np.sqrt(900)


def test_a_physics_spread_is_kept_and_the_noise_removed():
    """A physics spread as large as the noise: the separated pixels' spread is the physics' (within 10 %), not the
    seen one's (√2 larger), and they stay near their own truths (closer than the seen pixels)."""
    truth, seen, covariance = noisy([0.6, 0.3], 0.004, 0.004, 4000, 1)
    separated, spreads = separate_noise(seen, covariance, np.ones(4000, int))
    assert all(spreads[1].kept)
    assert separated.std(axis=0) == pytest.approx([0.004, 0.004], rel=0.1)
    assert seen.std(axis=0) == pytest.approx([0.004 * np.sqrt(2)] * 2, rel=0.1)
    assert np.mean(np.linalg.norm(separated - truth, axis=1)) < np.mean(np.linalg.norm(seen - truth, axis=1))


def test_materials_are_separated_each_on_its_own():
    """Two materials, one with a spread and one without: each keeps its own mean; a material of too few pixels is
    left as seen, with its reason."""
    _, a, ca = noisy([0.6, 0.3], 0.0, 0.004, 500, 2)
    _, b, cb = noisy([0.5, 0.35], 0.006, 0.004, 500, 3)
    _, c, cc = noisy([0.4, 0.4], 0.0, 0.004, GROUP_PIXELS_MIN - 1, 4)
    groups = np.repeat([1, 2, 3], [500, 500, GROUP_PIXELS_MIN - 1])
    separated, spreads = separate_noise(np.vstack([a, b, c]), np.vstack([ca, cb, cc]), groups)
    assert np.allclose(separated[:500], a.mean(axis=0)) and spreads[2].kept != (False, False)
    assert np.array_equal(separated[1000:], c) and not spreads[3].separated and "fewer than" in spreads[3].reason


def test_the_jackknife_gives_a_means_bias_and_covariance():
    """Replicates with skewed noise, as a render's few samples are (exponential, relative sd 100 % per replicate):
    the chromaticity of the mean of 12 is biased (over 4000 pixels of one colour, r is 4.6 standard errors low);
    the jackknife's bias estimate takes it off (within 2), and its covariance is the mean's own spread across the
    pixels (within 10 %)."""
    rng = np.random.default_rng(5)
    colour = np.array([8.0, 4.0, 2.0])
    replicates = colour * rng.exponential(1.0, (12, 4000, 3))
    bias, covariance = replicate_noise(replicates)
    chromaticity = rg_of(replicates.mean(axis=0))
    truth, se = rg_of(colour), chromaticity.std(axis=0) / np.sqrt(4000)
    assert np.abs(chromaticity.mean(axis=0) - truth)[0] > 4 * se[0]
    assert np.all(np.abs((chromaticity - bias).mean(axis=0) - truth) < 2 * se)
    assert np.diag(covariance.mean(axis=0)) == pytest.approx(chromaticity.var(axis=0), rel=0.1)


@pytest.mark.parametrize("args", [(np.zeros((3, 3)), np.zeros((3, 2, 2)), np.ones(3)),
                                  (np.zeros((3, 2)), np.zeros((2, 2, 2)), np.ones(3))])
def test_shapes_are_checked(args):
    with pytest.raises(SkinrenderError, match="separate_noise"):
        separate_noise(*args)


def test_one_replicate_has_no_spread():
    with pytest.raises(SkinrenderError, match="two or more"):
        replicate_noise(np.ones((1, 4, 3)))
