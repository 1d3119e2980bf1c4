"""
The pytest plugin: render regressions of your own scenes
========================================================

Registered with the ``pytest11`` entry point, so any project with skinrender installed has it (no conftest);
``-p no:skinrender.testing.plugin`` switches it off.

-   Fixture ``render_regression`` (:class:`RenderRegression`): ``render_regression.check(scene, camera=…,
    prevailing=…, calibration=…)`` renders a chart or a face and compares it with the stored reference
    ``<test file's folder>/<test file stem>/<basename or test name>.exr`` and its JSON sidecar
    (:mod:`skinrender.testing.reference`), statistically (:mod:`skinrender.testing.regression`): a
    patch's or region's change is told from Monte Carlo noise by its z, at a family-wise false-alarm rate
    α (default 0.01) over all of them.
-   ``--skinrender-regen``: write (or rewrite) the references of the checks that run; they pass.
-   ``--skinrender-results DIR``: for a failed check, write the new render (EXR and sidecar), the reference
    and a difference figure (PNG) under ``DIR/<test id>/``.

A missing reference fails its test with the command that writes it; a foreign or unreadable reference file
fails it too and is never overwritten; a bad argument fails it with one line naming it (no traceback).

The plugin is loaded by every pytest session where skinrender is installed, so it is thin: importing it imports
pytest and :mod:`skinrender.errors` only (``import skinrender`` imports its names on first use); what a check
needs (the renderer, Mitsuba) is imported by the fixture's :meth:`RenderRegression.check`, as pytest-regressions'
plugin imports its fixtures' modules.

Units: temperatures K (or ``A``, ``H``), illuminance lx, images in Eq. 4 output units.
"""

from __future__ import annotations

import hashlib
import os
import re
import shlex
import shutil
import tempfile
from dataclasses import replace
from pathlib import Path

import pytest

from typing import TYPE_CHECKING

from ..errors import SkinrenderError

if TYPE_CHECKING:
    from .regression import Comparison

__all__ = ["RenderRegression", "render_regression", "pytest_addoption", "pytest_terminal_summary", "safe_name",
           "claim_across_workers", "pytest_configure_node", "pytest_sessionfinish"]

_WRITTEN = pytest.StashKey[list]()
_CLAIMED = pytest.StashKey[dict]()
_OPTIONS = ("camera", "prevailing", "calibration", "spp", "seed", "physics", "skin", "imager", "illuminance",
            "basename", "size", "variant", "alpha")


def pytest_addoption(parser) -> None:
    """``--skinrender-regen`` and ``--skinrender-results DIR``."""
    group = parser.getgroup("skinrender", "skinrender render regressions (render_regression fixture)")
    group.addoption("--skinrender-regen", action="store_true", default=False,
                    help="write or rewrite the reference renders (EXR + JSON sidecar) of the render_regression "
                    "checks that run, beside each test file; those checks pass")
    group.addoption("--skinrender-results", metavar="DIR", default=None,
                    help="for each failed render_regression check, write the new render (EXR + sidecar), the "
                    "reference and a difference figure (PNG) under DIR/<test id>/")


def safe_name(text: str) -> str:
    """
    A file name from a test name or id: anything but letters, digits, ``.``, ``-``, ``_`` becomes ``_``.

    >>> safe_name("tests/test_a.py::test_chart[macbeth-2856]")
    'tests_test_a.py__test_chart_macbeth-2856_'
    """
    return re.sub(r"[^\w.-]", "_", text)


