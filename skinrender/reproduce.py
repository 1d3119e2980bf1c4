"""
Reproducing the paper's Stage 2 and Stage 3
===========================================

-   :func:`stage2_pairs`: Munsell gamut volume of every (prevailing,
    calibration) pair under one normalisation (the data of Figs. 3–5).
-   :func:`stage2_observation`: whether the largest volume per calibration
    falls on the calibration illuminant.
-   :func:`stage2_cases`: skin and Munsell one-calibration-case volumes and
    their ratio per calibration (Fig. 7).
-   :func:`table_rows`: the rows of Tables 2–5 from a :class:`SearchResult`.
-   :data:`PAPER_TABLES`: the paper's printed Tables 2–5, for comparison.
-   :func:`reproduce`: every table (Markdown and CSV) and figure (PNG) in a
    folder.

References
----------
-   :cite:`Martinkauppi2006` : the paper, Stage 2 (Figs. 3–7), Stage 3 (Tables 2–5).
"""

from __future__ import annotations

import csv
import sys
from pathlib import Path

import numpy as np

from .camera import camera, response
from .constants import TEMPERATURES_PAPER
from .datasets import reflectances
from .gamut import gamut, gamut_calibration, gamut_hull
from .hints import ArrayLike, NDArrayFloat
from .search import SENSORS_PAPER, TOLERANCE_TIE, SearchResult, search
from .spectra import GRID_DEFAULT, WavelengthGrid

__all__ = [
    "STAGE2_CAMERA",
    "STAGE2_NORMALISATIONS",
    "PAPER_TABLES",
    "stage2_pairs",
    "stage2_observation",
    "stage2_cases",
    "table_rows",
    "reproduce",
]

STAGE2_CAMERA = "Nikon 5100 (NPL)"
"""Camera of Stage 2 (the paper's Sony is not public; any bundled camera or CSV can stand in)."""

STAGE2_NORMALISATIONS = (("560nm", True), ("euclidean", True), ("white", False))
"""Figs. 3, 4, 5: 560nm and euclidean with the knee (the paper's choice), white without."""

# The paper's Tables 2–5 as printed (triplets in nm, temperatures in K).
PAPER_TABLES = {
    "table2_skin": {1: "400 590 700, 3900 K", 3: "400 530 700, 3300 K", 5: "400 540 700, 3300 K",
                    7: "400 550 700, 3300 K", 9: "400 550 700, 3300 K; 400 560 700, 3300 K",
                    11: "400 550 700, 3300 K", 13: "400 550 700, 3300 K", 15: "400 550 700, 3300 K"},
    "table2_munsell": {1: "420 530 700, 3300 K", 3: "430 540 700, 3300 K", 5: "430 540 700, 3300 K",
                       7: "430 540 700, 3300 K", 9: "430 540 700, 3300 K", 11: "430 540 700, 3300 K",
                       13: "430 540 700, 3300 K", 15: "430 540 700, 3300 K"},
    "table3_ratio": {1: "420 550 560, 2000 K", 3: "420 550 560, 2000 K",
                     5: "530 540 550, 2800 K; 530 540 550, 3300 K", 7: "520 540 550, 2200 K",
                     9: "510 520 530, 2800 K, 3300 K, 3900 K",
                     11: "520 530 540, 2500 K, 2800 K, 3300 K, 3900 K, 4800 K",
                     13: "520 530 540, 2000–7500 K (9 temperatures)",
                     15: "520 530 540, 2000–5900 K (8 temperatures)"},
    "table4_skin": {1: "470 610 700", 3: "470 610 700", 5: "470 600 700", 7: "470 600 700",
                    9: "470 590 700", 11: "470 590 700", 13: "470 590 700", 15: "470 590 700"},
    "table4_munsell": {1: "430 530 700", 3: "430 540 700", 5: "440 550 700", 7: "440 550 700",
                       9: "440 550 700", 11: "440 550 700", 13: "440 550 700", 15: "440 550 700"},
    "table5_ratio": {1: "550 570 580", 3: "540 550 560", 5: "530 540 550", 7: "530 540 550",
                     9: "440 450 460", 11: "450 460 470", 13: "440 450 460", 15: "440 450 460"},
}


def stage2_pairs(
    camera_spec: str = STAGE2_CAMERA,
    reflectance: str = "munsell",
    normalization: str = "white",
    knee: bool = False,
    illuminants: ArrayLike = TEMPERATURES_PAPER,
    grid: WavelengthGrid = GRID_DEFAULT,
) -> NDArrayFloat:
    """
    Gamut volume of one reflectance set for every (prevailing, calibration) pair.

    Returns
    -------
    :class:`numpy.ndarray`
        ``volumes[p, q]``, output units³, shape ``(P, Q)``.
    """

    t = np.asarray(illuminants, dtype=np.float64)
    points = response(camera(camera_spec), reflectances(reflectance).on(grid), t[:, None], t[None, :],
                      normalization, knee, grid)
    return np.array([[gamut(points[p, q]).volume for q in range(t.size)] for p in range(t.size)])


