"""
``skinrender bench calibration`` and ``bench validate``: how often the
validation's checks fail where their null holds, and what a validation costs
and shows as spp grows (:mod:`skinrender.studies.benchmarks.calibration`). The flags are
added to ``bench``'s parser (:mod:`skinrender.cli.studies`), which refuses
the ones another benchmark takes before calling :func:`command_bench_verdicts`.

Units: temperatures K, illuminance lx, times s, rates fractions.
"""

from __future__ import annotations

import argparse
import sys

from ..errors import SkinrenderError
from ..files import write_output
from .common import (HELP_CAMERA, HELP_PLANCKIAN, SEED_MAX, SPP_MAX, check_output, emit, flag, imaging_options,
                     integer_in, interruptible, table)

__all__ = ["VERDICT_BENCH_FLAGS", "add_bench_arguments", "command_bench_verdicts"]

VERDICT_BENCH_FLAGS = {"camera": ("render", "calibration", "validate"), "prevailing": ("calibration", "validate"),
                       "calibration": ("calibration", "validate"), "spp": ("calibration",),
                       "seeds": ("calibration", "validate"), "seed": ("calibration", "validate"),
                       "imager": ("calibration", "validate"), "illuminance": ("calibration", "validate"),
                       "exposure": ("calibration", "validate"), "level": ("calibration",),
                       "checks": ("calibration",), "skin": ("calibration",), "skin_set": ("calibration",),
                       "detection_tolerance": ("calibration",),
                       "mc_variance": ("calibration", "validate")}
"""``bench`` flags of the verdict benchmarks (``dest``: the benchmarks they go with)."""

SEEDS_DEFAULT = {"calibration": 40, "validate": 5}
"""``--seeds`` unless given."""

SPP_LIST_DEFAULT = (4, 16, 64, 256)
"""``bench validate --spp-list`` unless given."""


def add_bench_arguments(p: argparse.ArgumentParser) -> None:
    """The verdict benchmarks' flags (each ``None`` unless given, so that a flag given elsewhere is refused)."""
    from ..rendering.sensor_validation import MC_VARIANCE
    from .common import choices_help

    p.add_argument("--camera", help="render, calibration, validate: the camera (default gbell:9@450,540,610); "
                   + HELP_CAMERA)
    p.add_argument("--prevailing", help="calibration, validate: prevailing light (default 3300; a face 2856; "
                   "--scene ptc: the grey chart's one light, default 5900); "
                   + HELP_PLANCKIAN)
    p.add_argument("--calibration", help="calibration, validate: calibration light (default 4800; a face 5900); "
                   + HELP_PLANCKIAN)
    p.add_argument("--spp", metavar="N", help="calibration: samples per pixel (default 16; 64 with --imager; a face "
                   "256, split over its 12 replicates; --scene ptc 64, its one render)")
    p.add_argument("--seeds", metavar="N", help="calibration: independent validations (default 40); validate: "
                   "validations per spp (default 5)")
    p.add_argument("--seed", metavar="S", help="calibration, validate: the first seed (default 0); the runs use S, "
                   "S + 2, … (each validation takes its seed and the next; a face's S, S + 12, …: its 12 replicates; "
                   "--scene ptc's sensor seeds S, S + 1, … of one render with seed S)")
    p.add_argument("--imager", help="calibration, validate: through an image sensor (a preset or a TOML)")
    p.add_argument("--illuminance", type=float, help="calibration, validate with --imager: lux at the chart "
                   "(default 500)")
    p.add_argument("--exposure", help="calibration, validate with --imager: seconds or auto (default)")
    p.add_argument("--level", help="calibration: a face's level of physics (default direct; faces only: refused for "
                   "charts); eq4_shift's failures count as false alarms only where Eq. 4 holds (direct, noise)")
    p.add_argument("--checks", choices=["all", "detection"],
                   help="calibration --scene face: every check of validate face (all, default) or the detection "
                   "verdict alone (detection: at any spp, no floor per replicate; with --size, --skin, --skin-set, "
                   "--detection-tolerance)")
    p.add_argument("--skin", help="calibration --scene face --checks detection: the face's skin (default the "
                   "scene's)")
    p.add_argument("--skin-set", metavar="SET", help="calibration --scene face --checks detection: the locus's "
                   "reflectance set (default skin)")
    p.add_argument("--detection-tolerance", metavar="RATE", help="calibration --scene face --checks detection: "
                   "the verdict's tolerance in TPR and FPR, a fraction (default 0.02)")
    p.add_argument("--mc-variance", choices=list(MC_VARIANCE),
                   help="calibration, validate with --imager: how the render's own variance enters the sensor's "
                   "predictions: " + choices_help(MC_VARIANCE))
    # --max-minutes (the cap on the estimated time) is bench's own (skinrender.workload)


