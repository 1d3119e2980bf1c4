"""
Reproducing the paper's Stage 2 and Stage 3
===========================================

-   :func:`stage2_pairs`: Munsell gamut volume of every (prevailing,
    calibration) pair under one normalisation (the data of Figs. 3–5).
-   :func:`stage2_observation`: whether the largest volume per calibration
    falls on the calibration illuminant.
-   :func:`stage2_cases`: skin and Munsell one-calibration-case volumes and
    their ratio per calibration (Fig. 7).
-   :func:`stage2_gamut_panels`: the data of Fig. 6.
-   :func:`reproduce`: every table (Markdown and CSV) and figure (PNG) in a
    folder.

References
----------
-   :cite:`Martinkauppi2006` : the paper, Stage 2 (Figs. 3–7), Stage 3 (Tables 2–5).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from scipy.spatial import ConvexHull

from ..constants import TEMPERATURES_PAPER
from ..datasets import reflectances
from ..design.bank import SENSORS_PAPER
from ..design.search import search
from ..evaluation.gamut import gamut, gamut_calibration, gamut_hull
from ..hints import ArrayLike, NDArrayFloat
from ..model.camera import camera
from ..model.response import response
from ..spectra import GRID_DEFAULT, WavelengthGrid
from .figures import figure_cases, figure_gamuts, figure_pairs
from .tables import table_rows, write_tables

__all__ = [
    "STAGE2_CAMERA",
    "STAGE2_NORMALISATIONS",
    "stage2_pairs",
    "stage2_observation",
    "stage2_cases",
    "stage2_gamut_panels",
    "reproduce",
]

STAGE2_CAMERA = "Nikon 5100 (NPL)"
"""Camera of Stage 2 (the paper's Sony is not public; any bundled camera or CSV can stand in)."""

STAGE2_NORMALISATIONS = (("560nm", True), ("euclidean", True), ("white", False))
"""Figs. 3, 4, 5: 560nm and euclidean with the knee (the paper's choice), white without."""

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


def stage2_gamut_panels(
    camera_spec: str = STAGE2_CAMERA,
    reflectance: str = "munsell",
    illuminants: ArrayLike = TEMPERATURES_PAPER,
    grid: WavelengthGrid = GRID_DEFAULT,
) -> list[dict]:
    """
    Fig. 6's data: Munsell responses (560nm normalisation with the knee) at
    p = c (the fifth illuminant) and at the first illuminant balanced to the
    fifth, each with its hull facets and volume (output units³).
    """
    t = np.asarray(illuminants, dtype=np.float64)
    o = reflectances(reflectance).on(grid)
    panels = []
    for p, q in ((t[4], t[4]), (t[0], t[4])):
        rgb = response(camera_spec, o, p, q, "560nm", True, grid)
        result, _ = gamut_hull(rgb)
        panels.append({"rgb": rgb, "simplices": None if result.degenerate else ConvexHull(rgb).simplices,
                       "volume": result.volume, "label": f"prevailing {p:g} K, calibration {q:g} K"})
    return panels


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
        figure_pairs(volumes, temperatures,
                      f"Fig. {number}: Munsell gamut per pair, {normalization}{' with knee' if knee else ''} "
                      f"({camera_spec})", path)
        artifacts.append(path)
        np.savetxt(directory / f"fig{number}_{normalization}.csv", volumes, delimiter=",",
                   header="rows: prevailing, columns: calibration (paper illuminants 1-10); output units^3")
        artifacts.append(directory / f"fig{number}_{normalization}.csv")
    path = directory / "fig6_gamuts.png"
    figure_gamuts(stage2_gamut_panels(camera_spec, munsell, temperatures, grid),
                  f"Fig. 6: Munsell gamuts, 560nm normalisation with knee ({camera_spec})", path)
    artifacts.append(path)
    cases = stage2_cases(camera_spec, skin, munsell, temperatures, grid)
    path = directory / "fig7_cases.png"
    figure_cases(cases, path)
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
    artifacts += write_tables(rows, directory)
    return {
        "artifacts": [str(p) for p in artifacts],
        "stage2": stage2,
        "tables": {f"{k:g}": v for k, v in rows.items()},
        "search_s": timings,
    }
