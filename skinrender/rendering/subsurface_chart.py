"""
Charts with subsurface scattering: the volumetric reference
===========================================================

A chart rendered at ``--physics subsurface-volume`` (named ``subsurface``
until issue 34, which gave that name to the fast transport of
:mod:`skinrender.rendering.slab_chart`): each skin patch (``skin =
true``) is the skin model's two layers (:func:`~skinrender.rendering.subsurface.skin_media_of`:
its ``skin-model:`` parameters, or the model fitted to its measured
reflectance) rendered as media under a smooth dielectric boundary, and
checked against the adding-doubling reflectance of the same slab; every other
patch (the white reference too) stays Lambertian.

-   :class:`SubsurfaceChart`, :func:`subsurface_chart`: a chart's patches as
    rendered, with the reflectance of each that Eq. 4 is checked with.
-   :class:`SubsurfaceChartRenderer`, :func:`subsurface_renderer`: the raw
    renders (:class:`~skinrender.rendering.renderer.RawRender`).
-   :func:`estimate_seconds`, :data:`SAMPLES_PER_S_SLAB`: the cost (the
    command line refuses beyond ``--max-minutes`` with it).

The geometry and the light, and why the check is exact
------------------------------------------------------
Each patch is rendered on its own: its slab (the epidermis over a dermis
:data:`~skinrender.rendering.subsurface.SLAB_DERMIS_MM` thick, a smooth
dielectric of the layers' ``n`` on top and below; the layers by depth below
the top, :mod:`~skinrender.rendering.skin_integrator`) is centred at the
scene's origin (scene unit 1 mm, the rectangles 2 m wide: a laterally infinite
slab), a black floor 1 mm under it, seen straight down by an orthographic
camera whose film is the patch's pixels over a footprint of
:data:`FOOTPRINT_MM`. The slab is uniform laterally, so any footprint sees the
same. ``translate_mm`` moves the whole scene (slab, floor, camera) away from
the origin: the integrator samples every free flight from the true point, so
the answer does not change (``docs/subsurface.md`` measures it at 0, 100 and
200 mm, and tilted 45°).

The light is a uniform sky of radiance ``L(λ)`` (a ``constant`` emitter), not
the chart renderer's directional light along the view axis. Looking down the
normal ``n`` at ``x``, a slab's radiance is, with ``S`` its BSSRDF (the
boundary's specular reflection included)::

    L_o = ∫_A ∫_2π S(x, n; x', ω) L cos θ dω dA'
        = L ∫_2π cos θ ∫_A S(x', ω; x, n) dA' dω          (reciprocity: both ends in air)
        = L ∫_2π cos θ ∫_A S(x, ω; x'', n) dA'' dω        (translation invariance)
        = L · R(n)

``R(n)`` the power leaving the slab, into every direction, of a collimated beam
of unit irradiance along the normal: adding-doubling's total reflectance for
collimated normal incidence (``UR1``,
:func:`~skinrender.rendering.subsurface.slab_reflectance`). The black floor
stops the sky reaching the slab from below; light leaving the dermis' bottom
is lost, as adding-doubling's air below a finite layer has it. A white
Lambertian patch under the same sky returns ``L``, so the balanced patch is
Eq. 4 of the reflectance ``R`` (:func:`~skinrender.rendering.validation.analytic_reference`
with the slab's ``R``). Under the directional light the pixel would be the
slab's reflectance into the view direction, which is not ``R`` (and a delta
light seen through a smooth dielectric renders black).

The sky's radiance is ``P(λ) / π`` (``P`` Planck's radiance, as the chart
renderer's light has irradiance ``P``), so a white reads the same in both.
Non-skin patches render with the ``direct`` integrator sampling the BSDF only
(a cosine-sampled Lambertian patch under a uniform sky: ``ρ L`` with no noise
but the wavelengths'); skin patches with
:func:`~skinrender.rendering.subsurface.integrator_dict`'s integrator. Each patch
has its own seed (from the render's seed and its index), so patches' noise is
independent; a patch's pixels are independent (box filter).

Units: radiance W·m⁻²·sr⁻¹·nm⁻¹ (times the sensitivity's unit after the
specfilm); lengths mm; temperatures K.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..errors import SkinrenderError
from ..hints import NDArrayFloat
from ..model.camera import Camera, camera
from ..spectra import GRID_DEFAULT, WavelengthGrid, planck
from .renderer import (SAMPLES_MAX, CameraKey, RawRender, emitter_peak, channels_separate, mitsuba_spectrum, channel_names,
                       emitter_grid)
from .scene import ChartScene, load_chart_scene
from .placement import check_float32_range, translation
from .settings import RenderSettings
from .skin_integrator import register
from .subsurface import (SLAB_DERMIS_MM, SkinMedia, chart_skin_media, check_truncation, integrator_dict,
                         mean_free_path, slab_reflectance, subsurface_variant)
from .variants import mitsuba

__all__ = ["FOOTPRINT_MM", "SLAB_HALF_WIDTH_MM", "SAMPLES_PER_S_SLAB", "SAMPLER_SUBSURFACE", "SECONDS_PER_FIT",
           "SubsurfaceChart", "subsurface_chart", "SubsurfaceChartRenderer", "subsurface_renderer",
           "estimate_seconds", "slab_document", "SlabOptions", "check_chart_range"]

FOOTPRINT_MM = 1.0
"""Width of the scene a patch's film sees, mm."""

