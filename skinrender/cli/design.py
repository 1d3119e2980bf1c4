"""
Camera design: ``search`` (Stage 3) and ``design`` (continuous optimisation).
"""

from __future__ import annotations

import argparse
import math
import os
import sys

from ..constants import SENSOR_RULE
from ..errors import SkinrenderError
from ..workload import check_work
from .common import (add_common, add_max_minutes, add_grid, add_search, check_output, flag, imaging_options, integer_in,
                     emit, grid_of)
from .preflight import check_dask


def add_noisy(parser) -> None:
    """The noise-aware criterion's flags: --imager, --illuminance, --exposure, --noise-samples, --noise-seed."""
    parser.add_argument("--imager", help="judge detection on noisy pixels of this image sensor: a preset (see "
                        "'skinrender imagers') or a TOML file")
    parser.add_argument("--illuminance", type=float, default=None,
                        help="with --imager: lx at the chart (default 500)")
    parser.add_argument("--exposure", default=None, help="with --imager: s, or auto (the calibration white at 0.7 of "
                        "the full well, at most a 1/30 s video frame; default)")
    parser.add_argument("--noise-calibration", type=float, default=None,
                        help="with --imager: the white balance (K, one of the illuminants; default 3300)")
    parser.add_argument("--noise-samples", type=int, default=None,
                        help="with --imager: noisy frames per pixel (default 4)")
    parser.add_argument("--noise-seed", type=int, default=None, help="with --imager: the noise seed (default 0)")


NOISE_FLAGS = ("noise_calibration", "noise_samples", "noise_seed")


def noisy_of(args: argparse.Namespace, temperatures=None):
    """
    The :class:`~skinrender.design.noise_aware.NoisySetting` of the flags, or ``None`` without ``--imager``
    (then a ``--noise-*`` flag given is refused, not ignored). The calibration must be one of ``temperatures``
    (K; default the paper's); without ``--noise-calibration`` it is 3300 K where that is one of them.
    """
    from ..constants import TEMPERATURES_PAPER
    from ..design.noise_aware import (NOISE_CALIBRATION_K, NOISE_SAMPLES_MAX, NOISE_SEED_MAX, calibration_index,
                                      noisy_setting)

    imaging = imaging_options(args)  # --imager, --illuminance and --exposure, checked as for renders
    if imaging is None:
        given = [name for name in NOISE_FLAGS if getattr(args, name, None) is not None]
        if given:
            option = f"--{given[0].replace('_', '-')}"
            raise SkinrenderError(f"{option} goes with --imager (the noisy criterion)", flag=option)
        return None
    samples = 4 if args.noise_samples is None else integer_in(args.noise_samples, "--noise-samples", 1,
                                                              NOISE_SAMPLES_MAX)
    seed = 0 if args.noise_seed is None else integer_in(args.noise_seed, "--noise-seed", 0, NOISE_SEED_MAX)
    temperatures = TEMPERATURES_PAPER if temperatures is None else temperatures
    calibration = args.noise_calibration
    if calibration is None:
        calibration = NOISE_CALIBRATION_K
        if NOISE_CALIBRATION_K not in list(temperatures):
            raise SkinrenderError(f"--noise-calibration: the default {NOISE_CALIBRATION_K:g} K is not one of the "
                                  "illuminants; give one of them", flag="--noise-calibration")
    flag("--noise-calibration", calibration_index, temperatures, calibration)
    return flag("--imager", noisy_setting, imaging["imager_"], imaging["illuminance_lux"], imaging["exposure"],
                calibration, samples, seed)


