"""``cable-ocp simulate`` and ``cable-ocp modes``: cable dynamics (parse, call, format)."""

from __future__ import annotations

import argparse
import re
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.cli import output as out
from cable_ocp.cli.cost import dynamics_cost
from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import interrupt
from cable_ocp.numerics.export import netcdf_engine, write_netcdf


def register(sub: argparse._SubParsersAction, parent: argparse.ArgumentParser) -> None:
    """Add ``simulate`` and ``modes``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The ``cable-ocp`` parser's subparsers, to which the commands are added.
    parent : argparse.ArgumentParser
        The common options (``--quiet``, ``--debug``: :func:`cable_ocp.cli.output.common_parent`),
        a parent of every parser added.
    """
    s = sub.add_parser(
        "simulate", parents=[parent],
        help="cable dynamics in the time domain: axial, planar or 3D lumped-mass "
             "(Huang 1992, ch. 3-5)",
        description="Simulate a dynamic scene from its static state: top heave, horizontal or "
                    "circular motion, a towing path, pay-out or haul-in; report the top "
                    "tension, the unit's motion, the smallest tension and slack (where and "
                    "when). Exit 0 solved, 1 slack or a numerical failure (the JSON status "
                    "says which), 2 invalid input.")
    s.add_argument("file", help="dynamic scene (UTF-8 TOML), e.g. "
                                "problems/dynamics/huang_3_3_5.toml")
    out.add_set_option(s)
    out.add_json_option(s, "the time series (t, length, top and unit positions, top "
                           "tension) and the slack report")
    out.add_csv_option(s, "the node positions and element tensions over time")
    out.add_plot_option(s, "the unit trajectory, the tension envelope along the cable and "
                           "top against unit heave")
    s.add_argument("--netcdf", metavar="PATH",
                   help="write the full time series as netCDF (needs xarray and netCDF4 or "
                        "scipy's netCDF3 writer)")
    out.add_force_option(s)
    s.set_defaults(func=cmd_simulate)

    m = sub.add_parser(
        "modes", parents=[parent],
        help="natural frequencies and mode shapes about the static state",
        description="Linearise the scene's model ([simulation] model: axial or lumped3d) "
                    "about its static state and solve for the natural frequencies and mode "
                    "shapes. With --lengths, the frequencies against paid-out length: a "
                    "deployment resonance chart with the wave band shaded.")
    m.add_argument("file", help="dynamic scene (UTF-8 TOML)")
    m.add_argument("--count", type=int, metavar="N",
                   help="number of modes (default [modes] count of the file)")
    m.add_argument("--lengths", metavar="START:STOP:N",
                   help="unstretched lengths in m, N of them evenly spaced, for the "
                        "deployment chart")
    out.add_set_option(m)
    out.add_json_option(m, "the modes ({\"modes\": [{\"frequency_rad_s\", \"period_s\", "
                           "\"shape\"}]}) or the chart")
    out.add_csv_option(m, "the frequencies (and the chart's rows with --lengths)")
    out.add_plot_option(m, "the mode shapes, or the deployment chart with --lengths")
    out.add_force_option(m)
    m.set_defaults(func=cmd_modes)


def _load(args: argparse.Namespace) -> Any:
    from cable_ocp.scene.dynamics import load_dynamic_scene

    return load_dynamic_scene(args.file, out.overrides(args))


def cmd_simulate(args: argparse.Namespace) -> int:
    """``cable-ocp simulate FILE``."""
    from cable_ocp.dynamics.simulation import simulate

    out.check_outputs(args)
    out.check_output_path(args.netcdf, "--netcdf", allow_stdout=False)
    if args.netcdf:  # before the run: a missing xarray is found at once
        netcdf_engine("--netcdf")
    scene = _load(args)
    out.check_cost(args, dynamics_cost(scene))
    with out.progress(args, 1, f"simulate ({scene.simulation.model})", "step") as bar:
        res = simulate(scene, progress=lambda done, total: bar(done, total))
    title = scene.statics.meta.get("title", Path(args.file).stem)
    # a Ctrl-C from here on waits until the finished run is written (then exit 130)
    with interrupt.deferred():
        return _simulate_outputs(args, scene, res, title)