SLAB_HALF_WIDTH_MM = 1000.0
"""Half the width of the slab's (and the floor's) rectangles, mm: laterally infinite for light in skin."""

SAMPLES_PER_S_SLAB = 10000.0
"""Samples (paths) per second of a skin slab on one core (``llvm_ad_spectral``), the estimates' rate: the 30 slabs of
``skin_patches`` at 32 spp, 1.4 × 10⁵ paths in 12 CPU seconds with every patch's own scene (``docs/subsurface.md``;
a light slab alone 2.4 × 10⁴ paths per CPU second, a dark one 6.6 × 10⁴)."""

SAMPLER_SUBSURFACE = "independent"
"""The sampler of a subsurface-volume chart unless one is named (``validate``, ``render``, ``detect``; Python: where no
settings are given): its pixels are independent samples by construction, so a patch's standard error from its
pixels' spread holds whatever the paths, and validate's difference test was calibrated with it (2 false alarms in
100 seeds at α 0.01, ``docs/subsurface.md``). Over 150 seeds of a slab (8 × 8 px, 16 spp, the skin fitted to Vrhel
095) the patch means' spread over their standard errors was 0.98, 1.02, 0.98 (R, G, B) with it and 0.96, 0.95, 0.94
with ``multijitter`` (``tools/measure_subsurface.py samplers``): both honest, within the ratio's ±6 % noise;
multijitter's means spread 13–15 % less for the same paths, its difference test not yet calibrated on slabs."""

SECONDS_PER_FIT = 1.3
"""Seconds to fit the skin model to one measured skin patch (one core, ~101 wavelengths), the estimates'."""


@dataclass(frozen=True, eq=False)
class SubsurfaceChart:
    """
    A chart's patches at ``subsurface-volume``: per patch its :class:`~skinrender.rendering.subsurface.SkinMedia`
    (``None``: Lambertian) and ``reflectances`` ``(patches, grid.size)``, the reflectance Eq. 4 is checked with:
    the slab's adding-doubling reflectance for a skin patch, the patch's own for the others.
    """

    scene: ChartScene
    grid: WavelengthGrid
    media: tuple
    reflectances: NDArrayFloat

    @property
    def slabs(self) -> list[int]:
        """Indices of the patches rendered as skin media."""
        return [i for i, m in enumerate(self.media) if m is not None]

    def rows(self) -> list[dict | None]:
        """Per patch the JSON of its skin model (``spec``, ``source``, ``parameters``, ``fit_rms``, …, and the
        slab's ``dermis_mm``), ``None`` for a Lambertian patch."""
        return [None if m is None else {**m.as_dict(), "dermis_mm": SLAB_DERMIS_MM} for m in self.media]