def stage2_observation(volumes: NDArrayFloat) -> dict:
    """
    Where the largest volume of each calibration falls (the paper's Stage 2 claim).

    Returns
    -------
    dict
        ``argmax_prevailing`` (index per calibration), ``on_calibration``
        (count of calibrations whose largest volume is at p = q), ``total``.
    """

    argmax = np.argmax(volumes, axis=0)
    on = int(np.sum(argmax == np.arange(volumes.shape[1])))
    return {"argmax_prevailing": argmax.tolist(), "on_calibration": on, "total": int(volumes.shape[1])}


def stage2_cases(
    camera_spec: str = STAGE2_CAMERA,
    skin: str = "skin",
    munsell: str = "munsell",
    illuminants: ArrayLike = TEMPERATURES_PAPER,
    grid: WavelengthGrid = GRID_DEFAULT,
) -> dict:
    """Skin and Munsell one-calibration-case volumes per calibration (white) and their ratio (Fig. 7)."""
    t = np.asarray(illuminants, dtype=np.float64)
    cam = camera(camera_spec)
    out = {}
    for name, spec in (("skin", skin), ("munsell", munsell)):
        values = reflectances(spec).on(grid)
        out[name] = np.array([gamut_calibration(cam, values, q, t, "white", False, grid).volume for q in t])
    out["ratio"] = out["skin"] / out["munsell"]
    out["temperatures"] = t
    return out


def _triplet_text(triplet) -> str:
    return " ".join(f"{v:g}" for v in triplet)


def _rows_text(rows: list[dict]) -> str:
    """``p1 p2 p3, T1 K, T2 K; …`` grouping tied temperatures per triplet as the paper does."""
    groups: dict[str, list] = {}
    for row in rows:
        groups.setdefault(_triplet_text(row["triplet"]), []).append(row["temperature_K"])
    parts = []
    for triplet, temperatures in groups.items():
        kelvin = [f"{t:g} K" for t in temperatures if t is not None]
        parts.append(", ".join([triplet, *kelvin]))
    return "; ".join(parts)


def table_rows(result: SearchResult, tolerance: float = TOLERANCE_TIE) -> dict:
    """Tables 2–5 entries (text as the paper prints them) for one sensor's search."""
    table = result.table(tolerance)
    one = lambda rows: [r for r in rows if r["temperature_K"] is not None]  # noqa: E731
    every = lambda rows: [r for r in rows if r["temperature_K"] is None]  # noqa: E731
    return {
        "table2_skin": _rows_text(one(table["max_skin"])),
        "table2_munsell": _rows_text(one(table["max_munsell"])),
        "table3_ratio": _rows_text(one(table["min_ratio"])),
        "table4_skin": _rows_text(every(table["max_skin"])),
        "table4_munsell": _rows_text(every(table["max_munsell"])),
        "table5_ratio": _rows_text(every(table["min_ratio"])),
    }


_TABLES = (
    ("Table 2. Maximum gamut, one calibration case (skin)", "table2_skin"),
    ("Table 2. Maximum gamut, one calibration case (Munsell)", "table2_munsell"),
    ("Table 3. Minimum skin/Munsell ratio, one calibration case", "table3_ratio"),
    ("Table 4. Maximum gamut, all calibrations (skin)", "table4_skin"),
    ("Table 4. Maximum gamut, all calibrations (Munsell)", "table4_munsell"),
    ("Table 5. Minimum skin/Munsell ratio, all calibrations", "table5_ratio"),
)


def _write_tables(rows: dict[float, dict], directory: Path) -> list[Path]:
    markdown = ["# Tables 2–5: ours beside the paper's", ""]
    paths = []
    for title, key in _TABLES:
        markdown += [f"## {title}", "", "| sensor | skinrender | paper |", "|---|---|---|"]
        path = directory / f"{key}.csv"
        with open(path, "w", encoding="utf-8", newline="") as handle:
            writer = csv.writer(handle, lineterminator="\n")
            writer.writerow(["sensor", "skinrender", "paper"])
            for sensor, entries in rows.items():
                paper = PAPER_TABLES[key].get(int(sensor), "")
                writer.writerow([f"{sensor:g}", entries[key], paper])
                markdown.append(f"| {sensor:g} | {entries[key]} | {paper} |")
        markdown.append("")
        paths.append(path)
    md = directory / "tables.md"
    md.write_text("\n".join(markdown), encoding="utf-8")
    return [md, *paths]


def _figure_pairs(volumes: NDArrayFloat, temperatures: NDArrayFloat, title: str, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

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
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)


