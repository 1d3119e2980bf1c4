"""
Benchmarks
==========

Speed figures printed by ``skinrender bench``; measured here, never asserted
in unit tests.

-   :func:`bench_search`: the Stage 3 search, straightforward vs fast.
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

from ...model.camera import camera
from ...model.response import response
from ...constants import CONSTANT_OUTPUT_SCALE, TEMPERATURES_PAPER
from ...datasets import reflectances
from ...design.bank import SENSORS_PAPER
from ...errors import SkinrenderError
from ...spectra import GRID_DEFAULT, planck
from ...execution import check_workers

__all__ = ["at_least_one", "machine", "bench_analytic", "bench_search", "bench_sweep", "bench_render"]


def at_least_one(value, flag: str) -> int:
    """An integer ≥ 1, or a one-line :class:`SkinrenderError` naming ``flag``."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise SkinrenderError(f"{flag} must be an integer ≥ 1, got {value!r}", flag=flag)
    return int(value)


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
    for _ in range(repeat):
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

    repeat = at_least_one(repeat, "--repeat")
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


def bench_search(
    sensor: float = 9,
    sample: int = 20,
    steps: tuple[float, ...] = (20.0, 10.0, 5.0),
    full_steps: tuple[float, ...] = (20.0, 10.0, 5.0),
    workers: int | None = None,
    sweep_positions: str | None = "400:700:30",
    sweep_slopes: tuple[float, ...] = (1.0, 3.0),
) -> dict:
    """
    Time the Stage 3 search: straightforward vs fast method, and the full search.

    -   ``naive_ms_per_triplet`` and ``fast_ms_per_triplet``: one core, the same
        ``sample`` triplets (evenly spread over the 4495 of the 10 nm grid),
        skin and Munsell sets, all eleven cases each; ``speedup`` their ratio,
        ``max_rel_difference`` the largest relative volume difference.
    -   ``full_search_s``: the whole 10 nm search on every core (``None``
        where 10 nm is not among ``full_steps``); ``elapsed_s``: the whole
        benchmark's wall time.
    -   ``hull_kernel``: ``quickhull`` (compiled) or ``qhull`` (no C compiler
        at install time; see :data:`skinrender.evaluation.hull.HULL_KERNEL`).
    -   ``growth``: per grid step, the triplet count and the time — measured in
        full for ``full_steps``, estimated from ``sample`` triplets timed on
        one core (divided by the worker count) for the others, and marked so.
    -   ``sweep_s_per_setting``: seconds per setting of a small ``reproduce
        --sweep`` (all eight sensors at ``sweep_positions``; the default and
        ``sweep_slopes``, each setting computing every volume anew), and
        ``sweep_s_per_setting_10nm_estimate``, scaled to the 4495 triplets of
        the paper's grid by the triplet count. ``sweep_positions=None`` skips it.

    ``sample`` and ``workers`` are checked (integers ≥ 1) before anything is timed.
    """

    begun = time.perf_counter()
    sample = at_least_one(sample, "--sample")
    if workers is not None:
        workers = check_workers(workers)

    from ...design.bank import positions_grid, sensor_bank, triplets
    from ...design.criteria import triplet_volumes_fast, triplet_volumes_naive
    from ...design.search import search
    from ...evaluation.hull import HULL_KERNEL

    grid = GRID_DEFAULT
    skin, munsell = reflectances("skin").on(grid), reflectances("munsell").on(grid)
    where = positions_grid("400:700:10")
    banks = [sensor_bank(sensor, values, where) for values in (skin, munsell)]
    index = triplets(where.size)
    chosen = index[np.linspace(0, len(index) - 1, sample).astype(int)]

    def run(method):
        return np.array([[method(bank, t) for t in chosen] for bank in banks])

    start = time.perf_counter()
    naive = run(triplet_volumes_naive)
    naive_s = time.perf_counter() - start
    start = time.perf_counter()
    fast = run(triplet_volumes_fast)
    fast_s = time.perf_counter() - start
    relative = np.abs(fast - naive) / np.where(naive > 0, naive, 1.0)
    cores = workers or os.cpu_count() or 1

    growth = []
    full_search_s = None
    for step in steps:
        spec = f"400:700:{step:g}"
        count = len(triplets(positions_grid(spec).size))
        if step in full_steps:
            result = search(sensor, skin, munsell, spec, workers=workers)
            growth.append({"step_nm": step, "triplets": count, "seconds": result.elapsed_s, "measured": "full"})
            if step == 10.0:
                full_search_s = result.elapsed_s
        else:
            fine = positions_grid(spec)
            fine_banks = [sensor_bank(sensor, values, fine) for values in (skin, munsell)]
            fine_index = triplets(fine.size)
            picked = fine_index[np.linspace(0, len(fine_index) - 1, sample).astype(int)]
            start = time.perf_counter()
            for bank in fine_banks:
                for t in picked:
                    triplet_volumes_fast(bank, t)
            per = (time.perf_counter() - start) / sample
            growth.append({"step_nm": step, "triplets": count, "seconds": per * count / cores,
                           "measured": f"estimated from {sample} triplets on one core / {cores} workers"})
    sweep_s = sweep_estimate = None
    if sweep_positions is not None:
        timed = bench_sweep(sweep_positions, workers=workers, candidates={"slope": list(sweep_slopes)})
        sweep_s = timed["s_per_setting"]
        sweep_estimate = timed["s_per_setting_10nm_estimate"]
    return {
        "machine": machine(),
        "sensor": sensor,
        "sample_triplets": sample,
        "naive_ms_per_triplet": 1e3 * naive_s / sample,
        "fast_ms_per_triplet": 1e3 * fast_s / sample,
        "speedup": naive_s / fast_s,
        "max_rel_difference": float(relative.max()),
        "full_search_s": full_search_s,
        "elapsed_s": time.perf_counter() - begun,
        "workers": cores,
        "hull_kernel": HULL_KERNEL,
        "growth": growth,
        "sweep_positions": sweep_positions,
        "sweep_s_per_setting": sweep_s,
        "sweep_s_per_setting_10nm_estimate": sweep_estimate,
    }


