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
    but a chart's levels, :data:`~skinrender.rendering.chart_effects.CHART_REGISTRY`);
-   :func:`chart_request_of` (a face's: :func:`~skinrender.cli.face.face_request_of`): the request of a render
    command (:mod:`skinrender.rendering.request`), built by its scene kind's
    ``request`` as every front door builds it, each refusal naming its flag
    (:data:`REQUEST_FLAGS`); :func:`check_request_work`: its estimate against
    ``--max-minutes``;
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
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import SkinrenderError
from .common import camera_from, check_output, flag, flagged, grid_from
from .placement import translate_of

if TYPE_CHECKING:
    from ..model.camera import Camera
    from ..rendering.face.scene import FaceScene
    from ..rendering.scene import ChartScene
    from ..rendering.settings import RenderSettings
    from ..spectra import WavelengthGrid

__all__ = ["REQUEST_FLAGS", "by_kind", "scene_of", "scene_from", "figure_from", "is_auto", "ChartInputs", "chart_inputs",
           "chart_inputs_from", "chart_only", "refuse_face_flags", "chart_flags", "chart_request_of",
           "chart_request_from",
           "settings_fields", "settings_keywords", "sensor_flags", "check_request_work", "imaging_document",
           "imaging_notes"]

REQUEST_FLAGS = {"scene": "SCENE", "camera": "--camera", "prevailing": "--prevailing", "calibration": "--calibration",
                 "physics": "--physics", "spp": "--spp", "seed": "--seed", "sampler": "--sampler",
                 "variant": "--variant", "channels": "--channels", "imager": "--imager", "illuminance": "--illuminance",
                 "exposure": "--exposure", "skin": "--skin", "size": "--size", "normalization": "--normalization",
                 "knee": "--knee", "grid": "--grid", "bands": "--bands", "translate_mm": "--translate-mm"}
"""The flag of each argument of a request (an error's ``role`` → the flag a refusal names)."""


def by_kind(scene, **commands):
    """The function of ``scene``'s kind among ``commands``: :func:`skinrender.rendering.kinds.by_kind`, the
    command line's one dispatch on a scene's kind."""
    from ..rendering.kinds import by_kind as of_kind

    return of_kind(scene, **commands)


def scene_of(args: argparse.Namespace, name: str = "SCENE") -> ChartScene | FaceScene:
    """:func:`scene_from` ``args.scene``."""
    return scene_from(args.scene, name)


def scene_from(spec: str, name: str = "SCENE") -> ChartScene | FaceScene:
    """The scene ``spec`` loaded once (:func:`~skinrender.rendering.dispatch.load_scene`): a chart or a face scene;
    a refusal names ``name``."""
    from ..rendering.dispatch import load_scene

    return flag(name, load_scene, spec)


def is_auto(spp) -> bool:
    """Whether ``--spp`` is ``auto`` (:func:`~skinrender.rendering.spp_choice.is_auto`)."""
    from ..rendering.spp_choice import is_auto as auto

    return auto(spp)


def figure_from(path: str | None, *taken) -> Path | None:
    """
    ``--figure`` checked before any work (:func:`~skinrender.cli.common.check_output`, a ``.png``), and refused
    when it is one of the command's other outputs ``taken``; ``None`` when the flag is not given.
    """
    figure = check_output(path, "--figure", (".png",))
    if figure is not None and any(figure.resolve() == Path(other).resolve() for other in taken):
        raise SkinrenderError(f"--figure: {figure} is also another output of the command; name another PNG",
                              flag="--figure")
    return figure


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
        ``--physics`` as given: ``direct``, ``subsurface`` or ``subsurface-volume``, parsed into a level where the
        request is built (:meth:`request`).
    """

    scene: ChartScene
    camera: Camera
    prevailing: float
    calibration: float
    grid: WavelengthGrid
    normalization: str = "white"
    knee: bool = False
    physics: str = "direct"

    def keywords(self) -> dict:
        """The arguments of :func:`~skinrender.rendering.balance.render` and
        :func:`~skinrender.rendering.validation.validate` they give."""
        return {"scene": self.scene, "camera_": self.camera, "prevailing": self.prevailing,
                "calibration": self.calibration, "normalization": self.normalization, "knee": self.knee,
                "grid": self.grid, "physics": self.physics}

    @property
    def pixels(self) -> int:
        """The pixels of the chart's image."""
        width, height = self.scene.size
        return int(width) * int(height)

    def request(self, args: argparse.Namespace, settings: RenderSettings, **changes):
        """
        The :class:`~skinrender.rendering.request.ChartRequest` of these inputs, ``settings`` (the sampler left to
        the level where ``--sampler`` was not given: :func:`settings_fields`) and the sensor's flags
        (``--imager``, ``--illuminance``, ``--exposure``), as every front door builds it
        (:meth:`~skinrender.rendering.kinds.ChartKind.request`); ``changes``: keywords replaced (``knee``).
        """
        from ..rendering.kinds import CHART

        keywords = {"normalization": self.normalization, "knee": self.knee, "grid": self.grid,
                    "physics": self.physics, "translate_mm": translate_of(getattr(args, "translate_mm", None)),
                    **sensor_flags(args),
                    **settings_fields(args, settings), **changes}
        return flagged(REQUEST_FLAGS, CHART.request, self.scene, self.camera, self.prevailing, self.calibration,
                       **keywords)

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
    """:func:`chart_inputs_from` the flags of ``args``."""
    return chart_inputs_from(scene, args.camera, args.prevailing, args.calibration, getattr(args, "grid", None),
                             getattr(args, "extrapolation", "refuse"), getattr(args, "normalization", "white"),
                             getattr(args, "knee", False), getattr(args, "physics", "direct"))


def chart_inputs_from(scene: ChartScene, camera: str, prevailing: str, calibration: str, grid: str | None = None,
                      extrapolation: str = "refuse", normalization: str = "white", knee: bool = False,
                      physics: str = "direct") -> ChartInputs:
    """
    The camera and the two Planckian temperatures (K) of a chart render, each parsed once here with its flag
    named in any error, and checked to give the camera light on the grid (``--grid`` parsed once too) before
    anything renders; ``scene``: the chart :func:`scene_from` loaded.
    """
    from ..model.illuminant import illuminant
    from .preflight import check_render_lights

    grid = grid_from(grid)
    cam = camera_from(camera, extrapolation, grid)
    temperatures = {}
    for name, spec in (("prevailing", prevailing), ("calibration", calibration)):
        light = flag(f"--{name}", illuminant, spec)
        if light.temperature is None:
            raise SkinrenderError(f"--{name}: rendering needs a Planckian illuminant (kelvin, A or H), got {light}",
                                  flag=f"--{name}")
        temperatures[name] = light.temperature
    check_render_lights(cam, temperatures, grid)  # each light seen by the camera, the one at fault named
    try:  # every patch's data covers the grid, before the render needs it
        scene.reflectances(grid)
    except SkinrenderError as error:  # the chart's own data: --extrapolation (CSV cameras') does not apply
        if error.cause != "coverage":
            raise error.reworded(f"SCENE: {error.message}", flag="SCENE") from None
        raise error.reworded(f"--grid: {error.message}", flag="--grid", cause=None,
                             hint="choose a --grid inside the chart's data") from None
    return ChartInputs(scene, cam, temperatures["prevailing"], temperatures["calibration"], grid,
                       normalization, bool(knee), str(physics).strip())


def chart_only(args: argparse.Namespace, skin: bool = True) -> None:
    """:func:`refuse_face_flags` of ``args``."""
    refuse_face_flags(args.physics, args.skin, args.size, skin)


def refuse_face_flags(physics: str, skin: str | None, size: str | None, skin_refused: bool = True) -> None:
    """The face-only flags refused on a chart: ``--physics`` but a chart's levels
    (:data:`~skinrender.rendering.chart_effects.CHART_REGISTRY`), ``--size`` and (``skin_refused``: but for
    ``detect``) ``--skin``."""
    from ..rendering.chart_effects import CHART_REGISTRY

    try:
        CHART_REGISTRY.names(physics)
        chart_level = True
    except SkinrenderError:
        chart_level = False
    given = [name for name, on in (("--physics", not chart_level), ("--skin", skin_refused and skin is not None),
                                   ("--size", size is not None)) if on]
    if given:
        levels = f" (a chart takes --physics {', '.join(CHART_REGISTRY.named)})" if "--physics" in given else ""
        raise SkinrenderError(f"{', '.join(given)}: {'goes' if len(given) == 1 else 'go'} with a face scene "
                              f"(e.g. 'face'), not a chart{levels}", flag=given[0])


def settings_fields(args: argparse.Namespace, settings: RenderSettings) -> dict:
    """:func:`settings_keywords` of ``settings`` and ``--sampler``."""
    return settings_keywords(settings, getattr(args, "sampler", None))


def settings_keywords(settings: RenderSettings, sampler: str | None) -> dict:
    """``settings``' fields as a request's keywords, the sampler ``None`` (the level's or the default) where
    ``sampler`` (``--sampler``) was not given."""
    import dataclasses

    fields = dataclasses.asdict(settings)
    if sampler is None:
        fields["sampler"] = None
    return fields


def sensor_flags(args: argparse.Namespace) -> dict:
    """``--imager``, ``--illuminance`` (lx) and ``--exposure`` (s or ``auto``) as a request's keywords (``None``
    where not given): the ``noise`` effect's options, checked where the request is built."""
    return {name: getattr(args, name, None) for name in ("imager", "illuminance", "exposure")}


def chart_flags(args) -> dict:
    """The flags of a chart render (``render``, ``validate``, ``detect``) by the keywords of
    :func:`chart_request_from` (absent ones their defaults)."""
    names = ("grid", "extrapolation", "normalization", "knee", "physics", "imager", "illuminance", "exposure",
             "sampler")
    moved = translate_of(getattr(args, "translate_mm", None))  # checked: (x, y, z) mm or None
    return {"camera": args.camera, "prevailing": args.prevailing, "calibration": args.calibration,
            **{name: getattr(args, name) for name in names if hasattr(args, name)},
            **({} if moved is None else {"translate_mm": moved})}


def chart_request_of(args: argparse.Namespace, scene: ChartScene, settings: RenderSettings, **changes):
    """:func:`chart_request_from` the flags of ``args``."""
    return chart_request_from(scene, settings, **chart_flags(args), **changes)


def chart_request_from(scene: ChartScene, settings: RenderSettings, *, camera: str, prevailing: str,
                       calibration: str, grid: str | None = None, extrapolation: str = "refuse",
                       normalization: str = "white", knee: bool = False, physics: str = "direct",
                       imager: str | None = None, illuminance=None, exposure=None, sampler: str | None = None,
                       **changes):
    """
    A chart command's :class:`~skinrender.rendering.request.ChartRequest` from its flags' values:
    :func:`chart_inputs_from` (each flag's object, checked against the others) made the request by the chart kind,
    as every front door builds it, with ``settings`` (the sampler left to the level where ``sampler``,
    ``--sampler``, was not given) and the sensor's flags; ``changes``: keywords replaced (``knee``).
    """
    from ..rendering.kinds import CHART

    inputs = chart_inputs_from(scene, camera, prevailing, calibration, grid, extrapolation, normalization, knee,
                               physics)
    keywords = {"normalization": inputs.normalization, "knee": inputs.knee, "grid": inputs.grid,
                "physics": inputs.physics, "imager": imager, "illuminance": illuminance, "exposure": exposure,
                **settings_keywords(settings, sampler), **changes}
    return flagged(REQUEST_FLAGS, CHART.request, inputs.scene, inputs.camera, inputs.prevailing, inputs.calibration,
                   **keywords)


def check_request_work(args, request, renders: int = 1, spp: int | None = None) -> None:
    """
    Refuse, naming ``--spp``, ``renders`` renders of ``request`` (at ``spp`` each where given) whose samples per
    pass exceed Mitsuba's 32-bit wavefront or whose estimate
    (:meth:`~skinrender.rendering.kinds.SceneKind.workload` on every core) exceeds ``--max-minutes`` (``args``:
    the parsed arguments or what a command made of them, its ``max_minutes`` in minutes; or the minutes); then what
    the level's effects prepare before any render (:meth:`~skinrender.rendering.physics.Level.prepare`: a
    subsurface chart's skin patches fitted, one that is not skin refused, naming it and why).
    """
    import dataclasses
    import os

    from ..rendering.kinds import scene_kind
    from ..rendering.renderer import SAMPLES_MAX
    from ..workload import check_work

    if spp is not None:
        request = dataclasses.replace(request, settings=request.settings.replace(spp=spp))
    spp, pixels = request.settings.spp, request.pixels
    if spp * pixels > SAMPLES_MAX:
        raise SkinrenderError(f"--spp: {spp} spp × {pixels} pixels = {spp * pixels:.3g} samples per pass, more than "
                              f"{SAMPLES_MAX:.3g} (Mitsuba's 32-bit wavefront); at most {SAMPLES_MAX // pixels} spp "
                              "for this scene", flag="--spp")
    seconds, what = scene_kind(request.scene).workload(request, renders, os.cpu_count() or 1)
    minutes = args if args is None or isinstance(args, (int, float)) else getattr(args, "max_minutes", None)
    check_work(seconds, "--spp", what, minutes, fewer="lower --spp")
    request.level.prepare(request)


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
