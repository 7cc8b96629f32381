"""Planar (two-dimensional) dynamics of a cable with a varying length.

Huang (1992), ch. 4: the cable and its subsea unit move in a vertical plane, swung out of
the vertical by a current in that plane and by the top's vertical, horizontal or circular
motion, while cable is paid out or hauled in at the top.

Equations (z up, the plane is x-z; s the unstretched arc length from the unit, end_a,
s = 0, to the top, end_b, s = L(t); r(s, t) = (x, z) the position of material point s;
e = |r_s| - 1 the strain, t = r_s / |r_s| the unit tangent)::

    (m I + A(t)) r_tt = (T t)_s - w k + (1 + e) f_D(U(z) - r_t, t),   T = T(e) + c e_t
    (M I + M_a) r_tt(0, t) = T t (0, t) - W k + D(U(z) - r_t)              (the unit)
    r(L(t), t) = r_b(t)                                                   (the top)

m the mass per length, A = m_an (I - t t^T) + m_at t t^T the direction-dependent added
mass (normal m_an = C_a rho pi d^2 / 4, tangential m_at, Huang (1992) (5.2)), w the
weight in water per length, f_D the drag per stretched length with the normal and
tangential parts 1/2 rho C_n d |u_n| u_n + 1/2 rho C_t pi d |u_t| u_t of the flow relative
to the cable, U(z) the current (in the plane), c the internal damping; M, M_a = diag(M_ax,
M_az), W, D the unit's mass, added mass, weight in water and drag (Huang's (4.11)-(4.12):
per axis, D_k = 1/2 rho C_Dk S_k |u_k| u_k, when the scene gives per-axis lists; else the
vector law 1/2 rho C_D S |u| u). This is Huang's (4.1) with the boundary conditions of
4.4.1 written in z-up axes for material points (Huang's ch. 4 has y downwards, the top at
s = 0 and displacements p, q from the unstrained vertical line; (4.2)-(4.3) are (4.1)
expanded with T = EA e). Where it differs from the printed equations, deliberately:

* added mass normal and tangential to the cable, as Huang's (5.2) (rotation invariant),
  where (4.2)-(4.3) write per-axis m_ap, m_aq (the same for a vertical line only);
* drag per stretched length (the factor 1 + e, the convention of Huang's (2.46) and of the
  lumped-mass model), where (4.1) has sqrt(1 + e) (a diameter shrinking at constant
  volume, Huang's (12.2)): a relative change of order the strain;
* no compression: T(e) = (EA e + sqrt((EA e)^2 + delta_T^2)) / 2 (delta_T = 0.01 N), the
  smooth no-compression law of the lumped-mass model. Huang's (4.2)-(4.3) use T = EA e
  "e >= 0" and predict negative tensions (4.5.1); a string in compression is ill-posed
  (its transverse stiffness is negative), so with ``on_slack = "continue"`` a slack
  element here carries no load and the model follows the slack cable approximately.

Fixed-domain transformation (Huang's 4.4.3, measured here from the unit): y = s / L(t) in
[0, 1], R(y, t) = r(yL, t) and the material velocity V(y, t) = r_t(yL, t); with
a(y, t) = y L_t / L the chain rule gives::

    R_t = V + a R_y
    (m I + A) (V_t - a V_y) = (T t)_y / L - w k + (1 + e) f_D,     e = |R_y| / L - 1

with R = r_b and V = r_b' - L_t R_y / L at y = 1 (the material passing the top leaves
along the cable's tangent). The state is stored relative to the unstretched line hanging
straight down from the current top, R_ref(y, t) = (x_b(t), z_b(t) - L(t) (1 - y)): the
element vectors R_{i+1} - R_i = (0, L/N) + (q_{i+1} - q_i) then carry no round-off from
the absolute heights.

A line of ``[[cable.segments]]`` whose joints fall on the grid's nodes has each element's
own properties (:mod:`cable_ocp.dynamics.planar_line`; no pay-out then), and bending
stiffness adds the hinge forces of :mod:`cable_ocp.dynamics.bending_terms`.

Space: lumped-mass finite differences on the uniform grid y_i = i / N, as the axial model
(:mod:`cable_ocp.dynamics.axial`): node i carries half of each adjacent element's mass
and added mass, element tensions act along the element chords, drag acts on each element
at its mean velocity (half to each end node). At fixed length this is exactly Huang's ch. 5
lumped-mass chain restricted to the plane, so the two agree to the Newton tolerance; the
undamped semi-discrete system is Hamiltonian, and the modes are a symmetric generalised
eigenproblem. The pay-out (advection) terms a R_y and a V_y use central differences, at
the top a one-sided second-order difference.

Time: the implicit midpoint rule with a discrete-gradient tension (the energy-momentum
method of Simo & Tarnow (1992), Gonzalez (1996)): the element force is the mean of T over
[e_0, e_1] (:func:`cable_ocp.physics.elasticity.mean_material_tension`: exact from the strain
energy for the linear law, across the no-compression kink when an element goes slack or
taut; 3-point Gauss for a tension-strain table) along
(d_0 + d_1) / (|d_0| + |d_1|), so that an undamped run in
air conserves the discrete energy to the Newton tolerance, at any time step (A-stable,
symplectic for the linear part, no numerical damping). The kinematic equation is
eliminated (V_m = (R_1 - R_0) / dt - a R_y,m), the step is a Newton ``rootfinder`` in the
2N new positions (sparse LU, exact Jacobian), folded over an output interval and
``mapaccum``'d in chunks: no Python runs per step; one call per chunk drives the progress
hook.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.dynamics.bending_terms import LineBending
from cable_ocp.dynamics.checks import check_planar
from cable_ocp.dynamics.driven import planar_driven_step
from cable_ocp.dynamics.model import DrivenStep
from cable_ocp.dynamics.planar_line import PlanarLine
from cable_ocp.dynamics.result import (
    ModesResult,
    SimulationResult,
    coarse_step_warnings,
    full_speed_start_warnings,
    slack_element,
    slack_report,
    until_slack,
)
from cable_ocp.dynamics.snap import dropped_message, snap_report
from cable_ocp.dynamics.stepping import chunk_functions, halving, run_chunks
from cable_ocp.errors import CableOCPError
from cable_ocp.physics.added_mass import added_mass_per_length, line_added_mass_2d
from cable_ocp.physics.current import profile_velocity
from cable_ocp.physics.drag import line_drag_factors, point_drag
from cable_ocp.physics.elasticity import (
    SLACK_SMOOTHING,
    cable_material,
    mean_material_switch,
    mean_material_tension,
    smooth_positive,
)
from cable_ocp.scene.dynamics import DynamicScene
from cable_ocp.scene.motion import motion_function

__all__ = ["SLACK_MESSAGE", "PlanarModel", "check_planar"]

#: the planar model's slack message (:func:`cable_ocp.dynamics.result.slack_report`)
SLACK_MESSAGE = ("slack: tension <= 0 first at t = {t:.6g} s in element {segment} (s = "
                 "{location:.4g} m from end_a; Huang's (4.2)-(4.3) predict slack but cannot "
                 "follow it, 4.5.1): {action}; the Hooke's-law tension EA e reached "
                 "{hooke:.4g} N")

class PlanarModel:
    """The discretised planar model of one scene (see the module docstring).

    Parameters
    ----------
    scene : DynamicScene
        A planar scene (:func:`check_planar`).
    segments : int, optional
        Number of elements N (default ``simulation.segments``).

    Attributes
    ----------
    n : int
        Number of elements (nodes 0..N, node N the top).
    free : list of int
        The free nodes: 0..N-1 with a unit, 1..N-1 with an anchored end_a.

    The model implements :class:`cable_ocp.dynamics.model.CableModel`.
    """

    #: the scene's ``simulation.model`` of this model
    name = "planar"

    #: symbols that :attr:`motion` reads besides the time (None: a function of time only):
    #: the driven step (:mod:`cable_ocp.dynamics.driven`) sets them, and
    #: :meth:`output_function` takes them as its last input
    motion_params: Any = None

    def __init__(self, scene: DynamicScene, segments: int | None = None) -> None:
        check_planar(scene)
        self.scene = scene
        st = scene.statics
        cab = st.cable
        dyn = scene.cable[0]
        env = st.environment
        rho = env.water_density
        self.n = int(segments or scene.simulation.segments)
        self.anchored = scene.unit is None
        self.free = list(range(1 if self.anchored else 0, self.n))
        self.nf = len(self.free)
        if self.nf == 0:
            raise CableOCPError("simulation.segments = 1 with an anchored end_a leaves no "
                                "free node: give at least 2")
        self.mu = dyn.mass_per_length
        # normal and tangential added mass, kg/m (Huang (1992) (5.2))
        self.man = added_mass_per_length(dyn.added_mass_coefficient, rho, cab.diameter)
        self.mat = added_mass_per_length(dyn.tangential_added_mass_coefficient, rho,
                                         cab.diameter)
        self.w = float(cab.weight_in_water)
        self.ea = float(cab.axial_stiffness)
        self.c = float(dyn.axial_damping)
        self.kn, self.kt = line_drag_factors(rho, cab.diameter, cab.normal_drag,
                                             cab.tangential_drag)
        #: per-element properties of a line of segments (:mod:`cable_ocp.dynamics.planar_line`)
        self.line = PlanarLine(scene, self.n)
        self.delta = st.solver.smoothing
        self.delta_t = SLACK_SMOOTHING
        #: the tension law (linear or a tension-strain table, physics.elasticity)
        self.table = cab.strain_table
        if self.table is not None and not self.line.uniform:
            raise CableOCPError("cable.tension_strain: the planar model takes a tension-strain "
                                "table on a line of one segment only (valid: one "
                                "[[cable.segments]] entry, or axial_stiffness per segment)")
        self.material = cable_material(self.line.value("ea"), self.table,
                                       slack_smoothing=self.delta_t)
        self.rho = rho
        self.length0 = scene.length
        #: the hinges of a line with bending stiffness (:mod:`cable_ocp.dynamics.bending_terms`)
        self.bending = LineBending.from_scene(scene, np.full(self.n, self.length0 / self.n))
        self.top0 = np.array([scene.top_position[0], scene.top_position[2]], dtype=float)
        self.y_plane = float(scene.top_position[1])
        unit = scene.unit
        if unit is not None:
            self.unit_mass = (unit.virtual_mass[0], unit.virtual_mass[2])
            self.unit_weight = unit.weight_in_water
            self.unit_cs = (unit.drag_area[0] * unit.drag_coefficient[0],
                            unit.drag_area[2] * unit.drag_coefficient[2])
            self.unit_per_axis = unit.drag_per_axis
            self.anchor = None
        else:
            self.unit_mass = (0.0, 0.0)
            self.unit_weight = 0.0
            self.unit_cs = (0.0, 0.0)
            self.unit_per_axis = False
            pa = st.end_a.position
            self.anchor = (float(pa[0]), float(pa[2]))  # type: ignore[arg-type]
        cur = env.current
        self.current = cur
        self.motion = motion_function(scene)
        self.gravity = env.gravity
        weight = abs(self.unit_weight) + float(np.mean(np.abs(self.line.rows["w"]))
                                                 ) * self.length0
        #: force scale of the Newton residuals, N: the total weight in water (>= 1 N),
        #: raised to the largest static tension by :meth:`initial_state`
        self.force_scale = max(weight, 1.0)
        #: a strain below -slack_strain is slack: a tension EA e below -1e-9 of the static
        #: top weight, clear of round-off where a line released unstretched carries no load
        self.slack_strain = 1e-9 * max(weight, 1.0) / float(np.min(self.line.rows["ea"]))

    # ------------------------------------------------------------------ pieces
    def _tension(self, eps: Any) -> Any:
        """Smooth no-compression tension law, N (elementwise; the material's
        :meth:`~cable_ocp.physics.elasticity.AxialMaterial.tension`)."""
        return self.material.tension(eps)

    def _taut(self, eps: Any) -> Any:
        """Smooth switch 0 (slack) .. 1 (taut), - (elementwise; the material's
        :meth:`~cable_ocp.physics.elasticity.AxialMaterial.taut`)."""
        return self.material.taut(eps)

    # The expressions below work on 2 x K matrices (columns = nodes or elements, rows =
    # x, z): a few dozen whole-matrix operations per expression, whatever N is.

    def _current(self, z: Any) -> Any:
        """Current (u_x, u_z) at the heights of the row z (1 x K), m/s, 2 x K."""
        k = z.shape[1]
        if self.current is None:
            return ca.SX.zeros(2, k)
        if self.current.uniform:
            return ca.repmat(ca.vertcat(self.current.ux[0], 0.0), 1, k)
        zs = ca.SX.sym("z")
        cur = self.current
        fn = ca.Function("current_x", [zs], [profile_velocity(zs, cur.z, cur.ux, cur.uy)[0]])
        return ca.vertcat(fn.map(k)(z), ca.SX.zeros(1, k))

    def _motion(self, t: Any) -> dict[str, Any]:
        length, dl, ddl, xb, vb, ab = self.motion(t)
        return {"L": length, "Lt": dl, "Ltt": ddl, "xb": ca.vertcat(xb[0], xb[2]),
                "vb": ca.vertcat(vb[0], vb[2]), "ab": ca.vertcat(ab[0], ab[2])}

    def _offsets(self, q: Any, mo: dict[str, Any]) -> Any:
        """Offsets Q = R - R_ref of every node (2 x (N+1), m): the free nodes' from q, the
        top's zero, the anchor's from its fixed position."""
        cols = [ca.reshape(q, 2, self.nf), ca.SX.zeros(2, 1)]
        if self.anchored:
            xa, za = self.anchor  # type: ignore[misc]
            cols.insert(0, ca.vertcat(xa - mo["xb"][0], za - mo["xb"][1] + mo["L"]))
        return ca.horzcat(*cols)

    @staticmethod
    def _elements(qq: Any, h: Any) -> Any:
        """Element vectors d_j = R_{j+1} - R_j (2 x N, m)."""
        dq = qq[:, 1:] - qq[:, :-1]
        return ca.vertcat(dq[0, :], h + dq[1, :])

    def _heights(self, qq: Any, mo: dict[str, Any]) -> Any:
        """Absolute node heights (1 x (N+1), m)."""
        y = ca.DM(np.arange(self.n + 1) / self.n).T
        return mo["xb"][1] - mo["L"] * (1.0 - y) + qq[1, :]

    def _tangent_y(self, dd: Any) -> Any:
        """R_y at the nodes from element vectors (2 x (N+1), m): central differences
        inside, one-sided second order at the top, zero at node 0 (where y = 0)."""
        n, dy = self.n, 1.0 / self.n
        if n >= 2:
            top = (3.0 * dd[:, n - 1] - dd[:, n - 2]) / (2.0 * dy)
            inner = (dd[:, :-1] + dd[:, 1:]) / (2.0 * dy)
            return ca.horzcat(ca.SX.zeros(2, 1), inner, top)
        return ca.horzcat(ca.SX.zeros(2, 1), dd[:, 0] / dy)

    @staticmethod
    def _norms(dd: Any) -> Any:
        return ca.sqrt(ca.sum1(dd * dd))

    def _element_drag(self, dd: Any, urel: Any) -> Any:
        """Drag on the elements of chords dd (m) in the relative flows urel (m/s), N
        (2 x N): per stretched length |d| times the vector law
        (:func:`cable_ocp.physics.drag.vector_drag_columns`)."""
        k = dd.shape[1]
        if not (np.any(self.line.rows["kn"]) or np.any(self.line.rows["kt"])):
            return ca.SX.zeros(2, k)
        ll = self._norms(dd)
        tt = dd / ca.repmat(ll, 2, 1)
        f = self.line.drag(urel, tt, self.delta)
        return ca.repmat(ll, 2, 1) * f

    def _unit_drag(self, z0: Any, v0: Any) -> Any:
        """The unit's drag (2 x 1, N) at height z0 and velocity v0."""
        if self.anchored or not any(self.unit_cs):
            return ca.SX.zeros(2, 1)
        u = self._current(z0) - v0
        return point_drag(u, self.unit_cs, rho=self.rho, delta=self.delta,
                          per_axis=self.unit_per_axis)

    def _share(self) -> np.ndarray:
        """Share of an element length lumped at each node (1/2 at the ends)."""
        c = np.ones(self.n + 1)
        c[[0, -1]] = 0.5
        return c

    def _mass_rows(self, dd: Any, h: Any) -> tuple[Any, Any, Any]:
        """Mass blocks [[m_xx, m_xz], [m_xz, m_zz]] of every node (three 1 x (N+1) rows,
        kg): half of each adjacent element's mass and added mass (normal and tangential
        to its chord), plus the unit's."""
        n = self.n
        base = h * self.line.nodes("mu")
        mxx, mxz, mzz = base, ca.SX.zeros(1, n + 1), base
        if np.any(self.line.rows["man"]) or np.any(self.line.rows["mat"]):
            axx, axz, azz = line_added_mass_2d(dd, self.line.value("man"),
                                               self.line.value("mat"), 0.5 * h)
            z1 = ca.SX.zeros(1, 1)
            mxx = mxx + ca.horzcat(axx, z1) + ca.horzcat(z1, axx)
            mxz = mxz + ca.horzcat(axz, z1) + ca.horzcat(z1, axz)
            mzz = mzz + ca.horzcat(azz, z1) + ca.horzcat(z1, azz)
        if not self.anchored:
            unit = np.zeros((2, n + 1))
            unit[:, 0] = self.unit_mass
            mxx = mxx + ca.DM(unit[0]).T
            mzz = mzz + ca.DM(unit[1]).T
        return mxx, mxz, mzz

    def _weights(self, h: Any) -> Any:
        """Weights in water at the nodes (2 x (N+1), N; z negative)."""
        wz = h * self.line.nodes("w")
        if not self.anchored:
            unit = np.zeros(self.n + 1)
            unit[0] = self.unit_weight
            wz = wz + ca.DM(unit).T
        return ca.vertcat(ca.SX.zeros(1, self.n + 1), -wz)

    @staticmethod
    def _spread(fe: Any) -> Any:
        """Element forces (2 x N) acting +fe on node j and -fe on node j+1."""
        z = ca.SX.zeros(2, 1)
        return ca.horzcat(fe, z) - ca.horzcat(z, fe)

    @staticmethod
    def _halves(fe: Any) -> Any:
        """Element loads (2 x N) shared half and half by their end nodes."""
        z = ca.SX.zeros(2, 1)
        return 0.5 * (ca.horzcat(fe, z) + ca.horzcat(z, fe))

    def _free_cols(self, mat: Any) -> Any:
        return mat[:, 1:self.n] if self.anchored else mat[:, 0:self.n]

    # ------------------------------------------------------------------ the step
    def _step_expressions(self, dt: float) -> tuple[Any, ...]:
        """Symbols and expressions of one midpoint step (see the module docstring)."""
        n, nf = self.n, self.nf
        dy = 1.0 / n
        q1 = ca.SX.sym("q1", 2 * nf)
        q0 = ca.SX.sym("q0", 2 * nf)
        v0 = ca.SX.sym("v0", 2 * nf)
        t0 = ca.SX.sym("t0")
        m0, m1, mm = self._motion(t0), self._motion(t0 + dt), self._motion(t0 + 0.5 * dt)
        h0, h1, hm = m0["L"] / n, m1["L"] / n, mm["L"] / n
        qa, qb = self._offsets(q0, m0), self._offsets(q1, m1)
        d0, d1 = self._elements(qa, h0), self._elements(qb, h1)
        dm = 0.5 * (d0 + d1)
        y = ca.DM(np.arange(n + 1) / n).T
        adv = ca.repmat(y * mm["Lt"] / mm["L"], 2, 1)  # a = y L_t / L
        # midpoint material velocities of every node: R_1 - R_0 = dt (V_m + a R_y,m)
        dxb = m1["xb"] - m0["xb"]
        dlen = m1["L"] - m0["L"]
        dref = ca.vertcat(ca.repmat(dxb[0], 1, n + 1), dxb[1] - dlen * (1.0 - y))
        vm = (dref + qb - qa) / dt - adv * self._tangent_y(dm)
        # discrete-gradient tension (mean of T over [e0, e1] along (d0 + d1)/(l0 + l1))
        l0, l1 = self._norms(d0), self._norms(d1)
        e0, e1 = l0 / h0 - 1.0, l1 / h1 - 1.0
        tbar = mean_material_tension(self.material, e0, e1)
        u = (d0 + d1) / ca.repmat(l0 + l1, 2, 1)
        if np.any(self.line.rows["c"] > 0.0):
            rate = ca.sum1(u * (vm[:, 1:] - vm[:, :-1])) / hm
            switch = mean_material_switch(self.material, e0, e1)
            tbar = smooth_positive(tbar + self.line.value("c") * rate * switch, self.delta_t)
        force = self._spread(ca.repmat(tbar, 2, 1) * u)
        force = force + self.bending.node_forces(dm, mm["L"] / self.length0)
        # drag at the mean positions with the midpoint velocities
        zm = 0.5 * (self._heights(qa, m0) + self._heights(qb, m1))
        urel = (self._current(0.5 * (zm[:, :-1] + zm[:, 1:]))
                - 0.5 * (vm[:, :-1] + vm[:, 1:]))
        force = force + self._halves(self._element_drag(dm, urel))
        if not self.anchored:
            force = force + ca.horzcat(self._unit_drag(zm[:, 0], vm[:, 0]),
                                       ca.SX.zeros(2, n))
        force = force + self._weights(hm)
        mxx, mxz, mzz = self._mass_rows(dm, hm)
        # material accelerations (V_t - a V_y) of the free nodes
        vv0 = ca.reshape(v0, 2, nf)
        v1 = 2.0 * self._free_cols(vm) - vv0
        vy = ca.horzcat(ca.SX.zeros(2, 1), (vm[:, 2:] - vm[:, :-2]) / (2.0 * dy),
                        ca.SX.zeros(2, 1))  # V_y inside (a = 0 at node 0; the top is given)
        acc = (v1 - vv0) / dt - self._free_cols(adv * vy)
        fm = self._free_cols
        res = ca.vertcat(fm(mxx) * acc[0, :] + fm(mxz) * acc[1, :] - fm(force)[0, :],
                         fm(mxz) * acc[0, :] + fm(mzz) * acc[1, :] - fm(force)[1, :])
        # predictor: q_t = V + a R_y - R_ref_t at t0, one explicit Euler step
        vref = ca.vertcat(ca.repmat(m0["vb"][0], 1, n + 1), m0["vb"][1] - m0["Lt"] * (1.0 - y))
        adv0 = ca.repmat(y * m0["Lt"] / m0["L"], 2, 1)
        rate0 = self._free_cols(adv0 * self._tangent_y(d0) - vref) + vv0
        pred = q0 + dt * ca.vec(rate0)
        return (q1, q0, v0, t0, ca.vec(res) / self.force_scale, ca.vec(v1), e1.T, pred)

    def step_function(self, dt: float, tol: float, max_iter: int) -> ca.Function:
        """One step as a CasADi function ``(acc, t0) -> acc``.

        ``acc`` stacks the offsets q (2 n_free), the material velocities V (2 n_free), the
        largest scaled Newton residual so far, the smallest element strain so far, the
        time of the first slack strain (s, inf if none) and that element's index.

        Parameters
        ----------
        dt : float
            Time step, s.
        tol : float
            Newton tolerance on the scaled residual (-).
        max_iter : int
            Newton iterations allowed per step.
        """
        q1, q0, v0, t0, res, v1, eps1, pred = self._step_expressions(dt)
        nf2 = 2 * self.nf
        p = ca.vertcat(q0, v0, t0)
        guess = ca.Function("guess", [p], [pred])
        rf = ca.rootfinder("rf", "newton", {"x": q1, "p": p, "g": res},
                           {"abstol": tol, "abstolStep": 1e-14 * tol, "max_iter": max_iter,
                            "error_on_fail": False})
        post = ca.Function("post", [q1, p], [v1, ca.norm_inf(res), eps1])
        acc = ca.MX.sym("acc", 2 * nf2 + 4)
        tm = ca.MX.sym("t")
        qa, va = acc[:nf2], acc[nf2:2 * nf2]
        pv = ca.vertcat(qa, va, tm)
        qn = rf(guess(pv), pv)
        vn, r, eps = post(qn, pv)
        emin_step = ca.mmin(eps)
        rmax, emin, t_slack, e_slack = (acc[2 * nf2 + k] for k in range(4))
        idx = ca.DM(np.arange(self.n, dtype=float))
        is_min = eps <= emin_step
        e_now = ca.dot(idx, is_min) / ca.sum1(is_min)
        first = ca.logic_and(emin_step <= -self.slack_strain, t_slack > 1e300)
        new = [qn, vn,
               ca.fmax(rmax, ca.if_else(r <= 1e300, r, ca.inf)),  # a NaN residual -> inf
               ca.fmin(emin, emin_step),
               ca.if_else(first, tm + dt, t_slack),
               ca.if_else(first, e_now, e_slack)]
        return ca.Function("step", [acc, tm], [ca.vertcat(*new)])

    # ------------------------------------------------------------------ outputs
    def output_function(self) -> ca.Function:
        """``(t, q, V) -> (node positions (2, N+1), element tensions (N), top tension,
        L, node velocities (2, N+1), strains (N))`` (m, N, N, m, m/s, -); with
        :attr:`motion_params` set, ``(t, q, V, p)``."""
        n = self.n
        t = ca.SX.sym("t")
        q = ca.SX.sym("q", 2 * self.nf)
        v = ca.SX.sym("v", 2 * self.nf)
        mo = self._motion(t)
        extra = [] if self.motion_params is None else [self.motion_params]
        h = mo["L"] / n
        qq = self._offsets(q, mo)
        dd = self._elements(qq, h)
        y = ca.DM(np.arange(n + 1) / n).T
        rs = ca.vertcat(mo["xb"][0] + qq[0, :], mo["xb"][1] - mo["L"] * (1.0 - y) + qq[1, :])
        ry_top = self._tangent_y(dd)[:, n]
        cols = [ca.reshape(v, 2, self.nf), mo["vb"] - mo["Lt"] * ry_top / mo["L"]]
        if self.anchored:
            cols.insert(0, ca.SX.zeros(2, 1))
        vs = ca.horzcat(*cols)
        ll = self._norms(dd)
        eps = ll / h - 1.0
        tens = self._tension(eps)
        if np.any(self.line.rows["c"] > 0.0):
            rate = ca.sum1(dd / ca.repmat(ll, 2, 1) * (vs[:, 1:] - vs[:, :-1])) / h
            tens = smooth_positive(tens + self.line.value("c") * rate * self._taut(eps),
                                   self.delta_t)
        # the top: node N's balance, M_N a_N - (cable, weight, drag); a_N the material
        # acceleration a_b - L_tt R_y / L (the turning of the top tangent neglected)
        zs = rs[1, :]
        d_top = dd[:, n - 1]
        f_n = -tens[n - 1] * d_top / ll[n - 1] + self._weights(h)[:, n]
        f_n = f_n + self.bending.node_forces(dd, mo["L"] / self.length0)[:, n]
        urel = (self._current(0.5 * (zs[:, n - 1] + zs[:, n]))
                - 0.5 * (vs[:, n - 1] + vs[:, n]))
        f_n = f_n + 0.5 * self._element_drag(d_top, urel)
        a_n = mo["ab"] - mo["Ltt"] * ry_top / mo["L"]
        mxx, mxz, mzz = (r[n] for r in self._mass_rows(dd, h))
        inert = ca.vertcat(mxx * a_n[0] + mxz * a_n[1], mxz * a_n[0] + mzz * a_n[1])
        top = ca.norm_2(inert - f_n)
        return ca.Function("outputs", [t, q, v, *extra],
                           [rs, tens.T, top, mo["L"], vs, eps.T])

    # ------------------------------------------------------------------ statics
    def _static_function(self, with_drag: bool = True, linear: bool = False) -> ca.Function:
        """``q -> (F, dF/dq)``: the nodal forces (N) at rest at t = 0 (every node at rest,
        the current's drag included if ``with_drag``; ``linear``: Hooke's law EA e in
        tension and compression)."""
        n = self.n
        q = ca.SX.sym("q", 2 * self.nf)
        mo = self._motion(0.0)
        h = self.length0 / n
        qq = self._offsets(q, mo)
        dd = self._elements(qq, h)
        ll = self._norms(dd)
        eps = ll / h - 1.0
        tens = (self.line.value("ea") * eps if self.table is None
                else self.table.tension_of(eps)) if linear else self._tension(eps)
        force = self._spread(ca.repmat(tens / ll, 2, 1) * dd) + self.bending.node_forces(dd)
        if with_drag:
            zs = self._heights(qq, mo)
            force = force + self._halves(self._element_drag(
                dd, self._current(0.5 * (zs[:, :-1] + zs[:, 1:]))))
            if not self.anchored:
                force = force + ca.horzcat(self._unit_drag(zs[:, 0], ca.SX.zeros(2, 1)),
                                           ca.SX.zeros(2, n))
        f = ca.vec(self._free_cols(force + self._weights(h)))
        return ca.Function("static", [q], [f, ca.jacobian(f, q)])

    def _mass_function(self) -> ca.Function:
        """``q -> M``: the free nodes' mass matrix at rest at t = 0 (kg, 2 n_free)."""
        q = ca.SX.sym("q", 2 * self.nf)
        h = self.length0 / self.n
        dd = self._elements(self._offsets(q, self._motion(0.0)), h)
        rows = [self._free_cols(r) for r in self._mass_rows(dd, h)]
        blocks = [ca.vertcat(ca.horzcat(rows[0][k], rows[1][k]),
                             ca.horzcat(rows[1][k], rows[2][k])) for k in range(self.nf)]
        return ca.Function("mass", [q], [ca.diagcat(*blocks)])

    def static_equilibrium(self, q_guess: np.ndarray, tol: float = 1e-12,
                           max_iter: int = 80) -> tuple[np.ndarray, dict[str, Any]]:
        """Rest state of the discrete model at t = 0 by damped Newton from ``q_guess``
        (offsets, m): the nodal forces below ``tol`` times the force scale.

        Where the guess has compressed elements (the chords of a strongly curved, lightly
        loaded stretch are shorter than the arc: the statics solution interpolated at the
        nodes), the no-compression law gives them no stiffness; Hooke's law in tension
        and compression is solved first from there, then the model's own law.

        Parameters
        ----------
        q_guess : numpy.ndarray
            Start: the free nodes' offsets from the unstretched line hanging from end_b, m,
            node-major (x, z) pairs.
        tol : float
            Tolerance on the nodal forces, times the force scale (-).
        max_iter : int
            Newton iterations allowed (each solve).
        """
        q = np.asarray(q_guess, dtype=float).copy()
        eps = np.asarray(self._strain_function()(q)).ravel()
        its = 0
        if np.any(eps <= 0.0):
            q_lin, info = self._newton(self._static_function(linear=True), q, tol, max_iter)
            its = info["iterations"]
            if info["converged"]:
                q = q_lin
        q, info = self._newton(self._static_function(), q, tol, max_iter)
        info["iterations"] += its
        return q, info

    def _strain_function(self) -> ca.Function:
        q = ca.SX.sym("q", 2 * self.nf)
        h = self.length0 / self.n
        dd = self._elements(self._offsets(q, self._motion(0.0)), h)
        return ca.Function("strain", [q], [self._norms(dd) / h - 1.0])

    def _newton(self, fj: ca.Function, q: np.ndarray, tol: float, max_iter: int
                ) -> tuple[np.ndarray, dict[str, Any]]:
        """Damped Newton on the nodal forces of ``fj`` (see :meth:`static_equilibrium`)."""
        from scipy.sparse import csc_matrix
        from scipy.sparse.linalg import spsolve

        q = q.copy()

        def ev(x: np.ndarray) -> tuple[np.ndarray, Any]:
            f, j = fj(x)
            return np.asarray(f).ravel(), j

        f, jac = ev(q)
        stalled = False
        it = 0
        for it in range(1, max_iter + 1):  # noqa: B007 - reported
            if not np.all(np.isfinite(f)) or np.abs(f).max() <= tol * self.force_scale:
                it -= 1
                break
            try:
                with warnings.catch_warnings():  # a singular Jacobian: NaN, reported below
                    warnings.simplefilter("ignore")
                    dq = -spsolve(csc_matrix(jac.sparse()), f)
            except Exception:  # noqa: BLE001 - reported, never raised
                break
            if not np.all(np.isfinite(dq)):
                break
            n0 = np.linalg.norm(f)
            lam = 1.0
            while lam > 1e-6:
                fn, jn = ev(q + lam * dq)
                if np.all(np.isfinite(fn)) and np.linalg.norm(fn) < (1.0 - 1e-4 * lam) * n0:
                    break
                lam *= 0.5
            else:  # no decrease along the Newton step: the rounding floor (or a failure)
                stalled = True
                break
            q = q + lam * dq
            f, jac = fn, jn
            # the rounding floor of a stiff line: steps of 1e-13 of the length
            stalled = lam * np.abs(dq).max() <= 1e-13 * self.length0
            if stalled and np.abs(f).max() <= 1e-9 * self.force_scale:
                break
        rmax = float(np.abs(f).max()) if np.all(np.isfinite(f)) else math.inf
        ok = rmax <= tol * self.force_scale or (stalled and rmax <= 1e-9 * self.force_scale)
        return q, {"converged": bool(ok), "iterations": it, "residual_N": rmax,
                   "relative_residual": rmax / self.force_scale}

    def initial_state(self) -> tuple[np.ndarray | None, dict[str, Any]]:
        """(q, V) at t = 0 stacked, and information on how it was found.

        ``"static"``: the statics solver's solution of the scene
        (:func:`cable_ocp.dynamics.static.static_state`) interpolated at the nodes'
        unstretched arc lengths, then refined to the discrete model's own equilibrium by
        Newton, so that the run starts exactly at rest. ``"unstrained"``: hanging straight
        down from end_b, unstretched, at rest (q = 0). ``"dropped"``: straight down and
        slack, every node raised by h (1 - y) (h = ``simulation.drop_height``), at rest.
        """
        nf2 = 2 * self.nf
        info: dict[str, Any] = {"source": self.scene.simulation.start}
        if self.scene.simulation.start in ("unstrained", "dropped"):
            q = np.zeros((self.nf, 2))
            q[:, 1] = self.scene.simulation.drop_height * (
                1.0 - np.asarray(self.free, dtype=float) / self.n)
            info.update(converged=True, message=dropped_message(self.scene.simulation))
            return np.concatenate([q.ravel(), np.zeros(nf2)]), info
        from scipy.interpolate import CubicSpline

        from cable_ocp.dynamics.static import static_state

        sol = static_state(self.scene)
        info["statics_status"] = sol.status
        if not sol.success:
            info.update(converged=False, message=f"the statics solve failed: {sol.message}")
            return None, info
        s = np.asarray(sol.s, dtype=float)
        pos = np.asarray(sol.position, dtype=float)
        keep = np.concatenate([[True], np.diff(s) > 1e-12 * max(sol.length, 1.0)])
        spline = CubicSpline(s[keep], pos[keep], axis=0)
        s_nodes = np.arange(self.n + 1) * self.length0 / self.n
        guess = spline(np.clip(s_nodes, s[keep][0], s[keep][-1]))
        info["max_off_plane_m"] = float(np.abs(guess[:, 1] - self.y_plane).max())
        # the Newton residuals are scaled by the largest of the weights and the tensions
        t_max = float(np.max(np.linalg.norm(np.asarray(sol.tension_vector, float), axis=1)))
        if np.isfinite(t_max):
            self.force_scale = max(self.force_scale, t_max)
        ref_x = self.top0[0]
        ref_z = self.top0[1] - self.length0 * (1.0 - s_nodes / self.length0)
        q = np.column_stack([guess[:, 0] - ref_x, guess[:, 2] - ref_z])[self.free].ravel()
        self.bending.set_clamp(guess[-1, [0, 2]] - guess[-2, [0, 2]])
        qe, newton = self.static_equilibrium(q)
        shift = float(np.abs(qe - q).max())
        info.update(converged=newton["converged"], iterations=newton["iterations"],
                    relative_residual=newton["relative_residual"], max_node_shift_m=shift,
                    statics_wall_time_s=sol.wall_time_s)
        if not newton["converged"]:
            info["message"] = ("the discrete equilibrium did not converge from the statics "
                               f"solution (relative residual {newton['relative_residual']:.3g})")
            return None, info
        info["message"] = (f"statics solution refined to the discrete equilibrium (largest "
                           f"node shift {shift:.3g} m)")
        return np.concatenate([qe, np.zeros(nf2)]), info

    # ------------------------------------------------------------------ simulate
    def simulate(self, progress: Callable[[int, int], None] | None = None,
                 state: np.ndarray | None = None) -> SimulationResult:
        """Integrate over ``simulation.duration`` from the static state (or ``state``).

        Parameters
        ----------
        progress : callable, optional
            Called as ``progress(done, total)`` with output samples done, a bounded number
            of times; the library never prints.
        state : numpy.ndarray, optional
            The initial (q, V) stacked (offsets from the unstretched line hanging from
            end_b, m, and material velocities, m/s, of the free nodes, node-major (x, z)
            pairs), instead of ``simulation.start``.
        """
        sc = self.scene
        sim = sc.simulation
        dt = sim.time_step
        every = sim.output_every
        n_out = sim.steps // every
        nf2 = 2 * self.nf
        if state is None:
            x0, info = self.initial_state()
            if x0 is None:
                return self._failed(info)
        else:
            x0 = np.asarray(state, dtype=float).reshape(-1)
            if x0.size != 2 * nf2:
                raise CableOCPError(f"state: expected {2 * nf2} numbers (q and V of "
                                    f"{self.nf} free nodes), got {x0.size}")
            info = {"source": "given", "converged": True, "message": "the given state"}
            eps = np.asarray(self._strain_function()(x0[:nf2])).ravel()
            self.force_scale = max(self.force_scale, self.ea * float(np.max(eps)))
        t_build = time.perf_counter()
        chunk_fn, per_chunk = chunk_functions(
            self.step_function(dt, sim.tolerance, sim.max_iterations), every, n_out)
        post = self.output_function()
        build_time = time.perf_counter() - t_build
        eps0 = float(np.min(np.asarray(post(0.0, x0[:nf2], x0[nf2:])[5])))
        acc = np.concatenate([x0, [0.0, eps0, np.inf, -1.0]])
        tol_fail = max(1e3 * sim.tolerance, 1e-6)
        off = 2 * nf2
        stats: dict[str, Any] = {}
        ts, xs, acc, status, message, wall = run_chunks(
            chunk_fn, acc, n_out, per_chunk, every, dt, off, off, tol_fail,
            sim.on_slack == "stop", progress,
            refine=halving(lambda h: self.step_function(h, sim.tolerance, sim.max_iterations),
                           dt, every), stats=stats)
        info = {**info, "step_halving": stats}
        times, states = [0.0, *ts], [x0, *xs]
        return self._result(np.asarray(times), np.stack(states, axis=1), acc[off:off + 4],
                            post, status, message, wall, build_time, info)

    def _failed(self, info: dict[str, Any]) -> SimulationResult:
        return SimulationResult.failed(
            self.n, info.get("message", "the static start failed"), "planar",
            self.scene.simulation.scheme, {"start": info})

    def _result(self, ts: np.ndarray, xs: np.ndarray, tail: np.ndarray, post: ca.Function,
                status: str, message: str, wall: float, build_time: float,
                info: dict[str, Any]) -> SimulationResult:
        sc = self.scene
        sim = sc.simulation
        dt = sim.time_step
        nf2 = 2 * self.nf
        rmax, emin, t_slack, e_slack = (float(v) for v in tail)
        n_t = ts.size
        outs = post.map(n_t)(ts.reshape(1, -1), xs[:nf2], xs[nf2:])
        pos, tens, top, length, vel, eps = (np.asarray(v) for v in outs)
        n1 = self.n + 1
        # map stacks the (2, N + 1) outputs side by side, one block per time
        pos = np.stack([pos[:, k * n1:(k + 1) * n1].T for k in range(n_t)])
        vel = np.stack([vel[:, k * n1:(k + 1) * n1].T for k in range(n_t)])
        keep = until_slack(ts, t_slack, sim.output_every * dt, sim.on_slack)
        if keep is not None:
            ts, pos, vel = ts[keep], pos[keep], vel[keep]
            tens, top, length, eps = tens[:, keep], top[:, keep], length[:, keep], eps[:, keep]
            n_t = ts.size
        nodes = np.empty((n_t, n1, 3))
        nodes[:, :, 0] = pos[:, :, 0]
        nodes[:, :, 1] = self.y_plane
        nodes[:, :, 2] = pos[:, :, 1]
        velocities = np.zeros_like(nodes)
        velocities[:, :, 0] = vel[:, :, 0]
        velocities[:, :, 2] = vel[:, :, 1]
        tens = tens.T
        top = top.reshape(n_t)
        length = length.reshape(n_t)
        min_strain = float(min(emin, np.min(eps)))
        min_t = float(min(np.min(np.asarray(self._tension(min_strain), dtype=float)),
                          np.min(tens)))
        e, where = slack_element(t_slack, e_slack, ts, length, self.n)
        slack, status, message = slack_report(
            t_slack, e, where, status=status, message=message, on_slack=sim.on_slack,
            template=SLACK_MESSAGE,
            continued="the run continued through slack: a slack element carries no tension "
                      "(the no-compression law, elastic and damping) and the lumps move "
                      "freely until the line is taut again (no bending, no contact); the "
                      "snap that ends it is in the result's snap",
            hooke=self.ea * min_strain)
        if status == "solved":
            message = f"{sim.steps} steps of {dt:g} s ({sim.scheme}), {self.n} elements"
        warnings = []
        tm_ = sc.top_motion
        if tm_.ramp_time == 0.0:
            # the top's velocity at t = 0+ (the circle starts vertically)
            jump = math.hypot(tm_.horizontal_amplitude * tm_.horizontal_frequency,
                              tm_.heave_amplitude * tm_.heave_frequency
                              + tm_.circular_radius * tm_.circular_frequency
                              ) + abs(tm_.payout_speed)
            warnings += full_speed_start_warnings(
                jump, self.mu, self.ea, abs(self.unit_weight) + abs(self.w) * self.length0)
        warnings += coarse_step_warnings(dt, (("heave_frequency", tm_.heave_frequency),
                                              ("horizontal_frequency", tm_.horizontal_frequency),
                                              ("circular_frequency", tm_.circular_frequency),
                                              ("payout_frequency", tm_.payout_frequency)))
        diagnostics = {
            "build_time_s": build_time,
            "steps": int(round(ts[-1] / dt)) if n_t else 0,
            "elements": self.n,
            "max_scaled_residual": rmax,
            "tolerance": sim.tolerance,
            "start": {k: v for k, v in info.items() if k != "step_halving"},
            "step_halving": info.get("step_halving"),
            "min_strain": min_strain,
            "min_linear_tension_N": self.ea * min_strain,
            "wall_time_per_simulated_second": wall / ts[-1] if n_t > 1 else None,
        }
        return SimulationResult.from_nodes(
            nodes, t=ts, length=length, top_tension=top, segment_tensions=tens,
            min_tension=min_t, slack=slack, status=status, message=message, warnings=warnings,
            snap=snap_report(ts, tens, (np.arange(self.n) + 0.5) / self.n * length[:, None]),
            wall_time_s=wall, model="planar", scheme=sim.scheme, diagnostics=diagnostics,
            node_velocities=velocities)

    # ------------------------------------------------------------------ the interface
    def state_size(self) -> int:
        """Offsets q and material velocities V of the free nodes: ``4 n_free``."""
        return 4 * self.nf

    def static_state(self) -> tuple[np.ndarray | None, dict[str, Any]]:
        """:meth:`initial_state`."""
        return self.initial_state()

    def driven_step(self, dt: float | None = None) -> DrivenStep:
        """The midpoint step with the top's height and the length as inputs
        (:func:`cable_ocp.dynamics.driven.planar_driven_step`; ``dt`` s, or a symbol)."""
        return planar_driven_step(self, dt)

    def linearize(self) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`matrices` about the static state.

        Raises
        ------
        CableOCPError
            When the static state failed.
        """
        x0, info = self.initial_state()
        if x0 is None:
            raise CableOCPError(info["message"])
        return self.matrices(x0[:2 * self.nf])

    # ------------------------------------------------------------------ modes
    def matrices(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Stiffness K (N/m) and mass M (kg) of the free nodes about the rest state q
        (offsets, m), dense (2 n_free square), both symmetric.

        K = -dF/dq of the tensions and weights (the current shapes the rest state and its
        tensions, but its drag is left out of K: its orientation stiffness is not
        symmetric and its velocity part is damping); M with the added mass normal and
        tangential to the chords at q.
        """
        fj = self._static_function(with_drag=False)
        k = -np.asarray(ca.densify(fj(q)[1]))
        m = np.asarray(ca.densify(self._mass_function()(q)))
        return 0.5 * (k + k.T), 0.5 * (m + m.T)

    def modes(self, count: int) -> ModesResult:
        """In-plane modes about the static state: K v = omega^2 M v."""
        from scipy.linalg import eigh

        x0, info = self.initial_state()
        n = self.n
        if x0 is None:
            return ModesResult(frequencies=np.zeros(0), shapes=np.zeros((0, n + 1, 3)),
                               node_positions=np.zeros((n + 1, 3)), length=self.length0,
                               model="planar", status="failed", message=info["message"],
                               diagnostics={"start": info})
        q = x0[:2 * self.nf]
        kmat, mmat = self.matrices(q)
        count = max(1, min(int(count), kmat.shape[0]))
        lam, vec = eigh(kmat, mmat, subset_by_index=[0, count - 1])
        omega = np.sign(lam) * np.sqrt(np.abs(lam))
        shapes = np.zeros((count, n + 1, 3))
        for k in range(count):
            s = np.zeros((n + 1, 2))
            s[self.free] = vec[:, k].reshape(-1, 2)
            big = s.reshape(-1)[int(np.argmax(np.abs(s)))]
            shapes[k, :, 0] = s[:, 0] / big
            shapes[k, :, 2] = s[:, 1] / big
        pos = np.asarray(self.output_function()(0.0, q, np.zeros(2 * self.nf))[0]).T
        nodes = np.column_stack([pos[:, 0], np.full(n + 1, self.y_plane), pos[:, 1]])
        status, msg = "solved", f"{count} in-plane modes, {n} elements"
        if np.any(lam < 0):
            status = "failed"
            msg = (f"the static state is unstable: {int(np.sum(lam < 0))} negative "
                   "eigenvalues of K (a compressed or slack line)")
        return ModesResult(frequencies=omega, shapes=shapes, node_positions=nodes,
                           length=self.length0, model="planar", status=status, message=msg,
                           diagnostics={"elements": n, "start": info,
                                        "stiffness": "tension and weight; drag neglected"})
