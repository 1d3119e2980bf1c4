"""
Commands of the analytic model: ``illuminants`` (Stage 1), ``response`` (Eq. 4), ``gamut``.
"""

from __future__ import annotations

import argparse
import math

from ..errors import SkinrenderError
from .common import (HELP_CAMERA, camera_of, HELP_ILLUMINANT, add_common, add_grid, add_model, emit, flag,
                     grid_of, integer_in, table)
from .preflight import check_lights


def add_parsers(commands) -> None:
    """Add the parsers of illuminants, response, gamut."""
    p = commands.add_parser("illuminants", run=command_illuminants,
                            help="Stage 1: illuminants equally spaced in the NCC measure")
    p.add_argument("--camera", required=True, help=HELP_CAMERA)
    p.add_argument("--range", nargs=2, type=float, default=[2000.0, 10000.0], metavar=("START_K", "END_K"),
                   help="candidate temperatures, K (default 2000 10000)")
    p.add_argument("--step", type=float, default=100.0, help="candidate spacing, K (default 100)")
    p.add_argument("--count", type=int, default=10, help="how many illuminants (default 10)")
    p.add_argument("--pair", default="gb", help="NCC pair of the Eq. 3 measure (default gb)")
    add_grid(p)
    add_common(p)

    p = commands.add_parser("response", run=command_response,
                            help="Eq. 4 white-balanced responses and NCC of a reflectance set")
    p.add_argument("--camera", required=True, help=HELP_CAMERA)
    p.add_argument("--reflectances", required=True,
                   help="reflectance set: a name (see 'skinrender datasets') or a CSV path "
                   "(wavelength nm, one column per sample, header row of names)")
    p.add_argument("--prevailing", required=True, help="prevailing illuminant: " + HELP_ILLUMINANT)
    p.add_argument("--calibration", required=True, help="calibration (white balance) illuminant: " + HELP_ILLUMINANT)
    add_model(p)
    add_grid(p)
    add_common(p)

    p = commands.add_parser("gamut", run=command_gamut,
                            help="convex-hull gamut volume of Eq. 4 responses (output units³)")
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
    add_model(p)
    add_grid(p)
    add_common(p)


def command_illuminants(args: argparse.Namespace) -> None:
    import numpy as np

    from ..model.chromaticity import measure
    from ..model.stage1 import illuminant_selection, temperature_range

    integer_in(args.count, "--count", 2)  # each flag checked on its own, so that its error names it
    if not (math.isfinite(args.step) and args.step > 0):
        raise SkinrenderError(f"--step must be a finite number of kelvin > 0, got {args.step}", flag="--step")
    flag("--range", temperature_range, args.range[0], args.range[1], args.step)
    flag("--pair", measure, np.full((1, 3), 1.0 / 3.0), args.pair)
    grid = grid_of(args)
    cam = camera_of(args, grid)
    selection = flag({"camera": "--camera", "illuminant": "--range", None: "--count"}, illuminant_selection,
                     cam, args.count, args.range[0], args.range[1], args.step, grid, args.pair)
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
    text = f"Stage 1 for {cam.name} (measure of NCC {args.pair}):\n" + table(rows, ["temperature", "measure", "target"])
    if not selection.monotonic:
        text += "\nnote: the measure does not grow strictly with temperature for this camera"
    emit(args, document, text)


def command_response(args: argparse.Namespace) -> None:
    from ..model.chromaticity import ncc
    from ..datasets import reflectances
    from ..model.illuminant import illuminant
    from ..model.response import illuminant_factors, response

    grid = grid_of(args)
    cam = camera_of(args, grid)
    refl = flag("--reflectances", reflectances, args.reflectances, extrapolation=args.extrapolation)
    flag("--reflectances", refl.on, grid)  # its coverage of the grid, named here
    prevailing, calibration = flag("--prevailing", illuminant, args.prevailing), flag("--calibration", illuminant, args.calibration)
    for name, light in (("--prevailing", prevailing), ("--calibration", calibration)):
        check_lights(args, cam, light, grid, name)
        flag(name, illuminant_factors, light, args.normalization, grid)  # its factor defined (Eqs. 5–7)
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
        + table(rows, ["sample", "R", "G", "B", "r", "g", "b"])
    )
    emit(args, document, text)


def command_gamut(args: argparse.Namespace) -> None:
    from ..datasets import reflectances
    from ..evaluation.gamut import gamut_all_calibrations, gamut_calibration
    from ..model.illuminant import illuminant
    from ..model.stage1 import illuminant_set

    grid = grid_of(args)
    cam = camera_of(args, grid)
    temperatures = flag({"camera": "--camera", None: "--illuminants"}, illuminant_set, args.illuminants, cam)
    check_lights(args, cam, temperatures, grid)
    if args.ratio == bool(args.reflectances):
        raise SkinrenderError("give either --reflectances R or --ratio (with --skin and --munsell), not both or neither")
    if not args.ratio:
        for name, default in (("skin", "skin"), ("munsell", "munsell")):
            if getattr(args, name) != default:
                raise SkinrenderError(f"--{name} goes with --ratio; with --reflectances it would be ignored",
                                      flag=f"--{name}")
    if args.calibration is not None:
        calibration = flag("--calibration", illuminant, args.calibration)
        if calibration.temperature is None:
            raise SkinrenderError("--calibration must be a Planckian illuminant (kelvin, A or H) for a gamut case",
                                  flag="--calibration")

    def volume_of(spec: str, name: str):
        refl = flag(name, reflectances, spec, extrapolation=args.extrapolation)
        flag(name, refl.on, grid)  # its coverage of the grid, named here
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
        (skin_name, skin), (munsell_name, munsell) = volume_of(args.skin, "--skin"), volume_of(args.munsell,
                                                                                              "--munsell")
        ratio = skin.volume / munsell.volume if munsell.volume > 0 else None
        if ratio is None:
            document["undefined"] = {"ratio": "the Munsell gamut has zero volume (degenerate: flat or coincident "
                                              "channels), so skin / Munsell is undefined"}
        document.update(
            skin={"name": skin_name, "volume": skin.volume, "points": skin.points, "degenerate": skin.degenerate},
            munsell={"name": munsell_name, "volume": munsell.volume, "points": munsell.points,
                     "degenerate": munsell.degenerate},
            ratio=ratio, volume=skin.volume, points=skin.points, degenerate=skin.degenerate or munsell.degenerate,
        )
        text = (f"{cam.name}, {document['case']}: skin {skin.volume:.6g}, Munsell {munsell.volume:.6g} "
                f"(output units³), ratio {'undefined (degenerate Munsell gamut)' if ratio is None else f'{ratio:.6g}'}")
    else:
        name, result = volume_of(args.reflectances, "--reflectances")
        document.update(reflectances=name, volume=result.volume, points=result.points, degenerate=result.degenerate)
        text = (f"{name} through {cam.name}, {document['case']}: volume {result.volume:.6g} output units³ "
                f"({result.points} points{', degenerate' if result.degenerate else ''})")
    emit(args, document, text)
