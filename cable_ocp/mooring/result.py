"""The result of a system equilibrium: poses, line tables, point positions, stiffness.

:class:`SystemResult` keeps the habits of the line result
(:class:`~cable_ocp.statics.solution.StaticsSolution`): numpy arrays, a ``status`` of the
one vocabulary, ``message`` and ``diagnostics``, ``to_dict()`` strict-JSON-ready (a
number that does not exist is null), ``plot()``.

Per line (docs/systems.md, "Outputs"): the tensions at both ends (N), the largest
tension and, per part, its safety factor against the part's MBL (the smallest over the
parts is the line's), the laid length (the grounded length at the lower end, m), and at
each fixed point (an anchor) the horizontal load and the vertical load (uplift positive:
the line pulls the anchor up), N. Per body: the pose, the force and moment (about the
reference point) of every line on it and their sum, and the 6x6 stiffness.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from cable_ocp.mooring.stiffness import body_stiffness
from cable_ocp.numerics.jsonable import json_safe as jsonable
from cable_ocp.status import Status

__all__ = ["SystemResult", "build_result", "line_row"]


@dataclass
class SystemResult:
    """A solved (or failed) system.

    Attributes
    ----------
    status : Status
        ``"solved"`` when the net loads are within the scene's tolerance; else
        ``"failed"`` (``message`` says why) or ``"interrupted"``.
    message : str
        What happened.
    bodies : list of dict
        Per body: ``name``, ``position`` (m), ``rotation_deg`` (roll, pitch, yaw),
        ``mooring_force`` (N), ``mooring_moment`` (N m, about the reference point),
        ``line_loads`` (line name -> [F; M]), ``stiffness`` (see
        :func:`cable_ocp.mooring.stiffness.body_stiffness`; None when not solved).
    lines : list of dict
        Per line: :func:`line_row`.
    points : list of dict
        Per point: ``name``, ``kind``, ``position`` (m).
    solutions : dict
        Line name -> its :class:`StaticsSolution` (end_a at the line's lower end).
    iterations : int
        Newton steps.
    wall_time_s : float
        s.
    diagnostics : dict
        ``residual_history`` (scaled residual per step), counts, the tolerance,
        ``line_models`` (line name -> "catenary" or "collocation", the model of its
        last solve).
    """

    status: Status
    message: str
    bodies: list[dict[str, Any]]
    lines: list[dict[str, Any]]
    points: list[dict[str, Any]]
    solutions: dict[str, Any] = field(repr=False)
    iterations: int = 0
    wall_time_s: float = 0.0
    diagnostics: dict[str, Any] = field(default_factory=dict)
    state: Any = field(default=None, repr=False)

    def __setattr__(self, name: str, value: Any) -> None:
        object.__setattr__(self, name, Status(value) if name == "status" else value)

    @property
    def converged(self) -> bool:
        """True when the equilibrium was found."""
        return self.status == "solved"

    def body(self, name: str | None = None) -> dict[str, Any]:
        """One body's entry (the only one when ``name`` is None).

        Parameters
        ----------
        name : str, optional
            The body's name.
        """
        if name is None:
            return self.bodies[0]
        return next(b for b in self.bodies if b["name"] == name)

    def line(self, name: str) -> dict[str, Any]:
        """One line's entry.

        Parameters
        ----------
        name : str
            The line's name.
        """
        return next(ln for ln in self.lines if ln["name"] == name)

    def stiffness(self, body: str | None = None, which: str = "mooring") -> np.ndarray | None:
        """A body's 6x6 stiffness (N/m, N/rad, N m/m, N m/rad).

        Parameters
        ----------
        body : str, optional
            The body (the only one when None).
        which : str
            ``"mooring"``, ``"hydrostatic"``, ``"total"``, ``"elastic"`` or ``"geometric"``.
        """
        st = self.body(body)["stiffness"]
        return None if st is None else np.asarray(st[which])

    @property
    def max_tension(self) -> float:
        """The largest tension of any line, N."""
        return max((ln["max_tension"] for ln in self.lines), default=math.nan)

    @property
    def min_safety_factor(self) -> float | None:
        """The smallest safety factor of any line against its MBL (None: no MBL)."""
        vals = [ln["safety_factor"] for ln in self.lines if ln["safety_factor"] is not None]
        return min(vals) if vals else None

    def plot(self, ax: Any = None, **kwargs: Any) -> tuple[Any, Any]:
        """Draw the system (plan and 3D views, tension colour-coded).

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Draw the plan view on it; None: a new figure with both views.
        **kwargs
            Passed to :func:`cable_ocp.plots.system.system_figure`.
        """
        from cable_ocp.plots.accessors import plot_system_result

        return plot_system_result(self, ax, **kwargs)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (SI units; docs/systems.md, "Outputs")."""
        def body(b: dict[str, Any]) -> dict[str, Any]:
            out = {k: v for k, v in b.items() if k != "stiffness"}
            st = b["stiffness"]
            out["stiffness"] = None if st is None else {
                "definition": ("K = -d[F; M]/d[x; theta]: F, M the load on the body (M about "
                               "its reference point), theta small rotations about the fixed "
                               "axes; positive in surge for a stable mooring (MoorPy's sign)"),
                **{k: np.asarray(v).tolist() for k, v in st.items()}}
            return out

        return jsonable({"kind": "system", "status": str(self.status),
                         "message": self.message,
                         "bodies": [body(b) for b in self.bodies], "lines": self.lines,
                         "points": self.points, "iterations": self.iterations,
                         "wall_time_s": self.wall_time_s, "diagnostics": self.diagnostics})

    def __repr__(self) -> str:
        return (f"<SystemResult {self.status}: {self.message}; {len(self.lines)} lines, "
                f"{len(self.bodies)} bodies, max tension {self.max_tension:.6g} N>")


def _part_bounds(line: Any) -> list[tuple[str, float, float]]:
    """(type, s0, s1) of each part in the line scene's arc length (from its end_a)."""
    parts = tuple(reversed(line.parts)) if line.reversed else line.parts
    out, s = [], 0.0
    for name, length in parts:
        out.append((name, s, s + length))
        s += length
    return out


def line_row(scene: Any, line: Any, sol: Any, forces: tuple[np.ndarray, np.ndarray]
             ) -> dict[str, Any]:
    """One line's table row.

    Parameters
    ----------
    scene : SystemScene
        The system (line types, points).
    line : SystemLine
        The line.
    sol : StaticsSolution
        Its solution (the scene's orientation).
    forces : tuple
        The forces the line exerts on point_a and point_b, N.
    """
    fa, fb = forces
    tension = np.asarray(sol.tension)
    parts = []
    for name, s0, s1 in _part_bounds(line):
        inside = (sol.s >= s0 - 1e-9) & (sol.s <= s1 + 1e-9)
        tmax = float(np.max(tension[inside])) if inside.any() else math.nan
        mbl = scene.line_types[name].mbl
        parts.append({"type": name, "length": s1 - s0, "max_tension": tmax,
                      "safety_factor": None if mbl is None or not tmax > 0 else mbl / tmax})
    sfs = [p["safety_factor"] for p in parts if p["safety_factor"] is not None]
    row: dict[str, Any] = {
        "name": line.name, "point_a": line.point_a, "point_b": line.point_b,
        "length": line.length, "tension_a": float(np.linalg.norm(fa)),
        "tension_b": float(np.linalg.norm(fb)), "force_a": fa.tolist(), "force_b": fb.tolist(),
        "max_tension": float(np.max(tension)), "safety_factor": min(sfs) if sfs else None,
        "laid_length": float(sol.grounded_length), "parts": parts,
        "error_estimate": sol.error_estimate, "status": str(sol.status)}
    for key, pname, f in (("anchor_a", line.point_a, fa), ("anchor_b", line.point_b, fb)):
        if scene.point(pname).kind == "fixed":
            row[key] = {"point": pname, "horizontal": float(math.hypot(f[0], f[1])),
                        "vertical": float(f[2])}
    return row


def build_result(model: Any, ev: Any, status: str, message: str, iterations: int,
                 history: list[float], wall: float, stiffness: bool) -> SystemResult:
    """The :class:`SystemResult` of an evaluation.

    Parameters
    ----------
    model : SystemModel
        The model.
    ev : Evaluation
        The last evaluation (its state is the result's).
    status, message : str
        The outcome.
    iterations : int
        Newton steps taken.
    history : list of float
        Scaled residual per step.
    wall : float
        Wall time, s.
    stiffness : bool
        Compute each body's 6x6.
    """
    scene = model.scene
    state = ev.state
    lines, sols = [], {}
    if ev.ok:
        for line, sol, forces in zip(model.lines, ev.lines, ev.end_forces, strict=True):
            lines.append(line_row(scene, line, sol, forces))
            sols[line.name] = sol
    bodies = []
    for b in scene.bodies:
        pose = state.bodies[b.name]
        entry: dict[str, Any] = {"name": b.name, "position": pose[:3].tolist(),
                                 "rotation_deg": [math.degrees(a) for a in pose[3:]],
                                 "held": [d for d, h in zip(("x", "y", "z", "roll", "pitch",
                                                             "yaw"), b.held, strict=True)
                                          if h]}
        if ev.ok:
            load = ev.line_loads[b.name]
            entry["mooring_force"] = load[:3].tolist()
            entry["mooring_moment"] = load[3:].tolist()
            entry["line_loads"] = _line_loads(model, ev, b.name)
        entry["stiffness"] = (body_stiffness(model, ev, b.name)
                              if stiffness and ev.jac is not None else None)
        bodies.append(entry)
    points = [{"name": p.name, "kind": p.kind,
               "position": model.position(p.name, state).tolist()} for p in scene.points]
    diag = {"residual_history": history, "tolerance": scene.tolerance,
            "unknowns": int(model.free_dofs().size), "lines": len(model.lines),
            "formulation": "nested: Newton on the free points and bodies, each line the "
                           "closed-form catenary or the collocation BVP with exact end "
                           "Jacobians (docs/systems.md)",
            "line_models": {ln.name: model.line_models.get(ln.name, "collocation")
                            for ln in model.lines}}
    return SystemResult(status=Status(status), message=message, bodies=bodies, lines=lines,
                        points=points, solutions=sols, iterations=iterations,
                        wall_time_s=wall, diagnostics=diag, state=state.copy())


def _line_loads(model: Any, ev: Any, body: str) -> dict[str, list[float]]:
    """Per line, its [F; M] on ``body`` (N, N m about the reference point)."""
    out: dict[str, list[float]] = {}
    for line, (fa, fb) in zip(model.lines, ev.end_forces, strict=True):
        total = np.zeros(6)
        for pname, f in ((line.point_a, fa), (line.point_b, fb)):
            p = model.points[pname]
            if p.kind == "body" and p.body == body:
                arm = model.position(pname, ev.state) - ev.state.bodies[body][:3]
                total += np.concatenate([f, np.cross(arm, f)])
        if np.any(total):
            out[line.name] = total.tolist()
    return out
