"""
Ctrl-C before the command line starts
=====================================

The ``skinrender`` command imports the package (numpy, scipy, every command's module: ~0.2–0.5 s) before
:func:`skinrender.cli.main` runs and takes Ctrl-C over. An interrupt in that time used to end in a
``KeyboardInterrupt`` traceback. :func:`quiet_while_starting`, the package's first statement, makes it end the
process with one line, ``skinrender: interrupted``, and exit status 130 instead, as an interrupt later does; and
only when this process is the command line (the ``skinrender`` script or ``python -m skinrender``): a program
that imports skinrender keeps its own Ctrl-C. :func:`skinrender.cli.main` hands Ctrl-C back to Python
(:func:`hand_back`) as it starts.

Standard library only: it runs before anything else is imported.
"""

from __future__ import annotations

import os
import signal
import sys
import threading

__all__ = ["INTERRUPTED_STATUS", "quiet_while_starting", "hand_back", "is_command_line"]

INTERRUPTED_STATUS = 130
"""Exit status of a command ended by Ctrl-C (128 + SIGINT), as the shells give it."""


def is_command_line(argv: list[str] | None = None, original: list[str] | None = None) -> bool:
    """
    Whether this process is the ``skinrender`` command: its script (``argv[0]`` named ``skinrender``) or
    ``python -m skinrender`` (the interpreter's own arguments, ``sys.orig_argv``, hold ``-m skinrender``).

    >>> is_command_line(["/usr/bin/skinrender", "render"], []), is_command_line(["-m"], ["python", "-m", "skinrender"])
    (True, True)
    >>> is_command_line(["pytest"], ["python", "-m", "pytest"])
    False
    """
    argv = sys.argv if argv is None else argv
    original = list(getattr(sys, "orig_argv", [])) if original is None else original
    script = os.path.basename(argv[0]) if argv else ""
    if script in ("skinrender", "skinrender.exe"):
        return True
    return any(a == "-m" and b in ("skinrender", "skinrender.__main__") for a, b in zip(original, original[1:]))


def _end(signum, frame) -> None:  # noqa: ARG001 - a signal handler's arguments
    try:
        os.write(2, b"skinrender: interrupted\n")
    finally:
        os._exit(INTERRUPTED_STATUS)


def quiet_while_starting() -> None:
    """
    In the command line's process, while it starts: Ctrl-C ends it at once with one line and status 130. Left
    alone: another program's process, a thread other than the main one, and a Ctrl-C that is not Python's
    default (ignored, as in a background job, or a handler of the caller's).
    """
    if (threading.current_thread() is threading.main_thread() and is_command_line()
            and signal.getsignal(signal.SIGINT) is signal.default_int_handler):
        signal.signal(signal.SIGINT, _end)


def hand_back() -> None:
    """Ctrl-C raises ``KeyboardInterrupt`` again (the command line handles it), where :func:`quiet_while_starting`
    had taken it; anything else is left as it is."""
    if threading.current_thread() is threading.main_thread() and signal.getsignal(signal.SIGINT) is _end:
        signal.signal(signal.SIGINT, signal.default_int_handler)
