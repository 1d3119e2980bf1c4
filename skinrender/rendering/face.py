"""
Rendering faces
===============

A face scene (:mod:`skinrender.rendering.face_scene`) rendered through a
camera's three channels at a level of physics
(:data:`~skinrender.rendering.face_dict.PHYSICS`), white balanced as Eq. 4
does, with a label image from the geometry.

-   :func:`render_face`, :class:`FaceRendering`: one render.
-   :func:`white_references`: the channel responses to a white under the
    prevailing and the calibration light.
-   :func:`write_face_exr`: the float32 EXR, with a ``label`` channel.

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
its reflectance, and a white there reads 255 at p = c.

The image sensor (physics ``noise``)
------------------------------------
A channel's quantum efficiency is taken proportional to ``x_k(λ) / λ`` (the
curves weight energy, as in Eq. 1), so a pixel's electron rate is a constant
per channel times its rendered ``∫ L x_k dλ``
(:func:`skinrender.model.exposure.electrons_mean`); the lights keep their
illuminances (lx); the exposure is given or ``auto``, as for charts
(:func:`skinrender.rendering.imaging.exposure_for`: the calibration white at
the key light's illuminance, its brightest channel at 0.7 of the full well, a
video frame at most); one frame (:func:`skinrender.model.noise.simulate_dn`,
seeded from the render's seed on a stream of its own), less the black level
and clipped at 0 DN as a raw pipeline does (and as
:mod:`skinrender.evaluation.noisy_detection` does: NCC needs light, not
negative DN), is balanced with the gain of the noise-free whites in DN, as
:func:`skinrender.rendering.imaging.render_imaged` does.

Units: radiance images in W·m⁻²·sr⁻¹ times the sensitivity's unit (the
specfilm's ``∫ L x_k dλ``); balanced images in output units; illuminance lx.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ..constants import CONSTANT_OUTPUT_SCALE
from ..errors import SkinrenderError
from ..files import Output, write_outputs
from ..hints import NDArrayFloat
from ..methods import validate_method
from ..model.camera import Camera, camera
from ..model.illuminant import illuminant
from ..model.response import gain
from ..spectra import GRID_DEFAULT, WavelengthGrid, planck
from .exr import write_exr, write_preview
from .face_dict import (PHYSICS, active_lights, channel_groups, channel_integral, face_document,
                        light_irradiance, parse_physics)
from .face_labels import label_names, render_labels, shape_labels
from .face_scene import MESH_HEAD, FaceScene, load_face_scene, skin_reflectance_of
from .renderer import SAMPLERS, SAMPLES_MAX, channel_names
from .variants import choose_variant, mitsuba

__all__ = ["PHYSICS", "IMAGER_DEFAULT", "FaceRendering", "planckian_temperature", "white_references",
           "render_face", "face_exr", "write_face_exr"]

IMAGER_DEFAULT = "sony-icx418"
"""The image sensor of physics ``noise`` unless one is named: the paper's class of 3-CCD camera, 8-bit."""


_LOADED: dict = {}
_LOADED_MAX = 6


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


def planckian_temperature(spec, name: str) -> float:
    """
    The temperature, K, of a Planckian light spec (kelvin, ``A`` or ``H``); a one-line error naming ``name``
    for any other light (a face's lights are Planckian).

    >>> planckian_temperature("A", "prevailing")
    2856.0
    """
    item = illuminant(spec)
    if item.temperature is None:
        raise SkinrenderError(f"{name}: the face is lit by Planckian lights (kelvin, A or H), got {spec!r}")
    return float(item.temperature)


def _prevailing_light(scene: FaceScene) -> str:
    return "key" if scene.key is not None else "environment"


def white_references(scene: FaceScene, cam: Camera, calibration: float,
                     grid: WavelengthGrid = GRID_DEFAULT) -> tuple[NDArrayFloat, NDArrayFloat]:
    """
    ``white_p`` and ``white_c`` (channels, specfilm units): a perfect white at
    the camera target facing the key light (or open to the environment in a
    scene without one), and under the calibration Planckian at ``calibration``
    K (its scale arbitrary: Eq. 4 cancels it).
    """
    light = getattr(scene, _prevailing_light(scene))
    if light is None:
        raise SkinrenderError(f"face scene {scene.source or scene.name} has no key light and no environment")
    lam, irradiance = light_irradiance(light, grid)
    white_p = channel_integral(cam, grid, lam, irradiance / np.pi)
    spd = planck(lam, calibration)
    white_c = channel_integral(cam, grid, lam, spd / np.max(spd))
    if np.any(white_c <= 0) or np.any(white_p <= 0):
        raise SkinrenderError(f"camera {cam.name}: a channel sees no light from the white reference")
    return white_p, white_c


