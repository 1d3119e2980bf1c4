"""
The paper's unknowns
====================

The paper does not state the gbell slope *b*, the wavelength range and step of
its sums, its skin set, or the camera its Stage 1 illuminants came from. A
:class:`Setting` names one choice of each; :func:`resolve_setting` checks it
(every refusal a one-line :class:`~skinrender.errors.SkinrenderError` naming
the flag) and loads what it names; :func:`setting_tables` computes Tables 2–5
under it, sharing the volumes it has in common with earlier settings.

-   :class:`Setting`, :data:`SETTING_DEFAULT`, :func:`resolve_setting`.
-   :func:`check_sensors`, :func:`check_positions`, :func:`check_camera`:
    the other arguments of ``reproduce``.
-   :func:`setting_tables`: Tables 2–5 and their matches with the paper.

Units: wavelength in nm, temperature in K.

References
----------
-   :cite:`Martinkauppi2006` : Stage 1, Stage 3, Tables 2–5 (docs/references.md).
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass, fields, replace
from pathlib import Path

import numpy as np

from ...constants import SENSOR_RULE
from ...datasets import looks_like_path, reflectances
from ...design.bank import positions_grid, sensor_bank
from ...design.search import SECONDS_PER_TRIPLET
from ...errors import SkinrenderError, naming
from ...hints import ArrayLike, NDArrayFloat
from ...methods import validate_method
from ...model.camera import Camera, camera
from ...model.stage1 import illuminant_set
from ...spectra import EXTRAPOLATIONS, WavelengthGrid
from ...workload import check_work
from .matching import count_matches
from .tables import table_rows
from ...execution import check_workers
from .volumes import VolumeCache, bank_key, search_result

__all__ = ["STAGE1_CAMERA", "Setting", "SETTING_DEFAULT", "ResolvedSetting", "resolve_setting", "check_sensors",
           "check_positions", "check_search_work", "check_camera", "setting_tables", "with_unknown"]

STAGE1_CAMERA = "Nikon 5100 (NPL)"
"""The camera of ``--illuminants auto`` unless ``--stage1-camera`` names another (the Stage 2 camera)."""


@dataclass(frozen=True)
class Setting:
    """
    One choice of the paper's unknowns.

    Attributes
    ----------
    slope
        gbell slope *b* (``--slope``).
    grid
        Integration grid ``START:END:STEP`` in nm (``--grid``).
    skin, munsell
        Reflectance sets, names or CSV paths (``--skin``, ``--munsell``).
    illuminants
        ``paper``, ``auto`` (Stage 1 for ``stage1_camera``) or comma-separated
        kelvin (``--illuminants``).
    stage1_camera
        The camera of ``auto`` (``--stage1-camera``).
    extrapolation
        For reflectance sets that do not cover the grid (``--extrapolation``):
        ``refuse``, ``zero`` or ``constant``.
    """

    slope: float = 2.0
    grid: str = "400:700:1"
    skin: str = "skin"
    munsell: str = "munsell"
    illuminants: str = "paper"
    stage1_camera: str = STAGE1_CAMERA
    extrapolation: str = "refuse"

    def unknowns(self) -> dict:
        """The setting as a plain dict (JSON)."""
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def label(self, default: Setting | None = None, names: dict | None = None) -> str:
        """
        ``default`` or the unknowns that differ from ``default``, e.g.
        ``slope=3, illuminants=auto (Kodak DCS-200)``; ``names`` maps a spec
        (a CSV path) to a short name.
        """
        default = SETTING_DEFAULT if default is None else default
        names = names or {}

        def short(value) -> str:
            return names.get(value, Path(value).name if looks_like_path(str(value)) else str(value))

        parts = [f"slope={self.slope:g}"] if self.slope != default.slope else []
        parts += [f"{key}={short(getattr(self, key))}" for key in ("grid", "skin", "munsell")
                  if getattr(self, key) != getattr(default, key)]
        if self._illuminants() != default._illuminants():
            parts.append(f"illuminants={self.illuminants}" + (f" ({short(self.stage1_camera)})" if self._auto() else ""))
        if self.extrapolation != default.extrapolation:
            parts.append(f"extrapolation={self.extrapolation}")
        return ", ".join(parts) or "default"

    def _auto(self) -> bool:
        return str(self.illuminants).strip().lower() == "auto"

    def _illuminants(self) -> tuple:
        return (self.illuminants, self.stage1_camera) if self._auto() else (self.illuminants,)


SETTING_DEFAULT = Setting()
"""Our reading of the paper (docs/model.md): b = 2, 400–700 nm every 1 nm, Vrhel skin, Joensuu Munsell, its ten
illuminants."""


@dataclass(frozen=True)
class ResolvedSetting:
    """A checked :class:`Setting` with what it names loaded: grid, temperatures (K), reflectances on the grid."""

    setting: Setting
    grid: WavelengthGrid
    temperatures: NDArrayFloat
    skin: NDArrayFloat
    munsell: NDArrayFloat


_flagged = naming  # skinrender.errors.naming, as the command line's flag()


def resolve_setting(setting: Setting) -> ResolvedSetting:
    """
    Check every unknown of ``setting`` and load what it names.

    Raises
    ------
    SkinrenderError
        One line naming the flag: a slope that is not a finite number > 0, a
        malformed grid, an unknown set or one that does not cover the grid
        (without ``--extrapolation``), a bad illuminant list, an unknown
        Stage 1 camera.
    """

    slope = setting.slope
    if isinstance(slope, bool) or not isinstance(slope, (int, float, np.floating)) or not (
            np.isfinite(slope) and slope > 0):
        raise SkinrenderError(f"--slope must be a finite number > 0 (the gbell slope b), got {slope!r}", flag="--slope")
    grid = _flagged("--grid", WavelengthGrid.parse, setting.grid)
    _flagged("--extrapolation", validate_method, setting.extrapolation, EXTRAPOLATIONS, "extrapolation")
    values = {}
    for flag, spec in (("--skin", setting.skin), ("--munsell", setting.munsell)):
        spectra = _flagged(flag, reflectances, spec, setting.extrapolation)
        values[flag] = _flagged(flag, spectra.on, grid, None if setting.extrapolation == "refuse" else setting.extrapolation)
        if values[flag].shape[0] < 4:
            raise SkinrenderError(f"{flag}: a gamut needs at least 4 reflectances, {spec!r} has {values[flag].shape[0]}",
                                  flag=flag)
    stage1 = check_camera(setting.stage1_camera, grid, "--stage1-camera") if setting._auto() else None
    temperatures = _flagged("--illuminants", illuminant_set, setting.illuminants, stage1)
    if temperatures.size < 1:
        raise SkinrenderError(f"--illuminants names no illuminant: {setting.illuminants!r}", flag="--illuminants")
    return ResolvedSetting(setting, grid, np.asarray(temperatures, dtype=np.float64), values["--skin"],
                           values["--munsell"])


def check_sensors(sensors: str | ArrayLike) -> list[float]:
    """The paper's sensor numbers (``1,3,…,15``; :data:`~skinrender.design.bank.SENSOR_RULE`), checked."""
    try:
        items = [float(v) for v in sensors.split(",")] if isinstance(sensors, str) else [float(v) for v in sensors]
    except (TypeError, ValueError):
        raise SkinrenderError(f"--sensors must be comma-separated numbers (1 = impulse, 3, 5, … = gbell), "
                              f"got {sensors!r}", flag="--sensors") from None
    if not items:
        raise SkinrenderError("--sensors names no sensor", flag="--sensors")
    bad = [v for v in items if not (np.isfinite(v) and v > 0)]
    if bad:
        raise SkinrenderError(f"--sensors: {bad[0]:g} is not a sensor: each must be {SENSOR_RULE}", flag="--sensors")
    if len(set(items)) != len(items):
        raise SkinrenderError(f"--sensors lists a sensor twice: {sensors!r}", flag="--sensors")
    return items


