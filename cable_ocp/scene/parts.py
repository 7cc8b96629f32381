"""The parts every scene kind shares: environment (water, current, seabed), cable and
segments, point bodies and end conditions, as frozen dataclasses with their parsers.

Units are SI throughout. The statics schema (:mod:`cable_ocp.scene.statics`) lists every
key; the dynamics scenes reuse these tables and add their own.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

from cable_ocp.errors import CableOCPError
from cable_ocp.physics import seabed as _seabed
from cable_ocp.physics.current import is_uniform, profile_velocity_np
from cable_ocp.physics.elasticity import TensionStrainTable
from cable_ocp.physics.viscoelastic import StandardLinearSolid
from cable_ocp.scene.fields import FREE, check_keys, number, require, vector3

END_KEYS = {"position", "force", "tension"}
CURRENT_KEYS = {"speed", "heading_deg", "profile"}
SEABED_KEYS = {"depth_offset", "friction", "slope_deg", "slope_heading_deg"}
SEGMENT_KEYS = {"length", "diameter", "weight_in_water", "axial_stiffness", "normal_drag",
                "tangential_drag", "intervals", "bending_stiffness"}
BODY_KEYS = {"joint", "kind", "weight_in_water", "net_buoyancy", "drag_area",
             "drag_coefficient", "thrust"}

# Ranges of the numbers every scene kind shares, with the reason for each bound. They are
# wide (physical extremes, not design limits) and keep every number far from overflow.
#: coordinates, m
COORD_MAX = 1e5
COORD_WHY = "further than the longest cable (100 km)"
#: depths, m
DEPTH_MAX = 12000.0
DEPTH_WHY = "deeper than the deepest ocean (10.9 km)"
#: forces and tensions, N
FORCE_MAX = 1e10
FORCE_WHY = "above the breaking load of any cable or chain (~2e7 N)"
#: weights per length, N/m
WEIGHT_MAX = 1e6
WEIGHT_WHY = "100x the heaviest mooring chain (~8e3 N/m in water)"
#: point loads of bodies, N
BODY_MAX = 1e9
BODY_WHY = "more than any crane vessel lifts (~2e8 N)"
#: drag coefficients, -
CD_MAX = 10.0
CD_WHY = "drag coefficients of cables, chains and bodies are 0.005-3"
#: current speeds, m/s
SPEED_MAX = 30.0
SPEED_WHY = "the fastest tidal races are ~6 m/s, fast tows ~15 m/s"
#: angles, deg
ANGLE_MAX = 360.0
ANGLE_WHY = "an angle in degrees"
#: cable lengths, m
LENGTH_MIN, LENGTH_MAX = 1e-2, 1e5
LENGTH_WHY = "from 1 cm to 100 km (deep-tow cables reach ~12 km)"


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
        return is_uniform(self.z, self.ux, self.uy)

    def velocity(self, z: Any) -> Any:
        """Velocity (m/s) at heights z (m), shape ``z.shape + (3,)``
        (:func:`cable_ocp.physics.current.profile_velocity_np`)."""
        return profile_velocity_np(z, self.z, self.ux, self.uy)

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

    def normal(self) -> Any:
        """Unit normal of the plane, up into the water (:mod:`cable_ocp.physics.seabed`)."""
        return _seabed.plane_normal(self.slope_deg, self.slope_heading_deg)

    def height(self, x: Any, y: Any) -> Any:
        """Seabed height z (m) at (x, y).

        Parameters
        ----------
        x, y : float or array
            Horizontal position, m.
        """
        return _seabed.plane_height(x, y, self.slope_deg, self.slope_heading_deg,
                                    self.depth_offset)

    def gap(self, r: Any) -> Any:
        """Signed distance (m) of points r (n, 3) above the plane (negative = below)."""
        return _seabed.plane_gap(r, self.slope_deg, self.slope_heading_deg, self.depth_offset)


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
    tension_strain : tuple of (float, float)
        ``[cable] tension_strain`` rows (T_k N, e_k -), () for the linear law. With a
        table, ``axial_stiffness`` holds its largest tangent stiffness (N; the wave
        speeds and scales), and the law is the table
        (:class:`cable_ocp.physics.elasticity.TensionStrainTable`).
    viscoelastic : Viscoelastic or None
        ``[cable] viscoelastic``: the standard linear solid of the dynamics, whose static
        modulus is ``axial_stiffness``.
    """

    length: float | None
    diameter: float
    weight_in_water: float
    axial_stiffness: float = math.inf
    normal_drag: float = 0.0
    tangential_drag: float = 0.0
    drag_law: str = "vector"
    bending_stiffness: float = 0.0
    tension_strain: tuple[tuple[float, float], ...] = ()
    viscoelastic: Viscoelastic | None = None

    @property
    def elastic(self) -> bool:
        """True when EA is finite."""
        return math.isfinite(self.axial_stiffness)

    @property
    def strain_table(self) -> TensionStrainTable | None:
        """The tension-strain table's law, or None for the linear law."""
        if not self.tension_strain:
            return None
        return TensionStrainTable(tuple(r[0] for r in self.tension_strain),
                                  tuple(r[1] for r in self.tension_strain))

    def strain_at(self, tension: Any) -> Any:
        """Static strain at a tension (-): e(T) of the table, else T / EA (the static
        modulus of a viscoelastic cable).

        Parameters
        ----------
        tension : float, array or casadi expression
            Tension, N.
        """
        table = self.strain_table
        if table is not None:
            return table.strain_of(tension)
        return tension / self.axial_stiffness


