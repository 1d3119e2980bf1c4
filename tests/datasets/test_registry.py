"""Tests for :mod:`skinrender.datasets`: counts, ranges, provenance and refusal of bad data."""

from __future__ import annotations

import numpy as np
import pytest

import skinrender.datasets as datasets
from skinrender.datasets import registry
from skinrender.datasets.registry import ROOT_RESOURCES
from skinrender.errors import SkinrenderError
from skinrender.spectra import GRID_DEFAULT

COUNTS = {"macbeth": 24, "munsell": 1269, "munsell-nickerson": 462, "skin": 30, "vrhel": 170, "vrhel-nonskin": 140}


class TestReflectances:
    @pytest.mark.parametrize("name, count", COUNTS.items())
    def test_counts_and_range(self, name, count):
        spectra = datasets.reflectances(name)
        assert spectra.count == count
        values = spectra.on(GRID_DEFAULT)  # every bundled set covers the paper's 400–700 nm
        assert values.shape == (count, GRID_DEFAULT.size)
        assert np.all(values >= 0) and np.all(values <= 1)

    def test_skin_is_skin(self):
        names = datasets.reflectances("skin").names
        assert all("skin" in n.lower() and "peach" not in n.lower() for n in names)

    def test_every_entry_states_source_and_licence(self):
        for row in datasets.list_reflectances() + datasets.list_cameras():
            assert row["source"] and row["licence"]
            assert len(row["wavelengths"]) == 3

    def test_unknown_lists_known(self):
        with pytest.raises(SkinrenderError, match=r"unknown reflectance set 'munsel'; known: 'macbeth', 'munsell'"):
            datasets.reflectances("munsel")

    def test_user_csv_refused_then_extrapolated(self, tmp_path):
        path = tmp_path / "short.csv"
        path.write_text("nm,a\n420,0.5\n680,0.5\n")
        with pytest.raises(SkinrenderError, match=r"short.csv: measured over 420–680 nm, which does not cover"):
            datasets.reflectances(str(path)).on(GRID_DEFAULT)
        assert datasets.reflectances(str(path), extrapolation="constant").on(GRID_DEFAULT)[0, 0] == 0.5


class TestCameras:
    def test_listed(self):
        names = [row["name"] for row in datasets.list_cameras()]
        assert {"Nikon 5100 (NPL)", "Sigma SDMerill (NPL)", "Canon EOS 5D Mark II", "Kodak DCS-200"} <= set(names)

    def test_zero_outside_measured_range(self):
        """The Sigma data stop at 680 nm; bundled cameras declare zero outside the measured range."""
        sigma = datasets.camera_sensitivities("Sigma SDMerill (NPL)")
        assert sigma.extrapolation == "zero"
        assert np.all(sigma.on(GRID_DEFAULT)[:, -20:] == 0)


class TestBundledFiles:
    def test_checksum_catches_edit(self, tmp_path, monkeypatch):
        original = (ROOT_RESOURCES / "camera_kodak_dcs200.csv").read_text()
        (tmp_path / "camera_kodak_dcs200.csv").write_text(original.replace("2.33", "2.34", 1))
        monkeypatch.setattr(registry, "ROOT_RESOURCES", tmp_path)
        with pytest.raises(SkinrenderError, match="was modified"):
            registry.read_bundled_csv("camera_kodak_dcs200.csv", "0" * 64)

    def test_licence_file_present(self):
        assert "Permission is hereby granted" in (ROOT_RESOURCES / "LICENCE-psychtoolbox.txt").read_text()

    def test_rebuild_script_matches(self, tmp_path):
        """tools/build_psychtoolbox_data.py rebuilds the bundled CSVs byte for byte (needs Debian's
        psychtoolbox-3-common)."""
        import importlib.util
        from pathlib import Path

        script = Path(__file__).resolve().parents[2] / "tools" / "build_psychtoolbox_data.py"
        spec = importlib.util.spec_from_file_location("build", script)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        if not module.ROOT_PSYCHTOOLBOX.is_dir():
            pytest.skip("psychtoolbox-3-common is not installed")
        module.ROOT_RESOURCES = tmp_path
        module.main()
        for name in ("vrhel_surfaces.csv", "nickerson_munsell.csv", "camera_kodak_dcs200.csv"):
            assert (tmp_path / name).read_bytes() == (ROOT_RESOURCES / name).read_bytes()



def test_a_set_name_wins_over_a_file_of_that_name_here(tmp_path, monkeypatch):
    """``macbeth`` is the bundled set even where the working folder holds a file named ``macbeth``."""
    from skinrender.datasets import looks_like_path, reflectances

    monkeypatch.chdir(tmp_path)
    (tmp_path / "macbeth").write_text("not a CSV")
    (tmp_path / "mine").write_text("wavelength,a\n400,0.5\n700,0.5\n")
    assert reflectances("macbeth").count == 24
    assert not looks_like_path("macbeth") and looks_like_path("mine") and looks_like_path("other.csv")
