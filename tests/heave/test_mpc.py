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
    # docs/conventions.md: at default tolerances it is off by ~1e-2), so 1e-12.
    from cable_ocp.heave.stochastic import discrete_delay_lqr

    m = mpc.LinearMPC(plant_636, tau, mpc.MPCSettings(horizon=50, sample_time=0.05,
                                                     solver=solver, solver_options=opts))
    # q = 553.6: the weight calibrated to 6.3.6's 2.96e-4 m (the thesis states none)
    G = discrete_delay_lqr(plant_636.A, plant_636.B1, plant_636.e("x"), 553.6, 1.0, 0.05, tau)
    assert G.shape == (1, plant_636.n + round(tau / 0.05))
    rng = np.random.default_rng(0)
    for _ in range(2):
        z0 = rng.standard_normal(m.nz) * 0.1
        r = m.solve(z0)
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
        r = m.solve(z, up)
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
        r = m.solve(z)
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


def _preview_lq_rms(a: float, b: float, K: float, h: float, d: int, q: float, N: int,
                    x0: np.ndarray, steps: int, preview: bool) -> float:
    """Unit heave RMS after 10 s of the unconstrained MPC written in closed form.

    Without limits, with the DARE solution P as terminal cost and the boom tip D known over
    the horizon, the MPC is a finite-horizon LQ problem whose Riccati recursion stays at P;
    the boom tip adds an affine term: u_0 = -Kg z_0 - (R + B'PB)^-1 B' (P E D_0 + s_1),
    s_N = 0, s_k = (A - B Kg)' (P E D_k + s_{k+1}). Model and cost from
    :func:`_sampled_regulator`; without preview D = 0 (u = -Kg z, the discrete LQR).
    """
    A, B, E, _, P = _sampled_regulator(a, b, K, h, d, q, 1.0)
    Rh = np.array([[1.0 * h]])
    Minv = np.linalg.inv(Rh + B.T @ P @ B)
    Kg = Minv @ B.T @ P @ A
    Acl = A - B @ Kg
    z = np.zeros(A.shape[0])
    xs = []
    for k in range(steps):
        D = x0[k : k + N] if preview else np.zeros(N)
        s = np.zeros(A.shape[0])
        for j in range(N - 1, 0, -1):
            s = Acl.T @ (P @ E[:, 0] * D[j] + s)
        u = float(-(Kg @ z)[0] - (Minv @ B.T @ (P @ E[:, 0] * D[0] + s))[0])
        z = A @ z + B[:, 0] * u + E[:, 0] * x0[k]
        xs.append(z[0])
    return float(np.sqrt(np.mean(np.array(xs[200:]) ** 2)))


def test_wave_preview_lets_the_regulator_cancel_a_known_wave() -> None:
    # Regulator plant (6.6) of 6.3.6 (boom tip an exogenous input), 0.2 s delay, boom tip
    # x0 = 0.5 sin(0.6 t) m. Without preview the MPC only sees the unit's state and reacts;
    # with the boom tip known 2 s ahead (the whole 40-step horizon) it cancels the wave
    # through the delay (same exactly sampled plant, ZOH boom tip): a factor of more than 20.
    # Independent check: the same unconstrained MPC in closed form (_preview_lq_rms: model,
    # cost and DARE written separately, the preview as the affine term of the LQ
    # recursion) gives the same RMS to 1e-6 relative (both exact; measured 1e-13).
    # Regression values (this project's output): 0.140 m and 0.0021 m, 10 %.
    from cable_ocp.heave import lqr
    from cable_ocp.heave.thesis import A_636, B_636

    p = lqr.regulator_plant(A_636, B_636, 1.0)
    h, N = 0.05, 40
    t = np.arange(0.0, 60.0 + (N + 1) * h, h)
    x0 = 0.5 * np.sin(0.6 * t)
    rms = {}
    for pv in (0.0, 2.0):  # q = 553.6: the weight calibrated to 6.3.6 (any weight would do)
        m = mpc.LinearMPC(p, 0.2, mpc.MPCSettings(horizon=N, q=553.6, preview_time=pv))
        z = np.zeros(m.nz)
        xs = []
        for k in range(int(round(60.0 / h))):
            D = m.preview_correction(z, x0[k : k + N]) if pv > 0 else None
            r = m.solve(z, 0.0, D)
            z = m.model.Ad @ z + m.model.Bd[:, 0] * r.u0 + m.model.Ed[:, 0] * x0[k]
            xs.append(z[0])
        rms[pv] = float(np.sqrt(np.mean(np.array(xs[200:]) ** 2)))  # after 10 s
        ref = _preview_lq_rms(A_636, B_636, 1.0, h, 4, 553.6, N, x0, len(xs), pv > 0)
        assert rms[pv] == pytest.approx(ref, rel=1e-6)
    assert rms[0.0] > 20 * rms[2.0]
    assert rms[0.0] == pytest.approx(0.140, rel=0.1)  # regression value
    assert rms[2.0] == pytest.approx(0.0021, rel=0.1)  # regression value


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
        rq, ri = mq.solve(z, up), mi.solve(z, up)
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
    rq, ri = mq.solve(z, 0.3), mi.solve(z, 0.3)
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
        assert m.solve(rng.standard_normal(m.nz) * 0.01).success
    out, err = capfd.readouterr()
    assert out == "" and err == ""


