"""Dynamic problem files (TOML, SI units) -> validated :class:`DynamicScene`.

A dynamic scene is a statics scene (:mod:`cable_ocp.scene`: ``[meta]``, ``[environment]``,
``[cable]`` / ``[[cable.segments]]``, ``[[bodies]]``, ``[end_b]``, ``[solver]``) plus the
dynamic keys below. The statics part is parsed by :func:`cable_ocp.scene.scene_from_dict`
(the dynamic keys are stripped first) and kept in :attr:`DynamicScene.statics`: it is the
problem whose solution is the initial state (Huang (1992), section 5.6.1).

Schema of the dynamic keys (all SI; units in brackets)::

    [cable]                      (or per segment in [[cable.segments]])
    mass_per_length = 7.2        kg/m, mass in air per unstretched length (required)
    added_mass_coefficient = 1.0 C_a (-), normal to the cable: added mass per length
                                 C_a rho pi d^2 / 4 (default 1.0, a circular cylinder in
                                 potential flow; 0 = none, e.g. in air)
    tangential_added_mass_coefficient = 0.0
                                 (-), along the cable (default 0: Huang (1992) section 5.2.1
                                 "if it is accelerated longitudinally no hydrodynamic
                                 reaction due to inertia occurs")
    axial_damping = 0.0          N s, internal (material) damping c: T = EA e + c de/dt
    tension_strain, viscoelastic the statics' [cable] keys of a nonlinear (table) or a
                                 viscoelastic rope (docs/dynamics.md "Cable materials";
                                 cable_ocp.dynamics.checks.check_material: which model
                                 carries which)
    [unit]                       the subsea unit at end_a (replaces [end_a])
    mass = 5000.0                kg (in air), >= 0
    added_mass = 8000.0          kg, >= 0; a number or [x, y, z] per axis (default 0)
    weight_in_water = 42600.0    N (negative = buoyant); or give volume instead
    volume = 0.354               m^3, optional: weight_in_water = (mass - rho volume) g
    drag_area = 0.5              m^2, projected area S (default 0); a number or [x, y, z]
    drag_coefficient = 1.5       C_D (-) (default 0); a number or [x, y, z]
                                 Numbers: D = -1/2 rho C_D S |u| u (u the velocity relative
                                 to the water). Per-axis lists: each component on its own,
                                 D_k = -1/2 rho C_Dk S_k |u_k| u_k (Huang (1992) section 5.2.2)
    [end_a]                      instead of [unit]: an anchored lower end, position only
    [[bodies]]                   as in statics, plus mass (kg, required) and
                                 added_mass (kg, number or [x, y, z], default 0)
    [end_b]
    position = [x, y, z]         m, the ship attachment's position at t = 0 (static position)
    [top_motion]                 prescribed motion of end_b, offsets from end_b.position
    heave_amplitude = 0.0        m;  z += A sin(w t)
    heave_frequency = 0.628      rad/s (required when heave_amplitude != 0)
    horizontal_amplitude = 0.0   m;  (x, y) += A sin(w t) (cos psi, sin psi)
    horizontal_frequency         rad/s
    horizontal_heading_deg = 0.0 psi, deg from +x towards +y
    circular_radius = 0.0        m;  z += r sin(w t), (x, y) += r (1 - cos(w t)) (cos psi,
                                 sin psi): a circle in a vertical plane, started at rest
                                 position (Huang (1992) section 4.5.5: P = sin t, Q = 1 - cos t)
    circular_frequency           rad/s
    circular_heading_deg = 0.0   deg
    series = [[t, dx, dy, dz], ...]   s, m: a measured vessel motion, linear in t between
                                 rows, held after the last row (rows from t = 0, increasing)
    ramp_time = 0.0              s; > 0 ramps the oscillation amplitudes and the pay-out /
                                 tow speeds smoothly (10x^3 - 15x^4 + 6x^5, x = t/ramp_time:
                                 no jump in velocity or acceleration) from 0 (Huang (1992)
                                 5.6.1: avoid impulsive loading); 0 = start at once
    payout_law = "linear"        "linear" | "quadratic" | "periodic" (Huang (1992) 3.1):
                                 L = L0 + v t  |  L0 + v t + a t^2/2  |  L0 + p sin(w t)
                                 | "table" (one of the two tables below)
    payout_speed = 0.0           v, m/s of unstretched cable; > 0 pays out (lowers the unit)
    payout_acceleration = 0.0    a, m/s^2 (quadratic)
    payout_amplitude = 0.0       p, m (periodic)
    payout_frequency             w, rad/s (periodic)
    payout_speed_table = [[t, v], ...]   s, m/s (table): v linear in t between rows, held
                                 after the last; L its exact integral; rows from t = 0, a
                                 time given twice is a jump in speed (a sudden stop)
    payout_length_table = [[t, L], ...]  s, m (table): L linear in t between rows, held
                                 after the last; the first L is cable.length
    [top_motion.tow]             a towing path (Huang (1992) 5.7.4): straight, turn, straight
    speed = 4.0                  m/s along the path
    heading_deg = 0.0            deg, initial direction from +x towards +y
    straight_length = 800.0      m before the turn
    turn_diameter = 300.0        m
    turn_angle_deg = 360.0       deg turned (then straight again)
    turn_direction = "left"      "left" (counter-clockwise seen from above) | "right"
    [simulation]
    model = "axial"              "axial" | "planar" | "lumped3d" (required)
    duration = 100.0             s (required)
    time_step = 0.01             s (required)
    output_step = 0.1            s, a multiple of time_step (default time_step)
    segments = 20                number of elements along the line (default 20)
    start = "static"             "static" (the statics solution, default) | "unstrained"
                                 (at rest, unstretched, hanging straight down from end_b,
                                 as Huang (1992) 5.7.1) | "dropped" (planar, lumped3d:
                                 straight down and slack, the unit drop_height above
                                 where the line goes taut, at rest)
    drop_height                  m, with start = "dropped" (below cable.length)
    scheme = "midpoint"          time integration; valid values per model in SCHEMES
    tolerance = 1e-10            Newton tolerance of an implicit step (scaled residual:
                                 positions over the static elongation, accelerations over g)
    max_iterations = 20          Newton iterations per step
    on_slack = "continue"        "continue" | "stop": what to do when a tension <= 0 is
                                 found (Huang (1992) 4.5.1: the model predicts slack but
                                 cannot follow it); either way the result says so
    top_end = "pinned"           "pinned" (default) | "clamped": with bending stiffness, the
                                 top tangent held at its static direction (a cantilever;
                                 planar model only; cable_ocp.dynamics.bending_terms)
    [response]                   defaults of `cable-ocp response` (frequencies, amplitudes,
                                 outputs, ...: :mod:`cable_ocp.scene.response`)
    [deployment]                 the optimal pay-out (or haul-in) schedule of
                                 `cable-ocp deploy` (:mod:`cable_ocp.scene.deployment`)
    [modes]                      modal analysis and the deployment chart
    count = 6                    number of modes (default 6)
    wave_band = [0.314, 1.571]   rad/s, the wave-frequency band shaded on the chart
                                 (default periods 4-20 s)

The static start: end_a of :attr:`DynamicScene.statics` is a free end whose external load
is the unit's weight in water plus its drag in the current at rest,
1/2 rho C_D S |U| U (the current at the unit's estimated depth: see
:func:`cable_ocp.dynamics.static.static_state`); end_b is fixed at ``end_b.position``.

In air: set ``added_mass_coefficient = 0``, the drag coefficients to 0 (or leave them out
without a current) and ``weight_in_water`` to the weight in air.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from cable_ocp.errors import CableOCPError
from cable_ocp.physics.current import profile_velocity_np
from cable_ocp.scene.deployment import DeploymentProblem, parse_deployment
from cable_ocp.scene.dynamic_parts import (
    BODY_DYN_KEYS,
    CABLE_DYN_KEYS,
    DEFAULT_SCHEME,
    DYNAMIC_TABLES,
    MODELS,
    ROUNDING,
    SCHEMES,
    BodyDynamics,
    ModesOptions,
    SegmentDynamics,
    Simulation,
    TopMotion,
    Tow,
    Unit,
    Vec3,
    parse_modes,
    parse_segment_dynamics,
    parse_simulation,
    parse_top_motion,
    parse_unit,
    vec_or_scalar,
)
from cable_ocp.scene.fields import number as _number
from cable_ocp.scene.fields import require as _require
from cable_ocp.scene.files import apply_overrides, check_kind, read_problem
from cable_ocp.scene.motion import length_numeric
from cable_ocp.scene.parts import Current, End
from cable_ocp.scene.response import ResponseDefaults, parse_response
from cable_ocp.scene.statics import TOP_LEVEL_TABLES, Scene, scene_from_dict

__all__ = [
    "DEFAULT_SCHEME",
    "MODELS",
    "SCHEMES",
    "BodyDynamics",
    "DynamicScene",
    "ModesOptions",
    "SegmentDynamics",
    "Simulation",
    "TopMotion",
    "Tow",
    "Unit",
    "current_at",
    "dynamic_scene_from_dict",
    "is_dynamic_dict",
    "load_dynamic_scene",
]


@dataclass(frozen=True)
class DynamicScene:
    """A validated dynamics problem.

    Attributes
    ----------
    statics : Scene
        The statics problem of the initial state (end_a free with the unit's load, or the
        anchor; end_b fixed at its static position).
    cable : tuple of SegmentDynamics
        Dynamic properties per segment, from end_a to end_b (one for a single cable).
    unit : Unit or None
        The subsea unit at end_a; None for an anchored end_a.
    bodies : tuple of BodyDynamics
        Masses of the point bodies, in the order of ``statics.bodies``.
    top_motion : TopMotion
        Motion of end_b and pay-out.
    simulation : Simulation
        Time-domain settings.
    modes : ModesOptions
        Modal-analysis settings.
    response : ResponseDefaults
        Defaults of ``cable-ocp response`` (:mod:`cable_ocp.scene.response`).
    deployment : DeploymentProblem or None
        The optimal pay-out problem of ``cable-ocp deploy`` (:mod:`cable_ocp.scene.deployment`);
        None without a ``[deployment]`` table.
    """

    statics: Scene
    cable: tuple[SegmentDynamics, ...]
    unit: Unit | None
    bodies: tuple[BodyDynamics, ...]
    top_motion: TopMotion
    simulation: Simulation
    modes: ModesOptions = field(default_factory=ModesOptions)
    response: ResponseDefaults = field(default_factory=ResponseDefaults)
    deployment: DeploymentProblem | None = None
    meta: dict[str, str] = field(default_factory=dict, compare=False, hash=False)
    raw: dict[str, Any] = field(default_factory=dict, compare=False, hash=False, repr=False)

    @property
    def length(self) -> float:
        """Unstretched length at t = 0, m."""
        return float(self.statics.cable.length)  # type: ignore[arg-type]

    @property
    def top_position(self) -> Vec3:
        """Static position of end_b (the ship's attachment), m."""
        return self.statics.end_b.position  # type: ignore[return-value]

    @property
    def anchored(self) -> bool:
        """True when end_a is an anchor (no unit)."""
        return self.unit is None

    def with_overrides(self, overrides: dict[str, Any]) -> DynamicScene:
        """Return a new scene with dotted-key overrides applied to the source dict."""
        return dynamic_scene_from_dict(apply_overrides(self.raw, overrides))


# --------------------------------------------------------------------------------------
# Parsing
# --------------------------------------------------------------------------------------

def is_dynamic_dict(data: dict[str, Any]) -> bool:
    """True when a problem dictionary has any dynamic table ([unit], [top_motion],
    [simulation], [modes])."""
    return isinstance(data, dict) and any(k in data for k in DYNAMIC_TABLES)


def current_at(current: Current | None, z: float) -> Vec3:
    """Current velocity (m/s) at height z (m): linear in the components between knots,
    constant beyond the first and last knot (docs/conventions.md, "Frame and scene files";
    :func:`cable_ocp.physics.current.profile_velocity_np`).

    Parameters
    ----------
    current : Current or None
        The scene's current (None: still water).
    z : float
        Height, m.
    """
    if current is None:
        return (0.0, 0.0, 0.0)
    u = profile_velocity_np(z, current.z, current.ux, current.uy)
    return (float(u[0]), float(u[1]), 0.0)


def _length_history_min(tm: TopMotion, length0: float, duration: float) -> tuple[float, float]:
    """(smallest unstretched length over [0, duration], its time) of the pay-out law."""
    n = 20001
    ts = [duration * k / (n - 1) for k in range(n)]
    ls = length_numeric(tm, length0, ts)[0]
    k = min(range(n), key=lambda i: ls[i])
    return float(ls[k]), ts[k]


def _strip_dynamic(data: dict[str, Any]) -> tuple[dict[str, Any], dict[str, Any]]:
    """Split a dynamic problem dict into (statics dict, dynamic parts)."""
    stat = copy.deepcopy(data)
    dyn: dict[str, Any] = {k: stat.pop(k) for k in DYNAMIC_TABLES if k in stat}
    cab = stat.get("cable")
    if isinstance(cab, dict):
        dyn["cable"] = {k: cab.pop(k) for k in list(cab) if k in CABLE_DYN_KEYS}
        segs = cab.get("segments")
        if isinstance(segs, list):
            dyn["segments"] = [
                {k: s.pop(k) for k in list(s) if k in CABLE_DYN_KEYS} if isinstance(s, dict)
                else {} for s in segs]
    bodies = stat.get("bodies")
    if isinstance(bodies, list):
        dyn["bodies"] = [{k: b.pop(k) for k in list(b) if k in BODY_DYN_KEYS}
                         if isinstance(b, dict) else {} for b in bodies]
    return stat, dyn


def dynamic_scene_from_dict(data: dict[str, Any]) -> DynamicScene:
    """Validate a dynamic problem dictionary (as read from TOML).

    Raises
    ------
    CableOCPError
        On a statics scene (no [simulation]), unknown keys, missing required fields,
        non-finite or out-of-range numbers, or inconsistent settings; the message names
        the key.
    """
    if not isinstance(data, dict):
        raise CableOCPError("a problem must be a table")
    raw = copy.deepcopy(data)
    if "simulation" not in data:
        if is_dynamic_dict(data):
            raise CableOCPError("[simulation] is missing: a dynamic scene needs model, "
                                "duration and time_step")
        raise CableOCPError("this is a statics scene (no [simulation] table): use "
                            "`cable-ocp solve`, or add [simulation] and [unit] for dynamics")
    if "footprint" in data:
        raise CableOCPError("[footprint] is a statics problem: use `cable-ocp footprint`; "
                            "remove [footprint] from a dynamic scene")
    if "layout" in data:
        raise CableOCPError("[layout] is not supported in a dynamic scene: give "
                            "end_b.position directly")
    tables = sorted((set(TOP_LEVEL_TABLES) - {"footprint", "layout"}) | set(DYNAMIC_TABLES))
    unknown = sorted(set(data) - set(tables))
    if unknown:
        raise CableOCPError(f"unknown top-level table [{unknown[0]}]; valid in a dynamic "
                            f"scene: {', '.join(tables)}")
    stat, dyn = _strip_dynamic(data)
    for name in ("environment", "cable"):
        if name not in stat:
            raise CableOCPError(f"[{name}] is missing")
    env_t = stat["environment"] if isinstance(stat["environment"], dict) else {}
    rho = _number(_require(env_t, "water_density", "environment"),
                  "environment.water_density", positive=True)
    g = _number(env_t.get("gravity", 9.81), "environment.gravity", positive=True)

    # the lower end: a unit (free end with its load) or an anchor
    unit = None
    if "unit" in dyn:
        if "end_a" in stat:
            raise CableOCPError("[end_a] and [unit] both given: in a dynamic scene [unit] "
                                "replaces end_a (the unit hangs at end_a); remove [end_a], or "
                                "remove [unit] for an anchored end_a")
        unit = parse_unit(dyn["unit"], rho, g)
        stat["end_a"] = {"force": [0.0, 0.0, -unit.weight_in_water]}  # current added below
    elif "end_a" in stat:
        ea = stat["end_a"]
        if not isinstance(ea, dict) or set(ea) != {"position"}:
            raise CableOCPError(
                "end_a: in a dynamic scene end_a is either an anchor (only position = "
                "[x, y, z], all numbers) or a subsea unit ([unit] instead of [end_a])")
    else:
        raise CableOCPError("[unit] is missing: give the subsea unit at end_a ([unit] with "
                            "mass, weight_in_water, ...) or an anchored [end_a] position")
    eb = stat.get("end_b")
    if not isinstance(eb, dict) or set(eb) != {"position"}:
        raise CableOCPError("end_b: in a dynamic scene end_b is the ship's attachment: give "
                            "only position = [x, y, z] (m, its static position); its motion "
                            "goes in [top_motion]")
    cab = stat.get("cable")
    if isinstance(cab, dict):
        lv = cab.get("length")
        if isinstance(lv, str):
            raise CableOCPError(f"cable.length = {lv!r}: a dynamic scene needs the unstretched "
                                "length at t = 0 (m); a free length is a statics problem")
    statics = scene_from_dict(stat)
    if not all(statics.end_b.fixed_mask):
        raise CableOCPError("end_b.position: every component must be a number (m) in a "
                            "dynamic scene")
    if statics.end_a.tension is not None or statics.end_b.tension is not None:
        raise CableOCPError("end tensions are a statics input; remove them")

    # unit: its drag in the current at rest joins the static load
    if unit is not None and statics.environment.current is not None:
        z_est = statics.end_b.position[2] - statics.cable.length  # type: ignore[operator]
        load = unit.static_load(current_at(statics.environment.current, z_est), rho)
        statics = replace(statics, end_a=End(position=(None, None, None), force=load))

    # cable dynamics, per segment
    lines = statics.lines
    if statics.segments:
        seg_t = dyn.get("segments", [{} for _ in lines])
        extra = sorted(dyn.get("cable", {}))
        if extra:
            raise CableOCPError(f"cable.{extra[0]}: with [[cable.segments]] every segment "
                                f"gives its own {extra[0]}")
        cable = tuple(parse_segment_dynamics(seg_t[i], f"cable.segments[{i}]",
                                              lines[i].diameter, True)
                      for i in range(len(lines)))
    else:
        cable = (parse_segment_dynamics(dyn.get("cable", {}), "cable", lines[0].diameter,
                                         True),)
    for i, (c, d) in enumerate(zip(lines, cable, strict=True)):
        where = f"cable.segments[{i}]" if statics.segments else "cable"
        if c.weight_in_water > d.mass_per_length * g * (1.0 + ROUNDING):
            raise CableOCPError(
                f"{where}.weight_in_water = {c.weight_in_water} N/m exceeds the weight in air "
                f"mass_per_length g = {d.mass_per_length * g:.6g} N/m (buoyancy cannot be "
                f"negative): check {where}.mass_per_length")
        if not c.elastic:
            raise CableOCPError(f"{where}.axial_stiffness is missing: dynamics needs an "
                                "elastic cable (EA, N)")
        if c.tangential_drag > 0.0 and c.diameter <= 0.0:
            raise CableOCPError(f"{where}.diameter is missing: tangential_drag acts on pi d")
        if c.normal_drag > 0.0 and c.diameter <= 0.0:
            raise CableOCPError(f"{where}.diameter is missing: normal_drag acts on d")

    bodies_t = dyn.get("bodies", [])
    bodies = []
    for i, b in enumerate(bodies_t):
        if "mass" not in b:
            raise CableOCPError(f"bodies[{i}].mass is missing (kg, mass in air; a dynamic "
                                "scene needs the mass of every body)")
        mass = _number(b["mass"], f"bodies[{i}].mass", nonneg=True)
        added, _ = vec_or_scalar(b.get("added_mass", 0.0), f"bodies[{i}].added_mass")
        sb = statics.bodies[i]
        w = sb.weight_in_water - sb.net_buoyancy
        if w > mass * g * (1.0 + ROUNDING) + 1e-12:
            raise CableOCPError(f"bodies[{i}].mass = {mass} kg: the weight in water {w} N "
                                f"exceeds the weight in air {mass * g:.6g} N")
        bodies.append(BodyDynamics(mass=mass, added_mass=added))

    top = parse_top_motion(dyn.get("top_motion", {}))
    if top.payout_table_kind == "length" and statics.cable.length is not None:
        l_first = top.payout_table[0][1]
        if abs(l_first - statics.cable.length) > 1e-9 * statics.cable.length:
            raise CableOCPError(
                f"top_motion.payout_length_table[0][1] = {l_first} m: the table's first "
                f"length must be cable.length = {statics.cable.length} m (the length at "
                "t = 0)")
    sim = parse_simulation(dyn["simulation"])
    modes = parse_modes(dyn.get("modes", {}))
    response = parse_response(dyn.get("response", {}))
    deployment = (parse_deployment(dyn["deployment"], statics.cable.length)  # type: ignore[arg-type]
                  if "deployment" in dyn else None)

    if top.varying_length:
        lmin, tmin = _length_history_min(top, statics.cable.length, sim.duration)  # type: ignore[arg-type]
        if lmin <= 0.0:
            key = top.payout_key
            raise CableOCPError(
                f"top_motion.{key}: the unstretched length reaches {lmin:.4g} m at t = "
                f"{tmin:.4g} s (within simulation.duration = {sim.duration} s); it must stay "
                "> 0: haul in less or shorten the duration")
        if statics.segments and statics.cable.length is not None:
            top_seg = statics.segments[-1].length
            shrink = statics.cable.length - lmin  # type: ignore[operator]
            if shrink >= top_seg:  # type: ignore[operator]
                raise CableOCPError(
                    f"top_motion: hauling in {shrink:.4g} m would remove the whole top segment "
                    f"(cable.segments[{len(statics.segments) - 1}].length = {top_seg} m); "
                    "pay-out changes the top segment only")
    if unit is None and sim.start in ("unstrained", "dropped"):
        raise CableOCPError(f'simulation.start = "{sim.start}" needs a unit at end_a: an '
                            "anchored line cannot hang straight and unstretched")
    if sim.start == "dropped" and sim.drop_height >= statics.cable.length:  # type: ignore[operator]
        raise CableOCPError(f"simulation.drop_height = {sim.drop_height} m: must be below "
                            f"cable.length = {statics.cable.length} m")
    meta = {str(k): str(v) for k, v in (data.get("meta") or {}).items()}
    return DynamicScene(statics=statics, cable=cable, unit=unit, bodies=tuple(bodies),
                        top_motion=top, simulation=sim, modes=modes, response=response,
                        deployment=deployment, meta=meta, raw=raw)


def load_dynamic_scene(path: str | Path,
                       overrides: dict[str, Any] | None = None) -> DynamicScene:
    """Read a TOML dynamic problem file, apply dotted-key ``overrides`` and validate it.

    Parameters
    ----------
    path : str or Path
        The problem file.
    overrides : dict, optional
        Dotted keys, e.g. ``{"top_motion.payout_speed": 1.0, "simulation.segments": 40}``
        (values as parsed by :func:`cable_ocp.scene.parse_override`).

    Raises
    ------
    CableOCPError
        Missing file, invalid TOML, a statics scene, or any invalid key (named).
    """
    data = read_problem(path)
    check_kind(data, "dynamics", path)
    if overrides:
        data = apply_overrides(data, overrides)
    return dynamic_scene_from_dict(data)