def _or(value, default):
    return default if value is None else value


def _checked(args: argparse.Namespace, spp_list: list[int] | None) -> dict:
    """Every flag of ``bench calibration`` / ``bench validate`` checked before anything renders (``spp_list``:
    ``--spp-list`` as parsed by ``bench``, ``None`` when not given)."""
    from ..rendering.kinds import scene_kind
    from ..studies.benchmarks.calibration import calibration_path
    from .inputs import by_kind

    scene_spec = _or(args.scene, "macbeth")
    if scene_spec == "ptc":
        return _checked_ptc(args)
    run = calibration_path(scene_kind(scene_spec).name, args.level)
    return by_kind(scene_spec, chart=_checked_chart, face=_checked_face)(args, run, scene_spec, spp_list)


def _checked_chart(args: argparse.Namespace, run, scene_spec: str, spp_list: list[int] | None) -> dict:
    """A chart's calibration or validation flags, checked (:func:`_checked`)."""
    from ..model.camera import camera
    from ..model.illuminant import illuminant
    from ..rendering.renderer import SAMPLES_MAX, render_passes
    from ..rendering.scene import load_chart_scene
    from ..studies.benchmarks.calibration import estimate_seconds, renders_of
    from ..workload import check_work

    for name in DETECTION_FLAGS + ("size",):
        if getattr(args, name, None) is not None:
            option = "--" + name.replace("_", "-")
            raise SkinrenderError(f"{option} goes with 'bench calibration --scene face', not a chart", flag=option)
    scene = flag("--scene", load_chart_scene, scene_spec)
    cam = flag("--camera", camera, _or(args.camera, "gbell:9@450,540,610"))
    lights = {}
    for name, default in (("prevailing", "3300"), ("calibration", "4800")):
        light = flag(f"--{name}", illuminant, _or(getattr(args, name), default))
        if light.temperature is None:
            raise SkinrenderError(f"--{name}: rendering needs a Planckian illuminant (kelvin, A or H), got {light}")
        lights[name] = light.temperature
    imaging = imaging_options(args)
    if args.mc_variance is not None and imaging is None:
        raise SkinrenderError("--mc-variance sets how the render's variance enters a sensor's predictions: it goes "
                              "with --imager", flag="--mc-variance")
    seeds = integer_in(_or(args.seeds, SEEDS_DEFAULT[args.what]), "--seeds", 1, 100_000)
    first = integer_in(_or(args.seed, 0), "--seed", 0, SEED_MAX)
    if first + 2 * seeds - 1 > SEED_MAX:
        raise SkinrenderError(f"--seed: the runs use seeds {first} to {first + 2 * seeds - 1}, beyond {SEED_MAX}",
                              flag="--seed")
    if args.what == "calibration":
        spps = [integer_in(_or(args.spp, 64 if imaging else 16), "--spp", 1, SPP_MAX)]
    else:
        spps = list(SPP_LIST_DEFAULT) if spp_list is None else list(spp_list)
    plot = check_output(args.plot, "--plot", (".png",))
    width, height = scene.size
    for spp in spps:
        if spp * width * height > SAMPLES_MAX:
            raise SkinrenderError(f"--spp: {spp} spp × {width * height} pixels is more than {SAMPLES_MAX} samples a "
                                  "render may take", flag="--spp")
    passes = render_passes(cam)
    renders = 1 if imaging else renders_of(lights["prevailing"], lights["calibration"])
    startup = estimate_seconds(0, width * height, 1)  # the first compilation, once
    seconds = startup + sum(estimate_seconds(seeds, width * height, spp, renders, passes, imaging is not None)
                            - startup for spp in spps)
    what = (f"{seeds} seeds at {spps[0]} spp" if args.what == "calibration"
            else f"{seeds} seeds at each of {', '.join(map(str, spps))} spp")
    check_work(seconds, "--seeds", what, args.max_minutes, fewer="run fewer --seeds")
    return {"run": run, "scene": scene, "camera_": cam, **lights, "spps": spps, "seeds": seeds, "first_seed": first,
            "imaging": imaging, "mc_variance": _or(args.mc_variance, "frames"), "plot": plot, "estimate_s": seconds,
            "level": args.level}


