"""
Face renders on every core or a Dask cluster
============================================

The executor of the face studies (:mod:`~skinrender.studies.face.sweep`,
:mod:`~skinrender.studies.face.locus`): a list of tasks, each one render,
run in this process, in a pool of worker processes, or on a Dask cluster, as
the Stage 3 search spreads its triplets (:mod:`skinrender.design.search`),
with the same numbers every way.

-   :func:`run_renders`: the results of ``function(task)`` in task order.
-   :data:`RENDER_THREADS`, :func:`set_threads`: one drjit thread per render.

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

import multiprocessing
import os
import signal
import sys
from collections.abc import Callable, Sequence
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

from ...design.search import DASK_TIMEOUT_S
from ...errors import SkinrenderError
from ...extras import require
from ...rendering.variants import choose_variant, libllvm_path, mitsuba
from ...workload import announce, progress_bar

__all__ = ["RENDER_THREADS", "run_renders", "set_threads", "dask_name"]

RENDER_THREADS = 1
"""drjit threads per render, in every worker and in this process (restored after a one-worker run): the same
split of the work everywhere gives the same numbers."""


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
    """A pool worker: Ctrl-C is the parent's, stdout is stderr, the variant is set, :data:`RENDER_THREADS`."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    sys.stdout.flush()
    os.dup2(2, 1)  # a worker shares the parent's stdout, the JSON's: nothing of Mitsuba's may land there
    sys.stdout = sys.stderr
    mitsuba(choose_variant(variant))
    set_threads(RENDER_THREADS)


def _threaded(function: Callable, task):
    """``function(task)`` with :data:`RENDER_THREADS` drjit threads (a Dask worker's process is set here)."""
    set_threads(RENDER_THREADS)
    return function(task)


def dask_name(dask) -> str | None:
    """The scheduler address of ``dask`` (an address or a ``distributed.Client``), ``None`` without one."""
    if dask is None or isinstance(dask, str):
        return dask
    return str(getattr(getattr(dask, "scheduler", None), "address", "a Dask client"))


def run_renders(function: Callable, tasks: Sequence, variant: str, workers: int = 1, dask=None, progress=None,
                label: str = "renders") -> list:
    """
    ``function(task)`` for every task, in task order.

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
    results: list = [None] * len(tasks)
    bar = progress_bar(len(tasks), label, progress, "render")
    try:
        if dask is not None:
            _run_dask(dask, function, tasks, results, bar, lambda: announce(progress, label, len(tasks), "render"))
        elif workers == 1:
            announce(progress, label, len(tasks), "render")
            before = set_threads(RENDER_THREADS)
            try:
                for i, task in enumerate(tasks):
                    results[i] = function(task)
                    bar.update(1)
            finally:
                set_threads(before)
        else:
            _run_pool(workers, function, tasks, variant, results, bar, lambda: announce(progress, label, len(tasks),
                                                                                         "render"))
    finally:
        bar.close()
    return results


def _run_pool(workers: int, function: Callable, tasks: Sequence, variant: str, results: list, bar, started=lambda: None) -> None:
    pool = ProcessPoolExecutor(min(workers, len(tasks)), mp_context=multiprocessing.get_context("spawn"),
                               initializer=_init_worker, initargs=(variant,))
    try:
        futures = {pool.submit(function, task): i for i, task in enumerate(tasks)}
        started()  # the workers are spawned and busy
        pending = set(futures)
        while pending:
            done, pending = wait(pending, return_when=FIRST_COMPLETED)
            for future in done:
                results[futures[future]] = future.result()
                bar.update(1)
    except BaseException:  # Ctrl-C or an error: stop the workers now and drop the queued renders
        for process in list((getattr(pool, "_processes", None) or {}).values()):
            process.terminate()
        # waiting is short once the workers are gone, and it frees the queues' named semaphores: a `spawn` pool's
        # resource tracker would otherwise warn of them on stderr when the command line exits at once (130)
        pool.shutdown(wait=True, cancel_futures=True)
        raise
    pool.shutdown()


def _run_dask(dask, function: Callable, tasks: Sequence, results: list, bar, started=lambda: None) -> None:
    require("dask", "--dask")
    from distributed import Client, as_completed

    own = not isinstance(dask, Client)
    if own:
        try:
            client = Client(dask, timeout=DASK_TIMEOUT_S)
        except (OSError, ValueError, TypeError, TimeoutError) as error:
            raise SkinrenderError(f"--dask: cannot reach a Dask scheduler at {dask!r} within {DASK_TIMEOUT_S:g} s "
                                  f"({type(error).__name__}: {' '.join(str(error).split())[:120]})",
                                  flag="--dask") from None
    else:
        client = dask
    started()  # the scheduler answered: the renders start
    try:
        futures = [client.submit(_threaded, function, task, pure=False) for task in tasks]
        index = {future.key: i for i, future in enumerate(futures)}
        for future in as_completed(futures):
            results[index[future.key]] = future.result()
            bar.update(1)
    finally:
        if own:
            client.close()
