"""A controlled deployment through resonance: the unit is lowered with the compensator on.

The heave scene's ``[deployment]`` table lowers the unit of ``[unit] cable_scene`` from the
cable scene's length to ``final_length`` at ``payout_speed`` (after the warm-up, the speed
ramped in and out over ``ramp_time``, 20 s held at the end) in the scene's sea, on the cable plant
(:mod:`cable_ocp.heave.closed_loop`): the axial plant of a ``model = "axial"`` cable scene, or,
for ``model = "lumped3d"``, the 3D lumped-mass line whose nodes enter and leave at the winch
(:class:`cable_ocp.heave.lumped_deploy.LumpedPayoutPlant`: the unit lowered in a current of
any heading and profile, e.g. one that turns with depth). On the way the first axial
natural frequency ``omega_1(L)`` falls through the wave band (Huang (1992), section 3.3.5
lowers through resonance without control), and the design model (6.2) changes with it:
``a(L) ~ 1 / omega_1(L)^2``.

Three compensators are compared on the same sea:

* ``passive``: the compensating winch held still;
* ``lqr_fixed``: the LQR and Kalman filter (three sensors, as on the cable plant) designed
  once, on ``a, b`` identified at ``fixed_length`` (default: the start, where a crew would
  identify the line before lowering);
* ``lqr_scheduled``: the same design tabulated over ``schedule_lengths`` from the
  identification (6.2.3) at each length; the gain, the filter's gains and its sampled model
  are interpolated linearly in the paid-out length as it changes (gain scheduling).

The unit's heave is measured from the static depth at the current paid-out length (in the
current, on the lumped3d plant). Results per ``window`` metres of length: unit heave RMS,
tension extremes at the unit and the top, slack samples; on the lumped3d plant also the
unit's mean horizontal position and the line's segments. A Ctrl-C during a run keeps the
runs finished (the others ``interrupted``, no per-length rows).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from cable_ocp.heave.axial_plant import AxialCablePlant
from cable_ocp.heave.closed_loop import INTERRUPTED, LoopRun, make_wave, run_loop, unstable_bound
from cable_ocp.heave.design import cable_controller, design_damping, design_table
from cable_ocp.heave.identify_cable import CableIdentification, identify_from_cable
from cable_ocp.heave.loop_plants import CableLine, WinchedLine
from cable_ocp.heave.lumped_deploy import LumpedPayoutPlant
from cable_ocp.heave.metrics import (
    CableComparison,
    CableMetrics,
    cable_run_metrics,
    cable_status,
    limit_excess,
    limit_warning,
    no_cable_metrics,
    reduction_pct,
)
from cable_ocp.numerics import interrupt
from cable_ocp.scene.dynamics import DynamicScene
from cable_ocp.scene.heave import HeaveScene

__all__ = ["deploy", "length_history", "summary"]

CONTROLLERS = ("passive", "lqr_fixed", "lqr_scheduled")


def length_history(t: np.ndarray, start: float, final: float, speed: float, t0: float,
                   ramp: float) -> np.ndarray:
    """Paid-out length (m) at times ``t`` (s): ``start`` until ``t0``, then moving to
    ``final`` with the speed ``v (r(s) - r(s - T_c))``, ``s = t - t0``, ``T_c = |final -
    start| / v`` and ``r`` the ramp ``10 x^3 - 15 x^4 + 6 x^5`` over ``ramp`` s: the speed
    rises smoothly to ``v`` and falls smoothly to 0 (no acceleration step at either end),
    covering exactly the distance. ``ramp`` is cut to ``T_c`` if longer.

    Parameters
    ----------
    t : numpy.ndarray
        Times, s.
    start, final : float
        Paid-out length at the start and the end, m.
    speed : float
        Pay-out speed, m/s.
    t0 : float
        Start of the pay-out, s.
    ramp : float
        Ramp time of the speed, s.
    """
    dist = abs(final - start)
    tc = dist / speed
    ramp = min(ramp, tc)

    def big_r(s: np.ndarray) -> np.ndarray:  # integral of the ramp from 0 to s
        s = np.maximum(s, 0.0)
        if ramp <= 0:
            return s
        x = np.clip(s / ramp, 0.0, 1.0)
        return np.where(s < ramp, ramp * x**4 * (2.5 - 3.0 * x + x**2), s - 0.5 * ramp)

    s = np.asarray(t, dtype=float) - t0
    d = speed * (big_r(s) - big_r(s - tc))
    sign = 1.0 if final >= start else -1.0
    return start + sign * np.minimum(d, dist)


def _schedule(sc: HeaveScene, dyn: DynamicScene, ident0: CableIdentification,
              lengths: np.ndarray) -> list[CableIdentification]:
    out = []
    for L in lengths:
        if abs(L - ident0.length) < 1e-9:
            out.append(ident0)
        else:
            out.append(identify_from_cable(sc, dyn, length=float(L)))
    return out


def deploy(scene: HeaveScene, design: HeaveScene, cable_scene: DynamicScene,
           ident0: CableIdentification, extra: dict,
           progress: Callable[[int, int, Any], None] | None = None) -> CableComparison:
    """Run the deployment of ``scene.deployment`` (module docstring).

    ``design`` is the design scene (:func:`cable_ocp.heave.design.design_scene`), ``ident0``
    the identification at the start. Returns a
    :class:`~cable_ocp.heave.metrics.CableComparison` whose ``json_extra["deployment"]``
    holds the schedule and the per-length table.

    Parameters
    ----------
    scene : HeaveScene
        The heave scene with ``[deployment]``.
    design : HeaveScene
        The design scene.
    cable_scene : DynamicScene
        The cable scene (axial or lumped3d).
    ident0 : CableIdentification
        The identification at the start.
    extra : dict
        Top-level JSON fields so far (``plant``, ``design_model``, ``identified``).
    progress : callable, optional
        ``progress(done, total, None)`` every 100 samples.
    """
    from cable_ocp.heave import design_loop as sm
    from cable_ocp.heave.identify_cable import first_frequency, identified_json

    dep = scene.deployment
    assert dep is not None and dep.final_length is not None
    c = scene.controller
    h = c.sample_time
    L0, L1 = cable_scene.length, dep.final_length
    lo, hi = sorted((L0, L1))
    lengths = design_lengths(scene, cable_scene)
    lf = dep.fixed_length if dep.fixed_length is not None else L0
    idents = _schedule(scene, cable_scene, ident0, lengths)
    a_tab = np.array([i.linear.a for i in idents])
    warnings: list[str] = []
    b_tab = np.empty(len(idents))
    for j, (i, L) in enumerate(zip(idents, lengths, strict=True)):
        b_tab[j], w = design_damping(i.linear.b, f"schedule at {L:g} m")
        if w:
            warnings.append(w)
    fixed_ident = next((i for i, L in zip(idents, lengths, strict=True) if abs(L - lf) < 1e-9),
                       None) or identify_from_cable(scene, cable_scene, length=lf)
    sched, p = design_table(design, lengths, a_tab, b_tab)
    b_fixed, w = design_damping(fixed_ident.linear.b, f"fixed design at {lf:g} m")
    if w and w not in warnings:
        warnings.append(w)
    fixed, _ = design_table(design, np.array([lf]), np.array([fixed_ident.linear.a]),
                               np.array([b_fixed]))

    warm = scene.simulation.warmup
    T = warm + abs(L1 - L0) / dep.payout_speed + dep.ramp_time + 20.0
    n_ctrl = int(math.ceil(T / h))
    models = sm.build_models(design)
    lumped = cable_scene.simulation.model == "lumped3d"
    plant = (LumpedPayoutPlant(cable_scene, h, (lo, hi)) if lumped
             else AxialCablePlant(cable_scene, h))
    m = plant.substeps
    t_f, x0_f, _ = sm.wave_realisation(models.plant, n_ctrl * h + 2 * h,
                                       h / scene.simulation.substeps, scene.simulation.seed)
    wave = make_wave(t_f, x0_f, h, m, n_ctrl,
                        lambda t: length_history(t, L0, L1, dep.payout_speed, warm,
                                                 dep.ramp_time), 0.5 * warm)
    rng = np.random.default_rng(scene.simulation.seed + 1000)
    noise = rng.standard_normal((n_ctrl + 1, 3)) * np.array(
        [c.measurement_noise, c.winch_noise, c.boom_tip_noise])
    total = n_ctrl * len(CONTROLLERS)
    bound = unstable_bound(wave.x0)
    runs: dict[str, LoopRun] = {}
    offsets: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    energy: dict[str, float | None] = {}
    for idx, name in enumerate(CONTROLLERS):
        table = {"passive": None, "lqr_fixed": fixed, "lqr_scheduled": sched}[name]
        ctrl = cable_controller(name, table, None)
        energy[name] = ctrl.energy_index  # None for the schedule: the gain changes with L

        def prog(k: int, base: int = idx * n_ctrl) -> None:
            if progress is not None:
                progress(base + k, total, None)

        try:
            runs[name] = run_loop(WinchedLine(scene, CableLine(plant), wave, noise), ctrl,
                                  n_ctrl, bound, prog)
            if lumped:  # the unit's (x, y) and the segments at the end of each sample
                offsets[name] = (np.array(plant.unit_xy).reshape(-1, 2),
                                 np.array(plant.segment_counts, dtype=int))
        except (KeyboardInterrupt, Exception) as exc:  # a CasADi error may be a Ctrl-C
            # an interruption: keep the runs finished; this one and the rest: interrupted
            if not interrupt.is_interruption(exc):
                raise
            break
    stopped = len(runs) < len(CONTROLLERS)
    if progress is not None and not stopped:  # (after a Ctrl-C it would raise it again)
        progress(total, total, None)

    metrics, statuses, messages = {}, {}, {}
    base = None
    for name, run in runs.items():
        d = cable_run_metrics(design, run, energy[name])
        statuses[name], messages[name] = cable_status(run, d, cable_scene.simulation.model)
        if statuses[name] == "solved" or statuses[name] == "slack":
            lim = limit_warning(name, limit_excess(design, run.trace, run.commands, h))
            if lim:
                warnings.append(lim)
        if name == "passive":
            base = d["heave_rms"]
        d["reduction_pct"] = reduction_pct(d["heave_rms"], base)
        metrics[name] = CableMetrics(d)
    for name in CONTROLLERS[len(runs):]:
        statuses[name], messages[name] = INTERRUPTED
        metrics[name] = CableMetrics(no_cable_metrics())

    window = dep.window if dep.window is not None else (hi - lo) / 40.0
    table = _per_length(runs, scene, lo, hi, window)
    if lumped:
        _per_length_3d(table, runs, offsets, scene, lo, hi, window)
    w1 = np.array([first_frequency(cable_scene.with_overrides({"cable.length": float(L)}))
                   if abs(L - cable_scene.length) > 1e-9 else ident0.omega_1 for L in lengths])
    extra = dict(extra)
    extra["deployment"] = {
        "start_length": L0, "final_length": L1, "payout_speed": dep.payout_speed,
        "duration": n_ctrl * h, "sample_time": h, "fixed_length": lf,
        "schedule": {"lengths": lengths.tolist(), "a": a_tab.tolist(), "b": b_tab.tolist(),
                     "b_identified": [i.linear.b for i in idents],
                     "omega_1": w1.tolist(), "a_modal": (1.0 / w1**2).tolist(),
                     "fit_pct": [i.linear.fit_pct for i in idents]},
        "fixed_identified": identified_json(fixed_ident),
        "window": window, "per_length": table,
    }
    extra["cable_plant"] = {"segments": plant.model.n, "time_step": plant.dt, "substeps": m}
    if lumped:
        extra["cable_plant"].update(
            model="lumped3d", element_length=plant.line.element_length,
            segments_end={k: int(v[1][-1]) if v[1].size else None for k, v in offsets.items()})
    traces = {k: r.trace for k, r in runs.items()}
    return CableComparison(models.sigma_uncontrolled, metrics, traces, models, None, 0,
                              statuses, messages, base, warnings, stopped,
                              json_extra=extra)


def _per_length(runs: dict[str, LoopRun], sc: HeaveScene, lo: float, hi: float,
                window: float) -> dict[str, Any]:
    """Per window of paid-out length: centre (m) and, per controller, the unit's heave from
    the static depth at the paid-out length (RMS, mean, standard deviation about the mean,
    largest magnitude; m), tension extremes at the unit and the top (N) and slack samples.

    The mean is the quasi-steady offset of a pay-out (the drag of the moving line and unit
    lifts the unit by centimetres, the pay-out's acceleration at the ends shifts it); the
    standard deviation is the heave the compensator acts on."""
    edges = np.arange(lo, hi + 0.5 * window, window)
    if edges[-1] < hi - 1e-9:
        edges = np.append(edges, hi)
    centres = 0.5 * (edges[:-1] + edges[1:])
    out: dict[str, Any] = {"length": centres.tolist()}
    h = sc.controller.sample_time
    warm = sc.simulation.warmup
    for name, run in runs.items():
        tr = run.trace
        ok = (tr.t >= warm - 1e-12) & np.isfinite(tr.x)  # NaN after a run that stopped
        idx = np.clip(np.searchsorted(edges, tr.length, side="right") - 1, 0, centres.size - 1)
        ks = np.arange(tr.min_element_tension.size)
        lk = tr.length[ks * (tr.t.size - 1) // max(1, tr.min_element_tension.size)]
        kidx = np.clip(np.searchsorted(edges, lk, side="right") - 1, 0, centres.size - 1)
        kok = ks * h >= warm - 1e-12
        rows: dict[str, list] = {k: [] for k in ("heave_rms", "heave_mean", "heave_std",
                                                 "heave_max", "tension_unit_min",
                                                 "tension_unit_max", "tension_top_min",
                                                 "tension_top_max", "slack_samples")}
        for j in range(centres.size):
            sel = ok & (idx == j)
            if not np.any(sel):
                for v in rows.values():
                    v.append(None)
                continue
            rows["heave_rms"].append(float(np.sqrt(np.mean(tr.x[sel] ** 2))))
            rows["heave_mean"].append(float(np.mean(tr.x[sel])))
            rows["heave_std"].append(float(np.std(tr.x[sel])))
            rows["heave_max"].append(float(np.max(np.abs(tr.x[sel]))))
            rows["tension_unit_min"].append(float(np.min(tr.tension_unit[sel])))
            rows["tension_unit_max"].append(float(np.max(tr.tension_unit[sel])))
            rows["tension_top_min"].append(float(np.min(tr.tension_top[sel])))
            rows["tension_top_max"].append(float(np.max(tr.tension_top[sel])))
            rows["slack_samples"].append(int(np.count_nonzero(
                (tr.min_element_tension <= 0.0) & kok & (kidx == j))))
        out[name] = rows
    return out


def _per_length_3d(table: dict[str, Any], runs: dict[str, LoopRun],
                   offsets: dict[str, tuple[np.ndarray, np.ndarray]], sc: HeaveScene,
                   lo: float, hi: float, window: float) -> None:
    """Add to the per-length ``table`` the unit's mean horizontal position (``unit_x``,
    ``unit_y``, m) and the largest number of the line's segments per window (lumped3d)."""
    edges = np.arange(lo, hi + 0.5 * window, window)
    if edges[-1] < hi - 1e-9:
        edges = np.append(edges, hi)
    n_win = edges.size - 1
    warm = sc.simulation.warmup
    h = sc.controller.sample_time
    for name, (xy, segs) in offsets.items():
        tr = runs[name].trace
        m = (tr.t.size - 1) // max(1, xy.shape[0]) if xy.shape[0] else 1
        k = np.arange(xy.shape[0])
        lk = tr.length[np.minimum((k + 1) * m, tr.length.size - 1)]
        idx = np.clip(np.searchsorted(edges, lk, side="right") - 1, 0, n_win - 1)
        ok = (k + 1) * h >= warm - 1e-12
        rows = table[name]
        rows["unit_x"], rows["unit_y"], rows["segments"] = [], [], []
        for j in range(n_win):
            sel = ok & (idx == j)
            if not np.any(sel):
                for key in ("unit_x", "unit_y", "segments"):
                    rows[key].append(None)
                continue
            rows["unit_x"].append(float(np.mean(xy[sel, 0])))
            rows["unit_y"].append(float(np.mean(xy[sel, 1])))
            rows["segments"].append(int(np.max(segs[sel])))