def _checked_face(args: argparse.Namespace, run, scene_spec: str, spp_list: list[int] | None = None) -> dict:
    """``bench calibration --scene FACE [--level L]``'s flags checked (``bench validate`` and ``--mc-variance``
    refused: the face's checks have no tolerance, and no sensor prediction to correct)."""
    from ..model.camera import camera
    from ..rendering.face.effects import PHYSICS_BASE, physics_level
    from ..rendering.face.scene import load_face_scene
    from ..studies.benchmarks.face_calibration import SEED_STEP, estimate_face_seconds
    from ..workload import check_work
    from .face import planckian_flag

    if args.what != "calibration":
        raise SkinrenderError("--scene: bench validate runs a chart's tolerance against spp; a face's checks: bench "
                              "calibration --scene face [--level L]")
    if args.mc_variance is not None:
        raise SkinrenderError("--mc-variance corrects a chart's sensor predictions; a face's checks through a sensor "
                              "take their noise from the replicates")
    scene = flag("--scene", load_face_scene, scene_spec)
    level = flag("--level", physics_level, _or(args.level, PHYSICS_BASE))  # parsed once: the studies take it
    cam = flag("--camera", camera, _or(args.camera, "gbell:9@450,540,610"))
    lights = {name: planckian_flag(_or(getattr(args, name), default), f"--{name}")
              for name, default in (("prevailing", "2856"), ("calibration", "5900"))}
    imaging = imaging_options(args)
    if imaging is not None and args.illuminance is None:
        imaging["illuminance_lux"] = None  # the scene's
    seeds = integer_in(_or(args.seeds, SEEDS_DEFAULT["calibration"]), "--seeds", 1, 100_000)
    first = integer_in(_or(args.seed, 0), "--seed", 0, SEED_MAX)
    if first + SEED_STEP * seeds - 1 > SEED_MAX:
        raise SkinrenderError(f"--seed: the runs use seeds {first} to {first + SEED_STEP * seeds - 1}, beyond "
                              f"{SEED_MAX}")
    detection = _or(args.checks, "all") == "detection"
    if not detection:
        for name in DETECTION_FLAGS[1:] + ("size",):
            if getattr(args, name, None) is not None:
                option = "--" + name.replace("_", "-")
                raise SkinrenderError(f"{option} goes with --checks detection (validate face's own checks run at "
                                      "the scene's size, skin and locus)", flag=option)
    spp = integer_in(_or(args.spp, 16 if detection else 256), "--spp", 1, SPP_MAX)
    plot = check_output(args.plot, "--plot", (".png",))
    if detection:
        return _checked_detection(args, scene, level, cam, lights, imaging, seeds, first, spp, plot)
    seconds = estimate_face_seconds(seeds, scene.camera.width * scene.camera.height, spp, level)
    check_work(seconds, "--seeds", f"{seeds} validations of the face at {spp} spp", args.max_minutes,
               fewer="run fewer --seeds")
    return {"run": run, "study": _study_face, "scene": scene, "camera_": cam, **lights, "spps": [spp], "seeds": seeds,
            "first_seed": first, "imaging": imaging, "mc_variance": None, "plot": plot, "estimate_s": seconds,
            "level": level}


