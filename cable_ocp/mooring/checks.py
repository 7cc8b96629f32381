"""Design checks of a moored body: its restoring curve, its loads per heading, and the
loss of each line in turn (the checks the mooring standards ask for: DNV-OS-E301 ch. 2
sec. 2, "intact" and "one line failure" conditions; API RP 2SK sec. 5 and 6).

Every check is a sequence of static equilibria (:func:`cable_ocp.mooring.solve_system`)
that reuses one :class:`~cable_ocp.mooring.model.SystemModel` per set of lines (the
lines' solver sessions warm-start from their last solution) and starts each case from
the previous case's equilibrium (continuation).

The reference position (the *neutral* or *mean* position) is the equilibrium of the
system with every body's external steady load (``bodies[].force`` and ``moment``: the
environment's mean load) set to zero, the loads of the free points (clump weights,
buoys) kept: the restoring curve of the standards is about that position (API RP 2SK
sec. 6.3: "the mooring system's restoring force as a function of the vessel offset from
its mean position without environmental load"). Offsets are horizontal, m, along a
heading measured in degrees from +x towards +y.

- :func:`offset_curve`: the body's x, y held at the neutral position plus an offset
  along a heading, its other free degrees of freedom (z, roll, pitch, yaw) and every free
  point in equilibrium; per offset the mooring's restoring force along the heading
  (positive: pointing back towards the neutral position), its transverse force, each
  line's largest tension and the smallest safety factor.
- :func:`heading_loads`: the equilibrium under a steady horizontal load of a given
  magnitude (and moment) turned to each heading; per heading the body's offset from the
  neutral position, the largest tension and the smallest safety factor, and which line.
- :func:`line_failure`: each line removed in turn under the file's loads; per case the
  new equilibrium, the largest tension of the remaining lines and its safety factor, the
  body's offset from the intact equilibrium. A case the solver cannot balance (a body or
  point left without restoring, no equilibrium found) is a failed case with its message,
  not an error of the whole check.

The slope of the restoring curve at zero offset is e^T S e, e = (cos h, sin h), S the
Schur complement on (x, y) of the body's total (mooring + hydrostatic) 6x6 stiffness at
the neutral position, the other free degrees of freedom eliminated
(tests/mooring/test_checks.py checks it).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.mooring.equilibrium import solve_system
from cable_ocp.mooring.model import State, SystemModel
from cable_ocp.mooring.result import SystemResult
from cable_ocp.numerics.jsonable import json_safe
from cable_ocp.scene.system import SystemBody, SystemScene
from cable_ocp.statics.solver import SolveSession

__all__ = ["HeadingLoads", "LineFailure", "OffsetCurve", "heading_loads", "line_failure",
           "neutral_scene", "offset_curve"]

#: the default headings of :func:`heading_loads`, deg
HEADINGS_DEG = tuple(float(h) for h in range(0, 360, 30))


# -- scenes and models ---------------------------------------------------------------------
def neutral_scene(scene: SystemScene) -> SystemScene:
    """The scene without environmental load: every body's ``force`` and ``moment`` zero
    (the free points' own loads kept).

    Parameters
    ----------
    scene : SystemScene
        The system.
    """
    bodies = tuple(replace(b, force=(0.0, 0.0, 0.0), moment=(0.0, 0.0, 0.0))
                   for b in scene.bodies)
    return replace(scene, bodies=bodies)


def _with_body(scene: SystemScene, name: str, **changes: Any) -> SystemScene:
    """``scene`` with the body ``name`` changed (``dataclasses.replace`` arguments)."""
    return replace(scene, bodies=tuple(replace(b, **changes) if b.name == name else b
                                       for b in scene.bodies))


def _retarget(model: SystemModel, scene: SystemScene) -> SystemModel:
    """``model`` evaluating ``scene``, a scene with the same points and lines that differs
    in its bodies' loads or held flags only (read from ``model.scene`` at every
    evaluation): the lines' sessions keep their warm starts."""
    model.scene = scene
    model.bodies = {b.name: b for b in scene.bodies}
    return model


def _failed_model(scene: SystemScene, name: str, donor: SystemModel) -> SystemModel:
    """``SystemModel(scene, skip={name})`` using the built line solvers of ``donor`` (the
    intact model: the same line structures), each line with a new session."""
    model = SystemModel(scene, skip={name})
    model.solvers = donor.solvers
    model.sessions = [SolveSession(error_estimate=False, solvers=donor.solvers)
                      for _ in model.lines]
    return model


