"""Tests for :mod:`skinrender.studies.paper.tables`: Table 1 reports the sample count its renders used and its verdict."""

from __future__ import annotations

import pytest

from skinrender.studies.paper.tables import PAPER_TABLES, table1

pytest.importorskip("mitsuba")


def test_table1_reports_the_spp_used():
    """multijitter rounds 7 samples per pixel up to 8: the table says 8, beside the 7 asked for."""
    result = table1(spp=7)
    assert result["spp"] == 8 and result["spp_requested"] == 7


def test_paper_tables_cover_the_eight_sensors():
    assert all(sorted(rows) == [1, 3, 5, 7, 9, 11, 13, 15] for rows in PAPER_TABLES.values())


def test_table1_verdict_eq4_within_its_tolerance_and_eq1_differs():
    """Eq. 4 agrees with the render in NCC (shown within 0.01 at 64 spp; the bound is what would pass); Eq. 1 with
    WP and no white balance is detected as different."""
    result = table1(spp=64, tolerance=0.01)
    assert result["verdict"]["verdict"] == "pass" and result["passed"] and result["bound"] < 0.01
    assert result["difference_eq1"]["verdict"] == "fail"
    tight = table1(spp=64, tolerance=result["bound"] / 2)
    assert tight["verdict"]["verdict"] != "pass"
