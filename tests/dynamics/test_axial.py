"""The axial model (Huang (1992) ch. 3) against closed forms and independent methods.

References written here, independently of the code under test:

* a uniform elastic rod (mass mu per length, stiffness EA, length L) fixed at the top and
  carrying a tip mass M: modes phi_n(s) = sin(beta_n (L - s)) (s from the tip) with
  beta_n L tan(beta_n L) = mu L / M, omega_n = beta_n sqrt(EA / mu), orthogonal with the
  weight mu ds + M delta(s); free vibration and the response to a prescribed top motion
  R(t) from rest by modal superposition (u = R + sum q_n phi_n, the quasi-static part of
  the top tension (M + mu L) R'' taken out of the series: the mode-acceleration method);
* the quasi-steady tension of a steady pay-out from (3.1)-(3.3) with u_tt = 0, and the
  exact material-point version (a rigid translation at v (1 + e_top));
* the statics solver (collocation) for the state a damped run settles to.

The lumped-mass finite differences converge as (beta h)^2 / 24 in frequency and the
schemes at second (gauss4: fourth) order in time; tolerances below say which error
dominates.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.integrate import cumulative_simpson, quad, solve_ivp
from scipy.optimize import brentq

from cable_ocp.dynamics import dynamic_scene_from_dict, modes, simulate
from cable_ocp.dynamics.axial import AxialModel, static_profile
from cable_ocp.errors import CableOCPError

G = 9.81
SCHEMES = ("midpoint", "gauss4", "trapezoidal", "bdf2", "thesis")


def rod_betas(ratio: float, count: int) -> np.ndarray:
    """beta_n L of beta L tan(beta L) = ratio (= mu L / M), one root per branch of tan."""
    return np.array([brentq(lambda b: b * math.tan(b) - ratio, k * math.pi + 1e-12,
                            k * math.pi + math.pi / 2 - 1e-12) for k in range(count)])


class TipRod:
    """Closed-form modes of a rod fixed at the top with a tip mass (see the module doc)."""

    def __init__(self, length: float, mu: float, ea: float, mass: float, count: int) -> None:
        self.L, self.mu, self.ea, self.m = length, mu, ea, mass
        self.bl = rod_betas(mu * length / mass, count)
        self.beta = self.bl / length
        self.omega = self.beta * math.sqrt(ea / mu)
        # generalised masses and participation of a uniform acceleration
        self.norm = (mu * (length / 2 - np.sin(2 * self.bl) / (4 * self.beta))
                     + mass * np.sin(self.bl) ** 2)
        self.part = mu / self.beta * (1 - np.cos(self.bl)) + mass * np.sin(self.bl)

    def free(self, d: callable, t: np.ndarray) -> np.ndarray:
        """Tip displacement for an initial displacement field d(s) at rest."""
        q0 = np.array([(quad(lambda s, b=b: self.mu * d(s) * math.sin(b * (self.L - s)), 0,
                             self.L, epsabs=1e-14, limit=200)[0]
                        + self.m * d(0.0) * math.sin(b * self.L)) / nn
                       for b, nn in zip(self.beta, self.norm, strict=True)])
        return (q0 * np.sin(self.bl)) @ np.cos(np.outer(self.omega, t))

    def forced(self, amp: float, w: float, tau: float, t: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray]:
        """(tip displacement, top tension change) for R(t) = r(t) A sin(w t) from rest,
        r the quintic ramp over tau (tau = 0: no ramp). Duhamel integrals by cumulative
        Simpson on a grid of 60 points per period of the highest mode (the ramp makes R
        twice differentiable)."""
        n_grid = max(20_001, int(60 * self.omega[-1] * t[-1] / (2 * math.pi)) + 1)
        tf = np.linspace(0.0, t[-1], n_grid)
        if tau > 0:
            x = np.clip(tf / tau, 0.0, 1.0)
            r0 = x**3 * (10 - 15 * x + 6 * x**2)
            r1 = 30 * x**2 * (1 - x) ** 2 / tau
            r2 = 60 * x * (1 - x) * (1 - 2 * x) / tau**2
        else:
            r0, r1, r2 = np.ones_like(tf), np.zeros_like(tf), np.zeros_like(tf)
        sw, cw = np.sin(w * tf), np.cos(w * tf)
        big_r = amp * r0 * sw
        r_dd = amp * (r2 * sw + 2 * r1 * w * cw - r0 * w**2 * sw)
        wn = self.omega
        gam = self.part / self.norm
        # q_n'' + w_n^2 q_n = -gam R'', q_n(0) = 0, q_n'(0) = -gam R'(0) (the line starts at
        # rest, u = R + w): q_n = -gam [R - w_n int_0^t R(s) sin(w_n (t - s)) ds]
        c = cumulative_simpson(big_r[:, None] * np.cos(np.outer(tf, wn)), x=tf, axis=0,
                               initial=0)
        s = cumulative_simpson(big_r[:, None] * np.sin(np.outer(tf, wn)), x=tf, axis=0,
                               initial=0)
        integral = np.sin(np.outer(tf, wn)) * c - np.cos(np.outer(tf, wn)) * s
        q = -gam * (big_r[:, None] - wn * integral)  # (the R'(0) terms cancel)
        tip = big_r + q @ np.sin(self.bl)
        q_dyn = q + gam * r_dd[:, None] / wn**2  # minus the quasi-static part
        top = (self.m + self.mu * self.L) * r_dd + self.ea * (q_dyn @ (-self.beta))
        return np.interp(t, tf, tip), np.interp(t, tf, top)


_REFERENCE: dict[tuple, tuple[np.ndarray, np.ndarray]] = {}

# a rod with a tip mass of the same mass (mu L / M = 1): beta_1 L = 0.860, 3.426, 6.437
L0, MU, EA, MASS = 100.0, 1.0, 1.0e6, 100.0


def air_scene(**sim) -> dict:
    """The rod in air: no drag, no added mass (zero values are valid)."""
    d = {"environment": {"water_depth": 500.0, "water_density": 1.225},
         "cable": {"length": L0, "weight_in_water": MU * G, "axial_stiffness": EA,
                   "mass_per_length": MU, "added_mass_coefficient": 0.0},
         "unit": {"mass": MASS, "weight_in_water": MASS * G},
         "end_b": {"position": [0.0, 0.0, 200.0]},
         "simulation": {"model": "axial", "duration": 1.0, "time_step": 0.01}}
    d["simulation"].update(sim)
    return d


def test_closed_form_limits() -> None:
    """The frequency equation itself: a heavy tip tends to the spring-mass
    omega^2 = EA / (L (M + mu L / 3)) (Rayleigh), a light tip to the fixed-free rod
    beta L = (2n - 1) pi / 2."""
    heavy = TipRod(100.0, 1.0, 1e6, 1e5, 1)  # mu L / M = 1e-3
    w_rayleigh = math.sqrt(1e6 / (100.0 * (1e5 + 100.0 / 3)))
    assert heavy.omega[0] == pytest.approx(w_rayleigh, rel=1e-6)  # error O(ratio^2)
    light = TipRod(100.0, 1.0, 1e6, 1e-6, 3)  # mu L / M = 1e8
    np.testing.assert_allclose(light.bl, (2 * np.arange(3) + 1) * math.pi / 2, rtol=1e-7)


def test_modes_match_the_frequency_equation() -> None:
    """modes() of the axial model: first 3 frequencies to 1e-3 (80 elements: the lumped
    mass error (beta h)^2 / 24 is 2.7e-4 for the third mode), shapes to 1e-3."""
    s = dynamic_scene_from_dict(air_scene(segments=80))
    res = modes(s, 3)
    rod = TipRod(L0, MU, EA, MASS, 3)
    np.testing.assert_allclose(res.frequencies, rod.omega, rtol=1e-3)
    np.testing.assert_allclose(res.periods, 2 * np.pi / rod.omega, rtol=1e-3)
    sn = np.linspace(0.0, L0, 81)
    for k in range(3):
        exact = np.sin(rod.beta[k] * (L0 - sn))
        exact /= exact[np.argmax(np.abs(exact))]
        np.testing.assert_allclose(res.shapes[k, :, 2], exact, atol=1e-3)
        assert np.all(res.shapes[k, :, :2] == 0.0)
    d = res.to_dict()
    json.dumps(d, allow_nan=False)
    assert d["modes"][0]["frequency_rad_s"] == pytest.approx(rod.omega[0], rel=1e-3)
    assert len(d["modes"][0]["shape"]) == 81


def test_modes_in_water_carry_the_added_masses() -> None:
    """In water the axial line moves with its tangential added mass m_at = C_at rho pi d^2/4
    per length and the unit with its heave added mass M_a (Huang (1992) (3.1)-(3.2)): the
    frequencies are the tip-rod's with mu + m_at and M + M_a (frequency equation above),
    to 1e-3 as the in-air test (80 elements: lumped-mass error (beta h)^2 / 24 below
    3e-4 for the third mode). The added masses are chosen large (m_at = mu/2, M_a = M) so
    that leaving either out moves omega_1 by far more than that (by 7 % and 25 %)."""
    rho, diam, cat = 1025.0, 0.05, 0.5
    m_at = cat * rho * math.pi * diam**2 / 4.0  # 1.006 kg/m, written here from its definition
    d = air_scene(segments=80)
    d["environment"]["water_density"] = rho
    d["cable"].update(diameter=diam, tangential_added_mass_coefficient=cat,
                      normal_drag=0.0, tangential_drag=0.0)
    d["unit"]["added_mass"] = [0.0, 0.0, MASS]
    res = modes(dynamic_scene_from_dict(d), 3)
    assert res.status == "solved", res.message
    rod = TipRod(L0, MU + m_at, EA, 2.0 * MASS, 3)
    np.testing.assert_allclose(res.frequencies, rod.omega, rtol=1e-3)


@pytest.mark.parametrize("scheme", SCHEMES)
def test_free_vibration_and_natural_frequency(scheme: str) -> None:
    """Released unstretched at rest (start = "unstrained"), the tip oscillates about the
    static state as the modal superposition of the rod; to 1e-3 of the static elongation
    over 3 s (four first-mode periods). The zero-crossing frequency matches omega_1 to
    1e-3 (mu L / M = 0.1: mode 2 carries 0.01 % of the motion, which would otherwise
    shift the crossings)."""
    mass = 1000.0  # mu L / M = 0.1
    d = air_scene(duration=3.0, time_step=0.00125, segments=80, start="unstrained",
                  scheme=scheme)
    d["unit"] = {"mass": mass, "weight_in_water": mass * G}
    res = simulate(dynamic_scene_from_dict(d))
    # the swing equals the static elongation: the tension returns to 0 at the top of each
    # swing, so the run may report slack there (correctly); the motion is still linear
    assert res.status in ("solved", "slack"), res.message
    w, big_w = MU * G, mass * G

    def d0(s: float) -> float:
        return (big_w * (L0 - s) + w * (L0**2 - s**2) / 2) / EA

    rod = TipRod(L0, MU, EA, mass, 20)
    z_static = 200.0 - L0 - d0(0.0)
    u = res.unit_position[:, 2] - z_static
    ref = rod.free(d0, res.t)
    # thesis: its three-level stencil for u_tt has twice the phase error of the others
    tol = 3e-3 if scheme == "thesis" else 1e-3
    assert np.max(np.abs(u - ref)) <= tol * d0(0.0)
    zc = np.where(np.diff(np.sign(u)) != 0)[0]
    tc = res.t[zc] - u[zc] * (res.t[zc + 1] - res.t[zc]) / (u[zc + 1] - u[zc])
    omega = math.pi * (len(tc) - 1) / (tc[-1] - tc[0])
    assert omega == pytest.approx(rod.omega[0], rel=1e-3)


@pytest.mark.parametrize("scheme", SCHEMES)
def test_undamped_response_to_top_heave(scheme: str) -> None:
    """Top heave r(t) A sin(w t) from rest (1 s quintic ramp), no damping: tip motion and
    top tension against the modal superposition, to 1e-3 of their largest values
    (80 elements, dt = 1.25 ms: observed 1e-4..6e-4, second order in both)."""
    amp, w, tau = 0.05, 5.0, 1.0  # the tension stays > 0 (no slack)
    d = air_scene(duration=2.5, time_step=0.00125, segments=80, scheme=scheme)
    d["top_motion"] = {"heave_amplitude": amp, "heave_frequency": w, "ramp_time": tau}
    res = simulate(dynamic_scene_from_dict(d))
    assert res.status == "solved", res.message
    # 30 modes: the series (quasi-static part taken out) changes by 3e-7 from 30 to 60
    key = ("ramped", res.t.size, float(res.t[-1]))
    if key not in _REFERENCE:  # the same for every scheme: computed once
        _REFERENCE[key] = TipRod(L0, MU, EA, MASS, 30).forced(amp, w, tau, res.t)
    tip, top = _REFERENCE[key]
    du = res.unit_position[:, 2] - res.unit_position[0, 2]
    dt_ = res.top_tension - res.top_tension[0]
    assert np.max(np.abs(du - tip)) <= 1e-3 * np.max(np.abs(tip))
    assert np.max(np.abs(dt_ - top)) <= 1e-3 * np.max(np.abs(top))
    # the top follows the prescribed motion exactly
    x = np.clip(res.t / tau, 0, 1)
    np.testing.assert_allclose(res.top_position[:, 2] - 200.0,
                               x**3 * (10 - 15 * x + 6 * x**2) * amp * np.sin(w * res.t),
                               atol=1e-12)


@pytest.mark.parametrize("scheme", ("midpoint", "gauss4", "trapezoidal"))
def test_undamped_response_impulsive_start(scheme: str) -> None:
    """z_b = z_b(0) + A sin(w t) at once (the top jumps to speed A w): the tip motion
    against the modal superposition to 1e-3. Only the tip: the top tension carries the
    step front of the jump, which no finite grid resolves. The non-dissipative schemes
    only (the dissipative ones smear the front at first order)."""
    amp, w = 0.05, 5.0
    d = air_scene(duration=2.5, time_step=0.00125, segments=80, scheme=scheme)
    d["top_motion"] = {"heave_amplitude": amp, "heave_frequency": w}
    res = simulate(dynamic_scene_from_dict(d))
    rod = TipRod(L0, MU, EA, MASS, 200)
    # closed form of the Duhamel integral for R = A sin(w t):
    # q_n = gam_n A w (w sin(w t) - w_n sin(w_n t)) / (w_n^2 - w^2)
    gam = rod.part / rod.norm
    wn = rod.omega
    q = (gam * amp * w / (wn**2 - w**2)) * (w * np.sin(np.outer(res.t, np.ones_like(wn)) * w)
                                             - wn * np.sin(np.outer(res.t, wn)))
    tip = amp * np.sin(w * res.t) + q @ np.sin(rod.bl)
    du = res.unit_position[:, 2] - res.unit_position[0, 2]
    assert np.max(np.abs(du - tip)) <= 1e-3 * np.max(np.abs(tip))


def test_duhamel_reference_against_its_closed_form() -> None:
    """The numerical Duhamel integrals of TipRod.forced (used with the ramp) against the
    closed form for R = A sin(w t) (no ramp), 20 modes: to 1e-7 of the tip amplitude
    (cumulative Simpson)."""
    amp, w = 0.05, 5.0
    rod = TipRod(L0, MU, EA, MASS, 20)
    t = np.linspace(0.0, 1.0, 101)
    tip, _ = rod.forced(amp, w, 0.0, t)
    gam, wn = rod.part / rod.norm, rod.omega
    q = (gam * amp * w / (wn**2 - w**2)) * (w * np.sin(np.outer(t, np.ones_like(wn)) * w)
                                             - wn * np.sin(np.outer(t, wn)))
    exact = amp * np.sin(w * t) + q @ np.sin(rod.bl)
    assert np.max(np.abs(tip - exact)) <= 1e-7 * np.max(np.abs(exact))


def _energy(res, model: AxialModel) -> np.ndarray:
    """Kinetic + elastic + gravity energy of the lumped system (top node fixed), J."""
    n = model.n
    h = model.length0 / n
    m = np.full(n, model.mu * h)
    m[0] += model.unit_mass - 0.5 * model.mu * h
    wt = np.full(n, model.w * h)
    wt[0] = model.unit_weight + 0.5 * model.w * h
    z = res.node_positions[:, :, 2]
    v = res.node_velocities[:, :n, 2]
    eps = np.diff(z, axis=1) / h - 1.0
    return (0.5 * (m * v**2).sum(1) + 0.5 * model.ea * h * (eps**2).sum(1)
            + (wt * z[:, :n]).sum(1))


@pytest.mark.parametrize("scheme", ("midpoint", "gauss4", "trapezoidal"))
def test_energy_is_conserved_in_air(scheme: str) -> None:
    """Undamped, no drag, top fixed, released unstretched: the energy of the discrete
    system is a quadratic invariant, kept by these symmetric schemes to the Newton
    tolerance; 2000 steps of 0.01 s with the highest mode at omega dt = 4 (unresolved:
    the schemes are A-stable). Observed drift 1e-12 of the kinetic energy swing (112 J),
    1e-16 of the total; tolerance 1e-9."""
    d = air_scene(duration=20.0, time_step=0.01, segments=20, start="unstrained",
                  scheme=scheme)
    s = dynamic_scene_from_dict(d)
    res = simulate(s)
    model = AxialModel(s)
    e = _energy(res, model)
    n = model.n
    h = model.length0 / n
    m = np.full(n, model.mu * h)
    m[0] += model.unit_mass - 0.5 * model.mu * h
    kinetic = 0.5 * (m * res.node_velocities[:, :n, 2] ** 2).sum(1)
    assert kinetic.max() > 100.0  # J: the line really swings (112 J)
    assert np.max(np.abs(e - e[0])) <= 1e-9 * kinetic.max()


@pytest.mark.parametrize("scheme,char", [
    ("bdf2", lambda wh: [1 - 2j / 3 * wh, -4 / 3, 1 / 3]),
    ("thesis", lambda wh: [2 + wh**2, -5, 4, -1]),
])
def test_dissipative_schemes_decay_at_their_predicted_rate(scheme: str, char) -> None:
    """A heavy tip (mu L / M = 0.01: a single mode) oscillating freely: the amplitude
    decays by the modulus of the principal root of the scheme's characteristic
    polynomial for u'' = -omega^2 u (bdf2 on the first-order system; Huang's
    three-level stencil (2 U^(j+1) - 5 U^j + 4 U^(j-1) - U^(j-2)) / dt^2 on the
    second-order one) at omega_1 dt = 0.2; the decay exponent to 2 %."""
    mass = 1e4  # mu L / M = 0.01
    rod = TipRod(L0, MU, EA, mass, 1)
    dt = 0.2 / rod.omega[0]
    periods = 25
    steps = int(periods * 2 * math.pi / rod.omega[0] / dt)
    d = air_scene(duration=steps * dt, time_step=dt, segments=4, start="unstrained",
                  scheme=scheme)
    d["unit"] = {"mass": mass, "weight_in_water": mass * G}
    res = simulate(dynamic_scene_from_dict(d))
    z_static = static_profile(dynamic_scene_from_dict(d), np.array([0.0]))[0][0]
    u = res.unit_position[:, 2] - z_static
    peaks = [i for i in range(1, len(u) - 1) if u[i] >= u[i - 1] and u[i] > u[i + 1]]
    tp, up = res.t[peaks], u[peaks]
    rate = -np.polyfit(tp[2:], np.log(up[2:]), 1)[0]
    root = max(abs(np.roots(char(rod.omega[0] * dt))))
    expected = -math.log(root) / dt
    assert expected > 0
    assert rate == pytest.approx(expected, rel=2e-2)


def _payout_scene(scheme: str, ramp: float) -> dict:
    return {"environment": {"water_depth": 2000.0, "water_density": 1025.0},
            "cable": {"length": 100.0, "diameter": 0.03, "weight_in_water": 50.0,
                      "axial_stiffness": 1.0e8, "tangential_drag": 0.1,
                      "mass_per_length": 6.0},
            "unit": {"mass": 600.0, "added_mass": 200.0, "weight_in_water": 5000.0,
                     "drag_area": 4.0, "drag_coefficient": 1.0},
            "end_b": {"position": [0.0, 0.0, 2000.0]},
            "top_motion": {"payout_speed": 1.0, "ramp_time": ramp},
            "simulation": {"model": "axial", "duration": 40.0, "time_step": 0.01,
                           "output_step": 0.5, "segments": 20, "scheme": scheme}}


def test_first_sample_of_an_abrupt_start_is_the_static_state() -> None:
    """Pay-out and heave switched on at full speed at t = 0 (no ramp) on a damped line
    (c = 2e4 N s): the sample at t = 0 is the initial state, the static line at rest, whose
    top tension is the weight in water of the line and unit, W + w L = 10 kN (004, (3.1)
    and (3.3) at rest: EA u_z = w_2 + w_1 z). Evaluated with the new top velocity (heave
    0.5 m/s up, pay-out 1 m/s down) against the resting line, the damping term c e_t of the
    top element read c (1 - 0.5) / h = 2 kN less (8.0 kN). Tolerance 1e-9 of the tension:
    the static profile is exact at the nodes, round-off only. The element tensions there
    are the static W + w s at the elements' mid-points (the tension is linear in s)."""
    d = _payout_scene("midpoint", 0.0)
    d["cable"]["axial_damping"] = 2.0e4
    d["top_motion"].update(heave_amplitude=0.5, heave_frequency=1.0)
    d["simulation"].update(duration=0.1, output_step=0.05)
    res = simulate(dynamic_scene_from_dict(d))
    w_static = 5000.0 + 50.0 * 100.0
    assert res.t[0] == 0.0
    assert res.top_tension[0] == pytest.approx(w_static, rel=1e-9)
    mid = (np.arange(20) + 0.5) * 100.0 / 20
    np.testing.assert_allclose(res.segment_tensions[0], 5000.0 + 50.0 * mid, rtol=1e-9)
    # the later samples are the stepped ones: the pay-out has started to unload the line
    assert res.top_tension[1] < w_static - 100.0