@dataclass(frozen=True)
class Viscoelastic:
    """``[cable] viscoelastic = {dynamic_stiffness, relaxation_time}``: a standard linear
    solid (:class:`cable_ocp.physics.elasticity.StandardLinearSolid`) whose static modulus
    is the cable's ``axial_stiffness``.

    Attributes
    ----------
    dynamic_stiffness : float
        EA_d, N (>= axial_stiffness): the modulus under a fast load.
    relaxation_time : float
        tau, s.
    """

    dynamic_stiffness: float
    relaxation_time: float

    def law(self, static_stiffness: float) -> StandardLinearSolid:
        """The law with EA_s = ``static_stiffness`` (N).

        Parameters
        ----------
        static_stiffness : float
            EA_s, N.
        """
        return StandardLinearSolid(static_stiffness, self.dynamic_stiffness,
                                   self.relaxation_time)


#: keys of ``[cable] viscoelastic``
VISCOELASTIC_KEYS = {"dynamic_stiffness", "relaxation_time"}
#: the largest strain of a tension-strain row, -: synthetic ropes break at 15-40 %
STRAIN_MAX = 1.0


def parse_tension_strain(value: Any, key: str = "cable.tension_strain"
                         ) -> tuple[tuple[float, float], ...]:
    """``[[T_k, e_k], ...]`` -> validated rows: (0, 0) first, then at least one more row,
    tension and strain both strictly increasing (a monotone law), 0 < e <= 1.

    Parameters
    ----------
    value : Any
        The TOML value: an array of [tension (N), strain (-)] pairs.
    key : str
        Dotted key for the messages.
    """
    form = (f"{key}: expected an array of [tension_N, strain] pairs starting at [0, 0], "
            "e.g. [[0, 0], [1e4, 0.01], [3e4, 0.02]]")
    if not isinstance(value, list) or len(value) < 2:
        raise CableOCPError(form + f" (got {value!r}: at least two rows)")
    rows = []
    for i, r in enumerate(value):
        if not isinstance(r, list) or len(r) != 2:
            raise CableOCPError(form + f"; row {i} is {r!r}")
        t = number(r[0], f"{key}[{i}][0]", nonneg=True, high=FORCE_MAX, unit="N",
                   why=FORCE_WHY)
        e = number(r[1], f"{key}[{i}][1]", nonneg=True, high=STRAIN_MAX, unit="-",
                   why="synthetic ropes break at 15-40 % strain")
        rows.append((t, e))
    if rows[0] != (0.0, 0.0):
        raise CableOCPError(f"{key}[0] = {value[0]!r}: the first row must be [0, 0] (no "
                            "tension at zero strain)")
    for i in range(1, len(rows)):
        if not (rows[i][0] > rows[i - 1][0] and rows[i][1] > rows[i - 1][1]):
            raise CableOCPError(
                f"{key}[{i}] = {value[i]!r}: not monotonic: tension and strain must both "
                f"increase from row {i - 1} ({value[i - 1]!r})")
    return tuple(rows)


