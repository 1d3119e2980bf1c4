"""
Rendering commands: ``render``, ``validate``, ``detect`` (``validate``'s command and verdict flags are
:mod:`skinrender.cli.chart_validation`).
"""

from __future__ import annotations

import argparse
import sys

from ..errors import SkinrenderError
from ..files import Output, write_outputs
from ..studies.labelled import chart_figure
from .common import (HELP_CAMERA, HELP_PLANCKIAN, interruptible, add_common, add_grid, add_model, add_render,
                     check_output, choices_help, emit, flag, settings_from, table)
from .chart_validation import add_check_arguments, add_verdict_arguments, command_validate
from .inputs import (by_kind, chart_flags, chart_request_from, check_request_work, figure_from, imaging_document,
                     imaging_notes, refuse_face_flags, scene_from)
from .bands_flags import add_spectral_arguments, bands_from
from .spectral_commands import command_render_spectral
from .placement import add_translate, translate_key
from .subsurface import subsurface_keys



def add_parsers(commands) -> None:
    """Add the parsers of render, validate, detect."""
    from ..evaluation.locus import BOUNDARIES

    for name, text in (("render", "spectral render of a chart or face scene with Mitsuba 3 (float32 EXR + PNG "
                                  "preview)"),
                       ("validate", "render a chart and check every patch against Eq. 4: pass, fail or "
                                    "inconclusive within --tolerance; a face: the analytic limits that hold at its "
                                    "level of physics and Eq. 4's error against the detection budget")):
        p = commands.add_parser(name, run=command_validate if name == "validate" else command_render, help=text)
        p.add_argument("scene", help="scene: a chart (macbeth, skin_patches, face_chart), a face (face) or a .toml path "
                       "(see scenes/)")
        spectral = " (none with --spectral)" if name == "render" else ""
        p.add_argument("--camera", required=name == "validate", help=HELP_CAMERA + spectral)
        p.add_argument("--prevailing", required=True, help="prevailing (emitter) illuminant: " + HELP_PLANCKIAN)
        p.add_argument("--calibration", required=name == "validate",
                       help="calibration (white balance) illuminant: " + HELP_PLANCKIAN + spectral)
        add_render(p, spp_auto=name == "validate")
        add_spectral_arguments(p, name)
        add_model(p)
        add_grid(p)
        if name == "validate":  # what it checks (--gamut, --limits) and its verdict's flags (--tolerance, below)
            add_check_arguments(p)
        from .face import add_face_arguments

        add_face_arguments(p)
        add_translate(p)
        if name == "render":
            p.add_argument("-o", "--output", default="render.exr",
                           help="output EXR (float32, Eq. 4 output units, channels named by the camera); a PNG "
                           "preview is written beside it (NAME.png); default render.exr (and render.png) in the "
                           "current folder, replaced if there")
            p.add_argument("--figure", metavar="PNG",
                           help="also write a labelled figure: a chart upscaled with each patch's name on it "
                           "(skin patches outlined), a face with its labels outlined")
        add_common(p)
        if name == "validate":
            add_verdict_arguments(p)

    p = commands.add_parser("detect", run=command_detect,
                            help="skin detection on a rendered chart or face with the camera's skin locus")
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


@interruptible
def command_render(args: argparse.Namespace) -> None:
    """``render``: the scene loaded once, then its kind's command (a chart's, :func:`command_render_chart`; a face's,
    :func:`~skinrender.cli.face.command_render_face`)."""
    from .face import command_render_face

    scene = scene_from(args.scene)
    if args.spectral:
        return command_render_spectral(args, scene)
    bands_from(args.spectral, args.bands)  # --bands without --spectral: refused
    missing = [name for name, value in (("--camera", args.camera), ("--calibration", args.calibration))
               if value is None]
    if missing:
        raise SkinrenderError(f"the following arguments are required: {', '.join(missing)} (or --spectral: the "
                              "bands, for any camera afterwards)", flag=missing[0])
    return by_kind(scene, chart=command_render_chart, face=command_render_face)(args, scene)


