"""Tests for :mod:`skinrender.rendering.face.document`: transforms, the renderer's integral, and the document
holding what the level's effects supply (what each level supplies: ``effects/test_levels.py``)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import trapezoid

from skinrender.model.camera import camera
from skinrender.model.exposure import illuminance_lux
from skinrender.rendering.face.document import (channel_groups, channel_integral, face_document, light_irradiance,
                                                transform)
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


def test_the_document_holds_what_the_level_supplies(tmp_path):
    """A user's mesh (a dict in the document, where the bundled head is a built Mesh): integrator, materials, lights."""
    pytest.importorskip("mitsuba")
    from skinrender.rendering.face.effects import physics_level
    from skinrender.rendering.face.labels import SHAPE_SKIN, prop_shape_id
    from skinrender.rendering.face.scene import load_face_scene, skin_reflectance_of
    from skinrender.rendering.scene import reflectance_of
    from skinrender.rendering.variants import choose_variant, mitsuba

    mesh = tmp_path / "tri.obj"
    mesh.write_text("v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nf 1 2 3\n")
    scene = replace(load_face_scene("face"), mesh=str(mesh))
    cam = camera("gbell:9@450,540,610")
    mi = mitsuba(choose_variant(None))
    for spec in ("direct", "interreflection+sheen+mixed"):
        level = physics_level(spec)
        lights = level.lights(scene)
        document = face_document(mi, scene, cam, GRID_DEFAULT, level, scene.skin, (0, 1, 2), 4, 0, "independent",
                                 lights, 1.0)
        setup = level.setup(scene, cam, GRID_DEFAULT, lights)
        assert document["integrator"] == level.integrator(setup)
        skin = level.skin(skin_reflectance_of(scene.skin, GRID_DEFAULT), setup)
        assert document[SHAPE_SKIN]["bsdf"] == skin["bsdf"] and document[SHAPE_SKIN]["type"] == "obj"
        prop = scene.props[0]
        assert document[prop_shape_id(0)]["bsdf"] == level.prop(reflectance_of(prop.reflectance, GRID_DEFAULT, ""),
                                                                  setup)["bsdf"]
        assert sorted(k for k in document if k.startswith("light_")) == sorted(f"light_{n}" for n in lights)
        mi.load_dict(document)  # Mitsuba takes it
