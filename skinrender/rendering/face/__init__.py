"""
Faces
=====

A head in skin under Planckian lights, props beside it, rendered through a
camera's three channels at a level of physics and checked against the
analytic limits that hold there. One module per concept:

-   :mod:`~skinrender.rendering.face.scene`: face scene files
    (:class:`FaceScene`, :func:`load_face_scene`).
-   :mod:`~skinrender.rendering.face.effects`: the effects of physics, one
    module each, their registry and levels as their compositions
    (:data:`PHYSICS`, :func:`physics_level`).
-   :mod:`~skinrender.rendering.face.document`: the Mitsuba 3 scene
    dictionary of a face scene at a level, and the spectral pieces every face
    render shares.
-   :mod:`~skinrender.rendering.face.render`: one render
    (:func:`render_face`, :class:`FaceRendering`, :func:`write_face_exr`).
-   :mod:`~skinrender.rendering.face.labels`: the label image (which surface
    each pixel sees).
-   :mod:`~skinrender.rendering.face.limits`,
    :mod:`~skinrender.rendering.face.limit_scenes`: the analytic limits'
    statistics and checks, the furnace and sphere scenes.
-   :mod:`~skinrender.rendering.face.shift`: Eq. 4's error on the face
    against a detection budget (``eq4_shift``).
-   :mod:`~skinrender.rendering.face.validation`: ``validate`` on a face
    (:func:`validate_face`).

The public names below are importable from here
(``from skinrender.rendering.face import render_face``).
"""

from __future__ import annotations

from .effects import PHYSICS, Level, parse_physics, physics_level
from .effects.noise import IMAGER_DEFAULT
from .render import FaceRendering, planckian_temperature, render_face, white_references, write_face_exr
from .scene import FaceScene, load_face_scene
from .validation import FaceValidation, validate_face

__all__ = ["PHYSICS", "IMAGER_DEFAULT", "Level", "parse_physics", "physics_level", "FaceScene", "load_face_scene",
           "FaceRendering", "planckian_temperature", "white_references", "render_face", "write_face_exr",
           "FaceValidation", "validate_face"]
