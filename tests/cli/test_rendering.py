"""
Bad inputs to ``render``, ``validate`` and ``detect`` (:mod:`skinrender.cli.rendering`) are refused before
anything renders; Mitsuba's own warnings stay off stdout; undefined rates are null with their reason.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from .refusal import assert_refused, bad_files, interrupt_after, run  # noqa: F401  (fixture)
from skinrender.files import shown  # long paths are cut in messages (tmp_path under xdist is long)

pytest.importorskip("mitsuba")

CAM = "gbell:9@450,540,610"
LIGHTS = ["--prevailing", "A", "--calibration", "H"]


@pytest.fixture(params=["render", "validate", "detect"])
def command(request, tmp_path):
    """Each render command with a valid output in ``tmp_path``."""
    output = {"render": ["-o", tmp_path / "r.exr"], "detect": ["-o", tmp_path / "m.png"], "validate": []}
    return [request.param], output[request.param], tmp_path


@pytest.mark.parametrize("extra, names", [
    (["--seed", "-1"], "--seed"),
    (["--seed", "4294967295"], "--seed"),
    (["--seed", "99999999999999"], "--seed"),
    (["--seed", "1.5"], "--seed"),
    (["--spp", "0"], "--spp"),
    (["--spp", "1000000000"], "--spp"),
    (["--camera", "Sony 755"], "--camera"),
    (["--camera", "impulse@401.5,500,600"], "--camera"),
    (["--prevailing", "20"], ("prevailing", "no light")),
    (["--calibration", "20"], ("calibration", "no light")),
    # issue 36: "--calibration: prevailing illuminant 1K …" (the light was checked as a prevailing one)
    (["--calibration", "1"], "--calibration: calibration illuminant 1K gives no light"),
    (["--prevailing", "1"], "--prevailing: prevailing illuminant 1K gives no light"),
    (["--prevailing", "x"], "--prevailing"),
    (["--sampler", "random"], "--sampler"),
    (["--quality", "ultra"], "--quality"),
    (["--channels", "two"], "--channels"),
    (["--variant", "nosuch_spectral"], "variant"),
    (["--imager", "nosuch"], "--imager"),
    (["--imager", "sony-imx174", "--illuminance", "-5"], "--illuminance"),
    (["--imager", "sony-imx174", "--illuminance", "nan"], "--illuminance"),
    (["--imager", "sony-imx174", "--exposure", "soon"], "--exposure"),
    (["--imager", "sony-imx174", "--exposure", "0"], "--exposure"),
])
def test_render_commands_refuse(command, extra, names, capsys):
    name, output, folder = command
    argv = [*name, "macbeth", "--camera", CAM, *LIGHTS, "--spp", "4", *output]
    assert_refused(argv + extra, names, capsys, output=folder)


@pytest.mark.parametrize("key, names", [
    ("folder.toml", "folder"), ("scene_bad_toml.toml", "TOML"), ("scene_unknown_field.toml", "colour"),
    ("scene_no_patch.toml", "patch"), ("scene_black_white.toml", "white"), ("scene_huge.toml", "pixels"),
    ("scene_one_pixel.toml", "pixel"), ("scene_unknown_reflectance.toml", "nosuchset"),
])
def test_bad_scene_files_are_refused(key, names, bad_files, capsys):
    assert_refused(["render", bad_files[key], "--camera", CAM, *LIGHTS], ("SCENE", names), capsys)


@pytest.mark.parametrize("scene", ["", "no_such_scene"])
def test_bad_scene_names_are_refused(scene, capsys):
    assert_refused(["validate", scene, "--camera", CAM, *LIGHTS], "SCENE", capsys)


@pytest.mark.parametrize("output", ["folder", "png", "empty", "parent_file"])
def test_render_checks_its_output_before_rendering(output, bad_files, tmp_path, capsys):
    path = {"folder": tmp_path, "png": tmp_path / "r.png", "empty": "", "parent_file": bad_files["a_file"] / "r.exr"}
    assert_refused(["render", "macbeth", "--camera", CAM, *LIGHTS, "-o", path[output]], "--output", capsys,
                   output=tmp_path)


def test_render_with_a_preview_path_taken_by_a_folder_writes_nothing(tmp_path, capsys):
    (tmp_path / "r.png").mkdir()
    assert_refused(["render", "macbeth", "--camera", CAM, *LIGHTS, "-o", tmp_path / "r.exr"], "--output", capsys,
                   output=tmp_path)


@pytest.mark.parametrize("output", ["folder", "txt", "empty"])
def test_detect_checks_its_output_before_rendering(output, tmp_path, capsys):
    path = {"folder": tmp_path, "txt": tmp_path / "m.txt", "empty": ""}
    assert_refused(["detect", "skin_patches", "--camera", CAM, *LIGHTS, "-o", path[output]], "--output", capsys,
                   output=tmp_path)


def test_rounded_spp_is_reported_and_the_json_stays_one_document(tmp_path, capsys):
    """multijitter rounds 7 spp up to 8; Mitsuba's warning goes to stderr, the JSON reports the count used."""
    status, out, err = run(["render", "macbeth", "--camera", CAM, *LIGHTS, "--spp", "7", "-o", tmp_path / "r.exr",
                            "--json"], capsys)
    document = json.loads(out)
    assert status == 0 and document["spp"] == 8 and document["spp_requested"] == 7
    assert "WARN" not in err and err.count("rounded") == 1  # Mitsuba's warnings said once, by the command line
    assert err.strip().splitlines()[-1] == ("skinrender render: note: the sampler rounded the samples per pixel up "
                                            "to 8 (1 render pass; multijitter takes a product of two integers): "
                                            "each JSON's 'spp' is the count used")


