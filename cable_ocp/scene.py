"""Problem files (TOML, SI units) -> validated scenes (frozen dataclasses).

This module is the only place that reads user input for the statics. Everything it
returns is validated: downstream code may assume finite numbers, consistent end
conditions and SI units. Every user error raises :class:`~cable_ocp.errors.CableOCPError`
with a message that names the offending key and says what would be valid.

Schema (all values SI; the README repeats this with examples)::

    [meta]                       free-form strings: title, source, notes, ...
    [layout]                     optional conveniences
    psi0_deg = 90.0              rotate end_b about the vertical through end_a to this
                                 bearing (deg from +x towards +y), keeping its horizontal
                                 distance and height (De Zoysa's psi0, 000 eq. (28))
    [environment]
    water_depth = 183.0          m; the free surface is at z = water_depth, seabed at z = 0
    water_density = 1021.0       kg/m^3
    gravity = 9.81               m/s^2 (default 9.81)
    [environment.seabed]         optional; turns seabed contact on (a plane; see Seabed):
    depth_offset = 0.0           m, friction = 0.0 (-), slope_deg = 0.0,
                                 slope_heading_deg = 0.0 (direction the seabed rises)
    [environment.current]        optional; absent = still water (no drag terms are built)
    speed = 1.0278               m/s, uniform current ...
    heading_deg = 0.0            deg, direction the water flows TO, from +x towards +y
    profile = [[z, speed, heading_deg], ...]   ... or a depth profile (m, m/s, deg),
                                 interpolated linearly in the velocity components
    [cable]
    length = 305.0               m (unstretched), or "free" with a prescribed end tension
    diameter = 0.023             m, hydrodynamic diameter
    weight_in_water = 12.3       N/m (per unstretched length)
    axial_stiffness = 1.0e9      N (EA); omit or "inf" for an inextensible cable
    normal_drag = 1.0            C_n (-)
    tangential_drag = 0.005      C_t (-), acts on the wetted perimeter pi*D
    drag_law = "vector"          "vector" (independence principle) | "componentwise" (000)
    [[cable.segments]]           optional multi-segment line, listed from end_a to end_b;
                                 each with length, diameter, weight_in_water,
                                 axial_stiffness, normal_drag, tangential_drag (as above)
                                 and optional intervals (collocation intervals) and
                                 bending_stiffness (EI, N m^2: a planar beam-cable in the
                                 x-z plane, pinned ends, see formulation); then
                                 [cable] holds only drag_law (see :class:`Scene`)
    [[bodies]]                   optional point bodies at joints between segments:
    joint = 1                    1..n_segments-1: after this many segments from end_a
    kind = "clump"               "clump" (weight_in_water, N) | "buoy" (net_buoyancy, N)
                                 | "unit" (weight_in_water N, drag_area m^2,
                                 drag_coefficient -, thrust = [Tx, Ty, Tz] N)
    [end_a]  /  [end_b]          end_a is s = 0, end_b is s = L
    position = [x, y, z]         m; entries may be "free"
    force = [Fx, Fy, Fz]         N, the EXTERNAL load on the attachment (a towed body's
                                 drag and weight, a unit's thrust); entries may be "free"
    tension = 11146.6            N, |T| at this end; needs cable.length = "free"
    [solver]                     see :class:`SolverOptions`
    [footprint]                  optional; see :class:`Footprint`

At each end and for each of x, y, z exactly one of ``position`` and ``force`` gives a
number: a fixed end gives ``position`` only, a free (towed) end ``force`` only, a
mooring end mixes them, e.g. ``position = ["free", "free", 100.0]`` with
``force = [2000.0, 0.0, "free"]`` (004 eqs (2.12)-(2.15)).

Force sign example: a towed body whose drag is 500 N along -x and whose weight in water
is 2 kN hangs at end_a: ``force = [-500.0, 0.0, -2000.0]``. At equilibrium the cable
pulls on the body with (+500, 0, +2000) N, which is what the JSON output reports as
``end_a.force`` (the force the cable exerts on the attachment).
"""

from __future__ import annotations

import copy
import math
import tomllib
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from cable_ocp.baselines import METHODS
from cable_ocp.errors import CableOCPError

__all__ = [
    "Body",
    "Cable",
    "Current",
    "End",
    "Environment",
    "Footprint",
    "Scene",
    "Seabed",
    "SolverOptions",
    "apply_overrides",
    "load_scene",
    "parse_override",
    "scene_from_dict",
]

FREE = "free"


@dataclass(frozen=True)
class Current:
    """Horizontal current, piecewise linear in z.

    Attributes
    ----------
    z : tuple of float
        Knot heights, m, strictly increasing. One knot means a uniform current.
    ux, uy : tuple of float
        Velocity components at the knots, m/s. Constant beyond the first and last knot.
    """

    z: tuple[float, ...]
    ux: tuple[float, ...]
    uy: tuple[float, ...]

    @property
    def uniform(self) -> bool:
        """True when the velocity does not depend on z."""
        return len(self.z) == 1 or (len(set(self.ux)) == 1 and len(set(self.uy)) == 1)

    @property
    def max_speed(self) -> float:
        """Largest speed over the knots, m/s."""
        return max(math.hypot(a, b) for a, b in zip(self.ux, self.uy, strict=True))


