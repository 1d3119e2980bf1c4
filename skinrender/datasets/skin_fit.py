"""
Fitting the skin model to measured spectra
==========================================

Bounded least squares of the skin model (:mod:`.skin_model`) to measured
reflectance spectra, one spectrum at a time or a whole table over worker
processes, each fit reported with its parameters, its RMS error, the bounds it
sits on and whether the optimiser converged.

The bounds (:data:`FIT_BOUNDS`), each with its source:

-   ``melanin`` [0, 0.5]: melanosome volume fractions of the epidermis reported
    for light (1.3–6.3 %), moderately (11–16 %) and darkly (18–43 %) pigmented
    skin :cite:`Jacques1998`; 0.5 is above the darkest.
-   ``blood`` [0, 0.2]: dermal blood volume fractions of 4 % (papillary and
    reticular dermis) to 30 % (the upper vascular plexus) :cite:`Meglinski2002`;
    a semi-infinite dermis averages them.
-   ``oxygenation`` [0, 1]: a saturation.
-   ``scattering`` (μs' at 500 nm) [10, 200] cm⁻¹: a fifth to four times the
    skin average of 46 cm⁻¹ :cite:`Jacques2013`, a range that holds the ex vivo
    epidermis (71 cm⁻¹) and dermis (47 cm⁻¹) of :cite:`Salomatina2006`.
-   ``scattering_power`` [0, 4]: from scatterers much larger than the
    wavelength (0) to Rayleigh scatterers (4) :cite:`Jacques2013`.
-   ``surface`` (Kubelka–Munk only) [0, 0.1]: the Fresnel reflectance of skin
    (n 1.4) is 0.028 at normal incidence; 0.1 allows an oily or rough surface.

Speed: a spectrum of ~100 wavelengths takes ~1.2 s by adding-doubling on one core
(:data:`SECONDS_PER_FIT`): the iterations run with 8 quadrature points, the
Jacobian's evaluations batched with the point into one vectorised call, then
corrected twice for the difference the model's own 16 points make (defect
correction: the same RMS to 5 decimals as a fit run at 16 points, in half its
time, measured on 12 NIST skins); the reported RMS is the model's
(:func:`~skinrender.datasets.skin_model.skin_reflectance`) on every wavelength.

-   :class:`SkinFit`: one column's result.
-   :func:`fit_skin_spectrum`: one spectrum; :func:`fit_skin`, its parameters and RMS.
-   :func:`fit_skin_spectra`: every spectrum of a table, on worker processes.
-   :func:`measured_reflectance`: the model as a contact instrument of a sample port reads it (``port_mm``, the
    lateral loss of :mod:`.port_loss`): a fit to such a measurement sees the model through the same port.
-   :func:`fit_seconds`: the time a fit of a table should take.
-   :func:`skin_verdict`, :data:`SKIN_RMS_MAX`, :data:`SKIN_BOUNDS_MAX`: when a fit says the spectrum is not
    skin: an RMS beyond the measured skins', or most of its parameters on a bound (a black patch fits to RMS
    0.029 with every parameter on a bound). Every fit carries its verdict.

References
----------
-   Jacques, S. L. (1998). Skin optics summary. Oregon Medical Laser Center News.
-   Jacques, S. L. (2013). Optical properties of biological tissues: a review.
    Physics in Medicine & Biology, 58(11), R37.
-   Meglinski, I. V., & Matcher, S. J. (2002). Quantitative assessment of skin layers absorption and skin
    reflectance spectra simulation in the visible and near-infrared spectral regions. Physiological
    Measurement, 23(4), 741–753.
-   Salomatina, E., Jiang, B., Novak, J., & Yaroslavsky, A. N. (2006). Optical properties of normal and
    cancerous human skin in the visible and near-infrared spectral range. Journal of Biomedical Optics,
    11(6), 064026.
"""

from __future__ import annotations

import math
import os
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import SkinrenderError, check_flag
from ..hints import ArrayLike, NDArrayFloat
from ..spectral_csv import measured_spectrum
from ..methods import method_of, takes, validate_method
from .adding_doubling import QUAD_PTS_DEFAULT, Slab, stack_reflectance
from .port_loss import check_port, through_port
from .skin_model import (G_SKIN, LAYER_KEYS, SKIN_REFLECTANCE_METHODS, SURFACE_KUBELKA_MUNK, SkinParameters,
                         kubelka_munk_two_layers, layer_coefficients, skin_reflectance)