@pytest.mark.parametrize("scheme", ("midpoint", "thesis"))
def test_steady_payout_reaches_the_quasi_steady_state(scheme: str) -> None:
    """Pay-out at v = 1 m/s with cable and unit drag. After the start transient has died
    out (drag damps every mode at about kappa v / mu = 0.8 1/s), the tension and the
    elongation are those of (3.1)-(3.3) with u_tt = 0:
    T(s) = W - 1/2 rho C_D S v^2 + (w - kappa v^2) s, kappa = rho C_t pi d / 2.

    That closed form treats the point at a fixed distance below the sheave as material
    (Huang's frame); the exact material-point steady state translates rigidly at
    v_m = v (1 + e_top) with drag per stretched length: dT/ds = w - kappa v_m^2 (1 + T/EA),
    T(0) = W - 1/2 rho C_D S v_m^2. The models differ from the closed form by O(strain)
    (strain here <= 1e-4: tolerance 5e-4 of the tension). The model on material points
    (midpoint) matches the exact material steady state to 1e-6; Huang's scheme matches the
    steady state of its own equations (where the point at a fixed z below the sheave moves
    at v (1 + (T_top - T)/EA)) to 1e-6."""
    d = _payout_scene(scheme, 0.0 if scheme == "thesis" else 2.0)
    s = dynamic_scene_from_dict(d)
    res = simulate(s)
    assert res.status == "solved", res.message
    rho, ea, v = 1025.0, 1.0e8, 1.0
    kappa = 0.5 * rho * 0.1 * math.pi * 0.03
    cu = 0.5 * rho * 1.0 * 4.0
    ell = res.length[-1]
    n = res.segment_tensions.shape[1]
    s_mid = (np.arange(n) + 0.5) * ell / n
    ten = res.segment_tensions[-1]
    t_huang = 5000.0 - cu * v**2 + (50.0 - kappa * v**2) * s_mid
    assert np.max(np.abs(ten - t_huang)) <= 5e-4 * t_huang.max()

    def exact(vm: float, s_: np.ndarray) -> np.ndarray:
        a = kappa * vm**2 / ea
        t0 = 5000.0 - cu * vm**2
        b = 50.0 - kappa * vm**2
        return (t0 - b / a) * np.exp(-a * s_) + b / a

    vm = brentq(lambda x: x - v * (1.0 + exact(x, np.array([ell]))[0] / ea), 0.5, 2.0)
    t_exact = exact(vm, s_mid)
    if scheme == "thesis":
        # Huang's equations in their own steady state: the profile is frozen in s = L - z,
        # so at a fixed z, dU/dt = v (T_top - T(s)) / EA and the velocity in (3.1) and
        # (3.3) is u_t = v (1 + (T_top - T) / EA) (u_tt = 0 up to terms in dT_top/dt)
        def profile(t_top: float) -> np.ndarray:
            def ut(tt: np.ndarray) -> np.ndarray:
                return v * (1.0 + (t_top - tt) / ea)

            t0 = brentq(lambda x: x - (5000.0 - cu * ut(x) ** 2), 0.0, 1e4)
            sol = solve_ivp(lambda _s, tt: 50.0 - kappa * ut(tt) ** 2, (0.0, ell), [t0],
                            rtol=1e-13, atol=1e-10, dense_output=True)
            return sol.sol(s_mid)[0], sol.y[0, -1]

        t_top = t_huang.max()
        for _ in range(10):
            t_h, t_top_new = profile(t_top)
            if abs(t_top_new - t_top) < 1e-9:
                break
            t_top = t_top_new
        assert np.max(np.abs(ten - t_h)) <= 1e-6 * t_h.max()
    else:
        assert np.max(np.abs(ten - t_exact)) <= 1e-6 * t_exact.max()
        # elongation: the unit hangs the stretched length below the sheave
        ss = np.linspace(0.0, ell, 20001)
        stretched = ell + np.trapezoid(exact(vm, ss), ss) / ea
        assert res.unit_position[-1, 2] == pytest.approx(2000.0 - stretched, abs=1e-6)
        assert res.length[-1] == pytest.approx(100.0 + 1.0 * (40.0 - 1.0), rel=1e-12)


