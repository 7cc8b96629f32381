"""Benchmark of load-case batches: De Zoysa's cable over psi0 x current speed, the same cases
solved bare in this process (a SolveSession: build once, warm starts, no batch machinery)
and as batches on 1 and 2 local workers, in one run.

The bare loop runs twice and the second pass is timed: its solvers are built, so it is
the bare warm solve the batch is compared with. Per-case overhead = (batch wall time on
one worker - bare wall time) / cases: everything the batch adds to each case (the worker
process, its own solver build, pipes, rows written as they arrive, cold starts at chunk
boundaries). Speed-up = batch time on one worker / batch time on two. The load average
is recorded: the speed-up needs the cores to be free.
"""

from __future__ import annotations

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
        progress: Callable[[str], None] | None = None) -> dict[str, Any]:
    """Time the bare loop and the batches; returns rows and the derived figures."""
    ranges = [parse_range(f"environment.current.speed=0.4:1.3:{n_speeds}"),
              parse_range(f"layout.psi0_deg=0:140:{n_angles}")]
    data = read_problem(SCENE)
    cases = build_cases(ranges)
    n = len(cases)
    if progress:
        progress(f"bare loop, {n} cases")
    session = SolveSession()
    scenes = [scene_from_dict(apply_overrides(data, c.overrides)) for c in cases]
    for sc in scenes:  # first pass: builds the solvers (not timed)
        session.solve(sc)
    t0 = time.perf_counter()
    for sc in scenes:
        session.solve(sc)
    bare = time.perf_counter() - t0
    rows = [{"run": "bare warm loop (this process)", "workers": 0, "wall_s": bare,
             "per_case_ms": 1e3 * bare / n, "speedup": None, "overhead_ms": None,
             "solved": None}]
    times = {}
    for w in workers:
        if progress:
            progress(f"batch on {w} worker(s)")
        with tempfile.TemporaryDirectory() as tmp:
            t0 = time.perf_counter()
            res = run_batch(data, ranges=ranges, workers=w, out=Path(tmp) / "b")
            times[w] = time.perf_counter() - t0
        rows.append({"run": f"batch, {w} local worker(s)", "workers": w, "wall_s": times[w],
                     "per_case_ms": 1e3 * times[w] / n,
                     "speedup": times[min(times)] / times[w] if min(times) == 1 else None,
                     "overhead_ms": 1e3 * (times[w] * w - bare) / n,
                     "solved": sum(r["status"] == "solved" for r in res.rows)})
    one = times.get(1)
    summary = {
        "cases": n,
        "load_average": list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
        "cpu_count": os.cpu_count(),
        "bare_per_case_ms": 1e3 * bare / n,
        "overhead_per_case_ms": None if one is None else 1e3 * (one - bare) / n,
        "overhead_fraction": None if one is None else (one - bare) / bare,
        "speedup_2_workers": None if one is None or 2 not in times else one / times[2],
    }
    return {"rows": rows, "summary": summary}
