"""
Sensor noise
============

The render recorded by an image sensor (:func:`skinrender.model.noise.simulate_dn`):
shot, dark, read and quantisation noise, full well and ADC clipping. It acts
after rendering, on the frame, and changes nothing in the Mitsuba document.

-   :data:`NOISE`: the effect; :data:`IMAGER_DEFAULT`. Its options are
    :class:`~skinrender.rendering.sensor.NoiseOptions` (imager, illuminance,
    exposure); an ``imager`` adds it to a level; :func:`relit` scales the
    scene's lights to its illuminance.
-   :func:`through_imager`: one noisy frame of a rendered radiance.
-   :func:`sensor_terms`, :data:`DITHER_SIGMA_DN`: what validation checks
    through the sensor.

The frame
---------
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

Its limits
----------
The sensor adds no limit and breaks none: a level's check runs on the
frames' mean, the dark signal removed, pixels with a clipped replicate left
out, and the rounding to codes bounded (:func:`sensor_terms`).

Units: radiance in the specfilm's units (W·m⁻²·sr⁻¹ times the sensitivity's
unit); frames and whites in DN; illuminance lx; exposure s.
"""

from __future__ import annotations

import numpy as np

from ....hints import NDArrayFloat
from ....model.camera import Camera
from ....spectra import WavelengthGrid, planck
from ..document import channel_integral, light_irradiance
from ..labels import LABEL_SKIN
from ..limits import rounding_bias
from ...sensor import NoiseOptions
from ..scene import FaceScene, Light, prevailing_name
from .base import Effect, Frame, Limits, Measured, Setup

__all__ = ["EFFECT", "NOISE", "IMAGER_DEFAULT", "relit", "DITHER_SIGMA_DN", "through_imager", "sensor_terms"]

IMAGER_DEFAULT = "sony-icx418"
"""The image sensor of physics ``noise`` unless one is named: the paper's class of 3-CCD camera, 8-bit."""

DITHER_SIGMA_DN = 0.25
"""Through a sensor, a pixel is tested only where its modelled noise (shot and read, DN) is at least this in
every channel: the noise then dithers the rounding to codes (its mean error below 0.003 DN,
:func:`~skinrender.rendering.face.limits.rounding_bias`) and the replicates differ, so their spread measures
the noise; below it, twelve frames may read one code and hide a rounding error of up to half a code."""


def through_imager(radiance: NDArrayFloat, white_p: NDArrayFloat, scene: FaceScene, cam: Camera,
                   calibration: float, grid: WavelengthGrid, imager_, exposure,
                   seed: int) -> tuple[NDArrayFloat, NDArrayFloat, NDArrayFloat, dict]:
    """
    The signal (DN above black, ≥ 0) of one noisy frame, the noise-free whites ``white_p`` and
    ``white_c`` in DN at the same exposure (``white_c`` at the key light's illuminance), the settings.
    """
    from ....model.exposure import electrons_mean
    from ....model.imager import imager as imager_of
    from ....model.noise import clipping_counts, clipping_note, simulate_dn_clipped
    from ...imaging import exposure_for, exposure_note

    im = imager_of(imager_)
    x = cam.sensitivities(grid)
    # electrons per second per unit of ∫ L x_k dλ: the same for every spectrum (QE ∝ x_k / λ): any probe
    probe = planck(grid.wavelengths, calibration)
    per_unit = (electrons_mean(im, x / grid.wavelengths, probe, 1.0, grid) - im.dark_current_e_per_s) / (
        probe @ x.T * grid.step)
    lux = getattr(scene, prevailing_name(scene)).illuminance
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
    lam, irradiance = light_irradiance(Light(temperature, lux), grid)
    return channel_integral(cam, grid, lam, irradiance / np.pi)


def _options(setup: Setup) -> NoiseOptions:
    """The effect's own options in ``setup`` (the defaults where none were given)."""
    return setup.options.get("noise") or NoiseOptions()


