"""
Spectral renders on the command line: ``render SCENE --spectral``, ``validate CHART --spectral``
==============================================================================================

``render SCENE --spectral --prevailing P [--bands START:END:STEP]`` renders a
chart or a face once with the bands of :mod:`skinrender.rendering.bands` as its
film (no camera, no calibration) into a float32 EXR
(:meth:`~skinrender.rendering.spectral.SpectralImage.save`); any camera is
applied afterwards (``sr.read_spectral(path).through(camera, calibration=K)``).
``validate CHART --spectral`` renders a chart so, sees it through ``--camera``
and checks it against Eq. 4 and against a direct render of that camera
(:func:`~skinrender.rendering.spectral_validation.validate_spectral`).

Units: wavelengths nm, temperatures K, times s, memory bytes.
"""

from __future__ import annotations

import argparse
import os
import sys

from ..errors import SkinrenderError
from .common import check_output, emit, flag, grid_of, settings_of, table

__all__ = ["add_spectral_arguments", "add_cameras_arguments", "bands_of", "bands_for", "check_spectral_work",
           "command_render_spectral", "command_validate_spectral", "command_ladders", "HELP_BANDS"]

HELP_BANDS = ("with --spectral: the band grid START:END:STEP in nm (default 400:700:5, 61 bands), inside --grid: "
              "one film channel per band, a piecewise-linear hat, so that a camera given on this grid is seen "
              "exactly")


def add_spectral_arguments(parser: argparse.ArgumentParser, command: str) -> None:
    """``--spectral`` and ``--bands`` of ``render`` or ``validate`` (``command``)."""
    text = ("render the scene once with a film of wavelength bands instead of the camera's channels: no --camera, no "
            "--calibration (applied afterwards: sr.read_spectral(PATH).through(camera, calibration=K)); -o writes the "
            "bands as a float32 EXR, a channel per band named by its wavelength" if command == "render" else
            "render the chart once with a film of wavelength bands, see it through --camera, and check it against "
            "Eq. 4 (within --tolerance; the difference test allows the bands' basis error, reported) and against a "
            "direct render of --camera at independent seeds (a difference test that must not fire)")
    parser.add_argument("--spectral", action="store_true", help=text)
    parser.add_argument("--bands", metavar="START:END:STEP", help=HELP_BANDS)


def add_cameras_arguments(parser: argparse.ArgumentParser) -> None:
    """``--direct`` and ``--bands`` of a command whose ``--camera`` repeats (``face-sweep``, ``ladder``)."""
    parser.add_argument("--direct", action="store_true",
                        help="render every camera on its own (the default for one --camera); without it several "
                        "cameras are seen through one spectral render per light, skin and level")
    parser.add_argument("--bands", metavar="START:END:STEP",
                        help="the spectral renders' band grid in nm (default 400:700:5): a hat per band, a camera on "
                        "this grid seen exactly")


def bands_for(args: argparse.Namespace, cameras: list):
    """
    The bands several ``--camera`` are seen through (``--bands``, default 400:700:5; each camera checked against
    them), or ``None`` for one render per camera (one camera, or ``--direct``; ``--bands`` then refused).
    """
    from ..rendering.bands import BANDS_DEFAULT, check_bands, parse_bands, projection
    from ..spectra import GRID_DEFAULT

    if len(cameras) == 1 or args.direct:
        if args.bands is not None:
            raise SkinrenderError("--bands: the bands of a spectral render, which several --camera share (not with "
                                  "--direct or one camera)", flag="--bands")
        return None
    bands = BANDS_DEFAULT if args.bands is None else flag("--bands", parse_bands, args.bands)
    flag("--bands", check_bands, bands, GRID_DEFAULT, "the face's lights and reflectances (400–700 nm)")
    for cam in cameras:
        flag({"camera": "--camera", None: "--bands"}, projection, cam, bands, GRID_DEFAULT)
    return bands


def bands_of(args: argparse.Namespace):
    """``--bands`` checked (with ``--spectral`` only), or the default bands; ``None`` without ``--spectral``."""
    from ..rendering.bands import BANDS_DEFAULT, parse_bands

    if not getattr(args, "spectral", False):
        if getattr(args, "bands", None) is not None:
            raise SkinrenderError("--bands goes with --spectral", flag="--bands")
        return None
    return BANDS_DEFAULT if args.bands is None else flag("--bands", parse_bands, args.bands)


