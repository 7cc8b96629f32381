"""Axial (one-dimensional) dynamics of a vertical cable with a varying length.

Huang (1992), ch. 3: a cable hangs vertically from a sheave that heaves with the ship,
cable is paid out or hauled in at the sheave, and a subsea unit hangs at the lower end.

Equations (z up; s the unstretched arc length from the unit, end_a, s = 0, to the sheave,
s = L(t); z(s, t) the height of material point s; e = z_s - 1 the strain)::

    (m + m_at) z_tt = T_s - w - k (1 + e) |z_t| z_t,      T = EA e + c e_t
    (M + M_a) z_tt(0, t) = T(0, t) - W - 1/2 rho C_D S |z_t| z_t    (the unit)
    z(L(t), t) = z_b(t)                                   (the sheave)

with m the mass and m_at the tangential added mass per length, w the weight in water per
length, k = 1/2 rho C_t pi d the tangential drag factor, c the internal damping, EA the
axial stiffness, M, M_a, W, C_D S the unit's mass, added mass (z), weight in water and drag
area. This is Huang's eq. (3.1) with boundary conditions (3.2)-(3.3) written for material
points: Huang differentiates in time at a fixed distance below the sheave, which is a
material point only when the strain is neglected; the two differ by terms of order
(strain x pay-out speed). The drag is taken per stretched length (the factor 1 + e) as in
Huang's (2.46); Huang's (3.1) omits it (a relative change of order the strain).

Materials (:mod:`cable_ocp.physics.elasticity`, :func:`~cable_ocp.physics.elasticity.
axial_law_tension`): with ``[cable] tension_strain`` T = u(e) + c e_t (the table's PCHIP);
with ``[cable] viscoelastic`` T = EA_s e + (EA_d - EA_s)(e - e_v) + c e_t, each element's
dashpot strain e_v a state, e_v,t = (e - e_v) / tau + (y L_t / L) e_v,y (carried with the
material during pay-out; central differences between elements, one-sided at the ends).

Fixed-domain transformation (Huang's (3.4)-(3.7), measured here from the unit): with
y = s / L(t) in [0, 1] and the unknowns Z(y, t) = z(yL, t) and the material velocity
V(y, t) = z_t(yL, t), the chain rule gives the first-order system::

    Z_t = V + (y L_t / L) Z_y
    (m + m_at) (V_t - (y L_t / L) V_y) = T_y / L - w - k (1 + e) |V| V,   e = Z_y / L - 1

on the fixed interval; at y = 1, Z = z_b(t) and V = z_b'(t) - L_t Z_y / L (the material
passing over the sheave).

Space: finite differences on the uniform grid y_i = i / N (as Huang's 3.2.6), written in
the conservative lumped-mass form: node i carries the cable between the mid-points of its
elements (mass (m + m_at) L / N, half of it at the two ends), element tensions come from
the node differences, and the unit's node adds its own mass. Why: (i) at fixed length it
is exactly the mass-spring chain, so the undamped semi-discrete system is Hamiltonian
(the energy-conserving integrators conserve it to round-off) and its modes are a
symmetric generalised eigenproblem; (ii) the static profile of a uniform line is exact at
the nodes (the tension is linear in s); (iii) the tip-mass boundary is second-order
accurate without one-sided stencils; (iv) a vertical line of the 3D lumped-mass model
(Huang ch. 5) is the same discrete system. The advection terms (pay-out) use central
differences (second order); at the sheave a one-sided second-order difference.
Frequencies converge as (beta L / N)^2 / 24 (lumped-mass dispersion).

Time: implicit, A-stable schemes written as a CasADi Newton ``rootfinder`` step and stepped
with ``fold``/``mapaccum`` (no Python per step; a Python call per chunk of steps for the
progress hook):

* ``midpoint`` (default): implicit midpoint rule, second order, symplectic; conserves the
  energy of the undamped linear system exactly (quadratic invariant);
* ``gauss4``: two-stage Gauss-Legendre, fourth order, symplectic;
* ``trapezoidal``: second order, A-stable, non-dissipative;
* ``bdf2``: second-order backward differentiation, L-stable (damps unresolved high
  modes), started with one trapezoidal step;
* ``thesis``: Huang's own second-order implicit finite-difference scheme (3.8)-(3.10), a
  separate baseline in :mod:`cable_ocp.dynamics.axial_thesis`.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

import casadi as ca
import numpy as np
import scipy.linalg

from cable_ocp.dynamics.checks import check_axial
from cable_ocp.dynamics.driven import axial_driven_step
from cable_ocp.dynamics.model import DrivenStep
from cable_ocp.dynamics.result import (
    ModesResult,
    SimulationResult,
    coarse_step_warnings,
    full_speed_start_warnings,
    slack_element,
    slack_report,
    until_slack,
)
from cable_ocp.dynamics.stepping import chunk_functions, run_chunks
from cable_ocp.dynamics.vertical_line import vertical_line
from cable_ocp.errors import CableOCPError
from cable_ocp.physics.drag import quadratic_drag
from cable_ocp.physics.elasticity import axial_law_tension
from cable_ocp.scene.dynamics import DynamicScene
from cable_ocp.scene.motion import motion_function

__all__ = ["SLACK_MESSAGE", "AxialModel", "check_axial", "static_profile"]

_GAUSS_C = (0.5 - math.sqrt(3.0) / 6.0, 0.5 + math.sqrt(3.0) / 6.0)
_GAUSS_A = ((0.25, 0.25 - math.sqrt(3.0) / 6.0), (0.25 + math.sqrt(3.0) / 6.0, 0.25))
#: the axial model's slack message (:func:`cable_ocp.dynamics.result.slack_report`)
SLACK_MESSAGE = ("slack: tension <= 0 first at t = {t:.6g} s in element {segment} (s = "
                 "{location:.4g} m from the unit); the axial model cannot follow slack "
                 "(Huang (1992) 4.5.1): {action}")



def static_profile(scene: DynamicScene, s: np.ndarray, length: float | None = None
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Closed-form static state of the vertical line: (height z (m), tension T (N)) at the
    unstretched arc lengths ``s`` (m, from the unit).

    T(s) = W + w s and z(s) = z_b - (L - s) - (W (L - s) + w (L^2 - s^2) / 2) / EA.

    Parameters
    ----------
    scene : DynamicScene
        A vertical-line scene with a unit.
    s : ndarray
        Unstretched arc lengths from the unit, m.
    length : float or ndarray, optional
        Unstretched length L, m (default the scene's).
    """
    length = scene.length if length is None else length
    w = scene.statics.cable.weight_in_water
    big_w = scene.unit.weight_in_water  # type: ignore[union-attr]
    ea = scene.statics.cable.axial_stiffness
    s = np.asarray(s, dtype=float)
    tension = big_w + w * s
    z = (scene.top_position[2] - (length - s)
         - (big_w * (length - s) + 0.5 * w * (length**2 - s**2)) / ea)
    return z, tension


