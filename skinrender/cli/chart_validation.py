"""
``skinrender validate`` on a chart: every patch's rendered mean against Eq. 4
(:func:`skinrender.rendering.validation.validate`), through an image sensor
with ``--imager`` (:func:`skinrender.rendering.sensor_validation.validate_imaged`),
and the chart's gamut volumes with ``--gamut``.

The verdict is three-way (:mod:`skinrender.evaluation.verdict`): ``pass`` when
every patch channel is shown within ``--tolerance`` at family-wise 95 %
confidence, ``fail`` when one is shown outside it, ``inconclusive`` when the
samples cannot tell (with ``spp_needed``). Exit status 0 pass, 1 fail,
3 inconclusive, 2 a refused input, 130 an interrupt. ``--spp auto`` picks the
smallest spp expected to pass (:mod:`skinrender.rendering.spp_choice`).

Units: output units (255 for white at p = c), temperatures K, times s.
"""

from __future__ import annotations

import argparse
import dataclasses
import sys

from ..errors import SkinrenderError
from .common import emit, flag, interruptible, settings_from, table
from .placement import translate_key

__all__ = ["HELP_TOLERANCE", "EPILOG_VALIDATE", "SIGMAS_DEPRECATED", "add_check_arguments", "add_verdict_arguments",
           "tolerance_of", "tolerance_from", "spp_of", "spp_auto_from", "command_validate", "command_validate_chart",
           "command_validate_spectral"]

HELP_TOLERANCE = (
    "relative tolerance REL in [5.96e-08 (2^-24), 1) on each lit patch channel (default 0.01, 1 %%); a channel darker than 1 %% of "
    "white (a perfect white's brightest channel under the prevailing light: 255 output units at p = c with the "
    "white normalisation) is held to the absolute floor REL × 1 %% of that white. pass: every patch channel shown within it at "
    "family-wise 95 %% confidence; fail: one shown outside it; inconclusive: the samples cannot tell (spp_needed "
    "says how many would)")

from ..rendering.chart_document import SIGMAS_DEPRECATED  # noqa: E402, F401 - the JSON's (re-exported)

EPILOG_VALIDATE = ("exit status: 0 pass, 1 fail, 3 inconclusive (a chart: the verdict of --tolerance; a face: its "
                   "checks' verdicts combined, detection held to --detection-tolerance; eq4_shift against the "
                   "detection budget is a diagnostic), 2 a refused input, 130 interrupted")


def add_check_arguments(p) -> None:
    """``validate``'s ``--gamut`` (charts) and ``--limits`` (faces), added to the parser
    :mod:`skinrender.cli.rendering` builds."""
    p.add_argument("--gamut", action="store_true",
                   help="also render the chart under every paper illuminant and compare its gamut volumes "
                   "(one calibration case each, and all calibrations) with the analytic ones, within "
                   "--tolerance (relative to each volume)")
    p.add_argument("--limits", metavar="LIST",
                   help="face scenes: the scene-free limits run beside the level's own: furnace, sphere "
                   "(comma-separated) or none (default: both)")
    p.add_argument("--detection-tolerance", metavar="RATE",
                   help="face scenes: how far Eq. 4 may be off in TPR and in FPR, a fraction in (0, 1), for the "
                   "detection check (default 0.02)")
    p.add_argument("--skin-set", metavar="SET",
                   help="face scenes: the reflectance set of the skin locus the detection check classifies with "
                   "(default skin; skin-tones spans very light to very dark)")


def add_verdict_arguments(p) -> None:
    """``validate``'s verdict flags and epilog, added to the parser :mod:`skinrender.cli.rendering` builds."""
    p.add_argument("--tolerance", metavar="REL", help=HELP_TOLERANCE)
    p.epilog = EPILOG_VALIDATE


@interruptible
def command_validate(args: argparse.Namespace) -> None:
    """``validate``: a face (:mod:`skinrender.cli.face_validation`) or a chart (:func:`command_validate_chart`),
    the scene loaded once."""
    from .face_validation import command_validate_face
    from .inputs import by_kind, scene_from

    scene = scene_from(args.scene)
    return by_kind(scene, chart=command_validate_chart, face=command_validate_face)(args, scene)


