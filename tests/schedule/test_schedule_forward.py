"""Pay-out schedules re-simulated (cable_ocp/schedule/forward.py): the trapezoid's closed
form, the speed table's integral, the limits checked on the forward simulator, the
bisection of the fastest constant speed and its infeasible case.

The runs are huang_3_3_5.toml (a 50 m line, a 13 t virtual unit mass) paid out to 80 m
on 5 elements at 0.05 s (a fraction of a second each)."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.scene.dynamic_parts import TopMotion
from cable_ocp.scene.dynamics import load_dynamic_scene
from cable_ocp.scene.motion import length_numeric
from cable_ocp.schedule.forward import (
    JUMP_RAMP,
    Schedule,
    fastest_constant_speed,
    resimulate,
    trapezoid_schedule,
)
from cable_ocp.schedule.sea import vessel_motions

ROOT = Path(__file__).resolve().parents[2]
HUANG = ROOT / "problems" / "dynamics" / "huang_3_3_5.toml"
COARSE = {"deployment.target_length": 80.0, "simulation.segments": 5,
          "simulation.time_step": 0.05}


def _scene(**deploy):
    ov = dict(COARSE)
    ov.update({f"deployment.{k}": v for k, v in deploy.items()})
    return load_dynamic_scene(HUANG, ov)


def _still(**deploy):
    """The scene without its heave: the unit's tension falls monotonically with speed."""
    ov = dict(COARSE, **{"top_motion.heave_amplitude": 0.0})
    ov.update({f"deployment.{k}": v for k, v in deploy.items()})
    return load_dynamic_scene(HUANG, ov)


def test_trapezoid_duration_is_the_closed_form():
    d, v, a = 30.0, 1.2, 0.4
    s = trapezoid_schedule(50.0, 50.0 + d, v, a)
    assert s.duration == pytest.approx(d / v + v / a, rel=1e-12)  # round-off
    assert np.max(np.abs(s.accel)) == pytest.approx(a, rel=1e-12)
    assert s.length[-1] == 80.0 and s.speed[0] == 0.0 and s.speed[-1] == 0.0
    # triangle: D < v^2/a, peak sqrt(D a), duration 2 sqrt(D/a)
    t = trapezoid_schedule(50.0, 51.0, 2.0, 0.5)
    assert np.max(t.speed) == pytest.approx(math.sqrt(0.5), rel=1e-12)
    assert t.duration == pytest.approx(2.0 * math.sqrt(1.0 / 0.5), rel=1e-12)
    # haul-in: negative speeds, the same duration
    h = trapezoid_schedule(80.0, 50.0, v, a)
    assert h.duration == pytest.approx(d / v + v / a, rel=1e-12)
    assert np.min(h.speed) == -v and h.length[-1] == 50.0
    # no acceleration limit: JUMP_RAMP-long ramps; a hold appends rest
    j = trapezoid_schedule(50.0, 80.0, 1.0, None, hold=5.0)
    assert j.duration == pytest.approx(30.0 + JUMP_RAMP + 5.0, rel=1e-12)
    assert j.speed[-1] == 0.0 and j.length[-2] == 80.0


def test_speed_table_integrates_to_the_target():
    s = trapezoid_schedule(50.0, 80.0, 1.3, 0.3, hold=2.0)
    tm = TopMotion(payout_law="table", payout_table=tuple(map(tuple, s.speed_table())),
                   payout_table_kind="speed")
    length, speed = length_numeric(tm, 50.0, [0.0, s.time[1], s.duration])
    # the simulator's exact integral of the linear speed: round-off only
    assert length[-1] == pytest.approx(80.0, abs=1e-12)
    assert length[1] == pytest.approx(s.length[1], abs=1e-12)
    assert speed[1] == pytest.approx(1.3, abs=1e-12)
    x = Schedule.from_speed(np.array([0.0, 2.0, 4.0]), np.array([0.0, 1.0, 0.0]), 10.0)
    assert x.length.tolist() == [10.0, 11.0, 12.0] and x.accel.tolist() == [0.5, -0.5]


