"""``cable-ocp heave``: the heave-compensation comparison (parse, call, format)."""

from __future__ import annotations

import argparse
import math
import textwrap
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.cli import output as out
from cable_ocp.numerics.text_table import MISSING, WIDTH, table

CONTROLLERS = ("passive", "lqr", "lqg", "mpc", "phc", "phc+lqr", "phc+lqg", "phc+mpc",
               "printed-g3", "printed-g5")


def register(sub: argparse._SubParsersAction, parent: argparse.ArgumentParser) -> None:
    """Add ``heave``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The ``cable-ocp`` parser's subparsers, to which the command is added.
    parent : argparse.ArgumentParser
        The common options (``--quiet``, ``--debug``: :func:`cable_ocp.cli.output.common_parent`),
        a parent of every parser added.
    """
    p = sub.add_parser(
        "heave", parents=[parent],
        help="heave compensation: passive, LQR, LQG and MPC compared on one seeded sea "
             "(Huang 1992, ch. 6)",
        description="Simulate the scene's controllers on one seeded wave realisation and "
                    "compare them: unit heave RMS and its reduction, winch speed and stroke, "
                    "limit violations (a warning names each limit a controller exceeds), MPC "
                    "solve times. Exit 0 when every controller ran and stayed finite and "
                    "stable (on the cable: its line never went slack), 1 otherwise "
                    "(per-controller status in the JSON), 2 invalid input.")
    p.add_argument("file", help="heave scene (UTF-8 TOML), e.g. problems/heave/ex_6_3_6.toml")
    out.add_set_option(p)
    p.add_argument("--duration", type=float, metavar="S",
                   help="simulated time, s (same as --set simulation.duration=S)")
    p.add_argument("--seed", type=int, metavar="N",
                   help="seed of the wave realisation (same as --set simulation.seed=N)")
    p.add_argument("--controllers", nargs="+", choices=CONTROLLERS, metavar="NAME",
                   help="controllers to run, any of: " + ", ".join(CONTROLLERS)
                        + " (default: [controller] controllers of the file)")
    out.add_json_option(p, "the metrics of every controller")
    out.add_csv_option(p, "the closed-loop time series of every controller")
    out.add_plot_option(p, "spectra, time series and the trade-off curves")
    out.add_force_option(p)
    p.set_defaults(func=cmd_heave)


def _overrides(args: argparse.Namespace) -> dict[str, Any]:
    over = out.overrides(args)
    if args.duration is not None:
        over["simulation.duration"] = args.duration
    if args.seed is not None:
        over["simulation.seed"] = args.seed
    if args.controllers:
        over["controller.controllers"] = list(args.controllers)
    return over


def cmd_heave(args: argparse.Namespace) -> int:
    """``cable-ocp heave FILE``."""
    from cable_ocp.cli.cost import heave_cost
    from cable_ocp.heave.cable_compare import compare
    from cable_ocp.scene.heave import load_scene

    out.check_outputs(args)
    sc = load_scene(args.file, _overrides(args))
    out.check_outputs(args, inputs=[("[unit] cable_scene", sc.unit.cable_scene)])
    out.check_cost(args, heave_cost(sc))
    with out.progress(args, 1, "heave simulation", "sample") as bar:
        res = compare(sc, progress=lambda done, total, _: bar(done, total))
    bad = [k for k, s in res.statuses.items() if s != "solved"]
    message = ("every controller ran to the end with finite, bounded states" if not bad
               else "; ".join(f"{k}: {res.statuses[k]}: {res.messages[k]}" for k in bad))
    # a Ctrl-C: the controllers finished go to --json and --csv; no table, no figure
    stopped = res.status == "interrupted"
    if stopped:
        done = [k for k, s in res.statuses.items() if s != "interrupted"]
        message = (f"interrupted after {len(done)} of {len(res.statuses)} controllers"
                   + (f" ({', '.join(done)})" if done else "")
                   + (", in the passive baseline (no reductions)"
                      if len(done) == len(res.statuses) else ""))
    if out.stdout_free(args) and not stopped:
        _print_table(sc, args, res)
    ctrl = {k: {"status": res.statuses[k], "message": res.messages[k], **v.as_dict()}
            for k, v in res.metrics.items()}
    if "mpc" in ctrl:
        ctrl["mpc"]["solver_failures"] = res.mpc_failures
    data = {"sigma_uncontrolled": res.sigma_uncontrolled,
            "passive_heave_rms": res.passive_heave_rms, "controllers": ctrl}
    data.update(getattr(res, "json_extra", None) or {})  # cable scenes: plant, identified
    out.emit_json(args, out.envelope(res.status, message, data, res.warnings))
    if args.csv and res.traces:
        names = list(res.traces)
        t = next(iter(res.traces.values())).t
        header = ["t [s]", "boom_tip_heave [m]"]
        cols: list[np.ndarray] = [t, next(iter(res.traces.values())).x0]
        for k in names:
            tr = res.traces[k]
            header += [f"{k}_unit_heave [m]", f"{k}_winch_output [m]", f"{k}_winch_speed [m/s]",
                       f"{k}_command [m]"]
            cols += [tr.x, tr.u, tr.u_dot, tr.u0]
            # the line tension, the winch motor and the passive compensator, where known
            for key, label in (("tension", "tension [N]"), ("torque", "torque [N m]"),
                               ("power", "power [W]"), ("stroke_phc", "phc_stroke [m]")):
                series = getattr(tr, key, None)
                if series is not None:
                    header.append(f"{k}_{label}")
                    cols.append(series)
        out.emit_csv(args, header, np.column_stack(cols).tolist(), partial=stopped)
    if stopped:
        raise KeyboardInterrupt
    if args.plot:
        if res.traces:
            out.emit_plot(args, lambda path: _plot(sc, args, res, path))
        else:
            out.note(args, f"--plot {args.plot}: no controller ran; no figure written")
    if bad:
        out.note(args, f"cable-ocp: not solved ({res.status}): {message}")
    return out.EXIT_OK if not bad else out.EXIT_NOT_SUCCESS


