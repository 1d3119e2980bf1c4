"""Tests for :mod:`skinrender.rendering.face.document`: physics specs, transforms and the renderer's integral."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import trapezoid

from skinrender.errors import SkinrenderError
from skinrender.model.camera import camera
from skinrender.model.exposure import illuminance_lux
from skinrender.rendering.face.document import (EFFECTS, PHYSICS, active_lights, channel_groups, channel_integral,
                                            light_irradiance, parse_physics, transform)
from skinrender.rendering.face.scene import Light, load_face_scene
from skinrender.spectra import GRID_DEFAULT, WavelengthGrid


class TestParsePhysics:
    def test_levels_and_combinations(self):
        assert parse_physics("direct") == ()
        assert parse_physics(" noise + mixed ") == ("mixed", "noise")
        assert parse_physics("+".join(reversed(EFFECTS))) == EFFECTS
        assert set(EFFECTS) | {"direct"} == set(PHYSICS)

    @pytest.mark.parametrize("spec", ["", "glossy", "direct+noise", "sheen+", "subsurface"])
    def test_refused(self, spec):
        with pytest.raises(SkinrenderError, match="physics"):
            parse_physics(spec)


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


class TestActiveLights:
    def test_levels_choose_lights(self):
        scene = load_face_scene("face")
        assert list(active_lights(scene, ())) == ["key"]
        assert list(active_lights(scene, ("mixed",))) == ["key", "fill", "environment"]
        sky = replace(scene, key=None, fill=None)
        assert list(active_lights(sky, ())) == ["environment"]
        with pytest.raises(SkinrenderError, match="mixed"):
            active_lights(replace(scene, fill=None, environment=None), ("mixed",))


def test_an_effect_named_twice_is_refused():
    from skinrender.errors import SkinrenderError
    from skinrender.rendering.face.document import parse_physics

    with pytest.raises(SkinrenderError, match="named twice"):
        parse_physics("sheen+interreflection+sheen")
