"""
Measure the coverage of ``validate``'s equivalence bounds at a known truth, over many seeds (docs/verdicts.md,
"Heavy tails").

A chart's renderer is unbiased: its expectation is Eq. 4 of what it integrates (the analytic reference), so the
truth of every error ``rendered − analytic`` is 0. The equivalence gives each value the upper bound
``|e| + h`` of its ``|error|`` (``h = c·SE``, widened to Cantelli's for a value too skewed for the normal law),
all together at 95 % (family-wise, Šidák). Its coverage at a truth ``δ`` far from 0 on either side is what a
false pass at the tolerance's edge depends on: for ``δ > 0`` on every value the bounds hold together exactly
when every ``e ≥ −h`` (the noise's lower tail), for ``δ < 0`` when every ``e ≤ h`` (its upper tail). Both are
counted per seed (seeds S, S + 2, …: each validation takes its seed and the next); each should be ≥ 95 %. A
heavy-tailed estimate (a dark channel drawing few wavelength samples, a subsurface slab's long paths) has a
sample standard error that shrinks with the mean when the rare large values are missing, so its lower tail is
heavier than the normal law's.

Also printed: the largest excess kurtosis of a patch channel's pixels (≈ 0 for normal pixels) and how many
values the skewness guard held to Cantelli's bound.

    PYTHONPATH=. python tools/measure_coverage.py --seeds 100 --scene macbeth --camera gbell:9@450,540,610 \\
        --prevailing A --calibration 5900 --spp 16
    PYTHONPATH=. python tools/measure_coverage.py --seeds 100 --scene slabs.toml --physics subsurface-volume --spp 16
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np


def run(scene, camera, prevailing, calibration, spp, seed, physics, normalization, tolerance) -> dict:
    """One validation: per value the error, the bound's half-width ``h``, and the pixels' excess kurtosis."""
    from skinrender.rendering.validation import validate

    options = {"physics": physics} if physics != "direct" else {}
    v = validate(scene, camera, prevailing, calibration, spp=spp, seed=seed, normalization=normalization,
                 tolerance=tolerance, **options)
    error = v.rendered - v.analytic
    half = v.upper - np.abs(error)
    chart, image = v.rendering.scene, v.rendering.image.astype(np.float64)
    kurtosis = np.zeros(error.shape)
    for i in range(error.shape[0]):
        rows, columns = chart.patch_pixels(i)
        pixels = image[rows, columns].reshape(-1, 3)
        centred = pixels - pixels.mean(axis=0)
        var = (centred**2).mean(axis=0)
        with np.errstate(divide="ignore", invalid="ignore"):
            kurtosis[i] = np.where(var > 0, (centred**4).mean(axis=0) / var**2 - 3.0, 0.0)
    return {"error": error, "half": half, "sigma": v.sigma, "kurtosis": kurtosis,
            "skewness": np.zeros(error.shape) if v.skewness is None else np.asarray(v.skewness),
            "dof": float(np.min(v.rendering.patches.count) - 1),
            "skewed": int(v.verdict.details.get("skewed", 0)), "outcome": v.verdict.outcome,
            "white_level": v.white_level, "critical": v.verdict.details.get("critical")}


def coverage(runs: list[dict]) -> dict:
    """The coverage at a truth above and below every value, and per value its tails' shares."""
    from skinrender.evaluation.verdict import binomial_interval

    e = np.array([r["error"] for r in runs])
    h = np.array([r["half"] for r in runs])
    below, above = np.any(e < -h, axis=(1, 2)), np.any(e > h, axis=(1, 2))
    n = len(runs)
    out = {}
    for name, missed in (("truth_above", below), ("truth_below", above), ("both_sides", below | above)):
        misses = int(np.sum(missed))
        out[name] = {"coverage": 1 - misses / n, "misses": misses, "seeds": n,
                     "interval_of_coverage": [1 - x for x in reversed(binomial_interval(misses, n))]}
    t = np.divide(e, np.array([r["sigma"] for r in runs]), out=np.zeros_like(e),
                  where=np.array([r["sigma"] for r in runs]) > 0)
    worst = np.unravel_index(np.argmax(np.mean(e < -h, axis=0)), e.shape[1:])
    out["worst_value"] = {"index": [int(i) for i in worst], "lower_tail_share": float(np.mean(e < -h, axis=0)[worst]),
                          "upper_tail_share": float(np.mean(e > h, axis=0)[worst]),
                          "t_skewness": float(_skew(t[(slice(None), *worst)]))}
    out["kurtosis_max"] = float(np.max([r["kurtosis"] for r in runs]))
    out["kurtosis_median_of_max"] = float(np.median([np.max(r["kurtosis"]) for r in runs]))
    out["skewed_values_per_run"] = float(np.mean([r["skewed"] for r in runs]))
    return out


def _skew(x) -> float:
    x = np.asarray(x, dtype=np.float64)
    s = x.std()
    return float(np.mean((x - x.mean()) ** 3) / s**3) if s > 0 else 0.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="macbeth")
    parser.add_argument("--camera", default="gbell:9@450,540,610")
    parser.add_argument("--prevailing", default="A")
    parser.add_argument("--calibration", default="5900")
    parser.add_argument("--spp", type=int, default=16)
    parser.add_argument("--seeds", type=int, default=100)
    parser.add_argument("--first", type=int, default=0)
    parser.add_argument("--physics", default="direct")
    parser.add_argument("--normalization", default="white")
    parser.add_argument("--tolerance", type=float, default=0.01)
    parser.add_argument("--save", help="write every run's errors, bounds, SEs and skewnesses to this .npz")
    args = parser.parse_args()
    from skinrender.model.illuminant import illuminant

    p, c = (illuminant(x).temperature for x in (args.prevailing, args.calibration))
    start = time.perf_counter()
    runs = [run(args.scene, args.camera, p, c, args.spp, args.first + 2 * j, args.physics, args.normalization,
                args.tolerance) for j in range(args.seeds)]
    out = {"scene": args.scene, "camera": args.camera, "prevailing_K": p, "calibration_K": c, "spp": args.spp,
           "physics": args.physics, "normalization": args.normalization, "seeds": args.seeds,
           "first_seed": args.first, **coverage(runs), "elapsed_s": time.perf_counter() - start}
    print(json.dumps(out))
    if args.save:
        np.savez(args.save, **{key: np.array([r[key] for r in runs]) for key in
                                ("error", "half", "sigma", "kurtosis", "skewness", "critical", "dof")})
    print(f"{args.scene} ({args.physics}) through {args.camera}, {p:g} K / {c:g} K, {args.spp} spp, {args.seeds} "
          f"seeds: coverage at a truth above every value {out['truth_above']['coverage']:.3f}, below "
          f"{out['truth_below']['coverage']:.3f} (nominal ≥ 0.95 each); pixels' excess kurtosis up to "
          f"{out['kurtosis_max']:.3g}; {out['skewed_values_per_run']:.2f} values a run held to Cantelli's bound; "
          f"{out['elapsed_s']:.0f} s")


if __name__ == "__main__":
    main()
