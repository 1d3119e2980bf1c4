"""
Files in and out
================

Every file the package reads from a user and every file it writes goes
through this module, so that both fail the same clean way.

-   :func:`read_input`: the bytes of an input file, checked to be a regular
    file (a symbolic link is followed and its target checked) of at most a
    stated size before anything is read: a named pipe, a device (``/dev/zero``),
    a folder or an oversized file is refused at once, never read without end.
-   :func:`exists`: whether a path names something (a spec that may be a
    path), its name-too-long and permission errors turned into refusals.
-   :func:`write_outputs`, :func:`write_output`: outputs made whole in memory,
    written to temporary files beside their targets and renamed into place
    only when every one was written; on any failure nothing new is left
    behind, and the message names the output (its flag) and the system's
    reason (a full disk, a name too long, no permission).
-   :func:`check_output_path`: an output path refused before any work (a
    folder, a dangling symbolic link, a name too long, a place that cannot be
    written).
-   :func:`write_stdout`: text on standard output, every byte's write checked
    (a full disk under ``> file`` is an error naming the output, never a
    short file and exit status 0).

Sizes are bytes. The caps of each kind of input are stated where the input is
read (:data:`skinrender.spectral_csv.CSV_BYTES_MAX`, :data:`TOML_BYTES_MAX`,
:data:`MESH_BYTES_MAX`).
"""

from __future__ import annotations

import errno
import io
import os
import secrets
import select
import stat
import sys
from collections.abc import Callable
from pathlib import Path
from typing import BinaryIO, NamedTuple

from .errors import SkinrenderError

__all__ = ["MACHINE_ERRNOS", "TOML_BYTES_MAX", "MESH_BYTES_MAX", "EXR_BYTES_MAX", "OutputError", "Output",
           "read_input", "check_input", "exists",
           "reason_of", "shown", "check_output_path", "write_outputs", "write_output", "remove_pending", "write_stdout"]

TOML_BYTES_MAX = 1_000_000
"""Largest scene or imager TOML read, bytes: the bundled ones are under 4 kB; a chart of 2 000 patches ~100 kB."""

MESH_BYTES_MAX = 256_000_000
"""Largest mesh (OBJ, PLY) read, bytes: a few million triangles; the bundled head is 0.2 MB."""

EXR_BYTES_MAX = 1_000_000_000
"""Largest EXR image read (a reference render, an image to detect in), bytes: a 4096 × 4096 image of four float32
channels is 268 MB; the package's renders are under 5 MB."""

MACHINE_ERRNOS = frozenset({errno.ENOSPC, errno.EDQUOT, errno.EFBIG, errno.EIO, errno.EROFS})
"""Errors of the machine rather than of the input (a full disk or quota, a file over the size limit, a failing
device, a read-only file system): exit status 1, as the command line gives them."""

_REASONS = {
    errno.ENOENT: "no such file or folder",
    errno.ENAMETOOLONG: "the name is too long (at most 255 bytes a name, 4096 a path)",
    errno.EACCES: "permission denied",
    errno.EPERM: "permission denied",
    errno.ELOOP: "a loop of symbolic links",
    errno.ENOTDIR: "a part of the path is a file, not a folder",
    errno.EISDIR: "a folder, not a file",
    errno.ENOSPC: "no space left on the device (the disk is full)",
    errno.EDQUOT: "the disk quota is used up",
    errno.EFBIG: "the file would be larger than this system allows",
    errno.EROFS: "a read-only file system",
    errno.EIO: "an input/output error of the device",
}


def reason_of(error: OSError) -> str:
    """
    The system's reason of ``error`` in a few plain words.

    >>> import errno
    >>> reason_of(OSError(errno.ENOSPC, "No space left on device"))
    'no space left on the device (the disk is full)'
    """
    return _REASONS.get(error.errno, error.strerror or str(error))


def shown(path) -> str:
    """
    A path as messages show it: whole, or a long one cut in the middle (the message stays one readable line).

    >>> shown("a" * 300)[:8], len(shown("a" * 300))
    ('aaaaaaaa', 81)
    """
    text = str(path)
    return text if len(text) <= 81 else f"{text[:60]}…{text[-20:]}"


