"""Exact sampled-data models (heave/discrete.py) against direct integration.

Each check integrates the continuous model with scipy (``solve_ivp``, DOP853, rtol 1e-12, or
adaptive ``quad_vec``) with the command delayed by exactly ``tau``, sharing no code with
discrete.py; both sides are exact up to their tolerances, hence 1e-9 relative.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import integrate, linalg

from cable_ocp.heave import lqr
from cable_ocp.heave.discrete import discretize_cost, discretize_delayed, discretize_noise
from cable_ocp.heave.thesis import A_636, B_636

H = 0.05


def _plant() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    p = lqr.regulator_plant(A_636, B_636, 1.0)
    return p.A, p.B1, p.B2


@pytest.mark.parametrize("tau", [0.0, 0.13, 0.2])
def test_delayed_zoh_model_equals_integration_with_the_true_delay(tau: float) -> None:
    # Random held commands u_k on [k h, (k + 1) h); the plant sees u(t - tau). Integrated
    # piecewise between the breakpoints k h and k h + tau, compared with the shift-register
    # model's plant states at every sample (its buffer starts at zero like the history).
    A, B, E = _plant()
    n = A.shape[0]
    mdl = discretize_delayed(A, B, H, tau, E)
    rng = np.random.default_rng(0)
    steps = 30
    u = rng.standard_normal(steps)
    w = rng.standard_normal(steps)  # disturbance, held over each sample (not delayed)

    def applied(t: float) -> float:
        k = int(np.floor((t - tau) / H + 1e-9))
        return u[k] if k >= 0 else 0.0

    x = np.zeros(n)
    z = np.zeros(mdl.Ad.shape[0])
    for k in range(steps):
        t0, t1 = k * H, (k + 1) * H
        cuts = sorted({t0, t1, *(t for t in (t0 + (tau % H),) if t0 < t < t1)})
        for a, b in zip(cuts[:-1], cuts[1:], strict=True):
            v = applied(0.5 * (a + b))
            x = integrate.solve_ivp(lambda _t, y, v=v, k=k: A @ y + B[:, 0] * v + E[:, 0] * w[k],
                                    (a, b), x, method="DOP853", rtol=1e-12, atol=1e-14).y[:, -1]
        z = mdl.Ad @ z + mdl.Bd[:, 0] * u[k] + mdl.Ed[:, 0] * w[k]
        np.testing.assert_allclose(z[:n], x, rtol=1e-9, atol=1e-11)
    assert mdl.d == int(np.ceil(tau / H - 1e-9))


@pytest.mark.parametrize("d", [0, 4])
def test_sampled_cost_equals_the_integrated_continuous_cost(d: int) -> None:
    # Stage cost z^T Qz z + 2 z^T Nz u + Rz u^2 = int_0^h x^T Q x dt + R h u^2 along the exact
    # trajectory from z with the applied command held (u itself without delay, the oldest
    # buffered command with a delay of d samples); R = 0.7, Q = diag(553.6, 2, 0) (553.6: the
    # weight calibrated to 6.3.6's 2.96e-4 m; any weights would do here).
    A, B, _ = _plant()
    n = A.shape[0]
    Q = np.diag([553.6, 2.0, 0.0])
    R = 0.7
    Qz, Rz, Nz = discretize_cost(A, B, Q, R, H, d)
    rng = np.random.default_rng(1)
    for _ in range(3):
        z = rng.standard_normal(n + d)
        u = float(rng.standard_normal())
        v = z[n] if d else u

        def rhs(_t: float, y: np.ndarray, v: float = v) -> np.ndarray:
            x = y[:n]
            return np.concatenate([A @ x + B[:, 0] * v, [x @ Q @ x]])

        y = integrate.solve_ivp(rhs, (0.0, H), np.concatenate([z[:n], [0.0]]), method="DOP853",
                                rtol=1e-12, atol=1e-14).y[:, -1]
        expect = y[-1] + R * H * u**2
        got = float(z @ Qz @ z + 2 * (z @ Nz[:, 0]) * u + Rz[0, 0] * u**2)
        assert got == pytest.approx(expect, rel=1e-9)


def test_sampled_noise_covariance_equals_its_integral() -> None:
    # int_0^h e^{A s} G W G^T e^{A^T s} ds by adaptive quadrature, W = pi.
    A, _, E = _plant()
    Qd = discretize_noise(A, E, np.pi, H)
    ref, _ = integrate.quad_vec(
        lambda s: linalg.expm(A * s) @ (np.pi * E @ E.T) @ linalg.expm(A.T * s), 0.0, H,
        epsabs=0.0, epsrel=1e-12)
    np.testing.assert_allclose(Qd, ref, rtol=1e-9, atol=1e-12 * np.abs(ref).max())
