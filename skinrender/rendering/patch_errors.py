"""
The errors of a balanced chart's patch means
=============================================

A patch's balanced mean (Eq. 4 on a render) carries its own pixels' Monte
Carlo error and the white references' through the white balance and WP
(Eq. 8). :func:`error_law` gives each patch channel's standard error and the
skewness of its error, from which the validation's tests
(:mod:`skinrender.rendering.validation`) take their normal law — trusted up
to :data:`SKEW_MAX`, beyond which they use distribution-free bounds.

-   :data:`SKEW_MAX`, :func:`error_law`, :func:`noise_of`.

Units: output units (255 for white at p = c); skewness unitless.
"""

from __future__ import annotations

import numpy as np

from ..hints import NDArrayFloat
from ..model.response import uses_whites
from .balance import Rendering
from .renderer import RawRender
from .scene import ChartScene

__all__ = ["SKEW_MAX", "error_law", "noise_of"]

SKEW_MAX = 0.5
"""Largest skewness of a patch channel's error (its mean's third cumulant over σ³) at which the tests' normal law
is trusted (beyond it: distribution-free bounds). Measured on the Macbeth chart: at most 0.05–0.15 at 4–64 spp
under 3300–4800 K, 0.3 through the Nikon at 2300 K and 16 spp; 0.6 for a near-exact white at 1024 spp (relative
error 7e-6); up to 1.0 for a gbell:3 channel at 400 nm under 1000 K at 64 spp, whose calibration white's pixels
have a kurtosis of ~90. There the sample's own skewness is unreliable too: the difference test still failed 10 of
40 seeds at α = 0.01 (docs/verdicts.md, its limits)."""


def _relative_pixels(raw: RawRender, scene: ChartScene) -> NDArrayFloat:
    """The white reference's pixels in ``raw`` over their mean, ``(n, 3)`` (0 in a channel it does not reach)."""
    rows, columns = scene.patch_pixels(scene.white_index)
    pixels = raw.radiance[rows, columns].reshape(-1, 3)
    mean = pixels.mean(axis=0)
    return np.divide(pixels, mean, out=np.zeros_like(pixels), where=mean > 0)


def _mean_cumulants(pixels: NDArrayFloat) -> tuple[NDArrayFloat, NDArrayFloat]:
    """Second and third cumulants of the mean of ``pixels`` (rows: n independent draws), per column."""
    n = len(pixels)
    centred = pixels - pixels.mean(axis=0)
    return np.sum(centred**2, axis=0) / (n - 1) / n, np.mean(centred**3, axis=0) / n**2


def error_law(rendering: Rendering, reference: NDArrayFloat) -> tuple[NDArrayFloat, NDArrayFloat]:
    """
    The standard error, output units, and the skewness of every patch channel's balanced mean.

    Linearised, a balanced mean's relative error is ``δr_ik − δc_k − Σ_j w_j (δp_j − δc_j)``: its raw patch's
    (``δr``), the calibration white's (``δc``, which divides each channel) and, through WP (Eq. 8, ``white``
    normalisation with two renders), both whites' with weights ``w_j = ρ_j / Σ ρ`` (``ρ_j`` the white ratios).
    The whites' terms are formed pixel by pixel (their channels share wavelength samples, so their errors
    correlate); the white reference's own balanced mean has ``δr = δp`` (its pixels are the prevailing white),
    and with one render (p = c) ``δp = δc``, so its balanced mean is exact there; a calibration white computed
    rather than rendered (a spectral render's at p ≠ c: ``info["white_calibration"] == "analytic"``) has
    ``δc = 0``. Second and third cumulants of
    the independent parts add: the skewness is their third over σ³ (0 where σ = 0).
    """
    scene = rendering.scene
    analytic = rendering.info.get("white_calibration") == "analytic"  # a spectral render's: exact, no noise
    one = len(rendering.raw) == 1 and not analytic
    white_p = _relative_pixels(rendering.raw[0], scene)
    white_c = white_p if one else 0.0 * white_p if analytic else _relative_pixels(rendering.raw[-1], scene)
    weights = np.zeros(3)
    if uses_whites(rendering.normalization) and not one:
        ratio = rendering.info["white_ratio"]
        weights = ratio / ratio.sum()
    second, third = np.zeros(reference.shape), np.zeros(reference.shape)
    for i in range(len(scene.patches)):
        rows, columns = scene.patch_pixels(i)
        own = _mean_cumulants(np.asarray(rendering.image[rows, columns], dtype=np.float64).reshape(-1, 3))
        for k in range(3):
            on_c, on_p = weights - np.eye(3)[k], -weights  # coefficients of δc_j and δp_j
            if i == scene.white_index:
                on_p = on_p + np.eye(3)[k]
                parts = []
            else:
                parts = [(own[0][k], own[1][k])]
            if one:
                parts.append(tuple(c[0] * reference[i, k] ** (2 + j) for j, c in
                                   enumerate(_mean_cumulants((white_c @ (on_p + on_c))[:, None]))))
            else:
                for pixels, coefficients in ((white_p, on_p), (white_c, on_c)):
                    parts.append(tuple(c[0] * reference[i, k] ** (2 + j) for j, c in
                                       enumerate(_mean_cumulants((pixels @ coefficients)[:, None]))))
            second[i, k] = max(sum(part[0] for part in parts), 0.0)
            third[i, k] = sum(part[1] for part in parts)
    sigma = np.sqrt(second)
    skewness = np.divide(third, sigma**3, out=np.zeros_like(third), where=sigma > 0)
    return sigma, skewness


def noise_of(rendering: Rendering, reference: NDArrayFloat) -> NDArrayFloat:
    """The standard error of every patch channel's balanced mean, output units (:func:`error_law`)."""
    return error_law(rendering, reference)[0]