def check_spectral_work(args: argparse.Namespace, bands, pixels: int, spp: int, levels=None) -> tuple[float, float]:
    """
    A spectral render's memory and time estimate (:func:`~skinrender.rendering.bands.estimate`: the three-channel
    render's time, :func:`~skinrender.studies.face.sweep.estimate_seconds`, times the bands' cost), refused
    beyond the memory cap or ``--max-minutes`` (naming ``--bands``) before anything renders; ``(bytes, s)``.
    """
    from ..rendering.bands import estimate
    from ..rendering.renderer import SAMPLES_MAX
    from ..studies.face.sweep import estimate_seconds
    from ..workload import check_work

    if spp * pixels > SAMPLES_MAX:
        raise SkinrenderError(f"--spp: {spp} spp × {pixels} pixels = {spp * pixels:.3g} samples per pass, more than "
                              f"{SAMPLES_MAX:.3g}; at most {SAMPLES_MAX // pixels} spp for this scene", flag="--spp")
    three = estimate_seconds(1, pixels, spp, os.cpu_count() or 1, levels)
    memory, seconds = flag("--bands", estimate, bands, pixels, three)
    check_work(seconds, "--bands", f"a spectral render of {bands.size} bands, {pixels} pixels at {spp} spp",
               getattr(args, "max_minutes", None), fewer="use fewer --bands, a lower --spp or a smaller --size")
    return memory, seconds


def _refuse(args: argparse.Namespace, given: dict, why: str) -> None:
    """Refuse the first flag of ``given`` (flag → given?) with ``why``."""
    for name, on in given.items():
        if on:
            raise SkinrenderError(f"{name}: {why}", flag=name)


def _common_refusals(args: argparse.Namespace) -> None:
    _refuse(args, {"--camera": args.camera is not None, "--calibration": args.calibration is not None},
            "a spectral render takes no camera and no calibration: both are applied afterwards "
            "(sr.read_spectral(PATH).through(camera, calibration=K))")
    _refuse(args, {"--figure": getattr(args, "figure", None) is not None, "--knee": bool(args.knee),
                   "--normalization": args.normalization != "white", "--channels": args.channels != "auto"},
            "goes with a camera's render: a spectral render records bands (apply it with through())")


def command_render_spectral(args: argparse.Namespace, scene) -> None:
    """``render SCENE --spectral``: the bands' EXR of a chart or a face (module docstring)."""
    from ..rendering.bands import bands_text
    from ..rendering.face.scene import FaceScene

    _common_refusals(args)
    bands = bands_of(args)
    settings = settings_of(args)
    output = check_output(args.output, "--output", (".exr",))
    face = isinstance(scene, FaceScene)
    if face:
        from ..rendering.face.spectral import render_face_spectral
        from .face import face_inputs, face_pixels

        scene, _, temperatures, physics, skin, size, imager, exposure, lux = face_inputs(args, scene, spectral=True)
        memory, seconds = check_spectral_work(args, bands, face_pixels(scene, size), settings.spp, [physics])
        print(f"rendering the face ({physics}) spectrally, {bands.size} bands, at {settings.spp} spp …",
              file=sys.stderr)
        result = flag({"bands": "--bands", None: "SCENE"}, render_face_spectral, scene, temperatures["prevailing"],
                      skin, physics, settings.spp, settings.seed, size, settings.sampler, settings.variant,
                      bands=bands, imager=imager, exposure=exposure, illuminance=lux)
    else:
        result, memory, seconds = _chart(args, scene, bands, settings)
    result.save(output)
    document = {"image": str(output), "channels": [*result.channels, *(["label"] if face else [])],
                "bands_nm": bands_text(result.bands), "bands": int(result.bands.size), "basis": "hat", "spp": result.spp,
                "spp_requested": result.spp_requested, "sampler": result.sampler, "seed": result.seed,
                "variant": result.variant, "elapsed_s": result.seconds, "scene": result.scene.name,
                "prevailing_K": result.prevailing, "physics": result.physics, "scale": result.scale,
                "memory_estimate_bytes": memory, "seconds_estimate": seconds}
    if face:
        document.update({"skin": result.skin, "labels": result.label_names,
                         "size": [result.scene.camera.width, result.scene.camera.height],
                         "imager": result.info.get("imager"), "exposure": result.info.get("exposure")})
    text = (f"{result.scene.name} ({result.physics}) under {result.prevailing:g} K, {result.bands.size} bands "
            f"{result.bands} (hat basis): {output}, {result.spp} spp, {result.variant}, {result.seconds:.2f} s; see it "
            "through a camera with sr.read_spectral(path).through(camera, calibration=K)")
    emit(args, document, text)