def subsurface_chart(scene, grid: WavelengthGrid = GRID_DEFAULT) -> SubsurfaceChart:
    """
    The chart's patches at ``subsurface-volume`` (:class:`SubsurfaceChart`): its skin patches' layers (fitting those
    given as measured reflectances, ~1.3 s each) and the reflectances Eq. 4 is checked with. Cached.

    Raises
    ------
    SkinrenderError
        A chart without a skin patch, or a skin patch the skin model does not fit (the patch named).
    """
    return _subsurface_chart(load_chart_scene(scene), grid)


@lru_cache(maxsize=8)
def _subsurface_chart(chart: ChartScene, grid: WavelengthGrid) -> SubsurfaceChart:
    media, wheres = chart_skin_media(chart, grid)
    reflectances = chart.reflectances(grid).copy()
    for index, item in enumerate(media):
        if item is not None:
            check_truncation(item, wheres[index])
            reflectances[index] = slab_reflectance(item.layers)
    reflectances.setflags(write=False)
    return SubsurfaceChart(chart, grid, media, reflectances)


@dataclass(frozen=True)
class SlabOptions:
    """
    The options of a chart's ``subsurface-volume`` level.

    Parameters
    ----------
    translate_mm
        ``(x, y, z)`` mm, or ``X,Y,Z`` text: every skin patch's scene (slab, floor, camera) moved that far from the
        origin (:func:`~skinrender.rendering.placement.translation`).

    Examples
    --------
    >>> SlabOptions("0,100,0").translate_mm
    (0.0, 100.0, 0.0)
    """

    translate_mm: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        object.__setattr__(self, "translate_mm", translation(self.translate_mm, "translate_mm"))


def check_chart_range(chart: SubsurfaceChart, translate_mm) -> None:
    """
    Refuse ``chart``'s patches moved by ``translate_mm`` (x, y, z mm) beyond float32's useful range for any of
    its skins (:func:`~skinrender.rendering.placement.check_float32_range`: the slab's top, where its walks start,
    and the camera 10 mm above it, against the skin's mean free path), naming the chart.
    """
    reach = max(abs(float(v)) for v in translate_mm) + 10.0 + FOOTPRINT_MM
    for media in chart.media:
        if media is not None:
            check_float32_range(chart.scene.source or chart.scene.name, reach, mean_free_path(media.layers),
                                f"the mean free path of its skin {media.spec!r}")


def estimate_seconds(scene: ChartScene, spp: int, fits: int = 0) -> float:
    """
    Seconds one subsurface render of ``scene`` should take on one core: its skin patches' paths at
    :data:`SAMPLES_PER_S_SLAB` and ``fits`` fits at :data:`SECONDS_PER_FIT` (the Lambertian patches are free).

    >>> round(estimate_seconds(load_chart_scene("skin_patches"), 16), 1)
    9.4
    """
    skins = sum(p.skin for p in scene.patches)
    return skins * scene.patch_px**2 * int(spp) / SAMPLES_PER_S_SLAB + fits * SECONDS_PER_FIT


def _film(cam: Camera, grid: WavelengthGrid, group: tuple[int, ...], size: int) -> dict:
    film = {"type": "specfilm", "width": size, "height": size, "component_format": "float32",
            "rfilter": {"type": "box"}}
    curves, names = cam.sensitivities(grid), channel_names(cam)
    for k in group:
        film[names[k]] = mitsuba_spectrum(grid.wavelengths, curves[k])
    return film


