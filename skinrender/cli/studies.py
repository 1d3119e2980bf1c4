"""The paper's studies and benchmarks: ``reproduce``, ``table1``, ``bench`` (``bench rank``: :mod:`skinrender.cli.ranking`'s)."""

from __future__ import annotations

import argparse
import sys

from ..constants import SENSOR_RULE
from ..errors import SkinrenderError
from ..workload import check_work
from ..files import write_output
from .common import (HELP_CAMERA, add_common, add_max_minutes, add_grid, add_search, check_output, flag, integer_in,
                     emit, positive_number, table)
from .preflight import check_dask
from .ranking import command_bench_rank


def _g(value) -> str:
    return "—" if value is None else f"{value:.2g}"


def _spp(value) -> str:
    return "—" if value is None else str(value)


def _or_default(args: argparse.Namespace, dest: str, defaults: dict | None = None):
    """The flag ``dest`` where given, else its default (from ``defaults``, by default :data:`BENCH_DEFAULTS`)."""
    value = getattr(args, dest, None)
    return (BENCH_DEFAULTS if defaults is None else defaults)[dest] if value is None else value


def size_text(size) -> str:
    return f"{size[0]}×{size[1]} px"


POSITIONS_DEFAULT = "400:700:10"
"""``reproduce --positions`` when not given (the paper's 31 peaks)."""


def add_parsers(commands) -> None:
    """Add the parsers of reproduce, table1, bench."""
    p = commands.add_parser("reproduce", run=command_reproduce,
                            help="the paper's Figs. 3–7 (PNG) and Tables 2–5 (Markdown, CSV), with "
                            "their matches with the paper; --sweep: the tables under each choice of the paper's unknowns")
    p.add_argument("-o", "--output", required=True,
                   help="output folder: new, empty or an earlier reproduce folder (replaced only when the run completes)")
    p.add_argument("--sensors", default="1,3,5,7,9,11,13,15",
                   help="comma-separated sensor numbers, each " + SENSOR_RULE + " (default 1,3,…,15)")
    p.add_argument("--positions", help=f"peak positions START:END:STEP in nm (default {POSITIONS_DEFAULT})")
    p.add_argument("--camera", default="Nikon 5100 (NPL)",
                   help="Stage 2 camera for Figs. 3–7 (the paper's Sony is not public); " + HELP_CAMERA)
    p.add_argument("--slope", type=float, default=2.0, help="gbell slope b, not given by the paper (default 2)")
    add_grid(p, named_sets=True)
    p.add_argument("--illuminants", default="paper", help="illuminant set: 'paper' (its ten, default), 'auto' "
                   "(Stage 1 for --stage1-camera) or comma-separated kelvin")
    p.add_argument("--stage1-camera", help="camera of --illuminants auto (default: --camera); " + HELP_CAMERA)
    p.add_argument("--no-figures", action="store_true", help="the tables only (no Stage 2 figures)")
    p.add_argument("--sweep", action="store_true",
                   help="tables only, under each value of one unknown at a time (slope 1–6; grids 400:700:1/5, "
                        "380:780:1/5; skin sets; Munsell sets; Stage 1 illuminants of every camera), then the best "
                        "values of the most telling unknowns combined; writes sweep.csv and sweep.md")
    p.add_argument("--sweep-positions", help="peak positions of the sweep (default: --positions; 400:700:20 for a "
                   "quick look)")
    p.add_argument("--sweep-combine", type=int, default=None,
                   help="how many unknowns the sweep combines, the most telling first (default 3)")
    add_max_minutes(p, "the sensors × the triplets of --positions (--sweep: of each setting)")
    p.add_argument("--sweep-values", type=int, default=None,
                   help="how many best values of each combined unknown are combined, beside the default (default 1)")
    add_search(p)
    add_common(p)

    p = commands.add_parser("table1", run=command_table1,
                            help="the paper's Table 1: NCC differences, render vs model, Macbeth under A and H")
    p.add_argument("--camera", default="gbell:9@450,540,610", help=HELP_CAMERA)
    p.add_argument("--spp", type=int, default=256, help="samples per pixel (default 256)")
    p.add_argument("--seed", type=int, default=0, help="sampler seed (default 0)")
    p.add_argument("--tolerance", metavar="NCC", help="the verdict's tolerance: an absolute NCC difference in (0, 1) "
                   "every kept patch's rendered NCC must be shown within of Eq. 4's, at family-wise 95 %% confidence "
                   "(default 0.001); exit status 0 pass, 1 fail, 3 inconclusive")
    add_common(p)

    p = commands.add_parser("bench", run=command_bench,
                            help="speed and accuracy figures; calibration: the validation's false-alarm "
                            "rates over seeds; validate: seconds, bound and false alarms per spp")
    p.add_argument("what", choices=["analytic", "search", "sweep", "render", "calibration", "validate", "rank"],
                   help="which benchmark (rank: the issue's ranking, against 10 minutes on 2 cores)")
    p.add_argument("--quick", action="store_true", help="render: a short curve (spp 4…256, one variant); search: "
                   "only the 20 nm search in full (10 and 5 nm estimated from --sample), no sweep; rank: small")
    p.add_argument("--plot", help="render: write the error-against-time plot (log–log) to this PNG; calibration: the "
                   "observed false-alarm rates with their 95 %% intervals against the nominal α")
    p.add_argument("--repeat", type=int, help="analytic: timed repetitions, best kept (default 3)")
    p.add_argument("--sensor", type=float, help="search: sensor number (default 9)")
    p.add_argument("--sample", type=int, help="search: triplets timed per method (default 20)")
    p.add_argument("--workers", type=int, help="search, sweep: processes (default: every core)")
    p.add_argument("--positions",
                   help="sweep: peak positions START:END:STEP nm of the timed sweep (default 400:700:20)")
    p.add_argument("--scene", help="render: a face scene (face or a .toml with [camera] and [mesh]) to time the "
                   "face at each level of physics instead of the charts; calibration, validate: the chart (default "
                   "macbeth; a face is refused until its checks' calibration is registered); calibration: 'ptc' "
                   "runs the photon transfer's fits over --seeds sensor seeds (with --imager)")
    p.add_argument("--size", metavar="PX", help="render --scene: image side, pixels (default 256; --quick 64)")
    from ..studies.benchmarks.bench_face import LEVELS_BENCH

    p.add_argument("--levels", help="render --scene: comma-separated levels of physics (default "
                   + ",".join(LEVELS_BENCH) + ")")
    p.add_argument("--spp-list", metavar="N,N,…",
                   help="render --scene: samples per pixel of the curve (default 4,16,64,256; --quick 4,16,64); "
                   "validate: the spp of the rows (default 4,16,64,256)")
    p.add_argument("--reference-spp", metavar="N",
                   help="render --scene: spp of each level's reference render (default 4 × the largest of --spp-list)")
    add_max_minutes(p, "analytic: --repeat; search: --sample; sweep: the triplets of --positions; calibration: "
                    "--seeds × --spp; validate: --seeds × --spp-list; render --scene: the levels × --spp-list × "
                    "--size²")
    from .calibration import add_bench_arguments
    from .spectral_commands import add_bench_spectral_arguments

    add_bench_arguments(p)
    add_bench_spectral_arguments(p)
    add_common(p)