def _free_body(scene: SystemScene, body: str | None) -> SystemBody:
    """The body checked: ``body``, or the only free body."""
    if body is not None:
        b = scene.body(body)
        if not b.free:
            raise CableOCPError(f"body {body!r} is fixed (every degree of freedom held); "
                                "the checks need a body with free x and y")
        return b
    free = [b for b in scene.bodies if b.free]
    if len(free) != 1:
        raise CableOCPError(
            f"the system has {len(free)} free bodies ({', '.join(b.name for b in free)}); "
            "name the body to check")
    return free[0]


def _solve(scene: SystemScene, model: SystemModel, start: State | None
           ) -> tuple[SystemResult | None, str]:
    """One equilibrium, a 'no restoring' error of the solver turned into a message."""
    try:
        res = solve_system(scene, model=model, start=start, stiffness=False)
    except CableOCPError as exc:
        return None, str(exc)
    return res, res.message


def _line_table(res: SystemResult | None, names: Sequence[str]
                ) -> tuple[np.ndarray, np.ndarray]:
    """Per line name, its largest tension (N) and safety factor (NaN: removed, failed or
    no MBL)."""
    t = np.full(len(names), math.nan)
    sf = np.full(len(names), math.nan)
    if res is None or not res.converged:
        return t, sf
    for i, n in enumerate(names):
        row = next((ln for ln in res.lines if ln["name"] == n), None)
        if row is not None:
            t[i] = row["max_tension"]
            sf[i] = math.nan if row["safety_factor"] is None else row["safety_factor"]
    return t, sf


def _worst(values: np.ndarray, names: Sequence[str], largest: bool) -> tuple[float, str]:
    """The largest (or smallest) finite value and its line's name (NaN, '' when none)."""
    ok = np.isfinite(values)
    if not ok.any():
        return math.nan, ""
    idx = np.where(ok)[0]
    k = idx[int(np.argmax(values[idx]) if largest else np.argmin(values[idx]))]
    return float(values[k]), names[k]


def _neutral(scene: SystemScene, model: SystemModel, name: str) -> SystemResult:
    """The equilibrium without environmental load (raises when there is none)."""
    res = solve_system(scene, model=model, stiffness=True)
    if not res.converged:
        raise CableOCPError(f"no equilibrium of the system without environmental load "
                            f"(the reference position of the checks): {res.message}")
    return res


# -- the restoring curve -------------------------------------------------------------------
@dataclass
class OffsetCurve:
    """The restoring curve of a body along one heading (:func:`offset_curve`).

    Attributes
    ----------
    body : str
        The body.
    heading_deg : float
        deg from +x towards +y.
    neutral : ndarray
        (x, y, z) of the neutral position (no environmental load), m.
    offsets : ndarray
        (n,) horizontal offsets along the heading from the neutral position, m.
    restoring_force : ndarray
        (n,) the mooring's horizontal force on the body along -heading, N (positive:
        restoring, pointing back).
    transverse_force : ndarray
        (n,) its component along the heading turned by +90 deg, N.
    line_names : list of str
        The lines, in file order.
    line_tension : ndarray
        (n, lines) each line's largest tension, N.
    max_tension : ndarray
        (n,) the largest of them, N.
    min_safety_factor : ndarray
        (n,) the smallest safety factor against the MBL (NaN: no MBL), -.
    poses : ndarray
        (n, 6) the body's pose, m and deg (roll, pitch, yaw).
    status : list of str
        Per offset, "solved" or "failed".
    messages : list of str
        Per offset, the solver's message.
    neutral_stiffness : ndarray
        The body's total (mooring + hydrostatic) 6x6 at the neutral position.
    """

    body: str
    heading_deg: float
    neutral: np.ndarray
    offsets: np.ndarray
    restoring_force: np.ndarray
    transverse_force: np.ndarray
    line_names: list[str]
    line_tension: np.ndarray
    max_tension: np.ndarray
    min_safety_factor: np.ndarray
    poses: np.ndarray
    status: list[str]
    messages: list[str]
    neutral_stiffness: np.ndarray = field(repr=False)

    def to_dict(self) -> dict[str, Any]:
        """Strict-JSON-ready dictionary (SI; NaN as null)."""
        return json_safe({
            "kind": "offset_curve", "body": self.body, "heading_deg": self.heading_deg,
            "neutral": self.neutral, "offsets": self.offsets,
            "restoring_force": self.restoring_force,
            "restoring_force_definition": "-(mooring force on the body) . (cos h, sin h), N",
            "transverse_force": self.transverse_force, "line_names": self.line_names,
            "line_tension": self.line_tension, "max_tension": self.max_tension,
            "min_safety_factor": self.min_safety_factor, "poses": self.poses,
            "status": self.status, "messages": self.messages,
            "neutral_stiffness": self.neutral_stiffness})


