"""Where the cases of a batch run: in this process, on a pool of local worker processes, or
on a dask.distributed cluster. Every executor calls ``on_row(row)`` once per case, in the
order rows complete, and never loses or duplicates a case.

Local pool
    One worker process per core by default. Each worker builds its runner (solvers) once and
    receives *chunks*: runs of consecutive cases, so that each case warm-starts from its
    neighbour. Each worker has its own pipe, and reports which case it starts before it
    runs it. A worker that dies (a crash in native code, an out-of-memory kill, SIGKILL) is
    replaced; the rest of its chunk is queued again, and the case it was running is retried
    on its own, up to ``max_attempts`` times, after which it becomes a row with status
    ``"worker_lost"``. Rows that arrived before the death are kept, so nothing is run twice
    to completion and no row is written twice.
Dask
    Chunks are submitted as tasks to a running scheduler (``--scheduler ADDRESS``); each
    dask worker keeps its runners between tasks. The scheduler retries a task whose worker
    died; a chunk that still fails (``KilledWorker``) is split into single cases, and a
    single case that fails that way becomes a ``"worker_lost"`` row.
"""

from __future__ import annotations

import contextlib
import ctypes
import hashlib
import json
import multiprocessing as mp
import os
import pickle
import signal
import sys
import threading
import time
import traceback
from collections import deque
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field
from multiprocessing.connection import Connection, wait
from typing import Any

from cable_ocp.batch.cases import Case
from cable_ocp.batch.kinds import RUNNERS, Runner
from cable_ocp.numerics import interrupt
from cable_ocp.status import Status

OnRow = Callable[[dict[str, Any]], None]

#: a worker's exit code when its batch is stopped (as the command line's, see docs/cli.md)
EXIT_INTERRUPTED = 130
#: linux/prctl.h: the signal a process gets when its parent dies
PR_SET_PDEATHSIG = 1


@dataclass
class RunnerSpec:
    """What a worker needs to build its runner: the kind, the base problem and options.

    Picklable (it travels to worker processes and dask workers). :meth:`make` builds the
    runner; subclasses may wrap it (the tests inject faults this way).
    """

    kind: str
    data: dict[str, Any]
    options: dict[str, Any] = field(default_factory=dict)

    def key(self) -> str:
        """A key under which a worker caches the runner between tasks."""
        text = json.dumps([type(self).__module__, type(self).__qualname__, asdict(self)],
                          sort_keys=True, default=str)
        return hashlib.sha1(text.encode()).hexdigest()

    def make(self) -> Runner:
        """A fresh runner."""
        return RUNNERS[self.kind](self.data, self.options)


def error_row(case: Case, status: str, message: str) -> dict[str, Any]:
    """The row of a case that produced no result of its own.

    Parameters
    ----------
    case : Case
        The case; its index, identifier and overrides go into the row.
    status : str
        The row's status: ``"error"`` (an exception, or the runner could not be built) or
        ``"worker_lost"`` (its worker process died too often).
    message : str
        One line saying what went wrong.
    """
    return {"case": case.index, "case_id": case.case_id, "status": Status(status),
            "message": message, "wall_time_s": None, **case.overrides}


def _safe_run(runner: Runner, case: Case) -> dict[str, Any]:
    """``runner.run(case)``, with an unexpected exception turned into an ``"error"`` row."""
    try:
        return runner.run(case)
    except Exception as exc:  # noqa: BLE001 - one case's bug must not stop the batch
        interrupt.reraise_interruption(exc)  # a Ctrl-C stops the batch, it is not a row
        last = traceback.extract_tb(exc.__traceback__)[-1]
        return error_row(case, "error", f"{type(exc).__name__}: {exc} "
                                        f"({os.path.basename(last.filename)}:{last.lineno})")


# --------------------------------------------------------------------------------------
# In this process
# --------------------------------------------------------------------------------------

