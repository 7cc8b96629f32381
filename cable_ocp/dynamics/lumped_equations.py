"""The equations of motion of the lumped-mass line (Huang (1992), eqs. (5.1)-(5.6)), once.

Newton's law at node i, ``(m_i I + A_i(x)) x_i'' = F_i(x, x', t)`` (Huang (1992), eqs.
(5.1)-(5.2)), is assembled here from three kinds of terms, each written once and used by
every form of the model: the model's CasADi functions (forces, mass matrix, tensions, top
force, energy, statics; :class:`cable_ocp.dynamics.lumped.LumpedMassModel`), the compiled
segment kernel of its time step (:func:`cable_ocp.dynamics.lumped_kernel.segment_kernel_expr`,
which adds the Newton blocks to these terms) and the step with the top motion and the top
segment's length as inputs (:mod:`cable_ocp.dynamics.lumped_driven`, the heave plant's):

* a segment's pull (:func:`segment_tension`): the smooth no-compression Hooke's law (5.3)
  ``T = (EA eps + sqrt((EA eps)^2 + delta_T^2)) / 2`` plus the material damping
  ``c deps/dt`` while taut (:mod:`cable_ocp.physics.elasticity`), along the chord (one
  level), or, over a time step, the discrete gradient of Simo & Tarnow (1992) / Gonzalez
  (1996): the mean of T over ``[eps0, eps1]`` (exact for EA e,
  :func:`~cable_ocp.physics.elasticity.mean_strain_tension`) along
  ``(d0 + d1) / (|d0| + |d1|)``, its damping switch the mean switch over the interval
  (:func:`~cable_ocp.physics.elasticity.mean_strain_switch`). A damped segment cannot push:
  elastic plus damping tension pass through
  :func:`~cable_ocp.physics.elasticity.smooth_positive` (:func:`interval_tension`), as in
  the planar model;
* a segment's drag (:func:`segment_drag`): the drag per stretched length of
  :func:`cable_ocp.physics.drag.drag_per_length` (in the kernel its form with the
  Jacobian, :func:`cable_ocp.physics.drag.line_drag_kernel`) in the relative flow ``U(z) - (v_a +
  v_b) / 2`` times the chord's length, half to each end node, and its added mass
  (:func:`added_mass_share`, eq. (5.2), :mod:`cable_ocp.physics.added_mass`):
  ``e/2 (I - t t^T) + e_t/2 t t^T`` on each end;
* the nodes' own terms (:func:`node_masses`, :func:`node_weights`, :func:`node_loads`,
  :func:`point_drag`): half of each adjacent segment's mass and weight in water per
  unstretched length, the unit's (eq. (5.6)) and the point bodies' mass, added mass,
  weight, load and drag (:func:`cable_ocp.physics.drag.point_drag`).
"""

from __future__ import annotations

from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.dynamics.bending_terms import LineBending
from cable_ocp.dynamics.lumped_params import LumpedParams
from cable_ocp.physics.added_mass import (
    added_mass_per_length,
    line_added_mass,
    projected_added_mass,
)
from cable_ocp.physics.drag import drag_per_length
from cable_ocp.physics.drag import point_drag as physics_point_drag
from cable_ocp.physics.elasticity import (
    material_damping,
    mean_strain_switch,
    mean_strain_tension,
    smooth_positive,
    smooth_strain_energy,
    strain_switch,
    strain_tension,
)

__all__ = ["LumpedEquations", "added_mass_share", "interval_tension", "node_loads",
           "node_masses", "node_weights", "no_push", "point_drag", "point_drag_items",
           "segment_drag", "segment_tension"]


# --------------------------------------------------------------------------------------
# The laws on one segment
# --------------------------------------------------------------------------------------

