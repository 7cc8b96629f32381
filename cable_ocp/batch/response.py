"""Frequency-response sweeps: ``frequency_response(scene, frequencies, amplitudes)`` ->
:class:`ResponseResult`, the steady-state amplitude of chosen outputs from time runs with a
harmonic top motion, beside the linear transfer function of the modes
(:mod:`cable_ocp.dynamics.response`), as the thesis' Figs 3.3-3.7 and 4.2-4.6 plot them
(Huang (1992), 004 sections 3.3.1-3.3.4 and 4.5.1-4.5.2).

One time run per (amplitude, frequency), a case of the batch machinery
(:mod:`cable_ocp.batch.executors`: in this process, on local worker processes, or on a
dask.distributed cluster). Each run (:func:`steady_run`):

* samples ``samples_per_period`` points per excitation period T = 2 pi / w (the time step
  the largest divisor of T / samples_per_period not above the scene's ``time_step``);
* ramps the motion in over ``ramp_periods`` periods (``top_motion.ramp_time``; 0 keeps the
  scene's ramp), then runs ``min_periods`` more periods;
* is *periodic* when the harmonic amplitude at w over the last period and over the one
  before agree to ``tolerance`` (relative) for every output; else the run is repeated with
  twice the periods, up to ``max_periods`` (status ``"not_converged"``, amplitudes kept);
* gives per output the amplitude and phase of the Fourier (least-squares) fit at w over
  the last ``window_periods`` whole periods, the half range (max - min) / 2, the mean and
  the maximum there.

A run that goes slack keeps its status ``"slack"`` (the models cannot follow slack: Huang
(1992) 4.5.1); one that fails keeps ``"failed"`` with NaN amplitudes.
"""

from __future__ import annotations

import math
import re
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.batch.cases import Case
from cable_ocp.batch.executors import RunnerSpec, run_dask, run_local, run_serial
from cable_ocp.batch.kinds import Runner
from cable_ocp.dynamics.response import (
    EXCITATIONS,
    LinearResponse,
    check_response_scene,
    excitation_keys,
    excitation_kind,
    linear_response,
    output_series,
    output_unit,
    parse_outputs,
    period_change,
    window_fit,
)
from cable_ocp.errors import CableOCPError
from cable_ocp.scene.files import apply_overrides, read_problem
from cable_ocp.status import Status

__all__ = ["ResponseResult", "ResponseSettings", "frequency_response", "parse_amplitudes",
           "parse_frequencies", "steady_run"]

#: the fields of one output in a run's row (name -> unit: "" the output's own)
FIT_FIELDS = ("amplitude", "phase", "half_range", "mean", "max")


def parse_frequencies(text: str) -> np.ndarray:
    """``START:STOP:N`` -> N evenly spaced frequencies from START to STOP, rad/s.

    Raises
    ------
    CableOCPError
        Not three fields, not numbers, N < 1, or a frequency <= 0 (named).
    """
    m = re.fullmatch(r"\s*([^:]+):([^:]+):([^:]+)\s*", str(text))
    if not m:
        raise CableOCPError(f"--frequencies {text!r}: expected START:STOP:N (rad/s), e.g. "
                            "5:40:36")
    try:
        start, stop, n = float(m.group(1)), float(m.group(2)), int(m.group(3))
    except ValueError:
        raise CableOCPError(f"--frequencies {text!r}: START and STOP must be numbers (rad/s) "
                            "and N an integer") from None
    if not (math.isfinite(start) and math.isfinite(stop)) or start <= 0 or stop <= 0:
        raise CableOCPError(f"--frequencies {text!r}: START and STOP must be finite and > 0 "
                            "(rad/s)")
    if not 1 <= n <= 10000:
        raise CableOCPError(f"--frequencies {text!r}: N must be 1..10000")
    return np.linspace(start, stop, n)