def parse_material(cab_t: dict[str, Any], where: str = "cable"
                   ) -> tuple[float | None, tuple[tuple[float, float], ...],
                              Viscoelastic | None]:
    """``tension_strain`` and ``viscoelastic`` of a cable table -> (axial_stiffness to
    use or None (the key's own), rows, viscoelastic law).

    Parameters
    ----------
    cab_t : dict
        The ``[cable]`` table.
    where : str
        Its dotted key.
    """
    rows: tuple[tuple[float, float], ...] = ()
    ea = None
    if "tension_strain" in cab_t:
        if "axial_stiffness" in cab_t:
            raise CableOCPError(f"{where}.axial_stiffness: give either axial_stiffness (a "
                                "linear law) or tension_strain (a table), not both")
        rows = parse_tension_strain(cab_t["tension_strain"], f"{where}.tension_strain")
        table = TensionStrainTable(tuple(r[0] for r in rows), tuple(r[1] for r in rows))
        ea = table.max_stiffness
    visco = None
    if "viscoelastic" in cab_t:
        vk = f"{where}.viscoelastic"
        v_t = cab_t["viscoelastic"]
        if not isinstance(v_t, dict):
            raise CableOCPError(f"{vk}: expected a table {{dynamic_stiffness = N, "
                                "relaxation_time = s}")
        v_t = check_keys(v_t, VISCOELASTIC_KEYS, vk)
        if rows:
            raise CableOCPError(f"{vk}: a viscoelastic law needs a linear static modulus "
                                f"({where}.axial_stiffness); remove {where}.tension_strain")
        if "axial_stiffness" not in cab_t:
            raise CableOCPError(f"{vk}: give {where}.axial_stiffness, the static modulus "
                                "EA_s (N)")
        ea_s = cable_number(cab_t["axial_stiffness"], f"{where}.axial_stiffness",
                            "axial_stiffness")
        ea_d = number(require(v_t, "dynamic_stiffness", vk), f"{vk}.dynamic_stiffness",
                      positive=True, low=ea_s, high=1e14, unit="N",
                      why=f"at least the static modulus {where}.axial_stiffness = {ea_s:g} N")
        tau = number(require(v_t, "relaxation_time", vk), f"{vk}.relaxation_time",
                     positive=True, high=1e9, unit="s",
                     why="synthetic ropes relax in 0.1 s to days")
        visco = Viscoelastic(ea_d, tau)
    return ea, rows, visco


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



def parse_meta(table: Any) -> dict[str, str]:
    """``[meta]``: free-form text (title, source, notes, ...); every value a string."""
    if not isinstance(table, dict):
        raise CableOCPError(f"[meta] must be a table of strings (title, source, ...), got "
                            f"{table!r}")
    for key, value in table.items():
        if not isinstance(value, (str, int, float)) or isinstance(value, bool):
            raise CableOCPError(f"meta.{key} = {value!r}: expected a string")
    return {str(k): str(v) for k, v in table.items()}


