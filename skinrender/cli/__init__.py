"""
Command line
============

``skinrender COMMAND …``: the commands of the contract (README). The command
line only parses, calls the package and prints: every command takes
``--json`` and then prints exactly one JSON document on stdout; progress and
errors go to stderr. A bad input exits with status 2 and a one-line message,
never a traceback.

One module per command group (:data:`GROUPS`): :mod:`~skinrender.cli.data`,
:mod:`~skinrender.cli.model`, :mod:`~skinrender.cli.evaluation`,
:mod:`~skinrender.cli.design`, :mod:`~skinrender.cli.rendering` (with
:mod:`~skinrender.cli.chart_validation`), :mod:`~skinrender.cli.studies`, :mod:`~skinrender.cli.face`,
:mod:`~skinrender.cli.face_sweep`, :mod:`~skinrender.cli.ranking`, :mod:`~skinrender.cli.skin`; :mod:`~skinrender.cli.common` holds what
they share, :mod:`~skinrender.cli.inputs` the objects a render command parses its flags into.

The command registry is the parser: a group's ``add_parsers(commands)`` registers each of its commands in one
call, ``commands.add_parser(NAME, run=FUNCTION, help=…)``, which builds the command's parser and ties the
function that runs it to it (:class:`~skinrender.cli.common.Parser`'s ``run``); :func:`main` runs the parsed
command's ``run``, and :func:`commands` lists them.
"""

from __future__ import annotations

import argparse
import errno
import os
import re
import sys
from collections.abc import Sequence

from .. import files
from .._interrupt import INTERRUPTED_STATUS, hand_back
from ..errors import SkinrenderError
from . import data, design, evaluation, face, face_sweep, imaging, model, ranking, rendering, skin, studies
from .common import Parser, coverage_hint

__all__ = ["main", "build_parser", "commands", "GROUPS"]

GROUPS = (data, model, design, studies, rendering, evaluation, imaging, face, face_sweep, ranking, skin)
"""The command groups, in the order of ``skinrender --help``: each registers its commands (``add_parsers``)."""


_GROUP_OF: dict = {}
"""Command name → the group of :data:`GROUPS` that registers it, learned as :func:`build_parser` builds the groups."""


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """
    The argument parser of every command: the command registry (each command's parser carries its ``run``).
    ``command``: a command's name whose group (:data:`GROUPS`) registered it before in this process: only that
    group's parsers are built, the command's own as the whole registry builds it (:func:`main`, which runs one
    command, may run several in one process: ~6 ms a build of every group's parsers).
    """
    parser = Parser(
        prog="skinrender",
        description="Design and validate three-channel cameras for skin detection "
        "(wavelengths in nm, temperatures in K, radiance in W·m⁻²·sr⁻¹·nm⁻¹).",
    )
    subparsers = parser.add_subparsers(dest="command", required=True, metavar="COMMAND", parser_class=Parser)
    owner = _GROUP_OF.get(command) if isinstance(command, str) else None
    for group in GROUPS if owner is None else (owner,):
        before = set(subparsers.choices)
        group.add_parsers(subparsers)
        _GROUP_OF.update(dict.fromkeys(set(subparsers.choices) - before, group))
    unrun = sorted(name for name, command in subparsers.choices.items() if command.run is None)
    if unrun:  # a command registered without the function that runs it: the package's own error
        raise RuntimeError(f"commands without a run function: {', '.join(unrun)}")
    return parser


def _subparsers(parser: argparse.ArgumentParser) -> dict[str, Parser]:
    return next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction)).choices


def commands(parser: argparse.ArgumentParser | None = None) -> dict:
    """The registry: every command's name → the function that runs it, read from ``parser`` (:func:`build_parser`'s
    where ``None``)."""
    return {name: command.run for name, command in _subparsers(parser or build_parser()).items()}


def _negative_triples(words: list[str]) -> list[str]:
    """``--translate-mm -100,0,0`` as ``--translate-mm=-100,0,0``: argparse reads a value starting with ``-`` that is
    not one number as a flag ("expected one argument")."""
    out = []
    for word in words:
        flag = str(out[-1]) if out else ""  # argparse takes an abbreviation (--t, --translate) too
        if len(flag) > 2 and "--translate-mm".startswith(flag) and re.match(r"-[\d.]", str(word)) and "," in str(word):
            out[-1] = f"{flag}={word}"
        else:
            out.append(word)
    return out


