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
  ``c deps/dt`` while the segment is taut (the same smooth switch);
* at end_a a subsea unit (Huang eq. (5.6)): mass, added mass per axis, weight in water,
  drag area and coefficient, an external load (thrust); or end_a fixed;
* at end_b the prescribed top motion (5.5), a function of time.

Point bodies (clump weights, buoys, units on the line: the statics' ``[[bodies]]``) sit at
nodes with their own mass, added mass, weight in water, drag and load. Every segment has its
own properties (the statics' ``[[cable.segments]]``).

Time integration (see :class:`LumpedMassModel.step_function`): the default scheme is the
implicit midpoint rule with a discrete-gradient tension (the energy-momentum method of
Simo & Tarnow (1992) and Gonzalez (1996)), solved by Newton's method in a CasADi
``rootfinder`` and stepped by ``mapaccum``; ``"bdf2"`` is the L-stable alternative.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics.compile import CACHE_OFF, c_compiler, cache_dir, compile_function
from cable_ocp.physics.drag import DRAG_LAWS, drag_per_length
from cable_ocp.physics.smooth import smooth_abs

__all__ = [
    "SCHEMES",
    "LumpedMassModel",
    "LumpedParams",
    "LumpedRun",
    "PointBody",
    "UnitParams",
    "run",
    "uniform_params",
]

#: time-integration schemes of :meth:`LumpedMassModel.step_function`
SCHEMES = ("midpoint", "trapezoidal", "bdf2")

Vec3 = tuple[float, float, float]
#: a function of time (CasADi SX/MX or float) returning a 3-vector expression (m or m/s)
TimeFunction = Callable[[Any], Any]
#: a function of height z (m) returning the current velocity 3-vector (m/s)
CurrentFunction = Callable[[Any], Any]

# 3-point Gauss-Legendre rule on [-1, 1] (mean of the tension over a strain interval)
_GAUSS_X = (-math.sqrt(0.6), 0.0, math.sqrt(0.6))
_GAUSS_W = (5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0)


def _vec3(value: float | Sequence[float], name: str) -> Vec3:
    if isinstance(value, (int, float)):
        return (float(value),) * 3
    v = tuple(float(a) for a in value)
    if len(v) != 3:
        raise CableOCPError(f"{name} = {value!r}: expected a number or 3 numbers [x, y, z]")
    return v  # type: ignore[return-value]


@dataclass(frozen=True)
class UnitParams:
    """The subsea unit at end_a (Huang 1992, eq. (5.6)).

    Attributes
    ----------
    mass : float
        Mass M_0, kg (in addition to half the first segment's mass).
    added_mass : tuple of 3 float
        Added masses M_ax, M_ay, M_az along x, y, z, kg.
    weight_in_water : float
        Weight minus buoyancy, N (positive pulls down; Huang's (M_0 g - rho g V_0)).
    drag_area : tuple of 3 float
        Projected areas S_x, S_y, S_z, m^2.
    drag_coefficient : tuple of 3 float
        Drag coefficients C_Dx, C_Dy, C_Dz (-).
    drag_law : str
        ``"vector"``: D = 1/2 rho |u| diag(C_D S) u with the relative flow u (equals the
        statics' body drag 1/2 rho C_d A |U| U for equal areas), or ``"per_axis"``: Huang's
        eq. (5.6), D_k = 1/2 rho C_Dk S_k |u_k| u_k.
    force : tuple of 3 float
        Any other external load on the unit (thrust), N.
    """

    mass: float = 0.0
    added_mass: Vec3 = (0.0, 0.0, 0.0)
    weight_in_water: float = 0.0
    drag_area: Vec3 = (0.0, 0.0, 0.0)
    drag_coefficient: Vec3 = (0.0, 0.0, 0.0)
    drag_law: str = "vector"
    force: Vec3 = (0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        for name in ("added_mass", "drag_area", "drag_coefficient", "force"):
            object.__setattr__(self, name, _vec3(getattr(self, name), f"unit.{name}"))
        if self.mass < 0 or any(a < 0 for a in self.added_mass):
            raise CableOCPError("unit.mass and unit.added_mass must be >= 0 (kg)")
        if self.drag_law not in ("vector", "per_axis"):
            raise CableOCPError(
                f"unit.drag_law = {self.drag_law!r}: valid are 'vector', 'per_axis'")


@dataclass(frozen=True)
class PointBody:
    """A point body at an interior node (a clump weight, buoy or unit on the line).

    Attributes
    ----------
    node : int
        Node index, 1..N-1 (number of segments between end_a and the body).
    mass : float
        Mass, kg.
    added_mass : tuple of 3 float
        Added mass per axis, kg.
    weight_in_water : float
        Weight minus buoyancy, N (negative for a buoy).
    drag_area : float
        Projected area, m^2.
    drag_coefficient : float
        Drag coefficient (-); drag 1/2 rho C_d A |u| u (the statics' body drag).
    force : tuple of 3 float
        Any other external load (thrust), N.
    """

    node: int
    mass: float = 0.0
    added_mass: Vec3 = (0.0, 0.0, 0.0)
    weight_in_water: float = 0.0
    drag_area: float = 0.0
    drag_coefficient: float = 0.0
    force: Vec3 = (0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        object.__setattr__(self, "added_mass", _vec3(self.added_mass, "body.added_mass"))
        object.__setattr__(self, "force", _vec3(self.force, "body.force"))
        if self.mass < 0 or any(a < 0 for a in self.added_mass):
            raise CableOCPError("body mass and added_mass must be >= 0 (kg)")


def _const_fn(value: Sequence[float]) -> TimeFunction:
    v = [float(a) for a in value]

    def fn(t: Any) -> Any:  # noqa: ARG001 - constant
        return ca.DM(v)

    return fn


@dataclass(frozen=True, eq=False)
class LumpedParams:
    """Every input of the lumped-mass model, explicitly (SI units).

    Per-segment arrays have one entry per lumped segment, from end_a to end_b.

    Attributes
    ----------
    segment_length : ndarray (N,)
        Unstretched segment lengths l, m.
    axial_stiffness : ndarray (N,)
        EA, N (finite).
    diameter : ndarray (N,)
        Hydrodynamic diameter d, m (drag, added mass and displaced area pi d^2 / 4).
    mass_per_length : ndarray (N,)
        Mass per unstretched length mu, kg/m.
    weight_in_water : ndarray (N,)
        Weight in water per unstretched length w, N/m.
    normal_drag, tangential_drag : ndarray (N,)
        C_n (on d) and C_t (on the perimeter pi d), -.
    added_mass_coefficient : ndarray (N,)
        Normal added-mass coefficient C_a (-): added mass rho C_a pi d^2/4 per length.
    tangential_added_mass_coefficient : ndarray (N,)
        Tangential added-mass coefficient (-); Huang (1992) ch. 5 takes 0.
    axial_damping : ndarray (N,)
        Internal (material) damping c, N s: T = EA eps + c deps/dt while taut (default 0).
    top_position : callable
        r_b(t), m: end_b's prescribed position (a CasADi-compatible function of t).
    top_velocity : callable or None
        r_b'(t), m/s; None = differentiate ``top_position`` with CasADi.
    water_density : float
        kg/m^3 (0 for a cable in air: no drag, no added mass).
    gravity : float
        m/s^2.
    unit : UnitParams or None
        The subsea unit at a free end_a (zero mass and loads = a bare free end); None when
        end_a is fixed.
    end_a_position : callable or None
        r_a(t), m, when end_a is fixed (``unit`` must then be None).
    bodies : tuple of PointBody
        Point bodies at interior nodes.
    current : callable or None
        U(z), m/s: current velocity at height z (CasADi-compatible); None = still water.
    drag_law : str
        ``"vector"`` or ``"componentwise"`` (:mod:`cable_ocp.physics.drag`).
    smoothing : float
        Velocity scale of the smooth modulus in every |u| u, m/s.
    vertical_blend : float
        Vertical blend of the componentwise law (-).
    slack_smoothing : float
        Force scale delta_T of the smooth no-compression law, N.
    """

    segment_length: np.ndarray
    axial_stiffness: np.ndarray
    diameter: np.ndarray
    mass_per_length: np.ndarray
    weight_in_water: np.ndarray
    normal_drag: np.ndarray
    tangential_drag: np.ndarray
    added_mass_coefficient: np.ndarray
    tangential_added_mass_coefficient: np.ndarray
    top_position: TimeFunction
    axial_damping: np.ndarray | float = 0.0
    top_velocity: TimeFunction | None = None
    water_density: float = 1025.0
    gravity: float = 9.81
    unit: UnitParams | None = field(default_factory=UnitParams)
    end_a_position: TimeFunction | None = None
    bodies: tuple[PointBody, ...] = ()
    current: CurrentFunction | None = None
    drag_law: str = "vector"
    smoothing: float = 1e-5
    vertical_blend: float = 1e-2
    slack_smoothing: float = 1e-2

    def __post_init__(self) -> None:
        names = ("segment_length", "axial_stiffness", "diameter", "mass_per_length",
                 "weight_in_water", "normal_drag", "tangential_drag",
                 "added_mass_coefficient", "tangential_added_mass_coefficient",
                 "axial_damping")
        n = np.size(self.segment_length)
        for name in names:
            a = np.asarray(getattr(self, name), dtype=float).reshape(-1)
            if a.size == 1 and n > 1:
                a = np.full(n, float(a[0]))
            if a.size != n:
                raise CableOCPError(f"{name}: expected {n} values (one per segment), "
                                    f"got {a.size}")
            if not np.all(np.isfinite(a)):
                raise CableOCPError(f"{name}: expected finite numbers (an inextensible "
                                    "cable is not a lumped-mass model: give a finite EA)"
                                    if name == "axial_stiffness" else
                                    f"{name}: expected finite numbers")
            object.__setattr__(self, name, a)
        if n < 1:
            raise CableOCPError("segment_length: at least one segment is needed")
        if np.any(self.segment_length <= 0) or np.any(self.axial_stiffness <= 0):
            raise CableOCPError("segment_length and axial_stiffness must be > 0")
        for name in ("diameter", "mass_per_length", "normal_drag", "tangential_drag",
                     "added_mass_coefficient", "tangential_added_mass_coefficient",
                     "axial_damping"):
            if np.any(getattr(self, name) < 0):
                raise CableOCPError(f"{name} must be >= 0")
        if (self.unit is None) == (self.end_a_position is None):
            raise CableOCPError("give either a unit (free end_a) or end_a_position "
                                "(fixed end_a), not both and not neither")
        if self.drag_law not in DRAG_LAWS:
            raise CableOCPError(f"drag_law = {self.drag_law!r}: valid are {DRAG_LAWS}")
        for b in self.bodies:
            if not 1 <= b.node <= n - 1:
                raise CableOCPError(f"body at node {b.node}: valid nodes are 1..{n - 1}")
        if self.water_density < 0 or self.gravity < 0:
            raise CableOCPError("water_density and gravity must be >= 0")
        if not (self.smoothing > 0 and self.slack_smoothing > 0):
            raise CableOCPError("smoothing and slack_smoothing must be > 0")

    @property
    def segments(self) -> int:
        """Number of lumped segments N."""
        return int(self.segment_length.size)

    @property
    def node_arc_length(self) -> np.ndarray:
        """Unstretched arc length of the nodes from end_a, m, shape (N + 1,)."""
        return np.concatenate([[0.0], np.cumsum(self.segment_length)])

    @property
    def length(self) -> float:
        """Unstretched cable length L, m."""
        return float(self.segment_length.sum())

    @property
    def fixed_a(self) -> bool:
        """True when end_a is prescribed."""
        return self.end_a_position is not None


def uniform_params(length: float, segments: int, *, axial_stiffness: float, diameter: float,
                   mass_per_length: float, weight_in_water: float,
                   top_position: TimeFunction | Sequence[float],
                   normal_drag: float = 0.0, tangential_drag: float = 0.0,
                   added_mass_coefficient: float = 0.0,
                   tangential_added_mass_coefficient: float = 0.0,
                   axial_damping: float = 0.0, **kwargs: Any) -> LumpedParams:
    """Parameters of a uniform cable cut into ``segments`` equal segments.

    ``top_position`` may be a constant 3-vector (m); further keywords go to
    :class:`LumpedParams` (``unit``, ``end_a_position``, ``current``, ...). A constant
    ``end_a_position`` is accepted too.
    """
    if segments < 1:
        raise CableOCPError(f"segments = {segments}: must be >= 1")
    if not callable(top_position):
        top_position = _const_fn(top_position)
        kwargs.setdefault("top_velocity", _const_fn((0.0, 0.0, 0.0)))
    ea = kwargs.get("end_a_position")
    if ea is not None and not callable(ea):
        kwargs["end_a_position"] = _const_fn(ea)
        kwargs["unit"] = None
    elif ea is not None:
        kwargs["unit"] = None
    n = int(segments)
    return LumpedParams(
        segment_length=np.full(n, length / n), axial_stiffness=np.full(n, axial_stiffness),
        diameter=np.full(n, diameter), mass_per_length=np.full(n, mass_per_length),
        weight_in_water=np.full(n, weight_in_water), normal_drag=np.full(n, normal_drag),
        tangential_drag=np.full(n, tangential_drag),
        added_mass_coefficient=np.full(n, added_mass_coefficient),
        tangential_added_mass_coefficient=np.full(n, tangential_added_mass_coefficient),
        axial_damping=np.full(n, axial_damping), top_position=top_position, **kwargs)


# --------------------------------------------------------------------------------------
# The model
# --------------------------------------------------------------------------------------


def _next_state(scheme: str, x1: Any, z: Any, dt: Any, nf3: int) -> tuple[Any, Any]:
    """The stepped state from the new positions ``x1`` and the old stepped state ``z``
    (positions, velocities, then the scheme's history: the acceleration for the midpoint
    and trapezoidal rules, the previous positions and velocities and the start flag for
    BDF2); returns (new stepped state, new velocities)."""
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
        ``segment_tension(x, v, t) -> T`` (N), with the material damping term.
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
        self._node_mass = self._lumped_masses()
        self._node_weight = self._lumped_weights()
        self._top_vel = (p.top_velocity if p.top_velocity is not None
                         else self._derivative(p.top_position))
        self._a_vel = self._derivative(p.end_a_position) if p.fixed_a else None
        nf3 = 3 * self.n_free
        x = ca.SX.sym("x", nf3)
        v = ca.SX.sym("v", nf3)
        t = ca.SX.sym("t")
        r = self._all_positions(x, t)
        vel = self._all_velocities(v, t)
        f_el = self._elastic(r, None, vel, None)
        f_ext = self._static_loads()
        f_drag = self._drag(r, vel)
        f = self._free(self._sum(f_el, f_ext, f_drag))
        self.forces = ca.Function("forces", [x, v, t], [f], ["x", "v", "t"], ["F"])
        self.external_forces = ca.Function(
            "external_forces", [x, v, t], [self._free(self._sum(f_ext, f_drag))],
            ["x", "v", "t"], ["F"])
        self.mass_matrix = ca.Function("mass_matrix", [x, t], [self._mass_expr(r)],
                                       ["x", "t"], ["M"])
        tens, strain = self._tension_expr(r)
        self.tensions = ca.Function("tensions", [x, t], [tens, strain], ["x", "t"],
                                    ["T", "strain"])
        self.nodes = ca.Function("nodes", [x, t], [ca.horzcat(*r)], ["x", "t"], ["r"])
        self.node_velocities = ca.Function("node_velocities", [v, t], [ca.horzcat(*vel)],
                                           ["v", "t"], ["u"])
        self.segment_tension = ca.Function(
            "segment_tension", [x, v, t], [self._tension_expr(r, vel)[0]], ["x", "v", "t"],
            ["T"])
        # the force the attachment applies to node N: M_N a_b - (cable, weight, drag)
        acc_b = ca.jacobian(vel[-1], t)
        f_n = self._sum(self._elastic(r, None, vel, None), f_ext, f_drag)[-1]
        self.top_force = ca.Function(
            "top_force", [x, v, t], [ca.mtimes(self._mass_blocks(r)[-1], acc_b) - f_n],
            ["x", "v", "t"], ["F"])
        self.energy = ca.Function("energy", [x, v, t], list(self._energy_expr(v, r)),
                                  ["x", "v", "t"], ["kinetic", "potential"])
        f0 = self._free(self._sum(self._elastic(r, None, None, None), f_ext))
        self.static_stiffness = ca.Function(
            "static_stiffness", [x, t], [-ca.jacobian(f0, x)], ["x", "t"], ["K"])
        # at rest: every node, the prescribed ends included, has zero velocity
        still = [ca.SX.zeros(3) for _ in r]
        lam = ca.SX.sym("lam")  # load factor on the drag (continuation)
        fs = self._free(self._sum(self._elastic(r, None, None, None), f_ext,
                                  [lam * fd for fd in self._drag(r, still)]))
        self._static_fj = ca.Function("static_fj", [x, t, lam], [fs, ca.jacobian(fs, x)])
        self._steps: dict[tuple, ca.Function] = {}
        self._residuals: dict[tuple, ca.Function] = {}
        #: the scaled residual's inf-norm alone, per key of ``_residuals``
        self._residual_norms: dict[tuple, ca.Function] = {}

    # -- parameters ---------------------------------------------------------------------
    @staticmethod
    def _derivative(fn: TimeFunction) -> TimeFunction:
        ts = ca.SX.sym("t")
        dfun = ca.Function("d", [ts], [ca.jacobian(ca.vec(fn(ts)), ts)])

        def vel(t: Any) -> Any:
            return dfun(t)

        return vel

    def _lumped_masses(self) -> np.ndarray:
        """Node masses per axis (kg), shape (N+1, 3): half of each adjacent segment's mass
        plus the unit's or body's mass and added mass."""
        p = self.params
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

    def _lumped_weights(self) -> np.ndarray:
        """Downward weight in water at the nodes, N, shape (N+1,)."""
        p = self.params
        half = 0.5 * p.weight_in_water * p.segment_length
        w = np.zeros(p.segments + 1)
        w[:-1] += half
        w[1:] += half
        if p.unit is not None:
            w[0] += p.unit.weight_in_water
        for b in p.bodies:
            w[b.node] += b.weight_in_water
        return w

    @property
    def node_mass(self) -> np.ndarray:
        """Mass plus the added mass of units and bodies per node and axis, kg, shape
        (N+1, 3) (the cable's own added mass depends on the configuration: see
        :attr:`mass_matrix`)."""
        return self._node_mass.copy()

    @property
    def node_weight(self) -> np.ndarray:
        """Weight in water lumped at each node, N (positive down), shape (N+1,)."""
        return self._node_weight.copy()

    # -- assembling expressions ----------------------------------------------------------
    def _all_positions(self, x: Any, t: Any) -> list[Any]:
        p = self.params
        r = [x[3 * k:3 * k + 3] for k in range(self.n_free)]
        if p.fixed_a:
            r = [ca.vec(p.end_a_position(t))] + r
        return r + [ca.vec(p.top_position(t))]

    def _all_velocities(self, v: Any, t: Any) -> list[Any]:
        p = self.params
        u = [v[3 * k:3 * k + 3] for k in range(self.n_free)]
        if p.fixed_a:
            u = [ca.vec(self._a_vel(t))] + u
        return u + [ca.vec(self._top_vel(t))]

    def _free(self, f: list[Any]) -> Any:
        return ca.vertcat(*[f[i] for i in self.free_nodes])

    @staticmethod
    def _sum(*parts: list[Any]) -> list[Any]:
        return [sum(c[i] for c in parts) for i in range(len(parts[0]))]

    def _zero_list(self) -> list[Any]:
        return [ca.SX.zeros(3) for _ in range(self.params.segments + 1)]

    def _tension_of_strain(self, eps: Any, j: int) -> Any:
        """Smooth no-compression Hooke's law (5.3), N."""
        ea = float(self.params.axial_stiffness[j])
        dd = self.params.slack_smoothing
        u = ea * eps
        return 0.5 * (u + ca.sqrt(u * u + dd * dd))

    def _taut(self, eps: Any, j: int) -> Any:
        """Smooth switch 0 (slack) .. 1 (taut) of a segment, -."""
        ea = float(self.params.axial_stiffness[j])
        dd = self.params.slack_smoothing
        u = ea * eps
        return 0.5 * (1.0 + u / ca.sqrt(u * u + dd * dd))

    def _tension_expr(self, r: list[Any], vel: list[Any] | None = None) -> tuple[Any, Any]:
        """Segment tensions (N; with the material damping when velocities are given) and
        strains (-)."""
        p = self.params
        ts, es = [], []
        for j in range(p.segments):
            d = r[j + 1] - r[j]
            big_l = ca.norm_2(d)
            ell = float(p.segment_length[j])
            eps = big_l / ell - 1.0
            tens = self._tension_of_strain(eps, j)
            c = float(p.axial_damping[j])
            if vel is not None and c > 0:
                tens = tens + c * ca.dot(d, vel[j + 1] - vel[j]) / (big_l * ell) * self._taut(
                    eps, j)
            ts.append(tens)
            es.append(eps)
        return ca.vertcat(*ts), ca.vertcat(*es)

    def _elastic(self, r0: list[Any], r1: list[Any] | None, vel: list[Any] | None,
                 dt: float | None) -> list[Any]:
        """Segment tensions on the nodes, N.

        With ``r1 is None``: T(eps) along the segment at the positions r0 (material damping
        from the velocities ``vel``, none if ``vel`` is None). Else the discrete gradient
        between r0 and r1 over ``dt``: the mean of T over [eps0, eps1] (3-point Gauss)
        along (d0 + d1) / (|d0| + |d1|), and the damping c (|d1| - |d0|) / (l dt).
        """
        p = self.params
        f = self._zero_list()
        for j in range(p.segments):
            ell = float(p.segment_length[j])
            c = float(p.axial_damping[j])
            if r1 is None:
                d = r0[j + 1] - r0[j]
                big_l = ca.norm_2(d)
                eps = big_l / ell - 1.0
                tens = self._tension_of_strain(eps, j)
                if c > 0 and vel is not None:
                    rate = ca.dot(d, vel[j + 1] - vel[j]) / (big_l * ell)
                    tens = tens + c * rate * self._taut(eps, j)
                fe = tens * d / big_l
            else:
                d0 = r0[j + 1] - r0[j]
                d1 = r1[j + 1] - r1[j]
                l0 = ca.norm_2(d0)
                l1 = ca.norm_2(d1)
                e0 = l0 / ell - 1.0
                e1 = l1 / ell - 1.0
                em, de = 0.5 * (e0 + e1), 0.5 * (e1 - e0)
                tens = sum(w * self._tension_of_strain(em + g * de, j)
                           for g, w in zip(_GAUSS_X, _GAUSS_W, strict=True))
                if c > 0:
                    tens = tens + c * (l1 - l0) / (ell * dt) * self._taut(em, j)
                fe = tens * (d0 + d1) / (l0 + l1)
            f[j] = f[j] + fe
            f[j + 1] = f[j + 1] - fe
        return f

    def _static_loads(self) -> list[Any]:
        """Weights in water and the external loads of the unit and bodies, N."""
        p = self.params
        f = [ca.SX(ca.vertcat(0, 0, -float(w))) for w in self._node_weight]
        if p.unit is not None:
            f[0] = f[0] + ca.DM(p.unit.force)
        for b in p.bodies:
            f[b.node] = f[b.node] + ca.DM(b.force)
        return f

    def _drag(self, r: list[Any], vel: list[Any]) -> list[Any]:
        """Hydrodynamic drag with current on segments (half to each node), unit and bodies,
        N, at positions r and node velocities vel."""
        p = self.params
        f = self._zero_list()
        rho = p.water_density
        if rho == 0:
            return f
        for j in range(p.segments):
            if p.normal_drag[j] == 0 and p.tangential_drag[j] == 0:
                continue
            dm = r[j + 1] - r[j]
            lm = ca.norm_2(dm)
            u = -0.5 * (vel[j] + vel[j + 1])
            if p.current is not None:
                u = u + ca.vec(p.current(0.5 * (r[j][2] + r[j + 1][2])))
            fd = lm * drag_per_length(
                p.drag_law, u, dm / lm, rho=rho, diameter=float(p.diameter[j]),
                normal_drag=float(p.normal_drag[j]),
                tangential_drag=float(p.tangential_drag[j]), delta=p.smoothing,
                blend=p.vertical_blend)
            f[j] = f[j] + 0.5 * fd
            f[j + 1] = f[j + 1] + 0.5 * fd
        if p.unit is not None:
            un = p.unit
            f[0] = f[0] + self._point_drag(r[0], vel[0], un.drag_area, un.drag_coefficient,
                                           un.drag_law)
        for b in p.bodies:
            f[b.node] = f[b.node] + self._point_drag(
                r[b.node], vel[b.node], (b.drag_area,) * 3, (b.drag_coefficient,) * 3,
                "vector")
        return f

    def _point_drag(self, r: Any, v: Any, area: Vec3, coef: Vec3, law: str) -> Any:
        p = self.params
        cs = [a * c for a, c in zip(area, coef, strict=True)]
        if not any(cs):
            return ca.SX.zeros(3)
        u = -v
        if p.current is not None:
            u = u + ca.vec(p.current(r[2]))
        half_rho = 0.5 * p.water_density
        if law == "vector":
            speed = ca.sqrt(ca.dot(u, u) + p.smoothing**2)
            return half_rho * speed * ca.vertcat(*[cs[k] * u[k] for k in range(3)])
        return half_rho * ca.vertcat(*[cs[k] * smooth_abs(u[k], p.smoothing) * u[k]
                                       for k in range(3)])

    def _mass_expr(self, r: list[Any]) -> Any:
        """Block-diagonal mass matrix of the free nodes with the direction-dependent added
        mass of (5.2), kg."""
        blocks = self._mass_blocks(r)
        return ca.diagcat(*[blocks[i] for i in self.free_nodes])

    def _mass_blocks(self, r: list[Any]) -> list[Any]:
        """3x3 mass blocks of every node (kg), with the added mass of (5.2)."""
        p = self.params
        n = p.segments
        blocks = [ca.SX(ca.diag(ca.DM(self._node_mass[i]))) for i in range(n + 1)]
        area = math.pi * p.diameter**2 / 4.0
        for j in range(n):
            en = p.water_density * p.added_mass_coefficient[j] * area[j] * p.segment_length[j]
            et = (p.water_density * p.tangential_added_mass_coefficient[j] * area[j]
                  * p.segment_length[j])
            if en == 0 and et == 0:
                continue
            d = r[j + 1] - r[j]
            tt = ca.mtimes(d, d.T) / ca.dot(d, d)
            add = 0.5 * (en * (ca.SX.eye(3) - tt) + et * tt)
            blocks[j] = blocks[j] + add
            blocks[j + 1] = blocks[j + 1] + add
        return blocks

    def _energy_expr(self, v: Any, r: list[Any]) -> tuple[Any, Any]:
        """Kinetic energy 1/2 v^T M v and potential energy (strain + weight), J."""
        p = self.params
        kin = 0.5 * ca.dot(v, ca.mtimes(self._mass_expr(r), v))
        pot = 0
        dd = p.slack_smoothing
        for j in range(p.segments):
            ell = float(p.segment_length[j])
            ea = float(p.axial_stiffness[j])
            eps = ca.norm_2(r[j + 1] - r[j]) / ell - 1.0
            u = ea * eps
            # ell * int_0^eps T de with T = (EA e + sqrt((EA e)^2 + dd^2)) / 2
            pot = pot + ell * (ea * eps**2 / 4.0
                             + (u * ca.sqrt(u * u + dd * dd) + dd * dd * ca.asinh(u / dd))
                             / (4.0 * ea))
        for i in range(p.segments + 1):
            pot = pot + float(self._node_weight[i]) * r[i][2]
        return kin, pot

    # -- reference scales --------------------------------------------------------------
    def force_scale(self, x: np.ndarray | None = None, t: float = 0.0) -> float:
        """Force scale F of the scaled residual, N: the largest of the total weight in
        water, the largest segment tension at the positions ``x`` (if given) and 1 N."""
        f = max(float(np.abs(self._node_weight).sum()), 1.0)
        if x is not None:
            f = max(f, float(np.max(np.asarray(self.tensions(x, t)[0]))))
        return f

    # -- time stepping -----------------------------------------------------------------
    def state_size(self, scheme: str) -> int:
        """Length of the stepped state vector of ``scheme``.

        ``(x, v, a)`` for ``"midpoint"`` and ``"trapezoidal"`` (a: the acceleration, used by
        the trapezoidal rule and, for the midpoint rule, only by the Newton predictor);
        ``(x, v, x_prev, v_prev, started)`` for ``"bdf2"`` (started = 0 before the first
        step, which is then a backward-Euler step).
        """
        nf3 = 3 * self.n_free
        return 4 * nf3 + 1 if scheme == "bdf2" else 3 * nf3

    def initial_state(self, x: np.ndarray, v: np.ndarray | None = None,
                      scheme: str = "midpoint", t: float = 0.0) -> np.ndarray:
        """Stepped state of ``scheme`` from free-node positions (m) and velocities (m/s)
        at time t (s)."""
        x = np.asarray(x, float).reshape(-1)
        v = np.zeros_like(x) if v is None else np.asarray(v, float).reshape(-1)
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

        Schemes (all implicit, A-stable, second order; the equations of a step are solved for
        the new free-node positions x1):

        ``"midpoint"`` (default): the implicit midpoint rule with a discrete-gradient
            tension, x1 - x0 = dt (v0 + v1) / 2 and
            M(x_m) (v1 - v0) = dt [F_T(x0, x1) + F_other(x_m, (x1 - x0) / dt, t0 + dt/2)],
            where each segment pulls with T_bar (d0 + d1) / (|d0| + |d1|), T_bar the mean
            of T over [eps0, eps1] (3-point Gauss) and d the segment vectors at the two
            levels (the energy-momentum method of Simo & Tarnow (1992), Gonzalez (1996)).
            The elastic work then equals the change of the strain energy, weights are
            constant forces and the mass is constant in air, so an undamped run in air
            conserves the energy (up to the Newton tolerance and the quadrature of T where a
            segment turns slack). No numerical damping: |amplification| = 1 for every
            undamped linear mode, at any dt.
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
            step = self._fast_step(dt, scheme, tol, max_iter, linear_solver, compile_kernel,
                                   force_scale)
            self._steps[key] = step
            return step
        p = self.params
        nf3 = 3 * self.n_free
        fscale = self.force_scale() if force_scale is None else float(force_scale)
        x1 = ca.SX.sym("x1", nf3)
        x0 = ca.SX.sym("x0", nf3)
        v0 = ca.SX.sym("v0", nf3)
        t0 = ca.SX.sym("t0")
        t1 = t0 + dt
        if scheme == "midpoint":
            a0 = ca.SX.sym("a0", nf3)
            r0 = self._all_positions(x0, t0)
            r1 = self._all_positions(x1, t1)
            rm = [0.5 * (a + b) for a, b in zip(r0, r1, strict=True)]
            vm = (x1 - x0) / dt

            def velocities(vf: Any) -> list[Any]:
                vel = [vf[3 * k:3 * k + 3] for k in range(self.n_free)]
                if p.fixed_a:
                    vel = [(r1[0] - r0[0]) / dt] + vel
                return vel + [(r1[-1] - r0[-1]) / dt]

            f_el = self._free(self._elastic(r0, r1, velocities(vm), dt))
            drag = self._free(self._drag(rm, velocities(vm)))
            mass = self._mass_expr(rm)
            v1 = 2.0 * vm - v0
            inert = ca.mtimes(mass, v1 - v0) / dt
            extra = ca.vertcat(x0, v0, a0, t0)
            guess = x0 + dt * v0 + 0.5 * dt * dt * a0
            z = ca.vertcat(x0, v0, a0)
        elif scheme == "trapezoidal":
            a0 = ca.SX.sym("a0", nf3)
            r1 = self._all_positions(x1, t1)
            v1 = 2.0 * (x1 - x0) / dt - v0
            a1 = 2.0 * (v1 - v0) / dt - a0
            vel1 = self._all_velocities(v1, t1)
            f_el = self._free(self._elastic(r1, None, vel1, None))
            drag = self._free(self._drag(r1, vel1))
            mass = self._mass_expr(r1)
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
            r1 = self._all_positions(x1, t1)
            vel1 = self._all_velocities(v1, t1)
            f_el = self._free(self._elastic(r1, None, vel1, None))
            drag = self._free(self._drag(r1, vel1))
            mass = self._mass_expr(r1)
            inert = ca.mtimes(mass, a1)
            extra = ca.vertcat(x0, v0, xp, vp, started, t0)
            guess = x0 + dt * v0 + started * (x0 - xp - dt * v0)
            z = ca.vertcat(x0, v0, xp, vp, started)
        f_ext = self._free(self._static_loads())
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
        z1, _ = _next_state(scheme, x1m, zs, dt, nf3)
        eps = self.tensions(x1m, ts + dt)[1]
        emin = ca.mmin(eps)
        step = ca.Function(f"step_{scheme}", [zs, ts],
                           [z1, resid, iters, emin, ca.find(eps <= emin)],
                           ["z", "t0"], ["z1", "residual", "iterations", "min_strain",
                                         "slack_segment"])
        self._steps[key] = step
        return step

    # -- the fast Newton step ------------------------------------------------------------
    def _segment_parameters(self) -> np.ndarray:
        """Kernel parameters per segment, shape (12, N) (:data:`_KERNEL_PARAMS`)."""
        p = self.params
        area = math.pi * p.diameter**2 / 4.0
        rows = {
            "l": p.segment_length, "ea": p.axial_stiffness, "c": p.axial_damping,
            "d": p.diameter, "cn": p.normal_drag, "ct": p.tangential_drag,
            "en": p.water_density * p.added_mass_coefficient * area * p.segment_length,
            "et": (p.water_density * p.tangential_added_mass_coefficient * area
                   * p.segment_length),
            "rho": np.full(p.segments, p.water_density),
            "delta": np.full(p.segments, p.smoothing),
            "delta_t": np.full(p.segments, p.slack_smoothing),
            "blend": np.full(p.segments, p.vertical_blend)}
        return np.vstack([rows[k] for k in _KERNEL_PARAMS])

    def _ends_function(self) -> ca.Function:
        """``ends(t) -> (r_a, v_a, r_b, v_b)``: prescribed end positions and velocities (a
        zeros when end_a is free)."""
        p = self.params
        t = ca.SX.sym("t")
        if p.fixed_a:
            ra, va = ca.vec(p.end_a_position(t)), ca.vec(self._a_vel(t))
        else:
            ra, va = ca.SX.zeros(3), ca.SX.zeros(3)
        return ca.Function("ends", [t], [ra, va, ca.vec(p.top_position(t)),
                                         ca.vec(self._top_vel(t))])

    def _point_terms(self, r: Any, v: Any, gamma: Any, sym: Any = ca.MX) -> tuple[Any, Any]:
        """Drag (N, 3 x (N+1)) and its Newton blocks (9 x (N+1)) of the unit and the bodies
        at node positions r and velocities v (MX, 3 x (N+1))."""
        p = self.params
        n = p.segments
        items = []
        if p.unit is not None:
            items.append((0, [a * c for a, c in zip(p.unit.drag_area, p.unit.drag_coefficient,
                                                    strict=True)], p.unit.drag_law))
        items += [(b.node, [b.drag_area * b.drag_coefficient] * 3, "vector")
                  for b in p.bodies]
        items = [it for it in items if any(it[1]) and p.water_density > 0]
        fcols = [sym.zeros(3, 1) for _ in range(n + 1)]
        ccols = [sym.zeros(9, 1) for _ in range(n + 1)]
        if not items:
            return ca.horzcat(*fcols), ca.horzcat(*ccols)
        rs, vs, gs = ca.SX.sym("r", 3), ca.SX.sym("v", 3), ca.SX.sym("g")
        eye = ca.SX.eye(3)
        for node, cs, law in items:
            u = -vs
            if p.current is not None:
                u = u + ca.vec(p.current(rs[2]))
            half_rho = 0.5 * p.water_density
            if law == "vector":
                sp = ca.sqrt(ca.dot(u, u) + p.smoothing**2)
                f = half_rho * sp * ca.vertcat(*[cs[k] * u[k] for k in range(3)])
                dmat = half_rho * ca.mtimes(ca.diag(ca.DM(cs)),
                                            sp * eye + ca.mtimes(u, u.T) / sp)
                dmat = 0.5 * (dmat + dmat.T)
            else:
                f = half_rho * ca.vertcat(*[cs[k] * smooth_abs(u[k], p.smoothing) * u[k]
                                            for k in range(3)])
                dmat = half_rho * ca.diag(ca.vertcat(*[
                    cs[k] * (smooth_abs(u[k], p.smoothing)
                             + u[k] ** 2 / smooth_abs(u[k], p.smoothing)) for k in range(3)]))
            fn = ca.Function("point_drag", [rs, vs, gs], [f, ca.vec(gs * dmat)])
            fk, ck = fn(r[:, node], v[:, node], gamma)
            fcols[node] = fcols[node] + fk
            ccols[node] = ccols[node] + ck
        return ca.horzcat(*fcols), ca.horzcat(*ccols)

    def _residual_function(self, scheme: str, compile_kernel: bool, fscale: float
                           ) -> ca.Function:
        """``gj(x1, z, t0, dt)``: the step's scaled residual and, for the MX path, the
        Newton matrix and force residual (``(res, J, f)``), or, for the SX path, the
        Newton update by block elimination (``(res, dx)``). Cached: one function for
        every step size (the step halving reuses it)."""
        key = (scheme, compile_kernel, fscale)
        if key in self._residuals:
            return self._residuals[key]
        p = self.params
        n = p.segments
        nf = self.n_free
        nf3 = 3 * nf
        first = 1 if p.fixed_a else 0
        kern = _segment_kernel(p.drag_law, compile_kernel).map(n, "serial")
        if not compile_kernel:
            kern = _segment_kernel_expr(p.drag_law).map(n, "unroll")
        par = ca.DM(self._segment_parameters())
        ends = self._ends_function()
        node_m = ca.DM(np.vstack([np.diag(m).T.reshape(-1) for m in self._node_mass]).T)
        static = np.zeros((3, n + 1))
        static[2] = -self._node_weight
        if p.unit is not None:
            static[:, 0] += p.unit.force
        for b in p.bodies:
            static[:, b.node] += b.force
        static = ca.DM(static)
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
        zsym = sym.sym("z", self.state_size(scheme))
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
        if cur is not None:
            ucur = cur(0.5 * (rm[2, 0:n] + rm[2, 1:n + 1]))
        else:
            ucur = sym.zeros(3, n)
        fa, fb, madd, kb, cb = kern(r0[:, 0:n], r0[:, 1:n + 1], r1[:, 0:n], r1[:, 1:n + 1],
                                    vel[:, 0:n], vel[:, 1:n + 1], ucur, par, scv)
        z3 = sym.zeros(3, 1)
        z9 = sym.zeros(9, 1)
        fpt, cpt = self._point_terms(rm, vel, gamma, sym)
        force = ca.horzcat(fa, z3) + ca.horzcat(z3, fb) + static + fpt
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
        vals = ca.vertcat(ca.vec(diag_b), ca.vec(off_b))
        if compile_kernel:
            jac = ca.MX(sp, 0)
            jac.nz[:] = vals[src_sorted]
            gj = ca.Function("gj", [x1, zsym, t0, dt], [res, jac, fres])
        else:
            # the Newton update by block-tridiagonal elimination (3x3 blocks, no pivoting:
            # the matrix is close to symmetric positive definite), inlined in SX
            dx_sx = _block_thomas(diag_b, off_b, ca.reshape(fres, 3, nf))
            gj = ca.Function("gj", [x1, zsym, t0, dt], [res, dx_sx])
        # the residual alone (the SX graph keeps only its part: about a third of gj's
        # operations), to check an iterate accepted on the contraction estimate
        self._residual_norms[key] = ca.Function("g", [x1, zsym, t0, dt], [ca.norm_inf(res)])
        self._residuals[key] = gj
        return gj

    def _core_step(self, dt: float, scheme: str, tol: float, max_iter: int,
                   linear_solver: str, compile_kernel: bool, force_scale: float | None
                   ) -> ca.Function:
        """One Newton-solved step ``(z, t0) -> (z1, residual, iterations, converged)``."""
        p = self.params
        nf3 = 3 * self.n_free
        fscale = self.force_scale() if force_scale is None else float(force_scale)
        x_scale = p.length + float(np.max(np.abs(np.asarray(p.top_position(0.0)))))
        gj4 = self._residual_function(scheme, compile_kernel, fscale)
        zsym = ca.MX.sym("z", self.state_size(scheme))
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
            dx = _switch("maybe_solve", skip, no_step, solve, jk, fk)
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
        r_chk = _switch("maybe_check", check, chk, no_chk, xk - dx, zsym, t0)
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
        resid = _switch("final_residual", done, known, last, rni, xi, zsym, t0)
        x1m = xi
        z1, _ = _next_state(scheme, x1m, zsym, dt, nf3)
        return ca.Function(f"core_{scheme}", [zsym, t0], [z1, resid, count, done])

    def _halving_step(self, dt: float, scheme: str, tol: float, max_iter: int,
                      linear_solver: str, compile_kernel: bool, force_scale: float | None,
                      halvings: int) -> ca.Function:
        """``(z, t0) -> (z1, residual, iterations, converged)``: the core step; where its
        Newton iteration does not converge, two steps of dt/2 instead (recursively, at
        most ``halvings`` times; only for the one-step schemes)."""
        core = self._core_step(dt, scheme, tol, max_iter, linear_solver, compile_kernel,
                               force_scale)
        if halvings <= 0 or scheme == "bdf2":
            return core
        half = self._halving_step(0.5 * dt, scheme, tol, max_iter, linear_solver,
                                  compile_kernel, force_scale, halvings - 1)
        z = ca.MX.sym("z", self.state_size(scheme))
        t0 = ca.MX.sym("t0")
        za, ra, ia, da = half(z, t0)
        zb, rb, ib, db = half(za, t0 + 0.5 * dt)
        two = ca.Function("two_halves", [z, t0],
                          [ca.vertcat(zb, ca.fmax(ra, rb), ia + ib, da * db)])
        z1, r1, i1, d1 = core(z, t0)
        y = ca.MX.sym("y", z.shape[0] + 3)
        keep = ca.Function("keep", [y, z, t0], [y])
        halves = ca.Function("halves", [y, z, t0], [two(z, t0)])
        packed = _switch("halving_select", d1, keep, halves, ca.vertcat(z1, r1, i1, d1), z, t0)
        n = z.shape[0]
        return ca.Function(f"halving_{scheme}", [z, t0],
                           [packed[0:n], packed[n], packed[n + 1], packed[n + 2]])

    def _fast_step(self, dt: float, scheme: str, tol: float, max_iter: int,
                   linear_solver: str, compile_kernel: bool, force_scale: float | None,
                   halvings: int = 3) -> ca.Function:
        """The ``"newton"`` solver of :meth:`step_function` (see there)."""
        step = self._halving_step(dt, scheme, tol, max_iter, linear_solver, compile_kernel,
                                  force_scale, halvings)
        nf3 = 3 * self.n_free
        z = ca.MX.sym("z", self.state_size(scheme))
        t0 = ca.MX.sym("t0")
        z1, resid, count, _ = step(z, t0)
        eps = self.tensions(z1[0:nf3], t0 + dt)[1]
        emin = ca.mmin(eps)
        return ca.Function(f"step_{scheme}", [z, t0],
                           [z1, resid, count, emin, ca.find(eps <= emin)],
                           ["z", "t0"], ["z1", "residual", "iterations", "min_strain",
                                         "slack_segment"])

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
        fscale = max(float(np.abs(self._node_weight).max()), float(np.abs(tens).max()), 1.0)
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
        """
        k = np.asarray(self.static_stiffness(x, t))
        m = np.asarray(ca.densify(self.mass_matrix(x, t)))
        return 0.5 * (k + k.T), 0.5 * (m + m.T)

    def modes(self, x: np.ndarray, count: int | None = None, t: float = 0.0
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Natural frequencies and mode shapes about the rest state ``x``.

        Solves K phi = omega^2 M phi (:meth:`linearize`).

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


@dataclass
class LumpedRun:
    """A time-domain run of the lumped-mass model (recorded every ``record_every`` steps).

    Attributes
    ----------
    status : str
        ``"solved"``, ``"failed"`` (a Newton step did not converge: the run stops there) or
        ``"interrupted"``.
    message : str
        Detail of the status.
    t : ndarray (n,)
        Record times, s.
    x, v : ndarray (n, 3 n_free)
        Free-node positions (m) and velocities (m/s).
    positions : ndarray (n, N + 1, 3)
        All node positions from end_a to end_b, m.
    velocities : ndarray (n, N + 1, 3) or None
        All node velocities, m/s.
    tension : ndarray (n, N)
        Segment tensions, N.
    top_force : ndarray (n, 3)
        Force of end_b's attachment on the cable, N (:attr:`LumpedMassModel.top_force`);
        its norm is the top tension.
    strain : ndarray (n, N)
        Segment strains (-); <= 0 means slack.
    residual : ndarray (n,)
        Largest scaled Newton residual over the steps since the previous record, m/s^2.
    scheme : str
    time_step : float
        s.
    steps : int
        Time steps taken.
    wall_time_s : float
        Wall time of the stepping, s (excludes building the CasADi functions).
    build_time_s : float
        Time to build the step and chunk functions, s.
    mean_iterations : float
        Newton iterations per step, on average (NaN for the ``rootfinder`` solver).
    compiled : str
        What ran as compiled C: ``"step"``, ``"kernel"`` or ``"none"``.
    min_strain : float
        Smallest segment strain over every step (-); <= 0 means a segment went slack.
    slack : tuple (time, segment) or None
        End time of the first step with a slack segment (s) and that segment's index from
        end_a (the one with the smallest strain), or None.
    """

    status: str
    message: str
    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    positions: np.ndarray
    velocities: np.ndarray | None
    tension: np.ndarray
    strain: np.ndarray
    top_force: np.ndarray
    residual: np.ndarray
    scheme: str
    time_step: float
    steps: int
    wall_time_s: float
    build_time_s: float
    mean_iterations: float = math.nan
    compiled: str = "none"
    min_strain: float = math.nan
    slack: tuple[float, int] | None = None

    @property
    def success(self) -> bool:
        """True when every step converged."""
        return self.status == "solved"


def run(model: LumpedMassModel, x0: np.ndarray, v0: np.ndarray | None, duration: float,
        time_step: float, *, scheme: str = "midpoint", record_every: int = 1,
        chunk_records: int | None = None, t0: float = 0.0, tol: float = 1e-10,
        max_iter: int = 20, solver: str = "newton", compile: str | bool = "kernel",
        progress: Callable[[float, float], Any] | None = None) -> LumpedRun:
    """Integrate the lumped-mass model from (x0, v0) at t0 over ``duration`` seconds.

    Steps are chained with ``mapaccum`` in chunks: no Python runs per time step. After each
    chunk ``progress(t_done, duration)`` is called (s, s) if given. A step whose scaled
    Newton residual stays above max(1000 tol, 1e-6) (or is NaN) stops the run with status
    ``"failed"`` at the last good record.

    Parameters
    ----------
    model : LumpedMassModel
    x0, v0 : ndarray (3 n_free,)
        Initial free-node positions (m) and velocities (m/s; None = at rest).
    duration : float
        Simulated time, s.
    time_step : float
        s; reduced if needed so that a whole number of steps (and of records) fills
        ``duration``.
    scheme : {"midpoint", "trapezoidal", "bdf2"}
        See :meth:`LumpedMassModel.step_function`.
    record_every : int
        Keep every k-th step.
    chunk_records : int, optional
        Records per chunk (default: about 20 chunks).
    tol : float
        Newton tolerance on the residual scaled by the force scale (-; the largest of the
        total weight in water and the largest tension at the start).
    max_iter : int
        Newton iterations per step.
    solver : {"newton", "rootfinder"}
        See :meth:`LumpedMassModel.step_function`.
    compile : {"kernel", "step", False}
        ``"kernel"`` (default): the per-segment kernel is compiled to C once per machine
        (cached; needs a C compiler, else interpreted); ``"step"``: the whole chunk of
        steps (Newton iterations, linear solves) is generated as C and compiled, cached by
        the hash of its code (a few seconds per new scene and time step; fastest);
        False: everything interpreted by CasADi's virtual machine. All give the same
        numbers up to rounding.
    progress : callable, optional
        ``progress(t_done, duration)`` after each chunk (s, s).
    """
    import time

    if compile not in ("kernel", "step", False):
        raise CableOCPError(f"compile = {compile!r}: valid are 'kernel', 'step', False")

    if not duration > 0:
        raise CableOCPError(f"duration = {duration}: must be > 0")
    k = max(1, int(record_every))
    n_steps = max(1, int(math.ceil(duration / time_step - 1e-9)))
    n_steps = int(math.ceil(n_steps / k) * k)
    dt = duration / n_steps
    n_rec = n_steps // k
    c = chunk_records or max(1, int(math.ceil(n_rec / 20)))
    c = min(c, n_rec)
    tb = time.perf_counter()
    x0 = np.asarray(x0, float).reshape(-1)
    fscale = model.force_scale(x0, t0)
    step = model.step_function(dt, scheme, tol=tol, max_iter=max_iter, solver=solver,
                               compile_kernel=compile == "kernel", force_scale=fscale)
    zs = ca.MX.sym("z", step.size1_in(0))
    ts = ca.MX.sym("t")
    # a record = k steps: last state, largest residual, iterations, smallest strain, the
    # first step (0..k-1) that ends slack (k: none) and its slack segment
    acc = step.mapaccum("acc", k)
    zk, rk, ik, ek, sk = acc(zs, ts + dt * ca.DM(np.arange(k).reshape(1, -1)))
    first = ca.find((ek <= 0.0).T)
    seg_first = ca.dot(sk.T, ca.DM(np.arange(k)) == first)
    rec = ca.Function("rec", [zs, ts], [zk[:, -1], ca.mmax(rk), ca.sum2(ik), ca.mmin(ek),
                                        first, seg_first])
    # one chunk function; the last chunk is padded beyond the end and cut
    chunk = rec.mapaccum("chunk", c)
    compiled = "none"
    if compile == "kernel" and solver == "newton" and _segment_kernel(
            model.params.drag_law, True).class_name() == "External":
        compiled = "kernel"
    if compile == "step":
        cc = _compile(chunk, "-O1")  # -O2: 4x the compile time, the same speed here
        compiled = "step" if cc is not chunk else "none"
        chunk = cc
    build = time.perf_counter() - tb
    z = model.initial_state(x0, v0, scheme, t0)
    nf3 = 3 * model.n_free
    zs_out = [z[None, :]]
    res_out = [np.zeros(1)]
    times = [np.array([t0])]
    iterations = 0.0
    slack: tuple[float, int] | None = None
    min_strain = math.inf
    status, message = "solved", f"{n_steps} steps of {dt:.6g} s ({scheme})"
    tw = time.perf_counter()
    done = 0
    tol_fail = max(1e3 * tol, 1e-6)
    while done < n_rec:
        m = min(c, n_rec - done)
        tstart = t0 + dt * k * (done + np.arange(c))
        zc, rc, ic, ec, fc, sc = chunk(z, tstart[None, :])
        zc = np.asarray(zc).T[:m]
        rc = np.asarray(rc).reshape(-1)[:m]
        tstart = tstart[:m]
        ic = np.asarray(ic).reshape(-1)[:m]
        ec = np.asarray(ec).reshape(-1)[:m]
        fc = np.asarray(fc).reshape(-1)[:m]
        sc = np.asarray(sc).reshape(-1)[:m]
        found = (fc >= 0) & (fc < k)  # casadi.find returns k when nothing is found
        if slack is None and np.any(found):
            j = int(np.flatnonzero(found)[0])
            slack = (float(tstart[j] + dt * (fc[j] + 1)), int(round(sc[j])))
        min_strain = min(min_strain, float(np.min(ec)))
        bad = np.flatnonzero(~np.isfinite(rc) | (rc > tol_fail)
                             | ~np.all(np.isfinite(zc), axis=1))
        iterations += float(np.nansum(ic[:bad[0]] if bad.size else ic))
        if bad.size:
            b = int(bad[0])
            zs_out.append(zc[:b])
            res_out.append(rc[:b])
            times.append(tstart[:b] + dt * k)
            status = "failed"
            message = (f"Newton did not converge in a step ending by t = "
                       f"{tstart[b] + dt * k:.6g} s (scaled residual {rc[b]:.3g} > "
                       f"{tol_fail:.3g}); the history stops at the last good record: a "
                       "smaller time step may help")
            break
        zs_out.append(zc)
        res_out.append(rc)
        times.append(tstart + dt * k)
        z = zc[-1]
        done += m
        if progress is not None:
            progress(min(done * k * dt, duration), duration)
    wall = time.perf_counter() - tw
    zall = np.concatenate(zs_out)
    tall = np.concatenate(times)
    xs, vs = zall[:, :nf3], zall[:, nf3:2 * nf3]
    n = len(tall)
    pos = np.asarray(model.nodes.map(n)(xs.T, tall[None, :]))
    positions = pos.reshape(3, n, model.params.segments + 1).transpose(1, 2, 0)
    vel = np.asarray(model.node_velocities.map(n)(vs.T, tall[None, :]))
    velocities = vel.reshape(3, n, model.params.segments + 1).transpose(1, 2, 0)
    strain = model.tensions.map(n)(xs.T, tall[None, :])[1]
    tens = model.segment_tension.map(n)(xs.T, vs.T, tall[None, :])
    ftop = np.asarray(model.top_force.map(n)(xs.T, vs.T, tall[None, :])).T
    steps = (len(tall) - 1) * k
    return LumpedRun(
        status=status, message=message, t=tall, x=xs, v=vs, positions=positions,
        velocities=velocities,
        tension=np.asarray(tens).T, strain=np.asarray(strain).T, top_force=ftop,
        residual=np.concatenate(res_out), scheme=scheme, time_step=dt,
        steps=steps, wall_time_s=wall, build_time_s=build,
        mean_iterations=iterations / max(steps, 1), compiled=compiled,
        min_strain=min_strain, slack=slack)


# --------------------------------------------------------------------------------------
# Per-segment kernel of the time step (compiled once, mapped over the segments)
# --------------------------------------------------------------------------------------

#: segment parameters fed to the kernel, in this order
_KERNEL_PARAMS = ("l", "ea", "c", "d", "cn", "ct", "en", "et", "rho", "delta", "delta_t",
                  "blend")


def _segment_kernel_expr(drag_law: str) -> ca.Function:
    """One segment's contribution to a time step, as a CasADi Function (SX).

    Inputs: node positions at the two levels ``ra0, rb0, ra1, rb1`` (m), node velocities
    ``va, vb`` (m/s, for the drag and the material damping), the current ``u`` at the
    segment's mid-height (m/s), the parameters ``par`` (:data:`_KERNEL_PARAMS`) and
    ``sc = (dt, mid, beta, gamma)``.

    With ``mid = 1`` the tension is the discrete gradient between the levels (mean of T
    over [eps0, eps1] along (d0 + d1) / (|d0| + |d1|)) and the damping c (|d1| - |d0|) /
    (l dt); with ``mid = 0`` (and r0 = r1) it is T(eps1) along d1 and c d1.(vb - va) /
    (|d1| l). Drag and added mass are taken at the mean positions (r0 + r1) / 2.

    Outputs: the forces on nodes a and b (N), the added-mass share of each node (3x3,
    kg, row-major 9-vector), and the Newton blocks ``kb`` (the tension's stiffness: the
    derivative of the mean tension along e e^T plus T / |d| across, times beta = 1/2 for
    the midpoint, 1 otherwise; plus gamma (c/l) H e e^T) and ``cb`` = gamma |d| D / 4
    (N/m) of :meth:`LumpedMassModel.step_function`.
    """
    ra0, rb0, ra1, rb1, va, vb, u_c = (ca.SX.sym(n, 3) for n in
                                       ("ra0", "rb0", "ra1", "rb1", "va", "vb", "u"))
    par = ca.SX.sym("par", len(_KERNEL_PARAMS))
    sc = ca.SX.sym("sc", 4)
    ell, ea, c, d, cn, ct, en, et, rho, delta, delta_t, blend = (par[k] for k in range(12))
    dt, mid, beta, gamma = sc[0], sc[1], sc[2], sc[3]

    def tension(eps: Any) -> Any:
        u = ea * eps
        return 0.5 * (u + ca.sqrt(u * u + delta_t * delta_t))

    def taut(eps: Any) -> Any:
        u = ea * eps
        return 0.5 * (1.0 + u / ca.sqrt(u * u + delta_t * delta_t))

    d0 = rb0 - ra0
    d1 = rb1 - ra1
    l0 = ca.norm_2(d0)
    l1 = ca.norm_2(d1)
    e0 = l0 / ell - 1.0
    e1 = l1 / ell - 1.0
    em, de = 0.5 * (e0 + e1), 0.5 * (e1 - e0)
    tbar = sum(w * tension(em + g * de) for g, w in zip(_GAUSS_X, _GAUSS_W, strict=True))
    # derivative of the Gauss mean with respect to eps1 (the midpoint's Newton matrix)
    dtbar = sum(w * ea * taut(em + g * de) * 0.5 * (1.0 + g)
                for g, w in zip(_GAUSS_X, _GAUSS_W, strict=True))
    rate = mid * (l1 - l0) / (ell * dt) + (1.0 - mid) * ca.dot(d1, vb - va) / (l1 * ell)
    tbar = tbar + c * rate * taut(em)
    f_el = tbar * (d0 + d1) / (l0 + l1)
    # drag and added mass at the mean positions
    dm = 0.5 * (d0 + d1)
    lm = ca.norm_2(dm)
    tm = dm / lm
    urel = u_c - 0.5 * (va + vb)
    f_d = lm * drag_per_length(drag_law, urel, tm, rho=1.0, diameter=1.0, normal_drag=1.0,
                               tangential_drag=0.0, delta=delta, blend=blend) * (rho * cn * d)
    ut = ca.dot(urel, tm)
    f_d = f_d + lm * 0.5 * rho * ct * math.pi * d * ca.sqrt(ut * ut + delta * delta) * ut * tm
    eye = ca.SX.eye(3)
    eet = ca.mtimes(tm, tm.T)
    madd = 0.5 * (en * (eye - eet) + et * eet)
    # Newton blocks
    # d(T u)/d d1 with u = (d0 + d1) / (|d0| + |d1|), e1 = d1 / |d1|:
    # (dT/deps1 / l) u e1^T + T (I - u e1^T) / (|d0| + |d1|), times 2 beta (beta = 1/2 for
    # the midpoint, where T is the Gauss mean; 1 with r0 = r1, where dtbar = T'/2 and u =
    # e1). Not symmetric for the midpoint: the strain at level 1 follows e1, the force u.
    uet = ca.mtimes((d0 + d1) / (l0 + l1), (d1 / l1).T)
    kb = 2.0 * beta * (dtbar / ell * uet + tbar / (l0 + l1) * (eye - uet)) + gamma * c / ell * (
        taut(em) * uet)
    un = urel - ut * tm
    sn = ca.sqrt(ca.dot(un, un) + delta * delta)
    st = ca.sqrt(ut * ut + delta * delta)
    dmat = 0.5 * rho * cn * d * (sn * (eye - eet) + ca.mtimes(un, un.T) / sn)
    dmat = dmat + 0.5 * rho * ct * math.pi * d * (st + ut * ut / st) * eet
    cb = 0.25 * gamma * lm * dmat
    # drag_per_length(rho=1, d=1, C_n=1) is half of |u_n| u_n: scaled by rho C_n d above
    return ca.Function(
        f"segment_{drag_law}", [ra0, rb0, ra1, rb1, va, vb, u_c, par, sc],
        [f_el + 0.5 * f_d, -f_el + 0.5 * f_d, ca.vec(madd.T), ca.vec(kb.T), ca.vec(cb.T)],
        ["ra0", "rb0", "ra1", "rb1", "va", "vb", "u", "par", "sc"],
        ["fa", "fb", "madd", "kb", "cb"])


_KERNELS: dict[str, ca.Function] = {}


def _switch(name: str, cond: Any, if_true: ca.Function, if_false: ca.Function,
            *args: Any) -> Any:
    """``if_true(*args)`` where ``cond`` holds, else ``if_false(*args)``: only one is
    evaluated. (CasADi's ``if_else(c, a, b, True)`` on expressions builds each branch as a
    function of the graph's *inputs*, so a branch that reuses a value computed before it
    (a Newton iterate, a step's result) evaluates that value again: here the branches take
    those values as arguments.)"""
    return ca.Function.if_else(name, if_true, if_false)(cond, *args)


def _block_thomas(diag: Any, off: Any, rhs: Any) -> Any:
    """Solve the block-tridiagonal system with 3x3 diagonal blocks ``diag`` (9 x n,
    row-major) and equal upper and lower blocks ``off`` (9 x (n-1)) for ``rhs`` (3 x n), by
    block elimination without pivoting (SX). Returns the solution as a (3 n,) vector."""
    n = rhs.shape[1]

    def blk(m: Any, k: int) -> Any:
        return ca.reshape(m[:, k], 3, 3).T

    d_p = [blk(diag, 0)]
    y = [rhs[:, 0]]
    for i in range(1, n):
        w = ca.mtimes(blk(off, i - 1), ca.inv(d_p[i - 1]))
        d_p.append(blk(diag, i) - ca.mtimes(w, blk(off, i - 1)))
        y.append(rhs[:, i] - ca.mtimes(w, y[i - 1]))
    x = [None] * n
    x[n - 1] = ca.solve(d_p[n - 1], y[n - 1])
    for i in range(n - 2, -1, -1):
        x[i] = ca.solve(d_p[i], y[i] - ca.mtimes(blk(off, i), x[i + 1]))
    return ca.vertcat(*x)


def _segment_kernel(drag_law: str, compile_kernel: bool = True) -> ca.Function:
    """The segment kernel of ``drag_law``, compiled to C once and cached on disk when a C
    compiler is available (see :func:`_compile`), else interpreted."""
    key = f"{drag_law}:{compile_kernel}"
    if key not in _KERNELS:
        fn = _segment_kernel_expr(drag_law)
        _KERNELS[key] = _compile(fn) if compile_kernel else fn
    return _KERNELS[key]


#: values of ``CABLE_OCP_CACHE`` that turn the compilation to C off
_CACHE_OFF = CACHE_OFF
_cache_dir = cache_dir
_c_compiler = c_compiler


def _compile(fn: ca.Function, opt: str = "-O2") -> ca.Function:
    """Compile ``fn`` to C, cached (:func:`cable_ocp.numerics.compile.compile_function`); ``fn``
    itself when compiling is off or impossible. Silent."""
    return compile_function(fn, opt)
