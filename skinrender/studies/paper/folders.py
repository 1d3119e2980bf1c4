"""
Output folders that are complete or absent
==========================================

``reproduce`` checks its output folder before it computes anything, writes
into a hidden temporary folder beside it and moves that into place at the
end: an interrupted or refused run leaves nothing that looks complete.

-   :data:`MANIFEST`: the file that marks a finished ``reproduce`` folder.
-   :func:`check_output`: refuse an unusable ``-o`` with one line naming it
    (an earlier folder that also holds files it did not write included:
    :func:`foreign_files`).
-   :func:`output_folder`: a context manager yielding the temporary folder,
    moved into place on success and removed on any failure (an interrupt
    included).
"""

from __future__ import annotations

import errno
import json
import os
import shutil
import tempfile
from contextlib import contextmanager
from pathlib import Path

from ...errors import SkinrenderError
from ...files import OutputError, read_input, reason_of, shown

__all__ = ["MANIFEST", "check_output", "foreign_files", "output_folder"]

MANIFEST = "reproduce.json"
"""Written last into every ``reproduce`` folder: an existing folder holding it may be replaced."""

MANIFEST_BYTES_MAX = 64_000_000
"""Largest earlier :data:`MANIFEST` read, bytes (a sweep's is ~1 MB): a larger one lists nothing."""


def check_output(directory, flag: str = "-o") -> Path:
    """
    The output folder, refused (:class:`SkinrenderError` naming ``flag``) when
    it is empty text, an existing file, a non-empty folder that an earlier
    ``reproduce`` did not write (it would be replaced), or under a file.
    Whether its place is writable is tried by :func:`output_folder`.
    """
    if directory is None or not str(directory).strip():
        raise SkinrenderError(f"{flag} must name an output folder, got {'' if directory is None else directory!r}",
                              flag=flag)
    target = Path(str(directory)).expanduser().absolute()
    try:
        return _checked(target, directory, flag)
    except OSError as error:  # a name too long, no permission to look
        raise OutputError(f"{flag} {shown(directory)}: cannot be written ({reason_of(error)})", flag, error) from None


def _checked(target: Path, directory, flag: str) -> Path:
    if len(target.name.encode()) > 255:
        raise OSError(errno.ENAMETOOLONG, os.strerror(errno.ENAMETOOLONG))
    if target.is_symlink():  # the folder it names is the output; a link to nothing names none
        if not target.exists():
            raise SkinrenderError(f"{flag} {directory}: a symbolic link to nothing ({os.readlink(target)}); name a "
                                  "folder", flag=flag)
        target = Path(os.path.realpath(target))
    if target.exists() and not target.is_dir():
        raise SkinrenderError(f"{flag} {directory}: an existing file, not a folder", flag=flag)
    if target.is_dir() and any(target.iterdir()) and not (target / MANIFEST).is_file():
        raise SkinrenderError(f"{flag} {directory}: a folder that holds other files (no {MANIFEST} of an earlier "
                              "reproduce); name a new or empty folder", flag=flag)
    if (target / MANIFEST).is_file():
        foreign = foreign_files(target)
        if foreign:
            listed = ", ".join(foreign[:3]) + (f" and {len(foreign) - 3} more" if len(foreign) > 3 else "")
            raise SkinrenderError(f"{flag} {directory}: an earlier reproduce folder that also holds files it did not "
                                  f"write ({listed}); they would be deleted with it: move them or name another folder",
                                  flag=flag)
    for ancestor in target.parents:
        if ancestor.exists():
            if not ancestor.is_dir():
                raise SkinrenderError(f"{flag} {directory}: {ancestor} is a file, not a folder", flag=flag)
            break
    return target


def foreign_files(folder: Path) -> list[str]:
    """
    What under an earlier ``reproduce`` folder its :data:`MANIFEST` does not list among its ``artifacts``
    (relative paths, sorted; folders end in ``/``): files, links (never followed) and folders that hold no
    listed file. Replacing the folder would delete them. Everything is foreign when the manifest cannot be read.
    """
    try:
        manifest = read_input(folder / MANIFEST, MANIFEST_BYTES_MAX, f"a {MANIFEST}").decode("utf-8")
        artifacts = [Path(p) for p in json.loads(manifest)["artifacts"]]
        written = next(p.parent for p in artifacts if p.name == MANIFEST)  # the folder as it was named then
        listed = {p.relative_to(written).as_posix() for p in artifacts}
    except (OSError, ValueError, KeyError, TypeError, StopIteration):  # SkinrenderError is a ValueError
        listed = set()
    foreign = []
    for root, folders, files in os.walk(folder):  # links to folders are listed among folders, not entered
        here = Path(root).relative_to(folder)
        for name in files + [f for f in folders if (Path(root) / f).is_symlink()]:
            relative = (here / name).as_posix()
            if relative not in listed and relative != MANIFEST:
                foreign.append(relative)
        for name in folders:
            relative = (here / name).as_posix()
            if not (Path(root) / name).is_symlink() and not any(item.startswith(relative + "/") for item in listed):
                foreign.append(relative + "/")
    return sorted(foreign)


@contextmanager
def output_folder(target: Path, flag: str = "-o"):
    """
    Yield a new temporary folder beside ``target`` (``.NAME.partial-XXXX``);
    on success it replaces ``target``, on any exception it is removed, as are
    the parent folders this call created.
    """
    created = []
    for ancestor in reversed(target.parents):
        if not ancestor.exists():
            created.append(ancestor)
    try:
        for folder in created:
            folder.mkdir()
        temporary = Path(tempfile.mkdtemp(prefix=f".{target.name[:100]}.partial-", dir=target.parent))
        mask = os.umask(0)
        os.umask(mask)
        os.chmod(temporary, 0o777 & ~mask)  # mkdtemp's 0700 would outlive the move
    except OSError as error:
        _remove_created(created)
        raise OutputError(f"{flag} {target}: cannot write there ({reason_of(error)})", flag, error) from None
    try:
        yield temporary
        _move_into_place(temporary, target)
    except BaseException as error:
        shutil.rmtree(temporary, ignore_errors=True)
        _remove_created(created)
        if isinstance(error, OutputError) and error.flag is None:  # a file of the folder could not be written
            raise OutputError(f"{flag} {target}: cannot be written ({error.reason}); nothing was left there", flag,
                              error.oserror) from None
        if isinstance(error, OSError) and str(error.filename or "").startswith(str(temporary)):
            raise OutputError(f"{flag} {target}: cannot be written ({reason_of(error)}); nothing was left there",
                              flag, error) from None
        raise


def _remove_created(created: list[Path]) -> None:
    for folder in reversed(created):
        try:
            folder.rmdir()
        except OSError:
            break


def _move_into_place(temporary: Path, target: Path) -> None:
    """
    ``temporary`` becomes ``target``; a previous ``target`` (empty or an earlier run's) is removed — unless
    files it did not hold at the start were put there during the run (:func:`foreign_files`): then it is kept
    beside, as ``NAME.previous-XXXX``, rather than deleted with them.
    """
    if not target.exists():
        os.rename(temporary, target)
        return
    keep = (target / MANIFEST).is_file() and bool(foreign_files(target))
    old = Path(tempfile.mkdtemp(prefix=f"{target.name[:100]}.previous-" if keep else f".{target.name[:100]}.old-",
                                dir=target.parent))
    os.rename(target, old / target.name)
    os.rename(temporary, target)
    if not keep:
        shutil.rmtree(old, ignore_errors=True)
