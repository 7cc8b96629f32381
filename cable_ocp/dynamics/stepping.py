"""The chunked time loop shared by the axial and planar models.

Each model builds a CasADi function that advances one integration step;
:func:`chunk_functions` folds it over ``every`` steps per output sample and maps that over
``m`` samples (``mapaccum``). The loop below calls it chunk by chunk (no Python per time
step), keeps the good samples, and stops at the first sample whose scaled Newton residual
exceeds the failure tolerance or whose state is not finite.

The accumulator row layout is the models': the state (and any scheme history) in rows
``[0, off)``, then the residual at ``off`` and the slack time at ``off + 2``.

Step halving (``refine``): a sample whose implicit steps do not converge (an element going
taut within a step, the snap that ends a slack spell, is the usual cause) is computed
again from the last good state with the step halved, then quartered, ... up to
:data:`MAX_HALVINGS` times (the same sample times: 2^k times the steps of dt / 2^k), and
the run goes on with the model's own step from the next sample. Only when the finest step
fails too does the run end as ``"failed"``. The count of the samples so refined is in
``stats["refined_samples"]``.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.numerics import interrupt

__all__ = ["MAX_CHUNKS", "MAX_HALVINGS", "chunk_functions", "halving", "run_chunks"]

#: at most this many progress calls (chunks) per run, in every model
MAX_CHUNKS = 200
#: at most this many halvings of the step for a sample whose steps fail (dt / 2^6)
MAX_HALVINGS = 6


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


def halving(step_for: Callable[[float], ca.Function], dt: float, every: int
            ) -> Callable[[int], ca.Function]:
    """The ``refine`` of :func:`run_chunks`: ``refine(k)`` advances one output sample in
    2^k steps of dt / 2^k (``step_for(dt / 2^k)`` folded; built on first use and kept).

    Parameters
    ----------
    step_for : callable
        ``step_for(h)``: the model's one-step function ``(acc, t) -> acc`` for a step h, s.
    dt : float
        The model's time step, s.
    every : int
        Steps of dt per output sample.
    """
    built: dict[int, ca.Function] = {}

    def refine(level: int) -> ca.Function:
        if level not in built:
            built[level] = step_for(dt / 2**level).fold(every * 2**level).mapaccum(
                "halved", 1)
        return built[level]

    return refine


def run_chunks(chunk_fn: Callable[[int], ca.Function], acc: np.ndarray, n_out: int,
               per_chunk: int, every: int, dt: float, off: int, n_state: int,
               tol_fail: float, stop_on_slack: bool,
               progress: Callable[[int, int], None] | None,
               refine: Callable[[int], ca.Function] | None = None,
               stats: dict[str, Any] | None = None,
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
    refine : callable or None
        ``refine(k)``: the function advancing one sample in 2^k steps of dt / 2^k (the
        step halving of the module docstring); None: no halving, a failed step ends
        the run.
    stats : dict or None
        Filled with ``refined_samples`` (samples computed with a halved step) and
        ``finest_step_s`` (the smallest step used, s).
    """
    times: list[float] = []
    states: list[np.ndarray] = []
    status, message = "solved", ""
    done = 0
    refined, finest = 0, dt
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
            if bad.size and refine is not None:
                base = res[:, k_good - 1].copy() if k_good > 0 else acc
                fixed = _halved_sample(refine, base, done + k_good, every, dt, off, n_state,
                                       tol_fail)
                if fixed is not None:
                    acc, level = fixed
                    refined += 1
                    finest = min(finest, dt / 2**level)
                    states.append(acc[:n_state].copy())
                    times.append((done + k_good + 1) * every * dt)
                    done += k_good + 1
                    if progress is not None:
                        progress(done * every, n_out * every)
                    if stop_on_slack and np.isfinite(acc[off + 2]):
                        break
                    continue
            if bad.size:
                status = "failed"
                message = (f"the implicit step did not converge before t = "
                           f"{(done + k_good + 1) * every * dt:.6g} s (scaled residual "
                           f"{rcol[k_good]:.3g} > {tol_fail:.3g}"
                           + (f", also with the step halved {MAX_HALVINGS} times"
                              if refine is not None else "")
                           + "); the history stops at the last good sample: try a smaller "
                           "simulation.time_step")
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
    if stats is not None:
        stats.update(refined_samples=refined, finest_step_s=finest)
    return times, states, acc, status, message, time.perf_counter() - t0


def _halved_sample(refine: Callable[[int], ca.Function], acc: np.ndarray, sample: int,
                   every: int, dt: float, off: int, n_state: int, tol_fail: float
                   ) -> tuple[np.ndarray, int] | None:
    """The accumulator after output sample ``sample`` (0-based) computed from ``acc`` with
    the step halved k = 1 .. :data:`MAX_HALVINGS` times (the first k that converges), and
    that k; None when every k fails."""
    t_start = sample * every * dt
    for level in range(1, MAX_HALVINGS + 1):
        sub = dt / 2**level
        tgrid = t_start + np.arange(every * 2**level) * sub
        res = np.asarray(refine(level)(acc, tgrid.reshape(1, -1))).reshape(-1)
        if res[off] <= tol_fail and np.all(np.isfinite(res[:n_state])):
            return res, level
    return None
