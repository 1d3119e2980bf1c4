"""
What a face command was asked, as objects
=========================================

The converters of a face's flags (``render``, ``validate``, ``detect`` on a face scene, ``ladder``,
``face-sweep``), each taking the flags' values (never the parsed arguments) and naming the flag at fault in
every refusal:

-   :func:`face_flags_from`: what only the command line checks (camera, Planckian lights the camera sees, the
    white normalisation, the default grid, a level named, ``--size``); :func:`face_request_from`: the
    :class:`~skinrender.rendering.face.request.FaceRequest`, built by the face kind as every front door builds it.
-   :func:`planckian_flag`, :func:`check_lights_seen`: a light's temperature (K) and the camera's view of it.
-   :func:`levels_of`: ``--levels`` as :class:`~skinrender.rendering.physics.Level` objects;
    :func:`noise_sensor_from`: the sensor's options of a study over levels; :func:`skins_from`: a study's
    ``--skin`` specs, each checked; :func:`refuse_repeated`: a flag's items each named once.
-   :func:`level_names`, :func:`face_pixels`, :data:`SIZE_MAX`.

Units: temperatures K, illuminance lx, sizes pixels.
"""

from __future__ import annotations

from ..errors import SkinrenderError
from .common import camera_from, flag, flagged, integer_in, positive_number

__all__ = ["SIZE_MAX", "level_names", "planckian_flag", "check_lights_seen", "face_flags_from", "face_request_from",
           "face_pixels", "levels_of", "noise_sensor_from", "skins_from", "refuse_repeated"]

SIZE_MAX = 2000
"""Largest image side, pixels (the chart scenes' 4 000 000-pixel cap)."""

GRID_FACE = "400:700:1"
"""The one grid a face renders on, as ``--grid`` spells it."""


def level_names(short: bool = False) -> str:
    """The registered levels of physics, comma-separated (``short``: as words for prose, ``mixed light``)."""
    from ..rendering.face.effects import PHYSICS_EFFECTS

    return ", ".join(effect.short or name if short else name for name, effect in PHYSICS_EFFECTS.items())


def planckian_flag(spec: str, name: str) -> float:
    """The temperature, K, of the Planckian light ``spec`` given to flag ``name``; a one-line error otherwise."""
    from ..rendering.face import planckian_temperature

    return flag(name, planckian_temperature, spec, name)


def check_lights_seen(cam, temperatures: dict) -> None:
    """Each light (flag name → K) gives the camera light on the grid (else a one-line error naming the flag and
    the light by its role: :func:`~skinrender.cli.preflight.check_render_lights`)."""
    from .preflight import check_render_lights

    check_render_lights(cam, temperatures)


def face_flags_from(camera: str | None, prevailing: str, calibration: str | None, normalization: str = "white",
                    grid: str | None = GRID_FACE, physics: str | None = None, size: str | None = None,
                    spectral: bool = False) -> tuple:
    """
    What only the command line checks of a face render's flags, each refusal naming its flag: ``--camera`` (with
    its curves on the default grid), ``--prevailing`` and ``--calibration`` (Planckian, K; the camera sees each),
    ``--normalization`` (one whose factor is WP: a face is balanced with it), ``--grid`` (the default: a face
    renders on 400:700:1 nm), ``--physics`` (not empty) and ``--size`` (an integer in [1, :data:`SIZE_MAX`]);
    ``spectral``: a spectral render's, with no camera and no calibration (applied afterwards). Returns
    ``(camera or None, {prevailing, calibration} K or None, size px or None)``; the rest is the request's
    (:func:`face_request_from`).
    """
    from ..model.response import uses_whites

    cam = None if spectral else camera_from(camera)
    temperatures = {"prevailing": planckian_flag(prevailing, "--prevailing"),
                    "calibration": None if spectral else planckian_flag(calibration, "--calibration")}
    if cam is not None:
        check_lights_seen(cam, temperatures)
    if not uses_whites(normalization):
        raise SkinrenderError(f"--normalization: a face is balanced with WP (white) only, got {normalization!r}",
                              flag="--normalization")
    if str(GRID_FACE if grid is None else grid).strip() != GRID_FACE:
        raise SkinrenderError(f"--grid: a face renders on 400:700:1 nm, got {grid!r}", flag="--grid")
    if physics is not None and not str(physics).strip():
        raise SkinrenderError(f"--physics: name a level ({level_names()}; '+' combines them), got ''", flag="--physics")
    return cam, temperatures, None if size is None else integer_in(size, "--size", 1, SIZE_MAX)


