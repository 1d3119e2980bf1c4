"""
Command line
============

``skinrender COMMAND …``: the commands of CONTRACT.md. Thin: parse, call the
package, print. Every command takes ``--json`` and then prints exactly one JSON
document on stdout; progress and errors go to stderr. A bad input exits with
status 2 and a one-line message, never a traceback.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence

from .errors import SkinrenderError

__all__ = ["main", "build_parser"]

HELP_CAMERA = (
    "camera: 'gbell:N@P1,P2,P3' (sensor N, FWHM N·10 nm, peaks in nm), 'gbell:N,b=B@…', "
    "'impulse@P1,P2,P3', a bundled name (see 'skinrender cameras') or a CSV path "
    "(wavelength nm, R, G, B)"
)
HELP_ILLUMINANT = "kelvin (3300 or 3300K, a Planckian radiator), A (2856 K), H (Horizon, 2300 K) or a CSV path"
HELP_GRID = "integration grid START:END:STEP in nm (default 400:700:1)"


def _add_common(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--json", action="store_true", help="print one JSON document on stdout")


def _add_grid(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--grid", default="400:700:1", help=HELP_GRID)
    parser.add_argument(
        "--extrapolation", default="refuse", choices=["refuse", "zero", "constant"],
        help="for CSV cameras and reflectances that do not cover the grid: refuse (default), "
        "zero outside the measured range, or hold the end value",
    )


def _add_model(parser: argparse.ArgumentParser) -> None:
    from .camera import NORMALISATIONS

    parser.add_argument("--normalization", default="white", choices=NORMALISATIONS,
                        help="illuminant normalisation: none (Eq. 5), 560nm (Eq. 6), euclidean (Eq. 7), "
                        "white (Eq. 8, default)")
    parser.add_argument("--knee", action="store_true", help="apply the knee of Eq. 11 (output ≤ 255)")


def _add_search(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--skin", default="skin", help="skin reflectance set, name or CSV path (default skin)")
    parser.add_argument("--munsell", default="munsell", help="Munsell reflectance set, name or CSV path (default munsell)")
    parser.add_argument("--workers", type=int, help="processes (default: every core)")
    parser.add_argument("--dask", metavar="ADDRESS", help="run on a Dask cluster (scheduler address, tcp://host:8786)")
    parser.add_argument("--quiet", action="store_true", help="no progress bar on stderr")


def _add_render(parser: argparse.ArgumentParser) -> None:
    from .render import QUALITY_PRESETS, SAMPLERS

    parser.add_argument("--quality", choices=list(QUALITY_PRESETS), default="standard",
                        help="preset: draft (16 spp), standard (256 spp, default), reference (4096 spp), multijitter")
    parser.add_argument("--spp", type=int, help="samples per pixel (overrides --quality)")
    parser.add_argument("--sampler", choices=SAMPLERS, help="Mitsuba sampler (default multijitter)")
    parser.add_argument("--seed", type=int, default=0, help="sampler seed; the same seed gives the same image (default 0)")
    parser.add_argument("--variant", help="force a Mitsuba variant (llvm_ad_spectral, cuda_ad_spectral, scalar_spectral); "
                        "default: the fastest that works here")
    parser.add_argument("--channels", choices=["auto", "together", "separate"], default="auto",
                        help="render the three channels in one pass or one pass each (auto: separate for the "
                        "impulse, narrow gbell or very unequal channels)")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of every command."""
    parser = argparse.ArgumentParser(
        prog="skinrender",
        description="Design and validate three-channel cameras for skin detection "
        "(wavelengths in nm, temperatures in K, radiance in W·m⁻²·sr⁻¹·nm⁻¹).",
    )
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    p = commands.add_parser("cameras", help="list bundled cameras")
    _add_common(p)

    p = commands.add_parser("datasets", help="list reflectance sets with source, licence, count, range")
    _add_common(p)

    p = commands.add_parser("illuminants", help="Stage 1: illuminants equally spaced in the NCC measure")
    p.add_argument("--camera", required=True, help=HELP_CAMERA)
    p.add_argument("--range", nargs=2, type=float, default=[2000.0, 10000.0], metavar=("START_K", "END_K"),
                   help="candidate temperatures, K (default 2000 10000)")
    p.add_argument("--step", type=float, default=100.0, help="candidate spacing, K (default 100)")
    p.add_argument("--count", type=int, default=10, help="how many illuminants (default 10)")
    p.add_argument("--pair", default="gb", help="NCC pair of the Eq. 3 measure (default gb)")
    _add_grid(p)
    _add_common(p)

    p = commands.add_parser("response", help="Eq. 4 white-balanced responses and NCC of a reflectance set")
    p.add_argument("--camera", required=True, help=HELP_CAMERA)
    p.add_argument("--reflectances", required=True,
                   help="reflectance set: a name (see 'skinrender datasets') or a CSV path "
                   "(wavelength nm, one column per sample, header row of names)")
    p.add_argument("--prevailing", required=True, help="prevailing illuminant: " + HELP_ILLUMINANT)
    p.add_argument("--calibration", required=True, help="calibration (white balance) illuminant: " + HELP_ILLUMINANT)
    _add_model(p)
    _add_grid(p)
    _add_common(p)

    p = commands.add_parser("gamut", help="convex-hull gamut volume of Eq. 4 responses (output units³)")
    p.add_argument("--camera", required=True, help=HELP_CAMERA)
    p.add_argument("--reflectances", help="reflectance set (name or CSV path); not with --ratio")
    case = p.add_mutually_exclusive_group(required=True)
    case.add_argument("--calibration", help="one calibration case: this calibration illuminant with every "
                      "prevailing illuminant of the set; " + HELP_ILLUMINANT)
    case.add_argument("--all-calibrations", action="store_true",
                      help="the union over every (prevailing, calibration) pair of the set")
    p.add_argument("--illuminants", default="paper",
                   help="illuminant set: 'paper' (the ten, default), 'auto' (Stage 1) or comma-separated kelvin")
    p.add_argument("--ratio", action="store_true", help="skin volume / Munsell volume")
    p.add_argument("--skin", default="skin", help="skin set for --ratio (default skin)")
    p.add_argument("--munsell", default="munsell", help="Munsell set for --ratio (default munsell)")
    _add_model(p)
    _add_grid(p)
    _add_common(p)

    p = commands.add_parser("search", help="Stage 3: gamut volumes of every sensor triplet (Tables 2–5)")
    p.add_argument("--sensor", required=True, type=float,
                   help="the paper's sensor: 1 (impulse) or N = 3, 5, … (gbell, FWHM N·10 nm)")
    p.add_argument("--slope", type=float, default=2.0, help="gbell slope b (default 2; the paper does not give it)")
    p.add_argument("--positions", default="400:700:10",
                   help="peak positions START:END:STEP in nm (default 400:700:10: 31 positions, 4495 triplets)")
    _add_search(p)
    p.add_argument("--csv", help="write every triplet's volumes (output units³) and ratios to this CSV file")
    p.add_argument("--detection", action="store_true",
                   help="also rank triplets by detection: the share of Munsell chromaticities inside the skin "
                   "locus (false-positive rate at 100 %% skin acceptance), per calibration (JSON min_fpr)")
    p.add_argument("--method", default="fast", choices=["fast", "naive"],
                   help="fast (hull vertices only, exact; default) or naive (Qhull on every full point set)")
    p.add_argument("--tie-tolerance", type=float, default=1e-9,
                   help="relative difference under which two values tie (default 1e-9); ties are all listed")
    p.add_argument("--illuminants", default="paper",
                   help="illuminant set: 'paper' (the ten, default) or comma-separated kelvin")
    _add_grid(p)
    _add_common(p)

    p = commands.add_parser("reproduce", help="the paper's Figs. 3–7 (PNG) and Tables 2–5 (Markdown, CSV)")
    p.add_argument("-o", "--output", required=True, help="output folder")
    p.add_argument("--sensors", default="1,3,5,7,9,11,13,15", help="sensor numbers (default 1,3,…,15)")
    p.add_argument("--positions", default="400:700:10", help="peak positions START:END:STEP in nm (default 400:700:10)")
    p.add_argument("--camera", default="Nikon 5100 (NPL)",
                   help="Stage 2 camera for Figs. 3–7 (the paper's Sony is not public); " + HELP_CAMERA)
    p.add_argument("--slope", type=float, default=2.0, help="gbell slope b (default 2)")
    _add_search(p)
    _add_common(p)

    for name, text in (("render", "spectral render of a chart scene with Mitsuba 3 (float32 EXR + PNG preview)"),
                       ("validate", "render a chart and check every patch against Eq. 4 within its noise")):
        p = commands.add_parser(name, help=text)
        p.add_argument("scene", help="scene: macbeth, skin_patches, face_chart or a .toml path (see scenes/)")
        p.add_argument("--camera", required=True, help=HELP_CAMERA)
        p.add_argument("--prevailing", required=True, help="prevailing (emitter) illuminant, Planckian: " + HELP_ILLUMINANT)
        p.add_argument("--calibration", required=True, help="calibration (white balance) illuminant: " + HELP_ILLUMINANT)
        _add_render(p)
        _add_model(p)
        _add_grid(p)
        if name == "validate":
            p.add_argument("--gamut", action="store_true",
                           help="also render the chart under every paper illuminant and compare its gamut volumes "
                           "(one calibration case each, and all calibrations) with the analytic ones")
        if name == "render":
            p.add_argument("-o", "--output", default="render.exr",
                           help="output EXR (float32, Eq. 4 output units, channels named by the camera); "
                           "a PNG preview is written beside it")
        _add_common(p)

    p = commands.add_parser("locus", help="skin locus in NCC (r, g) over the illuminant set, and its false positives")
    p.add_argument("--camera", required=True, help=HELP_CAMERA)
    p.add_argument("--illuminants", default="paper",
                   help="illuminant set: 'paper' (the ten, default), 'auto' (Stage 1) or comma-separated kelvin")
    p.add_argument("--calibration", help="one white balancing at this illuminant (kelvin, A, H); "
                   "default: every calibration of the set")
    p.add_argument("--boundary", choices=["hull", "quadratic"], default="hull",
                   help="convex hull (default) or two quadratics (Soriano et al. 2003)")
    p.add_argument("--skin", default="skin", help="skin reflectance set (default skin)")
    p.add_argument("--nonskin", default="munsell,vrhel-nonskin,macbeth",
                   help="comma-separated non-skin sets for false-positive rates (default munsell,vrhel-nonskin,macbeth)")
    p.add_argument("--plot", help="write the locus, the training chromaticities and the Planckian track to this PNG")
    _add_common(p)

    p = commands.add_parser("detect", help="skin detection on a rendered chart with the camera's skin locus")
    p.add_argument("scene", help="scene: macbeth, skin_patches, face_chart or a .toml path")
    p.add_argument("--camera", required=True, help=HELP_CAMERA)
    p.add_argument("--prevailing", required=True, help="prevailing illuminant, Planckian: " + HELP_ILLUMINANT)
    p.add_argument("--calibration", required=True, help="calibration illuminant: " + HELP_ILLUMINANT)
    p.add_argument("--boundary", choices=["hull", "quadratic"], default="hull", help="locus boundary (default hull)")
    p.add_argument("--skin", default="skin", help="skin set the locus is trained on (default skin)")
    p.add_argument("-o", "--output", default="detect.png", help="mask PNG (a preview PNG is written beside it)")
    _add_render(p)
    _add_common(p)

    p = commands.add_parser("design", help="optimise a gbell camera's peaks off the grid (derivative-free, several starts)")
    p.add_argument("--objective", choices=["detection", "ratio"], default="detection",
                   help="detection: Munsell false-positive rate in the skin locus (default); ratio: skin/Munsell "
                   "all-calibration gamut volume")
    p.add_argument("--sensor", type=float, default=9, help="gbell sensor N (FWHM N·10 nm) of the start (default 9)")
    p.add_argument("--slope", type=float, default=2.0, help="gbell slope b of the start (default 2)")
    p.add_argument("--free-shape", action="store_true", help="also optimise the shared FWHM (nm) and slope")
    p.add_argument("--starts", default="450,540,610;420,550,680;480,560,640",
                   help="starting peak triplets in nm, ';'-separated (default three)")
    p.add_argument("--evaluations", type=int, default=150, help="objective evaluations per start (default 150)")
    p.add_argument("--skin", default="skin", help="skin set (default skin)")
    p.add_argument("--munsell", default="munsell", help="Munsell set (default munsell)")
    _add_common(p)

    p = commands.add_parser("table1", help="the paper's Table 1: NCC differences, render vs model, Macbeth under A and H")
    p.add_argument("--camera", default="gbell:9@450,540,610", help=HELP_CAMERA)
    p.add_argument("--spp", type=int, default=256, help="samples per pixel (default 256)")
    p.add_argument("--seed", type=int, default=0, help="sampler seed (default 0)")
    _add_common(p)

    p = commands.add_parser("bench", help="speed and accuracy figures")
    p.add_argument("what", choices=["analytic", "search", "render"], help="which benchmark")
    p.add_argument("--quick", action="store_true", help="render: a short curve (spp 4…256, one variant)")
    p.add_argument("--plot", help="render: write the error-against-time plot (log–log) to this PNG")
    p.add_argument("--repeat", type=int, default=3, help="analytic: timed repetitions, best kept (default 3)")
    p.add_argument("--sensor", type=float, default=9, help="search: sensor number (default 9)")
    p.add_argument("--sample", type=int, default=20, help="search: triplets timed per method (default 20)")
    p.add_argument("--workers", type=int, help="search: processes (default: every core)")
    _add_common(p)
    return parser


