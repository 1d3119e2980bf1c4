"""
Camera response
===============

The paper's Eqs. 1–11 for a :class:`~skinrender.model.camera.Camera`: the raw
response of Eq. 1, the white-balanced response of Eq. 4 with the illuminant
normalisations of Eqs. 5–8 (the Eq. 10 factor), and the knee of Eq. 11.

-   :data:`NORMALISATIONS` (Eqs. 5–8, name → the factor of each illuminant) with its dispatcher
    :func:`illuminant_factors`, :func:`normalisation_factor` (Eqs. 5–7) and :data:`QUADRATURES`: defined in
    :mod:`skinrender.model.factors`, importable here; :func:`white_coefficient`.
-   :func:`gain`: the one implementation of the Eq. 4 gain ``v · F / W_c``
    (white balance and Eq. 10 factor), used by the analytic model, the
    Stage 3 search, the renderer's white balance and the validation.
-   :func:`response_raw` (Eq. 1), :func:`response` (Eq. 4 / Eq. 10).
-   :func:`knee` (Eq. 11); the NCC of Eq. 2 and the measure of Eq. 3 are
    :mod:`skinrender.model.chromaticity`.

Units: wavelength in nm, temperature in K, radiance in W·m⁻²·sr⁻¹·nm⁻¹;
white-balanced responses in output units (``v = 255`` for a white object at
``p = c``).

References
----------
-   :cite:`Martinkauppi2006` : the paper, Eqs. 1–11, with the decisions of
    docs/model.md (Eq. 8 scaled to 1 at p = c, Eq. 11's knee with its erratum).
"""

from __future__ import annotations

import numpy as np

from ..constants import (
    CONSTANT_KNEE_CEILING,
    CONSTANT_KNEE_FACTOR,
    CONSTANT_KNEE_POINT,
    CONSTANT_OUTPUT_SCALE,
)
from ..datasets import SpectralSet, reflectances
from ..errors import SkinrenderError, given_role
from ..hints import ArrayLike, Literal, NDArrayFloat
from ..methods import method_of, validate_method
from ..spectra import GRID_DEFAULT, WavelengthGrid, as_grid, broadcast, float_array
from .camera import Camera, camera
from .factors import (NORMALISATIONS, QUADRATURES, factor_560nm, factor_euclidean, factor_none,  # noqa: F401
                      factor_white, illuminant_factors, normalisation_factor, spds_on, sum_weights,
                      trapezoid_weights, uses_whites)
from .illuminant import Illuminant, illuminants_array

__all__ = [
    "NORMALISATIONS",
    "QUADRATURES",
    "factor_none",
    "factor_560nm",
    "factor_euclidean",
    "factor_white",
    "sum_weights",
    "trapezoid_weights",
    "illuminant_factors",
    "uses_whites",
    "normalisation_factor",
    "white_coefficient",
    "white_coefficient_from_whites",
    "gain",
    "check_light",
    "spds_on",
    "response_raw",
    "response",
    "knee",
]

def check_light(cam: Camera, items: list[Illuminant], spds: NDArrayFloat, grid: WavelengthGrid, role: str) -> None:
    """
    Refuse illuminants that give a channel of ``cam`` no light on ``grid`` (the error's role: ``role``'s first
    word, e.g. ``prevailing`` of ``prevailing illuminant``)
    (Planck underflows below ~40 K over 400–700 nm; an all-zero CSV), and a
    camera with a channel that is zero over the grid: Eq. 4 divides by the
    white's response, which would be 0.
    """
    x = cam.sensitivities(grid)
    for channel, row in zip(cam.channels, x):
        if not np.any(row > 0):
            raise SkinrenderError(f"camera {cam.name}: channel {channel} is zero at every wavelength of the grid "
                                  f"{grid}", role="camera")
    white = spds @ x.T
    with np.errstate(over="ignore", invalid="ignore"):  # the camera's curves scaled to a peak of 1
        scaled = spds @ (x / x.max(axis=1, keepdims=True)).T
    for item, row, seen in zip(items, white, scaled):
        if not np.all(np.isfinite(row) & (row > 1e-300)):
            if np.all(np.isfinite(seen) & (seen > 1e-300)):  # scaled up, the camera sees the light: its values
                raise SkinrenderError(f"camera {cam.name}: its sensitivities (largest {x.max():.3g}) are too small: "
                                      f"the responses to {role} {item} underflow to 0 (every one would be 0/0); "
                                      "scale them up", role="camera")
            raise SkinrenderError(f"{role} {item} gives no light in the sensors' range ({grid}) of camera "
                                  f"{cam.name}: every response would be 0/0", role=role.split()[0])


