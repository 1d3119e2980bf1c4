"""
Rendering faces
===============

A face scene (:mod:`skinrender.rendering.face.scene`) rendered through a
camera's three channels at a level of physics
(:mod:`skinrender.rendering.face.effects`), white balanced as Eq. 4 does,
with a label image from the geometry.

-   :func:`render_face`, :class:`FaceRendering`: one render (``.save()``,
    ``.figure()``); :func:`render_face_request`: the render of a
    :class:`~skinrender.rendering.face.request.FaceRequest`.
-   :func:`white_references`: the channel responses to a white under the
    prevailing and the calibration light.
-   :func:`balanced_frame`: a radiance as one frame of a level (its sensor's, if it has one), balanced.
-   :func:`write_face_exr`: the float32 EXR, with a ``label`` channel.
-   :func:`planckian_temperature`: a Planckian light spec in K.

The white balance
-----------------
The chart renderer renders its white reference; a face scene has none in
view, so the whites are computed, as the renderer integrates (the curves
linearly interpolated, the Planckian tabulated every 0.1 nm, trapezoid):

-   ``white_p``: a perfect Lambertian white at the camera target facing the
    key light (radiance ``E_key / π``), or, in a scene without a key light,
    open to the whole environment (radiance ``E_env / π``);
-   ``white_c``: the calibration Planckian (its scale cancels in Eq. 4).

The image is ``gain(white_p, white_c) · radiance``
(:func:`skinrender.model.response.gain`, WP of Eq. 8): a surface facing
the key light at the target, lit by it alone, reads exactly as Eq. 4 gives
its reflectance, and a white there reads 255 at p = c. An effect acting
after the render (``noise``: :mod:`skinrender.rendering.face.effects.noise`)
replaces the radiance and the whites first (DN of one frame, and the whites
in DN at the same exposure).

Units: radiance images in W·m⁻²·sr⁻¹ times the sensitivity's unit (the
specfilm's ``∫ L x_k dλ``); balanced images in output units; illuminance lx.
"""

from __future__ import annotations

import functools
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...constants import CONSTANT_OUTPUT_SCALE
from ...errors import SkinrenderError
from ...files import Output, write_outputs
from ...hints import NDArrayFloat
from ...model.camera import Camera
from ...model.response import gain
from ...spectra import GRID_DEFAULT, WavelengthGrid, planck
from ..exr import camera_attributes, write_exr, write_preview
from ..outputs import draw_figure, save_result
from ..renderer import CameraKey, channel_names
from ..skin_integrator import PLUGIN, register
from ..variants import mitsuba
from .document import channel_groups, channel_integral, face_document, light_irradiance
from .effects import Frame, Level
from .labels import label_names, render_labels, shape_labels
from .scene import MESH_HEAD, FaceScene, prevailing_name

__all__ = ["FaceRendering", "planckian_temperature", "white_references", "render_face", "render_face_request",
           "finish_face", "balanced_frame", "face_exr", "write_face_exr", "DocumentKey", "load_document",
           "loaded_document"]

LOADED_KEPT = 6
"""Face documents kept loaded in Mitsuba (the least recently used goes first)."""


@dataclass(frozen=True)
class FaceRendering:
    """
    One face render.

    Attributes
    ----------
    image
        ``(height, width, 3)`` float32, output units (Eq. 4).
    radiance
        ``(height, width, 3)`` float64, the specfilm's ``∫ L x_k dλ``
        (W·m⁻²·sr⁻¹ times the sensitivity's unit), before any sensor.
    labels
        ``(height, width)`` int32: 0 background, 1 skin, 2… the props.
    label_names
        ``{name: label}``.
    physics
        The level rendered (``direct`` or effects joined by ``+``).
    skin
        The skin spec.
    spp
        Samples per pixel used (the sampler may round the request up).
    seconds
        Wall time of the whole render (scene loading, kernels, labels), s.
    white_prevailing, white_calibration, gain
        The white references and the Eq. 4 gain applied, per channel.
    info
        ``lights`` (``{name: {temperature_K, illuminance_lx}}``), and with
        ``noise`` ``imager``, ``exposure_s``, ``clipping`` (pixels at the full well and the ADC range, per
        channel) and ``notes`` (a capped ``auto`` exposure, clipped pixels).
    """

    scene: FaceScene
    camera: Camera
    physics: str
    skin: str
    prevailing: float
    calibration: float
    image: NDArrayFloat
    radiance: NDArrayFloat
    labels: NDArrayFloat
    label_names: dict
    spp: int
    spp_requested: int
    seed: int
    sampler: str
    variant: str
    seconds: float
    passes: int
    white_prevailing: NDArrayFloat
    white_calibration: NDArrayFloat
    gain: NDArrayFloat
    info: dict = field(default_factory=dict)

    @property
    def channels(self) -> tuple[str, str, str]:
        """EXR channel names of the image (as the chart renderer's)."""
        return channel_names(self.camera)

    def save(self, exr: str | Path, png: bool | str | Path = True, figure: str | Path | None = None) -> dict:
        """
        Write the render: the float32 EXR with its ``label`` channel (:func:`write_face_exr`), a PNG preview
        (``True``: beside the EXR; a path; ``False``: none) and a labelled figure (a PNG path; ``None``:
        none). Returns ``{"exr": path, "png": path or None, "figure": path or None}``.
        """
        return save_result(self, "face", exr, png, figure, lambda stream: write_exr(stream, *face_exr(self)))

    def figure(self, path: str | Path, **options) -> Path:
        """
        Draw the render with its labels outlined into a PNG at ``path`` and return it
        (:func:`skinrender.studies.labelled.face_figure`; ``mask``: detected pixels drawn over it,
        ``title``: the figure's title).
        """
        return draw_figure("face", self, path, **options)


