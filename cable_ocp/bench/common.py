"""Shared pieces of the statics benchmarks: reference solutions and error measures."""

from __future__ import annotations

import contextlib
import os
import tempfile
import time
from collections.abc import Iterator
from contextlib import nullcontext
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from scipy.interpolate import CubicSpline

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import interrupt
from cable_ocp.scene import Scene
from cable_ocp.statics.solution import StaticsSolution
from cable_ocp.statics.solver import solve


@dataclass
class Reference:
    """A high-resolution solution and how far an independent method agrees with it."""

    solution: StaticsSolution
    check: StaticsSolution | None
    agreement: float  # relative end-force difference to the check solution (-)
    how: str


def reference_solution(scene: Scene) -> Reference:
    """Gauss-Legendre degree 5 on 320 intervals (order 10), checked against multiple
    shooting (RK4) on 1280 intervals, an independent transcription of the same equations.
    Their agreement bounds the reference's own error (both are far below the errors the
    benchmarks measure unless stated)."""
    ref = solve(scene.with_overrides({"solver.method": "collocation", "solver.degree": 5,
                                      "solver.intervals": 320, "solver.scheme": "legendre",
                                      "solver.error_estimate": False}))
    chk = solve(scene.with_overrides({"solver.method": "multiple_shooting",
                                      "solver.intervals": 1280, "solver.error_estimate": False}),
                warm_start=ref if ref.success else None)
    agree = force_error(chk, ref) if (ref.success and chk.success) else float("nan")
    return Reference(ref, chk, agree, "collocation legendre d=5, N=320; checked by multiple "
                                      "shooting RK4, N=1280")


def force_error(sol: StaticsSolution, ref: StaticsSolution) -> float:
    """Largest end-force difference over the reference's largest tension (-).

    Parameters
    ----------
    sol : StaticsSolution
        The solution to measure.
    ref : StaticsSolution
        The reference (e.g. :func:`reference_solution`'s), a successful solve of the same
        scene. Its ``max_tension`` (N) scales the error.
    """
    return float(max(np.max(np.abs(sol.force_a - ref.force_a)),
                     np.max(np.abs(sol.force_b - ref.force_b))) / ref.max_tension)


def profile_error(sol: StaticsSolution, ref: StaticsSolution) -> float:
    """Largest position difference at the method's own nodes over the length (-).

    The reference is interpolated with cubic splines in s/L through its nodes (320 x 6
    nodes, spline error far below the compared errors); the method is compared only where
    it computed values, so a low-order method is not charged for interpolation.

    Parameters
    ----------
    sol : StaticsSolution
        The solution to measure.
    ref : StaticsSolution
        The reference (e.g. :func:`reference_solution`'s), a successful solve of the same
        scene. Its length (m) scales the error, and a difference in length
        (m) counts as a position difference.
    """
    sig_r, idx = np.unique(ref.s / ref.length, return_index=True)
    spline = CubicSpline(sig_r, ref.position[idx], axis=0)
    sig = sol.s / sol.length
    dpos = np.max(np.abs(sol.position - spline(sig)))
    return float(max(dpos, abs(sol.length - ref.length)) / ref.length)


@contextlib.contextmanager
def cache_folder(folder: str | Path | None) -> Iterator[None]:
    """Point the statics function cache (:mod:`cable_ocp.statics.cache`) at ``folder``
    (None: switch it off) for a while."""
    old = {k: os.environ.get(k) for k in ("CABLE_OCP_CACHE_DIR", "CABLE_OCP_CACHE")}
    if folder is None:
        os.environ["CABLE_OCP_CACHE"] = "0"
    else:
        os.environ["CABLE_OCP_CACHE_DIR"] = str(folder)
        os.environ.pop("CABLE_OCP_CACHE", None)
    try:
        yield
    finally:
        for k, v in old.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v


def timed_solve(scene: Scene, repeats: int = 1, budget_s: float = 2.0
                ) -> tuple[StaticsSolution | None, float, str]:
    """Solve and time the whole call (build included); fastest of ``repeats`` runs.

    Returns (solution or None, seconds, note). A scene the method cannot represent gives
    None and the reason; any other exception is reported as an error note, never hidden.

    Parameters
    ----------
    scene : Scene
        The statics scene, solved as it is (its ``[solver]`` says how).
    repeats : int
        Number of timed runs (default 1); the fastest counts.
    budget_s : float
        Time budget, s (default 2): when the first run times ``repeats`` exceeds it, only
        the first run is made.
    """
    sol, wall, _, note = timed_solve_cpu(scene, repeats, budget_s)
    return sol, wall, note


def timed_solve_cpu(scene: Scene, repeats: int = 1, budget_s: float = 2.0,
                    fresh_cache: bool = False
                    ) -> tuple[StaticsSolution | None, float, float, str]:
    """:func:`timed_solve` with CPU time too: (solution or None, wall s, CPU s, note), the
    wall time and the CPU time each the smallest over the repeats.

    With ``fresh_cache`` every repeat starts with an empty statics function cache (a new
    temporary folder), as a first process does: the CasADi functions are built and
    stored inside the timed call.

    Parameters
    ----------
    scene : Scene
        The statics scene, solved as it is (its ``[solver]`` says how).
    repeats : int
        Number of timed runs (default 1); the smallest wall and CPU times count.
    budget_s : float
        Time budget, s (default 2): when the first run's wall time times ``repeats``
        exceeds it, only the first run is made.
    fresh_cache : bool
        Give every run an empty statics function cache (default False: the cache the
        environment names, warm after the first run).
    """
    best, best_cpu = np.inf, np.inf
    sol: StaticsSolution | None = None
    with tempfile.TemporaryDirectory(prefix="cable_ocp_first_") as tmp:
        for k in range(repeats):
            ctx = cache_folder(Path(tmp) / str(k)) if fresh_cache else nullcontext()
            with ctx:
                t0, c0 = time.perf_counter(), time.process_time()
                try:
                    sol = solve(scene)
                except CableOCPError as exc:
                    return None, float("nan"), float("nan"), f"unsupported: {exc}"
                except Exception as exc:  # noqa: BLE001 - a crash is a result, reported
                    interrupt.reraise_interruption(exc)
                    return None, float("nan"), float("nan"), \
                        f"crashed: {type(exc).__name__}: {exc}"
                dt, dc = time.perf_counter() - t0, time.process_time() - c0
            best, best_cpu = min(best, dt), min(best_cpu, dc)
            if k == 0 and dt * repeats > budget_s:
                break
    return sol, float(best), float(best_cpu), ""


def fmt_sci(x: Any) -> str:
    """Short scientific format, '-' for None/NaN."""
    if x is None or (isinstance(x, float) and not np.isfinite(x)):
        return "-"
    return f"{x:.1e}"
