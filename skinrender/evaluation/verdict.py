"""
Verdicts
========

Every statistical check of the package says what it showed, in one shape:
``pass``, ``fail``, ``inconclusive`` or ``not_applicable``, with the bound
it reached, the tolerance it was held to and its false-alarm rate α.

Two kinds of test give verdicts:

-   **Equivalence** (:func:`equivalence`): "is the error within a
    tolerance?" Each value's error gets a simultaneous (Šidák) confidence
    interval at family-wise confidence ``1 − α``. The check *passes* when every
    interval lies inside ``±tolerance`` (the error is *shown* within it),
    *fails* when some interval lies wholly outside (some error is *shown*
    beyond it) and is *inconclusive* otherwise: more samples are needed. A
    noisy render can therefore never pass by being noisy.
-   **Difference** (:func:`difference`): "is there any error at all?" The
    largest ``|deviation| / standard error`` against the Šidák critical value
    of a family-wise α. Its *pass* only means "no difference detected"; its
    false-alarm rate is α, which :func:`binomial_interval` lets a benchmark
    check over many seeds.

-   :data:`OUTCOMES`, :data:`EXIT_STATUS`; :class:`Verdict`; :func:`combine`.
-   :func:`sidak`, :func:`critical_z`, :func:`equivalence`, :func:`difference`,
    :func:`samples_needed`, :func:`binomial_interval`.

Units are those of the values tested (output units, NCC fractions, …); α and
confidences are probabilities.

References
----------
-   :cite:`Sidak1967` : Z. Šidák (1967). Rectangular confidence regions for
    the means of multivariate normal distributions. J. Am. Stat. Assoc. 62,
    626–633.
-   :cite:`Schuirmann1987` : D. J. Schuirmann (1987). A comparison of the two
    one-sided tests procedure and the power approach for assessing the
    equivalence of average bioavailability. J. Pharmacokinet. Biopharm. 15,
    657–680.
-   :cite:`Clopper1934` : C. J. Clopper, E. S. Pearson (1934). The use of
    confidence or fiducial limits illustrated in the case of the binomial.
    Biometrika 26, 404–413.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import SkinrenderError
from ..hints import ArrayLike

__all__ = ["OUTCOMES", "EXIT_STATUS", "ALPHA_EQUIVALENCE", "ALPHA_DIFFERENCE", "Verdict", "combine", "Combined", "sidak",
           "critical_z", "equivalence", "difference", "samples_needed", "binomial_interval"]

OUTCOMES = {
    "pass": "shown to hold: every value within its tolerance (equivalence), or no difference detected (difference)",
    "fail": "shown not to hold: some value beyond its tolerance, or a difference detected at the stated α",
    "inconclusive": "the samples cannot tell: some confidence interval straddles the tolerance",
    "not_applicable": "nothing to test here (the reason says why)",
}
"""The outcomes of a check, name → meaning."""

EXIT_STATUS = {"pass": 0, "not_applicable": 0, "fail": 1, "inconclusive": 3}
"""The command line's exit status for a verdict (2 stays a refused input, 130 an interrupt)."""

ALPHA_EQUIVALENCE = 0.05
"""Default family-wise α of equivalence checks: every bound holds together at 95 % confidence."""

ALPHA_DIFFERENCE = 0.01
"""Default family-wise false-alarm rate of difference checks."""


