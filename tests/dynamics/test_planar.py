"""The planar model (Huang (1992) ch. 4) against closed forms and the other models.

References written here, independently of the code under test:

* the axial model (Huang ch. 3) for a purely vertical case, with pay-out and heave: the
  same lumped chain in space, the time discretisations differ at O(dt^2);
* the 3D lumped-mass model (Huang ch. 5) restricted to the x-z plane: the same discrete
  equations at fixed length, so the two agree to the Newton tolerance;
* transverse modes of a hanging cable with a tip mass (Bessel functions) and of a taut
  string (the exact discrete chain and the continuum string);
* the discrete energy (kinetic + strain + weight) of an undamped run in air;
* the statics solver (collocation) for the state damped runs settle to;
* the arrival of a tension-drop front at the unit (wave travel time L / c and the
  reflection from a heavy mass) for slack.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from closed_forms import hanging_cable_frequencies
from scipy.interpolate import CubicSpline
from scipy.optimize import brentq

from cable_ocp.dynamics import dynamic_scene_from_dict, load_dynamic_scene, modes, simulate
from cable_ocp.dynamics.planar import SLACK_SMOOTHING, PlanarModel
from cable_ocp.errors import CableOCPError

G = 9.81


def _air_wire(**sim) -> dict:
    """A 100 m steel wire with a 100 kg mass in air (no drag, no added mass)."""
    d = {"environment": {"water_depth": 200.0, "water_density": 1.225},
         "cable": {"length": 100.0, "diameter": 0.01, "weight_in_water": 0.0785 * G,
                   "axial_stiffness": 7.0e6, "mass_per_length": 0.0785,
                   "added_mass_coefficient": 0.0},
         "unit": {"mass": 100.0, "weight_in_water": 100.0 * G},
         "end_b": {"position": [0.0, 0.0, 150.0]},
         "simulation": {"model": "planar", "duration": 1.0, "time_step": 0.01,
                        "segments": 20}}
    d["simulation"].update(sim)
    return d


# --------------------------------------------------------------------------------------
# across models
# --------------------------------------------------------------------------------------
def test_vertical_case_equals_axial_model(problems) -> None:
    """A purely vertical planar case equals the axial model: Huang's 3.3.5 line lowered
    at 1 m/s (ramped over 10 s) while heaving 0.5 m at 1.26 rad/s, in water with the
    unit's drag. Both are the same lumped chain with the same pay-out terms; their
    midpoint rules take the prescribed top and length differently (increments over the
    step here, their values at t + dt/2 there), an O(dt^2) difference: the gaps in the
    unit's heave and in the top tension must be below 1e-4 of their ranges at
    dt = 0.05 s and fall by 3.5-4.5 when dt is halved (seen: 4.0). The cable's tangential
    drag is set to 0: it acts on the element's mean velocity here (as in ch. 5) and on
    the node's in the axial model, a spatial O(h^2) difference. The unit stays on the
    vertical (x = 0 to 1e-12 m)."""
    f = problems / "dynamics" / "huang_3_3_5.toml"
    base = {"simulation.duration": 30.0, "simulation.output_step": 0.5,
            "cable.tangential_drag": 0.0, "top_motion.payout_speed": 1.0,
            "top_motion.ramp_time": 10.0}
    gaps = []
    for dt in (0.05, 0.025):
        ov = {**base, "simulation.time_step": dt}
        a = simulate(f, overrides={**ov, "simulation.model": "planar"})
        b = simulate(f, overrides=ov)
        assert a.status == b.status == "solved", (a.message, b.message)
        assert np.abs(a.unit_position[:, 0]).max() < 1e-12
        np.testing.assert_allclose(a.length, b.length, rtol=1e-12)
        dz = np.abs(a.unit_position[:, 2] - b.unit_position[:, 2]).max() / np.ptp(
            b.unit_position[:, 2])
        dtt = np.abs(a.top_tension - b.top_tension).max() / np.ptp(b.top_tension)
        gaps.append((dz, dtt))
    gaps = np.array(gaps)
    assert np.all(gaps[0] < 1e-4), gaps
    ratio = gaps[0] / gaps[1]
    assert np.all((ratio > 3.5) & (ratio < 4.5)), ratio


def _inplane_scene_overrides() -> dict:
    """Huang's 5.7 line in a 0.5 m/s current along x, the top on Huang's 4.5.5 circle
    (1 m at 0.628 rad/s, ramped over one period), the unit's per-axis drag and added
    mass, material damping."""
    return {"top_motion.horizontal_amplitude": 0.0, "top_motion.heave_amplitude": 0.0,
            "top_motion.circular_radius": 1.0, "top_motion.circular_frequency": 0.628,
            "top_motion.ramp_time": 10.0, "environment.current.speed": 0.5,
            "cable.axial_damping": 1.0e5, "simulation.duration": 20.0,
            "simulation.time_step": 0.1, "simulation.output_step": 0.5}


def test_planar_case_equals_lumped3d(problems) -> None:
    """A planar case equals the 3D lumped-mass model on the same scene: at fixed length
    the two discretisations are the same discrete equations (chain, direction-dependent
    added mass, drag with current on the element chords, discrete-gradient midpoint
    step), solved to a Newton tolerance of 1e-10 of the force scale; the static starts are
    the same discrete equilibrium. Node positions agree to 1e-7 m (seen 1e-8 over a 2 m
    swing of the unit), tensions to 1e-8 relative, and the lumped model's y stays 0."""
    f = problems / "dynamics" / "huang_5_7.toml"
    ov = _inplane_scene_overrides()
    a = simulate(f, overrides={**ov, "simulation.model": "planar"})
    b = simulate(f, overrides=ov)
    assert a.status == b.status == "solved", (a.message, b.message)
    assert np.ptp(b.unit_position[:, 0]) > 0.1 and np.ptp(b.unit_position[:, 2]) > 0.5
    assert np.abs(b.node_positions[:, :, 1]).max() < 1e-9
    assert np.abs(a.node_positions - b.node_positions).max() < 1e-7
    assert np.abs(a.node_velocities - b.node_velocities).max() < 1e-7
    scale = b.segment_tensions.max()
    assert np.abs(a.segment_tensions - b.segment_tensions).max() < 1e-8 * scale
    assert np.abs(a.top_tension - b.top_tension).max() < 1e-8 * scale