def test_the_exr_header_traces_the_camera(tmp_path, capsys):
    """``render``'s EXR carries its camera's curves' SHA-256 (on the --grid), and reads back by name."""
    from skinrender.model.camera import camera
    from skinrender.rendering.exr import camera_attributes, read_exr, read_exr_attributes
    from skinrender.spectra import WavelengthGrid

    status, out, err = run(["render", "macbeth", "--camera", "Kodak DCS-200", *LIGHTS, "--spp", "4", "--grid",
                            "400:700:2", "-o", tmp_path / "r.exr"], capsys)
    assert status == 0, err
    attributes = read_exr_attributes(tmp_path / "r.exr")
    grid = WavelengthGrid.parse("400:700:2")
    assert attributes["camera_sha256"] == camera_attributes(camera("Kodak DCS-200"), grid)["camera_sha256"]
    assert attributes["camera_grid_nm"] == "400:700:2" and read_exr(tmp_path / "r.exr", ("R", "G", "B")).shape[-1] == 3


def test_a_black_patch_renders_and_validates(tmp_path, capsys):
    scene = tmp_path / "black.toml"
    scene.write_text("columns = 2\n[[patch]]\nname = 'black'\nreflectance = 'grey:0'\n"
                     "[[patch]]\nreflectance = 'grey:0.5'\n")
    status, out, err = run(["validate", scene, "--camera", CAM, *LIGHTS, "--spp", "4", "--tolerance", "0.2",
                            "--json"], capsys)
    document = json.loads(out)
    assert status == 0, err
    assert document["patches"][0]["rendered"] == [0.0, 0.0, 0.0] and document["passed"]
    assert document["patches"][0]["shown"] == ["within"] * 3 and document["verdict"] == "pass"


def test_detect_on_a_chart_without_non_skin_says_the_rate_is_undefined(tmp_path, capsys):
    status, out, err = run(["detect", "skin_patches", "--camera", CAM, "--prevailing", "A", "--calibration", "A",
                            "--spp", "4", "-o", tmp_path / "m.png", "--json"], capsys)
    document = json.loads(out)
    assert status == 0, err
    assert document["fpr"] is None and "no non-skin" in document["undefined"]["fpr"]
    assert 0.0 <= document["tpr"] <= 1.0