def run_serial(spec: RunnerSpec, chunks: Sequence[Sequence[Case]], on_row: OnRow) -> None:
    """Run every chunk here, in order (``workers = 0``).

    Parameters
    ----------
    spec : RunnerSpec
        The runner's kind, base problem and options; one runner is built here for all chunks.
    chunks : sequence of sequence of Case
        Runs of consecutive cases (each case warm-starts from the one before).
    on_row : callable
        ``on_row(row)``, called once per case with its result row (a dict: ``case``,
        ``case_id``, ``status``, ``message``, ``wall_time_s``, the overrides, ...), in the
        order rows complete.
    """
    runner = spec.make()
    for chunk in chunks:
        for case in chunk:
            on_row(_safe_run(runner, case))


# --------------------------------------------------------------------------------------
# Local worker processes
# --------------------------------------------------------------------------------------

def _worker_main(conn: Connection, spec: RunnerSpec, parent: int) -> None:
    """A worker: build the runner once, then run chunks until told to stop (None).

    It leaves interruptions to its parent: SIGINT is ignored (a Ctrl-C at the terminal
    reaches the whole process group; the parent stops the batch and the workers), SIGTERM
    ends it at once, and a Ctrl-C that IPOPT caught ends it quietly, without a row. It
    exits when its parent dies (:func:`_exit_with_parent`), even in the middle of a case.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if hasattr(signal, "pthread_sigmask"):  # blocked by the parent while it started us
        signal.pthread_sigmask(signal.SIG_UNBLOCK, interrupt.SIGNALS)
    _exit_with_parent(parent)
    try:
        try:
            runner: Runner | None = spec.make()
            why = ""
        except Exception as exc:  # noqa: BLE001 - reported per case below
            interrupt.reraise_interruption(exc)
            runner, why = None, f"{type(exc).__name__}: {exc}"
        while True:
            try:
                chunk = conn.recv()
            except (EOFError, OSError):
                return
            if chunk is None:
                return
            for case in chunk:
                conn.send(("start", case.index))
                conn.send(("row", _safe_run(runner, case) if runner is not None
                           else error_row(case, "error", f"building the runner failed: {why}")))
    except (KeyboardInterrupt, BrokenPipeError):  # the batch is being stopped: no traceback
        os._exit(EXIT_INTERRUPTED)


#: how often a worker checks that its parent is alive where the kernel cannot tell it, s
PARENT_POLL_S = 0.5


def _exit_with_parent(parent: int) -> None:
    """End this worker process when the process ``parent`` dies: on Linux the kernel sends
    SIGKILL (``prctl(PR_SET_PDEATHSIG)``); everywhere a daemon thread polls
    :func:`os.getppid` every :data:`PARENT_POLL_S` (a parent gone means a new parent pid).
    Without this a batch killed with ``kill -9`` left its workers blocked for ever on their
    pipes (each inherits the other pipes' parent ends, so no EOF arrives).

    Parameters
    ----------
    parent : int
        The batch process's pid, taken before the worker started.
    """
    if sys.platform.startswith("linux"):
        with contextlib.suppress(OSError, AttributeError):
            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    first = os.getppid()  # the batch, or a fork server that started this worker for it

    def gone() -> bool:
        if os.getppid() != first:  # orphaned: adopted by another process
            return True
        if first == parent:
            return False
        try:
            os.kill(parent, 0)
        except ProcessLookupError:
            return True
        except OSError:  # exists, not ours to signal
            return False
        return False

    if gone():  # the batch died before the prctl
        os._exit(EXIT_INTERRUPTED)

    def watch() -> None:
        while not gone():
            time.sleep(PARENT_POLL_S)
        os._exit(EXIT_INTERRUPTED)

    threading.Thread(target=watch, name="cable_ocp-parent-watch", daemon=True).start()


class _Worker:
    def __init__(self, ctx: Any, spec: RunnerSpec) -> None:
        self.conn, child = ctx.Pipe(duplex=True)
        self.proc = ctx.Process(target=_worker_main, args=(child, spec, os.getpid()),
                                daemon=True)
        with interrupt.signals_blocked():  # no Ctrl-C traceback from a half-started worker
            self.proc.start()
        child.close()
        self.chunk: list[Case] = []      # cases sent and not yet reported as rows
        self.running: int | None = None  # the case it reported starting

    @property
    def idle(self) -> bool:
        return not self.chunk

    def stop(self) -> None:
        try:
            self.conn.send(None)
        except (OSError, BrokenPipeError):
            pass

    def kill(self) -> None:
        if self.proc.is_alive():
            self.proc.kill()
        self.proc.join(timeout=5)
        self.conn.close()


def run_local(spec: RunnerSpec, chunks: Sequence[Sequence[Case]], on_row: OnRow,
              workers: int, max_attempts: int = 2, start_method: str | None = None) -> None:
    """Run the chunks on ``workers`` local processes (see the module docstring).

    Parameters
    ----------
    spec : RunnerSpec
        The runner's kind, base problem and options; each worker process builds its own runner
        from it once.
    chunks : sequence of sequence of Case
        Runs of consecutive cases, each sent whole to one worker; empty chunks are skipped.
    on_row : callable
        ``on_row(row)``, called once per case with its result row (a dict: ``case``,
        ``case_id``, ``status``, ``message``, ``wall_time_s``, the overrides, ...), in the
        order rows complete.
    workers : int
        Number of worker processes (at least 1, at most one per chunk).
    max_attempts : int
        How many times a case may kill its worker before it becomes a ``"worker_lost"``
        row (default 2: retried once, alone).
    start_method : str, optional
        ``"fork"`` (default where available: workers inherit the loaded modules, no
        re-import) or ``"spawn"``.
    """
    method = start_method or ("fork" if "fork" in mp.get_all_start_methods()
                              and sys.platform != "darwin" else "spawn")
    ctx = mp.get_context(method)
    queue: deque[list[Case]] = deque(list(c) for c in chunks if c)
    attempts: dict[int, int] = {}
    pool = [_Worker(ctx, spec) for _ in range(max(1, min(workers, len(queue))))]
    try:
        while queue or any(not w.idle for w in pool):
            for w in pool:
                if w.idle and queue:
                    w.chunk = queue.popleft()
                    w.running = None
                    w.conn.send(w.chunk)
            ready = wait([w.conn for w in pool if not w.idle]
                         + [w.proc.sentinel for w in pool if not w.idle])
            for w in list(pool):
                if w.idle:
                    continue
                died = w.proc.sentinel in ready and not w.proc.is_alive()
                # read everything the worker sent before it (maybe) died
                try:
                    while w.conn.poll():
                        kind, payload = w.conn.recv()
                        if kind == "start":
                            w.running = payload
                        else:  # "row": the chunk shrinks; empty = idle
                            w.chunk = [c for c in w.chunk if c.index != payload["case"]]
                            w.running = None
                            on_row(payload)
                except (EOFError, OSError, pickle.UnpicklingError, ValueError):
                    died = True  # EOF or a message cut short by the death
                if died:
                    w.kill()
                    _recover(w, queue, attempts, max_attempts, on_row)
                    pool[pool.index(w)] = _Worker(ctx, spec)
    except BaseException:  # interrupted (Ctrl-C, SIGTERM) or failed: stop every worker now
        for w in pool:
            w.kill()
        raise
    for w in pool:
        w.stop()
    for w in pool:
        w.proc.join(timeout=2)
        w.kill()


def _recover(w: _Worker, queue: deque[list[Case]], attempts: dict[int, int],
             max_attempts: int, on_row: OnRow) -> None:
    """A worker died: retry the case it was running on its own (or give it up), and queue
    the rest of its chunk again."""
    code = w.proc.exitcode
    rest = list(w.chunk)
    crashed = next((c for c in rest if c.index == w.running), None)
    if crashed is None and rest:  # died before reporting a start: the first case
        crashed = rest[0]
    if crashed is not None:
        rest.remove(crashed)
        attempts[crashed.index] = attempts.get(crashed.index, 0) + 1
        if attempts[crashed.index] >= max_attempts:
            on_row(error_row(crashed, "worker_lost",
                             f"the worker process died {attempts[crashed.index]} times while "
                             f"running this case (last exit code {code}); given up"))
        else:
            queue.appendleft([crashed])
    if rest:
        queue.append(rest)
    w.chunk = []


# --------------------------------------------------------------------------------------
# dask.distributed
# --------------------------------------------------------------------------------------

_DASK_RUNNERS: dict[str, Runner] = {}


def _dask_chunk(spec: RunnerSpec, chunk: list[Case]) -> list[dict[str, Any]]:
    """A dask task: run a chunk with the worker's cached runner."""
    key = spec.key()
    if key not in _DASK_RUNNERS:
        _DASK_RUNNERS[key] = spec.make()
    runner = _DASK_RUNNERS[key]
    return [_safe_run(runner, case) for case in chunk]


def run_dask(spec: RunnerSpec,
             chunks: Sequence[Sequence[Case]] | Callable[[int], Sequence[Sequence[Case]]],
             on_row: OnRow, scheduler: Any, max_attempts: int = 2) -> None:
    """Run the chunks on a dask.distributed cluster.

    Two phases. First every chunk runs as a task (dask itself retries a task whose worker
    died, up to its ``distributed.scheduler.allowed-failures``). A chunk that still failed
    that way (``KilledWorker``) goes to the second phase, where its cases run one at a
    time, alone on the cluster: a case that then kills its worker ``max_attempts`` times is
    certainly the culprit and becomes a ``"worker_lost"`` row, while the innocent cases that
    shared its chunk or its worker are solved.

    Parameters
    ----------
    spec : RunnerSpec
        The runner's kind, base problem and options; each dask worker builds (and keeps) one
        runner per spec (:meth:`RunnerSpec.key`). Must be picklable.
    chunks : sequence of case runs, or callable
        The chunks, or ``chunks(n)`` that makes them for the cluster's ``n`` worker
        threads (known once connected).
    on_row : callable
        ``on_row(row)``, called once per case with its result row (a dict: ``case``,
        ``case_id``, ``status``, ``message``, ``wall_time_s``, the overrides, ...), in the
        order rows complete.
    scheduler : str or distributed.Client
        The scheduler's address (``tcp://host:8786``) or a connected client (left open;
        a client made from an address is closed at the end).
    max_attempts : int
        In the second phase, how many times a case may kill its worker before it becomes
        a ``"worker_lost"`` row (default 2).
    """
    try:
        from distributed import Client, as_completed
        from distributed.scheduler import KilledWorker
    except ImportError:  # pragma: no cover - depends on the installation
        from cable_ocp.errors import CableOCPError

        raise CableOCPError("--scheduler needs dask.distributed: pip install -e '.[cluster]'"
                            ) from None
    own = not hasattr(scheduler, "submit")
    client = Client(scheduler, timeout="20s") if own else scheduler
    suspects: list[Case] = []
    try:
        if callable(chunks):
            workers = client.scheduler_info().get("workers", {})
            chunks = chunks(max(1, sum(int(w.get("nthreads", 1)) for w in workers.values())))
        futures = {client.submit(_dask_chunk, spec, list(c), pure=False): list(c)
                   for c in chunks if c}
        for fut in as_completed(list(futures)):
            chunk = futures.pop(fut)
            try:
                rows = fut.result()
            except KilledWorker:
                suspects += chunk
                continue
            except Exception as exc:  # noqa: BLE001 - a task error is a row, not a stop
                rows = [error_row(c, "error", f"{type(exc).__name__}: {exc}") for c in chunk]
            for row in rows:
                on_row(row)
        for case in suspects:  # alone on the cluster, one after the other
            for attempt in range(1, max_attempts + 1):
                try:
                    row = client.submit(_dask_chunk, spec, [case], pure=False).result()[0]
                    break
                except KilledWorker as exc:
                    row = error_row(case, "worker_lost",
                                    f"dask workers died {attempt} times running this case "
                                    f"alone: {exc}")
                except Exception as exc:  # noqa: BLE001
                    row = error_row(case, "error", f"{type(exc).__name__}: {exc}")
                    break
            on_row(row)
    finally:
        if own:
            client.close()
