"""
The notebooks under notebooks/: each is paired with a jupytext percent script (``NN_name.py``) that holds
the same cells, and each executes without an error cell (``slow``).

Edit either side and sync the other with ``jupytext --sync notebooks/NN_name.ipynb`` (the pairing is in the
notebook's metadata); the test below fails while the two differ.
"""

from __future__ import annotations

from pathlib import Path

import pytest

ROOT_NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks"
NOTEBOOKS = sorted(ROOT_NOTEBOOKS.glob("*.ipynb"))


def cells(path: Path) -> list[tuple[str, str]]:
    """(type, source) of every cell of a notebook or its paired script, as jupytext reads it."""
    jupytext = pytest.importorskip("jupytext")
    return [(cell.cell_type, cell.source.strip()) for cell in jupytext.read(path).cells]


def test_every_notebook_has_its_script():
    """Seven notebooks, each with a ``.py`` beside it, and no script without its notebook."""
    assert len(NOTEBOOKS) == 7
    assert sorted(p.stem for p in ROOT_NOTEBOOKS.glob("*.py")) == [p.stem for p in NOTEBOOKS]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.name for p in NOTEBOOKS])
def test_notebook_and_script_hold_the_same_cells(path):
    """The notebook and its percent script: the same cells, in the same order, of the same type and source."""
    notebook, script = cells(path), cells(path.with_suffix(".py"))
    assert len(notebook) == len(script), f"{path.name}: {len(notebook)} cells, its script {len(script)}"
    for index, (a, b) in enumerate(zip(notebook, script)):
        sync = f"jupytext --sync {path.relative_to(ROOT_NOTEBOOKS.parent)}"
        assert a == b, f"{path.name}, cell {index} differs from its script's: run `{sync}`"


@pytest.mark.slow
@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.name for p in NOTEBOOKS])
def test_notebook_executes(path):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    notebook = nbformat.read(path, as_version=4)
    client = nbclient.NotebookClient(notebook, timeout=600, kernel_name="python3",
                                     resources={"metadata": {"path": str(ROOT_NOTEBOOKS)}})
    client.execute()
    errors = [o for cell in notebook.cells if cell.cell_type == "code" for o in cell.get("outputs", [])
              if o.get("output_type") == "error"]
    assert not errors, errors