def test_validate_through_an_imager_reports_the_noise(capsys):
    """``validate --imager``: per patch rendered and predicted standard deviations, the sensor's settings."""
    status, out, err = run(["validate", "macbeth", "--camera", CAM, *LIGHTS, "--spp", "64", "--imager", "sony-imx174",
                            "--illuminance", "300", "--tolerance", "0.05", "--json"], capsys)
    document = json.loads(out)
    assert status == 0, err
    assert document["imager"] == "sony-imx174" and document["illuminance_lux"] == 300.0 and document["exposure_s"] > 0
    assert document["passed"] and all(len(p["rendered_std"]) == 3 for p in document["patches"])
    assert set(document["checks"]) == {"mean", "variance", "equivalence", "difference"}
    assert document["mc_variance"] == "frames" and document["bound"] < 0.05


def test_render_through_an_imager_says_what_it_clipped_and_capped(tmp_path, capsys):
    """A 10 s exposure fills every well: ``clipping`` counts the pixels and a note says so; a dim auto
    exposure stopped at a video frame is noted (JSON ``notes`` and the text's ``note:`` lines)."""
    status, out, err = run(["render", "macbeth", "--camera", CAM, *LIGHTS, "--spp", "4", "-o", tmp_path / "r.exr",
                            "--imager", "sony-imx174", "--illuminance", "500", "--exposure", "10", "--json"], capsys)
    document = json.loads(out)
    assert status == 0, err
    assert document["clipping"] and any("clipped" in note for note in document["notes"])
    status, out, err = run(["render", "macbeth", "--camera", CAM, *LIGHTS, "--spp", "4", "-o", tmp_path / "d.exr",
                            "--imager", "sony-imx174", "--illuminance", "0.5"], capsys)
    assert status == 0, err
    assert "note: auto exposure capped" in out


def test_render_figure_labels_the_chart(tmp_path, capsys):
    """``render --figure``: the chart upscaled with its patch names, far larger than the 130 × 82 preview."""
    from PIL import Image

    figure = tmp_path / "labelled.png"
    status, out, err = run(["render", "macbeth", "--camera", CAM, *LIGHTS, "--spp", "4", "-o", tmp_path / "r.exr",
                            "--figure", figure, "--json"], capsys)
    document = json.loads(out)
    assert status == 0, err
    assert document["figure"] == str(figure)
    preview, labelled = Image.open(document["preview_png"]).size, Image.open(figure).size
    assert labelled[0] >= 5 * preview[0] and labelled[1] >= 5 * preview[1]


def test_detect_figure_adds_the_mask_panel(tmp_path, capsys):
    from PIL import Image

    status, out, err = run(["detect", "face_chart", "--camera", CAM, *LIGHTS, "--spp", "4", "-o", tmp_path / "m.png",
                            "--figure", tmp_path / "d.png", "--json"], capsys)
    document = json.loads(out)
    assert status == 0, err
    width, height = Image.open(document["figure"]).size
    assert height > width  # two chart panels, one above the other


@pytest.mark.parametrize("command, figure", [
    ("render", "f.svg"), ("render", "r.png"), ("render", "folder"), ("detect", "m.png"), ("detect", "m_preview.png"),
    ("detect", "f.pdf"), ("detect", ""),
])
def test_figure_is_checked_before_rendering(command, figure, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "folder").mkdir()
    output = "r.exr" if command == "render" else "m.png"
    assert_refused([command, "face_chart", "--camera", CAM, *LIGHTS, "-o", output, "--figure", figure], "--figure",
                   capsys, output=tmp_path)


def test_validate_takes_no_figure(capsys):
    status, out, err = run(["validate", "macbeth", "--camera", CAM, *LIGHTS, "--figure", "f.png"], capsys)
    assert status == 2 and out == "" and "--figure" in err


def test_detect_on_a_black_chart_has_null_rates_with_the_reason(tmp_path, capsys):
    """Seen by a user: a black chart reported fpr 0.0; nothing there has a colour, so both rates are null."""
    scene = tmp_path / "black.toml"
    scene.write_text("columns = 2\n[[patch]]\nname = 'black skin'\nreflectance = 'grey:0'\nskin = true\n"
                     "[[patch]]\nname = 'black'\nreflectance = 'grey:0'\n")
    status, out, err = run(["detect", scene, "--camera", CAM, *LIGHTS, "--spp", "4", "-o", tmp_path / "m.png",
                            "--json"], capsys)
    document = json.loads(out)
    assert status == 0, err
    assert document["tpr"] is None and document["fpr"] is None
    assert "no scored non-skin pixel" in document["undefined"]["fpr"] and "no scored skin" in document["undefined"]["tpr"]
    assert document["scored_min_output"] > 0
    assert [row["detected_fraction"] for row in document["per_patch"]] == [None, None]
    assert all(row["scored_pixels"] == 0 < row["pixels"] for row in document["per_patch"])


