"""
Eq. 10's factors and the sums' weights
======================================

The illuminant normalisations of the paper's Eqs. 5–8 as a method table (name → the factor of each
illuminant, :data:`NORMALISATIONS`, dispatched by :func:`illuminant_factors`) and the quadrature rules of the
sums over the grid (:data:`QUADRATURES`); :mod:`skinrender.model.response` applies them (its :func:`gain`).

-   :func:`factor_none`, :func:`factor_560nm`, :func:`factor_euclidean`, :func:`factor_white`: Eqs. 5–8.
-   :data:`NORMALISATIONS`, :func:`illuminant_factors`, :func:`uses_whites`, :func:`normalisation_factor`.
-   :func:`sum_weights`, :func:`trapezoid_weights`, :data:`QUADRATURES`.
-   :func:`spds_on`: illuminants' SPDs on a grid.

Units: wavelength in nm, radiance in W·m⁻²·sr⁻¹·nm⁻¹; a factor's unit is the inverse of the SPD's.

References
----------
-   :cite:`Martinkauppi2006` : the paper, Eqs. 5–8 and 10.
"""

from __future__ import annotations

import numpy as np

from ..errors import SkinrenderError
from ..hints import ArrayLike, Literal, NDArrayFloat
from ..methods import method_of
from ..spectra import GRID_DEFAULT, WavelengthGrid, as_grid
from .illuminant import Illuminant, illuminants_array

__all__ = ["NORMALISATIONS", "QUADRATURES", "factor_none", "factor_560nm", "factor_euclidean", "factor_white",
           "sum_weights", "trapezoid_weights", "spds_on", "illuminant_factors", "uses_whites", "normalisation_factor"]


def factor_none(illuminants: list[Illuminant], grid: WavelengthGrid = GRID_DEFAULT) -> NDArrayFloat:
    """Eq. 5: the absolute Planck SPD

    ``F = 1`` for each illuminant."""
    return np.ones(len(illuminants))


def factor_560nm(illuminants: list[Illuminant], grid: WavelengthGrid = GRID_DEFAULT) -> NDArrayFloat:
    """Eq. 6: SPD scaled to 100 at 560 nm

    ``F = 100 / SPD(560 nm)`` for each illuminant; refused for one without light there."""
    level = np.array([i.spd(np.array([560.0]))[0] for i in illuminants])
    return 100.0 / _lit(illuminants, level, "at 560 nm (Planck underflows)", "560nm normalisation (Eq. 6)")


def factor_euclidean(illuminants: list[Illuminant], grid: WavelengthGrid = GRID_DEFAULT) -> NDArrayFloat:
    """Eq. 7: SPD of unit Euclidean norm over the grid samples

    ``F = 1 / sqrt(Σ SPD²)`` over the samples of ``grid`` for each illuminant (so it depends on the grid as the
    paper's sum does); refused for one without light on the grid."""
    norm = np.linalg.norm(spds_on(illuminants, grid), axis=-1)
    return 1.0 / _lit(illuminants, norm, f"on the grid {grid}", "euclidean normalisation (Eq. 7)")


def _lit(illuminants: list[Illuminant], values: NDArrayFloat, where: str, what: str) -> NDArrayFloat:
    """``values`` (one per illuminant), refused where an illuminant has no light ``where``: ``what`` is undefined."""
    dark = [str(i) for i, v in zip(illuminants, values) if not (np.isfinite(v) and v > 1e-300)]
    if dark:
        raise SkinrenderError(f"illuminant {dark[0]} has no light {where}: the {what} is undefined for it")
    return values


def factor_white(illuminants: list[Illuminant], grid: WavelengthGrid = GRID_DEFAULT) -> None:
    """Eq. 8: the white coefficient WP (default)

    ``None``: WP is no factor of one illuminant but of a pair, from the camera's whites under both
    (:func:`~skinrender.model.response.white_coefficient_from_whites`), which
    :func:`~skinrender.model.response.gain` computes where it is given no factors."""
    return None


