"""
Analytic limits of face renders
===============================

Where the analytic camera model holds exactly on a rendered face, and the
statistics that check it (``skinrender validate face`` and the tests share
them). Every check works on ``K`` replicate renders (independent seeds): a
statistic of their mean is compared with its analytic value against its own
measured noise (the jackknife over the replicates, Student's t with ``K − 1``
degrees of freedom), the critical value Šidák-corrected for the number of
values tested, so that a correct renderer fails a check with probability
:data:`ALPHA` at most.

-   :func:`check_shading` (``direct``), :func:`check_dichromatic` (``sheen``) [Shafer1985],
    :func:`check_furnace`, :func:`check_sphere` (their scenes:
    :mod:`skinrender.rendering.face.limit_scenes`); :func:`eq4_shift`: how far skin moves from
    Eq. 4 (information).
-   :func:`critical_t`, :func:`jackknife`, :func:`rounding_bias`; :class:`LimitCheck`, a result;
    :func:`sphere_emission`, the closed sphere's emission.

A check's ``statistic`` is the largest ``|deviation| / standard error`` (a
Student t) over the values it tests, its ``tolerance`` the Šidák critical t;
it passes when ``statistic ≤ tolerance``. Each standard error is the
jackknife's combined in quadrature with the float32 floor
(:data:`~skinrender.rendering.validation.FLOAT32_FLOOR` of the value); through
an image sensor a pixel's deviation may also use up the bound of the
quantisation's mean error (:func:`rounding_bias`), which is subtracted from it
first, and its standard error is taken no smaller than the sensor model's.

Units: images in Eq. 4 output units; radiance in the specfilm's units;
temperatures K; NCC fractions.

References
----------
-   :cite:`Shafer1985` : S. A. Shafer (1985). Using color to separate
    reflection components. Color Research & Application 10(4), 210–218.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...hints import NDArrayFloat
from ...model.camera import Camera, camera
from ...model.chromaticity import ncc
from ...spectra import GRID_DEFAULT, WavelengthGrid, planck
from ..validation import FLOAT32_FLOOR
from .document import channel_integral, light_irradiance
from .labels import LABEL_SKIN, interior
from .scene import Light

__all__ = ["ALPHA", "REPLICATES", "LINEAR", "PIXELS_MIN", "LimitCheck", "critical_t", "jackknife", "rg",
           "rounding_bias", "lit_skin", "check_shading", "eq4_shift", "check_dichromatic", "check_furnace",
           "check_sphere", "sphere_emission"]

ALPHA = 0.01
"""Family-wise false-alarm rate of each check (Šidák-corrected over its pixels and channels)."""

REPLICATES = 12
"""Independent renders (seeds) per check: the jackknife's t has 11 degrees of freedom."""

LINEAR = 0.05
"""Pixels whose channels' relative standard error is below this are 'lit': a ratio's (NCC's) jackknife
error is then first order, its neglected bias ~LINEAR² of the value, far below the error itself."""

PIXELS_MIN = 10
"""Fewer tested pixels than this and a check is not run (``passed`` None): too small an image or too few spp."""


def sphere_emission(grid: WavelengthGrid = GRID_DEFAULT) -> tuple[NDArrayFloat, NDArrayFloat]:
    """Wavelengths (nm) and the relative emission of the closed sphere: a 3000 K Planckian, peak 1."""
    lam = light_irradiance(Light(3000.0, 1.0), grid)[0]
    return lam, planck(lam, 3000.0) / planck(lam, 3000.0).max()