def segment_tension(d1: Any, ell1: Any, ea: Any, c: Any, delta_t: Any, *,
                    d0: Any = None, ell0: Any = None, dt: Any = None, dv: Any = None,
                    mid: Any = None, length_rate: Any = None, table: Any = None,
                    shift: Any = 0.0) -> dict[str, Any]:
    """A segment's tension and the direction it pulls along (the law (5.3) with damping).

    One level (``d0`` None): ``T(eps1)`` along ``d1``, plus the damping ``c deps/dt
    taut(eps1)`` where the ends' relative velocity ``dv`` (m/s) is given, with
    ``deps/dt = d1 . dv / (|d1| l1)`` (less ``|d1| l1' / l1^2`` where the unstretched
    length changes at ``length_rate``, m/s). Two levels (``d0`` given, the start of a step
    of ``dt`` seconds): :func:`interval_tension`, the mean of T over ``[eps0, eps1]`` plus
    ``c deps/dt`` times the mean switch, along ``(d0 + d1) / (|d0| + |d1|)``, with
    ``deps/dt = (|d1| - |d0|) / (l dt)`` (``(eps1 - eps0) / dt`` where ``ell0`` differs from
    ``ell1``). With ``mid`` (the compiled kernel's switch between the two, 1 or 0, where
    ``d0 = d1`` when 0) the damping rate is ``mid`` times the two-level one plus ``1 - mid``
    times the one-level one. Where damped (c > 0), elastic plus damping tension pass
    through :func:`no_push` at both levels: the segment cannot push.

    Parameters
    ----------
    d1 : casadi expression (3,)
        The chord (end b minus end a), m; at the end of a step for two levels.
    ell1 : float or casadi expression
        Unstretched length, m (at the end of the step).
    ea, c, delta_t : float or casadi expression
        EA (N), the material damping c (N s) and the smoothing force scale (N).
    d0 : casadi expression (3,), optional
        The chord at the start of the step, m.
    ell0 : float or casadi expression, optional
        Unstretched length at the start of the step, m (default: ``ell1``, constant).
    dt : float or casadi expression, optional
        The step, s (two levels).
    dv : casadi expression (3,), optional
        Velocity of end b minus that of end a, m/s (the one-level damping).
    mid : casadi expression, optional
        The kernel's switch (-).
    length_rate : casadi expression, optional
        Rate of the unstretched length, m/s (one level).
    table : TensionStrainTable, optional
        A tension-strain law in place of EA e
        (:func:`cable_ocp.physics.elasticity.strain_tension`).
    shift : float or casadi expression
        A strain subtracted from the strains in the law, EA (e - shift) (-): the
        viscoelastic law, EA_d (e - (EA_d - EA_s) e_v / EA_d) at an instant, or its
        midpoint step's k (e - F_0 / k)
        (:class:`cable_ocp.physics.viscoelastic.StandardLinearSolid`); 0 otherwise.

    Returns
    -------
    dict
        ``tension`` (N, with the damping, >= 0), ``num`` and ``den`` (the pull on end a is
        ``tension * num / den``, end b takes the opposite), ``strain`` (eps1), ``l1`` (m),
        ``damping`` (N, the damping term before :func:`no_push`, 0 where there is none)
        and, for two levels, ``l0``, ``e0`` (eps0) and ``rate`` (the damping's strain
        rate, 1/s).
    """
    l1 = ca.norm_2(d1)
    e1 = l1 / ell1 - 1.0
    out: dict[str, Any] = {"strain": e1, "l1": l1}
    if d0 is None:
        tens = strain_tension(e1 - shift, ea, delta_t, table)
        damp: Any = 0.0
        if dv is not None:
            rate = ca.dot(d1, dv) / (l1 * ell1)
            if length_rate is not None:
                rate = rate - l1 * length_rate / ell1**2  # d/dt (|d| / l) with l changing
            damp = _damping(rate, e1 - shift, c, ea, delta_t, table)
            tens = no_push(tens + damp, c, delta_t)
        out.update(tension=tens, num=d1, den=l1, damping=damp)
        return out
    l0 = ca.norm_2(d0)
    e0 = l0 / (ell1 if ell0 is None else ell0) - 1.0
    if ell0 is None:  # a constant unstretched length
        step_rate = (l1 - l0) / (ell1 * dt)
    else:
        step_rate = (e1 - e0) / dt
    if mid is not None:
        rate = mid * (l1 - l0) / (ell1 * dt) + (1.0 - mid) * ca.dot(d1, dv) / (l1 * ell1)
    else:
        rate = step_rate
    tbar, damp = interval_tension(e0, e1, rate, ea, c, delta_t, table, shift)
    out.update(tension=tbar, num=d0 + d1, den=l0 + l1, damping=damp, l0=l0, e0=e0, rate=rate)
    return out