def _print(args: argparse.Namespace, document: dict, text: str) -> None:
    if args.json:
        json.dump(document, sys.stdout, indent=2, allow_nan=False)
        sys.stdout.write("\n")
    else:
        sys.stdout.write(text.rstrip("\n") + "\n")


def _table(rows: list[list[str]], header: list[str]) -> str:
    widths = [max(len(str(r[i])) for r in [header, *rows]) for i in range(len(header))]
    lines = ["  ".join(str(c).ljust(w) for c, w in zip(header, widths))]
    lines.append("  ".join("-" * w for w in widths))
    lines += ["  ".join(str(c).ljust(w) for c, w in zip(row, widths)) for row in rows]
    return "\n".join(lines)


def _range_text(values: list) -> str:
    start, end, step = values
    return f"{start:g}–{end:g} nm" + (f" / {step:g}" if step else "")


def command_cameras(args: argparse.Namespace) -> None:
    from .datasets import list_cameras

    cameras = list_cameras()
    text = _table([[c["name"], _range_text(c["wavelengths"]), c["source"]] for c in cameras],
                  ["name", "wavelengths", "source"])
    _print(args, {"cameras": cameras}, text)


def command_datasets(args: argparse.Namespace) -> None:
    from .datasets import list_reflectances

    datasets = list_reflectances()
    text = _table(
        [[d["name"], d["count"], _range_text(d["wavelengths"]), d["licence"]] for d in datasets],
        ["name", "count", "wavelengths", "licence"],
    )
    _print(args, {"datasets": datasets}, text)


