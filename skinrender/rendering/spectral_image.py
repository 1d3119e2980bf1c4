"""
Render once, see through every camera
=====================================

A multispectral render: the scene's radiance recorded in the bands of
:mod:`skinrender.rendering.bands` (hat functions on a band grid), with no
camera and no calibration; any camera's Eq. 4 image follows from it by a
projection, because Eq. 4 is linear in the camera's curves. A study over N
cameras then costs one render per scene, light and level instead of N, and
every camera's image comes from the same light paths (common random numbers:
the difference between two cameras is far less noisy than between two
independent renders).

-   :class:`SpectralImage`: the render; ``.through(camera, calibration=K)``
    returns the result a direct render of that camera returns (a chart's
    :class:`~skinrender.rendering.balance.Rendering`, a face's
    :class:`~skinrender.rendering.face.render.FaceRendering`: Eq. 4-balanced,
    with ``.save()`` and ``.figure()``); ``.save(exr)`` writes it.
-   :func:`~skinrender.rendering.dispatch.render_spectral`: a chart or a face
    rendered so (``sr.render(…, spectral=True)``);
    :func:`~skinrender.rendering.dispatch.render_cameras`: render once, return
    each camera's result (``sr.render_cameras``).
-   :func:`~skinrender.rendering.spectral_files.read_spectral`: an EXR written
    by ``.save`` read back (``sr.read_spectral``).

The EXR: float32, one channel per band named by its wavelength (``400nm``,
``405nm``, …; a face's ``label`` channel beside them), holding ``∫ L h_j dλ /
scale``; its header carries the basis (``hat``), the bands, the light (K), the
level, spp, seed, variant, the ``scale`` (W·m⁻²·sr⁻¹ per stored unit) and what
it takes to see it through a camera again (the scene, the skin, the size).

Units: band values W·m⁻²·sr⁻¹ (radiance integrated over a hat, nm);
temperatures K; illuminance lx.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import SkinrenderError
from ..hints import NDArrayFloat
from ..spectra import WavelengthGrid
from .bands import band_names, bands_text

__all__ = ["FORMAT", "SpectralImage", "spectral_attributes"]

FORMAT = "1"
"""The spectral EXR's format (header ``skinrender_spectral``)."""


