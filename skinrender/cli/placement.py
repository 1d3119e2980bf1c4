"""
``--translate-mm X,Y,Z`` (``render``, ``validate``, ``ladder``)
===============================================================

The whole scene moved away from the origin (a face: its camera, mesh, props
and point lights; a chart at ``--physics subsurface-volume``: each patch's slab,
floor and camera), to test a render where float32 positions are coarsest. A
scene beyond float32's useful range is refused, naming it, before anything
renders (:mod:`skinrender.rendering.placement`).

-   :func:`add_translate`: the flag.
-   :func:`translate_of`: its value, checked (``None`` when not given).
-   :func:`translated_face`: a face scene moved and checked at its level.
-   :func:`translate_key`: what it adds to a command's JSON.
"""

from __future__ import annotations

import argparse

__all__ = ["add_translate", "translate_of", "translated_face", "translate_key"]


def add_translate(parser: argparse.ArgumentParser) -> None:
    """Add ``--translate-mm``."""
    parser.add_argument("--translate-mm", metavar="X,Y,Z",
                        help="move the whole scene X, Y, Z mm away from the origin (a face; a chart at --physics "
                        "subsurface-volume) to test it where float32 is coarsest, e.g. -100,0,0; refused beyond "
                        "float32's useful range and, a face, beyond ~10 m (Mitsuba's spawn offset over 1 mm)")


def translate_of(value: str | None) -> tuple[float, float, float] | None:
    """``--translate-mm``'s ``value`` (``"X,Y,Z"``) as ``(x, y, z)`` mm, or ``None`` when not given; a one-line
    error naming the flag otherwise."""
    from ..rendering.placement import translation

    return None if value is None else translation(value, "--translate-mm")


def translated_face(value: str | None, scene, levels, skin: str | None):
    """
    The face ``scene`` moved by ``--translate-mm``'s ``value`` (unchanged without it), refused, naming it, where it lies
    beyond float32's useful range at any of ``levels`` with ``skin`` (``None``: the scene's).
    """
    from ..rendering.face.reach import check_face_range
    from ..spectra import GRID_DEFAULT

    translate = translate_of(value)
    moved = scene if translate is None else scene.translated(translate)
    for level in levels:
        check_face_range(moved, level, moved.skin if skin is None else skin, GRID_DEFAULT)
    return moved


def translate_key(value: str | None) -> dict:
    """``{"translate_mm": [x, y, z]}`` where ``--translate-mm`` was given (its ``value``), else ``{}``."""
    translate = translate_of(value)
    return {} if translate is None else {"translate_mm": list(translate)}
