"""
Tests for :mod:`skinrender.testing.plugin`, as a user meets it: a project of one test file (no conftest) run by
pytest (in-process, ``pytester``) with the plugin; references written, passed, failed on a changed camera with
the files to look at, and every refusal in one line without a traceback.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from .test_regression import TINY, csv_camera

pytest_plugins = ["pytester"]
pytest.importorskip("mitsuba")

TEST_FILE = """
import os
from pathlib import Path

HERE = Path(__file__).parent
CAMERA = str(HERE / "camera.csv")
SEED = int(os.environ.get("CHECK_SEED", "0"))
VARIANT = os.environ.get("CHECK_VARIANT") or None


def test_chart(render_regression):
    render_regression.check(str(HERE / "tiny.toml"), camera=CAMERA, prevailing="A", calibration=5000, spp=16,
                            seed=SEED, variant=VARIANT)


def test_face(render_regression):
    render_regression.check("face", camera=CAMERA, prevailing=3300, calibration=3300, spp=32, size=32, seed=SEED)
"""


@pytest.fixture(scope="module", autouse=True)
def warm(tmp_path_factory):
    """Import what the renders import, once, before any in-process run: ``pytester`` removes the modules a run
    imported when it ends, and Mitsuba's variants cannot be imported twice in one process."""
    from skinrender.testing.regression import measure

    chart = tmp_path_factory.mktemp("warm") / "tiny.toml"
    chart.write_text(TINY)
    for variant in (None, "scalar_spectral"):
        measure(str(chart), "gbell:9@450,540,610", "A", 5000, spp=4, variant=variant)
    measure("face", "gbell:9@450,540,610", "A", "A", spp=4, size=8)
    measure("macbeth", "gbell:9@450,540,610", "A", "A", spp=4)
    import matplotlib.pyplot  # noqa: F401  (the difference figure's)
    import scipy.stats  # noqa: F401  (the comparison's: it imports numpy.fft, a C module loaded once a process)

    # contourpy too: imported first inside a run, it is unloaded after it and, compiled, cannot be imported again
    # (later tests of the same pytest-xdist worker drawing a contour failed)
    import contourpy  # noqa: F401

    # hypothesis' pytest plugin imports hypothesis at the end of every run (its terminal summary): ~1–2 s a run when
    # each run imports it anew (measured: the most of a run that renders nothing)
    try:
        import hypothesis.internal.observability  # noqa: F401
    except ImportError:  # no hypothesis, no plugin of it
        pass


@pytest.fixture
def project(pytester):
    """A user's project: the test file, a chart and a CSV camera (channels R, G, B)."""
    pytester.makepyfile(test_scenes=TEST_FILE)
    (pytester.path / "tiny.toml").write_text(TINY)
    csv_camera(pytester.path / "camera.csv")
    return pytester


def run(pytester, *args):
    return pytester.runpytest("-p", "skinrender.testing.plugin", "-p", "no:cacheprovider", *args)


def test_regen_pass_and_a_shifted_camera_fails_with_its_files(project, monkeypatch):
    missing = run(project)
    missing.assert_outcomes(failed=2)
    missing.stdout.fnmatch_lines(["*render_regression.check: no reference render *test_scenes/test_chart.exr (nor "
                                  "its sidecar test_chart.json): write it with `pytest --skinrender-regen "
                                  "test_scenes.py::test_chart` and commit both files"])
    assert not (project.path / "test_scenes").exists()

    run(project, "--skinrender-regen").assert_outcomes(passed=2)
    folder = project.path / "test_scenes"
    assert sorted(p.name for p in folder.iterdir()) == ["test_chart.exr", "test_chart.json", "test_face.exr",
                                                        "test_face.json"]
    sidecar = json.loads((folder / "test_chart.json").read_text())
    assert sidecar["settings"]["spp"] == 64 and sidecar["settings"]["spp_requested"] == 16  # 4 × the check's
    # issue 36: the reference has its own seed (not the check's 0), and the camera's path is the test file's
    assert sidecar["settings"]["seed"] == 0 and sidecar["settings"]["reference_seed"] not in (0, 1)
    assert sidecar["settings"]["camera"] == "camera.csv"
    from skinrender.rendering.exr import read_exr_attributes

    assert read_exr_attributes(folder / "test_chart.exr")["camera"] == "camera.csv"
    assert len(sidecar["settings"]["camera_sha256"]) == 64 and sidecar["compared"]["items"][0]["name"].endswith("/ R")
    face = json.loads((folder / "test_face.json").read_text())
    assert face["regions"]["skin"] == 1 and face["compared"]["items"][-1]["name"] == "skin NCC / g"

    run(project).assert_outcomes(passed=2)
    monkeypatch.setenv("CHECK_VARIANT", "scalar_spectral")  # another variant renders the same, within noise
    run(project, "-k", "chart").assert_outcomes(passed=1)
    monkeypatch.delenv("CHECK_VARIANT")

    csv_camera(project.path / "camera.csv", shift=2.0)
    shifted = run(project, "--skinrender-results", "results")
    shifted.assert_outcomes(failed=2)
    text = shifted.stdout.str()
    assert "Traceback" not in text and "def check" not in text
    shifted.stdout.fnmatch_lines(["*tiny through *camera.csv differs from its reference *test_chart.exr beyond "
                                  "the noise:", "*worst * / ?: * against *, z = *(critical * for 12 values at "
                                  "family-wise α = 0.01, Šidák)", "*note: the camera's curves changed: *",
                                  "*files: results/test_scenes.py__test_chart/test_chart.new.exr, *"])
    results = project.path / "results" / "test_scenes.py__test_chart"
    assert {p.name for p in results.iterdir()} >= {"test_chart.new.exr", "test_chart.new.json",
                                                   "test_chart.reference.exr", "test_chart.difference.png"}
    assert (results / "test_chart.difference.png").read_bytes()[:4] == b"\x89PNG"
    assert (project.path / "results" / "test_scenes.py__test_face" / "test_face.difference.png").exists()


