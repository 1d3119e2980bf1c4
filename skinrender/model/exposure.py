"""
Exposure
========

From light to expected electrons: photometry (illuminance, a Planckian
irradiance of a given illuminance, a Lambertian patch's radiance), the
expected photo- and dark electrons of a pixel, and the automatic exposure.

-   :data:`CONSTANT_K_M`, :func:`photopic_efficiency`: the CIE 1924 V(λ)
    and its maximum luminous efficacy.
-   :func:`illuminance_lux`, :func:`irradiance_planck`,
    :func:`radiance_lambertian`: photometry.
-   :func:`electrons_mean`, :func:`auto_exposure`: expected electrons and the
    exposure that puts a white at a fraction of the full well;
    :func:`auto_exposure_note`: what to say when the longest exposure stops it
    short of that fraction.
-   :class:`Imaging`, :func:`imaging`: an imager at an illuminance and an
    exposure, checked once, taken whole by what forms noisy pixels.

Units: wavelength nm, radiance W·m⁻²·sr⁻¹·nm⁻¹, irradiance W·m⁻²·nm⁻¹,
illuminance lx, time s, charge e⁻.

References
----------
-   :cite:`CIE1924` : CIE 1924 photopic luminous efficiency V(λ), as tabulated
    by colour-science (``SDS_LEFS_PHOTOPIC``), with K_m = 683.002 lm/W.
-   :cite:`EMVA1288` : European Machine Vision Association (2021). EMVA
    Standard 1288, Release 4.0 Linear: the photon count μ_p = A E t λ / (h c).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from ..constants import CONSTANT_C, CONSTANT_H
from ..errors import SkinrenderError
from ..hints import ArrayLike, NDArrayFloat
from ..spectra import WavelengthGrid, planck
from .imager import Imager, checked_array, checked_grid
from .imager import imager as imager_of

__all__ = [
    "CONSTANT_K_M",
    "AUTO_EXPOSURE_FRACTION",
    "Imaging",
    "imaging",
    "AUTO_EXPOSURE_MAX_S",
    "auto_exposure",
    "auto_exposure_note",
    "electrons_mean",
    "illuminance_lux",
    "irradiance_planck",
    "photopic_efficiency",
    "radiance_lambertian",
]

CONSTANT_K_M: float = 683.002
"""Maximum luminous efficacy for the CIE 1924 V(λ) table, lm/W (683 lm/W at
540 THz, referred to V's tabulated peak at 555 nm)."""


AUTO_EXPOSURE_FRACTION = 0.7
"""``auto`` exposure puts the calibration white's brightest channel at this share of the full well (every
user of :func:`auto_exposure` in the package: renders, faces, the noisy search and detection)."""

AUTO_EXPOSURE_MAX_S = 1.0 / 30.0
"""The longest automatic exposure, s: one frame of a 30 frames/s video camera, as the paper's 3-CCD cameras
were. Below the light that fills the well in that time, less light means fewer electrons and more noise."""


@lru_cache(maxsize=16)
def photopic_efficiency(grid: WavelengthGrid) -> NDArrayFloat:
    """
    CIE 1924 V(λ) on ``grid`` (nm), unitless, read-only.

    Interpolated linearly from colour-science's table (bundled:
    :func:`~skinrender.datasets.colour_science.photopic_v_cie1924`); 0 outside 360–830 nm.

    Examples
    --------
    >>> print(f"{photopic_efficiency(WavelengthGrid(555, 556, 1))[0]:.3f}")
    1.000
    """
    from ..datasets.colour_science import photopic_v_cie1924

    v = photopic_v_cie1924()
    values = np.interp(grid.wavelengths, v.wavelengths, v.values[0], left=0.0, right=0.0)
    values.flags.writeable = False
    return values


def illuminance_lux(spd: ArrayLike, grid: WavelengthGrid | str) -> NDArrayFloat:
    """
    Illuminance, lx, of a spectral irradiance: E_v = K_m Σ V(λ) E(λ) Δλ.

    Parameters
    ----------
    spd
        Spectral irradiance, W·m⁻²·nm⁻¹, shape ``(..., n)``, on ``grid``.
    grid
        The wavelength grid, nm (a :class:`WavelengthGrid` or ``START:END:STEP``).

    Returns
    -------
    :class:`numpy.ndarray`
        Illuminance, lx, shape ``(...)``.

    Examples
    --------
    >>> print(f"{illuminance_lux([1.0, 0.0], WavelengthGrid(555, 556, 1)):.3f} lx")  # K_m · V(555) · 1 nm
    683.002 lx
    """

    grid = checked_grid(grid)
    e = checked_array(spd, "spd", "W·m⁻²·nm⁻¹", grid=grid)
    return CONSTANT_K_M * np.sum(e * photopic_efficiency(grid), axis=-1) * grid.step


def irradiance_planck(temperature_K: ArrayLike, lux: ArrayLike, grid: WavelengthGrid | str) -> NDArrayFloat:
    """
    Planckian spectral irradiance at the chart, W·m⁻²·nm⁻¹, of illuminance ``lux``.

    Parameters
    ----------
    temperature_K, lux
        Colour temperature, K > 0, and illuminance, lx ≥ 0 (they broadcast).
    grid
        The wavelength grid, nm. A Lambertian patch of reflectance ρ then has
        radiance ρ E / π (:func:`radiance_lambertian`).

    Returns
    -------
    :class:`numpy.ndarray`
        Shape ``broadcast(temperature_K, lux) + (n,)``, W·m⁻²·nm⁻¹.

    Examples
    --------
    >>> grid = WavelengthGrid(400, 700, 5)
    >>> print(f"{illuminance_lux(irradiance_planck(2856, 500, grid), grid):.6f} lx")
    500.000000 lx
    """

    grid = checked_grid(grid)
    lux = checked_array(lux, "lux", "lx")
    shape = planck(grid.wavelengths, np.asarray(temperature_K, dtype=np.float64)[..., None])
    per_unit = illuminance_lux(shape, grid)
    if np.any(per_unit <= 0):
        raise SkinrenderError(f"grid {grid} carries no photopic weight, so no illuminance can be set")
    return shape * (lux / per_unit)[..., None]


def radiance_lambertian(reflectance: ArrayLike, irradiance: ArrayLike) -> NDArrayFloat:
    """
    Radiance of a Lambertian patch, L = ρ E / π, W·m⁻²·sr⁻¹·nm⁻¹.

    Parameters
    ----------
    reflectance
        ρ, fraction ≥ 0.
    irradiance
        E, W·m⁻²·nm⁻¹, broadcast against ``reflectance``.

    Examples
    --------
    >>> print(f"{radiance_lambertian(0.5, math.pi):.3f}")  # W·m⁻²·sr⁻¹·nm⁻¹
    0.500
    """
    rho = checked_array(reflectance, "reflectance", "(fraction)")
    return rho * checked_array(irradiance, "irradiance", "W·m⁻²·nm⁻¹") / math.pi


def electrons_mean(
    imager: str | Path | Imager, sensitivities: ArrayLike, radiance: ArrayLike, exposure_s: ArrayLike,
    grid: WavelengthGrid | str,
) -> NDArrayFloat:
    """
    Expected electrons per pixel and channel: photo-electrons plus dark electrons.

    Parameters
    ----------
    imager
        An :class:`Imager`, or a preset name or TOML path (:func:`~skinrender.model.imager.imager`).
    sensitivities
        R, G, B quantum-efficiency shapes on ``grid``, shape ``(3, n)``, any
        scale; QE_k(λ) = qe_peak s_k(λ) / max s_k. (A curve that weights
        energy, as Eq. 1's does, is a QE shape once divided by λ.)
    radiance
        Scene spectral radiance, W·m⁻²·sr⁻¹·nm⁻¹, shape ``(..., n)``.
    exposure_s
        Exposure, s ≥ 0, broadcast against ``radiance``'s leading axes.
    grid
        The wavelength grid, nm; Δλ is its step.

    Returns
    -------
    :class:`numpy.ndarray`
        Mean electrons, e⁻, shape ``(..., 3)``.

    Notes
    -----
    On axis the sensor-plane irradiance is E_s = π τ L / (4 N²), W·m⁻²·nm⁻¹;
    photons per second and nm are E_s A_pix λ / (h c) with λ in m and
    A_pix = pixel_um² in m²; electrons are t Σ_λ QE_k(λ) photons(λ) Δλ +
    dark_current t. No cos⁴ fall-off, vignetting or PRNU.

    Examples
    --------
    A 1 nm band at 555 nm (the grid 555–556 nm, radiance 0 at 556 nm) of radiance 0.01 W·m⁻²·sr⁻¹·nm⁻¹, f/2.8, τ = 0.9,
    5 µm pixel, QE 0.5, 10 ms: E_s = π·0.9·0.01 / (4·2.8²) = 9.016050e-4
    W·m⁻²·nm⁻¹; on the pixel 9.016050e-4 · (5e-6 m)² = 2.254013e-14 W·nm⁻¹;
    h c / λ = 6.62607015e-34 · 299792458 / 555e-9 = 3.579182e-19 J; photons
    2.254013e-14 / 3.579182e-19 · 1 nm · 0.01 s = 629.756; electrons 0.5 ·
    629.756 = 314.878.

    >>> im = Imager(pixel_um=5.0, f_number=2.8, transmittance=0.9, qe_peak=0.5, full_well_e=1e5,
    ...             read_noise_e=0.0, dark_current_e_per_s=0.0, gain_dn_per_e=1.0, bits=16,
    ...             black_level_dn=0.0)
    >>> e = electrons_mean(im, np.ones((3, 2)), [0.01, 0.0], 0.01, WavelengthGrid(555, 556, 1))
    >>> print(f"{e[0]:.3f} e-")
    314.878 e-
    """

    im, grid = imager_of(imager), checked_grid(grid)
    s = checked_array(sensitivities, "sensitivities", "(any scale)")
    if s.shape != (3, grid.size):
        raise SkinrenderError(f"sensitivities must have shape (3, {grid.size}) on grid {grid}, got {s.shape}")
    peak = s.max(axis=1)
    if np.any(peak <= 0):
        raise SkinrenderError("sensitivities: every channel (R, G, B) needs a positive peak")
    radiance = checked_array(radiance, "radiance", "W·m⁻²·sr⁻¹·nm⁻¹", grid=grid)
    t = checked_array(exposure_s, "exposure_s", "s")
    optics = math.pi * im.transmittance / (4.0 * im.f_number**2)  # E_s / L, sr
    photons = optics * (im.pixel_um * 1e-6) ** 2 * grid.wavelengths * 1e-9 / (CONSTANT_H * CONSTANT_C)
    rate = (radiance * photons) @ (im.qe_peak * s / peak[:, None]).T * grid.step  # e⁻/s, (..., 3)
    return (rate + im.dark_current_e_per_s) * t[..., None]


def auto_exposure(
    imager: str | Path | Imager, white_electrons_per_s: ArrayLike, fraction: float = 0.7,
    longest_s: float | None = None,
) -> float | NDArrayFloat:
    """
    The exposure, s, putting a white's brightest channel at ``fraction`` of the full well.

    Parameters
    ----------
    imager
        An :class:`Imager`, a preset name or a TOML path.
    white_electrons_per_s
        The white's electron rate per channel, e⁻/s, shape ``(..., 3)``, dark
        current included (as :func:`electrons_mean` gives it for
        ``exposure_s=1``).
    fraction
        Target share of ``full_well_e``, in (0, 1] (0.7 by default).
    longest_s
        The longest exposure allowed, s (``None``: no limit); the command line
        uses :data:`AUTO_EXPOSURE_MAX_S`, a video frame.

    Returns
    -------
    float or :class:`numpy.ndarray`
        ``fraction · full_well_e / max_k rate_k``, s, a float or shape ``(...)``.

    Examples
    --------
    >>> auto_exposure("sony-imx174", [1e5, 2e5, 5e4], fraction=0.5)  # s: 0.5 · 32691 e⁻ / 2e5 e⁻/s
    0.0817275
    """

    im = imager_of(imager)
    rate = checked_array(white_electrons_per_s, "white_electrons_per_s", "e⁻/s")
    if rate.ndim == 0 or rate.shape[-1] != 3:
        raise SkinrenderError(f"white_electrons_per_s must have 3 channels last, got shape {rate.shape}")
    if isinstance(fraction, bool) or not isinstance(fraction, numbers.Real) or not 0 < fraction <= 1:
        raise SkinrenderError(f"fraction must be a number in (0, 1], got {fraction!r}")
    brightest = rate.max(axis=-1)
    if np.any(brightest <= 0):
        raise SkinrenderError("white_electrons_per_s: the white gives no electrons in any channel")
    exposure = fraction * im.full_well_e / brightest
    if longest_s is not None:  # a video camera's auto-exposure stops at its frame time: dim light stays dim
        if not (np.isfinite(longest_s) and longest_s > 0):
            raise SkinrenderError(f"longest_s must be a finite number of seconds > 0, got {longest_s!r}")
        exposure = np.minimum(exposure, longest_s)
    return float(exposure) if exposure.ndim == 0 else exposure


def auto_exposure_note(
    imager: str | Path | Imager, white_electrons_per_s: ArrayLike, fraction: float, longest_s: float,
) -> str | None:
    """
    A note where :func:`auto_exposure`'s longest exposure binds, ``None`` where the white reaches its target.

    Parameters
    ----------
    imager
        An :class:`Imager`, a preset name or a TOML path.
    white_electrons_per_s
        The white's electron rate per channel, e⁻/s, ``(..., 3)`` (one white per row, e.g. per calibration).
    fraction, longest_s
        The target share of the full well and the longest exposure, s, given to :func:`auto_exposure`.

    Returns
    -------
    str or None
        The cap (ms), the target share and the share of the full well the brightest channel reaches (the
        lowest over the rows), and how many of the rows were capped.

    Examples
    --------
    >>> print(auto_exposure_note("sony-imx174", [1e5, 3e5, 2e5], 0.7, 1 / 30))  # 0.7 of the well in 76 ms
    auto exposure capped at the longest exposure, 33.3 ms: the white's brightest channel reaches 0.306 of the full well, not the 0.7 target (1 of 1 whites)
    >>> auto_exposure_note("sony-imx174", [1e6, 3e6, 2e6], 0.7, 1 / 30) is None  # 7.6 ms: not capped
    True
    """
    im = imager_of(imager)
    exposure = np.atleast_1d(auto_exposure(im, white_electrons_per_s, fraction, longest_s))
    brightest = np.atleast_2d(checked_array(white_electrons_per_s, "white_electrons_per_s", "e⁻/s")).max(axis=-1)
    reached = brightest.reshape(exposure.shape) * exposure / im.full_well_e
    capped = reached < fraction * (1 - 1e-9)
    if not capped.any():
        return None
    return (f"auto exposure capped at the longest exposure, {longest_s * 1e3:.3g} ms: the white's brightest channel "
            f"reaches {reached.min():.3g} of the full well, not the {fraction:g} target "
            f"({int(capped.sum())} of {capped.size} whites)")


@dataclass(frozen=True)
class Imaging:
    """
    An imager over a chart lit at an illuminance and exposed for a time: what noisy pixels are formed under
    (build it checked with :func:`imaging`).

    Attributes
    ----------
    imager
        The :class:`~skinrender.model.imager.Imager`.
    illuminance_lux
        The chart's illuminance, lx > 0.
    exposure
        Exposure, s > 0, or ``"auto"`` (:func:`auto_exposure`: the white under the calibration light at
        :data:`AUTO_EXPOSURE_FRACTION` of the full well).
    """

    imager: Imager
    illuminance_lux: float
    exposure: float | str = "auto"


def _positive(value: object, name: str, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not math.isfinite(value) or value <= 0:
        raise SkinrenderError(f"{name} must be a finite number > 0, {unit}, got {value!r}")
    return float(value)


def imaging(imager_: str | Path | Imager, illuminance_lux: float, exposure: float | str = "auto") -> Imaging:
    """
    A checked :class:`Imaging`: ``imager_`` an :class:`~skinrender.model.imager.Imager`, a preset name or a TOML
    path; ``illuminance_lux`` (lx) and ``exposure`` (s) finite and > 0, or ``exposure`` ``auto`` (any case).

    Raises
    ------
    SkinrenderError
        One line naming the argument (``illuminance_lux``, ``exposure``, the imager).

    Examples
    --------
    >>> setting = imaging("sony-imx174", 500, "Auto")
    >>> setting.imager.name, setting.illuminance_lux, setting.exposure
    ('sony-imx174', 500.0, 'auto')
    """
    im = imager_of(imager_)
    lux = _positive(illuminance_lux, "illuminance_lux", "lx")
    if isinstance(exposure, str) and exposure.strip().lower() == "auto":
        return Imaging(im, lux, "auto")
    return Imaging(im, lux, _positive(exposure, "exposure", "s (or 'auto')"))
