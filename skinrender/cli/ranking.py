"""
``rank``: would Eq. 4 still choose the same camera once the physics is on?
The top ``--top`` triplets of the Stage 3 search (``--sensor``,
``--positions``, ``--slope`` as ``search``) and any ``--camera`` are scored
on rendered faces (``--skin`` × ``--lights`` at each of ``--levels``) and by
Eq. 4 with one score, Youden's J = TPR − FPR, and ranked both ways
(:mod:`skinrender.studies.face.ranking`).

Units: temperatures K, image sides pixels, rates and scores fractions, times s.
"""

from __future__ import annotations

import argparse
import os
import sys

from ..errors import SkinrenderError
from .common import (HELP_CAMERA, SEED_MAX, SPP_MAX, add_common, add_max_minutes, check_output, emit, flag,
                     integer_in, table, variant_of)
from .detection_options import add_skin_set, skin_set_from

__all__ = ["add_parsers", "command_rank", "command_bench_rank", "TOP_DEFAULT", "POSITIONS_DEFAULT"]

TOP_DEFAULT = 10
"""``--top`` unless given: the search's best ten triplets."""

POSITIONS_DEFAULT = "400:700:20"
"""``--positions`` unless given, nm (455 triplets; ``search``'s 10 nm grid has 4495, minutes of detection
criteria)."""

SECONDS_PER_TRIPLET_DETECTION = 0.03
"""One triplet's detection criterion (the Munsell set in its skin locus at every calibration) on one core, s
(measured: 455 triplets in 13 s of CPU, ``search --sensor 9 --positions 400:700:20 --detection``)."""

SECONDS_DETECTION_RATES = 0.3
"""One camera on one scene: its projections through the spectral replicates and its detection rates (its locus,
the noise separation on the half-samples), s (measured ~0.64 s of CPU per camera and scene with renders per camera,
whose renders took about half)."""


HELP_RANK = ("the camera decision under physics: the Stage 3 search's top triplets and any --camera scored on "
             "rendered faces and by Eq. 4 (Youden's J = TPR − FPR) and ranked both ways, per level: Kendall's τ with "
             "its 95 %% interval, the top-k overlap, whether Eq. 4's best camera stays best")
"""``rank``'s help (argparse formats it: a percent sign is written ``%%``)."""


def add_parsers(commands) -> None:
    """Add the parser of rank."""
    from ..studies.face.effects_table import SKIN_TONES
    from ..studies.face.ranking import LEVELS_RANK
    from .face import HELP_SKIN, level_names
    from .face_sweep import LIGHTS_DEFAULT

    p = commands.add_parser("rank", run=command_rank, help=HELP_RANK)
    p.add_argument("--top", metavar="K", default=str(TOP_DEFAULT),
                   help=f"candidates from the Stage 3 search: its best K triplets by Eq. 4's detection criterion "
                   f"(the Munsell false-positive rate in the skin locus; 0: only --camera) (default {TOP_DEFAULT})")
    p.add_argument("--sensor", metavar="N", default="9",
                   help="as search: sensor number (1 = impulse, N ≥ 2: gbell of FWHM N·10 nm) (default 9)")
    p.add_argument("--slope", metavar="B", default="2", help="as search: the gbell slope b (default 2)")
    p.add_argument("--positions", default=POSITIONS_DEFAULT,
                   help=f"as search: peak positions START:END:STEP in nm (default {POSITIONS_DEFAULT})")
    p.add_argument("--camera", action="append", help="a further candidate (repeat the flag); " + HELP_CAMERA)
    p.add_argument("--lights", action="append", metavar="P/C[,P/C…]",
                   help=f"as face-sweep: PREVAILING/CALIBRATION pairs in K (default {LIGHTS_DEFAULT})")
    p.add_argument("--skin", action="append", help="a skin of the face (repeat the flag): "
                   + HELP_SKIN.split(" (default")[0] + "; default light, medium and dark: "
                   + " ".join(SKIN_TONES.values()))
    p.add_argument("--levels", default=",".join(LEVELS_RANK),
                   help=f"comma-separated levels of physics ({level_names()}; effects combine with '+'); default "
                   + ",".join(LEVELS_RANK))
    p.add_argument("--scene", default="face", help="face scene: a bundled name (face) or a .toml path")
    p.add_argument("--size", metavar="PX", default="64", help="image side in pixels (default 64)")
    p.add_argument("--spp", metavar="N", default="16",
                   help="samples per pixel of each scene in all, over 12 replicates whose spread separates the "
                   "renderer's noise (default 16)")
    p.add_argument("--seed", metavar="S", default="0", help="sampler seed of the first replicate (default 0)")
    p.add_argument("--imager", help="image sensor of the noise level: a preset or a TOML (default sony-icx418)")
    p.add_argument("--illuminance", metavar="LUX",
                   help="the key light's illuminance at the face, lx (default: the scene's); only noise sees it")
    p.add_argument("--variant", help="force a Mitsuba variant; default: the fastest that works here")
    p.add_argument("--workers", metavar="N", help="processes (default: every core); 1 renders in this process")
    p.add_argument("--dask", metavar="ADDRESS", help="run on a Dask cluster (scheduler address, tcp://host:8786)")
    p.add_argument("--quiet", action="store_true", help="no progress bar on stderr")
    p.add_argument("--plot", metavar="PNG", help="write rank against rank per level to this PNG")
    add_skin_set(p)
    add_max_minutes(p, "the search's triplets and the candidates × scenes × levels × replicates × --size² × --spp")
    add_common(p)


