"""The result of a statics solve: numpy arrays plus diagnostics (never a bare exception).

Every statics method returns a :class:`StaticsSolution`; ``status`` says whether it may be
used. A failed solve keeps its last iterate for inspection but ``success`` is False and
the CLI exits non-zero.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics.export import optional_module, summary_repr
from cable_ocp.status import Status

#: statuses whose iterate solves the discretised equations (see :attr:`StaticsSolution.converged`)
CONVERGED = ("solved", "inaccurate", "below_seabed", "above_surface")


@dataclass
class StaticsSolution:
    """Static equilibrium of a cable.

    Attributes
    ----------
    status : Status
        ``"solved"`` or a failure code (``"failed"``, ``"max_iterations"``, ...), a member
        of :class:`cable_ocp.status.Status` (a string; setting any other raises
        ``ValueError``).
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

    status: Status
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
    #: computes the end stiffness on first use (set by the collocation/shooting solver)
    _stiffness_source: Callable[[], dict[str, dict[str, Any]]] | None = field(
        default=None, repr=False, compare=False)
    _stiffness_cache: dict[str, dict[str, Any]] | None = field(
        default=None, repr=False, compare=False)
    #: computes the 6x6 end Jacobian on demand (both ends fixed; see :meth:`end_jacobian`)
    _jacobian_source: Callable[[], np.ndarray] | None = field(default=None, repr=False,
                                                              compare=False)
    #: computes the length sensitivities on demand (see :meth:`length_sensitivity`)
    _length_source: Callable[[], dict[str, Any]] | None = field(default=None, repr=False,
                                                                compare=False)
    #: (solver token, scaled unknowns): lets the solver that produced this solution
    #: warm-start from its own unknowns without interpolating the node arrays
    _unknowns: tuple[object, np.ndarray] | None = field(default=None, repr=False,
                                                         compare=False)

    def __setattr__(self, name: str, value: Any) -> None:
        # the status is one of the package's vocabulary (cable_ocp.status), however set
        object.__setattr__(self, name, Status(value) if name == "status" else value)

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

    def end_tension(self, end: str) -> float:
        """Tension magnitude at ``end`` ("a" or "b"), N: the magnitude of the end force."""
        return float(np.linalg.norm(self.tension_vector[_end_index(end)]))

    def end_tangent(self, end: str) -> np.ndarray:
        """Unit tangent dr/ds of the cable at ``end`` ("a" or "b"), pointing towards
        increasing s (from end_a towards end_b along the cable), (3,).

        T/|T| on a flexible cable; from the bending angle where the end segment has bending
        stiffness (T carries shear there); along the first distinct nodes where the
        tension vanishes (a slack grounded part at an anchor)."""
        i = _end_index(end)
        stiff = (self.diagnostics.get("end_tangents") or {}).get(end)
        if stiff is not None:
            return np.asarray(stiff, dtype=float)
        t = self.tension_vector[i]
        tmag = float(np.linalg.norm(t))
        if tmag > 1e-12 * max(self.max_tension, 1e-300):
            return t / tmag
        r = self.position
        others = r[1:] if end == "a" else r[-2::-1]
        step = others - r[i]
        dist = np.linalg.norm(step, axis=1)
        k = int(np.argmax(dist > 0)) if np.any(dist > 0) else 0
        if dist[k] == 0.0:
            return np.full(3, math.nan)
        d = step[k] / dist[k]
        return d if end == "a" else -d

    def angle_to_horizontal_deg(self, end: str) -> float:
        """Angle of the cable at ``end`` ("a" or "b") to the horizontal, deg.

        The elevation of the tangent :meth:`end_tangent` (pointing from end_a towards end_b
        along the cable) above the horizontal plane, measured from the horizontal
        direction of the chord end_a -> end_b: in [-90, 90] when the tangent's horizontal
        part points along that direction (or is zero), 180 deg minus the elevation when it
        points back, i.e. above 90 deg where the cable leans back past vertical and below
        -90 deg where it descends backwards. This is phi of Wang, Cheong &
        Chucheepsakul (1993), Table 1 (36.3 deg at Berteaux's anchor, 90.2 deg at the
        buoy). Negative where the cable descends from end_a or arrives at end_b from
        above. With a vertical chord the elevation itself, in [-90, 90].
        """
        t = self.end_tangent(end)
        if not np.all(np.isfinite(t)):
            return math.nan
        horiz = math.hypot(t[0], t[1])
        chord = self.position[-1] - self.position[0]
        along = t[0] * chord[0] + t[1] * chord[1]
        if along < 0.0 and math.hypot(chord[0], chord[1]) > 1e-12 * np.linalg.norm(chord):
            horiz = -horiz
        return math.degrees(math.atan2(t[2], horiz))

    def _stiffness(self) -> dict[str, dict[str, Any]]:
        """Stiffness at both ends (computed once, see :meth:`stiffness`)."""
        if not self.converged:
            note = f"not computed: the solve did not converge (status {self.status})"
            return {k: {"matrix": None, "note": note} for k in ("a", "b")}
        if self._stiffness_source is None:
            method = self.diagnostics.get("method", "this method")
            note = (f"not available for method {method}: the stiffness comes from the "
                    "sensitivities of the collocation and multiple-shooting solvers")
            return {k: {"matrix": None, "note": note} for k in ("a", "b")}
        if self._stiffness_cache is None:
            self._stiffness_cache = self._stiffness_source()
        return self._stiffness_cache

    def stiffness(self, end: str) -> np.ndarray | None:
        """The line's stiffness at ``end`` ("a" or "b"), N/m: K[i, j] = dF_i/dx_j.

        F is the force the cable exerts on that end's attachment (:attr:`force_a`,
        :attr:`force_b`) and x that end's position, the other end held as the scene says
        and the unstretched length held. A restoring line has a negative diagonal: moving
        a fairlead away from the anchor (+x) makes its force, which points back towards
        the anchor, more negative in x. MoorPy's end stiffness matrices are -K.

        Exact for the discretised equations (implicit-function theorem on the solver's
        equations, :meth:`StaticsSolver.end_stiffness`). NaN entries where a derivative
        does not exist (the z column at an anchor with the cable grounded on a flat
        seabed). None when not available: an end that is not fully fixed, a baseline
        method, a failed solve; :meth:`stiffness_note` says why.
        """
        mat = self._stiffness()[_end_key(end)]["matrix"]
        if mat is None:
            return None
        return np.array([[math.nan if v is None else v for v in row] for row in mat])

    def end_jacobian(self) -> np.ndarray:
        """dF/dx (6x6, N/m) of a line with both ends fixed: F = (force_a, force_b), the
        forces on the two attachments, x = (x_a, x_b) the end positions, the unstretched
        length held; the coupling blocks dF_a/dx_b and dF_b/dx_a included. The z_a column
        is NaN when the line is grounded at end_a (:meth:`stiffness`). Exact for the
        discretised equations (:meth:`StaticsSolver.end_jacobian`).

        Raises
        ------
        CableOCPError
            When the solve did not converge, the method has no sensitivities, or an end is
            not fixed.
        """
        return self._from_sensitivities(self._jacobian_source, "end Jacobian")

    def _from_sensitivities(self, source: Callable[[], Any] | None, what: str) -> Any:
        """``source()``, the solver's sensitivities at this solution; raise naming ``what``
        when the solve did not converge or the method has none."""
        if not self.converged:
            raise CableOCPError(f"no {what}: the solve did not converge (status "
                                f"{self.status})")
        if source is None:
            raise CableOCPError(f"no {what}: it comes from the sensitivities of the "
                                "collocation and multiple-shooting solvers")
        return source()

    def length_sensitivity(self) -> dict[str, Any]:
        """Sensitivities of a line with both ends fixed to its unstretched length L and
        its end positions x = (x_a, x_b), from one factorisation (exact for the
        discretised equations, :meth:`StaticsSolver.length_sensitivity`): ``force`` dF/dL
        (6,), N/m, F = (force_a, force_b); ``end_jacobian`` dF/dx (6x6), N/m
        (:meth:`end_jacobian`); ``grounded_length`` dg/dL (-) and ``grounded_length_ends``
        dg/dx (6,) (-), g the grounded length at end_a. The z_a entries are NaN when the
        line is grounded at end_a. On a multi-segment line L scales every segment (their
        shares held).

        Raises
        ------
        CableOCPError
            When the solve did not converge, the method has no sensitivities, an end is
            not fixed or the length is an unknown.
        """
        return self._from_sensitivities(self._length_source, "length sensitivity")

    def stiffness_note(self, end: str) -> str:
        """What :meth:`stiffness` holds fixed at ``end``, or why it is None."""
        return str(self._stiffness()[_end_key(end)]["note"])

    def _end_dict(self, end: str) -> dict[str, Any]:
        """JSON-ready results at one end (see :meth:`to_dict`)."""
        i = _end_index(end)
        force = self.force_a if end == "a" else self.force_b
        st = self._stiffness()[end]
        return {
            "position": [_num(v) for v in self.position[i]],
            "force": [_num(v) for v in force],
            "tension_N": _num(self.end_tension(end)),
            "angle_to_horizontal_deg": _num(self.angle_to_horizontal_deg(end)),
            "stiffness_N_per_m": st["matrix"],
            "stiffness_note": st["note"],
        }

    def __repr__(self) -> str:
        """A few lines: status, length, tensions, solver numbers and the arrays' shapes."""
        finite = bool(np.isfinite(self.tension_vector).all()) and len(self.s) > 0
        ends = [("tension_a", self.end_tension("a"), "N"),
                ("tension_b", self.end_tension("b"), "N")] if finite else []
        return summary_repr(
            "StaticsSolution", self.status, self.message,
            [("length", self.length, "m"),
             ("max_tension", self.max_tension if finite else None, "N"), *ends,
             ("grounded_length", self.grounded_length, "m"),
             ("method", self.diagnostics.get("method", "-"), ""),
             ("iterations", self.iterations, ""), ("error_estimate", self.error_estimate, ""),
             ("wall_time_s", self.wall_time_s, "s")],
            {"s": self.s, "position": self.position, "tension_vector": self.tension_vector})

    def _unique(self) -> np.ndarray:
        """The nodes listed once (Radau's last collocation point is the next interval's
        start): a mask over the nodes."""
        return np.concatenate([[True], np.diff(self.s) > 0])

    def to_xarray(self) -> Any:
        """The profile as an ``xarray.Dataset`` over the unstretched arc length ``s`` (m,
        from end_a), each node once: ``position`` (s, xyz; m), ``tension_vector`` (s,
        xyz; N), ``tension`` (s; N); the status, message and length as attributes. Needs
        xarray (the extra ``[io]``)."""
        xr = optional_module("xarray", "StaticsSolution.to_xarray()")
        keep = self._unique()
        return xr.Dataset(
            {"position": (("s", "xyz"), self.position[keep], {"units": "m"}),
             "tension_vector": (("s", "xyz"), self.tension_vector[keep], {"units": "N"}),
             "tension": ("s", self.tension[keep], {"units": "N"})},
            coords={"s": ("s", self.s[keep], {"units": "m",
                                              "long_name": "unstretched arc length from end_a"}),
                    "xyz": ["x", "y", "z"]},
            attrs={"kind": "statics", "status": str(self.status), "message": self.message,
                   "length_m": float(self.length),
                   "method": str(self.diagnostics.get("method", "")),
                   "conventions": "z up; s = 0 at end_a"})

    def to_pandas(self) -> Any:
        """The profile as a ``pandas.DataFrame``, one row per node (each once): ``s [m]``,
        ``x [m]``, ``y [m]``, ``z [m]``, ``tension [N]``, ``tension_x [N]``, ... Needs
        pandas (the extra ``[io]``)."""
        pd = optional_module("pandas", "StaticsSolution.to_pandas()")
        keep = self._unique()
        cols = {"s [m]": self.s[keep]}
        cols.update({f"{c} [m]": self.position[keep, i] for i, c in enumerate("xyz")})
        cols["tension [N]"] = self.tension[keep]
        cols.update({f"tension_{c} [N]": self.tension_vector[keep, i]
                     for i, c in enumerate("xyz")})
        return pd.DataFrame(cols)

    def plot(self, ax: Any = None, **kwargs: Any) -> tuple[Any, Any]:
        """Draw the solution (matplotlib), MoorPy's habit: ``fig, ax = sol.plot()``.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Draw the elevation (horizontal distance along the line's plane against z) on
            it; None (default): a new figure with every panel of ``cable-ocp solve
            --plot`` (:func:`cable_ocp.plots.statics.statics_figure`).
        **kwargs
            ``title``, ``scene`` (the solved scene: seabed, surface, current, bodies).

        Returns
        -------
        (fig, ax)
            The figure and the Axes drawn on (with ``ax=None``: an array of its panels).
        """
        from cable_ocp.plots.accessors import plot_statics_result

        return plot_statics_result(self, ax, **kwargs)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (SI units; see docs/statics.md, "Outputs", for the fields).

        Strict-JSON-ready: a number that does not exist is None (null), never NaN.
        """
        def lst(a: np.ndarray) -> list[float | None]:
            return [_num(v) for v in a]

        est = self.diagnostics.get("error_estimate_detail", {})
        keep = self._unique()
        out = {
            "status": self.status,
            "message": self.message,
            "length": _num(self.length),
            "end_a": self._end_dict("a"),
            "end_b": self._end_dict("b"),
            "max_tension": _num(self.max_tension),
            "grounded_length": self.grounded_length,
            "touchdown": self.diagnostics.get("touchdown"),
            "profile": {
                "s": lst(self.s[keep]),
                "x": lst(self.position[keep, 0]),
                "y": lst(self.position[keep, 1]),
                "z": lst(self.position[keep, 2]),
                "tension": lst(self.tension[keep]),
                "tension_x": lst(self.tension_vector[keep, 0]),
                "tension_y": lst(self.tension_vector[keep, 1]),
                "tension_z": lst(self.tension_vector[keep, 2]),
            },
            "warnings": list(self.diagnostics.get("warnings", [])),
            "solver": {
                "method": self.diagnostics.get("method"),
                "intervals": (self.diagnostics.get("mesh") or {}).get("intervals"),
                "degree": (self.diagnostics.get("mesh") or {}).get("degree"),
                "refinements": self.diagnostics.get("refinement", []),
                "iterations": int(self.iterations),
                "wall_time_s": _num(self.wall_time_s),
                "constraint_violation": _num(self.constraint_violation),
                "error_estimate": self.error_estimate,
                "error_estimate_force_N": est.get("force_N"),
                "error_estimate_position_m": est.get("position_m"),
                "smoothing_force_bound_N": self.diagnostics.get("smoothing_force_bound_N"),
                "continuation": self.diagnostics.get("continuation"),
                "mesh": _mesh_dict(self.diagnostics.get("mesh")),
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


def _mesh_dict(mesh: dict[str, Any] | None) -> dict[str, Any] | None:
    """The mesh's JSON entry: its kind ("uniform", or "kinks": mesh points on the kinks
    of the drag), the interval ends ``points_s`` (m; null on a uniform mesh) and the kinks
    this solve found ``kinks_s`` (m; null when it did not look); null without a mesh."""
    if not mesh or "kind" not in mesh:
        return None
    return {"kind": mesh["kind"], "points_s": mesh.get("points_s"),
            "kinks_s": mesh.get("kinks_s")}


def _num(v: Any) -> float | None:
    """A float for JSON, None for NaN or infinity."""
    v = float(v)
    return v if math.isfinite(v) else None


def _end_key(end: str) -> str:
    if end not in ("a", "b"):
        raise ValueError(f"end = {end!r}: give 'a' (end_a) or 'b' (end_b)")
    return end


def _end_index(end: str) -> int:
    return 0 if _end_key(end) == "a" else -1
