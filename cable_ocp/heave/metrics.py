"""The results of a heave comparison and the metrics of a run, one home for both loops.

Every metric is taken over the same window ``t >= [simulation] warmup`` (:func:`run_metrics`);
``reduction_pct`` is relative to a passive run on the same sea and plant
(:func:`reduction_pct`). :class:`Comparison` is the result of
:func:`cable_ocp.heave.design_loop.compare`, :class:`CableComparison` that of
:func:`cable_ocp.heave.cable_compare.compare_cable` (on the cable plant the metrics add the
tensions, the slack samples and the prediction of the design model: :class:`CableMetrics`,
:func:`cable_run_metrics`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from cable_ocp.dynamics.result import slack_report
from cable_ocp.heave.closed_loop import LoopRun, Trace, run_status
from cable_ocp.numerics.export import optional_module, summary_repr
from cable_ocp.scene.heave import HeaveScene
from cable_ocp.status import Status

if TYPE_CHECKING:
    from cable_ocp.heave.design_loop import Models

__all__ = ["CABLE_FIELDS", "LIMIT_TOLERANCE", "SLACK_MESSAGE", "WINCH_LIMITS", "CableComparison",
           "CableMetrics", "Comparison", "Metrics", "cable_run_metrics", "cable_status",
           "limit_excess", "limit_warning", "no_cable_metrics", "reduction_pct", "run_metrics",
           "with_reduction"]


@dataclass(frozen=True)
class Metrics:
    """JSON metrics of one controller (field names as in docs/conventions.md, "Heave compensation").

    Every field is None (JSON null) where the number does not exist: all but
    ``energy_index`` and ``solve_time_median_s`` for a controller whose status is not
    ``"solved"``; ``reduction_pct`` when the passive baseline has no heave;
    ``peak_torque`` (N m) and ``peak_power`` (W, the largest ``|tau|`` and ``|P|`` of the
    winch motor) without ``[winch] drum_radius``; ``max_stroke_phc`` (m, the passive
    compensator's largest ``|delta|``) and ``stop_time_phc`` (s, the time it spent at its end
    stops) for a controller without the compensator.
    """

    heave_rms: float | None
    reduction_pct: float | None
    peak_winch_speed: float | None
    max_stroke: float | None
    energy_index: float | None
    max_constraint_violation: float | None
    solve_time_median_s: float | None
    winch_speed_rms: float | None
    peak_torque: float | None = None
    peak_power: float | None = None
    max_stroke_phc: float | None = None
    stop_time_phc: float | None = None

    def as_dict(self) -> dict:
        """Plain dict for JSON."""
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


@dataclass(frozen=True)
class Comparison:
    """Result of :func:`cable_ocp.heave.design_loop.compare`.

    Attributes
    ----------
    sigma_uncontrolled : float or None
        Lyapunov standard deviation of the uncontrolled unit heave, m (None if it does not
        exist).
    metrics : dict
        Controller name -> :class:`Metrics`.
    traces : dict
        Controller name -> :class:`Trace` (NaN after the sample where a run was stopped).
    statuses, messages : dict
        Controller name -> status (:data:`cable_ocp.heave.closed_loop.STATUSES`) and its
        explanation.
    passive_heave_rms : float
        Heave RMS of the passive run on the same realisation (the baseline of
        ``reduction_pct``), m.
    mpc_failures : int
        MPC samples at which the QP failed and the shifted previous plan was applied.
    warnings : list of str
        Remarks that do not change a status (MPC fallbacks, a missing sigma_uncontrolled).
    interrupted : bool
        A Ctrl-C stopped the comparison (the controllers not finished have the status
        ``"interrupted"``; the passive baseline, when not a controller, may be the run stopped).
    """

    sigma_uncontrolled: float | None
    metrics: dict
    traces: dict
    models: Models
    mpc_solve_times: np.ndarray | None
    mpc_failures: int
    statuses: dict = field(default_factory=dict)
    messages: dict = field(default_factory=dict)
    passive_heave_rms: float | None = None
    warnings: list = field(default_factory=list)
    interrupted: bool = False

    def __post_init__(self) -> None:
        # every controller's status is one of the package's vocabulary (cable_ocp.status)
        for name, st in self.statuses.items():
            self.statuses[name] = Status(st)

    @property
    def status(self) -> Status:
        """``"interrupted"`` when a Ctrl-C stopped the comparison (some controller is), else
        ``"solved"`` when every controller is, else the first other status."""
        if self.interrupted or Status.INTERRUPTED in self.statuses.values():
            return Status.INTERRUPTED
        bad = [s for s in self.statuses.values() if s != "solved"]
        return bad[0] if bad else "solved"

    def __repr__(self) -> str:
        """A few lines: status, the passive baseline, each controller's status, heave RMS
        and reduction, and the traces' shapes."""
        nums: list[tuple[str, Any, str]] = [
            ("controllers", len(self.metrics), ""),
            ("passive_heave_rms", self.passive_heave_rms, "m"),
            ("sigma_uncontrolled", self.sigma_uncontrolled, "m")]
        for name, m in self.metrics.items():
            nums += [(f"{name}.status", str(self.statuses.get(name, "-")), ""),
                     (f"{name}.heave_rms", m.heave_rms, "m"),
                     (f"{name}.reduction", m.reduction_pct, "%")]
        nums.append(("warnings", len(self.warnings), ""))
        first = next(iter(self.traces.values()), None)
        return summary_repr(type(self).__name__, self.status, "", nums,
                            {"traces.t": None if first is None else first.t})

    def to_pandas(self) -> Any:
        """The metrics as a ``pandas.DataFrame``, one row per controller (index
        ``controller``): ``status`` and every :class:`Metrics` field (units as in
        docs/conventions.md: m, m/s, %, s). Needs pandas (the extra ``[io]``)."""
        pd = optional_module("pandas", f"{type(self).__name__}.to_pandas()")
        rows = [{"controller": name, "status": str(self.statuses.get(name, "")),
                 **{k: (np.nan if v is None else v) for k, v in m.as_dict().items()}}
                for name, m in self.metrics.items()]
        return pd.DataFrame(rows).set_index("controller")

    def to_xarray(self) -> Any:
        """The traces as an ``xarray.Dataset`` over dimensions ``controller`` and ``time``
        (s): ``unit_heave``, ``tip_heave``, ``winch_output``, ``command`` (m),
        ``winch_speed`` (m/s), and on a cable plant ``tension_unit``, ``tension_top`` (N)
        and ``deployment_length`` (m); where known ``line_tension`` (N), ``motor_torque``
        (N m), ``motor_power`` (W) and ``phc_stroke`` (m); NaN after a stopped run's last
        sample. Needs xarray (the extra ``[io]``)."""
        xr = optional_module("xarray", f"{type(self).__name__}.to_xarray()")
        names = {"x": ("unit_heave", "m"), "x0": ("tip_heave", "m"),
                 "u": ("winch_output", "m"), "u_dot": ("winch_speed", "m/s"),
                 "u0": ("command", "m"), "tension_unit": ("tension_unit", "N"),
                 "tension_top": ("tension_top", "N"), "length": ("deployment_length", "m"),
                 "tension": ("line_tension", "N"), "torque": ("motor_torque", "N m"),
                 "power": ("motor_power", "W"), "stroke_phc": ("phc_stroke", "m")}
        parts = []
        for tr in self.traces.values():
            data = {var: ("time", np.asarray(getattr(tr, key), dtype=float), {"units": unit})
                    for key, (var, unit) in names.items()
                    if np.shape(getattr(tr, key, None)) == np.shape(tr.t)}
            parts.append(xr.Dataset(data, coords={"time": ("time", tr.t, {"units": "s"})}))
        ds = xr.concat(parts, dim="controller", join="outer") if parts else xr.Dataset()
        return ds.assign_coords(controller=list(self.traces)).assign_attrs(
            kind="heave", status=str(self.status),
            statuses=", ".join(f"{k}: {v}" for k, v in self.statuses.items()))

    def plot(self, ax: Any = None, **kwargs: Any) -> tuple[Any, Any]:
        """Draw the comparison (matplotlib), MoorPy's habit: ``fig, ax = res.plot()``.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Draw the unit's heave against time, one line per controller, on it; None
            (default): a new figure with the panels of ``cable-ocp heave --plot``
            (:func:`cable_ocp.plots.heave.comparison_figure`).
        **kwargs
            ``scene`` (warm-up shading, limits, title), ``tradeoff``, ``references``.

        Returns
        -------
        (fig, ax)
            The figure and the Axes drawn on (with ``ax=None``: an array of its panels).
        """
        from cable_ocp.plots.accessors import plot_heave_result

        return plot_heave_result(self, ax, **kwargs)


