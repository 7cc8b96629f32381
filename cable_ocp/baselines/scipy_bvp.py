"""scipy.integrate.solve_bvp on the same equations as the collocation solver.

The outside reference a user would reach for: the same right-hand side (the scene's
:class:`~cable_ocp.statics.formulation.Formulation`, evaluated column-wise), the same end
conditions, scaled variables, the scaled length as an unknown parameter when it is free.
solve_bvp uses 4th-order Lobatto IIIA collocation with residual-based mesh refinement.
Its ``tol`` bounds that residual, not the error of the answer: the registry entry
(:func:`solve`) estimates the error by a second solve at tol/10 and refines the tolerance
to ``solver.accuracy``.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np
from scipy.integrate import solve_bvp as _scipy_solve_bvp

from cable_ocp.baselines.common import Estimate, compare, refine_to_accuracy, seabed_check
from cable_ocp.scene import Scene
from cable_ocp.statics.formulation import (
    P_CURRENT,
    P_END_A,
    P_END_B,
    P_LENGTH,
    P_TENSION,
    Formulation,
)
from cable_ocp.statics.initial_guess import initial_guess
from cable_ocp.statics.registry import register
from cable_ocp.statics.solution import StaticsSolution


def solve_bvp(scene: Scene, nodes: int = 41, tol: float = 1e-8, max_nodes: int = 100000,
              warm_start: StaticsSolution | None = None,
              form: Formulation | None = None, own_mesh: bool = False) -> StaticsSolution:
    """Solve a scene with :func:`scipy.integrate.solve_bvp`.

    Parameters
    ----------
    scene : Scene
        The statics problem.
    nodes : int
        Initial mesh size (uniform in s/L).
    tol : float
        solve_bvp's relative residual tolerance.
    max_nodes : int
        Mesh-size limit.
    warm_start : StaticsSolution, optional
        Start from this solution (resampled on ``nodes`` uniform nodes) instead of the
        drag-free guess.
    form : Formulation, optional
        Reuse an already built formulation (same scene structure).
    own_mesh : bool
        Start from ``warm_start`` on its own nodes (s/L) instead of ``nodes`` uniform ones
        (solve_bvp only inserts nodes, so the new mesh contains the old one).
    """
    form = Formulation(scene) if form is None else form
    p = form.params(scene)
    sc = form.scales
    free = scene.free_length
    t0 = time.perf_counter()
    if warm_start is not None:
        src, idx = np.unique(warm_start.s / warm_start.length, return_index=True)
        sig = src if own_mesh else np.linspace(0.0, 1.0, nodes)
        r, t = (np.stack([np.interp(sig, src, a[idx, k]) for k in range(3)], axis=1)
                for a in (warm_start.position, warm_start.tension_vector))
        length = warm_start.length
    else:
        sig = np.linspace(0.0, 1.0, nodes)
        r, t, length, _ = initial_guess(scene, sig, scene.solver.initial_guess)
    y0 = np.vstack([r.T / sc.length, t.T / sc.force])
    lam_fixed = p[P_LENGTH]

    def fun(_x: np.ndarray, y: np.ndarray, q: np.ndarray | None = None) -> np.ndarray:
        lam = q[0] if free else lam_fixed
        return np.asarray(form.rhs(y, lam, p[P_CURRENT]))

    def bc(ya: np.ndarray, yb: np.ndarray, q: np.ndarray | None = None) -> np.ndarray:
        res = form.end_residual(scene.end_a, ya, p[P_END_A], at_a=True)
        res += form.end_residual(scene.end_b, yb, p[P_END_B], at_a=False)
        if free:
            ye = ya if scene.end_a.tension is not None else yb
            res.append(float(ye[3:] @ ye[3:]) - p[P_TENSION] ** 2)
        return np.asarray(res, dtype=float)

    if free:
        res = _scipy_solve_bvp(lambda x, y, q: fun(x, y, q), lambda a, b, q: bc(a, b, q), sig, y0,
                               p=[length / sc.length], tol=tol, max_nodes=max_nodes)
        lam = float(res.p[0])
    else:
        res = _scipy_solve_bvp(lambda x, y: fun(x, y), lambda a, b: bc(a, b), sig, y0, tol=tol,
                               max_nodes=max_nodes)
        lam = float(lam_fixed)
    wall = time.perf_counter() - t0
    length = lam * sc.length
    y = res.y
    bcres = bc(y[:, 0], y[:, -1], np.array([lam]))
    viol = float(max(np.max(np.abs(res.rms_residuals)), np.max(np.abs(bcres))))
    status = "solved" if res.status == 0 else {1: "max_nodes", 2: "singular"}.get(
        res.status, "failed")
    return StaticsSolution(
        status=status,
        message=f"solve_bvp: {res.message}",
        s=res.x * length,
        position=y[:3].T * sc.length,
        tension_vector=y[3:].T * sc.force,
        length=length,
        iterations=int(res.niter),
        wall_time_s=wall,
        constraint_violation=viol,
        diagnostics={"method": "solve_bvp", "nodes": int(res.x.size), "tol": tol},
    )


#: solve_bvp's tolerance is refined down to TOL_FLOOR at most: the estimate of a solution
#: at tol needs a solve at tol/10, and below 1e-10 its residual-based mesh refinement
#: chases rounding (scaled variables of order 1) and stalls until max_nodes
TOL_FLOOR = 1e-9
#: solve_bvp's mesh-size limit (nodes); 1e-10 needs up to ~2800 on the benchmark scenes
MAX_NODES = 10000


def solve(scene: Scene, warm_start: StaticsSolution | None = None) -> StaticsSolution:
    """Registry entry (``solver.method = "solve_bvp"``), with the accuracy contract.

    ``solver.intervals + 1`` initial nodes; solve_bvp's tolerance starts at
    ``max(solver.tolerance, TOL_FLOOR)`` (1e-9: tighter requests stall its mesh
    refinement). solve_bvp's ``tol`` bounds its collocation residual, not the error of
    the end forces, so it is no error estimate. The estimate is the difference between
    this solution and a second solve at tol/10 started on this solution's own mesh (the
    larger of the end-force difference over the largest tension and the position and
    length differences over the length; positions compared at this solution's nodes): the
    error of the tol solution, up to the tol/10 solution's own error. While it exceeds
    ``solver.accuracy`` (and ``solver.refine``), the tolerance is divided by 10 (the
    comparison solve becomes the solution) down to ``TOL_FLOOR``, with at most
    ``MAX_NODES`` = 10000 nodes (solve_bvp's status ``"max_nodes"`` beyond). A result
    above the accuracy is ``"inaccurate"``
    (:func:`cable_ocp.baselines.common.refine_to_accuracy`). It has no seabed contact: a
    profile through a modelled seabed is reported as ``"seabed_contact"``.

    Parameters
    ----------
    scene : Scene
        The statics problem (project frame).
    warm_start : StaticsSolution, optional
        Start of the first solve (resampled on ``solver.intervals + 1`` uniform nodes,
        :func:`solve_bvp`) instead of ``solver.initial_guess``; later levels start from
        the previous one.
    """
    form = Formulation(scene)
    cache: dict[float, StaticsSolution] = {}
    first = {"warm": warm_start}

    def solve_at(tol: float, warm: StaticsSolution | None) -> StaticsSolution:
        if warm is not None and tol in cache:
            return cache[tol]  # the previous level's comparison solve
        start = first.pop("warm", None) if warm is None else warm
        sol = solve_bvp(scene, nodes=scene.solver.intervals + 1, tol=tol, max_nodes=MAX_NODES,
                        warm_start=start, form=form)
        cache[tol] = sol
        return sol

    def estimate(tol: float, sol: StaticsSolution) -> Estimate:
        fine = solve_bvp(scene, tol=tol / 10.0, max_nodes=MAX_NODES, warm_start=sol, form=form,
                         own_mesh=True)
        if fine.status != "solved":
            return Estimate(math.inf, {"note": f"the comparison solve at tol = {tol / 10:.0e} "
                                               f"did not succeed ({fine.status})"})
        cache[tol / 10.0] = fine
        dforce, dpos, tmax = compare(fine, sol, "s")
        return Estimate(max(dforce / tmax, dpos / sol.length), {
            "method": f"difference from a solve at tol = {tol / 10:.0e} started on this "
                      f"solution's mesh ({sol.s.size} -> {fine.s.size} nodes)",
            "force_N": dforce, "position_m": dpos})

    def finer(tol: float, est: Estimate) -> tuple[float | None, str]:
        if tol / 10.0 < TOL_FLOOR * (1.0 - 1e-9):
            return None, (f"tol = {tol:.0e} is solve_bvp's floor here (TOL_FLOOR = "
                          f"{TOL_FLOOR:.0e}: tighter requests stall its mesh refinement)")
        return tol / 10.0, ""

    def describe(tol: float) -> dict[str, Any]:
        out: dict[str, Any] = {"tolerance": tol}
        if tol in cache:
            out["intervals"] = int(cache[tol].s.size - 1)
        return out

    sol = refine_to_accuracy(scene, "solve_bvp", max(scene.solver.tolerance, TOL_FLOOR),
                             solve_at, estimate, finer, warm_start=None, describe=describe,
                             label=lambda tol: f"tol = {tol:.0e}")
    return seabed_check(scene, sol, "solve_bvp")


register("solve_bvp", solve)
