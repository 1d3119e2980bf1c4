"""Shared fixtures: a seeded generator and the reference data beside the checkout."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

ROOT_REPOSITORY = Path(__file__).resolve().parents[1]
ROOT_SHARED_DATA = ROOT_REPOSITORY.parent / "shared" / "data"


@pytest.fixture
def rng() -> np.random.Generator:
    """A seeded random generator."""
    return np.random.default_rng(12345)


@pytest.fixture
def shared_data() -> Path:
    """``../shared/data`` beside the checkout; the test is skipped without it."""
    if not ROOT_SHARED_DATA.is_dir():
        pytest.skip(f"reference data not found at {ROOT_SHARED_DATA} (a fresh clone has no ../shared)")
    return ROOT_SHARED_DATA


def sony_dxc930_csv(shared_data: Path, tmp_path: Path) -> Path:
    """The Sony DXC-930 sensitivities with the R and B measurement floors (82.2, 21.2) subtracted."""
    data = np.genfromtxt(shared_data / "camera_sony_dxc930_sfu.csv", delimiter=",", names=True)
    out = tmp_path / "sony_dxc930.csv"
    rows = np.column_stack(
        [data["wavelength_nm"], np.maximum(data["R"] - 82.2, 0), data["G"], np.maximum(data["B"] - 21.2, 0)]
    )
    np.savetxt(out, rows, delimiter=",", header="wavelength_nm,R,G,B", comments="", fmt="%.6g")
    return out


SMALL_CHART = """
name = "small"
columns = 3
patch_px = 10
gap_px = 1
border_px = 1
[[patch]]
reflectance = "macbeth:dark skin"
[[patch]]
reflectance = "macbeth:blue"
[[patch]]
reflectance = "skin:#14"
[[patch]]
reflectance = "macbeth:black 2 (1.5 D)"
[[patch]]
reflectance = "macbeth:yellow"
"""
"""A small chart for fast statistical tests of renders: five patches of 8 × 8 inner pixels and the white."""


@pytest.fixture(scope="session")
def small_chart(tmp_path_factory) -> Path:
    """The path of :data:`SMALL_CHART` as a scene file."""
    path = tmp_path_factory.mktemp("scene") / "small.toml"
    path.write_text(SMALL_CHART)
    return path


@pytest.fixture(autouse=True)
def release_scenes_after_each_test():
    """Each test leaves no Mitsuba scene loaded for the next one on the same worker: scenes kept alive make every
    later render in the process slower (:mod:`skinrender.rendering.loaded`). Measured over the suite on 2 cores:
    released after each test 137 s, after each module 144 s, never 166 s. A test's own module fixtures hold
    arrays, not scenes, and a released scene is loaded again when rendered."""
    yield
    import sys

    if "skinrender.rendering.renderer" in sys.modules:  # nothing to release where nothing rendered
        from skinrender.rendering.loaded import release_scenes

        release_scenes()


LONGEST_FIRST = (
    "tests/test_docs.py",
    "tests/cli/test_subsurface.py",
    "tests/test_notebooks.py",
    "tests/rendering/test_subsurface_chart.py",
    "tests/cli/test_face.py",
)
"""Test files that run longest (``pytest --durations``), started first so that the workers of
``scripts/test.sh`` (pytest-xdist, one file per worker at a time, ``--no-loadscope-reorder``) end together. xdist
would otherwise start the files with the most tests first and leave these, which hold few tests, to the end.
Only the order changes; a file missing here runs in its place."""


def pytest_collection_modifyitems(config, items):
    """
    Put the files of :data:`LONGEST_FIRST` first, in that order, then the tests marked ``slow`` (notebooks, long
    computations) of any other file; the rest keep their collection order. With pytest-xdist a file goes to one
    worker in the order its first test comes, so the long files start at once and short ones fill in behind them.
    """
    rank = {name: index for index, name in enumerate(LONGEST_FIRST)}
    root = Path(str(config.rootpath))

    def key(item):
        try:
            name = Path(str(item.path)).resolve().relative_to(root).as_posix()
        except ValueError:
            name = ""
        return rank.get(name, len(rank)), item.get_closest_marker("slow") is None

    items.sort(key=key)  # stable: the collection order within each rank