def _figure_gamuts(camera_spec: str, grid: WavelengthGrid, temperatures: NDArrayFloat, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    from scipy.spatial import ConvexHull

    o = reflectances("munsell").on(grid)
    cases = ((temperatures[4], temperatures[4]), (temperatures[0], temperatures[4]))
    figure = plt.figure(figsize=(10, 4.8))
    for i, (p, q) in enumerate(cases):
        rgb = response(camera_spec, o, p, q, "560nm", True, grid)
        axis = figure.add_subplot(1, 2, i + 1, projection="3d")
        result, _ = gamut_hull(rgb)
        if not result.degenerate:
            hull = ConvexHull(rgb)
            axis.add_collection3d(Poly3DCollection(rgb[hull.simplices], alpha=0.25, facecolor="tab:blue",
                                                   edgecolor="k", linewidth=0.1))
        axis.scatter(*rgb.T, s=1, c=np.clip(rgb / 255, 0, 1))
        axis.set(xlabel="R", ylabel="G", zlabel="B", xlim=(0, 260), ylim=(0, 260), zlim=(0, 260))
        axis.set_title(f"prevailing {p:g} K, calibration {q:g} K\nvolume {result.volume:.4g}", fontsize=9)
    figure.suptitle(f"Fig. 6: Munsell gamuts, 560nm normalisation with knee ({camera_spec})")
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)


def _figure_cases(cases: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    index = np.arange(1, cases["temperatures"].size + 1)
    figure, axes = plt.subplots(1, 3, figsize=(12, 3.6))
    for axis, key, label in zip(axes, ("skin", "munsell", "ratio"), ("skin gamut", "Munsell gamut", "skin / Munsell")):
        axis.plot(index, cases[key], "o-")
        axis.set(xlabel="calibration illuminant (1–10)", title=label, xticks=index)
    figure.suptitle("Fig. 7: one-calibration-case gamuts, white normalisation")
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)


def reproduce(
    directory: str | Path,
    sensors: ArrayLike = SENSORS_PAPER,
    positions: str | ArrayLike = "400:700:10",
    camera_spec: str = STAGE2_CAMERA,
    skin: str = "skin",
    munsell: str = "munsell",
    slope: float = 2.0,
    grid: WavelengthGrid = GRID_DEFAULT,
    workers: int | None = None,
    dask=None,
    progress=sys.stderr,
) -> dict:
    """
    Write the paper's Figs. 3–7 (PNG) and Tables 2–5 (Markdown, CSV) to ``directory``.

    Parameters
    ----------
    directory
        Output folder (created).
    sensors
        Sensor numbers of Tables 2–5 (1 = impulse).
    positions
        Peak grid, nm (the paper's ``400:700:10``; a coarser one for a quick look).
    camera_spec
        The Stage 2 camera (Figs. 3–7).
    skin, munsell
        Reflectance sets.
    progress
        Stream for progress bars (``None`` for silence).

    Returns
    -------
    dict
        ``artifacts`` (paths), ``stage2`` (per-normalisation observations),
        ``tables`` (rows per sensor), ``search_s`` (seconds per sensor).
    """

    directory = Path(directory)
    (directory / "search").mkdir(parents=True, exist_ok=True)
    temperatures = np.asarray(TEMPERATURES_PAPER, dtype=np.float64)
    artifacts: list[Path] = []
    stage2 = {}
    for number, (normalization, knee) in zip((3, 4, 5), STAGE2_NORMALISATIONS):
        volumes = stage2_pairs(camera_spec, munsell, normalization, knee, temperatures, grid)
        stage2[normalization] = stage2_observation(volumes)
        path = directory / f"fig{number}_{normalization}.png"
        _figure_pairs(volumes, temperatures,
                      f"Fig. {number}: Munsell gamut per pair, {normalization}{' with knee' if knee else ''} "
                      f"({camera_spec})", path)
        artifacts.append(path)
        np.savetxt(directory / f"fig{number}_{normalization}.csv", volumes, delimiter=",",
                   header="rows: prevailing, columns: calibration (paper illuminants 1-10); output units^3")
        artifacts.append(directory / f"fig{number}_{normalization}.csv")
    path = directory / "fig6_gamuts.png"
    _figure_gamuts(camera_spec, grid, temperatures, path)
    artifacts.append(path)
    cases = stage2_cases(camera_spec, skin, munsell, temperatures, grid)
    path = directory / "fig7_cases.png"
    _figure_cases(cases, path)
    artifacts.append(path)

    skin_values, munsell_values = reflectances(skin).on(grid), reflectances(munsell).on(grid)
    rows: dict[float, dict] = {}
    timings: dict[str, float] = {}
    for sensor in sensors:
        result = search(sensor, skin_values, munsell_values, positions, temperatures, slope, grid=grid,
                        workers=workers, dask=dask, progress=progress, label=f"sensor {sensor:>2g}")
        rows[float(sensor)] = table_rows(result)
        timings[f"{sensor:g}"] = result.elapsed_s
        path = directory / "search" / f"sensor_{sensor:g}.csv"
        result.to_csv(path)
        artifacts.append(path)
    artifacts += _write_tables(rows, directory)
    return {
        "artifacts": [str(p) for p in artifacts],
        "stage2": stage2,
        "tables": {f"{k:g}": v for k, v in rows.items()},
        "search_s": timings,
    }
