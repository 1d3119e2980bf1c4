"""
Spectral renders on the command line: ``render SCENE --spectral``, ``bench render --spectral``
==============================================================================================

``render SCENE --spectral --prevailing P [--bands START:END:STEP]`` renders a
chart or a face once with the bands of :mod:`skinrender.rendering.bands` as its
film (no camera, no calibration) into a float32 EXR
(:meth:`~skinrender.rendering.spectral_image.SpectralImage.save`); any camera is
applied afterwards (``sr.read_spectral(path).through(camera, calibration=K)``).
``bench render --spectral [--cameras N,…]`` measures the trade
(:mod:`skinrender.studies.benchmarks.bench_spectral`). ``validate CHART
--spectral`` is :func:`skinrender.cli.chart_validation.command_validate_spectral`; the flags are
:mod:`skinrender.cli.bands_flags`.

Units: wavelengths nm, temperatures K, times s, memory bytes.
"""

from __future__ import annotations

import argparse
import sys

from ..errors import SkinrenderError
from .bands_flags import bands_of, check_spectral_work
from .common import check_output, emit, flag, flagged, grid_of, settings_of, table
from .inputs import by_kind

__all__ = ["command_render_spectral", "add_bench_spectral_arguments", "command_bench_spectral",
           "BENCH_SPECTRAL_REFUSED"]


def _refuse(args: argparse.Namespace, given: dict, why: str) -> None:
    """Refuse the first flag of ``given`` (flag → given?) with ``why``."""
    for name, on in given.items():
        if on:
            raise SkinrenderError(f"{name}: {why}", flag=name)


def _common_refusals(args: argparse.Namespace) -> None:
    from ..model.response import uses_whites
    from ..rendering.settings import CHANNELS_DEFAULT

    _refuse(args, {"--camera": args.camera is not None, "--calibration": args.calibration is not None},
            "a spectral render takes no camera and no calibration: both are applied afterwards "
            "(sr.read_spectral(PATH).through(camera, calibration=K))")
    _refuse(args, {"--figure": getattr(args, "figure", None) is not None, "--knee": bool(args.knee),
                   "--normalization": not uses_whites(args.normalization),
                   "--channels": args.channels != CHANNELS_DEFAULT},
            "goes with a camera's render: a spectral render records bands (apply it with through())")


def command_render_spectral(args: argparse.Namespace, scene) -> None:
    """``render SCENE --spectral``: the bands' EXR of a chart or a face (module docstring): the scene kind's
    request with ``bands`` (no camera, no calibration), rendered by the kind."""
    from ..rendering.bands import bands_text
    from ..rendering.kinds import scene_kind

    _common_refusals(args)
    bands = bands_of(args)
    settings = settings_of(args)
    output = check_output(args.output, "--output", (".exr",))
    kind = scene_kind(scene)
    request = by_kind(scene, chart=_chart_request, face=_face_request)(args, scene, settings, bands)
    memory, seconds = check_spectral_work(args, bands, request.pixels, request.settings.spp, [request.level])
    print(f"rendering {request.scene.name} ({request.level.name}) spectrally, {bands.size} bands, at "
          f"{request.settings.spp} spp …", file=sys.stderr)
    result = flag({"bands": "--bands", None: "SCENE"}, kind.render, request)
    face = result.labels is not None  # a face's: its label channel and skin
    result.save(output)
    document = {"image": str(output), "channels": [*result.channels, *(["label"] if face else [])],
                "bands_nm": bands_text(result.bands), "bands": int(result.bands.size), "basis": "hat", "spp": result.spp,
                "spp_requested": result.spp_requested, "sampler": result.sampler, "seed": result.seed,
                "variant": result.variant, "elapsed_s": result.seconds, "scene": result.scene.name,
                "prevailing_K": result.prevailing, "physics": result.physics, "scale": result.scale,
                "memory_estimate_bytes": memory, "seconds_estimate": seconds}
    if face:
        sensor = request.sensor
        document.update({"skin": result.skin, "labels": result.label_names,
                         "size": [result.scene.camera.width, result.scene.camera.height],
                         "imager": None if sensor is None or sensor.imager is None else sensor.imager.name,
                         "exposure": None if sensor is None else sensor.exposure})
    text = (f"{result.scene.name} ({result.physics}) under {result.prevailing:g} K, {result.bands.size} bands "
            f"{bands_text(result.bands)} nm (hat basis): {output}, {result.spp} spp, {result.variant}, "
            f"{result.seconds:.2f} s; see it through a camera with sr.read_spectral(path).through(camera, "
            "calibration=K)")
    emit(args, document, text)


def _face_request(args: argparse.Namespace, scene, settings, bands):
    """A face's spectral request from the flags (:func:`~skinrender.cli.face.face_request_of`, with ``bands``)."""
    from .face import face_request_of

    return face_request_of(args, scene, settings, bands=bands)


