"""Model predictive control of the heave compensator in CasADi.

Prediction model: the assembled plant (Huang 1992, eq. (6.28), or the regulator plant (6.6)) sampled
exactly (ZOH) at ``h``, with the winch-command delay ``tau = d h`` as an **exact shift register**
of the last ``d`` commands: ``z = [x; u0_{k-d}, ..., u0_{k-1}]``
(:func:`cable_ocp.heave.discrete.discretize_delayed`), which the MPC keeps itself: the control
loop passes the plant's state to :meth:`LinearMPC.step` (:class:`cable_ocp.heave.delay.DelayLine`
holds the commands it sent). The cost is the continuous LQR cost
``int (q x^2 + r u0^2) dt`` sampled exactly, with the DARE solution as terminal cost, so that
without active constraints and delay the MPC reproduces the discrete LQR.

Limits (docs/conventions.md, "Heave compensation"):

* hard: stroke ``|u| <= stroke_max`` and winch speed ``|u'| <= speed_max`` for either winch. For
  the first-order winch (6.1) with a held command, ``u`` moves monotonically between samples and
  ``|u'|`` is largest just after a sample, so the limits imposed at the samples hold in continuous
  time; the acceleration of that winch is impulsive at every sample, so instead the change of the
  command per sample is limited (``command_rate_max``, m per sample). For the second-order winch
  the acceleration ``u''`` is limited at the samples (``accel_max``).
* soft: cable tension ``T = T_0 + (m/a) (x0 + u - x) >= T_min`` through a nonnegative slack with
  quadratic and exact linear (L1) penalties, when the plant carries tension (``[unit] mass`` and
  ``static_tension`` given).
* the winch motor (``[winch] drum_radius``, :mod:`cable_ocp.physics.winch_drive`): the torque
  ``|R T + J u''/R| <= torque_max`` (soft, exact while feasible: the tension's slack and
  penalties, the rows scaled to metres of stretch; linear in the state and the commands) and
  the power
  ``|tau u'/R| <= power_max``. The power is bilinear: the QP linearises it about the static
  tension (drum at rest), ``|T0 u'| <= power_max``, a speed limit; the IPOPT formulation
  keeps it exact. Both at the samples, once the sample's command is applied
  (:func:`cable_ocp.heave.mpc_drive.drive_rows`).

Wave preview: the boom-tip motion known ``preview_time`` s ahead enters as a known additive input
on the unit's ``x0`` channel that corrects the shaping-filter prediction to the forecast.

Solvers: ``"daqp"`` (the default), ``"qpoases"``, ``"osqp"``, ``"qrqp"`` solve a **condensed dense
QP** (decision variables: the ``N`` commands and one tension slack per kept tension row); Hessian
and constraint matrix are constant and computed once, and the gradient and the bounds are affine
in the parameters (state, previous command, boom-tip input), so a step assembles them with one
precomputed matrix-vector product. ``"daqp"`` is the dual active-set solver of Arnström, Bemporad
& Axehill (2022), called directly: its workspace keeps the Cholesky factor of the Hessian, the
constraint matrix in its factored (LDP) form and the working set between steps, so a step costs
``O(N^2)`` with no refactorisation; while the tension limit does not bind it solves the smaller
QP without tension rows and slacks, exactly (:class:`cable_ocp.heave.mpc_daqp.DaqpQP`). The
others go through CasADi's ``conic`` interface, which sets the solver up again at every call
(cost growing as ``N^3``); they are kept for comparison. ``"ipopt"`` solves a multiple-shooting
NLP built once with CasADi ``nlpsol`` with exactly the QP's cost, limit rows and bounds (with
the linear unit the two are the same convex problem); it can use the nonlinear unit model
(6.3). Every solver is built once and warm-started: DAQP from the previous working set, the
others with the shifted previous solution.
"""

from __future__ import annotations

import contextlib
import ctypes
import io
import os
import sys
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import casadi as cs
import numpy as np
from scipy import linalg

from cable_ocp.errors import CableOCPError
from cable_ocp.heave.delay import DelayLine
from cable_ocp.heave.discrete import discretize_cost, discretize_delayed
from cable_ocp.heave.mpc_daqp import DaqpQP
from cable_ocp.heave.mpc_drive import drive_rows
from cable_ocp.heave.plant import HeavePlant
from cable_ocp.numerics import interrupt
from cable_ocp.physics.drag import quadratic_drag

QP_SOLVERS = ("qpoases", "osqp", "qrqp")  # condensed QP through CasADi's ``conic``
DIRECT_SOLVERS = ("daqp",)  # condensed QP in a persistent solver workspace
SOLVERS = DIRECT_SOLVERS + QP_SOLVERS + ("ipopt",)