def add_parsers(commands) -> None:
    """Add the parsers of search, design."""
    p = commands.add_parser("search", run=command_search,
                            help="Stage 3: gamut volumes of every sensor triplet (Tables 2–5)")
    p.add_argument("--sensor", required=True, type=float,
                   help="the paper's sensor: " + SENSOR_RULE)
    p.add_argument("--slope", type=float, default=None,
                   help="gbell slope b (default 2; the paper does not give it; the impulse has none)")
    p.add_argument("--positions", default="400:700:10",
                   help="peak positions START:END:STEP in nm (default 400:700:10: 31 positions, 4495 triplets)")
    add_search(p)
    p.add_argument("--csv", help="write every triplet's volumes (output units³) and ratios to this CSV file")
    p.add_argument("--detection", action="store_true",
                   help="also rank triplets by detection: the share of Munsell chromaticities inside the skin "
                   "locus (false-positive rate at 100 %% skin acceptance), per calibration (JSON min_fpr)")
    from ..design.optimise import OBJECTIVES
    from ..design.search import SEARCH_METHODS

    p.add_argument("--method", default="fast", choices=list(SEARCH_METHODS),
                   help="fast (hull vertices only, exact; default) or naive (Qhull on every full point set)")
    add_noisy(p)
    p.add_argument("--max-triplets", type=int, default=1_000_000,
                   help="refuse searches of more triplets than this (default 1 000 000; the 5 nm grid has 35 990; "
                   "the estimate of the time is printed with the refusal)")
    add_max_minutes(p, "the triplets (× --noise-samples with --imager)")
    p.add_argument("--tie-tolerance", type=float, default=1e-9,
                   help="relative difference under which two values tie (default 1e-9); ties are all listed")
    p.add_argument("--illuminants", default="paper",
                   help="illuminant set: 'paper' (the ten, default) or comma-separated kelvin")
    add_grid(p, named_sets=True)
    add_common(p)

    p = commands.add_parser("design", run=command_design,
                            help="optimise a gbell camera's peaks off the grid (derivative-free, several starts)")
    add_noisy(p)
    p.add_argument("--objective", choices=list(OBJECTIVES), default="detection",
                   help="detection: Munsell false-positive rate in the skin locus (default); ratio: skin/Munsell "
                   "all-calibration gamut volume")
    p.add_argument("--sensor", type=float, default=9, help="gbell sensor N (FWHM N·10 nm) of the start (default 9)")
    p.add_argument("--slope", type=float, default=2.0, help="gbell slope b of the start (default 2)")
    p.add_argument("--free-shape", action="store_true", help="also optimise the shared FWHM (nm) and slope")
    p.add_argument("--starts", default="450,540,610;420,550,680;480,560,640",
                   help="starting peak triplets in nm, ';'-separated (default three)")
    p.add_argument("--evaluations", type=int, default=150, help="objective evaluations per start (default 150)")
    p.add_argument("--skin", default="skin", help="skin set (default skin)")
    p.add_argument("--munsell", default="munsell", help="Munsell set (default munsell)")
    add_max_minutes(p, "the starts × --evaluations (× --noise-samples with --imager)")
    add_common(p)


def _row_text(row: dict) -> str:
    kelvin = "all calibrations" if row["temperature_K"] is None else f"{row['temperature_K']:g} K"
    return f"{' '.join(f'{v:g}' for v in row['triplet'])} nm, {kelvin}: {row['value']:.6g}"


def command_search(args: argparse.Namespace) -> None:
    from ..datasets import reflectances
    from ..model.stage1 import illuminant_set
    from ..design.bank import positions_grid, sensor_bank
    from ..design.search import search
    from ..model.camera import sensor_curves
    from ..studies.paper.unknowns import check_positions

    check_output(args.csv, "--csv", (".csv",))
    if not (math.isfinite(args.tie_tolerance) and args.tie_tolerance >= 0):
        raise SkinrenderError(f"--tie-tolerance must be a finite relative difference ≥ 0, got {args.tie_tolerance}",
                              flag="--tie-tolerance")
    max_triplets = integer_in(args.max_triplets, "--max-triplets", 1)
    grid = grid_of(args)
    skin = flag("--skin", reflectances, args.skin, extrapolation=args.extrapolation)
    munsell = flag("--munsell", reflectances, args.munsell, extrapolation=args.extrapolation)
    rule = None if args.extrapolation == "refuse" else args.extrapolation  # named sets take it too, as in reproduce
    skin_values = flag("--skin", skin.on, grid, rule)
    munsell_values = flag("--munsell", munsell.on, grid, rule)
    if isinstance(args.illuminants, str) and args.illuminants.strip().lower() == "auto":
        raise SkinrenderError("--illuminants: 'auto' (Stage 1 for a camera) is for reproduce and stage1; "
                              "search takes 'paper' or comma-separated kelvin", flag="--illuminants")
    temperatures = flag("--illuminants", illuminant_set, args.illuminants)
    positions = flag("--positions", positions_grid, args.positions)
    if not (math.isfinite(args.sensor) and args.sensor > 0):
        raise SkinrenderError(f"--sensor must be {SENSOR_RULE}, got {args.sensor}", flag="--sensor")
    slope = 2.0 if args.slope is None else args.slope
    if not (math.isfinite(slope) and slope > 0):
        raise SkinrenderError(f"--slope must be a finite number > 0 (the gbell slope b), got {slope}", flag="--slope")
    if args.workers is not None:
        from ..execution import check_workers

        check_workers(args.workers)
    flag("--positions", sensor_curves, positions, grid, None if args.sensor == 1 else args.sensor * 10.0, slope)
    check_positions(positions, grid)  # inside the grid, as reproduce checks them
    flag("--illuminants", sensor_bank, args.sensor, skin_values[:1], positions[:3], temperatures, slope,
         grid=grid)
    noisy = noisy_of(args, temperatures)
    check_search_time(args, positions.size, noisy, max_triplets)
    check_dask(args)
    result = flag({"positions": "--positions", None: None}, search,
        args.sensor, skin_values, munsell_values, args.positions, temperatures, slope, grid=grid,
        method=args.method, workers=args.workers, dask=args.dask,
        progress=None if args.quiet else sys.stderr, label=f"sensor {args.sensor:g}", detection=args.detection,
        max_triplets=max_triplets, noisy=noisy,
    )
    if args.csv is not None:
        result.to_csv(args.csv, "--csv")
    best = result.table(args.tie_tolerance)
    document = {
        "sensor": args.sensor,
        "slope": slope,
        "positions": result.positions.tolist(),
        "triplets": int(len(result.triplets)),
        "illuminants_K": result.temperatures.tolist(),
        "skin": skin.name,
        "munsell": munsell.name,
        "method": result.method,
        "hull_kernel": result.info["hull_kernel"],
        **({"noisy": {k: result.info[k] for k in ("imager", "illuminance_lux", "exposure", "calibration_K",
                                                  "noise_samples", "noise_seed", "tpr_min")}}
           if result.noisy is not None else {}),
        "workers": result.workers,
        **best,
        "elapsed_s": result.elapsed_s,
        "csv": args.csv,
        "notes": search_notes(result, best, None if args.sensor != 1 else args.slope)
        + extrapolation_notes((("--skin", skin), ("--munsell", munsell)), grid, args.extrapolation),
    }
    lines = [f"sensor {args.sensor:g}: {len(result.triplets)} triplets in {result.elapsed_s:.1f} s "
             f"({result.method}, {result.workers} workers); volumes in output units³"]
    for key, label in (("max_skin", "max skin gamut"), ("max_munsell", "max Munsell gamut"),
                       ("min_ratio", "min skin/Munsell ratio"), ("min_fpr", "min false-positive rate"),
                       ("min_noisy_fpr", "min false-positive rate on noisy pixels (TPR ≥ 0.9)")):
        if key in best:
            lines += [f"{label}:"] + [f"  {_row_text(row)}" for row in best[key]]
    lines += [f"note: {note}" for note in document["notes"]]
    emit(args, document, "\n".join(lines))


