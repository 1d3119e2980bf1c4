"""
The skin's path tracer
======================

``skinvolpath``: a Mitsuba 3 integrator, written in Python and traced by
Dr.Jit into one kernel, for skin as the skin model's layers under a
dielectric boundary (:mod:`skinrender.rendering.subsurface`). It replaces
``volpathmis`` for skin because Mitsuba offsets a ray leaving a surface by
``(1 + max|p|) · 8.9e-5`` scene units along the normal and a ray leaving a
medium interaction not at all, so a path entering the skin, or reflected
inside it, skips that much of it: 6–16 % of a slab's light 100 mm from the
origin (``docs/subsurface.md``).

-   :func:`register`: the plugin registered for the variant set (JIT variants).
-   :data:`PLUGIN`, :data:`RR_WEIGHT`, :data:`WALK_MAX`, :data:`THROUGH_DEPTH_MM`, :data:`THROUGH_G`: its
    name and the defaults of its properties.

What it does
------------
In air it is a path tracer (emitter sampling and BSDF sampling combined by
multiple importance sampling, Russian roulette from ``rr_depth`` bounces,
``hide_emitters``). A shape with an ``interior`` medium is skin's outer
surface. Where a path refracts into it, the **walk** starts:

-   **Free flights from the true point.** Each flight starts at the exact
    point the path is at (the surface point, or the last scattering point);
    the intersection query that finds the boundary starts at Mitsuba's offset
    origin (after a surface event) or a few float32 steps behind the point
    (:func:`margin`), and the boundary's distance is measured from the true
    point. No skin is skipped, at any distance from the origin.
-   **Layers by depth** (``epidermis_thickness`` > 0): the depth below the
    outer surface is tracked along the normal of the last point where the
    path touched it, layers locally flat; the epidermis is ``depth <
    epidermis_thickness``, the dermis below. Exact for flat skin; on curved
    skin the boundary between the layers would drift by ``r² / 2R`` (``r``
    the path's lateral distance from that point, ``R`` the radius of
    curvature), so a scattering within ``reanchor_depth`` of the epidermis
    measures its depth again, to the surface straight above it, and takes
    that point's normal: the drift is then over one flight, not the whole
    walk. Without a thickness (``0``) a shape with a ``null`` BSDF inside the
    skin is the layers' boundary (an offset surface).
-   **Spectral MIS over the path.** Each path draws one of its four
    wavelengths (the hero) and samples every flight by the hero's extinction;
    each wavelength's value is weighted by the balance heuristic over the
    four wavelengths' densities of the *whole* walk (Wilkie et al. 2014), so
    a wavelength's weight never exceeds four times its survival
    (product of its albedos).
-   **Fresnel splitting at a smooth boundary**: where a path meets a smooth
    (``dielectric``) skin surface, from air or from inside, the light met
    straight along the branch not taken (reflected, or refracted) is added
    with its Fresnel weight, and the branch taken counts the light it meets
    first with its own: a dark skin's specular reflection is not a lottery of
    3 % of its paths (per-path spread 3–4 → 1.6–1.8 on a dark slab).
-   **Through the boundary to a point light** (a rough boundary): at a
    scattering within ``nee_depth`` of the surface, a direction is drawn
    about the one the boundary refracts towards a point light
    (Henyey–Greenstein of ``nee_g``), followed to the boundary and connected
    to the light there; the walk's own way to that light (its phase sampling
    meets the boundary, whose emitter sampling finds the light) is weighed
    against it by the balance heuristic. Where a rough boundary's
    transmission lobe is narrow against the skin's near-isotropic light, the
    walk's own way alone is a lottery: fireflies (a slab under a point light:
    per-path spread 5.6 → 1.8, 9.6 → 2.3 for dark skin, at 1.9× the CPU time).
-   **Russian roulette on the weight**: a walk whose largest weight over its
    wavelengths falls below ``rr_weight`` survives with probability
    weight / ``rr_weight`` (its weight divided by it): unbiased, and, unlike
    Mitsuba's roulette (at most 0.95 a bounce), harmless to the hundreds of
    scatterings of light in skin. A walk ends at ``max_walk`` events at the most.
-   **Flat shading at skin**: a skin surface's BSDF takes the triangle's own
    normal, so the side a path is on and the side its BSDF sees never differ.

The walk uses neither Mitsuba's media nor its medium pointers: the integrator
takes the two layers' media (``epidermis``, ``dermis``: their extinction,
albedo and Henyey–Greenstein ``g``) and the boundary's ``eta``; the skin
shape's ``interior`` only marks it as skin.

References
----------
-   :cite:`Jakob2022` : W. Jakob et al. (2022). Mitsuba 3 renderer.
-   :cite:`Wilkie2014` : A. Wilkie et al. (2014). Hero wavelength spectral sampling.
-   :cite:`Veach1997` : E. Veach (1997). Multiple importance sampling (the balance heuristic).
"""