@dataclass(frozen=True)
class MPCSettings:
    """MPC settings (``[controller]`` and ``[winch]`` limits of a heave scene).

    Attributes
    ----------
    horizon : int
        Prediction horizon ``N`` (samples).
    sample_time : float
        ``h``, s.
    q : float
        Weight on the unit's heave, 1/m^2. The default 553.6 is a calibration (Huang 1992,
        6.3.6, states no weights): fitted so that the delay-free 11-state LQR gives the
        thesis' controlled 2.96e-4 m.
    r : float
        Weight on the winch command, 1/m^2.
    solver : str
        One of :data:`SOLVERS`.
    stroke_max, speed_max : float or None
        Hard limits on ``|u|`` (m) and ``|u'|`` (m/s).
    command_rate_max : float or None
        Hard limit on ``|u0_k - u0_{k-1}|`` (m per sample; first-order winch).
    accel_max : float or None
        Hard limit on ``|u''|`` (m/s^2; second-order winch only).
    tension_min : float or None
        Soft lower limit on the tension at the unit, N (needs ``unit_mass``, ``static_tension``).
    unit_mass : float
        Unit mass (incl. added mass), kg; the cable stiffness is ``unit_mass / a``.
    static_tension : float
        Static tension at the unit, N.
    tension_penalty : float
        Quadratic penalty on the tension slack (1/m^2, slack in metres of stretch); the linear
        penalty is ``sqrt`` of it times 10, enough to make the soft limit exact when feasible.
    preview_time : float
        Wave preview, s (0: none).
    terminal : str
        ``"dare"`` (terminal cost from the discrete Riccati equation) or ``"none"``.
    nonlinear_b : float
        Quadratic damping ``b`` of (6.3) for the IPOPT prediction model (0: linear model).
    solver_options : dict
        Extra options passed to the CasADi solver plugin (for ``"daqp"``: DAQP settings such as
        ``primal_tol``).
    drum_radius, drum_inertia : float or None
        The winch drum's radius (m) and inertia at its shaft (kg m^2).
    torque_max : float or None
        Soft limit on the motor torque ``|R T + J u''/R|``, N m (needs the tension data and
        ``drum_radius``; the tension's penalties, exact while the limit can be kept).
    power_max : float or None
        Limit on the motor power ``|tau u'/R|``, W: linearised about the static tension
        (``|T0 u'| <= power_max``) in the QP, exact (bilinear) with ``"ipopt"``.
    """

    horizon: int = 50
    sample_time: float = 0.05
    q: float = 553.6  # 1/m^2; a calibration: 6.3.6's LQR gives the thesis' 2.96e-4 m
    r: float = 1.0
    solver: str = "daqp"
    stroke_max: float | None = None
    speed_max: float | None = None
    command_rate_max: float | None = None
    accel_max: float | None = None
    tension_min: float | None = None
    unit_mass: float = 0.0
    static_tension: float = 0.0
    tension_penalty: float = 1e6
    preview_time: float = 0.0
    terminal: str = "dare"
    nonlinear_b: float = 0.0
    solver_options: dict = field(default_factory=dict, hash=False)
    drum_radius: float | None = None
    drum_inertia: float = 0.0
    torque_max: float | None = None
    power_max: float | None = None


@dataclass(frozen=True)
class MPCStep:
    """Result of one :meth:`LinearMPC.step`.

    Attributes
    ----------
    u0 : float
        Command to apply now, m.
    success : bool
        Solver status.
    solve_time : float
        Wall time of the step (bounds/gradient assembly + solve), s.
    plan : numpy.ndarray
        Planned commands ``u0_k .. u0_{k+N-1}``, m.
    max_slack : float
        Largest tension slack (m of stretch; 0 if the tension limit is inactive).
    """

    u0: float
    success: bool
    solve_time: float
    plan: np.ndarray
    max_slack: float


@dataclass(frozen=True)
class _Row:
    """One limit at prediction step ``k``: ``c_z z_k + c_u u0_k + c_p u0_{k-1} + c_D D_k``
    (plus a tension slack if ``slack``) within ``[-limit, limit]``, or ``>= limit`` if
    ``lo_only``; ``tag`` ``"power"`` marks the linearised power rows (IPOPT writes the power
    exactly instead)."""

    k: int
    cz: np.ndarray
    cu: float
    cp: float
    cd: float
    limit: float
    lo_only: bool
    slack: bool
    tag: str = ""


def _winch_indices(plant: HeavePlant) -> tuple[int, int | None]:
    sl = plant.blocks["winch"]
    iu = sl.start
    iud = sl.start + 1 if plant.winch_model == "second_order" else None
    return iu, iud


