"""The stepping kernel of the lumped-mass model: one time step as a CasADi Function.

:class:`LumpedStepper` builds, on first use and cached per setting, the steps of
:meth:`cable_ocp.dynamics.lumped.LumpedMassModel.step_function`:

* the per-segment kernel (:func:`segment_kernel`: forces, added mass and the Newton
  blocks of one segment, compiled to C once per machine and mapped over the segments);
* the step's residual and Newton matrix assembled from it (:meth:`LumpedStepper.residual_function`);
* Newton's method written in the CasADi graph, with a backtracking line search and the
  contraction-estimate stop (:meth:`LumpedStepper.core_step`);
* step halving where Newton fails (:meth:`LumpedStepper.halving_step`);
* the reference step solved by CasADi's ``rootfinder`` (``solver = "rootfinder"``).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import casadi as ca
import numpy as np

from cable_ocp.dynamics.lumped_equations import (
    added_mass_share,
    interval_tension,
    point_drag,
    point_drag_items,
    segment_tension,
)
from cable_ocp.errors import CableOCPError
from cable_ocp.numerics.block_tridiagonal import block_tridiagonal_solve
from cable_ocp.numerics.compile import compile_function
from cable_ocp.physics.drag import line_drag_kernel, point_drag_jacobian

if TYPE_CHECKING:
    from cable_ocp.dynamics.lumped import LumpedMassModel

__all__ = ["SCHEMES", "LumpedStepper", "segment_kernel", "switch"]

#: time-integration schemes of :meth:`cable_ocp.dynamics.lumped.LumpedMassModel.step_function`
SCHEMES = ("midpoint", "trapezoidal", "bdf2")

def next_state(scheme: str, x1: Any, z: Any, dt: Any, nf3: int) -> tuple[Any, Any]:
    """The stepped state from the new positions ``x1`` and the old stepped state ``z``
    (positions, velocities, then the scheme's history: the acceleration for the midpoint
    and trapezoidal rules, the previous positions and velocities and the start flag for
    BDF2); returns (new stepped state, new velocities).

    Parameters
    ----------
    scheme : str
        The scheme.
    x1 : casadi expression
        New free-node positions, m.
    z : casadi expression
        The old stepped state.
    dt : float or casadi expression
        The step, s.
    nf3 : int
        Number of free coordinates.
    """
    x0, v0 = z[0:nf3], z[nf3:2 * nf3]
    if scheme == "midpoint":
        v1 = 2.0 * (x1 - x0) / dt - v0
        return ca.vertcat(x1, v1, (v1 - v0) / dt), v1
    if scheme == "trapezoidal":
        v1 = 2.0 * (x1 - x0) / dt - v0
        return ca.vertcat(x1, v1, 2.0 * (v1 - v0) / dt - z[2 * nf3:3 * nf3]), v1
    st, xp = z[4 * nf3], z[2 * nf3:3 * nf3]
    v1 = ((1.0 + 0.5 * st) * x1 + (-1.0 - st) * x0 + 0.5 * st * xp) / dt
    return ca.vertcat(x1, v1, x0, v0, 1.0), v1



class LumpedStepper:
    """The time steps of one :class:`~cable_ocp.dynamics.lumped.LumpedMassModel`, built on
    first use and cached per setting (step size, scheme, tolerances, compilation, force
    scale)."""

    def __init__(self, model: LumpedMassModel) -> None:
        self.model = model
        self._steps: dict[tuple, ca.Function] = {}
        self._residuals: dict[tuple, ca.Function] = {}
        #: the scaled residual's inf-norm alone, per key of ``_residuals``
        self._residual_norms: dict[tuple, ca.Function] = {}

    def step_function(self, dt: float, scheme: str = "midpoint", *, tol: float = 1e-10,
                      max_iter: int = 20, solver: str = "newton",
                      linear_solver: str = "qr", compile_kernel: bool = True,
                      force_scale: float | None = None) -> ca.Function:
        """:meth:`LumpedMassModel.step_function` (see there).

        Parameters
        ----------
        dt, scheme, tol, max_iter, solver, linear_solver, compile_kernel, force_scale
            As :meth:`~cable_ocp.dynamics.lumped.LumpedMassModel.step_function`
            (s, -, -, -, -, -, -, N).
        """
        if scheme not in SCHEMES:
            raise CableOCPError(f"scheme = {scheme!r}: valid are {SCHEMES}")
        if solver not in ("newton", "rootfinder"):
            raise CableOCPError(f"solver = {solver!r}: valid are 'newton', 'rootfinder'")
        if not dt > 0:
            raise CableOCPError(f"time_step = {dt}: must be > 0")
        key = (float(dt), scheme, tol, max_iter, solver, linear_solver, compile_kernel,
               force_scale)
        if key in self._steps:
            return self._steps[key]
        if solver == "newton":
            step = self.newton_step(dt, scheme, tol, max_iter, linear_solver, compile_kernel,
                                   force_scale)
            self._steps[key] = step
            return step
        p = self.model.params
        if p.viscoelastic is not None:
            raise CableOCPError('solver = "rootfinder": the viscoelastic law steps with the '
                                'Newton solver (valid: "newton")')
        nf3 = 3 * self.model.n_free
        fscale = self.model.force_scale() if force_scale is None else float(force_scale)
        x1 = ca.SX.sym("x1", nf3)
        x0 = ca.SX.sym("x0", nf3)
        v0 = ca.SX.sym("v0", nf3)
        t0 = ca.SX.sym("t0")
        t1 = t0 + dt
        if scheme == "midpoint":
            a0 = ca.SX.sym("a0", nf3)
            r0 = self.model.all_positions(x0, t0)
            r1 = self.model.all_positions(x1, t1)
            rm = [0.5 * (a + b) for a, b in zip(r0, r1, strict=True)]
            vm = (x1 - x0) / dt

            def velocities(vf: Any) -> list[Any]:
                vel = [vf[3 * k:3 * k + 3] for k in range(self.model.n_free)]
                if p.fixed_a:
                    vel = [(r1[0] - r0[0]) / dt] + vel
                return vel + [(r1[-1] - r0[-1]) / dt]

            f_el = self.model.free(self.model.eq.elastic(r0, r1, velocities(vm), dt))
            drag = self.model.free(self.model.eq.drag(rm, velocities(vm)))
            mass = self.model.mass_expr(rm)
            v1 = 2.0 * vm - v0
            inert = ca.mtimes(mass, v1 - v0) / dt
            extra = ca.vertcat(x0, v0, a0, t0)
            guess = x0 + dt * v0 + 0.5 * dt * dt * a0
            z = ca.vertcat(x0, v0, a0)
        elif scheme == "trapezoidal":
            a0 = ca.SX.sym("a0", nf3)
            r1 = self.model.all_positions(x1, t1)
            v1 = 2.0 * (x1 - x0) / dt - v0
            a1 = 2.0 * (v1 - v0) / dt - a0
            vel1 = self.model.all_velocities(v1, t1)
            f_el = self.model.free(self.model.eq.elastic(r1, None, vel1, None))
            drag = self.model.free(self.model.eq.drag(r1, vel1))
            mass = self.model.mass_expr(r1)
            inert = ca.mtimes(mass, a1)
            extra = ca.vertcat(x0, v0, a0, t0)
            guess = x0 + dt * v0 + 0.5 * dt * dt * a0
            z = ca.vertcat(x0, v0, a0)
        else:
            xp = ca.SX.sym("xp", nf3)
            vp = ca.SX.sym("vp", nf3)
            started = ca.SX.sym("started")
            c0 = 1.0 + 0.5 * started
            c1 = -1.0 - started
            c2 = 0.5 * started
            v1 = (c0 * x1 + c1 * x0 + c2 * xp) / dt
            a1 = (c0 * v1 + c1 * v0 + c2 * vp) / dt
            r1 = self.model.all_positions(x1, t1)
            vel1 = self.model.all_velocities(v1, t1)
            f_el = self.model.free(self.model.eq.elastic(r1, None, vel1, None))
            drag = self.model.free(self.model.eq.drag(r1, vel1))
            mass = self.model.mass_expr(r1)
            inert = ca.mtimes(mass, a1)
            extra = ca.vertcat(x0, v0, xp, vp, started, t0)
            guess = x0 + dt * v0 + started * (x0 - xp - dt * v0)
            z = ca.vertcat(x0, v0, xp, vp, started)
        f_ext = self.model.free(self.model.eq.static_loads())
        res = (inert - f_el - f_ext - drag) / fscale
        g = ca.Function("g", [x1, extra], [res])
        zin = ca.Function("split", [z, t0], [extra, guess])
        zs = ca.MX.sym("z", z.shape[0])
        ts = ca.MX.sym("t0")
        extra_m, guess_m = zin(zs, ts)
        newton = ca.rootfinder("newton_step", "newton", g, {
            "abstol": tol, "abstolStep": 1e-14, "max_iter": max_iter,
            "linear_solver": "csparse", "error_on_fail": False})
        x1m = newton(guess_m, extra_m)
        resid = ca.norm_inf(g(x1m, extra_m))
        iters = ca.MX(math.nan)
        z1, _ = next_state(scheme, x1m, zs, dt, nf3)
        eps = self.model.tensions(x1m, ts + dt)[1]
        emin = ca.mmin(eps)
        step = ca.Function(f"step_{scheme}", [zs, ts],
                           [z1, resid, iters, emin, ca.find(eps <= emin)],
                           ["z", "t0"], ["z1", "residual", "iterations", "min_strain",
                                         "slack_segment"])
        self._steps[key] = step
        return step


    # -- the fast Newton step ------------------------------------------------------------
    def segment_parameters(self) -> np.ndarray:
        """Kernel parameters per segment, shape (12, N) (:data:`KERNEL_PARAMS`)."""
        p = self.model.params
        en, et = self.model.eq.added_mass
        rows = {
            "l": p.segment_length, "ea": p.axial_stiffness, "c": p.axial_damping,
            "d": p.diameter, "cn": p.normal_drag, "ct": p.tangential_drag, "en": en, "et": et,
            "rho": np.full(p.segments, p.water_density),
            "delta": np.full(p.segments, p.smoothing),
            "delta_t": np.full(p.segments, p.slack_smoothing),
            "blend": np.full(p.segments, p.vertical_blend)}
        return np.vstack([rows[k] for k in KERNEL_PARAMS])

    def point_terms(self, r: Any, v: Any, gamma: Any, sym: Any = ca.MX) -> tuple[Any, Any]:
        """Drag (N, 3 x (N+1)) and its Newton blocks (9 x (N+1)) of the unit and the bodies
        at node positions r and velocities v (MX, 3 x (N+1)).

        Parameters
        ----------
        r, v : casadi expression (3, N+1)
            Node positions (m) and velocities (m/s).
        gamma : casadi expression
            The scheme's velocity coefficient of the Newton matrix, 1/s.
        sym : type
            casadi.MX or casadi.SX.
        """
        p = self.model.params
        n = p.segments
        items = point_drag_items(p)
        fcols = [sym.zeros(3, 1) for _ in range(n + 1)]
        ccols = [sym.zeros(9, 1) for _ in range(n + 1)]
        if not items:
            return ca.horzcat(*fcols), ca.horzcat(*ccols)
        rs, vs, gs = ca.SX.sym("r", 3), ca.SX.sym("v", 3), ca.SX.sym("g")
        for node, cs, law in items:
            u = self.model.eq.current(rs[2]) - vs
            f = point_drag(u, cs, law, p.water_density, p.smoothing)
            # its Newton block: -dF/dv = dF/du (the current's dependence on the height left
            # out), symmetrised
            dmat = point_drag_jacobian(u, cs, rho=p.water_density, delta=p.smoothing,
                                       per_axis=law == "per_axis")
            if law == "vector":
                dmat = 0.5 * (dmat + dmat.T)
            fn = ca.Function("point_drag", [rs, vs, gs], [f, ca.vec(gs * dmat)])
            fk, ck = fn(r[:, node], v[:, node], gamma)
            fcols[node] = fcols[node] + fk
            ccols[node] = ccols[node] + ck
        return ca.horzcat(*fcols), ca.horzcat(*ccols)

    def residual_function(self, scheme: str, compile_kernel: bool, fscale: float
                           ) -> ca.Function:
        """``gj(x1, z, t0, dt)``: the step's scaled residual and, for the MX path, the
        Newton matrix and force residual (``(res, J, f)``), or, for the SX path, the
        Newton update by block elimination (``(res, dx)``). Cached: one function for
        every step size (the step halving reuses it).

        Parameters
        ----------
        scheme : str
            The scheme.
        compile_kernel : bool
            MX around the compiled kernel, else one SX function.
        fscale : float
            Force scale, N.
        """
        key = (scheme, compile_kernel, fscale)
        if key in self._residuals:
            return self._residuals[key]
        p = self.model.params
        n = p.segments
        nf = self.model.n_free
        nf3 = 3 * nf
        first = 1 if p.fixed_a else 0
        solid = p.viscoelastic is not None
        kern = segment_kernel(p.drag_law, compile_kernel, p.tension_strain, solid
                              ).map(n, "serial")
        if not compile_kernel:
            kern = segment_kernel_expr(p.drag_law, p.tension_strain, solid).map(n, "unroll")
        par = ca.DM(self.segment_parameters())
        ends = self.model.ends
        node_m = ca.DM(np.vstack([np.diag(m).T.reshape(-1) for m in self.model.eq.node_mass]).T)
        static = ca.DM(self.model.eq.loads)
        cur = None
        if p.current is not None:
            zs = ca.SX.sym("z")
            cur = ca.Function("current", [zs], [ca.vec(p.current(zs))]).map(n, "serial")

        def nodes(xf: Any, ra: Any, rb: Any) -> Any:
            cols = [ra] if p.fixed_a else []
            return ca.horzcat(*cols, ca.reshape(xf, 3, nf), rb)

        def mat_vec(mb: Any, w: Any) -> Any:
            """Row-major 3x3 blocks (9 x k) times vectors (3 x k), column by column."""
            return ca.vertcat(*[mb[3 * i, :] * w[0, :] + mb[3 * i + 1, :] * w[1, :]
                                + mb[3 * i + 2, :] * w[2, :] for i in range(3)])

        # sparsity and nonzero map of the block-tridiagonal Newton matrix (free nodes)
        rows, cols, src = [], [], []
        for a in range(nf):
            for r in range(3):
                for c in range(3):
                    rows.append(3 * a + r)
                    cols.append(3 * a + c)
                    src.append(9 * a + 3 * r + c)
        off = 9 * nf
        for a in range(nf - 1):
            for r in range(3):
                for c in range(3):
                    rows += [3 * a + r, 3 * (a + 1) + r]
                    cols += [3 * (a + 1) + c, 3 * a + c]
                    src += [off + 9 * a + 3 * r + c, off + 9 * a + 3 * r + c]
        sp = ca.Sparsity.triplet(nf3, nf3, rows, cols)
        # order the values as the sparsity stores them (column-major)
        order = np.lexsort((np.asarray(rows), np.asarray(cols)))
        src_sorted = [src[k] for k in order]

        # the residual and Newton matrix: MX around the compiled kernel, or one SX
        # function with the kernel inlined (compiled with the whole step: no overhead)
        sym = ca.MX if compile_kernel else ca.SX
        x1 = sym.sym("x1", nf3)
        zsym = sym.sym("z", self.model.state_size(scheme))
        t0 = sym.sym("t0")
        dt = sym.sym("dt")
        x0 = zsym[0:nf3]
        v0 = zsym[nf3:2 * nf3]
        ra0, va0, rb0, vb0 = ends(t0)
        ra1, va1, rb1, vb1 = ends(t0 + dt)
        r1 = nodes(x1, ra1, rb1)
        if scheme == "midpoint":
            r0 = nodes(x0, ra0, rb0)
            vel = (r1 - r0) / dt
            v1 = 2.0 * (x1 - x0) / dt - v0
            coef = (2.0 / dt**2, 0.5, 1.0 / dt)
            mid = 1.0
            rm = 0.5 * (r0 + r1)
        else:
            r0 = r1
            rm = r1
            mid = 0.0
            if scheme == "trapezoidal":
                v1 = 2.0 * (x1 - x0) / dt - v0
                a1 = 2.0 * (v1 - v0) / dt - zsym[2 * nf3:3 * nf3]
                coef = (4.0 / dt**2, 1.0, 2.0 / dt)
            else:
                st = zsym[4 * nf3]
                c0, c1, c2 = 1.0 + 0.5 * st, -1.0 - st, 0.5 * st
                xp = zsym[2 * nf3:3 * nf3]
                vp = zsym[3 * nf3:4 * nf3]
                v1 = (c0 * x1 + c1 * x0 + c2 * xp) / dt
                a1 = (c0 * v1 + c1 * v0 + c2 * vp) / dt
                coef = (c0 * c0 / dt**2, 1.0, c0 / dt)
            vel = nodes(v1, va1, vb1)
        alpha, beta, gamma = coef
        scv = ca.vertcat(dt, mid, beta, gamma)
        if solid:  # the midpoint step's law k (e - F_0 / k) (physics.viscoelastic)
            sls = p.viscoelastic
            k_step = sls.step_stiffness(dt)
            ev0 = ca.reshape(zsym[3 * nf3:3 * nf3 + n], 1, n)
            ea_row = KERNEL_PARAMS.index("ea")
            par = ca.vertcat(par[:ea_row, :], k_step * sym.ones(1, n), par[ea_row + 1:, :],
                             sls.step_offset(ev0, dt) / k_step)
        if cur is not None:
            ucur = cur(0.5 * (rm[2, 0:n] + rm[2, 1:n + 1]))
        else:
            ucur = sym.zeros(3, n)
        fa, fb, madd, kb, cb = kern(r0[:, 0:n], r0[:, 1:n + 1], r1[:, 0:n], r1[:, 1:n + 1],
                                    vel[:, 0:n], vel[:, 1:n + 1], ucur, par, scv)
        z3 = sym.zeros(3, 1)
        z9 = sym.zeros(9, 1)
        fpt, cpt = self.point_terms(rm, vel, gamma, sym)
        force = ca.horzcat(fa, z3) + ca.horzcat(z3, fb) + static + fpt
        bend = self.model.eq.bending
        if bend.active:  # linear in the positions (cable_ocp.dynamics.bending_terms)
            force = force + bend.node_forces(rm[:, 1:] - rm[:, :-1])
        mass = node_m + ca.horzcat(madd, z9) + ca.horzcat(z9, madd)
        free = slice(first, n)
        if scheme == "midpoint":
            inert = mat_vec(mass[:, free], ca.reshape(v1 - v0, 3, nf)) / dt
        else:
            inert = mat_vec(mass[:, free], ca.reshape(a1, 3, nf))
        fres = ca.vec(inert - force[:, free])
        res = fres / fscale
        kc = ca.horzcat(kb, z9) + ca.horzcat(z9, kb) + ca.horzcat(cb, z9) + ca.horzcat(
            z9, cb) + cpt
        diag_b = alpha * mass[:, free] + kc[:, free]
        off_b = -kb[:, first:n - 1] + cb[:, first:n - 1]
        if bend.active:  # its constant Jacobian (d rm / d x1 = beta); off_b is symmetric
            kd, ko, k_rest = bend.free_blocks(first, nf)
            diag_b = diag_b + beta * ca.DM(kd)
            off_b = off_b + beta * ca.DM(ko)
        vals = ca.vertcat(ca.vec(diag_b), ca.vec(off_b))
        if compile_kernel:
            jac = ca.MX(sp, 0)
            jac.nz[:] = vals[src_sorted]
            if bend.active and k_rest.nnz() > 0:  # the blocks two nodes apart
                jac = jac + beta * k_rest
            gj = ca.Function("gj", [x1, zsym, t0, dt], [res, jac, fres])
        else:
            # the Newton update by block-tridiagonal elimination (3x3 blocks, no pivoting:
            # the matrix is close to symmetric positive definite), inlined in SX
            def blk(m: Any, k: int) -> Any:  # row-major 3x3 block k of the 9 x k rows
                return ca.reshape(m[:, k], 3, 3).T

            offs = [blk(off_b, k) for k in range(nf - 1)]
            rhs = ca.reshape(fres, 3, nf)
            dx_sx = ca.vertcat(*block_tridiagonal_solve(
                [blk(diag_b, k) for k in range(nf)], offs, offs,
                [rhs[:, k] for k in range(nf)]))
            gj = ca.Function("gj", [x1, zsym, t0, dt], [res, dx_sx])
        # the residual alone (the SX graph keeps only its part: about a third of gj's
        # operations), to check an iterate accepted on the contraction estimate
        self._residual_norms[key] = ca.Function("g", [x1, zsym, t0, dt], [ca.norm_inf(res)])
        self._residuals[key] = gj
        return gj

    def core_step(self, dt: float, scheme: str, tol: float, max_iter: int,
                   linear_solver: str, compile_kernel: bool, force_scale: float | None
                   ) -> ca.Function:
        """One Newton-solved step ``(z, t0) -> (z1, residual, iterations, converged)``.

        Parameters
        ----------
        dt, scheme, tol, max_iter, linear_solver, compile_kernel, force_scale
            As :meth:`~cable_ocp.dynamics.lumped.LumpedMassModel.step_function`
            (s, -, -, -, -, -, N).
        """
        p = self.model.params
        nf3 = 3 * self.model.n_free
        fscale = self.model.force_scale() if force_scale is None else float(force_scale)
        x_scale = p.length + float(np.max(np.abs(np.asarray(p.top_position(0.0)))))
        gj4 = self.residual_function(scheme, compile_kernel, fscale)
        zsym = ca.MX.sym("z", self.model.state_size(scheme))
        t0 = ca.MX.sym("t0")
        x0 = zsym[0:nf3]
        v0 = zsym[nf3:2 * nf3]

        def gj(x: Any, z: Any, t: Any) -> Any:
            return gj4(x, z, t, dt)

        # Newton with backtracking, skipped once converged: an iteration evaluates the
        # residual at x; if it did not decrease (2-norm) from the last accepted point, x
        # moves back along the last step (halving it, down to 1/16); else a Newton step.
        xk = ca.MX.sym("xk", nf3)
        xo = ca.MX.sym("xo", nf3)
        dl = ca.MX.sym("dl", nf3)
        rno = ca.MX.sym("rno")
        rio = ca.MX.sym("rio")  # inf-norm residual where the last Newton step was taken
        lam = ca.MX.sym("lam")
        if compile_kernel:
            rk, jk, fk = gj(xk, zsym, t0)
        else:
            rk, dxk = gj(xk, zsym, t0)
        rn = ca.norm_inf(rk)
        rn2 = ca.norm_2(rk)
        # converged: the residual below tol, or (rounding floor: the residual of a heavy
        # node at a small step, M eps |x| / dt^2, can exceed tol) the last Newton update
        # at rounding level with the residual below the failure threshold
        dln = ca.norm_inf(dl)
        stalled = ca.logic_and(ca.logic_and(dln > 0.0, dln <= 1e-13 * x_scale),
                               rn <= max(1e3 * tol, 1e-6))
        conv = ca.logic_or(rn <= tol, stalled)
        worse = ca.logic_and(ca.logic_and(rn2 > rno, lam > 1.0 / 16.0),
                             ca.logic_not(conv))
        x_back = xo - 0.5 * lam * dl
        skip = ca.logic_or(conv, worse)
        if compile_kernel:
            # the sparse solve only when a Newton step is taken (on the values computed
            # above: the solve's function takes J and f, not x)
            jm = ca.MX.sym("J", jk.sparsity())
            fm = ca.MX.sym("f", nf3)
            solve = ca.Function("newton_solve", [jm, fm], [ca.solve(jm, fm, linear_solver)])
            no_step = ca.Function("no_step", [jm, fm], [ca.MX.zeros(nf3)])
            dx = switch("maybe_solve", skip, no_step, solve, jk, fk)
        else:
            dx = ca.if_else(skip, ca.MX.zeros(nf3), dxk)
        # stop on the contraction estimate (after Hairer & Wanner (1996), Solving ODEs II,
        # sec. IV.8, eq. (8.10), written for the residual): where this Newton step follows
        # one that reduced the residual from rio to rn, the residual after it should be
        # about rn * (rn / rio). Below tol, the new iterate is checked with the residual
        # alone (about a third of the work of a residual-and-matrix evaluation) and
        # accepted if it is below tol; else the iteration goes on from it. The estimate
        # only decides when to check (it can be optimistic: near the rounding floor and
        # where the matrix leaves out the drag's orientation terms); the reported
        # residual is always evaluated at the accepted iterate.
        est = rn * rn / rio
        check = ca.logic_and(ca.logic_and(ca.logic_not(skip), rio < 1e300),
                             ca.logic_and(rn < rio, est <= tol))
        g_only = self._residual_norms[(scheme, compile_kernel, fscale)]
        xs_, zs_, ts_ = ca.MX.sym("x", nf3), ca.MX.sym("z", zsym.shape[0]), ca.MX.sym("t")
        no_chk = ca.Function("no_check", [xs_, zs_, ts_], [ca.inf])
        chk = ca.Function("check", [xs_, zs_, ts_], [g_only(xs_, zs_, ts_, dt)])
        r_chk = switch("maybe_check", check, chk, no_chk, xk - dx, zsym, t0)
        early = ca.logic_and(check, r_chk <= tol)
        x_new = ca.if_else(conv, xk, ca.if_else(worse, x_back, xk - dx))
        xo_new = ca.if_else(ca.logic_or(conv, worse), xo, xk)
        dl_new = ca.if_else(ca.logic_or(conv, worse), dl, dx)
        rno_new = ca.if_else(ca.logic_or(conv, worse), rno, rn2)
        rio_new = ca.if_else(ca.logic_or(conv, worse), rio, rn)
        lam_new = ca.if_else(worse, 0.5 * lam, 1.0)
        state_in = [xk, xo, dl, rno, rio, lam, zsym, t0]
        work = ca.Function("work", state_in,
                           [x_new, xo_new, dl_new, rno_new, rio_new, lam_new,
                            ca.if_else(early, r_chk, rn), ca.logic_or(conv, early)])
        rs = ca.MX.sym("r")
        idle = ca.Function("idle", state_in + [rs], [xk, xo, dl, rno, rio, lam, rs, 1.0])
        work_r = ca.Function("work_r", state_in + [rs], work(*state_in))
        it = ca.Function.if_else("newton_iteration", idle, work_r)
        if scheme in ("midpoint", "trapezoidal"):
            guess = x0 + dt * v0 + 0.5 * dt * dt * zsym[2 * nf3:3 * nf3]
        else:
            st = zsym[4 * nf3]
            guess = x0 + dt * v0 + st * (x0 - zsym[2 * nf3:3 * nf3] - dt * v0)
        xi, xoi, dli = guess, guess, ca.MX.zeros(nf3)
        rnoi, rioi, lami = ca.MX(ca.inf), ca.MX(ca.inf), ca.MX(1.0)
        rni, done, count = ca.MX(ca.inf), ca.MX(0.0), ca.MX(0.0)
        for _ in range(max_iter):
            count = count + (1.0 - done)
            xi, xoi, dli, rnoi, rioi, lami, rni, done = it(done, xi, xoi, dli, rnoi, rioi,
                                                           lami, zsym, t0, rni)
        # the residual at the last iterate where the iteration ran out of iterations
        rs_ = ca.MX.sym("r")
        last = ca.Function("last_residual", [rs_, xk, zsym, t0], [g_only(xk, zsym, t0, dt)])
        known = ca.Function("known_residual", [rs_, xk, zsym, t0], [rs_])
        resid = switch("final_residual", done, known, last, rni, xi, zsym, t0)
        x1m = xi
        z1, _ = next_state(scheme, x1m, zsym, dt, nf3)
        sls = self.model.params.viscoelastic
        if sls is not None:  # e_v by the midpoint rule of de_v/dt = (e - e_v) / tau
            strains = self.model.tensions
            z1 = ca.vertcat(z1, sls.step_internal(strains(x0, t0)[1], strains(x1m, t0 + dt)[1],
                                                  zsym[3 * nf3:], dt))
        return ca.Function(f"core_{scheme}", [zsym, t0], [z1, resid, count, done])

    def halving_step(self, dt: float, scheme: str, tol: float, max_iter: int,
                      linear_solver: str, compile_kernel: bool, force_scale: float | None,
                      halvings: int) -> ca.Function:
        """``(z, t0) -> (z1, residual, iterations, converged)``: the core step; where its
        Newton iteration does not converge, two steps of dt/2 instead (recursively, at
        most ``halvings`` times; only for the one-step schemes).

        Parameters
        ----------
        dt, scheme, tol, max_iter, linear_solver, compile_kernel, force_scale
            As :meth:`core_step`.
        halvings : int
            Most halvings.
        """
        core = self.core_step(dt, scheme, tol, max_iter, linear_solver, compile_kernel,
                               force_scale)
        if halvings <= 0 or scheme == "bdf2":
            return core
        half = self.halving_step(0.5 * dt, scheme, tol, max_iter, linear_solver,
                                  compile_kernel, force_scale, halvings - 1)
        z = ca.MX.sym("z", self.model.state_size(scheme))
        t0 = ca.MX.sym("t0")
        za, ra, ia, da = half(z, t0)
        zb, rb, ib, db = half(za, t0 + 0.5 * dt)
        two = ca.Function("two_halves", [z, t0],
                          [ca.vertcat(zb, ca.fmax(ra, rb), ia + ib, da * db)])
        z1, r1, i1, d1 = core(z, t0)
        y = ca.MX.sym("y", z.shape[0] + 3)
        keep = ca.Function("keep", [y, z, t0], [y])
        halves = ca.Function("halves", [y, z, t0], [two(z, t0)])
        packed = switch("halving_select", d1, keep, halves, ca.vertcat(z1, r1, i1, d1), z, t0)
        n = z.shape[0]
        return ca.Function(f"halving_{scheme}", [z, t0],
                           [packed[0:n], packed[n], packed[n + 1], packed[n + 2]])

    def newton_step(self, dt: float, scheme: str, tol: float, max_iter: int,
                   linear_solver: str, compile_kernel: bool, force_scale: float | None,
                   halvings: int = 3) -> ca.Function:
        """The ``"newton"`` solver of :meth:`step_function` (see there).

        Parameters
        ----------
        dt, scheme, tol, max_iter, linear_solver, compile_kernel, force_scale
            As :meth:`core_step`.
        halvings : int
            Most halvings.
        """
        step = self.halving_step(dt, scheme, tol, max_iter, linear_solver, compile_kernel,
                                  force_scale, halvings)
        nf3 = 3 * self.model.n_free
        z = ca.MX.sym("z", self.model.state_size(scheme))
        t0 = ca.MX.sym("t0")
        z1, resid, count, _ = step(z, t0)
        eps = self.model.tensions(z1[0:nf3], t0 + dt)[1]
        emin = ca.mmin(eps)
        return ca.Function(f"step_{scheme}", [z, t0],
                           [z1, resid, count, emin, ca.find(eps <= emin)],
                           ["z", "t0"], ["z1", "residual", "iterations", "min_strain",
                                         "slack_segment"])


# --------------------------------------------------------------------------------------
# Per-segment kernel of the time step (compiled once, mapped over the segments)
# --------------------------------------------------------------------------------------

#: segment parameters fed to the kernel, in this order
KERNEL_PARAMS = ("l", "ea", "c", "d", "cn", "ct", "en", "et", "rho", "delta", "delta_t",
                  "blend")


def segment_kernel_expr(drag_law: str, table: Any = None, solid: bool = False
                        ) -> ca.Function:
    """One segment's contribution to a time step, as a CasADi Function (SX).

    Inputs: node positions at the two levels ``ra0, rb0, ra1, rb1`` (m), node velocities
    ``va, vb`` (m/s, for the drag and the material damping), the current ``u`` at the
    segment's mid-height (m/s), the parameters ``par`` (:data:`KERNEL_PARAMS`) and
    ``sc = (dt, mid, beta, gamma)``.

    With ``mid = 1`` the tension is the discrete gradient between the levels (mean of T
    over [eps0, eps1] along (d0 + d1) / (|d0| + |d1|)) and the damping c (|d1| - |d0|) /
    (l dt) times the mean switch; with ``mid = 0`` (and r0 = r1) it is T(eps1) along d1 and
    c d1.(vb - va) / (|d1| l). Elastic plus damping tension cannot push
    (:func:`~cable_ocp.dynamics.lumped_equations.interval_tension`). Drag and added mass are
    taken at the mean positions (r0 + r1) / 2.

    Outputs: the forces on nodes a and b (N), the added-mass share of each node (3x3,
    kg, row-major 9-vector), and the Newton blocks ``kb`` (the tension's stiffness: its
    derivative in eps1 along e e^T plus T / |d| across, times beta = 1/2 for the midpoint,
    1 otherwise; plus gamma (dT/drate / l) e e^T, the damping's) and ``cb`` =
    gamma |d| D / 4 (N/m) of :meth:`LumpedMassModel.step_function`.

    Parameters
    ----------
    drag_law : str
        The normal drag's law.
    table : TensionStrainTable, optional
        The line's tension-strain law (None: EA e with ``ea`` of ``par``).
    solid : bool
        The viscoelastic law's step: ``par`` has a 13th row, the strain shift s of the
        step's law ``ea`` (e - s) (:func:`segment_tension`'s ``shift``).
    """
    ra0, rb0, ra1, rb1, va, vb, u_c = (ca.SX.sym(n, 3) for n in
                                       ("ra0", "rb0", "ra1", "rb1", "va", "vb", "u"))
    par = ca.SX.sym("par", len(KERNEL_PARAMS) + (1 if solid else 0))
    shift = par[len(KERNEL_PARAMS)] if solid else 0.0
    sc = ca.SX.sym("sc", 4)
    ell, ea, c, d, cn, ct, en, et, rho, delta, delta_t, blend = (par[k] for k in range(12))
    dt, mid, beta, gamma = sc[0], sc[1], sc[2], sc[3]
    # the segment's terms of the equations of motion (lumped_equations: one law for every
    # form of the model), then their Newton blocks
    d0 = rb0 - ra0
    d1 = rb1 - ra1
    st_ = segment_tension(d1, ell, ea, c, delta_t, d0=d0, dt=dt, dv=vb - va, mid=mid,
                          table=table, shift=shift)
    l0, l1, tbar = st_["l0"], st_["l1"], st_["tension"]
    f_el = tbar * st_["num"] / st_["den"]
    # the step's tension's partial derivatives in eps1 and in the damping's strain rate
    # (the mean law, its mean switch and the no-push cap: lumped_equations.interval_tension,
    # differentiated by CasADi and evaluated at the segment's eps1 and rate)
    e1s, rs = ca.SX.sym("e1"), ca.SX.sym("rate")
    t_s = interval_tension(st_["e0"], e1s, rs, ea, c, delta_t, table, shift)[0]
    dtbar, dtrate = ca.substitute([ca.jacobian(t_s, e1s), ca.jacobian(t_s, rs)], [e1s, rs],
                                  [st_["strain"], st_["rate"]])
    # drag and added mass at the mean positions
    dm = 0.5 * (d0 + d1)
    lm = ca.norm_2(dm)
    tm = dm / lm
    urel = u_c - 0.5 * (va + vb)
    # the drag's kernel form: its value and Jacobian (physics.drag)
    f_d, dmat = line_drag_kernel(drag_law, urel, tm, lm, rho=rho, diameter=d,
                                 normal_drag=cn, tangential_drag=ct, delta=delta,
                                 blend=blend)
    eye = ca.SX.eye(3)
    madd = added_mass_share(dm, en, et, ca.mtimes(tm, tm.T))
    # Newton blocks
    # d(T u)/d d1 with u = (d0 + d1) / (|d0| + |d1|), e1 = d1 / |d1|:
    # (dT/deps1 / l) u e1^T + T (I - u e1^T) / (|d0| + |d1|), times 2 beta (beta = 1/2 for
    # the midpoint, where T is the mean over [eps0, eps1]; 1 with r0 = r1, where T is
    # symmetric in eps0, eps1, so dtbar = T'/2, and u = e1), plus the damping's
    # (dT/drate) (drate/d d1) = (dT/drate) gamma e1^T / l. Not symmetric for the midpoint:
    # the strain at level 1 follows e1, the force u.
    uet = ca.mtimes((d0 + d1) / (l0 + l1), (d1 / l1).T)
    kb = 2.0 * beta * (dtbar / ell * uet + tbar / (l0 + l1) * (eye - uet)) + (
        gamma * dtrate / ell * uet)
    cb = 0.25 * gamma * lm * dmat
    # the terms share subexpressions that their functions build again (the tangent's
    # t t^T, the strain switch, ...): merged once (the same operations, fewer of them)
    outs = ca.cse([f_el + 0.5 * f_d, -f_el + 0.5 * f_d, ca.vec(madd.T), ca.vec(kb.T),
                   ca.vec(cb.T)])
    return ca.Function(
        f"segment_{drag_law}", [ra0, rb0, ra1, rb1, va, vb, u_c, par, sc], outs,
        ["ra0", "rb0", "ra1", "rb1", "va", "vb", "u", "par", "sc"],
        ["fa", "fb", "madd", "kb", "cb"])


_KERNELS: dict[Any, ca.Function] = {}


def switch(name: str, cond: Any, if_true: ca.Function, if_false: ca.Function,
            *args: Any) -> Any:
    """``if_true(*args)`` where ``cond`` holds, else ``if_false(*args)``: only one is
    evaluated. (CasADi's ``if_else(c, a, b, True)`` on expressions builds each branch as a
    function of the graph's *inputs*, so a branch that reuses a value computed before it
    (a Newton iterate, a step's result) evaluates that value again: here the branches take
    those values as arguments.)

    Parameters
    ----------
    name : str
        Name of the switch function.
    cond : casadi expression
        The condition.
    if_true, if_false : casadi.Function
        The branches, called on ``args``.
    *args
        Their arguments.
    """
    return ca.Function.if_else(name, if_true, if_false)(cond, *args)


def segment_kernel(drag_law: str, compile_kernel: bool = True, table: Any = None,
                   solid: bool = False) -> ca.Function:
    """The segment kernel of ``drag_law``, compiled to C once and cached on disk when a C
    compiler is available (:func:`cable_ocp.numerics.compile.compile_function`), else
    interpreted.

    Parameters
    ----------
    drag_law : str
        The normal drag's law.
    compile_kernel : bool
        Compile to C (else the SX function).
    table : TensionStrainTable, optional
        The line's tension-strain law (None: EA e), built into the kernel.
    solid : bool
        The viscoelastic law's kernel (:func:`segment_kernel_expr`).
    """
    key = (drag_law, compile_kernel, table, solid)
    if key not in _KERNELS:
        fn = segment_kernel_expr(drag_law, table, solid)
        _KERNELS[key] = compile_function(fn, "-O2") if compile_kernel else fn
    return _KERNELS[key]