@dataclass(frozen=True)
class LimitCheck:
    """
    One analytic limit checked on replicate renders.

    Attributes
    ----------
    name
        ``shading_cancels``, ``dichromatic_plane``, ``white_furnace``,
        ``closed_sphere`` or ``eq4_shift`` (information).
    applies
        Whether the limit holds at the level rendered (``False``: the row is information).
    passed
        ``True``/``False``; ``None`` when nothing was tested (``reason`` says why).
    statistic, tolerance
        The largest ``|deviation| / standard error`` and the Šidák critical t
        (for ``eq4_shift``: the shift of the skin's mean NCC (r, g), Euclidean,
        and the shift the replicates could resolve).
    pixels
        Pixels tested.
    reason
        What was tested, or why not.
    details
        Further figures (JSON-ready).
    """

    name: str
    applies: bool
    passed: bool | None
    statistic: float | None
    tolerance: float | None
    pixels: int
    reason: str
    details: dict = field(default_factory=dict)

    def document(self) -> dict:
        """The JSON row: ``name, applies, passed, statistic, tolerance, pixels, reason`` and the details."""
        return {"name": self.name, "applies": self.applies, "passed": self.passed, "statistic": self.statistic,
                "tolerance": self.tolerance, "pixels": self.pixels, "reason": self.reason, **self.details}


def critical_t(tests: int, replicates: int = REPLICATES, alpha: float = ALPHA) -> float:
    """
    Two-sided Student-t critical value of ``tests`` independent tests at family-wise ``alpha`` (Šidák).

    Examples
    --------
    >>> round(critical_t(1, 12, 0.05), 3)  # one test, 11 degrees of freedom
    2.201
    >>> critical_t(1000) > critical_t(10)
    True
    """
    from scipy import stats

    each = -np.expm1(np.log1p(-alpha) / max(int(tests), 1))
    return float(stats.t.isf(each / 2, replicates - 1))


def jackknife(samples: NDArrayFloat, statistic) -> tuple[NDArrayFloat, NDArrayFloat]:
    """
    ``statistic`` of the replicate mean and its jackknife standard error; replicates on axis 0.

    Examples
    --------
    >>> value, error = jackknife(np.array([1.0, 2.0, 3.0, 4.0]), lambda m: m)  # the mean: SE = s / √K
    >>> float(value), round(float(error), 4)
    (2.5, 0.6455)
    """
    samples = np.asarray(samples, dtype=np.float64)
    k = samples.shape[0]
    total = samples.sum(axis=0)
    value = statistic(total / k)
    leave_out = np.array([statistic((total - s) / (k - 1)) for s in samples])
    error = np.sqrt((k - 1) / k * np.sum((leave_out - leave_out.mean(axis=0)) ** 2, axis=0))
    return value, error


def rg(rgb: NDArrayFloat) -> NDArrayFloat:
    """NCC (r, g) of channels on the last axis."""
    return ncc(rgb)[..., :2]


def rounding_bias(sigma_dn: NDArrayFloat, terms: int = 32) -> NDArrayFloat:
    """
    Bound of the mean error of rounding a normal value of standard deviation ``sigma_dn`` (DN) to a code, DN.

    ``E[round(x + σZ)] − x`` is periodic in ``x``; its Fourier series has
    terms ``(−1)^m / (π m) · exp(−2π² m² σ²) · sin(2π m x)``, so its size is at
    most ``Σ exp(−2π² m² σ²) / (π m)``, and never more than half a code.

    Examples
    --------
    >>> print(f"{rounding_bias(0.25):.3f} {rounding_bias(1.0):.1e}")
    0.094 8.5e-10
    """
    sigma = np.asarray(sigma_dn, dtype=np.float64)[..., None]
    m = np.arange(1, terms + 1)
    return np.minimum(np.sum(np.exp(-2 * np.pi**2 * m**2 * sigma**2) / (np.pi * m), axis=-1), 0.5)


def _ratio(deviation: NDArrayFloat, error: NDArrayFloat) -> NDArrayFloat:
    """``deviation / error``, 0 where both are 0 (a shadowed pixel is exactly black in every replicate)."""
    deviation, error = np.broadcast_arrays(np.asarray(deviation, dtype=np.float64), error)
    out = np.where(deviation > 0, np.inf, 0.0)
    np.divide(deviation, error, out=out, where=error > 0)
    return out


