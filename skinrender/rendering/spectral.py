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
-   :func:`render_spectral`: a chart or a face rendered so (``sr.render(…,
    spectral=True)``).
-   :func:`render_cameras`: render once, return each camera's result.
-   :func:`read_spectral`: an EXR written by ``.save`` read back
    (``sr.read_spectral``).

The EXR: float32, one channel per band named by its wavelength (``400nm``,
``405nm``, …; a face's ``label`` channel beside them), holding ``∫ L h_j dλ /
scale``; its header carries the basis (``hat``), the bands, the light (K), the
level, spp, seed, variant, the ``scale`` (W·m⁻²·sr⁻¹ per stored unit) and what
it takes to see it through a camera again (the scene, the skin, the size).

Units: band values W·m⁻²·sr⁻¹ (radiance integrated over a hat, nm);
temperatures K; illuminance lx.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import SkinrenderError
from ..hints import NDArrayFloat
from ..spectra import WavelengthGrid
from .bands import BANDS_DEFAULT, band_names, bands_text

__all__ = ["SpectralImage", "render_spectral", "render_cameras", "read_spectral", "spectral_attributes"]

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
        A face's ``lights``, ``imager`` and ``exposure`` (the ``noise`` level's sensor, applied per camera);
        a chart's ``emitter``.
    plan
        A face's :class:`~skinrender.rendering.face.render.FacePlan` (what ``through`` needs).
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
    seed: int
    sampler: str
    variant: str
    seconds: float
    grid: WavelengthGrid
    labels: NDArrayFloat | None = None
    label_names: dict = field(default_factory=dict)
    skin: str | None = None
    info: dict = field(default_factory=dict)
    plan: object = field(default=None, repr=False, compare=False)

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
        if self.kind == "face":
            if options:
                raise SkinrenderError(f"{', '.join(sorted(options))}: not an option of a face's through(); "
                                      "a face is balanced with WP (white) alone")
            from .face.spectral import face_through

            return face_through(self, camera, calibration)
        from .spectral_chart import chart_through

        return chart_through(self, camera, calibration, **options)

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
                  "bands_nm": bands_text(image.bands),
                  "grid_nm": f"{image.grid.start:g}:{image.grid.end:g}:{image.grid.step:g}",
                  "scene": _scene_text(image.scene), "prevailing_K": repr(float(image.prevailing)),
                  "physics": image.physics, "spp": image.spp, "spp_requested": image.spp_requested,
                  "seed": image.seed, "sampler": image.sampler, "variant": image.variant,
                  "scale": repr(float(image.scale)),
                  "units": "per band: the integral of L(λ) h_j(λ) dλ over the band's hat, W m^-2 sr^-1, divided by "
                           "scale"}
    if image.kind == "face":
        key = image.plan.scene if image.plan is not None else image.scene
        from .face.scene import prevailing_name

        light = getattr(key, prevailing_name(key))
        attributes.update({"skin": image.skin, "size": f"{key.camera.width}x{key.camera.height}",
                           "illuminance_lx": repr(float(light.illuminance)),
                           "imager": "" if image.info.get("imager") is None else str(image.info["imager"]),
                           "exposure": str(image.info.get("exposure", "auto")),
                           "labels": ", ".join(f"{k}={v}" for k, v in image.label_names.items())})
    else:
        attributes["emitter"] = image.info.get("emitter", "tabulated")
    return attributes


def read_spectral(path) -> SpectralImage:
    """
    A spectral EXR written by :meth:`SpectralImage.save`, read back: its bands, label channel and settings;
    its scene loaded again from the header (a bundled scene by name, another from its file) so that
    ``through`` works as on the render.

    Raises
    ------
    SkinrenderError
        Not a regular file, not an EXR, no spectral header, a band channel missing, or a scene that cannot
        be loaded again (named).
    """
    from .exr import read_exr, read_exr_attributes

    from ..files import EXR_BYTES_MAX, check_input

    check_input(path, EXR_BYTES_MAX, "a spectral EXR")
    try:
        header = read_exr_attributes(path)
    except (OSError, RuntimeError, ValueError) as error:
        raise SkinrenderError(f"{path}: not a readable EXR ({error})") from None
    if header.get("skinrender_spectral") != FORMAT:
        raise SkinrenderError(f"{path}: not a skinrender spectral EXR (no skinrender_spectral = {FORMAT} in its "
                              "header; write one with SpectralImage.save or render --spectral)")
    bands, grid = WavelengthGrid.parse(header["bands_nm"]), WavelengthGrid.parse(header["grid_nm"])
    face = header["kind"] == "face"
    names = band_names(bands) + (("label",) if face else ())
    stack = read_exr(path, names)
    values = {key: header[key] for key in ("physics", "sampler", "variant")}
    numbers = dict(prevailing=float(header["prevailing_K"]), spp=int(header["spp"]),
                   spp_requested=int(header["spp_requested"]), seed=int(header["seed"]))
    if not face:
        from .scene import load_chart_scene

        scene = load_chart_scene(header["scene"])
        return SpectralImage("chart", scene, bands, stack, float(header["scale"]), numbers["prevailing"],
                             values["physics"], numbers["spp"], numbers["spp_requested"], numbers["seed"],
                             values["sampler"], values["variant"], 0.0, grid, info={"emitter": header["emitter"]})
    from dataclasses import replace

    from .face.render import plan_face

    width, height = (int(v) for v in header["size"].split("x"))
    plan = plan_face(header["scene"], numbers["prevailing"], header["skin"], values["physics"],
                     numbers["spp_requested"], numbers["seed"], (width, height), values["sampler"], None, grid,
                     float(header["illuminance_lx"]))
    plan = replace(plan, variant=values["variant"])
    labels = stack[..., -1].astype(np.int32)
    label_names = {k.strip(): int(v) for k, v in (item.split("=") for item in header["labels"].split(","))}
    info = {"imager": header["imager"] or None, "exposure": _exposure(header["exposure"]),
            "lights": {k: {"temperature_K": v.temperature, "illuminance_lx": v.illuminance}
                       for k, v in plan.lights.items()}}
    return SpectralImage("face", plan.scene, bands, np.ascontiguousarray(stack[..., :-1]), float(header["scale"]),
                         numbers["prevailing"], values["physics"], numbers["spp"], numbers["spp_requested"],
                         numbers["seed"], values["sampler"], values["variant"], 0.0, grid, labels, label_names,
                         header["skin"], info, plan)