@dataclass(frozen=True)
class Verdict:
    """
    What one statistical check showed.

    Attributes
    ----------
    name
        The check (``equivalence``, ``shading_cancels``, …).
    outcome
        A key of :data:`OUTCOMES`.
    alpha
        Family-wise error rate the check was run at.
    test
        What was tested, in words (the statistic, its law, the correction).
    statistic
        Equivalence: the largest upper confidence bound of ``|error| / tolerance``; difference: the
        largest ``|deviation| / standard error``. ``None`` when nothing was tested.
    threshold
        What the statistic is compared with (1 for equivalence, the critical value for difference).
    bound
        Equivalence: the smallest tolerance that would pass, in the tolerance's own units (relative
        where the tolerance is relative); ``None`` where not defined.
    tolerance
        The tolerance held to (``None`` for a difference test).
    reason
        Why the outcome, in one line (always set for ``inconclusive`` and ``not_applicable``).
    details
        Further JSON-ready figures (counts, ``samples_needed``, the worst item).
    """

    name: str
    outcome: str
    alpha: float
    test: str
    statistic: float | None = None
    threshold: float | None = None
    bound: float | None = None
    tolerance: float | None = None
    reason: str = ""
    details: dict = field(default_factory=dict)

    def __post_init__(self):
        if self.outcome not in OUTCOMES:
            raise SkinrenderError(f"verdict outcome must be one of {', '.join(OUTCOMES)}, got {self.outcome!r}")

    @property
    def passed(self) -> bool | None:
        """``True`` for pass, ``False`` for fail, ``None`` for inconclusive or not applicable."""
        return {"pass": True, "fail": False}.get(self.outcome)

    @property
    def exit_status(self) -> int:
        """:data:`EXIT_STATUS` of the outcome."""
        return EXIT_STATUS[self.outcome]

    def summary(self) -> dict:
        """
        What a result's JSON document says of its verdict: ``verdict`` (the outcome) and ``exit_status``.

        >>> Verdict("a", "fail", 0.01, "z").summary()
        {'verdict': 'fail', 'exit_status': 1}
        """
        return {"verdict": self.outcome, "exit_status": EXIT_STATUS[self.outcome]}

    def document(self) -> dict:
        """The JSON form: every attribute, the details merged in."""
        return {"name": self.name, "verdict": self.outcome, "passed": self.passed, "alpha": self.alpha,
                "test": self.test, "statistic": self.statistic, "threshold": self.threshold, "bound": self.bound,
                "tolerance": self.tolerance, "reason": self.reason, **self.details}


def combine(verdicts, name: str = "overall") -> Verdict:
    """
    One verdict of several: ``fail`` if any failed, else ``inconclusive`` if any was, else ``pass`` if any
    passed, else ``not_applicable``. α is the largest of the parts' (each part controls its own).

    Examples
    --------
    >>> a = Verdict("a", "pass", 0.01, "z")
    >>> b = Verdict("b", "inconclusive", 0.05, "TOST", reason="too few samples")
    >>> combine([a, b]).outcome
    'inconclusive'
    >>> combine([]).outcome
    'not_applicable'
    """

    verdicts = list(verdicts)
    for outcome in ("fail", "inconclusive", "pass"):
        which = [v for v in verdicts if v.outcome == outcome]
        if which:
            reason = "; ".join(f"{v.name}: {v.reason or v.outcome}" for v in which)
            return Verdict(name, outcome, max(v.alpha for v in verdicts), "every check's own", reason=reason)
    return Verdict(name, "not_applicable", max((v.alpha for v in verdicts), default=0.0), "every check's own",
                   reason="no check applies" if not verdicts else "; ".join(v.reason for v in verdicts))


class Combined:
    """
    A result whose ``verdicts`` (its checks', a list of :class:`Verdict`) give its ``verdict``: them combined
    (:func:`combine`) under the class's :attr:`VERDICT_NAME`.
    """

    VERDICT_NAME = "overall"
    """The combined verdict's name."""

    @property
    def verdict(self) -> Verdict:
        """Every check's verdict combined (:func:`combine`)."""
        return combine(self.verdicts, self.VERDICT_NAME)


def _check_alpha(alpha: float) -> float:
    if not (isinstance(alpha, (int, float, np.floating)) and 0 < alpha < 1):
        raise SkinrenderError(f"alpha must be a probability in (0, 1), got {alpha!r}")
    return float(alpha)


def sidak(alpha: float, tests: int) -> float:
    """
    The per-test level that keeps ``tests`` independent tests' family-wise rate at ``alpha``:
    ``1 − (1 − α)^(1/m)``.

    >>> round(sidak(0.05, 1), 12)
    0.05
    >>> sidak(0.01, 100) > 0.01 / 100  # a little less strict than Bonferroni
    True
    """
    alpha = _check_alpha(alpha)
    return -math.expm1(math.log1p(-alpha) / max(int(tests), 1))


