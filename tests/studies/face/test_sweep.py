"""
Tests for :mod:`skinrender.studies.face.sweep`: every combination rendered and scored as the ladder scores a
level, the same numbers with one process, two or a Dask cluster, the size refusals before any render, and the
CSV written whole.
"""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.studies.face.sweep import CSV_COLUMNS, FaceSweep, estimate_seconds, face_sweep, spectral_tasks, sweep_tasks
from skinrender.studies.face.ladder import score_rendering

pytest.importorskip("mitsuba")

CAMERA = "gbell:9@450,540,610"
SKINS = ("skin-model:melanin=0.02", "skin-model:melanin=0.4")
LEVELS = ("direct", "interreflection+sheen+mixed+noise")
TINY = {"size": 16, "spp": 4, "seed": 3}


def numbers(rows: list[dict]) -> list[dict]:
    """The rows without their wall times (the only thing allowed to differ between runs)."""
    return [{k: v for k, v in row.items() if k != "seconds"} for row in rows]


SPLIT = {"size": 48, "spp": 32, "seed": 3}
"""Large enough a render that drjit's LLVM backend splits the work and its sums depend on the thread count
(measured: at 48 px and 32 spp two threads and one differ by ~1e-10 in the NCC; at 16 px and 4 spp they agree)."""


@pytest.fixture(scope="module")
def one_worker() -> FaceSweep:
    return face_sweep([CAMERA], [(2856, 5900)], SKINS, LEVELS, workers=1, **TINY)


@pytest.fixture(scope="module")
def split_work() -> FaceSweep:
    return face_sweep([CAMERA], [(2856, 5900)], SKINS, LEVELS[:1], workers=1, **SPLIT)


