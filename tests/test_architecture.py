"""
The house rules of the package (docs/architecture.md, CONTRIBUTING.md): layers kept by
import-linter, no import cycles, one meaning per ``skinrender.<name>``, no
two module names a letter apart, small modules, doctests that pass on their
own, and a core that runs without the optional extras.
"""

from __future__ import annotations

import functools
import importlib
import json
import pkgutil
import subprocess
import sys
from pathlib import Path

import pytest

import skinrender

ROOT = Path(skinrender.__file__).parent
REPOSITORY = ROOT.parent
LAYER_MODULES = {"constants", "errors", "files", "hints", "workload", "execution", "toml_tables", "spectra", "spectral_csv", "methods",
                 "extras", "datasets", "model", "evaluation", "design", "rendering", "studies", "cli", "testing"}
"""What ``skinrender.<name>`` may be when it is a module."""
MODULE_LINES_MAX = 450
"""'None over ~400 lines': the largest module may exceed 400 by little."""


def modules() -> list[str]:
    """Every module of the package, dotted."""
    return sorted(m.name for m in pkgutil.walk_packages([str(ROOT)], "skinrender.") if not m.name.endswith("_hull3d"))


def source_of(module: str) -> Path:
    """The file of a dotted module name (a package's ``__init__.py``)."""
    path = ROOT.joinpath(*module.split(".")[1:]) if module != "skinrender" else ROOT
    return path / "__init__.py" if path.is_dir() else path.with_suffix(".py")


def test_import_linter_contracts_are_kept():
    """The layers (and the figures/render-extra rules) of pyproject.toml hold."""
    importlinter_cli = pytest.importorskip("importlinter.cli")
    code = importlinter_cli.lint_imports(config_filename=str(REPOSITORY / "pyproject.toml"), no_cache=True)
    assert code == 0, "import-linter found a broken contract: run `lint-imports` for the details"


def test_no_import_cycles():
    """No module imports (at module level or inside a function) a module that imports it back, directly or not.

    A package's ``__init__`` importing its own modules is not counted (the command line's registry does)."""
    grimp = pytest.importorskip("grimp")
    graph = grimp.build_graph("skinrender")
    cycles = []
    for importer in sorted(graph.modules):
        for imported in graph.find_modules_directly_imported_by(importer):
            if importer.startswith(imported + ".") or imported.startswith(importer + "."):
                continue
            chain = graph.find_shortest_chain(importer=imported, imported=importer)
            if chain:
                cycles.append(" -> ".join((importer, *chain)))
    assert cycles == []


def test_one_meaning_per_top_level_name():
    """``skinrender.<name>`` is a layer module or a public object, never a module shadowed by a function."""
    for name in skinrender.__all__:
        assert not isinstance(getattr(skinrender, name), type(skinrender)), f"skinrender.{name} is a module"
    for name, value in vars(skinrender).items():
        # "@py_builtins", "@pytest_ar": pytest's assertion rewriting, which marks the whole package once its
        # pytest11 entry point (skinrender.testing.plugin) is installed; never a Python name
        if isinstance(value, type(skinrender)) and not name.startswith(("_", "@")):
            assert name in LAYER_MODULES, f"skinrender.{name} is a module outside the layers"
    for package in ("model", "evaluation", "design", "rendering", "studies", "cli", "datasets", "testing"):
        module = importlib.import_module(f"skinrender.{package}")
        for info in pkgutil.iter_modules(module.__path__):
            value = getattr(module, info.name, None)
            importlib.import_module(f"skinrender.{package}.{info.name}")
            value = getattr(module, info.name)
            assert isinstance(value, type(skinrender)), f"skinrender.{package}.{info.name} is not its module"


def test_no_two_module_names_a_letter_apart():
    """``illuminant`` beside ``illuminants`` confused readers: no two module names differ by one letter."""
    names = sorted({m.rpartition(".")[2] for m in modules()} - {"__init__"})

    def one_apart(a: str, b: str) -> bool:
        if abs(len(a) - len(b)) > 1 or a == b:
            return False
        if len(a) == len(b):
            return sum(x != y for x, y in zip(a, b)) == 1
        short, long = sorted((a, b), key=len)
        return any(long[:i] + long[i + 1:] == short for i in range(len(long)))

    pairs = [(a, b) for i, a in enumerate(names) for b in names[i + 1:] if one_apart(a, b)]
    assert not pairs


