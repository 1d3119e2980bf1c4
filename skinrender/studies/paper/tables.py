"""
Tables
======

The paper's tables: Table 1 recomputed with the render as the "real camera",
the rows of Tables 2–5 from a Stage 3 search, and the paper's printed Tables
2–5 to set beside them.

-   :data:`PAPER_TABLES`: the paper's printed Tables 2–5.
-   :func:`table_rows`: one sensor's entries of Tables 2–5.
-   :func:`write_tables`: Tables 2–5 as Markdown and CSV, ours beside the paper's.
-   :data:`TABLE1_CASES`, :data:`TABLE1_TOLERANCE`, :func:`table1`: Table 1,
    with the verdict that the render agrees with Eq. 4 in NCC.

Units: peaks in nm, temperatures in K, NCC unitless.

References
----------
-   :cite:`Martinkauppi2006` : Tables 1–5 (docs/references.md).
"""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import numpy as np

from ...design.search import TOLERANCE_TIE, SearchResult
from ...errors import SkinrenderError
from ...files import write_output
from ...model.camera import Camera, camera
from ...model.chromaticity import ncc
from ...model.response import response_raw, uses_whites, white_coefficient
from ...rendering.balance import render
from ...rendering.scene import load_chart_scene
from ...rendering.settings import RenderSettings
from ...rendering.patch_errors import noise_of
from ...rendering.validation import analytic_reference
from ...hints import NDArrayFloat
from ...spectra import GRID_DEFAULT, WavelengthGrid

__all__ = ["PAPER_TABLES", "TABLES", "table_rows", "write_tables", "TABLE1_CASES", "TABLE1_TOLERANCE", "table1"]

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


TABLES = (
    ("Table 2. Maximum gamut, one calibration case (skin)", "table2_skin"),
    ("Table 2. Maximum gamut, one calibration case (Munsell)", "table2_munsell"),
    ("Table 3. Minimum skin/Munsell ratio, one calibration case", "table3_ratio"),
    ("Table 4. Maximum gamut, all calibrations (skin)", "table4_skin"),
    ("Table 4. Maximum gamut, all calibrations (Munsell)", "table4_munsell"),
    ("Table 5. Minimum skin/Munsell ratio, all calibrations", "table5_ratio"),
)


def write_tables(rows: dict[float, dict], directory: Path) -> list[Path]:
    """Tables 2–5 (``rows`` per sensor from :func:`table_rows`) as ``tables.md`` and one CSV per table."""
    markdown = ["# Tables 2–5: ours beside the paper's", ""]
    paths = []
    for title, key in TABLES:
        markdown += [f"## {title}", "", "| sensor | skinrender | paper |", "|---|---|---|"]
        path = directory / f"{key}.csv"
        handle = io.StringIO(newline="")
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(["sensor", "skinrender", "paper"])
        for sensor, entries in rows.items():
            paper = PAPER_TABLES[key].get(int(sensor), "")
            writer.writerow([f"{sensor:g}", entries[key], paper])
            markdown.append(f"| {sensor:g} | {entries[key]} | {paper} |")
        markdown.append("")
        paths.append(write_output(path, handle.getvalue()))
    md = write_output(directory / "tables.md", "\n".join(markdown))
    return [md, *paths]


TABLE1_CASES = (("AA", "A", "A"), ("AH", "A", "H"), ("HH", "H", "H"), ("HA", "H", "A"))
"""Table 1's (prevailing, calibration) pairs: A = 2856 K, H (Horizon) = 2300 K."""


TABLE1_TOLERANCE = 0.001
"""Default tolerance of Table 1's verdict: an absolute NCC difference (the paper's Eq. 4 rows are ~1e-4 at 256 spp)."""


def _ncc_standard_error(mean: NDArrayFloat, sigma: NDArrayFloat) -> NDArrayFloat:
    """First-order standard errors of the NCC of channel means ``(N, 3)`` with independent errors ``sigma``."""
    total = mean.sum(axis=-1, keepdims=True)
    c = mean / total
    # ∂c_i/∂x_j = (δ_ij − c_i) / S: Var c_i = Σ_j (δ_ij − c_i)² σ_j² / S²
    jacobian = (np.eye(3)[None, :, :] - c[:, :, None]) / total[:, :, None]
    return np.sqrt(np.einsum("nij,nj->ni", jacobian**2, sigma**2))


