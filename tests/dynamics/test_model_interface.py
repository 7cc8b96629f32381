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
    status and message. ``until_slack`` keeps the samples up to one output interval after
    the first slack time (relative margin 1e-9 against the grid's rounding)."""
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
    assert until_slack(t, 0.25, 0.1, "continue") is None
    assert until_slack(t, math.inf, 0.1, "stop") is None


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