def _loaded(scene, cam, grid, effects, skin, group, spp, sampler, variant, lights, scale):
    key = (scene, cam.name, cam.kind, cam.sensitivities(grid).tobytes(), grid,
           tuple(e for e in effects if e != "noise"), skin, group, spp, sampler, variant,
           tuple(sorted(lights.items())), scale)
    if key not in _LOADED:
        if len(_LOADED) >= _LOADED_MAX:
            _LOADED.pop(next(iter(_LOADED)))
        mi = mitsuba(variant)
        document = face_document(mi, scene, cam, grid, effects, skin, group, spp, 0, sampler, lights, scale)
        try:
            _LOADED[key] = mi.load_dict(document)
        except RuntimeError as error:  # the checks of load_face_scene passed, yet Mitsuba refused the user's mesh
            if scene.mesh == MESH_HEAD or Path(scene.mesh).name not in str(error):
                raise
            reason = " ".join(str(error).split())[-300:]
            raise SkinrenderError(f"{scene.source}: [mesh]: field 'file': Mitsuba could not load {scene.mesh}: "
                                  f"{reason}") from None
    return _LOADED[key]


def _through_imager(radiance: NDArrayFloat, white_p: NDArrayFloat, scene: FaceScene, cam: Camera,
                    calibration: float, grid: WavelengthGrid, imager_, exposure,
                    seed: int) -> tuple[NDArrayFloat, NDArrayFloat, NDArrayFloat, dict]:
    """
    The signal (DN above black, ≥ 0) of one noisy frame, the noise-free whites ``white_p`` and
    ``white_c`` in DN at the same exposure (``white_c`` at the key light's illuminance), the settings.
    """
    from ..model.exposure import electrons_mean
    from ..model.imager import imager as imager_of
    from ..model.noise import clipping_counts, clipping_note, simulate_dn_clipped
    from .imaging import exposure_for, exposure_note

    im = imager_of(imager_)
    x = cam.sensitivities(grid)
    # electrons per second per unit of ∫ L x_k dλ: the same for every spectrum (QE ∝ x_k / λ): any probe
    probe = planck(grid.wavelengths, calibration)
    per_unit = (electrons_mean(im, x / grid.wavelengths, probe, 1.0, grid) - im.dark_current_e_per_s) / (
        probe @ x.T * grid.step)
    lux = getattr(scene, _prevailing_light(scene)).illuminance
    exposure_s = exposure_for(im, cam, calibration, lux, exposure, grid)
    electrons = (per_unit * radiance + im.dark_current_e_per_s) * exposure_s
    frame, well_full, adc_clipped = simulate_dn_clipped(im, electrons, np.random.default_rng([int(seed), 0x5EED]))
    clipping = clipping_counts(well_full, adc_clipped)  # the sensor's own stream, as simulate_dn draws it
    notes = [note for note in (exposure_note(im, cam, calibration, lux, exposure, grid), clipping_note(clipping))
             if note]
    dn_per_unit = im.gain_dn_per_e * per_unit * exposure_s
    white_c_lux = _white_at(cam, calibration, lux, grid)  # the calibration white, the key light's lux
    return (np.maximum(frame - im.black_level_dn, 0.0), dn_per_unit * white_p, dn_per_unit * white_c_lux,
            {"imager": im.name, "illuminance_lux": float(lux), "exposure_s": float(exposure_s), "clipping": clipping,
             "notes": notes})


def _white_at(cam: Camera, temperature: float, lux: float, grid: WavelengthGrid) -> NDArrayFloat:
    """A perfect white's channels under a Planckian of ``lux`` (radiance ``E / π``), specfilm units."""
    from .face_scene import Light

    lam, irradiance = light_irradiance(Light(temperature, lux), grid)
    return channel_integral(cam, grid, lam, irradiance / np.pi)