def _jacobian(mean: NDArrayFloat) -> NDArrayFloat:
    """``∂(r, g)/∂c_k = (δ_ik − c_i / S) / S`` of channels ``mean``, shape ``(..., 2, 3)``."""
    total = mean.sum(axis=-1, keepdims=True)[..., None]
    return (np.eye(3)[:2] - (mean / total[..., 0])[..., :2, None]) / total


def _sensor(bias, floor, mean: NDArrayFloat, weights=None) -> tuple:
    """
    A sensor's bound of the mean error and floor of the standard error, carried from the channels to
    (r, g) (``weights`` None) or to a projection on ``weights``; zeros without a sensor.
    """
    if bias is None:
        return np.zeros(1), np.zeros(1)
    floor = np.zeros_like(bias) if floor is None else floor
    if weights is None:
        jacobian = _jacobian(mean)
        return (np.einsum("...ik,...k->...i", np.abs(jacobian), bias),
                np.sqrt(np.einsum("...ik,...k->...i", jacobian**2, floor)))
    return bias @ np.abs(weights), np.sqrt(floor @ weights**2)


def lit_skin(images: NDArrayFloat, labels: NDArrayFloat, usable: NDArrayFloat | None = None) -> NDArrayFloat:
    """
    The interior skin pixels whose every channel's replicate mean has a relative standard error below
    :data:`LINEAR` (and that are ``usable``): where NCC's jackknife error is first order.
    """
    mean = images.mean(axis=0)
    error = images.std(axis=0, ddof=1) / np.sqrt(images.shape[0])
    lit = interior(labels, LABEL_SKIN) & np.all(error < LINEAR * mean, axis=-1)
    return lit if usable is None else lit & usable


def _skin_ncc(images: NDArrayFloat, labels: NDArrayFloat, usable: NDArrayFloat | None) -> tuple:
    """
    The lit skin pixels (:func:`lit_skin`) and their count, and, when there are at least
    :data:`PIXELS_MIN`, their NCC (r, g) per pixel and pooled over them with jackknife standard errors
    (``(value, se, pooled, pooled_se)``, else ``None``): what :func:`check_shading` and
    :func:`eq4_shift` compare with Eq. 4.
    """
    lit = lit_skin(images, labels, usable)
    pixels = int(lit.sum())
    if pixels < PIXELS_MIN:
        return lit, pixels, None
    samples = images[:, lit]
    return lit, pixels, (*jackknife(samples, rg), *jackknife(samples, lambda m: rg(m).mean(axis=0)))