def gain(
    white_p: ArrayLike,
    white_c: ArrayLike,
    normalization: str = "white",
    factor_p: ArrayLike | None = None,
    factor_c: ArrayLike | None = None,
    scale: float = CONSTANT_OUTPUT_SCALE,
) -> NDArrayFloat:
    """
    The Eq. 4 gain ``v · F / W_c`` of each channel: the white balance to the
    calibration light with the Eq. 10 factor.

    Parameters
    ----------
    white_p, white_c
        Channel responses to a white object under the prevailing and the
        calibration light (channels on the last axis; broadcast against each
        other), e.g. ``Σ_λ I_p x_k Δλ`` or a rendered white reference.
    normalization
        ``white``: ``F`` is WP (Eq. 8) from the two whites; ``none``,
        ``560nm``, ``euclidean``: ``F = F_p / F_c`` (Eqs. 5–7).
    factor_p, factor_c
        ``F_p`` and ``F_c`` for the non-white normalisations (broadcast
        against the whites without their channel axis).
    scale
        Output scale *v* (255).

    Returns
    -------
    :class:`numpy.ndarray`
        Shape ``broadcast(white_p, white_c)``; output units per unit of
        ``white_c``. Multiplying the prevailing-light response by it gives
        Eq. 4.

    Examples
    --------
    >>> gain([1.0, 2.0, 4.0], [1.0, 2.0, 4.0]).tolist()
    [255.0, 127.5, 63.75]
    """

    validate_method(normalization, NORMALISATIONS, "normalization")
    scale = _positive(scale, "scale")
    white_p, white_c = float_array(white_p, "white_p"), float_array(white_c, "white_c")
    tiny = np.finfo(np.float64).tiny  # 1 / a subnormal white overflows
    for name, white, low in (("white_p", white_p, "≥ 0"), ("white_c", white_c, f"≥ {tiny:.3g}")):
        ok = np.isfinite(white) & ((white >= 0) if name == "white_p" else (white >= tiny))
        if white.shape[-1:] != (3,) or not np.all(ok):
            raise SkinrenderError(f"{name} must be a white's three channel responses, finite and {low}, got "
                                  f"{np.ravel(white)[:6].tolist()} (shape {white.shape})", role=name)
    broadcast(("white_p", white_p), ("white_c", white_c))
    if uses_whites(normalization):  # WP (Eq. 8): the pair's, from the whites
        if np.any(np.sum(white_p, axis=-1) <= 0):
            raise SkinrenderError("white_p must have light in some channel: a white that is black under the "
                                  "prevailing light makes WP (Eq. 8) infinite", role="white_p")
        factor = white_coefficient_from_whites(white_p, white_c)
    else:
        if factor_p is None or factor_c is None:
            raise SkinrenderError(f"normalization {normalization!r} needs the factors F_p and F_c (Eqs. 5–7)",
                                  role="factor_p" if factor_p is None else "factor_c")
        factor = _positive(factor_p, "factor_p") / _positive(factor_c, "factor_c")
    try:
        return scale * np.asarray(factor)[..., None] / white_c
    except ValueError:
        raise SkinrenderError(f"factor_p, factor_c (shape {np.shape(factor)}) must broadcast against the whites "
                              f"without their channel axis (shape {white_c.shape[:-1]})", role="factor_p") from None


