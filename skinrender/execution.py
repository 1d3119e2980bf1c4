"""
Many tasks on one core, every core or a Dask cluster
====================================================

One way to run a list of independent tasks: :func:`map_tasks` calls ``function(task)`` for each, in this process
(one worker), in a pool of worker processes (:class:`concurrent.futures.ProcessPoolExecutor`), or on a Dask
cluster (the ``concurrent.futures`` executor of a ``distributed.Client``, :meth:`Client.get_executor`), and
returns the results in task order, the same every way. The Stage 3 search
(:func:`skinrender.design.search.search`), the volumes of many searches
(:mod:`skinrender.studies.paper.volumes`) and the face renders (:mod:`skinrender.studies.face.workers`) run
on it.

What every caller gets the same:

-   **Progress**: a bar on a terminal, one line elsewhere (:func:`~skinrender.workload.progress_bar`,
    :func:`~skinrender.workload.announce`), said once the work is under way (the workers started).
-   **Ctrl-C and errors**: the workers ignore SIGINT (the parent handles it, no traceback per worker); an
    interrupt or a task's error terminates the workers at once, drops the queued tasks and is raised here.
-   **Data shared by every task** (``shared``): sent once per worker (the pool's initializer, Dask's
    ``scatter(broadcast=True)``), not with every task.
-   **Workers**: :func:`check_workers` (``--workers``: ``None`` is every core); :func:`dask_client`
    (``--dask``: an address or a client).

Determinism is the caller's: a task carries its seed; a result does not depend on the worker that computed
it or on the order tasks finish in.

-   :func:`map_tasks` (formerly ``map``, which shadowed the builtin: a deprecated alias), :func:`check_workers`,
    :func:`dask_client`, :func:`check_dask_address` (a scheduler's handshake, within a timeout), :func:`dask_name`,
    :func:`stop_pool`.
-   :data:`WORKERS_MAX`, :data:`DASK_TIMEOUT_S`.

Units: times s.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import signal
import threading
from collections.abc import Callable, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait

import numpy as np

from .errors import SkinrenderError, flag_of
from .extras import require
from .workload import announce, progress_bar

__all__ = ["WORKERS_MAX", "DASK_TIMEOUT_S", "DASK_SCHEMES", "map_tasks", "check_workers", "dask_client",
           "check_dask_address", "dask_name", "stop_pool"]

WORKERS_MAX = max(64, 4 * (os.cpu_count() or 1))
"""Most worker processes a command may start (each holds the data its tasks share)."""

DASK_TIMEOUT_S = 10.0
"""Seconds to wait for a Dask scheduler before giving up."""


def check_workers(workers: int | None, flag: str = "--workers") -> int:
    """
    The worker processes: ``None`` means every core; anything but an integer (``int`` or a numpy integer, not a
    bool or a float) in ``[1, WORKERS_MAX]`` is refused, naming ``flag``.

    >>> check_workers(2)
    2
    >>> check_workers(0, "workers")
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: workers must be an integer in [1, ...] (processes), got 0
    """
    if workers is None:
        return os.cpu_count() or 1
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or not 1 <= workers <= WORKERS_MAX:
        raise SkinrenderError(f"{flag} must be an integer in [1, {WORKERS_MAX}] (processes), got {workers!r}",
                              flag=flag_of(flag), role=flag.lstrip("-"))
    return int(workers)


def dask_client(dask):
    """
    A ``distributed.Client`` for a scheduler address (owned: the caller closes it) or the client given, as
    ``(client, owned)``; an address that cannot be reached within :data:`DASK_TIMEOUT_S` is a one-line error
    naming ``--dask``.
    """
    require("dask", "--dask")
    from distributed import Client

    if not isinstance(dask, Client):
        check_dask_address(dask)
        try:
            client = Client(dask, timeout=DASK_TIMEOUT_S)
        except (OSError, ValueError, TypeError, TimeoutError, MemoryError) as error:
            raise SkinrenderError(f"--dask: cannot reach a Dask scheduler at {dask!r} within {DASK_TIMEOUT_S:g} s "
                                  f"({type(error).__name__}: {' '.join(str(error).split())[:120]})",
                                  flag="--dask") from None
        try:
            client.wait_for_workers(1, timeout=DASK_TIMEOUT_S)
        except (TimeoutError, OSError) as error:
            client.close()
            raise SkinrenderError(f"--dask: the Dask scheduler at {dask} has no workers (none joined within "
                                  f"{DASK_TIMEOUT_S:g} s): start some (dask worker {dask})", flag="--dask") from error
        return client, True
    return dask, False


DASK_SCHEMES = ("tcp", "tls", "ws", "wss", "ucx", "inproc")
"""Address schemes a Dask scheduler listens on (``tcp`` when none is given)."""

_HANDSHAKE_BYTES_MAX = 1 << 16
"""Largest first message a Dask scheduler sends (its handshake: ~60 bytes of msgpack), bytes."""


def check_dask_address(address, flag: str = "--dask", timeout: float | None = None) -> str:
    """
    ``address`` checked to be a Dask scheduler before any work is sent to it: a one-line error naming ``flag``
    otherwise, within ``timeout`` s (default :data:`DASK_TIMEOUT_S`; never a hang, never "out of memory").

    A ``tcp://`` address (or ``host:port``) gets Dask's handshake: the connection is opened, a client's handshake
    sent, and the server's read — a scheduler sends one on every connection (its comm framing: an 8-byte length,
    the frame count and lengths, a msgpack map with ``python`` and ``pickle-protocol``). An HTTP server answers
    with ``HTTP/1.1 …`` (which Dask had read as an 8-byte length of ~3e18 bytes and ran out of memory allocating,
    or waited on past a minute); anything that says nothing within ``timeout`` is refused too. Other Dask schemes
    (``tls``, ``ws``, ``ucx``, ``inproc``) are left to the client's own timeout; any other scheme is refused.
    Returns the address.
    """
    import socket
    import struct
    import time

    from distributed.comm.addressing import parse_address, parse_host_port

    timeout = DASK_TIMEOUT_S if timeout is None else timeout
    text = str(address).strip() if isinstance(address, str) else ""
    if not text:
        raise SkinrenderError(f"{flag}: expected a Dask scheduler address (tcp://host:8786), got {address!r}",
                              flag=flag_of(flag), role=flag.lstrip("-"))
    try:
        scheme, location = parse_address(text, strict=False)
        host, port = parse_host_port(location, 8786) if scheme == "tcp" else (None, None)
    except (ValueError, TypeError) as error:
        raise SkinrenderError(f"{flag}: {text!r} is not a Dask scheduler address (tcp://host:8786): "
                              f"{' '.join(str(error).split())[:120]}", flag=flag) from None
    if scheme not in DASK_SCHEMES:
        raise SkinrenderError(f"{flag}: {text!r} is a {scheme}:// address, not a Dask scheduler's (schemes "
                              f"{', '.join(DASK_SCHEMES)}; e.g. tcp://host:8786)", flag=flag)
    if scheme != "tcp":
        return text
    deadline = time.monotonic() + timeout

    def receive(sock, count: int) -> bytes:
        data = b""
        while len(data) < count:
            sock.settimeout(max(deadline - time.monotonic(), 0.001))
            chunk = sock.recv(count - len(data))
            if not chunk:
                raise ConnectionError("the server closed the connection")
            data += chunk
        return data

    try:
        sock = socket.create_connection((host, port), timeout=timeout)
    except OSError as error:
        raise SkinrenderError(f"{flag}: cannot reach a Dask scheduler at {text!r} within {timeout:g} s (cannot "
                              f"connect: {' '.join((error.strerror or str(error)).split())[:100]})", flag=flag) from None
    refusal = None
    try:
        with sock:
            # Dask's handshake, then an empty line: a scheduler has closed its read by then (it reads the line
            # as the start of the next message, cut short when this probe closes); an HTTP server takes the
            # bytes for a malformed request and answers at once (HTTP/1.x 400), rather than waiting for more
            sock.sendall(_client_handshake() + b"\r\n\r\n")
            (size,) = struct.unpack("<Q", receive(sock, 8))
            if not 16 <= size <= _HANDSHAKE_BYTES_MAX:
                refusal = f"its first message is not Dask's ({_shown_bytes(struct.pack('<Q', size))}…)"
            elif not _is_dask_handshake(receive(sock, size)):
                refusal = "its first message is not Dask's handshake"
    except TimeoutError:
        refusal = f"no Dask handshake within {timeout:g} s (a Dask scheduler sends one on every connection)"
    except OSError as error:
        refusal = f"the connection failed ({' '.join((error.strerror or str(error)).split())[:100]})"
    if refusal is not None:
        raise SkinrenderError(f"{flag}: {text} is not a Dask scheduler: {refusal}", flag=flag)
    return text


def _client_handshake() -> bytes:
    """A Dask client's handshake in Dask's TCP framing (what ``distributed.comm`` sends on connecting)."""
    import pickle
    import struct
    import sys

    import msgpack

    frame = msgpack.dumps({"compression": None, "python": tuple(sys.version_info[:3]),
                           "pickle-protocol": pickle.HIGHEST_PROTOCOL}, use_bin_type=True)
    body = struct.pack("<QQ", 1, len(frame)) + frame
    return struct.pack("<Q", len(body)) + body


def _is_dask_handshake(body: bytes) -> bool:
    """Whether ``body`` (a message's frames, after its length) holds Dask's handshake: a frame count, the frames'
    lengths, and a msgpack map with ``python`` or ``pickle-protocol``."""
    import struct

    import msgpack

    (count,) = struct.unpack_from("<Q", body)
    if not 1 <= count <= 16 or len(body) < 8 * (count + 1):
        return False
    lengths = struct.unpack_from(f"<{count}Q", body, 8)
    if sum(lengths) != len(body) - 8 * (count + 1):
        return False
    start = 8 * (count + 1)
    for length in lengths:
        try:
            message = msgpack.loads(body[start:start + length], raw=False, strict_map_key=False)
        except Exception:  # noqa: BLE001 - not msgpack: not Dask's
            message = None
        if isinstance(message, dict) and ({"python", "pickle-protocol"} & set(map(str, message))):
            return True
        start += length
    return False


def _shown_bytes(data: bytes) -> str:
    """Bytes as a reader sees them: text where printable (``HTTP/1.1``), else hexadecimal."""
    text = data.decode("ascii", errors="replace")
    return repr(text) if text.isprintable() else data.hex()


def dask_name(dask) -> str | None:
    """
    The scheduler address of ``dask`` (an address or a ``distributed.Client``), ``None`` without one.

    >>> dask_name(None), dask_name("tcp://h:8786")
    (None, 'tcp://h:8786')
    """
    if dask is None or isinstance(dask, str):
        return dask
    return str(getattr(getattr(dask, "scheduler", None), "address", "a Dask client"))


def stop_pool(pool: ProcessPoolExecutor) -> None:
    """Stop a process pool at once (Ctrl-C, an error): its workers terminated, its queued work dropped."""
    for process in list((getattr(pool, "_processes", None) or {}).values()):
        process.terminate()
    # waiting is short once the workers are gone, and it frees the queues' named semaphores: a `spawn` pool's
    # resource tracker would otherwise warn of them on stderr when the command line exits at once (130)
    pool.shutdown(wait=True, cancel_futures=True)


_SHARED = None
"""A pool worker's copy of the data its tasks share (set once, by :func:`_start_worker`)."""


def _start_worker(shared, initializer: Callable | None, initargs: tuple) -> None:
    global _SHARED
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the parent's to handle: no traceback per worker
    _SHARED = shared
    if initializer is not None:
        initializer(*initargs)


def _with_shared(function: Callable, task):
    """``function(shared, task)`` in a pool worker, with the worker's copy of the shared data."""
    return function(_SHARED, task)


def map_tasks(function: Callable, tasks: Sequence, *, workers: int = 1, dask=None, shared=None,
        initializer: Callable | None = None, initargs: tuple = (), start: str | None = None, progress=None,
        label: str = "tasks", unit: str = "task", sizes: Sequence[int] | None = None,
        on_start: Callable[[], None] | None = None,
        on_result: Callable[[int, object], None] | None = None) -> list:
    """
    ``function(task)`` for every task (``function(shared, task)`` with ``shared``), results in task order.

    Parameters
    ----------
    function
        A picklable callable (a module-level function or a :func:`functools.partial` of one) for a pool or
        Dask; any callable for one worker.
    tasks
        The tasks (picklable for a pool or Dask).
    workers
        Processes; 1 (and no ``dask``) runs every task in this process, in order.
    dask
        A Dask scheduler address (``tcp://host:8786``) or a ``distributed.Client``: the tasks run there
        (``workers`` is not used).
    shared
        Data every task needs (sensor banks): sent once to each worker, passed as ``function``'s first
        argument; ``None``: ``function(task)``.
    initializer, initargs
        Called in each pool worker when it starts (after SIGINT is ignored there), e.g. to set a renderer up.
    start
        How pool workers start (:func:`multiprocessing.get_context`: ``"spawn"``, ``"fork"``); ``None``: the
        platform's default.
    progress
        A stream (``sys.stderr``) for the progress bar (a terminal) or the line saying the work started, or
        ``None``.
    label, unit
        The progress's label and the unit of ``sizes``.
    sizes
        Units of work per task (``None``: one each): the progress counts them.
    on_start
        Called once the tasks are under way (a pool's workers started): the caller's other work may run then;
        an exception it raises stops the workers and is raised here.
    on_result
        Called with ``(index, result)`` as each task finishes (in the order they finish).

    Returns
    -------
    list
        One result per task, in task order.

    Examples
    --------
    >>> from functools import partial
    >>> import operator
    >>> map_tasks(partial(operator.mul, 3), [5, 1, 4])
    [15, 3, 12]
    >>> map_tasks(operator.add, [1, 2], shared=10)
    [11, 12]
    """
    results: list = [None] * len(tasks)
    sizes = [1] * len(tasks) if sizes is None else list(sizes)
    bar = progress_bar(sum(sizes), label, progress, unit)

    def started() -> None:
        announce(progress, label, sum(sizes), unit)
        if on_start is not None:
            on_start()

    def store(index: int, result) -> None:
        results[index] = result
        bar.update(sizes[index])
        if on_result is not None:
            on_result(index, result)

    try:
        if dask is not None:
            _map_dask(dask, function, tasks, shared, started, store)
        elif workers == 1:
            started()
            for index, task in enumerate(tasks):
                store(index, function(task) if shared is None else function(shared, task))
        elif tasks:
            context = multiprocessing.get_context(start) if start is not None else None
            pool = ProcessPoolExecutor(min(workers, len(tasks)), mp_context=context, initializer=_start_worker,
                                       initargs=(shared, initializer, initargs))
            try:
                calls = [(function, task) if shared is None else (_with_shared, function, task) for task in tasks]
                _collect({pool.submit(*call): index for index, call in enumerate(calls)}, started, store)
            except BaseException:  # Ctrl-C or an error: stop the workers now and drop the queued tasks
                stop_pool(pool)
                raise
            pool.shutdown()
        else:
            started()
    finally:
        bar.close()
    return results


INTERRUPT_POLL_S = 0.2
"""How often, s, :func:`_collect` looks for a Ctrl-C that arrived while it waited (see :func:`_deferred_interrupt`)."""


@contextlib.contextmanager
def _deferred_interrupt():
    """
    Ctrl-C (SIGINT) while waiting on futures is noted, not raised, and ``interrupted()`` says whether it came.

    A KeyboardInterrupt raised inside ``concurrent.futures.wait`` can land while it holds some of the futures'
    locks (it takes them one by one), which are then never released: the pool's manager thread blocks on one of
    them and stopping the pool waits for ever. The caller raises KeyboardInterrupt itself between waits, where it
    holds no lock. Outside the main thread (where Python delivers signals) nothing changes.
    """
    previous = signal.getsignal(signal.SIGINT)
    # signals reach the main thread only; a handler of the caller's own, or SIGINT ignored, is left as it is
    if threading.current_thread() is not threading.main_thread() or previous is not signal.default_int_handler:
        yield lambda: False
        return
    came = threading.Event()
    signal.signal(signal.SIGINT, lambda signum, frame: came.set())
    try:
        yield came.is_set
    finally:
        signal.signal(signal.SIGINT, previous)


def _collect(futures: dict[Future, int], started: Callable[[], None], store: Callable[[int, object], None]) -> None:
    """Each future's result stored under its task's index as it finishes (after ``started()``); Ctrl-C raises
    KeyboardInterrupt between waits, holding no future's lock."""
    started()  # the workers are started and busy
    pending = set(futures)
    with _deferred_interrupt() as interrupted:
        while pending:
            done, pending = wait(pending, timeout=INTERRUPT_POLL_S, return_when=FIRST_COMPLETED)
            if interrupted():
                raise KeyboardInterrupt
            for future in done:
                store(futures[future], future.result())


def _map_dask(dask, function: Callable, tasks: Sequence, shared, started, store) -> None:
    client, own = dask_client(dask)
    executor = client.get_executor(pure=False)
    try:
        # hash=False: a key of its own; with the content's hash, two clients scattering the same data (two runs on
        # one scheduler) shared one key, and the first to release it cancelled the other's tasks (CancelledError)
        arguments = () if shared is None else (client.scatter([shared], broadcast=True, hash=False)[0],)
        try:
            _collect({executor.submit(function, *arguments, task): index for index, task in enumerate(tasks)},
                     started, store)
        except BaseException:
            executor.shutdown(wait=False)  # cancels what is left
            raise
    finally:
        if own:
            client.close()


def __getattr__(name: str):
    """``map``: the deprecated name of :func:`map_tasks` (it shadowed the builtin), with a notice."""
    if name == "map":
        import warnings

        warnings.warn("skinrender.execution.map is deprecated: use skinrender.execution.map_tasks",
                      DeprecationWarning, stacklevel=2)
        return map_tasks
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