def check_shading(images: NDArrayFloat, labels: NDArrayFloat, expected: NDArrayFloat,
                  usable: NDArrayFloat | None = None, bias: NDArrayFloat | None = None,
                  floor: NDArrayFloat | None = None) -> LimitCheck:
    """
    Shading cancels in NCC: every lit skin pixel's (r, g) equals Eq. 4's.

    Under one Planckian with direct light only, a skin pixel's radiance is
    ``ρ(λ) E(λ) G`` with ``G`` the shading (cosine, distance, shadowing, the
    pixel's coverage) independent of λ, so its channels are ``G ∫ ρ E x_k``
    and its NCC is Eq. 4's, whatever ``G``. Tested per pixel and pooled over
    the pixels (a bias too small for any one pixel, in one direction, shows
    there).

    Parameters
    ----------
    images
        ``(K, height, width, 3)`` balanced replicate images, output units.
    labels
        ``(height, width)`` label image (1 skin).
    expected
        Eq. 4's NCC of the skin, ``[r, g, b]`` (or ``[r, g]``).
    usable
        Pixels a sensor left linear (unclipped); ``None``: all.
    bias, floor
        ``(height, width, 3)``: the bound of each channel's mean error from
        the sensor's quantisation, output units, and the variance of each
        channel's replicate mean by the sensor's model (shot, read and
        quantisation noise), output units², below which the standard error
        is not taken (twelve frames may read one code); ``None``: no sensor.
    """
    images = np.asarray(images, dtype=np.float64)
    expected = np.asarray(expected, dtype=np.float64)[:2]
    lit, pixels, measured = _skin_ncc(images, labels, usable)
    if measured is None:
        return LimitCheck("shading_cancels", True, None, None, None, pixels,
                          f"only {pixels} lit skin pixels (channels' relative standard error < {LINEAR:g}): "
                          "render larger or with more spp")
    value, se, pooled, pooled_se = measured
    tests = value.size + 2
    systematic, least = _sensor(None if bias is None else bias[lit], None if floor is None else floor[lit],
                                images.mean(axis=0)[lit])
    se = np.maximum(se, least)
    t_pixel = _ratio(np.maximum(np.abs(value - expected) - systematic, 0.0), np.hypot(se, FLOAT32_FLOOR * value))
    pooled_se = np.maximum(pooled_se, np.sqrt(np.sum(np.square(least), axis=0)) / pixels)
    t_pooled = _ratio(np.maximum(np.abs(pooled - expected) - np.mean(systematic, axis=0), 0.0),
                      np.hypot(pooled_se, FLOAT32_FLOOR))
    statistic = float(max(t_pixel.max(), t_pooled.max()))
    tolerance = critical_t(tests, images.shape[0])
    shading = images.mean(axis=0)[lit].sum(axis=-1)
    return LimitCheck("shading_cancels", True, statistic <= tolerance, statistic, tolerance, pixels,
                      "every lit skin pixel's NCC (r, g) against Eq. 4's, and their mean (direct light from one "
                      "Planckian: the shading cancels)",
                      {"worst_pixel_t": float(t_pixel.max()), "pooled_t": float(t_pooled.max()),
                       "ncc_expected": expected.tolist(), "ncc_mean": pooled.tolist(),
                       "shading_range": float(shading.max() / shading.min())})


def eq4_shift(images: NDArrayFloat, labels: NDArrayFloat, expected: NDArrayFloat, why: str,
              usable: NDArrayFloat | None = None) -> LimitCheck:
    """
    How far skin moves from Eq. 4 (information: ``applies`` False, ``passed`` None).

    ``statistic``: the Euclidean shift of the lit skin pixels' mean NCC (r, g)
    from Eq. 4's; ``tolerance``: the shift the replicates resolve (the Šidák
    critical t times the pooled standard error); ``share_outside``: the share
    of lit skin pixels whose own NCC lies beyond their per-pixel tolerance
    (:func:`check_shading`'s); ``why``: why no limit holds.
    """
    images = np.asarray(images, dtype=np.float64)
    expected = np.asarray(expected, dtype=np.float64)[:2]
    _, pixels, measured = _skin_ncc(images, labels, usable)
    if measured is None:
        return LimitCheck("eq4_shift", False, None, None, None, pixels,
                          f"{why}; only {pixels} lit skin pixels, no shift measured")
    value, se, pooled, pooled_se = measured
    tolerance = critical_t(value.size + 2, images.shape[0])
    outside = np.any(_ratio(np.abs(value - expected), np.hypot(se, FLOAT32_FLOOR * value)) > tolerance, axis=-1)
    shift = pooled - expected
    return LimitCheck("eq4_shift", False, None, float(np.hypot(*shift)),
                      float(tolerance * np.hypot(*pooled_se)), pixels,
                      f"information, not a test: {why}",
                      {"ncc_expected": expected.tolist(), "ncc_mean": pooled.tolist(), "shift": shift.tolist(),
                       "share_outside": float(outside.mean())})


