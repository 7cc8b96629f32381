"""The OCP's multi-start warm start (cable_ocp/schedule/planning.py: ``start_speeds``,
:func:`best_start`): the OCP line's constant speed and each given speed's trapezoid solved
on one built OCP, the shortest solved kept, the diagnostics naming it.

The line is test_optima's stiff one in still water (speed_max 1 m/s, accel_max 0.1 m/s^2,
30 m): the optimum is the trapezoid at speed_max, T = D / v + v / a = 40 s, which is also
the OCP line's own constant speed. IPOPT reaches it in 8 iterations from there and in 15
from the 0.3 m/s trapezoid (seen, default options); so with ``max_iter`` 11 the 0.3 m/s
start fails and the other solves, which decides which start is kept."""

from __future__ import annotations

import math

import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.schedule import planning
from cable_ocp.schedule.planning import (
    EXTRA_START,
    OCP_LINE_START,
    ConstantSpeed,
    best_start,
    solve_schedule,
    trapezoid,
)
from tests.schedule.test_optima import D, _stiff

V, A = 1.0, 0.1  # m/s, m/s^2
EXACT = D / V + V / A  # s, the trapezoid at speed_max
SLOW = 0.3  # m/s, a start IPOPT needs more than MAX_ITER iterations from
MAX_ITER = 11
OPTS = {"ipopt.max_iter": MAX_ITER}


def test_best_start_is_the_shortest_solved_else_the_first() -> None:
    """Failed starts never win however short; ties keep the first; nan is no duration."""
    assert best_start([("solved", 50.0), ("solved", 40.0)]) == 1
    assert best_start([("solved", 40.0), ("solved", 50.0)]) == 0
    assert best_start([("failed", 30.0), ("solved", 40.0)]) == 1
    assert best_start([("solved", 40.0), ("infeasible", 30.0), ("solved", 45.0)]) == 0
    assert best_start([("solved", 40.0), ("solved", 40.0)]) == 0
    assert best_start([("solved", math.nan), ("solved", 60.0)]) == 1
    assert best_start([("failed", 30.0), ("failed", 20.0)]) == 0
    assert best_start([("solved", 40.0)]) == 0


def test_the_ocp_lines_start_is_kept_when_the_given_one_fails() -> None:
    """Given 0.3 m/s: that start stops at max_iter, the OCP line's (1 m/s) solves to 40 s;
    the result is the latter's, and its diagnostics name both."""
    scene = _stiff(1.57e10, 4, speed_max=V, accel_max=A)
    res = solve_schedule(scene, steps=160, time_step=0.25, ipopt=OPTS, start_speeds=[SLOW])
    assert res.success, res.message
    # IPOPT's tol 1e-8: the time to 1e-6 (as test_optima)
    assert res.duration == pytest.approx(EXACT, rel=1e-6)
    d = res.diagnostics
    assert d["start"] == OCP_LINE_START and d["start_index"] == 0
    assert d["start_speed_m_s"] == pytest.approx(V, rel=1e-12)
    first, other = d["starts"]
    assert (first["start"], first["status"]) == (OCP_LINE_START, "solved")
    assert first["iterations"] == d["iterations"] < MAX_ITER
    assert (other["start"], other["speed_m_s"]) == (EXTRA_START, SLOW)
    assert other["status"] == "failed" and other["iterations"] == MAX_ITER
    assert other["return_status"] == "Maximum_Iterations_Exceeded"
    assert d["solve_total_s"] == pytest.approx(first["solve_time_s"] + other["solve_time_s"])
    assert "kept the start from the OCP line's constant speed" in res.message
    assert "given start speed, 0.3 m/s: failed" in res.message


def test_the_given_start_is_kept_when_the_ocp_lines_start_fails(monkeypatch) -> None:
    """The OCP line's constant speed replaced by the slow 0.3 m/s trapezoid (a stand-in
    for Huang's 3.3.5 line, where IPOPT creeps from it), given the 1 m/s: the given
    start's 40 s is kept, the OCP line's reported failed."""
    scene = _stiff(1.57e10, 4, speed_max=V, accel_max=A)

    def slow(sc, line, heaves, pb, dt, *args, **kw) -> ConstantSpeed:
        dur = trapezoid(sc.length, pb.target_length, SLOW, A, dt)[0]
        return ConstantSpeed(SLOW, A, dur, True, 1, "stand-in")

    monkeypatch.setattr(planning, "discrete_constant_speed", slow)
    res = solve_schedule(scene, steps=160, time_step=0.25, ipopt=OPTS, start_speeds=[V])
    assert res.success, res.message
    assert res.duration == pytest.approx(EXACT, rel=1e-6)  # as above
    assert res.warm_start is not None and res.warm_start.speed == SLOW  # still reported
    d = res.diagnostics
    assert (d["start"], d["start_index"], d["start_speed_m_s"]) == (EXTRA_START, 1, V)
    first, kept = d["starts"]
    assert (first["start"], first["status"], first["iterations"]) == (
        OCP_LINE_START, "failed", MAX_ITER)
    assert kept["status"] == "solved" and kept["iterations"] == d["iterations"]
    assert kept["duration_s"] == res.duration
    assert "kept the start from the given start speed, 1 m/s" in res.message


def test_no_start_solved_reports_the_ocp_lines() -> None:
    """max_iter 2: neither start solves; the result is the OCP line's failure."""
    scene = _stiff(1.57e10, 4, speed_max=V, accel_max=A)
    res = solve_schedule(scene, steps=160, time_step=0.25, ipopt={"ipopt.max_iter": 2},
                         start_speeds=[SLOW])
    assert res.status == "failed"
    assert res.diagnostics["start"] == OCP_LINE_START
    assert [s["status"] for s in res.diagnostics["starts"]] == ["failed", "failed"]


@pytest.mark.parametrize("bad", [0.0, -1.0, math.nan, 1.5])
def test_a_start_speed_outside_0_speed_max_is_refused(bad: float) -> None:
    scene = _stiff(1.57e10, 4, speed_max=V, accel_max=A)
    with pytest.raises(CableOCPError, match="start_speeds.*speed_max = 1 m/s"):
        solve_schedule(scene, steps=160, time_step=0.25, start_speeds=[bad])
