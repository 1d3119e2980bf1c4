"""
The photon transfer's verdict
=============================

Whether the figures :func:`~skinrender.studies.benchmarks.ptc.photon_transfer` measured agree with those the imager
states, as one difference test (:func:`~skinrender.evaluation.verdict.difference`), and how often it fails
where they do (its calibration over seeds).

-   :func:`ptc_verdict`: per tested figure and channel ``z = (fit − stated) / SE``; the largest ``|z|`` against the
    two-sided critical value of a family-wise α of 0.01 over the figures tested: exact for the fits' correlation
    within each channel (``result["correlation"]``), Šidák's where each channel tests one value.
-   :func:`false_alarm_rows`, :func:`estimate_ptc_seconds`: for
    :func:`~skinrender.studies.benchmarks.ptc.ptc_calibration`, ``seeds`` measurements of one render (the sensor noise's seed changes, the chart's
    render is shared: its Monte Carlo noise is a fixed pattern the two-frame differences cancel), the observed
    false-alarm rate with its Clopper–Pearson 95 % interval against α (``skinrender bench calibration --scene
    ptc``).

Tested: the conversion gain K (DN/e⁻) of each channel; the read noise (e⁻) where defined (σ_dark ≥ 0.5 DN);
the dark current (e⁻/s) where resolved. Information only: the saturation capacity (EMVA 1288 defines it as the
mean at the variance's peak, below the full well by construction: not an estimate of the stated full well) and
the linearity error (the imager states none; the model is linear below the well).

Units: those of the figures (DN/e⁻, e⁻, e⁻/s); z dimensionless; α and rates probabilities.

References
----------
-   :cite:`EMVA1288` : EMVA Standard 1288, release 4.0 (docs/references.md).
-   :cite:`Sidak1967`, :cite:`Clopper1934` : see :mod:`skinrender.evaluation.verdict`.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ...evaluation.verdict import ALPHA_DIFFERENCE, EXIT_STATUS, binomial_interval, difference

__all__ = ["TESTED", "INFORMATION_ONLY", "SECONDS_PER_MEASUREMENT", "estimate_ptc_seconds", "ptc_verdict",
           "false_alarm_rows"]

TESTED = ("gain_dn_per_e", "read_noise_e", "dark_current_e_per_s")
"""The figures tested against the imager's stated values (each per channel, where reported)."""

INFORMATION_ONLY = {
    "full_well_e": "EMVA 1288's saturation capacity is the mean at the variance's peak, where part of the pixels "
                   "already fill: below the full well by construction, so not an estimate of the stated figure",
    "linearity_error": "the imager states no linearity error (its model is linear below the well); reported, not "
                       "tested",
}
"""Figures reported without a test, and why."""