def _positive(value, name: str):
    """``value`` as finite float(s) > 0, else an error naming ``name``."""
    array = float_array(value, name) if not isinstance(value, bool) else np.array(np.nan)
    if array.size == 0 or not np.all(np.isfinite(array) & (array > 0)):
        raise SkinrenderError(f"{name} must be finite and > 0, got {value!r}", role=name)
    return array if array.ndim else float(array)


def white_coefficient_from_whites(white_p: ArrayLike, white_c: ArrayLike) -> NDArrayFloat:
    """
    WP (Eq. 8, scaled to 1 at ``p = c``) from the channel responses to white
    under the prevailing and the calibration light (channels on the last
    axis, broadcast against each other): ``WP = 3 / Σ_k white_p,k / white_c,k``.
    """
    return 3.0 / np.sum(np.asarray(white_p) / np.asarray(white_c), axis=-1)


def white_coefficient(
    camera_: Camera | str,
    prevailing: ArrayLike | Illuminant | str,
    calibration: ArrayLike | Illuminant | str,
    grid: WavelengthGrid = GRID_DEFAULT,
) -> NDArrayFloat:
    """
    The white coefficient *WP* of Eq. 8, scaled so that ``WP = 1`` at ``p = c``.

    ``1 / WP = (1/3) Σ_k Σ_λ x_k I_0p / Σ_λ x_k I_0c``

    Notes
    -----
    Taken literally, Eq. 8 gives ``WP = 1/3`` at ``p = c``; the paper says WP
    "can be scaled to the wanted range" and equals 1 when ``p = c``, so the
    project uses ``WP = 3 / Σ_k ratio_k`` (NOTES.md).

    Returns
    -------
    :class:`numpy.ndarray`
        Shape: ``prevailing`` broadcast against ``calibration``; unitless.
    """

    grid = as_grid(grid)
    cam = camera(camera_)
    p_items, p_shape = illuminants_array(prevailing, "prevailing")
    c_items, c_shape = illuminants_array(calibration, "calibration")
    x = cam.sensitivities(grid)
    spd_p, spd_c = spds_on(p_items, grid), spds_on(c_items, grid)
    check_light(cam, p_items, spd_p, grid, "prevailing illuminant")
    check_light(cam, c_items, spd_c, grid, "calibration illuminant")
    pi, ci = pair_indices(p_items, p_shape, c_items, c_shape)
    return white_coefficient_from_whites((spd_p @ x.T)[pi], (spd_c @ x.T)[ci])


def pair_indices(p_items, p_shape, c_items, c_shape) -> tuple:
    """The prevailing and calibration lights' indices broadcast against each other, or an error naming both."""
    p, c = np.arange(len(p_items)).reshape(p_shape), np.arange(len(c_items)).reshape(c_shape)
    broadcast(("prevailing", p), ("calibration", c))
    return np.broadcast_arrays(p, c)


def _reflectance_values(reflectance, grid: WavelengthGrid) -> NDArrayFloat:
    return given_role("reflectance", _reflectance_array, reflectance, grid)  # a set's name, file or array


def _reflectance_array(reflectance, grid: WavelengthGrid) -> NDArrayFloat:
    if isinstance(reflectance, (str, SpectralSet)):
        return reflectances(reflectance).on(grid)
    values = float_array(reflectance, "reflectance")
    if values.shape[-1:] != (grid.size,):
        raise SkinrenderError(
            f"reflectance array must have the grid's {grid.size} samples ({grid}) on its last axis, "
            f"got shape {values.shape}"
        )
    if not np.all(np.isfinite(values)):
        raise SkinrenderError("reflectance array contains NaN or inf")
    if values.size and (values.min() < 0 or values.max() > REFLECTANCE_MAX):
        raise SkinrenderError(f"reflectance array must hold fractions in [0, {REFLECTANCE_MAX:g}] (as a CSV does), "
                              f"got values from {values.min():g} to {values.max():g}")
    return values


REFLECTANCE_MAX = 1.5
"""Largest reflectance accepted (fractions; a little above 1 for measurement noise or fluorescence, as the
CSV reader of :mod:`skinrender.spectral_csv` allows), so that percent is never taken for a fraction."""