def _post(frame: Frame, setup: Setup) -> Frame:
    options = _options(setup)
    signal, white_p, white_c, settings = through_imager(
        frame.signal, frame.white_prevailing, setup.scene, setup.camera, setup.calibration, setup.grid,
        options.imager or IMAGER_DEFAULT, options.exposure, setup.seed)
    return Frame(signal, white_p, white_c, {**frame.info, **settings})


def relit(scene: FaceScene, options: NoiseOptions | None) -> FaceScene:
    """
    The face scene with every light scaled so that the prevailing one (the key, or in a scene without a key the
    environment) gives ``options.illuminance`` lx at the target (``None``: the scene as it is). Only the sensor
    sees it: Eq. 4 cancels a common scale of the lights.
    """
    from dataclasses import replace

    name = prevailing_name(scene)
    if options is None or options.illuminance is None or getattr(scene, name) is None:
        return scene
    ratio = float(options.illuminance) / getattr(scene, name).illuminance
    return replace(scene, **{k: replace(getattr(scene, k), illuminance=getattr(scene, k).illuminance * ratio)
                             for k in ("key", "fill", "environment") if getattr(scene, k) is not None})


def sensor_terms(first, images: NDArrayFloat, spec) -> tuple[NDArrayFloat, ...]:
    """
    Images less the dark signal, the pixels no replicate clipped, and the rounding's bound (output units).

    ``first`` is the first replicate (a :class:`~skinrender.rendering.face.render.FaceRendering` through the
    sensor), ``images`` the replicates ``(K, height, width, 3)`` in output units, ``spec`` the imager
    (``None``: :data:`IMAGER_DEFAULT`). Returns ``(images, usable, bias, floor, excluded)``.
    """
    from ....model.imager import imager as imager_of

    im = imager_of(spec or IMAGER_DEFAULT)
    g = np.asarray(first.gain, dtype=np.float64)  # output units per DN
    k = im.gain_dn_per_e
    dark = k * im.dark_current_e_per_s * first.info["exposure_s"]  # DN
    signal = images / g  # DN above the black level
    saturation = min(float(im.max_dn), k * im.full_well_e + im.black_level_dn) - im.black_level_dn
    electrons = np.maximum(signal.mean(axis=0) / k, 0.0)
    sigma = k * np.sqrt(electrons + im.read_noise_e**2)
    unclipped = np.all((signal > 0) & (signal < saturation - 0.5), axis=(0, -1))
    dithered = np.all(sigma >= DITHER_SIGMA_DN, axis=-1)
    skin = first.labels == LABEL_SKIN
    excluded = {"skin_pixels_clipped": int((skin & ~unclipped).sum()),
                "skin_pixels_undithered": int((skin & unclipped & ~dithered).sum())}
    floor = g**2 * (sigma**2 + 1.0 / 12.0) / images.shape[0]  # EMVA 1288: shot, read and quantisation
    return images - g * dark, unclipped & dithered, g * rounding_bias(sigma), floor, excluded


def _measure(measured: Measured, first, options: NoiseOptions | None) -> Measured:
    images, usable, bias, floor, excluded = sensor_terms(first, measured.images, (options or NoiseOptions()).imager)
    note = (f"the sensor left out {excluded['skin_pixels_clipped']} skin pixels clipped at 0 or saturation and "
            f"{excluded['skin_pixels_undithered']} whose noise is below {DITHER_SIGMA_DN:g} DN in some channel (its "
            "codes too coarse for it: more light, or a sensor of finer codes)")
    return Measured(images, usable, bias, floor, excluded, note)


NOISE = Effect(
    "noise",
    "through an image sensor (skinrender.model.noise.simulate_dn): shot, dark, read and quantisation noise, full "
    "well and ADC clipping",
    short="sensor noise", post=_post, limits=Limits(measure=_measure),
    order=50, options=NoiseOptions, added_by=("imager",), scene=relit,
)

EFFECT = NOISE
"""This module's effect (the registry takes it: :mod:`.levels`)."""
