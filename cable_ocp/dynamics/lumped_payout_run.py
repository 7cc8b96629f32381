"""A lumped3d scene with a pay-out, run: :func:`simulate_payout`.

:class:`cable_ocp.dynamics.lumped_scene.LumpedSceneModel` dispatches here when
``[top_motion]`` varies the length (the keys of the axial and planar models:
``payout_law``, ``payout_speed``, ``payout_acceleration``, ``payout_amplitude``,
``payout_frequency``, ``ramp_time``). The line starts at the fixed-length model's static
state (:func:`cable_ocp.dynamics.lumped_scene.lumped_start`, at the initial length) and
runs on :class:`cable_ocp.dynamics.lumped_payout.PayoutLine` with
``[simulation] element_length`` (default: the top segment's initial length, L0 /
``simulation.segments`` for a single ``[cable]``).

The result has ``simulation.segments + 1`` output nodes at the fixed fractions
y = s / L(t) = i / segments of the unstretched length (as the axial and planar models'
fixed domain), linearly interpolated in s between the model's nodes (exact at the unit
and the winch); its segment tensions are interpolated at the output segments' middles,
its top tension the force of the winch on the line (the top segment's pull with its
share of the weight, drag and inertia at the winch, as the fixed-length model's). The
number of the model's segments over time, the splits and merges and the element length
are in ``diagnostics["payout"]``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import casadi as ca
import numpy as np

from cable_ocp.dynamics.lumped_payout import MERGE, SPLIT, PayoutLine, PayoutRun
from cable_ocp.dynamics.result import (
    SimulationResult,
    coarse_step_warnings,
    slack_report,
    until_slack,
)
from cable_ocp.dynamics.snap import snap_report
from cable_ocp.errors import CableOCPError
from cable_ocp.scene.dynamics import DynamicScene
from cable_ocp.scene.motion import length_expr

if TYPE_CHECKING:
    from cable_ocp.dynamics.lumped_scene import LumpedSceneModel

__all__ = ["PAYOUT_SLACK_MESSAGE", "length_function", "payout_line", "resample",
           "simulate_payout"]

#: the slack message of a lumped3d pay-out
PAYOUT_SLACK_MESSAGE = ("slack: a segment near s = {location:.4g} m from end_a first went "
                        "slack at t = {t:.6g} s (recorded samples); Huang (1992) ch. 5 "
                        "excludes slack cable: {action}")


def length_function(scene: DynamicScene) -> Callable[[float], tuple[float, float]]:
    """``length(t) -> (L, L_t)``: the scene's pay-out law (m, m/s) at t (s)
    (:func:`cable_ocp.scene.motion.length_expr`).

    Parameters
    ----------
    scene : DynamicScene
        The scene.
    """
    t = ca.SX.sym("t")
    expr = length_expr(scene.top_motion, scene.length, t)
    fn = ca.Function("L", [t], [expr, ca.jacobian(expr, t)])

    def length(tt: float) -> tuple[float, float]:
        a, b = fn(tt)
        return float(a), float(b)

    return length


def payout_line(model: LumpedSceneModel) -> PayoutLine:
    """The :class:`~cable_ocp.dynamics.lumped_payout.PayoutLine` of a lumped3d scene model.

    Parameters
    ----------
    model : LumpedSceneModel
        The scene's fixed-length model (its segments at t = 0).
    """
    sim = model.scene.simulation
    if sim.scheme != "midpoint":
        raise CableOCPError(f'simulation.scheme = "{sim.scheme}": a lumped3d pay-out runs '
                            'the midpoint rule only; give scheme = "midpoint"')
    le = sim.element_length
    line = PayoutLine(model.params, length_function(model.scene), element_length=le,
                      tol=sim.tolerance, max_iter=sim.max_iterations)
    top0 = float(model.params.segment_length[-1])
    if not MERGE * line.element_length <= top0 <= SPLIT * line.element_length:
        raise CableOCPError(f"simulation.element_length = {le} m: the top segment's initial "
                            f"length {top0:.4g} m (L0 / segments) must lie between {MERGE} "
                            f"and {SPLIT} element lengths")
    return line


def resample(run: PayoutRun, count: int) -> dict[str, np.ndarray]:
    """The recorded states on ``count + 1`` output nodes at s = i L(t) / count.

    Parameters
    ----------
    run : PayoutRun
        The run.
    count : int
        Output segments.

    Returns
    -------
    dict
        ``t`` (s), ``positions`` (n_t, count + 1, 3, m), ``velocities`` (m/s),
        ``tensions`` (n_t, count, N), ``top_tension`` (N), ``length`` (m), ``segments``
        (the model's, per time).
    """
    n_t = len(run.states)
    pos = np.zeros((n_t, count + 1, 3))
    vel = np.zeros_like(pos)
    tens = np.zeros((n_t, count))
    for k, (st, te) in enumerate(zip(run.states, run.tensions, strict=True)):
        s = np.concatenate([[0.0], np.cumsum(st.lengths)])
        y = np.linspace(0.0, s[-1], count + 1)
        for c in range(3):
            pos[k, :, c] = np.interp(y, s, st.r[:, c])
            vel[k, :, c] = np.interp(y, s, st.v[:, c])
        tens[k] = np.interp(0.5 * (y[:-1] + y[1:]), 0.5 * (s[:-1] + s[1:]), te)
    return {"t": np.array([st.t for st in run.states]), "positions": pos, "velocities": vel,
            "tensions": tens, "top_tension": np.array([np.linalg.norm(f) for f in run.top_force]),
            "length": np.array([float(np.sum(st.lengths)) for st in run.states]),
            "segments": np.array([st.segments for st in run.states])}


def simulate_payout(model: LumpedSceneModel,
                    progress: Callable[[int, int], None] | None = None) -> SimulationResult:
    """Time-domain simulation of a lumped3d scene with a pay-out.

    Parameters
    ----------
    model : LumpedSceneModel
        The scene's model.
    progress : callable, optional
        ``progress(done, total)`` in steps.
    """
    scene = model.scene
    sim = scene.simulation
    line = payout_line(model)
    x0, info = model.static_positions()
    if x0 is None:
        return SimulationResult.failed(sim.segments, info["message"], "lumped3d", sim.scheme,
                                       {"start": info})
    total = sim.steps

    def prog(t_done: float, duration: float) -> None:  # noqa: ARG001 - the total is known
        if progress is not None:
            progress(min(total, int(round(t_done / sim.time_step))), total)

    run = line.run(np.asarray(x0, float), sim.duration, sim.time_step,
                   record_every=sim.output_every, progress=prog)
    out = resample(run, sim.segments)
    ts = out["t"]
    min_t = np.min(out["tensions"], axis=1) if ts.size else np.zeros(0)
    slack_tol = 1e-9 * line.force_scale
    slack_at = np.flatnonzero(np.array([np.min(te) <= slack_tol for te in run.tensions]))
    t_slack = seg = loc = None
    if slack_at.size:
        k = int(slack_at[0])
        st = run.states[k]
        seg = int(np.argmin(run.tensions[k]))
        loc = float(np.sum(st.lengths[:seg]) + 0.5 * st.lengths[seg])
        t_slack = float(ts[k])
    keep = until_slack(ts, t_slack, sim.output_step, sim.on_slack)
    if keep is not None:
        out = {k: (v[keep] if isinstance(v, np.ndarray) and v.shape[:1] == ts.shape else v)
               for k, v in out.items()}
        ts = out["t"]
        min_t = min_t[keep]
    slack, status, message = slack_report(
        t_slack, seg, loc, status=run.status, message=run.message, on_slack=sim.on_slack,
        template=PAYOUT_SLACK_MESSAGE,
        continued="the run continued: a slack segment carries no tension (the smooth "
                  "no-compression law) and the line may fold there, which the model follows "
                  "only approximately")
    tm = scene.top_motion
    warnings = coarse_step_warnings(sim.time_step, (
        ("heave_frequency", tm.heave_frequency),
        ("horizontal_frequency", tm.horizontal_frequency),
        ("circular_frequency", tm.circular_frequency),
        ("payout_frequency", tm.payout_frequency)))
    sim_time = float(ts[-1] - ts[0]) if ts.size > 1 else 0.0
    payout: dict[str, Any] = {
        "element_length_m": line.element_length, "split_above": SPLIT, "merge_below": MERGE,
        "splits": run.splits, "merges": run.merges,
        "segments_min": int(np.min(out["segments"])), "segments_max":
            int(np.max(out["segments"])), "segments_end": int(out["segments"][-1]),
        "max_event_momentum_jump_Ns": max((float(np.max(np.abs(e["momentum_jump"])))
                                           for e in run.events), default=0.0)}
    diagnostics = {"steps": len(ts) and int(round(ts[-1] / sim.time_step)),
                   "segments": sim.segments, "start": info, "payout": payout,
                   "tolerance": sim.tolerance, "min_strain": run.min_strain,
                   "wall_time_per_simulated_second":
                       run.wall_time_s / sim_time if sim_time else None}
    return SimulationResult.from_nodes(
        out["positions"], t=ts, length=out["length"], top_tension=out["top_tension"],
        segment_tensions=out["tensions"], node_velocities=out["velocities"],
        min_tension=float(np.min(min_t)) if min_t.size else math.nan, slack=slack,
        snap=snap_report(ts, out["tensions"], (np.arange(sim.segments) + 0.5) / sim.segments
                         * np.asarray(out["length"])[:, None]),
        status=status, message=message, warnings=warnings, wall_time_s=run.wall_time_s,
        model="lumped3d", scheme=sim.scheme, diagnostics=diagnostics)
