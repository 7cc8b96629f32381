"""Robust pay-out schedules: the sea is not known in advance (issue 25, item 3).

A schedule solved on design realisations of a sea (:func:`cable_ocp.schedule.sea.vessel_motions`
``"design"``) is re-simulated on unseen realisations of the same sea state (``"unseen"``,
seeds disjoint from the design ones) and the runs that go slack, exceed ``tension_max``,
fall under ``tension_min`` or keep every limit are counted (:func:`tally`), against the
constant-speed schedule of the same duration (:func:`same_duration_trapezoid`).

:func:`robust_study` solves (a) the nominal schedule, on the first design realisation
without a tension margin, and (b) the robust ones, on all design realisations together
(one schedule, every realisation inside the limits), with each of the given tension
margins (``deployment.tension_margin``, N, kept inside both tension limits by the OCP);
each schedule and its same-duration trapezoid are tallied on the unseen realisations.

The same-duration trapezoid: ramps at a, cruise v, distance D, duration
T = D / v + v / a, i.e. v^2 - a T v + a D = 0, whose roots have the product a D: one root
is <= sqrt(a D), the other >= sqrt(a D). A trapezoid needs D >= v^2 / a (it reaches its
cruise speed), i.e. v <= sqrt(a D): the smaller root

    v = (a T - sqrt(a^2 T^2 - 4 a D)) / 2 = 2 a D / (a T + sqrt(a^2 T^2 - 4 a D)),

(the second form without cancellation) is the one meant; the larger root's "trapezoid"
would be a triangle of peak sqrt(a D) and the shorter duration 2 sqrt(D / a). No real
root when T < 2 sqrt(D / a): no trapezoid is that short.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.scene.dynamics import DynamicScene
from cable_ocp.schedule.forward import (
    JUMP_RAMP,
    ForwardCheck,
    Schedule,
    resimulate,
    trapezoid_schedule,
    worst_violations,
)
from cable_ocp.schedule.planning import ScheduleResult, ramp_acceleration, verified_schedule
from cable_ocp.schedule.sea import VesselMotion, vessel_motions

__all__ = ["KEEP_TOL", "RobustStudy", "RobustTally", "ScheduleTally", "StudyEntry",
           "count_checks", "robust_study", "same_duration_speed", "same_duration_trapezoid",
           "schedule_of", "tally"]

#: the relative excess (-) a run may have and still keep a limit: the 1 % of issue 25's
#: "keeps every limit to 1 % of its value" (:meth:`ForwardCheck.keeps_limits`)
KEEP_TOL = 0.01


def same_duration_speed(distance: float, duration: float, accel: float) -> float:
    """The cruise speed v (m/s) of the trapezoid from rest to rest, ramped at ``accel``,
    that covers ``distance`` in ``duration``: the smaller root of v^2 - a T v + a D = 0
    (D / v + v / a = T), v = 2 a D / (a T + sqrt(a^2 T^2 - 4 a D)) without cancellation.
    The larger root is no trapezoid (it exceeds sqrt(a D): the ramps would overlap).

    Parameters
    ----------
    distance : float
        D, m, > 0.
    duration : float
        T, s.
    accel : float
        a, m/s^2, > 0.

    Raises
    ------
    CableOCPError
        ``accel`` not > 0, or ``duration`` shorter than the triangle's 2 sqrt(D / a).
    """
    if not accel > 0.0:
        raise CableOCPError(f"same_duration_trapezoid: accel = {accel} m/s^2 must be > 0")
    disc = (accel * duration) ** 2 - 4.0 * accel * distance
    if disc < 0.0:
        shortest = 2.0 * math.sqrt(distance / accel)
        raise CableOCPError(f"same_duration_trapezoid: duration = {duration:.6g} s: no "
                            f"trapezoid over {distance:.6g} m ramped at {accel:.6g} m/s^2 is "
                            f"that short; the shortest is the triangle's 2 sqrt(D / a) = "
                            f"{shortest:.6g} s")
    return 2.0 * accel * distance / (accel * duration + math.sqrt(disc))


def same_duration_trapezoid(start: float, target: float, duration: float,
                            accel: float | None) -> Schedule:
    """The constant-speed schedule (a trapezoid ramped at ``accel``) of a given duration.

    The cruise speed is the smaller root of v^2 - a T v + a D = 0 (module docstring),
    v = 2 a D / (a T + sqrt(a^2 T^2 - 4 a D)); at T = 2 sqrt(D / a) the triangle.
    Without an acceleration limit the ramps are :data:`~cable_ocp.schedule.forward.JUMP_RAMP`
    s long (:func:`~cable_ocp.schedule.forward.trapezoid_schedule`): v = D / (T - JUMP_RAMP).

    Parameters
    ----------
    start, target : float
        Lengths, m (a haul-in when target < start).
    duration : float
        T, s.
    accel : float or None
        The ramps' acceleration a, m/s^2, > 0 (None: a jump).

    Raises
    ------
    CableOCPError
        ``duration`` shorter than the triangle's 2 sqrt(D / a) (or than JUMP_RAMP without
        an acceleration), not finite, or an invalid ``accel`` (named).
    """
    dist = abs(target - start)
    if not dist > 0.0:
        raise CableOCPError(f"same_duration_trapezoid: target = {target} m equals start")
    if not (math.isfinite(duration) and duration > 0.0):
        raise CableOCPError(f"same_duration_trapezoid: duration = {duration} s must be a "
                            "finite time > 0")
    if accel is None:
        if not duration > JUMP_RAMP:
            raise CableOCPError(f"same_duration_trapezoid: duration = {duration} s: a jump "
                                f"in speed needs more than JUMP_RAMP = {JUMP_RAMP} s")
        return trapezoid_schedule(start, target, dist / (duration - JUMP_RAMP), None)
    sched = trapezoid_schedule(start, target, same_duration_speed(dist, duration, accel),
                               accel)
    # the nodes' sum D / v + v / a carries round-off: the last node is T by construction
    tt = sched.time.copy()
    tt[-1] = duration
    return Schedule(time=tt, length=sched.length, speed=sched.speed,
                    accel=np.diff(sched.speed) / np.diff(tt), ahc_gain=sched.ahc_gain)


@dataclass(frozen=True, eq=False)
class ScheduleTally:
    """One schedule re-simulated on every motion (:func:`tally`).

    Attributes
    ----------
    name : str
        The schedule's name.
    duration : float
        Its duration, s.
    runs : int
        Runs finished (one per motion, fewer when interrupted).
    slack : int
        Runs that went slack (a tension <= 0: the simulator stopped there).
    over_max : int
        Runs whose ``tension_max`` excess is above ``tol`` (0 without the limit).
    under_min : int
        Runs whose ``tension_min`` shortfall is above ``tol`` (a slack run counts too:
        its tension fell to 0; 0 without the limit).
    failed : int
        Runs whose simulation failed (neither solved nor slack).
    kept : int
        Runs keeping every limit within ``tol`` (:meth:`ForwardCheck.keeps_limits`).
    worst : dict of str to float
        Per limit imposed, the largest relative excess over the runs, -.
    checks : tuple of ForwardCheck
        The runs, in the motions' order (empty when not kept).
    summaries : tuple of dict
        Per run: ``motion``, ``status``, ``slack``, ``violations`` (-), ``tension_min_N``
        and ``tension_max_N`` (the smallest and largest element tension of the run, N).
    """

    name: str
    duration: float
    runs: int
    slack: int
    over_max: int
    under_min: int
    failed: int
    kept: int
    worst: dict[str, float]
    checks: tuple[ForwardCheck, ...] = ()
    summaries: tuple[dict[str, Any], ...] = ()

    def as_dict(self) -> dict[str, Any]:
        """The counts, the worst excesses and the summaries (JSON-ready)."""
        return {"name": self.name, "duration_s": self.duration, "runs": self.runs,
                "slack": self.slack, "over_tension_max": self.over_max,
                "under_tension_min": self.under_min, "failed": self.failed,
                "keeps_limits": self.kept, "worst_excess": dict(self.worst),
                "runs_detail": [dict(s) for s in self.summaries]}


@dataclass(frozen=True, eq=False)
class RobustTally:
    """Schedules re-simulated on a set of vessel motions (:func:`tally`).

    Attributes
    ----------
    status : str
        ``"solved"`` (every run done) or ``"interrupted"``.
    tol : float
        The relative excess (-) counted as keeping a limit.
    motions : tuple of str
        The motions' names.
    schedules : dict of str to ScheduleTally
        Per schedule, in the given order.
    time_s : float
        Wall time of the runs, s.
    """

    status: str
    tol: float
    motions: tuple[str, ...]
    schedules: dict[str, ScheduleTally]
    time_s: float = 0.0

    def __getitem__(self, name: str) -> ScheduleTally:
        return self.schedules[name]

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready."""
        return {"status": self.status, "tol": self.tol, "motions": list(self.motions),
                "time_s": self.time_s,
                "schedules": {k: v.as_dict() for k, v in self.schedules.items()}}


