"""
``skinrender validate`` on a face scene: the face rendered at ``--physics``'s
level in replicates and checked against the analytic limits that hold there
(:mod:`skinrender.rendering.face.validation`): ``shading_cancels`` at
``direct``, ``dichromatic_plane`` at ``sheen`` (both through the sensor too,
with ``noise`` or ``--imager``), the white furnace and the closed sphere at
every level, ``detection`` (the skin locus's rates against Eq. 4's,
``--detection-tolerance``, the locus of ``--skin-set``) and, as a diagnostic
that does not decide the verdict, ``eq4_shift`` (Eq. 4's NCC error against the
detection budget) at every level. Each check is a verdict — pass, fail, inconclusive or not
applicable — with its test and α; the validation's verdict is their
combination, and the exit status is the verdict's
(:data:`~skinrender.evaluation.verdict.EXIT_STATUS`): 0 pass (or nothing
applicable), 1 fail, 3 inconclusive, 2 bad input.

Units: temperatures K, times s, NCC fractions.
"""

from __future__ import annotations

import argparse
import sys

from ..errors import SkinrenderError

__all__ = ["command_validate_face", "check_samples", "limits_of", "refuse_chart_verdict_flags"]


def limits_of(text: str | None) -> tuple[str, ...]:
    """
    The scene-free limits to run from ``--limits`` (``furnace,sphere``, ``none``); ``None``: all of them.

    Examples
    --------
    >>> limits_of("sphere"), limits_of("none"), limits_of(None)
    (('sphere',), (), ('furnace', 'sphere'))
    """
    from ..rendering.face.validation import LIMITS_SCENE_FREE

    if text is None:
        return tuple(LIMITS_SCENE_FREE)
    names = [name.strip() for name in str(text).split(",") if name.strip()]
    if names == ["none"]:
        return ()
    unknown = [name for name in names if name not in LIMITS_SCENE_FREE]
    if unknown or not names:
        raise SkinrenderError(f"--limits must be 'none' or a comma-separated list of {', '.join(LIMITS_SCENE_FREE)}, "
                              f"got {text!r}", flag="--limits")
    return tuple(dict.fromkeys(names))


def _number(value) -> str:
    return "—" if value is None else f"{value:.3g}"