SWEEP_FLAGS = {"sweep_positions": None, "sweep_combine": 3, "sweep_values": 1}
"""``reproduce`` flags of ``--sweep`` only (``None`` when not given), with their defaults."""


def check_sweep_flags(args: argparse.Namespace) -> None:
    """
    ``--sweep-*`` without ``--sweep``, and ``--positions`` beside ``--sweep-positions`` (the sweep would use
    one of the two), refused with one line naming the flag rather than silently ignored.
    """
    given = [dest for dest in SWEEP_FLAGS if getattr(args, dest) is not None]
    if not args.sweep and given:
        option = f"--{given[0].replace('_', '-')}"
        raise SkinrenderError(f"{option} goes with --sweep", flag=option)
    if args.sweep and args.sweep_positions is not None and args.positions is not None:
        raise SkinrenderError("--positions: the sweep takes its peaks from --sweep-positions; give one of the two",
                              flag="--positions")


def command_reproduce(args: argparse.Namespace) -> None:
    progress = None if args.quiet else sys.stderr
    if args.stage1_camera is not None and args.illuminants.strip().lower() != "auto":
        raise SkinrenderError(f"--stage1-camera is the camera of --illuminants auto; got --illuminants {args.illuminants!r}",
                              flag="--stage1-camera")
    check_sweep_flags(args)
    check_dask(args)
    if args.sweep:
        from ..studies.paper.sweep import reproduce_sweep
        from ..studies.paper.unknowns import Setting

        base = Setting(args.slope, args.grid, args.skin, args.munsell, args.illuminants,
                       args.stage1_camera or args.camera, args.extrapolation)
        positions, named = ((args.sweep_positions, "--sweep-positions") if args.sweep_positions is not None
                            else (POSITIONS_DEFAULT if args.positions is None else args.positions, "--positions"))
        result = reproduce_sweep(args.output, args.sensors, positions, base, positions_flag=named,
                                 combine=_or_default(args, "sweep_combine", SWEEP_FLAGS),
                                 values_per_unknown=_or_default(args, "sweep_values", SWEEP_FLAGS),
                                 workers=args.workers, dask=args.dask, progress=progress,
                                 max_minutes=args.max_minutes)
        rows = [[r["setting"], r["unknown"], f"{r['exact']}/{r['total']}", str(r["within_step"]), f"{r['seconds']:.1f}"]
                for r in result["sweep"]]
        text = (table(rows, ["setting", "changed", "exact", "within 10 nm", "s"])
                + f"\nsweep: {len(rows)} settings in {result['elapsed_s']:.1f} s; wrote "
                + ", ".join(result["artifacts"]) + "".join(f"\nnote: {n}" for n in result["notes"]))
        emit(args, result, text)
        return
    from ..studies.paper.reproduce import reproduce, summary_text

    result = reproduce(
        args.output, args.sensors, POSITIONS_DEFAULT if args.positions is None else args.positions, args.camera,
        args.skin, args.munsell, args.slope, args.grid,
        workers=args.workers, dask=args.dask, progress=progress, illuminants=args.illuminants,
        stage1_camera=args.stage1_camera, extrapolation=args.extrapolation, figures=not args.no_figures,
        max_minutes=args.max_minutes,
    )
    emit(args, result, summary_text(result))


