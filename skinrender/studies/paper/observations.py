"""
The paper's observations, camera by camera
==========================================

The paper states, in its text, figures for Stage 1 (NCC differences between
Planckian illuminants, seen by its Sony camera) and observations for Stage 2
(where the largest Munsell gamut of each calibration falls). Its camera is not
public; these functions recompute both for every bundled camera and for the
measured Sony DXC-930 (its closest relative, in ``../shared/data`` beside a
checkout) so that the paper's numbers stand beside ours.

-   :data:`PAPER_STAGE1_TEXT`, :func:`stage1_text`: the Stage 1 differences.
-   :data:`PAPER_STAGE2_CLAIMS`, :func:`stage2_by_camera`: the Stage 2
    observations, counted per camera.
-   :data:`ROOT_SHARED_DATA`, :func:`shared_file`, :func:`sony_dxc930_csv`,
    :func:`paper_cameras`: the reference data and the cameras compared.

Units: temperatures in K; chromaticities unitless.

References
----------
-   :cite:`Martinkauppi2006` : Stage 1 (text beside Fig. 2), Stage 2 (Figs. 3–5)
    (docs/references.md).
-   :cite:`Barnard2002` : the SFU data set, DXC-930 sensitivities.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from ...constants import TEMPERATURES_PAPER
from ...datasets import list_cameras
from ...files import write_output
from ...model.stage1 import illuminant_track, select_illuminants
from ...spectra import GRID_DEFAULT, WavelengthGrid
from .normalisation import STAGE2_NORMALISATIONS, stage2_observation, stage2_pairs

__all__ = ["ROOT_SHARED_DATA", "SONY_DXC930_FLOORS", "PAPER_STAGE1_TEXT", "PAPER_STAGE2_CLAIMS", "shared_file",
           "sony_dxc930_csv", "paper_cameras", "stage1_pairs", "stage1_text", "stage2_by_camera"]

ROOT_SHARED_DATA = Path(os.environ.get("SKINRENDER_SHARED_DATA",
                                       Path(__file__).resolve().parents[3] / "shared" / "data"))
"""``../shared/data`` beside the checkout (``SKINRENDER_SHARED_DATA`` overrides it); absent in a fresh clone."""

SONY_DXC930_FLOORS = {"R": 82.2, "B": 21.2}
"""The flat measurement floors of the DXC-930's R and B curves (``../shared/data/README.md``), subtracted."""

_STEP_INVERSE = 1.0 / 9000.0 - 1.0 / 10000.0  # K⁻¹

PAPER_STAGE1_TEXT = {
    "inverse_step_high": {"between_K": [9000.0, 10000.0], "ncc_r": 0.0116, "ncc_b": 0.0071, "euclidean": 0.0208},
    "inverse_step_low": {"between_K": [2000.0, 1.0 / (1.0 / 2000.0 - _STEP_INVERSE)], "ncc_r": 0.0097,
                         "ncc_b": 0.0040, "euclidean": 0.0105},
    "range_low": {"between_K": [2000.0, 3000.0], "ncc_r": 0.1665, "ncc_b": 0.0930, "euclidean": 0.1912},
}
"""The paper's Stage 1 figures (text beside Fig. 2): the differences in NCC r, NCC b and their Euclidean
combination between 9000 K and 10000 K, over the same step of inverse temperature from 2000 K (to
2045.5 K), and between 2000 K and 3000 K, for its Sony camera. Its 0.0208 is not √(0.0116² + 0.0071²) =
0.0136; the other two Euclidean figures are (0.0105, 0.1907)."""

PAPER_STAGE2_CLAIMS = {"560nm": "off", "euclidean": "off", "white": "on"}
"""Stage 2 (Figs. 3–5): the largest Munsell gamut of a calibration falls off the calibration illuminant
for the 560nm and euclidean normalisations (with the knee), on it for white (WP)."""


def shared_file(name: str, shared: str | Path | None = None) -> Path | None:
    """A file of ``../shared/data`` (or ``shared``), ``None`` where absent."""
    path = Path(ROOT_SHARED_DATA if shared is None else shared) / name
    return path if path.is_file() else None