def response_raw(
    camera_: Camera | str,
    reflectance,
    illuminant: ArrayLike | Illuminant | str,
    normalization: Literal["none", "560nm", "euclidean"] | str = "none",
    grid: WavelengthGrid = GRID_DEFAULT,
) -> NDArrayFloat:
    """
    The raw camera response of Eq. 1, ``X = Σ_λ I_n(λ) x(λ) o(λ) Δλ``.

    Parameters
    ----------
    camera_
        Camera or camera spec.
    reflectance
        A reflectance set (name, :class:`SpectralSet`) or an array of
        reflectances on ``grid``, shape ``(..., grid.size)``, fractions in [0, 1].
    illuminant
        Illuminant(s), shape ``S`` (kelvin, ``A``, ``H``, CSV, :class:`Illuminant`).
    normalization
        ``none`` (Eq. 5, absolute radiance), ``560nm`` (Eq. 6) or ``euclidean`` (Eq. 7).
    grid
        Integration grid.

    Returns
    -------
    :class:`numpy.ndarray`
        Shape ``S + reflectance.shape[:-1] + (3,)``. With ``none`` the unit is
        W·m⁻²·sr⁻¹ times the sensitivity's unit (a Riemann sum over nm).
    """

    grid = as_grid(grid)
    cam = camera(camera_)
    o = _reflectance_values(reflectance, grid)
    items, shape = illuminants_array(illuminant, "illuminant")
    check_light(cam, items, spds_on(items, grid), grid, "illuminant")
    factor = normalisation_factor(items, normalization, grid)
    weighted = spds_on(items, grid)[:, None, :] * cam.sensitivities(grid)[None, :, :] * grid.step
    out = np.einsum("...w,skw->s...k", o, weighted) * factor.reshape(-1, *([1] * o.ndim))
    return out.reshape(*shape, *o.shape[:-1], 3)


def response(
    camera_: Camera | str,
    reflectance,
    prevailing: ArrayLike | Illuminant | str,
    calibration: ArrayLike | Illuminant | str,
    normalization: Literal["none", "560nm", "euclidean", "white"] | str = "white",
    knee: bool = False,
    grid: WavelengthGrid = GRID_DEFAULT,
    scale: float = CONSTANT_OUTPUT_SCALE,
    quadrature: Literal["sum", "trapezoid"] | str = "sum",
) -> NDArrayFloat:
    """
    The white-balanced camera response of Eq. 4 with normalisation (Eq. 10).

    ``X_k = v · (F_p / F_c) · Σ_λ I_0p x_k o / Σ_λ I_0c x_k``

    with ``F`` the normalisation factor of Eqs. 5–7, or, for ``white``,
    ``F_p / F_c`` replaced by the white coefficient WP of Eq. 8.

    Parameters
    ----------
    camera_
        Camera or camera spec.
    reflectance
        A reflectance set (name, :class:`SpectralSet`) or an array on ``grid``,
        shape ``(..., grid.size)``, fractions in [0, 1].
    prevailing, calibration
        Illuminants (kelvin, ``A``, ``H``, CSV, :class:`Illuminant`) or arrays
        of kelvin; they are broadcast against each other (``p[:, None]`` and
        ``c[None, :]`` give every pair at once).
    normalization
        ``none``, ``560nm``, ``euclidean`` or ``white`` (default).
    knee
        Apply the knee of Eq. 11.
    grid
        Integration grid (default 400–700 nm every 1 nm).
    scale
        Output scale *v* (255).
    quadrature
        ``sum`` (the paper's Σ over the grid samples, default) or
        ``trapezoid`` (end samples weighted ½: the integral of the linearly
        interpolated spectra, which is what a spectral renderer estimates).
        They differ by up to ~1 % for sensors peaking at the grid's ends.

    Returns
    -------
    :class:`numpy.ndarray`
        Shape ``broadcast(p, c) + reflectance.shape[:-1] + (3,)``, output units.
        A white object (``o = 1``) at ``p = c`` gives ``v`` in every channel.

    Notes
    -----
    Computed without a Python loop over samples: one weighted sensitivity per
    distinct prevailing illuminant, one matrix product for all reflectances.

    Examples
    --------
    >>> response("gbell:9@450,540,610", [[1.0] * 301], 3300, 3300).tolist()
    [[255.0, 255.0, 255.0]]
    """

    validate_method(normalization, NORMALISATIONS, "normalization")
    grid = as_grid(grid)
    if not isinstance(knee, (bool, np.bool_)):
        raise SkinrenderError(f"knee must be True or False, got {knee!r}", role="knee")
    cam = camera(camera_)
    o = _reflectance_values(reflectance, grid)
    p_items, p_shape = illuminants_array(prevailing, "prevailing")
    c_items, c_shape = illuminants_array(calibration, "calibration")
    x = cam.sensitivities(grid)
    spd_p = spds_on(p_items, grid)
    spd_c = spds_on(c_items, grid)
    weights = method_of(quadrature, QUADRATURES, "quadrature")(grid)
    spd_p, spd_c = spd_p * weights, spd_c * weights
    signal = np.einsum("...w,pkw->p...k", o, spd_p[:, None, :] * x[None, :, :])  # (P, ..., 3)
    white_p = spd_p @ x.T  # (P, 3)
    white_c = spd_c @ x.T  # (C, 3)
    check_light(cam, p_items, spd_p, grid, "prevailing illuminant")
    check_light(cam, c_items, spd_c, grid, "calibration illuminant")
    pi, ci = pair_indices(p_items, p_shape, c_items, c_shape)
    factor_p, factor_c = (illuminant_factors(items, normalization, grid) for items in (p_items, c_items))
    factors = (None, None) if factor_p is None else (factor_p[pi], factor_c[ci])  # None: WP, from the whites
    gains = gain(white_p[pi], white_c[ci], normalization, *factors, scale=scale)
    gains = gains.reshape(*gains.shape[:-1], *((1,) * (o.ndim - 1)), 3)
    out = signal[pi] * gains
    return _apply_knee(out) if knee else out


