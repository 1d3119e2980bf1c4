"""
Run modules' doctests each in a fresh interpreter state, as pytest's ``--doctest-modules`` would, without
pytest's start-up.

-   ``python tests/doctest_alone.py skinrender.spectra``: one module, in this interpreter; exit 0 when every
    example passes (the failures are printed).
-   ``python tests/doctest_alone.py --serve``: reads module names on standard input, one a line, and for each
    forks a child that imports the module and runs its doctests; answers one JSON line
    ``{"module", "failed", "attempted", "output"}`` a module. Before forking, it imports third-party libraries
    whose import changes neither numpy's printing nor the warning filters (checked: numpy and scipy, and
    matplotlib's pyplot and pandas, which colour-science imports), pytest's doctest checker, and the package's
    ``skinrender/__init__.py`` with what it imports: what a fresh interpreter runs first, to the end, before any
    module ``skinrender.x.y`` (the same for every module, so nothing one module's doctests could rely on another
    for). Not colour-science: its import sets numpy's legacy printing, which a module's doctests must see only
    when that module (or what it calls) imports colour. So each child pays for its module's own imports beyond the
    package's ``__init__`` and for colour's, and nothing of them is shared between modules: no module's doctests
    can rely on another's import. (A package whose ``__init__`` fails to import is not preloaded: each child then
    reports the error.)

Used by ``tests/test_architecture.py::test_doctests_pass_on_their_own``. The option flags are the project's
(``pyproject.toml``: ELLIPSIS, NORMALIZE_WHITESPACE, NUMBER), NUMBER through pytest's own output checker.
Mitsuba and drjit are never imported before a fork (their threads do not survive it).
"""

from __future__ import annotations

import doctest
import gc
import importlib
import io
import json
import os
import sys
from contextlib import redirect_stdout

PRELOADED = ("matplotlib.pyplot", "pandas")
"""Imported by the server before it forks, besides numpy, scipy and pytest's checker (module docstring):
colour-science's heaviest imports (~0.5 s of CPU in each child that imports colour)."""
PACKAGE = "skinrender"
"""Imported by the server before it forks, after :data:`PRELOADED`: its ``__init__`` is what a fresh interpreter
runs before any of its modules (~0.2 s of CPU in every child)."""


def run_module(module_name: str) -> tuple[int, int, str]:
    """``(failed, attempted, output)`` of one module's doctests in this interpreter."""
    from _pytest.doctest import _get_checker, _get_number_flag

    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE | _get_number_flag()
    output = io.StringIO()
    with redirect_stdout(output):
        module = importlib.import_module(module_name)
        runner = doctest.DocTestRunner(checker=_get_checker(), optionflags=flags)
        for test in sorted(doctest.DocTestFinder().find(module, module_name), key=lambda t: t.name):
            if test.examples:  # examples marked +SKIP are not attempted, as pytest skips them
                runner.run(test)
    result = runner.summarize(verbose=False)
    return result.failed, result.attempted, output.getvalue()


def serve() -> None:
    """Answer module names on standard input, each run in a forked child (module docstring)."""
    import warnings

    import numpy as np

    defaults = np.get_printoptions()
    import scipy.optimize  # noqa: F401
    import scipy.stats  # noqa: F401
    from _pytest.doctest import _get_checker

    _get_checker()
    filters = list(warnings.filters)  # scipy's own are there in any interpreter that imports it
    for name in PRELOADED:
        importlib.import_module(name)
    assert np.get_printoptions() == defaults, "a preloaded library changed numpy's printing"
    assert warnings.filters == filters, "a preloaded library changed the warning filters"
    try:
        with redirect_stdout(io.StringIO()):  # standard output is the answers' channel
            importlib.import_module(PACKAGE)
    except BaseException:  # noqa: BLE001  (each child reports it)
        for name in [n for n in sys.modules if n.partition(".")[0] == PACKAGE]:
            del sys.modules[name]
    assert not {"mitsuba", "drjit"} & set(sys.modules), "Mitsuba imported before forking (its threads die in one)"
    # The children's garbage collections leave the preloaded objects alone: without this, the first collection in
    # each child touches every object and so copies every page the server holds (about as slow as the preloads).
    gc.freeze()
    for line in sys.stdin:
        name = line.strip()
        if not name:
            continue
        read, write = os.pipe()
        child = os.fork()
        if child == 0:  # the child: run, report, leave without cleaning up the parent's state
            os.close(read)
            try:
                failed, attempted, output = run_module(name)
            except BaseException as error:  # noqa: BLE001  (an import error is a failure to report)
                failed, attempted, output = 1, 0, f"{type(error).__name__}: {error}"
            with os.fdopen(write, "w") as pipe:
                json.dump({"module": name, "failed": failed, "attempted": attempted, "output": output[-3000:]}, pipe)
            os._exit(0)
        os.close(write)
        with os.fdopen(read) as pipe:
            answer = pipe.read()
        _, status = os.waitpid(child, 0)
        if not answer:
            answer = json.dumps({"module": name, "failed": 1, "attempted": 0,
                                 "output": f"the child died (wait status {status})"})
        sys.stdout.write(answer.replace("\n", " ") + "\n")
        sys.stdout.flush()


def main(argv: list[str]) -> int:
    if argv == ["--serve"]:
        serve()
        return 0
    failed, attempted, output = run_module(argv[0])
    print(output + f"{argv[0]}: {attempted} examples, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
