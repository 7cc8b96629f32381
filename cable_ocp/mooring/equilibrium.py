"""The static equilibrium of a mooring system, and its 6x6 stiffness.

Newton's method on the net loads of the free points and bodies (:mod:`.model`), the
bodies' rotations as Euler angles (a held angle keeps its value), with the exact
Jacobian assembled from the lines' end Jacobians: each step solves every line once
(warm-started) and factorises each line's collocated Jacobian once. A backtracking line
search on the 2-norm of the scaled residual (forces over the largest tension, moments
also over a length of the system) halves the step where it does not decrease, where a
line fails, or where a line leaves the water column (passes below the seabed) when the
iterate before did not.

Why a nested solve and not one NLP for the whole system: each line keeps the solver
that exists (contact switching at the touchdown, the warm starts, the fallbacks and the
a-posteriori error estimate), the system's Newton matrix is small and dense (3 per free
point, 6 per body), and the end Jacobians are exact, so the outer iteration converges
quadratically; the same Jacobians give the 6x6 stiffness at the end at no extra cost.

The stiffness (CONVENTIONS "Mooring systems"): K = -d[F; M]/d[x; theta] of the mooring's
load on the body, theta small rotations about the fixed axes at the pose, M about the
reference point, the free points and the other bodies' free degrees of freedom in
equilibrium (a Schur complement). Its parts: ``elastic`` (the lines' end stiffness
carried to the reference point, symmetric for conservative lines: no current, no seabed
friction) and ``geometric`` (-[F_e]x [rho_e]x summed over the fairleads: the
rotation of the arms under a load, whose antisymmetric part is (1/2)[M]x with M the
mooring's moment on the body). So K is symmetric exactly when the lines are conservative
and their net moment on the body about its reference point is zero.
"""

from __future__ import annotations

import time

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.mooring.model import Evaluation, State, SystemModel
from cable_ocp.mooring.result import SystemResult, build_result
from cable_ocp.numerics import interrupt
from cable_ocp.scene.system import DOF_NAMES, SystemScene

__all__ = ["solve_system"]

#: the largest Newton step of a point or body translation, as a fraction of the shortest
#: line, and of a rotation, rad
STEP_FRACTION = 0.1
STEP_ROTATION = 0.1
#: step halvings of the line search
HALVINGS = 12


def _scales(model: SystemModel, ev: Evaluation) -> np.ndarray:
    """Per unknown, the force (N) or moment (N m) that counts as 1 in the residual."""
    tens = max([float(np.linalg.norm(f)) for pair in ev.end_forces for f in pair] + [1.0])
    length = max(ln.length for ln in model.lines)
    s = np.full(model.n, tens)
    for b in model.scene.bodies:
        c = model.cols[b.name]
        s[c.start + 3: c.stop] = tens * length
    return s


def _step_limit(model: SystemModel, dx: np.ndarray) -> float:
    """The factor (<= 1) that keeps a Newton step within :data:`STEP_FRACTION` of the
    shortest line in translation and :data:`STEP_ROTATION` in rotation."""
    lmin = min(ln.length for ln in model.lines)
    trans = np.ones(model.n, bool)
    for b in model.scene.bodies:
        c = model.cols[b.name]
        trans[c.start + 3: c.stop] = False
    biggest = max(float(np.max(np.abs(dx[trans]), initial=0.0)) / (STEP_FRACTION * lmin),
                  float(np.max(np.abs(dx[~trans]), initial=0.0)) / STEP_ROTATION, 1.0)
    return 1.0 / biggest


def _moved(model: SystemModel, state: State, dx: np.ndarray) -> State:
    """``state`` moved by ``dx`` (the unknowns' coordinates: Euler angles)."""
    new = state.copy()
    for name in new.points:
        new.points[name] = new.points[name] + dx[model.cols[name]]
    for name in new.bodies:
        new.bodies[name] = new.bodies[name] + dx[model.cols[name]]
    return new


def _no_restoring(model: SystemModel, jac: np.ndarray, free: np.ndarray,
                  scale: np.ndarray) -> str:
    """The unknown with no restoring, when the Newton matrix (forces and moments over
    their scales, displacements in m and rad) is singular to 1e-12 of its largest
    singular value: the largest component of the null vector; "" when it is regular."""
    names = []
    for p in model.scene.points:
        if p.kind == "free":
            names += [f"point {p.name!r} {c}" for c in "xyz"]
    for b in model.scene.bodies:
        names += [f"body {b.name!r} {d}" for d in DOF_NAMES]
    sub = jac[np.ix_(free, free)] / scale[free][:, None]
    _, sv, vt = np.linalg.svd(sub)
    if sv[-1] > 1e-12 * sv[0]:
        return ""
    return names[free[int(np.argmax(np.abs(vt[-1])))]]


