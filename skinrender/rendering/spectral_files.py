"""
Spectral images read back
=========================

:func:`read_spectral` (``sr.read_spectral``) reads an EXR written by
:meth:`~skinrender.rendering.spectral_image.SpectralImage.save` (or by
``skinrender render SCENE --spectral``): its bands, a face's label channel and
the header's settings, its scene loaded again so that ``.through(camera,
calibration=K)`` works as on the render.

Units: band values W·m⁻²·sr⁻¹ (after ``scale``); temperatures K; illuminance lx.
"""

from __future__ import annotations

import numpy as np

from ..errors import SkinrenderError
from ..spectra import WavelengthGrid
from .bands import band_names
from .spectral_image import FORMAT, SpectralImage

__all__ = ["read_spectral"]


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
        from .spectral_chart import chart_through

        return SpectralImage("chart", scene, bands, stack, float(header["scale"]), numbers["prevailing"],
                             values["physics"], numbers["spp"], numbers["spp_requested"], numbers["seed"],
                             values["sampler"], values["variant"], 0.0, grid, info={"emitter": header["emitter"]},
                             seen_through=chart_through)
    from dataclasses import replace

    from .face.render import plan_face
    from .face.spectral_face import face_through

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
                         header["skin"], info, plan, face_through)


def _exposure(text: str):
    return text if text == "auto" else float(text)