def _summary(chk: ForwardCheck) -> dict[str, Any]:
    n = chk.tension_min_line.size
    return {"motion": chk.motion, "status": chk.status, "slack": chk.slack,
            "violations": dict(chk.violations),
            "tension_min_N": float(np.min(chk.tension_min_line)) if n else math.nan,
            "tension_max_N": float(np.max(chk.tension_max_line)) if n else math.nan}


def count_checks(name: str, duration: float, checks: Sequence[ForwardCheck], tol: float,
                 keep: bool = True) -> ScheduleTally:
    """The counts of re-simulated runs (:class:`ScheduleTally`): the one home of what
    counts as slack, over ``tension_max``, under ``tension_min`` (a relative excess above
    ``tol``), failed and kept, for :func:`tally` and the receding horizon's comparison.

    Parameters
    ----------
    name : str
        The schedule's name.
    duration : float
        Its duration, s.
    checks : sequence of ForwardCheck
        The runs.
    tol : float
        The relative tolerance on each limit (-).
    keep : bool
        Keep the checks themselves in the result.
    """
    worst = worst_violations(checks)
    return ScheduleTally(
        name=name, duration=duration, runs=len(checks),
        slack=sum(1 for c in checks if c.slack or c.status == "slack"),
        over_max=sum(1 for c in checks if c.violations.get("tension_max", 0.0) > tol),
        under_min=sum(1 for c in checks if c.violations.get("tension_min", 0.0) > tol),
        failed=sum(1 for c in checks if c.status not in ("solved", "slack")),
        kept=sum(1 for c in checks if c.keeps_limits(tol)),
        worst=worst, checks=tuple(checks) if keep else (),
        summaries=tuple(_summary(c) for c in checks))


