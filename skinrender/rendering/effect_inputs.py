"""
What an effect's functions read and return
==========================================

The objects a face render hands its level's effects (:class:`~skinrender.rendering.physics.Effect`; their parts:
:mod:`skinrender.rendering.face.effects.base`): :class:`Setup` (the render's scene, camera, grid, lights and
options), :class:`Frame` (a rendered frame for ``post``), :class:`Replicates` (what a limit's check reads) and
:class:`Measured` (a level's measurement of them). Importable from :mod:`skinrender.rendering.physics` too.

Units: images in Eq. 4 output units, temperatures K.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from ..hints import NDArrayFloat

if TYPE_CHECKING:
    from ..model.camera import Camera
    from ..spectra import WavelengthGrid
    from .face.scene import FaceScene, Light

__all__ = ["Setup", "Frame", "Replicates", "Measured"]


@dataclass(frozen=True)
class Setup:
    """
    What an effect's functions may read about the render.

    ``scene``, ``camera``, ``grid`` and the level's ``lights`` (``{name: Light}``) for the Mitsuba
    document, and the ``skin`` spec rendered (its reflectance is the ``skin`` part's argument; an effect that
    needs more of it, as the skin model's layers, reads the spec); ``calibration`` (K), ``seed``
    and ``options`` (effect name → its options, :attr:`Effect.options`) for ``post``, ``None`` while the
    document is built.
    """

    scene: FaceScene
    camera: Camera
    grid: WavelengthGrid
    lights: Mapping[str, Light]
    calibration: float | None = None
    seed: int | None = None
    options: Mapping[str, object] = field(default_factory=dict)
    skin: str | None = None


@dataclass(frozen=True)
class Frame:
    """
    A rendered frame before Eq. 4's gain: ``signal`` ``(height, width, 3)`` (the specfilm's radiance,
    or DN after a sensor), the whites in the same units that the gain is formed from, ``(3,)`` each,
    and the rendering's ``info`` (JSON-ready).
    """

    signal: NDArrayFloat
    white_prevailing: NDArrayFloat
    white_calibration: NDArrayFloat
    info: dict


@dataclass(frozen=True)
class Replicates:
    """
    What a limit's check reads: the replicate images ``(K, height, width, 3)`` (balanced, output units,
    after any ``measure``), the ``labels``, Eq. 4's NCC of the skin ``expected``, the ``first`` replicate
    (a :class:`~skinrender.rendering.face.render.FaceRendering`), the level's ``lights`` in its scene,
    and a sensor's ``usable`` pixels, ``bias`` bound and standard-error ``floor`` (``None`` without one).
    """

    images: NDArrayFloat
    labels: NDArrayFloat
    expected: NDArrayFloat
    first: object
    """A :class:`~skinrender.rendering.face.render.FaceRendering`."""
    lights: Mapping[str, Light]
    usable: NDArrayFloat | None = None
    bias: NDArrayFloat | None = None
    floor: NDArrayFloat | None = None


@dataclass(frozen=True)
class Measured:
    """
    The replicate images as the checks see them, after a ``measure`` step (a sensor's: its dark signal
    removed), with the ``usable`` pixels, the ``bias`` bound and the standard-error ``floor``
    (:class:`Replicates`), the pixels it left out (``excluded``, ``{name: count}``, added to the check's
    details) and a ``note`` added to the reason of a check left undecided.
    """

    images: NDArrayFloat
    usable: NDArrayFloat | None = None
    bias: NDArrayFloat | None = None
    floor: NDArrayFloat | None = None
    excluded: dict = field(default_factory=dict)
    note: str = ""
