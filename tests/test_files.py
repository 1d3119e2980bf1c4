"""
Tests for :mod:`skinrender.files`: inputs are read only when they are regular files of bounded size (a pipe, a
device, a folder, an oversized file or a name too long is refused at once, naming what it is), and outputs are
written whole or not at all (a full disk, a failed rename or an interrupt leaves nothing new behind).
"""

from __future__ import annotations

import errno
import os

import pytest

from skinrender import files
from skinrender.errors import SkinrenderError
from skinrender.files import Output, OutputError, check_output_path, exists, read_input, write_output, write_outputs

from .cli.refusal import full_disk

LONG = "n" * 300
"""A file name longer than any file system takes (255 bytes)."""


class TestReadInput:
    def test_a_regular_file_is_read_whole(self, tmp_path):
        (tmp_path / "a.csv").write_bytes(b"nm,a\n400,0.5\n")
        assert read_input(tmp_path / "a.csv", 100) == b"nm,a\n400,0.5\n"

    def test_a_symbolic_link_is_followed(self, tmp_path):
        (tmp_path / "a.csv").write_bytes(b"x")
        (tmp_path / "link.csv").symlink_to(tmp_path / "a.csv")
        assert read_input(tmp_path / "link.csv", 100) == b"x"

    def test_a_named_pipe_is_refused_without_waiting_for_a_writer(self, tmp_path):
        """Seen: a scene given as a named pipe blocked forever."""
        os.mkfifo(tmp_path / "pipe.toml")
        with pytest.raises(SkinrenderError, match="a named pipe, not a regular file"):
            read_input(tmp_path / "pipe.toml", 100, "a scene TOML")

    @pytest.mark.parametrize("target", ["/dev/zero", "/dev/urandom"])
    def test_a_device_behind_a_link_is_refused_unread(self, target, tmp_path):
        """Seen: ``render /dev/zero`` reached 12.8 GB in 15 s; a .toml link to /dev/zero 5.8 GB."""
        if not os.path.exists(target):
            pytest.skip(f"no {target}")
        (tmp_path / "scene.toml").symlink_to(target)
        with pytest.raises(SkinrenderError, match="a device, not a regular file; expected a scene TOML"):
            read_input(tmp_path / "scene.toml", 10**12, "a scene TOML")

    def test_a_folder_is_refused(self, tmp_path):
        (tmp_path / "set.csv").mkdir()
        with pytest.raises(SkinrenderError, match="a folder"):
            read_input(tmp_path / "set.csv", 100)

    def test_check_input_refuses_as_read_input_does_without_reading(self, tmp_path):
        """For files a library opens itself (OpenEXR): a pipe, a device, an oversized file refused; a file passes."""
        from skinrender.files import check_input

        os.mkfifo(tmp_path / "pipe.exr")
        with pytest.raises(SkinrenderError, match="a named pipe, not a regular file; expected an EXR image"):
            check_input(tmp_path / "pipe.exr", 100, "an EXR image")
        with open(tmp_path / "big.exr", "wb") as handle:
            handle.truncate(10**6)
        with pytest.raises(SkinrenderError, match=r"1 MB is larger than an EXR image may be \(0.001 MB\)"):
            check_input(tmp_path / "big.exr", 1000, "an EXR image")
        with pytest.raises(SkinrenderError, match="no such file"):
            check_input(tmp_path / "none.exr", 1000)
        assert check_input(tmp_path / "big.exr", 10**6) is None

    def test_an_oversized_file_is_refused_before_it_is_read(self, tmp_path):
        path = tmp_path / "big.csv"
        with open(path, "wb") as handle:  # sparse: no disk used
            handle.truncate(10**9)
        with pytest.raises(SkinrenderError, match=r"1e\+03 MB is larger than a spectral CSV may be \(64 MB\)"):
            read_input(path, 64_000_000, "a spectral CSV")

    @pytest.mark.parametrize("name, reason", [(LONG + ".csv", "the name is too long"), ("missing.csv", "no such file")])
    def test_a_path_that_cannot_be_opened_says_why(self, name, reason, tmp_path):
        with pytest.raises(SkinrenderError, match=reason) as caught:
            read_input(tmp_path / name, 100)
        assert len(str(caught.value)) < 200  # a long name is cut in the middle: one readable line

    def test_exists_refuses_a_name_too_long_rather_than_saying_no(self, tmp_path):
        assert exists(tmp_path) and not exists(tmp_path / "missing") and not exists("gbell:9@450,540,610")
        with pytest.raises(SkinrenderError, match="the name is too long"):
            exists(tmp_path / LONG)


