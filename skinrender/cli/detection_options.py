"""
The detection options the face commands share: ``--skin-set`` (the set a skin
locus is built from) and ``--detection-tolerance`` (how far Eq. 4 may be off
in TPR and FPR), each parsed once and refused with a one-line error naming
the flag.

Units: rates fractions.
"""

from __future__ import annotations

import argparse

from ..errors import SkinrenderError
from .common import flag

__all__ = ["HELP_SKIN_SET", "add_skin_set", "add_detection_tolerance", "add_detection_options", "skin_set_from",
           "detection_tolerance_from"]

HELP_SKIN_SET = ("reflectance set the skin locus is built from: skin (the 30 Vrhel skins, default), skin-tones (very "
                 "light to very dark: the skin model fitted to measured colours, and its dark end), skin-model, "
                 "or a CSV path")


def add_skin_set(parser: argparse.ArgumentParser) -> None:
    """``--skin-set SET`` (default ``skin``)."""
    parser.add_argument("--skin-set", metavar="SET", default="skin", help=HELP_SKIN_SET + " (default skin)")


def add_detection_tolerance(parser: argparse.ArgumentParser) -> None:
    """``--detection-tolerance RATE`` (default :data:`~skinrender.evaluation.detection_verdict.DETECTION_TOLERANCE`)."""
    from ..evaluation.detection_verdict import DETECTION_TOLERANCE

    parser.add_argument("--detection-tolerance", metavar="RATE", default=str(DETECTION_TOLERANCE),
                        help="how far Eq. 4 may be off in TPR and in FPR, as a fraction in (0, 1), for the detection "
                        f"verdict (default {DETECTION_TOLERANCE:g}: two percentage points)")


def add_detection_options(parser: argparse.ArgumentParser) -> None:
    """The detection verdict's flags of a face study (``ladder``, ``face-sweep``): :func:`add_skin_set` and
    :func:`add_detection_tolerance`."""
    add_skin_set(parser)
    add_detection_tolerance(parser)


def detection_tolerance_from(text: str | float | None) -> float:
    """``--detection-tolerance``'s value as a fraction in (0, 1) (``None``: the default,
    :data:`~skinrender.evaluation.detection_verdict.DETECTION_TOLERANCE`)."""
    from ..evaluation.detection_verdict import check_tolerance

    return check_tolerance(text, "--detection-tolerance")


def skin_set_from(spec: str | None, cam, calibrations, grid=None):
    """
    ``--skin-set``'s value (``None``: ``skin``) as a :class:`~skinrender.datasets.SpectralSet`, refused (naming the
    flag) when it is unknown, unreadable, empty, does not cover the grid, or gives ``cam`` a locus of no area at one
    of ``calibrations`` (K) over the paper's ten lights: detection with it would find no skin.
    """
    from ..datasets import reflectances
    from ..evaluation.locus import skin_locus
    from ..spectra import GRID_DEFAULT

    grid = GRID_DEFAULT if grid is None else grid
    spec = "skin" if spec is None else str(spec).strip()
    if not spec:
        raise SkinrenderError("--skin-set: expected a reflectance set (skin, skin-tones, a CSV path), got an empty "
                              "one", flag="--skin-set")
    skins = flag("--skin-set", reflectances, spec)
    if skins.count == 0:
        raise SkinrenderError(f"--skin-set: {spec!r} holds no spectrum; a locus needs skins", flag="--skin-set")
    flag("--skin-set", skins.on, grid)  # its coverage of the grid, named here
    for calibration in sorted(set(float(c) for c in calibrations)):
        locus = skin_locus(cam, skins, calibration=calibration, grid=grid)
        if locus.degenerate is not None:
            raise SkinrenderError(f"--skin-set: {spec!r} gives {cam.name} a skin locus of no area at calibration "
                                  f"{calibration:g} K ({locus.degenerate}); a detector with it finds no skin: name a "
                                  "set of several skins", flag="--skin-set")
    return skins
