"""
Shared check for the bad-input tests of the command line: a refusal is exit
status 2, exactly one line on stderr that names the argument, no traceback,
nothing on stdout (so ``--json`` prints one document or nothing), and no file
left behind in the output folder.
"""

from __future__ import annotations

import errno
import os
import signal
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from skinrender.cli import main

BAD_BINARY = bytes(range(256)) * 4
"""Content of a binary 'CSV' file."""


def run(argv: list[str], capsys) -> tuple[int, str, str]:
    """Run the command line in this process; returns (status, stdout, stderr)."""
    try:
        status = main([str(a) for a in argv])
    except SystemExit as exit_:  # argparse's own refusals
        status = exit_.code
    out, err = capsys.readouterr()
    return status, out, err


def assert_refused(argv: list[str], names: str | tuple[str, ...], capsys, output: Path | None = None) -> str:
    """``argv`` (``--json`` added) is refused cleanly, the one line naming each of ``names``; returns the line."""
    before = sorted(output.rglob("*")) if output is not None and output.exists() else None
    status, out, err = run([*argv, "--json"], capsys)
    lines = [line for line in err.splitlines() if line.strip()]
    assert status == 2, f"exit {status}, stderr: {err[-500:]}"
    assert len(lines) == 1, f"expected one line, got: {err[-800:]}"
    assert "Traceback" not in err and "internal error" not in err
    assert out == "", f"stdout must stay empty on a refusal, got {out[:200]!r}"
    for name in (names,) if isinstance(names, str) else names:
        assert name in lines[0], f"{name!r} not named in: {lines[0]}"
    if before is not None:
        assert sorted(output.rglob("*")) == before, "a refused command left files behind"
    return lines[0]


@pytest.fixture(scope="session")
def bad_files(tmp_path_factory) -> dict[str, Path]:
    """Malformed input files: binary, Latin-1, zero-valued, header-only CSVs and broken scene files."""
    folder = tmp_path_factory.mktemp("bad")
    files = {
        "binary.csv": BAD_BINARY,
        "latin1.csv": "nm,h\u00e4ut\n400,0.5\n700,0.5\n".encode("latin-1"),
        "header_only.csv": b"nm,a\n",
        "zero_spd.csv": b"nm,spd\n400,0\n550,0\n700,0\n",
        "camera_zero.csv": b"nm,R,G,B\n400,0,0,0\n700,0,0,0\n",
        "camera_two.csv": b"nm,R,G\n400,1,1\n700,1,1\n",
        "refl_negative.csv": b"nm,a\n400,-0.5\n700,0.5\n",
        "refl_nan.csv": b"nm,a\n400,nan\n700,0.5\n",
        "refl_unsorted.csv": b"nm,a\n700,0.5\n400,0.5\n",
        "scene_bad_toml.toml": b"name = [\n",
        "scene_unknown_field.toml": b"columns = 2\ncolour = 'red'\n[[patch]]\nreflectance = 'grey:0.5'\n",
        "scene_no_patch.toml": b"columns = 2\n",
        "scene_black_white.toml": b"columns = 2\nwhite = 'grey:0'\n[[patch]]\nreflectance = 'grey:0.5'\n",
        "scene_huge.toml": b"columns = 1\npatch_px = 100000\n[[patch]]\nreflectance = 'grey:0.5'\n",
        "scene_one_pixel.toml": b"columns = 1\npatch_px = 3\nborder_px = 1\n[[patch]]\nreflectance = 'grey:0.5'\n",
        "scene_unknown_reflectance.toml": b"columns = 1\n[[patch]]\nreflectance = 'nosuchset:3'\n",
    }
    paths = {}
    for name, content in files.items():
        paths[name] = folder / name
        paths[name].write_bytes(content)
    (folder / "folder.toml").mkdir()
    paths["folder.toml"] = folder / "folder.toml"
    paths["a_file"] = folder / "a_file"
    paths["a_file"].write_text("not a folder")
    return paths


def child_command(argv: list) -> list[str]:
    """The command line of a child Python process running ``skinrender argv`` (this checkout's package)."""
    argv = [str(a) for a in argv]
    return [sys.executable, "-c", f"import sys; from skinrender.cli import main; sys.exit(main({argv!r}))"]


def interrupt_after(argv: list, marker: str, timeout: float = 600.0) -> tuple[int, str, str]:
    """
    Run ``skinrender argv`` in a child process, read its stderr until a line holding ``marker`` (the command's
    own progress line) appears, then send it SIGINT (Ctrl-C); returns (status, stdout, stderr). No sleep: the
    interrupt follows the progress line at once, so a command whose work outlasts that instant on any machine
    is interrupted during it. Fails when the command ends before the line, or prints nothing for ``timeout`` s.
    """
    child = subprocess.Popen(child_command(argv), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    watchdog = threading.Timer(timeout, child.kill)  # a guard against a hang, not a speed assertion
    watchdog.start()
    seen = []
    try:
        while not any(marker in line for line in seen[-1:]):
            line = child.stderr.readline()
            assert line, f"the command ended before its progress line {marker!r}: {''.join(seen)[-800:]}"
            seen.append(line)
        child.send_signal(signal.SIGINT)
        out, err = child.communicate()  # the pipes close only when every worker is gone
    finally:
        watchdog.cancel()
        if child.poll() is None:
            child.kill()
    return child.returncode, out, "".join(seen) + err


def full_disk(monkeypatch, after: int = 0, code: int = errno.ENOSPC) -> None:
    """``os.write`` in :mod:`skinrender.files` (every output's writes) fails with ``code`` (a full disk) after
    ``after`` successful calls: the disk fills while the outputs are written."""
    from skinrender import files

    calls = {"n": 0}
    real = os.write

    def write(handle, data):
        calls["n"] += 1
        if calls["n"] > after:
            raise OSError(code, os.strerror(code))
        return real(handle, data)

    monkeypatch.setattr(files.os, "write", write)
