"""
Analytic limits of face renders
===============================

Where the analytic camera model holds exactly on a rendered face, and the
statistics that check it (``skinrender validate face`` and the tests share
them). Every check works on ``K`` replicate renders (independent seeds): a
statistic of their mean is compared with its analytic value against its own
measured noise (the spread of the replicates, Student's t with ``K − 1``
degrees of freedom), the critical value Šidák-corrected for the number of
values tested, so that a correct renderer fails a check with probability
:data:`ALPHA`.

-   :func:`check_shading` (``direct``), :func:`check_dichromatic` (``sheen``) [Shafer1985];
    the scene-free limits' checks are in :mod:`skinrender.rendering.face.limit_scenes`, and
    ``eq4_shift`` (Eq. 4's error against a detection budget) in :mod:`skinrender.rendering.face.shift`.
-   :func:`critical_t`, :func:`jackknife`, :func:`rounding_bias`, :func:`rg`; :class:`LimitCheck`, a result
    (its :attr:`~LimitCheck.verdict`, a :class:`~skinrender.evaluation.verdict.Verdict`);
    :func:`two_part`, the verdict of a check made of a per-pixel and a pooled test;
    :func:`sphere_emission`, the closed sphere's emission.

The tests
---------
Each check of an exact limit is a *difference* test made of two parts, each
with its own α, :data:`ALPHA_PART` (their family-wise rate is :data:`ALPHA`):

-   **per pixel**: the largest ``|deviation| / standard error`` over every
    value tested (pixels × components) against the two-sided Šidák critical
    value of Student's t with ``K − 1`` degrees of freedom;
-   **pooled**: the same for the sum (or mean) over the pixels, per replicate
    (a bias too small for any one pixel, in one direction, shows there).

Every statistic is *linear* in the pixels' channels (a projection, a sum),
so its mean over the replicates is unbiased at any spp, and every interior
pixel of the region is tested: no pixel is chosen by its own noise (choosing
"lit" pixels by the replicates' own spread biased the pooled NCC at 4 spp per
replicate to t 4–13, measured: pixels whose dim channel happened to come out
high were let in more often). A check's ``statistic`` is the larger of the two
parts' ``|t| / critical``, its ``tolerance`` 1; each part's ``t`` and critical
value are in its details. Each standard error is the replicates' combined in
quadrature with the float32 floor (:data:`~skinrender.rendering.validation.FLOAT32_FLOOR`
of the value); through an image sensor a pixel's deviation may also use up the
bound of the quantisation's mean error (:func:`rounding_bias`), which is
subtracted from it first, and its standard error is taken no smaller than the
sensor model's. Each replicate needs :data:`SPP_REPLICATE_MIN` spp at least:
below it a replicate's pixel values are far from normal and the per-pixel
tails heavier than Student's (measured: 1.4× at t = 6 at 4 spp, 1.2× at 24).

Units: images in Eq. 4 output units; radiance in the specfilm's units;
temperatures K; NCC fractions.

References
----------
-   :cite:`Shafer1985` : S. A. Shafer (1985). Using color to separate
    reflection components. Color Research & Application 10(4), 210–218.
-   :cite:`Sidak1967` : see :mod:`skinrender.evaluation.verdict`.
-   :cite:`Efron1982` : B. Efron (1982). The Jackknife, the Bootstrap and
    Other Resampling Plans. SIAM, CBMS-NSF 38 (the jackknife's standard
    error and bias correction).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...evaluation.verdict import OUTCOMES, Verdict, critical_z, sidak
from ...hints import NDArrayFloat
from ...spectra import GRID_DEFAULT, WavelengthGrid, planck
from ..validation import FLOAT32_FLOOR
from .document import light_irradiance
from .labels import LABEL_SKIN, interior
from .scene import Light

__all__ = ["ALPHA", "ALPHA_PART", "REPLICATES", "SPP_REPLICATE_MIN", "PIXELS_MIN", "LimitCheck", "critical_t",
           "jackknife", "rg", "rounding_bias", "two_part", "check_shading", "check_dichromatic", "sphere_emission",
           "deviation_ratio"]

ALPHA = 0.01
"""Family-wise false-alarm rate of each check of an exact limit (its per-pixel and pooled parts together)."""

ALPHA_PART = sidak(ALPHA, 2)
"""False-alarm rate of each of a check's two parts, per pixel and pooled (Šidák: together :data:`ALPHA`)."""

REPLICATES = 12
"""Independent renders (seeds) per check: Student's t has 11 degrees of freedom."""

