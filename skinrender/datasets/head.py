"""
The head mesh
=============

A scanned human head for rendering faces: "Infinite, 3D Head Scan" by Lee
Perry-Smith, 8 844 vertices and 17 684 triangles (the scan's 8 842 quads,
each split in two), bundled as ``resources/head_lee_perry_smith.npz`` with
its attribution and licence text beside it
(``resources/head_lee_perry_smith_LICENSE.txt``, CC BY 3.0), and checked
against its SHA-256 on load.

-   :func:`mesh_head`: vertices and triangles, read once.
-   :data:`SOURCE_HEAD`, :data:`LICENCE_HEAD`: where it comes from, and the
    licence and attribution it is bundled under.

Geometry: units of the scan, about metres (0.45 m wide across the
shoulders), y up, the face looking along +z, the nose tip near
(0, −0.04, 0.05); triangles wound as the scan's quads were.
``tools/build_head_mesh.py`` rebuilds the npz from the distributed OBJ.

References
----------
-   Lee Perry-Smith, Infinite Realities (2010). Infinite, 3D Head Scan.
    CC BY 3.0, based on a work at www.triplegangers.com; as distributed by
    M. McGuire, Computer Graphics Archive (2017), https://casual-effects.com/data.
"""

from __future__ import annotations

import hashlib
import io
from functools import lru_cache

import numpy as np

from ..errors import SkinrenderError
from ..hints import NDArrayFloat
from .registry import ROOT_RESOURCES

__all__ = ["FILE_HEAD", "FILE_HEAD_LICENCE", "SHA256_HEAD", "SOURCE_HEAD", "LICENCE_HEAD", "TRIANGLES_HEAD",
           "mesh_head"]

FILE_HEAD = "head_lee_perry_smith.npz"
"""The bundled mesh, under :data:`~skinrender.datasets.registry.ROOT_RESOURCES`."""

FILE_HEAD_LICENCE = "head_lee_perry_smith_LICENSE.txt"
"""The attribution and licence text, beside the mesh."""

SHA256_HEAD = "ccd556e459d22274c904743f324c6cf3d93bdaa25a5927529fc729c070636343"
"""SHA-256 of :data:`FILE_HEAD` as ``tools/build_head_mesh.py`` writes it."""

TRIANGLES_HEAD = 17684
"""Triangles of the mesh (8 842 quads, each split in two)."""

SOURCE_HEAD = ("\"Infinite, 3D Head Scan\" by Lee Perry-Smith (Infinite Realities, based on a work at "
               "www.triplegangers.com), as distributed by Morgan McGuire's Computer Graphics Archive "
               "(https://casual-effects.com/data); quads split into triangles, UVs and textures left out")

LICENCE_HEAD = ("CC BY 3.0 (Creative Commons Attribution 3.0 Unported); attribution and licence text in "
                f"skinrender/datasets/resources/{FILE_HEAD_LICENCE}")


@lru_cache(maxsize=1)
def mesh_head() -> tuple[NDArrayFloat, NDArrayFloat]:
    """
    The head mesh: vertices and triangles.

    Returns
    -------
    vertices, triangles
        ``(8844, 3)`` float32 positions (about metres, y up, the face along
        +z) and ``(17684, 3)`` int32 vertex indices (0-based); both
        read-only.

    Raises
    ------
    SkinrenderError
        The bundled file is missing or was modified (its SHA-256 differs).

    Examples
    --------
    >>> vertices, triangles = mesh_head()
    >>> vertices.shape, triangles.shape
    ((8844, 3), (17684, 3))
    """

    path = ROOT_RESOURCES / FILE_HEAD
    try:
        data = path.read_bytes()
    except OSError as error:
        raise SkinrenderError(f"bundled head mesh {path} cannot be read ({error.strerror})") from None
    digest = hashlib.sha256(data).hexdigest()
    if digest != SHA256_HEAD:
        raise SkinrenderError(f"bundled head mesh {path} has SHA-256 {digest}, expected {SHA256_HEAD}: the "
                              "file was modified; rebuild it with tools/build_head_mesh.py")
    with np.load(io.BytesIO(data), allow_pickle=False) as archive:
        vertices, triangles = archive["vertices"], archive["triangles"]
    for array in (vertices, triangles):
        array.setflags(write=False)
    return vertices, triangles
