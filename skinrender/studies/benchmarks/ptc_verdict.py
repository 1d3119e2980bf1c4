"""
The photon transfer's verdict
=============================

Whether the figures :func:`~skinrender.studies.benchmarks.ptc.photon_transfer` measured agree with those the imager
states, as one difference test (:func:`~skinrender.evaluation.verdict.difference`), and how often it fails
where they do (its calibration over seeds).

-   :func:`ptc_verdict`: per tested figure and channel ``z = (fit − stated) / SE``; the largest ``|z|`` against the
    two-sided Šidák critical value of a family-wise α of 0.01 over the figures tested.
-   :func:`ptc_calibration`: ``seeds`` measurements of one render (the sensor noise's seed changes, the chart's
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

import time
from collections.abc import Callable

import numpy as np

from ...evaluation.verdict import ALPHA_DIFFERENCE, EXIT_STATUS, binomial_interval, difference, sidak

__all__ = ["TESTED", "INFORMATION_ONLY", "SECONDS_PER_MEASUREMENT", "estimate_ptc_seconds", "ptc_verdict", "ptc_calibration"]

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
    two-sided Šidák critical value of family-wise ``alpha`` over the values tested (normal law: each standard
    error is propagated from thousands of pixel pairs' own moments, so its own error is a few percent).

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


SECONDS_PER_MEASUREMENT = 0.3
"""One measurement of the 24-point series beside the shared render, s (0.19–0.42 measured on a loaded 2-core VM)."""


def estimate_ptc_seconds(seeds: int, points: int = 24, spp: int = 64) -> float:
    """Wall time of :func:`ptc_calibration`, s: the render (64 × 64 pixels) and its compilation once, then ``seeds``
    measurements of ``points`` exposures.

    >>> round(estimate_ptc_seconds(400))
    126
    """
    from .calibration import estimate_seconds

    return estimate_seconds(1, 64 * 64, spp, renders=1) + seeds * SECONDS_PER_MEASUREMENT * points / 24


def _rows(runs: list[dict], alpha: float) -> list[dict]:
    """The family's and each figure's observed rate against its nominal one (a figure's: its channels' share of the
    family, 1 − (1 − α_Šidák)^channels, averaged over the runs: a dark current is tested only where resolved), with
    Clopper–Pearson 95 % intervals."""

    def share(run: dict, figure: str) -> float:  # the figure's nominal rate in one run: its channels tested
        channels = sum(name.startswith(figure + " ") for name in run["tested"])
        return 1 - (1 - sidak(alpha, len(run["tested"]))) ** channels if channels else 0.0

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


def ptc_calibration(camera_, imager_, temperature: float = 5900.0, illuminance_lux: float = 500.0, seeds: int = 40,
                    first_seed: int = 0, points: int = 24, spp: int = 64, alpha: float = ALPHA_DIFFERENCE,
                    progress: Callable[[str], None] | None = None) -> dict:
    """
    ``seeds`` photon-transfer measurements of a correct imager (the sensor noise's seeds ``first_seed``,
    ``first_seed + 1``, …; the grey chart rendered once at ``spp`` with seed ``first_seed``): every failure of the
    fits' test is a false alarm. Per check (``fits``, the family; each tested figure, its share of it) the observed
    rate with its Clopper–Pearson 95 % interval against the nominal α, and per figure and channel the mean and
    standard deviation of z (0 and 1 where the standard errors are right).

    Returns
    -------
    dict
        ``machine``, ``scene`` (``ptc``), ``camera``, ``imager``, ``illuminance_lux``, ``prevailing_K`` (the light,
        K), ``calibration_K`` (``None``), ``spp``, ``points``, ``seeds``, ``first_seed``, ``seed_step`` (1),
        ``checks`` (``[{name, nominal_alpha, nominal, failures, seeds, rate, interval, consistent, outcomes}]``),
        ``z`` (``{figure: {mean, sd, values}}``, per channel), ``tests``, ``runs`` (``[{seed, verdict, statistic,
        worst}]``), ``elapsed_s``.
    """
    from ...model.imager import imager
    from ...rendering.settings import RenderSettings
    from .bench import machine
    from .ptc import electron_rates, measure

    begun = time.perf_counter()
    im = imager(imager_)
    rate, used = electron_rates(camera_, im, temperature, illuminance_lux, RenderSettings(spp=spp, seed=first_seed))
    runs, test = [], ""
    for seed in range(first_seed, first_seed + seeds):
        verdict = ptc_verdict(measure(im, rate, seed, points), alpha)
        check = verdict["checks"]["fits"]
        test = check["test"]
        runs.append({"seed": seed, "verdict": verdict["verdict"], "statistic": check["statistic"],
                     "threshold": check["threshold"], "worst": check.get("worst_figure"), "tested": check["tested"],
                     "z": verdict["z"]})
        if progress is not None:
            progress(f"seed {seed}: {verdict['verdict']}, largest |z| {check['statistic']:.3g}"
                     + (f" ({check['worst_figure']})" if verdict["verdict"] == "fail" else ""))
    z = {}
    for figure in TESTED:
        values = np.array([[np.nan if v is None else v for v in run["z"][figure]] for run in runs])
        tested = ~np.isnan(values)
        if tested.any():
            with np.errstate(invalid="ignore", divide="ignore"):
                z[figure] = {"mean": [float(np.nanmean(c)) if t.any() else None for c, t in zip(values.T, tested.T)],
                             "sd": [float(np.nanstd(c, ddof=1)) if t.sum() > 1 else None
                                    for c, t in zip(values.T, tested.T)],
                             "values": tested.sum(axis=0).tolist()}
    return {"machine": machine(), "scene": "ptc", "camera": camera_.name, "imager": im.name,
            "illuminance_lux": float(illuminance_lux), "prevailing_K": float(temperature), "calibration_K": None,
            "spp": used, "points": points, "seeds": seeds, "first_seed": first_seed, "seed_step": 1, "alpha": alpha,
            "checks": _rows(runs, alpha), "z": z, "tests": {"fits": test},
            "runs": [{key: run[key] for key in ("seed", "verdict", "statistic", "worst")} for run in runs],
            "elapsed_s": time.perf_counter() - begun}
