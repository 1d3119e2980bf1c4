"""
Tests for :mod:`skinrender.rendering.bands`: the hat basis represents a camera on the band grid exactly, sums to
1 (uniform wavelength sampling), and refuses bands beyond the scene's range, cameras beyond the bands, and too
many bands or pixels, each with the range or the estimate named.
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.model.camera import camera
from skinrender.rendering.bands import (BANDS_DEFAULT, BANDS_MAX, SPECTRAL_BYTES_MAX, band_integrals, band_names,
                                        check_bands, estimate, film_channels, hat_matrix, hats, parse_bands,
                                        projection)
from skinrender.spectra import GRID_DEFAULT, WavelengthGrid

FINE = WavelengthGrid(400, 700, 0.1).wavelengths


def test_the_hats_sum_to_one_everywhere_on_the_bands():
    """A partition of unity: specfilm, which samples wavelengths by the sum of its channels, samples uniformly."""
    total = hat_matrix(BANDS_DEFAULT, FINE).sum(axis=0)
    assert np.allclose(total, 1.0, atol=1e-12)
    assert hat_matrix(BANDS_DEFAULT, np.array([399.0, 701.0])).sum() == 0.0


def test_a_camera_on_the_band_grid_is_represented_exactly():
    """A curve linearly interpolated from the band samples is Σ_j s(λ_j) h_j(λ), so its integral against any
    spectrum is its samples times the band integrals (here a 10 nm CSV camera on 5 nm bands, to 1e-12)."""
    cam = camera("Nikon 5100 (NPL)")
    spectrum = 1.0 + 0.5 * np.sin(FINE / 17.0)
    curves = np.array([np.interp(FINE, BANDS_DEFAULT.wavelengths, row) for row in cam.sensitivities(BANDS_DEFAULT)])
    weights = np.full(FINE.size, 0.1)
    weights[[0, -1]] = 0.05
    direct = (spectrum * weights) @ curves.T
    through = band_integrals(FINE, spectrum, BANDS_DEFAULT) @ projection(cam, BANDS_DEFAULT, GRID_DEFAULT).T
    assert np.allclose(through, direct, rtol=1e-12)


def test_names_and_film_channels_follow_the_bands():
    bands = WavelengthGrid(400, 420, 10)
    assert band_names(bands) == ("400nm", "410nm", "420nm")
    film = film_channels(bands)
    assert list(film) == ["400nm", "410nm", "420nm"]
    assert film["400nm"] == {"type": "regular", "wavelength_min": 400.0, "wavelength_max": 410.0, "values": "1,0"}
    assert [len(w) for w, _ in hats(bands)] == [2, 3, 2]


def test_bad_band_grids_are_refused_naming_the_bands():
    for text in ("700:400:5", "400:700:7", "abc", f"400:700:{300 / (BANDS_MAX + 5):.6f}"):
        with pytest.raises(SkinrenderError, match="bands") as error:
            parse_bands(text)
        assert error.value.role == "bands"


def test_bands_beyond_the_scene_are_refused_naming_both_ranges():
    with pytest.raises(SkinrenderError, match="380–700 nm reach beyond 400–700 nm"):
        check_bands(WavelengthGrid(380, 700, 5), GRID_DEFAULT)


def test_a_camera_sensitive_outside_the_bands_is_refused_naming_where():
    """Bands of 450–650 nm would drop light gbell 9's tails see on 400–700 nm: refused, the range named."""
    with pytest.raises(SkinrenderError, match=r"sensitive at 400–700 nm, outside the bands 450–650 nm"):
        projection(camera("gbell:9@450,540,610"), WavelengthGrid(450, 650, 5), GRID_DEFAULT)


def test_a_camera_whose_data_do_not_cover_the_bands_is_refused(tmp_path):
    path = tmp_path / "narrow.csv"
    path.write_text("nm,R,G,B\n450,1,1,1\n650,1,1,1\n")
    with pytest.raises(SkinrenderError, match="on the bands"):
        projection(camera(str(path)), BANDS_DEFAULT, WavelengthGrid(450, 650, 1))


def test_a_render_too_large_for_memory_is_refused_with_the_estimate():
    pixels = int(SPECTRAL_BYTES_MAX / (61 * 24)) + 1000
    with pytest.raises(SkinrenderError, match=r"GiB \(estimated"):
        estimate(BANDS_DEFAULT, pixels, 1.0)
    memory, seconds = estimate(BANDS_DEFAULT, 100, 1.0)
    assert memory == 100 * 61 * 24 and seconds > 1.0
