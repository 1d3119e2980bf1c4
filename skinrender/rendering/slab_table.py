"""
The skin's slab as a table of angular reflectance
=================================================

The fast subsurface transport (``--physics subsurface``) renders skin as a
BSDF: the skin model's layers, a flat and laterally infinite slab, reduced to
the light they return into each direction for light arriving from each other
one, by adding-doubling (:func:`~skinrender.datasets.adding_doubling.angular_reflectance`).
This module builds that table on the render's wavelengths and on a uniform
grid of cosines, which :mod:`~skinrender.rendering.slab_bsdf` hands to
Mitsuba.

-   :class:`SlabTable`, :func:`slab_table`: the table of a skin spec's layers
    (cached per spec and grid), :func:`table_of_layers` of any layers.
-   :data:`QUAD_PTS_TABLE`, :data:`COSINE_STEPS`: its resolution.

From the quadrature's nodes to a grid
-------------------------------------
Adding-doubling gives the BRDF ``f(μ_o, μ_i)`` (sr⁻¹, azimuthally averaged)
at :data:`QUAD_PTS_TABLE` / 2 cosines in air, unevenly spaced (the nodes of
Gauss and Radau quadratures inside the skin, mapped through Snell's law).
The light entering and leaving crosses the smooth surface twice, so
``f = T(μ_o) T(μ_i) h(μ_o, μ_i)``, ``T = 1 − F`` the Fresnel transmittance
from air, which falls to 0 at grazing angles; ``h``, the light under the
surface, is smooth in both cosines. The table interpolates ``h`` along each
axis with a shape-preserving cubic (PCHIP: never negative, no overshoot)
onto :data:`COSINE_STEPS` cosines evenly spaced on [0, 1] and multiplies by
the exact ``T`` there, symmetrised (reciprocity; PCHIP along one axis and then
the other differs from the other order by ~1e-5 relative). Last, the grid is
scaled symmetrically (``f c(μ_o) c(μ_i)``, ``c`` within ~2e-4 of 1) so that
at every cosine of incidence the light it returns, integrated as the BSDF
reads it (linear between the cosines), is adding-doubling's
directional-hemispherical reflectance: a patch under a uniform sky seen
along the normal then reflects ``UR1`` to float32, where the unscaled grid
was 1.6e-4 short (the interpolation's error in the integral, measured).
Below the smallest node (μ ≈ 0.068, 86° from the
normal, ~0.5 % of a cosine-weighted hemisphere) ``h`` is held at its value
there: the only values not between nodes, where ``T`` takes ``f`` to 0
anyway. How far the interpolated table is from adding-doubling at twice the
nodes is measured in ``tests/rendering/test_slab_table.py`` and
``docs/subsurface.md``.

Units: wavelengths nm; cosines; BRDF sr⁻¹; reflectances fractions.

References
----------
-   :cite:`Prahl1995` : S. A. Prahl (1995). The adding-doubling method.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..hints import NDArrayFloat
from ..spectra import WavelengthGrid

__all__ = ["QUAD_PTS_TABLE", "COSINE_STEPS", "SlabTable", "table_of_layers", "slab_table", "fresnel_from_air",
           "linear_weights"]

QUAD_PTS_TABLE = 32
"""Quadrature points of the adding-doubling behind the table (16 angles leave into air): its ``UR1`` is within
2.1e-4 of 16 points' for the skin model (``skinrender.datasets.adding_doubling.QUAD_PTS_DEFAULT``)."""

COSINE_STEPS = 64
"""Cosines of the table's grid, evenly spaced on [0, 1] (both angles)."""


def fresnel_from_air(mu: NDArrayFloat, n: float) -> NDArrayFloat:
    """
    Fresnel reflectance (unpolarised) of a smooth surface of index ``n`` for light from air at the cosines
    ``mu`` (1 at grazing incidence).

    >>> round(float(fresnel_from_air(1.0, 1.4)), 6), float(fresnel_from_air(0.0, 1.4))
    (0.027778, 1.0)
    """
    from ..datasets.adding_doubling import fresnel_reflectance

    mu = np.asarray(mu, dtype=np.float64)
    inside = np.sqrt(1.0 - (1.0 - mu**2) / n**2)  # the refracted cosine: the same Fresnel term
    return fresnel_reflectance(inside, n)


