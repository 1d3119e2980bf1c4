"""
Reproducing the paper's Stage 2 and Stage 3
===========================================

-   :func:`reproduce`: every table (Markdown and CSV) and figure (PNG) in a
    folder, under a stated choice of the paper's unknowns (gbell slope,
    integration grid, skin and Munsell sets, illuminants), with how many table
    cells match the paper's, the paper's Stage 1 figures per camera and its
    Stage 2 observations per camera.
-   :func:`summary_text`: the result as lines of text.
-   The Stage 2 functions of :mod:`~skinrender.studies.paper.normalisation`
    (:func:`stage2_pairs`, :func:`stage2_observation`, :func:`stage2_cases`,
    :func:`stage2_gamut_panels`) are importable from here too.

References
----------
-   :cite:`Martinkauppi2006` : the paper, Stage 2 (Figs. 3–7), Stage 3 (Tables 2–5).
"""

from __future__ import annotations

import json
import sys
import tempfile
import threading
import time
from pathlib import Path

from ...design.bank import SENSORS_PAPER
from ...files import write_output
from ...hints import ArrayLike
from ...spectra import WavelengthGrid
from .folders import MANIFEST, check_output, output_folder
from .matching import unmatched_sensors
from .normalisation import (STAGE2_CAMERA, STAGE2_NORMALISATIONS, Stage2, stage2_cases, stage2_gamut_panels,
                            stage2_observation, stage2_pairs, stage2_write)
from .observations import paper_cameras, stage1_text, stage2_by_camera
from .tables import write_tables
from .unknowns import (Setting, check_camera, check_positions, check_search_work, check_sensors, resolve_setting,
                       setting_tables)
from ...execution import check_workers
from .volumes import VolumeCache

__all__ = [
    "STAGE2_CAMERA",
    "STAGE2_NORMALISATIONS",
    "stage2_pairs",
    "stage2_observation",
    "stage2_cases",
    "stage2_gamut_panels",
    "reproduce",
    "summary_text",
]


