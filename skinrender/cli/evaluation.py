"""
The skin locus: ``locus``.
"""

from __future__ import annotations

import argparse

import numpy as np

from ..errors import SkinrenderError
from ..files import write_output
from .common import HELP_CAMERA, camera_of, add_common, check_output, emit, flag
from .detection_options import HELP_SKIN_SET
from .preflight import check_lights


def add_parsers(commands) -> None:
    """Add the parsers of locus."""
    p = commands.add_parser("locus", run=command_locus,
                            help="skin locus in NCC (r, g) over the illuminant set, and its false positives")
    p.add_argument("--camera", required=True, help=HELP_CAMERA)
    p.add_argument("--illuminants", default="paper",
                   help="illuminant set: 'paper' (the ten, default), 'auto' (Stage 1) or comma-separated kelvin")
    p.add_argument("--calibration", help="one white balancing at this illuminant (kelvin, A, H); "
                   "default: every calibration of the set")
    from ..evaluation.locus import BOUNDARIES

    p.add_argument("--boundary", choices=list(BOUNDARIES), default="hull",
                   help="convex hull (default) or two quadratics (Soriano et al. 2003)")
    p.add_argument("--skin-set", metavar="SET", help=HELP_SKIN_SET + " (default skin)")
    p.add_argument("--skin", help="deprecated spelling of --skin-set (kept: it names the same set)")
    p.add_argument("--munsell", default="munsell",
                   help="the Munsell set, name or CSV path: the 'munsell' item of --nonskin (default munsell)")
    p.add_argument("--nonskin", default="munsell,vrhel-nonskin,macbeth",
                   help="comma-separated non-skin sets for false-positive rates, each named once (a set named twice "
                        "is refused); the item 'munsell' is the --munsell set (default munsell,vrhel-nonskin,macbeth)")
    p.add_argument("--plot", help="write the locus, the training chromaticities and the Planckian track to this PNG")
    add_common(p)


def nonskin_sets(spec: str, munsell: str = "munsell") -> dict[str, str]:
    """
    The items of ``--nonskin`` in order, each with its set; the item ``munsell`` stands for the ``--munsell`` set.

    >>> nonskin_sets("munsell,macbeth", "munsell-nickerson")
    {'munsell': 'munsell-nickerson', 'macbeth': 'macbeth'}
    """
    items = [name.strip() for name in spec.split(",")]
    if not spec.strip() or any(not name for name in items):
        raise SkinrenderError(f"--nonskin: expected comma-separated reflectance sets without empty items, got {spec!r}",
                              flag="--nonskin")
    names = [munsell if name == "munsell" else name for name in items]
    repeated = sorted({name for name in names if names.count(name) > 1})
    if munsell in repeated and munsell != "munsell":
        raise SkinrenderError(f"--munsell {munsell} is already in --nonskin {spec!r} (whose item 'munsell' is the "
                              "--munsell set): name another set, or list the non-skin sets without it",
                              flag="--munsell")
    if repeated:
        raise SkinrenderError(f"--nonskin: each set once, got {', '.join(repeated)} more than once", flag="--nonskin")
    if munsell != "munsell" and munsell not in names:
        raise SkinrenderError(f"--munsell {munsell} is not used: --nonskin {spec!r} has no item 'munsell'",
                              flag="--munsell")
    return dict(zip(items, names))


def command_locus(args: argparse.Namespace) -> None:
    from ..datasets import reflectances
    from ..evaluation.locus import false_positive_rate, locus_points, skin_locus
    from ..model.illuminant import illuminant
    from ..model.chromaticity import ncc
    from ..model.response import response
    from ..model.stage1 import illuminant_set
    from ..spectra import GRID_DEFAULT
    from ..studies.figures import figure_locus

    plot = check_output(args.plot, "--plot", (".png",))
    cam = camera_of(args)
    temperatures = flag({"camera": "--camera", None: "--illuminants"}, illuminant_set, args.illuminants, cam)
    check_lights(args, cam, temperatures)
    calibration = None
    if args.calibration is not None:
        calibration = flag("--calibration", illuminant, args.calibration).temperature
        if calibration is None:
            raise SkinrenderError("--calibration must be Planckian (kelvin, A or H)", flag="--calibration")
    if args.skin is not None and args.skin_set is not None:
        raise SkinrenderError("--skin is the old spelling of --skin-set: give one of them", flag="--skin")
    which = "--skin" if args.skin is not None else "--skin-set"
    spec = args.skin if args.skin is not None else "skin" if args.skin_set is None else args.skin_set
    if not str(spec).strip():
        raise SkinrenderError(f"{which}: expected a reflectance set (skin, skin-tones, a CSV path), got an empty one",
                              flag=which)
    skin = flag(which, reflectances, spec)
    flag(which, skin.on)  # its coverage of the grid, checked here to name the flag
    if skin.count == 0:
        raise SkinrenderError(f"{which}: {spec!r} holds no spectrum; a locus needs skins", flag=which)
    locus = skin_locus(cam, skin, temperatures, calibration, args.boundary)
    # keyed by the --nonskin items: the Munsell set's rate is 'munsell' whichever set --munsell names
    sets = {}
    for item, name in nonskin_sets(args.nonskin, args.munsell).items():  # every set checked before any rate
        which = "--munsell" if item == "munsell" and name != "munsell" else "--nonskin"
        sets[item] = flag(which, reflectances, name)
        flag(which, sets[item].on)  # its coverage of the grid, named here
    rates = {item: false_positive_rate(locus, cam, values) for item, values in sets.items()}
    document = {"camera": cam.name, "boundary": args.boundary, "polygon": locus.polygon.tolist(), "area": locus.area, "degenerate": locus.degenerate,
                "illuminants_K": temperatures.tolist(), "calibration_K": calibration, "skin": skin.name,
                "skin_set": skin.name,
                "munsell": args.munsell,
                "false_positive_rate": rates}
    if args.plot:
        # the Planckian track: a white object under 2000–10000 K, balanced to the calibration (or 5900 K)
        reference = calibration if calibration is not None else 5900.0
        track = ncc(response(cam, np.ones((1, GRID_DEFAULT.size)), np.linspace(2000, 10000, 81), reference))[:, 0, :2]
        points = locus_points(cam, skin, temperatures, calibration)
        write_output(plot, lambda stream: figure_locus(
            locus.polygon, locus.area, args.boundary, points, skin.name, track,
            f"Planckian track (white, calibration {reference:g} K)", f"Skin locus of {cam.name}", stream), "--plot")
        document["plot"] = str(plot)
    text = (f"skin locus of {cam.name} from the {skin.name} set ({args.boundary}, {len(locus.polygon)} vertices, area "
            f"{locus.area:.5f} in r,g) "
            f"over {len(temperatures)} illuminants, "
            + ("every calibration" if calibration is None else f"calibration {calibration:g} K") + "\n"
            + "\n".join(f"  false positives, {k}{f' ({args.munsell})' if k == 'munsell' != args.munsell else ''}: "
                        f"{v:.3f}" for k, v in rates.items()))
    emit(args, document, text)
