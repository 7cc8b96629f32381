"""The :class:`~cable_ocp.statics.solution.StaticsSolution` of a discretised line.

From a statics solver's unknowns at the end of a solve: the node arrays (with the nodes of
a grounded part prepended, :func:`cable_ocp.physics.seabed.grounded_nodes`), the status
from the residual at the returned point (only a residual within tolerance is
``"solved"``), and the diagnostics every solve reports: touchdown, smoothing-force bound,
lowest point and seabed gap, warnings, the bodies and joints of a multi-segment line (and
its free-surface check), the bending state of stiff segments.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from cable_ocp.physics import seabed
from cable_ocp.statics.formulation import P_CURRENT
from cable_ocp.statics.solution import StaticsSolution

if TYPE_CHECKING:
    from cable_ocp.statics.line_solver import StaticsSolver

__all__ = ["assemble_solution"]


def assemble_solution(solver: StaticsSolver, w: np.ndarray, p: np.ndarray, g: np.ndarray,
                      ok: bool, how: str, it: int, wall: float, diag: dict[str, Any]
                      ) -> StaticsSolution:
    """The solution of ``solver`` at the unknowns ``w``.

    Parameters
    ----------
    solver : StaticsSolver
        The solver (its scene, formulation, transcription, mesh and tolerance).
    w : ndarray
        Scaled unknowns returned by the solve.
    p : ndarray
        The residual's parameter vector of the solve.
    g : ndarray
        The residual at ``w`` (scaled).
    ok : bool
        The iteration reported success.
    how : str
        Which solver did it (for the message).
    it : int
        Iterations taken.
    wall : float
        Solve time, s.
    diag : dict
        Diagnostics so far (completed here).

    Returns
    -------
    StaticsSolution
        ``"solved"`` only when the iteration succeeded, the iterate is finite and the
        scaled residual is within 10 x tolerance.
    """
    scene, form, coll, tol = solver.scene, solver.form, solver.coll, solver.tol
    viol = float(np.max(np.abs(g))) if np.all(np.isfinite(g)) else math.inf
    r, t, length, g_len = coll.unpack(w, p)
    s = coll.node_s(length, g_len)
    finite = bool(np.all(np.isfinite(w)))
    offset = 0
    if solver.grounded and finite:
        sb, cab = scene.environment.seabed, scene.cable
        tmag0 = float(np.linalg.norm(t[0]))
        e = t[0] / tmag0
        k = float(seabed.axial_gradient(sb, cab.weight_in_water, e))
        anchor = np.asarray(scene.end_a.position, dtype=float)
        ng = max(2, min(41, int(np.ceil(g_len / max(length, 1e-12) * len(s))) + 1))
        sg, rg, tg = seabed.grounded_nodes(anchor, e, tmag0, k, max(g_len, 0.0),
                                           cab.axial_stiffness, ng)
        s, r, t = (np.concatenate([sg[:-1], s]), np.vstack([rg[:-1], r]),
                   np.vstack([tg[:-1], t]))
        offset = ng - 1
        diag["touchdown"] = {"position": [float(v) for v in r[offset]],
                             "grounded_length": float(g_len)}
    elif scene.environment.seabed is not None:
        diag["touchdown"] = None
    tol_ok = viol <= 10.0 * tol
    if ok and finite and tol_ok:
        status, msg = "solved", f"converged ({how}), max scaled residual {viol:.2e}"
    elif not finite:
        status, msg = "failed", f"non-finite iterate ({how})"
    elif ok and not tol_ok:
        status, msg = "failed", (
            f"solver reported success ({how}) but the scaled residual {viol:.2e} "
            f"exceeds 10 x tolerance {tol:.1e}")
    else:
        status, msg = "failed", f"did not converge ({how}); max scaled residual {viol:.2e}"
    sol = StaticsSolution(status=status, message=msg, s=s, position=r, tension_vector=t,
                          length=length, iterations=it, wall_time_s=wall,
                          constraint_violation=viol, diagnostics=diag, node_offset=offset)
    tmax = float(np.max(np.linalg.norm(t, axis=1))) if finite else math.nan
    diag["smoothing_force_bound_N"] = form.smoothing_force_bound(length, tmax)
    diag["min_z"] = float(np.min(r[:, 2])) if finite else math.nan
    warnings = []
    sb = scene.environment.seabed
    if finite and sb is not None:
        diag["min_gap"] = float(np.min(seabed.gap(sb, r)))
    if finite and np.min(np.linalg.norm(t, axis=1)) <= 0.0:
        warnings.append("tension vanishes somewhere along the cable")
    diag["warnings"] = warnings
    if form.segmented and finite:
        _segment_diagnostics(solver, sol, r, offset, p)
    bend = coll.unpack_bending(w)
    if bend is not None:
        bend = np.vstack([np.zeros((offset, 2)), bend])  # grounded nodes: no bending
        # per node: tangent angle from +x towards +z (rad) and bending moment (N m);
        # zeros on flexible segments (planar beam-cable, formulation module)
        diag["bending"] = {"angle_rad": bend[:, 0].tolist(), "moment_Nm": bend[:, 1].tolist()}
        # axial force T . t on the stiff segments (T carries the shear there too):
        # a stiff segment in compression may sit on an unstable branch (an inverted
        # column), which a statics solve cannot tell from a stable one
        ang = bend[:, 0]
        axial = t[:, 0] * np.cos(ang) + t[:, 2] * np.sin(ang)
        on_stiff = np.zeros(len(axial), dtype=bool)
        offs = solver.mesh.segment_offsets()
        for k, stiff in enumerate(form.stiff):
            if stiff:
                on_stiff[offset + offs[k]: offset + offs[k + 1]] = True
        # tangent at an end on a stiff segment (T carries shear there, so T/|T| is not
        # the tangent): from theta (StaticsSolution.end_tangent)
        diag["end_tangents"] = {
            key: [math.cos(ang[i]), 0.0, math.sin(ang[i])] if on_stiff[i] else None
            for key, i in (("a", 0), ("b", len(ang) - 1))}
        worst = float(np.min(axial[on_stiff])) if on_stiff.any() else 0.0
        diag["bending"]["min_axial_force_N"] = worst
        if worst < -1e-6 * max(tmax, 1.0):
            warnings.append(
                f"a stiff segment carries {-worst:.4g} N of compression: this equilibrium "
                "may be unstable (e.g. an inverted column); check the branch")
    return sol


def _segment_diagnostics(solver: StaticsSolver, sol: StaticsSolution, r: np.ndarray,
                         offset: int, p: np.ndarray) -> None:
    """Per-body loads at the joints, and the free-surface check: a multi-segment line
    (a buoy may lift it) that would leave the water is a failure, never a profile."""
    diag, scene, form = sol.diagnostics, solver.scene, solver.form
    offs = solver.mesh.segment_offsets()
    bodies = []
    for i, body in enumerate(scene.bodies):
        pos = r[offset + offs[body.joint] - 1]
        force = form.body_load(i, pos, float(p[P_CURRENT]))
        bodies.append({"joint": body.joint, "kind": body.kind,
                       "position": [float(v) for v in pos],
                       "force": [float(v) for v in force]})
    diag["bodies"] = bodies
    diag["joints"] = [[float(v) for v in r[offset + offs[k] - 1]]
                      for k in range(1, len(offs) - 1)]
    first = scene.segments[0].length
    if sol.status in ("solved", "inaccurate") and sol.grounded_length >= first:
        sol.status = "failed"
        sol.message = (
            f"the grounded length {sol.grounded_length:.6g} m reaches beyond the first "
            f"segment (cable.segments[0].length = {first:g} m); contact of later "
            "segments and bodies with the seabed is not modelled")