def critical_z(alpha: float, tests: int = 1, sides: int = 2, dof: float | None = None) -> float:
    """
    The critical value of ``tests`` standard-normal (or Student-t with ``dof`` degrees of freedom)
    statistics at family-wise ``alpha`` (Šidák), ``sides`` 1 or 2.

    >>> round(critical_z(0.05, 1, sides=2), 3)
    1.96
    >>> round(critical_z(0.05, 1, sides=1), 3)
    1.645
    """
    level = sidak(alpha, tests) / (2 if sides == 2 else 1)
    return _isf(level, None if dof is None else float(dof))


@functools.lru_cache(maxsize=1024)
def _isf(level: float, dof: float | None) -> float:
    """The standard normal's (or Student t's with ``dof`` degrees of freedom) upper ``level`` quantile, kept: a
    verdict over many seeds or draws asks for the same few (scipy's ``isf`` costs ~0.1 ms a call)."""
    from scipy import stats

    return float(stats.norm.isf(level) if dof is None else stats.t.isf(level, dof))


def equivalence(error: ArrayLike, standard_error: ArrayLike, tolerance: ArrayLike,
                alpha: float = ALPHA_EQUIVALENCE, dof: float | None = None, name: str = "equivalence",
                scale: ArrayLike | None = None) -> tuple[Verdict, dict]:
    """
    Whether every ``error`` is shown within ``±tolerance`` at family-wise confidence ``1 − α``.

    Each value gets the simultaneous interval ``error ± c · standard_error`` (``c`` the one-sided Šidák
    critical value over all values, normal or Student-t with ``dof``): as the two one-sided tests of
    :cite:`Schuirmann1987`, both ends inside ``±tolerance`` shows the value within it. The check passes
    when every value is shown within, fails when some value's whole interval lies beyond its tolerance,
    and is inconclusive otherwise.

    Parameters
    ----------
    error
        Measured − expected, any shape (same units as ``tolerance``).
    standard_error
        The error's standard error, broadcast to ``error`` (≥ 0).
    tolerance
        The allowed ``|error|``, broadcast to ``error`` (> 0).
    alpha
        Family-wise error rate.
    scale
        Divides every bound for the reported :attr:`Verdict.bound` (e.g. the expected values, so that the
        bound is relative); ``None``: ``tolerance`` itself, giving the bound in units of the tolerance.

    Returns
    -------
    (Verdict, dict)
        The verdict (``statistic`` the largest ``upper / tolerance``; ``bound`` the smallest tolerance, in
        ``scale``'s units, that would pass), and per value ``upper`` and ``lower`` (the bounds of
        ``|error|``), ``shown_within`` and ``shown_outside`` (booleans), arrays shaped as ``error``.

    Examples
    --------
    >>> v, _ = equivalence([0.01, -0.02], [0.01, 0.01], 0.1)
    >>> v.outcome, round(v.statistic, 3)
    ('pass', 0.395)
    >>> equivalence([0.5, 0.0], [0.01, 0.01], 0.1)[0].outcome
    'fail'
    >>> equivalence([0.0, 0.0], [1.0, 1.0], 0.1)[0].outcome
    'inconclusive'
    """

    e = np.asarray(error, dtype=np.float64)
    se = np.broadcast_to(np.asarray(standard_error, dtype=np.float64), e.shape)
    tol = np.broadcast_to(np.asarray(tolerance, dtype=np.float64), e.shape)
    if np.any(~np.isfinite(e)) or np.any(~np.isfinite(se)) or np.any(se < 0):
        raise SkinrenderError("equivalence: errors and standard errors must be finite (standard errors ≥ 0)")
    if np.any(~(tol > 0)):
        raise SkinrenderError("equivalence: tolerances must be > 0")
    c = critical_z(alpha, e.size, sides=1, dof=dof)
    upper = np.abs(e) + c * se
    lower = np.maximum(np.abs(e) - c * se, 0.0)
    within, outside = upper <= tol, lower > tol
    ratio = upper / tol
    worst = int(np.argmax(ratio)) if e.size else 0
    denominator = tol if scale is None else np.broadcast_to(np.abs(np.asarray(scale, dtype=np.float64)), e.shape)
    with np.errstate(divide="ignore", invalid="ignore"):
        relative = np.where(denominator > 0, upper / np.where(denominator > 0, denominator, 1), np.inf)
    bound = float(np.max(relative)) if e.size else None
    law = f"Student t, {dof:g} dof" if dof is not None else "normal"
    test = (f"equivalence (two one-sided tests): |error| + {c:.3g}·SE ≤ tolerance for all {e.size} values, "
            f"simultaneous {100 * (1 - alpha):g} % bounds (Šidák, {law})")
    if e.size == 0:
        return Verdict(name, "not_applicable", alpha, test, reason="no values to test"), {}
    if np.all(within):
        outcome, reason = "pass", f"every value shown within its tolerance (worst at {ratio.flat[worst]:.3g} of it)"
    elif np.any(outside):
        n = int(np.sum(outside))
        outcome, reason = "fail", f"{n} value{'s' if n > 1 else ''} shown beyond the tolerance"
    else:
        n = int(np.sum(~within))
        outcome, reason = "inconclusive", (f"{n} value{'s' if n > 1 else ''} neither shown within nor beyond the "
                                           "tolerance: more samples are needed")
    verdict = Verdict(name, outcome, alpha, test, float(np.max(ratio)), 1.0, bound,
                      float(np.max(tol)) if np.ptp(tol) == 0 else None, reason,
                      {"values": int(e.size), "shown_within": int(np.sum(within)),
                       "shown_outside": int(np.sum(outside)), "critical": c})
    return verdict, {"upper": upper, "lower": lower, "shown_within": within, "shown_outside": outside}


