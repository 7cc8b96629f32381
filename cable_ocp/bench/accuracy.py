"""Work-precision benchmark: error against run time for every statics method.

For each scene, a reference (:func:`cable_ocp.bench.common.reference_solution`: collocation
of order 10 on 320 intervals, checked against multiple shooting on 1280) and then each
method over a range of resolutions. Times are whole calls as a user makes them (problem
already parsed; CasADi build included), the fastest of up to three repeats, as wall-clock
and CPU time; the repeats are interleaved passes over every method and resolution, so
that a slower or faster stretch of a shared machine meets every series alike. The error
estimate and mesh refinement are off while timing. Errors: end forces over the largest
tension, and positions at the method's own nodes over the length
(:func:`cable_ocp.bench.common.profile_error`).

Our series (collocation, multiple shooting) are timed twice: as a first process meets
them (every repeat with an empty function cache, so the CasADi functions are built and
stored inside the timed call) and as a second process meets them: a real subprocess
whose cache the first process filled (:mod:`cable_ocp.statics.cache`), rows labelled
"(2nd process)", timed there in interleaved passes too. :func:`versus_solve_bvp` compares
the cheapest cold collocation that reaches each error level with scipy's ``solve_bvp``.

Methods with an a-posteriori estimate are re-run with it on (not timed) and the ratio
estimate / true error is reported: it must not fall below 0.1.
"""

from __future__ import annotations

import argparse
import csv
import io
import json
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.bench.common import (
    cache_folder,
    force_error,
    profile_error,
    reference_solution,
    timed_solve_cpu,
)
from cable_ocp.numerics.atomic import write_text_atomically
from cable_ocp.scene import Scene, load_scene
from cable_ocp.statics.line_solver import StaticsSolver
from cable_ocp.statics.solver import solve

ROOT = Path(__file__).resolve().parents[2] / "problems"

# label -> (overrides, resolutions, key that the resolution sets)
PLAN: dict[str, tuple[dict[str, Any], list[Any], str]] = {
    # up to the meshes that reach 1e-10 on De Zoysa with a uniform mesh (the |u|u kink of
    # the drag where a flow component changes sign slows its convergence there; the
    # default mesh has a point on it)
    "collocation legendre d=2": ({"solver.method": "collocation", "solver.degree": 2},
                                 [4, 8, 16, 32, 64, 128, 256], "solver.intervals"),
    "collocation legendre d=3": ({"solver.method": "collocation", "solver.degree": 3},
                                 [2, 4, 8, 16, 32, 64, 128, 256], "solver.intervals"),
    "collocation legendre d=4": ({"solver.method": "collocation", "solver.degree": 4},
                                 [2, 4, 8, 16, 32, 64, 128], "solver.intervals"),
    "collocation radau d=3": ({"solver.method": "collocation", "solver.degree": 3,
                               "solver.scheme": "radau"}, [4, 8, 16, 32, 64, 128],
                              "solver.intervals"),
    # degree 4 without mesh points on the drag's kinks (solver.mesh, default "kinks"):
    # what the kinks cost a uniform mesh, in the same run
    "collocation legendre d=4, uniform mesh": ({"solver.method": "collocation",
                                                "solver.degree": 4, "solver.mesh": "uniform"},
                                               [2, 4, 8, 16, 32, 64, 128], "solver.intervals"),
    "multiple shooting (RK4)": ({"solver.method": "multiple_shooting"},
                                [10, 20, 40, 80, 160, 320], "solver.intervals"),
    "scipy solve_bvp": ({"solver.method": "solve_bvp", "solver.intervals": 10},
                        [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9], "solver.tolerance"),
    "Wang shooting-optimization": ({"solver.method": "wang_shooting_optimization"},
                                   [10, 20, 40, 80, 160], "solver.intervals"),
    "Huang semi-analytic": ({"solver.method": "huang_semianalytic"},
                            [10, 20, 40, 80, 160, 320], "solver.intervals"),
    "Chucheepsakul FEM": ({"solver.method": "chucheepsakul_fem"},
                          [5, 10, 20, 40, 80], "solver.intervals"),
}
OURS = [k for k in PLAN if k.startswith(("collocation", "multiple"))]


def default_scenes() -> list[tuple[str, Path, dict[str, Any]]]:
    """(label, file, overrides) of the scenes the README shows."""
    return [("De Zoysa psi0=90", ROOT / "dezoysa_sea_buggy.toml", {"layout.psi0_deg": 90.0}),
            ("Berteaux", ROOT / "berteaux_mooring.toml", {})]


SECOND = " (2nd process)"
#: a call slower than this over the number of repeats is timed once (as
#: :func:`cable_ocp.bench.common.timed_solve_cpu` does)
REPEAT_BUDGET_S = 2.0