def check_search_time(args: argparse.Namespace, positions: int, noisy, max_triplets: int) -> None:
    """
    Refuse a search whose estimated time (every triplet, and its noise samples with ``--imager``, at the measured
    rates on the cores that will run it) exceeds ``--max-minutes``; more triplets than ``--max-triplets`` are the
    search's own refusal, with its count cap.
    """
    from ..design.noise_aware import SECONDS_PER_NOISY_SAMPLE
    from ..design.search import SECONDS_PER_TRIPLET
    from ..execution import check_workers

    count = positions * (positions - 1) * (positions - 2) // 6
    if count > max_triplets:
        return
    cores = min(check_workers(args.workers), os.cpu_count() or 1) if args.dask is None else 1
    each = SECONDS_PER_TRIPLET + (0 if noisy is None else noisy.samples * SECONDS_PER_NOISY_SAMPLE)
    check_work(count * each / cores, "--positions" if noisy is None else "--noise-samples",
               f"{count} triplets" + ("" if noisy is None else f" × {noisy.samples} noise samples")
               + f" on {cores} core{'s' * (cores != 1)}", args.max_minutes,
               fewer="use fewer positions" + ("" if noisy is None else " or --noise-samples"))


def extrapolation_notes(sets, grid, rule: str) -> list[str]:
    """One note per reflectance set (``(option, SpectralSet)``) that ``--extrapolation`` ``rule`` extended to the
    ``grid`` (nm): it was measured over less (nothing is extrapolated without a word)."""
    notes = []
    for option, spectra in sets:
        low, high = float(spectra.wavelengths[0]), float(spectra.wavelengths[-1])
        if rule != "refuse" and (low > grid.start or high < grid.end):
            notes.append(f"{option} {spectra.name}: measured over {low:g}–{high:g} nm, extrapolated "
                         f"('{rule}') to the grid {grid.start:g}–{grid.end:g} nm")
    return notes


