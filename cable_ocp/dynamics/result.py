"""Results of the dynamics: time histories, modes and the deployment chart.

Every model returns these types. A numerical failure comes back as a result whose
``status`` is not ``"solved"`` (with what was computed up to the failure and diagnostics),
never as an exception. ``to_dict()`` gives strict JSON (no NaN or infinity: ``null``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from cable_ocp.numerics.export import optional_module, summary_repr
from cable_ocp.numerics.jsonable import json_safe
from cable_ocp.status import Status

__all__ = ["DeploymentChart", "ModesResult", "SimulationResult", "coarse_step_warnings",
           "full_speed_start_warnings", "json_safe", "slack_element", "slack_report",
           "until_slack"]


#: what the slack message says when ``simulation.on_slack = "stop"``
SLACK_STOPPED = "the run stopped there"


def until_slack(t: np.ndarray, first_time: float | None, sample_step: float,
                on_slack: str) -> np.ndarray | None:
    """The samples a run keeps when it stops at slack: those up to the first sample at or
    after the first slack time (boolean mask over ``t``), or None when nothing is cut (no
    slack, or ``on_slack = "continue"``). A slack time on the sample grid (the end of a
    step that ends a sample interval) keeps the sample at that time and none after it,
    whatever samples the run computed beyond (the axial and planar loops stop after the
    chunk of samples in which slack occurred; the lumped-mass run does not stop).

    Parameters
    ----------
    t : ndarray (n,)
        Sample times, s.
    first_time : float or None
        End time of the first step with slack, s (None or inf: none).
    sample_step : float
        The output interval, s.
    on_slack : {"stop", "continue"}
        ``simulation.on_slack``.
    """
    if on_slack != "stop" or first_time is None or not math.isfinite(first_time):
        return None
    # the first sample at or after first_time: below first_time + sample_step, by a
    # margin of 1e-9 of the step against the rounding of the two grids (k dt, t + dt)
    return t < first_time + sample_step * (1.0 - 1e-9)


def slack_element(first_time: float, element: float, t: np.ndarray, length: np.ndarray,
                  elements: int) -> tuple[int | None, float | None]:
    """``(segment, location)`` for :func:`slack_report` from a run of ``elements`` equal
    elements: the first slack element (its recorded index rounded) and its middle's
    unstretched arc length from end_a when slack occurred, (e + 1/2) L(first_time) / N
    with L interpolated in the samples; ``(None, None)`` otherwise.

    Parameters
    ----------
    first_time : float
        End time of the first step with slack, s (inf: none).
    element : float
        The first slack element's index as recorded (a float of the accumulator).
    t : ndarray (n,)
        Sample times, s.
    length : ndarray (n,)
        Unstretched length at the samples, m.
    elements : int
        Number of elements N.
    """
    e = int(round(element)) if np.isfinite(first_time) else None
    if e is None:
        return None, None
    return e, (e + 0.5) * float(np.interp(first_time, t, length)) / elements


def slack_report(first_time: float | None, segment: int | None, location: float | None, *,
                 status: str, message: str, on_slack: str, template: str,
                 continued: str = "", **fields: Any) -> tuple[dict[str, Any], str, str]:
    """The ``slack`` entry of a :class:`SimulationResult` and the status and message it
    implies, for every model.

    A run that went slack and otherwise succeeded gets the status ``"slack"`` and the
    model's message ``template`` formatted with ``t`` (the first slack time, s),
    ``segment``, ``location`` (m from end_a), ``action`` (:data:`SLACK_STOPPED` where
    ``on_slack = "stop"``, else ``continued``: what the model does with a slack line) and
    any further ``fields``; a failed run keeps its status and message.

    Parameters
    ----------
    first_time : float or None
        End time of the first step with slack, s (None or inf: no slack).
    segment : int or None
        The first slack element or segment from end_a.
    location : float or None
        Its middle's unstretched arc length from end_a, m.
    status, message : str
        The run's status and message so far.
    on_slack : {"stop", "continue"}
        ``simulation.on_slack``.
    template : str
        The model's slack message (``str.format`` fields as above).
    continued : str
        The model's words for a run that continues through slack.
    **fields
        Further fields of ``template``.

    Returns
    -------
    (slack, status, message)
        ``slack``: ``occurred``, ``first_time`` (s), ``location`` (m), ``segment``.
    """
    occurred = first_time is not None and math.isfinite(first_time)
    slack: dict[str, Any] = {"occurred": bool(occurred), "first_time": None,
                             "location": None, "segment": None}
    if not occurred:
        return slack, status, message
    slack.update(first_time=first_time, segment=segment, location=location)
    if status == "solved":
        status = "slack"
        action = SLACK_STOPPED if on_slack == "stop" else continued
        message = template.format(t=first_time, segment=segment, location=location,
                                  action=action, **fields)
    return slack, status, message


def coarse_step_warnings(time_step: float, frequencies: Sequence[tuple[str, float]]
                         ) -> list[str]:
    """The warnings of a time step that gives fewer than 20 steps per period of a top
    motion, for every model.

    Parameters
    ----------
    time_step : float
        ``simulation.time_step``, s.
    frequencies : sequence of (str, float)
        ``(name, omega)``: the key of each ``top_motion`` frequency the model follows and
        its value, rad/s (0: that motion is off).
    """
    return [f"simulation.time_step = {time_step} s gives fewer than 20 steps per period of "
            f"top_motion.{name} = {w} rad/s"
            for name, w in frequencies if w > 0.0 and w * time_step > 2.0 * math.pi / 20.0]


def full_speed_start_warnings(jump: float, mass_per_length: float, axial_stiffness: float,
                              static_top_tension: float) -> list[str]:
    """The warning of a top that starts at full speed (``top_motion.ramp_time = 0``): a
    velocity jump dv sends a tension step mu c dv down the line (c = sqrt(EA / mu), the
    axial wave speed); said when it is above 10 % of the static top tension.

    Parameters
    ----------
    jump : float
        The top's speed at t = 0+, m/s.
    mass_per_length : float
        mu, the line's mass per length with its tangential added mass, kg/m.
    axial_stiffness : float
        EA, N.
    static_top_tension : float
        The static top tension the step is compared with, N.
    """
    step = mass_per_length * math.sqrt(axial_stiffness / mass_per_length) * jump
    if not step > 0.1 * static_top_tension:
        return []
    return [f"the top starts at full speed ({jump:.3g} m/s at t = 0): a tension step of about "
            f"{step:.3g} N (mu c dv) runs down the line, {step / static_top_tension:.0%} of the "
            "static top tension; set top_motion.ramp_time for a smooth start"]


class _StatusVocabulary:
    """The results' common base: ``status`` is made a :class:`cable_ocp.status.Status`
    when a result is built (a status outside the vocabulary raises ``ValueError``)."""

    def __post_init__(self) -> None:
        # the status is one of the package's vocabulary (cable_ocp.status)
        object.__setattr__(self, "status", Status(self.status))


@dataclass(frozen=True)
class SimulationResult(_StatusVocabulary):
    """Time history of a dynamics simulation.

    Attributes
    ----------
    t : ndarray, shape (n_t,)
        Sample times, s.
    length : ndarray, shape (n_t,)
        Unstretched paid-out length, m.
    top_position : ndarray, shape (n_t, 3)
        Position of end_b (the ship's attachment), m.
    unit_position : ndarray, shape (n_t, 3)
        Position of end_a (the unit, or the anchor), m.
    top_tension : ndarray, shape (n_t,)
        Tension at end_b, N.
    node_positions : ndarray, shape (n_t, n_nodes, 3)
        Node positions from end_a to end_b, m.
    segment_tensions : ndarray, shape (n_t, n_nodes - 1)
        Tension in each element from end_a to end_b, N (negative = compression of a model
        that cannot go slack).
    min_tension : float
        Smallest element tension over the run, N.
    slack : dict
        ``occurred`` (bool), ``first_time`` (s or None), ``location`` (unstretched arc
        length from end_a of the middle of the first slack element, m, or None),
        ``segment`` (its index from end_a or None).
    status : Status
        ``"solved"``; ``"slack"`` (a tension <= 0 occurred: the model cannot follow
        slack, Huang (1992) 4.5.1); ``"failed"`` (an implicit step did not converge: the
        history stops at the last good sample); ``"interrupted"``.
    message : str
        Human-readable detail of the status.
    warnings : list of str
        Things the user should know (e.g. a coarse time step).
    wall_time_s : float
        Wall-clock time of the time integration, s (without building the model).
    model : str
        ``"axial"``, ``"planar"`` or ``"lumped3d"``.
    scheme : str
        The time-integration scheme.
    diagnostics : dict
        Everything else: build time, steps, Newton residuals, the static start, ...
    node_velocities : ndarray, shape (n_t, n_nodes, 3), or None
        Material velocities of the nodes, m/s (None when a model does not provide them).
    snap : dict
        The largest snap load, the peak tension that ends a slack spell
        (:func:`cable_ocp.dynamics.snap.snap_report`): ``occurred``, ``count``,
        ``peak_tension`` (N), ``time`` (s), ``segment``, ``location`` (m from end_a),
        ``slack_from``, ``taut_at`` (s); empty for a model that does not follow slack.
    """

    t: np.ndarray
    length: np.ndarray
    top_position: np.ndarray
    unit_position: np.ndarray
    top_tension: np.ndarray
    node_positions: np.ndarray
    segment_tensions: np.ndarray
    min_tension: float
    slack: dict[str, Any]
    status: Status
    message: str
    warnings: list[str] = field(default_factory=list)
    wall_time_s: float = 0.0
    model: str = ""
    scheme: str = ""
    diagnostics: dict[str, Any] = field(default_factory=dict)
    node_velocities: np.ndarray | None = None
    snap: dict[str, Any] = field(default_factory=dict)

    @classmethod
    def from_nodes(cls, node_positions: np.ndarray, **fields: Any) -> SimulationResult:
        """A result whose end positions are its nodes' first (end_a, the unit) and last
        (end_b, the top) ones: the one place that reads the node layout.

        Parameters
        ----------
        node_positions : ndarray, shape (n_t, n_nodes, 3)
            Node positions from end_a to end_b, m.
        **fields
            Every other field of :class:`SimulationResult`.
        """
        return cls(top_position=node_positions[:, -1, :].copy(),
                   unit_position=node_positions[:, 0, :].copy(),
                   node_positions=node_positions, **fields)

    @classmethod
    def failed(cls, elements: int, message: str, model: str, scheme: str,
               diagnostics: dict[str, Any]) -> SimulationResult:
        """The empty history of a run that could not start (status ``"failed"``).

        Parameters
        ----------
        elements : int
            The line's elements (segments), for the arrays' shapes.
        message : str
            Why the run could not start.
        model : str
            The model's name.
        scheme : str
            The time-integration scheme.
        diagnostics : dict
            The diagnostics (e.g. ``{"start": info}``).
        """
        return cls.from_nodes(
            np.zeros((0, elements + 1, 3)), t=np.zeros(0), length=np.zeros(0),
            top_tension=np.zeros(0), segment_tensions=np.zeros((0, elements)),
            min_tension=math.nan,
            slack=slack_report(None, None, None, status="failed", message=message,
                               on_slack="stop", template="")[0],
            status="failed", message=message, model=model, scheme=scheme,
            diagnostics=diagnostics)

    def _ok(self, a: np.ndarray) -> float | None:
        """Largest of ``a`` where it is finite (None for none)."""
        a = np.asarray(a, dtype=float)
        return float(np.nanmax(a)) if a.size and np.isfinite(a).any() else None

    def __repr__(self) -> str:
        """A few lines: status, model, span, tensions, slack and the arrays' shapes."""
        t = self.t
        span = float(t[-1] - t[0]) if len(t) else 0.0
        return summary_repr(
            "SimulationResult", self.status, self.message,
            [("model", self.model or "-", ""), ("scheme", self.scheme or "-", ""),
             ("simulated", span, "s"), ("samples", len(t), ""),
             ("max_top_tension", self._ok(self.top_tension), "N"),
             ("min_tension", self.min_tension, "N"),
             ("slack", bool(self.slack.get("occurred")), ""),
             ("snap_peak_tension", self.snap.get("peak_tension"), "N"),
             ("warnings", len(self.warnings), ""), ("wall_time_s", self.wall_time_s, "s")],
            {"t": self.t, "top_tension": self.top_tension,
             "node_positions": self.node_positions, "segment_tensions": self.segment_tensions,
             "node_velocities": self.node_velocities})

    def to_xarray(self) -> Any:
        """The time series as an ``xarray.Dataset`` (what ``cable-ocp simulate --netcdf``
        writes): dimensions ``time`` (s), ``node`` (end_a = 0 to end_b), ``element`` and
        ``xyz``; variables ``length`` (m, unstretched), ``top_position``,
        ``unit_position``, ``node_position`` (m), ``top_tension``, ``element_tension`` (N)
        and ``node_velocity`` (m/s, when the model gives it), each with its ``units``.
        Needs xarray (the extra ``[io]``)."""
        xr = optional_module("xarray", "SimulationResult.to_xarray()")
        n_nodes = self.node_positions.shape[1]
        data = {
            "length": ("time", self.length, {"units": "m", "long_name": "unstretched length"}),
            "top_position": (("time", "xyz"), self.top_position, {"units": "m"}),
            "unit_position": (("time", "xyz"), self.unit_position, {"units": "m"}),
            "top_tension": ("time", self.top_tension, {"units": "N"}),
            "node_position": (("time", "node", "xyz"), self.node_positions, {"units": "m"}),
            "element_tension": (("time", "element"), self.segment_tensions, {"units": "N"})}
        if self.node_velocities is not None:
            data["node_velocity"] = (("time", "node", "xyz"), self.node_velocities,
                                     {"units": "m/s"})
        return xr.Dataset(
            data,
            coords={"time": ("time", self.t, {"units": "s"}), "xyz": ["x", "y", "z"],
                    "node": np.arange(n_nodes), "element": np.arange(max(n_nodes - 1, 0))},
            attrs={"kind": "simulation", "model": self.model, "scheme": self.scheme,
                   "status": str(self.status), "message": self.message,
                   "min_tension_N": float(self.min_tension),
                   "conventions": "z up; end_a = node 0 (unit), end_b = last node (ship)"})

    def plot(self, ax: Any = None, **kwargs: Any) -> tuple[Any, Any]:
        """Draw the result (matplotlib), MoorPy's habit: ``fig, ax = res.plot()``.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Draw the top tension against time on it; None (default): a new figure with
            the four panels of ``cable-ocp simulate --plot``
            (:func:`cable_ocp.plots.dynamics.simulation_figure`).
        **kwargs
            ``title``, ``scene``.

        Returns
        -------
        (fig, ax)
            The figure and the Axes drawn on (with ``ax=None``: an array of its panels).
        """
        from cable_ocp.plots.accessors import plot_simulation_result

        return plot_simulation_result(self, ax, **kwargs)

    @property
    def success(self) -> bool:
        """True when the run finished without slack or failure."""
        return self.status == "solved"

    def to_dict(self, full: bool = False) -> dict[str, Any]:
        """JSON-ready dictionary (strict JSON; SI units).

        Fields: ``status``, ``message``, ``model``, ``scheme``, ``t`` (s), ``length`` (m,
        unstretched), ``top_position`` ([[x, y, z], ...], m), ``unit_position``,
        ``top_tension`` (N), ``min_tension`` (N), ``slack``, ``snap``, ``wall_time_s``,
        ``warnings``,
        ``diagnostics``; with ``full`` also ``node_positions`` (m), ``segment_tensions``
        (N) and ``node_velocities`` (m/s, when the model gives them).
        """
        out: dict[str, Any] = {
            "status": self.status,
            "message": self.message,
            "model": self.model,
            "scheme": self.scheme,
            "t": self.t,
            "length": self.length,
            "top_position": self.top_position,
            "unit_position": self.unit_position,
            "top_tension": self.top_tension,
            "min_tension": self.min_tension,
            "slack": self.slack,
            "snap": self.snap,
            "wall_time_s": self.wall_time_s,
            "warnings": list(self.warnings),
            "diagnostics": self.diagnostics,
        }
        if full:
            out["node_positions"] = self.node_positions
            out["segment_tensions"] = self.segment_tensions
            if self.node_velocities is not None:
                out["node_velocities"] = self.node_velocities
        return json_safe(out)


@dataclass(frozen=True)
class ModesResult(_StatusVocabulary):
    """Natural frequencies and mode shapes, linearised about the static state.

    Attributes
    ----------
    frequencies : ndarray, shape (n_modes,)
        Natural frequencies omega, rad/s, ascending.
    shapes : ndarray, shape (n_modes, n_nodes, 3)
        Mode shapes (displacements dx, dy, dz per node, from end_a to end_b), scaled so
        that the largest |component| is 1 and positive.
    node_positions : ndarray, shape (n_nodes, 3)
        Static node positions, m.
    length : float
        Unstretched length of the line, m.
    model : str
        The model that was linearised.
    status : Status
        ``"solved"`` or a failure code (e.g. the static state did not converge).
    message : str
        Detail of the status.
    diagnostics : dict
        Everything else (segments, the static state's source, ...).
    """

    frequencies: np.ndarray
    shapes: np.ndarray
    node_positions: np.ndarray
    length: float
    model: str
    status: Status = Status.SOLVED
    message: str = ""
    diagnostics: dict[str, Any] = field(default_factory=dict)

    @property
    def periods(self) -> np.ndarray:
        """Natural periods 2 pi / omega, s (inf for a zero frequency)."""
        with np.errstate(divide="ignore"):
            return np.where(self.frequencies > 0.0, 2.0 * np.pi / self.frequencies, np.inf)

    def __repr__(self) -> str:
        """A few lines: status, model, the lowest frequencies and the arrays' shapes."""
        nums = [("model", self.model or "-", ""), ("length", self.length, "m"),
                ("modes", len(self.frequencies), "")]
        nums += [(f"omega_{k + 1}", w, "rad/s") for k, w in enumerate(self.frequencies[:3])]
        if len(self.frequencies):
            nums.append(("period_1", self.periods[0], "s"))
        return summary_repr("ModesResult", self.status, self.message, nums,
                            {"frequencies": self.frequencies, "shapes": self.shapes,
                             "node_positions": self.node_positions})

    def to_pandas(self) -> Any:
        """The modes as a ``pandas.DataFrame``, one row per mode (index ``mode``, from 1):
        ``frequency [rad/s]``, ``frequency [Hz]``, ``period [s]``. Needs pandas (the
        extra ``[io]``)."""
        pd = optional_module("pandas", "ModesResult.to_pandas()")
        idx = pd.Index(np.arange(1, len(self.frequencies) + 1), name="mode")
        return pd.DataFrame({"frequency [rad/s]": self.frequencies,
                             "frequency [Hz]": self.frequencies / (2.0 * math.pi),
                             "period [s]": self.periods}, index=idx)

    def to_xarray(self) -> Any:
        """The modes as an ``xarray.Dataset``: dimensions ``mode`` (from 1), ``node``
        (end_a = 0) and ``xyz``; ``frequency`` (rad/s), ``period`` (s), ``shape`` (mode,
        node, xyz; largest component 1) and ``node_position`` (m, the static state). Needs
        xarray (the extra ``[io]``)."""
        xr = optional_module("xarray", "ModesResult.to_xarray()")
        return xr.Dataset(
            {"frequency": ("mode", self.frequencies, {"units": "rad/s"}),
             "period": ("mode", self.periods, {"units": "s"}),
             "shape": (("mode", "node", "xyz"), self.shapes,
                       {"units": "1", "long_name": "mode shape, largest component 1"}),
             "node_position": (("node", "xyz"), self.node_positions, {"units": "m"})},
            coords={"mode": np.arange(1, len(self.frequencies) + 1),
                    "node": np.arange(self.node_positions.shape[0]), "xyz": ["x", "y", "z"]},
            attrs={"kind": "modes", "model": self.model, "status": str(self.status),
                   "message": self.message, "length_m": float(self.length)})

    def plot(self, ax: Any = None, **kwargs: Any) -> tuple[Any, Any]:
        """Draw the result (matplotlib), MoorPy's habit: ``fig, ax = res.plot()``.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Draw the static profile and the lowest three mode shapes on it; None
            (default): a new figure with one panel per mode (``cable-ocp modes --plot``).
        **kwargs
            ``title``, ``max_modes`` (default 6).

        Returns
        -------
        (fig, ax)
            The figure and the Axes drawn on (with ``ax=None``: an array of its panels).
        """
        from cable_ocp.plots.accessors import plot_modes_result

        return plot_modes_result(self, ax, **kwargs)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary: ``{"modes": [{"frequency_rad_s", "period_s", "shape"}],
        ...}`` in ascending frequency, ``shape`` one [dx, dy, dz] row per node from end_a
        to end_b; plus ``status``, ``message``, ``model``, ``length``,
        ``node_positions`` and ``diagnostics``."""
        modes = [{"frequency_rad_s": float(w), "frequency_hz": float(w) / (2.0 * math.pi),
                  "period_s": float(p), "shape": s}
                 for w, p, s in zip(self.frequencies, self.periods, self.shapes, strict=True)]
        return json_safe({"status": self.status, "message": self.message,
                          "model": self.model, "length": self.length, "modes": modes,
                          "node_positions": self.node_positions,
                          "diagnostics": self.diagnostics})


@dataclass(frozen=True)
class DeploymentChart(_StatusVocabulary):
    """Natural frequencies against paid-out length (a deployment resonance chart).

    Attributes
    ----------
    lengths : ndarray, shape (n_L,)
        Unstretched lengths, m.
    frequencies : ndarray, shape (n_L, n_modes)
        Natural frequencies at each length, rad/s, ascending per row (NaN where the
        static state failed).
    wave_band : tuple of float
        Wave-frequency band (low, high), rad/s.
    model : str
        The model that was linearised.
    status : Status
        ``"solved"`` or ``"failed"`` (some lengths failed: their rows are NaN).
    message : str
        Detail of the status.
    diagnostics : dict
        Everything else.
    """

    lengths: np.ndarray
    frequencies: np.ndarray
    wave_band: tuple[float, float]
    model: str
    status: Status = Status.SOLVED
    message: str = ""
    diagnostics: dict[str, Any] = field(default_factory=dict)

    def __repr__(self) -> str:
        """A few lines: status, model, the lengths, the band and the arrays' shapes."""
        lo, hi = self.wave_band
        lengths = np.asarray(self.lengths, dtype=float)
        return summary_repr(
            "DeploymentChart", self.status, self.message,
            [("model", self.model or "-", ""),
             ("lengths", f"{lengths.min():.6g}..{lengths.max():.6g}" if lengths.size else "-",
              "m"), ("modes", self.frequencies.shape[-1] if self.frequencies.ndim == 2 else 0,
                     ""),
             ("wave_band", f"{lo:.6g}..{hi:.6g}", "rad/s"),
             ("in_band", int(self.in_band.sum()), "")],
            {"lengths": self.lengths, "frequencies": self.frequencies})

    def to_xarray(self) -> Any:
        """The chart as an ``xarray.Dataset``: ``frequency`` (rad/s) over dimensions
        ``length`` (m, unstretched) and ``mode`` (from 1), ``in_band`` (bool). Needs
        xarray (the extra ``[io]``)."""
        xr = optional_module("xarray", "DeploymentChart.to_xarray()")
        n = self.frequencies.shape[1]
        return xr.Dataset(
            {"frequency": (("length", "mode"), self.frequencies, {"units": "rad/s"}),
             "in_band": (("length", "mode"), self.in_band)},
            coords={"length": ("length", self.lengths, {"units": "m"}),
                    "mode": np.arange(1, n + 1)},
            attrs={"kind": "deployment_chart", "model": self.model,
                   "status": str(self.status), "message": self.message,
                   "wave_band_rad_s": list(self.wave_band)})

    def to_pandas(self) -> Any:
        """The chart as a ``pandas.DataFrame``: one row per length (index ``length [m]``),
        one column per mode (``mode k [rad/s]``). Needs pandas (the extra ``[io]``)."""
        pd = optional_module("pandas", "DeploymentChart.to_pandas()")
        cols = {f"mode {k + 1} [rad/s]": self.frequencies[:, k]
                for k in range(self.frequencies.shape[1])}
        return pd.DataFrame(cols, index=pd.Index(self.lengths, name="length [m]"))

    def plot(self, ax: Any = None, **kwargs: Any) -> tuple[Any, Any]:
        """Draw the result (matplotlib), MoorPy's habit: ``fig, ax = res.plot()``.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Draw the frequencies against the length on it; None (default): a new figure
            with the chart of ``cable-ocp modes --lengths --plot``.
        **kwargs
            ``title``.

        Returns
        -------
        (fig, ax)
            The figure and the Axes drawn on (with ``ax=None``: an array of its panels).
        """
        from cable_ocp.plots.accessors import plot_deployment_chart

        return plot_deployment_chart(self, ax, **kwargs)

    @property
    def in_band(self) -> np.ndarray:
        """(n_L, n_modes) bool: the frequency lies in the wave band."""
        lo, hi = self.wave_band
        f = np.nan_to_num(self.frequencies, nan=-1.0)
        return (f >= lo) & (f <= hi)

    def crossings(self) -> list[dict[str, Any]]:
        """Lengths where a mode's frequency crosses a band edge (linear interpolation).

        Each entry: ``mode`` (0-based), ``edge`` (rad/s), ``length_m``.
        """
        out = []
        for k in range(self.frequencies.shape[1]):
            f = self.frequencies[:, k]
            for edge in self.wave_band:
                d = f - edge
                for i in range(len(d) - 1):
                    if np.isfinite(d[i]) and np.isfinite(d[i + 1]) and d[i] * d[i + 1] < 0:
                        a = d[i] / (d[i] - d[i + 1])
                        length = self.lengths[i] + a * (self.lengths[i + 1] - self.lengths[i])
                        out.append({"mode": k, "edge": float(edge), "length_m": float(length)})
        return sorted(out, key=lambda c: c["length_m"])

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary: ``lengths`` (m), ``frequencies_rad_s`` (rows per length),
        ``wave_band_rad_s``, ``crossings``, ``status``, ``message``, ``model``."""
        return json_safe({"status": self.status, "message": self.message, "model": self.model,
                          "lengths": self.lengths, "frequencies_rad_s": self.frequencies,
                          "wave_band_rad_s": list(self.wave_band),
                          "crossings": self.crossings(), "diagnostics": self.diagnostics})
