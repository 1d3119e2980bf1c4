"""
Tests for :mod:`skinrender.rendering.spectral_validation`: one spectral render of the Macbeth chart, seen through
the gbell 9 and narrow gbell 3 cameras and every bundled measured camera, passes Eq. 4 at 1 %; against a direct
render of the same camera, for two cameras and two light pairs, the difference test does not fire; the basis
error it allows is Eq. 4's own, 0 for a camera on the band grid.
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.datasets import list_cameras
from skinrender.rendering.spectral_chart import render_chart_spectral
from skinrender.rendering.spectral_validation import validate_spectral

pytest.importorskip("mitsuba")

CAMERAS = ["gbell:9@450,540,610", "gbell:3@450,540,610", *(entry["name"] for entry in list_cameras())]
"""The six cameras of the issue: gbell 9, a narrow gbell 3 (FWHM 30 nm) and each bundled measured camera."""


@pytest.fixture(scope="module")
def renders():
    """Spectral renders at 2856 K (256 spp: the narrow gbell 3's bound ~0.5 %, room under 1 %; 64 spp left it at
    ~0.9–1.2 %) and 2300 K (64 spp, for the difference tests, whose power grows with the spp)."""
    return {2856: render_chart_spectral("macbeth", 2856, spp=256, seed=5),
            2300: render_chart_spectral("macbeth", 2300, spp=64, seed=7)}


@pytest.mark.parametrize("cam", CAMERAS)
def test_every_camera_passes_eq4_at_one_percent(renders, cam):
    result = validate_spectral("macbeth", cam, 2856, 5900, spectral=renders[2856], direct=False, tolerance=0.01)
    assert result.verdict.outcome == "pass", result.verdict.reason
    assert result.validation.difference.outcome == "pass", result.validation.difference.reason
    assert result.basis_relative < 0.005  # the bands' own error, well inside the tolerance (docs/spectral.md)


@pytest.mark.parametrize("lights", [(2856, 5900), (2300, 2300)])
@pytest.mark.parametrize("cam", ["gbell:9@450,540,610", "Nikon 5100 (NPL)"])
def test_the_difference_from_a_direct_render_does_not_fire(renders, cam, lights):
    """Spectral against direct, independent seeds, both at the spectral render's spp: no difference beyond the
    noise and the basis error (α = 0.01, Šidák over 75 patch channels)."""
    p, c = lights
    spp = renders[p].spp_requested
    result = validate_spectral("macbeth", cam, p, c, spectral=renders[p], spp=spp, seed=renders[p].seed)
    assert result.direct is not None and result.direct.raw[0].seed == renders[p].seed + 2
    assert result.direct_difference.outcome == "pass", result.direct_difference.reason


def test_a_camera_on_the_band_grid_has_no_basis_error(renders):
    """The Nikon 5100 (NPL) is given every 5 nm: the 5 nm bands see its curves exactly."""
    result = validate_spectral("macbeth", "Nikon 5100 (NPL)", 2856, 5900, spectral=renders[2856], direct=False)
    assert np.max(np.abs(result.basis_error)) < 1e-9 * 255
    document = result.document()
    assert document["bands_nm"] == "400:700:5" and document["bands"] == 61 and document["direct"] is None