@dataclass(frozen=True)
class SpectralImage:
    """
    A multispectral render of a chart or a face.

    Attributes
    ----------
    kind
        ``chart`` or ``face``.
    scene
        The :class:`~skinrender.rendering.scene.ChartScene` or the
        :class:`~skinrender.rendering.face.scene.FaceScene` as rendered (resized, its lights set).
    bands
        The band grid, nm.
    image
        ``(height, width, bands)`` float32: ``∫ L h_j dλ`` divided by ``scale``.
    scale
        W·m⁻²·sr⁻¹ per unit of ``image`` (the emitters are handed to Mitsuba divided by it).
    prevailing
        The light's temperature (a face: its key light's, or its environment's), K.
    physics
        The level rendered (``direct``, a face's effects joined by ``+``).
    spp, spp_requested, seed, sampler, variant, seconds
        As a render's (``spp``: the count the sampler used).
    grid
        The grid the scene's spectra are tabulated on, nm.
    labels, label_names, skin
        A face's label image ``(height, width)`` int32, ``{name: label}`` and skin spec; ``None`` for a chart.
    info
        A face's ``lights``; a chart's ``emitter``.
    request
        The spectral request rendered (:class:`~skinrender.rendering.request.ChartRequest` or
        :class:`~skinrender.rendering.face.request.FaceRequest` with ``bands``; its options, e.g. the ``noise``
        sensor applied per camera): what ``through`` needs.
    seen_through
        ``(image, camera, calibration, **options) → result``: the kind's projection
        (:func:`~skinrender.rendering.spectral_chart.chart_through`,
        :func:`~skinrender.rendering.face.spectral_face.face_through`), set by what made the image.
    """

    kind: str
    scene: object
    bands: WavelengthGrid
    image: NDArrayFloat
    scale: float
    prevailing: float
    physics: str
    spp: int
    spp_requested: int
    """The spp asked (``spp``: the count the sampler took)."""
    seed: int
    sampler: str
    variant: str
    seconds: float  # the render's, s
    grid: WavelengthGrid
    labels: NDArrayFloat | None = None
    label_names: dict = field(default_factory=dict)
    skin: str | None = None
    info: dict = field(default_factory=dict)
    request: object = field(default=None, repr=False, compare=False)
    seen_through: Callable | None = field(default=None, repr=False, compare=False)

    @property
    def radiance(self) -> NDArrayFloat:
        """``∫ L h_j dλ`` per pixel and band, float64, W·m⁻²·sr⁻¹."""
        return self.image.astype(np.float64) * self.scale

    @property
    def channels(self) -> tuple[str, ...]:
        """The bands' EXR channel names (``400nm``, …)."""
        return band_names(self.bands)

    def through(self, camera, calibration=None, **options):
        """
        The render ``camera`` would give, white balanced to ``calibration`` (kelvin, ``A``, ``H``; ``None``:
        the prevailing light): a chart's :class:`~skinrender.rendering.balance.Rendering` (``options``:
        ``normalization``, ``knee``), a face's :class:`~skinrender.rendering.face.render.FaceRendering`
        (the ``noise`` level's sensor applied to this camera's frame).

        Raises
        ------
        SkinrenderError
            A camera whose data do not cover the bands, or that is sensitive outside them on the render's
            grid (its range named); a bad light; an option of the other kind of scene.
        """
        if self.labels is not None and options:  # a face's (its label image): balanced with WP alone
            raise SkinrenderError(f"{', '.join(sorted(options))}: not an option of a face's through(); a face is "
                                  "balanced with WP (white) alone")
        if self.seen_through is None:
            raise SkinrenderError("this spectral image carries no way to see it through a camera (made without its "
                                  "scene's renderer: read it with read_spectral)")
        return self.seen_through(self, camera, calibration, **options)

    def save(self, exr) -> dict:
        """Write the float32 EXR (module docstring), whole or not at all; ``{"exr": path}``."""
        from ..files import write_output
        from .exr import write_exr

        path = Path(exr)
        if path.suffix.lower() != ".exr" or path.is_dir():
            raise SkinrenderError(f"exr: {path} must be a .exr file path")
        stack, names = self.image, self.channels
        if self.labels is not None:
            stack = np.concatenate([stack, self.labels[..., None].astype(np.float32)], axis=-1)
            names = (*names, "label")
        write_output(path, lambda stream: write_exr(stream, stack, names, spectral_attributes(self)))
        return {"exr": path}


def _scene_text(scene) -> str:
    """A scene as the header names it: a bundled scene by its name, another by its file."""
    from .scene import ROOT_SCENES

    source = Path(scene.source) if scene.source else None
    if source is not None and ROOT_SCENES in source.resolve().parents:
        return scene.name
    return str(source) if source is not None else scene.name


def spectral_attributes(image: SpectralImage) -> dict:
    """The EXR header of a spectral image (module docstring), every value text."""
    attributes = {"skinrender_spectral": FORMAT, "kind": image.kind, "basis": "hat",
                  "bands_nm": bands_text(image.bands), "grid_nm": bands_text(image.grid),
                  "scene": _scene_text(image.scene), "prevailing_K": repr(float(image.prevailing)),
                  "physics": image.physics, "spp": image.spp, "spp_requested": image.spp_requested,
                  "seed": image.seed, "sampler": image.sampler, "variant": image.variant,
                  "scale": repr(float(image.scale)),
                  "units": "per band: the integral of L(λ) h_j(λ) dλ over the band's hat, W m^-2 sr^-1, divided by "
                           "scale"}
    sensor = None if image.request is None else image.request.sensor
    if sensor is not None:  # the noise effect's options, applied per camera
        attributes.update({"imager": "" if sensor.imager is None else sensor.imager.name,
                           "exposure": str(sensor.exposure),
                           "illuminance_lx": "" if sensor.illuminance is None else repr(float(sensor.illuminance))})
    if image.labels is not None:  # a face's: its skin, size and labels
        scene = image.scene
        attributes.update({"skin": image.skin, "size": f"{scene.camera.width}x{scene.camera.height}",
                           "labels": ", ".join(f"{k}={v}" for k, v in image.label_names.items())})
    else:
        attributes["emitter"] = image.info.get("emitter", "tabulated")
    return attributes