def _kind(mode: int) -> str:
    """What a file that is not a regular file is, in words."""
    for test, name in ((stat.S_ISDIR, "a folder"), (stat.S_ISFIFO, "a named pipe"), (stat.S_ISCHR, "a device"),
                       (stat.S_ISBLK, "a device"), (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return name
    return "not a regular file"


def _open_checked(path, limit: int, what: str, where: str | None) -> int:
    """An open, non-blocking descriptor of ``path`` once it is shown a regular file of at most ``limit`` bytes."""
    try:
        handle = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
    except OSError as error:
        raise SkinrenderError(f"{where or shown(path)}: "
                              f"{'no such file' if error.errno == errno.ENOENT else reason_of(error)}") from None
    except ValueError:  # an embedded NUL byte
        raise SkinrenderError(f"{where or repr(str(path))}: not a file name (it holds a NUL byte)") from None
    try:
        info = os.fstat(handle)
        if not stat.S_ISREG(info.st_mode):
            raise SkinrenderError(f"{where or path}: {_kind(info.st_mode)}, not a regular file; expected {what}")
        if info.st_size > limit:
            raise SkinrenderError(f"{where or path}: {info.st_size / 1e6:.3g} MB is larger than {what} may be "
                                  f"({limit / 1e6:.3g} MB)")
    except OSError as error:
        os.close(handle)
        raise SkinrenderError(f"{where or path}: cannot be read ({reason_of(error)})") from None
    except SkinrenderError:
        os.close(handle)
        raise
    return handle


def check_input(path: str | Path, limit: int, what: str = "a file", where: str | None = None) -> None:
    """
    Refuse ``path`` unless it is a regular file of at most ``limit`` bytes, as :func:`read_input` does, for a
    file a library reads itself (an EXR through OpenEXR): nothing is read, a named pipe is not waited on.

    >>> check_input("/dev/zero", 1000, "an EXR image")
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: /dev/zero: a device, not a regular file; expected an EXR image
    """
    os.close(_open_checked(path, limit, what, where))


def read_input(path: str | Path, limit: int, what: str = "a file", where: str | None = None) -> bytes:
    """
    The bytes of the input file ``path``, refused unless it is a regular file of at most ``limit`` bytes.

    The file is opened without blocking (a named pipe does not wait for a writer), checked on its open handle
    (a symbolic link is followed: its target is checked) and read to at most ``limit`` bytes, so nothing is
    read without bound.

    Parameters
    ----------
    path
        The file.
    limit
        Largest size read, bytes.
    what
        What the file should be, for the messages (``a spectral CSV``, ``a scene TOML``).
    where
        What the messages start with instead of the path (``--mesh``, a scene's field).

    Raises
    ------
    SkinrenderError
        ``PATH: …`` (or ``WHERE: …``) naming what is wrong: missing, a folder, a named pipe, a device, larger than ``limit``,
        a name too long, no permission.

    Examples
    --------
    >>> read_input("/dev/zero", 1000)
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: /dev/zero: a device, not a regular file; expected a file
    """
    handle = _open_checked(path, limit, what, where)
    try:
        chunks, size = [], 0
        while size <= limit:
            chunk = os.read(handle, min(1 << 20, limit + 1 - size))
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
        if size > limit:  # it grew while read
            raise SkinrenderError(f"{where or path}: larger than {what} may be ({limit / 1e6:.3g} MB)")
        return b"".join(chunks)
    except OSError as error:
        raise SkinrenderError(f"{where or path}: cannot be read ({reason_of(error)})") from None
    finally:
        os.close(handle)


def exists(path: str | Path) -> bool:
    """
    Whether ``path`` names anything (a file, a folder, a pipe, a device, a dangling symbolic link): for specs
    that may be a name or a path. A name too long, a loop of links or no permission is a refusal, not ``False``.

    >>> exists("/dev/null"), exists("gbell:9@450,540,610")
    (True, False)
    """
    text = str(path)
    if not text or "\0" in text:
        return False
    try:
        os.lstat(text)
        return True
    except OSError as error:
        if error.errno in (errno.ENOENT, errno.ENOTDIR):
            return False
        raise SkinrenderError(f"{shown(text)}: {reason_of(error)}") from None


class OutputError(SkinrenderError):
    """An output that could not be written: ``flag`` and ``reason`` named; exit status 1 for the machine's errors."""

    def __init__(self, message: str, flag: str | None = None, error: OSError | None = None):
        super().__init__(message, flag=flag, cause="output")
        self.oserror = error
        self.reason = None if error is None else reason_of(error)
        if error is not None and error.errno in MACHINE_ERRNOS:
            self.status = 1


def _named(flag: str | None, path) -> str:
    return f"{flag} {shown(path)}" if flag else shown(path)


def check_output_path(path: str | Path, flag: str | None = None) -> Path:
    """
    The file an output ``path`` writes (a symbolic link to a file: its target), refused before any work with
    one line naming ``flag``: a folder, a dangling symbolic link, a name too long, a parent that is a file, a
    place where no file can be made (tried by making one and removing it). Missing parent folders are fine.

    >>> check_output_path("/dev/null/x.png", "--plot")
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: --plot /dev/null/x.png: /dev/null is not a folder, so no file can be made under it
    """
    where = _named(flag, path)
    text = str(path)
    if not text.strip() or "\0" in text:
        raise SkinrenderError(f"{flag or 'output'}: expected a file path, got {text!r}", flag=flag)
    try:
        if os.path.islink(text):
            if not os.path.exists(text):
                raise SkinrenderError(f"{where}: a symbolic link to nothing ({os.readlink(text)}); name a file", flag=flag)
            text = os.path.realpath(text)
        target = Path(text)
        if target.is_dir():
            raise SkinrenderError(f"{where}: is a folder, expected a file", flag=flag)
        if target.exists() and not target.is_file():
            raise SkinrenderError(f"{where}: {_kind(os.stat(target).st_mode)}, expected a regular file", flag=flag)
        existing = target.parent
        while not existing.exists() and existing != existing.parent:
            existing = existing.parent
        if not existing.is_dir():
            raise SkinrenderError(f"{where}: {existing} is {'a file' if existing.is_file() else 'not a folder'}, so no "
                                  "file can be made under it", flag=flag)
        probe = existing / f".{secrets.token_hex(6)}.probe"
        os.close(os.open(probe, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600))
        os.unlink(probe)
        if len(target.name.encode()) > 255:  # a missing name is not looked up: its length is checked here
            raise OSError(errno.ENAMETOOLONG, os.strerror(errno.ENAMETOOLONG))
    except OSError as error:
        raise OutputError(f"{where}: cannot be written ({reason_of(error)})", flag, error) from None
    return target


class Output(NamedTuple):
    """One output of a command: its ``path``, the ``flag`` that named it and its ``content`` (bytes, or a
    function that writes them to a binary stream)."""

    path: str | Path
    flag: str | None
    content: bytes | Callable[[BinaryIO], object]


def _content(content) -> bytes:
    if isinstance(content, (bytes, bytearray, memoryview)):
        return bytes(content)
    if isinstance(content, str):
        return content.encode("utf-8")
    stream = io.BytesIO()
    content(stream)
    return stream.getvalue()


def write_outputs(*outputs: Output | tuple) -> list[Path]:
    """
    Write every output whole or none: all are made in memory first, then written to temporary files beside
    their targets (``.NAME.XXXX.partial``), then renamed into place. On any failure (a full disk, a name too
    long, no permission, an interrupt) every temporary file and every folder this call made is removed and
    the targets are untouched.

    Returns
    -------
    list of Path
        The files written (a symbolic link's target where one was given).

    Raises
    ------
    OutputError
        ``FLAG PATH: cannot be written (reason)``; its ``status`` is 1 for the machine's errors
        (:data:`MACHINE_ERRNOS`), 2 otherwise.

    Examples
    --------
    >>> import tempfile
    >>> folder = Path(tempfile.mkdtemp())
    >>> [p.name for p in write_outputs(Output(folder / "a.txt", "--a", b"one"), (folder / "b" / "b.txt", "--b", "two"))]
    ['a.txt', 'b.txt']
    >>> sorted(p.name for p in folder.rglob("*"))
    ['a.txt', 'b', 'b.txt']
    """
    items = [Output(*item) for item in outputs]
    targets = [check_output_path(item.path, item.flag) for item in items]
    if len(set(targets)) < len(targets):
        raise SkinrenderError("outputs: " + ", ".join(_named(i.flag, i.path) for i in items) + " name one file twice")
    contents = [_content(item.content) for item in items]
    created: list[Path] = []
    staged: list[Path] = []
    current = items[0]
    try:
        for item, target, data in zip(items, targets, contents):
            current = item
            for folder in reversed([target.parent, *target.parent.parents]):
                if not folder.exists():
                    folder.mkdir()
                    created.append(folder)
                    _PENDING.append(folder)
            temporary = target.with_name(f".{target.name[:100]}.{secrets.token_hex(4)}.partial")
            handle = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0), 0o666)
            staged.append(temporary)
            _PENDING.append(temporary)
            try:
                view = memoryview(data)
                while view:
                    view = view[os.write(handle, view):]
            finally:
                os.close(handle)
        for item, target, temporary in zip(items, targets, staged):
            current = item
            os.replace(temporary, target)
            _PENDING.remove(temporary)
    except BaseException as error:
        for temporary in staged:
            try:
                os.unlink(temporary)
            except OSError:
                pass
        for folder in reversed(created):
            try:
                folder.rmdir()
            except OSError:
                break
        _forget(staged + created)
        if isinstance(error, OSError):
            raise OutputError(f"{_named(current.flag, current.path)}: cannot be written ({reason_of(error)}); "
                              "nothing was written", current.flag, error) from None
        raise
    _forget(created)
    return targets


