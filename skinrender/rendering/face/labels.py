"""
Face labels
===========

The label image of a face render: which surface each pixel sees, from the
geometry, not from colour. Mitsuba's ``aov`` integrator (``shape_index``)
has been reported to crash beside a ``specfilm``, so the labels are a
separate pass: one camera ray through each pixel centre, intersected with
the loaded scene (``Scene.ray_intersect``), its shape mapped to a label by
the id it was added under.

-   :data:`LABEL_BACKGROUND`, :data:`LABEL_SKIN`: 0 and 1; props are 2, 3, …
    in the order of the scene file.
-   :func:`label_names`: ``{name: label}`` of a face scene.
-   :func:`shape_labels`: ``{Mitsuba shape id: label}``.
-   :func:`render_labels`: the label image of a loaded scene.
-   :func:`interior`: the pixels of a label whose whole neighbourhood has it
    (no pixel footprint straddling two surfaces).

Pixels whose footprint covers two surfaces get the label of the surface at
their centre; :func:`interior` leaves them out where that matters.
"""

from __future__ import annotations

import numpy as np

from ...hints import NDArrayFloat
from .scene import FaceScene

__all__ = ["LABEL_BACKGROUND", "LABEL_SKIN", "SHAPE_SKIN", "label_names", "prop_shape_id", "shape_labels",
           "render_labels", "interior"]

LABEL_BACKGROUND = 0
"""Label of pixels that see no surface."""

LABEL_SKIN = 1
"""Label of pixels that see the head (skin)."""

SHAPE_SKIN = "skin"
"""The Mitsuba id of the head mesh."""


def prop_shape_id(index: int) -> str:
    """The Mitsuba id of the ``index``-th prop (0-based)."""
    return f"prop_{index:03d}"


def label_names(scene: FaceScene) -> dict[str, int]:
    """
    ``{name: label}``: ``background`` 0, ``skin`` 1, then each prop by name.

    Examples
    --------
    >>> from skinrender.rendering.face.scene import load_face_scene
    >>> label_names(load_face_scene("face"))["skin"]
    1
    """
    names = {"background": LABEL_BACKGROUND, "skin": LABEL_SKIN}
    names.update({prop.name: LABEL_SKIN + 1 + k for k, prop in enumerate(scene.props)})
    return names


def shape_labels(scene: FaceScene) -> dict[str, int]:
    """``{Mitsuba shape id: label}`` of the shapes a face scene adds."""
    labels = {SHAPE_SKIN: LABEL_SKIN}
    labels.update({prop_shape_id(k): LABEL_SKIN + 1 + k for k in range(len(scene.props))})
    return labels


def render_labels(mi, loaded, width: int, height: int, labels: dict[str, int]) -> NDArrayFloat:
    """
    The label of the surface seen through each pixel centre.

    Parameters
    ----------
    mi
        The ``mitsuba`` module, its variant set.
    loaded
        The loaded Mitsuba scene (its first sensor is the camera).
    width, height
        Image size, pixels.
    labels
        ``{shape id: label}``; shapes not named get :data:`LABEL_BACKGROUND`.

    Returns
    -------
    :class:`numpy.ndarray`
        ``(height, width)`` int32, rows from the top.
    """

    sensor = loaded.sensors()[0]
    rows, columns = np.meshgrid(np.arange(height), np.arange(width), indexing="ij")
    u = ((columns + 0.5) / width).ravel().astype(np.float32)
    v = ((rows + 0.5) / height).ravel().astype(np.float32)
    by_shape = {}
    for shape in loaded.shapes():
        by_shape[shape.id()] = labels.get(shape.id(), LABEL_BACKGROUND)
    if mi.variant().startswith("scalar"):
        out = np.zeros(u.size, dtype=np.int32)
        for k in range(u.size):
            ray, _ = sensor.sample_ray(0.0, 0.5, mi.Point2f(u[k], v[k]), mi.Point2f(0.5, 0.5))
            hit = loaded.ray_intersect(ray)
            if hit.is_valid():
                out[k] = by_shape.get(hit.shape.id(), LABEL_BACKGROUND)
        return out.reshape(height, width)
    import drjit as dr

    count = u.size
    time_, wavelength = mi.Float(np.zeros(count, np.float32)), mi.Float(np.full(count, 0.5, np.float32))
    ray, _ = sensor.sample_ray(time_, wavelength, mi.Point2f(u, v), mi.Point2f(0.5, 0.5))
    hit = loaded.ray_intersect(ray)
    seen = np.array(dr.reinterpret_array(mi.UInt32, hit.shape))
    valid = np.array(hit.is_valid(), dtype=bool)
    registry = np.array(dr.reinterpret_array(mi.UInt32, loaded.shapes_dr()))
    out = np.zeros(count, dtype=np.int32)
    for key, shape in zip(registry, loaded.shapes()):
        out[valid & (seen == key)] = by_shape[shape.id()]
    return out.reshape(height, width)


def interior(labels: NDArrayFloat, label: int, margin: int = 1) -> NDArrayFloat:
    """
    The pixels labelled ``label`` whose neighbours within ``margin`` pixels
    (a square) are all labelled so too; image-border pixels are left out.

    Examples
    --------
    >>> image = np.zeros((5, 5), dtype=int)
    >>> image[1:4, 1:4] = 1
    >>> int(interior(image, 1).sum())
    1
    """

    labels = np.asarray(labels)
    mask = labels == label
    height, width = mask.shape
    out = np.zeros_like(mask)
    if min(height, width) <= 2 * margin:
        return out
    inner = np.ones((height - 2 * margin, width - 2 * margin), dtype=bool)
    for dy in range(-margin, margin + 1):
        for dx in range(-margin, margin + 1):
            inner &= mask[margin + dy:height - margin + dy, margin + dx:width - margin + dx]
    out[margin:height - margin, margin:width - margin] = inner
    return out
