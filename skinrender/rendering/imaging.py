"""
Renders through an image sensor
===============================

The rendered road of the imager model: a noise-free spectral render becomes
the image a camera would record — photo-electrons, shot, dark and read noise,
the full well, conversion gain and ADC (:mod:`skinrender.model.noise`) — at a
stated illuminance and exposure, then Eq. 4 as always.

-   :func:`electrons_per_radiance`: electrons per unit of the render's channel
    value, from the white's electrons under the lit chart.
-   :func:`render_imaged`, :class:`ImagedRendering`: the noisy image of a
    (prevailing, calibration) pair, seeded (the same seed, the same image),
    with what it clipped (:func:`~skinrender.model.noise.clipping_counts`) and
    a note where the ``auto`` exposure's cap binds; :func:`render_imaged_request`:
    the same of a :class:`~skinrender.rendering.request.ChartRequest` (the
    ``noise`` effect's chart part).
-   :func:`predicted_electrons`, :func:`predicted_patches`: each patch's
    analytic electrons, e⁻, and its mean and variance, DN.

Its validation against the sensor model is
:mod:`skinrender.rendering.sensor_validation`.

Units: illuminance in lx, exposure in s, electrons e⁻, digital numbers DN;
the balanced image in output units (255 for white at p = c).

Notes
-----
The camera's curves weight energy (Eq. 1), so the quantum efficiency is
proportional to x(λ)/λ and a patch's photo-electrons are the white's times
the ratio of their Eq. 1 responses (as
:func:`skinrender.evaluation.noisy_detection.pixel_electrons` computes them
analytically). A render's channel value is ``∫ L x_k dλ``; divided by the same
integral for a perfect white under the emitter (``∫ E x_k dλ / π``, the
trapezoid rule on the emitter's 0.1 nm table, as the renderer integrates) it
is that ratio. The exposure is the same for both renders of a pair: fixed, or
``auto`` (the calibration white's brightest channel at 0.7 of the full well).
The white balance uses the noise-free whites, as a camera calibrated once on a
white would.

References
----------
-   [EMVA1288]_ : the sensor model (docs/references.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import SkinrenderError
from ..hints import NDArrayFloat
from ..model.camera import Camera
from ..model.exposure import (AUTO_EXPOSURE_FRACTION, AUTO_EXPOSURE_MAX_S, auto_exposure,
                              auto_exposure_note, electrons_mean, irradiance_planck)
from ..model.imager import Imager
from ..model.noise import clipping_counts, clipping_note, simulate_dn_clipped, statistics_dn
from ..spectra import GRID_DEFAULT, WavelengthGrid, planck
from .balance import Rendering, pair_gain, patch_statistics
from .renderer import RawRender, emitter_grid
from .scene import ChartScene
from .settings import RenderSettings

__all__ = ["AUTO_EXPOSURE_FRACTION", "ImagedRendering", "electrons_per_radiance", "check_exposure", "exposure_for",
           "exposure_note", "render_imaged", "render_imaged_request", "predicted_electrons", "predicted_patches"]


def _white_radiance(cam: Camera, temperature: float, grid: WavelengthGrid) -> NDArrayFloat:
    """``∫ planck(λ, T) x_k(λ) dλ / π`` per channel: a perfect white's render value (trapezoid, emitter table)."""
    lam = emitter_grid(grid)
    x = np.array([np.interp(lam, grid.wavelengths, curve) for curve in cam.sensitivities(grid)])
    weights = np.full(lam.size, lam[1] - lam[0])
    weights[[0, -1]] *= 0.5
    return (planck(lam, temperature) * weights) @ x.T / math.pi


def _white_rate(im: Imager, cam: Camera, temperature: float, lux: float, grid: WavelengthGrid) -> NDArrayFloat:
    """The white's electron rate per channel under ``lux`` at ``temperature``, e⁻/s, dark current included."""
    x = cam.sensitivities(grid)
    return electrons_mean(im, x / grid.wavelengths, irradiance_planck(temperature, lux, grid) / math.pi, 1.0, grid)


def electrons_per_radiance(im: Imager, cam: Camera, temperature: float, lux: float,
                           grid: WavelengthGrid = GRID_DEFAULT) -> NDArrayFloat:
    """Photo-electrons per second per unit of render value, per channel (e⁻ s⁻¹ per W·m⁻²·sr⁻¹)."""
    photo = _white_rate(im, cam, temperature, lux, grid) - im.dark_current_e_per_s
    return photo / _white_radiance(cam, temperature, grid)