@dataclass(frozen=True, eq=False)
class SlabTable:
    """
    A slab's angular reflectance on a grid (module docstring).

    Attributes
    ----------
    wavelengths
        nm, ``(L,)``, evenly spaced.
    mu
        The grid's cosines, evenly spaced on [0, 1], ``(U,)``.
    brdf
        ``f(λ, μ_o, μ_i)``, sr⁻¹, ``(L, U, U)`` (exit on the middle axis, incidence on the last): the light that
        entered the slab, the surface's specular reflection excluded.
    albedo
        The directional-hemispherical reflectance of ``brdf`` at each incidence on the grid, ``(L, U)``,
        from adding-doubling's nodes (interpolated between them as ``h``): the specular part excluded.
    ur1
        Adding-doubling's total reflectance for collimated normal incidence, specular part included
        (``UR1``), at :data:`QUAD_PTS_TABLE` points, ``(L,)``: what a flat patch of the table reflects towards
        a viewer along the normal under a uniform sky.
    n
        The surface's refractive index.
    nodes
        The :class:`~skinrender.datasets.adding_doubling.AngularReflectance` it was built from.
    """

    wavelengths: NDArrayFloat
    mu: NDArrayFloat
    brdf: NDArrayFloat
    albedo: NDArrayFloat
    ur1: NDArrayFloat
    n: float
    nodes: object

    def value(self, mu_o, mu_i) -> NDArrayFloat:
        """
        ``f`` at the cosines ``mu_o``, ``mu_i`` (broadcast; in [0, 1]) on every wavelength, bilinear between the
        grid's cosines as Mitsuba's texture reads it: shape ``(L, *broadcast)``, sr⁻¹.
        """
        mu_o, mu_i = np.broadcast_arrays(np.asarray(mu_o, dtype=np.float64), np.asarray(mu_i, dtype=np.float64))
        steps = self.mu.size - 1
        x, y = np.clip(mu_o, 0, 1) * steps, np.clip(mu_i, 0, 1) * steps
        x0, y0 = np.minimum(np.floor(x).astype(int), steps - 1), np.minimum(np.floor(y).astype(int), steps - 1)
        fx, fy = x - x0, y - y0
        f = self.brdf
        return ((1 - fx) * (1 - fy) * f[:, x0, y0] + fx * (1 - fy) * f[:, x0 + 1, y0]
                + (1 - fx) * fy * f[:, x0, y0 + 1] + fx * fy * f[:, x0 + 1, y0 + 1])


def _along(nodes: NDArrayFloat, values: NDArrayFloat, at: NDArrayFloat, axis: int) -> NDArrayFloat:
    """``values`` over ``nodes`` on ``axis`` interpolated (PCHIP) at ``at``, held beyond the nodes."""
    from scipy.interpolate import PchipInterpolator

    return PchipInterpolator(nodes, values, axis=axis)(np.clip(at, nodes[0], nodes[-1]))


def linear_weights(mu: NDArrayFloat) -> NDArrayFloat:
    """
    Weights ``W`` of the evenly spaced cosines ``mu`` (0 to 1) such that ``Σ W_k g_k = ∫₀¹ g(μ) 2μ dμ`` for ``g``
    linear between them, as the texture reads the table: ``2 μ_k h`` inside, ``h²/3`` at 0 and ``h − h²/3`` at 1.

    >>> w = linear_weights(np.linspace(0, 1, 5))
    >>> round(float(w.sum()), 12), round(float(w @ np.linspace(0, 1, 5)), 12)  # ∫ 2μ dμ, ∫ 2μ² dμ
    (1.0, 0.666666666667)
    """
    h = float(mu[1] - mu[0])
    weights = 2 * mu * h
    weights[0], weights[-1] = h * h / 3, h - h * h / 3
    return weights