from __future__ import annotations

from ..errors import SkinrenderError
from .rough_boundary import Boundary
from .skin_sampling import (bind, coefficients, component, flat, hg_pdf, hg_sample, inside_direction, layer_lengths,
                            margin, phase_g, power, spectral)

__all__ = ["PLUGIN", "RR_WEIGHT", "WALK_MAX", "THROUGH_DEPTH_MM", "THROUGH_G", "REANCHOR_DEPTH_MM", "register"]

PLUGIN = "skinvolpath"
"""The integrator's name in a Mitsuba document."""

RR_WEIGHT = 0.3
"""A walk's weight (largest over its wavelengths) below which Russian roulette plays: paths per CPU second over
the variance per path, 2.1 × 10⁴ for a light slab and 2.2 × 10⁴ for a dark one, against 1.6–1.7 × 10⁴ at 0.1 and
2.2–2.5 × 10⁴ at 0.6 (whose spread per path is larger) (``docs/subsurface.md``)."""

WALK_MAX = 2**16
"""Events (scatterings and boundary contacts) a walk may have."""

THROUGH_DEPTH_MM = 0.1
"""Scatterings within this depth of the skin's surface, mm, connect to point lights through it (``nee_depth``):
deeper ones rarely reach it (measured while choosing it, a light slab under a point light, 16 × 16 px × 256 spp: the
per-path spread 2.1 at 0.05 mm, 1.7 at 0.1 mm and 1.7 at 0.3 mm, for 25 % more time)."""

THROUGH_G = 0.95
"""The Henyey–Greenstein ``g`` of the directions drawn about the one leaving towards a point light (``nee_g``;
measured as :data:`THROUGH_DEPTH_MM`: the per-path spread 1.8, 1.7, 1.9 at 0.9, 0.95, 0.98)."""

REANCHOR_DEPTH_MM = 3.0
"""A scattering whose depth by the walk's reckoning is within this of the epidermis, mm, measures it again: the
distance to the surface straight above it along the last normal, whose normal it takes (``reanchor_depth``). A
sphere of dark skin 10 mm in radius rendered 42 % too bright in red with the depth reckoned from the last contact
alone, 2.5 % re-anchoring within 1 mm, 1.1 % within 3 mm and 1.0 % at every scattering (± 0.9 %); on a slab, for
24 %, 33 % and 40 % more time than none (``docs/subsurface.md``)."""

_REGISTERED: set[str] = set()
mi = dr = None  # the mitsuba and drjit modules, set by register (imported late: variants.mitsuba sets libLLVM first)


def register(module) -> None:
    """
    Register :data:`PLUGIN` for the variant set in ``module`` (``mitsuba``), once per variant. A JIT variant only:
    the walk is traced into one kernel; in a scalar variant Python would run per sample.

    Raises
    ------
    SkinrenderError
        A scalar variant.
    """
    global mi, dr
    import drjit

    mi, dr = module, drjit
    bind(module)
    variant = mi.variant()
    if variant in _REGISTERED:
        return
    if variant.startswith("scalar"):
        raise SkinrenderError(f"variant {variant}: the subsurface-volume level's integrator runs in llvm_ad_spectral or "
                              "cuda_ad_spectral (one traced kernel), not in a scalar variant", role="variant")
    cls = _integrator_class()
    mi.register_integrator(PLUGIN, lambda props: cls(props))
    _REGISTERED.add(variant)