def parse_current(table: Any) -> Current | None:
    table = check_keys(table, CURRENT_KEYS, "environment.current")
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
            rows.append((number(row[0], key + "[0]", low=-DEPTH_MAX, high=DEPTH_MAX, unit="m",
                                why=DEPTH_WHY),
                         number(row[1], key + "[1]", nonneg=True, high=SPEED_MAX, unit="m/s",
                                why=SPEED_WHY),
                         number(row[2], key + "[2]", low=-ANGLE_MAX, high=ANGLE_MAX,
                                unit="deg", why=ANGLE_WHY)))
        rows.sort(key=lambda r: r[0])
        zs = [r[0] for r in rows]
        if any(b <= a for a, b in zip(zs, zs[1:], strict=False)):
            raise CableOCPError("environment.current.profile: knot heights z must be distinct")
        ux = tuple(r[1] * math.cos(math.radians(r[2])) for r in rows)
        uy = tuple(r[1] * math.sin(math.radians(r[2])) for r in rows)
        cur = Current(z=tuple(zs), ux=ux, uy=uy)
    else:
        speed = number(require(table, "speed", "environment.current"),
                       "environment.current.speed", nonneg=True, high=SPEED_MAX, unit="m/s",
                       why=SPEED_WHY)
        heading = number(table.get("heading_deg", 0.0), "environment.current.heading_deg",
                         low=-ANGLE_MAX, high=ANGLE_MAX, unit="deg", why=ANGLE_WHY)
        cur = Current(z=(0.0,), ux=(speed * math.cos(math.radians(heading)),),
                      uy=(speed * math.sin(math.radians(heading)),))
    if cur.max_speed == 0.0:
        return None
    return cur


def parse_seabed(table: Any) -> Seabed:
    table = check_keys(table, SEABED_KEYS,
                        "environment.seabed")
    slope = number(table.get("slope_deg", 0.0), "environment.seabed.slope_deg", nonneg=True,
                   unit="deg")
    if slope >= 45.0:
        raise CableOCPError(f"environment.seabed.slope_deg = {slope}: must be in [0, 45) "
                            "(deg); steeper slopes are walls, not a seabed the model holds for")
    return Seabed(
        depth_offset=number(table.get("depth_offset", 0.0), "environment.seabed.depth_offset",
                            low=-DEPTH_MAX, high=DEPTH_MAX, unit="m", why=DEPTH_WHY),
        friction=number(table.get("friction", 0.0), "environment.seabed.friction", nonneg=True,
                        high=10.0, unit="-",
                        why="axial friction of cables and chains on soil is 0.1-1.5"),
        slope_deg=slope,
        slope_heading_deg=number(table.get("slope_heading_deg", 0.0),
                                 "environment.seabed.slope_heading_deg", low=-ANGLE_MAX,
                                 high=ANGLE_MAX, unit="deg", why=ANGLE_WHY),
    )


def parse_end(table: Any, name: str) -> End:
    """``[end_a]`` or ``[end_b]`` -> :class:`End`: per component exactly one of a position
    and a force, and an optional tension.

    Parameters
    ----------
    table : Any
        The end's TOML table: ``position = [x, y, z]`` (m) and/or ``force = [Fx, Fy, Fz]``
        (N, the external load on the attachment), entries ``"free"`` where not
        prescribed, and optionally ``tension`` (N, > 0), which needs a fully fixed
        position.
    name : str
        ``"end_a"`` (the lower end, s = 0) or ``"end_b"`` (the ship, s = L): the table's
        name in messages.
    """
    table = check_keys(table, END_KEYS, name)
    pos = (vector3(table["position"], f"{name}.position", bound=COORD_MAX, unit="m",
                   why=COORD_WHY) if "position" in table else None)
    frc = (vector3(table["force"], f"{name}.force", bound=FORCE_MAX, unit="N", why=FORCE_WHY)
           if "force" in table else None)
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
        tension = number(table["tension"], f"{name}.tension", positive=True, high=FORCE_MAX,
                         unit="N", why=FORCE_WHY)
        if not all(p is not None for p in pos):
            raise CableOCPError(
                f"{name}.tension needs a fully fixed {name}.position at the same end")
    return End(position=pos, force=frc, tension=tension)


