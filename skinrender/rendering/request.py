"""
Render requests
===============

What a render is asked, as one frozen object, checked once where it is made:
the scene (parsed), the :class:`~skinrender.model.camera.Camera`, the lights
(K), the grid, the :class:`~skinrender.rendering.physics.Level`, the
:class:`~skinrender.rendering.settings.RenderSettings` and each effect's
options by effect name (the sensor's:
:class:`~skinrender.rendering.sensor.NoiseOptions`). Every front door builds
one the same way — the command line's converters, ``skinrender.render`` /
``skinrender.validate`` and the pytest plugin, through its scene kind's
``request`` (:mod:`skinrender.rendering.kinds`) — and everything below takes
the request: a spec (a physics level, a camera, a scene) is parsed there
once, and every bound (seed, spp, lights, options) is checked there, before
any work.

-   :class:`Request`: what every request holds; :class:`ChartRequest` (with
    Eq. 4's normalisation, knee and the emitter) and
    :class:`~skinrender.rendering.face.request.FaceRequest` (with the skin).
-   :func:`chart_request`: a chart's request from specs or objects.
-   :func:`planckian`: a Planckian light spec in K.

Units: temperatures K, wavelengths nm, illuminance lx, exposure s.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

from ..errors import SkinrenderError, flag_of
from ..methods import validate_method
from ..model.camera import Camera, camera as camera_of
from ..model.illuminant import illuminant
from ..model.response import NORMALISATIONS, uses_whites
from ..spectra import GRID_DEFAULT, WavelengthGrid, as_grid
from .physics import Level
from .settings import RenderSettings

__all__ = ["ILLUMINANCE_DEFAULT", "Request", "ChartRequest", "chart_request", "planckian", "named",
           "settings_for", "spectral_only"]

ILLUMINANCE_DEFAULT = 500.0
"""A chart's illuminance through an imager unless one is given, lx (an office)."""


def named(role: str, function, *args, **kwargs):
    """``function(*args, **kwargs)``, its :class:`SkinrenderError` given the ``role`` (the argument at fault; a
    flag such as ``--prevailing`` sets the error's ``flag`` too) and worded with it where it has neither
    (``camera: unknown camera 'x'``)."""
    try:
        return function(*args, **kwargs)
    except SkinrenderError as error:
        if error.role is not None or error.flag is not None:
            raise
        words = error.message if error.message.startswith(role) else f"{role}: {error.message}"
        raise error.reworded(words, role=role.lstrip("-"), flag=flag_of(role)) from None


def _light(spec):
    """:func:`~skinrender.model.illuminant.illuminant` of ``spec``, a refusal left without a role: its argument is
    the caller's (``prevailing``, ``calibration``), which :func:`named` gives it."""
    try:
        return illuminant(spec)
    except SkinrenderError as error:
        raise (error.reworded(role=None) if error.role == "illuminant" else error) from None


def planckian(spec, name: str) -> float:
    """
    The temperature, K, of a Planckian light spec (kelvin, ``A`` or ``H``); a one-line error naming ``name`` (its
    ``role``) for any other light.

    >>> planckian("A", "prevailing")
    2856.0
    """
    if isinstance(spec, bool):
        raise SkinrenderError(f"{name}: a Planckian light (kelvin, A or H), got {spec!r}", role=name.lstrip("-"),
                              flag=flag_of(name))
    light = named(name, _light, spec)
    if light.temperature is None:
        raise SkinrenderError(f"{name}: rendering needs a Planckian illuminant (kelvin, A or H), got {spec!r}",
                              role=name.lstrip("-"), flag=flag_of(name))
    return float(light.temperature)


def settings_for(level: Level, settings: RenderSettings | None = None, **fields) -> RenderSettings:
    """
    The render settings of a request at ``level``: ``settings`` (the defaults where ``None``) with ``fields``
    (``spp``, ``seed``, ``sampler``, ``variant``, ``channels``; ``None`` values not given); the level's own sampler
    (:attr:`~skinrender.rendering.physics.Level.sampler`: a subsurface-volume chart's) where neither names one.
    ``quality`` (a :data:`~skinrender.rendering.settings.QUALITY_PRESETS` name, as ``--quality``) stands for
    ``settings``: its spp and sampler, the other fields given overriding them.
    """
    fields = {key: value for key, value in fields.items() if value is not None}
    quality = fields.pop("quality", None)
    if quality is not None:
        if settings is not None:
            raise SkinrenderError("quality names preset settings: give quality or settings, not both", role="quality")
        settings = RenderSettings.preset(quality)
    if settings is None and "sampler" not in fields and level.sampler is not None:
        fields["sampler"] = level.sampler
    return RenderSettings.of(settings, **fields)


