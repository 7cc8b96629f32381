"""Benchmark of load-case batches: De Zoysa's cable over psi0 x current speed, the same cases
solved bare in this process (a SolveSession: build once, warm starts, no batch machinery)
and as batches on 1 and 2 local workers, in one run.

One untimed pass builds the solvers' functions; then the bare loop (a new SolveSession,
as each batch worker starts one) and each batch run ``repeats`` times, the fastest
counted. The batch on one worker is compared with the bare warm loop two ways: the
difference of their wall times per case (everything the batch adds, its cases' own
run-to-run spread included), and the machinery's own share, wall time minus the cases'
own run time (each row's ``wall_time_s``): the worker process, pipes, rows written as
they arrive. Speed-up = batch time on one worker / batch time on two. The load average
is recorded: the speed-up needs the cores to be free. So is the machine's own ceiling
(:func:`machine_ceiling`): the bare loop in one process, then in two at once, with no batch
machinery; the batch's parallel efficiency is its speed-up over that ceiling.
"""

from __future__ import annotations

import math
import os
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from cable_ocp.batch import build_cases, parse_range, run_batch
from cable_ocp.scene import read_problem, scene_from_dict
from cable_ocp.scene.files import apply_overrides
from cable_ocp.statics.solver import SolveSession

SCENE = Path(__file__).resolve().parents[2] / "problems" / "dezoysa_sea_buggy.toml"


def run(n_angles: int = 20, n_speeds: int = 10, workers: tuple[int, ...] = (1, 2),
        progress: Callable[[str], None] | None = None, repeats: int = 2,
        dask_workers: int = 0) -> dict[str, Any]:
    """Time the bare loop and the batches (the fastest of ``repeats`` runs each, after one
    untimed pass that builds the solvers); with ``dask_workers`` also on a dask.distributed
    LocalCluster of that many single-threaded worker processes (its workers' first batch,
    which builds their solvers, untimed). Returns rows and the derived figures.

    Parameters
    ----------
    n_angles : int
        Number of psi0 values, evenly spaced over 0-140 deg (default 20).
    n_speeds : int
        Number of current speeds, evenly spaced over 0.4-1.3 m/s (default 10); the batch
        has ``n_angles * n_speeds`` cases.
    workers : tuple of int
        Local worker counts to time the batch on (default (1, 2)); the speed-up and
        overhead figures need 1 and 2.
    progress : callable, optional
        ``progress(text)``, called with what starts next; None (default): none.
    repeats : int
        Timed runs of the bare loop and of each batch (default 2); the fastest counts.
    dask_workers : int
        Number of single-threaded workers of a dask LocalCluster to time the batch on too;
        0 (default): no dask run.
    """
    ranges = [parse_range(f"environment.current.speed=0.4:1.3:{n_speeds}"),
              parse_range(f"layout.psi0_deg=0:140:{n_angles}")]
    data = read_problem(SCENE)
    cases = build_cases(ranges)
    n = len(cases)
    if progress:
        progress(f"bare loop, {n} cases")
    scenes = [scene_from_dict(apply_overrides(data, c.overrides)) for c in cases]
    warm_up = SolveSession()
    for sc in scenes:  # builds the solvers' functions (not timed)
        warm_up.solve(sc)
    bare = math.inf
    for _ in range(repeats):  # a new session each time: the batch's workers start one too
        session = SolveSession()
        t0 = time.perf_counter()
        for sc in scenes:
            session.solve(sc)
        bare = min(bare, time.perf_counter() - t0)
    rows = [{"run": "bare warm loop (this process)", "workers": 0, "wall_s": bare,
             "per_case_ms": 1e3 * bare / n, "solve_ms": 1e3 * bare / n, "speedup": None,
             "overhead_ms": None, "solved": None}]
    if progress:
        progress("the machine's ceiling: the bare loop in one process, then in two at once")
    ceiling = machine_ceiling(scenes, repeats)
    times: dict[tuple[str, int], float] = {}
    solve: dict[tuple[str, int], float] = {}

    def fastest(label: str, key: tuple[str, int], **kw: Any) -> None:
        """Run the batch ``repeats`` times; keep the fastest run's wall and case times."""
        times[key] = math.inf
        for _ in range(repeats):
            with tempfile.TemporaryDirectory() as tmp:
                t0 = time.perf_counter()
                res = run_batch(data, ranges=ranges, out=Path(tmp) / "b", **kw)
                wall = time.perf_counter() - t0
            if wall < times[key]:
                times[key], solve[key] = wall, sum(r["wall_time_s"] for r in res.rows)
                solved = sum(r["status"] == "solved" for r in res.rows)
        w, one = key[1], times.get(("local", 1))
        rows.append({"run": label, "workers": w, "wall_s": times[key],
                     "per_case_ms": 1e3 * times[key] / n, "solve_ms": 1e3 * solve[key] / n,
                     "speedup": None if one is None else one / times[key],
                     "overhead_ms": 1e3 * (times[key] * w - solve[key]) / n,
                     "solved": solved})

    for w in workers:
        if progress:
            progress(f"batch on {w} worker(s)")
        fastest(f"batch, {w} local worker(s)", ("local", w), workers=w)
    if dask_workers:
        if progress:
            progress(f"batch on a dask LocalCluster of {dask_workers} worker(s)")
        from distributed import Client, LocalCluster

        with LocalCluster(n_workers=dask_workers, threads_per_worker=1, processes=True,
                          dashboard_address=None) as cluster, Client(cluster) as client:
            run_batch(data, ranges=ranges, scheduler=client)  # workers build (not timed)
            fastest(f"batch, dask LocalCluster, {dask_workers} worker(s)",
                    ("dask", dask_workers), scheduler=client)
    one, two = times.get(("local", 1)), times.get(("local", 2))
    one_solve = solve.get(("local", 1), 0.0)
    summary = {
        "cases": n,
        "load_average": list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
        "cpu_count": os.cpu_count(),
        "bare_per_case_ms": 1e3 * bare / n,
        # what the machinery adds per case on one worker: wall time minus the cases' own
        # run time (process start, pipes, rows written, bookkeeping)
        "overhead_per_case_ms": None if one is None else 1e3 * (one - one_solve) / n,
        "overhead_fraction": None if one is None else (one - one_solve) / bare,
        # the cases' own run time in the batch against the bare loop (warm starts intact)
        "solve_in_batch_per_case_ms": None if one is None else 1e3 * one_solve / n,
        "difference_to_bare_per_case_ms": None if one is None else 1e3 * (one - bare) / n,
        "speedup_2_workers": None if one is None or two is None else one / two,
        # what two processes of the bare loop reach together on this machine (no batch
        # machinery): the speed-up no 2-worker batch can beat here
        "ceiling_2_processes": ceiling,
        "efficiency_vs_ceiling": None if one is None or two is None or not ceiling
        else one / two / ceiling,
    }
    return {"rows": rows, "summary": summary}


