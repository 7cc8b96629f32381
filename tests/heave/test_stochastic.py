"""Stochastic analysis (004 section 6.3): variances (6.31)/(6.33)-(6.35), LQR, LQG, 6.3.5."""

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

Q_636 = 553.6  # weight found for 6.3.6 (README "Heave compensation"; problems/heave/ex_6_3_6)


def test_sigma_uncontrolled_0255(plant_636: pl.HeavePlant) -> None:
    # 004 Fig. 6.23: sigma = 0.255 m, in the convention sigma^2 = pi P11 (CONVENTIONS); the
    # thesis prints 3 digits, so +-0.0005 m.
    s = np.sqrt(st.output_variance_lyapunov(plant_636.A, plant_636.B2, plant_636.e("x")))
    assert s == pytest.approx(SIGMA_UNCONTROLLED_636, abs=5e-4)
    # The as-printed readings give other numbers (CONVENTIONS): P11 alone and (-inf, inf).
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


def test_lqr_636_reproduces_296e_4(plant_636: pl.HeavePlant) -> None:
    # 004 Fig. 6.24: sigma = 2.96e-4 m; weights unstated. Q = q e1 e1^T, R = 1, q = 553.6
    # reproduces it to the printed 3 digits (+-0.005e-4); the loop is stable and the reduction
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
    # CONVENTIONS: the exact discrete-delay design (tau = 0.2 s, h = 0.05 s) recovers 2.96e-4 m
    # (within 1 %: sampling changes the optimum slightly).
    p = plant_636
    G = st.discrete_delay_lqr(p.A, p.B1, p.e("x"), Q_636, 1.0, 0.05, 0.2)
    s = st.sampled_loop_sigma(p.A, p.B1, p.B2, p.e("x"), 0.05, 0.2, G[:, :11], G[:, 11:])
    assert s == pytest.approx(SIGMA_CONTROLLED_636, rel=0.01)


def test_undelayed_gain_on_the_true_delay(plant_636: pl.HeavePlant) -> None:
    # The undelayed q = 553.6 gain has a continuous delay margin of 0.2161 s (exact crossing
    # condition, confirmed by the Nyquist count on either side), so with a true 0.2 s delay it
    # is stable but degraded: sigma = 8.71e-4 m (sampled at 1 ms; 8.70e-4 extrapolated to
    # h -> 0, O(h) convergence, 0.5 % tolerance), about 3x the 2.96e-4 m of the delay-aware
    # design. Sampled with a ZOH at 0.05 s (about h/2 = 25 ms of extra delay, past the margin)
    # the same gain is unstable.
    p = plant_636
    g0 = st.stochastic_lqr(p.A, p.B1, p.B2, p.e("x"), Q_636).G
    des = lqr.LQRDesign(g0, "none", 0.0, p.n, p.A, p.B1, p.B2, np.zeros((0, 0)),
                        np.zeros((0, 1)))
    margin = lqr.delay_margin(des, 1.0)
    assert margin == pytest.approx(0.2161, abs=1e-4)
    assert lqr.unstable_roots(des, 0.2) == 0
    assert lqr.unstable_roots(des, margin + 2e-3) > 0
    s_fine = st.sampled_loop_sigma(p.A, p.B1, p.B2, p.e("x"), 1e-3, 0.2, g0)
    assert s_fine == pytest.approx(8.71e-4, rel=5e-3)
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
    # 004 Fig. 6.25: at a prescribed sigma, the energy index falls as K grows and levels off.
    f = sea.thesis_shaping_filter(HS_636, WM_636)

    def build(K: float) -> pl.HeavePlant:
        return pl.assemble_plant(A_636, B_636, pl.winch_first(K),
                                 vessel=pl.vessel_block(0.393, 0.6, 0.5), sea=f)

    res = st.winch_gain_study(build, [0.5, 1.0, 2.0, 8.0], 2.96e-4)
    e = [r[2] for r in res]
    assert e[0] > e[1] > e[2] > e[3]
    # levels off: the last step (2 -> 8) gains relatively less than the first (0.5 -> 1).
    assert (e[2] - e[3]) / e[2] < (e[0] - e[1]) / e[0]