def tally(scene: DynamicScene, schedules: Mapping[str, Schedule],
          motions: Sequence[VesselMotion], *, time_step: float | None = None,
          segments: int | None = None, hold: float = 20.0,
          motion_step: float | None = None, tol: float = KEEP_TOL, keep_checks: bool = True,
          progress: Callable[[int, int, str, str], None] | None = None) -> RobustTally:
    """Re-simulate every schedule on every motion
    (:func:`~cable_ocp.schedule.forward.resimulate`) and count the runs.

    Per schedule: runs, slack, over ``tension_max`` (excess > ``tol``), under
    ``tension_min`` (shortfall > ``tol``), failed, keeping every limit
    (``keeps_limits(tol)``), the worst relative excess per limit (:class:`ScheduleTally`).
    The limits are the scene's ``[deployment]`` ones, without ``tension_margin``.

    Parameters
    ----------
    scene : DynamicScene
        With its ``[deployment]`` limits (none: only slack and failures are counted).
    schedules : mapping of str to Schedule
        Named schedules, each from L(0) = cable.length.
    motions : sequence of VesselMotion
        The vessel motions (e.g. ``vessel_motions(scene, "unseen")``).
    time_step : float, optional
        s, of the runs (default ``simulation.time_step``).
    segments : int, optional
        Elements of the runs (default ``simulation.segments``).
    hold : float
        s simulated after each schedule's end (the winch at rest), >= 0.
    motion_step : float, optional
        s, the heave series' sampling (default ``time_step``).
    tol : float
        The relative excess (-) that still keeps a limit, >= 0 (default 1 %).
    keep_checks : bool
        Keep every run's :class:`ForwardCheck` (else the summaries only).
    progress : callable, optional
        ``progress(done, total, schedule, motion)`` after each run.

    Raises
    ------
    CableOCPError
        No schedule or no motion, a negative ``tol``, or :func:`resimulate`'s errors.
    """
    if not schedules:
        raise CableOCPError("tally: give at least one schedule")
    if not motions:
        raise CableOCPError("tally: give at least one vessel motion")
    if not tol >= 0.0:
        raise CableOCPError(f"tally: tol = {tol} must be >= 0")
    t0 = time.perf_counter()
    total = len(schedules) * len(motions)
    done = 0
    status = "solved"
    out: dict[str, ScheduleTally] = {}
    for name, sched in schedules.items():
        checks: list[ForwardCheck] = []
        for m in motions:
            if status == "interrupted":
                break
            chk = resimulate(scene, sched, m, time_step=time_step, segments=segments,
                             hold=hold, motion_step=motion_step)
            if chk.status == "interrupted":
                status = "interrupted"
                break
            checks.append(chk)
            done += 1
            if progress is not None:
                progress(done, total, name, m.name)
        out[name] = count_checks(name, sched.duration, checks, tol, keep_checks)
    return RobustTally(status=status, tol=float(tol), motions=tuple(m.name for m in motions),
                       schedules=out, time_s=time.perf_counter() - t0)