def bench_sweep(
    positions: str = "400:700:20",
    sensors=SENSORS_PAPER,
    workers: int | None = None,
    candidates: dict | None = None,
) -> dict:
    """
    Time ``reproduce --sweep`` (tables only) one unknown at a time, no combinations.

    Returns
    -------
    dict
        ``machine``, ``positions``, ``triplets`` (per sensor), ``settings``
        (``[{setting, seconds}]``), ``s_per_setting`` (mean),
        ``s_per_setting_10nm_estimate`` (the mean scaled by the triplet count
        to the paper's 4495), ``elapsed_s``, ``volumes_computed`` (banks
        computed: settings that share volumes compute fewer).
    """

    from ...design.bank import positions_grid, triplets
    from ..paper.sweep import sweep

    if workers is not None:
        workers = check_workers(workers)
    count = len(triplets(positions_grid(positions).size))
    result = sweep(sensors, positions, combine=0, workers=workers, candidates=candidates)
    seconds = [row["seconds"] for row in result["sweep"]]
    mean = float(np.mean(seconds))
    return {
        "machine": machine(),
        "positions": positions,
        "triplets": count,
        "settings": [{"setting": row["setting"], "seconds": row["seconds"]} for row in result["sweep"]],
        "s_per_setting": mean,
        "s_per_setting_10nm_estimate": mean * len(triplets(31)) / count,
        "elapsed_s": result["elapsed_s"],
        "volumes_computed": result["volumes_computed"],
    }


