"""Tests for :mod:`skinrender.rendering.loaded`: the rendering caches' scenes are released, and a released scene
renders the same image again: the same samples (the seed), to the renderer's float32 floor
(:data:`~skinrender.rendering.validation.FLOAT32_FLOOR`, 2e-6 relative). A kernel compiled again in another state of
the process (other scenes' objects alive) may round a pixel differently in its last bits (measured in test workers
that had rendered other scenes before: one pixel of 192 of a face off by 7.5e-8 and, in another run, 2.9e-7
relative); another seed's samples differ by percents at 4 spp."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("mitsuba")


def test_release_empties_the_caches_and_the_same_seed_renders_the_same_image():
    import skinrender as sr
    from skinrender.rendering import renderer
    from skinrender.rendering.face import render as face_render
    from skinrender.rendering.loaded import release_scenes
    from skinrender.rendering.validation import FLOAT32_FLOOR

    release_scenes()
    kwargs = dict(camera="gbell:9@450,540,610", prevailing=2856, calibration=5900, spp=4, seed=3)
    first = sr.render("macbeth", **kwargs)
    face = sr.render("face", size=8, **kwargs)
    assert renderer._renderer.cache_info().currsize == 1 and face_render.load_document.cache_info().currsize >= 1
    assert release_scenes() >= 2
    assert renderer._renderer.cache_info().currsize == 0 and face_render.load_document.cache_info().currsize == 0
    assert release_scenes() == 0
    np.testing.assert_allclose(sr.render("macbeth", **kwargs).image, first.image, rtol=FLOAT32_FLOOR, atol=0)
    np.testing.assert_allclose(sr.render("face", size=8, **kwargs).image, face.image, rtol=FLOAT32_FLOOR, atol=0)
    other = sr.render("macbeth", **{**kwargs, "seed": 4}).image
    assert not np.allclose(other, first.image, rtol=FLOAT32_FLOOR, atol=0)  # the comparison tells seeds apart
    release_scenes()