def parse_amplitudes(text: str) -> np.ndarray:
    """``A1,A2,...`` -> the excitation amplitudes, m (> 0).

    Raises
    ------
    CableOCPError
        A value that is not a positive finite number (named).
    """
    vals = []
    for part in str(text).split(","):
        try:
            v = float(part)
        except ValueError:
            raise CableOCPError(f"--amplitudes {text!r}: {part!r} is not a number; expected "
                                "A1,A2,... in m, e.g. 0.0254,0.0508") from None
        if not (math.isfinite(v) and v > 0.0):
            raise CableOCPError(f"--amplitudes {text!r}: every amplitude must be > 0 (m)")
        vals.append(v)
    return np.asarray(vals, dtype=float)


@dataclass(frozen=True)
class ResponseSettings:
    """How the time runs reach and measure the steady state (module docstring).

    Attributes
    ----------
    samples_per_period : int
        Output samples per excitation period (default 64).
    ramp_periods : float
        Periods of the smooth ramp of the motion (default 10; 0 keeps the scene's
        ``ramp_time``).
    min_periods : int
        Periods after the ramp in the first run (default 12).
    max_periods : int
        The cap on the periods after the ramp (default 192).
    tolerance : float
        Relative change of the amplitude between the last two periods that counts as
        periodic (default 0.01).
    window_periods : int
        Whole periods at the end of a run that the fit uses (default 2).
    """

    samples_per_period: int = 64
    ramp_periods: float = 10.0
    min_periods: int = 12
    max_periods: int = 192
    tolerance: float = 0.01
    window_periods: int = 2

    def __post_init__(self) -> None:
        checks = [("samples_per_period", self.samples_per_period >= 8),
                  ("ramp_periods", math.isfinite(self.ramp_periods) and self.ramp_periods >= 0),
                  ("window_periods", self.window_periods >= 1),
                  ("min_periods", self.min_periods >= max(2, self.window_periods)),
                  ("max_periods", self.max_periods >= self.min_periods),
                  ("tolerance", math.isfinite(self.tolerance) and self.tolerance > 0)]
        for name, ok in checks:
            if not ok:
                raise CableOCPError(
                    f"response {name} = {getattr(self, name)}: need samples_per_period >= 8, "
                    "ramp_periods >= 0, window_periods >= 1, min_periods >= max(2, "
                    "window_periods), max_periods >= min_periods, tolerance > 0")


def _run_overrides(data: dict[str, Any], kind: str, omega: float, amplitude: float,
                   periods: int, st: ResponseSettings) -> dict[str, Any]:
    """The dotted keys of one time run."""
    amp_key, freq_key = excitation_keys(kind)
    period = 2.0 * math.pi / omega
    dt_scene = float(data["simulation"]["time_step"])
    out_step = period / st.samples_per_period
    sub = max(1, math.ceil(out_step / dt_scene * (1.0 - 1e-12)))
    ov: dict[str, Any] = {f"top_motion.{amp_key}": amplitude, f"top_motion.{freq_key}": omega,
                          "simulation.time_step": out_step / sub,
                          "simulation.output_step": out_step,
                          "simulation.duration": (periods + math.ceil(st.ramp_periods))
                          * period}
    if st.ramp_periods > 0:
        ov["top_motion.ramp_time"] = st.ramp_periods * period
    return ov