def offset_curve(scene: SystemScene, body: str | None, heading_deg: float,
                 offsets: Sequence[float]) -> OffsetCurve:
    """The restoring curve: the body's x, y held at offsets along a heading from its
    neutral position (no environmental load, module notes), z, roll, pitch, yaw (those
    free in the file) and the free points in equilibrium.

    Parameters
    ----------
    scene : SystemScene
        The system (its bodies' external loads are ignored).
    body : str or None
        The body (None: the only free body); its x and y must be free.
    heading_deg : float
        Direction of the offsets, deg from +x towards +y.
    offsets : sequence of float
        Offsets along the heading, m (negative: the other way). Solved outwards from
        zero on each side, each from the previous one's equilibrium.

    Returns
    -------
    OffsetCurve
        In the order of ``offsets``; a failed offset has NaN values and its message.
    """
    b = _free_body(scene, body)
    if b.held[0] or b.held[1]:
        raise CableOCPError(f"body {b.name!r} holds x or y (bodies[].held = "
                            f"{[d for d, h in zip('xy', b.held[:2], strict=True) if h]}); "
                            "the offset curve needs both free")
    d = np.asarray(offsets, float)
    if d.ndim != 1 or d.size == 0 or not np.all(np.isfinite(d)):
        raise CableOCPError(f"offsets = {offsets!r}: give a non-empty list of finite "
                            "offsets in m")
    h = math.radians(float(heading_deg))
    e = np.array([math.cos(h), math.sin(h)])
    et = np.array([-math.sin(h), math.cos(h)])
    free = neutral_scene(scene)
    model = SystemModel(free)
    zero = _neutral(free, model, b.name)
    x0 = np.asarray(zero.state.bodies[b.name], float)
    held = _with_body(free, b.name, held=(True, True, *b.held[2:]))
    _retarget(model, held)
    names = [ln.name for ln in scene.lines]
    n = d.size
    rest, trans, mins = np.full(n, math.nan), np.full(n, math.nan), np.full(n, math.nan)
    tmax = np.full(n, math.nan)
    tens = np.full((n, len(names)), math.nan)
    poses = np.full((n, 6), math.nan)
    status, messages = ["failed"] * n, [""] * n
    # outwards from zero on each side: continuation from the neighbour nearer zero
    sides = [[i for i in np.argsort(d) if d[i] >= 0], [i for i in np.argsort(-d) if d[i] < 0]]
    for side in sides:
        start = zero.state.copy()
        for i in side:
            trial = start.copy()
            trial.bodies[b.name][:2] = x0[:2] + d[i] * e
            res, messages[i] = _solve(held, model, trial)
            if res is None or not res.converged:
                continue
            status[i] = "solved"
            f = np.asarray(res.body(b.name)["mooring_force"], float)
            rest[i], trans[i] = -float(f[:2] @ e), float(f[:2] @ et)
            tens[i], sf = _line_table(res, names)
            mins[i] = _worst(sf, names, largest=False)[0]
            tmax[i] = _worst(tens[i], names, largest=True)[0]
            pose = res.state.bodies[b.name]
            poses[i] = [*pose[:3], *np.degrees(pose[3:])]
            start = res.state
    return OffsetCurve(
        body=b.name, heading_deg=float(heading_deg), neutral=x0[:3].copy(), offsets=d,
        restoring_force=rest, transverse_force=trans, line_names=names, line_tension=tens,
        max_tension=tmax,
        min_safety_factor=mins, poses=poses, status=status, messages=messages,
        neutral_stiffness=np.asarray(zero.stiffness(b.name, "total")))