def _chart(args: argparse.Namespace, scene, bands, settings) -> tuple:
    """A chart's spectral render from the flags: ``(image, memory, seconds)``."""
    from ..model.illuminant import illuminant
    from ..rendering.bands import check_bands
    from ..rendering.spectral_chart import render_chart_spectral
    from .inputs import chart_only

    chart_only(args)
    _refuse(args, {"--physics": str(args.physics).strip() != "direct"},
            "a chart's spectral render is at the direct level (subsurface renders each patch as a slab through a "
            "camera)")
    _refuse(args, {"--imager": args.imager is not None, "--illuminance": args.illuminance is not None,
                   "--exposure": args.exposure is not None},
            "a chart's image sensor records a camera's channels: apply it to a direct render of the camera")
    grid = grid_of(args)
    light = flag("--prevailing", illuminant, args.prevailing)
    if light.temperature is None:
        raise SkinrenderError(f"--prevailing: rendering needs a Planckian illuminant (kelvin, A or H), got {light}",
                              flag="--prevailing")
    flag("--bands", check_bands, bands, grid, "the chart's light and reflectances (--grid)")
    try:
        scene.reflectances(grid)
    except SkinrenderError as error:
        raise error.reworded(f"--grid: {error.message}", flag="--grid") from None
    width, height = scene.size
    memory, seconds = check_spectral_work(args, bands, width * height, settings.spp)
    print(f"rendering {scene.name} spectrally, {bands.size} bands, at {settings.spp} spp …", file=sys.stderr)
    result = render_chart_spectral(scene, light.temperature, bands, settings, grid)
    return result, memory, seconds


def command_validate_spectral(args: argparse.Namespace, scene, inputs, settings, tolerance) -> None:
    """``validate CHART --spectral``: the projected render against Eq. 4 and against a direct render."""
    from ..evaluation.verdict import EXIT_STATUS, combine
    from ..rendering.spectral_validation import validate_spectral
    from .chart_validation import _chart_report

    bands = bands_of(args)
    _refuse(args, {"--imager": args.imager is not None, "--gamut": bool(args.gamut)},
            "goes without --spectral (validate --spectral checks the projected render against Eq. 4 and a direct "
            "render)")
    flag("--bands", _inside, bands, inputs.grid)
    from .common import check_render_work

    check_spectral_work(args, bands, inputs.pixels, settings.spp)
    check_render_work(args, inputs.pixels, settings.spp, 2)  # the direct render: prevailing and calibration
    print(f"rendering {inputs.scene.name} spectrally ({bands.size} bands) and directly at {settings.spp} spp …",
          file=sys.stderr)
    result = flag({"camera": "--camera", "bands": "--bands", None: "--camera"}, validate_spectral, inputs.scene,
                  inputs.camera, inputs.prevailing, inputs.calibration, bands=bands, grid=inputs.grid,
                  normalization=inputs.normalization, knee=inputs.knee, tolerance=tolerance, settings=settings)
    document, lines = _chart_report(inputs, result.validation, settings, settings.spp, tolerance)
    document["spectral"] = result.document()
    direct = result.direct_difference
    lines.append(f"spectral: {bands.size} bands {bands} (hat basis), basis error at most "
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


def _inside(bands, grid) -> None:
    from ..rendering.bands import check_bands

    check_bands(bands, grid, "the chart's light and reflectances (--grid)")


def command_ladders(args: argparse.Namespace, inputs: dict, cameras: list, bands, plot) -> None:
    """``ladder`` with several ``--camera``: each level's replicates rendered once spectrally (or, ``--direct``,
    per camera) and seen through every camera; one ladder per camera, the verdict their combination."""
    from ..evaluation.verdict import combine
    from ..studies.face.ladder import ladders
    from .face import ladder_text

    if plot is not None:
        raise SkinrenderError("--plot draws one camera's ladder: give one --camera", flag="--plot")
    say = lambda line: print(line, file=sys.stderr)  # noqa: E731
    inputs = {key: value for key, value in inputs.items() if key != "camera_"}
    results = ladders(cameras, **inputs, bands=bands, progress=say)
    documents = [result.document() for result in results]
    verdict = combine([result.verdict for result in results], "ladders")
    document = {"cameras": documents, "spectral": None if bands is None else {"bands_nm": _text(bands),
                                                                            "bands": bands.size, "basis": "hat"},
                **verdict.summary()}
    text = "\n\n".join(ladder_text(result, doc) for result, doc in zip(results, documents))
    text += f"\nverdict over {len(results)} cameras: {verdict.outcome.upper().replace('_', ' ')} (exit status " \
            f"{document['exit_status']})"
    emit(args, document, text)
    if document["exit_status"]:
        raise SystemExit(document["exit_status"])


def _text(bands) -> str:
    from ..rendering.bands import bands_text

    return bands_text(bands)
