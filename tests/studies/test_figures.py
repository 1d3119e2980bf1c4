"""
Tests for :mod:`skinrender.studies.figures`: the labelled pictures (chart, face, ladder) from arrays alone (no
render), each a PNG a person can read: written, an image of the expected shape, its panels in place.
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.studies.figures import DPI, display_srgb, figure_chart, figure_face, figure_ladder

pytest.importorskip("matplotlib")

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def png_size(path) -> tuple[int, int]:
    """(width, height) of a PNG, from its header."""
    data = path.read_bytes()
    assert data[:8] == PNG_SIGNATURE, f"{path} is not a PNG"
    return int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")


def chart(columns: int = 3, rows: int = 2, patch: int = 6, gap: int = 2):
    """A tiny chart image (output units) with its patch boxes, names and skin flags."""
    width, height = columns * (patch + gap) + gap, rows * (patch + gap) + gap
    image = np.zeros((height, width, 3))
    boxes, names, skin = [], [], []
    for i in range(columns * rows):
        row, column = divmod(i, columns)
        x0, y0 = gap + column * (patch + gap), gap + row * (patch + gap)
        boxes.append((x0, y0, x0 + patch, y0 + patch))
        image[y0:y0 + patch, x0:x0 + patch] = 40.0 * (i + 1)
        names.append(f"patch number {i} with a long name")
        skin.append(i % 2 == 0)
    return image, boxes, names, skin


def face(size: int = 20):
    """A disc of skin (label 1) beside a square prop (label 2) on a black background, output units."""
    y, x = np.mgrid[:size, :size]
    labels = np.zeros((size, size), int)
    labels[(x - size / 3) ** 2 + (y - size / 2) ** 2 < (size / 4) ** 2] = 1
    labels[2:6, -6:-2] = 2
    image = np.where(labels[..., None] > 0, [200.0, 150.0, 110.0], 0.0)
    return image, labels


class TestDisplaySrgb:
    def test_white_is_one_and_black_zero(self):
        shown = display_srgb(np.array([[0.0, 0.0, 0.0], [255.0, 255.0, 255.0], [1e4, -5.0, np.nan]]))
        np.testing.assert_allclose(shown, [[0, 0, 0], [1, 1, 1], [1, 0, 0]], atol=1e-12)

    def test_n_dimensional(self):
        image = np.linspace(0, 255, 24).reshape(2, 4, 3)
        np.testing.assert_allclose(display_srgb(image).reshape(-1, 3), display_srgb(image.reshape(-1, 3)))

    def test_transfer_curve_is_monotonic_and_brightens_the_mid_tones(self):
        shown = display_srgb(np.linspace(0, 255, 256)[:, None].repeat(3, 1))[:, 0]
        assert np.all(np.diff(shown) > 0) and shown[64] > 64 / 255


class TestFigureChart:
    def test_render_only_is_one_panel_of_the_chart_shape(self, tmp_path):
        image, boxes, names, skin = chart()
        path = figure_chart(image, boxes, names, skin, "a chart", tmp_path / "c.png")
        width, height = png_size(path)
        # about 1.45 in per patch column: three columns are several hundred pixels wide, a readable size
        assert width >= 3 * 1.4 * DPI and height < width

    def test_with_a_mask_adds_a_second_panel_below(self, tmp_path):
        image, boxes, names, skin = chart()
        one = png_size(figure_chart(image, boxes, names, skin, "t", tmp_path / "one.png"))
        two = png_size(figure_chart(image, boxes, names, skin, "t", tmp_path / "two.png",
                                    mask=image[..., 0] > 100, fractions=[0.5] * (len(boxes) - 1) + [None]))
        assert two[0] == one[0] and two[1] > 1.6 * one[1]


    def test_a_long_title_on_a_narrow_chart_is_wrapped_not_clipped(self, tmp_path):
        """The title wraps to the figure's width: the PNG's left and right edges stay blank (white)."""
        image, boxes, names, skin = chart(columns=2, rows=1)
        title = ("macbeth through gbell:9@450,540,610, 2856 K white-balanced to 5900 K, 4 spp: TPR undefined "
                 "(the chart has no skin patch), FPR 0.160")
        path = figure_chart(image, boxes, names, skin, title, tmp_path / "narrow.png",
                            mask=image[..., 0] > 100, fractions=[0.5] * len(boxes))
        matplotlib_image = pytest.importorskip("matplotlib.image")
        pixels = matplotlib_image.imread(path)[..., :3]
        edges = np.concatenate([pixels[:, :3], pixels[:, -3:]], axis=1)
        assert edges.min() > 0.95, "the title runs off the figure's edge"


class TestFigureFace:
    def test_render_and_overlay(self, tmp_path):
        image, labels = face()
        names = {"background": 0, "skin": 1, "wood": 2}
        alone = png_size(figure_face(image, labels, names, "a face", tmp_path / "f.png"))
        both = png_size(figure_face(image, labels, names, "TPR 1, FPR 0", tmp_path / "d.png", mask=labels == 1))
        assert both[0] > 1.6 * alone[0]

    def test_a_label_not_in_view_is_left_out(self, tmp_path):
        image, labels = face()
        path = figure_face(image, labels, {"skin": 1, "wood": 2, "hidden": 7}, "t", tmp_path / "f.png",
                           mask=np.zeros_like(labels, bool))
        assert png_size(path)[0] > 0


class TestFigureLadder:
    def test_one_row_per_level(self, tmp_path):
        image, labels = face()
        rng = np.random.default_rng(12345)
        level = {"name": "direct", "image": image, "labels": labels, "detected": labels == 1,
                 "skin_rg": 0.45 + 0.01 * rng.standard_normal((50, 2)), "prop_rg": rng.uniform(0.3, 0.4, (20, 2)),
                 "tpr": 1.0, "fpr": None, "seconds": 0.5, "spp": 4}
        polygon = np.array([[0.4, 0.3], [0.6, 0.3], [0.5, 0.4]])
        analytic = np.array([0.45, 0.33, 0.22])
        names = {"background": 0, "skin": 1, "wood": 2}
        one = png_size(figure_ladder([level], polygon, analytic, "one", tmp_path / "1.png", names))
        three = png_size(figure_ladder([level, {**level, "name": "mixed"}, {**level, "name": "sheen+noise"}],
                                       polygon, analytic, "three", tmp_path / "3.png", names))
        assert three[0] == one[0] and three[1] > 2.2 * one[1]


@pytest.mark.parametrize("count, shape", [(10, (2, 5)), (3, (1, 3)), (12, (3, 5))])
def test_figure_pairs_has_one_panel_per_calibration(count, shape, tmp_path):
    """Figs. 3–5 for any number of illuminants (``reproduce --illuminants`` takes a list of kelvin): one panel per
    calibration, five to a row; three once raised an IndexError on the paper's fixed 2 × 5 grid, twelve would have
    dropped two."""
    from skinrender.studies import figures

    temperatures = np.linspace(2000.0, 10000.0, count)
    volumes = np.random.default_rng(0).uniform(1.0, 2.0, (count, count))
    drawn = {}
    close = figures.pyplot_agg().close

    def keep(figure):
        drawn["axes"] = [a for a in figure.axes if a.get_visible()]
        drawn["grid"] = figure.axes[0].get_subplotspec().get_gridspec().get_geometry()
        close(figure)

    figures.pyplot_agg().close = keep
    try:
        path = figures.figure_pairs(volumes, temperatures, "test", tmp_path / "pairs.png")
    finally:
        figures.pyplot_agg().close = close
    assert png_size(path)[0] > 0
    assert drawn["grid"] == shape and len(drawn["axes"]) == count
    assert [a.get_title() for a in drawn["axes"]] == [f"calibration {t:g} K" for t in temperatures]
