"""Tests for :mod:`skinrender.rendering.face.document`: transforms, the renderer's integral, and each level's
Mitsuba document as it was before the effects became a registry."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import trapezoid

from skinrender.model.camera import camera
from skinrender.model.exposure import illuminance_lux
from skinrender.rendering.face.document import channel_groups, channel_integral, light_irradiance, transform
from skinrender.rendering.face.scene import Light
from skinrender.spectra import GRID_DEFAULT, WavelengthGrid


class TestTransform:
    def test_rotation_order_and_scale(self):
        m = transform([1, 2, 3], [90, 0, 0], 2.0)
        assert np.allclose(m @ [0, 1, 0, 1], [1, 2, 5, 1])  # y → z about x, doubled, moved
        m = transform([0, 0, 0], [90, 90, 0], 1.0)  # about x first, then y
        assert np.allclose(m[:3, :3] @ [0, 1, 0], [1, 0, 0])


class TestSpectra:
    def test_a_light_has_its_illuminance(self):
        light = Light(3000.0, 250.0)
        lam, irradiance = light_irradiance(light, GRID_DEFAULT)
        fine = WavelengthGrid(GRID_DEFAULT.start, GRID_DEFAULT.end, lam[1] - lam[0])
        assert np.isclose(illuminance_lux(irradiance, fine), 250.0)

    def test_channel_integral_of_a_flat_spectrum_is_the_curve_area(self):
        cam = camera("gbell:9@450,540,610")
        lam = np.linspace(400, 700, 3001)
        curves = [np.interp(lam, GRID_DEFAULT.wavelengths, c) for c in cam.sensitivities(GRID_DEFAULT)]
        area = trapezoid(np.array(curves), lam, axis=1)
        assert np.allclose(channel_integral(cam, GRID_DEFAULT, lam, np.ones_like(lam)), area)

    def test_channel_groups(self):
        assert channel_groups(camera("gbell:9@450,540,610"), GRID_DEFAULT) == [(0, 1, 2)]
        assert channel_groups(camera("impulse@450,540,610"), GRID_DEFAULT) == [(0,), (1,), (2,)]
