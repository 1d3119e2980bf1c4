"""
Tests for :mod:`skinrender.cli.bands_flags`: ``--bands`` goes with a spectral render only, several ``--camera``
are seen through the bands unless ``--direct``, each camera checked against them; refusals name the flag.
"""

from __future__ import annotations

import argparse

import pytest

from skinrender.errors import SkinrenderError
from skinrender.cli.bands_flags import bands_for, bands_of, cameras_of
from skinrender.rendering.bands import BANDS_DEFAULT


def namespace(**fields):
    return argparse.Namespace(**{"spectral": False, "bands": None, "direct": False, **fields})


def test_bands_of_a_spectral_render():
    assert bands_of(namespace()) is None
    assert bands_of(namespace(spectral=True)) == BANDS_DEFAULT
    assert bands_of(namespace(spectral=True, bands="400:700:10")).size == 31
    with pytest.raises(SkinrenderError, match="--bands goes with --spectral"):
        bands_of(namespace(bands="400:700:10"))
    with pytest.raises(SkinrenderError, match="--bands") as error:
        bands_of(namespace(spectral=True, bands="700:400:5"))
    assert error.value.flag == "--bands"


def test_several_cameras_are_seen_through_bands_unless_direct():
    one, two = cameras_of(["gbell:9@450,540,610"]), cameras_of(["gbell:9@450,540,610", "Nikon 5100 (NPL)"])
    assert bands_for(namespace(), one) is None
    assert bands_for(namespace(), two) == BANDS_DEFAULT
    assert bands_for(namespace(direct=True), two) is None
    for fields, cams in ((dict(bands="400:700:5"), one), (dict(bands="400:700:5", direct=True), two)):
        with pytest.raises(SkinrenderError, match="--bands"):
            bands_for(namespace(**fields), cams)
    with pytest.raises(SkinrenderError, match="--camera: camera gbell:9@450,540,610 is sensitive"):
        bands_for(namespace(bands="450:650:5"), two)


def test_a_camera_named_twice_is_refused():
    with pytest.raises(SkinrenderError, match="--camera: each once"):
        cameras_of(["gbell:9@450,540,610", "gbell:9@450,540,610"])