SPP_REPLICATE_MIN = 16
"""Fewest samples per pixel of one replicate: ``validate`` renders each replicate with at least this many."""

from ...evaluation.detection_verdict import PIXELS_MIN  # noqa: E402, F401 - one minimum for every check (re-exported)


def sphere_emission(grid: WavelengthGrid = GRID_DEFAULT) -> tuple[NDArrayFloat, NDArrayFloat]:
    """Wavelengths (nm) and the relative emission of the closed sphere: a 3000 K Planckian, peak 1."""
    lam = light_irradiance(Light(3000.0, 1.0), grid)[0]
    return lam, planck(lam, 3000.0) / planck(lam, 3000.0).max()


@dataclass(frozen=True)
class LimitCheck:
    """
    One analytic limit checked on replicate renders, and its verdict.

    Attributes
    ----------
    name
        ``shading_cancels``, ``dichromatic_plane``, ``white_furnace``, ``closed_sphere`` or ``eq4_shift``.
    applies
        Whether the check is a test at the level rendered (every check is, now; ``False`` marks a row given
        for information only).
    passed
        ``True`` (pass), ``False`` (fail) or ``None`` (inconclusive or not applicable: ``outcome`` says which).
    statistic, tolerance
        Difference tests: the largest ``|t| / critical`` over the check's parts, and 1. ``eq4_shift``: the shift
        of the skin's mean NCC (r, g) from Eq. 4's (Euclidean) and the detection budget it is held to.
    pixels
        Pixels tested.
    reason
        What was tested, or why not.
    details
        Further figures (JSON-ready).
    outcome
        A key of :data:`~skinrender.evaluation.verdict.OUTCOMES`; ``None``: from ``passed`` (``None`` →
        ``inconclusive``, or ``not_applicable`` for a row that does not apply).
    alpha
        The check's false-alarm rate (difference tests) or its confidence's complement (equivalence).
    test
        The test, in words.
    bound
        ``eq4_shift``: the upper confidence bound of the shift (the smallest budget that would pass); ``None``
        for difference tests.
    """

    name: str
    applies: bool
    passed: bool | None
    statistic: float | None
    tolerance: float | None
    pixels: int
    reason: str
    details: dict = field(default_factory=dict)
    outcome: str | None = None
    alpha: float = ALPHA
    test: str = ""
    bound: float | None = None

    def __post_init__(self):
        undecided = "inconclusive" if self.applies else "not_applicable"  # a row for information decides nothing
        outcome = self.outcome or {True: "pass", False: "fail"}.get(self.passed, undecided)
        if outcome not in OUTCOMES or {"pass": True, "fail": False}.get(outcome) != self.passed:
            raise ValueError(f"check {self.name}: outcome {self.outcome!r} does not go with passed {self.passed!r}")
        object.__setattr__(self, "outcome", outcome)

    @property
    def verdict(self) -> Verdict:
        """The check as a :class:`~skinrender.evaluation.verdict.Verdict` (``threshold``: the tolerance)."""
        equivalence = self.bound is not None
        return Verdict(self.name, self.outcome, self.alpha, self.test, self.statistic,
                       None if equivalence else self.tolerance, self.bound,
                       self.tolerance if equivalence else None, self.reason, {"pixels": self.pixels, **self.details})

    def document(self) -> dict:
        """The JSON row: ``name, applies, passed, verdict, alpha, test, statistic, tolerance, bound, pixels,
        reason`` and the details."""
        return {"name": self.name, "applies": self.applies, "passed": self.passed, "verdict": self.outcome,
                "alpha": self.alpha, "test": self.test, "statistic": self.statistic, "tolerance": self.tolerance,
                "bound": self.bound, "pixels": self.pixels, "reason": self.reason, **self.details}


def critical_t(tests: int, replicates: int = REPLICATES, alpha: float = ALPHA) -> float:
    """
    Two-sided Student-t critical value of ``tests`` independent tests at family-wise ``alpha`` (Šidák),
    ``replicates − 1`` degrees of freedom (:func:`skinrender.evaluation.verdict.critical_z`).

    Examples
    --------
    >>> round(critical_t(1, 12, 0.05), 3)  # one test, 11 degrees of freedom
    2.201
    >>> critical_t(1000) > critical_t(10)
    True
    """
    return critical_z(alpha, max(int(tests), 1), sides=2, dof=replicates - 1)