def tolerance_of(args: argparse.Namespace) -> float:
    """:func:`tolerance_from` ``--tolerance``."""
    return tolerance_from(args.tolerance)


def tolerance_from(text) -> float:
    """``--tolerance`` checked (in (0, 1)), or the default."""
    from ..rendering.agreement import TOLERANCE_DEFAULT, check_tolerance

    return TOLERANCE_DEFAULT if text is None else check_tolerance(text, "--tolerance")


def spp_of(args: argparse.Namespace) -> bool:
    """:func:`spp_auto_from` ``--spp`` and ``--tolerance``."""
    return spp_auto_from(args.spp, args.tolerance)


def spp_auto_from(spp, tolerance) -> bool:
    """
    Whether ``--spp`` is ``auto`` (then ``--tolerance`` must be given); any other ``--spp`` is
    :func:`~skinrender.cli.common.settings_from`'s.
    """
    from .inputs import is_auto

    if not is_auto(spp):
        return False
    if tolerance is None:
        raise SkinrenderError("--spp auto picks the smallest spp expected to pass --tolerance: give --tolerance "
                              "REL as well", flag="--spp")
    return True


def _number(value: float) -> str:
    return f"{value:.5g}"


def _summary(name: str, verdict) -> list[str]:
    """A check's lines: its outcome and reason, then its test in words."""
    return [f"{name}: {verdict.outcome.upper().replace('_', ' ')} — {verdict.reason}", f"  test: {verdict.test}"]


def _auto_spp(request, tolerance) -> dict:
    """``--spp auto``: the pilots and the spp chosen (:meth:`~skinrender.rendering.kinds.ChartKind.choose_spp`,
    as ``skinrender.validate(…, spp="auto")``), with a line on stderr before and after."""
    from ..rendering.kinds import CHART

    print(f"spp auto: pilot renders of {request.scene.name} …", file=sys.stderr)
    choice = CHART.choose_spp(request, tolerance)
    print(f"spp auto: {choice['spp']} spp ({choice['why']})", file=sys.stderr)
    return choice


def _refused(request, option: str, flag: str, words: str) -> None:
    """Refuse a validation ``option`` (its ``flag``) that an effect of the request's level does not take."""
    refused = request.level.refused(option)
    if refused is not None:
        effect, why = refused
        given = [f"--physics {effect.name}"] * effect.named + [f"--{name}" for name in effect.added_by]
        raise SkinrenderError(f"{words} does not go with {' or '.join(given)}: {why}", flag=flag)