class TestWriteOutputs:
    def test_every_output_is_written_and_parents_made(self, tmp_path):
        written = write_outputs(Output(tmp_path / "a.png", "--output", b"a"),
                                Output(tmp_path / "new" / "b.png", "--figure", lambda stream: stream.write(b"b")))
        assert [p.read_bytes() for p in written] == [b"a", b"b"]
        assert sorted(p.name for p in tmp_path.rglob("*")) == ["a.png", "b.png", "new"]

    @pytest.mark.parametrize("after", [0, 1])
    def test_a_full_disk_leaves_nothing_new_behind(self, after, tmp_path, monkeypatch):
        """Seen: ``render -o`` left a truncated EXR; ``detect -o m.png --figure f.png`` left m.png and its preview.
        The disk fills on the first or the second file: no temporary, no target, no folder made is left, an
        earlier file of the same name is untouched, and the message names the flag and the reason."""
        (tmp_path / "m.png").write_bytes(b"earlier")
        full_disk(monkeypatch, after)
        with pytest.raises(OutputError) as caught:
            write_outputs(Output(tmp_path / "m.png", "--output", b"mask"),
                          Output(tmp_path / "figures" / "f.png", "--figure", b"figure"))
        assert caught.value.status == 1 and caught.value.flag == ("--output", "--figure")[after]
        assert str(caught.value).startswith(("--output", "--figure")[after])
        assert "no space left on the device (the disk is full)" in str(caught.value)
        assert sorted(p.name for p in tmp_path.rglob("*")) == ["m.png"]
        assert (tmp_path / "m.png").read_bytes() == b"earlier"

    def test_a_failed_rename_leaves_no_temporary(self, tmp_path, monkeypatch):
        def rename(source, target):
            raise OSError(errno.EIO, os.strerror(errno.EIO))

        monkeypatch.setattr(files.os, "replace", rename)
        with pytest.raises(OutputError, match="--csv .*input/output error"):
            write_output(tmp_path / "rows.csv", "a,b\n", "--csv")
        assert list(tmp_path.iterdir()) == []

    def test_an_interrupt_while_writing_leaves_nothing(self, tmp_path, monkeypatch):
        def write(handle, data):
            raise KeyboardInterrupt

        monkeypatch.setattr(files.os, "write", write)
        with pytest.raises(KeyboardInterrupt):
            write_output(tmp_path / "out" / "r.exr", b"x", "--output")
        assert list(tmp_path.iterdir()) == []

    def test_an_immediate_exit_removes_the_writes_under_way(self, tmp_path, monkeypatch):
        """Ctrl-C while a command's worker thread writes: the main thread exits at once (os._exit) after
        :func:`~skinrender.files.remove_pending`, which leaves no temporary and no new folder."""
        seen = []

        def write(handle, data):  # the main thread's turn, mid-write
            seen.append(sorted(p.name for p in (tmp_path / "new").iterdir()))
            files.remove_pending()
            raise SystemExit(130)

        monkeypatch.setattr(files.os, "write", write)
        with pytest.raises(SystemExit):
            write_output(tmp_path / "new" / "r.exr", b"x", "--output")
        assert len(seen[0]) == 1 and seen[0][0].startswith(".r.exr.") and seen[0][0].endswith(".partial")
        assert list(tmp_path.iterdir()) == [] and files._PENDING == []

    def test_content_that_fails_to_draw_writes_nothing(self, tmp_path):
        def draw(stream):
            raise ValueError("no figure")

        with pytest.raises(ValueError):
            write_outputs(Output(tmp_path / "a.png", "--output", b"a"), Output(tmp_path / "f.png", "--figure", draw))
        assert list(tmp_path.iterdir()) == []

    def test_a_link_to_a_file_is_written_through(self, tmp_path):
        (tmp_path / "real.csv").write_text("old")
        (tmp_path / "link.csv").symlink_to(tmp_path / "real.csv")
        assert write_output(tmp_path / "link.csv", "new", "--csv") == tmp_path / "real.csv"
        assert (tmp_path / "link.csv").is_symlink() and (tmp_path / "real.csv").read_text() == "new"

    def test_one_file_named_twice_is_refused(self, tmp_path):
        with pytest.raises(SkinrenderError, match="name one file twice"):
            write_outputs(Output(tmp_path / "a.png", "--output", b"a"), Output(tmp_path / "a.png", "--figure", b"b"))


