"""
Tests for :mod:`skinrender.execution`: one ``map_tasks`` in this process, in worker processes and on Dask, results in
task order every way; the data the tasks share; progress; an error or an interrupt stops the workers and reaches
the caller; the worker count's check. (Ctrl-C from the command line: tests/cli/test_design.py and
tests/cli/test_face_sweep.py; the Stage 3 search, the volumes and the face renders on it: their own tests.)
"""

from __future__ import annotations

import io
import operator
import os
import threading
from functools import partial

import numpy as np
import pytest

from skinrender import execution
from skinrender.errors import SkinrenderError
from skinrender.execution import WORKERS_MAX, check_workers, dask_name


def _pid(_task) -> int:
    return os.getpid()


def _shared_sum(shared: np.ndarray, task: int) -> float:
    return float(shared[task]) + 0.5


def _pid_and_shared(shared, _task) -> tuple[int, int]:
    return os.getpid(), id(shared)


def _signal_ignored(_task) -> bool:
    import signal

    return signal.getsignal(signal.SIGINT) == signal.SIG_IGN


_STARTED: list = []


def _mark(value) -> None:
    _STARTED.append(value)


def _marked(_task) -> list:
    return list(_STARTED)


class TestMap:
    @pytest.mark.parametrize("workers", [1, 2])
    def test_results_in_task_order(self, workers):
        assert execution.map_tasks(partial(operator.mul, 3), [5, 1, 4, 2, 7], workers=workers) == [15, 3, 12, 6, 21]

    def test_map_is_the_deprecated_name_of_map_tasks(self):
        """``execution.map`` shadowed the builtin: still there, with a notice, and the same function."""
        with pytest.warns(DeprecationWarning, match="map_tasks"):
            assert execution.map is execution.map_tasks
        assert "map" not in vars(execution)

    def test_no_tasks(self):
        started = []
        assert execution.map_tasks(abs, [], workers=2, on_start=lambda: started.append(True)) == []
        assert started == [True]

    def test_one_worker_runs_here(self):
        assert set(execution.map_tasks(_pid, range(3))) == {os.getpid()}

    def test_two_workers_run_elsewhere(self):
        pids = execution.map_tasks(_pid, range(6), workers=2)
        assert os.getpid() not in pids and 1 <= len(set(pids)) <= 2

    @pytest.mark.parametrize("workers", [1, 2])
    def test_shared_data_is_the_first_argument(self, workers):
        shared = np.arange(10.0)
        assert execution.map_tasks(_shared_sum, [3, 0, 9], workers=workers, shared=shared) == [3.5, 0.5, 9.5]

    def test_shared_data_is_sent_once_per_worker(self):
        """Every task of one worker sees the same object: the worker's copy, not one pickled with each task."""
        seen = execution.map_tasks(_pid_and_shared, range(8), workers=2, shared=np.zeros(1000))
        by_worker = {}
        for pid, identity in seen:
            by_worker.setdefault(pid, set()).add(identity)
        assert all(len(ids) == 1 for ids in by_worker.values())

    def test_workers_ignore_ctrl_c_the_parent_handles_it(self):
        assert execution.map_tasks(_signal_ignored, range(2), workers=2) == [True, True]

    def test_the_initializer_runs_in_each_worker(self):
        assert execution.map_tasks(_marked, range(2), workers=2, initializer=_mark, initargs=("ready",)) == [["ready"]] * 2

    @pytest.mark.parametrize("workers", [1, 2])
    def test_on_start_and_on_result(self, workers):
        events = []
        execution.map_tasks(abs, [-1, -2, -3], workers=workers, on_start=lambda: events.append("start"),
                      on_result=lambda i, r: events.append((i, r)))
        assert events[0] == "start" and sorted(events[1:]) == [(0, 1), (1, 2), (2, 3)]

    def test_progress_counts_the_sizes(self):
        """Not a terminal: one line saying the work started, in the units of ``sizes``."""
        log = io.StringIO()
        execution.map_tasks(abs, [-1, -2], sizes=[4, 3], progress=log, label="sensor 9", unit="triplet")
        assert log.getvalue() == "sensor 9: 7 triplets …\n"

    @pytest.mark.parametrize("workers", [1, 2])
    def test_an_error_in_a_task_reaches_the_caller(self, workers):
        with pytest.raises(ZeroDivisionError):
            execution.map_tasks(partial(operator.truediv, 1), [1, 0, 2], workers=workers)

    def test_an_interrupt_stops_the_workers(self, monkeypatch):
        """Ctrl-C (raised by ``on_start``, once the workers are busy: no timing involved) terminates them."""
        pools = []
        real = execution.ProcessPoolExecutor

        def recorded(*args, **kwargs):
            pools.append(real(*args, **kwargs))
            return pools[-1]

        workers = []

        def interrupt():
            workers.extend(pools[0]._processes.values())  # started and busy
            raise KeyboardInterrupt

        monkeypatch.setattr(execution, "ProcessPoolExecutor", recorded)
        with pytest.raises(KeyboardInterrupt):
            execution.map_tasks(abs, range(50), workers=2, on_start=interrupt)
        assert workers and not any(process.is_alive() for process in workers)
        assert pools[0]._shutdown_thread  # the pool was shut down: the queued tasks were dropped

    def test_dask(self):
        distributed = pytest.importorskip("distributed")
        with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                      dashboard_address=None) as cluster, distributed.Client(cluster) as client:
            assert execution.map_tasks(partial(operator.add, 1), [2, 3, 4], dask=client) == [3, 4, 5]
            assert execution.map_tasks(_shared_sum, [1, 2], dask=client, shared=np.arange(3.0)) == [1.5, 2.5]
            with pytest.raises(ZeroDivisionError):
                execution.map_tasks(partial(operator.truediv, 1), [1, 0], dask=client)
            assert dask_name(client) == cluster.scheduler_address
        assert dask_name(None) is None and dask_name("tcp://h:1") == "tcp://h:1"

    def test_an_unreachable_scheduler_is_one_line_naming_the_flag(self, monkeypatch):
        """Waiting 1 s for the scheduler (:data:`~skinrender.execution.DASK_TIMEOUT_S`) rather than the
        default 10 s: the refusal is the same, and it names the wait."""
        pytest.importorskip("distributed")
        monkeypatch.setattr(execution, "DASK_TIMEOUT_S", 1.0)
        with pytest.raises(SkinrenderError, match="^--dask: cannot reach a Dask scheduler") as error:
            execution.map_tasks(abs, [1], dask="tcp://127.0.0.1:9")
        message = str(error.value)
        assert error.value.flag == "--dask" and "within 1 s" in message and "\n" not in message