def run_scene(label: str, scene: Scene, methods: list[str] | None = None,
              repeats: int = 3, progress: Callable[[dict[str, Any]], None] | None = None,
              source: tuple[str | Path, dict[str, Any]] | None = None,
              second_process: bool = True) -> dict[str, Any]:
    """All methods on one scene; rows of (method, resolution, time, errors, ratio).

    ``progress(row)`` is called after each row. ``source`` (problem file, overrides) lets
    a second process load the scene and time our series with the function cache the
    first-process runs filled.

    Parameters
    ----------
    label : str
        The scene's name in the rows (e.g. ``"De Zoysa psi0=90"``).
    scene : Scene
        The statics scene; each series overrides its ``[solver]`` keys.
    methods : list of str, optional
        Series to run: labels of :data:`PLAN` (others are skipped) and :data:`REUSED` (the
        built-once solver). None (default): all of them.
    repeats : int
        Timing passes over every row (default 3), interleaved; the fastest counts (a row
        slower than :data:`REPEAT_BUDGET_S` over ``repeats`` is timed once).
    progress : callable, optional
        ``progress(row)``, called after each row and each repeat of it (see
        :func:`planned_rows`). None (default): none.
    source : (str or Path, dict), optional
        The problem file and overrides that make ``scene``, for the second process. None
        (default): no second-process rows.
    second_process : bool
        Time our series in a second process too (default True; needs ``source``).
    """
    ref = reference_solution(scene)
    rows: list[dict[str, Any]] = []
    notes: dict[str, str] = {}
    jobs: list[dict[str, Any]] = []  # our rows, for the second process
    timed: list[tuple[dict[str, Any], Scene, bool]] = []  # (row, scene, fresh cache)
    with tempfile.TemporaryDirectory(prefix="cable_ocp_accuracy_") as tmp:
        shared = Path(tmp) / "cache"
        for name in methods or list(PLAN):
            if name not in PLAN:
                continue
            over, resolutions, key = PLAN[name]
            for res in resolutions:
                extra = {**over, key: res, "solver.error_estimate": False,
                         "solver.refine": False}
                sc = scene.with_overrides(extra)
                sol, dt, cpu, note = timed_solve_cpu(sc, repeats=1,
                                                     fresh_cache=name in OURS)
                if sol is None:
                    notes[name] = note
                    break
                row = {"scene": label, "method": name, "resolution": res, "time_s": dt,
                       "cpu_s": cpu, "status": sol.status, "force_error": None,
                       "profile_error": None, "estimate_ratio": None}
                if sol.success and ref.solution.success:
                    row["force_error"] = force_error(sol, ref.solution)
                    row["profile_error"] = profile_error(sol, ref.solution)
                    if name in OURS:
                        with cache_folder(shared):
                            solve(sc)  # fills the second process's cache (not timed)
                            est = solve(sc.with_overrides({"solver.error_estimate": True,
                                                           "solver.accuracy": 1.0}))
                        true = max(row["force_error"], row["profile_error"])
                        if est.error_estimate is not None and true > 1e-9:
                            row["estimate_ratio"] = est.error_estimate / true
                        jobs.append({"row": row, "overrides": extra})
                rows.append(row)
                timed.append((row, sc, name in OURS))
                if progress is not None:
                    progress(row)
        # the other repeats, interleaved: every series meets the same faster and slower
        # stretches of a shared machine (one series after another, fastest of 3 each, a
        # slow minute moved one series against another by up to 70 %)
        for _ in range(repeats - 1):
            for row, sc, fresh in timed:
                if row["time_s"] * repeats <= REPEAT_BUDGET_S:  # else timed once
                    _, dt, cpu, _ = timed_solve_cpu(sc, repeats=1, fresh_cache=fresh)
                    row["time_s"] = float(np.fmin(row["time_s"], dt))
                    row["cpu_s"] = float(np.fmin(row["cpu_s"], cpu))
                if progress is not None:
                    progress(row)
        if second_process and source is not None and jobs:
            timings = _second_process(source, [j["overrides"] for j in jobs], repeats,
                                      shared)
            for job, (wall, cpu, how) in zip(jobs, timings, strict=True):
                row = {**job["row"], "method": job["row"]["method"] + SECOND,
                       "time_s": wall, "cpu_s": cpu, "estimate_ratio": None,
                       "build": how}
                rows.append(row)
                if progress is not None:
                    progress(row)
    if methods is None or REUSED in methods:
        for row in _reused_rows(label, scene, ref.solution, repeats):
            rows.append(row)
            if progress is not None:
                progress(row)
    return {"scene": label, "reference": ref.how, "reference_check": ref.agreement,
            "rows": rows, "notes": notes, "dominance": dominance(rows),
            "versus_solve_bvp": versus_solve_bvp(rows)}


