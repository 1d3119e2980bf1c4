"""Tests for :mod:`skinrender.studies.paper.observations`: the paper's Stage 1 and Stage 2 statements per camera."""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.spectra import WavelengthGrid
from skinrender.studies.paper.observations import (PAPER_STAGE1_TEXT, paper_cameras, sony_dxc930_csv, stage1_text,
                                             stage2_by_camera)

GRID = WavelengthGrid(400, 700, 5)


class TestStage1Text:
    def test_paper_values(self):
        assert PAPER_STAGE1_TEXT["inverse_step_high"]["ncc_r"] == 0.0116
        low, high = PAPER_STAGE1_TEXT["inverse_step_low"]["between_K"]
        assert low == 2000 and 1 / low - 1 / high == pytest.approx(1 / 9000 - 1 / 10000)
        low_range = PAPER_STAGE1_TEXT["range_low"]
        assert np.hypot(low_range["ncc_r"], low_range["ncc_b"]) == pytest.approx(low_range["euclidean"], abs=1e-3)

    def test_recomputed_for_a_camera(self):
        out = stage1_text([("Kodak", "Kodak DCS-200")], GRID)
        row = out["cameras"][0]
        assert row["camera"] == "Kodak" and len(row["temperatures"]) == 10
        for name in PAPER_STAGE1_TEXT:
            values = row[name]
            assert values["euclidean"] == pytest.approx(np.hypot(values["ncc_r"], values["ncc_b"]))
        # Chromaticity changes fastest at low temperature, for any camera.
        assert row["range_low"]["euclidean"] > row["inverse_step_high"]["euclidean"]
        assert 0 <= row["shared_with_paper"] <= 10


class TestStage2ByCamera:
    def test_counts(self):
        rows = stage2_by_camera([("Kodak", "Kodak DCS-200")], "macbeth", [2000.0, 3300.0, 6500.0], GRID)
        row = rows[0]
        assert row["total"] == 9 and 0 <= row["as_paper"] <= 9
        assert row["white"]["as_paper"] == row["white"]["on_calibration"]
        assert row["560nm"]["as_paper"] == 3 - row["560nm"]["on_calibration"]


class TestSharedData:
    def test_absent_reference_data(self, tmp_path):
        assert sony_dxc930_csv(tmp_path, shared=tmp_path / "none") is None
        cameras = paper_cameras(tmp_path, shared=tmp_path / "none")
        assert "Kodak DCS-200" in [label for label, _ in cameras]
        assert not any(label.startswith("Sony") for label, _ in cameras)

    def test_dxc930_floors_removed(self, shared_data, tmp_path):
        path = sony_dxc930_csv(tmp_path, shared_data)
        data = np.genfromtxt(path, delimiter=",", names=True)
        assert data["R"].min() == 0 and data["B"].min() >= 0 and data["wavelength_nm"][0] == 380
