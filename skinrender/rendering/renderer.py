"""
Spectral rendering of chart scenes with Mitsuba 3
=================================================

A chart scene (:mod:`skinrender.rendering.scene`) under a Planck blackbody emitter, seen
through a camera's three sensor curves with Mitsuba's ``specfilm``, then white
balanced as Eq. 4 does.

-   :func:`scene_dict`: the Mitsuba scene of a chart, camera and temperature.
-   :func:`render_raw`: one render: per pixel and channel the specfilm value
    ``∫ L(λ) s_k(λ) dλ`` (L in W·m⁻²·sr⁻¹·nm⁻¹, λ in nm), float32.
-   :class:`ChartRenderer`, :func:`chart_renderer`: a chart and camera loaded
    once, rendered at any temperature.

The white balance of renders is :mod:`skinrender.rendering.balance`; EXR and
PNG files are :mod:`skinrender.rendering.exr`.

Modelling choices
-----------------
-   The emitter is ``directional`` along the view axis with a Planck
    irradiance (absolute Planck radiance values, W·m⁻²·sr⁻¹·nm⁻¹, used as the
    irradiance per unit solid angle); a patch returns ``ρ E / π``. By default
    Planck is tabulated in float64 every 0.1 nm over the grid and handed to
    Mitsuba as an ``irregular`` spectrum, so one compiled kernel serves every
    temperature (:class:`ChartRenderer`); ``emitter="blackbody"`` uses
    Mitsuba's plugin instead (agreeing to ~1e-6, measured, but recompiling for
    every temperature). Normalisations (Eqs.
    5–8) are scalars per illuminant and are applied after rendering, exactly
    as Eq. 10 applies them.
-   Sensor curves and reflectances are given to Mitsuba as ``irregular``
    spectra on the integration grid (zero outside it), so the renderer
    estimates the integral of the linearly interpolated spectra over the grid:
    the analytic reference for validation is Eq. 4 with ``quadrature =
    "trapezoid"`` on the same grid.
-   ``specfilm`` samples wavelengths from the sum of its channel curves: a
    narrow channel beside broad ones gets few samples. With ``channels =
    "auto"`` a camera whose channel areas differ by more than
    :data:`CHANNEL_AREA_RATIO_SEPARATE` (the impulse always) is rendered one
    channel per pass.
-   The impulse sensor (a unit-area delta on one grid sample) becomes, as a
    linearly interpolated curve, a triangle of unit area and base 2 Δλ: its
    bias against the exact sample is second order in Δλ and measured by the
    tests.
-   A ``box`` reconstruction filter keeps pixels independent, so a patch's
    standard error is its pixel standard deviation over √pixels.
"""

from __future__ import annotations

import functools
import time
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from ..errors import SkinrenderError
from ..hints import NDArrayFloat
from ..methods import method_of
from ..model.camera import Camera, camera
from ..spectra import GRID_DEFAULT, WavelengthGrid, planck
from .scene import ChartScene, load_chart_scene
from .settings import (CHANNEL_AREA_RATIO_SEPARATE, CHANNEL_GROUPINGS, FWHM_SEPARATE, QUALITY_PRESETS,  # noqa: F401
                       SAMPLERS, RenderSettings)
from .variants import choose_variant, mitsuba

__all__ = [
    "SAMPLERS",
    "CHANNEL_AREA_RATIO_SEPARATE",
    "CHANNEL_GROUPINGS",
    "SAMPLES_MAX",
    "FWHM_SEPARATE",
    "QUALITY_PRESETS",
    "EMITTERS",
    "Emission",
    "emitter_tabulated",
    "emitter_blackbody",
    "emission",
    "channel_names",
    "render_passes",
    "mitsuba_spectrum",
    "emitter_peak",
    "channels_separate",
    "scene_dict",
    "RawRender",
    "render_raw",
    "ChartRenderer",
    "chart_renderer",
    "CameraKey",
]

SAMPLES_MAX = 2**31 - 1
"""Most samples one render pass may take (pixels × spp): drjit sizes its wavefront with 32-bit integers."""



