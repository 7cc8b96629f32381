"""The one model interface (dynamics/model.py) and the one slack report (dynamics/result.py).

The axial, planar and lumped-mass models of the shipped 113 m line (the heave examples'
cable scenes) implement :class:`CableModel`; their steps with the top motion and the
length as inputs keep the static state at rest when the top and the length stay still;
``simulate`` and ``modes`` dispatch on the interface; ``slack_report`` words every
model's slack the same way, and ``coarse_step_warnings`` and ``full_speed_start_warnings``
every model's warnings.
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest

from cable_ocp.dynamics import modes, simulate
from cable_ocp.dynamics.model import CableModel, DrivenStep, model_for
from cable_ocp.dynamics.result import (
    SLACK_STOPPED,
    coarse_step_warnings,
    full_speed_start_warnings,
    slack_report,
    until_slack,
)
from cable_ocp.scene.dynamics import load_dynamic_scene

LINES = {"axial": "line_6_3_6.toml", "planar": "line_6_3_6_planar.toml",
         "lumped3d": "line_6_3_6_lumped3d.toml"}
#: the driven step's scaled residual at rest: the planar and lumped starts are the discrete
#: equilibria by Newton (to 1e-12 and 1e-9 of the force scale); the axial start is the
#: closed-form profile, exact at the nodes, but evaluated from absolute heights (-1000 m:
#: offsets to 1e-13 m, a strain error of 2e-14: 3.3e-8 g of acceleration on this line, the
#: scale of its velocity rows; the bound leaves a factor 30)
BOUND = {"axial": 1e-6, "planar": 1e-8, "lumped3d": 1e-8}


@pytest.mark.parametrize("name", sorted(LINES))
def test_models_implement_the_interface_and_rest_in_their_driven_step(problems, name: str
                                                                     ) -> None:
    """Each model is a CableModel named as its ``simulation.model``, its static state has
    ``state_size()`` numbers, its K and M are symmetric, and its driven step at rest (the
    static start, the top and the length still: p = [L0, L0, z0, z0]) has a scaled
    residual at the model's predictor within :data:`BOUND`: a still top moves nothing."""
    scene = load_dynamic_scene(problems / "dynamics" / LINES[name])
    model = model_for(scene)
    assert isinstance(model, CableModel)
    assert model.name == name == scene.simulation.model
    x0, info = model.static_state()
    assert x0 is not None, info
    assert x0.size == model.state_size()
    k, m = model.linearize()
    assert k.shape == m.shape and np.allclose(k, k.T) and np.allclose(m, m.T)
    st = model.driven_step(scene.simulation.time_step)
    assert isinstance(st, DrivenStep)
    z0 = float(scene.top_position[2])
    p = [scene.length, scene.length, z0, z0]
    pars = [st.state, st.inputs] + ([] if isinstance(st.dt, float) else [st.dt])
    vals = [st.start, p] + ([] if isinstance(st.dt, float) else [scene.simulation.time_step])
    res = st.residual if st.residual_scale is None else st.residual * st.residual_scale
    guess = ca.Function("guess", pars, [st.guess])(*vals)
    r = ca.Function("res", [st.unknown, *pars], [res])(guess, *vals)
    assert float(np.max(np.abs(np.asarray(r)))) <= BOUND[name], float(np.max(np.abs(r)))


def test_simulate_and_modes_dispatch_on_the_interface(problems) -> None:
    """``simulate`` and ``modes`` give the model's own ``simulate`` and ``modes`` (the
    same numbers: one code path)."""
    f = problems / "dynamics" / "huang_5_7.toml"
    ov = {"simulation.duration": 2.0, "simulation.segments": 6}
    scene = load_dynamic_scene(f, ov)
    a, b = simulate(f, overrides=ov), model_for(scene).simulate()
    assert a.status == b.status and np.array_equal(a.top_tension, b.top_tension)
    ma, mb = modes(scene, 3), model_for(scene).modes(3)
    assert np.array_equal(ma.frequencies, mb.frequencies)


