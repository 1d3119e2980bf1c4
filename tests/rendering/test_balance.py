"""
Tests for :mod:`skinrender.rendering.balance`: the package's own render regressions of charts, on its own
pytest plugin (:mod:`skinrender.testing`). The references (EXR + sidecar, 4× the check's spp) are in
``tests/rendering/test_balance/``; ``pytest --skinrender-regen tests/rendering/test_balance.py`` rewrites them
when a change of the renders is meant.
"""

from __future__ import annotations

import pytest

pytest.importorskip("mitsuba")


def test_macbeth_through_a_bundled_camera_renders_as_its_reference(render_regression):
    """Every patch's white-balanced mean (Eq. 4, A → 5900 K) within its noise of the stored render's, through
    a measured camera whose channels are named R, G, B."""
    render_regression.check("macbeth", camera="Kodak DCS-200", prevailing="A", calibration=5900,
                            basename="macbeth_kodak")


def test_skin_patches_under_h_render_as_their_reference(render_regression):
    """The skin chart at the paper's other corner (H → A), through a gbell camera (channels R_610nm, …)."""
    render_regression.check("skin_patches", camera="gbell:9@450,540,610", prevailing="H", calibration="A", spp=16,
                            basename="skin_patches_gbell")


@pytest.mark.parametrize("scene", ["macbeth", "face"])
@pytest.mark.parametrize("role", ["prevailing", "calibration"])
def test_a_light_the_camera_cannot_see_is_refused_before_any_render(scene, role, monkeypatch):
    """Issue 36: ``sr.render(chart, …, calibration=1)`` rendered the prevailing light first, then said "the Planck
    emitter is zero" naming no argument; a face rendered its white references first (9 s) and failed on NaN."""
    import skinrender as sr
    import skinrender.rendering.face.render as face_render
    import skinrender.rendering.balance as balance

    stop = lambda *a, **k: pytest.fail("rendered before the light was checked")  # noqa: E731
    monkeypatch.setattr(balance, "render_balanced", stop)
    monkeypatch.setattr(face_render, "render_face_request", stop)
    lights = {"prevailing": "A", "calibration": 5900, role: 1}
    with pytest.raises(sr.SkinrenderError, match=f"^{role} illuminant 1K gives no light") as error:
        sr.render(scene, "gbell:9@450,540,610", lights["prevailing"], lights["calibration"], spp=4,
                  **({"size": 8} if scene == "face" else {}))
    assert error.value.role == role
