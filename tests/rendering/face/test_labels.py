"""Tests for :mod:`skinrender.rendering.face.labels`: label names and ids, and the interior of a label."""

from __future__ import annotations

import numpy as np

from skinrender.rendering.face.labels import (LABEL_BACKGROUND, LABEL_SKIN, SHAPE_SKIN, interior, label_names,
                                              prop_shape_id, shape_labels)
from skinrender.rendering.face.scene import load_face_scene


class TestLabelNames:
    def test_background_skin_then_props_in_file_order(self):
        scene = load_face_scene("face")
        names = label_names(scene)
        assert names["background"] == LABEL_BACKGROUND == 0 and names["skin"] == LABEL_SKIN == 1
        assert [names[p.name] for p in scene.props] == list(range(2, 2 + len(scene.props)))
        shapes = shape_labels(scene)
        assert shapes[SHAPE_SKIN] == 1 and shapes[prop_shape_id(0)] == 2
        assert sorted(shapes.values()) == sorted(set(names.values()) - {0})


class TestInterior:
    def test_erosion(self):
        image = np.zeros((7, 7), dtype=int)
        image[1:6, 1:6] = 3
        assert interior(image, 3).sum() == 9
        assert interior(image, 3, margin=2).sum() == 1
        assert interior(image, 0).sum() == 0  # the frame of zeros touches the image border or the square

    def test_tiny_images(self):
        assert interior(np.ones((2, 2), dtype=int), 1).sum() == 0