@dataclass(frozen=True)
class Seabed:
    """A plane seabed with contact (``[environment.seabed]``).

    Attributes
    ----------
    depth_offset : float
        Height of the seabed plane at x = y = 0, m (default 0: seabed at z = 0).
    friction : float
        Axial friction coefficient on the grounded cable (-), default 0.
    slope_deg : float
        Slope of the plane, deg, in [0, 45).
    slope_heading_deg : float
        Direction in which the seabed rises, deg from +x towards +y.
    """

    depth_offset: float = 0.0
    friction: float = 0.0
    slope_deg: float = 0.0
    slope_heading_deg: float = 0.0


@dataclass(frozen=True)
class Environment:
    """Water and gravity. ``water_depth`` (m) puts the surface at z = water_depth.

    ``seabed`` is None when the scene has no ``[environment.seabed]`` table: the seabed
    plane z = 0 is then only checked (a warning when the profile passes below it), not
    modelled.
    """

    water_depth: float
    water_density: float
    gravity: float = 9.81
    current: Current | None = None
    seabed: Seabed | None = None


@dataclass(frozen=True)
class Cable:
    """One uniform cable.

    Attributes
    ----------
    length : float or None
        Unstretched length, m; None when it is an unknown (a tension is prescribed).
    diameter : float
        Hydrodynamic diameter, m.
    weight_in_water : float
        Weight in water per unstretched length, N/m (negative = buoyant).
    axial_stiffness : float
        EA, N; ``math.inf`` for an inextensible cable.
    normal_drag, tangential_drag : float
        Drag coefficients C_n, C_t (-); the tangential one acts on the perimeter pi*D.
    drag_law : str
        ``"vector"`` or ``"componentwise"``.
    bending_stiffness : float
        EI, N m^2 (``[[cable.segments]]`` only); 0 = a perfectly flexible cable. A segment
        with EI > 0 is a planar beam-cable in the x-z plane
        (:mod:`cable_ocp.statics.formulation`).
    """

    length: float | None
    diameter: float
    weight_in_water: float
    axial_stiffness: float = math.inf
    normal_drag: float = 0.0
    tangential_drag: float = 0.0
    drag_law: str = "vector"
    bending_stiffness: float = 0.0

    @property
    def elastic(self) -> bool:
        """True when EA is finite."""
        return math.isfinite(self.axial_stiffness)


@dataclass(frozen=True)
class Body:
    """A point body at a joint between two cable segments (``[[bodies]]``).

    Attributes
    ----------
    joint : int
        Number of segments between end_a and the body (1 .. n_segments - 1).
    kind : str
        ``"clump"``, ``"buoy"`` or ``"unit"``.
    weight_in_water : float
        Weight in water, N (clump, unit; pulls down). 0 for a buoy.
    net_buoyancy : float
        Net buoyancy, N (buoy; pulls up). 0 otherwise.
    drag_area : float
        Projected area for the drag, m^2 (unit; 0 = no drag).
    drag_coefficient : float
        Drag coefficient C_d (-) (unit).
    thrust : tuple of float
        Thrust vector, N (unit), an external load on the body.
    """

    joint: int
    kind: str
    weight_in_water: float = 0.0
    net_buoyancy: float = 0.0
    drag_area: float = 0.0
    drag_coefficient: float = 0.0
    thrust: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @property
    def static_load(self) -> tuple[float, float, float]:
        """External load without drag (weight, buoyancy, thrust), N."""
        fz = self.net_buoyancy - self.weight_in_water
        return (self.thrust[0], self.thrust[1], self.thrust[2] + fz)

    @property
    def has_drag(self) -> bool:
        """True when the body has a drag area and coefficient."""
        return self.drag_area > 0.0 and self.drag_coefficient > 0.0


@dataclass(frozen=True)
class End:
    """End condition at one end of the cable.

    Attributes
    ----------
    position : tuple of (float or None)
        Prescribed coordinates, m; None where the coordinate is free.
    force : tuple of (float or None)
        Prescribed external load on the attachment, N; None where not prescribed.
        Exactly one of ``position[i]`` and ``force[i]`` is a number.
    tension : float or None
        Prescribed tension magnitude at this end, N (cable length then unknown).
    """

    position: tuple[float | None, float | None, float | None]
    force: tuple[float | None, float | None, float | None]
    tension: float | None = None

    @property
    def fixed_mask(self) -> tuple[bool, bool, bool]:
        """Per component: True where the position is prescribed."""
        return tuple(p is not None for p in self.position)  # type: ignore[return-value]

    @property
    def values(self) -> tuple[float, float, float]:
        """Per component, the prescribed number (position in m or force in N)."""
        return tuple(  # type: ignore[return-value]
            p if p is not None else f for p, f in zip(self.position, self.force, strict=True)
        )


