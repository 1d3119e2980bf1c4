"""
The effects table's figure
==========================

:func:`figure_effects` draws :mod:`skinrender.studies.face.effects_table` (``skinrender ladder --effects --plot``): per
level and skin tone the skin's NCC shift from Eq. 4 against its detection budget, the TPR and FPR changes from
``direct``, and the seconds. It draws with :mod:`skinrender.studies.figures`' helpers (one figure style, one
place that imports matplotlib).

Units: NCC fractions, rates fractions, seconds s.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..figures import LABEL_COLOURS, pyplot_agg, save_figure

__all__ = ["figure_effects"]


def figure_effects(rows: list[dict], title: str, path: str | Path) -> Path:
    """
    The effects table (:mod:`skinrender.studies.face.effects_table`): per level and skin tone the skin's NCC shift from
    Eq. 4 (to its 95 % upper bound; the tone's budget a dash), the TPR and FPR change from ``direct``, the seconds.
    ``rows``: ``{"tone", "level", "eq4_shift", "eq4_shift_bound", "budget", "tpr_change", "fpr_change",
    "seconds"}`` (``None`` left out).
    """
    plt = pyplot_agg()
    tones = list(dict.fromkeys(row["tone"] for row in rows))
    levels = list(dict.fromkeys(row["level"] for row in rows))
    width = 0.8 / max(len(tones), 1)
    figure, axes = plt.subplots(1, 4, figsize=(16, 4.2))
    colours = ["#e8b88a", "#b07848", "#5a3820", *LABEL_COLOURS]
    value = lambda row, key: np.nan if row.get(key) is None else row[key]  # noqa: E731
    for t, tone in enumerate(tones):
        mine = {row["level"]: row for row in rows if row["tone"] == tone}
        x = np.arange(len(levels)) + (t - (len(tones) - 1) / 2) * width
        get = lambda key: np.array([value(mine.get(level, {}), key) for level in levels], dtype=float)  # noqa: E731
        shift, bound, budget = get("eq4_shift"), get("eq4_shift_bound"), get("budget")
        axes[0].bar(x, shift, width, color=colours[t % len(colours)], label=f"{tone} skin")
        axes[0].errorbar(x, shift, yerr=[np.zeros_like(shift), np.maximum(bound - shift, 0)], fmt="none",
                         ecolor="k", lw=0.8)
        axes[0].plot(x, budget, "_", color="k", ms=14, mew=2)
        axes[1].bar(x, get("tpr_change"), width, color=colours[t % len(colours)])
        axes[2].bar(x, get("fpr_change"), width, color=colours[t % len(colours)])
        axes[3].bar(x, get("seconds"), width, color=colours[t % len(colours)])
    for axis, name in zip(axes, ("skin's NCC shift from Eq. 4 (— budget)", "TPR change from direct",
                                 "FPR change from direct", "seconds per level")):
        axis.set_xticks(np.arange(len(levels)), [level.replace("+", "+\n") for level in levels], fontsize=8)
        axis.set_title(name, fontsize=10)
        axis.tick_params(labelsize=8)
    for axis in axes[1:3]:
        axis.axhline(0, color="k", lw=0.6)
    axes[0].set_yscale("symlog", linthresh=1e-3)
    axes[0].legend(fontsize=8)
    figure.suptitle(title, fontsize=11)
    return save_figure(figure, path)
