"""
The skin's rough boundary, energy conserving
============================================

Mitsuba's ``roughdielectric`` scatters light once off its microfacets: the
light a microfacet would send on to another one is lost. For skin's boundary
(GGX α 0.35, n 1.4) that is 1–2 % of the light arriving from air within 25°
of the normal, 7 % at 60°, 28 % at grazing, and 12–33 % of the light
arriving from inside, which skin's light meets many times before it leaves:
a flat slab under a uniform sky lost 9–19 % of its reflectance, red most,
and a slab that does not absorb, inside the sky on every side (the white
furnace, where every pixel must be the sky), 29 % (``docs/subsurface.md``).

``skinvolpath`` puts the lost light back at a rough skin boundary as lobes
of the shape of Kulla & Conty's (2017) multiple-scattering lobe:
cosine-distributed, symmetric in their directions (reciprocal), with
``E(μ)`` the single-scattering energy albedo (reflected plus transmitted
light, the transmission's radiance factor ``η²`` taken out) on each side and
``E_avg = 2 ∫ E(μ) μ dμ``::

    K(ω, ω') = (1 − E_out(μ)) (1 − E_in(μ')) / (π (1 − E_avg,in))     ω outside, ω' inside

Light arriving from air loses ``1 − E_out(μ)`` and ``K`` carries all of it
into the skin (light scattered between a dielectric's microfacets mostly
refracts); by reciprocity the same ``K`` carries light from inside out,
``share = (1 − E_avg,out) / (1 − E_avg,in)`` (0.24) of what is lost there,
and the rest is reflected back inside by ``(1 − share) (1 − E_in(μ))
(1 − E_in(μ')) / (π (1 − E_avg,in))``. Every meeting then returns all the
light (the white furnace within 1.3 %), and the single-scattering lobes are
Mitsuba's.

-   :class:`Boundary`: the skin's BSDF as ``skinvolpath`` evaluates and
    samples it (the lobes added where the boundary is rough).
-   :func:`albedo_table`: ``E`` on :data:`ALBEDO_NODES` cosines per side,
    from Mitsuba's own BSDF sampling, cached per variant, α and η; and
    ``E_avg`` per side.
-   :func:`albedo`, :func:`lost_lobes`: ``E`` at a cosine; the lobes'
    values, chances and densities, traced.

Units: cosines; α the GGX roughness; η the skin's index over air's.

References
----------
-   :cite:`Kulla2017` : C. Kulla, A. Conty (2017). Revisiting physically based shading at Imageworks.
"""

from __future__ import annotations

import numpy as np

__all__ = ["ALBEDO_NODES", "ALBEDO_SAMPLES", "Boundary", "albedo_table", "albedo", "lost_lobes"]

ALBEDO_NODES = 65
"""Cosines per side (0 to 1, evenly) of the albedo's table; linear between them."""

ALBEDO_SAMPLES = 2**15
"""BSDF samples per cosine: a standard error of ~0.2 % of ``E``."""

_TABLES: dict[tuple, tuple] = {}


def albedo_table(mi, alpha: float, eta: float) -> tuple[np.ndarray, np.ndarray]:
    """
    ``E(μ)`` of a GGX ``roughdielectric`` of roughness ``alpha`` and index ``eta`` (inside over outside), shape
    ``(2, ALBEDO_NODES)``: from outside (row 0) and from inside (row 1), at ``μ = k / (ALBEDO_NODES − 1)``
    (``μ`` 0 taken as 0.001); and ``E_avg`` per side, shape ``(2,)``. ``mi`` is ``mitsuba`` with a JIT variant
    set. Cached; the same samples each time.
    """
    key = (mi.variant(), float(alpha), float(eta))
    if key not in _TABLES:
        bsdf = mi.load_dict({"type": "roughdielectric", "distribution": "ggx", "alpha": float(alpha),
                             "int_ior": float(eta), "ext_ior": 1.0})
        rng = np.random.default_rng(0)
        mu = np.maximum(np.linspace(0.0, 1.0, ALBEDO_NODES), 1e-3)
        table = np.empty((2, ALBEDO_NODES))
        count = ALBEDO_NODES * ALBEDO_SAMPLES
        for row, side in enumerate((1.0, -1.0)):
            bs, weight = bsdf.sample(mi.BSDFContext(), _interaction(mi, np.repeat(mu, ALBEDO_SAMPLES) * side, count),
                                     mi.Float(rng.random(count)), mi.Point2f(rng.random(count), rng.random(count)))
            value = np.array(weight)
            value = value[0] if value.ndim > 1 else value
            crossed = np.array(bs.wo.z) * side < 0
            value = np.where(crossed, value * (eta**2 if side > 0 else eta**-2), value)  # the radiance factor out
            table[row] = np.minimum(value.reshape(ALBEDO_NODES, ALBEDO_SAMPLES).mean(axis=1), 1.0)
        nodes = np.linspace(0.0, 1.0, ALBEDO_NODES)
        average = np.trapezoid(table * nodes, nodes, axis=1) * 2.0
        _TABLES[key] = table, average
    return _TABLES[key]


