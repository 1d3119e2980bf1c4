"""
Fitting the skin model to a measured colour
===========================================

Published skin measurements across ethnic groups often give a colour, not a
spectrum: CIELAB L*, a*, b* under D65 for the CIE 1964 10° observer
(:cite:`Alaluf2002`, :cite:`Xiao2017`). This module finds the skin model's
spectrum (:mod:`.skin_model`, adding-doubling) whose colour is the measured
one: bounded least squares on the three CIELAB differences over the model's
melanin, blood and scattering (:data:`COLOUR_FIT_PARAMETERS`, within
:data:`~skinrender.datasets.skin_fit.FIT_BOUNDS`), the other parameters at
their defaults. Three colour coordinates fix three parameters; the spectrum
is then one metamer of the colour (the model's), not a measurement.

-   :func:`cielab_of`: L*, a*, b* of reflectances (D65, 10°, 380–780 nm every
    5 nm, the white of the same sums).
-   :func:`fit_skin_colour`, :class:`ColourFit`: one colour's fit, with its
    ΔE*ab (CIE 1976) and ΔE00 (CIEDE2000).

Units: wavelengths nm; reflectance fractions; CIELAB unitless.

References
----------
-   :cite:`Alaluf2002` : Alaluf, S., Atkins, D., Barrett, K., Blount, M., Carter, N., & Heath, A. (2002).
    Ethnic variation in melanin content and composition in photoexposed and photoprotected human skin.
    Pigment Cell Research, 15(2), 112–118.
-   :cite:`Xiao2017` : Xiao, K., Yates, J. M., Zardawi, F., Sueeprasan, S., Liao, N., Gill, L., Li, C., &
    Wuerger, S. (2017). Characterising the variations in ethnic skin colours: a new calibrated data base for
    human skin. Skin Research and Technology, 23(1), 21–29.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np

from ..errors import SkinrenderError
from ..hints import ArrayLike, NDArrayFloat
from .skin_fit import FIT_BOUNDS
from .skin_model import SkinParameters, skin_reflectance

__all__ = ["COLOUR_FIT_PARAMETERS", "WAVELENGTHS_CIELAB", "MELANIN_STARTS", "ColourFit", "cielab_of", "delta_e",
           "fit_skin_colour"]

COLOUR_FIT_PARAMETERS = ("melanin", "blood", "scattering")
"""The skin model's parameters a colour fit moves (three, for the three CIELAB coordinates)."""

WAVELENGTHS_CIELAB = np.arange(380.0, 780.5, 5.0)
"""The wavelengths of the CIELAB sums, nm (the CIE's 380–780 nm, every 5 nm)."""

MELANIN_STARTS = (0.01, 0.05, 0.15, 0.3)
"""Melanin fractions a fit starts from unless told (the best of the four is kept)."""


@lru_cache(maxsize=1)
def _observer() -> tuple[NDArrayFloat, NDArrayFloat, NDArrayFloat]:
    """D65 × the CIE 1964 10° CMFs on :data:`WAVELENGTHS_CIELAB`, ``(n, 3)``; the white's XYZ (Y = 1); its xy."""
    import colour

    shape = colour.SpectralShape(float(WAVELENGTHS_CIELAB[0]), float(WAVELENGTHS_CIELAB[-1]), 5.0)
    cmfs = colour.MSDS_CMFS["CIE 1964 10 Degree Standard Observer"].copy().align(shape).values
    weights = colour.SDS_ILLUMINANTS["D65"].copy().align(shape).values[:, None] * cmfs
    white = weights.sum(axis=0)
    weights = weights / white[1]
    return weights, white / white[1], np.asarray(colour.XYZ_to_xy(white / white[1]))


