"""Heave compensation on the cable: identification from the axial model (Huang (1992),
section 6.2.3) and the controllers in closed loop with the cable dynamics.

Independent references written here:

* the first axial natural frequency of a rod with a tip mass (no drag), from
  ``beta L tan(beta L) = mu L / M``, ``omega_1 = beta sqrt(EA / mu)`` (brentq);
* the axial model's own simulator (:meth:`AxialModel.simulate`, a CasADi Newton rootfinder,
  a prescribed motion as a function of time), against the stepped plant;
* SUNDIALS IDAS integrating the axial model's right-hand side with the recorded winch and
  boom-tip histories, against the cable's response inside the closed loop.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import casadi as ca
import numpy as np
import pytest
from heave_files import heave_with_line
from scipy.optimize import brentq

from cable_ocp.cli import main
from cable_ocp.dynamics import dynamic_scene_from_dict, simulate
from cable_ocp.dynamics.axial import AxialModel
from cable_ocp.errors import CableOCPError
from cable_ocp.heave import cable_compare as cc
from cable_ocp.heave.axial_plant import AxialCablePlant
from cable_ocp.heave.design import design_scene, design_table
from cable_ocp.heave.identify_cable import identify_line
from cable_ocp.scene.heave import load_cable_scene, load_scene, scene_from_dict

ROOT = Path(__file__).resolve().parents[2]
HEAVE = ROOT / "problems" / "heave"
G = 9.81


def rod_scene(ratio: float, segments: int = 20, **extra: dict) -> dict:
    """A rod of 100 m (mu = 1 kg/m, EA = 1e6 N) with a tip mass M = mu L / ratio, in air,
    no drag, no added mass: the rod with a tip mass of the closed form."""
    mass = 100.0 / ratio
    d = {"environment": {"water_depth": 500.0, "water_density": 1.225},
         "cable": {"length": 100.0, "weight_in_water": G, "axial_stiffness": 1.0e6,
                   "mass_per_length": 1.0, "added_mass_coefficient": 0.0},
         "unit": {"mass": mass, "weight_in_water": mass * G},
         "end_b": {"position": [0.0, 0.0, 200.0]},
         "simulation": {"model": "axial", "duration": 1.0, "time_step": 0.01,
                        "segments": segments}}
    for k, v in extra.items():
        d.setdefault(k, {}).update(v)
    return d


def omega_1(ratio: float) -> float:
    """Closed form: beta L tan(beta L) = mu L / M on the first branch, L = 100 m, c = 1000 m/s."""
    bl = brentq(lambda b: b * math.tan(b) - ratio, 1e-12, math.pi / 2 - 1e-12)
    return bl / 100.0 * math.sqrt(1.0e6 / 1.0)


# ------------------------------------------------------------------------------------------
# The stepped plant against the axial model's own simulator
# ------------------------------------------------------------------------------------------

def test_stepped_plant_equals_axial_simulator() -> None:
    """Top heave 0.05 m at 5 rad/s and a pay-out of 0.5 m/s (30 s^-1 ramp, 2 s) on the rod
    with an equal tip mass: the plant (two block-tridiagonal Newton iterations per midpoint
    step, the top and the length linear within a step) against AxialModel.simulate (Newton
    rootfinder to 1e-10, the exact motion at the midpoint). Both are the midpoint rule on
    the same grid, so they differ by the interpolation of the motion inside a step,
    O(dt^2 A w^2 / 8) ~ 1e-6 of the heave amplitude's scale (tolerance 1e-3 of the unit's
    range: an error in the Jacobian or the parameters would be of order 1)."""
    d = rod_scene(1.0, segments=20, top_motion={
        "heave_amplitude": 0.05, "heave_frequency": 5.0, "payout_speed": 0.5,
        "ramp_time": 1.0}, simulation={"duration": 2.0, "time_step": 0.005})
    sc = dynamic_scene_from_dict(d)
    ref = simulate(sc)
    plant = AxialCablePlant(sc, 0.05)
    m = plant.substeps
    motion = AxialModel(sc).motion
    tf = np.arange(int(round(2.0 / plant.dt)) + 1) * plant.dt
    L = np.array([float(motion(t)[0]) for t in tf])
    top = np.array([float(motion(t)[3][2]) for t in tf])
    out = plant.run_open_loop(L, top)
    z_ref = ref.unit_position[:, 2]
    assert ref.t.size == tf.size and m == 10
    rng_z = np.ptp(z_ref)
    assert np.max(np.abs(out["z_unit"] - z_ref)) < 1e-3 * rng_z
    assert out["residual"] < 1e-9


# ------------------------------------------------------------------------------------------
# Identification (6.2.3) on the rod with a tip mass
# ------------------------------------------------------------------------------------------

@pytest.mark.parametrize("ratio", [1.0, 0.1])
@pytest.mark.parametrize("noise", [0.0, 1e-3])
def test_identified_a_gives_first_axial_frequency(ratio: float, noise: float) -> None:
    """The multisine over [0.3, 2] omega_1 (0.01 m RMS, 30 s) moves the top of the rod; the
    fit of (6.2) gives 1 / sqrt(a) = omega_1 of the closed form to 1 % (the requirement; seen:
    0.01-0.06 %, the rest is the midpoint rule's (omega dt)^2 / 12 and the lumped mesh's
    (beta h)^2 / 24, both ~1e-4), without noise and with 1 mm of white noise on the recorded
    depth (10 % of the response's RMS). mu L / M = 1 is a heavy line (the low-frequency
    expansion of the rod would give a 11 % larger a: the fit follows the resonance), 0.1 a
    light one. The standard error of a must cover the noisy fit's distance from the clean
    one (4 sigma)."""
    sc = dynamic_scene_from_dict(rod_scene(ratio))
    w1 = omega_1(ratio)
    kw = dict(excitation="multisine", amplitude=0.01, band=(0.3 * w1, 2.0 * w1),
              duration=30.0, sample_time=0.05, seed=3)
    res = identify_line(sc, noise=noise, **kw)
    assert 1.0 / math.sqrt(res.linear.a) == pytest.approx(w1, rel=0.01)
    assert res.linear.converged
    assert abs(res.omega_1 / w1 - 1.0) < 1e-3  # modes() of the 20-element mesh
    if noise:
        clean = identify_line(sc, noise=0.0, **kw)
        assert abs(res.linear.a - clean.linear.a) < 4 * res.linear.std_errors[0]
        assert res.linear.fit_pct < clean.linear.fit_pct


def test_excitation_signals_have_the_asked_rms_and_band() -> None:
    """The multisine: RMS = amplitude after the fade-in, its harmonics inside the band."""
    from cable_ocp.heave.identify_cable import excitation_signal

    t = np.arange(0, 180.0 + 1e-9, 0.05)
    x = excitation_signal("multisine", t, 0.3, (0.4, 2.0))
    keep = t >= 10.0
    assert np.sqrt(np.mean(x[keep] ** 2)) == pytest.approx(0.3, rel=1e-12)
    spec = np.abs(np.fft.rfft(x[t >= 60.0 - 1e-9][:2400]))  # two whole periods (60 s)
    w = np.fft.rfftfreq(2400, 0.05) * 2 * np.pi
    strong = w[spec > 0.05 * spec.max()]
    assert strong.min() >= 0.4 - 1e-9 and strong.max() <= 2.0 + 1e-9
    with pytest.raises(CableOCPError, match="band"):
        excitation_signal("multisine", t, 0.3, (0.01, 0.02))


# ------------------------------------------------------------------------------------------
# Closed loop on the cable: the stiff, short line (CLI, JSON)
# ------------------------------------------------------------------------------------------

SHORT = ["--set", "simulation.duration=90.0", "--set", "identification.duration=60.0",
         "--set", "controller.controllers=[\"passive\", \"lqr\", \"mpc\"]"]


@pytest.fixture(scope="module")
def short_json(tmp_path_factory: pytest.TempPathFactory) -> dict:
    """ex_6_3_6_cable.toml (113 m, a = 0.90 s^2, second mode at 39 rad/s) shortened to 90 s
    (60 s after the warm-up) with a 10-element line and tight winch limits (speed 0.25 m/s,
    stroke 0.3 m: they bind), through the CLI."""
    tmp = tmp_path_factory.mktemp("cable")
    text = (ROOT / "problems" / "dynamics" / "line_6_3_6.toml").read_text()
    heave = heave_with_line(tmp, "ex_6_3_6_cable.toml",
                            text.replace("segments = 50", "segments = 10"))
    out = tmp / "out.json"
    rc = main(["heave", str(heave), "--json", str(out), "--quiet",
               "--set", "winch.speed_max=0.25", "--set", "winch.stroke_max=0.3", *SHORT])
    data = json.loads(out.read_text())
    data["_rc"] = rc
    return data


def test_cable_json_has_identification_and_prediction(short_json: dict) -> None:
    d = short_json
    # the passive unit resonates and takes the line slack: status slack, exit 1; the
    # controllers' lines do not go slack
    assert d["_rc"] == 1 and d["status"] == "slack" and d["plant"] == "cable"
    assert {k: v["status"] for k, v in d["controllers"].items()} == {
        "passive": "slack", "lqr": "solved", "mpc": "solved"}
    idf = d["identified"]
    for key in ("a", "b", "b_quadratic", "fit_pct", "excitation", "a_std", "b_std",
                "b_quadratic_std", "omega_1", "a_modal"):
        assert key in idf
    assert idf["excitation"] == "multisine"
    # a against the first axial mode of the same line: the 10-element mesh's omega_1 and the
    # identified a agree to 0.5 % (the drag's amplitude dependence is all that is left).
    assert idf["a"] == pytest.approx(idf["a_modal"], rel=5e-3)
    assert d["design_model"]["source"] == "identified"
    assert d["design_model"]["a"] == idf["a"]
    for name in ("passive", "lqr", "mpc"):
        m = d["controllers"][name]
        for key in ("reduction_predicted_pct", "heave_rms_predicted", "tension_unit_min",
                    "tension_unit_max", "tension_top_min", "tension_top_max",
                    "slack_samples"):
            assert key in m


def test_short_line_achieves_the_predicted_reduction(short_json: dict) -> None:
    """On the stiff, short line (6.2) is accurate: the reduction achieved on the cable equals
    the one the design model predicts (same estimator, sensors, noise and sea) to 2 percentage
    points (the requirement; seen: 0.1-0.4). Both runs see the same sea, so the difference is
    the model error, not sampling noise."""
    for name in ("lqr", "mpc"):
        m = short_json["controllers"][name]
        assert m["reduction_pct"] > 50.0
        assert abs(m["reduction_pct"] - m["reduction_predicted_pct"]) < 2.0


def test_mpc_keeps_its_hard_limits_on_the_cable(short_json: dict) -> None:
    """Stroke 0.3 m and speed 0.25 m/s bind (the LQR, which has no limits, exceeds them):
    the MPC's largest violation over the samples and sub-steps is zero (DAQP's primal
    tolerance 1e-10 m: 1e-9 relative). The winch is the same exact model in the plant and in
    the prediction, and its state is the estimator's exactly (no process noise on it)."""
    c = short_json["controllers"]
    assert c["lqr"]["max_constraint_violation"] > 0.05
    assert c["mpc"]["max_constraint_violation"] <= 1e-9
    assert c["mpc"]["max_stroke"] <= 0.3 + 1e-9
    assert c["mpc"]["peak_winch_speed"] <= 0.25 + 1e-9
    assert c["mpc"]["solver_failures"] == 0


