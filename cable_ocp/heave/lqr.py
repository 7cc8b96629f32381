"""LQR regulators with the winch delay handled three ways (Huang 1992, sections 6.2.4-6.2.6).

* ``"none"``: design on the undelayed plant (6.6).
* ``"taylor"``: the thesis' second-order Taylor model (6.13)-(6.14); the two extra states
  ``[u0(t - tau), u0'(t - tau)]`` are not measurable, so the controller computes them by running
  the filter (6.13) on its own command.
* ``"pade"``: a Pade approximation of chosen order, implemented the same way.
* ``"discrete"``: the exact delay in discrete time: ZOH at sample time ``h``, the last
  ``d = tau/h`` commands in a shift register, ``dlqr`` with the exactly sampled cost.

Every design is judged on the **true** delayed loop: stability versus the actual delay (the
stable interval of delays containing the design delay, from the exact frequency-domain crossing
condition of ``1 + L2(s) + L1(s) e^{-s tau} = 0``) and the indices J_d, J_v, J_c
(6.16)-(6.18) on a boom-tip record, plus the coordinate-free winch-speed energy ``J_w`` that the
trade-off curves use as their effort axis (``J_c`` of a Pade design depends on its realisation).

Sign convention: ``u0 = -G x`` (the thesis' (6.9) writes ``u0 = G x`` with ``G = -R^{-1} B^T M``
in (6.10); its printed gains in Figs. 6.15-6.17 are positive, i.e. the ``-G`` convention).
"""

from __future__ import annotations

from dataclasses import dataclass

import control as ct
import numpy as np
from scipy import optimize

from cable_ocp.errors import CableOCPError
from cable_ocp.heave.discrete import DelayedDiscreteModel, discretize_cost, discretize_delayed
from cable_ocp.heave.plant import HeavePlant, assemble_plant, delay_block, winch_first


@dataclass(frozen=True)
class LQRDesign:
    """A state-feedback design for the regulator plant (Huang 1992, (6.6)/(6.14)).

    Attributes
    ----------
    G : numpy.ndarray, shape (1, n_p + n_f)
        Gains on ``[plant states; controller-internal delay states]``; ``u0 = -G z``.
    method : str
        ``"none"``, ``"taylor"``, ``"pade"`` or ``"discrete"``.
    tau : float
        Design delay, s.
    n_p : int
        Number of plant (unit + winch) states.
    Ap, Bp : numpy.ndarray
        Undelayed plant (command input after the delay), disturbance excluded.
    Ep : numpy.ndarray
        Boom-tip input column.
    Af, Bf : numpy.ndarray
        Controller's delay model (empty for ``"none"``/``"discrete"``).
    h : float
        Sample time for ``"discrete"`` designs, s (0 for continuous ones).
    d : int
        Buffer length for ``"discrete"`` designs.
    """

    G: np.ndarray
    method: str
    tau: float
    n_p: int
    Ap: np.ndarray
    Bp: np.ndarray
    Ep: np.ndarray
    Af: np.ndarray
    Bf: np.ndarray
    h: float = 0.0
    d: int = 0

    @property
    def Gp(self) -> np.ndarray:  # noqa: N802
        """Gains on the plant states."""
        return self.G[:, : self.n_p]

    @property
    def Gf(self) -> np.ndarray:  # noqa: N802
        """Gains on the controller's delay states (filter or buffer)."""
        return self.G[:, self.n_p :]

    @property
    def control_energy(self) -> float:
        """J_c = sum G_i^2 (Huang 1992, eq. (6.18))."""
        return float(np.sum(self.G**2))


def regulator_plant(a: float, b: float, K: float = 1.0, winch: ct.StateSpace | None = None,
                    delay: ct.StateSpace | None = None) -> HeavePlant:
    """The regulator plant (6.6), or (6.14) with a delay block: boom-tip motion as input.

    Parameters
    ----------
    a, b : float
        Unit coefficients (6.2), s^2 and s.
    K : float
        First-order winch gain, 1/s (when ``winch`` is not given).
    winch : control.StateSpace, optional
        Winch block (default :func:`cable_ocp.heave.plant.winch_first` with ``K``).
    delay : control.StateSpace, optional
        Delay block (:func:`cable_ocp.heave.plant.delay_block`), default none.
    """
    return assemble_plant(a, b, winch if winch is not None else winch_first(K), delay=delay)