def ptc_verdict(result: dict, alpha: float = ALPHA_DIFFERENCE) -> dict:
    """
    The difference test of a photon transfer ``result`` (``gain_dn_per_e``, ``read_noise_e``,
    ``dark_current_e_per_s``, ``standard_error``, ``stated``): per figure of :data:`TESTED` and channel the
    deviation ``fit − stated`` over its standard error, ``z``; ``fail`` when the largest ``|z|`` exceeds the
    two-sided critical value of family-wise ``alpha`` over the values tested (normal law: each standard error is
    propagated from thousands of pixel pairs' own moments, so its own error is a few percent; measured over
    seeds, z is normal). The values are correlated within a channel (the read noise and the dark current divide
    by the gain): the critical value is the exact one for ``result["correlation"]`` where present, lower than
    Šidák's for independent values.

    Returns
    -------
    dict
        ``z`` (per figure, per channel, ``None`` where not tested), ``checks`` (``{"fits": Verdict document}``:
        the test in words, statistic, threshold, α, the worst value's figure and channel), ``verdict``,
        ``passed``, ``exit_status`` and ``information_only`` (figure → why it is not tested).

    Examples
    --------
    >>> doc = {"gain_dn_per_e": [0.1, 0.1, 0.1], "read_noise_e": [None] * 3, "dark_current_e_per_s": [None] * 3,
    ...        "standard_error": {"gain_dn_per_e": [0.001] * 3, "read_noise_e": [None] * 3,
    ...                           "dark_current_e_per_s": [None] * 3},
    ...        "stated": {"gain_dn_per_e": 0.101, "read_noise_e": 5.0, "dark_current_e_per_s": 1.0}}
    >>> v = ptc_verdict(doc)
    >>> v["verdict"], v["z"]["gain_dn_per_e"]
    ('pass', [-1.0, -1.0, -1.0])
    >>> doc["stated"]["gain_dn_per_e"] = 0.11  # 10 % off: ten standard errors
    >>> ptc_verdict(doc)["exit_status"]
    1
    """
    deviations, errors, names, z = [], [], [], {}
    for figure in TESTED:
        z[figure] = []
        for channel, (fit, se) in zip("RGB", zip(result[figure], result["standard_error"][figure])):
            if fit is None or se is None:
                z[figure].append(None)
                continue
            deviation = fit - result["stated"][figure]
            deviations.append(deviation)
            errors.append(se)
            names.append(f"{figure} {channel}")
            z[figure].append(float(deviation / se) if se > 0 else None)
    verdict = difference(deviations, errors, alpha=alpha, name="fits")
    blocks = _blocks(result, names)
    if verdict.statistic is not None and any(len(b) > 1 for b in blocks):
        verdict = _correlated(verdict, blocks, alpha, len(names))
    details = {"tested": names}
    if verdict.statistic is not None:
        details["worst_figure"] = names[verdict.details["worst"]]
    delta = ", the read noise's by the delta method" if any(n.startswith("read_noise_e") for n in names) else ""
    test = (f"{verdict.test}; each value (fit − stated) / SE of {', '.join(names)}; SE from each point's sampling "
            f"variance (the pixel pairs' fourth moments) through the least-squares fits{delta}" if names
            else verdict.test)
    document = {**verdict.document(), "test": test, **details}
    return {"z": z, "checks": {"fits": document}, "verdict": verdict.outcome, "passed": verdict.passed,
            "exit_status": EXIT_STATUS[verdict.outcome], "information_only": dict(INFORMATION_ONLY)}


CORRELATED_DRAWS = 1 << 18
"""Normal draws (a fixed seed: the same critical value every time) that give the family's critical value where the
fits are correlated: the probability that a channel's largest ``|z|`` exceeds c is known to ±4 % of its 0.0033 (binomial)."""

_PAIRS = {("gain_dn_per_e", "read_noise_e"): "gain_read_noise", ("gain_dn_per_e", "dark_current_e_per_s"):
          "gain_dark_current", ("read_noise_e", "dark_current_e_per_s"): "read_noise_dark_current"}


def _blocks(result: dict, names: list[str]) -> list[np.ndarray]:
    """Per channel, the correlation matrix of its tested figures' z (from ``result["correlation"]``; a figure
    without one is taken as independent)."""
    correlation, blocks = result.get("correlation", {}), []
    for k, channel in enumerate("RGB"):
        figures = [n.split()[0] for n in names if n.split()[1] == channel]
        block = np.eye(len(figures))
        for i, a in enumerate(figures):
            for j, b in enumerate(figures[:i]):
                r = correlation.get(_PAIRS.get((b, a)) or _PAIRS.get((a, b)) or "", [None] * 3)[k]
                block[i, j] = block[j, i] = 0.0 if r is None else r
        if len(figures):
            blocks.append(block)
    return blocks


@lru_cache(maxsize=4)
def _draws(dimension: int) -> np.ndarray:
    """:data:`CORRELATED_DRAWS` standard normal draws of ``dimension`` values (a fixed seed)."""
    return np.random.default_rng([0x5EED, dimension]).standard_normal((CORRELATED_DRAWS, dimension))


@lru_cache(maxsize=256)
def _block_maxima(block: tuple) -> np.ndarray:
    """The sorted largest ``|z|`` of the fixed draws with this correlation (a tuple of rows)."""
    w, v = np.linalg.eigh(np.array(block))
    return np.sort(np.abs(_draws(len(block)) @ (v * np.sqrt(np.clip(w, 0, None))).T).max(axis=1))


