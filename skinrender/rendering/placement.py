"""
A scene moved away from the origin
==================================

``--translate-mm X,Y,Z`` (``render``, ``validate``, ``ladder``) moves a whole
scene, camera and lights with it, away from the origin: far from the origin
is where float32 positions are coarsest, one of the extremes at which a
render's numerical stability is tested. A scene moved so far that float32
can no longer resolve the smallest length its render depends on is refused,
naming the scene, before anything renders.

-   :func:`translation`: a translation, checked (three finite mm).
-   :func:`check_float32_range`, :data:`FLOAT32_SHARE`: float32's useful range.
-   :func:`float32_limit_mm`: how far a scene may be moved.
-   :func:`check_spawn_offset`, :data:`SPAWN_OFFSET_MAX_MM`: Mitsuba's offset of the rays it spawns at a surface,
    which grows with the distance from the origin and brightens a face (occlusion lost).

Units: mm.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import SkinrenderError

__all__ = ["FLOAT32_SHARE", "RAY_EPSILON", "SPAWN_OFFSET_MAX_MM", "translation", "float32_spacing", "float32_limit_mm",
           "check_float32_range", "spawn_offset_mm", "check_spawn_offset"]

RAY_EPSILON = 1500 * 2.0**-24
"""Mitsuba 3's ray epsilon in float32 (~8.9e-5): a ray spawned at a surface starts ``(1 + max|p|) × RAY_EPSILON``
scene units off it along the normal."""

SPAWN_OFFSET_MAX_MM = 1.0
"""The largest spawn offset, mm, a face is rendered with: measured, the face's skin at ``direct`` (16 and 64 px,
64 spp, four seeds each) is brighter by 0.25 ± 0.1 % at 10 m from the origin (offset 1.0 mm), 1.3 % at 100 m,
5.1 % at 1000 m (every channel alike: its NCC unchanged), whatever the image size; at the origin the offset is
0.12 mm (``docs/subsurface.md``)."""

FLOAT32_SHARE = 0.01
"""Float32's useful range: where the spacing of float32 positions is at most this share of the smallest length
the render depends on (the skin's mean free path at ``subsurface-volume``, a pixel's footprint otherwise).
``docs/subsurface.md`` measures a slab out to where the spacing is a tenth of its mean free path."""


def translation(value, name: str = "--translate-mm") -> tuple[float, float, float]:
    """
    A translation ``(x, y, z)`` in mm from ``X,Y,Z`` text or three numbers; a one-line error naming ``name``
    otherwise.

    >>> translation("100,0,-5")
    (100.0, 0.0, -5.0)
    """
    parts = value.split(",") if isinstance(value, str) else value
    try:
        values = tuple(float(part) for part in parts)
    except (TypeError, ValueError):
        values = ()
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise SkinrenderError(f"{name} must be three finite numbers of mm, X,Y,Z (e.g. 100,0,0), got {value!r}",
                              role="translate_mm", flag=name if name.startswith("--") else None)
    return values


def float32_spacing(coordinate_mm: float) -> float:
    """The spacing of float32 numbers at ``coordinate_mm`` (mm, in a document whose unit is the mm)."""
    return float(np.spacing(np.float32(abs(coordinate_mm))))


def float32_limit_mm(smallest_mm: float, share: float = FLOAT32_SHARE) -> float:
    """
    The largest coordinate, mm, at which float32 positions are at most ``share × smallest_mm`` apart.

    >>> float32_limit_mm(0.0167)
    2048.0
    """
    exponent = math.floor(math.log2(share * smallest_mm))
    return float(2.0 ** (exponent + 24))


def spawn_offset_mm(farthest_mm: float, unit_mm: float = 1.0) -> float:
    """Mitsuba's offset of a ray spawned at a surface ``farthest_mm`` from the origin, mm, in a document whose unit
    is ``unit_mm`` mm: ``(1 + farthest / unit) × RAY_EPSILON`` units.

    >>> round(spawn_offset_mm(10_000.0, 1000.0), 2)
    0.98
    """
    return (1.0 + abs(farthest_mm) / unit_mm) * RAY_EPSILON * unit_mm


def check_spawn_offset(where: str, farthest_mm: float, unit_mm: float = 1.0,
                       limit_mm: float = SPAWN_OFFSET_MAX_MM) -> float:
    """
    Refuse a scene whose rays spawned at its farthest surface would start more than ``limit_mm`` off it (mm;
    :func:`spawn_offset_mm`): the occlusion lost brightens the render (:data:`SPAWN_OFFSET_MAX_MM`). Returns the
    offset, mm.

    Raises
    ------
    SkinrenderError
        Naming ``where`` (the scene), how far it reaches and how far it may.
    """
    offset = spawn_offset_mm(farthest_mm, unit_mm)
    if offset > limit_mm:
        reach = (limit_mm / (RAY_EPSILON * unit_mm) - 1.0) * unit_mm
        raise SkinrenderError(f"{where}: it reaches {farthest_mm:.4g} mm from the origin, where Mitsuba starts the rays "
                              f"it spawns at a surface {offset:.2g} mm off it, more than {limit_mm:g} mm (lost "
                              f"occlusion brightens the render: 1.3 % at 100 m); keep it within {reach:.4g} mm of the "
                              "origin (--translate-mm)", role="translate_mm", flag="--translate-mm")
    return offset


def check_float32_range(where: str, farthest_mm: float, smallest_mm: float, what: str, unit_mm: float = 1.0) -> float:
    """
    Refuse a scene beyond float32's useful range: where its farthest coordinate from the origin, ``farthest_mm``,
    float32 positions (in a document whose unit is ``unit_mm`` mm) are more than :data:`FLOAT32_SHARE` of
    ``smallest_mm`` (``what``, named in the error) apart. Returns the spacing there, mm.

    >>> check_float32_range("slab", 200.0, 0.0167, "its mean free path")
    1.52587890625e-05

    Raises
    ------
    SkinrenderError
        Naming ``where`` (the scene), how far it reaches and how far it may.
    """
    spacing = float32_spacing(farthest_mm / unit_mm) * unit_mm
    if spacing > FLOAT32_SHARE * smallest_mm:
        limit = float32_limit_mm(smallest_mm / unit_mm) * unit_mm
        raise SkinrenderError(f"{where}: it reaches {farthest_mm:.4g} mm from the origin, where float32 positions are "
                              f"{spacing:.2g} mm apart, more than {FLOAT32_SHARE:g} of {what} ({smallest_mm:.3g} mm): "
                              f"beyond float32's useful range (coordinates up to {limit:.4g} mm); move it nearer the "
                              "origin (--translate-mm)", role="translate_mm", flag="--translate-mm")
    return spacing