def _interaction(mi, cos: np.ndarray, count: int):
    """Surface interactions with the normal +z, ``wi`` at cosines ``cos`` (in the xz plane)."""
    import drjit as dr

    si = dr.zeros(mi.SurfaceInteraction3f, count)
    si.sh_frame = mi.Frame3f(mi.Vector3f(0.0, 0.0, 1.0))
    si.wi = mi.Vector3f(mi.Float(np.sqrt(np.maximum(1.0 - cos**2, 0.0))), mi.Float(np.zeros(count)), mi.Float(cos))
    return si


def albedo(mi, table, cos):
    """``E`` at ``cos`` (a traced ``Float``, > 0 outside), ``table`` :func:`albedo_table`'s flattened into a
    ``Float`` (outside's row first)."""
    import drjit as dr

    x = dr.minimum(dr.abs(cos), 1.0) * (ALBEDO_NODES - 1)
    low = mi.UInt32(dr.minimum(dr.floor(x), ALBEDO_NODES - 2))
    row = dr.select(cos > 0, 0, ALBEDO_NODES)
    return dr.lerp(dr.gather(mi.Float, table, row + low), dr.gather(mi.Float, table, row + low + 1),
                   x - mi.Float(low))


def lost_lobes(mi, table, average, eta: float, cos_i, cos_o):
    """
    The lost light's lobes at ``wi``, ``wo`` (cosines ``cos_i``, ``cos_o``, traced; > 0 outside; module
    docstring): ``(value · |μ_o|, chance of the lobe wo is in, its cosine density)``; from outside the lobe into
    the skin, from inside the lobes out (the share ``(1 − E_avg,out) / (1 − E_avg,in)``) and back. ``average``
    the :func:`albedo_table`'s ``E_avg`` (a Python pair); ``eta`` inside over outside (the transmitted radiance
    scales by ``1/η²`` going in, ``η²`` coming out, as Mitsuba's transmission does).
    """
    import drjit as dr

    a_out, a_in = float(average[0]), float(average[1])
    share = (1.0 - a_out) / (1.0 - a_in)
    outside, same = cos_i > 0, cos_i * cos_o > 0
    lost_i, lost_o = 1.0 - albedo(mi, table, cos_i), 1.0 - albedo(mi, table, cos_o)
    cosine = dr.abs(cos_o) / dr.pi
    kernel = lost_i * lost_o / (1.0 - a_in) * cosine  # symmetric: from inside ×(1 − share) back, ×η² out
    value = dr.select(outside, dr.select(same, 0.0, kernel / eta**2),
                      dr.select(same, (1.0 - share) * kernel, kernel * eta**2))
    chance = dr.select(outside, dr.select(same, 0.0, lost_i), dr.select(same, 1.0 - share, share) * lost_i)
    return value, chance, cosine


