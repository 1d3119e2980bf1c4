"""
Face commands: ``ladder`` (the face at each level of physics, with skin
detection scored at each), and ``render face …`` (:func:`command_render_face`,
which the ``render`` command hands a face scene to).

Units: temperatures K, times s, images in Eq. 4 output units, NCC and rates
fractions.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..errors import SkinrenderError
from ..files import Output, write_output, write_outputs
from .common import (HELP_CAMERA, HELP_PLANCKIAN, SEED_MAX, SPP_MAX, add_common, add_max_minutes, check_output,
                     check_seed, choices_help, emit, flag, integer_in, interruptible, settings_from, variant_of)
from .detection_options import add_detection_options, detection_tolerance_from, skin_set_from
from .face_inputs import (SIZE_MAX, check_lights_seen, face_flags_from, face_pixels, face_request_from,  # noqa: F401
                          level_names, levels_of, noise_sensor_from, planckian_flag)
from .inputs import check_request_work, figure_from
from .ladder_text import ladder_text  # noqa: F401 - its old place
from .placement import add_translate, translate_key, translate_of, translated_face

__all__ = ["add_parsers", "add_face_arguments", "check_figure", "check_face_flags", "face_request_of", "is_face_scene", "level_names", "levels_of", "noise_sensor", "planckian_flag", "command_ladder", "command_render_face", "ladder_text", "command_ladders",
           "SIZE_MAX", "LADDER_SPP_DEFAULT", "LADDER_SIZE_DEFAULT"]

LADDER_SPP_DEFAULT = 64
"""``ladder --spp`` unless given."""

LADDER_SIZE_DEFAULT = 128
"""``ladder --size`` unless given, pixels."""

HELP_SKIN = ("skin of the face: SET:SAMPLE, SET:#N or skin-model:melanin=0.05,blood=0.02 "
             "(default: the scene's)")


def _physics_help() -> str:
    from ..rendering.face.effects import PHYSICS

    return "level of physics: " + choices_help(PHYSICS) + "; effects combine with '+'"


def add_face_arguments(parser: argparse.ArgumentParser) -> None:
    """
    The face options of ``render`` (``--physics``, ``--skin``, ``--size``); the sensor's (``--imager``,
    ``--illuminance``, ``--exposure``) are the render options' (:func:`~skinrender.cli.common.add_render`).
    """
    parser.add_argument("--physics", default="direct",
                        help=_physics_help() + " (face scenes; --imager adds noise)")
    parser.add_argument("--skin", help=HELP_SKIN)
    parser.add_argument("--size", metavar="PX",
                        help="image side of a face scene, pixels (default: the scene's)")


def add_parsers(commands) -> None:
    """Add the parser of ladder."""
    from ..studies.face.ladder import LEVELS_DEFAULT, REPLICATES_LADDER

    p = commands.add_parser("ladder", run=command_ladder,
                            help=f"the face rendered at each level of physics ({level_names(True)}, "
                            "all), with the skin locus's detection rates at each against Eq. 4's (exit 0 Eq. 4 "
                            "shown right within --detection-tolerance at every level, 1 shown wrong at one: a "
                            "finding, 3 one undecided) and the skin's NCC shift against the detection budget")
    p.add_argument("--camera", required=True, action="append", help=HELP_CAMERA + "; repeat it for several cameras, "
                   "seen through one spectral render per level (one ladder each; not with --effects, --plot)")
    p.add_argument("--prevailing", required=True, help="the key light: " + HELP_PLANCKIAN)
    p.add_argument("--calibration", required=True, help="the white balance: " + HELP_PLANCKIAN)
    p.add_argument("--skin", action="append", help=HELP_SKIN + "; repeat it with --effects")
    p.add_argument("--effects", action="store_true",
                   help="the effects table instead: the base and each effect alone (or --levels, with direct) for "
                   "each --skin (default light, medium and dark: the skin model at melanin 0.02, 0.13, 0.3): the "
                   "skin's shift from Eq. 4 against the budget, the TPR/FPR change from direct, the seconds")
    p.add_argument("--scene", default="face", help="face scene: a bundled name (face) or a .toml path")
    p.add_argument("--levels",
                   help="comma-separated levels (" + _physics_help() + "); default "
                   + ",".join(LEVELS_DEFAULT) + " (with --effects: direct and each effect alone)")
    p.add_argument("--size", metavar="PX", default=str(LADDER_SIZE_DEFAULT),
                   help=f"image side in pixels (default {LADDER_SIZE_DEFAULT})")
    p.add_argument("--spp", metavar="N", default=str(LADDER_SPP_DEFAULT),
                   help=f"samples per pixel of a level in all, split over {REPLICATES_LADDER} replicates whose "
                   f"spread is the shift's noise (default {LADDER_SPP_DEFAULT})")
    p.add_argument("--seed", metavar="S", default="0", help="sampler seed, every level the same (default 0)")
    p.add_argument("--imager",
                   help="image sensor of the noise level: a preset or a TOML (default sony-icx418)")
    p.add_argument("--illuminance", metavar="LUX",
                   help="the key light's illuminance at the face, lx, every light scaled with it (default: "
                   "the scene's); only the noise level sees it")
    p.add_argument("--variant",
                   help="force a Mitsuba variant (llvm_ad_spectral, cuda_ad_spectral, scalar_spectral)")
    add_translate(p)
    p.add_argument("--plot", metavar="PNG",
                   help="write the ladder's figure to this PNG: per level the render, the label mask, the "
                   "detected mask and the skin pixels' NCC over the analytic skin locus with the budget; with "
                   "--effects, the table's bars")
    add_detection_options(p)
    add_max_minutes(p, "the levels × --size² × --spp (with --effects, × the skins)")
    from .bands_flags import add_cameras_arguments

    add_cameras_arguments(p)
    add_common(p)


def check_figure(args: argparse.Namespace, *taken) -> Path | None:
    """:func:`~skinrender.cli.inputs.figure_from` ``--figure``."""
    return figure_from(getattr(args, "figure", None), *taken)


def face_flags(args) -> dict:
    """The flags of a face render (``render``, ``validate``, ``detect``) by the keywords of
    :func:`~skinrender.cli.face_inputs.face_request_from` (absent ones their defaults)."""
    names = ("normalization", "grid", "physics", "size", "skin", "imager", "illuminance", "exposure", "sampler")
    moved = translate_of(getattr(args, "translate_mm", None))  # checked: (x, y, z) mm or None
    return {"camera": args.camera, "prevailing": args.prevailing, "calibration": args.calibration,
            **{name: getattr(args, name) for name in names if hasattr(args, name)},
            **({} if moved is None else {"translate_mm": moved})}


def check_face_flags(args: argparse.Namespace, spectral: bool = False) -> tuple:
    """:func:`~skinrender.cli.face_inputs.face_flags_from` the flags of ``args`` (``spectral``: a spectral render's,
    without a camera or a calibration light)."""
    flags = face_flags(args)
    return face_flags_from(*(flags.get(name) for name in ("camera", "prevailing", "calibration")),
                           **{name: flags[name] for name in ("normalization", "grid", "physics", "size")
                              if name in flags}, spectral=spectral)


def face_request_of(args: argparse.Namespace, scene, settings, **changes):
    """:func:`~skinrender.cli.face_inputs.face_request_from` the flags of ``args``."""
    return face_request_from(scene, settings, **face_flags(args), **changes)


def noise_sensor(args: argparse.Namespace, levels: list) -> tuple:
    """:func:`~skinrender.cli.face_inputs.noise_sensor_from` ``--imager`` and ``--illuminance``."""
    return noise_sensor_from(args.imager, args.illuminance, levels)


def is_face_scene(spec: str) -> bool:
    """Whether a ``render`` SCENE is a face scene: bundled, or a TOML with ``[camera]`` and ``[mesh]``."""
    from ..rendering.kinds import FACE

    return FACE.owns(spec)


def _ladder_inputs(args: argparse.Namespace) -> dict:
    """The ladder's flags, each checked with a one-line error naming it (``--skin`` repeats only with
    ``--effects``; ``--levels`` defaults to the base and each effect alone there)."""
    from ..rendering.face.effects import levels_each, levels_ladder
    from ..rendering.face.scene import load_face_scene, skin_reflectance_of
    from ..spectra import GRID_DEFAULT

    from .bands_flags import bands_for_cameras, cameras_of

    cams = cameras_of(args.camera)
    temperatures = {"prevailing": planckian_flag(args.prevailing, "--prevailing"),
                    "calibration": planckian_flag(args.calibration, "--calibration")}
    for cam in cams:
        check_lights_seen(cam, temperatures)
    if len(cams) > 1 and args.effects:
        raise SkinrenderError("--camera: the effects table is one camera's; give one --camera", flag="--camera")
    size = integer_in(args.size, "--size", 1, SIZE_MAX)
    spp = integer_in(args.spp, "--spp", 1, SPP_MAX)
    seed = check_seed(integer_in(args.seed, "--seed", 0, SEED_MAX))
    scene = flag("--scene", load_face_scene, args.scene)
    skins = list(args.skin or [])
    if len(skins) > 1 and not args.effects:
        raise SkinrenderError(f"--skin: one skin for the ladder (several go with --effects), got {len(skins)}")
    for skin in skins:
        skin_reflectance_of(skin, GRID_DEFAULT, "--skin")
    default = ",".join(levels_each() if args.effects else levels_ladder())  # as registered now
    levels = levels_of(default if args.levels is None else args.levels)
    if any(effect.name.startswith("subsurface") for level in levels for effect in level.effects):
        from ..rendering.subsurface import skin_media_of

        for skin in skins:  # the user's skin the subsurface levels fit, refused naming --skin before any render
            skin_media_of(skin, GRID_DEFAULT, "--skin")
    if args.effects and all(level.names for level in levels):
        raise SkinrenderError(f"--levels: the effects table compares each effect with direct; add it, got "
                              f"{','.join(level.name for level in levels)!r}")
    variant_of(args.variant)
    imager, lux = noise_sensor_from(args.imager, args.illuminance, levels)
    from ..studies.face.effects_table import SKIN_TONES

    for skin in skins or (list(SKIN_TONES.values()) if args.effects else [None]):
        moved = translated_face(args.translate_mm, scene, levels, skin)  # each level and skin: float32's range
    from ..studies.face.sweep import estimate_seconds
    from ..studies.face.ladder import REPLICATES_LADDER
    from ..workload import check_work

    bands = bands_for_cameras(args.bands, args.direct, cams)
    tones = len(skins or SKIN_TONES) if args.effects else 1
    renders = len(levels) * REPLICATES_LADDER * tones
    renders *= len(cams) if bands is None else 1
    each = -(-spp // REPLICATES_LADDER)
    check_work(estimate_seconds(renders, size * size, each, 1, [level for level in levels
                                                                for _ in range(renders // len(levels))], bands,
                                tones), "--spp",
               f"{len(levels)} levels of {REPLICATES_LADDER} × {size}×{size} px at {each} spp"
               + (f" for {len(skins or SKIN_TONES)} skins" if args.effects else ""), args.max_minutes,
               fewer="lower --spp or --size, or name fewer --levels")
    return {"cameras": cams, "bands": bands, "prevailing": temperatures["prevailing"],
            "calibration": temperatures["calibration"],
            "levels": levels, "spp": spp, "seed": seed, "size": size, "scene": moved, "variant": args.variant,
            "imager": imager, "illuminance": lux, "skins": skins,
            "skin_set": [skin_set_from(args.skin_set, cam, [temperatures["calibration"]]) for cam in cams][-1],
            "detection_tolerance": detection_tolerance_from(args.detection_tolerance)}


@interruptible
def command_ladder(args: argparse.Namespace) -> None:
    from ..studies.face.effects_table import effects_table
    from ..studies.face.ladder import ladder
    from .ladder_text import effects_text, verdict_text

    plot = check_output(getattr(args, "plot", None), "--plot", (".png",))
    inputs = _ladder_inputs(args)
    cams, bands = inputs.pop("cameras"), inputs.pop("bands")
    if len(cams) > 1:
        skins = inputs.pop("skins")
        return command_ladders(args.json, {**inputs, "skin": skins[0] if skins else None}, cams, bands, plot,
                               getattr(args, "translate_mm", None))
    inputs["camera_"] = cams[0]
    skins = inputs.pop("skins")
    say = lambda line: print(line, file=sys.stderr)  # noqa: E731
    if args.effects:
        result = effects_table(**inputs, skins=None if not skins else {skin: skin for skin in skins}, progress=say)
        document = result.document()
        text = effects_text(result, document)
    else:
        result = ladder(**inputs, skin=skins[0] if skins else None, progress=say)
        document = result.document()
        text = ladder_text(result, document)
    document.update(translate_key(getattr(args, "translate_mm", None)))
    text = _spp_said(document, [document], inputs["spp"]) + text
    if plot is not None:
        write_output(plot, result.figure, "--plot")
        document["plot"] = str(plot)
        text += f"\nfigure: {plot}"
    text += "\n" + verdict_text(document)
    emit(args.json, document, text)
    if document["exit_status"]:
        raise SystemExit(document["exit_status"])


def _spp_said(document: dict, ladders: list, requested: int) -> str:
    """``spp_requested`` put in ``document``, and the note (first: a ladder's last lines are its finding and verdict)
    where the ``ladders``' levels or rows rendered another spp: whole replicates of ⌈spp / replicates⌉."""
    document["spp_requested"] = requested
    used = sorted({row["spp"] for ladder in ladders for row in ladder.get("levels", []) + ladder.get("rows", [])
                   if isinstance(row, dict) and "spp" in row})
    if not used or used == [requested]:
        return ""
    return (f"note: --spp {requested} rendered as {', '.join(map(str, used))} spp (whole replicates of ⌈spp / "
            "replicates⌉)\n")


def command_ladders(as_json: bool, inputs: dict, cameras: list, bands, plot, translate=None) -> None:
    """``ladder`` with several ``--camera``: each level's replicates rendered once spectrally (or, ``--direct``,
    per camera) and seen through every camera; one ladder per camera, the verdict their combination
    (``as_json``: ``--json``)."""
    from ..evaluation.verdict import combine
    from ..rendering.bands import bands_text
    from ..studies.face.ladder import ladders

    if plot is not None:
        raise SkinrenderError("--plot draws one camera's ladder: give one --camera", flag="--plot")
    say = lambda line: print(line, file=sys.stderr)  # noqa: E731
    results = ladders(cameras, **inputs, bands=bands, progress=say)
    documents = [result.document() for result in results]
    verdict = combine([result.verdict for result in results], "ladders")
    spectral = None if bands is None else {"bands_nm": bands_text(bands), "bands": bands.size, "basis": "hat"}
    document = {"cameras": documents, "spectral": spectral, **verdict.summary(), **translate_key(translate)}
    text = _spp_said(document, documents, inputs["spp"])
    text += "\n\n".join(ladder_text(result, doc) for result, doc in zip(results, documents))
    text += (f"\nverdict over {len(results)} cameras: {verdict.outcome.upper().replace('_', ' ')} (exit status "
             f"{document['exit_status']})")
    emit(as_json, document, text)
    if document["exit_status"]:
        raise SystemExit(document["exit_status"])


def command_render_face(args: argparse.Namespace, scene) -> None:
    """
    ``render SCENE …`` for a face scene: the ``render`` flags (``--camera``,
    ``--prevailing``, ``--calibration``, the render options, ``-o``) and the
    face's (:func:`add_face_arguments`; absent ones take their defaults).
    """
    from ..model.response import knee as apply_knee
    from ..rendering.exr import write_exr, write_preview
    from ..rendering.face.render import face_exr

    from ..rendering.kinds import FACE

    settings = settings_from(args.quality, args.spp, args.sampler, args.seed, args.variant, args.channels)
    output = check_output(getattr(args, "output", "render.exr"), "--output", (".exr",))
    check_output(str(output.with_suffix(".png")), "--output (its PNG preview)", (".png",))
    figure = figure_from(args.figure, output.with_suffix(".png"))
    request = face_request_from(scene, settings, **face_flags(args))
    check_request_work(args.max_minutes, request)
    print(f"rendering the face ({request.level.name}) at {settings.spp} spp …", file=sys.stderr)
    result = FACE.render(request)
    if getattr(args, "knee", False):
        import dataclasses

        result = dataclasses.replace(result, image=apply_knee(result.image).astype(result.image.dtype))
    path, preview = output, output.with_suffix(".png")
    outputs = [Output(path, "--output", lambda stream: write_exr(stream, *face_exr(result))),
               Output(preview, "--output (its PNG preview)", lambda stream: write_preview(stream, result.image))]
    if figure is not None:
        from ..studies.labelled import face_figure

        outputs.append(Output(figure, "--figure", lambda stream: face_figure(result, stream)))
    write_outputs(*outputs)  # every file whole, or none of them
    document = {"image": str(path), "preview_png": str(preview), "channels": [*result.channels, "label"],
                "spp": result.spp, "spp_requested": result.spp_requested, "sampler": result.sampler,
                "seed": result.seed, "variant": result.variant, "elapsed_s": result.seconds,
                "scene": result.scene.name, "camera": result.camera.name, "prevailing_K": result.prevailing,
                "calibration_K": result.calibration, "normalization": "white",
                "knee": bool(getattr(args, "knee", False)),
                "labels": result.label_names, "physics": result.physics, "skin": result.skin,
                "size": [result.scene.camera.width, result.scene.camera.height], **result.info,
                **translate_key(getattr(args, "translate_mm", None))}
    if figure is not None:
        document["figure"] = str(figure)
    labels = ", ".join(f"{k}={v}" for k, v in result.label_names.items())
    text = (f"{result.scene.name} ({result.skin}, {result.physics}) through {result.camera.name}, "
            f"{result.prevailing:g} K white-balanced to {result.calibration:g} K: {path} (+ {preview}, "
            f"label channel: {labels}), {result.spp} spp, {result.variant}, {result.seconds:.2f} s")
    emit(args.json, document, text)