def planckian_temperature(spec, name: str) -> float:
    """
    The temperature, K, of a Planckian light spec (kelvin, ``A`` or ``H``); a one-line error naming ``name``
    for any other light (:func:`skinrender.rendering.request.planckian`).

    >>> planckian_temperature("A", "prevailing")
    2856.0
    """
    from ..request import planckian

    return planckian(spec, name)


def white_references(scene: FaceScene, cam: Camera, calibration: float, grid: WavelengthGrid = GRID_DEFAULT,
                     bands=None) -> tuple[NDArrayFloat, NDArrayFloat]:
    """
    ``white_p`` and ``white_c`` (channels, specfilm units): a perfect white at
    the camera target facing the key light (or open to the environment in a
    scene without one), and under the calibration Planckian at ``calibration``
    K (its scale arbitrary: Eq. 4 cancels it). ``bands``: integrated as a spectral render sees the camera
    (:mod:`~skinrender.rendering.bands`: its curves at the bands, through the hats).
    """
    light = getattr(scene, prevailing_name(scene))
    if light is None:
        raise SkinrenderError(f"face scene {scene.source or scene.name} has no key light and no environment")
    lam, irradiance = light_irradiance(light, grid)
    if bands is None:
        integral = lambda spectrum: channel_integral(cam, grid, lam, spectrum)  # noqa: E731
    else:
        from ..bands import band_integrals, projection

        matrix = projection(cam, bands, grid)
        integral = lambda spectrum: band_integrals(lam, spectrum, bands) @ matrix.T  # noqa: E731
    white_p = integral(irradiance / np.pi)
    spd = planck(lam, calibration)
    white_c = integral(spd / np.max(spd))
    if np.any(white_c <= 0) or np.any(white_p <= 0):
        raise SkinrenderError(f"camera {cam.name}: a channel sees no light from the white reference")
    return white_p, white_c


@dataclass(frozen=True)
class DocumentKey:
    """
    A face's Mitsuba document as a cache key: what it depends on (the camera by its curves, or a spectral
    render's bands on its grid; the level by the effects that change the document, the lights by name); the level
    and the lights themselves ride along, outside the key.
    """

    scene: FaceScene
    camera: CameraKey | None
    grid: WavelengthGrid
    bands: WavelengthGrid | None
    effects: tuple[str, ...]
    skin: str | None
    group: tuple[int, ...]
    spp: int
    sampler: str
    variant: str
    light_key: tuple
    scale: float
    level: Level = field(compare=False, hash=False)
    lights: dict = field(compare=False, hash=False)


@functools.lru_cache(maxsize=LOADED_KEPT)
def load_document(document: DocumentKey):
    from ..bands import film_channels

    mi, scene = mitsuba(document.variant), document.scene
    channels = None if document.bands is None else film_channels(document.bands)
    cam = None if document.camera is None else document.camera.camera
    built = face_document(mi, scene, cam, document.grid, document.level, document.skin, document.group,
                          document.spp, 0, document.sampler, document.lights, document.scale, channels)
    if built["integrator"]["type"] == PLUGIN:
        register(mi)
    try:
        return mi.load_dict(built)
    except RuntimeError as error:  # the checks of load_face_scene passed, yet Mitsuba refused the user's mesh
        if scene.mesh == MESH_HEAD or Path(scene.mesh).name not in str(error):
            raise
        reason = " ".join(str(error).split())[-300:]
        raise SkinrenderError(f"{scene.source}: [mesh]: field 'file': Mitsuba could not load {scene.mesh}: "
                              f"{reason}") from None


