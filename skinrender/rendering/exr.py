"""
Image files
===========

-   :func:`write_exr`, :func:`read_exr`: float32 OpenEXR with one named channel
    per last-axis slice (EXR files sort channels by name: they are looked up
    by name); :func:`read_exr_attributes`: the header's attributes.
-   :func:`camera_attributes`: the header attributes that trace a file back to
    its camera's curves (a SHA-256 of them on the grid).
-   :func:`write_preview`: a tone-mapped 8-bit PNG (sRGB transfer curve).

Units: whatever the image holds (output units for balanced renders).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..constants import CONSTANT_OUTPUT_SCALE
from ..errors import SkinrenderError
from ..extras import require
from ..files import write_output
from ..hints import NDArrayFloat

__all__ = ["write_exr", "read_exr", "read_exr_attributes", "camera_attributes", "write_preview", "write_png"]


def write_exr(path, image: NDArrayFloat, names: tuple[str, ...], attributes: dict | None = None):
    """
    Write a float32 EXR with one named channel per last-axis slice, whole or not at all
    (:func:`skinrender.files.write_output`); ``path`` may also be a binary stream (returned as it is).
    """
    require("render", "writing EXR files")
    import OpenEXR

    header = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}
    for key, value in (attributes or {}).items():
        header[key] = str(value)
    data = {name: np.ascontiguousarray(image[..., k], dtype=np.float32) for k, name in enumerate(names)}

    def write(stream) -> None:
        with OpenEXR.File(header, data) as handle:
            handle.write(stream)

    return _written(path, write)


def _written(path, write):
    """``write(stream)`` into ``path``: a binary stream as it is, a file whole or not at all; returns ``path``."""
    if hasattr(path, "write"):
        write(path)
        return path
    return write_output(path, write)


def read_exr(path: str | Path, names: tuple[str, ...]) -> NDArrayFloat:
    """Read the named channels of an EXR (EXR files sort channels by name: look them up by name); the file is first
    checked to be a regular file of at most :data:`~skinrender.files.EXR_BYTES_MAX` bytes."""
    require("render", "reading EXR files")
    import OpenEXR

    from ..files import EXR_BYTES_MAX, check_input

    check_input(path, EXR_BYTES_MAX, "an EXR image")
    # separate_channels: else OpenEXR merges channels named R, G, B (every CSV or bundled camera) into one "RGB"
    with OpenEXR.File(str(path), separate_channels=True) as handle:
        channels = handle.channels()
        missing = [n for n in names if n not in channels]
        if missing:
            raise SkinrenderError(f"{path}: no channel(s) {', '.join(missing)}; it has {', '.join(sorted(channels))}")
        return np.stack([np.asarray(channels[n].pixels, dtype=np.float32) for n in names], axis=-1)


def read_exr_attributes(path: str | Path) -> dict:
    """The header attributes of an EXR that are text (as :func:`write_exr` stores every given attribute)."""
    require("render", "reading EXR files")
    import OpenEXR

    with OpenEXR.File(str(path), header_only=True) as handle:
        return {k: v for k, v in handle.header().items() if isinstance(v, str)}


def camera_attributes(cam, grid=None) -> dict:
    """
    ``camera`` (its name), ``camera_sha256`` (SHA-256 of its sensitivities on ``grid`` as little-endian float64,
    rows R, G, B, after the grid's text) and ``camera_grid_nm``: enough to trace an image back to the curves
    that made it (the same curves from a CSV, a gbell spec or a bundled camera give the same hash).

    >>> from skinrender.model.camera import camera
    >>> a = camera_attributes(camera("gbell:9@450,540,610"))
    >>> a["camera_grid_nm"], len(a["camera_sha256"])
    ('400:700:1', 64)
    >>> a["camera_sha256"] == camera_attributes(camera("gbell:9@452,542,612"))["camera_sha256"]
    False
    """
    import hashlib

    from ..spectra import GRID_DEFAULT

    grid = GRID_DEFAULT if grid is None else grid
    text = f"{grid.start:g}:{grid.end:g}:{grid.step:g}"
    curves = np.ascontiguousarray(cam.sensitivities(grid), dtype="<f8")
    return {"camera": cam.name, "camera_sha256": hashlib.sha256(text.encode() + curves.tobytes()).hexdigest(),
            "camera_grid_nm": text}



def write_png(path, image: NDArrayFloat):
    """
    Write an 8-bit PNG of ``image`` in [0, 1] (grey ``(h, w)`` or colour ``(h, w, 3)``), rounded to 0–255,
    whole or not at all; ``path`` may also be a binary stream.
    """
    from PIL import Image

    values = np.clip(np.asarray(image, dtype=np.float64), 0.0, 1.0)
    picture = Image.fromarray(np.round(values * 255.0).astype(np.uint8))
    return _written(path, lambda stream: picture.save(stream, format="PNG"))


def write_preview(path, image: NDArrayFloat, scale: float = CONSTANT_OUTPUT_SCALE) -> Path:
    """A tone-mapped PNG preview: output units / ``scale``, clipped to [0, 1], sRGB transfer curve."""
    linear = np.clip(np.asarray(image, dtype=np.float64) / scale, 0.0, 1.0)
    encoded = np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * linear ** (1 / 2.4) - 0.055)
    return write_png(path, encoded)