def command_table1(args: argparse.Namespace) -> None:
    from ..model.camera import camera
    from ..studies.paper.tables import table1
    from .common import SPP_MAX, check_seed

    from ..evaluation.verdict import EXIT_STATUS
    from ..studies.paper.tables import TABLE1_TOLERANCE

    from ..rendering.settings import RenderSettings

    spp = integer_in(args.spp, "--spp", 1, SPP_MAX)  # each flag checked on its own, so that its error names it
    settings = RenderSettings(spp=spp, seed=check_seed(args.seed))
    tolerance = TABLE1_TOLERANCE if args.tolerance is None else positive_number(args.tolerance, "--tolerance", "NCC")
    from ..rendering.agreement import TOLERANCE_MIN

    if not TOLERANCE_MIN <= tolerance < 1:  # below float32's resolution: 1e-320 ended in an internal error
        raise SkinrenderError(f"--tolerance must be an NCC difference in [{TOLERANCE_MIN:.3g}, 1) (its lower end is "
                              f"float32's resolution), got {args.tolerance!r}", flag="--tolerance")
    cam = flag("--camera", camera, args.camera)
    result = flag({"spp": "--spp", None: "--camera"}, table1, cam, settings, tolerance=tolerance)
    rows = [[r["model"], r["case"], f"{r['mean']:.5f}", f"{r['std']:.5f}"] for r in result["rows"]]
    verdict = result["verdict"]
    result["exit_status"] = EXIT_STATUS[verdict["verdict"]]
    text = (f"Table 1 for {result['camera']} ({len(result['patches'])} Macbeth patches with 90 % of values in "
            f"10–245; render at {result['spp']} spp as the real camera):\n"
            + table(rows, ["model", "case", "mean |ΔNCC|", "std"])
            + f"\nverdict (Eq. 4 against the render, NCC within {tolerance:g}): "
            f"{verdict['verdict'].upper().replace('_', ' ')} — {verdict['reason']}; bound {result['bound']:.2g}"
            f"\n  test: {verdict['test']}"
            f"\ndifference, Eq. 4: {result['difference']['verdict']} — {result['difference']['reason']}"
            f"\ndifference, Eq. 1 with WP: {result['difference_eq1']['verdict']} — {result['difference_eq1']['reason']}"
            f"\nexit status {result['exit_status']}")
    emit(args, result, text)
    if result["exit_status"]:
        raise SystemExit(result["exit_status"])


FACE_BENCH_FLAGS = ("levels", "spp_list", "reference_spp")
"""``bench`` flags that go with ``render --scene``."""