def _grid(args: argparse.Namespace):
    from .spectra import WavelengthGrid

    return WavelengthGrid.parse(args.grid)


def command_illuminants(args: argparse.Namespace) -> None:
    from .camera import camera
    from .illuminants import illuminant_selection

    cam = camera(args.camera, extrapolation=args.extrapolation)
    selection = illuminant_selection(
        cam, args.count, args.range[0], args.range[1], args.step, _grid(args), args.pair
    )
    document = {
        "camera": cam.name,
        "pair": args.pair,
        "temperatures": selection.temperatures.tolist(),
        "measure": selection.measures.tolist(),
        "targets": selection.targets.tolist(),
        "monotonic": selection.monotonic,
        "track": {
            "temperatures_K": selection.track.temperatures.tolist(),
            "ncc": selection.track.chromaticities.tolist(),
            "measure": selection.track.measures.tolist(),
        },
    }
    rows = [[f"{t:g} K", f"{m:.5f}", f"{g:.5f}"] for t, m, g in
            zip(selection.temperatures, selection.measures, selection.targets)]
    text = f"Stage 1 for {cam.name} (measure of NCC {args.pair}):\n" + _table(rows, ["temperature", "measure", "target"])
    if not selection.monotonic:
        text += "\nnote: the measure does not grow strictly with temperature for this camera"
    _print(args, document, text)


