"""Stochastic analysis (Huang 1992, section 6.3): variances (6.31)/(6.33)-(6.35), LQR, LQG,
6.3.5."""

from __future__ import annotations

import numpy as np
import pytest

from cable_ocp.heave import lqr, sea
from cable_ocp.heave import plant as pl
from cable_ocp.heave import stochastic as st
from cable_ocp.heave.thesis import (
    A_636,
    B_636,
    HS_636,
    SIGMA_CONTROLLED_636,
    SIGMA_UNCONTROLLED_636,
    WM_636,
)

Q_636 = 553.6  # calibrated to 6.3.6's 2.96e-4 m (README "Reproductions and calibrations")


def test_sigma_uncontrolled_0255(plant_636: pl.HeavePlant) -> None:
    # Huang (1992) Fig. 6.23: sigma = 0.255 m, in the convention sigma^2 = pi P11
    # (docs/conventions.md); the thesis prints 3 digits, so +-0.0005 m.
    s = np.sqrt(st.output_variance_lyapunov(plant_636.A, plant_636.B2, plant_636.e("x")))
    assert s == pytest.approx(SIGMA_UNCONTROLLED_636, abs=5e-4)
    # The as-printed readings give other numbers (docs/conventions.md): P11 alone and (-inf, inf).
    P = st.state_covariance(plant_636.A, plant_636.B2)
    assert np.sqrt(P[0, 0]) == pytest.approx(0.144, abs=5e-4)
    assert np.sqrt(2 * np.pi * P[0, 0]) == pytest.approx(0.361, abs=5e-4)


@pytest.mark.parametrize("controlled", [False, True])
def test_lyapunov_equals_spectral(plant_636: pl.HeavePlant, controlled: bool) -> None:
    # Two independent computations of the same variance (Lyapunov (6.31) vs the integral of
    # (6.34)); relative tolerance 1e-6 as the issue asks (they agree to ~1e-12 here). Relative,
    # since the controlled variance is ~1e-7 m^2.
    A0 = plant_636.A
    if controlled:
        A0 = A0 - plant_636.B1 @ st.stochastic_lqr(plant_636.A, plant_636.B1, plant_636.B2,
                                                    plant_636.e("x"), Q_636).G
    v1 = st.output_variance_lyapunov(A0, plant_636.B2, plant_636.e("x"))
    v2 = st.output_variance_spectral(A0, plant_636.B2, plant_636.e("x"))
    assert v2 == pytest.approx(v1, rel=1e-6)


def test_lqr_636_calibrated_weight_gives_296e_4(plant_636: pl.HeavePlant) -> None:
    # Huang (1992) Fig. 6.24: sigma = 2.96e-4 m; weights unstated. Q = q e1 e1^T, R = 1, with
    # q = 553.6 CALIBRATED to that sigma (so this checks the calibration, not the thesis): it
    # holds to the printed 3 digits (+-0.005e-4); the loop is stable and the reduction
    # exceeds 99 %.
    d = st.stochastic_lqr(plant_636.A, plant_636.B1, plant_636.B2, plant_636.e("x"), Q_636)
    assert d.sigma == pytest.approx(SIGMA_CONTROLLED_636, abs=5e-7)
    assert np.max(d.closed_loop_poles.real) < 0
    assert d.reduction_pct > 99.0


def test_weight_for_sigma_inverts_design(plant_636: pl.HeavePlant) -> None:
    # Bisection on q must return a weight whose design gives the target (rel 1e-8).
    q = st.weight_for_sigma(plant_636.A, plant_636.B1, plant_636.B2, plant_636.e("x"), 1e-3)
    d = st.stochastic_lqr(plant_636.A, plant_636.B1, plant_636.B2, plant_636.e("x"), q)
    assert d.sigma == pytest.approx(1e-3, rel=1e-8)