def channel_names(cam: Camera) -> tuple[str, str, str]:
    """EXR channel names: ``R``, ``G``, ``B`` with the peak for gbell/impulse cameras (``R_610nm``)."""
    if cam.peaks is None:
        return cam.channels
    return tuple(f"{c}_{p:g}nm" for c, p in zip(cam.channels, cam.peaks))


def mitsuba_spectrum(wavelengths: NDArrayFloat, values: NDArrayFloat) -> dict:
    """A Mitsuba spectrum: ``irregular`` on the wavelengths (nm), or ``uniform`` 0 for an all-zero one (a black
    patch), which Mitsuba refuses as an irregular spectrum ("no probability mass found")."""
    if not np.any(np.asarray(values) != 0):
        return {"type": "uniform", "value": 0.0}
    return {"type": "irregular", "wavelengths": _text(np.asarray(wavelengths, dtype=np.float64).tobytes()),
            "values": _text(np.asarray(values, dtype=np.float64).tobytes())}


@functools.lru_cache(maxsize=4096)
def _text(data: bytes) -> str:
    """Comma-separated ``%.10g`` text of float64 ``data``, as Mitsuba's ``irregular`` reads it (cached: every
    document of a chart spells its patches' spectra again)."""
    return ",".join(f"{v:.10g}" for v in np.frombuffer(data, dtype=np.float64))


def scene_dict(
    scene: ChartScene,
    cam: Camera,
    temperature: float,
    spp: int,
    seed: int,
    sampler: str,
    grid: WavelengthGrid,
    channels: tuple[int, ...] = (0, 1, 2),
    variant: str | None = None,
    emitter: str = "tabulated",
    film: dict | None = None,
) -> dict:
    """
    The Mitsuba scene dictionary: an orthographic camera over the chart, one
    directional Planck emitter at ``temperature`` (K), a ``specfilm`` with
    the camera's ``channels`` (indices into R, G, B), float32, box filter; ``film``: a spectral render's
    channels (name → Mitsuba spectrum, :func:`~skinrender.rendering.bands.film_channels`) in place of the
    camera's (``cam`` may then be ``None``).

    ``emitter``: ``tabulated`` (Planck radiance, W·m⁻²·sr⁻¹·nm⁻¹, computed in
    float64 on a grid :data:`EMITTER_REFINE` times finer than ``grid`` and
    stored as an ``irregular`` spectrum, whose values can be changed without
    recompiling) or ``blackbody`` (Mitsuba's plugin, whose temperature is
    compiled into the kernel: every new temperature costs a compilation).
    """

    mi = mitsuba(choose_variant(variant))  # remembered per process by choose_variant
    width, height = scene.size
    wavelengths = grid.wavelengths
    channels_given, film = film, {"type": "specfilm", "width": width, "height": height,
                                  "component_format": "float32", "rfilter": {"type": "box"}}
    if channels_given is not None:
        film.update(channels_given)
    else:
        curves, names = cam.sensitivities(grid), channel_names(cam)
        for k in channels:
            film[names[k]] = mitsuba_spectrum(wavelengths, curves[k])
    transform = mi.ScalarTransform4f
    document = {
        "type": "scene",
        "integrator": {"type": "direct", "emitter_samples": 1, "bsdf_samples": 0},
        "sensor": {
            "type": "orthographic",
            "to_world": transform().look_at(origin=[0, 0, 10], target=[0, 0, 0], up=[0, 1, 0])
            @ transform().scale([width / 2, width / 2, 1]),  # y extent = x extent / aspect
            "sampler": {"type": sampler, "sample_count": int(spp), "seed": int(seed)},
            "film": film,
        },
        "light": {"type": "directional", "direction": [0, 0, -1], "irradiance": emission(temperature, grid, emitter).document},
    }
    values = scene.reflectances(grid)
    for index, patch in enumerate(scene.patches):
        x0, y0, x1, y1 = scene.patch_box(index)
        centre = [(x0 + x1) / 2 - width / 2, height / 2 - (y0 + y1) / 2, 0.0]
        half = scene.patch_px / 2
        # The orthographic camera looks down -z with +y up: image rows grow downwards, world y upwards.
        document[f"patch_{index:03d}"] = {
            "type": "rectangle",
            "to_world": transform().translate(centre) @ transform().scale([half, half, 1]),
            "bsdf": {"type": "diffuse", "reflectance": mitsuba_spectrum(wavelengths, values[index])},
        }
    return document