def _num(v: float | None, spec: str, scale: float = 1.0) -> str:
    """A table cell: ``v / scale`` formatted, or ``-`` where the number does not exist."""
    if v is None or not math.isfinite(v):
        return MISSING
    return format(v / scale, spec)


def _wrap(text: str) -> str:
    """A remark within the tables' width, its continuation lines indented."""
    return textwrap.fill(text, WIDTH, subsequent_indent="  ", break_on_hyphens=False)


def filter_lines(sc: Any, fit: Any) -> list[str]:
    """The shaping filter's fit, and for the thesis' filter what its known misfit means.

    Parameters
    ----------
    sc : HeaveScene
        The scene (``[sea] shaping_filter``).
    fit : cable_ocp.heave.sea.FilterFit
        The filter's fit to the scene's spectrum.
    """
    lines = [f"shaping filter: spectral error {fit.spectral_error:.3f}, variance error "
             f"{100 * fit.variance_error:+.2f} %"]
    if sc.sea.shaping_filter == "thesis":
        lines.append(f"  (the thesis' filter: its spectrum is {100 * fit.spectral_error:.0f} % off "
                     "the sea's (L2); kept: it gives the thesis' sigma)")
    return lines


def heave_table(res: Any) -> str:
    """The comparison table of a heave run: one row per controller, every row with every
    column (a value that does not exist, e.g. of a failed controller, is ``-``).

    Parameters
    ----------
    res : Comparison or CableComparison
        The result (:func:`cable_ocp.heave.compare`).
    """
    hdr = ["controller", "status", "heave rms", "reduction", "peak u'", "max |u|", "u' rms",
           "energy", "violation", "solve med"]
    units = ["", "", "[m]", "[%]", "[m/s]", "[m]", "[m/s]", "[-]", "[-]", "[s]"]
    rows = [[name, str(res.statuses[name]), _num(m.heave_rms, ".3e"),
             _num(m.reduction_pct, ".2f"), _num(m.peak_winch_speed, ".3f"),
             _num(m.max_stroke, ".3f"), _num(m.winch_speed_rms, ".3f"),
             _num(m.energy_index, ".2f"), _num(m.max_constraint_violation, ".3f"),
             _num(m.solve_time_median_s, ".2e")] for name, m in res.metrics.items()]
    # the winch motor and the passive compensator, where the scene has them
    extra = [("peak_torque", "peak tau", "[kN m]", 1e3), ("peak_power", "peak P", "[kW]", 1e3),
             ("max_stroke_phc", "max |delta|", "[m]", 1.0),
             ("stop_time_phc", "at stops", "[s]", 1.0)]
    for key, head, unit, scale in extra:
        vals = [getattr(m, key, None) for m in res.metrics.values()]
        if any(v is not None for v in vals):
            hdr.append(head)
            units.append(unit)
            for row, v in zip(rows, vals, strict=True):
                row.append(_num(v, ".2f", scale))
    return table(hdr, rows, units, left=1)


def cable_table(res: Any) -> str:
    """Predicted against achieved on the cable plant: reductions, tensions and slack per
    controller (every row with every column, ``-`` where a number does not exist).

    Parameters
    ----------
    res : CableComparison
        The result on the cable plant.
    """
    hdr = ["controller", "predicted", "achieved", "T unit min", "T unit max", "T top min",
           "T top max", "slack"]
    units = ["", "[%]", "[%]", "[kN]", "[kN]", "[kN]", "[kN]", "[samples]"]
    rows = []
    for name, m in res.metrics.items():
        d = m.as_dict()
        rows.append([name, _num(d.get("reduction_predicted_pct"), ".3f"),
                     _num(d.get("reduction_pct"), ".3f")]
                    + [_num(d.get(k), ".1f", 1e3) for k in
                       ("tension_unit_min", "tension_unit_max", "tension_top_min",
                        "tension_top_max")]
                    + [MISSING if d.get("slack_samples") is None else str(d["slack_samples"])])
    return table(hdr, rows, units, left=1)


