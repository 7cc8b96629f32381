"""The receding-horizon form of the deployment schedule: re-planned every few seconds from
the measured state, with a short preview of the vessel's motion, and its comparison with
the open-loop schedule on unseen realisations of the sea.

The horizon problem (:class:`HorizonNLP`), on a fixed step dt (``deployment.time_step``)
and N_h = ceil(preview / dt) steps, parametric in the measured line state x_0, the
winch's L_0 and v_0 and the heave h_k previewed at the horizon's nodes::

    min  sum_{k=1..N_h} s (L* - L_k) dt / (D N_h dt)  +  eps sum_k (a_k / a_ref)^2 / N_h
    s.t. x_{k+1} = Phi(x_k; L_k, L_{k+1}, z_b + h_k, z_b + h_{k+1}, dt),  x_0 measured
         v_{k+1} = v_k + a_k dt,  L_{k+1} = L_k + dt (v_k + v_{k+1}) / 2,  L_0, v_0 measured
         |a_k| <= accel_max,  0 <= s v_k <= speed_max,  s L_k <= s L*
         the tension and power limits of the OCP (tension_margin included)
         s (L* - L_N) >= v_N^2 / (2 accel_max) + s v_N dt / 2        (braking)

with L* the target, s the direction (+1 pay-out), D = |L* - cable.length|, and Phi the
line model's own implicit step (:class:`cable_ocp.schedule.ocp.LineStep`), transcribed by
implicit multiple shooting as the OCP (:mod:`cable_ocp.schedule.ocp`). The tension and
power limits are the OCP's own constraint groups
(:func:`~cable_ocp.schedule.ocp.limit_constraints`: one home for them); the end's rest is
not a horizon constraint (the horizon does not know when it ends) but the closed loop's
stopping rule (below). Choices, and why:

* *Distance to go, integrated* (not the time): with a horizon shorter than the deployment
  the time to the target is not a function of the horizon's decisions; its integral is,
  and its minimiser pays out as fast as the limits let it at every instant. The
  regulariser (eps = 1e-4) makes the minimiser unique at rest at the target (where the
  distance term no longer depends on the accelerations).
* *Braking* at the horizon's end: the winch can always stop before the target (the
  recursive feasibility of the kinematics; the tension limits during the stop are not
  guaranteed, the next plan sees them). The continuous stop takes v^2 / (2 a); the
  discrete one (decelerating at accel_max, the last step's deceleration what is left)
  v^2 / (2 a) + a dt^2 (f - f^2) / 2 with f the fractional part of v / (a dt), which
  s v dt / 2 bounds from above and which vanishes at rest (so a plan can land on the
  target). Without accel_max the stop takes one step: s v dt / 2.
* *Fixed step*: the plan's nodes are the plant's, so the first replan_interval / dt of its
  accelerations are applied exactly (piecewise constant, as in the OCP).
* *Built once*: the NLP's symbols are the parameters above; each re-plan calls the one
  solver (:attr:`HorizonNLP.builds` counts the builds), warm started from the previous
  solution shifted by the interval (its tail repeated).

The closed loop (:func:`receding_horizon`): the plant is the line model's own Newton step
(:attr:`LineStep.forward`, the same discretisation as the plan) driven by the true
motion; every ``replan_interval`` s (a whole number of steps) the horizon is solved from
the plant's state with the true heave over the preview (a perfect preview) and the first
interval of its accelerations applied (clipped to the limits: the applied schedule keeps
accel_max and speed_max exactly). A failed re-plan is counted and reported: the winch
goes on with the previous plan's remainder (planned from the state the plant then
reached: the model is the plant), and where none is left it brakes at accel_max. The run
ends at rest at the target: L within :data:`LENGTH_TOL` of it with the winch stopped, and
then (the winch held) the first node where the unit's speed relative to the ship is
within ``rest_tolerance`` (the OCP's end condition). The compensation (``ahc_stroke``,
``ahc_speed``) is not handled here.

The comparison (:func:`compare_receding`): for each unseen realisation, the open-loop
schedule (solved on the design motions) and the receding horizon's applied schedule on
that realisation, both re-simulated on the forward simulator
(:func:`cable_ocp.schedule.forward.resimulate`, independent of the transcription);
counted: slack, over tension_max, under tension_min, every limit kept.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import interrupt
from cable_ocp.scene.deployment import DeploymentProblem
from cable_ocp.scene.dynamics import DynamicScene
from cable_ocp.schedule.forward import ForwardCheck, Schedule, resimulate
from cable_ocp.schedule.ocp import LineStep, limit_constraints, line_step, static_tensions
from cable_ocp.schedule.planning import ramp_acceleration
from cable_ocp.schedule.sea import VesselMotion

__all__ = ["LENGTH_TOL", "REGULARISER", "HorizonNLP", "HorizonSolution", "RecedingComparison",
           "RecedingResult", "RecedingRow", "compare_receding", "horizon_nlp",
           "receding_horizon"]

#: m: the target is reached when the length is this close to it, the winch stopped
LENGTH_TOL = 1e-3
#: m/s: a speed this small at a node is a stopped winch (set to 0 there when the
#: acceleration that does so keeps accel_max)
SPEED_TOL = 1e-4
#: the weight eps of the accelerations' regulariser (module docstring)
REGULARISER = 1e-4
#: IPOPT's return statuses that count as solved
_SOLVED = ("Solve_Succeeded", "Solved_To_Acceptable_Level")
#: the largest constraint violation a solved plan may keep (scaled constraints, -)
_FEASIBLE = 1e-5


@dataclass(frozen=True, eq=False)
class HorizonSolution:
    """One re-plan (:meth:`HorizonNLP.solve`).

    Attributes
    ----------
    status : str
        ``"solved"`` or ``"failed"`` (IPOPT's status not a solution, or its point breaks
        a constraint by more than 1e-5 scaled).
    return_status : str
        IPOPT's.
    accel : numpy.ndarray (N_h,)
        m/s^2.
    speed, length : numpy.ndarray (N_h + 1,)
        m/s, m.
    w : numpy.ndarray
        The NLP's variables (the next warm start).
    iterations : int
        IPOPT's iterations.
    solve_time : float
        s.
    """

    status: str
    return_status: str
    accel: np.ndarray
    speed: np.ndarray
    length: np.ndarray
    w: np.ndarray
    iterations: int
    solve_time: float


class HorizonNLP:
    """The receding horizon's NLP (module docstring), built once, solved per re-plan.

    Parameters
    ----------
    scene : DynamicScene
        The scene (its start length fixes the direction and the bounds).
    line : LineStep
        The line's step (:func:`~cable_ocp.schedule.ocp.line_step`).
    problem : DeploymentProblem
        The limits.
    steps : int
        N_h.
    time_step : float
        dt, s.
    ipopt : dict, optional
        IPOPT options added to the defaults (``ipopt.`` prefixed keys).
    """

    #: the builds so far (every instance adds one: the loop must not build)
    builds = 0

    def __init__(self, scene: DynamicScene, line: LineStep, problem: DeploymentProblem,
                 steps: int, time_step: float, ipopt: dict[str, Any] | None = None) -> None:
        t0 = time.perf_counter()
        HorizonNLP.builds += 1
        pb = problem
        self.scene, self.line, self.problem = scene, line, pb
        self.steps, self.dt = int(steps), float(time_step)
        start, target = scene.length, pb.target_length
        s = 1.0 if target > start else -1.0
        self.direction = s
        dist = abs(target - start)
        n, dt = self.steps, self.dt
        nx, ny = line.start.size, line.y_scale.size
        self.nx, self.ny = nx, ny
        ts = max(*static_tensions(scene, max(start, target)), 1.0)
        xs, ys = ca.DM(line.x_scale), ca.DM(line.y_scale)
        # parameters: the measured state, the winch, the previewed heave
        x0 = ca.MX.sym("x0", nx)
        l0, v0 = ca.MX.sym("L0"), ca.MX.sym("v0")
        hv = ca.MX.sym("h", 1, n + 1)
        par = ca.vertcat(x0, l0, v0, ca.vec(hv))
        # variables
        acc = ca.MX.sym("a", 1, n)
        vel = ca.MX.sym("v", 1, n + 1)
        lng = ca.MX.sym("L", 1, n + 1)
        xr = ca.MX.sym("x", nx, n)
        yr = None if line.same else ca.MX.sym("y", ny, n)
        g_list: list[Any] = []
        lo_g: list[np.ndarray] = []
        hi_g: list[np.ndarray] = []

        def add(name: str, expr: Any, lo: Any, hi: Any) -> None:
            e = ca.vec(expr)
            k = e.shape[0]
            g_list.append(e)
            lo_g.append(np.broadcast_to(lo, (k,)).astype(float))
            hi_g.append(np.broadcast_to(hi, (k,)).astype(float))

        add("initial", vel[0] - v0, 0.0, 0.0)
        add("initial", (lng[0] - l0) / max(dist, 1.0), 0.0, 0.0)
        add("kinematics", vel[1:] - vel[:-1] - acc * dt, 0.0, 0.0)
        add("kinematics", (lng[1:] - lng[:-1] - 0.5 * dt * (vel[1:] + vel[:-1]))
            / max(dist, 1.0), 0.0, 0.0)
        zt = line.top_height + hv
        p = ca.vertcat(lng[:-1], lng[1:], zt[:-1], zt[1:])
        xx = ca.horzcat(x0, ca.diag(xs) @ xr)
        yy = ca.diag(xs) @ xr if line.same else ca.diag(ys) @ yr
        res, nxt, tens, outs = line.step.map(n)(yy, xx[:, :-1], p, ca.repmat(dt, 1, n))
        add("dynamics", res, 0.0, 0.0)
        if not line.same:
            add("dynamics", (nxt - xx[:, 1:]) / ca.repmat(xs, 1, n), 0.0, 0.0)
        limit_constraints(add, pb, ts, tens, outs, vel)
        need = s * vel[-1] * dt / 2.0
        if pb.accel_max is not None:
            need = need + vel[-1] ** 2 / (2.0 * pb.accel_max)
        add("braking", (s * (target - lng[-1]) - need) / max(dist, 1.0), 0.0, math.inf)
        a_ref = pb.accel_max if pb.accel_max is not None else ramp_acceleration(scene, pb)
        objective = (ca.sum2(s * (target - lng[1:])) / (max(dist, 1.0) * n)
                     + REGULARISER * ca.sumsqr(acc / a_ref) / n)
        parts = [ca.vec(acc), ca.vec(vel), ca.vec(lng), ca.vec(xr)]
        parts += [] if yr is None else [ca.vec(yr)]
        w = ca.vertcat(*parts)
        inf = math.inf
        a_max = pb.accel_max if pb.accel_max is not None else inf
        v_max = pb.speed_max if pb.speed_max is not None else inf
        lo_v, hi_v = (0.0, v_max) if s > 0 else (-v_max, 0.0)
        lo_l, hi_l = sorted((start, target))
        self._lbx = np.concatenate([np.full(n, -a_max), np.full(n + 1, lo_v),
                                    np.full(n + 1, lo_l), np.full(nx * n + (0 if yr is None
                                                                            else ny * n), -inf)])
        self._ubx = np.concatenate([np.full(n, a_max), np.full(n + 1, hi_v),
                                    np.full(n + 1, hi_l), np.full(nx * n + (0 if yr is None
                                                                           else ny * n), inf)])
        g_all = ca.vertcat(*g_list)
        self._lbg, self._ubg = np.concatenate(lo_g), np.concatenate(hi_g)
        opts = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes",
                "ipopt.max_iter": 300, "ipopt.tol": 1e-8, "ipopt.acceptable_tol": 1e-6,
                "ipopt.mu_strategy": "adaptive"}
        opts.update(ipopt or {})
        self._solver = ca.nlpsol("horizon", "ipopt", {"x": w, "p": par, "f": objective,
                                                      "g": g_all}, opts)
        self._rollout = line.forward.mapaccum(n)
        self.variables, self.constraints = int(w.shape[0]), int(g_all.shape[0])
        self.build_time = time.perf_counter() - t0

    def guess(self, x0: np.ndarray, length: float, speed: float, heave: np.ndarray
              ) -> np.ndarray:
        """The first warm start: the winch at its measured speed, coasting to rest at
        accel_max (or stopping in one step), the line rolled out under it on the
        previewed heave.

        Parameters
        ----------
        x0 : ndarray (nx,)
            The measured line state (SI).
        length, speed : float
            L_0 (m), v_0 (m/s).
        heave : ndarray (N_h + 1,)
            The previewed heave, m.
        """
        n, dt, s = self.steps, self.dt, self.direction
        a_max = self.problem.accel_max
        v = np.empty(n + 1)
        v[0] = speed
        for k in range(n):
            dv = s * v[k] if a_max is None else min(s * v[k], a_max * dt)
            v[k + 1] = v[k] - s * dv
        acc = np.diff(v) / dt
        lng = length + np.concatenate([[0.0], np.cumsum(0.5 * dt * (v[1:] + v[:-1]))])
        zt = self.line.top_height + np.asarray(heave, dtype=float)
        p = np.vstack([lng[:-1], lng[1:], zt[:-1], zt[1:]])
        xn, yn, _, _ = self._rollout(x0, p, np.full((1, n), dt))
        xn, yn = np.asarray(xn), np.asarray(yn)
        parts = [acc, v, lng, (xn / self.line.x_scale[:, None]).ravel(order="F")]
        if not self.line.same:
            parts.append((yn / self.line.y_scale[:, None]).ravel(order="F"))
        return np.concatenate(parts)

    def shifted(self, w: np.ndarray, shift: int) -> np.ndarray:
        """A solution's variables shifted by ``shift`` steps, the tail repeated (the next
        re-plan's warm start).

        Parameters
        ----------
        w : ndarray
            The previous solution's variables.
        shift : int
            Steps applied since (>= 0).
        """
        n = self.steps
        i = [0, n, 2 * n + 1, 3 * n + 2, 3 * n + 2 + self.nx * n]
        acc, vel, lng = w[i[0]:i[1]], w[i[1]:i[2]], w[i[2]:i[3]]
        xr = w[i[3]:i[4]].reshape(self.nx, n, order="F")

        def sh(a: np.ndarray, axis: int = 0) -> np.ndarray:
            k = a.shape[axis]
            idx = np.minimum(np.arange(k) + shift, k - 1)
            return np.take(a, idx, axis=axis)

        acc2 = sh(acc)
        acc2[max(n - shift, 0):] = 0.0
        parts = [acc2, sh(vel), sh(lng), sh(xr, 1).ravel(order="F")]
        if not self.line.same:
            yr = w[i[4]:].reshape(self.ny, n, order="F")
            parts.append(sh(yr, 1).ravel(order="F"))
        return np.concatenate(parts)

    def solve(self, x0: np.ndarray, length: float, speed: float, heave: np.ndarray,
              w0: np.ndarray) -> HorizonSolution:
        """One re-plan from the measured state.

        Parameters
        ----------
        x0 : ndarray (nx,)
            The measured line state (SI).
        length, speed : float
            L_0 (m), v_0 (m/s).
        heave : ndarray (N_h + 1,)
            The heave at the horizon's nodes, m.
        w0 : ndarray
            The warm start (:meth:`guess`, :meth:`shifted`).

        Raises
        ------
        KeyboardInterrupt
            On a Ctrl-C inside IPOPT.
        """
        n = self.steps
        par = np.concatenate([np.asarray(x0, dtype=float).ravel(), [length, speed],
                              np.asarray(heave, dtype=float).ravel()])
        t0 = time.perf_counter()
        res, stats = interrupt.call_solver(self._solver, x0=w0, p=par, lbx=self._lbx,
                                           ubx=self._ubx, lbg=self._lbg, ubg=self._ubg)
        elapsed = time.perf_counter() - t0
        ret = str(stats.get("return_status", "unknown"))
        w = np.asarray(res["x"]).ravel()
        g = np.asarray(res["g"]).ravel()
        with np.errstate(invalid="ignore"):
            viol = np.max(np.maximum(self._lbg - g, g - self._ubg), initial=0.0)
        ok = ret in _SOLVED and bool(np.isfinite(viol)) and viol <= _FEASIBLE
        return HorizonSolution(status="solved" if ok else "failed", return_status=ret,
                               accel=w[:n].copy(), speed=w[n:2 * n + 1].copy(),
                               length=w[2 * n + 1:3 * n + 2].copy(), w=w,
                               iterations=int(stats.get("iter_count", -1)),
                               solve_time=elapsed)


@dataclass(frozen=True, eq=False)
class RecedingResult:
    """A receding-horizon run on one vessel motion (:func:`receding_horizon`).

    Attributes
    ----------
    status : str
        ``"solved"`` (at rest at the target), ``"failed"`` (``max_time`` reached, or the
        plant's step failed: ``message`` says which) or ``"interrupted"``.
    message : str
        What happened.
    motion : str
        The motion's name.
    schedule : Schedule or None
        The applied schedule from t = 0 (time s, length m, speed m/s, accel m/s^2), to the
        end (or the interruption); None before the first step.
    arrival : float
        s, when the length reached the target with the winch stopped (nan if never).
    duration : float
        s, the run's end: at rest relative to the ship after the arrival (nan if never).
    replan_times : numpy.ndarray
        s, the re-plans' times (multiples of the interval).
    replan_status : tuple of str
        Each re-plan's ``"solved"`` or ``"failed"``.
    return_status : tuple of str
        IPOPT's status of each re-plan.
    iterations : numpy.ndarray of int
        IPOPT's iterations per re-plan.
    solve_times : numpy.ndarray
        s, per re-plan.
    failed_replans : int
        The re-plans that failed (the winch went on with the previous plan or braked).
    unit_tension, top_tension, tension_min_line : numpy.ndarray
        The plant's tensions at the schedule's nodes, N (node 0 the static start).
    rest_speed : float
        m/s, |V_unit - dh/dt| at the end (nan if never arrived).
    diagnostics : dict
        ``build_time_s``, ``horizon_steps``, ``replan_steps``, ``time_step_s``,
        ``variables``, ``constraints``, ``builds`` (of the NLP during the run: 0 when it
        was given).
    """

    status: str
    message: str
    motion: str
    schedule: Schedule | None
    arrival: float
    duration: float
    replan_times: np.ndarray
    replan_status: tuple[str, ...]
    return_status: tuple[str, ...]
    iterations: np.ndarray
    solve_times: np.ndarray
    failed_replans: int
    unit_tension: np.ndarray
    top_tension: np.ndarray
    tension_min_line: np.ndarray
    rest_speed: float = math.nan
    diagnostics: dict[str, Any] = field(default_factory=dict)

    @property
    def success(self) -> bool:
        """True when the run ended at rest at the target."""
        return self.status == "solved"


def _settings(scene: DynamicScene, problem: DeploymentProblem | None,
              replan_interval: float | None, preview: float | None,
              time_step: float | None) -> tuple[DeploymentProblem, float, int, int]:
    """(problem, dt (s), steps per re-plan, horizon steps), checked."""
    pb = problem if problem is not None else scene.deployment
    if pb is None:
        raise CableOCPError("[deployment] is missing: the receding horizon needs "
                            "target_length and its limits (docs/deployment.md)")
    if pb.ahc:
        raise CableOCPError("deployment.ahc_stroke / ahc_speed: the receding horizon does not "
                            "handle the heave compensation; remove them for this run")
    dt = float(time_step or pb.time_step or scene.simulation.time_step)
    interval = float(replan_interval if replan_interval is not None else pb.replan_interval)
    look = float(preview if preview is not None else pb.preview)
    if not (dt > 0.0 and math.isfinite(dt)):
        raise CableOCPError(f"receding horizon: time_step = {dt} s must be > 0")
    m = round(interval / dt)
    if m < 1 or abs(m * dt - interval) > 1e-9 * max(interval, 1.0):
        raise CableOCPError(f"deployment.replan_interval = {interval:.6g} s: give a whole "
                            f"number (>= 1) of the horizon's steps of {dt:.6g} s")
    n_h = math.ceil(look / dt - 1e-9)
    if not (math.isfinite(look) and n_h >= m):
        raise CableOCPError(f"deployment.preview = {look:.6g} s: give at least the "
                            f"replan_interval = {interval:.6g} s (the plan must cover it)")
    return pb, dt, m, n_h


def horizon_nlp(scene: DynamicScene, *, problem: DeploymentProblem | None = None,
                replan_interval: float | None = None, preview: float | None = None,
                segments: int | None = None, time_step: float | None = None,
                ipopt: dict[str, Any] | None = None) -> HorizonNLP:
    """The horizon's NLP of a scene (one build; :func:`receding_horizon` takes it to run
    several motions on one build).

    Parameters
    ----------
    scene : DynamicScene
        With its ``[deployment]``.
    problem : DeploymentProblem, optional
        Default ``scene.deployment``.
    replan_interval, preview : float, optional
        s (default ``deployment.replan_interval``, ``deployment.preview``).
    segments : int, optional
        Elements (default ``deployment.segments``, else the scene's).
    time_step : float, optional
        dt, s (default ``deployment.time_step``, else the scene's).
    ipopt : dict, optional
        Extra IPOPT options.
    """
    pb, dt, _, n_h = _settings(scene, problem, replan_interval, preview, time_step)
    return HorizonNLP(scene, line_step(scene, segments), pb, n_h, dt, ipopt)


def _default_max_time(scene: DynamicScene, pb: DeploymentProblem) -> float:
    """s: ten times the fastest kinematic trapezoid (speed_max, the ramp's acceleration),
    and at least 600 s."""
    dist = abs(pb.target_length - scene.length)
    a = ramp_acceleration(scene, pb)
    v = pb.speed_max if pb.speed_max is not None else math.sqrt(a * dist)
    return max(600.0, 10.0 * (dist / v + v / a))


def receding_horizon(scene: DynamicScene, motion: VesselMotion, *,
                     problem: DeploymentProblem | None = None,
                     replan_interval: float | None = None, preview: float | None = None,
                     segments: int | None = None, time_step: float | None = None,
                     max_time: float | None = None, ipopt: dict[str, Any] | None = None,
                     horizon: HorizonNLP | None = None) -> RecedingResult:
    """The receding-horizon deployment on one (true) vessel motion (module docstring).

    Parameters
    ----------
    scene : DynamicScene
        With its ``[deployment]``.
    motion : VesselMotion
        The true motion: the plant's and (over the preview) the plan's.
    problem : DeploymentProblem, optional
        Default ``scene.deployment``.
    replan_interval : float, optional
        s, a whole number of steps (default ``deployment.replan_interval``).
    preview : float, optional
        s, >= replan_interval (default ``deployment.preview``).
    segments : int, optional
        Elements of the plan's and the plant's line (default ``deployment.segments``).
    time_step : float, optional
        dt, s (default ``deployment.time_step``, else the scene's).
    max_time : float, optional
        s, the run gives up after this (default ten times the kinematic trapezoid, at
        least 600 s).
    ipopt : dict, optional
        Extra IPOPT options (e.g. ``{"ipopt.max_iter": 50}``).
    horizon : HorizonNLP, optional
        A built NLP (:func:`horizon_nlp`) of the same problem and settings; default: built
        here.

    Raises
    ------
    CableOCPError
        No ``[deployment]``, the compensation on, an interval that is not a whole number
        of steps, a preview shorter than it.
    """
    pb, dt, m, n_h = _settings(scene, problem, replan_interval, preview, time_step)
    builds0 = HorizonNLP.builds
    nlp = horizon if horizon is not None else HorizonNLP(
        scene, line_step(scene, segments), pb, n_h, dt, ipopt)
    if nlp.steps != n_h or abs(nlp.dt - dt) > 1e-12 * dt:
        raise CableOCPError(f"receding_horizon: the given horizon has {nlp.steps} steps of "
                            f"{nlp.dt:.6g} s; the settings ask {n_h} of {dt:.6g} s")
    line = nlp.line
    s = nlp.direction
    target = pb.target_length
    a_max = pb.accel_max if pb.accel_max is not None else math.inf
    v_max = pb.speed_max if pb.speed_max is not None else math.inf
    t_end = float(max_time if max_time is not None else _default_max_time(scene, pb))
    k_max = math.ceil(t_end / dt - 1e-9)
    ts0 = static_tensions(scene, scene.length)
    x = np.asarray(line.start, dtype=float).copy()
    length, speed = float(scene.length), 0.0
    ts_v, vs_v = [0.0], [0.0]  # the applied schedule: node times (s), speeds (m/s)
    unit_t, top_t, min_t = [ts0[0]], [ts0[1]], [min(ts0)]
    r_t: list[float] = []
    r_st: list[str] = []
    r_ret: list[str] = []
    r_it: list[int] = []
    r_time: list[float] = []
    plan: list[float] = []  # the accelerations still planned from now on
    w_prev: np.ndarray | None = None
    since = 0  # steps since the last successful plan
    status, message = "failed", ""
    arrival = duration = rest_speed = math.nan
    k = 0
    vz_unit = 0.0

    def brake(v: float) -> float:
        return -s * min(s * v / dt, a_max)

    def arrived() -> bool:
        return s * (target - length) <= LENGTH_TOL and speed == 0.0

    fwd: dict[int, ca.Function] = {}  # the plant's steps over an interval, one call each

    def plant(x0: np.ndarray, lengths: Sequence[float], t0: float
              ) -> tuple[np.ndarray, np.ndarray]:
        """The plant (the line's step, Newton) over len(lengths) - 1 steps from t0: the
        states (nx, n) and the outputs (5, n) at the steps' ends."""
        n = len(lengths) - 1
        if n not in fwd:
            fwd[n] = line.forward.mapaccum(n)
        zt = line.top_height + motion.heave(t0 + dt * np.arange(n + 1))
        lv = np.asarray(lengths, dtype=float)
        p = np.vstack([lv[:-1], lv[1:], zt[:-1], zt[1:]])
        xn, _, _, outs = fwd[n](x0, p, np.full((1, n), dt))
        return np.asarray(xn).reshape(-1, n), np.asarray(outs).reshape(-1, n)

    def record(t1: np.ndarray, v1: Sequence[float], outs: np.ndarray) -> None:
        ts_v.extend(t1.tolist())
        vs_v.extend(v1)
        unit_t.extend(outs[2].tolist())
        top_t.extend(outs[3].tolist())
        min_t.extend(outs[4].tolist())

    try:
        while k < k_max:
            if arrived():
                arrival = k * dt
                break
            if k % m == 0:
                tk = k * dt
                hv = motion.heave(tk + np.arange(n_h + 1) * dt)
                w0 = nlp.guess(x, length, speed, hv) if w_prev is None else nlp.shifted(
                    w_prev, since)
                sol = nlp.solve(x, length, speed, hv, w0)
                r_t.append(tk)
                r_st.append(sol.status)
                r_ret.append(sol.return_status)
                r_it.append(sol.iterations)
                r_time.append(sol.solve_time)
                if sol.status == "solved":
                    plan, w_prev, since = list(sol.accel), sol.w, 0
            # the winch to the next re-plan (or the arrival), then the plant in one call
            ls, vs, accs = [length], [speed], []
            while k + len(accs) < k_max and len(accs) < m - k % m:
                if s * (target - ls[-1]) <= LENGTH_TOL and vs[-1] == 0.0:
                    break  # arrived
                v0 = vs[-1]
                a = plan.pop(0) if plan else brake(v0)
                # the limits exactly: |a| <= accel_max, 0 <= s v <= speed_max
                a = min(max(a, -a_max), a_max)
                lo, hi = (0.0, v_max) if s > 0 else (-v_max, 0.0)
                v1 = min(max(v0 + a * dt, lo), hi)
                if abs(v1) <= SPEED_TOL and abs(v0) <= a_max * dt:
                    v1 = 0.0
                accs.append((v1 - v0) / dt)
                ls.append(ls[-1] + 0.5 * dt * (v0 + v1))
                vs.append(v1)
            n = len(accs)
            xn, outs = plant(x, ls, k * dt)
            good = np.all(np.isfinite(xn), axis=0) & np.all(np.isfinite(outs), axis=0)
            keep = n if bool(np.all(good)) else int(np.argmin(good))
            t1 = (k + 1 + np.arange(keep)) * dt
            record(t1, vs[1:keep + 1], outs[:, :keep])
            if keep:
                x, length, speed = xn[:, keep - 1], ls[keep], vs[keep]
                vz_unit = float(outs[1, keep - 1])
            k += keep
            since += keep
            if keep < n:
                message = f"the plant's step failed at t = {(k + 1) * dt:.4g} s"
                break
        if math.isnan(arrival) and arrived():
            arrival = k * dt
        if not math.isnan(arrival):
            # the winch held: the end is the first node at rest relative to the ship
            while True:
                rest_speed = abs(vz_unit - float(motion.heave_rate(np.array([k * dt]))[0]))
                if rest_speed <= pb.rest_tolerance:
                    duration = k * dt
                    status = "solved"
                    message = (f"at rest at the target at {duration:.4g} s (arrived at "
                               f"{arrival:.4g} s)")
                    break
                if k >= k_max:
                    message = (f"arrived at {arrival:.4g} s but not at rest (relative speed "
                               f"{rest_speed:.3g} m/s) by max_time = {t_end:.4g} s")
                    break
                # held over up to one interval in one call; the first node at rest ends it
                n = min(m, k_max - k)
                xn, outs = plant(x, [length] * (n + 1), k * dt)
                t1 = (k + 1 + np.arange(n)) * dt
                rel = np.abs(outs[1] - motion.heave_rate(t1))
                at_rest = np.flatnonzero(rel <= pb.rest_tolerance)
                keep = int(at_rest[0]) + 1 if at_rest.size else n
                record(t1[:keep], [0.0] * keep, outs[:, :keep])
                x, vz_unit = xn[:, keep - 1], float(outs[1, keep - 1])
                k += keep
        elif not message:
            message = (f"not at the target by max_time = {t_end:.4g} s (at {length:.6g} m, "
                       f"{speed:.3g} m/s)")
    except KeyboardInterrupt:
        status, message = "interrupted", f"interrupted at t = {k * dt:.4g} s"
    failed = sum(1 for st in r_st if st != "solved")
    if failed and status == "solved":
        message += f"; {failed} of {len(r_st)} re-plans failed"
    sched = None
    if len(ts_v) >= 2:
        sched = Schedule.from_speed(np.array(ts_v), np.array(vs_v), float(scene.length))
    diag = {"build_time_s": nlp.build_time, "horizon_steps": n_h, "replan_steps": m,
            "time_step_s": dt, "variables": nlp.variables, "constraints": nlp.constraints,
            "builds": HorizonNLP.builds - builds0}
    return RecedingResult(status=status, message=message, motion=motion.name, schedule=sched,
                          arrival=arrival, duration=duration, replan_times=np.array(r_t),
                          replan_status=tuple(r_st), return_status=tuple(r_ret),
                          iterations=np.array(r_it, dtype=int),
                          solve_times=np.array(r_time), failed_replans=failed,
                          unit_tension=np.array(unit_t), top_tension=np.array(top_t),
                          tension_min_line=np.array(min_t), rest_speed=rest_speed,
                          diagnostics=diag)


@dataclass(frozen=True, eq=False)
class RecedingRow:
    """One unseen realisation of :func:`compare_receding`.

    Attributes
    ----------
    motion : str
        The realisation's name.
    open_loop : ForwardCheck
        The open-loop schedule re-simulated on it.
    receding : ForwardCheck or None
        The receding horizon's applied schedule re-simulated on it (None when the run did
        not reach the target: it counts as failed).
    run : RecedingResult
        The receding-horizon run.
    """

    motion: str
    open_loop: ForwardCheck
    receding: ForwardCheck | None
    run: RecedingResult


def _tally(checks: Sequence[ForwardCheck | None], tol: float) -> dict[str, int]:
    """Counts of the runs (:func:`cable_ocp.schedule.robust.count_checks`): ``runs``,
    ``slack``, ``over_tension_max``, ``under_tension_min``, ``keeps_limits``, ``failed`` (a run
    without a schedule counts as failed)."""
    from cable_ocp.schedule.robust import count_checks

    done = [c for c in checks if c is not None]
    d = count_checks("", math.nan, done, tol, keep=False).as_dict()
    return {"runs": len(checks), "slack": d["slack"], "over_tension_max": d["over_tension_max"],
            "under_tension_min": d["under_tension_min"], "keeps_limits": d["keeps_limits"],
            "failed": d["failed"] + len(checks) - len(done)}


@dataclass(frozen=True, eq=False)
class RecedingComparison:
    """The open-loop schedule against the receding horizon on unseen realisations
    (:func:`compare_receding`).

    Attributes
    ----------
    status : str
        ``"solved"`` (every realisation run) or ``"interrupted"``.
    rows : tuple of RecedingRow
        Per realisation.
    open_loop_duration : float
        s.
    counts : dict
        ``{"open_loop": {...}, "receding": {...}}``: the counts of :func:`_tally` (runs,
        slack, over_tension_max, under_tension_min, keeps_limits, failed).
    tol : float
        The relative excess counted as a violation (-).
    """

    status: str
    rows: tuple[RecedingRow, ...]
    open_loop_duration: float
    counts: dict[str, dict[str, int]]
    tol: float

    @property
    def durations(self) -> np.ndarray:
        """s, the receding horizon's duration per realisation (nan: not at rest at the
        target)."""
        return np.array([r.run.duration for r in self.rows])

    @property
    def solve_times(self) -> np.ndarray:
        """s, every re-plan's solve time over the realisations."""
        parts = [r.run.solve_times for r in self.rows]
        return np.concatenate(parts) if parts else np.zeros(0)

    @property
    def failed_replans(self) -> int:
        """The failed re-plans over the realisations."""
        return sum(r.run.failed_replans for r in self.rows)


def compare_receding(scene: DynamicScene, motions: Sequence[VesselMotion],
                     open_loop: Schedule, *, problem: DeploymentProblem | None = None,
                     replan_interval: float | None = None, preview: float | None = None,
                     segments: int | None = None, time_step: float | None = None,
                     max_time: float | None = None, check_time_step: float | None = None,
                     check_segments: int | None = None, hold: float = 20.0,
                     tol: float = 0.01, ipopt: dict[str, Any] | None = None
                     ) -> RecedingComparison:
    """The open-loop schedule and the receding horizon on each (unseen) motion, both
    re-simulated on the forward simulator (module docstring). One horizon NLP is built
    for every motion (its heave is a parameter).

    Parameters
    ----------
    scene : DynamicScene
        With its ``[deployment]`` (the limits of the check: the raw ones, without the
        margin).
    motions : sequence of VesselMotion
        The realisations (:func:`cable_ocp.schedule.sea.vessel_motions` ``"unseen"``).
    open_loop : Schedule
        The schedule solved on the design motions
        (:func:`~cable_ocp.schedule.planning.solve_schedule`).
    problem, replan_interval, preview, segments, time_step, max_time, ipopt
        Of the receding horizon (:func:`receding_horizon`).
    check_time_step : float, optional
        s, the forward simulator's step (default ``simulation.time_step``).
    check_segments : int, optional
        Its elements (default ``simulation.segments``).
    hold : float
        s simulated after each schedule's end.
    tol : float
        Relative excess counted as a violation (-; 0.01: the 1 % of the issue's check).

    Raises
    ------
    CableOCPError
        No motion, or an invalid setting (:func:`receding_horizon`).
    """
    if not motions:
        raise CableOCPError("compare_receding: give at least one vessel motion")
    nlp = horizon_nlp(scene, problem=problem, replan_interval=replan_interval,
                      preview=preview, segments=segments, time_step=time_step, ipopt=ipopt)
    rows: list[RecedingRow] = []
    status = "solved"
    for mo in motions:
        run = receding_horizon(scene, mo, problem=problem, replan_interval=replan_interval,
                               preview=preview, time_step=time_step, max_time=max_time,
                               horizon=nlp)
        if run.status == "interrupted" or interrupt.requested():
            status = "interrupted"
            break
        ol = resimulate(scene, open_loop, mo, time_step=check_time_step,
                        segments=check_segments, hold=hold)
        rh = None
        if run.success and run.schedule is not None:
            rh = resimulate(scene, run.schedule, mo, time_step=check_time_step,
                            segments=check_segments, hold=hold)
        rows.append(RecedingRow(motion=mo.name, open_loop=ol, receding=rh, run=run))
    counts = {"open_loop": _tally([r.open_loop for r in rows], tol),
              "receding": _tally([r.receding for r in rows], tol)}
    return RecedingComparison(status=status, rows=tuple(rows),
                              open_loop_duration=open_loop.duration, counts=counts, tol=tol)
