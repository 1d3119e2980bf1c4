"""
Tests for :mod:`skinrender.studies.benchmarks.bench_spectral`: its cameras, its error, its speedup at equal
error (never credited for a less noisy render), and the basis error, exact, of curves off the band grid. The
bench's figures themselves are measured by ``skinrender bench render --spectral`` (docs/speed.md), not here.
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.studies.benchmarks.bench_spectral import (_row, basis_errors, bench_cameras, channel_errors,
                                                           estimate_bench_seconds)


def test_the_cameras_spread_over_sixty_nm():
    assert bench_cameras(1) == ["gbell:9@450,540,610"]
    assert len(set(bench_cameras(61))) == 61 and bench_cameras(61)[0] == "gbell:9@420,510,580"
    with pytest.raises(SkinrenderError, match="at most 61"):
        bench_cameras(62)


def test_the_error_is_relative_over_the_scored_skin():
    reference = np.full((4, 4, 3), 100.0)
    labels = np.ones((4, 4), dtype=int)
    labels[0] = 0  # background: left out
    image = reference.copy()
    image[1:, :, 0] += 10.0  # every skin pixel 10 % off in R
    image[0, :, 1] += 1000.0  # the background, not counted
    assert np.allclose(channel_errors(image, reference, labels), [0.1, 0.0, 0.0])


def test_the_speedup_is_at_equal_error_and_never_credited():
    """Twice as noisy costs 4× the spp (1/spp law): the speedup quartered; less noisy is not rewarded."""
    assert _row(20, 2.0, 40.0, 0.2, 0.1)["speedup"] == pytest.approx(5.0)
    less = _row(20, 2.0, 40.0, 0.05, 0.1)
    assert less["speedup"] == less["speedup_timed"] == pytest.approx(20.0)


def test_the_basis_error_is_zero_on_the_grid_and_small_off_it():
    rows = {(r["camera"], r["bands_nm"]): r["max_rel_error"]
            for r in basis_errors(["gbell:9@450,540,610", "Nikon 5100 (NPL)"], (5.0, 10.0))}
    assert rows[("Nikon 5100 (NPL)", "400:700:5")] < 1e-12  # given every 5 nm
    assert 1e-4 < rows[("gbell:9@450,540,610", "400:700:5")] < 0.005 < rows[("gbell:9@450,540,610", "400:700:10")]


def test_the_estimate_grows_with_the_cameras():
    assert estimate_bench_seconds([1, 5]) < estimate_bench_seconds([1, 5, 20])
