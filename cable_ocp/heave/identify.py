"""Identification of the cable/unit coefficients ``a, b`` (Huang 1992, section 6.2.3).

The thesis fits ``a x'' + b x' + x = x0`` (6.2), or ``a x'' + b x'|x'| + x = x0`` (6.3), to a
simulated unit response ``z(t_i)`` by Gauss-Newton: ``[da, db] = (X^T X)^{-1} X^T e`` with the
columns of ``X`` the sensitivities ``dx/da, dx/db`` from auxiliary ODEs. Here the model is
discretised by classical RK4 on the sample grid (``x0`` interpolated linearly between samples)
and the sensitivities are the exact derivatives of that discrete map, computed by CasADi's
forward-mode AD: the discrete counterpart of the thesis' sensitivity equations, same iteration.
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as cs
import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics.export import summary_repr
from cable_ocp.physics.drag import quadratic_drag


@dataclass(frozen=True)
class IdentificationResult:
    """Result of :func:`identify_unit`.

    Attributes
    ----------
    a, b : float
        Identified coefficients (s^2; s for (6.2), s^2/m for (6.3)).
    model : str
        ``"linear"`` (6.2) or ``"quadratic"`` (6.3).
    iterations : int
        Gauss-Newton iterations.
    converged : bool
        Whether the relative step fell below the tolerance.
    rms_residual : float
        RMS of ``z - x``, m.
    fit_pct : float
        ``100 (1 - ||z - x|| / ||z - mean(z)||)`` (100 is a perfect fit).
    std_errors : numpy.ndarray
        Asymptotic standard errors of ``(a, b)`` from ``s^2 (X^T X)^{-1}``.
    x_model : numpy.ndarray
        The identified model's response on the sample grid, m.
    """

    a: float
    b: float
    model: str
    iterations: int
    converged: bool
    rms_residual: float
    fit_pct: float
    std_errors: np.ndarray
    x_model: np.ndarray

    def __repr__(self) -> str:
        """A few lines: the model, convergence, the coefficients and the fit."""
        unit_b = "s" if self.model == "linear" else "s^2/m"
        return summary_repr(
            "IdentificationResult", "converged" if self.converged else "not converged",
            f"{self.model} unit model", [
                ("a", self.a, "s^2"), ("b", self.b, unit_b),
                ("std_error_a", float(self.std_errors[0]), "s^2"),
                ("std_error_b", float(self.std_errors[1]), unit_b),
                ("fit", self.fit_pct, "%"), ("rms_residual", self.rms_residual, "m"),
                ("iterations", self.iterations, "")],
            {"x_model": self.x_model})


def _rhs(model: str) -> cs.Function:
    s = cs.SX.sym("s", 2)
    p = cs.SX.sym("p", 2)
    x0 = cs.SX.sym("x0")
    a, b = p[0], p[1]
    damp = b * s[1] if model == "linear" else quadratic_drag(b, s[1])
    return cs.Function("f", [s, p, x0], [cs.vertcat(s[1], (x0 - s[0] - damp) / a)])


def simulator(model: str, n_samples: int, dt: float) -> cs.Function:
    """CasADi function ``(p = [a, b], x0 samples, s0) -> x samples`` (RK4 on the sample grid).

    Parameters
    ----------
    model : {"linear", "quadratic"}
        (6.2) or (6.3).
    n_samples : int
        Number of samples (the first is the initial state).
    dt : float
        Sample interval, s.
    """
    if model not in ("linear", "quadratic"):
        raise CableOCPError(f'unit.model = {model!r}: valid are "linear", "quadratic"')
    f = _rhs(model)
    s = cs.MX.sym("s", 2)
    p = cs.MX.sym("p", 2)
    xa = cs.MX.sym("xa")
    xb = cs.MX.sym("xb")
    xm = 0.5 * (xa + xb)
    k1 = f(s, p, xa)
    k2 = f(s + dt / 2 * k1, p, xm)
    k3 = f(s + dt / 2 * k2, p, xm)
    k4 = f(s + dt * k3, p, xb)
    step = cs.Function("step", [s, p, xa, xb], [s + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)])
    acc = step.mapaccum("acc", n_samples - 1, [0], [0])
    P = cs.MX.sym("P", 2)
    X0 = cs.MX.sym("X0", n_samples)
    S0 = cs.MX.sym("S0", 2)
    traj = acc(S0, cs.repmat(P, 1, n_samples - 1), X0[:-1].T, X0[1:].T)
    x = cs.vertcat(S0[0], traj[0, :].T)
    return cs.Function("sim", [P, X0, S0], [x, cs.jacobian(x, P)])


def identify_unit(
    t: np.ndarray,
    x0: np.ndarray,
    z: np.ndarray,
    *,
    model: str = "linear",
    guess: tuple[float, float] = (1.0, 0.1),
    z_dot0: float = 0.0,
    tol: float = 1e-10,
    max_iter: int = 50,
) -> IdentificationResult:
    """Fit ``a, b`` of (6.2) or (6.3) to a measured response by Gauss-Newton (Huang 1992, 6.2.3).

    Parameters
    ----------
    t : array_like, shape (L,)
        Uniform sample times, s.
    x0 : array_like, shape (L,)
        Boom-tip heave, m.
    z : array_like, shape (L,)
        Measured unit heave, m (``z[0]`` is the initial position).
    model : {"linear", "quadratic"}
        (6.2) or (6.3).
    guess : tuple of float
        Starting ``(a, b)``.
    z_dot0 : float
        Initial unit velocity, m/s.
    tol : float
        Stop when ``|delta p| / |p| < tol``.
    max_iter : int
        Iteration limit.

    Returns
    -------
    IdentificationResult
    """
    t = np.asarray(t, dtype=float)
    x0 = np.asarray(x0, dtype=float)
    z = np.asarray(z, dtype=float)
    if not (t.shape == x0.shape == z.shape and t.ndim == 1 and t.size >= 4):
        raise CableOCPError("identification data t, x0, z must be 1-D arrays of equal length >= 4")
    dt = float(t[1] - t[0])
    if dt <= 0 or np.max(np.abs(np.diff(t) - dt)) > 1e-9 * max(1.0, abs(t[-1])):
        raise CableOCPError("identification data: t must be uniformly spaced and increasing")
    if guess[0] <= 0:
        raise CableOCPError(f"identification guess a = {guess[0]} must be > 0")
    sim = simulator(model, t.size, dt)
    p = np.array(guess, dtype=float)
    s0 = np.array([z[0], z_dot0])
    converged = False
    it = 0
    def cost(pp: np.ndarray) -> float:
        xx = np.asarray(sim(pp, x0, s0)[0]).ravel()
        c = float(np.sum((z - xx) ** 2))
        return c if np.isfinite(c) else np.inf

    for _ in range(max_iter):
        it += 1
        xk, X = sim(p, x0, s0)
        e = z - np.asarray(xk).ravel()
        c0 = float(e @ e)
        dp, *_ = np.linalg.lstsq(np.asarray(X), e, rcond=None)
        # Gauss-Newton step with backtracking (the thesis' full step can diverge from a poor
        # start); keep a > 0.
        step = 1.0
        while step > 1e-8 and (p[0] + step * dp[0] <= 0 or cost(p + step * dp) > c0):
            step *= 0.5
        p = p + step * dp
        if np.linalg.norm(step * dp) <= tol * np.linalg.norm(p) or step <= 1e-8:
            # A vanishing line-search step means no descent is left: converged if the GN step
            # itself is small.
            converged = bool(np.linalg.norm(dp) <= max(tol, 1e-6) * np.linalg.norm(p))
            break
    xk, X = sim(p, x0, s0)
    xk = np.asarray(xk).ravel()
    X = np.asarray(X)
    res = z - xk
    dof = max(1, z.size - 2)
    s2 = float(res @ res) / dof
    try:
        cov = s2 * np.linalg.inv(X.T @ X)
        se = np.sqrt(np.abs(np.diag(cov)))
    except np.linalg.LinAlgError:
        se = np.full(2, np.nan)
    fit = 100.0 * (1.0 - np.linalg.norm(res) / np.linalg.norm(z - z.mean()))
    return IdentificationResult(a=float(p[0]), b=float(p[1]), model=model, iterations=it,
                                converged=converged, rms_residual=float(np.sqrt(np.mean(res**2))),
                                fit_pct=float(fit), std_errors=se, x_model=xk)