def table1(
    camera_: Camera | str = "gbell:9@450,540,610",
    settings: RenderSettings | None = None,
    grid: WavelengthGrid = GRID_DEFAULT,
    low: float = 10.0,
    high: float = 245.0,
    fraction: float = 0.9,
    tolerance: float = TABLE1_TOLERANCE,
    **options,
) -> dict:
    """
    The paper's Table 1 with the render as the "real camera", and its verdict.

    Patches are kept when at least ``fraction`` of their pixel values (all
    channels) lie in ``[low, high]`` in all four cases (the paper's rule).
    For each case, the mean and standard deviation of the absolute NCC
    differences (r, g, b pooled) between the rendered patch means and the
    model: Eq. 1 with WP (no white balance), and Eq. 4 with each
    normalisation.

    The verdict (:func:`~skinrender.evaluation.verdict.equivalence`): every
    kept patch's rendered NCC (r, g, b, all four cases) shown within
    ``tolerance`` (absolute NCC) of Eq. 4's at family-wise 95 % confidence,
    the NCC standard errors propagated to first order from the patch
    channels' (:func:`~skinrender.rendering.validation.noise_of`). A
    difference test of the same values (family-wise α = 0.01) is reported
    beside it, and one of Eq. 1 with WP, which the paper's Table 1 shows to
    differ.

    Returns
    -------
    dict
        ``patches`` (kept names), ``rows``: ``[{model, case, mean, std}]``,
        ``verdict`` and ``difference`` (Eq. 4) and ``difference_eq1`` (verdict
        documents), ``bound`` (the smallest NCC tolerance that would pass),
        ``passed`` (the verdict is a pass), ``spp``, ``spp_requested``.
    """

    from ...evaluation.verdict import ALPHA_DIFFERENCE, difference, equivalence

    from ...rendering.agreement import TOLERANCE_MIN

    # below float32's resolution no render resolves it (and 1e-320 overflowed the bounds' ratios to infinity)
    if isinstance(tolerance, bool) or not (isinstance(tolerance, (int, float)) and TOLERANCE_MIN <= tolerance < 1):
        raise SkinrenderError(f"tolerance must be an NCC difference in [{TOLERANCE_MIN:.3g}, 1) (its lower end is "
                              f"float32's resolution), got {tolerance!r}", role="tolerance")
    for name, value in (("low", low), ("high", high), ("fraction", fraction)):
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise SkinrenderError(f"{name} must be a finite number, got {value!r}", role=name)
    if not 0 <= low < high:
        raise SkinrenderError(f"low and high must bound the pixel values kept, 0 ≤ low < high (output units), got "
                              f"{low!r} and {high!r}", role="low" if not 0 <= low else "high")
    if not 0 < fraction <= 1:
        raise SkinrenderError(f"fraction must be in (0, 1], got {fraction!r}", role="fraction")
    chart = load_chart_scene("macbeth")
    cam = camera(camera_)
    cache: dict = {}
    settings = RenderSettings.of(settings, **options)
    renders = {case: render(chart, cam, p, q, "white", False, settings, grid, cache) for case, p, q in TABLE1_CASES}
    keep = []
    for i in range(len(chart.patches) - 1):  # not the white reference
        ok = True
        for r in renders.values():
            rows, columns = chart.patch_pixels(i)
            values = r.image[rows, columns].ravel()
            ok &= np.mean((values >= low) & (values <= high)) >= fraction
        if ok:
            keep.append(i)
    if not keep:
        raise SkinrenderError("Table 1: no Macbeth patch has 90 % of its values within 10–245 in all four cases")
    reflectance = chart.reflectances(grid)[keep]
    rows = []
    models = [("Eq. 1, WP", None)] + [(f"Eq. 4, {n}", n) for n in ("none", "560nm", "euclidean", "white")]
    errors, errors_eq1, standard_errors = [], [], []
    for label, normalization in models:
        for case, p, q in TABLE1_CASES:
            r = renders[case]
            rendered = ncc(r.patches.mean[keep])
            if normalization is None:
                model = response_raw(cam, reflectance, r.prevailing, "none", grid) * white_coefficient(
                    cam, r.prevailing, r.calibration, grid)
            else:
                model = analytic_reference(cam, reflectance, r.prevailing, r.calibration, normalization, False, grid)
            difference_ncc = rendered - ncc(model)
            if normalization is None or uses_whites(normalization):
                full = analytic_reference(cam, chart.reflectances(grid), r.prevailing, r.calibration, "white", False,
                                          grid)
                se = _ncc_standard_error(r.patches.mean[keep], noise_of(r, full)[keep])
                (errors if normalization else errors_eq1).append(difference_ncc)
                if normalization:
                    standard_errors.append(se)
                else:
                    se_eq1 = se
            difference_ncc = np.abs(difference_ncc).ravel()
            rows.append({"model": label, "case": case, "mean": float(difference_ncc.mean()),
                         "std": float(difference_ncc.std(ddof=1))})
    error, se = np.concatenate(errors), np.concatenate(standard_errors)
    dof = float(np.min(next(iter(renders.values())).patches.count) - 1)
    verdict, _ = equivalence(error, se, tolerance, dof=dof, name="table1", scale=np.ones_like(error))
    test = difference(error, se, ALPHA_DIFFERENCE, dof, "difference")
    eq1 = difference(np.concatenate(errors_eq1), np.concatenate([se_eq1] * len(errors_eq1)), ALPHA_DIFFERENCE, dof,
                     "difference_eq1")
    used = next(iter(renders.values())).raw[0].spp  # multijitter rounds the count up
    return {"camera": cam.name, "patches": [chart.patches[i].name for i in keep], "rows": rows, "spp": used,
            "spp_requested": settings.spp, "tolerance": tolerance, "bound": verdict.bound, "verdict": verdict.document(),
            "difference": test.document(), "difference_eq1": eq1.document(), "passed": verdict.outcome == "pass"}
