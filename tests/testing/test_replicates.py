"""Tests for :mod:`skinrender.testing.replicates`: a face region's standard error from the replicates' per-pixel
covariance is calibrated where the pixels' means differ (shading), and the skin NCC is of the skin's mean."""

from __future__ import annotations

import numpy as np

from skinrender.testing.replicates import REPLICATES, region_values, replicate_seeds


class TestFaceValues:
    def test_region_standard_errors_from_replicates_are_calibrated(self, rng):
        """Pixels of one region with different means and noises (shading): the region mean's standard error from
        the per-pixel replicate covariance matches the spread of the region mean over 400 draws."""
        labels = np.zeros((12, 12), dtype=np.int32)
        labels[3:9, 3:9] = 1
        shade = rng.uniform(0.2, 1.0, (12, 12, 1)) * np.array([100.0, 60.0, 30.0])
        noise = rng.uniform(0.5, 3.0, (12, 12, 1))
        regions = {"background": 0, "skin": 1}
        draws, ses = [], []
        for _ in range(400):
            stack = shade + noise * rng.normal(size=(REPLICATES, 12, 12, 3))
            deviation = stack - stack.mean(axis=0)
            covariance = np.einsum("khwi,khwj->hwij", deviation, deviation) / (REPLICATES - 1) / REPLICATES
            mean, se, dof = region_values(stack.mean(axis=0), labels, regions, covariance)
            draws.append(mean)
            ses.append(se)
        ratio = np.std(draws, axis=0, ddof=1) / np.sqrt(np.mean(np.square(ses), axis=0))
        assert mean.size == 3 + 3 + 2 and np.all(dof[:6] > 20)
        np.testing.assert_allclose(ratio, 1.0, atol=0.15)

    def test_ncc_is_of_the_skin_mean(self):
        image = np.zeros((2, 2, 3))
        image[0, 0] = [2.0, 1.0, 1.0]
        labels = np.array([[1, 0], [0, 0]])
        mean, _, _ = region_values(image, labels, {"background": 0, "skin": 1})
        np.testing.assert_allclose(mean[-2:], [0.5, 0.25])


def test_replicate_seeds_are_32_bit_and_distinct():
    seeds = replicate_seeds(0) + replicate_seeds(1) + replicate_seeds(2**32 - 2)
    assert len(set(seeds)) == 3 * REPLICATES and all(0 <= s < 2**32 for s in seeds)