# -- Independent plants: the limit rows' delay, the nonlinear unit's NLP ----------------

def _boom_tip(t: np.ndarray | float) -> np.ndarray | float:
    """A known boom-tip heave, m: two sinusoids, peak speed about 0.35 m/s."""
    return 0.3 * np.sin(0.6 * t) + 0.15 * np.sin(1.1 * t + 1.0)


def test_speed_limit_alone_holds_on_an_independent_plant_with_the_true_delay() -> None:
    # Regulator plant (6.6) of 6.3.6 (a = 0.8959 s^2, b = 0.1658 s, K = 1 1/s), winch
    # command delayed by 0.2 s (4 samples of 0.05 s), the speed limit 0.25 m/s ALONE (no
    # stroke or command-rate limit that could hide it), the boom tip known over the horizon.
    # The plant is written here, not taken from the MPC's prediction model: the unit
    # a x'' + b x' + x = x0(t) + u with the continuous boom tip, and the winch u' = K (v - u)
    # driven by the command sent d = 4 samples earlier, v = u0_{k-4}, integrated by solve_ivp
    # (DOP853, rtol 1e-12) over each sample. For the first-order winch the speed is largest
    # just after a sample, K (u0_{k-4} - u(t_k)), and it is checked there; the winch is
    # linear and decoupled from the unit, so the limit must hold to the QP's feasibility
    # tolerance: 1e-9 relative. (Writing the newest buffered command u0_{k-1} into the limit
    # rows instead of the applied one lets the true speed exceed the limit by ~12 % here.)
    from scipy.integrate import solve_ivp

    from cable_ocp.heave import lqr
    from cable_ocp.heave.thesis import A_636, B_636

    a, b, K, h, N, d, vmax = A_636, B_636, 1.0, 0.05, 30, 4, 0.25
    m = mpc.LinearMPC(lqr.regulator_plant(a, b, K), d * h,
                      mpc.MPCSettings(horizon=N, sample_time=h, speed_max=vmax))
    assert m.model.d == d and m.nz == 3 + d

    def rhs(t: float, y: np.ndarray, v: float) -> list[float]:
        x, xd, u = y
        return [xd, (_boom_tip(t) + u - x - b * xd) / a, K * (v - u)]

    y = np.zeros(3)
    sent = [0.0] * d  # u0_{k-4} .. u0_{k-1}
    speeds, heave = [], []
    for k in range(300):
        t = k * h
        z = np.concatenate([y, sent])
        r = m.solve(z, 0.0, m.preview_correction(z, _boom_tip(t + h * np.arange(N))))
        assert r.success
        v = sent[0]  # applied over [t, t + h)
        speeds.append(K * (v - y[2]))
        sent = sent[1:] + [r.u0]
        y = solve_ivp(rhs, (t, t + h), y, args=(v,), method="DOP853", rtol=1e-12,
                      atol=1e-13).y[:, -1]
        heave.append(y[0])
    peak = np.max(np.abs(speeds))
    assert peak <= vmax * (1 + 1e-9)
    assert peak >= vmax * (1 - 1e-6)  # the limit was active
    # ... and the loop still compensates: unit heave RMS after 5 s well below the boom tip's
    # (0.237 m RMS).
    assert np.sqrt(np.mean(np.square(heave[100:]))) < 0.3 * 0.237


