"""The roles of the heave loop (issue 21, item 6): the delay line, the estimators, the
controller interface, the MPC's own delay buffer and the one closed loop for any plant."""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.heave import mpc
from cable_ocp.heave import plant as pl
from cable_ocp.heave.closed_loop import make_wave, run_loop
from cable_ocp.heave.controllers import Controller, StateFeedback
from cable_ocp.heave.delay import DelayLine
from cable_ocp.heave.design_loop import build_models, wave_realisation
from cable_ocp.heave.discrete import discretize_delayed, discretize_noise
from cable_ocp.heave.estimators import FullState, KalmanFilter, Observation, kalman_gain
from cable_ocp.heave.loop_plants import ModelLine, UnitWinchPlant, WinchedLine
from cable_ocp.scene.heave import load_scene

ROOT = Path(__file__).resolve().parents[2]
HEAVE = ROOT / "problems" / "heave"


def test_delay_line_applies_the_command_of_d_samples_before() -> None:
    # A shift register: copies, so exact equality.
    line = DelayLine(3)
    applied = [line.push(float(k + 1)) for k in range(6)]
    assert applied == [0.0, 0.0, 0.0, 1.0, 2.0, 3.0]
    assert line.buffer.tolist() == [4.0, 5.0, 6.0] and line.last == 6.0
    line.reset()
    assert line.buffer.tolist() == [0.0, 0.0, 0.0] and line.last == 0.0
    assert DelayLine(0).push(2.5) == 2.5


class _Sequence(Controller):
    """Commands 0.01 k at sample k (m): each one different, to follow through the delay."""

    name = "sequence"

    def __init__(self) -> None:
        super().__init__()
        self.k = 0

    def reset(self) -> None:
        super().reset()
        self.k = 0

    def step(self, obs: Observation) -> float:  # noqa: ARG002
        self.k += 1
        return 0.01 * self.k


def _unit_plant(n: int) -> tuple[Any, int]:
    sc = load_scene(HEAVE / "ex_6_3_6.toml")
    p = build_models(sc).plant
    m = sc.simulation.substeps
    h = sc.controller.sample_time
    t, x0, sea = wave_realisation(p, (n + 1) * h, h / m, seed=3)
    return UnitWinchPlant(sc, p, t, x0, sea, np.zeros(n + 1), n), m


def _line_plant(n: int) -> tuple[Any, int]:
    sc = load_scene(HEAVE / "ex_6_3_6.toml")
    h, m = sc.controller.sample_time, 5
    t = np.arange(n * m + 1) * (h / m)
    wave = make_wave(t, 0.5 * np.sin(0.6 * t), h, m, n, lambda s: np.full_like(s, 300.0), 0.0)
    u = sc.unit
    line = ModelLine(u.a, u.b, u.b_quadratic, False, m, h / m, u.mass, 5e4, 7e4)
    return WinchedLine(sc, line, wave, np.zeros((n + 1, 3))), m


@pytest.mark.parametrize("make", [_unit_plant, _line_plant])
def test_every_plant_applies_the_command_exactly_tau_late(make: Any) -> None:
    """On both kinds of plant the loop's delay line applies command k over every sub-step of
    sample k + d (tau = 0.2 s = 4 samples of 0.05 s, ex_6_3_6.toml): on the sub-step grid
    the delay is exactly d m sub-steps. Copies of the commands: exact equality."""
    n, d = 40, 4
    plant, m = make(n)
    run = run_loop(plant, _Sequence(), n, bound=1e6)
    assert run.stop is None
    cmds = run.commands
    assert np.array_equal(cmds, 0.01 * np.arange(1, n + 1))
    k = np.arange(n * m) // m
    expected = np.where(k >= d, cmds[np.maximum(k - d, 0)], 0.0)
    assert np.array_equal(run.trace.u0[:-1], expected)
    assert run.trace.u0[-1] == run.trace.u0[-2]


def test_mpc_keeps_its_own_delay_buffer(plant_636: pl.HeavePlant) -> None:
    """``step`` with the plant's state alone gives the moves that ``solve`` gives on the
    shift-register state the caller keeps (the same numbers: bitwise), including the last
    command for the command-rate limit; after ``reset`` the run repeats (DAQP from its cold
    working set again: 1e-12 m)."""
    st = mpc.MPCSettings(horizon=20, stroke_max=0.6, speed_max=0.5, command_rate_max=0.05)
    own, kept = mpc.LinearMPC(plant_636, 0.2, st), mpc.LinearMPC(plant_636, 0.2, st)
    lam, V = np.linalg.eigh(discretize_noise(plant_636.A, plant_636.B2, np.pi, 0.05))
    Lw = V * np.sqrt(np.clip(lam, 0.0, None))

    def run(m_own: mpc.LinearMPC, m_kept: mpc.LinearMPC | None) -> list[float]:
        rng = np.random.default_rng(4)
        z = np.zeros(own.nz)
        up, moves = 0.0, []
        for _ in range(120):
            r = m_own.step(z[: own.n])
            if m_kept is not None:
                q = m_kept.solve(z, up)
                assert r.u0 == q.u0 and np.array_equal(r.plan, q.plan)
            assert np.array_equal(m_own.delay.buffer, np.append(z[own.n + 1:], r.u0))
            up = r.u0
            moves.append(r.u0)
            z = own.model.Ad @ z + own.model.Bd[:, 0] * r.u0
            z[: own.n] += 3.0 * Lw @ rng.standard_normal(own.n)
        return moves

    first = run(own, kept)
    assert max(abs(u) for u in first) > 0.1  # the limits were in play
    own.reset()
    assert not own.delay.buffer.any() and own.delay.last == 0.0
    np.testing.assert_allclose(run(own, None), first, rtol=0, atol=1e-12)
    with pytest.raises(CableOCPError, match="keeps its own delay buffer"):
        own.step(np.zeros(own.nz))