def test_slack_report_words_every_model_alike() -> None:
    """No slack: the entry says so and the status stays. Slack in a solved run: status
    "slack", the model's message with the action of ``on_slack``; a failed run keeps its
    status and message. ``until_slack`` keeps the samples up to the first at or after the
    first slack time: between samples (0.25 s) the next one, on a sample (0.3 s, as 0.3 and
    as 0.2 + 0.1, the grid's rounding either way) that one and none after it."""
    tpl = "slack at t = {t:.3g} s, segment {segment}, s = {location:.3g} m: {action}{x}"
    slack, status, msg = slack_report(None, None, None, status="solved", message="ok",
                                      on_slack="stop", template=tpl)
    assert slack == {"occurred": False, "first_time": None, "location": None,
                     "segment": None} and (status, msg) == ("solved", "ok")
    slack, status, msg = slack_report(1.5, 3, 12.0, status="solved", message="ok",
                                      on_slack="continue", template=tpl, continued="went on",
                                      x="!")
    assert slack == {"occurred": True, "first_time": 1.5, "location": 12.0, "segment": 3}
    assert status == "slack" and msg == "slack at t = 1.5 s, segment 3, s = 12 m: went on!"
    _, _, msg = slack_report(1.5, 3, 12.0, status="solved", message="ok", on_slack="stop",
                             template=tpl, x="")
    assert msg.endswith(SLACK_STOPPED)
    _, status, msg = slack_report(1.5, 3, 12.0, status="failed", message="no", on_slack="stop",
                                  template=tpl, x="")
    assert (status, msg) == ("failed", "no")
    t = np.arange(6) * 0.1
    assert until_slack(t, 0.25, 0.1, "stop").tolist() == [True] * 4 + [False] * 2
    for on_grid in (0.3, 0.2 + 0.1, 3 * 0.1):
        assert until_slack(t, on_grid, 0.1, "stop").tolist() == [True] * 4 + [False] * 2
    assert until_slack(t, 0.25, 0.1, "continue") is None
    assert until_slack(t, math.inf, 0.1, "stop") is None


# --------------------------------------------------------------------------------------
# a slack scene for every model
# --------------------------------------------------------------------------------------
MODELS = ("axial", "planar", "lumped3d")


def _drop_scene(model: str, **sim) -> dict:
    """A 100 m line in air (mu = 1 kg/m, EA = 1e6 N: c = 1000 m/s; 20 elements of 5 m) with
    a 100 kg unit; the top starts down at 0.6 m/s at t = 0 (a velocity step): the tension
    drop mu c V = 600 N reaches the unit at 0.1 s and doubles there, beyond the unit's
    981 N (test_planar's slack scene, at every model)."""
    g = 9.81
    d = {"environment": {"water_depth": 500.0, "water_density": 1.225},
         "cable": {"length": 100.0, "diameter": 0.01, "weight_in_water": g,
                   "axial_stiffness": 1.0e6, "mass_per_length": 1.0,
                   "added_mass_coefficient": 0.0},
         "unit": {"mass": 100.0, "weight_in_water": 100.0 * g},
         "end_b": {"position": [0.0, 0.0, 200.0]},
         "top_motion": {"series": [[0.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, -0.6]]},
         "simulation": {"model": model, "duration": 0.13, "time_step": 1e-3,
                        "output_step": 1e-3, "segments": 20}}
    d["simulation"].update(sim)
    return d


@pytest.mark.parametrize("name", MODELS)
def test_a_stopped_run_ends_at_the_first_sample_at_or_after_the_slack_time(name: str) -> None:
    """``on_slack = "stop"`` ends the history at the first output at or after the slack
    time (docs/dynamics.md, Slack), the same for every model and whatever the chunks of the
    run: with a sample every step the slack time (0.109 s here) is a sample, and the
    history ends there, for a run of 130 samples (the axial and planar loops advance one
    sample per chunk and stop there), of 300 (two per chunk: the loop has computed 0.110 s
    too) and of the lumped model (which does not stop). Tolerance 1e-12 s: the rounding of
    the grid k dt. Before the fix the history kept one output step more where the loop had
    computed it: 0.110 s for the lumped model and the 300-sample runs, 0.109 s for the
    others."""
    from cable_ocp.scene.dynamics import dynamic_scene_from_dict

    ends = []
    for duration in (0.13, 0.3):
        res = simulate(dynamic_scene_from_dict(_drop_scene(name, on_slack="stop",
                                                           duration=duration)))
        assert res.status == "slack" and SLACK_STOPPED in res.message
        first = res.slack["first_time"]
        assert res.t[-1] == pytest.approx(first, abs=1e-12)
        assert res.t.size == res.node_positions.shape[0] == res.top_tension.size
        ends.append((res.t.size, first))
    assert ends[0] == ends[1]