@dataclass(frozen=True, repr=False)  # the short summary of Comparison
class CableComparison(Comparison):
    """Result of :func:`cable_ocp.heave.cable_compare.compare_cable` (the fields of
    :class:`Comparison` plus the cable's).

    Attributes
    ----------
    statuses, messages : dict
        Controller name -> status (:data:`cable_ocp.heave.closed_loop.STATUSES`) of its run on
        the plant, and its explanation.
    passive_heave_rms : float or None
        Heave RMS of the passive run on the same plant and sea (the baseline of
        ``reduction_pct``), m.
    warnings : list of str
        Remarks that do not change a status.
    json_extra : dict
        Top-level JSON fields: ``plant``, ``design_model`` (a, b used and where from),
        ``identified`` (see :func:`cable_ocp.heave.identify_cable.identified_json`).
    predicted_traces : dict
        The runs on the design model (same estimator, sensors, noise, sea).
    """

    json_extra: dict = field(default_factory=dict)
    predicted_traces: dict = field(default_factory=dict)


def reduction_pct(rms: float | None, base: float | None) -> float | None:
    """``100 (1 - rms / base)`` (%): the heave reduction against the passive run's RMS
    ``base`` (m); None where either does not exist (or ``base`` is not positive).

    Parameters
    ----------
    rms : float or None
        The controller's heave RMS, m.
    base : float or None
        The passive run's heave RMS on the same sea and plant, m.
    """
    ok = rms is not None and base is not None and base > 0
    return float(100.0 * (1.0 - rms / base)) if ok else None