def _integrator_class():
    class SkinVolpath(mi.SamplingIntegrator):
        def __init__(self, props):
            super().__init__(props)
            self.dermis = props["dermis"]
            self.epidermis = props["epidermis"] if "epidermis" in props.keys() else self.dermis
            self.thickness = float(props.get("epidermis_thickness", 0.0))
            self.g = (phase_g(self.epidermis), phase_g(self.dermis))
            self.eta = float(props.get("eta", 1.4))
            self.max_walk = int(props.get("max_walk", WALK_MAX))
            depth = int(props.get("max_depth", -1))
            self.max_depth = 2**32 - 1 if depth < 0 else depth
            self.rr_depth = int(props.get("rr_depth", 5))
            self.rr_weight = float(props.get("rr_weight", RR_WEIGHT))
            self.hide_emitters = bool(props.get("hide_emitters", False))
            self.nee_depth = float(props.get("nee_depth", THROUGH_DEPTH_MM))
            self.nee_g = float(props.get("nee_g", THROUGH_G))
            self.through = bool(props.get("through", True))
            self.reanchor = float(props.get("reanchor_depth", 0.0))  # 0: by the last contact alone
            # the skin's BSDF as the walk uses it: a rough boundary's lost light put back (rough_boundary)
            self.boundary = Boundary(mi, float(props.get("boundary_alpha", 0.0)), self.eta)
            self.points = False

        def aov_names(self):
            return []

        def to_string(self):
            return f"SkinVolpath[epidermis_thickness={self.thickness}, eta={self.eta}]"

        @dr.syntax
        def sample(self, scene, sampler, ray, medium=None, active=True):
            ray = mi.Ray3f(ray)
            self.points = self.through and any(mi.has_flag(emitter.flags(), mi.EmitterFlags.Delta)
                                               for emitter in scene.emitters())
            lam = ray.wavelengths
            media = coefficients(self.epidermis, lam), coefficients(self.dermis, lam)
            hero = dr.minimum(mi.UInt32(sampler.next_1d() * 4), 3)
            ctx = mi.BSDFContext()
            L, beta = mi.Spectrum(0.0), mi.Spectrum(1.0)
            log_a, log_r = mi.Spectrum(0.0), mi.Spectrum(0.0)
            depth = mi.UInt32(0)
            active = mi.Bool(active)
            prev = dr.zeros(mi.SurfaceInteraction3f)
            prev_pdf, prev_delta, first = mi.Float(1.0), mi.Bool(True), mi.Float(1.0)

            while active:
                si = scene.ray_intersect(ray, active)
                weight = beta * spectral(log_a, log_r)
                # light met along the ray (by BSDF sampling)
                emitter = si.emitter(scene)
                seen = active & (emitter != None)  # noqa: E711
                if self.hide_emitters:
                    seen &= depth > 0
                ds = mi.DirectionSample3f(scene, si, prev)
                pdf_e = scene.pdf_emitter_direction(prev, ds, seen & ~prev_delta)
                L[seen] += weight * first * emitter.eval(si, seen) * dr.select(prev_delta, 1.0, power(prev_pdf, pdf_e))
                active &= si.is_valid() & (depth < self.max_depth)
                skin = active & (si.shape.interior_medium() != None)  # noqa: E711
                flat(si, skin, -ray.d)
                bsdf = si.bsdf(ray)
                # emitter sampling
                nee = active & mi.has_flag(bsdf.flags(), mi.BSDFFlags.Smooth)
                ds, em = scene.sample_emitter_direction(si, sampler.next_2d(nee), True, nee)
                nee = self.boundary.lights(si, bsdf, ds, nee & (ds.pdf != 0))
                value, pdf_b = self.boundary.eval_pdf(ctx, bsdf, si, si.to_local(ds.d), nee)
                L[nee] += weight * value * em * dr.select(ds.delta, 1.0, power(ds.pdf, pdf_b))
                # the next direction: Fresnel splitting at smooth skin, else the BSDF's sample
                smooth = skin & mi.has_flag(bsdf.flags(), mi.BSDFFlags.Delta)
                outside = si.wi.z > 0
                wo, b_weight, b_pdf, b_delta, chance, emitted = self._next_direction(scene, ctx, bsdf, si, sampler,
                                                                                    smooth, active)
                L[smooth] += weight * emitted
                active &= b_pdf > 0
                beta[active] *= b_weight
                prev[active] = si
                prev_pdf[active] = b_pdf
                prev_delta[active] = smooth | b_delta
                first = dr.select(smooth, chance, 1.0)
                ray[active] = si.spawn_ray(wo)
                depth[active] += 1
                if depth >= self.rr_depth:
                    q = dr.minimum(dr.max(beta * spectral(log_a, log_r)), 0.95)
                    active &= sampler.next_1d(active) < q
                    beta[active] /= q
                enter = active & skin & outside & (dr.dot(wo, si.n) < 0)
                walk = self._walk(scene, sampler, si, wo, lam, media, hero, enter, beta, log_a, log_r)
                L[enter] += walk[0]
                beta, log_a, log_r = walk[1], walk[2], walk[3]
                out = walk[4]
                ray[enter] = out[0]
                prev[enter] = out[1]
                prev_pdf[enter] = out[2]
                prev_delta[enter] = out[3]
                first[enter] = out[4]
                active &= ~enter | out[5]
            return L, mi.Bool(True), []

        def _next_direction(self, scene, ctx, bsdf, si, sampler, smooth, active):
            """The next direction at the skin's boundary (world), its weight, pdf and whether it is a delta:
            Fresnel splitting where the boundary is smooth (weight and pdf 1), the boundary's sample elsewhere;
            with the split's chance and the light met along the other branch (:meth:`_split`)."""
            split, chance, emitted = self._split(scene, si, sampler, smooth)
            b_wo, b_weight, b_pdf, b_delta = self.boundary.sample(ctx, bsdf, si, sampler, active)
            wo = si.to_world(b_wo)
            wo[smooth] = split
            b_weight[smooth] = 1.0
            b_pdf[smooth] = 1.0
            return wo, b_weight, b_pdf, b_delta, chance, emitted

        def _split(self, scene, si, sampler, active):
            """At a smooth boundary: the branch taken (world direction), the other branch's, and the light met
            straight along the other branch times its Fresnel weight."""
            r, cos_t, _, eta_ti = mi.fresnel(mi.Frame3f.cos_theta(si.wi), mi.Float(self.eta))
            reflected = si.to_world(mi.reflect(si.wi))
            refracted = si.to_world(mi.refract(si.wi, cos_t, eta_ti))
            take_reflection = sampler.next_1d(active) < r
            taken = dr.select(take_reflection, reflected, refracted)
            other = dr.select(take_reflection, refracted, reflected)
            other_weight = dr.select(take_reflection, 1.0 - r, r)
            look = active & (other_weight > 0)
            there = scene.ray_intersect(si.spawn_ray(other), look)
            emitter = there.emitter(scene)
            emitted = mi.Spectrum(0.0)
            emitted[look & (emitter != None)] = emitter.eval(there, look) * other_weight  # noqa: E711
            return taken, dr.select(take_reflection, r, 1.0 - r), emitted

        def _through(self, scene, sampler, x, d_in, g, z, in_epi, anchor, media, lam, active, beta, log_a, log_r):
            """
            From the scattering at ``x`` (arriving along ``d_in``, phase ``g``): a direction sampled about the one
            that leaves the skin towards a point light, the boundary it meets, and the light through it there;
            weighted against the walk's own way there (its phase sampling, then the boundary met) by the balance
            heuristic over both ways and the four wavelengths.
            """
            (epi_s, epi_t), (der_s, der_t) = media
            ctx = mi.BSDFContext()
            u = sampler.next_2d(active)
            ref = dr.zeros(mi.Interaction3f)
            ref.p, ref.wavelengths = x, lam
            ds, _ = scene.sample_emitter_direction(ref, u, False, active)
            aim, above = inside_direction(dr.normalize(ds.p - x), anchor, self.eta)
            active &= ds.delta & (ds.pdf > 0) & above
            w, q = hg_sample(self.nee_g, aim, sampler.next_2d(active))
            phase = hg_pdf(g, dr.dot(d_in, w))
            hit = scene.ray_intersect(mi.Ray3f(x - margin(x) * w, w, 0.0, lam), active)
            flat(hit, active & hit.is_valid(), -w)
            bsdf = hit.bsdf(mi.RayDifferential3f(mi.Ray3f(x, w, 0.0, lam)))
            active &= hit.is_valid() & (dr.dot(w, hit.n) > 0) & ~mi.has_flag(bsdf.flags(), mi.BSDFFlags.Null)
            l_1, l_2 = layer_lengths(z, -dr.dot(w, anchor), dr.maximum(dr.dot(hit.p - x, w), 0.0), in_epi,
                                     self.thickness)
            t_1, t_2 = dr.select(in_epi, epi_t, der_t), dr.select(in_epi, der_t, epi_t)
            log_t = -(t_1 * l_1 + t_2 * l_2)
            ds_y, em = scene.sample_emitter_direction(hit, u, True, active)
            active &= ds_y.delta & (ds_y.pdf > 0)
            value = self.boundary.eval_pdf(ctx, bsdf, hit, hit.to_local(ds_y.d), active)[0]
            top = dr.max(log_r)
            both = dr.mean(dr.exp(log_r - top) * (phase * dr.exp(log_t) + q))
            light = mi.Spectrum(0.0)
            light[active] = (beta * dr.exp(log_a + log_r - top) * phase * dr.exp(log_t) * value * em / both)
            return light

        @dr.syntax
        def _walk(self, scene, sampler, si, d, lam, media, hero, active, beta, log_a, log_r):
            """The walk under the skin from ``si`` along ``d``: (light, beta, log_a, log_r, (ray out, its
            surface interaction, BSDF pdf, delta, light already counted, left the skin))."""
            (epi_s, epi_t), (der_s, der_t) = media
            e = self.thickness
            ctx = mi.BSDFContext()
            L = mi.Spectrum(0.0)
            walking = mi.Bool(active)
            x, origin, from_surface = mi.Point3f(si.p), si.spawn_ray(d).o, mi.Bool(True)
            anchor, z = mi.Vector3f(si.n), mi.Float(0.0)
            in_epi = mi.Bool(True)
            events = mi.UInt32(0)
            left = mi.Bool(False)
            ray_out = si.spawn_ray(d)
            out_si = dr.zeros(mi.SurfaceInteraction3f)
            out_pdf, out_delta, out_first = mi.Float(1.0), mi.Bool(True), mi.Float(1.0)
            phase_x, near_x = mi.Float(0.0), mi.Bool(False)
            while walking:
                s_1, t_1 = dr.select(in_epi, epi_s, der_s), dr.select(in_epi, epi_t, der_t)
                s_2, t_2 = dr.select(in_epi, der_s, epi_s), dr.select(in_epi, der_t, epi_t)
                x_start, anchor_start, log_r_start = mi.Point3f(x), mi.Vector3f(anchor), mi.Spectrum(log_r)
                scattered = walking & ~from_surface  # the flight starts at a scattering (not at the surface)
                rate = -dr.dot(d, anchor)  # depth gained per unit length
                crosses = (e > 0) & dr.select(in_epi, rate > 0, rate < 0)
                t_cross = dr.select(crosses, dr.maximum((e - z) / rate, 0.0), dr.inf)
                tau = -dr.log(1.0 - sampler.next_1d(walking))
                m_1, m_2 = component(t_1, hero), component(t_2, hero)
                flight = dr.select(tau < m_1 * t_cross, tau / m_1, t_cross + (tau - m_1 * t_cross) / m_2)
                back = margin(x)
                start = dr.select(from_surface, origin, x - back * d)
                probe = mi.Ray3f(start, d, 0.0, lam)
                probe.maxt = flight + dr.norm(start - x)
                hit = scene.ray_intersect(probe, walking)
                t_hit = dr.maximum(dr.dot(hit.p - x, d), 0.0)
                met = walking & hit.is_valid() & (t_hit < flight)
                end = dr.select(met, t_hit, flight)
                l_1 = dr.minimum(end, t_cross)
                second = end > t_cross
                log_p = -(t_1 * l_1 + t_2 * (end - l_1))
                t_end, s_end = dr.select(second, t_2, t_1), dr.select(second, s_2, s_1)
                log_p[~met] += dr.log(t_end)
                log_r[walking] += log_p - component(log_p, hero)
                scatter = walking & ~met
                log_a[scatter] += dr.log(s_end / t_end)
                z[walking] += rate * end
                in_epi[walking & second] = ~in_epi
                x[scatter] = dr.fma(d, end, x)
                from_surface[scatter] = False
                d_in = mi.Vector3f(d)
                if dr.hint(self.reanchor > 0, mode="scalar"):  # the depth measured again: the surface right above
                    look = scatter & (e > 0) & (z < e + self.reanchor)
                    up = scene.ray_intersect(mi.Ray3f(x - margin(x) * anchor, anchor, 0.0, lam), look)
                    found = look & up.is_valid() & (up.shape.interior_medium() != None) & (dr.dot(anchor, up.n) > 0)  # noqa: E711
                    z[found] = dr.maximum(dr.dot(up.p - x, anchor), 0.0)
                    anchor[found] = up.n
                    in_epi[found] = z < e
                g = dr.select(in_epi, self.g[0], self.g[1])
                if dr.hint(self.points, mode="scalar"):  # to a point light through the boundary, from a scattering near the surface
                    L += self._through(scene, sampler, x, d_in, g, z, in_epi, anchor, media, lam,
                                       scatter & (z < self.nee_depth), beta, log_a, log_r)
                # Henyey–Greenstein
                d_new, phase_new = hg_sample(g, d, sampler.next_2d(scatter))
                d[scatter] = d_new
                phase_x[scatter] = phase_new
                near_x[scatter] = z < self.nee_depth
                events[walking] += 1
                # a surface: passed through (a null BSDF: the layers' boundary; or met from outside, a float32
                # rounding's doing), or the skin's boundary met from inside
                flat(hit, met, -d_in)
                bsdf = hit.bsdf(probe)
                through = met & (mi.has_flag(bsdf.flags(), mi.BSDFFlags.Null) | (dr.dot(d, hit.n) <= 0))
                boundary = met & ~through
                x[met] = hit.p
                origin[met] = hit.spawn_ray(d).o
                from_surface[met] = True
                in_epi[through & (e <= 0) & mi.has_flag(bsdf.flags(), mi.BSDFFlags.Null)] = dr.dot(d, hit.n) > 0
                outer = boundary & (hit.shape.interior_medium() != None)  # noqa: E711
                anchor[outer] = hit.n
                z[outer] = 0.0
                in_epi[outer & (e > 0)] = True
                weight = beta * spectral(log_a, log_r)
                nee = boundary & mi.has_flag(bsdf.flags(), mi.BSDFFlags.Smooth)
                ds, em = scene.sample_emitter_direction(hit, sampler.next_2d(nee), True, nee)
                nee = self.boundary.lights(hit, bsdf, ds, nee & (ds.pdf != 0))
                value, pdf_b = self.boundary.eval_pdf(ctx, bsdf, hit, hit.to_local(ds.d), nee)
                share = mi.Float(1.0)
                if dr.hint(self.points, mode="scalar"):  # MIS against the path through the boundary from the scattering it left
                    aim, above = inside_direction(dr.normalize(ds.p - x_start), anchor_start, self.eta)
                    q = dr.select(above & ds.delta & scattered & near_x, hg_pdf(self.nee_g, dr.dot(d_in, aim)), 0.0)
                    top = dr.max(log_r_start)
                    sampled = dr.exp(log_r_start - top) * phase_x * dr.exp(log_p)
                    share = dr.select(q > 0, dr.mean(sampled) / dr.mean(sampled + dr.exp(log_r_start - top) * q), 1.0)
                L[nee] += weight * value * em * share * dr.select(ds.delta, 1.0, power(ds.pdf, pdf_b))
                smooth = boundary & mi.has_flag(bsdf.flags(), mi.BSDFFlags.Delta)
                wo, b_weight, b_pdf, b_delta, chance, emitted = self._next_direction(scene, ctx, bsdf, hit, sampler,
                                                                                    smooth, boundary)
                L[smooth] += weight * emitted
                ok = boundary & (b_pdf > 0)
                beta[ok] *= b_weight
                leaves = ok & (dr.dot(wo, hit.n) > 0)
                stays = ok & ~leaves
                d[stays] = wo
                origin[stays] = hit.spawn_ray(wo).o
                left |= leaves
                ray_out[leaves] = hit.spawn_ray(wo)
                out_si[leaves] = hit
                out_pdf[leaves] = b_pdf
                out_delta[leaves] = smooth | b_delta
                out_first[leaves] = dr.select(smooth, chance, 1.0)
                walking &= ~boundary | stays
                # Russian roulette on the weight
                q = dr.minimum(dr.max(beta * spectral(log_a, log_r)) / self.rr_weight, 1.0)
                walking &= (sampler.next_1d(walking) < q) & (events < self.max_walk)
                beta[walking] /= q
            return L, beta, log_a, log_r, (ray_out, out_si, out_pdf, out_delta, out_first, left)

    return SkinVolpath
