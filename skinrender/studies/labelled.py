"""
Labelled figures of renders
===========================

The figures a person reads a render by: a chart with each patch's name on it
(and, after detection, its mask and each patch's detected fraction), a face
with its labels outlined. ``render --figure``, ``detect --figure`` and a
result's ``.figure(path)`` and ``.save(…, figure=path)`` draw them.

Only the studies layer draws (matplotlib stays out of ``rendering``): this
module registers its drawers with :mod:`skinrender.rendering.outputs` when it
is imported, and that module imports it (its ``FIGURE_MODULE``) on the first
figure asked for, so a
:class:`~skinrender.rendering.balance.Rendering` or
:class:`~skinrender.rendering.face.render.FaceRendering` can draw itself
without ``rendering`` importing ``studies``.

-   :func:`chart_figure`: a chart render (:func:`~skinrender.studies.figures.figure_chart`).
-   :func:`face_figure`: a face render (:func:`~skinrender.studies.figures.figure_face`).

Units: images in Eq. 4 output units; temperatures K.
"""

from __future__ import annotations

from pathlib import Path

from ..rendering.outputs import register_figure
from .figures import figure_chart, figure_face

__all__ = ["chart_figure", "face_figure"]


def chart_figure(rendering, path: str | Path, detection=None, rates: str = "") -> Path:
    """
    The labelled figure of a chart render: its patch names and boxes from the scene, and with a ``detection``
    (:class:`~skinrender.evaluation.detection.Detection`) its mask and each patch's detected fraction, ``rates``
    (e.g. ``TPR 0.9, FPR 0.1``) in the title.
    """
    chart = rendering.scene
    boxes = [chart.patch_box(i) for i in range(len(chart.patches))]
    names = [patch.name for patch in chart.patches]
    skin = [patch.skin for patch in chart.patches]
    title = (f"{chart.name} through {rendering.camera.name}, {rendering.prevailing:g} K white-balanced to "
             f"{rendering.calibration:g} K, {rendering.raw[0].spp} spp")
    if detection is None:
        return figure_chart(rendering.image, boxes, names, skin, title, path)
    fractions = [p["detected_fraction"] for p in detection.per_patch] + [None]  # the white reference: not scored
    return figure_chart(rendering.image, boxes, names, skin, f"{title}: {rates}", path, detection.mask, fractions)


def face_figure(rendering, path: str | Path, mask=None, title: str | None = None) -> Path:
    """
    The labelled figure of a face render: its labels outlined and, with ``mask`` (``(height, width)`` bools),
    the detected pixels over it; ``title`` by default names the scene, skin, level, camera, lights and spp.
    """
    r = rendering
    if title is None:
        title = (f"{r.scene.name} ({r.skin}, {r.physics}) through {r.camera.name}, {r.prevailing:g} K balanced to "
                 f"{r.calibration:g} K\n{r.spp} spp; the labels outlined")
    return figure_face(r.image, r.labels, r.label_names, title, path, mask)


register_figure("chart", chart_figure)
register_figure("face", face_figure)
