"""
Imager
======

The image sensor and optics behind the three spectral channels: scene radiance → electrons per
pixel → digital numbers (DN), with the noise, saturation and quantisation of the EMVA 1288
linear camera model, as analytic mean and variance and as seeded Monte Carlo frames.

-   :class:`Imager`, :func:`imager`, :func:`list_imagers`: parameters and presets
    (``datasets/resources/imagers/*.toml``, found from this file, read on first use).
-   :func:`illuminance_lux`, :func:`irradiance_planck`, :func:`radiance_lambertian`: photometry.
-   :func:`electrons_mean`, :func:`auto_exposure`: expected electrons and exposure.
-   :func:`statistics_dn`, :func:`signal_dn`, :func:`simulate_dn`: output in DN.
-   :func:`ncc_covariance`: the noise carried to white-balanced NCC chromaticities.

Units: wavelength nm, radiance W·m⁻²·sr⁻¹·nm⁻¹, irradiance W·m⁻²·nm⁻¹, illuminance lx, time s,
charge e⁻ (electrons), output DN, system gain K in DN/e⁻.

References
----------
-   :cite:`EMVA1288` : European Machine Vision Association (2021). EMVA Standard 1288, Standard
    for Characterization of Image Sensors and Cameras, Release 4.0 Linear: the linear model
    μ_y = μ_y.dark + K μ_e, σ_y² = K² σ_d² + K² μ_e + σ_q², σ_q² = 1/12 DN², and saturation.
-   :cite:`CIE1924` : CIE 1924 photopic luminous efficiency V(λ), as tabulated by colour-science
    (``SDS_LEFS_PHOTOPIC``), with K_m = 683.002 lm/W.
-   :cite:`SonyICX418` : Sony, ICX418AKB/ALB/AKL datasheets, diagonal 8 mm (type 1/2) interline
    CCD, 768 × 494 pixels, unit cell 8.4 µm × 9.8 µm (preset ``sony-icx418``).
-   :cite:`Herb2016` : F. Herb, "Sony Exmor Sensoren: Datenblattrekonstruktion IMX157",
    fhotolab.fherb.de, 2016: EMVA 1288 figures of the Sony IMX174 (attributed to Point Grey's
    Grasshopper3 GS3-U3-23S6M data; preset ``sony-imx174``). Each preset file states its
    sources and which values are assumed.
"""

from __future__ import annotations

import math
import numbers
import tomllib
from dataclasses import dataclass, fields
from functools import lru_cache
from pathlib import Path

import numpy as np
from scipy.special import ndtr

# Absolute imports, so that the module also imports on its own (doctests).
from skinrender.constants import CONSTANT_C, CONSTANT_H
from skinrender.errors import SkinrenderError
from skinrender.hints import ArrayLike, NDArrayFloat
from skinrender.spectra import WavelengthGrid, planck

__all__ = [
    "CONSTANT_K_M", "ROOT_RESOURCES_IMAGERS", "Imager", "auto_exposure", "electrons_mean", "illuminance_lux",
    "imager", "irradiance_planck", "list_imagers", "ncc_covariance", "radiance_lambertian", "signal_dn",
    "simulate_dn", "statistics_dn",
]

CONSTANT_K_M: float = 683.002
"""Maximum luminous efficacy for the CIE 1924 V(λ) table, lm/W (683 lm/W at 540 THz, referred to
V's tabulated peak at 555 nm)."""

ROOT_RESOURCES_IMAGERS: Path = Path(__file__).resolve().parents[1] / "datasets" / "resources" / "imagers"
"""The folder of the imager presets, one TOML file each."""

_WINDOW_SIGMA = 8.0  # exact sums over codes reach ±8 σ: the normal tail beyond is < 1e-15
_SWITCH_DN = 4.0  # σ ≥ 4 DN: closed form, whose Euler–Maclaurin remainder is < 1e-5 DN
_POISSON_CAP = 1e18  # numpy's Poisson limit; any larger mean saturates every real pixel
_NUMBER_FIELDS = {  # field: (unit, lower bound, lower bound allowed, upper bound)
    "pixel_um": ("µm", 0.0, False, math.inf), "f_number": ("(dimensionless)", 0.0, False, math.inf),
    "transmittance": ("(fraction)", 0.0, False, 1.0), "qe_peak": ("(fraction)", 0.0, False, 1.0),
    "full_well_e": ("e⁻", 0.0, False, math.inf), "read_noise_e": ("e⁻ rms", 0.0, True, math.inf),
    "dark_current_e_per_s": ("e⁻/s", 0.0, True, math.inf), "gain_dn_per_e": ("DN/e⁻", 0.0, False, math.inf),
    "black_level_dn": ("DN", 0.0, True, math.inf),
}