def command_render_chart(args: argparse.Namespace, scene) -> None:
    """``render`` on a chart ``scene``: its request, rendered (through an image sensor with ``--imager``)."""
    from ..rendering.exr import write_preview
    from ..rendering.kinds import CHART
    from ..rendering.outputs import write_chart_exr
    from ..rendering.renderer import channel_names

    refuse_face_flags(args.physics, args.skin, args.size)
    settings = settings_from(args.quality, args.spp, args.sampler, args.seed, args.variant, args.channels)
    output = check_output(args.output, "--output", (".exr",))
    check_output(str(output.with_suffix(".png")), "--output (its PNG preview)", (".png",))
    figure = figure_from(args.figure, output.with_suffix(".png"))
    request = chart_request_from(scene, settings, **chart_flags(args))
    check_request_work(args.max_minutes, request)
    settings = request.settings
    print(f"rendering {request.scene.name} at {settings.spp} spp …", file=sys.stderr)
    result, imaged = CHART.render_imaged(request)  # through a sensor, the knee on its image (the kind's)
    spp = result.raw[0].spp
    names = channel_names(result.camera)
    preview = output.with_suffix(".png")
    outputs = [Output(output, "--output", lambda stream: write_chart_exr(stream, result, settings.seed, request.grid)),
               Output(preview, "--output (its PNG preview)", lambda stream: write_preview(stream, result.image))]
    if figure is not None:
        outputs.append(Output(figure, "--figure", lambda stream: chart_figure(result, stream)))
    write_outputs(*outputs)  # every file whole, or none of them
    document = {"image": str(output), "preview_png": str(preview), "channels": list(names), "spp": spp,
                "spp_requested": settings.spp,
                "sampler": settings.sampler, "seed": settings.seed, "variant": result.variant,
                "elapsed_s": result.seconds, "scene": result.scene.name, "camera": result.camera.name,
                "prevailing_K": result.prevailing, "calibration_K": result.calibration,
                "normalization": request.normalization, "knee": request.knee, **imaging_document(imaged),
                **subsurface_keys(result), **translate_key(getattr(args, "translate_mm", None))}
    if figure is not None:
        document["figure"] = str(figure)
    text = (f"{result.scene.name} through {result.camera.name}, {result.prevailing:g} K white-balanced to "
            f"{result.calibration:g} K: {output} (+ {preview}), {spp} spp, {result.variant}, "
            f"{result.seconds:.2f} s" + (f"; figure {figure}" if figure is not None else "") + imaging_notes(imaged))
    emit(args.json, document, text)


def locus_skin_of(args: argparse.Namespace, chart: bool) -> str:
    """
    The skin set ``detect`` trains the locus on: ``--locus-skin`` (default ``skin``); on a chart ``--skin`` is
    its deprecated alias (a notice on stderr), on a face ``--skin`` is the face's own skin.
    """
    locus_skin = getattr(args, "locus_skin", None)
    if chart and args.skin is not None:
        if locus_skin is not None:
            raise SkinrenderError("--skin: on a chart it is the deprecated name of --locus-skin; give one of them",
                                  flag="--skin")
        print("skinrender detect: notice: --skin on a chart names the locus's training set; it is deprecated, "
              "use --locus-skin (on a face --skin is the face's skin)", file=sys.stderr)
        return args.skin
    return "skin" if locus_skin is None else locus_skin


@interruptible
def command_detect(args: argparse.Namespace) -> None:
    """``detect``: the scene loaded once, then its kind's command (the face's label channel is its ground truth)."""
    from .face_detection import command_detect_face

    scene = scene_from(args.scene)
    return by_kind(scene, chart=command_detect_chart, face=command_detect_face)(args, scene)


def command_detect_chart(args: argparse.Namespace, scene) -> None:
    """``detect`` on a chart ``scene``: its request rendered, every pixel classified by the camera's skin locus."""
    from ..datasets import reflectances
    from ..evaluation.detection import SCORED_MIN_OUTPUT, detect
    from ..evaluation.locus import skin_locus
    from ..rendering.exr import write_png, write_preview
    from ..rendering.kinds import CHART

    refuse_face_flags(args.physics, args.skin, args.size, skin_refused=False)
    locus_skin = locus_skin_of(args, chart=True)
    settings = settings_from(args.quality, args.spp, args.sampler, args.seed, args.variant, args.channels)
    output = check_output(args.output, "--output", (".png",))
    check_output(str(output.with_name(output.stem + "_preview.png")), "--output (its preview)", (".png",))
    figure = figure_from(args.figure, output, output.with_name(output.stem + "_preview.png"))
    request = chart_request_from(scene, settings, **chart_flags(args))
    which = "--locus-skin" if args.skin is None else "--skin"
    skin = flag(which, reflectances, locus_skin)
    # the camera is white-balanced to the calibration light: the locus of that one balancing (before the render: a
    # set that does not cover the grid was refused after it)
    locus = flag(which, skin_locus, request.camera, skin, calibration=request.calibration, boundary=args.boundary)
    check_request_work(args.max_minutes, request)
    settings = request.settings
    print(f"rendering {request.scene.name} at {settings.spp} spp …", file=sys.stderr)
    rendering, imaged = CHART.render_imaged(request)
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
                "boundary": args.boundary, "spp": rendering.raw[0].spp, "spp_requested": settings.spp,
                "variant": rendering.variant, **imaging_document(imaged), **subsurface_keys(rendering)}
    rows = [[p["name"][:30], "skin" if p["is_skin"] else "",
             "undefined" if p["detected_fraction"] is None else f"{p['detected_fraction']:.2f}"]
            for p in result.per_patch]
    if figure is not None:
        document["figure"] = str(figure)
    text = (table(rows, ["patch", "", "detected"])
            + f"\nTPR {rate(result.tpr, 'tpr')}, FPR {rate(result.fpr, 'fpr')}; mask {output}"
            + (f"; figure {figure}" if figure is not None else "") + imaging_notes(imaged))
    emit(args.json, document, text)