class RenderRegression:
    """The ``render_regression`` fixture's object: :meth:`check` as many scenes as a test likes."""

    def __init__(self, request):
        self._request = request
        self._config = request.config
        self._used: set = set()

    @property
    def folder(self) -> Path:
        """Where this test file's references live: ``<test file's folder>/<test file stem>/``."""
        path = Path(self._request.path)
        return path.parent / path.stem

    def reference_path(self, basename: str | None = None) -> Path:
        """The reference EXR of a check (``basename`` or the test's name)."""
        return self.folder / f"{safe_name(basename or self._request.node.name)}.exr"

    def check(self, scene=None, *, camera=None, prevailing=None, calibration=None, spp: int | None = None,
              seed: int = 0, physics: str | None = None, skin: str | None = None, imager: str | None = None,
              illuminance: float | None = None, basename: str | None = None, size: int | None = None,
              variant: str | None = None, alpha: float | None = None, **unknown) -> Comparison | None:
        """
        Render ``scene`` and compare it with its stored reference; the test fails when they differ beyond
        their noise, or when the reference is missing, foreign or unreadable.

        Parameters
        ----------
        scene
            A chart (``macbeth``, ``skin_patches``, ``face_chart`` or a chart TOML) or a face (``face`` or a
            face TOML), as the command line's ``render`` takes.
        camera
            A camera name, ``gbell:N@P1,P2,P3``, ``impulse@P1,P2,P3`` or a CSV path (wavelength nm, R, G, B); or
            a list of them: the scene is rendered once spectrally and seen through each, every camera compared
            with its own reference ``<basename or test name>.<camera>.exr`` (a list of comparisons returned).
        prevailing, calibration
            Planckian lights: kelvin, ``A`` (2856 K) or ``H`` (2300 K).
        spp, seed
            Samples per pixel (default 64 for a chart, 64 over the 4 replicates of a face) and the sampler's
            seed. The reference is rendered at 4× the spp with its own seed, drawn from this one
            (:func:`~skinrender.testing.reference.reference_seed`: independent of the check's samples).
        physics, skin, size
            A face's level of physics (``direct`` or effects joined by ``+``), skin spec and image side in
            pixels (default 64).
        imager, illuminance
            An image sensor (preset or TOML) and the illuminance, lx: its noise is in the render (a face:
            physics ``noise``).
        basename
            The reference's name (default: the test's name); needed for a second check in one test.
        variant
            A Mitsuba variant (default: the fastest that works).
        alpha
            Family-wise false-alarm rate over all compared values (Šidák); ``None``:
            :data:`~skinrender.evaluation.verdict.ALPHA_DIFFERENCE` (0.01).

        Returns
        -------
        :class:`~skinrender.testing.regression.Comparison`, a list of them (several cameras) or ``None``
            ``None`` when the reference was (re)written (``--skinrender-regen``).
        """
        try:
            return self._check(scene, camera, prevailing, calibration, spp, seed, physics, skin, imager,
                               illuminance, basename, size, variant, alpha, unknown)
        except SkinrenderError as error:
            message = f"render_regression.check: {error}"
        pytest.fail(message, pytrace=False)  # outside the except: no chained traceback

    def _claim(self, path: Path, basename: str | None) -> None:
        """One reference per check: refused when another test, or another check of this one, has ``path`` — in
        this process, or under pytest-xdist in another worker of the same run (:func:`claim_across_workers`)."""
        claimed = self._config.stash.setdefault(_CLAIMED, {})
        node = self._request.node.nodeid
        if claimed.get(path, node) != node:
            raise SkinrenderError(f"basename: {path} is already the reference of {claimed[path]}; give this "
                                  "check its own basename=")
        if path in self._used:
            raise SkinrenderError(f"basename: {path.name} is already the reference of another check in this test; "
                                  "give each check its own basename=")
        other = claim_across_workers(path, node)
        if other is not None:
            raise SkinrenderError(f"basename: {path} is already the reference of {other} (another pytest-xdist "
                                  "worker); give this check its own basename=")
        claimed[path] = node
        self._used.add(path)

    def _portable(self, settings: dict) -> dict:
        """The settings with a CSV camera's path relative to the test file's folder (a writer's absolute path
        churned the diffs of every reference in the user's repository)."""
        camera = settings.get("camera")
        try:
            found = isinstance(camera, str) and Path(camera).is_file()
        except (OSError, ValueError):
            found = False
        if not found:
            return settings
        relative = os.path.relpath(Path(camera).resolve(), Path(self._request.path).resolve().parent)
        return {**settings, "camera": Path(relative).as_posix()}

    def _check(self, scene, camera, prevailing, calibration, spp, seed, physics, skin, imager, illuminance,
               basename, size, variant, alpha, unknown) -> Comparison | None:
        from ..evaluation.verdict import ALPHA_DIFFERENCE
        from .reference import (ReferenceProblem, read_reference, reference_seed, shown, sidecar_of, state,
                                write_reference)
        from .regression import REFERENCE_SPP_FACTOR, compare, measure, setting_notes

        alpha = ALPHA_DIFFERENCE if alpha is None else alpha
        if unknown:
            raise SkinrenderError(f"unknown option(s) {', '.join(sorted(unknown))}; known: scene, "
                                  f"{', '.join(_OPTIONS)}")
        for name, value in (("scene", scene), ("camera", camera), ("prevailing", prevailing),
                            ("calibration", calibration)):
            if value is None:
                raise SkinrenderError(f"{name}: required")
        if not (isinstance(alpha, float) and 0 < alpha < 1):
            raise SkinrenderError(f"alpha must be a probability in (0, 1), got {alpha!r}")
        if basename is not None and not (isinstance(basename, str) and safe_name(basename) == basename
                                         and basename.strip(".")):
            raise SkinrenderError(f"basename must be a file name of letters, digits, '.', '-', '_', got {basename!r}")
        options = dict(spp=spp, seed=seed, physics=physics, skin=skin, imager=imager, illuminance=illuminance,
                       size=size, variant=variant)
        if isinstance(camera, (list, tuple)):
            return self._check_cameras(scene, list(camera), prevailing, calibration, options, basename, alpha)
        path = self.reference_path(basename)
        self._claim(path, basename)
        found = state(path)
        if self._config.getoption("skinrender_regen"):
            reference = measure(scene, camera, prevailing, calibration, factor=REFERENCE_SPP_FACTOR,
                                render_seed=reference_seed(seed), **options)
            written = write_reference(path, replace(reference, settings=self._portable(reference.settings)), alpha)
            self._config.stash.setdefault(_WRITTEN, []).append((self._request.node.nodeid, written[0]))
            return None
        if found == "missing":
            raise ReferenceProblem(f"no reference render {shown(path)} (nor its sidecar "
                                   f"{sidecar_of(path).name}): write it with `pytest --skinrender-regen "
                                   f"{shlex.quote(self._request.node.nodeid)}` and commit both files")
        new = measure(scene, camera, prevailing, calibration, **options)
        reference = read_reference(path, new)
        result = compare(new, reference.mean, reference.standard_error, reference.dof, alpha,
                         setting_notes(new.settings, reference.settings))
        if not result.passed:
            pytest.fail(self._failure(new, reference, result), pytrace=False)
        return result

    def _check_cameras(self, scene, cameras: list, prevailing, calibration, options: dict, basename,
                       alpha: float) -> list | None:
        """
        Several cameras seen through one spectral render (:mod:`skinrender.testing.spectral_checks`), each compared with
        its own reference ``<basename or test name>.<camera>.exr``; the test fails with every camera that differs.
        """
        from .reference import ReferenceProblem, read_reference, reference_seed, shown, state, write_reference
        from .regression import REFERENCE_SPP_FACTOR, compare, measure, setting_notes

        if not cameras:
            raise SkinrenderError("camera: name at least one camera")
        base = basename or self._request.node.name
        paths = [self.reference_path(f"{base}.{getattr(cam, 'name', cam)}") for cam in cameras]
        for path in paths:
            self._claim(path, basename)
        if self._config.getoption("skinrender_regen"):
            references = measure(scene, cameras, prevailing, calibration, factor=REFERENCE_SPP_FACTOR,
                                 render_seed=reference_seed(options["seed"]), **options)
            for path, reference in zip(paths, references):
                written = write_reference(path, replace(reference, settings=self._portable(reference.settings)),
                                          alpha)
                self._config.stash.setdefault(_WRITTEN, []).append((self._request.node.nodeid, written[0]))
            return None
        missing = [path for path in paths if state(path) == "missing"]
        if missing:
            raise ReferenceProblem(f"no reference render {', '.join(str(shown(p)) for p in missing)} (nor their "
                                   f"sidecars): write them with `pytest --skinrender-regen "
                                   f"{shlex.quote(self._request.node.nodeid)}` and commit them")
        results, failures = [], []
        for path, new in zip(paths, measure(scene, cameras, prevailing, calibration, **options)):
            reference = read_reference(path, new)
            results.append(compare(new, reference.mean, reference.standard_error, reference.dof, alpha,
                                   setting_notes(new.settings, reference.settings)))
            if not results[-1].passed:
                failures.append(self._failure(new, reference, results[-1]))
        if failures:
            pytest.fail("\n".join(failures), pytrace=False)
        return results

    def _failure(self, new, reference, result: Comparison) -> str:
        from .reference import shown

        settings = new.settings
        beyond = result.beyond
        lines = [f"render_regression.check: {settings['scene']} through {settings['camera']} differs from its "
                 f"reference {shown(reference.path)} beyond the noise:",
                 f"  {result.summary()}",
                 f"  {len(beyond)} of {len(result.items)} values beyond their critical values: "
                 + ", ".join(f"{result.items[i]} ({result.z[i]:+.3g})" for i in beyond[:6])
                 + (", …" if len(beyond) > 6 else "")]
        lines += [f"  note: {note}" for note in result.notes]
        folder = self._config.getoption("skinrender_results")
        if folder is not None:
            try:
                files = self._write_results(Path(folder), new, reference, result)
                lines.append("  files: " + ", ".join(str(f) for f in files))
            except (OSError, SkinrenderError) as error:
                lines.append(f"  files: --skinrender-results {folder}: not written ({error})")
        else:
            lines.append("  (--skinrender-results DIR writes the new render, the reference and a difference "
                         "figure; --skinrender-regen accepts the new render as the reference)")
        return "\n".join(lines)

    def _write_results(self, folder: Path, new, reference, result: Comparison) -> list[Path]:
        from .figures import difference_figure
        from ..files import Output, write_outputs
        from .reference import sidecar_of, write_reference

        folder = folder / safe_name(self._request.node.nodeid)
        folder.mkdir(parents=True, exist_ok=True)
        stem = reference.path.stem
        written = list(write_reference(folder / f"{stem}.new.exr", new, result.verdict.alpha))
        copy = folder / f"{stem}.reference.exr"
        write_outputs(Output(copy, None, reference.path.read_bytes()),  # whole, every write checked
                      Output(sidecar_of(copy), None, sidecar_of(reference.path).read_bytes()))
        regions = new.regions
        title = (f"{new.settings['scene']} through {new.settings['camera']}: "
                 + result.summary().split(" (critical")[0])
        figure = difference_figure(folder / f"{stem}.difference.png", reference.image, new.image, result.items,
                                   result.z, result.critical, regions, title, new.scene, new.labels)
        return [written[0], copy, figure]