def steady_run(data: dict[str, Any], kind: str, outputs: Sequence[str], omega: float,
               amplitude: float, settings: ResponseSettings | None = None
               ) -> tuple[str, str, dict[str, Any]]:
    """One frequency and amplitude run until periodic (module docstring).

    Parameters
    ----------
    data : dict
        The dynamic problem (as read from TOML).
    kind : str
        The excitation (:data:`cable_ocp.dynamics.response.EXCITATIONS`).
    outputs : sequence of str
        Output names (:func:`cable_ocp.dynamics.response.parse_outputs`).
    omega : float
        Excitation frequency, rad/s.
    amplitude : float
        Excitation amplitude, m.
    settings : ResponseSettings, optional
        Defaults as documented there.

    Returns
    -------
    (status, message, values)
        ``values``: ``"{output}_{field}"`` for the fields of :data:`FIT_FIELDS`, and
        ``periods`` (after the ramp), ``change`` (the largest relative change over the
        outputs between the last two periods), ``min_tension`` (the smallest element
        tension of the run, N: <= 0 where it went slack, also before a failed step) and
        ``simulation_wall_time`` (s).
    """
    from cable_ocp.dynamics.simulation import simulate
    from cable_ocp.scene.dynamics import dynamic_scene_from_dict

    st = settings or ResponseSettings()
    periods = st.min_periods
    wall = 0.0
    while True:
        scene = dynamic_scene_from_dict(
            apply_overrides(data, _run_overrides(data, kind, omega, amplitude, periods, st)))
        res = simulate(scene)
        wall += res.wall_time_s
        values: dict[str, Any] = {"periods": periods, "simulation_wall_time": wall,
                                  "min_tension": res.min_tension}
        if res.status not in ("solved", "slack") or res.t.size < 8:
            low = res.min_tension
            tail = f" (smallest tension before: {low:.3g} N)" if math.isfinite(low) else ""
            return str(res.status), res.message + tail, values
        t = np.asarray(res.t, dtype=float)
        change = 0.0
        for name in outputs:
            y = output_series(res, name)
            change = max(change, period_change(t, y, omega)[2])
            fit = window_fit(t, y, omega, st.window_periods)
            for f in FIT_FIELDS:
                values[f"{name}_{f}"] = fit[f]
        values["change"] = change
        if res.status == "slack":
            return "slack", res.message, values
        if change <= st.tolerance:
            return "solved", (f"periodic after {periods} periods (change {change:.2g} <= "
                              f"{st.tolerance:g})"), values
        if periods >= st.max_periods:
            return "not_converged", (f"not periodic after {periods} periods (the cap): the "
                                     f"amplitude changes by {change:.2g} over the last "
                                     f"period"), values
        periods = min(2 * periods, st.max_periods)


class ResponseRunner(Runner):
    """One case = one (amplitude, frequency) of a sweep: :func:`steady_run`.

    Options: ``kind`` (the excitation), ``outputs`` (names), ``settings`` (the fields of
    :class:`ResponseSettings`)."""

    kind = "response"

    def columns(self) -> list[str]:
        """The row's outputs: per output its fit fields, then the run's."""
        cols = []
        for name in self.options["outputs"]:
            u = output_unit(name)
            cols += [f"{name}_{f} [{'rad' if f == 'phase' else u}]" for f in FIT_FIELDS]
        return cols + ["periods [-]", "change [-]", "min_tension [N]",
                       "simulation_wall_time [s]"]

    def _run(self, case: Case) -> tuple[str, str, dict[str, Any]]:
        amp_key, freq_key = excitation_keys(self.options["kind"])
        omega = float(case.overrides[f"top_motion.{freq_key}"])
        amp = float(case.overrides[f"top_motion.{amp_key}"])
        status, msg, vals = steady_run(self.data, self.options["kind"], self.options["outputs"],
                                       omega, amp, ResponseSettings(**self.options["settings"]))
        out = {}
        for name in self.options["outputs"]:
            u = output_unit(name)
            for f in FIT_FIELDS:
                out[f"{name}_{f} [{'rad' if f == 'phase' else u}]"] = vals.get(f"{name}_{f}")
        out.update({"periods [-]": vals.get("periods"), "change [-]": vals.get("change"),
                    "min_tension [N]": vals.get("min_tension"),
                    "simulation_wall_time [s]": vals.get("simulation_wall_time")})
        return status, msg, out


@dataclass
class ResponseSpec(RunnerSpec):
    """The sweep's runner for the executors (picklable: it travels to the workers)."""

    def make(self) -> Runner:
        """A :class:`ResponseRunner`."""
        return ResponseRunner(self.data, self.options)


