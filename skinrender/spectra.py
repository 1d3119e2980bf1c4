"""
Spectra
=======

The wavelength grid, explicit resampling, Planck's law and the paper's sensor
shapes, plus the validating reader for spectral CSV files.

-   :class:`WavelengthGrid`, :data:`GRID_DEFAULT`: the uniform integration grid.
-   :func:`resample`: linear interpolation with a stated extrapolation rule.
-   :func:`planck`: blackbody spectral radiance.
-   :func:`gbell`, :func:`impulse`: the paper's sensor shapes.

Spectral CSV files are read by :mod:`skinrender.spectral_csv`.

Units: wavelength in nm, temperature in K, spectral radiance in
W·m⁻²·sr⁻¹·nm⁻¹; reflectances and sensitivities are unitless.

References
----------
-   :cite:`CODATA2018`, see :mod:`skinrender.constants`.
-   :cite:`MathWorksGbellmf` : MathWorks, ``gbellmf`` — generalised bell-shaped
    membership function, ``f(x; a, b, c) = 1 / (1 + |(x - c)/a|^(2b))``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .constants import CONSTANT_C, CONSTANT_H, CONSTANT_K_B, TEMPERATURE_MAX
from .errors import SkinrenderError, given_role
from .hints import ArrayLike, Literal, NDArrayFloat
from .methods import RangeWords, method_of, parse_range, range_steps

__all__ = [
    "WavelengthGrid",
    "GRID_DEFAULT",
    "EXTRAPOLATIONS",
    "extrapolate_refuse",
    "extrapolate_zero",
    "extrapolate_constant",
    "GRID_SIZE_MAX",
    "resample",
    "planck",
    "gbell",
    "impulse",
    "float_array",
    "as_grid",
]

GRID_SIZE_MAX = 100_001
"""Most samples a wavelength grid may have (400–700 nm every 0.003 nm): a
reflectance set of 1269 spectra on it takes 1 GB."""

def extrapolate_refuse(values: NDArrayFloat, outside: NDArrayFloat, measured: NDArrayFloat, target: NDArrayFloat,
                      source: str) -> NDArrayFloat:
    """an error (default)

    ``values`` (spectra on ``target``, nm, the end values held beyond the ``measured`` wavelengths) where no
    wavelength is ``outside`` them, else a :class:`SkinrenderError` naming ``source`` (its ``cause``:
    ``coverage``)."""
    if np.any(outside):
        raise SkinrenderError(
            f"{source}: measured over {measured[0]:g}–{measured[-1]:g} nm, which does not cover the "
            f"grid {target[0]:g}–{target[-1]:g} nm", cause="coverage",
            hint="choose a grid inside the data or state an extrapolation ('zero' or 'constant')",
        )
    return values


def extrapolate_zero(values: NDArrayFloat, outside: NDArrayFloat, measured: NDArrayFloat, target: NDArrayFloat,
                     source: str) -> NDArrayFloat:
    """0 outside the measured range (the usual rule for sensor sensitivities)

    ``values`` with the wavelengths ``outside`` the measured range set to 0."""
    values[:, outside] = 0.0
    return values


def extrapolate_constant(values: NDArrayFloat, outside: NDArrayFloat, measured: NDArrayFloat, target: NDArrayFloat,
                         source: str) -> NDArrayFloat:
    """the nearest measured value is held

    ``values`` as interpolated: the end values are held beyond the measured range."""
    return values


EXTRAPOLATIONS = {"refuse": extrapolate_refuse, "zero": extrapolate_zero, "constant": extrapolate_constant}
"""Rules for wavelengths of the grid outside the measured range, name → function ``(values, outside, measured,
target, source) → values`` of the spectra interpolated onto the grid (the end values held); :func:`resample`
dispatches."""


_GRID_WORDS = RangeWords(
    lambda r: f"grid end ({r.end:g} nm) must be above grid start ({r.start:g} nm): a grid needs two samples",
    lambda r: (f"grid {r.start:g}:{r.end:g}:{r.step:g} nm has {r.values:.3g} samples, more than {GRID_SIZE_MAX} "
               f"(every spectrum would need {8 * r.values / 1e6:.3g} MB); use a larger step"),
    lambda r: f"grid {r.start}–{r.end} nm is not a whole number of {r.step} nm steps",
)


@dataclass(frozen=True)
class WavelengthGrid:
    """
    A uniform wavelength grid for the spectral sums of Eqs. 1 and 4.

    Parameters
    ----------
    start, end
        First and last wavelength, nm; ``end`` is included.
    step
        Spacing, nm; ``end - start`` must be a whole number of steps.

    Notes
    -----
    The paper sums over 400–700 nm; the default grid does so every 1 nm.
    Integrals are Riemann sums ``Σ f(λ) Δλ`` over the grid samples.

    Examples
    --------
    >>> WavelengthGrid(400, 700, 10).wavelengths[:3].tolist()
    [400.0, 410.0, 420.0]
    """

    start: float = 400.0
    end: float = 700.0
    step: float = 1.0

    def __post_init__(self) -> None:
        for name in ("start", "end", "step"):
            value = getattr(self, name)
            try:
                finite = not isinstance(value, (str, bool)) and np.isfinite(float(value))
            except (TypeError, ValueError, OverflowError):
                finite = False
            if not finite:
                raise SkinrenderError(f"grid {name} must be a finite number of nm, got {value!r}", role="grid")
        if self.start <= 0:
            raise SkinrenderError(f"grid start must be > 0 nm, got {self.start}", role="grid")
        if self.step <= 0:
            raise SkinrenderError(f"grid step must be > 0 nm, got {self.step}", role="grid")
        range_steps(self.start, self.end, self.step, GRID_SIZE_MAX, _GRID_WORDS, role="grid")

    @property
    def size(self) -> int:
        """Number of samples."""
        return int(round((self.end - self.start) / self.step)) + 1

    @property
    def wavelengths(self) -> NDArrayFloat:
        """The sample wavelengths, nm, shape ``(size,)``."""
        return self.start + self.step * np.arange(self.size, dtype=np.float64)

    def index_of(self, wavelength: float) -> int:
        """Index of a wavelength that lies on the grid; an error otherwise."""
        position = (wavelength - self.start) / self.step
        index = int(round(position)) if np.isfinite(position) else -1
        if abs(position - index) > 1e-6 or not 0 <= index < self.size:
            raise SkinrenderError(
                f"wavelength {wavelength} nm is not a sample of the grid "
                f"{self.start:g}:{self.end:g}:{self.step:g} nm", role="wavelength"
            )
        return index

    def __str__(self) -> str:
        return f"{self.start:g}:{self.end:g}:{self.step:g} nm"

    @classmethod
    def parse(cls, text: str) -> WavelengthGrid:
        """Parse ``START:END:STEP`` (nm), e.g. ``400:700:5``."""
        return cls(*parse_range(text, "grid", "400:700:1"))


GRID_DEFAULT = WavelengthGrid(400.0, 700.0, 1.0)
"""The default integration grid: 400–700 nm every 1 nm, as the paper."""


def float_array(value, name: str) -> NDArrayFloat:
    """
    ``value`` as a float64 array, or a one-line :class:`SkinrenderError` naming the argument ``name`` (``None``,
    text that is not a number, objects): never numpy's bare ``ValueError``.

    >>> float_array([1, "2"], "x").tolist()
    [1.0, 2.0]
    >>> float_array("x", "temperature")
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: temperature must be numbers, got 'x'
    """
    error = value is None or isinstance(value, bool)  # True is not the number 1 here
    if not error:
        try:
            return np.asarray(value, dtype=np.float64)
        except (TypeError, ValueError, OverflowError):
            error = True
    shown = repr(value)
    raise SkinrenderError(f"{name} must be numbers, got {shown if len(shown) <= 60 else shown[:57] + '...'}",
                          role=name)


def broadcast(*named) -> tuple:
    """The broadcast shape of ``(name, array)`` pairs, or an error naming the first two and their shapes."""
    try:
        return np.broadcast_shapes(*(np.shape(array) for _, array in named))
    except ValueError:
        shown = ", ".join(f"{name} {np.shape(array)}" for name, array in named)
        raise SkinrenderError(f"{named[0][0]} and {named[1][0]} must broadcast together, got shapes {shown}",
                              role=named[0][0]) from None


def as_grid(grid, name: str = "grid") -> WavelengthGrid:
    """
    ``grid`` as a :class:`WavelengthGrid`: one already, or its text ``START:END:STEP`` (nm); anything else is a
    one-line :class:`SkinrenderError` naming ``name``.

    >>> as_grid("400:700:10")
    WavelengthGrid(start=400.0, end=700.0, step=10.0)
    """
    if isinstance(grid, WavelengthGrid):
        return grid
    if isinstance(grid, str):
        return given_role(name, WavelengthGrid.parse, grid)  # its message names the grid; its role, the argument
    raise SkinrenderError(f"{name} must be a WavelengthGrid or 'START:END:STEP' in nm, got {grid!r}", role=name)


def resample(
    wavelengths: ArrayLike,
    values: ArrayLike,
    grid: WavelengthGrid | ArrayLike,
    extrapolation: Literal["refuse", "zero", "constant"] | str = "refuse",
    source: str = "spectra",
) -> NDArrayFloat:
    """
    Resample spectra onto a grid by linear interpolation.

    Parameters
    ----------
    wavelengths
        Measured wavelengths, nm, strictly increasing, shape ``(n,)``.
    values
        Spectra with wavelength on the last axis, shape ``(..., n)``.
    grid
        Target grid or target wavelengths, nm.
    extrapolation
        What to do where the grid leaves the measured range: ``refuse``
        (raise :class:`SkinrenderError`), ``zero`` or ``constant`` (hold the
        end value). See :data:`EXTRAPOLATIONS`.
    source
        Name used in error messages (a file, a dataset).

    Returns
    -------
    :class:`numpy.ndarray`
        Shape ``(..., grid size)``.

    Notes
    -----
    Linear interpolation never creates values outside the range of its two
    neighbours, so a non-negative reflectance stays non-negative.
    """

    x = float_array(wavelengths, "wavelengths")
    y = float_array(values, "values")
    target = (grid.wavelengths if isinstance(grid, WavelengthGrid) else as_grid(grid).wavelengths
              if isinstance(grid, str) else float_array(grid, "grid"))
    if x.ndim != 1 or y.ndim < 1 or target.ndim != 1:
        raise SkinrenderError(f"{source}: expected wavelengths (1-D), spectra (…, n) and a grid, got shapes "
                              f"{x.shape}, {y.shape}, {target.shape}")
    rule = method_of(extrapolation, EXTRAPOLATIONS, "extrapolation")
    if x.ndim != 1 or x.size != y.shape[-1] or x.size == 0:
        raise SkinrenderError(f"{source}: {x.size} wavelengths but spectra of length {y.shape[-1]} (at least one "
                              "each)", role="values" if x.size else "wavelengths")
    if x.size >= 2 and np.any(np.diff(x) <= 0):
        raise SkinrenderError(f"{source}: wavelengths must be strictly increasing")
    tolerance = 1e-9
    outside = (target < x[0] - tolerance) | (target > x[-1] + tolerance)
    if np.all(outside) and target.size > 1:  # no extrapolation rule makes data of it (µm given for nm?)
        raise SkinrenderError(
            f"{source}: measured over {x[0]:g}–{x[-1]:g} nm, which does not overlap the grid "
            f"{target[0]:g}–{target[-1]:g} nm at all{' (wavelengths in µm? they are in nm)' if x[-1] < 10 else ''}"
        )
    flat = y.reshape(-1, x.size)
    if x.size == 1:
        out = np.repeat(flat, target.size, axis=1)
    else:
        # Vectorised linear interpolation over every spectrum at once.
        index = np.clip(np.searchsorted(x, target, side="right") - 1, 0, x.size - 2)
        t = np.clip((target - x[index]) / (x[index + 1] - x[index]), 0.0, 1.0)
        out = flat[:, index] * (1.0 - t) + flat[:, index + 1] * t
    return rule(out, outside, x, target, source).reshape(*y.shape[:-1], target.size)


def planck(wavelength: ArrayLike, temperature: ArrayLike) -> NDArrayFloat:
    """
    Spectral radiance of a blackbody (Planck's law).

    ``L(λ, T) = 2hc² / λ⁵ / (exp(hc / (λ k T)) − 1)``

    Parameters
    ----------
    wavelength
        Wavelength λ, nm, > 0.
    temperature
        Temperature T, K, > 0. Broadcast against ``wavelength``.

    Returns
    -------
    :class:`numpy.ndarray`
        Spectral radiance, W·m⁻²·sr⁻¹·nm⁻¹, finite and non-negative.

    Notes
    -----
    The exponent is evaluated with ``expm1`` (no loss at high T where
    ``hc/λkT`` is small) and in log space where it is large, so 300 K gives a
    tiny positive or zero value instead of an overflow warning.

    References
    ----------
    :cite:`CODATA2018`

    Examples
    --------
    >>> float(planck(560, 5000))  # W·m⁻²·sr⁻¹·nm⁻¹  # doctest: +ELLIPSIS
    12762.19...
    """

    lam = float_array(wavelength, "wavelength")
    t = float_array(temperature, "temperature")
    if np.any(~np.isfinite(t)) or np.any(t <= 0) or np.any(t > TEMPERATURE_MAX):
        bad = t[~(np.isfinite(t) & (t > 0) & (t <= TEMPERATURE_MAX))]
        raise SkinrenderError(f"temperature must be a finite number of kelvin in (0, {TEMPERATURE_MAX:g}], "
                              f"got {float(np.ravel(bad)[0])!r}", role="temperature")
    if np.any(~np.isfinite(lam)) or np.any(lam <= 0):
        raise SkinrenderError(f"wavelength must be a finite number of nm > 0, got {show_values(lam)}",
                              role="wavelength")
    broadcast(("wavelength", lam), ("temperature", t))
    lam_m = lam * 1e-9
    with np.errstate(divide="ignore", over="ignore", under="ignore", invalid="ignore"):  # T → 0: x → inf, radiance 0
        x = CONSTANT_H * CONSTANT_C / (lam_m * CONSTANT_K_B * t)
        prefactor = 2.0 * CONSTANT_H * CONSTANT_C**2 / lam_m**5 * 1e-9  # per nm
    # For x > 700, exp(x) overflows float64; there 1/(e^x − 1) = e^−x (1 + e^−x …)
    # to machine precision, computed as exp(log(prefactor) − x), which underflows
    # gracefully to 0 instead of warning.
    large = x > 700.0
    with np.errstate(over="ignore", under="ignore", divide="ignore", invalid="ignore"):
        small_part = prefactor / np.expm1(np.where(large, 1.0, x))
        large_part = np.exp(np.log(prefactor) - np.where(large, x, 0.0))
    radiance = np.where(large, large_part, small_part)
    if not np.all(np.isfinite(radiance)):
        raise SkinrenderError(f"Planck radiance overflows float64 at wavelength {show_values(lam)} nm: "
                              "wavelengths must be of a physical size (e.g. 1–1e6 nm)")
    return radiance


def gbell(
    wavelength: ArrayLike, peak: ArrayLike, fwhm: ArrayLike, slope: ArrayLike = 2.0
) -> NDArrayFloat:
    """
    The generalised bell curve of Matlab's ``gbellmf``.

    ``f(λ) = 1 / (1 + |(λ − c) / a|^(2b))`` with ``c`` the peak, ``a = FWHM / 2``.

    Parameters
    ----------
    wavelength
        Wavelength λ, nm.
    peak
        Peak position *c*, nm; the curve is 1 there.
    fwhm
        Full width at half maximum, nm (the paper's sensor *n* has ``n · 10``).
    slope
        Slope parameter *b* (> 0), unitless. The paper does not give it; the
        default 2 gives a curve with clear shoulders and tails that fall as
        ``λ⁻⁴``. The value is 1/2 at ``c ± a`` for every *b*.

    Returns
    -------
    :class:`numpy.ndarray`
        Relative sensitivity in [0, 1], broadcast of the inputs.

    References
    ----------
    :cite:`MathWorksGbellmf`

    Examples
    --------
    >>> gbell([540, 585], 540, 90).tolist()
    [1.0, 0.5]
    """

    lam, peak = float_array(wavelength, "wavelength"), float_array(peak, "peak")
    a = float_array(fwhm, "fwhm") / 2.0
    b = float_array(slope, "slope")
    if np.any(~np.isfinite(lam)) or np.any(~np.isfinite(peak)):
        raise SkinrenderError("wavelength and peak must be finite numbers of nm", role="wavelength")
    if np.any(~(a > 0)) or np.any(~np.isfinite(a)):
        raise SkinrenderError(f"fwhm must be a finite number of nm > 0, got {show_values(2 * a)}", role="fwhm")
    if np.any(~(b > 0)) or np.any(~np.isfinite(b)):
        raise SkinrenderError(f"slope b must be a finite number > 0, got {show_values(b)}", role="slope")
    broadcast(("wavelength", lam), ("peak", peak), ("fwhm", a), ("slope", b))
    with np.errstate(over="ignore"):
        return 1.0 / (1.0 + np.abs((lam - peak) / a) ** (2.0 * b))


def impulse(grid: WavelengthGrid, peak: float) -> NDArrayFloat:
    """
    The paper's "sensor 1": an impulse at ``peak`` on the grid.

    Parameters
    ----------
    grid
        Integration grid; ``peak`` must be one of its samples.
    peak
        Impulse position, nm.

    Returns
    -------
    :class:`numpy.ndarray`
        Shape ``(grid.size,)``: ``1 / Δλ`` at the peak sample, 0 elsewhere.

    Notes
    -----
    The impulse is a unit-area delta, so that the integral ``Σ x(λ) f(λ) Δλ``
    equals ``f(peak)`` whatever the grid step. The paper's "value one at a
    wavelength" differs by the constant ``Δλ``, which Eq. 4 cancels.
    """

    grid = as_grid(grid)
    values = np.zeros(grid.size)
    try:
        values[grid.index_of(float(float_array(peak, "peak")))] = 1.0 / grid.step
    except SkinrenderError as error:  # off the grid or NaN: the peak's fault
        raise error.reworded(role="peak") from None
    except TypeError:  # not one number
        raise SkinrenderError(f"peak must be one wavelength of the grid {grid}, got {peak!r}", role="peak") from None
    return values


def show_values(values: NDArrayFloat) -> str:
    """The first value that is not finite and > 0, or all of them, for an error message."""
    flat = np.ravel(values)
    bad = flat[~(np.isfinite(flat) & (flat > 0))]
    return repr(float(bad[0])) if bad.size else repr(flat.tolist())
