"""
Face renders on every core or a Dask cluster
============================================

How the face studies (:mod:`~skinrender.studies.face.sweep`,
:mod:`~skinrender.studies.face.locus`) run a list of tasks, each one render,
in this process, in a pool of worker processes, or on a Dask cluster: on
:func:`skinrender.execution.map_tasks`, as the Stage 3 search spreads its triplets,
with workers set up for Mitsuba and the same numbers every way.

-   :func:`run_renders`: the results of ``function(task)`` in task order.
-   :data:`RENDER_THREADS`, :func:`set_threads`: one drjit thread per render.
-   :class:`RenderRun`: how a study's renders ran (size, spp, seed, variant, workers, time, Dask), the fields the
    sweep's and the ranking's results share.

Determinism: every render uses the Mitsuba variant chosen once by the caller
and :data:`RENDER_THREADS` drjit thread (the LLVM backend's sums over a
pixel's samples depend on how the work is split between threads: measured,
2 threads against 1 move a face's skin NCC by ~1e-10 at 48 px and 32 spp),
so one worker, several or a Dask cluster give the same numbers. Parallelism
is over renders: one process per core. Workers are started fresh
(``spawn``: drjit's threads do not survive a ``fork``; a script that asks for
several workers needs the ``if __name__ == "__main__":`` guard); each sets
the variant and sends anything written on its stdout to stderr, so that
``--json`` keeps stdout to itself. On Dask, run workers of one thread each
(``dask worker --nworkers N --nthreads 1``): a render sets its process's
drjit thread count.

Units: times s.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import partial

from ... import execution
from ...execution import dask_name
from ...rendering.variants import choose_variant, libllvm_path, mitsuba

__all__ = ["RENDER_THREADS", "RenderRun", "run_renders", "set_threads", "dask_name"]

RENDER_THREADS = 1
"""drjit threads per render, in every worker and in this process (restored after a one-worker run): the same
split of the work everywhere gives the same numbers."""


@dataclass(frozen=True, kw_only=True)
class RenderRun:
    """
    How a face study's renders ran; its fields are keywords, after the study's own.

    Attributes
    ----------
    size
        Image side, pixels.
    spp
        Samples per pixel of each render (as the study reports it).
    seed
        The first seed.
    variant
        The Mitsuba variant every render used.
    workers
        Worker processes (1 on a Dask cluster).
    elapsed_s
        Wall time of the renders, s.
    dask
        The Dask scheduler's address, or ``None``.
    """

    size: int
    spp: int
    seed: int
    variant: str
    workers: int
    elapsed_s: float
    dask: str | None = None


def set_threads(count: int = RENDER_THREADS) -> int:
    """
    Set drjit's thread count (the LLVM backend's pool); returns the count before.

    Examples
    --------
    >>> before = set_threads(1)
    >>> set_threads(before)
    1
    """
    libllvm_path()  # before drjit is first imported (a fresh Dask worker)
    import drjit

    before = drjit.thread_count()
    if before != count:
        drjit.set_thread_count(count)
    return before


def _init_worker(variant: str) -> None:
    """A pool worker: stdout is stderr, the variant is set, :data:`RENDER_THREADS`."""
    sys.stdout.flush()
    os.dup2(2, 1)  # a worker shares the parent's stdout, the JSON's: nothing of Mitsuba's may land there
    sys.stdout = sys.stderr
    mitsuba(choose_variant(variant))
    set_threads(RENDER_THREADS)


def _threaded(function: Callable, task):
    """``function(task)`` with :data:`RENDER_THREADS` drjit threads (a Dask worker's process is set here)."""
    set_threads(RENDER_THREADS)
    return function(task)


def run_renders(function: Callable, tasks: Sequence, variant: str, workers: int = 1, dask=None, progress=None,
                label: str = "renders") -> list:
    """
    ``function(task)`` for every task, in task order (:func:`skinrender.execution.map_tasks`).

    Parameters
    ----------
    function
        A picklable callable (a module-level function, or a :func:`functools.partial` of one) that renders one
        task with ``variant`` and returns a picklable result.
    tasks
        The tasks (picklable).
    variant
        The Mitsuba variant every worker sets (chosen once by the caller, e.g. with
        :func:`~skinrender.rendering.variants.choose_variant`).
    workers
        Processes; 1 runs in this process.
    dask
        A Dask scheduler address (``tcp://host:8786``) or a ``distributed.Client``: the tasks run there.
    progress
        A stream (``sys.stderr``) for a progress bar (shown on a terminal only), or ``None``.
    label
        The progress bar's label.

    Returns
    -------
    list
        One result per task.
    """
    before = set_threads(RENDER_THREADS) if dask is None and workers == 1 else None
    try:
        return execution.map_tasks(partial(_threaded, function), tasks, workers=workers, dask=dask,
                             initializer=_init_worker, initargs=(variant,), start="spawn", progress=progress,
                             label=label, unit="render")
    finally:
        if before is not None:
            set_threads(before)
