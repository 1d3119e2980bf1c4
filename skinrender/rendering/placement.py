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

Units: mm.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import SkinrenderError

__all__ = ["FLOAT32_SHARE", "translation", "float32_spacing", "float32_limit_mm", "check_float32_range"]

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