class AxialModel:
    """The discretised axial model of one scene (see the module docstring).

    Parameters
    ----------
    scene : DynamicScene
        A vertical-line scene (:func:`check_axial`).
    segments : int, optional
        Number of elements N (default ``simulation.segments``).

    Attributes
    ----------
    n : int
        Number of elements; the state is (zeta_0..zeta_{N-1}, V_0..V_{N-1})
        (:meth:`_fields`).

    The model implements :class:`cable_ocp.dynamics.model.CableModel`.
    """

    #: the scene's ``simulation.model`` of this model
    name = "axial"

    def __init__(self, scene: DynamicScene, segments: int | None = None) -> None:
        check_axial(scene)
        self.scene = scene
        line = vertical_line(scene)
        self.n = int(segments or scene.simulation.segments)
        self.ea = line.axial_stiffness
        self.mu = line.mass_per_length
        self.w = line.weight_per_length
        self.c = float(scene.cable[0].axial_damping)
        cab = scene.statics.cable
        #: the tension-strain table (None: linear) and the standard linear solid (None:
        #: elastic); with the solid the state carries each element's dashpot strain e_v
        self.table = cab.strain_table
        self.solid = cab.viscoelastic.law(cab.axial_stiffness) if cab.viscoelastic else None
        self.k_drag = line.drag_factor
        self.unit_mass = line.unit_mass
        self.unit_weight = line.unit_weight
        self.unit_drag = line.unit_drag
        self.z_top0 = line.top_height
        self.length0 = line.length
        self.motion = motion_function(scene)
        #: a tension below -slack_tolerance (N) is slack: 1e-9 of the static top tension,
        #: clear of round-off where a line released unstretched carries no load yet
        self.slack_tolerance = 1e-9 * (self.unit_weight + abs(self.w) * self.length0)
        self.gravity = scene.statics.environment.gravity
        #: static elongation of the line, m (floored at 1e-9 L): the position scale of the
        #: Newton residual
        self.elongation = max((self.unit_weight * self.length0
                               + 0.5 * abs(self.w) * self.length0**2) / self.ea,
                              1e-9 * self.length0)
        self._rhs_fn: ca.Function | None = None

    # ------------------------------------------------------------------ equations
    def _fields(self, t: Any, x: Any, top_at_rest: bool = False) -> dict[str, Any]:
        """Symbolic nodal fields at time t for state x (shared by rhs and outputs).

        The state holds zeta_i = Z_i - Z_ref(y_i, t), the height relative to the
        unstretched line hanging from the current top, Z_ref = z_b(t) - L(t) (1 - y):
        zeta is of the size of the elongation, so the strains (zeta_{i+1} - zeta_i) / h
        carry no round-off from the absolute heights; zeta_N = 0 at the sheave.

        ``top_at_rest``: the sheave's heave velocity and acceleration and the pay-out
        speed and its rate taken as zero (the top's position and the length kept): the
        fields of the initial state, which is at rest, before the motion starts (t = 0-).
        """
        n = self.n
        zeta, vel = x[:n], x[n:2 * n]
        length, dl, ddl, xb, vb, ab = self.motion(t)
        if top_at_rest:
            dl, ddl, vb, ab = 0.0 * dl, 0.0 * ddl, 0.0 * vb, 0.0 * ab
        dy = 1.0 / n
        h = length * dy
        z_full = ca.vertcat(zeta, 0.0)
        eps = (z_full[1:] - z_full[:-1]) / h
        if n >= 2:
            zeta_y_top = (3 * z_full[n] - 4 * z_full[n - 1] + z_full[n - 2]) / (2 * dy)
        else:
            zeta_y_top = (z_full[n] - z_full[n - 1]) / dy
        v_top = vb[2] - dl * (1.0 + zeta_y_top / length)
        v_full = ca.vertcat(vel, v_top)
        eps_dot = (v_full[1:] - v_full[:-1]) / h
        e_v = x[2 * n:3 * n] if self.solid is not None else None
        tension = axial_law_tension(eps, eps_dot, self.ea, self.c, table=self.table,
                                    solid=self.solid, internal_strain=e_v)
        y = ca.DM(np.arange(n + 1) / n)
        heights = z_full + xb[2] - length * (1.0 - y)
        return dict(zeta=zeta, vel=vel, length=length, dl=dl, ddl=ddl, vb=vb, ab=ab, h=h,
                    dy=dy, z_full=z_full, v_full=v_full, eps=eps, tension=tension,
                    heights=heights, e_v=e_v)

    def rhs(self, t: Any, x: Any) -> Any:
        """Time derivative of the state (CasADi expression).

        Parameters
        ----------
        t : casadi expression
            Time, s.
        x : casadi expression (2N,)
            The state (:meth:`_fields`).
        """
        f = self._fields(t, x)
        n, h, dy = self.n, f["h"], f["dy"]
        vel, eps, ten = f["vel"], f["eps"], f["tension"]
        z_full, v_full = f["z_full"], f["v_full"]
        y = np.arange(n) * (1.0 / n)
        adv = ca.DM(y) * f["dl"] / f["length"]  # y L_t / L at the nodes
        ref_rate = f["dl"] - f["vb"][2]  # L_t - z_b': zeta_t = V + L_t - z_b' + adv zeta_y
        # strain at the nodes (mean of the neighbouring elements; the end element at node 0)
        eps_node = ca.vertcat(eps[0], 0.5 * (eps[:-1] + eps[1:])) if n >= 2 else eps[0]
        drag = quadratic_drag(self.k_drag * (1.0 + eps_node), vel)
        # node 0: the unit plus half an element
        m0 = self.unit_mass + 0.5 * self.mu * h
        f0 = (ten[0] - self.unit_weight - 0.5 * h * (self.w + drag[0])
              - quadratic_drag(self.unit_drag, vel[0]))
        acc = [f0 / m0]
        dz = [vel[0] + ref_rate]
        for i in range(1, n):
            zy = (z_full[i + 1] - z_full[i - 1]) / (2 * dy)
            vy = (v_full[i + 1] - v_full[i - 1]) / (2 * dy)
            acc.append((ten[i] - ten[i - 1] - h * (self.w + drag[i])) / (self.mu * h)
                       + adv[i] * vy)
            dz.append(vel[i] + ref_rate + adv[i] * zy)
        if self.solid is None:
            return ca.vertcat(*dz, *acc)
        # the dashpot strain of the material at the element mid-points y_{i+1/2}, carried
        # with the material as the grid moves through it (pay-out): e_v,t + adv e_v,y
        e_v = f["e_v"]
        y_mid = (np.arange(n) + 0.5) / n
        dev = []
        for i in range(n):
            lo, hi = max(i - 1, 0), min(i + 1, n - 1)
            dvy = (e_v[hi] - e_v[lo]) / ((hi - lo) * dy) if hi > lo else 0.0
            dev.append(self.solid.internal_rate(eps[i], e_v[i])
                       + y_mid[i] * f["dl"] / f["length"] * dvy)
        return ca.vertcat(*dz, *acc, *dev)

    def outputs(self, t: Any, x: Any, top_at_rest: bool = False
                ) -> tuple[Any, Any, Any, Any, Any]:
        """(node heights z_0..z_N (m), element tensions (N), top tension (N), L (m),
        node material velocities V_0..V_N (m/s)).

        Parameters
        ----------
        t : casadi expression
            Time, s.
        x : casadi expression (2N,)
            The state.
        top_at_rest : bool
            Evaluate with the top at rest (:meth:`_fields`): the sample of the initial
            state. Without it, an abrupt start (``ramp_time = 0``: the pay-out speed or the
            heave velocity jumps at t = 0) would give the sheave's material its new velocity
            against a line still at rest, and the damping term c e_t of the top element
            a tension the state does not carry (with c = 1e5 N s, 25.2 kN against the static
            45.3 kN on huang_3_3_5.toml paid out at 0.5 m/s).
        """
        f = self._fields(t, x, top_at_rest)
        eps_top = f["eps"][self.n - 1]
        v_top = f["v_full"][self.n]
        a_top = f["ab"][2] - f["ddl"] * (1.0 + eps_top)
        drag_top = quadratic_drag(self.k_drag * (1.0 + eps_top), v_top)
        top = f["tension"][self.n - 1] + 0.5 * f["h"] * (self.w + self.mu * a_top + drag_top)
        return f["heights"], f["tension"], top, f["length"], f["v_full"]

    # ------------------------------------------------------------------ initial state
    def initial_state(self) -> np.ndarray:
        """State at t = 0: the closed-form static profile ("static") or the unstretched
        line hanging straight down from end_b ("unstrained", zeta = 0), at rest."""
        if self.scene.simulation.start == "unstrained":
            return np.zeros(self.state_size())
        return self.rest_state()

    def rest_state(self) -> np.ndarray:
        """The closed-form static profile at rest (whatever ``simulation.start`` says)."""
        n = self.n
        s = np.arange(n) * self.length0 / n
        z, _ = static_profile(self.scene, s)
        zeta = z - (self.z_top0 - (self.length0 - s))
        if self.table is not None:
            # the discrete static state: element i carries W + w h (i + 1/2), at the strain
            # of the model's own law u(e) (exact inverse, not the statics' e(T))
            h = self.length0 / n
            eps = self.table.invert(self.unit_weight + self.w * h * (np.arange(n) + 0.5))
            zeta = -np.cumsum((h * eps)[::-1])[::-1]
        if self.solid is not None:  # at rest the dashpot carries the static strain
            eps = np.diff(np.append(zeta, 0.0)) / (self.length0 / n)
            return np.concatenate([zeta, np.zeros(n), eps])
        return np.concatenate([zeta, np.zeros(n)])

    def state_size(self) -> int:
        """The nodes' height offsets zeta and material velocities V: ``2 N``."""
        return 3 * self.n if self.solid is not None else 2 * self.n

    def static_state(self) -> tuple[np.ndarray, dict[str, Any]]:
        """:meth:`initial_state` (``simulation.start``) and its source."""
        start = self.scene.simulation.start
        how = ("hanging straight down, unstretched, at rest" if start == "unstrained" else
               "the closed-form static profile, at rest")
        return self.initial_state(), {"source": start, "converged": True, "message": how}

    def driven_step(self, dt: float | ca.SX | None = None) -> DrivenStep:
        """The midpoint step with the top's height and the length as inputs over a step of
        ``dt`` s (default ``simulation.time_step``; a CasADi symbol: the step's size an input;
        :func:`cable_ocp.dynamics.driven.axial_driven_step`; the linear law only)."""
        if self.table is not None or self.solid is not None:
            raise CableOCPError("cable.tension_strain / cable.viscoelastic: the driven axial "
                                "step (the heave plant) has the linear law only; give "
                                "axial_stiffness alone")
        if dt is None:
            dt = self.scene.simulation.time_step
        return axial_driven_step(self, dt if isinstance(dt, ca.SX) else float(dt))

    def linearize(self) -> tuple[np.ndarray, np.ndarray]:
        """Stiffness K (N/m) and mass M (kg) about the static state (:meth:`matrices`)."""
        m, k = self.matrices()
        return k, m

    # ------------------------------------------------------------------ time stepping
    def _rhs_function(self) -> ca.Function:
        if self._rhs_fn is None:
            t = ca.SX.sym("t")
            x = ca.SX.sym("x", self.state_size())
            self._rhs_fn = ca.Function("rhs", [t, x], [self.rhs(t, x)])
        return self._rhs_fn

    def step_function(self, scheme: str, dt: float, tol: float, max_iter: int) -> ca.Function:
        """One step as a CasADi function ``(acc, t0) -> acc``.

        ``acc`` stacks the state (2N), the previous state (2N) and a first-step flag (bdf2
        only: its first step is trapezoidal), the largest scaled Newton residual so far,
        the smallest element tension so far (N), the time of the first tension <= 0 (s,
        inf if none) and that element's index.

        Parameters
        ----------
        scheme : str
            ``midpoint``, ``gauss4``, ``trapezoidal`` or ``bdf2``.
        dt : float
            The step, s.
        tol : float
            Newton tolerance on the scaled residual (-).
        max_iter : int
            Newton iterations per step.
        """
        n2 = self.state_size()
        f = self._rhs_function()
        # residual scales: positions in units of the static elongation of the line (the
        # displacement scale of the motion), accelerations in units of g, so that the
        # tolerance bounds the force balance of every node relative to its weight
        scale_x = ca.DM([1.0 / self.elongation] * self.n + [1.0 / (dt * self.gravity)] * self.n
                        + [self.length0 / self.elongation] * (n2 - 2 * self.n))
        x0 = ca.SX.sym("x0", n2)
        t0 = ca.SX.sym("t0")
        params = [x0, t0]
        if scheme in ("midpoint", "trapezoidal", "bdf2"):
            x1 = ca.SX.sym("x1", n2)
            unknown = x1
            trap = x1 - x0 - 0.5 * dt * (f(t0, x0) + f(t0 + dt, x1))
            if scheme == "midpoint":
                res = x1 - x0 - dt * f(t0 + 0.5 * dt, 0.5 * (x0 + x1))
            elif scheme == "trapezoidal":
                res = trap
            else:
                xm1 = ca.SX.sym("xm1", n2)
                first = ca.SX.sym("first")
                bdf = x1 - 4.0 / 3.0 * x0 + xm1 / 3.0 - 2.0 / 3.0 * dt * f(t0 + dt, x1)
                res = first * trap + (1.0 - first) * bdf
                params += [xm1, first]
            res = res * scale_x
            x_new = x1
        elif scheme == "gauss4":
            k = ca.SX.sym("k", n2, 2)
            unknown = ca.vec(k)
            rows = []
            for i in range(2):
                xi = x0 + dt * (_GAUSS_A[i][0] * k[:, 0] + _GAUSS_A[i][1] * k[:, 1])
                rows.append((k[:, i] - f(t0 + _GAUSS_C[i] * dt, xi)) * dt * scale_x)  # dt k ~ x
            res = ca.vertcat(*rows)
            x_new = x0 + 0.5 * dt * (k[:, 0] + k[:, 1])
        else:
            raise CableOCPError(f'simulation.scheme = "{scheme}": not an axial scheme of this '
                                "module (valid: midpoint, gauss4, trapezoidal, bdf2)")
        p = ca.vertcat(*params)
        rf = ca.rootfinder("rf", "newton", {"x": unknown, "p": p, "g": res},
                           {"abstol": tol, "abstolStep": 1e-14 * tol, "max_iter": max_iter,
                            "error_on_fail": False})
        res_fn = ca.Function("res", [unknown, p], [ca.norm_inf(res)])
        xnew_fn = ca.Function("xnew", [unknown, p], [x_new])
        t_sym = ca.SX.sym("t")
        x_sym = ca.SX.sym("x", n2)
        ten = self.outputs(t_sym, x_sym)[1]
        ten_fn = ca.Function("ten", [t_sym, x_sym], [ten])

        # the step in MX (the rootfinder is an MX-level call)
        bdf = scheme == "bdf2"
        off = 2 * n2 + 1 if bdf else n2
        acc = ca.MX.sym("acc", off + 4)
        tm = ca.MX.sym("t")
        xa = acc[:n2]
        pv = ca.vertcat(xa, tm, acc[n2:off]) if bdf else ca.vertcat(xa, tm)
        if scheme == "gauss4":  # stage derivatives: start from the current slope
            guess = ca.repmat(f(tm, xa), 2, 1)
        else:
            guess = xa
        sol = rf(guess, pv)
        xn = xnew_fn(sol, pv)
        r = res_fn(sol, pv)
        tens = ten_fn(tm + dt, xn)
        tmin_step = ca.mmin(tens)
        rmax, tmin, t_slack, e_slack = (acc[off + k] for k in range(4))
        idx = ca.DM(np.arange(self.n, dtype=float))
        is_min = tens <= tmin_step
        e_now = ca.dot(idx, is_min) / ca.sum1(is_min)
        first_slack = ca.logic_and(tmin_step <= -self.slack_tolerance, t_slack > 1e300)
        new = [xn] + ([xa, ca.MX(0.0)] if bdf else []) + [
            ca.fmax(rmax, ca.if_else(r <= 1e300, r, ca.inf)),  # a NaN residual -> inf
            ca.fmin(tmin, tmin_step),
            ca.if_else(first_slack, tm + dt, t_slack),
            ca.if_else(first_slack, e_now, e_slack),
        ]
        return ca.Function("step", [acc, tm], [ca.vertcat(*new)])

    # ------------------------------------------------------------------ simulate
    def simulate(self, progress: Callable[[int, int], None] | None = None) -> SimulationResult:
        """Integrate over ``simulation.duration`` with ``simulation.scheme``; ``"thesis"``
        is Huang's own finite-difference scheme (3.8)-(3.10) of the same equations
        (:class:`cable_ocp.dynamics.axial_thesis.ThesisAxialModel`, a baseline)."""
        sc = self.scene
        sim = sc.simulation
        scheme = sim.scheme
        if scheme == "thesis":
            from cable_ocp.dynamics.axial_thesis import ThesisAxialModel

            return ThesisAxialModel(sc, self.n).simulate(progress)
        dt = sim.time_step
        n_steps = sim.steps
        every = sim.output_every
        n_out = n_steps // every
        n2 = self.state_size()
        t_build = time.perf_counter()
        chunk_fn, per_chunk = chunk_functions(
            self.step_function(scheme, dt, sim.tolerance, sim.max_iterations), every, n_out)
        tt = ca.SX.sym("t")
        xx = ca.SX.sym("x", n2)
        post = ca.Function("post", [tt, xx], list(self.outputs(tt, xx)))
        # the sample at t = 0 is the initial state at rest, before the motion starts
        post0 = ca.Function("post0", [tt, xx], list(self.outputs(tt, xx, top_at_rest=True)))
        build_time = time.perf_counter() - t_build

        x0 = self.initial_state()
        # the initial state is given (static or unstrained), not checked for slack
        ten0 = float(np.min(np.asarray(post0(0.0, x0)[1])))
        bdf = scheme == "bdf2"
        off = 2 * n2 + 1 if bdf else n2
        acc = np.concatenate([x0] + ([x0, [1.0]] if bdf else [])
                             + [[0.0, ten0, np.inf, -1.0]])
        tol_fail = max(1e3 * sim.tolerance, 1e-6)
        ts, xs, acc, status, message, wall = run_chunks(
            chunk_fn, acc, n_out, per_chunk, every, dt, off, n2, tol_fail,
            sim.on_slack == "stop", progress)
        times, states = [0.0, *ts], [x0, *xs]
        return self._result(np.asarray(times), np.stack(states, axis=1), acc[off:off + 4],
                            (post0, post), status, message, wall, build_time)

    def _result(self, ts: np.ndarray, xs: np.ndarray, tail: np.ndarray,
                post: tuple[ca.Function, ca.Function], status: str, message: str, wall: float,
                build_time: float) -> SimulationResult:
        sc = self.scene
        sim = sc.simulation
        dt = sim.time_step
        rmax, tmin, t_slack, e_slack = (float(v) for v in tail)
        # the first sample (t = 0) with the top at rest (post[0]), the others as stepped
        first = [np.asarray(v).reshape(-1, 1) for v in post[0](ts[0], xs[:, 0])]
        rest = (post[1].map(xs.shape[1] - 1)(ts[1:].reshape(1, -1), xs[:, 1:])
                if xs.shape[1] > 1 else [np.zeros((a.shape[0], 0)) for a in first])
        z_nodes, tens, top, length, vel = (np.hstack([a, np.asarray(v)])
                                           for a, v in zip(first, rest, strict=True))
        keep = until_slack(ts, t_slack, sim.output_every * dt, sim.on_slack)
        if keep is not None:
            ts, z_nodes, tens, top, length, vel = (ts[keep], z_nodes[:, keep], tens[:, keep],
                                                   top[:, keep], length[:, keep], vel[:, keep])
        n_t = ts.size
        top = top.reshape(n_t)
        length = length.reshape(n_t)
        tens = tens.T
        nodes = np.empty((n_t, self.n + 1, 3))
        nodes[:, :, 0] = sc.top_position[0]
        nodes[:, :, 1] = sc.top_position[1]
        nodes[:, :, 2] = z_nodes.T
        velocities = np.zeros_like(nodes)
        velocities[:, :, 2] = vel.T
        min_t = float(min(tmin, np.min(tens)))
        e, where = slack_element(t_slack, e_slack, ts, length, self.n)
        slack, status, message = slack_report(
            t_slack, e, where, status=status, message=message, on_slack=sim.on_slack,
            template=SLACK_MESSAGE,
            continued="the run continued with the linear model (tensions < 0 after that are "
                      "not physical)")
        if status == "solved":
            message = f"{sim.steps} steps of {dt:g} s ({sim.scheme}), {self.n} elements"
        warnings = []
        tm_ = sc.top_motion
        if tm_.ramp_time == 0.0:
            jump = abs(tm_.payout_speed) + abs(tm_.heave_amplitude * tm_.heave_frequency)
            warnings += full_speed_start_warnings(jump, self.mu, self.ea,
                                                  self.unit_weight + self.w * self.length0)
        warnings += coarse_step_warnings(dt, (("heave_frequency", tm_.heave_frequency),
                                              ("payout_frequency", tm_.payout_frequency)))
        diagnostics = {
            "build_time_s": build_time,
            "steps": sim.steps,
            "elements": self.n,
            "max_scaled_residual": rmax,
            "tolerance": sim.tolerance,
            "start": sim.start,
            "static_top_tension_N": self.unit_weight + self.w * self.length0,
            "wall_time_per_simulated_second": wall / ts[-1] if n_t > 1 else None,
        }
        return SimulationResult.from_nodes(
            nodes, t=ts, length=length, top_tension=top, segment_tensions=tens,
            min_tension=min_t, slack=slack, status=status, message=message, warnings=warnings,
            wall_time_s=wall, model="axial", scheme=sim.scheme, diagnostics=diagnostics,
            node_velocities=velocities)

    # ------------------------------------------------------------------ modes
    def matrices(self, length: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Lumped mass matrix M (kg, diagonal) and stiffness K (N/m) of the free nodes
        0..N-1 about the static state at ``length`` (m), top node fixed. Drag is quadratic
        in the velocity, so it adds no linear damping about rest; the internal damping
        is left out (undamped modes)."""
        length = self.length0 if length is None else length
        n = self.n
        h = length / n
        k = np.full(n, self.ea / h)
        if self.table is not None:  # the tangent EA(e) of each element at rest
            t_el = self.unit_weight + self.w * h * (np.arange(n) + 0.5)
            k = self.table.tangent(self.table.invert(t_el)) / h
        elif self.solid is not None:  # vibration much faster than 1 / tau: EA_d
            k = np.full(n, self.solid.dynamic_stiffness / h)
        mass = np.full(n, self.mu * h)
        mass[0] = self.unit_mass + 0.5 * self.mu * h
        stiff = np.zeros((n, n))
        for e in range(n):  # element e joins nodes e and e+1 (node n is fixed)
            stiff[e, e] += k[e]
            if e + 1 < n:
                stiff[e + 1, e + 1] += k[e]
                stiff[e, e + 1] -= k[e]
                stiff[e + 1, e] -= k[e]
        return np.diag(mass), stiff

    def modes(self, count: int) -> ModesResult:
        """Undamped axial modes about the static state: K v = omega^2 M v."""
        m, k = self.matrices()
        count = min(count, self.n)
        vals, vecs = scipy.linalg.eigh(k, m, subset_by_index=[0, count - 1])
        freqs = np.sqrt(np.clip(vals, 0.0, None))
        shapes = np.zeros((count, self.n + 1, 3))
        for j in range(count):
            v = vecs[:, j]
            big = v[np.argmax(np.abs(v))]
            shapes[j, :-1, 2] = v / big
        s = np.arange(self.n + 1) * self.length0 / self.n
        z, _ = static_profile(self.scene, s)
        nodes = np.zeros((self.n + 1, 3))
        nodes[:, 0] = self.scene.top_position[0]
        nodes[:, 1] = self.scene.top_position[1]
        nodes[:, 2] = z
        return ModesResult(frequencies=freqs, shapes=shapes, node_positions=nodes,
                           length=self.length0, model="axial",
                           message=f"{count} axial modes, {self.n} elements",
                           diagnostics={"elements": self.n,
                                        "unit_virtual_mass_kg": self.unit_mass,
                                        "cable_virtual_mass_per_length_kg_m": self.mu})
