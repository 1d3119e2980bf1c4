"""
Tests for :mod:`skinrender.studies.face.workers`: results in task order from this process, worker processes and
Dask; a worker's stdout goes to stderr; errors reach the caller (an unreachable scheduler:
tests/cli/test_face_sweep.py). (That renders give the same numbers every way is
tested through the face sweep, tests/studies/face/test_sweep.py; the pool itself: tests/test_execution.py.)
"""

from __future__ import annotations

import operator
import subprocess
import sys
from functools import partial

import pytest

from skinrender.rendering.variants import choose_variant
from skinrender.studies.face.workers import dask_name, run_renders, set_threads

pytest.importorskip("mitsuba")


@pytest.fixture(scope="module")
def variant() -> str:
    return choose_variant(None)


@pytest.mark.parametrize("workers", [1, 2])
def test_results_in_task_order(variant, workers):
    assert run_renders(partial(operator.mul, 3), [5, 1, 4, 2], variant, workers) == [15, 3, 12, 6]


def test_one_worker_restores_the_thread_count(variant):
    before = set_threads(2)
    try:
        run_renders(abs, [-1], variant, 1)
        assert set_threads(before) == 2
    finally:
        set_threads(before)


def test_dask(variant):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        assert run_renders(partial(operator.add, 1), [2, 3], variant, dask=client) == [3, 4]
        assert dask_name(client) == cluster.scheduler_address
    assert dask_name(None) is None and dask_name("tcp://h:1") == "tcp://h:1"


def test_an_error_in_a_worker_reaches_the_caller(variant):
    with pytest.raises(ZeroDivisionError):
        run_renders(partial(operator.truediv, 1), [1, 0, 2], variant, 2)


def test_a_worker_writes_nothing_on_stdout():
    """A pool worker's writes on its stdout (file descriptor 1, where Mitsuba's native log would go, and print)
    reach stderr, never the parent's stdout, which holds ``--json``'s one document. Both kinds of write are tasks of
    one pool of two workers (``exec`` of each line: a builtin, so it pickles), not a pool each."""
    script = ("from skinrender.rendering.variants import choose_variant\n"
              "from skinrender.studies.face.workers import run_renders\n"
              "run_renders(exec, ['import os; os.write(1, b\"written on descriptor 1\\\\n\")',\n"
              "                   'print(\"printed by a worker\")', 'print(\"and another\")'], choose_variant(None), 2)\n"
              "print('the parent')\n")
    done = subprocess.run([sys.executable, "-c", script], check=False, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-800:]
    assert done.stdout == "the parent\n"
    assert "written on descriptor 1" in done.stderr and "printed by a worker" in done.stderr
