"""Tests for :mod:`skinrender.rendering.loaded`: the rendering caches' scenes are released, and a released scene
renders the same image again."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("mitsuba")


def test_release_empties_the_caches_and_the_same_seed_renders_the_same_image():
    import skinrender as sr
    from skinrender.rendering import renderer
    from skinrender.rendering.face import render as face_render
    from skinrender.rendering.loaded import release_scenes

    release_scenes()
    kwargs = dict(camera="gbell:9@450,540,610", prevailing=2856, calibration=5900, spp=4, seed=3)
    first = sr.render("macbeth", **kwargs)
    face = sr.render("face", size=8, **kwargs)
    assert renderer._renderer.cache_info().currsize == 1 and face_render._load.cache_info().currsize >= 1
    assert release_scenes() >= 2
    assert renderer._renderer.cache_info().currsize == 0 and face_render._load.cache_info().currsize == 0
    assert release_scenes() == 0
    np.testing.assert_array_equal(sr.render("macbeth", **kwargs).image, first.image)
    np.testing.assert_array_equal(sr.render("face", size=8, **kwargs).image, face.image)
    release_scenes()
