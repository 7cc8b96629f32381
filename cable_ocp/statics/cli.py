"""``cable-ocp solve`` and ``cable-ocp bench``: argument parsing and output formatting only."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from cable_ocp import report
from cable_ocp.scene import load_scene, parse_override


def register(sub: argparse._SubParsersAction) -> None:
    """Add the statics subcommands to the top-level parser."""
    p = sub.add_parser("solve", help="solve a static cable problem (TOML file)",
                       description="Solve a static cable problem and print a summary.")
    p.add_argument("file", help="problem file (TOML, SI units)")
    p.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                   help="override a key with a dotted name, e.g. end_b.position=[0,229,183]")
    p.add_argument("--json", metavar="PATH", help="write the solution as JSON ('-' = stdout)")
    p.add_argument("--plot", metavar="PATH", help="save the profile and tension figure")
    p.set_defaults(func=_cmd_solve)

    f = sub.add_parser("footprint", help="footprint of a tethered seabed unit (004 2.2.4)",
                       description="Reach of a thrust-limited seabed unit in N directions.")
    f.add_argument("file", help="problem file with a [footprint] table")
    f.add_argument("--directions", type=int, default=72)
    f.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE")
    f.add_argument("--plot", metavar="PATH", help="save the footprint polygon")
    f.add_argument("--json", metavar="PATH",
                   help="write the polygon and per-direction data ('-' = stdout)")
    f.set_defaults(func=_cmd_footprint)

    b = sub.add_parser("bench", help="benchmarks that print a table",
                       description="Timing benchmarks (tables; nothing is asserted).")
    b.add_argument("which", nargs="?", default="sweep",
                   choices=["sweep", "accuracy", "robustness"],
                   help="sweep: De Zoysa psi0 sweep timing, collocation vs scipy solve_bvp; "
                        "accuracy: error against run time of every method; robustness: "
                        "every method on every extreme scene")
    b.add_argument("--scene", action="append", default=None,
                   help="problem file (repeatable; default: the benchmark's own scenes)")
    b.add_argument("--method", action="append", default=None,
                   help="restrict to these methods (accuracy: labels; robustness: names)")
    b.add_argument("--intervals", type=int, default=40, help="sweep: collocation intervals")
    b.add_argument("--repeats", type=int, default=3, help="accuracy: timing repeats")
    b.add_argument("--plot", metavar="PATH", help="save the figure")
    b.add_argument("--csv", metavar="PATH", help="accuracy: write the table as CSV")
    b.add_argument("--json", metavar="PATH", help="accuracy/robustness: write JSON")
    b.set_defaults(func=_cmd_bench)


def _emit_json(path: str, text: str) -> None:
    """Write JSON text to ``path``, or to stdout when it is '-'."""
    if path == "-":
        print(text)
    else:
        Path(path).write_text(text)


def _cmd_solve(args: argparse.Namespace) -> int:
    from cable_ocp.statics.solver import solve

    overrides = dict(parse_override(s) for s in args.overrides)
    scene = load_scene(args.file, overrides)
    sol = solve(scene)
    data = sol.to_dict()
    if args.json == "-":
        print(report.to_json(data))
    else:
        print(report.statics_summary(sol, title=f"{scene.meta.get('title', args.file)}"))
        if args.json:
            Path(args.json).write_text(report.to_json(data))
    if args.plot:
        from cable_ocp.plots import plot_statics

        plot_statics(sol, args.plot, title=scene.meta.get("title", Path(args.file).stem))
    if not sol.success:
        print(f"cable-ocp: solve failed: {sol.message}", file=sys.stderr)
        return 1
    return 0


def _cmd_bench(args: argparse.Namespace) -> int:
    if args.which == "accuracy":
        return _bench_accuracy(args)
    if args.which == "robustness":
        return _bench_robustness(args)
    from cable_ocp.bench import statics_sweep

    kw = {"intervals": args.intervals}
    if args.scene:
        kw["scene_path"] = args.scene[0]
    res = statics_sweep.run(**kw)
    print(f"De Zoysa psi0 sweep, {len(res['angles'])} angles, {args.intervals} intervals "
          "(fastest of 3 repeats for the collocation sweep)")
    print(report.table(res["headers"], res["rows"]))
    m, t = res["measured"], res["targets"]
    print(f"\nwarm solve median {m['warm_median_ms']:.2f} ms (target < {t['warm_median_ms']} ms); "
          f"sweep incl. build {m['sweep_total_ms']:.0f} ms (target < {t['sweep_total_ms']:.0f} ms)")
    print(f"collocation vs solve_bvp end_a force: max relative difference {res['agreement']:.1e}")
    if args.plot:
        from cable_ocp.plots import plot_sweep

        plot_sweep(res["angles"], res["forces"], args.plot, "psi0 [deg]",
                   "De Zoysa: force at the buggy", overlays={"solve_bvp": res["forces_bvp"]})
    return 0


def _bench_accuracy(args: argparse.Namespace) -> int:
    from cable_ocp.bench import accuracy
    from cable_ocp.bench.common import fmt_sci

    scenes = None
    if args.scene:
        scenes = [(Path(f).stem, Path(f), {}) for f in args.scene]
    results = accuracy.run(scenes, args.method, repeats=args.repeats)
    for res in results:
        print(f"\n{res['scene']}: reference = {res['reference']} "
              f"(agreement {res['reference_check']:.1e})")
        rows = [[r["method"], r["resolution"], f"{r['time_s'] * 1e3:.2f}", r["status"],
                 fmt_sci(r["force_error"]), fmt_sci(r["profile_error"]),
                 fmt_sci(r["estimate_ratio"])] for r in res["rows"]]
        print(report.table(["method", "resolution", "time [ms]", "status", "force err",
                            "profile err", "est/true"], rows))
        for name, note in res["notes"].items():
            print(f"  {name}: {note}")
        for name, d in sorted(res["dominance"].items()):
            print(f"  {name}: {d}")
    low = [(res["scene"], r["method"], r["resolution"], r["estimate_ratio"])
           for res in results for r in res["rows"]
           if r["estimate_ratio"] is not None and r["estimate_ratio"] < 0.1]
    print("\nerror estimates under-estimating by more than 10x: "
          + (", ".join(f"{a} {b} {c} ({d:.2f})" for a, b, c, d in low) if low else "none"))
    if args.csv:
        accuracy.write_csv(results, args.csv)
    if args.json:
        _emit_json(args.json, report.to_json(results))
    if args.plot:
        accuracy.plot(results, args.plot)
    return 0


def _bench_robustness(args: argparse.Namespace) -> int:
    from cable_ocp.bench import robustness

    scenes = [Path(f) for f in args.scene] if args.scene else None
    res = robustness.run(scenes, args.method)
    print("Robustness matrix (ok: converged and within 1 % of the reference; FAIL: honest "
          "failure; n/a: method cannot represent the scene; WRONG: converged but off by "
          "more than 1 %)")
    print(report.table(res["headers"], res["rows"]))
    print("\nnot ok:")
    for d in res["details"]:
        if d["category"] != "ok":
            print(f"  {d['scene']:<26} {d['method']:<28} {d['category']:<6} "
                  f"{d['message'][:110]}")
    print("\ncollocation reported as success but wrong: "
          + (", ".join(d["scene"] for d in res["wrong_ours"]) or "none"))
    if args.json:
        _emit_json(args.json, report.to_json(res))
    return 1 if res["wrong_ours"] else 0


def _cmd_footprint(args: argparse.Namespace) -> int:
    from cable_ocp.statics.footprint import footprint, plot_footprint

    scene = load_scene(args.file, dict(parse_override(s) for s in args.overrides))
    res = footprint(scene, args.directions)
    rows = [[f"{th:.1f}", "-" if r != r else f"{r:.3f}", "-" if r != r else f"{x:.3f}",
             "-" if r != r else f"{y:.3f}", "-" if r != r else f"{tx:.1f}",
             "-" if r != r else f"{ty:.1f}", "-" if r != r else f"{ln:.3f}", st]
            for th, r, (x, y), (tx, ty), ln, st in zip(
                res.theta_deg, res.reach, res.points, res.thrust, res.length, res.status,
                strict=True)]
    if args.json != "-":  # '-' = JSON only on stdout
        print(f"{scene.meta.get('title', args.file)}: {args.directions} directions, "
              f"{res.wall_time_s:.2f} s")
        print(report.table(["theta [deg]", "reach [m]", "x [m]", "y [m]", "Tx [N]", "Ty [N]",
                            "L [m]", "status"], rows))
    if args.plot:
        plot_footprint(res, args.plot, scene.meta.get("title", ""))
    if args.json:
        _emit_json(args.json, report.to_json({
            "theta_deg": res.theta_deg.tolist(), "reach": res.reach.tolist(),
            "points": res.points.tolist(), "thrust": res.thrust.tolist(),
            "length": res.length.tolist(), "status": res.status}))
    return 0 if all(s == "solved" for s in res.status) else 1
