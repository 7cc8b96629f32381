"""MPC (issue 4 item 4): equality with discrete LQR, hard limits with delay, preview."""

from __future__ import annotations

import numpy as np
import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.heave import mpc
from cable_ocp.heave import plant as pl
from cable_ocp.heave.discrete import discretize_noise

SOLVERS = [("daqp", {}), ("qpoases", {}), ("qrqp", {}),
           ("osqp", {"osqp": {"eps_abs": 1e-12, "eps_rel": 1e-12, "max_iter": 100000}}),
           ("ipopt", {})]


@pytest.mark.parametrize("tau", [0.0, 0.2])
@pytest.mark.parametrize("solver,opts", SOLVERS)
def test_unconstrained_mpc_equals_dlqr(plant_636: pl.HeavePlant, solver: str, opts: dict,
                                       tau: float) -> None:
    # With the DARE solution as terminal cost and no limits, the MPC's first move is the
    # discrete LQR's (Bellman), here python-control's dlqr on the same sampled model and cost
    # (stochastic.discrete_delay_lqr), without delay and with the 0.2 s delay as a 4-sample
    # shift register. The issue asks for 1e-6; every solver reaches <= 9e-14 here (IPOPT too:
    # the problem is a convex QP that it solves in one Newton step; OSQP needs tight eps,
    # CONVENTIONS: at default tolerances it is off by ~1e-2), so 1e-12.
    from cable_ocp.heave.stochastic import discrete_delay_lqr

    m = mpc.LinearMPC(plant_636, tau, mpc.MPCSettings(horizon=50, sample_time=0.05,
                                                     solver=solver, solver_options=opts))
    G = discrete_delay_lqr(plant_636.A, plant_636.B1, plant_636.e("x"), 553.6, 1.0, 0.05, tau)
    assert G.shape == (1, plant_636.n + round(tau / 0.05))
    rng = np.random.default_rng(0)
    for _ in range(2):
        z0 = rng.standard_normal(m.nz) * 0.1
        r = m.step(z0)
        assert r.success
        assert r.u0 == pytest.approx(-(G @ z0)[0], abs=1e-12)


def test_dlqr_of_python_control_matches_dare_gain(plant_636: pl.HeavePlant) -> None:
    # The MPC's K from scipy's DARE equals python-control's dlqr on the same sampled cost.
    import control as ct

    m = mpc.LinearMPC(plant_636, 0.0, mpc.MPCSettings(horizon=5))
    K, _, _ = ct.dlqr(m.model.Ad, m.model.Bd, m.Qz, m.Rz, m.Nz)
    np.testing.assert_allclose(m.K_lqr, K, rtol=1e-7, atol=1e-10)


def _factor(Q: np.ndarray) -> np.ndarray:
    """``L`` with ``L L^T = Q`` for a PSD ``Q`` whose winch rows are exactly zero (no jitter)."""
    lam, V = np.linalg.eigh(Q)
    return V * np.sqrt(np.clip(lam, 0.0, None))


def _run(plant: pl.HeavePlant, m: mpc.LinearMPC, steps: int, seed: int, scale: float = 1.0
         ) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """Closed loop on the exactly sampled plant (noise by Van Loan); returns u, u', du, fails."""
    rng = np.random.default_rng(seed)
    Ad, Bd = m.model.Ad, m.model.Bd
    Lw = _factor(discretize_noise(plant.A, plant.B2, np.pi, 0.05))
    z = np.zeros(m.nz)
    up = 0.0
    us, speeds, dus, fails = [], [], [], 0
    iu = plant.blocks["winch"].start
    for _ in range(steps):
        r = m.step(z, up)
        fails += not r.success
        v = z[m.n] if m.model.d else r.u0
        speeds.append(plant.K * (v - z[iu]))
        dus.append(r.u0 - up)
        up = r.u0
        z = Ad @ z + Bd[:, 0] * r.u0
        z[: plant.n] += scale * Lw @ rng.standard_normal(plant.n)
        us.append(z[iu])
    return np.array(us), np.array(speeds), np.array(dus), fails


def test_delayed_constrained_mpc_keeps_every_hard_limit(plant_636: pl.HeavePlant) -> None:
    # Limits tight enough to be active (the wave is scaled up 3x): every step keeps stroke,
    # speed (just after each sample, where the first-order winch is fastest) and command rate,
    # to 1e-9 relative (solver feasibility tolerance).
    st = mpc.MPCSettings(horizon=30, sample_time=0.05, stroke_max=0.6, speed_max=0.5,
                         command_rate_max=0.05)
    m = mpc.LinearMPC(plant_636, 0.2, st)
    u, sp, du, fails = _run(plant_636, m, 600, seed=1, scale=3.0)
    assert fails == 0
    assert np.max(np.abs(u)) <= 0.6 * (1 + 1e-9)
    assert np.max(np.abs(sp)) <= 0.5 * (1 + 1e-9)
    assert np.max(np.abs(du)) <= 0.05 * (1 + 1e-9)
    # The limits were active (otherwise this test proves nothing).
    assert max(np.max(np.abs(u)) / 0.6, np.max(np.abs(sp)) / 0.5, np.max(np.abs(du)) / 0.05) \
        > 0.99