def slab_document(mi, media: SkinMedia | None, reflectance: NDArrayFloat, cam: Camera, grid: WavelengthGrid,
                  group: tuple[int, ...], size: int, spp: int, sampler: str, sky: NDArrayFloat,
                  to_world=None) -> dict:
    """
    The Mitsuba scene of one patch (module docstring): the slab of ``media`` under the sky (``media`` ``None``: a
    Lambertian rectangle of ``reflectance``), ``size`` × ``size`` pixels; ``sky`` the radiance on
    :func:`~skinrender.rendering.renderer.emitter_grid` (scaled as the caller chooses); ``to_world`` (a
    ``ScalarTransform4f``, mm) places the whole scene (``None``: at the origin).
    """
    t = mi.ScalarTransform4f
    place = t() if to_world is None else to_world
    wide = t().scale([SLAB_HALF_WIDTH_MM, SLAB_HALF_WIDTH_MM, 1.0])
    document = {
        "type": "scene",
        "sensor": {"type": "orthographic", "near_clip": 1e-3, "far_clip": 1e3,
                   "to_world": place @ t().look_at(origin=[0, 0, 10.0], target=[0, 0, 0], up=[0, 1, 0])
                   @ t().scale([FOOTPRINT_MM / 2, FOOTPRINT_MM / 2, 1]),
                   "sampler": {"type": sampler, "sample_count": int(spp), "seed": 0},
                   "film": _film(cam, grid, group, size)},
        "sky": {"type": "constant", "radiance": mitsuba_spectrum(emitter_grid(grid), sky)},
    }
    if media is None:
        document["integrator"] = {"type": "direct", "emitter_samples": 0, "bsdf_samples": 1}
        document["patch"] = {"type": "rectangle", "to_world": place @ wide,
                             "bsdf": {"type": "diffuse", "reflectance": mitsuba_spectrum(grid.wavelengths, reflectance)}}
        return document
    epidermis, dermis = media.layers
    boundary = {"type": "dielectric", "int_ior": float(dermis.n), "ext_ior": 1.0}
    depth = float(epidermis.thickness_mm) + SLAB_DERMIS_MM
    document.update({
        "integrator": integrator_dict(media.layers, grid),
        # the skin's surface: its interior medium marks it (the integrator takes the layers)
        "top": {"type": "rectangle", "to_world": place @ wide, "bsdf": boundary,
                "interior": integrator_dict(media.layers, grid)["epidermis"]},
        "bottom": {"type": "rectangle", "bsdf": boundary,
                   "to_world": place @ t().translate([0, 0, -depth]) @ t().rotate([1, 0, 0], 180) @ wide},
        "floor": {"type": "rectangle", "to_world": place @ t().translate([0, 0, -depth - 1.0]) @ wide,
                  "bsdf": {"type": "diffuse", "reflectance": {"type": "uniform", "value": 0.0}}},
    })
    return document


def _patch_seed(seed: int, index: int) -> int:
    """A 32-bit seed of its own for each patch, from the render's seed."""
    return int(np.random.SeedSequence([int(seed), int(index)]).generate_state(1)[0])


