"""The deployment (and recovery) optimal-control problem: the fastest pay-out schedule that
keeps the cable inside its limits.

Problem (docs/deployment.md; the scene's ``[deployment]`` table,
:mod:`cable_ocp.scene.deployment`): lower the unit from L(0) = ``cable.length`` to L(T) =
``target_length`` (haul in when it is shorter) in the least time T, the vessel's heave
h_r(t) given for each design realisation r (:mod:`cable_ocp.schedule.sea`)::

    min  T  [+ energy_weight sum_k dt |T_top,k v_k|]
    s.t. x_{r,k+1} = Phi(x_{r,k}; L_k, L_{k+1}, z_b + h_r(t_k), z_b + h_r(t_{k+1}), dt)
         v_{k+1} = v_k + a_k dt,   L_{k+1} = L_k + dt (v_k + v_{k+1}) / 2,   dt = T / N
         |a_k| <= accel_max,  0 <= s v_k <= speed_max,  |T_top v| <= power_max
         tension_min + margin <= T_j <= tension_max - margin   (every element, or the unit
                                                            and the top: ``tension_at``)
         v_0 = v_N = 0,  L_N = target,  |V_unit(T) - (1 - g) dh_r/dt(T)| <= rest_tolerance

with ``s`` the direction (+1 pay-out, -1 haul-in: the winch does not reverse), ``a`` the
pay-out acceleration (the control, piecewise constant), Phi the line model's own implicit
midpoint step (:meth:`cable_ocp.dynamics.model.CableModel.driven_step`: the axial or the
planar varying-length line of Huang (1992) ch. 3-4, on the scene's discretisation) with
the length linear over a step, and the active heave compensation optional on top: the
length the line sees is L + g h_r, g in [0, 1] one gain for every realisation,
|g h_r| <= ahc_stroke and |g dh_r/dt| <= ahc_speed.

Transcription: a direct *implicit multiple shooting* (equivalently, the collocation of the
model's one-stage Gauss method, the midpoint rule): every step's state is a decision
variable and the step's residual an equality constraint. Why: (i) the tension limits are
path constraints on the state, which a single-shooting transcription would see only
through long, ill-conditioned sensitivities of a lightly damped line; (ii) the step is
the model's own (the same residual that the heave plants and the simulator's midpoint
scheme solve), so the schedule and the forward simulation agree to the time step's
error; (iii) the Jacobian is banded and sparse, which IPOPT's sparse factorisation uses;
(iv) the free duration enters as the step size dt = T / N, a symbol of the built step.
IPOPT gets the exact Hessian of the Lagrangian (CasADi's AD). The NLP is built once for
a step count N; the warm start is the fastest constant-speed schedule that keeps the
limits on the same discrete model
(:func:`~cable_ocp.schedule.planning.discrete_constant_speed`), rolled out with the
step's Newton iteration.

Scaling: the states are scaled by the model's static elongation (heights) and 1 m/s
(velocities), the tensions by the static top tension at the longer length, the residual by
the step's own row scale (:attr:`~cable_ocp.dynamics.model.DrivenStep.residual_scale`).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.dynamics.axial import AxialModel
from cable_ocp.dynamics.model import DrivenStep
from cable_ocp.dynamics.planar import PlanarModel
from cable_ocp.dynamics.vertical_line import vertical_line
from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import interrupt
from cable_ocp.scene.deployment import DeploymentProblem
from cable_ocp.scene.dynamics import DynamicScene
from cable_ocp.schedule.sea import heave_rate  # the rest condition's reference

#: the constraint groups that are the model's equations, not limits
_EQUATIONS = ("kinematics", "dynamics")

__all__ = ["LineStep", "OCPSolution", "ScheduleOCP", "constrained_tensions", "heave_rate",
           "limit_constraints", "line_step", "static_tensions", "winch_power"]


@dataclass(frozen=True)
class LineStep:
    """The line model's step as CasADi Functions for the schedule (module docstring).

    Attributes
    ----------
    model : AxialModel or PlanarModel
        The model (its scene's start length, the OCP's segments).
    step : casadi.Function
        ``(y, x, p, dt) -> (residual (scaled, -), next state, element tensions (N),
        outputs (5))`` with ``p = [L_a, L_b, z_a, z_b]`` (m): the outputs are the unit's
        height (m) and vertical velocity (m/s), the tension at the unit and at the top (N)
        and the smallest element tension (N).
    forward : casadi.Function
        ``(x, p, dt) -> (next state, y, element tensions, outputs)``: the step solved by
        Newton's method from the model's guess (the rollout of the warm start).
    guess : casadi.Function
        ``(x, p, dt) -> y``: the model's predictor.
    start : numpy.ndarray
        The static state at the start length.
    x_scale, y_scale : numpy.ndarray
        The scale of the state's and the unknown's entries (m, m/s).
    same : bool
        The unknown is the next state itself (the axial step).
    top_height : float
        The static top's height z_b, m.
    elements : int
        The line's elements.
    """

    model: Any
    step: ca.Function
    forward: ca.Function
    guess: ca.Function
    start: np.ndarray
    x_scale: np.ndarray
    y_scale: np.ndarray
    same: bool
    top_height: float
    elements: int


def line_step(scene: DynamicScene, segments: int | None = None) -> LineStep:
    """The scene's axial or planar step with a symbolic step size (:class:`LineStep`).

    Parameters
    ----------
    scene : DynamicScene
        The dynamic scene (``simulation.model`` "axial" or "planar").
    segments : int, optional
        Elements (default ``deployment.segments``, else ``simulation.segments``).

    Raises
    ------
    CableOCPError
        For another model or a line the driven step does not carry.
    """
    dep = scene.deployment
    n = segments or (dep.segments if dep is not None else None) or scene.simulation.segments
    kind = scene.simulation.model
    if kind == "axial":
        model: Any = AxialModel(scene, n)
        st: DrivenStep = model.driven_step(ca.SX.sym("dt"))
    elif kind == "planar":
        model = PlanarModel(scene, n)
        st = model.driven_step(None)
    else:
        raise CableOCPError(f'simulation.model = "{kind}": the deployment schedule runs on '
                            'the "axial" or "planar" line (the lumped3d model has no '
                            "driven step with a free step size)")
    dt = st.dt
    res = st.residual if st.residual_scale is None else st.residual * st.residual_scale
    y, x, p = st.unknown, st.state, st.inputs
    step = ca.Function("line_step", [y, x, p, dt],
                       [res, st.next_state, st.tensions, st.outputs],
                       ["y", "x", "p", "dt"], ["res", "next", "tensions", "outputs"])
    guess = ca.Function("line_guess", [x, p, dt], [st.guess])
    rf = ca.rootfinder("line_newton", "newton", ca.Function("g", [y, ca.vertcat(x, p, dt)],
                                                             [res]),
                       {"abstol": 1e-10, "max_iter": 50, "error_on_fail": False})
    xs, ps, ds = ca.MX.sym("x", x.shape[0]), ca.MX.sym("p", 4), ca.MX.sym("dt")
    ysol = rf(guess(xs, ps, ds), ca.vertcat(xs, ps, ds))
    _, nxt, tens, outs = step(ysol, xs, ps, ds)
    forward = ca.Function("line_forward", [xs, ps, ds], [nxt, ysol, tens, outs])
    start = np.asarray(st.start, dtype=float)
    nx, ny = x.shape[0], y.shape[0]
    pos = max(float(getattr(model, "elongation", 0.0)) or 0.0,
              1e-3 * float(np.max(np.abs(start[: nx // 2])) if nx else 1.0), 1e-6)
    x_scale = np.concatenate([np.full(nx // 2, pos), np.ones(nx - nx // 2)])
    y_scale = x_scale.copy() if ny == nx else np.full(ny, pos)
    return LineStep(model=model, step=step, forward=forward, guess=guess, start=start,
                    x_scale=x_scale, y_scale=y_scale, same=bool(ca.depends_on(
                        st.next_state, y) and ny == nx and _is_identity(st, nx)),
                    top_height=float(scene.top_position[2]), elements=int(n))


def _is_identity(st: DrivenStep, nx: int) -> bool:
    """True when the step's next state is its unknown (the axial step's layout)."""
    jac = ca.Function("j", [st.unknown], [ca.jacobian(st.next_state, st.unknown)])
    return bool(np.allclose(np.asarray(jac(np.zeros(nx))), np.eye(nx)))


def static_tensions(scene: DynamicScene, length: float) -> tuple[float, float]:
    """The static (tension at the unit, tension at the top) of the vertical line at an
    unstretched length (N): W and W + w L (the axial model's own
    :func:`~cable_ocp.dynamics.vertical_line.vertical_line` coefficients).

    Parameters
    ----------
    scene : DynamicScene
        The scene.
    length : float
        m.
    """
    line = vertical_line(scene)
    return float(line.unit_weight), float(line.unit_weight + line.weight_per_length * length)


def constrained_tensions(problem: DeploymentProblem, tensions: Any, outputs: Any) -> list[Any]:
    """The tensions ``tension_at`` constrains (N): ``"line"`` the whole line, every
    element's and both ends' (the pull on the unit and the top's, the outputs' rows 2 and
    3); ``"unit"``, ``"top"`` those ends alone; on numpy arrays or CasADi expressions (the
    one home of the selection: :func:`limit_constraints`, the warm start's rollout,
    :func:`cable_ocp.schedule.planning.discrete_constant_speed`, and the forward check,
    :func:`cable_ocp.schedule.forward.resimulate`).

    Why the ends with ``"line"``: an element's tension is at its middle, w h / 2 above the
    unit's end of a hanging line (h = L / n), so the elements alone bound a point that
    moves with the mesh: the OCP's 10 elements and the check's 20 read 1350 N apart at
    1000 m of the 6.3.6 line, and a schedule the OCP kept at tension_min broke it by 5 %
    when re-simulated (docs/deployment.md, "The 6.3.6 line with compensation"). The ends
    are where a hanging line's tension is smallest (the unit) and largest (the top),
    whatever the mesh. Until 2026-12-03 ``"line"`` was the elements alone.

    Parameters
    ----------
    problem : DeploymentProblem
        Its ``tension_at``.
    tensions : array or casadi expression (n, K)
        Element tensions, N.
    outputs : array or casadi expression (5, K)
        The step's outputs (:class:`LineStep`).
    """
    out = []
    at = problem.tension_at
    if "line" in at:
        out.append(tensions)
    if "line" in at or "unit" in at:
        out.append(outputs[2, :])
    if "line" in at or "top" in at:
        out.append(outputs[3, :])
    return out


def winch_power(outputs: Any, speed: Any) -> Any:
    """The winch's power T_top v per step (W): the top tension at the step's end times
    the step's mean speed (numpy or CasADi).

    Parameters
    ----------
    outputs : array or casadi expression (5, K)
        The step's outputs (:class:`LineStep`).
    speed : array or casadi expression (K + 1,) or (1, K + 1)
        The winch's speed at the nodes, m/s.
    """
    return outputs[3, :] * 0.5 * (speed[:-1] + speed[1:])


def limit_constraints(add: Callable[[str, Any, Any, Any], None], problem: DeploymentProblem,
                      tension_scale: float, tensions: Any, outputs: Any, speed: Any, *,
                      rest_ref: Any = None, comp: Any = None, dt: Any = None,
                      rest_index: int = -1) -> Any:
    """The limits of one realisation's steps, as constraint groups (the one home of the
    tension, power, rest and compensation limits: :class:`ScheduleOCP` and the receding
    horizon's NLP, :mod:`cable_ocp.schedule.receding`, both add them through this).

    Adds, through ``add(name, expr, lo, hi)``, in this order: ``"tension"`` (every element,
    the unit, the top: ``tension_at``; scaled by ``tension_scale``, inside [tension_min +
    margin, tension_max - margin]), ``"power_max"`` (|T_top v| <= power_max, v the step's
    mean speed), ``"rest"`` (|V_unit(T) - rest_ref| <= rest_tolerance at the last node;
    skipped when ``rest_ref`` is None), ``"ahc_stroke"`` and ``"ahc_speed"`` (only with
    ``comp``).

    Parameters
    ----------
    add : callable
        ``add(name, expr, lo, hi)``: the NLP's constraint collector.
    problem : DeploymentProblem
        The limits.
    tension_scale : float
        N, the tensions' scale.
    tensions : casadi.MX (n, K)
        Element tensions at the steps' ends, N.
    outputs : casadi.MX (5, K)
        The step's outputs (:class:`LineStep`): unit height (m) and velocity (m/s), unit
        and top tension, smallest element tension (N).
    speed : casadi.MX (1, K + 1)
        The winch's speed at the nodes, m/s.
    rest_ref : casadi.MX, optional
        The unit's velocity at rest relative to the ship at the end, (1 - g) dh/dt, m/s.
    comp : casadi.MX (1, K + 1), optional
        The compensating length g h at the nodes, m (with the compensation).
    dt : casadi.MX, optional
        The step, s (with ``comp``).
    rest_index : int
        The column of ``outputs`` the rest condition reads (default the last; the node
        of arrival when a hold follows it, :class:`ScheduleOCP`).

    Returns
    -------
    casadi.MX (1, K)
        The winch's power T_top v per step, W (the energy objective's integrand).
    """
    pb, ts, outs = problem, tension_scale, outputs
    margin = pb.tension_margin
    t_lo = (pb.tension_min + margin) / ts if pb.tension_min is not None else -math.inf
    t_hi = (pb.tension_max - margin) / ts if pb.tension_max is not None else math.inf
    if pb.tension_min is not None or pb.tension_max is not None:
        for tens in constrained_tensions(pb, tensions, outs):
            add("tension", tens / ts, t_lo, t_hi)
    power = winch_power(outs, speed)
    if pb.power_max is not None:
        add("power_max", power / pb.power_max, -1.0, 1.0)
    if rest_ref is not None:
        add("rest", (outs[1, rest_index] - rest_ref) / pb.rest_tolerance, -1.0, 1.0)
    if comp is not None:
        if pb.ahc_stroke is not None:
            add("ahc_stroke", comp / pb.ahc_stroke, -1.0, 1.0)
        if pb.ahc_speed is not None:
            add("ahc_speed", (comp[1:] - comp[:-1]) / dt / pb.ahc_speed, -1.0, 1.0)
    return power


@dataclass(frozen=True)
class OCPSolution:
    """The OCP's solution (or its failed iterate: see ``status``).

    Attributes
    ----------
    status : str
        ``"solved"``, ``"infeasible"`` (IPOPT found the limits inconsistent; ``binding``
        names the limits most violated at its last iterate), ``"failed"`` or
        ``"interrupted"``.
    message : str
        IPOPT's return status and what it means here.
    time, length, speed : numpy.ndarray (N + 1,)
        s, m (unstretched), m/s.
    accel : numpy.ndarray (N,)
        m/s^2, per step.
    ahc_gain : float
        The compensation's gain g (-; 0 without it).
    tensions : numpy.ndarray (R, N + 1, n)
        Element tensions of each design realisation, N (row 0 the static start).
    outputs : numpy.ndarray (R, N + 1, 5)
        Unit height (m), unit velocity (m/s), unit tension, top tension, smallest element
        tension (N).
    heave : numpy.ndarray (R, N + 1)
        The vessel heave the schedule saw, m.
    binding : tuple of str
        The limits active at the solution (within 0.1 % of their bound), or, when
        infeasible, the most violated limits (never the model's equations, which the
        message names when IPOPT broke them instead).
    violations : dict
        The largest relative excess of each limit group at the returned point (-).
    diagnostics : dict
        build and solve times (s), iterations, variables, constraints, steps, IPOPT's
        return status.
    variables_vector : numpy.ndarray
        The NLP's variables at the returned point (scaled: :meth:`ScheduleOCP.pack`), the
        warm start of a re-solve.
    """

    status: str
    message: str
    time: np.ndarray
    length: np.ndarray
    speed: np.ndarray
    accel: np.ndarray
    ahc_gain: float
    tensions: np.ndarray
    outputs: np.ndarray
    heave: np.ndarray
    binding: tuple[str, ...] = ()
    violations: dict[str, float] = field(default_factory=dict)
    diagnostics: dict[str, Any] = field(default_factory=dict)
    variables_vector: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def duration(self) -> float:
        """T, s."""
        return float(self.time[-1])

    @property
    def success(self) -> bool:
        """True for a solved schedule."""
        return self.status == "solved"


#: IPOPT's return statuses that count as solved
_SOLVED = ("Solve_Succeeded", "Solved_To_Acceptable_Level")
#: ... and those that say the constraints cannot be met
_INFEASIBLE = ("Infeasible_Problem_Detected", "Restoration_Failed",
               "Not_Enough_Degrees_Of_Freedom")


class ScheduleOCP:
    """The deployment OCP (module docstring), built once for ``steps`` steps and the
    design heaves; :meth:`solve` from a warm start.

    Parameters
    ----------
    scene : DynamicScene
        The scene with its ``[deployment]`` problem.
    line : LineStep
        The line's step (:func:`line_step`).
    heaves : sequence of casadi.Function
        The vessel heave h_r(t) (m) of each design realisation.
    steps : int
        N, the hold's steps included.
    problem : DeploymentProblem, optional
        Default ``scene.deployment``.
    ipopt : dict, optional
        IPOPT options added to the defaults (``ipopt.`` prefixed keys).
    hold_steps : int
        M >= 0: the last M of the N steps are a hold of ``hold`` s (steps of hold / M s,
        fixed; the free duration T is the arrival's, T / (N - M) the other steps'), the
        winch stopped at the target (v = 0, a = 0, L = target) while the sea goes on, its
        tensions inside the limits as every step's; the rest condition is at the arrival,
        node N - M, and the solution reports the schedule up to it (:meth:`extend` appends
        the hold to a schedule). Why: a
        minimum-time arrival stops the winch with the line stretched (6.3.6: the unit's
        tension 92.6 kN at the stop against 50 kN static), and the free oscillation after
        the stop, which the forward check simulates (:func:`~cable_ocp.schedule.forward.
        resimulate`'s ``hold``) and an OCP ending at the arrival does not see, falls below
        tension_min (docs/deployment.md, "The 6.3.6 line with compensation").
    hold : float
        s, > 0 with ``hold_steps``.
    """

    def __init__(self, scene: DynamicScene, line: LineStep, heaves: Sequence[ca.Function],
                 steps: int, problem: DeploymentProblem | None = None,
                 ipopt: dict[str, Any] | None = None, hold_steps: int = 0,
                 hold: float = 0.0) -> None:
        t0 = time.perf_counter()
        pb = problem if problem is not None else scene.deployment
        if pb is None:
            raise CableOCPError("[deployment] is missing: the schedule needs target_length "
                                "and its limits")
        self.scene, self.line, self.problem, self.steps = scene, line, pb, int(steps)
        self.hold_steps = int(hold_steps)
        if not 0 <= self.hold_steps < self.steps:
            raise CableOCPError(f"ScheduleOCP: hold_steps = {hold_steps} must be in [0, "
                                f"steps = {steps})")
        n_a = self.steps - self.hold_steps  # the node of arrival
        if self.hold_steps and not (math.isfinite(hold) and hold > 0.0):
            raise CableOCPError(f"ScheduleOCP: hold = {hold} s must be > 0 with hold_steps")
        #: the hold's step, s (0 without a hold)
        self.hold_step = float(hold) / self.hold_steps if self.hold_steps else 0.0
        n_r = len(heaves)
        self.realisations = n_r
        start, target = scene.length, pb.target_length
        self.direction = 1.0 if target > start else -1.0
        self.tension_scale = max(*static_tensions(scene, max(start, target)), 1.0)
        n_k = self.steps
        nx, ny = line.start.size, line.y_scale.size
        xs, ys = ca.DM(line.x_scale), ca.DM(line.y_scale)
        # decision variables
        tt = ca.MX.sym("T")
        acc = ca.MX.sym("a", 1, n_k)
        vel = ca.MX.sym("v", 1, n_k + 1)
        lng = ca.MX.sym("L", 1, n_k + 1)
        gain = ca.MX.sym("g") if pb.ahc else None
        xr = [ca.MX.sym(f"x{r}", nx, n_k) for r in range(n_r)]  # states 1..N (scaled)
        yr = [] if line.same else [ca.MX.sym(f"y{r}", ny, n_k) for r in range(n_r)]
        dt = tt / n_a
        m_h, dt_h = self.hold_steps, self.hold_step
        dts = ca.horzcat(ca.repmat(dt, 1, n_a), ca.DM.ones(1, m_h) * dt_h)  # each step's
        tgrid = ca.horzcat(ca.MX(0.0), ca.cumsum(dts, 1))  # the nodes' times, from the steps
        self._grid = ca.Function("grid", [tt], [tgrid])  # the nodes' times, s
        step_map = line.step.map(n_k)
        g_list: list[Any] = []
        self._groups: list[tuple[str, int, int, np.ndarray, np.ndarray]] = []

        def add(name: str, expr: Any, lo: Any, hi: Any) -> None:
            e = ca.vec(expr)
            k = e.shape[0]
            off = sum(x.shape[0] for x in g_list)
            g_list.append(e)
            self._groups.append((name, off, off + k, np.broadcast_to(lo, (k,)).astype(float),
                                 np.broadcast_to(hi, (k,)).astype(float)))

        # kinematics of the winch
        # (up to the arrival: in the hold the bounds fix v = a = 0 and L = target)
        add("kinematics", vel[1:n_a + 1] - vel[:n_a] - acc[:n_a] * dt, 0.0, 0.0)
        add("kinematics", (lng[1:n_a + 1] - lng[:n_a] - 0.5 * dt * (vel[1:n_a + 1] + vel[:n_a]))
            / max(abs(target - start), 1.0), 0.0, 0.0)
        inf = math.inf
        ts = self.tension_scale
        x0 = ca.DM(line.start)
        energy = 0.0
        self._heave_fns = [h.map(n_k + 1) for h in heaves]
        self._heave_rates = [heave_rate(h) for h in heaves]
        outs_all: list[Any] = []  # what the result reports, from the variables
        for r in range(n_r):
            hv = self._heave_fns[r](tgrid)
            comp = gain * hv if gain is not None else 0.0 * hv
            lw = lng + comp
            zt = line.top_height + hv
            p = ca.vertcat(lw[:-1], lw[1:], zt[:-1], zt[1:])
            xx = ca.horzcat(x0, ca.diag(xs) @ xr[r])  # states 0..N (SI)
            yy = ca.diag(xs) @ xr[r] if line.same else ca.diag(ys) @ yr[r]
            res, nxt, tens, outs = step_map(yy, xx[:, :-1], p, dts)
            outs_all += [tens, outs, hv]
            add("dynamics", res, 0.0, 0.0)
            if not line.same:
                add("dynamics", (nxt - xx[:, 1:]) / ca.repmat(xs, 1, n_k), 0.0, 0.0)
            # at rest relative to the ship: a stopped winch on a taut line carries the unit
            # with the top's heave, less what the compensation pays out, (1 - g) dh/dt
            rate = self._heave_rates[r](n_a * dt)
            ref = (1.0 - gain) * rate if gain is not None else rate
            power = limit_constraints(add, pb, ts, tens, outs, vel, rest_ref=ref,
                                      comp=comp if gain is not None else None, dt=dts,
                                      rest_index=n_a - 1)
            if pb.objective == "time_energy":
                energy = energy + ca.sum2(ca.sqrt(power[:, :n_a]**2 + (1e-3 * ts) ** 2)) \
                    * dt / n_r
            self._outputs = None
        objective = tt + pb.energy_weight * energy
        # the variables and their bounds
        parts = [tt, ca.vec(acc), ca.vec(vel), ca.vec(lng)]
        parts += [gain] if gain is not None else []
        parts += [ca.vec(x) for x in xr] + [ca.vec(y) for y in yr]
        self._sizes = [1, n_k, n_k + 1, n_k + 1, 1 if gain is not None else 0] \
            + [nx * n_k] * n_r + [ny * n_k] * len(yr)
        w = ca.vertcat(*parts)
        a_max = pb.accel_max if pb.accel_max is not None else inf
        v_max = pb.speed_max if pb.speed_max is not None else inf
        lo_v, hi_v = (0.0, v_max) if self.direction > 0 else (-v_max, 0.0)
        lo_l, hi_l = sorted((start, target))
        lbx = [np.array([1e-3]), np.full(n_k, -a_max), np.full(n_k + 1, lo_v),
               np.full(n_k + 1, lo_l)]
        ubx = [np.array([inf]), np.full(n_k, a_max), np.full(n_k + 1, hi_v),
               np.full(n_k + 1, hi_l)]
        for b, val in ((lbx, 0.0), (ubx, 0.0)):
            b[2][0] = b[2][-1] = val
        lbx[3][0] = ubx[3][0] = start
        lbx[3][n_a:] = ubx[3][n_a:] = target
        # the hold: the winch stopped at the target
        for b in (lbx, ubx):
            b[2][n_a:] = 0.0
            b[1][n_a:] = 0.0
        if gain is not None:
            lbx.append(np.array([0.0]))
            ubx.append(np.array([1.0]))
        for size in [nx * n_k] * n_r + [ny * n_k] * len(yr):
            lbx.append(np.full(size, -inf))
            ubx.append(np.full(size, inf))
        self._lbx, self._ubx = np.concatenate(lbx), np.concatenate(ubx)
        g_all = ca.vertcat(*g_list)
        self._lbg = np.concatenate([grp[3] for grp in self._groups])
        self._ubg = np.concatenate([grp[4] for grp in self._groups])
        opts = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes",
                "ipopt.max_iter": 500, "ipopt.tol": 1e-8, "ipopt.acceptable_tol": 1e-3,
                "ipopt.acceptable_constr_viol_tol": 1e-5,
                "ipopt.mu_strategy": "adaptive"}
        opts.update(ipopt or {})
        self._solver = ca.nlpsol("deployment", "ipopt", {"x": w, "f": objective, "g": g_all},
                                 opts)
        self._report = ca.Function("report", [w], outs_all)
        self.build_time = time.perf_counter() - t0
        self.variables, self.constraints = int(w.shape[0]), int(g_all.shape[0])

    # ---------------------------------------------------------------- packing
    def extend(self, duration: float, accel: np.ndarray, speed: np.ndarray,
               length: np.ndarray) -> tuple[float, np.ndarray, np.ndarray, np.ndarray]:
        """A schedule of N - M equal steps with the hold's M steps appended (the winch
        stopped at its last length): (duration (s, the arrival's: unchanged), accel
        (m/s^2), speed (m/s), length (m)) on the NLP's N steps, for :meth:`pack` and
        :meth:`rollout`; unchanged without a hold.

        Parameters
        ----------
        duration : float
            The schedule's, s.
        accel : ndarray (N - M,)
            m/s^2.
        speed, length : ndarray (N - M + 1,)
            m/s, m.
        """
        m = self.hold_steps
        accel, speed, length = (np.asarray(x, dtype=float) for x in (accel, speed, length))
        if accel.size != self.steps - m:
            raise CableOCPError(f"ScheduleOCP.extend: {accel.size} steps given, the OCP's "
                                f"schedule has {self.steps - m} before its hold")
        if m == 0:
            return duration, accel, speed, length
        return (duration, np.append(accel, np.zeros(m)), np.append(speed, np.zeros(m)),
                np.append(length, np.full(m, length[-1])))

    def pack(self, duration: float, accel: np.ndarray, speed: np.ndarray, length: np.ndarray,
             states: Sequence[np.ndarray], unknowns: Sequence[np.ndarray] = (),
             gain: float = 0.0) -> np.ndarray:
        """The NLP's variable vector from a schedule and its states (SI units).

        Parameters
        ----------
        duration : float
            T, s.
        accel : ndarray (N,)
            m/s^2.
        speed, length : ndarray (N + 1,)
            m/s, m.
        states : sequence of ndarray (nx, N + 1)
            Each realisation's states (column 0 the start).
        unknowns : sequence of ndarray (ny, N)
            Each realisation's step unknowns (the planar step; empty for the axial).
        gain : float
            The compensation's gain (-).
        """
        xs = self.line.x_scale[:, None]
        parts = [np.array([duration]), np.ravel(accel), np.ravel(speed), np.ravel(length)]
        if self.problem.ahc:
            parts.append(np.array([gain]))
        parts += [(np.asarray(x)[:, 1:] / xs).ravel(order="F") for x in states]
        if not self.line.same:
            parts += [(np.asarray(y) / self.line.y_scale[:, None]).ravel(order="F")
                      for y in unknowns]
        return np.concatenate(parts)

    def rollout(self, duration: float, accel: np.ndarray, speed: np.ndarray,
                length: np.ndarray, gain: float = 0.0) -> tuple[list[np.ndarray],
                                                                list[np.ndarray]]:
        """Each design realisation's states (nx, N + 1) and unknowns (ny, N) under a
        schedule, by the step's Newton iteration (the warm start's states).

        Parameters
        ----------
        duration : float
            s.
        accel, speed, length : ndarray
            The schedule (m/s^2 (N,), m/s and m (N + 1,)).
        gain : float
            The compensation's gain (-).
        """
        n_k = self.steps
        n_a, m_h = n_k - self.hold_steps, self.hold_steps
        dt = duration / n_a
        steps = np.concatenate([np.full(n_a, dt), np.full(m_h, self.hold_step)])
        tg = np.concatenate([[0.0], np.cumsum(steps)])
        fwd = self.line.forward.mapaccum(n_k)
        xs_all, ys_all = [], []
        for hf in self._heave_fns:
            hv = np.asarray(hf(tg)).ravel()
            lw = np.asarray(length) + gain * hv
            zt = self.line.top_height + hv
            p = np.vstack([lw[:-1], lw[1:], zt[:-1], zt[1:]])
            xn, yn, _, _ = fwd(self.line.start, p, steps.reshape(1, -1))
            xs_all.append(np.hstack([self.line.start[:, None], np.asarray(xn)]))
            ys_all.append(np.asarray(yn))
        return xs_all, ys_all

    # ---------------------------------------------------------------- solving
    def bounds(self, tighten: dict[str, float] | None = None) -> tuple[np.ndarray, np.ndarray]:
        """The constraints' (lower, upper) bounds, the limits moved inwards by ``tighten``
        (the verified schedule's margins, :func:`cable_ocp.schedule.planning.verified_schedule`:
        the bounds are the solver's parameters, so no rebuild).

        Parameters
        ----------
        tighten : dict, optional
            ``"tension_min"``, ``"tension_max"`` (N) and ``"power_max"`` (W): how far inside
            its limit each is kept, on top of ``tension_margin``.
        """
        lbg, ubg = self._lbg.copy(), self._ubg.copy()
        extra = tighten or {}
        ts, pm = self.tension_scale, self.problem.power_max
        for name, a, b, _, _ in self._groups:
            if name == "tension":
                lbg[a:b] += extra.get("tension_min", 0.0) / ts
                ubg[a:b] -= extra.get("tension_max", 0.0) / ts
            elif name == "power_max" and pm is not None:
                ubg[a:b] -= extra.get("power_max", 0.0) / pm
                lbg[a:b] += extra.get("power_max", 0.0) / pm
        return lbg, ubg

    def solve(self, w0: np.ndarray, tighten: dict[str, float] | None = None) -> OCPSolution:
        """Solve from the variable vector ``w0`` (:meth:`pack`).

        Parameters
        ----------
        w0 : ndarray
            The warm start (a previous :attr:`OCPSolution.variables_vector` too).
        tighten : dict, optional
            Margins moving the limits inwards (:meth:`bounds`; N, W).

        Raises
        ------
        KeyboardInterrupt
            On a Ctrl-C inside IPOPT (never retried).
        """
        t0 = time.perf_counter()
        lbg, ubg = self.bounds(tighten)
        res, stats = interrupt.call_solver(self._solver, x0=w0, lbx=self._lbx, ubx=self._ubx,
                                           lbg=lbg, ubg=ubg)
        solve_time = time.perf_counter() - t0
        ret = str(stats.get("return_status", "unknown"))
        w = np.asarray(res["x"]).ravel()
        g = np.asarray(res["g"]).ravel()
        viol = self._violations(g, lbg, ubg)
        worst = sorted((k for k in viol if viol[k] > 1e-5), key=lambda k: -viol[k])
        if ret in _SOLVED and not worst:
            status, msg = "solved", f"IPOPT: {ret}"
            binding = self._active(g, w, lbg, ubg)
        elif ret in _SOLVED and all(k in _EQUATIONS for k in worst):
            status, binding = "failed", ()
            msg = (f"IPOPT: {ret}, but its point breaks the model's equations: "
                   + ", ".join(f"{k} by {viol[k]:.3g} (relative)" for k in worst[:2])
                   + "; not a schedule")
        elif ret in _INFEASIBLE or (ret in _SOLVED):
            status = "infeasible"
            # the limits, not the model's own equations, are what a user can change: IPOPT's
            # last iterate may keep the limits by breaking the equations instead
            limits = [k for k in worst if k not in _EQUATIONS]
            binding = tuple(limits[:2])
            msg = (f"IPOPT: {ret}: no schedule keeps the limits; most violated at its last "
                   f"iterate: " + ", ".join(f"{k} by {viol[k]:.3g} (relative)" for k in worst[:3]))
        else:
            status, msg, binding = "failed", f"IPOPT: {ret}", ()
        return self._solution(w, status, msg, binding, viol, dict(
            build_time_s=self.build_time, solve_time_s=solve_time,
            iterations=int(stats.get("iter_count", -1)), variables=self.variables,
            constraints=self.constraints, steps=self.steps, return_status=ret,
            realisations=self.realisations, elements=self.line.elements))

    def _split(self, w: np.ndarray) -> list[np.ndarray]:
        out, i = [], 0
        for s in self._sizes:
            out.append(w[i:i + s])
            i += s
        return out

    def _violations(self, g: np.ndarray, lbg: np.ndarray, ubg: np.ndarray
                    ) -> dict[str, float]:
        viol: dict[str, float] = {}
        for name, a, b, _, _ in self._groups:
            seg, lo, hi = g[a:b], lbg[a:b], ubg[a:b]
            with np.errstate(invalid="ignore"):
                exc = np.maximum(np.nan_to_num(lo - seg, nan=0.0, neginf=0.0),
                                 np.nan_to_num(seg - hi, nan=0.0, neginf=0.0))
            val = float(np.max(exc)) if exc.size else 0.0
            key = self._limit_name(name, seg, lo, hi)
            viol[key] = max(viol.get(key, 0.0), val)
        return viol

    def _limit_name(self, name: str, seg: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> str:
        if name != "tension":
            return name
        low = np.nan_to_num(lo - seg, neginf=-np.inf)
        high = np.nan_to_num(seg - hi, neginf=-np.inf)
        return "tension_min" if np.max(low, initial=-np.inf) >= np.max(high, initial=-np.inf) \
            else "tension_max"

    def _active(self, g: np.ndarray, w: np.ndarray, lbg: np.ndarray, ubg: np.ndarray
                ) -> tuple[str, ...]:
        act: list[str] = []
        for name, a, b, _, _ in self._groups:
            if name in ("kinematics", "dynamics", "rest"):
                continue
            seg, lo, hi = g[a:b], lbg[a:b], ubg[a:b]
            if np.any(np.isfinite(lo) & (seg - lo <= 1e-3 * np.maximum(abs(lo), 1e-9))):
                act.append("tension_min" if name == "tension" else name)
            if np.any(np.isfinite(hi) & (hi - seg <= 1e-3 * np.maximum(abs(hi), 1e-9))):
                act.append("tension_max" if name == "tension" else name)
        parts = self._split(w)
        pb = self.problem
        if pb.accel_max is not None and np.any(np.abs(parts[1]) >= pb.accel_max * (1 - 1e-3)):
            act.append("accel_max")
        if pb.speed_max is not None and np.any(np.abs(parts[2]) >= pb.speed_max * (1 - 1e-3)):
            act.append("speed_max")
        return tuple(dict.fromkeys(act))

    def gain_of(self, w: np.ndarray) -> float:
        """The compensation's gain g of a variable vector (-; 0 without compensation),
        put back into its bounds [0, 1]: IPOPT's relaxed bounds (``bound_relax_factor``
        1e-8) may return 1 + 1e-8 (the 6.3.6 line's 1.0000000098), which the forward
        check and the constant speed's bisection refuse as a gain.

        Parameters
        ----------
        w : numpy.ndarray
            The NLP's variables (:meth:`pack`, :attr:`OCPSolution.variables_vector`).
        """
        g = self._split(w)[4]
        return float(np.clip(g[0], 0.0, 1.0)) if g.size else 0.0

    def _solution(self, w: np.ndarray, status: str, msg: str, binding: tuple[str, ...],
                  viol: dict[str, float], diag: dict[str, Any]) -> OCPSolution:
        parts = self._split(w)
        n_k = self.steps
        n_a = n_k - self.hold_steps
        dur = float(parts[0][0])
        rep = self._report(w)
        rep = rep if isinstance(rep, (list, tuple)) else [rep]
        tens_l, outs_l, heave_l = [], [], []
        ts0 = static_tensions(self.scene, self.scene.length)
        ln = self.line
        y0 = ln.start if ln.same else ln.start[: ln.y_scale.size]
        p0 = [self.scene.length] * 2 + [ln.top_height] * 2
        start_t = np.asarray(ln.step(y0, ln.start, p0, 1.0)[2]).ravel()
        for r in range(self.realisations):
            tens = np.asarray(rep[3 * r]).T
            outs = np.asarray(rep[3 * r + 1]).T
            if self.hold_steps:
                diag = dict(diag)
                low = float(np.min(tens[n_a:]))
                diag["hold_min_tension_N"] = min(diag.get("hold_min_tension_N", low), low)
            tens_l.append(np.vstack([start_t, tens[:n_a]]))
            first = np.array([[np.nan, 0.0, ts0[0], ts0[1], min(ts0)]])
            outs_l.append(np.vstack([first, outs[:n_a]]))
            heave_l.append(np.asarray(rep[3 * r + 2]).ravel()[:n_a + 1])
        if self.hold_steps:
            grid = np.asarray(self._grid(dur)).ravel()  # the NLP's own nodes
            diag.update(hold_steps=self.hold_steps, hold_s=float(grid[-1] - grid[n_a]))
        # the schedule up to the arrival (the hold is the NLP's, not the schedule's)
        return OCPSolution(status=status, message=msg,
                           time=np.arange(n_a + 1) * dur / n_a,
                           length=parts[3][:n_a + 1].copy(),
                           speed=parts[2][:n_a + 1].copy(), accel=parts[1][:n_a].copy(),
                           ahc_gain=self.gain_of(w),
                           tensions=np.array(tens_l), outputs=np.array(outs_l),
                           heave=np.array(heave_l), binding=binding, violations=viol,
                           diagnostics=diag, variables_vector=w.copy())
