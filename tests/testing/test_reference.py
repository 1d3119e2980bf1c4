"""Tests for :mod:`skinrender.testing.reference`: a reference written and read back, and every damaged or foreign
file reported in one line, never overwritten."""

from __future__ import annotations

import json

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.testing.reference import ReferenceProblem, read_reference, sidecar_of, state, write_reference
from skinrender.testing.regression import Measurement
from skinrender.testing.replicates import region_values

pytest.importorskip("OpenEXR")


@pytest.fixture
def face(rng) -> Measurement:
    """A small synthetic face measurement (channels R, G, B: the names OpenEXR once merged into 'RGB')."""
    image = rng.uniform(0, 200, (6, 5, 3)).astype(np.float32)
    labels = np.zeros((6, 5), dtype=np.int32)
    labels[1:4, 1:4] = 1
    regions = {"background": 0, "skin": 1}
    mean = region_values(image, labels, regions)[0]
    items = ("background / R", "background / G", "background / B", "skin / R", "skin / G", "skin / B",
             "skin NCC / r", "skin NCC / g")
    return Measurement("face", image, labels, ("R", "G", "B"), regions, items, mean, np.full(8, 0.5),
                       np.array([30.0] * 7 + [np.inf]), {"kind": "face", "camera": "c.csv", "spp": 16})


def test_round_trip(face, tmp_path):
    path, sidecar = write_reference(tmp_path / "ref" / "x.exr", face, 0.01)
    assert state(path) == "ours" and sidecar == sidecar_of(path) and sorted(p.name for p in path.parent.iterdir()) \
        == ["x.exr", "x.json"]  # no temporary left
    back = read_reference(path, face)
    np.testing.assert_array_equal(back.image, face.image)
    np.testing.assert_array_equal(back.labels, face.labels)
    np.testing.assert_allclose(back.mean, face.mean, rtol=1e-12)
    assert back.items == face.items and back.dof[-1] == np.inf and back.settings["spp"] == 16
    document = json.loads(sidecar.read_text())
    assert document["compared"]["items"][-1]["dof"] is None and document["regions"] == {"background": 0, "skin": 1}


def test_state_of_missing_and_foreign(face, tmp_path):
    assert state(tmp_path / "none.exr") == "missing"
    (tmp_path / "a.exr").write_bytes(b"not ours")
    with pytest.raises(ReferenceProblem, match="its sidecar a.json is not: it is not a skinrender reference"):
        state(tmp_path / "a.exr")


@pytest.mark.parametrize("change, match", [
    ({"kind": "chart"}, "is the reference of a face, the check renders a chart"),
    ({"items": ("a / R",) * 8}, "the values compared differ"),
    ({"image": np.zeros((7, 5, 3), np.float32)}, "is 5×6 pixels, the render now 5×7"),
])
def test_a_reference_that_does_not_fit_the_check(face, tmp_path, change, match):
    path, _ = write_reference(tmp_path / "x.exr", face, 0.01)
    other = Measurement(**{**face.__dict__, **change})
    with pytest.raises(ReferenceProblem, match=match):
        read_reference(path, other)


@pytest.mark.parametrize("which", ["exr", "sidecar"])
def test_a_reference_that_is_not_a_regular_file_is_refused_unread(face, tmp_path, which):
    """Issue 25: the reference's hash and its sidecar were read whole, whatever they were (a link to /dev/zero)."""
    import os

    path, sidecar = write_reference(tmp_path / "x.exr", face, 0.01)
    target = path if which == "exr" else sidecar
    target.unlink()
    os.mkfifo(target)  # a named pipe: read whole, it would block for ever
    with pytest.raises(ReferenceProblem, match="a named pipe, not a regular file"):
        read_reference(path, face)


@pytest.mark.parametrize("edit", [
    lambda d: [item.update(standard_error=1e30) for item in d["compared"]["items"]],
    lambda d: [item.update(dof=0) for item in d["compared"]["items"]],
    lambda d: d["settings"].update(spp=999),
    lambda d: d.update(statistics_sha256="0" * 64),
], ids=["standard_errors_1e30", "dof_0", "settings", "the_hash_itself"])
def test_a_hand_edited_sidecar_is_refused(face, tmp_path, edit):
    """Issue 36: every standard error set to 1e30, or dof to 0, switched the check off (a different camera
    passed): what a check reads from the sidecar is hashed into the EXR's header, which the sidecar's hash covers."""
    path, sidecar = write_reference(tmp_path / "x.exr", face, 0.01)
    read_reference(path, face)  # as written: fine
    document = json.loads(sidecar.read_text())
    edit(document)
    sidecar.write_text(json.dumps(document))
    with pytest.raises(ReferenceProblem, match="was changed after the reference was written"):
        read_reference(path, face)


def test_a_reference_of_the_old_format_asks_for_regen(face, tmp_path):
    path, sidecar = write_reference(tmp_path / "x.exr", face, 0.01)
    document = json.loads(sidecar.read_text())
    document["skinrender_reference"] = 1
    sidecar.write_text(json.dumps(document))
    assert state(path) == "ours"  # ours: --skinrender-regen may rewrite it
    with pytest.raises(ReferenceProblem, match="written by an older skinrender .*rerun with --skinrender-regen"):
        read_reference(path, face)


def test_the_statistics_hash_is_in_the_exr_header(face, tmp_path):
    from skinrender.rendering.exr import read_exr_attributes
    from skinrender.testing.reference import statistics_sha256

    path, sidecar = write_reference(tmp_path / "x.exr", face, 0.01)
    document = json.loads(sidecar.read_text())
    assert read_exr_attributes(path)["statistics_sha256"] == document["statistics_sha256"] == statistics_sha256(
        document)


def test_the_reference_seed_is_its_own():
    """Issue 36: the reference was rendered with the check's seed, so the check's samples were its first ones (the
    difference's variance 0.55–0.97 of what the test assumed). Its seed is now drawn from the check's by a hash:
    deterministic, never within one of it (the calibration render takes seed + 1), 32-bit, distinct per seed."""
    from skinrender.rendering.settings import SEED_MAX
    from skinrender.testing.reference import reference_seed

    seeds = [0, 1, 2, 1000, SEED_MAX - 1, SEED_MAX]
    drawn = [reference_seed(s) for s in seeds]
    assert drawn == [reference_seed(s) for s in seeds] and len(set(drawn)) == len(seeds)
    assert all(0 <= r <= SEED_MAX and abs(r - s) > 1 for r, s in zip(drawn, seeds))
    for bad in (-1, SEED_MAX + 1, 1.0, True, "0"):
        with pytest.raises(SkinrenderError, match="seed must be an integer"):
            reference_seed(bad)
