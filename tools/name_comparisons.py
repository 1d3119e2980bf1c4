"""
Find where the code compares a value with the name of a method, a level of physics or a kind of scene, or tests
a scene's class (issue 35, "One front door": a choice among named methods is made once, by its table's
dispatcher; a level or a kind by its registry).

Every module of the package is parsed (nothing runs); reported are

-   ``==``, ``!=``, ``in``, ``not in`` between a string constant (or a tuple, list or set of them) that is a key of
    a method table (:data:`TABLES`), the name of an effect of a registry or of a scene kind, and an expression that
    names what carries such a value (the table's roles: ``normalization``, ``method``, ``physics``, ``kind``, …;
    ``auto`` compared with an exposure or an spp is a value's spelling, not a method's name, and is not counted);
-   ``isinstance(x, ChartScene)``, ``isinstance(x, FaceScene)`` (and tuples holding them).

Where a name is meant to be read — the tables' validator, the registries and kinds, the loaders and requests
checking their own objects, the argument parsers (:data:`ALLOWED`, each with its reason) — a comparison is listed
apart, with the reason.

    .venv/bin/python tools/name_comparisons.py          # the table
    .venv/bin/python tools/name_comparisons.py --json   # one JSON document
"""

from __future__ import annotations

import argparse
import ast
import importlib
import json
import sys
from pathlib import Path

TABLES = {
    ("skinrender.spectra", "EXTRAPOLATIONS"): ("extrapolation",),
    ("skinrender.model.response", "NORMALISATIONS"): ("normalization", "normalisation", "method"),
    ("skinrender.model.response", "QUADRATURES"): ("quadrature",),
    ("skinrender.evaluation.locus", "BOUNDARIES"): ("boundary",),
    ("skinrender.design.search", "SEARCH_METHODS"): ("method",),
    ("skinrender.design.optimise", "OBJECTIVES"): ("objective", "kind"),
    ("skinrender.rendering.settings", "SAMPLERS"): ("sampler",),
    ("skinrender.rendering.settings", "CHANNEL_GROUPINGS"): ("channels",),
    ("skinrender.rendering.settings", "QUALITY_PRESETS"): ("quality",),
    ("skinrender.rendering.sensor_validation", "MC_VARIANCE"): ("mc_variance", "method"),
    ("skinrender.rendering.renderer", "EMITTERS"): ("emitter", "kind"),
    ("skinrender.datasets.skin_model", "SKIN_REFLECTANCE_METHODS"): ("method",),
    ("skinrender.rendering.face.validation", "LIMITS_SCENE_FREE"): ("limits", "limit"),
    ("skinrender.rendering.face.effects", "PHYSICS_EFFECTS"): ("physics", "level", "name", "names"),
    ("skinrender.rendering.chart_effects", "CHART_EFFECTS"): ("physics", "level", "name", "names"),
    ("skinrender.rendering.kinds", "SCENE_KINDS"): ("kind",),
}
"""(module, table) → the words of the expressions that carry its names (a method table's, a registry's effects,
the scene kinds): a comparison of one of its names with an expression holding such a word is a choice by name."""

SCENE_CLASSES = {"ChartScene", "FaceScene"}

ALLOWED = {
    ("skinrender.methods", None): "the method tables' validator",
    ("skinrender.rendering.registry", None): "a scene kind's registry of effects: the one parser of a physics spec",
    ("skinrender.rendering.kinds", None): "the scene kinds: the one place a scene is told to be a chart or a face",
    ("skinrender.rendering.scene", "load_chart_scene"): "the chart loader: a chart given parsed is returned as it is",
    ("skinrender.rendering.face.scene", "load_face_scene"): "the face loader: a face given parsed is returned as it is",
    ("skinrender.rendering.face.scene", "is_face_scene"): "the face kind's owns (a parsed face, a bundled name, a TOML)",
    ("skinrender.rendering.request", "_check"): "a chart request checks its own field's type",
    ("skinrender.rendering.face.request", "_check"): "a face request checks its own field's type",
    ("skinrender.rendering.spectral_files", "read_spectral"): "a spectral EXR's reader: its header names its kind",
    ("skinrender.cli.common", "coverage_hint"): "an argument parser: the advice a refusal gives for --extrapolation",
    ("skinrender.cli.design", "command_search"): "an argument parser: --extrapolation's default keeps a named set's rule",
    ("skinrender.studies.paper.unknowns", "resolve_setting"): "the sweep's settings parser: as search's --extrapolation",
}
"""(module, function; ``None``: every function) where a name is read by design, and why: the tables' validator,
the registries and kinds, the loaders and requests checking their own objects, and the argument parsers."""


