"""
Charts rendered once for every camera
=====================================

A chart (:mod:`skinrender.rendering.scene`) rendered with the bands of
:mod:`skinrender.rendering.bands` as its film, under the directional Planck
emitter of :mod:`skinrender.rendering.renderer`, and then seen through any
camera as :func:`skinrender.rendering.balance.render` would render it.

-   :func:`render_chart_spectral`: the render (a :class:`~skinrender.rendering.spectral_image.SpectralImage`).
-   :func:`chart_through`: one camera's :class:`~skinrender.rendering.balance.Rendering` from it.
-   :func:`calibration_white`: the white reference under the calibration light, as the bands see a camera.

The white balance
-----------------
Eq. 4 divides by the white reference under the calibration light. A direct
render renders it (a second render at ``seed + 1`` where p ≠ c); a spectral
render takes no calibration, so where p ≠ c the white is computed as the
renderer integrates it (the white's reflectance and Planck tabulated every
``grid.step / 10`` nm, the camera as the bands see it: its curves at the
bands through the hats) and carries no noise; at p = c the white of the render
itself is used, as a direct render does. Eq. 4 cancels the white's scale.

Units: band values W·m⁻²·sr⁻¹; images in Eq. 4 output units; temperatures K.
"""

from __future__ import annotations

import functools
import time

import numpy as np

from ..errors import SkinrenderError
from ..hints import NDArrayFloat
from ..methods import validate_method
from ..model.camera import camera
from ..model.response import NORMALISATIONS
from ..spectra import GRID_DEFAULT, WavelengthGrid, planck
from .balance import Eq4Options, Rendering, patch_statistics
from .request import planckian
from .bands import BANDS_DEFAULT, band_integrals, bands_text, estimate, projection
from .renderer import RENDERERS_KEPT, ChartRenderer, RawRender, emitter_grid
from .scene import ChartScene
from .settings import CHANNELS_DEFAULT, RenderSettings

__all__ = ["render_chart_spectral", "render_chart_spectral_request", "chart_through", "calibration_white"]


@functools.lru_cache(maxsize=RENDERERS_KEPT)
def _renderer(chart: ChartScene, bands: WavelengthGrid, settings: RenderSettings, grid: WavelengthGrid,
              emitter: str) -> ChartRenderer:
    return ChartRenderer(chart, None, settings, grid, emitter, bands=bands)


def render_chart_spectral(scene, prevailing, bands: WavelengthGrid | str = BANDS_DEFAULT,
                          settings: RenderSettings | None = None, grid: WavelengthGrid = GRID_DEFAULT,
                          emitter: str = "tabulated", physics: str = "direct", **options):
    """
    Render a chart under ``prevailing`` (kelvin, ``A``, ``H``) once, its film the bands.

    Parameters
    ----------
    bands
        ``START:END:STEP`` nm or a grid, inside ``grid`` (default 400:700:5).
    settings, options
        :class:`~skinrender.rendering.settings.RenderSettings` or its fields (``spp``, ``seed``, ``sampler``,
        ``variant``; ``channels`` must be ``auto``: the bands are one pass).
    grid, emitter
        As :func:`~skinrender.rendering.renderer.render_raw`.
    physics
        ``direct`` (a chart's ``subsurface`` renders each patch as a slab through the camera: refused).

    Returns
    -------
    :class:`~skinrender.rendering.spectral_image.SpectralImage`
    """
    from .request import chart_request

    request = chart_request(scene, None, prevailing, None, settings=settings, grid=grid, emitter=emitter,
                            physics=physics, bands=bands, **options)
    return render_chart_spectral_request(request)


