"""The receding-horizon deployment (cable_ocp/schedule/receding.py) in still water with
only the winch's speed and acceleration limits, where the open-loop optimum is the
trapezoid D/v + v/a (docs/deployment.md, "Checks"): the closed loop reaches the target,
its arrival time is within one step of the trapezoid's, its applied schedule keeps the
limits, the NLP is built once, and the re-plans come at multiples of the interval."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from cable_ocp.scene.dynamics import load_dynamic_scene
from cable_ocp.schedule.receding import HorizonNLP, receding_horizon
from cable_ocp.schedule.sea import VesselMotion, vessel_motions

ROOT = Path(__file__).resolve().parents[2]
SMALL = ROOT / "problems" / "dynamics" / "deploy_small.toml"
V, A, D = 3.0, 0.2, 100.0  # deploy_small's speed_max (m/s), accel_max (m/s^2), 50 -> 150 m


@pytest.fixture(scope="module")
def run():
    """deploy_small without its heave and without tension limits (a still sea: the
    tension limits cannot bind on a trapezoid at 0.2 m/s^2), 3 elements."""
    scene = load_dynamic_scene(SMALL, overrides={"top_motion.heave_amplitude": 0.0,
                                                 "deployment.segments": 3})
    scene = _without_tension_limits(scene)
    motion: VesselMotion = vessel_motions(scene, "design")[0]
    before = HorizonNLP.builds
    res = receding_horizon(scene, motion)
    return scene, res, HorizonNLP.builds - before


def _without_tension_limits(scene):
    import dataclasses
    pb = dataclasses.replace(scene.deployment, tension_min=None, tension_max=None)
    return dataclasses.replace(scene, deployment=pb)


def test_receding_horizon_reaches_the_target_within_a_step_of_the_trapezoid(run) -> None:
    scene, res, builds = run
    assert res.status == "solved", res.message
    dt = scene.deployment.time_step
    t_trap = D / V + V / A  # 48.33 s: the braking constraint is exact for the trapezoid
    # the arrival falls on the step grid: at most one step after the continuous optimum
    # (and never before it: nothing beats the trapezoid under these limits, up to IPOPT's
    # tolerance on the final length, 1 mm)
    assert t_trap - 1e-6 <= res.arrival <= t_trap + dt + 1e-9
    sch = res.schedule
    assert sch.length[-1] == pytest.approx(scene.deployment.target_length, abs=1e-3)
    assert builds == 1  # built once, then called with parameters


def test_receding_horizon_keeps_the_winch_limits_and_its_grid(run) -> None:
    scene, res, _ = run
    pb = scene.deployment
    sch = res.schedule
    # the plan's bounds are exact in IPOPT (bound constraints); round-off only
    assert np.max(np.abs(sch.accel)) <= pb.accel_max * (1 + 1e-9)
    assert np.max(sch.speed) <= pb.speed_max * (1 + 1e-9) and np.min(sch.speed) >= -1e-9
    assert res.failed_replans == 0 and all(s == "solved" for s in res.replan_status)
    k = res.replan_times / pb.replan_interval
    # re-plans at t = 0, I, 2I, ...: whole multiples of the interval, one after another
    assert np.allclose(k, np.arange(k.size), atol=1e-9)
    assert np.allclose(np.diff(sch.time), pb.time_step, rtol=1e-9)
    assert not math.isnan(res.duration) and res.duration >= res.arrival


@pytest.fixture(scope="module")
def heaved():
    """deploy_small in its 0.5 m heave, without tension limits, 3 elements: the unit is
    not at rest relative to the ship when the winch stops (the hold is not empty)."""
    scene = _without_tension_limits(load_dynamic_scene(SMALL, overrides={
        "deployment.segments": 3}))
    motion = vessel_motions(scene, "design")[0]
    return scene, motion, receding_horizon(scene, motion)


def test_receding_records_are_the_plants_and_the_hold_ends_at_the_first_rest(heaved) -> None:
    """The plant stepped over whole intervals in one call: its recorded tensions are the
    line's own steps along the applied schedule (recomputed here in one rollout), and
    the winch's hold ends at the first node after the arrival where the unit is at rest
    relative to the ship (|V_unit - dh/dt| <= rest_tolerance)."""
    from cable_ocp.schedule.ocp import line_step

    scene, motion, res = heaved
    assert res.status == "solved", res.message
    pb = scene.deployment
    dt = pb.time_step
    line = line_step(scene, 3)
    sch = res.schedule
    n = sch.time.size - 1
    zt = line.top_height + motion.heave(sch.time)
    p = np.vstack([sch.length[:-1], sch.length[1:], zt[:-1], zt[1:]])
    _, _, _, outs = line.forward.mapaccum(n)(line.start, p, np.full((1, n), dt))
    outs = np.asarray(outs)
    # the same steps, another grouping of the calls: round-off only (1e-9 of ~45 kN)
    np.testing.assert_allclose(res.unit_tension[1:], outs[2], rtol=1e-9)
    np.testing.assert_allclose(res.top_tension[1:], outs[3], rtol=1e-9)
    k_arr, k_end = round(res.arrival / dt), round(res.duration / dt)
    assert k_end == n and k_end > k_arr  # the schedule ends at the end; the hold is there
    rel = np.abs(outs[1] - motion.heave_rate(sch.time[1:]))  # at node j + 1
    rest = rel <= pb.rest_tolerance
    assert rest[k_end - 1] and not np.any(rest[k_arr - 1:k_end - 1])
    assert res.rest_speed == pytest.approx(rel[-1], rel=1e-9)