EMITTER_REFINE = 10
"""The tabulated Planck emitter is sampled every ``grid.step / EMITTER_REFINE`` nm."""

def emitter_grid(grid: WavelengthGrid) -> NDArrayFloat:
    """Wavelengths (nm) of the tabulated Planck emitter."""
    return WavelengthGrid(grid.start, grid.end, grid.step / EMITTER_REFINE).wavelengths


class Emission(NamedTuple):
    """
    A Planck emitter at one temperature: its Mitsuba ``document`` (the directional light's irradiance), the
    ``scale`` its values were divided by (W·m⁻²·sr⁻¹·nm⁻¹; 1 where none) and the ``values`` a loaded scene takes
    through its parameters, without recompiling (``None``: the temperature is compiled in, the scene is loaded
    again).
    """

    document: dict
    scale: float
    values: NDArrayFloat | None


def emitter_tabulated(temperature: float, grid: WavelengthGrid) -> Emission:
    """Planck tabulated every grid.step / EMITTER_REFINE nm, one kernel for every temperature (default)

    Planck radiance in float64 on a grid :data:`EMITTER_REFINE` times finer than ``grid``, scaled to a peak of 1,
    an ``irregular`` spectrum whose values a new temperature replaces."""
    lam = emitter_grid(grid)
    radiance = planck(lam, temperature)
    scale = emitter_peak(radiance)
    return Emission(mitsuba_spectrum(lam, radiance / scale), scale, (radiance / scale).astype(np.float32))


def emitter_blackbody(temperature: float, grid: WavelengthGrid) -> Emission:
    """Mitsuba's blackbody plugin (recompiled for every temperature)"""
    return Emission({"type": "blackbody", "temperature": float(temperature)}, 1.0, None)


EMITTERS = {"tabulated": emitter_tabulated, "blackbody": emitter_blackbody}
"""Planck emitters, name → the function ``(temperature K, grid) → Emission``; :func:`emission` dispatches."""


def emission(temperature: float, grid: WavelengthGrid, emitter: str = "tabulated") -> Emission:
    """The :class:`Emission` of ``emitter`` (one of :data:`EMITTERS`) at ``temperature`` K on ``grid``."""
    return method_of(emitter, EMITTERS, "emitter")(temperature, grid)


def emitter_peak(values: NDArrayFloat) -> float:
    """The largest value of a Planck emitter's spectrum on the grid (W·m⁻²·sr⁻¹·nm⁻¹), which scales it; a
    refusal where it is zero or not finite."""
    peak = float(np.max(values))
    if not (np.isfinite(peak) and peak > 0):
        raise SkinrenderError("the Planck emitter is zero (or not finite) over the whole grid at this temperature")
    return peak


@dataclass(frozen=True)
class RawRender:
    """
    One render: ``image`` ``(height, width, 3)`` float32 such that
    ``image · emitter_scale`` is, per channel, the specfilm value ``∫ L s_k dλ``
    (W·m⁻²·sr⁻¹ times the sensitivity's unit).

    The tabulated emitter is handed to Mitsuba divided by its peak
    (``emitter_scale``, float64) so that float32 holds any temperature: at
    300 K absolute Planck radiance over 400–700 nm is ~1e-35 and its products
    would fall into float32's denormals.
    """

    image: NDArrayFloat
    temperature: float
    spp: int
    seed: int
    sampler: str
    variant: str
    seconds: float
    passes: int
    emitter_scale: float = 1.0

    @property
    def radiance(self) -> NDArrayFloat:
        """``∫ L s_k dλ`` per pixel and channel, float64, absolute units."""
        return self.image.astype(np.float64) * self.emitter_scale


def channels_separate(cam: Camera, grid: WavelengthGrid, channels: str) -> bool:
    """Whether ``cam``'s three channels are rendered in separate passes on ``grid`` (``channels``: one of
    :data:`CHANNEL_GROUPINGS`; ``auto``: the impulse, a narrow gbell or very unequal channel areas)."""
    return method_of(channels, CHANNEL_GROUPINGS, "channels")(cam, grid)


