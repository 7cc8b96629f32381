"""The DAQP backend of the linear MPC (``[controller] solver = "daqp"``, the default): the
condensed QP of :class:`cable_ocp.heave.mpc.LinearMPC` in persistent DAQP workspaces.

``mpc`` and ``others`` of :class:`DaqpQP`: the MPC whose QP it solves (its ``N``, ``H``,
``Ac``, ``lbx``, ``ubx``, ``lb0``, ``ub0``, ``ns``, ``slack_of_row`` and settings) and the
names of the other solvers (for the message when daqp is not installed).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from cable_ocp.errors import CableOCPError

if TYPE_CHECKING:
    from cable_ocp.heave.mpc import LinearMPC

__all__ = ["DaqpQP", "DaqpWorkspace"]


class DaqpQP:
    """The condensed QP of :class:`cable_ocp.heave.mpc.LinearMPC` in persistent DAQP
    workspaces (``"daqp"``).

    DAQP (Arnström, Bemporad & Axehill (2022), "A dual active-set solver for embedded quadratic
    programming using recursive LDL^T updates", IEEE Trans. Automatic Control) is set up once:
    the Cholesky factor ``R`` of the constant Hessian and the constant constraint matrix in its
    least-distance form ``A R^-1`` stay in the workspace. A step only updates the gradient and
    the bounds (``O(N^2)``) and starts from the previous step's working set (warm start), so an
    unchanged active set costs one iteration.

    The problem is the very QP the CasADi solvers get (``H``, ``A_c``, ``lbx``, ``ubx``, rows
    ``lb0 - c <= A_c [U; S] <= ub0 - c``); infinite bounds are passed as DAQP's ``1e30``. With a
    tension limit it is solved in two stages, exactly: first the QP in the commands alone with
    the hard limits (no tension rows, no slacks); if its solution keeps every tension row, it
    is the solution of the whole QP with zero slacks (the KKT conditions of the whole QP hold
    with zero tension multipliers: the slack bounds take the multipliers equal to the positive
    linear slack penalty). Only when a tension row would be violated is the whole QP solved
    (its own workspace, slack bounds starting in the working set), and then again at the next
    steps, directly, until no slack is positive. The reduced QP has half the variables and no
    slack bounds in its working set, which makes a step about 2-3x cheaper.

    Parameters
    ----------
    mpc : LinearMPC
        The MPC whose condensed QP this solves.
    others : tuple of str
        The other solvers (named when daqp is not installed).
    """

    def __init__(self, mpc: LinearMPC, others: tuple[str, ...]) -> None:
        try:
            import daqp
        except ImportError as exc:  # a hard dependency, but say what to do if it is missing
            raise CableOCPError(
                "[controller] solver = 'daqp' needs the daqp package (pip install daqp); "
                f"the other solvers are {others}"
            ) from exc
        N, nv, m, ns = mpc.N, mpc.H.shape[0], mpc.Ac.shape[0], mpc.ns
        st = daqp.Model().settings
        # Violations above primal_tol enter the working set. DAQP's default 1e-6 would let a
        # limit be exceeded by up to 1e-6 (m, m/s) and the moves differ from an exact QP
        # solution by as much; 1e-10 is far above round-off on these well-scaled rows.
        st["primal_tol"] = 1e-10
        unknown = set(mpc.settings.solver_options) - set(st)
        if unknown:
            raise CableOCPError(f"[controller] solver_options {sorted(unknown)} are not DAQP "
                                f"settings; valid: {sorted(st)}")
        st.update(mpc.settings.solver_options)
        self.tol = float(st["primal_tol"])
        sense = np.zeros(nv + m, dtype=np.intc)
        sense[N:nv] = DaqpWorkspace.ACTIVE_LOWER  # slacks are zero unless the tension binds
        self.full = DaqpWorkspace(daqp, st, mpc.H, mpc.Ac, mpc.lbx, mpc.ubx, mpc.lb0,
                                   mpc.ub0, sense)
        # Tension rows are built last (``LinearMPC._build_constraints``): rows [mh:] are soft.
        soft = mpc.slack_of_row >= 0
        mh = m - ns
        self.reduced: DaqpWorkspace | None = None
        self.binding = False  # the tension limit bound at the last step
        if ns and not soft[:mh].any() and soft[mh:].all():
            self.N, self.mh = N, mh
            self.reduced = DaqpWorkspace(
                daqp, st, mpc.H[:N, :N], mpc.Ac[:mh, :N], mpc.lbx[:N], mpc.ubx[:N],
                mpc.lb0[:mh], mpc.ub0[:mh], np.zeros(N + mh, dtype=np.intc))
            self.A_soft = np.ascontiguousarray(mpc.Ac[mh:, :N])
            self.lb_soft = mpc.lb0[mh:] - self.tol
            self.zeros_s = np.zeros(ns)

    def reset(self) -> None:
        """Cold working sets (as set up), the reduced QP first again."""
        for ws in (self.full, self.reduced):
            if ws is not None:
                ws.model.update(sense=ws.sense0.copy())
        self.binding = False

    def solve(self, g: np.ndarray, c: np.ndarray) -> tuple[np.ndarray, bool]:
        """Solve with gradient ``g`` and row offsets ``c``; returns ``(x, success)``.

        Parameters
        ----------
        g : numpy.ndarray
            The QP's gradient (commands, then slacks).
        c : numpy.ndarray
            The part of the limit rows fixed by the parameters (bounds ``lb0 - c``,
            ``ub0 - c``).
        """
        red = self.reduced
        if red is not None and not self.binding:
            N, mh = self.N, self.mh
            u, ok = red.solve(g[:N], c[:mh])
            if ok:
                t = self.A_soft @ u
                t += c[mh:]
                if (t >= self.lb_soft).all():
                    return np.concatenate([u, self.zeros_s]), True
        x, ok = self.full.solve(g, c)
        if red is not None:
            # While the tension binds, stay on the whole QP (its working set stays fresh
            # from step to step); back to the reduced QP once every slack is zero again.
            self.binding = ok and bool(np.max(x[self.N :]) > self.tol)
        return x, ok


class DaqpWorkspace:
    """One DAQP workspace: ``min 0.5 x'Hx + g'x``, ``lbx <= x <= ubx``,
    ``lb0 - c <= A x <= ub0 - c``, set up once; :meth:`solve` updates ``g`` and ``c``.

    Parameters
    ----------
    daqp : module
        The daqp package.
    settings : dict
        DAQP settings.
    H, A : numpy.ndarray
        Hessian and constraint rows.
    lbx, ubx, lb0, ub0 : numpy.ndarray
        Variable bounds and the rows' bounds before the offsets.
    sense : numpy.ndarray
        DAQP's initial working-set flags.
    """

    INF = 1e30  # DAQP's infinity (DAQP_INF)
    ACTIVE_LOWER = 3  # sense flags: ACTIVE (1) | LOWER (2)

    def __init__(self, daqp: Any, settings: dict, H: np.ndarray, A: np.ndarray,
                 lbx: np.ndarray, ubx: np.ndarray, lb0: np.ndarray, ub0: np.ndarray,
                 sense: np.ndarray) -> None:
        nv, m = H.shape[0], A.shape[0]
        inf = self.INF
        self.nv = nv
        self.ub0 = np.minimum(ub0, inf)
        self.lb0 = np.maximum(lb0, -inf)
        # Bounds on the variables first (DAQP's simple bounds), then the rows.
        self.bu = np.concatenate([np.minimum(ubx, inf), self.ub0])
        self.bl = np.concatenate([np.maximum(lbx, -inf), self.lb0])
        self.sense0 = sense
        self.model = daqp.Model()
        self.model.settings = settings
        A = np.ascontiguousarray(A) if m else np.zeros((0, nv))
        flag, _ = self.model.setup(np.ascontiguousarray(H), np.zeros(nv), A, self.bu, self.bl,
                                   sense.copy())
        if flag < 0:  # H is positive definite by construction (r > 0, slack penalty > 0)
            raise CableOCPError(f"DAQP could not set up the MPC problem (exit flag {flag})")

    def solve(self, g: np.ndarray, c: np.ndarray) -> tuple[np.ndarray, bool]:
        """As :meth:`DaqpQP.solve` on this workspace (a retry from the cold working set)."""
        nv = self.nv
        np.subtract(self.ub0, c, out=self.bu[nv:])
        np.subtract(self.lb0, c, out=self.bl[nv:])
        self.model.update(f=g, bupper=self.bu, blower=self.bl)
        x, _, flag, _ = self.model.solve()
        if flag < 0:
            # A stale working set (e.g. after a jump in the state) could stall the dual
            # active-set iteration: retry once from the cold working set.
            self.model.update(sense=self.sense0.copy())
            x, _, flag, _ = self.model.solve()
        return x, flag > 0
