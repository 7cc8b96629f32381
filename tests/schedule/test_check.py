"""The forward check's margins on the OCP's bounds (cable_ocp/schedule/ocp.py
``ScheduleOCP.bounds``; the loop itself: tests/test_deploy_cli.py, issue 25's 1 % check).

The margins move each limit's rows inwards, scaled as the rows are (tensions by the
OCP's tension scale, the power by power_max), and leave every other row alone."""

from __future__ import annotations

import copy
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from cable_ocp.scene.dynamics import dynamic_scene_from_dict, load_dynamic_scene
from cable_ocp.schedule.ocp import ScheduleOCP, line_step

SMALL = Path(__file__).resolve().parents[2] / "problems" / "dynamics" / "deploy_small.toml"
STILL = [ca.Function("still", [ca.SX.sym("t")], [ca.SX(0.0)])]


def test_margins_move_only_their_limits_rows_by_their_scale():
    raw = copy.deepcopy(load_dynamic_scene(SMALL).raw)
    raw["deployment"]["power_max"] = 2e5  # W
    raw["deployment"]["segments"] = 2
    scene = dynamic_scene_from_dict(raw)
    ocp = ScheduleOCP(scene, line_step(scene), STILL, 10)
    lo0, hi0 = ocp.bounds()
    lo, hi = ocp.bounds({"tension_min": 100.0, "tension_max": 300.0, "power_max": 1e3})
    ts = ocp.tension_scale
    rows = {name: np.concatenate([np.arange(a, b) for n, a, b, _, _ in ocp._groups
                                  if n == name]) for name in ("tension", "power_max")}
    # 10 steps x (2 elements + the line's 2 ends): the tension rows; 10 power rows
    assert rows["tension"].size == 40 and rows["power_max"].size == 10
    # exact in floating point but for the division's rounding (1e-12 relative)
    np.testing.assert_allclose(lo[rows["tension"]] - lo0[rows["tension"]], 100.0 / ts,
                               rtol=1e-9)
    np.testing.assert_allclose(hi0[rows["tension"]] - hi[rows["tension"]], 300.0 / ts,
                               rtol=1e-9)
    np.testing.assert_allclose(hi0[rows["power_max"]] - hi[rows["power_max"]], 1e3 / 2e5,
                               rtol=1e-9)
    np.testing.assert_allclose(lo[rows["power_max"]] - lo0[rows["power_max"]], 1e3 / 2e5,
                               rtol=1e-9)
    other = np.setdiff1d(np.arange(lo.size), np.concatenate(list(rows.values())))
    assert other.size > 0
    assert np.array_equal(lo[other], lo0[other]) and np.array_equal(hi[other], hi0[other])
    # the built bounds are not changed by a call
    assert np.array_equal(ocp.bounds()[0], lo0)
    assert ts == pytest.approx(42645.0 + 53.19 * 150.0, rel=1e-12)  # W + w L at 150 m