class SubsurfaceChartRenderer:
    """
    A chart at ``subsurface-volume`` through a camera (:class:`SubsurfaceChart`), rendered at any temperature.

    Each patch is its own Mitsuba scene (module docstring). ``settings``
    (:class:`~skinrender.rendering.settings.RenderSettings`) gives the spp, sampler, variant and channel passes
    (the defaults where ``None``, with :data:`SAMPLER_SUBSURFACE`); each render takes its own seed.
    ``raw(temperature, seed, skins=False)`` renders only the Lambertian patches (what a white balance reads; the
    skin patches stay 0): the calibration render. ``translate_mm`` moves every patch's scene that far from the
    origin (x, y, z, mm; refused where float32 cannot resolve the skin there:
    :func:`~skinrender.rendering.placement.check_float32_range`).
    """

    def __init__(self, scene, camera_, settings: RenderSettings | None = None, grid: WavelengthGrid = GRID_DEFAULT,
                 translate_mm=(0.0, 0.0, 0.0)):
        self.scene = load_chart_scene(scene)
        self.camera = camera(camera_)
        settings = RenderSettings(sampler=SAMPLER_SUBSURFACE) if settings is None else RenderSettings.of(settings)
        spp = settings.spp
        if spp * self.scene.patch_px**2 > SAMPLES_MAX:
            raise SkinrenderError(f"spp {spp} × {self.scene.patch_px**2} pixels is more than {SAMPLES_MAX:.3g} "
                                  "samples per pass", role="spp")
        self.translate_mm = translation(translate_mm, "translate_mm")
        self.chart = subsurface_chart(self.scene, grid)
        check_chart_range(self.chart, self.translate_mm)
        self.sampler, self.grid, self.requested_spp = settings.sampler, grid, spp
        self.variant = subsurface_variant(settings.variant)
        self.groups = [(0,), (1,), (2,)] if channels_separate(self.camera, grid, settings.channels) else [(0, 1, 2)]
        self.spp = spp

    def raw(self, temperature: float, seed: int = 0, skins: bool = True) -> RawRender:
        """Render at ``temperature`` (K) with ``seed`` (an integer in [0, 2³²)); ``skins``: the skin patches too."""
        if not (np.isfinite(temperature) and temperature > 0):
            raise SkinrenderError(f"temperature must be a finite number of kelvin > 0, got {temperature}")
        if not (isinstance(seed, (int, np.integer)) and 0 <= seed < 2**32):
            raise SkinrenderError(f"seed must be an integer in [0, 2^32) (Mitsuba's seeds are 32-bit), got {seed!r}",
                                  role="seed")
        mi = mitsuba(self.variant)
        register(mi)
        place = mi.ScalarTransform4f().translate(list(self.translate_mm))
        start = time.perf_counter()
        radiance = planck(emitter_grid(self.grid), temperature)
        peak = emitter_peak(radiance)
        chart, size = self.chart, self.scene.patch_px
        width, height = self.scene.size
        image = np.zeros((height, width, 3), dtype=np.float32)
        for index, media in enumerate(chart.media):
            if media is not None and not skins:
                continue
            x0, y0, x1, y1 = self.scene.patch_box(index)
            for group in self.groups:
                document = slab_document(mi, media, chart.reflectances[index], self.camera, self.grid, group, size,
                                         self.requested_spp, self.sampler, radiance / peak, place)
                loaded = mi.load_dict(document)
                self.spp = int(loaded.sensors()[0].sampler().sample_count())
                values = np.array(mi.render(loaded, seed=_patch_seed(seed, index)), dtype=np.float32)
                image[y0:y1, x0:x1, list(group)] = values.reshape(size, size, len(group))
        return RawRender(image, float(temperature), self.spp, int(seed), self.sampler, self.variant,
                         time.perf_counter() - start, len(self.groups), peak / np.pi)


@lru_cache(maxsize=4)
def _renderer(chart: ChartScene, key: CameraKey, settings: RenderSettings,
              translate_mm: tuple[float, float, float]) -> SubsurfaceChartRenderer:
    return SubsurfaceChartRenderer(chart, key.camera, settings, key.grid, translate_mm)


def subsurface_renderer(scene, camera_, settings: RenderSettings | None = None, grid: WavelengthGrid = GRID_DEFAULT,
                        translate_mm=(0.0, 0.0, 0.0), **options) -> SubsurfaceChartRenderer:
    """
    A :class:`SubsurfaceChartRenderer`, reused across calls with the same chart, camera curves, settings (but the
    seed), grid and ``translate_mm`` (a few kept); ``options``: the fields of ``settings``
    (:meth:`~skinrender.rendering.settings.RenderSettings.of`), the sampler :data:`SAMPLER_SUBSURFACE` unless
    ``settings`` or ``options`` name one.
    """
    chart, cam = load_chart_scene(scene), camera(camera_)
    if settings is None:
        options = {"sampler": SAMPLER_SUBSURFACE, **options}
    settings = RenderSettings.of(settings, **options).replace(seed=0)  # the seed is each render's
    return _renderer(chart, CameraKey.of(cam, grid), settings, translation(translate_mm, "translate_mm"))