def test_modules_are_small():
    """One job per module: none over :data:`MODULE_LINES_MAX` lines (the C kernel aside)."""
    sizes = {str(p.relative_to(ROOT)): len(p.read_text(encoding="utf-8").splitlines()) for p in ROOT.rglob("*.py")}
    assert {k: v for k, v in sizes.items() if v > MODULE_LINES_MAX} == {}


def test_tests_mirror_the_package():
    """Every test module names a module of the package at the same place (tests/model/test_response.py ↔ model/response.py)."""
    tests = REPOSITORY / "tests"
    orphans = []
    for path in tests.rglob("test_*.py"):
        relative = path.relative_to(tests)
        stem = path.stem[len("test_"):]
        target = ROOT.joinpath(*relative.parts[:-1], stem)
        if not (target.with_suffix(".py").exists() or target.is_dir() or stem in {"architecture", "docs", "notebooks", "public_api"}):
            orphans.append(str(relative))
    assert orphans == []


DOCTESTED = sorted(m for m in ["skinrender", *modules()] if ">>>" in source_of(m).read_text(encoding="utf-8"))


DOCTEST_ALONE = Path(__file__).with_name("doctest_alone.py")
"""Runs modules' doctests each in a fresh interpreter state with the project's flags (no pytest start-up)."""


def doctests_alone(module: str, cwd: Path = REPOSITORY, path: str | None = None) -> subprocess.CompletedProcess:
    """``tests/doctest_alone.py MODULE`` in a fresh interpreter (``path`` prepended to its import path)."""
    env = None
    if path is not None:
        import os

        env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [path, os.environ.get("PYTHONPATH")]))}
    return subprocess.run([sys.executable, str(DOCTEST_ALONE), module], capture_output=True, text=True, cwd=cwd,
                          env=env)


@pytest.fixture(scope="module")
def doctest_examples(tmp_path_factory) -> Path:
    """A folder on the doctest server's import path, for example modules written by the tests."""
    return tmp_path_factory.mktemp("doctest_examples")


@pytest.fixture(scope="module")
def doctest_server(doctest_examples):
    """``doctest_alone.py --serve``: each module's doctests in a child forked from an interpreter that imported
    only third-party libraries and the package's ``__init__`` (what a fresh interpreter runs before any module of
    the package), not this test worker; :func:`doctest_examples` is on its import path."""
    import os

    path = os.pathsep.join(filter(None, [os.environ.get("PYTHONPATH"), str(doctest_examples)]))
    server = subprocess.Popen([sys.executable, str(DOCTEST_ALONE), "--serve"], stdin=subprocess.PIPE,
                              stdout=subprocess.PIPE, text=True, cwd=REPOSITORY,
                              env={**os.environ, "PYTHONPATH": path})

    def run(module: str) -> dict:
        server.stdin.write(module + "\n")
        server.stdin.flush()
        line = server.stdout.readline()
        assert line, f"the doctest server ended (exit {server.poll()})"
        return json.loads(line)

    yield run
    server.stdin.close()
    server.wait(timeout=60)


@pytest.mark.parametrize("module", DOCTESTED)
def test_doctests_pass_on_their_own(module, doctest_server):
    """Each module's doctests in a fresh interpreter state: no reliance on another import changing numpy's
    printing."""
    result = doctest_server(module)
    assert result["failed"] == 0, result["output"]


def test_a_failing_doctest_fails_on_its_own(tmp_path):
    """The runner above fails a module whose example prints something else; NUMBER compares as pytest does."""
    (tmp_path / "wrong_example.py").write_text('"""\n>>> 1 + 1\n3\n"""\n', encoding="utf-8")
    (tmp_path / "number_example.py").write_text('"""\n>>> 1 / 3\n0.333\n"""\n', encoding="utf-8")
    assert doctests_alone("wrong_example", tmp_path, str(tmp_path)).returncode == 1
    assert doctests_alone("number_example", tmp_path, str(tmp_path)).returncode == 0  # NUMBER, as pytest's


def test_the_doctest_server_reports_a_failure(doctest_server):
    """The server's children pass a good module and fail one that cannot be imported."""
    assert doctest_server("skinrender.errors")["failed"] == 0
    assert doctest_server("no_such_module_here")["failed"] == 1