def difference(deviation: ArrayLike, standard_error: ArrayLike, alpha: float = ALPHA_DIFFERENCE,
               dof: float | ArrayLike | None = None, name: str = "difference") -> Verdict:
    """
    Whether any ``deviation`` differs from 0 beyond its noise, at family-wise false-alarm rate ``alpha``:
    the largest ``|deviation| / standard_error`` against the two-sided Šidák critical value (normal, or
    Student-t with ``dof`` degrees of freedom). Values with a zero standard error and zero deviation are exact
    and pass; a non-zero deviation with a zero standard error fails.

    ``dof`` may also give each value its own degrees of freedom (broadcast to ``deviation``; ``inf`` is
    normal), e.g. Welch's for differences of means estimated from samples of different sizes: each value is
    then held to its own critical value at the Šidák level, and ``statistic`` and ``threshold`` are those of
    the value nearest to, or furthest beyond, its own.

    Examples
    --------
    >>> difference([0.1, -0.2], [0.1, 0.1]).outcome
    'pass'
    >>> difference([1.0, 0.0], [0.1, 0.1]).outcome
    'fail'
    >>> v = difference([4.0, 4.0], [1.0, 1.0], dof=[3.0, 1e6])  # 4 SE: beyond the normal's 2.8, not t(3)'s
    >>> v.outcome, v.details["worst"], round(v.threshold, 2)
    ('fail', 1, 2.81)
    """

    d = np.asarray(deviation, dtype=np.float64)
    se = np.broadcast_to(np.asarray(standard_error, dtype=np.float64), d.shape)
    if d.size == 0:
        return Verdict(name, "not_applicable", alpha, "z test", reason="no values to test")
    if np.any(~np.isfinite(d)) or np.any(~np.isfinite(se)) or np.any(se < 0):
        raise SkinrenderError("difference: deviations and standard errors must be finite (standard errors ≥ 0)")
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.where(se > 0, np.abs(d) / np.where(se > 0, se, 1), np.where(d == 0, 0.0, np.inf))
    if dof is not None and np.ndim(dof) > 0:
        from scipy import stats

        dofs = np.broadcast_to(np.asarray(dof, dtype=np.float64), d.shape)
        if np.any(~(dofs > 0)):
            raise SkinrenderError("difference: degrees of freedom must be > 0")
        c = stats.t.isf(sidak(alpha, d.size) / 2, dofs)
        law = f"Student t, {np.min(dofs):.3g}–{np.max(dofs):.3g} dof per value"
    else:
        c = np.full(d.shape, critical_z(alpha, d.size, sides=2, dof=dof))
        law = f"Student t, {dof:g} dof" if dof is not None else "normal"
    ratio = z / c
    worst = int(np.argmax(ratio))
    statistic, threshold = float(z.flat[worst]), float(c.flat[worst])
    shown = f"{threshold:.3g}" if np.ptp(c) == 0 else f"its own critical value ({np.min(c):.3g}–{np.max(c):.3g})"
    test = f"difference: max |deviation| / SE ≤ {shown} over {d.size} values (Šidák, two-sided, {law})"
    if np.all(z <= c):
        return Verdict(name, "pass", alpha, test, statistic, threshold, reason="no difference detected",
                       details={"values": int(d.size), "worst": worst})
    return Verdict(name, "fail", alpha, test, statistic, threshold,
                   reason=f"a difference detected: {statistic:.3g} standard errors against {threshold:.3g}",
                   details={"values": int(d.size), "worst": worst})


