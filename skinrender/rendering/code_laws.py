"""
Exact and approximate laws of a patch's codes
=============================================

What the validation of a render through an image sensor
(:mod:`skinrender.rendering.sensor_validation`) tests its patches with: a
patch's n pixel codes are independent draws of a discrete code law (the
sensor's, :func:`skinrender.model.noise.code_probabilities`, mixed over the
render's spread), so its mean and sample variance have exact laws on the code
lattice (:func:`exact_p_values`); where the lattice is too large, the
variance is tested as a scaled χ² (:func:`p_variance`) with the spread of a
sample variance (:func:`spread_of_variance`), and the mean as a normal z
(:func:`normal_sf`).

-   :data:`EXACT_CELLS`, :data:`NEGLIGIBLE`.
-   :func:`exact_p_values`, :func:`two_sided`, :func:`mixture`, :func:`difference_law`.
-   :func:`spread_of_variance`, :func:`p_variance`, :func:`normal_sf`.

Units: codes in DN, variances in DN².

References
----------
-   :cite:`Satterthwaite1946` : F. E. Satterthwaite (1946). An approximate distribution of estimates of
    variance components. Biometrics Bulletin 2(6), 110–114.
"""

from __future__ import annotations

import numpy as np

from ..hints import NDArrayFloat

__all__ = ["EXACT_CELLS", "NEGLIGIBLE", "two_sided", "exact_p_values", "spread_of_variance", "mixture",
           "difference_law", "p_variance", "normal_sf"]

EXACT_CELLS = 1 << 20
"""The largest (sum, sum of squares) lattice, cells, on which a patch's statistics are summed exactly."""

NEGLIGIBLE = 1e-15
"""Codes less likely than this per pixel are left out of the exact law (their total over a patch is < 1e-11)."""


def two_sided(law: NDArrayFloat, below: NDArrayFloat, above: NDArrayFloat) -> float:
    """2 · min(P(T ≤ t), P(T ≥ t)) of a discrete law (both tails keep the observed value), at most 1."""
    return float(min(1.0, 2.0 * min(law[below].sum(), law[above].sum())))


def exact_p_values(pmf: NDArrayFloat, first: float, codes: NDArrayFloat) -> tuple[float, float] | None:
    """
    Exact two-sided p-values of a patch's pixel mean and sample variance, n pixels of the code law ``pmf``.

    The n codes are independent draws of P(DN = first + j) = ``pmf[j]``: the joint law of (Σ d, Σ d²) is the
    n-fold convolution of one pixel's, summed on its integer lattice (by FFT; codes counted from the most likely
    one, d = 0). The patch mean is Σ d / n and the sample variance (Σ d² − (Σ d)² / n) / (n − 1): both lattice
    laws, never normal where the noise spans a few codes (every pixel one code has probability Σ_j pmf_j^n).
    ``None`` where the lattice exceeds :data:`EXACT_CELLS`.
    """
    n = codes.size
    keep = np.flatnonzero(pmf > NEGLIGIBLE)
    probs = pmf[keep[0]:keep[-1] + 1] / pmf[keep[0]:keep[-1] + 1].sum()
    offsets = np.arange(probs.size) - int(np.argmax(probs))  # d, from the most likely code
    width, depth = n * (probs.size - 1) + 1, n * int((offsets**2).max()) + 1
    if n < 2 or width * depth > EXACT_CELLS:
        return None
    observed = codes - (first + keep[0]) + offsets[0]  # each pixel's d
    if observed.min() < offsets[0] or observed.max() > offsets[-1]:
        return 0.0, 0.0  # a code the model gives < 1e-15 per pixel
    from scipy import fft

    shape = (fft.next_fast_len(width, real=True), fft.next_fast_len(depth, real=True))  # ≥ the sums: no wrap
    one = np.zeros(shape)
    one[offsets - offsets[0], offsets**2] = probs
    spectrum = fft.rfft2(one)
    power = np.abs(spectrum) ** n * np.exp(1j * n * np.angle(spectrum))  # the n-fold convolution
    joint = np.maximum(fft.irfft2(power, s=shape)[:width, :depth], 0.0)
    marginal = joint.sum(axis=1)
    row = int(observed.sum() - n * offsets[0])
    index = np.arange(width)
    p_mean = two_sided(marginal, index <= row, index >= row)
    cells = np.nonzero(joint > 1e-300)  # (Σ d − n d_min, Σ d²) reachable
    total = cells[0] + float(n * offsets[0])
    variance = (cells[1] - total**2 / n) / (n - 1)
    seen = (np.sum(observed**2) - observed.sum() ** 2 / n) / (n - 1)
    slack = 1e-9 * max(1.0, abs(seen))
    return p_mean, two_sided(joint[cells], variance <= seen + slack, variance >= seen - slack)


def spread_of_variance(pmf: NDArrayFloat | None, first: float, mean: float, variance: float, n: int) -> float:
    """
    Var(s²) of the sample variance of n draws: μ₄ / n − σ⁴ (n − 3) / (n (n − 1)), μ₄ from the code law ``pmf``
    (first code ``first``), or 3 σ⁴ (a normal law) where none is known.
    """
    fourth = 3.0 * variance**2
    if pmf is not None and np.all(np.isfinite(pmf)):
        fourth = float(np.sum(pmf * (first + np.arange(pmf.size) - mean) ** 4))
    spread = fourth / n - variance**2 * (n - 3) / (n * (n - 1))
    return spread if spread > 0 else 2.0 * variance**2 / (n - 1)


def mixture(firsts: NDArrayFloat, pmfs: NDArrayFloat) -> tuple[float, NDArrayFloat] | None:
    """The average of code laws (rows of ``pmfs`` from codes ``firsts``) on one window: (first, pmf); ``None`` if
    any row has no law (NaN)."""
    if np.any(np.isnan(firsts)) or np.any(np.isnan(pmfs)):
        return None
    start = firsts.astype(np.int64) - int(firsts.min())
    out = np.zeros(int(start.max()) + pmfs.shape[1])
    for offset in np.unique(start):
        out[offset:offset + pmfs.shape[1]] += pmfs[start == offset].sum(axis=0)
    return float(firsts.min()), out / len(pmfs)


def difference_law(pmfs: NDArrayFloat) -> tuple[float, NDArrayFloat]:
    """The law of A − B, two frames of one pixel, averaged over the rows' code laws: (first, pmf)."""
    width = pmfs.shape[1]
    law = np.mean([np.convolve(p, p[::-1]) for p in pmfs], axis=0)
    return float(-(width - 1)), law


def p_variance(statistic: float, dof: float) -> float:
    """Two-sided p-value of a scaled χ² statistic with ``dof`` degrees of freedom."""
    from scipy.stats import chi2

    return float(min(1.0, 2 * min(chi2.cdf(statistic, dof), chi2.sf(statistic, dof))))


def normal_sf(x: float) -> float:
    """The standard normal's upper tail P(Z > x)."""
    from scipy.stats import norm

    return float(norm.sf(x))