DETECTION_FLAGS = ("checks", "skin", "skin_set", "detection_tolerance")
"""``bench calibration`` flags of the face's detection verdict (``--checks detection``)."""


def _checked_detection(args, scene, level, cam, lights, imaging, seeds, first, spp, plot) -> dict:
    """``bench calibration --scene face --checks detection``'s flags checked (``--size`` default 64)."""
    from ..rendering.face.scene import skin_reflectance_of
    from ..spectra import GRID_DEFAULT
    from ..studies.benchmarks.detection_calibration import estimate_detection_seconds
    from ..workload import check_work
    from .detection_options import detection_tolerance_from, skin_set_from
    from .face_inputs import SIZE_MAX

    size = integer_in(_or(args.size, 64), "--size", 1, SIZE_MAX)
    if args.skin is not None:
        skin_reflectance_of(args.skin, GRID_DEFAULT, "--skin")
    skins = skin_set_from(args.skin_set, cam, [lights["calibration"]])
    tolerance = detection_tolerance_from(args.detection_tolerance)
    seconds = estimate_detection_seconds(seeds, size * size, spp, level)
    check_work(seconds, "--seeds", f"{seeds} detection verdicts of the face at {spp} spp", args.max_minutes,
               fewer="run fewer --seeds")
    return {"study": _study_detection, "scene": scene, "camera_": cam, **lights, "spp": spp, "size": size,
            "skin": args.skin, "skin_set": skins, "tolerance": tolerance, "seeds": seeds,
            "first_seed": first, "imaging": imaging, "plot": plot, "estimate_s": seconds, "level": level}


PTC_REFUSED = ("calibration", "exposure", "level", "mc_variance", *DETECTION_FLAGS)
"""``bench`` flags that ``--scene ptc`` refuses: the photon transfer has one light, its own exposure series, no
level of physics and no render variance in its predictions (its two-frame differences cancel it)."""


def _checked_ptc(args: argparse.Namespace) -> dict:
    """``bench calibration --scene ptc --imager I``'s flags checked
    (:func:`~skinrender.studies.benchmarks.ptc.ptc_calibration`): ``--prevailing`` is the grey chart's light (default 5900 K, as ``ptc --temperature``),
    ``--illuminance`` its lux (default 500), ``--spp`` the one render's (default 64), ``--seed`` the first sensor
    seed (the runs use S, S + 1, …; the render S)."""
    from ..model.camera import camera
    from ..model.imager import imager
    from ..studies.benchmarks.ptc_verdict import estimate_ptc_seconds
    from ..workload import check_work
    from .common import positive_number
    from .face import planckian_flag

    if args.what != "calibration":
        raise SkinrenderError("--scene ptc: bench validate runs a chart's tolerance against spp; the photon "
                              "transfer's fits: bench calibration --scene ptc --imager I", flag="--scene")
    for name in PTC_REFUSED:
        if getattr(args, name) is not None:
            option = f"--{name.replace('_', '-')}"
            raise SkinrenderError(f"{option} does not go with --scene ptc: the photon transfer has one light "
                                  "(--prevailing), its own exposure series and no render variance to correct",
                                  flag=option)
    if args.imager is None:
        raise SkinrenderError("--scene ptc measures an image sensor: give --imager I (see 'skinrender imagers')",
                              flag="--imager")
    sensor = flag("--imager", imager, args.imager)
    lux = positive_number(_or(args.illuminance, 500.0), "--illuminance", "lx")
    temperature = planckian_flag(_or(args.prevailing, "5900"), "--prevailing")
    cam = flag("--camera", camera, _or(args.camera, "gbell:9@450,540,610"))
    seeds = integer_in(_or(args.seeds, SEEDS_DEFAULT["calibration"]), "--seeds", 1, 100_000)
    first = integer_in(_or(args.seed, 0), "--seed", 0, SEED_MAX)
    if first + seeds - 1 > SEED_MAX:
        raise SkinrenderError(f"--seed: the runs use seeds {first} to {first + seeds - 1}, beyond {SEED_MAX}",
                              flag="--seed")
    spp = integer_in(_or(args.spp, 64), "--spp", 1, SPP_MAX)
    plot = check_output(args.plot, "--plot", (".png",))
    seconds = estimate_ptc_seconds(seeds, spp=spp)
    check_work(seconds, "--seeds", f"{seeds} photon-transfer measurements", args.max_minutes,
               fewer="run fewer --seeds")
    return {"study": _study_ptc, "camera_": cam, "imager_": sensor, "illuminance_lux": lux, "temperature": temperature,
            "seeds": seeds, "first_seed": first, "spp": spp, "plot": plot, "estimate_s": seconds}