def test_damped_run_settles_to_the_statics_solution() -> None:
    """In water with drag and internal damping, released unstretched with the top fixed,
    the line settles to the static state the statics solver (collocation) computes for
    the same scene: tensions and the unit's elongation to 1e-6 relative."""
    from cable_ocp.statics.solver import solve

    d = {"environment": {"water_depth": 1000.0, "water_density": 1025.0},
         "cable": {"length": 100.0, "diameter": 0.03, "weight_in_water": 50.0,
                   "axial_stiffness": 1.0e8, "tangential_drag": 0.1, "normal_drag": 1.2,
                   "mass_per_length": 6.0, "axial_damping": 3.2e5},
         "unit": {"mass": 600.0, "added_mass": 200.0, "weight_in_water": 5000.0,
                  "drag_area": 4.0, "drag_coefficient": 1.0},
         "end_b": {"position": [0.0, 0.0, 1000.0]},
         "simulation": {"model": "axial", "duration": 12.0, "time_step": 0.01,
                        "output_step": 0.5, "segments": 20, "start": "unstrained"}}
    s = dynamic_scene_from_dict(d)
    res = simulate(s)
    st = solve(s.statics)
    assert st.status == "solved", st.message
    n = res.segment_tensions.shape[1]
    s_mid = (np.arange(n) + 0.5) * 100.0 / n
    t_static = np.interp(s_mid, st.s, st.tension)
    np.testing.assert_allclose(res.segment_tensions[-1], t_static, rtol=1e-6)
    elong = 1000.0 - 100.0 - st.position[0, 2]
    elong_dyn = 1000.0 - 100.0 - res.unit_position[-1, 2]
    assert elong_dyn == pytest.approx(elong, rel=1e-6)
    # it really moved: released 0.0075 m above the static position
    assert res.unit_position[0, 2] - st.position[0, 2] > 5e-3


