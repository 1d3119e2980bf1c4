"""
Tests for :mod:`skinrender.studies.benchmarks.calibration`: the paths by kind of scene (the face's registered with its seed
step, a chart's level refused), the time estimate, the false-alarm bookkeeping on a simulated run, and small-N
calibrations of real renders (12 seeds on a chart of 8 × 8-pixel patches, where the expected failures are ~0.1).
"""

from __future__ import annotations

import pytest

from skinrender.errors import SkinrenderError
from skinrender.evaluation.verdict import Verdict
from skinrender.studies.benchmarks.calibration import (CALIBRATION_PATHS, bench_calibration, bench_validate, calibration_path,
                                            estimate_seconds)

CAMERA = "gbell:9@450,540,610"


@pytest.fixture(scope="module")
def tiny(small_chart):
    from skinrender.rendering.scene import load_chart_scene

    return load_chart_scene(small_chart)


class TestPaths:
    def test_the_face_is_registered_with_its_seed_step(self):
        """The face's run (studies.benchmarks.face_calibration.face_run) is registered; its validations take 12 seeds each, so
        two independent runs' seeds are 12 apart; an unknown kind is refused."""
        from skinrender.studies.benchmarks.face_calibration import SEED_STEP

        run = calibration_path("face", "sheen")
        assert run is CALIBRATION_PATHS["face"] and run.seed_step == SEED_STEP == 12
        with pytest.raises(SkinrenderError, match="--scene: no calibration of a moon scene"):
            calibration_path("moon")

    def test_runs_are_a_runs_seed_step_apart(self):
        seen = []

        def run(scene, camera_, prevailing, calibration, spp, seed, *rest):
            seen.append(seed)
            return {"checks": {"difference": Verdict("difference", "pass", 0.01, "z")}, "bound": None,
                    "seconds": 0.0, "spp": spp}

        run.seed_step = 12
        bench_calibration(run, "s", CAMERA, 2856, 5900, 16, seeds=3, first_seed=5)
        assert seen == [5, 17, 29]

    def test_a_level_is_refused_for_a_chart(self):
        with pytest.raises(SkinrenderError, match="--level direct: levels of physics go with a face scene"):
            calibration_path("chart", "direct")

    def test_a_registered_path_is_used(self, monkeypatch):
        run = lambda *args: {}  # noqa: E731
        monkeypatch.setitem(CALIBRATION_PATHS, "face", run)
        assert calibration_path("face", "sheen") is run


class TestEstimate:
    def test_grows_with_seeds_and_spp(self):
        base = estimate_seconds(10, 8036, 16)
        assert estimate_seconds(20, 8036, 16) > base and estimate_seconds(10, 8036, 64) > base
        assert estimate_seconds(10, 8036, 16, passes=3) > base and estimate_seconds(10, 8036, 16, sensor=True) > base


def _simulated(fail_every: int):
    """A run whose difference test fails on every ``fail_every``-th seed (seeds step by 2)."""
    def run(scene, camera_, prevailing, calibration, spp, seed, imaging, mc_variance, tolerance, level):
        outcome = "fail" if (seed // 2) % fail_every == 0 else "pass"
        checks = {"difference": Verdict("difference", outcome, 0.01, "z", 1.0, 3.0),
                  "equivalence": Verdict("equivalence", "pass", 0.05, "TOST", 0.5, 1.0, bound=0.001)}
        return {"checks": checks, "bound": 0.001 * (16 / spp), "seconds": 0.01, "spp": spp}
    return run


def test_the_rates_and_intervals_are_counted():
    result = bench_calibration(_simulated(4), "chart", CAMERA, 3300.0, 4800.0, 16, seeds=20)
    rows = {row["name"]: row for row in result["checks"]}
    assert rows["difference"]["failures"] == 5 and rows["difference"]["rate"] == 0.25
    lo, hi = rows["difference"]["interval"]
    assert lo < 0.25 < hi and not rows["difference"]["consistent"]  # 5 of 20 is far above α = 0.01
    assert rows["equivalence"]["failures"] == 0 and rows["equivalence"]["consistent"]
    assert [run["seed"] for run in result["runs"]][:3] == [0, 2, 4]


def test_validate_rows_and_the_fitted_exponent():
    result = bench_validate(_simulated(1000), "chart", CAMERA, 3300.0, 4800.0, [4, 16, 64], seeds=2)
    assert [row["bound"] for row in result["rows"]] == [0.004, 0.001, 0.00025]
    assert result["bound_exponent"] == pytest.approx(1.0)


@pytest.mark.parametrize("imager", [None, "sony-imx174"])
def test_small_calibration_of_real_renders(tiny, imager):
    """12 independent seeds at 16 spp, where the null holds: the difference tests raise at most 2 false alarms
    (expected 0.12 at α = 0.01), the equivalence none. Through the sensor the render's variance is several times
    the sensor's at 16 spp: without its correction most seeds would fail (tests/rendering/test_sensor_validation.py)."""
    pytest.importorskip("mitsuba")
    from skinrender.model.imager import imager as imager_of

    run = calibration_path("chart")
    imaging = None if imager is None else {"imager_": imager_of(imager), "illuminance_lux": 500.0,
                                           "exposure": "auto"}
    result = bench_calibration(run, tiny, CAMERA, 3300.0, 4800.0, 16, seeds=12, first_seed=50, imaging=imaging)
    rows = {row["name"]: row for row in result["checks"]}
    assert rows["difference"]["failures"] <= 2 and rows["difference"]["seeds"] == 12
    assert rows["equivalence"]["failures"] == 0
    assert len(result["runs"]) == 12 and result["spp"] == 16


def test_bound_falls_and_seconds_are_measured(tiny):
    pytest.importorskip("mitsuba")
    result = bench_validate(calibration_path("chart"), tiny, CAMERA, 3300.0, 4800.0, [4, 16, 64], seeds=2)
    bounds = [row["bound"] for row in result["rows"]]
    assert bounds[0] > bounds[1] > bounds[2] and result["bound_exponent"] > 0.4
    assert all(row["seconds"] > 0 and row["seeds"] == 2 for row in result["rows"])