def search_notes(result, best: dict, impulse_slope: float | None) -> list[str]:
    """
    What a search's tables do not show by themselves: a ``--slope`` given for the impulse (which has none), gamuts
    that are all degenerate (zero volume), an ``auto`` exposure capped at a video frame, and a noisy criterion
    that no triplet meets.
    """
    import numpy as np

    notes = []
    if impulse_slope is not None:
        notes.append(f"--slope {impulse_slope:g} does not apply: the impulse sensor (--sensor 1) has no slope")
    for name, label in (("skin", "skin"), ("munsell", "Munsell")):
        volumes = getattr(result, name)
        for columns, cases in ((slice(0, -1), "one-calibration"), (slice(-1, None), "all-calibration")):
            if volumes.size and not np.any(volumes[:, columns] > 0):
                notes.append(f"every {cases} {label} gamut has zero volume (degenerate: a --grid too coarse for "
                             "the sensors, channels that coincide, or spectra all alike); the tables list every "
                             f"triplet as tied, and min_ratio has no {cases} row: the ratio is undefined there")
    if result.info.get("exposure_note"):
        notes.append(result.info["exposure_note"])
    if result.noisy is not None and not best.get("min_noisy_fpr"):
        notes.append(f"no triplet keeps a noisy TPR ≥ {result.info['tpr_min']:g}: the skin leaves its locus on "
                     "noisy pixels (for instance too little light, or pixels clipped at the full well by a long "
                     "--exposure)")
    return notes


DESIGN_SECONDS_PER_EVALUATION = 0.16
"""One evaluation of the detection objective on noise-free pixels, s (``design --evaluations`` 5 vs 40, one start,
2-core AMD EPYC VM shared with other jobs)."""

DESIGN_SECONDS_PER_NOISE_SAMPLE = 0.015
"""What each ``--noise-samples`` adds to an evaluation with ``--imager``, s (4 vs 64 samples, same machine)."""


def command_design(args: argparse.Namespace) -> None:
    from ..datasets import reflectances
    from ..design.optimise import noisy_report, optimise_camera
    from ..spectra import GRID_DEFAULT

    try:
        starts = [[float(v) for v in part.split(",")] for part in args.starts.split(";")]
    except ValueError:
        starts = []
    if not starts or any(len(s) != 3 for s in starts):
        raise SkinrenderError("--starts must be triplets of nm separated by ';', e.g. 450,540,610;420,550,680",
                              flag="--starts")
    grid = GRID_DEFAULT

    skin, munsell = flag("--skin", reflectances, args.skin), flag("--munsell", reflectances, args.munsell)
    if not (math.isfinite(args.sensor) and args.sensor > 0):
        raise SkinrenderError(f"--sensor must be a gbell number N > 0 (FWHM N·10 nm), got {args.sensor}",
                              flag="--sensor")
    noisy = noisy_of(args)
    if noisy is not None:  # noisy pixels go with an objective that takes them
        from ..design.optimise import OBJECTIVES
        from ..methods import takes

        if not takes(OBJECTIVES[args.objective], "noisy"):
            noisy_ones = " or ".join(name for name, each in OBJECTIVES.items() if takes(each, "noisy"))
            raise SkinrenderError(f"--imager goes with --objective {noisy_ones} (noisy pixels), not "
                                  f"{args.objective}", flag="--imager")
    evaluations = len(starts) * max(int(args.evaluations), 0)
    each = DESIGN_SECONDS_PER_EVALUATION + (0 if noisy is None else noisy.samples * DESIGN_SECONDS_PER_NOISE_SAMPLE)
    check_work(evaluations * each, "--evaluations", f"{len(starts)} starts × {args.evaluations} evaluations",
               args.max_minutes, fewer="ask for fewer --evaluations or --starts")
    # the argument at fault by the flag the user gave it (its error's role)
    result = flag({"starts": "--starts", "max_evaluations": "--evaluations", "slope": "--slope", "fwhm": "--sensor"},
                  optimise_camera, args.objective, skin.on(grid), munsell.on(grid), starts, args.sensor * 10.0,
                  args.slope, args.free_shape, args.evaluations, noisy=noisy)
    document = {"objective": args.objective, "camera": result.camera_spec, "peaks": result.peaks.tolist(),
                "fwhm_nm": result.fwhm, "slope": result.slope, "value": result.value, "starts": result.starts,
                "method": "Nelder-Mead (derivative-free)",
                **({} if noisy is None else {"noisy": {"imager": noisy.imager.name, "illuminance_lux":
                                                       noisy.illuminance_lux, "exposure": noisy.exposure}})}
    if noisy is not None:  # what the value stands for on noisy pixels, and what was capped
        document["noisy"].update(noisy_report(result, skin.on(grid), munsell.on(grid), noisy))
        document["notes"] = document["noisy"].pop("notes")
    lines = [f"{args.objective}: best {result.camera_spec} = {result.value:.5g}"]
    shown = lambda value: "undefined" if value is None else f"{value:.5g}"  # noqa: E731
    lines += [f"  start {s['start']} ({shown(s['start_value'])}) -> {[round(p, 1) for p in s['peaks']]} "
              f"({shown(s['value'])})" for s in result.starts]
    lines += [f"note: {note}" for note in document.get("notes", [])]
    emit(args, document, "\n".join(lines))