def _critical(blocks: list[np.ndarray], alpha: float) -> float:
    """c with P(every ``|z|`` ≤ c) = 1 − α for z normal, independent between the blocks, each block's correlation as
    given, rounded to 0.01 (:data:`CORRELATED_DRAWS` fixed draws per block of two or more)."""
    from scipy.stats import norm

    maxima = [None if len(b) == 1 else _block_maxima(tuple(map(tuple, np.round(b, 2)))) for b in blocks]

    def covered(c: float) -> float:
        return float(np.prod([1 - 2 * norm.sf(c) if m is None else np.searchsorted(m, c, side="right") / m.size
                              for m in maxima]))

    low, high = 0.0, 10.0
    for _ in range(40):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if covered(middle) < 1 - alpha else (low, middle)
    return high


def _correlated(verdict, blocks: list[np.ndarray], alpha: float, values: int):
    """``verdict`` held to the exact critical value of its correlated values instead of Šidák's (which assumes them
    independent: the read noise and the dark current divide by the gain, correlations to ±0.96)."""
    from dataclasses import replace

    c = _critical(blocks, alpha)
    test = (f"difference: max |deviation| / SE ≤ {c:.3g} over {values} values (two-sided, normal; the family-wise "
            f"α exact for the fits' correlation within each channel, by {CORRELATED_DRAWS} fixed normal draws; "
            f"Šidák's, for independent values, would be {verdict.threshold:.3g})")
    if verdict.statistic <= c:
        return replace(verdict, outcome="pass", threshold=c, test=test, reason="no difference detected")
    return replace(verdict, outcome="fail", threshold=c, test=test,
                   reason=f"a difference detected: {verdict.statistic:.3g} standard errors against {c:.3g}")


SECONDS_PER_MEASUREMENT = 0.6
"""One measurement of the 24-point series beside the shared render, s (0.19–0.68 measured on a 2-core VM under a
load of 2–10: 400 seeds took 169 s for the imx174, 270 s for the icx418)."""


def estimate_ptc_seconds(seeds: int, points: int = 24, spp: int = 64) -> float:
    """Wall time of :func:`ptc_calibration`, s: the render (64 × 64 pixels) and its compilation once, then ``seeds``
    measurements of ``points`` exposures.

    >>> round(estimate_ptc_seconds(400))
    245
    """
    from .calibration import estimate_seconds

    return estimate_seconds(1, 64 * 64, spp, renders=1) + seeds * SECONDS_PER_MEASUREMENT * points / 24


def false_alarm_rows(runs: list[dict], alpha: float = ALPHA_DIFFERENCE) -> list[dict]:
    """Over ``runs`` (``[{verdict, threshold, tested, z}]``, one per seed of a correct imager), the family's and each
    figure's observed rate against its nominal one (a figure's: its channels' share of the
    family, 1 − (1 − α_Šidák)^channels, averaged over the runs: a dark current is tested only where resolved), with
    Clopper–Pearson 95 % intervals."""

    from scipy.stats import norm

    def share(run: dict, figure: str) -> float:  # the figure's nominal rate in one run: its channels tested
        channels = sum(name.startswith(figure + " ") for name in run["tested"])
        return 1 - (1 - 2 * norm.sf(run["threshold"])) ** channels if channels else 0.0

    nominal = {"fits": alpha, **{figure: float(np.mean([share(run, figure) for run in runs])) for figure in TESTED
                                 if any(share(run, figure) > 0 for run in runs)}}
    rows = []
    for name, rate in nominal.items():
        if name == "fits":
            failures = sum(run["verdict"] == "fail" for run in runs)
        else:
            failures = sum(any(abs(z) > run["threshold"] for z in run["z"][name] if z is not None) for run in runs)
        lo, hi = binomial_interval(failures, len(runs))
        rows.append({"name": name, "nominal_alpha": rate, "nominal": "equal to", "failures": failures,
                     "seeds": len(runs), "rate": failures / len(runs), "interval": [lo, hi],
                     "consistent": bool(lo <= rate <= hi),
                     "outcomes": {"fail": failures, "pass": len(runs) - failures}})
    return rows