BENCH_FLAGS = {"repeat": ("analytic",), "sensor": ("search",), "sample": ("search",), "positions": ("sweep",),
               "workers": ("search", "sweep", "rank"), "quick": ("render", "search", "rank"), "plot": ("render", "calibration"),
               "scene": ("render", "calibration", "validate"), "size": ("render", "calibration"), "spectral": ("render",), "cameras": ("render",),
               "max_minutes": ("analytic", "search", "sweep", "calibration", "validate", "render")}
"""``bench`` flags of one or a few benchmarks (``dest``: the benchmarks they go with); the face's are
:data:`FACE_BENCH_FLAGS`, the verdict benchmarks' :data:`skinrender.cli.calibration.VERDICT_BENCH_FLAGS`."""

BENCH_DEFAULTS = {"repeat": 3, "sensor": 9.0, "sample": 20, "positions": "400:700:20"}
"""Defaults of the benchmarks' own flags (left ``None`` by the parser so that a given flag is seen)."""


def refuse_foreign_flags(args: argparse.Namespace) -> None:
    """
    Refuse (one line naming it) the first ``bench`` flag given that the benchmark ``args.what`` does not take
    (``--plot`` with ``--scene``: refused by :func:`face_bench_options`).
    """
    from .calibration import VERDICT_BENCH_FLAGS

    face = getattr(args, "scene", None) is not None and args.what == "render"
    for dest, benches in {**BENCH_FLAGS, **VERDICT_BENCH_FLAGS}.items():
        value = getattr(args, dest, None)
        if value is None or value is False or dest == "scene":
            continue
        name = "--" + dest.replace("_", "-")
        if args.what not in benches:
            goes = " or ".join(f"'bench {b}'" for b in benches)
            raise SkinrenderError(f"{name} goes with {goes}, not 'bench {args.what}"
                                  + (" --scene'" if face else "'"), flag=name)


def _integers(text: str, name: str, high: int, many: bool = True) -> list[int]:
    """Comma-separated integers in [1, ``high``] (one unless ``many``), or a one-line error naming ``name``."""
    values = []
    parts = str(text).split(",")
    for part in parts:
        try:
            value = int(part.strip())
        except ValueError:
            value = 0
        if not 1 <= value <= high or (len(parts) > 1 and not many):
            what = "comma-separated integers" if many else "an integer"
            raise SkinrenderError(f"{name} must be {what} in [1, {high}], got {text!r}", flag=name)
        values.append(value)
    return values


def face_bench_options(args: argparse.Namespace) -> dict | None:
    """
    The face bench's options from ``bench render --scene …`` (checked, one-line errors naming the flag), or
    ``None`` for the chart bench; the face flags without ``--scene`` are refused.
    """
    given = [name for name in (*FACE_BENCH_FLAGS, "size") if getattr(args, name, None) is not None]
    if args.scene is not None and args.what != "render":
        raise SkinrenderError(f"--scene goes with 'bench render', 'bench calibration' or 'bench validate', not "
                              f"'bench {args.what}'", flag="--scene")
    refuse_foreign_flags(args)
    if args.scene is None:
        if given:
            option = f"--{given[0].replace('_', '-')}"
            raise SkinrenderError(f"{option} goes with 'bench render --scene SCENE' (a face)", flag=option)
        if args.what == "render" and args.max_minutes is not None:
            raise SkinrenderError("--max-minutes caps the face bench (bench render --scene SCENE); the charts' render "
                                  "bench does a fixed amount of work", flag="--max-minutes")
        return None
    from ..rendering.face.scene import load_face_scene
    from ..rendering.kinds import FACE
    from ..rendering.renderer import SAMPLES_MAX
    from ..studies.benchmarks.bench_face import LEVELS_BENCH, SIZE_BENCH, SPPS_BENCH
    from .common import SPP_MAX, flag
    from .face import SIZE_MAX, levels_of

    if not FACE.owns(args.scene):
        raise SkinrenderError(f"--scene: the render bench times a face scene (face or a .toml with [camera] and "
                              f"[mesh]); the charts' bench runs without --scene, got {args.scene!r}", flag="--scene")
    if args.plot:
        raise SkinrenderError("--plot draws the charts' curve; the face bench (--scene) prints its table only",
                              flag="--plot")
    scene = flag("--scene", load_face_scene, args.scene)
    size = (_integers(args.size, "--size", SIZE_MAX, many=False)[0] if args.size is not None
            else 64 if args.quick else SIZE_BENCH)
    spps = (_integers(args.spp_list, "--spp-list", SPP_MAX) if args.spp_list is not None
            else [s for s in SPPS_BENCH if not args.quick or s <= 64])
    if len(set(spps)) < len(spps):
        raise SkinrenderError(f"--spp-list: each spp once, got {args.spp_list!r}", flag="--spp-list")
    reference = (_integers(args.reference_spp, "--reference-spp", SPP_MAX, many=False)[0]
                 if args.reference_spp is not None else 4 * max(spps))
    if reference <= max(spps):
        raise SkinrenderError(f"--reference-spp must be more than the largest of --spp-list ({max(spps)}: the "
                              f"reference must converge further than the curve), got {reference}",
                              flag="--reference-spp")
    for name, spp in (("--reference-spp", reference), ("--spp-list", max(spps))):
        if spp * size * size > SAMPLES_MAX:
            raise SkinrenderError(f"{name}: {spp} spp × {size}² pixels is more than {SAMPLES_MAX} samples a pass",
                                  flag=name)
    levels = levels_of(args.levels if args.levels is not None else ",".join(LEVELS_BENCH))
    for level in levels:  # each level's lights in the scene (mixed needs a fill light)
        flag("--levels", level.lights, scene)
    check_face_bench_work(args, levels, size * size, spps, reference)
    return {"scene": scene, "size": size, "spps": spps, "reference_spp": reference, "levels": levels}