WRITTEN: dict[str, bytes] = {}
"""The files ``--skinrender-regen -k chart`` wrote in the first project (name → content), for the next ones."""


@pytest.fixture
def written(project):
    """The project with its references written: by ``--skinrender-regen`` in the first test that asks, copied byte
    for byte into the next ones (the same test file, chart and camera: the regen writes the same files, and each test
    damages its own copy)."""
    folder = project.path / "test_scenes"
    if not WRITTEN:
        run(project, "--skinrender-regen", "-k", "chart").assert_outcomes(passed=1)
        WRITTEN.update({path.name: path.read_bytes() for path in folder.iterdir()})
    else:
        folder.mkdir()
        for name, content in WRITTEN.items():
            (folder / name).write_bytes(content)
    return project, folder / "test_chart.exr"


@pytest.mark.parametrize("damage, message", [
    ("delete_exr", "*the reference render *test_chart.exr is missing (its sidecar test_chart.json is there)*"),
    ("delete_sidecar", "*test_chart.exr is there but its sidecar test_chart.json is not: it is not a skinrender "
                       "reference*it was not overwritten*"),
    ("garble_sidecar", "*the reference's sidecar *test_chart.json is unreadable (JSONDecodeError*"),
    ("foreign_sidecar", "*test_chart.json is not a skinrender reference sidecar*"),
    ("edit_exr", "*test_chart.exr changed after its sidecar was written (SHA-256 differs)*"),
    # issue 36: a hand-edited sidecar switched the check off (a shifted camera passed)
    ("inflate_standard_errors", "*the sidecar *test_chart.json was changed after the reference was written*"),
    ("zero_dof", "*the sidecar *test_chart.json was changed after the reference was written*"),
])
def test_damaged_references_are_reported_and_never_rewritten(written, damage, message):
    project, exr = written
    sidecar = exr.with_suffix(".json")
    if damage in ("inflate_standard_errors", "zero_dof"):
        csv_camera(project.path / "camera.csv", shift=2.0)  # a change the check must not miss
        document = json.loads(sidecar.read_text())
        for item in document["compared"]["items"]:
            item.update({"standard_error": 1e30} if damage == "inflate_standard_errors" else {"dof": 0})
        sidecar.write_text(json.dumps(document))
    elif damage == "delete_exr":
        exr.unlink()
    elif damage == "delete_sidecar":
        sidecar.unlink()
    elif damage == "garble_sidecar":
        sidecar.write_text("{not json")
    elif damage == "foreign_sidecar":
        sidecar.write_text(json.dumps({"mine": True}))
    else:
        exr.write_bytes(exr.read_bytes()[:-64] + bytes(64))
    before = {p.name: p.read_bytes() for p in exr.parent.iterdir()}
    result = run(project, "-k", "chart")
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines([message])
    if damage != "delete_exr":  # a sidecar of ours with its EXR gone may be rewritten; nothing else
        again = run(project, "-k", "chart", "--skinrender-regen")
        rewritable = ("edit_exr", "inflate_standard_errors", "zero_dof")  # ours, damaged: regen writes them again
        assert again.ret != 0 or damage in rewritable
        if damage not in rewritable:
            assert {p.name: p.read_bytes() for p in exr.parent.iterdir()} == before


