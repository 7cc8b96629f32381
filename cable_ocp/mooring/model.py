"""The state of a mooring system, its net loads and their exact Jacobian.

The unknowns are the positions of the free points and the poses of the bodies. Every
line is solved with both ends held where the state puts them, warm-started from its last
solution, by one of two line models (``[system] line_model``, docs/systems.md): where the
closed-form elastic catenary is exact (no current, one line type, no bending stiffness, a
flat seabed z = 0 or none: :func:`cable_ocp.statics.catenary_line.catenary_exact`) by it
(:func:`cable_ocp.statics.catenary_line.solve_catenary_scene`, Newton from the line's last
(H, V_b); should it fail, the collocation takes that solve), else as the collocation BVP
(:class:`cable_ocp.statics.solver.SolveSession`). Either gives the end forces and their
exact 6x6 Jacobian in the end positions
(:meth:`cable_ocp.statics.solution.StaticsSolution.end_jacobian`). Assembly
(docs/systems.md, "Formulation"): an end e of a line on an entity moves by
dr_e = T_e dq, T_e = I for a free point and T_e = [I, -[rho_e]x] for a point of a body
(rho_e = R r_e, dq = (dx, dtheta), dtheta small rotations about the fixed axes); the
entity's generalised load is Q = sum_e T_e^T F_e + its own load, and

    dQ/dq = sum_{e,e'} T_e^T K_ee' T_e' + sum_e [F_e]x [rho_e]x (bodies) + own loads,

the second sum being the geometric term of the rotations, the only part of the body's
matrix that is not symmetric when the lines are conservative: its antisymmetric part is
-(1/2)[M]x, M the lines' moment on the body about its reference point.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics.rotation import (
    euler_rate_derivatives,
    euler_rate_matrix,
    rotation_matrix,
    skew,
)
from cable_ocp.physics.hydrostatics import body_load, load_jacobian
from cable_ocp.scene import End
from cable_ocp.scene.system import SystemLine, SystemScene
from cable_ocp.statics.catenary_line import catenary_exact, solve_catenary_scene
from cable_ocp.statics.solution import StaticsSolution
from cable_ocp.statics.solver import SolveSession

__all__ = ["Evaluation", "State", "SystemModel"]

_EZ = np.array([0.0, 0.0, 1.0])


@dataclass
class State:
    """Positions of the free points (m) and poses of the bodies (m; rad, roll-pitch-yaw).

    Attributes
    ----------
    points : dict
        Free point name -> position (3,), m.
    bodies : dict
        Body name -> pose (6,): reference point (m) and (roll, pitch, yaw) (rad).
    """

    points: dict[str, np.ndarray]
    bodies: dict[str, np.ndarray]

    def copy(self) -> State:
        """A deep copy."""
        return State({k: v.copy() for k, v in self.points.items()},
                     {k: v.copy() for k, v in self.bodies.items()})


@dataclass
class Evaluation:
    """Everything at one state: the line solutions, the entities' net loads and the
    Jacobian of those loads in the small coordinates.

    Attributes
    ----------
    state : State
        The state evaluated.
    lines : list
        One :class:`StaticsSolution` per line (in the scene's orientation: ``end_a`` at
        the line's lower end, ``SystemLine.reversed``).
    ok : bool
        Every line solve converged (its forces may be used by the iteration).
    message : str
        Why not, when ``ok`` is False.
    end_forces : list
        Per line, (F at point_a, F at point_b): the forces the line exerts on its two
        points, N.
    q : ndarray
        Net loads on the entities in the small coordinates: per free point its force
        (N), per body [F; M] (N, N m about its reference point).
    jac : ndarray or None
        dq/d(small coordinates), without the bodies' own loads (``own``).
    own : dict
        Body name -> the 6x6 Jacobian of its own load (:func:`load_jacobian`).
    geometric : dict
        Body name -> the 6x6 geometric part of the lines' Jacobian on it.
    line_loads : dict
        Body name -> [F; M] of the lines alone on it (N, N m).
    """

    state: State
    lines: list[StaticsSolution]
    ok: bool
    message: str = ""
    #: why a converged line is not a solution (e.g. it passes below the seabed, where
    #: contact is not modelled), "" when every line is
    unphysical: str = ""
    end_forces: list[tuple[np.ndarray, np.ndarray]] = field(default_factory=list)
    q: np.ndarray | None = None
    jac: np.ndarray | None = None
    own: dict[str, np.ndarray] = field(default_factory=dict)
    geometric: dict[str, np.ndarray] = field(default_factory=dict)
    line_loads: dict[str, np.ndarray] = field(default_factory=dict)


class SystemModel:
    """A system's lines, each with its solver session, and the assembly of its loads.

    Parameters
    ----------
    scene : SystemScene
        The validated system.
    skip : set of str, optional
        Names of lines left out (a failed line: the line-failure check).
    """

    def __init__(self, scene: SystemScene, skip: set[str] | None = None) -> None:
        self.scene = scene
        self.env = scene.environment
        self.lines = [ln for ln in scene.lines if ln.name not in (skip or set())]
        #: the built line solvers, by structure, shared by the lines' sessions
        self.solvers: dict[tuple, Any] = {}
        self.sessions = [SolveSession(error_estimate=False, solvers=self.solvers)
                         for _ in self.lines]
        self.points = {p.name: p for p in scene.points}
        self.bodies = {b.name: b for b in scene.bodies}
        #: line name -> the model of its last solve, "catenary" or "collocation"
        self.line_models: dict[str, str] = {}
        #: line name -> its last catenary solution's (H, V_b), N: the warm start
        self.catenary_starts: dict[str, tuple[float, float]] = {}
        # columns of the small coordinates: 3 per free point, 6 per body
        self.cols: dict[str, slice] = {}
        n = 0
        for p in scene.points:
            if p.kind == "free":
                self.cols[p.name] = slice(n, n + 3)
                n += 3
        for b in scene.bodies:
            self.cols[b.name] = slice(n, n + 6)
            n += 6
        self.n = n

    def update(self, scene: SystemScene) -> bool:
        """Take ``scene`` in place of this model's when only loads, masses, positions or
        poses differ (the lines keep their sessions and warm starts); False, and nothing
        changed, when its lines, points or bodies differ in structure.

        Parameters
        ----------
        scene : SystemScene
            Another case of this system (a batch's next case).
        """
        same = ([(ln.name, ln.parts, ln.point_a, ln.point_b) for ln in scene.lines
                 if ln.name in {m.name for m in self.lines}]
                == [(ln.name, ln.parts, ln.point_a, ln.point_b) for ln in self.lines]
                and scene.environment == self.env
                and [(p.name, p.kind) for p in scene.points]
                == [(p.name, p.kind) for p in self.scene.points]
                and [b.name for b in scene.bodies] == [b.name for b in self.scene.bodies])
        if same:
            keep = {ln.name for ln in self.lines}
            self.scene = scene
            self.lines = [ln for ln in scene.lines if ln.name in keep]
            self.points = {p.name: p for p in scene.points}
            self.bodies = {b.name: b for b in scene.bodies}
        return same

    # -- the state ---------------------------------------------------------------------
    def initial_state(self) -> State:
        """The file's positions and poses."""
        return State({p.name: np.array(p.position, float) for p in self.scene.points
                      if p.kind == "free"},
                     {b.name: np.array([*b.position, *b.rotation], float)
                      for b in self.scene.bodies})

    def free_dofs(self) -> np.ndarray:
        """Indices of the unknowns among the small coordinates: the free points' and the
        bodies' degrees of freedom that are not held."""
        idx: list[int] = []
        for p in self.scene.points:
            if p.kind == "free":
                idx.extend(range(self.cols[p.name].start, self.cols[p.name].stop))
        for b in self.scene.bodies:
            start = self.cols[b.name].start
            idx.extend(start + k for k in range(6) if not b.held[k])
        return np.array(idx, dtype=int)

    def position(self, name: str, state: State) -> np.ndarray:
        """Global position of a point at a state, m.

        Parameters
        ----------
        name : str
            The point.
        state : State
            The state.
        """
        p = self.points[name]
        if p.kind == "fixed":
            return np.array(p.position, float)
        if p.kind == "free":
            return state.points[name]
        pose = state.bodies[p.body]  # type: ignore[index]
        return pose[:3] + rotation_matrix(*pose[3:]) @ np.asarray(p.position, float)

    # -- evaluation ----------------------------------------------------------------------
    def solve_lines(self, state: State) -> tuple[list[StaticsSolution], bool, str]:
        """Every line solved with its ends where ``state`` puts them (warm-started).

        Parameters
        ----------
        state : State
            The state.
        """
        sols, ok, why = [], True, ""
        for line, session in zip(self.lines, self.sessions, strict=True):
            xa, xb = self.position(line.point_a, state), self.position(line.point_b, state)
            lo, hi = (xb, xa) if line.reversed else (xa, xb)
            sc = replace(line.scene, end_a=_held(lo), end_b=_held(hi))
            sol = None
            if self.uses_catenary(line):
                sol = solve_catenary_scene(sc, self.catenary_starts.get(line.name))
                if sol.converged:
                    d = sol.diagnostics
                    self.catenary_starts[line.name] = (d["horizontal_tension"],
                                                       d["vertical_force"])
                    self.line_models[line.name] = "catenary"
                else:
                    sol = None
            if sol is None:
                sol = session.solve(sc)
                self.line_models[line.name] = "collocation"
            sols.append(sol)
            if not sol.converged and ok:
                ok, why = False, f"line {line.name!r}: {sol.status} ({sol.message})"
        return sols, ok, why

    def uses_catenary(self, line: SystemLine) -> bool:
        """True when ``line`` is solved by the closed-form catenary: ``[system]
        line_model`` is "auto" and the catenary is exact for it (:func:`catenary_exact`).

        Parameters
        ----------
        line : SystemLine
            One of the model's lines.
        """
        return self.scene.line_model == "auto" and not catenary_exact(line.scene)

    def evaluate(self, state: State, jacobian: bool = True) -> Evaluation:
        """Solve the lines at ``state`` and assemble the net loads (and their Jacobian).

        Parameters
        ----------
        state : State
            The state.
        jacobian : bool
            Also assemble dq/d(small coordinates) (one sparse LU per line).
        """
        sols, ok, why = self.solve_lines(state)
        ev = Evaluation(state=state, lines=sols, ok=ok, message=why)
        bad = [(ln, sol) for ln, sol in zip(self.lines, sols, strict=True)
               if sol.converged and not sol.success]
        if bad:
            ev.unphysical = "; ".join(f"line {ln.name!r}: {sol.status} ({sol.message})"
                                      for ln, sol in bad)
        if not ok:
            return ev
        rho, g = self.env.water_density, self.env.gravity
        q = np.zeros(self.n)
        jac = np.zeros((self.n, self.n)) if jacobian else None
        for b in self.scene.bodies:
            ev.geometric[b.name] = np.zeros((6, 6))
            ev.line_loads[b.name] = np.zeros(6)
        for line, sol in zip(self.lines, sols, strict=True):
            fa, fb = (sol.force_b, sol.force_a) if line.reversed else (sol.force_a, sol.force_b)
            ev.end_forces.append((np.array(fa), np.array(fb)))
            maps = [self._end_map(line.point_a, state), self._end_map(line.point_b, state)]
            for (cols, t, arm, body), f in zip(maps, (fa, fb), strict=True):
                if cols is None:
                    continue
                q[cols] += t.T @ f
                if body is not None:
                    ev.line_loads[body] += t.T @ f
                    geo = np.zeros((6, 6))
                    geo[3:, 3:] = skew(f) @ skew(arm)
                    ev.geometric[body] += geo
                    if jac is not None:
                        jac[cols, cols] += geo
            if jac is None:
                continue
            k = sol.end_jacobian()
            if line.reversed:  # the scene's end_a is point_b
                k = k[np.ix_([3, 4, 5, 0, 1, 2], [3, 4, 5, 0, 1, 2])]
            for i, (ci, ti, _, _) in enumerate(maps):
                if ci is None:
                    continue
                for j, (cj, tj, _, _) in enumerate(maps):
                    if cj is None:
                        continue
                    block = k[3 * i: 3 * i + 3, 3 * j: 3 * j + 3]
                    if not np.all(np.isfinite(block)):
                        raise CableOCPError(
                            f"line {line.name!r} lies on the seabed at a free point or a "
                            "body: its end force is not differentiable there (one-sided "
                            "contact); hold that point, or lift it off the seabed")
                    jac[ci, cj] += ti.T @ block @ tj
        for p in self.scene.points:
            if p.kind == "free":
                q[self.cols[p.name]] += np.asarray(p.force) + (rho * p.volume - p.mass) * g * _EZ
        for b in self.scene.bodies:
            pose = state.bodies[b.name]
            r = rotation_matrix(*pose[3:])
            cols = self.cols[b.name]
            q[cols] += body_load(b, pose[:3], r, rho, g, self.env.water_depth)
            ev.own[b.name] = load_jacobian(b, pose[:3], r, rho, g)
        ev.q, ev.jac = q, jac
        return ev

    def _end_map(self, name: str, state: State
                 ) -> tuple[slice | None, np.ndarray, np.ndarray, str | None]:
        """(columns, T, arm, body) of a line end at point ``name``: dr = T dq on those
        columns (None for a fixed point); arm = R r for a body point."""
        p = self.points[name]
        if p.kind == "fixed":
            return None, np.zeros((3, 0)), np.zeros(3), None
        if p.kind == "free":
            return self.cols[name], np.eye(3), np.zeros(3), None
        pose = state.bodies[p.body]  # type: ignore[index]
        arm = rotation_matrix(*pose[3:]) @ np.asarray(p.position, float)
        return self.cols[p.body], np.hstack([np.eye(3), -skew(arm)]), arm, p.body  # type: ignore

    # -- Euler coordinates (the unknowns of the Newton iteration) --------------------------
    def euler_system(self, ev: Evaluation) -> tuple[np.ndarray, np.ndarray]:
        """(r, J) in the unknowns' coordinates: the bodies' rotations as Euler angles, so
        that a held angle stays at its value. r = T^T q (the moment projected on the
        Euler axes), J = T^T (dq/dq_small) T + (dE/d angle)^T M, exactly.

        Parameters
        ----------
        ev : Evaluation
            An evaluation with its Jacobian.
        """
        t = np.eye(self.n)
        extra = np.zeros((self.n, self.n))
        full = ev.jac.copy()  # type: ignore[union-attr]
        for b in self.scene.bodies:
            c = self.cols[b.name]
            full[c, c] += ev.own[b.name]
            pose = ev.state.bodies[b.name]
            e = euler_rate_matrix(*pose[3:])
            rot = slice(c.start + 3, c.stop)
            t[rot, rot] = e
            d = euler_rate_derivatives(pose[4], pose[5])
            m = ev.q[rot]  # type: ignore[index]
            for k in range(3):
                extra[rot, c.start + 3 + k] = d[k].T @ m
        r = t.T @ ev.q
        return r, t.T @ full @ t + extra


def _held(x: np.ndarray) -> End:
    """An end held at ``x`` (m)."""
    pos = tuple(float(v) for v in x)
    return End(position=pos, force=(None, None, None))  # type: ignore[arg-type]


def condensed(jac: np.ndarray, keep: np.ndarray, eliminate: np.ndarray) -> np.ndarray:
    """The Schur complement J_kk - J_ke J_ee^-1 J_ek: the Jacobian in the kept
    coordinates when the eliminated ones stay in equilibrium.

    Parameters
    ----------
    jac : ndarray
        The full Jacobian.
    keep, eliminate : ndarray
        Index arrays.
    """
    jkk = jac[np.ix_(keep, keep)]
    if eliminate.size == 0:
        return jkk
    jee = jac[np.ix_(eliminate, eliminate)]
    return jkk - jac[np.ix_(keep, eliminate)] @ np.linalg.solve(
        jee, jac[np.ix_(eliminate, keep)])


def describe(model: SystemModel) -> dict[str, Any]:
    """Counts of the system's parts (for diagnostics).

    Parameters
    ----------
    model : SystemModel
        The model.
    """
    sc = model.scene
    return {"lines": len(model.lines), "points": len(sc.points),
            "free_points": sum(p.kind == "free" for p in sc.points),
            "bodies": len(sc.bodies), "unknowns": int(model.free_dofs().size)}
