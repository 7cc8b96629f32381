"""Stochastic analysis and design (Huang 1992, section 6.3): variances, LQG, winch-gain study.

Variance convention (docs/conventions.md, "Heave compensation"): for ``x' = A0 x + B2 w`` with ``w``
white noise of unit **one-sided** spectral density,

    sigma^2 = pi * C P C^T = integral_0^inf |H(i w)|^2 dw,     A0 P + P A0^T + B2 B2^T = 0,

with ``H = C (i w I - A0)^{-1} B2`` (6.33). ``P`` is the solution of (6.31) exactly as printed;
the factor ``pi`` converts it to the one-sided spectral integral. The thesis' (6.35) writes the
integral over ``(-inf, inf)``, which would give sqrt(2) times this; only the one-sided reading
reproduces its sigma = 0.255 m for 6.3.6.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import control as ct
import numpy as np
from scipy import integrate, linalg

from cable_ocp.errors import CableOCPError
from cable_ocp.heave.discrete import discretize_delayed, discretize_noise
from cable_ocp.heave.lqr import exact_delay_dlqr
from cable_ocp.heave.plant import HeavePlant

#: Intensity of the continuous white noise that has a one-sided spectral density of 1 (module
#: docstring); also exported by :mod:`cable_ocp.heave.sea`.
WHITE_NOISE_INTENSITY = np.pi


def state_covariance(A0: np.ndarray, B2: np.ndarray) -> np.ndarray:  # noqa: N803
    """Solution ``P`` of the Lyapunov equation (Huang 1992, eq. (6.31)) as printed (unit intensity).

    Parameters
    ----------
    A0 : numpy.ndarray
        Closed-loop (or open-loop) state matrix, shape (n, n).
    B2 : numpy.ndarray
        Noise input columns, shape (n, m).

    Raises
    ------
    CableOCPError
        If ``A0`` is not Hurwitz (no stationary covariance exists).
    """
    A0 = np.asarray(A0, dtype=float)
    B2 = np.asarray(B2, dtype=float).reshape(A0.shape[0], -1)
    ev = np.linalg.eigvals(A0)
    if np.max(ev.real) >= 0:
        raise CableOCPError(
            f"the system matrix is not stable (max Re eig = {np.max(ev.real):.3g}); "
            "no stationary variance exists"
        )
    P = linalg.solve_continuous_lyapunov(A0, -B2 @ B2.T)
    return 0.5 * (P + P.T)


def output_variance_lyapunov(A0: np.ndarray, B2: np.ndarray, C: np.ndarray) -> float:  # noqa: N803
    """``sigma^2 = pi C P C^T`` (m^2 for a position output), ``P`` from (6.31).

    Parameters
    ----------
    A0 : numpy.ndarray
        State matrix of the loop, shape (n, n).
    B2 : numpy.ndarray
        Noise input columns (intensity ``pi``).
    C : numpy.ndarray
        Output row, shape (n,) or (1, n).
    """
    P = state_covariance(A0, B2)
    C = np.asarray(C, dtype=float).reshape(1, -1)
    return float(WHITE_NOISE_INTENSITY * (C @ P @ C.T)[0, 0])


def output_variance_spectral(A0: np.ndarray, B2: np.ndarray, C: np.ndarray,  # noqa: N803
                             rtol: float = 1e-12) -> float:
    """``sigma^2 = integral_0^inf |H(i w)|^2 dw`` with ``H`` from (6.33)-(6.34), by quadrature.

    An independent check of :func:`output_variance_lyapunov`: ``H`` is evaluated through a
    complex linear solve at each frequency and the integral is taken with adaptive Gauss-Kronrod
    quadrature on ``(0, inf)`` mapped to ``(0, pi/2)`` by ``w = w_s tan(theta)``, split at the
    poles' natural frequencies. The tolerance is relative (``epsabs = 0``), since a controlled
    variance is ~1e-7 m^2.

    Parameters
    ----------
    A0 : numpy.ndarray
        State matrix of the loop, shape (n, n).
    B2 : numpy.ndarray
        Noise input columns.
    C : numpy.ndarray
        Output row.
    rtol : float
        Relative tolerance of the quadrature.
    """
    A0 = np.asarray(A0, dtype=float)
    n = A0.shape[0]
    B2 = np.asarray(B2, dtype=float).reshape(n, 1)
    C = np.asarray(C, dtype=float).reshape(1, n)
    ev = np.linalg.eigvals(A0)
    if np.max(ev.real) >= 0:
        raise CableOCPError("the system matrix is not stable; the spectral integral diverges")
    ws = float(np.median(np.abs(ev)))
    eye = np.eye(n)

    def integrand(theta: float) -> float:
        w = ws * np.tan(theta)
        h = (C @ np.linalg.solve(1j * w * eye - A0, B2))[0, 0]
        return float(abs(h) ** 2 * ws / np.cos(theta) ** 2)

    brk = sorted({float(np.arctan(abs(e) / ws)) for e in ev if abs(e) > 0})
    edges = [0.0] + [t for t in brk if 0 < t < np.pi / 2] + [np.pi / 2]
    total = 0.0
    for lo, hi in zip(edges[:-1], edges[1:], strict=True):
        if hi - lo < 1e-14:
            continue
        val, _ = integrate.quad(integrand, lo, hi, epsabs=0.0, epsrel=rtol, limit=500)
        total += val
    return float(total)


def lqr_continuous(A: np.ndarray, B: np.ndarray, Q: np.ndarray, R: np.ndarray  # noqa: N803
                   ) -> np.ndarray:
    """Continuous LQR gain ``G`` (``u0 = -G x``, Huang (1992) (6.10)/(6.30)) via ``control.lqr``.

    Parameters
    ----------
    A, B : numpy.ndarray
        Continuous plant and command column.
    Q : numpy.ndarray
        State weight.
    R : numpy.ndarray
        Command weight, 1/m^2.
    """
    G, _, _ = ct.lqr(A, B, Q, R)
    return np.asarray(G)


@dataclass(frozen=True)
class StochasticDesign:
    """An 11-state (or general) stochastic LQR design and its stationary performance.

    Attributes
    ----------
    G : numpy.ndarray, shape (1, n)
        Gain, ``u0 = -G x``.
    sigma : float
        Closed-loop standard deviation of the unit's heave, m (one-sided convention).
    sigma_uncontrolled : float
        Open-loop value, m.
    energy_index : float
        ``sqrt(sum G_i^2)`` (Huang 1992, section 6.3.5).
    reduction_pct : float
        ``100 (1 - sigma / sigma_uncontrolled)``.
    closed_loop_poles : numpy.ndarray
        Eigenvalues of ``A - B1 G``.
    """

    G: np.ndarray
    sigma: float
    sigma_uncontrolled: float
    energy_index: float
    reduction_pct: float
    closed_loop_poles: np.ndarray


def stochastic_lqr(A: np.ndarray, B1: np.ndarray, B2: np.ndarray, c_x: np.ndarray,  # noqa: N803
                   q: float, r: float = 1.0) -> StochasticDesign:
    """Full-state LQR with ``Q = q c_x^T c_x``, ``R = r`` (Huang 1992, (6.29)-(6.31)).

    Parameters
    ----------
    A, B1, B2 : numpy.ndarray
        Plant (6.28): state matrix, control column, noise column.
    c_x : numpy.ndarray, shape (1, n)
        Row that picks the unit's heave.
    q : float
        Weight on the unit's heave, 1/m^2 (relative to ``r``).
    r : float
        Weight on the command ``u0``, 1/m^2.
    """
    if q < 0 or r <= 0:
        raise CableOCPError(f"controller.q = {q!r}, controller.r = {r!r}: q must be >= 0 and r > 0 "
                            "(1/m^2)")
    c_x = np.asarray(c_x, dtype=float).reshape(1, -1)
    Q = q * c_x.T @ c_x
    G = lqr_continuous(A, B1, Q, np.array([[r]]))
    A0 = A - B1 @ G
    s_cl = np.sqrt(output_variance_lyapunov(A0, B2, c_x))
    s_ol = np.sqrt(output_variance_lyapunov(A, B2, c_x))
    return StochasticDesign(G=G, sigma=float(s_cl), sigma_uncontrolled=float(s_ol),
                            energy_index=float(np.sqrt(np.sum(G**2))),
                            reduction_pct=float(100.0 * (1.0 - s_cl / s_ol)),
                            closed_loop_poles=np.linalg.eigvals(A0))


def weight_for_sigma(A: np.ndarray, B1: np.ndarray, B2: np.ndarray, c_x: np.ndarray,  # noqa: N803
                     sigma_target: float, r: float = 1.0, q_lo: float = 1e-3,
                     q_hi: float = 1e9) -> float:
    """Weight ``q`` whose LQR design gives the closed-loop sigma ``sigma_target`` (m).

    Bisection in ``log q`` (sigma decreases monotonically with ``q`` for this plant); relative
    tolerance 1e-10 on ``q``.

    Parameters
    ----------
    A, B1, B2 : numpy.ndarray
        Plant (6.28): state matrix, command and noise columns.
    c_x : numpy.ndarray
        Row of the unit's heave.
    sigma_target : float
        Closed-loop heave sigma to reach, m.
    r : float
        Command weight, 1/m^2.
    q_lo, q_hi : float
        Bracket of the bisection in ``q``, 1/m^2.
    """
    def f(lq: float) -> float:
        return np.log(stochastic_lqr(A, B1, B2, c_x, float(np.exp(lq)), r).sigma / sigma_target)

    lo, hi = np.log(q_lo), np.log(q_hi)
    if f(lo) < 0 or f(hi) > 0:
        raise CableOCPError(
            f"sigma target {sigma_target} m is not reachable with q in [{q_lo}, {q_hi}]"
        )
    from scipy.optimize import brentq

    return float(np.exp(brentq(f, lo, hi, xtol=1e-10)))


def lqg_kalman(A: np.ndarray, B2: np.ndarray, c_meas: np.ndarray,  # noqa: N803
               noise_std: float, sample_time: float) -> np.ndarray:
    """Continuous Kalman gain ``L`` for a sampled position sensor (python-control ``lqe``).

    The process noise enters through ``B2`` with intensity ``pi`` (one-sided unit spectral
    density, see module docstring); ``G = B2`` is passed explicitly because ``control.lqe(sys,
    QN, RN)`` would assume the noise enters through the control input. A sensor sampled every
    ``sample_time`` seconds with white noise of standard deviation ``noise_std`` (m) is the
    continuous measurement noise of intensity ``noise_std^2 * sample_time`` (m^2 s).

    Parameters
    ----------
    A, B2 : numpy.ndarray
        Plant (6.28): state matrix and noise columns.
    c_meas : numpy.ndarray
        Row of the measured position.
    noise_std : float
        Standard deviation of the sensor's white noise per sample, m.
    sample_time : float
        The sensor's sample time, s.

    Returns
    -------
    numpy.ndarray, shape (n, 1)
        ``x_hat' = A x_hat + B1 u0 + L (y - C x_hat)``.
    """
    if noise_std <= 0 or sample_time <= 0:
        raise CableOCPError(
            f"controller.measurement_noise = {noise_std!r}, controller.sample_time = "
            f"{sample_time!r}: both must be > 0 (m, s)"
        )
    c = np.asarray(c_meas, dtype=float).reshape(1, -1)
    QN = np.array([[WHITE_NOISE_INTENSITY]])
    RN = np.array([[noise_std**2 * sample_time]])
    L, _, _ = ct.lqe(A, B2, c, QN, RN)
    return np.asarray(L)


def lqg_closed_loop_sigma(A: np.ndarray, B1: np.ndarray, B2: np.ndarray,  # noqa: N803
                          c_x: np.ndarray, G: np.ndarray, L: np.ndarray,
                          noise_intensity: float) -> float:
    """Stationary heave sigma (m) of the continuous LQG loop (plant + Kalman filter + ``-G``).

    The augmented state ``[x; x_hat]`` is driven by the process noise (intensity ``pi``) and the
    measurement noise (intensity ``noise_intensity``); the variance is ``C P C^T`` with ``P``
    from the Lyapunov equation of that pair. Built with python-control: the compensator
    ``x_hat' = (A - B1 G - L C) x_hat + L y``, ``u0 = -G x_hat`` already contains the minus
    sign, so it closes with ``feedback(..., sign=+1)``.

    Parameters
    ----------
    A, B1, B2 : numpy.ndarray
        Plant (6.28): state matrix, command and noise columns.
    c_x : numpy.ndarray
        Row of the unit's heave (also the measured output).
    G : numpy.ndarray
        LQR gain, ``u0 = -G x_hat``.
    L : numpy.ndarray
        Continuous Kalman gain (:func:`lqg_kalman`).
    noise_intensity : float
        Intensity of the measurement noise, m^2 s.
    """
    n = A.shape[0]
    c_x = np.asarray(c_x, dtype=float).reshape(1, n)
    # Plant with inputs [u0, w, v] and output y = heave + v.
    plant = ct.ss(A, np.hstack([B1, B2, np.zeros((n, 1))]), c_x, [[0.0, 0.0, 1.0]])
    # Compensator y -> [u0, 0, 0]; it already outputs -G x_hat, hence sign=+1.
    Cc = np.vstack([-G, np.zeros((2, n))])
    comp = ct.ss(A - B1 @ G - L @ c_x, L, Cc, np.zeros((3, 1)))
    cl = ct.feedback(plant, comp, sign=+1)
    Acl = np.asarray(cl.A)
    Bcl = np.asarray(cl.B)[:, 1:3]
    Ccl = np.hstack([c_x, np.zeros((1, n))])
    W = np.diag([WHITE_NOISE_INTENSITY, noise_intensity])
    if np.max(np.linalg.eigvals(Acl).real) >= 0:
        raise CableOCPError("the LQG closed loop is unstable")
    P = linalg.solve_continuous_lyapunov(Acl, -Bcl @ W @ Bcl.T)
    return float(np.sqrt((Ccl @ P @ Ccl.T)[0, 0]))


def winch_gain_study(build: Callable[[float], HeavePlant], K_values: np.ndarray,  # noqa: N803
                     sigma_target: float, r: float = 1.0) -> list[tuple[float, float, float]]:
    """Energy index versus winch gain ``K`` at a prescribed sigma (Huang 1992, section 6.3.5, Fig.
    6.25).

    Parameters
    ----------
    build : callable
        ``build(K) -> HeavePlant`` (11-state plant for winch gain ``K``).
    K_values : array_like
        Winch gains, 1/s.
    sigma_target : float
        Prescribed closed-loop sigma of the unit's heave, m.
    r : float
        Command weight.

    Returns
    -------
    list of (K, q, energy_index)
    """
    out = []
    for K in np.asarray(K_values, dtype=float):
        p = build(float(K))
        cx = p.e("x")
        q = weight_for_sigma(p.A, p.B1, p.B2, cx, sigma_target, r)
        d = stochastic_lqr(p.A, p.B1, p.B2, cx, q, r)
        out.append((float(K), q, d.energy_index))
    return out


def sampled_loop_sigma(A: np.ndarray, B1: np.ndarray, B2: np.ndarray,  # noqa: N803
                       c_x: np.ndarray, h: float, tau_true: float, G_x: np.ndarray,  # noqa: N803
                       G_buf: np.ndarray | None = None) -> float:
    """Stationary heave sigma (m) of a sampled state-feedback loop with an exact input delay.

    The plant (6.28) is discretised exactly (ZOH, delay ``tau_true``, noise covariance by Van
    Loan with intensity ``pi``); the command is ``u_k = -G_x x_k - G_buf [u_{k-d}..u_{k-1}]``
    (``G_buf`` for an exact discrete-delay design with ``d`` buffered commands, which must match
    the plant's buffer). Sampled stationary variance = continuous stationary variance at the
    sample instants; ``sigma^2 = C P C^T`` with ``P`` from the discrete Lyapunov equation.

    Parameters
    ----------
    A, B1, B2 : numpy.ndarray
        Plant (6.28): state matrix, command and noise columns.
    c_x : numpy.ndarray
        Row of the unit's heave.
    h : float
        Sample time, s.
    tau_true : float
        The plant's true delay, s.
    G_x : numpy.ndarray
        Gain on the plant's states.
    G_buf : numpy.ndarray, optional
        Gain on the buffered commands (exact discrete-delay designs).
    """
    n = A.shape[0]
    mdl = discretize_delayed(A, B1, h, tau_true)
    N = mdl.Ad.shape[0]
    Kc = np.zeros((1, N))
    Kc[:, :n] = G_x
    if G_buf is not None and np.size(G_buf):
        nb = np.size(G_buf)
        if nb != mdl.d:
            raise CableOCPError(f"buffer gains ({nb}) must match the delay steps ({mdl.d})")
        Kc[:, n:] = np.reshape(G_buf, (1, nb))
    Acl = mdl.Ad - mdl.Bd @ Kc
    if np.max(np.abs(np.linalg.eigvals(Acl))) >= 1:
        return float("inf")
    Qw = np.zeros((N, N))
    Qw[:n, :n] = discretize_noise(A, B2, WHITE_NOISE_INTENSITY, h)
    P = linalg.solve_discrete_lyapunov(Acl, Qw)
    cz = np.zeros((1, N))
    cz[:, :n] = np.asarray(c_x).reshape(1, n)
    return float(np.sqrt((cz @ P @ cz.T)[0, 0]))


def discrete_delay_lqr(A: np.ndarray, B1: np.ndarray, c_x: np.ndarray, q: float,  # noqa: N803
                       r: float, h: float, tau: float) -> np.ndarray:
    """Exact discrete-delay LQR for the full plant (6.28) with ``Q = q c_x^T c_x``, ``R = r``.

    The same design as :func:`cable_ocp.heave.lqr.design_lqr` with ``method="discrete"``
    (:func:`cable_ocp.heave.lqr.exact_delay_dlqr`: ``dlqr`` on the shift-register model with
    the continuous cost ``int (q x^2 + r u0^2) dt`` sampled exactly); ``tau/h`` must be an
    integer.

    Parameters
    ----------
    A, B1 : numpy.ndarray
        Plant (6.28): state matrix and command column.
    c_x : numpy.ndarray
        Row of the unit's heave.
    q : float
        Heave weight, 1/m^2.
    r : float
        Command weight, 1/m^2.
    h : float
        Sample time, s.
    tau : float
        Delay, s (a whole number of samples).

    Returns
    -------
    numpy.ndarray, shape (1, n + d)
        Gains on ``[x; u_{k-d} .. u_{k-1}]``.
    """
    cx = np.asarray(c_x, dtype=float).reshape(1, -1)
    G, _ = exact_delay_dlqr(A, B1, q * cx.T @ cx, r, h, tau)
    return G