def test_second_order_winch_accel_limit() -> None:
    from cable_ocp.heave import sea
    from cable_ocp.heave.thesis import A_636, B_636, HS_636, WM_636

    p = pl.assemble_plant(A_636, B_636, pl.winch_second(1.4, 0.7),
                          vessel=pl.vessel_block(0.393, 0.6, 0.5),
                          sea=sea.thesis_shaping_filter(HS_636, WM_636))
    m = mpc.LinearMPC(p, 0.1, mpc.MPCSettings(horizon=30, stroke_max=1.0, speed_max=0.6,
                                              accel_max=0.4))
    rng = np.random.default_rng(2)
    Lw = _factor(discretize_noise(p.A, p.B2, np.pi, 0.05))
    z = np.zeros(m.nz)
    iu = p.blocks["winch"].start
    acc = []
    for _ in range(400):
        r = m.step(z)
        assert r.success
        acc.append(1.4**2 * (z[m.n] - z[iu]) - 2 * 0.7 * 1.4 * z[iu + 1])
        z = m.model.Ad @ z + m.model.Bd[:, 0] * r.u0
        z[: p.n] += 3.0 * Lw @ rng.standard_normal(p.n)
        assert abs(z[iu]) <= 1.0 * (1 + 1e-9) and abs(z[iu + 1]) <= 0.6 * (1 + 1e-9)
    assert np.max(np.abs(acc)) <= 0.4 * (1 + 1e-9)


def test_acceleration_limit_rejected_for_first_order_winch(plant_636: pl.HeavePlant) -> None:
    with pytest.raises(CableOCPError, match="command_rate_max"):
        mpc.LinearMPC(plant_636, 0.0, mpc.MPCSettings(accel_max=1.0))


def test_delay_must_be_whole_samples(plant_636: pl.HeavePlant) -> None:
    with pytest.raises(CableOCPError, match="integer multiple"):
        mpc.LinearMPC(plant_636, 0.12, mpc.MPCSettings(sample_time=0.05))


def test_wave_preview_lets_the_regulator_cancel_a_known_wave() -> None:
    # Regulator plant (6.6) (boom tip an exogenous input), 0.2 s delay, boom tip
    # x0 = 0.5 sin(0.6 t) m. Without preview the MPC only sees the unit's state and reacts:
    # unit heave RMS 0.140 m. With the boom tip known 2 s ahead (the whole 40-step horizon) it
    # cancels the wave through the delay: 0.0021 m (same exactly sampled plant, ZOH boom tip).
    # Assert a factor of more than 20 and the two levels within 10 %.
    from cable_ocp.heave import lqr
    from cable_ocp.heave.thesis import A_636, B_636

    p = lqr.regulator_plant(A_636, B_636, 1.0)
    h, N = 0.05, 40
    t = np.arange(0.0, 60.0 + (N + 1) * h, h)
    x0 = 0.5 * np.sin(0.6 * t)
    rms = {}
    for pv in (0.0, 2.0):
        m = mpc.LinearMPC(p, 0.2, mpc.MPCSettings(horizon=N, q=553.6, preview_time=pv))
        z = np.zeros(m.nz)
        xs = []
        for k in range(int(round(60.0 / h))):
            D = m.preview_correction(z, x0[k : k + N]) if pv > 0 else None
            r = m.step(z, 0.0, D)
            z = m.model.Ad @ z + m.model.Bd[:, 0] * r.u0 + m.model.Ed[:, 0] * x0[k]
            xs.append(z[0])
        rms[pv] = float(np.sqrt(np.mean(np.array(xs[200:]) ** 2)))  # after 10 s
    assert rms[0.0] == pytest.approx(0.140, rel=0.1)
    assert rms[2.0] == pytest.approx(0.0021, rel=0.1)
    assert rms[0.0] > 20 * rms[2.0]