class Boundary:
    """
    A skin surface's BSDF as :mod:`~skinrender.rendering.skin_integrator` evaluates and samples it: Mitsuba's,
    with the lost light's lobes added (:func:`lost_lobes`) where it is a rough boundary of skin and ``alpha`` > 0
    (the roughness its ``E`` is tabulated for; 0: Mitsuba's BSDF as it is). There, emitter sampling counts delta
    lights only and BSDF sampling the others, unweighted: Mitsuba's ``roughdielectric`` samples a few directions
    its ``pdf()`` gives 0, so a multiple-importance weight on the mixture's density would not sum to one (measured:
    the white furnace 6 % bright).
    """

    def __init__(self, mi, alpha: float, eta: float):
        self.mi, self.eta = mi, float(eta)
        self.table = None
        if alpha > 0:
            table, average = albedo_table(mi, alpha, eta)
            self.table, self.average = mi.Float(table.ravel()), tuple(float(v) for v in average)
            self.out_share = (1.0 - self.average[0]) / (1.0 - self.average[1])

    def rough(self, si, bsdf, active):
        """Where ``si`` is a rough skin boundary (a shape with an interior medium, neither smooth nor null)."""
        mi = self.mi
        return active & (si.shape.interior_medium() != None) & ~mi.has_flag(  # noqa: E711
            bsdf.flags(), mi.BSDFFlags.Delta | mi.BSDFFlags.Null)

    def lights(self, si, bsdf, ds, active):
        """Where emitter sampling's light ``ds`` counts: everywhere but, with the lobes, a rough skin boundary's
        light that is not a delta."""
        return active if self.table is None else active & (ds.delta | ~self.rough(si, bsdf, active))

    def eval_pdf(self, ctx, bsdf, si, wo, active, parts: bool = False):
        """The value (times the cosine) and density at ``wo`` (local), the lobes added and the density mixed by the
        single-scattering albedo at a rough skin boundary; ``parts``: and the single-scattering density alone."""
        import drjit as dr

        value, pdf = bsdf.eval_pdf(ctx, si, wo, active)
        if self.table is None:
            return (value, pdf, pdf) if parts else (value, pdf)
        rough = self.rough(si, bsdf, active)
        lobe, chance, density = lost_lobes(self.mi, self.table, self.average, self.eta, si.wi.z, wo.z)
        e = albedo(self.mi, self.table, si.wi.z)
        mixed = dr.select(rough, value + lobe, value), dr.select(rough, e * pdf + chance * density, pdf)
        return (*mixed, pdf) if parts else mixed

    def sample(self, ctx, bsdf, si, sampler, active):
        """
        ``(wo (local), weight, density, whole)``: the BSDF's sample, or at a rough skin boundary the mixture of its
        sample (chance ``E(μ_i)``) and the lobes (into the skin from outside; from inside out, chance
        ``share · (1 − E)``, or back); ``whole``: what it finds counts unweighted (a delta, or the mixture's).
        """
        import drjit as dr

        mi = self.mi
        u_1, u_2 = sampler.next_1d(active), sampler.next_2d(active)
        if self.table is None:
            bs, weight = bsdf.sample(ctx, si, u_1, u_2, active)
            return bs.wo, weight, bs.pdf, mi.has_flag(bs.sampled_type, mi.BSDFFlags.Delta)
        rough = self.rough(si, bsdf, active)
        e = dr.select(rough, albedo(mi, self.table, si.wi.z), 1.0)
        lobe = rough & (u_1 >= e)
        bs, weight = bsdf.sample(ctx, si, dr.minimum(u_1 / e, 0.99999994), u_2, active & ~lobe)
        across = (si.wi.z > 0) | (u_1 < e + self.out_share * (1.0 - e))
        turned = mi.warp.square_to_cosine_hemisphere(u_2)
        turned.z = dr.mulsign(turned.z, dr.select(across, -si.wi.z, si.wi.z))
        wo = dr.select(lobe, turned, bs.wo)
        value, pdf, single = self.eval_pdf(ctx, bsdf, si, wo, rough, parts=True)
        # the BSDF's own sample only where its pdf() says it could be (else the lobes' density would count it)
        kept = (pdf > 0) & (lobe | ((bs.pdf > 0) & (single > 0) & (dr.max(weight) > 0)))
        weight = dr.select(rough, dr.select(kept, value / pdf, 0.0), weight)
        return wo, weight, dr.select(rough, pdf, bs.pdf), rough | mi.has_flag(bs.sampled_type, mi.BSDFFlags.Delta)