def command_validate_chart(args: argparse.Namespace, scene) -> None:
    """``validate`` on a chart ``scene`` (loaded by :func:`command_validate`; the face is
    :mod:`skinrender.cli.face_validation`)."""
    from ..evaluation.verdict import EXIT_STATUS
    from ..rendering.kinds import CHART
    from ..rendering.sensor_validation import ImagedValidation
    from ..rendering.spp_choice import PILOT_SPP
    from ..model.response import uses_whites
    from .inputs import chart_flags, chart_request_from, check_request_work, refuse_face_flags

    tolerance = tolerance_from(args.tolerance)
    auto = spp_auto_from(args.spp, args.tolerance)
    refuse_face_flags(args.physics, args.skin, args.size)
    for option, given in (("--limits", args.limits), ("--detection-tolerance", args.detection_tolerance),
                          ("--skin-set", args.skin_set)):
        if given is not None:
            raise SkinrenderError(f"{option} goes with a face scene (e.g. 'face'), not a chart", flag=option)
    if args.gamut and (not uses_whites(args.normalization) or args.knee):  # its volumes were taken with WP, no knee
        given = "--knee" if args.knee else f"--normalization {args.normalization}"
        raise SkinrenderError(f"--gamut compares the volumes of Eq. 4 with the white normalisation and no knee; "
                              f"{given} would not apply to them: drop one of the two", flag="--gamut")
    if args.knee and args.imager is not None:  # the sensor's tests compare linear codes with its model
        raise SkinrenderError("--knee: validate --imager tests the sensor's linear codes (DN) against its model; "
                              "drop --knee", flag="--knee")
    settings = settings_from(args.quality, args.spp, args.sampler, args.seed, args.variant, args.channels, auto)
    requested = "auto" if auto else settings.spp
    request = chart_request_from(scene, settings, **chart_flags(args))
    if args.spectral or args.bands is not None:
        from .bands_flags import bands_from

        bands_from(args.spectral, args.bands)  # --bands without --spectral: refused
        if auto:
            raise SkinrenderError("--spp auto goes without --spectral: give --spp N", flag="--spp")
        return command_validate_spectral(args, request, tolerance)
    if args.gamut:  # the gamut volumes of the Lambertian, noise-free chart
        _refused(request, "gamut", "--gamut", "--gamut (the chart's gamut volumes under the paper's lights)")
    if auto:
        _refused(request, "spp_auto", "--spp", "--spp auto")
    renders = 11 if args.gamut else 1  # --gamut: ten more, one per paper illuminant
    choice = None
    if auto:
        check_request_work(args.max_minutes, request, len(PILOT_SPP), max(PILOT_SPP))
        choice = _auto_spp(request, tolerance)
        request = dataclasses.replace(request, settings=request.settings.replace(spp=choice["spp"]))
    check_request_work(args.max_minutes, request, renders)
    settings = request.settings
    print(f"rendering {request.scene.name} at {settings.spp} spp and validating …", file=sys.stderr)
    result = CHART.validate(request, tolerance=tolerance)
    if isinstance(result, ImagedValidation):  # through the image sensor: the sensor's checks too
        document, text = _imaged_report(result, result.imaged, requested)
        verdict = result.verdict
    else:
        document, lines = _chart_report(request, result, settings, requested, tolerance)
        document.update(translate_key(getattr(args, "translate_mm", None)))
        verdict = result.verdict
        if args.gamut:
            verdict = _gamut(request, settings, tolerance, document, lines, verdict)
        text = "\n".join(lines)
        document["verdict"] = verdict.outcome
        document["passed"] = verdict.outcome == "pass"
    if choice is not None:
        document["spp_auto"] = choice
        text = f"spp auto: {choice['spp']} spp — {choice['why']}\n" + text
    document["exit_status"] = EXIT_STATUS[verdict.outcome]
    text += f"\nverdict: {verdict.outcome.upper().replace('_', ' ')} (exit status {document['exit_status']})"
    emit(args.json, document, text)
    if document["exit_status"]:
        raise SystemExit(document["exit_status"])


def _chart_report(inputs, result, settings, requested, tolerance) -> tuple[dict, list[str]]:
    """A chart validation's document and text lines: per patch and channel the values, error, bound, tolerance."""
    from ..rendering.renderer import channel_names
    from .common import SPP_MAX
    from .subsurface import subsurface_lines

    r = result.rendering
    document = result.document(requested)  # the one document, Python's too (rendering.chart_document)
    names = channel_names(r.camera)
    rows = [[p["name"], names[k], _number(p["analytic"][k]), _number(p["rendered"][k]), f"{p['error'][k]:+.3g}",
             f"{p['bound'][k]:.3g}", f"{p['tolerance'][k]:.3g}", p["shown"][k]]
            for p in document["patches"] for k in range(3)]
    lines = [f"{r.scene.name} through {r.camera.name}, {r.prevailing:g} K / {r.calibration:g} K, "
             f"{r.raw[0].spp} spp {settings.sampler}, {r.variant}, {r.seconds:.2f} s; output units (a perfect "
             f"white's brightest channel: {result.white_level:.4g}); bound: the upper 95 % (family-wise) confidence "
             "bound of |error|",
             *subsurface_lines(r), table(rows, ["patch", "channel", "analytic", "rendered", "error", "bound", "tolerance", "shown"])]
    lines += _summary("equivalence", result.verdict)
    needed = "—" if result.spp_needed is None else (result.spp_needed if result.spp_needed <= SPP_MAX
                                                    else f"{result.spp_needed:.3g} (more than a render may take)")
    lines.append(f"  bound {result.bound:.3g} (the smallest relative tolerance that would pass; asked {tolerance:g}); "
                 f"spp needed ≈ {needed} (bounds taken to fall as 1/√spp: an upper estimate for multijitter)")
    lines += _summary("difference", result.difference)
    lines.append(f"paper Σ vs rendered integral (quadrature): {result.quadrature:.1e} relative")
    return document, lines


