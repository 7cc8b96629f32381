"""Design optimisation of a mooring system, with exact gradients through the equilibrium.

Variables (:func:`parse_variable`, chosen by name): a line's unstretched length
(``"length:L1"``; ``"length:L1,L2,L3"`` ties several lines to one value; on a line of
several parts the value is the line's total length with every part's share held, and
``"length:L1/0"`` is part 0's length alone), a free point's mass (``"mass:clump"``, kg),
a line's anchor radius (``"radius:L1"``, m) and heading (``"heading:L1"``, rad): the
line's fixed point moved on the horizontal ray from the reference point of the body
(its position in the file) at that heading, its z kept.

Outputs (:class:`DesignPoint`), at the equilibrium under a design load (a force at a
body's reference point, replacing the file's force on that body): the body's horizontal
offset from its position in the file (m); every line's end tensions (N, at point_a and
point_b) and their safety factors MBL / T_end (MBL of the part at that end: end tensions,
which are differentiable, stand for the largest tension, which for a chain hanging in
still water is at the upper end); every line's laid length (m, grounded at its lower
end); every fixed point's uplift (the vertical force of its lines on it, N, + up); the
mooring's mass (kg: sum of mass_per_length * length and the free points' masses) and
cost (sum of cost_per_length * length).

Exact gradients by the implicit-function theorem on the system: at an equilibrium
R(q, p) = 0 (q the unknowns, Euler angles for rotations, p the variables),
dq/dp = -R_q^-1 R_p, with R_q the equilibrium's Newton matrix
(:meth:`SystemModel.euler_system`) and R_p assembled, like R_q, from the lines' own
sensitivities to their ends and to their length
(:meth:`cable_ocp.statics.solution.StaticsSolution.length_sensitivity`); an output
y(q, p) then has dy/dp = y_p + y_q dq/dp. Exact for the discretised equations except
the derivative in one part's length of a multi-part line: the parts' shares are baked
into the line's built functions (``Formulation.fractions``), so that derivative is a
central difference of two line solves (step :data:`PART_STEP`) at the equilibrium's end
positions, each a new line structure (a solver build).

:func:`optimise` minimises the mass or the cost under offset, safety-factor, laid-length
and uplift constraints with ``scipy.optimize.minimize(method="SLSQP")`` and these
gradients; :func:`gradient_timing` times an exact gradient against finite differences of
full equilibria.
"""

from __future__ import annotations

import copy
import math
import time
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.mooring.equilibrium import solve_system
from cable_ocp.mooring.model import Evaluation, SystemModel
from cable_ocp.numerics.rotation import euler_rate_matrix
from cable_ocp.scene import End
from cable_ocp.scene.system import SystemScene, system_from_dict
from cable_ocp.statics.solver import SolveSession

__all__ = ["DesignPoint", "DesignResult", "MooringDesign", "Variable", "gradient_timing",
           "optimise", "parse_variable"]

KINDS = ("length", "mass", "radius", "heading")
#: central-difference step of a part's length (m), the one derivative not exact
PART_STEP = 1e-2
_SWAP = [3, 4, 5, 0, 1, 2]


@dataclass(frozen=True)
class Variable:
    """A design variable: ``kind`` (length | mass | radius | heading) on ``targets`` (line
    names, ``"line/part"`` for one part's length, free point names for a mass), all held
    at one value."""

    kind: str
    targets: tuple[str, ...]

    @property
    def name(self) -> str:
        """``kind:target,target``."""
        return f"{self.kind}:{','.join(self.targets)}"


def parse_variable(text: str) -> Variable:
    """A variable from its name, ``kind:target[,target...]``.

    Parameters
    ----------
    text : str
        E.g. ``"length:L1,L2,L3"``, ``"length:L1/0"``, ``"mass:clump"``, ``"radius:L1"``,
        ``"heading:L2"``.
    """
    kind, sep, rest = text.partition(":")
    targets = tuple(t.strip() for t in rest.split(",") if t.strip())
    if not sep or kind not in KINDS or not targets:
        raise CableOCPError(f"design variable {text!r}: expected kind:target[,target...] with "
                            f"kind one of {', '.join(KINDS)}")
    return Variable(kind, targets)


