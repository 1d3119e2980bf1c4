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
