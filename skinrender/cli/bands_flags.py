"""
The spectral render's flags: ``--spectral``, ``--bands``, ``--direct``
======================================================================

``render`` and ``validate`` take ``--spectral`` (the scene rendered once with the bands of
:mod:`skinrender.rendering.bands` as its film) and ``--bands START:END:STEP`` (nm); ``face-sweep`` and
``ladder``, whose ``--camera`` repeats, see several cameras through one spectral render unless ``--direct``,
with ``--bands``. This module parses and checks those flags (the commands are
:mod:`skinrender.cli.spectral_commands`, ``validate``'s :mod:`skinrender.cli.chart_validation`, ``ladder``'s
:mod:`skinrender.cli.face`).

Units: wavelengths nm, times s, memory bytes.
"""

from __future__ import annotations

import argparse
import os

from ..errors import SkinrenderError
from .common import flag

__all__ = ["HELP_BANDS", "add_spectral_arguments", "add_cameras_arguments", "bands_of", "bands_from", "bands_for", "bands_for_cameras",
           "check_spectral_work", "cameras_of"]

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
    direct = ("render every camera on its own (the default for one --camera); without it several cameras are seen "
              "through one spectral render per light, skin and level")
    bands = ("the spectral renders' band grid in nm (default 400:700:5): a hat per band, a camera on this grid seen "
             "exactly")
    parser.add_argument("--direct", action="store_true", help=direct)
    parser.add_argument("--bands", metavar="START:END:STEP", help=bands)



def bands_for(args: argparse.Namespace, cameras: list):
    """:func:`bands_for_cameras` ``--bands`` and ``--direct``."""
    return bands_for_cameras(args.bands, args.direct, cameras)


def bands_for_cameras(bands: str | None, direct: bool, cameras: list):
    """
    The bands several ``--camera`` are seen through (``--bands``, default 400:700:5; each camera checked against
    them), or ``None`` for one render per camera (one camera, or ``--direct``; ``--bands`` then refused).
    """
    from ..rendering.bands import BANDS_DEFAULT, check_bands, parse_bands, projection
    from ..spectra import GRID_DEFAULT

    if len(cameras) == 1 or direct:
        if bands is not None:
            raise SkinrenderError("--bands: the bands of a spectral render, which several --camera share (not with "
                                  "--direct or one camera)", flag="--bands")
        return None
    bands = BANDS_DEFAULT if bands is None else flag("--bands", parse_bands, bands)
    flag("--bands", check_bands, bands, GRID_DEFAULT, "the face's lights and reflectances (400–700 nm)")
    for cam in cameras:
        flag({"camera": "--camera", None: "--bands"}, projection, cam, bands, GRID_DEFAULT)
    return bands



def bands_of(args: argparse.Namespace):
    """:func:`bands_from` ``--spectral`` and ``--bands``."""
    return bands_from(getattr(args, "spectral", False), getattr(args, "bands", None))


def bands_from(spectral: bool, bands: str | None):
    """``--bands`` checked (with ``--spectral`` only), or the default bands; ``None`` without ``--spectral``."""
    from ..rendering.bands import BANDS_DEFAULT, parse_bands

    if not spectral:
        if bands is not None:
            raise SkinrenderError("--bands goes with --spectral", flag="--bands")
        return None
    return BANDS_DEFAULT if bands is None else flag("--bands", parse_bands, bands)



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


def cameras_of(specs: list[str], name: str = "--camera") -> list:
    """Every repeated ``--camera`` made a camera once, its curves checked on the default grid, none twice."""
    from ..model.camera import camera
    from ..spectra import GRID_DEFAULT

    cams = []
    for spec in specs:
        cam = flag(name, camera, spec)
        flag(name, cam.sensitivities, GRID_DEFAULT)
        cams.append(cam)
    twice = sorted({cam.name for cam in cams if [c.name for c in cams].count(cam.name) > 1})
    if twice:
        raise SkinrenderError(f"{name}: each once, got {', '.join(twice)} more than once", flag=name)
    return cams