def check_face_bench_work(args: argparse.Namespace, levels: list, pixels: int, spps: list[int],
                          reference: int) -> None:
    """
    Refuse the face bench when its estimate exceeds ``--max-minutes``: per level one reference render at
    ``reference`` spp and, per spp of the curve, a warm-up and a timed render (``2 × Σ spps``), all of ``pixels``
    pixels (:func:`~skinrender.studies.face.sweep.estimate_seconds` on every core, each level at its own rate:
    ``subsurface-volume`` is far slower), naming ``--spp-list``.
    """
    import os

    from ..studies.face.sweep import estimate_seconds

    each = reference + 2 * sum(spps)
    check_work(estimate_seconds(len(levels), pixels, each, os.cpu_count() or 1, levels), "--spp-list",
               f"{len(levels)} levels × ({reference} + 2 × {sum(spps)}) spp × {pixels} pixels", args.max_minutes,
               fewer="lower --spp-list, --reference-spp or --size")


BENCH_ANALYTIC_SECONDS = 4.0
"""One ``bench analytic`` repetition (both routes), s: the estimates' rate, from ``--repeat 1`` against ``4``
(docs/speed.md, "The rates behind the estimates")."""

BENCH_SEARCH_SECONDS_PER_SAMPLE = 0.33
"""What each ``bench search --sample`` triplet adds, s: the estimates' rate, from ``--quick --sample 20``
against ``200`` with ``--workers 1`` (docs/speed.md, "The rates behind the estimates")."""


def _bench_camera(args: argparse.Namespace) -> str:
    """``bench render --camera`` checked (its curves on the default grid), or the default gbell:9@450,540,610."""
    if args.camera is None:
        return "gbell:9@450,540,610"
    return flag("--camera", _camera_spec, args.camera)


def _camera_spec(spec: str) -> str:
    """``spec`` when it names a camera whose curves cover the default grid (else the camera's own error)."""
    from ..model.camera import camera
    from ..spectra import GRID_DEFAULT

    camera(spec).sensitivities(GRID_DEFAULT)
    return spec