def test_static_start_is_the_statics_solution() -> None:
    """The closed-form static profile (T = W + w s) used as the start equals the statics
    solver's solution of scene.statics (unit free, loaded by its weight in water)."""
    from cable_ocp.statics.solver import solve

    s = dynamic_scene_from_dict(_payout_scene("midpoint", 0.0))
    st = solve(s.statics)
    z, ten = static_profile(s, st.s)
    np.testing.assert_allclose(ten, st.tension, rtol=1e-9)
    np.testing.assert_allclose(z, st.position[:, 2], atol=1e-7)
    res = simulate(s.with_overrides({"simulation.duration": 0.5}))
    assert res.unit_position[0, 2] == pytest.approx(st.position[0, 2], abs=1e-7)


# a soft weightless line in air (c = sqrt(EA / mu) = 100 m/s, strain W / EA = 0.1 at rest)
# paid out from rest: the pay-out wave travels down and reaches the unit at t = L0 / c = 1 s
WV_L0, WV_MU, WV_EA, WV_W = 100.0, 1.0, 1.0e4, 1000.0
WV_C = math.sqrt(WV_EA / WV_MU)


def _payout_wave_scene(speed: float, ramp: float, duration: float, model: str = "axial"
                       ) -> dict:
    return {"environment": {"water_depth": 500.0, "water_density": 1.225},
            "cable": {"length": WV_L0, "weight_in_water": 0.0, "axial_stiffness": WV_EA,
                      "mass_per_length": WV_MU, "added_mass_coefficient": 0.0},
            "unit": {"mass": 200.0, "weight_in_water": WV_W},
            "end_b": {"position": [0.0, 0.0, 200.0]},
            "top_motion": {"payout_speed": speed, "ramp_time": ramp},
            "simulation": {"model": model, "duration": duration, "time_step": 1e-3,
                           "segments": 200}}