def face_request_from(scene, settings, *, camera: str | None, prevailing: str, calibration: str | None,
                      normalization: str = "white", grid: str | None = GRID_FACE, physics: str | None = None,
                      size: str | None = None, skin: str | None = None, imager: str | None = None,
                      illuminance=None, exposure=None, sampler: str | None = None, **changes):
    """
    A face command's :class:`~skinrender.rendering.face.request.FaceRequest` from its flags' values (absent ones
    their defaults), as every front door builds it (:meth:`~skinrender.rendering.kinds.FaceKind.request`), each
    refusal naming its flag; ``settings``: the render settings (the sampler left to the level where ``sampler``,
    ``--sampler``, was not given); ``changes``: keywords replaced (``spp``: a validation's per replicate). What only
    the command line has is checked first (:func:`face_flags_from`; a spectral render's, ``bands`` among the
    changes, without a camera and a calibration).
    """
    from ..rendering.kinds import FACE
    from .inputs import REQUEST_FLAGS, settings_keywords

    cam, temperatures, size = face_flags_from(camera, prevailing, calibration, normalization, grid, physics, size,
                                              spectral=changes.get("bands") is not None)
    keywords = {"skin": skin, "physics": physics or "direct", "size": size, "imager": imager,
                "illuminance": illuminance, "exposure": exposure, **settings_keywords(settings, sampler),
                **changes}
    return flagged(REQUEST_FLAGS, FACE.request, scene, cam, temperatures["prevailing"], temperatures["calibration"],
                   **keywords)


def face_pixels(scene, size: int | None) -> int:
    """The pixels of a face render: ``size`` squared where given, else the scene camera's."""
    return size * size if size is not None else scene.camera.width * scene.camera.height


def levels_of(text: str) -> list:
    """
    ``--levels``: comma-separated levels of physics, none empty and none twice (``a+b`` and ``b+a`` are one
    level), each parsed once into its :class:`~skinrender.rendering.physics.Level`; a one-line error naming the
    flag otherwise.
    """
    from ..rendering.face.effects import PHYSICS_REGISTRY

    specs = [level.strip() for level in str(text).split(",")]
    if not any(specs) or not all(specs):
        raise SkinrenderError(f"--levels: comma-separated levels of physics, none empty, got {text!r}", flag="--levels")
    levels = [flag("--levels", PHYSICS_REGISTRY.level, spec) for spec in specs]
    if len({level.name for level in levels}) < len(levels):
        raise SkinrenderError(f"--levels: a level is named twice in {text!r}; name each once", flag="--levels")
    return levels


def noise_sensor_from(imager: str | None, illuminance, levels: list) -> tuple:
    """
    The sensor's options of a study over ``levels`` (:class:`~skinrender.rendering.physics.Level` objects):
    ``(imager, lux)``, ``--imager`` loaded once (``None``: the effect's default) and ``--illuminance`` in lx
    (``None``: the scene's), each checked as a request checks it; either is refused where no level has an effect
    that takes it (nothing would see it).
    """
    from ..rendering.face.effects import PHYSICS_REGISTRY
    from ..rendering.sensor import NoiseOptions

    options = flagged({"imager": "--imager", "illuminance": "--illuminance"}, NoiseOptions, imager,
                      None if illuminance is None else positive_number(illuminance, "--illuminance", "lx"))
    for name, given in (("imager", imager), ("illuminance", illuminance)):
        if given is not None and not any(PHYSICS_REGISTRY.options_for(level, {name: True}) for level in levels):
            raise SkinrenderError(f"--{name} is the noise level's: add a level with noise to --levels "
                                  f"(e.g. noise or interreflection+noise), got "
                                  f"{','.join(level.name for level in levels)!r}", flag=f"--{name}")
    return options.imager, options.illuminance


def refuse_repeated(name: str, items: list[str]) -> None:
    """Refuse a study that names one camera, light pair or skin twice (it would render it twice), naming ``name``."""
    twice = sorted({item for item in items if items.count(item) > 1})
    if twice:
        raise SkinrenderError(f"{name}: each once, got {', '.join(twice)} more than once", flag=name)


def skins_from(specs) -> list[str]:
    """A study's ``--skin`` specs, each stripped, none empty, parsed on the default grid and named once; a one-line
    error naming ``--skin`` otherwise."""
    from ..rendering.face.scene import skin_reflectance_of
    from ..spectra import GRID_DEFAULT

    skins = [str(spec).strip() for spec in specs]
    for skin in skins:
        if not skin:
            raise SkinrenderError("--skin: expected a skin spec, got an empty one", flag="--skin")
        skin_reflectance_of(skin, GRID_DEFAULT, "--skin")
    refuse_repeated("--skin", skins)
    return skins
