"""The deployment schedule from a scene: the static check, the warm start, the OCP.

:func:`solve_schedule` is the Python API of ``cable-ocp deploy``:

1. the limits are checked against the line at rest at the start and the target lengths
   (a ``tension_max`` below the static tension, or a ``tension_min`` above it, can be met
   by no schedule: an honest ``"infeasible"`` that names the limit, without a solve);
2. the warm start: the fastest constant speed (a trapezoid, ramped at ``accel_max``, or
   where none is given at :func:`ramp_acceleration`) whose rollout on the OCP's own
   discrete line keeps the tension and power limits, by a grid search on the speed
   and then bisection (:func:`discrete_constant_speed`); its duration fixes the step count
   N = ceil(T_0 / time_step);
3. the OCP (:class:`cable_ocp.schedule.ocp.ScheduleOCP`), built once for N and the design
   heaves, solved from the warm start and, when the caller gives ``start_speeds`` (e.g.
   the forward simulator's fastest constant speed), from each of their trapezoids too,
   re-sampled on the same N steps: the shortest solved schedule is kept
   (:func:`best_start`), the diagnostics name its start and every start's outcome.

:func:`verified_schedule` adds the forward check (docs/deployment.md, "Checks"): the
schedule is re-simulated on the forward simulator (:func:`cable_ocp.schedule.forward.resimulate`,
the scene's own model at ``check_time_step`` and ``check_segments``: independent of the
OCP's transcription) on every design motion, and while a limit (tension_min, tension_max,
power_max) is broken there by more than ``check_tolerance`` of its value the OCP is solved
again, warm, with that limit moved inwards by the excess seen (the bounds are the built
solver's parameters: no rebuild), at most ``check_rounds`` times. The OCP's midpoint step
and its coarser line carry an error of the tensions of a few % at 0.25-0.5 s (second order
in the step); the margin the check finds is that error, measured, not guessed. A schedule
the check still rejects is ``"failed"``, never reported as a schedule.
"""

from __future__ import annotations

import dataclasses
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
from cable_ocp.schedule.forward import (
    CHECK_HOLD,
    SCAN,
    Schedule,
    resimulate,
    trapezoid_schedule,
    worst_violations,
)
from cable_ocp.schedule.ocp import (
    LineStep,
    OCPSolution,
    ScheduleOCP,
    constrained_tensions,
    line_step,
    static_tensions,
    winch_power,
)

#: the most steps of one OCP (its variables grow as steps x states x realisations)
MAX_STEPS = 20000
#: the warm start's fine grid under the top speed: this many speeds (a geometric grid, a
#: factor 1.06 apart) down to WARM_TOP_FLOOR of it, before the coarse descent of
#: forward.SCAN speeds to the floor (a window of feasible speeds under speed_max, as
#: through a resonance on Huang's 3.3.5 line, 1.5-2.07 of 3 m/s, is not stepped over)
WARM_TOP = 24
#: ... the fine grid's slowest speed, as a fraction of the top speed
WARM_TOP_FLOOR = 0.25
#: the name of the OCP's own start (the OCP line's fastest constant speed) in the
#: diagnostics' ``"start"`` and ``"starts"`` (:func:`solve_schedule`)
OCP_LINE_START = "OCP line's constant speed"
#: ... and of a start speed given by the caller (``start_speeds``; the diagnostics'
#: ``"start_speed_m_s"`` and ``"start_index"`` tell several apart)
EXTRA_START = "given start speed"

__all__ = ["CHECKED_LIMITS", "EXTRA_START", "MAX_STEPS", "OCP_LINE_START", "CheckRound",
           "ConstantSpeed", "ScheduleResult", "best_start", "discrete_constant_speed",
           "ramp_acceleration", "solve_schedule", "static_check", "trapezoid",
           "verified_schedule", "with_margins"]

#: the limits the forward check moves inwards when the re-simulation breaks them (speed
#: and acceleration are the schedule's own, the same in both)
CHECKED_LIMITS = ("tension_min", "tension_max", "power_max")


def ramp_acceleration(scene: DynamicScene, problem: DeploymentProblem) -> float:
    """The acceleration of a constant-speed schedule's ramps, m/s^2: ``accel_max``, or
    where none is given half the unit's acceleration in free fall through still water,
    W / (M + M_a) / 2 (the speed of a crane's winch is ramped; a jump in speed is a snap
    load on an elastic line).

    Parameters
    ----------
    scene : DynamicScene
        The scene.
    problem : DeploymentProblem
        The limits.
    """
    if problem.accel_max is not None:
        return float(problem.accel_max)
    unit = scene.unit
    if unit is None:
        raise CableOCPError("deployment: an anchored line has no unit to lower; give [unit]")
    mass = float(unit.mass) + float(unit.added_mass[2])
    return 0.5 * abs(float(unit.weight_in_water)) / max(mass, 1e-9)