def _second_process(source: tuple[str | Path, dict[str, Any]], overrides: list[dict],
                    repeats: int, folder: Path) -> list[tuple[float, float, str]]:
    """Time ``solve`` of each variant of the scene in a new Python process whose function
    cache is ``folder``: (wall s, CPU s, where the functions came from) each."""
    path, over = source
    args = json.dumps({"path": str(path), "overrides": over, "variants": overrides,
                       "repeats": repeats})
    env = {**os.environ, "CABLE_OCP_CACHE_DIR": str(folder)}
    env.pop("CABLE_OCP_CACHE", None)
    root = str(Path(__file__).resolve().parents[2])
    env["PYTHONPATH"] = root + os.pathsep + env.get("PYTHONPATH", "")
    out = subprocess.run([sys.executable, "-m", "cable_ocp.bench.accuracy", "--child", args],
                         capture_output=True, text=True, env=env, timeout=3600, check=True)
    return [tuple(x) for x in json.loads(out.stdout.strip().splitlines()[-1])]


def _child(args: dict[str, Any]) -> None:
    """The second process: each variant timed with the functions from the cache."""
    from cable_ocp.statics.line_solver import StaticsSolver

    base = load_scene(args["path"], args["overrides"])
    scenes = [base.with_overrides(extra) for extra in args["variants"]]
    best = [[np.inf, np.inf] for _ in scenes]
    for k in range(args["repeats"]):  # interleaved, as in the first process
        for b, sc in zip(best, scenes, strict=True):
            if k and b[0] * args["repeats"] > REPEAT_BUDGET_S:
                continue
            _, wall, cpu, _ = timed_solve_cpu(sc, repeats=1)
            b[0], b[1] = float(np.fmin(b[0], wall)), float(np.fmin(b[1], cpu))
    print(json.dumps([(b[0], b[1], StaticsSolver(sc).build_source)
                      for b, sc in zip(best, scenes, strict=True)]))


REUSED = "collocation d=3, built once, warm"


def _reused_rows(label: str, scene: Scene, ref: Any, repeats: int) -> list[dict[str, Any]]:
    """The sweep workload: a solver built once and re-solved from a neighbouring solution
    (here the same scene at 99 % of the current, or the same scene in still water), timed
    without the build. This is what each point of a sweep or an MPC-style loop costs."""
    rows = []
    for n in (4, 8, 16, 32, 64):
        sc = scene.with_overrides({"solver.intervals": n, "solver.error_estimate": False,
                                   "solver.refine": False})
        solver = StaticsSolver(sc)
        near = solver.solve(sc, current_scale=0.99)
        best, best_cpu, sol = np.inf, np.inf, None
        for _ in range(max(repeats, 5)):
            t0, c0 = time.perf_counter(), time.process_time()
            sol = solver.solve(sc, warm_start=near)
            best = min(best, time.perf_counter() - t0)
            best_cpu = min(best_cpu, time.process_time() - c0)
        row = {"scene": label, "method": REUSED, "resolution": n, "time_s": best,
               "cpu_s": best_cpu, "status": sol.status, "force_error": None,
               "profile_error": None, "estimate_ratio": None}
        if sol.success and ref.success:
            row["force_error"] = force_error(sol, ref)
            row["profile_error"] = profile_error(sol, ref)
        rows.append(row)
    return rows


def dominance(rows: list[dict[str, Any]]) -> dict[str, str]:
    """For each other method: how many of its points are beaten (less or equal time and
    smaller error) by some cold collocation point (build included; the reused-solver
    series is left out of this comparison: it measures a different workload)."""
    def err(r: dict[str, Any]) -> float:
        return max(r["force_error"], r["profile_error"])

    cold = [r for r in rows if r["method"].startswith("collocation ") and r["method"] != REUSED
            and not r["method"].endswith(SECOND)]
    ours = [(r["time_s"], err(r)) for r in cold if r["force_error"] is not None]
    out = {}
    theirs = {r["method"] for r in rows if not r["method"].endswith(SECOND)}
    for name in theirs - {r["method"] for r in cold} - {REUSED}:
        pts = [(r["time_s"], err(r)) for r in rows
               if r["method"] == name and r["force_error"] is not None]
        if not pts:
            continue
        beaten = sum(any(t <= tb and e < eb for t, e in ours) for tb, eb in pts)
        out[name] = f"{beaten}/{len(pts)} points dominated by collocation"
    return out


