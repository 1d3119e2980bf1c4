"""
Tests for :mod:`skinrender.rendering.face.validation`: which limits are checked at which level, the spp
split over replicates, the sensor's checks, and refusals. (The limits themselves and their failing
controls: ``test_face.py`` and ``test_face_limits.py``.)
"""

from __future__ import annotations

import pytest

from skinrender.errors import SkinrenderError
from skinrender.rendering.face.validation import LIMITS_SCENE_FREE, validate_face

pytest.importorskip("mitsuba")

CAM = "gbell:9@450,540,610"


def names(result) -> list[str]:
    return [c.name for c in result.checks]


@pytest.mark.parametrize("physics, expected", [
    ("direct", ["shading_cancels", "eq4_shift"]),
    ("sheen", ["dichromatic_plane", "eq4_shift"]),
    ("noise", ["shading_cancels", "eq4_shift"]),
    ("sheen+noise", ["dichromatic_plane", "eq4_shift"]),
    ("mixed", ["eq4_shift"]),
])
def test_the_checks_of_each_level(physics, expected):
    result = validate_face(CAM, physics=physics, size=48, spp=48, limits=(), prevailing=2856, calibration=2856)
    assert names(result) == expected
    assert result.spp == 48 and result.spp_requested == 48 and result.replicates == 12
    first = result.checks[0]
    if first.applies:
        assert first.passed is True, first
    else:
        assert result.passed is None and first.passed is None
    document = result.document()
    assert document["physics"] == physics and document["checks"][0]["name"] == expected[0]


def test_spp_is_split_over_the_replicates_and_seeds_follow():
    result = validate_face(CAM, size=12, spp=25, seed=2**32 - 3, replicates=4, limits=(), sampler="independent")
    assert result.spp == 4 * 7 and result.spp_requested == 25 and result.seed == 2**32 - 3


def test_through_the_sensor_the_shading_check_runs_and_its_control_fails(monkeypatch):
    """The 8-bit sensor's dithered pixels pass; the same frames against an Eq. 4 off by 1 % in R fail."""
    import skinrender.rendering.face.validation as module

    kwargs = {"physics": "noise", "size": 64, "spp": 96, "limits": (), "prevailing": 2856, "calibration": 5900}
    check = validate_face(CAM, **kwargs).checks[0]
    assert check.name == "shading_cancels" and check.pixels > 100 and check.passed is True, check
    assert check.details["skin_pixels_undithered"] > 0
    reference = module.analytic_reference
    monkeypatch.setattr(module, "analytic_reference", lambda *a, **k: reference(*a, **k) * [1.01, 1.0, 1.0])
    assert validate_face(CAM, **kwargs).checks[0].passed is False


@pytest.mark.parametrize("kwargs, match", [
    ({"replicates": 2}, "replicates"),
    ({"limits": ("moon",)}, "limits"),
    ({"spp": 0}, "spp"),
    ({"physics": "glossy"}, "physics"),
])
def test_refusals(kwargs, match):
    with pytest.raises(SkinrenderError, match=match):
        validate_face(CAM, **{"size": 8, "spp": 12, **kwargs})


def test_scene_free_limits_are_named():
    assert set(LIMITS_SCENE_FREE) == {"furnace", "sphere"}


def _verdict(*rows) -> bool | None:
    """The verdict of checks given as (applies, passed) pairs."""
    from skinrender.rendering.face.limits import LimitCheck
    from skinrender.rendering.face.validation import FaceValidation

    checks = [LimitCheck(f"check{i}", applies, passed, None, None, 0, "why") for i, (applies, passed) in enumerate(rows)]
    return FaceValidation(None, checks, 12, 12, 12, 0, 0.0).passed


@pytest.mark.parametrize("rows, expected", [
    ([(True, True), (True, True), (False, None)], True),
    ([(True, None), (True, True), (True, True)], None),  # the main check undecided: no pass on the others
    ([(True, True), (True, None)], None),  # a scene-free limit undecided
    ([(True, None), (True, False)], False),  # a failure decides whatever else is undecided
    ([(False, None)], None),  # nothing applies
    ([], None),
])
def test_the_verdict_passes_only_when_every_check_that_applies_passed(rows, expected):
    assert _verdict(*rows) is expected


def test_a_tiny_face_with_no_lit_skin_does_not_pass():
    """At 2 px no skin pixel is lit: ``shading_cancels`` undecided, so the verdict is too (the sphere passes)."""
    result = validate_face(CAM, size=2, spp=12, limits=("sphere",), prevailing=2856, calibration=2856)
    shading, sphere = result.checks[0], result.checks[-1]
    assert shading.name == "shading_cancels" and shading.applies and shading.passed is None and shading.pixels == 0
    assert sphere.name == "closed_sphere" and sphere.passed is True
    assert result.passed is None and result.document()["passed"] is None