def test_in_plane_modes_equal_lumped3d(problems) -> None:
    """The planar model's modes about the static state in current are the lumped-mass
    model's in-plane modes (those with no y-motion: its out-of-plane modes are left
    out), through :func:`cable_ocp.dynamics.modes`: the same K (tension and weight, drag
    left out) and M (direction-dependent added mass) of the same equilibrium, to 1e-9
    relative (seen 1e-11; the eigensolver on a stiffness ratio of about 1e8); shapes ascend, one row
    per node, the top row zero, max |component| 1."""
    f = problems / "dynamics" / "huang_5_7.toml"
    ov = {**_inplane_scene_overrides(), "simulation.segments": 10}
    a = modes(f, 12, overrides={**ov, "simulation.model": "planar"})
    b = modes(f, 40, overrides=ov)
    assert a.status == b.status == "solved"
    assert a.shapes.shape == (12, 11, 3)
    np.testing.assert_array_equal(a.shapes[:, -1, :], 0.0)
    np.testing.assert_array_equal(a.shapes[:, :, 1], 0.0)
    np.testing.assert_allclose(np.max(np.abs(a.shapes), axis=(1, 2)), 1.0)
    assert np.all(np.diff(a.frequencies) > 0)
    y_share = np.array([np.sum(s[:, 1] ** 2) / np.sum(s**2) for s in b.shapes])
    inplane = b.frequencies[y_share < 1e-9]
    np.testing.assert_allclose(a.frequencies, inplane[:12], rtol=1e-9)


# --------------------------------------------------------------------------------------
# modes: closed forms
# --------------------------------------------------------------------------------------
def _hanging_scene(n: int) -> dict:
    """Huang's 5.7 line (300 m, 3000 kg unit, both with added mass) in still water, EA
    raised to 1e11 N so that the stretch (< 4e-7) stays far below the discretisation
    error of the inextensible closed form."""
    rho, d, mu = 1025.0, 0.047, 5.4
    area = math.pi * d * d / 4.0
    return {"environment": {"water_depth": 1000.0, "water_density": rho},
            "cable": {"length": 300.0, "diameter": d, "weight_in_water": (mu - rho * area) * G,
                      "axial_stiffness": 1.0e11, "mass_per_length": mu},
            "unit": {"mass": 3000.0, "added_mass": 3000.0, "weight_in_water": 25870.4},
            "end_b": {"position": [0.0, 0.0, 1000.0]},
            "simulation": {"model": "planar", "duration": 1.0, "time_step": 0.1,
                           "segments": n}}


def test_hanging_cable_with_tip_mass_against_bessel() -> None:
    """Transverse (x) modes of a vertical hanging line with a tip mass in water against
    the Bessel closed form (mu_t = mu + normal added mass, M_t = M + M_a, weights in
    water). On a vertical line the x and z degrees of freedom decouple exactly in K and M,
    so the x-x blocks are solved alone (the axial stiffness EA / h = 1e10 N/m would
    otherwise set the condition number of the full problem and the rounding of the first
    mode). The lumped chain converges as O(1/N^2): the error falls by 3.5-4.5 from 20 to
    40 elements, and at 40 elements it is below 2.5e-3 on the first four modes (seen
    2e-5, 3e-4, 1.1e-3, 2.4e-3)."""
    from scipy.linalg import eigh

    rho, d, mu = 1025.0, 0.047, 5.4
    area = math.pi * d * d / 4.0
    exact = hanging_cable_frequencies(300.0, (mu - rho * area) * G, mu + rho * area,
                                      25870.4, 6000.0, 4)
    errs = []
    for n in (20, 40):
        m = PlanarModel(dynamic_scene_from_dict(_hanging_scene(n)))
        x0, info = m.initial_state()
        assert info["converged"]
        k, mm = m.matrices(x0[:2 * m.nf])
        assert np.abs(k[0::2, 1::2]).max() <= 1e-9 * np.abs(k[0::2, 0::2]).max()
        assert np.abs(mm[0::2, 1::2]).max() == 0.0
        lam = eigh(k[0::2, 0::2], mm[0::2, 0::2], eigvals_only=True, subset_by_index=[0, 3])
        errs.append(np.abs(np.sqrt(lam) / exact - 1.0))
    errs = np.array(errs)
    assert np.all(errs[-1] < 2.5e-3), errs
    ratio = errs[0] / errs[1]
    assert np.all((ratio > 3.5) & (ratio < 4.5)), ratio


