"""Write the API reference's pages from the package itself, at every build.

One page per module (``automodule`` of its own members: names a module re-exports are documented where
they are defined), one page per subpackage listing its modules, and a first page with the package's
docstring and every name of ``skinrender.__all__`` linked to where it is defined. A module added to the
package appears without editing the docs. The pages are written under ``docs/api/`` (not tracked): a page
is rewritten only when its text changes (an incremental build reads only what changed), and a deleted
module's page is removed.
"""

from __future__ import annotations

import ast
import importlib
import pkgutil
import shutil
from pathlib import Path

SKIPPED = {"skinrender.__main__", "skinrender.evaluation._hull3d"}
"""Modules with no page: ``__main__`` runs the command line when imported; the compiled kernel has no
docstrings."""


def module_names(package: str = "skinrender") -> list[str]:
    """Every module of ``package``, dotted, packages before their modules (:data:`SKIPPED` left out)."""
    root = importlib.import_module(package)
    names = [package] + [m.name for m in pkgutil.walk_packages(root.__path__, f"{package}.")]
    return sorted((n for n in names if n not in SKIPPED), key=lambda n: n.split("."))


def is_package(name: str) -> bool:
    """Whether the dotted name is a package (it has a ``__path__``)."""
    return hasattr(importlib.import_module(name), "__path__")


def title(text: str) -> str:
    """An RST section title."""
    return f"{text}\n{'=' * len(text)}\n"


def public_names(init: Path) -> dict[str, str]:
    """``skinrender.__all__``'s names → the module each is imported from on first use (the ``__init__``'s
    ``_WHERE``, read from its source)."""
    tree = ast.parse(init.read_text(encoding="utf-8"))
    table = next(node.value for node in tree.body if isinstance(node, ast.Assign)
                 and any(isinstance(t, ast.Name) and t.id == "_WHERE" for t in node.targets))
    where = eval(compile(ast.Expression(table), str(init), "eval"), {})  # a literal table: name → module
    return {name: f"skinrender.{module}" for name, module in where.items()}


def top_page(package: str, subpackages: list[str], modules: list[str]) -> str:
    """The package's page: its docstring, the public names and where they live, its layers."""
    root = importlib.import_module(package)
    lines = [title(package), f".. automodule:: {package}\n", title("Public names").replace("=", "-"), ""]
    lines += [".. list-table::", "   :header-rows: 1", "   :widths: 30 70", "",
              "   * - name", "     - defined in"]
    where = public_names(Path(root.__file__))
    for name in root.__all__:
        value = getattr(root, name)
        defined = getattr(value, "__module__", None) if callable(value) else None  # constants: where imported
        module = defined if defined and defined.startswith(package) else where[name]
        role = "py:class" if isinstance(value, type) else "py:obj"
        lines += [f"   * - :{role}:`{name} <{module}.{name}>`", f"     - :py:mod:`{module}`"]
    lines += ["", ".. toctree::", "   :maxdepth: 1", ""]
    lines += [f"   {n}" for n in subpackages + modules]
    return "\n".join(lines) + "\n"


def package_page(package: str, children: list[str]) -> str:
    """A subpackage's page: its docstring (own members only) and its modules."""
    lines = [title(package), f".. automodule:: {package}", "   :members:", "   :ignore-module-all:", ""]
    lines += [".. toctree::", "   :maxdepth: 1", ""] + [f"   {n}" for n in children]
    return "\n".join(lines) + "\n"


def module_page(module: str) -> str:
    """A module's page: its docstring and its own public members."""
    return "\n".join([title(module), f".. automodule:: {module}", "   :members:", "   :ignore-module-all:",
                      ""])


def write_api_pages(folder: Path, package: str = "skinrender") -> list[str]:
    """Write every API page into ``folder``, removing any other file there; returns the modules documented."""
    folder.mkdir(parents=True, exist_ok=True)
    names = module_names(package)
    pages = {}
    children = {n: [m for m in names if m.rpartition(".")[0] == n] for n in names}
    for name in names:
        if name == package:
            subpackages = [m for m in children[name] if is_package(m)]
            text = top_page(name, subpackages, [m for m in children[name] if m not in subpackages])
        elif is_package(name):
            text = package_page(name, children[name])
        else:
            text = module_page(name)
        pages[f"{name}.rst"] = text
    for path in folder.iterdir():
        if path.name not in pages:
            shutil.rmtree(path) if path.is_dir() else path.unlink()
    for name, text in pages.items():
        path = folder / name
        if not path.exists() or path.read_text(encoding="utf-8") != text:
            path.write_text(text, encoding="utf-8")
    return names