def _flagged_by_role(error: SkinrenderError, command, args) -> SkinrenderError:
    """``error`` worded with the command's flag of its role where it names the argument instead (``skin: …`` →
    ``--skin: …``, from a layer that knows no flags) and the user gave that flag; as it is otherwise (a scene's own
    skin is not ``--skin``'s)."""
    flag = f"--{error.role.replace('_', '-')}" if error.role and error.flag is None else None
    action = None if flag is None or command is None else command._option_string_actions.get(flag)
    if action is None or error.message.startswith(flag) or getattr(args, action.dest, None) in (None, action.default):
        return error
    words = error.message[len(error.role) + 1:].lstrip() if error.message.startswith(f"{error.role}:") else error.message
    return error.reworded(f"{flag}: {words}", flag=flag)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    hand_back()  # Ctrl-C raises KeyboardInterrupt again: handled below, from the first parse on
    name, args, command = "skinrender", argparse.Namespace(), None
    try:
        words = _negative_triples(list(sys.argv[1:] if argv is None else argv))
        parser = build_parser(words[0] if len(words) else None)  # the command's group, where it is known
        args, extra = parser.parse_known_args(words)
        name = f"skinrender {args.command}"
        command = _subparsers(parser)[args.command]
        if extra:  # argparse's own message would name the top-level program: name the command and its help
            command.error(f"unrecognized arguments: {' '.join(extra)}")
        _sampler_note(None)  # forget an earlier command's (main may run several in one process)
        status = _run(command, args)
        sys.stdout.flush()  # here, so that a failing standard output is reported below, not at exit
        _sampler_note(args.command)
        return status
    except SystemExit as stop:  # argparse's --help (0) or its refusal, already said (2)
        sys.stdout.flush()
        return _status_of(stop)
    except SkinrenderError as error:
        error = _flagged_by_role(error, command, args)
        print(f"{name}: error: {' '.join(coverage_hint(error, args).split())}", file=sys.stderr)
        return error.status
    except KeyboardInterrupt:
        print(f"{name}: interrupted", file=sys.stderr, flush=True)
        files.remove_pending()  # a worker thread's half-written temporaries, which os._exit would leave
        # at once: the interpreter's exit would wait on worker pipes that no one reads any more
        os._exit(INTERRUPTED_STATUS)
    except BrokenPipeError:
        return 0
    except OSError as error:
        if error.errno in USER_PATH_ERRNOS and error.filename:  # a path given that no check caught: still one line
            print(f"{name}: error: {error.filename}: {files.reason_of(error)}", file=sys.stderr)
            return 2
        if error.errno not in MACHINE_ERRNOS:
            return _internal_error(name, error)
        where = f" ({error.filename})" if error.filename else ""  # the machine's, not the input's: one line
        print(f"{name}: error: {error.strerror or error}{where}", file=sys.stderr)
        return 1
    except MemoryError:
        print(f"{name}: error: out of memory: ask for less (a coarser grid, fewer positions)", file=sys.stderr)
        return 2
    except Exception as error:  # the last resort: one line, never a traceback (a bug to report)
        return _internal_error(name, error)


def _run(command: Parser, args: argparse.Namespace) -> int:
    """The command's exit status: 0, or the status a verdict command ends with (its ``SystemExit``, raised after
    its document was written whole)."""
    try:
        command.run(args)
    except SystemExit as stop:
        return _status_of(stop)
    return 0


def _status_of(stop: SystemExit) -> int:
    """The exit status of a ``SystemExit``: its code, 0 for ``None``, 1 for a message."""
    if stop.code is None:
        return 0
    return stop.code if isinstance(stop.code, int) else 1


MACHINE_ERRNOS = files.MACHINE_ERRNOS
"""Errors of the machine rather than of the input or of skinrender (a full disk or standard output, a failing
device, a read-only file system): said in one line; any other ``OSError`` is an internal error to report."""


USER_PATH_ERRNOS = frozenset({errno.ENAMETOOLONG, errno.ELOOP, errno.EACCES, errno.EPERM, errno.ENOENT,
                              errno.ENOTDIR, errno.EISDIR})
"""Errors of a path the user gave (too long, a loop of links, no permission, missing): a refusal naming the path,
should one reach :func:`main` past the checks that name its flag."""


def _sampler_note(command: str | None) -> None:
    """Mitsuba's "Sample count rounded up" warnings of the command, said once on stderr (never on stdout), then
    forgotten; ``None``: forgotten unsaid."""
    variants = sys.modules.get("skinrender.rendering.variants")  # not loaded: nothing rendered
    note = variants.rounded_note() if variants is not None else None
    if note and command is not None:
        print(f"skinrender {command}: note: {note}", file=sys.stderr)
    if variants is not None:
        variants.ROUNDED.clear()


def _internal_error(name: str, error: BaseException) -> int:
    print(f"{name}: internal error: {type(error).__name__}: "
          f"{' '.join(str(error).split())[:300]} (please report this)", file=sys.stderr)
    return 1


if __name__ == "__main__":
    sys.exit(main())
