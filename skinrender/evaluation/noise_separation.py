"""
Monte Carlo noise separated from physics
========================================

A rendered pixel's chromaticity is its physics' (what an infinitely sampled
render would give) plus the renderer's Monte Carlo noise. Skin detection
classifies single pixels, so the noise moves detection rates by itself: at 64
px and 16 spp the face's chromaticity noise across the skin locus (~0.004 in
NCC) exceeds the margin of most skins to the locus's boundary (0.002–0.007).
The rates of an infinitely sampled render are recovered here by removing the
noise's share of each pixel's deviation, material by material:

-   the pixels of a material (a label) deviate from their mean chromaticity
    by ``d_i``; the mean is freed of the chromaticities' ratio bias (the
    jackknife's correction, :func:`replicate_noise`: a dim channel's noise
    biases a chromaticity, and a biased mean would carry a skin near the
    boundary across it), giving ``c̄``; across the pixels ``d`` has covariance ``T = P + C̄``,
    ``P`` the physics' own spread (shading-dependent colour, a sensor's noise:
    everything but the renderer's noise) and ``C̄`` the mean of the pixels'
    Monte Carlo covariances ``C_i`` (measured from independent replicates);
-   ``P`` is estimated as ``T − C̄`` in the directions of ``C̄``'s whitened
    ``T``, each kept only where it is shown positive (its excess over 1 in
    whitened units beyond :data:`SPREAD_Z` standard errors, from the fourth
    moment: render noise is heavy tailed); elsewhere it is 0;
-   each pixel becomes ``c̄ + P^½ (P + C_i)^−½ d_i``: its deviation scaled from
    the spread it has (physics and noise) to the physics' alone. The pixels
    keep their order and their shape of spread; their covariance is ``P``.

Where the physics adds no spread (the analytic model's world: a face at one
light, one bounce) every pixel of a material goes to the material's mean
chromaticity, and the rates are those of that chromaticity: Eq. 4's when the
mean is Eq. 4's. This is the noise-induced loss extrapolated to infinitely
many samples on the chromaticities themselves, not on the rates: with the
noise wider than the margins the rates are far from their ``1/spp`` regime,
where extrapolating them from two sample counts leaves most of the loss.

-   :func:`separate_noise`: the separated chromaticities and each material's
    :class:`Spread`.
-   :func:`replicate_noise`: the bias and ``C_i`` of a mean's chromaticity, by
    the jackknife over its replicates.
-   :data:`SPREAD_Z`: the test of a spread.

Units: NCC (r, g), unitless.

References
----------
-   :cite:`Efron1982` : see :mod:`skinrender.rendering.face.limits` (the jackknife).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import SkinrenderError
from ..hints import ArrayLike, NDArrayFloat

__all__ = ["SPREAD_Z", "GROUP_PIXELS_MIN", "Spread", "separate_noise", "replicate_noise", "rg_of"]

SPREAD_Z = 5.0
"""Standard errors by which a material's spread must exceed its Monte Carlo noise, in a whitened direction, to be
counted as physics (one-sided). At 3 (0.13 % of directions for a normal statistic) noise alone passed in 2 of 240
camera × scene renders at ``direct`` (``skinrender bench rank``: 12 replicates of 2 spp, whose heavy tails the
fourth-moment standard error does not fully hold); the spreads that change detection (a sensor's noise, a coat's
colour, mixed light) stand 20 or more standard errors out."""

GROUP_PIXELS_MIN = 8
"""Fewest pixels of a material whose spread is measured; a smaller one keeps its pixels as rendered."""


@dataclass(frozen=True)
class Spread:
    """
    One material's spread: ``pixels``, its mean chromaticity ``mean`` (r, g), the Monte Carlo covariance
    ``noise`` (mean of the pixels', 2 × 2), the physics' ``physics`` (2 × 2, the kept part), and per whitened
    direction ``excess`` (spread over noise − 1), ``excess_se`` and ``kept``. ``separated`` is ``False`` where
    the material kept its pixels as rendered, with the ``reason``.
    """

    pixels: int
    mean: tuple
    noise: tuple
    physics: tuple
    excess: tuple = ()
    excess_se: tuple = ()
    kept: tuple = ()
    separated: bool = True
    reason: str = ""


def rg_of(values: ArrayLike) -> NDArrayFloat:
    """NCC (r, g) of ``(..., 3)`` values; ``1/3`` where a pixel has no light (the chromaticity of grey)."""
    values = np.asarray(values, dtype=np.float64)
    total = values.sum(axis=-1, keepdims=True)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(total > 0, values / np.where(total > 0, total, 1.0), 1.0 / 3.0)[..., :2]


def replicate_noise(replicates: ArrayLike) -> tuple[NDArrayFloat, NDArrayFloat]:
    """
    The bias and the covariance of the NCC (r, g) of the mean of ``K`` replicates ``(K, n, 3)`` (any linear
    units), per pixel, ``(n, 2)`` and ``(n, 2, 2)``: the jackknife over the replicates (their leave-one-out means'
    chromaticities). A chromaticity is a ratio, biased by its noise (``O(1/K)`` of each pixel's relative
    variance, large for a dim channel): subtracting the bias leaves the mean's chromaticity unbiased to
    ``O(1/K²)`` :cite:`Efron1982`.

    >>> x = np.array([[[1.0, 1.0, 1.0]], [[1.2, 1.0, 1.0]], [[1.0, 1.0, 1.2]]])
    >>> [a.shape for a in replicate_noise(x)]
    [(1, 2), (1, 2, 2)]
    """
    x = np.asarray(replicates, dtype=np.float64)
    k = x.shape[0]
    if k < 2:
        raise SkinrenderError(f"replicates: the jackknife needs two or more, got {k}")
    total = x.sum(axis=0)
    leave_out = rg_of((total[None] - x) / (k - 1))
    centre = leave_out.mean(axis=0)
    deviation = leave_out - centre
    bias = (k - 1) * (centre - rg_of(total / k))
    return bias, (k - 1) / k * np.einsum("kni,knj->nij", deviation, deviation)


def _root(matrix: NDArrayFloat, power: float) -> NDArrayFloat:
    """``matrix ** power`` of symmetric ``(..., 2, 2)`` matrices (eigenvalues clipped at 0; ``power`` < 0 of a
    zero eigenvalue is 0)."""
    w, v = np.linalg.eigh(matrix)
    w = np.maximum(w, 0.0)
    with np.errstate(divide="ignore"):
        scaled = np.where(w > 0, w ** power, 0.0)
    return np.einsum("...ij,...j,...kj->...ik", v, scaled, v)


def _spread(d: NDArrayFloat, noise: NDArrayFloat, z: float) -> tuple[NDArrayFloat, dict]:
    """The physics' covariance of deviations ``d`` (n, 2) beyond the mean noise covariance ``noise``."""
    n = len(d)
    whiten, colour = _root(noise, -0.5), _root(noise, 0.5)
    white = d @ whiten
    total = white.T @ white / (n - 1)
    excess, directions = np.linalg.eigh(total)
    projected = white @ directions
    se = np.sqrt(np.maximum(np.mean(projected**4, axis=0) - excess**2, 0.0) / n)
    excess = excess - 1.0
    kept = excess > z * se
    physics = colour @ (directions * np.where(kept, excess, 0.0)) @ directions.T @ colour
    return physics, {"excess": tuple(excess.tolist()), "excess_se": tuple(se.tolist()),
                     "kept": tuple(bool(k) for k in kept)}


def separate_noise(chromaticity: ArrayLike, noise: ArrayLike, groups: ArrayLike, z: float = SPREAD_Z,
                   bias: ArrayLike | None = None) -> tuple[NDArrayFloat, dict]:
    """
    The chromaticities with their Monte Carlo noise removed, material by material (see the module).

    Parameters
    ----------
    chromaticity
        ``(n, 2)`` NCC (r, g) of the pixels as rendered.
    noise
        ``(n, 2, 2)`` each pixel's Monte Carlo covariance (:func:`replicate_noise`).
    groups
        ``(n,)`` each pixel's material (label).
    z
        :data:`SPREAD_Z`.
    bias
        ``(n, 2)`` each pixel's ratio bias (:func:`replicate_noise`), taken off each material's mean (not off
        the deviations, whose noise its own estimate would raise); ``None``: none.

    Returns
    -------
    (ndarray, dict)
        The separated ``(n, 2)`` chromaticities and ``{group: Spread}``.

    Examples
    --------
    A material of one chromaticity seen through noise goes back to it:

    >>> rng = np.random.default_rng(0)
    >>> noisy = np.array([0.5, 0.3]) + 0.01 * rng.standard_normal((400, 2))
    >>> separated, spreads = separate_noise(noisy, np.tile(1e-4 * np.eye(2), (400, 1, 1)), np.ones(400))
    >>> bool(np.allclose(separated, noisy.mean(axis=0))), spreads[1].kept
    (True, (False, False))
    """
    c = np.asarray(chromaticity, dtype=np.float64)
    cov = np.asarray(noise, dtype=np.float64)
    labels = np.asarray(groups)
    if c.ndim != 2 or c.shape[1] != 2 or cov.shape != (len(c), 2, 2) or labels.shape != (len(c),):
        raise SkinrenderError(f"separate_noise: expected (n, 2) chromaticities, (n, 2, 2) covariances and (n,) "
                              f"groups, got {c.shape}, {cov.shape}, {labels.shape}")
    out, spreads = c.copy(), {}
    for group in np.unique(labels):
        members = labels == group
        n = int(members.sum())
        mean = c[members].mean(axis=0)
        centre = mean if bias is None else mean - np.asarray(bias, dtype=np.float64)[members].mean(axis=0)
        average = cov[members].mean(axis=0)
        keyed = group.item() if hasattr(group, "item") else group
        if n < GROUP_PIXELS_MIN or not np.all(np.isfinite(average)) or np.linalg.eigvalsh(average)[0] <= 0:
            why = (f"{n} pixels, fewer than {GROUP_PIXELS_MIN}" if n < GROUP_PIXELS_MIN
                   else "no Monte Carlo noise measured (identical replicates)")
            spreads[keyed] = Spread(n, tuple(centre.tolist()), tuple(average.ravel().tolist()), (), separated=False,
                                    reason=f"kept as rendered: {why}")
            continue
        d = c[members] - mean
        physics, tested = _spread(d, average, z)
        if not physics.any():  # no spread kept: every pixel to the material's mean (its scale is 0)
            out[members] = centre
        else:
            scale = _root(physics, 0.5)[None] @ _root(physics[None] + cov[members], -0.5)
            out[members] = centre + np.einsum("nij,nj->ni", scale, d)
        spreads[keyed] = Spread(n, tuple(centre.tolist()), tuple(average.ravel().tolist()),
                                tuple(physics.ravel().tolist()), **tested)
    return out, spreads