class LinearMPC:
    """Condensed linear MPC, built once (see module docstring).

    Parameters
    ----------
    plant : HeavePlant
        Undelayed plant; its first input is the winch command ``u0``. If its disturbance input
        is ``w`` (full plant (6.28)) the sea is predicted by the shaping filter; if it is ``x0``
        (regulator plant) the boom-tip motion must be supplied as a known sequence.
    tau : float
        Winch-command delay, s (integer multiple of ``sample_time``).
    settings : MPCSettings
        Horizon, weights, limits, solver.
    """

    def __init__(self, plant: HeavePlant, tau: float, settings: MPCSettings) -> None:
        s = settings
        if s.solver not in SOLVERS:
            raise CableOCPError(f"controller.solver = {s.solver!r}: valid are "
                                + ", ".join(f'"{v}"' for v in SOLVERS))
        if not (isinstance(s.horizon, int) and s.horizon >= 1):
            raise CableOCPError(f"controller.horizon = {s.horizon!r}: expected an integer >= 1")
        _check_settings(s)
        h = s.sample_time
        if abs(tau / h - round(tau / h)) > 1e-9:
            raise CableOCPError(
                f"winch.delay = {tau!r}: must be an integer multiple of "
                f"controller.sample_time = {h} s (exact shift register)"
            )
        if s.accel_max is not None and plant.winch_model != "second_order":
            raise CableOCPError(
                'winch.accel_max: needs winch.model = "second_order"; for the first-order '
                "winch limit winch.command_rate_max (m per sample) instead"
            )
        if s.tension_min is not None and not (s.unit_mass > 0):
            raise CableOCPError("winch.tension_min: needs unit.mass > 0 (kg) and "
                                "unit.static_tension (N)")
        self.plant = plant
        self.settings = s
        self.tau = float(tau)
        self.N = N = s.horizon
        n = plant.n
        self.n = n
        self.exogenous_x0 = plant.sys.input_labels[1] == "x0"
        # Known additive boom-tip input on the unit's x0 channel.
        e_x0 = np.zeros((n, 1))
        e_x0[plant.blocks["unit"].start + 1, 0] = 1.0 / plant.a
        comp = plant.blocks.get("comp")
        if comp is not None and comp.stop > comp.start:
            # the compensator sees x0 as it sees the winch output u
            e_x0[comp.start, 0] = plant.A[comp.start, plant.blocks["winch"].start]
        cx = plant.e("x")
        mdl = discretize_delayed(plant.A, plant.B1, h, tau, e_x0)
        self.model = mdl
        A, B, E = mdl.Ad, mdl.Bd, mdl.Ed
        nz = A.shape[0]
        self.nz = nz
        d = mdl.d
        Qz, Rz, Nz = discretize_cost(plant.A, plant.B1, s.q * cx.T @ cx, s.r, h, d)
        self.Qz, self.Rz, self.Nz = Qz, Rz, Nz
        if s.terminal == "dare":
            P = linalg.solve_discrete_are(A, B, Qz, Rz, s=Nz)
        elif s.terminal == "none":
            P = np.zeros((nz, nz))
        else:
            raise CableOCPError(f'controller.terminal = {s.terminal!r}: valid are "dare", "none"')
        self.P = 0.5 * (P + P.T)
        self.K_lqr = np.linalg.solve(Rz + B.T @ self.P @ B, B.T @ self.P @ A + Nz.T)
        # Prediction: z_k = S[k] z0 + T[k] U + W[k] D, k = 0..N.
        S = np.zeros((N + 1, nz, nz))
        T = np.zeros((N + 1, nz, N))
        W = np.zeros((N + 1, nz, N))
        S[0] = np.eye(nz)
        for k in range(N):
            S[k + 1] = A @ S[k]
            T[k + 1] = A @ T[k]
            T[k + 1][:, k] += B[:, 0]
            W[k + 1] = A @ W[k]
            W[k + 1][:, k] += E[:, 0]
        self._S, self._T, self._W = S, T, W
        # Condensed cost 0.5 U'HU + g'U, g = Gz z0 + Gd D.
        H = np.zeros((N, N))
        Gz = np.zeros((N, nz))
        Gd = np.zeros((N, N))
        for k in range(N + 1):
            Qk = self.P if k == N else Qz
            Tk = T[k]
            H += 2 * Tk.T @ Qk @ Tk
            Gz += 2 * Tk.T @ Qk @ S[k]
            Gd += 2 * Tk.T @ Qk @ W[k]
            if k < N:
                ek = np.zeros((1, N))
                ek[0, k] = 1.0
                H += 2 * (Tk.T @ Nz @ ek + ek.T @ Nz.T @ Tk + ek.T @ Rz @ ek)
                Gz += 2 * ek.T @ Nz.T @ S[k]
                Gd += 2 * ek.T @ Nz.T @ W[k]
        self._build_constraints(plant)
        nv = N + self.ns
        Hf = np.zeros((nv, nv))
        Hf[:N, :N] = 0.5 * (H + H.T)
        self.g_slack = np.zeros(nv)
        if self.ns:
            Hf[N:, N:] = 2 * s.tension_penalty * np.eye(self.ns)
            self.g_slack[N:] = 10.0 * np.sqrt(s.tension_penalty)
        self.H = Hf
        self.Gz = np.vstack([Gz, np.zeros((self.ns, nz))])
        self.Gd = np.vstack([Gd, np.zeros((self.ns, N))])
        # Command bounds |u0| <= stroke_max. For the first-order winch the output is a convex
        # combination of its state and its held commands, so with these bounds the stroke limit
        # can never become infeasible (it is implied from the first free sample on), and
        # holding the last command keeps the command-rate limit. The speed limit (and the
        # second-order winch's limits) has no terminal constraint, so recursive feasibility is
        # NOT guaranteed for it: the shifted plan can violate the speed row appended at the end
        # of the horizon. No infeasible step occurred in the examples; if one does, ``step``
        # falls back on the shifted previous plan and reports ``success = False``. For the
        # second-order winch the bound is a sensible extra limit, not a guarantee.
        ulim = np.inf if s.stroke_max is None else s.stroke_max
        self.lbx = np.concatenate([np.full(N, -ulim), np.zeros(self.ns)])
        self.ubx = np.concatenate([np.full(N, ulim), np.full(self.ns, np.inf)])
        # Parametric maps: [g; c] = Pz z0 + PD D + Pu u_prev + p0, with g the QP gradient and
        # c the part of the limit rows fixed by the parameters (bounds lb0 - c, ub0 - c).
        self._nv = nv
        self._Pz = np.ascontiguousarray(np.vstack([self.Gz, self.Cz]))
        self._PD = np.ascontiguousarray(np.vstack([self.Gd, self.CD]))
        self._Pu = np.concatenate([np.zeros(nv), self.Cup])
        self._p0 = np.concatenate([self.g_slack, np.zeros(self.Ac.shape[0])])
        self._solver = None
        self._daqp: DaqpQP | None = None
        if s.solver in QP_SOLVERS:
            self._build_qp()
        elif s.solver == "daqp":
            self._daqp = DaqpQP(self, SOLVERS[1:])
        else:
            self._nlp = _NonlinearMPC(self)
        self._warm = None
        self._first = True
        self._last_plan: np.ndarray | None = None
        self._solves = 0
        self.n_preview = int(round(s.preview_time / h))
        #: the MPC's own shift register of its last ``d`` commands (:meth:`step`)
        self.delay = DelayLine(d)
        self._z0 = np.zeros(nz)  # the state of a step: [x; own buffer]

    def reset(self) -> None:
        """Back to the start of a run: the delay buffer and the last command zero, no plan
        to fall back on, the solver's warm start and working set cleared."""
        self.delay.reset()
        self._last_plan = None
        self._warm = None
        if self._solves:
            if self._daqp is not None:
                self._daqp.reset()
            elif self._solver is None:
                self._nlp.warm = None
        self._solves = 0

    # ---------------------------------------------------------------------------------------
    def _build_constraints(self, plant: HeavePlant) -> None:
        """Limit rows, built once as step-wise descriptors and condensed for the QP.

        Each limit is a row ``lim_lo <= c_z z_k + c_u u0_k + c_p u0_{k-1} + c_D D_k (+ s) <=
        lim_hi`` on the predicted state ``z_k`` (:class:`_Row`); ``u0_{-1}`` is the previous
        command. Rows that no decision variable can change (fixed by commands already sent,
        ``k <= d``) are dropped: they can only make the problem infeasible. The condensed QP
        uses ``lb - c(z0, D, u_prev) <= A_c [U; S] <= ub - c(...)``; the IPOPT formulation
        (:class:`_NonlinearMPC`) writes the same rows on its shooting states.
        """
        s = self.settings
        N, nz, n, d = self.N, self.nz, self.n, self.model.d
        iu, iud = _winch_indices(plant)
        rows: list[_Row] = []

        def applied(k: int) -> tuple[np.ndarray, float]:
            """Applied (delayed) command at step k as (z-row, coefficient of u0_k)."""
            c = np.zeros(nz)
            if d > 0:
                c[n] = 1.0
                return c, 0.0
            return c, 1.0

        def add(k: int, cz: np.ndarray, cu: float, limit: float, cp: float = 0.0,
                cd: float = 0.0, lo_only: bool = False, slack: bool = False,
                tag: str = "") -> None:
            rU = cz @ self._T[k]
            if k < N:
                rU = rU.copy()
                rU[k] += cu
            if k > 0:
                rU = rU.copy()
                rU[k - 1] += cp
            if np.max(np.abs(rU)) < 1e-14:
                return  # fixed by the past: nothing to decide
            rows.append(_Row(k, cz, cu, cp, cd if k < N else 0.0, limit, lo_only, slack,
                             tag))

        eu = np.zeros(nz)
        eu[iu] = 1.0
        if s.stroke_max is not None:
            for k in range(1, N + 1):
                add(k, eu, 0.0, s.stroke_max)
        if s.speed_max is not None:
            if iud is None:
                K = plant.K
                for k in range(N):
                    cz, cu = applied(k)
                    add(k, K * (cz - eu), K * cu, s.speed_max)
            else:
                eud = np.zeros(nz)
                eud[iud] = 1.0
                for k in range(1, N + 1):
                    add(k, eud, 0.0, s.speed_max)
        if s.accel_max is not None:
            ww = float(np.sqrt(-plant.A[iu + 1, iu]))
            two_zw = float(-plant.A[iu + 1, iu + 1])
            eud = np.zeros(nz)
            eud[iud] = 1.0
            for k in range(N):
                cz, cu = applied(k)
                add(k, ww**2 * (cz - eu) - two_zw * eud, ww**2 * cu, s.accel_max)
        if s.command_rate_max is not None:
            for k in range(N):
                add(k, np.zeros(nz), 1.0, s.command_rate_max, cp=-1.0)
        self.drive_terms: dict[int, tuple] = {}
        drive = s.torque_max is not None or s.power_max is not None
        if drive:  # the power's hard rows before the soft rows
            self.drive_terms = drive_rows(self, plant, add, applied, eu, iu, iud, "power")
        if s.tension_min is not None:
            c_str, _ = plant.output_row("stretch")
            cs_ = np.zeros(nz)
            cs_[:n] = c_str
            kc = s.unit_mass / plant.a
            smin = (s.tension_min - s.static_tension) / kc
            for k in range(1, N + 1):
                # The known boom-tip correction D_k adds to the stretch.
                add(k, cs_, 0.0, smin, cd=1.0, lo_only=True, slack=True)
            self.stretch_min = smin
        if drive:  # the torque's soft rows last, after the tension's (mpc_daqp's stages)
            drive_rows(self, plant, add, applied, eu, iu, iud, "torque")
        self.rows = rows
        m = len(rows)
        self.slack_of_row = np.full(m, -1)
        ns = 0
        Ac = np.zeros((m, N + sum(r.slack for r in rows)))
        Cz = np.zeros((m, nz))
        CD = np.zeros((m, N))
        Cup = np.zeros(m)
        for i, r in enumerate(rows):
            k = r.k
            Ac[i, :N] = r.cz @ self._T[k]
            Cz[i] = r.cz @ self._S[k]
            CD[i] = r.cz @ self._W[k]
            if k < N:
                Ac[i, k] += r.cu
                CD[i, k] += r.cd
            if k > 0:
                Ac[i, k - 1] += r.cp
            else:
                Cup[i] = r.cp
            if r.slack:
                Ac[i, N + ns] = 1.0
                self.slack_of_row[i] = ns
                ns += 1
        self.ns = ns
        self.Ac, self.Cz, self.CD, self.Cup = Ac, Cz, CD, Cup
        lim_a = np.array([r.limit for r in rows], dtype=float)
        lo_only_a = np.array([r.lo_only for r in rows], dtype=bool)
        self.lb0 = np.where(lo_only_a, lim_a, -lim_a)
        self.ub0 = np.where(lo_only_a, np.inf, lim_a)

    def _build_qp(self) -> None:
        s = self.settings
        nv = self.H.shape[0]
        m = self.Ac.shape[0]
        opts: dict = {}
        if s.solver == "qpoases":
            opts = {"printLevel": "none", "error_on_fail": False}
        elif s.solver == "osqp":
            # Polishing off: OSQP prints "Polishing not needed ..." on every solve without
            # an active set, whatever ``verbose`` says. Every OSQP call is also silenced
            # (``step``), in case ``solver_options`` turns polishing back on.
            opts = {"osqp": {"verbose": False, "eps_abs": 1e-6, "eps_rel": 1e-6,
                             "polish": False}, "warm_start_primal": True,
                    "warm_start_dual": True, "error_on_fail": False}
        elif s.solver == "qrqp":
            opts = {"print_iter": False, "print_header": False, "print_info": False,
                    "error_on_fail": False}
        _merge(opts, s.solver_options)
        Hs = cs.Sparsity.dense(nv, nv)
        As = cs.Sparsity.dense(m, nv) if m else cs.Sparsity(0, nv)
        with _quiet_stdout():
            self._solver = cs.conic("heave_mpc", s.solver, {"h": Hs, "a": As}, opts)
        self._Hdm = cs.DM(self.H)
        self._Adm = cs.DM(self.Ac) if m else cs.DM(0, nv)

    # ---------------------------------------------------------------------------------------
    def preview_correction(self, x: np.ndarray, x0_forecast: np.ndarray) -> np.ndarray:
        """Known boom-tip input ``D`` that makes the prediction follow a forecast.

        For the full plant, ``D_k = forecast_k - (model's predicted x0)_k`` for the first
        ``n_preview`` steps and 0 after; for the regulator plant (boom tip exogenous), ``D`` is
        the forecast itself, held at its last value beyond the preview.

        Parameters
        ----------
        x : numpy.ndarray, shape (n,) or (nz,)
            The plant's state (the MPC's own delay buffer is appended, as in :meth:`step`),
            or a whole shift-register state ``z`` as :meth:`solve` takes.
        x0_forecast : numpy.ndarray
            Boom-tip heave at the next samples, m.
        """
        N = self.N
        z0 = self._state(x)
        D = np.zeros(N)
        f = np.asarray(x0_forecast, dtype=float)
        npv = min(self.n_preview if self.n_preview else N, N, f.size)
        if self.exogenous_x0:
            D[:npv] = f[:npv]
            if npv < N and npv > 0:
                D[npv:] = f[npv - 1]
            return D
        cx0, _ = self.plant.output_row("x0")
        c = np.zeros(self.nz)
        c[: self.n] = cx0
        for k in range(npv):
            D[k] = f[k] - c @ self._S[k] @ z0
        return D

    def _state(self, x: np.ndarray) -> np.ndarray:
        """``[x; own buffer]`` for a plant state ``x``; a state of size ``nz`` as it is."""
        x = np.asarray(x, dtype=float).reshape(-1)
        if x.size == self.nz:
            return x
        return np.concatenate([x, self.delay.buffer])

    def step(self, x: np.ndarray, u_prev: float | None = None, D: np.ndarray | None = None
             ) -> MPCStep:
        """One sample of the control loop: the first command of the plan from the plant's
        state ``x``; the MPC keeps the delay buffer itself.

        The state of the prediction is ``z0 = [x; u0_{k-d} .. u0_{k-1}]``, the buffer being the
        MPC's own past commands (:attr:`delay`, zero at the start and after :meth:`reset`);
        the command returned is shifted into it.

        Parameters
        ----------
        x : numpy.ndarray, shape (n,)
            The plant's state (measured or estimated).
        u_prev : float, optional
            Previous command (for the command-rate limit), m; default the MPC's own last
            command (0 at the start).
        D : numpy.ndarray, shape (N,), optional
            Known boom-tip input (see :meth:`preview_correction`), m.
        """
        t0 = time.perf_counter()
        z0, n, line = self._z0, self.n, self.delay
        try:
            z0[:n] = x
        except ValueError:
            raise CableOCPError(f"LinearMPC.step: the plant state has {np.size(x)} entries, "
                                f"expected n = {n} (the MPC keeps its own delay buffer; "
                                "LinearMPC.solve takes a whole shift-register state)") from None
        z0[n:] = line.buffer
        r = self._solve(z0, line.last if u_prev is None else u_prev, D, t0)
        line.push(r.u0)
        return r

    def solve(self, z0: np.ndarray, u_prev: float = 0.0, D: np.ndarray | None = None
              ) -> MPCStep:
        """Solve the MPC problem at a given shift-register state ``z0`` and return the first
        command; the MPC's own delay buffer is neither read nor changed (the control loop
        calls :meth:`step`).

        Parameters
        ----------
        z0 : numpy.ndarray, shape (nz,)
            ``[plant state; u0_{k-d} .. u0_{k-1}]``.
        u_prev : float
            Previous command (for the command-rate limit), m.
        D : numpy.ndarray, shape (N,), optional
            Known boom-tip input (see :meth:`preview_correction`), m.
        """
        t0 = time.perf_counter()
        return self._solve(np.asarray(z0, dtype=float).reshape(-1), u_prev, D, t0)

    def _solve(self, z0: np.ndarray, u_prev: float, D: np.ndarray | None, t0: float
               ) -> MPCStep:
        """The QP (or NLP) at ``z0``; ``t0`` the start of the timed step."""
        self._solves += 1
        N = self.N
        v = self._Pz @ z0
        v += self._p0
        if D is not None:
            v += self._PD @ np.asarray(D, dtype=float)
        if u_prev:
            v += u_prev * self._Pu
        g = v[: self._nv]
        c = v[self._nv :]
        if self._daqp is not None:
            x, ok = self._daqp.solve(g, c)
        elif self._solver is not None:
            lba = self.lb0 - c
            uba = self.ub0 - c
            args = {"h": self._Hdm, "g": g, "a": self._Adm, "lba": lba, "uba": uba,
                    "lbx": self.lbx, "ubx": self.ubx}
            if self._warm is not None:
                args.update(self._warm)
            if self._first or self.settings.solver == "osqp":
                # qpOASES prints a banner on its first call, OSQP's polish on every call (about
                # 16 us per call to redirect file descriptor 1; library code never prints).
                with _quiet_stdout():
                    sol = self._solver(**args)
                self._first = False
            else:
                sol = self._solver(**args)
            ok = bool(self._solver.stats().get("success", False))
            interrupt.check()  # a Ctrl-C that the QP solver turned into a failure
            if not ok and self._warm is not None:
                # A stale warm start (e.g. after a jump in the state) can make an active-set
                # solver fail (qrqp: "Failed to calculate search direction"): retry cold once.
                for key in self._warm:
                    args.pop(key)
                with _quiet_stdout():
                    sol = self._solver(**args)
                ok = bool(self._solver.stats().get("success", False))
            x = np.asarray(sol["x"]).ravel()
            if ok:
                U, Sl = x[:N], x[N:]
                xs = np.concatenate([U[1:], U[-1:], Sl[1:], Sl[-1:]])
                self._warm = {"x0": xs, "lam_a0": np.asarray(sol["lam_a"]).ravel(),
                              "lam_x0": np.asarray(sol["lam_x"]).ravel()}
        else:
            x, ok = self._nlp.solve(z0, u_prev, np.zeros(N) if D is None else D)
        if not ok and self._last_plan is not None:
            # Fall back on the previous (feasible) plan shifted by one sample.
            x = np.concatenate([self._last_plan[1:], self._last_plan[-1:],
                                np.zeros(x.size - N)])
        self._last_plan = x[:N].copy()
        dt = time.perf_counter() - t0
        return MPCStep(u0=float(x[0]), success=ok, solve_time=dt, plan=x[:N].copy(),
                       max_slack=float(np.max(x[N:])) if x.size > N else 0.0)