def _chart_request(args: argparse.Namespace, scene, settings, bands):
    """A chart's spectral request from the flags (each refusal naming its flag): the direct level, no sensor."""
    from ..rendering.chart_effects import CHART_REGISTRY
    from ..rendering.kinds import CHART
    from .inputs import REQUEST_FLAGS, chart_only, settings_fields

    chart_only(args)
    _refuse(args, {"--physics": bool(flag("--physics", CHART_REGISTRY.names, args.physics))},
            "a chart's spectral render is at the direct level (subsurface renders each patch as a slab through a "
            "camera)")
    _refuse(args, {"--imager": args.imager is not None, "--illuminance": args.illuminance is not None,
                   "--exposure": args.exposure is not None},
            "a chart's image sensor records a camera's channels: apply it to a direct render of the camera")
    grid = grid_of(args)
    request = flagged(REQUEST_FLAGS, CHART.request, scene, None, args.prevailing, None, grid=grid, bands=bands,
                      **settings_fields(args, settings))
    try:
        scene.reflectances(grid)
    except SkinrenderError as error:
        raise error.reworded(f"--grid: {error.message}", flag="--grid") from None
    return request


BENCH_SPECTRAL_REFUSED = ("quick", "scene", "camera", "size", "levels", "spp_list", "reference_spp", "workers")
"""``bench render`` flags that do not go with ``--spectral`` (its workload is fixed: docs/spectral.md)."""


def add_bench_spectral_arguments(parser: argparse.ArgumentParser) -> None:
    """``bench render --spectral`` and its ``--cameras``."""
    parser.add_argument("--spectral", action="store_true",
                        help="render: the spectral render's trade on a face sweep (2 light pairs × 2 skins × 2 levels, "
                        "64 px, 16 spp): seconds one render per camera against one spectral render seen through "
                        "each, at equal error on a broad channel; the narrow-channel penalty; the basis error")
    parser.add_argument("--cameras", metavar="N[,N…]",
                        help="render --spectral: camera counts of the rows (default 1,5,20,61; at most 61)")


def command_bench_spectral(args: argparse.Namespace) -> None:
    """``bench render --spectral [--cameras N,…] [--plot PNG]`` (:func:`~skinrender.studies.benchmarks.bench_spectral.bench_spectral`)."""
    from ..studies.benchmarks.bench_spectral import CAMERA_COUNTS, bench_spectral, estimate_bench_seconds
    from ..workload import check_work
    from .common import integer_in

    for dest in BENCH_SPECTRAL_REFUSED:
        if getattr(args, dest, None) not in (None, False):
            name = "--" + dest.replace("_", "-")
            raise SkinrenderError(f"{name} does not go with 'bench render --spectral' (its workload is fixed)", flag=name)
    counts = list(CAMERA_COUNTS)
    if args.cameras is not None:
        counts = [integer_in(part.strip(), "--cameras", 1, 61) for part in str(args.cameras).split(",")]
        if len(set(counts)) < len(counts):
            raise SkinrenderError(f"--cameras: each count once, got {args.cameras!r}", flag="--cameras")
    plot = check_output(args.plot, "--plot", (".png",))
    check_work(estimate_bench_seconds(counts), "--cameras", f"the sweeps of {', '.join(map(str, counts))} cameras "
               "both ways", args.max_minutes, fewer="ask for fewer --cameras")
    result = bench_spectral(counts, progress=lambda line: print(line, file=sys.stderr))
    if plot is not None:
        from ..files import write_output
        from ..studies.benchmarks.spectral_figure import figure_spectral

        write_output(plot, lambda stream: figure_spectral(result, stream), "--plot")
        result["plot"] = str(plot)
    rows = [[row["cameras"], f"{row['spectral_s']:.1f}", f"{row['direct_s']:.1f}", f"{row['speedup_timed']:.2f}",
             f"{row['speedup']:.2f}", f"{row['error_spectral']:.4f}", f"{row['error_direct']:.4f}"]
            for row in result["rows"]]
    narrow, crn = result["narrow"], result["common_random_numbers"]
    text = (f"face sweep: {len(result['lights_K'])} light pairs × {len(result['skins'])} skins × "
            f"{len(result['levels'])} levels, {result['size']} px, {result['spp']} spp, one worker; errors on the "
            f"{result['errors']['channel']} channel against {result['reference_spp']}-spp references:\n"
            + table(rows, ["cameras", "spectral s", "direct s", "speedup (timed)", "speedup (equal error)",
                           "error spectral", "error direct"])
            + f"\nnarrow channels ({narrow['camera']}): error spectral "
            + " ".join(f"{v:.4f}" for v in narrow["error_spectral"]) + ", direct "
            + " ".join(f"{v:.4f}" for v in narrow["error_direct"]) + "; penalty (spp factor) "
            + " ".join(f"{v:.2f}" for v in narrow["penalty"])
            + f"\ncommon random numbers ({' − '.join(crn['cameras'])}, Macbeth, {crn['seeds']} seeds): variance of the "
            f"difference {crn['variance_ratio_median']:.3g}× smaller through one spectral render (median; "
            f"{crn['variance_ratio_min']:.3g}–{crn['variance_ratio_max']:.3g})"
            + "".join(f"\nbasis error {row['camera']} at {row['bands_nm']} nm: {row['max_rel_error']:.2g}"
                      for row in result["basis"] if row["bands_nm"].endswith(":5"))
            + (f"\nfigure: {plot}" if plot is not None else ""))
    emit(args, result, text)
