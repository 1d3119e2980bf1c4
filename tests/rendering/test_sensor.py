"""
Tests for :mod:`skinrender.rendering.sensor`: the ``noise`` effect's options, each bound checked once, named.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.model.imager import imager
from skinrender.rendering.sensor import EXPOSURE_MAX, ILLUMINANCE_MAX, NoiseOptions


def test_values_become_what_they_are():
    options = NoiseOptions(" sony-imx174 ", np.float32(250.0), " AUTO ")
    assert options.imager == imager("sony-imx174") and options.illuminance == 250.0 and options.exposure == "auto"
    assert type(options.illuminance) is float
    assert NoiseOptions(exposure=np.int64(2)).exposure == 2.0 and NoiseOptions().imager is None
    assert NoiseOptions(imager("sony-icx418")).imager.name == "sony-icx418"  # an Imager is kept as it is
    with pytest.raises(dataclasses.FrozenInstanceError):
        options.exposure = 1.0  # type: ignore[misc]


@pytest.mark.parametrize("kwargs, role", [
    ({"exposure": -1}, "exposure"), ({"exposure": 0}, "exposure"), ({"exposure": EXPOSURE_MAX * 2}, "exposure"),
    ({"exposure": math.inf}, "exposure"), ({"exposure": "never"}, "exposure"), ({"exposure": True}, "exposure"),
    ({"illuminance": 0}, "illuminance"), ({"illuminance": -5}, "illuminance"), ({"illuminance": math.nan}, "illuminance"),
    ({"illuminance": ILLUMINANCE_MAX * 10}, "illuminance"), ({"illuminance": "x"}, "illuminance"),
    ({"illuminance": False}, "illuminance"), ({"imager": "nosuch"}, "imager"), ({"imager": 3}, "imager"),
])
def test_bad_options_are_refused_with_their_role(kwargs, role):
    with pytest.raises(SkinrenderError) as error:
        NoiseOptions(**kwargs)
    assert error.value.role == role and role in str(error.value)