def check_dichromatic(images: NDArrayFloat, labels: NDArrayFloat, body: NDArrayFloat, light: NDArrayFloat,
                      usable: NDArrayFloat | None = None, bias: NDArrayFloat | None = None,
                      floor: NDArrayFloat | None = None) -> LimitCheck:
    """
    The dichromatic model [Shafer1985]: each skin pixel lies in the plane of the body and the light colour.

    A coated (roughplastic) surface under one light reflects
    ``m_b(geometry) ρ(λ) E(λ) + m_s(geometry) F E(λ)`` with a spectrally flat
    Fresnel term (one refractive index), so each pixel's channels are a
    non-negative mix of the body colour ``∫ ρ E x_k`` and the light's colour
    ``∫ E x_k``: at zero distance from their plane. ``body`` and ``light`` are
    those colours balanced as the images are (their scale is free); ``usable``,
    ``bias`` and ``floor`` as :func:`check_shading`'s. Tested per
    interior skin pixel and pooled; ``specular_t`` (the largest significance of a
    pixel's light-colour component) shows that highlights were there to test.
    """
    images = np.asarray(images, dtype=np.float64)
    k = images.shape[0]
    normal = np.cross(body, light)
    normal = normal / np.linalg.norm(normal)
    skin = interior(labels, LABEL_SKIN) if usable is None else interior(labels, LABEL_SKIN) & usable
    pixels = int(skin.sum())
    if pixels < PIXELS_MIN:
        return LimitCheck("dichromatic_plane", True, None, None, None, pixels,
                          f"only {pixels} interior skin pixels: render larger")
    values = images[:, skin]
    distance = values @ normal
    mean = distance.mean(axis=0)
    error = distance.std(axis=0, ddof=1) / np.sqrt(k)
    scale = np.linalg.norm(values.mean(axis=0), axis=-1)
    systematic, least = _sensor(None if bias is None else bias[skin], None if floor is None else floor[skin],
                                None, normal)
    error = np.maximum(error, least)
    tests = mean.size + 1
    t_pixel = _ratio(np.maximum(np.abs(mean) - systematic, 0.0), np.hypot(error, FLOAT32_FLOOR * scale))
    pooled = distance.mean(axis=1)  # over the pixels, per replicate
    pooled_error = max(pooled.std(ddof=1) / np.sqrt(k), float(np.sqrt(np.sum(np.square(least)))) / pixels)
    t_pooled = float(_ratio(max(abs(pooled.mean()) - np.mean(systematic), 0.0),
                            np.hypot(pooled_error, FLOAT32_FLOOR * scale.mean())))
    basis = np.linalg.pinv(np.stack([body, light], axis=1))  # (2, 3): channels -> (m_b, m_s)
    specular = values @ basis[1]
    spread = specular.std(axis=0, ddof=1) / np.sqrt(k)
    shown = spread > 0  # shadowed pixels are exactly black
    specular_t = float((specular.mean(axis=0)[shown] / spread[shown]).max()) if shown.any() else 0.0
    statistic = float(max(t_pixel.max(), t_pooled))
    tolerance = critical_t(tests, k)
    return LimitCheck("dichromatic_plane", True, statistic <= tolerance, statistic, tolerance, pixels,
                      "each skin pixel's distance from the plane of the skin's body colour and the light's "
                      "colour, and their mean (one light, a coat of one refractive index)",
                      {"worst_pixel_t": float(t_pixel.max()), "pooled_t": float(t_pooled),
                       "specular_t": specular_t, "highlights": specular_t > tolerance})


