"""
Follow what a command was asked through the code (issue 35, "One front door"): which functions receive the
parsed ``argparse.Namespace``, which functions below the command line receive a level, physics, camera or scene
as a string, and where a spec parser (``parse_physics`` and its kin) is called from.

Each command runs in this process through ``skinrender.cli.main`` under ``sys.setprofile`` (and
``threading.setprofile``: ``interruptible`` commands run in a worker thread); every call of a function of the
package is looked at:

-   **Namespace readers**: the functions with an ``argparse.Namespace`` among their arguments.
-   **Strings below the front doors**: a function outside ``skinrender.cli`` with an argument whose name says it
    holds a level, physics, camera or scene (:data:`ROLES`) and whose value is a string (or strings). The
    functions that turn such a spec into its object are the front doors' own (:data:`PARSERS`, the request
    builders and the spec parsers) and are listed apart.
-   **Parser calls**: each call of a spec parser (:data:`PARSERS`) with a string, by its caller. A caller in the
    command line or among the parsers and request builders is where a request is built; any other is not.

    .venv/bin/python tools/trace_front_door.py            # the table
    .venv/bin/python tools/trace_front_door.py --json     # one JSON document

Another checkout (e.g. main at 99c7dbf, the figures before issue 35) is traced by putting it first on the path:

    git archive 99c7dbf | tar -x -C /tmp/before && cp skinrender/evaluation/_hull3d*.so /tmp/before/skinrender/evaluation/
    PYTHONPATH=/tmp/before .venv/bin/python tools/trace_front_door.py

The renders are small (a chart at 4 spp, a face at 16 px) so that the whole trace takes a minute or two; what is
counted does not depend on their size.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import os
import sys
import threading
import time
from collections import defaultdict

CAMERA = "gbell:9@450,540,610"

COMMANDS = {
    "validate": ["validate", "macbeth", "--camera", CAMERA, "--prevailing", "A", "--calibration", "5900",
                 "--spp", "4", "--json"],
    "render": ["render", "macbeth", "--camera", CAMERA, "--prevailing", "A", "--calibration", "5900",
               "--spp", "4", "--output", "{tmp}/render.exr", "--json"],
    "ladder": ["ladder", "--camera", CAMERA, "--prevailing", "3300", "--calibration", "3300", "--size", "16",
               "--spp", "8", "--levels", "direct,noise", "--json"],
    "validate face": ["validate", "face", "--camera", CAMERA, "--prevailing", "3300", "--calibration", "3300",
                      "--size", "16", "--spp", "16", "--json"],
}
"""The commands traced, their arguments (``{tmp}``: a temporary folder)."""

ROLES = {"physics": "physics", "level": "level", "levels": "level", "physics_level": "level",
         "camera": "camera", "camera_": "camera", "cam": "camera", "scene": "scene", "scene_spec": "scene"}
"""Argument names → the role their value plays (a string there is a spec not yet parsed)."""

PARSERS = {"parse_physics", "physics_level", "level", "names", "camera", "load_scene", "load_chart_scene",
           "load_face_scene", "is_face_scene", "owns", "load", "scene_kind", "request", "chart_request",
           "face_request", "named", "naming", "planckian", "planckian_temperature"}
"""The functions (by name) that turn a spec into its object: the spec parsers (``parse_physics``,
``Registry.level``/``names``, ``camera``, the scene loaders, a kind's ``owns``/``load``) and the request builders
(a kind's ``request``, ``chart_request``, ``face_request``) with their error-naming wrappers."""

SPEC_PARSERS = {"parse_physics", "physics_level", "level", "names", "camera", "load_scene", "load_chart_scene",
                "load_face_scene"}
"""The parsers whose callers are listed (``parse_physics`` and its kin)."""


def _strings(value) -> bool:
    """Whether ``value`` is a string, or a non-empty sequence of strings."""
    if isinstance(value, str):
        return True
    return isinstance(value, (list, tuple)) and bool(value) and all(isinstance(item, str) for item in value)


def _arguments(frame) -> dict:
    """A called frame's arguments, name → value."""
    code = frame.f_code
    count = code.co_argcount + code.co_kwonlyargcount
    names = list(code.co_varnames[:count])
    flags = code.co_flags
    if flags & 0x04:  # *args
        names.append(code.co_varnames[count])
        count += 1
    if flags & 0x08:  # **kwargs
        names.append(code.co_varnames[count])
    values = {}
    for name in names:
        if name not in frame.f_locals:
            continue
        value = frame.f_locals[name]
        if name == code.co_varnames[code.co_argcount + code.co_kwonlyargcount] and flags & 0x04 and isinstance(
                value, tuple):
            values.update({f"{name}[{i}]": item for i, item in enumerate(value)})
        elif flags & 0x08 and isinstance(value, dict) and name == names[-1]:
            values.update(value)
        else:
            values[name] = value
    return values


class Trace:
    """What one command's calls showed (see the module's docstring)."""

    def __init__(self) -> None:
        self.namespace: dict[str, int] = defaultdict(int)
        self.strings: dict[tuple[str, str], int] = defaultdict(int)
        self.parsers: dict[tuple[str, str, str], int] = defaultdict(int)
        self.modules: set[str] = set()
        self.lock = threading.Lock()

    def __call__(self, frame, event, arg):  # noqa: D102 - the profile hook
        if event != "call":
            return
        module = frame.f_globals.get("__name__", "")
        if not module.startswith("skinrender"):
            return
        code = frame.f_code
        where = f"{module}.{getattr(code, 'co_qualname', code.co_name)}"
        try:
            arguments = _arguments(frame)
        except Exception:  # noqa: BLE001 - a frame whose locals cannot be read is skipped
            return
        found = [name for name, value in arguments.items() if isinstance(value, argparse.Namespace)]
        cli = module.startswith("skinrender.cli")
        roles = [] if cli else [f"{ROLES[name]}={arguments[name]!r}"[:60] for name in ROLES
                                if name in arguments and _strings(arguments[name])]
        spec = next((value for key, value in arguments.items() if key != "self"), None)  # the first argument
        parser = code.co_name in SPEC_PARSERS and _strings(spec)
        if not (found or roles or parser):
            return
        with self.lock:
            if found:
                self.namespace[where] += 1
                self.modules.add(module)
            for role in roles:
                self.strings[(where, role.split("=")[0])] += 1
            if parser:
                back = frame.f_back
                caller = "?" if back is None else (f"{back.f_globals.get('__name__', '')}."
                                                   f"{getattr(back.f_code, 'co_qualname', back.f_code.co_name)}")
                self.parsers[(where, caller, _door(caller))] += 1

    def document(self) -> dict:
        """The figures and the lists."""
        readers = sorted(self.namespace)
        below = sorted({where for where, _ in self.strings if where.rsplit(".", 1)[-1] not in PARSERS})
        doors = sorted({where for where, _ in self.strings if where.rsplit(".", 1)[-1] in PARSERS})
        callers = sorted({(where, caller, door) for where, caller, door in self.parsers})
        return {
            "namespace_readers": len(readers),
            "namespace_modules": sorted(self.modules),
            "namespace_readers_outside_cli": [where for where in readers if not where.startswith("skinrender.cli")],
            "readers": readers,
            "string_roles_below": len(below),
            "string_roles_below_list": [f"{where} ({', '.join(sorted({r for w, r in self.strings if w == where}))})"
                                        for where in below],
            "string_roles_at_doors": doors,
            "parser_calls_elsewhere": sorted({f"{where} ← {caller}" for where, caller, door in callers
                                              if not door}),
            "parser_calls_at_doors": sorted({f"{where} ← {caller}" for where, caller, door in callers if door}),
        }


def _door(caller: str) -> bool:
    """Whether a parser's caller is where a request is built: the command line, or a parser or request builder."""
    module, _, name = caller.rpartition(".")
    return caller.startswith("skinrender.cli") or name in PARSERS or name.startswith("<") and module.endswith(
        ("request", "kinds", "registry"))


def trace(name: str, argv: list[str]) -> dict:
    """Run one command under the profile hook; its figures, exit status and seconds."""
    from skinrender.cli import main

    hook = Trace()
    start = time.perf_counter()
    stdout, stderr = io.StringIO(), io.StringIO()
    threading.setprofile(hook)
    sys.setprofile(hook)
    try:
        with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
            try:
                status = main(argv)
            except SystemExit as exit_:
                status = exit_.code
    finally:
        sys.setprofile(None)
        threading.setprofile(None)  # type: ignore[arg-type]
    document = {"command": name, "argv": argv, "exit_status": status,
                "seconds": round(time.perf_counter() - start, 1), **hook.document()}
    if status not in (0, 1, 3):
        document["stderr"] = stderr.getvalue()[-2000:]
    return document


def main() -> int:
    """Trace every command of :data:`COMMANDS`; print the table (or ``--json``)."""
    import tempfile

    import skinrender

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--json", action="store_true", help="one JSON document")
    parser.add_argument("--command", action="append", choices=list(COMMANDS), help="only these (default: all)")
    options = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        results = [trace(name, [part.format(tmp=tmp) for part in COMMANDS[name]])
                   for name in options.command or COMMANDS]
    document = {"package": os.path.dirname(skinrender.__file__), "commands": results}
    if options.json:
        print(json.dumps(document, indent=2))
        return 0
    print(f"package: {document['package']}")
    print(f"{'command':15} {'exit':>4} {'Namespace readers':>17} {'outside cli':>11} {'str roles below':>15} "
          f"{'parsers elsewhere':>17}")
    for r in results:
        print(f"{r['command']:15} {str(r['exit_status']):>4} {r['namespace_readers']:>17} "
              f"{len(r['namespace_readers_outside_cli']):>11} {r['string_roles_below']:>15} "
              f"{len(r['parser_calls_elsewhere']):>17}")
    for r in results:
        print(f"\n{r['command']}: Namespace read by {r['namespace_readers']} functions in "
              f"{len(r['namespace_modules'])} modules")
        for where in r["readers"]:
            print(f"  {where}")
        if r["string_roles_below_list"]:
            print("  strings below the front doors:")
            for where in r["string_roles_below_list"]:
                print(f"    {where}")
        if r["parser_calls_elsewhere"]:
            print("  spec parsers called elsewhere than where a request is built:")
            for where in r["parser_calls_elsewhere"]:
                print(f"    {where}")
        if "stderr" in r:
            print("  stderr: " + r["stderr"].strip().replace("\n", "\n    "))
    return 0


if __name__ == "__main__":
    sys.exit(main())
