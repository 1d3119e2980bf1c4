"""
White balance of renders
========================

Eq. 4 applied to rendered images: the white reference rendered under the
calibration light gives the white balance, the two whites give WP (Eq. 8) or
the Eq. 10 factor, through the one gain of the analytic model
(:func:`skinrender.model.response.gain`).

-   :class:`PatchStatistics`, :func:`patch_statistics`: patch means and
    standard errors.
-   :class:`Eq4Options`: Eq. 4's options (normalisation, knee, grid, scale), taken whole.
-   :func:`balance`: Eq. 4 on a pair of raw renders.
-   :func:`render`, :class:`Rendering`: the Eq. 4 image of a (prevailing,
    calibration) pair; :func:`render_balanced`: the same of a
    :class:`~skinrender.rendering.request.ChartRequest`.

Units: raw renders in W·m⁻²·sr⁻¹ times the sensitivity's unit; balanced
images in output units (255 for white at p = c).

References
----------
-   :cite:`Martinkauppi2006` : Eqs. 4, 8, 10 (docs/references.md).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..constants import CONSTANT_OUTPUT_SCALE
from ..errors import SkinrenderError
from ..hints import NDArrayFloat
from ..model.camera import Camera
from ..model.response import gain, illuminant_factors, knee as apply_knee
from ..spectra import GRID_DEFAULT, WavelengthGrid
from .renderer import RawRender
from .scene import ChartScene
from .settings import RenderSettings, seed_at

__all__ = ["PatchStatistics", "patch_statistics", "Rendering", "Eq4Options", "pair_gain", "balance", "render",
           "render_balanced", "CHART_PHYSICS"]


def __getattr__(name: str):
    if name == "CHART_PHYSICS":  # read from the chart's registry of effects (a chart's levels, name → meaning)
        from .chart_effects import CHART_REGISTRY

        return {effect_name: effect.description for effect_name, effect in CHART_REGISTRY.named.items()}
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


@dataclass(frozen=True)
class PatchStatistics:
    """Per patch and channel: ``mean``, ``standard_error`` (std/√n) and pixel ``count``."""

    mean: NDArrayFloat
    standard_error: NDArrayFloat
    count: NDArrayFloat


def patch_statistics(image: NDArrayFloat, scene: ChartScene) -> PatchStatistics:
    """Means and standard errors of every patch's inner pixels, shape ``(patches, channels)``."""
    means, errors, counts = [], [], []
    for index in range(len(scene.patches)):
        rows, columns = scene.patch_pixels(index)
        pixels = np.asarray(image[rows, columns], dtype=np.float64).reshape(-1, image.shape[-1])
        means.append(pixels.mean(axis=0))
        errors.append(pixels.std(axis=0, ddof=1) / np.sqrt(len(pixels)))
        counts.append(len(pixels))
    return PatchStatistics(np.array(means), np.array(errors), np.array(counts))


@dataclass(frozen=True)
class Rendering:
    """
    The Eq. 4 image of a (prevailing, calibration) pair.

    Attributes
    ----------
    image
        ``(height, width, 3)`` float32, output units (white = 255 at p = c).
    patches
        Patch statistics of ``image``.
    white_relative_error
        Relative standard error of the white reference under the prevailing
        and the calibration illuminant, shape ``(2, 3)``.
    """

    scene: ChartScene
    camera: Camera
    prevailing: float
    calibration: float
    normalization: str
    knee: bool
    image: NDArrayFloat
    patches: PatchStatistics
    white_relative_error: NDArrayFloat
    raw: tuple[RawRender, ...]
    info: dict = field(default_factory=dict)

    @property
    def variant(self) -> str:
        """The Mitsuba variant used."""
        return self.raw[0].variant

    @property
    def seconds(self) -> float:
        """Rendering time, s."""
        return sum(r.seconds for r in self.raw)

    def save(self, exr, png=True, figure=None) -> dict:
        """
        Write the render: the float32 EXR (channels named by the camera, output units), a PNG preview (``True``:
        beside the EXR; a path; ``False``: none) and the labelled figure (a PNG path; ``None``: none). Returns
        ``{"exr": path, "png": path or None, "figure": path or None}``
        (:func:`skinrender.rendering.outputs.save_result`).
        """
        from .outputs import save_result, write_chart_exr

        return save_result(self, "chart", exr, png, figure, lambda path: write_chart_exr(path, self))

    def figure(self, path, **options):
        """
        Draw the render with each patch's name on it into a PNG at ``path`` and return it
        (:func:`skinrender.studies.labelled.chart_figure`; ``detection``, ``rates``: a detection's mask over it).
        """
        from .outputs import draw_figure

        return draw_figure("chart", self, path, **options)