def reproduce(
    directory: str | Path,
    sensors: ArrayLike | str = SENSORS_PAPER,
    positions: str | ArrayLike = "400:700:10",
    camera_spec: str = STAGE2_CAMERA,
    skin: str = "skin",
    munsell: str = "munsell",
    slope: float = 2.0,
    grid: WavelengthGrid | str = "400:700:1",
    workers: int | None = None,
    dask=None,
    progress=sys.stderr,
    illuminants: str = "paper",
    stage1_camera: str | None = None,
    extrapolation: str = "refuse",
    observations: bool = True,
    shared: str | Path | None = None,
    figures: bool = True,
    max_minutes: float | None = None,
) -> dict:
    """
    Write the paper's Figs. 3–7 (PNG) and Tables 2–5 (Markdown, CSV) to ``directory``.

    Every argument and the folder are checked before anything is written (the
    Stage 2 camera while the searches start: a bad one stops them); the
    results go to a temporary folder beside ``directory`` that is moved into
    place at the end (an interrupted run leaves no folder that looks
    complete). The Stage 2 figures are drawn in a thread while the worker
    processes compute the triplet volumes.

    Parameters
    ----------
    directory
        Output folder: new, empty, or an earlier ``reproduce`` folder (replaced).
    sensors
        Sensor numbers of Tables 2–5 (1 = impulse), a sequence or ``"1,3,5"``.
    positions
        Peak grid, nm (the paper's ``400:700:10``; a coarser one for a quick look).
    camera_spec
        The Stage 2 camera (Figs. 3–7).
    skin, munsell
        Reflectance sets (names or CSV paths).
    slope
        gbell slope *b* (the paper does not give it).
    grid
        Integration grid, ``START:END:STEP`` nm.
    workers, dask
        Processes (``None`` = every core) or a Dask scheduler.
    progress
        Stream for progress bars (``None`` for silence).
    illuminants
        ``paper``, ``auto`` (Stage 1 for ``stage1_camera``) or kelvin, comma-separated.
    stage1_camera
        The camera of ``auto`` (default: ``camera_spec``).
    extrapolation
        For reflectance sets that do not cover ``grid``: ``refuse``, ``zero``, ``constant``.
    observations
        Also recompute the paper's Stage 1 figures and Stage 2 observations
        for every bundled camera and the DXC-930 (``stage1_text``,
        ``stage2_by_camera``).
    shared
        The reference data folder (default ``../shared/data`` beside the checkout).
    figures
        Draw Figs. 3–7 (``False``: the tables only, ``stage2`` empty).
    max_minutes
        Refuse searches estimated to take longer, minutes (:func:`~skinrender.studies.paper.unknowns.check_search_work`;
        ``None``: :data:`skinrender.workload.MINUTES_MAX`).

    Returns
    -------
    dict
        ``artifacts`` (paths), ``setting`` (the unknowns), ``illuminants_K``,
        ``stage2`` (per-normalisation observations), ``tables`` (rows per
        sensor), ``matches`` (``exact``, ``within_step``, ``total``),
        ``matches_by_table``, ``matches_temperature`` (Tables 2–3 cells sharing
        a calibration temperature, not part of ``matches``), ``search_s``
        (seconds per sensor), ``notes`` (sensors the paper has no row for),
        ``elapsed_s`` and, with ``observations``,
        ``stage1_text`` and ``stage2_by_camera``.
    """

    start = time.perf_counter()
    target = check_output(directory)
    setting = Setting(slope, str(grid).replace(" nm", ""), str(skin), str(munsell), str(illuminants),
                      camera_spec if stage1_camera is None else stage1_camera, extrapolation)
    resolved = resolve_setting(setting)
    chosen = check_sensors(sensors)
    where = check_positions(positions, resolved.grid)
    workers = check_workers(workers)
    check_search_work(len(chosen), where, "--positions", max_minutes, workers)
    if dask is not None:
        from ...extras import require

        require("dask", "--dask")

    with output_folder(target) as folder:
        (folder / "search").mkdir()
        side: dict = {}

        def stage2_and_observations() -> None:
            try:
                stage = Stage2(camera_spec, setting.skin, setting.munsell, resolved.temperatures, resolved.grid)
                side["stage2"], side["artifacts"] = stage2_write(folder, stage) if figures else ({}, [])
                if observations:
                    with tempfile.TemporaryDirectory() as scratch:
                        cameras = paper_cameras(scratch, shared)
                        side["stage1_text"] = stage1_text(cameras)
                        side["stage2_by_camera"] = stage2_by_camera(cameras, setting.munsell)
            except BaseException as error:  # re-raised in the main thread
                side["error"] = error

        thread = threading.Thread(target=stage2_and_observations, name="skinrender-stage2", daemon=True)

        def on_start() -> None:
            # The Stage 2 camera is checked once the searches run: loading a colour-science camera
            # imports colour (~2 s on one core, the other idle until then). A bad one stops them.
            check_camera(camera_spec, resolved.grid, "--camera")
            thread.start()

        try:
            computed = setting_tables(resolved, chosen, where, VolumeCache(), workers, dask, progress, progress,
                                      on_start=on_start)
        finally:
            if thread.is_alive():  # also on an interrupt: let it finish writing before the folder goes
                thread.join()
        if "error" in side:
            raise side["error"]
        artifacts = list(side["artifacts"])
        for sensor, result in computed["results"].items():
            path = folder / "search" / f"sensor_{sensor:g}.csv"
            result.to_csv(path)
            artifacts.append(path)
        artifacts += write_tables(computed["tables"], folder)
        matches = computed["matches"]
        document = {
            "artifacts": [str(target / Path(p).relative_to(folder)) for p in artifacts] + [str(target / MANIFEST)],
            "setting": setting.unknowns(),
            "illuminants_K": resolved.temperatures.tolist(),
            "stage2": side["stage2"],
            "tables": {f"{k:g}": v for k, v in computed["tables"].items()},
            "matches": {key: matches[key] for key in ("exact", "within_step", "total")},
            "matches_by_table": matches["by_table"],
            "matches_temperature": matches["temperatures"],
            "search_s": computed["search_s"],
            "notes": unmatched_sensors(chosen),
            **({"stage1_text": side["stage1_text"], "stage2_by_camera": side["stage2_by_camera"]}
               if observations else {}),
        }
        document["elapsed_s"] = time.perf_counter() - start
        write_output(folder / MANIFEST, json.dumps(document, indent=2, allow_nan=False) + "\n")
    return document


def summary_text(result: dict) -> str:
    """The lines ``skinrender reproduce`` prints: files, matches, search times, Stage 2 per camera."""
    matches = result["matches"]
    lines = ["wrote:"] + [f"  {p}" for p in result["artifacts"]]
    lines.append(f"matches with the paper's Tables 2–5: {matches['exact']} of {matches['total']} cells exactly, "
                 f"{matches['within_step']} within 10 nm per peak")
    lines += [f"  {key}: {v['exact']} exact, {v['within_step']} within 10 nm of {v['total']}"
              for key, v in result["matches_by_table"].items()]
    temperature = result["matches_temperature"]
    lines.append(f"  Tables 2–3 cells sharing a calibration temperature with the paper's: "
                 f"{temperature['shared']} of {temperature['total']} (not part of the counts above)")
    searches = ", ".join(f"sensor {k}: {v:.1f} s" for k, v in result["search_s"].items())
    lines.append(f"searches: {sum(result['search_s'].values()):.1f} s ({searches}); total {result['elapsed_s']:.1f} s")
    for row in result.get("stage2_by_camera", []):
        lines.append(f"Stage 2 as the paper says, {row['camera']}: {row['as_paper']} of {row['total']} calibrations "
                     f"(largest gamut on the calibration: " + ", ".join(
                         f"{n} {row[n]['on_calibration']}/{row[n]['total']}" for n, _ in STAGE2_NORMALISATIONS) + ")")
    lines += [f"note: {note}" for note in result.get("notes", [])]
    return "\n".join(lines)