__all__ = ["FIT_BOUNDS", "FIT_PARAMETERS", "FIT_MODELS", "fit_model_adding_doubling", "fit_model_kubelka_munk",
           "SECONDS_PER_FIT", "SKIN_RMS_MAX", "SKIN_BOUNDS_MAX", "SKIN_NEEDS", "SkinFit", "skin_verdict", "fit_skin",
           "fit_skin_spectrum", "fit_skin_spectra", "fit_seconds", "measured_reflectance"]

FIT_BOUNDS = {
    "melanin": (0.0, 0.5, "epidermal melanosome fractions up to 43 % (Jacques 1998)"),
    "blood": (0.0, 0.2, "dermal blood fractions 4–30 % by layer (Meglinski & Matcher 2002)"),
    "oxygenation": (0.0, 1.0, "a saturation"),
    "scattering": (10.0, 200.0, "a fifth to four times the skin average 46 cm⁻¹ (Jacques 2013)"),
    "scattering_power": (0.0, 4.0, "large scatterers (0) to Rayleigh (4)"),
    "surface": (0.0, 0.1, "Fresnel 0.028 at n 1.4; up to 0.1 for an oily or rough surface"),
    "background": (0.0, 1.0, "water's 0.006 cm⁻¹ at 700 nm to 4 times Jacques 1998's bloodless 0.244 cm⁻¹"),
    "melanin_power": (2.0, 6.0, "flatter and steeper than the melanin spectra reported, λ^−3.33 to λ^−4.75 "
                                "(Jacques 1998; Donner & Jensen 2006's pheomelanin)"),
}
"""Bounds of the fit, parameter → ``(low, high, source)``."""

FIT_PARAMETERS = {
    "adding-doubling": ("melanin", "blood", "oxygenation", "scattering", "scattering_power"),
    "kubelka-munk": ("melanin", "blood", "oxygenation", "scattering", "scattering_power", "surface"),
}
"""The parameters each method fits (the others stay at their :class:`SkinParameters` defaults)."""

SECONDS_PER_FIT = {"adding-doubling": 1.5, "kubelka-munk": 0.05}
"""Seconds per spectrum of 100 wavelengths on one core, measured (``docs/skin-model.md``): the estimates' rate."""

_SCALE = {"melanin": 0.05, "blood": 0.02, "oxygenation": 0.3, "scattering": 30.0, "scattering_power": 0.5,
          "surface": 0.02, "background": 0.05, "melanin_power": 0.5}
_QUAD_ITERATIONS = 8
CORRECTIONS = 2
"""Defect corrections of an adding-doubling fit from 8 to the model's 16 quadrature points."""
_MELANIN_SCAN = (0.005, 0.015, 0.04, 0.1, 0.2, 0.4)

SKIN_RMS_MAX = 0.03
"""A fit worse than this RMS (fraction of reflectance) is not skin: twice the worst of the measured skins'
(``docs/skin-model.md``: the 100 NIST and 30 Vrhel skins fit to at most 0.0151 by either method; 0.017, 1.8 times,
before the melanin power's calibration)."""
SKIN_BOUNDS_MAX = {"adding-doubling": 3, "kubelka-munk": 3}
"""A fit with more of its parameters on a bound than this is not skin (most of its parameters sit where the model's
range ends, not where the spectrum puts them): the most any of the 100 NIST and 30 Vrhel skins has, per method
(3 of 5, one Vrhel skin by adding-doubling since the melanin power's calibration, 2 before; 3 of 6 by
Kubelka–Munk, 4 before). A black patch (``grey:0``) fits with all 5 on a bound."""
SKIN_NEEDS = ("melanin", "blood")
"""A fit with one of these at its low bound (0) is not skin: living skin has melanin and blood (the measured skins'
least are 0.0076 and 0.0039 by adding-doubling, 0.015 and 0.0036 by Kubelka–Munk; a flat white 0.9 fits by
Kubelka–Munk with neither)."""