def _simulate_outputs(args: argparse.Namespace, scene: Any, res: Any, title: str) -> int:
    """The text, JSON, CSV, netCDF and figure of a finished (or interrupted) run."""
    data = res.to_dict()
    if out.stdout_free(args):
        t = res.t
        rows = [
            ("status", f"{res.status}: {res.message}"),
            ("model, scheme", f"{res.model}, {res.scheme}"),
        ]
        if len(t) == 0:  # failed before the first sample (e.g. the static state)
            rows += [("simulated", "nothing")]
        else:
            rows += _series_rows(res, t)
        width = max(len(k) for k, _ in rows)
        print(title)
        print("\n".join(f"{k:<{width}}  {v}" for k, v in rows))
    if res.status != "interrupted":  # an interruption says so in one line (warnings: JSON)
        for w in res.warnings:  # the result's warnings, one line each on stderr
            out.warn(w)
    out.emit_json(args, out.envelope(res.status, res.message, data, res.warnings))
    empty = len(res.t) == 0
    if empty and (args.csv or args.netcdf or args.plot):
        out.note(args, "no time series (the run failed before its first sample): no CSV, "
                       "netCDF or figure written")
    stopped = res.status == "interrupted"  # the samples finished: JSON, CSV, netCDF
    if args.csv and not empty:
        out.emit_csv(args, *_series_table(res), partial=stopped)
    if args.netcdf and not empty:
        with out.output_errors("--netcdf", args.netcdf):
            write_netcdf(res, args.netcdf)
        out.confirm(args, args.netcdf, "netCDF")
    if stopped:
        raise KeyboardInterrupt
    if args.plot and not empty:
        from cable_ocp.plots.dynamics import plot_simulation

        out.emit_plot(args, lambda path: plot_simulation(res, path, title=title, scene=scene))
    return out.EXIT_OK if res.success else out.EXIT_NOT_SUCCESS


def _series_rows(res: Any, t: Any) -> list[tuple[str, str]]:
    """The summary rows of a non-empty time series ('-' where a number does not exist)."""
    def g(v: Any) -> str:
        return "-" if v is None or not np.isfinite(v) else f"{v:.6g}"

    span = t[-1] - t[0]
    return [
        ("simulated", f"{span:.4g} s in {len(t)} samples"),
        ("wall time", f"{res.wall_time_s:.3g} s "
                      f"({res.wall_time_s / max(span, 1e-12):.3g} s per simulated s)"),
        ("length", f"{res.length[0]:.4f} -> {res.length[-1]:.4f} m (unstretched)"),
        ("top tension", f"{g(np.nanmin(res.top_tension))} .. "
                        f"{g(np.nanmax(res.top_tension))} N"),
        ("smallest tension", f"{g(res.min_tension)} N"),
        ("unit heave", f"{g(np.nanmin(res.unit_position[:, 2]))} .. "
                       f"{g(np.nanmax(res.unit_position[:, 2]))} m (z)"),
        ("slack", _slack_text(res.slack)),
        ("snap", _snap_text(res.snap)),
    ]


def _snap_text(snap: dict[str, Any]) -> str:
    if not snap.get("occurred"):
        return "none"
    return (f"peak {snap['peak_tension']:.4g} N at t = {snap['time']:.4g} s in element "
            f"{snap['segment']} (s = {snap['location']:.4g} m from end_a), taut again at "
            f"{snap['taut_at']:.4g} s; {snap['count']} snap(s)")


def _slack_text(slack: dict[str, Any]) -> str:
    if not slack.get("occurred"):
        return "none"
    loc = slack.get("location")
    where = (f", at s = {loc:.4g} m from end_a" if isinstance(loc, (int, float))
             else f", {loc}" if loc is not None else "")
    return f"first at t = {slack.get('first_time'):.4g} s{where}"


def _series_table(res: Any) -> tuple[list[str], list[list[float]]]:
    """One row per sample: t, length, top and unit positions, top tension, then every node's
    x, y, z, every element's tension and the snap-peak marker."""
    n_nodes = res.node_positions.shape[1]
    header = ["t [s]", "length [m]", "top_x [m]", "top_y [m]", "top_z [m]", "unit_x [m]",
              "unit_y [m]", "unit_z [m]", "top_tension [N]"]
    header += [f"node{i}_{c} [m]" for i in range(n_nodes) for c in "xyz"]
    header += [f"element{i}_tension [N]" for i in range(res.segment_tensions.shape[1])]
    header += ["snap_peak [-]"]
    # 1 on the sample of the largest snap's peak (SimulationResult.snap), else 0
    peak = np.zeros((len(res.t), 1))
    if res.snap.get("occurred"):
        peak[int(np.argmin(np.abs(res.t - res.snap["time"]))), 0] = 1.0
    cols = [res.t[:, None], res.length[:, None], res.top_position, res.unit_position,
            res.top_tension[:, None], res.node_positions.reshape(len(res.t), -1),
            res.segment_tensions, peak]
    return header, np.hstack(cols).tolist()