def loaded_document(scene, cam, grid, level: Level, skin, group, spp, sampler, variant, lights, scale,
                    bands=None):
    """The face's document loaded into Mitsuba, reused across renders that share it (:data:`LOADED_KEPT` kept);
    ``bands``: a spectral render's film (``cam`` ``None``)."""
    key = None if cam is None else CameraKey.of(cam, grid)
    return load_document(DocumentKey(scene, key, grid, bands, level.document_key, skin, group, spp, sampler,
                                     variant, tuple(sorted(lights.items())), scale, level, lights))


def render_face(
    camera_: Camera | str,
    scene: FaceScene | str = "face",
    prevailing=None,
    calibration=None,
    skin: str | None = None,
    physics: str | Level = "direct",
    spp: int = 64,
    seed: int = 0,
    size: int | tuple[int, int] | None = None,
    sampler: str = "multijitter",
    variant: str | None = None,
    grid: WavelengthGrid = GRID_DEFAULT,
    channels: str = "auto",
    imager: str | None = None,
    exposure=None,
    illuminance: float | None = None,
    translate_mm=None,
) -> FaceRendering:
    """
    Render a face scene through a camera, white balanced to ``calibration``.

    Parameters
    ----------
    camera_
        Camera or spec.
    scene
        A bundled face scene name (``face``), a TOML path or a :class:`FaceScene`.
    prevailing
        The key light's temperature (kelvin, ``A``, ``H``); ``None`` keeps the
        scene's. In a scene without a key light it sets the environment's.
    calibration
        The white balance's Planckian; ``None``: the prevailing light.
    skin
        The skin spec (``SET:SAMPLE``, ``SET:#N``, ``skin-model:melanin=…``);
        ``None`` keeps the scene's.
    physics
        ``direct`` or effects of :data:`~skinrender.rendering.face.effects.PHYSICS` joined by ``+``
        (or a :class:`~skinrender.rendering.face.effects.Level`).
    spp, seed, sampler, variant, grid, channels
        As :func:`skinrender.rendering.renderer.render_raw`.
    size
        Image size in pixels (``N`` or ``(width, height)``); ``None`` keeps the scene's.
    imager, exposure, illuminance
        The ``noise`` effect's options (:class:`~skinrender.rendering.sensor.NoiseOptions`): the image sensor (a
        preset or TOML; default :data:`~skinrender.rendering.face.effects.noise.IMAGER_DEFAULT`; an imager adds
        ``noise`` to the level), ``auto`` or seconds, and the key light's illuminance at the target, lx (every
        light scaled with it; ``None`` keeps the scene's; Eq. 4 cancels a common scale of the lights). Without
        ``noise`` (or an imager) ``exposure`` and ``illuminance`` are refused.
    translate_mm
        ``(x, y, z)`` mm (or ``X,Y,Z`` text): the whole scene moved that far
        (:meth:`~skinrender.rendering.face.scene.FaceScene.translated`); ``None``: where it is. A scene beyond
        float32's useful range at its level is refused, naming it
        (:func:`~skinrender.rendering.face.reach.check_face_range`).

    Returns
    -------
    :class:`FaceRendering`

    Raises
    ------
    SkinrenderError
        A bad argument, named, before any render (:func:`~skinrender.rendering.face.request.face_request`).
    """

    from .request import face_request

    request = face_request(scene, camera_, prevailing, calibration, skin=skin, physics=physics, size=size, spp=spp,
                           seed=seed, sampler=sampler, variant=variant, grid=grid, channels=channels, imager=imager,
                           exposure=exposure, illuminance=illuminance, translate_mm=translate_mm)
    return render_face_request(request)


def render_face_request(request, seed: int | None = None) -> FaceRendering:
    """
    Render a :class:`~skinrender.rendering.face.request.FaceRequest` (module docstring): its scene at its level,
    through its camera, white balanced to its calibration light. ``seed``: a seed derived from the request's
    (a replicate's, :func:`~skinrender.rendering.settings.seed_at`; any 32-bit integer), else the request's.
    """
    start = time.perf_counter()
    face, cam, grid, level, settings = request.scene, request.camera, request.grid, request.level, request.settings
    seed = settings.seed if seed is None else int(seed)
    if not 0 <= seed < 2**32:
        raise SkinrenderError(f"seed must be a 32-bit integer, got {seed}", role="seed")
    spp, sampler, skin = settings.spp, settings.sampler, request.skin
    c = request.calibration
    lights = level.lights(face)
    white_p, white_c = white_references(face, cam, c, grid)
    scale = max(float(np.max(light_irradiance(light, grid)[1])) for light in lights.values())
    variant = level.choose_variant(settings.variant)
    mi = mitsuba(variant)
    groups = channel_groups(cam, grid, settings.channels)
    width, height = face.camera.width, face.camera.height
    radiance = np.zeros((height, width, 3))
    spp_used, first = int(spp), None
    for group in groups:
        loaded = loaded_document(face, cam, grid, level, skin, group, int(spp), sampler, variant, lights, scale)
        first = first or loaded
        spp_used = int(loaded.sensors()[0].sampler().sample_count())
        values = np.array(mi.render(loaded, seed=seed), dtype=np.float64)
        radiance[:, :, list(group)] = values.reshape(height, width, len(group)) * scale
    labels = render_labels(mi, first, width, height, shape_labels(face))
    return finish_face(request, cam, c, radiance, white_p, white_c, labels, spp_used, len(groups), seed, variant,
                       start)