def test_a_grid_outside_the_charts_data_is_refused_before_rendering(tmp_path, capsys):
    """The chart's reflectances are checked on --grid with the other inputs (it failed after 'rendering …')."""
    line = assert_refused(["render", "macbeth", "--camera", CAM, *LIGHTS, "--spp", "2", "--grid", "300:900:1",
                           "-o", tmp_path / "r.exr"], "--grid", capsys, tmp_path)
    assert "380–780 nm" in line and "--extrapolation" not in line  # the chart's data: no extrapolation flag applies


@pytest.mark.parametrize("name, content", [
    ("empty.obj", b""), ("binary.obj", bytes(range(256)) * 8), ("nofaces.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\n"),
    ("badheader.ply", b"ply\nformat nonsense 1.0\nelement vertex 3\nend_header\n"),
])
def test_a_bad_mesh_is_refused_before_rendering(name, content, tmp_path, capsys):
    """Each kind gave Mitsuba's 'internal error' after the render had started; now one line, exit 2."""
    from skinrender.rendering.face.scene import ROOT_FACE_SCENES

    (tmp_path / name).write_bytes(content)
    scene = tmp_path / "scene.toml"
    scene.write_text((ROOT_FACE_SCENES / "face.toml").read_text().replace('file = "head"', f'file = "{name}"'))
    out = tmp_path / "out"
    out.mkdir()
    line = assert_refused(["render", scene, "--camera", CAM, *LIGHTS, "--size", "8", "--spp", "2",
                           "-o", out / "r.exr"], (str(scene), "[mesh]: field 'file'", name, "expected"), capsys, out)
    assert "rendering" not in line


def test_interruptible_passes_the_commands_result_and_errors_on():
    from argparse import Namespace

    from skinrender.cli.rendering import interruptible
    from skinrender.errors import SkinrenderError

    assert interruptible(lambda args: args.value * 2)(Namespace(value=21)) == 42

    def fails(args):
        raise SkinrenderError("--spp: bad")

    with pytest.raises(SkinrenderError, match="--spp: bad"):
        interruptible(fails)(Namespace())
    with pytest.raises(SystemExit):
        interruptible(lambda args: (_ for _ in ()).throw(SystemExit(1)))(Namespace())


def test_ctrl_c_stops_a_render_at_once_with_no_output(tmp_path):
    """Seen by a user: Ctrl-C waited for the whole Mitsuba render (~30 s at 160 px, 2048 spp). The interrupt
    follows the command's own progress line at once; the render (5.3e8 samples, ~3 min here) cannot finish in
    that instant on any machine."""
    output = tmp_path / "r.exr"
    status, _, err = interrupt_after(["render", "macbeth", "--camera", CAM, *LIGHTS, "--spp", "65536", "-o", output],
                                     "rendering macbeth")
    assert status == 130 and err.strip().splitlines()[-1] == "skinrender render: interrupted", err[-800:]
    assert not output.exists() and not output.with_suffix(".png").exists()


def test_a_full_disk_leaves_no_render_behind(tmp_path):
    """Seen: ``render -o`` on a full disk left a truncated EXR and said "internal error … please report". Here a
    file-size limit (RLIMIT_FSIZE: writes past it fail with EFBIG, as on a full disk) stops the EXR: exit 1 (the
    machine's error), one line naming --output and the reason, and nothing left, the folder it made included."""
    script = ("import resource, signal, sys; signal.signal(signal.SIGXFSZ, signal.SIG_IGN); "
              "resource.setrlimit(resource.RLIMIT_FSIZE, (4096, 4096)); "
              "from skinrender.cli import main; sys.exit(main(sys.argv[1:]))")
    target = tmp_path / "new" / "r.exr"
    done = subprocess.run([sys.executable, "-c", script, "render", "macbeth", "--camera", CAM, *LIGHTS, "--spp", "1",
                           "-o", str(target), "--json"], capture_output=True, text=True, timeout=600)
    lines = [line for line in done.stderr.splitlines() if line.startswith("skinrender render: error")]  # (drjit
    # says it could not cache a kernel under the same limit)
    assert done.returncode == 1 and done.stdout == "" and len(lines) == 1, done.stderr[-800:]
    assert lines[0].startswith(f"skinrender render: error: --output {shown(target)}: cannot be written (the file would "
                               "be larger than this system allows)")
    assert list(tmp_path.iterdir()) == []


