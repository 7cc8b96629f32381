"""Pay-out and haul-in of the 3D lumped-mass line: nodes enter and leave at the winch.

The line of :mod:`cable_ocp.dynamics.lumped_equations` (Huang (1992) ch. 5) with a varying
unstretched length L(t), the pay-out law of ``[top_motion]``
(:func:`cable_ocp.scene.motion.length_expr`, Huang's 3.1), as ch. 3-4 vary it in 1D and 2D
and as 004 7.3 (2) recommends for the 3D model.

Approach: the material nodes keep their identity; only the top segment (between the top
free node and the winch at end_b) changes its unstretched length, l_top(t) = L(t) - (the
sum of the others). When l_top exceeds ``split`` (1.5) element lengths l_e, a node enters
at the winch: the top segment is cut into a segment of l_e (the lower one, a regular
element) and a new top segment of l_top - l_e (>= 0.5 l_e); when l_top falls below
``merge`` (0.4) l_e, the top free node leaves: the top two segments become one of
l_top + l_below (<= 1.4 l_e, so the two thresholds never undo each other). Why this
rather than a moving mesh (Huang's fixed domain y = s / L(t), (3.4)-(3.7), which the axial
and planar models use): in 3D a fixed-domain mesh moves every material point each step and
needs the advection of the positions and velocities in y (upwinded or central, with its
numerical dispersion), while here the equations of every segment but the top one are the
fixed-length model's unchanged (the material nodes move with the material, no advection
error), the elements stay within [0.4, 1.5] l_e, and the bookkeeping across an event is
exact and checkable:

* mass: every segment carries mu l_j, half at each end node; the cut and the join only
  re-split the lengths (their sum is L(t)), so the line's mass sum(m_i) (the winch's share
  included) is mu L(t) plus the unit's and bodies' masses, to round-off;
* a split puts the new node on the chord, the stretched length shared so that the two
  nodes keep their force balance: the lower part (l_e) at the strain eps - w_t (l_top -
  l_e) / (2 EA), the upper one at eps + w_t l_e / (2 EA) (w_t the weight in water per
  length along the chord; a hanging line's tension grows by w_t per length, and the new
  node carries w l_top / 2); the strain energy then grows by w_t^2 l_e (l_top - l_e) l_top
  / (8 EA) (second order in the strain step; keeping the strain instead sends an axial
  wave of order w l_e / 2 down the line at every split). The velocity is interpolated at
  f = l_e / l_top between the node below and the material at the winch (v_b - L' (1 +
  eps_top) t, t the top segment's unit tangent), which keeps the line's momentum (the
  winch's share at the material's velocity) exactly; its kinetic energy drops by mu l_top
  f (1 - f) |v_below - v_winch|^2 / 4 (the lumped masses' own redistribution, second order
  in the relative velocity across the top segment);
* a merge gives the leaving node's mass to the node below (mu l_top / 2, with its momentum)
  and to the winch (mu l_below / 2, which leaves the free nodes with its momentum).

Between events the unstretched lengths are fixed but the top one, whose rate is L'. The
material entering at the winch joins the top free node (its mass grows at mu L' / 2) with
that node's velocity (no impact force: the material at the winch moves as the line's top
in a steady pay-out), so Newton's law is M a = F at every free node. Energy identity of the
semi-discrete line (no added mass, no material damping; E = the free nodes' kinetic energy
plus the strain energy sum_j l_j W(eps_j), W the stored energy of
:func:`cable_ocp.physics.elasticity.smooth_strain_energy`):

    dE/dt = P_gravity + P_drag + P_winch + P_inflow
    P_winch  = T_top t . (v_b - L' (1 + eps_top) t)     (the tension times the velocity
                                                         of the material at the winch)
    P_inflow = L' (W(eps_top) + mu |v_top node|^2 / 4)  (the strain and kinetic energy of
                                                         the cable paid out)

with P_gravity and P_drag the powers of the weights (and loads) and of the drag on the free
nodes. The time step below keeps this identity exactly over each step (the midpoint rule
with a diagonal mass, the discrete gradient, masses at the mean lengths): the step's works
are dt v_m . F at the free nodes for gravity and drag, T_bar (t_m . dx_b - (1 + eps_mean)
dL) for the winch (T_bar the top segment's mean tension, t_m its mean direction) and
dL W_mean + mu dL (|v0|^2 + |v1|^2) / 8 for the inflow, so that E(t) - E(0) equals their
sum plus the events' jumps to the Newton tolerance; :meth:`PayoutLine.run` sums them
(``energy=True``) so that the balance of a run is checkable
(:mod:`tests.dynamics.test_lumped_payout`).

Time: the fixed-length model's implicit midpoint rule with the discrete-gradient tension
(:func:`cable_ocp.dynamics.lumped_equations.segment_tension` with the unstretched lengths
at both levels), solved for the new positions by CasADi's Newton ``rootfinder``; one CasADi
function per number of segments, built on first use and cached; events after each step.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.dynamics.lumped_equations import (
    LumpedEquations,
    added_mass_share,
    segment_drag,
    segment_tension,
)
from cable_ocp.dynamics.lumped_params import LumpedParams
from cable_ocp.errors import CableOCPError
from cable_ocp.physics.elasticity import smooth_strain_energy

__all__ = ["MERGE", "SPLIT", "PayoutLine", "PayoutRun", "PayoutState"]

#: a node enters at the winch when the top segment exceeds this many element lengths
SPLIT = 1.5
#: the top free node leaves when the top segment is shorter than this many element lengths
MERGE = 0.4

_PROPS = ("axial_stiffness", "diameter", "mass_per_length", "weight_in_water", "normal_drag",
          "tangential_drag", "added_mass_coefficient", "tangential_added_mass_coefficient",
          "axial_damping")


@dataclass
class PayoutState:
    """The line at one time: every node's position and velocity (end_a to end_b; at end_b
    the winch's position and the velocity of the material there) and the segments'
    unstretched lengths.

    Attributes
    ----------
    t : float
        Time, s.
    lengths : ndarray (n,)
        Unstretched segment lengths, m (end_a to end_b; the last is the top segment).
    r : ndarray (n + 1, 3)
        Node positions, m.
    v : ndarray (n + 1, 3)
        Node velocities, m/s.
    """

    t: float
    lengths: np.ndarray
    r: np.ndarray
    v: np.ndarray

    @property
    def segments(self) -> int:
        """Number of segments n."""
        return int(self.lengths.size)


@dataclass
class PayoutRun:
    """A pay-out run: the recorded states and what happened.

    Attributes
    ----------
    states : list of PayoutState
        The states at the recorded times (the first the start).
    tensions : list of ndarray
        Segment tensions (N) at the recorded times.
    top_force : list of ndarray
        The force of the winch on the line (N, 3) at the recorded times.
    status : str
        ``"solved"`` or ``"failed"``.
    message : str
        What happened.
    splits, merges : int
        Nodes that entered and left at the winch.
    events : list of dict
        Every split and merge: ``t`` (s), ``kind``, ``segments`` after it, the jump of the
        energy E (J) and of the line's momentum (N s, 3) across it.
    energy : dict or None
        With ``energy=True``: the times (s), E (J) and the cumulative work (J) of
        ``gravity``, ``drag``, ``winch``, ``inflow`` and ``events`` at the recorded times.
    wall_time_s : float
        Wall time, s.
    min_strain : float
        Smallest segment strain at the recorded times (-).
    """

    states: list[PayoutState]
    tensions: list[np.ndarray]
    top_force: list[np.ndarray] = field(default_factory=list)
    status: str = "solved"
    message: str = ""
    splits: int = 0
    merges: int = 0
    events: list[dict[str, Any]] = field(default_factory=list)
    energy: dict[str, Any] | None = None
    wall_time_s: float = 0.0
    min_strain: float = math.inf


class PayoutLine:
    """The lumped-mass line with a varying length.

    Parameters
    ----------
    params : LumpedParams
        The line at t = 0 (its segments, unit, bodies, ends, current); the segments added at
        the winch take the top segment's properties.
    length : callable
        ``length(t) -> (L, L_t)``: the unstretched length (m) and its rate (m/s) at t (s).
    element_length : float, optional
        l_e, m (default: the top segment's length at t = 0).
    split, merge : float
        The thresholds in element lengths (:data:`SPLIT`, :data:`MERGE`).
    tol : float
        Newton tolerance on the nodal force residual over the force scale (-).
    max_iter : int
        Newton iterations per step.
    """

    def __init__(self, params: LumpedParams, length: Callable[[float], tuple[float, float]],
                 element_length: float | None = None, split: float = SPLIT,
                 merge: float = MERGE, tol: float = 1e-10, max_iter: int = 20) -> None:
        self.params = p = params
        self.length = length
        le = float(p.segment_length[-1]) if element_length is None else float(element_length)
        if not le > 0:
            raise CableOCPError(f"simulation.element_length = {element_length}: must be > 0 (m)")
        if not (0 < merge < 0.5 * split and split > 1.0 + merge):
            raise CableOCPError(f"split = {split}, merge = {merge}: need 0 < merge < split/2 "
                                "and split > 1 + merge (else a split undoes a merge)")
        self.element_length = le
        self.split_at, self.merge_at = split * le, merge * le
        self.tol, self.max_iter = tol, max_iter
        self.eq = LumpedEquations(p)  # the unit's and bodies' terms, the current
        self.n0 = p.segments
        self._props = {k: np.asarray(getattr(p, k), float) for k in _PROPS}
        top = np.array([self._props[k][-1] for k in _PROPS])
        j = self.n0 - 1
        while j > 0 and np.array_equal([self._props[k][j - 1] for k in _PROPS], top):
            j -= 1
        #: the lowest segment of the top material: a merge never reaches below it
        self.top_first = j
        body_nodes = [b.node for b in p.bodies]
        self.top_first = max([self.top_first] + body_nodes)
        self.force_scale = max(float(np.sum(np.abs(self.eq.node_weight))), 1.0)
        self._fns: dict[int, dict[str, ca.Function]] = {}
        ts, zs, zr = ca.SX.sym("t"), ca.SX.sym("dz"), ca.SX.sym("dz_rate")
        ez = ca.DM([0.0, 0.0, 1.0])
        # the top at t, raised by dz (m; the heave plant's boom tip, 0 for a scene's run)
        self._top = ca.Function("top", [ts, zs], [ca.vec(p.top_position(ts)) + zs * ez])
        self._top_v = ca.Function("top_v", [ts, zr], [
            ca.jacobian(ca.vec(p.top_position(ts)), ts) + zr * ez])
        if p.fixed_a:
            self._a = ca.Function("a", [ts], [ca.vec(p.end_a_position(ts))])

    # -- properties and node terms -------------------------------------------------------
    def props(self, n: int) -> dict[str, np.ndarray]:
        """The segments' properties with ``n`` segments: the first ones' of the line at t = 0,
        those added at the winch the top segment's.

        Parameters
        ----------
        n : int
            Number of segments.
        """
        idx = np.minimum(np.arange(n), self.n0 - 1)
        return {k: v[idx] for k, v in self._props.items()}

    def node_masses(self, lengths: np.ndarray) -> np.ndarray:
        """Node masses per axis (kg), shape (n + 1, 3): half of each adjacent segment's
        mass, the unit's and bodies' mass and added mass (not the line's added mass, which
        depends on the configuration).

        Parameters
        ----------
        lengths : ndarray (n,)
            Unstretched segment lengths, m.
        """
        lengths = np.asarray(lengths, float)
        half = 0.5 * self.props(lengths.size)["mass_per_length"] * lengths
        m = np.zeros(lengths.size + 1)
        m[:-1] += half
        m[1:] += half
        out = np.repeat(m[:, None], 3, axis=1)
        p = self.params
        if p.unit is not None:
            out[0] += p.unit.mass + np.asarray(p.unit.added_mass)
        for b in p.bodies:
            out[b.node] += b.mass + np.asarray(b.added_mass)
        return out

    def momentum(self, state: PayoutState) -> np.ndarray:
        """The line's momentum (N s, 3): every node's mass of :meth:`node_masses` times its
        velocity, the winch's share at the material's velocity there.

        Parameters
        ----------
        state : PayoutState
            The line.
        """
        return np.sum(self.node_masses(state.lengths) * state.v, axis=0)

    def free(self, n: int) -> np.ndarray:
        """The free nodes' indices with ``n`` segments."""
        return np.arange(1 if self.params.fixed_a else 0, n)

    # -- the CasADi functions ------------------------------------------------------------
    def _terms(self, n: int, r: list[Any], vel: list[Any], ell: Any) -> dict[str, Any]:
        """Masses (3x3 per node), weights and loads, drag at nodes ``r`` (m), velocities
        ``vel`` (m/s) and unstretched lengths ``ell`` (m)."""
        p = self.params
        pr = self.props(n)
        ez = ca.DM([0.0, 0.0, 1.0])
        mass = [ca.SX.zeros(3, 3) for _ in range(n + 1)]
        loads = [ca.SX.zeros(3) for _ in range(n + 1)]
        drag = [ca.SX.zeros(3) for _ in range(n + 1)]
        an, at = (np.array([self.eq.added_mass_per_length[k][min(j, self.n0 - 1)]
                            for j in range(n)]) for k in (0, 1))
        for j in range(n):
            half_m = 0.5 * float(pr["mass_per_length"][j]) * ell[j]
            half_w = 0.5 * float(pr["weight_in_water"][j]) * ell[j]
            dm = r[j + 1] - r[j]
            add = (added_mass_share(dm, an[j] * ell[j], at[j] * ell[j])
                   if (an[j] or at[j]) else 0)
            for i in (j, j + 1):
                mass[i] = mass[i] + half_m * ca.SX.eye(3) + add
                loads[i] = loads[i] - half_w * ez
            if p.water_density > 0 and (pr["normal_drag"][j] or pr["tangential_drag"][j]):
                urel = (self.eq.current(0.5 * (r[j][2] + r[j + 1][2]))
                        - 0.5 * (vel[j] + vel[j + 1]))
                fd = segment_drag(p.drag_law, dm, urel, rho=p.water_density,
                                  diameter=float(pr["diameter"][j]),
                                  normal_drag=float(pr["normal_drag"][j]),
                                  tangential_drag=float(pr["tangential_drag"][j]),
                                  delta=p.smoothing, blend=p.vertical_blend)
                drag[j] = drag[j] + 0.5 * fd
                drag[j + 1] = drag[j + 1] + 0.5 * fd
        m_own = np.zeros((n + 1, 3))
        if p.unit is not None:
            m_own[0] += p.unit.mass + np.asarray(p.unit.added_mass)
            loads[0] = loads[0] + ca.DM(p.unit.force) - p.unit.weight_in_water * ez
        for b in p.bodies:
            m_own[b.node] += b.mass + np.asarray(b.added_mass)
            loads[b.node] = loads[b.node] + ca.DM(b.force) - b.weight_in_water * ez
        for i in range(n + 1):
            mass[i] = mass[i] + ca.diag(ca.DM(m_own[i]))
            if p.water_density > 0:
                drag[i] = drag[i] + self.eq.point_drag(i, r[i], vel[i])
        return {"mass": mass, "loads": loads, "drag": drag}

    def _tension(self, n: int, j: int, d1: Any, ell1: Any, **kw: Any) -> dict[str, Any]:
        pr = self.props(n)
        return segment_tension(d1, ell1, float(pr["axial_stiffness"][j]),
                               float(pr["axial_damping"][j]), self.params.slack_smoothing,
                               table=self.params.tension_strain, **kw)

    def _energy_density(self, strain: Any, ea: float) -> Any:
        """Stored energy per unstretched length (J/m) at ``strain``: the line's
        tension-strain table's, or the smooth Hooke law's."""
        table = self.params.tension_strain
        if table is not None:
            return table.energy(strain)
        return smooth_strain_energy(strain, ea, self.params.slack_smoothing)

    def _nodes(self, n: int, q: Any, t: Any, dz: Any = 0.0) -> list[Any]:
        nodes = [q[3 * k:3 * k + 3] for k in range(self.free(n).size)]
        if self.params.fixed_a:
            nodes = [self._a(t)] + nodes
        return nodes + [self._top(t, dz)]

    def _winch_velocity(self, n: int, r: list[Any], ell: Any, ldot: Any, t: Any,
                        dz_rate: Any = 0.0) -> Any:
        """The velocity of the material at the winch, v_b - L' (1 + eps_top) t (m/s)."""
        d = r[n] - r[n - 1]
        return self._top_v(t, dz_rate) - ldot * d / ell[n - 1]

    def functions(self, n: int) -> dict[str, ca.Function]:
        """The CasADi functions with ``n`` segments (built on first use, cached):
        ``step(q0, v0, l0, l1, t0, dt) -> (q1, v1)``, ``forces(q, v, l, t, ldot) ->
        (tensions, strains, top_force)``, ``energy(q, v, l, t, ldot) -> E`` (J) and
        ``balance(q0, v0, q1, l0, l1, t0, dt) -> (W_gravity, W_drag, W_winch, W_inflow)``
        (J, the step's works of the energy identity in the module docstring); and, for the
        heave plant (:mod:`cable_ocp.heave.lumped_deploy`), ``step_top(q0, v0, l0, l1, t0,
        dt, z0, z1)`` with the top raised by ``z0`` at t0 and ``z1`` at t0 + dt (m, linear
        between) and ``forces_top(q, v, l, t, ldot, z, z_rate)`` (m, m/s): ``step`` and
        ``forces`` are these at ``z = 0``.

        Parameters
        ----------
        n : int
            Number of segments.
        """
        if n in self._fns:
            return self._fns[n]
        nf = self.free(n).size
        sx = ca.SX.sym
        q0, v0, q1 = sx("q0", 3 * nf), sx("v0", 3 * nf), sx("q1", 3 * nf)
        l0, l1, t0, dt = sx("l0", n), sx("l1", n), sx("t0"), sx("dt")
        z0, z1 = sx("z0"), sx("z1")  # the top's extra height at t0 and t0 + dt, m
        free = [int(i) for i in self.free(n)]
        # -- the step: implicit midpoint, discrete-gradient tension -----------------------
        tm = t0 + 0.5 * dt
        r0, r1 = self._nodes(n, q0, t0, z0), self._nodes(n, q1, t0 + dt, z1)
        rm = [0.5 * (a + b) for a, b in zip(r0, r1, strict=True)]
        lm = 0.5 * (l0 + l1)
        vm = (q1 - q0) / dt
        v1 = 2.0 * vm - v0
        ldot = (l1[n - 1] - l0[n - 1]) / dt
        vel = [vm[3 * k:3 * k + 3] for k in range(nf)]
        if self.params.fixed_a:
            vel = [(r1[0] - r0[0]) / dt] + vel
        vel = vel + [self._winch_velocity(n, rm, lm, ldot, tm, (z1 - z0) / dt)]
        terms = self._terms(n, rm, vel, lm)
        f = [terms["loads"][i] + terms["drag"][i] for i in range(n + 1)]
        pr = self.props(n)
        for j in range(n):
            st = self._tension(n, j, r1[j + 1] - r1[j], l1[j], d0=r0[j + 1] - r0[j],
                               ell0=l0[j], dt=dt)
            fe = st["tension"] * st["num"] / st["den"]
            f[j] = f[j] + fe
            f[j + 1] = f[j + 1] - fe
        # the step's exact energy balance (no line added mass, no material damping): the
        # work of the loads and the drag on the free nodes, of the top segment's mean
        # tension on the material at the winch, and the paid-out cable's energy
        dl = l1[n - 1] - l0[n - 1]
        ea_top = float(pr["axial_stiffness"][n - 1])
        e0 = ca.norm_2(r0[n] - r0[n - 1]) / l0[n - 1] - 1.0
        e1 = st["strain"]
        w_load = dt * sum(ca.dot(vel[i], terms["loads"][i]) for i in free)
        w_drag = dt * sum(ca.dot(vel[i], terms["drag"][i]) for i in free)
        w_winch = st["tension"] * (ca.dot(st["num"] / st["den"], r1[n] - r0[n])
                                   - (1.0 + 0.5 * (e0 + e1)) * dl)
        w_in = dl * 0.5 * sum(self._energy_density(e, ea_top) for e in (e0, e1))
        if (n - 1) in free:
            k = free.index(n - 1)
            vv0, vv1 = v0[3 * k:3 * k + 3], v1[3 * k:3 * k + 3]
            w_in = w_in + 0.125 * float(pr["mass_per_length"][n - 1]) * dl * (
                ca.dot(vv0, vv0) + ca.dot(vv1, vv1))
        zero = ca.vertcat(z0, z1)
        balance = ca.Function("balance", [q0, v0, q1, l0, l1, t0, dt],
                              ca.substitute([w_load, w_drag, w_winch, w_in], [zero],
                                            [ca.DM.zeros(2)]))
        acc = (v1 - v0) / dt
        res = ca.vertcat(*[ca.mtimes(terms["mass"][i], acc[3 * k:3 * k + 3]) - f[i]
                           for k, i in enumerate(free)]) / self.force_scale
        pars = ca.vertcat(v0, l0, l1, t0, dt, q0, z0, z1)
        g = ca.Function("g", [q1, pars], [res])
        rf = ca.rootfinder("rf", "newton", g, {"abstol": self.tol, "max_iter": self.max_iter,
                                                "error_on_fail": False})
        guess = q0 + dt * v0 + ca.repmat(ca.vertcat(0.0, 0.0, z1 - z0), nf, 1)
        q1s = rf(guess, pars)
        step_out = [q1s, 2.0 * (q1s - q0) / dt - v0, ca.norm_inf(ca.substitute(res, q1, q1s))]
        names = (["q0", "v0", "l0", "l1", "t0", "dt"], ["q1", "v1", "residual"])
        step_top = ca.Function("step_top", [q0, v0, l0, l1, t0, dt, z0, z1], step_out,
                               names[0] + ["z0", "z1"], names[1])
        step = ca.Function("step", [q0, v0, l0, l1, t0, dt],
                           ca.substitute(step_out, [zero], [ca.DM.zeros(2)]), *names)
        # -- one level: tensions, energy and powers ---------------------------------------
        q, v, ell, t, ld = sx("q", 3 * nf), sx("v", 3 * nf), sx("l", n), sx("t"), sx("ld")
        z, zr = sx("z"), sx("z_rate")
        r = self._nodes(n, q, t, z)
        vv = [v[3 * k:3 * k + 3] for k in range(nf)]
        vb = self._winch_velocity(n, r, ell, ld, t, zr)
        if self.params.fixed_a:
            vv = [ca.SX.zeros(3)] + vv
        vall = vv + [vb]
        tens, strains, pot = [], [], 0
        for j in range(n):
            st = self._tension(n, j, r[j + 1] - r[j], ell[j])
            tens.append(st["tension"])
            strains.append(st["strain"])
            pot = pot + ell[j] * self._energy_density(st["strain"],
                                                      float(pr["axial_stiffness"][j]))
        d_top = r[n] - r[n - 1]
        t_hat = d_top / ca.norm_2(d_top)
        one = self._terms(n, r, vall, ell)
        # the force of the winch on the line: M_N a_b minus the forces on the winch's node
        # (the top segment's pull, its share of the weight, its drag), as the fixed-length
        # model's top_force
        # (the scene's top acceleration: the heave plant's extra height z is linear over
        # each step, and its top tension is the balance without the acceleration)
        acc_b = ca.jacobian(self._top_v(t, zr), t)
        f_n = -tens[-1] * t_hat + one["loads"][n] + one["drag"][n]
        top_force = ca.mtimes(one["mass"][n], acc_b) - f_n
        f_out = [ca.vertcat(*tens), ca.vertcat(*strains), top_force]
        forces_top = ca.Function("forces_top", [q, v, ell, t, ld, z, zr], f_out)
        still = ca.vertcat(z, zr)
        forces = ca.Function("forces", [q, v, ell, t, ld],
                             ca.substitute(f_out, [still], [ca.DM.zeros(2)]))
        kin = sum(0.5 * ca.dot(vall[i], ca.mtimes(one["mass"][i], vall[i])) for i in free)
        energy = ca.Function("energy", [q, v, ell, t, ld],
                             [ca.substitute(kin + pot, still, ca.DM.zeros(2))])
        self._fns[n] = out = {"step": step, "forces": forces, "energy": energy,
                              "balance": balance, "step_top": step_top,
                              "forces_top": forces_top}
        return out

    # -- states --------------------------------------------------------------------------
    def state(self, t: float, lengths: np.ndarray, q: np.ndarray, v: np.ndarray
              ) -> PayoutState:
        """The :class:`PayoutState` of the free nodes' positions ``q`` (m) and velocities
        ``v`` (m/s, node-major) at ``t`` (s) with the unstretched ``lengths`` (m).

        Parameters
        ----------
        t : float
            Time, s.
        lengths : ndarray (n,)
            Unstretched segment lengths, m.
        q, v : ndarray (3 n_free,)
            Free-node positions (m) and velocities (m/s).
        """
        n = len(lengths)
        fr = self.free(n)
        rr = np.zeros((n + 1, 3))
        vv = np.zeros((n + 1, 3))
        rr[fr] = np.asarray(q, float).reshape(-1, 3)
        vv[fr] = np.asarray(v, float).reshape(-1, 3)
        if self.params.fixed_a:
            rr[0] = np.asarray(self._a(t), float).ravel()
        rr[-1] = np.asarray(self._top(t, 0.0), float).ravel()
        ldot = self.length(t)[1]
        vv[-1] = (np.asarray(self._top_v(t, 0.0), float).ravel()
                  - ldot * (rr[-1] - rr[-2]) / lengths[-1])
        return PayoutState(float(t), np.asarray(lengths, float).copy(), rr, vv)

    def free_vectors(self, state: PayoutState) -> tuple[np.ndarray, np.ndarray]:
        """(q, v): the free nodes' positions (m) and velocities (m/s), node-major.

        Parameters
        ----------
        state : PayoutState
            The line.
        """
        fr = self.free(state.segments)
        return state.r[fr].reshape(-1).copy(), state.v[fr].reshape(-1).copy()

    def energy_of(self, state: PayoutState) -> float:
        """E (J): the free nodes' kinetic energy plus the strain energy.

        Parameters
        ----------
        state : PayoutState
            The line.
        """
        q, v = self.free_vectors(state)
        return float(self.functions(state.segments)["energy"](
            q, v, state.lengths, state.t, self.length(state.t)[1])[0])

    # -- events --------------------------------------------------------------------------
    def split(self, state: PayoutState) -> PayoutState:
        """A node enters at the winch: the top segment cut into l_e (below) and the rest.

        Parameters
        ----------
        state : PayoutState
            The line (its top segment longer than l_e).
        """
        le = self.element_length
        ltop = state.lengths[-1]
        f = le / ltop
        d = state.r[-1] - state.r[-2]
        chord = float(np.linalg.norm(d))
        n = state.segments
        pr = self.props(n)
        w_t = float(pr["weight_in_water"][n - 1]) * d[2] / chord
        # the lower part's strain less w_t (l_top - l_e) / (2 EA), the upper's more by
        # w_t l_e / (2 EA) (EA the tangent of a tension-strain table): the same stretched
        # length, and both nodes keep their balance
        eps = chord / ltop - 1.0
        table = self.params.tension_strain
        tangent = (float(pr["axial_stiffness"][n - 1]) if table is None
                   else float(table.tangent(eps)))  # dT/deps of the material, N
        eps_low = eps - w_t * (ltop - le) / (2.0 * tangent)
        rn = state.r[-2] + le * (1.0 + eps_low) * d / chord
        vn = state.v[-2] + f * (state.v[-1] - state.v[-2])
        lengths = np.concatenate([state.lengths[:-1], [le, ltop - le]])
        return PayoutState(state.t, lengths, np.insert(state.r, -1, rn, axis=0),
                           np.insert(state.v, -1, vn, axis=0))

    def can_merge(self, state: PayoutState) -> bool:
        """True when the top free node may leave: at least two segments, the one below of
        the top material, and no body or unit at the node."""
        n = state.segments
        return n >= 2 and n - 2 >= self.top_first and (n - 1) in self.free(n)

    def merge(self, state: PayoutState) -> PayoutState:
        """The top free node leaves at the winch: the top two segments joined.

        Parameters
        ----------
        state : PayoutState
            The line (:meth:`can_merge`).
        """
        n = state.segments
        m = self.node_masses(state.lengths)
        mu = float(self.props(n)["mass_per_length"][n - 1])
        v = state.v.copy()
        if (n - 2) in self.free(n):
            give = 0.5 * mu * state.lengths[-1]
            v[n - 2] = (m[n - 2] * v[n - 2] + give * v[n - 1]) / (m[n - 2] + give)
        lengths = np.concatenate([state.lengths[:-2], [state.lengths[-2] + state.lengths[-1]]])
        return PayoutState(state.t, lengths, np.delete(state.r, n - 1, axis=0),
                           np.delete(v, n - 1, axis=0))

    def lengths_at(self, lengths: np.ndarray, t: float) -> np.ndarray:
        """The segment lengths at ``t`` (s): the top one L(t) minus the others (m).

        Parameters
        ----------
        lengths : ndarray (n,)
            The current lengths, m (all but the top one are kept).
        t : float
            Time, s.
        """
        out = np.asarray(lengths, float).copy()
        out[-1] = self.length(t)[0] - float(np.sum(out[:-1]))
        return out

    # -- the run -------------------------------------------------------------------------
    def run(self, q0: np.ndarray, duration: float, dt: float, *, record_every: int = 1,
            energy: bool = False, progress: Callable[[float, float], None] | None = None
            ) -> PayoutRun:
        """Integrate from the free nodes' positions ``q0`` (m) at rest at t = 0.

        Parameters
        ----------
        q0 : ndarray (3 n_free,)
            Free-node positions at t = 0, m (with the line's segments at t = 0).
        duration : float
            Simulated time, s.
        dt : float
            Time step, s.
        record_every : int
            Steps per recorded state.
        energy : bool
            Sum each step's exact energy balance (``balance`` of :meth:`functions`;
            slower).
        progress : callable, optional
            ``progress(t_done, duration)`` (s), about 100 times.
        """
        wall = time.perf_counter()
        p = self.params
        lengths = self.lengths_at(p.segment_length, 0.0)
        q = np.asarray(q0, float).copy()
        v = np.zeros_like(q)
        st = self.state(0.0, lengths, q, v)
        out = PayoutRun(states=[], tensions=[])
        self._record(out, st)
        steps = int(round(duration / dt))
        en = None
        if energy:
            en = {"t": [0.0], "E": [self.energy_of(st)], "gravity": [0.0], "drag": [0.0],
                  "winch": [0.0], "inflow": [0.0], "events": [0.0]}
            acc = dict.fromkeys(("gravity", "drag", "winch", "inflow", "events"), 0.0)
        every_progress = max(1, steps // 100)
        for k in range(steps):
            t0 = k * dt
            n = lengths.size
            l1 = self.lengths_at(lengths, t0 + dt)
            if l1[-1] <= 0.0:
                out.status = "failed"
                out.message = (f"t = {t0 + dt:.6g} s: the top segment's unstretched length "
                               f"{l1[-1]:.3g} m is not positive; the haul-in is too fast for "
                               "the time step, or the line is hauled in completely")
                break
            fn = self.functions(n)
            q1, v1, resid = (np.asarray(a, float).ravel() for a in fn["step"](
                q, v, lengths, l1, t0, dt))
            if not (np.all(np.isfinite(q1)) and float(resid[0]) <= max(1e3 * self.tol, 1e-8)):
                out.status = "failed"
                out.message = (f"t = {t0:.6g} s: Newton did not converge (scaled residual "
                               f"{float(resid[0]):.3g}); take a smaller simulation.time_step")
                break
            if en is not None:
                works = fn["balance"](q, v, q1, lengths, l1, t0, dt)
                for key, val in zip(("gravity", "drag", "winch", "inflow"), works,
                                    strict=True):
                    acc[key] += float(val)
            st = self.state(t0 + dt, l1, q1, v1)
            st, ok = self._events(st, out, en is not None, acc if en is not None else None)
            lengths = st.lengths
            q, v = self.free_vectors(st)
            if not ok:
                out.status = "failed"
                out.message = (f"t = {st.t:.6g} s: the line is hauled in to a top segment of "
                               f"{lengths[-1]:.3g} m (< {MERGE} element lengths) and no node "
                               "can leave (the unit, a body or another material is next)")
            if (k + 1) % record_every == 0 or not ok:
                self._record(out, st)
                if en is not None:
                    en["t"].append(st.t)
                    en["E"].append(self.energy_of(st))
                    for key in acc:
                        en[key].append(acc[key])
            if not ok:
                break
            if progress is not None and (k + 1) % every_progress == 0:
                progress((k + 1) * dt, duration)
        if out.status == "solved":
            out.message = (f"{steps} steps; nodes that entered at the winch: {out.splits}, "
                           f"left: {out.merges} (element length {self.element_length:.4g} m)")
        if en is not None:
            out.energy = {k: np.asarray(val) for k, val in en.items()}
        out.wall_time_s = time.perf_counter() - wall
        return out

    def _events(self, st: PayoutState, out: PayoutRun, track: bool,
                acc: dict[str, float] | None) -> tuple[PayoutState, bool]:
        """Split and merge until the top segment is within the bounds."""
        while True:
            ltop = st.lengths[-1]
            if ltop > self.split_at:
                new, kind = self.split(st), "split"
                out.splits += 1
            elif ltop < self.merge_at and st.segments > 1:
                if not self.can_merge(st):
                    return st, False
                new, kind = self.merge(st), "merge"
                out.merges += 1
            else:
                return st, True
            ev: dict[str, Any] = {"t": st.t, "kind": kind, "segments": new.segments,
                                  "momentum_jump": (self.momentum(new)
                                                    - self.momentum(st)).tolist()}
            if track:
                ev["energy_jump"] = self.energy_of(new) - self.energy_of(st)
                acc["events"] += ev["energy_jump"]  # type: ignore[index]
            out.events.append(ev)
            st = new

    def _tensions(self, st: PayoutState) -> np.ndarray:
        return self._forces(st)[0]

    def _forces(self, st: PayoutState) -> list[np.ndarray]:
        q, v = self.free_vectors(st)
        return [np.asarray(a, float).ravel() for a in self.functions(st.segments)["forces"](
            q, v, st.lengths, st.t, self.length(st.t)[1])]

    def _record(self, out: PayoutRun, st: PayoutState) -> None:
        tens, strain, top = self._forces(st)
        out.states.append(st)
        out.tensions.append(tens)
        out.top_force.append(top)
        out.min_strain = min(out.min_strain, float(np.min(strain)))