def pair_gain(white_p: NDArrayFloat, white_c: NDArrayFloat, normalization: str, prevailing: float,
              calibration: float, grid: WavelengthGrid = GRID_DEFAULT,
              scale: float = CONSTANT_OUTPUT_SCALE) -> NDArrayFloat:
    """
    The Eq. 4 gain of one (prevailing, calibration) pair of Planckian lights
    (K) from the channel whites ``(3,)``: :func:`skinrender.model.response.gain`
    with WP for ``white``, else ``F_p / F_c`` (Eqs. 5–7) of the two Planck SPDs.
    """

    f = illuminant_factors([prevailing, calibration], normalization, grid)  # None: WP, from the whites
    return gain(white_p, white_c, normalization, *((None, None) if f is None else f), scale=scale)


@dataclass(frozen=True)
class Eq4Options:
    """
    Eq. 4's options, taken whole by what applies it: the normalisation (``white``: WP, Eq. 8; ``none``,
    ``560nm``, ``euclidean``: Eqs. 5–7), the knee (Eq. 10), the wavelength grid (nm) the Eqs. 5–7 factors are
    computed on, and the output scale ``v`` (output units: 255 for white at p = c).

    Examples
    --------
    >>> Eq4Options().apply(np.array([1.0, 2.0, 4.0]), np.full(3, 4.0), np.full(3, 4.0), 2856.0, 2856.0)
    array([ 63.75, 127.5 , 255.  ])
    """

    normalization: str = "white"
    knee: bool = False
    grid: WavelengthGrid = GRID_DEFAULT
    scale: float = CONSTANT_OUTPUT_SCALE

    def apply(self, signal: NDArrayFloat, white_p: NDArrayFloat, white_c: NDArrayFloat, prevailing: float,
              calibration: float) -> NDArrayFloat:
        """
        Eq. 4 of ``signal`` (shape ``(..., 3)``, the raw unit of the whites): the :func:`pair_gain` of the
        whites ``(3,)`` under the prevailing and calibration lights (K) times it, through the knee (Eq. 10)
        where asked; output units.
        """
        out = pair_gain(white_p, white_c, self.normalization, prevailing, calibration, self.grid, self.scale) * signal
        return apply_knee(out) if self.knee else out


def balance(raw_prevailing: RawRender, raw_calibration: RawRender, scene: ChartScene, cam: Camera,
            eq4: Eq4Options) -> tuple[NDArrayFloat, NDArrayFloat, NDArrayFloat]:
    """
    Eq. 4 (with Eq. 10, as ``eq4`` asks) applied to raw renders: ``v · F · raw_p / white_c``.

    ``white_c`` is the white reference's mean under the calibration render;
    ``F`` is WP (Eq. 8) from the two renders' whites for ``white``, or
    ``F_p / F_c`` (Eqs. 5–7) for the others. Returns the image, the
    whites' relative standard errors ``(2, 3)`` and the white ratios
    ``white_p / white_c`` ``(3,)``.
    """

    white = scene.white_index
    stats_p = patch_statistics(raw_prevailing.radiance, scene)
    stats_c = patch_statistics(raw_calibration.radiance, scene)
    white_p, white_c = stats_p.mean[white], stats_c.mean[white]
    if np.any(white_c <= 0):
        raise SkinrenderError(f"camera {cam.name}: a channel sees no light from the white reference at "
                              f"{raw_calibration.temperature:g} K")
    image = eq4.apply(raw_prevailing.radiance, white_p, white_c, raw_prevailing.temperature,
                      raw_calibration.temperature)
    relative = np.array([stats_p.standard_error[white] / white_p, stats_c.standard_error[white] / white_c])
    return image.astype(np.float32), relative, white_p / white_c


