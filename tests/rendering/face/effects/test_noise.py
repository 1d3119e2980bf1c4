"""
Tests for :mod:`skinrender.rendering.face.effects.noise`: what validation checks through the sensor, and the
frame through the sensor composed after the render as Eq. 4's gain expects.
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.rendering.face.effects.noise import sensor_terms as _sensor_terms
from skinrender.rendering.face.limits import rounding_bias

pytest.importorskip("mitsuba")

CAM = "gbell:9@450,540,610"


def test_sensor_terms_remove_the_dark_signal_and_clipped_pixels():
    from skinrender.model.imager import imager
    from skinrender.rendering.face import render_face

    first = render_face(CAM, size=2, spp=1, physics="noise")
    im = imager("sony-icx418")
    g = np.asarray(first.gain)
    signal = np.full((3, 2, 2, 3), 50.0)
    signal[1, 0, 0, 2] = 0.0  # clipped at the black level in one replicate
    signal[2, 1, 1, 0] = im.max_dn - im.black_level_dn  # saturated
    images, usable, bias, floor, excluded = _sensor_terms(first, signal * g, "sony-icx418")
    dark = im.gain_dn_per_e * im.dark_current_e_per_s * first.info["exposure_s"]
    assert np.allclose(images[0, 0, 1], g * (50.0 - dark))
    assert usable.tolist() == [[False, True], [True, False]]
    sigma = im.gain_dn_per_e * np.sqrt(50.0 / im.gain_dn_per_e + im.read_noise_e**2)
    assert np.allclose(bias[0, 1], g * rounding_bias(sigma))
    assert np.allclose(floor[0, 1], g**2 * (sigma**2 + 1 / 12) / 3)  # EMVA: shot, read, quantisation; 3 frames
    assert set(excluded) == {"skin_pixels_clipped", "skin_pixels_undithered"}
    dim = _sensor_terms(first, np.full((3, 2, 2, 3), 2.0) * g, "sony-icx418")[1]  # σ ≈ 0.2 DN: codes undithered
    assert not dim.any()


def test_the_frame_through_the_sensor_is_balanced_with_the_whites_in_dn():
    """``noise`` renders as ``direct`` and then records one frame: Eq. 4's gain of the whites in DN times it."""
    from skinrender.constants import CONSTANT_OUTPUT_SCALE
    from skinrender.model.response import gain
    from skinrender.rendering.face import render_face
    from skinrender.rendering.face.effects.noise import IMAGER_DEFAULT, through_imager
    from skinrender.spectra import GRID_DEFAULT

    kwargs = {"size": 12, "spp": 2, "seed": 5, "prevailing": 2856, "calibration": 5900}
    direct, noisy = render_face(CAM, physics="direct", **kwargs), render_face(CAM, physics="noise", **kwargs)
    assert np.array_equal(noisy.radiance, direct.radiance)
    signal, white_p, white_c, settings = through_imager(direct.radiance, direct.white_prevailing, direct.scene,
                                                        direct.camera, 5900.0, GRID_DEFAULT, IMAGER_DEFAULT, "auto", 5)
    expected = gain(white_p, white_c, scale=CONSTANT_OUTPUT_SCALE) * signal
    assert np.array_equal(noisy.image, expected.astype(np.float32))
    assert noisy.info == {"lights": direct.info["lights"], **settings}
