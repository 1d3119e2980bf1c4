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
==============  ==============================================================

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
from ..scene import FaceScene, Light

__all__ = ["Effect", "Limits", "Setup", "Frame", "Replicates", "Measured", "twosided", "spectrum"]


@dataclass(frozen=True)
class Setup:
    """
    What an effect's functions may read about the render.

    ``scene``, ``camera``, ``grid`` and the level's ``lights`` (``{name: Light}``) for the Mitsuba
    document, and the ``skin`` spec rendered (its reflectance is the ``skin`` part's argument; an effect that
    needs more of it, as the skin model's layers, reads the spec); ``calibration`` (K), ``seed``, ``imager``
    (a preset, a TOML path or ``None``: the default) and ``exposure`` (``auto`` or s) for ``post``, ``None``
    while the document is built.
    """

    scene: FaceScene
    camera: Camera
    grid: WavelengthGrid
    lights: Mapping[str, Light]
    calibration: float | None = None
    seed: int | None = None
    imager: object = None
    exposure: object = "auto"
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


@dataclass(frozen=True)
class Limits:
    """
    An effect's analytic limits.

    Attributes
    ----------
    check
        ``(replicates: Replicates) → LimitCheck``: the test of a level this effect is in (a later
        effect's check replaces an earlier one's: ``sheen``'s dichromatic plane replaces ``direct``'s
        shading), or ``None``.
    holds
        ``False`` when no analytic limit holds with the effect (``interreflection``, ``mixed``): a level
        with it has no check, only ``eq4_shift``.
    why
        Why the level's check is what it is (or why there is none): ``eq4_shift``'s reason. A level
        takes it from its first effect that breaks the limits, else from the effect whose check it runs.
    measure
        ``(measured: Measured, first, imager) → Measured``: how the replicate images become the values
        checked (a sensor's dark signal, clipping and quantisation), or ``None``.
    """

    check: Callable | None = None
    holds: bool = True
    why: str | None = None
    measure: Callable | None = None


@dataclass(frozen=True)
class Effect:
    """
    One effect of physics (see the module docstring for what each part does).

    Attributes
    ----------
    name
        What a user types (``--physics NAME``), a key of the registry.
    description
        One line: what the effect renders (the CLI's help shows it).
    short
        A few words for lists in prose (``mixed light``); default the name.
    integrator, skin, prop, lights, post
        What it changes, or ``None``.
    limits
        Its analytic limits.
    samples_per_s
        Samples per second of a face render with this effect on one core, measured: the estimates' rate
        (``None``: it costs no more than the base). A level runs at the slowest of its effects' rates.
    scene_scale
        Scene units per metre of the Mitsuba document (1: metres). Mitsuba starts a ray leaving a surface
        ``(1 + max|p|) · 8.9e-5`` scene units off it: in metres, ~0.1 mm at the face; in millimetres (1000),
        ~0.01 mm. A level writes its document at the largest of its effects' scales.
    variant
        ``(requested) → variant``: the Mitsuba variant the effect renders best with (``requested``: the one the
        user named, or ``None``), or ``None`` to leave the choice to
        :func:`~skinrender.rendering.variants.choose_variant`.
    setup_seconds
        One-off seconds on one core before a process's first render of a skin at a level with this effect (the
        fast ``subsurface``: the skin's table, a fit of the skin model to a measured skin and its kernel's
        compilation), measured: the estimates add it once per level and skin.
    excludes
        Effects it cannot be combined with (two transports of the same skin: ``subsurface`` and
        ``subsurface-volume``); a level naming both is refused.
    by_default
        Whether the default levels (``ladder``, ``face-sweep``, the effects table, the face bench) include it;
        ``False`` for a reference too slow for them (``subsurface-volume``), which a user names.
    """

    name: str
    description: str
    short: str = ""
    integrator: Callable | None = None
    skin: Callable | None = None
    prop: Callable | None = None
    lights: Callable | None = None
    post: Callable | None = None
    limits: Limits = field(default_factory=Limits)
    samples_per_s: float | None = None
    scene_scale: float = 1.0
    variant: Callable | None = None
    setup_seconds: float = 0.0
    excludes: tuple[str, ...] = ()
    by_default: bool = True

    @property
    def changes_document(self) -> bool:
        """Whether it changes the Mitsuba document (else it acts after rendering only)."""
        return any(part is not None for part in (self.integrator, self.skin, self.prop, self.lights)) or \
            self.scene_scale != 1.0


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
