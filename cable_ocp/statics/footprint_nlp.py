"""Footprint of a tethered subsea unit (Huang 1992, section 2.2.4, type 4, eqs (2.16)-(2.17)).

The unit (end_a) rests on the seabed and pushes with bounded thrust; the ship (end_b) is
fixed. For each direction theta, one NLP maximises the unit's horizontal distance from the
ship along theta,

    max  c1 = (r_a - r_b)_h . (cos theta, sin theta)
    s.t. (r_a - r_b)_h . (-sin theta, cos theta) = 0,     the collocated statics,
         |T_h| <= T_max  (or |T_x| <= T_xmax, |T_y| <= T_ymax; docs/conventions.md "Footprint"),
         L_min <= L <= L_max,  the cable above the seabed (z >= 0 at the nodes) and leaving
         the unit upwards (vertical force on the unit >= 0),

over the thrust components and the cable length (:class:`~cable_ocp.statics.optimize.
StaticsNLP`, built once with theta as a parameter). Each direction starts from its
neighbour's optimum. A direction with no feasible configuration is reported with the
optimiser's status (``"infeasible"``, or ``"max_iterations"`` at the iteration cap:
:func:`cable_ocp.status.from_ipopt`), never as a reach.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics.export import optional_module, summary_repr
from cable_ocp.scene import Scene
from cable_ocp.statics.optimize import OptimizationResult, StaticsNLP, View
from cable_ocp.statics.solver import solve


@dataclass
class FootprintResult:
    """Footprint polygon and per-direction diagnostics.

    Attributes
    ----------
    theta_deg : ndarray
        Directions, deg from +x towards +y.
    reach : ndarray
        Largest horizontal distance from the ship along each direction, m (NaN if failed).
    points : ndarray, shape (n, 2)
        Unit positions (x, y) at the optimum of each direction, m.
    thrust : ndarray, shape (n, 2)
        Thrust (Tx, Ty) at the optimum, N.
    length : ndarray
        Cable length at the optimum, m.
    status : list of str
        Per direction: ``"solved"`` or IPOPT's status.
    wall_time_s : float
        Total time, s.
    ship : ndarray, shape (2,)
        Horizontal position of the ship (end_b), m.
    """

    theta_deg: np.ndarray
    reach: np.ndarray
    points: np.ndarray
    thrust: np.ndarray
    length: np.ndarray
    status: list[str]
    wall_time_s: float
    ship: np.ndarray

    @property
    def summary_status(self) -> str:
        """``"solved"`` when every direction is, else how many are (``"70 of 72 directions
        solved"``)."""
        ok = sum(st == "solved" for st in self.status)
        return "solved" if ok == len(self.status) else (
            f"{ok} of {len(self.status)} directions solved")

    def __repr__(self) -> str:
        """A few lines: directions solved, the largest and smallest reach, the arrays."""
        fin = np.isfinite(self.reach)
        return summary_repr(
            "FootprintResult", self.summary_status, "",
            [("directions", len(self.theta_deg), ""),
             ("max_reach", float(np.max(self.reach[fin])) if fin.any() else None, "m"),
             ("min_reach", float(np.min(self.reach[fin])) if fin.any() else None, "m"),
             ("area", self.area(), "m^2"), ("wall_time_s", self.wall_time_s, "s")],
            {"theta_deg": self.theta_deg, "reach": self.reach, "points": self.points,
             "thrust": self.thrust, "length": self.length})

    def area(self) -> float | None:
        """Area of the polygon of the reached unit positions, m^2 (shoelace formula;
        None unless every direction was reached)."""
        p = np.asarray(self.points, dtype=float)
        if len(p) < 3 or not np.isfinite(p).all():
            return None
        x, y = p[:, 0], p[:, 1]
        return float(0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))

    def _columns(self) -> dict[str, tuple[np.ndarray, str]]:
        return {"reach": (self.reach, "m"), "x": (self.points[:, 0], "m"),
                "y": (self.points[:, 1], "m"), "thrust_x": (self.thrust[:, 0], "N"),
                "thrust_y": (self.thrust[:, 1], "N"), "length": (self.length, "m")}

    def to_pandas(self) -> Any:
        """The directions as a ``pandas.DataFrame`` (index ``theta [deg]``): ``reach [m]``,
        ``x [m]``, ``y [m]``, ``thrust_x [N]``, ``thrust_y [N]``, ``length [m]``,
        ``status``. Needs pandas (the extra ``[io]``)."""
        pd = optional_module("pandas", "FootprintResult.to_pandas()")
        cols = {f"{k} [{u}]": v for k, (v, u) in self._columns().items()}
        cols["status"] = [str(st) for st in self.status]
        return pd.DataFrame(cols, index=pd.Index(self.theta_deg, name="theta [deg]"))

    def to_xarray(self) -> Any:
        """The directions as an ``xarray.Dataset`` over the dimension ``theta`` (deg, from
        +x towards +y): ``reach``, ``x``, ``y``, ``length`` (m), ``thrust_x``,
        ``thrust_y`` (N), ``status``. Needs xarray (the extra ``[io]``)."""
        xr = optional_module("xarray", "FootprintResult.to_xarray()")
        data = {k: ("theta", v, {"units": u}) for k, (v, u) in self._columns().items()}
        data["status"] = ("theta", np.array([str(st) for st in self.status]))
        return xr.Dataset(data, coords={"theta": ("theta", self.theta_deg, {"units": "deg"})},
                          attrs={"kind": "footprint", "status": self.summary_status,
                                 "ship_xy_m": [float(v) for v in self.ship]})

    def plot(self, ax: Any = None, **kwargs: Any) -> tuple[Any, Any]:
        """Draw the footprint (matplotlib), MoorPy's habit: ``fig, ax = res.plot()``.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Draw the plan (the reached unit positions around the ship) on it; None
            (default): a new figure as ``cable-ocp footprint --plot``
            (:func:`cable_ocp.plots.statics_series.footprint_figure`).
        **kwargs
            ``title``, ``scene``.

        Returns
        -------
        (fig, ax)
            The figure and the Axes drawn on (with ``ax=None``: an array of its panels).
        """
        from cable_ocp.plots.accessors import plot_footprint_result

        return plot_footprint_result(self, ax, **kwargs)