def test_discrete_exact_delay_design_recovers_sigma(plant_636: pl.HeavePlant) -> None:
    # docs/conventions.md: the exact discrete-delay design (tau = 0.2 s, h = 0.05 s) recovers
    # 2.96e-4 m (within 1 %: sampling changes the optimum slightly).
    p = plant_636
    G = st.discrete_delay_lqr(p.A, p.B1, p.e("x"), Q_636, 1.0, 0.05, 0.2)
    s = st.sampled_loop_sigma(p.A, p.B1, p.B2, p.e("x"), 0.05, 0.2, G[:, :11], G[:, 11:])
    assert s == pytest.approx(SIGMA_CONTROLLED_636, rel=0.01)


def _delay_margin_and_pade_sigma(A: np.ndarray, B1: np.ndarray, B2: np.ndarray,  # noqa: N803
                                 c_x: np.ndarray, G: np.ndarray, tau: float
                                 ) -> tuple[float, float]:
    """Independent of lqr.py/stochastic.py: (i) the delay margin of u0 = -G x from the loop
    frequency response L(iw) = G (iw I - A)^-1 B1: at each gain crossover |L(iw_c)| = 1
    (found by brentq on a log grid), the smallest delay tau > 0 with
    1 + L(iw_c) e^{-i w_c tau} = 0 is (arg L - pi mod 2 pi) / w_c; (ii) the heave sigma of the
    loop with the delay replaced by a 6th-order Pade approximant (python-control ``pade``),
    by the continuous Lyapunov equation (noise intensity pi)."""
    import control as ct
    from scipy import linalg, optimize

    n = A.shape[0]

    def loop(w: float) -> complex:
        return complex((G @ np.linalg.solve(1j * w * np.eye(n) - A, B1))[0, 0])

    ws = np.logspace(-3, 3, 4000)
    mag = np.array([abs(loop(w)) for w in ws]) - 1.0
    margins = []
    for i in np.flatnonzero(np.diff(np.sign(mag))):
        wc = optimize.brentq(lambda w: abs(loop(w)) - 1.0, ws[i], ws[i + 1], xtol=1e-14)
        margins.append((np.angle(loop(wc)) - np.pi) % (2 * np.pi) / wc)
    num, den = ct.pade(tau, 6)
    pd = ct.ss(ct.tf(num, den))
    Ap, Bp, Cp, Dp = (np.asarray(m, dtype=float) for m in (pd.A, pd.B, pd.C, pd.D))
    Acl = np.block([[A - B1 @ Dp @ G, B1 @ Cp], [-Bp @ G, Ap]])
    Bn = np.vstack([B2, np.zeros((Ap.shape[0], 1))])
    P = np.pi * linalg.solve_continuous_lyapunov(Acl, -Bn @ Bn.T)
    return float(min(margins)), float(np.sqrt(P[0, 0]))


def test_undelayed_gain_on_the_true_delay(plant_636: pl.HeavePlant) -> None:
    # The undelayed q = 553.6 gain with a true 0.2 s delay: stable but degraded, about 3x the
    # 2.96e-4 m of the delay-aware design; sampled with a ZOH at 0.05 s (about h/2 = 25 ms of
    # extra delay, past the margin) the same gain is unstable.
    # Delay margin: the library's exact crossing condition (lqr.delay_margin) against the
    # crossover computed here (_delay_margin_and_pade_sigma): same equation, different code,
    # 1e-6 s; regression value 0.2161 s (this project's output, 4 digits) beside it, and the
    # Nyquist count on either side.
    # sigma: the library's exactly sampled loop at h = 1 ms against the continuous loop with
    # a 6th-order Pade delay (4th and 6th order agree to 2e-5 here): 8.691e-4 m. The sampled
    # loop converges at O(h) (a ZOH adds ~h/2 of delay): measured 0.24 % at 1 ms (and the
    # extrapolation 2 s(h/2) - s(h) lands within 1e-5 of the Pade value), so 0.5 %.
    # Regression value 8.71e-4 m (1 ms) beside it.
    p = plant_636
    g0 = st.stochastic_lqr(p.A, p.B1, p.B2, p.e("x"), Q_636).G
    des = lqr.LQRDesign(g0, "none", 0.0, p.n, p.A, p.B1, p.B2, np.zeros((0, 0)),
                        np.zeros((0, 1)))
    margin = lqr.delay_margin(des, 1.0)
    m_ref, s_ref = _delay_margin_and_pade_sigma(p.A, p.B1, p.B2, p.e("x"), g0, 0.2)
    assert margin == pytest.approx(m_ref, abs=1e-6)
    assert margin == pytest.approx(0.2161, abs=1e-4)  # regression value
    assert lqr.unstable_roots(des, 0.2) == 0
    assert lqr.unstable_roots(des, margin + 2e-3) > 0
    s_fine = st.sampled_loop_sigma(p.A, p.B1, p.B2, p.e("x"), 1e-3, 0.2, g0)
    assert s_fine == pytest.approx(s_ref, rel=5e-3)
    assert s_fine == pytest.approx(8.71e-4, rel=5e-3)  # regression value
    assert s_fine > 2.9 * SIGMA_CONTROLLED_636
    assert st.sampled_loop_sigma(p.A, p.B1, p.B2, p.e("x"), 0.05, 0.2, g0) == float("inf")