def _taut_string(n: int) -> dict:
    """A weightless string (no weight, no drag, in air) anchored at both ends on a
    horizontal line, pre-tensioned to T = 100 N (EA = 1e6 N, L = 10 m, mu = 1 kg/m)."""
    length, ea, tension = 10.0, 1.0e6, 100.0
    return {"environment": {"water_depth": 100.0, "water_density": 1.225},
            "cable": {"length": length, "diameter": 0.01, "weight_in_water": 0.0,
                      "axial_stiffness": ea, "mass_per_length": 1.0,
                      "added_mass_coefficient": 0.0},
            "end_a": {"position": [0.0, 0.0, 50.0]},
            "end_b": {"position": [length * (1.0 + tension / ea), 0.0, 50.0]},
            "simulation": {"model": "planar", "duration": 1.0, "time_step": 0.01,
                           "segments": n}}


def test_taut_string_frequencies() -> None:
    """Small-amplitude modes of a taut string (both ends anchored, weightless):

    * the transverse (z) modes equal the exact discrete chain omega_k =
      2 sqrt(T / (m l_s)) sin(k pi / (2N)) (m = mu L / N the node mass, l_s the stretched
      spacing) and the axial (x) modes 2 sqrt(EA / (m l)) sin(k pi / (2N)), to 1e-8
      (the linearisation is exact for a straight chain; the smooth no-compression law
      adds delta^2 / (4 T) = 2.5e-7 N to T and changes its slope by 1e-13);
    * and they converge to the continuum string, omega_k = (k pi / L) sqrt(T / (mu (1 +
      e))) (per unstretched length), as O(1/N^2): 1 - sin(x)/x = x^2 / 6, x = k pi / 2N;
      the tolerance x^4 / 100 covers the next term (x^4 / 120).
    """
    length, ea, tension, mu = 10.0, 1.0e6, 100.0, 1.0
    eps = tension / ea
    for n in (20, 40):
        res = modes(dynamic_scene_from_dict(_taut_string(n)), 2 * (n - 1))
        assert res.status == "solved", res.message
        z_share = np.array([np.sum(s[:, 2] ** 2) / np.sum(s**2) for s in res.shapes])
        trans = res.frequencies[z_share > 1.0 - 1e-9]
        axial = res.frequencies[z_share < 1e-9]
        k = np.arange(1, n)
        node_m = mu * length / n
        ls = length * (1.0 + eps) / n
        t_model = tension + SLACK_SMOOTHING**2 / (4.0 * tension)
        np.testing.assert_allclose(
            trans, 2.0 * np.sqrt(t_model / (node_m * ls)) * np.sin(k * np.pi / (2 * n)),
            rtol=1e-8)
        np.testing.assert_allclose(
            axial[:3], 2.0 * np.sqrt(ea / (node_m * length / n))
            * np.sin(k[:3] * np.pi / (2 * n)), rtol=1e-8)
        continuum = k * np.pi / length * math.sqrt(tension / (mu * (1.0 + eps)))
        x = k[:3] * np.pi / (2 * n)
        np.testing.assert_allclose(trans[:3] / continuum[:3] - 1.0, -x**2 / 6.0,
                                   atol=x[-1] ** 4 / 100.0)


# --------------------------------------------------------------------------------------
# energy and rest
# --------------------------------------------------------------------------------------
def _energy(pos: np.ndarray, vel: np.ndarray, n: int) -> np.ndarray:
    """Kinetic + strain + weight energy of the lumped wire of :func:`_air_wire` (J),
    from the result's node positions and velocities, written independently: node masses
    mu h (half at the ends) plus the unit's 100 kg, strain energy h int_0^e T de of the
    smooth no-compression law T = (EA e + sqrt((EA e)^2 + delta^2)) / 2. ``pos`` and
    ``vel``: (n_t, N + 1, 2) node positions (x, z) and velocities."""
    length, mu, ea, big_m = 100.0, 0.0785, 7.0e6, 100.0
    h = length / n
    m = np.full(n + 1, mu * h)
    m[[0, -1]] *= 0.5
    m[0] += big_m
    wt = m * G  # in air: the weights are the masses' (no buoyancy counted)
    kin = 0.5 * (m * (vel**2).sum(2)).sum(1)
    e = np.linalg.norm(np.diff(pos, axis=1), axis=2) / h - 1.0
    u, dd = ea * e, SLACK_SMOOTHING
    phi = (ea * e**2 / 4.0 + (u * np.sqrt(u * u + dd * dd) + dd * dd * np.arcsinh(u / dd))
           / (4.0 * ea))
    return kin + h * phi.sum(1) + (wt * pos[:, :, 1]).sum(1)