def with_reduction(mt: Metrics, base: float | None) -> Metrics:
    """``mt`` with its ``reduction_pct`` (:func:`reduction_pct`).

    Parameters
    ----------
    mt : Metrics
        A controller's metrics.
    base : float or None
        The passive run's heave RMS, m.
    """
    d = mt.as_dict()
    d["reduction_pct"] = reduction_pct(mt.heave_rms, base)
    return Metrics(**d)


#: the winch's limits, in the order :func:`limit_excess` checks them: key, what, unit
WINCH_LIMITS = (("stroke_max", "stroke", "m"), ("speed_max", "winch speed", "m/s"),
                ("command_rate_max", "command change", "m per sample"),
                ("accel_max", "winch acceleration", "m/s^2"),
                ("torque_max", "motor torque", "N m"), ("power_max", "motor power", "W"))


def limit_excess(scene: HeaveScene, tr: Trace, cmds: np.ndarray, h: float
                 ) -> list[tuple[str, float, float, str]]:
    """The winch limits a run exceeds after the warm-up: ``(key, largest value, limit,
    unit)`` per ``[winch]`` key, in :data:`WINCH_LIMITS`' order (empty when every limit
    holds). Stroke ``|u|`` and speed ``|u'|``; the change of the command per sample (command
    ``k`` is issued at ``t = k h``, command -1 is the initial 0; its change from command
    ``k - 1`` counts if ``k h >= warm-up``); the acceleration for the second-order winch only
    (docs/conventions.md, "Heave compensation"); the motor's torque and power (``|tau|``,
    ``|P|``, :mod:`cable_ocp.heave.drive`) where ``[winch] drum_radius`` is given. The plant
    does not saturate: a run past a
    limit assumes a winch that can do what it was asked.

    Parameters
    ----------
    scene : HeaveScene
        The scene (warm-up, winch limits).
    tr : Trace
        The run's trace.
    cmds : numpy.ndarray
        The commands per sample, m.
    h : float
        Sample time, s.
    """
    warm = scene.simulation.warmup
    keep = tr.t >= warm - 1e-12
    w = scene.winch
    largest: dict[str, float] = {}
    if np.any(keep):
        largest["stroke_max"] = float(np.max(np.abs(tr.u[keep])))
        largest["speed_max"] = float(np.max(np.abs(tr.u_dot[keep])))
    if w.command_rate_max is not None and cmds.size > 1:
        k0 = max(0, int(np.ceil(warm / h - 1e-9)))
        dcmd = np.diff(np.concatenate([[0.0], cmds]))[k0:]
        if dcmd.size:
            largest["command_rate_max"] = float(np.max(np.abs(dcmd)))
    if w.accel_max is not None and w.model == "second_order" and np.any(keep):
        largest["accel_max"] = float(np.max(np.abs(np.gradient(tr.u_dot, tr.t)[keep])))
    for key, series in (("torque_max", tr.torque), ("power_max", tr.power)):
        if series is not None and np.any(keep):
            largest[key] = float(np.max(np.abs(series[keep])))
    out = []
    for key, _, unit in WINCH_LIMITS:
        limit = getattr(w, key, None)
        if limit is not None and key in largest and largest[key] > limit:
            out.append((key, largest[key], float(limit), unit))
    return out


