"""scipy.integrate.solve_bvp on the same equations as the collocation solver.

The outside reference a user would reach for: the same right-hand side (the scene's
:class:`~cable_ocp.statics.formulation.Formulation`, evaluated column-wise), the same end
conditions, scaled variables, the scaled length as an unknown parameter when it is free.
solve_bvp uses 4th-order Lobatto IIIA collocation with residual-based mesh refinement.
"""

from __future__ import annotations

import time

import numpy as np
from scipy.integrate import solve_bvp as _scipy_solve_bvp

from cable_ocp.baselines.common import seabed_check
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
              form: Formulation | None = None) -> StaticsSolution:
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
    """
    form = Formulation(scene) if form is None else form
    p = form.params(scene)
    sc = form.scales
    free = scene.free_length
    t0 = time.perf_counter()
    if warm_start is not None:
        src, idx = np.unique(warm_start.s / warm_start.length, return_index=True)
        sig = np.linspace(0.0, 1.0, nodes)
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


def solve(scene: Scene, warm_start: StaticsSolution | None = None) -> StaticsSolution:
    """Registry entry (``solver.method = "solve_bvp"``): ``solver.intervals + 1`` initial
    nodes, solve_bvp's tolerance = ``solver.tolerance`` but not below 1e-9 (tighter
    requests stall its mesh refinement). It has no seabed contact: a profile through a
    modelled seabed is reported as ``"seabed_contact"``."""

    sol = solve_bvp(scene, nodes=scene.solver.intervals + 1,
                    tol=max(scene.solver.tolerance, 1e-9), max_nodes=10000,
                    warm_start=warm_start)
    return seabed_check(scene, sol, "solve_bvp")


register("solve_bvp", solve)