def test_energy_conserved_in_air() -> None:
    """Undamped run in air (no drag, no added mass, top fixed), released from rest swung
    0.02 rad about the top (the unit 2 m sideways: a pendulum swing) and stretched 1 mm
    more at the unit: the discrete-gradient midpoint step conserves the total energy to
    1e-9 of the energy exchanged (the Newton tolerance 1e-10 of the force scale sets the
    floor; seen 1e-12), at 20 times the explicit axial limit sqrt(m h / EA). The energy
    exchanged is the initial potential energy above the static state."""
    n = 20
    h = 100.0 / n
    dt = round(20.0 * math.sqrt(0.0785 * h * h / 7.0e6), 4)
    sc = dynamic_scene_from_dict(_air_wire(duration=400 * dt, time_step=dt, segments=n))
    m = PlanarModel(sc)
    xs, info = m.initial_state()
    assert info["converged"]
    nf2 = 2 * m.nf
    # released state: rotate the static line about the top, stretch by 1 mm at the unit
    y = np.arange(n) / n
    q = xs[:nf2].reshape(-1, 2)
    depth = 100.0 * (1.0 - y) - q[:, 1]  # below the top
    th = 0.02
    q_new = np.column_stack([depth * math.sin(th), 100.0 * (1.0 - y) - depth * math.cos(th)
                             - 0.001 * (1.0 - y)])
    res = m.simulate(state=np.concatenate([q_new.ravel(), np.zeros(nf2)]))
    assert res.status == "solved", res.message
    e = _energy(res.node_positions[:, :, [0, 2]], res.node_velocities[:, :, [0, 2]], n)
    pos_static = np.asarray(m.output_function()(0.0, xs[:nf2], xs[nf2:])[0]).T[None]
    e_static = _energy(pos_static, np.zeros_like(pos_static), n)[0]
    swing = e[0] - e_static
    assert swing > 10.0  # J: the pendulum and the axial oscillation carry energy
    assert np.ptp(res.unit_position[:, 0]) > 0.1
    assert np.abs(e - e[0]).max() <= 1e-9 * swing


def test_damped_vertical_run_settles_to_the_statics_solution(problems) -> None:
    """Huang's 5.7 line in still water, started unstretched (Huang's 5.7.1 start) and
    damped by a material damping c = 5e6 N s and the unit's drag: after 120 s it rests at
    the statics solver's solution to 1e-6 of the length (every node; the lumped chain's
    statics of a vertical line is exact at the nodes: the tension is linear in s)."""
    from cable_ocp.statics.solver import solve

    f = problems / "dynamics" / "huang_5_7.toml"
    ov = {"top_motion.heave_amplitude": 0.0, "top_motion.horizontal_amplitude": 0.0,
          "simulation.start": "unstrained", "cable.axial_damping": 5.0e6,
          "simulation.duration": 120.0, "simulation.time_step": 0.1,
          "simulation.output_step": 1.0, "simulation.segments": 20,
          "simulation.model": "planar"}
    res = simulate(f, overrides=ov)
    assert res.status == "solved", res.message
    sol = solve(load_dynamic_scene(f, ov).statics)
    ref = CubicSpline(sol.s, sol.position, axis=0)(np.linspace(0.0, 300.0, 21))
    assert np.abs(res.node_positions[0] - ref).max() > 0.5  # the stretch, ~0.6 m
    assert np.abs(res.node_positions[-1] - ref).max() <= 1e-6 * 300.0


def test_damped_run_in_current_settles_to_the_statics_solution(problems) -> None:
    """Huang's 5.7 line released from its still-water static state into a 0.25 m/s
    current along x (the unit moves 2.7 m downstream): with material damping and the
    drag the run settles, after 200 s, to the statics solver's solution in the current
    (cable_ocp.statics.solver.solve of DynamicScene.statics, collocation error < 1e-9) to
    1e-6 of the length. The remaining gap is the chain's discretisation error: its
    equilibrium converges to the statics solution as O(1/N^2) (the gap falls by 3.5-4.5
    from 10 to 20 elements), 1.3e-4 m at the 32 elements of the run."""
    from cable_ocp.statics.solver import solve

    f = problems / "dynamics" / "huang_5_7.toml"
    still = {"top_motion.heave_amplitude": 0.0, "top_motion.horizontal_amplitude": 0.0,
             "cable.axial_damping": 5.0e6, "simulation.model": "planar"}
    n = 32
    ov = {**still, "environment.current.speed": 0.25, "simulation.segments": n,
          "simulation.duration": 200.0, "simulation.time_step": 0.5,
          "simulation.output_step": 10.0}
    sc = load_dynamic_scene(f, ov)
    x_still, _ = PlanarModel(load_dynamic_scene(f, {**still, "simulation.segments": n})
                             ).initial_state()
    res = PlanarModel(sc).simulate(state=x_still)
    assert res.status == "solved", res.message
    sol = solve(sc.statics)
    assert sol.status == "solved"
    ref = CubicSpline(sol.s, sol.position, axis=0)(np.linspace(0.0, 300.0, n + 1))
    assert np.abs(res.node_positions[0] - ref).max() > 2.0
    assert np.abs(res.node_positions[-1] - ref).max() <= 1e-6 * 300.0
    gaps = []
    for k in (10, 20):
        sck = load_dynamic_scene(f, {**ov, "simulation.segments": k})
        xk, info = PlanarModel(sck).initial_state()
        assert info["converged"]
        pos = np.asarray(PlanarModel(sck).output_function()(0.0, xk[:2 * k], xk[2 * k:])[0]).T
        refk = CubicSpline(sol.s, sol.position[:, [0, 2]], axis=0)(np.linspace(0, 300, k + 1))
        gaps.append(np.abs(pos - refk).max())
    assert 3.5 < gaps[0] / gaps[1] < 4.5, gaps


