"""Huang's scheme (5.21) is not unconditionally stable: its transverse part is explicit.

Huang (1992) 5.5 finds all amplification factors |lambda| <= 1 after setting delta B =
delta C = 0, i.e. dropping the tension times the perturbed segment direction: the
transverse restoring force. With it, a transverse perturbation of the taut chain obeys the
explicit central difference m (y^{j+1} - 2 y^j + y^{j-1}) = -dt^2 omega^2 m y^j, whose
amplification solves lambda^2 - (2 - omega^2 dt^2) lambda + 1 = 0: bounded for
omega dt <= 2, growing by ((b - 2) + sqrt((b - 2)^2 - 4)) / 2 per step (b = omega^2 dt^2)
beyond. For the highest mode of a fixed-fixed chain omega = 2 sqrt(T / (m l_s)) sin((N - 1)
pi / (2 N)), so the limit is dt ~ sqrt(m l_s / T). The axial part is implicit and decays
as Huang's lambda_{5,6} say: |lambda|^2 = 1 / (1 + a), a = 4 sin^2(beta / 2) EA dt^2 / (l m).

The tests run the implementation of (5.21) as printed (:mod:`cable_ocp.dynamics.lumped_thesis`)
and measure growth per step, against these predictions; and check that the project's
implicit midpoint scheme stays bounded at the same and 100 times larger steps.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from cable_ocp.dynamics.lumped import LumpedMassModel
from cable_ocp.dynamics.lumped_params import uniform_params
from cable_ocp.dynamics.lumped_run import run
from cable_ocp.dynamics.lumped_thesis import run_thesis, thesis_step

N, LENGTH, EA, MU, TENSION = 20, 10.0, 1.0e6, 1.0, 100.0
EPS = TENSION / EA
LS = LENGTH / N * (1.0 + EPS)  # stretched spacing
NODE_M = MU * LENGTH / N
OMEGA_T = 2.0 * math.sqrt(TENSION / (NODE_M * LS)) * math.sin((N - 1) * math.pi / (2 * N))


def _chain() -> LumpedMassModel:
    p = uniform_params(LENGTH, N, axial_stiffness=EA, diameter=0.01, mass_per_length=MU,
                       weight_in_water=0.0, top_position=[0.0, 0.0, LENGTH * (1.0 + EPS)],
                       end_a_position=[0.0, 0.0, 0.0], water_density=0.0, gravity=0.0)
    return LumpedMassModel(p)


def _perturbed(component: int, amp: float) -> np.ndarray:
    """Straight chain plus the highest mode (alternating signs) in one component."""
    i = np.arange(1, N)
    x = np.zeros((N - 1, 3))
    x[:, 2] = i * LS
    x[:, component] += amp * np.sin((N - 1) * np.pi * i / N)
    return x.reshape(-1)


def _predicted_growth(omega: float, dt: float) -> float:
    b = (omega * dt) ** 2
    return float(max(abs(np.roots([1.0, -(2.0 - b), 1.0]))))


@pytest.mark.parametrize("factor", [1.02, 1.1, 1.5, 3.0])
def test_transverse_growth_above_the_limit_matches_explicit_central_difference(
        factor: float) -> None:
    """Above dt_c = 2 / omega_max the highest transverse mode grows by the predicted factor
    per step (to 0.5 %: measured over steps where the amplitude stays below 1e-7 m, so that
    the perturbation is linear; starting amplitude 1e-13 m)."""
    m = _chain()
    step = thesis_step(m)
    dt = factor * 2.0 / OMEGA_T
    x0 = _perturbed(1, 1e-13)
    xp, xn = x0.copy(), x0.copy()
    amps = []
    for j in range(60):
        xp, xn = xn, step(xp, xn, j * dt, dt)
        amps.append(np.abs(xn.reshape(-1, 3)[:, 1]).max())
        if amps[-1] > 1e-7:
            break
    amps = np.array(amps)
    j1 = len(amps) - 2
    j0 = max(1, j1 - 10)
    growth = (amps[j1] / amps[j0]) ** (1.0 / (j1 - j0))
    assert growth == pytest.approx(_predicted_growth(OMEGA_T, dt), rel=5e-3)
    assert growth > 1.1  # Huang's analysis says |lambda| = 1 for x and y


def test_transverse_bounded_below_the_limit() -> None:
    """At 0.9 dt_c the same perturbation stays bounded over 500 steps (the explicit
    central difference is neutrally stable there: the amplitude oscillates within a
    factor 1/sqrt(1 - (omega dt / 2)^2) = 2.3 of its start)."""
    m = _chain()
    step = thesis_step(m)
    dt = 0.9 * 2.0 / OMEGA_T
    x0 = _perturbed(1, 1e-9)
    xp, xn = x0.copy(), x0.copy()
    peak = 0.0
    for j in range(500):
        xp, xn = xn, step(xp, xn, j * dt, dt)
        peak = max(peak, float(np.abs(xn.reshape(-1, 3)[:, 1]).max()))
    assert peak < 2.5e-9


def test_axial_part_is_huangs_lambda_5_6() -> None:
    """The axial part is as Huang says: the implicit tension gives the recurrence
    (1 + a) u^{j+1} - 2 u^j + u^{j-1} = 0 for the amplitude u of an axial mode, hence
    |lambda|^2 = 1 / (1 + a), a = 4 sin^2(beta/2) EA dt^2 / (l m), beta = (N - 1) pi / N
    here, at twice the explicit axial limit. The measured (2 u^j - u^{j-1}) / u^{j+1} equals
    1 + a to 1e-4 (amplitude 1e-6 m: strain 4e-6, linear; the tension's rounding sets
    the tolerance)."""
    m = _chain()
    step = thesis_step(m)
    ell = LENGTH / N
    beta = (N - 1) * math.pi / N
    dt = 2.0 * math.sqrt(NODE_M * ell / EA)
    a = 4.0 * math.sin(beta / 2.0) ** 2 * EA * dt**2 / (ell * NODE_M)
    shape = np.sin(beta * np.arange(1, N))
    rest = _perturbed(2, 0.0).reshape(-1, 3)[:, 2]
    x0 = _perturbed(2, 1e-6)
    xp, xn = x0.copy(), x0.copy()
    u = [1e-6, 1e-6]
    for j in range(4):
        xp, xn = xn, step(xp, xn, j * dt, dt)
        u.append(float(np.dot(xn.reshape(-1, 3)[:, 2] - rest, shape) / np.dot(shape, shape)))
    u = np.array(u)
    measured = (2.0 * u[1:-1] - u[:-2]) / u[2:]
    np.testing.assert_allclose(measured, 1.0 + a, rtol=1e-4)
    assert 1.0 / math.sqrt(1.0 + a) < 0.3  # strongly damped: Huang's claim holds here


@pytest.mark.parametrize("factor", [100.0, 1000.0])
def test_midpoint_stays_bounded_far_above_the_explicit_limits(factor: float) -> None:
    """The project's implicit midpoint scheme on the same chain, perturbed in the highest
    transverse mode (0.1 mm: 2e-4 of the spacing) and axial mode (0.1 um), at 100 and 1000
    times dt_c (and 1e4 to 1e5 times the explicit axial limit): no growth (amplitude never
    above its start, up to 1e-6 relative), the energy conserved (relative drift below 1e-9
    over 200 steps: the scheme conserves it up to the Newton tolerance), while in (5.21)
    the zigzag grows a hundredfold or more within 20 steps (it then saturates: the
    linearised tension of the folded chain turns compressive)."""
    m = _chain()
    dt = factor * 2.0 / OMEGA_T
    x0 = _perturbed(1, 1e-4) + _perturbed(2, 1e-7) - _perturbed(2, 0.0)
    out = run(m, x0, None, 200 * dt, dt)
    assert out.success
    amp = np.abs(out.positions[:, 1:-1, 1]).max()
    assert amp <= 1e-4 * (1.0 + 1e-6)
    kin, pot = (np.asarray(v).ravel() for v in m.energy.map(out.t.size)(
        out.x.T, out.v.T, out.t[None, :]))
    e = kin + pot
    assert np.abs(e - e[0]).max() <= 1e-9 * e[0]
    thesis = run_thesis(m, x0, None, 20 * dt, dt)
    grown = np.abs(thesis.positions[:, 1:-1, 1]).max()
    assert thesis.status == "failed" or grown > 100.0 * 1e-4