class TestDaskAddress:
    """Issue 36: ``--dask`` pointing at something that is not a Dask scheduler hung past 60 s or said "out of
    memory" (Dask read an HTTP answer's first bytes as a message length of ~3e18 bytes)."""

    @staticmethod
    def server(answer: bytes | None):
        """A TCP server on a free port that answers ``answer`` to whatever it is sent (``None``: says nothing)."""
        import socket
        import threading

        listener = socket.create_server(("127.0.0.1", 0))
        held = []

        def serve():
            while True:
                try:
                    connection, _ = listener.accept()
                except OSError:
                    return
                held.append(connection)
                if answer is not None:
                    connection.recv(1024)
                    connection.sendall(answer)

        threading.Thread(target=serve, daemon=True).start()
        return listener, f"tcp://127.0.0.1:{listener.getsockname()[1]}"

    def test_an_http_server_is_refused_at_once(self):
        pytest.importorskip("distributed")
        listener, address = self.server(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n")
        with listener, pytest.raises(SkinrenderError, match=r"^--dask: tcp://127\.0\.0\.1:\d+ is not a Dask "
                                     r"scheduler: its first message is not Dask's \('HTTP/1\.1'…\)$") as error:
            execution.check_dask_address(address, timeout=60)  # refused on its answer, not on the timeout
        assert error.value.flag == "--dask"

    def test_a_silent_server_is_refused_after_the_timeout(self):
        pytest.importorskip("distributed")
        listener, address = self.server(None)
        with listener, pytest.raises(SkinrenderError, match="is not a Dask scheduler: no Dask handshake within 0.3 s"):
            execution.check_dask_address(address, timeout=0.3)

    @pytest.mark.parametrize("address, message", [
        ("", "expected a Dask scheduler address"), ("  ", "expected a Dask scheduler address"),
        ("http://127.0.0.1:8787", "is a http:// address, not a Dask scheduler's"),
        ("tcp://127.0.0.1:notaport", "is not a Dask scheduler address"),
    ])
    def test_malformed_addresses(self, address, message):
        pytest.importorskip("distributed")
        with pytest.raises(SkinrenderError, match=message):
            execution.check_dask_address(address)

    def test_a_scheduler_passes_and_one_without_workers_is_named(self, monkeypatch):
        distributed = pytest.importorskip("distributed")
        monkeypatch.setattr(execution, "DASK_TIMEOUT_S", 1.0)
        with distributed.LocalCluster(n_workers=0, processes=False, dashboard_address=None) as cluster:
            address = cluster.scheduler_address
            assert execution.check_dask_address(address) == address  # its handshake is Dask's
            with pytest.raises(SkinrenderError, match="has no workers .none joined within 1 s."):
                execution.map_tasks(abs, [1], dask=address)


class TestCheckWorkers:
    def test_default_is_every_core(self):
        assert check_workers(None) == (os.cpu_count() or 1)

    def test_the_bounds(self):
        assert check_workers(1) == 1 and check_workers(WORKERS_MAX) == WORKERS_MAX
        assert check_workers(np.int64(2)) == 2

    @pytest.mark.parametrize("bad", [0, -1, 1.5, 2.0, True, 1000, "2", float("nan")])
    def test_refused(self, bad):
        with pytest.raises(SkinrenderError, match="--workers") as error:
            check_workers(bad)
        assert error.value.flag == "--workers"


def test_ctrl_c_while_collecting_is_raised_between_waits_holding_no_lock():
    """A Ctrl-C that arrives while results are collected is raised by ``_collect`` itself, between two waits, with
    no future's lock held. (Raised wherever it landed, it could fall inside ``concurrent.futures.wait`` while that
    held some futures' locks: the process pool's manager thread then blocked on one, and stopping the pool waited
    for ever: a search interrupted in CI hung until its watchdog.) The signal is sent from inside the first
    result's ``store``: the old handler raised it there."""
    import os
    import signal
    import traceback
    from concurrent.futures import ThreadPoolExecutor

    from skinrender.execution import _collect

    gate = threading.Event()
    with ThreadPoolExecutor(2) as pool:
        futures = {pool.submit(lambda: 1): 0, pool.submit(gate.wait): 1}
        futures_list = list(futures)
        futures_list[0].result()

        def store(index, result):
            os.kill(os.getpid(), signal.SIGINT)

        try:
            with pytest.raises(KeyboardInterrupt) as raised:
                _collect(futures, lambda: None, store)
            assert traceback.extract_tb(raised.tb)[-1].name == "_collect"
            for future in futures_list:
                assert future._condition.acquire(blocking=False), "a future's lock was left held"
                future._condition.release()
        finally:
            gate.set()
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