def test_sampled_loop_matches_continuous_for_small_step(plant_636: pl.HeavePlant) -> None:
    # Independent paths: continuous Lyapunov vs exactly sampled loop with tau = 0. A ZOH at
    # h = 1 ms perturbs sigma by O(h); 2 % bound.
    p = plant_636
    d = st.stochastic_lqr(p.A, p.B1, p.B2, p.e("x"), Q_636)
    s = st.sampled_loop_sigma(p.A, p.B1, p.B2, p.e("x"), 1e-3, 0.0, d.G)
    assert s == pytest.approx(d.sigma, rel=0.02)


def test_lqg_approaches_lqr_as_noise_vanishes(plant_636: pl.HeavePlant) -> None:
    # Separation principle: the LQG sigma exceeds the LQR sigma and decreases with the sensor
    # noise. (Only the unit's position is measured, so the sea states are poorly observable.)
    p = plant_636
    d = st.stochastic_lqr(p.A, p.B1, p.B2, p.e("x"), Q_636)
    sig = []
    for std in [1e-1, 1e-2, 1e-3]:
        L = st.lqg_kalman(p.A, p.B2, p.e("x"), std, 0.05)
        sig.append(st.lqg_closed_loop_sigma(p.A, p.B1, p.B2, p.e("x"), d.G, L, std**2 * 0.05))
    assert sig[0] > sig[1] > sig[2] > d.sigma


def test_lqg_variance_lyapunov_equals_spectral_of_hand_built_loop(plant_636: pl.HeavePlant
                                                                    ) -> None:
    # Two independent paths to the LQG heave variance (1 cm sensor at 0.05 s): (a) the library
    # (python-control feedback with sign=+1, Lyapunov of the augmented loop); (b) the loop
    # [x; x_hat]' = [[A, -B1 G], [L C, A - B1 G - L C]] [x; x_hat] + [[B2, 0], [0, L]] [w; v]
    # written by hand, its variance by quadrature of the one-sided spectral integral (6.33)
    # for each noise (intensities pi and RN, so v contributes RN/pi times its integral).
    # Relative 1e-6 as for the other Lyapunov/spectral pairs.
    p = plant_636
    cx = p.e("x")
    d = st.stochastic_lqr(p.A, p.B1, p.B2, cx, Q_636)
    std, h = 0.01, 0.05
    L = st.lqg_kalman(p.A, p.B2, cx, std, h)
    RN = std**2 * h
    s_lib = st.lqg_closed_loop_sigma(p.A, p.B1, p.B2, cx, d.G, L, RN)
    n = p.n
    Acl = np.block([[p.A, -p.B1 @ d.G], [L @ cx, p.A - p.B1 @ d.G - L @ cx]])
    Bw = np.vstack([p.B2, np.zeros((n, 1))])
    Bv = np.vstack([np.zeros((n, 1)), L])
    C = np.hstack([cx, np.zeros((1, n))])
    var = st.output_variance_spectral(Acl, Bw, C) + RN / np.pi * st.output_variance_spectral(
        Acl, Bv, C)
    assert np.sqrt(var) == pytest.approx(s_lib, rel=1e-6)
    # and it lies between full-state LQR and no control (separation principle)
    assert d.sigma < s_lib < d.sigma_uncontrolled