# ------------------------------------------------------------------------------------------
# The long line near resonance: a regression pin, with the plant checked independently
# ------------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def long_run() -> tuple:
    """compare_6_2_6_cable.toml (900 m, omega_1 = 0.371 rad/s at the peak of the 6 m PM sea),
    10 elements, 90 s (60 s after the warm-up), LQR and the depth-only LQG, identification
    over 60 s."""
    sc = load_scene(HEAVE / "compare_6_2_6_cable.toml", {
        "simulation.duration": 90.0, "identification.duration": 60.0,
        "controller.controllers": ["passive", "lqr", "lqg"]})
    dyn = load_cable_scene(sc).with_overrides({"simulation.segments": 10})
    from cable_ocp.heave.identify_cable import identify_from_cable

    ident = identify_from_cable(sc, dyn)
    sd, _ = design_scene(sc, ident, dyn)
    res = cc._compare_on_cable(sc, sd, dyn, None, None, {})
    return sc, dyn, ident, res


def test_long_line_difference_regression(long_run: tuple) -> None:
    """REGRESSION PIN (values of this code, not of a source): on the 900 m line the LQR's
    heave on the cable is 1.07x the design model's prediction (the cable's second axial mode
    at 5.2 rad/s and its distributed mass, which (6.2) lacks; docs/heave.md). The plant
    behind it is checked independently in the next test."""
    _, _, ident, res = long_run
    m = res.metrics["lqr"]
    ratio = m.heave_rms / m.heave_rms_predicted
    assert ident.linear.a == pytest.approx(7.24, rel=0.01)  # 1/omega_1^2 = 7.26 (10 elements)
    assert ratio == pytest.approx(REGRESSION_LONG_RATIO, rel=0.02)
    assert m.reduction_pct == pytest.approx(REGRESSION_LONG_REDUCTION, abs=0.05)