def skin_verdict(rms: float, bounds_hit: dict, method: str = "adding-doubling",
                 converged: bool = True) -> str | None:
    """
    Why a fit by ``method`` is not skin, or ``None`` where it is: a fit that did not converge, else every one of
    these that holds, joined by "; ": no melanin or no blood (:data:`SKIN_NEEDS`), an RMS above
    :data:`SKIN_RMS_MAX`, more parameters on a bound than :data:`SKIN_BOUNDS_MAX` allows.

    >>> skin_verdict(0.005, {"scattering_power": "low"}) is None
    True
    >>> skin_verdict(0.029, {"melanin": "high", "blood": "low", "scattering": "low"})
    'its fit has no blood (living skin has both)'
    >>> skin_verdict(0.029, {"melanin": "high", "blood": "high", "scattering": "low", "oxygenation": "low"})
    'its fit has 4 of 5 parameters on a bound (melanin high, blood high, scattering low, oxygenation low); measured skins have at most 3'
    """
    if not converged or not math.isfinite(rms):
        return "the skin model's fit to it did not converge"
    reasons = []
    missing = [name for name in SKIN_NEEDS if bounds_hit.get(name) == "low"]
    if missing:
        reasons.append(f"its fit has no {' and no '.join(missing)} (living skin has both)")
    if rms > SKIN_RMS_MAX:
        reasons.append(f"the skin model fits it to RMS {rms:.3g}, beyond the measured skins' (at most "
                       f"{SKIN_RMS_MAX:g} is skin-like)")
    if len(bounds_hit) > SKIN_BOUNDS_MAX[method]:
        sides = ", ".join(f"{k} {v}" for k, v in bounds_hit.items())
        reasons.append(f"its fit has {len(bounds_hit)} of {len(FIT_PARAMETERS[method])} parameters on a bound "
                       f"({sides}); measured skins have at most {SKIN_BOUNDS_MAX[method]}")
    return "; ".join(reasons) or None


@dataclass(frozen=True)
class SkinFit:
    """
    One spectrum's fit: its ``name``, the fitted :class:`SkinParameters`, the RMS reflectance error over its
    wavelengths (fraction), the bounds it sits on (parameter → ``"low"``/``"high"``), whether the optimiser
    converged, its message and its function evaluations; ``not_skin_reason``: why the spectrum is not skin as
    the model knows it (:func:`skin_verdict`), ``None`` where it is.
    """

    name: str
    parameters: SkinParameters
    rms: float
    bounds_hit: dict = field(default_factory=dict)
    converged: bool = True
    message: str = ""
    evaluations: int = 0
    not_skin_reason: str | None = None

    @property
    def not_skin(self) -> bool:
        """Whether the spectrum is refused as skin (:attr:`not_skin_reason` says why)."""
        return self.not_skin_reason is not None

    def as_dict(self, method: str) -> dict:
        """JSON values: the fitted parameters (only those of ``method``'s fit), rms, bounds_hit, converged,
        not_skin and not_skin_reason (``null`` for skin)."""
        values = {name: getattr(self.parameters, name) for name in FIT_PARAMETERS[method]}
        rms = self.rms if math.isfinite(self.rms) else None
        return {"name": self.name, "parameters": values, "rms": rms, "bounds_hit": self.bounds_hit,
                "converged": self.converged, "message": self.message, "evaluations": self.evaluations,
                "not_skin": self.not_skin, "not_skin_reason": self.not_skin_reason}


def fit_model_adding_doubling(coefficients: tuple, base: SkinParameters, quad_pts: int) -> NDArrayFloat:
    """
    The adding-doubling model's reflectances of the layers' ``coefficients`` (``(μa epidermis, μa dermis, μs
    epidermis, μs dermis)``, mm⁻¹, rows of parameters): two slabs under a Fresnel boundary of ``base.n``,
    ``quad_pts`` quadrature points (a fit runs with fewer and corrects the defect: :data:`CORRECTIONS`). Its surface
    is that boundary: it takes no ``surface`` reflectance.
    """
    mu_a_epidermis, mu_a_dermis, mu_s_epidermis, mu_s_dermis = coefficients
    slabs = [Slab(mu_a_epidermis, mu_s_epidermis, G_SKIN, float(base.epidermis_mm)),
             Slab(mu_a_dermis, mu_s_dermis, G_SKIN, None)]
    return stack_reflectance(slabs, n=float(base.n), quad_pts=quad_pts)


def fit_model_kubelka_munk(coefficients: tuple, base: SkinParameters, surface) -> NDArrayFloat:
    """The Kubelka-Munk two-layer model's reflectances of the layers' ``coefficients`` (as
    :func:`fit_model_adding_doubling`) under a flat ``surface`` reflectance (a fraction, rows of parameters;
    ``None``: :data:`~skinrender.datasets.skin_model.SURFACE_KUBELKA_MUNK`)."""
    mu_a_epidermis, mu_a_dermis, mu_s_epidermis, mu_s_dermis = coefficients
    surface = SURFACE_KUBELKA_MUNK if surface is None else surface
    surface = np.asarray(surface, dtype=np.float64)[..., None] if np.ndim(surface) else surface
    return kubelka_munk_two_layers(mu_a_epidermis, mu_a_dermis, mu_s_epidermis, G_SKIN, base.epidermis_mm, surface,
                                   mu_s_dermis)