def _ramp_integral(t: float, tau: float) -> float:
    """R(t) = int_0^t r of the quintic ramp r = 10 x^3 - 15 x^4 + 6 x^5, x = t / tau."""
    x = min(t / tau, 1.0)
    return tau * x**4 * (2.5 - 3.0 * x + x * x) if t < tau else t - 0.5 * tau


def _payout_wave_drop(speed: float) -> float:
    """Tension drop behind the pay-out wave front, N (see the test below)."""
    e = WV_W / WV_EA
    return WV_MU * WV_C * speed * (1.0 + e) / (1.0 + speed / WV_C)


@pytest.mark.parametrize("model", ("axial", "planar"))
def test_payout_wave_against_dalembert(model: str) -> None:
    """Pay-out from rest (L = L0 + v R(t), ramped over 0.3 s) on a weightless line in air,
    before the wave reaches the unit: the exact material solution. With u = z - z0(s),
    z0 the static profile at rest extended above s = L0, (3.1) is the wave equation
    u_tt = c^2 u_ss (no weight gradient, no drag), so u = G(t + s / c), a wave going
    down; the sheave condition z(L(t), t) = z_b gives G(t + L(t) / c) = -(L(t) - L0)
    (1 + e), e = W / EA (the material arriving at the sheave comes from above the old
    top). The wave is Doppler-shifted by the moving boundary: behind the ramp the material
    velocity is u_t = -v (1 + e) / (1 + v / c) and the tension drops by mu c of it.
    Here v / c = 0.05, so this checks the pay-out terms of the fixed-domain
    transformation (3.4)-(3.7) at 5 %: the whole profile at t = 0.8 s to 1e-3 of the
    wave's amplitude (seen 9e-5: lumped-mass dispersion of a 30 m long ramp on 0.5 m
    elements) and the top tension behind the ramp to 1e-4 (seen 6e-6). The planar model
    (Huang ch. 4, its own fixed-domain transformation) on the same vertical line obeys the
    same equation along z."""
    v, tau = 5.0, 0.3
    res = simulate(dynamic_scene_from_dict(_payout_wave_scene(v, tau, 0.8, model)))
    assert res.status == "solved", res.message
    e = WV_W / WV_EA

    def g_wave(arg: float) -> float:
        if arg <= WV_L0 / WV_C:
            return 0.0
        t = brentq(lambda t: t + (WV_L0 + v * _ramp_integral(t, tau)) / WV_C - arg,
                   0.0, arg, xtol=1e-14)
        return -v * _ramp_integral(t, tau) * (1.0 + e)

    t_end, length = float(res.t[-1]), float(res.length[-1])
    s = np.linspace(0.0, 1.0, res.node_positions.shape[1]) * length
    z0 = 200.0 - (WV_L0 - s) * (1.0 + e)
    ref = np.array([g_wave(t_end + si / WV_C) for si in s])
    u = res.node_positions[-1, :, 2] - z0
    assert np.max(np.abs(ref)) > 3.0  # the wave has travelled 80 m down the line
    assert np.max(np.abs(u - ref)) <= 1e-3 * np.max(np.abs(ref))
    behind = res.t >= tau + 0.05
    np.testing.assert_allclose(res.top_tension[behind], WV_W - _payout_wave_drop(v),
                               rtol=1e-4)