# -- loads per heading ---------------------------------------------------------------------
@dataclass
class HeadingLoads:
    """The equilibria under one steady load turned to each heading (:func:`heading_loads`).

    Attributes
    ----------
    body : str
        The body loaded.
    force : float
        Magnitude of the horizontal load, N.
    moment : ndarray
        (Mx, My, Mz) at heading 0, N m (turned with the force).
    neutral : ndarray
        (x, y, z) of the neutral position, m.
    headings_deg : ndarray
        (n,) deg from +x towards +y.
    offsets : ndarray
        (n, 2) the body's horizontal offset from the neutral position, m.
    offset : ndarray
        (n,) its length, m.
    rotation_deg : ndarray
        (n, 3) roll, pitch, yaw, deg.
    max_tension : ndarray
        (n,) the largest tension of any line, N.
    max_tension_line : list of str
        Per heading, that line.
    min_safety_factor : ndarray
        (n,) the smallest safety factor (NaN: no MBL), -.
    min_safety_factor_line : list of str
        Per heading, that line.
    line_names : list of str
        The lines.
    line_tension : ndarray
        (n, lines) each line's largest tension, N.
    status, messages : list of str
        Per heading.
    """

    body: str
    force: float
    moment: np.ndarray
    neutral: np.ndarray
    headings_deg: np.ndarray
    offsets: np.ndarray
    offset: np.ndarray
    rotation_deg: np.ndarray
    max_tension: np.ndarray
    max_tension_line: list[str]
    min_safety_factor: np.ndarray
    min_safety_factor_line: list[str]
    line_names: list[str]
    line_tension: np.ndarray
    status: list[str]
    messages: list[str]

    def to_dict(self) -> dict[str, Any]:
        """Strict-JSON-ready dictionary (SI; NaN as null)."""
        return json_safe({"kind": "heading_loads", **{
            k: getattr(self, k) for k in self.__dataclass_fields__}})


def heading_loads(scene: SystemScene, body: str | None, force: float,
                  moment: Sequence[float] = (0.0, 0.0, 0.0),
                  headings_deg: Sequence[float] = HEADINGS_DEG) -> HeadingLoads:
    """The equilibrium under a steady horizontal load of magnitude ``force`` at each
    heading (the file's loads on the body replaced; the other bodies without load).

    Parameters
    ----------
    scene : SystemScene
        The system.
    body : str or None
        The body loaded (None: the only free body).
    force : float
        Magnitude of the horizontal force at the reference point, N; at heading h it is
        force * (cos h, sin h, 0).
    moment : sequence of float
        (Mx, My, Mz) at heading 0, N m, about the reference point; turned about z with
        the force (Mz unchanged).
    headings_deg : sequence of float
        deg from +x towards +y; solved in this order, each from the previous equilibrium.

    Returns
    -------
    HeadingLoads
        Per heading; a failed heading has NaN values and its message.
    """
    b = _free_body(scene, body)
    mag = float(force)
    if not math.isfinite(mag) or mag < 0.0:
        raise CableOCPError(f"force = {force!r}: give the load's magnitude, N (>= 0)")
    mom = np.asarray(moment, float)
    if mom.shape != (3,) or not np.all(np.isfinite(mom)):
        raise CableOCPError(f"moment = {moment!r}: give [Mx, My, Mz], N m")
    hd = np.asarray(headings_deg, float)
    free = neutral_scene(scene)
    model = SystemModel(free)
    zero = _neutral(free, model, b.name)
    x0 = np.asarray(zero.state.bodies[b.name], float)
    names = [ln.name for ln in scene.lines]
    n = hd.size
    offs, rot = np.full((n, 2), math.nan), np.full((n, 3), math.nan)
    tmax, sfmin = np.full(n, math.nan), np.full(n, math.nan)
    tline, sfline = [""] * n, [""] * n
    tens = np.full((n, len(names)), math.nan)
    status, messages = ["failed"] * n, [""] * n
    start = zero.state
    for i, hdeg in enumerate(hd):
        c, s = math.cos(math.radians(hdeg)), math.sin(math.radians(hdeg))
        rz = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        loaded = _with_body(free, b.name, force=(mag * c, mag * s, 0.0),
                            moment=tuple(float(v) for v in rz @ mom))
        res, messages[i] = _solve(loaded, _retarget(model, loaded), start)
        if res is None or not res.converged:
            continue
        status[i] = "solved"
        pose = res.state.bodies[b.name]
        offs[i], rot[i] = pose[:2] - x0[:2], np.degrees(pose[3:])
        tens[i], sf = _line_table(res, names)
        tmax[i], tline[i] = _worst(tens[i], names, largest=True)
        sfmin[i], sfline[i] = _worst(sf, names, largest=False)
        start = res.state
    return HeadingLoads(
        body=b.name, force=mag, moment=mom, neutral=x0[:3].copy(), headings_deg=hd,
        offsets=offs, offset=np.hypot(offs[:, 0], offs[:, 1]), rotation_deg=rot,
        max_tension=tmax, max_tension_line=tline, min_safety_factor=sfmin,
        min_safety_factor_line=sfline, line_names=names, line_tension=tens, status=status,
        messages=messages)