FIT_MODELS = {"adding-doubling": fit_model_adding_doubling, "kubelka-munk": fit_model_kubelka_munk}
"""The model a fit evaluates for each method of :data:`~skinrender.datasets.skin_model.SKIN_REFLECTANCE_METHODS`,
name → ``(coefficients, base, quad_pts | surface) → reflectances``: a model that takes ``quad_pts`` is corrected
from a coarse quadrature, one that takes ``surface`` fits it (:data:`FIT_PARAMETERS`)."""


def _specular(method: str, base: SkinParameters, surface) -> NDArrayFloat | float:
    """The part of ``method``'s reflectance the surface reflects: adding-doubling's Fresnel reflection at
    normal incidence (index ``base.n``), Kubelka–Munk's flat ``surface`` (rows, or ``None``: its default)."""
    if takes(FIT_MODELS[method], "quad_pts"):
        return ((float(base.n) - 1.0) / (float(base.n) + 1.0)) ** 2
    surface = SURFACE_KUBELKA_MUNK if surface is None else surface
    return np.asarray(surface, dtype=np.float64)[..., None] if np.ndim(surface) else float(surface)


def _seen(method: str, reflectance, coefficients: tuple, base: SkinParameters, surface, port_mm: float | None):
    """``reflectance`` as read through a sample port of ``port_mm`` (mm; ``None``: itself), the diffuse part's
    lateral loss from the dermis' ``coefficients`` (:mod:`.port_loss`)."""
    if port_mm is None:
        return reflectance
    return through_port(reflectance, _specular(method, base, surface), coefficients[1], coefficients[3], port_mm,
                        G_SKIN, float(base.n))


def _model(method: str, lam: NDArrayFloat, x: NDArrayFloat, names: tuple, base: SkinParameters,
           quad_pts: int, port_mm: float | None = None) -> NDArrayFloat:
    """The model at parameter rows ``x`` ``(m, len(names))``: reflectances ``(m, len(lam))``, read through a
    sample port of ``port_mm`` (mm; ``None``: none)."""
    values = {name: getattr(base, name) for name in (*LAYER_KEYS, "surface", "melanin_law")}
    values.update({name: x[:, i] for i, name in enumerate(names)})
    coefficients = layer_coefficients(lam, values)
    model = method_of(method, FIT_MODELS, "method")
    reflectance = model(coefficients, base, **({"quad_pts": quad_pts} if takes(model, "quad_pts")
                                               else {"surface": values["surface"]}))
    return _seen(method, reflectance, coefficients, base, values["surface"], port_mm)


def measured_reflectance(wavelength: ArrayLike, parameters: SkinParameters, method: str = "adding-doubling",
                         port_mm: float | None = None) -> NDArrayFloat:
    """
    The skin model's reflectance (:func:`~skinrender.datasets.skin_model.skin_reflectance`) as a contact
    instrument of sample port diameter ``port_mm`` (mm) reads it: the diffuse part's lateral loss removed
    (:mod:`.port_loss`); ``None``: the model's own, as a camera sees skin. Fractions on ``wavelength`` (nm).
    """
    lam = np.asarray(wavelength, dtype=np.float64)
    port_mm = check_port(port_mm)
    with np.errstate(all="ignore"):
        reflectance = skin_reflectance(lam, parameters, method)
    if port_mm is None:
        return reflectance
    from dataclasses import asdict

    return _seen(method, reflectance, layer_coefficients(lam, asdict(parameters)), parameters, parameters.surface,
                 port_mm)


def _least_squares(method, lam, target, x0, names, base, quad_pts, low, high, port_mm=None):
    from scipy.optimize import least_squares  # here: importing scipy.optimize costs every command ~0.6 s

    steps = np.array([1e-4 * _SCALE[name] for name in names])

    def residual(x):
        return _model(method, lam, x[None, :], names, base, quad_pts, port_mm)[0] - target

    def jacobian(x):
        # forward differences, stepping back at an upper bound; the point and its steps in one batched call
        h = np.where(x + steps > high, -steps, steps)
        rows = np.vstack([x, x + np.diag(h)])
        values = _model(method, lam, rows, names, base, quad_pts, port_mm)
        return ((values[1:] - values[0]) / h[:, None]).T

    scale = np.array([_SCALE[name] for name in names])
    return least_squares(residual, np.clip(x0, low, high), jac=jacobian, bounds=(low, high), x_scale=scale,
                         method="trf", max_nfev=200)


