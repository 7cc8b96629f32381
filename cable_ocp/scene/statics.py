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
                                 distance and height (De Zoysa's psi0, Wang et al. (1993) eq. (28))
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
    [cable] length = 305.0               m (unstretched), or "free" with a prescribed end tension
    diameter = 0.023             m, hydrodynamic diameter weight_in_water = 12.3       N/m (per
    unstretched length) axial_stiffness = 1.0e9      N (EA); omit or "inf" for an inextensible cable
    normal_drag = 1.0            C_n (-) tangential_drag = 0.005      C_t (-), acts on the wetted
    perimeter pi*D drag_law = "vector"          "vector" (independence principle) | "componentwise"
    (Wang et al. (1993)) [[cable.segments]]           optional multi-segment line, listed from end_a
    to end_b;
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
``force = [2000.0, 0.0, "free"]`` (Huang 1992, eqs (2.12)-(2.15)).

Force sign example: a towed body whose drag is 500 N along -x and whose weight in water
is 2 kN hangs at end_a: ``force = [-500.0, 0.0, -2000.0]``. At equilibrium the cable
pulls on the body with (+500, 0, +2000) N, which is what the JSON output reports as
``end_a.force`` (the force the cable exerts on the attachment).
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from cable_ocp.errors import CableOCPError
from cable_ocp.scene.fields import check_keys, choice, integer, number, require
from cable_ocp.scene.files import apply_overrides, check_kind, read_problem
from cable_ocp.scene.parts import (
    ANGLE_MAX,
    ANGLE_WHY,
    DEPTH_MAX,
    DEPTH_WHY,
    END_KEYS,
    FORCE_MAX,
    FORCE_WHY,
    Body,
    Cable,
    End,
    Environment,
    cable_number,
    check_planar_bending,
    parse_bodies,
    parse_current,
    parse_end,
    parse_meta,
    parse_seabed,
    parse_segments,
    parse_single_cable,
)

#: statics methods a scene may name in ``[solver] method``; the solvers register their
#: functions under these names (:mod:`cable_ocp.methods`), the scene only checks the name
METHODS = ("collocation", "multiple_shooting", "solve_bvp", "wang_shooting_optimization",
           "huang_semianalytic", "chucheepsakul_fem")


@dataclass(frozen=True)
class SolverOptions:
    """Discretisation and solver settings (all optional in a problem file).

    Attributes
    ----------
    method : str
        ``"collocation"`` (default) or another registered method
        (:data:`METHODS`: multiple_shooting, solve_bvp,
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
    compile : str
        ``"never"`` (default): the Newton kernel runs in CasADi's virtual machine.
        ``"auto"``: the residual and its sparse Jacobian are compiled to C with the
        system's C compiler and the library is cached on disk (:mod:`cable_ocp.numerics.compile`):
        a Jacobian about 10x faster and a warm sweep point about 4x (De Zoysa, 40
        intervals: ~0.5 ms against ~2 ms), at the price of a C compilation of about 2 s
        per scene structure and mesh the first time (a later process loads the
        library). Without a compiler it runs interpreted, silently.
    mesh : str
        Collocation of degree 3 and up. ``"kinks"`` (default): a mesh point on every kink
        of the drag (where a flow component relative to the cable changes sign, and at the
        knots of a current profile; :mod:`cable_ocp.statics.kinks`), the parts between
        kinks divided uniformly: uniform high-order collocation loses its order at such a
        kink. Newton moves the mesh onto the kinks of its iterate as it converges, in
        cold solves and in solves started from another mesh's solution (refinement, the
        error estimate, a contact switch); a warm solve from the solver's own solution
        (a sweep, a load-case batch) keeps its start's mesh, so that it costs what it
        did. ``"tracking"``: warm solves move the mesh with the kinks too (about 5-15 %
        more time per warm point of the De Zoysa sweep). ``"uniform"``: ``intervals``
        uniform intervals (per segment).
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
    compile: str = "never"
    mesh: str = "kinks"


@dataclass(frozen=True)
class Footprint:
    """Footprint problem settings (``[footprint]``; Huang (1992) section 2.2.4, type 4).

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
        thrust_x_max, |T_y| <= thrust_y_max, symmetric; docs/conventions.md "Footprint").
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
        "tension_strain",
        "viscoelastic",
    },
    "bodies": "list",
    "footprint": {"max_length", "min_length", "bound", "thrust_max", "thrust_x_max",
                  "thrust_y_max"},
    "end_a": END_KEYS,
    "end_b": END_KEYS,
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
        "compile",
        "mesh",
    },
}