@dataclass(frozen=True)
class ResponseResult:
    """A frequency-response sweep: time runs and the linear transfer function.

    Attributes
    ----------
    frequencies : ndarray (n_f,)
        Excitation frequencies w, rad/s.
    amplitudes : ndarray (n_a,)
        Excitation amplitudes A, m.
    outputs : list of str
        Output names; ``units`` their units ("N" or "m").
    excitation : str
        ``"heave"``, ``"horizontal"`` or ``"circular"``.
    amplitude : ndarray (n_a, n_f, n_o)
        Steady-state amplitude from the Fourier fit at w (N or m); NaN where a run failed.
    half_range, mean, peak, phase : ndarray (n_a, n_f, n_o)
        (max - min) / 2, the mean, the maximum (N or m) and the phase (rad) over the fit's
        window.
    run_status : ndarray (n_a, n_f) of str
        Per run: ``"solved"`` (periodic), ``"not_converged"`` (not periodic within the cap),
        ``"slack"``, ``"failed"``, ``"invalid_input"``, ``"error"``.
    run_message : ndarray (n_a, n_f) of str
        Per run, what its status means.
    periods, change : ndarray (n_a, n_f)
        Periods run after the ramp; the largest relative change between the last two.
    min_tension : ndarray (n_a, n_f)
        The smallest element tension of each run, N (<= 0: slack, also before a failure).
    linear : LinearResponse
        The transfer function at ``frequencies``; ``linear_curve`` on a dense grid.
    status : Status
        ``"solved"`` when every run is periodic, ``"partial"`` when some are, ``"failed"``
        when none is (or ``"interrupted"``).
    message : str
        Detail of the status.
    diagnostics : dict
        Settings, the model, wall time, workers.
    """

    frequencies: np.ndarray
    amplitudes: np.ndarray
    outputs: list[str]
    units: list[str]
    excitation: str
    amplitude: np.ndarray
    half_range: np.ndarray
    mean: np.ndarray
    peak: np.ndarray
    phase: np.ndarray
    run_status: np.ndarray
    run_message: np.ndarray
    periods: np.ndarray
    change: np.ndarray
    min_tension: np.ndarray
    linear: LinearResponse
    linear_curve: LinearResponse
    status: Status
    message: str
    diagnostics: dict[str, Any] = field(default_factory=dict)

    @property
    def rao(self) -> np.ndarray:
        """amplitude / A: the time runs' response amplitude operator (N/m or m/m)."""
        return self.amplitude / self.amplitudes[:, None, None]

    @property
    def success(self) -> bool:
        """True when every run is periodic."""
        return self.status == "solved"

    def table(self) -> tuple[list[str], list[list[Any]]]:
        """(header, rows) of the CSV: one row per amplitude and frequency."""
        head = ["amplitude [m]", "frequency [rad/s]", "status", "periods [-]", "change [-]",
                "min_tension [N]"]
        for name, u in zip(self.outputs, self.units, strict=True):
            head += [f"{name}_amplitude [{u}]", f"{name}_rao [{u}/m]",
                     f"{name}_half_range [{u}]", f"{name}_max [{u}]",
                     f"{name}_linear_rao [{u}/m]"]
        rows = []
        for a, amp in enumerate(self.amplitudes):
            for f, w in enumerate(self.frequencies):
                row: list[Any] = [float(amp), float(w), str(self.run_status[a, f]),
                                  _num(self.periods[a, f]), _num(self.change[a, f]),
                                  _num(self.min_tension[a, f])]
                for k in range(len(self.outputs)):
                    row += [_num(self.amplitude[a, f, k]), _num(self.rao[a, f, k]),
                            _num(self.half_range[a, f, k]), _num(self.peak[a, f, k]),
                            _num(self.linear.rao[f, k])]
                rows.append(row)
        return head, rows

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the arrays as nested lists (NaN as null), the statuses, the linear
        curves and the natural frequencies."""
        def arr(a: np.ndarray) -> Any:
            return [[[_num(v) for v in r] for r in p] for p in a]

        lin = self.linear
        return {
            "excitation": self.excitation,
            "frequencies_rad_s": [float(w) for w in self.frequencies],
            "amplitudes_m": [float(a) for a in self.amplitudes],
            "outputs": [{"name": n, "unit": u} for n, u in zip(self.outputs, self.units,
                                                                 strict=True)],
            "time_runs": {
                "index": "[amplitude][frequency][output]",
                "amplitude": arr(self.amplitude), "rao": arr(self.rao),
                "half_range": arr(self.half_range), "mean": arr(self.mean),
                "max": arr(self.peak), "phase_rad": arr(self.phase),
                "status": [[str(s) for s in r] for r in self.run_status],
                "message": [[str(s) for s in r] for r in self.run_message],
                "periods": [[_num(v) for v in r] for r in self.periods],
                "change": [[_num(v) for v in r] for r in self.change],
                "min_tension_N": [[_num(v) for v in r] for r in self.min_tension]},
            "linear": {
                "status": lin.status, "message": lin.message,
                "natural_frequencies_rad_s": [float(w) for w in lin.natural_frequencies],
                "index": "[frequency][output]",
                "rao": [[_num(v) for v in r] for r in lin.rao],
                "phase_rad": [[_num(v) for v in r] for r in np.angle(lin.transfer)],
                "curve_frequencies_rad_s": [float(w) for w in self.linear_curve.frequencies],
                "curve_rao": [[_num(v) for v in r] for r in self.linear_curve.rao],
                "diagnostics": lin.diagnostics},
            "diagnostics": self.diagnostics,
        }

    def plot(self, ax: Any = None, **kwargs: Any) -> tuple[Any, Any]:
        """Draw the sweep (matplotlib): ``fig, axes = res.plot()``.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Draw the first output's amplitude ratio on it; None (default): the figure of
            ``cable-ocp response --plot`` (:func:`cable_ocp.plots.response.response_figure`).
        **kwargs
            ``title``.

        Returns
        -------
        (fig, ax)
            The figure and the Axes drawn on (with ``ax=None``: an array of its panels).
        """
        from cable_ocp.plots.accessors import plot_response_result

        return plot_response_result(self, ax, **kwargs)


def _num(x: Any) -> float | None:
    try:
        v = float(x)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


def frequency_response(problem: str | Path | dict[str, Any], frequencies: Sequence[float],
                       amplitudes: Sequence[float] | None = None,
                       outputs: Sequence[str] | str | None = None, *,
                       excitation: str | None = None,
                       settings: ResponseSettings | None = None,
                       damping_ratio: float | None = None,
                       overrides: dict[str, Any] | None = None, workers: int | None = 0,
                       scheduler: Any = None, curve_points: int = 400,
                       progress: Callable[[int, int], None] | None = None) -> ResponseResult:
    """The steady-state response over frequencies and amplitudes (module docstring).

    Parameters
    ----------
    problem : path or dict
        A dynamic problem file (problems/dynamics/*.toml) or its dictionary.
    frequencies : sequence of float
        Excitation frequencies, rad/s (> 0).
    amplitudes : sequence of float, optional
        Excitation amplitudes, m (default: ``[response] amplitudes``, else the scene's
        amplitude of the excitation). Every ``None`` below takes the scene's ``[response]``
        value where it gives one (:mod:`cable_ocp.scene.response`).
    outputs : sequence of str or str, optional
        Output names (default ``top_tension, unit_tension`` and the unit's motion along
        the excitation: ``unit_z`` for heave and circular, ``unit_x`` for horizontal).
    excitation : str, optional
        ``"heave"``, ``"horizontal"`` or ``"circular"`` (default: the one the scene gives);
        the swept motion replaces the scene's harmonic top motion (its other harmonic
        components are set to 0).
    settings : ResponseSettings, optional
        The periodicity test and the runs' lengths (default: ``[response] tolerance``,
        ``max_periods``, ``ramp_periods``, else :class:`ResponseSettings`' defaults).
    damping_ratio : float, optional
        Modal damping ratio of the linear transfer function (-), default
        ``[response] damping_ratio`` or 0.
    overrides : dict, optional
        Dotted keys applied to the problem first (``--set``).
    workers : int or None
        Local worker processes (0: this process, default; None: every core).
    scheduler : str or distributed.Client, optional
        Run the time runs on a dask.distributed cluster instead.
    curve_points : int
        Points of the dense linear curve (default 400), plus the natural frequencies in
        the range.
    progress : callable, optional
        ``progress(done, total)`` after each time run.

    Returns
    -------
    ResponseResult

    Raises
    ------
    CableOCPError
        An invalid scene, excitation, output, frequency or amplitude (named).
    """
    import os

    from cable_ocp.numerics import interrupt
    from cable_ocp.scene.dynamics import dynamic_scene_from_dict

    t0 = time.perf_counter()
    data = problem if isinstance(problem, dict) else read_problem(problem)
    if overrides:
        data = apply_overrides(data, overrides)
    scene = dynamic_scene_from_dict(data)
    dflt = scene.response
    excitation = dflt.excitation if excitation is None else excitation
    if amplitudes is None and dflt.amplitudes:
        amplitudes = list(dflt.amplitudes)
    if outputs is None and dflt.outputs:
        outputs = list(dflt.outputs)
    if damping_ratio is None:
        damping_ratio = dflt.damping_ratio or 0.0
    if settings is None:
        base = ResponseSettings()
        settings = ResponseSettings(
            tolerance=base.tolerance if dflt.tolerance is None else dflt.tolerance,
            max_periods=base.max_periods if dflt.max_periods is None else dflt.max_periods,
            ramp_periods=base.ramp_periods if dflt.ramp_periods is None
            else dflt.ramp_periods)
    kind = excitation_kind(scene) if excitation is None else excitation
    amp_key, freq_key = excitation_keys(kind)
    # the swept motion replaces the scene's harmonic motion: the other components go to 0
    others = {f"top_motion.{a}": 0.0 for k, (a, _, _) in EXCITATIONS.items()
              if k != kind and getattr(scene.top_motion, a) != 0.0}
    if others:
        data = apply_overrides(data, others)
        scene = dynamic_scene_from_dict(data)
    check_response_scene(scene, kind)
    freqs = np.asarray(frequencies, dtype=float).ravel()
    if freqs.size == 0 or not np.all(np.isfinite(freqs)) or np.any(freqs <= 0):
        raise CableOCPError(f"--frequencies: expected finite frequencies > 0 (rad/s), got "
                            f"{freqs.tolist()}")
    if amplitudes is None:
        a0 = float(getattr(scene.top_motion, amp_key))
        if a0 == 0.0:
            raise CableOCPError(f"--amplitudes: the scene gives no top_motion.{amp_key}; "
                                "give the amplitudes (m)")
        amplitudes = [a0]
    amps = np.asarray(amplitudes, dtype=float).ravel()
    if amps.size == 0 or not np.all(np.isfinite(amps)) or np.any(amps <= 0):
        raise CableOCPError(f"--amplitudes: expected amplitudes > 0 (m), got {amps.tolist()}")
    n_nodes = scene.simulation.segments + 1
    if outputs is None:
        outputs = ["top_tension", "unit_tension",
                   "unit_x" if kind == "horizontal" else "unit_z"]
    names = parse_outputs(outputs, n_nodes)
    st = settings or ResponseSettings()
    # the linear transfer function, at the sweep and on a dense curve
    lin = linear_response(scene, freqs, names, kind, damping_ratio)
    lo, hi = float(freqs.min()), float(freqs.max())
    dense = np.linspace(lo, hi, max(2, curve_points)) if hi > lo else freqs.copy()
    nat = lin.natural_frequencies
    dense = np.unique(np.concatenate([dense, nat[(nat >= lo) & (nat <= hi)]]))
    curve = linear_response(scene, dense, names, kind, damping_ratio)
    # the time runs, as batch cases
    cases = [Case(index=i, overrides={f"top_motion.{amp_key}": float(a),
                                      f"top_motion.{freq_key}": float(w)})
             for i, (a, w) in enumerate((a, w) for a in amps for w in freqs)]
    spec = ResponseSpec("response", data, {"kind": kind, "outputs": names,
                                           "settings": st.__dict__.copy()})
    rows: dict[int, dict[str, Any]] = {}

    def on_row(row: dict[str, Any]) -> None:
        rows[row["case"]] = row
        if progress is not None:
            progress(len(rows), len(cases))

    n_workers = (os.cpu_count() or 1) if workers is None else int(workers)
    interrupted = False
    try:
        if scheduler is not None:
            run_dask(spec, [[c] for c in cases], on_row, scheduler)
        elif n_workers == 0 or len(cases) <= 1:
            run_serial(spec, [[c] for c in cases], on_row)
        else:
            run_local(spec, [[c] for c in cases], on_row, n_workers)
        interrupt.check()
    except KeyboardInterrupt:
        interrupted = True
    shape = (amps.size, freqs.size)
    fits = {f: np.full(shape + (len(names),), np.nan) for f in FIT_FIELDS}
    run_status = np.full(shape, "interrupted", dtype=object)
    run_message = np.full(shape, "not run (interrupted)", dtype=object)
    periods = np.full(shape, np.nan)
    change = np.full(shape, np.nan)
    min_tension = np.full(shape, np.nan)
    for i in range(len(cases)):
        row = rows.get(i)
        if row is None:
            continue
        a, f = divmod(i, freqs.size)
        run_status[a, f] = str(row["status"])
        run_message[a, f] = str(row.get("message", ""))
        periods[a, f] = row.get("periods [-]") if row.get("periods [-]") is not None \
            else np.nan
        change[a, f] = row.get("change [-]") if row.get("change [-]") is not None else np.nan
        if row.get("min_tension [N]") is not None:
            min_tension[a, f] = row["min_tension [N]"]
        for k, name in enumerate(names):
            u = output_unit(name)
            for fld in FIT_FIELDS:
                v = row.get(f"{name}_{fld} [{'rad' if fld == 'phase' else u}]")
                fits[fld][a, f, k] = np.nan if v is None else v
    good = int(np.sum(run_status == "solved"))
    total = run_status.size
    if interrupted:
        status, msg = Status.INTERRUPTED, f"interrupted after {len(rows)} of {total} runs"
    elif good == total:
        status, msg = Status.SOLVED, f"{total} runs, all periodic"
    else:
        bad = {str(s): int(np.sum(run_status == s)) for s in np.unique(run_status)
               if s != "solved"}
        status = Status.PARTIAL if good else Status.FAILED
        msg = (f"{good} of {total} runs periodic; "
               + ", ".join(f"{n} {s}" for s, n in sorted(bad.items())))
    diag = {"model": scene.simulation.model, "segments": scene.simulation.segments,
            "settings": st.__dict__.copy(), "damping_ratio": float(damping_ratio),
            "workers": "dask" if scheduler is not None else n_workers,
            "wall_time_s": time.perf_counter() - t0,
            "simulation_wall_time_s": float(sum(r.get("simulation_wall_time [s]") or 0.0
                                                for r in rows.values()))}
    return ResponseResult(
        frequencies=freqs, amplitudes=amps, outputs=names,
        units=[output_unit(n) for n in names], excitation=kind,
        amplitude=fits["amplitude"], half_range=fits["half_range"], mean=fits["mean"],
        peak=fits["max"], phase=fits["phase"], run_status=run_status,
        run_message=run_message, periods=periods, change=change, min_tension=min_tension,
        linear=lin,
        linear_curve=curve, status=status, message=msg, diagnostics=diag)
