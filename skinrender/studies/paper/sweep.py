"""
Sweeping the paper's unknowns
=============================

Which of the paper's unknowns explain the difference between our Tables 2–5
and its own? :func:`sweep` changes one unknown at a time around the default
(:data:`~skinrender.studies.paper.unknowns.SETTING_DEFAULT`), counts the matching
cells of each setting, then combines the best values of the most telling
unknowns. Only the tables are computed (no Stage 2 figures); volumes that two
settings share are computed once (a different skin set reuses the Munsell
volumes), and every setting runs on every core.

-   :data:`SWEEP_SLOPES`, :data:`SWEEP_GRIDS`, :data:`SWEEP_MUNSELL`,
    :data:`SWEEP_SKIN`: the values tried.
-   :func:`sweep_candidates`: the values of every unknown, with the reference
    data where present.
-   :func:`sweep`: the sweep; :func:`write_sweep`: ``sweep.csv``, ``sweep.md``;
    :func:`reproduce_sweep`: both into a checked output folder.

Units: wavelength in nm.
"""

from __future__ import annotations

import csv
import io
import itertools
import json
import tempfile
import time
from pathlib import Path

from ...design.bank import SENSORS_PAPER
from ...errors import SkinrenderError
from ...files import write_output
from ...hints import ArrayLike
from .folders import MANIFEST, check_output, output_folder
from .matching import unmatched_sensors
from .observations import paper_cameras, shared_file
from .tables import TABLES
from .unknowns import (SETTING_DEFAULT, Setting, check_positions, check_search_work, check_sensors, resolve_setting,
                       setting_tables, with_unknown)
from ...execution import check_workers
from .volumes import VolumeCache

__all__ = ["SWEEP_SLOPES", "SWEEP_GRIDS", "SWEEP_MUNSELL", "SWEEP_SKIN", "UNKNOWNS", "sweep_candidates", "sweep",
           "write_sweep", "reproduce_sweep"]

SWEEP_SLOPES = (1.0, 2.0, 3.0, 4.0, 5.0, 6.0)
"""gbell slopes *b* tried (the paper gives none; Matlab's ``gbellmf`` examples use 2 to 4)."""

SWEEP_GRIDS = ("400:700:1", "400:700:5", "380:780:1", "380:780:5")
"""Integration grids tried, nm; outside 400–700 nm the reflectance sets are held constant beyond their data."""

SWEEP_MUNSELL = ("munsell", "munsell-nickerson")
"""Munsell sets tried: Joensuu's 1269 matte chips, Nickerson's 462 papers."""

SWEEP_SKIN = ("skin", "skin-model")
"""Skin sets tried, with the NIST subjects of ``../shared/data/skin_nist.csv`` where present."""

UNKNOWNS = ("slope", "grid", "skin", "munsell", "illuminants")
"""The unknowns, in the order the sweep tries them."""


def sweep_candidates(scratch: str | Path, shared: str | Path | None = None) -> tuple[dict, list[str], dict]:
    """
    The values of every unknown, default first.

    Returns
    -------
    tuple
        ``values`` (unknown → values; ``illuminants`` values are ``(spec,
        Stage 1 camera)``), ``notes`` (what was skipped and why) and ``names``
        (a CSV path → its short name). The DXC-930's cleaned CSV is written to
        ``scratch``.
    """
    notes, names = [], {}
    skin = list(SWEEP_SKIN)
    nist = shared_file("skin_nist.csv", shared)
    if nist is None:
        notes.append("skin: the NIST subjects (../shared/data/skin_nist.csv) are absent, skipped")
    else:
        skin.append(str(nist))
        names[str(nist)] = "NIST (100 subjects)"
    cameras = paper_cameras(scratch, shared)
    if not any(label.startswith("Sony") for label, _ in cameras):
        notes.append("illuminants: the DXC-930 (../shared/data/camera_sony_dxc930_sfu.csv) is absent, skipped")
    names.update({spec: label for label, spec in cameras if label != spec})
    values = {
        "slope": list(SWEEP_SLOPES),
        "grid": list(SWEEP_GRIDS),
        "skin": skin,
        "munsell": list(SWEEP_MUNSELL),
        "illuminants": [("paper", None)] + [("auto", spec) for _, spec in cameras],
    }
    return values, notes, names


def _value(setting: Setting, unknown: str):
    return (setting.illuminants, setting.stage1_camera if setting._auto() else None) if unknown == "illuminants" \
        else getattr(setting, unknown)


def _score(row: dict) -> tuple[int, int]:
    return row["exact"], row["within_step"]


