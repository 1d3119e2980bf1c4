"""
What an effect supplies
=======================

An effect of physics (interreflection, a sheen coat, mixed lights, sensor
noise, …) is one :class:`Effect`: its name, a one-line description, and what
it changes in a face render, each a function, or ``None`` where it changes
nothing. A level of physics (:class:`~skinrender.rendering.face.effects.levels.Level`)
applies the effects it is made of in the registry's order, the base
(``direct``) first, each function receiving what the effects before it built:

==============  ==============================================================
part            what the function does
==============  ==============================================================
``integrator``  ``(integrator, setup) → dict``: the Mitsuba integrator so far
                (``None`` before the base) → the integrator
``skin``        ``(material, reflectance, setup) → dict``: the skin's shape
                properties so far (``{"bsdf": …}``; a medium would add
                ``"interior"``) → the skin's
``prop``        ``(material, reflectance, setup) → dict``: the same for a prop
``lights``      ``(lights, scene) → {name: Light}``: the lights so far → the
                lights the render adds (their emitters:
                :func:`~skinrender.rendering.face.document.face_document`)
``post``        ``(frame, setup) → Frame``: after the render, before Eq. 4's
                gain (the image sensor of ``noise``)
``limits``      :class:`Limits`: the analytic limit the effect makes the
                level's test, or that it breaks every limit, and why
``scene``       ``(scene, options) → scene``: the scene as the render sees it
                (``noise``: the lights scaled to its illuminance)
``refuse``      ``(request) → None``: refuses, before any work, what does not
                go with the effect (naming the argument)
``chart``       ``(request, cache) → (Rendering, ImagedRendering | None)``:
                how a chart renders at a level whose last chart part is this
==============  ==============================================================

An effect **owns its options**: ``options`` is a frozen dataclass whose fields
are them (``noise``: :class:`~skinrender.rendering.sensor.NoiseOptions`,
``imager``, ``illuminance``, ``exposure``), each with its default and its
bounds checked in ``__post_init__``; a request holds one instance per effect
of its level, by effect name, and the effect's functions read it from
``setup.options[name]``. ``added_by`` names the options whose presence adds
the effect to a level (an ``imager`` adds ``noise``).

-   :class:`Effect`, :class:`Limits`: an effect and its analytic limits.
-   :class:`Setup`, :class:`Frame`: what the functions read, and what ``post``
    works on.
-   :class:`Replicates`, :class:`Measured`: what a limit's check reads, and
    what a ``measure`` step hands it.
-   :func:`twosided`, :func:`spectrum`: helpers for materials.

Units: reflectance fractions on the grid's wavelengths (nm); a frame's signal
in the specfilm's units (W·m⁻²·sr⁻¹ times the sensitivity's unit) or, after
a sensor, DN; temperatures K; exposure s.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from ....hints import NDArrayFloat
from ....model.camera import Camera
from ....spectra import WavelengthGrid
from ...renderer import _spectrum
from ...physics import Effect, Limits
from ..scene import FaceScene, Light

__all__ = ["Effect", "Limits", "Setup", "Frame", "Replicates", "Measured", "twosided", "spectrum"]


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


def twosided(bsdf: dict) -> dict:
    """
    ``bsdf`` on both sides of a surface: the scan is open at the shoulders, and a path that enters it must
    meet skin, not a black back face.

    >>> twosided({"type": "diffuse"})
    {'type': 'twosided', 'bsdf': {'type': 'diffuse'}}
    """
    return {"type": "twosided", "bsdf": bsdf}


def spectrum(grid: WavelengthGrid, values: NDArrayFloat) -> dict:
    """A Mitsuba spectrum of ``values`` on the grid's wavelengths (nm), as the chart renderer writes them."""
    return _spectrum(grid.wavelengths, values)