def test_slack_threshold_against_the_payout_wave() -> None:
    """The pay-out wave above drops the tension by mu c v (1 + e) / (1 + v / c) (exact,
    linear): speeds that take the tension to -5 % and +5 % of the static W. The first run
    must report slack, the second must not (the threshold is 1e-9 of the static top
    tension; the discrete minimum matches the closed form to 1e-4 of W, see above)."""
    for target, expect in ((-0.05, True), (0.05, False)):
        v = brentq(lambda sp, tg=target: WV_W - _payout_wave_drop(sp) - tg * WV_W, 1.0, 20.0)
        res = simulate(dynamic_scene_from_dict(_payout_wave_scene(v, 0.3, 0.6)))
        assert res.min_tension == pytest.approx(target * WV_W, abs=1e-3 * WV_W)
        assert res.slack["occurred"] is expect, (target, res.slack, res.min_tension)
        assert (res.status == "slack") is expect


def test_slack_is_detected_located_and_stops_when_asked() -> None:
    """Huang (1992) 3.3.2's rope and sphere at 0.1 m and 2 Hz: the linear model predicts
    a dynamic tension (about K X r^2/(1 - r^2) with K = EA/L) larger than the 46 N static
    one, so the rope goes slack (3.3.2: "cable snatching occurs"). The run reports when
    and where; on_slack = "stop" ends the history there."""
    from pathlib import Path

    path = Path(__file__).resolve().parents[2] / "problems" / "dynamics" / "huang_3_3_2.toml"
    res = simulate(path)
    assert res.status == "slack"
    assert res.slack["occurred"] and res.slack["first_time"] > 0
    assert 0.0 <= res.slack["location"] <= 4.573
    assert res.min_tension < 0
    assert "slack" in res.message
    stop = simulate(path, overrides={"simulation.on_slack": "stop"})
    assert stop.status == "slack" and stop.t[-1] < res.t[-1]
    assert stop.slack["first_time"] == pytest.approx(res.slack["first_time"], abs=1e-12)
    assert stop.t[-1] <= stop.slack["first_time"] + 0.01 + 1e-9
    json.dumps(stop.to_dict(full=True), allow_nan=False)


