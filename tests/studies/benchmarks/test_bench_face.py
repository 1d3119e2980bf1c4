"""Tests for :mod:`skinrender.studies.benchmarks.bench_face`: the error model, the presets it gives, the document's keys
and the refusals (no timing asserted)."""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.studies.benchmarks.bench_face import PRESET_THRESHOLDS, bench_face, fit_error, presets_of, spp_for


class TestFitError:
    def test_recovers_the_monte_carlo_term_and_the_floor(self):
        spps, reference = np.array([4, 16, 64, 256]), 1024
        errors = np.sqrt(0.3 * (1 / spps + 1 / reference) + 2e-4)
        a, b = fit_error(spps, errors, reference)
        assert np.isclose(a, 0.3) and np.isclose(b, 2e-4)

    def test_no_negative_floor_or_term(self):
        spps = [4, 16, 64]
        a, b = fit_error(spps, [0.1, 0.02, 0.004], 256)  # faster than 1/√spp: the fit would want b < 0
        assert b == 0.0 and a > 0
        a, b = fit_error(spps, [0.01, 0.02, 0.03], 256)  # growing: a floor alone
        assert a == 0.0 and b > 0


class TestSppFor:
    def test_a_power_of_two_that_reaches_the_threshold(self):
        spp = spp_for(0.01, 0.05, 0.0)
        assert spp & (spp - 1) == 0 and np.sqrt(0.05 / spp) <= 0.01 < np.sqrt(0.05 / (spp // 2))

    def test_none_when_the_floor_is_above(self):
        assert spp_for(0.01, 0.05, 1e-4) is None and spp_for(0.01, 0.05, 0.99e-4) is not None


class TestPresetsOf:
    def test_measured_where_reached_extrapolated_beyond(self):
        spps, reference = [4, 16, 64, 256], 4096
        errors = list(np.sqrt(0.64 * (1 / np.array(spps) + 1 / reference)))  # 0.4, 0.2, 0.1, 0.05
        errors = [e / 8 for e in errors]  # 0.05, 0.025, 0.0125, 0.00625
        presets = presets_of(spps, errors, reference)
        assert presets["draft"] == 256 and presets["extrapolated"] == ["standard", "reference"]
        assert presets["standard"] == 2048 and presets["reference"] == 16384  # a = 0.01: a / spp ≤ threshold²
        assert presets["b"] == 0.0 and presets["spp_at_floor"] is None
        assert set(presets["undefined"]) == {"spp_at_floor"} and "no floor" in presets["undefined"]["spp_at_floor"]

    def test_an_exact_monte_carlo_curve_has_no_floor(self):
        """A floor of rounding size is none (not an spp_at_floor of 2⁶⁰)."""
        spps = [4, 16, 64, 256]
        presets = presets_of(spps, list(0.1 * np.sqrt(1 / np.array(spps) + 1 / 4096)), 4096)
        assert presets["b"] == 0.0 and presets["spp_at_floor"] is None

    def test_a_floor_above_the_thresholds_gives_none(self):
        spps, reference = [4, 16, 64], 256
        errors = np.sqrt(0.01 * (1 / np.array(spps) + 1 / reference) + 2 * 0.012**2)
        presets = presets_of(spps, list(errors), reference)
        assert presets["draft"] is None and np.isclose(presets["floor"], 0.012, rtol=1e-3)
        assert presets["spp_at_floor"] >= 8 * 0.01 / (2 * 0.012**2)
        # each None comes with its reason: the floor above the threshold
        assert set(presets["undefined"]) == {name for name in PRESET_THRESHOLDS if presets[name] is None}
        assert "floor 0.012" in presets["undefined"]["draft"] and "threshold 0.01" in presets["undefined"]["draft"]


def test_bench_face_document():
    pytest.importorskip("mitsuba")
    result = bench_face(levels=("direct",), spps=(1, 8), size=24, reference_spp=32)
    assert {"machine", "curve", "presets", "reference_spp", "thresholds", "elapsed_s"} <= set(result)
    rows = result["curve"]
    assert [(r["level"], r["spp"]) for r in rows] == [("direct", 1), ("direct", 8)]
    assert all({"level", "spp", "seconds", "skin_ncc_error", "skin_ncc_rms"} <= set(r) for r in rows)
    assert rows[0]["pixels"] > 50
    assert rows[1]["skin_ncc_rms"] < rows[0]["skin_ncc_rms"]  # 8 × the samples: about √8 × less noise
    assert set(result["presets"]["direct"]) >= set(PRESET_THRESHOLDS)


def test_a_level_too_long_is_named_and_refused_before_rendering():
    """subsurface-volume's reference at the bench's 256 px and 4096 spp would take hours (2.5 h on one core at its
    rate): refused up front (it is benched when named, at a smaller size; LEVELS_BENCH leaves it out)."""
    with pytest.raises(SkinrenderError,
                       match=r"^--levels: subsurface-volume's reference .* would take about .*--max-minutes"):
        bench_face(levels=("direct", "subsurface-volume"), reference_spp=4096)


@pytest.mark.parametrize("kwargs, flag", [
    ({"spps": (0, 4)}, "--spp-list"),
    ({"spps": ()}, "--spp-list"),
    ({"size": 0}, "--size"),
    ({"reference_spp": -1}, "--reference-spp"),
    ({"levels": ("glossy",)}, "--levels"),
    ({"levels": ()}, "--levels"),
    ({"spps": (4, 4)}, "--spp-list"),
    ({"spps": (4, 16), "reference_spp": 8}, "--reference-spp"),
    ({"spps": (4, 16), "reference_spp": 16}, "--reference-spp"),
])
def test_bad_arguments_are_refused_before_rendering(kwargs, flag):
    with pytest.raises(SkinrenderError, match=f"^{flag}"):
        bench_face(**kwargs)