def command_response(args: argparse.Namespace) -> None:
    from .camera import camera, ncc, response
    from .datasets import reflectances
    from .illuminant import illuminant

    grid = _grid(args)
    cam = camera(args.camera, extrapolation=args.extrapolation)
    refl = reflectances(args.reflectances, extrapolation=args.extrapolation)
    prevailing, calibration = illuminant(args.prevailing), illuminant(args.calibration)
    rgb = response(cam, refl.on(grid), prevailing, calibration, args.normalization, args.knee, grid)
    chromaticity = ncc(rgb)
    samples = [
        {"name": name, "rgb": values.tolist(), "ncc": c.tolist()}
        for name, values, c in zip(refl.names, rgb, chromaticity)
    ]
    document = {
        "camera": cam.name,
        "reflectances": refl.name,
        "prevailing": str(prevailing),
        "calibration": str(calibration),
        "normalization": args.normalization,
        "knee": args.knee,
        "grid": str(grid),
        "samples": samples,
    }
    rows = [[s["name"], *(f"{v:.2f}" for v in s["rgb"]), *(f"{v:.4f}" for v in s["ncc"])] for s in samples]
    text = (
        f"Eq. 4 responses of {refl.name} through {cam.name}, prevailing {prevailing}, calibration "
        f"{calibration}, normalization {args.normalization}{', knee' if args.knee else ''} (output units, v = 255):\n"
        + _table(rows, ["sample", "R", "G", "B", "r", "g", "b"])
    )
    _print(args, document, text)