def _checked(args: argparse.Namespace) -> dict:
    """Every flag checked, before the search and any render."""
    from ..design.bank import positions_grid
    from ..execution import WORKERS_MAX, check_workers
    from ..studies.face.ranking import triplet_camera
    from ..model.camera import camera
    from ..rendering.face.scene import load_face_scene
    from ..spectra import GRID_DEFAULT
    from ..studies.face.effects_table import SKIN_TONES
    from ..studies.face.sweep import estimate_seconds
    from ..rendering.face.limits import REPLICATES
    from ..workload import check_work
    from .common import positive_number
    from .face_inputs import SIZE_MAX, levels_of, noise_sensor_from, refuse_repeated, skins_from
    from .face_sweep import LIGHTS_DEFAULT, light_pairs

    plot = check_output(args.plot, "--plot", (".png",))
    sensor = positive_number(args.sensor, "--sensor", "(1 impulse, N ≥ 2 gbell)")
    slope = positive_number(args.slope, "--slope", "(the gbell slope b)")
    positions = flag("--positions", positions_grid, args.positions)
    count = len(positions) * (len(positions) - 1) * (len(positions) - 2) // 6
    top = integer_in(args.top, "--top", 0)
    if top > count:
        raise SkinrenderError(f"--top: {top} is more than the {count} triplets of --positions {args.positions}",
                              flag="--top")
    extra = []
    for spec in args.camera or []:
        cam = flag("--camera", camera, spec)
        flag("--camera", cam.sensitivities, GRID_DEFAULT)
        extra.append(cam)
    refuse_repeated("--camera", [cam.name for cam in extra])
    if top + len(extra) < 2:
        raise SkinrenderError(f"--top: a ranking needs two or more candidates, got {top} from the search and "
                              f"{len(extra)} --camera", flag="--top")
    pairs = light_pairs(args.lights or [LIGHTS_DEFAULT])
    skins = skins_from(args.skin or SKIN_TONES.values())
    levels = levels_of(args.levels)
    scene = flag("--scene", load_face_scene, args.scene)
    variant_of(args.variant)
    imager, lux = noise_sensor_from(args.imager, args.illuminance, levels)
    size = integer_in(args.size, "--size", 1, SIZE_MAX)
    spp = integer_in(args.spp, "--spp", 1, SPP_MAX)
    seed = integer_in(args.seed, "--seed", 0, SEED_MAX - REPLICATES)
    workers = None if args.workers is None else integer_in(args.workers, "--workers", 1, WORKERS_MAX)
    if args.dask is not None and not str(args.dask).strip():
        raise SkinrenderError("--dask: expected a scheduler address (tcp://host:8786), got an empty one", flag="--dask")
    for cam in extra:
        skin_set_from(args.skin_set, cam, [c for _, c in pairs])
    probe = extra[0] if extra else camera(triplet_camera(sensor, (450, 540, 610), slope))  # the search's kind
    skins_set = skin_set_from(args.skin_set, probe, [c for _, c in pairs])
    cores = min(check_workers(workers), os.cpu_count() or 1) if args.dask is None else os.cpu_count() or 1
    candidates = top + len(extra)
    each = -(-spp // REPLICATES)
    from ..rendering.bands import BANDS_DEFAULT

    renders = len(pairs) * len(skins) * len(levels) * REPLICATES  # spectral: one render serves every candidate
    seconds = (count * SECONDS_PER_TRIPLET_DETECTION * (top > 0)
               + estimate_seconds(renders, size * size, each, 1,
                                  [level for level in levels for _ in range(renders // len(levels))], BANDS_DEFAULT)
               + candidates * len(pairs) * len(skins) * len(levels) * SECONDS_DETECTION_RATES) / cores
    check_work(seconds, "--top", f"{candidates} candidates through {len(pairs) * len(skins)} scenes × {len(levels)} "
               f"levels × {REPLICATES} spectral replicates of {size}×{size} px at {each} spp (and {count} triplets "
               "searched)"
               f" on {cores} core{'s' * (cores != 1)}", args.max_minutes,
               fewer="lower --top, --size or --spp, or name fewer --lights, --skin or --levels")
    return {"top": top, "sensor": sensor, "slope": slope, "positions": args.positions, "extra": extra,
            "lights": pairs, "skins": skins, "levels": levels, "scene": scene, "size": size, "spp": spp,
            "seed": seed, "variant": args.variant, "imager": imager, "illuminance": lux, "workers": workers,
            "dask": args.dask, "skin_set": skins_set, "plot": plot, "estimate_s": seconds}


def _answer(level: dict) -> str:
    same = {True: "yes", False: "NO", None: "undecided"}[level["same_best"]]
    tau, interval = level["kendall_tau"], level["kendall_tau_interval"]
    said = "τ —" if tau is None else f"τ {tau:.2f}" + ("" if interval is None else
                                                        f" [{interval[0]:.2f}, {interval[1]:.2f}]")
    if level["top_k_overlap"] is None:
        return f"{level['level']}: undecided ({level['undefined']['level']})"
    return (f"{level['level']}: {same} ({said}; top-{level['top_k']} overlap {level['top_k_overlap']:.2f}; "
            f"Eq. 4's best {', '.join(level['best_eq4'])}, rendered best {level['best_rendered']})")


def command_rank(args: argparse.Namespace) -> None:
    """The search (``--top`` > 0), the renders and the ranking; every flag checked before the first."""
    from ..studies.face.ranking import rank, search_candidates

    options = _checked(args)
    progress = None if args.quiet else sys.stderr
    print(f"rank: about {options['estimate_s'] / 60:.1f} min (estimated) …", file=sys.stderr)
    from ..model.camera import camera

    cameras = []
    if options["top"]:  # the search's triplets as cameras, parsed once here
        cameras = [camera(spec) for spec in search_candidates(options["top"], options["sensor"], options["positions"],
                                                              options["slope"], options["workers"], options["dask"],
                                                              progress=progress)]
    searched = {c.name for c in cameras}
    cameras += [cam for cam in options["extra"] if cam.name not in searched]
    if len(cameras) < 2:  # only the search tells that a --camera is one of its triplets
        same = ", ".join(cam.name for cam in options["extra"] if cam.name in searched)
        raise SkinrenderError(f"--camera: {same} is the search's own triplet (--top {options['top']}): a ranking needs "
                              "two or more distinct candidates; raise --top or name another --camera", flag="--camera")
    result = rank(cameras, options["lights"], options["skins"], options["levels"], options["size"], options["spp"],
                  options["seed"], options["scene"], options["skin_set"], options["variant"], options["imager"],
                  options["illuminance"], options["workers"], options["dask"], progress,
                  candidates_from={"top": options["top"], "sensor": options["sensor"], "slope": options["slope"],
                                   "positions": options["positions"],
                                   "criterion": "Munsell false-positive rate in the skin locus, mean over "
                                                "calibrations (search --detection)",
                                   "cameras": [cam.name for cam in options["extra"]]})
    document = {**result.document(), "estimate_s": options["estimate_s"]}
    lines = []
    for level in document["levels"]:
        rows = [[c["camera"], f"{c['score_eq4']:.3f}", f"{c['score_rendered']:.3f}", f"{c['score_bound']:.3f}",
                 c["rank_eq4"], c["rank_rendered"]] for c in level["candidates"]]
        lines += [f"{level['level']}:", table(rows, ["camera", "J Eq. 4", "J rendered", "bound", "rank Eq. 4",
                                                     "rank rendered"])]
    lines.append(f"would Eq. 4 still choose the same camera? ({len(cameras)} candidates, {len(result.lights)} light "
                 f"pairs × {len(result.skins)} skins, {result.size} px, {result.spp} spp, the {result.skin_set} "
                 f"locus; J = TPR − FPR, the renderer's noise separated; {result.elapsed_s:.0f} s)")
    lines += [f"  {_answer(level)}" for level in document["levels"]]
    if options["plot"] is not None:
        from ..files import write_output

        write_output(options["plot"], result.figure, "--plot")
        document["plot"] = str(options["plot"])
        lines.append(f"figure: {options['plot']}")
    emit(args, document, "\n".join(lines))


def command_bench_rank(args: argparse.Namespace, refuse_foreign_flags) -> None:
    """``bench rank [--quick] [--workers N]``: the ranking's speed on the issue's configuration (``bench``'s other
    flags refused by ``refuse_foreign_flags``)."""
    refuse_foreign_flags(args)
    from ..execution import check_workers
    from ..studies.benchmarks.bench_rank import bench_rank

    if args.scene is not None:
        raise SkinrenderError("--scene goes with 'bench render', 'bench calibration' or 'bench validate', not "
                              "'bench rank'", flag="--scene")
    if args.workers is not None:
        check_workers(args.workers)
    result = bench_rank(args.quick, args.workers, None if args.json else sys.stderr)
    load = result["load_average"]
    text = (f"rank: {result['candidates']} candidates × {result['lights']} light pairs × {result['skins']} skins × "
            f"{len(result['levels'])} levels at {result['size']} px, {result['spp']} spp: {result['seconds']:.0f} s "
            f"(search {result['search_s']:.0f} s, renders and ranking {result['rank_s']:.0f} s) on "
            f"{result['machine']['cpu_count']} cores, load average {load['before'][0]:.1f} → {load['after'][0]:.1f}; "
            f"target {result['target_s']:.0f} s on 2 cores: "
            + {True: "within", False: "BEYOND", None: "not judged here (another machine or --quick)"}[
                result["within_target"]])
    emit(args, result, text)