def sony_dxc930_csv(directory: str | Path, shared: str | Path | None = None) -> Path | None:
    """
    The DXC-930 sensitivities with their R and B floors subtracted (clipped at 0),
    written to ``directory/sony_dxc930.csv``; ``None`` where the data is absent.
    """
    source = shared_file("camera_sony_dxc930_sfu.csv", shared)
    if source is None:
        return None
    data = np.genfromtxt(source, delimiter=",", names=True)
    rows = np.column_stack([data["wavelength_nm"], np.maximum(data["R"] - SONY_DXC930_FLOORS["R"], 0.0), data["G"],
                            np.maximum(data["B"] - SONY_DXC930_FLOORS["B"], 0.0)])
    out = Path(directory) / "sony_dxc930.csv"
    write_output(out, lambda stream: np.savetxt(stream, rows, delimiter=",", header="wavelength_nm,R,G,B",
                                                comments="", fmt="%.6g"))
    return out


def paper_cameras(directory: str | Path, shared: str | Path | None = None) -> list[tuple[str, str]]:
    """``(label, spec)`` of every bundled camera and, where present, the DXC-930 (its CSV written to ``directory``)."""
    cameras = [(row["name"], row["name"]) for row in list_cameras()]
    dxc = sony_dxc930_csv(directory, shared)
    return cameras + ([("Sony DXC-930 (SFU)", str(dxc))] if dxc is not None else [])


def stage1_pairs() -> dict:
    """The temperature pairs (K) of :data:`PAPER_STAGE1_TEXT`, name → ``[T1, T2]``."""
    return {name: list(entry["between_K"]) for name, entry in PAPER_STAGE1_TEXT.items()}


def stage1_text(cameras: list[tuple[str, str]], grid: WavelengthGrid = GRID_DEFAULT) -> dict:
    """
    The paper's Stage 1 figures recomputed per camera.

    For each pair of :data:`PAPER_STAGE1_TEXT`: ``|Δ NCC r|``, ``|Δ NCC b|`` and
    ``euclidean = √(Δr² + Δb²)`` of a white object (Eq. 1, Eq. 2); and the
    camera's Stage 1 selection with how many of the paper's ten it shares.

    Returns
    -------
    dict
        ``paper`` (:data:`PAPER_STAGE1_TEXT` with the paper's ten
        temperatures) and ``cameras``: ``[{camera, <pair>: {ncc_r, ncc_b,
        euclidean}, temperatures, shared_with_paper}]``.

    Examples
    --------
    >>> row = stage1_text([("Nikon", "Nikon 5100 (NPL)")])["cameras"][0]
    >>> 0 < row["range_low"]["ncc_r"] < 1
    True
    """
    rows = []
    for label, spec in cameras:
        row: dict = {"camera": label}
        for name, (low, high) in stage1_pairs().items():
            ncc = illuminant_track(spec, np.array([low, high]), grid).chromaticities
            dr, db = ncc[1, 0] - ncc[0, 0], ncc[1, 2] - ncc[0, 2]
            row[name] = {"ncc_r": float(abs(dr)), "ncc_b": float(abs(db)), "euclidean": float(np.hypot(dr, db))}
        chosen = select_illuminants(spec, grid=grid)
        row["temperatures"] = chosen.tolist()
        row["shared_with_paper"] = len(set(chosen.tolist()) & set(TEMPERATURES_PAPER))
        rows.append(row)
    return {"paper": {**PAPER_STAGE1_TEXT, "temperatures": list(TEMPERATURES_PAPER)}, "cameras": rows}


def stage2_by_camera(cameras: list[tuple[str, str]], munsell: str = "munsell",
                     illuminants=TEMPERATURES_PAPER, grid: WavelengthGrid = GRID_DEFAULT) -> list[dict]:
    """
    The paper's Stage 2 observations (:data:`PAPER_STAGE2_CLAIMS`) checked per camera.

    Returns
    -------
    list of dict
        Per camera: ``camera``; per normalisation ``{on_calibration,
        as_paper, total}`` (calibrations whose largest Munsell gamut falls on
        the calibration illuminant; those where it falls as the paper says);
        and ``as_paper``, ``total`` over the three.
    """
    out = []
    for label, spec in cameras:
        row: dict = {"camera": label}
        agree = total = 0
        for normalization, knee in STAGE2_NORMALISATIONS:
            seen = stage2_observation(stage2_pairs(spec, munsell, normalization, knee, illuminants, grid))
            on = seen["on_calibration"]
            as_paper = on if PAPER_STAGE2_CLAIMS[normalization] == "on" else seen["total"] - on
            row[normalization] = {"on_calibration": on, "as_paper": as_paper, "total": seen["total"]}
            agree, total = agree + as_paper, total + seen["total"]
        row["as_paper"], row["total"] = agree, total
        out.append(row)
    return out