#: a run exceeds a limit for :func:`limit_warning` when it is past it by more than this
#: fraction: the MPC keeps its hard limits to its QP solver's tolerance (its command change
#: ends 1e-10 m past 0.1 m), which is no excess a winch would notice
LIMIT_TOLERANCE = 1e-3


def limit_warning(name: str, excess: list[tuple[str, float, float, str]]) -> str | None:
    """One warning line for a controller past the winch's limits (:func:`limit_excess`) by
    more than :data:`LIMIT_TOLERANCE`, or None when it keeps them.

    Parameters
    ----------
    name : str
        The controller.
    excess : list of tuple
        :func:`limit_excess` of its run.
    """
    what = {key: text for key, text, _ in WINCH_LIMITS}
    parts = [f"{what[key]} {value:.3g} {unit}, winch.{key} = {limit:g} ({value / limit:.1f}x)"
             for key, value, limit, unit in excess if value > limit * (1.0 + LIMIT_TOLERANCE)]
    if not parts:
        return None
    return (f"{name} exceeds the winch's limits (the plant does not saturate): "
            + "; ".join(parts))


#: the heave plant's slack message (:func:`cable_ocp.dynamics.result.slack_report`, the rule
#: that gives ``simulate`` its status ``slack``)
SLACK_MESSAGE = ("an element tension <= 0 at {samples} samples after the warm-up, "
                 "first at t = {t:.2f} s; the {model} model {action}")


def cable_status(run: LoopRun, metrics: dict, model: str) -> tuple[str, str]:
    """``(status, message)`` of a run on the cable: :func:`cable_ocp.heave.closed_loop.
    run_status`, then ``"slack"`` where the line went slack after the warm-up and the run
    otherwise succeeded (:func:`cable_ocp.dynamics.result.slack_report`, as ``simulate``
    decides it): until the plant follows slack physically, its tensions and heave past
    slack are not physical.

    Parameters
    ----------
    run : LoopRun
        The run on the cable.
    metrics : dict
        Its :func:`cable_run_metrics` (``slack_first_time_s``, ``slack_samples``).
    model : str
        The cable plant's model (``"axial"``, ``"planar"``, ``"lumped3d"``).
    """
    status, message = run_status(run)
    why = ("cannot follow slack (it carries compression): its tensions and heave past there "
           "are not physical" if model == "axial" else "has no compression and follows a "
           "slack line only approximately (it may fold there)")
    _, status, message = slack_report(
        metrics.get("slack_first_time_s"), None, None, status=status, message=message,
        on_slack="continue", template=SLACK_MESSAGE, continued=why,
        samples=metrics.get("slack_samples"), model=model)
    return status, message


def run_metrics(scene: HeaveScene, tr: Trace, cmds: np.ndarray, energy: float | None,
                times: np.ndarray | None, h: float) -> Metrics:
    """Metrics of one run, all over the same window ``t >= [simulation] warmup``.

    The run starts with the unit and winch at rest while the sea starts in a stationary random
    state, so the first seconds are an artificial start-up transient. Every metric (RMS values,
    peaks, stroke, constraint violations, including the command change per sample and the
    second-order winch's acceleration) is taken after the warm-up only, so that they describe
    the same stationary operation.

    Parameters
    ----------
    scene : HeaveScene
        The scene (warm-up, winch limits).
    tr : Trace
        The run's trace.
    cmds : numpy.ndarray
        The commands per sample, m.
    energy : float or None
        The controller's energy index.
    times : numpy.ndarray or None
        The solver's times per sample, s (the MPC's).
    h : float
        Sample time, s.
    """
    warm = scene.simulation.warmup
    keep = tr.t >= warm - 1e-12
    u, ud = tr.u[keep], tr.u_dot[keep]
    viol = max([0.0] + [(value - limit) / limit
                        for _, value, limit, _ in limit_excess(scene, tr, cmds, h)])
    return Metrics(
        heave_rms=float(np.sqrt(np.mean(tr.x[keep] ** 2))),
        reduction_pct=None,
        peak_winch_speed=float(np.max(np.abs(ud))),
        max_stroke=float(np.max(np.abs(u))),
        energy_index=energy,
        max_constraint_violation=float(viol),
        solve_time_median_s=float(np.median(times)) if times is not None and times.size
        else None,
        winch_speed_rms=float(np.sqrt(np.mean(ud**2))),
        peak_torque=_peak(tr.torque, keep),
        peak_power=_peak(tr.power, keep),
        max_stroke_phc=_peak(tr.stroke_phc, keep),
        stop_time_phc=_stop_time(scene, tr, keep),
    )