def render_passes(cam: Camera, grid: WavelengthGrid = GRID_DEFAULT, channels: str = "auto") -> int:
    """
    Passes a chart render of ``cam`` takes: 3 where its channels are rendered separately, else 1.

    >>> render_passes(camera("gbell:9@450,540,610")), render_passes(camera("impulse@450,550,650"))
    (1, 3)
    """
    return 3 if channels_separate(camera(cam), grid, channels) else 1


class ChartRenderer:
    """
    A chart and camera loaded into Mitsuba once, rendered at any temperature.

    With the ``tabulated`` emitter a new temperature only replaces the
    emitter's values (a kernel input), so the compiled kernels are reused:
    after the first render each takes about a third of its time, and about
    40 % of a render with Mitsuba's ``blackbody``, whose temperature is
    compiled in (docs/speed.md, "Rendering the charts"). ``settings`` (:class:`~skinrender.rendering.settings.RenderSettings`)
    gives the spp, sampler, variant and channel passes; each render takes its own seed.
    """

    def __init__(self, scene, camera_, settings: RenderSettings | None = None, grid: WavelengthGrid = GRID_DEFAULT,
                 emitter: str = "tabulated", bands: WavelengthGrid | None = None):
        self.scene = load_chart_scene(scene)
        self.bands = bands  # a spectral render's (camera_ None): one pass, a channel per band
        self.camera = None if bands is not None else camera(camera_)
        settings = RenderSettings.of(settings)
        spp = settings.spp
        width, height = self.scene.size
        if spp * width * height > SAMPLES_MAX:
            raise SkinrenderError(f"spp {spp} × {width * height} pixels = {spp * width * height:.3g} samples per pass, "
                                  f"more than {SAMPLES_MAX:.3g} (Mitsuba's 32-bit wavefront); at most "
                                  f"{SAMPLES_MAX // (width * height)} spp for this chart", role="spp")
        method_of(emitter, EMITTERS, "emitter")
        self.sampler, self.grid, self.emitter = settings.sampler, grid, emitter
        self.variant = choose_variant(settings.variant)
        self.groups = ([tuple(range(bands.size))] if bands is not None else
                       [(0,), (1,), (2,)] if channels_separate(self.camera, grid, settings.channels) else [(0, 1, 2)])
        self.requested_spp = spp
        self._loaded: list = []
        self.spp = spp

    EMITTER_PARAMETER = "light.irradiance.values"
    """The document's parameter holding the tabulated emitter's values (divided by their peak)."""
    EMITTER_DIVISOR = 1.0
    """The raw image times the emitter's peak over this is the specfilm value (1: a directional light's
    irradiance P gives a white ``P / π``, as Mitsuba renders it)."""

    def document(self, mi, temperature: float, group: tuple[int, ...], film: dict | None = None) -> dict:
        """The Mitsuba document of the channels ``group`` (:func:`scene_dict`; ``film``: a spectral render's
        channels)."""
        return scene_dict(self.scene, self.camera, temperature, self.requested_spp, 0, self.sampler, self.grid,
                          group, self.variant, self.emitter, film)

    def _load(self, temperature: float) -> None:
        mi = mitsuba(self.variant)
        self._loaded = []
        film = None
        if self.bands is not None:
            from .bands import film_channels

            film = film_channels(self.bands)
        for group in self.groups:
            loaded = mi.load_dict(self.document(mi, temperature, group, film))
            self._loaded.append((group, loaded, mi.traverse(loaded)))
        # multijitter rounds the count to a product of two integers
        self.spp = int(self._loaded[0][1].sensors()[0].sampler().sample_count())

    def raw(self, temperature: float, seed: int = 0) -> "RawRender":
        """Render at ``temperature`` (K) with ``seed`` (an integer in [0, 2³²)): the specfilm image, float32."""
        if not (np.isfinite(temperature) and temperature > 0):
            raise SkinrenderError(f"temperature must be a finite number of kelvin > 0, got {temperature}")
        if not (isinstance(seed, (int, np.integer)) and 0 <= seed < 2**32):
            raise SkinrenderError(f"seed must be an integer in [0, 2^32) (Mitsuba's seeds are 32-bit), got {seed!r}")
        mi = mitsuba(self.variant)
        start = time.perf_counter()
        light = emission(temperature, self.grid, self.emitter)
        scale = light.scale
        if not self._loaded or light.values is None:  # a temperature compiled in: loaded again
            self._load(temperature)
        if light.values is not None:
            # always set through the parameters (the scene file's text values round differently by an ulp)
            for _, _, params in self._loaded:
                kind = type(params[self.EMITTER_PARAMETER])  # mi.Float, or a dynamic array in scalar variants
                params[self.EMITTER_PARAMETER] = kind(light.values)
                params.update()
        width, height = self.scene.size
        image = np.zeros((height, width, 3 if self.bands is None else self.bands.size), dtype=np.float32)
        for group, loaded, _ in self._loaded:
            values = np.array(mi.render(loaded, seed=int(seed)), dtype=np.float32).reshape(height, width, len(group))
            image[:, :, list(group)] = values
        seconds = time.perf_counter() - start
        return RawRender(image, float(temperature), self.spp, int(seed), self.sampler, self.variant, seconds,
                         len(self.groups), scale / self.EMITTER_DIVISOR)