class TestCheckOutputPath:
    def test_a_dangling_link_is_refused_naming_the_flag(self, tmp_path):
        """Seen: a dangling-symlink -o was an internal error from OpenEXR after the render."""
        (tmp_path / "r.exr").symlink_to(tmp_path / "missing" / "r.exr")
        with pytest.raises(SkinrenderError, match=r"--output .*r\.exr: a symbolic link to nothing"):
            check_output_path(tmp_path / "r.exr", "--output")

    @pytest.mark.parametrize("name", [LONG + ".png", LONG + "/f.png", "a/" * 2100 + "f.png"])
    def test_a_name_too_long_is_refused_naming_the_flag(self, name, tmp_path):
        """Seen: ENAMETOOLONG on -o was an internal error."""
        with pytest.raises(OutputError, match=r"--plot .*cannot be written \(the name is too long") as caught:
            check_output_path(tmp_path / name, "--plot")
        assert caught.value.status == 2 and not any(tmp_path.iterdir())

    def test_a_folder_or_a_device_is_refused(self, tmp_path):
        with pytest.raises(SkinrenderError, match="a folder, expected a file"):
            check_output_path(tmp_path, "--csv")
        with pytest.raises(SkinrenderError, match="a device, expected a regular file"):
            check_output_path("/dev/null", "--csv")

    def test_a_missing_folder_is_fine_and_nothing_is_made(self, tmp_path):
        assert check_output_path(tmp_path / "a" / "b" / "f.png", "--figure") == tmp_path / "a" / "b" / "f.png"
        assert list(tmp_path.iterdir()) == []

    @pytest.mark.skipif(os.geteuid() == 0, reason="root writes anywhere")
    def test_a_folder_without_permission_is_refused(self, tmp_path):
        locked = tmp_path / "locked"
        locked.mkdir(mode=0o500)
        with pytest.raises(OutputError, match="permission denied"):
            check_output_path(locked / "f.png", "--figure")


class TestStandardOutput:
    """Issue 36: Python's buffered standard output dropped the rest of a document after one short write (a disk
    filling under ``> k.json``: 4 096 bytes, exit status 0). :func:`skinrender.files.write_stdout` checks every
    write (the whole command: ``tests/test_cli.py``)."""

    @staticmethod
    def stdout_on(monkeypatch, handle: int):
        import io
        import sys

        stream = io.TextIOWrapper(io.FileIO(handle, "w", closefd=False), encoding="utf-8")
        monkeypatch.setattr(sys, "stdout", stream)
        return stream

    def test_short_writes_are_continued(self, monkeypatch):
        from skinrender import files

        read, write = os.pipe()
        self.stdout_on(monkeypatch, write)
        real = os.write
        monkeypatch.setattr(files.os, "write", lambda handle, data: real(handle, bytes(data)[:3]))  # 3 bytes a time
        files.write_stdout("é, a document\n")
        os.close(write)
        assert os.read(read, 100).decode("utf-8") == "é, a document\n"
        os.close(read)

    @pytest.mark.parametrize("errno_, status", [(errno.ENOSPC, 1), (errno.EFBIG, 1)])
    def test_a_failed_write_names_standard_output(self, monkeypatch, errno_, status):
        from skinrender import files

        read, write = os.pipe()
        self.stdout_on(monkeypatch, write)

        def fail(handle, data):
            raise OSError(errno_, os.strerror(errno_))

        monkeypatch.setattr(files.os, "write", fail)
        with pytest.raises(files.OutputError, match="^standard output: cannot be written .*; the output is "
                           "incomplete$") as error:
            files.write_stdout("{}\n")
        assert error.value.status == status and error.value.flag == "standard output"
        os.close(read)
        os.close(write)

    def test_a_stream_without_a_descriptor_is_written_as_it_is(self, capsys):
        from skinrender import files

        files.write_stdout("captured\n")
        assert capsys.readouterr().out == "captured\n"