def jackknife(samples: NDArrayFloat, statistic, corrected: bool = False) -> tuple[NDArrayFloat, NDArrayFloat]:
    """
    ``statistic`` of the replicate mean and its jackknife standard error; replicates on axis 0.

    ``corrected``: the value less the jackknife's estimate of its bias, ``K θ − (K − 1) mean(θ₋ₖ)`` (for a
    non-linear statistic, a ratio: its ``O(1/K)`` bias removed) :cite:`Efron1982`.

    Examples
    --------
    >>> value, error = jackknife(np.array([1.0, 2.0, 3.0, 4.0]), lambda m: m)  # the mean: SE = s / √K
    >>> float(value), round(float(error), 4)
    (2.5, 0.6455)
    >>> round(float(jackknife(np.array([1.0, 2.0, 3.0, 4.0]), lambda m: m**2, corrected=True)[0]), 4)  # x̄² − s²/K
    5.8333
    """
    samples = np.asarray(samples, dtype=np.float64)
    k = samples.shape[0]
    total = samples.sum(axis=0)
    value = statistic(total / k)
    leave_out = np.array([statistic((total - s) / (k - 1)) for s in samples])
    error = np.sqrt((k - 1) / k * np.sum((leave_out - leave_out.mean(axis=0)) ** 2, axis=0))
    if corrected:
        value = k * value - (k - 1) * leave_out.mean(axis=0)
    return value, error


def rg(rgb: NDArrayFloat) -> NDArrayFloat:
    """
    NCC (r, g) of channels on the last axis (Eq. 2), for any sign (a mean of dark-subtracted frames may dip
    below 0); a zero sum gives (1/3, 1/3).

    >>> rg(np.array([2.0, 1.0, 1.0])).tolist()
    [0.5, 0.25]
    """
    rgb = np.asarray(rgb, dtype=np.float64)
    total = rgb.sum(axis=-1, keepdims=True)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(total != 0, rgb[..., :2] / np.where(total != 0, total, 1.0), 1.0 / 3.0)


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


def deviation_ratio(deviation: NDArrayFloat, error: NDArrayFloat) -> NDArrayFloat:
    """``deviation / error``, 0 where both are 0 (a shadowed pixel is exactly black in every replicate)."""
    deviation, error = np.broadcast_arrays(np.asarray(deviation, dtype=np.float64), error)
    out = np.where(deviation > 0, np.inf, 0.0)
    np.divide(deviation, error, out=out, where=error > 0)
    return out


def _sensor(bias, floor, weights) -> tuple:
    """A sensor's bound of the mean error and floor of the standard error, carried from the channels to a
    projection on ``weights`` (``(3,)`` or ``(3, m)``); zeros without a sensor."""
    if bias is None:
        return np.zeros(1), np.zeros(1)
    floor = np.zeros_like(bias) if floor is None else floor
    return bias @ np.abs(weights), np.sqrt(floor @ weights**2)


def _projected(values: NDArrayFloat, weights: NDArrayFloat, bias, floor, scale: NDArrayFloat) -> tuple:
    """
    Per pixel and pooled ``t`` of the projection of ``values`` ``(K, N, 3)`` on ``weights`` ``(3,)`` or
    ``(3, m)`` (expected 0): each pixel's ``|mean| − systematic`` over its standard error (floored by the
    sensor's and by float32's, relative to ``scale``, the pixels' sizes), and the same for the sum over the
    pixels, per replicate. Shapes ``(N, m)`` and ``(m,)``.
    """
    k = values.shape[0]
    weights = np.asarray(weights, dtype=np.float64).reshape(3, -1)
    projection = values @ weights
    mean = projection.mean(axis=0)
    systematic, least = (np.broadcast_to(part, mean.shape) for part in _sensor(bias, floor, weights))
    error = np.maximum(projection.std(axis=0, ddof=1) / np.sqrt(k), least)
    t_pixel = deviation_ratio(np.maximum(np.abs(mean) - systematic, 0.0), np.hypot(error, FLOAT32_FLOOR * scale[:, None]))
    total = projection.sum(axis=1)
    total_error = np.maximum(total.std(axis=0, ddof=1) / np.sqrt(k), np.sqrt(np.sum(least**2, axis=0)))
    t_pooled = deviation_ratio(np.maximum(np.abs(total.mean(axis=0)) - systematic.sum(axis=0), 0.0),
                      np.hypot(total_error, FLOAT32_FLOOR * scale.sum()))
    return t_pixel, t_pooled