def sweep(
    sensors: ArrayLike | str = SENSORS_PAPER,
    positions: str | ArrayLike = "400:700:10",
    base: Setting = SETTING_DEFAULT,
    combine: int = 3,
    values_per_unknown: int = 1,
    workers: int | None = None,
    dask=None,
    progress=None,
    shared: str | Path | None = None,
    candidates: dict | None = None,
) -> dict:
    """
    Tables 2–5 under each setting of the unknowns, one at a time, then combined.

    Parameters
    ----------
    sensors, positions
        As :func:`~skinrender.studies.paper.reproduce.reproduce` (a coarser
        ``positions`` gives a quick sweep).
    base
        The setting the unknowns are changed around.
    combine
        How many unknowns to combine (the most telling: the largest gain in
        exact, then within-step matches, over ``base``); 0 for none.
    values_per_unknown
        How many of the best values of each combined unknown are combined;
        each combined unknown also keeps its ``base`` value, so that the
        pairs and the triple of the best values are tried (with 1 and three
        unknowns: four settings).
    candidates
        Unknown → values to try instead of :func:`sweep_candidates` (tests).

    Returns
    -------
    dict
        ``sweep``: one row per setting ``{setting, unknown, values, exact,
        within_step, total, matches_by_table, temperatures, seconds,
        tables}``; ``combined`` (the unknowns combined), ``notes``,
        ``positions``, ``sensors``, ``volumes_computed`` (banks whose
        volumes were computed), ``elapsed_s``.
    """

    start = time.perf_counter()
    chosen = check_sensors(sensors)
    workers = check_workers(workers)
    _check_combine(combine, values_per_unknown)
    where = check_positions(positions, resolve_setting(base).grid)  # the default's grid; a candidate's may skip
    cache = VolumeCache()
    rows: list[dict] = []
    done: dict[Setting, dict] = {}
    with tempfile.TemporaryDirectory() as scratch:
        if candidates is None:
            candidates, notes, names = sweep_candidates(scratch, shared)
        else:
            notes, names = [], {}
        notes = unmatched_sensors(chosen) + notes

        skipped: set[Setting] = set()

        def run(setting: Setting, unknown: str) -> dict | None:
            if setting in done or setting in skipped:
                return done.get(setting)
            resolved = resolve_setting(setting)
            if where.min() < resolved.grid.start or where.max() > resolved.grid.end:  # a candidate grid, not given
                notes.append(f"{setting.label(base, names)}: skipped, its integration grid {resolved.grid} does not "
                             f"hold the peaks {where.min():g}–{where.max():g} nm")
                skipped.add(setting)
                return None
            began = time.perf_counter()
            out = setting_tables(resolved, chosen, where, cache, workers, dask, progress, progress)
            values = {k: names.get(v, v) if isinstance(v, str) else v for k, v in setting.unknowns().items()}
            row = {"setting": setting.label(base, names), "unknown": unknown, "values": values,
                   "exact": out["matches"]["exact"], "within_step": out["matches"]["within_step"],
                   "total": out["matches"]["total"], "matches_by_table": out["matches"]["by_table"],
                   "temperatures": out["matches"]["temperatures"], "seconds": time.perf_counter() - began,
                   "tables": {f"{k:g}": v for k, v in out["tables"].items()}}
            rows.append(row)
            done[setting] = row
            return row

        default = run(base, "default")
        for unknown in UNKNOWNS:
            for value in candidates.get(unknown, []):
                run(with_unknown(base, unknown, value), unknown)
        ranked = _rank(rows, default)
        combined = [u for u in ranked if any(r["unknown"] == u for r in rows)][:combine]
        if len(combined) >= 2:
            best = {u: [_value(base, u)] + _best_values(done, u, base, values_per_unknown) for u in combined}
            for values in itertools.product(*(best[u] for u in combined)):
                setting = base
                for unknown, value in zip(combined, values):
                    setting = with_unknown(setting, unknown, value)
                changed = [u for u, v in zip(combined, values) if v != _value(base, u)]
                if len(changed) >= 2:
                    run(setting, "+".join(changed))
    return {"sweep": rows, "combined": combined, "notes": notes, "positions": str(positions),
            "sensors": chosen, "volumes_computed": cache.computed, "elapsed_s": time.perf_counter() - start}


def _check_combine(combine, values_per_unknown) -> None:
    """``--sweep-combine`` in [0, the number of unknowns] (more would be cut silently), ``--sweep-values`` ≥ 1."""
    for flag, value, low, high in (("--sweep-combine", combine, 0, len(UNKNOWNS)),
                                   ("--sweep-values", values_per_unknown, 1, None)):
        if isinstance(value, bool) or not isinstance(value, int) or value < low or (high is not None and value > high):
            bounds = f"≥ {low}" if high is None else f"in [{low}, {high}] (the unknowns: {', '.join(UNKNOWNS)})"
            raise SkinrenderError(f"{flag} must be an integer {bounds}, got {value!r}", flag=flag)


def _rank(rows: list[dict], default: dict) -> list[str]:
    """Unknowns by the best gain over the default (exact, then within one step), then by their spread."""
    def key(unknown: str):
        mine = [r for r in rows if r["unknown"] == unknown] + [default]
        best = max(_score(r) for r in mine)
        spread = max(r["exact"] for r in mine) - min(r["exact"] for r in mine)
        return (best[0] - default["exact"], best[1] - default["within_step"], spread)
    return sorted(UNKNOWNS, key=key, reverse=True)