def test_ipopt_and_qp_give_the_same_moves_with_active_limits(plant_636: pl.HeavePlant) -> None:
    # The IPOPT formulation has the QP's cost, limit rows (rows fixed by commands already sent
    # dropped), |u0| <= stroke_max bound and tension slacks, and with the linear unit the exact
    # sampled model: it is the same convex problem. Along a closed-loop run (driven by the QP
    # MPC, 3x the sea, limits tight enough to be active), IPOPT solved at the same state must
    # give the same first move. Tolerance 5e-7 m: with tol = 1e-12 IPOPT agrees to ~7e-8 m
    # (interior point near weakly active limits; at the default tol 1e-10, ~2e-6 m), the
    # active-set QP to ~1e-15.
    lim = {"stroke_max": 0.3, "speed_max": 0.15, "command_rate_max": 0.01,
           "tension_min": 5000.0, "unit_mass": 125000.0, "static_tension": 50000.0}
    mq = mpc.LinearMPC(plant_636, 0.2, mpc.MPCSettings(horizon=20, solver="qpoases", **lim))
    mi = mpc.LinearMPC(plant_636, 0.2, mpc.MPCSettings(
        horizon=20, solver="ipopt", solver_options={"ipopt": {"tol": 1e-12}}, **lim))
    assert mi._nlp.ns == mq.ns == 16  # the 4 stretch rows fixed by the 4-sample delay dropped
    rng = np.random.default_rng(1)
    Lw = _factor(discretize_noise(plant_636.A, plant_636.B2, np.pi, 0.05))
    iu = plant_636.blocks["winch"].start
    z = np.zeros(mq.nz)
    up = 0.0
    diffs, active = [], 0
    for _ in range(130):
        rq, ri = mq.step(z, up), mi.step(z, up)
        assert rq.success and ri.success
        diffs.append(abs(rq.u0 - ri.u0))
        used = max(abs(z[iu]) / 0.3, abs(z[mq.n] - z[iu]) / 0.15, abs(rq.u0 - up) / 0.01)
        active += used > 1 - 1e-6
        up = rq.u0
        z = mq.model.Ad @ z + mq.model.Bd[:, 0] * rq.u0
        z[: plant_636.n] += 3.0 * Lw @ rng.standard_normal(plant_636.n)
    assert max(diffs) < 5e-7
    assert active >= 10  # limits were active on the first move (else this proves little)


def test_rows_fixed_by_sent_commands_do_not_make_ipopt_infeasible(plant_636: pl.HeavePlant
                                                                   ) -> None:
    # The winch is at u = 0.31 m > stroke_max = 0.3 m and the 4 buffered commands are 0.3 m:
    # the stroke over the next 4 samples is fixed by commands already sent and violates the
    # limit. Those rows are dropped (nothing can be decided), so both formulations solve and
    # agree (5e-7 m as above); keeping them made the IPOPT problem infeasible.
    st = {"horizon": 15, "stroke_max": 0.3, "speed_max": 0.3, "command_rate_max": 0.2}
    mq = mpc.LinearMPC(plant_636, 0.2, mpc.MPCSettings(solver="qpoases", **st))
    mi = mpc.LinearMPC(plant_636, 0.2, mpc.MPCSettings(
        solver="ipopt", solver_options={"ipopt": {"tol": 1e-12}}, **st))
    z = np.zeros(mq.nz)
    z[plant_636.blocks["winch"].start] = 0.31
    z[mq.n :] = 0.3
    rq, ri = mq.step(z, 0.3), mi.step(z, 0.3)
    assert rq.success and ri.success
    assert ri.u0 == pytest.approx(rq.u0, abs=5e-7)
    assert abs(ri.u0) <= 0.3 * (1 + 1e-9)  # the command bound |u0| <= stroke_max


@pytest.mark.parametrize("solver,opts", [("osqp", {}), ("osqp", {"osqp": {"polish": True}}),
                                         ("qpoases", {}), ("qrqp", {}), ("ipopt", {}),
                                         ("daqp", {})])
@pytest.mark.parametrize("limits", [{}, {"stroke_max": 2.0, "speed_max": 1.5,
                                         "command_rate_max": 0.1}])
def test_mpc_steps_print_nothing(plant_636: pl.HeavePlant, capfd: pytest.CaptureFixture,
                                 solver: str, opts: dict, limits: dict) -> None:
    # Library code never prints. OSQP with polishing printed "Polishing not needed ..." on
    # every unconstrained solve; qpOASES prints a banner on its first call. Captured at the
    # file-descriptor level (C libraries write to fd 1 directly).
    m = mpc.LinearMPC(plant_636, 0.2, mpc.MPCSettings(horizon=10, solver=solver,
                                                     solver_options=opts, **limits))
    rng = np.random.default_rng(0)
    for _ in range(4):
        assert m.step(rng.standard_normal(m.nz) * 0.01).success
    out, err = capfd.readouterr()
    assert out == "" and err == ""