NORMALISATIONS = {"none": factor_none, "560nm": factor_560nm, "euclidean": factor_euclidean, "white": factor_white}
"""Illuminant normalisations (Eqs. 5–8), name → the function ``(illuminants, grid) → F`` of each illuminant
(``I_n = F · I_0``; ``None`` for WP, a pair's); :func:`illuminant_factors` dispatches,
:func:`~skinrender.model.response.gain` applies."""


def sum_weights(grid: WavelengthGrid) -> NDArrayFloat:
    """the paper's Σ over the grid samples

    Every sample weighted 1."""
    return np.ones(grid.size)


def trapezoid_weights(grid: WavelengthGrid) -> NDArrayFloat:
    """end samples weighted ½: the integral of the linearly interpolated spectra (what a renderer estimates)

    The trapezoid rule's weights (in units of the step): 1, the two end samples ½."""
    weights = np.ones(grid.size)
    weights[[0, -1]] = 0.5
    return weights


QUADRATURES = {"sum": sum_weights, "trapezoid": trapezoid_weights}
"""Quadrature rules of :func:`response`, name → the weights of the grid's samples ``(grid) → (grid.size,)``."""


def spds_on(illuminants: list[Illuminant], grid: WavelengthGrid) -> NDArrayFloat:
    """SPDs of illuminants on ``grid``, shape ``(len(illuminants), grid.size)``, W·m⁻²·sr⁻¹·nm⁻¹."""
    return np.array([illuminant.spd(grid.wavelengths) for illuminant in illuminants])


def illuminant_factors(
    illuminants: ArrayLike | Illuminant | str,
    normalization: str = "white",
    grid: WavelengthGrid = GRID_DEFAULT,
) -> NDArrayFloat | None:
    """
    The factor *F_n* of each illuminant (``I_n = F_n · I_0``) of a normalisation: the dispatcher of
    :data:`NORMALISATIONS` (the name checked, its function called); ``None`` for ``white``, whose WP is a pair's.

    Returns
    -------
    :class:`numpy.ndarray` or None
        Shape of ``illuminants``; unit the inverse of the SPD's.
    """
    grid = as_grid(grid)
    items, shape = illuminants_array(illuminants, "illuminants")
    factor = method_of(normalization, NORMALISATIONS, "normalization")(items, grid)
    return None if factor is None else np.asarray(factor, dtype=np.float64).reshape(shape)


def uses_whites(normalization: str) -> bool:
    """
    Whether a normalisation's factor is WP, the pair's, from the camera's whites under both lights (Eq. 8:
    ``white``), rather than one factor per illuminant (Eqs. 5–7).

    >>> uses_whites("white"), uses_whites("560nm")
    (True, False)
    """
    return method_of(normalization, NORMALISATIONS, "normalization") is factor_white


def normalisation_factor(
    illuminants: ArrayLike | Illuminant | str,
    method: Literal["none", "560nm", "euclidean"] | str,
    grid: WavelengthGrid = GRID_DEFAULT,
) -> NDArrayFloat:
    """
    The factor *F_n* with ``I_n = F_n · I_0`` (Eqs. 5–7): :func:`illuminant_factors` of a normalisation that
    has one per illuminant.

    Parameters
    ----------
    illuminants
        Illuminant(s): kelvin, ``A``, ``H``, a CSV path or :class:`Illuminant`.
    method
        ``none`` (``F = 1``), ``560nm`` (``F = 100 / SPD(560 nm)``) or
        ``euclidean`` (``F = 1 / sqrt(Σ SPD²)`` over the samples of ``grid``, so
        it depends on the grid as the paper's sum does).

    Returns
    -------
    :class:`numpy.ndarray`
        Shape of ``illuminants``; unit the inverse of the SPD's.
    """
    grid = as_grid(grid)
    factor = illuminant_factors(illuminants, method, grid) if method in NORMALISATIONS else None
    if factor is None:
        per = ", ".join(name for name in NORMALISATIONS if not uses_whites(name))
        raise SkinrenderError(f"method (a normalization) must be one of {per} (white has no per-illuminant "
                              f"factor), got {method!r}", role="method")
    return factor