#: error levels at which :func:`versus_solve_bvp` compares (relative, -)
LEVELS = (1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10)
BVP = "scipy solve_bvp"


def versus_solve_bvp(rows: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """For each error level: the least time (wall and CPU) in which scipy's solve_bvp and
    the cold collocation series (any scheme and degree; first process, and second process
    when timed) reach that error; None where none of their points does. ``ahead`` says
    whether collocation needs no more time than solve_bvp (True also where only
    collocation reaches the level)."""
    def err(r: dict[str, Any]) -> float:
        return max(r["force_error"], r["profile_error"])

    def least(sel: list[dict[str, Any]], level: float, key: str) -> float | None:
        t = [r[key] for r in sel if r["force_error"] is not None and err(r) <= level]
        return min(t) if t else None

    bvp = [r for r in rows if r["method"] == BVP]
    first = [r for r in rows if r["method"].startswith("collocation ")
             and r["method"] != REUSED and not r["method"].endswith(SECOND)]
    second = [r for r in rows if r["method"].startswith("collocation ")
              and r["method"].endswith(SECOND)]
    out = []
    for level in LEVELS:
        entry: dict[str, Any] = {"error": level}
        for name, sel in (("solve_bvp", bvp), ("first", first), ("second", second)):
            for key, suffix in (("time_s", "_s"), ("cpu_s", "_cpu_s")):
                entry[name + suffix] = least(sel, level, key)
        for name in ("first", "second"):
            for suffix in ("_s", "_cpu_s"):
                mine, theirs = entry[name + suffix], entry["solve_bvp" + suffix]
                entry[f"{name}_ahead{suffix}"] = (
                    None if mine is None and theirs is None else
                    mine is not None and (theirs is None or mine <= theirs))
        out.append(entry)
    return out


def planned_rows(methods: list[str] | None = None, repeats: int = 1) -> int:
    """Number of progress calls one scene gives (for a progress bar): each row once per
    repeat (the repeats are interleaved passes), the second process's rows once.

    Parameters
    ----------
    methods : list of str, optional
        Series to run: labels of :data:`PLAN` (others are skipped) and :data:`REUSED` (the
        built-once solver). None (default): all of them.
    repeats : int
        Timing passes, as in :func:`run_scene` (default 1; values below 1 count as 1).
    """
    n = sum(len(PLAN[m][1]) for m in (methods or list(PLAN)) if m in PLAN) * max(repeats, 1)
    n += sum(len(PLAN[m][1]) for m in (methods or list(PLAN)) if m in OURS)  # 2nd process
    return n + (5 if methods is None or REUSED in methods else 0)


def run(scenes: list[tuple[str, Path, dict[str, Any]]] | None = None,
        methods: list[str] | None = None, repeats: int = 3,
        progress: Callable[[dict[str, Any]], None] | None = None,
        second_process: bool = True) -> list[dict[str, Any]]:
    """Run every scene; ``progress(row)`` is called after each row.

    Parameters
    ----------
    scenes : list of (str, Path, dict), optional
        ``(label, problem file, overrides)`` per scene; None (default):
        :func:`default_scenes`.
    methods : list of str, optional
        Series to run: labels of :data:`PLAN` (others are skipped) and :data:`REUSED` (the
        built-once solver). None (default): all of them.
    repeats : int
        Timing passes over every row (default 3); the fastest counts.
    progress : callable, optional
        ``progress(row)``, called after each row and each repeat; None (default): none.
    second_process : bool
        Also time our series in a second process that loads the cache (default True).
    """
    return [run_scene(label, load_scene(path, over), methods, repeats, progress,
                      source=(path, over), second_process=second_process)
            for label, path, over in (scenes or default_scenes())]


def write_csv(results: list[dict[str, Any]], path: str | Path) -> None:
    """One row per (scene, method, resolution).

    Parameters
    ----------
    results : list of dict
        :func:`run`'s results, one per scene; their ``rows`` are written.
    path : str or Path
        The CSV file, overwritten: columns scene, method, resolution, time_s and cpu_s (s),
        status, force_error, profile_error and estimate_ratio (-).
    """
    keys = ["scene", "method", "resolution", "time_s", "cpu_s", "status", "force_error",
            "profile_error", "estimate_ratio"]
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=keys)
    w.writeheader()
    for res in results:
        for r in res["rows"]:
            w.writerow({k: r.get(k) for k in keys})
    write_text_atomically(path, buf.getvalue())  # whole or not at all


if __name__ == "__main__":  # the second process of :func:`_second_process`
    parser = argparse.ArgumentParser()
    parser.add_argument("--child", required=True)
    _child(json.loads(parser.parse_args().child))