class TestFaceSweep:
    def test_every_combination_in_order(self, one_worker):
        document = json.loads(json.dumps(one_worker.document(), allow_nan=False))
        rows = document["combinations"]
        assert [(r["skin"], r["level"]) for r in rows] == [(s, level) for s in SKINS for level in LEVELS]
        assert document["renders"] == 4 and document["workers"] == 1 and document["size"] == 16
        for row in rows:
            assert set(row) >= {"camera", "prevailing_K", "calibration_K", "skin", "level", "seconds", "spp",
                                "skin_ncc_mean", "skin_ncc_std", "tpr", "fpr", "undefined"}
            assert row["undefined"] == {}  # the ladder's reasons for a None score: none here
            assert row["camera"] == CAMERA and row["prevailing_K"] == 2856 and row["calibration_K"] == 5900
            # 12 replicates of ⌈4 / 12⌉ spp, each scored with its detection verdict on the Vrhel locus
            assert row["spp"] == 12 and row["replicates"] == 12 and row["seconds"] > 0 and row["skin_pixels"] > 0
            assert row["skin_set"] == "skin" and row["detection"]["verdict"] in ("pass", "fail", "inconclusive")
            assert abs(sum(row["skin_ncc_mean"]) - 1) < 1e-9 and 0 <= row["tpr"] <= 1 and 0 <= row["fpr"] <= 1
        # at the direct level each skin's NCC is Eq. 4's (shading cancels), so the rendered skins move apart
        # as the analytic ones do; the dark skin has fewer pixels bright enough to score
        light, dark = rows[0], rows[2]
        for row in (light, dark):
            assert np.abs(np.subtract(row["skin_ncc_mean"], row["skin_ncc_analytic"])).max() < 3 * max(row["skin_ncc_std"])
        # (the channels whose analytic shift is beyond 3 standard errors of the two means; the dark skin's
        # chromaticity nears the flat surface reflection's, so not every channel moves: here the blue)
        shift = np.subtract(dark["skin_ncc_analytic"], light["skin_ncc_analytic"])
        error = sum(np.asarray(row["skin_ncc_std"]) / np.sqrt(row["skin_pixels"]) for row in (light, dark))
        moved = np.abs(shift) > 3 * error
        assert moved.any()
        assert np.all(np.sign(np.subtract(dark["skin_ncc_mean"], light["skin_ncc_mean"]))[moved] == np.sign(shift)[moved])
        assert dark["skin_pixels"] < light["skin_pixels"]
        assert rows[1]["imager"] == "sony-icx418" and "imager" not in rows[0]

    def test_two_workers_give_the_same_numbers(self, split_work):
        two = face_sweep([CAMERA], [(2856, 5900)], SKINS, LEVELS[:1], workers=2, **SPLIT)
        assert two.workers == 2 and two.variant == split_work.variant
        assert numbers(two.combinations) == numbers(split_work.combinations)

    def test_dask_gives_the_same_numbers(self, split_work):
        distributed = pytest.importorskip("distributed")
        with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                      dashboard_address=None) as cluster, distributed.Client(cluster) as client:
            remote = face_sweep([CAMERA], [(2856, 5900)], SKINS[:1], LEVELS[:1], dask=client, **SPLIT)
        assert remote.dask is not None
        assert numbers(remote.combinations) == numbers(split_work.combinations[:1])

    def test_the_ladders_scores(self, one_worker):
        """The sweep scores a combination exactly as the ladder scores a level: the same replicates (seeds seed,
        seed + 1, … at ⌈spp / 12⌉), their mean scored by score_frame against the ladder's locus, and the same
        detection verdict."""
        from skinrender.studies.face.ladder import ladder

        result = ladder(CAMERA, 2856, 5900, SKINS[1], levels=LEVELS[:1], **TINY)
        theirs, mine = result.levels[0], one_worker.combinations[2]
        for key in ("skin_ncc_mean", "skin_ncc_std", "tpr", "fpr", "skin_pixels", "prop_pixels", "spp"):
            assert mine[key] == theirs[key], key
        assert mine["detection"] == theirs["detection"]
        assert mine["skin_ncc_analytic"] == pytest.approx(result.skin_ncc_analytic, abs=1e-15)

    def test_csv_whole(self, one_worker, tmp_path):
        path = one_worker.to_csv(tmp_path / "deep" / "sweep.csv")
        with open(path, encoding="utf-8", newline="") as handle:
            rows = list(csv.reader(handle))
        assert tuple(rows[0]) == CSV_COLUMNS and len(rows) == 5
        assert [r[0] for r in rows[1:]] == [CAMERA] * 4  # the camera's commas quoted
        assert float(rows[1][CSV_COLUMNS.index("tpr")]) == one_worker.combinations[0]["tpr"]
        assert sorted(p.name for p in path.parent.iterdir()) == ["sweep.csv"]  # no .partial left

    def test_csv_empty_cells_for_none(self, tmp_path):
        row = {"camera": "c", "prevailing_K": 2856.0, "calibration_K": 5900.0, "skin": "s", "level": "direct",
               "seconds": 1.0, "spp": 4, "skin_ncc_mean": None, "skin_ncc_std": None, "tpr": None, "fpr": 0.5,
               "skin_pixels": 0, "prop_pixels": 3, "skin_ncc_analytic": [0.5, 0.3, 0.2]}
        path = FaceSweep("face", [row], size=8, spp=4, seed=0, variant="v", workers=1, elapsed_s=1.0).to_csv(tmp_path / "one.csv")
        with open(path, encoding="utf-8", newline="") as handle:
            cells = dict(zip(CSV_COLUMNS, list(csv.reader(handle))[1]))
        assert cells["skin_ncc_mean_r"] == "" and cells["tpr"] == "" and cells["fpr"] == "0.5"


def test_score_rendering_counts_only_lit_pixels():
    """A dark skin pixel (below 10 output units) is not scored; a prop inside the locus is a false positive."""

    class Rendering:
        image = np.array([[[200.0, 100.0, 50.0], [5.0, 3.0, 1.0], [200.0, 100.0, 50.0], [0.0, 0.0, 0.0]]])
        labels = np.array([[1, 1, 2, 0]])

    class Everything:
        @staticmethod
        def contains(points):
            return np.ones(points.shape[:-1], dtype=bool)

    score = score_rendering(Rendering(), Everything())
    assert score["skin_pixels"] == 1 and score["prop_pixels"] == 1
    assert score["tpr"] == 1.0 and score["fpr"] == 1.0
    assert score["skin_ncc_mean"] == pytest.approx([200 / 350, 100 / 350, 50 / 350]) and score["skin_ncc_std"] == [0, 0, 0]


def test_tasks_cameras_outermost():
    tasks = sweep_tasks(["a", "b"], [(1.0, 2.0), (3.0, 4.0)], ["s"], ["x", "y"])
    assert len(tasks) == 8 and tasks[0] == ("a", 1.0, 2.0, "s", "x") and tasks[-1] == ("b", 3.0, 4.0, "s", "y")


