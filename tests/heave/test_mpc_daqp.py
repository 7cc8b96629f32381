"""The DAQP backend of the MPC: same moves as the condensed qpOASES QP, failures, errors."""

from __future__ import annotations

import sys

import numpy as np
import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.heave import mpc
from cable_ocp.heave import plant as pl
from cable_ocp.heave.discrete import discretize_noise

# Limits tight enough to be active under 3x the 6.3.6 sea (stroke, speed, command rate), and a
# tension limit (40 kN of a 50 kN static tension) that the soft constraint has to give way on.
LIMITS = {"stroke_max": 0.2, "speed_max": 0.15, "command_rate_max": 0.01,
          "tension_min": 40000.0, "unit_mass": 125000.0, "static_tension": 50000.0}


def _factor(Q: np.ndarray) -> np.ndarray:
    lam, V = np.linalg.eigh(Q)
    return V * np.sqrt(np.clip(lam, 0.0, None))


def _row_kinds(m: mpc.LinearMPC, iu: int) -> np.ndarray:
    """Kind of every limit row: 0 stroke, 1 speed, 2 command rate, 3 tension (soft)."""
    kinds = []
    for r in m.rows:
        if r.slack:
            kinds.append(3)
        elif r.cp != 0.0:
            kinds.append(2)
        elif r.cu == 0.0 and np.count_nonzero(r.cz) == 1 and r.cz[iu] == 1.0:
            kinds.append(0)
        else:
            kinds.append(1)
    return np.array(kinds)


@pytest.mark.parametrize("horizon,steps", [(20, 200), (50, 200)])
def test_daqp_moves_equal_qpoases_with_active_limits_and_delay(plant_636: pl.HeavePlant,
                                                               horizon: int, steps: int) -> None:
    # Both solve the same condensed QP (0.2 s delay as a 4-sample shift register, stroke,
    # speed and command-rate rows, soft tension rows with slacks). Along a closed loop driven
    # by the qpOASES moves under 3x the sea, DAQP at the same state and previous command must
    # give the same first move and plan to 1e-8 m (the target; both are active-set solvers
    # that end on an exact solve of the same optimality system, and agree to ~1e-13 here).
    # The run must actually activate every kind of limit in the plans (counted from the
    # qpOASES solution) and the tension slack, and DAQP must take both of its paths (the QP
    # without tension rows alone, and the whole QP when a tension row binds), or this test
    # proves little.
    mq = mpc.LinearMPC(plant_636, 0.2, mpc.MPCSettings(horizon=horizon, solver="qpoases",
                                                       **LIMITS))
    md = mpc.LinearMPC(plant_636, 0.2, mpc.MPCSettings(horizon=horizon, solver="daqp",
                                                       **LIMITS))
    full_calls = []
    full_solve = md._daqp.full.solve
    md._daqp.full.solve = lambda g, c: full_calls.append(1) or full_solve(g, c)
    iu = plant_636.blocks["winch"].start
    kinds = _row_kinds(mq, iu)
    rng = np.random.default_rng(1)
    Lw = _factor(discretize_noise(plant_636.A, plant_636.B2, np.pi, 0.05))
    z = np.zeros(mq.nz)
    up = 0.0
    du0, dplan, slack_steps = [], [], 0
    active_kinds = np.zeros(4, dtype=int)
    for _ in range(steps):
        rq, rd = mq.solve(z, up), md.solve(z, up)
        assert rq.success and rd.success
        du0.append(abs(rq.u0 - rd.u0))
        dplan.append(float(np.max(np.abs(rq.plan - rd.plan))))
        slack_steps += rq.max_slack > 1e-9
        # Active rows of the qpOASES plan: hard rows at a bound (to 1e-9, in m or m/s),
        # tension rows at or below their limit (the slack takes the rest).
        val = mq.Ac[:, : mq.N] @ rq.plan + mq.Cz @ z + mq.Cup * up
        on = (kinds < 3) & ((np.abs(val - mq.lb0) < 1e-9) | (np.abs(val - mq.ub0) < 1e-9))
        on |= (kinds == 3) & (val < mq.lb0 + 1e-9)
        active_kinds += np.bincount(kinds[on], minlength=4) > 0
        # The stroke is held by the command bounds |u0| <= stroke_max (the stroke rows are
        # implied by them, LinearMPC): count a command at its bound as an active stroke limit.
        active_kinds[0] += not on[kinds == 0].any() and \
            np.max(np.abs(rq.plan)) > LIMITS["stroke_max"] - 1e-9
        up = rq.u0
        z = mq.model.Ad @ z + mq.model.Bd[:, 0] * rq.u0
        z[: plant_636.n] += 3.0 * Lw @ rng.standard_normal(plant_636.n)
    assert max(du0) < 1e-8
    assert max(dplan) < 1e-8
    assert np.all(active_kinds >= 5), active_kinds  # each kind of limit active on >= 5 steps
    assert slack_steps >= 5
    assert 5 <= len(full_calls) <= steps - 5


