"""
Tests for :mod:`skinrender.rendering.spectral_files`: a spectral EXR round-trips through ``read_spectral`` (bands,
labels, header, and what a camera sees through it), and anything else is refused in one line.
"""

from __future__ import annotations

import numpy as np
import pytest

import skinrender as sr
from skinrender.errors import SkinrenderError
from skinrender.rendering.exr import read_exr_attributes, write_exr

pytest.importorskip("mitsuba")


@pytest.mark.parametrize("scene, options", [("macbeth", {}), ("face", {"size": 8, "physics": "sheen+noise"})])
def test_the_exr_round_trips(tmp_path, scene, options):
    image = sr.render(scene, prevailing=2856, spectral=True, spp=2, seed=4, bands="400:700:25", **options)
    path = image.save(tmp_path / "bands.exr")["exr"]
    header = read_exr_attributes(path)
    assert header["basis"] == "hat" and header["bands_nm"] == "400:700:25" and header["prevailing_K"] == "2856.0"
    assert header["spp"] == str(image.spp) and header["seed"] == "4" and header["variant"] == image.variant
    back = sr.read_spectral(path)
    assert np.array_equal(back.image, image.image) and back.scale == image.scale and back.bands == image.bands
    assert back.physics == image.physics and back.kind == image.kind
    a, b = image.through("Nikon 5100 (NPL)", 5900), back.through("Nikon 5100 (NPL)", 5900)
    assert np.array_equal(a.image, b.image)
    if scene == "face":
        assert np.array_equal(back.labels, image.labels) and back.label_names == image.label_names
        assert back.skin == image.skin and back.request.sensor == image.request.sensor is not None


def test_other_files_are_refused(tmp_path):
    plain = tmp_path / "plain.exr"
    write_exr(plain, np.zeros((2, 2, 1), dtype=np.float32), ("Y",))
    with pytest.raises(SkinrenderError, match="not a skinrender spectral EXR"):
        sr.read_spectral(plain)
    text = tmp_path / "text.exr"
    text.write_text("not an EXR")
    with pytest.raises(SkinrenderError, match="text.exr"):
        sr.read_spectral(text)
    with pytest.raises(SkinrenderError):
        sr.read_spectral(tmp_path / "missing.exr")
