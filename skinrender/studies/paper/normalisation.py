"""
Stage 2: the normalisations compared
====================================

The data of the paper's Figs. 3–7 and the figures themselves.

-   :data:`STAGE2_CAMERA`, :data:`STAGE2_NORMALISATIONS`; :class:`Stage2`:
    the setting (camera, sets, illuminants, grid) taken whole.
-   :func:`stage2_pairs`: Munsell gamut volume of every (prevailing,
    calibration) pair under one normalisation (the data of Figs. 3–5).
-   :func:`stage2_observation`: whether the largest volume per calibration
    falls on the calibration illuminant.
-   :func:`stage2_cases`: skin and Munsell one-calibration-case volumes and
    their ratio per calibration (Fig. 7).
-   :func:`stage2_gamut_panels`: the data of Fig. 6.
-   :func:`stage2_write`: Figs. 3–7 (PNG, with CSV) in a folder.

Units: volumes in output units³, temperatures in K.

References
----------
-   :cite:`Martinkauppi2006` : the paper, Stage 2 (Figs. 3–7).
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
from scipy.spatial import ConvexHull

from ...constants import TEMPERATURES_PAPER
from ...datasets import reflectances
from ...errors import SkinrenderError
from ...evaluation.gamut import gamut_calibration, gamut_hull
from ...files import write_output
from ...evaluation.hull import hull_volume_vertices
from ...hints import ArrayLike, NDArrayFloat
from ...model.camera import camera
from ...model.response import response
from ...spectra import GRID_DEFAULT, WavelengthGrid

__all__ = ["STAGE2_CAMERA", "STAGE2_NORMALISATIONS", "Stage2", "stage2_pairs", "stage2_observation", "stage2_cases",
           "stage2_gamut_panels", "stage2_write"]

STAGE2_CAMERA = "Nikon 5100 (NPL)"
"""Camera of Stage 2 (the paper's Sony is not public; any bundled camera or CSV can stand in)."""

STAGE2_NORMALISATIONS = (("560nm", True), ("euclidean", True), ("white", False))
"""Figs. 3, 4, 5: 560nm and euclidean with the knee (the paper's choice), white without."""


@dataclasses.dataclass(frozen=True)
class Stage2:
    """
    Stage 2's setting, taken whole by :func:`stage2_cases` and :func:`stage2_write`: the camera (a spec), the
    skin and Munsell reflectance sets (specs), the illuminant set (K) and the wavelength grid (nm).

    Examples
    --------
    >>> Stage2.of("Kodak DCS-200", munsell="macbeth")
    Stage2(camera_spec='Kodak DCS-200', skin='skin', munsell='macbeth', illuminants=(2000.0, ...), grid=...)
    """

    camera_spec: str = STAGE2_CAMERA
    skin: str = "skin"
    munsell: str = "munsell"
    illuminants: ArrayLike = TEMPERATURES_PAPER
    grid: WavelengthGrid = GRID_DEFAULT

    @classmethod
    def of(cls, camera_spec: str | Stage2 = STAGE2_CAMERA, **fields) -> Stage2:
        """``camera_spec`` (a camera spec, or a whole :class:`Stage2`) with ``fields`` replaced; an unknown
        field is refused, named."""
        names = [field.name for field in dataclasses.fields(cls)]
        unknown = sorted(set(fields) - set(names))
        if unknown:
            raise SkinrenderError(f"{', '.join(unknown)}: not a Stage 2 setting; the settings: {', '.join(names)}")
        return dataclasses.replace(camera_spec if isinstance(camera_spec, cls) else cls(camera_spec), **fields)

    @property
    def temperatures(self) -> NDArrayFloat:
        """The illuminant set as an array, K."""
        return np.asarray(self.illuminants, dtype=np.float64)


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

    Each volume comes from :func:`skinrender.evaluation.hull.hull_volume_vertices`
    (the compiled Quickhull, Qhull for flat clouds: the volumes of
    :func:`skinrender.gamut` to ~1e-15, several times faster).

    Returns
    -------
    :class:`numpy.ndarray`
        ``volumes[p, q]``, output units³, shape ``(P, Q)``.
    """

    t = np.asarray(illuminants, dtype=np.float64)
    points = response(camera(camera_spec), reflectances(reflectance).on(grid), t[:, None], t[None, :],
                      normalization, knee, grid)
    return np.array([[hull_volume_vertices(np.ascontiguousarray(points[p, q]))[0] for q in range(t.size)]
                     for p in range(t.size)])


def stage2_observation(volumes: NDArrayFloat) -> dict:
    """
    Where the largest volume of each calibration falls (the paper's Stage 2 claim).

    Returns
    -------
    dict
        ``argmax_prevailing`` (index per calibration), ``on_calibration``
        (count of calibrations whose largest volume is at p = q), ``total``.

    Examples
    --------
    >>> stage2_observation(np.array([[2.0, 1.0], [1.0, 3.0]]))["on_calibration"]
    2
    """

    argmax = np.argmax(volumes, axis=0)
    on = int(np.sum(argmax == np.arange(volumes.shape[1])))
    return {"argmax_prevailing": argmax.tolist(), "on_calibration": on, "total": int(volumes.shape[1])}


def stage2_cases(camera_spec: str | Stage2 = STAGE2_CAMERA, **setting) -> dict:
    """
    Skin and Munsell one-calibration-case volumes per calibration (white) and their ratio (Fig. 7).

    ``camera_spec`` is a camera spec or a whole :class:`Stage2`; ``setting`` its other fields by keyword
    (``skin``, ``munsell``, ``illuminants`` in K, ``grid`` in nm). Returns ``skin`` and ``munsell`` (output
    units³ per calibration), their ``ratio`` and the ``temperatures`` (K).
    """
    stage = Stage2.of(camera_spec, **setting)
    t, grid = stage.temperatures, stage.grid
    cam = camera(stage.camera_spec)
    out = {}
    for name, spec in (("skin", stage.skin), ("munsell", stage.munsell)):
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
    p = c (the fifth illuminant, or the last of a shorter set) and at the
    first illuminant balanced to it, each with its hull facets and volume
    (output units³).
    """
    t = np.asarray(illuminants, dtype=np.float64)
    middle = t[min(4, t.size - 1)]
    o = reflectances(reflectance).on(grid)
    panels = []
    for p, q in ((middle, middle), (t[0], middle)):
        rgb = response(camera_spec, o, p, q, "560nm", True, grid)
        result, _ = gamut_hull(rgb)
        panels.append({"rgb": rgb, "simplices": None if result.degenerate else ConvexHull(rgb).simplices,
                       "volume": result.volume, "label": f"prevailing {p:g} K, calibration {q:g} K"})
    return panels


def stage2_write(directory: str | Path, camera_spec: str | Stage2 = STAGE2_CAMERA,
                 **setting) -> tuple[dict, list[Path]]:
    """
    Figs. 3–7 (PNG; Figs. 3–5 with their volumes as CSV) in ``directory``, for ``camera_spec`` (a camera spec or
    a whole :class:`Stage2`) and ``setting`` (its other fields by keyword, as :func:`stage2_cases`).

    Returns
    -------
    tuple
        The observation per normalisation (:func:`stage2_observation`) and the
        paths written.
    """
    from ..figures import figure_cases, figure_gamuts, figure_pairs

    directory = Path(directory)
    stage = Stage2.of(camera_spec, **setting)
    camera_spec, munsell, temperatures, grid = stage.camera_spec, stage.munsell, stage.temperatures, stage.grid
    artifacts: list[Path] = []
    stage2 = {}
    for number, (normalization, knee) in zip((3, 4, 5), STAGE2_NORMALISATIONS):
        volumes = stage2_pairs(camera_spec, munsell, normalization, knee, temperatures, grid)
        stage2[normalization] = stage2_observation(volumes)
        path = directory / f"fig{number}_{normalization}.png"
        figure_pairs(volumes, temperatures,
                     f"Fig. {number}: Munsell gamut per pair, {normalization}{' with knee' if knee else ''} "
                     f"({camera_spec})", path)
        csv = directory / f"fig{number}_{normalization}.csv"
        header = (f"rows: prevailing, columns: calibration (illuminants {', '.join(f'{t:g}' for t in temperatures)} "
                  "K); output units^3")
        write_output(csv, lambda stream, volumes=volumes: np.savetxt(stream, volumes, delimiter=",", header=header))
        artifacts += [path, csv]
    path = directory / "fig6_gamuts.png"
    figure_gamuts(stage2_gamut_panels(camera_spec, munsell, temperatures, grid),
                  f"Fig. 6: Munsell gamuts, 560nm normalisation with knee ({camera_spec})", path)
    artifacts.append(path)
    path = directory / "fig7_cases.png"
    figure_cases(stage2_cases(stage), path)
    artifacts.append(path)
    return stage2, artifacts
