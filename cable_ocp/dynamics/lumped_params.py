"""Parameters of the lumped-mass model (Huang (1992), ch. 5): every input, explicitly, in SI.

* :class:`UnitParams`: the subsea unit at end_a (Huang's eq. (5.6));
* :class:`PointBody`: a point body at an interior node (a clump weight, buoy or unit on the
  line);
* :class:`LumpedParams`: the segments (lengths, stiffness, masses, weights, drag and added
  mass coefficients, material damping), the prescribed ends, the current and the
  smoothing scales;
* :func:`uniform_params`: a uniform cable cut into equal segments.

The equations built from them are in :mod:`cable_ocp.dynamics.lumped_equations`, the model
in :mod:`cable_ocp.dynamics.lumped`.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.physics.drag import DRAG_LAWS

__all__ = [
    "CurrentFunction",
    "LumpedParams",
    "PointBody",
    "TimeFunction",
    "UnitParams",
    "Vec3",
    "uniform_params",
]

Vec3 = tuple[float, float, float]
#: a function of time (CasADi SX/MX or float) returning a 3-vector expression (m or m/s)
TimeFunction = Callable[[Any], Any]
#: a function of height z (m) returning the current velocity 3-vector (m/s)
CurrentFunction = Callable[[Any], Any]

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
    bending_stiffness : ndarray (N,)
        EI, N m^2 (default 0: a flexible cable), the hinge law of
        :mod:`cable_ocp.dynamics.bending_terms` (pinned ends).
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
    tension_strain : TensionStrainTable or None
        The line's tension-strain law u(e) in place of EA e (every segment;
        :class:`cable_ocp.physics.elasticity.TensionStrainTable`), None for the linear law.
    viscoelastic : StandardLinearSolid or None
        The line's standard linear solid (every segment;
        :class:`cable_ocp.physics.viscoelastic.StandardLinearSolid`, its static modulus
        the segments' ``axial_stiffness``): each segment carries its dashpot strain in the
        stepped state; None for an elastic line.
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
    bending_stiffness: np.ndarray | float = 0.0
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
    tension_strain: Any = None
    viscoelastic: Any = None

    def __post_init__(self) -> None:
        names = ("segment_length", "axial_stiffness", "diameter", "mass_per_length",
                 "weight_in_water", "normal_drag", "tangential_drag",
                 "added_mass_coefficient", "tangential_added_mass_coefficient",
                 "axial_damping", "bending_stiffness")
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
                     "axial_damping", "bending_stiffness"):
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

    Parameters
    ----------
    length : float
        Unstretched cable length, m.
    segments : int
        Number of equal segments.
    axial_stiffness : float
        EA, N.
    diameter : float
        Hydrodynamic diameter, m.
    mass_per_length, weight_in_water : float
        kg/m and N/m.
    top_position : callable or sequence of 3 float
        end_b's position, m (a function of t, s, or constant).
    normal_drag, tangential_drag : float
        C_n, C_t (-).
    added_mass_coefficient, tangential_added_mass_coefficient : float
        C_a, C_at (-).
    axial_damping : float
        Material damping c, N s.
    **kwargs
        Further fields of :class:`LumpedParams`.
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
