"""Work-precision benchmark: error against wall time for every statics method (issue 5).

For each scene, a reference (:func:`cable_ocp.bench.common.reference_solution`: collocation
of order 10 on 320 intervals, checked against multiple shooting on 1280) and then each
method over a range of resolutions. Times are whole calls as a user makes them (problem
already parsed; CasADi build included), the fastest of up to three repeats; the error
estimate and mesh refinement are off while timing. Errors: end forces over the largest
tension, and positions at the method's own nodes over the length
(:func:`cable_ocp.bench.common.profile_error`).

Methods with an a-posteriori estimate are re-run with it on (not timed) and the ratio
estimate / true error is reported: it must not fall below 0.1 (issue 5).
"""

from __future__ import annotations

import csv
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.bench.common import (
    force_error,
    profile_error,
    reference_solution,
    timed_solve,
)
from cable_ocp.scene import Scene, load_scene
from cable_ocp.statics.solver import StaticsSolver, solve

ROOT = Path(__file__).resolve().parents[2] / "problems"

# label -> (overrides, resolutions, key that the resolution sets)
PLAN: dict[str, tuple[dict[str, Any], list[Any], str]] = {
    "collocation legendre d=2": ({"solver.method": "collocation", "solver.degree": 2},
                                 [4, 8, 16, 32, 64, 128], "solver.intervals"),
    "collocation legendre d=3": ({"solver.method": "collocation", "solver.degree": 3},
                                 [2, 4, 8, 16, 32, 64], "solver.intervals"),
    "collocation legendre d=4": ({"solver.method": "collocation", "solver.degree": 4},
                                 [2, 4, 8, 16, 32], "solver.intervals"),
    "collocation radau d=3": ({"solver.method": "collocation", "solver.degree": 3,
                               "solver.scheme": "radau"}, [4, 8, 16, 32, 64],
                              "solver.intervals"),
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


def run_scene(label: str, scene: Scene, methods: list[str] | None = None,
              repeats: int = 3, progress: Callable[[dict[str, Any]], None] | None = None
              ) -> dict[str, Any]:
    """All methods on one scene; rows of (method, resolution, time, errors, ratio).

    ``progress(row)`` is called after each row."""
    ref = reference_solution(scene)
    rows: list[dict[str, Any]] = []
    notes: dict[str, str] = {}
    for name in methods or list(PLAN):
        if name not in PLAN:
            continue
        over, resolutions, key = PLAN[name]
        for res in resolutions:
            sc = scene.with_overrides({**over, key: res, "solver.error_estimate": False,
                                       "solver.refine": False})
            sol, dt, note = timed_solve(sc, repeats=repeats)
            if sol is None:
                notes[name] = note
                break
            row = {"scene": label, "method": name, "resolution": res, "time_s": dt,
                   "status": sol.status, "force_error": None, "profile_error": None,
                   "estimate_ratio": None}
            if sol.success and ref.solution.success:
                row["force_error"] = force_error(sol, ref.solution)
                row["profile_error"] = profile_error(sol, ref.solution)
                if name in OURS:
                    est = solve(sc.with_overrides({"solver.error_estimate": True,
                                                   "solver.accuracy": 1.0}))
                    true = max(row["force_error"], row["profile_error"])
                    if est.error_estimate is not None and true > 1e-9:
                        row["estimate_ratio"] = est.error_estimate / true
            rows.append(row)
            if progress is not None:
                progress(row)
    if methods is None or REUSED in methods:
        for row in _reused_rows(label, scene, ref.solution, repeats):
            rows.append(row)
            if progress is not None:
                progress(row)
    return {"scene": label, "reference": ref.how, "reference_check": ref.agreement,
            "rows": rows, "notes": notes, "dominance": dominance(rows)}


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
        best, sol = np.inf, None
        for _ in range(max(repeats, 5)):
            t0 = time.perf_counter()
            sol = solver.solve(sc, warm_start=near)
            best = min(best, time.perf_counter() - t0)
        row = {"scene": label, "method": REUSED, "resolution": n, "time_s": best,
               "status": sol.status, "force_error": None, "profile_error": None,
               "estimate_ratio": None}
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

    cold = [r for r in rows if r["method"].startswith("collocation ") and r["method"] != REUSED]
    ours = [(r["time_s"], err(r)) for r in cold if r["force_error"] is not None]
    out = {}
    for name in {r["method"] for r in rows} - {r["method"] for r in cold} - {REUSED}:
        pts = [(r["time_s"], err(r)) for r in rows
               if r["method"] == name and r["force_error"] is not None]
        if not pts:
            continue
        beaten = sum(any(t <= tb and e < eb for t, e in ours) for tb, eb in pts)
        out[name] = f"{beaten}/{len(pts)} points dominated by collocation"
    return out


def planned_rows(methods: list[str] | None = None) -> int:
    """Number of rows one scene gives (for a progress bar)."""
    n = sum(len(PLAN[m][1]) for m in (methods or list(PLAN)) if m in PLAN)
    return n + (5 if methods is None or REUSED in methods else 0)


def run(scenes: list[tuple[str, Path, dict[str, Any]]] | None = None,
        methods: list[str] | None = None, repeats: int = 3,
        progress: Callable[[dict[str, Any]], None] | None = None) -> list[dict[str, Any]]:
    """Run every scene; ``progress(row)`` is called after each row."""
    return [run_scene(label, load_scene(path, over), methods, repeats, progress)
            for label, path, over in (scenes or default_scenes())]


def write_csv(results: list[dict[str, Any]], path: str | Path) -> None:
    """One row per (scene, method, resolution)."""
    keys = ["scene", "method", "resolution", "time_s", "status", "force_error",
            "profile_error", "estimate_ratio"]
    with Path(path).open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        for res in results:
            for r in res["rows"]:
                w.writerow({k: r[k] for k in keys})


def plot(results: list[dict[str, Any]], path: str | Path) -> Path:
    """Log-log error (the larger of force and profile error) against wall time
    (:func:`cable_ocp.plots.bench.plot_work_precision`)."""
    from cable_ocp.plots.bench import plot_work_precision

    plot_work_precision(results, path)
    return Path(path)
