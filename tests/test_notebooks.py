"""
The notebooks under notebooks/: each is paired with a jupytext percent script (``NN_name.py``) that holds
the same cells, and each executes without an error cell (``slow``), one after the other in one Jupyter
kernel emptied of the previous notebook's names and figures before each.

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


RESET = """\
%reset -f
import gc as _gc, sys as _sys
for _name, _module in list(_sys.modules.items()):
    if _name.partition(".")[0] == "skinrender":
        for _value in list(vars(_module).values()):
            if getattr(_value, "__module__", None) == _name and hasattr(_value, "cache_clear"):
                _value.cache_clear()
if "matplotlib.pyplot" in _sys.modules:
    _sys.modules["matplotlib.pyplot"].close("all")
_gc.collect()
del _gc, _sys
"""
"""Run before each notebook in the shared kernel: no name of an earlier notebook (variables, imported names,
``Out``) and no figure is left, so each notebook runs on its own names; and the package's caches
(``functools.lru_cache``) are emptied, so that the Mitsuba scenes an earlier notebook loaded are released, as
in a kernel of its own (kept loaded, they make later renders several times slower: Mitsuba dispatches over the
objects of every loaded scene)."""


@pytest.fixture(scope="module")
def kernel():
    """One Jupyter kernel (in ``notebooks/``) for the notebooks of this module, emptied before each
    (:data:`RESET`); started anew if a notebook killed it. Starting a kernel and importing colour, matplotlib,
    Mitsuba and skinrender again for every notebook cost ~3 s each; a module imported once stays imported."""
    pytest.importorskip("nbclient")
    from jupyter_client import KernelManager

    manager = KernelManager(kernel_name="python3")

    def ready() -> KernelManager:
        if not manager.has_kernel or not manager.is_alive():
            if manager.has_kernel:
                manager.cleanup_resources()
            manager.start_kernel(cwd=str(ROOT_NOTEBOOKS))
        return manager

    yield ready
    if manager.has_kernel:
        manager.shutdown_kernel(now=True)


def execute(notebook, manager) -> None:
    """Run every cell of ``notebook`` (in place) in the kernel of ``manager``, as ``jupyter nbconvert --execute``
    does: a cell that raises stops the run with its error (nbclient's CellExecutionError)."""
    import nbclient

    client = nbclient.NotebookClient(notebook, km=manager, timeout=600, kernel_name="python3",
                                     resources={"metadata": {"path": str(ROOT_NOTEBOOKS)}})
    try:
        client.execute()
    finally:
        if client.kc is not None:
            client.kc.stop_channels()


@pytest.mark.slow
@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.name for p in NOTEBOOKS])
def test_notebook_executes(path, kernel):
    """Every cell runs without an error, in a kernel holding none of an earlier notebook's names."""
    nbformat = pytest.importorskip("nbformat")
    manager = kernel()
    execute(nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(RESET)]), manager)
    notebook = nbformat.read(path, as_version=4)
    execute(notebook, manager)
    errors = [o for cell in notebook.cells if cell.cell_type == "code" for o in cell.get("outputs", [])
              if o.get("output_type") == "error"]
    assert not errors, errors


@pytest.mark.slow
def test_a_notebook_sees_no_name_of_the_one_before(kernel):
    """The shared kernel is emptied between notebooks: a name, an imported module's name, a figure and the
    package's cached results (here the imager presets) of one notebook are gone in the next."""
    nbformat = pytest.importorskip("nbformat")
    pytest.importorskip("matplotlib")
    cell, new = nbformat.v4.new_code_cell, nbformat.v4.new_notebook
    manager = kernel()
    execute(new(cells=[cell(RESET)]), manager)
    before = new(cells=[cell("import matplotlib\nmatplotlib.use('Agg')\nimport matplotlib.pyplot as plt\n"
                             "from skinrender.model import imager\n"
                             "from skinrender.model.imager import list_imagers\n"
                             "left_behind = plt.figure().number\nlist_imagers()\n"
                             "print(imager._presets.cache_info().currsize)")])
    execute(before, manager)
    assert before.cells[0].outputs[0]["text"].strip() == "1"  # the cache below held something
    execute(new(cells=[cell(RESET)]), manager)
    after = new(cells=[cell("import sys\n"
                            "names = {'left_behind', 'plt', 'matplotlib', 'imager', 'list_imagers'} & set(dir())\n"
                            "print(sorted(names), sys.modules['matplotlib.pyplot'].get_fignums(), "
                            "sys.modules['skinrender.model.imager']._presets.cache_info().currsize)")])
    execute(after, manager)
    assert after.cells[0].outputs[0]["text"].strip() == "[] [] 0"
