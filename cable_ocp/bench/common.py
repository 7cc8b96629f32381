"""Shared pieces of the statics benchmarks: reference solutions and error measures."""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.interpolate import CubicSpline

from cable_ocp.errors import CableOCPError
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
    """Largest end-force difference over the reference's largest tension (-)."""
    return float(max(np.max(np.abs(sol.force_a - ref.force_a)),
                     np.max(np.abs(sol.force_b - ref.force_b))) / ref.max_tension)


def profile_error(sol: StaticsSolution, ref: StaticsSolution) -> float:
    """Largest position difference at the method's own nodes over the length (-).

    The reference is interpolated with cubic splines in s/L through its nodes (320 x 6
    nodes, spline error far below the compared errors); the method is compared only where
    it computed values, so a low-order method is not charged for interpolation.
    """
    sig_r, idx = np.unique(ref.s / ref.length, return_index=True)
    spline = CubicSpline(sig_r, ref.position[idx], axis=0)
    sig = sol.s / sol.length
    dpos = np.max(np.abs(sol.position - spline(sig)))
    return float(max(dpos, abs(sol.length - ref.length)) / ref.length)


def timed_solve(scene: Scene, repeats: int = 1, budget_s: float = 2.0
                ) -> tuple[StaticsSolution | None, float, str]:
    """Solve and time the whole call (build included); fastest of ``repeats`` runs.

    Returns (solution or None, seconds, note). A scene the method cannot represent gives
    None and the reason; any other exception is reported as an error note, never hidden.
    """
    best = np.inf
    sol: StaticsSolution | None = None
    for k in range(repeats):
        t0 = time.perf_counter()
        try:
            sol = solve(scene)
        except CableOCPError as exc:
            return None, float("nan"), f"unsupported: {exc}"
        except Exception as exc:  # noqa: BLE001 - a crash is a result, reported as such
            return None, float("nan"), f"crashed: {type(exc).__name__}: {exc}"
        dt = time.perf_counter() - t0
        best = min(best, dt)
        if k == 0 and dt * repeats > budget_s:
            break
    return sol, float(best), ""


def fmt_sci(x: Any) -> str:
    """Short scientific format, '-' for None/NaN."""
    if x is None or (isinstance(x, float) and not np.isfinite(x)):
        return "-"
    return f"{x:.1e}"