_RUN_UID = "PYTEST_XDIST_TESTRUNUID"
"""pytest-xdist's identifier of a run, the same in every worker of it (unset without xdist)."""

_RUNS = pytest.StashKey[list]()


def _claims_folder(uid: str) -> Path:
    """Where the workers of the run ``uid`` claim their references: a folder of the system's temporary files (the
    user's repository is left alone), removed when the run ends."""
    return Path(tempfile.gettempdir()) / f"skinrender-claims-{safe_name(uid)}"


def claim_across_workers(path: Path, node: str, uid: str | None = None) -> str | None:
    """
    Claim the reference ``path`` for the test ``node`` among the pytest-xdist workers of this run: ``None`` when
    it is this test's (claimed now, or before by it), else the test that claimed it first. The claim is a lock
    file made atomically (``O_CREAT | O_EXCL``) in :func:`_claims_folder`, named by the hash of the reference's
    resolved path and holding the test's id. Without xdist (``uid`` ``None`` and no run identifier) there is
    one process, whose own record suffices: ``None``.
    """
    uid = os.environ.get(_RUN_UID) if uid is None else uid
    if not uid:
        return None
    folder = _claims_folder(uid)
    folder.mkdir(parents=True, exist_ok=True)
    lock = folder / (hashlib.sha256(str(Path(path).resolve()).encode("utf-8")).hexdigest() + ".claim")
    try:
        handle = os.open(lock, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644)
    except FileExistsError:
        owner = lock.read_text(encoding="utf-8")
        return None if owner == node else owner or "another test"
    try:
        os.write(handle, node.encode("utf-8"))
    finally:
        os.close(handle)
    return None