def command_gamut(args: argparse.Namespace) -> None:
    from .camera import camera
    from .datasets import reflectances
    from .gamut import gamut_all_calibrations, gamut_calibration
    from .illuminant import illuminant
    from .illuminants import illuminant_set

    grid = _grid(args)
    cam = camera(args.camera, extrapolation=args.extrapolation)
    temperatures = illuminant_set(args.illuminants, cam)
    if args.ratio == bool(args.reflectances):
        raise SkinrenderError("give either --reflectances R or --ratio (with --skin and --munsell), not both or neither")
    if args.calibration is not None:
        calibration = illuminant(args.calibration)
        if calibration.temperature is None:
            raise SkinrenderError("--calibration must be a Planckian illuminant (kelvin, A or H) for a gamut case")

    def volume_of(spec: str):
        refl = reflectances(spec, extrapolation=args.extrapolation)
        if args.all_calibrations:
            result = gamut_all_calibrations(cam, refl, temperatures, args.normalization, args.knee, grid)
        else:
            result = gamut_calibration(cam, refl, calibration.temperature, temperatures, args.normalization,
                                       args.knee, grid)
        return refl.name, result

    document = {
        "camera": cam.name,
        "case": "all calibrations" if args.all_calibrations else f"calibration {args.calibration}",
        "illuminants_K": temperatures.tolist(),
        "normalization": args.normalization,
        "knee": args.knee,
    }
    if args.ratio:
        (skin_name, skin), (munsell_name, munsell) = volume_of(args.skin), volume_of(args.munsell)
        ratio = skin.volume / munsell.volume if munsell.volume > 0 else None
        document.update(
            skin={"name": skin_name, "volume": skin.volume, "points": skin.points, "degenerate": skin.degenerate},
            munsell={"name": munsell_name, "volume": munsell.volume, "points": munsell.points,
                     "degenerate": munsell.degenerate},
            ratio=ratio, volume=skin.volume, points=skin.points, degenerate=skin.degenerate or munsell.degenerate,
        )
        text = (f"{cam.name}, {document['case']}: skin {skin.volume:.6g}, Munsell {munsell.volume:.6g} "
                f"(output units³), ratio {'undefined (degenerate Munsell gamut)' if ratio is None else f'{ratio:.6g}'}")
    else:
        name, result = volume_of(args.reflectances)
        document.update(reflectances=name, volume=result.volume, points=result.points, degenerate=result.degenerate)
        text = (f"{name} through {cam.name}, {document['case']}: volume {result.volume:.6g} output units³ "
                f"({result.points} points{', degenerate' if result.degenerate else ''})")
    _print(args, document, text)


def _row_text(row: dict) -> str:
    kelvin = "all calibrations" if row["temperature_K"] is None else f"{row['temperature_K']:g} K"
    return f"{' '.join(f'{v:g}' for v in row['triplet'])} nm, {kelvin}: {row['value']:.6g}"


def command_search(args: argparse.Namespace) -> None:
    from .datasets import reflectances
    from .illuminants import illuminant_set
    from .search import search

    grid = _grid(args)
    skin = reflectances(args.skin, extrapolation=args.extrapolation)
    munsell = reflectances(args.munsell, extrapolation=args.extrapolation)
    temperatures = illuminant_set(args.illuminants)
    result = search(
        args.sensor, skin.on(grid), munsell.on(grid), args.positions, temperatures, args.slope, grid=grid,
        method=args.method, workers=args.workers, dask=args.dask,
        progress=None if args.quiet else sys.stderr, label=f"sensor {args.sensor:g}", detection=args.detection,
    )
    if args.csv:
        result.to_csv(args.csv)
    table = result.table(args.tie_tolerance)
    document = {
        "sensor": args.sensor,
        "slope": args.slope,
        "positions": result.positions.tolist(),
        "triplets": int(len(result.triplets)),
        "illuminants_K": result.temperatures.tolist(),
        "skin": skin.name,
        "munsell": munsell.name,
        "method": result.method,
        "hull_kernel": result.info["hull_kernel"],
        "workers": result.workers,
        **table,
        "elapsed_s": result.elapsed_s,
        "csv": args.csv,
    }
    lines = [f"sensor {args.sensor:g}: {len(result.triplets)} triplets in {result.elapsed_s:.1f} s "
             f"({result.method}, {result.workers} workers); volumes in output units³"]
    for key, label in (("max_skin", "max skin gamut"), ("max_munsell", "max Munsell gamut"),
                       ("min_ratio", "min skin/Munsell ratio"), ("min_fpr", "min false-positive rate")):
        if key in table:
            lines += [f"{label}:"] + [f"  {_row_text(row)}" for row in table[key]]
    _print(args, document, "\n".join(lines))