def _is_auto(exposure: float | str) -> bool:
    return isinstance(exposure, str) and exposure.strip().lower() == "auto"


def exposure_note(im: Imager, cam: Camera, calibration: float, lux: float, exposure: float | str,
                  grid: WavelengthGrid = GRID_DEFAULT) -> str | None:
    """
    Where an ``auto`` exposure (:func:`exposure_for`) stopped at :data:`AUTO_EXPOSURE_MAX_S` before the
    calibration white (K, under ``lux`` lx) reached its share of the well, the note saying so; else ``None``.
    """
    if not _is_auto(exposure):
        return None
    return auto_exposure_note(im, _white_rate(im, cam, calibration, lux, grid), AUTO_EXPOSURE_FRACTION,
                              AUTO_EXPOSURE_MAX_S)


def check_exposure(exposure) -> float | str:
    """
    ``exposure`` checked before anything renders: ``"auto"``, or a finite number of seconds > 0 (text of one
    too); else a one-line error naming it.

    >>> check_exposure("AUTO"), check_exposure("0.01")
    ('auto', 0.01)
    """
    if isinstance(exposure, str) and _is_auto(exposure):
        return "auto"
    try:
        value = float(exposure)
    except (TypeError, ValueError, OverflowError):
        raise SkinrenderError(f"exposure must be 'auto' or seconds > 0, got {exposure!r}", role="exposure") from None
    if isinstance(exposure, bool) or not (np.isfinite(value) and value > 0):
        raise SkinrenderError(f"exposure must be 'auto' or a finite number of seconds > 0, got {exposure!r}",
                              role="exposure")
    return value


def exposure_for(im: Imager, cam: Camera, calibration: float, lux: float, exposure: float | str,
                 grid: WavelengthGrid = GRID_DEFAULT) -> float:
    """The exposure, s: ``exposure`` itself (> 0), or ``auto`` from the calibration white."""
    exposure = check_exposure(exposure)
    if exposure == "auto":
        return float(auto_exposure(im, _white_rate(im, cam, calibration, lux, grid), AUTO_EXPOSURE_FRACTION,
                                   AUTO_EXPOSURE_MAX_S))
    return float(exposure)


@dataclass(frozen=True)
class ImagedRendering:
    """
    A render through an image sensor.

    Attributes
    ----------
    rendering
        The Eq. 4 image of the noisy DN (output units) with its patch statistics.
    dn
        The prevailing frame, DN, ``(height, width, 3)``.
    electrons
        Its expected electrons per pixel, e⁻ (noise-free, photo plus dark).
    imager, illuminance_lux, exposure_s, seed
        What made it.
    gains
        The Eq. 4 gain, output units per DN above the black level, ``(3,)``.
    clipping
        :func:`~skinrender.model.noise.clipping_counts` of the frame: pixels clipped at the full well and at the ADC range, per channel.
    notes
        What was capped or clipped (an ``auto`` exposure stopped by :data:`AUTO_EXPOSURE_MAX_S`, clipped pixels).
    exposure_auto
        Whether the exposure was ``auto`` (it then follows the light).
    """

    rendering: Rendering
    dn: NDArrayFloat
    electrons: NDArrayFloat
    imager: Imager
    illuminance_lux: float
    exposure_s: float
    seed: int
    gains: NDArrayFloat
    clipping: dict = field(default_factory=dict)
    notes: tuple[str, ...] = ()
    exposure_auto: bool = False


def render_imaged(
    scene: ChartScene | str,
    camera_: Camera,
    prevailing: float,
    calibration: float,
    imager_: Imager | str,
    illuminance_lux: float,
    exposure: float | str = "auto",
    normalization: str = "white",
    settings: RenderSettings | None = None,
    grid: WavelengthGrid = GRID_DEFAULT,
    **options,
) -> ImagedRendering:
    """
    Render ``scene`` lit at ``illuminance_lux`` by the prevailing Planckian light (K) and record it with an
    image sensor; white balance to ``calibration`` (K) from the noise-free whites (Eq. 4).

    The render's noise is Monte Carlo (``settings``, :class:`~skinrender.rendering.settings.RenderSettings`,
    or its fields ``spp``, ``seed`` … as ``options``); the sensor's noise is drawn per pixel from the seed too
    (another stream), so the same seed gives the same image. ``normalization`` other than ``white`` needs no
    whites: the gain then uses ``F_p / F_c`` as for renders without a sensor.
    """

    from .request import chart_request

    request = chart_request(scene, camera_, prevailing, calibration, normalization=normalization, settings=settings,
                            grid=grid, imager=imager_, illuminance=illuminance_lux, exposure=exposure, **options)
    return render_imaged_request(request)