def _check_settings(s: MPCSettings) -> None:
    """Reject settings that would fail deep inside a solver (names as in the scene file)."""
    rules = [("winch", "stroke_max", s.stroke_max, True), ("winch", "speed_max", s.speed_max, True),
             ("winch", "command_rate_max", s.command_rate_max, True),
             ("winch", "accel_max", s.accel_max, True),
             ("controller", "sample_time", s.sample_time, True),
             ("controller", "q", s.q, False), ("controller", "r", s.r, True),
             ("controller", "preview_time", s.preview_time, False),
             ("controller", "tension_penalty", s.tension_penalty, True),
             ("winch", "torque_max", s.torque_max, True),
             ("winch", "power_max", s.power_max, True)]
    for table, key, val, strict in rules:
        if val is None:
            continue
        if not (np.isfinite(val) and (val > 0 if strict else val >= 0)):
            raise CableOCPError(f"{table}.{key} = {val!r}: expected a finite number "
                                f"{'> 0' if strict else '>= 0'}")


@contextlib.contextmanager
def _quiet_stdout() -> Iterator[None]:
    """Silence a solver call (library code never prints).

    Two paths reach the terminal: CasADi routes its plugins' messages (qpOASES' banner, OSQP's
    polish notice) to Python's ``sys.stdout``, which is replaced by a sink here; C code that
    writes to file descriptor 1 directly is sent to ``/dev/null`` (C stdio buffers are flushed
    before the descriptor is restored, or they would surface later).
    """
    sink = io.StringIO()
    try:
        sys.stdout.flush()
        fd = os.dup(1)
    except (OSError, ValueError, AttributeError):
        with contextlib.redirect_stdout(sink):
            yield
        return
    try:
        with open(os.devnull, "w") as devnull:
            os.dup2(devnull.fileno(), 1)
            try:
                with contextlib.redirect_stdout(sink):
                    yield
            finally:
                _flush_c_stdio()
    finally:
        os.dup2(fd, 1)
        os.close(fd)


