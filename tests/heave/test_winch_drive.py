"""The winch drive's torque and power (issue 24 item 7; Huang (1992),
004_7da4a1ee8042db40.txt, 6.5: "the speed, acceleration and torque of the winch"): the law, on
a run, and as limits of the MPC."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.heave import design_loop as sm
from cable_ocp.heave.closed_loop import make_wave, run_loop
from cable_ocp.heave.controllers import Controller
from cable_ocp.heave.loop_plants import ModelLine, WinchedLine
from cable_ocp.heave.mpc import LinearMPC, settings_from_scene
from cable_ocp.physics.winch_drive import drum_power, drum_torque, linearised_power
from cable_ocp.scene.heave import load_scene

ROOT = Path(__file__).resolve().parents[2]
PHC = ROOT / "problems" / "heave" / "ex_6_3_6_phc.toml"


def test_law_against_hand_values() -> None:
    # R = 0.5 m, T = 50 kN, J = 2e4 kg m^2, u'' = 0.2 m/s^2: 25 kN m + 2e4 0.2 / 0.5 = 33 kN m
    tau = drum_torque(50e3, 0.2, 0.5, 2.0e4)
    assert tau == pytest.approx(33000.0, rel=1e-15)
    # at u' = 0.3 m/s the drum turns at 0.6 rad/s: 19.8 kW; paying out, -19.8 kW
    assert drum_power(tau, 0.3, 0.5) == pytest.approx(19800.0, rel=1e-15)
    assert drum_power(tau, -0.3, 0.5) == pytest.approx(-19800.0, rel=1e-15)
    assert linearised_power(50e3, 0.3) == pytest.approx(15000.0, rel=1e-15)


@pytest.fixture(scope="module")
def run() -> tuple:
    sc = load_scene(PHC, {"simulation.duration": 40.0,
                          "controller.controllers": ["passive", "lqr", "phc+lqr"]})
    return sc, sm.compare(sc)


def test_torque_and_power_on_a_run(run: tuple) -> None:
    sc, res = run
    R, J = sc.winch.drum_radius, sc.winch.drum_inertia
    kc, t0 = sc.unit.mass / sc.unit.a, sc.unit.static_tension
    for name in ("lqr", "phc+lqr"):
        tr = res.traces[name]
        delta = tr.stroke_phc if tr.stroke_phc is not None else 0.0
        tension = t0 + kc * (tr.x0 + tr.u - delta - tr.x)
        # u'' by a central difference of the speed inside each control sample (the
        # first-order winch's speed jumps at the samples): sub-steps 1..3 of every sample
        i = np.arange(tr.t.size - 1)
        inner = i[(i % sc.simulation.substeps >= 1) & (i % sc.simulation.substeps <= 3)]
        dt = tr.t[1] - tr.t[0]
        acc = (tr.u_dot[inner + 1] - tr.u_dot[inner - 1]) / (2 * dt)
        # u' decays as exp(-K t) within a sample: the central difference is off by
        # (K dt)^2 / 6 = 1.7e-5 relative, and the inertia term with it; 2e-5 (plus rounding)
        assert np.allclose(tr.torque[inner] - R * tension[inner], J * acc / R, rtol=2e-5,
                           atol=1e-6), name
        assert np.allclose(tr.power[inner], tr.torque[inner] * tr.u_dot[inner] / R,
                           rtol=1e-14, atol=1e-9), name
    # the winch held still: torque R T, no power
    tp = res.traces["passive"]
    assert np.allclose(tp.torque, R * (t0 + kc * (tp.x0 - tp.x)), rtol=1e-12)
    assert np.all(tp.power == 0.0)
    m = res.metrics["lqr"]
    keep = res.traces["lqr"].t >= sc.simulation.warmup
    assert m.peak_torque == pytest.approx(np.max(np.abs(res.traces["lqr"].torque[keep])))
    assert m.peak_power > 0 and res.metrics["passive"].peak_power == 0.0


def _samples(tr: object, sc: object) -> np.ndarray:
    """The trace's indices at the control samples after the warm-up."""
    idx = np.arange(0, tr.t.size - 1, sc.simulation.substeps)
    return idx[tr.t[idx] >= sc.simulation.warmup]


@pytest.mark.parametrize("name", ["mpc", "phc+mpc"])
def test_mpc_keeps_the_torque_limit(name: str) -> None:
    limit = 30500.0  # N m: below the LQR's peak (31.4 kN m on this sea)
    sc = load_scene(PHC, {"simulation.duration": 60.0, "winch.torque_max": limit,
                          "controller.controllers": ["lqr", name]})
    res = sm.compare(sc)
    assert res.statuses[name] == "solved" and res.mpc_failures == 0
    assert res.metrics["lqr"].peak_torque > limit  # the limit binds
    tr = res.traces[name]
    k = _samples(tr, sc)
    # at the samples, where the QP imposes it on its prediction: 2.5e-7 relative seen
    # without the compensator (DAQP's tolerance), 1.0e-6 with it (the plant's gas spring is
    # nonlinear, the prediction linear): 1e-5
    assert np.max(np.abs(tr.torque[k])) <= limit * (1 + 1e-5)
    # between the samples the line's tension keeps moving: within 1 % (0.03 % seen)
    keep = tr.t >= sc.simulation.warmup
    assert np.max(np.abs(tr.torque[keep])) <= limit * 1.01
    assert not any("motor torque" in w for w in res.warnings if w.startswith(name + " "))