@dataclass(frozen=True, kw_only=True)
class Imager:
    """
    An image sensor behind a lens: the parameters of the noise model, validated.

    Parameters
    ----------
    name, source : str
        Preset name and the citation of its values.
    pixel_um, f_number, transmittance : float
        Pixel pitch, µm (square pixel) > 0; lens f-number N > 0; optics transmittance τ in (0, 1].
    qe_peak : float
        Quantum efficiency at each channel's sensitivity peak, in (0, 1].
    full_well_e, read_noise_e, dark_current_e_per_s : float
        Saturation capacity, e⁻ > 0; temporal dark noise, e⁻ rms ≥ 0; dark current, e⁻/s ≥ 0.
    gain_dn_per_e, bits, black_level_dn
        System gain K, DN/e⁻ > 0; ADC bits, an integer 1–32 (codes 0 … 2^bits − 1); offset, DN, in
        [0, 2^bits − 1].

    Examples
    --------
    >>> Imager(pixel_um=5.0, f_number=2.8, transmittance=0.9, qe_peak=0.6, full_well_e=2e4,
    ...        read_noise_e=5.0, dark_current_e_per_s=1.0, gain_dn_per_e=0.2, bits=12,
    ...        black_level_dn=10.0).max_dn
    4095
    """

    name: str = "custom"
    source: str = "user-defined"
    pixel_um: float
    f_number: float
    transmittance: float
    qe_peak: float
    full_well_e: float
    read_noise_e: float
    dark_current_e_per_s: float
    gain_dn_per_e: float
    bits: int
    black_level_dn: float

    def __post_init__(self) -> None:
        for field in ("name", "source"):
            if not isinstance(getattr(self, field), str) or not getattr(self, field).strip():
                raise SkinrenderError(f"{field} must be a non-empty string, got {getattr(self, field)!r}")
        for field, (unit, low, closed, high) in _NUMBER_FIELDS.items():
            value = getattr(self, field)
            if isinstance(value, bool) or not isinstance(value, numbers.Real):
                raise SkinrenderError(f"{field} must be a number, {unit}, got {value!r}")
            value = float(value)
            if not (math.isfinite(value) and (value >= low if closed else value > low) and value <= high):
                bounds = f"{'[' if closed else '('}{low:g}, {'∞)' if math.isinf(high) else f'{high:g}]'}"
                raise SkinrenderError(f"{field} must be a finite number in {bounds} {unit}, got {value!r}")
            object.__setattr__(self, field, value)
        if not _is_int(self.bits) or not 1 <= self.bits <= 32:
            raise SkinrenderError(f"bits must be an integer from 1 to 32, got {self.bits!r}")
        object.__setattr__(self, "bits", int(self.bits))
        if self.black_level_dn > self.max_dn:
            raise SkinrenderError(
                f"black_level_dn must be ≤ 2**bits - 1 = {self.max_dn} DN, got {self.black_level_dn:g}"
            )

    @property
    def max_dn(self) -> int:
        """The largest output code, 2^bits − 1, DN."""
        return 2**self.bits - 1


def _read_imager_toml(path: Path) -> Imager:
    """One imager file; every problem names the file and the field."""
    try:
        with open(path, "rb") as handle:
            data = tomllib.load(handle)
    except OSError as error:
        raise SkinrenderError(f"imager file {path}: cannot be read ({error.strerror})") from None
    except tomllib.TOMLDecodeError as error:
        raise SkinrenderError(f"imager file {path}: not valid TOML ({error})") from None
    names = [field.name for field in fields(Imager)]
    for key in data:
        if key not in names:
            raise SkinrenderError(f"imager file {path}: unknown field {key!r} (expected {', '.join(names)})")
    for key in names:
        if key not in data:
            raise SkinrenderError(f"imager file {path}: missing field {key!r}")
    try:
        return Imager(**data)
    except SkinrenderError as error:
        raise SkinrenderError(f"imager file {path}: {error}") from None


