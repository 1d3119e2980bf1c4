"""Tests for :mod:`skinrender.testing.figures`: the difference figure of a failed check is written."""

from __future__ import annotations

import numpy as np

from skinrender.testing.figures import difference_figure, region_z


def test_face_figure(tmp_path, rng):
    labels = np.zeros((20, 16), dtype=np.int32)
    labels[5:15, 4:12] = 1
    image = rng.uniform(0, 255, (20, 16, 3)).astype(np.float32)
    items = ("background / R", "skin / R", "skin NCC / r")
    path = difference_figure(tmp_path / "d" / "f.png", image, image * 1.1, items, np.array([0.5, 9.0, -2.0]),
                             np.full(3, 3.5), {"background": 0, "skin": 1}, "a title", labels=labels)
    assert path.read_bytes()[:4] == b"\x89PNG"


def test_region_z_groups_channels_and_ncc():
    worst, beyond = region_z(("a / R", "a / G", "skin / B", "skin NCC / g"), np.array([0.1, -5.0, 1.0, 4.0]),
                             np.array([3.0, 3.0, 3.0, 4.5]))
    assert worst == {"a": 5.0, "skin": 4.0} and beyond == {"a"}