_PENDING: list[Path] = []
"""Temporary files and new folders of writes under way: :func:`remove_pending` removes them when the process
must end at once (Ctrl-C while a command's worker thread writes)."""


def _forget(paths: list[Path]) -> None:
    for path in paths:
        if path in _PENDING:
            _PENDING.remove(path)


def remove_pending() -> None:
    """Remove the temporary files and new folders of writes under way (newest first); for an immediate exit."""
    for path in reversed(list(_PENDING)):
        try:
            path.rmdir() if path.is_dir() else path.unlink()
        except OSError:
            pass
    _PENDING.clear()


def write_output(path: str | Path, content, flag: str | None = None) -> Path:
    """One output written whole or not at all (:func:`write_outputs`); returns the file written."""
    return write_outputs(Output(path, flag, content))[0]


def _write_all(handle: int, data: bytes) -> None:
    """Every byte of ``data`` to the descriptor ``handle``: each ``write`` checked, a short one continued, one that
    writes nothing an error (a non-blocking pipe that is full is waited on)."""
    view = memoryview(data)
    while view:
        try:
            count = os.write(handle, view)
        except BlockingIOError:
            select.select([], [handle], [])
            continue
        if count <= 0:
            raise OSError(errno.EIO, "the write took no bytes")
        view = view[count:]


def write_stdout(text: str) -> None:
    """
    ``text`` on standard output, every byte's write checked.

    Python's own buffered standard output can drop the rest of a document after one short write (a disk filling
    under ``> file.json``: 4 096 bytes written, the command's exit status still 0). Here the stream's buffer is
    flushed, then the text is written to its descriptor directly, each ``write`` checked and a short one
    continued. A stream without a descriptor (a test's capture) is written and flushed as it is.

    Raises
    ------
    OutputError
        ``standard output: cannot be written (reason); the output is incomplete``: status 1 for the machine's
        errors (a full disk or quota, a file-size limit, a failing device). A closed pipe
        (:class:`BrokenPipeError`) is passed on as it is: the reader has gone.
    """
    stream = sys.stdout
    try:
        handle = stream.fileno()
    except (AttributeError, OSError, ValueError, io.UnsupportedOperation):
        handle = None
    try:
        if handle is None:
            stream.write(text)
            stream.flush()
            return
        stream.flush()
        _write_all(handle, text.encode(stream.encoding or "utf-8", stream.errors or "strict"))
    except BrokenPipeError:
        raise
    except OSError as error:
        raise OutputError(f"standard output: cannot be written ({reason_of(error)}); the output is incomplete",
                          "standard output", error) from None
