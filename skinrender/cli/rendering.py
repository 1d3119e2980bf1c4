"""
Rendering commands: ``render``, ``validate``, ``detect`` (``validate``'s command and verdict flags are
:mod:`skinrender.cli.chart_validation`).
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

from ..errors import SkinrenderError
from ..files import Output, write_outputs
from ..studies.labelled import chart_figure
from .common import (HELP_CAMERA, HELP_PLANCKIAN, interruptible, imaging_options, add_common, camera_of, add_grid,
                     add_model, add_render, check_output, check_render_work, choices_help, emit, flag, grid_of,
                     render_options, table)
from .face import check_figure


def add_parsers(commands) -> None:
    """Add the parsers of render, validate, detect."""
    from ..evaluation.locus import BOUNDARIES

    for name, text in (("render", "spectral render of a chart or face scene with Mitsuba 3 (float32 EXR + PNG "
                                  "preview)"),
                       ("validate", "render a chart and check every patch against Eq. 4: pass, fail or "
                                    "inconclusive within --tolerance; a face: the analytic limits that hold at its "
                                    "level of physics and Eq. 4's error against the detection budget")):
        p = commands.add_parser(name, help=text)
        p.add_argument("scene", help="scene: a chart (macbeth, skin_patches, face_chart), a face (face) or a .toml path "
                       "(see scenes/)")
        p.add_argument("--camera", required=True, help=HELP_CAMERA)
        p.add_argument("--prevailing", required=True, help="prevailing (emitter) illuminant: " + HELP_PLANCKIAN)
        p.add_argument("--calibration", required=True, help="calibration (white balance) illuminant: " + HELP_PLANCKIAN)
        add_render(p, spp_auto=name == "validate")
        add_model(p)
        add_grid(p)
        if name == "validate":  # its verdict's flags (--tolerance): skinrender.cli.chart_validation
            p.add_argument("--gamut", action="store_true",
                           help="also render the chart under every paper illuminant and compare its gamut volumes "
                           "(one calibration case each, and all calibrations) with the analytic ones, within "
                           "--tolerance (relative to each volume)")
            p.add_argument("--limits", metavar="LIST",
                           help="face scenes: the scene-free limits run beside the level's own: furnace, sphere "
                           "(comma-separated) or none (default: both)")
        from .face import add_face_arguments

        add_face_arguments(p)
        if name == "render":
            p.add_argument("-o", "--output", default="render.exr",
                           help="output EXR (float32, Eq. 4 output units, channels named by the camera); a PNG "
                           "preview is written beside it (NAME.png); default render.exr (and render.png) in the "
                           "current folder, replaced if there")
            p.add_argument("--figure", metavar="PNG",
                           help="also write a labelled figure: a chart upscaled with each patch's name on it "
                           "(skin patches outlined), a face with its labels outlined")
        add_common(p)

    p = commands.add_parser("detect", help="skin detection on a rendered chart or face with the camera's skin locus")
    p.add_argument("scene", help="scene: a chart (macbeth, skin_patches, face_chart), a face (face) or a .toml path")
    p.add_argument("--camera", required=True, help=HELP_CAMERA)
    p.add_argument("--prevailing", required=True, help="prevailing illuminant: " + HELP_PLANCKIAN)
    p.add_argument("--calibration", required=True, help="calibration illuminant: " + HELP_PLANCKIAN)
    p.add_argument("--boundary", choices=list(BOUNDARIES), default="hull", help="locus boundary: " + choices_help(BOUNDARIES))
    p.add_argument("--locus-skin", metavar="SET",
                   help="skin reflectance set the locus is trained on, a name or CSV path (default skin)")
    p.add_argument("--skin", help="face scenes: the face's skin (SPEC as for render); on a chart, the locus's "
                   "training set (deprecated there: use --locus-skin)")
    p.add_argument("--physics", default="direct", help="face scenes: the level of physics, as for render "
                   "(--imager adds noise)")
    p.add_argument("--size", metavar="PX", help="face scenes: image side, pixels (default: the scene's)")
    p.add_argument("-o", "--output", default="detect.png",
                   help="mask PNG (white: detected skin); a preview PNG is written beside it (NAME_preview.png); "
                   "default detect.png (and detect_preview.png) in the current folder, replaced if there")
    p.add_argument("--figure", metavar="PNG",
                   help="also write a labelled figure: a chart with its patch names over the render and over "
                   "the detection mask with each patch's detected fraction; a face with the detected skin over it "
                   "and its labels outlined, TPR and FPR in the title")
    add_render(p)
    add_common(p)


def chart_only(args: argparse.Namespace, skin: bool = True) -> None:
    """
    A chart command's scene loaded first (its own error for an unknown or broken scene), then the face-only
    flags refused: ``--physics``, ``--size`` and (but for ``detect``) ``--skin``.
    """
    from ..rendering.scene import load_scene

    flag("SCENE", load_scene, args.scene)
    given = [name for name, on in (("--physics", args.physics != "direct"), ("--skin", skin and args.skin is not None),
                                   ("--size", args.size is not None)) if on]
    if given:
        raise SkinrenderError(f"{', '.join(given)}: {'goes' if len(given) == 1 else 'go'} with a face scene "
                              "(e.g. 'face'), not a chart")


def render_inputs(args: argparse.Namespace) -> dict:
    """
    The scene, camera and the two Planckian temperatures (K) of a render
    command, each parsed once here with its flag named in any error, and
    checked to give the camera light on the grid before anything renders.
    """
    import numpy as np

    from ..model.illuminant import illuminant
    from ..model.response import response
    from ..rendering.scene import load_scene

    scene = flag("SCENE", load_scene, args.scene)
    grid = grid_of(args) if hasattr(args, "grid") else None
    cam = camera_of(args, grid)
    temperatures = {}
    for name in ("prevailing", "calibration"):
        light = flag(f"--{name}", illuminant, getattr(args, name))
        if light.temperature is None:
            raise SkinrenderError(f"--{name}: rendering needs a Planckian illuminant (kelvin, A or H), got {light}")
        temperatures[name] = light.temperature
    from ..spectra import GRID_DEFAULT

    grid = grid or GRID_DEFAULT
    for name, kelvin in temperatures.items():  # each light seen by the camera, the one at fault named
        flag({"camera": "--camera", None: f"--{name}"}, response, cam, np.ones((1, grid.size)), kelvin, kelvin,
             grid=grid)
    try:  # every patch's data covers the grid, before the render needs it
        scene.reflectances(grid)
    except SkinrenderError as error:  # the chart's own data: --extrapolation (CSV cameras') does not apply
        if error.cause != "coverage":
            raise error.reworded(f"SCENE: {error.message}", flag="SCENE") from None
        raise error.reworded(f"--grid: {error.message}", flag="--grid", cause=None,
                             hint="choose a --grid inside the chart's data") from None
    return {"scene": scene, "camera_": cam, "prevailing": temperatures["prevailing"],
            "calibration": temperatures["calibration"]}


def pixels_of(scene) -> int:
    """The pixels of a chart scene's image."""
    width, height = scene.size
    return int(width) * int(height)