def solve_system(scene: SystemScene, model: SystemModel | None = None,
                 start: State | None = None, stiffness: bool = True) -> SystemResult:
    """The static equilibrium of a system: the free points and the bodies' free degrees
    of freedom in balance, every line solved with its current, seabed and parts.

    Parameters
    ----------
    scene : SystemScene
        The system.
    model : SystemModel, optional
        A model of this scene to reuse (its lines warm-start from their last solutions);
        None: built here.
    start : State, optional
        The first guess; None: the file's positions and poses (or the model's last state).
    stiffness : bool
        Also compute each body's 6x6 stiffness at the equilibrium.

    Returns
    -------
    SystemResult
        ``status`` "solved" only when the residual is within ``scene.tolerance``.
    """
    t0 = time.perf_counter()
    model = model or SystemModel(scene)
    if not model.lines:
        raise CableOCPError("the system has no line left: nothing holds its points and bodies")
    state = start.copy() if start is not None else model.initial_state()
    free = model.free_dofs()
    ev = model.evaluate(state)
    history: list[float] = []
    status, message, it = "failed", "", 0
    if not ev.ok:
        return build_result(model, ev, "failed", f"at the first guess: {ev.message}", 0,
                            history, time.perf_counter() - t0, stiffness=False)
    while True:
        r, jac = model.euler_system(ev)
        scale = _scales(model, ev)
        err = float(np.max(np.abs(r[free]) / scale[free], initial=0.0))
        history.append(err)
        if err <= scene.tolerance:
            status, message = "solved", f"equilibrium in {it} Newton steps"
            if ev.unphysical:
                status = "failed"
                message = (f"an equilibrium in {it} Newton steps, but not a solution: "
                           f"{ev.unphysical}")
            break
        if it >= scene.max_iterations:
            message = (f"no equilibrium in system.max_iterations = {scene.max_iterations} "
                       f"Newton steps (scaled residual {err:.3g})")
            break
        sub = jac[np.ix_(free, free)]
        why = _no_restoring(model, jac, free, scale)
        if why:
            raise CableOCPError(
                f"{why} has no restoring: nothing resists a displacement in it (no line "
                "stiffness, no hydrostatics); hold it (bodies[].held) or add a line")
        try:
            step = np.linalg.solve(sub, -r[free])
        except np.linalg.LinAlgError:
            message = "the Newton matrix is singular (a degree of freedom without restoring)"
            break
        dx = np.zeros(model.n)
        dx[free] = step * _step_limit(model, _full(model.n, free, step))
        # the merit is the 2-norm of the scaled residual (the Newton step is a descent
        # direction for it, not for the largest entry), on this step's scales
        merit = float(np.linalg.norm(r[free] / scale[free]))
        alpha, accepted = 1.0, False
        for _ in range(HALVINGS):
            interrupt.check()
            trial = model.evaluate(_moved(model, state, alpha * dx))
            # a trial whose lines leave the water column is no better iterate, unless the
            # iteration is not yet out of such states itself
            if trial.ok and (not trial.unphysical or ev.unphysical):
                rt = _residual(model, trial)
                if float(np.linalg.norm(rt[free] / scale[free])) < \
                        (1.0 - 1e-4 * alpha) * merit:
                    accepted = True
                    break
            alpha /= 2.0
        it += 1
        if not accepted:
            message = (f"the line search found no decrease of the residual after "
                       f"{HALVINGS} halvings (scaled residual {err:.3g})"
                       + (f"; {trial.message}" if not trial.ok else ""))
            break
        state, ev = trial.state, trial
    wall = time.perf_counter() - t0
    return build_result(model, ev, status, message, it, history, wall,
                        stiffness=stiffness and status == "solved")


def _full(n: int, idx: np.ndarray, values: np.ndarray) -> np.ndarray:
    out = np.zeros(n)
    out[idx] = values
    return out


def _residual(model: SystemModel, ev: Evaluation) -> np.ndarray:
    """The residual in the unknowns' coordinates (no Jacobian needed)."""
    q = ev.q.copy()  # type: ignore[union-attr]
    from cable_ocp.numerics.rotation import euler_rate_matrix

    for b in model.scene.bodies:
        c = model.cols[b.name]
        rot = slice(c.start + 3, c.stop)
        q[rot] = euler_rate_matrix(*ev.state.bodies[b.name][3:]).T @ q[rot]
    return q