#: the top-level tables of a statics scene
TOP_LEVEL_TABLES: tuple[str, ...] = tuple(_SCHEMA)
_CURRENT_KEYS = {"speed", "heading_deg", "profile"}
_SEGMENT_KEYS = {"length", "diameter", "weight_in_water", "axial_stiffness", "normal_drag",
                 "tangential_drag", "intervals", "bending_stiffness"}
_BODY_KEYS = {"joint", "kind", "weight_in_water", "net_buoyancy", "drag_area",
              "drag_coefficient", "thrust"}

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
    meta = parse_meta(data.get("meta", {}))

    env_t = check_keys(require(data, "environment", "problem"), _SCHEMA["environment"],
                        "environment")
    depth = number(require(env_t, "water_depth", "environment"), "environment.water_depth",
                   positive=True, high=DEPTH_MAX, unit="m", why=DEPTH_WHY)
    rho = number(require(env_t, "water_density", "environment"), "environment.water_density",
                 low=0.1, high=2000.0, unit="kg/m^3",
                 why="air is 1.2 (a cable tested in air), fresh water 1000, sea water "
                     "1020-1030, dense brines ~1300")
    g = number(env_t.get("gravity", 9.81), "environment.gravity", low=0.1, high=30.0,
               unit="m/s^2", why="9.81 on Earth; 1.35 on Titan to 24.8 on Jupiter")
    current = parse_current(env_t["current"]) if "current" in env_t else None
    seabed = parse_seabed(env_t["seabed"]) if "seabed" in env_t else None
    env = Environment(water_depth=depth, water_density=rho, gravity=g, current=current,
                      seabed=seabed)

    cab_t = check_keys(require(data, "cable", "problem"), _SCHEMA["cable"], "cable")
    segments: tuple[Cable, ...] = ()
    seg_intervals: tuple[int | None, ...] = ()
    if "segments" in cab_t:
        cable, segments, seg_intervals = parse_segments(cab_t, current is not None)
    else:
        cable = parse_single_cable(cab_t, current is not None)
    length = cable.length
    bodies = parse_bodies(data.get("bodies"), len(segments)) if "bodies" in data else ()

    end_a = parse_end(require(data, "end_a", "problem"), "end_a")
    end_b = parse_end(require(data, "end_b", "problem"), "end_b")

    layout = check_keys(data.get("layout", {}), _SCHEMA["layout"], "layout")
    if "psi0_deg" in layout:
        psi = number(layout["psi0_deg"], "layout.psi0_deg", low=-ANGLE_MAX, high=ANGLE_MAX,
                     unit="deg", why=ANGLE_WHY)
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
                f"end_a.position and end_b.position ({chord:.6g} m); an inextensible cable "
                "needs length > chord (or give cable.axial_stiffness)"
            )

    sol_t = check_keys(data.get("solver", {}), _SCHEMA["solver"], "solver")
    defaults = SolverOptions()
    method = sol_t.get("method", defaults.method)
    if method not in METHODS:
        raise CableOCPError(f"solver.method = {method!r}: valid are {', '.join(METHODS)}")
    if cable.tension_strain:
        if method not in ("collocation", "multiple_shooting"):
            raise CableOCPError(
                f"solver.method = {method!r}: cable.tension_strain (a nonlinear law) is "
                'solved by "collocation" or "multiple_shooting" only')
        if seabed is not None:
            raise CableOCPError("cable.tension_strain: [environment.seabed] (the grounded "
                                "part's closed-form stretch) needs a linear law; give "
                                "axial_stiffness or remove the seabed table")
    scheme = sol_t.get("scheme", defaults.scheme)
    if scheme not in ("legendre", "radau"):
        raise CableOCPError(f'solver.scheme = {scheme!r}: valid are "legendre", "radau"')
    degree = sol_t.get("degree", defaults.degree)
    if isinstance(degree, bool) or not isinstance(degree, int) or not 1 <= degree <= 9:
        raise CableOCPError(f"solver.degree = {degree!r}: expected an integer 1..9")
    intervals = sol_t.get("intervals", defaults.intervals)
    if isinstance(intervals, bool) or not isinstance(intervals, int) or not 1 <= intervals <= 20000:
        raise CableOCPError(f"solver.intervals = {intervals!r}: expected an integer 1..20000")
    max_it = integer(sol_t.get("max_iterations", defaults.max_iterations),
                     "solver.max_iterations", 1, 100000,
                     why="IPOPT iterations per attempt; a solve converges in tens")
    guess = sol_t.get("initial_guess", defaults.initial_guess)
    if guess not in ("catenary", "straight"):
        raise CableOCPError(f'solver.initial_guess = {guess!r}: valid are "catenary", "straight"')
    est = sol_t.get("error_estimate", defaults.error_estimate)
    if not isinstance(est, bool):
        raise CableOCPError(f"solver.error_estimate = {est!r}: expected true or false")
    refine = sol_t.get("refine", defaults.refine)
    if not isinstance(refine, bool):
        raise CableOCPError(f"solver.refine = {refine!r}: expected true or false")
    max_int = integer(sol_t.get("max_intervals", defaults.max_intervals),
                      "solver.max_intervals", 1, 20000, why="as solver.intervals")
    solver = SolverOptions(
        method=method,
        scheme=scheme,
        degree=degree,
        intervals=intervals,
        tolerance=number(sol_t.get("tolerance", defaults.tolerance), "solver.tolerance",
                         low=1e-16, high=1e-2,
                         why="a scaled residual; above 1e-2 an iterate is no solution, and "
                             "the error estimate reports what the tolerance lets through"),
        max_iterations=max_it,
        smoothing=number(sol_t.get("smoothing", defaults.smoothing), "solver.smoothing",
                         positive=True, low=1e-12, high=0.1, unit="m/s",
                         why="the drag is off by up to smoothing^2 / 2 (m/s)^2 (reported as "
                             "smoothing_force_bound_N); below 1e-12 the modulus is not smooth "
                             "in double precision"),
        vertical_blend=number(sol_t.get("vertical_blend", defaults.vertical_blend),
                              "solver.vertical_blend", positive=True, unit="-"),
        error_estimate=est,
        initial_guess=guess,
        compile=choice(sol_t.get("compile", defaults.compile), "solver.compile",
                       ("never", "auto")),
        mesh=choice(sol_t.get("mesh", defaults.mesh), "solver.mesh",
                    ("kinks", "tracking", "uniform")),
        accuracy=number(sol_t.get("accuracy", defaults.accuracy), "solver.accuracy",
                        low=1e-12, high=1.0, unit="-",
                        why="a relative error: 1e-12 is near what double precision resolves; "
                            "1 accepts any estimate (to read it at a fixed mesh)"),
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
    check_planar_bending(segments, env, end_a, end_b, bodies)
    return Scene(environment=env, cable=cable, end_a=end_a, end_b=end_b, solver=solver,
                 footprint=footprint, meta=meta, raw=raw, segments=segments,
                 segment_intervals=seg_intervals, bodies=bodies)


def _parse_footprint(table: Any, end_a: End, end_b: End) -> Footprint:
    table = check_keys(table, _SCHEMA["footprint"], "footprint")
    if end_a.fixed_mask != (False, False, True) or not all(end_b.fixed_mask):
        raise CableOCPError(
            '[footprint] needs the unit at end_a with position = ["free", "free", z] and '
            'force = [Fx, Fy, "free"] (thrust), and the ship at a fixed end_b.position')
    lmax = cable_number(require(table, "max_length", "footprint"), "footprint.max_length",
                        "length")
    lmin = cable_number(table.get("min_length", abs(end_b.position[2] - end_a.position[2])),
                        "footprint.min_length", "length")
    if lmin >= lmax:
        raise CableOCPError(f"footprint.min_length = {lmin} must be < max_length = {lmax}")
    bound = table.get("bound", "magnitude")
    if bound not in ("magnitude", "components"):
        raise CableOCPError(f'footprint.bound = {bound!r}: valid are "magnitude", "components"')
    need = ("thrust_max",) if bound == "magnitude" else ("thrust_x_max", "thrust_y_max")
    vals = {k: number(require(table, k, "footprint"), f"footprint.{k}", nonneg=True,
                      high=FORCE_MAX, unit="N", why=FORCE_WHY) for k in need}
    return Footprint(max_length=lmax, min_length=lmin, bound=bound, **vals)


def load_scene(path: str | Path, overrides: dict[str, Any] | None = None) -> Scene:
    """Read a TOML problem file, apply ``overrides`` (dotted keys) and validate it.

    Parameters
    ----------
    path : str or Path
        The statics problem file (UTF-8 TOML, SI units).
    overrides : dict, optional
        Dotted key -> value (as ``--set`` gives them, e.g. ``{"cable.length": 305.0}``),
        applied before validation; None (default): none.

    Raises
    ------
    CableOCPError
        When the file cannot be read (:func:`~cable_ocp.scene.files.read_problem`), is a
        heave or dynamics scene, or does not validate.
    """
    data = read_problem(path)
    check_kind(data, "statics", path)
    if overrides:
        data = apply_overrides(data, overrides)
    return scene_from_dict(data)