def test_stroke_limit_alone_holds_for_an_undelayed_second_order_winch() -> None:
    # Second-order winch u'' + 2 zeta w u' + w^2 u = w^2 u0 (w = 1.4 rad/s, zeta = 0.7), no
    # delay, so the stroke at the very next sample already depends on the command being
    # chosen (unlike the first-order winch, whose output between held commands never leaves
    # the commands' range, and unlike a delayed winch, where that row is fixed by commands
    # already sent). Stroke 0.3 m alone, boom tip 0.5 sin(0.6 t) m known over the horizon,
    # plant integrated here by solve_ivp: |u| <= 0.3 m at every sample to 1e-9 relative,
    # and reached.
    from scipy.integrate import solve_ivp

    from cable_ocp.heave import lqr
    from cable_ocp.heave.thesis import A_636, B_636

    a, b, w, zeta, h, N, umax = A_636, B_636, 1.4, 0.7, 0.05, 30, 0.3
    m = mpc.LinearMPC(lqr.regulator_plant(a, b, winch=pl.winch_second(w, zeta)), 0.0,
                      mpc.MPCSettings(horizon=N, sample_time=h, stroke_max=umax))

    def tip(t: np.ndarray | float) -> np.ndarray | float:
        return 0.5 * np.sin(0.6 * t)

    def rhs(t: float, y: np.ndarray, v: float) -> list[float]:
        x, xd, u, ud = y
        return [xd, (tip(t) + u - x - b * xd) / a, ud, w**2 * (v - u) - 2 * zeta * w * ud]

    y = np.zeros(4)
    stroke = []
    for k in range(120):
        t = k * h
        r = m.solve(y, 0.0, m.preview_correction(y, tip(t + h * np.arange(N))))
        assert r.success
        y = solve_ivp(rhs, (t, t + h), y, args=(r.u0,), method="DOP853", rtol=1e-12,
                      atol=1e-13).y[:, -1]
        stroke.append(abs(y[2]))
    assert max(stroke) <= umax * (1 + 1e-9)
    assert max(stroke) >= umax * (1 - 1e-6)


def test_tension_limit_alone_holds_on_an_independent_plant() -> None:
    # The soft tension limit alone (no other limit), exact when feasible (L1 penalty): the
    # regulator plant (6.6) of 6.3.6 with the 6.2.6 unit's mass (125 t, static tension 50 kN:
    # cable stiffness m/a = 139.5 kN/m), 0.2 s delay, T >= 45 kN. The unit starts 0.5 m
    # high at rest in equilibrium (winch paid in 0.5 m, all buffered commands 0.5 m) in
    # still water; lowering it quickly needs slack in the cable, which the limit bounds.
    # The plant is written here (unit a x'' + b x' + x = u, winch u' = K (u0_{k-4} - u),
    # solve_ivp) and the tension T = T0 + (m/a)(x0 + u - x) checked at the samples: the
    # limit must hold to 1e-9 relative and be reached (else this proves nothing). A stretch
    # row with the wrong sign of x, or a limit turned into a floor above T0, fails here.
    from scipy.integrate import solve_ivp

    from cable_ocp.heave import lqr
    from cable_ocp.heave.thesis import A_636, B_636

    a, b, K, h, d, mass, t0, tmin = A_636, B_636, 1.0, 0.05, 4, 125000.0, 50000.0, 45000.0
    m = mpc.LinearMPC(lqr.regulator_plant(a, b, K), d * h, mpc.MPCSettings(
        horizon=30, sample_time=h, tension_min=tmin, unit_mass=mass, static_tension=t0))

    def rhs(_t: float, y: np.ndarray, v: float) -> list[float]:
        x, xd, u = y
        return [xd, (u - x - b * xd) / a, K * (v - u)]

    y = np.array([0.5, 0.0, 0.5])
    sent = [0.5] * d
    tension, heave = [], []
    for k in range(200):
        z = np.concatenate([y, sent])
        r = m.solve(z, 0.0, np.zeros(30))
        assert r.success
        tension.append(t0 + mass / a * (y[2] - y[0]))
        v = sent[0]
        sent = sent[1:] + [r.u0]
        y = solve_ivp(rhs, (k * h, (k + 1) * h), y, args=(v,), method="DOP853", rtol=1e-12,
                      atol=1e-13).y[:, -1]
        heave.append(y[0])
    assert min(tension) >= tmin * (1 - 1e-9)
    assert min(tension) <= tmin * (1 + 1e-6)  # the limit was reached
    assert abs(heave[-1]) < 0.05  # and the unit was brought down


