"""
Sampling pieces of the skin's integrator
========================================

The functions :mod:`~skinrender.rendering.skin_integrator`'s traced kernel is
made of, each on Dr.Jit arrays of the variant set (:func:`bind`).

-   :func:`component`, :func:`spectral`, :func:`power`: a wavelength's value,
    the spectral MIS weight of a walk, the power heuristic.
-   :func:`hg_pdf`, :func:`hg_sample`, :func:`phase_g`: Henyey–Greenstein.
-   :func:`inside_direction`, :func:`layer_lengths`, :func:`coefficients`:
    the skin's optics (refraction, layers by depth, a medium's coefficients).
-   :func:`flat`, :func:`margin`: a skin surface's shading frame, a
    scattering point's float32 margin.

Units: lengths in scene units, densities per steradian.
"""

from __future__ import annotations

__all__ = ["bind", "phase_g", "component", "power", "spectral", "coefficients", "hg_pdf", "hg_sample",
           "inside_direction", "layer_lengths", "flat", "margin"]

mi = dr = None  # the mitsuba and drjit modules, set by bind


def bind(module) -> None:
    """Use ``module`` (``mitsuba``, its variant set) and drjit."""
    global mi, dr
    import drjit

    mi, dr = module, drjit


def phase_g(medium) -> float:
    """The Henyey–Greenstein ``g`` of a medium's phase function."""
    return float(mi.traverse(medium.phase_function())["g"][0])


def component(spectrum, index):
    """``spectrum[index]`` per lane."""
    return dr.select(index == 0, spectrum[0], dr.select(index == 1, spectrum[1],
                                                        dr.select(index == 2, spectrum[2], spectrum[3])))

def power(a, b):
    """The power heuristic's weight of a density ``a`` against ``b``."""
    a2, b2 = dr.square(a), dr.square(b)
    return dr.select(a2 + b2 > 0, a2 / (a2 + b2), 0.0)

def spectral(log_a, log_r):
    """Per wavelength: its survival times its density over the mean of the four (the MIS'd weight)."""
    top = dr.max(log_r)
    return dr.exp(log_a + log_r - top) / dr.mean(dr.exp(log_r - top))

def coefficients(medium, wavelengths):
    """A medium's scattering and extinction at ``wavelengths``; the extinction at least 1e-12 per scene unit: a
    wavelength sampled a float32 step outside the medium's spectrum reads 0 there, whose albedo 0 / 0 was a NaN
    pixel in ~10⁷ paths (a skin_patches chart at 256 spp); at 1e-12 it is clear, as it reads, and carries nothing."""
    mei = dr.zeros(mi.MediumInteraction3f)
    mei.wavelengths = wavelengths
    sigma_s, _, sigma_t = medium.get_scattering_coefficients(mei)
    return mi.Spectrum(sigma_s), dr.maximum(mi.Spectrum(sigma_t), 1e-12)

def hg_pdf(g, cos_theta):
    """The Henyey–Greenstein density (per steradian) of the angle whose cosine is ``cos_theta``."""
    denominator = 1.0 + g * g - 2.0 * g * cos_theta
    return (1.0 - g * g) / (4.0 * dr.pi * denominator * dr.safe_sqrt(denominator))


def hg_sample(g, axis, u):
    """A direction about ``axis`` with the Henyey–Greenstein density of ``g``, and that density."""
    sq = (1.0 - g * g) / (1.0 - g + 2.0 * g * u.x)
    cos_t = dr.clip(dr.select(dr.abs(g) > 1e-3, (1.0 + g * g - sq * sq) / (2.0 * g), 1.0 - 2.0 * u.x), -1.0, 1.0)
    sin_t = dr.safe_sqrt(1.0 - cos_t * cos_t)
    sin_p, cos_p = dr.sincos(2.0 * dr.pi * u.y)
    return mi.Frame3f(axis).to_world(mi.Vector3f(sin_t * cos_p, sin_t * sin_p, cos_t)), hg_pdf(g, cos_t)


def inside_direction(light, normal, eta):
    """The direction inside the skin (index ``eta``) that a smooth surface of ``normal`` refracts into the unit
    direction ``light`` outside; valid where ``light`` is above the surface."""
    tangent = (light - dr.dot(light, normal) * normal) / eta
    return tangent + dr.safe_sqrt(1.0 - dr.squared_norm(tangent)) * normal, dr.dot(light, normal) > 0


def layer_lengths(z, rate, length, in_epi, thickness):
    """How much of a straight ``length`` from depth ``z`` (depth gained per unit length ``rate``) lies in the
    layer the segment starts in, and in the other."""
    crosses = (thickness > 0) & dr.select(in_epi, rate > 0, rate < 0)
    t_cross = dr.select(crosses, dr.maximum((thickness - z) / rate, 0.0), dr.inf)
    first = dr.minimum(length, t_cross)
    return first, length - first


def flat(si, active, wi_world):
    """At a skin surface, the triangle's own normal as the shading frame (``wi`` recomputed): with interpolated
    normals a path's side of the surface and its BSDF's could disagree (energy from nowhere: fireflies)."""
    frame, shading = mi.Frame3f(si.n), si.sh_frame
    shading.s, shading.t, shading.n = (dr.select(active, a, b) for a, b in
                                       ((frame.s, shading.s), (frame.t, shading.t), (frame.n, shading.n)))
    si.sh_frame = shading
    si.wi = dr.select(active, frame.to_local(wi_world), si.wi)


def margin(p):
    """A few float32 steps at ``p``: how far behind a scattering point its intersection query starts."""
    return (1.0 + dr.max(dr.abs(p))) * 2.0**-21