@dataclass(frozen=True)
class SolverOptions:
    """Discretisation and solver settings (all optional in a problem file).

    Attributes
    ----------
    method : str
        ``"collocation"`` (default) or another registered method
        (:data:`cable_ocp.baselines.METHODS`: multiple_shooting, solve_bvp,
        wang_shooting_optimization, huang_semianalytic, chucheepsakul_fem).
    scheme : str
        Collocation points: ``"legendre"`` (Gauss-Legendre, order 2d at mesh points)
        or ``"radau"`` (order 2d - 1).
    degree : int
        Collocation polynomial degree d, 1..9.
    intervals : int
        Number of uniform mesh intervals N along the unstretched arc length.
    tolerance : float
        Relative tolerance of the nonlinear solve (scaled residual).
    max_iterations : int
        IPOPT iteration limit per attempt (Newton gets 30). A square system from a good
        start converges in well under 30; the limit caps the cost of a doomed attempt
        before the current ramp takes over.
    smoothing : float
        Velocity scale delta of the smooth modulus, m/s: |u| is replaced by
        sqrt(u^2 + delta^2), so |u|u is off by at most delta^2 / 2 (m/s)^2.
    vertical_blend : float
        Componentwise law only: below this value of |e_z x t| (the sine of the angle
        to the vertical) the load blends into the vector law, which stays defined on
        a vertical cable.
    error_estimate : bool
        Compute the a-posteriori discretisation error (re-solves on N/2 and N/4 intervals).
    accuracy : float
        Target relative discretisation error (-). A solve whose error estimate exceeds it
        is refined (N doubled, up to ``max_intervals``) when ``refine`` is true, and is
        reported as ``"inaccurate"`` (not solved) if it still exceeds it.
    refine : bool
        Refine the mesh automatically to reach ``accuracy``.
    max_intervals : int
        Upper limit of the automatic refinement.
    initial_guess : str
        ``"catenary"`` (drag-free, default) or ``"straight"``.
    """

    method: str = "collocation"
    scheme: str = "legendre"
    degree: int = 3
    intervals: int = 40
    tolerance: float = 1e-10
    max_iterations: int = 100
    smoothing: float = 1e-5
    vertical_blend: float = 1e-2
    error_estimate: bool = True
    accuracy: float = 1e-6
    refine: bool = True
    max_intervals: int = 2560
    initial_guess: str = "catenary"


@dataclass(frozen=True)
class Footprint:
    """Footprint problem settings (``[footprint]``; 004 section 2.2.4, type 4).

    The subsea unit is end_a, resting on the seabed (its z fixed, x and y free), pushed by
    its thrusters (the external load ``end_a.force`` x, y); the ship is end_b, fixed.

    Attributes
    ----------
    max_length : float
        Largest cable length L_max, m.
    min_length : float
        Smallest cable length considered, m.
    bound : str
        ``"magnitude"`` (default: |T_h| <= thrust_max) or ``"components"`` (|T_x| <=
        thrust_x_max, |T_y| <= thrust_y_max, symmetric; CONVENTIONS "Footprint").
    thrust_max, thrust_x_max, thrust_y_max : float
        Thrust limits, N.
    """

    max_length: float
    min_length: float
    bound: str = "magnitude"
    thrust_max: float = 0.0
    thrust_x_max: float = 0.0
    thrust_y_max: float = 0.0


@dataclass(frozen=True)
class Scene:
    """A validated statics problem: the input of every statics method.

    A multi-segment line (``[[cable.segments]]``) has its segments, from end_a to end_b,
    in ``segments`` (each a :class:`Cable` with its own length) and its point bodies in
    ``bodies``; ``cable`` then summarises the line: the total length with the first
    segment's properties (the segment that touches the seabed at an anchored end_a).
    A single-cable scene has ``segments == ()`` and ``bodies == ()``.
    """

    environment: Environment
    cable: Cable
    end_a: End
    end_b: End
    solver: SolverOptions = field(default_factory=SolverOptions)
    footprint: Footprint | None = None
    segments: tuple[Cable, ...] = ()
    segment_intervals: tuple[int | None, ...] = ()
    bodies: tuple[Body, ...] = ()
    meta: dict[str, str] = field(default_factory=dict, compare=False, hash=False)
    raw: dict[str, Any] = field(default_factory=dict, compare=False, hash=False, repr=False)

    @property
    def free_length(self) -> bool:
        """True when the cable length is an unknown."""
        return self.cable.length is None

    @property
    def lines(self) -> tuple[Cable, ...]:
        """The segments from end_a to end_b (a single cable is one segment)."""
        return self.segments or (self.cable,)

    def with_overrides(self, overrides: dict[str, Any]) -> Scene:
        """Return a new scene with dotted-key overrides applied to the source dict."""
        return scene_from_dict(apply_overrides(self.raw, overrides))


# --------------------------------------------------------------------------------------
# Parsing helpers
# --------------------------------------------------------------------------------------

_SCHEMA: dict[str, Any] = {
    "meta": "any",
    "layout": {"psi0_deg"},
    "environment": {"water_depth", "water_density", "gravity", "current", "seabed"},
    "cable": {
        "length",
        "diameter",
        "weight_in_water",
        "axial_stiffness",
        "normal_drag",
        "tangential_drag",
        "drag_law",
        "segments",
    },
    "bodies": "list",
    "footprint": {"max_length", "min_length", "bound", "thrust_max", "thrust_x_max",
                  "thrust_y_max"},
    "end_a": {"position", "force", "tension"},
    "end_b": {"position", "force", "tension"},
    "solver": {
        "method",
        "scheme",
        "degree",
        "intervals",
        "tolerance",
        "max_iterations",
        "smoothing",
        "vertical_blend",
        "error_estimate",
        "initial_guess",
        "accuracy",
        "refine",
        "max_intervals",
    },
}
_CURRENT_KEYS = {"speed", "heading_deg", "profile"}
_SEGMENT_KEYS = {"length", "diameter", "weight_in_water", "axial_stiffness", "normal_drag",
                 "tangential_drag", "intervals", "bending_stiffness"}