def test_long_line_depth_only_lqg_fails_on_the_cable(long_run: tuple) -> None:
    """The status contract on the cable: the depth-only LQG, stable on the design model
    (its predicted run solved, a reduction predicted), diverges on the 900 m line (the
    cable's larger gain above omega_1; docs/heave.md) until a cable step fails. Its status is
    "failed" with the time of the failure, its cable metrics null (never NaN), and the other
    controllers keep theirs. (The time, 25.9 s here and 25.1 s with 50 elements, is a
    regression value; the test asks only that it comes after the 30 s warm-up's fade-in has
    begun and before the end.)"""
    _, _, _, res = long_run
    # the passive unit near resonance takes the line slack (docs/heave.md: 1806 samples in
    # 300 s): status slack, the first status that is not solved, so the top level's
    assert res.statuses == {"passive": "slack", "lqr": "solved", "lqg": "failed"}
    assert res.status == "slack" and "Newton step did not converge" in res.messages["lqg"]
    d = res.metrics["lqg"].as_dict()
    assert 5.0 < d["plant_failed_at_s"] < 90.0
    assert d["heave_rms"] is None and d["reduction_pct"] is None
    assert d["tension_unit_min"] is None and d["slack_samples"] is None
    assert d["reduction_predicted_pct"] > 90.0  # stable on (6.2)
    assert all(isinstance(v, (int, float)) for v in res.metrics["lqr"].as_dict().values()
               if v is not None)