def command_reproduce(args: argparse.Namespace) -> None:
    from .reproduce import reproduce

    try:
        sensors = [float(v) for v in args.sensors.split(",")]
    except ValueError:
        raise SkinrenderError(f"--sensors must be comma-separated numbers, got {args.sensors!r}") from None
    result = reproduce(
        args.output, sensors, args.positions, args.camera, args.skin, args.munsell, args.slope,
        workers=args.workers, dask=args.dask, progress=None if args.quiet else sys.stderr,
    )
    searches = ", ".join(f"sensor {k}: {v:.1f} s" for k, v in result["search_s"].items())
    text = "\n".join(["wrote:"] + [f"  {p}" for p in result["artifacts"]]
                     + [f"searches: {sum(result['search_s'].values()):.1f} s ({searches})"])
    _print(args, result, text)


def _render_options(args: argparse.Namespace) -> dict:
    from .render import QUALITY_PRESETS

    preset = QUALITY_PRESETS[args.quality]
    spp = args.spp if args.spp is not None else preset["spp"]
    if spp < 1:
        raise SkinrenderError(f"--spp must be ≥ 1, got {spp}")
    return {"spp": spp, "sampler": args.sampler or preset["sampler"], "seed": args.seed, "variant": args.variant,
            "channels": args.channels}


def command_render(args: argparse.Namespace) -> None:
    from pathlib import Path

    from .render import channel_names, render, write_exr, write_preview

    options = _render_options(args)
    print(f"rendering {args.scene} at {options['spp']} spp …", file=sys.stderr)
    result = render(args.scene, args.camera, args.prevailing, args.calibration, args.normalization, args.knee,
                    grid=_grid(args), **options)
    output = Path(args.output)
    if output.suffix.lower() != ".exr":
        raise SkinrenderError(f"--output must end in .exr, got {output}")
    names = channel_names(result.camera)
    write_exr(output, result.image, names, {"camera": result.camera.name, "prevailing_K": result.prevailing,
                                            "calibration_K": result.calibration, "spp": options["spp"],
                                            "seed": args.seed, "variant": result.variant, "units": "Eq. 4 output units"})
    preview = write_preview(output.with_suffix(".png"), result.image)
    document = {"image": str(output), "preview_png": str(preview), "channels": list(names), "spp": options["spp"],
                "sampler": options["sampler"], "seed": args.seed, "variant": result.variant,
                "elapsed_s": result.seconds, "scene": result.scene.name, "camera": result.camera.name,
                "prevailing_K": result.prevailing, "calibration_K": result.calibration,
                "normalization": args.normalization, "knee": args.knee}
    text = (f"{result.scene.name} through {result.camera.name}, {result.prevailing:g} K white-balanced to "
            f"{result.calibration:g} K: {output} (+ {preview}), {options['spp']} spp, {result.variant}, "
            f"{result.seconds:.2f} s")
    _print(args, document, text)