def samples_needed(samples: int, error: ArrayLike, standard_error: ArrayLike, tolerance: ArrayLike,
                   alpha: float = ALPHA_EQUIVALENCE, dof: float | None = None, shrinking: bool = False) -> int | None:
    """
    The samples (e.g. spp) at which :func:`equivalence` is expected to pass, from a run at ``samples``:
    standard errors shrinking as ``1/√samples``, the measured errors taken as they are (a Monte Carlo
    error shrinks too, so this is conservative). ``None`` when no count can pass (some ``|error|`` is at
    or beyond its tolerance).

    ``shrinking``: the errors are themselves the noise of an unbiased estimator (a Monte Carlo render's),
    so they shrink with the standard errors and every bound ``|error| + c·SE`` falls as ``1/√samples``:
    ``samples · max((|error| + c·SE) / tolerance)²`` (an error beyond the tolerance is then taken for noise; a
    render with a real bias stays short of a pass at the count given), ``None`` only where that count is beyond
    any a float can hold (a tolerance of 5e-324, below every float's resolution).

    >>> samples_needed(16, [0.0], [0.1], 0.1)
    44
    >>> samples_needed(16, [0.2], [0.1], 0.1) is None
    True
    >>> samples_needed(16, [0.2], [0.1], 0.1, shrinking=True)
    213
    >>> samples_needed(16, [0.2], [0.1], 5e-324, shrinking=True) is None
    True
    """

    e = np.abs(np.asarray(error, dtype=np.float64))
    se = np.broadcast_to(np.asarray(standard_error, dtype=np.float64), e.shape)
    tol = np.broadcast_to(np.asarray(tolerance, dtype=np.float64), e.shape)
    c = critical_z(alpha, e.size, sides=1, dof=dof)
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        if shrinking:
            factor = np.max(((e + c * se) / tol) ** 2)
        elif np.any(e >= tol):
            return None
        else:
            factor = np.max((c * se / (tol - e)) ** 2)
        count = samples * factor
    if not math.isfinite(count):  # beyond any count: a tolerance below the floats' resolution
        return None
    return max(1, int(math.ceil(count)))


def binomial_interval(failures: int, trials: int, level: float = 0.95) -> tuple[float, float]:
    """
    The Clopper–Pearson interval of a rate from ``failures`` of ``trials`` :cite:`Clopper1934`: an observed
    false-alarm rate is consistent with a nominal α when α lies inside.

    >>> lo, hi = binomial_interval(2, 100)
    >>> round(lo, 4), round(hi, 4)
    (0.0024, 0.0704)
    """
    from scipy import stats

    if not (isinstance(trials, (int, np.integer)) and trials >= 1 and 0 <= failures <= trials):
        raise SkinrenderError(f"binomial_interval: need 0 ≤ failures ≤ trials, trials ≥ 1, got {failures}, {trials}")
    tail = (1 - level) / 2
    lo = 0.0 if failures == 0 else float(stats.beta.ppf(tail, failures, trials - failures + 1))
    hi = 1.0 if failures == trials else float(stats.beta.isf(tail, failures + 1, trials - failures))
    return lo, hi