def _gamut(inputs, settings, tolerance, document, lines, verdict):
    """``--gamut``: the volumes' verdicts added to the document and the text; the combined verdict. The chart and
    the camera are the objects the command parsed (a CSV camera keeps its ``--extrapolation``)."""
    from ..evaluation.verdict import Verdict, combine
    from ..rendering.validation import validate_gamut

    gamuts = validate_gamut(inputs.scene, inputs.camera, settings=settings, grid=inputs.grid, tolerance=tolerance)
    document["gamut"] = gamuts
    labels = [f"calibration {t:g} K" for t in gamuts["illuminants_K"]] + ["all calibrations"]
    rows = [[label, f"{a:.6g}", f"{r:.6g}", f"{s:.2g}", f"{b:.3g}"]
            for label, r, a, s, b in zip(labels, gamuts["rendered"], gamuts["analytic"], gamuts["sigma"],
                                         gamuts["bound"])]
    lines.append(f"gamut volumes (output units³), {len(gamuts['illuminants_K'])} illuminants:")
    lines.append(table(rows, ["volume", "analytic", "rendered", "σ", "relative bound"]))
    doc = gamuts["verdict"]
    lines.append(f"gamut equivalence: {doc['verdict'].upper().replace('_', ' ')} — {doc['reason']}")
    lines.append(f"gamut difference: {gamuts['difference']['verdict']} — {gamuts['difference']['reason']}")
    gamut_verdict = Verdict("gamut", doc["verdict"], doc["alpha"], doc["test"], reason=doc["reason"])
    return combine([verdict, gamut_verdict], "validation")


def _imaged_report(result, imaged, requested) -> tuple[dict, str]:
    """``validate --imager``'s document and text."""
    from ..rendering.renderer import channel_names
    from .inputs import imaging_document, imaging_notes

    rendering = imaged.rendering
    patches = result.patches()
    checks = {**result.checks, "difference": result.difference}
    document = {"scene": rendering.scene.name, "camera": rendering.camera.name, "prevailing_K": rendering.prevailing,
                "calibration_K": rendering.calibration, "normalization": rendering.normalization,
                "spp": rendering.raw[0].spp, "spp_requested": requested, "seed": rendering.raw[0].seed,
                "variant": rendering.variant, "elapsed_s": rendering.seconds, **imaging_document(imaged),
                "tolerance": result.checks["equivalence"].tolerance, "bound": result.bound,
                "spp_needed": result.spp_needed, "spp_needed_reason": result.spp_reason or None,
                "mc_variance": result.mc_variance,
                "test": result.difference.test, "alpha_per_test": result.level,
                "checks": {name: v.document() for name, v in checks.items()},
                "saturation": result.saturation.document(), "patches": patches,
                "verdict": result.verdict.outcome, "passed": result.passed}
    names = channel_names(rendering.camera)
    rows = [[p["name"], names[k], _number(p["analytic"][k]), _number(p["rendered"][k]), f"{p['error'][k]:+.3g}",
             *((f"{p['bound'][k]:.3g}", f"{p['tolerance'][k]:.3g}") if not p["saturated"][k] else ("saturated", "—")),
             f"{p['rendered_std'][k]:.3g}",
             f"{p['predicted_std'][k]:.3g}", f"{p['p_mean'][k]:.2g}", f"{p['p_variance'][k]:.2g}"]
            for p in patches for k in range(3)]
    lines = [f"{rendering.scene.name} through {rendering.camera.name} and {imaged.imager.name}, "
             f"{imaged.illuminance_lux:g} lx, {imaged.exposure_s * 1e3:.3g} ms, {rendering.raw[0].spp} spp; output "
             "units; predicted std: the sensor's and the render's together",
             table(rows, ["patch", "channel", "analytic", "rendered", "error", "bound", "tolerance", "std",
                          "predicted std", "p mean", "p variance"])]
    for name in ("equivalence", "variance", "mean"):
        lines += _summary(name, result.checks[name])
    if result.saturation.outcome != "not_applicable":
        lines += _summary("saturation", result.saturation)
    needed = result.spp_needed if result.spp_needed is not None else f"— ({result.spp_reason})"
    bound = "—" if result.bound is None else f"{result.bound:.3g}"
    lines.append(f"bound {bound} (the smallest relative tolerance the means would pass); spp needed ≈ "
                 f"{needed}")
    return document, "\n".join(lines) + imaging_notes(imaged)