@pytest.mark.parametrize("name", MODELS)
def test_the_slack_time_is_the_end_of_the_first_step_with_a_slack_element(name: str) -> None:
    """``slack.first_time`` is the end time of the first step with a slack element (each
    model's ``step_function``: axial T <= -1e-9 of the static top tension, planar strain
    <= -1e-9 W / EA, lumped strain <= 0). With a sample every step that is exactly the
    first sample whose element strains, computed here from the stored node positions
    (|r_j+1 - r_j| / 5 m - 1), go negative; the sample before has none. Tolerance 1e-12 s:
    the step's end t_k + dt and the sample time (k + 1) dt differ by rounding only (one step
    is 1e-3 s). The strains at the two samples are about -39e-6 and +30e-6 (EA eps = -39 N
    and +30 N; asserted beyond -30e-6 and +20e-6): far beyond the models' thresholds
    (1e-6 N) and the rounding of the positions, so the strains from the positions and the
    models' own criteria pick the same step. ``segment`` is the element with the smallest
    strain there and ``location`` its middle (5 m elements, to rounding); the JSON says
    the same."""
    from cable_ocp.scene.dynamics import dynamic_scene_from_dict

    res = simulate(dynamic_scene_from_dict(_drop_scene(name)))
    assert res.status == "slack" and res.slack["occurred"], res.message
    strain = np.linalg.norm(np.diff(res.node_positions, axis=1), axis=2) / 5.0 - 1.0
    k = int(np.flatnonzero(strain.min(axis=1) < 0.0)[0])
    assert strain[k].min() < -30e-6 and strain[k - 1].min() > 20e-6
    first = res.slack["first_time"]
    assert first == pytest.approx(res.t[k], abs=1e-12)
    assert first == pytest.approx(k * 1e-3, abs=1e-12)
    assert res.slack["segment"] == int(np.argmin(strain[k]))
    assert res.slack["location"] == pytest.approx(5.0 * (res.slack["segment"] + 0.5),
                                                  rel=1e-12)
    assert res.to_dict()["slack"] == res.slack


@pytest.mark.parametrize("name", MODELS)
def test_the_output_grid_is_every_kth_step_when_the_ratio_is_inexact_in_binary(
        name: str) -> None:
    """time_step 0.1 s, output_step 0.3 s and duration 1.2 s: neither ratio is exact in
    binary (0.3 / 0.1 = 2.9999999999999996, 1.2 / 0.1 = 11.999999999999998), yet the run is
    12 steps with a sample every 3rd: exactly 5 samples at t = 0, 0.3, ..., 1.2 s
    (tolerance 1e-12 s: the rounding of k 3 dt), every history has 5 rows, the
    diagnostics and the progress hook count 12 steps, and the samples are the states after
    0, 3, ..., 12 steps: every 3rd sample of the run that stores every step (equal today;
    1e-12 m for the rounding of the step times k dt, computed otherwise in the two runs).
    The top heaves (0.1 m at 1 rad/s) so that the samples differ."""
    from cable_ocp.scene.dynamics import dynamic_scene_from_dict

    d = _drop_scene(name, duration=1.2, time_step=0.1, output_step=0.3)
    d["top_motion"] = {"heave_amplitude": 0.1, "heave_frequency": 1.0}
    scene = dynamic_scene_from_dict(d)
    assert (scene.simulation.steps, scene.simulation.output_every) == (12, 3)
    calls: list[tuple[int, int]] = []
    res = simulate(scene, progress=lambda done, total: calls.append((done, total)))
    assert res.status == "solved", res.message
    np.testing.assert_allclose(res.t, 0.3 * np.arange(5), rtol=0.0, atol=1e-12)
    for series in (res.length, res.top_position, res.unit_position, res.top_tension,
                   res.node_positions, res.segment_tensions):
        assert series.shape[0] == 5
    assert res.diagnostics["steps"] == 12
    assert calls[-1] == (12, 12)
    assert len(res.to_dict()["t"]) == 5
    # the samples are the states after 0, 3, ..., 12 steps: every 3rd of a run sampling
    # every step (the same 12 steps grouped otherwise: equal today, 1e-12 m for rounding)
    every_step = simulate(scene.with_overrides({"simulation.output_step": 0.1}))
    assert every_step.t.size == 13
    np.testing.assert_allclose(res.node_positions, every_step.node_positions[::3], rtol=0.0,
                               atol=1e-12)
    assert np.ptp(res.unit_position[:, 2]) > 0.05  # the samples differ


