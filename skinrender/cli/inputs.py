"""
What a render command was asked, as objects
===========================================

The converters of the render commands (``render``, ``validate``, ``detect``):
each flag is parsed and checked once, here, into a frozen, typed object, and
everything below the command line takes those objects (never the strings):

-   :func:`scene_of`: ``SCENE`` → a :class:`~skinrender.rendering.scene.ChartScene` or a
    :class:`~skinrender.rendering.face.scene.FaceScene` (one
    :func:`~skinrender.rendering.dispatch.load_scene` for both: the command then
    takes the chart's road or the face's);
-   :func:`chart_inputs`, :class:`ChartInputs`: the camera (with its
    ``--extrapolation``), the two Planckian lights (K), the grid, the
    normalisation and knee of a chart render, each checked against the others
    before anything renders;
-   :func:`chart_only`: the face's flags refused on a chart (``--physics``
    but a chart's levels, :data:`~skinrender.rendering.balance.CHART_PHYSICS`);
-   :func:`imaging_document`, :func:`imaging_notes`: what a render through
    ``--imager`` adds to a command's JSON and text.

The render settings (``--quality``, ``--spp``, ``--sampler``, ``--seed``,
``--variant``, ``--channels``) are :func:`~skinrender.cli.common.settings_of`'s
:class:`~skinrender.rendering.settings.RenderSettings`.

Units: temperatures K, wavelengths nm.
"""

from __future__ import annotations

import argparse
from dataclasses import dataclass
from typing import TYPE_CHECKING

from ..errors import SkinrenderError
from .common import camera_of, flag, grid_of
from .placement import translate_of

if TYPE_CHECKING:
    from ..model.camera import Camera
    from ..rendering.face.scene import FaceScene
    from ..rendering.scene import ChartScene
    from ..rendering.settings import RenderSettings
    from ..spectra import WavelengthGrid

__all__ = ["scene_of", "ChartInputs", "chart_inputs", "chart_only", "imaging_document", "imaging_notes"]


def scene_of(args: argparse.Namespace, name: str = "SCENE") -> ChartScene | FaceScene:
    """``args.scene`` loaded once (:func:`~skinrender.rendering.dispatch.load_scene`): a chart or a face scene;
    a refusal names ``name``."""
    from ..rendering.dispatch import load_scene

    return flag(name, load_scene, args.scene)


@dataclass(frozen=True)
class ChartInputs:
    """
    A chart render's inputs, each parsed once from its flag.

    Attributes
    ----------
    camera
        With the ``--extrapolation`` of its CSV curves.
    prevailing, calibration
        The Planckian lights, K.
    grid
        ``--grid``, nm.
    physics
        ``--physics``: ``direct`` or ``subsurface`` (:data:`~skinrender.rendering.balance.CHART_PHYSICS`; the
        checks of ``subsurface`` are :func:`~skinrender.cli.subsurface.check_chart_subsurface`'s).
    translate_mm
        ``--translate-mm`` (x, y, z mm; ``subsurface`` only), or ``None``.
    """

    scene: ChartScene
    camera: Camera
    prevailing: float
    calibration: float
    grid: WavelengthGrid
    normalization: str = "white"
    knee: bool = False
    physics: str = "direct"
    translate_mm: tuple[float, float, float] | None = None

    def keywords(self) -> dict:
        """The arguments of :func:`~skinrender.rendering.balance.render` and
        :func:`~skinrender.rendering.validation.validate` they give."""
        moved = {} if self.translate_mm is None else {"translate_mm": self.translate_mm}
        return {"scene": self.scene, "camera_": self.camera, "prevailing": self.prevailing,
                "calibration": self.calibration, "normalization": self.normalization, "knee": self.knee,
                "grid": self.grid, "physics": self.physics, **moved}

    @property
    def pixels(self) -> int:
        """The pixels of the chart's image."""
        width, height = self.scene.size
        return int(width) * int(height)

    def render(self, settings: RenderSettings, imaging: dict | None = None, knee: bool = False) -> tuple:
        """
        The chart rendered with ``settings``: plain (Eq. 4 on the radiance; ``knee`` applied there) or through the
        image sensor of ``imaging`` (:func:`~skinrender.cli.common.imaging_options`); ``(rendering, imaged)``,
        ``imaged`` ``None`` without a sensor.
        """
        from ..rendering.balance import render

        if imaging is None:
            return render(**{**self.keywords(), "knee": knee}, settings=settings), None
        from ..rendering.imaging import render_imaged

        imaged = render_imaged(self.scene, self.camera, self.prevailing, self.calibration, **imaging,
                               normalization=self.normalization, settings=settings, grid=self.grid)
        return imaged.rendering, imaged


