"""Optimisation through the statics: decision variables and an objective on top of the
collocated cable equations (which MoorPy, MoorDyn and OrcaFlex do not offer).

Because a statics solve is an NLP, scene parameters can become decision variables of a
larger NLP whose equality constraints are the collocation equations
(:class:`~cable_ocp.statics.collocation.Collocation`); IPOPT (exact Hessian) solves it.

Decision variables are named scene parameters, each with bounds:

* ``"cable.length"`` (m, when the length is fixed in the scene),
* ``"end_a.force.x"`` ... ``"end_b.force.z"`` (N; components whose force is prescribed),
* ``"end_a.position.x"`` ... (m; components whose position is prescribed),
* ``"tension"`` (N, when the scene prescribes an end tension).

The objective and extra constraints are written by the user as functions of a
:class:`View`: CasADi expressions for the node positions and tension vectors (physical
units), the length, the end forces (the force the cable exerts on each attachment) and the
decision variables. Example: the length that minimises the top tension with the whole cable
above the seabed::

    nlp = StaticsNLP(scene, {"cable.length": (296.0, 400.0)})
    res = nlp.solve(lambda v: ca.sumsqr(v.force_b) / 1e6,
                    lambda v: [(v.position[:, 2], 0.0, np.inf)])
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import interrupt
from cable_ocp.numerics.export import summary_repr
from cable_ocp.scene import Scene
from cable_ocp.statics.collocation import Collocation
from cable_ocp.statics.formulation import (
    NX,
    P_END_A,
    P_END_B,
    P_LENGTH,
    P_TENSION,
    Formulation,
)
from cable_ocp.statics.line_solver import StaticsSolver
from cable_ocp.statics.solution import StaticsSolution
from cable_ocp.status import Status, from_ipopt

__all__ = ["OptimizationResult", "StaticsNLP", "View"]

_AXES = {"x": 0, "y": 1, "z": 2}


@dataclass
class View:
    """Symbolic view of the statics unknowns for objectives and constraints.

    Attributes
    ----------
    position, tension_vector : casadi.MX, shape (n, 3)
        Node positions (m) and tension vectors (N), from end_a to end_b.
    length : casadi.MX
        Unstretched cable length, m.
    force_a, force_b : casadi.MX, shape (3, 1)
        Forces the cable exerts on the end_a / end_b attachments, N.
    var : dict of casadi.MX
        The decision variables by name, in physical units.
    theta : casadi.MX
        User parameters of a built NLP (see :meth:`StaticsNLP.build`).
    """

    position: Any
    tension_vector: Any
    length: Any
    force_a: Any
    force_b: Any
    var: dict[str, Any] = field(default_factory=dict)
    theta: Any = None


@dataclass
class OptimizationResult:
    """Outcome of :meth:`StaticsNLP.solve`.

    Attributes
    ----------
    status : Status
        ``"solved"``, or IPOPT's failure in the package's vocabulary
        (:func:`cable_ocp.status.from_ipopt`: ``"infeasible"``, ``"max_iterations"``,
        ``"interrupted"``, ``"failed"``); IPOPT's own string is in the solution's message.
    variables : dict
        Optimal decision variables, physical units.
    objective : float
        Objective at the optimum.
    solution : StaticsSolution
        The cable at the optimum (its status mirrors this one).
    iterations : int
    wall_time_s : float
    """

    status: Status
    variables: dict[str, float]
    objective: float
    solution: StaticsSolution
    iterations: int
    wall_time_s: float

    @property
    def success(self) -> bool:
        """True when IPOPT converged to a (local) optimum."""
        return self.status == "solved"

    def __repr__(self) -> str:
        """A few lines: the status, the objective, the optimal variables (physical units,
        see the module docstring) and the cable's largest tension."""
        return summary_repr(
            "OptimizationResult", self.status, self.solution.message,
            [("objective", self.objective, ""),
             *((name, value, "") for name, value in self.variables.items()),
             ("max_tension", self.solution.max_tension, "N"),
             ("iterations", self.iterations, ""), ("wall_time_s", self.wall_time_s, "s")])