# --------------------------------------------------------------------------------------
# slack
# --------------------------------------------------------------------------------------
def _drop_scene(speed: float, **sim) -> dict:
    """A 100 m line (mu = 1 kg/m, EA = 1e6 N: c = sqrt(EA / mu) = 1000 m/s) with a 100 kg
    unit in air; the top starts moving down at ``speed`` at t = 0 (a velocity step)."""
    d = {"environment": {"water_depth": 500.0, "water_density": 1.225},
         "cable": {"length": 100.0, "diameter": 0.01, "weight_in_water": G,
                   "axial_stiffness": 1.0e6, "mass_per_length": 1.0,
                   "added_mass_coefficient": 0.0},
         "unit": {"mass": 100.0, "weight_in_water": 100.0 * G},
         "end_b": {"position": [0.0, 0.0, 200.0]},
         "top_motion": {"series": [[0.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, -speed]]},
         "simulation": {"model": "planar", "duration": 0.14, "time_step": 1e-3,
                        "output_step": 2e-3, "segments": 40}}
    d["simulation"].update(sim)
    return d


def test_slack_is_detected_where_and_when_the_wave_front_predicts() -> None:
    """The top jumps to a downward speed V: a tension drop mu c V runs down the line at
    c = 1000 m/s and reaches the unit at L / c = 0.1 s, where the heavy mass reflects it
    as from a fixed end (the drop doubles, then relaxes over M / (mu c) = 0.1 s). With
    mu c V = 600 N the line stays taut on the way (T >= 981 N before the drop) and the
    reflected drop 1200 N exceeds the unit's 981 N: slack first at the unit's element
    (index 0), at 0.1 s up to the front's spread over a few elements (the lumped chain
    smears a step front over ~N^(1/3) elements; the window is 0.1-0.11 s). With V = 0.4 m/s
    (drop 800 N < 981 N) nothing goes slack. on_slack = "stop" ends the history there;
    the result says what happened (status, message) and stays strict JSON."""
    res = simulate(dynamic_scene_from_dict(_drop_scene(0.6)))
    assert res.status == "slack"
    assert res.slack["occurred"] and res.slack["segment"] == 0
    assert 0.1 <= res.slack["first_time"] <= 0.11
    assert res.slack["location"] == pytest.approx(100.0 / 40 / 2)
    assert res.t[-1] == pytest.approx(0.14)
    assert "slack" in res.message and "continued" in res.message
    assert res.diagnostics["min_linear_tension_N"] < 0.0
    # before the front arrives every element is taut
    before = res.t < 0.099
    assert res.segment_tensions[before].min() > 200.0
    stop = simulate(dynamic_scene_from_dict(_drop_scene(0.6, on_slack="stop")))
    assert stop.status == "slack" and "stopped" in stop.message
    assert stop.slack["first_time"] == pytest.approx(res.slack["first_time"], abs=1e-12)
    assert stop.t[-1] <= stop.slack["first_time"] + 2e-3 + 1e-9
    json.dumps(stop.to_dict(full=True), allow_nan=False)
    calm = simulate(dynamic_scene_from_dict(_drop_scene(0.4)))
    assert calm.status == "solved" and not calm.slack["occurred"]
    assert calm.min_tension > 0.0


# --------------------------------------------------------------------------------------
# the scene
# --------------------------------------------------------------------------------------
@pytest.mark.parametrize("path,value,needle", [
    ("environment.current", {"speed": 0.5, "heading_deg": 45.0}, "environment.current"),
    ("top_motion", {"horizontal_amplitude": 1.0, "horizontal_frequency": 1.0,
                    "horizontal_heading_deg": 90.0}, "top_motion.horizontal_heading_deg"),
    ("top_motion", {"circular_radius": 1.0, "circular_frequency": 1.0,
                    "circular_heading_deg": 30.0}, "top_motion.circular_heading_deg"),
    ("top_motion", {"tow": {"speed": 1.0, "straight_length": 10.0, "turn_diameter": 50.0}},
     "top_motion.tow"),
    ("top_motion", {"series": [[0.0, 0, 0, 0], [1.0, 0, 1.0, 0]]}, "top_motion.series"),
    ("environment.seabed", {}, "environment.seabed"),
    ("unit", {"mass": 10.0, "weight_in_water": -5.0}, "unit.weight_in_water"),
])
def test_planar_rejects_what_leaves_the_plane(path: str, value, needle: str) -> None:
    d = _air_wire()
    node = d
    parts = path.split(".")
    for p in parts[:-1]:
        node = node[p]
    node[parts[-1]] = value
    if path == "environment.current":
        d["cable"].update(normal_drag=1.0, tangential_drag=0.0)
    with pytest.raises(CableOCPError, match=needle.replace(".", r"\.")):
        simulate(dynamic_scene_from_dict(d))