def two_part(name: str, t_pixel: NDArrayFloat, t_pooled: NDArrayFloat, replicates: int, what: str,
             pooled_what: str) -> tuple[str, float, str, dict]:
    """
    The outcome (``pass``/``fail``), statistic (the larger ``|t| / critical``), test (in words) and details of a
    check made of a per-pixel and a pooled part, each at :data:`ALPHA_PART` (Šidák over its own values).

    Examples
    --------
    >>> outcome, statistic, test, details = two_part("x", np.zeros(100), np.array([5.0, 0.0]), 12, "v", "s")
    >>> outcome, round(statistic, 2), round(details["pooled_critical"], 2)
    ('fail', 1.28, 3.89)
    """
    t_pixel, t_pooled = np.asarray(t_pixel, dtype=np.float64), np.asarray(t_pooled, dtype=np.float64)
    dof = replicates - 1
    critical_pixel = critical_z(ALPHA_PART, max(t_pixel.size, 1), sides=2, dof=dof)
    critical_pooled = critical_z(ALPHA_PART, max(t_pooled.size, 1), sides=2, dof=dof)
    worst, pooled = float(t_pixel.max(initial=0.0)), float(t_pooled.max(initial=0.0))
    statistic = max(worst / critical_pixel, pooled / critical_pooled)
    test = (f"difference, two parts at α {ALPHA_PART:.4g} each ({ALPHA:g} together): per pixel, max |t| ≤ "
            f"{critical_pixel:.3g} over {t_pixel.size} values ({what}); pooled, max |t| ≤ {critical_pooled:.3g} over "
            f"{t_pooled.size} ({pooled_what}); Student t, {dof} dof, Šidák, two-sided")
    details = {"worst_pixel_t": worst, "pixel_critical": critical_pixel, "pooled_t": pooled,
               "pooled_critical": critical_pooled, "alpha_pixel": ALPHA_PART, "alpha_pooled": ALPHA_PART,
               "spp_replicate_min": SPP_REPLICATE_MIN}
    return ("pass" if statistic <= 1.0 else "fail"), statistic, test, details


def _orthogonal(colour: NDArrayFloat) -> NDArrayFloat:
    """Two orthonormal directions orthogonal to ``colour`` ``(3,)``, as columns ``(3, 2)``: the first also
    orthogonal to grey (a change of hue), the second a change of saturation."""
    c = np.asarray(colour, dtype=np.float64) / np.linalg.norm(colour)
    first = np.cross(c, np.ones(3))
    if np.linalg.norm(first) < 1e-12:  # a grey colour: any direction across it
        first = np.cross(c, [1.0, 0.0, 0.0])
    first /= np.linalg.norm(first)
    return np.stack([first, np.cross(c, first)], axis=1)


