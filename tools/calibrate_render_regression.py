"""
Measure the false-alarm rate and the power of ``render_regression``'s comparison (docs/testing.md).

``chart`` / ``face`` (the power, and the rate against references of other seeds): 10 references (seeds
1000…1009, rendered at REFERENCE_SPP_FACTOR × spp) × 20 checks (seeds 1…20) at the default spp, a chart
(macbeth) or a face, through a CSV camera of three Gaussian channels (peaks 600, 530, 460 nm), A → 5000 K; the
rate is printed with its Clopper–Pearson 95 % interval. Then 10 checks through the same camera with every peak
2 nm longer, against a reference at seed 0.

``aa`` (the plugin's own A/A test: what a user's suite does): for each seed S of ``--seeds`` (S = ``--first`` …),
the reference rendered as ``--skinrender-regen`` renders it (REFERENCE_SPP_FACTOR × spp, seed
``reference_seed(S)``) and the check at seed S, nothing changed between them; the failures with their
Clopper–Pearson interval against α = 0.01, and the spread of every z (1 where the standard errors are right).
``--same-seed`` renders the reference with S itself, as the plugin did before (its samples begin with the
check's): the z spread then falls below 1.

    PYTHONPATH=. python tools/calibrate_render_regression.py chart
    PYTHONPATH=. python tools/calibrate_render_regression.py face
    PYTHONPATH=. python tools/calibrate_render_regression.py aa --variant llvm_ad_spectral --seeds 200
    PYTHONPATH=. python tools/calibrate_render_regression.py aa --variant scalar_spectral --seeds 200
    PYTHONPATH=. python tools/calibrate_render_regression.py aa --variant scalar_spectral --seeds 50 --same-seed

``se`` (are the standard errors right?): ``--seeds`` checks (seeds 1, 3, …) of the same chart; per value the
variance of its mean across seeds over the mean of its stated SE², averaged per channel and overall (1 where
they are right; < 1 where they overstate the noise, which makes the test conservative), at A → 5000 K and at
A → A.

    PYTHONPATH=. python tools/calibrate_render_regression.py se --seeds 40
"""

from __future__ import annotations

import argparse
import json
import tempfile
import time
from pathlib import Path

import numpy as np

from skinrender.evaluation.verdict import ALPHA_DIFFERENCE, binomial_interval
from skinrender.testing.reference import reference_seed
from skinrender.testing.regression import REFERENCE_SPP_FACTOR, compare, measure


def csv_camera(path: Path, shift: float = 0.0) -> str:
    """Three Gaussian channels (peaks 600, 530, 460 nm + ``shift``, nm), written as wavelength_nm,R,G,B."""
    lam = np.arange(380, 781, 5.0)
    curves = [np.exp(-((lam - peak - shift) / width) ** 2) for peak, width in ((600, 40), (530, 40), (460, 35))]
    np.savetxt(path, np.column_stack([lam, *curves]), delimiter=",", header="wavelength_nm,R,G,B", comments="",
               fmt="%.6g")
    return str(path)


def power(kind: str) -> None:
    """The rate against references of other seeds, and the power against a 2 nm shift (module docstring)."""
    scene = {"chart": "macbeth", "face": "face"}[kind]
    folder = Path(tempfile.mkdtemp())
    kwargs = {"camera": csv_camera(folder / "camera.csv"), "prevailing": "A", "calibration": 5000}
    failures, zs, start = 0, [], time.perf_counter()
    for r in range(10):
        reference = measure(scene, seed=1000 + r, factor=REFERENCE_SPP_FACTOR, **kwargs)
        for seed in range(1, 21):
            result = compare(measure(scene, seed=seed, **kwargs), reference.mean, reference.standard_error,
                             reference.dof)
            failures += not result.passed
            zs.append(result.z)
    low, high = binomial_interval(failures, 200)
    print(f"{kind}: {failures}/200 false alarms (95 % interval {low:.4f}–{high:.4f}; α 0.01); z spread "
          f"{np.std(zs):.3f} over {np.size(zs)} values; {time.perf_counter() - start:.0f} s")
    reference = measure(scene, seed=0, factor=REFERENCE_SPP_FACTOR, **kwargs)
    shifted = {**kwargs, "camera": csv_camera(folder / "shifted.csv", 2.0)}
    results = [compare(measure(scene, seed=seed, **shifted), reference.mean, reference.standard_error, reference.dof)
               for seed in range(1, 11)]
    worst = [abs(r.z[r.worst]) for r in results]
    print(f"{kind}, peaks 2 nm longer: {sum(not r.passed for r in results)}/10 caught, worst |z| "
          f"{min(worst):.3g}–{max(worst):.3g}; e.g. {results[0].summary()}")