def command_validate(args: argparse.Namespace) -> None:
    from .validate import SIGMAS, validate

    options = _render_options(args)
    print(f"rendering {args.scene} at {options['spp']} spp and validating …", file=sys.stderr)
    result = validate(args.scene, args.camera, args.prevailing, args.calibration, args.normalization, args.knee,
                      grid=_grid(args), **options)
    r = result.rendering
    document = {"scene": r.scene.name, "camera": r.camera.name, "prevailing_K": r.prevailing,
                "calibration_K": r.calibration, "normalization": args.normalization, "knee": args.knee,
                "spp": options["spp"], "sampler": options["sampler"], "seed": args.seed, "variant": r.variant,
                "elapsed_s": r.seconds, "sigmas": SIGMAS, "patches": result.patches(), "worst": result.worst(),
                "max_rel_error": float(result.rel_error.max()), "quadrature_rel_difference": result.quadrature,
                "passed": result.passed}
    lines = [f"{r.scene.name} through {r.camera.name}, {r.prevailing:g} K / {r.calibration:g} K, "
             f"{options['spp']} spp {options['sampler']}, {r.variant}, {r.seconds:.2f} s"]
    rows = [[p["name"][:28], *(f"{v:.3f}" for v in p["rendered"]), *(f"{v:.1e}" for v in p["rel_error"]),
             "ok" if p["passed"] else "FAIL"] for p in document["patches"]]
    lines.append(_table(rows, ["patch", "R", "G", "B", "relerr R", "relerr G", "relerr B", ""]))
    lines += [f"worst {w['channel']}: {w['patch']} ({w['z']:+.2f} σ, {w['rel_error']:.1e} relative)" for w in result.worst()]
    lines.append(f"paper Σ vs rendered integral (quadrature): {result.quadrature:.1e} relative; "
                 f"{'PASSED' if result.passed else 'FAILED'} (tolerance {SIGMAS:g} σ of the measured noise)")
    passed = result.passed
    if args.gamut:
        from .validate import validate_gamut

        gamuts = validate_gamut(args.scene, args.camera, spp=options["spp"], seed=args.seed,
                                sampler=options["sampler"], variant=args.variant, grid=_grid(args))
        document["gamut"] = gamuts
        passed = passed and gamuts["passed"]
        lines.append(f"gamut volumes (output units³), rendered vs analytic, {len(gamuts['illuminants_K'])} illuminants:")
        labels = [f"calibration {t:g} K" for t in gamuts["illuminants_K"]] + ["all calibrations"]
        for label, r, a, sg in zip(labels, gamuts["rendered"], gamuts["analytic"], gamuts["sigma"]):
            lines.append(f"  {label:20s} {r:.6g} vs {a:.6g} (σ {sg:.2g})")
        lines.append("gamuts " + ("agree within 5 σ" if gamuts["passed"] else "DISAGREE"))
    document["passed"] = passed
    _print(args, document, "\n".join(lines))
    if not passed:
        raise SystemExit(1)


def command_locus(args: argparse.Namespace) -> None:
    from .camera import camera
    from .datasets import reflectances
    from .illuminant import illuminant
    from .illuminants import illuminant_set
    from .locus import false_positive_rate, locus_points, skin_locus

    cam = camera(args.camera)
    temperatures = illuminant_set(args.illuminants, cam)
    calibration = None
    if args.calibration:
        calibration = illuminant(args.calibration).temperature
        if calibration is None:
            raise SkinrenderError("--calibration must be Planckian (kelvin, A or H)")
    skin = reflectances(args.skin)
    locus = skin_locus(cam, skin, temperatures, calibration, args.boundary)
    rates = {name: false_positive_rate(locus, cam, reflectances(name)) for name in args.nonskin.split(",") if name}
    document = {"camera": cam.name, "boundary": args.boundary, "polygon": locus.polygon.tolist(), "area": locus.area,
                "illuminants_K": temperatures.tolist(), "calibration_K": calibration, "skin": skin.name,
                "false_positive_rate": rates}
    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import numpy as np

        from .camera import ncc, response

        figure, axis = plt.subplots(figsize=(5.5, 5))
        training = locus_points(cam, skin, temperatures, calibration)
        axis.plot(*training.T, ".", ms=2, color="tab:orange", label=f"{skin.name} ({len(training)} points)")
        closed = np.vstack([locus.polygon, locus.polygon[:1]])
        axis.plot(*closed.T, "-", color="tab:red", label=f"locus ({args.boundary}), area {locus.area:.4f}")
        track_t = np.linspace(2000, 10000, 81)
        reference = calibration if calibration is not None else 5900.0
        from .spectra import GRID_DEFAULT

        track = ncc(response(cam, np.ones((1, GRID_DEFAULT.size)), track_t, reference))[:, 0, :2]
        axis.plot(*track.T, "k--", label=f"Planckian track (white, calibration {reference:g} K)")
        axis.set(xlabel="NCC r", ylabel="NCC g", title=f"Skin locus of {cam.name}")
        axis.legend(fontsize=7)
        figure.tight_layout()
        figure.savefig(args.plot, dpi=110)
        plt.close(figure)
        document["plot"] = args.plot
    text = (f"skin locus of {cam.name} ({args.boundary}, {len(locus.polygon)} vertices, area {locus.area:.5f} in r,g) "
            f"over {len(temperatures)} illuminants, "
            + ("every calibration" if calibration is None else f"calibration {calibration:g} K") + "\n"
            + "\n".join(f"  false positives, {k}: {v:.3f}" for k, v in rates.items()))
    _print(args, document, text)


