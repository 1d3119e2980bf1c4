"""
A chart's effects of physics
============================

The chart's registry of effects (:class:`~skinrender.rendering.registry.Registry`,
the same classes as the face's): ``direct`` (the Lambertian patches under the
directional light, the analytic model's world), ``subsurface`` (the skin
patches as the skin model's layers under a sky, their flat slab's angular
reflectance as a BSDF: :mod:`~skinrender.rendering.slab_chart`),
``subsurface-volume`` (the same layers as media, path traced, the volumetric
reference: :mod:`~skinrender.rendering.subsurface_chart`) and the image sensor, ``noise``
(added by an ``imager``, not named in ``--physics``: a chart records through a
sensor with ``--imager``). ``subsurface-volume`` has options too
(:class:`~skinrender.rendering.subsurface_chart.SlabOptions`: ``translate_mm``,
the slabs moved away from the origin). ``direct`` and the two subsurface levels supply the ``chart``
part, the source of a level's raw renders (``source.raw(temperature, seed,
skins)``, ``source.info``) that :func:`~skinrender.rendering.balance.render_balanced`
balances; the sensor supplies its options, and a request that holds them is
recorded through it (:func:`~skinrender.rendering.imaging.render_imaged_request`).
Each says what does not go with it (``refuse`` before any work; ``refuses``:
the validation's options).

-   :data:`CHART_REGISTRY`, :data:`CHART_EFFECTS`: the registry and its table.
-   :data:`CHART_DIRECT`, :data:`CHART_SUBSURFACE`, :data:`CHART_SUBSURFACE_VOLUME`, :data:`CHART_NOISE`: the
    effects; :func:`prepare_slabs`: a subsurface chart's skin patches' layers before any render.

Units: temperatures K, illuminance lx, exposure s, times s.
"""

from __future__ import annotations

from ..errors import SkinrenderError
from .physics import SAMPLES_PER_S_DIRECT, Effect
from .registry import Registry
from .sensor import NoiseOptions
from .subsurface_chart import SAMPLER_SUBSURFACE, SAMPLES_PER_S_SLAB, SlabOptions

__all__ = ["CHART_DIRECT", "CHART_SUBSURFACE", "CHART_SUBSURFACE_VOLUME", "CHART_NOISE", "CHART_EFFECTS",
           "CHART_REGISTRY", "prepare_slabs"]


class _Lambertian:
    """The raw renders of the Lambertian chart (:class:`~skinrender.rendering.renderer.ChartRenderer`)."""

    def __init__(self, request):
        from .renderer import chart_renderer

        self.renderer = chart_renderer(request.scene, request.camera, request.settings, request.grid,
                                       request.emitter)
        self.info: dict = {}

    def raw(self, temperature: float, seed: int, skins: bool = True):
        return self.renderer.raw(temperature, seed)


class _Slabs:
    """The raw renders of a chart whose skin patches are slabs, by its level's slab renderer (a subclass's
    ``renderer_of``; ``slabs_as``: how it renders them, in words)."""

    slabs_as = ""

    def __init__(self, request):
        self.renderer = self.renderer_of(request)
        chart = self.renderer.chart
        self.info = {"physics": request.level.name, "reflectances": chart.reflectances, "skin_model": chart.rows(),
                     "slabs_as": self.slabs_as}

    @staticmethod
    def renderer_of(request):
        raise NotImplementedError

    def raw(self, temperature: float, seed: int, skins: bool = True):
        return self.renderer.raw(temperature, seed, skins)


class _SlabTables(_Slabs):
    """At ``subsurface``: the skin patches' tables as BSDFs (:func:`~skinrender.rendering.slab_chart.slab_renderer`)."""

    slabs_as = "their slab's angular reflectance (a BSDF)"

    @staticmethod
    def renderer_of(request):
        from .slab_chart import slab_renderer

        return slab_renderer(request.scene, request.camera, request.settings, request.grid)


class _SlabMedia(_Slabs):
    """At ``subsurface-volume``: the skin patches as media
    (:func:`~skinrender.rendering.subsurface_chart.subsurface_renderer`)."""

    slabs_as = "media, path traced"

    @staticmethod
    def renderer_of(request):
        from .subsurface_chart import subsurface_renderer

        return subsurface_renderer(request.scene, request.camera, request.settings, request.grid,
                                   request.options[CHART_SUBSURFACE_VOLUME.name].translate_mm)


def prepare_slabs(request) -> None:
    """
    Where the request's level renders a chart's skin patches as slabs, their layers now (measured reflectances
    fitted, the tables built at ``subsurface``; cached for the render): a patch that is not skin, or that the
    volumetric level's depth cap cannot render, refused naming it, before anything renders. Nothing at ``direct``.
    """
    request.level.prepare(request)  # each effect's (Effect.prepare): the slabs' at either subsurface level


def _skin_patches(request) -> None:
    """Refuse a chart without a skin patch at a subsurface level (nothing would be a slab), and a sensor on it."""
    scene, physics = request.scene, request.level.name
    if not any(patch.skin for patch in scene.patches):
        raise SkinrenderError(f"physics {physics} renders a chart's skin patches (skin = true) as the skin model's "
                              f"layers; {scene.name} has none", role="physics")
    if request.sensor is not None:
        raise SkinrenderError(f"imager: a chart at physics {physics} is rendered without an image sensor; drop it "
                              "(or use physics direct)", role="imager")
    slabs = request.options.get(CHART_SUBSURFACE_VOLUME.name)  # the volumetric level's options: translate_mm
    if slabs is not None and any(slabs.translate_mm):  # float32's range against its skins' mean free paths
        from .subsurface_chart import check_chart_range, subsurface_chart

        check_chart_range(subsurface_chart(scene, request.grid), slabs.translate_mm)


