"""Tests for :mod:`skinrender.studies.paper.reproduce`: a tiny reproduction writes its tables and matches; refusals leave nothing."""

from __future__ import annotations

import json
import os

import pytest

from skinrender.cli import main
from skinrender.errors import SkinrenderError
from skinrender.studies.paper.folders import foreign_files
from skinrender.studies.paper.reproduce import reproduce, summary_text
from skinrender.studies.paper.sweep import reproduce_sweep


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    """Sensors 1 and 9 on a 50 nm peak grid, everything else as the paper's defaults."""
    out = tmp_path_factory.mktemp("reproduce") / "out"
    return out, reproduce(out, [1, 9], "400:700:50", workers=2, progress=None)


class TestReproduce:
    def test_writes_tables_figures_and_manifest(self, tiny):
        out, result = tiny
        names = set(os.listdir(out))
        assert {"tables.md", "table2_skin.csv", "table5_ratio.csv", "fig3_560nm.png", "fig7_cases.png", "search",
                "reproduce.json"} <= names
        assert not any(name.startswith(".") for name in os.listdir(out.parent))  # no temporary folder left
        assert json.loads((out / "reproduce.json").read_text())["matches"] == result["matches"]
        assert all(os.path.exists(p) for p in result["artifacts"])

    def test_matches(self, tiny):
        _, result = tiny
        matches = result["matches"]
        assert set(matches) == {"exact", "within_step", "total"} and matches["total"] == 12
        assert 0 <= matches["exact"] <= matches["within_step"] <= 12
        assert sum(v["exact"] for v in result["matches_by_table"].values()) == matches["exact"]
        assert result["matches_temperature"]["total"] == 6

    def test_setting_and_observations(self, tiny):
        _, result = tiny
        assert result["setting"]["slope"] == 2.0 and result["setting"]["grid"] == "400:700:1"
        assert len(result["illuminants_K"]) == 10 and set(result["search_s"]) == {"1", "9"}
        cameras = [row["camera"] for row in result["stage2_by_camera"]]
        assert "Nikon 5100 (NPL)" in cameras
        assert {"560nm", "euclidean", "white", "as_paper", "total"} <= set(result["stage2_by_camera"][0])
        assert [row["camera"] for row in result["stage1_text"]["cameras"]] == cameras
        assert "of 12 cells exactly" in summary_text(result)
        assert result["notes"] == []  # the paper has rows for sensors 1 and 9
        unlisted = dict(result, notes=["sensor 17: the paper's Tables 2–5 have no row for it"])
        assert summary_text(unlisted).endswith("note: sensor 17: the paper's Tables 2–5 have no row for it")

    def test_rerun_replaces_an_earlier_run(self, tmp_path):
        out = tmp_path / "out"
        for _ in range(2):
            result = reproduce(out, [1], "400:700:100", workers=1, progress=None, observations=False, figures=False)
        assert os.listdir(tmp_path) == ["out"]
        assert result["stage2"] == {} and not any(name.endswith(".png") for name in os.listdir(out))

    def test_a_sweep_folder_and_a_reproduce_folder_replace_each_other(self, tmp_path):
        # the manifests the two write are read back by the check that protects a user's own files
        out = tmp_path / "out"
        reproduce_sweep(out, [9], "400:700:100", candidates={}, combine=0, workers=1)
        assert foreign_files(out) == []
        reproduce(out, [9], "400:700:100", workers=1, progress=None, observations=False, figures=False)
        assert foreign_files(out) == [] and "tables.md" in os.listdir(out)
        reproduce_sweep(out, [9], "400:700:100", candidates={}, combine=0, workers=1)
        assert sorted(os.listdir(out)) == ["reproduce.json", "sweep.csv", "sweep.md"]


class TestRefusals:
    @pytest.mark.parametrize(("options", "flag"), [
        ({"sensors": "1,x"}, "--sensors"), ({"positions": "400:900:10"}, "--positions"),
        ({"camera_spec": "Sony 755"}, "--camera"), ({"skin": "nope"}, "--skin"), ({"munsell": "nope"}, "--munsell"),
        ({"slope": -1.0}, "--slope"), ({"workers": 0}, "--workers"), ({"illuminants": "2000,x"}, "--illuminants"),
        ({"grid": "400:700:7"}, "--grid"), ({"illuminants": "auto", "stage1_camera": "x"}, "--stage1-camera"),
    ])
    def test_bad_arguments_leave_no_folder(self, tmp_path, options, flag):
        with pytest.raises(SkinrenderError, match=f"^{flag}"):
            reproduce(tmp_path / "out", **{"sensors": [9], "positions": "400:700:100", **options})
        assert os.listdir(tmp_path) == []

    def test_a_bad_stage2_camera_stops_the_searches_it_overlaps(self, tmp_path):
        """The Stage 2 camera is checked once the workers run (loading it imports colour): a bad one
        stops them at once, with the refusal every other argument gets and nothing left behind."""
        import multiprocessing

        with pytest.raises(SkinrenderError, match="^--camera"):
            reproduce(tmp_path / "out", sensors=[9, 11], positions="400:700:10", camera_spec="Sony 755", workers=2)
        assert multiprocessing.active_children() == [] and os.listdir(tmp_path) == []

    def test_output_refusals_on_the_command_line(self, tmp_path, capsys):
        (tmp_path / "file").write_text("x")
        for target in ("", str(tmp_path / "file"), "/proc/skinrender-no/out"):
            assert main(["reproduce", "-o", target, "--sensors", "9", "--positions", "400:700:100"]) == 2
            err = capsys.readouterr().err
            assert err.count("\n") == 1 and "-o" in err and "Traceback" not in err
        assert os.listdir(tmp_path) == ["file"]

    def test_stage1_camera_needs_auto(self, capsys):
        assert main(["reproduce", "-o", "x", "--stage1-camera", "Kodak DCS-200"]) == 2
        assert "--stage1-camera" in capsys.readouterr().err