def check_search_work(sensors: int, where: NDArrayFloat, flag: str = "--positions", max_minutes: float | None = None,
                      workers: int | None = None, each: str = "") -> None:
    """
    Refuse searches of ``sensors`` sensors over the peaks ``where`` (nm) whose estimated time (every triplet at
    :data:`~skinrender.design.search.SECONDS_PER_TRIPLET` per core) exceeds ``max_minutes``
    (:func:`skinrender.workload.check_work`), naming ``flag``; ``each``: a prefix such as ``"each setting's "``.

    >>> check_search_work(8, np.arange(400.0, 701.0, 10.0))
    """
    n = int(np.size(where))
    count = n * (n - 1) * (n - 2) // 6
    cores = workers or os.cpu_count() or 1
    check_work(sensors * count * SECONDS_PER_TRIPLET / cores, flag,
               f"{each}{sensors} search{'es' * (sensors != 1)} of {count} triplets ({n} positions) on {cores} "
               f"core{'s' * (cores != 1)}", max_minutes, fewer=f"use fewer positions (a larger {flag} step)")


def check_positions(positions: str | ArrayLike, grid: WavelengthGrid, flag: str = "--positions") -> NDArrayFloat:
    """Sensor peaks (nm) from ``START:END:STEP``, at least three, inside ``grid``; errors name ``flag``."""
    where = _flagged(flag, positions_grid, positions)
    if where.min() < grid.start or where.max() > grid.end:
        raise SkinrenderError(f"{flag} {where.min():g}–{where.max():g} nm leave the integration grid {grid} "
                              "(peaks are in nm; or widen --grid)", flag=flag)
    return where