def test_an_unreadable_exr_is_reported(written):
    project, exr = written
    data = bytearray(exr.read_bytes())
    data[:4] = b"junk"
    exr.write_bytes(bytes(data))
    sidecar = exr.with_suffix(".json")
    document = json.loads(sidecar.read_text())
    import hashlib

    document["exr_sha256"] = hashlib.sha256(bytes(data)).hexdigest()
    sidecar.write_text(json.dumps(document))
    result = run(project, "-k", "chart")
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["*the reference render *test_chart.exr is unreadable (*"])


@pytest.mark.parametrize("call, message", [
    ('"nosuch", camera=CAMERA, prevailing="A", calibration="A"', "*render_regression.check: scene: unknown scene "
     "'nosuch'; bundled scenes: *"),
    ('"macbeth", camera="nosuch", prevailing="A", calibration="A"', "*render_regression.check: camera: unknown "
     "camera 'nosuch'; known: *"),
    ('"macbeth", camera=CAMERA, prevailing="A", calibration="A", colour=True', "*render_regression.check: unknown "
     "option(s) colour; known: scene, camera, *"),
    ('"macbeth", camera=CAMERA, prevailing="A"', "*render_regression.check: calibration: required"),
    ('"macbeth", camera=CAMERA, prevailing="A", calibration="A", physics="sheen"', "*render_regression.check: "
     "physics: goes with a face scene (e.g. 'face'), not a chart"),
    ('"face", camera=CAMERA, prevailing="A", calibration="A", physics="glossy"', "*render_regression.check: "
     "physics ('glossy') must be one of *"),
    ('"macbeth", camera=CAMERA, prevailing="A", calibration="A", basename="../x"', "*render_regression.check: "
     "basename must be a file name*"),
    ('"macbeth", camera=CAMERA, prevailing="A", calibration="A", alpha=2.0', "*alpha must be a probability*"),
])
def test_bad_arguments_fail_in_one_line(pytester, call, message):
    pytester.makepyfile(test_bad=f"""
CAMERA = "gbell:9@450,540,610"

def test_bad(render_regression):
    render_regression.check({call})
""")
    result = run(pytester, "--skinrender-regen")
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines([message])
    text = result.stdout.str()
    assert "Traceback" not in text and "skinrender/testing" not in text and not (pytester.path / "test_bad").exists()


def test_two_checks_in_one_test_need_their_own_basenames(pytester):
    pytester.makepyfile(test_two="""
def test_two(render_regression):
    for scene in ("macbeth", "skin_patches"):
        render_regression.check(scene, camera="gbell:9@450,540,610", prevailing="A", calibration="A", spp=4)
""")
    result = run(pytester, "--skinrender-regen")
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["*basename: test_two.exr is already the reference of another check in this test;*"])


def test_a_reference_is_claimed_once_across_xdist_workers(tmp_path, monkeypatch):
    """Issue 36: two tests with one basename under ``pytest -n 2 --skinrender-regen`` both passed (each worker knew
    only its own claims) and one reference was lost. The claim is a lock file shared by the run's workers."""
    from skinrender.testing import plugin

    monkeypatch.setattr(plugin.tempfile, "gettempdir", lambda: str(tmp_path))
    reference = tmp_path / "tests" / "test_a" / "same.exr"
    assert plugin.claim_across_workers(reference, "test_a.py::test_one", uid="run1") is None
    assert plugin.claim_across_workers(reference, "test_a.py::test_one", uid="run1") is None  # its own, again
    assert plugin.claim_across_workers(reference, "test_b.py::test_two", uid="run1") == "test_a.py::test_one"
    assert plugin.claim_across_workers(reference, "test_b.py::test_two", uid="run2") is None  # another run
    monkeypatch.delenv("PYTEST_XDIST_TESTRUNUID", raising=False)
    assert plugin.claim_across_workers(reference, "test_c.py::test", uid=None) is None  # no xdist: one process
    assert not list(reference.parent.parent.rglob("*.claim"))  # nothing beside the references

    class Node:  # the controller hears of each worker's run identifier, and removes the claims at the end
        workerinput = {"testrunuid": "run1"}
        config = type("Config", (), {"stash": pytest.Stash()})()

    plugin.pytest_configure_node(Node)
    session = type("Session", (), {"config": Node.config})()
    plugin.pytest_sessionfinish(session)
    assert not (tmp_path / "skinrender-claims-run1").exists() and (tmp_path / "skinrender-claims-run2").exists()