def _study_ptc(args: argparse.Namespace, options: dict, progress) -> tuple[dict, str]:
    """``bench calibration --scene ptc``: the photon transfer's fits over the seeds."""
    from ..studies.benchmarks.ptc import ptc_calibration

    result = ptc_calibration(options["camera_"], options["imager_"], options["temperature"],
                             options["illuminance_lux"], options["seeds"], options["first_seed"],
                             spp=options["spp"], progress=progress)
    return _plotted(result, options), _calibration_text(result)


def _study_face(args: argparse.Namespace, options: dict, progress) -> tuple[dict, str]:
    """A face's calibration: the face's own study (it knows where Eq. 4's null holds)."""
    from ..studies.benchmarks.face_calibration import face_calibration

    result = face_calibration(options["level"], options["seeds"], options["camera_"], options["scene"],
                              options["prevailing"], options["calibration"], options["spps"][0],
                              first_seed=options["first_seed"], imaging=options["imaging"], progress=progress)
    return _plotted(result, options), _calibration_text(result)


def _study_detection(args: argparse.Namespace, options: dict, progress) -> tuple[dict, str]:
    """A face's detection verdict alone over the seeds, at any spp (``--checks detection``)."""
    from ..studies.benchmarks.detection_calibration import detection_calibration

    result = detection_calibration(options["level"], options["seeds"], options["camera_"], options["scene"],
                                   options["prevailing"], options["calibration"], options["spp"],
                                   options["size"], options["skin"], options["skin_set"], options["tolerance"],
                                   options["first_seed"], options["imaging"], progress=progress)
    return _plotted(result, options), _calibration_text(result)


def _study_chart(args: argparse.Namespace, options: dict, progress) -> tuple[dict, str]:
    """A chart's ``bench calibration`` (its verdicts' false alarms) or ``bench validate`` (over the spp)."""
    from ..studies.benchmarks.calibration import bench_calibration, bench_validate

    common = {"scene": options["scene"], "camera_": options["camera_"], "prevailing": options["prevailing"],
              "calibration": options["calibration"], "first_seed": options["first_seed"],
              "imaging": options["imaging"], "mc_variance": options["mc_variance"], "progress": progress}
    if args.what == "calibration":
        result = bench_calibration(options["run"], spp=options["spps"][0], seeds=options["seeds"],
                                   level=options["level"], **common)
        return _plotted(result, options), _calibration_text(result)
    result = bench_validate(options["run"], spps=options["spps"], seeds=options["seeds"], **common)
    result["estimate_s"] = options["estimate_s"]
    return result, _validate_text(result)


def _plotted(result: dict, options: dict) -> dict:
    """A calibration's result with its estimate, and its figure written (whole or not at all) where asked."""
    result["estimate_s"] = options["estimate_s"]
    if options["plot"] is not None:
        from ..studies.figures import figure_calibration

        result["plot"] = str(write_output(options["plot"], lambda stream: figure_calibration(result, stream),
                                          "--plot"))
    return result


@interruptible
def _run(wrapped: argparse.Namespace) -> None:
    args = wrapped.args
    options = _checked(args, wrapped.spp_list)
    print(f"bench {args.what}: about {options['estimate_s']:.0f} s (estimated) …", file=sys.stderr)
    progress = lambda line: print(line, file=sys.stderr)  # noqa: E731
    result, text = options.get("study", _study_chart)(args, options, progress)
    emit(args, result, text)