def trapezoid(start: float, target: float, speed: float, accel: float, time_step: float
              ) -> tuple[float, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The constant-speed schedule of :func:`~cable_ocp.schedule.forward.trapezoid_schedule`
    (from rest to rest, ramped at ``accel``; a triangle when the distance is too short)
    sampled on N = ceil(T / time_step) equal steps: (T (s), time (s), accel (m/s^2, per
    step), speed (m/s), length (m)).

    The speed at the nodes is the exact trapezoid; the step's acceleration its difference
    quotient, the length the trapezoidal rule (the OCP's kinematics, exact for it).

    Parameters
    ----------
    start, target : float
        Unstretched lengths, m.
    speed : float
        Cruise speed magnitude, m/s (> 0).
    accel : float
        Ramp acceleration, m/s^2 (> 0).
    time_step : float
        The nominal step, s.
    """
    profile = trapezoid_schedule(start, target, speed, accel)
    dur = profile.duration
    n = max(int(math.ceil(dur / time_step - 1e-9)), 4)
    t = np.linspace(0.0, dur, n + 1)
    spd = np.interp(t, profile.time, profile.speed)
    spd[0] = spd[-1] = 0.0
    length = start + np.concatenate([[0.0], np.cumsum(0.5 * (spd[1:] + spd[:-1]) * np.diff(t))])
    length[-1] = target
    return dur, t, np.diff(spd) / np.diff(t), spd, length


def static_check(scene: DynamicScene, problem: DeploymentProblem) -> tuple[str, str] | None:
    """(the limit, why) when the line at rest at the start or the target length already
    breaks a tension limit (no schedule can meet it), else None.

    Parameters
    ----------
    scene : DynamicScene
        The scene.
    problem : DeploymentProblem
        The limits.
    """
    margin = problem.tension_margin
    for length in (scene.length, problem.target_length):
        unit_t, top_t = static_tensions(scene, length)
        vals = []
        if "line" in problem.tension_at or "unit" in problem.tension_at:
            vals.append(unit_t)
        if "line" in problem.tension_at or "top" in problem.tension_at:
            vals.append(top_t)
        t_max, t_min = max(vals), min(vals)
        if problem.tension_max is not None and t_max > problem.tension_max - margin:
            return "tension_max", (
                f"deployment.tension_max = {problem.tension_max:.6g} N (less the margin "
                f"{margin:.6g} N) is below the static tension {t_max:.6g} N of the line at "
                f"rest at L = {length:.6g} m: no schedule can meet it")
        if problem.tension_min is not None and t_min < problem.tension_min + margin:
            return "tension_min", (
                f"deployment.tension_min = {problem.tension_min:.6g} N (plus the margin "
                f"{margin:.6g} N) is above the static tension {t_min:.6g} N of the line at "
                f"rest at L = {length:.6g} m: no schedule can meet it")
    return None


@dataclass(frozen=True)
class ConstantSpeed:
    """The fastest constant-speed schedule on a discrete line (the warm start).

    Attributes
    ----------
    speed : float
        m/s (magnitude; nan when none keeps the limits).
    accel : float
        The ramps' acceleration, m/s^2.
    duration : float
        s.
    feasible : bool
        True when the speed keeps the limits (else the slowest speed tried).
    rollouts : int
        The rollouts of the bisection.
    binding : str
        The limit that bounds the speed (the one the next faster speed breaks).
    fastest : float
        The fastest speed tried, m/s (``speed_max``, or the triangle's peak over the
        distance).
    least_excess : float
        The speed tried whose worst limit excess was the smallest, m/s: the OCP's warm
        start when no speed keeps the limits (the fastest breaks them most, often).
    """

    speed: float
    accel: float
    duration: float
    feasible: bool
    rollouts: int
    binding: str = ""
    fastest: float = math.nan
    least_excess: float = math.nan

    @property
    def start_speed(self) -> float:
        """The OCP's warm-start speed, m/s: ``speed`` when it keeps the limits, else
        ``least_excess`` (else ``fastest``): the OCP decides."""
        if self.feasible:
            return self.speed
        return self.least_excess if math.isfinite(self.least_excess) else self.fastest


def _rollout_limits(line: LineStep, heaves: Sequence[ca.Function], problem: DeploymentProblem,
                    dur: float, spd: np.ndarray, length: np.ndarray) -> dict[str, float]:
    """The largest relative excess of each limit (tension_min/max, power_max) over the
    rollout of a schedule on the discrete line (inf where a step fails). The end's rest is
    left to the OCP: in a sea the unit's speed relative to the ship at the end depends on
    the phase of the heave, which the OCP sets through T; a grid of speeds would only
    sample it."""
    n = spd.size - 1
    dt = dur / n
    tg = np.arange(n + 1) * dt
    fwd = line.forward.mapaccum(n)
    exc = {"tension_min": 0.0, "tension_max": 0.0, "power_max": 0.0}
    margin = problem.tension_margin
    for hf in heaves:
        hv = np.asarray(hf.map(n + 1)(tg)).ravel()
        zt = line.top_height + hv
        p = np.vstack([length[:-1], length[1:], zt[:-1], zt[1:]])
        _, _, tens, outs = fwd(line.start, p, np.full((1, n), dt))
        tens, outs = np.asarray(tens), np.asarray(outs)
        if not (np.all(np.isfinite(tens)) and np.all(np.isfinite(outs))):
            return {k: math.inf for k in exc}
        vals = constrained_tensions(problem, tens, outs)
        allv = np.concatenate([np.ravel(v) for v in vals])
        if problem.tension_min is not None:
            lim = problem.tension_min + margin
            exc["tension_min"] = max(exc["tension_min"], (lim - allv.min()) / max(lim, 1.0))
        if problem.tension_max is not None:
            lim = problem.tension_max - margin
            exc["tension_max"] = max(exc["tension_max"], (allv.max() - lim) / lim)
        if problem.power_max is not None:
            pw = np.abs(winch_power(outs, spd))
            exc["power_max"] = max(exc["power_max"], pw.max() / problem.power_max - 1.0)
    return exc


def discrete_constant_speed(scene: DynamicScene, line: LineStep, heaves: Sequence[ca.Function],
                            problem: DeploymentProblem, time_step: float,
                            rel_tol: float = 1e-2, floor: float = 1e-3) -> ConstantSpeed:
    """The fastest constant speed whose rollout on the OCP's discrete line keeps the tension
    and power limits on every heave (module docstring): from the top speed down, a fine
    geometric grid of :data:`WARM_TOP` speeds to :data:`WARM_TOP_FLOOR` of it, then
    :data:`~cable_ocp.schedule.forward.SCAN` coarser ones to ``floor``; then bisection to
    ``rel_tol`` between the first speed that keeps the limits and the rejected one above.
    When none does, ``least_excess`` is the speed of the smallest worst excess.

    Parameters
    ----------
    scene : DynamicScene
        The scene.
    line : LineStep
        The OCP's line.
    heaves : sequence of casadi.Function
        The design heaves h(t), m.
    problem : DeploymentProblem
        The limits.
    time_step : float
        The nominal step, s.
    rel_tol : float
        The bisection's relative width (-).
    floor : float
        The slowest speed tried, as a fraction of the fastest candidate (-).
    """
    acc = ramp_acceleration(scene, problem)
    dist = abs(problem.target_length - scene.length)
    v_hi = problem.speed_max if problem.speed_max is not None else math.sqrt(acc * dist)
    count = 0
    least = [math.inf, math.nan]  # the smallest worst excess seen, and its speed

    def ok(v: float) -> tuple[bool, str]:
        nonlocal count
        count += 1
        dur, _, _, spd, length = trapezoid(scene.length, problem.target_length, v, acc,
                                           time_step)
        exc = _rollout_limits(line, heaves, problem, dur, spd, length)
        worst = max(exc, key=lambda k: exc[k])
        if exc[worst] < least[0]:
            least[:] = [exc[worst], v]
        return exc[worst] <= 0.0, worst

    good, why = ok(v_hi)
    if good:
        dur = trapezoid(scene.length, problem.target_length, v_hi, acc, time_step)[0]
        return ConstantSpeed(v_hi, acc, dur, True, count, "speed_max" if problem.speed_max
                             is not None else "distance", v_hi)
    # feasibility is not monotone in the speed (a resonance can bind a slower speed and
    # spare a faster one): a geometric grid from the top down first, then bisection
    # between the first speed that keeps the limits and the rejected one above it
    fine = v_hi * WARM_TOP_FLOOR ** (np.arange(1, WARM_TOP + 1) / WARM_TOP)
    coarse = fine[-1] * (floor / WARM_TOP_FLOOR) ** (np.arange(1, SCAN + 1) / SCAN)
    grid = np.concatenate([fine, coarse]) if floor < WARM_TOP_FLOOR else v_hi * floor ** (
        np.arange(1, SCAN + 1) / SCAN)
    hi, binding, lo = v_hi, why, math.nan
    for v in grid:
        # a slower speed's rollout has more steps (~ 1 / v): past MAX_STEPS no warm start
        # of the OCP (:func:`solve_schedule` refuses it) and, at 40 elements over 800 m,
        # rollouts of 10^5-10^6 steps whose memory ran out (docs/deployment.md, "Cost")
        if trapezoid(scene.length, problem.target_length, float(v), acc,
                     time_step)[3].size - 1 > MAX_STEPS:
            break
        good, w = ok(float(v))
        if good:
            lo = float(v)
            break
        hi, binding = float(v), w
    if math.isnan(lo):
        dur = trapezoid(scene.length, problem.target_length, hi, acc, time_step)[0]
        return ConstantSpeed(hi, acc, dur, False, count, binding, v_hi, least[1])
    while hi - lo > rel_tol * lo:
        mid = 0.5 * (lo + hi)
        good, w = ok(mid)
        if good:
            lo = mid
        else:
            hi, binding = mid, w
    dur = trapezoid(scene.length, problem.target_length, lo, acc, time_step)[0]
    return ConstantSpeed(lo, acc, dur, True, count, binding, v_hi)


@dataclass(frozen=True)
class CheckRound:
    """One round of the forward check (:func:`verified_schedule`).

    Attributes
    ----------
    margins : dict of str to float
        How far inside each limit the OCP kept its tensions (N) and power (W) this round,
        on top of ``tension_margin``.
    status : str
        The OCP's status this round.
    duration : float
        Its schedule's duration, s.
    violations : dict of str to float
        The re-simulation's worst relative excess of each limit over the motions (-).
    failed_runs : int
        Re-simulations that went slack or failed.
    runs : tuple of ForwardCheck
        The re-simulations themselves, one per motion
        (:class:`cable_ocp.schedule.forward.ForwardCheck`).
    """

    margins: dict[str, float]
    status: str
    duration: float
    violations: dict[str, float]
    failed_runs: int = 0
    runs: tuple[Any, ...] = ()

    @property
    def worst(self) -> tuple[str, float]:
        """(limit, relative excess) of the largest excess ("", 0.0 without limits)."""
        if not self.violations:
            return "", 0.0
        k = max(self.violations, key=lambda n: self.violations[n])
        return k, self.violations[k]


@dataclass(frozen=True)
class ScheduleResult:
    """The optimal schedule of a scene's ``[deployment]`` (or why there is none).

    Attributes
    ----------
    status : str
        ``"solved"``, ``"infeasible"``, ``"failed"`` or ``"interrupted"``.
    message : str
        What happened; for ``"infeasible"`` the limit that binds.
    binding : tuple of str
        The limits active at the optimum, or those no schedule can meet.
    solution : OCPSolution or None
        The OCP's schedule (None when the static check failed); when ``status`` is not
        ``"solved"`` its arrays are IPOPT's last iterate, not a schedule.
    warm_start : ConstantSpeed or None
        The fastest constant speed on the OCP's discrete line.
    problem : DeploymentProblem
        The problem solved.
    diagnostics : dict
        Times (s: the warm start, the build, the solve, the check), steps, sizes.
    checks : tuple of CheckRound
        The forward check's rounds (:func:`verified_schedule`; empty without the check).
    """

    status: str
    message: str
    binding: tuple[str, ...]
    solution: OCPSolution | None
    warm_start: ConstantSpeed | None
    problem: DeploymentProblem
    diagnostics: dict[str, Any] = field(default_factory=dict)
    checks: tuple[CheckRound, ...] = ()

    @property
    def success(self) -> bool:
        """True for a solved schedule."""
        return self.status == "solved"

    @property
    def duration(self) -> float:
        """The schedule's time to the target, s (nan unless solved)."""
        return self.solution.duration if self.success and self.solution else math.nan

    @property
    def margins(self) -> dict[str, float]:
        """The forward check's margins of the returned schedule (N, W; empty without
        the check or when the OCP alone passed it)."""
        return dict(self.checks[-1].margins) if self.checks else {}


def best_start(results: Sequence[tuple[str, float]]) -> int:
    """The index of the start whose solve is kept (:func:`solve_schedule`): the shortest
    duration among the ``"solved"`` ones (the first of equal durations), else 0 (the OCP
    line's start, whose failure the result then reports).

    Parameters
    ----------
    results : sequence of (str, float)
        Each start's (status, duration (s)), in the order of the starts.
    """
    best = -1
    for i, (status, dur) in enumerate(results):
        if status == "solved" and math.isfinite(dur) and (
                best < 0 or dur < results[best][1]):
            best = i
    return max(best, 0)


def solve_schedule(scene: DynamicScene, heaves: Sequence[ca.Function] | None = None, *,
                   problem: DeploymentProblem | None = None, segments: int | None = None,
                   time_step: float | None = None, steps: int | None = None,
                   ipopt: dict[str, Any] | None = None, hold: float | None = None,
                   start_speeds: Sequence[float] = ()) -> ScheduleResult:
    """The optimal pay-out (or haul-in) schedule of a scene (module docstring).

    A multi-start: the built OCP is solved from the OCP line's fastest constant speed
    (:func:`discrete_constant_speed`) and from the trapezoid of each of ``start_speeds``
    (the same ramps, re-sampled on the same N steps); the solved one of the shortest
    duration is kept (:func:`best_start`; none solved: the first start's failure). The
    diagnostics name the start kept (``"start"``: :data:`OCP_LINE_START` or
    :data:`EXTRA_START`, ``"start_speed_m_s"``, ``"start_index"`` (0 the OCP line's); its IPOPT
    numbers are ``"solve_time_s"`` and ``"iterations"``), list every start's status,
    duration, iterations and solve time (``"starts"``) and their total solve time
    (``"solve_total_s"``); with more than one start the message names them too.

    Parameters
    ----------
    scene : DynamicScene
        The scene with its ``[deployment]`` table.
    heaves : sequence of casadi.Function, optional
        The design realisations of the vessel's heave h(t) (m); default none (still
        water). The command line passes :func:`cable_ocp.schedule.sea.vessel_motions`.
    problem : DeploymentProblem, optional
        Default ``scene.deployment``.
    segments : int, optional
        The OCP line's elements (default ``deployment.segments``, else the scene's).
    time_step : float, optional
        The nominal step, s (default ``deployment.time_step``, else the scene's).
    steps : int, optional
        N, overriding ceil(T_0 / time_step).
    ipopt : dict, optional
        Extra IPOPT options.
    hold : float, optional
        s, >= 0: the OCP goes on this long after the arrival, the winch stopped, its
        tensions kept inside the limits (:class:`~cable_ocp.schedule.ocp.ScheduleOCP`'s
        ``hold_steps``: ceil(hold / time_step) steps of hold / M s); 0: the OCP
        ends at the arrival. Default ``deployment.hold``, else 0 (the OCP alone; the
        forward check simulates :data:`~cable_ocp.schedule.forward.CHECK_HOLD` s after
        it, and :func:`verified_schedule` models that hold by default).
    start_speeds : sequence of float, optional
        Further warm starts' cruise speeds, m/s (magnitudes, > 0, at most ``speed_max``):
        e.g. the forward simulator's fastest constant speed
        (:func:`cable_ocp.schedule.forward.fastest_constant_speed`), which on Huang's
        3.3.5 line starts IPOPT where the OCP line's own does not converge
        (docs/deployment.md, "Comparisons"). Each costs one more solve. Default none.

    Raises
    ------
    CableOCPError
        Without a ``[deployment]`` table, a model without a driven step, or a start speed
        that is not positive or is above ``speed_max``.
    KeyboardInterrupt
        On a Ctrl-C (never retried).
    """
    return _solve(scene, heaves, problem, segments, time_step, steps, ipopt,
                  _hold(scene, problem, hold, 0.0), start_speeds)[0]


def with_margins(pb: DeploymentProblem, margins: dict[str, float]) -> DeploymentProblem:
    """The problem with its limits moved inwards by ``margins`` (N, W): the warm start's
    search of a re-solve, and the receding horizon's limits after the forward check
    (:attr:`ScheduleResult.margins`).

    Parameters
    ----------
    pb : DeploymentProblem
        The problem.
    margins : dict of str to float
        ``"tension_min"``, ``"tension_max"`` (N), ``"power_max"`` (W).
    """
    kw: dict[str, Any] = {}
    for name, sign in (("tension_min", 1.0), ("tension_max", -1.0), ("power_max", -1.0)):
        if getattr(pb, name) is not None and name in margins:
            kw[name] = getattr(pb, name) + sign * margins[name]
    return dataclasses.replace(pb, **kw)


def _solve(scene: DynamicScene, heaves: Sequence[ca.Function] | None,
           problem: DeploymentProblem | None, segments: int | None, time_step: float | None,
           steps: int | None, ipopt: dict[str, Any] | None, hold: float = 0.0,
           start_speeds: Sequence[float] = ()
           ) -> tuple[ScheduleResult, ScheduleOCP | None, Any]:
    """:func:`solve_schedule`, the built OCP (None when the static check failed) and
    ``restart(margins) -> w0``: the warm start of the limits moved inwards, for its N (of
    the start kept: the OCP line's constant speed of the moved limits, or the given start
    speed's trapezoid itself)."""
    pb = problem if problem is not None else scene.deployment
    if pb is None:
        raise CableOCPError("[deployment] is missing: the schedule needs target_length and "
                            "its limits (docs/deployment.md)")
    extra = [float(v) for v in start_speeds]
    for v in extra:
        if not (math.isfinite(v) and v > 0.0) or (pb.speed_max is not None
                                                  and v > pb.speed_max * (1.0 + 1e-12)):
            raise CableOCPError(
                f"start_speeds: {v!r} m/s is no warm start; give cruise speeds > 0"
                + (f" and at most deployment.speed_max = {pb.speed_max:g} m/s"
                   if pb.speed_max is not None else ""))
    diag: dict[str, Any] = {}
    bad = static_check(scene, pb)
    if bad is not None:
        return ScheduleResult("infeasible", bad[1], (bad[0],), None, None, pb, diag), None, None
    if heaves is None:
        heaves = [ca.Function("still", [ca.SX.sym("t")], [ca.SX(0.0)])]
    dt_nom = time_step or pb.time_step or scene.simulation.time_step
    t0 = time.perf_counter()
    line = line_step(scene, segments)
    warm = discrete_constant_speed(scene, line, heaves, pb, dt_nom)
    diag["warm_start_s"] = time.perf_counter() - t0
    dur, _, acc, _, _ = trapezoid(scene.length, pb.target_length, warm.start_speed,
                                  warm.accel, dt_nom)
    n = steps or acc.size
    if n > MAX_STEPS:
        raise CableOCPError(f"deployment.time_step = {dt_nom:.4g} s: the warm start's "
                            f"{dur:.6g} s would take {n} steps (at most {MAX_STEPS}); give a "
                            "longer time_step")
    if not (math.isfinite(hold) and hold >= 0.0):
        raise CableOCPError(f"hold = {hold} s: give the time after the arrival that the OCP "
                            "keeps the limits, >= 0 (0: none)")
    m = int(math.ceil(hold / dt_nom - 1e-9)) if hold > 0.0 else 0
    ocp = ScheduleOCP(scene, line, heaves, n + m, pb, ipopt, hold_steps=m, hold=hold)
    diag["build_s"] = ocp.build_time

    def start(speed: float) -> np.ndarray:
        """The NLP's variables of a constant-speed warm start (a trapezoid at ``speed``,
        m/s, ramped as the warm start), re-sampled on the OCP's N steps (the hold's
        appended)."""
        d, _, a, v, length = trapezoid(scene.length, pb.target_length, speed, warm.accel,
                                       dt_nom)
        if a.size != n:
            d, _, a, v, length = trapezoid(scene.length, pb.target_length, speed, warm.accel,
                                           d / n)
        d, a, v, length = ocp.extend(d, a, v, length)
        return ocp.pack(d, a, v, length, *ocp.rollout(d, a, v, length))

    # the starts: the OCP line's constant speed, then each given speed (one built OCP)
    starts = [(OCP_LINE_START, warm.start_speed)] + [(EXTRA_START, v) for v in extra]
    sols = [ocp.solve(start(v)) for _, v in starts]
    best = best_start([(s.status, s.duration) for s in sols])
    sol = sols[best]
    label, speed = starts[best]

    def restart(margins: dict[str, float]) -> np.ndarray:
        # the OCP line's start moves with the limits; a given speed is the caller's own
        if best > 0:
            return start(speed)
        return start(discrete_constant_speed(scene, line, heaves, with_margins(pb, margins),
                                             dt_nom).start_speed)

    diag.update(sol.diagnostics)
    diag.update(start=label, start_speed_m_s=speed, start_index=best, starts=[
        {"start": lb, "speed_m_s": v, "status": s.status, "duration_s": s.duration,
         "iterations": s.diagnostics.get("iterations"),
         "solve_time_s": s.diagnostics.get("solve_time_s"),
         "return_status": s.diagnostics.get("return_status")}
        for (lb, v), s in zip(starts, sols, strict=True)],
        solve_total_s=sum(float(s.diagnostics.get("solve_time_s", 0.0)) for s in sols))
    msg, binding = sol.message, sol.binding
    if len(starts) > 1:
        msg += f" (kept the start from the {label}, {speed:.4g} m/s; " + "; ".join(
            f"from the {lb}, {v:.4g} m/s: {s.status} at {s.duration:.6g} s"
            for i, ((lb, v), s) in enumerate(zip(starts, sols, strict=True)) if i != best) + ")"
    if sol.status == "infeasible" and not warm.feasible:
        msg += (f"; no constant speed down to {warm.speed:.3g} m/s keeps the limits either "
                f"({warm.binding} binds)")
        # IPOPT's iterate broke only the model's equations: the warm start names the limit
        binding = binding or (warm.binding,)
    return ScheduleResult(sol.status, msg, binding, sol, warm, pb, diag), ocp, restart


def verified_schedule(scene: DynamicScene, motions: Sequence[Any], *,
                      problem: DeploymentProblem | None = None, segments: int | None = None,
                      time_step: float | None = None, steps: int | None = None,
                      ipopt: dict[str, Any] | None = None, rounds: int | None = None,
                      tolerance: float | None = None, check_time_step: float | None = None,
                      check_segments: int | None = None, hold: float | None = None,
                      start_speeds: Sequence[float] = ()) -> ScheduleResult:
    """The optimal schedule, re-simulated on the forward simulator and re-solved with
    margins until the re-simulation keeps its limits (module docstring).

    The OCP is :func:`solve_schedule`'s multi-start; the forward check is run on the start
    kept (the shortest solved), and its first re-solve starts from that start's trapezoid
    (the OCP line's constant speed of the moved limits, or the given speed itself).

    Parameters
    ----------
    scene : DynamicScene
        The scene with its ``[deployment]`` table.
    motions : sequence of VesselMotion
        The design motions (:func:`cable_ocp.schedule.sea.vessel_motions`): the OCP's
        heaves and the check's.
    problem, segments, time_step, steps, ipopt, start_speeds
        As :func:`solve_schedule` (e.g. ``start_speeds=[fastest_constant_speed(scene,
        motions).speed]``: ``cable-ocp bench deploy --part compare`` does).
    rounds : int, optional
        Re-solves allowed (default ``deployment.check_rounds``; 0: the OCP alone).
    tolerance : float, optional
        The relative excess accepted (default ``deployment.check_tolerance``).
    check_time_step : float, optional
        The check's step, s (default ``deployment.check_time_step``, else the scene's).
    check_segments : int, optional
        The check's elements (default ``deployment.check_segments``, else the scene's).
    hold : float, optional
        s after the arrival that the OCP keeps the limits (:func:`solve_schedule`).
        Default ``deployment.hold``, else :data:`~cable_ocp.schedule.forward.CHECK_HOLD`:
        the check simulates that long after the arrival, and an OCP that ends at the
        arrival is checked on a hold it never bounded (docs/deployment.md, "The 6.3.6
        line with compensation").

    Raises
    ------
    CableOCPError
        As :func:`solve_schedule`.
    KeyboardInterrupt
        On a Ctrl-C inside IPOPT (never retried).
    """
    res, ocp, restart = _solve(scene, [m.casadi_heave() for m in motions], problem,
                               segments, time_step, steps, ipopt,
                               _hold(scene, problem, hold, CHECK_HOLD), start_speeds)
    pb = res.problem
    n_rounds = pb.check_rounds if rounds is None else int(rounds)
    if n_rounds < 0:
        raise CableOCPError(f"check rounds = {n_rounds}: give 0 (no check) or more")
    if not res.success or ocp is None:
        return res
    if n_rounds == 0:
        return dataclasses.replace(res, message=res.message + (
            "; not checked on the forward simulator (check_rounds = 0): the tensions are "
            "the OCP's own, within its transcription's error (docs/deployment.md)"))
    tol = pb.check_tolerance if tolerance is None else float(tolerance)
    if not 0.0 < tol < 0.5:
        raise CableOCPError(f"check tolerance = {tol}: give a relative excess in (0, 0.5)")
    c_step = check_time_step or pb.check_time_step or scene.simulation.time_step
    c_seg = check_segments or pb.check_segments or scene.simulation.segments
    sol = res.solution
    assert sol is not None
    t0 = time.perf_counter()
    margins: dict[str, float] = {}
    rounds_done: list[CheckRound] = []
    diag = dict(res.diagnostics)
    where = (f"on the forward simulator ({c_seg} elements, {c_step:g} s, "
             f"{len(motions)} motion(s))")
    while True:
        sched = Schedule.from_speed(sol.time, sol.speed, scene.length, sol.ahc_gain)
        runs = [resimulate(scene, sched, m, time_step=c_step, segments=c_seg,
                           hold=CHECK_HOLD) for m in motions]
        worst = worst_violations(runs)
        broken = sum(1 for run in runs if run.status != "solved" or run.slack)
        rnd = CheckRound(dict(margins), sol.status, sol.duration, worst, broken, tuple(runs))
        rounds_done.append(rnd)
        diag.update(check_s=time.perf_counter() - t0, check_rounds=len(rounds_done) - 1)
        if interrupt.requested() or any(run.status == "interrupted" for run in runs):
            return ScheduleResult("interrupted", "the forward check was interrupted", (),
                                  sol, res.warm_start, pb, diag, tuple(rounds_done))
        over = {k: v for k, v in worst.items() if v > tol}
        if not over and broken == 0:
            msg = (f"{res.message}; the limits kept to {100 * tol:g} % {where}"
                   + (f" after {len(rounds_done) - 1} re-solve(s) with margins "
                      + _margins_text(margins) if margins else ""))
            return ScheduleResult("solved", msg, sol.binding, sol, res.warm_start, pb, diag,
                                  tuple(rounds_done))
        fixable = {k: v for k, v in over.items() if k in CHECKED_LIMITS}
        if len(rounds_done) > n_rounds or len(fixable) < len(over):
            why = ", ".join(f"{k} by {100 * v:.3g} %" for k, v in sorted(
                over.items(), key=lambda kv: -kv[1]))
            msg = (f"the schedule breaks {why or 'nothing'} {where}"
                   + (f" ({broken} run(s) slack or failed)" if broken else "")
                   + f" after {len(rounds_done) - 1} re-solve(s)"
                   + (f" with margins {_margins_text(margins)}" if margins else "")
                   + "; not a schedule: give a finer deployment.time_step or more "
                     "deployment.segments (docs/deployment.md, Checks)")
            return ScheduleResult("failed", msg, tuple(over), sol, res.warm_start, pb, diag,
                                  tuple(rounds_done))
        first = not margins
        for k, v in fixable.items():
            # aim half the tolerance inside: the excess changes with the schedule
            margins[k] = margins.get(k, 0.0) + (v + 0.5 * tol) * _limit_value(
                pb, k, ocp.tension_scale)
        # the first re-solve starts from the warm start of the moved limits (from the
        # optimum, which breaks them by the whole excess, IPOPT took 10-100 times longer,
        # and once called a feasible problem infeasible); later ones, small moves, from
        # the last schedule, falling back to the warm start
        sol = ocp.solve(restart(margins) if first else sol.variables_vector, margins)
        if not first and not sol.success:
            sol = ocp.solve(restart(margins), margins)
        diag.update({f"resolve_{len(rounds_done)}_s": sol.diagnostics.get("solve_time_s")})
        if not sol.success:
            msg = (f"{sol.message} (re-solved with margins {_margins_text(margins)} after "
                   f"the forward check {where} broke " + ", ".join(sorted(fixable)) + ")")
            return ScheduleResult(sol.status, msg, sol.binding or tuple(fixable), sol,
                                  res.warm_start, pb, diag, tuple(rounds_done))


def _hold(scene: DynamicScene, problem: DeploymentProblem | None, hold: float | None,
          default: float) -> float:
    """The OCP's hold, s: ``hold``, else ``deployment.hold``, else ``default``."""
    if hold is not None:
        return float(hold)
    pb = problem if problem is not None else scene.deployment
    return default if pb is None or pb.hold is None else float(pb.hold)


def _limit_value(pb: DeploymentProblem, name: str, scale: float) -> float:
    """A limit's value (N, W) that its relative excess refers to (the scale for a zero
    tension_min, as :func:`cable_ocp.schedule.forward.resimulate`)."""
    value = getattr(pb, name)
    return float(value) if value else float(scale)


def _margins_text(margins: dict[str, float]) -> str:
    return ", ".join(f"{k} {v:.4g} {'W' if k == 'power_max' else 'N'}"
                     for k, v in margins.items())