class StaticsNLP:
    """The collocated statics of ``scene`` with some parameters turned into variables.

    Parameters
    ----------
    scene : Scene
        The scene; its values are the starting point of the variables.
    variables : dict
        Name -> (lower, upper) bounds in physical units (see module docstring).
    """

    def __init__(self, scene: Scene, variables: dict[str, tuple[float, float]]):
        if scene.solver.method != "collocation":
            raise CableOCPError(
                f"solver.method = {scene.solver.method!r}: the optimisation (and the "
                "footprint) transcribe the statics by collocation; give solver.method = "
                '"collocation"')
        if scene.segments:
            raise CableOCPError("optimisation is not supported for multi-segment lines "
                                "([[cable.segments]]) yet")
        self.scene = scene
        self.form = Formulation(scene)
        o = scene.solver
        self.coll = Collocation(self.form, o.intervals, o.degree, o.scheme)
        self.names = list(variables)
        self.bounds = variables
        self.index = [self._param_index(n) for n in self.names]

    def _param_index(self, name: str) -> tuple[int, float]:
        """Parameter-vector index and scale (physical = scale * scaled) of a variable."""
        sc, scene = self.form.scales, self.scene
        if name == "cable.length":
            if scene.free_length:
                raise CableOCPError("variable cable.length: the scene's length is already free")
            return P_LENGTH, sc.length
        if name == "tension":
            if not scene.free_length:
                raise CableOCPError("variable tension: the scene prescribes no end tension")
            return P_TENSION, sc.force
        parts = name.split(".")
        if len(parts) != 3 or parts[0] not in ("end_a", "end_b") or parts[2] not in _AXES \
                or parts[1] not in ("force", "position"):
            raise CableOCPError(
                f"unknown decision variable {name!r}; valid: cable.length, tension, "
                "end_a|end_b . force|position . x|y|z")
        end = getattr(scene, parts[0])
        i = _AXES[parts[2]]
        fixed = end.fixed_mask[i]
        if (parts[1] == "position") != fixed:
            raise CableOCPError(
                f"variable {name}: that component's {parts[1]} is not prescribed in the scene "
                f"({'position' if fixed else 'force'} is)")
        base = P_END_A.start if parts[0] == "end_a" else P_END_B.start
        return base + i, (sc.length if fixed else sc.force)

    def build(self, objective: Callable[[View], Any],
              constraints: Callable[[View], Sequence[tuple[Any, Any, Any]]] | None = None,
              n_theta: int = 0, max_iter: int = 300) -> None:
        """Build the NLP once: minimise ``objective(view)`` subject to the statics and
        ``constraints(view)``; both may use ``view.theta``, a vector of ``n_theta`` user
        parameters given at each :meth:`run` (e.g. a footprint direction).

        ``objective``: View -> scalar CasADi expression (keep it O(1): scale it yourself);
        ``constraints``: View -> list of (expression, lower, upper).

        Parameters
        ----------
        objective : callable
            ``objective(view) -> casadi.MX``, a scalar to minimise, in the units the user
            chooses (scale it to O(1): IPOPT's tolerance is 1e-10).
        constraints : callable, optional
            ``constraints(view) -> [(expression, lower, upper), ...]``; each bound a number
            or an array broadcast to the expression's entries (``numpy.inf`` for none),
            in the expression's units. Default: the statics equations only.
        n_theta : int, default 0
            Length of ``view.theta``, the user parameters whose values :meth:`run` takes.
        max_iter : int, default 300
            IPOPT's iteration limit (``ipopt.max_iter``).
        """
        self.p0 = self.form.params()
        w = ca.MX.sym("w", self.coll.n_w)
        v = ca.MX.sym("v", len(self.names))
        theta = ca.MX.sym("theta", n_theta)
        pieces = []
        for k in range(len(self.p0)):
            hit = [j for j, (i, _) in enumerate(self.index) if i == k]
            pieces.append(v[hit[0]] if hit else ca.MX(float(self.p0[k])))
        pv = ca.vertcat(*pieces, ca.DM(self.coll.mesh_params().tolist()))
        g_eq = self.coll.residual(w, pv)
        view = self._view(w, v, pv)
        view.theta = theta
        f = objective(view)
        cons = list(constraints(view)) if constraints else []
        g = ca.vertcat(g_eq, *[ca.vec(c[0]) for c in cons])

        def side(k: int) -> np.ndarray:
            return np.concatenate([np.zeros(g_eq.numel())] + [
                np.broadcast_to(np.asarray(c[k], float), (ca.vec(c[0]).numel(),))
                for c in cons])

        self._lbg, self._ubg = side(1), side(2)
        scales = [s for _, s in self.index]
        self._lbx = np.concatenate([-np.inf * np.ones(self.coll.n_w),
                                    [self.bounds[n][0] / s for n, s in zip(self.names, scales,
                                                                           strict=True)]])
        self._ubx = np.concatenate([np.inf * np.ones(self.coll.n_w),
                                    [self.bounds[n][1] / s for n, s in zip(self.names, scales,
                                                                           strict=True)]])
        self._nlp = ca.nlpsol("statics_opt", "ipopt",
                              {"x": ca.vertcat(w, v), "p": theta, "f": f, "g": g}, {
            "print_time": False, "error_on_fail": False,
            "ipopt.print_level": 0, "ipopt.sb": "yes", "ipopt.max_iter": max_iter,
            "ipopt.tol": 1e-10, "ipopt.constr_viol_tol": 1e-10, "ipopt.mumps_scaling": 0,
        })
        # the NLP is collocated on the uniform mesh: so are the starts from this solver
        self._uniform = replace(self.scene, solver=replace(self.scene.solver, mesh="uniform"))
        self._solver = StaticsSolver(self._uniform)

    def run(self, theta: Sequence[float] = (), start: StaticsSolution | None = None,
            start_values: dict[str, float] | None = None) -> OptimizationResult:
        """Solve the built NLP for user parameters ``theta``.

        Parameters
        ----------
        theta : sequence of float
            Values of ``view.theta``.
        start : StaticsSolution, optional
            Starting cable (default: a statics solve of the scene as given).
        start_values : dict, optional
            Starting values of the variables, physical units (default: the scene's).
        """
        t0 = time.perf_counter()
        nw = self.coll.n_w
        v0 = np.array([self.p0[i] for i, _ in self.index])
        for k, name in enumerate(self.names):
            if start_values and name in start_values:
                v0[k] = start_values[name] / self.index[k][1]
        if start is None:
            start = self._solver.solve(self._uniform, error_estimate=False)
        x0 = np.concatenate([self._solver._from_solution(start),
                             np.clip(v0, self._lbx[nw:], self._ubx[nw:])])
        # a Ctrl-C: KeyboardInterrupt, never a failed direction to retry
        res, st = interrupt.call_solver(self._nlp, x0=x0, p=np.asarray(theta, float),
                                        lbx=self._lbx, ubx=self._ubx, lbg=self._lbg,
                                        ubg=self._ubg)
        x = np.asarray(res["x"]).ravel()
        vals = {n: float(x[nw + k] * s)
                for k, (n, (_, s)) in enumerate(zip(self.names, self.index, strict=True))}
        status = from_ipopt(st.get("return_status"), bool(st.get("success")))
        p_opt = self.p0.copy()
        for (i, _), val in zip(self.index, x[nw:], strict=True):
            p_opt[i] = val
        r, t, length, _ = self.coll.unpack(x[:nw], p_opt)
        viol = float(np.max(np.abs(np.asarray(self.coll.residual(
            x[:nw], self.coll.params(p_opt))))))
        wall = time.perf_counter() - t0
        sol = StaticsSolution(
            status=status, message=f"optimisation: ipopt ({st.get('return_status')})",
            s=self.coll.mesh.sigma() * length, position=r, tension_vector=t, length=length,
            iterations=int(st.get("iter_count", 0)), wall_time_s=wall,
            constraint_violation=viol, diagnostics={"method": "collocation NLP",
                                                    "variables": vals})
        return OptimizationResult(status=status, variables=vals, objective=float(res["f"]),
                                  solution=sol, iterations=sol.iterations, wall_time_s=wall)

    def solve(self, objective: Callable[[View], Any],
              constraints: Callable[[View], Sequence[tuple[Any, Any, Any]]] | None = None,
              start: StaticsSolution | None = None,
              start_values: dict[str, float] | None = None) -> OptimizationResult:
        """Build and run once (see :meth:`build` and :meth:`run`).

        Parameters
        ----------
        objective : callable
            ``objective(view) -> casadi.MX``, a scalar to minimise (see :meth:`build`).
        constraints : callable, optional
            ``constraints(view) -> [(expression, lower, upper), ...]`` (see :meth:`build`).
        start : StaticsSolution, optional
            Starting cable (default: a statics solve of the scene as given).
        start_values : dict of str to float, optional
            Starting values of the variables, physical units (default: the scene's).

        Notes
        -----
        Built without user parameters (``n_theta = 0``) and with IPOPT's default limit of
        :meth:`build` (300 iterations).
        """
        self.build(objective, constraints)
        return self.run((), start, start_values)

    def _view(self, w: ca.MX, v: ca.MX, pv: ca.MX) -> View:
        sc = self.form.scales
        xs = ca.reshape(w[: self.coll.n_x], NX, self.coll.mesh.n_nodes).T
        lam, _ = self.coll._lengths(w, pv)
        pos = xs[:, 0:3] * sc.length
        ten = xs[:, 3:6] * sc.force
        var = {n: v[k] * s for k, (n, (_, s)) in enumerate(zip(self.names, self.index,
                                                               strict=True))}
        return View(position=pos, tension_vector=ten, length=lam * sc.length,
                    force_a=ten[0, :].T, force_b=-ten[-1, :].T, var=var)