def _parse_lengths(text: str) -> np.ndarray:
    m = re.fullmatch(r"\s*([^:]+):([^:]+):([^:]+)\s*", text)
    try:
        start, stop, n = (float(m.group(1)), float(m.group(2)),  # type: ignore[union-attr]
                          int(m.group(3)))  # type: ignore[union-attr]
    except (AttributeError, ValueError):
        raise CableOCPError(f"--lengths {text!r}: expected START:STOP:N, e.g. 100:1000:46"
                            ) from None
    if not (np.isfinite(start) and np.isfinite(stop) and 0 < start and 0 < stop
            and 1 <= n <= 2000):
        raise CableOCPError(f"--lengths {text!r}: lengths > 0 m and N in 1..2000")
    return np.linspace(start, stop, n)


def cmd_modes(args: argparse.Namespace) -> int:
    """``cable-ocp modes FILE``."""
    from cable_ocp import report
    from cable_ocp.dynamics.modal import at_length, modes

    out.check_outputs(args)
    if args.count is not None and not 1 <= args.count <= 200:
        raise CableOCPError(f"--count {args.count}: give 1..200")
    lengths = _parse_lengths(args.lengths) if args.lengths else None
    scene = _load(args)
    out.check_cost(args, dynamics_cost(scene, lengths=1 if lengths is None else len(lengths)))
    title = scene.statics.meta.get("title", Path(args.file).stem)
    if lengths is not None:
        for length in (lengths.min(), lengths.max()):  # the bounds, before the plan line
            at_length(scene, float(length))
        out.note(args, f"modes: {len(lengths)} lengths, one static solve and eigenproblem "
                       "each ...")
    res = modes(scene, args.count, lengths)
    data = res.to_dict()
    if res.status == "interrupted":  # the lengths finished: JSON and CSV, then the one line
        n = res.frequencies.shape[1]
        out.emit_json(args, out.envelope(res.status, res.message, data))
        out.emit_csv(args, ["length [m]"] + [f"mode{k + 1} [rad/s]" for k in range(n)],
                     [[L, *row] for L, row in zip(res.lengths, res.frequencies, strict=True)],
                     partial=True)
        raise KeyboardInterrupt
    if lengths is None:
        rows = [[k + 1, f"{w:.6g}", f"{w / (2 * np.pi):.6g}", f"{p:.6g}"]
                for k, (w, p) in enumerate(zip(res.frequencies, res.periods, strict=True))]
        out.say(args, f"{title}: {res.model} model, {res.status}"
                      + (f" ({res.message})" if res.message else ""))
        out.say(args, report.table(["mode", "omega [rad/s]", "f [Hz]", "period [s]"], rows)
                if rows else "no modes")
        out.emit_csv(args, ["mode", "frequency [rad/s]", "frequency [Hz]", "period [s]"],
                     [[k + 1, w, w / (2 * np.pi), p] for k, (w, p) in
                      enumerate(zip(res.frequencies, res.periods, strict=True))])
    else:
        n = res.frequencies.shape[1]
        out.say(args, f"{title}: {res.model} model, natural frequencies (rad/s) against "
                      f"length; wave band {res.wave_band[0]:.4g}..{res.wave_band[1]:.4g} rad/s")
        out.say(args, report.table(["length [m]"] + [f"mode {k + 1} [rad/s]" for k in range(n)],
                                   [[f"{L:.4g}"] + ["-" if not np.isfinite(w) else f"{w:.5g}"
                                                    for w in row]
                                    for L, row in zip(res.lengths, res.frequencies,
                                                      strict=True)]))
        cross = res.crossings()
        out.say(args, "crossings of the wave band: " + (", ".join(
            f"mode {c['mode'] + 1} at {c['length_m']:.1f} m ({c['edge']:.3g} rad/s)"
            for c in cross) if cross else "none"))
        out.emit_csv(args, ["length [m]"] + [f"mode{k + 1} [rad/s]" for k in range(n)],
                     [[L, *row] for L, row in zip(res.lengths, res.frequencies, strict=True)])
    out.emit_json(args, out.envelope(res.status, res.message or res.status, data))
    if args.plot:
        from cable_ocp.plots.dynamics import plot_deployment, plot_modes

        if lengths is None:
            out.emit_plot(args, lambda path: plot_modes(res, path, title=title))
        else:
            out.emit_plot(args, lambda path: plot_deployment(res, path, title=title))
    return out.EXIT_OK if res.status == "solved" else out.EXIT_NOT_SUCCESS