def test_progress_hook_is_bounded_and_library_is_silent(capfd) -> None:
    calls = []
    s = dynamic_scene_from_dict(air_scene(duration=2.0, time_step=0.0005, segments=4))
    res = simulate(s, progress=lambda done, total: calls.append((done, total)))
    assert 1 <= len(calls) <= 200
    assert calls[-1] == (4000, 4000)
    assert all(a[0] < b[0] for a, b in zip(calls, calls[1:], strict=False))
    out = capfd.readouterr()
    assert out.out == "" and out.err == ""
    d = res.to_dict()
    json.dumps(d, allow_nan=False)
    for key in ("t", "length", "top_position", "unit_position", "top_tension",
                "min_tension", "slack", "wall_time_s", "status"):
        assert key in d
    assert d["slack"] == {"occurred": False, "first_time": None, "location": None,
                          "segment": None}


@pytest.mark.parametrize("key,value,needle", [
    ("environment.current", {"speed": 0.5}, "environment.current"),
    ("top_motion", {"horizontal_amplitude": 1.0, "horizontal_frequency": 1.0},
     "top_motion.horizontal_amplitude"),
    ("top_motion", {"circular_radius": 1.0, "circular_frequency": 1.0},
     "top_motion.circular_radius"),
    ("top_motion", {"tow": {"speed": 1.0}}, "top_motion.tow"),
    ("unit", {"mass": 10.0, "weight_in_water": -5.0}, "unit.weight_in_water"),
])
def test_axial_rejects_what_it_cannot_model(key: str, value, needle: str) -> None:
    d = air_scene()
    if key == "environment.current":
        d["environment"]["current"] = value
        d["cable"]["diameter"] = 0.01
        d["cable"]["normal_drag"] = 1.0
        d["cable"]["tangential_drag"] = 0.01
    else:
        d[key] = value
    with pytest.raises(CableOCPError, match=needle.replace(".", r"\.")):
        simulate(dynamic_scene_from_dict(d))


def test_thesis_scheme_limits() -> None:
    d = air_scene(scheme="thesis")
    d["top_motion"] = {"payout_law": "quadratic", "payout_speed": 0.1,
                       "payout_acceleration": 0.01}
    with pytest.raises(CableOCPError, match="payout_law"):
        simulate(dynamic_scene_from_dict(d))
    d = air_scene(scheme="thesis", segments=2)
    with pytest.raises(CableOCPError, match="simulation.segments"):
        simulate(dynamic_scene_from_dict(d))
