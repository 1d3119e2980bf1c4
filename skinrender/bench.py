"""
Benchmarks
==========

Speed figures printed by ``skinrender bench``; measured here, never asserted
in unit tests.

-   :func:`bench_analytic`: Eq. 4 responses per second for the 1269 Munsell
    chips under all 100 (prevailing, calibration) pairs of the paper's ten
    illuminants, beside colour-science's ``training_data_sds_to_RGB`` doing the
    same work.
"""

from __future__ import annotations

import os
import platform
import time

import numpy as np

from .camera import camera, response
from .constants import CONSTANT_OUTPUT_SCALE, TEMPERATURES_PAPER
from .datasets import reflectances
from .spectra import GRID_DEFAULT, planck

__all__ = ["machine", "bench_analytic"]


def machine() -> dict:
    """A description of the machine the figures were measured on."""
    return {
        "cpu_count": os.cpu_count(),
        "processor": platform.processor() or platform.machine(),
        "python": platform.python_version(),
        "numpy": np.__version__,
    }


def _best_time(function, repeat: int) -> float:
    best = np.inf
    for _ in range(max(1, repeat)):
        start = time.perf_counter()
        function()
        best = min(best, time.perf_counter() - start)
    return best


def bench_analytic(camera_spec: str = "Nikon 5100 (NPL)", repeat: int = 3) -> dict:
    """
    Time Eq. 4 for 1269 Munsell reflectances × 100 illuminant pairs.

    Both routes compute the same responses on the default grid (400–700 nm,
    1 nm): skinrender's vectorised :func:`skinrender.response` in one call,
    and colour-science's ``training_data_sds_to_RGB`` called once per
    (prevailing, calibration) pair with the prevailing Planck SPD, its
    white-balance multipliers replaced by the calibration's (Eq. 4). The
    largest relative difference between the two is reported as a check.

    Returns
    -------
    dict
        ``machine``, ``elapsed_s`` (skinrender), ``responses_per_s``,
        ``colour_elapsed_s``, ``colour_responses_per_s``, ``speedup``,
        ``max_rel_difference``, ``responses`` (reflectances × pairs).
    """

    from colour import MultiSpectralDistributions, SpectralDistribution, SpectralShape
    from colour.characterisation import RGB_CameraSensitivities, training_data_sds_to_RGB
    from colour.characterisation.aces_it import white_balance_multipliers

    grid = GRID_DEFAULT
    cam = camera(camera_spec)
    munsell = reflectances("munsell")
    o = munsell.on(grid)
    temperatures = np.array(TEMPERATURES_PAPER)
    count = o.shape[0] * temperatures.size**2

    ours: list[np.ndarray] = []
    elapsed = _best_time(
        lambda: ours.append(response(cam, o, temperatures[:, None], temperatures[None, :])), repeat
    )

    wavelengths = grid.wavelengths
    shape = SpectralShape(grid.start, grid.end, grid.step)
    training = MultiSpectralDistributions(o.T, wavelengths)
    sensitivities = RGB_CameraSensitivities(cam.sensitivities(grid).T, wavelengths)
    sds = [SpectralDistribution(planck(wavelengths, t), wavelengths) for t in temperatures]
    assert training.shape == shape

    def colour_route() -> np.ndarray:
        out = np.empty((temperatures.size, temperatures.size, o.shape[0], 3))
        for i, sd_p in enumerate(sds):
            for j, sd_c in enumerate(sds):
                rgb, rgb_w = training_data_sds_to_RGB(training, sensitivities, sd_p)
                # Eq. 4 balances with the calibration light: swap the multipliers.
                out[i, j] = rgb / rgb_w * white_balance_multipliers(sensitivities, sd_c)
        return out

    theirs: list[np.ndarray] = []
    colour_elapsed = _best_time(lambda: theirs.append(colour_route()), repeat)

    # colour-science's multipliers are scaled so that the smallest is 1; Eq. 4
    # makes every channel's white v. The two routes therefore differ by one
    # factor per pair, common to all samples and channels: take it from one.
    a, b = ours[-1], theirs[-1]
    scale = a[..., 1:2, 1:2] / b[..., 1:2, 1:2]
    relative = np.abs(a - b * scale) / np.maximum(np.abs(a), 1e-300)
    return {
        "machine": machine(),
        "camera": cam.name,
        "responses": int(count),
        "elapsed_s": elapsed,
        "responses_per_s": count / elapsed,
        "colour_elapsed_s": colour_elapsed,
        "colour_responses_per_s": count / colour_elapsed,
        "speedup": colour_elapsed / elapsed,
        "max_rel_difference": float(relative.max()),
        "output_scale": CONSTANT_OUTPUT_SCALE,
    }
