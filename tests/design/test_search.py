"""Tests for :mod:`skinrender.search`: the fast search equals the straightforward one, ties, degenerate triplets, Dask."""

from __future__ import annotations

import numpy as np
import pytest

import skinrender as sr
from skinrender.errors import SkinrenderError
from skinrender.evaluation.gamut import gamut_calibration, gamut_all_calibrations
from skinrender.design.bank import positions_grid, sensor_bank, triplets
from skinrender.design.criteria import triplet_volumes_fast, triplet_volumes_naive
from skinrender.design.search import WORKERS_MAX, SearchResult, search
from skinrender.spectra import GRID_DEFAULT

POSITIONS_SMALL = "400:700:50"  # 7 positions, 35 triplets


@pytest.fixture(scope="module")
def sets():
    return sr.reflectances("skin").on(GRID_DEFAULT), sr.reflectances("munsell").on(GRID_DEFAULT)


class TestTriplets:
    def test_count_of_the_paper_grid(self):
        assert len(triplets(positions_grid().size)) == 4495

    def test_ascending_distinct(self):
        index = triplets(7)
        assert np.all(index[:, 0] < index[:, 1]) and np.all(index[:, 1] < index[:, 2])
        assert len({tuple(t) for t in index}) == 35

    @pytest.mark.parametrize("spec", ["400:700", "700:400:10", "a:b:c", [400, 500]])
    def test_bad_positions(self, spec):
        with pytest.raises(SkinrenderError, match="positions"):
            positions_grid(spec)


class TestVolumes:
    @pytest.mark.parametrize("sensor", [1, 3, 15])
    def test_fast_equals_naive_triplet_by_triplet(self, sets, sensor):
        where = positions_grid("400:700:75")
        for values in sets:
            bank = sensor_bank(sensor, values, where)
            for triplet in triplets(where.size):
                naive = triplet_volumes_naive(bank, triplet)
                fast = triplet_volumes_fast(bank, triplet)
                np.testing.assert_allclose(fast, naive, rtol=1e-9, atol=0)

    def test_naive_matches_the_gamut_module(self, sets):
        """The bank's volumes are those of gamut_calibration / gamut_all_calibrations for that camera."""
        skin, _ = sets
        bank = sensor_bank(9, skin, positions_grid(POSITIONS_SMALL))
        volumes = triplet_volumes_fast(bank, [1, 3, 5])  # 450, 550, 650 nm
        camera = "gbell:9@450,550,650"
        assert volumes[4] == pytest.approx(gamut_calibration(camera, skin, 3300).volume, rel=1e-9)
        assert volumes[-1] == pytest.approx(gamut_all_calibrations(camera, skin).volume, rel=1e-9)

    def test_collapsing_triplets_give_zero_not_an_error(self):
        """Grey chips under one illuminant lie on a line: all volumes 0, ratios undefined, no exception.

        (Under several prevailing illuminants the grey lines fan out and span a real volume.)"""
        grey = np.linspace(0.05, 0.9, 40)[:, None] * np.ones(GRID_DEFAULT.size)
        result = search(9, grey, grey, POSITIONS_SMALL, illuminants=[3300.0], workers=1)
        assert np.all(result.skin == 0) and np.all(result.munsell == 0)
        assert np.all(np.isnan(result.ratio))
        assert result.table()["min_ratio"] == []

    def test_knee_uses_the_straightforward_method(self, sets):
        skin, _ = sets
        bank = sensor_bank(9, skin, positions_grid(POSITIONS_SMALL), normalization="560nm", knee=True)
        np.testing.assert_array_equal(triplet_volumes_fast(bank, [0, 3, 6]), triplet_volumes_naive(bank, [0, 3, 6]))