@dataclass(frozen=True)
class Request:
    """
    What every render request holds, checked once (``__post_init__``).

    Attributes
    ----------
    scene
        The parsed scene (a :class:`~skinrender.rendering.scene.ChartScene`, a
        :class:`~skinrender.rendering.face.scene.FaceScene`).
    camera
        A :class:`~skinrender.model.camera.Camera` (a CSV's extrapolation inside it).
    prevailing, calibration
        The Planckian lights, K.
    level
        The :class:`~skinrender.rendering.physics.Level` of physics, of the scene kind's registry.
    settings
        How it samples: spp, seed (in [0, :data:`~skinrender.rendering.settings.SEED_MAX`]), sampler, variant,
        channels.
    grid
        The wavelength grid, nm.
    options
        Effect name → its options (:attr:`~skinrender.rendering.physics.Effect.options`: ``noise``'s
        :class:`~skinrender.rendering.sensor.NoiseOptions`), one for every effect of the level that has
        options (the defaults filled in); read-only.

    Raises
    ------
    SkinrenderError
        A field of the wrong type or out of its bounds, or what an effect of the level refuses
        (:meth:`~skinrender.rendering.physics.Level.refuse`); its ``role`` the argument at fault.
    """

    scene: object
    camera: Camera
    prevailing: float
    calibration: float
    level: Level
    settings: RenderSettings = field(default_factory=RenderSettings)
    grid: WavelengthGrid = GRID_DEFAULT
    options: Mapping[str, object] = field(default_factory=dict)

    def __post_init__(self) -> None:
        object.__setattr__(self, "grid", as_grid(self.grid))  # its text START:END:STEP (nm) too, as --grid
        self._check_bands()
        for name, kind, what in (("camera", Camera, "a Camera (skinrender.camera(spec) makes one)"),
                                 ("level", Level, "a Level (of the scene kind's registry of effects)"),
                                 ("settings", RenderSettings, "a RenderSettings"),
                                 ("grid", WavelengthGrid, "a WavelengthGrid")):
            if not isinstance(getattr(self, name), kind) and not (name == "camera" and self.spectral):
                raise SkinrenderError(f"{name} must be {what}, got {getattr(self, name)!r}", role=name)
        for name in ("prevailing", "calibration"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not (math.isfinite(value)
                                                                                      and value > 0):
                raise SkinrenderError(f"{name} must be a temperature, a finite number of kelvin > 0, got {value!r}",
                                      role=name)
            object.__setattr__(self, name, float(value))
        self._check_lights()
        object.__setattr__(self, "options", MappingProxyType(self.level.default_options(self.options)))
        self._check()
        self.level.refuse(self)

    def _check_lights(self) -> None:
        """
        Each light gives the camera light on the grid, the one at fault named by its role (``calibration
        illuminant 1K gives no light …``, ``role`` ``calibration``): a chart's calibration light of 1 K had been
        refused only after the prevailing render ("the Planck emitter is zero", no argument named), a face's after
        its white references (~9 s, then a NaN).
        """
        from ..model.illuminant import illuminant
        from ..model.response import check_light, spds_on

        if self.camera is None:  # a spectral render: no camera yet (each is checked where it sees the render)
            return
        for role in ("prevailing", "calibration"):
            item = illuminant(getattr(self, role))
            check_light(self.camera, [item], spds_on([item], self.grid), self.grid, f"{role} illuminant")

    def _check(self) -> None:
        """The checks of a scene kind's request (its own fields)."""

    @property
    def spectral(self) -> bool:
        """Whether the request renders the bands of :mod:`~skinrender.rendering.bands` (its subclass's ``bands``
        field) rather than a camera's channels: a spectral render, whose camera and calibration are applied
        afterwards (``camera`` ``None``, ``calibration`` the prevailing light)."""
        return getattr(self, "bands", None) is not None

    def _check_bands(self) -> None:
        """A spectral request takes no camera, and its bands lie inside its grid (the range its lights and spectra
        are tabulated over)."""
        bands = getattr(self, "bands", None)
        if bands is None:
            return
        from .bands import check_bands

        if not isinstance(bands, WavelengthGrid):
            raise SkinrenderError(f"bands must be a WavelengthGrid, got {bands!r}", role="bands")
        if self.camera is not None:
            raise SkinrenderError("camera: a spectral render (bands) takes no camera: see it through one afterwards, "
                                  "SpectralImage.through(camera, calibration=K)", role="camera")
        check_bands(bands, self.grid)

    @property
    def sensor(self):
        """The image sensor's options where the level records through one (its effect's options are a
        :class:`~skinrender.rendering.sensor.NoiseOptions`), else ``None``."""
        from .sensor import NoiseOptions

        return next((options for options in self.options.values() if isinstance(options, NoiseOptions)), None)

    @property
    def pixels(self) -> int:
        """The pixels of the scene's image."""
        raise NotImplementedError


@dataclass(frozen=True)
class ChartRequest(Request):
    """
    A chart render's request: :class:`Request` with Eq. 4's ``normalization`` (one of
    :data:`~skinrender.model.response.NORMALISATIONS`) and ``knee`` (Eq. 10), and the ``emitter``
    (:data:`~skinrender.rendering.renderer.EMITTERS`, or ``blackbody``).

    Examples
    --------
    >>> request = chart_request("macbeth", "gbell:9@450,540,610", "A", 5900, spp=16, imager="sony-imx174")
    >>> request.level.name, request.options["noise"].imager.name, request.pixels
    ('noise', 'sony-imx174', 8036)
    """

    normalization: str = "white"
    knee: bool = False
    emitter: str = "tabulated"
    bands: WavelengthGrid | None = None

    def _check(self) -> None:
        from .renderer import EMITTERS
        from .scene import ChartScene

        if not isinstance(self.scene, ChartScene):
            raise SkinrenderError(f"scene must be a chart scene (a ChartScene), got {self.scene!r}", role="scene")
        validate_method(self.normalization, NORMALISATIONS, "normalization", role="normalization")
        if not isinstance(self.knee, bool):
            raise SkinrenderError(f"knee must be True or False, got {self.knee!r}", role="knee")
        validate_method(self.emitter, EMITTERS, "emitter", role="emitter")

    @property
    def pixels(self) -> int:
        """The pixels of the chart's image."""
        width, height = self.scene.size
        return int(width) * int(height)


def chart_request(scene, camera, prevailing, calibration, *, normalization: str = "white", knee: bool = False,
                  settings: RenderSettings | None = None, grid: WavelengthGrid = GRID_DEFAULT,
                  emitter: str = "tabulated", physics="direct", imager=None, illuminance=None, exposure=None,
                  bands=None, translate_mm=None, **fields) -> ChartRequest:
    """
    A chart's :class:`ChartRequest`, each argument parsed once and checked, a refusal naming it (its ``role``).

    Parameters
    ----------
    scene, camera
        A chart (bundled name, TOML path or :class:`~skinrender.rendering.scene.ChartScene`) and a camera (spec or
        :class:`~skinrender.model.camera.Camera`).
    prevailing, calibration
        Planckian lights: kelvin, ``A`` (2856 K) or ``H`` (2300 K).
    normalization, knee, grid, emitter
        Eq. 4's normalisation and knee (Eq. 10), the grid (nm), the emitter.
    settings, **fields
        A :class:`~skinrender.rendering.settings.RenderSettings`, or its fields one by one (``spp``, ``seed``,
        ``sampler``, ``variant``, ``channels``); at ``subsurface-volume`` the sampler is that level's unless named.
    physics
        ``direct``, ``subsurface`` or ``subsurface-volume`` (:data:`~skinrender.rendering.chart_effects.CHART_REGISTRY`),
        or a level.
    imager, illuminance, exposure
        The sensor's options (:class:`~skinrender.rendering.sensor.NoiseOptions`): an ``imager`` records the
        chart through an image sensor at ``illuminance`` lx (default :data:`ILLUMINANCE_DEFAULT`) and
        ``exposure`` (s or ``auto``); without an imager the other two are refused.
    bands
        A spectral render's band grid (``START:END:STEP`` nm or a grid, :mod:`~skinrender.rendering.bands`):
        then no camera and no calibration (``None``; applied afterwards), nor Eq. 4's normalisation or knee.
    translate_mm
        The ``subsurface`` level's option (:class:`~skinrender.rendering.subsurface_chart.SlabOptions`): every
        skin patch's scene moved ``(x, y, z)`` mm from the origin; refused at any other level (a Lambertian chart
        is laid out in pixels).
    """
    from .chart_effects import CHART_REGISTRY
    from .scene import load_chart_scene

    chart = named("scene", load_chart_scene, scene)
    if bands is not None:
        from .bands import parse_bands

        bands = parse_bands(bands)
        spectral_only(camera, calibration, not uses_whites(normalization) and "normalization", knee and "knee")
        cam, p = None, planckian(prevailing, "prevailing")
        c = p
    else:
        cam = named("camera", camera_of, camera)
        p, c = planckian(prevailing, "prevailing"), planckian(calibration, "calibration")
    level = CHART_REGISTRY.level(physics if isinstance(physics, Level) else str(physics).strip())
    level, options = CHART_REGISTRY.with_options(level, {"imager": imager, "illuminance": illuminance,
                                                         "exposure": exposure, "translate_mm": translate_mm})
    return ChartRequest(chart, cam, p, c, level, settings_for(level, settings, **fields), grid, options,
                        normalization, knee, emitter, bands)


def spectral_only(camera, calibration, *others) -> None:
    """Refuse what a spectral request (bands) does not take: a camera, a calibration light, and any of
    ``others`` (the names of options given that go with a camera's render, ``False`` where not given)."""
    for name, value in (("camera", camera), ("calibration", calibration)):
        if value is not None:
            raise SkinrenderError(f"{name}: a spectral render takes no {name}; see it through one afterwards: "
                                  "SpectralImage.through(camera, calibration=K)", role=name)
    for name in others:
        if name:
            raise SkinrenderError(f"{name}: goes with a camera's render; a spectral render applies it in "
                                  "through()", role=name)