def test_linearised_power_limit_is_a_speed_limit() -> None:
    pmax = 6000.0  # W
    sc = load_scene(PHC, {"simulation.duration": 45.0, "winch.power_max": pmax,
                          "controller.controllers": ["mpc"]})
    res = sm.compare(sc)
    tr = res.traces["mpc"]
    k = _samples(tr, sc)
    # |T0 u'| <= P_max at the samples (the first-order winch's speed is largest there)
    assert np.max(np.abs(tr.u_dot[k])) <= pmax / sc.unit.static_tension * (1 + 1e-6)
    # the exact power exceeds it: the dynamic tension and the inertia the linearisation drops
    assert res.metrics["mpc"].peak_power > pmax


def test_ipopt_keeps_the_exact_power_on_its_plan() -> None:
    pmax = 2000.0
    sc = load_scene(PHC, {"winch.power_max": pmax, "controller.solver": "ipopt",
                          "controller.horizon": 8, "winch.delay": 0.0})
    models = sm.build_models(sc)
    mpc = LinearMPC(models.plant, 0.0, settings_from_scene(sc))
    z0 = np.zeros(mpc.nz)
    z0[0] = 0.3  # the unit 0.3 m up: the plan hauls out fast
    plan, ok = mpc._nlp.solve(z0, 0.0, np.zeros(mpc.N))
    assert ok
    R, t0 = sc.winch.drum_radius, sc.unit.static_tension
    z = z0.copy()
    powers = []
    for k in range(mpc.N):
        tz, tu, _, sz, su = mpc.drive_terms[k]
        tau = R * t0 + tz @ z + tu * plan[k]
        powers.append(tau * (sz @ z + su * plan[k]) / R)
        z = mpc.model.Ad @ z + mpc.model.Bd[:, 0] * plan[k]
    # IPOPT's tolerance 1e-10 on the constraint (W): 1e-6 relative is generous
    assert max(abs(p) for p in powers) <= pmax * (1 + 1e-6)
    assert max(abs(p) for p in powers) > 0.9 * pmax  # and it binds


def test_json_fields_and_scene_errors(tmp_path: Path) -> None:
    from cable_ocp.cli import main

    out = tmp_path / "r.json"
    rc = main(["heave", str(PHC), "--json", str(out), "--duration", "35", "--controllers",
               "passive", "phc", "--quiet"])
    assert rc == 0
    data = json.loads(out.read_text())["controllers"]
    assert data["phc"]["peak_torque"] > 0 and data["phc"]["max_stroke_phc"] > 0
    assert data["passive"]["max_stroke_phc"] is None
    with pytest.raises(CableOCPError, match="winch.torque_max: needs winch.drum_radius"):
        load_scene(ROOT / "problems" / "heave" / "ex_6_3_6.toml", {"winch.torque_max": 1e4})
    with pytest.raises(CableOCPError, match="winch.drum_radius"):
        load_scene(ROOT / "problems" / "heave" / "ex_6_3_6.toml", {"winch.drum_radius": 0.5,
                                                                  "unit.static_tension": 0.0})


class _Sine(Controller):
    """A command of 0.1 m at 0.8 rad/s (the winch moves, so the inertia term is not 0)."""

    name = "sine"

    def step(self, obs: object) -> float:  # noqa: ARG002
        self.k = getattr(self, "k", -1) + 1
        return 0.1 * np.sin(0.8 * 0.05 * self.k)


def test_line_plant_torque_uses_the_top_tension() -> None:
    # the plant of the cable comparison (WinchedLine), here with the design model as its line
    sc = load_scene(PHC, {"winch.delay": 0.0})
    h, m = sc.controller.sample_time, 5
    n = 400
    t = np.arange(n * m + 1) * (h / m)
    wave = make_wave(t, 0.2 * np.sin(0.6 * t), h, m, n, lambda tt: np.full_like(tt, 100.0),
                     5.0)
    un = sc.unit
    line = ModelLine(un.a, un.b, 0.0, False, m, h / m, un.mass, un.static_tension,
                     un.static_tension + 1.0e4)
    plant = WinchedLine(sc, line, wave, np.zeros((n + 1, 3)))
    tr = run_loop(plant, _Sine(), n, bound=1e3).trace
    R, J, K = sc.winch.drum_radius, sc.winch.drum_inertia, sc.winch.gain
    i = np.arange(1, n * m)
    # tau = R T_top + J (-K u') / R on the sub-step grid, exactly the law (rounding only)
    assert np.allclose(tr.torque[i], R * tr.tension_top[i] - J * K * tr.u_dot[i] / R,
                       rtol=1e-12, atol=1e-6)
    assert np.max(np.abs(tr.u_dot[i])) > 0.02  # the winch moves
    assert np.allclose(tr.power[i], tr.torque[i] * tr.u_dot[i] / R, rtol=1e-12, atol=1e-6)