def test_winch_gain_study_energy_decreases_with_K() -> None:
    # Huang (1992) Fig. 6.25: at a prescribed sigma, the energy index falls as K grows and levels
    # off.
    f = sea.thesis_shaping_filter(HS_636, WM_636)

    def build(K: float) -> pl.HeavePlant:
        return pl.assemble_plant(A_636, B_636, pl.winch_first(K),
                                 vessel=pl.vessel_block(0.393, 0.6, 0.5), sea=f)

    res = st.winch_gain_study(build, [0.5, 1.0, 2.0, 8.0], 2.96e-4)
    e = [r[2] for r in res]
    assert e[0] > e[1] > e[2] > e[3]
    # levels off: the last step (2 -> 8) gains relatively less than the first (0.5 -> 1).
    assert (e[2] - e[3]) / e[2] < (e[0] - e[1]) / e[0]


def test_lqg_sigma_against_an_independent_riccati_and_lyapunov_solution(
        plant_636: pl.HeavePlant) -> None:
    # One LQG sigma pinned against a truth computed here with scipy, sharing nothing with
    # stochastic.py but the plant matrices (checked against the thesis by the 0.255 m test):
    # regulator gain from the control Riccati equation (solve_continuous_are, Q = q e1 e1^T,
    # R = 1), Kalman gain from the filter Riccati equation (process noise through B2 with
    # intensity pi, the one-sided unit spectral density; 1 cm sensor sampled every 0.05 s =
    # continuous measurement noise of intensity 1e-4 * 0.05 m^2 s), and the heave variance from
    # the Lyapunov equation of the closed loop [x; x_hat] written here. Both sides are direct
    # solves of the same equations: rtol 1e-6 (measured 3e-12; sigma = 0.01297 m). Replacing
    # pi by 1 in the filter's process-noise intensity moves the library's sigma by 22 %.
    from scipy import linalg

    p = plant_636
    A, B1, B2, cx = p.A, p.B1, p.B2, p.e("x")
    n = A.shape[0]
    std, h = 0.01, 0.05
    Vn = std**2 * h
    M = linalg.solve_continuous_are(A, B1, Q_636 * cx.T @ cx, np.array([[1.0]]))
    G = B1.T @ M  # R = 1
    S = linalg.solve_continuous_are(A.T, cx.T, np.pi * B2 @ B2.T, np.array([[Vn]]))
    L = S @ cx.T / Vn
    Acl = np.block([[A, -B1 @ G], [L @ cx, A - B1 @ G - L @ cx]])
    Bn = np.block([[B2, np.zeros((n, 1))], [np.zeros((n, 1)), L]])
    Pcl = linalg.solve_continuous_lyapunov(Acl, -Bn @ np.diag([np.pi, Vn]) @ Bn.T)
    sigma_truth = float(np.sqrt(Pcl[0, 0]))
    # the library's path: stochastic_lqr -> lqg_kalman -> lqg_closed_loop_sigma
    d = st.stochastic_lqr(A, B1, B2, cx, Q_636)
    np.testing.assert_allclose(d.G, G, rtol=1e-6)
    L_lib = st.lqg_kalman(A, B2, cx, std, h)
    s_lib = st.lqg_closed_loop_sigma(A, B1, B2, cx, d.G, L_lib, Vn)
    assert s_lib == pytest.approx(sigma_truth, rel=1e-6)
    # a meaningful number: between the full-state LQR and no control
    assert d.sigma < sigma_truth < d.sigma_uncontrolled