def bench_render(
    camera_spec: str = "gbell:9@450,540,610",
    quick: bool = False,
    variants: tuple[str, ...] | None = None,
    spps: tuple[int, ...] | None = None,
    samplers: tuple[str, ...] = ("independent", "multijitter"),
    seed: int = 1,
    all_pairs: bool = True,
    all_pairs_spp: int = 64,
) -> dict:
    """
    Error against time of the Mitsuba render of the Macbeth chart.

    -   ``curve``: for every variant that runs here, sampler and spp, the
        render time (s, best of two after a warm-up, kernel compilation
        excluded) and the RMS relative error of the 25 patch means (Eq. 4 at
        p = c = A, 144 pixels averaged per patch) against
        :func:`skinrender.validate.analytic_reference`; plus the analytic
        model's own error on 5 and 10 nm grids against 1 nm
        (``variant = "analytic"``).
    -   ``all_pairs_s``: rendering all three charts at every paper
        illuminant (``all_pairs_spp``, multijitter) and validating all 100 (prevailing,
        calibration) pairs of each — one render per chart and temperature,
        the pairs are Eq. 4 applied afterwards.
    -   ``curve_s``: the curve's timings summed (best of two each);
        ``elapsed_s``: the whole benchmark's wall time, warm-ups and
        ``all_pairs`` included.
    """

    begun = time.perf_counter()
    from ...rendering.balance import render
    from ...rendering.renderer import render_raw
    from ...rendering.scene import load_chart_scene
    from ...rendering.settings import RenderSettings
    from ...rendering.validation import analytic_reference, validate
    from ...rendering.variants import VARIANTS_SPECTRAL, variant_works, choose_variant

    chart = load_chart_scene("macbeth")
    cam = camera(camera_spec)
    reference = analytic_reference(cam, chart.reflectances(GRID_DEFAULT), 2856.0, 2856.0)
    if variants is None:
        variants = (choose_variant(),) if quick else tuple(v for v in VARIANTS_SPECTRAL if variant_works(v))
    curve = []
    for variant in variants:
        top = 256 if quick or variant.startswith("scalar") else 4096
        for sampler in samplers:
            for spp in spps or tuple(s for s in (4, 16, 64, 256, 1024, 4096) if s <= top):
                settings = RenderSettings(spp, seed, sampler, variant)
                render_raw(chart, cam, 2856.0, settings)  # warm-up: compile kernels
                best, rendering = np.inf, None
                for repeat in range(2):
                    rendering = render(chart, cam, 2856.0, 2856.0, settings=settings.replace(seed=seed + repeat))
                    best = min(best, rendering.seconds)
                error = float(np.sqrt(np.mean((rendering.patches.mean / reference - 1) ** 2)))
                curve.append({"variant": variant, "sampler": sampler, "spp": spp, "seconds": best, "rel_error": error})
    for step in (5.0, 10.0):
        from ...spectra import WavelengthGrid

        coarse = WavelengthGrid(400.0, 700.0, step)
        start = time.perf_counter()
        approx = analytic_reference(cam, chart.reflectances(coarse), 2856.0, 2856.0, grid=coarse)
        seconds = time.perf_counter() - start
        error = float(np.sqrt(np.mean((approx / reference - 1) ** 2)))
        curve.append({"variant": "analytic", "sampler": f"grid {step:g} nm", "spp": 0, "seconds": seconds,
                      "rel_error": error})

    all_pairs_s = None
    all_pairs_worst = None
    if all_pairs:
        spp = all_pairs_spp
        temperatures = np.array(TEMPERATURES_PAPER)
        start = time.perf_counter()
        worst, bound = 0.0, 0.0
        outcomes: dict = {}
        for name in ("macbeth", "skin_patches", "face_chart"):
            cache: dict = {}
            for p in temperatures:
                for q in temperatures:
                    # one render per temperature: the calibration white comes from the same cache
                    r = render(name, cam, p, q, spp=spp, seed=seed, cache=cache)
                    v = validate(name, cam, p, q, rendering=r)
                    worst, bound = max(worst, float(v.rel_error.max())), max(bound, v.bound)
                    for check in (v.verdict, v.difference):
                        key = f"{check.name} {check.outcome}"
                        outcomes[key] = outcomes.get(key, 0) + 1
        all_pairs_s = time.perf_counter() - start
        # passed: every pair's verdict a pass (shown within the default 1 %); outcomes: the verdicts' and the
        # difference tests' counts; max_bound: the largest tolerance one of them needed
        all_pairs_worst = {"max_rel_error": worst, "max_bound": bound, "outcomes": outcomes,
                           "passed": outcomes.get("equivalence pass", 0) == 3 * len(temperatures) ** 2, "spp": spp}
    return {
        "machine": machine(),
        "camera": cam.name,
        "curve": curve,
        "all_pairs_s": all_pairs_s,
        "all_pairs": all_pairs_worst,
        "curve_s": sum(row["seconds"] for row in curve),
        "elapsed_s": time.perf_counter() - begun,
    }
