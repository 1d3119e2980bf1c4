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
``chart``       ``(request) → source``: a chart's raw renders at a level
                whose last chart part is this (``source.raw(temperature,
                seed, skins)``, ``source.info``; a chart's effects only)
==============  ==============================================================

An effect **owns its options**: ``options`` is a frozen dataclass whose fields
are them (``noise``: :class:`~skinrender.rendering.sensor.NoiseOptions`,
``imager``, ``illuminance``, ``exposure``), each with its default and its
bounds checked in ``__post_init__``; a request holds one instance per effect
of its level, by effect name, and the effect's functions read it from
``setup.options[name]``. ``added_by`` names the options whose presence adds
the effect to a level (an ``imager`` adds ``noise``).

-   :class:`Effect`, :class:`Limits`: an effect and its analytic limits (the
    classes every scene kind's physics is made of:
    :mod:`skinrender.rendering.physics`, where they are defined).
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

from ....hints import NDArrayFloat
from ....spectra import WavelengthGrid
from ...physics import Effect, Frame, Limits, Measured, Replicates, Setup
from ...renderer import mitsuba_spectrum

__all__ = ["Effect", "Limits", "Setup", "Frame", "Replicates", "Measured", "twosided", "spectrum"]


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
    return mitsuba_spectrum(grid.wavelengths, values)
