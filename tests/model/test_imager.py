"""
Tests for :mod:`skinrender.model.imager`: the presets, the validation of every
:class:`Imager` field and TOML file, and the shared input checks.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.model.imager import (
    ROOT_RESOURCES_IMAGERS,
    Imager,
    checked_array,
    checked_grid,
    imager,
    is_integer,
    list_imagers,
)
from skinrender.spectra import WavelengthGrid


def make_imager(**changes) -> Imager:
    """A test imager whose saturated code K·μ_sat + b = 0.2 · 20000 + 10 = 4010 DN is an exact integer."""
    values = {
        "name": "test", "source": "tests", "pixel_um": 5.0, "f_number": 2.8, "transmittance": 0.9,
        "qe_peak": 0.5, "full_well_e": 20000.0, "read_noise_e": 5.0, "dark_current_e_per_s": 0.0,
        "gain_dn_per_e": 0.2, "bits": 12, "black_level_dn": 10.0,
    }
    return Imager(**(values | changes))


class TestPresets:
    def test01_list_and_load(self):
        rows = list_imagers()
        assert {row["name"] for row in rows} >= {"sony-imx174", "sony-icx418"}
        for row in rows:
            assert set(row) == {"name", "source", "pixel_um", "full_well_e", "read_noise_e", "gain_dn_per_e",
                                "bits"}
            item = imager(row["name"].upper())
            assert item.source.strip() and item.name == row["name"]
            assert item.gain_dn_per_e * item.full_well_e + item.black_level_dn <= item.max_dn
        assert imager("sony-imx174").full_well_e == 32691.0
        assert imager("Sony-ICX418").bits == 8

    def test02_found_beside_the_package_and_by_path(self):
        assert ROOT_RESOURCES_IMAGERS.is_dir()
        assert ROOT_RESOURCES_IMAGERS.parent.parent.name == "datasets"
        path = ROOT_RESOURCES_IMAGERS / "sony-imx174.toml"
        assert imager(path) == imager(str(path)) == imager("sony-imx174")
        assert imager(imager("sony-imx174")) is imager("sony-imx174")

    def test03_black_level_above_the_dark_noise(self):
        """Every preset's black level lies several read-noise σ above 0 DN, so its dark frames are unclipped."""
        for row in list_imagers():
            item = imager(row["name"])
            assert item.black_level_dn >= 5 * item.gain_dn_per_e * item.read_noise_e


GOOD_TOML = """name = "mine"
source = "a test"
pixel_um = 4.0
f_number = 2.0
transmittance = 0.9
qe_peak = 0.6
full_well_e = 10000.0
read_noise_e = 3.0
dark_current_e_per_s = 1.0
gain_dn_per_e = 0.4
bits = 12
black_level_dn = 8.0
"""


class TestBadInput:
    @pytest.mark.parametrize(
        ("field", "value"),
        [("name", ""), ("source", 3), ("pixel_um", 0.0), ("pixel_um", "5"), ("pixel_um", math.nan),
         ("f_number", 0.0), ("f_number", -2.8), ("transmittance", 0.0), ("transmittance", 1.2),
         ("qe_peak", 0.0), ("qe_peak", 1.01), ("full_well_e", 0.0), ("full_well_e", -1.0),
         ("full_well_e", math.inf), ("read_noise_e", -0.1), ("dark_current_e_per_s", -1.0),
         ("gain_dn_per_e", 0.0), ("bits", 12.5), ("bits", 0), ("bits", 33), ("bits", True),
         ("bits", "12"), ("black_level_dn", -1.0), ("black_level_dn", 4096.0), ("pixel_um", True)],
    )
    def test01_each_imager_field(self, field, value):
        with pytest.raises(SkinrenderError, match=field):
            make_imager(**{field: value})

    @pytest.mark.parametrize(
        ("edit", "field"),
        [(lambda t: t + "colour = 1\n", "colour"),
         (lambda t: t.replace("read_noise_e = 3.0\n", ""), "read_noise_e"),
         (lambda t: t.replace("pixel_um = 4.0", 'pixel_um = "four"'), "pixel_um"),
         (lambda t: t.replace("bits = 12", "bits = 12.5"), "bits"),
         (lambda t: t.replace("read_noise_e = 3.0", "read_noise_e = -3.0"), "read_noise_e"),
         (lambda t: t.replace("qe_peak = 0.6", "qe_peak = "), "TOML")],
    )
    def test02_bad_toml_files(self, tmp_path: Path, edit, field):
        path = tmp_path / "bad_imager.toml"
        path.write_text(edit(GOOD_TOML), encoding="utf-8")
        with pytest.raises(SkinrenderError) as caught:
            imager(path)
        assert "bad_imager.toml" in str(caught.value) and field in str(caught.value)

    def test02b_a_binary_file_is_refused_as_not_text(self, tmp_path: Path):
        path = tmp_path / "binary.toml"
        path.write_bytes(b"\x00\xff\xfe" * 8)
        with pytest.raises(SkinrenderError, match="binary.toml: not a UTF-8 text file"):
            imager(path)

    def test03_good_toml_and_unknown_presets(self, tmp_path: Path):
        path = tmp_path / "mine.toml"
        path.write_text(GOOD_TOML, encoding="utf-8")
        assert imager(path).gain_dn_per_e == 0.4
        for spec in ("no-such-imager", tmp_path / "missing.toml"):
            with pytest.raises(SkinrenderError, match="sony-imx174"):
                imager(spec)
        with pytest.raises(SkinrenderError, match="imager"):
            imager(42)


class TestChecks:
    def test01_checked_array(self):
        grid = WavelengthGrid(400.0, 700.0, 10.0)
        np.testing.assert_array_equal(checked_array([[1, 2]], "x", "s"), [[1.0, 2.0]])
        assert checked_array(-1.0, "x", "DN", low=None) == -1.0
        assert checked_array(np.ones((2, grid.size)), "x", "nm", grid=grid).shape == (2, grid.size)
        for values, kwargs in [(-1.0, {}), (math.nan, {"low": None}), ("a", {}), (np.ones(3), {"grid": grid}),
                               (1.0, {"grid": grid})]:
            with pytest.raises(SkinrenderError, match="exposure_s"):
                checked_array(values, "exposure_s", "s", **kwargs)

    def test02_checked_grid_and_integers(self):
        assert checked_grid("400:700:10") == WavelengthGrid(400.0, 700.0, 10.0)
        grid = WavelengthGrid(400.0, 700.0, 5.0)
        assert checked_grid(grid) is grid
        with pytest.raises(SkinrenderError, match="grid"):
            checked_grid((400, 700, 10))
        assert is_integer(3) and is_integer(np.int64(3))
        assert not is_integer(True) and not is_integer(3.0)
