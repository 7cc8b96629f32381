"""The a-posteriori error estimate of a statics solution on a collocation mesh.

The discretisation error: the line is solved again on N/2 and N/4 intervals (warm-started
from the fine solution, by the same scene's solvers on the coarser meshes, built once and
shared) and Richardson's formula is applied with the observed order
(:func:`richardson_estimate`). The iterate's own algebraic error, which the comparison of
meshes cannot see, is added (:func:`algebraic_error`); above ``solver.accuracy`` the
solution is ``"inaccurate"`` and says which of the two dominates
(:func:`apply_error_estimate`).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from cable_ocp.scene import Scene
from cable_ocp.statics.solution import StaticsSolution

if TYPE_CHECKING:
    from cable_ocp.statics.line_solver import StaticsSolver

__all__ = ["algebraic_error", "apply_error_estimate", "coarse_solver", "richardson_estimate"]


def coarse_solver(solver: StaticsSolver, level: int) -> StaticsSolver:
    """The solver of the same scene on N / 2**level intervals (built on first use, kept
    in the solvers' shared cache).

    Parameters
    ----------
    solver : StaticsSolver
        The solver on the fine mesh (N intervals).
    level : int
        1 for N/2, 2 for N/4.
    """
    return solver.on_intervals(solver.mesh.intervals // 2**level)


def apply_error_estimate(solver: StaticsSolver, sol: StaticsSolution, scene: Scene,
                         current_scale: float, w: np.ndarray, p: np.ndarray) -> None:
    """Estimate the error of a successful solve and mark it ``"inaccurate"`` above
    ``solver.accuracy`` (in place).

    Parameters
    ----------
    solver : StaticsSolver
        The solver that produced ``sol``.
    sol : StaticsSolution
        Its solution (``error_estimate``, ``status``, ``message`` and the diagnostics'
        ``error_estimate_detail`` are set here).
    scene : Scene
        The scene solved.
    current_scale : float
        The current scale of the solve (the coarse solves use the same).
    w : ndarray
        The solution's scaled unknowns.
    p : ndarray
        The solve's parameter vector.
    """
    richardson_estimate(solver, sol, scene, current_scale)
    if sol.error_estimate is not None:
        # the iterate's own (algebraic) error, from one Newton correction: the
        # estimate stays true whatever solver.tolerance allowed
        alg = algebraic_error(solver, w, p, sol)
        sol.error_estimate += alg
        sol.diagnostics["error_estimate_detail"]["algebraic"] = alg
    if sol.error_estimate is not None and sol.error_estimate > scene.solver.accuracy:
        alg = sol.diagnostics["error_estimate_detail"].get("algebraic", 0.0)
        sol.status = "inaccurate"
        if alg > 0.5 * sol.error_estimate:
            sol.diagnostics["algebraic_error_dominates"] = True
            sol.message = (
                f"the iterate's algebraic error {alg:.1e} (one more Newton correction) "
                f"exceeds solver.accuracy = {scene.solver.accuracy:.0e}: lower "
                f"solver.tolerance = {scene.solver.tolerance:.0e}")
        else:
            sol.message = (
                f"converged, but the discretisation error estimate "
                f"{sol.error_estimate:.1e} exceeds solver.accuracy = "
                f"{scene.solver.accuracy:.0e}; increase solver.intervals")


def algebraic_error(solver: StaticsSolver, w: np.ndarray, p: np.ndarray,
                    sol: StaticsSolution) -> float:
    """Relative change of the end forces, positions and length under one more Newton
    correction -J(w)^-1 g(w) at the returned iterate (0 for a converged one): the
    algebraic part of the error, which the mesh comparison cannot see.

    Parameters
    ----------
    solver : StaticsSolver
        The solver that produced ``sol``.
    w : ndarray
        The solution's scaled unknowns.
    p : ndarray
        The solve's parameter vector.
    sol : StaticsSolution
        The solution (its largest tension and length scale the changes).
    """
    dw = solver.newton_correction(w, p)
    if not np.all(np.isfinite(dw)):
        return math.inf
    r0, t0, l0, _ = solver.coll.unpack(w, p)
    r1, t1, l1, _ = solver.coll.unpack(w + dw, p)
    tmax, length = max(sol.max_tension, 1e-300), max(sol.length, 1e-300)
    return float(max(np.max(np.abs(t1 - t0)) / tmax, np.max(np.abs(r1 - r0)) / length,
                     abs(l1 - l0) / length))


def _differences(fine: StaticsSolution, coarse: StaticsSolution, solver: StaticsSolver
                 ) -> tuple[float, float]:
    """End-force and position differences. Positions are compared at every node of the
    finer solution (interior collocation points included: they converge only at the
    stage order d + 1), against the coarser solution's collocation polynomials;
    multiple-shooting solutions at their common nodes."""
    dforce = max(np.max(np.abs(fine.force_a - coarse.force_a)),
                 np.max(np.abs(fine.force_b - coarse.force_b)))
    fo, co = fine.node_offset, coarse.node_offset
    fpos, cpos = fine.position[fo:], coarse.position[co:]
    if solver.mesh.degree >= 1:
        g = fine.grounded_length
        sig = solver.coll.sigma_of_s(fine.s[fo:], fine.length, g)
        dpos = np.max(np.abs(fpos - solver.coll.interpolate(cpos, sig)))
    else:
        dpos = np.max(np.abs(fpos[::2] - cpos))
    return float(dforce), max(float(dpos), abs(fine.length - coarse.length),
                              abs(fine.grounded_length - coarse.grounded_length))


def richardson_estimate(solver: StaticsSolver, sol: StaticsSolution, scene: Scene,
                        current_scale: float) -> None:
    """Richardson estimate with the observed order (sets ``sol.error_estimate`` and the
    diagnostics' ``error_estimate_detail``).

    With x_N, x_{N/2}, x_{N/4} the end forces and mesh-point positions on three nested
    meshes, the observed order is q = log2(|x_{N/2} - x_{N/4}| / |x_N - x_{N/2}|),
    clipped to [1, p] (p the scheme's nominal order), and the error of x_N is estimated
    as |x_N - x_{N/2}| / (2^q - 1). Using q rather than p keeps the estimate honest
    where a kink in the drag (a flow component changing sign) lowers the order.
    With fewer than 4 intervals, or when the N/4 solve fails, only two meshes are
    used, with q = min(p, d + 1) (the stage order, which the interior points follow).

    Parameters
    ----------
    solver : StaticsSolver
        The solver on the fine mesh, which produced ``sol``.
    sol : StaticsSolution
        The fine solution.
    scene : Scene
        The scene solved.
    current_scale : float
        The current scale of the solve.
    """
    n = solver.mesh.intervals
    if n < 2:
        sol.diagnostics["error_estimate_detail"] = {"note": "needs at least 2 intervals"}
        return
    levels = 2 if n >= 4 else 1
    sols = [sol]
    for lev in range(1, levels + 1):
        c = coarse_solver(solver, lev).solve_unchecked(scene, warm_start=sols[-1],
                                                       error_estimate=False,
                                                       current_scale=current_scale)
        if not c.success:
            if lev == 1:
                sol.diagnostics["error_estimate_detail"] = {
                    "note": f"coarse solve failed: {c.message}"}
                return
            levels = 1  # fall back to two meshes and the nominal order
            break
        sols.append(c)

    d1 = _differences(sols[0], sols[1], coarse_solver(solver, 1))
    p = solver.mesh.order
    # two meshes only: assume the order of the slowest-converging quantity compared,
    # the stage order d + 1 of the interior collocation points (not the mesh order)
    q = float(min(p, solver.mesh.degree + 1) if solver.mesh.degree >= 1 else p)
    if levels == 2:
        d2 = _differences(sols[1], sols[2], coarse_solver(solver, 2))
        rel1 = max(d1[0] / sol.max_tension, d1[1] / sol.length)
        rel2 = max(d2[0] / sol.max_tension, d2[1] / sol.length)
        if rel1 > 0 and rel2 > 0:
            q = float(np.clip(np.log2(rel2 / rel1), 1.0, p))
    factor = 1.0 / (2.0**q - 1.0)
    force_n, pos_m = factor * d1[0], factor * d1[1]
    sol.error_estimate = max(force_n / sol.max_tension, pos_m / sol.length)
    sol.diagnostics["error_estimate_detail"] = {
        "force_N": force_n, "position_m": pos_m, "observed_order": q,
        "method": f"Richardson, N={n}/{n // 2}" + (f"/{n // 4}" if levels == 2 else "")
                  + f", observed order {q:.2f} (nominal {p})",
    }