# -- one line failed -----------------------------------------------------------------------
@dataclass
class LineFailure:
    """The equilibria with each line removed in turn (:func:`line_failure`).

    Attributes
    ----------
    body : str
        The body whose offset is reported.
    intact_position : ndarray
        (x, y, z) of the intact equilibrium under the file's loads, m.
    intact_max_tension : float
        The largest tension of the intact system, N.
    intact_max_tension_line : str
        Its line.
    intact_min_safety_factor : float
        Its smallest safety factor (NaN: no MBL).
    removed : list of str
        Per case, the line removed.
    max_tension : ndarray
        (n,) the largest tension of the remaining lines, N.
    max_tension_line : list of str
        Per case, that line.
    min_safety_factor : ndarray
        (n,) the smallest safety factor of the remaining lines (NaN: no MBL), -.
    min_safety_factor_line : list of str
        Per case, that line.
    offsets : ndarray
        (n, 2) the body's horizontal move from the intact equilibrium, m.
    offset : ndarray
        (n,) its length, m.
    line_names : list of str
        The lines.
    line_tension : ndarray
        (n, lines) each line's largest tension (NaN for the removed one), N.
    status, messages : list of str
        Per case: "solved" or "failed" and why (e.g. a degree of freedom left without
        restoring).
    """

    body: str
    intact_position: np.ndarray
    intact_max_tension: float
    intact_max_tension_line: str
    intact_min_safety_factor: float
    removed: list[str]
    max_tension: np.ndarray
    max_tension_line: list[str]
    min_safety_factor: np.ndarray
    min_safety_factor_line: list[str]
    offsets: np.ndarray
    offset: np.ndarray
    line_names: list[str]
    line_tension: np.ndarray
    status: list[str]
    messages: list[str]
    results: list[SystemResult | None] = field(default_factory=list, repr=False)

    def to_dict(self) -> dict[str, Any]:
        """Strict-JSON-ready dictionary (SI; NaN as null; without the full results)."""
        return json_safe({"kind": "line_failure", **{
            k: getattr(self, k) for k in self.__dataclass_fields__ if k != "results"}})


def line_failure(scene: SystemScene, body: str | None = None,
                 lines: Sequence[str] | None = None) -> LineFailure:
    """Each line removed in turn (``SystemModel(scene, skip={name})``) under the file's
    loads, each case started from the intact equilibrium.

    Parameters
    ----------
    scene : SystemScene
        The system, with its environmental loads.
    body : str, optional
        The body whose offset is reported (the only free body when None).
    lines : sequence of str, optional
        The lines to remove (one per case); None: every line.

    Returns
    -------
    LineFailure
        Per case; a case without equilibrium is "failed" with the solver's message.
    """
    b = _free_body(scene, body)
    names = [ln.name for ln in scene.lines]
    cases = list(names if lines is None else lines)
    for c in cases:
        if c not in names:
            raise CableOCPError(f"lines: no line {c!r}; lines: {', '.join(names)}")
    donor = SystemModel(scene)
    intact = solve_system(scene, model=donor, stiffness=False)
    if not intact.converged:
        raise CableOCPError(f"no intact equilibrium under the file's loads: {intact.message}")
    x0 = np.asarray(intact.state.bodies[b.name], float)
    t0, sf0 = _line_table(intact, names)
    n = len(cases)
    tmax, sfmin = np.full(n, math.nan), np.full(n, math.nan)
    tline, sfline = [""] * n, [""] * n
    offs = np.full((n, 2), math.nan)
    tens = np.full((n, len(names)), math.nan)
    status, messages = ["failed"] * n, [""] * n
    results: list[SystemResult | None] = []
    for i, name in enumerate(cases):
        if len(names) == 1:
            res, messages[i] = None, f"removing line {name!r} leaves no line"
        else:
            res, messages[i] = _solve(scene, _failed_model(scene, name, donor), intact.state)
        results.append(res)
        if res is None or not res.converged:
            continue
        status[i] = "solved"
        offs[i] = res.state.bodies[b.name][:2] - x0[:2]
        tens[i], sf = _line_table(res, names)
        tmax[i], tline[i] = _worst(tens[i], names, largest=True)
        sfmin[i], sfline[i] = _worst(sf, names, largest=False)
    return LineFailure(
        body=b.name, intact_position=x0[:3].copy(),
        intact_max_tension=_worst(t0, names, True)[0],
        intact_max_tension_line=_worst(t0, names, True)[1],
        intact_min_safety_factor=_worst(sf0, names, False)[0], removed=cases,
        max_tension=tmax, max_tension_line=tline, min_safety_factor=sfmin,
        min_safety_factor_line=sfline, offsets=offs, offset=np.hypot(offs[:, 0], offs[:, 1]),
        line_names=names, line_tension=tens, status=status, messages=messages,
        results=results)
