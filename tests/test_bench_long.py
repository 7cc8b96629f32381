"""The long run's bookkeeping (cable_ocp/bench/deployment.py ``long_run``, issue 25): its
nlpsol options and peak memory as reported, and the line that prints them. The long run
itself takes hours (docs/deployment.md, "The long run"); nothing here solves it."""

from __future__ import annotations

import math
import resource

from cable_ocp.bench import deployment as bd
from cable_ocp.cli.bench_deploy import format_long


def test_peak_memory_is_the_process_peak_in_bytes():
    # ru_maxrss is kB on Linux: the reported bytes are 1024 x it, never below the 1 MB
    # that any Python process already holds (a kB-for-bytes slip would give ~1e5)
    kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    got = bd._peak_rss_bytes()
    assert got >= 1024.0 * kb > 1e6


def test_long_run_defaults_to_the_measured_options():
    # the options of the measured 600 s / 40-element run (docs/deployment.md, "The long
    # run": solved in 20 iterations with them)
    assert bd.LONG_IPOPT == {"expand": True, "ipopt.mumps_pivtol": 1e-4}


def test_long_line_reports_memory_and_options():
    row = dict(file="x.toml", distance_m=800.0, speed_max_m_s=1.3507, segments=40,
               time_step_s=0.5, status="interrupted", message="stopped", duration_s=math.nan,
               warm_duration_s=600.0, saving_pct=math.nan, steps=1200, variables=99,
               constraints=98, warm_start_s=1.0, build_s=2.0, solve_s=math.nan,
               iterations=None, wall_s=3.0, binding=[], ipopt={"expand": True},
               peak_rss_bytes=2.5e9)
    text = format_long(row)
    assert "peak memory 2.50 GB" in text and "'expand': True" in text
    assert "nlpsol options the defaults" in format_long({**row, "ipopt": {}})


def test_warm_start_scan_stops_before_max_steps():
    # no constant speed keeps a tension_min above the line's static tension, so the scan
    # runs down its whole grid: the top speed, WARM_TOP speeds down to 0.25 m/s, then
    # 0.25 m/s * (1e-3 / 0.25)^(k/6), k = 1..6: 100 m at 0.0025 m/s on 4 s steps is about
    # 10 000 steps, at 0.001 m/s 25 000 > MAX_STEPS (20000), not rolled out: 1 + WARM_TOP
    # + 5 rollouts (the OOM of the 6.3.6 long run, docs/deployment.md)
    import casadi as ca

    from cable_ocp.scene.dynamics import load_dynamic_scene
    from cable_ocp.schedule.ocp import line_step
    from cable_ocp.schedule.planning import MAX_STEPS, WARM_TOP, discrete_constant_speed

    scene = load_dynamic_scene("problems/dynamics/deploy_small.toml",
                               {"deployment.speed_max": 1.0, "deployment.tension_min": 1e9,
                                "deployment.tension_max": 2e9})
    still = ca.Function("still", [ca.SX.sym("t")], [ca.SX(0.0)])
    warm = discrete_constant_speed(scene, line_step(scene, 2), [still], scene.deployment, 4.0)
    assert MAX_STEPS == 20000 and not warm.feasible
    assert warm.rollouts == 1 + WARM_TOP + 5 and warm.binding == "tension_min"


def test_long_run_speed_sets_the_target_length():
    # with a speed v the target is the start + v (T - v / a): 0.5 (600 - 0.5 / 0.2) =
    # 298.75 m on the cost grid's line (start 50 m, a = 0.2 m/s^2), exact in binary
    # fractions; without one the scene's 100 m is kept and v solves d / v + v / a = T
    scene, dist, v = bd._long_scene(bd.LONG_FILE, 600.0, bd.LONG_SPEED, None)
    assert bd.LONG_SPEED == 0.5 and dist == 298.75 and v == 0.5
    assert scene.deployment.target_length == 348.75 and scene.deployment.speed_max == 0.5
    scene, dist, v = bd._long_scene(bd.LONG_FILE, 600.0, None, 1.0)
    assert dist == 100.0 and scene.deployment.target_length == 150.0
    assert scene.deployment.time_step == 1.0
    assert math.isclose(dist / v + v / 0.2, 600.0, rel_tol=1e-12)  # the root, to rounding
