"""
Agreement of rendered values with analytic ones
===============================================

The two questions a validation asks of every rendered value (a patch channel's
mean, a gamut volume), each answered with a :class:`~skinrender.evaluation.verdict.Verdict`:

-   **within a tolerance?** (:func:`agreement`'s ``equivalence``): the error
    ``rendered − analytic`` gets a simultaneous upper confidence bound
    ``|error| + c·SE`` (one-sided Šidák over every value, Student t, family-wise
    confidence ``1 − α``, α = :data:`~skinrender.evaluation.verdict.ALPHA_EQUIVALENCE`).
    The check passes when every bound is at most the value's tolerance, fails
    when some value's lower bound is beyond it, and is inconclusive otherwise,
    with the samples per pixel expected to pass (``spp_needed``). A noisy
    render cannot pass by being noisy: its bounds are wide.
-   **any difference at all?** (``difference``): the largest
    ``|error beyond the float32 floor| / SE`` against the two-sided Šidák
    critical value of a family-wise false-alarm rate α
    (:data:`~skinrender.evaluation.verdict.ALPHA_DIFFERENCE`). Its pass only
    says no difference was detected; its false-alarm rate is measured by
    ``skinrender bench calibration``.

Both take each error as normal (Student t). Where an error is too skewed for
that (a heavy-tailed Monte Carlo estimate: the skewness of its mean beyond a
stated limit), its bound is distribution-free instead — Cantelli's one-sided
inequality ``P(X − μ ≥ kσ) ≤ 1 / (1 + k²)`` for the equivalence, Chebyshev's
``P(|X − μ| ≥ kσ) ≤ 1 / k²`` for the difference test, at the same Šidák level
— which needs the standard error alone.

Below that limit the equivalence's bound still carries the skewness: a mean
divided by its own sample standard error is skewed the other way (a sample
short of the rare large values has both a low mean and a small standard
error), and its one-sided quantile moves by ``g (2c² + 1) / 6`` standard errors
(``g`` the mean's skewness, ``c`` the normal quantile; the Edgeworth expansion
of the studentized mean, :cite:`Hall1992`). Each bound is widened by that
much, ``|e| + (c + g (2c² + 1) / 6)·SE``, with ``g`` taken
:data:`SKEW_SPREAD` standard errors (``√6 / n`` each, n pixels) above its
estimate's magnitude: the estimate is low exactly in the samples that lack the
rare large values. Measured (issue 36, ``tools/measure_coverage.py``): a
subsurface chart of two slabs at 16 spp (pixels' excess kurtosis up to 20)
covered a truth above its values in 92 of 100 seeds, three times over, against
the 95 % stated; with the widening 95–99 of 100 (docs/verdicts.md, "Heavy
tails"). The bounds are 5 % wider on 144-pixel patches, 10 % on 64-pixel ones.

A tolerance is relative: each channel's allowed ``|error|`` is ``tolerance ×
max(|analytic|, DARK_LEVEL × v)`` with ``v`` the white level of the values'
units (``scale``: a perfect white's brightest channel in the render, e.g.
:func:`~skinrender.rendering.validation.white_level`; 255 =
:data:`~skinrender.constants.CONSTANT_OUTPUT_SCALE` at p = c with the white
normalisation), so a channel darker than :data:`DARK_LEVEL` of white is held
to the absolute floor ``tolerance × DARK_LEVEL × v`` rather than to a relative
error of a near-zero value. The floor follows the white actually rendered: with
``--normalization none`` a white is a few output units, and a floor of 1 % of
255 there let a black patch's channel err by several times its value.

-   :data:`TOLERANCE_DEFAULT`, :data:`TOLERANCE_MIN`, :data:`DARK_LEVEL`, :func:`check_tolerance`,
    :func:`tolerance_scale`, :func:`agreement`.

Units: output units (255 for white at p = c) unless said; tolerances and
bounds relative (fractions).

References
----------
-   :cite:`Schuirmann1987`, :cite:`Sidak1967` : see :mod:`skinrender.evaluation.verdict`.
-   :cite:`Hall1992` : P. Hall (1992). The Bootstrap and Edgeworth Expansion. Springer, New York
    (the studentized mean's Edgeworth expansion, its one-sided quantiles: §2.6).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..constants import CONSTANT_OUTPUT_SCALE
from ..errors import SkinrenderError, flag_of
from ..evaluation.verdict import (ALPHA_DIFFERENCE, ALPHA_EQUIVALENCE, critical_z, difference, equivalence,
                                  samples_needed, sidak)
from ..hints import ArrayLike, NDArrayFloat

__all__ = ["TOLERANCE_DEFAULT", "TOLERANCE_MIN", "SKEW_SPREAD", "DARK_LEVEL", "check_tolerance", "tolerance_scale",
           "agreement"]

TOLERANCE_DEFAULT = 0.01
"""Default relative tolerance of ``validate``: 1 % of each lit channel. At the default 256 spp a Macbeth
chart's bound is ~0.05 % (measured, docs/verdicts.md), so a correct render passes with room; at 4 spp (bound
~6 %) it is inconclusive."""

SKEW_SPREAD = 2.0
"""Standard errors of its estimate (``√6 / n`` for the mean of ``n`` pixels) added to a value's skewness before
its equivalence bound is widened by it (module notes): with the estimate itself, a subsurface chart's coverage at
a known truth was 92–97 % over three sets of 100 seeds; with two standard errors 95–98 %, and every dark-channel
setting measured 96–99 % (docs/verdicts.md)."""

DARK_LEVEL = 0.01
"""A channel below this fraction of white (``v``: a perfect white's brightest channel, 255 output units at p = c
with the white normalisation) is dark: its tolerance is absolute, ``tolerance × DARK_LEVEL × v`` (2.55 ×
tolerance at v = 255)."""


TOLERANCE_MIN = 2.0**-24
"""Smallest relative tolerance, ≈ 6e-8: float32's unit round-off. Renders are float32, so a smaller relative error
cannot be resolved (and a tolerance of 5e-324 overflowed the bounds' ratios to infinity)."""


def check_tolerance(value, name: str = "tolerance") -> float:
    """
    A relative tolerance in [:data:`TOLERANCE_MIN`, 1), else a one-line :class:`SkinrenderError` naming ``name``.

    >>> check_tolerance("0.01")
    0.01
    >>> check_tolerance(5e-324, "--tolerance")
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: --tolerance must be a relative error in [5.96e-08, 1) ...
    """
    try:
        tolerance = float(value)
    except (TypeError, ValueError, OverflowError):
        tolerance = math.nan
    if isinstance(value, bool) or not (TOLERANCE_MIN <= tolerance < 1):
        raise SkinrenderError(f"{name} must be a relative error in [{TOLERANCE_MIN:.3g}, 1) (its lower end is "
                              f"float32's resolution: renders are float32), e.g. 0.01 for 1 %, got {value!r}",
                              role="tolerance", flag=flag_of(name))
    return tolerance


def tolerance_scale(analytic: ArrayLike, scale: float = CONSTANT_OUTPUT_SCALE) -> NDArrayFloat:
    """
    What a relative tolerance multiplies: ``max(|analytic|, DARK_LEVEL × scale)``, output units.

    >>> tolerance_scale([100.0, 0.5]).tolist()
    [100.0, 2.55]
    """
    return np.maximum(np.abs(np.asarray(analytic, dtype=np.float64)), DARK_LEVEL * scale)


def agreement(rendered: ArrayLike, analytic: ArrayLike, sigma: ArrayLike, tolerance: float, spp: int,
              dof: float | None = None, floor: ArrayLike = 0.0, alpha: float = ALPHA_EQUIVALENCE,
              alpha_difference: float = ALPHA_DIFFERENCE, what: str = "patch channel means",
              scale: float = CONSTANT_OUTPUT_SCALE, skewness: ArrayLike | None = None,
              skew_max: float | None = None) -> dict:
    """
    The equivalence and difference verdicts of rendered values against analytic ones.

    Parameters
    ----------
    rendered, analytic
        The values, any shape (output units, or any unit with ``scale`` in it).
    sigma
        Each rendered value's standard error (≥ 0), broadcast to ``rendered``.
    tolerance
        Relative tolerance in (0, 1) (module docstring: dark values get an absolute floor).
    spp
        Samples per pixel the values were rendered with (for ``spp_needed``).
    dof
        Degrees of freedom of the standard errors (Student t), ``None`` for normal.
    floor
        A known systematic allowance (the float32 floor), left out of the difference test only.
    what
        The values, in words, for the tests' statements.
    scale
        The white level ``v`` of the values' units (a perfect white's brightest channel; 255 output units at
        p = c with the white normalisation): a value below ``DARK_LEVEL × v`` is held to that absolute floor.
    skewness, skew_max
        Each error's skewness and the largest at which its normal law is trusted: a value beyond is held to
        distribution-free bounds (Cantelli's one-sided for the equivalence, Chebyshev's two-sided for the
        difference test, at the same Šidák level), which need only its standard error; a value within has its
        equivalence bound widened by its skewness (module notes).

    Returns
    -------
    dict
        ``equivalence`` and ``difference`` (:class:`~skinrender.evaluation.verdict.Verdict`; the
        equivalence's ``bound`` is the smallest relative tolerance that would pass and its details hold
        ``spp_needed``), ``error``, ``upper`` (the bound on ``|error|``), ``tolerance`` (allowed ``|error|``),
        ``relative_bound`` (``upper / scale``), ``z`` (``error / sigma``, 0 where σ = 0), ``shown_within``,
        ``shown_outside``, ``trusted`` (the normal law trusted), arrays shaped as ``rendered``; ``spp_needed``
        (``None`` after a fail).

    Examples
    --------
    >>> out = agreement([100.5, 50.0], [100.0, 50.0], [0.1, 0.1], 0.01, spp=64)
    >>> out["equivalence"].outcome, out["difference"].outcome, round(out["equivalence"].bound, 4)
    ('pass', 'fail', 0.007)
    """

    tolerance = check_tolerance(tolerance)
    r, a = np.asarray(rendered, dtype=np.float64), np.asarray(analytic, dtype=np.float64)
    s = np.broadcast_to(np.asarray(sigma, dtype=np.float64), r.shape)
    error = r - a
    width = tolerance_scale(a, scale)
    allowed = tolerance * width
    trusted = np.ones(r.shape, dtype=bool)
    if skewness is not None and skew_max is not None:
        trusted = np.abs(np.broadcast_to(np.asarray(skewness, dtype=np.float64), r.shape)) <= skew_max
    # a value too skewed for the normal law gets a distribution-free bound instead: its standard error widened
    # so that the normal critical value gives Cantelli's (one-sided) and Chebyshev's (two-sided) at the same level
    widened = ~trusted
    m = max(r.size, 1)
    c = critical_z(alpha, m, sides=1, dof=dof)
    cantelli = math.sqrt(1 / sidak(alpha, m) - 1) / c
    chebyshev = math.sqrt(1 / sidak(alpha_difference, m)) / critical_z(alpha_difference, m, sides=2, dof=dof)
    # a trusted value's bound moved by its skewness (the studentized mean's one-sided quantile, module notes), the
    # skewness taken SKEW_SPREAD standard errors (√6 / n each, the mean of n draws) above its estimate
    g = np.zeros(r.shape)
    if skewness is not None:
        spread = SKEW_SPREAD * math.sqrt(6.0) / (dof + 1.0) if dof is not None and np.isfinite(dof) else 0.0
        g = np.abs(np.broadcast_to(np.asarray(skewness, dtype=np.float64), r.shape)) + spread
    hall = 1.0 + np.where(widened, 0.0, g) * (2 * c**2 + 1) / (6 * c)
    bounded = np.where(widened, s * cantelli, s * hall)  # the standard error each bound takes
    verdict, rows = equivalence(error, bounded, allowed, alpha, dof, "equivalence", scale=width)
    statement = (f"{what}: |rendered − analytic| + c·SE ≤ {tolerance:g} × max(|analytic|, "
                 f"{DARK_LEVEL * scale:g}) for every value; {verdict.test}")
    note = ""
    if skewness is not None:
        statement += (f"; each bound widened by its mean's skewness g ({SKEW_SPREAD:g} standard errors above its "
                      "estimate), "
                      f"c → c + g(2c² + 1)/6 (largest × {float(np.max(hall, initial=1.0)):.3g})")
    if np.any(widened):
        count = int(np.sum(widened))
        note = (f"{count} value{'s' * (count > 1)} too skewed for the normal law (skewness > {skew_max:g}) held to "
                "distribution-free bounds")
        statement += (f"; a value whose error's skewness exceeds {skew_max:g} is held to Cantelli's bound "
                      f"(c × {cantelli:.3g})")
        verdict = replace(verdict, reason=f"{verdict.reason}; {note}")
    needed = None
    if verdict.outcome in ("pass", "inconclusive"):
        needed = samples_needed(spp, error, bounded, allowed, alpha, dof, shrinking=True)
    verdict = replace(verdict, test=statement, tolerance=tolerance,
                      details={**verdict.details, "spp_needed": needed, "tolerance_relative": tolerance,
                               "dark_level": DARK_LEVEL * scale, "skewed": int(np.sum(widened)),
                               "skew_widening_max": float(np.max(hall, initial=1.0))})
    beyond = np.sign(error) * np.maximum(np.abs(error) - np.broadcast_to(np.asarray(floor, dtype=np.float64),
                                                                          r.shape), 0.0)
    test = difference(beyond, np.where(widened, s * chebyshev, s), alpha_difference, dof, "difference")
    test = replace(test, test=f"{what}: rendered − analytic beyond the float32 floor, over its SE; {test.test}"
                   + (f"; a value too skewed for the normal law is held to Chebyshev's bound (c × {chebyshev:.3g})"
                      if np.any(widened) else ""),
                   reason=test.reason + (f"; {note}" if note else ""))
    z = np.divide(error, s, out=np.zeros_like(error), where=s > 0)
    return {"equivalence": verdict, "difference": test, "error": error, "upper": rows.get("upper", error),
            "tolerance": allowed, "relative_bound": rows.get("upper", error) / width, "z": z,
            "shown_within": rows.get("shown_within"), "shown_outside": rows.get("shown_outside"),
            "trusted": trusted, "spp_needed": needed}