class TestSearch:
    def test_fast_search_equals_naive_search_and_its_rows(self, sets):
        fast = search(7, *sets, POSITIONS_SMALL, workers=1)
        naive = search(7, *sets, POSITIONS_SMALL, workers=1, method="naive")
        np.testing.assert_allclose(fast.skin, naive.skin, rtol=1e-9)
        np.testing.assert_allclose(fast.munsell, naive.munsell, rtol=1e-9)
        for key in ("max_skin", "max_munsell", "min_ratio"):
            a, b = fast.table()[key], naive.table()[key]
            assert [(r["triplet"], r["temperature_K"]) for r in a] == [(r["triplet"], r["temperature_K"]) for r in b]

    def test_rows_are_argmax_and_argmin(self, sets):
        result = search(9, *sets, POSITIONS_SMALL, workers=1)
        table = result.table()
        one = [r for r in table["max_skin"] if r["temperature_K"] is not None]
        assert one[0]["value"] == pytest.approx(result.skin[:, :-1].max())
        every = [r for r in table["min_ratio"] if r["temperature_K"] is None]
        assert every[0]["value"] == pytest.approx(np.nanmin(result.ratio[:, -1]))

    def test_processes_give_the_same_volumes(self, sets):
        one = search(5, *sets, POSITIONS_SMALL, workers=1)
        two = search(5, *sets, POSITIONS_SMALL, workers=2)
        np.testing.assert_array_equal(one.skin, two.skin)
        np.testing.assert_array_equal(one.munsell, two.munsell)

    def test_dask_local_cluster_gives_the_same_volumes(self, sets):
        distributed = pytest.importorskip("distributed")
        with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                      dashboard_address=None) as cluster, distributed.Client(cluster) as client:
            remote = search(5, *sets, POSITIONS_SMALL, dask=client)
            by_address = search(5, *sets, POSITIONS_SMALL, dask=cluster.scheduler_address)
        local = search(5, *sets, POSITIONS_SMALL, workers=1)
        np.testing.assert_array_equal(remote.munsell, local.munsell)
        np.testing.assert_array_equal(by_address.skin, local.skin)

    def test_ties_are_all_reported(self):
        temperatures = np.array([2000.0, 3000.0])
        skin = np.array([[1.0, 2.0, 5.0], [2.0, 2.0, 5.0], [1.0, 1.0, 3.0]])
        munsell = np.array([[10.0, 10.0, 50.0], [20.0, 40.0, 50.0], [10.0, 20.0, 30.0]])
        result = SearchResult(9, 2, np.arange(5.0), np.array([[1, 2, 3], [1, 2, 4], [1, 3, 4.0]]), temperatures,
                              skin, munsell, 0.0)
        table = result.table()
        max_one = [(r["triplet"], r["temperature_K"]) for r in table["max_skin"] if r["temperature_K"]]
        assert max_one == [([1.0, 2.0, 3.0], 3000.0), ([1.0, 2.0, 4.0], 2000.0), ([1.0, 2.0, 4.0], 3000.0)]
        max_all = [r["triplet"] for r in table["max_skin"] if r["temperature_K"] is None]
        assert max_all == [[1.0, 2.0, 3.0], [1.0, 2.0, 4.0]]
        min_ratio = [(r["triplet"], r["temperature_K"]) for r in table["min_ratio"] if r["temperature_K"]]
        assert min_ratio == [([1.0, 2.0, 4.0], 3000.0), ([1.0, 3.0, 4.0], 3000.0)]  # 2/40 = 1/20 = 0.05

    def test_csv_has_every_triplet(self, sets, tmp_path):
        result = search(3, *sets, POSITIONS_SMALL, workers=1)
        path = tmp_path / "volumes.csv"
        result.to_csv(path)
        data = np.genfromtxt(path, delimiter=",", names=True)
        assert data.shape == (35,)
        np.testing.assert_allclose(data["munsell_all"], result.munsell[:, -1], rtol=1e-15)
        np.testing.assert_allclose(data["p3_nm"], result.triplets[:, 2])

    def test_bad_method_and_workers(self, sets):
        with pytest.raises(SkinrenderError, match="method"):
            search(3, *sets, POSITIONS_SMALL, method="quick")
        for workers in (0, True, 2.0, WORKERS_MAX + 1):  # one check, shared with the studies (check_workers)
            with pytest.raises(SkinrenderError, match="workers must be an integer"):
                search(3, *sets, POSITIONS_SMALL, workers=workers)
        assert search(3, *sets, "400:700:100", workers=np.int64(1)).workers == 1
        with pytest.raises(SkinrenderError, match="sensor"):
            sensor_bank(-1, sets[0])


def test_detection_criterion_alongside_the_volumes(sets):
    from skinrender.evaluation.locus import false_positive_rate, skin_locus

    result = search(9, *sets, POSITIONS_SMALL, workers=1, detection=True)
    assert result.fpr.shape == (35, 10) and np.all((result.fpr >= 0) & (result.fpr <= 1))
    # one entry against the direct route: locus of the camera, one calibration, Munsell inside it
    t = 12
    p1, p2, p3 = (int(v) for v in result.triplets[t])
    locus = skin_locus(f"gbell:9@{p1},{p2},{p3}", "skin", calibration=5900.0)
    assert result.fpr[t, 7] == pytest.approx(false_positive_rate(locus, f"gbell:9@{p1},{p2},{p3}", "munsell"))
    rows = result.table()["min_fpr"]
    assert rows and rows[0]["value"] == pytest.approx(np.nanmin(result.fpr))
    two = search(9, *sets, POSITIONS_SMALL, workers=2, detection=True)
    np.testing.assert_array_equal(two.fpr, result.fpr)