def test_kalman_gain_is_the_current_estimators_and_dlqe_the_predictors(
        plant_636: pl.HeavePlant) -> None:
    """The gain of :func:`kalman_gain` is ``M = P C^T (C P C^T + R)^-1`` with ``P`` the
    a-priori covariance: checked against the Riccati recursion iterated to convergence
    (independent of the DARE solver), and python-control's ``dlqe`` gives the predictor's
    ``A M`` (the pitfall). Both to 1e-8 relative (the DARE solvers agree to ~1e-10)."""
    import control as ct

    h = 0.05
    mdl = discretize_delayed(plant_636.A, plant_636.B1, h, 0.2)
    A, nz, n = mdl.Ad, mdl.Ad.shape[0], plant_636.n
    Q = np.zeros((nz, nz))
    Q[:n, :n] = discretize_noise(plant_636.A, plant_636.B2, np.pi, h)
    Q += 1e-12 * np.eye(nz)
    C = np.zeros((1, nz))
    C[0, :n] = plant_636.e("x")
    R = np.array([[1e-4]])
    M = kalman_gain(A, C, Q, R)
    P = np.eye(nz)
    for _ in range(20000):
        P = A @ (P - P @ C.T @ np.linalg.solve(C @ P @ C.T + R, C @ P)) @ A.T + Q
    M_it = P @ C.T @ np.linalg.inv(C @ P @ C.T + R)
    np.testing.assert_allclose(M, M_it, rtol=1e-8, atol=1e-8 * np.max(np.abs(M)))
    L, _, _ = ct.dlqe(A, np.eye(nz), C, Q, R)
    np.testing.assert_allclose(np.asarray(L), A @ M, rtol=1e-8,
                               atol=1e-8 * np.max(np.abs(A @ M)))


def test_estimators_keep_the_delay_buffer_of_the_commands_sent(plant_636: pl.HeavePlant
                                                               ) -> None:
    """The estimate's buffer states are the commands sent, exactly (copies), for the full-state
    estimator and for the Kalman filter (whose gain on them is not zero: the 1e-14
    regularisation of the noise), and the Kalman filter is the current estimator: after the
    update its depth estimate moves by ``M_x (y - C x_pred)`` from the prediction."""
    h, d = 0.05, 4
    mdl = discretize_delayed(plant_636.A, plant_636.B1, h, 0.2)
    nz, n = mdl.Ad.shape[0], plant_636.n
    Q = np.zeros((nz, nz))
    Q[:n, :n] = discretize_noise(plant_636.A, plant_636.B2, np.pi, h)
    Q += 1e-14 * np.eye(nz) * np.max(np.abs(Q))
    C = np.zeros((1, nz))
    C[0, :n] = plant_636.e("x")
    M = kalman_gain(mdl.Ad, C, Q, np.array([[1e-4]]))
    kf, fs = KalmanFilter((mdl.Ad, mdl.Bd, M), C, n, d), FullState(n, d)
    rng = np.random.default_rng(1)
    sent: list[float] = []
    for k in range(12):
        y = np.array([0.1 * np.sin(k)])
        xp = kf.xp.copy()
        xh = kf.update(Observation(y=y))
        assert xh[0] == pytest.approx(xp[0] + M[0, 0] * (y[0] - C[0] @ xp), rel=1e-12)
        full = fs.update(Observation(y=y, state=rng.standard_normal(n)))
        past = ([0.0] * d + sent)[-d:]
        assert xh[n:].tolist() == past and full[n:].tolist() == past
        u0 = float(rng.standard_normal())
        kf.predict(u0)
        fs.predict(u0)
        sent.append(u0)


def test_controllers_report_their_energy_index() -> None:
    """A fixed gain reports ``||G||_F``; a schedule over several lengths none (its gain
    changes with the length); the interface's reset clears the statistics."""
    from cable_ocp.heave.design import design_table

    sc = load_scene(HEAVE / "ex_6_3_6.toml")
    sd = dataclasses.replace(sc, unit=dataclasses.replace(sc.unit, a=1.0, b=0.05))
    tab, _ = design_table(sd, np.array([100.0, 200.0]), np.array([1.0, 2.0]),
                          np.array([0.05, 0.08]))
    G = tab.G[0]
    fixed = StateFeedback("lqr", G, FullState(tab.n, tab.nz - tab.n))
    assert fixed.energy_index == float(np.sqrt(np.sum(G**2)))
    assert StateFeedback("lqr_scheduled", tab, tab.kalman_filter(3)).energy_index is None
    np.testing.assert_allclose(StateFeedback("s", tab, tab.kalman_filter(3)).gain_at(150.0),
                               0.5 * (tab.G[0] + tab.G[1]), rtol=1e-12, atol=1e-15)
    fixed.solve_times.append(1.0)
    fixed.failures = 2
    fixed.reset()
    assert fixed.solve_times == [] and fixed.failures == 0
