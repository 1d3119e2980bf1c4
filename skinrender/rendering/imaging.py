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
    a note where the ``auto`` exposure's cap binds.
-   :func:`predicted_patches`: each patch's analytic mean and variance, DN.
-   :func:`validate_imaged`, :class:`ImagedValidation`: every patch's mean and
    pixel variance tested against the sensor model (exact on the code lattice
    where the noise spans a few codes, else z and χ²), Šidák-corrected.

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
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import SkinrenderError
from ..hints import NDArrayFloat
from ..model.camera import Camera
from ..model.exposure import (AUTO_EXPOSURE_FRACTION, AUTO_EXPOSURE_MAX_S, auto_exposure,
                              auto_exposure_note, electrons_mean, irradiance_planck)
from ..model.imager import Imager, imager
from ..model.noise import clipping_counts, clipping_note, code_probabilities, simulate_dn_clipped, statistics_dn
from ..model.response import gain
from ..spectra import GRID_DEFAULT, WavelengthGrid, planck
from .balance import Rendering, patch_statistics
from .renderer import RawRender, emitter_grid, render_raw
from .scene import ChartScene, load_scene

__all__ = ["AUTO_EXPOSURE_FRACTION", "ALPHA_FAMILY", "ImagedRendering", "ImagedValidation", "electrons_per_radiance",
           "exposure_for", "exposure_note", "render_imaged", "predicted_patches", "validate_imaged"]


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


def exposure_for(im: Imager, cam: Camera, calibration: float, lux: float, exposure: float | str,
                 grid: WavelengthGrid = GRID_DEFAULT) -> float:
    """The exposure, s: ``exposure`` itself (> 0), or ``auto`` from the calibration white."""
    if isinstance(exposure, str):
        if not _is_auto(exposure):
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
    clipping
        :func:`~skinrender.model.noise.clipping_counts` of the frame: pixels clipped at the full well and at the ADC range, per channel.
    notes
        What was capped or clipped (an ``auto`` exposure stopped by :data:`AUTO_EXPOSURE_MAX_S`, clipped pixels).
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
    dn, well_full, adc_clipped = simulate_dn_clipped(im, electrons, np.random.default_rng([seed, 0x5EED]))
    clipping = clipping_counts(well_full, adc_clipped)
    notes = tuple(note for note in (exposure_note(im, camera_, calibration, illuminance_lux, exposure, grid),
                                    clipping_note(clipping)) if note)
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
                          {"white_ratio": white["p"] / white["c"], "exposure_s": t, "clipping": clipping,
                           "notes": list(notes)})
    return ImagedRendering(rendering, dn, electrons, im, float(illuminance_lux), t, int(seed), gains, clipping, notes)


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


def _patch_laws(imaged: ImagedRendering, reference_ratio: NDArrayFloat,
                grid: WavelengthGrid = GRID_DEFAULT) -> tuple[NDArrayFloat, NDArrayFloat]:
    """Each patch's code law (:func:`~skinrender.model.noise.code_probabilities`): first code, DN, ``(patches, 3)``,
    and the probabilities, ``(patches, 3, w)``; NaN where the model has none (σ ≥ 4 DN, a filling well)."""
    im, r = imaged.imager, imaged.rendering
    photo = reference_ratio * (_white_rate(im, r.camera, r.prevailing, imaged.illuminance_lux, grid)
                               - im.dark_current_e_per_s)
    electrons = (photo + im.dark_current_e_per_s) * imaged.exposure_s
    first, pmf = code_probabilities(im, electrons.ravel())
    return first.reshape(electrons.shape), pmf.reshape(*electrons.shape, -1)

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
    exact: NDArrayFloat | None = None

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
                 "z_mean": self.z[i].tolist(), "p_mean": self.p_mean[i].tolist(),
                 "p_variance": self.p_variance[i].tolist(),
                 "test": ["exact" if self.exact is not None and self.exact[i, k] else "normal" for k in range(3)],
                 "passed": bool(np.all(self.p_mean[i] >= self.level) and np.all(self.p_variance[i] >= self.level))}
                for i, name in enumerate(names)]


_EXACT_CELLS = 1 << 20
"""The largest (sum, sum of squares) lattice, cells, on which a patch's statistics are summed exactly."""

_NEGLIGIBLE = 1e-15
"""Codes less likely than this per pixel are left out of the exact law (their total over a patch is < 1e-11)."""


def _two_sided(law: NDArrayFloat, below: NDArrayFloat, above: NDArrayFloat) -> float:
    """2 · min(P(T ≤ t), P(T ≥ t)) of a discrete law (both tails keep the observed value), at most 1."""
    return float(min(1.0, 2.0 * min(law[below].sum(), law[above].sum())))


