"""
Are the imager checks' z statistics normal? (issue 36 follow-up: the ptc fits' false alarms pooled at 1.6 %)

-   ``ptc IMAGER LUX FIRST N``: the photon transfer of gbell:9@450,540,610 at 5900 K, the grey chart rendered once
    (64 spp, seed FIRST), measured with sensor seeds FIRST … FIRST + N − 1 — exactly the runs of ``skinrender bench
    calibration --scene ptc --imager IMAGER --illuminance LUX --seeds N --seed FIRST`` — and per figure and
    channel z's standard deviation and excess kurtosis, the standard error's own spread over seeds (its
    coefficient of variation c and the degrees of freedom 1/(2c²) a Student t would give it), the correlation of
    fit and standard error, the share of |z| beyond the test's threshold against the normal law's; the family's
    failures with their Clopper–Pearson interval, and with Student-t critical values at the smallest of those
    degrees of freedom instead of normal ones.
-   ``validate LUX FIRST N``: the Macbeth chart through the sony-imx174 at 3300 K / 4800 K, 64 spp, seeds FIRST,
    FIRST + 2, … (as ``bench calibration --imager sony-imx174 --illuminance LUX --spp 64 --seed FIRST`` runs them):
    the mean test's z per patch channel (their means' χ², pooled sd, kurtosis, tail counts against the normal's).

Usage: ``PYTHONPATH=. python tools/measure_z_tails.py ptc sony-imx174 500 10000 3000``. Units: z dimensionless;
rates fractions.
"""

from __future__ import annotations

import sys

import numpy as np
from scipy import stats

from skinrender.evaluation.verdict import binomial_interval

CAM = "gbell:9@450,540,610"


def ptc(name: str, lux: float, first: int, n: int) -> None:
    from skinrender.model.camera import camera
    from skinrender.model.imager import imager
    from skinrender.rendering.settings import RenderSettings
    from skinrender.studies.benchmarks.ptc import electron_rates, measure
    from skinrender.studies.benchmarks.ptc_verdict import TESTED, ptc_verdict

    im = imager(name)
    rate, _ = electron_rates(camera(CAM), im, 5900.0, lux, RenderSettings(spp=64, seed=first))
    runs = []
    for seed in range(first, first + n):
        m = measure(im, rate, seed)
        v = ptc_verdict(m)
        runs.append((m, v))
    threshold, dofs, rows, pooled = runs[0][1]["checks"]["fits"]["threshold"], [], [], []
    for figure in TESTED:
        for k in range(3):
            pairs = [(v["z"][figure][k], m[figure][k], m["standard_error"][figure][k]) for m, v in runs
                     if v["z"][figure][k] is not None]
            if len(pairs) < 10:
                continue
            z, fit, se = (np.array(c, dtype=float) for c in zip(*pairs))
            cv = se.std() / se.mean()
            dofs.append(1 / (2 * cv**2))
            pooled.append(z)
            rows.append(f"{figure} {'RGB'[k]}: z sd {z.std(ddof=1):.3f}, kurtosis {stats.kurtosis(z):+.2f}, SE cv "
                        f"{cv:.4f} (dof ≈ {dofs[-1]:.0f}), corr(fit, SE) {np.corrcoef(fit, se)[0, 1]:+.2f}, "
                        f"|z| > {threshold:.3f}: {np.mean(np.abs(z) > threshold):.5f}")
    values = max(len(v["checks"]["fits"]["tested"]) for _, v in runs)
    per_value = 1 - (1 - 0.01) ** (1 / values)
    fails = sum(v["verdict"] == "fail" for _, v in runs)
    t_crit = stats.t.isf(per_value / 2, min(dofs))
    largest = [v["checks"]["fits"]["statistic"] for _, v in runs]
    t_fails = sum(s > t_crit for s in largest)
    z = np.concatenate(pooled)
    print(f"{name}, {lux:g} lx, seeds {first}–{first + n - 1}: fits failed {fails}/{n} "
          f"{tuple(round(x, 4) for x in binomial_interval(fails, n))}; pooled z sd {z.std(ddof=1):.3f}, kurtosis "
          f"{stats.kurtosis(z):+.3f}, per value |z| > {threshold:.3f}: {np.mean(np.abs(z) > threshold):.5f} (normal "
          f"{per_value:.5f}); Student t at dof {min(dofs):.0f} (critical {t_crit:.3f}): {t_fails}/{n} "
          f"{tuple(round(x, 4) for x in binomial_interval(t_fails, n))}")
    print("\n".join("  " + row for row in rows))


def validate(lux: float, first: int, n: int) -> None:
    from skinrender.model.camera import camera
    from skinrender.rendering.imaging import render_imaged
    from skinrender.rendering.scene import load_chart_scene
    from skinrender.rendering.sensor_validation import validate_imaged
    from skinrender.rendering.validation import analytic_reference
    from skinrender.spectra import GRID_DEFAULT

    cam, chart = camera(CAM), load_chart_scene("macbeth")
    ratio = analytic_reference(cam, chart.reflectances(GRID_DEFAULT), 3300.0, 3300.0) / 255.0
    z = np.array([validate_imaged(render_imaged(chart, cam, 3300.0, 4800.0, "sony-imx174", lux, spp=64, seed=s),
                                  ratio).z for s in range(first, first + 2 * n, 2)])
    means, sds = z.mean(axis=0), z.std(axis=0, ddof=1)
    tails = ", ".join(f"|z| > {c}: {int(np.sum(np.abs(z) > c))} (normal {z.size * 2 * stats.norm.sf(c):.1f})"
                      for c in (3.0, 3.5, 4.0))
    print(f"validate, {lux:g} lx, seeds {first}, {first + 2}, … ({n}): pooled z sd {z.std():.4f}, kurtosis "
          f"{stats.kurtosis(z.ravel()):+.3f}; per patch channel sd {sds.min():.2f}–{sds.max():.2f}, means' χ² "
          f"{np.sum(means**2) * n:.1f} on {means.size} dof; {tails}")


if __name__ == "__main__":
    mode, *rest = sys.argv[1:]
    if mode == "ptc":
        ptc(rest[0], float(rest[1]), int(rest[2]), int(rest[3]))
    else:
        validate(float(rest[0]), int(rest[1]), int(rest[2]))
