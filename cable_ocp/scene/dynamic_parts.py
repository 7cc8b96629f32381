"""The parts of a dynamic scene (:mod:`cable_ocp.scene.dynamics`): a segment's dynamics,
the subsea unit, a body's mass, the towing path, the top motion and pay-out law, the
simulation and modes options; each with its parser (the keys and units are in the schema
of :mod:`cable_ocp.scene.dynamics`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.physics.added_mass import added_mass_per_length, virtual_mass, weight_in_water
from cable_ocp.physics.drag import point_drag_np
from cable_ocp.scene.fields import check_keys as _check_keys
from cable_ocp.scene.fields import number as _number
from cable_ocp.scene.fields import require as _require

__all__ = ["BODY_DYN_KEYS", "CABLE_DYN_KEYS", "DEFAULT_SCHEME", "DYNAMIC_TABLES", "MAX_STEPS",
           "MODELS", "PAYOUT_LAWS", "ROUNDING", "SCHEMES", "BodyDynamics", "ModesOptions",
           "SegmentDynamics",
           "Simulation", "TopMotion", "Tow", "Unit", "parse_modes", "parse_segment_dynamics",
           "parse_simulation", "parse_top_motion", "parse_tow", "parse_unit",
           "vec_or_scalar"]

MODELS = ("axial", "planar", "lumped3d")
#: Time-integration schemes offered by each model (the first is the default).
SCHEMES: dict[str, tuple[str, ...]] = {
    "axial": ("midpoint", "gauss4", "trapezoidal", "bdf2", "thesis"),
    "planar": ("midpoint",),
    "lumped3d": ("midpoint", "trapezoidal", "bdf2", "thesis"),
}
DEFAULT_SCHEME = {m: s[0] for m, s in SCHEMES.items()}

#: Top-level tables that only dynamic scenes have (their presence marks a dynamic scene).
DYNAMIC_TABLES = ("unit", "top_motion", "simulation", "modes", "response", "deployment")
CABLE_DYN_KEYS = {"mass_per_length", "added_mass_coefficient",
                   "tangential_added_mass_coefficient", "axial_damping"}
_UNIT_KEYS = {"mass", "added_mass", "weight_in_water", "volume", "drag_area",
              "drag_coefficient"}
BODY_DYN_KEYS = {"mass", "added_mass"}
_TOP_KEYS = {"heave_amplitude", "heave_frequency", "horizontal_amplitude",
             "horizontal_frequency", "horizontal_heading_deg", "circular_radius",
             "circular_frequency", "circular_heading_deg", "series", "ramp_time",
             "payout_law", "payout_speed", "payout_acceleration", "payout_amplitude",
             "payout_frequency", "payout_speed_table", "payout_length_table", "tow"}
_LAW_KEYS = {"linear": {"payout_speed"},
             "quadratic": {"payout_speed", "payout_acceleration"},
             "periodic": {"payout_amplitude", "payout_frequency"},
             "table": {"payout_speed_table", "payout_length_table"}}
#: the pay-out laws of ``top_motion.payout_law``
PAYOUT_LAWS = ("linear", "quadratic", "periodic", "table")
_TOW_KEYS = {"speed", "heading_deg", "straight_length", "turn_diameter", "turn_angle_deg",
             "turn_direction"}
_SIM_KEYS = {"model", "duration", "time_step", "output_step", "segments", "start", "scheme",
             "tolerance", "max_iterations", "on_slack", "drop_height", "element_length",
             "top_end"}
#: ``simulation.top_end``: the bending condition at end_b (with bending stiffness)
TOP_ENDS = ("pinned", "clamped")
_MODES_KEYS = {"count", "wave_band"}
#: Relative slack allowed for rounded inputs when a weight in water is checked against
#: the weight in air (the buoyancy must not be negative).
ROUNDING = 1e-3
#: The largest number of time steps a scene may ask for (memory of the outputs).
MAX_STEPS = 20_000_000

Vec3 = tuple[float, float, float]


# --------------------------------------------------------------------------------------
# Dataclasses
# --------------------------------------------------------------------------------------

@dataclass(frozen=True)
class SegmentDynamics:
    """Dynamic properties of one cable segment (``[cable]`` or ``[[cable.segments]]``).

    Attributes
    ----------
    mass_per_length : float
        Mass in air per unstretched length, kg/m.
    added_mass_coefficient : float
        Normal added-mass coefficient C_a (-): added mass C_a rho pi d^2/4 per length
        for acceleration normal to the cable.
    tangential_added_mass_coefficient : float
        Tangential added-mass coefficient (-), same form, for acceleration along the cable.
    axial_damping : float
        Internal damping coefficient c, N s: the tension is EA e + c de/dt (e the strain).
    """

    mass_per_length: float
    added_mass_coefficient: float = 1.0
    tangential_added_mass_coefficient: float = 0.0
    axial_damping: float = 0.0

    def added_mass_per_length(self, diameter: float, rho: float) -> float:
        """Normal added mass per unstretched length, kg/m
        (:func:`cable_ocp.physics.added_mass.added_mass_per_length`).

        Parameters
        ----------
        diameter : float
            Hydrodynamic diameter, m.
        rho : float
            Water density, kg/m^3.
        """
        return added_mass_per_length(self.added_mass_coefficient, rho, diameter)

    def tangential_added_mass_per_length(self, diameter: float, rho: float) -> float:
        """Tangential added mass per unstretched length, kg/m.

        Parameters
        ----------
        diameter : float
            Hydrodynamic diameter, m.
        rho : float
            Water density, kg/m^3.
        """
        return added_mass_per_length(self.tangential_added_mass_coefficient, rho, diameter)


@dataclass(frozen=True)
class Unit:
    """The subsea unit hanging at end_a (``[unit]``).

    Attributes
    ----------
    mass : float
        Mass in air, kg.
    added_mass : tuple of float
        Added masses along x, y, z, kg (Huang (1992) 5.2.2: M_ax, M_ay, M_az).
    weight_in_water : float
        Weight minus buoyancy, N (negative = buoyant).
    volume : float or None
        Displaced volume, m^3, when given.
    drag_area : tuple of float
        Projected areas S_x, S_y, S_z, m^2.
    drag_coefficient : tuple of float
        Drag coefficients C_Dx, C_Dy, C_Dz (-).
    drag_per_axis : bool
        True: each velocity component has its own quadratic drag (Huang (1992) 5.2.2);
        False (scalar keys): the vector law -1/2 rho C_D S |u| u.
    """

    mass: float
    added_mass: Vec3 = (0.0, 0.0, 0.0)
    weight_in_water: float = 0.0
    volume: float | None = None
    drag_area: Vec3 = (0.0, 0.0, 0.0)
    drag_coefficient: Vec3 = (0.0, 0.0, 0.0)
    drag_per_axis: bool = False

    def drag(self, relative_velocity: Any, rho: float) -> list[float]:
        """Drag force on the unit, N, for its velocity relative to the water (m/s).

        ``relative_velocity`` is the unit's velocity minus the current's (3 numbers). The
        exact law (no smoothing) of :func:`cable_ocp.physics.drag.point_drag_np`, whose flow
        is the current relative to the unit.

        Parameters
        ----------
        relative_velocity : sequence of 3 float
            The unit's velocity minus the current's, m/s.
        rho : float
            Water density, kg/m^3.
        """
        flow = -np.asarray([float(c) for c in relative_velocity])
        cs = [self.drag_area[k] * self.drag_coefficient[k] for k in range(3)]
        return [float(f) for f in point_drag_np(flow, cs, rho=rho,
                                                per_axis=self.drag_per_axis)]

    def static_load(self, current: Vec3, rho: float) -> Vec3:
        """External load on end_a at rest in a current: weight in water plus drag, N.

        Parameters
        ----------
        current : sequence of 3 float
            Current velocity at the unit, m/s.
        rho : float
            Water density, kg/m^3.
        """
        d = self.drag([-c for c in current], rho)
        return (d[0], d[1], d[2] - self.weight_in_water)

    @property
    def virtual_mass(self) -> Vec3:
        """Mass plus added mass per axis, kg."""
        return virtual_mass(self.mass, self.added_mass)  # type: ignore[return-value]


@dataclass(frozen=True)
class BodyDynamics:
    """Mass data of one ``[[bodies]]`` entry (same order as ``statics.bodies``).

    Attributes
    ----------
    mass : float
        Mass in air, kg.
    added_mass : tuple of float
        Added masses along x, y, z, kg.
    """

    mass: float
    added_mass: Vec3 = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class Tow:
    """A towing path for end_b (``[top_motion.tow]``): straight, a turn, straight again
    (Huang (1992) section 5.7.4).

    Attributes
    ----------
    speed : float
        Speed along the path, m/s.
    heading_deg : float
        Initial direction, deg from +x towards +y.
    straight_length : float
        Distance before the turn, m (``math.inf``: never turns).
    turn_diameter : float
        Diameter of the turning circle, m.
    turn_angle_deg : float
        Angle turned, deg; then straight on along the new heading.
    turn_direction : str
        ``"left"`` (counter-clockwise seen from above) or ``"right"``.
    """

    speed: float
    heading_deg: float = 0.0
    straight_length: float = math.inf
    turn_diameter: float = 0.0
    turn_angle_deg: float = 360.0
    turn_direction: str = "left"


@dataclass(frozen=True)
class TopMotion:
    """Prescribed motion of end_b and the pay-out law (``[top_motion]``).

    Offsets are from ``end_b.position`` (m); see the module docstring for the formulas and
    :mod:`cable_ocp.scene.motion` for their CasADi expressions.

    Attributes
    ----------
    heave_amplitude, heave_frequency : float
        m, rad/s: z offset A sin(w t).
    horizontal_amplitude, horizontal_frequency, horizontal_heading_deg : float
        m, rad/s, deg: horizontal offset A sin(w t) along the heading.
    circular_radius, circular_frequency, circular_heading_deg : float
        m, rad/s, deg: a vertical circle, z += r sin(w t), horizontal r (1 - cos(w t)).
    series : tuple of (t, dx, dy, dz)
        s, m: tabulated offsets (linear interpolation, held after the last row).
    ramp_time : float
        s, smooth start of amplitudes and speeds (0 = none).
    payout_law : str
        ``"linear"``, ``"quadratic"``, ``"periodic"`` (Huang (1992) 3.1) or ``"table"``.
    payout_speed : float
        v, m/s of unstretched cable (> 0 lowers the unit).
    payout_acceleration : float
        a, m/s^2 (quadratic law).
    payout_amplitude, payout_frequency : float
        p (m), w (rad/s) of the periodic law.
    payout_table : tuple of (t, value)
        The table law's rows: (s, m/s) of ``payout_speed_table`` or (s, m) of
        ``payout_length_table`` (:func:`cable_ocp.scene.motion.length_expr`).
    payout_table_kind : str
        ``"speed"`` or ``"length"`` (the table law), else ``""``.
    tow : Tow or None
        Towing path.
    """

    heave_amplitude: float = 0.0
    heave_frequency: float = 0.0
    horizontal_amplitude: float = 0.0
    horizontal_frequency: float = 0.0
    horizontal_heading_deg: float = 0.0
    circular_radius: float = 0.0
    circular_frequency: float = 0.0
    circular_heading_deg: float = 0.0
    series: tuple[tuple[float, float, float, float], ...] = ()
    ramp_time: float = 0.0
    payout_law: str = "linear"
    payout_speed: float = 0.0
    payout_acceleration: float = 0.0
    payout_amplitude: float = 0.0
    payout_frequency: float = 0.0
    payout_table: tuple[tuple[float, float], ...] = ()
    payout_table_kind: str = ""
    tow: Tow | None = None

    @property
    def varying_length(self) -> bool:
        """True when the unstretched length changes with time."""
        if self.payout_law == "table":
            vals = [r[1] for r in self.payout_table]
            return (any(v != 0.0 for v in vals) if self.payout_table_kind == "speed"
                    else any(v != vals[0] for v in vals))
        return (self.payout_speed != 0.0 or self.payout_acceleration != 0.0
                or self.payout_amplitude != 0.0)

    @property
    def payout_key(self) -> str:
        """The ``[top_motion]`` key that sets the pay-out (for messages)."""
        if self.payout_law == "table":
            return f"payout_{self.payout_table_kind}_table"
        return "payout_amplitude" if self.payout_law == "periodic" else "payout_speed"

    @property
    def horizontal(self) -> bool:
        """True when end_b moves horizontally (horizontal, circular, tow or series)."""
        return (self.horizontal_amplitude != 0.0 or self.circular_radius != 0.0
                or self.tow is not None
                or any(r[1] != 0.0 or r[2] != 0.0 for r in self.series))

    @property
    def moves(self) -> bool:
        """True when end_b moves at all."""
        return (self.horizontal or self.heave_amplitude != 0.0
                or any(r[3] != 0.0 for r in self.series))


@dataclass(frozen=True)
class Simulation:
    """Time-domain settings (``[simulation]``).

    Attributes
    ----------
    model : str
        ``"axial"``, ``"planar"`` or ``"lumped3d"``.
    duration : float
        Simulated time, s.
    time_step : float
        Integration step, s.
    output_step : float
        Interval between stored samples, s (a multiple of ``time_step``).
    segments : int
        Elements along the line.
    start : str
        ``"static"``, ``"unstrained"`` or ``"dropped"``.
    scheme : str
        Time-integration scheme (:data:`SCHEMES`).
    tolerance : float
        Newton tolerance of an implicit step (scaled residual, -).
    max_iterations : int
        Newton iterations per step.
    on_slack : str
        ``"continue"`` or ``"stop"``.
    drop_height : float
        m, ``start = "dropped"``: the line straight down from end_b and slack, the unit
        this far above where it goes taut (every node raised by h (1 - s / L)), at rest.
    element_length : float or None
        Length l_e (m) of the segments that enter and leave at the winch in a lumped3d
        pay-out (:mod:`cable_ocp.dynamics.lumped_payout`); None: the top segment's initial
        length.
    top_end : str
        ``"pinned"`` (default: no bending moment at end_b) or ``"clamped"`` (the top
        tangent held at its static direction; a line with bending stiffness,
        :mod:`cable_ocp.dynamics.bending_terms`).
    """

    model: str
    duration: float
    time_step: float
    output_step: float
    segments: int = 20
    start: str = "static"
    scheme: str = "midpoint"
    tolerance: float = 1e-10
    max_iterations: int = 20
    on_slack: str = "continue"
    drop_height: float = 0.0
    element_length: float | None = None
    top_end: str = "pinned"

    @property
    def steps(self) -> int:
        """Number of integration steps."""
        return int(round(self.duration / self.time_step))

    @property
    def output_every(self) -> int:
        """Integration steps per stored sample."""
        return int(round(self.output_step / self.time_step))


@dataclass(frozen=True)
class ModesOptions:
    """Modal-analysis settings (``[modes]``).

    Attributes
    ----------
    count : int
        Number of modes.
    wave_band : tuple of float
        Wave-frequency band (low, high), rad/s, shaded on the deployment chart.
    """

    count: int = 6
    wave_band: tuple[float, float] = (2.0 * math.pi / 20.0, 2.0 * math.pi / 4.0)


def _int(value: Any, key: str, lo: int, hi: int | None = None) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < lo or (
            hi is not None and value > hi):
        rng = f"{lo}..{hi}" if hi is not None else f">= {lo}"
        raise CableOCPError(f"{key} = {value!r}: expected an integer {rng}")
    return value


def _choice(value: Any, key: str, valid: tuple[str, ...]) -> str:
    if value not in valid:
        raise CableOCPError(f"{key} = {value!r}: valid are "
                            + ", ".join(f'"{v}"' for v in valid))
    return value


def vec_or_scalar(value: Any, key: str) -> tuple[Vec3, bool]:
    """A nonnegative number or [x, y, z] -> (triple, given per axis).

    Parameters
    ----------
    value : float or list of 3 float
        The key's value from the scene file, in the key's unit: one nonnegative number
        for all three axes, or one per axis.
    key : str
        The dotted key (e.g. ``"unit.drag_area"``), for error messages.

    Returns
    -------
    triple : tuple of 3 float
        The value per axis x, y, z.
    per_axis : bool
        True when ``value`` was a list.
    """
    if isinstance(value, list):
        if len(value) != 3:
            raise CableOCPError(f"{key} = {value!r}: expected a number or [x, y, z]")
        return tuple(_number(v, f"{key}[{i}]", nonneg=True)  # type: ignore[return-value]
                     for i, v in enumerate(value)), True
    x = _number(value, key, nonneg=True)
    return (x, x, x), False


def parse_segment_dynamics(t: dict[str, Any], where: str, diameter: float,
                            need_diameter: bool) -> SegmentDynamics:
    """A segment's dynamic properties from its table (keys :data:`CABLE_DYN_KEYS`).

    Parameters
    ----------
    t : dict
        The segment's dynamic keys (``[cable]`` or one ``[[cable.segments]]`` entry):
        ``mass_per_length`` (kg/m, required), ``added_mass_coefficient`` (-, default 1.0),
        ``tangential_added_mass_coefficient`` (-, default 0.0), ``axial_damping`` (N s,
        default 0.0).
    where : str
        The table's name (e.g. ``"cable"``, ``"cable.segments[1]"``), for error messages.
    diameter : float
        The segment's hydrodynamic diameter, m (from the statics part of the scene).
    need_diameter : bool
        True: a nonzero added-mass coefficient with ``diameter`` <= 0 is an error (the
        added mass is C_a rho pi d^2 / 4 per metre); False: accepted.
    """
    mass = _number(_require(t, "mass_per_length", where), f"{where}.mass_per_length",
                   positive=True)
    ca_n = _number(t.get("added_mass_coefficient", 1.0), f"{where}.added_mass_coefficient",
                   nonneg=True)
    ca_t = _number(t.get("tangential_added_mass_coefficient", 0.0),
                   f"{where}.tangential_added_mass_coefficient", nonneg=True)
    damping = _number(t.get("axial_damping", 0.0), f"{where}.axial_damping", nonneg=True)
    if (ca_n > 0.0 or ca_t > 0.0) and diameter <= 0.0 and need_diameter:
        key = "added_mass_coefficient" if ca_n > 0.0 else "tangential_added_mass_coefficient"
        default = " (default 1.0)" if ca_n > 0.0 and "added_mass_coefficient" not in t else ""
        raise CableOCPError(
            f"{where}.diameter is missing: the added mass ({where}.{key} = {ca_n if ca_n else ca_t}"
            f"{default}) is C_a rho pi d^2 / 4 per metre; give {where}.diameter (m) or set "
            f"{where}.{key} = 0 (e.g. in air)")
    return SegmentDynamics(mass_per_length=mass, added_mass_coefficient=ca_n,
                           tangential_added_mass_coefficient=ca_t, axial_damping=damping)


def parse_unit(t: Any, rho: float, g: float) -> Unit:
    """The subsea unit at end_a from the ``[unit]`` table.

    ``weight_in_water`` (N) or ``volume`` (m^3) must be given; with both, the weight in
    water must match (m - rho V) g to 1e-3 of the larger of its magnitude and m g, and it
    may not exceed the weight in air m g (by more than :data:`ROUNDING`).

    Parameters
    ----------
    t : dict
        The ``[unit]`` table: ``mass`` (kg, required), ``added_mass`` (kg, a number or
        [x, y, z]), ``weight_in_water`` (N), ``volume`` (m^3), ``drag_area`` (m^2) and
        ``drag_coefficient`` (-) (each a number or [x, y, z], both or neither per axis).
    rho : float
        Water density, kg/m^3 (for the weight in water from the volume).
    g : float
        Gravitational acceleration, m/s^2.
    """
    t = _check_keys(t, _UNIT_KEYS, "unit")
    mass = _number(_require(t, "mass", "unit"), "unit.mass", nonneg=True)
    added, _ = vec_or_scalar(t.get("added_mass", 0.0), "unit.added_mass")
    volume = None
    if "volume" in t:
        volume = _number(t["volume"], "unit.volume", nonneg=True)
    if "weight_in_water" in t:
        w = _number(t["weight_in_water"], "unit.weight_in_water")
        if volume is not None:
            w_v = weight_in_water(mass, volume, rho, g)
            if abs(w - w_v) > 1e-3 * max(abs(w), mass * g, 1e-12):
                raise CableOCPError(
                    f"unit.weight_in_water = {w} N disagrees with unit.volume = {volume} m^3: "
                    f"(mass - rho volume) g = {w_v:.6g} N; give one of them")
    elif volume is not None:
        w = weight_in_water(mass, volume, rho, g)
    else:
        raise CableOCPError("unit.weight_in_water is missing (N; or give unit.volume, m^3)")
    if w > mass * g * (1.0 + ROUNDING) + 1e-12:
        raise CableOCPError(
            f"unit.weight_in_water = {w} N exceeds the weight in air mass g = {mass * g:.6g} N "
            "(buoyancy cannot be negative): check unit.mass and unit.weight_in_water")
    area, area_axes = vec_or_scalar(t.get("drag_area", 0.0), "unit.drag_area")
    cd, cd_axes = vec_or_scalar(t.get("drag_coefficient", 0.0), "unit.drag_coefficient")
    for k in range(3):
        if (area[k] > 0.0) != (cd[k] > 0.0):
            raise CableOCPError("unit: give both drag_area (m^2) and drag_coefficient (-) "
                                "for every axis that has drag, or neither")
    return Unit(mass=mass, added_mass=added, weight_in_water=w, volume=volume,
                drag_area=area, drag_coefficient=cd, drag_per_axis=area_axes or cd_axes)


def parse_tow(t: Any) -> Tow:
    where = "top_motion.tow"
    t = _check_keys(t, _TOW_KEYS, where)
    speed = _number(_require(t, "speed", where), f"{where}.speed", positive=True)
    straight = _number(t.get("straight_length", math.inf), f"{where}.straight_length",
                       nonneg=True, allow_inf=True)
    diameter = _number(t.get("turn_diameter", 0.0), f"{where}.turn_diameter", nonneg=True)
    angle = _number(t.get("turn_angle_deg", 360.0), f"{where}.turn_angle_deg", nonneg=True)
    direction = _choice(t.get("turn_direction", "left"), f"{where}.turn_direction",
                        ("left", "right"))
    if math.isfinite(straight) and diameter <= 0.0 and angle > 0.0:
        raise CableOCPError(f"{where}.turn_diameter is missing: a turn after straight_length "
                            f"= {straight} m needs turn_diameter > 0 (m)")
    return Tow(speed=speed, heading_deg=_number(t.get("heading_deg", 0.0),
                                                f"{where}.heading_deg"),
               straight_length=straight, turn_diameter=diameter, turn_angle_deg=angle,
               turn_direction=direction)


def parse_top_motion(t: Any) -> TopMotion:
    where = "top_motion"
    t = _check_keys(t, _TOP_KEYS, where)
    kw: dict[str, Any] = {}
    for amp, freq in (("heave_amplitude", "heave_frequency"),
                      ("horizontal_amplitude", "horizontal_frequency"),
                      ("circular_radius", "circular_frequency")):
        a = _number(t.get(amp, 0.0), f"{where}.{amp}",
                    nonneg=amp == "circular_radius")
        kw[amp] = a
        if freq in t:
            kw[freq] = _number(t[freq], f"{where}.{freq}", positive=True)
        elif a != 0.0:
            raise CableOCPError(f"{where}.{freq} is missing: {where}.{amp} = {a} needs a "
                                "frequency (rad/s)")
    for key in ("horizontal_heading_deg", "circular_heading_deg"):
        kw[key] = _number(t.get(key, 0.0), f"{where}.{key}")
    kw["ramp_time"] = _number(t.get("ramp_time", 0.0), f"{where}.ramp_time", nonneg=True)
    if "series" in t:
        rows = t["series"]
        if not isinstance(rows, list) or len(rows) < 2:
            raise CableOCPError(f"{where}.series: expected at least two rows [t, dx, dy, dz] "
                                "(s, m)")
        out = []
        for i, r in enumerate(rows):
            if not isinstance(r, list) or len(r) != 4:
                raise CableOCPError(f"{where}.series[{i}] = {r!r}: expected [t, dx, dy, dz] "
                                    "(s, m)")
            out.append(tuple(_number(v, f"{where}.series[{i}][{k}]") for k, v in enumerate(r)))
        if out[0][0] != 0.0:
            raise CableOCPError(f"{where}.series[0][0] = {out[0][0]}: the series starts at "
                                "t = 0 s")
        if any(b[0] <= a[0] for a, b in zip(out, out[1:], strict=False)):
            raise CableOCPError(f"{where}.series: times must increase strictly")
        if any(v != 0.0 for v in out[0][1:]):
            raise CableOCPError(f"{where}.series[0]: the offsets at t = 0 must be 0 (end_b "
                                "starts at end_b.position)")
        kw["series"] = tuple(out)
    law = _choice(t.get("payout_law", "linear"), f"{where}.payout_law", PAYOUT_LAWS)
    kw["payout_law"] = law
    all_law_keys = set().union(*_LAW_KEYS.values())
    for key in sorted(all_law_keys & set(t)):
        if key not in _LAW_KEYS[law]:
            raise CableOCPError(
                f"{where}.{key} does not belong to payout_law = \"{law}\"; its keys are "
                f"{', '.join(sorted(_LAW_KEYS[law]))}")
    kw["payout_speed"] = _number(t.get("payout_speed", 0.0), f"{where}.payout_speed")
    kw["payout_acceleration"] = _number(t.get("payout_acceleration", 0.0),
                                        f"{where}.payout_acceleration")
    kw["payout_amplitude"] = _number(t.get("payout_amplitude", 0.0),
                                     f"{where}.payout_amplitude")
    if law == "periodic":
        if "payout_frequency" not in t:
            raise CableOCPError(f"{where}.payout_frequency is missing (rad/s; payout_law = "
                                "\"periodic\": L = L0 + p sin(w t))")
        kw["payout_frequency"] = _number(t["payout_frequency"], f"{where}.payout_frequency",
                                         positive=True)
    if law == "table":
        kw["payout_table_kind"], kw["payout_table"] = _payout_table(t, where)
    if "tow" in t:
        kw["tow"] = parse_tow(t["tow"])
    return TopMotion(**kw)


def _payout_table(t: dict[str, Any], where: str
                  ) -> tuple[str, tuple[tuple[float, float], ...]]:
    """(kind, rows) of ``payout_law = "table"``: exactly one of ``payout_speed_table``
    ([[t, v], ...], s and m/s; times from 0, non-decreasing, a time given twice is a jump
    in speed such as a sudden stop) and ``payout_length_table`` ([[t, L], ...], s and m;
    times from 0, increasing)."""
    given = [k for k in ("payout_speed_table", "payout_length_table") if k in t]
    if len(given) != 1:
        raise CableOCPError(
            f'{where}.payout_law = "table" needs exactly one of {where}.payout_speed_table '
            f"([[t, v], ...], s and m/s) and {where}.payout_length_table ([[t, L], ...], s "
            f"and m); got {', '.join(given) if given else 'neither'}")
    key = given[0]
    kind = "speed" if key == "payout_speed_table" else "length"
    unit = "m/s" if kind == "speed" else "m"
    rows = t[key]
    if not isinstance(rows, list) or len(rows) < 2:
        raise CableOCPError(f"{where}.{key}: expected at least two rows [t, "
                            f"{'v' if kind == 'speed' else 'L'}] (s, {unit})")
    out = []
    for i, r in enumerate(rows):
        if not isinstance(r, list) or len(r) != 2:
            raise CableOCPError(f"{where}.{key}[{i}] = {r!r}: expected [t, "
                                f"{'v' if kind == 'speed' else 'L'}] (s, {unit})")
        out.append((_number(r[0], f"{where}.{key}[{i}][0]", nonneg=True),
                    _number(r[1], f"{where}.{key}[{i}][1]", positive=kind == "length")))
    if out[0][0] != 0.0:
        raise CableOCPError(f"{where}.{key}[0][0] = {out[0][0]}: the table starts at t = 0 s")
    for i, (a, b) in enumerate(zip(out, out[1:], strict=False)):
        if b[0] < a[0] or (b[0] == a[0] and kind == "length"):
            raise CableOCPError(
                f"{where}.{key}[{i + 1}][0] = {b[0]} s: times must "
                + ("not decrease (a time given twice is a jump in speed)" if kind == "speed"
                   else "increase strictly (a length cannot jump)"))
        if kind == "speed" and i + 2 < len(out) and out[i + 2][0] == a[0] == b[0]:
            raise CableOCPError(f"{where}.{key}[{i + 2}][0] = {a[0]} s: a time may be given "
                                "at most twice (the speeds before and after a jump)")
    return kind, tuple(out)


def parse_simulation(t: Any) -> Simulation:
    where = "simulation"
    t = _check_keys(t, _SIM_KEYS, where)
    model = _choice(_require(t, "model", where), f"{where}.model", MODELS)
    duration = _number(_require(t, "duration", where), f"{where}.duration", positive=True)
    dt = _number(_require(t, "time_step", where), f"{where}.time_step", positive=True)
    if dt > duration:
        raise CableOCPError(f"{where}.time_step = {dt} s exceeds {where}.duration = "
                            f"{duration} s")
    steps = duration / dt
    if abs(steps - round(steps)) > 1e-6 * steps:
        raise CableOCPError(f"{where}.duration = {duration} s is not a whole number of "
                            f"time steps ({where}.time_step = {dt} s, {steps:.6g} steps)")
    if steps > MAX_STEPS:
        raise CableOCPError(f"{where}.time_step = {dt} s: {steps:.3g} steps over {duration} s "
                            f"exceed the limit {MAX_STEPS:.0e}; take a larger time step")
    out = _number(t.get("output_step", dt), f"{where}.output_step", positive=True)
    ratio = out / dt
    if ratio < 1.0 - 1e-9 or abs(ratio - round(ratio)) > 1e-6 * ratio:
        raise CableOCPError(f"{where}.output_step = {out} s: must be a whole multiple of "
                            f"{where}.time_step = {dt} s")
    if round(steps) % round(ratio) != 0:
        raise CableOCPError(f"{where}.output_step = {out} s: duration = {duration} s must be "
                            "a whole number of output steps")
    scheme = _choice(t.get("scheme", DEFAULT_SCHEME[model]), f"{where}.scheme "
                     f"(model \"{model}\")", SCHEMES[model])
    start = _choice(t.get("start", "static"), f"{where}.start",
                    ("static", "unstrained", "dropped"))
    drop = 0.0
    if start == "dropped":
        if "drop_height" not in t:
            raise CableOCPError(f'{where}.drop_height is missing: start = "dropped" needs the '
                                "height (m) the unit falls before the line goes taut")
        drop = _number(t["drop_height"], f"{where}.drop_height", positive=True)
        if model == "axial":
            raise CableOCPError(f'{where}.start = "dropped": the axial model cannot follow a '
                                'slack line; use model = "planar" or "lumped3d"')
    elif "drop_height" in t:
        raise CableOCPError(f'{where}.drop_height belongs to start = "dropped" (start is '
                            f'"{start}")')
    return Simulation(
        model=model, duration=duration, time_step=dt, output_step=out,
        segments=_int(t.get("segments", 20), f"{where}.segments", 1, 100_000),
        start=start, drop_height=drop, scheme=scheme,
        tolerance=_number(t.get("tolerance", 1e-10), f"{where}.tolerance", positive=True),
        max_iterations=_int(t.get("max_iterations", 20), f"{where}.max_iterations", 1, 1000),
        on_slack=_choice(t.get("on_slack", "continue"), f"{where}.on_slack",
                         ("continue", "stop")),
        element_length=_element_length(t, model, where),
        top_end=_choice(t.get("top_end", "pinned"), f"{where}.top_end", TOP_ENDS),
    )


def _element_length(t: dict[str, Any], model: str, where: str) -> float | None:
    if "element_length" not in t:
        return None
    if model != "lumped3d":
        raise CableOCPError(f'{where}.element_length: only simulation.model = "lumped3d" '
                            f'takes it (model "{model}" has simulation.segments elements)')
    return _number(t["element_length"], f"{where}.element_length", positive=True)


def parse_modes(t: Any) -> ModesOptions:
    t = _check_keys(t, _MODES_KEYS, "modes")
    d = ModesOptions()
    band = d.wave_band
    if "wave_band" in t:
        v = t["wave_band"]
        if not isinstance(v, list) or len(v) != 2:
            raise CableOCPError(f"modes.wave_band = {v!r}: expected [low, high] (rad/s)")
        lo = _number(v[0], "modes.wave_band[0]", positive=True)
        hi = _number(v[1], "modes.wave_band[1]", positive=True)
        if hi <= lo:
            raise CableOCPError(f"modes.wave_band = {v!r}: expected low < high (rad/s)")
        band = (lo, hi)
    return ModesOptions(count=_int(t.get("count", d.count), "modes.count", 1, 10_000),
                        wave_band=band)
