"""Robust schedules (cable_ocp/schedule/robust.py): the same-duration trapezoid against its
closed form, the tally's counts against the runs themselves, the robust schedule on its own
design realisations after re-simulation.

The scene is problems/dynamics/deploy_small.toml lowered 50 -> 80 m on a coarse line (a
fraction of a second per run); the OCP on 3 elements at a 0.5 s step (a few s)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.scene.dynamics import load_dynamic_scene
from cable_ocp.schedule.forward import JUMP_RAMP, resimulate, trapezoid_schedule
from cable_ocp.schedule.robust import robust_study, same_duration_trapezoid, tally
from cable_ocp.schedule.sea import vessel_motions

ROOT = Path(__file__).resolve().parents[2]
SMALL = ROOT / "problems" / "dynamics" / "deploy_small.toml"
COARSE = {"deployment.target_length": 80.0, "simulation.segments": 5,
          "simulation.time_step": 0.05}
#: a mild sea: the limits of deploy_small keep on it at moderate speeds
SEA = {"deployment.sea.significant_height": 0.4, "deployment.sea.peak_frequency": 0.9,
       "deployment.sea.components": 16, "deployment.sea.fade_in": 5.0,
       "deployment.sea.realisations": 2, "deployment.sea.unseen": 1}


def _scene(**over):
    ov = dict(COARSE)
    ov.update(over)
    return load_dynamic_scene(SMALL, ov)


@pytest.mark.parametrize("dist, accel, duration", [
    (100.0, 0.2, 60.0), (30.0, 0.5, 31.7), (1.0, 2.0, 1.5), (500.0, 0.05, 2000.0)])
def test_same_duration_trapezoid_has_the_asked_duration(dist, accel, duration):
    s = same_duration_trapezoid(50.0, 50.0 + dist, duration, accel)
    # the last node is T by construction; D / v + v / a recomputed carries round-off only
    assert s.duration == pytest.approx(duration, rel=1e-12)
    v = float(np.max(s.speed))
    assert dist / v + v / accel == pytest.approx(duration, rel=1e-12)
    # the smaller root: the trapezoid reaches its cruise speed (v <= sqrt(a D))
    assert v <= math.sqrt(accel * dist)
    assert np.max(np.abs(s.accel)) == pytest.approx(accel, rel=1e-9)  # T's round-off
    assert s.length[-1] == 50.0 + dist and s.speed[-1] == 0.0
    # a haul-in: the same speed, negative
    h = same_duration_trapezoid(50.0 + dist, 50.0, duration, accel)
    assert h.duration == pytest.approx(duration, rel=1e-12)
    assert float(np.min(h.speed)) == pytest.approx(-v, rel=1e-12)


def test_same_duration_trapezoid_triangle_jump_and_bad_input():
    d, a = 40.0, 0.4
    shortest = 2.0 * math.sqrt(d / a)
    tri = same_duration_trapezoid(0.5, 0.5 + d, shortest, a)
    # the double root: the triangle of peak sqrt(a D)
    assert tri.duration == pytest.approx(shortest, rel=1e-12)
    assert float(np.max(tri.speed)) == pytest.approx(math.sqrt(a * d), rel=1e-6)
    jump = same_duration_trapezoid(0.5, 0.5 + d, 20.0, None)
    assert jump.duration == pytest.approx(20.0, rel=1e-12)
    assert float(np.max(jump.speed)) == pytest.approx(d / (20.0 - JUMP_RAMP), rel=1e-12)
    with pytest.raises(CableOCPError, match=r"duration = 19\.9 s.*shortest.*20 s"):
        same_duration_trapezoid(0.5, 0.5 + d, 19.9, a)
    for bad in (0.0, -1.0, math.inf):
        with pytest.raises(CableOCPError, match="duration"):
            same_duration_trapezoid(0.5, 0.5 + d, bad, a)
    with pytest.raises(CableOCPError, match="accel"):
        same_duration_trapezoid(0.5, 0.5 + d, 30.0, 0.0)
    with pytest.raises(CableOCPError, match="equals start"):
        same_duration_trapezoid(0.5, 0.5, 30.0, a)


def test_tally_counts_equal_the_runs_and_a_jump_goes_slack():
    scene = _scene(**SEA)
    motions = vessel_motions(scene, "design")
    # a jump to 3 m/s: the unit (W / (M + M_a) = 3.3 m/s^2 at most) cannot follow the
    # sheave, the line goes slack; a gentle trapezoid keeps every limit
    scheds = {"jump": trapezoid_schedule(50.0, 80.0, 3.0, None),
              "gentle": trapezoid_schedule(50.0, 80.0, 1.0, 0.2)}
    seen = []
    tal = tally(scene, scheds, motions, hold=5.0, progress=lambda *a: seen.append(a))
    assert tal.status == "solved" and tal.motions == tuple(m.name for m in motions)
    assert [s[:2] for s in seen] == [(1, 4), (2, 4), (3, 4), (4, 4)]
    jump, gentle = tal["jump"], tal["gentle"]
    assert jump.runs == gentle.runs == 2
    assert jump.slack == 2 and jump.kept == 0 and jump.under_min == 2
    assert gentle.slack == 0 and gentle.kept == 2 and gentle.over_max == 0
    for st in (jump, gentle):
        # the counts recomputed from the runs themselves
        chks = st.checks
        assert st.slack == sum(c.slack for c in chks)
        assert st.kept == sum(c.keeps_limits(0.01) for c in chks)
        assert st.over_max == sum(c.violations["tension_max"] > 0.01 for c in chks)
        assert st.under_min == sum(c.violations["tension_min"] > 0.01 for c in chks)
        assert st.worst == {k: max(c.violations[k] for c in chks) for k in chks[0].violations}
        assert [s["motion"] for s in st.summaries] == [m.name for m in motions]
    # a run of its own: the tally's check is resimulate's (same inputs, same numbers)
    own = resimulate(scene, scheds["gentle"], motions[1], hold=5.0)
    assert gentle.checks[1].violations == own.violations
    assert gentle.summaries[1]["tension_min_N"] == float(np.min(own.tension_min_line))
    d = tal.as_dict()
    assert d["schedules"]["jump"]["slack"] == 2 and d["schedules"]["gentle"]["keeps_limits"] == 2
    with pytest.raises(CableOCPError, match="tol"):
        tally(scene, scheds, motions, tol=-1.0)
    with pytest.raises(CableOCPError, match="motion"):
        tally(scene, scheds, [])


def test_robust_schedule_keeps_the_limits_on_its_design_realisations():
    scene = _scene(**SEA, **{"deployment.segments": 3, "deployment.time_step": 0.5})
    st = robust_study(scene, nominal=False, margins=(0.0,), segments=3, hold=5.0)
    assert st.status == "solved", st.entries[0].result.message
    (e,) = st.entries
    assert e.name == "robust" and len(e.realisations) == 2
    # re-simulated on the OCP's 3 elements at a tenth of its step: every limit to 1 %
    des = st.design["robust"]
    assert des.runs == 2 and des.kept == 2, des.summaries
    # the same-duration trapezoid and both on the unseen realisation
    assert e.constant.duration == pytest.approx(e.duration, rel=1e-12)
    assert set(st.unseen.schedules) == {"robust", "robust constant"}
    assert st.unseen["robust constant"].runs == 1