def finish_face(request, cam: Camera, calibration: float, radiance: NDArrayFloat, white_p: NDArrayFloat,
                white_c: NDArrayFloat, labels: NDArrayFloat, spp_used: int, passes: int, seed: int, variant: str,
                start: float, info: dict | None = None) -> FaceRendering:
    """
    A face render of ``request`` from its ``radiance`` through ``cam`` (``(height, width, 3)``, specfilm units)
    and the whites: the level's post-processing (``noise``: one frame through the sensor, seeded from ``seed``),
    Eq. 4's gain (WP, Eq. 8) to ``calibration`` (K), the :class:`FaceRendering` (``start``: when the work began,
    ``time.perf_counter()``; ``info``: keys added to its ``info``). A spectral render's projection ends here too.
    """
    face, level, grid = request.scene, request.level, request.grid
    lights = level.lights(face)
    extra = {"lights": {k: {"temperature_K": v.temperature, "illuminance_lx": v.illuminance}
                        for k, v in lights.items()}, **(info or {})}
    after = level.setup(face, cam, grid, lights, calibration=calibration, seed=seed, options=request.options)
    frame = level.post(Frame(radiance, white_p, white_c, extra), after)  # e.g. noise: one frame through a sensor
    applied = gain(frame.white_prevailing, frame.white_calibration, scale=CONSTANT_OUTPUT_SCALE)
    image = applied * frame.signal
    return FaceRendering(face, cam, level.name, request.skin, float(request.prevailing), float(calibration),
                         image.astype(np.float32), radiance, labels, label_names(face), int(spp_used),
                         request.settings.spp, seed, request.settings.sampler, variant, time.perf_counter() - start,
                         passes, white_p, white_c, applied, frame.info)


def balanced_frame(first: FaceRendering, level: Level, radiance: NDArrayFloat, grid: WavelengthGrid, seed: int,
                   options=None) -> tuple[NDArrayFloat, Frame, NDArrayFloat]:
    """
    A ``radiance`` (specfilm units, ``(..., 3)``) of ``first``'s scene, camera and lights as one frame of
    ``level``: through its ``post`` (a sensor's frame, seeded by ``seed``; ``options``: the effects' options, as
    the render's) and Eq. 4's gain. Returns the image (output units, float64), the frame and the gain.
    """
    setup = level.setup(first.scene, first.camera, grid, level.lights(first.scene), calibration=first.calibration,
                        seed=int(seed), options=dict(options or {}))
    frame = level.post(Frame(radiance, first.white_prevailing, first.white_calibration,
                             {"lights": first.info.get("lights", {})}), setup)
    applied = gain(frame.white_prevailing, frame.white_calibration, scale=CONSTANT_OUTPUT_SCALE)
    return applied * frame.signal, frame, applied


def face_exr(rendering: FaceRendering) -> tuple[NDArrayFloat, tuple[str, ...], dict]:
    """
    The EXR of a face render: the image (output units, channels named by the camera) with its ``label``
    channel, the channel names and the header attributes.
    """
    stack = np.concatenate([rendering.image, rendering.labels[..., None].astype(np.float32)], axis=-1)
    attributes = {**camera_attributes(rendering.camera), "prevailing_K": rendering.prevailing,
                  "calibration_K": rendering.calibration, "spp": rendering.spp, "seed": rendering.seed,
                  "variant": rendering.variant, "physics": rendering.physics, "skin": rendering.skin,
                  "labels": ", ".join(f"{k}={v}" for k, v in rendering.label_names.items()),
                  "units": "Eq. 4 output units; label: 0 background, 1 skin, 2... props"}
    return stack, (*rendering.channels, "label"), attributes


def write_face_exr(path: str | Path, rendering: FaceRendering,
                   preview: bool = True) -> tuple[Path, Path | None]:
    """
    Write the image and its ``label`` channel as a float32 EXR (:func:`face_exr`), and a tone-mapped PNG
    beside it: both whole or neither (:func:`skinrender.files.write_outputs`).
    """
    path = Path(path)
    outputs = [Output(path, None, lambda stream: write_exr(stream, *face_exr(rendering)))]
    if preview:
        outputs.append(Output(path.with_suffix(".png"), None, lambda stream: write_preview(stream, rendering.image)))
    write_outputs(*outputs)
    return path, path.with_suffix(".png") if preview else None