def test_detect_writes_its_mask_preview_and_figure_all_or_none(tmp_path, capsys, monkeypatch):
    """Seen: ``detect -o m.png --figure f.png`` failing on the figure left m.png and m_preview.png. The disk fills
    on the third file: none of the three is left, and the line names --figure and the reason."""
    from .refusal import full_disk

    full_disk(monkeypatch, after=2)
    status, out, err = run(["detect", "macbeth", "--camera", CAM, *LIGHTS, "--spp", "1", "-o", tmp_path / "m.png",
                            "--figure", tmp_path / "f.png", "--json"], capsys)
    lines = [line for line in err.splitlines() if "error" in line]
    assert status == 1 and out == "" and len(lines) == 1, err
    assert lines[0].startswith(f"skinrender detect: error: --figure {shown(tmp_path / 'f.png')}: cannot be written (no "
                               "space left on the device (the disk is full)); nothing was written")
    assert list(tmp_path.iterdir()) == []


def test_help_says_where_the_output_goes_without_o():
    from skinrender.cli import build_parser

    commands = next(a for a in build_parser()._actions if a.dest == "command").choices
    for name, default in (("render", "render.exr (and render.png) in the current folder"),
                          ("detect", "detect.png (and detect_preview.png) in the current folder")):
        assert default in " ".join(commands[name].format_help().split())


@pytest.mark.parametrize("scene, reason", [("/dev/zero", "a device"), ("/dev/null", "a device")])
def test_a_device_as_the_scene_is_refused_unread(scene, reason, capsys):
    """Seen: ``render /dev/zero …`` read 12.8 GB in 15 s."""
    line = assert_refused(["render", scene, "--camera", CAM, *LIGHTS], "SCENE", capsys)
    assert reason in line


@pytest.mark.parametrize("extra, names", [
    (["--spp", "1048576"], ("--spp", "at most 267232 spp")),
    (["--imager", "sony-imx174", "--illuminance", "1e308"], "--illuminance"),
    (["--imager", "sony-imx174", "--exposure", "1e308"], "--exposure"),
    (["--spp", "200000", "--max-minutes", "1"], ("--spp", "--max-minutes")),
])
def test_a_render_out_of_bounds_is_refused_before_its_progress_line(extra, names, tmp_path, capsys):
    """Seen: a render of too many samples was refused after "rendering … at N spp", unflagged; an illuminance
    or exposure of 1e308 overflowed into a warning and an unflagged error."""
    assert_refused(["render", "macbeth", "--camera", CAM, *LIGHTS, "-o", tmp_path / "r.exr", *extra], names, capsys,
                   output=tmp_path)


def test_a_locus_skin_that_does_not_cover_the_grid_is_refused_before_the_render_naming_it(tmp_path, capsys,
                                                                                          monkeypatch):
    """``detect … --locus-skin narrow.csv`` rendered, then refused the set as ``--skin`` (the locus now carries the
    role skin): refused first, naming --locus-skin."""
    from skinrender.rendering import kinds

    def refuse(*args, **kwargs):
        raise AssertionError("rendered before the locus' skin set was checked")

    monkeypatch.setattr(kinds.ChartKind, "render_imaged", refuse)
    narrow = tmp_path / "narrow.csv"
    narrow.write_text("wavelength,a,b\n450,0.3,0.4\n550,0.35,0.45\n650,0.5,0.6\n")
    line = assert_refused(["detect", "macbeth", "--camera", CAM, *LIGHTS, "--locus-skin", narrow, "--spp", "8",
                           "-o", tmp_path / "d.png"], ("--locus-skin", "does not cover"), capsys)
    assert "--skin:" not in line