def test_resimulate_keeps_limits_and_ends_at_the_target():
    scene = _scene(tension_min=15000.0, tension_max=80000.0, speed_max=1.5, accel_max=0.5,
                   power_max=1e5)
    motion = vessel_motions(scene)[0]
    chk = resimulate(scene, trapezoid_schedule(50.0, 80.0, 1.0, 0.5), motion)
    assert chk.status == "solved" and not chk.slack
    assert set(chk.violations) == {"tension_min", "tension_max", "speed_max", "accel_max",
                                   "power_max"}
    assert chk.keeps_limits(0.0)
    # the simulator integrates the same speed table: its end length is the target to
    # round-off
    assert chk.length[-1] == pytest.approx(80.0, abs=1e-9)
    assert chk.t[-1] == pytest.approx(30.0 / 1.0 + 1.0 / 0.5 + 20.0, abs=0.05 + 1e-9)
    assert np.all(chk.power == pytest.approx(chk.top_tension * np.abs(chk.speed)))
    # at rest at t = 0: element 0 carries the unit's weight in water plus half an element
    # (42645 + 53.19 * 10 / 2 N, the static state to its solver's tolerance) and the line
    # pulls the unit with its weight, 42645 N (the check's unit tension, the OCP's pull:
    # 1 N for the half element's inertia at the first sample's one-sided acceleration,
    # seen 0.2 N)
    assert chk.tension_min_line[0] == pytest.approx(42645.0 + 53.19 * 5.0, rel=1e-9)
    assert chk.unit_tension[0] == pytest.approx(42645.0, abs=1.0)


def test_the_check_reads_every_step_up_to_max_samples(monkeypatch):
    """The limits are read at the stored samples: every step of the check's time_step
    (0.05 s here, 52 s: 1041 samples) while the steps fit MAX_SAMPLES; above it every
    ceil(steps / MAX_SAMPLES)-th step, the run lengthened to a whole number of those."""
    import cable_ocp.schedule.forward as fwd

    scene = _scene(tension_min=15000.0)
    motion = vessel_motions(scene)[0]
    sched = trapezoid_schedule(50.0, 80.0, 1.0, 0.5)  # 32 s, and the 20 s hold
    chk = resimulate(scene, sched, motion)
    assert np.allclose(np.diff(chk.t), 0.05, rtol=0, atol=1e-9) and chk.t.size == 1041
    monkeypatch.setattr(fwd, "MAX_SAMPLES", 300)
    few = resimulate(scene, sched, motion)  # 1040 steps: every 4th
    assert np.allclose(np.diff(few.t), 0.2, rtol=0, atol=1e-9) and few.t.size == 261
    # the same run, read at every 4th step (the line's tensions to round-off; the unit's
    # pull moves by a few N: its acceleration is the samples' central differences)
    assert few.tension_min_line == pytest.approx(chk.tension_min_line[::4], rel=1e-9)
    # a hold of 20.1 s: 1042 steps, lengthened to 1044 (not cut to 1040, short of the hold)
    odd = resimulate(scene, sched, motion, hold=20.1)
    assert odd.t.size == 262 and odd.t[-1] == pytest.approx(52.2, abs=1e-9)


def test_violations_are_relative_excesses():
    scene = _scene(tension_max=50000.0, speed_max=0.8)
    chk = resimulate(scene, trapezoid_schedule(50.0, 80.0, 1.0, 0.5), vessel_motions(scene)[0])
    # tension_at = "line": the elements and both ends (the top's the largest here)
    top = float(max(np.max(chk.tension_max_line), np.max(chk.top_tension),
                    np.max(chk.unit_tension)))
    assert np.max(chk.top_tension) > np.max(chk.tension_max_line)
    assert chk.violations["tension_max"] == pytest.approx((top - 50000.0) / 50000.0,
                                                          rel=1e-12)
    assert chk.violations["speed_max"] == pytest.approx((1.0 - 0.8) / 0.8, rel=1e-12)
    assert not chk.keeps_limits()
    # named points: only the unit's element and the sheave's tension
    scene_u = _scene(tension_max=50000.0, tension_at=["unit"])
    chk_u = resimulate(scene_u, trapezoid_schedule(50.0, 80.0, 1.0, 0.5),
                       vessel_motions(scene_u)[0])
    assert chk_u.violations["tension_max"] == pytest.approx(
        max(0.0, (float(np.max(chk_u.unit_tension)) - 5e4) / 5e4), rel=1e-12)


