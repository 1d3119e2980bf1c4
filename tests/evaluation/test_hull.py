"""Tests for :mod:`skinrender.evaluation._hull3d`, the compiled Quickhull of the Stage 3 search, against Qhull."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import ConvexHull

import skinrender.design.bank as bank_module
import skinrender.design.search as search_module
import skinrender.evaluation.hull as hull_module
import skinrender.design.criteria as criteria_module
from skinrender.evaluation.hull import FLAT_SUSPECT, HULL_KERNEL

_hull3d = hull_module.compiled_kernel()
needs_kernel = pytest.mark.skipif(
    _hull3d is None, reason="skinrender was installed without a C compiler; see test_the_kernel_was_built"
)

KERNEL_VS_QHULL = 1e-12
"""Relative volume difference allowed between the kernel and Qhull: both are
exact hulls up to rounding; a point within the kernel's tolerance (1e-12 of the
scaled cloud) of a facet may be kept by one and dropped by the other."""


def kernel(points):
    answer = _hull3d.hull(np.ascontiguousarray(points, dtype=np.float64), FLAT_SUSPECT)
    return None if answer is None else (answer[0], np.frombuffer(answer[1], dtype=np.int32))


def clouds(rng):
    """Clouds of every shape the search meets and some it does not."""
    for count in (4, 5, 12, 100, 1269, 3000):
        yield "gaussian", rng.normal(size=(count, 3))
        sphere = rng.normal(size=(count, 3))
        yield "sphere", sphere / np.linalg.norm(sphere, axis=1)[:, None]  # every point a vertex
        yield "anisotropic", rng.random((count, 3)) * [1.0, 0.05, 30.0]
        yield "cone", np.abs(rng.normal(size=(count, 3))) * rng.random((count, 1))  # like reflectance clouds
        yield "grid", rng.integers(0, 4, size=(count, 3)).astype(float)  # duplicates, coplanar runs
        surface = rng.random((count, 3))
        surface[np.arange(count), rng.integers(0, 3, count)] = rng.integers(0, 2, count)
        yield "cube-surface", surface  # many points on each facet's plane
        yield "duplicates", np.repeat(rng.normal(size=(max(4, count // 10), 3)), 10, axis=0)


def test_the_kernel_was_built():
    """The fast search needs the compiled kernel; pip builds it when a C compiler is present."""
    assert HULL_KERNEL == "quickhull", "skinrender.evaluation._hull3d is missing: reinstall with a C compiler (gcc) present"


@needs_kernel
class TestHull:
    def test_unit_cube_with_interior_points(self, rng):
        corners = np.array(np.meshgrid([0, 1], [0, 1], [0, 1])).reshape(3, -1).T.astype(float)
        points = np.vstack([rng.random((500, 3)) * 0.98 + 0.01, corners])
        volume, vertices = kernel(points)
        assert volume == pytest.approx(1.0, rel=1e-14)
        assert sorted(vertices) == list(range(500, 508))

    def test_volume_and_vertices_equal_qhull(self, rng):
        for shape, points in clouds(rng):
            qhull = ConvexHull(points)
            answer = kernel(points)
            assert answer is not None, shape
            volume, vertices = answer
            assert volume == pytest.approx(qhull.volume, rel=KERNEL_VS_QHULL), shape
            assert np.all(np.diff(vertices) > 0) and vertices.min() >= 0 and vertices.max() < len(points)
            if shape not in ("grid", "cube-surface", "duplicates"):
                # with coplanar or repeated points either may keep one Qhull drops, or the other copy
                assert set(qhull.vertices) == set(vertices), shape
            # what the kernel keeps spans the whole hull
            assert ConvexHull(points[vertices]).volume == pytest.approx(qhull.volume, rel=KERNEL_VS_QHULL)

    def test_diagonal_scaling_scales_the_volume_and_keeps_the_vertices(self, rng):
        points = np.abs(rng.normal(size=(800, 3)))
        scales = np.array([0.03, 2.0, 40.0])
        volume, vertices = kernel(points)
        scaled_volume, scaled_vertices = kernel(points * scales)
        assert scaled_volume == pytest.approx(volume * np.prod(scales), rel=1e-13)
        np.testing.assert_array_equal(vertices, scaled_vertices)

    @pytest.mark.parametrize(
        "points",
        [
            np.zeros((0, 3)),
            np.eye(3),  # three points
            np.ones((10, 3)),  # coincident
            np.outer(np.linspace(0, 1, 30), [1.0, 2.0, 3.0]),  # collinear
            np.c_[np.random.default_rng(1).random((50, 2)), np.zeros(50)],  # flat
            np.c_[np.random.default_rng(2).random((50, 2)), 1e-9 * np.random.default_rng(3).random(50)],  # nearly
        ],
        ids=["empty", "three", "coincident", "collinear", "flat", "nearly-flat"],
    )
    def test_degenerate_clouds_are_declined_for_qhull(self, points):
        assert kernel(points) is None

    def test_very_thin_clouds_go_to_qhull_and_get_the_same_answer(self, rng):
        """Volume below FLAT_SUSPECT·L³ (here 1e-9·L³): the kernel declines and the search's hull
        routine asks Qhull, which answers as gamut() does: each axis scaled to [-1, 1] first, so a
        cloud thin along one axis keeps its volume and only a flat one (coplanar) has volume 0."""
        thin = rng.random((300, 3)) * [1.0, 1e-3, 1e3]
        assert kernel(thin) is None
        volume, vertices = hull_module.hull_volume_vertices(thin)
        assert volume == pytest.approx(ConvexHull(thin).volume, rel=1e-12)
        assert set(vertices) == set(ConvexHull(thin).vertices)
        axis_thin = rng.random((300, 3)) * [1.0, 1e-12, 1.0]
        volume, vertices = hull_module.hull_volume_vertices(axis_thin)
        assert volume > 0 and volume == pytest.approx(criteria_module.gamut(axis_thin).volume, rel=1e-9)
        coplanar = rng.random((300, 3))
        coplanar[:, 2] = 0.3 * coplanar[:, 0] - 2.0 * coplanar[:, 1] + 0.7
        assert hull_module.hull_volume_vertices(coplanar) == (0.0, None)
        assert criteria_module.gamut(coplanar).volume == 0.0

    @pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
    def test_non_finite_points_are_declined(self, rng, bad):
        points = rng.random((20, 3))
        points[7, 1] = bad
        assert kernel(points) is None

    @pytest.mark.parametrize(
        "points",
        [np.zeros((5, 2)), np.zeros((5, 3), dtype=np.float32), np.zeros((3, 5)).T, np.zeros(15)],
        ids=["two-columns", "float32", "not-contiguous", "flat-array"],
    )
    def test_wrong_arrays_are_refused(self, points):
        with pytest.raises(ValueError, match=r"float64 array of shape \(n, 3\)"):
            _hull3d.hull(points, FLAT_SUSPECT)


@needs_kernel
class TestSearchWithoutTheKernel:
    def test_qhull_everywhere_gives_the_same_volumes(self, monkeypatch, rng):
        """With no compiled kernel (installed without a C compiler) every hull goes to Qhull."""
        from skinrender import reflectances
        from skinrender.spectra import GRID_DEFAULT

        bank = bank_module.sensor_bank(9, reflectances("munsell").on(GRID_DEFAULT)[::4], [420, 500, 580, 660])
        with_kernel = [criteria_module.triplet_volumes_fast(bank, t) for t in bank_module.triplets(4)]
        monkeypatch.setattr(hull_module, "_hull3d", None)
        for triplet, expected in zip(bank_module.triplets(4), with_kernel):
            np.testing.assert_allclose(criteria_module.triplet_volumes_fast(bank, triplet), expected, rtol=1e-9)

    def test_the_search_says_once_which_kernel_ran(self, monkeypatch):
        import io

        grey = np.linspace(0.05, 0.9, 12)[:, None] * np.linspace(0.5, 1.5, 301)[None, :] ** np.arange(12)[:, None]
        monkeypatch.setattr(hull_module, "_hull3d", None)
        monkeypatch.setattr(search_module, "HULL_KERNEL", "qhull")
        monkeypatch.setattr(hull_module, "_NOTICED", [])
        stream = io.StringIO()
        for _ in range(2):
            result = search_module.search(9, grey, grey, "400:700:100", workers=1, notice=stream)
        assert result.info["hull_kernel"] == "qhull"
        assert stream.getvalue().count("notice") == 1 and "_hull3d" in stream.getvalue()


@needs_kernel
class TestTripletVolumes:
    """``_hull3d.triplet_volumes``, the whole triplet in one call, against the hull-by-hull Python route."""

    class _HullsOnly:
        """The kernel with its triplet call declining, so that search takes the Python route."""

        hull = staticmethod(_hull3d.hull)

        @staticmethod
        def triplet_volumes(*args):
            return None

    @pytest.mark.parametrize("sensor", [1, 9])
    @pytest.mark.parametrize("name", ["skin", "munsell"])
    def test_one_call_equals_the_python_route(self, monkeypatch, sensor, name):
        from skinrender import reflectances
        from skinrender.spectra import GRID_DEFAULT

        bank = bank_module.sensor_bank(sensor, reflectances(name).on(GRID_DEFAULT), [410, 470, 530, 600, 690])
        chosen = bank_module.triplets(5)
        one_call = [criteria_module.triplet_volumes_fast(bank, t) for t in chosen]
        monkeypatch.setattr(hull_module, "_hull3d", self._HullsOnly)
        for triplet, expected in zip(chosen, one_call):
            np.testing.assert_allclose(criteria_module.triplet_volumes_fast(bank, triplet), expected, rtol=1e-12)

    def test_a_declined_hull_declines_the_triplet(self):
        grey = np.ones((1, 40, 3)) * np.linspace(0.1, 1.0, 40)[None, :, None]  # one collinear cloud
        assert _hull3d.triplet_volumes(grey, np.ones((1, 1, 3)), False, False, FLAT_SUSPECT) is None

    def test_mismatched_gains_are_refused(self, rng):
        with pytest.raises(ValueError, match=r"gains must have shape \(P, Q, 3\)"):
            _hull3d.triplet_volumes(rng.random((3, 50, 3)), np.ones((2, 3, 3)), True, False, FLAT_SUSPECT)
        with pytest.raises(ValueError, match="clouds must be a C-contiguous float64 array"):
            _hull3d.triplet_volumes(rng.random((50, 3)), np.ones((1, 3, 3)), True, False, FLAT_SUSPECT)

    def test_a_coplanar_cloud_that_folded_the_hull_is_declined_and_answered_right(self):
        """Impulse, skin, peaks 420 530 590 nm: the all-calibration cloud (diagonal copies of 30
        spectra, many points coplanar) once made the kernel build a facet facing inwards and lose
        8e-7 of the volume. Such a facet now declines the hull, and Qhull answers."""
        from skinrender import reflectances
        from skinrender.spectra import GRID_DEFAULT

        positions = bank_module.positions_grid()
        bank = bank_module.sensor_bank(1, reflectances("skin").on(GRID_DEFAULT), positions)
        triplet = np.searchsorted(positions, [420, 530, 590])
        clouds, gains = bank.clouds(triplet), bank.gains(triplet)
        everything = np.vstack([clouds[p] * gains[p, q] for p in range(len(clouds)) for q in range(gains.shape[1])])
        centred = everything - everything.mean(axis=0)
        scale = np.max(np.abs(centred), axis=0)
        expected = ConvexHull(centred / scale).volume * np.prod(scale)
        assert criteria_module.triplet_volumes_fast(bank, triplet)[-1] == pytest.approx(expected, rel=1e-12)
        assert criteria_module.triplet_volumes_naive(bank, triplet)[-1] == pytest.approx(expected, rel=1e-12)

    @pytest.mark.parametrize("sensor", [1, 9])
    def test_a_chunk_in_one_call_equals_triplet_by_triplet(self, sensor):
        """``chunk_volumes`` gathers the clouds itself: the same numbers, to the bit, as one call per triplet."""
        from skinrender import reflectances
        from skinrender.spectra import GRID_DEFAULT
        from skinrender.studies.paper.volumes import chunk_gains

        bank = bank_module.sensor_bank(sensor, reflectances("munsell").on(GRID_DEFAULT), [410, 470, 530, 600, 690])
        chosen = bank_module.triplets(5)
        signal = np.ascontiguousarray(bank.signal.transpose(1, 0, 2))
        volumes, declined = _hull3d.chunk_volumes(signal, np.ascontiguousarray(chosen[:, ::-1], dtype=np.int64),
                                                  chunk_gains(bank, chosen), True, bank.diagonal, FLAT_SUSPECT)
        assert declined == bytes(len(chosen))
        expected = [np.frombuffer(_hull3d.triplet_volumes(bank.clouds(t), np.ascontiguousarray(bank.gains(t)), True,
                                                          bank.diagonal, FLAT_SUSPECT), dtype=np.float64)
                    for t in chosen]
        np.testing.assert_array_equal(np.frombuffer(volumes, dtype=np.float64).reshape(len(chosen), -1), expected)

    def test_a_declined_triplet_of_a_chunk_is_flagged_and_nan(self, rng):
        signal = rng.random((5, 1, 40))  # J = 5 positions, P = 1 illuminant, 40 reflectances
        signal[0, 0] = signal[1, 0] = np.linspace(0.1, 1.0, 40)  # positions 0 and 1: one grey ramp
        channels = np.array([[0, 1, 1], [2, 3, 4]], dtype=np.int64)  # the first cloud is collinear
        volumes, declined = _hull3d.chunk_volumes(signal, channels, np.ones((2, 1, 1, 3)), False, False, FLAT_SUSPECT)
        rows = np.frombuffer(volumes, dtype=np.float64).reshape(2, 2)
        assert declined == b"\x01\x00" and np.isnan(rows[0]).all() and (rows[1] > 0).all()

    def test_a_chunk_with_wrong_arrays_is_refused(self, rng):
        signal, gains = rng.random((4, 2, 30)), np.ones((1, 2, 3, 3))
        with pytest.raises(ValueError, match=r"channels must be positions in \[0, J\)"):
            _hull3d.chunk_volumes(signal, np.array([[0, 1, 4]]), gains, True, False, FLAT_SUSPECT)
        with pytest.raises(ValueError, match=r"gains must have shape \(T, P, Q, 3\)"):
            _hull3d.chunk_volumes(signal, np.array([[0, 1, 2]]), np.ones((1, 3, 3, 3)), True, False, FLAT_SUSPECT)
        with pytest.raises(ValueError, match="channels must be a C-contiguous int64 array"):
            _hull3d.chunk_volumes(signal, np.array([[0.0, 1.0, 2.0]]), gains, True, False, FLAT_SUSPECT)
        with pytest.raises(ValueError, match="signal must be a C-contiguous float64 array"):
            _hull3d.chunk_volumes(signal[..., ::2], np.array([[0, 1, 2]]), gains, True, False, FLAT_SUSPECT)


@pytest.fixture
def steps_restored():
    """``_hull3d.steps`` as it was after the test (and its counts reset)."""
    before = _hull3d.steps()[0]
    yield
    _hull3d.steps(int(before))


def _cases_by_qhull(clouds: np.ndarray, gains: np.ndarray) -> np.ndarray:
    """Each calibration case's volume and the all-calibration volume, Qhull on the full point sets."""
    def volume(points):
        centred = points - points.mean(axis=0)
        scale = np.max(np.abs(centred), axis=0)
        return ConvexHull(centred / scale).volume * np.prod(scale)

    cases = [np.vstack([clouds[p] * gains[p, q] for p in range(len(clouds))]) for q in range(gains.shape[1])]
    return np.array([volume(points) for points in cases] + [volume(np.vstack(cases))])