def render_with(args: argparse.Namespace, inputs: dict, options: dict, imaging: dict | None, knee: bool = False):
    """The render of a command: plain (Eq. 4 on the radiance) or through ``--imager``; returns (rendering, imaged)."""
    from ..rendering.balance import render

    normalization = getattr(args, "normalization", "white")
    grid = grid_of(args) if hasattr(args, "grid") else None
    extra = {} if grid is None else {"grid": grid}
    if imaging is None:
        return render(**inputs, normalization=normalization, knee=knee, **extra, **options), None
    from ..rendering.imaging import render_imaged

    imaged = render_imaged(inputs["scene"], inputs["camera_"], inputs["prevailing"], inputs["calibration"],
                           **imaging, normalization=normalization, **extra, **options)
    return imaged.rendering, imaged


def imaging_document(imaged) -> dict:
    """
    The JSON keys a render through an imager adds: imager, illuminance_lux, exposure_s, ``clipping`` (pixels at the
    full well and at the ADC range, per channel) and ``notes`` (a capped ``auto`` exposure, clipped pixels).
    """
    if imaged is None:
        return {}
    return {"imager": imaged.imager.name, "illuminance_lux": imaged.illuminance_lux, "exposure_s": imaged.exposure_s,
            "clipping": imaged.clipping, "notes": list(imaged.notes)}


def imaging_notes(imaged) -> str:
    """The text lines of a render's imaging notes (a capped exposure, clipped pixels), or nothing."""
    return "".join(f"\nnote: {note}" for note in (imaged.notes if imaged is not None else ()))


@interruptible
def command_render(args: argparse.Namespace) -> None:
    from .face import command_render_face, is_face_scene

    if is_face_scene(args.scene):  # a face (perspective camera, mesh, lights): its own renderer
        return command_render_face(args)
    chart_only(args)
    from ..rendering.exr import write_preview
    from ..rendering.outputs import write_chart_exr
    from ..rendering.renderer import channel_names

    options = render_options(args)
    output = check_output(args.output, "--output", (".exr",))
    check_output(str(output.with_suffix(".png")), "--output (its PNG preview)", (".png",))
    figure = check_figure(args, output.with_suffix(".png"))
    inputs = render_inputs(args)
    imaging = imaging_options(args)
    check_render_work(args, pixels_of(inputs["scene"]), options["spp"])
    print(f"rendering {inputs['scene'].name} at {options['spp']} spp …", file=sys.stderr)
    result, imaged = render_with(args, inputs, options, imaging, args.knee)
    if imaged is not None and args.knee:
        from dataclasses import replace

        from ..model.response import knee

        result = replace(result, image=knee(result.image).astype(np.float32), knee=True)
    spp = result.raw[0].spp
    names = channel_names(result.camera)
    preview = output.with_suffix(".png")
    outputs = [Output(output, "--output", lambda stream: write_chart_exr(stream, result, args.seed, grid_of(args))),
               Output(preview, "--output (its PNG preview)", lambda stream: write_preview(stream, result.image))]
    if figure is not None:
        outputs.append(Output(figure, "--figure", lambda stream: chart_figure(result, stream)))
    write_outputs(*outputs)  # every file whole, or none of them
    document = {"image": str(output), "preview_png": str(preview), "channels": list(names), "spp": spp,
                "spp_requested": options["spp"],
                "sampler": options["sampler"], "seed": args.seed, "variant": result.variant,
                "elapsed_s": result.seconds, "scene": result.scene.name, "camera": result.camera.name,
                "prevailing_K": result.prevailing, "calibration_K": result.calibration,
                "normalization": args.normalization, "knee": args.knee, **imaging_document(imaged)}
    if figure is not None:
        document["figure"] = str(figure)
    text = (f"{result.scene.name} through {result.camera.name}, {result.prevailing:g} K white-balanced to "
            f"{result.calibration:g} K: {output} (+ {preview}), {spp} spp, {result.variant}, "
            f"{result.seconds:.2f} s" + (f"; figure {figure}" if figure is not None else "") + imaging_notes(imaged))
    emit(args, document, text)