@dataclass
class DesignPoint:
    """Outputs at one design and their gradients in the variables (last axis).

    Attributes
    ----------
    x : ndarray
        The variables' values (m, kg, rad).
    offset : float
        The body's horizontal offset from its file position under the design load, m
        (its gradient does not exist at 0: a design load that leaves the body in place).
    tension : ndarray
        (n_lines, 2) end tensions at point_a and point_b, N.
    safety_factor : ndarray
        (n_lines, 2) MBL / end tension (-); NaN without an MBL.
    laid_length : ndarray
        (n_lines,) grounded length at the lower end, m.
    uplift : ndarray
        (n_fixed,) vertical force of the lines on each fixed point, N (+ up).
    mass, cost : float
        The mooring's mass (kg) and cost (currency; NaN without cost_per_length).
    grad : dict
        Output name -> its gradient, shape (*output shape, n_variables).
    """

    x: np.ndarray
    offset: float
    tension: np.ndarray
    safety_factor: np.ndarray
    laid_length: np.ndarray
    uplift: np.ndarray
    mass: float
    cost: float
    grad: dict[str, np.ndarray] = field(default_factory=dict)


@dataclass
class DesignResult:
    """The optimum.

    Attributes
    ----------
    success : bool
        SLSQP's verdict.
    message : str
        SLSQP's message.
    x : dict
        Variable name -> value at the optimum (m, kg, rad).
    point : DesignPoint
        The outputs there.
    constraints : dict
        Constraint name -> its margin (>= 0 feasible, 0 active), scaled as documented in
        :func:`optimise`.
    evaluations : int
        Equilibria solved.
    """

    success: bool
    message: str
    x: dict[str, float]
    point: DesignPoint
    constraints: dict[str, np.ndarray]
    evaluations: int


