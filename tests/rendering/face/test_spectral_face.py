"""
Tests for :mod:`skinrender.rendering.face.spectral_face`: the face rendered once with the bands at every level of
physics, seen through a camera, is the :class:`FaceRendering` a render of that camera returns: the same radiance
in expectation (a camera on the band grid, against direct renders, by a two-sample test), its labels, its level's
post-processing (``noise``: the sensor applied per camera).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats

from skinrender.errors import SkinrenderError
from skinrender.rendering.face import FaceRendering, render_face
from skinrender.rendering.face.effects import LEVELS_EACH
from skinrender.rendering.face.labels import LABEL_SKIN
from skinrender.rendering.face.spectral_face import face_through, render_face_spectral

pytest.importorskip("mitsuba")

CAM = "Nikon 5100 (NPL)"
"""Given every 5 nm: the 5 nm bands see its curves exactly, so spectral and direct renders share an expectation
(at 50 nm bands it is seen approximately; that test uses the default bands)."""


SKIN = "skin-model:melanin=0.1"
"""The skin model's own parameters: its layers need no fit at ``subsurface`` (as its own tests' skin)."""


@pytest.mark.parametrize("level", LEVELS_EACH)
def test_every_level_renders_spectrally(level):
    """8 px, 1–2 spp, 50 nm bands (7: a small kernel to compile): what is tested is that each level's document
    takes the bands and its result is whole."""
    image = render_face_spectral("face", 2856, skin=SKIN, physics=level, spp=1 if level == "subsurface" else 2,
                                 size=8, bands="400:700:50")
    assert image.image.shape == (8, 8, 7) and image.physics == level and np.all(np.isfinite(image.image))
    result = image.through(CAM, 5900)
    assert isinstance(result, FaceRendering) and result.physics == level and result.calibration == 5900.0
    assert result.image.shape == (8, 8, 3) and np.all(np.isfinite(result.image))
    assert np.array_equal(result.labels, image.labels) and (result.labels == LABEL_SKIN).any()
    assert result.info["spectral"]["bands_nm"] == "400:700:50"


def test_the_radiance_agrees_with_direct_renders():
    """Four replicates each way (16 px, 16 spp, independent seeds): each channel's skin mean radiance, spectral
    against direct, by Welch's t at a two-sided α of 0.001 per channel (Šidák over 3: 0.003 in all)."""
    seeds = range(4)
    spectral = [render_face_spectral("face", 2856, spp=16, size=16, seed=s).through(CAM, 5900) for s in seeds]
    direct = [render_face(CAM, "face", 2856, 5900, spp=16, size=16, seed=100 + s) for s in seeds]
    skin = spectral[0].labels == LABEL_SKIN
    a = np.array([r.radiance[skin].mean(axis=0) for r in spectral])
    b = np.array([r.radiance[skin].mean(axis=0) for r in direct])
    t, p = stats.ttest_ind(a, b, equal_var=False)
    assert np.all(p > 0.001), (a.mean(axis=0), b.mean(axis=0), p)
    assert np.allclose(spectral[0].white_prevailing, direct[0].white_prevailing, rtol=1e-9)  # on the band grid


def test_the_sensor_is_applied_per_camera():
    image = render_face_spectral("face", 2856, physics="noise", spp=2, size=8, imager="sony-icx418",
                                 bands="400:700:50")
    a, b = image.through(CAM, 5900), image.through("gbell:9@450,540,610", 5900)
    assert a.info["imager"] == b.info["imager"] == "sony-icx418" and "exposure_s" in a.info
    assert not np.allclose(a.image, b.image)
    assert np.allclose(a.image, np.round(a.image / a.gain) * a.gain, rtol=1e-5)  # whole DN above black, balanced


def test_an_imager_adds_the_noise_level_and_a_sensor_option_needs_it():
    """As every front door builds a request: an imager adds ``noise``; an exposure without it is refused."""
    image = render_face_spectral("face", 2856, physics="direct", spp=1, size=8, imager="sony-icx418",
                                 bands="400:700:50")
    assert image.physics == "noise"
    with pytest.raises(SkinrenderError, match="exposure"):
        render_face_spectral("face", 2856, physics="direct", spp=1, size=8, exposure=0.01, bands="400:700:50")


def test_an_image_without_its_request_cannot_be_seen_through():
    image = render_face_spectral("face", 2856, spp=1, size=8, bands="400:700:50")
    from dataclasses import replace

    with pytest.raises(SkinrenderError, match="no face scene"):
        face_through(replace(image, request=None), CAM)