def _peak(series: np.ndarray | None, keep: np.ndarray) -> float | None:
    """The largest ``|series|`` after the warm-up, or None without the series."""
    return None if series is None else float(np.max(np.abs(series[keep])))


def _stop_time(scene: HeaveScene, tr: Trace, keep: np.ndarray) -> float | None:
    """The time (s) the passive compensator spent at its end stops after the warm-up (to
    1e-9 of its stroke), or None without one."""
    if tr.stroke_phc is None or scene.passive_compensator is None:
        return None
    smax = scene.passive_compensator.stroke_max
    dt = float(tr.t[1] - tr.t[0]) if tr.t.size > 1 else 0.0
    return float(np.count_nonzero(np.abs(tr.stroke_phc[keep]) >= smax * (1 - 1e-9)) * dt)


#: the cable-plant fields of a controller's metrics (None where the run is not solved)
CABLE_FIELDS = ("tension_unit_min", "tension_unit_max", "tension_top_min", "tension_top_max",
                "slack_samples", "slack_first_time_s", "plant_failed_at_s")


def no_cable_metrics() -> dict:
    """The metrics (:func:`cable_run_metrics`' keys) of a controller that has none (its design
    failed, or an interruption came before its run finished): every value None."""
    return dict.fromkeys(tuple(Metrics.__dataclass_fields__) + CABLE_FIELDS)


def cable_run_metrics(scene: HeaveScene, run: LoopRun, energy: float | None) -> dict:
    """The metrics of :func:`run_metrics` and the cable's for a run of a line under the
    winch; every value None (JSON null) but ``energy_index``, the solve time and
    ``plant_failed_at_s`` when the run is not solved.

    Parameters
    ----------
    scene : HeaveScene
        The design scene (warm-up, sample time, winch limits).
    run : LoopRun
        The run (a :class:`cable_ocp.heave.closed_loop.CableTrace`).
    energy : float or None
        The controller's energy index (:attr:`cable_ocp.heave.controllers.Controller.
        energy_index`).
    """
    times = run.times
    if run_status(run)[0] != "solved":
        d = dict.fromkeys(tuple(Metrics.__dataclass_fields__) + CABLE_FIELDS)
        d["energy_index"] = energy
        d["solve_time_median_s"] = (float(np.median(times)) if times is not None
                                    and times.size else None)
        d["plant_failed_at_s"] = run.plant_failed_at
        return d
    base = run_metrics(scene, run.trace, run.commands, energy, times, scene.controller.sample_time)
    tr = run.trace
    keep = tr.t >= scene.simulation.warmup - 1e-12
    h = scene.controller.sample_time
    kk = np.arange(tr.min_element_tension.size) * h >= scene.simulation.warmup - 1e-12
    slack = tr.min_element_tension <= 0.0
    first = np.flatnonzero(slack & kk)
    return {**base.as_dict(),
            "tension_unit_min": float(np.min(tr.tension_unit[keep])),
            "tension_unit_max": float(np.max(tr.tension_unit[keep])),
            "tension_top_min": float(np.min(tr.tension_top[keep])),
            "tension_top_max": float(np.max(tr.tension_top[keep])),
            "slack_samples": int(np.count_nonzero(slack[kk])),
            "slack_first_time_s": float(first[0] * h) if first.size else None,
            "plant_failed_at_s": run.plant_failed_at}


@dataclass(frozen=True)
class CableMetrics:
    """Per-controller metrics on the cable plant (JSON fields).

    The fields of :class:`Metrics` for the run on the cable, and:
    ``heave_rms_predicted`` (m) and ``reduction_predicted_pct`` (%) of the same controller
    (estimator, sensors, noise, sea) on the design model; ``tension_unit_min/max``,
    ``tension_top_min/max`` (N, after the warm-up); ``slack_samples`` (samples after the
    warm-up with an element tension <= 0), ``slack_first_time_s`` (s or None);
    ``plant_failed_at_s`` (a Newton step of the cable did not converge there, or None).
    """

    values: dict

    def as_dict(self) -> dict:
        """Plain dict for JSON."""
        return dict(self.values)

    def __getattr__(self, key: str) -> Any:
        try:
            return self.__dict__["values"][key]
        except KeyError as exc:
            raise AttributeError(key) from exc