def check_shading(images: NDArrayFloat, labels: NDArrayFloat, expected: NDArrayFloat,
                  usable: NDArrayFloat | None = None, bias: NDArrayFloat | None = None,
                  floor: NDArrayFloat | None = None) -> LimitCheck:
    """
    Shading cancels in NCC: every skin pixel's colour is Eq. 4's, whatever its shading.

    Under Planckian light of one temperature with direct light only, a skin
    pixel's radiance is ``ρ(λ) E(λ) G`` with ``G`` the shading (cosine,
    distance, shadowing, the pixel's coverage, the share of each light)
    independent of λ, so its channels are ``G ∫ ρ E x_k``: a multiple of Eq. 4's
    colour ``C``, and its NCC is Eq. 4's. Tested on the two components of each
    interior skin pixel's channels orthogonal to ``C`` (zero in expectation,
    at any shading and any spp), per pixel and summed over the pixels.

    Parameters
    ----------
    images
        ``(K, height, width, 3)`` balanced replicate images, output units.
    labels
        ``(height, width)`` label image (1 skin).
    expected
        Eq. 4's colour of the skin, or its NCC ``[r, g, b]`` (its direction is what counts).
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
    expected = np.asarray(expected, dtype=np.float64)[:3]
    skin = interior(labels, LABEL_SKIN) if usable is None else interior(labels, LABEL_SKIN) & usable
    skin &= np.any(images != 0, axis=(0, -1))  # a pixel black in every replicate has nothing to test
    pixels = int(skin.sum())
    if pixels < PIXELS_MIN:
        return LimitCheck("shading_cancels", True, None, None, None, pixels,
                          f"only {pixels} skin pixels with light: render larger or with more light",
                          outcome="inconclusive", test="difference, per pixel and pooled (not run)")
    values = images[:, skin]
    weights = _orthogonal(expected)
    mean = values.mean(axis=0)
    t_pixel, t_pooled = _projected(values, weights, None if bias is None else bias[skin],
                                   None if floor is None else floor[skin], np.linalg.norm(mean, axis=-1))
    outcome, statistic, test, details = two_part(
        "shading_cancels", t_pixel, t_pooled, images.shape[0],
        "each pixel's channels projected on the two directions orthogonal to Eq. 4's colour",
        "the same summed over the pixels")
    shading = mean.sum(axis=-1)
    lit = shading[shading > 0]
    return LimitCheck("shading_cancels", True, outcome == "pass", statistic, 1.0, pixels,
                      "every interior skin pixel's colour against Eq. 4's (its two components across Eq. 4's colour, "
                      "zero whatever the shading), and their sum (direct light of one temperature: the shading "
                      "cancels in NCC)",
                      {**details, "ncc_expected": rg(expected).tolist(), "ncc_mean": rg(mean.sum(axis=0)).tolist(),
                       "shading_range": float(lit.max() / lit.min()) if lit.size else None},
                      outcome=outcome, test=test)


def check_dichromatic(images: NDArrayFloat, labels: NDArrayFloat, body: NDArrayFloat, light: NDArrayFloat,
                      usable: NDArrayFloat | None = None, bias: NDArrayFloat | None = None,
                      floor: NDArrayFloat | None = None) -> LimitCheck:
    """
    The dichromatic model [Shafer1985]: each skin pixel lies in the plane of the body and the light colour.

    A coated (roughplastic) surface under lights of one spectrum reflects
    ``m_b(geometry) ρ_b(λ) E(λ) + m_s(geometry) F E(λ)`` with a spectrally flat
    Fresnel term (one refractive index), so each pixel's channels are a
    non-negative mix of the body colour ``∫ ρ_b E x_k`` and the light's colour
    ``∫ E x_k``: at zero distance from their plane. ``body`` and ``light`` are
    those colours balanced as the images are (their scale is free); ``usable``,
    ``bias`` and ``floor`` as :func:`check_shading`'s. Tested per interior skin
    pixel and on their mean.

    Without a resolved highlight (no pixel whose light-colour component exceeds
    its noise at the per-pixel critical value, one-sided) the plane is not
    tested beyond the body colour: the check is ``not_applicable`` (unless it
    failed: pixels shown off the plane fail it, highlights or not).
    """
    images = np.asarray(images, dtype=np.float64)
    k = images.shape[0]
    normal = np.cross(body, light)
    normal = normal / np.linalg.norm(normal)
    skin = interior(labels, LABEL_SKIN) if usable is None else interior(labels, LABEL_SKIN) & usable
    pixels = int(skin.sum())
    if pixels < PIXELS_MIN:
        return LimitCheck("dichromatic_plane", True, None, None, None, pixels,
                          f"only {pixels} interior skin pixels: render larger", outcome="inconclusive",
                          test="difference, per pixel and pooled (not run)")
    values = images[:, skin]
    scale = np.linalg.norm(values.mean(axis=0), axis=-1)
    t_pixel, t_pooled = _projected(values, normal, None if bias is None else bias[skin],
                                   None if floor is None else floor[skin], scale)
    outcome, statistic, test, details = two_part(
        "dichromatic_plane", t_pixel, t_pooled, k, "each pixel's distance from the plane",
        "the distances summed over the pixels")
    basis = np.linalg.pinv(np.stack([body, light], axis=1))  # (2, 3): channels -> (m_b, m_s)
    specular = values @ basis[1]
    spread = specular.std(axis=0, ddof=1) / np.sqrt(k)
    shown = spread > 0  # shadowed pixels are exactly black
    specular_t = float((specular.mean(axis=0)[shown] / spread[shown]).max()) if shown.any() else 0.0
    highlight_critical = critical_z(ALPHA_PART, pixels, sides=1, dof=k - 1)
    highlights = specular_t > highlight_critical
    reason = ("each skin pixel's distance from the plane of the skin's body colour and the light's colour, and their "
              "sum (lights of one spectrum, a coat of one refractive index)")
    if outcome == "pass" and not highlights:
        outcome = "not_applicable"
        reason = (f"no highlight resolved (the largest light-colour component is {specular_t:.3g} standard errors, "
                  f"below {highlight_critical:.3g}): the plane is not tested beyond the body colour; render larger "
                  "or with more spp")
    return LimitCheck("dichromatic_plane", True, {"pass": True, "fail": False}.get(outcome), statistic, 1.0, pixels,
                      reason, {**details, "specular_t": specular_t, "highlight_critical": highlight_critical,
                               "highlights": bool(highlights)}, outcome=outcome, test=test)
