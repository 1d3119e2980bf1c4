"""
Figures
=======

Every figure skinrender draws, and the only module that imports matplotlib:
computation happens elsewhere and hands arrays here.

-   :func:`figure_pairs`: Figs. 3–5, a relative gamut per (prevailing,
    calibration) pair.
-   :func:`figure_gamuts`: Fig. 6, two Munsell gamuts in RGB.
-   :func:`figure_cases`: Fig. 7, one-calibration-case volumes and their ratio.
-   :func:`figure_render_curve`: render error against time (``bench render``).
-   :func:`figure_ptc`: a photon transfer curve (variance against mean, DN).
-   :func:`figure_locus`: a skin locus with its training chromaticities and the
    Planckian track.

Every function writes a PNG (Agg backend, no display needed) and returns its
path. Units are those of the data: volumes in output units³, chromaticities
unitless, times in s.

References
----------
-   [Martinkauppi2006]_ : Figs. 3–7 (docs/references.md).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..hints import NDArrayFloat

__all__ = ["figure_pairs", "figure_gamuts", "figure_cases", "figure_render_curve", "figure_locus", "figure_ptc"]

DPI = 110
"""Resolution of every figure, dots per inch."""


def _pyplot():
    """matplotlib's pyplot on the Agg backend (files only, no display)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(figure, path: str | Path) -> Path:
    path = Path(path)
    figure.tight_layout()
    figure.savefig(path, dpi=DPI)
    _pyplot().close(figure)
    return path


def figure_pairs(volumes: NDArrayFloat, temperatures: NDArrayFloat, title: str, path: str | Path) -> Path:
    """Figs. 3–5: ``volumes[p, q]`` (output units³) relative to each calibration's largest, one panel per calibration."""
    plt = _pyplot()
    relative = volumes / volumes.max(axis=0, keepdims=True)
    figure, axes = plt.subplots(2, 5, figsize=(13, 5.2), sharey=True)
    index = np.arange(1, temperatures.size + 1)
    for q, axis in enumerate(axes.ravel()):
        axis.plot(index, relative[:, q], "o-", ms=3)
        axis.plot(index[q], relative[q, q], "D", mfc="none", mec="k", ms=8, label="calibration")
        axis.set_title(f"calibration {temperatures[q]:g} K", fontsize=9)
        axis.set_xticks(index)
        axis.tick_params(labelsize=7)
    axes[1, 0].set_xlabel("prevailing illuminant (1–10)")
    axes[0, 0].set_ylabel("relative Munsell gamut")
    figure.suptitle(title)
    return _save(figure, path)


def figure_gamuts(panels: list[dict], title: str, path: str | Path) -> Path:
    """
    Fig. 6: RGB clouds with their hulls, one panel each.

    ``panels``: ``{"rgb": (N, 3) output units, "simplices": (F, 3) hull facet
    indices or None, "volume": output units³, "label": str}``.
    """
    plt = _pyplot()
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    figure = plt.figure(figsize=(5 * len(panels), 4.8))
    for i, panel in enumerate(panels):
        rgb = panel["rgb"]
        axis = figure.add_subplot(1, len(panels), i + 1, projection="3d")
        if panel["simplices"] is not None:
            axis.add_collection3d(Poly3DCollection(rgb[panel["simplices"]], alpha=0.25, facecolor="tab:blue",
                                                   edgecolor="k", linewidth=0.1))
        axis.scatter(*rgb.T, s=1, c=np.clip(rgb / 255, 0, 1))
        axis.set(xlabel="R", ylabel="G", zlabel="B", xlim=(0, 260), ylim=(0, 260), zlim=(0, 260))
        axis.set_title(f"{panel['label']}\nvolume {panel['volume']:.4g}", fontsize=9)
    figure.suptitle(title)
    return _save(figure, path)


def figure_cases(cases: dict, path: str | Path) -> Path:
    """Fig. 7: ``cases["skin"]``, ``["munsell"]`` (output units³) and ``["ratio"]`` per calibration."""
    plt = _pyplot()
    index = np.arange(1, cases["temperatures"].size + 1)
    figure, axes = plt.subplots(1, 3, figsize=(12, 3.6))
    for axis, key, label in zip(axes, ("skin", "munsell", "ratio"), ("skin gamut", "Munsell gamut", "skin / Munsell")):
        axis.plot(index, cases[key], "o-")
        axis.set(xlabel="calibration illuminant (1–10)", title=label, xticks=index)
    figure.suptitle("Fig. 7: one-calibration-case gamuts, white normalisation")
    return _save(figure, path)


def figure_render_curve(result: dict, path: str | Path) -> Path:
    """Error against time (log–log) of ``bench render``'s curve, one line per variant and sampler."""
    plt = _pyplot()
    figure, axis = plt.subplots(figsize=(6, 4.2))
    lines = sorted({(r["variant"], r["sampler"]) for r in result["curve"] if r["variant"] != "analytic"})
    for variant, sampler in lines:
        rows = [r for r in result["curve"] if (r["variant"], r["sampler"]) == (variant, sampler)]
        axis.loglog([r["seconds"] for r in rows], [r["rel_error"] for r in rows], "o-", label=f"{variant}, {sampler}")
        for r in rows:
            axis.annotate(str(r["spp"]), (r["seconds"], r["rel_error"]), fontsize=6)
    axis.set(xlabel="render time per Macbeth image (s)", ylabel="RMS relative error of patch means",
             title="Render error against time (labels: spp)")
    axis.legend(fontsize=7)
    return _save(figure, path)


def figure_locus(polygon: NDArrayFloat, area: float, boundary: str, training: NDArrayFloat, training_label: str,
                 track: NDArrayFloat, track_label: str, title: str, path: str | Path) -> Path:
    """A skin locus (closed ``polygon`` in NCC r, g), its training points ``(N, 2)`` and a Planckian ``track`` ``(M, 2)``."""
    plt = _pyplot()
    figure, axis = plt.subplots(figsize=(5.5, 5))
    axis.plot(*training.T, ".", ms=2, color="tab:orange", label=f"{training_label} ({len(training)} points)")
    closed = np.vstack([polygon, polygon[:1]])
    axis.plot(*closed.T, "-", color="tab:red", label=f"locus ({boundary}), area {area:.4f}")
    axis.plot(*track.T, "k--", label=track_label)
    axis.set(xlabel="NCC r", ylabel="NCC g", title=title)
    axis.legend(fontsize=7)
    return _save(figure, path)


def figure_ptc(result: dict, path: str | Path) -> Path:
    """Photon transfer (``skinrender ptc``): temporal variance, DN², against dark-subtracted mean, DN, per channel."""
    plt = _pyplot()
    figure, axis = plt.subplots(figsize=(6, 4.2))
    means = np.array([p["mean_dn"] for p in result["points"]])
    variances = np.array([p["variance_dn"] for p in result["points"]])
    for k, (name, colour) in enumerate(zip("RGB", ("tab:red", "tab:green", "tab:blue"))):
        axis.plot(means[:, k], variances[:, k], "o-", ms=3, color=colour,
                  label=f"{name}: K = {result['gain_dn_per_e'][k]:.4g} DN/e⁻")
    axis.set(xlabel="mean − dark, DN", ylabel="temporal variance, DN²",
             title=f"Photon transfer: {result['camera']} through {result['imager']}")
    axis.legend(fontsize=7)
    return _save(figure, path)
