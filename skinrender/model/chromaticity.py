"""
Chromaticity
============

-   :func:`ncc`: the normalised colour coordinates of Eq. 2,
    ``(r, g, b) = (R, G, B) / (R + G + B)``.
-   :func:`measure`: the Stage 1 measure of Eq. 3 on a pair of NCC
    coordinates.

Units: responses in any unit (NCC is scale-free); chromaticities unitless.

References
----------
-   :cite:`Martinkauppi2006` : Eqs. 2 and 3 (docs/references.md).
"""

from __future__ import annotations

import numpy as np

from ..errors import SkinrenderError
from ..spectra import float_array
from ..hints import ArrayLike, NDArrayFloat

__all__ = ["ncc", "measure"]


def ncc(rgb: ArrayLike) -> NDArrayFloat:
    """
    Normalised colour coordinates (Eq. 2): ``r = R / (R + G + B)``, likewise g, b.

    Parameters
    ----------
    rgb
        Responses, channels on the last axis, shape ``(..., 3)``.

    Returns
    -------
    :class:`numpy.ndarray`
        Same shape; each row sums to 1. A zero response (black) gives the
        achromatic point (1/3, 1/3, 1/3) instead of 0/0.

    Examples
    --------
    >>> ncc([2.0, 1.0, 1.0]).tolist()
    [0.5, 0.25, 0.25]
    """

    rgb = float_array(rgb, "rgb")
    if rgb.shape[-1:] != (3,):
        raise SkinrenderError(f"rgb: ncc expects three channels on the last axis, got shape {rgb.shape}", role="rgb")
    if not np.all(np.isfinite(rgb)) or np.any(rgb < 0):
        raise SkinrenderError("ncc expects finite, non-negative responses (Eq. 2 is defined for light, not for "
                              "NaN, inf or negative values)")
    peak = rgb.max(axis=-1, keepdims=True)  # scaled first, so that sums near float64's limit cannot overflow
    scaled = rgb / np.where(peak > 0, peak, 1.0)
    total = scaled.sum(axis=-1, keepdims=True)
    black = total == 0
    out = scaled / np.where(black, 1.0, total)
    return np.where(black, 1.0 / 3.0, out) if black.any() else out


_CHANNEL_INDEX = {"r": 0, "g": 1, "b": 2}


def measure(chromaticity: ArrayLike, pair: str = "gb") -> NDArrayFloat:
    """
    The Euclidean measure of Eq. 3, ``m = sqrt(c1² + c2²)``.

    Parameters
    ----------
    chromaticity
        NCC chromaticities, shape ``(..., 3)``.
    pair
        The two coordinates: ``gb`` (Stage 1, grows with temperature), ``rg``
        or ``rb``.

    Returns
    -------
    :class:`numpy.ndarray`
        Shape ``(...)``.
    """

    pair = str(pair).lower()
    if len(pair) != 2 or any(c not in _CHANNEL_INDEX for c in pair) or pair[0] == pair[1]:
        raise SkinrenderError(f"pair must be two of r, g, b (e.g. 'gb'), got {pair!r}", role="pair")
    c = float_array(chromaticity, "chromaticity")
    if c.shape[-1:] != (3,):
        raise SkinrenderError(f"measure expects NCC chromaticities with three channels on the last axis, got shape "
                              f"{c.shape}", role="chromaticity")
    return np.hypot(c[..., _CHANNEL_INDEX[pair[0]]], c[..., _CHANNEL_INDEX[pair[1]]])