def _exact_p_values(pmf: NDArrayFloat, first: float, codes: NDArrayFloat) -> tuple[float, float] | None:
    """
    Exact two-sided p-values of a patch's pixel mean and sample variance, n pixels of the code law ``pmf``.

    The n codes are independent draws of P(DN = first + j) = ``pmf[j]``: the joint law of (Σ d, Σ d²) is the
    n-fold convolution of one pixel's, summed on its integer lattice (by FFT; codes counted from the most likely
    one, d = 0). The patch mean is Σ d / n and the sample variance (Σ d² − (Σ d)² / n) / (n − 1): both lattice
    laws, never normal where the noise spans a few codes (every pixel one code has probability Σ_j pmf_j^n).
    ``None`` where the lattice exceeds :data:`_EXACT_CELLS`.
    """
    n = codes.size
    keep = np.flatnonzero(pmf > _NEGLIGIBLE)
    probs = pmf[keep[0]:keep[-1] + 1] / pmf[keep[0]:keep[-1] + 1].sum()
    offsets = np.arange(probs.size) - int(np.argmax(probs))  # d, from the most likely code
    width, depth = n * (probs.size - 1) + 1, n * int((offsets**2).max()) + 1
    if n < 2 or width * depth > _EXACT_CELLS:
        return None
    observed = codes - (first + keep[0]) + offsets[0]  # each pixel's d
    if observed.min() < offsets[0] or observed.max() > offsets[-1]:
        return 0.0, 0.0  # a code the model gives < 1e-15 per pixel
    from scipy import fft

    shape = (fft.next_fast_len(width, real=True), fft.next_fast_len(depth, real=True))  # ≥ the sums: no wrap
    one = np.zeros(shape)
    one[offsets - offsets[0], offsets**2] = probs
    spectrum = fft.rfft2(one)
    power = np.abs(spectrum) ** n * np.exp(1j * n * np.angle(spectrum))  # the n-fold convolution
    joint = np.maximum(fft.irfft2(power, s=shape)[:width, :depth], 0.0)
    marginal = joint.sum(axis=1)
    row = int(observed.sum() - n * offsets[0])
    index = np.arange(width)
    p_mean = _two_sided(marginal, index <= row, index >= row)
    cells = np.nonzero(joint > 1e-300)  # (Σ d − n d_min, Σ d²) reachable
    total = cells[0] + float(n * offsets[0])
    variance = (cells[1] - total**2 / n) / (n - 1)
    seen = (np.sum(observed**2) - observed.sum() ** 2 / n) / (n - 1)
    slack = 1e-9 * max(1.0, abs(seen))
    return p_mean, _two_sided(joint[cells], variance <= seen + slack, variance >= seen - slack)


def _variance_dof(pmf: NDArrayFloat, first: float, mean: float, variance: float, n: int) -> float:
    """
    Degrees of freedom ν of the scaled χ² matching the sample variance's two moments (Satterthwaite).

    Var(s²) = μ₄ / n − σ⁴ (n − 3) / (n (n − 1)), with μ₄ from the code law; ν = 2 σ⁴ / Var(s²), which is n − 1 for a
    normal law (μ₄ = 3 σ⁴, the plain χ² test, used where no code law is known).
    """
    if not np.all(np.isfinite(pmf)) or variance <= 0:
        return float(n - 1)
    fourth = float(np.sum(pmf * (first + np.arange(pmf.size) - mean) ** 4))
    spread = fourth / n - variance**2 * (n - 3) / (n * (n - 1))
    return float(2.0 * variance**2 / spread) if spread > 0 else float(n - 1)


def validate_imaged(imaged: ImagedRendering, reference_ratio: NDArrayFloat, model: Imager | None = None,
                    alpha: float = ALPHA_FAMILY, grid: WavelengthGrid = GRID_DEFAULT) -> ImagedValidation:
    """
    Check every patch's pixel mean and variance against the analytic model of ``model`` (default: the imager
    that recorded it), with a Šidák correction over all tests.

    ``reference_ratio``: each patch's render value over a perfect white's, ``(patches, 3)``. Where the noise
    spans a few codes (σ < 4 DN and a small patch), both tests are exact on the code lattice
    (:func:`_exact_p_values`): a patch of one code passes when that code is likely enough. Elsewhere the mean
    takes a z-test and the variance a χ² test whose degrees of freedom match the law's fourth moment
    (:func:`_variance_dof`; n − 1 for a normal law). The render's own Monte Carlo noise is left out of the
    prediction: at the spp the command line uses it is far below the sensor's (tests/rendering/test_imaging.py
    shows a correct model passing).
    """
    from scipy.stats import chi2, norm

    if model is not None:
        imaged = replace(imaged, imager=imager(model))
    mean, variance = predicted_patches(imaged, reference_ratio, grid)
    first, pmf = _patch_laws(imaged, reference_ratio, grid)
    scene = imaged.rendering.scene
    stats = [imaged.dn[rows, columns].reshape(-1, 3) for rows, columns in map(scene.patch_pixels,
                                                                               range(len(scene.patches)))]
    count = np.array([len(pixels) for pixels in stats])[:, None]
    rendered_mean = np.array([pixels.mean(axis=0) for pixels in stats])
    rendered_var = np.array([pixels.var(axis=0, ddof=1) for pixels in stats])
    constant = variance <= 0  # a clipped, noiseless pixel: it must equal its prediction exactly
    z = np.divide(rendered_mean - mean, np.sqrt(variance / count), out=np.zeros_like(mean), where=~constant)
    p_mean = np.where(constant, (np.abs(rendered_mean - mean) < 1e-9).astype(float), 2 * norm.sf(np.abs(z)))
    dof = np.array([[_variance_dof(pmf[i, k], first[i, k], mean[i, k], variance[i, k], len(pixels))
                     for k in range(3)] for i, pixels in enumerate(stats)])
    statistic = np.divide(dof * rendered_var, variance, out=np.zeros_like(mean), where=~constant)
    tail = np.minimum(chi2.cdf(statistic, dof), chi2.sf(statistic, dof))
    p_variance = np.where(constant, (rendered_var < 1e-9).astype(float), np.minimum(1.0, 2 * tail))
    exact = np.zeros(mean.shape, dtype=bool)
    for i, k in np.ndindex(mean.shape):
        found = None if np.isnan(first[i, k]) else _exact_p_values(pmf[i, k], first[i, k], stats[i][:, k])
        if found is not None:
            (p_mean[i, k], p_variance[i, k]), exact[i, k] = found, True
    level = 1.0 - (1.0 - alpha) ** (1.0 / (2 * mean.size))
    return ImagedValidation(imaged, rendered_mean, mean, np.sqrt(rendered_var), np.sqrt(variance), z, p_mean,
                            p_variance, level, exact)