def test_parametric_maps_give_the_gradient_and_row_offsets(plant_636: pl.HeavePlant) -> None:
    # The step assembles [g; c] with one product of the stacked maps; it must equal the
    # separate products g = Gz z0 + Gd D + g_slack, c = Cz z0 + CD D + Cup u_prev (to
    # round-off, 1e-12 relative).
    m = mpc.LinearMPC(plant_636, 0.2, mpc.MPCSettings(horizon=15, **LIMITS))
    rng = np.random.default_rng(3)
    z, D, up = rng.standard_normal(m.nz), rng.standard_normal(m.N), 0.37
    v = m._Pz @ z + m._PD @ D + up * m._Pu + m._p0
    g = m.Gz @ z + m.Gd @ D + m.g_slack
    c = m.Cz @ z + m.CD @ D + m.Cup * up
    np.testing.assert_allclose(v[: m._nv], g, rtol=1e-12, atol=1e-12 * np.max(np.abs(g)))
    np.testing.assert_allclose(v[m._nv :], c, rtol=1e-12, atol=1e-12 * np.max(np.abs(c)))


def test_infeasible_step_reports_failure_and_falls_back_on_the_plan(plant_636: pl.HeavePlant
                                                                    ) -> None:
    # First-order winch, 4-sample delay: the speed at the first free sample is
    # K (U_0 - u_4) with u_4 fixed by the past. The winch is at u = 0.5 m with the buffer full
    # of 0.5 m, so |speed| <= 0.1 m/s needs U_0 in [0.4, 0.6] m, while |U_0 - u_prev| <= 0.01 m
    # with u_prev = 0 needs U_0 in [-0.01, 0.01] m: infeasible. Both solvers must report
    # failure (no exception) and return the previous plan shifted by one sample. (With the
    # tension limit DAQP tries the QP without tension rows, then the whole QP.)
    st = {"horizon": 10, "speed_max": 0.1, "command_rate_max": 0.01, "tension_min": 5000.0,
          "unit_mass": 125000.0, "static_tension": 50000.0}
    for solver in ("daqp", "qpoases"):
        m = mpc.LinearMPC(plant_636, 0.2, mpc.MPCSettings(solver=solver, **st))
        first = m.solve(np.zeros(m.nz), 0.0)
        assert first.success
        z = np.zeros(m.nz)
        z[plant_636.blocks["winch"].start] = 0.5
        z[m.n :] = 0.5
        r = m.solve(z, 0.0)
        assert not r.success, solver
        np.testing.assert_array_equal(r.plan, np.concatenate([first.plan[1:],
                                                              first.plan[-1:]]))


def test_daqp_missing_or_bad_options_raise_clear_errors(plant_636: pl.HeavePlant,
                                                       monkeypatch: pytest.MonkeyPatch) -> None:
    st = mpc.MPCSettings(horizon=5, solver="daqp", solver_options={"tolerance": 1e-9})
    with pytest.raises(CableOCPError, match="not DAQP settings.*primal_tol"):
        mpc.LinearMPC(plant_636, 0.0, st)
    monkeypatch.setitem(sys.modules, "daqp", None)  # import daqp -> ImportError
    with pytest.raises(CableOCPError, match="pip install daqp"):
        mpc.LinearMPC(plant_636, 0.0, mpc.MPCSettings(horizon=5, solver="daqp"))


def test_daqp_two_stage_steps_print_nothing(plant_636: pl.HeavePlant,
                                            capfd: pytest.CaptureFixture) -> None:
    # Library code never prints: both DAQP workspaces (the QP without tension rows, and the
    # whole QP once the tension binds), captured at the file-descriptor level.
    m = mpc.LinearMPC(plant_636, 0.2, mpc.MPCSettings(horizon=10, solver="daqp", **LIMITS))
    full_calls = []
    full_solve = m._daqp.full.solve
    m._daqp.full.solve = lambda g, c: full_calls.append(1) or full_solve(g, c)
    z = np.zeros(m.nz)
    assert m.solve(z).success
    # Winch at u = -0.15 m with the buffered commands there too: the stretch x0 + u - x stays
    # at -0.15 m for the next samples, below the -0.072 m that the 40 kN limit allows.
    z[plant_636.blocks["winch"].start] = -0.15
    z[m.n :] = -0.15
    r = m.solve(z, -0.15)
    assert r.success and r.max_slack > 0
    assert full_calls
    out, err = capfd.readouterr()
    assert out == "" and err == ""
