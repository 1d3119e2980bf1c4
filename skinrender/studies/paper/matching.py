"""
Matching our tables with the paper's
====================================

How many cells of Tables 2–5 (sensors 1, 3, …, 15: 6 tables × 8 sensors = 48
cells) our search reproduces, read from the cells' text as the paper prints
them (:data:`skinrender.studies.paper.tables.PAPER_TABLES`) and as
:func:`skinrender.studies.paper.tables.table_rows` writes ours.

-   :data:`STEP_MATCH_NM`: the tolerance of a "within one step" match (the
    paper's 10 nm position grid).
-   :func:`cell_triplets`, :func:`cell_temperatures`: parse one cell.
-   :func:`cell_match`: does one of our cells match the paper's?
-   :func:`count_matches`: the counts per table and in total.

A cell matches **exactly** when our triplet, or one of our tied triplets,
equals the paper's triplet, or one of them where the paper lists two. It
matches **within one step** when one of our triplets has every peak within
:data:`STEP_MATCH_NM` of one of the paper's (exact matches included). The
calibration temperatures of Tables 2 and 3 are not part of the triplet match:
they are counted apart (``temperatures``: a cell shares a temperature when one
of our tied rows has a temperature the paper lists for that cell).

Units: peaks in nm, temperatures in K.

References
----------
-   :cite:`Martinkauppi2006` : Tables 2–5 (docs/references.md).
"""

from __future__ import annotations

import re

from ...constants import TEMPERATURES_PAPER
from .tables import PAPER_TABLES, TABLES

__all__ = ["STEP_MATCH_NM", "TABLES_WITH_TEMPERATURE", "cell_triplets", "cell_temperatures", "cell_match",
           "count_matches", "unmatched_sensors"]

STEP_MATCH_NM = 10.0
"""A peak within this distance (nm) of the paper's counts as "within one step": the paper's position grid."""

TABLES_WITH_TEMPERATURE = ("table2_skin", "table2_munsell", "table3_ratio")
"""The one-calibration tables, whose cells also name calibration temperatures (K)."""

_NUMBER = r"\d+(?:\.\d+)?"


def cell_triplets(text: str) -> list[tuple[float, float, float]]:
    """
    The triplets (nm) of one cell: ``"p1 p2 p3, T K; q1 q2 q3, T K"`` gives two.

    Examples
    --------
    >>> cell_triplets("400 550 700, 3300 K; 400 560 700, 3300 K")
    [(400.0, 550.0, 700.0), (400.0, 560.0, 700.0)]
    >>> cell_triplets("")
    []
    """
    out = []
    for part in str(text).split(";"):
        found = re.match(rf"\s*({_NUMBER})\s+({_NUMBER})\s+({_NUMBER})\b", part)
        if found:
            out.append(tuple(float(v) for v in found.groups()))
    return out


def cell_temperatures(text: str, temperatures=TEMPERATURES_PAPER) -> set[float]:
    """
    The calibration temperatures (K) a cell names: single values (``3300 K``)
    and ranges over the illuminant set (``2000–7500 K (9 temperatures)`` = the
    members of ``temperatures`` from 2000 to 7500 K).

    Examples
    --------
    >>> sorted(cell_temperatures("510 520 530, 2800 K, 3300 K"))
    [2800.0, 3300.0]
    >>> len(cell_temperatures("520 530 540, 2000–7500 K (9 temperatures)"))
    9
    """
    found: set[float] = set()
    for part in str(text).split(";"):
        rest = re.sub(rf"^\s*{_NUMBER}\s+{_NUMBER}\s+{_NUMBER}\b", "", part)
        rest = re.sub(r"\(.*?\)", "", rest)
        for low, high in re.findall(rf"({_NUMBER})\s*[–-]\s*({_NUMBER})\s*K", rest):
            found |= {float(t) for t in temperatures if float(low) <= t <= float(high)}
        rest = re.sub(rf"{_NUMBER}\s*[–-]\s*{_NUMBER}\s*K", "", rest)
        found |= {float(v) for v in re.findall(rf"({_NUMBER})\s*K", rest)}
    return found