@lru_cache(maxsize=1)
def _presets() -> dict[str, Imager]:
    items = map(_read_imager_toml, sorted(ROOT_RESOURCES_IMAGERS.glob("*.toml")))
    return {item.name.lower(): item for item in items}


def imager(spec: str | Path | Imager) -> Imager:
    """
    An :class:`Imager` from a preset name (any case), a TOML file path or an :class:`Imager`.

    Examples
    --------
    >>> imager("SONY-IMX174").full_well_e  # e⁻
    32691.0
    """

    if isinstance(spec, Imager):
        return spec
    if not isinstance(spec, (str, Path)):
        raise SkinrenderError(f"imager must be a preset name, a TOML path or an Imager, got {spec!r}")
    presets = _presets()
    if isinstance(spec, str) and spec.strip().lower() in presets:
        return presets[spec.strip().lower()]
    if Path(spec).is_file():
        return _read_imager_toml(Path(spec))
    names = ", ".join(item.name for item in presets.values())
    raise SkinrenderError(f"imager {str(spec)!r} is neither a preset ({names}) nor an existing TOML file")


def list_imagers() -> list[dict]:
    """The presets: name, source, pixel_um (µm), full_well_e, read_noise_e (e⁻), gain_dn_per_e, bits."""
    keys = ("name", "source", "pixel_um", "full_well_e", "read_noise_e", "gain_dn_per_e", "bits")
    return [{key: getattr(item, key) for key in keys} for item in _presets().values()]


def _is_int(value: object) -> bool:
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


def _grid(grid: WavelengthGrid | str) -> WavelengthGrid:
    if isinstance(grid, WavelengthGrid):
        return grid
    if isinstance(grid, str):
        return WavelengthGrid.parse(grid)
    raise SkinrenderError(f"grid must be a WavelengthGrid or START:END:STEP in nm, got {grid!r}")


def _array(
    values: ArrayLike, name: str, unit: str, low: float | None = 0.0, grid: WavelengthGrid | None = None
) -> NDArrayFloat:
    """A finite float array, ≥ ``low`` unless None, with ``grid.size`` samples last if a grid is given."""
    try:
        out = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise SkinrenderError(f"{name} must be an array of numbers, {unit}, got {values!r}") from None
    if not np.all(np.isfinite(out)) or (low is not None and np.any(out < low)):
        raise SkinrenderError(f"{name} must be finite{'' if low is None else f' and ≥ {low:g}'}, {unit}")
    if grid is not None and (out.ndim == 0 or out.shape[-1] != grid.size):
        raise SkinrenderError(f"{name} must have {grid.size} samples (grid {grid}) last, got {out.shape}")
    return out


@lru_cache(maxsize=16)
def _photopic(grid: WavelengthGrid) -> NDArrayFloat:
    from colour.colorimetry import SDS_LEFS_PHOTOPIC  # a heavy import, only when needed

    sd = SDS_LEFS_PHOTOPIC["CIE 1924 Photopic Standard Observer"]
    values = np.interp(grid.wavelengths, sd.wavelengths, sd.values, left=0.0, right=0.0)
    values.flags.writeable = False
    return values


def illuminance_lux(spd: ArrayLike, grid: WavelengthGrid | str) -> NDArrayFloat:
    """
    Illuminance, lx, shape ``(...)``, of a spectral irradiance: E_v = K_m Σ V(λ) E(λ) Δλ.

    Parameters
    ----------
    spd, grid
        Spectral irradiance, W·m⁻²·nm⁻¹, shape ``(..., n)``, on the grid (nm); V(λ) (CIE 1924) is
        interpolated linearly to the grid and is 0 outside 360–830 nm.

    Examples
    --------
    >>> print(f"{illuminance_lux([1.0], WavelengthGrid(555, 555, 1)):.3f} lx")  # K_m · V(555) · 1 nm
    683.002 lx
    """

    grid = _grid(grid)
    e = _array(spd, "spd", "W·m⁻²·nm⁻¹", grid=grid)
    return CONSTANT_K_M * np.sum(e * _photopic(grid), axis=-1) * grid.step


