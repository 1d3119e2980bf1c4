"""Tests for :mod:`skinrender.studies.paper.volumes`: many banks on one pool give the search's volumes, bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

import skinrender as sr
from skinrender.design.bank import positions_grid, sensor_bank, triplets
from skinrender.design.search import search
from skinrender.spectra import GRID_DEFAULT
from skinrender.studies.paper.volumes import (
    VolumeCache,
    bank_key,
    chunk_gains,
    compute_volumes,
    search_result,
)

POSITIONS = "400:700:50"  # 7 positions, 35 triplets


@pytest.fixture(scope="module")
def sets():
    return sr.reflectances("skin").on(GRID_DEFAULT), sr.reflectances("munsell-nickerson").on(GRID_DEFAULT)


def banks_of(sets, sensors=(1, 9)):
    where = positions_grid(POSITIONS)
    return {(s, name): sensor_bank(s, values, where) for s in sensors for name, values in zip(("skin", "munsell"), sets)}


class TestComputeVolumes:
    @pytest.mark.parametrize("workers", [1, 2])
    def test_equal_to_the_search(self, sets, workers):
        volumes, finished = compute_volumes(banks_of(sets), workers=workers)
        for sensor in (1, 9):
            reference = search(sensor, *sets, POSITIONS, workers=1)
            np.testing.assert_array_equal(volumes[(sensor, "skin")], reference.skin)
            np.testing.assert_array_equal(volumes[(sensor, "munsell")], reference.munsell)
        assert set(finished) == set(volumes) and all(t > 0 for t in finished.values())

    def test_nothing_to_do_still_starts_the_caller(self):
        started = []
        assert compute_volumes({}, on_start=lambda: started.append(True)) == ({}, {})
        assert started == [True]

    def test_search_result_gives_the_tables(self, sets):
        volumes, _ = compute_volumes(banks_of(sets, (9,)), workers=1)
        reference = search(9, *sets, POSITIONS, workers=1)
        result = search_result(9, 2.0, positions_grid(POSITIONS), reference.temperatures, volumes[(9, "skin")],
                               volumes[(9, "munsell")], 0.0, 1)
        assert result.table() == reference.table()


class TestChunkGains:
    @pytest.mark.parametrize("sensor", [1, 9])
    def test_equal_to_the_banks_gains_to_the_bit(self, sets, sensor):
        bank = banks_of(sets, (sensor,))[(sensor, "munsell")]
        index = triplets(bank.positions.size)
        gains = chunk_gains(bank, index)
        for row, triplet in enumerate(index):
            np.testing.assert_array_equal(gains[row], bank.gains(triplet))


class TestVolumeCache:
    def test_computes_each_key_once(self, sets):
        cache = VolumeCache()
        banks = banks_of(sets, (9,))
        cache.ensure(banks, workers=1)
        assert cache.computed == 2
        cache.ensure(banks, workers=1)
        assert cache.computed == 2 and (9, "skin") in cache

    def test_the_impulse_has_no_slope(self):
        where, t = positions_grid(POSITIONS), np.array([2000.0, 3000.0])
        assert bank_key(1, "skin", where, t, 2.0, GRID_DEFAULT, "refuse") == bank_key(1, "skin", where, t, 5.0,
                                                                                        GRID_DEFAULT, "refuse")
        assert bank_key(9, "skin", where, t, 2.0, GRID_DEFAULT, "refuse") != bank_key(9, "skin", where, t, 5.0,
                                                                                        GRID_DEFAULT, "refuse")


def test_dask_gives_the_same_volumes(sets):
    distributed = pytest.importorskip("distributed")
    banks = banks_of(sets, (9,))
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        remote, _ = compute_volumes(banks, dask=client)
    local, _ = compute_volumes(banks, workers=1)
    for key in banks:
        np.testing.assert_array_equal(remote[key], local[key])
