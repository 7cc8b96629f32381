"""A pay-out schedule re-simulated on the forward simulator, its limits checked; the
fastest constant-speed (trapezoid) schedule by bisection.

A :class:`Schedule` is the winch's length L(t) (m of unstretched cable paid out, > 0
lowering) with a piecewise-linear speed dL/dt and so a piecewise-constant acceleration: L
is the speed's exact (piecewise-quadratic) integral, the law of ``top_motion.payout_law =
"table"`` with ``payout_speed_table`` (:func:`cable_ocp.scene.motion.table_length_expr`).
With heave compensation of gain g the winch pays out L(t) + g z(t), z the vessel's heave
(:class:`cable_ocp.schedule.sea.VesselMotion`).

:func:`resimulate` runs the scene's model (:func:`cable_ocp.dynamics.simulate`) with the
schedule and a vessel motion and measures the tensions, speed, acceleration and power
against the limits of ``[deployment]`` (:class:`cable_ocp.scene.deployment.DeploymentProblem`;
the raw limits, without ``tension_margin``, which is the OCP's margin against the sea it
does not know). :func:`fastest_constant_speed` is the baseline of the optimal schedule: the
fastest cruise speed of a trapezoid (ramped at ``accel_max``) that keeps every limit on
every given motion.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from cable_ocp.dynamics import simulate
from cable_ocp.dynamics.axial import AxialModel
from cable_ocp.dynamics.driven import axial_unit_pull
from cable_ocp.errors import CableOCPError
from cable_ocp.scene.dynamics import DynamicScene, dynamic_scene_from_dict
from cable_ocp.schedule.ocp import constrained_tensions
from cable_ocp.schedule.sea import VesselMotion

__all__ = ["CHECK_HOLD", "JUMP_RAMP", "MAX_SAMPLES", "ConstantSpeedResult", "ForwardCheck",
           "Schedule", "fastest_constant_speed", "resimulate", "trapezoid_schedule",
           "worst_violations"]

#: s: a speed step without an acceleration limit is a linear ramp this short (the
#: Schedule keeps every interval of positive length; the simulator's step of 1e-3..1e-1 s
#: sees it as the jump)
JUMP_RAMP = 1e-6
#: s simulated after a schedule's end, the winch stopped (the default ``hold`` of
#: :func:`resimulate` and :func:`fastest_constant_speed`, the forward check's, and what
#: ``hold`` of :func:`cable_ocp.schedule.planning.verified_schedule` gives the OCP to match)
CHECK_HOLD = 20.0
#: the most samples a re-simulation stores (output_step a multiple of time_step above it;
#: the check reads the limits at the samples only). 40 000: every step of a 2000 s run
#: at 0.05 s (an axial line of 20 elements: about 50 MB); it was 4000 until 2026-12-03,
#: so that a 0.1 s check of the 6.3.6 line's 560 s read every second step and missed
#: 90 N of the start ramp's dip (docs/deployment.md, "The 6.3.6 line with compensation")
MAX_SAMPLES = 40000
#: relative allowance of the commanded acceleration against accel_max (round-off)
ACCEL_ROUNDOFF = 1e-9
#: the bracket's top without speed_max and without unit drag, m/s (checked first)
FALLBACK_SPEED = 10.0
#: the bisection's floor without one given: the bracket's top over this, m/s
FLOOR_DIVISOR = 32.0
#: speeds tried between the bracket's top and the floor (a geometric grid, from the top
#: down) before the bisection: the first accepted one and the rejected one above bracket it
SCAN = 6


@dataclass(frozen=True, eq=False)
class Schedule:
    """A pay-out schedule: piecewise-linear speed, its exact integral the length.

    Attributes
    ----------
    time : numpy.ndarray (N+1,)
        Nodes, s, from 0, strictly increasing.
    length : numpy.ndarray (N+1,)
        Unstretched length at the nodes, m (L_0 the scene's cable.length).
    speed : numpy.ndarray (N+1,)
        dL/dt at the nodes, m/s (> 0 pays out); linear between nodes.
    accel : numpy.ndarray (N,)
        d^2L/dt^2 on each interval, m/s^2 (constant there).
    ahc_gain : float
        g, -: the heave compensation's gain; the winch pays out L(t) + g z(t).
    """

    time: np.ndarray
    length: np.ndarray
    speed: np.ndarray
    accel: np.ndarray
    ahc_gain: float = 0.0

    @classmethod
    def from_speed(cls, time: np.ndarray, speed: np.ndarray, start: float,
                   ahc_gain: float = 0.0) -> Schedule:
        """The schedule of nodal speeds (linear between) from the length ``start``.

        Parameters
        ----------
        time : numpy.ndarray (N+1,)
            s, from 0, strictly increasing.
        speed : numpy.ndarray (N+1,)
            m/s.
        start : float
            L(0), m.
        ahc_gain : float
            g, -.
        """
        t = np.asarray(time, dtype=float)
        v = np.asarray(speed, dtype=float)
        if t.ndim != 1 or t.shape != v.shape or len(t) < 2:
            raise CableOCPError("Schedule: time and speed need the same length >= 2")
        if t[0] != 0.0 or np.any(np.diff(t) <= 0.0):
            raise CableOCPError("Schedule: times must start at 0 and increase strictly")
        dt = np.diff(t)
        length = start + np.concatenate(([0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * dt)))
        return cls(time=t, length=length, speed=v, accel=np.diff(v) / dt,
                   ahc_gain=float(ahc_gain))

    @property
    def duration(self) -> float:
        """The last node's time, s."""
        return float(self.time[-1])

    def speed_table(self) -> list[list[float]]:
        """Rows [t, v] (s, m/s) of ``top_motion.payout_speed_table`` (the compensation
        not included: :func:`resimulate` adds it)."""
        return [[float(t), float(v)] for t, v in zip(self.time, self.speed, strict=True)]


def trapezoid_schedule(start: float, target: float, speed: float, accel_max: float | None,
                       hold: float = 0.0, ahc_gain: float = 0.0) -> Schedule:
    """Constant speed between two ramps at ``accel_max``: start -> target.

    The duration is D / v + v / a (D = |target - start|) when D >= v^2 / a; else a
    triangle of peak speed sqrt(D a) and duration 2 sqrt(D / a). Without an acceleration
    limit the ramps take :data:`JUMP_RAMP` s each.

    Parameters
    ----------
    start, target : float
        Lengths, m (a haul-in when target < start: negative speeds).
    speed : float
        The cruise speed's magnitude, m/s, > 0.
    accel_max : float or None
        m/s^2, > 0; None: a jump (module constant :data:`JUMP_RAMP`).
    hold : float
        s of rest appended at the end, >= 0.
    ahc_gain : float
        g, -, in [0, 1]: the heave compensation's gain (:attr:`Schedule.ahc_gain`).
    """
    _check_gain("trapezoid_schedule", ahc_gain)
    if not speed > 0.0:
        raise CableOCPError(f"trapezoid_schedule: speed = {speed} m/s must be > 0")
    if accel_max is not None and not accel_max > 0.0:
        raise CableOCPError(f"trapezoid_schedule: accel_max = {accel_max} m/s^2 must be > 0")
    if hold < 0.0:
        raise CableOCPError(f"trapezoid_schedule: hold = {hold} s must be >= 0")
    dist = abs(target - start)
    if not dist > 0.0:
        raise CableOCPError(f"trapezoid_schedule: target = {target} m equals start")
    sign = 1.0 if target > start else -1.0
    a = accel_max if accel_max is not None else speed / JUMP_RAMP
    if dist > speed**2 / a * (1.0 + 1e-12):
        t1 = speed / a
        t2 = dist / speed
        time = [0.0, t1, t2, t2 + t1]
        v = [0.0, speed, speed, 0.0]
    else:
        tp = math.sqrt(dist / a)
        time = [0.0, tp, 2.0 * tp]
        v = [0.0, a * tp, 0.0]
    if hold > 0.0:
        time.append(time[-1] + hold)
        v.append(0.0)
    sched = Schedule.from_speed(np.array(time), sign * np.array(v), start)
    # the trapezoidal sums carry round-off: the end is the target by construction
    length = sched.length.copy()
    length[-1 - (hold > 0.0):] = target
    return Schedule(time=sched.time, length=length, speed=sched.speed, accel=sched.accel,
                    ahc_gain=float(ahc_gain))


def _check_gain(where: str, gain: float) -> None:
    """The compensation's gain must be in [0, 1] (-), as the OCP's bounds on g."""
    if not 0.0 <= gain <= 1.0:
        raise CableOCPError(f"{where}: ahc_gain = {gain} must be in [0, 1] (the heave "
                            "compensation's gain; 0 without compensation)")


@dataclass(frozen=True, eq=False)
class ForwardCheck:
    """A schedule re-simulated on one vessel motion (:func:`resimulate`).

    Attributes
    ----------
    status : str
        The simulation's ``"solved"``, ``"slack"`` or ``"failed"``.
    message : str
        Its message.
    motion : str
        The motion's name.
    t : numpy.ndarray (n,)
        Samples, s.
    length : numpy.ndarray (n,)
        Unstretched length, m (the simulator's).
    speed : numpy.ndarray (n,)
        The winch's commanded dL/dt with the compensation, m/s.
    tension_min_line, tension_max_line : numpy.ndarray (n,)
        The smallest and largest element tension per sample, N.
    top_tension : numpy.ndarray (n,)
        At the sheave, N.
    unit_tension : numpy.ndarray (n,)
        The line's pull on the unit, N: on the axial line element 0's tension less the half
        element node 0 carries (:func:`cable_ocp.dynamics.driven.axial_unit_pull`, the
        OCP's own ``tension_at = "unit"``; the unit's acceleration the samples' central
        differences); on the planar line element 0's tension (at its middle: the pull
        plus about half an element's weight). Until 2026-12-03 (gap636) element 0's on
        both, w h / 2 above the OCP's (1350 N on 1000 m of the 6.3.6 line at 20
        elements).
    power : numpy.ndarray (n,)
        top_tension |v|, W, v the schedule's own pay-out speed (the compensation not
        included: the OCP's winch power, :func:`cable_ocp.schedule.ocp.winch_power`).
    accel_peak : float
        The largest |d^2L/dt^2| of the schedule's own pay-out over the run, m/s^2 (the
        compensation's g d^2z/dt^2 not included, as the OCP's accel_max).
    violations : dict of str to float
        Per limit imposed in ``[deployment]`` (``tension_min``, ``tension_max``,
        ``speed_max``, ``accel_max``, ``power_max``; with a compensation's gain g > 0 and
        ``ahc_stroke`` / ``ahc_speed`` given, those too): the worst relative excess, e.g.
        (limit - min) / limit for tension_min, 0 when inside (a zero tension_min is
        measured on the first sample's top tension); inf when the run has no sample.
        As in the OCP, speed_max, accel_max and power_max bound the schedule's own
        pay-out (v, its acceleration), and the compensation is bounded apart:
        |g z| <= ahc_stroke and |g dz/dt| <= ahc_speed, measured on the motion itself at
        the samples (a property of g and the heave only).
    slack : bool
        The simulator found a tension <= 0.
    """

    status: str
    message: str
    motion: str
    t: np.ndarray
    length: np.ndarray
    speed: np.ndarray
    tension_min_line: np.ndarray
    tension_max_line: np.ndarray
    top_tension: np.ndarray
    unit_tension: np.ndarray
    power: np.ndarray
    accel_peak: float
    violations: dict[str, float] = field(default_factory=dict)
    slack: bool = False

    def keeps_limits(self, tol: float = 0.01) -> bool:
        """True when the run is ``"solved"`` (no slack) and every violation <= ``tol``
        (relative, -)."""
        return (self.status == "solved" and not self.slack
                and all(v <= tol for v in self.violations.values()))

    @property
    def binding(self) -> str | None:
        """The limit of the largest violation (None without limits)."""
        if not self.violations:
            return None
        return max(self.violations, key=lambda k: self.violations[k])


def _motion_keys(motion: VesselMotion, duration: float, step: float) -> dict[str, Any]:
    """The ``[top_motion]`` keys of the vessel's heave: the scene's own harmonic heave as
    its exact keys, else a series."""
    tm = motion.top_motion
    if tm is not None and not tm.series:
        if tm.heave_amplitude == 0.0:
            return {}
        return {"heave_amplitude": tm.heave_amplitude, "heave_frequency": tm.heave_frequency,
                "ramp_time": tm.ramp_time}
    if not motion.amplitudes and not motion.series:
        return {}
    z0 = float(motion.heave(np.array([0.0]))[0])
    if abs(z0) > 1e-12:
        raise CableOCPError(f"resimulate: the motion {motion.name!r} starts at z = {z0:.4g} m; "
                            "the simulator starts at rest at end_b.position: give "
                            "deployment.sea.fade_in > 0")
    return {"series": motion.series_rows(duration, step)}


def _speed_rows(schedule: Schedule, motion: VesselMotion, duration: float,
                step: float) -> tuple[np.ndarray, np.ndarray]:
    """(t, v) of the winch's speed table: the schedule's, plus g dz/dt on the grid."""
    if schedule.ahc_gain == 0.0:
        return schedule.time, schedule.speed
    n = max(1, math.ceil(duration / step - 1e-9))
    grid = np.union1d(schedule.time, np.linspace(0.0, n * step, n + 1))
    keep = np.concatenate(([True], np.diff(grid) > 1e-9 * step))
    grid = grid[keep]
    v = np.interp(grid, schedule.time, schedule.speed) + schedule.ahc_gain * motion.heave_rate(
        grid)
    return grid, v


def _relative_excess(value: float, limit: float, scale: float, upper: bool) -> float:
    ref = limit if limit > 0.0 else scale
    excess = (value - limit) if upper else (limit - value)
    return max(0.0, excess / ref)


def resimulate(scene: DynamicScene, schedule: Schedule, motion: VesselMotion, *,
               time_step: float | None = None, segments: int | None = None,
               hold: float = CHECK_HOLD, motion_step: float | None = None) -> ForwardCheck:
    """Run the forward simulator with a schedule and a vessel motion; check the limits.

    The scene's ``[top_motion]`` is replaced: ``payout_law = "table"`` with the
    schedule's speed table (with compensation, the speed plus g dz/dt on a grid of
    ``motion_step``), and the heave: the scene's own harmonic heave by its exact keys
    (heave_amplitude, heave_frequency, ramp_time), any other motion as a ``series`` sampled
    every ``motion_step`` (ramp_time 0). ``simulation.duration`` is the schedule's
    duration plus ``hold``, rounded up to whole steps.

    Parameters
    ----------
    scene : DynamicScene
        The scene; its ``[deployment]`` gives the limits (none: no violations).
    schedule : Schedule
        From L(0) = cable.length.
    motion : VesselMotion
        The vessel's heave.
    time_step : float, optional
        s (default ``simulation.time_step``).
    segments : int, optional
        Elements (default ``simulation.segments``).
    hold : float
        s simulated after the schedule's end (the winch at rest), >= 0.
    motion_step : float, optional
        s, the series' and the compensation's sampling (default ``time_step``).

    Raises
    ------
    CableOCPError
        The schedule does not start at cable.length; an invalid value (named).
    """
    if abs(schedule.length[0] - scene.length) > 1e-9 * scene.length:
        raise CableOCPError(f"resimulate: the schedule starts at {schedule.length[0]} m, the "
                            f"scene at cable.length = {scene.length} m")
    if hold < 0.0:
        raise CableOCPError(f"resimulate: hold = {hold} s must be >= 0")
    dt = float(time_step if time_step is not None else scene.simulation.time_step)
    if not dt > 0.0:
        raise CableOCPError(f"resimulate: time_step = {dt} s must be > 0")
    mstep = float(motion_step if motion_step is not None else dt)
    steps = max(1, math.ceil((schedule.duration + hold) / dt - 1e-9))
    every = max(1, math.ceil(steps / MAX_SAMPLES))
    steps = every * math.ceil(steps / every)
    duration = steps * dt
    raw = copy.deepcopy(scene.raw)
    tt, vv = _speed_rows(schedule, motion, duration, mstep)
    top: dict[str, Any] = {"payout_law": "table",
                           "payout_speed_table": [[float(a), float(b)] for a, b in zip(
                               tt, vv, strict=True)]}
    top.update(_motion_keys(motion, duration, mstep))
    raw["top_motion"] = top
    sim = dict(raw["simulation"])
    sim.update(duration=duration, time_step=dt, output_step=every * dt,
               segments=int(segments if segments is not None else scene.simulation.segments))
    raw["simulation"] = sim
    run_scene = dynamic_scene_from_dict(raw)
    res = simulate(run_scene)

    t = np.asarray(res.t, dtype=float)
    ten = np.asarray(res.segment_tensions, dtype=float).reshape(len(t), -1)
    top_t = np.asarray(res.top_tension, dtype=float)
    speed = np.interp(t, tt, vv)
    # the limits of the pay-out are the schedule's own (the OCP's v and a); the
    # compensation's g z is bounded by ahc_stroke / ahc_speed below
    own = np.interp(t, schedule.time, schedule.speed, right=0.0)
    live = schedule.time[:-1] < (t[-1] if len(t) else 0.0)
    accel_peak = float(np.max(np.abs(schedule.accel[live]))) if np.any(live) else 0.0
    empty = len(t) == 0
    tmin = ten.min(axis=1) if not empty else np.zeros(0)
    tmax = ten.max(axis=1) if not empty else np.zeros(0)
    unit = ten[:, 0] if not empty else np.zeros(0)
    if run_scene.simulation.model == "axial" and len(t) > 1:
        # the pull on the unit, as the OCP's (axial_unit_pull: one home)
        v0 = np.asarray(res.node_velocities, dtype=float)[:, 0, 2]
        a0 = np.gradient(v0, t)
        line = AxialModel(run_scene)
        unit = axial_unit_pull(line, unit, np.asarray(res.length, dtype=float) / line.n, v0,
                               a0)
    power = top_t * np.abs(own)
    viol: dict[str, float] = {}
    dp = scene.deployment
    if dp is not None:
        scale = float(top_t[0]) if not empty else 1.0
        # the OCP's selection (constrained_tensions: every element, the unit, the top)
        outs = np.vstack([np.full_like(unit, np.nan), np.full_like(unit, np.nan), unit,
                          top_t, np.full_like(unit, np.nan)]) if not empty else np.zeros((5, 0))
        lows = constrained_tensions(dp, tmin[None, :], outs)
        highs = constrained_tensions(dp, tmax[None, :], outs)
        checks: list[tuple[str, float | None, list[np.ndarray], bool]] = [
            ("tension_min", dp.tension_min, lows, False),
            ("tension_max", dp.tension_max, highs, True),
            ("speed_max", dp.speed_max, [np.abs(own)], True),
            ("power_max", dp.power_max, [power], True)]
        g = schedule.ahc_gain
        if g > 0.0:
            checks += [("ahc_stroke", dp.ahc_stroke, [np.abs(g * motion.heave(t))], True),
                       ("ahc_speed", dp.ahc_speed, [np.abs(g * motion.heave_rate(t))], True)]
        for name, limit, series, upper in checks:
            if limit is None:
                continue
            if empty:
                viol[name] = math.inf
                continue
            val = (max(float(np.max(s)) for s in series) if upper
                   else min(float(np.min(s)) for s in series))
            viol[name] = _relative_excess(val, limit, scale, upper)
        if dp.accel_max is not None:
            # the table's accelerations are differences of its rows: their round-off
            # (1e-15 relative) is not an excess
            viol["accel_max"] = (math.inf if empty else _relative_excess(
                accel_peak, dp.accel_max * (1.0 + ACCEL_ROUNDOFF), 1.0, True))
    return ForwardCheck(status=str(res.status), message=res.message, motion=motion.name, t=t,
                        length=np.asarray(res.length, dtype=float), speed=speed,
                        tension_min_line=tmin, tension_max_line=tmax, top_tension=top_t,
                        unit_tension=unit, power=power, accel_peak=accel_peak,
                        violations=viol, slack=bool(res.slack.get("occurred", False)))


def worst_violations(checks: Any) -> dict[str, float]:
    """Per limit, the largest relative excess over the runs (-; the limits sorted by
    name): the one home of that reduction (the forward check of
    :func:`cable_ocp.schedule.planning.verified_schedule`, the tallies of
    :func:`cable_ocp.schedule.robust.count_checks`).

    Parameters
    ----------
    checks : iterable of ForwardCheck
        The runs.
    """
    checks = list(checks)
    limits = sorted({k for c in checks for k in c.violations})
    return {k: max(c.violations.get(k, 0.0) for c in checks) for k in limits}


@dataclass(frozen=True, eq=False)
class ConstantSpeedResult:
    """The fastest trapezoid schedule that keeps the limits (:func:`fastest_constant_speed`).

    Attributes
    ----------
    status : str
        ``"solved"`` or ``"infeasible"`` (the floor speed breaks a limit).
    message : str
        What was found; the binding limit when infeasible.
    speed : float
        The accepted cruise speed, m/s (nan when infeasible).
    schedule : Schedule or None
        Its trapezoid (None when infeasible).
    duration : float
        The schedule's duration, s (nan when infeasible).
    checks : tuple of ForwardCheck
        The accepted speed's runs, one per motion (infeasible: the floor's failing run).
    simulations : int
        Forward simulations run.
    bracket : tuple of float
        (accepted, rejected) speeds at the end, m/s (rejected inf when the bracket's top
        was accepted).
    binding : str or None
        The limit that rejected the speed just above (or the floor).
    """

    status: str
    message: str
    speed: float
    schedule: Schedule | None
    duration: float
    checks: tuple[ForwardCheck, ...]
    simulations: int
    bracket: tuple[float, float]
    binding: str | None = None


def _top_speed(scene: DynamicScene) -> float:
    """The bracket's top without speed_max: the unit's terminal speed sqrt(2 W / (rho C_D
    S)) (at a steady speed above it the unit's drag exceeds its weight in water and the
    line cannot pull: slack); :data:`FALLBACK_SPEED` without unit drag."""
    u = scene.unit
    if u is None:
        return FALLBACK_SPEED
    cs = u.drag_area[2] * u.drag_coefficient[2]
    rho = scene.statics.environment.water_density
    if cs <= 0.0 or u.weight_in_water <= 0.0:
        return FALLBACK_SPEED
    return math.sqrt(2.0 * u.weight_in_water / (rho * cs))


def fastest_constant_speed(scene: DynamicScene, motions: list[VesselMotion], *,
                           rel_tol: float = 1e-3, time_step: float | None = None,
                           segments: int | None = None, hold: float = CHECK_HOLD,
                           floor: float | None = None, tol: float = 0.0,
                           motion_step: float | None = None,
                           ahc_gain: float = 0.0) -> ConstantSpeedResult:
    """The fastest cruise speed of a trapezoid schedule (ramps at ``accel_max``) from
    cable.length to ``deployment.target_length`` that keeps every limit on every motion.

    The bracket's top is ``speed_max``, else the unit's terminal speed (:func:`_top_speed`;
    without unit drag :data:`FALLBACK_SPEED`), checked first and accepted when it keeps
    the limits. Else the speeds of a geometric grid of :data:`SCAN` points between the top
    and the floor (default top / :data:`FLOOR_DIVISOR`), then the floor, are tried from the
    top down: none accepted, the result is ``"infeasible"`` with the floor's binding limit.
    Else bisection between the first accepted speed and the rejected one above it until
    (rejected - accepted) <= rel_tol accepted. The bisection takes acceptance to be
    monotone inside that bracket (it is where a faster lowering only lowers the unit's
    tension; a heave fading in during the run can make a slower run worse: the grid
    then finds the fastest accepted grid speed, not a slow one). A speed is
    accepted when every motion's run keeps the limits within ``tol``
    (:meth:`ForwardCheck.keeps_limits`; default 0: no excess at all); the runs of one
    speed stop at the first motion that breaks one.

    Parameters
    ----------
    scene : DynamicScene
        With a ``[deployment]``.
    motions : list of VesselMotion
        The design motions (:func:`cable_ocp.schedule.sea.vessel_motions`).
    rel_tol : float
        Relative width of the final bracket, -.
    time_step : float, optional
        s, of the runs (default ``simulation.time_step``).
    segments : int, optional
        Elements of the runs (default ``simulation.segments``; fewer are cheaper).
    hold : float
        s simulated after each schedule.
    floor : float, optional
        m/s, the lowest speed tried.
    tol : float
        Relative excess accepted, -.
    motion_step : float, optional
        s (:func:`resimulate`).
    ahc_gain : float
        g, -, in [0, 1]: every trapezoid carries the heave compensation of this gain (the
        winch pays out L(t) + g z(t), :attr:`Schedule.ahc_gain`; e.g. the optimum's own g,
        :attr:`cable_ocp.schedule.ocp.OCPSolution.ahc_gain`), and its runs check
        ``ahc_stroke`` and ``ahc_speed`` as the optimum's do (:attr:`ForwardCheck.violations`);
        0: no compensation.

    Raises
    ------
    CableOCPError
        No ``[deployment]``, no motion or an invalid value (named).
    """
    _check_gain("fastest_constant_speed", ahc_gain)
    dp = scene.deployment
    if dp is None:
        raise CableOCPError("fastest_constant_speed: the scene has no [deployment] table "
                            "(target_length and the limits)")
    if not motions:
        raise CableOCPError("fastest_constant_speed: give at least one vessel motion")
    if not 0.0 < rel_tol < 1.0:
        raise CableOCPError(f"fastest_constant_speed: rel_tol = {rel_tol} must be in (0, 1)")
    top = dp.speed_max if dp.speed_max is not None else _top_speed(scene)
    lo_speed = floor if floor is not None else top / FLOOR_DIVISOR
    if not 0.0 < lo_speed < top:
        raise CableOCPError(f"fastest_constant_speed: floor = {lo_speed} m/s must be in "
                            f"(0, {top:.6g}) m/s")
    count = 0

    def trial(v: float) -> tuple[bool, Schedule, list[ForwardCheck]]:
        nonlocal count
        sched = trapezoid_schedule(scene.length, dp.target_length, v, dp.accel_max,
                                   ahc_gain=ahc_gain)
        out = []
        for m in motions:
            chk = resimulate(scene, sched, m, time_step=time_step, segments=segments,
                             hold=hold, motion_step=motion_step)
            count += 1
            out.append(chk)
            if not chk.keeps_limits(tol):
                return False, sched, out
        return True, sched, out

    def reason(chks: list[ForwardCheck]) -> str:
        bad = chks[-1]
        if bad.status != "solved" or bad.slack:
            return "slack" if bad.slack else bad.status
        return bad.binding or bad.status

    ok, sched, chks = trial(top)
    if ok:
        return ConstantSpeedResult(
            status="solved", message=f"the bracket's top {top:.6g} m/s keeps the limits",
            speed=top, schedule=sched, duration=sched.duration, checks=tuple(chks),
            simulations=count, bracket=(top, math.inf), binding=None)
    binding = reason(chks)
    hi = top
    lo = math.nan
    for v in np.geomspace(top, lo_speed, SCAN + 2)[1:]:
        ok, sched_v, chks_v = trial(float(v))
        if ok:
            lo, sched_lo, chks_lo = float(v), sched_v, chks_v
            break
        hi, binding = float(v), reason(chks_v)
    if math.isnan(lo):
        bad = chks_v[-1]
        return ConstantSpeedResult(
            status="infeasible",
            message=(f"no speed from {top:.4g} m/s down to {lo_speed:.4g} m/s keeps the "
                     f"limits: the floor breaks {binding} (motion {bad.motion!r}, "
                     f"violations {bad.violations})"),
            speed=math.nan, schedule=None, duration=math.nan, checks=tuple(chks_v),
            simulations=count, bracket=(0.0, lo_speed), binding=binding)
    while hi - lo > rel_tol * lo:
        mid = 0.5 * (lo + hi)
        ok, s_mid, c_mid = trial(mid)
        if ok:
            lo, sched_lo, chks_lo = mid, s_mid, c_mid
        else:
            hi, binding = mid, reason(c_mid)
    return ConstantSpeedResult(
        status="solved",
        message=f"{lo:.6g} m/s keeps the limits, {hi:.6g} m/s breaks {binding}",
        speed=lo, schedule=sched_lo, duration=sched_lo.duration, checks=tuple(chks_lo),
        simulations=count, bracket=(lo, hi), binding=binding)
