"""
A contact instrument's lateral loss
===================================

A spectrophotometer pressed on the skin reads only the light that leaves the skin
within its sample port. Light diffuses millimetres sideways in the dermis before it
leaves (the more, the less the skin absorbs: in the red), so a small port reads
skin darker than a camera, which sees skin over an area much larger than that
spread: a 5 mm aperture reads skin up to ~10 % darker at 700 nm than an 11 mm one
:cite:`Takiwaki2002`. The 100 NIST skins were measured on a spot ~5 mm across
:cite:`CookseyAllen2013`. Fitting the skin model to such a measurement, the model's
reflectance is seen through the port (``skinrender skin --fit … --port-mm D``): the
loss is the instrument's, not the skin's, and the fitted parameters are the skin's.

The diffuse part of the reflectance (all but the surface's specular reflection)
keeps the fraction of a semi-infinite medium's diffuse reflectance, for a pencil
beam at the port's centre, that leaves within the port's radius ``ρ``, from the
diffusion model of :cite:`Farrell1992` (a source at ``z₀ = 1/μt'`` and its image
beyond the extrapolated boundary, whose radial reflectance integrates over a disc in
closed form):

``kept = Σᵢ [e^(−μeff zᵢ) − zᵢ e^(−μeff rᵢ) / rᵢ] / Σᵢ e^(−μeff zᵢ)``, ``rᵢ = √(zᵢ² + ρ²)``,

over ``z₀`` and ``z₀ + 2 z_b``, ``z_b = 2 (1 + R_eff) / (3 μt' (1 − R_eff))`` (``R_eff`` of
:cite:`Groenhuis1983` at the skin's index), ``μeff = √(3 μa μt')``, ``μt' = μa + μs (1 − g)``.
The dermis' coefficients stand for the whole skin: the epidermis (0.1 mm) is thin
against the millimetres the red light spreads, and the loss is small where the
epidermis absorbs most (the blue: a 5 mm port keeps 99.6 % of the default skin's
diffuse reflectance at 450 nm, 80 % at 700 nm).

-   :func:`kept_fraction`: the fraction a port of a radius keeps.
-   :func:`through_port`: a reflectance as an instrument of a port diameter reads it.

References
----------
-   Cooksey, C. C., & Allen, D. W. (2013). Reflectance measurements of human skin from the ultraviolet to the
    shortwave infrared (250 nm to 2500 nm). Proc. SPIE 8734, 87340N (the skin under test ~5 mm across).
-   Farrell, T. J., Patterson, M. S., & Wilson, B. (1992). A diffusion theory model of spatially resolved,
    steady-state diffuse reflectance for the noninvasive determination of tissue optical properties in vivo.
    Medical Physics, 19(4), 879–888.
-   Groenhuis, R. A. J., Ferwerda, H. A., & Ten Bosch, J. J. (1983). Scattering and absorption of turbid
    materials determined from reflection measurements. 1: Theory. Applied Optics, 22(16), 2456–2462.
-   Takiwaki, H., Miyaoka, Y., Skrebova, N., Kohno, H., & Arase, S. (2002). Skin reflectance-spectra and
    colour-value dependency on measuring-head aperture area in ordinary reflectance spectrophotometry and
    tristimulus colourimetry. Skin Research and Technology, 8(2).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import SkinrenderError
from ..hints import ArrayLike, NDArrayFloat

__all__ = ["kept_fraction", "through_port", "check_port"]


def check_port(port_mm) -> float | None:
    """``port_mm`` as a float, ``None`` for none; a finite diameter > 0 mm (not a bool), else an error naming it."""
    if port_mm is None:
        return None
    try:
        value = math.nan if isinstance(port_mm, bool) else float(port_mm)
    except (TypeError, ValueError):
        value = math.nan
    if not (math.isfinite(value) and value > 0):
        raise SkinrenderError(f"port_mm must be a sample port's diameter, finite mm > 0, got {port_mm!r}",
                              role="port_mm")
    return value


def kept_fraction(mu_a: ArrayLike, mu_s: ArrayLike, radius_mm: float, g: float, n: float) -> NDArrayFloat:
    """
    The fraction of a semi-infinite medium's diffuse reflectance that leaves within ``radius_mm`` of a pencil
    beam (Farrell et al. 1992's diffusion model; module docstring).

    Parameters
    ----------
    mu_a, mu_s
        Absorption and scattering coefficients, mm⁻¹ (broadcast together).
    radius_mm
        The port's radius, mm (≥ 0; broadcast with them).
    g, n
        The medium's anisotropy and refractive index.

    Returns
    -------
    ndarray
        Fractions in [0, 1]: 0 at radius 0, 1 as the radius grows without bound.

    Examples
    --------
    >>> float(kept_fraction(0.01, 20.0, 0.0, 0.8, 1.4))
    0.0
    >>> round(float(kept_fraction(0.01, 20.0, 2.5, 0.8, 1.4)), 3)
    0.859
    >>> round(float(kept_fraction(0.01, 20.0, 1e4, 0.8, 1.4)), 6)
    1.0
    """
    mu_a, mu_s, radius_mm = (_checked(value, name, low) for value, name, low in
                             ((mu_a, "mu_a", 0.0), (mu_s, "mu_s", 0.0), (radius_mm, "radius_mm", 0.0)))
    g, n = _checked(g, "g", -1.0), _checked(n, "n", 1.0)
    if g.ndim or n.ndim or not -1.0 < float(g) < 1.0:
        name = "g" if g.ndim or not -1.0 < float(g) < 1.0 else "n"
        raise SkinrenderError(f"{name} must be one number (g an anisotropy in (−1, 1), n ≥ 1)", role=name)
    g, n = float(g), float(n)
    if np.any(mu_a + mu_s * (1.0 - g) <= 0):
        raise SkinrenderError("mu_a and mu_s must not both be 0: the medium has no transport length", role="mu_a")
    transport = mu_a + mu_s * (1.0 - g)
    effective = np.sqrt(3.0 * mu_a * transport)
    r_eff = -1.440 / n**2 + 0.710 / n + 0.668 + 0.0636 * n  # Groenhuis et al. 1983
    z0 = 1.0 / transport
    total = inside = 0.0
    for z in (z0, z0 + 4.0 * (1.0 + r_eff) / (1.0 - r_eff) / (3.0 * transport)):
        r = np.sqrt(z * z + np.asarray(radius_mm, dtype=np.float64) ** 2)
        total = total + np.exp(-effective * z)
        inside = inside + np.exp(-effective * z) - z * np.exp(-effective * r) / r
    return np.clip(inside / total, 0.0, 1.0)


def _checked(value, name: str, low: float) -> NDArrayFloat:
    """``value`` as finite float(s) ≥ ``low``, else an error naming ``name``."""
    try:
        array = np.asarray(value, dtype=np.float64) if not isinstance(value, bool) else np.array(math.nan)
    except (TypeError, ValueError):
        array = np.array(math.nan)
    if array.size == 0 or not np.all(np.isfinite(array) & (array >= low)):
        raise SkinrenderError(f"{name} must be finite and ≥ {low:g}, got {value!r}", role=name)
    return array


def through_port(reflectance: ArrayLike, specular: ArrayLike, mu_a: ArrayLike, mu_s: ArrayLike,
                 port_mm: float | None, g: float, n: float) -> NDArrayFloat:
    """
    ``reflectance`` as an instrument of sample port diameter ``port_mm`` (mm) reads it: its ``specular`` part
    (the surface's reflection, fraction) whole, its diffuse rest times :func:`kept_fraction` of the medium
    ``mu_a``, ``mu_s`` (mm⁻¹; the dermis', module docstring); ``port_mm`` ``None``: ``reflectance`` itself
    (an area much larger than the light's spread, as a camera sees skin).

    >>> float(through_port(0.5, 0.03, 0.01, 20.0, None, 0.8, 1.4))
    0.5
    >>> round(float(through_port(0.5, 0.03, 0.01, 20.0, 5.0, 0.8, 1.4)), 3)
    0.434
    """
    reflectance = _checked(reflectance, "reflectance", 0.0)
    port_mm = check_port(port_mm)
    if port_mm is None:
        return reflectance
    specular = _checked(specular, "specular", 0.0)
    return specular + (reflectance - specular) * kept_fraction(mu_a, mu_s, port_mm / 2.0, g, n)