def _pad_Q(Q: np.ndarray, n: int) -> np.ndarray:  # noqa: N802
    Q = np.atleast_2d(np.asarray(Q, dtype=float))
    out = np.zeros((n, n))
    out[: Q.shape[0], : Q.shape[1]] = Q
    return out


def exact_delay_dlqr(A: np.ndarray, B: np.ndarray, Q: np.ndarray, R: float, h: float,  # noqa: N803
                     tau: float) -> tuple[np.ndarray, DelayedDiscreteModel]:
    """Exact discrete-delay LQR: ``dlqr`` on the shift-register model (section 6.2.5 done
    exactly instead of by the Taylor model (6.13)).

    ``x' = A x + B u0(t - tau)`` is sampled by ZOH at ``h`` with the last ``d = tau / h``
    commands as extra states, and the continuous cost ``int (x^T Q x + R u0^2) dt`` is sampled
    exactly (:func:`cable_ocp.heave.discrete.discretize_cost`); then python-control's ``dlqr``.

    Parameters
    ----------
    A, B : numpy.ndarray
        Continuous plant and command column (any plant: regulator (6.6) or full (6.28)).
    Q : numpy.ndarray
        State weight (n x n).
    R : float
        Command weight, 1/m^2.
    h : float
        Sample time, s.
    tau : float
        Delay, s; ``tau / h`` must be an integer.

    Returns
    -------
    G : numpy.ndarray, shape (1, n + d)
        Gains on ``[x; u0_{k-d} .. u0_{k-1}]``, ``u0_k = -G z_k``.
    model : DelayedDiscreteModel
        The sampled shift-register model.
    """
    d_real = tau / h
    if abs(d_real - round(d_real)) > 1e-9:
        raise CableOCPError(
            f"winch.delay = {tau!r}: must be an integer multiple of controller.sample_time "
            f"= {h} s for the exact discrete design"
        )
    mdl = discretize_delayed(A, B, h, tau)
    Qz, Rz, Nz = discretize_cost(A, B, Q, R, h, mdl.d)
    G, _, _ = ct.dlqr(mdl.Ad, mdl.Bd, Qz, Rz, Nz)
    return np.asarray(G), mdl


def design_lqr(a: float, b: float, Q: np.ndarray, R: float = 1.0, *, tau: float = 0.0,
               method: str = "taylor", pade_order: int = 2, K: float = 1.0,
               winch: ct.StateSpace | None = None, h: float = 0.05) -> LQRDesign:
    """LQR gain for the regulator plant with the delay handled by ``method``.

    Parameters
    ----------
    a, b : float
        Unit coefficients (6.2), s^2 and s.
    Q : array_like
        State weight on the plant states ``[x, x', u(, u')]`` (padded with zeros for the delay
        states), 1/m^2 and (s/m)^2.
    R : float
        Command weight, 1/m^2.
    tau : float
        Delay, s.
    method : {"none", "taylor", "pade", "discrete"}
        Delay handling (module docstring).
    pade_order : int
        Pade order for ``"pade"``.
    K : float
        First-order winch gain, 1/s (ignored when ``winch`` is given).
    winch : control.StateSpace, optional
        Winch block (default first-order with ``K``).
    h : float
        Sample time for ``"discrete"``, s; ``tau / h`` must be an integer.

    Returns
    -------
    LQRDesign
    """
    if method not in ("none", "taylor", "pade", "discrete"):
        raise CableOCPError(
            f"delay method {method!r} is unknown; valid: 'none', 'taylor', 'pade', 'discrete'"
        )
    base = regulator_plant(a, b, K, winch)
    n_p = base.n
    Ap, Bp, Ep = base.A, base.B1, base.B2
    empty = np.zeros((0, 0)), np.zeros((0, 1))
    if method == "discrete":
        G, mdl = exact_delay_dlqr(Ap, Bp, _pad_Q(Q, n_p), R, h, tau)
        return LQRDesign(G, method, float(tau), n_p, Ap, Bp, Ep, *empty, h=h, d=mdl.d)
    kind = "none" if method == "none" else method
    dblk = delay_block(kind, tau, pade_order)
    plant = regulator_plant(a, b, K, winch, dblk)
    G, _, _ = ct.lqr(plant.A, plant.B1, _pad_Q(Q, plant.n), np.array([[R]]))
    return LQRDesign(np.asarray(G), method, float(tau), n_p, Ap, Bp, Ep,
                     np.asarray(dblk.A), np.asarray(dblk.B))