def irradiance_planck(temperature_K: ArrayLike, lux: ArrayLike, grid: WavelengthGrid | str) -> NDArrayFloat:
    """
    Planckian spectral irradiance at the chart, W·m⁻²·nm⁻¹, shape ``(..., n)``, of illuminance ``lux``.

    Parameters
    ----------
    temperature_K, lux, grid
        Colour temperature, K > 0, and illuminance, lx ≥ 0 (they broadcast); the grid, nm. A
        Lambertian patch of reflectance ρ then has radiance ρ E / π (:func:`radiance_lambertian`).

    Examples
    --------
    >>> grid = WavelengthGrid(400, 700, 5)
    >>> print(f"{illuminance_lux(irradiance_planck(2856, 500, grid), grid):.6f} lx")
    500.000000 lx
    """

    grid = _grid(grid)
    lux = _array(lux, "lux", "lx")
    shape = planck(grid.wavelengths, np.asarray(temperature_K, dtype=np.float64)[..., None])
    per_unit = illuminance_lux(shape, grid)
    if np.any(per_unit <= 0):
        raise SkinrenderError(f"grid {grid} carries no photopic weight, so no illuminance can be set")
    return shape * (lux / per_unit)[..., None]


def radiance_lambertian(reflectance: ArrayLike, irradiance: ArrayLike) -> NDArrayFloat:
    """Radiance, W·m⁻²·sr⁻¹·nm⁻¹, of a Lambertian patch: L = ρ E / π for reflectance ρ (fraction ≥ 0)
    and irradiance E (W·m⁻²·nm⁻¹), broadcast against each other."""
    rho = _array(reflectance, "reflectance", "(fraction)")
    return rho * _array(irradiance, "irradiance", "W·m⁻²·nm⁻¹") / math.pi


def electrons_mean(
    imager: str | Path | Imager, sensitivities: ArrayLike, radiance: ArrayLike, exposure_s: ArrayLike,
    grid: WavelengthGrid | str,
) -> NDArrayFloat:
    """
    Expected electrons per pixel and channel: photo-electrons plus dark electrons.

    Parameters
    ----------
    imager
        An :class:`Imager`, or a preset name or TOML path (:func:`imager`).
    sensitivities
        R, G, B sensitivities on ``grid``, shape ``(3, n)``, any scale; QE_k = qe_peak s_k / max s_k.
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
    On axis the sensor-plane irradiance is E_s = π τ L / (4 N²), W·m⁻²·nm⁻¹; photons per second and
    nm are E_s A_pix λ / (h c) with λ in m and A_pix = pixel_um² in m²; electrons are
    t Σ_λ QE_k(λ) photons(λ) Δλ + dark_current t. No cos⁴ fall-off, vignetting or PRNU.

    Examples
    --------
    A 1 nm band at 555 nm of radiance 0.01 W·m⁻²·sr⁻¹·nm⁻¹, f/2.8, τ = 0.9, 5 µm pixel, QE 0.5,
    10 ms: E_s = π·0.9·0.01 / (4·2.8²) = 9.016050e-4 W·m⁻²·nm⁻¹; on the pixel 9.016050e-4 ·
    (5e-6 m)² = 2.254013e-14 W·nm⁻¹; h c / λ = 6.62607015e-34 · 299792458 / 555e-9 = 3.579182e-19 J;
    photons 2.254013e-14 / 3.579182e-19 · 1 nm · 0.01 s = 629.756; electrons 0.5 · 629.756 = 314.878.

    >>> im = Imager(pixel_um=5.0, f_number=2.8, transmittance=0.9, qe_peak=0.5, full_well_e=1e5,
    ...             read_noise_e=0.0, dark_current_e_per_s=0.0, gain_dn_per_e=1.0, bits=16,
    ...             black_level_dn=0.0)
    >>> e = electrons_mean(im, np.ones((3, 1)), [0.01], 0.01, WavelengthGrid(555, 555, 1))
    >>> print(f"{e[0]:.3f} e-")
    314.878 e-
    """

    im, grid = _as_imager(imager), _grid(grid)
    s = _array(sensitivities, "sensitivities", "(any scale)")
    if s.shape != (3, grid.size):
        raise SkinrenderError(f"sensitivities must have shape (3, {grid.size}) on grid {grid}, got {s.shape}")
    peak = s.max(axis=1)
    if np.any(peak <= 0):
        raise SkinrenderError("sensitivities: every channel (R, G, B) needs a positive peak")
    radiance = _array(radiance, "radiance", "W·m⁻²·sr⁻¹·nm⁻¹", grid=grid)
    t = _array(exposure_s, "exposure_s", "s")
    optics = math.pi * im.transmittance / (4.0 * im.f_number**2)  # E_s / L, sr
    photons = optics * (im.pixel_um * 1e-6) ** 2 * grid.wavelengths * 1e-9 / (CONSTANT_H * CONSTANT_C)
    rate = (radiance * photons) @ (im.qe_peak * s / peak[:, None]).T * grid.step  # e⁻/s, (..., 3)
    return (rate + im.dark_current_e_per_s) * t[..., None]


