"""Bending stiffness in the dynamic models (Huang (1992) 12.4.6; Bielański 003 eqs (4)-(7);
cable_ocp/physics/bending.py, cable_ocp/dynamics/bending_terms.py), against closed forms:

* the dispersion relation of a taut string with EI (a pinned beam under tension; Huang
  (1992) 12.4.6 after (12.31)), omega = k sqrt(T / mu + EI k^2 / mu), k = n pi / L, mu
  with the normal added mass,
  from the planar model's linearised modes;
* the natural frequencies of a clamped-free beam (a cantilever, no tension, in air),
  omega_n = (beta_n L)^2 sqrt(EI / (mu L^4)), beta_n L = 1.8751, 4.6941, 7.8548, 10.9955;
* the energy of an undamped run in air with EI (kinetic + strain + weight + bending);
* the 3D lumped-mass model's modes equal the planar model's for an in-plane line.
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest

from cable_ocp.dynamics import dynamic_scene_from_dict, modes
from cable_ocp.dynamics.planar import SLACK_SMOOTHING, PlanarModel
from cable_ocp.errors import CableOCPError

G = 9.81
#: beta_n L of a clamped-free beam (roots of cos x cosh x = -1)
BETA_L = np.array([1.8751040687, 4.6940911330, 7.8547574382, 10.9955407349])


def _taut(n: int, ei: float) -> dict:
    """A neutrally buoyant string in water (no weight, no drag, no current) anchored at
    both ends on a horizontal line, pre-tensioned to T = 100 N: L = 10 m, EA = 1e7 N
    (strain 1e-5), mu = 1 kg/m, d = 0.05 m, C_a = 1."""
    length, ea, tension = 10.0, 1.0e7, 100.0
    return {"environment": {"water_depth": 100.0, "water_density": 1025.0},
            "cable": {"segments": [{
                "length": length, "diameter": 0.05, "weight_in_water": 0.0,
                "axial_stiffness": ea, "mass_per_length": 1.0, "bending_stiffness": ei,
                "added_mass_coefficient": 1.0}]},
            "end_a": {"position": [0.0, 0.0, 50.0]},
            "end_b": {"position": [length * (1.0 + tension / ea), 0.0, 50.0]},
            "simulation": {"model": "planar", "duration": 1.0, "time_step": 0.01,
                           "segments": n}}


def _transverse(res, axis: int) -> np.ndarray:
    share = np.array([np.sum(s[:, axis] ** 2) / np.sum(s**2) for s in res.shapes])
    return res.frequencies[share > 1.0 - 1e-6]


def test_taut_string_with_bending_stiffness_dispersion() -> None:
    """Transverse modes of the taut string with EI = 20 N m^2 (EI k^2 / T from 0.02 to 1.6
    over the modes): omega_n = k sqrt(T / mu' + EI k^2 / mu'), mu' = mu + C_a rho pi d^2 / 4
    (the normal added mass the model puts on a transverse motion).

    The discrete chain has the same sine modes with k^2 replaced by lambda = (2 sin(kh/2)
    / h)^2 (tension: second difference; bending: its square), so the error is second
    order: omega / omega_exact - 1 = -(kh)^2 / 24 (T + 2 EI k^2) / (T + EI k^2) + O((kh)^4).
    Checked to (kh)^4 / 50 (the next term is about (kh)^4 / 200) plus 2e-5 (the strain
    1e-5 shifts T / mu per unstretched length); N = 40, modes 1..5 (errors 2.7e-4 .. 9e-3).
    """
    n, length, tension, ei, mu = 40, 10.0, 100.0, 20.0, 1.0
    res = modes(dynamic_scene_from_dict(_taut(n, ei)), 12)
    assert res.status == "solved", res.message
    omega = _transverse(res, 2)[:5]
    mu_t = mu + 1025.0 * math.pi * 0.05**2 / 4.0
    k = np.arange(1, 6) * math.pi / length
    exact = k * np.sqrt(tension / mu_t + ei * k**2 / mu_t)
    x = (k * length / n) ** 2
    err = omega / exact - 1.0
    pred = -x / 24.0 * (tension + 2.0 * ei * k**2) / (tension + ei * k**2)
    assert np.all(np.abs(err - pred) <= x**2 / 50.0 + 2e-5), (err, pred)
    assert 2e-4 < abs(err[0]) < 4e-4  # the O(h^2) error is there, and it is that size
    # without EI the same line is a string: the bending term is what moves the frequencies
    plain = _transverse(modes(dynamic_scene_from_dict(_taut(n, 0.0)), 12), 2)[:5]
    assert np.all(omega / plain - 1.0 > 0.005)


def _cantilever(n: int, **sim) -> dict:
    """A 10 m weightless beam in air (mu = 2 kg/m, EI = 5000 N m^2, EA = 1e7 N), clamped
    at end_b, free at end_a (a massless, weightless 'unit'), hanging straight down."""
    d = {"environment": {"water_depth": 100.0, "water_density": 1.225},
         "cable": {"segments": [{
             "length": 10.0, "diameter": 0.05, "weight_in_water": 0.0,
             "axial_stiffness": 1.0e7, "mass_per_length": 2.0, "bending_stiffness": 5000.0,
             "added_mass_coefficient": 0.0}]},
         "unit": {"mass": 0.0, "weight_in_water": 0.0},
         "end_b": {"position": [0.0, 0.0, 50.0]},
         "simulation": {"model": "planar", "duration": 1.0, "time_step": 0.01,
                        "segments": n, "start": "unstrained", "top_end": "clamped"}}
    d["simulation"].update(sim)
    return d


def test_cantilever_frequencies() -> None:
    """Clamped-free beam, no tension, in air: omega_n = (beta_n L)^2 sqrt(EI / mu) / L^2.

    Second order: N = 40 gives 5.3e-4 .. 9.7e-3 on modes 1-4 (the finite-difference beam
    with a mirror-image clamp, computed independently: -5.28e-4, -2.68e-3, -5.63e-3,
    -9.64e-3), and halving h divides the error by 4 (3.6 .. 4.4: the O(h^4) term). The
    smooth no-compression law leaves 0.005 N of tension: it raises omega_1 by
    T / (2 EI k_1^2) ~ 3e-6 (tolerance 2e-5). Without the clamp (pinned top) nothing
    holds the weightless line: the scene is refused.
    """
    exact = BETA_L**2 * math.sqrt(5000.0 / 2.0) / 100.0
    errs = {}
    for n in (20, 40):
        res = modes(dynamic_scene_from_dict(_cantilever(n)), 6)
        assert res.status == "solved", res.message
        errs[n] = _transverse(res, 0)[:4] / exact - 1.0
    np.testing.assert_allclose(errs[40], [-5.28e-4, -2.676e-3, -5.626e-3, -9.639e-3],
                               atol=2e-5)
    ratio = errs[20] / errs[40]
    assert np.all((ratio > 3.6) & (ratio < 4.4)), ratio
    with pytest.raises(CableOCPError, match="unit.weight_in_water"):
        PlanarModel(dynamic_scene_from_dict(_cantilever(40, top_end="pinned")))


def _air_beam(ei: float, **sim) -> dict:
    """A 100 m steel wire with EI and a 100 kg mass in air (no drag, no added mass)."""
    d = {"environment": {"water_depth": 200.0, "water_density": 1.225},
         "cable": {"segments": [{
             "length": 100.0, "diameter": 0.01, "weight_in_water": 0.0785 * G,
             "axial_stiffness": 7.0e6, "mass_per_length": 0.0785,
             "added_mass_coefficient": 0.0, "bending_stiffness": ei}]},
         "unit": {"mass": 100.0, "weight_in_water": 100.0 * G},
         "end_b": {"position": [0.0, 0.0, 150.0]},
         "simulation": {"model": "planar", "duration": 1.0, "time_step": 0.01,
                        "segments": 20}}
    d["simulation"].update(sim)
    return d


def _energy(pos: np.ndarray, vel: np.ndarray, n: int, ei: float, clamp=None) -> np.ndarray:
    """Kinetic + strain + weight + bending energy (J) of the wire of :func:`_air_beam`,
    written independently from node positions and velocities (n_t, N + 1, 2): lumped
    masses, strain energy h int_0^e T de of the smooth no-compression law, and the hinge
    energy EI / (2 h^3) |d_{j+1} - d_j|^2 (plus EI / h^3 |d_n|^2, d_n the top element's
    part normal to the clamp ``clamp``)."""
    length, mu, ea, big_m = 100.0, 0.0785, 7.0e6, 100.0
    h = length / n
    m = np.full(n + 1, mu * h)
    m[[0, -1]] *= 0.5
    m[0] += big_m
    kin = 0.5 * (m * (vel**2).sum(2)).sum(1)
    d = np.diff(pos, axis=1)
    e = np.linalg.norm(d, axis=2) / h - 1.0
    u, dd = ea * e, SLACK_SMOOTHING
    phi = (ea * e**2 / 4.0 + (u * np.sqrt(u * u + dd * dd) + dd * dd * np.arcsinh(u / dd))
           / (4.0 * ea))
    bend = ei / (2.0 * h**3) * (np.diff(d, axis=1) ** 2).sum((1, 2))
    if clamp is not None:
        top = d[:, -1, :]
        normal = top - (top @ clamp)[:, None] * clamp[None, :]
        bend = bend + ei / h**3 * (normal**2).sum(1)
    return kin + h * phi.sum(1) + (m * G * pos[:, :, 1]).sum(1) + bend


@pytest.mark.parametrize("top_end", ["pinned", "clamped"])
def test_energy_conserved_with_bending_in_air(top_end: str) -> None:
    """Undamped run in air, released from rest from the static line bent into half a sine
    wave (0.1 m at mid-length) and swung 0.005 rad: the midpoint step conserves kinetic +
    strain + weight + bending energy to 1e-9 of the energy exchanged (the bending forces
    are linear in the positions, so the midpoint force is their exact discrete gradient;
    the Newton tolerance sets the floor, seen ~1e-11), at 20 times the explicit axial
    limit. The bending energy takes part: it is over 1 % of the energy exchanged."""
    n, ei = 20, 1.0e5
    h = 100.0 / n
    dt = round(20.0 * math.sqrt(0.0785 * h * h / 7.0e6), 4)
    sc = dynamic_scene_from_dict(_air_beam(ei, duration=300 * dt, time_step=dt, segments=n,
                                           top_end=top_end))
    m = PlanarModel(sc)
    xs, info = m.initial_state()
    assert info["converged"]
    nf2 = 2 * m.nf
    y = np.arange(n) / n
    q = xs[:nf2].reshape(-1, 2)
    depth = 100.0 * (1.0 - y) - q[:, 1]
    th = 0.005
    q_new = np.column_stack([depth * math.sin(th) + 0.1 * np.sin(math.pi * y),
                             100.0 * (1.0 - y) - depth * math.cos(th)])
    res = m.simulate(state=np.concatenate([q_new.ravel(), np.zeros(nf2)]))
    assert res.status == "solved", res.message
    clamp = np.array([0.0, 1.0]) if top_end == "clamped" else None
    e = _energy(res.node_positions[:, :, [0, 2]], res.node_velocities[:, :, [0, 2]], n, ei,
                clamp)
    pos_static = np.asarray(m.output_function()(0.0, xs[:nf2], xs[nf2:])[0]).T[None]
    e_static = _energy(pos_static, np.zeros_like(pos_static), n, ei, clamp)[0]
    swing = e[0] - e_static
    pos0 = res.node_positions[:1][:, :, [0, 2]]
    bend0 = _energy(pos0, np.zeros_like(pos0), n, ei, clamp)[0] - _energy(
        pos0, np.zeros_like(pos0), n, 0.0)[0]
    assert swing > 1.0 and bend0 > 0.01 * swing, (swing, bend0)
    assert np.abs(e - e[0]).max() <= 1e-9 * swing


def test_planar_line_of_segments_equals_lumped3d() -> None:
    """Bielański's rope and object (problems/dynamics/bielanski_tow_speed_change.toml: two
    segments of different mass, weight, diameter and drag, EI on the object) in the planar
    model, whose elements take their segment's properties, against lumped3d on the same
    line: the same discrete equations, so the nodes agree to 1e-7 m over the 1800 m line
    (the Newton tolerance 1e-10 of a 52 kN force scale; seen 2.3e-8 m) during the
    slow-down (24 elements, 2 s steps, 40 s). A grid that puts the joint between nodes,
    or a pay-out, is refused, naming the key."""
    from pathlib import Path

    from cable_ocp.dynamics import load_dynamic_scene, simulate

    f = (Path(__file__).resolve().parents[2] / "problems" / "dynamics"
         / "bielanski_tow_speed_change.toml")
    ov = {"simulation.duration": 40.0, "simulation.time_step": 2.0,
          "simulation.output_step": 10.0, "simulation.segments": 24}
    runs = {m: simulate(load_dynamic_scene(f, {**ov, "simulation.model": m}))
            for m in ("planar", "lumped3d")}
    for r in runs.values():
        assert r.status == "solved", r.message
    diff = np.abs(runs["planar"].node_positions - runs["lumped3d"].node_positions).max()
    assert diff <= 1e-7, diff
    np.testing.assert_allclose(runs["planar"].top_tension, runs["lumped3d"].top_tension,
                               rtol=1e-8)
    assert runs["planar"].top_tension[0] - runs["planar"].top_tension[-1] > 2e4  # it slows
    with pytest.raises(CableOCPError, match="simulation.segments = 25"):
        PlanarModel(load_dynamic_scene(f, {**ov, "simulation.segments": 25}))
    with pytest.raises(CableOCPError, match="top_motion"):
        PlanarModel(load_dynamic_scene(f, {**ov, "top_motion.payout_speed": 0.5}))


def test_top_end_is_validated() -> None:
    """``simulation.top_end`` takes "pinned" or "clamped" only."""
    with pytest.raises(CableOCPError, match="top_end"):
        dynamic_scene_from_dict(_cantilever(4, top_end="welded"))


def test_lumped3d_modes_equal_planar_with_bending() -> None:
    """The 3D lumped-mass line with EI (the same hinge law through
    cable_ocp/dynamics/bending_terms.py) has the planar model's transverse frequencies,
    each twice (in the plane and out of it: a straight line has no preferred normal), to
    1e-8 (both linearise the same discrete equations; eigensolver rounding)."""
    d = _taut(40, 20.0)
    planar = _transverse(modes(dynamic_scene_from_dict(d), 12), 2)[:5]
    d["simulation"]["model"] = "lumped3d"
    res = modes(dynamic_scene_from_dict(d), 10)
    assert res.status == "solved", res.message
    pairs = res.frequencies[:10].reshape(5, 2)
    np.testing.assert_allclose(pairs[:, 0], planar, rtol=1e-8)
    np.testing.assert_allclose(pairs[:, 1], planar, rtol=1e-8)


def test_lumped3d_run_with_bending_equals_planar() -> None:
    """A driven run (the top swung 0.5 m at 3 rad/s) of the stiff wire of
    :func:`_air_beam` in the x-z plane: the lumped-mass model's compiled Newton step (with
    the hinges' constant Jacobian) follows the planar model's nodes to 1e-9 m (the same
    discrete equations at a fixed length; the Newton tolerance), while the line moves
    0.5 m; without EI the nodes differ by more than 1 mm (the bending is felt). Newton
    converges as Newton does (the matrix has the hinges' constant Jacobian)."""
    from cable_ocp.dynamics import simulate

    runs = {}
    for model in ("planar", "lumped3d"):
        for ei in (1.0e5, 0.0):
            d = _air_beam(ei, duration=0.5, time_step=0.005, segments=20)
            d["simulation"]["model"] = model
            d["top_motion"] = {"horizontal_amplitude": 0.5, "horizontal_frequency": 3.0}
            res = simulate(dynamic_scene_from_dict(d))
            assert res.status == "solved", res.message
            runs[model, ei] = res.node_positions
            if model == "lumped3d":
                # the hinges' Jacobian is in the Newton matrix: a near-linear step converges
                # in 2-3 iterations (seen 3.0 with EI, 2.0 without; 7 without the hinges'
                # diagonal blocks)
                assert res.diagnostics["mean_newton_iterations"] <= 4.0, res.diagnostics
    diff = np.abs(runs["planar", 1.0e5] - runs["lumped3d", 1.0e5]).max()
    assert diff <= 1e-9, diff
    assert np.abs(runs["planar", 1.0e5] - runs["planar", 0.0]).max() > 1e-3


def test_a_flexible_segment_meets_a_stiff_one_at_a_pin() -> None:
    """Where a stiff segment (EI = 1e3 N m^2) meets a flexible one, the hinge carries no
    moment (the statics' M = 0 there): bending the line at the joint node alone gives no
    force on any node, while the same kink one node into the stiff part gives the closed
    form of one hinge, EI / h^3 (d_{j+1} - d_j) at its ends (h = 1 m, a kink of 0.1 m)."""
    from cable_ocp.dynamics.bending_terms import LineBending

    d = _taut(10, 0.0)
    seg = dict(d["cable"]["segments"][0], length=5.0)
    d["cable"]["segments"] = [dict(seg, bending_stiffness=1.0e3), seg]
    bend = LineBending.from_scene(dynamic_scene_from_dict(d), np.ones(10))
    straight = np.vstack([np.ones(10), np.zeros(10)])  # 2 x 10 element vectors, h = 1 m
    at_joint = straight.copy()
    at_joint[1, 5:] = 0.1  # the flexible part (elements 5..9) turned at node 5, the joint
    f = np.asarray(bend.node_forces(ca.DM(at_joint)))
    assert np.abs(f).max() == 0.0, f
    inside = straight.copy()
    inside[1, 4:] = 0.1  # turned at node 4, inside the stiff part
    f = np.asarray(bend.node_forces(ca.DM(inside)))
    jump = inside[:, 4] - inside[:, 3]
    np.testing.assert_allclose(f[:, 3], -1.0e3 * jump, rtol=1e-12)
    np.testing.assert_allclose(f[:, 5], -1.0e3 * jump, rtol=1e-12)
    np.testing.assert_allclose(f[:, 4], 2.0e3 * jump, rtol=1e-12)