def check_furnace(radiance: NDArrayFloat, labels: NDArrayFloat, expected: NDArrayFloat) -> LimitCheck:
    """
    White furnace: a head of reflectance 1 (both sides) in a uniform sky of radiance ``L`` returns ``L``.

    The radiance leaving every surface is ``L`` (the fixed point of
    ``L_o = ∫ ρ/π L_i cos`` with ``ρ = 1`` and ``L_i = L`` from every
    direction), so with every bounce every pixel, the concavities included,
    reads ``∫ L x_k dλ``. Tested per pixel and channel and on the head's mean.
    """
    radiance = np.asarray(radiance, dtype=np.float64)
    k = radiance.shape[0]
    head = labels == LABEL_SKIN
    mean = radiance.mean(axis=0)
    error = radiance.std(axis=0, ddof=1) / np.sqrt(k)
    tests = mean.size + 3
    t_pixel = _ratio(np.abs(mean - expected), np.hypot(error, FLOAT32_FLOOR * expected))
    pooled = radiance[:, head].mean(axis=1) if head.any() else radiance.reshape(k, -1, 3).mean(axis=1)
    pooled_error = pooled.std(axis=0, ddof=1) / np.sqrt(k)
    t_pooled = _ratio(np.abs(pooled.mean(axis=0) - expected), np.hypot(pooled_error, FLOAT32_FLOOR * expected))
    statistic = float(max(t_pixel.max(), t_pooled.max()))
    tolerance = critical_t(tests, k)
    return LimitCheck("white_furnace", True, statistic <= tolerance, statistic, tolerance, int(mean.shape[0] *
                      mean.shape[1]), "every pixel of a white head (reflectance 1, every bounce) in a uniform "
                      f"sky against the sky's radiance; the head covers {int(head.sum())} pixels",
                      {"worst_pixel_t": float(t_pixel.max()), "pooled_t": float(t_pooled.max()),
                       "head_rel_error": (pooled.mean(axis=0) / expected - 1).tolist()})


def check_sphere(cam: Camera | str, rho: NDArrayFloat, every: NDArrayFloat, one: NDArrayFloat) -> LimitCheck:
    """
    Closed sphere: interreflection's closed form, and how it saturates colour.

    A closed Lambertian sphere of reflectance ρ(λ) emitting E(λ) uniformly,
    seen from inside: by symmetry the radiance is the same everywhere and
    ``L = E + (ρ/π) ∫ L cos θ dω = E + ρ L``, so ``L = E / (1 − ρ)`` with every
    bounce (``every``: :func:`sphere_channels` at depth −1), ``E (1 + ρ)`` with
    one (``one``: depth 2). Both rendered NCCs (r, g) are tested against these;
    and the higher terms ρⁿ being ever more coloured, every bounce must move the
    chromaticity further from the light's than one bounce does
    (``saturation_t``, one-sided, must exceed the tolerance).
    """
    cam = camera(cam)
    lam, emission = sphere_emission()
    rho_fine = np.interp(lam, GRID_DEFAULT.wavelengths, rho)
    light = rg(channel_integral(cam, GRID_DEFAULT, lam, emission))
    tests = 2 * 2 + 1
    k = np.asarray(every).shape[0]
    tolerance = critical_t(tests, k)
    worst, distances = 0.0, []
    for samples, radiance in ((every, emission / (1 - rho_fine)), (one, emission * (1 + rho_fine))):
        expected = rg(channel_integral(cam, GRID_DEFAULT, lam, radiance))
        value, se = jackknife(samples, rg)
        worst = max(worst, float((np.abs(value - expected) / np.hypot(se, FLOAT32_FLOOR)).max()))
        distances.append(jackknife(samples, lambda m: np.linalg.norm(rg(m) - light, axis=-1)))
    (far, se_far), (near, se_near) = distances
    saturation_t = float((far - near) / np.hypot(se_far, se_near))
    passed = worst <= tolerance and saturation_t > tolerance
    return LimitCheck("closed_sphere", True, passed, worst, tolerance, 0,
                      "the NCC (r, g) of a closed emitting sphere of the skin's reflectance, every bounce "
                      "(E / (1 − ρ)) and one (E (1 + ρ)); every bounce must saturate the colour more",
                      {"saturation_t": saturation_t, "distance_from_light": [float(far), float(near)]})