def interval_tension(strain0: Any, strain1: Any, rate: Any, ea: Any, c: Any, delta_t: Any,
                     table: Any = None, shift: Any = 0.0) -> tuple[Any, Any]:
    """A segment's tension over a time step, N, and its damping term, N: the mean of the
    no-compression law over the step's strains
    (:func:`~cable_ocp.physics.elasticity.mean_strain_tension`: exact for EA e, also across
    the kink at e = 0) plus ``c rate`` times the mean taut switch
    (:func:`~cable_ocp.physics.elasticity.mean_strain_switch`), through :func:`no_push`
    where damped. The planar step's law (:mod:`cable_ocp.dynamics.planar`).

    Parameters
    ----------
    strain0, strain1 : float or casadi expression
        The strains at the start and end of the step (-).
    rate : float or casadi expression
        The damping's strain rate, 1/s.
    ea, c, delta_t : float or casadi expression
        EA (N), the material damping c (N s) and the smoothing force scale (N).
    table : TensionStrainTable, optional
        A tension-strain law in place of EA e.
    shift : float or casadi expression
        A strain subtracted from both strains (-; :func:`segment_tension`).
    """
    a, b = strain0 - shift, strain1 - shift
    damp = c * rate * mean_strain_switch(a, b, ea, delta_t, table)
    return no_push(mean_strain_tension(a, b, ea, delta_t, table) + damp, c, delta_t), damp


def no_push(tension: Any, c: Any, delta_t: Any) -> Any:
    """A segment's elastic plus damping tension that cannot push, N:
    :func:`~cable_ocp.physics.elasticity.smooth_positive` of it where the segment is damped
    (c > 0; >= 0, above max(T, 0) by at most delta_T / 2); unchanged where c = 0 (the
    elastic law alone is positive already, and the step's tension stays the discrete
    gradient of the strain energy: an undamped line conserves energy).

    Parameters
    ----------
    tension : float or casadi expression
        Elastic plus damping tension, N.
    c : float or casadi expression
        The material damping, N s.
    delta_t : float or casadi expression
        The smoothing force scale delta_T, N.
    """
    if isinstance(c, (ca.SX, ca.MX)):
        return ca.if_else(c > 0, smooth_positive(tension, delta_t), tension)
    return smooth_positive(tension, delta_t) if float(c) > 0 else tension


def _damping(rate: Any, strain: Any, c: Any, ea: Any, delta_t: Any, table: Any) -> Any:
    if table is None:
        return material_damping(rate, strain, c, ea, delta_t)
    return c * rate * strain_switch(strain, ea, delta_t, table)


def segment_drag(drag_law: str, dm: Any, urel: Any, *, rho: float, diameter: float,
                 normal_drag: float, tangential_drag: float, delta: float,
                 blend: float) -> Any:
    """Drag on a segment of chord ``dm`` (m) in the relative flow ``urel`` (m/s), N: the
    drag per stretched length (:func:`cable_ocp.physics.drag.drag_per_length`) times the
    chord's length. Each end node takes half. The compiled kernel's form of the same law,
    with its Jacobian, is :func:`cable_ocp.physics.drag.line_drag_kernel`.

    Parameters
    ----------
    drag_law : {"vector", "componentwise"}
        The normal drag's law.
    dm : casadi expression (3,)
        The chord, m.
    urel : casadi expression (3,)
        Flow relative to the segment, m/s.
    rho, diameter, normal_drag, tangential_drag : float
        Water density (kg/m^3), diameter d (m), C_n and C_t (-).
    delta, blend : float
        Smoothing velocity of the moduli (m/s) and the componentwise law's vertical blend
        (-).
    """
    lm = ca.norm_2(dm)
    return lm * drag_per_length(drag_law, urel, dm / lm, rho=rho, diameter=diameter,
                                normal_drag=normal_drag, tangential_drag=tangential_drag,
                                delta=delta, blend=blend)


