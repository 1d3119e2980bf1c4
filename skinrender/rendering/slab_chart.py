"""
Charts at the fast subsurface transport
=======================================

A chart rendered at ``--physics subsurface``: each skin patch (``skin =
true``) reflects as the skin model's layers do, a flat slab whose angular
reflectance adding-doubling tabulates
(:class:`~skinrender.rendering.slab_table.SlabTable`, rendered by the
:mod:`~skinrender.rendering.slab_bsdf` plugin); every other patch (the white
reference too) stays Lambertian. The volumetric reference of the same skins,
path traced through media, is ``--physics subsurface-volume``
(:mod:`skinrender.rendering.subsurface_chart`).

-   :class:`SlabChart`, :func:`slab_chart`: a chart's skin patches' tables,
    with the reflectance of each patch that Eq. 4 is checked with.
-   :class:`SlabChartRenderer`, :func:`slab_renderer`: the raw renders.
-   :func:`estimate_seconds`, :data:`SAMPLES_PER_S_TABLE`: the cost.

Why the check is exact
----------------------
The whole chart is one Mitsuba scene, as at ``direct``: each patch a
rectangle seen straight down by an orthographic camera, so every pixel looks
along the patch's normal. The light is a **uniform sky** of radiance
``L(λ) = P(λ) / π`` (P Planck's radiance, as the chart renderer's directional
light has irradiance P; a white Lambertian patch reads ``P / π`` under
either), hidden from the camera (the gaps stay black). A BSDF needs no
lateral extent, so a patch of the table reflects as the infinite slab: seen
along the normal under the sky its radiance is

    ``L_o = L (∫ f(λ, 1, μ_i) μ_i dω_i + F(1)) = L · A(1)``

the table's directional-hemispherical reflectance at normal incidence by
reciprocity (``f`` symmetric), which for the slab is its total reflectance for
collimated normal incidence, specular part included: adding-doubling's
``UR1`` (:attr:`~skinrender.rendering.slab_table.SlabTable.ur1`, the
reflectance Eq. 4 is checked with; the surface reflection here is smooth).
The table's grid is scaled so that it returns exactly that, as the BSDF
reads it (:mod:`~skinrender.rendering.slab_table`: to 3e-10), so what
separates the render from it is float32 and the render's noise. The integrator samples the
BSDF only (``direct``, no emitter samples): a Lambertian patch under the sky
then has no noise but the wavelengths', and a skin patch only the table's
variation with the angle of incidence.

Units: radiance W·m⁻²·sr⁻¹·nm⁻¹ (times the sensitivity's unit after the
specfilm); temperatures K.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..hints import NDArrayFloat
from ..model.camera import camera
from ..spectra import GRID_DEFAULT, WavelengthGrid
from .renderer import CameraKey, ChartRenderer, scene_dict
from .scene import ChartScene, load_chart_scene
from .settings import RenderSettings
from .slab_table import slab_table
from .subsurface import chart_skin_media

__all__ = ["SAMPLES_PER_S_TABLE", "SECONDS_PER_TABLE", "SlabChart", "slab_chart", "SlabChartRenderer",
           "slab_renderer", "estimate_seconds"]

SAMPLES_PER_S_TABLE = 4e5
"""Samples per second of a chart at ``subsurface`` on one core (llvm_ad_spectral), the estimates' rate: set below
what was measured (``skin_patches`` at 256 spp, its two renders' 4.9e6 samples in 2.4 s on the 2-core machine at a
load of ~16, ``docs/subsurface.md``): the renders are a small part of the estimate, its tables and fits the rest."""

SECONDS_PER_TABLE = 0.6
"""Seconds to build one skin patch's table on one core (adding-doubling at 32 points on 301 wavelengths: 0.4–0.7 s
measured at a load of ~3, 1.4 s at ~10), beside any fit of the model to a measured skin
(``subsurface_chart.SECONDS_PER_FIT``)."""


@dataclass(frozen=True, eq=False)
class SlabChart:
    """
    A chart's patches at ``subsurface``: per patch its :class:`~skinrender.rendering.subsurface.SkinMedia` and
    :class:`~skinrender.rendering.slab_table.SlabTable` (``None`` for a Lambertian patch) and ``reflectances``
    ``(patches, grid.size)``: the table's ``UR1`` for a skin patch, the patch's own for the others.
    """

    scene: ChartScene
    grid: WavelengthGrid
    media: tuple
    tables: tuple
    reflectances: NDArrayFloat

    def rows(self) -> list[dict | None]:
        """Per patch the JSON of its skin model (``spec``, ``source``, ``parameters``, ``fit_rms``, …;
        ``dermis_mm`` ``None``: the model's semi-infinite dermis), ``None`` for a Lambertian patch."""
        return [None if m is None else {**m.as_dict(), "dermis_mm": None} for m in self.media]


def slab_chart(scene, grid: WavelengthGrid = GRID_DEFAULT) -> SlabChart:
    """
    The chart's patches at ``subsurface`` (:class:`SlabChart`): each skin patch's layers (fitting those given as
    measured reflectances, ~1.3 s each) and their table (~0.6 s each). Cached. Refused as
    :func:`~skinrender.rendering.subsurface_chart.subsurface_chart` refuses (a :class:`SkinrenderError`).
    """
    return _slab_chart(load_chart_scene(scene), grid)


@lru_cache(maxsize=8)
def _slab_chart(chart: ChartScene, grid: WavelengthGrid) -> SlabChart:
    media, wheres = chart_skin_media(chart, grid)
    tables = tuple(None if item is None else slab_table(item.spec, grid, where) for item, where in zip(media, wheres))
    reflectances = chart.reflectances(grid).copy()
    for index, table in enumerate(tables):
        if table is not None:
            reflectances[index] = table.ur1
    reflectances.setflags(write=False)
    return SlabChart(chart, grid, media, tables, reflectances)


def estimate_seconds(scene: ChartScene, spp: int, fits: int = 0, cores: int = 1) -> float:
    """
    Seconds a render of ``scene`` at ``subsurface`` should take on ``cores`` cores: its pixels at
    :data:`SAMPLES_PER_S_TABLE` per core (the prevailing and the calibration render), and on one core a table per
    skin patch (:data:`SECONDS_PER_TABLE`) and ``fits`` fits of the skin model to measured skins
    (:data:`~skinrender.rendering.subsurface_chart.SECONDS_PER_FIT`).

    >>> round(estimate_seconds(load_chart_scene("skin_patches"), 64, fits=30))
    60
    """
    from .subsurface_chart import SECONDS_PER_FIT

    width, height = scene.size
    skins = sum(p.skin for p in scene.patches)
    render = 2 * width * height * int(spp) / SAMPLES_PER_S_TABLE / max(1, int(cores))
    return render + skins * SECONDS_PER_TABLE + fits * SECONDS_PER_FIT


class SlabChartRenderer(ChartRenderer):
    """
    A chart at ``subsurface`` through a camera (:class:`SlabChart`), rendered at any temperature: the chart
    renderer's scene (:func:`~skinrender.rendering.renderer.scene_dict`) under the sky, its skin patches' BSDFs
    the tables. ``raw(temperature, seed, skins=True)``: every patch is rendered either way (the skin patches
    cost no more than the others); ``skins`` is taken for the volumetric renderer's interface.
    """

    EMITTER_PARAMETER = "light.radiance.values"
    EMITTER_DIVISOR = float(np.pi)  # the sky's radiance is the normalised Planck: P / π once scaled

    def __init__(self, scene, camera_, settings: RenderSettings | None = None, grid: WavelengthGrid = GRID_DEFAULT):
        super().__init__(scene, camera_, settings, grid)
        self.chart = slab_chart(self.scene, grid)

    def document(self, mi, temperature: float, group: tuple[int, ...], film: dict | None = None) -> dict:
        """The chart's document (module docstring): the sky for the light, the skin patches' tables."""
        from .slab_bsdf import register, slab_bsdf_dict

        register(mi)
        document = scene_dict(self.scene, self.camera, temperature, self.requested_spp, 0, self.sampler, self.grid,
                              group, self.variant, self.emitter, film)
        sky = document.pop("light")["irradiance"]
        document["light"] = {"type": "constant", "radiance": sky}
        document["integrator"] = {"type": "direct", "emitter_samples": 0, "bsdf_samples": 1, "hide_emitters": True}
        for index, table in enumerate(self.chart.tables):
            if table is not None:
                document[f"patch_{index:03d}"]["bsdf"] = slab_bsdf_dict(table)
        return document

    def raw(self, temperature: float, seed: int = 0, skins: bool = True):
        """Render at ``temperature`` (K) with ``seed`` (an integer in [0, 2³²)); ``skins``: see the class."""
        return super().raw(temperature, seed)


@lru_cache(maxsize=4)
def _renderer(chart: ChartScene, key: CameraKey, settings: RenderSettings) -> SlabChartRenderer:
    return SlabChartRenderer(chart, key.camera, settings, key.grid)


def slab_renderer(scene, camera_, settings: RenderSettings | None = None, grid: WavelengthGrid = GRID_DEFAULT,
                  **options) -> SlabChartRenderer:
    """
    A :class:`SlabChartRenderer`, reused across calls with the same chart, camera curves, settings (but the seed)
    and grid (a few kept); ``options``: the fields of ``settings``
    (:meth:`~skinrender.rendering.settings.RenderSettings.of`).
    """
    chart, cam = load_chart_scene(scene), camera(camera_)
    settings = RenderSettings.of(settings, **options).replace(seed=0)  # the seed is each render's
    return _renderer(chart, CameraKey.of(cam, grid), settings)