def _fits(scene) -> int:
    """The skin patches given as measured reflectances, which the skin model is fitted to."""
    from .scene import skin_parameters_of

    return sum(1 for p in scene.patches if p.skin and skin_parameters_of(p.reflectance, "SCENE") is None)


def _table_seconds(request, cores: int) -> tuple[float, str]:
    """A chart at ``subsurface`` on ``cores`` cores: its pixels, and its skin patches' tables and fits on one core
    (:func:`~skinrender.rendering.slab_chart.estimate_seconds`)."""
    from .slab_chart import SAMPLES_PER_S_TABLE, estimate_seconds

    scene, spp, fits = request.scene, request.settings.spp, _fits(request.scene)
    what = (f"{scene.name} at {spp} spp with {sum(p.skin for p in scene.patches)} skin patches' tables and {fits} "
            f"fits ({SAMPLES_PER_S_TABLE:g} samples/s per core, {cores} core{'s' * (cores > 1)})")
    return estimate_seconds(scene, spp, fits=fits, cores=cores), what


def _fit_skin_patches(request) -> None:
    """``subsurface-volume``'s prepare: the chart's skin patches as the skin model's layers, fitted now (cached for
    the render): a patch that is not skin, or that the depth cap cannot render, refused naming it."""
    from .subsurface_chart import subsurface_chart

    subsurface_chart(request.scene, request.grid)


def _prepare_tables(request) -> None:
    """``subsurface``'s prepare: the skin patches' layers fitted and their slabs' tables built now (cached for the
    render): a patch that is not skin refused naming it."""
    from .slab_chart import slab_chart

    slab_chart(request.scene, request.grid)


def _slab_seconds(request, cores: int) -> tuple[float, str]:
    """A subsurface-volume chart's render on ``cores`` cores: its skin patches' paths (the Lambertian ones are
    free), and its measured skins' fits on one core (they were left out: 1.2 s estimated, 39 s taken)."""
    from .subsurface_chart import SECONDS_PER_FIT, estimate_seconds

    scene, spp, fits = request.scene, request.settings.spp, _fits(request.scene)
    what = (f"the {sum(p.skin for p in scene.patches)} skin patches of {scene.name} as media at {spp} spp and "
            f"{fits} fits ({SAMPLES_PER_S_SLAB:g} samples/s per core, {cores} core{'s' * (cores > 1)})")
    return estimate_seconds(scene, spp) / cores + fits * SECONDS_PER_FIT, what


CHART_DIRECT = Effect(
    "direct",
    "Lambertian patches under the directional light along the view axis (the analytic model's world)",
    chart=_Lambertian, samples_per_s=SAMPLES_PER_S_DIRECT, order=0,
)
"""The base: the chart the analytic model describes."""

_REFUSES_SLABS = {"gamut": "the gamut volumes are compared on the Lambertian chart"}

CHART_SUBSURFACE = Effect(
    "subsurface",
    "the skin patches as the skin model's layers, a flat slab's angular reflectance from adding-doubling as a BSDF "
    "(fast; no lateral transport), lit by a uniform sky, against the slab's adding-doubling reflectance",
    chart=_SlabTables, refuse=_skin_patches, estimate=_table_seconds, prepare=_prepare_tables, order=30,
    refuses=_REFUSES_SLABS,
)
"""The skin patches as their slab's table (:mod:`~skinrender.rendering.slab_chart`); the chart's default sampler."""

CHART_SUBSURFACE_VOLUME = Effect(
    "subsurface-volume",
    "the skin patches as the skin model's two layers of participating media under a dielectric boundary, path "
    "traced (the volumetric reference; minutes), lit by a uniform sky, against their slab's adding-doubling "
    "reflectance",
    short="volumetric subsurface scattering", chart=_SlabMedia, sampler=SAMPLER_SUBSURFACE, refuse=_skin_patches,
    samples_per_s=SAMPLES_PER_S_SLAB, options=SlabOptions, estimate=_slab_seconds, prepare=_fit_skin_patches,
    order=35, refuses=_REFUSES_SLABS,
    excludes=("subsurface",), by_default=False,
)
"""The skin patches as slabs of media (:mod:`~skinrender.rendering.subsurface_chart`)."""

CHART_NOISE = Effect(
    "noise",
    "through an image sensor (skinrender.model.noise.simulate_dn): shot, dark, read and quantisation noise, full "
    "well and ADC clipping",
    short="sensor noise", options=NoiseOptions, added_by=("imager",), named=False, order=50,
    refuses={"gamut": "the gamut volumes are compared on the noise-free render"},
)
"""The chart recorded by an image sensor (:func:`~skinrender.rendering.imaging.render_imaged_request`: a request
whose options hold the sensor's, :attr:`~skinrender.rendering.request.Request.sensor`)."""

CHART_EFFECTS: dict[str, Effect] = {effect.name: effect for effect in (CHART_DIRECT, CHART_SUBSURFACE,
                                                                      CHART_SUBSURFACE_VOLUME, CHART_NOISE)}
"""A chart's effects, name → effect, in the order a level applies them, the base first."""

CHART_REGISTRY = Registry(CHART_EFFECTS, "physics (of a chart)")
"""A chart's registry of effects: its physics specs (``direct``, ``subsurface``, ``subsurface-volume``) and levels."""