def added_mass_share(dm: Any, en: Any, et: Any, eet: Any = None) -> Any:
    """Each end node's share of a segment's added mass (Huang (1992), eq. (5.2)), 3x3, kg:
    half of :func:`cable_ocp.physics.added_mass.line_added_mass` with the segment's normal
    and tangential added masses ``en``, ``et`` (kg) at its chord ``dm`` (m).

    ``eet``: the compiled kernel's ``t t^T`` from its unit tangent (it has it for the drag's
    Jacobian); the law is then taken on it
    (:func:`cable_ocp.physics.added_mass.projected_added_mass`) rather than on
    ``dm dm^T / |dm|^2`` (the two differ by rounding, and the kernel's steps are kept
    bitwise).

    Parameters
    ----------
    dm : casadi expression (3,)
        The chord, m.
    en, et : float or casadi expression
        Normal and tangential added mass of the segment, kg.
    eet : casadi expression (3, 3), optional
        t t^T from the unit tangent (-).
    """
    if eet is None:
        return 0.5 * line_added_mass(dm, en, et)
    return 0.5 * projected_added_mass(eet, en, et)


def point_drag(u: Any, cs: list[float], law: str, rho: float, delta: float) -> Any:
    """Drag of a point body (the unit, eq. (5.6), or a body on the line), N:
    :func:`cable_ocp.physics.drag.point_drag` of the flow ``u`` relative to it (m/s), with
    the drag areas ``cs`` (m^2 per axis), the law ``"vector"`` or ``"per_axis"``, the
    water density ``rho`` (kg/m^3) and the smoothing velocity ``delta`` (m/s).

    Parameters
    ----------
    u : casadi expression (3,)
        Flow relative to the body, m/s.
    cs : list of 3 float
        Drag areas C_D S per axis, m^2.
    law : {"vector", "per_axis"}
        The law.
    rho : float
        Water density, kg/m^3.
    delta : float
        Smoothing velocity, m/s.
    """
    return physics_point_drag(u, cs, rho=rho, delta=delta, per_axis=law == "per_axis")


def point_drag_items(p: LumpedParams) -> list[tuple[int, list[float], str]]:
    """``(node, cs, law)`` of the unit and every body that has drag (none in air)."""
    items = []
    if p.unit is not None:
        items.append((0, [a * c for a, c in zip(p.unit.drag_area, p.unit.drag_coefficient,
                                                strict=True)], p.unit.drag_law))
    items += [(b.node, [b.drag_area * b.drag_coefficient] * 3, "vector") for b in p.bodies]
    return [it for it in items if any(it[1]) and p.water_density > 0]


# --------------------------------------------------------------------------------------
# The nodes' own terms
# --------------------------------------------------------------------------------------

def node_masses(p: LumpedParams) -> np.ndarray:
    """Node masses per axis (kg), shape (N+1, 3): half of each adjacent segment's mass plus
    the unit's or body's mass and added mass."""
    half = 0.5 * p.mass_per_length * p.segment_length
    m = np.zeros(p.segments + 1)
    m[:-1] += half
    m[1:] += half
    out = np.repeat(m[:, None], 3, axis=1)
    if p.unit is not None:
        out[0] += p.unit.mass + np.asarray(p.unit.added_mass)
    for b in p.bodies:
        out[b.node] += b.mass + np.asarray(b.added_mass)
    return out


def node_weights(p: LumpedParams) -> np.ndarray:
    """Downward weight in water at the nodes, N, shape (N+1,)."""
    half = 0.5 * p.weight_in_water * p.segment_length
    w = np.zeros(p.segments + 1)
    w[:-1] += half
    w[1:] += half
    if p.unit is not None:
        w[0] += p.unit.weight_in_water
    for b in p.bodies:
        w[b.node] += b.weight_in_water
    return w


