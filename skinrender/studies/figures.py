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
-   :func:`figure_chart`: a chart render with its patch names (and the
    detection mask with each patch's detected fraction).
-   :func:`figure_face`: a face render with its labels outlined (and the
    detected skin over it).
-   :func:`figure_ladder`: the physics ladder, one row per level.
-   :func:`figure_skin_model`: the skin model's reflectance beside measured skin.
-   :func:`display_srgb`: how renders are shown (camera RGB as sRGB).

Every function writes a PNG (Agg backend, no display needed) and returns its
path. Units are those of the data: volumes in output units³, chromaticities
unitless, times in s.

References
----------
-   :cite:`Martinkauppi2006` : Figs. 3–7 (docs/references.md).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..files import write_output
from ..hints import NDArrayFloat

__all__ = ["figure_pairs", "figure_gamuts", "figure_cases", "figure_render_curve", "figure_locus", "figure_ptc",
           "figure_chart", "figure_face", "figure_ladder", "figure_calibration", "display_srgb", "figure_skin_model",
           "pyplot_agg", "save_figure", "LABEL_COLOURS"]

DPI = 110
"""Resolution of every figure, dots per inch."""


def pyplot_agg():
    """matplotlib's pyplot on the Agg backend (files only, no display)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(figure, path, legend: dict | None = None, layout: bool = True):
    """
    Lay out (``layout``: tight layout; ``False`` where the caller placed the
    panels), write and close a figure; ``legend``: a figure legend's
    keywords, put below the panels. ``path``: a PNG written whole or not at
    all (:func:`skinrender.files.write_output`), or a binary stream (PNG).
    """
    try:
        if layout:
            figure.tight_layout()
        if legend is not None:
            figure.legend(**{"loc": "upper center", "bbox_to_anchor": (0.5, 0.0), "fontsize": 8, "frameon": False,
                             **legend})
        options = {"dpi": DPI, **({} if legend is None else {"bbox_inches": "tight"})}
        if hasattr(path, "write"):
            figure.savefig(path, format="png", **options)
            return path
        form = Path(path).suffix.lstrip(".").lower() or "png"
        return write_output(path, lambda stream: figure.savefig(stream, format=form, **options))
    finally:
        pyplot_agg().close(figure)


def figure_pairs(volumes: NDArrayFloat, temperatures: NDArrayFloat, title: str, path: str | Path) -> Path:
    """Figs. 3–5: ``volumes[p, q]`` (output units³) relative to each calibration's largest, one panel per calibration
    (K), five to a row (the paper's ten: 2 × 5)."""
    plt = pyplot_agg()
    relative = volumes / volumes.max(axis=0, keepdims=True)
    count = temperatures.size
    columns = min(5, count)
    rows = -(-count // columns)  # the paper's ten: 2 × 5
    figure, axes = plt.subplots(rows, columns, figsize=(13 * max(columns, 3) / 5, 2.6 * rows), sharey=True,
                                squeeze=False)
    index = np.arange(1, count + 1)
    for q, axis in enumerate(axes.ravel()):
        if q >= count:
            axis.set_visible(False)
            continue
        axis.plot(index, relative[:, q], "o-", ms=3)
        axis.plot(index[q], relative[q, q], "D", mfc="none", mec="k", ms=8, label="calibration")
        axis.set_title(f"calibration {temperatures[q]:g} K", fontsize=9)
        axis.set_xticks(index)
        axis.tick_params(labelsize=7)
    axes[-1, 0].set_xlabel(f"prevailing illuminant (1–{count})")
    axes[0, 0].set_ylabel("relative Munsell gamut")
    figure.suptitle(title)
    # Fixed margins for this fixed grid: tight_layout took ~0.6 s per figure, a third of reproduce's Stage 2 thread.
    figure.subplots_adjust(left=0.055, right=0.99, bottom=0.1, top=0.87, wspace=0.08, hspace=0.33)
    return save_figure(figure, path, layout=False)


def figure_gamuts(panels: list[dict], title: str, path: str | Path) -> Path:
    """
    Fig. 6: RGB clouds with their hulls, one panel each.

    ``panels``: ``{"rgb": (N, 3) output units, "simplices": (F, 3) hull facet
    indices or None, "volume": output units³, "label": str}``.
    """
    plt = pyplot_agg()
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
    return save_figure(figure, path)


def figure_cases(cases: dict, path: str | Path) -> Path:
    """Fig. 7: ``cases["skin"]``, ``["munsell"]`` (output units³) and ``["ratio"]`` per calibration."""
    plt = pyplot_agg()
    index = np.arange(1, cases["temperatures"].size + 1)
    figure, axes = plt.subplots(1, 3, figsize=(12, 3.6))
    for axis, key, label in zip(axes, ("skin", "munsell", "ratio"), ("skin gamut", "Munsell gamut", "skin / Munsell")):
        axis.plot(index, cases[key], "o-")
        axis.set(xlabel=f"calibration illuminant (1–{index.size})", title=label, xticks=index)
    figure.suptitle("Fig. 7: one-calibration-case gamuts, white normalisation")
    return save_figure(figure, path)


def figure_render_curve(result: dict, path: str | Path) -> Path:
    """Error against time (log–log) of ``bench render``'s curve, one line per variant and sampler."""
    plt = pyplot_agg()
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
    return save_figure(figure, path)


def figure_calibration(result: dict, path: str | Path) -> Path:
    """``bench calibration``: per check the observed false-alarm rate with its 95 % interval, and the nominal α."""
    plt = pyplot_agg()
    checks = result["checks"]
    figure, axis = plt.subplots(figsize=(6.4, 1.9 + 0.45 * max(len(checks), 1)))
    for y, check in enumerate(checks):
        lo, hi = check["interval"]
        axis.plot([lo, hi], [y, y], "-", color="tab:blue", lw=2, label="observed, 95 % interval" if y == 0 else None)
        axis.plot(check["rate"], y, "o", color="tab:blue")
        marker = "|" if check["nominal"] == "equal to" else "<"
        if check["nominal_alpha"] is not None:  # None: no null (a face's eq4_shift where Eq. 4 does not hold)
            axis.plot(check["nominal_alpha"], y, marker, color="tab:red", ms=14 if marker == "|" else 8, mew=2,
                      label="nominal α (| equal to, < at most)" if y == 0 else None)
    axis.set_yticks(range(len(checks)), [f"{c['name']} ({c['failures']}/{c['seeds']})" for c in checks])
    axis.set_ylim(-0.6, len(checks) - 0.4)
    axis.set_xlim(0, max([0.1] + [c["interval"][1] * 1.05 for c in checks]))
    sensor = f", {result['imager']} at {result['illuminance_lux']:g} lx" if result.get("imager") else ""
    axis.set(xlabel="false-alarm rate", title=f"{result['scene']}, {result['spp']} spp, {result['seeds']} seeds{sensor}")
    axis.legend(fontsize=7, loc="lower right")
    return save_figure(figure, path)


def figure_locus(polygon: NDArrayFloat, area: float, boundary: str, training: NDArrayFloat, training_label: str,
                 track: NDArrayFloat, track_label: str, title: str, path: str | Path) -> Path:
    """A skin locus (closed ``polygon`` in NCC r, g), its training points ``(N, 2)`` and a Planckian ``track`` ``(M, 2)``."""
    plt = pyplot_agg()
    figure, axis = plt.subplots(figsize=(5.5, 5))
    axis.plot(*training.T, ".", ms=2, color="tab:orange", label=f"{training_label} ({len(training)} points)")
    closed = np.vstack([polygon, polygon[:1]])
    axis.plot(*closed.T, "-", color="tab:red", label=f"locus ({boundary}), area {area:.4f}")
    axis.plot(*track.T, "k--", label=track_label)
    axis.set(xlabel="NCC r", ylabel="NCC g", title=title)
    axis.legend(fontsize=7)
    return save_figure(figure, path)


def figure_ptc(result: dict, path: str | Path) -> Path:
    """Photon transfer (``skinrender ptc``): temporal variance, DN², against dark-subtracted mean, DN, per channel."""
    plt = pyplot_agg()
    figure, axis = plt.subplots(figsize=(6, 4.2))
    means = np.array([p["mean_dn"] for p in result["points"]])
    variances = np.array([p["variance_dn"] for p in result["points"]])
    for k, (name, colour) in enumerate(zip("RGB", ("tab:red", "tab:green", "tab:blue"))):
        axis.plot(means[:, k], variances[:, k], "o-", ms=3, color=colour,
                  label=f"{name}: K = {result['gain_dn_per_e'][k]:.4g} DN/e⁻")
    axis.set(xlabel="mean − dark, DN", ylabel="temporal variance, DN²",
             title=f"Photon transfer: {result['camera']} through {result['imager']}")
    axis.legend(fontsize=7)
    return save_figure(figure, path)


def display_srgb(image: NDArrayFloat, scale: float = 255.0) -> NDArrayFloat:
    """
    A display of white-balanced camera RGB: ``image / scale`` clipped to [0, 1], then the sRGB transfer curve.

    The camera's channels are shown as if they were sRGB's (no colour matrix): "sRGB-ish", for looking at, not
    for colour measurement. ``image`` in output units (Eq. 4, white = ``scale``), shape ``(..., 3)``.

    Examples
    --------
    >>> display_srgb(np.array([[0.0, 255.0, 1000.0]])).round(3).tolist()
    [[0.0, 1.0, 1.0]]
    """
    linear = np.clip(np.nan_to_num(np.asarray(image, dtype=np.float64) / scale), 0.0, 1.0)
    return np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * linear ** (1 / 2.4) - 0.055)


def _wrap(name: str, width: int = 13) -> str:
    """A patch name broken into lines of about ``width`` characters, at spaces."""
    import textwrap

    return "\n".join(textwrap.wrap(name.replace(" -- ", " – ").replace(" - ", " – "), width)) or name


TITLE_PT = 10
"""Font size of a chart figure's title, points."""

TITLE_LINE_IN = 1.25 * TITLE_PT / 72
"""Height of one title line, inches."""


def _wrap_to(text: str, inches: float, points: float) -> str:
    """
    ``text`` (its own lines kept) wrapped at spaces to lines that fit ``inches`` at ``points`` (a DejaVu Sans
    character about 0.6 em wide at most on average, a margin of 0.3 in kept).

    Examples
    --------
    >>> _wrap_to("one two three four", 1.0, 10).splitlines()
    ['one two', 'three', 'four']
    """
    import textwrap

    characters = max(8, int((inches - 0.3) * 72 / (0.6 * points)))
    return "\n".join(wrapped for line in text.split("\n")
                     for wrapped in (textwrap.wrap(line, characters, break_on_hyphens=False) or [""]))


def figure_chart(image: NDArrayFloat, boxes: list, names: list, skin: list, title: str, path: str | Path,
                 mask: NDArrayFloat | None = None, fractions: list | None = None) -> Path:
    """
    A chart render a person can read: each patch's name written on it (skin patches outlined), and with ``mask``
    a second panel of the detection mask (white: inside the skin locus) with each patch's detected fraction.

    ``image``: ``(h, w, 3)`` output units (shown by :func:`display_srgb`, upscaled nearest); ``boxes``: pixel
    ``(x0, y0, x1, y1)`` per patch (end exclusive); ``names``, ``skin`` (bools) and ``fractions`` (0–1 or
    None) per patch.
    """
    plt = pyplot_agg()
    from matplotlib.patches import Rectangle

    shown = display_srgb(image)
    height, width = shown.shape[:2]
    columns = len({box[0] for box in boxes})
    panels = [("render (camera RGB shown as sRGB" + ("; dashed orange: the skin patches)" if any(skin) else ")"),
               shown)]
    if mask is not None:
        panels.append(("detected: inside the skin locus (white)", np.repeat(np.asarray(mask, float)[..., None], 3, -1)))
    # inches per pixel: a patch column about 1.45 in wide (names at 8.5 pt fit), the figure at most 30 in a side
    inch = min(1.45 * columns / width, 30.0 / width, 30.0 / (len(panels) * height))
    # the title wrapped to the figure's width (a narrow chart clipped a long title at both edges)
    heading = _wrap_to(f"{title}\n{panels[0][0]}", inch * width + 0.4, TITLE_PT)
    figure, axes = plt.subplots(len(panels), 1, figsize=(inch * width + 0.4, len(panels) * inch * height + 0.9
                                                         + TITLE_LINE_IN * (heading.count("\n") - 1)),
                                squeeze=False)
    for k, (axis, (label, picture)) in enumerate(zip(axes[:, 0], panels)):
        axis.imshow(picture, interpolation="nearest", extent=(0, width, height, 0))
        axis.set_title(heading if k == 0 else label, fontsize=TITLE_PT)
        axis.axis("off")
        for i, (x0, y0, x1, y1) in enumerate(boxes):
            cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
            text = _wrap(names[i])
            if picture is not shown and fractions is not None and fractions[i] is not None:
                text += f"\n{100 * fractions[i]:.0f} % detected"
            axis.text(cx, cy, text, ha="center", va="center", fontsize=8.5, color="black", linespacing=1.1,
                      bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": "none", "alpha": 0.85})
            if skin[i]:
                axis.add_patch(Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, ec="tab:orange", lw=2, ls="--"))
    return save_figure(figure, path)


LABEL_COLOURS = ("tab:blue", "tab:purple", "tab:cyan", "tab:olive", "tab:pink", "tab:brown", "tab:gray")
"""Outline colours of the props' labels (skin is outlined in white)."""


def figure_face(image: NDArrayFloat, labels: NDArrayFloat, label_names: dict, title: str, path: str | Path,
                mask: NDArrayFloat | None = None) -> Path:
    """
    A face render with its ground-truth labels outlined (skin white, each prop its colour) and, with ``mask``,
    the detected pixels over it: green where the label is skin (true positives), red on props (false
    positives), yellow on the background.

    ``image``: ``(h, w, 3)`` output units (:func:`display_srgb`); ``labels``: ``(h, w)`` ints (0 background,
    1 skin, 2… props, named by ``label_names`` ``{name: id}``); ``mask``: ``(h, w)`` bools.
    """
    plt = pyplot_agg()
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    shown = display_srgb(image)
    labels = np.asarray(labels)
    panels = [("render (camera RGB shown as sRGB)", shown, False)]
    if mask is not None:
        panels.append(("detected skin over the render", 0.55 * shown + 0.2, True))
    figure, axes = plt.subplots(1, len(panels), figsize=(5.2 * len(panels), 5.8), squeeze=False)
    handles = {}
    for axis, (label, picture, overlay) in zip(axes[0], panels):
        axis.imshow(picture, interpolation="nearest")
        if overlay:
            tint = np.zeros((*labels.shape, 4))
            for ident, colour in ((1, (0.1, 0.9, 0.1)), (0, (1.0, 0.9, 0.0))):
                tint[np.asarray(mask) & (labels == ident)] = (*colour, 0.75)
            tint[np.asarray(mask) & (labels >= 2)] = (0.95, 0.1, 0.1, 0.85)
            axis.imshow(tint, interpolation="nearest")
        for k, (name, ident) in enumerate((n, i) for n, i in label_names.items() if i > 0):
            colour = "white" if ident == 1 else LABEL_COLOURS[k % len(LABEL_COLOURS)]
            if (labels == ident).any():
                axis.contour(labels == ident, levels=[0.5], colors=[colour], linewidths=1.2)
                handles[name] = Line2D([], [], color=colour, lw=2, label=f"label: {name}")
        axis.set_title(label, fontsize=10)
        axis.set_xticks([])
        axis.set_yticks([])
    handles = list(handles.values())
    if mask is not None:
        handles += [Patch(color=(0.1, 0.9, 0.1), label="detected on skin"), Patch(color=(0.95, 0.1, 0.1),
                    label="detected on a prop"), Patch(color=(1.0, 0.9, 0.0), label="detected on background")]
    figure.suptitle(title, fontsize=11)
    legend = {"handles": handles, "ncol": 3 if mask is not None else 2, "frameon": True, "facecolor": "0.7"}
    return save_figure(figure, path, legend if handles else None)  # a grey ground: the skin's outline is white


def figure_ladder(levels: list[dict], polygon: NDArrayFloat, analytic: NDArrayFloat, title: str,
                  path: str | Path, label_names: dict | None = None, budget: float | None = None) -> Path:
    """
    The physics ladder: one row per level with the render, its label mask, the detected mask and the skin
    pixels' NCC (r, g) over the analytic skin locus, with the detection budget around Eq. 4's skin and, in
    each row's title, how far the level moves the skin (against the budget), the rates and the seconds.

    ``levels``: ``{"name", "image" (h, w, 3) output units, "labels" (h, w) ints, "detected" (h, w) bools
    (scored pixels inside the locus), "skin_rg" (N, 2) and "prop_rg" (M, 2) NCC of the scored skin and prop
    pixels, "tpr", "fpr" (fractions or None), "seconds", "spp"}`` and optionally ``"eq4_shift"``,
    ``"within_budget"``, ``"tpr_change"``, ``"fpr_change"`` and ``"eq4_ncc_mean"`` (the skin's mean (r, g));
    ``polygon``: the locus, closed or not, ``(K, 2)``; ``analytic``: Eq. 4's skin NCC ``(r, g, …)``;
    ``label_names``: ``{name: id}`` for the labels' legend; ``budget``: the detection budget (NCC), drawn as a
    circle around Eq. 4's skin.
    """
    plt = pyplot_agg()
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    closed = np.vstack([polygon, polygon[:1]])
    points = np.vstack([analytic[None, :2], *[np.asarray(v[key]).reshape(-1, 2) for v in levels
                                             for key in ("skin_rg", "prop_rg")]])
    low = np.minimum(closed.min(axis=0), np.percentile(points, 0.5, axis=0))
    high = np.maximum(closed.max(axis=0), np.percentile(points, 99.5, axis=0))
    pad = 0.05 * (high - low).max() + 0.005
    colours = ["black", "tab:orange", *LABEL_COLOURS]
    names = {0: "background", **{i: n for n, i in (label_names or {}).items() if i > 0}}
    labels_max = max(int(np.asarray(v["labels"]).max()) for v in levels)
    cmap = ListedColormap([colours[i % len(colours)] for i in range(max(labels_max, *names) + 1)])
    figure, axes = plt.subplots(len(levels), 4, figsize=(12, 3.0 * len(levels) + 0.6), squeeze=False)
    shown = lambda v: "—" if v is None else f"{v:.3f}"  # noqa: E731
    from ..rendering.face.effects import PHYSICS_REGISTRY

    base = PHYSICS_REGISTRY.base.name  # the level the changes are from
    for row, level in zip(axes, levels):
        labels = np.asarray(level["labels"])
        row[0].imshow(display_srgb(level["image"]), interpolation="nearest")
        row[0].set_ylabel(level["name"].replace("+", "+\n"), fontsize=10)
        row[0].set_title(f"render, {level['spp']} spp, {level['seconds']:.1f} s", fontsize=9)
        row[1].imshow(labels, cmap=cmap, vmin=-0.5, vmax=cmap.N - 0.5, interpolation="nearest")
        row[1].set_title("labels (the ground truth)", fontsize=9)
        row[2].imshow(np.asarray(level["detected"]), cmap="gray", vmin=0, vmax=1, interpolation="nearest")
        changes = ""
        if level.get("tpr_change") is not None and level["name"] != base:  # the base: no change from itself
            changes = f" (Δ {level['tpr_change']:+.3f}, {level['fpr_change']:+.3f})" if level.get(
                "fpr_change") is not None else f" (Δ {level['tpr_change']:+.3f})"
        row[2].set_title(f"detected: TPR {shown(level['tpr'])}, FPR {shown(level['fpr'])}{changes}", fontsize=9)
        for axis in row[:3]:
            axis.set_xticks([])
            axis.set_yticks([])
        row[3].plot(*np.asarray(level["prop_rg"]).reshape(-1, 2).T, ".", ms=1.5, color="tab:blue", alpha=0.4,
                    label="prop pixels")
        row[3].plot(*np.asarray(level["skin_rg"]).reshape(-1, 2).T, ".", ms=1.5, color="tab:orange", alpha=0.5,
                    label="skin pixels")
        row[3].plot(*closed.T, "-", color="tab:red", lw=1.2, label="analytic skin locus")
        row[3].plot(analytic[0], analytic[1], "k+", ms=10, mew=2, label="Eq. 4's skin")
        if budget is not None:
            angle = np.linspace(0, 2 * np.pi, 90)
            row[3].plot(analytic[0] + budget * np.cos(angle), analytic[1] + budget * np.sin(angle), "k:", lw=1,
                        label="detection budget")
        if level.get("eq4_ncc_mean") is not None:
            row[3].plot(*level["eq4_ncc_mean"][:2], "kx", ms=8, mew=1.5, label="skin's mean")
        if level.get("eq4_shift") is not None:
            said = {True: "within", False: "beyond", None: "undecided:"}[level.get("within_budget")]
            row[3].set_title(f"shift {level['eq4_shift']:.4f} {said} budget"
                             + ("" if budget is None else f" {budget:.4f}"), fontsize=9)
        row[3].set(xlim=(low[0] - pad, high[0] + pad), ylim=(low[1] - pad, high[1] + pad))
        row[3].set_xlabel("NCC r", fontsize=8)
        row[3].set_ylabel("NCC g", fontsize=8)
        row[3].tick_params(labelsize=7)
    legend = axes[0, 3].legend(fontsize=7, loc="lower left", framealpha=0.8)
    for handle in legend.legend_handles[:2]:
        handle.set_markersize(6)
    handles = [Patch(color=cmap(i), label=names.get(i, f"label {i}")) for i in range(cmap.N)]
    figure.suptitle(title, fontsize=11)
    return save_figure(figure, path, {"handles": handles, "ncol": min(len(handles), 6), "title": "labels"})


def figure_skin_model(wavelength: NDArrayFloat, reflectance: NDArrayFloat, label: str, measured: list[tuple],
                      path: str | Path) -> Path:
    """
    The skin model's reflectance ``R(λ)`` (fraction, λ in nm) beside the range (min–max band and median) of each
    measured set in ``measured``: ``(name, wavelengths nm, values (n, n_wl))``.
    """
    plt = pyplot_agg()
    figure, axis = plt.subplots(figsize=(6.4, 4.2))
    for (name, lam, values), colour in zip(measured, ("tab:orange", "tab:blue", "tab:green", "tab:purple")):
        axis.fill_between(lam, values.min(axis=0), values.max(axis=0), color=colour, alpha=0.2,
                          label=f"{name}: range of {len(values)}")
        axis.plot(lam, np.median(values, axis=0), ":", color=colour, lw=1, label=f"{name}: median")
    axis.plot(wavelength, reflectance, "k-", lw=2, label=label)
    axis.set(xlabel="wavelength (nm)", ylabel="reflectance", xlim=(wavelength[0], wavelength[-1]), ylim=(0, None),
             title="Skin model against measured skin")
    axis.legend(fontsize=7)
    return save_figure(figure, path)