def command_validate_spectral(args: argparse.Namespace, request, tolerance: float) -> None:
    """``validate CHART --spectral``: the chart of ``request`` (the camera's) rendered once spectrally, seen
    through its camera, against Eq. 4 and against a direct render
    (:func:`~skinrender.rendering.spectral_validation.validate_spectral`)."""
    from ..evaluation.verdict import EXIT_STATUS, combine
    from ..rendering.bands import bands_text, check_bands
    from ..rendering.spectral_validation import validate_spectral
    from .bands_flags import bands_of, check_spectral_work
    from .inputs import check_request_work

    bands = bands_of(args)
    for name, given in (("--imager", request.sensor is not None), ("--gamut", bool(args.gamut)),
                        ("--physics", bool(request.level.names))):
        if given:
            raise SkinrenderError(f"{name} goes without --spectral (validate --spectral checks the projected render "
                                  "of the direct level against Eq. 4 and a direct render)", flag=name)
    flag("--bands", check_bands, bands, request.grid, "the chart's light and reflectances (--grid)")
    settings = request.settings
    check_spectral_work(args, bands, request.pixels, settings.spp)
    check_request_work(args, request, 2)  # the direct render: prevailing and calibration
    print(f"rendering {request.scene.name} spectrally ({bands.size} bands) and directly at {settings.spp} spp …",
          file=sys.stderr)
    result = flag({"camera": "--camera", "bands": "--bands", None: "--camera"}, validate_spectral, request.scene,
                  request.camera, request.prevailing, request.calibration, bands=bands, grid=request.grid,
                  normalization=request.normalization, knee=request.knee, tolerance=tolerance, settings=settings)
    document, lines = _chart_report(request, result.validation, settings, settings.spp, tolerance)
    document["spectral"] = result.document()
    direct = result.direct_difference
    lines.append(f"spectral: {bands.size} bands {bands_text(bands)} nm (hat basis), basis error at most "
                 f"{result.basis_relative:.2g} relative (Eq. 4 of the camera as the bands see it − of its curves; "
                 "allowed in the difference test above)")
    lines.append(f"spectral − direct render (seed {result.direct.raw[0].seed}): {direct.outcome.upper()} — "
                 f"{direct.reason}")
    verdict = combine([result.verdict, direct], "validation")
    document["verdict"], document["passed"] = verdict.outcome, verdict.outcome == "pass"
    document["exit_status"] = EXIT_STATUS[verdict.outcome]
    rows = [[name, document["checks"][key]["verdict"] if key in document["checks"] else direct.outcome]
            for name, key in (("Eq. 4 within tolerance", "equivalence"), ("Eq. 4 difference", "difference"),
                              ("spectral − direct difference", "direct"))]
    text = "\n".join(lines) + "\n" + table(rows, ["check", "outcome"])
    text += f"\nverdict: {verdict.outcome.upper().replace('_', ' ')} (exit status {document['exit_status']})"
    emit(args, document, text)
    if document["exit_status"]:
        raise SystemExit(document["exit_status"])