@dataclass(frozen=True)
class CameraKey:
    """
    A camera as a cache key: its name, kind and curves on ``grid`` (bytes), so that a CSV camera rewritten
    under the same path is another camera; ``camera`` rides along, outside the key.
    """

    name: str
    kind: str
    curves: bytes
    grid: WavelengthGrid
    camera: Camera = field(compare=False, hash=False, repr=False)

    @classmethod
    def of(cls, cam: Camera, grid: WavelengthGrid) -> CameraKey:
        """The key of ``cam`` with its curves on ``grid``."""
        return cls(cam.name, cam.kind, cam.sensitivities(grid).tobytes(), grid, cam)


RENDERERS_KEPT = 8
"""Chart renderers kept loaded (the least recently used goes first)."""


@functools.lru_cache(maxsize=RENDERERS_KEPT)
def _renderer(chart: ChartScene, key: CameraKey, settings: RenderSettings, emitter: str) -> ChartRenderer:
    return ChartRenderer(chart, key.camera, settings, key.grid, emitter)


def chart_renderer(scene, camera_, settings: RenderSettings | None = None, grid: WavelengthGrid = GRID_DEFAULT,
                   emitter: str = "tabulated", **options) -> ChartRenderer:
    """
    A :class:`ChartRenderer`, reused across calls with the same chart, camera curves, settings (but the seed),
    grid and emitter (:data:`RENDERERS_KEPT` kept); ``options``: the fields of ``settings``
    (:meth:`~skinrender.rendering.settings.RenderSettings.of`).
    """
    chart, cam = load_chart_scene(scene), camera(camera_)
    settings = RenderSettings.of(settings, **options).replace(seed=0)  # the seed is each render's
    return _renderer(chart, CameraKey.of(cam, grid), settings, emitter)


def render_raw(
    scene: ChartScene | str,
    camera_: Camera | str,
    temperature: float,
    settings: RenderSettings | None = None,
    grid: WavelengthGrid = GRID_DEFAULT,
    emitter: str = "tabulated",
    **options,
) -> RawRender:
    """
    Render a chart under a Planck emitter at ``temperature`` (K).

    Parameters
    ----------
    scene
        Scene name or :class:`ChartScene`.
    camera_
        Camera or spec.
    temperature
        Emitter temperature, K (any finite value > 0).
    settings
        :class:`~skinrender.rendering.settings.RenderSettings`: spp (multijitter rounds it to a product of two
        integers; the count used is reported), seed (the same seed gives the same image), sampler (one of
        :data:`SAMPLERS`), variant (``None``: the fastest that works) and channels (``auto``, ``together``: one
        pass, ``separate``: one pass per channel); the defaults where ``None``.
    grid
        Wavelength grid of the sensor curves and reflectances, nm.
    emitter
        ``tabulated`` (default) or ``blackbody``; see :func:`scene_dict`.
    **options
        ``spp``, ``seed``, ``sampler``, ``variant``, ``channels``: settings given one by one
        (:meth:`~skinrender.rendering.settings.RenderSettings.of`).
    """

    settings = RenderSettings.of(settings, **options)
    return chart_renderer(scene, camera_, settings, grid, emitter).raw(temperature, settings.seed)
