"""The chunked time loop shared by the axial and planar models.

Each model builds a CasADi function that advances one integration step;
:func:`chunk_functions` folds it over ``every`` steps per output sample and maps that over
``m`` samples (``mapaccum``). The loop below calls it chunk by chunk (no Python per time
step), keeps the good samples, and stops at the first sample whose scaled Newton residual
exceeds the failure tolerance or whose state is not finite.

The accumulator row layout is the models': the state (and any scheme history) in rows
``[0, off)``, then the residual at ``off`` and the slack time at ``off + 2``.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import casadi as ca
import numpy as np

from cable_ocp.numerics import interrupt

__all__ = ["MAX_CHUNKS", "chunk_functions", "run_chunks"]

#: at most this many progress calls (chunks) per run, in every model
MAX_CHUNKS = 200


def chunk_functions(step: ca.Function, every: int, n_out: int
                    ) -> tuple[Callable[[int], ca.Function], int]:
    """``(chunk_fn, per_chunk)`` for a run of ``n_out`` output samples: ``chunk_fn(m)``
    advances m samples of ``every`` steps each (``step`` folded over a sample, then
    ``mapaccum``'d over m; built on first use for each m and kept), and ``per_chunk``
    samples per call keep the calls (and progress reports) to at most :data:`MAX_CHUNKS`.

    Parameters
    ----------
    step : casadi.Function
        One integration step ``(acc, t) -> acc``.
    every : int
        Steps per output sample.
    n_out : int
        Output samples of the run.
    """
    macro = step.fold(every)
    per_chunk = max(1, math.ceil(n_out / MAX_CHUNKS))
    chunks: dict[int, ca.Function] = {}

    def chunk_fn(m: int) -> ca.Function:
        if m not in chunks:
            chunks[m] = macro.mapaccum("chunk", m)
        return chunks[m]

    return chunk_fn, per_chunk


def run_chunks(chunk_fn: Callable[[int], ca.Function], acc: np.ndarray, n_out: int,
               per_chunk: int, every: int, dt: float, off: int, n_state: int,
               tol_fail: float, stop_on_slack: bool,
               progress: Callable[[int, int], None] | None
               ) -> tuple[list[float], list[np.ndarray], np.ndarray, str, str, float]:
    """Advance ``n_out`` output samples from ``acc``.

    Returns ``(times, states, acc, status, message, wall)``: the sample times (s) and
    states (the first ``n_state`` rows) after the start, the last good accumulator,
    ``"solved"``, ``"failed"`` or ``"interrupted"`` (a Ctrl-C: the samples finished are
    kept) with its message, and the wall time of the loop (s).

    Parameters
    ----------
    chunk_fn : callable
        ``chunk_fn(m)``: the function advancing m samples (mapaccum).
    acc : ndarray
        The accumulator: state (and history) rows, then the residual at ``off``.
    n_out : int
        Samples to advance.
    per_chunk : int
        Samples per call.
    every : int
        Steps per sample.
    dt : float
        Time step, s.
    off : int
        Row of the residual in ``acc``.
    n_state : int
        Rows of the state.
    tol_fail : float
        Largest acceptable scaled residual (-).
    stop_on_slack : bool
        Stop after the chunk in which slack first occurs.
    progress : callable or None
        ``progress(done, total)`` (steps).
    """
    times: list[float] = []
    states: list[np.ndarray] = []
    status, message = "solved", ""
    done = 0
    t0 = time.perf_counter()
    try:
        while done < n_out:
            m = min(per_chunk, n_out - done)
            tgrid = (done * every + np.arange(m * every)) * dt
            res = np.asarray(chunk_fn(m)(acc, tgrid.reshape(1, -1)))
            rcol = res[off, :]
            bad = np.where(~(rcol <= tol_fail)
                           | ~np.all(np.isfinite(res[:n_state, :]), axis=0))[0]
            k_good = int(bad[0]) if bad.size else m
            for j in range(k_good):
                states.append(res[:n_state, j].copy())
                times.append((done + j + 1) * every * dt)
            if bad.size:
                status = "failed"
                message = (f"the implicit step did not converge before t = "
                           f"{(done + k_good + 1) * every * dt:.6g} s (scaled residual "
                           f"{rcol[k_good]:.3g} > {tol_fail:.3g}); the history stops at the "
                           "last good sample: try a smaller simulation.time_step")
                if k_good > 0:
                    acc = res[:, k_good - 1].copy()
                break
            acc = res[:, -1].copy()
            done += m
            if progress is not None:
                progress(done * every, n_out * every)
            if stop_on_slack and np.isfinite(acc[off + 2]):
                break
    except (KeyboardInterrupt, Exception) as exc:  # a Ctrl-C: keep the samples finished
        if not interrupt.is_interruption(exc):
            raise
        n_ok = min(len(states), len(times))  # the signal may fall between the appends
        del states[n_ok:], times[n_ok:]
        status = "interrupted"
        message = (f"interrupted after {len(times) * every * dt:.6g} s of simulated time; "
                   "the history stops at the last sample finished")
    return times, states, acc, status, message, time.perf_counter() - t0
