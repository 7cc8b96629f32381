"""The result of a statics solve: numpy arrays plus diagnostics (never a bare exception).

Every statics method returns a :class:`StaticsSolution`; ``status`` says whether it may be
used. A failed solve keeps its last iterate for inspection but ``success`` is False and
the CLI exits non-zero.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

#: statuses whose iterate solves the discretised equations (see :attr:`StaticsSolution.converged`)
CONVERGED = ("solved", "inaccurate", "below_seabed", "above_surface")


@dataclass
class StaticsSolution:
    """Static equilibrium of a cable.

    Attributes
    ----------
    status : str
        ``"solved"`` or a failure code (``"failed"``, ``"max_iterations"``, ...).
    message : str
        Human-readable detail of the status.
    s : ndarray, shape (n,)
        Unstretched arc length of the nodes, m, increasing from end_a (0) to end_b (L).
    position : ndarray, shape (n, 3)
        Node positions, m.
    tension_vector : ndarray, shape (n, 3)
        Tension vector T(s), N: the force the cable beyond s exerts on the cable before s.
    length : float
        Unstretched cable length L, m.
    iterations : int
        Nonlinear iterations (Newton or IPOPT) in the final solve.
    wall_time_s : float
        Wall-clock time of the solve, s (excluding the error estimate and any build).
    constraint_violation : float
        Largest absolute residual of the discretised equations, scaled units (-).
    error_estimate : float or None
        Estimated relative discretisation error (-): the larger of the end-force error
        over the largest tension and the position error over the length.
    diagnostics : dict
        Everything else: solver used, continuation steps, smoothing bound, mesh, ...
    """

    status: str
    message: str
    s: np.ndarray
    position: np.ndarray
    tension_vector: np.ndarray
    length: float
    iterations: int = 0
    wall_time_s: float = 0.0
    constraint_violation: float = math.nan
    error_estimate: float | None = None
    diagnostics: dict[str, Any] = field(default_factory=dict)
    node_offset: int = 0  # nodes of an analytic grounded part before the computed ones

    @property
    def grounded_length(self) -> float:
        """Unstretched length lying on the seabed at end_a, m (0 without contact)."""
        return float(self.s[self.node_offset]) if self.node_offset else 0.0

    @property
    def success(self) -> bool:
        """True when the solve converged and the result may be used."""
        return self.status == "solved"

    @property
    def converged(self) -> bool:
        """True when the discretised equations were solved, whether or not the result is a
        success (``"inaccurate"``, or a profile that leaves the water column): such a
        result is a valid warm start for a neighbouring solve."""
        return self.status in CONVERGED

    @property
    def tension(self) -> np.ndarray:
        """Tension magnitude |T(s)| at the nodes, N."""
        return np.linalg.norm(self.tension_vector, axis=1)

    @property
    def max_tension(self) -> float:
        """Largest tension magnitude over the nodes, N."""
        return float(self.tension.max())

    @property
    def force_a(self) -> np.ndarray:
        """Force the cable exerts on the end_a attachment, N (= +T(0))."""
        return self.tension_vector[0].copy()

    @property
    def force_b(self) -> np.ndarray:
        """Force the cable exerts on the end_b attachment, N (= -T(L))."""
        return -self.tension_vector[-1]

    def angle_to_horizontal_deg(self, end: str) -> float:
        """Angle of the cable tangent above the horizontal at ``end`` ("a" or "b"), deg."""
        t = self.tension_vector[0 if end == "a" else -1]
        return math.degrees(math.atan2(t[2], math.hypot(t[0], t[1])))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (SI units; see the README for the fields)."""
        def lst(a: np.ndarray) -> list[float]:
            return [float(v) for v in a]

        est = self.diagnostics.get("error_estimate_detail", {})
        # Radau's last collocation point is the next interval's start: list it once
        keep = np.concatenate([[True], np.diff(self.s) > 0])
        out = {
            "status": self.status,
            "message": self.message,
            "length": float(self.length),
            "end_a": {"position": lst(self.position[0]), "force": lst(self.force_a)},
            "end_b": {"position": lst(self.position[-1]), "force": lst(self.force_b)},
            "max_tension": self.max_tension,
            "touchdown": self.diagnostics.get("touchdown"),
            "profile": {
                "s": lst(self.s[keep]),
                "x": lst(self.position[keep, 0]),
                "y": lst(self.position[keep, 1]),
                "z": lst(self.position[keep, 2]),
                "tension": lst(self.tension[keep]),
            },
            "warnings": list(self.diagnostics.get("warnings", [])),
            "solver": {
                "method": self.diagnostics.get("method"),
                "intervals": (self.diagnostics.get("mesh") or {}).get("intervals"),
                "degree": (self.diagnostics.get("mesh") or {}).get("degree"),
                "refinements": self.diagnostics.get("refinement", []),
                "iterations": int(self.iterations),
                "wall_time_s": float(self.wall_time_s),
                "constraint_violation": float(self.constraint_violation),
                "error_estimate": self.error_estimate,
                "error_estimate_force_N": est.get("force_N"),
                "error_estimate_position_m": est.get("position_m"),
                "smoothing_force_bound_N": self.diagnostics.get("smoothing_force_bound_N"),
                "continuation": self.diagnostics.get("continuation"),
            },
        }
        if "bending" in self.diagnostics:
            # segments with bending stiffness: tangent angle from +x towards +z (rad) and
            # bending moment (N m) per node, 0 on flexible segments
            for key in ("angle_rad", "moment_Nm"):
                vals = np.asarray(self.diagnostics["bending"][key])
                out["profile"][f"bending_{key}"] = lst(vals[keep])
        if "bodies" in self.diagnostics:
            # point bodies at joints (multi-segment lines): joint, kind, position (m) and
            # the body's total external load (N), after the touchdown entry
            keys = list(out)
            items = [(k, out[k]) for k in keys[: keys.index("touchdown") + 1]]
            items.append(("bodies", self.diagnostics["bodies"]))
            items += [(k, out[k]) for k in keys[keys.index("touchdown") + 1:]]
            out = dict(items)
        return out
