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

    b = sub.add_parser("bench", help="benchmarks that print a table",
                       description="Timing benchmarks (tables; nothing is asserted).")
    b.add_argument("which", nargs="?", default="sweep", choices=["sweep"],
                   help="sweep: De Zoysa psi0 sweep, collocation vs scipy solve_bvp")
    b.add_argument("--scene", default=None, help="problem file (default: De Zoysa)")
    b.add_argument("--intervals", type=int, default=40)
    b.add_argument("--plot", metavar="PATH", help="save the swept forces figure")
    b.set_defaults(func=_cmd_bench)


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
    from cable_ocp.bench import statics_sweep

    kw = {"intervals": args.intervals}
    if args.scene:
        kw["scene_path"] = args.scene
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