def render_face(
    camera_: Camera | str,
    scene: FaceScene | str = "face",
    prevailing=None,
    calibration=None,
    skin: str | None = None,
    physics: str = "direct",
    spp: int = 64,
    seed: int = 0,
    size: int | tuple[int, int] | None = None,
    sampler: str = "multijitter",
    variant: str | None = None,
    grid: WavelengthGrid = GRID_DEFAULT,
    channels: str = "auto",
    imager: str | None = None,
    exposure="auto",
    illuminance: float | None = None,
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
        ``direct`` or effects of :data:`PHYSICS` joined by ``+``.
    spp, seed, sampler, variant, grid, channels
        As :func:`skinrender.rendering.renderer.render_raw`.
    size
        Image size in pixels (``N`` or ``(width, height)``); ``None`` keeps the scene's.
    imager, exposure
        For ``noise``: the image sensor (a preset or TOML; default
        :data:`IMAGER_DEFAULT`) and ``auto`` or seconds.
    illuminance
        The key light's illuminance at the target, lx (every light scaled
        with it); ``None`` keeps the scene's. Only ``noise`` sees it: Eq. 4
        cancels a common scale of the lights.

    Returns
    -------
    :class:`FaceRendering`
    """

    start = time.perf_counter()
    face = load_face_scene(scene)
    if size is not None:
        width, height = (size, size) if np.ndim(size) == 0 else size
        whole = [isinstance(v, (int, np.integer)) and not isinstance(v, bool) and v >= 1
                 for v in (width, height)]
        if not all(whole):
            raise SkinrenderError(f"size must be a positive number of pixels (or two), got {size!r}")
        face = face.resized(int(width), int(height))
    cam = camera(camera_)
    effects = parse_physics(physics)
    skin = face.skin if skin is None else str(skin).strip()
    skin_reflectance_of(skin, grid, "skin")
    validate_method(sampler, SAMPLERS, "sampler")
    if not (isinstance(spp, (int, np.integer)) and not isinstance(spp, bool) and spp >= 1):
        raise SkinrenderError(f"spp must be a positive integer, got {spp!r}")
    if not (isinstance(seed, (int, np.integer)) and not isinstance(seed, bool) and 0 <= seed < 2**32):
        raise SkinrenderError(f"seed must be an integer in [0, 2^32) (Mitsuba's seeds are 32-bit), "
                              f"got {seed!r}")
    pixels = face.camera.width * face.camera.height
    if spp * pixels > SAMPLES_MAX:
        raise SkinrenderError(f"spp {spp} × {pixels} pixels = {spp * pixels:.3g} samples per pass, more than "
                              f"{SAMPLES_MAX:.3g}; at most {SAMPLES_MAX // pixels} spp at this size")
    name = _prevailing_light(face)
    if illuminance is not None and getattr(face, name) is not None:
        if not (isinstance(illuminance, (int, float)) and np.isfinite(illuminance) and illuminance > 0):
            raise SkinrenderError(f"illuminance must be a finite number of lux > 0, got {illuminance!r}")
        ratio = float(illuminance) / getattr(face, name).illuminance
        face = replace(face, **{k: replace(getattr(face, k), illuminance=getattr(face, k).illuminance * ratio)
                                for k in ("key", "fill", "environment") if getattr(face, k) is not None})
    if prevailing is not None and getattr(face, name) is not None:
        light = replace(getattr(face, name), temperature=planckian_temperature(prevailing, "prevailing"))
        face = replace(face, **{name: light})
    p = getattr(face, name).temperature if getattr(face, name) is not None else None
    c = p if calibration is None else planckian_temperature(calibration, "calibration")
    lights = active_lights(face, effects)
    white_p, white_c = white_references(face, cam, c, grid)
    scale = max(float(np.max(light_irradiance(light, grid)[1])) for light in lights.values())
    variant = choose_variant(variant)
    mi = mitsuba(variant)
    groups = channel_groups(cam, grid, channels)
    width, height = face.camera.width, face.camera.height
    radiance = np.zeros((height, width, 3))
    spp_used, first = int(spp), None
    for group in groups:
        loaded = _loaded(face, cam, grid, effects, skin, group, int(spp), sampler, variant, lights, scale)
        first = first or loaded
        spp_used = int(loaded.sensors()[0].sampler().sample_count())
        values = np.array(mi.render(loaded, seed=int(seed)), dtype=np.float64)
        radiance[:, :, list(group)] = values.reshape(height, width, len(group)) * scale
    labels = render_labels(mi, first, width, height, shape_labels(face))
    info = {"lights": {k: {"temperature_K": v.temperature, "illuminance_lx": v.illuminance}
                       for k, v in lights.items()}}
    if "noise" in effects:
        signal, white_p_dn, white_c_dn, settings = _through_imager(radiance, white_p, face, cam, c, grid,
                                                                   imager or IMAGER_DEFAULT, exposure, seed)
        info.update(settings)
        applied = gain(white_p_dn, white_c_dn, scale=CONSTANT_OUTPUT_SCALE)
        image = applied * signal
    else:
        applied = gain(white_p, white_c, scale=CONSTANT_OUTPUT_SCALE)
        image = applied * radiance
    return FaceRendering(face, cam, "+".join(effects) or "direct", skin, float(p), float(c),
                         image.astype(np.float32), radiance, labels, label_names(face), spp_used, int(spp),
                         int(seed), sampler, variant, time.perf_counter() - start, len(groups), white_p,
                         white_c, applied, info)


def face_exr(rendering: FaceRendering) -> tuple[NDArrayFloat, tuple[str, ...], dict]:
    """
    The EXR of a face render: the image (output units, channels named by the camera) with its ``label``
    channel, the channel names and the header attributes.
    """
    stack = np.concatenate([rendering.image, rendering.labels[..., None].astype(np.float32)], axis=-1)
    attributes = {"camera": rendering.camera.name, "prevailing_K": rendering.prevailing,
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