def render_imaged_request(request) -> ImagedRendering:
    """
    The :class:`ImagedRendering` of a :class:`~skinrender.rendering.request.ChartRequest` whose level records
    through the sensor (its ``noise`` options: :class:`~skinrender.rendering.sensor.NoiseOptions`; the
    illuminance :data:`~skinrender.rendering.request.ILLUMINANCE_DEFAULT` unless given).
    """
    from .request import ILLUMINANCE_DEFAULT
    from .renderer import chart_renderer

    sensor, settings, grid = request.sensor, request.settings, request.grid
    chart, camera_, prevailing, calibration = request.scene, request.camera, request.prevailing, request.calibration
    im, exposure, normalization = sensor.imager, sensor.exposure, request.normalization
    illuminance_lux = ILLUMINANCE_DEFAULT if sensor.illuminance is None else sensor.illuminance
    seed = settings.seed
    t = exposure_for(im, camera_, calibration, illuminance_lux, exposure, grid)
    raw: RawRender = chart_renderer(chart, camera_, settings, grid, request.emitter).raw(prevailing, seed)
    electrons = (raw.radiance * electrons_per_radiance(im, camera_, prevailing, illuminance_lux, grid)
                 + im.dark_current_e_per_s) * t
    dn, well_full, adc_clipped = simulate_dn_clipped(im, electrons, np.random.default_rng([seed, 0x5EED]))
    clipping = clipping_counts(well_full, adc_clipped)
    notes = tuple(note for note in (exposure_note(im, camera_, calibration, illuminance_lux, exposure, grid),
                                    clipping_note(clipping)) if note)
    white = {name: (_white_rate(im, camera_, k, illuminance_lux, grid) - im.dark_current_e_per_s)
             * t * im.gain_dn_per_e for name, k in (("p", prevailing), ("c", calibration))}
    gains = pair_gain(white["p"], white["c"], normalization, prevailing, calibration, grid)
    image = ((dn - im.black_level_dn) * gains).astype(np.float32)
    rendering = Rendering(chart, camera_, prevailing, calibration, normalization, False, image,
                          patch_statistics(image, chart), np.zeros((2, 3)), (raw,),
                          {"white_ratio": white["p"] / white["c"], "imager": im.name,
                           "illuminance_lux": float(illuminance_lux), "exposure_s": t, "clipping": clipping,
                           "notes": list(notes)})
    return ImagedRendering(rendering, dn, electrons, im, float(illuminance_lux), t, int(seed), gains, clipping, notes,
                           _is_auto(exposure))


def predicted_electrons(imaged: ImagedRendering, reference_ratio: NDArrayFloat,
                        grid: WavelengthGrid = GRID_DEFAULT) -> NDArrayFloat:
    """
    Each patch's analytic electrons per pixel, e⁻ (photo plus dark), from ``reference_ratio`` — the patch's
    render value over a perfect white's, ``(patches, 3)`` (the Eq. 4 reference at p = c over 255).
    """
    im, r = imaged.imager, imaged.rendering
    photo = reference_ratio * (_white_rate(im, r.camera, r.prevailing, imaged.illuminance_lux, grid)
                               - im.dark_current_e_per_s)
    return (photo + im.dark_current_e_per_s) * imaged.exposure_s


def predicted_patches(imaged: ImagedRendering, reference_ratio: NDArrayFloat,
                      grid: WavelengthGrid = GRID_DEFAULT) -> tuple[NDArrayFloat, NDArrayFloat]:
    """Each patch's analytic mean, DN, and pixel variance, DN², at :func:`predicted_electrons`."""
    return statistics_dn(imaged.imager, predicted_electrons(imaged, reference_ratio, grid))
