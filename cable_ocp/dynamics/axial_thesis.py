"""Huang's own scheme for the axial model: the baseline (Huang (1992), 3.2.4-3.2.6).

Huang's frame: z measured down the cable from the sheave, u(z, t) the downward
displacement, U = u - v t, y = z / (L0 + v t) (3.4); the transformed equation (3.5) with
coefficients A..G, the sheave condition U(0, T) = R(T) (3.6) with R the downward heave, and
the unit's condition (3.7) with A'..G'. Discretisation as printed in 3.2.6: central
differences in y, second-order backward differences in T (three past levels: U^j, U^(j-1),
U^(j-2)), the one-sided second-order stencils of (3.10) at the unit; the tridiagonal system
(3.8) with the four-term last row (3.10) is solved by eliminating the last row's two extra
entries with the rows above and then the Thomas algorithm (written in CasADi, so the whole
step is one SX function stepped by ``fold``/``mapaccum``).

Readings (the text leaves them open):

* "linearization": the moduli |dU/dT - (v y / L) dU/dy + v| in D, F, G, D', F', G' are
  evaluated with dU/dT extrapolated from the three known levels,
  (5 U^j - 8 U^(j-1) + 3 U^(j-2)) / (2 dT) (second order), and dU/dy from U^j;
* the start is at rest: U^(-1), U^(-2) from U^0 by a Taylor expansion with the
  acceleration of the equations at rest (equal to U^0 for the static start);
* the printed equations have L = L0 + v T: this baseline accepts the linear pay-out law
  only, without a ramp on the pay-out (a heave ramp is fine);
* as printed, the drag has no stretch factor and the added mass in (3.1) is the cable's
  tangential added mass per length (0 by default: see docs/dynamics.md);
* tensions: EA dU/dz at the element mid-points; at the sheave the one-sided second-order
  derivative.

Needs at least 3 elements (the stencil of (3.10)).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.dynamics.result import (
    SimulationResult,
    slack_element,
    slack_report,
    until_slack,
)
from cable_ocp.dynamics.stepping import chunk_functions
from cable_ocp.dynamics.vertical_line import vertical_line
from cable_ocp.errors import CableOCPError
from cable_ocp.scene.dynamics import DynamicScene
from cable_ocp.scene.motion import motion_function

__all__ = ["SLACK_MESSAGE", "ThesisAxialModel"]

#: the thesis scheme's slack message (:func:`cable_ocp.dynamics.result.slack_report`)
SLACK_MESSAGE = ("slack: tension <= 0 first at t = {t:.6g} s in element {segment}; the model "
                 "cannot follow slack (Huang (1992) 4.5.1)")


class ThesisAxialModel:
    """Huang's implicit finite-difference scheme (3.8)-(3.10) for one scene.

    Parameters
    ----------
    scene : DynamicScene
        A vertical-line scene with the linear pay-out law (checked by the axial model,
        :meth:`cable_ocp.dynamics.axial.AxialModel.simulate`, which runs this scheme for
        ``simulation.scheme = "thesis"``).
    segments : int, optional
        Number of intervals N (nodes 0..N, 0 at the sheave); default
        ``simulation.segments``, at least 3.
    """

    def __init__(self, scene: DynamicScene, segments: int | None = None) -> None:
        tm = scene.top_motion
        if tm.payout_law != "linear":
            raise CableOCPError(f'simulation.scheme = "thesis" implements L = L0 + v t '
                                f'(Huang (1992) (3.4)); top_motion.payout_law = '
                                f'"{tm.payout_law}" needs another scheme (e.g. "midpoint")')
        if tm.payout_speed != 0.0 and tm.ramp_time > 0.0:
            raise CableOCPError('simulation.scheme = "thesis" needs a constant pay-out speed: '
                                "set top_motion.ramp_time = 0 or use another scheme")
        self.scene = scene
        self.n = int(segments or scene.simulation.segments)
        if self.n < 3:
            raise CableOCPError(f'simulation.segments = {self.n}: scheme "thesis" needs at '
                                "least 3 (the four-point stencil of Huang's (3.10))")
        line = vertical_line(scene)
        self.ea = line.axial_stiffness
        self.mu = line.mass_per_length
        self.w1 = line.weight_per_length
        # kappa = 1/2 rho C_t pi d, the drag of (3.1) linearised about the lagged modulus
        self.kappa = line.drag_factor
        self.mass = line.unit_mass
        self.w2 = line.unit_weight
        self.unit_drag = line.unit_drag
        self.v = tm.payout_speed
        self.length0 = line.length
        self.z_top0 = line.top_height
        self.motion = motion_function(scene)

    def static_u(self) -> np.ndarray:
        """Static U at the nodes y_i = i / N (from the sheave), m (exact for the scheme:
        U is quadratic in z)."""
        z = np.arange(self.n + 1) * self.length0 / self.n
        ell = self.length0
        return (self.w2 * z + self.w1 * (ell * z - 0.5 * z**2)) / self.ea

    def _heave_down(self, t: Any) -> Any:
        """R(T): the downward displacement of the sheave, m."""
        return -(self.motion(t)[3][2] - self.z_top0)

    def _coefficients(self, y: float, ell: Any, wabs: Any) -> tuple[Any, ...]:
        """A, B, C, D, F, G of (3.5) at y for length ell and modulus wabs (m/s)."""
        mu, ea, kap, v = self.mu, self.ea, self.kappa, self.v
        return (mu * v**2 * y**2 / ell**2 - ea / ell**2,
                mu,
                -2 * mu * v * y / ell,
                2 * mu * v**2 * y / ell**2 - kap * v * y / ell * wabs,
                kap * wabs,
                v * kap * wabs - self.w1)

    def _unit_coefficients(self, ell: Any, wabs: Any) -> tuple[Any, ...]:
        """A', B', C', D', F', G' of (3.7) for length ell and modulus wabs (m/s)."""
        big_m, cs, ea, v = self.mass, self.unit_drag, self.ea, self.v
        return (big_m * v**2 / ell**2,
                big_m,
                -2 * big_m * v / ell,
                2 * big_m * v**2 / ell**2 + ea / ell - v * cs / ell * wabs,
                cs * wabs,
                v * cs * wabs - self.w2)

    def initial_history(self, u0: np.ndarray, dt: float) -> tuple[np.ndarray, np.ndarray]:
        """(U^(-1), U^(-2)) for a start at rest (dU/dT = 0) from U^0.

        The second-order Taylor expansion U^(-k) = U^0 + (k dT)^2 / 2 U_TT with U_TT from
        (3.5) and (3.7) at rest (the same stencils as (3.8)-(3.10)); a static start gives
        U_TT = 0, i.e. U^(-2) = U^(-1) = U^0. Without it a start away from equilibrium (e.g.
        ``start = "unstrained"``) would carry a first-order error in dT.

        Parameters
        ----------
        u0 : ndarray
            Displacements U^0 at the nodes, m.
        dt : float
            The step dT, s.
        """
        n = self.n
        dy = 1.0 / n
        ell = self.length0
        v = self.v
        acc = np.zeros(n + 1)
        for i in range(1, n):
            uyy = (u0[i + 1] - 2 * u0[i] + u0[i - 1]) / dy**2
            uy = (u0[i + 1] - u0[i - 1]) / (2 * dy)
            wabs = abs(v - v * i * dy / ell * uy)
            a, b, _, d, _, g = self._coefficients(i * dy, ell, wabs)
            acc[i] = -(a * uyy + d * uy + g) / b
        uyy = (2 * u0[n] - 5 * u0[n - 1] + 4 * u0[n - 2] - u0[n - 3]) / dy**2
        uy = (3 * u0[n] - 4 * u0[n - 1] + u0[n - 2]) / (2 * dy)
        wabs = abs(v - v / ell * uy)
        a, b, _, d, _, g = self._unit_coefficients(ell, wabs)
        acc[n] = -(a * uyy + d * uy + g) / b
        return u0 + 0.5 * dt**2 * acc, u0 + 2.0 * dt**2 * acc

    def step_function(self, dt: float) -> ca.Function:
        """``(acc, t_j) -> acc``: one step from level j to j + 1. ``acc`` stacks U^j,
        U^(j-1), U^(j-2) (N + 1 each), the smallest element tension so far, the time of
        the first tension <= 0 (inf if none) and that element's index."""
        n = self.n
        dy = 1.0 / n
        ea = self.ea
        v = self.v
        acc = ca.SX.sym("acc", 3 * (n + 1) + 3)
        tj = ca.SX.sym("t")
        u0 = acc[0:n + 1]
        u1 = acc[n + 1:2 * (n + 1)]
        u2 = acc[2 * (n + 1):3 * (n + 1)]
        tmin, t_slack, e_slack = acc[3 * (n + 1)], acc[3 * (n + 1) + 1], acc[3 * (n + 1) + 2]
        t_new = tj + dt
        ell = self.length0 + v * t_new
        y = [i * dy for i in range(n + 1)]
        # lagged moduli (see the module docstring)
        ut = (5 * u0 - 8 * u1 + 3 * u2) / (2 * dt)
        uy = [None] * (n + 1)
        for i in range(1, n):
            uy[i] = (u0[i + 1] - u0[i - 1]) / (2 * dy)
        uy[n] = (3 * u0[n] - 4 * u0[n - 1] + u0[n - 2]) / (2 * dy)

        def speed(i: int) -> Any:
            return ca.fabs(ut[i] - v * y[i] / ell * uy[i] + v)

        rows: list[dict[int, Any]] = []
        rhs: list[Any] = []
        for i in range(1, n):
            a, b, c, d, f, g = self._coefficients(y[i], ell, speed(i))
            p = a / dy**2 + 3 * c / (4 * dy * dt) + d / (2 * dy)
            q = -2 * a / dy**2 + 2 * b / dt**2 + 3 * f / (2 * dt)
            r = a / dy**2 - 3 * c / (4 * dy * dt) - d / (2 * dy)
            e = (-g - b / dt**2 * (-5 * u0[i] + 4 * u1[i] - u2[i])
                 - c / (4 * dy * dt) * (u1[i + 1] - 4 * u0[i + 1] - u1[i - 1] + 4 * u0[i - 1])
                 - f / (2 * dt) * (u1[i] - 4 * u0[i]))
            rows.append({i + 1: p, i: q, i - 1: r})
            rhs.append(e)
        # the unit, (3.7) discretised as (3.10)
        a_, b_, c_, d_, f_, g_ = self._unit_coefficients(ell, speed(n))
        p_n = (2 * a_ / dy**2 + 2 * b_ / dt**2 + 9 * c_ / (4 * dy * dt) + 3 * d_ / (2 * dy)
               + 3 * f_ / (2 * dt))
        q_n = -5 * a_ / dy**2 - 3 * c_ / (dy * dt) - 2 * d_ / dy
        r_n = 4 * a_ / dy**2 + 3 * c_ / (4 * dy * dt) + d_ / (2 * dy)
        s_n = -a_ / dy**2
        e_n = (-g_ - b_ / dt**2 * (-5 * u0[n] + 4 * u1[n] - u2[n])
               - c_ / (4 * dy * dt) * (3 * u1[n] + u1[n - 2] - 4 * u1[n - 1] - 12 * u0[n]
                                       - 4 * u0[n - 2] + 16 * u0[n - 1])
               - f_ / (2 * dt) * (u1[n] - 4 * u0[n]))
        rows.append({n: p_n, n - 1: q_n, n - 2: r_n, n - 3: s_n})
        rhs.append(e_n)
        # the sheave (3.6): U_0 known -> right-hand sides
        r_top = self._heave_down(t_new)
        for k, row in enumerate(rows):
            if 0 in row:
                rhs[k] = rhs[k] - row.pop(0) * r_top
        # eliminate the last row's entries left of its tridiagonal band (N-3, then N-2)
        last = rows[-1]
        for col in (n - 3, n - 2):
            if col >= 1 and col in last:
                pr = rows[col]  # the equation of node col + 1: columns col .. col + 2
                factor = last[col] / pr[col]
                for cc, val in pr.items():
                    last[cc] = last.get(cc, 0.0) - factor * val
                rhs[-1] = rhs[-1] - factor * rhs[col]
                last.pop(col)
        # Thomas algorithm on nodes 1..N (rows[k] is node k + 1)
        cp: list[Any] = []
        dp: list[Any] = []
        for k in range(n):
            node = k + 1
            row = rows[k]
            low = row.get(node - 1, 0.0) if node > 1 else 0.0
            diag = row[node]
            up = row.get(node + 1, 0.0)
            den = diag - (low * cp[k - 1] if k > 0 else 0.0)
            cp.append(up / den)
            dp.append((rhs[k] - (low * dp[k - 1] if k > 0 else 0.0)) / den)
        sol: list[Any] = [None] * n
        sol[n - 1] = dp[n - 1]
        for k in range(n - 2, -1, -1):
            sol[k] = dp[k] - cp[k] * sol[k + 1]
        u_new = ca.vertcat(r_top, *sol)
        tens = ea * (u_new[1:] - u_new[:-1]) / (dy * ell)
        tmin_step = ca.mmin(tens)
        slack_tol = 1e-9 * (self.w2 + abs(self.w1) * self.length0)  # as the main model
        first = ca.logic_and(tmin_step <= -slack_tol, t_slack > 1e300)
        # element index counted from the unit (element 0 at the unit)
        idx = ca.DM(np.arange(n - 1, -1, -1, dtype=float))
        is_min = tens <= tmin_step
        e_now = ca.dot(idx, is_min) / ca.sum1(is_min)
        out = ca.vertcat(u_new, u0, u1, ca.fmin(tmin, tmin_step),
                         ca.if_else(first, t_new, t_slack), ca.if_else(first, e_now, e_slack))
        return ca.Function("thesis_step", [acc, tj], [out])

    def outputs(self, t: Any, u: Any) -> tuple[Any, Any, Any, Any]:
        """(heights from the unit to the sheave (m), element tensions from the unit (N),
        top tension (N), L (m)) for U at the nodes (from the sheave).

        Parameters
        ----------
        t : casadi expression
            Time, s.
        u : casadi expression
            Displacements U at the nodes (from the sheave), m.
        """
        n = self.n
        dy = 1.0 / n
        ell = self.length0 + self.v * t
        depth = ca.vertcat(*[i * dy * ell + u[i] for i in range(n + 1)])
        z = self.z_top0 - depth
        tens = self.ea * (u[1:] - u[:-1]) / (dy * ell)
        top = self.ea * (-3 * u[0] + 4 * u[1] - u[2]) / (2 * dy * ell)
        rev = list(range(n, -1, -1))
        return z[rev], tens[list(range(n - 1, -1, -1))], top, ell

    def simulate(self, progress: Callable[[int, int], None] | None = None) -> SimulationResult:
        """Integrate over ``simulation.duration`` with Huang's scheme."""
        sc = self.scene
        sim = sc.simulation
        dt = sim.time_step
        every = sim.output_every
        n_out = sim.steps // every
        n1 = self.n + 1
        t_build = time.perf_counter()
        chunk_fn, per_chunk = chunk_functions(self.step_function(dt), every, n_out)
        tt = ca.SX.sym("t")
        uu = ca.SX.sym("u", n1)
        post = ca.Function("post", [tt, uu], list(self.outputs(tt, uu)))
        build = time.perf_counter() - t_build
        u_init = self.static_u()
        if sim.start == "unstrained":
            u_init = np.zeros(n1)
        ten0 = np.asarray(post(0.0, u_init)[1]).ravel()
        u_m1, u_m2 = self.initial_history(u_init, dt)
        acc = np.concatenate([u_init, u_m1, u_m2, [ten0.min(), np.inf, -1.0]])
        states = [u_init]
        times = [0.0]
        done = 0
        t0 = time.perf_counter()
        status, message = "solved", ""
        while done < n_out:
            m = min(per_chunk, n_out - done)
            tgrid = (done * every + np.arange(m * every)) * dt
            res = np.asarray(chunk_fn(m)(acc, tgrid.reshape(1, -1)))
            finite = np.all(np.isfinite(res[:n1, :]), axis=0)
            k_good = int(np.argmin(finite)) if not finite.all() else m
            for j in range(k_good):
                states.append(res[:n1, j].copy())
                times.append((done + j + 1) * every * dt)
            if k_good < m:
                status = "failed"
                t_bad = (done + k_good + 1) * every * dt
                message = (f"non-finite displacement before t = {t_bad:.6g} s; the history "
                           "stops at the last good sample")
                break
            acc = res[:, -1].copy()
            done += m
            if progress is not None:
                progress(done * every, n_out * every)
            if sim.on_slack == "stop" and np.isfinite(acc[-2]):
                break
        wall = time.perf_counter() - t0
        ts = np.asarray(times)
        us = np.stack(states, axis=1)
        z_nodes, tens, top, length = (np.asarray(v) for v in
                                      post.map(us.shape[1])(ts.reshape(1, -1), us))
        tmin, t_slack, e_slack = (float(v) for v in acc[-3:])
        keep = until_slack(ts, t_slack, every * dt, sim.on_slack)
        if keep is not None:
            ts, z_nodes, tens, top, length = (ts[keep], z_nodes[:, keep], tens[:, keep],
                                              top[:, keep], length[:, keep])
        n_t = ts.size
        nodes = np.empty((n_t, n1, 3))
        nodes[:, :, 0] = sc.top_position[0]
        nodes[:, :, 1] = sc.top_position[1]
        nodes[:, :, 2] = z_nodes.T
        tens = tens.T
        length = length.reshape(n_t)
        e, where = slack_element(t_slack, e_slack, ts, length, self.n)
        slack, status, message = slack_report(
            t_slack, e, where, status=status, message=message, on_slack=sim.on_slack,
            template=SLACK_MESSAGE)
        if status == "solved":
            message = f"{sim.steps} steps of {dt:g} s (thesis scheme), {self.n} intervals"
        return SimulationResult.from_nodes(
            nodes, t=ts, length=length, top_tension=top.reshape(n_t), segment_tensions=tens,
            min_tension=float(min(tmin, tens.min())), slack=slack, status=status,
            message=message, warnings=[], wall_time_s=wall, model="axial", scheme="thesis",
            diagnostics={"build_time_s": build, "steps": sim.steps, "elements": self.n,
                         "start": sim.start,
                         "wall_time_per_simulated_second": wall / ts[-1] if n_t > 1 else None})
