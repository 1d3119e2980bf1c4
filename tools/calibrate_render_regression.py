"""
Measure the false-alarm rate and the power of ``render_regression``'s comparison (docs/testing.md).

Where nothing changed: 10 references (seeds 1000…1009, rendered at REFERENCE_SPP_FACTOR × spp) × 20 checks
(seeds 1…20) at the default spp, a chart (macbeth) or a face, through a CSV camera of three Gaussian channels
(peaks 600, 530, 460 nm), A → 5000 K; the rate is printed with its Clopper–Pearson 95 % interval. Then 10
checks through the same camera with every peak 2 nm longer, against a reference at seed 0.

    PYTHONPATH=. python tools/calibrate_render_regression.py chart
    PYTHONPATH=. python tools/calibrate_render_regression.py face
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from skinrender.evaluation.verdict import binomial_interval
from skinrender.testing.regression import REFERENCE_SPP_FACTOR, compare, measure


def csv_camera(path: Path, shift: float = 0.0) -> str:
    """Three Gaussian channels (peaks 600, 530, 460 nm + ``shift``, nm), written as wavelength_nm,R,G,B."""
    lam = np.arange(380, 781, 5.0)
    curves = [np.exp(-((lam - peak - shift) / width) ** 2) for peak, width in ((600, 40), (530, 40), (460, 35))]
    np.savetxt(path, np.column_stack([lam, *curves]), delimiter=",", header="wavelength_nm,R,G,B", comments="",
               fmt="%.6g")
    return str(path)


def main(kind: str) -> None:
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


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "chart")
