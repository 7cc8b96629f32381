"""Mooring systems: line types, points, floating bodies and lines (docs/systems.md).

A problem file with a ``[[lines]]`` array is a *system*: several lines between points,
some points fixed (anchors), some on bodies (fairleads), some free (connections, clump
weights, buoys), and bodies with six degrees of freedom. Every line is a single-line
statics scene (:class:`~cable_ocp.scene.statics.Scene`) of today's schema, built here
once with its ends at the file's positions; the equilibrium moves its ends
(:mod:`cable_ocp.mooring`). Schema (SI; the environment and ``[solver]`` as for one line)::

    [line_types.NAME]         diameter (m, volume-equivalent: buoyancy and drag),
                              mass_per_length (kg/m) or weight_in_water (N/m),
                              axial_stiffness (N), normal_drag, tangential_drag (on pi d),
                              added_mass, tangential_added_mass (-), mbl (N),
                              cost_per_length (currency/m); or standard = "studless_chain"
                              (:data:`cable_ocp.physics.line_types.STANDARDS`) with
                              nominal_diameter (m), any key above overriding it
    [[points]]                name, kind = "fixed" | "body" | "free", position (m: global;
                              in the body frame for "body"; the first guess for "free"),
                              body (kind "body"), mass (kg), volume (m^3), force (N)
    [[bodies]]                name, kind = "free" | "fixed", held = ["x", ..., "yaw"],
                              position (m), rotation_deg ([roll, pitch, yaw], deg),
                              mass (kg), center_of_gravity (m, body frame), volume (m^3),
                              center_of_buoyancy (m), waterplane_area (m^2),
                              waterplane_moments ([Ixx, Iyy], m^4) or metacenter (m),
                              hydrostatic_matrix (6x6), force (N), moment (N m)
    [[lines]]                 name, point_a, point_b, parts = [{type, length}, ...] (from
                              point_a) or type and length
    [system]                  tolerance (relative force residual), max_iterations,
                              line_model ("auto": the closed-form catenary where it is exact,
                              else the collocation; "collocation": every line by collocation)
    [moordyn]                 what a MoorDyn file carries that statics does not use (kept
                              for writing the file back; :mod:`cable_ocp.scene.moordyn`)

The rotation is R = Rz(yaw) Ry(pitch) Rx(roll) (MoorPy's and MoorDyn's order,
CONVENTIONS "Mooring systems").
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from cable_ocp.errors import CableOCPError
from cable_ocp.scene.fields import check_keys, choice, integer, number, require, vector3
from cable_ocp.scene.files import apply_overrides, read_problem
from cable_ocp.scene.parts import (
    BODY_MAX,
    BODY_WHY,
    COORD_MAX,
    COORD_WHY,
    FORCE_MAX,
    FORCE_WHY,
    Environment,
    parse_meta,
)
from cable_ocp.scene.statics import Scene, SolverOptions, scene_from_dict

__all__ = ["DOF_NAMES", "MOORDYN_SUFFIXES", "LineType", "Point", "SystemBody", "SystemLine",
           "SystemScene", "is_moordyn_path", "is_system", "load_system", "system_from_dict"]

#: file name endings read as MoorDyn input files (:mod:`cable_ocp.scene.moordyn`)
MOORDYN_SUFFIXES = (".dat", ".txt", ".in")

#: the degrees of freedom of a body, in pose order
DOF_NAMES = ("x", "y", "z", "roll", "pitch", "yaw")

_TOP = {"meta", "environment", "line_types", "points", "bodies", "lines", "solver", "system",
        "moordyn"}
_TYPE_KEYS = {"standard", "nominal_diameter", "diameter", "mass_per_length",
              "weight_in_water", "axial_stiffness", "normal_drag", "tangential_drag",
              "added_mass", "tangential_added_mass", "mbl", "cost_per_length"}
_POINT_KEYS = {"name", "kind", "position", "body", "mass", "volume", "force"}
_BODY_KEYS = {"name", "kind", "held", "position", "rotation_deg", "mass", "center_of_gravity",
              "volume", "center_of_buoyancy", "waterplane_area", "waterplane_moments",
              "metacenter", "hydrostatic_matrix", "force", "moment"}
_LINE_KEYS = {"name", "point_a", "point_b", "parts", "type", "length"}
_SYSTEM_KEYS = {"tolerance", "max_iterations", "line_model"}

#: values of ``[system] line_model``
LINE_MODELS = ("auto", "collocation")
#: the smallest system.tolerance over solver.tolerance: the net forces of an equilibrium
#: stall at ~25 x the lines' scaled residual tolerance (seen on the 3- and 9-line spreads:
#: 2.3e-9 at 1e-10), so a system tolerance below 50 x it cannot be reached
LINE_FLOOR = 50.0
#: masses, kg (bodies and clumps)
MASS_MAX = 1e9
MASS_WHY = "heavier than the largest floating structure (~6e8 kg)"


def is_system(data: dict[str, Any]) -> bool:
    """True when a problem dict is a mooring system (it has a ``lines`` array).

    Parameters
    ----------
    data : dict
        The problem as read from TOML.
    """
    return isinstance(data, dict) and "lines" in data


def is_moordyn_path(path: str | Path) -> bool:
    """True when ``path`` ends as a MoorDyn input file does (:data:`MOORDYN_SUFFIXES`).

    Parameters
    ----------
    path : str or Path
        A file name.
    """
    return Path(path).suffix.lower() in MOORDYN_SUFFIXES


def load_system(path: str | Path, overrides: dict[str, Any] | None = None) -> SystemScene:
    """Read a system (our TOML, or a MoorDyn v2 input file) and validate it.

    Parameters
    ----------
    path : str or Path
        The file.
    overrides : dict, optional
        Dotted keys set before validation (``--set``), e.g. ``{"bodies.0.force": [...]}``.
    """
    if is_moordyn_path(path):
        from cable_ocp.scene.moordyn import read_moordyn

        data = read_moordyn(path)
    else:
        data = read_problem(path)
    if not is_system(data):
        raise CableOCPError(f"{str(path)!r} is not a mooring system: it has no [[lines]]")
    if overrides:
        data = apply_overrides(data, overrides)
    return system_from_dict(data)


@dataclass(frozen=True)
class LineType:
    """A named line type (``[line_types.NAME]``).

    Attributes
    ----------
    name : str
        Its name in the file.
    diameter : float
        Volume-equivalent diameter, m (buoyancy and drag).
    weight_in_water : float
        Weight in water per unstretched length, N/m.
    mass_per_length : float or None
        Mass in air per unstretched length, kg/m (None when only the weight was given).
    axial_stiffness : float
        EA, N (``math.inf``: inextensible).
    normal_drag, tangential_drag : float
        C_dn on the diameter, C_dt on the perimeter pi d (-).
    added_mass, tangential_added_mass : float
        C_an, C_at (-); not used by the statics, kept for MoorDyn files and the dynamics.
    mbl : float or None
        Minimum breaking load, N (None: no safety factor).
    cost_per_length : float or None
        Cost per unstretched metre (currency/m), for the design objective.
    """

    name: str
    diameter: float
    weight_in_water: float
    mass_per_length: float | None = None
    axial_stiffness: float = math.inf
    normal_drag: float = 0.0
    tangential_drag: float = 0.0
    added_mass: float = 0.0
    tangential_added_mass: float = 0.0
    mbl: float | None = None
    cost_per_length: float | None = None


@dataclass(frozen=True)
class Point:
    """A point of the system (``[[points]]``).

    Attributes
    ----------
    name : str
        Its name.
    kind : str
        ``"fixed"`` (held at ``position``), ``"body"`` (on ``body``, at ``position`` in
        the body frame relative to its reference point) or ``"free"`` (found; ``position``
        is the first guess).
    position : tuple of float
        m, as ``kind`` says.
    body : str or None
        The body's name (kind ``"body"``).
    mass : float
        Mass, kg (free points).
    volume : float
        Displaced volume, m^3 (free points).
    force : tuple of float
        External steady load on the point, N.
    """

    name: str
    kind: str
    position: tuple[float, float, float]
    body: str | None = None
    mass: float = 0.0
    volume: float = 0.0
    force: tuple[float, float, float] = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class SystemBody:
    """A rigid body with six degrees of freedom (``[[bodies]]``).

    Attributes
    ----------
    name : str
        Its name.
    held : tuple of bool
        Per degree of freedom (:data:`DOF_NAMES`), True where it is held at the file's
        value; all True for ``kind = "fixed"``.
    position : tuple of float
        Reference point, m (moments are about it).
    rotation : tuple of float
        (roll, pitch, yaw), rad; R = Rz(yaw) Ry(pitch) Rx(roll).
    mass : float
        kg. center_of_gravity, center_of_buoyancy, metacenter: m, body frame.
    volume : float
        Displaced volume, m^3, at the file's draft.
    waterplane_area : float
        m^2 (the heave restoring rho g A_wp per metre below the waterline).
    waterplane_moments : tuple of float
        (Ixx, Iyy), m^4, about the waterplane's centroid axes.
    hydrostatic_matrix : tuple or None
        6x6 (N/m, N, N m per rad) restoring about the file's pose; replaces the above.
    force, moment : tuple of float
        External steady load at the reference point, N and N m.
    """

    name: str
    held: tuple[bool, ...]
    position: tuple[float, float, float]
    rotation: tuple[float, float, float] = (0.0, 0.0, 0.0)
    mass: float = 0.0
    center_of_gravity: tuple[float, float, float] = (0.0, 0.0, 0.0)
    volume: float = 0.0
    center_of_buoyancy: tuple[float, float, float] = (0.0, 0.0, 0.0)
    metacenter: tuple[float, float, float] | None = None
    waterplane_area: float = 0.0
    waterplane_moments: tuple[float, float] = (0.0, 0.0)
    hydrostatic_matrix: tuple[tuple[float, ...], ...] | None = None
    force: tuple[float, float, float] = (0.0, 0.0, 0.0)
    moment: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @property
    def free(self) -> bool:
        """True when some degree of freedom is found by the equilibrium."""
        return not all(self.held)


@dataclass(frozen=True)
class SystemLine:
    """A line between two points (``[[lines]]``), of one or more parts.

    Attributes
    ----------
    name : str
        Its name.
    point_a, point_b : str
        The points at its ends; the parts run from point_a.
    parts : tuple of (str, float)
        (line type name, unstretched length in m), from point_a.
    scene : Scene
        The line as a single-line statics scene with both ends fixed at the file's
        positions, end_a at the lower end (``reversed`` when that is point_b).
    reversed : bool
        True when the scene's end_a is point_b (the lower end, where the seabed contact is
        modelled).
    """

    name: str
    point_a: str
    point_b: str
    parts: tuple[tuple[str, float], ...]
    scene: Scene = field(repr=False, compare=False)
    reversed: bool = False

    @property
    def length(self) -> float:
        """Unstretched length, m."""
        return sum(length for _, length in self.parts)


@dataclass(frozen=True)
class SystemScene:
    """A validated mooring system.

    Attributes
    ----------
    environment : Environment
        Water, current and seabed (as for one line).
    line_types : dict
        Name -> :class:`LineType`.
    points, bodies, lines : tuple
        :class:`Point`, :class:`SystemBody`, :class:`SystemLine`, in file order.
    solver : SolverOptions
        The line solver's options (shared by every line).
    tolerance : float
        Relative force residual of the equilibrium (-): the largest net force (N) on a
        free point or body, over the largest line tension.
    max_iterations : int
        Newton iterations of the equilibrium.
    line_model : str
        ``"auto"``: a line gets the closed-form elastic catenary where it is exact (no
        current, one line type, no bending stiffness, a flat seabed z = 0 or none,
        :func:`cable_ocp.statics.catenary_line.catenary_exact`), else the collocation;
        ``"collocation"``: every line by collocation.
    meta : dict
        ``[meta]`` strings.
    raw : dict
        The problem dict as given (for ``--set``, batches and writing files back).
    """

    environment: Environment
    line_types: dict[str, LineType]
    points: tuple[Point, ...]
    bodies: tuple[SystemBody, ...]
    lines: tuple[SystemLine, ...]
    solver: SolverOptions
    tolerance: float = 1e-8
    max_iterations: int = 50
    line_model: str = "auto"
    meta: dict[str, str] = field(default_factory=dict)
    raw: dict[str, Any] = field(default_factory=dict, repr=False, compare=False)

    def point(self, name: str) -> Point:
        """The point called ``name``.

        Parameters
        ----------
        name : str
            A point's name.
        """
        for p in self.points:
            if p.name == name:
                return p
        raise CableOCPError(f"no point {name!r}; points: {', '.join(p.name for p in self.points)}")

    def body(self, name: str) -> SystemBody:
        """The body called ``name``.

        Parameters
        ----------
        name : str
            A body's name.
        """
        for b in self.bodies:
            if b.name == name:
                return b
        raise CableOCPError(f"no body {name!r}; bodies: "
                            f"{', '.join(b.name for b in self.bodies) or '(none)'}")


def _name(t: dict[str, Any], where: str, seen: set[str]) -> str:
    name = require(t, "name", where)
    if not isinstance(name, str) or not name.strip():
        raise CableOCPError(f"{where}.name = {name!r}: expected a non-empty string")
    if name in seen:
        raise CableOCPError(f"{where}.name = {name!r}: the name is used twice")
    seen.add(name)
    return name


def _parse_type(name: str, t: Any, rho: float, g: float) -> LineType:
    where = f"line_types.{name}"
    t = dict(check_keys(t, _TYPE_KEYS, where))
    if "standard" in t:
        from cable_ocp.physics.line_types import standard_line_type

        d_nom = number(require(t, "nominal_diameter", where), f"{where}.nominal_diameter",
                       positive=True, unit="m")
        props = standard_line_type(str(t["standard"]), d_nom)
        base = {"diameter": props.diameter, "mass_per_length": props.mass_per_length,
                "axial_stiffness": props.axial_stiffness, "normal_drag": props.normal_drag,
                "tangential_drag": props.tangential_drag, "added_mass": props.added_mass,
                "tangential_added_mass": props.tangential_added_mass, "mbl": props.mbl,
                "cost_per_length": props.cost_per_length}
        if "weight_in_water" in t:
            base.pop("mass_per_length")
        t = {**base, **{k: v for k, v in t.items() if k not in ("standard", "nominal_diameter")}}
    elif "nominal_diameter" in t:
        raise CableOCPError(f"{where}.nominal_diameter needs {where}.standard (one of the "
                            "standard line types, docs/line_types.md)")
    d = number(require(t, "diameter", where), f"{where}.diameter", positive=True, high=10.0,
               unit="m", why="the volume-equivalent diameter of a line")
    if "mass_per_length" in t:
        m = number(t["mass_per_length"], f"{where}.mass_per_length", positive=True,
                   high=1e5, unit="kg/m", why="100x the heaviest chain")
        w = (m - rho * math.pi * d * d / 4.0) * g
        if "weight_in_water" in t:
            raise CableOCPError(f"{where}: give mass_per_length or weight_in_water, not both "
                                f"(the mass gives {w:.6g} N/m in this water)")
    else:
        m = None
        if "weight_in_water" not in t:
            raise CableOCPError(f"{where}: needs mass_per_length (kg/m) or weight_in_water (N/m)")
        w = number(t["weight_in_water"], f"{where}.weight_in_water", low=-1e6, high=1e6,
                   unit="N/m")

    def opt(key: str, default: float | None, unit: str) -> float | None:
        if key not in t:
            return default
        return number(t[key], f"{where}.{key}", nonneg=True, allow_inf=key == "axial_stiffness",
                      unit=unit)

    ea = opt("axial_stiffness", math.inf, "N")
    if ea is not None and ea <= 0.0:
        raise CableOCPError(f"{where}.axial_stiffness = {ea}: must be > 0 (N)")
    return LineType(name=name, diameter=d, weight_in_water=w, mass_per_length=m,
                    axial_stiffness=ea,  # type: ignore[arg-type]
                    normal_drag=opt("normal_drag", 0.0, "-"),  # type: ignore[arg-type]
                    tangential_drag=opt("tangential_drag", 0.0, "-"),  # type: ignore[arg-type]
                    added_mass=opt("added_mass", 0.0, "-"),  # type: ignore[arg-type]
                    tangential_added_mass=opt("tangential_added_mass", 0.0,  # type: ignore
                                              "-"),
                    mbl=opt("mbl", None, "N"), cost_per_length=opt("cost_per_length", None,
                                                                  "currency/m"))


def _vec(t: dict[str, Any], key: str, where: str, bound: float, unit: str, why: str,
         default: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> tuple[float, float, float]:
    if key not in t:
        return default
    return vector3(t[key], f"{where}.{key}", bound=bound, unit=unit, why=why)  # type: ignore


def _parse_point(t: Any, i: int, seen: set[str]) -> Point:
    where = f"points[{i}]"
    t = check_keys(t, _POINT_KEYS, where)
    name = _name(t, where, seen)
    kind = choice(require(t, "kind", where), f"{where}.kind", ("fixed", "body", "free"))
    pos = vector3(require(t, "position", where), f"{where}.position", bound=COORD_MAX,
                  unit="m", why=COORD_WHY)
    body = t.get("body")
    if kind == "body" and not isinstance(body, str):
        raise CableOCPError(f"{where}.body: a point of kind \"body\" names its body")
    if kind != "body" and body is not None:
        raise CableOCPError(f"{where}.body: only a point of kind \"body\" is on a body "
                            f"(this one is {kind!r})")
    for key in ("mass", "volume", "force"):
        if kind != "free" and key in t:
            raise CableOCPError(f"{where}.{key}: only a free point carries its own {key} "
                                f"(this one is {kind!r}: its load is taken by what holds it)")
    return Point(name=name, kind=kind, position=pos, body=body,  # type: ignore[arg-type]
                 mass=number(t.get("mass", 0.0), f"{where}.mass", nonneg=True, high=MASS_MAX,
                             unit="kg", why=MASS_WHY),
                 volume=number(t.get("volume", 0.0), f"{where}.volume", nonneg=True,
                               high=1e6, unit="m^3"),
                 force=_vec(t, "force", where, BODY_MAX, "N", BODY_WHY))


def _parse_body(t: Any, i: int, seen: set[str]) -> SystemBody:
    where = f"bodies[{i}]"
    t = check_keys(t, _BODY_KEYS, where)
    name = _name(t, where, seen)
    kind = choice(t.get("kind", "free"), f"{where}.kind", ("free", "fixed"))
    held_t = t.get("held", [])
    if not isinstance(held_t, list) or any(h not in DOF_NAMES for h in held_t):
        raise CableOCPError(f"{where}.held = {held_t!r}: expected a list of "
                            f"{', '.join(DOF_NAMES)}")
    held = tuple(kind == "fixed" or d in held_t for d in DOF_NAMES)
    rot = _vec(t, "rotation_deg", where, 360.0, "deg", "an angle in degrees")
    matrix = None
    if "hydrostatic_matrix" in t:
        mt = t["hydrostatic_matrix"]
        if (not isinstance(mt, list) or len(mt) != 6
                or any(not isinstance(r, list) or len(r) != 6 for r in mt)):
            raise CableOCPError(f"{where}.hydrostatic_matrix: expected 6 rows of 6 numbers")
        matrix = tuple(tuple(number(v, f"{where}.hydrostatic_matrix[{r}][{c}]")
                             for c, v in enumerate(row)) for r, row in enumerate(mt))
        for key in ("waterplane_area", "waterplane_moments", "metacenter"):
            if key in t:
                raise CableOCPError(f"{where}.{key}: hydrostatic_matrix replaces the "
                                    "waterplane; give one or the other")
    if "metacenter" in t and "waterplane_moments" in t:
        raise CableOCPError(f"{where}: give waterplane_moments or metacenter, not both")
    wm = t.get("waterplane_moments", [0.0, 0.0])
    if not isinstance(wm, list) or len(wm) != 2:
        raise CableOCPError(f"{where}.waterplane_moments = {wm!r}: expected [Ixx, Iyy] (m^4)")
    big = (1e5, "m")
    return SystemBody(
        name=name, held=held,
        position=vector3(require(t, "position", where), f"{where}.position", bound=COORD_MAX,
                         unit="m", why=COORD_WHY),  # type: ignore[arg-type]
        rotation=tuple(math.radians(a) for a in rot),  # type: ignore[arg-type]
        mass=number(t.get("mass", 0.0), f"{where}.mass", nonneg=True, high=MASS_MAX,
                    unit="kg", why=MASS_WHY),
        center_of_gravity=_vec(t, "center_of_gravity", where, big[0], "m", "body frame"),
        volume=number(t.get("volume", 0.0), f"{where}.volume", nonneg=True, high=1e9,
                      unit="m^3"),
        center_of_buoyancy=_vec(t, "center_of_buoyancy", where, big[0], "m", "body frame"),
        metacenter=(_vec(t, "metacenter", where, big[0], "m", "body frame")
                    if "metacenter" in t else None),
        waterplane_area=number(t.get("waterplane_area", 0.0), f"{where}.waterplane_area",
                               nonneg=True, high=1e7, unit="m^2"),
        waterplane_moments=tuple(number(v, f"{where}.waterplane_moments[{k}]", nonneg=True,
                                        unit="m^4") for k, v in enumerate(wm)),  # type: ignore
        hydrostatic_matrix=matrix,
        force=_vec(t, "force", where, FORCE_MAX, "N", FORCE_WHY),
        moment=_vec(t, "moment", where, FORCE_MAX * 1e3, "N m", "a force times 1 km"),
    )


def _parts(t: dict[str, Any], where: str, types: dict[str, LineType]
           ) -> tuple[tuple[str, float], ...]:
    if "parts" in t:
        if "type" in t or "length" in t:
            raise CableOCPError(f"{where}: give parts, or type and length, not both")
        raw = t["parts"]
        if not isinstance(raw, list) or not raw:
            raise CableOCPError(f"{where}.parts: expected a non-empty array of "
                                "{type = ..., length = ...}")
        items = [(check_keys(p, {"type", "length"}, f"{where}.parts[{k}]"), f"{where}.parts[{k}]")
                 for k, p in enumerate(raw)]
    else:
        items = [({"type": require(t, "type", where), "length": require(t, "length", where)},
                  where)]
    out = []
    for p, w in items:
        name = require(p, "type", w)
        if name not in types:
            raise CableOCPError(f"{w}.type = {name!r}: no such line type; defined: "
                                f"{', '.join(sorted(types)) or '(none: add [line_types.NAME])'}")
        out.append((name, number(require(p, "length", w), f"{w}.length", positive=True,
                                 low=1e-2, high=1e5, unit="m")))
    return tuple(out)


def _line_dict(data: dict[str, Any], parts: tuple[tuple[str, float], ...],
               types: dict[str, LineType], end_a: tuple[float, ...], end_b: tuple[float, ...]
               ) -> dict[str, Any]:
    """The single-line problem dict of one line (today's schema), ends fixed."""
    segs = []
    for name, length in parts:
        lt = types[name]
        seg = {"length": length, "diameter": lt.diameter, "weight_in_water": lt.weight_in_water,
               "normal_drag": lt.normal_drag, "tangential_drag": lt.tangential_drag}
        if math.isfinite(lt.axial_stiffness):
            seg["axial_stiffness"] = lt.axial_stiffness
        segs.append(seg)
    cable: dict[str, Any] = {"segments": segs}
    if len(segs) == 1:
        cable = dict(segs[0])
    return {"environment": copy.deepcopy(data["environment"]), "cable": cable,
            "end_a": {"position": list(end_a)}, "end_b": {"position": list(end_b)},
            **({"solver": copy.deepcopy(data["solver"])} if "solver" in data else {})}


def initial_position(point: Point, bodies: dict[str, SystemBody]) -> tuple[float, float, float]:
    """A point's global position at the file's poses, m.

    Parameters
    ----------
    point : Point
        The point.
    bodies : dict
        Name -> body.
    """
    if point.kind != "body":
        return point.position
    from cable_ocp.numerics.rotation import rotation_matrix

    b = bodies[point.body]  # type: ignore[index]
    r = rotation_matrix(*b.rotation) @ list(point.position)
    return tuple(float(b.position[k] + r[k]) for k in range(3))  # type: ignore[return-value]


def _check_reach(where: str, name: str, total: float, xa: tuple[float, ...],
                 xb: tuple[float, ...], rev: bool, seabed: bool) -> None:
    """A line between held points longer than the way down to the seabed and back
    would lie on the seabed between its ends: modelled only from a lower end on a
    modelled seabed (the touchdown of :mod:`cable_ocp.physics.seabed`)."""
    low = xb if rev else xa
    reach = math.hypot(xa[0] - xb[0], xa[1] - xb[1]) + xa[2] + xb[2]
    if total > reach and not (seabed and abs(low[2]) < 1e-9):
        raise CableOCPError(
            f"{where} ({name}): {total:g} m is longer than the way from its ends down to the "
            f"seabed and along it ({reach:.6g} m): it would lie on the seabed between its "
            "ends, which is modelled only from an end on the seabed with "
            "[environment.seabed]; shorten it")


def system_from_dict(data: dict[str, Any]) -> SystemScene:
    """Validate a system problem dict (as read from TOML) and return a :class:`SystemScene`.

    Parameters
    ----------
    data : dict
        The problem, with a ``lines`` array (:func:`is_system`).

    Raises
    ------
    CableOCPError
        On unknown keys or tables, missing or out-of-range values, unknown names (line
        types, points, bodies), a line whose two ends are one point, or a line that no
        catenary can hold (shorter than the span of its fixed ends, inextensible).
    """
    if not isinstance(data, dict):
        raise CableOCPError("a problem must be a table")
    raw = copy.deepcopy(data)
    unknown = sorted(set(data) - _TOP)
    if unknown:
        raise CableOCPError(f"unknown top-level table [{unknown[0]}] in a system; valid: "
                            f"{', '.join(sorted(_TOP))}")
    meta = parse_meta(data.get("meta", {}))
    env_t = require(data, "environment", "problem")
    if not isinstance(env_t, dict):
        raise CableOCPError("[environment] must be a table")
    rho = number(require(env_t, "water_density", "environment"), "environment.water_density",
                 low=0.1, high=2000.0, unit="kg/m^3")
    g = number(env_t.get("gravity", 9.81), "environment.gravity", low=0.1, high=30.0,
               unit="m/s^2")
    types_t = require(data, "line_types", "system")
    if not isinstance(types_t, dict) or not types_t:
        raise CableOCPError("[line_types]: expected one table per line type, e.g. "
                            "[line_types.chain]")
    types = {name: _parse_type(name, t, rho, g) for name, t in types_t.items()}
    seen: set[str] = set()
    pts_t = require(data, "points", "system")
    if not isinstance(pts_t, list) or not pts_t:
        raise CableOCPError("points: expected an array of tables ([[points]])")
    points = tuple(_parse_point(t, i, seen) for i, t in enumerate(pts_t))
    seen_b: set[str] = set()
    bodies_t = data.get("bodies", [])
    if not isinstance(bodies_t, list):
        raise CableOCPError("bodies: expected an array of tables ([[bodies]])")
    bodies = tuple(_parse_body(t, i, seen_b) for i, t in enumerate(bodies_t))
    by_body = {b.name: b for b in bodies}
    by_point = {p.name: p for p in points}
    for i, p in enumerate(points):
        if p.kind == "body" and p.body not in by_body:
            raise CableOCPError(f"points[{i}].body = {p.body!r}: no such body; bodies: "
                                f"{', '.join(by_body) or '(none: add [[bodies]])'}")
    lines_t = data["lines"]
    if not isinstance(lines_t, list) or not lines_t:
        raise CableOCPError("lines: expected a non-empty array of tables ([[lines]])")
    seen_l: set[str] = set()
    lines = []
    used: set[str] = set()
    for i, t in enumerate(lines_t):
        where = f"lines[{i}]"
        t = check_keys(t, _LINE_KEYS, where)
        name = _name(t, where, seen_l)
        ends = []
        for key in ("point_a", "point_b"):
            pname = require(t, key, where)
            if pname not in by_point:
                raise CableOCPError(f"{where}.{key} = {pname!r}: no such point; points: "
                                    f"{', '.join(by_point)}")
            ends.append(pname)
        if ends[0] == ends[1]:
            raise CableOCPError(f"{where}: point_a and point_b are both {ends[0]!r}: a line "
                                "joins two different points")
        used.update(ends)
        parts = _parts(t, where, types)
        xa, xb = (initial_position(by_point[e], by_body) for e in ends)
        total = sum(length for _, length in parts)
        if (all(by_point[e].kind != "free" for e in ends)
                and all(not math.isfinite(types[n].axial_stiffness) for n, _ in parts)):
            chord = math.dist(xa, xb)
            if chord >= total:
                raise CableOCPError(
                    f"{where}: the line ({total:g} m, inextensible) is not longer than the "
                    f"span between {ends[0]!r} and {ends[1]!r} ({chord:.6g} m): no catenary "
                    "can hold it; lengthen it or give its line types an axial_stiffness")
        rev = xb[2] < xa[2]
        if all(by_point[e].kind != "free" for e in ends):
            _check_reach(where, name, total, xa, xb, rev, "seabed" in env_t)
        seq = tuple(reversed(parts)) if rev else parts
        lo, hi = (xb, xa) if rev else (xa, xb)
        try:
            scene = scene_from_dict(_line_dict(data, seq, types, lo, hi))
        except CableOCPError as exc:
            raise CableOCPError(f"{where} ({name}): {exc}") from None
        lines.append(SystemLine(name=name, point_a=ends[0], point_b=ends[1], parts=parts,
                                scene=scene, reversed=rev))
    for p in points:
        if p.name not in used:
            raise CableOCPError(f"point {p.name!r} is on no line: remove it or connect it")
    sys_t = check_keys(data.get("system", {}), _SYSTEM_KEYS, "system")
    tol = number(sys_t.get("tolerance", 1e-8), "system.tolerance", low=1e-14, high=1e-2,
                 unit="-", why="the net force on a free point or body over the largest "
                               "tension")
    max_it = integer(sys_t.get("max_iterations", 50), "system.max_iterations", 1, 1000)
    line_model = choice(sys_t.get("line_model", "auto"), "system.line_model", LINE_MODELS)
    first = lines[0].scene
    floor = LINE_FLOOR * first.solver.tolerance
    if tol < floor:
        raise CableOCPError(
            f"system.tolerance = {tol:g}: must be >= {floor:g} ({LINE_FLOOR:g} x "
            f"solver.tolerance = {first.solver.tolerance:g}): the lines' end forces are "
            "accurate to about that, so a smaller net force cannot be told from zero; "
            "lower solver.tolerance with it")
    return SystemScene(environment=first.environment, line_types=types, points=points,
                       bodies=bodies, lines=tuple(lines), solver=first.solver, tolerance=tol,
                       max_iterations=max_it, line_model=line_model, meta=meta,
                       raw=raw)
