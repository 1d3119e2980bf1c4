"""Tests for :mod:`skinrender.rendering.spp_choice`: even squares for multijitter, the fitted exponent and the spp
chosen from two pilots (a simulated validation whose bound falls as a known power of spp)."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from skinrender.errors import SkinrenderError
from skinrender.rendering.spp_choice import EXPONENT_RANGE, bound_exponent, spp_for_tolerance, square_spp


@pytest.mark.parametrize("spp, sampler, expected", [(1, "multijitter", 4), (16, "multijitter", 16),
                                                     (17, "multijitter", 36), (145, "multijitter", 196),
                                                     (145, "independent", 145), (0.3, "stratified", 1)])
def test_square_spp(spp, sampler, expected):
    assert square_spp(spp, sampler) == expected


def test_exponent_held_in_range():
    assert bound_exponent((16, 64), (1.0, 1 / 4**3)) == EXPONENT_RANGE[1]
    assert bound_exponent((16, 64), (1.0, 0.5)) == pytest.approx(0.5)
    assert bound_exponent((16, 64), (0.5, 1.0)) == EXPONENT_RANGE[0]


def _simulated(a: float, floor: float | None = None):
    """A validation whose bound is 0.01 · (16 / spp)^a (or a sensor's floor with spp_needed)."""
    def validate_at(spp, seed):
        bound = 0.01 * (16 / spp) ** a
        run = SimpleNamespace(bound=bound, rendering=SimpleNamespace(raw=[SimpleNamespace(spp=spp)], seconds=0.1))
        if floor is not None:
            run.spp_reason = "the sensor's noise alone keeps a bound above its tolerance" if floor >= 0.001 else ""
            run.spp_needed = None if floor >= 0.001 else 100
        return run
    return validate_at


@pytest.mark.parametrize("a", [0.5, 1.0, 1.25])
def test_the_choice_meets_the_tolerance(a):
    choice = spp_for_tolerance(_simulated(a), 0.001)
    assert choice["exponent"] == pytest.approx(a)
    assert 0.01 * (16 / choice["spp"]) ** a <= 0.001  # the simulated bound at the chosen spp passes
    assert 0.01 * (16 / (choice["spp"] / 4)) ** a > 0.001  # and a quarter of it would not: not wastefully large
    assert choice["spp"] ** 0.5 % 2 == 0 and [p["spp"] for p in choice["pilots"]] == [16, 64]


def test_through_a_sensor_the_pilots_spp_needed_is_used_or_the_tolerance_refused():
    assert spp_for_tolerance(_simulated(1.0, floor=0.0), 0.001)["spp"] == square_spp(125)
    with pytest.raises(SkinrenderError, match="--tolerance 0.001: no spp"):
        spp_for_tolerance(_simulated(1.0, floor=0.01), 0.001)


def test_never_below_the_first_pilot_where_nothing_was_measured():
    """A sensor's 64-spp pilot asked for 2 spp (its render noise extrapolated as 1/spp), which failed at 4 spp
    (bound 0.10 against 0.05): below the pilots the choice is held at the first's."""
    def sensor_pilot(spp, seed):
        run = _simulated(1.0)(spp, seed)
        run.spp_reason, run.spp_needed = "", 2
        return run

    choice = spp_for_tolerance(sensor_pilot, 0.05)
    assert choice["spp"] == 16 and "held at the first pilot's 16 spp" in choice["why"]
    assert spp_for_tolerance(_simulated(1.0), 0.5)["spp"] == 16  # the fitted law would have said 1


def test_a_refusal_names_the_tolerance_as_its_door_does():
    with pytest.raises(SkinrenderError) as error:
        spp_for_tolerance(_simulated(0.5), 1e-9, spp_max=10**6, name="tolerance")
    assert str(error.value).startswith("tolerance 1e-09: about") and error.value.role == "tolerance"
    assert error.value.flag is None
    with pytest.raises(SkinrenderError) as error:
        spp_for_tolerance(_simulated(1.0, floor=0.01), 0.001)
    assert error.value.flag == "--tolerance" and error.value.role == "tolerance"


def test_too_many_spp_refused_with_the_estimate():
    with pytest.raises(SkinrenderError, match="--tolerance 1e-09: about .* spp would be needed"):
        spp_for_tolerance(_simulated(0.5), 1e-9, spp_max=10**6)