def _bare_child(scenes: list[Any], conn: Any) -> None:
    """A child process: one untimed pass (builds), then the timed bare loop; sends the
    wall time (s)."""
    s = SolveSession()
    for sc in scenes:
        s.solve(sc)
    s = SolveSession()
    t0 = time.perf_counter()
    for sc in scenes:
        s.solve(sc)
    conn.send(time.perf_counter() - t0)
    conn.close()


def machine_ceiling(scenes: list[Any], repeats: int = 2) -> float | None:
    """The 2-process speed-up this machine allows: the bare warm loop over ``scenes`` in one
    child process, then in two at once (each the whole loop), the fastest of ``repeats``;
    2 x (time alone) / (time of the pair). 2 on two free, independent cores; less where
    the cores share a physical core, caches or memory bandwidth, or where other jobs run.
    None where processes cannot be forked.

    Parameters
    ----------
    scenes : list of Scene
        The statics scenes of the loop, solved in order by one SolveSession per process
        (one untimed pass first, then the timed one).
    repeats : int
        Number of runs alone and as a pair (default 2, at least 1); the fastest of each
        counts.
    """
    import multiprocessing as mp

    if "fork" not in mp.get_all_start_methods():
        return None
    ctx = mp.get_context("fork")

    def together(k: int) -> float:
        pipes, procs = [], []
        for _ in range(k):
            a, b = ctx.Pipe(duplex=False)
            p = ctx.Process(target=_bare_child, args=(scenes, b), daemon=True)
            p.start()
            b.close()
            pipes.append(a)
            procs.append(p)
        times = [a.recv() for a in pipes]
        for p in procs:
            p.join()
        return max(times)

    alone = min(together(1) for _ in range(max(1, repeats)))
    pair = min(together(2) for _ in range(max(1, repeats)))
    return 2.0 * alone / pair
