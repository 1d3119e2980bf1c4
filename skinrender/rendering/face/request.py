"""
A face render's request
=======================

:class:`FaceRequest`: what a face render is asked (the
:class:`~skinrender.rendering.request.Request` of every scene kind, with the
skin), and :func:`face_request`, its one builder from specs or objects, which
``skinrender.render`` / ``validate``, the command line's converters and the
pytest plugin all call. The scene it holds is the one rendered: resized to
``size``, its key light at ``prevailing`` and every light scaled to the
sensor's illuminance (the ``noise`` effect's
:func:`~skinrender.rendering.face.effects.noise.relit`).

Units: temperatures K, image sides pixels, illuminance lx, exposure s.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from ...errors import SkinrenderError
from ...model.camera import camera as camera_of
from ...model.imager import is_integer
from ...spectra import GRID_DEFAULT, WavelengthGrid
from ..physics import Level
from ..placement import translation
from ..request import Request, named, planckian, settings_for
from ..settings import RenderSettings
from .effects import PHYSICS_REGISTRY
from .reach import check_face_range
from .scene import FaceScene, load_face_scene, prevailing_name, skin_reflectance_of

__all__ = ["FaceRequest", "face_request", "SPP_FACE_DEFAULT"]

SPP_FACE_DEFAULT = 64
"""Samples per pixel of a face render unless given."""


@dataclass(frozen=True)
class FaceRequest(Request):
    """
    A face render's request: :class:`~skinrender.rendering.request.Request` with the ``skin`` spec (``SET:SAMPLE``,
    ``SET:#N``, ``skin-model:…``), checked against the grid; ``scene`` is the face as rendered.

    Examples
    --------
    >>> request = face_request("face", "gbell:9@450,540,610", 2856, 5900, physics="sheen", imager="sony-imx174",
    ...                        spp=4, size=16)
    >>> request.level.name, request.options["noise"].imager.name, request.pixels
    ('sheen+noise', 'sony-imx174', 256)
    """

    skin: str = ""
    bands: WavelengthGrid | None = None

    def _check(self) -> None:
        from ..renderer import SAMPLES_MAX

        if not isinstance(self.scene, FaceScene):
            raise SkinrenderError(f"scene must be a face scene (a FaceScene), got {self.scene!r}", role="scene")
        named("skin", skin_reflectance_of, self.skin, self.grid, "skin")
        self.level.lights(self.scene)  # a level's lights the scene lacks (mixed without a fill) refused
        check_face_range(self.scene, self.level, self.skin, self.grid)  # float32's useful range at the level
        spp, pixels = self.settings.spp, self.pixels
        if spp * pixels > SAMPLES_MAX:
            raise SkinrenderError(f"spp {spp} × {pixels} pixels = {spp * pixels:.3g} samples per pass, more than "
                                  f"{SAMPLES_MAX:.3g}; at most {SAMPLES_MAX // pixels} spp at this size", role="spp")

    @property
    def pixels(self) -> int:
        """The pixels of the face's image."""
        return int(self.scene.camera.width) * int(self.scene.camera.height)


def _sized(face: FaceScene, size) -> FaceScene:
    """The face at ``size`` pixels (``N`` or ``(width, height)``; ``None``: as it is)."""
    if size is None:
        return face
    width, height = (size, size) if not isinstance(size, (tuple, list)) else (tuple(size) + (None, None))[:2]
    if not all(is_integer(v) and v >= 1 for v in (width, height)):
        raise SkinrenderError(f"size must be a positive number of pixels (or two), got {size!r}", role="size")
    return face.resized(int(width), int(height))


def face_request(scene="face", camera=None, prevailing=None, calibration=None, *, skin: str | None = None,
                 physics="direct", size=None, settings: RenderSettings | None = None,
                 grid: WavelengthGrid = GRID_DEFAULT, imager=None, illuminance=None, exposure=None,
                 spp: int | None = None, bands=None, translate_mm=None, **fields) -> FaceRequest:
    """
    A face's :class:`FaceRequest`, each argument parsed once and checked, a refusal naming it (its ``role``).

    Parameters
    ----------
    scene, camera
        A face (``face``, a TOML path or a :class:`~skinrender.rendering.face.scene.FaceScene`) and a camera.
    prevailing
        The key light's temperature (kelvin, ``A``, ``H``); ``None`` keeps the scene's (in a scene without a key
        light, the environment's).
    calibration
        The white balance's Planckian; ``None``: the prevailing light.
    skin
        The skin spec; ``None`` keeps the scene's.
    physics
        ``direct`` or effects of :data:`~skinrender.rendering.face.effects.PHYSICS` joined by ``+``, or a level.
    size
        Image side in pixels (``N`` or ``(width, height)``); ``None`` keeps the scene's.
    settings, spp, **fields
        A :class:`~skinrender.rendering.settings.RenderSettings`, or its fields (``spp`` default
        :data:`SPP_FACE_DEFAULT`, ``seed``, ``sampler``, ``variant``, ``channels``).
    imager, illuminance, exposure
        The ``noise`` effect's options (:class:`~skinrender.rendering.sensor.NoiseOptions`); an ``imager`` adds
        ``noise`` to the level; ``illuminance`` (lx) and ``exposure`` (s or ``auto``) go with it.
    bands
        A spectral render's band grid (``START:END:STEP`` nm or a grid, :mod:`~skinrender.rendering.bands`):
        then no camera and no calibration (``None``; applied afterwards, the sensor of ``noise`` per camera).
    translate_mm
        ``(x, y, z)`` mm (or ``X,Y,Z`` text): the whole scene moved that far from the origin
        (:meth:`~skinrender.rendering.face.scene.FaceScene.translated`); ``None``: where it is. Any face request
        beyond float32's useful range at its level is refused, naming the scene
        (:func:`~skinrender.rendering.face.reach.check_face_range`).
    """
    face = named("scene", load_face_scene, scene)
    if translate_mm is not None:
        face = face.translated(translation(translate_mm, "translate_mm"))
    if bands is not None:
        from ..bands import parse_bands
        from ..request import spectral_only

        bands = parse_bands(bands)
        spectral_only(camera, calibration)
        cam = None
    elif camera is None:
        raise SkinrenderError("camera: name the camera (a Camera or a spec such as gbell:9@450,540,610)",
                              role="camera")
    else:
        cam = named("camera", camera_of, camera)
    level = PHYSICS_REGISTRY.level(physics if isinstance(physics, Level) else str(physics).strip())
    level, options = PHYSICS_REGISTRY.with_options(level, {"imager": imager, "illuminance": illuminance,
                                                           "exposure": exposure})
    if settings is None and spp is None and fields.get("quality") is None:
        spp = SPP_FACE_DEFAULT
    settings = settings_for(level, settings, spp=spp, **fields)
    face = level.scene(_sized(face, size), options)  # e.g. noise: the lights at its illuminance
    name = prevailing_name(face)
    light = getattr(face, name)
    if prevailing is not None and light is not None:
        light = replace(light, temperature=planckian(prevailing, "prevailing"))
        face = replace(face, **{name: light})
    if light is None:
        raise SkinrenderError(f"scene: face scene {face.source or face.name} has no key light and no environment",
                              role="scene")
    p = light.temperature
    c = p if calibration is None else planckian(calibration, "calibration")
    skin = face.skin if skin is None else str(skin).strip()
    return FaceRequest(face, cam, p, c, level, settings, grid, options, skin, bands)
