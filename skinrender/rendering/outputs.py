"""
Saving and drawing renders
==========================

What a render's result (a chart's :class:`~skinrender.rendering.balance.Rendering`,
a face's :class:`~skinrender.rendering.face.render.FaceRendering`) does
beside its arrays: ``.save(exr, png=…, figure=…)`` and ``.figure(path)``.

Only the studies layer draws (matplotlib stays out of ``rendering``, an
import-linter contract): it registers a drawer per kind of result here
(:func:`register_figure`; :mod:`skinrender.studies.labelled` does when it is
imported), and a result's ``.figure()`` reaches it through :func:`draw_figure`,
which imports the module that registers them (:data:`FIGURE_MODULE`) the first
time a figure is asked for: ``rendering`` never imports ``studies`` by name,
and ``import skinrender`` imports neither.

-   :data:`FIGURE_DRAWERS`, :data:`FIGURE_MODULE`, :func:`register_figure`, :func:`drawer`,
    :func:`draw_figure`.
-   :func:`output_paths`: a save's paths, checked before anything is written.
-   :func:`save_result`: figure, EXR and PNG preview of a result.
-   :func:`write_chart_exr`: a chart render's float32 EXR.

Units: images in Eq. 4 output units (255 for white at p = c).
"""

from __future__ import annotations

from collections.abc import Callable
from os import PathLike
from pathlib import Path

from ..errors import SkinrenderError
from ..files import Output, write_outputs
from .exr import camera_attributes, write_exr, write_preview
from .renderer import channel_names

__all__ = ["FIGURE_DRAWERS", "FIGURE_MODULE", "register_figure", "drawer", "draw_figure", "output_paths", "save_result", "write_chart_exr"]

FIGURE_DRAWERS: dict[str, Callable] = {}
"""Kind of result (``chart``, ``face``) → ``drawer(result, path, **options) → Path``; filled by the studies
layer (:data:`FIGURE_MODULE`) when it is imported."""

FIGURE_MODULE = "skinrender.studies.labelled"
"""The module that registers the drawers (:func:`register_figure`), imported by :func:`drawer` on the first
figure asked for (as a plugin is found by its name: ``rendering`` does not import the studies layer)."""


def register_figure(kind: str, drawer: Callable) -> None:
    """Register the figure ``drawer(result, path, **options) → Path`` of results of ``kind``."""
    FIGURE_DRAWERS[kind] = drawer


def drawer(kind: str) -> Callable:
    """The drawer of ``kind`` results, :data:`FIGURE_MODULE` imported first where none is registered; a
    refusal saying who draws them where it registers none."""
    if kind not in FIGURE_DRAWERS:
        import importlib

        importlib.import_module(FIGURE_MODULE)  # registers its drawers on its first import
    if kind not in FIGURE_DRAWERS:
        raise SkinrenderError(f"no figure of a {kind} render is registered: they are drawn by "
                              f"{FIGURE_MODULE} (importing it registers them)")
    return FIGURE_DRAWERS[kind]


def draw_figure(kind: str, result, path: str | Path, **options) -> Path:
    """Draw ``result`` (a ``kind`` result) into a PNG at ``path`` with its registered drawer; the path."""
    draw = drawer(kind)
    return Path(draw(result, _file_path("figure", path, ".png"), **options))


def output_paths(exr: str | Path, png: bool | str | Path | None = True,
                 figure: str | Path | None = None) -> tuple[Path, Path | None, Path | None]:
    """
    The paths of a save, checked before anything is written: the EXR (``.exr``), the PNG preview
    (``True``: the EXR's path with ``.png``; a path; ``False``/``None``: none) and the figure (a ``.png``
    path or ``None``), none empty or a folder and no two the same; a one-line error naming the argument
    otherwise.

    >>> [str(p) for p in output_paths("out/face.exr", True, "out/figure.png")]
    ['out/face.exr', 'out/face.png', 'out/figure.png']
    """
    exr = _file_path("exr", exr, ".exr")
    png = None if png is None or png is False else exr.with_suffix(".png") if png is True else _file_path(
        "png", png, ".png", "True (beside the EXR), False or ")
    figure = None if figure is None else _file_path("figure", figure, ".png", "None or ")
    if figure is not None and png is not None and figure.resolve() == png.resolve():
        raise SkinrenderError(f"figure: {figure} is also the PNG preview; name another PNG")
    return exr, png, figure


def _file_path(name: str, value, suffix: str, others: str = "") -> Path:
    """``value`` as a ``suffix`` file path, else a one-line error naming the argument ``name`` (an empty path, a
    folder, another suffix, something that is not a path at all)."""
    if isinstance(value, bool) or not isinstance(value, (str, PathLike)):
        raise SkinrenderError(f"{name}: expected {others}a {suffix} file path, got {value!r}", role=name)
    text = str(Path(value)) if str(value).strip() else ""
    if not text or text == "." or "\0" in text:
        raise SkinrenderError(f"{name}: expected {others}a {suffix} file path, got {str(value)!r}", role=name)
    path = Path(value)
    if path.suffix.lower() != suffix or path.is_dir():
        raise SkinrenderError(f"{name}: {path} must be a {suffix} file path", role=name)
    return path


def save_result(result, kind: str, exr: str | Path, png: bool | str | Path | None, figure: str | Path | None,
                write: Callable) -> dict:
    """
    Save a render: the EXR (``write(stream)``), the PNG preview (tone-mapped from the output units) and the
    figure, all made first and written whole or none of them (:func:`skinrender.files.write_outputs`).
    ``{"exr": path, "png": path or None, "figure": path or None}``.
    """
    exr, png, figure = output_paths(exr, png, figure)
    draw = drawer(kind) if figure is not None else None  # its refusal, before anything is written
    outputs = [Output(exr, "exr", write)]
    if png is not None:
        outputs.append(Output(png, "png", lambda stream: write_preview(stream, result.image)))
    if figure is not None:
        outputs.append(Output(figure, "figure", lambda stream: draw(result, stream)))
    written = iter(write_outputs(*outputs))
    return {"exr": next(written), "png": next(written) if png is not None else None,
            "figure": next(written) if figure is not None else None}


def write_chart_exr(path, rendering, seed=None, grid=None):
    """
    A chart render's float32 EXR: its image in output units, channels named by the camera, and the render's
    settings as attributes (``seed``: as given to the render, default the prevailing render's), with the
    camera's curves' hash on ``grid`` (:func:`~skinrender.rendering.exr.camera_attributes`; default the
    default grid); ``path`` a file (written whole or not at all) or a binary stream.
    """
    raw = rendering.raw[0]
    return write_exr(path, rendering.image, channel_names(rendering.camera), {
        **camera_attributes(rendering.camera, grid), "prevailing_K": rendering.prevailing,
        "calibration_K": rendering.calibration,
        "spp": raw.spp, "seed": raw.seed if seed is None else seed, "variant": rendering.variant,
        "units": "Eq. 4 output units"})
