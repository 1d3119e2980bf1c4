"""
Tests for :mod:`skinrender.testing.regression`: what a render regression compares, and that its
false-alarm rate is α where nothing changed (simulated, then rendered) and a 2 nm shift is caught.
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.evaluation.verdict import binomial_interval
from skinrender.testing.regression import Measurement, compare, measure, scene_kind, setting_notes

TINY = """
name = "tiny"
columns = 3
patch_px = 10
gap_px = 1
border_px = 1
[[patch]]
reflectance = "macbeth:dark skin"
[[patch]]
reflectance = "macbeth:orange"
[[patch]]
reflectance = "skin:#14"
"""


def csv_camera(path, shift: float = 0.0):
    """Three Gaussian channels (peaks 600, 530, 460 nm + ``shift``) as a CSV camera: channels named R, G, B."""
    lam = np.arange(380, 781, 5.0)
    curves = [np.exp(-((lam - peak - shift) / width) ** 2) for peak, width in ((600, 40), (530, 40), (460, 35))]
    np.savetxt(path, np.column_stack([lam, *curves]), delimiter=",", header="wavelength_nm,R,G,B", comments="",
               fmt="%.6g")
    return str(path)


def synthetic(mean, se, dof=200.0) -> Measurement:
    mean = np.asarray(mean, dtype=float)
    return Measurement("chart", None, None, (), (), tuple(f"p{i} / R" for i in range(mean.size)), mean,
                       np.broadcast_to(np.asarray(se, float), mean.shape).copy(), np.full(mean.size, dof))


class TestCompareOnSimulatedNulls:
    def test_false_alarm_rate_is_alpha(self, rng):
        """2000 pairs of 75 normal means with their own standard errors: the rate is α = 0.01 within its
        binomial interval (Šidák over independent values is exact)."""
        truth, se = rng.uniform(10, 200, 75), rng.uniform(0.01, 1.0, 75)
        trials, failures = 2000, 0
        for _ in range(trials):
            new = synthetic(truth + rng.normal(size=75) * se, se, dof=1e6)
            failures += not compare(new, truth + rng.normal(size=75) * se / 2, se / 2, np.full(75, 1e6)).passed
        lo, hi = binomial_interval(failures, trials)
        assert lo <= 0.01 <= hi, (failures, lo, hi)

    def test_a_shift_of_six_standard_errors_is_caught(self, rng):
        se = np.full(75, 0.1)
        shifted = synthetic(np.r_[100.6 + rng.normal() * 0.1, np.full(74, 100.0)], se)
        result = compare(shifted, np.full(75, 100.0), np.full(75, 1e-9), np.full(75, 200.0))
        assert not result.passed and result.worst == 0 and result.summary().startswith("worst p0 / R")

    def test_exact_equal_values_pass_and_exact_unequal_fail(self):
        exact = synthetic([0.0, 1.0], [0.0, 0.1])
        assert compare(exact, [0.0, 1.0], [0.0, 0.1], [np.inf, 50]).passed
        result = compare(exact, [1e-3, 1.0], [0.0, 0.1], [np.inf, 50])
        assert not result.passed and np.isinf(result.z[0])

    def test_student_t_at_the_smallest_welch_dof(self):
        """Few degrees of freedom widen the critical value (a patch of few pixels)."""
        many = compare(synthetic([1.0] * 10, 0.1, 1e6), [1.0] * 10, [0.1] * 10, [1e6] * 10)
        few = compare(synthetic([1.0] * 10, 0.1, 5.0), [1.0] * 10, [0.1] * 10, [5.0] * 10)
        assert few.verdict.threshold > many.verdict.threshold + 1


class TestRefusals:
    @pytest.mark.parametrize("kwargs, match", [
        ({"scene": "nosuch"}, "unknown scene 'nosuch'"),
        ({"camera": "nosuch"}, "camera: unknown camera 'nosuch'"),
        ({"prevailing": "x"}, "prevailing"),
        ({"calibration": "nosuch.csv"}, "calibration"),
        ({"physics": "sheen"}, "physics: goes with a face scene"),
        ({"skin": "skin:#1", "size": 8}, "skin, size: go with a face scene"),
        ({"illuminance": 100.0}, "illuminance sets the image sensor's exposure: it goes with imager"),
        ({"imager": "nosuch"}, "imager"),
        ({"spp": 0}, "spp must be an integer"),
        ({"seed": -1}, "seed must be an integer"),
        ({"seed": 1.5}, "seed must be an integer"),
        ({"scene": "face", "spp": 2}, "spp: a face check renders 4 replicates"),
        ({"scene": "face", "physics": "glossy"}, "physics"),
    ])
    def test_bad_arguments_are_named(self, kwargs, match):
        arguments = {"scene": "macbeth", "camera": "gbell:9@450,540,610", "prevailing": "A", "calibration": 5000,
                     **kwargs}
        with pytest.raises(SkinrenderError, match=match):
            measure(**arguments)

    def test_scene_kinds(self, tmp_path):
        chart = tmp_path / "c.toml"
        chart.write_text(TINY)
        face = tmp_path / "f.toml"
        face.write_text("[camera]\n[mesh]\n")
        assert [scene_kind(s) for s in ("macbeth", "face", str(chart), str(face), "nosuch")] == [
            "chart", "face", "chart", "face", "chart"]


def test_setting_notes_name_what_changed():
    old = {"camera": "a.csv", "camera_sha256": "0" * 64, "variant": "llvm_ad_spectral", "spp_requested": 64}
    new = {**old, "camera_sha256": "1" * 64, "variant": "scalar_spectral"}
    notes = setting_notes(new, old)
    assert notes[0].startswith("the camera's curves changed: a.csv 000000000000… in the reference")
    assert notes[1] == "the Mitsuba variant changed: llvm_ad_spectral in the reference, scalar_spectral now"
    assert setting_notes(old, old) == ()


@pytest.fixture(scope="module")
def setup(tmp_path_factory):
    """A tiny chart through a CSV camera at 16 spp, and its reference at 64 spp (seed 0)."""
    pytest.importorskip("mitsuba")
    folder = tmp_path_factory.mktemp("calibration")
    chart = folder / "tiny.toml"
    chart.write_text(TINY)
    camera = csv_camera(folder / "camera.csv")
    kwargs = {"scene": str(chart), "camera": camera, "prevailing": "A", "calibration": 5000, "spp": 16}
    return kwargs, measure(**{**kwargs, "spp": 64}), folder


class TestRenderedCalibration:
    """On renders: no change gives z of unit spread and few false alarms; a 2 nm shift is caught."""

    def test_chart_nulls(self, setup):
        kwargs, reference, _ = setup
        zs, failures = [], 0
        for seed in range(1, 41):
            result = compare(measure(**kwargs, seed=seed), reference.mean, reference.standard_error, reference.dof)
            zs.append(result.z)
            failures += not result.passed
        spread = float(np.std(zs))
        assert 0.8 < spread < 1.2, spread
        assert failures <= 2

    def test_chart_two_nm_shift_fails(self, setup):
        kwargs, reference, folder = setup
        shifted = measure(**{**kwargs, "camera": csv_camera(folder / "shifted.csv", 2.0)})
        result = compare(shifted, reference.mean, reference.standard_error, reference.dof)
        assert not result.passed and abs(result.z[result.worst]) > 10