def test_two_tests_with_one_basename_under_two_workers(pytester, monkeypatch):
    """The claim as the workers make it: the run's identifier in the environment (as pytest-xdist sets it)."""
    monkeypatch.setenv("PYTEST_XDIST_TESTRUNUID", "one-run")
    monkeypatch.setattr("tempfile.tempdir", str(pytester.path))
    for name in ("test_first", "test_second"):
        pytester.makepyfile(**{name: f"""
def test_it(render_regression):
    render_regression.check("macbeth", camera="gbell:9@450,540,610", prevailing="A", calibration="A", spp=4,
                            basename="shared")
"""})
    # each file is its own test file, so its own folder: the same basename is two references, both fine
    run(pytester, "--skinrender-regen").assert_outcomes(passed=2)
    # one folder, two tests, one basename, two "workers" (here one process forgetting its own record each run)
    pytester.makepyfile(test_third="""
def test_a(render_regression):
    render_regression.check("macbeth", camera="gbell:9@450,540,610", prevailing="A", calibration="A", spp=4,
                            basename="shared")
""")
    run(pytester, "--skinrender-regen", "test_third.py").assert_outcomes(passed=1)
    pytester.makepyfile(test_third="""
def test_b(render_regression):
    render_regression.check("macbeth", camera="gbell:9@450,540,610", prevailing="A", calibration="A", spp=4,
                            basename="shared")
""")
    result = run(pytester, "--skinrender-regen", "test_third.py")
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["*basename: *shared.exr is already the reference of test_third.py::test_a "
                                 "(another pytest-xdist worker)*"])


def test_the_fixture_gives_the_reference_path(pytester):
    pytester.makepyfile(test_where="""
def test_where(render_regression, request):
    path = render_regression.reference_path()
    assert path == request.path.parent / "test_where" / "test_where.exr"
    assert render_regression.reference_path("a").name == "a.exr"
""")
    run(pytester).assert_outcomes(passed=1)


def test_safe_names_are_file_names():
    from skinrender.testing.plugin import safe_name

    assert safe_name("test_x[a/b c]") == "test_x_a_b_c_"
    assert np.all([c.isalnum() or c in "._-" for c in safe_name("é::[]/\\ ")])


def test_the_entry_point_names_the_module_it_loads():
    """pyproject's pytest11 entry point: its name is the module's, so that ``-p skinrender.testing.plugin`` (this
    repository's addopts) and the installed entry point register one plugin, not the same module twice."""
    import importlib
    import tomllib
    from pathlib import Path

    import skinrender

    table = tomllib.loads((Path(skinrender.__file__).parents[1] / "pyproject.toml").read_text(encoding="utf-8"))
    points = table["project"]["entry-points"]["pytest11"]
    assert points == {"skinrender.testing.plugin": "skinrender.testing.plugin"}
    module = importlib.import_module(points["skinrender.testing.plugin"])
    assert callable(module.pytest_addoption) and hasattr(module, "render_regression")


def test_several_cameras_share_one_render_each_with_its_reference(pytester):
    """``camera=[A, B]``: one spectral render, a reference per camera (``<test>.<camera>.exr``); B's curves
    shifted by 4 nm (its CSV rewritten) fail B's check alone, named with the change."""
    pytester.makepyfile(test_many="""
from pathlib import Path

HERE = Path(__file__).parent


def test_many(render_regression):
    out = render_regression.check(str(HERE / "tiny.toml"), camera=["gbell:9@450,540,610", str(HERE / "b.csv")],
                                  prevailing="A", calibration=5000, spp=16)
    assert out is None or len(out) == 2
""")
    (pytester.path / "tiny.toml").write_text(TINY)
    csv_camera(pytester.path / "b.csv")
    assert run(pytester, "--skinrender-regen").ret == 0
    folder = pytester.path / "test_many"
    names = sorted(p.name for p in folder.glob("*.exr"))
    assert len(names) == 2 and names[1] == "test_many.gbell_9_450_540_610.exr" and names[0].endswith("b.csv.exr")
    sidecar = json.loads((folder / "test_many.gbell_9_450_540_610.json").read_text())
    assert sidecar["settings"]["spectral_bands_nm"] == "400:700:5"
    assert run(pytester).ret == 0
    csv_camera(pytester.path / "b.csv", shift=4.0)
    result = run(pytester)
    text = result.stdout.str()
    assert result.ret == 1 and names[0] in text and "gbell_9_450" not in text
    assert "the camera's curves changed" in text
