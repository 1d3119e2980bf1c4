"""
The ranking's figure
====================

:func:`figure_rank` draws :mod:`skinrender.studies.face.ranking` (``skinrender rank --plot``): per level each
candidate's rank by Eq. 4 against its rank on the rendered faces, the diagonal where they agree, Kendall's τ with
its 95 % interval and whether Eq. 4's best camera stays best in the title. It draws with
:mod:`skinrender.studies.figures`' helpers (one figure style, one place that imports matplotlib).

Units: ranks (1 = best).
"""

from __future__ import annotations

from pathlib import Path

from ..figures import pyplot_agg, save_figure

__all__ = ["figure_rank"]


def figure_rank(levels: list[dict], title: str, path: str | Path) -> Path:
    """
    Rank against rank per level. ``levels``: :class:`~skinrender.studies.face.ranking.Ranking`'s (``level``,
    ``candidates`` with ``rank_eq4`` and ``rank_rendered``, ``kendall_tau``, ``kendall_tau_interval``,
    ``same_best``).
    """
    plt = pyplot_agg()
    count = len(levels)
    columns = min(count, 5)
    rows = -(-count // columns)
    figure, axes = plt.subplots(rows, columns, figsize=(3.3 * columns, 3.4 * rows + 0.6), squeeze=False)
    for ax, level in zip(axes.flat, levels):
        a = [float("nan") if c["rank_eq4"] is None else c["rank_eq4"] for c in level["candidates"]]  # unscored
        b = [float("nan") if c["rank_rendered"] is None else c["rank_rendered"] for c in level["candidates"]]
        n = len(a)
        ax.plot([0.5, n + 0.5], [0.5, n + 0.5], color="0.75", lw=1, zorder=1)
        ax.scatter(a, b, s=22, color="#b07848", zorder=2)
        tau, interval = level["kendall_tau"], level["kendall_tau_interval"]
        said = "—" if tau is None else f"{tau:.2f}" + ("" if interval is None else
                                                       f" [{interval[0]:.2f}, {interval[1]:.2f}]")
        best = {True: "same best", False: "another best", None: "best undecided"}[level["same_best"]]
        ax.set_title(f"{level['level']}\nτ {said}; {best}", fontsize=9)
        ax.set_xlim(0.5, n + 0.5)
        ax.set_ylim(n + 0.5, 0.5)
        ax.set_xlim(n + 0.5, 0.5)
        ax.set_xlabel("rank by Eq. 4", fontsize=8)
        ax.set_ylabel("rank on the rendered face", fontsize=8)
        ax.tick_params(labelsize=7)
    for ax in list(axes.flat)[count:]:
        ax.axis("off")
    figure.suptitle(title, fontsize=10)
    return save_figure(figure, path)