def parse_law(cab_t: dict[str, Any]) -> str:
    law = cab_t.get("drag_law", "vector")
    if law not in ("vector", "componentwise"):
        raise CableOCPError(f'cable.drag_law = {law!r}: valid are "vector", "componentwise"')
    return law


#: cable and segment numbers: keyword arguments of :func:`~cable_ocp.scene.fields.number`
CABLE_RULES: dict[str, dict[str, Any]] = {
    "length": {"positive": True, "low": LENGTH_MIN, "high": LENGTH_MAX, "unit": "m",
               "why": LENGTH_WHY},
    "diameter": {"positive": True, "low": 1e-4, "high": 10.0, "unit": "m",
                 "why": "from a 0.1 mm line to a 10 m hose"},
    "weight_in_water": {"low": -WEIGHT_MAX, "high": WEIGHT_MAX, "unit": "N/m",
                        "why": WEIGHT_WHY},
    "axial_stiffness": {"positive": True, "allow_inf": True, "low": 1.0, "high": 1e14,
                        "unit": "N", "why": 'a 0.5 m steel bar has EA ~ 4e10 N; give "inf" '
                                            "for an inextensible cable"},
    "normal_drag": {"nonneg": True, "high": CD_MAX, "unit": "-", "why": CD_WHY},
    "tangential_drag": {"nonneg": True, "high": CD_MAX, "unit": "-", "why": CD_WHY},
    "bending_stiffness": {"nonneg": True, "high": 1e12, "unit": "N m^2",
                          "why": "a 1 m steel pipe with a 25 mm wall has EI ~ 2e9 N m^2"},
}


def cable_number(value: Any, key: str, name: str) -> float:
    """A cable or segment number ``name`` (a key of :data:`CABLE_RULES`) at ``key``.

    Parameters
    ----------
    value : Any
        The value as read from TOML, in the unit :data:`CABLE_RULES` gives for ``name``
        (m, N/m, N, N m^2 or (-)).
    key : str
        Dotted key for the message, e.g. ``"cable.segments[1].diameter"``.
    name : str
        The quantity: a key of :data:`CABLE_RULES` (``"length"``, ``"diameter"``,
        ``"weight_in_water"``, ``"axial_stiffness"``, ``"normal_drag"``,
        ``"tangential_drag"`` or ``"bending_stiffness"``), whose bounds and unit apply.
    """
    return number(value, key, **CABLE_RULES[name])


def parse_single_cable(cab_t: dict[str, Any], need_drag: bool) -> Cable:
    """``[cable]`` without segments -> one uniform :class:`Cable`.

    Parameters
    ----------
    cab_t : dict
        The ``[cable]`` table (keys already checked): ``length`` (m, or ``"free"`` for a
        length set by a prescribed end tension, then None), ``weight_in_water`` (N/m),
        optional ``axial_stiffness`` (N, default ``inf``: inextensible), ``diameter`` (m),
        ``normal_drag`` and ``tangential_drag`` (-), ``drag_law``.
    need_drag : bool
        True when the scene has a current: ``diameter``, ``normal_drag`` and
        ``tangential_drag`` are then required; otherwise each defaults to 0.
    """
    if "bending_stiffness" in cab_t:
        raise CableOCPError(
            "cable.bending_stiffness: bending stiffness is given per segment; put the stiff "
            "part in its own [[cable.segments]] entry with bending_stiffness (EI, N m^2)")
    length_v = require(cab_t, "length", "cable")
    if isinstance(length_v, str) and length_v.strip().lower() == FREE:
        length = None
    else:
        length = cable_number(length_v, "cable.length", "length")
    law = parse_law(cab_t)
    ea_table, rows, visco = parse_material(cab_t)

    def opt(key: str) -> float:
        if need_drag or key in cab_t:
            return cable_number(require(cab_t, key, "cable"), f"cable.{key}", key)
        return 0.0

    return Cable(
        length=length,
        diameter=opt("diameter"),
        weight_in_water=cable_number(require(cab_t, "weight_in_water", "cable"),
                                     "cable.weight_in_water", "weight_in_water"),
        axial_stiffness=ea_table if ea_table is not None else cable_number(
            cab_t.get("axial_stiffness", math.inf), "cable.axial_stiffness", "axial_stiffness"),
        normal_drag=opt("normal_drag"),
        tangential_drag=opt("tangential_drag"),
        drag_law=law,
        tension_strain=rows,
        viscoelastic=visco,
    )