def node_loads(p: LumpedParams, weights: np.ndarray | None = None) -> np.ndarray:
    """The constant loads on the nodes, N, shape (3, N+1): the weights in water
    (:func:`node_weights`, or ``weights``) and the external loads of the unit and the
    bodies.

    Parameters
    ----------
    p : LumpedParams
        The line.
    weights : ndarray (N+1,), optional
        The nodes' weights in water, N (default :func:`node_weights`).
    """
    static = np.zeros((3, p.segments + 1))
    static[2] = -(node_weights(p) if weights is None else weights)
    if p.unit is not None:
        static[:, 0] += p.unit.force
    for b in p.bodies:
        static[:, b.node] += b.force
    return static


# --------------------------------------------------------------------------------------
# The line: the terms above on every segment and node
# --------------------------------------------------------------------------------------

class LumpedEquations:
    """The terms of the equations of motion on every segment and node of one line, as
    lists of CasADi expressions (one 3-vector or 3x3 block per node, end_a to end_b).

    Parameters
    ----------
    params : LumpedParams
        The line.
    """

    def __init__(self, params: LumpedParams) -> None:
        self.params = p = params
        self.node_mass = node_masses(p)
        self.node_weight = node_weights(p)
        self.loads = node_loads(p, self.node_weight)
        #: normal and tangential added mass per unstretched length of each segment, kg/m
        self.added_mass_per_length = tuple(
            np.array([added_mass_per_length(float(c), p.water_density, float(d))
                      for c, d in zip(coef, p.diameter, strict=True)])
            for coef in (p.added_mass_coefficient, p.tangential_added_mass_coefficient))
        #: normal and tangential added mass of each segment, kg
        self.added_mass = tuple(a * p.segment_length for a in self.added_mass_per_length)
        #: the hinges of a line with bending stiffness (:mod:`cable_ocp.dynamics.bending_terms`)
        self.bending = LineBending(p.bending_stiffness, p.segment_length, 3)

    def zeros(self) -> list[Any]:
        """A zero 3-vector per node."""
        return [ca.SX.zeros(3) for _ in range(self.params.segments + 1)]

    @staticmethod
    def total(*parts: list[Any]) -> list[Any]:
        """The node-wise sum of lists of node terms."""
        return [sum(c[i] for c in parts) for i in range(len(parts[0]))]

    def tension(self, j: int, d1: Any, ell1: Any = None, internal: Any = None,
                **kw: Any) -> dict[str, Any]:
        """:func:`segment_tension` of segment ``j`` with chord ``d1`` (m): its EA, c and
        unstretched length (or ``ell1``, m; further keywords as there); with the
        viscoelastic law and the dashpot strain ``internal`` (-) its tension at the
        instant (EA_d, shifted), without it the relaxed law EA_s.

        Parameters
        ----------
        j : int
            Segment index from end_a.
        d1 : casadi expression (3,)
            The chord, m.
        ell1 : float or casadi expression, optional
            Unstretched length, m (default the segment's).
        internal : casadi expression, optional
            The segment's dashpot strain e_v (-), viscoelastic law only.
        **kw
            Further keywords of :func:`segment_tension`.
        """
        p = self.params
        ell1 = float(p.segment_length[j]) if ell1 is None else ell1
        ea = float(p.axial_stiffness[j])
        if internal is not None and p.viscoelastic is not None:
            sls = p.viscoelastic
            ea = sls.dynamic_stiffness
            kw["shift"] = (ea - sls.static_stiffness) * internal / ea
        return segment_tension(d1, ell1, ea, float(p.axial_damping[j]), p.slack_smoothing,
                               table=p.tension_strain, **kw)

    def tensions(self, r: list[Any], vel: list[Any] | None = None,
                 internal: Any = None) -> tuple[Any, Any]:
        """Segment tensions (N; with the material damping where velocities are given) and
        strains (-) at node positions ``r`` (and the dashpot strains ``internal``, -, of
        the viscoelastic law).

        Parameters
        ----------
        r : list of casadi expression
            Node positions, m.
        vel : list of casadi expression, optional
            Node velocities, m/s.
        internal : casadi expression (N,), optional
            The dashpot strains e_v (-).
        """
        ts, es = [], []
        p = self.params
        for j in range(p.segments):
            dv = vel[j + 1] - vel[j] if (vel is not None and p.axial_damping[j] > 0) else None
            st = self.tension(j, r[j + 1] - r[j], dv=dv,
                              internal=None if internal is None else internal[j])
            ts.append(st["tension"])
            es.append(st["strain"])
        return ca.vertcat(*ts), ca.vertcat(*es)

    def elastic(self, r0: list[Any], r1: list[Any] | None, vel: list[Any] | None,
                dt: float | None, internal: Any = None) -> list[Any]:
        """The segments' pulls on the nodes, N: at the positions ``r0`` (``r1`` None; the
        material damping from the velocities ``vel`` unless None), or the discrete
        gradient between ``r0`` and ``r1`` over ``dt`` (:func:`segment_tension`).

        Parameters
        ----------
        r0 : list of casadi expression
            Node positions (at the start of the step), m.
        r1 : list of casadi expression or None
            Node positions at the end of the step, m.
        vel : list of casadi expression or None
            Node velocities, m/s (one level).
        dt : float or None
            The step, s (two levels).
        internal : casadi expression (N,), optional
            The dashpot strains e_v of the viscoelastic law (-; one level only).
        """
        p = self.params
        f = self.zeros()
        for j in range(p.segments):
            c = float(p.axial_damping[j])
            if r1 is None:
                dv = vel[j + 1] - vel[j] if (c > 0 and vel is not None) else None
                st = self.tension(j, r0[j + 1] - r0[j], dv=dv,
                                  internal=None if internal is None else internal[j])
            else:
                st = self.tension(j, r1[j + 1] - r1[j], d0=r0[j + 1] - r0[j], dt=dt)
            fe = st["tension"] * st["num"] / st["den"]
            f[j] = f[j] + fe
            f[j + 1] = f[j + 1] - fe
        if self.bending.active:  # at the mean positions: the exact discrete gradient
            rb = r0 if r1 is None else [0.5 * (a + b) for a, b in zip(r0, r1, strict=True)]
            f = self.total(f, self.bending.node_list_forces(rb))
        return f

    def current(self, z: Any) -> Any:
        """The current at height z (m), m/s (zero in still water)."""
        p = self.params
        return ca.vec(p.current(z)) if p.current is not None else ca.SX.zeros(3)

    def segment_drag(self, j: int, dm: Any, urel: Any) -> Any:
        """:func:`segment_drag` of segment ``j`` with chord ``dm`` (m) in the relative flow
        ``urel`` (m/s), N (zero without drag or water).

        Parameters
        ----------
        j : int
            Segment index.
        dm : casadi expression (3,)
            The chord, m.
        urel : casadi expression (3,)
            Relative flow, m/s.
        """
        p = self.params
        if p.water_density == 0 or (p.normal_drag[j] == 0 and p.tangential_drag[j] == 0):
            return ca.SX.zeros(3)
        return segment_drag(p.drag_law, dm, urel, rho=p.water_density,
                            diameter=float(p.diameter[j]),
                            normal_drag=float(p.normal_drag[j]),
                            tangential_drag=float(p.tangential_drag[j]), delta=p.smoothing,
                            blend=p.vertical_blend)

    def point_drag(self, i: int, r: Any, v: Any) -> Any:
        """The drag of the unit and the bodies at node ``i`` at position ``r`` (m) and
        velocity ``v`` (m/s), N.

        Parameters
        ----------
        i : int
            Node index.
        r : casadi expression (3,)
            The node's position, m.
        v : casadi expression (3,)
            Its velocity, m/s.
        """
        p = self.params
        f = ca.SX.zeros(3)
        for node, cs, law in point_drag_items(p):
            if node == i:
                f = f + point_drag(self.current(r[2]) - v, cs, law, p.water_density,
                                   p.smoothing)
        return f

    def drag(self, r: list[Any], vel: list[Any]) -> list[Any]:
        """Hydrodynamic drag with current on the segments (half to each end node), the unit
        and the bodies, N, at positions ``r`` and node velocities ``vel``.

        Parameters
        ----------
        r : list of casadi expression
            Node positions, m.
        vel : list of casadi expression
            Node velocities, m/s.
        """
        p = self.params
        f = self.zeros()
        if p.water_density == 0:
            return f
        for j in range(p.segments):
            urel = self.current(0.5 * (r[j][2] + r[j + 1][2])) - 0.5 * (vel[j] + vel[j + 1])
            fd = self.segment_drag(j, r[j + 1] - r[j], urel)
            f[j] = f[j] + 0.5 * fd
            f[j + 1] = f[j + 1] + 0.5 * fd
        for node in sorted({it[0] for it in point_drag_items(p)}):
            f[node] = f[node] + self.point_drag(node, r[node], vel[node])
        return f

    def static_loads(self) -> list[Any]:
        """Weights in water and the external loads of the unit and bodies, N."""
        return [ca.SX(ca.DM(self.loads[:, i])) for i in range(self.params.segments + 1)]

    def added_mass_share(self, j: int, dm: Any, length: Any = None) -> Any:
        """:func:`added_mass_share` of segment ``j`` at chord ``dm`` (m), 3x3, kg; with
        ``length`` (m) that unstretched length instead of the segment's own.

        Parameters
        ----------
        j : int
            Segment index.
        dm : casadi expression (3,)
            The chord, m.
        length : float or casadi expression, optional
            Unstretched length, m.
        """
        en, et = (float(a[j]) for a in self.added_mass)
        if en == 0 and et == 0:
            return ca.SX.zeros(3, 3)
        if length is not None:
            en, et = (float(a[j]) * length for a in self.added_mass_per_length)
        return added_mass_share(dm, en, et)

    def mass_blocks(self, r: list[Any]) -> list[Any]:
        """3x3 mass blocks of every node (kg), with the added mass of (5.2)."""
        n = self.params.segments
        blocks = [ca.SX(ca.diag(ca.DM(self.node_mass[i]))) for i in range(n + 1)]
        for j in range(n):
            en, et = (float(a[j]) for a in self.added_mass)
            if en == 0 and et == 0:
                continue
            add = self.added_mass_share(j, r[j + 1] - r[j])
            blocks[j] = blocks[j] + add
            blocks[j + 1] = blocks[j + 1] + add
        return blocks

    def energy(self, v: Any, mass: Any, r: list[Any], internal: Any = None
               ) -> tuple[Any, Any]:
        """Kinetic energy 1/2 v^T M v (``mass`` the free nodes' mass matrix) and potential
        energy (strain, :func:`cable_ocp.physics.elasticity.smooth_strain_energy` per
        unstretched length, and weight), J; with the viscoelastic law and its dashpot
        strains ``internal`` the strain energy of its two springs
        (:meth:`~cable_ocp.physics.viscoelastic.StandardLinearSolid.energy`, a taut line).

        Parameters
        ----------
        v : casadi expression (3 n_free,)
            Free-node velocities, m/s.
        mass : casadi expression
            The free nodes' mass matrix, kg.
        r : list of casadi expression
            Node positions, m.
        internal : casadi expression (N,), optional
            The dashpot strains e_v (-).
        """
        p = self.params
        kin = 0.5 * ca.dot(v, ca.mtimes(mass, v))
        pot = 0
        for j in range(p.segments):
            ell = float(p.segment_length[j])
            eps = ca.norm_2(r[j + 1] - r[j]) / ell - 1.0
            if internal is not None and p.viscoelastic is not None:
                pot = pot + ell * p.viscoelastic.energy(eps, internal[j])
                continue
            pot = pot + ell * (smooth_strain_energy(eps, float(p.axial_stiffness[j]),
                                                    p.slack_smoothing)
                               if p.tension_strain is None else p.tension_strain.energy(eps))
        for i in range(p.segments + 1):
            pot = pot + float(self.node_weight[i]) * r[i][2]
        return kin, pot + self.bending.node_list_energy(r)
