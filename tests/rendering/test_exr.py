"""Tests for :mod:`skinrender.rendering.exr`: channels named R, G, B (every CSV or bundled camera) read back, and
an image's header traces it back to its camera's curves."""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.model.camera import camera
from skinrender.rendering.exr import camera_attributes, read_exr, read_exr_attributes, write_exr

from ..testing.test_regression import TINY, csv_camera

pytest.importorskip("OpenEXR")


def test_csv_camera_channels_r_g_b_read_back(tmp_path):
    pytest.importorskip("mitsuba")
    from skinrender.rendering.balance import render
    from skinrender.rendering.renderer import channel_names

    chart = tmp_path / "tiny.toml"
    chart.write_text(TINY)
    cam = camera(csv_camera(tmp_path / "camera.csv"))
    result = render(str(chart), cam, 3300, 5000, spp=4)
    names = channel_names(cam)
    assert names == ("R", "G", "B")
    path = write_exr(tmp_path / "x.exr", result.image, names, camera_attributes(cam))
    np.testing.assert_array_equal(read_exr(path, names), result.image)
    np.testing.assert_array_equal(read_exr(path, ("B",))[..., 0], result.image[..., 2])
    attributes = read_exr_attributes(path)
    assert attributes["camera_sha256"] == camera_attributes(camera(str(tmp_path / "camera.csv")))["camera_sha256"]
    assert attributes["camera_grid_nm"] == "400:700:1"


def test_the_face_exr_carries_the_camera_hash(tmp_path):
    pytest.importorskip("mitsuba")
    from skinrender.rendering.face import render_face, write_face_exr

    cam = camera(csv_camera(tmp_path / "camera.csv"))
    result = render_face(cam, size=8, spp=1)
    path, _ = write_face_exr(tmp_path / "face.exr", result)
    assert read_exr_attributes(path)["camera_sha256"] == camera_attributes(cam)["camera_sha256"]
    back = read_exr(path, ("R", "G", "B", "label"))
    np.testing.assert_array_equal(back[..., 3], result.labels)


def test_the_same_curves_give_the_same_hash_whatever_their_source(tmp_path):
    """A gbell camera written out as a CSV on the grid has the gbell's hash."""
    gbell = camera("gbell:9@450,540,610")
    lam = np.arange(400, 701, 1.0)
    path = tmp_path / "gbell.csv"
    np.savetxt(path, np.column_stack([lam, *gbell.sensitivities()]), delimiter=",", header="wavelength_nm,R,G,B",
               comments="", fmt="%.17g")
    assert camera_attributes(camera(str(path)))["camera_sha256"] == camera_attributes(gbell)["camera_sha256"]


def test_read_exr_refuses_a_device_unread(tmp_path):
    """Issue 25: an EXR path naming a device (here a link to /dev/zero) is refused before OpenEXR reads it."""
    import os

    from skinrender.errors import SkinrenderError

    if not os.path.exists("/dev/zero"):
        pytest.skip("no /dev/zero")
    (tmp_path / "image.exr").symlink_to("/dev/zero")
    with pytest.raises(SkinrenderError, match="a device, not a regular file; expected an EXR image"):
        read_exr(tmp_path / "image.exr", ("R", "G", "B"))