def chart_inputs(args: argparse.Namespace, scene: ChartScene) -> ChartInputs:
    """
    The camera and the two Planckian temperatures (K) of a chart render, each parsed once here with its flag
    named in any error, and checked to give the camera light on the grid (``--grid`` parsed once too) before
    anything renders; ``scene``: the chart :func:`scene_of` loaded.
    """
    import numpy as np

    from ..model.illuminant import illuminant
    from ..model.response import response

    grid = grid_of(args)
    cam = camera_of(args, grid)
    temperatures = {}
    for name in ("prevailing", "calibration"):
        light = flag(f"--{name}", illuminant, getattr(args, name))
        if light.temperature is None:
            raise SkinrenderError(f"--{name}: rendering needs a Planckian illuminant (kelvin, A or H), got {light}",
                                  flag=f"--{name}")
        temperatures[name] = light.temperature
    for name, kelvin in temperatures.items():  # each light seen by the camera, the one at fault named
        flag({"camera": "--camera", None: f"--{name}"}, response, cam, np.ones((1, grid.size)), kelvin, kelvin,
             grid=grid)
    try:  # every patch's data covers the grid, before the render needs it
        scene.reflectances(grid)
    except SkinrenderError as error:  # the chart's own data: --extrapolation (CSV cameras') does not apply
        if error.cause != "coverage":
            raise error.reworded(f"SCENE: {error.message}", flag="SCENE") from None
        raise error.reworded(f"--grid: {error.message}", flag="--grid", cause=None,
                             hint="choose a --grid inside the chart's data") from None
    physics = str(getattr(args, "physics", "direct")).strip()
    translate = translate_of(args)
    if translate is not None and physics != "subsurface":
        raise SkinrenderError("--translate-mm moves a face, or a chart at --physics subsurface (its slabs are in mm); "
                              f"a chart at --physics {physics} is laid out in pixels", flag="--translate-mm")
    return ChartInputs(scene, cam, temperatures["prevailing"], temperatures["calibration"], grid,
                       getattr(args, "normalization", "white"), bool(getattr(args, "knee", False)), physics,
                       translate)


def chart_only(args: argparse.Namespace, skin: bool = True) -> None:
    """The face-only flags refused on a chart: ``--physics`` but a chart's levels
    (:data:`~skinrender.rendering.balance.CHART_PHYSICS`), ``--size`` and (but for ``detect``) ``--skin``."""
    from ..rendering.balance import CHART_PHYSICS

    physics = str(args.physics).strip()
    given = [name for name, on in (("--physics", physics not in CHART_PHYSICS),
                                   ("--skin", skin and args.skin is not None), ("--size", args.size is not None)) if on]
    if given:
        levels = f" (a chart takes --physics {' or '.join(CHART_PHYSICS)})" if "--physics" in given else ""
        raise SkinrenderError(f"{', '.join(given)}: {'goes' if len(given) == 1 else 'go'} with a face scene "
                              f"(e.g. 'face'), not a chart{levels}", flag=given[0])


def imaging_document(imaged) -> dict:
    """
    The JSON keys a render through an imager adds: imager, illuminance_lux, exposure_s, ``clipping`` (pixels at the
    full well and at the ADC range, per channel) and ``notes`` (a capped ``auto`` exposure, clipped pixels).
    """
    if imaged is None:
        return {}
    return {"imager": imaged.imager.name, "illuminance_lux": imaged.illuminance_lux, "exposure_s": imaged.exposure_s,
            "clipping": imaged.clipping, "notes": list(imaged.notes)}


def imaging_notes(imaged) -> str:
    """The text lines of a render's imaging notes (a capped exposure, clipped pixels), or nothing."""
    return "".join(f"\nnote: {note}" for note in (imaged.notes if imaged is not None else ()))
