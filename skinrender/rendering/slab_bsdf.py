"""
The slab's table as a Mitsuba BSDF
==================================

Mitsuba 3 has no plugin for a spectral, tabulated reflectance, so this module
registers one written in Python (``mi.BSDF`` subclass, :func:`register`): the
skin as a surface that reflects as the skin model's flat slab does
(:class:`~skinrender.rendering.slab_table.SlabTable`), per wavelength. It runs
in the JIT variants (``llvm_ad_spectral``, ``cuda_ad_spectral``), where
Mitsuba traces the Python code once into its kernels; ``scalar_spectral``
would call it per ray.

-   :data:`PLUGIN_SLAB`: the plugin's name; :func:`register` registers it for
    the variant set; :func:`slab_bsdf_dict` the dictionary of one table.
-   :func:`table_key`, :func:`table_of_key`: how a dictionary names its table.

The table is named by a key, not carried in the dictionary, and the plugin
exposes no parameter to ``mi.traverse``: another skin is another document,
loaded anew (the spectral face renders' copy of new values into a kept
document, :mod:`skinrender.rendering.face.revalue`, finds no match for it and
loads it anew).

Two lobes
---------
-   **The surface** (component 0): the smooth boundary's Fresnel reflection,
    ``F(cos θ_i)`` of index ``n``, white; a delta reflection at ``alpha`` 0,
    else a GGX microfacet reflection of roughness ``alpha`` (visible normals
    sampled), which lets point lights make highlights (a delta lobe never
    meets a point light).
-   **The body** (component 1): the table's ``f(λ, μ_o, μ_i)``, the light that
    entered the slab and left it, read from a 3-D texture (λ, μ_i, μ_o),
    linear in each, clamped at the wavelengths' ends. Sampled by the cosine
    (``f`` is smooth and nearly flat away from grazing angles).

A sample picks the surface with probability ``F / (F + A)``, ``A`` the body's
directional-hemispherical reflectance at ``cos θ_i`` averaged over the
wavelengths, so that under light from every direction the two choices carry
about the same weight. ``pdf`` and ``eval`` give the smooth lobes (the body,
and the surface where it is rough) as Mitsuba's ``plastic`` does.

Its limits: a flat patch seen from straight above under a uniform sky of
radiance ``L`` reflects ``L · UR1`` (the table's
:attr:`~skinrender.rendering.slab_table.SlabTable.ur1`) at ``alpha`` 0;
under a directional light of irradiance ``E`` at ``cos θ_i`` it reflects
``f(λ, 1, cos θ_i) E cos θ_i`` towards that viewer, which is
``A(cos θ_i) E cos θ_i / π`` only where the slab is Lambertian, and it is
not (``tests/rendering/test_slab_bsdf.py`` checks both).

Units: wavelengths nm; BRDF sr⁻¹.
"""

from __future__ import annotations

import itertools
import sys

import numpy as np

from .slab_table import SlabTable

__all__ = ["PLUGIN_SLAB", "register", "slab_bsdf_dict", "table_key", "table_of_key"]

PLUGIN_SLAB = "skinrender_slab"
"""The registered plugin's name."""

_TABLES: dict[str, SlabTable] = {}
_KEYS: dict[int, str] = {}
_COUNTER = itertools.count()
_REGISTERED: set[str] = set()


def table_key(table: SlabTable) -> str:
    """A name for ``table`` that a plugin's dictionary carries (the table is kept while the process runs)."""
    key = _KEYS.get(id(table))
    if key is None or _TABLES.get(key) is not table:
        key = f"slab{next(_COUNTER)}"
        _KEYS[id(table)], _TABLES[key] = key, table
    return key


def table_of_key(key: str) -> SlabTable:
    """The table :func:`table_key` named ``key``."""
    return _TABLES[key]