def summary(per_length: dict[str, Any], sample_time: float) -> dict[str, dict[str, Any]]:
    """Per controller, the deployment over its windows of length (the README's table): the
    unit's heave standard deviation (median and largest over the windows, m, and the window
    centre of the largest, m), the lowest and highest tension at the unit (N), the slack time
    (s: slack samples times ``sample_time``) and the windows with slack; windows without
    samples (a run that stopped) are left out, a value over none is None.

    Parameters
    ----------
    per_length : dict
        The ``per_length`` table of the deployment's JSON (:func:`deploy`).
    sample_time : float
        The control sample, s.
    """
    centres = np.asarray(per_length["length"], dtype=float)
    out: dict[str, dict[str, Any]] = {}
    for name, rows in per_length.items():
        if name == "length":
            continue
        have = np.array([v is not None for v in rows["heave_std"]], dtype=bool)
        std = np.array([v for v in rows["heave_std"] if v is not None], dtype=float)
        slack = [int(v) for v in rows["slack_samples"] if v is not None]
        t_lo = [v for v in rows["tension_unit_min"] if v is not None]
        t_hi = [v for v in rows["tension_unit_max"] if v is not None]
        j = int(np.argmax(std)) if std.size else None
        out[name] = {
            "heave_std_median": float(np.median(std)) if std.size else None,
            "heave_std_max": float(std[j]) if j is not None else None,
            "heave_std_max_at": float(centres[have][j]) if j is not None else None,
            "tension_unit_min": min(t_lo) if t_lo else None,
            "tension_unit_max": max(t_hi) if t_hi else None,
            "slack_time": sum(slack) * sample_time,
            "slack_windows": sum(1 for v in slack if v > 0),
            "windows": int(centres.size)}
    return out


def design_lengths(scene: HeaveScene, cable_scene: DynamicScene) -> np.ndarray:
    """The schedule's lengths (m): ``[deployment] schedule_lengths`` or 7 from start to end.

    Parameters
    ----------
    scene : HeaveScene
        The heave scene with ``[deployment]``.
    cable_scene : DynamicScene
        Its cable scene (the start length).
    """
    dep = scene.deployment
    assert dep is not None and dep.final_length is not None
    if dep.schedule_lengths:
        return np.asarray(dep.schedule_lengths, dtype=float)
    lo, hi = sorted((cable_scene.length, dep.final_length))
    return np.linspace(lo, hi, 7)
