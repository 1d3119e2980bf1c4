"""Tests for :mod:`skinrender.spectral_csv`: spectral CSV files are read or refused with the line named."""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.spectral_csv import read_spectra_csv


class TestReadSpectraCsv:
    def write(self, tmp_path, text):
        path = tmp_path / "data.csv"
        path.write_text(text)
        return path

    def test_reads(self, tmp_path):
        table = read_spectra_csv(self.write(tmp_path, "nm,a,b\n400,0.1,0.2\n500,0.3,0.4\n"))
        assert table.names == ("a", "b")
        np.testing.assert_array_equal(table.values, [[0.1, 0.3], [0.2, 0.4]])

    @pytest.mark.parametrize(
        "text, message",
        [
            ("nm,a\n400,0.1\n500,nan\n", r"data.csv, line 3: reflectance in column 2 is not a finite number"),
            ("nm,a\n400,0.1\n500,\n", r"line 3: reflectance in column 2 is not a finite number"),
            ("nm,a\n400,0.1\n500,-0.2\n", r"line 3: negative reflectance -0.2 in column 2"),
            ("nm,a\n400,0.1\n500,0.2\n450,0.2\n", r"line 4: wavelength 450 nm does not increase"),
            ("nm,a\n400,0.1\n500,abc\n", r"line 3: 'abc' is not a number"),
            ("nm,a\n400,0.1\n500,0.2,0.3\n", r"line 3: 3 columns, expected 2"),
            ("nm,a\n400,10\n500,20\n", r"not percent"),
        ],
    )
    def test_refused_with_line(self, tmp_path, text, message):
        with pytest.raises(SkinrenderError, match=message):
            read_spectra_csv(self.write(tmp_path, text))

    def test_missing(self, tmp_path):
        with pytest.raises(SkinrenderError, match="no such file"):
            read_spectra_csv(tmp_path / "nope.csv")

    def test_expected_columns(self, tmp_path):
        with pytest.raises(SkinrenderError, match="expected 3"):
            read_spectra_csv(self.write(tmp_path, "nm,R,G\n400,1,1\n"), kind="sensitivity", expected_columns=3)