def fit_skin_spectrum(wavelength: ArrayLike, reflectance: ArrayLike, method: str = "adding-doubling",
                      start: SkinParameters | None = None, name: str = "", scan: bool | None = None,
                      fitted: tuple[str, ...] | None = None, port_mm: float | None = None) -> SkinFit:
    """
    Fit the skin model to one measured spectrum within :data:`FIT_BOUNDS`.

    Parameters
    ----------
    wavelength
        Wavelengths, nm (those of the measurement).
    reflectance
        Measured reflectance, fractions, on ``wavelength``.
    method
        ``adding-doubling`` (default) or ``kubelka-munk``.
    start
        Starting parameters, and the values of those not fitted (``epidermis_mm``, ``n``); ``None``: the
        defaults.
    name
        The spectrum's name, carried into the result.
    scan
        Start from the melanin of the best of a scan over light to very dark skin (``None``: when ``start``
        is ``None``).
    fitted
        The parameters fitted, melanin first (``None``: :data:`FIT_PARAMETERS` of ``method``); each needs
        :data:`FIT_BOUNDS`. The others are held at ``start``'s values.
    port_mm
        The measuring instrument's sample port diameter, mm: the model is read through it
        (:func:`measured_reflectance`; its lateral loss is the instrument's, the fitted parameters the skin's).
        ``None`` (default): an area much larger than the light's spread.

    Returns
    -------
    :class:`SkinFit`
        The RMS is the model's (:func:`measured_reflectance`, through ``port_mm``) against the measurement on
        every wavelength given.
    """
    validate_method(method, SKIN_REFLECTANCE_METHODS, "method")
    lam, target = measured_spectrum(wavelength, reflectance, least=8)
    if scan is not None:
        scan = check_flag(scan, "scan")
    if start is not None and not isinstance(start, SkinParameters):
        raise SkinrenderError(f"start must be SkinParameters or None, got {type(start).__name__}", role="start")
    if isinstance(fitted, str):
        raise SkinrenderError(f"fitted must be a sequence of parameter names, melanin first, got {fitted!r}",
                              role="fitted")
    names = FIT_PARAMETERS[method] if fitted is None else tuple(fitted)
    if not names or names[0] != "melanin" or any(n not in FIT_BOUNDS for n in names):
        raise SkinrenderError(f"fitted must name parameters of {sorted(FIT_BOUNDS)}, melanin first, got {names}",
                              role="fitted")
    port_mm = check_port(port_mm)
    base = start or SkinParameters()
    corrected = takes(FIT_MODELS[method], "quad_pts")  # adding-doubling: from 8 quadrature points to 16
    if not takes(FIT_MODELS[method], "surface"):  # its surface is the Fresnel boundary
        base = replace(base, surface=None)
    low = np.array([FIT_BOUNDS[n][0] for n in names])
    high = np.array([FIT_BOUNDS[n][1] for n in names])
    x0 = np.array([SURFACE_KUBELKA_MUNK if getattr(base, n) is None else float(getattr(base, n)) for n in names])
    quad = _QUAD_ITERATIONS
    if (start is None) if scan is None else scan:  # the melanin of the best of a scan, light to very dark
        rows = np.repeat(np.clip(x0, low, high)[None, :], len(_MELANIN_SCAN), axis=0)
        rows[:, 0] = _MELANIN_SCAN
        errors = np.mean((_model(method, lam, rows, names, base, quad, port_mm) - target) ** 2, axis=1)
        x0[0] = _MELANIN_SCAN[int(np.argmin(errors))]
    evaluations = 0
    try:
        with np.errstate(all="ignore"):
            found = _least_squares(method, lam, target, x0, names, base, quad, low, high, port_mm)
            evaluations += found.nfev
            for _ in range(CORRECTIONS if corrected else 0):
                # defect correction: the fit to 8 points' model, its target shifted by what 16 points change
                # at the current parameters, converges on the 16-point fit in half its time
                rows = found.x[None, :]
                defect = (_model(method, lam, rows, names, base, QUAD_PTS_DEFAULT, port_mm)
                          - _model(method, lam, rows, names, base, quad, port_mm))[0]
                found = _least_squares(method, lam, target - defect, found.x, names, base, quad, low, high,
                                       port_mm)
                evaluations += found.nfev + 2
    except SkinrenderError:
        raise  # bad input (wavelengths beyond the absorbers' data …), not a fit that failed
    except (np.linalg.LinAlgError, ValueError) as error:
        return SkinFit(name, base, math.nan, {}, False, f"the fit failed: {error}", evaluations,
                       skin_verdict(math.nan, {}, method, False))
    x = np.clip(found.x, low, high)
    fitted = replace(base, **{n: float(v) for n, v in zip(names, x)})
    model = measured_reflectance(lam, fitted, method, port_mm)
    rms = float(np.sqrt(np.mean((model - target) ** 2)))
    span = high - low
    hit = {n: side for n, v, lo, hi, s in zip(names, x, low, high, span)
           for side in (("low",) if v <= lo + 1e-3 * s else ("high",) if v >= hi - 1e-3 * s else ())}
    converged = bool(found.status > 0 and math.isfinite(rms))
    return SkinFit(name, fitted, rms, hit, converged, str(found.message), evaluations,
                   skin_verdict(rms, hit, method, converged))


