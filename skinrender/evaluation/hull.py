"""
Convex hulls
============

One function, :func:`hull_volume_vertices`, answers "what is the volume of
this cloud's convex hull, and which points are its vertices" for the gamut
evaluator and the Stage 3 search: the compiled Quickhull of
``skinrender/evaluation/_hull3d.c`` answers the general case, and Qhull
(scipy) answers what the kernel declines (flat or nearly flat clouds,
numerical doubt) and everything when the package was built without a C
compiler.

-   :data:`HULL_KERNEL`: which kernel this installation has.
-   :func:`hull_volume_vertices`: volume and vertex indices.
-   :data:`FLAT_SUSPECT`, :data:`QHULL_OPTIONS`.
-   :func:`notice_kernel`: the one-line notice when the kernel is missing.

References
----------
-   :cite:`Barber1996` : Quickhull (docs/references.md).
"""

from __future__ import annotations

import numpy as np

from ..hints import NDArrayFloat
from .gamut import is_flat, to_unit_box

try:
    from . import _hull3d
except ImportError:  # built without a C compiler: Qhull does every hull
    _hull3d = None

__all__ = ["HULL_KERNEL", "FLAT_SUSPECT", "QHULL_OPTIONS", "hull_volume_vertices", "compiled_kernel", "notice_kernel"]

HULL_KERNEL = "quickhull" if _hull3d is not None else "qhull"
"""The hull kernel: ``quickhull`` (the compiled Quickhull of
``skinrender/evaluation/_hull3d.c``, with Qhull for the flat and doubtful
clouds it declines) or ``qhull`` (scipy's Qhull for every hull, when the
package was installed without a C compiler; several times slower)."""

QHULL_OPTIONS = "Qt Q5 Q8"
"""Qhull options of the fast method: ``Qt`` (triangulated output, scipy's
default), ``Q5`` (no final check of outer planes) and ``Q8`` (no bookkeeping of
near-inside points): neither changes which points are vertices or the volume
(checked: identical volumes). One measurement showed them 40 % faster; a
careful rerun put the difference within the ±30 % run-to-run noise of these
machines, so no saving is claimed."""


FLAT_SUSPECT = 1e-6
"""A hull whose volume exceeds this fraction of ``L³`` (``L`` the bounding
box's longest side) is not flat by the test of
:func:`skinrender.gamut.is_flat`; only thinner hulls pay for that SVD test (and
the compiled kernel hands them to Qhull).

Why it is safe: a cloud of ``n`` points whose smallest principal extent is at
most 1e-10 of its largest has widths ``w1, w2 ≤ √3·L`` and ``w3 ≤ 2e-10·√(3n)·L``
(a width is at most twice the largest projection, a singular value at most √n
times it), so its hull volume is at most ``1.04e-9·√n·L³``: below this fraction
for every cloud of up to 900 000 points (the search's largest has 126 900)."""


def compiled_kernel():
    """The compiled module ``skinrender.evaluation._hull3d``, or ``None`` where it was not built."""
    return _hull3d


def hull_volume_vertices(cloud: NDArrayFloat) -> tuple[float, np.ndarray | None]:
    """
    Volume and vertex indices of the hull of ``cloud``; for a degenerate cloud
    (flat by the test of :func:`skinrender.gamut.gamut`) volume 0 and ``None``
    (every point is kept, since none can be ruled out).

    The compiled Quickhull (:data:`HULL_KERNEL`) answers the general case;
    Qhull answers what it declines (flat or nearly flat clouds, numerical
    doubt) and everything when the kernel was not built.
    """

    if len(cloud) < 4:
        return 0.0, None
    if _hull3d is not None:
        answer = _hull3d.hull(np.ascontiguousarray(cloud, dtype=np.float64), FLAT_SUSPECT)
        if answer is not None:
            return answer[0], np.frombuffer(answer[1], dtype=np.int32)
    boxed = to_unit_box(cloud)  # as gamut() does: flatness is scale-free
    if boxed is None:
        return 0.0, None
    unit, scale = boxed
    from scipy.spatial import ConvexHull, QhullError  # here: a heavy import most commands never use

    try:
        hull = ConvexHull(unit, qhull_options=QHULL_OPTIONS)
    except QhullError:
        return 0.0, None
    if not hull.volume > FLAT_SUSPECT * float(np.max(hull.max_bound - hull.min_bound)) ** 3 and is_flat(unit):
        return 0.0, None
    return float(hull.volume * np.prod(scale)), hull.vertices

_NOTICED: list[bool] = []


def notice_kernel(stream) -> None:
    """One line on ``stream``, once per process, when the compiled hull kernel is missing."""
    if _hull3d is None and stream is not None and not _NOTICED:
        _NOTICED.append(True)
        print(
            "skinrender: notice: the compiled hull kernel skinrender.evaluation._hull3d is missing (installed without a C "
            "compiler); the search uses Qhull for every hull, about 5x slower. Reinstall with gcc present.",
            file=stream,
        )