def locus_skin_of(args: argparse.Namespace, chart: bool) -> str:
    """
    The skin set ``detect`` trains the locus on: ``--locus-skin`` (default ``skin``); on a chart ``--skin`` is
    its deprecated alias (a notice on stderr), on a face ``--skin`` is the face's own skin.
    """
    locus_skin = getattr(args, "locus_skin", None)
    if chart and args.skin is not None:
        if locus_skin is not None:
            raise SkinrenderError("--skin: on a chart it is the deprecated name of --locus-skin; give one of them")
        print("skinrender detect: notice: --skin on a chart names the locus's training set; it is deprecated, "
              "use --locus-skin (on a face --skin is the face's skin)", file=sys.stderr)
        return args.skin
    return "skin" if locus_skin is None else locus_skin


@interruptible
def command_detect(args: argparse.Namespace) -> None:
    from .face import command_detect_face, is_face_scene

    if is_face_scene(args.scene):  # the label channel is the ground truth
        return command_detect_face(args)

    from ..evaluation.detection import SCORED_MIN_OUTPUT, detect
    from ..datasets import reflectances
    from ..evaluation.locus import skin_locus
    from ..rendering.exr import write_png, write_preview

    chart_only(args, skin=False)
    locus_skin = locus_skin_of(args, chart=True)
    options = render_options(args)
    output = check_output(args.output, "--output", (".png",))
    check_output(str(output.with_name(output.stem + "_preview.png")), "--output (its preview)", (".png",))
    figure = check_figure(args, output, output.with_name(output.stem + "_preview.png"))
    inputs = render_inputs(args)
    imaging = imaging_options(args)
    skin = flag("--locus-skin" if args.skin is None else "--skin", reflectances, locus_skin)
    check_render_work(args, pixels_of(inputs["scene"]), options["spp"])
    print(f"rendering {inputs['scene'].name} at {options['spp']} spp …", file=sys.stderr)
    rendering, imaged = render_with(args, inputs, options, imaging)
    # the camera is white-balanced to the calibration light: the locus of that one balancing
    locus = skin_locus(rendering.camera, skin, calibration=rendering.calibration, boundary=args.boundary)
    result = detect(rendering, locus, scored_min=SCORED_MIN_OUTPUT)  # scored as on a face: too dark has no colour
    preview = output.with_name(output.stem + "_preview.png")
    rate = lambda value, key: "undefined (" + result.undefined[key] + ")" if value is None else f"{value:.3f}"  # noqa: E731
    outputs = [Output(output, "--output", lambda stream: write_png(stream, result.mask.astype(float))),
               Output(preview, "--output (its preview)", lambda stream: write_preview(stream, rendering.image))]
    if figure is not None:
        outputs.append(Output(figure, "--figure", lambda stream: chart_figure(
            rendering, stream, result, f"TPR {rate(result.tpr, 'tpr')}, FPR {rate(result.fpr, 'fpr')}")))
    write_outputs(*outputs)  # every file whole, or none of them
    document = {"scene": rendering.scene.name, "camera": rendering.camera.name, "prevailing_K": rendering.prevailing,
                "calibration_K": rendering.calibration, "tpr": result.tpr, "fpr": result.fpr,
                "undefined": result.undefined, "locus_degenerate": locus.degenerate,
                "mask_png": str(output), "preview_png": str(preview), "per_patch": result.per_patch,
                "scored_min_output": SCORED_MIN_OUTPUT,
                "boundary": args.boundary, "spp": rendering.raw[0].spp, "spp_requested": options["spp"],
                "variant": rendering.variant, **imaging_document(imaged)}
    rows = [[p["name"][:30], "skin" if p["is_skin"] else "",
             "undefined" if p["detected_fraction"] is None else f"{p['detected_fraction']:.2f}"]
            for p in result.per_patch]
    if figure is not None:
        document["figure"] = str(figure)
    text = (table(rows, ["patch", "", "detected"])
            + f"\nTPR {rate(result.tpr, 'tpr')}, FPR {rate(result.fpr, 'fpr')}; mask {output}"
            + (f"; figure {figure}" if figure is not None else "") + imaging_notes(imaged))
    emit(args, document, text)