def test_the_doctest_server_children_start_alike(doctest_server, doctest_examples):
    """A child sees numpy's printing and the package's modules as a fresh interpreter would, whatever the child
    before it imported or changed: colour-science's legacy printing only where the module imports colour, and no
    attribute set by another module's doctests."""
    examples = {
        "with_colour": ">>> import numpy as np, colour\n>>> np.float64(0.5)\n0.5\n",
        "without_colour": ">>> import numpy as np\n>>> np.float64(0.5)\nnp.float64(0.5)\n",
        "sets_an_attribute": ">>> import skinrender.errors\n>>> skinrender.errors.LEFT_BEHIND = 1\n",
        "sees_no_attribute": (">>> import skinrender.errors\n"
                              ">>> hasattr(skinrender.errors, 'LEFT_BEHIND')\nFalse\n"),
    }
    for name, example in examples.items():
        (doctest_examples / f"{name}.py").write_text(f'"""\n{example}"""\n', encoding="utf-8")
    for name in ("with_colour", "without_colour", "sets_an_attribute", "sees_no_attribute", "with_colour"):
        result = doctest_server(name)
        assert (result["failed"], result["attempted"] > 0) == (0, True), result


def test_the_pytest_plugin_imports_neither_mitsuba_nor_the_renderer():
    """Every pytest session of a user with skinrender installed loads the plugin (its ``pytest11`` entry point):
    importing it, in a fresh interpreter, imports neither Mitsuba nor ``skinrender.rendering`` (its fixture
    imports what a check needs), and ``import skinrender`` alone imports nothing of the package but itself and its
    Ctrl-C guard."""
    code = ("import json, sys; import {module}; "
            "print(json.dumps(sorted(m for m in sys.modules if m.split('.')[0] in ('skinrender', 'mitsuba', 'drjit'))))")
    seen = {module: json.loads(subprocess.run([sys.executable, "-c", code.format(module=module)], check=True,
                                              capture_output=True, text=True).stdout)
            for module in ("skinrender.testing.plugin", "skinrender")}
    plugin = seen["skinrender.testing.plugin"]
    assert "skinrender.testing.plugin" in plugin
    assert [m for m in plugin if m.startswith(("mitsuba", "drjit", "skinrender.rendering"))] == []
    assert seen["skinrender"] == ["skinrender", "skinrender._interrupt"]  # and the Ctrl-C guard (standard library)


@functools.cache
def _parsed_modules():
    """Every module of the package, parsed: ``(dotted name, syntax tree)``; parsed once per session (the tests
    only read the trees)."""
    import ast

    return [(module, ast.parse(source_of(module).read_text(encoding="utf-8"))) for module in ["skinrender", *modules()]]


def test_no_private_name_is_imported_from_another_module():
    """A name another module needs is public (in its module's ``__all__``); ``_name`` stays in its module. Only a
    compiled kernel's own wrapper imports it (``evaluation.hull`` ← ``_hull3d``)."""
    import ast

    found = []
    for module, tree in _parsed_modules():
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.module != "__future__":
                found += [f"{module}: from {'.' * node.level}{node.module or ''} import {alias.name}"
                          for alias in node.names if alias.name.startswith("_") and not alias.name.startswith("__")
                          and not (module == "skinrender.evaluation.hull" and alias.name == "_hull3d")]
    assert found == []


def test_no_builtin_is_shadowed():
    """No module defines a name of Python's builtins at its top level (``execution.map`` became ``map_tasks``)."""
    import ast
    import builtins

    names = set(dir(builtins))
    found = []
    for module, tree in _parsed_modules():
        for node in tree.body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                defined = [node.name]
            elif isinstance(node, (ast.Assign, ast.AnnAssign)):
                targets = node.targets if isinstance(node, ast.Assign) else [node.target]
                defined = [target.id for target in targets if isinstance(target, ast.Name)]
            elif isinstance(node, (ast.Import, ast.ImportFrom)):
                defined = [(alias.asname or alias.name).split(".")[0] for alias in node.names]
            else:
                continue
            found += [f"{module}: {name}" for name in defined if name in names]
    assert found == []


def test_no_method_level_or_kind_name_is_compared_outside_the_registries():
    """A choice among named methods is made by its table's dispatcher, a level or a kind by its registry: no other
    code compares a value with such a name or tests a scene's class (``tools/name_comparisons.py``, whose
    ``ALLOWED`` says where a name is read by design, and why)."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("name_comparisons", REPOSITORY / "tools" / "name_comparisons.py")
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)
    found = tool.scan(ROOT, tool.tables())
    assert [f"{f['module']}:{f['line']} {f['text']}" for f in found if not f["allowed"]] == []
    assert len(tool.tables()) == len(tool.TABLES), "a table the tool reads is gone: update tools/name_comparisons.py"
