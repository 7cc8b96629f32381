"""The pull on the unit is the same point in the OCP and in the forward check
(cable_ocp/dynamics/driven.py ``axial_unit_pull``, cable_ocp/schedule/forward.py
``resimulate``): ``tension_at = ["unit"]`` bounds the line's pull on the unit (s = 0) in
both, whatever their elements.

Until 2026-12-03 the check's "unit" was element 0's tension, at the element's middle, w h / 2
above the OCP's pull (1350 N on 1000 m of the 6.3.6 line at 20 elements, 13.5 % of its
tension_min). The scene: huang_3_3_5.toml read as a dict (W = 42645 N, w = 53.19 N/m) on a
soft line (EA = 2.6 MN), lowered 50 -> 80 m in still water."""

from __future__ import annotations

import copy
import tomllib
from pathlib import Path

import numpy as np
import pytest

from cable_ocp.scene.dynamics import dynamic_scene_from_dict
from cable_ocp.schedule.forward import Schedule, resimulate
from cable_ocp.schedule.planning import solve_schedule
from cable_ocp.schedule.sea import vessel_motions

HUANG = Path(__file__).resolve().parents[2] / "problems" / "dynamics" / "huang_3_3_5.toml"
W, WL, L0 = 42645.0, 53.19, 50.0  # N, N/m, m


def _scene(segments: int):
    with HUANG.open("rb") as fh:
        d = copy.deepcopy(tomllib.load(fh))
    d["cable"].update(axial_stiffness=2.6e6, axial_damping=0.0)
    d["top_motion"] = {}
    d["simulation"]["segments"] = segments
    d["deployment"] = dict(target_length=80.0, segments=segments, time_step=0.25,
                           speed_max=2.0, accel_max=1.5, tension_min=0.7 * W,
                           tension_max=1.5 * W, tension_at=["unit"])
    return dynamic_scene_from_dict(d)


@pytest.mark.parametrize("segments", [2, 8])
def test_at_rest_the_pull_is_the_units_weight_whatever_the_elements(segments):
    """At rest the line pulls the unit with its weight in water, W: the check's unit tension
    is W (round-off of the static profile: 1e-6 N), element 0's W + w h / 2 (the closed form
    of its middle, h = L / n)."""
    scene = _scene(segments)
    still = Schedule.from_speed(np.array([0.0, 10.0, 20.0, 30.0]),
                                np.array([0.0, 0.0, 1.0, 0.0]), scene.length)
    run = resimulate(scene, still, vessel_motions(scene)[0], time_step=0.05, hold=0.0)
    rest = run.t < 9.0
    assert np.max(np.abs(run.unit_tension[rest] - W)) < 1e-6
    assert run.tension_min_line[0] == pytest.approx(W + 0.5 * WL * L0 / segments, abs=1e-6)


def test_the_check_reproduces_the_ocps_pull_at_its_own_resolution():
    """The OCP bounding the pull (tension_at = ["unit"]) on 2 elements, re-simulated on 2
    elements at its own step: the pull at the OCP's nodes agrees to 20 N (seen 3.9 N: the
    forward check's acceleration by central differences of the samples against the
    step's own; element 0's differs by w h / 2 = 665 N), and tension_min is kept to 1e-3
    (seen 5e-5)."""
    scene = _scene(2)
    motions = vessel_motions(scene)
    res = solve_schedule(scene, [m.casadi_heave() for m in motions])
    assert res.success, res.message
    sol = res.solution
    run = resimulate(scene, Schedule.from_speed(sol.time, sol.speed, scene.length),
                     motions[0], time_step=float(sol.time[1]), segments=2, hold=0.0)
    pull = np.interp(sol.time[1:], run.t, run.unit_tension)
    assert np.max(np.abs(pull - sol.outputs[0, 1:, 2])) < 20.0
    assert run.violations["tension_min"] < 1e-3
