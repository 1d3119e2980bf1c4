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
    (prevailing, calibration) pair, seeded (the same seed, the same image).
-   :func:`predicted_patches`: each patch's analytic mean and variance, DN.
-   :func:`validate_imaged`, :class:`ImagedValidation`: z-test of every patch
    mean and χ² test of its pixel variance, Šidák-corrected.

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
from dataclasses import dataclass

import numpy as np

from ..errors import SkinrenderError
from ..hints import NDArrayFloat
from ..model.camera import Camera
from ..model.exposure import AUTO_EXPOSURE_MAX_S, auto_exposure, electrons_mean, irradiance_planck
from ..model.imager import Imager, imager
from ..model.noise import simulate_dn, statistics_dn
from ..model.response import gain
from ..spectra import GRID_DEFAULT, WavelengthGrid, planck
from .balance import Rendering, patch_statistics
from .renderer import RawRender, emitter_grid, render_raw
from .scene import ChartScene, load_scene

__all__ = ["AUTO_EXPOSURE_FRACTION", "ALPHA_FAMILY", "ImagedRendering", "ImagedValidation", "electrons_per_radiance",
           "exposure_for", "render_imaged", "predicted_patches", "validate_imaged"]

AUTO_EXPOSURE_FRACTION = 0.7
"""``auto`` exposure puts the calibration white's brightest channel at this share of the full well."""


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


def exposure_for(im: Imager, cam: Camera, calibration: float, lux: float, exposure: float | str,
                 grid: WavelengthGrid = GRID_DEFAULT) -> float:
    """The exposure, s: ``exposure`` itself (> 0), or ``auto`` from the calibration white."""
    if isinstance(exposure, str):
        if exposure.strip().lower() != "auto":
            try:
                exposure = float(exposure)
            except ValueError:
                raise SkinrenderError(f"exposure must be 'auto' or seconds > 0, got {exposure!r}") from None
        else:
            return float(auto_exposure(im, _white_rate(im, cam, calibration, lux, grid), AUTO_EXPOSURE_FRACTION,
                                         AUTO_EXPOSURE_MAX_S))
    if not (np.isfinite(exposure) and exposure > 0):
        raise SkinrenderError(f"exposure must be 'auto' or a finite number of seconds > 0, got {exposure!r}")
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
    """

    rendering: Rendering
    dn: NDArrayFloat
    electrons: NDArrayFloat
    imager: Imager
    illuminance_lux: float
    exposure_s: float
    seed: int
    gains: NDArrayFloat


def render_imaged(
    scene: ChartScene | str,
    camera_: Camera,
    prevailing: float,
    calibration: float,
    imager_: Imager | str,
    illuminance_lux: float,
    exposure: float | str = "auto",
    normalization: str = "white",
    spp: int = 256,
    seed: int = 0,
    grid: WavelengthGrid = GRID_DEFAULT,
    **render_options,
) -> ImagedRendering:
    """
    Render ``scene`` lit at ``illuminance_lux`` by the prevailing Planckian light (K) and record it with an
    image sensor; white balance to ``calibration`` (K) from the noise-free whites (Eq. 4).

    The render's noise is Monte Carlo (seed ``seed``); the sensor's noise is drawn per pixel from
    ``seed`` too (another stream), so the same seed gives the same image. ``normalization`` other than
    ``white`` needs no whites: the gain then uses ``F_p / F_c`` as for renders without a sensor.
    """

    chart = load_scene(scene)
    im = imager(imager_)
    if not (np.isfinite(illuminance_lux) and illuminance_lux > 0):
        raise SkinrenderError(f"illuminance must be a finite number of lux > 0, got {illuminance_lux!r}")
    t = exposure_for(im, camera_, calibration, illuminance_lux, exposure, grid)
    raw: RawRender = render_raw(chart, camera_, prevailing, spp, seed, grid=grid, **render_options)
    electrons = (raw.radiance * electrons_per_radiance(im, camera_, prevailing, illuminance_lux, grid)
                 + im.dark_current_e_per_s) * t
    dn = simulate_dn(im, electrons, np.random.default_rng([seed, 0x5EED]))
    white = {name: (_white_rate(im, camera_, k, illuminance_lux, grid) - im.dark_current_e_per_s)
             * t * im.gain_dn_per_e for name, k in (("p", prevailing), ("c", calibration))}
    if normalization == "white":
        gains = gain(white["p"], white["c"])
    else:
        from ..model.response import normalisation_factor

        f = normalisation_factor([prevailing, calibration], normalization, grid)
        gains = gain(white["p"], white["c"], normalization, f[0], f[1])
    image = ((dn - im.black_level_dn) * gains).astype(np.float32)
    rendering = Rendering(chart, camera_, prevailing, calibration, normalization, False, image,
                          patch_statistics(image, chart), np.zeros((2, 3)), (raw,),
                          {"white_ratio": white["p"] / white["c"], "exposure_s": t})
    return ImagedRendering(rendering, dn, electrons, im, float(illuminance_lux), t, int(seed), gains)


def predicted_patches(imaged: ImagedRendering, reference_ratio: NDArrayFloat,
                      grid: WavelengthGrid = GRID_DEFAULT) -> tuple[NDArrayFloat, NDArrayFloat]:
    """
    Each patch's analytic mean, DN, and pixel variance, DN², from ``reference_ratio`` — the patch's
    render value over a perfect white's, ``(patches, 3)`` (the Eq. 4 reference at p = c over 255).
    """
    im, r = imaged.imager, imaged.rendering
    photo = reference_ratio * (_white_rate(im, r.camera, r.prevailing, imaged.illuminance_lux, grid)
                               - im.dark_current_e_per_s)
    return statistics_dn(im, (photo + im.dark_current_e_per_s) * imaged.exposure_s)


ALPHA_FAMILY = 0.01
"""Family-wise false-alarm rate of the noisy validation: each of the m tests (patch × channel × mean and
variance) runs at the Šidák level ``1 − (1 − α)^(1/m)``, as Mitsuba's render tests do."""


