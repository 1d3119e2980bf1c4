"""Tests for :mod:`skinrender.studies.paper.folders`: an output folder is complete or absent."""

from __future__ import annotations

import json
import os

import pytest

from skinrender.errors import SkinrenderError
from skinrender.studies.paper.folders import MANIFEST, check_output, foreign_files, output_folder


class TestCheckOutput:
    @pytest.mark.parametrize("bad", ["", "  ", None])
    def test_empty_is_refused(self, bad):
        with pytest.raises(SkinrenderError, match="^-o must name"):
            check_output(bad)

    def test_existing_file(self, tmp_path):
        path = tmp_path / "file"
        path.write_text("x")
        with pytest.raises(SkinrenderError, match="^-o .*an existing file"):
            check_output(path)

    def test_under_a_file(self, tmp_path):
        (tmp_path / "file").write_text("x")
        with pytest.raises(SkinrenderError, match="is a file"):
            check_output(tmp_path / "file" / "out")

    def test_foreign_folder(self, tmp_path):
        (tmp_path / "notes.txt").write_text("mine")
        with pytest.raises(SkinrenderError, match="holds other files"):
            check_output(tmp_path)

    def test_new_empty_or_earlier_run(self, tmp_path):
        assert check_output(tmp_path / "new") == tmp_path / "new"
        assert check_output(tmp_path) == tmp_path
        earlier_run(tmp_path, ["tables.md", "search/sensor_9.csv"])
        assert check_output(tmp_path) == tmp_path

    def test_an_earlier_run_moved_elsewhere_is_still_one(self, tmp_path):
        earlier_run(tmp_path / "then", ["tables.md"])
        os.rename(tmp_path / "then", tmp_path / "now")
        assert check_output(tmp_path / "now") == tmp_path / "now"

    @pytest.mark.parametrize("manifest", ["listed", "{}", "not json"])
    def test_files_an_earlier_run_did_not_write_are_not_deleted(self, tmp_path, manifest):
        earlier_run(tmp_path, ["tables.md"])
        if manifest != "listed":
            (tmp_path / MANIFEST).write_text(manifest)
        (tmp_path / "search").mkdir()
        (tmp_path / "search" / "my_notes.txt").write_text("mine")
        with pytest.raises(SkinrenderError, match=r"^-o .*did not write \(.*my_notes\.txt"):
            check_output(tmp_path)
        assert "search/my_notes.txt" in foreign_files(tmp_path)
        assert (tmp_path / "search" / "my_notes.txt").read_text() == "mine"

    def test_links_and_folders_it_did_not_write_are_foreign_too(self, tmp_path):
        earlier_run(tmp_path / "out", ["tables.md", "search/sensor_9.csv"])
        (tmp_path / "mine").mkdir()
        (tmp_path / "out" / "empty").mkdir()
        (tmp_path / "out" / "link").symlink_to(tmp_path / "mine")
        assert foreign_files(tmp_path / "out") == ["empty/", "link"]


def earlier_run(folder, names: list[str]) -> None:
    """A folder as ``reproduce`` leaves it: the files ``names`` and a manifest listing them (absolute paths)."""
    for name in names:
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text("old")
    artifacts = [str(folder / name) for name in names] + [str(folder / MANIFEST)]
    (folder / MANIFEST).write_text(json.dumps({"artifacts": artifacts}))


class TestOutputFolder:
    def test_moved_into_place(self, tmp_path):
        target = tmp_path / "a" / "b"
        with output_folder(target) as folder:
            assert folder.parent == target.parent and folder.name.startswith(".b.partial-")
            assert not target.exists()
            (folder / "x.txt").write_text("done")
        assert (target / "x.txt").read_text() == "done"
        assert sorted(os.listdir(tmp_path / "a")) == ["b"]

    def test_replaces_an_earlier_run(self, tmp_path):
        target = tmp_path / "out"
        target.mkdir()
        earlier_run(target, ["old.csv", "search/old.csv"])
        with output_folder(target) as folder:
            (folder / "new.csv").write_text("new")
        assert sorted(os.listdir(target)) == ["new.csv"]
        assert os.listdir(tmp_path) == ["out"]

    def test_files_put_into_the_old_folder_during_the_run_are_kept(self, tmp_path):
        target = tmp_path / "out"
        target.mkdir()
        earlier_run(target, ["old.csv"])
        with output_folder(check_output(target)) as folder:
            (target / "notes.txt").write_text("written while it ran")
            (folder / "new.csv").write_text("new")
        assert sorted(os.listdir(target)) == ["new.csv"]
        kept = [name for name in os.listdir(tmp_path) if name.startswith("out.previous-")]
        assert len(kept) == 1 and (tmp_path / kept[0] / "out" / "notes.txt").read_text() == "written while it ran"

    def test_failure_leaves_nothing(self, tmp_path):
        target = tmp_path / "a" / "b"
        with pytest.raises(KeyboardInterrupt):
            with output_folder(target) as folder:
                (folder / "half.csv").write_text("half")
                raise KeyboardInterrupt
        assert os.listdir(tmp_path) == []

    def test_unwritable_place(self, tmp_path):
        if os.geteuid() == 0:  # root writes anywhere but into /proc
            target = "/proc/skinrender-not-here/out"
        else:
            locked = tmp_path / "locked"
            locked.mkdir(mode=0o555)
            target = locked / "out"
        with pytest.raises(SkinrenderError, match="^-o .*cannot write there"):
            with output_folder(check_output(target)):
                pass