def test_progress_hook_and_output_contract(capfd) -> None:
    """A planar run in air with a horizontal top motion: the progress hook is called a
    bounded number of times, the library prints nothing, the JSON is strict, the unit
    swings in x and y stays on the plane."""
    d = _air_wire(duration=2.0, time_step=0.005, segments=6)
    d["top_motion"] = {"horizontal_amplitude": 0.5, "horizontal_frequency": 1.0,
                       "ramp_time": 1.0}
    calls = []
    res = simulate(dynamic_scene_from_dict(d), progress=lambda a, b: calls.append((a, b)))
    assert res.status == "solved" and res.model == "planar"
    assert 1 <= len(calls) <= 200 and calls[-1] == (400, 400)
    out = capfd.readouterr()
    assert out.out == "" and out.err == ""
    assert np.abs(res.unit_position[:, 1]).max() == 0.0
    assert np.abs(res.top_position[-1, 0] - 0.5 * math.sin(2.0)) < 1e-12
    dd = res.to_dict()
    json.dumps(dd, allow_nan=False)
    assert dd["slack"]["occurred"] is False


# --------------------------------------------------------------------------------------
# Huang's examples 4.5.3-4.5.5 (problems/dynamics/huang_4_5_*.toml)
# --------------------------------------------------------------------------------------
EA_453, W_453, W_UNIT = 1.25664e6, 47.853, 15000.0


def _rod_resonant_length(omega: float, ea: float, mu: float, tip: float) -> float:
    """Length (m) at which the first mode of a rod fixed at the top with a tip mass is
    omega: beta L tan(beta L) = mu L / M, omega = beta sqrt(EA / mu)."""
    def first(length: float) -> float:
        r = mu * length / tip
        bl = brentq(lambda b: b * math.tan(b) - r, 1e-12, math.pi / 2 - 1e-12)
        return bl / length * math.sqrt(ea / mu)

    return brentq(lambda length: first(length) - omega, 10.0, 5000.0)


def test_huang_4_5_5_static_elongation_and_resonant_length(problems) -> None:
    """4.5.5 subtracts the static elongation (L0 + v t) w2 / EA - g (m - rho A)
    (L0 + v t)^2 / (2 EA) from the unit's motion; the line's static elongation is
    W L / EA + w L^2 / (2 EA) (the cable's weight stretches it too): the static start
    matches the plus sign to 1e-9 m (the chain is exact at the nodes of a vertical line)
    and misses the printed one by w L^2 / EA = 1.52 m. The first axial mode of the planar
    model (modes at several lengths, the z-dominant mode) crosses the top motion's 1 rad/s
    at the rod-with-tip-mass length (310 m, the cable's own 5.2 kg/m counted) to 0.5 %
    (20 elements), not at Huang's 3.3.5 estimate EA / (omega^2 (M + M_a)) = 359 m."""
    f = problems / "dynamics" / "huang_4_5_5.toml"
    sc = load_dynamic_scene(f)
    m = PlanarModel(sc)
    x0, info = m.initial_state()
    assert info["converged"]
    z_unit = float(np.asarray(m.output_function()(0.0, x0[:2 * m.nf], x0[2 * m.nf:])[0])[1, 0])
    length = 200.0
    plus = (W_UNIT * length + 0.5 * W_453 * length**2) / EA_453
    minus = (W_UNIT * length - 0.5 * W_453 * length**2) / EA_453
    assert 1000.0 - length - z_unit == pytest.approx(plus, abs=1e-9)
    assert abs(1000.0 - length - z_unit - minus) > 1.5
    lengths = np.array([290.0, 300.0, 320.0, 330.0])
    axial = []
    for ell in lengths:
        res = modes(f, 6, overrides={"cable.length": float(ell),
                                     "top_motion.payout_speed": 0.0})
        z_share = np.array([np.sum(s[:, 2] ** 2) / np.sum(s**2) for s in res.shapes])
        axial.append(res.frequencies[np.argmax(z_share > 0.99)])
    l_res = float(np.interp(-1.0, -np.array(axial), lengths))
    exact = _rod_resonant_length(1.0, EA_453, 5.2, 3500.0)
    assert exact == pytest.approx(310.1, abs=0.1)
    assert l_res == pytest.approx(exact, rel=5e-3)
    assert EA_453 / 3500.0 > 1.15 * l_res  # Huang's estimate: 359 m


