"""Benchmark: the De Zoysa psi0 sweep (19 angles, 40 intervals), collocation vs solve_bvp.

Everything is timed in one run so the ratios are meaningful on a noisy machine. Each time
is taken twice: wall clock (``time.perf_counter``) and the process's CPU time
(``time.process_time``), which other jobs on the machine disturb much less. Nothing here
is asserted by the tests.

The collocation sweep is timed as a first process meets it (an empty function cache:
the CasADi functions are built, then stored; the scene-independent sparse-LU helper,
compiled once per machine, is present) and as a second process meets it: a real
subprocess with the cache the first one filled (:mod:`cable_ocp.statics.cache`), so the
functions are loaded, not built.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.baselines.scipy_bvp import solve_bvp
from cable_ocp.bench.common import cache_folder
from cable_ocp.numerics import sparse_lu
from cable_ocp.scene import Scene, load_scene
from cable_ocp.statics.formulation import Formulation
from cable_ocp.statics.line_solver import StaticsSolver
from cable_ocp.statics.solver import sweep

DEFAULT_SCENE = Path(__file__).resolve().parents[2] / "problems" / "dezoysa_sea_buggy.toml"

#: the issue's targets: warm solve median (ms) and the whole sweep with build (ms)
TARGETS = {"warm_median_ms": 1.0, "sweep_total_ms": 60.0}


def _timed_sweep(base: Scene, angles: np.ndarray, error_estimate: bool = False
                 ) -> dict[str, Any]:
    """One collocation sweep (solvers built inside): totals and per-point figures."""
    t0, c0 = time.perf_counter(), time.process_time()
    sols = sweep(base, "layout.psi0_deg", angles, error_estimate=error_estimate)
    total, total_cpu = time.perf_counter() - t0, time.process_time() - c0
    warm = [s for s in sols[1:]]
    return {
        "total_ms": total * 1e3, "total_cpu_ms": total_cpu * 1e3,
        "first_ms": sols[0].wall_time_s * 1e3,
        "first_cpu_ms": sols[0].diagnostics.get("cpu_time_s", float("nan")) * 1e3,
        "build_ms": sols[0].diagnostics.get("build_time_s", float("nan")) * 1e3,
        "warm_ms": [s.wall_time_s * 1e3 for s in warm],
        "warm_cpu_ms": [s.diagnostics.get("cpu_time_s", float("nan")) * 1e3 for s in warm],
        "iterations": [int(s.iterations) for s in warm],
        "factorizations": [int(s.diagnostics.get("factorizations", s.iterations))
                           for s in warm],
        "solvers": sorted({s.diagnostics.get("solver", "") for s in sols}),
        "solved": int(sum(s.success for s in sols)), "points": len(sols),
        "forces": [s.force_a.tolist() for s in sols],
        "compiled": bool(sols[0].diagnostics.get("compiled", False)),
    }


def _best(runs: list[dict[str, Any]]) -> dict[str, Any]:
    """The run with the smallest CPU total (the least disturbed), as timeit keeps the
    fastest repeat."""
    return min(runs, key=lambda r: r["total_cpu_ms"])


def first_process(base: Scene, angles: np.ndarray, repeats: int, folder: Path
                  ) -> dict[str, Any]:
    """Sweeps with an empty cache (a fresh folder each repeat: build and store); the
    last folder is left filled in ``folder`` for the second process.

    Parameters
    ----------
    base : Scene
        The statics scene swept over ``layout.psi0_deg`` (its ``solver.intervals`` set).
    angles : numpy.ndarray
        psi0 values of the sweep, deg, in sweep order.
    repeats : int
        Number of sweeps; the least disturbed (smallest CPU total) is returned.
    folder : Path
        Cache folder the last repeat fills; the earlier repeats use fresh folders next to
        it (in ``folder.parent``).
    """
    runs = []
    for k in range(repeats):
        sub = folder if k == repeats - 1 else Path(tempfile.mkdtemp(dir=folder.parent))
        with cache_folder(sub):
            # the scene-independent sparse-LU helper is compiled once per machine, not
            # per scene: present (copied) before the clock starts, as on a used machine
            sparse_lu.available()
            runs.append(_timed_sweep(base, angles))
    return _best(runs)


def second_process(scene_path: str | Path, angles: np.ndarray, intervals: int, repeats: int,
                   folder: Path, compile_mode: str = "never") -> dict[str, Any]:
    """The same sweep in a new Python process whose cache is ``folder`` (filled by the
    first process): each repeat loads the functions (and, with ``compile_mode`` "auto",
    the compiled libraries) instead of building them.

    Parameters
    ----------
    scene_path : str or Path
        Problem file the child process loads (with a ``layout.psi0_deg`` key).
    angles : numpy.ndarray
        psi0 values of the sweep, deg, in sweep order.
    intervals : int
        Collocation intervals (``solver.intervals``).
    repeats : int
        Number of sweeps; the least disturbed (smallest CPU total) is returned.
    folder : Path
        The cache folder filled by :func:`first_process` (``CABLE_OCP_CACHE_DIR`` of the
        child).
    compile_mode : str
        The child's ``solver.compile``: ``"never"`` (default) or ``"auto"`` (load the
        compiled Newton kernel from the cache).
    """
    args = json.dumps({"scene": str(scene_path), "angles": [float(a) for a in angles],
                       "intervals": intervals, "repeats": repeats,
                       "compile": compile_mode})
    env = {**os.environ, "CABLE_OCP_CACHE_DIR": str(folder)}
    env.pop("CABLE_OCP_CACHE", None)
    root = str(Path(__file__).resolve().parents[2])
    env["PYTHONPATH"] = root + os.pathsep + env.get("PYTHONPATH", "")
    out = subprocess.run([sys.executable, "-m", "cable_ocp.bench.statics_sweep", "--child",
                          args], capture_output=True, text=True, env=env, timeout=600,
                         check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def _row(label: str, r: dict[str, Any]) -> list[Any]:
    warm, warm_cpu, its = (np.asarray(r[k], float) for k in ("warm_ms", "warm_cpu_ms",
                                                              "iterations"))
    facs = np.asarray(r.get("factorizations", [np.nan]), float)  # none for solve_bvp
    return [label, r["points"], r["total_ms"], r["total_cpu_ms"], r["first_ms"],
            float(np.median(warm)), float(np.median(warm_cpu)), float(np.percentile(warm, 90)),
            float(np.mean(its)), float(np.median(its)), float(np.mean(facs)), r["solved"]]


def run(scene_path: str | Path = DEFAULT_SCENE, angles: np.ndarray | None = None,
        intervals: int = 40, repeats: int = 3, subprocess_run: bool = True
        ) -> dict[str, Any]:
    """Time the psi0 sweep; return rows for :func:`cable_ocp.report.table` and raw data.

    Parameters
    ----------
    scene_path : path
        Problem file with a ``layout.psi0_deg`` key.
    angles : array, optional
        psi0 values in degrees (default 0, 10, ..., 180).
    intervals : int
        Collocation intervals.
    repeats : int
        Each collocation sweep is repeated this many times and the least disturbed repeat
        (smallest CPU time) is reported, as timeit keeps the fastest.
    subprocess_run : bool
        Also time the sweep in a second process that loads the cached functions.
    """
    angles = np.arange(0.0, 181.0, 10.0) if angles is None else np.asarray(angles, float)
    base: Scene = load_scene(scene_path, {"solver.intervals": intervals})
    rows: list[list[Any]] = []
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    with tempfile.TemporaryDirectory(prefix="cable_ocp_bench_") as tmp:
        folder = Path(tmp) / "cache"
        first = first_process(base, angles, repeats, folder)
        rows.append(_row("collocation, 1st process (build)", first))
        second = None
        if subprocess_run:
            second = second_process(scene_path, angles, intervals, repeats, folder)
            rows.append(_row("  2nd process (disk cache)", second))
        # the Newton kernel compiled to C (solver.compile = "auto"): the first process
        # generates and compiles the C code (once: an empty folder), a second process
        # loads the cached libraries
        comp_base = base.with_overrides({"solver.compile": "auto"})
        comp_folder = Path(tmp) / "compiled"
        with cache_folder(comp_folder):
            sparse_lu.available()  # the helper present, as in first_process
            comp_first = _timed_sweep(comp_base, angles)
        rows.append(_row("compiled, 1st process (C compile)",
                         comp_first))
        comp_second = None
        if subprocess_run:
            comp_second = second_process(scene_path, angles, intervals, repeats, comp_folder,
                                         compile_mode="auto")
            rows.append(_row("  compiled, 2nd process (cache)", comp_second))
        with cache_folder(Path(tmp) / "est"):
            sparse_lu.available()
            est = _timed_sweep(base, angles, error_estimate=True)
        rows.append(_row("  with error estimates", est))
        builds = []
        for _ in range(repeats):
            with cache_folder(None):
                t0, c0 = time.perf_counter(), time.process_time()
                StaticsSolver(base)
                builds.append(((time.perf_counter() - t0) * 1e3,
                               (time.process_time() - c0) * 1e3))
        b_wall, b_cpu = min(builds, key=lambda x: x[1])
        nan = float("nan")
        rows.append(["  build only (no cache)", 1, b_wall, b_cpu, nan, nan,
                     nan, nan, nan, nan, nan, 1])

    scenes = [base.with_overrides({"layout.psi0_deg": float(a)}) for a in angles]
    form = Formulation(base)
    bvp: dict[str, dict[str, Any]] = {}
    for how in ("cold", "warm"):
        prev, sols, walls, cpus = None, [], [], []
        t0, c0 = time.perf_counter(), time.process_time()
        for sc in scenes:
            c1 = time.process_time()
            s = solve_bvp(sc, form=form, warm_start=prev if (
                how == "warm" and prev is not None and prev.success) else None)
            cpus.append((time.process_time() - c1) * 1e3)
            walls.append(s.wall_time_s * 1e3)
            sols.append(s)
            prev = s
        bvp[how] = {"total_ms": (time.perf_counter() - t0) * 1e3,
                    "total_cpu_ms": (time.process_time() - c0) * 1e3, "first_ms": walls[0],
                    "warm_ms": walls[1:], "warm_cpu_ms": cpus[1:],
                    "iterations": [s.iterations for s in sols[1:]],
                    "solved": int(sum(s.success for s in sols)), "points": len(sols),
                    "sols": sols}
    rows.append(_row("solve_bvp, from catenary", bvp["cold"]))
    rows.append(_row("solve_bvp, warm", bvp["warm"]))

    fa = np.array(first["forces"])
    fb = np.array([s.force_a for s in bvp["cold"]["sols"]])
    agree = float(np.max(np.abs(fa - fb)) / np.max(np.abs(fa)))
    headers = ["method", "points", "total [ms]", "CPU [ms]", "first [ms]", "next [ms]",
               "next CPU [ms]", "next p90 [ms]", "iters mean", "iters median",
               "factor. mean", "solved"]
    per_point = (first["total_ms"] - first["build_ms"] - first["first_ms"]) \
        / max(first["points"] - 1, 1)
    comp_row = _row("", comp_second or comp_first)
    summary = {
        "warm_median_ms": rows[0][5],
        "warm_iterations_median": rows[0][9],
        "sweep_total_ms": rows[0][2],
        "solve_bvp_median_ms": rows[-2][5],
        "max_rel_difference": agree,
        "warm_median_cpu_ms": rows[0][6],
        "warm_iterations_mean": rows[0][8],
        "warm_factorizations_mean": rows[0][10],
        "warm_point_all_in_ms": per_point,
        "sweep_total_cpu_ms": rows[0][3],
        "sweep_total_second_process_ms": second["total_ms"] if second else None,
        "sweep_total_second_process_cpu_ms": second["total_cpu_ms"] if second else None,
        "second_process_build_source": second.get("build_source") if second else None,
        "build_ms": b_wall, "build_cpu_ms": b_cpu,
        "solve_bvp_median_cpu_ms": rows[-2][6],
        "warm_ratio_solve_bvp_over_collocation": rows[-2][5] / rows[0][5],
        "load_average_1min": load,
        "compiled": comp_first["compiled"],
        "compiled_sweep_total_first_process_ms": comp_first["total_ms"],
        # per point: the second process's least disturbed repeat (the first process runs
        # once, as compiling is done once)
        "compiled_warm_median_ms": comp_row[5],
        "compiled_warm_median_cpu_ms": comp_row[6],
        "compiled_warm_iterations_median": comp_row[9],
        "compiled_warm_factorizations_mean": comp_row[10],
        "compiled_sweep_total_second_process_ms": (comp_second["total_ms"] if comp_second
                                                   else None),
        "compiled_sweep_total_second_process_cpu_ms": (comp_second["total_cpu_ms"]
                                                       if comp_second else None),
    }
    return {"headers": headers, "rows": rows, "angles": angles, "forces": fa,
            "forces_bvp": fb, "agreement": agree, "targets": dict(TARGETS),
            "measured": {"warm_median_ms": rows[0][5], "sweep_total_ms": rows[0][2]},
            "summary": summary}


def _child(args: dict[str, Any]) -> None:
    """The second process: the sweep, its functions loaded from the cache (prints JSON)."""
    from cable_ocp.statics.line_solver import StaticsSolver as Solver

    base = load_scene(args["scene"], {"solver.intervals": args["intervals"],
                                      "solver.compile": args.get("compile", "never")})
    angles = np.asarray(args["angles"], float)
    runs = [_timed_sweep(base, angles) for _ in range(args["repeats"])]
    best = _best(runs)
    best["build_source"] = Solver(base).build_source
    print(json.dumps(best))


if __name__ == "__main__":  # the second process of :func:`second_process`
    parser = argparse.ArgumentParser()
    parser.add_argument("--child", required=True)
    _child(json.loads(parser.parse_args().child))