def slab_bsdf_dict(table: SlabTable, alpha: float = 0.0) -> dict:
    """
    The plugin's dictionary for ``table``: a delta surface reflection at ``alpha`` 0, else GGX of roughness
    ``alpha``. The plugin is registered for Mitsuba's variant if one is set (else :func:`register` it before
    loading the dictionary).
    """
    mi = sys.modules.get("mitsuba")
    if mi is not None and mi.variant() is not None:
        register(mi)
    return {"type": PLUGIN_SLAB, "table": table_key(table), "alpha": float(alpha)}


def register(mi) -> None:
    """Register :data:`PLUGIN_SLAB` for ``mi``'s variant (once per variant)."""
    variant = mi.variant()
    if variant in _REGISTERED:
        return
    cls = _plugin_class(mi)
    mi.register_bsdf(PLUGIN_SLAB, lambda props: cls(props))
    _REGISTERED.add(variant)


def _plugin_class(mi):
    import drjit as dr

    flags = mi.BSDFFlags

    class SlabBSDF(mi.BSDF):
        """The slab's two lobes (module docstring), for one variant."""

        def __init__(self, props):
            mi.BSDF.__init__(self, props)
            table = table_of_key(props["table"])
            self.alpha = float(props["alpha"]) if "alpha" in props else 0.0
            self.n = float(table.n)
            lam = table.wavelengths
            self.start, self.step = float(lam[0]), float(lam[1] - lam[0]) if lam.size > 1 else 1.0
            self.count = int(lam.size)
            data = np.ascontiguousarray(np.swapaxes(table.brdf, 1, 2), dtype=np.float32)[..., None]  # (λ, μi, μo)
            self.texture = mi.Texture3f(mi.TensorXf(data), use_accel=False, filter_mode=dr.FilterMode.Linear,
                                        wrap_mode=dr.WrapMode.Clamp)
            self.albedo = mi.Float(np.asarray(table.albedo.mean(axis=0), dtype=np.float32))
            self.steps = int(table.mu.size)
            self.lobes = (flags.GlossyReflection if self.alpha > 0 else flags.DeltaReflection, flags.DiffuseReflection)
            self.m_components = [lobe | flags.FrontSide for lobe in self.lobes]
            self.m_flags = self.m_components[0] | self.m_components[1]
            self.distribution = (mi.MicrofacetDistribution(mi.MicrofacetType.GGX, self.alpha, True)
                                 if self.alpha > 0 else None)

        def _coordinate(self, mu):
            return (dr.clip(mu, 0.0, 1.0) * (self.steps - 1) + 0.5) / self.steps

        def _body(self, wavelengths, cos_o, cos_i):
            """``f(λ, μ_o, μ_i)`` at each of the ray's wavelengths (sr⁻¹)."""
            x, y = self._coordinate(cos_o), self._coordinate(cos_i)
            values = []
            for k in range(len(wavelengths)):
                z = ((wavelengths[k] - self.start) / self.step + 0.5) / self.count
                values.append(self.texture.eval(mi.Point3f(x, y, z))[0])
            return mi.Spectrum(*values)

        def _albedo(self, cos_i):
            """The body's directional-hemispherical reflectance at ``cos_i``, the wavelengths' mean."""
            position = dr.clip(cos_i, 0.0, 1.0) * (self.steps - 1)
            index = mi.UInt32(dr.minimum(dr.floor(position), self.steps - 2))
            t = position - mi.Float(index)
            return dr.lerp(dr.gather(mi.Float, self.albedo, index), dr.gather(mi.Float, self.albedo, index + 1), t)

        def _choice(self, ctx, cos_i):
            """``(F, probability of the surface)``, each lobe enabled or not by ``ctx``."""
            fresnel = mi.fresnel(cos_i, self.n)[0]
            surface = ctx.is_enabled(self.lobes[0], 0)
            body = ctx.is_enabled(self.lobes[1], 1)
            if surface and body:
                return fresnel, fresnel / dr.maximum(fresnel + self._albedo(cos_i), 1e-8)
            return fresnel, mi.Float(1.0 if surface else 0.0)

        def _rough(self, si, wo, cos_i, cos_o):
            """GGX reflection ``F D G / (4 cos θ_i)`` (times cos θ_o, as ``eval``) and its pdf."""
            h = dr.normalize(si.wi + wo)
            d = self.distribution.eval(h)
            value = mi.fresnel(dr.dot(si.wi, h), self.n)[0] * d * self.distribution.G(si.wi, wo, h) / (4 * cos_i)
            pdf = self.distribution.pdf(si.wi, h) / (4 * dr.abs(dr.dot(wo, h)))
            return value, pdf

        def eval(self, ctx, si, wo, active=True):
            cos_i, cos_o = mi.Frame3f.cos_theta(si.wi), mi.Frame3f.cos_theta(wo)
            active = active & (cos_i > 0) & (cos_o > 0)
            value = mi.Spectrum(0.0)
            if ctx.is_enabled(self.lobes[1], 1):
                value += self._body(si.wavelengths, cos_o, cos_i) * cos_o
            if self.alpha > 0 and ctx.is_enabled(self.lobes[0], 0):
                value += self._rough(si, wo, cos_i, cos_o)[0]
            return dr.select(active, value, 0.0)

        def pdf(self, ctx, si, wo, active=True):
            cos_i, cos_o = mi.Frame3f.cos_theta(si.wi), mi.Frame3f.cos_theta(wo)
            active = active & (cos_i > 0) & (cos_o > 0)
            _, surface = self._choice(ctx, cos_i)
            pdf = (1.0 - surface) * cos_o / dr.pi
            if self.alpha > 0:
                pdf += surface * self._rough(si, wo, cos_i, cos_o)[1]
            return dr.select(active, pdf, 0.0)

        def eval_pdf(self, ctx, si, wo, active=True):
            return self.eval(ctx, si, wo, active), self.pdf(ctx, si, wo, active)

        def sample(self, ctx, si, sample1, sample2, active=True):
            cos_i = mi.Frame3f.cos_theta(si.wi)
            active = active & (cos_i > 0)
            fresnel, surface = self._choice(ctx, cos_i)
            chose_surface = sample1 < surface
            bs = mi.BSDFSample3f()
            bs.eta = 1.0
            diffuse_wo = mi.warp.square_to_cosine_hemisphere(sample2)
            if self.alpha > 0:
                m = self.distribution.sample(si.wi, sample2)[0]
                wo = dr.select(chose_surface, mi.reflect(si.wi, m), diffuse_wo)
                bs.wo = wo
                bs.sampled_component = dr.select(chose_surface, mi.UInt32(0), mi.UInt32(1))
                bs.sampled_type = dr.select(chose_surface, mi.UInt32(+flags.GlossyReflection),
                                            mi.UInt32(+flags.DiffuseReflection))
                value, bs.pdf = self.eval_pdf(ctx, si, wo, active)
                ok = active & (bs.pdf > 0) & (mi.Frame3f.cos_theta(wo) > 0)
                return bs, dr.select(ok, value / dr.maximum(bs.pdf, 1e-20), 0.0)
            bs.wo = dr.select(chose_surface, mi.reflect(si.wi), diffuse_wo)
            bs.sampled_component = dr.select(chose_surface, mi.UInt32(0), mi.UInt32(1))
            bs.sampled_type = dr.select(chose_surface, mi.UInt32(+flags.DeltaReflection),
                                        mi.UInt32(+flags.DiffuseReflection))
            cos_o = mi.Frame3f.cos_theta(bs.wo)
            bs.pdf = dr.select(chose_surface, surface, (1.0 - surface) * cos_o / dr.pi)
            body = self._body(si.wavelengths, cos_o, cos_i) * dr.pi / dr.maximum(1.0 - surface, 1e-20)
            weight = dr.select(chose_surface, mi.Spectrum(fresnel / dr.maximum(surface, 1e-20)), body)
            ok = active & (bs.pdf > 0) & (cos_o > 0)
            return bs, dr.select(ok, weight, 0.0)

        def to_string(self):
            return f"SlabBSDF[n={self.n}, alpha={self.alpha}, wavelengths={self.count}, cosines={self.steps}]"

    return SlabBSDF