@dataclass(frozen=True)
class ImagedValidation:
    """
    A noisy render's patches against the analytic sensor model, per patch and channel.

    ``rendered_mean``/``predicted_mean`` (DN), ``rendered_std``/``predicted_std`` (DN), the z statistic of the
    mean, the χ² p-value of the variance, the Šidák level and ``passed``.
    """

    imaged: ImagedRendering
    rendered_mean: NDArrayFloat
    predicted_mean: NDArrayFloat
    rendered_std: NDArrayFloat
    predicted_std: NDArrayFloat
    z: NDArrayFloat
    p_mean: NDArrayFloat
    p_variance: NDArrayFloat
    level: float

    @property
    def passed(self) -> bool:
        """No test rejects at the Šidák level."""
        return bool(np.all(self.p_mean >= self.level) and np.all(self.p_variance >= self.level))

    def patches(self) -> list[dict]:
        """Per patch, in output units (DN above black × the Eq. 4 gain): CONTRACT.md's rows."""
        gains, names = self.imaged.gains, [p.name for p in self.imaged.rendering.scene.patches]
        black = self.imaged.imager.black_level_dn
        return [{"name": name,
                 "rendered": ((self.rendered_mean[i] - black) * gains).tolist(),
                 "analytic": ((self.predicted_mean[i] - black) * gains).tolist(),
                 "rendered_std": (self.rendered_std[i] * gains).tolist(),
                 "predicted_std": (self.predicted_std[i] * gains).tolist(),
                 "z_mean": self.z[i].tolist(), "p_variance": self.p_variance[i].tolist(),
                 "passed": bool(np.all(self.p_mean[i] >= self.level) and np.all(self.p_variance[i] >= self.level))}
                for i, name in enumerate(names)]


def validate_imaged(imaged: ImagedRendering, reference_ratio: NDArrayFloat, model: Imager | None = None,
                    alpha: float = ALPHA_FAMILY, grid: WavelengthGrid = GRID_DEFAULT) -> ImagedValidation:
    """
    Check every patch's pixel mean (z-test) and variance (χ² test) against the analytic model of ``model``
    (default: the imager that recorded it), with a Šidák correction over all tests.

    ``reference_ratio``: each patch's render value over a perfect white's, ``(patches, 3)``. The render's
    own Monte Carlo noise is left out of the prediction: at the spp the command line uses it is far below
    the sensor's (tests/rendering/test_imaging.py shows a correct model passing).
    """
    from scipy.stats import chi2, norm

    if model is not None:
        imaged = ImagedRendering(imaged.rendering, imaged.dn, imaged.electrons, imager(model),
                                 imaged.illuminance_lux, imaged.exposure_s, imaged.seed, imaged.gains)
    mean, variance = predicted_patches(imaged, reference_ratio, grid)
    scene = imaged.rendering.scene
    stats = [imaged.dn[rows, columns].reshape(-1, 3) for rows, columns in map(scene.patch_pixels,
                                                                               range(len(scene.patches)))]
    count = np.array([len(pixels) for pixels in stats])[:, None]
    rendered_mean = np.array([pixels.mean(axis=0) for pixels in stats])
    rendered_var = np.array([pixels.var(axis=0, ddof=1) for pixels in stats])
    constant = variance <= 0  # a clipped, noiseless pixel: it must equal its prediction exactly
    z = np.divide(rendered_mean - mean, np.sqrt(variance / count), out=np.zeros_like(mean), where=~constant)
    p_mean = np.where(constant, (np.abs(rendered_mean - mean) < 1e-9).astype(float), 2 * norm.sf(np.abs(z)))
    statistic = np.divide((count - 1) * rendered_var, variance, out=np.zeros_like(mean), where=~constant)
    tail = np.minimum(chi2.cdf(statistic, count - 1), chi2.sf(statistic, count - 1))
    p_variance = np.where(constant, (rendered_var < 1e-9).astype(float), np.minimum(1.0, 2 * tail))
    level = 1.0 - (1.0 - alpha) ** (1.0 / (2 * mean.size))
    return ImagedValidation(imaged, rendered_mean, mean, np.sqrt(rendered_var), np.sqrt(variance), z, p_mean,
                            p_variance, level)
