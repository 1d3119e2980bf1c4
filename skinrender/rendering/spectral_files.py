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
    A spectral EXR written by :meth:`~skinrender.rendering.spectral_image.SpectralImage.save`, read back: its
    bands, label channel and settings; its request built again from the header (a bundled scene by name, another
    from its file; a ``noise`` level's sensor by its preset's name) so that ``through`` works as on the render.

    Raises
    ------
    SkinrenderError
        Not a regular file, not an EXR, no spectral header, a band channel missing, or a scene or sensor that
        cannot be loaded again (named).
    """
    from ..files import EXR_BYTES_MAX, check_input
    from .exr import read_exr, read_exr_attributes

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
    stack = read_exr(path, band_names(bands) + (("label",) if face else ()))
    common = dict(physics=header["physics"], spp=int(header["spp_requested"]), seed=int(header["seed"]),
                  sampler=header["sampler"], grid=grid, bands=bands)
    if header.get("imager") is not None:  # the noise level's sensor
        common.update(imager=header["imager"] or None, exposure=_exposure(header["exposure"]),
                      illuminance=float(header["illuminance_lx"]) if header["illuminance_lx"] else None)
    prevailing = float(header["prevailing_K"])
    if not face:
        from .request import chart_request
        from .spectral_chart import chart_through

        request = chart_request(header["scene"], None, prevailing, None, emitter=header["emitter"], **common)
        return SpectralImage("chart", request.scene, bands, stack, float(header["scale"]), prevailing,
                             header["physics"], int(header["spp"]), request.settings.spp, request.settings.seed,
                             header["sampler"], header["variant"], 0.0, grid, info={"emitter": header["emitter"]},
                             request=request, seen_through=chart_through)
    from .face.request import face_request
    from .face.spectral_face import face_through

    width, height = (int(v) for v in header["size"].split("x"))
    request = face_request(header["scene"], None, prevailing, None, skin=header["skin"], size=(width, height),
                           **common)
    labels = stack[..., -1].astype(np.int32)
    label_names = {k.strip(): int(v) for k, v in (item.split("=") for item in header["labels"].split(","))}
    lights = {k: {"temperature_K": v.temperature, "illuminance_lx": v.illuminance}
              for k, v in request.level.lights(request.scene).items()}
    return SpectralImage("face", request.scene, bands, np.ascontiguousarray(stack[..., :-1]), float(header["scale"]),
                         prevailing, header["physics"], int(header["spp"]), request.settings.spp,
                         request.settings.seed, header["sampler"], header["variant"], 0.0, grid, labels, label_names,
                         header["skin"], {"lights": lights}, request, face_through)


def _exposure(text: str):
    return text if text == "auto" else float(text)