def cell_match(ours: str, paper: str, step: float = STEP_MATCH_NM) -> dict:
    """
    Whether our cell matches the paper's.

    Returns
    -------
    dict
        ``exact`` and ``within_step`` (bools, see the module notes) and
        ``temperature``: whether the two share a calibration temperature
        (``None`` where the paper's cell names none).

    Examples
    --------
    >>> cell_match("400 550 700, 3300 K", "400 550 700, 3300 K; 400 560 700, 3300 K")
    {'exact': True, 'within_step': True, 'temperature': True}
    >>> cell_match("410 540 700", "400 550 700")
    {'exact': False, 'within_step': True, 'temperature': None}
    """
    mine, theirs = cell_triplets(ours), cell_triplets(paper)
    exact = any(a == b for a in mine for b in theirs)
    within = any(all(abs(x - y) <= step + 1e-9 for x, y in zip(a, b)) for a in mine for b in theirs)
    paper_t = cell_temperatures(paper)
    return {"exact": exact, "within_step": within,
            "temperature": bool(cell_temperatures(ours) & paper_t) if paper_t else None}


def count_matches(rows: dict, paper: dict = PAPER_TABLES, step: float = STEP_MATCH_NM) -> dict:
    """
    How many cells of Tables 2–5 match the paper's.

    Parameters
    ----------
    rows
        Our cells per sensor: ``{sensor: {table key: text}}`` (the ``tables``
        of :func:`skinrender.studies.paper.reproduce.reproduce`, keys numbers or
        their text).
    paper
        The paper's cells, ``{table key: {sensor: text}}``.
    step
        Tolerance of ``within_step``, nm.

    Returns
    -------
    dict
        ``exact``, ``within_step``, ``total`` (cells the paper prints for our
        sensors), ``by_table`` (the same three per table key) and
        ``temperatures`` (``shared``, ``total``: Tables 2 and 3 cells sharing a
        calibration temperature with the paper's).

    Examples
    --------
    >>> count_matches({1: {"table4_skin": "470 610 700", "table5_ratio": "550 570 590"}})["by_table"]["table5_ratio"]
    {'exact': 0, 'within_step': 1, 'total': 1}
    """
    by_table = {key: {"exact": 0, "within_step": 0, "total": 0} for _, key in TABLES}
    shared = counted = 0
    for sensor, cells in rows.items():
        number = int(float(sensor))
        for key, counts in by_table.items():
            if key not in cells or number not in paper.get(key, {}):
                continue
            match = cell_match(cells[key], paper[key][number], step)
            counts["total"] += 1
            counts["exact"] += int(match["exact"])
            counts["within_step"] += int(match["within_step"])
            if key in TABLES_WITH_TEMPERATURE and match["temperature"] is not None:
                counted += 1
                shared += int(match["temperature"])
    total = {name: sum(c[name] for c in by_table.values()) for name in ("exact", "within_step", "total")}
    return {**total, "by_table": by_table, "temperatures": {"shared": shared, "total": counted}}


def unmatched_sensors(sensors, paper: dict = PAPER_TABLES) -> list[str]:
    """
    A note for each sensor the paper's Tables 2–5 have no row for: its cells count in no match (``total``
    leaves them out), which a reader of ``0/0`` would otherwise have to guess.

    >>> unmatched_sensors([9, 17])
    ["sensor 17: the paper's Tables 2–5 have no row for it, so its cells are in no match count"]
    """
    listed = {float(s) for cells in paper.values() for s in cells}
    return [f"sensor {float(s):g}: the paper's Tables 2–5 have no row for it, so its cells are in no match count"
            for s in sensors if float(s) not in listed]
