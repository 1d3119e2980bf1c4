"""Tests for :mod:`skinrender.design.criteria`: many triplets' volumes at once, to the bit of one at a time."""

from __future__ import annotations

import numpy as np
import pytest

import skinrender as sr
import skinrender.design.criteria as criteria
from skinrender.design.bank import positions_grid, sensor_bank, triplets
from skinrender.spectra import GRID_DEFAULT


@pytest.fixture(scope="module")
def sets():
    return {name: sr.reflectances(name).on(GRID_DEFAULT) for name in ("skin", "munsell-nickerson")}


@pytest.mark.parametrize("sensor", [1, 9])
@pytest.mark.parametrize("name", ["skin", "munsell-nickerson"])
def test_many_triplets_equal_one_at_a_time_to_the_bit(sets, sensor, name):
    bank = sensor_bank(sensor, sets[name], positions_grid("400:700:50"))
    index = triplets(bank.positions.size)
    expected = np.array([criteria.triplet_volumes_fast(bank, t) for t in index])
    np.testing.assert_array_equal(criteria.triplet_volumes_many(bank, index), expected)


def test_triplet_gains_equal_the_banks_to_the_bit(sets):
    bank = sensor_bank(9, sets["skin"], positions_grid("400:700:50"))
    index = triplets(bank.positions.size)
    gains = criteria.triplet_gains(bank, index)
    for row, triplet in enumerate(index):
        np.testing.assert_array_equal(gains[row], bank.gains(triplet))


def test_the_knee_and_other_normalisations_go_triplet_by_triplet(sets):
    """Only Stage 3's white normalisation without the knee has the one-call route; the others give the same
    volumes as one at a time."""
    for options in ({"knee": True}, {"normalization": "560nm"}):
        bank = sensor_bank(9, sets["skin"], positions_grid("400:700:100"), **options)
        index = triplets(bank.positions.size)
        np.testing.assert_array_equal(criteria.triplet_volumes_many(bank, index),
                                      np.array([criteria.triplet_volumes_fast(bank, t) for t in index]))


def test_without_the_kernel_the_same_volumes(sets, monkeypatch):
    bank = sensor_bank(9, sets["munsell-nickerson"], positions_grid("400:700:100"))
    index = triplets(bank.positions.size)
    with_kernel = criteria.triplet_volumes_many(bank, index)
    monkeypatch.setattr(criteria, "compiled_kernel", lambda: None)
    monkeypatch.setattr(sr.evaluation.hull, "_hull3d", None)
    np.testing.assert_allclose(criteria.triplet_volumes_many(bank, index), with_kernel, rtol=1e-9)
