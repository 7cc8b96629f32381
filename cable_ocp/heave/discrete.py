"""Exact sampled-data models: ZOH with an input delay, cost and noise discretisation.

Used for the exact-delay LQR (Huang 1992, section 6.2.5 done exactly rather than by (6.13)), the MPC
and the closed-loop simulations. References: Astrom & Wittenmark, *Computer-Controlled Systems*,
section 2.3 (fractional input delay); Van Loan (1978) for the integrals of matrix exponentials.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import linalg

from cable_ocp.errors import CableOCPError


def _phi_gamma(A: np.ndarray, B: np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray]:  # noqa: N803
    """``(e^{A t}, integral_0^t e^{A s} ds B)`` by one block exponential."""
    n, m = B.shape
    M = np.zeros((n + m, n + m))
    M[:n, :n] = A
    M[:n, n:] = B
    E = linalg.expm(M * t)
    return E[:n, :n], E[:n, n:]


def delay_steps(tau: float, h: float) -> int:
    """Number of buffered past commands needed for a delay ``tau`` at sample time ``h``.

    Parameters
    ----------
    tau : float
        Delay, s (>= 0).
    h : float
        Sample time, s (> 0).
    """
    if h <= 0:
        raise CableOCPError(f"controller.sample_time = {h!r}: must be > 0 (s)")
    if tau < 0:
        raise CableOCPError(f"winch.delay = {tau!r}: must be >= 0 (s)")
    return int(np.ceil(tau / h - 1e-9))


@dataclass(frozen=True)
class DelayedDiscreteModel:
    """``z_{k+1} = Ad z_k + Bd u_k`` with ``z = [x; u_{k-d}, ..., u_{k-1}]`` (shift register).

    Attributes
    ----------
    Ad, Bd : numpy.ndarray
        Augmented matrices; the buffer occupies the last ``d`` states, oldest first.
    Ed : numpy.ndarray
        Disturbance input matrix for a disturbance held over the sample (ZOH), ``(n + d, n_w)``.
    n : int
        Plant states.
    d : int
        Buffer length.
    h, tau : float
        Sample time and delay, s.
    """

    Ad: np.ndarray
    Bd: np.ndarray
    Ed: np.ndarray
    n: int
    d: int
    h: float
    tau: float


def discretize_delayed(A: np.ndarray, B: np.ndarray, h: float, tau: float,  # noqa: N803
                       E: np.ndarray | None = None) -> DelayedDiscreteModel:
    """Exact ZOH discretisation of ``x' = A x + B u(t - tau) + E w`` (any ``tau >= 0``).

    With ``tau = (d - 1) h + t'``, ``0 < t' <= h``:
    ``x_{k+1} = Phi x_k + Gamma1 u_{k-d} + Gamma0 u_{k-d+1}``,
    ``Gamma0 = int_0^{h-t'} e^{As} ds B``, ``Gamma1 = e^{A(h-t')} int_0^{t'} e^{As} ds B``
    (Astrom & Wittenmark, eq. (2.12)). For ``tau`` an integer multiple of ``h``, ``Gamma0 = 0``
    and the plant sees exactly ``u_{k-d}``: the shift register is exact.

    Parameters
    ----------
    A, B : numpy.ndarray
        Continuous plant, ``B`` the command column.
    h : float
        Sample time, s.
    tau : float
        Input delay, s.
    E : numpy.ndarray, optional
        Disturbance columns (ZOH).
    """
    A = np.asarray(A, dtype=float)
    B = np.asarray(B, dtype=float).reshape(A.shape[0], -1)
    n, m = B.shape
    if m != 1:
        raise CableOCPError("discretize_delayed supports one command input")
    d = delay_steps(tau, h)
    Phi, Gam = _phi_gamma(A, B, h)
    if E is None:
        E = np.zeros((n, 0))
    E = np.asarray(E, dtype=float).reshape(n, -1)
    _, GamE = _phi_gamma(A, E, h) if E.shape[1] else (None, E)
    N = n + d
    Ad = np.zeros((N, N))
    Bd = np.zeros((N, 1))
    Ad[:n, :n] = Phi
    if d == 0:
        Bd[:n] = Gam
    else:
        tp = tau - (d - 1) * h
        Phi_r, G0 = _phi_gamma(A, B, h - tp)
        _, G1p = _phi_gamma(A, B, tp)
        G1 = Phi_r @ G1p
        Ad[:n, n] = G1[:, 0]  # oldest buffered command u_{k-d}
        if d == 1:
            Bd[:n] = G0
        else:
            Ad[:n, n + 1] = G0[:, 0]
        for i in range(d - 1):
            Ad[n + i, n + i + 1] = 1.0
        Bd[N - 1, 0] = 1.0
    Ed = np.zeros((N, E.shape[1]))
    Ed[:n] = GamE
    return DelayedDiscreteModel(Ad=Ad, Bd=Bd, Ed=Ed, n=n, d=d, h=float(h), tau=float(tau))


def discretize_cost(A: np.ndarray, B: np.ndarray, Q: np.ndarray, R: float, h: float,  # noqa: N803
                    d: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Exact sampled cost of ``int (x^T Q x + R u0^2) dt`` for the shift-register model.

    Over one sample the plant is driven by the held, delayed command ``v`` (``v = u_{k-d}``; the
    delay must be an integer number of samples) and the command itself costs ``R h u_k^2``.
    ``W = int_0^h e^{F^T t} blkdiag(Q, 0) e^{F t} dt`` with ``F = [[A, B], [0, 0]]`` (Van Loan)
    gives ``x^T Q x`` integrated exactly.

    Parameters
    ----------
    A, B : numpy.ndarray
        Continuous plant and its command column.
    Q : numpy.ndarray
        State weight, shape (n, n).
    R : float
        Command weight, 1/m^2.
    h : float
        Sample time, s.
    d : int
        Delay in samples (buffered commands).

    Returns
    -------
    tuple of numpy.ndarray
        ``(Qz, Rz, Nz)`` for the augmented state ``z`` (size ``n + d``) and command: stage cost
        ``z^T Qz z + 2 z^T Nz u + u^T Rz u``.
    """
    A = np.asarray(A, dtype=float)
    B = np.asarray(B, dtype=float).reshape(A.shape[0], 1)
    n = A.shape[0]
    F = np.zeros((n + 1, n + 1))
    F[:n, :n] = A
    F[:n, n:] = B
    Qa = np.zeros((n + 1, n + 1))
    Qa[:n, :n] = Q
    M = np.zeros((2 * (n + 1), 2 * (n + 1)))
    M[: n + 1, : n + 1] = -F.T
    M[: n + 1, n + 1 :] = Qa
    M[n + 1 :, n + 1 :] = F
    Em = linalg.expm(M * h)
    W = Em[n + 1 :, n + 1 :].T @ Em[: n + 1, n + 1 :]
    W = 0.5 * (W + W.T)
    N = n + d
    if d == 0:
        Qz = W[:n, :n]
        Nz = W[:n, n:]
        Rz = W[n:, n:] + R * h
    else:
        S = np.zeros((n + 1, N))
        S[:n, :n] = np.eye(n)
        S[n, n] = 1.0
        Qz = S.T @ W @ S
        Nz = np.zeros((N, 1))
        Rz = np.array([[R * h]])
    return Qz, np.atleast_2d(Rz), Nz


def discretize_noise(A: np.ndarray, G: np.ndarray, W: float, h: float) -> np.ndarray:  # noqa: N803
    """Covariance ``int_0^h e^{A s} G W G^T e^{A^T s} ds`` of the sampled white-noise response.

    ``W`` is the noise intensity (``pi`` for unit one-sided spectral density, see
    :mod:`cable_ocp.heave.sea`).

    Parameters
    ----------
    A : numpy.ndarray
        Continuous state matrix, shape (n, n).
    G : numpy.ndarray
        Noise input columns, shape (n, m).
    W : float
        Noise intensity.
    h : float
        Sample time, s.
    """
    A = np.asarray(A, dtype=float)
    n = A.shape[0]
    G = np.asarray(G, dtype=float).reshape(n, -1)
    M = np.zeros((2 * n, 2 * n))
    M[:n, :n] = -A
    M[:n, n:] = W * G @ G.T
    M[n:, n:] = A.T
    Em = linalg.expm(M * h)
    Qd = Em[n:, n:].T @ Em[:n, n:]
    return 0.5 * (Qd + Qd.T)
