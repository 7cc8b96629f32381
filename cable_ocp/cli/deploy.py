"""``cable-ocp deploy``: the optimal pay-out (or haul-in) schedule of a dynamic scene's
``[deployment]`` (parse, call :func:`cable_ocp.schedule.planning.verified_schedule`: the
OCP and its forward check, format).

docs/deployment.md describes the problem and the outputs; docs/cli.md the command.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.cli import output as out
from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import interrupt

#: lengths of the deployment chart drawn in the figure (few: one eigenproblem each)
CHART_LENGTHS = 11


def register(sub: argparse._SubParsersAction, parent: argparse.ArgumentParser) -> None:
    """Add ``deploy``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The ``cable-ocp`` parser's subparsers, to which the command is added.
    parent : argparse.ArgumentParser
        The common options (``--quiet``, ``--debug``: :func:`cable_ocp.cli.output.common_parent`),
        a parent of every parser added.
    """
    d = sub.add_parser(
        "deploy", parents=[parent],
        help="the fastest pay-out (or haul-in) schedule of a subsea unit inside the "
             "limits of [deployment] (an optimal-control problem; docs/deployment.md)",
        description="Solve the optimal pay-out schedule of a dynamic scene's [deployment] "
                    "table: lower the unit from cable.length to target_length in the least "
                    "time, the vessel's heave given, inside the speed, acceleration, power "
                    "and tension limits. Report the time to depth against the fastest "
                    "constant speed and the limits that bind. Exit 0 solved, 1 infeasible "
                    "or failed (the message names the limit), 2 invalid input.")
    d.add_argument("file", help="dynamic scene with a [deployment] table (UTF-8 TOML), e.g. "
                                "problems/dynamics/deploy_small.toml")
    out.add_set_option(d)
    d.add_argument("--segments", type=int, metavar="N",
                   help="elements of the OCP's line (default deployment.segments, else "
                        "simulation.segments)")
    d.add_argument("--time-step", type=float, metavar="S", dest="time_step",
                   help="the OCP's nominal step in s (default deployment.time_step, else "
                        "simulation.time_step)")
    d.add_argument("--hold", type=float, metavar="S",
                   help="s after the arrival, the winch stopped, through which the OCP "
                        "keeps the limits (default deployment.hold, else the forward "
                        "check's 20 s hold; 0: the OCP ends at the arrival)")
    d.add_argument("--check-rounds", type=int, metavar="N", dest="check_rounds",
                   help="re-solves the forward check may ask for (default "
                        "deployment.check_rounds, 4; 0: the OCP alone, not re-simulated)")
    d.add_argument("--compare", action="store_true",
                   help="also find the fastest constant speed on the forward simulator "
                        "(bisection, one simulation per speed tried)")
    d.add_argument("--unseen", action="store_true",
                   help="also re-simulate the schedule, and the constant speed of the same "
                        "duration, on the [deployment.sea]'s unseen realisations (its "
                        "'unseen' count, seeds disjoint from the design ones) and count the "
                        "runs that go slack, exceed tension_max, fall under tension_min")
    d.add_argument("--receding", action="store_true",
                   help="also run the receding-horizon form (re-planned every "
                        "deployment.replan_interval s with deployment.preview s of the sea, "
                        "the forward check's margins kept) on the unseen realisations, "
                        "against the open-loop schedule, both re-simulated")
    out.add_json_option(d, "the status, the schedule (t, L, v, a), the tensions per "
                           "realisation, the forward check and the comparisons")
    out.add_csv_option(d, "the schedule: t, L, v, a and per realisation the smallest and "
                          "largest tension along the line, the unit and the top tension")
    out.add_plot_option(d, "length (with the resonant lengths), speed, the tension envelope "
                           "and the winch's power against time")
    d.set_defaults(func=cmd_deploy)


def _check_options(args: argparse.Namespace) -> None:
    from cable_ocp.scene.deployment import MAX_HOLD

    if args.segments is not None and not 1 <= args.segments <= 2000:
        raise CableOCPError(f"--segments {args.segments}: give 1..2000 elements")
    if args.time_step is not None and not (math.isfinite(args.time_step)
                                           and args.time_step > 0.0):
        raise CableOCPError(f"--time-step {args.time_step}: give a step > 0 s")
    if args.hold is not None and not (math.isfinite(args.hold)
                                      and 0.0 <= args.hold <= MAX_HOLD):
        raise CableOCPError(f"--hold {args.hold}: give 0..{MAX_HOLD:g} s after the arrival "
                            "(0: the OCP ends at the arrival)")
    if args.check_rounds is not None and not 0 <= args.check_rounds <= 10:
        raise CableOCPError(f"--check-rounds {args.check_rounds}: give 0..10 re-solves")


def cmd_deploy(args: argparse.Namespace) -> int:
    """``cable-ocp deploy FILE``."""
    from cable_ocp.scene.dynamics import load_dynamic_scene
    from cable_ocp.schedule.planning import verified_schedule
    from cable_ocp.schedule.sea import vessel_motions

    out.check_outputs(args)
    _check_options(args)
    scene = load_dynamic_scene(args.file, out.overrides(args))
    if scene.deployment is None:
        raise CableOCPError(f"{args.file}: no [deployment] table; give target_length and the "
                            "limits (docs/deployment.md)")
    for flag in ("unseen", "receding"):
        if getattr(args, flag) and scene.deployment.sea is None:
            raise CableOCPError(f"--{flag}: the scene has no [deployment.sea]; give its "
                                "significant_height and peak_frequency (and 'unseen', the "
                                "count)")
    motions = vessel_motions(scene)
    title = scene.statics.meta.get("title", Path(args.file).stem)
    out.note(args, f"deploy: {scene.length:.6g} -> {scene.deployment.target_length:.6g} m, "
                   f"{len(motions)} realisation(s): warm start, build, solve, forward check ...")
    res = verified_schedule(scene, motions, segments=args.segments, time_step=args.time_step,
                            rounds=args.check_rounds, hold=args.hold)
    if res.status == "interrupted":  # a Ctrl-C in the forward check: nothing is written
        raise KeyboardInterrupt
    extra: dict[str, dict[str, Any]] = {}  # the comparisons asked for, JSON-ready
    stopped = False
    for flag, job in (("compare", _forward_compare), ("unseen", _unseen),
                      ("receding", _receding)):
        if not (getattr(args, flag) and res.success) or stopped:
            continue
        try:
            extra[flag] = job(args, scene, motions, res)
        except KeyboardInterrupt:  # the schedule is whole: written, then exit 130
            stopped = True
        stopped = stopped or interrupt.requested()  # a Ctrl-C a simulation returned as status
        if stopped:
            extra[flag] = {"status": "interrupted",
                           "message": f"the {flag} runs were interrupted"}
    with interrupt.deferred():  # a Ctrl-C from here waits until the outputs are written
        rc = _outputs(args, scene, res, motions, extra, title)
    if stopped:
        raise KeyboardInterrupt
    return rc


def _forward_compare(args: argparse.Namespace, scene: Any, motions: list[Any], res: Any
                     ) -> dict[str, Any]:
    """The fastest constant speed on the forward simulator (a JSON-ready dict)."""
    from cable_ocp.schedule.forward import fastest_constant_speed

    out.note(args, "deploy --compare: the fastest constant speed on the forward simulator "
                   "(bisection) ...")
    fc = fastest_constant_speed(scene, motions)
    return {"status": fc.status, "message": fc.message, "speed_m_s": fc.speed,
            "duration_s": fc.duration, "binding": fc.binding, "simulations": fc.simulations,
            "bracket_m_s": list(fc.bracket),
            "schedule": None if fc.schedule is None else {
                "time_s": fc.schedule.time, "length_m": fc.schedule.length,
                "speed_m_s": fc.schedule.speed}}


def _check_text(scene: Any, res: Any) -> str:
    """The forward check's row: the last round's worst excess, the margins, the rounds."""
    pb, last = res.problem, res.checks[-1]
    name, val = last.worst
    step = pb.check_time_step or scene.simulation.time_step
    seg = pb.check_segments or scene.simulation.segments
    first = res.checks[0]
    fname, fval = first.worst
    text = (f"worst excess {100 * val:.2g} % ({name or '-'}; accepted "
            f"{100 * pb.check_tolerance:g} %) on the forward simulator, {seg} elements, "
            f"{step:g} s")
    if len(res.checks) > 1:
        margins = ", ".join(f"{k} {v:.4g} {'W' if k == 'power_max' else 'N'}"
                            for k, v in last.margins.items())
        text += (f"; the OCP alone broke {fname} by {100 * fval:.3g} % "
                 f"({first.duration:.4g} s): {len(res.checks) - 1} re-solve(s), margins "
                 f"{margins}")
    return text


def _unseen(args: argparse.Namespace, scene: Any, motions: list[Any], res: Any
            ) -> dict[str, Any]:
    """The schedule and its same-duration constant speed on the unseen seas (a JSON-ready
    dict: :func:`cable_ocp.schedule.robust.tally`'s counts)."""
    from cable_ocp.schedule.planning import ramp_acceleration
    from cable_ocp.schedule.robust import same_duration_trapezoid, schedule_of, tally
    from cable_ocp.schedule.sea import vessel_motions

    pb = scene.deployment  # the problem solved; its check settings
    seas = vessel_motions(scene, "unseen")
    sched = schedule_of(res, scene.length)
    const = same_duration_trapezoid(scene.length, pb.target_length, res.duration,
                                    ramp_acceleration(scene, pb))
    out.note(args, f"deploy --unseen: the schedule and the constant speed of the same "
                   f"duration on {len(seas)} unseen seas ...")
    tal = tally(scene, {"optimal": sched, "constant": const}, seas,
                time_step=pb.check_time_step, segments=pb.check_segments, keep_checks=False)
    data = tal.as_dict()
    data["constant_speed_m_s"] = float(np.max(np.abs(const.speed)))
    data["time_step_s"] = pb.check_time_step or scene.simulation.time_step
    data["segments"] = pb.check_segments or scene.simulation.segments
    return data


def _counts(c: dict[str, Any]) -> str:
    """The counts of re-simulated runs (robust.tally's or the receding comparison's)."""
    failed = f"{c['failed']} failed, " if c.get("failed") else ""
    return (f"{c['slack']} slack, {c['over_tension_max']} over tension_max, "
            f"{c['under_tension_min']} under tension_min, {failed}"
            f"{c['keeps_limits']} keep every limit")


def _unseen_text(u: dict[str, Any]) -> str:
    if u["status"] != "solved":
        return f"{u['status']}: {u.get('message', '')}"
    opt, con = u["schedules"]["optimal"], u["schedules"]["constant"]
    counts = _counts
    return (f"{len(u['motions'])} realisations ({u['segments']} elements, "
            f"{u['time_step_s']:g} s): the optimal schedule {counts(opt)}; the constant "
            f"speed of the same duration ({u['constant_speed_m_s']:.4g} m/s) {counts(con)}")


def _receding(args: argparse.Namespace, scene: Any, motions: list[Any], res: Any
              ) -> dict[str, Any]:
    """The receding horizon against the open-loop schedule on the unseen seas (a
    JSON-ready dict: :func:`cable_ocp.schedule.receding.compare_receding`'s counts)."""
    from cable_ocp.schedule.planning import with_margins
    from cable_ocp.schedule.receding import compare_receding
    from cable_ocp.schedule.robust import schedule_of
    from cable_ocp.schedule.sea import vessel_motions

    pb = res.problem
    seas = vessel_motions(scene, "unseen")
    out.note(args, f"deploy --receding: the receding horizon and the open-loop schedule on "
                   f"{len(seas)} unseen seas ...")
    # the plan's line is the OCP's: it keeps the margins the forward check found
    cmp = compare_receding(scene, seas, schedule_of(res, scene.length),
                           problem=with_margins(pb, res.margins),
                           check_time_step=pb.check_time_step,
                           check_segments=pb.check_segments)
    dur = cmp.durations
    st = cmp.solve_times
    return {"status": cmp.status, "message": "", "motions": [r.motion for r in cmp.rows],
            "counts": cmp.counts, "open_loop_duration_s": cmp.open_loop_duration,
            "durations_s": dur, "failed_replans": cmp.failed_replans,
            "replans": int(st.size), "replan_solve_s_median":
                float(np.median(st)) if st.size else math.nan,
            "replan_interval_s": pb.replan_interval, "preview_s": pb.preview,
            "margins": res.margins}


def _receding_text(r: dict[str, Any]) -> str:
    if r["status"] != "solved":
        return f"{r['status']}: {r.get('message', '')}"

    counts = _counts
    dur = np.asarray(r["durations_s"], dtype=float)
    ok = dur[np.isfinite(dur)]
    span = (f"{np.mean(ok):.4g} s on average ({np.min(ok):.4g}..{np.max(ok):.4g})"
            if ok.size else "never at rest at the target")
    return (f"{len(r['motions'])} realisations, re-planned every {r['replan_interval_s']:g} s "
            f"with {r['preview_s']:g} s of preview: {counts(r['counts']['receding'])}; "
            f"{span}; {r['failed_replans']} of {r['replans']} re-plans failed (median "
            f"solve {r['replan_solve_s_median']:.3g} s). The open-loop schedule "
            f"({r['open_loop_duration_s']:.4g} s): {counts(r['counts']['open_loop'])}")


def _saving(optimal: float, other: float) -> str:
    if not (math.isfinite(optimal) and math.isfinite(other) and other > 0.0):
        return "-"
    return f"{100.0 * (other - optimal) / other:.3g} %"


def _text(args: argparse.Namespace, scene: Any, res: Any, motions: list[Any],
          extra: dict[str, dict[str, Any]], title: str) -> None:
    pb = res.problem
    d = res.diagnostics
    rows = [("status", f"{res.status}: {res.message}"),
            ("lowering", f"{scene.length:.6g} -> {pb.target_length:.6g} m "
                         f"({scene.simulation.model} model, {len(motions)} realisation(s): "
                         + ", ".join(m.name for m in motions[:3])
                         + (", ..." if len(motions) > 3 else "") + ")")]
    ws = res.warm_start
    if res.success:
        rows.append(("time to depth", f"{res.duration:.4g} s (optimal schedule)"))
    if res.checks:
        rows.append(("re-simulated", _check_text(scene, res)))
    if ws is not None and ws.feasible:
        rows.append(("constant speed", f"{ws.duration:.4g} s at {ws.speed:.4g} m/s (the "
                                       f"fastest on the OCP's line; {ws.binding} binds); "
                                       f"saving {_saving(res.duration, ws.duration)}"))
    elif ws is not None:
        # no saving against a schedule that breaks the limits: it is none
        rows.append(("constant speed", f"none keeps the limits on the OCP's line (down to "
                                       f"{ws.speed:.4g} m/s, {ws.duration:.4g} s; "
                                       f"{ws.binding} binds): no saving to give"))
    compare = extra.get("compare")
    if compare is not None:
        if compare["status"] == "solved":
            rows.append(("forward check", f"{compare['duration_s']:.4g} s at "
                                          f"{compare['speed_m_s']:.4g} m/s (the fastest "
                                          "constant speed on the forward simulator, "
                                          f"{compare['simulations']} runs; "
                                          f"{compare['binding'] or 'speed_max'} binds); saving "
                                          f"{_saving(res.duration, compare['duration_s'])}"))
        else:
            rows.append(("forward check", f"{compare['status']}: "
                                          f"{compare.get('message', '')}"))
    if "unseen" in extra:
        rows.append(("unseen seas", _unseen_text(extra["unseen"])))
    if "receding" in extra:
        rows.append(("receding horizon", _receding_text(extra["receding"])))
    rows.append(("binding limits", ", ".join(res.binding) if res.binding else "none"))
    if res.success and pb.ahc:
        rows.append(("heave compensation", f"gain {res.solution.ahc_gain:.4g}"))
    if "steps" in d:
        hold = (f" (the last {d['hold_steps']}: the {d['hold_s']:.3g} s hold after the "
                "arrival)" if d.get("hold_steps") else "")
        rows.append(("size", f"{d['steps']} steps{hold}, {d.get('elements', '-')} elements, "
                             f"{d.get('variables', '-')} variables, "
                             f"{d.get('constraints', '-')} constraints"))
    if "solve_time_s" in d:
        rows.append(("times", f"warm start {d.get('warm_start_s', math.nan):.3g} s, build "
                              f"{d.get('build_s', math.nan):.3g} s, solve "
                              f"{d['solve_time_s']:.3g} s ({d.get('iterations', '-')} "
                              "iterations)" + (f", check {d['check_s']:.3g} s" if "check_s"
                                               in d else "")))
    width = max(len(k) for k, _ in rows)
    out.say(args, title)
    out.say(args, "\n".join(f"{k:<{width}}  {v}" for k, v in rows))


def _per_realisation(sol: Any) -> list[dict[str, np.ndarray]]:
    """Per realisation: the smallest and largest element tension per node of the
    schedule, the unit and the top tension, N; the heave, m."""
    outs = []
    for r in range(sol.tensions.shape[0]):
        tens = sol.tensions[r]
        outs.append({"tension_min_line": np.min(tens, axis=1),
                     "tension_max_line": np.max(tens, axis=1),
                     "unit_tension": sol.outputs[r, :, 2], "top_tension": sol.outputs[r, :, 3],
                     "heave": sol.heave[r], "unit_z": sol.outputs[r, :, 0],
                     "unit_vz": sol.outputs[r, :, 1]})
    return outs


def schedule_table(sol: Any) -> tuple[list[str], list[list[float]]]:
    """The CSV of a solved schedule: one row per node k = 0..N.

    Columns: t (s), L (m), v (m/s), a (m/s^2: the step's from k to k + 1, empty on the
    last row), then per realisation r the smallest and largest element tension, the unit
    and the top tension (N).

    Parameters
    ----------
    sol : OCPSolution
        The solved schedule.
    """
    per = _per_realisation(sol)
    header = ["t [s]", "L [m]", "v [m/s]", "a [m/s^2]"]
    for r in range(len(per)):
        header += [f"r{r}_tension_min [N]", f"r{r}_tension_max [N]", f"r{r}_unit_tension [N]",
                   f"r{r}_top_tension [N]"]
    acc = np.append(sol.accel, np.nan)
    cols = [sol.time, sol.length, sol.speed, acc]
    for p in per:
        cols += [p["tension_min_line"], p["tension_max_line"], p["unit_tension"],
                 p["top_tension"]]
    return header, np.column_stack(cols).tolist()


def _json(res: Any, motions: list[Any], compare: dict[str, Any] | None) -> dict[str, Any]:
    ws = res.warm_start
    pb = res.problem
    data: dict[str, Any] = {
        "binding": list(res.binding),
        "duration_s": res.duration if res.success else None,
        "start_length_m": None, "target_length_m": pb.target_length,
        "warm_start": None if ws is None else {
            "speed_m_s": ws.speed, "accel_m_s2": ws.accel, "duration_s": ws.duration,
            "feasible": ws.feasible, "binding": ws.binding, "rollouts": ws.rollouts},
        "compare": compare,
        "diagnostics": res.diagnostics,
        "checks": [{"margins": c.margins, "status": c.status, "duration_s": c.duration,
                    "violations": c.violations, "failed_runs": c.failed_runs}
                   for c in res.checks],
        "schedule": None,
        "realisations": None,
    }
    sol = res.solution
    if res.success and sol is not None:
        data["schedule"] = {"time_s": sol.time, "length_m": sol.length, "speed_m_s": sol.speed,
                            "accel_m_s2": sol.accel, "ahc_gain": sol.ahc_gain}
        data["realisations"] = [
            {"name": m.name, "seed": m.seed,
             "tension_min_line_N": p["tension_min_line"],
             "tension_max_line_N": p["tension_max_line"],
             "unit_tension_N": p["unit_tension"], "top_tension_N": p["top_tension"],
             "heave_m": p["heave"], "unit_z_m": p["unit_z"], "unit_vz_m_s": p["unit_vz"]}
            for m, p in zip(motions, _per_realisation(sol), strict=True)]
        data["violations"] = sol.violations
    return data


def _chart(scene: Any, res: Any) -> Any:
    """The deployment chart (omega_1 against length) on the lengths of the lowering, on
    the OCP's elements; None when it cannot be had (the figure then goes without)."""
    from cable_ocp.dynamics import modes
    from cable_ocp.scene.dynamics import dynamic_scene_from_dict

    raw = {k: v for k, v in scene.raw.items() if k != "deployment"}
    seg = res.diagnostics.get("elements")
    if seg:
        raw.setdefault("simulation", {})
        raw["simulation"] = {**raw["simulation"], "segments": int(seg)}
    plain = dynamic_scene_from_dict(raw)
    lo, hi = sorted((scene.length, res.problem.target_length))
    chart = modes(plain, 1, np.linspace(lo, hi, CHART_LENGTHS))
    return chart if chart.status != "interrupted" else None


def _resampled(t: np.ndarray, speed: np.ndarray, start: float
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A piecewise-linear speed on 400 samples and its exact integral, the length (m): the
    curve of a schedule given at its corners only."""
    tf = np.union1d(np.linspace(float(t[0]), float(t[-1]), 400), t)
    vf = np.interp(tf, t, speed)
    length = start + np.concatenate([[0.0], np.cumsum(0.5 * (vf[1:] + vf[:-1]) * np.diff(tf))])
    return tf, length, vf


def _outputs(args: argparse.Namespace, scene: Any, res: Any, motions: list[Any],
             extra: dict[str, dict[str, Any]], title: str) -> int:
    """The text, JSON, CSV and figure of a finished solve."""
    compare = extra.get("compare")
    _text(args, scene, res, motions, extra, title)
    data = _json(res, motions, compare)
    data["unseen"] = extra.get("unseen")
    data["receding"] = extra.get("receding")
    data["start_length_m"] = scene.length
    out.emit_json(args, out.envelope(res.status, res.message, data))
    if not res.success:
        if args.csv or args.plot:
            out.note(args, f"no schedule ({res.status}): no CSV or figure written")
        return out.EXIT_NOT_SUCCESS
    out.emit_csv(args, *schedule_table(res.solution))
    if args.plot:
        from cable_ocp.plots.deploy import plot_schedule
        from cable_ocp.schedule.planning import trapezoid

        chart = _chart(scene, res)
        constant = []
        ws = res.warm_start
        if ws is not None and ws.feasible:
            _, t, _, spd, _ = trapezoid(scene.length, res.problem.target_length, ws.speed,
                                        ws.accel, 0.01 * ws.duration)
            constant.append((f"constant {ws.speed:.3g} m/s (OCP's line)",
                             *_resampled(t, spd, scene.length)))
        if compare is not None and compare.get("schedule"):
            s = compare["schedule"]
            constant.append((f"constant {compare['speed_m_s']:.3g} m/s (forward simulator)",
                             *_resampled(np.asarray(s["time_s"]), np.asarray(s["speed_m_s"]),
                                         scene.length)))
        heave_w = sorted({w for m in motions for w in m.frequencies})
        if scene.deployment.sea is not None:
            heave_w = [scene.deployment.sea.peak_frequency]
        out.emit_plot(args, lambda path: plot_schedule(
            res, path, title=title, chart=chart, constant=constant,
            heave_frequencies=heave_w, names=[m.name for m in motions]))
    return out.EXIT_OK
