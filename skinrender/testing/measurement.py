"""
A render reduced to what a regression compares
===============================================

:class:`Measurement`, what :func:`skinrender.testing.regression.measure` makes of a render and
:func:`~skinrender.testing.regression.compare` compares, and :func:`named_argument`, the one wording of a check's
bad argument.

Units: means and standard errors in Eq. 4 output units, NCC fractions.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..errors import SkinrenderError
from ..hints import NDArrayFloat

__all__ = ["Measurement", "named_argument"]


@dataclass(frozen=True)
class Measurement:
    """A render reduced to the values a regression compares.

    Attributes
    ----------
    kind
        ``chart`` or ``face``.
    image
        ``(height, width, 3)`` float32, output units (a face: the mean of its replicates).
    labels
        ``(height, width)`` int32 region labels of a face; ``None`` for a chart.
    channels
        The image's EXR channel names (by the camera).
    regions
        Patch names (chart) or ``{name: label}`` of the regions present (face).
    items
        One name per value: ``"<patch or region> / <channel>"``, ``"skin NCC / r"``.
    mean, standard_error, dof
        Per value (output units; NCC fractions); ``dof`` inf where the standard error is 0.
    settings
        What made it, JSON-ready: scene, camera and its curves' hash, temperatures, spp, seed, variant, …
    scene
        The :class:`~skinrender.rendering.scene.ChartScene` of a chart (its patch layout); ``None`` for a face.
    """

    kind: str
    image: NDArrayFloat
    labels: NDArrayFloat | None
    channels: tuple[str, ...]
    regions: tuple[str, ...] | dict
    items: tuple[str, ...]
    mean: NDArrayFloat
    standard_error: NDArrayFloat
    dof: NDArrayFloat
    settings: dict = field(default_factory=dict)
    scene: object = None


def named_argument(name: str, function, *args, **kwargs):
    """``function(*args)``, its :class:`SkinrenderError` prefixed with the argument ``name`` unless it names it
    already (its message begins with ``name``: ``camera 'x': …``)."""
    try:
        return function(*args, **kwargs)
    except SkinrenderError as error:
        if error.message.startswith(name):
            raise error if error.role == name else error.reworded(role=name) from None
        raise error.reworded(f"{name}: {error.message}", role=name) from None