@pytest.mark.slow
def test_huang_4_5_5_trends(problems) -> None:
    """Lowering the 4.5.3 unit from 200 m on the 1 m circle at 1 rad/s (10 elements):
    "high launching speed will help to reduce the motion": the peak amplitude of the
    vertical dynamic part (the unit's height above its static-stretch position) is
    smaller at 3 m/s than at 1 m/s (seen 3.4 and 1.9 m at 20 elements); the drag at speed
    "tends to compress the cable": the mean dynamic part (the unit above its static
    position) grows with the speed (seen 0.42 and 1.34 m). The slow run peaks near the
    resonant length 310 m (within 15 %: the drag and the lowering shift it down)."""
    f = problems / "dynamics" / "huang_4_5_5.toml"
    out = {}
    for v in (1.0, 3.0):
        r = simulate(f, overrides={"top_motion.payout_speed": v, "simulation.segments": 10,
                                   "simulation.duration": round((200.0 / v + 10.0) / 0.25)
                                   * 0.25})
        assert r.status == "solved", r.message
        ell = r.length
        dz = r.unit_position[:, 2] - (1000.0 - ell - (W_UNIT * ell + 0.5 * W_453 * ell**2)
                                      / EA_453)
        per = int(round(2.0 * math.pi / 0.25))
        starts = range(0, dz.size - per, per)
        amp = np.array([np.ptp(dz[i:i + per]) / 2.0 for i in starts])
        mean = np.array([dz[i:i + per].mean() for i in starts])
        lp = np.array([ell[i + per // 2] for i in starts])
        out[v] = (amp.max(), lp[np.argmax(amp)], mean[lp > 250.0].mean())
    assert out[3.0][0] < 0.8 * out[1.0][0]
    assert out[3.0][2] > 2.0 * out[1.0][2] > 0.0
    assert out[1.0][1] == pytest.approx(310.0, rel=0.15)


@pytest.mark.slow
def test_huang_4_5_3_current_trends(problems) -> None:
    """4.5.3's steady dynamics in a current (10 elements, 150 s): as the current grows
    the unit's mean position moves away from the vertical through the top's mean
    position (x = 1 m) and rises (Figure 4.7's trends); its horizontal motion grows with
    the current (the static inclination couples the resonant vertical motion into it, as
    Huang's 4.3 perturbation analysis shows: with no stationary deflection the two
    decouple at first order), while the vertical amplitude (near the axial resonance,
    1 m at the top) changes by less than 5 %. The mean offset is larger than the static
    one (the statics solver's, the unit's drag at rest): the top's 1 m/s circle makes the
    upper cable's normal flow oscillate about the current, and the mean of a quadratic
    drag over a zero-mean oscillation exceeds the drag of the mean flow; the excess is
    large at 0.25 m/s (seen 2.9 m against 1.8 m) and small at 1 m/s (30.3 against 29.1 m).
    Figure 4.7 plots this dynamic mean, not the static offset."""
    from cable_ocp.dynamics.static import static_state

    f = problems / "dynamics" / "huang_4_5_3.toml"
    got = {}
    for u in (0.25, 1.0):
        ov = {"environment.current.speed": u, "simulation.segments": 10,
              "simulation.duration": 150.0}
        r = simulate(f, overrides=ov)
        assert r.status == "solved", r.message
        last = r.t >= r.t[-1] - 4.0 * math.pi
        p = r.unit_position[last]
        sol = static_state(load_dynamic_scene(f, ov))
        got[u] = (p[:, 0].mean() - 1.0, p[:, 2].mean(), np.ptp(p[:, 0]), np.ptp(p[:, 2]),
                  sol.position[0, 0])
    lo, hi = got[0.25], got[1.0]
    assert hi[0] > 4.0 * lo[0] > 0.0
    assert hi[1] > lo[1] + 1.0
    assert hi[2] > 2.0 * lo[2]
    assert hi[3] == pytest.approx(lo[3], rel=0.05)
    # the mean offset exceeds the static one: for a zero-mean oscillating flow u,
    # mean(|U + u| (U + u)) >= U^2 (the oscillation rectifies into extra mean drag),
    # and the excess shrinks as the current grows against the oscillation
    assert lo[0] > 1.2 * lo[4] and hi[0] > hi[4]
    assert hi[0] / hi[4] < lo[0] / lo[4]


@pytest.mark.slow
def test_huang_4_5_4_sway_falls_with_length(problems) -> None:
    """4.5.4: "the longer the cable is, the smaller the sway motion": lowered at 2 m/s
    with the top swaying 5 m at 0.628 rad/s (10 elements), the unit's sway amplitude per
    period falls with the length after the start transient: at every 50 m from 300 m to
    500 m, by 40 % over that range (seen 0.092 to 0.048 m)."""
    f = problems / "dynamics" / "huang_4_5_4.toml"
    r = simulate(f, overrides={"top_motion.payout_speed": 2.0, "simulation.segments": 10,
                               "simulation.duration": 160.0})
    assert r.status == "solved", r.message
    x, ell = r.unit_position[:, 0], r.length
    per = int(round(2.0 * math.pi / 0.628 / 0.25))
    starts = range(0, x.size - per, per)
    amp = np.array([np.ptp(x[i:i + per]) / 2.0 for i in starts])
    lp = np.array([ell[i + per // 2] for i in starts])
    at = [amp[np.argmin(np.abs(lp - target))] for target in (300.0, 350.0, 400.0, 450.0,
                                                             500.0)]
    assert all(b < a for a, b in zip(at, at[1:], strict=False)), at
    assert at[-1] < 0.6 * at[0], at


def test_anchored_catenary_start_and_payout() -> None:
    """An anchored line (end_a fixed) hanging as a catenary between points 283 m apart,
    300 m long, 100 N/m, EA = 1e8 N: near the anchor the tension is low (12 kN) and the
    curvature high, so the chords of the statics solution interpolated at the nodes are
    shorter than the elements (compressed, with no stiffness under the no-compression
    law): the start solves Hooke's law first and converges to the chain's equilibrium,
    whose distance from the statics solution is the chain's discretisation error, O(1/N^2)
    (falls by 3.5-4.5 from 20 to 40 elements). The run with heave and pay-out at the top
    is solved, the anchor stays put and the length grows as the law says."""
    d = {"environment": {"water_depth": 1000.0, "water_density": 1025.0},
         "cable": {"length": 300.0, "diameter": 0.05, "weight_in_water": 100.0,
                   "axial_stiffness": 1.0e8, "mass_per_length": 12.0, "normal_drag": 1.2,
                   "tangential_drag": 0.01},
         "end_a": {"position": [0.0, 0.0, 700.0]},
         "end_b": {"position": [200.0, 0.0, 900.0]},
         "top_motion": {"heave_amplitude": 1.0, "heave_frequency": 0.5,
                        "payout_speed": 0.5, "ramp_time": 10.0},
         "simulation": {"model": "planar", "duration": 20.0, "time_step": 0.05,
                        "output_step": 1.0, "segments": 20}}
    shifts = []
    for n in (20, 40):
        d["simulation"]["segments"] = n
        _, info = PlanarModel(dynamic_scene_from_dict(d)).initial_state()
        assert info["converged"], info
        shifts.append(info["max_node_shift_m"])
    assert 3.5 < shifts[0] / shifts[1] < 4.5, shifts
    d["simulation"]["segments"] = 20
    r = simulate(dynamic_scene_from_dict(d))
    assert r.status == "solved", r.message
    np.testing.assert_array_equal(r.unit_position, np.tile([0.0, 0.0, 700.0], (r.t.size, 1)))
    ramp = 10.0 * 0.5 * (2.5 - 3.0 + 1.0)  # the integral of the quintic ramp over 10 s
    assert r.length[-1] == pytest.approx(300.0 + 0.5 * (20.0 - 10.0) + ramp, rel=1e-12)


@pytest.mark.parametrize("model", ("planar", "lumped3d"))
def test_pendulum_and_spring_modes_use_the_units_added_mass_per_axis(model: str) -> None:
    """A light, stiff 10 m line with a 100 kg unit whose added mass differs per axis
    (M_ax = 50, M_ay = 0, M_az = 200 kg; Huang (1992) (4.11)-(4.12), (5.6)): the lowest
    modes are the pendulum swings omega^2 = W / (l (M + M_a,k)) along x (and y in 3D;
    l the stretched length L (1 + W / EA)) and the spring mode omega^2 = EA / (L (M +
    M_az)). Closed forms of a massless line; the line's mass (mu L / M = 1e-3) and
    weight (w L / W = 1e-3) shift them by a few 1e-4 (seen 1.4e-4, 8e-5, 6e-5), hence
    1e-3. Taking one axis's added mass for another moves them by 15-30 %."""
    mass, ma, ea, length, mu = 100.0, (50.0, 0.0, 200.0), 1.0e6, 10.0, 0.01
    big_w = mass * G
    d = {"environment": {"water_depth": 100.0, "water_density": 1.225},
         "cable": {"length": length, "diameter": 0.005, "weight_in_water": mu * G,
                   "axial_stiffness": ea, "mass_per_length": mu,
                   "added_mass_coefficient": 0.0, "normal_drag": 0.0,
                   "tangential_drag": 0.0},
         "unit": {"mass": mass, "added_mass": list(ma), "weight_in_water": big_w},
         "end_b": {"position": [0.0, 0.0, 50.0]},
         "simulation": {"model": model, "duration": 1.0, "time_step": 0.01,
                        "segments": 10}}
    ell = length * (1.0 + big_w / ea)
    pend = [math.sqrt(big_w / (ell * (mass + ma[k]))) for k in (0, 1)]
    spring = math.sqrt(ea / (length * (mass + ma[2])))
    expect = {"planar": [(pend[0], 0), (spring, 2)],
              "lumped3d": [(pend[0], 0), (pend[1], 1), (spring, 2)]}[model]
    res = modes(dynamic_scene_from_dict(d), len(expect))
    assert res.status == "solved", res.message
    for k, (omega, axis) in enumerate(expect):
        assert res.frequencies[k] == pytest.approx(omega, rel=1e-3), (k, res.frequencies)
        # the unit (node 0) moves along that axis
        assert abs(res.shapes[k, 0, axis]) == pytest.approx(1.0)