def design_from_gains(a: float, b: float, G: np.ndarray, *, tau: float = 0.0,
                      method: str = "none", K: float = 1.0) -> LQRDesign:
    """Wrap printed gains (e.g. :data:`cable_ocp.heave.thesis.G3_626`, ``G5_626``) as a design.

    Parameters
    ----------
    a, b : float
        Unit coefficients (6.2), s^2 and s.
    G : numpy.ndarray
        The printed gains.
    tau : float
        Delay, s.
    method : str
        Delay handling of the design (:func:`design_lqr`).
    K : float
        First-order winch gain, 1/s.
    """
    base = regulator_plant(a, b, K)
    G = np.atleast_2d(np.asarray(G, dtype=float))
    if method == "none":
        Af, Bf = np.zeros((0, 0)), np.zeros((0, 1))
    else:
        blk = delay_block(method, tau)
        Af, Bf = np.asarray(blk.A), np.asarray(blk.B)
    if G.shape[1] != base.n + Af.shape[0]:
        raise CableOCPError(f"gain has {G.shape[1]} entries; expected {base.n + Af.shape[0]}")
    return LQRDesign(G, method, float(tau), base.n, base.A, base.B1, base.B2, Af, Bf)


# --------------------------------------------------------------------------------------------
# True delayed loop: stability versus the actual delay
# --------------------------------------------------------------------------------------------
def _loop_responses(des: LQRDesign, w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``L1(i w) = Gp (iwI - Ap)^{-1} Bp`` and ``L2(i w) = Gf (iwI - Af)^{-1} Bf``."""
    s = 1j * np.asarray(w, dtype=float).reshape(-1)

    def resp(G: np.ndarray, A: np.ndarray, B: np.ndarray) -> np.ndarray:
        n = A.shape[0]
        if n == 0:
            return np.zeros(s.size, dtype=complex)
        M = s[:, None, None] * np.eye(n)[None] - A[None]
        X = np.linalg.solve(M, np.broadcast_to(B, (s.size, n, 1)))
        return (G[None] @ X)[:, 0, 0]

    return resp(des.Gp, des.Ap, des.Bp), resp(des.Gf, des.Af, des.Bf)


def _check_continuous(des: LQRDesign) -> None:
    if des.method == "discrete":
        raise CableOCPError("use discrete_delay_interval() for a discrete design")


def crossing_delays(des: LQRDesign, tau_max: float = 5.0) -> np.ndarray:
    """Delays in ``(0, tau_max]`` at which a root of ``1 + L2 + L1 e^{-s tau}`` is on ``i R``.

    At a crossing ``s = i w``: ``|L1(i w)| = |1 + L2(i w)|`` and ``e^{-i w tau} =
    -(1 + L2)/L1``, so ``tau = (-arg(-(1+L2)/L1) mod 2 pi + 2 pi k) / w``. Crossing frequencies
    are bracketed on a fine log grid and refined with Brent's method.

    Parameters
    ----------
    des : LQRDesign
        The design.
    tau_max : float
        Largest delay searched, s.
    """
    _check_continuous(des)

    def g(lw: float) -> float:
        L1, L2 = _loop_responses(des, np.array([np.exp(lw)]))
        return float(np.log(abs(L1[0])) - np.log(abs(1 + L2[0])))

    lw = np.linspace(np.log(1e-4), np.log(1e4), 4000)
    L1, L2 = _loop_responses(des, np.exp(lw))
    gv = np.log(np.abs(L1)) - np.log(np.abs(1 + L2))
    taus = []
    for i in np.nonzero(np.sign(gv[:-1]) != np.sign(gv[1:]))[0]:
        lc = optimize.brentq(g, lw[i], lw[i + 1], xtol=1e-14)
        wc = np.exp(lc)
        l1, l2 = _loop_responses(des, np.array([wc]))
        z = -(1 + l2[0]) / l1[0]
        t0 = (-np.angle(z)) % (2 * np.pi) / wc
        k = 0
        while t0 + 2 * np.pi * k / wc <= tau_max:
            t = t0 + 2 * np.pi * k / wc
            if t > 0:
                taus.append(t)
            k += 1
    return np.array(sorted(taus))


def unstable_roots(des: LQRDesign, tau: float) -> int:
    """Number of closed-loop roots in the open right half-plane for the true delay ``tau``.

    Nyquist's argument principle for ``f(s) = 1 + L2(s) + L1(s) e^{-s tau}``: ``Z = P - Delta /
    pi`` with ``Delta`` the net phase change of ``f(i w)`` over ``w`` in ``[0, inf)`` and ``P = 0``
    (plant and delay model are stable). Independent of :func:`crossing_delays`; at ``tau = 0`` it
    must agree with the eigenvalues of the delay-free closed loop.

    Parameters
    ----------
    des : LQRDesign
        The design.
    tau : float
        True delay, s.
    """
    _check_continuous(des)
    if max(np.linalg.eigvals(des.Ap).real.max(),
           np.linalg.eigvals(des.Af).real.max() if des.Af.size else -1.0) >= 0:
        raise CableOCPError("open loop is not stable; Nyquist count needs P")
    wl = np.logspace(-5, 5, 3000)
    L1, L2 = _loop_responses(des, wl)
    big = np.nonzero(np.abs(L1) + np.abs(L2) >= 0.5)[0]
    wmax = 2.0 * wl[big[-1]] if big.size else 1.0
    step = min(0.02 / max(tau, 1e-3), wmax / 2000)
    w = np.unique(np.concatenate([[0.0], np.logspace(-6, np.log10(wmax), 3000),
                                  np.arange(0.0, wmax, step)]))
    L1, L2 = _loop_responses(des, w)
    f = 1 + L2 + L1 * np.exp(-1j * w * tau)
    ph = np.unwrap(np.angle(f))
    delta = (ph[-1] - ph[0]) + (0.0 - np.angle(f[-1]))
    return int(round(-delta / np.pi))


@dataclass(frozen=True)
class DelayInterval:
    """Range of true delays over which a design's loop is stable.

    Attributes
    ----------
    lower, upper : float
        Stable for every true delay in ``(lower, upper)``, s; ``lower = 0`` if stable at zero.
        NaN if the loop is unstable at the design delay.
    stable_at_design : bool
        Whether the loop is stable at the design delay.
    """

    lower: float
    upper: float
    stable_at_design: bool


def delay_interval(des: LQRDesign, tau_max: float = 5.0) -> DelayInterval:
    """Stable interval of true delays containing the design delay (continuous designs).

    Roots cross the imaginary axis only at :func:`crossing_delays`; the number of unstable roots
    is constant in between and is counted with :func:`unstable_roots`.

    Parameters
    ----------
    des : LQRDesign
        The design.
    tau_max : float
        Largest delay searched, s.
    """
    cr = crossing_delays(des, tau_max)
    edges = np.concatenate([[0.0], cr, [tau_max]])
    t = des.tau
    i = int(np.searchsorted(edges, t, side="right") - 1)
    i = min(max(i, 0), len(edges) - 2)
    lo, hi = edges[i], edges[i + 1]
    probe = t if (lo < t < hi) else 0.5 * (lo + hi)
    stable = unstable_roots(des, probe) == 0
    if not stable:
        return DelayInterval(float("nan"), float("nan"), False)
    return DelayInterval(float(lo), float(hi), True)


def delay_margin(des: LQRDesign, tau_max: float = 5.0) -> float:
    """Largest true delay the design tolerates (upper end of the stable interval), s.

    Parameters
    ----------
    des : LQRDesign
        The design.
    tau_max : float
        Largest delay searched, s.
    """
    if des.method == "discrete":
        return discrete_delay_margin(des, tau_max)
    return delay_interval(des, tau_max).upper


def true_discrete_loop(des: LQRDesign, tau_true: float, h: float | None = None
                       ) -> ct.StateSpace:
    """Sampled closed loop with the exact true delay; input ``x0``, outputs ``[x, x', u, u0]``.

    Continuous designs are run at ``h`` (default 0.01 s) with their delay model discretised by
    ZOH (a sampled-data approximation, error O(h)); discrete designs at their own ``h`` with
    their own command buffer. The plant sees ``u0(t - tau_true)`` exactly, for any
    ``tau_true``.

    Parameters
    ----------
    des : LQRDesign
        The design.
    tau_true : float
        True delay, s.
    h : float, optional
        Sample time of a continuous design's loop, s (default 0.01 s).
    """
    if des.method == "discrete":
        h = des.h
    elif h is None:
        h = 0.01
    n_p = des.n_p
    mdl = discretize_delayed(des.Ap, des.Bp, h, tau_true, des.Ep)
    m = mdl.d
    if des.method == "discrete":
        nb = max(m, des.d)
        # State [xp; u_{k-nb} .. u_{k-1}]; embed the plant's buffer (last m) in the longer one.
        N = n_p + nb
        A = np.zeros((N, N))
        B = np.zeros((N, 1))
        A[:n_p, :n_p] = mdl.Ad[:n_p, :n_p]
        A[:n_p, n_p + nb - m : n_p + nb] = mdl.Ad[:n_p, n_p:]
        bu = mdl.Bd[:n_p]
        for i in range(nb - 1):
            A[n_p + i, n_p + i + 1] = 1.0
        if nb:
            B[-1, 0] = 1.0
        # Command u_k = -Gp x - Gb buf_last_d.
        Kc = np.zeros((1, N))
        Kc[:, :n_p] = des.Gp
        if des.d:
            Kc[:, n_p + nb - des.d :] = des.Gf
        Acl = A - (np.vstack([bu, B[n_p:]]) @ Kc)
        E = np.zeros((N, 1))
        E[:n_p] = mdl.Ed[:n_p]
        Cu0 = -Kc
    else:
        nf = des.Af.shape[0]
        if nf:
            Phf = discretize_delayed(des.Af, des.Bf, h, 0.0)
            Af_d, Bf_d = Phf.Ad, Phf.Bd
        else:
            Af_d, Bf_d = np.zeros((0, 0)), np.zeros((0, 1))
        N = mdl.Ad.shape[0] + nf
        A = np.zeros((N, N))
        B = np.zeros((N, 1))
        A[: mdl.Ad.shape[0], : mdl.Ad.shape[0]] = mdl.Ad
        B[: mdl.Ad.shape[0]] = mdl.Bd
        A[mdl.Ad.shape[0] :, mdl.Ad.shape[0] :] = Af_d
        B[mdl.Ad.shape[0] :] = Bf_d
        Kc = np.zeros((1, N))
        Kc[:, :n_p] = des.Gp
        Kc[:, mdl.Ad.shape[0] :] = des.Gf
        Acl = A - B @ Kc
        E = np.zeros((N, 1))
        E[:n_p] = mdl.Ed[:n_p]
        Cu0 = -Kc
    C = np.vstack([np.eye(N)[:3], Cu0])
    return ct.ss(Acl, E, C, 0, dt=h, inputs=["x0"], outputs=["x", "x_dot", "u", "u0"])


def discrete_delay_margin(des: LQRDesign, tau_max: float = 5.0) -> float:
    """Largest true delay >= the design delay keeping a sampled loop stable (bisection), s.

    The spectral radius of :func:`true_discrete_loop` is scanned in steps of ``h / 4`` from the
    design delay and the first crossing of 1 refined by bisection to 1e-6 s.

    Parameters
    ----------
    des : LQRDesign
        The design.
    tau_max : float
        Largest delay searched, s.
    """
    def rho(t: float) -> float:
        return float(np.max(np.abs(np.linalg.eigvals(true_discrete_loop(des, t).A))))

    h = des.h if des.method == "discrete" else 0.01
    t = des.tau
    if rho(t) >= 1:
        return float("nan")
    step = h / 4
    while t + step <= tau_max:
        if rho(t + step) >= 1:
            lo, hi = t, t + step
            while hi - lo > 1e-6:
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if rho(mid) < 1 else (lo, mid)
            return float(lo)
        t += step
    return float(tau_max)


# --------------------------------------------------------------------------------------------
# Indices and trade-off curves
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Indices:
    """Indices of Huang (1992) eqs. (6.16)-(6.18) for one design on one boom-tip record.

    Attributes
    ----------
    J_d : float
        ``int x^2 dt``, m^2 s.
    J_v : float
        ``int x'^2 dt``, m^2/s.
    J_c : float
        ``sum G_i^2`` (6.18). It depends on the coordinates of the controller's internal delay
        states: for a Pade design (realised by ``control.ss(control.tf(...))``) any similarity
        transform of that realisation gives the same controller and a different ``J_c``. Use
        it only for designs whose states are physical (undelayed, Taylor (6.14)).
    J_w : float
        ``int u'^2 dt``, m^2/s: the winch-speed energy, a coordinate-free control-effort
        measure that compares any two controllers (docs/conventions.md: the winch speed is "the
        comparison that holds across controllers"). Evaluated from the winch output ``u`` of
        the loop as ``sum ((u_{k+1} - u_k) / dt)^2 dt`` (mean speed over each loop step).
    stable : bool
        Whether the sampled true loop is stable.
    """

    J_d: float
    J_v: float
    J_c: float
    stable: bool
    J_w: float = float("nan")


def indices(des: LQRDesign, tau_true: float, t: np.ndarray, x0: np.ndarray,
            h: float | None = None) -> Indices:
    """Run the true delayed loop on the boom-tip record ``x0(t)``: (6.16)-(6.18) and ``J_w``.

    ``t`` must be uniform with the loop's sample time (0.01 s for continuous designs unless
    ``h`` is given, ``des.h`` for discrete ones).

    Parameters
    ----------
    des : LQRDesign
        The design.
    tau_true : float
        True delay, s.
    t : numpy.ndarray
        Uniform times, s.
    x0 : numpy.ndarray
        Boom-tip heave at ``t``, m.
    h : float, optional
        Sample time of a continuous design's loop, s.
    """
    sys = true_discrete_loop(des, tau_true, h)
    dt = float(sys.dt)
    if abs((t[1] - t[0]) - dt) > 1e-12:
        raise CableOCPError(f"boom-tip record step {t[1] - t[0]} s must equal the loop step {dt} s")
    stable = bool(np.max(np.abs(np.linalg.eigvals(sys.A))) < 1)
    if not stable:
        return Indices(J_d=float("inf"), J_v=float("inf"), J_c=des.control_energy, stable=False,
                       J_w=float("inf"))
    resp = ct.forced_response(sys, T=t, U=x0)
    y = np.asarray(resp.outputs)
    return Indices(J_d=float(np.sum(y[0] ** 2) * dt), J_v=float(np.sum(y[1] ** 2) * dt),
                   J_c=des.control_energy, stable=stable,
                   J_w=float(np.sum(np.diff(y[2]) ** 2) / dt))


def return_difference_min(A: np.ndarray, B: np.ndarray, G: np.ndarray) -> float:  # noqa: N803
    """``min_w |1 + G (i w I - A)^{-1} B|`` (Kalman's inverse-optimality test).

    A stabilising SISO state feedback is an LQR gain for some ``Q >= 0`` and ``R = 1`` only if
    this is >= 1 (Kalman 1964; Anderson & Moore, *Optimal Control*, section 5.2).

    Parameters
    ----------
    A, B : numpy.ndarray
        Plant and command column.
    G : numpy.ndarray
        State-feedback gain, ``u0 = -G x``.
    """
    w = np.concatenate([[0.0], np.logspace(-4, 4, 20000)])
    n = A.shape[0]
    vals = [abs(1 + (G @ np.linalg.solve(1j * wk * np.eye(n) - A, B))[0, 0]) for wk in w]
    i = int(np.argmin(vals))
    lo, hi = w[max(i - 1, 0)], w[min(i + 1, w.size - 1)]

    def f(wk: float) -> float:
        return abs(1 + (G @ np.linalg.solve(1j * wk * np.eye(n) - A, B))[0, 0])

    res = optimize.minimize_scalar(f, bounds=(lo, hi), method="bounded",
                                   options={"xatol": 1e-12})
    return float(min(res.fun, vals[i]))


def diagonal_weights_for_gain(A: np.ndarray, B: np.ndarray, G: np.ndarray,  # noqa: N803
                              R: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """The only diagonal ``Q`` (and its ``P``) for which a SISO gain ``G`` solves the LQR
    equations (inverse LQR, Huang (1992) (6.7)-(6.10) read backwards).

    With ``R B^T P = G`` the Riccati equation ``A^T P + P A - P B R^{-1} B^T P + Q = 0`` becomes
    linear in ``(P, Q)``: ``A^T P + P A + Q = G^T R G``. For ``n`` states that is
    ``n (n + 1) / 2 + n`` equations for the ``n (n + 1) / 2`` entries of ``P`` and the ``n``
    diagonal entries of ``Q``: square, solved directly. ``G`` is an LQR gain of a diagonal
    ``Q >= 0`` only if the returned ``Q`` is PSD (and ``P > 0``).

    Parameters
    ----------
    A, B : numpy.ndarray
        Plant and command column.
    G : numpy.ndarray
        State-feedback gain.
    R : float
        Command weight, 1/m^2.

    Raises
    ------
    CableOCPError
        If the linear system is singular (the diagonal ``Q`` is not unique).
    """
    A = np.asarray(A, dtype=float)
    n = A.shape[0]
    B = np.asarray(B, dtype=float).reshape(n, 1)
    G = np.asarray(G, dtype=float).reshape(1, n)
    idx = [(i, j) for i in range(n) for j in range(i, n)]
    npv = len(idx)

    def unpack(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        P = np.zeros((n, n))
        for k, (i, j) in enumerate(idx):
            P[i, j] = P[j, i] = x[k]
        return P, np.diag(x[npv:])

    def resid(x: np.ndarray) -> np.ndarray:
        P, Q = unpack(x)
        r1 = A.T @ P + P @ A + Q - R * G.T @ G
        return np.concatenate([[r1[i, j] for (i, j) in idx], (R * B.T @ P - G).ravel()])

    r0 = resid(np.zeros(npv + n))
    J = np.column_stack([resid(e) - r0 for e in np.eye(npv + n)])
    if np.linalg.matrix_rank(J) < J.shape[1]:
        raise CableOCPError("no unique diagonal Q for this gain (singular inverse-LQR system)")
    P, Q = unpack(np.linalg.solve(J, -r0))
    return Q, P


def tradeoff_curve(a: float, b: float, q_values: np.ndarray, t: np.ndarray, x0: np.ndarray,
                   *, tau: float, method: str, K: float = 1.0, pade_order: int = 2
                   ) -> list[tuple[float, Indices]]:
    """J_d, J_v, J_c and J_w for ``Q = diag(q, 0, 0)``, ``R = 1`` (Figs. 6.18-6.19).

    Each design is evaluated on the true loop with the delay ``tau``.

    Parameters
    ----------
    a, b : float
        Unit coefficients (6.2), s^2 and s.
    q_values : numpy.ndarray
        Heave weights, 1/m^2.
    t : numpy.ndarray
        Uniform times, s.
    x0 : numpy.ndarray
        Boom-tip heave at ``t``, m.
    tau : float
        Delay, s.
    method : str
        Delay handling (:func:`design_lqr`).
    K : float
        First-order winch gain, 1/s.
    pade_order : int
        Pade order for ``"pade"``.
    """
    out = []
    for q in np.asarray(q_values, dtype=float):
        des = design_lqr(a, b, np.diag([q, 0.0, 0.0]), 1.0, tau=tau, method=method, K=K,
                         pade_order=pade_order)
        out.append((float(q), indices(des, tau, t, x0)))
    return out


def tradeoff_data(a: float, b: float, K: float, tau: float, t: np.ndarray, x0: np.ndarray,
                  q_values: np.ndarray | None = None) -> dict:
    """Trade-off data of Huang (1992) Figs. 6.18-6.19 for ``Q = diag(q, 0, 0)``, ``R = 1``.

    The undelayed design on the undelayed plant and the Taylor and Pade designs on the true
    delayed plant. Returns ``{label: array of rows [J_w, J_d, J_v, J_c]}`` over the stable
    designs (:class:`cable_ocp.heave.lqr.Indices`). The effort axis is ``J_w = int u'^2 dt``
    (m^2/s), not the thesis' ``J_c = sum G_i^2`` (6.18): ``J_c`` of the Pade design depends on
    the arbitrary state realisation of the Pade filter, ``J_w`` on nothing but the loop.

    Parameters
    ----------
    a, b : float
        Unit coefficients (6.2), s^2 and s.
    K : float
        First-order winch gain, 1/s.
    tau : float
        Delay, s.
    t : numpy.ndarray
        Uniform times, s.
    x0 : numpy.ndarray
        Boom-tip heave at ``t``, m.
    q_values : numpy.ndarray, optional
        Heave weights, 1/m^2 (default a log grid).
    """
    q_values = np.logspace(1, 5, 7) if q_values is None else q_values
    out = {}
    for label, tt, meth in [("tau = 0", 0.0, "none"), (f"Taylor, tau = {tau:g} s", tau, "taylor"),
                            (f"Pade(2), tau = {tau:g} s", tau, "pade")]:
        cur = tradeoff_curve(a, b, q_values, t, x0, tau=tt, method=meth, K=K)
        out[label] = np.array([[c[1].J_w, c[1].J_d, c[1].J_v, c[1].J_c] for c in cur
                               if c[1].stable]).reshape(-1, 4)
    return out
