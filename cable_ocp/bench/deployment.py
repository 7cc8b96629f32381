"""``cable-ocp bench deploy``: issue 25's comparisons and cost of the deployment schedule.

Three parts, each returning rows (dicts, SI units) that the command line formats:

* ``compare``: on each case (default :data:`COMPARE_CASES`: Huang (1992) 3.3.5's line
  lowered 50 -> 1050 m through its resonant length, and the 6.3.6 line lowered 200 ->
  1000 m in the 6.3.6 sea), side by side in one run, the time to depth of

  - the optimal schedule (:func:`cable_ocp.schedule.planning.verified_schedule`: the OCP
    and its forward check; without heave compensation the forward simulator's fastest
    constant speed, found first, is the OCP's second warm start, ``start_speeds``: the
    shorter solve is kept and the OCP's ``start`` / ``starts`` say which), re-simulated
    on the forward simulator at the scene's own (finer) ``[simulation]`` step and
    elements (:func:`cable_ocp.schedule.forward.resimulate`) with its worst limit excess;
  - the fastest constant speed that keeps the same limits on the forward simulator
    (bisection: :func:`cable_ocp.schedule.forward.fastest_constant_speed`); when the case
    has heave compensation (``ahc_stroke`` / ``ahc_speed``), every trapezoid carries the
    optimum's gain g (:func:`comparison_gain`), so that both pay out L + g h with the same
    compensator and its limits;
  - where the case has a heave counterpart (:data:`HEAVE_COUNTERPARTS`), the
    scheduled-gain deployment of ``cable-ocp heave`` (its ``[deployment]``: the distance
    at ``payout_speed``, the speed ramped in and out over ``ramp_time``,
    :func:`cable_ocp.heave.deployment.length_history`: it lasts distance / speed +
    ramp_time), its pay-out re-simulated on the same motion (the forward simulator has no
    LQR compensator: with the case's compensation, the pay-out with the same gain g as
    the constant speed, a stand-in for its compensator; without, the pay-out alone, the
    compensating winch held);

  the saving of the optimum against each, 100 (T_other - T_opt) / T_other (%).
* ``cost``: the OCP's build time, solve time, iterations and variables on a grid of
  durations (the lowering distance d = v (T - v / a) at the binding ``speed_max`` v and
  ``accel_max`` a, so the warm start takes T) and of elements, on one line
  (:data:`COST_FILE`); the growth of each with the duration and with the elements as the
  least-squares exponent p of y = c x^p (:func:`fit_exponent`).
* ``long``: a ~600 s deployment on a 40-element line (the cost grid's, at
  :data:`LONG_SPEED`), its build and solve times apart.

Times are wall-clock (``time.perf_counter``) on whatever machine runs it; they are noisy
on a shared one. Nothing here is asserted by the tests but the bookkeeping.
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics.ramp import smoothstep

ROOT = Path(__file__).resolve().parents[2] / "problems"

#: the parts of the benchmark, in their order
PARTS = ("compare", "cost", "long")
#: the compared cases
COMPARE_CASES = (ROOT / "dynamics" / "deploy_3_3_5.toml", ROOT / "dynamics" / "deploy_6_3_6.toml")
#: a case's heave scene whose ``[deployment]`` is today's scheduled-gain lowering of its line
HEAVE_COUNTERPARTS = {"deploy_6_3_6": ROOT / "heave" / "deployment_6_3_6.toml"}
#: the line of the cost grid (the 3.3.5 line, 50 m at the start, a 0.5 m heave)
COST_FILE = ROOT / "dynamics" / "deploy_small.toml"
#: the cost grid's cruise speed, m/s: below the speed at which tension_min binds on that
#: line (2.1 m/s), so the warm start's duration is set by the distance alone; the longest
#: lowering (50 -> 525 m) stays short of the resonant length (677 m)
COST_SPEED = 1.0
#: the cost grid: durations (s) and elements
COST_DURATIONS = (60.0, 120.0, 240.0, 480.0)
COST_SEGMENTS = (5, 10, 20, 40)
#: the long run: the cost grid's line (:data:`COST_FILE`) lowered at :data:`LONG_SPEED` for
#: ~600 s on 40 elements (the measured run: docs/deployment.md, "The long run")
LONG_FILE = COST_FILE
LONG_DURATION = 600.0
LONG_SEGMENTS = 40
#: the long run's cruise speed, m/s: 600 s at 0.5 m/s ramped at 0.2 m/s^2 lowers the line
#: 298.75 m (50 -> 348.75 m), clear of its 677 m resonant length, where the constant speed
#: keeps the limits (the cost grid's 1 m/s would reach 645 m and break tension_min)
LONG_SPEED = 0.5
#: the long run's nlpsol options (docs/deployment.md, "Cost", "The long run"): the MX graph
#: expanded to SX, whose Hessian has half the structural nonzeros and evaluates ~20x faster
#: at 40 elements, and MUMPS's pivot tolerance 1e-4 (2-3x less IPOPT CPU on this line up
#: to 240 s). With them the 600 s / 40-element run solved in 20 iterations (82.6 s of
#: IPOPT after a 538 s build, 2026-12-03).
LONG_IPOPT: dict[str, Any] = {"expand": True, "ipopt.mumps_pivtol": 1e-4}

__all__ = ["COMPARE_CASES", "COST_DURATIONS", "COST_SEGMENTS", "PARTS", "compare_case",
           "comparison_gain", "cost_fits", "cost_grid", "distance_for", "fit_exponent",
           "heave_payout", "long_run", "payout_schedule", "saving_pct"]


def saving_pct(optimal: float, other: float) -> float:
    """The optimum's saving against another schedule, 100 (T_other - T_opt) / T_other (%);
    nan unless both durations are finite and T_other > 0.

    Parameters
    ----------
    optimal : float
        The optimal schedule's duration, s.
    other : float
        The other schedule's duration, s.
    """
    if not (math.isfinite(optimal) and math.isfinite(other) and other > 0.0):
        return math.nan
    return 100.0 * (other - optimal) / other


def fit_exponent(x: Sequence[float], y: Sequence[float]) -> tuple[float, float]:
    """(p, c) of the least-squares fit log y = log c + p log x over the positive finite
    pairs; (nan, nan) with fewer than two distinct x.

    Parameters
    ----------
    x : sequence of float
        The sizes (> 0; e.g. s or elements).
    y : sequence of float
        The costs (> 0; e.g. s or iterations).
    """
    xa, ya = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    ok = np.isfinite(xa) & np.isfinite(ya) & (xa > 0.0) & (ya > 0.0)
    if np.unique(xa[ok]).size < 2:
        return math.nan, math.nan
    p, logc = np.polyfit(np.log(xa[ok]), np.log(ya[ok]), 1)
    return float(p), float(math.exp(logc))


def distance_for(duration: float, speed: float, accel: float) -> float:
    """The distance (m) a trapezoid from rest to rest at cruise ``speed`` (m/s), ramped at
    ``accel`` (m/s^2), covers in ``duration`` (s): v (T - v / a) (> 0 only when T > 2 v / a,
    the triangle's limit).

    Parameters
    ----------
    duration : float
        s.
    speed : float
        m/s.
    accel : float
        m/s^2.
    """
    d = speed * (duration - speed / accel)
    if not d > speed**2 / accel:
        raise CableOCPError(f"bench deploy: a duration of {duration:g} s is too short for "
                            f"the cruise speed {speed:g} m/s ramped at {accel:g} m/s^2; give "
                            f"more than {2.0 * speed / accel:g} s")
    return d


def payout_schedule(start: float, final: float, speed: float, ramp: float,
                    step: float = 0.1) -> Any:
    """The pay-out of ``cable-ocp heave``'s ``[deployment]``
    (:func:`cable_ocp.heave.deployment.length_history` from t0 = 0) as a
    :class:`cable_ocp.schedule.forward.Schedule`: the speed v (f(s / r) - f((s - T_c) / r)),
    f the quintic ramp 10x^3 - 15x^4 + 6x^5 clipped to [0, 1], T_c = |final - start| / v,
    sampled every ``step`` s over the two ramps, [0, r] and [T_c, T_c + r] (linear between
    samples; the cruise between them is constant, so its two ends are exact: a short
    speed table keeps the forward simulator's table lookup cheap).

    Parameters
    ----------
    start, final : float
        Lengths, m.
    speed : float
        The pay-out speed v, m/s (> 0).
    ramp : float
        The ramp time r, s (cut to T_c as length_history does).
    step : float
        The sampling, s.
    """
    from cable_ocp.schedule.forward import Schedule

    dist = abs(final - start)
    tc = dist / speed
    ramp = min(ramp, tc)
    dur = tc + ramp
    n = max(int(math.ceil(ramp / step)), 2)
    t = np.union1d(np.linspace(0.0, ramp, n + 1), np.linspace(tc, dur, n + 1))
    if ramp <= 0.0:
        t = np.array([0.0, tc])

    def f(x: np.ndarray) -> np.ndarray:
        return smoothstep(np.clip(x, 0.0, 1.0))

    if ramp > 0.0:
        v = speed * (f(t / ramp) - f((t - tc) / ramp))
    else:
        v = np.where(t < tc, speed, 0.0)
    v[0] = v[-1] = 0.0
    sign = 1.0 if final >= start else -1.0
    return Schedule.from_speed(t, sign * v, start)


def heave_payout(heave_path: str | Path) -> dict[str, Any]:
    """Today's scheduled-gain deployment of a heave scene (``cable-ocp heave``'s
    ``[deployment]``): its lengths (m), pay-out speed (m/s), ramp time and duration
    (s: distance / speed + ramp_time, the pay-out alone, after the scene's warm-up) and
    the limits it states.

    Parameters
    ----------
    heave_path : str or Path
        The heave problem file.
    """
    from cable_ocp.scene.heave import load_cable_scene, load_scene

    sc = load_scene(heave_path)
    dep = sc.deployment
    if dep is None or dep.final_length is None:
        raise CableOCPError(f"{heave_path}: no [deployment] final_length: not a deployment")
    cable = load_cable_scene(sc)
    dist = abs(dep.final_length - cable.length)
    tc = dist / dep.payout_speed
    ramp = min(dep.ramp_time, tc)
    w = sc.winch
    return {"file": str(heave_path), "start_length_m": cable.length,
            "final_length_m": dep.final_length, "payout_speed_m_s": dep.payout_speed,
            "ramp_time_s": ramp, "duration_s": tc + ramp,
            "limits": {"tension_min_N": getattr(w, "tension_min", None),
                       "tension_max_N": getattr(w, "tension_max", None),
                       "compensator_speed_max_m_s": getattr(w, "speed_max", None),
                       "compensator_stroke_max_m": getattr(w, "stroke_max", None)}}


def comparison_gain(scene: Any, motions: Sequence[Any], result: Any,
                    duration: float) -> tuple[float, str]:
    """The compensation's gain g (-) of the compared schedules and where it comes from:
    0 without compensation (``[deployment]`` without ``ahc_stroke`` / ``ahc_speed``); the
    optimum's own g when the OCP solved; else the largest g in [0, 1] that keeps
    |g h| <= ahc_stroke and |g dh/dt| <= ahc_speed over the motions' first ``duration``
    s (sampled every 0.01 s).

    Parameters
    ----------
    scene : DynamicScene
        The case.
    motions : sequence of VesselMotion
        The design motions.
    result : ScheduleResult
        The OCP's (:func:`cable_ocp.schedule.planning.verified_schedule`).
    duration : float
        s, the span over which the fallback's heave is measured.
    """
    dp = scene.deployment
    if dp is None or not dp.ahc:
        return 0.0, "no compensation"
    if result.success and result.solution is not None:
        g = float(result.solution.ahc_gain)
        return g, f"the optimum's compensation gain g = {g:.4g}"
    t = np.linspace(0.0, duration, max(int(math.ceil(duration / 0.01)), 2) + 1)
    g = 1.0
    for m in motions:
        for limit, peak in ((dp.ahc_stroke, np.max(np.abs(m.heave(t)))),
                            (dp.ahc_speed, np.max(np.abs(m.heave_rate(t))))):
            if limit is not None and peak > 0.0:
                g = min(g, float(limit) / float(peak))
    return g, (f"no optimum: the largest compensation gain the stroke and speed allow, "
               f"g = {g:.4g}")


def _check_row(chk: Any) -> dict[str, Any]:
    """The forward check's worst excess and its limit."""
    worst = max(chk.violations.values(), default=0.0)
    return {"forward_status": chk.status, "slack": chk.slack,
            "worst_excess": worst, "worst_limit": chk.binding if worst > 0.0 else None,
            "violations": dict(chk.violations),
            "tension_min_seen_N": float(np.min(chk.tension_min_line))
            if chk.tension_min_line.size else math.nan,
            "tension_max_seen_N": float(np.max(chk.tension_max_line))
            if chk.tension_max_line.size else math.nan}


def _forward_checks(scene: Any, schedule: Any, motions: Sequence[Any],
                    motion_step: float | None = None) -> dict[str, Any]:
    """The worst over the motions of :func:`_check_row`."""
    from cable_ocp.schedule.forward import resimulate

    rows = [_check_row(resimulate(scene, schedule, m, motion_step=motion_step))
            for m in motions]
    worst = max(rows, key=lambda r: (r["forward_status"] != "solved", r["slack"],
                                     r["worst_excess"]))
    out = dict(worst)
    out["tension_min_seen_N"] = min(r["tension_min_seen_N"] for r in rows)
    out["tension_max_seen_N"] = max(r["tension_max_seen_N"] for r in rows)
    return out


def compare_case(path: str | Path, *, heave_path: str | Path | None = None,
                 rel_tol: float = 1e-2, motion_step: float | None = None,
                 floor_fraction: float | None = None, ipopt: dict[str, Any] | None = None,
                 progress: Callable[[str], None] | None = None,
                 on_row: Callable[[dict[str, Any]], None] | None = None) -> dict[str, Any]:
    """The optimal schedule of one case beside the fastest constant speed and today's
    scheduled-gain deployment (module docstring).

    Returns ``{"case", "file", "start_length_m", "target_length_m", "motions", "ocp": {...},
    "heave": {...} or None, "rows": [...], "complete": True}``: one row per method
    (``method``, ``status``, ``duration_s``, ``saving_pct`` of the optimum against it,
    ``speed_m_s``, ``binding``, the forward check's ``worst_excess`` and ``worst_limit``,
    ``note``).

    Parameters
    ----------
    path : str or Path
        The dynamic scene with its ``[deployment]``.
    heave_path : str or Path, optional
        The heave scene of today's deployment of the same line (default: from
        :data:`HEAVE_COUNTERPARTS`, else none).
    rel_tol : float
        The constant speed's bisection width, relative (-).
    motion_step : float, optional
        The forward simulator's sampling of a sea's heave (a ``series``) and of the
        compensation, s (default its ``[simulation] time_step``;
        :func:`cable_ocp.schedule.forward.resimulate`; the series is interpolated
        linearly, :mod:`cable_ocp.numerics.table`, its error about motion_step^2
        max|z''| / 8).
    floor_fraction : float, optional
        The slowest constant speed tried, as a fraction of ``speed_max`` (-; default
        1 / :data:`cable_ocp.schedule.forward.FLOOR_DIVISOR`): a floor of v_f over a
        distance d simulates d / v_f s, and slow runs are the dearest.
    ipopt : dict, optional
        IPOPT options for the OCP (``ipopt.`` prefixed; e.g. ``{"ipopt.max_iter": 2000}``:
        the OCP's default is 500 iterations).
    progress : callable, optional
        ``progress(what)`` before each stage.
    on_row : callable, optional
        ``on_row(case)`` after each row, with the case's result so far (the same keys,
        ``"complete"`` False until the last row): a stopped run keeps what it finished.
    """
    from cable_ocp.scene.dynamics import load_dynamic_scene
    from cable_ocp.schedule.forward import Schedule, fastest_constant_speed
    from cable_ocp.schedule.planning import verified_schedule
    from cable_ocp.schedule.sea import vessel_motions

    say = progress or (lambda what: None)
    path = Path(path)
    if heave_path is None and path.stem in HEAVE_COUNTERPARTS:
        heave_path = HEAVE_COUNTERPARTS[path.stem]
    scene = load_dynamic_scene(path)
    if scene.deployment is None:
        raise CableOCPError(f"{path}: no [deployment] table")
    motions = vessel_motions(scene)
    dp = scene.deployment
    top = dp.speed_max
    floor = floor_fraction * top if floor_fraction is not None and top is not None else None

    def bisection(gain: float) -> tuple[Any, float]:
        say(f"{path.stem}: the fastest constant speed on the forward simulator (bisection)")
        t1 = time.perf_counter()
        out = fastest_constant_speed(scene, motions, rel_tol=rel_tol, motion_step=motion_step,
                                     floor=floor, ahc_gain=gain)
        return out, time.perf_counter() - t1

    # without compensation the constant speed does not depend on the optimum (its gain):
    # found first, it is the OCP's second warm start
    fc, fc_s = bisection(0.0) if not dp.ahc else (None, math.nan)
    say(f"{path.stem}: the OCP")
    t0 = time.perf_counter()
    res = verified_schedule(scene, motions, ipopt=ipopt, start_speeds=[fc.speed] if (
        fc is not None and fc.status == "solved") else ())
    wall = time.perf_counter() - t0
    d = res.diagnostics
    ocp = {"status": res.status, "message": res.message, "binding": list(res.binding),
           "duration_s": res.duration, "wall_s": wall,
           "warm_start_s": d.get("warm_start_s"), "build_s": d.get("build_s"),
           "solve_s": d.get("solve_time_s"), "iterations": d.get("iterations"),
           "start": d.get("start"), "starts": d.get("starts", []),
           "solve_total_s": d.get("solve_total_s"),
           "variables": d.get("variables"), "constraints": d.get("constraints"),
           "steps": d.get("steps"), "elements": d.get("elements"),
           "check_s": d.get("check_s"), "check_rounds": d.get("check_rounds"),
           "margins": res.margins,
           "rounds": [{"margins": dict(r.margins), "status": r.status,
                       "duration_s": r.duration, "violations": dict(r.violations),
                       "failed_runs": r.failed_runs,
                       "resolve_s": d.get(f"resolve_{i}_s") if i else None}
                      for i, r in enumerate(res.checks)],
           "violations": dict(res.solution.violations) if res.solution is not None else {}}
    t_opt = res.duration
    rows: list[dict[str, Any]] = []
    sim = scene.simulation
    res_note = (f"{sim.time_step:g} s, {sim.segments} elements"
                + (f", heave sampled every {motion_step:g} s" if motion_step else ""))
    case: dict[str, Any] = {"case": path.stem, "file": str(path),
                            "start_length_m": scene.length,
                            "target_length_m": scene.deployment.target_length,
                            "motions": [m.name for m in motions], "ocp": ocp, "heave": None,
                            "rows": rows, "complete": False}

    def done(row: dict[str, Any]) -> None:
        rows.append(row)
        if on_row is not None:
            on_row(case)
    opt_row: dict[str, Any] = {"method": "optimal schedule (OCP)", "status": res.status,
                               "duration_s": t_opt, "saving_pct": math.nan,
                               "speed_m_s": float(np.max(res.solution.speed))
                               if res.success else math.nan,
                               "binding": ", ".join(res.binding) or "none",
                               "worst_excess": math.nan, "worst_limit": None, "note": ""}
    if res.success:
        say(f"{path.stem}: the optimum re-simulated")
        sol = res.solution
        sched = Schedule.from_speed(sol.time, sol.speed, scene.length, sol.ahc_gain)
        opt_row.update(_forward_checks(scene, sched, motions, motion_step))
        opt_row["note"] = "forward check at " + res_note
    else:
        opt_row["note"] = (f"{res.message} ({d.get('iterations', '-')} iterations); "
                           "not a schedule")
    done(opt_row)
    ws = res.warm_start
    gain, gain_note = comparison_gain(
        scene, motions, res, (t_opt if math.isfinite(t_opt) else 0.0)
        + abs(dp.target_length - scene.length) / (dp.speed_max or 1.0) + 60.0)
    case["ahc_gain"] = gain
    if ws is not None:
        done({"method": "constant speed, OCP's line", "status":
                     "solved" if ws.feasible else "infeasible", "duration_s": ws.duration
                     if ws.feasible else math.nan,
                     "saving_pct": saving_pct(t_opt, ws.duration) if ws.feasible else math.nan,
                     "speed_m_s": ws.speed, "binding": ws.binding, "worst_excess": math.nan,
                     "worst_limit": None, "note": f"warm start, {ws.rollouts} rollouts"
                     + ("; rolled out without the compensation (g = 0)" if dp.ahc else "")})
    if fc is None:
        fc, fc_s = bisection(gain)
    fc_row: dict[str, Any] = {
        "method": "constant speed, forward simulator", "status": fc.status,
        "duration_s": fc.duration, "saving_pct": saving_pct(t_opt, fc.duration),
        "speed_m_s": fc.speed, "binding": fc.binding or "speed_max",
        "worst_excess": math.nan, "worst_limit": None,
        "note": f"{fc.simulations} runs at {res_note}, {fc_s:.0f} s; "
                f"bracket {fc.bracket[0]:.4g}-{fc.bracket[1]:.4g} m/s"
                + (f" (floor {floor:.4g} m/s)" if floor is not None else "")
                + (f"; with {gain_note}" if dp.ahc else "")}
    if fc.checks:
        chk = _check_row(fc.checks[-1])
        fc_row.update(worst_excess=chk["worst_excess"], worst_limit=chk["worst_limit"])
    if heave_path is None:
        case["complete"] = True
    done(fc_row)
    if heave_path is not None:
        say(f"{path.stem}: today's scheduled-gain deployment re-simulated")
        heave = case["heave"] = heave_payout(heave_path)
        sched = payout_schedule(scene.length, scene.deployment.target_length,
                                heave["payout_speed_m_s"], heave["ramp_time_s"])
        sched = Schedule(time=sched.time, length=sched.length, speed=sched.speed,
                         accel=sched.accel, ahc_gain=gain)
        same = (abs(heave["start_length_m"] - scene.length) < 1e-6
                and abs(heave["final_length_m"] - scene.deployment.target_length) < 1e-6)
        row = {"method": "scheduled-gain deployment (heave)", "status": "solved",
               "duration_s": heave["duration_s"],
               "saving_pct": saving_pct(t_opt, heave["duration_s"]),
               "speed_m_s": heave["payout_speed_m_s"], "binding": "chosen",
               "note": (f"{heave['payout_speed_m_s']:g} m/s over "
                        f"{abs(heave['final_length_m'] - heave['start_length_m']):g} m, "
                        f"{heave['ramp_time_s']:g} s ramps; re-simulated "
                        + (f"with {gain_note} for its compensator (the forward simulator "
                           "has no LQR)" if dp.ahc else "without the compensator")
                        + " at " + res_note
                        + ("" if same else "; lengths differ from the case"))}
        row.update(_forward_checks(scene, sched, motions, motion_step))
        case["complete"] = True
        done(row)
    return case


def cost_grid(durations: Sequence[float] = COST_DURATIONS,
              segments: Sequence[int] = COST_SEGMENTS, *, path: str | Path = COST_FILE,
              speed: float = COST_SPEED, time_step: float | None = None,
              budget_s: float = 600.0,
              progress: Callable[[str], None] | None = None) -> list[dict[str, Any]]:
    """The OCP's cost on a grid of durations and elements (module docstring): one row
    per cell (``duration_target_s``, ``distance_m``, ``segments``, ``status``,
    ``duration_s`` (the optimum), ``warm_duration_s``, ``saving_pct``, ``build_s``,
    ``solve_s``, ``iterations``, ``variables``, ``constraints``, ``steps``). A cell whose
    row neighbour with fewer elements took longer than ``budget_s`` (build + solve) is
    ``"skipped"``, not run.

    Parameters
    ----------
    durations : sequence of float
        The warm start's durations, s (each > 2 speed / accel_max).
    segments : sequence of int
        The OCP line's elements.
    path : str or Path
        The scene (its ``[deployment]`` limits; its ``target_length`` replaced).
    speed : float
        ``deployment.speed_max``, m/s.
    time_step : float, optional
        The OCP's step, s (default the scene's ``deployment.time_step``).
    budget_s : float
        s, the affordable cell (above: the row's larger cells skipped).
    progress : callable, optional
        ``progress(what)`` before each cell.
    """
    from cable_ocp.scene.dynamics import load_dynamic_scene
    from cable_ocp.schedule.planning import solve_schedule
    from cable_ocp.schedule.sea import vessel_motions

    say = progress or (lambda what: None)
    base = load_dynamic_scene(path)
    if base.deployment is None or base.deployment.accel_max is None:
        raise CableOCPError(f"{path}: the cost grid needs [deployment] accel_max")
    rows: list[dict[str, Any]] = []
    for dur in durations:
        dist = distance_for(float(dur), speed, base.deployment.accel_max)
        sign = 1.0 if base.deployment.target_length >= base.length else -1.0
        over = {"deployment.target_length": base.length + sign * dist,
                "deployment.speed_max": speed}
        if time_step is not None:
            over["deployment.time_step"] = time_step
        scene = load_dynamic_scene(path, over)
        heaves = [m.casadi_heave() for m in vessel_motions(scene)]
        over_budget = False
        for n in segments:
            row: dict[str, Any] = {"duration_target_s": float(dur), "distance_m": dist,
                                   "segments": int(n)}
            if over_budget:
                row.update(status="skipped", note=f"the cell with fewer elements took more "
                                                  f"than {budget_s:g} s")
                rows.append(row)
                continue
            say(f"cost: {dur:g} s, {n} elements")
            res = solve_schedule(scene, heaves, segments=int(n))
            d = res.diagnostics
            ws = res.warm_start
            row.update(status=res.status, duration_s=res.duration,
                       warm_duration_s=ws.duration if ws is not None else math.nan,
                       saving_pct=saving_pct(res.duration, ws.duration if ws is not None
                                             else math.nan),
                       warm_start_s=d.get("warm_start_s", math.nan),
                       build_s=d.get("build_s", math.nan),
                       solve_s=d.get("solve_time_s", math.nan),
                       iterations=d.get("iterations"), variables=d.get("variables"),
                       constraints=d.get("constraints"), steps=d.get("steps"),
                       binding=", ".join(res.binding) or "none", note=res.message)
            rows.append(row)
            over_budget = (row["build_s"] + row["solve_s"]) > budget_s
    return rows


def cost_fits(rows: Sequence[dict[str, Any]]) -> dict[str, dict[str, float]]:
    """The exponents p of y = c x^p of the build and solve times (s), the iterations and
    the variables: against the duration at the most elements present in every duration
    (``"duration"``), against the elements at the longest duration present for every
    element count (``"segments"``), over the solved cells only (:func:`fit_exponent`).

    Parameters
    ----------
    rows : sequence of dict
        :func:`cost_grid`'s rows.
    """
    ok = [r for r in rows if r.get("status") == "solved"]
    out: dict[str, dict[str, float]] = {}
    keys = ("build_s", "solve_s", "iterations", "variables")
    if not ok:
        return out
    # along the duration: the element count solved at the most durations (the largest)
    segs = sorted({r["segments"] for r in ok})
    durs = sorted({r["duration_target_s"] for r in ok})
    n_best = max(segs, key=lambda n: (sum(r["segments"] == n for r in ok), n))
    d_best = max(durs, key=lambda t: (sum(r["duration_target_s"] == t for r in ok), t))
    along_d = [r for r in ok if r["segments"] == n_best]
    along_n = [r for r in ok if r["duration_target_s"] == d_best]
    out["duration"] = {"at_segments": float(n_best), **{k: fit_exponent(
        [r["duration_target_s"] for r in along_d], [r[k] for r in along_d])[0] for k in keys}}
    out["segments"] = {"at_duration_s": float(d_best), **{k: fit_exponent(
        [r["segments"] for r in along_n], [r[k] for r in along_n])[0] for k in keys}}
    return out


def long_run(path: str | Path = LONG_FILE, *, duration: float = LONG_DURATION,
             segments: int = LONG_SEGMENTS, speed: float | None = LONG_SPEED,
             time_step: float | None = None, ipopt: dict[str, Any] | None = None,
             progress: Callable[[str], None] | None = None) -> dict[str, Any]:
    """A deployment of about ``duration`` s on ``segments`` elements, its warm start lasting
    ``duration`` where the speed binds: with a ``speed``, the scene's ``speed_max`` set to
    it and its ``target_length`` to the start plus the distance d = v (T - v / a)
    (:func:`distance_for`, as :func:`cost_grid` does); without, the scene's distance kept
    and ``speed_max`` replaced by the v that covers it in ``duration``. Returns the times
    apart (``warm_start_s``, ``build_s``, ``solve_s``, ``wall_s``), the status, the
    duration, the sizes, the nlpsol options (``ipopt``) and the process's peak resident
    memory so far (``peak_rss_bytes``, bytes).

    Parameters
    ----------
    path : str or Path
        The scene with its ``[deployment]`` (and its sea).
    duration : float
        T, s.
    segments : int
        The OCP line's elements.
    speed : float, optional
        The cruise speed v, m/s (default :data:`LONG_SPEED`; None: the scene's own
        ``target_length``).
    time_step : float, optional
        The OCP's step, s (default ``deployment.time_step``).
    ipopt : dict, optional
        Options added to the OCP's nlpsol options (default :data:`LONG_IPOPT`; ``{}``
        for the OCP's own defaults).
    progress : callable, optional
        ``progress(what)``.
    """
    from cable_ocp.schedule.planning import solve_schedule
    from cable_ocp.schedule.sea import vessel_motions

    scene, dist, speed = _long_scene(path, duration, speed, time_step)
    pb = scene.deployment
    heaves = [m.casadi_heave() for m in vessel_motions(scene)]
    if progress is not None:
        progress(f"long: {duration:g} s, {segments} elements")
    t0 = time.perf_counter()
    opts = dict(LONG_IPOPT if ipopt is None else ipopt)
    res = solve_schedule(scene, heaves, segments=segments, ipopt=opts)
    wall = time.perf_counter() - t0
    d = res.diagnostics
    ws = res.warm_start
    return {"file": str(path), "distance_m": dist, "speed_max_m_s": speed,
            "target_length_m": pb.target_length,
            "segments": segments, "time_step_s": time_step or pb.time_step
            or scene.simulation.time_step, "status": res.status, "message": res.message,
            "binding": list(res.binding), "duration_s": res.duration,
            "warm_duration_s": ws.duration if ws is not None else math.nan,
            "saving_pct": saving_pct(res.duration, ws.duration if ws is not None
                                     else math.nan),
            "warm_start_s": d.get("warm_start_s", math.nan),
            "build_s": d.get("build_s", math.nan), "solve_s": d.get("solve_time_s", math.nan),
            "iterations": d.get("iterations"), "variables": d.get("variables"),
            "constraints": d.get("constraints"), "steps": d.get("steps"), "wall_s": wall,
            "ipopt": opts, "peak_rss_bytes": _peak_rss_bytes()}


def _long_scene(path: str | Path, duration: float, speed: float | None,
                time_step: float | None) -> tuple[Any, float, float]:
    """The long run's scene (:func:`long_run`), its distance (m) and ``speed_max`` (m/s)."""
    from cable_ocp.scene.dynamics import load_dynamic_scene
    from cable_ocp.schedule.robust import same_duration_speed

    base = load_dynamic_scene(path)
    pb = base.deployment
    if pb is None or pb.accel_max is None:
        raise CableOCPError(f"{path}: the long run needs [deployment] accel_max")
    over: dict[str, Any] = {}
    if speed is None:
        dist = abs(pb.target_length - base.length)
        speed = same_duration_speed(dist, duration, pb.accel_max)
    else:
        if not (math.isfinite(speed) and speed > 0.0):
            raise CableOCPError(f"bench deploy: the long run's speed {speed!r} m/s: give "
                                f"a speed > 0")
        dist = distance_for(duration, speed, pb.accel_max)
        sign = 1.0 if pb.target_length >= base.length else -1.0
        over["deployment.target_length"] = base.length + sign * dist
    over["deployment.speed_max"] = speed
    if time_step is not None:
        over["deployment.time_step"] = time_step
    return load_dynamic_scene(path, over), dist, speed


def _peak_rss_bytes() -> float:
    """The process's peak resident memory so far, bytes (nan where unknown)."""
    try:
        import resource
    except ImportError:  # not on Windows
        return math.nan
    scale = 1 if sys.platform == "darwin" else 1024  # ru_maxrss: bytes on macOS, else kB
    return float(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * scale)