def command_bench(args: argparse.Namespace) -> None:
    from ..studies.benchmarks.bench import bench_analytic, bench_search, bench_sweep

    if args.what == "rank":  # bench's other flags refused there
        return command_bench_rank(args, refuse_foreign_flags)
    if args.what in ("calibration", "validate"):
        from .calibration import command_bench_verdicts
        from .common import SPP_MAX

        refuse_foreign_flags(args)
        for name in FACE_BENCH_FLAGS:
            if getattr(args, name, None) is not None and not (name == "spp_list" and args.what == "validate"):
                raise SkinrenderError(f"--{name.replace('_', '-')} goes with 'bench render --scene SCENE' (a face)"
                                      + (" or 'bench validate'" if name == "spp_list" else ""),
                                      flag=f"--{name.replace('_', '-')}")
        spps = None if args.spp_list is None else _integers(args.spp_list, "--spp-list", SPP_MAX)
        if spps is not None and len(set(spps)) < len(spps):
            raise SkinrenderError(f"--spp-list: each spp once, got {args.spp_list!r}", flag="--spp-list")
        return command_bench_verdicts(args, spps)
    if args.what == "render" and args.spectral:
        from .spectral_commands import command_bench_spectral

        refuse_foreign_flags(args)
        return command_bench_spectral(args)
    if args.cameras is not None:
        raise SkinrenderError("--cameras goes with 'bench render --spectral'", flag="--cameras")
    face = face_bench_options(args)
    if face is not None:
        from ..studies.benchmarks.bench_face import bench_face

        result = bench_face(camera_spec=_bench_camera(args), levels=face["levels"], spps=face["spps"],
                            size=face["size"], reference_spp=face["reference_spp"], scene=face["scene"],
                            progress=lambda line: print(line, file=sys.stderr))
        rows = [[r["level"], r["spp"], f"{r['seconds']:.3f}", _g(r["skin_ncc_error"]), _g(r["skin_ncc_rms"])]
                for r in result["curve"]]
        presets = [[level, *(_spp(p.get(name)) + ("*" if name in p.get("extrapolated", ()) else "")
                             for name in ("draft", "standard", "reference")), _g(p.get("floor")),
                    _spp(p.get("spp_at_floor"))] for level, p in result["presets"].items()]
        extrapolated = any(p.get("extrapolated") for p in result["presets"].values())
        undefined = [f"\nnote: {level} {key}: {reason}" for level, p in result["presets"].items()
                     for key, reason in p.get("undefined", {}).items()]
        text = (f"the face ({result['scene']}) through {result['camera']}, {size_text(result['size'])}, reference "
                f"{result['reference_spp']} spp per level, {result['elapsed_s']:.0f} s in all:\n"
                + table(rows, ["level", "spp", "s", "mean NCC error", "RMS NCC error"])
                + "\npresets (spp reaching RMS " + ", ".join(f"{k} {v:g}" for k, v in result["thresholds"].items())
                + "):\n" + table(presets, ["level", "draft", "standard", "reference", "floor", "spp at floor"])
                + ("\n* extrapolated beyond the measured spp by the error model's fit (not measured)"
                   if extrapolated else "") + "".join(undefined))
        emit(args, result, text)
        return
    if args.workers is not None:  # before any timing starts
        from ..execution import check_workers

        check_workers(args.workers)
    if args.what == "sweep":
        from ..design.bank import SENSORS_PAPER, positions_grid
        from ..studies.paper.unknowns import check_search_work

        where = flag("--positions", positions_grid, _or_default(args, "positions"))
        check_search_work(len(SENSORS_PAPER), where, "--positions", args.max_minutes, args.workers,
                          "each setting's ")
    if args.what == "render":
        from ..studies.benchmarks.bench import bench_render

        plot = check_output(args.plot, "--plot", (".png",))  # before the ~30 s of timing
        result = bench_render(camera_spec=_bench_camera(args), quick=args.quick)
        if args.plot:
            from ..studies.figures import figure_render_curve

            write_output(plot, lambda stream: figure_render_curve(result, stream), "--plot")
            result["plot"] = str(plot)
    elif args.what == "search":
        quick = {"full_steps": (20.0,), "sweep_positions": None} if args.quick else {}
        sample = _or_default(args, "sample")
        if isinstance(sample, int) and sample >= 1:
            check_work(sample * BENCH_SEARCH_SECONDS_PER_SAMPLE, "--sample", f"{sample} sampled triplets per method",
                       args.max_minutes, fewer="ask for a smaller --sample")
        result = bench_search(_or_default(args, "sensor"), _or_default(args, "sample"), workers=args.workers, **quick)
    elif args.what == "sweep":
        result = bench_sweep(_or_default(args, "positions"), workers=args.workers)
    else:
        repeat = _or_default(args, "repeat")
        if isinstance(repeat, int) and repeat >= 1:  # a bad count is refused by the benchmark, naming the flag
            check_work(repeat * BENCH_ANALYTIC_SECONDS, "--repeat", f"{repeat} repetitions", args.max_minutes,
                       fewer="ask for fewer --repeat")
        result = bench_analytic(repeat=repeat)
    text = "\n".join(f"{key}: {value}" for key, value in result.items())
    emit(args, result, text)
