"""``cable-ocp heave FILE [--json PATH] [--plot PATH]`` and ``cable-ocp bench-heave``.

Parses arguments, calls the library and formats its results; no physics here.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
from pathlib import Path
from typing import Any

import numpy as np


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``heave`` and ``bench-heave`` subcommands."""
    p = subparsers.add_parser("heave", help="heave compensation: passive, LQR, LQG and MPC "
                              "compared on one seeded sea (004 ch. 6)")
    p.add_argument("file", help="heave scene TOML (e.g. problems/heave/ex_6_3_6.toml)")
    p.add_argument("--json", metavar="PATH", help="write the metrics as JSON")
    p.add_argument("--plot", metavar="PATH", help="save spectra, time series, trade-off (PNG)")
    p.add_argument("--duration", type=float, help="override [simulation] duration, s")
    p.add_argument("--controllers", nargs="+", choices=["passive", "lqr", "lqg", "mpc"],
                   help="override [controller] controllers")
    p.set_defaults(func=run_heave)
    b = subparsers.add_parser("bench-heave", help="MPC solve time per step (median, p99)")
    b.add_argument("--horizons", type=int, nargs="+", default=[20, 50, 100])
    b.add_argument("--steps", type=int, default=300, help="closed-loop steps per case")
    b.add_argument("--solvers", nargs="+", default=["daqp", "qpoases", "osqp", "qrqp", "ipopt"])
    b.add_argument("--no-do-mpc", action="store_true", help="skip do-mpc even if installed")
    b.add_argument("--json", metavar="PATH", help="write the timing rows as JSON ('-' = the "
                   "JSON alone on stdout)")
    b.set_defaults(func=run_bench)


def run_heave(args: argparse.Namespace) -> int:
    """Run the comparison for a scene file; print a table; write JSON/plot if asked."""
    from cable_ocp.heave.scene import load_scene
    from cable_ocp.heave.simulate import compare

    sc = load_scene(args.file)
    if args.duration is not None:
        sc = dataclasses.replace(sc, simulation=dataclasses.replace(sc.simulation,
                                                                    duration=args.duration))
        from cable_ocp.heave.scene import check

        check(sc)
    res = compare(sc, tuple(args.controllers) if args.controllers else None)
    if args.json != "-":  # '-' = the JSON alone on stdout
        _print_table(sc, args, res)
    if args.json:
        out = {"sigma_uncontrolled": res.sigma_uncontrolled,
               "controllers": {k: v.as_dict() for k, v in res.metrics.items()}}
        text = json.dumps(out, indent=2)
        if args.json == "-":
            print(text)
        else:
            Path(args.json).write_text(text)
    if args.plot:
        _plot(sc, args, res)
    return 0


def _print_table(sc: Any, args: argparse.Namespace, res: Any) -> None:
    """The comparison table (what `cable-ocp heave` prints)."""
    fit = res.models.filter_fit
    print(f"{sc.title or args.file}")
    print(f"sigma_uncontrolled (Lyapunov, sigma^2 = pi P11): {res.sigma_uncontrolled:.4f} m")
    print(f"shaping filter: spectral error {fit.spectral_error:.3f}, variance error "
          f"{100 * fit.variance_error:+.2f} %")
    hdr = ("controller", "heave_rms m", "reduct %", "peak u' m/s", "max |u| m", "u' rms",
           "energy", "viol", "solve med s")
    print("{:<10} {:>12} {:>9} {:>11} {:>9} {:>8} {:>8} {:>8} {:>11}".format(*hdr))
    for name, m in res.metrics.items():
        e = "-" if m.energy_index is None else f"{m.energy_index:.2f}"
        st = "-" if m.solve_time_median_s is None else f"{m.solve_time_median_s:.2e}"
        print(f"{name:<10} {m.heave_rms:12.4e} {m.reduction_pct:9.3f} {m.peak_winch_speed:11.3f} "
              f"{m.max_stroke:9.3f} {m.winch_speed_rms:8.3f} {e:>8} "
              f"{m.max_constraint_violation:8.3f} {st:>11}")
    if "mpc" in res.metrics:
        print(f"MPC solver failures (fell back on the shifted plan): {res.mpc_failures}")


def _plot(sc: Any, args: argparse.Namespace, res: Any) -> None:
    """Spectra, time series and the trade-off curves (`--plot`)."""
    from cable_ocp.heave.plots import plot_comparison, tradeoff_data

    tr = next(iter(res.traces.values()))
    step = 0.01
    t = np.arange(0.0, min(tr.t[-1], 200.0), step)
    x0 = np.interp(t, tr.t, tr.x0)
    tau = sc.winch.delay
    if tau <= 0:
        tau = 0.2
        print("trade-off plot: the scene has no delay; its delayed curves use 0.2 s, the "
              "delay of the thesis' study (Fig. 6.17)")
    td = tradeoff_data(sc.unit.a, sc.unit.b, sc.winch.gain, tau, t, x0)
    plot_comparison(res, args.plot, td)


def run_bench(args: argparse.Namespace) -> int:
    """Print the MPC timing table (cable_ocp.bench.heave_mpc); write its JSON if asked."""
    from cable_ocp.bench.heave_mpc import format_table, json_data, run

    rows = run(horizons=args.horizons, steps=args.steps, solvers=args.solvers,
               with_do_mpc=not args.no_do_mpc)
    if args.json != "-":  # '-' = the JSON alone on stdout
        print(format_table(rows))
    if args.json:
        text = json.dumps(json_data(rows), indent=2)
        if args.json == "-":
            print(text)
        else:
            Path(args.json).write_text(text)
    return 0