def cielab_of(reflectance: ArrayLike) -> NDArrayFloat:
    """
    CIELAB of reflectances on :data:`WAVELENGTHS_CIELAB` (fractions, ``(..., 81)``) under D65 for the 10°
    observer, the white the perfect diffuser of the same sums; shape ``(..., 3)``.

    Examples
    --------
    >>> cielab_of(np.ones(81)).round(6).tolist()
    [100.0, 0.0, 0.0]
    """
    import colour

    r = np.asarray(reflectance, dtype=np.float64)
    if r.shape[-1] != WAVELENGTHS_CIELAB.size:
        raise SkinrenderError(f"cielab_of: reflectances on {WAVELENGTHS_CIELAB.size} wavelengths (380–780 nm every "
                              f"5 nm), got {r.shape[-1]}")
    weights, _, xy = _observer()
    return np.asarray(colour.XYZ_to_Lab(r @ weights, xy))


def delta_e(lab: ArrayLike, reference: ArrayLike) -> tuple[float, float]:
    """
    ΔE*ab (CIE 1976) and ΔE00 (CIEDE2000) between two CIELAB colours.

    >>> [round(v, 3) for v in delta_e([50.0, 10.0, 15.0], [50.0, 10.0, 16.0])]
    [1.0, 0.672]
    """
    import colour

    lab, reference = np.asarray(lab, dtype=np.float64), np.asarray(reference, dtype=np.float64)
    return (float(np.linalg.norm(lab - reference)),
            float(colour.delta_E(lab, reference, method="CIE 2000")))


@dataclass(frozen=True)
class ColourFit:
    """
    One colour's fit: the ``target`` and ``fitted`` CIELAB, the fitted :class:`SkinParameters`, ``delta_e_ab``
    (CIE 1976) and ``delta_e_00`` (CIEDE2000) between them, and the bounds the fit sits on (parameter →
    ``"low"``/``"high"``).
    """

    target: tuple
    fitted: tuple
    parameters: SkinParameters
    delta_e_ab: float
    delta_e_00: float
    bounds_hit: dict


def fit_skin_colour(lab: ArrayLike, base: SkinParameters = SkinParameters(),
                    starts: tuple = MELANIN_STARTS) -> ColourFit:
    """
    The skin model's spectrum of a measured colour: melanin, blood and scattering fitted so that its CIELAB
    (D65, 10°) is ``lab``, the other parameters ``base``'s.

    Parameters
    ----------
    lab
        The measured L*, a*, b*.
    base
        The parameters not fitted (oxygenation, scattering power, thickness, n).
    starts
        Melanin fractions to start from (the best fit is kept); ~2 s each on one core.

    Returns
    -------
    :class:`ColourFit`

    """
    from scipy.optimize import least_squares

    target = np.asarray(lab, dtype=np.float64).reshape(-1)
    if target.size != 3 or not np.all(np.isfinite(target)) or not 0 < target[0] < 100:
        raise SkinrenderError(f"lab: expected a measured L*, a*, b* with 0 < L* < 100, got {lab!r}")
    low = np.array([FIT_BOUNDS[name][0] for name in COLOUR_FIT_PARAMETERS])
    high = np.array([FIT_BOUNDS[name][1] for name in COLOUR_FIT_PARAMETERS])

    def parameters(x) -> SkinParameters:
        return replace(base, **dict(zip(COLOUR_FIT_PARAMETERS, (float(v) for v in x))))

    def residual(x) -> NDArrayFloat:
        return cielab_of(skin_reflectance(WAVELENGTHS_CIELAB, parameters(x))) - target

    best = None
    if not starts:
        raise SkinrenderError("starts: give at least one melanin fraction to start from")
    for melanin in starts:
        start = np.clip([melanin, base.blood, base.scattering], low, high)
        result = least_squares(residual, start, bounds=(low, high), x_scale=[0.05, 0.02, 30.0])
        if best is None or result.cost < best.cost:
            best = result
    fitted = parameters(best.x)
    colour_fitted = cielab_of(skin_reflectance(WAVELENGTHS_CIELAB, fitted))
    ab, e00 = delta_e(colour_fitted, target)
    span = high - low
    hit = {name: side for name, v, lo, hi, s in zip(COLOUR_FIT_PARAMETERS, best.x, low, high, span)
           for side in (("low",) if v <= lo + 1e-6 * s else ("high",) if v >= hi - 1e-6 * s else ())}
    return ColourFit(tuple(target.tolist()), tuple(colour_fitted.tolist()), fitted, ab, e00, hit)