def schedule_of(result: ScheduleResult, start: float) -> Schedule:
    """The :class:`Schedule` of a solved OCP: its nodal speeds, the length their
    trapezoidal integral (the OCP's own kinematics), its compensation gain.

    Parameters
    ----------
    result : ScheduleResult
        A solved schedule.
    start : float
        L(0), m (the scene's cable.length).

    Raises
    ------
    CableOCPError
        The result is not solved (its arrays are no schedule).
    """
    if not result.success or result.solution is None:
        raise CableOCPError(f"schedule_of: the solve ended {result.status!r} "
                            f"({result.message}): no schedule")
    sol = result.solution
    return Schedule.from_speed(sol.time, sol.speed, start, sol.ahc_gain)


@dataclass(frozen=True, eq=False)
class StudyEntry:
    """One solved variant of :func:`robust_study` and its same-duration trapezoid.

    Attributes
    ----------
    name : str
        ``"nominal"``, ``"robust"`` or ``"robust margin <m> N"``.
    realisations : tuple of str
        The design motions it was solved on.
    tension_margin : float
        N, the OCP's margin inside both tension limits.
    result : ScheduleResult
        The solve (its status says whether there is a schedule).
    schedule : Schedule or None
        The optimal schedule (None unless solved).
    constant : Schedule or None
        The trapezoid of the same duration (None unless solved, or when no trapezoid has
        that duration: see ``message``).
    constant_speed : float
        Its cruise speed, m/s (nan without it).
    message : str
        Why a schedule or its trapezoid is missing ("" when both are there).
    """

    name: str
    realisations: tuple[str, ...]
    tension_margin: float
    result: ScheduleResult
    schedule: Schedule | None
    constant: Schedule | None
    constant_speed: float = math.nan
    message: str = ""

    @property
    def duration(self) -> float:
        """The optimal schedule's duration, s (nan unless solved)."""
        return self.result.duration