def knee(
    x: ArrayLike,
    a: float = CONSTANT_KNEE_FACTOR,
    point: float = CONSTANT_KNEE_POINT,
    ceiling: float = CONSTANT_KNEE_CEILING,
) -> NDArrayFloat:
    """
    The knee function of Eq. 11 (with the NOTES.md erratum).

    ``X`` for ``X ≤ 244``; ``244 (1 − a) + a X`` above, up to the ceiling 255.

    Parameters
    ----------
    x
        Responses, output units.
    a
        Knee factor (0.0127, from the Sony manual).
    point
        Knee point (244).
    ceiling
        Output ceiling (255).

    Returns
    -------
    :class:`numpy.ndarray`
        Same shape, output units, in ``(-∞, ceiling]``.

    Notes
    -----
    The slope reaches the ceiling at ``point + (ceiling − point) / a`` =
    1110.14 for the paper's values; the paper prints 1109 (its last branch as
    ``X > 255`` is an erratum). Ending the slope where it meets the ceiling
    keeps the knee continuous everywhere; at 1109 it gives 254.9855.
    """

    x = float_array(x, "x")
    for name, value in (("a", a), ("point", point), ("ceiling", ceiling)):
        if isinstance(value, (bool, str)) or np.ndim(value) != 0 or not np.isfinite(float_array(value, name)):
            raise SkinrenderError(f"{name} must be one finite number, got {value!r}", role=name)
    if not 0 < a <= 1:
        raise SkinrenderError(f"a (the knee factor) must be in (0, 1], got {a}", role="a")
    if not point < ceiling:
        raise SkinrenderError(f"point must be below the ceiling, got point {point:g}, ceiling {ceiling:g}",
                              role="point")
    if not np.all(np.isfinite(x)):
        raise SkinrenderError("x: knee expects finite responses, got NaN or inf", role="x")
    return np.where(x <= point, x, np.minimum(point * (1.0 - a) + a * x, ceiling))


_apply_knee = knee  # module-level name: inside response() "knee" is the flag