def render(
    scene: ChartScene | str,
    camera_: Camera | str,
    prevailing,
    calibration,
    normalization: str = "white",
    knee: bool = False,
    settings: RenderSettings | None = None,
    grid: WavelengthGrid = GRID_DEFAULT,
    cache: dict | None = None,
    emitter: str = "tabulated",
    physics: str = "direct",
    **options,
) -> Rendering:
    """
    Render a chart through a camera under ``prevailing`` light, white balanced
    to ``calibration`` (Eq. 4).

    Parameters
    ----------
    prevailing, calibration
        Planckian illuminants: kelvin, ``A`` (2856 K) or ``H`` (2300 K).
    normalization, knee
        As :func:`skinrender.response`.
    settings
        How it samples (:class:`~skinrender.rendering.settings.RenderSettings`: spp, seed, sampler, variant,
        channels; the defaults where ``None``). The calibration render uses ``seed + 1`` so that its noise is
        independent of the prevailing render's.
    grid, emitter
        As :func:`~skinrender.rendering.renderer.render_raw`.
    cache
        A dict to reuse raw renders across calls, keyed by temperature.
    physics
        ``direct`` (Lambertian patches under the directional light); ``subsurface``: the skin patches as the
        skin model's layers, the slab's angular reflectance as a BSDF, under a sky
        (:mod:`skinrender.rendering.slab_chart`); ``subsurface-volume``: the same layers as media, path traced
        (:mod:`skinrender.rendering.subsurface_chart`; the calibration render renders the Lambertian patches
        only, the white balance reading the white alone; the sampler
        :data:`~skinrender.rendering.subsurface_chart.SAMPLER_SUBSURFACE` unless ``settings`` or ``options``
        name one). At both ``info`` has ``physics``, ``reflectances`` (per patch, what Eq. 4 is checked with: the
        slab's adding-doubling reflectance for a skin patch) and ``skin_model`` (per patch its layers' source, or
        ``None``).
    **options
        ``spp``, ``seed``, ``sampler``, ``variant``, ``channels``: the settings one by one
        (:meth:`~skinrender.rendering.settings.RenderSettings.of`). (Through an image sensor: ``skinrender.render``
        with ``imager=``, or :func:`~skinrender.rendering.imaging.render_imaged`.)

    Returns
    -------
    :class:`Rendering`

    Raises
    ------
    SkinrenderError
        A bad argument, named, before any render (:func:`~skinrender.rendering.request.chart_request`).
    """

    from .request import chart_request

    request = chart_request(scene, camera_, prevailing, calibration, normalization=normalization, knee=knee,
                            settings=settings, grid=grid, emitter=emitter, physics=physics, **options)
    if request.sensor is not None:
        raise SkinrenderError("imager: this renders the radiance; through an image sensor: skinrender.render or "
                              "skinrender.rendering.imaging.render_imaged", role="imager")
    return render_balanced(request, request.level.chart(request), cache)


def render_balanced(request, source, cache: dict | None = None) -> Rendering:
    """
    The Eq. 4 image of a :class:`~skinrender.rendering.request.ChartRequest` from ``source``'s raw renders
    (``source.raw(temperature, seed, skins)``, ``source.info`` added to the rendering's): the prevailing render
    at the request's seed, the calibration's at :func:`~skinrender.rendering.settings.seed_at` ``(seed, 1)`` (its
    noise independent; ``skins=False``: a white balance reads the white alone), one render where the lights are
    equal. ``cache``: a dict to reuse raw renders across calls.
    """
    chart, cam, settings = request.scene, request.camera, request.settings
    p, c = request.prevailing, request.calibration
    cache = {} if cache is None else cache
    base = not request.level.names

    def raw(temperature: float, offset: int, skins: bool = True) -> RawRender:
        key = (temperature, offset) if base else (temperature, offset, request.level.name, skins)
        if key not in cache:
            cache[key] = source.raw(temperature, seed_at(settings.seed, offset), skins)
        return cache[key]

    raw_p = raw(p, 0)
    raw_c = raw_p if c == p else raw(c, 1, skins=False)
    eq4 = Eq4Options(request.normalization, request.knee, request.grid)
    image, white_error, white_ratio = balance(raw_p, raw_c, chart, cam, eq4)
    return Rendering(chart, cam, p, c, request.normalization, request.knee, image, patch_statistics(image, chart),
                     white_error, (raw_p,) if raw_c is raw_p else (raw_p, raw_c),
                     {"white_ratio": white_ratio, **source.info})
