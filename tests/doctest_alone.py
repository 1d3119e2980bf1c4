"""
Run one module's doctests in this (fresh) interpreter, as pytest's ``--doctest-modules`` would, without
pytest's start-up: ``python tests/doctest_alone.py skinrender.spectra``. Exit 0 when every example passes;
the failures are printed. Used by ``tests/test_architecture.py::test_doctests_pass_on_their_own``.

The option flags are the project's (``pyproject.toml``: ELLIPSIS, NORMALIZE_WHITESPACE, NUMBER), NUMBER
through pytest's own output checker.
"""

from __future__ import annotations

import doctest
import importlib
import sys


def main(module_name: str) -> int:
    from _pytest.doctest import _get_checker, _get_number_flag

    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE | _get_number_flag()
    module = importlib.import_module(module_name)
    runner = doctest.DocTestRunner(checker=_get_checker(), optionflags=flags)
    for test in sorted(doctest.DocTestFinder().find(module, module_name), key=lambda t: t.name):
        if test.examples:
            runner.run(test)
    result = runner.summarize(verbose=False)
    print(f"{module_name}: {result.attempted} examples, {result.failed} failed")
    return 1 if result.failed else 0  # examples marked +SKIP are not attempted (as pytest skips them)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