#: REGRESSION values of the pin above (this code, 10 elements, 90 s, seed 2)
REGRESSION_LONG_RATIO = 1.0664
REGRESSION_LONG_REDUCTION = 99.607


def test_long_line_plant_replayed_by_idas(long_run: tuple) -> None:
    """Independent check of the plant in the loop: the recorded boom-tip and winch histories
    drive the axial model's right-hand side (written here with the top height and the length
    as states whose rates are held over each 0.01 s sub-step: the same piecewise-linear
    motion the plant takes), integrated by SUNDIALS IDAS (variable-order BDF, rtol 1e-9) over
    the first 40 s. Its unit heave equals the closed loop's to 2e-3 of the controlled heave's
    range (seen: 7e-4, i.e. 2e-5 m). That is the midpoint rule's error at 0.01 s: the unit
    moves by metres with the boom tip and the winch, the controlled heave is the centimetre
    left over, and (omega dt)^2 / 12 of the metres is 1e-5 m; the plant at 0.000625 s agrees
    with IDAS to 3e-6 of the range. (CVODES through CasADi restarts poorly at the 4000 rate
    steps and is off by as much as the plant: not used.)"""
    _, dyn, _, res = long_run
    tr = res.traces["lqr"]
    md = AxialModel(dyn)
    n2 = 2 * md.n
    xs = ca.SX.sym("x", n2 + 2)  # line, L - L_0, z_b - z_b0 (offsets: metres, not km)
    us = ca.SX.sym("u", 2)  # L_t, z_b'
    l0, z0 = dyn.length, md.z_top0
    md.motion = lambda t: (l0 + xs[n2], us[0], ca.SX(0.0), ca.vertcat(0.0, 0.0, z0 + xs[n2 + 1]),
                           ca.vertcat(0.0, 0.0, us[1]), ca.SX.zeros(3))
    rhs = ca.vertcat(md.rhs(ca.SX(0.0), xs[:n2]), us)
    k_end = int(round(40.0 / (tr.t[1] - tr.t[0])))
    tg = tr.t[: k_end + 1]
    lg = tr.length[: k_end + 1] - tr.u[: k_end + 1]
    zg = z0 + tr.x0[: k_end + 1]
    rates = np.vstack([np.diff(lg), np.diff(zg)]) / np.diff(tg)
    integ = ca.integrator("replay", "idas", {"x": xs, "u": us, "ode": rhs}, 0.0, tg[1:],
                          {"reltol": 1e-9, "abstol": 1e-10, "max_num_steps": 1000000})
    plant = AxialCablePlant(dyn, 0.05)
    xf = np.asarray(integ(x0=np.concatenate([plant.initial_state(), [lg[0] - l0, zg[0] - z0]]),
                          u=rates)["xf"])
    heave = np.concatenate([[tr.x[0]], xf[0] + zg[1:] - lg[1:] - plant.static_unit_height(
        tr.length[1: k_end + 1])])
    assert np.max(np.abs(heave - tr.x[: k_end + 1])) < 2e-3 * np.ptp(tr.x[: k_end + 1])


# ------------------------------------------------------------------------------------------
# Scene keys
# ------------------------------------------------------------------------------------------