def tables() -> dict[str, tuple[set[str], tuple[str, ...]]]:
    """Each table's label → (its names, its roles); a table missing from the checkout traced is left out."""
    found = {}
    for (module, table), roles in TABLES.items():
        try:
            value = getattr(importlib.import_module(module), table)
        except (ImportError, AttributeError):
            continue
        found[f"{module.rsplit('.', 1)[-1]}.{table}"] = ({str(key) for key in getattr(value, "effects", value)},
                                                          roles)
    return found


def _words(node) -> set[str]:
    """The identifiers and attribute names of an expression (and the string keys it subscripts or gets)."""
    words = set()
    for child in ast.walk(node):
        if isinstance(child, ast.Name):
            words.add(child.id)
        elif isinstance(child, ast.Attribute):
            words.add(child.attr)
        elif isinstance(child, ast.Constant) and isinstance(child.value, str) and child is not node:
            words.add(child.value)
    return words


def _constants(node) -> list[str]:
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return [node.value]
    if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
        return [item.value for item in node.elts if isinstance(item, ast.Constant) and isinstance(item.value, str)]
    return []


def scan(root: Path, known: dict[str, tuple[set[str], tuple[str, ...]]]) -> list[dict]:
    """The comparisons and scene-class tests of every module under ``root`` (the package folder)."""
    found = []
    for path in sorted(root.rglob("*.py")):
        module = ".".join(("skinrender", *path.relative_to(root).with_suffix("").parts)).removesuffix(".__init__")
        tree = ast.parse(path.read_text(encoding="utf-8"))
        parents = {child: parent for parent in ast.walk(tree) for child in ast.iter_child_nodes(parent)}

        def function_of(node) -> str:
            while node in parents:
                node = parents[node]
                if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                    return node.name
            return "<module>"

        for node in ast.walk(tree):
            hits: list[str] = []
            if isinstance(node, ast.Compare) and any(isinstance(op, (ast.Eq, ast.NotEq, ast.In, ast.NotIn))
                                                     for op in node.ops):
                sides = (node.left, *node.comparators)
                constants = [value for side in sides for value in _constants(side)]
                words = set().union(*(_words(side) for side in sides if not _constants(side)))
                of = [label for label, (table, roles) in known.items()
                      if set(constants) & table and words & set(roles)]
                hits = sorted({value for value in constants for label in of if value in known[label][0]})
                if hits:
                    kind = "comparison"
            elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "isinstance"
                  and len(node.args) == 2):
                classes = node.args[1].elts if isinstance(node.args[1], ast.Tuple) else [node.args[1]]
                hits = [c.id if isinstance(c, ast.Name) else c.attr for c in classes
                        if (isinstance(c, ast.Name) and c.id in SCENE_CLASSES)
                        or (isinstance(c, ast.Attribute) and c.attr in SCENE_CLASSES)]
                if hits:
                    kind, of = "isinstance", ["scene class"]
            if hits:
                found.append({"module": module, "line": node.lineno, "function": function_of(node), "kind": kind,
                              "names": sorted(set(hits)), "of": sorted(of),
                              "allowed": ALLOWED.get((module, None), ALLOWED.get((module, function_of(node)))),
                              "text": ast.get_source_segment(
                                  path.read_text(encoding="utf-8"), node)[:100]})
    return found


def main() -> int:
    """Print the comparisons (``--json``: one document)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--json", action="store_true")
    options = parser.parse_args()
    import skinrender

    found = scan(Path(skinrender.__file__).parent, tables())
    outside = [f for f in found if not f["allowed"]]
    if options.json:
        print(json.dumps({"outside": len(outside), "allowed": len(found) - len(outside), "found": found}, indent=2))
        return 0
    print(f"{len(outside)} comparisons with a method, level or kind name (or scene-class tests) outside the "
          f"registries and argument parsers; {len(found) - len(outside)} where a name is read by design")
    for f in sorted(found, key=lambda f: (bool(f["allowed"]), f["module"], f["line"])):
        mark = f"  (allowed: {f['allowed']})" if f["allowed"] else ""
        print(f"{f['module']}:{f['line']} {f['function']}: {f['text']}  [{', '.join(f['of'])}]{mark}")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except BrokenPipeError:  # the reader (head) stopped reading
        sys.exit(0)