def _conserving(brdf: NDArrayFloat, albedo: NDArrayFloat, mu: NDArrayFloat, sweeps: int = 60) -> NDArrayFloat:
    """``brdf`` scaled symmetrically, ``f c_o c_i``, so that at every cosine of incidence its integral over exit
    directions as the BSDF reads it (:func:`linear_weights`) is ``albedo`` (reciprocity kept)."""
    weights = np.pi * linear_weights(mu)
    scale = np.ones(albedo.shape)
    lit = albedo > 0
    for _ in range(sweeps):
        seen = np.einsum("...oi,o,...o->...i", brdf, weights, scale) * scale
        scale = np.where(lit, scale * np.sqrt(np.divide(albedo, seen, out=np.ones_like(seen), where=seen > 0)), 1.0)
    return brdf * scale[..., :, None] * scale[..., None, :]


def table_of_layers(layers, wavelengths: NDArrayFloat, quad_pts: int = QUAD_PTS_TABLE,
                    steps: int = COSINE_STEPS) -> SlabTable:
    """
    The :class:`SlabTable` of layers (top first, each with ``mu_a_per_mm``, ``mu_s_per_mm``, ``g``,
    ``thickness_mm`` and one shared ``n``, as :func:`~skinrender.datasets.skin_model.skin_layers` gives them)
    on their ``wavelengths`` (nm, evenly spaced), at ``quad_pts`` adding-doubling points and ``steps`` cosines.

    Examples
    --------
    >>> from skinrender.datasets.skin_model import skin_layers, reflectance_of_layers
    >>> layers = skin_layers([450.0, 650.0])
    >>> table = table_of_layers(layers, [450.0, 650.0])
    >>> table.brdf.shape, bool(np.abs(table.ur1 - reflectance_of_layers(layers, quad_pts=32)).max() < 1e-12)
    ((2, 64, 64), True)
    """
    from ..datasets.adding_doubling import Slab, angular_reflectance

    indices = {float(layer.n) for layer in layers}
    n = indices.pop() if len(indices) == 1 else None
    if n is None:
        from ..errors import SkinrenderError

        raise SkinrenderError(f"the layers must share one refractive index, got {sorted({layer.n for layer in layers})}")
    slabs = [Slab(layer.mu_a_per_mm, layer.mu_s_per_mm, layer.g, layer.thickness_mm) for layer in layers]
    nodes = angular_reflectance(slabs, n=n, quad_pts=quad_pts)
    mu = np.linspace(0.0, 1.0, int(steps))
    t_nodes, t_grid = 1.0 - nodes.specular, 1.0 - fresnel_from_air(mu, n)
    under = nodes.brdf / (t_nodes[:, None] * t_nodes[None, :])  # h: the light under the surface
    under = _along(nodes.mu, _along(nodes.mu, under, mu, -1), mu, -2)
    under = (under + np.swapaxes(under, -1, -2)) / 2  # PCHIP is not linear: one axis first breaks symmetry by ~1e-5
    albedo_nodes = np.pi * np.einsum("...oi,o->...i", nodes.brdf, nodes.weights)
    albedo = _along(nodes.mu, albedo_nodes / t_nodes, mu, -1) * t_grid
    brdf = _conserving(np.clip(under, 0.0, None) * t_grid[:, None] * t_grid[None, :], albedo, mu)
    ur1 = nodes.albedo()[..., -1]
    for array in (mu, brdf, albedo, ur1):
        array.setflags(write=False)
    return SlabTable(np.asarray(wavelengths, dtype=np.float64), mu, brdf, albedo, ur1, float(n), nodes)


def slab_table(spec: str, grid: WavelengthGrid, where: str = "skin") -> SlabTable:
    """
    The :class:`SlabTable` of a skin spec's layers on ``grid`` (the skin model's parameters, or the model fitted
    to a measured reflectance: :func:`~skinrender.rendering.subsurface.skin_media_of`, refused naming ``where``
    when it does not fit). Cached per spec and grid.
    """
    return _slab_table(str(spec).strip(), grid, where)


@lru_cache(maxsize=64)
def _slab_table(spec: str, grid: WavelengthGrid, where: str) -> SlabTable:
    from .subsurface import skin_media_of

    media = skin_media_of(spec, grid, where)
    return table_of_layers(media.layers, grid.wavelengths)