def auto_exposure(
    imager: str | Path | Imager, white_electrons_per_s: ArrayLike, fraction: float = 0.7
) -> float | NDArrayFloat:
    """
    The exposure, s, putting the white's brightest channel at ``fraction`` (in (0, 1]) of full well.

    ``white_electrons_per_s``: the white's electron rate per channel, e⁻/s, shape ``(..., 3)``, dark
    current included (as :func:`electrons_mean` gives it for ``exposure_s=1``). Returns
    ``fraction · full_well_e / max_k rate_k``, s, a float or shape ``(...)``.
    """

    im = _as_imager(imager)
    rate = _array(white_electrons_per_s, "white_electrons_per_s", "e⁻/s")
    if rate.ndim == 0 or rate.shape[-1] != 3:
        raise SkinrenderError(f"white_electrons_per_s must have 3 channels last, got shape {rate.shape}")
    if isinstance(fraction, bool) or not isinstance(fraction, numbers.Real) or not 0 < fraction <= 1:
        raise SkinrenderError(f"fraction must be a number in (0, 1], got {fraction!r}")
    brightest = rate.max(axis=-1)
    if np.any(brightest <= 0):
        raise SkinrenderError("white_electrons_per_s: the white gives no electrons in any channel")
    exposure = fraction * im.full_well_e / brightest
    return float(exposure) if exposure.ndim == 0 else exposure


def _as_imager(value: str | Path | Imager) -> Imager:
    return imager(value)  # the public functions' parameter named ``imager`` hides the function


def _moments_closed(m: NDArrayFloat, s: NDArrayFloat, low: float, high: float) -> tuple[NDArrayFloat, ...]:
    """Normal N(m, s²) censored at the codes low, high, plus the Euler–Maclaurin rounding terms."""
    za, zb = (low - m) / s, (high - m) / s
    below, above = ndtr(za), ndtr(-zb)
    inside = np.maximum(1.0 - below - above, 0.0)
    fa, fb = np.exp(-0.5 * za**2) / math.sqrt(2 * math.pi), np.exp(-0.5 * zb**2) / math.sqrt(2 * math.pi)
    mz = za * below + zb * above + fa - fb  # E[clip(Z, za, zb)], Z standard normal
    vz = ((za - mz) ** 2 * below + (zb - mz) ** 2 * above + (1 + mz**2) * inside
          - 2 * mz * (fa - fb) + za * fa - zb * fb)  # Var[clip(Z, za, zb)]
    c1 = (fb - fa) / (24 * s)
    variance = s**2 * vz + inside / 12 + ((zb - mz) * fb - (za - mz) * fa) / 12 - c1**2
    # m + s·mz, written from the code U when m lies beyond it (m may then dwarf U in float64)
    beyond = high + s * (za * below - zb * ndtr(zb) + fa - fb)
    return np.where(m > high, beyond, m + s * mz) + c1, np.maximum(variance, 0.0)


def _moments_exact(m: NDArrayFloat, s: NDArrayFloat, low: float, high: float) -> tuple[NDArrayFloat, ...]:
    """Mean and variance of clip(round(N(m, s²)), low, high), summed code by code."""
    start = np.clip(np.floor(m - _WINDOW_SIGMA * s), low, high)
    steps = np.arange(math.ceil(2 * _WINDOW_SIGMA * s.max(initial=0.0)) + 2, dtype=np.float64)
    code = start[:, None] + steps
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        z = (m[:, None] - code - 0.5) / s[:, None]
    z = np.where(s[:, None] > 0, z, np.where(m[:, None] > code + 0.5, np.inf, -np.inf))
    exceed = np.where(code < high, ndtr(z), 0.0)  # P(DN > code); E[d] = Σ P(d > j), E[d²] = Σ (2j+1) P(d > j)
    shift = exceed.sum(axis=1)
    return start + shift, np.maximum(((2 * steps + 1) * exceed).sum(axis=1) - shift**2, 0.0)


