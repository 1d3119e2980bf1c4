"""
Skin as participating media under a dielectric boundary
=======================================================

Mitsuba 3 has no BSSRDF: subsurface scattering in skin is rendered as the
skin model's layers inside a dielectric boundary of the skin's refractive
index, path traced by the project's own integrator
(:mod:`~skinrender.rendering.skin_integrator`, ``skinvolpath``). This module
holds what the chart's slabs (:mod:`~skinrender.rendering.subsurface_chart`)
and the face (:mod:`skinrender.rendering.face.effects.subsurface`) share: the
skin model's layers of a skin spec, the slab rendered and its
adding-doubling reflectance, the Mitsuba media and integrator.

-   :class:`SkinMedia`, :func:`skin_media_of`: the layers of a skin spec, from
    the skin model's parameters (``skin-model:melanin=…``) or fitted to a
    measured reflectance (:mod:`skinrender.datasets.skin_fit`);
    :func:`chart_skin_media`: a chart's skin patches' (both subsurface levels).
-   :func:`slab_layers`, :func:`slab_reflectance`: the flat slab as rendered
    (the dermis :data:`SLAB_DERMIS_MM` thick, air below) and its adding-doubling
    reflectance.
-   :func:`effective_layer`: one semi-infinite medium of the two layers'
    reflectance (what the face rendered before it had two layers; kept for
    the measurements of ``docs/subsurface.md``).
-   :func:`medium_dict`, :func:`integrator_dict`, :func:`truncation_bound`,
    :func:`mean_free_path`, :func:`subsurface_variant`: the Mitsuba pieces.

Choices, each measured (``docs/subsurface.md`` has the commands)
-----------------------------------------------------------------
-   The integrator: Mitsuba starts a ray leaving a surface ``(1 + max|p|) ·
    8.9e-5`` scene units off it (float32), and a ray leaving a medium
    interaction not off it at all, so with ``volpathmis`` a path entering the
    skin, or reflected inside it, skipped that much of it: a slab 100 mm from
    the origin rendered 6–16 % dark. ``skinvolpath`` samples every free flight
    from the true point (the offset origin serves only the intersection
    query) and so renders a slab alike at 0, 100 and 200 mm, and tilted.
-   Layers by depth: the epidermis is the skin within
    ``epidermis_mm`` of its surface along the normal where the path last
    touched it (locally flat layers), so the face has its two layers without
    an offset mesh.
-   No roulette by bounce: light in skin scatters hundreds of times with an
    albedo of ~0.999, and Mitsuba's roulette (at most 0.95 a bounce) left a
    slab 21 % dark at 64 spp; the walk's roulette plays on its weight only
    (:data:`~skinrender.rendering.skin_integrator.RR_WEIGHT`). A walk ends at
    :data:`DEPTH_MAX_SUBSURFACE` events, where what it carries is below
    :func:`truncation_bound`.
-   The variant: ``llvm_ad_spectral`` (``cuda_ad_spectral`` on a GPU): the
    integrator is Python traced into one kernel, which a scalar variant cannot
    run.
-   Lengths: the media's coefficients are per mm and scaled to the scene's
    unit (``scale``).

Units: coefficients mm⁻¹, thicknesses mm, wavelengths nm, reflectance fractions.

References
----------
-   :cite:`Prahl1995` : S. A. Prahl (1995). The adding-doubling method.
-   :cite:`Jakob2022` : W. Jakob et al. (2022). Mitsuba 3 renderer.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np

from ..errors import SkinrenderError
from ..hints import NDArrayFloat
from ..spectra import WavelengthGrid
from .renderer import mitsuba_spectrum
from .scene import reflectance_of, skin_parameters_of
from .variants import choose_variant

__all__ = ["SLAB_DERMIS_MM", "FIT_RMS_MAX", "FIT_STEP_NM", "DEPTH_MAX_SUBSURFACE", "TRUNCATION_MAX", "SkinMedia",
           "skin_media_of", "chart_skin_media", "slab_layers", "slab_reflectance", "effective_layer", "medium_dict",
           "integrator_dict", "truncation_bound", "check_truncation", "mean_free_path", "subsurface_variant"]

SLAB_DERMIS_MM = 5.0
"""Thickness of the rendered dermis, mm, standing for the model's semi-infinite one. Since the skin model absorbs
only ~0.1 cm⁻¹ in the red (water, packaged blood and a 0.073 cm⁻¹ background, ``docs/skin-model.md``), red light
diffuses centimetres: the 5 mm slab's adding-doubling reflectance is up to 2.1 % (relative, 400–700 nm, melanin
0.01–0.3, blood 0.003–0.0092; 1.5 % before the melanin power's calibration) below the semi-infinite model's,
0.13 % at 10 mm, 5e-6 at 20 mm. A chart's skin
patch is checked against its own slab's reflectance (:func:`slab_reflectance`), so the check stays exact; a
thicker slab renders slower (20 mm: ~2× the time of 5 mm for a light skin, measured once on a loaded machine)."""

FIT_RMS_MAX = 0.03
"""A measured reflectance rendered as skin media must fit the skin model to this RMS (fraction) or better
(:data:`~skinrender.datasets.skin_fit.SKIN_RMS_MAX`, the same number), with no more of its parameters on a bound
than :data:`~skinrender.datasets.skin_fit.SKIN_BOUNDS_MAX` allows, and with melanin and blood
(:func:`~skinrender.datasets.skin_fit.skin_verdict`); otherwise the spectrum is not skin as the model knows
it."""

FIT_STEP_NM = 3.0
"""A measured reflectance is fitted every this many nm of its grid within 400–700 nm (the NIST fits' spacing)."""

DEPTH_MAX_SUBSURFACE = 2**16
"""Events (scatterings and boundary contacts) a walk under the skin may have."""

TRUNCATION_MAX = 1e-6
"""Largest :func:`truncation_bound` a render accepts (a fraction of the light)."""

RR_DEPTH_AIR = 5
"""Bounces in air from which the integrator's Russian roulette plays on a path's weight (Mitsuba's default)."""


@dataclass(frozen=True, eq=False)
class SkinMedia:
    """
    The skin model's layers of a skin spec.

    Attributes
    ----------
    spec
        The skin spec.
    parameters
        The :class:`~skinrender.datasets.skin_model.SkinParameters` (given, or fitted).
    fit_rms
        ``None`` where the spec gave the parameters; else the fit's RMS reflectance error (fraction) over the
        fitted wavelengths.
    bounds_hit
        The fit's parameters at a bound (name → ``"low"``/``"high"``).
    layers
        The epidermis and the semi-infinite dermis (:class:`~skinrender.datasets.skin_model.SkinLayer`) on
        ``wavelengths`` (nm).
    """

    spec: str
    parameters: object
    fit_rms: float | None
    layers: tuple
    wavelengths: NDArrayFloat
    bounds_hit: dict = field(default_factory=dict)

    def as_dict(self) -> dict:
        """JSON values: ``spec``, ``source`` (``parameters`` or ``fit``), ``parameters``, ``fit_rms``, ``bounds_hit``."""
        p = self.parameters
        names = ("melanin", "blood", "oxygenation", "scattering", "scattering_power", "epidermis_mm", "n",
                 "background", "vessel_min_um", "vessel_max_um", "epidermis_scattering", "melanin_power")
        return {"spec": self.spec, "source": "parameters" if self.fit_rms is None else "fit",
                "parameters": {**{name: float(getattr(p, name)) for name in names}, "melanin_law": p.melanin_law},
                "fit_rms": self.fit_rms, "bounds_hit": dict(self.bounds_hit)}


def skin_media_of(spec: str, grid: WavelengthGrid, where: str = "skin") -> SkinMedia:
    """
    The skin model's layers of a skin spec on ``grid``.

    ``skin-model:NAME=VALUE,…`` gives the parameters. Any other reflectance spec (``skin:089 …``) is a
    measured spectrum: the model is fitted to it every :data:`FIT_STEP_NM` nm within 400–700 nm
    (:func:`~skinrender.datasets.skin_fit.fit_skin_spectrum`, ~1.3 s) and its layers are rendered; a spectrum
    the fit says is not skin (:func:`~skinrender.datasets.skin_fit.skin_verdict`: RMS above :data:`FIT_RMS_MAX`,
    most parameters on a bound, or no fit) is refused naming ``where`` and the reason. Cached per spec and grid,
    the fit per spec and measured values.

    Raises
    ------
    SkinrenderError
        A bad spec, or a spectrum the model does not fit.
    """
    return _skin_media(str(spec).strip(), grid, where)


def _role(where: str) -> str | None:
    """The role of a refusal about ``where``: a flag's argument (``--skin``: ``skin``); ``None`` for words (a
    patch's, or ``skin``, which may be a scene's own skin and not the user's flag)."""
    name = str(where).lstrip("-").replace("-", "_")
    return name if str(where).startswith("--") and name.isidentifier() else None


@lru_cache(maxsize=256)
def _skin_media(spec: str, grid: WavelengthGrid, where: str) -> SkinMedia:
    from ..datasets.skin_model import skin_layers

    lam = grid.wavelengths
    parameters = skin_parameters_of(spec, where)
    if parameters is not None:
        return SkinMedia(spec, parameters, None, skin_layers(lam, parameters), lam)
    measured = reflectance_of(spec, grid, where)
    inside = np.flatnonzero((lam >= 400.0) & (lam <= 700.0))
    chosen = inside[::max(1, int(round(FIT_STEP_NM / grid.step)))]
    accepts = ("subsurface renders the skin model's layers: give its parameters "
               "(skin-model:melanin=…,blood=…) or a measured skin reflectance the model fits")
    if chosen.size < 8:
        raise SkinrenderError(f"{where}: {spec!r}: the grid has {chosen.size} wavelengths inside 400–700 nm to fit "
                              f"the skin model on, fewer than 8; {accepts}", role=_role(where))
    fit = _fit(spec, np.asarray(lam[chosen], dtype=np.float64).tobytes(),
               np.asarray(measured[chosen], dtype=np.float64).tobytes())
    if fit.not_skin:
        raise SkinrenderError(f"{where}: {spec!r} is a measured reflectance and not skin as the skin model knows "
                              f"it: {fit.not_skin_reason}; {accepts}", role=_role(where))
    return SkinMedia(spec, fit.parameters, float(fit.rms), skin_layers(lam, fit.parameters), lam,
                     dict(fit.bounds_hit))


def chart_skin_media(chart, grid: WavelengthGrid, physics: str | None = None) -> tuple[tuple, tuple]:
    """
    Per patch of a chart (a :class:`~skinrender.rendering.scene.ChartScene`) its skin's :class:`SkinMedia`
    (:func:`skin_media_of`; ``None`` for a patch that is not skin) and where a refusal names it
    (``"SOURCE: patch 'NAME'"``): ``(media, wheres)``. A chart without a skin patch is refused (``physics``: the
    level's name for the refusal, where a caller has it; the request refuses such a chart first, naming its level).
    """
    if not any(p.skin for p in chart.patches):
        level = "a subsurface level" if physics is None else f"physics {physics!r}"
        raise SkinrenderError(f"{chart.source or chart.name}: {level} renders a chart's skin patches (skin = true) as "
                              "the skin model's layers, and this chart has none")
    wheres = tuple(f"{chart.source}: patch {patch.name!r}" if patch.skin else None for patch in chart.patches)
    return tuple(None if where is None else skin_media_of(patch.reflectance, grid, where)
                 for patch, where in zip(chart.patches, wheres)), wheres


@lru_cache(maxsize=256)
def _fit(spec: str, wavelengths: bytes, measured: bytes):
    """The skin model's fit to a measured spectrum (float64 bytes of its wavelengths in nm and reflectances), named
    ``spec``: cached on every input, so the same spectrum in another chart (another ``where``) is not fitted again."""
    from ..datasets.skin_fit import fit_skin_spectrum

    return fit_skin_spectrum(np.frombuffer(wavelengths), np.frombuffer(measured), name=spec)


def slab_layers(layers, dermis_mm: float = SLAB_DERMIS_MM) -> tuple:
    """The flat slab as rendered: the epidermis over a dermis ``dermis_mm`` thick, air below (SkinLayer s)."""
    epidermis, dermis = layers
    return epidermis, replace(dermis, thickness_mm=float(dermis_mm))


def slab_reflectance(layers, dermis_mm: float = SLAB_DERMIS_MM) -> NDArrayFloat:
    """
    Adding-doubling reflectance of the rendered slab (:func:`slab_layers`): total reflectance for collimated
    light at normal incidence, the surface's specular reflection included (Prahl's ``UR1``), on the layers'
    wavelengths, fractions.

    Examples
    --------
    >>> from skinrender.datasets.skin_model import SkinParameters, skin_layers, reflectance_of_layers
    >>> layers = skin_layers([450.0, 650.0], SkinParameters(melanin=0.1))
    >>> bool(abs(slab_reflectance(layers, 20.0) - reflectance_of_layers(layers)).max() < 1e-7)
    True
    >>> bool(1e-4 < abs(slab_reflectance(layers) - reflectance_of_layers(layers)).max() < 2e-3)  # 5 mm: the red
    True
    """
    from ..datasets.skin_model import reflectance_of_layers

    return reflectance_of_layers(slab_layers(layers, dermis_mm))


def effective_layer(layers, tolerance: float = 1e-7):
    """
    One semi-infinite medium whose adding-doubling reflectance (collimated normal incidence) equals the two
    layers': the dermis' scattering, ``g`` and ``n``, and per wavelength the absorption ``μa_eff`` (mm⁻¹) found
    by bisection in log μa until the reflectances agree within ``tolerance``. The face renders it; under diffuse
    light its reflectance differs from the two layers' (:func:`~skinrender.datasets.skin_model.reflectance_of_layers`
    with ``diffuse=True``; measured in ``docs/subsurface.md``).

    Examples
    --------
    >>> from skinrender.datasets.skin_model import SkinParameters, skin_layers, reflectance_of_layers
    >>> layers = skin_layers([450.0, 650.0], SkinParameters(melanin=0.1))
    >>> single = effective_layer(layers)
    >>> single.name, single.thickness_mm, bool(abs(reflectance_of_layers((single,)) - reflectance_of_layers(layers)).max() < 1e-6)
    ('effective', None, True)
    """
    from ..datasets.adding_doubling import Slab, stack_reflectance
    from ..datasets.skin_model import SkinLayer, reflectance_of_layers

    dermis = layers[-1]
    target = reflectance_of_layers(layers)
    low, high = np.full(target.shape, 1e-8), np.full(target.shape, 1e4)
    for _ in range(80):
        middle = np.sqrt(low * high)
        r = stack_reflectance([Slab(middle, dermis.mu_s_per_mm, dermis.g, None)], n=dermis.n)
        bright = r > target
        low, high = np.where(bright, middle, low), np.where(bright, high, middle)
        if np.all(np.abs(r - target) <= tolerance):
            break
    mu_a = np.sqrt(low * high)
    return SkinLayer("effective", None, mu_a, np.array(dermis.mu_s_per_mm), dermis.g, dermis.n)


def medium_dict(layer, grid: WavelengthGrid, mm_per_unit: float = 1.0) -> dict:
    """
    A Mitsuba ``homogeneous`` medium of a layer (``mu_a_per_mm``, ``mu_s_per_mm`` on ``grid``'s wavelengths):
    extinction ``μa + μs`` and albedo ``μs / (μa + μs)`` as ``irregular`` spectra, scaled to a scene whose unit is
    ``mm_per_unit`` mm, and a Henyey–Greenstein phase function of the layer's ``g``.
    """
    mu_a, mu_s = np.asarray(layer.mu_a_per_mm, dtype=np.float64), np.asarray(layer.mu_s_per_mm, dtype=np.float64)
    mu_t = mu_a + mu_s
    if not (np.all(np.isfinite(mu_t)) and np.all(mu_t > 0)):
        raise SkinrenderError(f"layer {layer.name}: extinction μa + μs must be finite and > 0 mm⁻¹")
    return {"type": "homogeneous", "sigma_t": mitsuba_spectrum(grid.wavelengths, mu_t),
            "albedo": mitsuba_spectrum(grid.wavelengths, mu_s / mu_t), "scale": float(mm_per_unit),
            "phase": {"type": "hg", "g": float(layer.g)}}


def integrator_dict(layers, grid: WavelengthGrid, mm_per_unit: float = 1.0, hide_emitters: bool = False,
                    boundary_alpha: float = 0.0) -> dict:
    """
    The Mitsuba integrator of skin (:mod:`~skinrender.rendering.skin_integrator`): the epidermis and the dermis
    of ``layers`` as media (:func:`medium_dict`), the epidermis' thickness in scene units (a scene unit is
    ``mm_per_unit`` mm), the boundary's index ``n``, walks of at most :data:`DEPTH_MAX_SUBSURFACE` events, its
    depths (the re-anchoring's and the point lights' connections') in scene units too;
    ``hide_emitters``: the emitters seen straight from the camera left out (the background black);
    ``boundary_alpha``: the GGX roughness of a rough skin boundary, whose lost light the integrator puts back
    (:mod:`~skinrender.rendering.rough_boundary`; 0: a smooth boundary).
    """
    from .skin_integrator import PLUGIN, REANCHOR_DEPTH_MM, THROUGH_DEPTH_MM

    epidermis, dermis = layers
    return {"type": PLUGIN, "epidermis": medium_dict(epidermis, grid, mm_per_unit),
            "dermis": medium_dict(dermis, grid, mm_per_unit),
            "epidermis_thickness": float(epidermis.thickness_mm) / float(mm_per_unit), "eta": float(dermis.n),
            "max_walk": DEPTH_MAX_SUBSURFACE, "rr_depth": RR_DEPTH_AIR, "hide_emitters": bool(hide_emitters),
            "reanchor_depth": REANCHOR_DEPTH_MM / float(mm_per_unit), "nee_depth": THROUGH_DEPTH_MM / float(mm_per_unit),
            "boundary_alpha": float(boundary_alpha)}


def mean_free_path(layers) -> float:
    """The shortest mean free path ``1 / (μa + μs)`` of ``layers`` over their wavelengths, mm.

    >>> from skinrender.datasets.skin_model import skin_layers
    >>> 0.01 < mean_free_path(skin_layers([450.0, 650.0])) < 0.05
    True
    """
    return float(min(1.0 / np.max(np.asarray(layer.mu_a_per_mm) + np.asarray(layer.mu_s_per_mm)) for layer in layers))


def truncation_bound(layers, depth: int = DEPTH_MAX_SUBSURFACE) -> float:
    """
    The largest fraction of the light a path cut at ``depth`` interactions can have carried: light scattered
    ``n`` times survives absorption with probability at most ``ω_max^n``, ``ω = μs / (μa + μs)`` the largest
    albedo of the layers over the wavelengths.

    >>> from skinrender.datasets.skin_model import skin_layers
    >>> truncation_bound(skin_layers([400.0, 700.0])) < 1e-19
    True
    """
    albedo = max(float(np.max(np.asarray(layer.mu_s_per_mm) / (np.asarray(layer.mu_a_per_mm)
                                                                  + np.asarray(layer.mu_s_per_mm))))
                 for layer in layers)
    return float(math.exp(depth * math.log(albedo))) if albedo > 0 else 0.0


def check_truncation(media: SkinMedia, where: str) -> float:
    """:func:`truncation_bound` of ``media``, refused above :data:`TRUNCATION_MAX` (scattering too strong for
    its absorption: paths longer than the depth cap would carry light)."""
    bound = truncation_bound(media.layers)
    if bound > TRUNCATION_MAX:
        raise SkinrenderError(f"{where}: {media.spec!r}: paths cut at {DEPTH_MAX_SUBSURFACE} interactions would "
                              f"lose up to {bound:.2g} of the light (more than {TRUNCATION_MAX:g}): its scattering "
                              "is too strong for its absorption to render", role=_role(where))
    return bound


def subsurface_variant(requested: str | None = None) -> str:
    """
    The Mitsuba variant for skin media: ``requested`` if given, else the fastest here
    (:func:`~skinrender.rendering.variants.choose_variant`); a JIT variant (``llvm_ad_spectral``,
    ``cuda_ad_spectral``), as the integrator is Python traced into one kernel.

    Raises
    ------
    SkinrenderError
        A scalar variant, requested or the only one here (``role`` ``variant``).
    """
    chosen = choose_variant(requested)
    if chosen.startswith("scalar"):
        why = "asked" if requested is not None else "the only variant that runs here"
        raise SkinrenderError(f"variant {chosen} ({why}): the subsurface-volume level renders in llvm_ad_spectral or "
                              "cuda_ad_spectral (its integrator is traced into one kernel; llvm needs libLLVM ≥ 16)",
                              role="variant")
    return chosen