def _sampled_regulator(a: float, b: float, K: float, h: float, d: int, q: float, r: float
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Independent exact sampling of the delayed regulator plant (6.6) and of its LQR cost.

    State z = [x, x', u, u0_{k-d} .. u0_{k-1}]; the applied command v = u0_{k-d} and the boom
    tip x0 held over the sample. Transition by scipy ``expm``; the stage cost
    ``int_0^h q x^2 dt`` (without the boom tip, as the MPC's cost) by adaptive quadrature
    (``quad_vec``) of ``e^{F^T t} Q e^{F t}``, plus ``r h u0_k^2``; terminal weight from
    scipy's DARE. Returns (Ad, Bd, Ed, Qz, P), stage cost ``z^T Qz z + r h u^2``.
    """
    from scipy import integrate, linalg

    F = np.zeros((5, 5))  # [x, x', u, v, x0]' with v and x0 held
    F[:3, :3] = [[0.0, 1.0, 0.0], [-1 / a, -b / a, 1 / a], [0.0, 0.0, -K]]
    F[2, 3] = K
    F[1, 4] = 1 / a
    E = linalg.expm(F * h)
    nz = 3 + d
    Ad = np.zeros((nz, nz))
    Ad[:3, :3] = E[:3, :3]
    Ad[:3, 3] = E[:3, 3]
    for i in range(d - 1):
        Ad[3 + i, 4 + i] = 1.0
    Bd = np.zeros((nz, 1))
    Bd[-1, 0] = 1.0
    Ed = np.zeros((nz, 1))
    Ed[:3, 0] = E[:3, 4]
    F4 = F[:4, :4]
    Qa = np.zeros((4, 4))
    Qa[0, 0] = q
    W, _ = integrate.quad_vec(lambda t: linalg.expm(F4.T * t) @ Qa @ linalg.expm(F4 * t),
                              0.0, h, epsabs=0.0, epsrel=1e-13)
    S = np.zeros((4, nz))
    S[:3, :3] = np.eye(3)
    S[3, 3] = 1.0
    Qz = S.T @ (0.5 * (W + W.T)) @ S
    P = linalg.solve_discrete_are(Ad, Bd, Qz, np.array([[r * h]]))
    return Ad, Bd, Ed, Qz, P


def _opti_nmpc(a: float, bq: float, K: float, h: float, d: int, N: int, Qz: np.ndarray,
               P: np.ndarray, rh: float, vmax: float, umax: float):  # noqa: ANN202
    """The NLP of the nonlinear-unit MPC, written separately with ``casadi.Opti``.

    Unit (Huang 1992, eq. (6.3)): a x'' + bq |x'| x' + x = x0 + u, |x'| smoothed as
    sqrt(x'^2 + 1e-6) (as documented for the MPC); winch u' = K (v - u); v the command sent
    d samples earlier; the boom tip x0 = D_k held over sample k. RK4 with 2 substeps per
    sample. Limits: winch speed K (v_k - u_k) for k >= d (the first row a decision can
    change), stroke |u_k| for k >= d + 1 and |u0| <= umax on the commands.
    Returns a function (z0, D) -> (planned commands, largest planned |speed|).
    """
    import casadi as cs

    def f(s: cs.MX, v: cs.MX, x0: cs.MX) -> cs.MX:
        x, xd, u = s[0], s[1], s[2]
        return cs.vertcat(xd, (x0 + u - x - bq * xd * cs.sqrt(xd**2 + 1e-6)) / a, K * (v - u))

    opti = cs.Opti()
    X = opti.variable(3, N + 1)
    U = opti.variable(N)
    z0 = opti.parameter(3 + d)
    Dp = opti.parameter(N)
    opti.subject_to(X[:, 0] == z0[:3])
    buf = [z0[3 + i] for i in range(d)] + [U[k] for k in range(N)]  # v_k = buf[k]
    J = 0
    for k in range(N):
        s = X[:, k]
        hh = h / 2
        for _ in range(2):
            k1 = f(s, buf[k], Dp[k])
            k2 = f(s + hh / 2 * k1, buf[k], Dp[k])
            k3 = f(s + hh / 2 * k2, buf[k], Dp[k])
            k4 = f(s + hh * k3, buf[k], Dp[k])
            s = s + hh / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        opti.subject_to(X[:, k + 1] == s)
        zk = cs.vertcat(X[:, k], *buf[k : k + d])
        J += cs.bilin(cs.DM(Qz), zk, zk) + rh * U[k] ** 2
        if k >= d:
            opti.subject_to(opti.bounded(-vmax, K * (buf[k] - X[2, k]), vmax))
    for k in range(d + 1, N + 1):
        opti.subject_to(opti.bounded(-umax, X[2, k], umax))
    opti.subject_to(opti.bounded(-umax, U, umax))
    zN = cs.vertcat(X[:, N], *buf[N : N + d])
    J += cs.bilin(cs.DM(P), zN, zN)
    opti.minimize(J)
    opti.solver("ipopt", {"print_time": False},
                {"print_level": 0, "sb": "yes", "tol": 1e-10})

    def solve(z: np.ndarray, D: np.ndarray) -> float:
        opti.set_value(z0, z)
        opti.set_value(Dp, D)
        sol = opti.solve()
        speed = [sol.value(K * (buf[k] - X[2, k])) for k in range(d, N)]
        return np.asarray(sol.value(U)).ravel(), float(np.max(np.abs(speed)))

    return solve


def test_nonlinear_unit_mpc_matches_an_independent_nlp_and_closes_the_loop() -> None:
    # The IPOPT MPC on the quadratic-damping unit (Huang 1992, eq. (6.3), Fig. 6.13:
    # a = 7.326944 s^2, b_q = 0.0719096 s^2/m; K = 1 1/s, 0.2 s delay), boom tip
    # 1.5 sin(0.45 t) m known over the horizon, speed limit 0.5 m/s (the boom tip moves at up
    # to 0.675 m/s) and stroke 3 m. The cost is the exactly sampled LQR cost of the linear
    # design model (6.2) with b = 0.1906759 s, as the MPC documents.
    # (1) At the first 6 closed-loop states, where the speed limit is active in the plan, and
    # at 4 random states with the unit moving fast, its planned moves equal those of the same
    # NLP written separately with casadi.Opti (cost matrices computed here by quadrature and
    # scipy's DARE): both IPOPT on the same smooth problem, measured agreement ~1e-9 m
    # (tol 1e-10); 1e-6 m. The whole plan is compared: where the speed limit is active on the
    # first decidable row, the first move is fixed by the limit alone, whatever the unit.
    # (2) The loop closed on the true (6.3) unit (exact |x'| x', solve_ivp) with the true
    # delayed command keeps the speed limit at the samples to 1e-6 relative (IPOPT relaxes
    # bounds by 1e-8 relative, bound_relax_factor; its RK4 winch prediction errs by ~1e-10)
    # and cuts the heave RMS over 2.5-5 s to under a quarter of the passive unit's (winch
    # held still; measured ratio ~0.1 at this resonance-near excitation).
    from scipy.integrate import solve_ivp

    from cable_ocp.heave import lqr
    from cable_ocp.heave.thesis import A_626_NL, B_626, B_626_NL

    a, bq, b, K, h, d, N, vmax, umax = A_626_NL, B_626_NL, B_626, 1.0, 0.05, 4, 16, 0.5, 3.0
    # q = 553.6: the weight calibrated to 6.3.6's 2.96e-4 m, reused here (6.2.6 states none)
    m = mpc.LinearMPC(lqr.regulator_plant(a, b, K), d * h, mpc.MPCSettings(
        horizon=N, sample_time=h, q=553.6, r=1.0, solver="ipopt", nonlinear_b=bq,
        speed_max=vmax, stroke_max=umax))
    _, _, _, Qz, P = _sampled_regulator(a, b, K, h, d, 553.6, 1.0)
    np.testing.assert_allclose(m.Qz, Qz, rtol=1e-9, atol=1e-12 * np.abs(Qz).max())
    ref = _opti_nmpc(a, bq, K, h, d, N, Qz, P, 1.0 * h, vmax, umax)

    def tip(t: np.ndarray | float) -> np.ndarray | float:
        return 1.5 * np.sin(0.45 * t)

    def rhs(t: float, y: np.ndarray, v: float) -> list[float]:
        x, xd, u = y
        return [xd, (tip(t) + u - x - bq * abs(xd) * xd) / a, K * (v - u)]

    y = np.zeros(3)
    sent = [0.0] * d
    speeds, heave = [], []
    for k in range(100):
        t = k * h
        z = np.concatenate([y, sent])
        D = m.preview_correction(z, tip(t + h * np.arange(N)))
        r = m.solve(z, 0.0, D)
        assert r.success
        if k < 6:
            u_ref, speed_ref = ref(z, D)
            np.testing.assert_allclose(r.plan, u_ref, rtol=0, atol=1e-6)
            assert speed_ref >= vmax * (1 - 1e-6)  # the speed limit is active in the plan
        v = sent[0]
        speeds.append(K * (v - y[2]))
        sent = sent[1:] + [r.u0]
        y = solve_ivp(rhs, (t, t + h), y, args=(v,), method="DOP853", rtol=1e-12,
                      atol=1e-13).y[:, -1]
        heave.append(y[0])
    assert np.max(np.abs(speeds)) <= vmax * (1 + 1e-6)
    # (1') ... and at states where the unit moves fast (x' up to 0.8 m/s), where the damping
    # term b_q |x'| x' matters (the first closed-loop states start from rest).
    rng = np.random.default_rng(3)
    for _ in range(4):
        z = np.concatenate([rng.uniform(-1, 1, 3) * [1.0, 0.8, 1.0], rng.uniform(-1, 1, d)])
        D = tip(rng.uniform(0, 20) + h * np.arange(N))
        r = m.solve(z, 0.0, D)
        assert r.success
        np.testing.assert_allclose(r.plan, ref(z, D)[0], rtol=0, atol=1e-6)
    passive = solve_ivp(rhs, (0.0, 100 * h), np.zeros(3), args=(0.0,), method="DOP853",
                        rtol=1e-12, atol=1e-13, t_eval=h * np.arange(1, 101)).y[0]
    assert np.sqrt(np.mean(np.square(heave[50:]))) < 0.25 * np.sqrt(np.mean(passive[50:] ** 2))


def test_nonlinear_unit_mpc_reduces_to_the_linear_mpc_as_b_quadratic_vanishes() -> None:
    # (6.3) replaces the linear damping b x' of (6.2) by b_q |x'| x', so with b_q -> 0 it is
    # (6.2) with b = 0. On that plant (6.3.6's a, K = 1, 0.2 s delay, speed limit 0.3 m/s)
    # the IPOPT MPC with b_q = 1e-12 (its RK4 shooting model, 2 substeps) and the condensed QP
    # MPC (exact ZOH) give the same first moves at random states with the boom tip known:
    # RK4's error at h/2 = 0.025 s on this slow plant is ~1e-11, IPOPT's ~1e-9; 1e-7 m.
    from cable_ocp.heave import lqr
    from cable_ocp.heave.thesis import A_636

    p = lqr.regulator_plant(A_636, 0.0, 1.0)
    st = {"horizon": 20, "sample_time": 0.05, "speed_max": 0.3, "stroke_max": 2.0}
    mq = mpc.LinearMPC(p, 0.2, mpc.MPCSettings(solver="qpoases", **st))
    mi = mpc.LinearMPC(p, 0.2, mpc.MPCSettings(
        solver="ipopt", nonlinear_b=1e-12, solver_options={"ipopt": {"tol": 1e-12}}, **st))
    rng = np.random.default_rng(5)
    active = 0
    for _ in range(6):
        z = rng.standard_normal(mq.nz) * np.array([0.3, 0.3, 0.3, 0.2, 0.2, 0.2, 0.2])
        D = 0.8 * np.sin(0.6 * 0.05 * np.arange(20) + rng.uniform(0, 6))
        rq, ri = mq.solve(z, 0.0, D), mi.solve(z, 0.0, D)
        assert rq.success and ri.success
        assert ri.u0 == pytest.approx(rq.u0, abs=1e-7)
        np.testing.assert_allclose(ri.plan, rq.plan, atol=1e-6)
        active += np.max(np.abs(mq.Ac[:, :20] @ rq.plan + mq.Cz @ z + mq.CD @ D)) > 0.3 - 1e-6
    assert active >= 3  # the speed limit was active in most of them
