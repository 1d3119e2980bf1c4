"""
Triplet volumes for many searches at once
=========================================

The Stage 3 search of :func:`skinrender.design.search.search` computes one
sensor's skin and Munsell volumes together. Reproducing Tables 2–5 needs eight
sensors, and a sweep over the paper's unknowns needs them again for every
setting, where many volumes repeat: a different skin set leaves the Munsell
volumes as they were. This module computes the volumes of any number of
single-sensor banks (:class:`~skinrender.design.bank.SensorBank`) in one
process pool (or on one Dask cluster), so that no core idles between sensors,
and keeps them in a cache keyed by everything they depend on.

The volumes are those of :func:`skinrender.design.search.search`, to the bit:
the same function (:func:`skinrender.design.criteria.triplet_volumes_fast`)
computes every triplet.

-   :func:`bank_key`: the cache key of one bank.
-   :class:`VolumeCache`: volumes per key, computed on demand.
-   :func:`compute_volumes`: the volumes of several banks, every core.
-   :func:`search_result`: a :class:`~skinrender.design.search.SearchResult`
    from two banks' volumes.
"""

from __future__ import annotations

import time

import numpy as np

from ... import execution
from ...design.bank import SensorBank, triplets
from ...design.criteria import triplet_gains, triplet_volumes_many
from ...design.search import SearchResult
from ...execution import check_workers
from ...evaluation.hull import HULL_KERNEL, notice_kernel
from ...hints import NDArrayFloat

__all__ = ["bank_key", "VolumeCache", "compute_volumes", "chunk_gains", "search_result"]


def _chunk(banks: tuple[SensorBank, ...], task: tuple[int, np.ndarray]) -> NDArrayFloat:
    """Volumes ``(len(index), Q + 1)`` of the triplets ``index`` of bank number ``bank`` (``task``)."""
    bank, index = task
    return triplet_volumes_many(banks[bank], np.asarray(index))


chunk_gains = triplet_gains
"""The gains of many triplets at once: :func:`skinrender.design.criteria.triplet_gains` (its earlier name)."""


def bank_key(sensor: float, spec: str, positions: NDArrayFloat, temperatures: NDArrayFloat, slope: float,
             grid, extrapolation: str) -> tuple:
    """
    Everything a bank's volumes depend on (the white normalisation without the
    knee, Stage 3's); the impulse (sensor 1) has no slope.
    """
    return (float(sensor), str(spec), tuple(np.asarray(positions, float).tolist()),
            tuple(np.asarray(temperatures, float).tolist()), 0.0 if float(sensor) == 1 else float(slope), str(grid),
            str(extrapolation))


def compute_volumes(
    banks: dict[tuple, SensorBank],
    workers: int | None = None,
    dask=None,
    progress=None,
    label: str = "volumes",
    chunks_per_bank: int | None = None,
    notice=None,
    on_start=None,
) -> tuple[dict[tuple, NDArrayFloat], dict[tuple, float]]:
    """
    Every triplet's volumes for several banks on one pool.

    Parameters
    ----------
    banks
        Key → bank; all on the same positions.
    workers, dask
        As :func:`skinrender.design.search.search`: processes (``None`` =
        every core) or a Dask scheduler address / client.
    progress
        Stream for one progress bar over every bank, or ``None``.
    chunks_per_bank
        Work items per bank (default: four per worker, at least four).
    notice
        Stream for the one-line notice when the compiled hull kernel is missing.
    on_start
        Called once the work is under way (after the worker processes were
        forked): other work of the caller may run then (in this thread,
        or start in another); an exception it raises stops the workers and
        is raised here.

    Returns
    -------
    tuple
        ``volumes`` (key → ``(T, Q + 1)``, output units³) and ``finished``
        (key → seconds from the start until that bank's last triplet was
        done; banks run in the order given).
    """

    if not banks:
        if on_start is not None:
            on_start()
        return {}, {}
    workers = check_workers(workers)
    keys = list(banks)
    items = tuple(banks[k] for k in keys)
    index = triplets(items[0].positions.size)
    per_bank = chunks_per_bank or (1 if workers == 1 and dask is None else 4 * max(workers, 4))
    parts = [part for part in np.array_split(np.arange(len(index)), per_bank) if len(part)]
    jobs = [(b, part) for b in range(len(items)) for part in parts]
    out = {k: np.empty((len(index), items[0].white.shape[0] + 1)) for k in keys}
    remaining = {k: len(parts) for k in keys}
    finished: dict[tuple, float] = {}
    notice_kernel(notice)
    start = time.perf_counter()

    def store(number: int, values) -> None:
        bank, part = jobs[number]
        key = keys[bank]
        out[key][part] = values
        remaining[key] -= 1
        if remaining[key] == 0:
            finished[key] = time.perf_counter() - start

    execution.map_tasks(_chunk, [(b, index[part]) for b, part in jobs], workers=workers, dask=dask, shared=items,
                  progress=progress, label=label, unit="triplet", sizes=[len(part) for _, part in jobs],
                  on_start=on_start, on_result=store)
    return out, finished


class VolumeCache:
    """
    Volumes per :func:`bank_key`, computed on demand and kept.

    :meth:`ensure` computes the missing banks of a request in one pool; what
    was computed before (the Munsell volumes of a setting that only changes
    the skin set) is not computed again.
    """

    def __init__(self) -> None:
        self.volumes: dict[tuple, NDArrayFloat] = {}
        self.computed = 0

    def ensure(self, banks: dict[tuple, SensorBank], **options) -> dict[tuple, float]:
        """Compute the volumes of the keys not yet known; returns their finishing times (s)."""
        missing = {k: v for k, v in banks.items() if k not in self.volumes}
        volumes, finished = compute_volumes(missing, **options)
        self.volumes.update(volumes)
        self.computed += len(missing)
        return finished

    def __contains__(self, key: tuple) -> bool:
        return key in self.volumes

    def __getitem__(self, key: tuple) -> NDArrayFloat:
        return self.volumes[key]


def search_result(sensor: float, slope: float, positions: NDArrayFloat, temperatures: NDArrayFloat,
                  skin_volumes: NDArrayFloat, munsell_volumes: NDArrayFloat, elapsed_s: float,
                  workers: int) -> SearchResult:
    """The :class:`~skinrender.design.search.SearchResult` of one sensor from its two banks' volumes."""
    where = np.asarray(positions, dtype=np.float64)
    return SearchResult(float(sensor), float(slope), where, where[triplets(where.size)],
                        np.asarray(temperatures, dtype=np.float64),
                        skin_volumes, munsell_volumes, float(elapsed_s), "fast", workers, "white", False,
                        info={"hull_kernel": HULL_KERNEL})