def test_compensation_adds_the_heave_to_the_length():
    scene = _scene(accel_max=0.5)
    motion = vessel_motions(scene)[0]
    sched = dataclasses.replace(trapezoid_schedule(50.0, 80.0, 1.0, 0.5), ahc_gain=1.0)
    chk = resimulate(scene, sched, motion, hold=5.0, motion_step=0.05)
    z_end = float(motion.heave(np.array([chk.t[-1]]))[0])
    # the winch pays out L + g z: the table's linear speed integrates g dz/dt with an
    # error of about step^2 |z'''| / 12 per unit time (~1e-4 m over 37 s)
    assert chk.length[-1] == pytest.approx(80.0 + z_end, abs=2e-3)
    # the compensated line feels less of the heave than the plain one
    plain = resimulate(scene, trapezoid_schedule(50.0, 80.0, 1.0, 0.5), motion, hold=5.0)
    spread = np.ptp(chk.unit_tension[chk.t > 30.0])
    assert spread < np.ptp(plain.unit_tension[plain.t > 30.0])


def test_fastest_constant_speed_bracket_is_honest():
    scene = _still(tension_min=25000.0, accel_max=0.5)
    motions = vessel_motions(scene)
    rel = 1e-3
    res = fastest_constant_speed(scene, motions, rel_tol=rel)
    assert res.status == "solved" and res.binding == "tension_min"
    assert res.bracket[1] - res.bracket[0] <= rel * res.bracket[0]
    ok = resimulate(scene, trapezoid_schedule(50.0, 80.0, res.speed, 0.5), motions[0])
    assert ok.keeps_limits(0.0)
    bad = resimulate(scene, trapezoid_schedule(50.0, 80.0, res.speed * (1 + 2 * rel), 0.5),
                     motions[0])
    assert not bad.keeps_limits(0.0) and bad.violations["tension_min"] > 0.0
    assert res.duration == pytest.approx(30.0 / res.speed + res.speed / 0.5, rel=1e-12)
    # bounds of the binding tension at the end of the first ramp, where the unit moves at
    # v with the acceleration a: W' - f M a - 1/2 rho C_D S v^2 = tension_min (W' the
    # unit's weight plus half an element, M = 13 t the unit with its added mass);
    # f = 1 for a rigid line (quasi-static) and f = 2 for the elastic line's full
    # overshoot after the step in acceleration at t = 0 (undamped step response)
    drag = 0.5 * 1025.0 * 1.2 * 6.0
    v_rigid = math.sqrt((42645.0 + 53.19 * 3.0 - 13000.0 * 0.5 - 25000.0) / drag)
    v_elastic = math.sqrt((42645.0 + 53.19 * 3.0 - 2 * 13000.0 * 0.5 - 25000.0) / drag)
    assert v_elastic < res.speed < v_rigid
    assert res.simulations <= 20


def test_fastest_constant_speed_top_of_bracket_accepted():
    scene = _still(speed_max=0.5, tension_min=25000.0, accel_max=0.5)
    res = fastest_constant_speed(scene, vessel_motions(scene))
    assert res.status == "solved" and res.speed == 0.5 and res.simulations == 1
    assert math.isinf(res.bracket[1])


def test_impossible_tension_max_is_infeasible():
    # the static top tension W + w L = 42645 + 53.19 * 50 = 45305 N exceeds it
    scene = _still(tension_max=40000.0, accel_max=0.5)
    res = fastest_constant_speed(scene, vessel_motions(scene))
    assert res.status == "infeasible" and res.binding == "tension_max"
    assert "tension_max" in res.message and res.schedule is None and math.isnan(res.speed)
    assert res.checks[-1].violations["tension_max"] > 0.1


def test_errors_name_what_is_wrong():
    scene = _scene()
    motion = vessel_motions(scene)[0]
    with pytest.raises(CableOCPError, match="cable.length"):
        resimulate(scene, trapezoid_schedule(60.0, 80.0, 1.0, 0.5), motion)
    with pytest.raises(CableOCPError, match="deployment"):
        fastest_constant_speed(load_dynamic_scene(HUANG), [motion])
    with pytest.raises(CableOCPError, match="speed"):
        trapezoid_schedule(50.0, 80.0, 0.0, 0.5)
    sea = _scene(**{"sea.significant_height": 1.0, "sea.peak_frequency": 0.6,
                    "sea.fade_in": 0.0})
    with pytest.raises(CableOCPError, match="fade_in"):
        resimulate(sea, trapezoid_schedule(50.0, 80.0, 1.0, 0.5), vessel_motions(sea)[0])