_BODY_KEYS = {"joint", "kind", "weight_in_water", "net_buoyancy", "drag_area",
              "drag_coefficient", "thrust"}


def _number(value: Any, key: str, *, positive: bool = False, nonneg: bool = False,
            allow_inf: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise CableOCPError(f"{key} = {value!r}: expected a number")
    if isinstance(value, str):
        if allow_inf and value.strip().lower() in ("inf", "infinity"):
            return math.inf
        raise CableOCPError(
            f"{key} = {value!r}: expected a number" + (' or "inf"' if allow_inf else "")
        )
    x = float(value)
    if math.isnan(x) or (math.isinf(x) and not allow_inf):
        raise CableOCPError(f"{key} = {value!r}: expected a finite number")
    if positive and not x > 0:
        raise CableOCPError(f"{key} = {value!r}: must be > 0")
    if nonneg and x < 0:
        raise CableOCPError(f"{key} = {value!r}: must be >= 0")
    return x


def _require(table: dict[str, Any], key: str, where: str) -> Any:
    if key not in table:
        raise CableOCPError(f"{where}.{key} is missing (required, SI units)")
    return table[key]


def _check_keys(table: Any, allowed: set[str], where: str) -> dict[str, Any]:
    if not isinstance(table, dict):
        raise CableOCPError(f"[{where}] must be a table, got {table!r}")
    unknown = sorted(set(table) - allowed)
    if unknown:
        raise CableOCPError(
            f"unknown key {where}.{unknown[0]}; valid keys in [{where}]: "
            f"{', '.join(sorted(allowed))}"
        )
    return table


def _vector3(value: Any, key: str) -> tuple[float | None, float | None, float | None]:
    if not isinstance(value, (list, tuple)) or len(value) != 3:
        raise CableOCPError(f"{key} = {value!r}: expected a list of 3 entries [x, y, z]")
    out: list[float | None] = []
    for i, v in enumerate(value):
        if isinstance(v, str) and v.strip().lower() == FREE:
            out.append(None)
        else:
            out.append(_number(v, f"{key}[{i}]"))
    return tuple(out)  # type: ignore[return-value]


def _parse_current(table: Any) -> Current | None:
    table = _check_keys(table, _CURRENT_KEYS, "environment.current")
    if "profile" in table:
        if "speed" in table or "heading_deg" in table:
            raise CableOCPError(
                "environment.current: give either speed and heading_deg, or profile, not both"
            )
        prof = table["profile"]
        if not isinstance(prof, list) or not prof:
            raise CableOCPError(
                "environment.current.profile: expected a non-empty list of [z, speed, heading_deg]"
            )
        rows = []
        for i, row in enumerate(prof):
            key = f"environment.current.profile[{i}]"
            if not isinstance(row, list) or len(row) != 3:
                raise CableOCPError(f"{key} = {row!r}: expected [z (m), speed (m/s), heading_deg]")
            rows.append((_number(row[0], key + "[0]"), _number(row[1], key + "[1]", nonneg=True),
                         _number(row[2], key + "[2]")))
        rows.sort(key=lambda r: r[0])
        zs = [r[0] for r in rows]
        if any(b <= a for a, b in zip(zs, zs[1:], strict=False)):
            raise CableOCPError("environment.current.profile: knot heights z must be distinct")
        ux = tuple(r[1] * math.cos(math.radians(r[2])) for r in rows)
        uy = tuple(r[1] * math.sin(math.radians(r[2])) for r in rows)
        cur = Current(z=tuple(zs), ux=ux, uy=uy)
    else:
        speed = _number(_require(table, "speed", "environment.current"),
                        "environment.current.speed", nonneg=True)
        heading = _number(table.get("heading_deg", 0.0), "environment.current.heading_deg")
        cur = Current(z=(0.0,), ux=(speed * math.cos(math.radians(heading)),),
                      uy=(speed * math.sin(math.radians(heading)),))
    if cur.max_speed == 0.0:
        return None
    return cur


def _parse_seabed(table: Any) -> Seabed:
    table = _check_keys(table, {"depth_offset", "friction", "slope_deg", "slope_heading_deg"},
                        "environment.seabed")
    slope = _number(table.get("slope_deg", 0.0), "environment.seabed.slope_deg", nonneg=True)
    if slope >= 45.0:
        raise CableOCPError(f"environment.seabed.slope_deg = {slope}: must be in [0, 45)")
    return Seabed(
        depth_offset=_number(table.get("depth_offset", 0.0), "environment.seabed.depth_offset"),
        friction=_number(table.get("friction", 0.0), "environment.seabed.friction", nonneg=True),
        slope_deg=slope,
        slope_heading_deg=_number(table.get("slope_heading_deg", 0.0),
                                  "environment.seabed.slope_heading_deg"),
    )


def _parse_end(table: Any, name: str) -> End:
    table = _check_keys(table, _SCHEMA[name], name)
    pos = _vector3(table["position"], f"{name}.position") if "position" in table else None
    frc = _vector3(table["force"], f"{name}.force") if "force" in table else None
    if pos is None and frc is None:
        raise CableOCPError(
            f"[{name}] needs position = [x, y, z] (m) and/or force = [Fx, Fy, Fz] (N)")
    if pos is None:
        pos = (None, None, None)
    if frc is None:
        frc = (None, None, None)
    for i, c in enumerate("xyz"):
        if (pos[i] is None) == (frc[i] is None):
            raise CableOCPError(
                f"{name}: component {c} needs exactly one of position[{i}] and force[{i}] "
                f'as a number (the other "free" or absent)'
            )
    tension = None
    if "tension" in table:
        tension = _number(table["tension"], f"{name}.tension", positive=True)
        if not all(p is not None for p in pos):
            raise CableOCPError(
                f"{name}.tension needs a fully fixed {name}.position at the same end")
    return End(position=pos, force=frc, tension=tension)


def _parse_law(cab_t: dict[str, Any]) -> str:
    law = cab_t.get("drag_law", "vector")
    if law not in ("vector", "componentwise"):
        raise CableOCPError(f'cable.drag_law = {law!r}: valid are "vector", "componentwise"')
    return law


def _parse_single_cable(cab_t: dict[str, Any], need_drag: bool) -> Cable:
    if "bending_stiffness" in cab_t:
        raise CableOCPError(
            "cable.bending_stiffness: bending stiffness is given per segment; put the stiff "
            "part in its own [[cable.segments]] entry with bending_stiffness (EI, N m^2)")
    length_v = _require(cab_t, "length", "cable")
    if isinstance(length_v, str) and length_v.strip().lower() == FREE:
        length = None
    else:
        length = _number(length_v, "cable.length", positive=True)
    law = _parse_law(cab_t)
    diameter = (_number(_require(cab_t, "diameter", "cable"), "cable.diameter", positive=True)
                if need_drag or "diameter" in cab_t else 0.0)
    cn = (_number(_require(cab_t, "normal_drag", "cable"), "cable.normal_drag", nonneg=True)
          if need_drag or "normal_drag" in cab_t else 0.0)
    ct = (_number(_require(cab_t, "tangential_drag", "cable"), "cable.tangential_drag",
                  nonneg=True) if need_drag or "tangential_drag" in cab_t else 0.0)
    cable = Cable(
        length=length,
        diameter=diameter,
        weight_in_water=_number(_require(cab_t, "weight_in_water", "cable"),
                                "cable.weight_in_water"),
        axial_stiffness=_number(cab_t.get("axial_stiffness", math.inf), "cable.axial_stiffness",
                                positive=True, allow_inf=True),
        normal_drag=cn,
        tangential_drag=ct,
        drag_law=law,
    )
    return cable


def _parse_segments(cab_t: dict[str, Any], need_drag: bool
                    ) -> tuple[Cable, tuple[Cable, ...], tuple[int | None, ...]]:
    """``[[cable.segments]]`` -> (summary cable, segments, per-segment intervals)."""
    law = _parse_law(cab_t)
    for key in sorted(set(cab_t) - {"segments", "drag_law"}):
        raise CableOCPError(
            f"cable.{key}: with [[cable.segments]] every segment gives its own {key}; "
            "[cable] may hold only drag_law and segments")
    segs_t = cab_t["segments"]
    if not isinstance(segs_t, list) or not segs_t:
        raise CableOCPError("cable.segments: expected a non-empty array of tables "
                            "([[cable.segments]])")
    segs, ivals = [], []
    for i, t in enumerate(segs_t):
        where = f"cable.segments[{i}]"
        t = _check_keys(t, _SEGMENT_KEYS, where)
        lv = _require(t, "length", where)
        if isinstance(lv, str) and lv.strip().lower() == FREE:
            raise CableOCPError(
                f'{where}.length = "free": a free length (prescribed end tension) is not '
                "supported for multi-segment lines; give every segment its length")
        length = _number(lv, f"{where}.length", positive=True)

        def opt(key: str, t: dict[str, Any] = t, where: str = where) -> float:
            if need_drag or key in t:
                return _number(_require(t, key, where), f"{where}.{key}",
                               positive=key == "diameter", nonneg=key != "diameter")
            return 0.0

        segs.append(Cable(
            length=length,
            diameter=opt("diameter"),
            weight_in_water=_number(_require(t, "weight_in_water", where),
                                    f"{where}.weight_in_water"),
            axial_stiffness=_number(t.get("axial_stiffness", math.inf),
                                    f"{where}.axial_stiffness", positive=True, allow_inf=True),
            normal_drag=opt("normal_drag"),
            tangential_drag=opt("tangential_drag"),
            drag_law=law,
            bending_stiffness=_number(t.get("bending_stiffness", 0.0),
                                      f"{where}.bending_stiffness", nonneg=True),
        ))
        iv = t.get("intervals")
        if iv is not None and (isinstance(iv, bool) or not isinstance(iv, int)
                               or not 1 <= iv <= 20000):
            raise CableOCPError(f"{where}.intervals = {iv!r}: expected an integer 1..20000")
        ivals.append(iv)
    first = segs[0]
    summary = replace(first, length=sum(c.length for c in segs))  # type: ignore[misc]
    return summary, tuple(segs), tuple(ivals)


def _check_planar_bending(segments: tuple[Cable, ...], env: Environment, end_a: End,
                          end_b: End, bodies: tuple[Body, ...]) -> None:
    """Bending stiffness is modelled in the vertical x-z plane only (a planar beam-cable):
    reject any scene that could leave that plane, naming the key."""
    stiff = [i for i, c in enumerate(segments) if c.bending_stiffness > 0.0]
    if not stiff:
        return
    key = f"cable.segments[{stiff[0]}].bending_stiffness"
    why = (f"{key}: bending stiffness is modelled in the vertical x-z plane only (planar "
           "beam-cable); ")
    for name, end in (("end_a", end_a), ("end_b", end_b)):
        if end.position[1] is not None and end.position[1] != 0.0:
            raise CableOCPError(why + f"{name}.position[1] = {end.position[1]} must be 0")
        if end.force[1] is not None and end.force[1] != 0.0:
            raise CableOCPError(why + f"{name}.force[1] = {end.force[1]} must be 0")
    cur = env.current
    if cur is not None:
        for uy in cur.uy:
            if abs(uy) > 1e-12 * max(cur.max_speed, 1.0):
                raise CableOCPError(why + "environment.current: the heading must be 0 or "
                                    "180 deg at every knot (a current in the x-z plane)")
    for i, b in enumerate(bodies):
        if b.thrust[1] != 0.0:
            raise CableOCPError(why + f"bodies[{i}].thrust[1] = {b.thrust[1]} must be 0")
    if env.seabed is not None and segments[0].bending_stiffness > 0.0:
        raise CableOCPError(
            "cable.segments[0].bending_stiffness: seabed contact is modelled on a flexible "
            "first segment only; put a cable segment first or drop [environment.seabed]")


def _parse_bodies(value: Any, n_segments: int) -> tuple[Body, ...]:
    """``[[bodies]]`` -> point bodies at the joints between segments."""
    if not isinstance(value, list):
        raise CableOCPError("bodies: expected an array of tables ([[bodies]])")
    if value and n_segments < 2:
        raise CableOCPError(
            "bodies[0].joint: point bodies sit at joints between segments; give at least two "
            "[[cable.segments]] (a body at an end is an end force: add it to end_a/end_b.force)")
    out = []
    for i, t in enumerate(value):
        where = f"bodies[{i}]"
        t = _check_keys(t, _BODY_KEYS, where)
        joint = _require(t, "joint", where)
        if isinstance(joint, bool) or not isinstance(joint, int) or not 1 <= joint < n_segments:
            raise CableOCPError(
                f"{where}.joint = {joint!r}: expected an integer 1..{n_segments - 1} (the number "
                "of segments between end_a and the body); a body at an end is an end force")
        kind = _require(t, "kind", where)
        allowed = {"clump": {"joint", "kind", "weight_in_water"},
                   "buoy": {"joint", "kind", "net_buoyancy"},
                   "unit": {"joint", "kind", "weight_in_water", "drag_area",
                            "drag_coefficient", "thrust"}}
        if kind not in allowed:
            raise CableOCPError(f'{where}.kind = {kind!r}: valid are "clump", "buoy", "unit"')
        extra = sorted(set(t) - allowed[kind])
        if extra:
            raise CableOCPError(f"{where}.{extra[0]}: not a key of a {kind} body; valid: "
                                f"{', '.join(sorted(allowed[kind]))}")
        if kind == "clump":
            body = Body(joint, kind, weight_in_water=_number(
                _require(t, "weight_in_water", where), f"{where}.weight_in_water",
                positive=True))
        elif kind == "buoy":
            body = Body(joint, kind, net_buoyancy=_number(
                _require(t, "net_buoyancy", where), f"{where}.net_buoyancy", positive=True))
        else:
            area = _number(t.get("drag_area", 0.0), f"{where}.drag_area", nonneg=True)
            cd = _number(t.get("drag_coefficient", 0.0), f"{where}.drag_coefficient",
                         nonneg=True)
            if (area > 0) != (cd > 0):
                raise CableOCPError(f"{where}: give both drag_area (m^2) and drag_coefficient "
                                    "(-), or neither")
            thrust = (0.0, 0.0, 0.0)
            if "thrust" in t:
                v = t["thrust"]
                if not isinstance(v, list) or len(v) != 3:
                    raise CableOCPError(f"{where}.thrust = {v!r}: expected [Tx, Ty, Tz] (N)")
                thrust = tuple(_number(c, f"{where}.thrust[{k}]")  # type: ignore[assignment]
                               for k, c in enumerate(v))
            body = Body(joint, kind, weight_in_water=_number(
                _require(t, "weight_in_water", where), f"{where}.weight_in_water"),
                drag_area=area, drag_coefficient=cd, thrust=thrust)
        out.append(body)
    return tuple(out)


def scene_from_dict(data: dict[str, Any]) -> Scene:
    """Validate a problem dictionary (as read from TOML) and return a :class:`Scene`.

    Raises
    ------
    CableOCPError
        On unknown keys, missing required fields, non-finite or out-of-range numbers, or
        inconsistent end conditions; the message names the key.
    """
    data = copy.deepcopy(data)
    raw = copy.deepcopy(data)
    if not isinstance(data, dict):
        raise CableOCPError("a problem must be a table")
    unknown = sorted(set(data) - set(_SCHEMA))
    if unknown:
        raise CableOCPError(
            f"unknown top-level table [{unknown[0]}]; valid: {', '.join(sorted(_SCHEMA))}"
        )
    meta = {str(k): str(v) for k, v in (data.get("meta") or {}).items()}

    env_t = _check_keys(_require(data, "environment", "problem"), _SCHEMA["environment"],
                        "environment")
    depth = _number(_require(env_t, "water_depth", "environment"), "environment.water_depth",
                    positive=True)
    rho = _number(_require(env_t, "water_density", "environment"), "environment.water_density",
                  positive=True)
    g = _number(env_t.get("gravity", 9.81), "environment.gravity", positive=True)
    current = _parse_current(env_t["current"]) if "current" in env_t else None
    seabed = _parse_seabed(env_t["seabed"]) if "seabed" in env_t else None
    env = Environment(water_depth=depth, water_density=rho, gravity=g, current=current,
                      seabed=seabed)

    cab_t = _check_keys(_require(data, "cable", "problem"), _SCHEMA["cable"], "cable")
    segments: tuple[Cable, ...] = ()
    seg_intervals: tuple[int | None, ...] = ()
    if "segments" in cab_t:
        cable, segments, seg_intervals = _parse_segments(cab_t, current is not None)
    else:
        cable = _parse_single_cable(cab_t, current is not None)
    length = cable.length
    bodies = _parse_bodies(data.get("bodies"), len(segments)) if "bodies" in data else ()

    end_a = _parse_end(_require(data, "end_a", "problem"), "end_a")
    end_b = _parse_end(_require(data, "end_b", "problem"), "end_b")

    layout = _check_keys(data.get("layout", {}), _SCHEMA["layout"], "layout")
    if "psi0_deg" in layout:
        psi = _number(layout["psi0_deg"], "layout.psi0_deg")
        if not (all(end_a.fixed_mask[:2]) and all(end_b.fixed_mask[:2])):
            raise CableOCPError("layout.psi0_deg needs fixed horizontal positions at both ends")
        ax, ay = end_a.position[0], end_a.position[1]
        bx, by, bz = end_b.position
        radius = math.hypot(bx - ax, by - ay)  # type: ignore[operator]
        end_b = replace(end_b, position=(ax + radius * math.cos(math.radians(psi)),
                                         ay + radius * math.sin(math.radians(psi)), bz))

    tensions = [e.tension for e in (end_a, end_b) if e.tension is not None]
    if segments and tensions:
        raise CableOCPError(
            f"{'end_a' if end_a.tension is not None else 'end_b'}.tension: a prescribed end "
            "tension (free length) is not supported for multi-segment lines "
            "([[cable.segments]]); prescribe the positions or forces instead")
    if length is None and len(tensions) != 1:
        raise CableOCPError(
            'cable.length = "free" needs exactly one end tension (end_a.tension or end_b.tension)'
        )
    if length is not None and tensions:
        raise CableOCPError(
            'an end tension makes the length an unknown: set cable.length = "free"'
        )
    for i, c in enumerate("xyz"):
        if not (end_a.fixed_mask[i] or end_b.fixed_mask[i]):
            raise CableOCPError(
                f"the {c} position is free at both ends (end_a.position[{i}], "
                f"end_b.position[{i}]): the cable would float away; fix it at one end"
            )
    inextensible = not any(c.elastic for c in (segments or (cable,)))
    if length is not None and inextensible and all(end_a.fixed_mask) and all(end_b.fixed_mask):
        chord = math.dist(end_a.position, end_b.position)  # type: ignore[arg-type]
        if chord >= length:
            raise CableOCPError(
                f"cable.length = {length} m is not longer than the chord between the fixed ends "
                f"({chord:.6g} m); an inextensible cable needs length > chord "
                "(or give cable.axial_stiffness)"
            )

    sol_t = _check_keys(data.get("solver", {}), _SCHEMA["solver"], "solver")
    defaults = SolverOptions()
    method = sol_t.get("method", defaults.method)
    if method not in METHODS:
        raise CableOCPError(f"solver.method = {method!r}: valid are {', '.join(METHODS)}")
    scheme = sol_t.get("scheme", defaults.scheme)
    if scheme not in ("legendre", "radau"):
        raise CableOCPError(f'solver.scheme = {scheme!r}: valid are "legendre", "radau"')
    degree = sol_t.get("degree", defaults.degree)
    if isinstance(degree, bool) or not isinstance(degree, int) or not 1 <= degree <= 9:
        raise CableOCPError(f"solver.degree = {degree!r}: expected an integer 1..9")
    intervals = sol_t.get("intervals", defaults.intervals)
    if isinstance(intervals, bool) or not isinstance(intervals, int) or not 1 <= intervals <= 20000:
        raise CableOCPError(f"solver.intervals = {intervals!r}: expected an integer 1..20000")
    max_it = sol_t.get("max_iterations", defaults.max_iterations)
    if isinstance(max_it, bool) or not isinstance(max_it, int) or max_it < 1:
        raise CableOCPError(f"solver.max_iterations = {max_it!r}: expected a positive integer")
    guess = sol_t.get("initial_guess", defaults.initial_guess)
    if guess not in ("catenary", "straight"):
        raise CableOCPError(f'solver.initial_guess = {guess!r}: valid are "catenary", "straight"')
    est = sol_t.get("error_estimate", defaults.error_estimate)
    if not isinstance(est, bool):
        raise CableOCPError(f"solver.error_estimate = {est!r}: expected true or false")
    refine = sol_t.get("refine", defaults.refine)
    if not isinstance(refine, bool):
        raise CableOCPError(f"solver.refine = {refine!r}: expected true or false")
    max_int = sol_t.get("max_intervals", defaults.max_intervals)
    if isinstance(max_int, bool) or not isinstance(max_int, int) or max_int < 1:
        raise CableOCPError(f"solver.max_intervals = {max_int!r}: expected a positive integer")
    solver = SolverOptions(
        method=method,
        scheme=scheme,
        degree=degree,
        intervals=intervals,
        tolerance=_number(sol_t.get("tolerance", defaults.tolerance), "solver.tolerance",
                          positive=True),
        max_iterations=max_it,
        smoothing=_number(sol_t.get("smoothing", defaults.smoothing), "solver.smoothing",
                          positive=True),
        vertical_blend=_number(sol_t.get("vertical_blend", defaults.vertical_blend),
                               "solver.vertical_blend", positive=True),
        error_estimate=est,
        initial_guess=guess,
        accuracy=_number(sol_t.get("accuracy", defaults.accuracy), "solver.accuracy",
                         positive=True),
        refine=refine,
        max_intervals=max_int,
    )
    if solver.vertical_blend >= 1.0:
        raise CableOCPError(f"solver.vertical_blend = {solver.vertical_blend}: must be in (0, 1)")
    footprint = (_parse_footprint(data["footprint"], end_a, end_b)
                 if "footprint" in data else None)
    if segments and solver.method != "collocation":
        raise CableOCPError(
            f"solver.method = {solver.method!r}: multi-segment lines ([[cable.segments]]) are "
            'solved by solver.method = "collocation" only')
    if segments and footprint is not None:
        raise CableOCPError("[footprint] is not supported with [[cable.segments]]; give a "
                            "single [cable]")
    _check_planar_bending(segments, env, end_a, end_b, bodies)
    return Scene(environment=env, cable=cable, end_a=end_a, end_b=end_b, solver=solver,
                 footprint=footprint, meta=meta, raw=raw, segments=segments,
                 segment_intervals=seg_intervals, bodies=bodies)


def _parse_footprint(table: Any, end_a: End, end_b: End) -> Footprint:
    table = _check_keys(table, _SCHEMA["footprint"], "footprint")
    if end_a.fixed_mask != (False, False, True) or not all(end_b.fixed_mask):
        raise CableOCPError(
            '[footprint] needs the unit at end_a with position = ["free", "free", z] and '
            'force = [Fx, Fy, "free"] (thrust), and the ship at a fixed end_b.position')
    lmax = _number(_require(table, "max_length", "footprint"), "footprint.max_length",
                   positive=True)
    lmin = _number(table.get("min_length", abs(end_b.position[2] - end_a.position[2])),
                   "footprint.min_length", positive=True)
    if lmin >= lmax:
        raise CableOCPError(f"footprint.min_length = {lmin} must be < max_length = {lmax}")
    bound = table.get("bound", "magnitude")
    if bound not in ("magnitude", "components"):
        raise CableOCPError(f'footprint.bound = {bound!r}: valid are "magnitude", "components"')
    need = ("thrust_max",) if bound == "magnitude" else ("thrust_x_max", "thrust_y_max")
    vals = {k: _number(_require(table, k, "footprint"), f"footprint.{k}", nonneg=True)
            for k in need}
    return Footprint(max_length=lmax, min_length=lmin, bound=bound, **vals)


def parse_override(text: str) -> tuple[str, Any]:
    """Parse ``key=value`` (value in TOML syntax; bare words are strings).

    Examples: ``end_b.position=[0,229,183]``, ``cable.length=free``, ``solver.degree=4``.
    """
    if "=" not in text:
        raise CableOCPError(f"--set {text!r}: expected key=value, e.g. cable.length=305")
    key, value = text.split("=", 1)
    key = key.strip()
    if not key:
        raise CableOCPError(f"--set {text!r}: empty key")
    try:
        parsed = tomllib.loads(f"v = {value.strip()}")["v"]
    except tomllib.TOMLDecodeError:
        parsed = value.strip()
    return key, parsed


def apply_overrides(data: dict[str, Any], overrides: dict[str, Any]) -> dict[str, Any]:
    """Return a copy of ``data`` with dotted-key overrides set (tables are created; an
    integer part indexes an array of tables, e.g. ``cable.segments.0.length``)."""
    out = copy.deepcopy(data)
    for key, value in overrides.items():
        parts = key.split(".")
        node = out
        for p in parts[:-1]:
            if isinstance(node, list):  # an array of tables: cable.segments.0.length
                if not p.isdigit() or int(p) >= len(node):
                    raise CableOCPError(f"--set {key}: {p} is not an index 0..{len(node) - 1}")
                nxt = node[int(p)]
            else:
                nxt = node.setdefault(p, {})
            if not isinstance(nxt, (dict, list)):
                raise CableOCPError(f"--set {key}: {p} is not a table")
            node = nxt
        if isinstance(node, list):
            raise CableOCPError(f"--set {key}: give an index and a key, e.g. "
                                "cable.segments.0.length=1000")
        node[parts[-1]] = value
    return out


def load_scene(path: str | Path, overrides: dict[str, Any] | None = None) -> Scene:
    """Read a TOML problem file, apply ``overrides`` (dotted keys) and validate it."""
    path = Path(path)
    try:
        with path.open("rb") as fh:
            data = tomllib.load(fh)
    except FileNotFoundError:
        raise CableOCPError(f"problem file {str(path)!r} not found") from None
    except tomllib.TOMLDecodeError as exc:
        raise CableOCPError(f"problem file {str(path)!r} is not valid TOML: {exc}") from None
    if overrides:
        data = apply_overrides(data, overrides)
    return scene_from_dict(data)