def fit_skin(wavelength: ArrayLike, reflectance: ArrayLike, start: SkinParameters | None = None,
             method: str = "adding-doubling", port_mm: float | None = None) -> tuple[SkinParameters, float]:
    """
    Fit the model to one measured spectrum within :data:`FIT_BOUNDS`: the fitted :class:`SkinParameters` and
    the RMS reflectance error (fraction); ``port_mm``: the instrument's sample port diameter, mm
    (:func:`fit_skin_spectrum`, which gives the whole report).
    """
    fitted = fit_skin_spectrum(wavelength, reflectance, method=method, start=start, port_mm=port_mm)
    return fitted.parameters, fitted.rms


def _fit_one(job):
    lam, values, name, method, held, fitted, port_mm = job
    return fit_skin_spectrum(lam, values, method, start=held, name=name, scan=True, fitted=fitted, port_mm=port_mm)


def fit_seconds(count: int, wavelengths: int, method: str, workers: int = 1) -> float:
    """
    The time a fit of ``count`` spectra of ``wavelengths`` wavelengths should take on ``workers`` cores, s
    (:data:`SECONDS_PER_FIT`, linear in the wavelengths).

    >>> round(fit_seconds(100, 100, "adding-doubling", workers=2))
    75
    """
    return count * SECONDS_PER_FIT[method] * wavelengths / 100 / max(1, min(workers, count))


def fit_skin_spectra(wavelength: ArrayLike, values: ArrayLike, names, method: str = "adding-doubling",
                     workers: int | None = 1, progress=None, held: SkinParameters | None = None,
                     fitted: tuple[str, ...] | None = None, port_mm: float | None = None) -> list[SkinFit]:
    """
    Fit every spectrum (rows of ``values``, on ``wavelength`` in nm) on ``workers`` processes (``None``: every
    core), each started from a melanin scan; ``progress``: a stream for a progress bar, or ``None``; ``held``:
    the values of the parameters not fitted (``None``: the defaults); ``fitted``: as in
    :func:`fit_skin_spectrum`; ``port_mm``: the instrument's sample port diameter, mm (``None``: none;
    :func:`fit_skin_spectrum`). Results in the order of the rows.
    """
    validate_method(method, SKIN_REFLECTANCE_METHODS, "method")
    port_mm = check_port(port_mm)
    lam = np.asarray(wavelength, dtype=np.float64)
    values = np.atleast_2d(np.asarray(values, dtype=np.float64))
    jobs = [(lam, row, str(name), method, held, fitted, port_mm) for row, name in zip(values, names)]
    workers = min(len(jobs), workers or os.cpu_count() or 1)
    bar = None
    if progress is not None:  # a bar on a terminal, one line elsewhere (a log, a pipe: no carriage returns)
        from ..workload import announce, progress_bar

        announce(progress, f"fitting ({method})", len(jobs), "fit")
        bar = progress_bar(len(jobs), f"fitting ({method})", progress, "fit")
    results = []
    try:
        if workers <= 1:
            for job in jobs:
                results.append(_fit_one(job))
                if bar is not None:
                    bar.update()
        else:
            with ProcessPoolExecutor(max_workers=workers) as pool:
                for result in pool.map(_fit_one, jobs):
                    results.append(result)
                    if bar is not None:
                        bar.update()
    finally:
        if bar is not None:
            bar.close()
    return results