def _best_values(done: dict[Setting, dict], unknown: str, base: Setting, count: int) -> list:
    """The ``count`` values of ``unknown`` other than ``base``'s with the most matches (ties: the order tried)."""
    mine = [(row, setting) for setting, row in done.items() if row["unknown"] == unknown]
    out = []
    for _, setting in sorted(mine, key=lambda item: _score(item[0]), reverse=True):
        value = _value(setting, unknown)
        if value not in out and value != _value(base, unknown):
            out.append(value)
    return out[:max(1, count)]


def write_sweep(result: dict, directory: str | Path) -> list[Path]:
    """``sweep.csv`` (one row per setting, per-table counts) and ``sweep.md`` in ``directory``."""
    directory = Path(directory)
    keys = [key for _, key in TABLES]
    path_csv = directory / "sweep.csv"
    handle = io.StringIO(newline="")
    writer = csv.writer(handle, lineterminator="\n")
    writer.writerow(["setting", "unknown", "exact", "within_step", "total"]
                    + [f"{k}_{n}" for k in keys for n in ("exact", "within_step")]
                    + ["temperatures_shared", "temperatures_total", "seconds"])
    for row in result["sweep"]:
        writer.writerow([row["setting"], row["unknown"], row["exact"], row["within_step"], row["total"]]
                        + [row["matches_by_table"][k][n] for k in keys for n in ("exact", "within_step")]
                        + [row["temperatures"]["shared"], row["temperatures"]["total"], f"{row['seconds']:.2f}"])
    write_output(path_csv, handle.getvalue())
    best = max((r["exact"], r["within_step"]) for r in result["sweep"])
    intro = (f"Sensors {', '.join(f'{s:g}' for s in result['sensors'])}, peak positions {result['positions']} nm. "
             "A cell matches exactly when one of our (tied) triplets equals one of the paper's; within one step "
             "when every peak is within 10 nm. Tables 2–3 temperatures are not part of the match (last column: "
             "cells sharing a calibration temperature). Best setting in bold.")
    lines = ["# Tables 2–5 under the paper's unknowns", "", intro, "",
             "| setting | changed | exact | within 10 nm | " + " | ".join(k.replace("table", "T") for k in keys)
             + " | temperatures | s |",
             "|---|---|---|---|" + "---|" * len(keys) + "---|---|"]
    for row in result["sweep"]:
        name = f"**{row['setting']}**" if (row["exact"], row["within_step"]) == best else row["setting"]
        cells = " | ".join(f"{row['matches_by_table'][k]['exact']}/{row['matches_by_table'][k]['within_step']}"
                           for k in keys)
        lines.append(f"| {name} | {row['unknown']} | {row['exact']}/{row['total']} | {row['within_step']} | {cells} | "
                     f"{row['temperatures']['shared']}/{row['temperatures']['total']} | {row['seconds']:.1f} |")
    lines += ["", f"Per table: exact/within 10 nm of its {len(result['sensors'])} cells (one per sensor).", ""]
    lines += [f"- combined: {', '.join(result['combined']) or 'none'}"] + [f"- {note}" for note in result["notes"]]
    path_md = directory / "sweep.md"
    write_output(path_md, "\n".join(lines) + "\n")
    return [path_csv, path_md]


def reproduce_sweep(directory: str | Path, sensors: ArrayLike | str = SENSORS_PAPER,
                    positions: str | ArrayLike = "400:700:10", base: Setting = SETTING_DEFAULT,
                    positions_flag: str = "--positions", **options) -> dict:
    """
    :func:`sweep` into ``directory`` (``sweep.csv``, ``sweep.md`` and the JSON
    as ``reproduce.json``), every argument and the folder checked first, the
    folder moved into place only when complete. ``positions_flag`` names the
    positions in errors (``--sweep-positions`` where the CLI took them from
    there). ``options`` go to :func:`sweep`.
    """
    start = time.perf_counter()
    target = check_output(directory)
    where = check_positions(positions, resolve_setting(base).grid, positions_flag)
    check_search_work(len(check_sensors(sensors)), where, positions_flag, options.pop("max_minutes", None),
                      options.get("workers"), "each setting's ")
    check_workers(options.get("workers"))
    _check_combine(options.get("combine", 3), options.get("values_per_unknown", 1))
    with output_folder(target) as folder:
        result = sweep(sensors, positions, base, **options)
        artifacts = write_sweep(result, folder)
        result["artifacts"] = [str(target / p.name) for p in artifacts] + [str(target / MANIFEST)]
        result["elapsed_s"] = time.perf_counter() - start
        write_output(folder / MANIFEST, json.dumps(result, indent=2, allow_nan=False) + "\n")
    return result