def _exposure(text: str):
    return text if text == "auto" else float(text)


def render_spectral(scene, prevailing=None, bands=BANDS_DEFAULT, **options) -> SpectralImage:
    """
    Render a chart or a face once with the bands as its film (no camera, no calibration: both applied by
    :meth:`SpectralImage.through`).

    Parameters
    ----------
    scene
        A chart or a face: a bundled name, a TOML path or a parsed scene.
    prevailing
        The light: kelvin, ``A`` or ``H`` (a chart needs it; a face keeps its scene's key light where
        ``None``).
    bands
        ``START:END:STEP`` nm or a :class:`~skinrender.spectra.WavelengthGrid` (default 400:700:5).
    **options
        A chart's: ``spp``, ``seed``, ``sampler``, ``variant`` (or ``settings``), ``grid``, ``emitter``,
        ``physics`` (``direct``) (:func:`~skinrender.rendering.spectral_chart.render_chart_spectral`). A face's:
        ``skin``, ``physics``, ``spp``, ``seed``, ``size``, ``sampler``, ``variant``, ``grid``, ``imager``,
        ``exposure``, ``illuminance`` (:func:`~skinrender.rendering.face.spectral.render_face_spectral`).
    """
    from .dispatch import load_scene
    from .face.scene import FaceScene

    scene = load_scene(scene)
    if isinstance(scene, FaceScene):
        from .face.spectral import render_face_spectral

        return render_face_spectral(scene, prevailing, bands=bands, **options)
    from .spectral_chart import render_chart_spectral

    if prevailing is None:
        raise SkinrenderError("prevailing: a chart's spectral render needs its light (kelvin, A or H)")
    return render_chart_spectral(scene, prevailing, bands, **options)


def render_cameras(scene, cameras, prevailing=None, calibration=None, bands=BANDS_DEFAULT, **options) -> list:
    """
    Render ``scene`` once spectrally, then return each camera's result: what ``sr.render(scene, camera,
    prevailing, calibration, …)`` returns for every camera of ``cameras``, in their order, from one render
    (their images share its light paths).

    Parameters
    ----------
    scene, prevailing, bands, options
        As :func:`render_spectral`.
    cameras
        Cameras or specs (at least one).
    calibration
        The white balance's light (kelvin, ``A``, ``H``); ``None``: the prevailing light. The chart's
        ``normalization`` and ``knee`` go in ``options`` too.

    Examples
    --------
    >>> import skinrender as sr
    >>> faces = sr.render_cameras("face", ["gbell:9@450,540,610", "Nikon 5100 (NPL)"], 2856, 5900,
    ...                           spp=4, size=16)  # doctest: +SKIP
    >>> [face.camera.name for face in faces]  # doctest: +SKIP
    ['gbell:9@450,540,610', 'Nikon 5100 (NPL)']
    """
    from ..model.camera import camera
    from ..model.illuminant import illuminant
    from ..spectra import GRID_DEFAULT
    from .bands import parse_bands, projection

    cams = [camera(cam) for cam in cameras] if not isinstance(cameras, (str, bytes)) else [camera(cameras)]
    if not cams:
        raise SkinrenderError("cameras: name at least one camera")
    bands = parse_bands(bands)
    for cam in cams:  # every camera checked against the bands before the render
        projection(cam, bands, options.get("grid", GRID_DEFAULT))
    if calibration is not None and illuminant(calibration).temperature is None:
        raise SkinrenderError(f"calibration: a Planckian light (kelvin, A or H), got {calibration!r}")
    balance = {key: options.pop(key) for key in ("normalization", "knee") if key in options}
    spectral = render_spectral(scene, prevailing, bands, **options)
    return [spectral.through(cam, calibration, **balance) for cam in cams]
