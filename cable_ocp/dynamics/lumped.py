"""Three-dimensional lumped-mass cable dynamics (Huang 1992, ch. 5) as CasADi functions.

The cable is replaced by ``N`` massless elastic segments joining ``N + 1`` point masses,
numbered from end_a (node 0, the subsea unit's end, s = 0) to end_b (node N, the ship's
attachment, s = L), z up (Huang's ch. 5 also has z up). Newton's law at node i is
Huang (1992), eq. (5.1)-(5.2):

    (m_i I + A_i(x)) x_i'' = F_i(x, x', t),

* node mass ``m_i = (mu_{i-1/2} l_{i-1/2} + mu_{i+1/2} l_{i+1/2}) / 2`` (kg; unstretched
  lengths l, mass per length mu), plus the mass of a point body or of the unit;
* the direction-dependent added-mass matrix of eq. (5.2): each adjacent segment adds half
  of its added mass ``e = rho C_a (pi d^2 / 4) l`` for accelerations normal to it,
  ``e/2 (I - t t^T)`` (t its unit tangent). Huang assumes no tangential added mass; an
  optional tangential coefficient adds ``e_t/2 t t^T``. Added mass and mass use the
  unstretched length (mass and displaced volume are conserved, Huang's appendix, eq. (12.2));
* the forces of eqs. (5.2)-(5.4): segment tensions along the segments, weight in water per
  unstretched length (half of each adjacent segment at a node), and hydrodynamic drag with
  current. Drag acts on each segment with the relative flow ``U(z_mid) - (v_i + v_{i+1})/2``
  split into normal and tangential parts (the vector law of :mod:`cable_ocp.physics.drag`;
  the componentwise law is also offered), per unit *stretched* length: the segment's load is
  the per-length load times its current length ``|x_{i+1} - x_i| = l (1 + eps)``, and each
  end node takes half of it;
* tension from Hooke's law (5.3) without compression: ``T = EA max(eps, 0)``, smoothed as
  ``T = (EA eps + sqrt((EA eps)^2 + delta_T^2)) / 2`` with a force scale ``delta_T``
  (``slack_smoothing``, N; default 0.01 N), which changes a taut segment's tension by at
  most ``delta_T^2 / (4 T)`` and leaves a slack one with a vanishing pull. Slack
  (``eps <= 0``) is reported by the simulator. An optional material damping adds
  ``c deps/dt`` while the segment is taut (the same smooth switch). A tension-strain table
  replaces EA eps; the viscoelastic law (``[cable] viscoelastic``, midpoint scheme) adds each
  segment's dashpot strain e_v to the stepped state, advanced by the midpoint rule in
  closed form (:mod:`cable_ocp.physics.viscoelastic`; the kernel's strain shift);
* at end_a a subsea unit (Huang eq. (5.6)): mass, added mass per axis, weight in water,
  drag area and coefficient, an external load (thrust); or end_a fixed;
* at end_b the prescribed top motion (5.5), a function of time.

Point bodies (clump weights, buoys, units on the line: the statics' ``[[bodies]]``) sit at
nodes with their own mass, added mass, weight in water, drag and load. Every segment has its
own properties (the statics' ``[[cable.segments]]``).

Time integration (see :meth:`LumpedMassModel.step_function`): the default scheme is the
implicit midpoint rule with a discrete-gradient tension (the energy-momentum method of
Simo & Tarnow (1992) and Gonzalez (1996)), solved by Newton's method in a CasADi
``rootfinder`` and stepped by ``mapaccum``; ``"bdf2"`` is the L-stable alternative.

The module split: the parameters are :mod:`cable_ocp.dynamics.lumped_params`, the time
steps (the compiled segment kernel, Newton, step halving) :mod:`cable_ocp.dynamics.lumped_kernel`,
a run :mod:`cable_ocp.dynamics.lumped_run`; this module holds the model and its equations
(forces, mass, energy, tensions, statics and modes).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import cached_property
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.dynamics.lumped_equations import LumpedEquations
from cable_ocp.dynamics.lumped_kernel import SCHEMES, LumpedStepper
from cable_ocp.dynamics.lumped_params import LumpedParams, TimeFunction
from cable_ocp.errors import CableOCPError

__all__ = ["SCHEMES", "LumpedMassModel"]

class LumpedMassModel:
    """CasADi functions of the lumped-mass model built from :class:`LumpedParams`.

    The state is the position ``x`` and velocity ``v`` of the *free* nodes, each of shape
    ``(3 n_free,)``, node-major (x0, y0, z0, x1, ...): nodes 0..N-1 with a unit at end_a,
    1..N-1 with end_a fixed. End_b (node N) always follows ``top_position``.

    Attributes
    ----------
    params : LumpedParams
    n_free : int
        Number of free nodes.
    free_nodes : ndarray of int
        Indices of the free nodes.
    forces : casadi.Function
        ``forces(x, v, t) -> F`` (N), the right-hand side of (5.2) at the free nodes.
    external_forces : casadi.Function
        ``external_forces(x, v, t) -> F`` (N): the same without the segment tensions
        (weights, drag with current, loads of the unit and bodies).
    mass_matrix : casadi.Function
        ``mass_matrix(x, t) -> M`` (kg), sparse block diagonal (3x3 per node).
    tensions : casadi.Function
        ``tensions(x, t) -> (T, strain)``: elastic tension (N) and strain (-) per segment
        (without the material damping term).
    segment_tension : casadi.Function
        ``segment_tension(x, v, t) -> T`` (N), with the material damping term; with the
        viscoelastic law (``params.viscoelastic``) ``(x, v, t, e_v)``, and so
        :attr:`top_force` and :attr:`energy` (the dashpot strains e_v per segment, -, the
        stepped state's last N numbers).
    top_force : casadi.Function
        ``top_force(x, v, t) -> F`` (N): the force end_b's attachment applies to the cable
        (node N's balance: its mass times the prescribed acceleration minus the tension of
        the top segment, the node's weight and drag); its magnitude is the top tension
        (the tension at s = L, including the top half-segment).
    nodes : casadi.Function
        ``nodes(x, t) -> r`` (3, N+1), all node positions including the prescribed ends.
    node_velocities : casadi.Function
        ``node_velocities(v, t) -> u`` (3, N+1), all node velocities (m/s).
    energy : casadi.Function
        ``energy(x, v, t) -> (kinetic, potential)`` (J): 1/2 v^T M v and the strain energy
        plus the potential of the weights in water.
    static_stiffness : casadi.Function
        ``static_stiffness(x, t) -> K`` (N/m): -dF/dx of the forces without drag.
    """

    def __init__(self, params: LumpedParams):
        self.params = p = params
        n = p.segments
        self.free_nodes = np.arange(1 if p.fixed_a else 0, n)
        self.n_free = int(self.free_nodes.size)
        #: the terms of the equations of motion (:mod:`cable_ocp.dynamics.lumped_equations`)
        self.eq = LumpedEquations(p)
        #: the standard linear solid (None: elastic) and its dashpot strains' symbol
        self.solid = p.viscoelastic
        self._ev = ca.SX.sym("ev", n) if self.solid is not None else None
        self._names = ["x", "v", "t"] + ([] if self._ev is None else ["ev"])

    # -- the CasADi functions, each built on first use -----------------------------------
    @cached_property
    def stepper(self) -> LumpedStepper:
        """The time steps of this model
        (:class:`~cable_ocp.dynamics.lumped_kernel.LumpedStepper`)."""
        return LumpedStepper(self)

    @cached_property
    def _top_vel(self) -> TimeFunction:
        p = self.params
        return p.top_velocity if p.top_velocity is not None else self._derivative(
            p.top_position)

    @cached_property
    def _a_vel(self) -> TimeFunction | None:
        p = self.params
        return self._derivative(p.end_a_position) if p.fixed_a else None

    @cached_property
    def _symbols(self) -> tuple[Any, Any, Any, list[Any], list[Any]]:
        """``(x, v, t, r, vel)``: the free-node symbols, the time and every node's position
        and velocity expression."""
        nf3 = 3 * self.n_free
        x = ca.SX.sym("x", nf3)
        v = ca.SX.sym("v", nf3)
        t = ca.SX.sym("t")
        return x, v, t, self.all_positions(x, t), self.all_velocities(v, t)

    @cached_property
    def forces(self) -> ca.Function:
        """``forces(x, v, t) -> F`` (N), the right-hand side of (5.2) at the free nodes."""
        x, v, t, r, vel = self._symbols
        f = self.free(self.eq.total(self.eq.elastic(r, None, vel, None), self.eq.static_loads(),
                                 self.eq.drag(r, vel)))
        return ca.Function("forces", [x, v, t], [f], ["x", "v", "t"], ["F"])

    @cached_property
    def external_forces(self) -> ca.Function:
        """``external_forces(x, v, t) -> F`` (N): :attr:`forces` without the segment
        tensions."""
        x, v, t, r, vel = self._symbols
        return ca.Function(
            "external_forces", [x, v, t],
            [self.free(self.eq.total(self.eq.static_loads(), self.eq.drag(r, vel)))],
            ["x", "v", "t"], ["F"])

    @cached_property
    def mass_matrix(self) -> ca.Function:
        """``mass_matrix(x, t) -> M`` (kg), sparse block diagonal (3x3 per node)."""
        x, _, t, r, _ = self._symbols
        return ca.Function("mass_matrix", [x, t], [self.mass_expr(r)], ["x", "t"], ["M"])

    @cached_property
    def tensions(self) -> ca.Function:
        """``tensions(x, t) -> (T, strain)``: elastic tension (N) and strain (-) per
        segment."""
        x, _, t, r, _ = self._symbols
        tens, strain = self.eq.tensions(r)
        return ca.Function("tensions", [x, t], [tens, strain], ["x", "t"], ["T", "strain"])

    @cached_property
    def nodes(self) -> ca.Function:
        """``nodes(x, t) -> r`` (3, N+1), m."""
        x, _, t, r, _ = self._symbols
        return ca.Function("nodes", [x, t], [ca.horzcat(*r)], ["x", "t"], ["r"])

    @cached_property
    def node_velocities(self) -> ca.Function:
        """``node_velocities(v, t) -> u`` (3, N+1), m/s."""
        _, v, t, _, vel = self._symbols
        return ca.Function("node_velocities", [v, t], [ca.horzcat(*vel)], ["v", "t"], ["u"])

    @cached_property
    def segment_tension(self) -> ca.Function:
        """``segment_tension(x, v, t) -> T`` (N), with the material damping term."""
        x, v, t, r, vel = self._symbols
        ev = [] if self._ev is None else [self._ev]
        return ca.Function("segment_tension", [x, v, t, *ev],
                           [self.eq.tensions(r, vel, self._ev)[0]], self._names, ["T"])

    @cached_property
    def top_force(self) -> ca.Function:
        """``top_force(x, v, t) -> F`` (N), the force of end_b's attachment on the cable."""
        x, v, t, r, vel = self._symbols
        # the force the attachment applies to node N: M_N a_b - (cable, weight, drag)
        acc_b = ca.jacobian(vel[-1], t)
        f_n = self.eq.total(self.eq.elastic(r, None, vel, None, self._ev),
                            self.eq.static_loads(), self.eq.drag(r, vel))[-1]
        ev = [] if self._ev is None else [self._ev]
        return ca.Function(
            "top_force", [x, v, t, *ev], [ca.mtimes(self.eq.mass_blocks(r)[-1], acc_b) - f_n],
            self._names, ["F"])

    @cached_property
    def energy(self) -> ca.Function:
        """``energy(x, v, t) -> (kinetic, potential)`` (J)."""
        x, v, t, r, _ = self._symbols
        ev = [] if self._ev is None else [self._ev]
        return ca.Function("energy", [x, v, t, *ev],
                           list(self.eq.energy(v, self.mass_expr(r), r, self._ev)),
                           self._names, ["kinetic", "potential"])

    @cached_property
    def static_stiffness(self) -> ca.Function:
        """``static_stiffness(x, t) -> K`` (N/m): -dF/dx of the forces without drag (the
        viscoelastic law: with its dashpot strains held at the relaxed e_v = e(x), the
        fast-load stiffness EA_d, as the axial model's modes)."""
        x, _, t, r, _ = self._symbols
        f0 = self.free(self.eq.total(self.eq.elastic(r, None, None, None, self._ev),
                                     self.eq.static_loads()))
        k = -ca.jacobian(f0, x)
        if self._ev is not None:
            k = ca.substitute(k, self._ev, self.eq.tensions(r)[1])
        return ca.Function("static_stiffness", [x, t], [k], ["x", "t"], ["K"])

    @cached_property
    def _static_fj(self) -> ca.Function:
        """``static_fj(x, t, lam) -> (F, dF/dx)`` at rest, the drag scaled by ``lam``."""
        x, _, t, r, _ = self._symbols
        # at rest: every node, the prescribed ends included, has zero velocity
        still = [ca.SX.zeros(3) for _ in r]
        lam = ca.SX.sym("lam")  # load factor on the drag (continuation)
        fs = self.free(self.eq.total(self.eq.elastic(r, None, None, None), self.eq.static_loads(),
                                  [lam * fd for fd in self.eq.drag(r, still)]))
        return ca.Function("static_fj", [x, t, lam], [fs, ca.jacobian(fs, x)])

    @cached_property
    def ends(self) -> ca.Function:
        """``ends(t) -> (r_a, v_a, r_b, v_b)``: prescribed end positions (m) and velocities
        (m/s) (zeros for end_a when it is free)."""
        p = self.params
        t = ca.SX.sym("t")
        if p.fixed_a:
            ra, va = ca.vec(p.end_a_position(t)), ca.vec(self._a_vel(t))
        else:
            ra, va = ca.SX.zeros(3), ca.SX.zeros(3)
        return ca.Function("ends", [t], [ra, va, ca.vec(p.top_position(t)),
                                         ca.vec(self._top_vel(t))])

    @cached_property
    def mass_blocks(self) -> ca.Function:
        """``mass_blocks(x, t) -> B`` (kg): the 3x3 mass block of every node (with the
        added mass of (5.2)), each stored column-major, stacked, shape (9 (N+1),)."""
        x, _, t, r, _ = self._symbols
        blocks = self.eq.mass_blocks(r)
        return ca.Function("mass_blocks", [x, t], [ca.vertcat(*[ca.vec(b) for b in blocks])])

    # -- parameters ---------------------------------------------------------------------
    @staticmethod
    def _derivative(fn: TimeFunction) -> TimeFunction:
        ts = ca.SX.sym("t")
        dfun = ca.Function("d", [ts], [ca.jacobian(ca.vec(fn(ts)), ts)])

        def vel(t: Any) -> Any:
            return dfun(t)

        return vel

    @property
    def node_mass(self) -> np.ndarray:
        """Mass plus the added mass of units and bodies per node and axis, kg, shape
        (N+1, 3) (the cable's own added mass depends on the configuration: see
        :attr:`mass_matrix`)."""
        return self.eq.node_mass.copy()

    @property
    def node_weight(self) -> np.ndarray:
        """Weight in water lumped at each node, N (positive down), shape (N+1,)."""
        return self.eq.node_weight.copy()

    # -- the nodes -----------------------------------------------------------------------
    def all_positions(self, x: Any, t: Any) -> list[Any]:
        """Every node's position (m): the free nodes' from ``x``, the prescribed ends' at
        time ``t`` (s).

        Parameters
        ----------
        x : casadi expression (3 n_free,)
            Free-node positions, m.
        t : casadi expression or float
            Time, s.
        """
        p = self.params
        return self._with_ends(x, lambda: p.end_a_position(t), lambda: p.top_position(t))

    def all_velocities(self, v: Any, t: Any) -> list[Any]:
        """Every node's velocity (m/s): the free nodes' from ``v``, the prescribed ends' at
        time ``t`` (s).

        Parameters
        ----------
        v : casadi expression (3 n_free,)
            Free-node velocities, m/s.
        t : casadi expression or float
            Time, s.
        """
        return self._with_ends(v, lambda: self._a_vel(t), lambda: self._top_vel(t))

    def _with_ends(self, x: Any, end_a: Callable[[], Any], top: Callable[[], Any]
                   ) -> list[Any]:
        """Every node's 3-vector from end_a: ``end_a()`` where end_a is prescribed (called
        only then: its function is built on first use), the free nodes' from ``x``, then
        ``top()``."""
        nodes = [x[3 * k:3 * k + 3] for k in range(self.n_free)]
        if self.params.fixed_a:
            nodes = [ca.vec(end_a())] + nodes
        return nodes + [ca.vec(top())]

    def free(self, f: list[Any]) -> Any:
        """The free nodes' entries of a list of node terms, stacked."""
        return ca.vertcat(*[f[i] for i in self.free_nodes])

    def mass_expr(self, r: list[Any]) -> Any:
        """Block-diagonal mass matrix of the free nodes with the direction-dependent added
        mass of (5.2), kg."""
        blocks = self.eq.mass_blocks(r)
        return ca.diagcat(*[blocks[i] for i in self.free_nodes])

    # -- reference scales --------------------------------------------------------------
    def force_scale(self, x: np.ndarray | None = None, t: float = 0.0) -> float:
        """Force scale F of the scaled residual, N: the largest of the total weight in
        water, the largest segment tension at the positions ``x`` (if given) and 1 N.

        Parameters
        ----------
        x : ndarray (3 n_free,), optional
            Free-node positions, m.
        t : float
            Time of the prescribed ends, s.
        """
        f = max(float(np.abs(self.eq.node_weight).sum()), 1.0)
        if x is not None:
            f = max(f, float(np.max(np.asarray(self.tensions(x, t)[0]))))
        return f

    # -- time stepping -----------------------------------------------------------------
    def state_size(self, scheme: str) -> int:
        """Length of the stepped state vector of ``scheme``.

        ``(x, v, a)`` for ``"midpoint"`` and ``"trapezoidal"`` (a: the acceleration, used by
        the trapezoidal rule and, for the midpoint rule, only by the Newton predictor);
        ``(x, v, x_prev, v_prev, started)`` for ``"bdf2"`` (started = 0 before the first
        step, which is then a backward-Euler step). With the viscoelastic law (midpoint
        only) the N dashpot strains e_v follow.
        """
        nf3 = 3 * self.n_free
        if self.solid is not None:
            return 3 * nf3 + self.params.segments
        return 4 * nf3 + 1 if scheme == "bdf2" else 3 * nf3

    def initial_state(self, x: np.ndarray, v: np.ndarray | None = None,
                      scheme: str = "midpoint", t: float = 0.0) -> np.ndarray:
        """Stepped state of ``scheme`` from free-node positions (m) and velocities (m/s)
        at time t (s).

        Parameters
        ----------
        x : ndarray (3 n_free,)
            Free-node positions, m.
        v : ndarray (3 n_free,), optional
            Free-node velocities, m/s (None: at rest).
        scheme : str
            One of :data:`SCHEMES`.
        t : float
            Time, s.
        """
        x = np.asarray(x, float).reshape(-1)
        v = np.zeros_like(x) if v is None else np.asarray(v, float).reshape(-1)
        if self.solid is not None:
            if scheme != "midpoint":
                raise CableOCPError(f'scheme = "{scheme}": the viscoelastic law steps with '
                                    'the midpoint rule (valid: "midpoint")')
            # relaxed at rest: e_v = e (0 where a segment is slack: an unloaded rope)
            eps = np.asarray(self.tensions(x, t)[1]).ravel()
            return np.concatenate([x, v, np.zeros_like(x), np.maximum(eps, 0.0)])
        if scheme == "bdf2":
            return np.concatenate([x, v, x, v, [0.0]])
        a = np.zeros_like(x)
        if scheme == "trapezoidal":
            from scipy.sparse import csc_matrix

            from cable_ocp.numerics.linalg import solve_sparse

            mm = csc_matrix(self.mass_matrix(x, t).sparse())
            sol = solve_sparse(mm, np.asarray(self.forces(x, v, t)).reshape(-1))
            # a singular mass matrix (a massless free node) leaves a = 0: the trapezoidal
            # rule's first step then solves for it (its Newton reports a failure if it can't)
            a = np.zeros_like(x) if sol is None else sol
        return np.concatenate([x, v, a])


    def step_function(self, dt: float, scheme: str = "midpoint", *, tol: float = 1e-10,
                      max_iter: int = 20, solver: str = "newton",
                      linear_solver: str = "qr", compile_kernel: bool = True,
                      force_scale: float | None = None) -> ca.Function:
        """One time step ``step(z, t0) -> (z1, residual, iterations)`` as a CasADi Function.

        ``z`` is the state of :meth:`state_size`, ``t0`` the time at the start of the step
        (s). ``residual`` is the largest nodal force residual at the accepted iterate
        divided by the force scale F (``force_scale``, N; default :meth:`force_scale`),
        dimensionless; a step that did not converge in ``max_iter`` iterations returns a
        residual above ``tol`` (or NaN). ``iterations`` counts the Newton iterations;
        ``min_strain`` is the smallest segment strain at the end of the step (<= 0: a
        segment is slack) and ``slack_segment`` its index.

        Parameters
        ----------
        dt : float
            The time step, s.
        scheme : str
            One of :data:`SCHEMES` (below).
        tol : float
            Newton tolerance on the scaled residual (-).
        max_iter : int
            Newton iterations per step.
        solver : {"newton", "rootfinder"}
            Below.
        linear_solver : str
            CasADi linear solver of the compiled-kernel Newton matrix.
        compile_kernel : bool
            The per-segment kernel compiled to C (else interpreted).
        force_scale : float, optional
            Force scale F of the residual, N (default :meth:`force_scale`).

        Schemes (all implicit, A-stable, second order; the equations of a step are solved for
        the new free-node positions x1):

        ``"midpoint"`` (default): the implicit midpoint rule with a discrete-gradient
            tension, x1 - x0 = dt (v0 + v1) / 2 and
            M(x_m) (v1 - v0) = dt [F_T(x0, x1) + F_other(x_m, (x1 - x0) / dt, t0 + dt/2)],
            where each segment pulls with T_bar (d0 + d1) / (|d0| + |d1|), T_bar the mean
            of T over [eps0, eps1] (exact for EA e, also across the no-compression kink;
            3-point Gauss for a tension-strain table:
            :func:`~cable_ocp.dynamics.lumped_equations.interval_tension`) and d the
            segment vectors at the two levels (the energy-momentum method of Simo &
            Tarnow (1992), Gonzalez (1996)). The elastic work then equals the change of the
            strain energy, weights are constant forces and the mass is constant in air, so
            an undamped run in air conserves the energy (up to the Newton tolerance; with a
            table, up to the quadrature of T where a segment turns slack). A damped
            segment's elastic plus damping tension cannot push (smooth_positive). No
            numerical damping: |amplification| = 1 for every undamped linear mode, at any
            dt.
        ``"trapezoidal"``: x1 - x0 = dt (v0 + v1)/2, v1 - v0 = dt (a0 + a1)/2 with
            M(x1) a1 = F(x1, v1, t1) (Newmark's average acceleration). Same linear stability
            as the midpoint rule, not energy-conserving for the nonlinear springs.
        ``"bdf2"``: the two-step backward differentiation formula on x' = v, M v' = F,
            L-stable: unresolved high frequencies (axial waves at large dt) are damped
            out, at the price of some damping of the resolved motion. The first step is a
            backward-Euler step.

        Solvers:

        ``"newton"`` (default): Newton's method written in the CasADi graph (at most
            ``max_iter`` iterations, each skipped by a short-circuit ``if_else`` once the
            residual is below ``tol``, or once the Newton update is at rounding level,
            1e-13 of the coordinates, with the residual below max(1000 tol, 1e-6)). Its
            matrix has the tension's derivative exact and the mass and drag terms as
            M(x)/dt^2-type and velocity-derivative terms (the derivatives of the
            added-mass projector and of the drag with respect to the segment orientation
            are left out: they multiply small quantities, so Newton still converges fast,
            to the exact solution of the step); a backtracking line search on the
            residual; where Newton fails, two half steps instead (up to three times).
            Where the contraction of the last iteration predicts a residual below
            ``tol`` after the current Newton update, the updated iterate is checked with
            the residual alone (no matrix) and accepted if it is below ``tol``: two
            matrix evaluations per step instead of three in most steps; ``iterations``
            counts the matrix evaluations.
            Sparse QR (``linear_solver``, CasADi ``qr``): the midpoint's matrix is not
            symmetric.
        ``"rootfinder"``: CasADi's ``rootfinder("newton")`` with the exact Jacobian (about
            5x slower per iteration; a reference).
        """
        return self.stepper.step_function(dt, scheme, tol=tol, max_iter=max_iter,
                                          solver=solver, linear_solver=linear_solver,
                                          compile_kernel=compile_kernel,
                                          force_scale=force_scale)

    # -- statics and modes ---------------------------------------------------------------
    def static_equilibrium(self, x_guess: np.ndarray, t: float = 0.0, *, tol: float = 1e-9,
                           max_iter: int = 60) -> tuple[np.ndarray, dict[str, Any]]:
        """Rest state of the discrete model by damped Newton: the forces vanish with every
        node at rest (the prescribed ends too) at their positions at time t. If Newton fails
        from ``x_guess``, the current's drag is ramped in (0, 1/4, ..., 1) from there.

        Parameters
        ----------
        x_guess : ndarray (3 n_free,)
            Start, m (e.g. the statics solution interpolated onto the nodes).
        t : float
            Time at which the ends are taken, s.
        tol : float
            Stop when the largest nodal force is below ``tol`` times the force scale
            (largest nodal weight or tension), relative; or, at the rounding floor of a
            stiff cable, when Newton steps stall below 1e-12 of the line length with the
            force below 1e-6 of the scale.
        max_iter : int
            Newton iterations (per stage of the continuation).

        Returns
        -------
        x : ndarray (3 n_free,)
            Node positions, m.
        info : dict
            ``converged`` (bool), ``iterations``, ``residual_N`` (largest nodal force, N),
            ``relative_residual``.
        """
        x = np.asarray(x_guess, float).reshape(-1).copy()
        tens = np.asarray(self.tensions(x, t)[0]).reshape(-1)
        fscale = max(float(np.abs(self.eq.node_weight).max()), float(np.abs(tens).max()), 1.0)
        x1, info = self._static_newton(x, t, 1.0, tol, max_iter, fscale)
        if info["converged"]:
            return x1, info
        # continuation: the current's drag scaled from 0 to 1 (as the statics' ramp)
        xc = x
        total = info["iterations"]
        for lam in (0.0, 0.25, 0.5, 0.75, 1.0):
            xc, info = self._static_newton(xc, t, lam, tol, max_iter, fscale)
            total += info["iterations"]
            if not info["converged"]:
                break
        info["iterations"] = total
        info["continuation"] = True
        return xc, info

    def _static_newton(self, x: np.ndarray, t: float, lam_drag: float, tol: float,
                       max_iter: int, fscale: float) -> tuple[np.ndarray, dict[str, Any]]:
        from scipy.sparse import csc_matrix, identity

        from cable_ocp.numerics.linalg import solve_sparse

        def resid(xx: np.ndarray) -> tuple[np.ndarray, Any]:
            fv, jv = self._static_fj(xx, t, lam_drag)
            return np.asarray(fv).reshape(-1), jv

        x = x.copy()
        f, jac = resid(x)
        it = 0
        stalled = False
        singular = False
        # Levenberg-Marquardt fallback: where the Newton matrix is singular or gives no
        # descent (a start with slack segments: no transverse stiffness, e.g. the chords of
        # a sagging catenary interpolated from the statics are shorter than the stretched
        # segments), solve (K + mu I) dx = F, mu raised tenfold from 1e-8 of the force
        # scale per segment length until the force norm decreases, relaxed after success
        n_dof = x.size
        eye = identity(n_dof, format="csc")
        mu0 = 1e-8 * fscale / float(np.min(self.params.segment_length))
        mu_max = 1e12 * mu0
        mu = 0.0
        for it in range(1, max_iter + 1):  # noqa: B007 - reported
            if not np.all(np.isfinite(f)):
                break
            if np.abs(f).max() <= tol * fscale:
                it -= 1
                break
            jd = csc_matrix(jac.sparse())
            n0 = np.linalg.norm(f)
            m = mu
            accepted = False
            sol = None
            while True:
                sol = solve_sparse(jd if m == 0.0 else jd - m * eye, f)
                if sol is not None:
                    dx = -sol
                    lam = 1.0  # backtracking on the force norm
                    while lam > 1e-4:
                        fn, jn = resid(x + lam * dx)
                        if (np.all(np.isfinite(fn))
                                and np.linalg.norm(fn) < (1 - 1e-4 * lam) * n0):
                            accepted = True
                            break
                        lam *= 0.5
                    if accepted or np.abs(f).max() <= 1e-6 * fscale:
                        break  # descent, or the rounding floor of a converged iterate
                if m >= mu_max:
                    break
                m = mu0 if m == 0.0 else 10.0 * m
            if not accepted:
                singular = sol is None
                stalled = np.abs(f).max() <= 1e-6 * fscale
                break
            mu = 0.0 if m <= mu0 else m / 100.0
            x = x + lam * dx
            f, jac = fn, jn
            stalled = lam * np.abs(dx).max() <= 1e-12 * self.params.length
            if stalled and np.abs(f).max() <= 1e-6 * fscale:
                break
        rmax = float(np.abs(f).max()) if np.all(np.isfinite(f)) else math.inf
        ok = rmax <= tol * fscale or (stalled and rmax <= 1e-6 * fscale)
        return x, {"converged": bool(ok), "iterations": it, "residual_N": rmax,
                   "relative_residual": rmax / fscale, "singular_jacobian": singular}

    def linearize(self, x: np.ndarray, t: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
        """Stiffness and mass matrices about a rest state, dense (3 n_free square).

        K = -dF/dx of the forces without drag (tension, weight, body loads): the current
        shapes the rest state ``x`` and its tensions, but its drag is left out of K (its
        orientation stiffness is not symmetric and its velocity part is damping). K is
        symmetrised (it is symmetric up to rounding: the Hessian of the potential energy).
        M includes the direction-dependent added mass of (5.2) at ``x``.

        Parameters
        ----------
        x : ndarray (3 n_free,)
            Rest positions, m.
        t : float
            Time of the prescribed ends, s.
        """
        k = np.asarray(self.static_stiffness(x, t))
        m = np.asarray(ca.densify(self.mass_matrix(x, t)))
        return 0.5 * (k + k.T), 0.5 * (m + m.T)

    def modes(self, x: np.ndarray, count: int | None = None, t: float = 0.0
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Natural frequencies and mode shapes about the rest state ``x``.

        Solves K phi = omega^2 M phi (:meth:`linearize`).

        Parameters
        ----------
        x : ndarray (3 n_free,)
            Rest positions, m.
        count : int, optional
            Number of modes (default all).
        t : float
            Time of the prescribed ends, s.

        Returns
        -------
        omega : ndarray (count,)
            Natural frequencies, rad/s, ascending (a negative eigenvalue, an unstable
            direction, is reported as a negative omega = -sqrt(|lambda|)).
        shapes : ndarray (count, N + 1, 3)
            Node displacements from end_a to end_b (prescribed nodes are 0), scaled so
            that the largest |component| is 1 and positive.
        eigenvalues : ndarray (count,)
            omega^2, 1/s^2.
        """
        from scipy.linalg import eigh

        kmat, mmat = self.linearize(x, t)
        nfree3 = kmat.shape[0]
        count = nfree3 if count is None else max(1, min(int(count), nfree3))
        lam, vec = eigh(kmat, mmat, subset_by_index=[0, count - 1])
        omega = np.sign(lam) * np.sqrt(np.abs(lam))
        n = self.params.segments
        shapes = np.zeros((count, n + 1, 3))
        for k in range(count):
            s = np.zeros((n + 1, 3))
            s[self.free_nodes] = vec[:, k].reshape(-1, 3)
            big = s.reshape(-1)[int(np.argmax(np.abs(s)))]
            shapes[k] = s / big
        return omega, shapes, lam