def footprint(scene: Scene, directions: int = 72,
              progress: Callable[[int, int, dict[str, Any]], None] | None = None,
              max_iterations: int = 300) -> FootprintResult:
    """Compute the footprint of ``scene`` (which needs a ``[footprint]`` table).

    Parameters
    ----------
    scene : Scene
        A scene with a ``[footprint]`` table.
    directions : int
        Number of equally spaced directions (>= 3).
    progress : callable, optional
        Called after each direction as ``progress(done, total, row)`` with that direction's
        result (``theta_deg``, ``reach``, ``x``, ``y`` in m, ``thrust_x``, ``thrust_y`` in N,
        ``length`` in m, ``status``).
    max_iterations : int
        IPOPT's iteration cap per direction (``ipopt.max_iter``): a direction the unit
        cannot reach ends as IPOPT's infeasibility or this cap, whichever comes first.
    """
    fp = scene.footprint
    if fp is None:
        raise CableOCPError("the scene has no [footprint] table (max_length, thrust limits)")
    if directions < 3:
        raise CableOCPError(f"--directions {directions}: need at least 3")
    t0 = time.perf_counter()
    if fp.bound == "magnitude":
        tx = ty = fp.thrust_max
    else:
        tx, ty = fp.thrust_x_max, fp.thrust_y_max
    length0 = min(max(scene.cable.length or fp.max_length, fp.min_length), fp.max_length)
    scene = scene.with_overrides({"cable.length": length0, "solver.error_estimate": False})
    nlp = StaticsNLP(scene, {"end_a.force.x": (-tx, tx), "end_a.force.y": (-ty, ty),
                             "cable.length": (fp.min_length, fp.max_length)})
    ship = np.asarray(scene.end_b.position[:2], dtype=float)
    ell = fp.max_length
    sb = scene.environment.seabed
    floor = sb.depth_offset if sb is not None else 0.0

    def horiz(v: View) -> ca.MX:
        return v.position[0, 0:2].T - ca.DM(ship)

    def objective(v: View) -> ca.MX:
        d = ca.vertcat(ca.cos(v.theta[0]), ca.sin(v.theta[0]))
        return -ca.dot(horiz(v), d) / ell

    def constraints(v: View) -> list:
        n = ca.vertcat(-ca.sin(v.theta[0]), ca.cos(v.theta[0]))
        cons = [(ca.dot(horiz(v), n) / ell, 0.0, 0.0),
                (v.position[:, 2] - floor, 0.0, np.inf),
                (v.force_a[2] / (abs(scene.cable.weight_in_water) * ell), 0.0, np.inf)]
        if fp.bound == "magnitude" and fp.thrust_max > 0:
            fx, fy = v.var["end_a.force.x"], v.var["end_a.force.y"]
            cons.append(((fx * fx + fy * fy) / fp.thrust_max**2, -np.inf, 1.0))
        return cons

    nlp.build(objective, constraints, n_theta=1, max_iter=max_iterations)
    thetas = np.linspace(0.0, 360.0, directions, endpoint=False)
    reach = np.full(directions, np.nan)
    points = np.full((directions, 2), np.nan)
    thrust = np.full((directions, 2), np.nan)
    lengths = np.full(directions, np.nan)
    status: list[str] = []
    prev: OptimizationResult | None = None
    def fresh_start(rad: float) -> tuple:
        """A statics solve with the full thrust pointing along the direction and the
        shortest cable, so that the NLP starts on the near side of the ship, with the
        cable leaving the unit upwards (from the far side IPOPT can stop at a spurious
        stationary point with a negative reach)."""
        f = np.array([tx * np.cos(rad), ty * np.sin(rad)])
        sc = scene.with_overrides({"end_a.force": [float(f[0]), float(f[1]), "free"],
                                   "cable.length": fp.min_length})
        sol = solve(sc)
        vals = {"end_a.force.x": f[0], "end_a.force.y": f[1], "cable.length": fp.min_length}
        return (sol if sol.success else None), vals

    def reach_of(res: OptimizationResult, rad: float) -> float:
        r = res.solution.position[0, :2]
        return float((r - ship) @ [np.cos(rad), np.sin(rad)]) if res.success else -np.inf

    for k, th in enumerate(thetas):
        rad = np.radians(th)
        if prev is None:
            start, vals = fresh_start(rad)
            res = nlp.run([rad], start=start, start_values=vals)
        else:
            res = nlp.run([rad], start=prev.solution, start_values=prev.variables)
        if not res.success or reach_of(res, rad) < 0:  # retry from a fresh start
            start, vals = fresh_start(rad)
            alt = nlp.run([rad], start=start, start_values=vals)
            if reach_of(alt, rad) > reach_of(res, rad):
                res = alt
        status.append(res.status)
        if res.success:
            r = res.solution.position[0, :2]
            points[k] = r
            reach[k] = float((r - ship) @ [np.cos(rad), np.sin(rad)])
            thrust[k] = [res.variables["end_a.force.x"], res.variables["end_a.force.y"]]
            lengths[k] = res.variables["cable.length"]
            prev = res
        if progress is not None:
            progress(k + 1, directions, {
                "theta_deg": float(th), "reach": reach[k], "x": points[k, 0], "y": points[k, 1],
                "thrust_x": thrust[k, 0], "thrust_y": thrust[k, 1], "length": lengths[k],
                "status": res.status})
    return FootprintResult(theta_deg=thetas, reach=reach, points=points, thrust=thrust,
                           length=lengths, status=status, wall_time_s=time.perf_counter() - t0,
                           ship=ship)