@pytest.hookimpl(optionalhook=True)
def pytest_configure_node(node) -> None:
    """pytest-xdist's controller: note the run's identifier, so that its claims are removed when it ends."""
    uid = getattr(node, "workerinput", {}).get("testrunuid")
    if uid:
        node.config.stash.setdefault(_RUNS, []).append(uid)


def pytest_sessionfinish(session) -> None:
    """The controller (or a run without xdist): remove the run's claims (:func:`claim_across_workers`)."""
    if hasattr(session.config, "workerinput"):
        return  # a worker: the others may still claim; the controller removes the folder at the end
    for uid in set(session.config.stash.get(_RUNS, [])):
        shutil.rmtree(_claims_folder(uid), ignore_errors=True)


@pytest.fixture
def render_regression(request) -> RenderRegression:
    """Render regression checks of your scenes against stored references (:class:`RenderRegression`)."""
    return RenderRegression(request)


def pytest_terminal_summary(terminalreporter, exitstatus, config) -> None:
    """List the references ``--skinrender-regen`` wrote."""
    written = config.stash.get(_WRITTEN, [])
    if written:
        from .reference import shown, sidecar_of

        terminalreporter.section("skinrender references written")
        for node, path in written:
            terminalreporter.write_line(f"{shown(path)} (+ {sidecar_of(path).name})  ← {node}")