def render_chart_spectral_request(request):
    """
    The :class:`~skinrender.rendering.spectral_image.SpectralImage` of a spectral chart request (its ``bands``
    set): refused at another level than the base (``subsurface`` renders each patch as a slab through the
    camera), through an image sensor (it records a camera's channels) or with channel passes.
    """
    from .spectral_image import SpectralImage

    if not request.spectral:
        raise SkinrenderError("bands: this request renders a camera's channels; a spectral render needs bands",
                              role="bands")
    settings, chart, bands, grid = request.settings, request.scene, request.bands, request.grid
    if settings.channels != CHANNELS_DEFAULT:  # a grouping named: a spectral render has one pass of bands
        raise SkinrenderError(f"channels: a spectral render records its bands in one pass, got {settings.channels!r}",
                              role="channels")
    if request.level.names:
        raise SkinrenderError(f"physics: a chart's spectral render is at the direct level; {request.level.name!r} "
                              "renders each patch as its own slab through a camera (render it per camera)",
                              role="physics")
    if request.sensor is not None:
        raise SkinrenderError("imager: a chart's image sensor records one camera's channels: apply it to a render of "
                              "that camera", role="imager")
    chart.reflectances(grid)  # every patch's data cover the grid, before the render
    width, height = chart.size
    estimate(bands, width * height, 0.0)  # refused beyond the memory cap
    raw = _renderer(chart, bands, settings.replace(seed=0), grid, request.emitter).raw(request.prevailing,
                                                                                        settings.seed)
    return SpectralImage("chart", chart, bands, raw.image, raw.emitter_scale, request.prevailing, request.level.name,
                         raw.spp, settings.spp, settings.seed, raw.sampler, raw.variant, raw.seconds, grid,
                         info={"emitter": request.emitter}, request=request, seen_through=chart_through)


def calibration_white(chart: ChartScene, matrix: NDArrayFloat, bands: WavelengthGrid, grid: WavelengthGrid,
                      calibration: float) -> NDArrayFloat:
    """
    The chart's white reference under a Planckian at ``calibration`` (K) as the bands see the camera of
    ``matrix`` (:func:`~skinrender.rendering.bands.projection`), ``(3,)``, in arbitrary scale (Eq. 4 cancels it).
    """
    lam = emitter_grid(grid)
    white = np.interp(lam, grid.wavelengths, chart.reflectances(grid)[chart.white_index])
    spd = planck(lam, calibration)
    return band_integrals(lam, white * spd / np.max(spd), bands) @ matrix.T


def chart_through(spectral, camera_, calibration=None, normalization: str = "white", knee: bool = False) -> Rendering:
    """
    The :class:`~skinrender.rendering.balance.Rendering` a render of the chart through ``camera_`` gives, from a
    spectral render: its bands projected on the camera's curves, balanced to ``calibration`` (kelvin, ``A``,
    ``H``; ``None``: the prevailing light) by Eq. 4 with ``normalization`` and ``knee`` (module docstring: the
    calibration white). Its ``info`` adds ``white_calibration`` (``rendered`` or ``analytic``) and ``spectral``
    (the bands and the render's seconds; the result's ``seconds`` are the projection's own).
    """
    start = time.perf_counter()
    cam = camera(camera_)
    validate_method(normalization, NORMALISATIONS, "normalization")
    chart, bands, grid = spectral.scene, spectral.bands, spectral.grid
    matrix = projection(cam, bands, grid)
    p = spectral.prevailing
    c = p if calibration is None else planckian(calibration, "calibration")
    radiance = spectral.radiance @ matrix.T
    stats = patch_statistics(radiance, chart)
    white = chart.white_index
    white_p = stats.mean[white]
    rendered = c == p
    white_c = white_p if rendered else calibration_white(chart, matrix, bands, grid, c)
    if np.any(white_c <= 0) or np.any(white_p <= 0):
        raise SkinrenderError(f"camera {cam.name}: a channel sees no light from the white reference")
    image = Eq4Options(normalization, knee, grid).apply(radiance, white_p, white_c, p, c).astype(np.float32)
    relative_p = stats.standard_error[white] / white_p
    relative = np.array([relative_p, relative_p if rendered else np.zeros(3)])
    raw = RawRender((radiance / spectral.scale).astype(np.float32), p, spectral.spp, spectral.seed,
                    spectral.sampler, spectral.variant, time.perf_counter() - start, 1, spectral.scale)
    info = {"white_ratio": white_p / white_c, "white_calibration": "rendered" if rendered else "analytic",
            "spectral": {"bands_nm": bands_text(bands), "render_seconds": spectral.seconds}}
    return Rendering(chart, cam, p, c, normalization, knee, image, patch_statistics(image, chart), relative, (raw,),
                     info)