def deployment_table(res: Any) -> str:
    """The deployment's summary over the windows of paid-out length (the README's table):
    per controller the unit's heave (standard deviation about the window's mean: median and
    largest over the windows, and the length of the largest), the lowest and highest tension
    at the unit, and the slack (time and windows).

    Parameters
    ----------
    res : CableComparison
        The result of a scene with ``[deployment]``.
    """
    from cable_ocp.heave.deployment import summary

    dep = res.json_extra["deployment"]
    hdr = ["controller", "status", "heave std", "heave std", "at", "T unit min", "T unit max",
           "slack", "slack"]
    units = ["", "", "median [m]", "max [m]", "[m]", "[kN]", "[kN]", "[s]", "[windows]"]
    rows = []
    for name, row in summary(dep["per_length"], dep["sample_time"]).items():
        rows.append([name, str(res.statuses.get(name, MISSING)),
                     _num(row["heave_std_median"], ".4f"), _num(row["heave_std_max"], ".4f"),
                     _num(row["heave_std_max_at"], ".0f"),
                     _num(row["tension_unit_min"], ".1f", 1e3),
                     _num(row["tension_unit_max"], ".1f", 1e3),
                     _num(row["slack_time"], ".2f"),
                     f"{row['slack_windows']} of {row['windows']}"])
    return (f"per {dep['window']:.3g} m of paid-out length, "
            f"{min(dep['per_length']['length']):.0f}-{max(dep['per_length']['length']):.0f} m:\n"
            + table(hdr, rows, units, left=1))


def _print_table(sc: Any, args: argparse.Namespace, res: Any) -> None:
    """The comparison table (what ``cable-ocp heave`` prints)."""
    print(f"{sc.title or Path(args.file).stem}")
    sig = res.sigma_uncontrolled
    print("sigma_uncontrolled (Lyapunov, sigma^2 = pi P11): "
          + (f"{sig:.4f} m" if sig is not None else "- (no valid variance)"))
    for line in filter_lines(sc, res.models.filter_fit):
        print(line)
    print(heave_table(res))
    if "mpc" in res.metrics:
        print(f"MPC solver failures (fell back on the shifted plan): {res.mpc_failures}")
    if "passive" not in res.metrics and res.passive_heave_rms is not None:
        print(f"reduction relative to a passive run on the same sea: heave rms "
              f"{res.passive_heave_rms:.4e} m")
    for name, st in res.statuses.items():
        if st != "solved":
            print(_wrap(f"{name}: {st}: {res.messages[name]}"))
        elif name.startswith("printed-"):  # the plant it ran on (its own delay)
            print(_wrap(f"{name}: {res.messages[name]}"))
    for w in res.warnings:
        print(_wrap(f"WARNING {w}"))
    extra = getattr(res, "json_extra", None) or {}
    if extra:
        _print_cable(extra, res)


def _print_cable(extra: dict, res: Any) -> None:
    """Identification and, on the cable plant, predicted vs achieved (cable scenes)."""
    idf = extra.get("identified")
    if idf:
        print(f"identified from the cable ({idf['excitation']}, {idf['duration']:g} s):")
        print(f"  a = {idf['a']:.5g} +- {idf['a_std']:.2g} s^2, b = {idf['b']:.4g} +- "
              f"{idf['b_std']:.2g} s, fit {idf['fit_pct']:.2f} %;")
        print(f"  (6.3): b_quadratic = {idf['b_quadratic']:.4g} s^2/m, fit "
              f"{idf['fit_pct_quadratic']:.2f} %;")
        print(f"  first axial mode {idf['omega_1']:.4g} rad/s: 1/omega_1^2 = "
              f"{idf['a_modal']:.5g} s^2 ({idf['a_vs_modal_pct']:+.2f} %)")
    dm = extra.get("design_model", {})
    print(f"design model: a = {dm.get('a', float('nan')):.5g} s^2, "
          f"b = {dm.get('b', float('nan')):.4g} s ({dm.get('source', '-')}); "
          f"plant: {extra.get('plant', 'model')}")
    if "deployment" in extra:
        print(deployment_table(res))
        return
    if extra.get("plant") != "cable":
        return
    print(cable_table(res))


def _plot(sc: Any, args: argparse.Namespace, res: Any, path: str) -> None:
    """Spectra, time series and the trade-off curves (``--plot``)."""
    from cable_ocp.heave.lqr import tradeoff_data
    from cable_ocp.plots.heave import plot_comparison

    if "deployment" in (getattr(res, "json_extra", None) or {}):
        from cable_ocp.plots.heave_cable import plot_deployment

        plot_deployment(res, path, sc.title)
        return
    tr = next(iter(res.traces.values()))
    step = 0.01
    t = np.arange(0.0, min(tr.t[-1], 200.0), step)
    x0 = np.interp(t, tr.t, tr.x0)
    tau = sc.winch.delay
    if tau <= 0:
        tau = 0.2
        out.note(args, "trade-off plot: the scene has no delay; its delayed curves use 0.2 s, "
                       "the delay of the thesis' study (Fig. 6.17)")
    dm = (getattr(res, "json_extra", None) or {}).get("design_model", {})
    td = tradeoff_data(dm.get("a", sc.unit.a), dm.get("b", sc.unit.b), sc.winch.gain, tau, t,
                       x0)
    plot_comparison(res, path, td, scene=sc)