def statistics_dn(imager: str | Path | Imager, electrons_mean: ArrayLike) -> tuple[NDArrayFloat, ...]:
    """
    The analytic mean, DN, and variance, DN², of the pixels :func:`simulate_dn` draws.

    Parameters
    ----------
    imager, electrons_mean
        An :class:`Imager` (or preset name, TOML path); expected electrons, photo plus dark, e⁻ ≥ 0.

    Returns
    -------
    tuple of :class:`numpy.ndarray`
        ``(mean, variance)``, DN and DN², each of ``electrons_mean``'s shape.

    Notes
    -----
    The charge X is taken as normal, mean μ, variance μ + σ_r² (Poisson shot noise including dark,
    read noise in quadrature). DN = clip(round(K clip(X, 0, μ_sat) + b), 0, 2^bits − 1) equals
    clip(round(Y), L, U) for Y = K X + b ~ N(m, s²), L = round(b), U = min(round(K μ_sat + b),
    2^bits − 1). For s < 4 DN its moments are summed exactly over the codes; above, they are the
    normal censored at L and U plus the Euler–Maclaurin terms of the rounding (remainder < 1e-5 DN),
    which give the quantisation variance 1/12 DN² weighted by the unclipped probability. Far from
    L and U: mean K μ + b, variance K² (μ + σ_r²) + 1/12. A saturated pixel sits on the single code
    U: variance 0. The normal approximation ignores the Poisson skew (μ^-1/2) and the lattice of a
    count without read noise: expect errors up to ~1e-2 DN where a few-electron signal is clipped
    at 0 e⁻ or σ_r ≪ 1 e⁻ (against 200 000-pixel Monte Carlo runs; elsewhere within their error).

    Examples
    --------
    >>> mean, var = statistics_dn("sony-imx174", [1e4, 1e6])  # K = 0.1225 DN/e⁻, b = 16 DN
    >>> print(f"{mean[0]:.2f} {var[0]:.2f} | {mean[1]:.0f} {var[1]:.0f}")
    1241.00 150.85 | 4021 0
    """

    im = _as_imager(imager)
    mu = np.minimum(_array(electrons_mean, "electrons_mean", "e⁻"), _POISSON_CAP)
    m = (im.gain_dn_per_e * mu + im.black_level_dn).ravel()
    s = (im.gain_dn_per_e * np.sqrt(mu + im.read_noise_e**2)).ravel()
    low = float(np.rint(im.black_level_dn))
    high = float(min(np.rint(im.gain_dn_per_e * im.full_well_e + im.black_level_dn), im.max_dn))
    mean, variance = np.empty_like(m), np.empty_like(m)
    free = (m - low > _WINDOW_SIGMA * s) & (high - m > _WINDOW_SIGMA * s) & (s >= _SWITCH_DN)
    mean[free], variance[free] = m[free], s[free] ** 2 + 1 / 12  # unclipped: the linear model
    wide = (s >= _SWITCH_DN) & ~free
    with np.errstate(over="ignore", under="ignore"):
        mean[wide], variance[wide] = _moments_closed(m[wide], s[wide], low, high)
    narrow = np.flatnonzero(s < _SWITCH_DN)
    narrow = narrow[np.argsort(s[narrow], kind="stable")]  # chunks of like σ need like windows
    for chunk in np.array_split(narrow, max(1, narrow.size // 65536)):  # bounded memory
        mean[chunk], variance[chunk] = _moments_exact(m[chunk], s[chunk], low, high)
    return mean.reshape(mu.shape), variance.reshape(mu.shape)


def signal_dn(imager: str | Path | Imager, electrons_mean: ArrayLike) -> NDArrayFloat:
    """The analytic mean output, DN, for ``electrons_mean`` e⁻ (:func:`statistics_dn`'s mean)."""
    return statistics_dn(imager, electrons_mean)[0]


def _generator(rng_or_seed: np.random.Generator | int) -> np.random.Generator:
    if isinstance(rng_or_seed, np.random.Generator):
        return rng_or_seed
    if _is_int(rng_or_seed) and 0 <= rng_or_seed < 2**32:
        return np.random.default_rng(int(rng_or_seed))
    raise SkinrenderError(
        f"rng_or_seed must be a numpy Generator or an integer seed in [0, 2**32), got {rng_or_seed!r}"
    )


def simulate_dn(
    imager: str | Path | Imager, electrons_mean: ArrayLike, rng_or_seed: np.random.Generator | int
) -> NDArrayFloat:
    """
    One noisy frame, DN, for the expected electrons ``electrons_mean`` (e⁻ ≥ 0, any shape).

    Poisson(μ) electrons (shot noise with dark) + Normal(0, σ_r²) read noise → clip to
    [0, full_well_e] e⁻ → × K + black level → round to the nearest code (ties to even) → clip to
    [0, 2^bits − 1]. Returns integer codes as floats, of ``electrons_mean``'s shape; deterministic
    for a seed (an int in [0, 2³²)) or a Generator's state.

    Examples
    --------
    >>> [int(v) for v in simulate_dn("sony-imx174", np.full(3, 1e6), 7)]  # saturated
    [4021, 4021, 4021]
    """

    im = _as_imager(imager)
    mu = _array(electrons_mean, "electrons_mean", "e⁻")
    rng = _generator(rng_or_seed)
    charge = rng.poisson(np.minimum(mu, _POISSON_CAP)) + rng.normal(0.0, im.read_noise_e, mu.shape)
    volts = im.gain_dn_per_e * np.clip(charge, 0.0, im.full_well_e) + im.black_level_dn
    return np.clip(np.rint(volts), 0.0, float(im.max_dn))


def ncc_covariance(mean: ArrayLike, cov_or_var: ArrayLike, gains: ArrayLike) -> NDArrayFloat:
    """
    Covariance of the NCC chromaticities of white-balanced channels, by first-order propagation.

    Parameters
    ----------
    mean
        Channel means x (black level subtracted), DN, shape ``(..., 3)``.
    cov_or_var
        Their variances, DN², shape ``(..., 3)`` (independent channels), or covariance ``(..., 3, 3)``.
    gains
        White-balance gains g_k > 0 (Eq. 4 style, out_k = g_k x_k), output units per DN, ``(..., 3)``.

    Returns
    -------
    :class:`numpy.ndarray`
        Covariance of (r, g, b) = out / Σ out (unitless), shape ``(..., 3, 3)``; rows sum to 0.

    Notes
    -----
    J_ij = ∂c_i/∂x_j = (g_j / S)(δ_ij − c_i) with S = Σ g_k x_k, and Σ_c = J Σ_x Jᵀ; the neglected
    terms are of relative order (σ/x)².

    Examples
    --------
    >>> cov = ncc_covariance([100.0, 100.0, 100.0], [100.0, 100.0, 100.0], [1, 1, 1])
    >>> print(f"{cov[0, 0]:.7f} {cov[0, 1]:.7f}")  # 100/300² · (4/9 + 2/9) and · (−1/3)
    0.0007407 -0.0003704
    """

    x = _array(mean, "mean", "DN", low=None)
    c = _array(cov_or_var, "cov_or_var", "DN²", low=None)
    g = _array(gains, "gains", "(output units per DN)")
    if x.ndim == 0 or x.shape[-1] != 3 or g.ndim == 0 or g.shape[-1] != 3 or np.any(g <= 0):
        raise SkinrenderError("mean and gains must have 3 channels last, and gains must be > 0")
    if c.ndim >= 2 and c.ndim == x.ndim + 1 and c.shape[-2:] == (3, 3):
        covariance = c
    elif c.ndim == x.ndim and c.shape[-1] == 3 and np.all(c >= 0):
        covariance = c[..., :, None] * np.eye(3)
    else:
        raise SkinrenderError(
            f"cov_or_var must be variances ≥ 0, shape (..., 3), or a covariance, (..., 3, 3); got {c.shape}"
        )
    out = g * x
    total = out.sum(axis=-1)
    if np.any(total <= 0):
        raise SkinrenderError("mean: the white-balanced channels must have a positive sum")
    ncc = out / total[..., None]
    jacobian = (g[..., None, :] / total[..., None, None]) * (np.eye(3) - ncc[..., :, None])
    return jacobian @ covariance @ np.swapaxes(jacobian, -1, -2)