@needs_kernel
class TestSteps:
    """Hulls built from the previous hull's faces (``hull_step``) against hulls built from scratch and Qhull."""

    @pytest.mark.parametrize("sensor", [1, 4, 9])
    @pytest.mark.parametrize("name", ["skin", "munsell"])
    def test_stepped_hulls_equal_hulls_from_scratch(self, sensor, name, steps_restored):
        from skinrender import reflectances
        from skinrender.spectra import GRID_DEFAULT

        positions = bank_module.positions_grid()
        bank = bank_module.sensor_bank(sensor, reflectances(name).on(GRID_DEFAULT), positions)
        chosen = bank_module.triplets(positions.size)[::150]

        def volumes():  # a triplet the kernel declines (a flat cloud) gets Qhull's answer either way
            return np.array([criteria_module.triplet_volumes_fast(bank, t) for t in chosen])

        _hull3d.steps(0)
        scratch = volumes()
        _hull3d.steps(1)
        stepped = volumes()
        enabled, tried, taken = _hull3d.steps()
        np.testing.assert_allclose(stepped, scratch, rtol=KERNEL_VS_QHULL, atol=0)
        assert enabled and taken >= 0.9 * tried  # about 99 % taken, measured
        assert tried >= len(chosen) * (len(bank.temperatures) - 1)  # at least the calibration cases' steps ran

    @pytest.mark.parametrize("sensor", [1, 9])
    def test_stepped_volumes_equal_qhull(self, sensor, steps_restored):
        from skinrender import reflectances
        from skinrender.spectra import GRID_DEFAULT

        positions = bank_module.positions_grid()
        bank = bank_module.sensor_bank(sensor, reflectances("munsell").on(GRID_DEFAULT), positions)
        _hull3d.steps(1)
        for triplet in bank_module.triplets(positions.size)[::900]:
            clouds, gains = bank.clouds(triplet), np.ascontiguousarray(bank.gains(triplet))
            answer = np.frombuffer(_hull3d.triplet_volumes(clouds, gains, True, bank.diagonal, FLAT_SUSPECT))
            np.testing.assert_allclose(answer, _cases_by_qhull(clouds, gains), rtol=KERNEL_VS_QHULL, atol=0)

    @pytest.mark.parametrize("spread", [0.002, 0.02, 0.2, 2.0])
    @pytest.mark.parametrize("shape", ["gaussian", "sphere", "cone"])
    def test_clouds_that_move_more_are_stepped_or_built_afresh_and_right(self, rng, spread, shape, steps_restored):
        """Ten clouds, each the previous one moved by noise of ``spread`` (2.0: unrelated clouds): every
        case equals Qhull's, whether the steps flipped, removed, added or declined."""
        first = {"gaussian": rng.normal(size=(300, 3)), "cone": np.abs(rng.normal(size=(300, 3))) * rng.random((300, 1)),
                 "sphere": rng.normal(size=(300, 3))}[shape]
        if shape == "sphere":
            first /= np.linalg.norm(first, axis=1)[:, None]
        clouds = [first]
        for _ in range(9):
            clouds.append(clouds[-1] + spread * rng.normal(size=first.shape))
        clouds = np.ascontiguousarray(clouds)
        # per (prevailing, calibration) channel gains, each calibration's a little from the previous one's
        drift = 1.0 + 0.01 * np.arange(4)[None, :, None] * rng.normal(size=(10, 1, 3))
        gains = np.ascontiguousarray((1.0 + 0.3 * rng.random((10, 1, 3))) * drift)
        _hull3d.steps(1)
        answer = np.frombuffer(_hull3d.triplet_volumes(clouds, gains, True, False, FLAT_SUSPECT))
        enabled, tried, taken = _hull3d.steps()
        np.testing.assert_allclose(answer, _cases_by_qhull(clouds, gains), rtol=KERNEL_VS_QHULL, atol=0)
        assert tried == 9 + 3  # nine prevailing steps, three calibration-case steps
        if spread <= 0.02:  # small moves are mostly stepped (a step that cannot be certified is declined)
            assert taken >= tried // 2

    def test_steps_can_be_turned_off_and_counted(self, steps_restored):
        clouds = np.ascontiguousarray(np.random.default_rng(1).normal(size=(3, 100, 3)))
        gains = np.ones((3, 2, 3))
        _hull3d.steps(0)
        off = _hull3d.triplet_volumes(clouds, gains, True, False, FLAT_SUSPECT)
        assert _hull3d.steps(1) == (False, 0, 0)
        on = _hull3d.triplet_volumes(clouds, gains, True, False, FLAT_SUSPECT)
        enabled, tried, taken = _hull3d.steps()
        assert enabled and tried == 2 + 1 and _hull3d.steps() == (True, 0, 0)
        np.testing.assert_allclose(np.frombuffer(on), np.frombuffer(off), rtol=KERNEL_VS_QHULL)
