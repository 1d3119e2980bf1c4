"""
How far a face scene reaches from the origin
============================================

A face render is refused where its scene lies beyond float32's useful range
(:func:`~skinrender.rendering.placement.check_float32_range`): where float32
positions are too coarse for the smallest length its level depends on, the
skin's mean free path at ``subsurface-volume`` (where its walks are: the mesh), a
pixel's footprint at the camera target otherwise (on the mesh and the props). A scene gets there moved by ``--translate-mm``
(:meth:`~skinrender.rendering.face.scene.FaceScene.translated`), or written
there.

-   :func:`face_reach_mm`: the largest coordinate of a face scene.
-   :func:`check_face_range`: the refusal, naming the scene.

Units: mm.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..placement import check_float32_range, check_spawn_offset
from .document import transform
from .effects import physics_level
from .scene import MESH_HEAD, FaceScene

__all__ = ["face_reach_mm", "check_face_range"]


@lru_cache(maxsize=16)
def _mesh_reach_m(mesh: str, matrix: tuple) -> float:
    """The largest absolute coordinate of a mesh placed by ``matrix`` (a 4×4 as nested tuples), m."""
    m = np.array(matrix)
    if mesh == MESH_HEAD:
        from ...datasets.head import mesh_head

        vertices = mesh_head()[0].astype(np.float64)
        return float(np.max(np.abs(vertices @ m[:3, :3].T + m[:3, 3])))
    from ..variants import choose_variant, mitsuba

    mi = mitsuba(choose_variant(None))
    kind = "ply" if mesh.lower().endswith(".ply") else "obj"
    box = mi.load_dict({"type": kind, "filename": mesh, "to_world": mi.ScalarTransform4f(m)}).bbox()
    return float(np.max(np.abs([list(box.min), list(box.max)])))


def face_reach_mm(scene: FaceScene, props: bool = True) -> float:
    """
    The largest absolute coordinate of a face scene's surfaces, mm: its mesh (its vertices) and, with ``props``, its
    props (their centres plus half their size's diagonal). The camera and the lights are left out: where they are
    to a float32 step matters to nothing the render resolves.
    """
    matrix = transform(scene.mesh_translate, scene.mesh_rotate, scene.mesh_scale)
    reach = [_mesh_reach_m(scene.mesh, tuple(map(tuple, matrix)))]
    if props:
        reach += [float(np.max(np.abs(prop.position)) + np.linalg.norm(prop.size) / 2) for prop in scene.props]
    return 1000.0 * max(reach)


def check_face_range(scene: FaceScene, physics, skin: str, grid) -> float:
    """
    Refuse ``scene`` at level ``physics`` with ``skin`` where it lies beyond float32's useful range (module
    docstring); returns the float32 spacing at its farthest coordinate, mm.

    Raises
    ------
    SkinrenderError
        Naming the scene.
    """
    level = physics_level(physics)
    from .effects.subsurface import SUBSURFACE_VOLUME, face_media

    skin_walks = SUBSURFACE_VOLUME in level.effects  # the level walks under the skin (skinvolpath)
    if any(effect.name.startswith("subsurface") for effect in level.effects):  # the fast level's too: the skin's
        face_media(skin, grid)  # fit refused before any level renders (a ladder rendered the others first)
    if skin_walks:
        from ..subsurface import mean_free_path

        smallest, what = mean_free_path(face_media(skin, grid).layers), f"the mean free path of its skin {skin!r}"
    else:
        c = scene.camera
        distance = float(np.linalg.norm(np.subtract(c.target, c.position)))
        smallest = 2000.0 * distance * np.tan(np.radians(c.fov) / 2) / c.width
        what = "a pixel's footprint at the camera target"
    where, unit_mm = scene.source or scene.name, 1000.0 / level.scene_scale
    check_spawn_offset(where, face_reach_mm(scene), unit_mm)  # occlusion: the mesh's and the props' surfaces
    return check_float32_range(where, face_reach_mm(scene, props=not skin_walks), smallest, what, unit_mm)