class MooringDesign:
    """A system, its design variables and its design load: evaluates the outputs and their
    exact gradients at any values of the variables.

    Parameters
    ----------
    scene : SystemScene
        The system (its file values are the start).
    variables : sequence of str or Variable
        The design variables (:func:`parse_variable`).
    load : sequence of float
        The design load, a force (3,) at the body's reference point, N.
    body : str, optional
        The body; default the first body that is not fixed.
    """

    def __init__(self, scene: SystemScene, variables: Sequence[str | Variable],
                 load: Sequence[float], body: str | None = None) -> None:
        self.raw = copy.deepcopy(scene.raw)
        self.variables = [v if isinstance(v, Variable) else parse_variable(v)
                          for v in variables]
        free = [b.name for b in scene.bodies if not all(b.held)]
        if body is None and not free:
            raise CableOCPError("design: the system has no free body to load")
        self.body = body or free[0]
        if self.body not in {b.name for b in scene.bodies}:
            raise CableOCPError(f"design: body = {self.body!r}: no such body")
        self.load = np.asarray(load, float).reshape(3)
        for b in self.raw.get("bodies", []):
            if b["name"] == self.body:
                b["force"] = self.load.tolist()
                self.centre = np.array(b["position"][:2], float)
        self.scene = scene
        self._lines = {t["name"]: t for t in self.raw["lines"]}
        self._points = {t["name"]: t for t in self.raw["points"]}
        kinds = {p.name: p.kind for p in scene.points}
        for v in self.variables:
            for t in v.targets:
                line = t.split("/")[0]
                if v.kind == "mass":
                    if kinds.get(t) != "free":
                        raise CableOCPError(f"design variable {v.name!r}: {t!r} is no free "
                                            "point (a clump's mass is on a free point)")
                elif line not in self._lines:
                    raise CableOCPError(f"design variable {v.name!r}: no line {line!r}; "
                                        f"lines: {', '.join(self._lines)}")
                elif v.kind in ("radius", "heading") and self._anchor(line) is None:
                    raise CableOCPError(f"design variable {v.name!r}: line {line!r} has no "
                                        "fixed point (an anchor) to move")
        claims: list[tuple[str, str, str]] = []  # (kind, line or point, part or "")
        for v in self.variables:
            for t in v.targets:
                line, _, part = t.partition("/")
                if v.kind == "length" and part and len(_parts(self._lines[line])) == 1:
                    part = ""  # one part: the line's length (exact)
                where = self._anchor(line) if v.kind in ("radius", "heading") else line
                mine = (v.kind, str(where), part)
                if any(c[:2] == mine[:2] and (not c[2] or not part or c[2] == part)
                       for c in claims):
                    raise CableOCPError(
                        f"design variable {v.name!r}: {t!r} is already set by another "
                        "variable (a line's length and one of its parts' lengths, one anchor "
                        "moved twice, or one target twice)")
                claims.append(mine)
        self.model: SystemModel | None = None
        self.evaluations = 0

    # -- the scene at given values ---------------------------------------------------------
    def _anchor(self, line: str) -> str | None:
        t = self._lines[line]
        for key in ("point_a", "point_b"):
            if self._points[t[key]]["kind"] == "fixed":
                return t[key]
        return None

    def values(self) -> np.ndarray:
        """The variables' values in the file (m, kg, rad; of a tied variable, its first
        target's)."""
        out = []
        for v in self.variables:
            t = v.targets[0]
            if v.kind == "length":
                line, _, part = t.partition("/")
                parts = _parts(self._lines[line])
                out.append(parts[int(part)]["length"] if part else
                           sum(p["length"] for p in parts))
            elif v.kind == "mass":
                out.append(float(self._points[t].get("mass", 0.0)))
            else:
                rel = np.asarray(self._points[self._anchor(t)]["position"][:2]) - self.centre
                out.append(math.hypot(*rel) if v.kind == "radius" else math.atan2(rel[1],
                                                                                    rel[0]))
        return np.array(out, float)

    def data_at(self, x: Sequence[float]) -> dict[str, Any]:
        """The problem dict with the variables at ``x`` and the design load.

        Parameters
        ----------
        x : sequence of float
            The variables' values.
        """
        data = copy.deepcopy(self.raw)
        lines = {t["name"]: t for t in data["lines"]}
        points = {t["name"]: t for t in data["points"]}
        for v, val in zip(self.variables, x, strict=True):
            for t in v.targets:
                if v.kind == "length":
                    line, _, part = t.partition("/")
                    parts = _parts(lines[line])
                    if part:
                        parts[int(part)]["length"] = float(val)
                    else:
                        total = sum(p["length"] for p in parts)
                        for p in parts:
                            p["length"] = p["length"] * float(val) / total
                    lines[line].pop("type", None)
                    lines[line].pop("length", None)
                    lines[line]["parts"] = parts
                elif v.kind == "mass":
                    points[t]["mass"] = float(val)
                else:
                    pt = points[self._anchor(t)]
                    rel = np.asarray(pt["position"][:2], float) - self.centre
                    r, h = math.hypot(*rel), math.atan2(rel[1], rel[0])
                    r, h = (float(val), h) if v.kind == "radius" else (r, float(val))
                    pt["position"] = [self.centre[0] + r * math.cos(h),
                                      self.centre[1] + r * math.sin(h), pt["position"][2]]
        return data

    # -- evaluation ---------------------------------------------------------------------------
    def equilibrium(self, x: Sequence[float]) -> tuple[SystemScene, SystemModel, Evaluation]:
        """The equilibrium at ``x`` (warm-started from the last one): its scene, model and
        evaluation (with the Jacobian).

        Parameters
        ----------
        x : sequence of float
            The variables' values.
        """
        scene = system_from_dict(self.data_at(x))
        model = SystemModel(scene)
        start = None
        if self.model is not None and len(self.model.lines) == len(model.lines):
            model.solvers, model.sessions = self.model.solvers, self.model.sessions
            start = self._state
        res = solve_system(scene, model=model, start=start, stiffness=False)
        self.evaluations += 1
        if res.status != "solved":
            raise CableOCPError(f"design: no equilibrium at {self._named(x)}: {res.message}")
        self.model, self._state = model, res.state
        ev = model.evaluate(res.state)
        return scene, model, ev

    def _named(self, x: Sequence[float]) -> str:
        return ", ".join(f"{v.name} = {val:.6g}" for v, val in zip(self.variables, x,
                                                                   strict=True))

    def evaluate(self, x: Sequence[float], gradient: bool = True) -> DesignPoint:
        """The outputs at ``x`` and (``gradient``) their exact gradients.

        Parameters
        ----------
        x : sequence of float
            The variables' values (m, kg, rad).
        gradient : bool
            Also the gradients (the implicit-function theorem; one line factorisation per
            line, reused for the 6x6 and the length).
        """
        x = np.asarray(x, float)
        scene, model, ev = self.equilibrium(x)
        fixed = [p.name for p in scene.points if p.kind == "fixed"]
        nl, nv = len(model.lines), len(self.variables)
        pose = ev.state.bodies[self.body]
        dxy = pose[:2] - self.centre
        offset = float(math.hypot(*dxy))
        forces = np.array([np.concatenate(f) for f in ev.end_forces])  # (nl, 6), point order
        tension = np.linalg.norm(forces.reshape(nl, 2, 3), axis=2)
        mbl = np.array([[_mbl(scene, ln.parts[0][0]), _mbl(scene, ln.parts[-1][0])]
                        for ln in model.lines])
        laid = np.array([sol.grounded_length for sol in ev.lines])
        uplift = np.zeros(len(fixed))
        for i, ln in enumerate(model.lines):
            for k, pname in enumerate((ln.point_a, ln.point_b)):
                if pname in fixed:
                    uplift[fixed.index(pname)] += forces[i, 3 * k + 2]
        mass, dmass, cost, dcost = self._mass_cost(scene)
        point = DesignPoint(x=x, offset=offset, tension=tension, safety_factor=mbl / tension,
                            laid_length=laid, uplift=uplift, mass=mass, cost=cost)
        if not gradient:
            return point
        dforce, dlaid, dq = self._sensitivities(scene, model, ev)
        c = model.cols[self.body].start
        point.grad["offset"] = (dxy / max(offset, 1e-300)) @ dq[c: c + 2]
        f3 = forces.reshape(nl, 2, 3)
        dt = np.einsum("lkj,lkjv->lkv", f3 / tension[..., None], dforce.reshape(nl, 2, 3, nv))
        point.grad["tension"] = dt
        point.grad["safety_factor"] = -(mbl / tension**2)[..., None] * dt
        point.grad["laid_length"] = dlaid
        dup = np.zeros((len(fixed), nv))
        for i, ln in enumerate(model.lines):
            for k, pname in enumerate((ln.point_a, ln.point_b)):
                if pname in fixed:
                    dup[fixed.index(pname)] += dforce[i, 3 * k + 2]
        point.grad["uplift"] = dup
        point.grad["mass"], point.grad["cost"] = dmass, dcost
        return point

    def _mass_cost(self, scene: SystemScene) -> tuple[float, np.ndarray, float, np.ndarray]:
        """The mass (kg) and cost, and their gradients in the variables."""
        types = scene.line_types
        mpl = {n: (t.mass_per_length if t.mass_per_length is not None else math.nan)
               for n, t in types.items()}
        cpl = {n: (t.cost_per_length if t.cost_per_length is not None else math.nan)
               for n, t in types.items()}
        mass = sum(mpl[n] * length for ln in scene.lines for n, length in ln.parts) + sum(
            p.mass for p in scene.points if p.kind == "free")
        cost = sum(cpl[n] * length for ln in scene.lines for n, length in ln.parts)
        lines = {ln.name: ln for ln in scene.lines}
        dm, dc = np.zeros(len(self.variables)), np.zeros(len(self.variables))
        for j, v in enumerate(self.variables):
            for t in v.targets:
                if v.kind == "mass":
                    dm[j] += 1.0
                elif v.kind == "length":
                    line, _, part = t.partition("/")
                    parts = lines[line].parts
                    total = lines[line].length
                    share = [(n, 1.0) for n, _ in [parts[int(part)]]] if part else \
                        [(n, length / total) for n, length in parts]
                    dm[j] += sum(mpl[n] * s for n, s in share)
                    dc[j] += sum(cpl[n] * s for n, s in share)
        return float(mass), dm, float(cost), dc

    def _sensitivities(self, scene: SystemScene, model: SystemModel, ev: Evaluation
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(dF/dp (nl, 6, nv) of the end forces in point order, dg/dp (nl, nv) of the laid
        lengths, dq/dp (n, nv) of the unknowns): the implicit-function theorem."""
        nl, nv, n = len(model.lines), len(self.variables), model.n
        free = model.free_dofs()
        _, jac = model.euler_system(ev)
        t = np.eye(n)  # d(small coordinates) / d(unknowns): Euler rates for rotations
        for b in scene.bodies:
            c = model.cols[b.name]
            t[c.start + 3: c.stop, c.start + 3: c.stop] = euler_rate_matrix(
                *ev.state.bodies[b.name][3:])
        g = scene.environment.gravity
        k_q = np.zeros((nl, 6, n))  # dF/dq per line (point order)
        g_q = np.zeros((nl, n))
        f_p = np.zeros((nl, 6, nv))  # dF/dp at fixed q
        g_p = np.zeros((nl, nv))
        r_p = np.zeros((n, nv))  # dR/dp at fixed q, small coordinates
        maps_all = []
        for i, (ln, sol) in enumerate(zip(model.lines, ev.lines, strict=True)):
            sens = sol.length_sensitivity()
            kk, fl = sens["end_jacobian"], sens["force"]
            gx, gl = sens["grounded_length_ends"], sens["grounded_length"]
            if ln.reversed:  # the line scene's end_a is point_b
                kk, fl, gx = kk[np.ix_(_SWAP, _SWAP)], fl[_SWAP], gx[_SWAP]
            maps = [model._end_map(ln.point_a, ev.state), model._end_map(ln.point_b, ev.state)]
            maps_all.append(maps)
            u = np.zeros((6, n))  # d(x_a, x_b)/d(unknowns)
            for e, (cols, te, _, _) in enumerate(maps):
                if cols is not None:
                    u[3 * e: 3 * e + 3, cols] = te
            u = u @ t
            moving = np.any(u != 0.0, axis=1)
            k_q[i] = np.where(moving[None, :], np.nan_to_num(kk), 0.0) @ u
            g_q[i] = np.where(moving, np.nan_to_num(gx), 0.0) @ u
            if np.any(np.isnan(kk[:, moving])) or np.any(np.isnan(gx[moving])):
                raise CableOCPError(f"design: line {ln.name!r} is grounded at a moving end "
                                    "(its force is not differentiable there)")
            for j, v in enumerate(self.variables):
                dx = self._end_motion(v, ln, scene)
                f_p[i, :, j] = np.nan_to_num(kk) @ dx
                g_p[i, j] = np.nan_to_num(gx) @ dx
                for tname in v.targets:
                    if v.kind != "length" or tname.split("/")[0] != ln.name:
                        continue
                    if "/" in tname and len(ln.parts) > 1:
                        dfl, dgl = self._part_difference(scene, model, ev, i,
                                                         int(tname.split("/")[1]))
                        f_p[i, :, j] += dfl
                        g_p[i, j] += dgl
                    else:  # the value is the line's length (its parts' shares held)
                        f_p[i, :, j] += fl
                        g_p[i, j] += gl
            for e, (cols, te, _, _) in enumerate(maps):
                if cols is not None:
                    r_p[cols] += te.T @ f_p[i, 3 * e: 3 * e + 3]
        for j, v in enumerate(self.variables):
            if v.kind == "mass":
                for tname in v.targets:
                    r_p[model.cols[tname].start + 2, j] -= g
        r_p = t.T @ r_p
        dq = np.zeros((n, nv))
        dq[free] = -np.linalg.solve(jac[np.ix_(free, free)], r_p[free])
        dforce = f_p + np.einsum("lin,nv->liv", k_q, dq)
        dlaid = g_p + g_q @ dq
        return dforce, dlaid, dq

    def _end_motion(self, v: Variable, ln: Any, scene: SystemScene) -> np.ndarray:
        """d(x_a, x_b)/d(variable) (6,), m per unit, in point order, at fixed unknowns."""
        out = np.zeros(6)
        if v.kind not in ("radius", "heading"):
            return out
        for tname in v.targets:
            anchor = self._anchor(tname)
            for e, pname in enumerate((ln.point_a, ln.point_b)):
                if pname != anchor:
                    continue
                rel = np.asarray(scene.point(pname).position[:2]) - self.centre
                r, h = math.hypot(*rel), math.atan2(rel[1], rel[0])
                d = (np.array([math.cos(h), math.sin(h)]) if v.kind == "radius"
                     else r * np.array([-math.sin(h), math.cos(h)]))
                out[3 * e: 3 * e + 2] += d
        return out

    def _part_difference(self, scene: SystemScene, model: SystemModel, ev: Evaluation,
                         i: int, part: int) -> tuple[np.ndarray, float]:
        """d(F_a, F_b)/dL_k (point order) and dg/dL_k of line i in one part's length, by a
        central difference of two line solves (step :data:`PART_STEP`) at the equilibrium's
        end positions: the parts' shares are baked into a line's built functions."""
        ln = model.lines[i]
        xa, xb = model.position(ln.point_a, ev.state), model.position(ln.point_b, ev.state)
        out = []
        for sgn in (1.0, -1.0):
            data = copy.deepcopy(scene.raw)
            t = next(t for t in data["lines"] if t["name"] == ln.name)
            t["parts"][part]["length"] += sgn * PART_STEP
            line = next(x for x in system_from_dict(data).lines if x.name == ln.name)
            lo, hi = (xb, xa) if line.reversed else (xa, xb)
            sc = replace(line.scene, end_a=_held(lo), end_b=_held(hi))
            sol = SolveSession(error_estimate=False).solve(sc)
            fa, fb = (sol.force_b, sol.force_a) if line.reversed else (sol.force_a,
                                                                        sol.force_b)
            out.append((np.concatenate([fa, fb]), sol.grounded_length))
        h2 = 2.0 * PART_STEP
        return (out[0][0] - out[1][0]) / h2, (out[0][1] - out[1][1]) / h2


def _parts(t: dict[str, Any]) -> list[dict[str, Any]]:
    """A line table's parts as a list of {type, length} (a copy for one-part lines)."""
    if "parts" in t:
        return t["parts"]
    return [{"type": t["type"], "length": float(t["length"])}]


def _mbl(scene: SystemScene, type_name: str) -> float:
    mbl = scene.line_types[type_name].mbl
    return math.nan if mbl is None else mbl


def _held(x: np.ndarray) -> End:
    pos = tuple(float(v) for v in x)
    return End(position=pos, force=(None, None, None))  # type: ignore[arg-type]


def optimise(scene: SystemScene, variables: Sequence[str], load: Sequence[float],
             max_offset: float, min_safety_factor: float,
             min_laid_length: float | None = None, max_uplift: float | None = None,
             objective: str = "mass", bounds: Sequence[tuple[float, float]] | None = None,
             body: str | None = None, x0: Sequence[float] | None = None,
             tolerance: float = 1e-8, max_iterations: int = 100) -> DesignResult:
    """Minimise the mooring's mass or cost under the design load with SLSQP and exact
    gradients.

    Constraints (each a margin >= 0, scaled to order 1): ``offset`` 1 - offset /
    max_offset; ``safety_factor`` per line end 1 - min_safety_factor T_end / MBL (ends
    without an MBL left out); ``laid_length`` per line with a fixed point at its lower
    end (laid_length - min_laid_length) / ell, ell the line's length; ``uplift`` per
    fixed point (max_uplift - uplift) / T_ref, T_ref the largest end tension at the start.

    Parameters
    ----------
    scene : SystemScene
        The system.
    variables : sequence of str
        Variable names (:func:`parse_variable`).
    load : sequence of float
        Design load (3,) at the body's reference point, N.
    max_offset : float
        Largest horizontal offset of the body, m.
    min_safety_factor : float
        Smallest MBL / end tension (-).
    min_laid_length : float, optional
        Smallest laid length of the anchor lines, m.
    max_uplift : float, optional
        Largest vertical load on a fixed point, N (often 0).
    objective : str
        ``"mass"`` (kg) or ``"cost"``.
    bounds : sequence of (float, float), optional
        Per variable (m, kg, rad).
    body : str, optional
        The loaded body (default the first free one).
    x0 : sequence of float, optional
        Start (default the file's values).
    tolerance : float
        SLSQP's ftol on the objective scaled by its start value.
    max_iterations : int
        SLSQP's iteration limit.
    """
    from scipy.optimize import minimize

    if objective not in ("mass", "cost"):
        raise CableOCPError(f"objective = {objective!r}: valid are 'mass' and 'cost'")
    design = MooringDesign(scene, variables, load, body)
    start = design.values() if x0 is None else np.asarray(x0, float)
    first = design.evaluate(start)
    scale = abs(getattr(first, objective)) or 1.0
    if not math.isfinite(scale):
        raise CableOCPError(f"objective = {objective!r}: a line type has no "
                            f"{objective}_per_length" if objective == "cost" else
                            "objective 'mass': a line type has no mass_per_length")
    t_ref = float(np.max(first.tension))
    cache: dict[bytes, DesignPoint] = {start.tobytes(): first}
    lines = design.model.lines  # type: ignore[union-attr]
    fixed = {p.name for p in scene.points if p.kind == "fixed"}
    lower = [i for i, ln in enumerate(scene.lines) if (ln.point_b if ln.reversed
                                                       else ln.point_a) in fixed]
    ells = np.array([ln.length for ln in lines])

    def at(x: np.ndarray) -> DesignPoint:
        key = np.asarray(x, float).tobytes()
        if key not in cache:
            cache.clear()
            cache[key] = design.evaluate(x)
        return cache[key]

    def margins(pt: DesignPoint, grad: bool) -> dict[str, np.ndarray]:
        sf_ok = np.isfinite(pt.safety_factor)
        mbl = (pt.safety_factor * pt.tension)[sf_ok]
        out = {"offset": (np.array([1.0 - pt.offset / max_offset]),
                          -pt.grad["offset"][None] / max_offset),
               "safety_factor": (1.0 - min_safety_factor * pt.tension[sf_ok] / mbl,
                                 -min_safety_factor * pt.grad["tension"][sf_ok]
                                 / mbl[:, None])}
        if min_laid_length is not None:
            out["laid_length"] = ((pt.laid_length[lower] - min_laid_length) / ells[lower],
                                  pt.grad["laid_length"][lower] / ells[lower, None])
        if max_uplift is not None:
            out["uplift"] = ((max_uplift - pt.uplift) / t_ref, -pt.grad["uplift"] / t_ref)
        return {k: v[1] if grad else v[0] for k, v in out.items()}

    res = minimize(lambda x: getattr(at(x), objective) / scale, start,
                   jac=lambda x: at(x).grad[objective] / scale, method="SLSQP",
                   bounds=bounds,
                   constraints=[{"type": "ineq",
                                 "fun": lambda x: np.concatenate(list(margins(at(x),
                                                                              False).values())),
                                 "jac": lambda x: np.vstack(list(margins(at(x),
                                                                         True).values()))}],
                   options={"ftol": tolerance, "maxiter": max_iterations})
    pt = at(res.x)
    return DesignResult(success=bool(res.success), message=str(res.message),
                        x={v.name: float(val) for v, val in zip(design.variables, res.x,
                                                                 strict=True)},
                        point=pt, constraints=margins(pt, False),
                        evaluations=design.evaluations)


def gradient_timing(scene: SystemScene, variables: Sequence[str], load: Sequence[float],
                    step: float = 1e-3, repeats: int = 3) -> dict[str, float]:
    """Time per gradient of every output: exact (one equilibrium and the implicit-function
    theorem) against forward finite differences of full equilibria (one more equilibrium
    per variable, warm-started), s.

    Parameters
    ----------
    scene : SystemScene
        The system.
    variables : sequence of str
        Variable names.
    load : sequence of float
        Design load (3,), N.
    step : float
        Finite-difference step (m, kg, rad).
    repeats : int
        Timings averaged over this many gradients (after one warm-up).
    """
    design = MooringDesign(scene, variables, load)
    x0 = design.values()
    design.evaluate(x0)  # builds the solvers and the sensitivity functions
    t0 = time.perf_counter()
    for _ in range(repeats):
        design.evaluate(x0)
    exact = (time.perf_counter() - t0) / repeats
    plain = time.perf_counter()
    for _ in range(repeats):
        design.evaluate(x0, gradient=False)
    one = (time.perf_counter() - plain) / repeats
    t0 = time.perf_counter()
    for _ in range(repeats):
        design.evaluate(x0, gradient=False)
        for j in range(len(x0)):
            x = x0.copy()
            x[j] += step
            design.evaluate(x, gradient=False)
    fd = (time.perf_counter() - t0) / repeats
    return {"variables": float(len(x0)), "equilibrium_s": one, "exact_gradient_s": exact,
            "finite_difference_s": fd, "speedup": fd / exact}