def parse_segments(cab_t: dict[str, Any], need_drag: bool
                    ) -> tuple[Cable, tuple[Cable, ...], tuple[int | None, ...]]:
    """``[[cable.segments]]`` -> (summary cable, segments, per-segment intervals).

    Parameters
    ----------
    cab_t : dict
        The ``[cable]`` table, holding only ``segments`` (a non-empty array of tables,
        from end_a to end_b, each with its ``length`` (m), ``weight_in_water`` (N/m) and
        optional ``axial_stiffness`` (N), ``bending_stiffness`` (N m^2), drag keys and
        ``intervals``) and optionally ``drag_law``.
    need_drag : bool
        True when the scene has a current: every segment then needs ``diameter``,
        ``normal_drag`` and ``tangential_drag``; otherwise each defaults to 0.
    """
    law = parse_law(cab_t)
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
        t = check_keys(t, SEGMENT_KEYS, where)
        lv = require(t, "length", where)
        if isinstance(lv, str) and lv.strip().lower() == FREE:
            raise CableOCPError(
                f'{where}.length = "free": a free length (prescribed end tension) is not '
                "supported for multi-segment lines; give every segment its length")
        length = cable_number(lv, f"{where}.length", "length")

        def opt(key: str, t: dict[str, Any] = t, where: str = where) -> float:
            if need_drag or key in t:
                return cable_number(require(t, key, where), f"{where}.{key}", key)
            return 0.0

        segs.append(Cable(
            length=length,
            diameter=opt("diameter"),
            weight_in_water=cable_number(require(t, "weight_in_water", where),
                                         f"{where}.weight_in_water", "weight_in_water"),
            axial_stiffness=cable_number(t.get("axial_stiffness", math.inf),
                                         f"{where}.axial_stiffness", "axial_stiffness"),
            normal_drag=opt("normal_drag"),
            tangential_drag=opt("tangential_drag"),
            drag_law=law,
            bending_stiffness=cable_number(t.get("bending_stiffness", 0.0),
                                           f"{where}.bending_stiffness", "bending_stiffness"),
        ))
        iv = t.get("intervals")
        if iv is not None and (isinstance(iv, bool) or not isinstance(iv, int)
                               or not 1 <= iv <= 20000):
            raise CableOCPError(f"{where}.intervals = {iv!r}: expected an integer 1..20000")
        ivals.append(iv)
    first = segs[0]
    summary = replace(first, length=sum(c.length for c in segs))  # type: ignore[misc]
    return summary, tuple(segs), tuple(ivals)


def check_planar_bending(segments: tuple[Cable, ...], env: Environment, end_a: End,
                          end_b: End, bodies: tuple[Body, ...]) -> None:
    """Bending stiffness is modelled in the vertical x-z plane only (a planar beam-cable):
    reject any scene that could leave that plane, naming the key.

    Parameters
    ----------
    segments : tuple of Cable
        The cable's segments, from end_a; empty (a single cable) or no segment with
        ``bending_stiffness > 0`` passes without checks.
    env : Environment
        The environment: its current must lie in the x-z plane at every knot, and a seabed
        needs a flexible first segment.
    end_a, end_b : End
        The lower end (s = 0) and the ship's end (s = L): any prescribed y position (m) or
        y force (N) must be 0.
    bodies : tuple of Body
        The point bodies at the joints: any thrust's y component (N) must be 0.
    """
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