def command_bench_verdicts(args: argparse.Namespace, spp_list: list[int] | None = None) -> None:
    """``bench calibration`` or ``bench validate`` (``spp_list``: the parsed ``--spp-list``); Ctrl-C stops it at
    once (exit 130) and the plot is written whole or not at all."""
    _run(argparse.Namespace(args=args, spp_list=spp_list))


def _settings_text(result: dict) -> str:
    sensor = f" and {result['imager']} at {result['illuminance_lux']:g} lx" if result.get("imager") else ""
    lights = (f"{result['prevailing_K']:g} K" if result["calibration_K"] is None
              else f"{result['prevailing_K']:g} K / {result['calibration_K']:g} K")
    return f"{result['scene']} through {result['camera']}{sensor}, {lights}"


def _calibration_text(result: dict) -> str:
    def nominal(c) -> str:  # a face's eq4_shift where Eq. 4 does not hold has no null: its failures are findings
        return "— (no null)" if c["nominal"] is None else f"{'=' if c['nominal'] == 'equal to' else '≤'} " \
                                                         f"{c['nominal_alpha']:.3g}"

    rows = [[c["name"], nominal(c), f"{c['failures']}/{c['seeds']}", f"{c['rate']:.3g}",
             f"[{c['interval'][0]:.3g}, {c['interval'][1]:.3g}]",
             {True: "yes", False: "NO", None: "—"}[c["consistent"]]] for c in result["checks"]]
    seeds, step = result["seeds"], result.get("seed_step", 2)
    level = f", level {result['level']}" if result.get("level") else ""
    what = "ptc's fits" if result["scene"] == "ptc" else "validate"
    lines = [f"calibration of {what}: {_settings_text(result)}{level}, {result['spp']} spp, {seeds} seeds "
             f"({result['first_seed']}, {result['first_seed'] + step}, …), {result['elapsed_s']:.1f} s "
             f"(estimated {result['estimate_s']:.0f} s); every failure is a false alarm where the null holds:",
             table(rows, ["check", "nominal α", "failures", "rate", "95 % interval", "consistent"]), "tests:"]
    lines += [f"  {name}: {test}" for name, test in result["tests"].items()]
    if result.get("z"):  # the photon transfer's: z over the seeds, 0 ± 1 where the standard errors are right
        shown = lambda v: "—" if v is None else f"{v:+.2f}"  # noqa: E731
        lines += ["z = (fit − stated) / SE over the seeds, mean / sd per channel R, G, B (0 / 1 where the standard "
                  "errors are right):"]
        lines += [f"  {figure}: " + ", ".join(f"{shown(m)} / {'—' if s is None else f'{s:.2f}'}"
                                              for m, s in zip(z["mean"], z["sd"]))
                  for figure, z in result["z"].items()]
    if result.get("plot"):
        lines.append(f"plot: {result['plot']}")
    return "\n".join(lines)


def _validate_text(result: dict) -> str:
    rows = [[r["spp"], r["spp_used"], f"{r['seconds']:.3g}", f"{r['bound']:.3g}", f"{r['false_alarms']}/{r['seeds']}",
             f"[{r['interval'][0]:.3g}, {r['interval'][1]:.3g}]"] for r in result["rows"]]
    exponent = result["bound_exponent"]
    return "\n".join([
        f"validate {_settings_text(result)}, {result['seeds']} seeds per spp, {result['elapsed_s']:.1f} s; bound: "
        "the smallest relative tolerance that would pass (median over the seeds); false alarms: difference-test "
        f"failures at α = {result['alpha']:g} (the null holds)",
        table(rows, ["spp", "used", "s per validation", "bound", "false alarms", "95 % interval"]),
        "" if exponent is None else f"the bound falls as spp^-{exponent:.2f} (least squares over the rows; 0.5 for "
        "independent samples)"]).rstrip()