def test_the_warnings_of_a_coarse_step_and_a_full_speed_start() -> None:
    """Fewer than 20 steps per period of a motion that is on (4.5 rad/s at 0.25 s: 5.6),
    none for one that is off or well resolved; a tension step mu c dv = 4 kg/m x 500 m/s x
    1 m/s = 2000 N against a static top tension of 100 N, none below 10 % of it."""
    assert coarse_step_warnings(0.25, (("heave_frequency", 4.5), ("payout_frequency", 0.0),
                                       ("circular_frequency", 1.0))) == [
        "simulation.time_step = 0.25 s gives fewer than 20 steps per period of "
        "top_motion.heave_frequency = 4.5 rad/s"]
    assert full_speed_start_warnings(1.0, 4.0, 1.0e6, 100.0) == [
        "the top starts at full speed (1 m/s at t = 0): a tension step of about 2e+03 N "
        "(mu c dv) runs down the line, 2000% of the static top tension; set "
        "top_motion.ramp_time for a smooth start"]
    assert full_speed_start_warnings(1.0, 4.0, 1.0e6, 20000.0 + 1.0) == []


@pytest.mark.parametrize("name", ["planar", "lumped3d"])
def test_a_failed_static_start_is_an_empty_failed_history(problems, monkeypatch,
                                                          name: str) -> None:
    """A run whose statics start fails returns status "failed" and an empty history of the
    line's shapes (``SimulationResult.failed``), the statics message kept, no slack; it is
    never a solution. The statics solve is made to fail (a stand-in for an infeasible one)."""
    import json
    from types import SimpleNamespace

    import cable_ocp.dynamics.static as static

    failed = SimpleNamespace(success=False, status="infeasible", message="no equilibrium")
    monkeypatch.setattr(static, "static_state", lambda scene, *a, **k: failed)
    scene = load_dynamic_scene(problems / "dynamics" / LINES[name])
    res = simulate(scene)
    n = 20  # the file's simulation.segments
    assert res.status == "failed" and not res.success
    assert "no equilibrium" in res.message and res.model == name
    assert res.t.shape == (0,) and res.length.shape == (0,) and res.top_tension.shape == (0,)
    assert res.node_positions.shape == (0, n + 1, 3)
    assert res.top_position.shape == (0, 3) and res.unit_position.shape == (0, 3)
    assert res.segment_tensions.shape == (0, n) and math.isnan(res.min_tension)
    assert res.slack == {"occurred": False, "first_time": None, "location": None,
                         "segment": None}
    assert res.diagnostics["start"]["statics_status"] == "infeasible"
    json.dumps(res.to_dict(full=True), allow_nan=False)


@pytest.mark.parametrize("name", MODELS)
def test_the_end_positions_are_the_top_path_and_the_unit_node(name: str) -> None:
    """``top_position`` is end_b's imposed path and ``unit_position`` end_a's node, for every
    model (``SimulationResult.from_nodes``): the drop scene's top goes down from z = 200 m by
    the series' linear offset, 0.6 m/s t (exact but for rounding: 1e-9 m); the unit hangs
    the 100 m line's length below it (within its stretch, < 0.2 m here: T / EA < 2e-3)."""
    from cable_ocp.scene.dynamics import dynamic_scene_from_dict

    res = simulate(dynamic_scene_from_dict(_drop_scene(name, duration=0.05)))
    assert res.t.size == 51
    top = np.column_stack([0 * res.t, 0 * res.t, 200.0 - 0.6 * res.t])
    np.testing.assert_allclose(res.top_position, top, rtol=0, atol=1e-9)
    assert np.array_equal(res.top_position, res.node_positions[:, -1, :])
    assert np.array_equal(res.unit_position, res.node_positions[:, 0, :])
    drop = res.top_position[:, 2] - res.unit_position[:, 2]
    assert np.all((drop > 100.0 - 1e-9) & (drop < 100.2))