def command_detect(args: argparse.Namespace) -> None:
    from pathlib import Path

    import matplotlib.image

    from .locus import detect, skin_locus
    from .render import render, write_preview

    options = _render_options(args)
    print(f"rendering {args.scene} at {options['spp']} spp …", file=sys.stderr)
    rendering = render(args.scene, args.camera, args.prevailing, args.calibration, **options)
    # the camera is white-balanced to the calibration light: the locus of that one balancing
    locus = skin_locus(rendering.camera, args.skin, calibration=rendering.calibration, boundary=args.boundary)
    result = detect(rendering, locus)
    output = Path(args.output)
    output.parent.mkdir(parents=True, exist_ok=True)
    matplotlib.image.imsave(output, result.mask.astype(float), cmap="gray", vmin=0, vmax=1)
    preview = write_preview(output.with_name(output.stem + "_preview.png"), rendering.image)
    document = {"scene": rendering.scene.name, "camera": rendering.camera.name, "prevailing_K": rendering.prevailing,
                "calibration_K": rendering.calibration, "tpr": result.tpr, "fpr": result.fpr,
                "mask_png": str(output), "preview_png": str(preview), "per_patch": result.per_patch,
                "boundary": args.boundary, "spp": options["spp"], "variant": rendering.variant}
    rows = [[p["name"][:30], "skin" if p["is_skin"] else "", f"{p['detected_fraction']:.2f}"] for p in result.per_patch]
    text = (_table(rows, ["patch", "", "detected"]) + f"\nTPR {result.tpr:.3f}, FPR {result.fpr:.3f}; mask {output}")
    _print(args, document, text)


def command_design(args: argparse.Namespace) -> None:
    from .datasets import reflectances
    from .design import optimise_camera

    try:
        starts = [[float(v) for v in part.split(",")] for part in args.starts.split(";")]
    except ValueError:
        starts = []
    if not starts or any(len(s) != 3 for s in starts):
        raise SkinrenderError("--starts must be triplets of nm separated by ';', e.g. 450,540,610;420,550,680")
    from .spectra import GRID_DEFAULT as grid

    result = optimise_camera(args.objective, reflectances(args.skin).on(grid), reflectances(args.munsell).on(grid),
                             starts, args.sensor * 10.0, args.slope, args.free_shape, args.evaluations)
    document = {"objective": args.objective, "camera": result.camera_spec, "peaks": result.peaks.tolist(),
                "fwhm_nm": result.fwhm, "slope": result.slope, "value": result.value, "starts": result.starts,
                "method": "Nelder-Mead (derivative-free)"}
    lines = [f"{args.objective}: best {result.camera_spec} = {result.value:.5g}"]
    lines += [f"  start {s['start']} ({s['start_value']:.5g}) -> {[round(p, 1) for p in s['peaks']]} ({s['value']:.5g})"
              for s in result.starts]
    _print(args, document, "\n".join(lines))


def command_table1(args: argparse.Namespace) -> None:
    from .validate import table1

    result = table1(args.camera, spp=args.spp, seed=args.seed)
    rows = [[r["model"], r["case"], f"{r['mean']:.5f}", f"{r['std']:.5f}"] for r in result["rows"]]
    text = (f"Table 1 for {result['camera']} ({len(result['patches'])} Macbeth patches with 90 % of values in "
            f"10–245; render at {result['spp']} spp as the real camera):\n"
            + _table(rows, ["model", "case", "mean |ΔNCC|", "std"]))
    _print(args, result, text)


def command_bench(args: argparse.Namespace) -> None:
    from .bench import bench_analytic, bench_search

    if args.what == "render":
        from .bench import bench_render

        result = bench_render(quick=args.quick)
        if args.plot:
            from .bench import plot_render_curve

            result["plot"] = str(plot_render_curve(result, args.plot))
    elif args.what == "search":
        result = bench_search(args.sensor, args.sample, workers=args.workers)
    else:
        result = bench_analytic(repeat=args.repeat)
    text = "\n".join(f"{key}: {value}" for key, value in result.items())
    _print(args, result, text)


COMMANDS = {
    "cameras": command_cameras,
    "datasets": command_datasets,
    "illuminants": command_illuminants,
    "response": command_response,
    "gamut": command_gamut,
    "search": command_search,
    "reproduce": command_reproduce,
    "render": command_render,
    "validate": command_validate,
    "table1": command_table1,
    "locus": command_locus,
    "design": command_design,
    "detect": command_detect,
    "bench": command_bench,
}


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        COMMANDS[args.command](args)
    except SkinrenderError as error:
        print(f"skinrender {args.command}: error: {error}", file=sys.stderr)
        return 2
    except BrokenPipeError:
        return 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