@pytest.mark.parametrize("doc,match", [
    ({"simulation": {"plant": "cable"}}, 'simulation.plant = "cable": needs unit.cable_scene'),
    ({"simulation": {"plant": "rope"}}, "simulation.plant = 'rope'"),
    ({"unit": {"cable_scene": "no_such_file.toml"}}, "unit.cable_scene = .*not found"),
    ({"unit": {"cable_scene": "../berteaux_mooring.toml"}}, "unit.cable_scene = .*statics"),
    ({"controller": {"winch_noise": -0.01}}, "controller.winch_noise = -0.01"),
    ({"controller": {"measurement_noise": -0.01}}, "controller.measurement_noise = -0.01"),
    ({"identification": {"noise": -1.0}}, "identification.noise = -1.0: must be >= 0"),
    ({"unit": {"cable_scene": "huang_3_3_5.toml"}, "deployment": {"payout_speed": 1.0}},
     "final_length"),
    ({"unit": {"cable_scene": "line_6_3_6_planar.toml"},
      "deployment": {"final_length": 400.0, "payout_speed": 1.0}},
     r'simulation.model = "planar".*needs model = "axial" or "lumped3d"'),
    ({"identification": {"excitation": "impulse"}}, "excitation = 'impulse'"),
    ({"identification": {"band": [2.0, 1.0]}}, "increasing"),
    ({"controller": {"boom_tip_noise": 0.0}}, "boom_tip_noise"),
])
def test_bad_cable_keys_raise(doc: dict, match: str) -> None:
    doc = {"sea": {"modal_frequency": 0.7}, **doc}
    with pytest.raises(CableOCPError, match=match):
        scene_from_dict(doc, ROOT / "problems" / "dynamics")


def test_cable_scene_path_is_relative_to_the_heave_file() -> None:
    sc = load_scene(HEAVE / "ex_6_3_6_cable.toml")
    assert Path(sc.unit.cable_scene) == (ROOT / "problems" / "dynamics" / "line_6_3_6.toml")
    over = sc.with_overrides({"simulation.seed": 3})  # the resolved path survives overrides
    assert over.unit.cable_scene == sc.unit.cable_scene


def test_design_table_interpolates_linearly() -> None:
    """Gain scheduling: at the table's lengths the design is the tabulated one; between two
    lengths every entry is the linear interpolation (the state coordinates are the same
    physical states at every length, so entry-wise interpolation is meaningful)."""
    sc = load_scene(HEAVE / "ex_6_3_6.toml")
    sd = replace(sc, unit=replace(sc.unit, a=1.0, b=0.05))
    tab, _ = design_table(sd, np.array([100.0, 200.0]), np.array([1.0, 2.0]),
                             np.array([0.05, 0.08]))
    lo, hi, mid = tab.at(100.0), tab.at(200.0), tab.at(150.0)
    for k in range(5):
        assert np.array_equal(lo[k], [tab.Ad, tab.Bd, tab.G, tab.M3, tab.M1][k][0])
        np.testing.assert_allclose(mid[k], 0.5 * (lo[k] + hi[k]), rtol=1e-12, atol=1e-15)
    assert np.array_equal(tab.at(50.0)[2], lo[2])  # held outside the table


def test_cli_failed_controller_on_the_cable_exit_1(tmp_path: Path) -> None:
    """The output contract with a controller that fails on the cable (the depth-only LQG on
    the 900 m line, 10 elements, 40 s): exit 1, strict JSON with the top-level status
    "failed" and the controller's message, null metrics (no NaN), and the figure written."""
    text = (ROOT / "problems" / "dynamics" / "huang_6_2_6.toml").read_text()
    assert "segments = 50" in text
    heave = heave_with_line(tmp_path, "compare_6_2_6_cable.toml",
                            text.replace("segments = 50", "segments = 10"))
    out, fig = tmp_path / "out.json", tmp_path / "fig.png"
    rc = main(["heave", str(heave), "--json", str(out), "--plot", str(fig),
               "--quiet", "--duration", "40", "--set", "identification.duration=30",
               "--controllers", "passive", "lqg"])

    def strict(token: str) -> None:
        raise AssertionError(f"non-strict JSON token {token}")

    data = json.loads(out.read_text(), parse_constant=strict)
    assert rc == 1 and data["status"] == "failed"
    assert data["controllers"]["lqg"]["status"] == "failed"
    assert "lqg: failed:" in data["message"]
    assert data["controllers"]["lqg"]["heave_rms"] is None
    assert data["controllers"]["passive"]["status"] == "solved"
    assert fig.stat().st_size > 0
