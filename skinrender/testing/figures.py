"""
The difference figure of a failed render regression
===================================================

:func:`difference_figure`: the reference and the new render side by side (tone-mapped: output units / 255,
sRGB curve), and each patch or region filled with its largest ``|z|`` over its values, its name written on it,
those beyond the critical value outlined. The one module of :mod:`skinrender.testing` that imports
matplotlib (the import-linter contract "Only the figures module draws" lists the others).

Units: images in Eq. 4 output units (255 for white at p = c); z in combined standard errors.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..constants import CONSTANT_OUTPUT_SCALE
from ..files import write_output
from ..hints import NDArrayFloat

__all__ = ["region_z", "difference_figure"]


def region_z(items: tuple[str, ...], z: NDArrayFloat, critical: NDArrayFloat | None = None) -> tuple[dict, set]:
    """
    Each patch's or region's largest ``|z|`` over its values (``"<name> / <channel>"``; the skin NCC counts
    for ``skin``), and the names with a value beyond its ``critical`` value.

    >>> region_z(("a / R", "a / G", "skin / R", "skin NCC / r"), np.array([1.0, -3.0, 0.5, 2.0]), np.full(4, 2.5))
    ({'a': 3.0, 'skin': 2.0}, {'a'})
    """
    out: dict = {}
    beyond = set()
    critical = np.full(len(items), np.inf) if critical is None else np.asarray(critical, dtype=np.float64)
    for item, value, c in zip(items, np.abs(np.asarray(z, dtype=np.float64)), critical):
        name = item.rsplit(" / ", 1)[0]
        name = "skin" if name == "skin NCC" else name
        out[name] = max(out.get(name, 0.0), float(value))
        if value > c:
            beyond.add(name)
    return out, beyond


def _tone(image: NDArrayFloat) -> NDArrayFloat:
    linear = np.clip(np.asarray(image, dtype=np.float64) / CONSTANT_OUTPUT_SCALE, 0.0, 1.0)
    return np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * linear ** (1 / 2.4) - 0.055)


def _zones(shape, regions, scene, labels) -> list[tuple[str, NDArrayFloat]]:
    """``(name, mask)`` of every patch (chart ``scene``) or labelled region (face ``labels``)."""
    zones = []
    for index, name in enumerate(regions):
        mask = np.zeros(shape[:2], dtype=bool)
        if scene is not None:
            x0, y0, x1, y1 = scene.patch_box(index)
            mask[y0:y1, x0:x1] = True
        else:
            mask = labels == regions[name]
        zones.append((name, mask))
    return zones


def difference_figure(path: str | Path, reference: NDArrayFloat, new: NDArrayFloat, items: tuple[str, ...],
                      z: NDArrayFloat, critical: NDArrayFloat, regions, title: str, scene=None,
                      labels: NDArrayFloat | None = None) -> Path:
    """
    Write the PNG: reference, new render and the ``|z|`` map with names (module docstring).

    ``critical``: each value's critical value (those beyond it are outlined). ``regions``: the chart's patch
    names in order (with its ``scene`` for their boxes) or a face's ``{name: label}`` (with its ``labels``
    image).
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from scipy.ndimage import distance_transform_edt

    worst, beyond_names = region_z(items, z, critical)
    critical = float(np.min(critical))
    zones = _zones(new.shape, regions, scene, labels)
    zmap = np.zeros(new.shape[:2])
    for name, mask in zones:
        zmap[mask] = min(worst.get(name, 0.0), 1e6)
    height, width = new.shape[:2]
    scale = max(1.0, 360.0 / max(height, width))
    figure, axes = plt.subplots(1, 3, figsize=(3 * width * scale / 100 + 1.5, height * scale / 100 + 0.9),
                                dpi=100, constrained_layout=True)
    for axis, image, name in zip(axes, (reference, new), ("reference", "new render")):
        axis.imshow(_tone(image), interpolation="nearest")
        axis.set_title(name, fontsize=9)
    top = max(float(np.max(zmap)), 2.0 * critical)
    shown = axes[2].imshow(zmap, cmap="magma", vmin=0.0, vmax=top, interpolation="nearest")
    axes[2].set_title(f"largest |z| per {'patch' if scene is not None else 'region'} (critical ≥ {critical:.3g})",
                      fontsize=9)
    figure.colorbar(shown, ax=axes[2], shrink=0.8, label="|z|")
    for name, mask in zones:
        if not mask.any():
            continue
        row, column = np.unravel_index(int(np.argmax(distance_transform_edt(np.pad(mask, 1))[1:-1, 1:-1])),
                                       mask.shape)  # the pixel deepest inside: a label inside its region
        beyond = name in beyond_names
        if beyond:
            axes[2].contour(mask.astype(float), levels=[0.5], colors="cyan", linewidths=1.0)
        axes[2].text(float(column), float(row), f"{name}\n{worst.get(name, 0.0):.3g}",
                     ha="center", va="center", fontsize=5 if scene is not None else 6,
                     color="black" if worst.get(name, 0.0) > 0.6 * top else "white",
                     fontweight="bold" if beyond else "normal")
    for axis in axes:
        axis.set_xticks([])
        axis.set_yticks([])
    figure.suptitle(title, fontsize=9)
    try:
        return write_output(path, lambda stream: figure.savefig(stream, format="png"))  # whole or not at all
    finally:
        plt.close(figure)