def _flush_c_stdio() -> None:
    """``fflush(NULL)`` of the C runtime (no-op where libc cannot be loaded)."""
    try:
        ctypes.CDLL(None).fflush(None)
    except (OSError, AttributeError, TypeError):
        pass


def _merge(opts: dict, extra: dict) -> None:
    for k, v in extra.items():
        if isinstance(v, dict) and isinstance(opts.get(k), dict):
            opts[k].update(v)
        else:
            opts[k] = v


class _NonlinearMPC:
    """Multiple-shooting NLP solved by IPOPT, built once (used by ``solver = "ipopt"``).

    Cost, limits, command bounds and slacks are exactly those of the condensed QP of
    :class:`LinearMPC`: the same stage cost ``z^T Qz z + 2 z^T Nz u + Rz u^2``, DARE terminal
    cost, the same limit rows (:class:`_Row`, including the dropping of rows fixed by commands
    already sent), ``|u0| <= stroke_max`` and one nonnegative slack per kept tension row with
    the same penalties. With the linear unit (6.2) the shooting constraints are the exact ZOH
    model ``z_{k+1} = Ad z_k + Bd u0_k + Ed D_k``, so the NLP *is* the QP (same minimiser; a
    test checks the closed-loop moves agree). If ``nonlinear_b > 0`` the plant part is
    integrated with RK4 (2 substeps per sample) with the unit's damping ``b |x'| x'`` (Huang (1992)
    eq. (6.3), smoothed as ``b x' sqrt(x'^2 + 1e-6)``) instead.
    """

    def __init__(self, mpc: LinearMPC) -> None:
        s = mpc.settings
        p = mpc.plant
        N, nz, n, d = mpc.N, mpc.nz, mpc.n, mpc.model.d
        h = s.sample_time
        bnl = s.nonlinear_b
        Z = cs.MX.sym("Z", nz, N + 1)
        U = cs.MX.sym("U", N)
        ns = mpc.ns
        Sl = cs.MX.sym("S", ns)
        P0 = cs.MX.sym("z0", nz)
        Pup = cs.MX.sym("up")
        PD = cs.MX.sym("D", N)
        if bnl > 0:
            F = self._rk4_plant(p, h, bnl)
        Ad, Bd, Ed = cs.DM(mpc.model.Ad), cs.DM(mpc.model.Bd), cs.DM(mpc.model.Ed)
        g = [Z[:, 0] - P0]
        J = 0
        Qz, Rz, Nz = cs.DM(mpc.Qz), cs.DM(mpc.Rz), cs.DM(mpc.Nz)
        for k in range(N):
            zk = Z[:, k]
            if bnl > 0:
                vk = zk[n] if d > 0 else U[k]
                xn = F(zk[:n], vk, PD[k])
                if d > 1:
                    bn = cs.vertcat(zk[n + 1 :], U[k])
                elif d == 1:
                    bn = U[k]
                else:
                    bn = cs.MX(0, 1)
                znext = cs.vertcat(xn, bn)
            else:
                znext = cs.mtimes(Ad, zk) + Bd * U[k] + Ed * PD[k]
            g.append(Z[:, k + 1] - znext)
            J += cs.bilin(Qz, zk, zk) + 2 * cs.mtimes([zk.T, Nz, U[k]]) + Rz * U[k] ** 2
        J += cs.bilin(cs.DM(mpc.P), Z[:, N], Z[:, N])
        lbg = [0.0] * (nz * (N + 1))
        ubg = [0.0] * (nz * (N + 1))
        for i, r in enumerate(mpc.rows):
            k = r.k
            if r.tag == "power":  # the bilinear power tau u' / R, exactly
                tz, tu, td, sz, su = mpc.drive_terms[k]
                R = s.drum_radius
                tau = (R * s.static_tension + cs.mtimes(cs.DM(tz).T, Z[:, k]) + tu * U[k]
                       + td * PD[k])
                g.append(tau * (cs.mtimes(cs.DM(sz).T, Z[:, k]) + su * U[k]) / R)
                lbg.append(-s.power_max)
                ubg.append(s.power_max)
                continue
            e = cs.mtimes(cs.DM(r.cz).T, Z[:, k])
            if k < N:
                e = e + r.cu * U[k] + r.cd * PD[k]
            e = e + r.cp * (U[k - 1] if k > 0 else Pup)
            j = int(mpc.slack_of_row[i])
            if j >= 0:
                e = e + Sl[j]
                J += s.tension_penalty * Sl[j] ** 2 + mpc.g_slack[N + j] * Sl[j]
            g.append(e)
            lbg.append(mpc.lb0[i])
            ubg.append(mpc.ub0[i])
        w = cs.vertcat(cs.vec(Z), U, Sl)
        nlp = {"x": w, "p": cs.vertcat(P0, Pup, PD), "f": J, "g": cs.vertcat(*g)}
        # No automatic NLP scaling: the gradient-based scaling divides the objective by the
        # slack penalty's large linear term, which loosens the effective tolerance to ~1e-5 m on
        # the moves; unscaled (SI units, well scaled here) tol 1e-10 gives ~1e-8 m.
        opts = {"ipopt": {"print_level": 0, "sb": "yes", "tol": 1e-10,
                          "nlp_scaling_method": "none",
                          "warm_start_init_point": "yes", "mu_init": 1e-4},
                "print_time": False, "error_on_fail": False}
        _merge(opts, s.solver_options)
        self.solver = cs.nlpsol("heave_nmpc", "ipopt", nlp, opts)
        self.lbg = np.array(lbg)
        self.ubg = np.array(ubg)
        nw = w.shape[0]
        self.lbw = np.full(nw, -np.inf)
        self.ubw = np.full(nw, np.inf)
        # Command and slack bounds exactly as the QP's lbx/ubx.
        self.lbw[nz * (N + 1) :] = mpc.lbx
        self.ubw[nz * (N + 1) :] = mpc.ubx
        self.nz, self.N, self.ns = nz, N, ns
        self.warm: dict | None = None

    @staticmethod
    def _rk4_plant(p: HeavePlant, h: float, bnl: float) -> cs.Function:
        """One sample of the plant with the quadratic damping (6.3), RK4 with 2 substeps."""
        n = p.n
        iv = p.blocks["unit"].start + 1
        x = cs.MX.sym("x", n)
        v = cs.MX.sym("v")
        dd = cs.MX.sym("dd")
        e_unit = np.zeros(n)
        e_unit[iv] = 1.0
        xd = x[iv]
        # (6.3)'s quadratic damping with the smooth modulus sqrt(v^2 + delta^2), delta = 1e-3 m/s
        corr = (p.b * xd - quadratic_drag(bnl, xd, 1e-3)) / p.a
        xdot = (cs.mtimes(cs.DM(p.A), x) + cs.DM(p.B1) * v
                + cs.DM(e_unit) * (dd / p.a + corr))
        f = cs.Function("f", [x, v, dd], [xdot])
        M = 2
        hh = h / M
        xk = x
        for _ in range(M):
            k1 = f(xk, v, dd)
            k2 = f(xk + hh / 2 * k1, v, dd)
            k3 = f(xk + hh / 2 * k2, v, dd)
            k4 = f(xk + hh * k3, v, dd)
            xk = xk + hh / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        return cs.Function("F", [x, v, dd], [xk])

    def solve(self, z0: np.ndarray, u_prev: float, D: np.ndarray) -> tuple[np.ndarray, bool]:
        nz, N = self.nz, self.N
        pv = np.concatenate([z0, [u_prev], D])
        args = {"p": pv, "lbg": self.lbg, "ubg": self.ubg, "lbx": self.lbw, "ubx": self.ubw}
        if self.warm is None:
            args["x0"] = np.concatenate([np.tile(z0, N + 1), np.zeros(N + self.ns)])
        else:
            args.update(self.warm)
        sol, st = interrupt.call_solver(self.solver, **args)
        ok = bool(st.get("success", False))
        w = np.asarray(sol["x"]).ravel()
        Zs = w[: nz * (N + 1)].reshape(N + 1, nz)
        rest = w[nz * (N + 1) :]
        if ok:
            Zsh = np.vstack([Zs[1:], Zs[-1:]]).ravel()
            U = rest[:N]
            Ush = np.concatenate([U[1:], U[-1:]])
            Ssh = np.concatenate([rest[N + 1 :], rest[-1:]]) if self.ns else rest[N:]
            self.warm = {"x0": np.concatenate([Zsh, Ush, Ssh]),
                         "lam_g0": np.asarray(sol["lam_g"]).ravel(),
                         "lam_x0": np.asarray(sol["lam_x"]).ravel()}
        return rest, ok


def settings_from_scene(scene: Any) -> MPCSettings:
    """The MPC settings a heave scene asks for (``[controller]``, ``[winch]`` limits,
    ``[unit]`` tension data), as the closed-loop simulation builds them.

    Parameters
    ----------
    scene : HeaveScene
        A validated heave scene (:func:`cable_ocp.scene.heave.load_scene`).
    """
    c, w, u = scene.controller, scene.winch, scene.unit
    return MPCSettings(
        horizon=c.horizon, sample_time=c.sample_time, q=c.q, r=c.r, solver=c.solver,
        stroke_max=w.stroke_max, speed_max=w.speed_max, command_rate_max=w.command_rate_max,
        accel_max=w.accel_max, tension_min=w.tension_min, unit_mass=u.mass,
        static_tension=u.static_tension, tension_penalty=c.tension_penalty,
        preview_time=c.preview_time, terminal=c.terminal,
        nonlinear_b=u.b_quadratic if u.model == "quadratic" else 0.0,
        drum_radius=w.drum_radius, drum_inertia=w.drum_inertia, torque_max=w.torque_max,
        power_max=w.power_max)