def test_estimate_grows_with_samples():
    assert estimate_seconds(10, 256 * 256, 64) > estimate_seconds(10, 64 * 64, 64) > estimate_seconds(1, 64 * 64, 64)


def test_estimate_and_cap_count_each_level_at_its_cost():
    """A subsurface-volume render costs its own rate (samples/s): its estimate and its share of max_samples are larger;
    a fast subsurface render costs the base's rate and its table once per skin."""
    from skinrender.rendering.face.effects import physics_level

    ratio = physics_level("direct").samples_per_s / physics_level("subsurface-volume").samples_per_s
    base = estimate_seconds(2, 64 * 64, 32, levels=["direct", "direct"])
    assert base == pytest.approx(estimate_seconds(2, 64 * 64, 32))
    slow = estimate_seconds(2, 64 * 64, 32, levels=["direct", "sheen+subsurface-volume"])
    assert slow > 5 * base and ratio > 10  # 30 (9e5 against 3e4 samples/s); a render's fixed cost aside
    arguments = {"cameras": [CAMERA], "lights": [(2856, 5900)], "skins": SKINS[:1], "size": 16, "spp": 4,
                 "max_samples": 16 * 16 * 4 * 10}
    with pytest.raises(SkinrenderError, match=r"at subsurface-volume a sample counts as \d+ at the base's rate.*max-samples"):
        face_sweep(levels=["direct", "subsurface-volume"], **arguments)
    fast = physics_level("subsurface")
    assert fast.samples_per_s == physics_level("direct").samples_per_s and fast.setup_seconds > 0
    assert estimate_seconds(4, 64 * 64, 32, cores=1, levels=["subsurface"] * 4, skins=3) == pytest.approx(
        estimate_seconds(4, 64 * 64, 32, cores=1) + 3 * fast.setup_seconds)


@pytest.mark.parametrize("kwargs, match", [
    ({"levels": ()}, "levels"), ({"levels": ("glossy",)}, "physics"), ({"skins": ("skin:nobody",)}, "skin"),
    ({"lights": [("x", 5900)]}, "illuminant"), ({"cameras": ["gbell:9@450"]}, "camera|peak|triplet|three"),
    ({"workers": 0}, "workers"), ({"size": 0}, "size"), ({"spp": 0}, "spp"), ({"seed": -1}, "seed"),
    ({"max_renders": 3}, "4 renders.*max-renders"), ({"max_samples": 100}, "256 samples.*max-samples"),
    ({"size": 3000}, "pixels"),
])
def test_refusals_before_any_render(kwargs, match):
    arguments = {"cameras": [CAMERA], "lights": [(2856, 5900)], "skins": SKINS, "levels": LEVELS, "size": 8,
                 "spp": 1, **kwargs}
    with pytest.raises(SkinrenderError, match=match):
        face_sweep(**arguments)


def test_a_spectral_sweep_renders_once_per_light_skin_and_level():
    """Two cameras × two calibrations of one prevailing light: one spectral render (50 nm bands), four rows in the
    order of one render per combination, each camera's own analytic NCC; the same rows' keys one render each."""
    lights = [(2856.0, 5900.0), (2856.0, 2856.0)]
    cams = [CAMERA, "Nikon 5100 (NPL)"]
    spectral = face_sweep(cams, lights, SKINS[:1], ["direct"], bands="400:700:50", workers=1, **TINY)
    direct = face_sweep(cams, lights, SKINS[:1], ["direct"], spectral=False, workers=1, **TINY)
    keys = lambda sweep: [(r["camera"], r["calibration_K"]) for r in sweep.combinations]  # noqa: E731
    assert keys(spectral) == keys(direct) == [(c, k) for c in cams for _, k in lights]
    assert spectral.document()["spectral"] == {"bands_nm": "400:700:50", "bands": 7, "basis": "hat", "renders": 1}
    assert direct.document()["spectral"] is None
    assert [r["skin_ncc_analytic"] for r in spectral.combinations] == [r["skin_ncc_analytic"]
                                                                       for r in direct.combinations]
    assert len(spectral_tasks(cams, lights, SKINS, LEVELS)) == len(SKINS) * len(LEVELS)
    with pytest.raises(SkinrenderError, match="outside the bands"):
        face_sweep(cams, lights, SKINS[:1], ["direct"], bands="450:650:10", workers=1, **TINY)