def aa(variant: str, seeds: int, first: int, same_seed: bool, scene: str) -> dict:
    """The plugin's A/A test over ``seeds`` seeds (module docstring); its figures, also printed."""
    folder = Path(tempfile.mkdtemp())
    kwargs = {"camera": csv_camera(folder / "camera.csv"), "prevailing": "A", "calibration": 5000,
              "variant": variant}
    failures, zs, start = 0, [], time.perf_counter()
    for seed in range(first, first + seeds):
        reference = measure(scene, seed=seed, factor=REFERENCE_SPP_FACTOR,
                            render_seed=seed if same_seed else reference_seed(seed), **kwargs)
        result = compare(measure(scene, seed=seed, **kwargs), reference.mean, reference.standard_error,
                         reference.dof)
        failures += not result.passed
        zs.append(result.z)
    low, high = binomial_interval(failures, seeds)
    z = np.concatenate(zs)
    out = {"scene": scene, "variant": variant, "reference_seed": "the check's own" if same_seed else "reference_seed(S)",
           "seeds": [first, first + seeds - 1], "failures": failures, "trials": seeds, "alpha": ALPHA_DIFFERENCE,
           "interval": [low, high], "contains_alpha": bool(low <= ALPHA_DIFFERENCE <= high),
           "z_sd": float(np.std(z)), "z_variance": float(np.var(z)), "values": int(z.size),
           "elapsed_s": time.perf_counter() - start}
    print(f"{scene}, {variant}, reference seed {out['reference_seed']}: {failures}/{seeds} false alarms (95 % "
          f"interval {low:.4f}–{high:.4f}; α {ALPHA_DIFFERENCE}: {'inside' if out['contains_alpha'] else 'OUTSIDE'}); "
          f"z sd {out['z_sd']:.3f} (variance {out['z_variance']:.3f}) over {z.size} values; {out['elapsed_s']:.0f} s")
    print(json.dumps(out))
    return out


def se_spread(seeds: int, scene: str) -> None:
    """The observed spread of each value across seeds against its stated standard error (module docstring)."""
    folder = Path(tempfile.mkdtemp())
    camera = csv_camera(folder / "camera.csv")
    for calibration in (5000, "A"):
        found = [measure(scene, camera, "A", calibration, seed=2 * s + 1) for s in range(seeds)]
        mean = np.array([m.mean for m in found])
        se = np.array([m.standard_error for m in found])
        ratio = mean.var(axis=0, ddof=1) / (se**2).mean(axis=0)
        per = ratio.reshape(-1, 3)
        out = {"scene": scene, "prevailing": "A", "calibration": calibration, "seeds": seeds,
               "variance_ratio": float(np.mean(ratio)), "per_channel": per.mean(axis=0).tolist(),
               "white_patch": per[-1].tolist(), "other_patches": per[:-1].mean(axis=0).tolist()}
        print(f"{scene}, A → {calibration}: observed / stated variance {out['variance_ratio']:.3f} (channels "
              + ", ".join(f"{v:.2f}" for v in out["per_channel"]) + "; white patch "
              + ", ".join(f"{v:.2f}" for v in out["white_patch"]) + f") over {seeds} seeds")
        print(json.dumps(out))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mode", choices=["chart", "face", "aa", "se"], nargs="?", default="chart")
    parser.add_argument("--variant", default="llvm_ad_spectral", help="aa: the Mitsuba variant")
    parser.add_argument("--seeds", type=int, default=200, help="aa: seeds (checks, each with its reference)")
    parser.add_argument("--first", type=int, default=1, help="aa: the first seed")
    parser.add_argument("--scene", default="macbeth", help="aa: the scene (a chart or a face)")
    parser.add_argument("--same-seed", action="store_true", help="aa: the reference renders with the check's seed "
                        "(the plugin before format 2)")
    args = parser.parse_args()
    if args.mode == "aa":
        aa(args.variant, args.seeds, args.first, args.same_seed, args.scene)
    elif args.mode == "se":
        se_spread(args.seeds, args.scene)
    else:
        power(args.mode)


if __name__ == "__main__":
    main()