def check_samples(spp: int, pixels: int) -> None:
    """
    Refuse (one line naming ``--spp``) a validation whose replicates together take more samples than one
    render may (:data:`~skinrender.rendering.renderer.SAMPLES_MAX`), with the most spp at this size.

    >>> check_samples(48, 256 * 256)
    """
    from ..rendering.face.limits import REPLICATES, SPP_REPLICATE_MIN
    from ..rendering.renderer import SAMPLES_MAX
    from ..studies.face.sweep import SAMPLES_PER_S

    each = max(-(-int(spp) // REPLICATES), SPP_REPLICATE_MIN)
    total = each * REPLICATES * int(pixels)
    if total > SAMPLES_MAX:
        most = REPLICATES * (SAMPLES_MAX // (REPLICATES * int(pixels)))
        if most < REPLICATES * SPP_REPLICATE_MIN:
            raise SkinrenderError(f"--size: {pixels} pixels is too many for {REPLICATES} replicates of at least "
                                  f"{SPP_REPLICATE_MIN} spp; use a smaller --size", flag="--size")
        raise SkinrenderError(f"--spp: {REPLICATES} replicates × {each} spp × {pixels} pixels is {total:.3g} "
                              f"samples, more than one render may take ({SAMPLES_MAX}, ~{SAMPLES_MAX / SAMPLES_PER_S / 60:.0f} "
                              f"min on one core at {SAMPLES_PER_S:.1e} samples/s); at most {most} spp at this size",
                              flag="--spp")


def refuse_chart_verdict_flags(spp, tolerance, spectral: bool = False) -> None:
    """``validate`` on a face: the chart's flags (``--spectral``, ``--spp auto``, ``--tolerance``) refused (the
    face's checks have their own verdicts)."""
    from .inputs import is_auto

    if spectral:
        raise SkinrenderError("--spectral validates a chart (e.g. macbeth) against Eq. 4 and a direct render; a "
                              "face's spectral render is seen through cameras by face-sweep and ladder",
                              flag="--spectral")
    for name, option, given in (("--spp auto", "--spp", is_auto(spp)), ("--tolerance", "--tolerance",
                                                                       tolerance is not None)):
        if given:
            raise SkinrenderError(f"{name} goes with a chart scene; the face's checks have their own verdicts",
                                  flag=option)


def command_validate_face(args: argparse.Namespace, scene) -> None:
    """
    ``validate SCENE …`` for a face scene: the ``validate`` flags (``--camera``, ``--prevailing``,
    ``--calibration``, the render options) and the face's (``--physics``, ``--skin``, ``--size``);
    every flag is checked before anything renders; ``scene``: the face scene loaded.
    """
    from ..rendering.face.limits import REPLICATES, SPP_REPLICATE_MIN
    from ..rendering.kinds import FACE
    from .common import emit, flag, integer_in, settings_from, table
    from .detection_options import detection_tolerance_from, skin_set_from
    from .face import face_flags
    from .face_inputs import SIZE_MAX, face_pixels, face_request_from
    from .inputs import check_request_work
    from .placement import translate_key

    refuse_chart_verdict_flags(args.spp, getattr(args, "tolerance", None), getattr(args, "spectral", False))
    settings = settings_from(args.quality, args.spp, args.sampler, args.seed, args.variant, args.channels)
    if getattr(args, "knee", False):
        raise SkinrenderError("--knee: the face's limits are checked on the linear image; drop --knee", flag="--knee")
    if getattr(args, "gamut", False):
        raise SkinrenderError("--gamut compares a chart's gamut volumes; it does not apply to a face scene",
                              flag="--gamut")
    size = getattr(args, "size", None)
    check_samples(settings.spp, face_pixels(scene, None if size is None else integer_in(size, "--size", 1, SIZE_MAX)))
    each = max(-(-int(settings.spp) // REPLICATES), SPP_REPLICATE_MIN)  # a replicate's spp
    request = face_request_from(scene, settings, **face_flags(args), spp=each)
    # at its level's rate (subsurface-volume: far slower)
    check_request_work(getattr(args, "max_minutes", None), request, REPLICATES)
    limits = flag("--limits", limits_of, getattr(args, "limits", None))
    detection = {"detection_tolerance": detection_tolerance_from(getattr(args, "detection_tolerance", None) or None),
                 "skin_set": skin_set_from(getattr(args, "skin_set", None) or None, request.camera,
                                           [request.calibration])}
    result = flag("validate", FACE.validate, request, spp=settings.spp, limits=limits,
                  progress=lambda line: print(line, file=sys.stderr), **detection)
    document = {**result.document(), **translate_key(getattr(args, "translate_mm", None))}
    rows = [[c.name, c.outcome.replace("_", " ") + ("" if c.applies else " (diagnostic)"), _number(c.statistic),
             _number(c.tolerance), _number(c.bound), f"{c.alpha:g}", c.pixels] for c in result.checks]
    r, verdict = result.rendering, result.verdict
    if verdict.outcome in ("inconclusive", "not_applicable"):
        document["undefined"] = {"passed": f"{verdict.outcome.upper().replace('_', ' ')}: {verdict.reason}"}
    text = (f"{r.scene.name} ({r.skin}, {r.physics}) through {r.camera.name}, {r.prevailing:g} K balanced to "
            f"{r.calibration:g} K, {r.scene.camera.width}×{r.scene.camera.height} px, {result.replicates} "
            f"replicates × {result.info['spp_per_replicate']} spp, {result.spp} spp in all, {r.variant}, "
            f"{result.seconds:.1f} s\n"
            + table(rows, ["check", "verdict", "statistic", "tolerance", "bound", "α", "pixels"])
            + "".join(f"\n{c.name}: {c.reason}\n  test: {c.test}" for c in result.checks)
            + f"\nverdict: {verdict.outcome.upper().replace('_', ' ')} (exit status {document['exit_status']}); "
            "difference tests: statistic = the largest |t| / critical value (≤ 1 passes); detection: the TPR and "
            "FPR changes from Eq. 4's, the renderer's noise separated, bound their 95 % upper bound; eq4_shift "
            "(a diagnostic, not in the verdict): the shift of the skin's mean NCC against the detection budget"
            + ("" if result.spp_needed is None else
               f"\nspp needed for eq4_shift (a diagnostic) to pass: about {result.spp_needed} in all (--spp)"))
    emit(args.json, document, text)
    if document["exit_status"]:
        raise SystemExit(document["exit_status"])
