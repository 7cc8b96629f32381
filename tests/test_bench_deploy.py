"""The bookkeeping of ``cable-ocp bench deploy`` (cable_ocp/bench/deployment.py): the
saving, the exponent fit, the distances and speeds of the trapezoid, today's pay-out and a
tiny cost grid. The benchmark's numbers themselves are not asserted (docs/deployment.md)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from cable_ocp.bench import deployment as bd
from cable_ocp.cli import output as out
from cable_ocp.cli.app import main
from cable_ocp.errors import CableOCPError
from cable_ocp.schedule.robust import same_duration_speed


def test_saving_is_relative_to_the_other_duration():
    # 52 s against 65 s: 13 / 65 = 20 % exactly (not 13 / 52 = 25 %); 1e-12: round-off
    assert bd.saving_pct(52.0, 65.0) == pytest.approx(20.0, rel=1e-12)
    assert bd.saving_pct(70.0, 56.0) == pytest.approx(-25.0, rel=1e-12)
    assert math.isnan(bd.saving_pct(math.nan, 65.0))
    assert math.isnan(bd.saving_pct(52.0, 0.0))


def test_exponent_fit_recovers_a_power_law():
    x = np.array([60.0, 120.0, 240.0, 480.0])
    p, c = bd.fit_exponent(x, 3.0 * x**1.5)
    # an exact power law: the least squares in logs is exact to round-off (1e-9)
    assert p == pytest.approx(1.5, rel=1e-9) and c == pytest.approx(3.0, rel=1e-9)
    # non-positive or missing values are left out; one distinct x is no fit
    p2, _ = bd.fit_exponent([1.0, 2.0, 4.0, 8.0], [2.0, 8.0, math.nan, -1.0])
    assert p2 == pytest.approx(2.0, rel=1e-9)
    assert math.isnan(bd.fit_exponent([5.0, 5.0], [1.0, 2.0])[0])


def test_distance_and_cruise_speed_invert_each_other():
    # a trapezoid at 1 m/s ramped at 0.2 m/s^2 for 60 s: 5 s ramps lose 5 m: 55 m
    assert bd.distance_for(60.0, 1.0, 0.2) == pytest.approx(55.0, rel=1e-12)
    # 800 m in 600 s at 0.2 m/s^2: v^2 / a - T v + d = 0, the smaller root 1.3507 m/s
    v = same_duration_speed(800.0, 600.0, 0.2)  # the one home of the root (robust.py)
    assert v == pytest.approx(0.1 * (600.0 - math.sqrt(600.0**2 - 16000.0)), rel=1e-12)
    assert bd.distance_for(600.0, v, 0.2) == pytest.approx(800.0, rel=1e-12)
    with pytest.raises(CableOCPError, match="too short"):
        bd.distance_for(9.0, 1.0, 0.2)
    with pytest.raises(CableOCPError, match="the shortest is the triangle"):
        same_duration_speed(800.0, 100.0, 0.2)


def test_heave_payout_lasts_distance_over_speed_plus_ramp():
    hv = bd.heave_payout(bd.HEAVE_COUNTERPARTS["deploy_6_3_6"])
    # problems/heave/deployment_6_3_6.toml: 200 -> 1000 m at 1 m/s, 20 s ramps
    assert hv["duration_s"] == pytest.approx(800.0 / 1.0 + 20.0, rel=1e-12)
    sched = bd.payout_schedule(200.0, 1000.0, 1.0, 20.0)
    assert sched.duration == pytest.approx(820.0, rel=1e-12)
    # the quintic ramps integrate to the distance: the trapezoidal rule on 0.1 s samples of
    # the smooth speed errs by ~1e-6 m
    assert sched.length[-1] == pytest.approx(1000.0, abs=1e-4)
    assert np.max(sched.speed) == pytest.approx(1.0, rel=1e-9)
    # the ramp's largest acceleration 15/8 v / r (of 10x^3 - 15x^4 + 6x^5); sampled: 1e-3
    assert np.max(np.abs(sched.accel)) == pytest.approx(15.0 / 8.0 / 20.0, rel=1e-3)


def test_cost_fits_on_synthetic_rows():
    rows = [{"status": "solved", "duration_target_s": t, "segments": n,
             "build_s": 0.01 * t * n, "solve_s": 1e-4 * t**1.2 * n**2,
             "iterations": 30.0, "variables": 2.0 * n * t}
            for t in (60.0, 120.0, 240.0) for n in (5, 10)]
    rows.append({"status": "failed", "duration_target_s": 480.0, "segments": 10})
    f = bd.cost_fits(rows)
    # exact power laws: the fitted exponents to round-off (1e-9)
    assert f["duration"]["solve_s"] == pytest.approx(1.2, rel=1e-9)
    assert f["segments"]["solve_s"] == pytest.approx(2.0, rel=1e-9)
    assert f["duration"]["variables"] == pytest.approx(1.0, rel=1e-9)
    assert f["segments"]["at_duration_s"] == 240.0  # the failed 480 s cell is left out
    assert abs(f["duration"]["iterations"]) < 1e-9


def test_cost_grid_skips_beyond_the_budget():
    rows = bd.cost_grid([20.0], [2, 3], budget_s=1e-9)
    assert [r["status"] for r in rows] == ["solved", "skipped"]
    assert rows[0]["distance_m"] == pytest.approx(15.0, rel=1e-12)  # 1 m/s (20 - 5) s


def test_bench_deploy_cost_json_rows(tmp_path):
    path = tmp_path / "cost.json"
    rc = main(["bench", "deploy", "--quiet", "--part", "cost", "--durations", "20", "30",
               "--segments", "2", "--json", str(path)])
    assert rc == 0
    data = json.loads(path.read_text())
    rows = data["cost"]["rows"]
    assert [r["duration_target_s"] for r in rows] == [20.0, 30.0]
    for r in rows:
        assert r["status"] == "solved"
        # the saving as printed is the optimum against the warm start, relative to the
        # warm start (1e-9: the JSON's round trip is exact)
        assert r["saving_pct"] == pytest.approx(
            100.0 * (r["warm_duration_s"] - r["duration_s"]) / r["warm_duration_s"], rel=1e-9)
        assert r["warm_duration_s"] == pytest.approx(r["duration_target_s"], rel=0.02)
    # the variables grow with the steps: T, a (N), v and L (N + 1), states 2 n N
    for r in rows:
        n_k, n = r["steps"], r["segments"]
        assert r["variables"] == 1 + n_k + 2 * (n_k + 1) + 2 * n * n_k


_TINY = """
[environment]
water_depth = 3000.0
water_density = 1025.0
[cable]
length = 50.0
diameter = 0.047
weight_in_water = 53.19
axial_stiffness = 1.57012e7
tangential_drag = 0.01
mass_per_length = 7.2
[unit]
mass = 5000.0
added_mass = 8000.0
weight_in_water = 42645.0
[end_b]
position = [0.0, 0.0, 3000.0]
[simulation]
model = "axial"
duration = 20.0
time_step = 0.1
output_step = 0.5
segments = 2
[deployment]
target_length = 56.0
speed_max = 1.0
accel_max = 0.2
tension_min = 10000.0
tension_max = 120000.0
time_step = 0.5
segments = 2
"""


def test_bench_deploy_compare_keeps_each_finished_row(tmp_path, monkeypatch):
    # a stopped run keeps what it finished: the JSON is rewritten after every row, so a
    # run stopped by hand after the OCP's row leaves it on disk ("partial"). (Without
    # compensation the bisection on the forward simulator runs first, the OCP's second
    # warm start; the stop is put after the OCP's row, in the compared gain.)
    from cable_ocp.bench import deployment as bd

    case = tmp_path / "tiny.toml"
    case.write_text(_TINY)  # still water, 50 -> 56 m on 2 elements: a trapezoid
    path = tmp_path / "cmp.json"

    def stopped(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(bd, "comparison_gain", stopped)
    rc = main(["bench", "deploy", "--quiet", "--part", "compare", "--case", str(case),
               "--json", str(path)])
    assert rc == out.EXIT_INTERRUPTED
    data = json.loads(path.read_text())
    assert data["status"] == "partial"
    (got,) = data["compare"]
    assert got["complete"] is False
    assert [r["method"] for r in got["rows"]] == ["optimal schedule (OCP)"]
    assert got["rows"][0]["status"] == "solved"
    monkeypatch.undo()
    # the whole run: the case complete, the last envelope "ok"
    assert main(["bench", "deploy", "--quiet", "--part", "compare", "--case", str(case),
                 "--json", str(path)]) == 0
    data = json.loads(path.read_text())
    assert data["status"] == "ok"
    (got,) = data["compare"]
    assert got["complete"] is True and len(got["rows"]) == 3
    # the OCP solved from both starts: its own line's constant speed and the forward
    # simulator's (the row's speed, here speed_max: still water keeps the limits at it)
    starts = got["ocp"]["starts"]
    assert [s["start"] for s in starts] == ["OCP line's constant speed", "given start speed"]
    assert starts[1]["speed_m_s"] == got["rows"][2]["speed_m_s"] == 1.0
    assert got["ocp"]["start"] in {s["start"] for s in starts if s["status"] == "solved"}
    assert got["rows"][0]["duration_s"] == pytest.approx(11.0, rel=0.05)