def parse_bodies(value: Any, n_segments: int) -> tuple[Body, ...]:
    """``[[bodies]]`` -> point bodies at the joints between segments.

    Parameters
    ----------
    value : Any
        The ``bodies`` array of tables as read from TOML; each has ``joint`` (an integer
        1 .. n_segments - 1: the number of segments between end_a and the body) and
        ``kind`` (``"clump"``, ``"buoy"`` or ``"unit"``) with that kind's keys (N, m^2, (-)).
    n_segments : int
        Number of ``[[cable.segments]]`` (0 for a single cable); bodies need at least 2.
    """
    if not isinstance(value, list):
        raise CableOCPError("bodies: expected an array of tables ([[bodies]])")
    if value and n_segments < 2:
        raise CableOCPError(
            "bodies[0].joint: point bodies sit at joints between segments; give at least two "
            "[[cable.segments]] (a body at an end is an end force: add it to end_a/end_b.force)")
    out = []
    for i, t in enumerate(value):
        where = f"bodies[{i}]"
        t = check_keys(t, BODY_KEYS, where)
        joint = require(t, "joint", where)
        if isinstance(joint, bool) or not isinstance(joint, int) or not 1 <= joint < n_segments:
            raise CableOCPError(
                f"{where}.joint = {joint!r}: expected an integer 1..{n_segments - 1} (the number "
                "of segments between end_a and the body); a body at an end is an end force")
        kind = require(t, "kind", where)
        allowed = {"clump": {"joint", "kind", "weight_in_water"},
                   "buoy": {"joint", "kind", "net_buoyancy"},
                   "unit": {"joint", "kind", "weight_in_water", "drag_area",
                            "drag_coefficient", "thrust"}}
        if not isinstance(kind, str) or kind not in allowed:
            raise CableOCPError(f'{where}.kind = {kind!r}: valid are "clump", "buoy", "unit"')
        extra = sorted(set(t) - allowed[kind])
        if extra:
            raise CableOCPError(f"{where}.{extra[0]}: not a key of a {kind} body; valid: "
                                f"{', '.join(sorted(allowed[kind]))}")
        if kind == "clump":
            body = Body(joint, kind, weight_in_water=number(
                require(t, "weight_in_water", where), f"{where}.weight_in_water",
                positive=True, high=BODY_MAX, unit="N", why=BODY_WHY))
        elif kind == "buoy":
            body = Body(joint, kind, net_buoyancy=number(
                require(t, "net_buoyancy", where), f"{where}.net_buoyancy", positive=True,
                high=BODY_MAX, unit="N", why=BODY_WHY))
        else:
            area = number(t.get("drag_area", 0.0), f"{where}.drag_area", nonneg=True,
                          high=1e4, unit="m^2", why="larger than any subsea unit (~1e3 m^2)")
            cd = number(t.get("drag_coefficient", 0.0), f"{where}.drag_coefficient",
                        nonneg=True, high=CD_MAX, unit="-", why=CD_WHY)
            if (area > 0) != (cd > 0):
                raise CableOCPError(f"{where}: give both drag_area (m^2) and drag_coefficient "
                                    "(-), or neither")
            thrust = (0.0, 0.0, 0.0)
            if "thrust" in t:
                v = t["thrust"]
                if not isinstance(v, list) or len(v) != 3:
                    raise CableOCPError(f"{where}.thrust = {v!r}: expected [Tx, Ty, Tz] (N)")
                thrust = tuple(number(c, f"{where}.thrust[{k}]",  # type: ignore[assignment]
                                      low=-BODY_MAX, high=BODY_MAX, unit="N", why=BODY_WHY)
                               for k, c in enumerate(v))
            body = Body(joint, kind, weight_in_water=number(
                require(t, "weight_in_water", where), f"{where}.weight_in_water",
                low=-BODY_MAX, high=BODY_MAX, unit="N", why=BODY_WHY),
                drag_area=area, drag_coefficient=cd, thrust=thrust)
        out.append(body)
    return tuple(out)