def check_camera(spec: str | Camera, grid: WavelengthGrid, flag: str = "--camera") -> Camera:
    """A camera from its spec, checked to cover ``grid``."""
    cam = _flagged(flag, camera, spec)
    _flagged(flag, cam.sensitivities, grid)
    return cam


def setting_tables(
    resolved: ResolvedSetting,
    sensors: ArrayLike,
    positions: NDArrayFloat,
    cache: VolumeCache | None = None,
    workers: int | None = None,
    dask=None,
    progress=None,
    notice=None,
    on_start=None,
) -> dict:
    """
    Tables 2–5 under one setting, and their matches with the paper.

    Returns
    -------
    dict
        ``results`` (sensor → :class:`~skinrender.design.search.SearchResult`),
        ``tables`` (sensor → table cells, :func:`~skinrender.studies.paper.tables.table_rows`),
        ``matches`` (:func:`~skinrender.studies.paper.matching.count_matches`),
        ``search_s`` (sensor → seconds its volumes took, ``0`` when all came
        from the cache), ``elapsed_s``.
    """

    cache = VolumeCache() if cache is None else cache
    workers = check_workers(workers)
    s = resolved.setting
    banks, keys = {}, {}
    start = time.perf_counter()
    for sensor in sensors:
        pair = []
        for spec, values in ((s.skin, resolved.skin), (s.munsell, resolved.munsell)):
            key = bank_key(sensor, spec, positions, resolved.temperatures, s.slope, resolved.grid, s.extrapolation)
            if key not in cache and key not in banks:
                # the positions and slope are checked: what is left to refuse is a light the sensors do not see
                banks[key] = _flagged("--illuminants", sensor_bank, sensor, values, positions, resolved.temperatures,
                                      s.slope, "white", False, resolved.grid)
            pair.append(key)
        keys[float(sensor)] = pair
    finished = cache.ensure(banks, workers=workers, dask=dask, progress=progress, label=f"tables, {s.label()}",
                            notice=notice, on_start=on_start)
    results, tables, timings, previous = {}, {}, {}, 0.0
    for sensor, (skin_key, munsell_key) in keys.items():
        done = max([finished.get(skin_key, 0.0), finished.get(munsell_key, 0.0)])
        timings[f"{sensor:g}"] = max(done - previous, 0.0) if done else 0.0
        previous = max(previous, done)
        results[sensor] = search_result(sensor, s.slope, positions, resolved.temperatures, cache[skin_key],
                                        cache[munsell_key],
                                        timings[f"{sensor:g}"], 1 if dask is not None else workers)
        tables[sensor] = table_rows(results[sensor])
    return {"results": results, "tables": tables, "matches": count_matches(tables), "search_s": timings,
            "elapsed_s": time.perf_counter() - start}


def with_unknown(setting: Setting, name: str, value) -> Setting:
    """``setting`` with one unknown changed (``illuminants`` takes ``(spec, stage1 camera)``)."""
    if name == "illuminants":
        spec, stage1 = value
        return replace(setting, illuminants=spec, stage1_camera=stage1 or setting.stage1_camera)
    if name == "grid":
        wide = WavelengthGrid.parse(value)
        out = replace(setting, grid=value)
        return out if (wide.start >= 400 and wide.end <= 700) else replace(out, extrapolation="constant")
    return replace(setting, **{name: value})