@dataclass(frozen=True, eq=False)
class RobustStudy:
    """:func:`robust_study`'s schedules and their tallies.

    Attributes
    ----------
    status : str
        ``"solved"`` (every variant solved and tallied), ``"partial"`` (some variant has
        no schedule: its entry's status says why), ``"interrupted"``.
    entries : tuple of StudyEntry
        The variants, nominal first.
    unseen : RobustTally or None
        Every schedule and trapezoid on the unseen motions; the names are the entries'
        and ``"<name> constant"`` for the trapezoids.
    design : RobustTally or None
        The optimal schedules on the design motions (the robust one's own check).
    times : dict of str to float
        Wall times, s: ``"solve"`` (all variants), ``"unseen"``, ``"design"``, ``"total"``.
    """

    status: str
    entries: tuple[StudyEntry, ...]
    unseen: RobustTally | None
    design: RobustTally | None
    times: dict[str, float] = field(default_factory=dict)

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready: per entry its duration, status, constant speed and tallies."""
        rows = []
        for e in self.entries:
            row: dict[str, Any] = {
                "name": e.name, "status": e.result.status, "message": e.message or
                e.result.message, "realisations": list(e.realisations),
                "tension_margin_N": e.tension_margin,
                "duration_s": e.duration if e.result.success else None,
                "constant_speed_m_s": e.constant_speed if e.constant is not None else None}
            for key, tal in (("unseen", self.unseen), ("design", self.design)):
                if tal is not None and e.name in tal.schedules:
                    row[key] = tal.schedules[e.name].as_dict()
                if (key == "unseen" and tal is not None
                        and f"{e.name} constant" in tal.schedules):
                    row["unseen_constant"] = tal.schedules[f"{e.name} constant"].as_dict()
            rows.append(row)
        return {"status": self.status, "entries": rows, "times_s": dict(self.times)}


def robust_study(scene: DynamicScene, *, design: Sequence[VesselMotion] | None = None,
                 unseen: Sequence[VesselMotion] | None = None,
                 margins: Sequence[float] = (0.0,), nominal: bool = True,
                 check_design: bool = True, time_step: float | None = None,
                 segments: int | None = None, hold: float = 20.0,
                 tol: float = KEEP_TOL, ocp_segments: int | None = None,
                 ocp_time_step: float | None = None,
                 progress: Callable[[int, int, str, str], None] | None = None
                 ) -> RobustStudy:
    """The nominal and robust schedules of a scene and what they buy on unseen seas.

    Variants (module docstring): ``"nominal"`` on ``design[0]`` without margin; for each
    margin m of ``margins`` the schedule on every design motion together with
    ``tension_margin = m`` (named ``"robust"`` for m = 0, else ``"robust margin <m> N"``;
    with a single design motion the margin-0 variant is the nominal one and is skipped).
    Each solved schedule and its same-duration trapezoid (ramped at
    :func:`~cable_ocp.schedule.planning.ramp_acceleration`) are tallied on the unseen
    motions; with ``check_design`` the schedules also on the design motions.

    Parameters
    ----------
    scene : DynamicScene
        With a ``[deployment]`` (its limits; its own ``tension_margin`` is replaced).
    design : sequence of VesselMotion, optional
        Default ``vessel_motions(scene, "design")``.
    unseen : sequence of VesselMotion, optional
        Default ``vessel_motions(scene, "unseen")`` (needs a ``[deployment.sea]``).
    margins : sequence of float
        N, >= 0, the robust variants' tension margins.
    nominal : bool
        Solve the nominal variant.
    check_design : bool
        Tally the optimal schedules on the design motions too.
    time_step, segments, hold, tol
        Of the re-simulations (:func:`tally`; s, -, s, -).
    ocp_segments, ocp_time_step
        Of the OCPs (:func:`~cable_ocp.schedule.planning.verified_schedule`, each checked
        on its design motions; -, s).
    progress : callable, optional
        :func:`tally`'s, on the unseen runs.

    Raises
    ------
    CableOCPError
        No ``[deployment]``, no unseen motions, a negative margin, no variant asked.
    """
    pb = scene.deployment
    if pb is None:
        raise CableOCPError("robust_study: the scene has no [deployment] table")
    t_all = time.perf_counter()
    des = list(design) if design is not None else vessel_motions(scene, "design")
    uns = list(unseen) if unseen is not None else vessel_motions(scene, "unseen")
    if not des or not uns:
        raise CableOCPError("robust_study: give at least one design and one unseen motion")
    for m in margins:
        if not (math.isfinite(m) and m >= 0.0):
            raise CableOCPError(f"robust_study: margins has {m} N; each must be >= 0")
    variants: list[tuple[str, list[VesselMotion], float]] = []
    if nominal:
        variants.append(("nominal", des[:1], 0.0))
    for m in margins:
        if m == 0.0 and len(des) == 1 and nominal:
            continue
        variants.append(("robust" if m == 0.0 else f"robust margin {m:.6g} N", des, float(m)))
    if not variants:
        raise CableOCPError("robust_study: no variant (nominal = False and no margins)")
    accel = ramp_acceleration(scene, pb)
    t0 = time.perf_counter()
    entries: list[StudyEntry] = []
    for name, motions, margin in variants:
        # each schedule passes the forward check on its own design motions first
        # (:func:`~cable_ocp.schedule.planning.verified_schedule`)
        res = verified_schedule(scene, motions, problem=replace(pb, tension_margin=margin),
                                segments=ocp_segments, time_step=ocp_time_step)
        sched = const = None
        speed, msg = math.nan, ""
        if res.success:
            sched = schedule_of(res, scene.length)
            try:
                const = same_duration_trapezoid(scene.length, pb.target_length,
                                                res.duration, accel)
                speed = float(np.max(np.abs(const.speed)))
            except CableOCPError as exc:
                msg = str(exc)
        entries.append(StudyEntry(name, tuple(m.name for m in motions), margin, res, sched,
                                  const, speed, msg))
        if res.status == "interrupted":
            break
    times = {"solve": time.perf_counter() - t0}
    if any(e.result.status == "interrupted" for e in entries):
        times["total"] = time.perf_counter() - t_all
        return RobustStudy("interrupted", tuple(entries), None, None, times)
    runs: dict[str, Schedule] = {}
    for e in entries:
        if e.schedule is not None:
            runs[e.name] = e.schedule
        if e.constant is not None:
            runs[f"{e.name} constant"] = e.constant
    kw: dict[str, Any] = dict(time_step=time_step, segments=segments, hold=hold, tol=tol,
                              keep_checks=False)
    un = de = None
    status = "solved" if all(e.schedule is not None for e in entries) else "partial"
    if runs:
        t0 = time.perf_counter()
        un = tally(scene, runs, uns, progress=progress, **kw)
        times["unseen"] = time.perf_counter() - t0
        if un.status == "interrupted":
            status = "interrupted"
        elif check_design:
            t0 = time.perf_counter()
            de = tally(scene, {e.name: e.schedule for e in entries if e.schedule is not None},
                       des, **kw)
            times["design"] = time.perf_counter() - t0
            status = "interrupted" if de.status == "interrupted" else status
    times["total"] = time.perf_counter() - t_all
    return RobustStudy(status, tuple(entries), un, de, times)
