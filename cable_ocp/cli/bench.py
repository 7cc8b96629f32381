"""``cable-ocp bench {sweep,accuracy,robustness,batch,systems,dynamics,deploy}`` and
``cable-ocp bench-heave``.

Benchmarks print tables (and write JSON/CSV/plots when asked); nothing here is asserted by
the tests. Each compares methods side by side in one run, so ratios stay meaningful on a
noisy machine.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from cable_ocp.cli import output as out
from cable_ocp.numerics import interrupt


def register(sub: argparse._SubParsersAction, parent: argparse.ArgumentParser) -> None:
    """Add ``bench`` (with its benchmarks) and ``bench-heave``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The ``cable-ocp`` parser's subparsers, to which the commands are added.
    parent : argparse.ArgumentParser
        The common options (``--quiet``, ``--debug``: :func:`cable_ocp.cli.output.common_parent`),
        a parent of every parser added.
    """
    b = sub.add_parser(
        "bench", parents=[parent], help="statics and dynamics benchmarks that print a table",
        description="Benchmarks (tables; nothing is asserted). Without a benchmark name: "
                    "sweep.")
    b.set_defaults(func=cmd_sweep, scene=None, intervals=40, json=None, csv=None, plot=None)
    which = b.add_subparsers(dest="which", metavar="BENCHMARK")

    s = which.add_parser(
        "sweep", parents=[parent],
        help="De Zoysa psi0 sweep timing: collocation (built once, warm) vs scipy solve_bvp",
        description="Time the 19-angle De Zoysa psi0 sweep: collocation built once and "
                    "warm-started (as a first process: functions built; and in a second "
                    "process: functions from the disk cache), with and without error "
                    "estimates, with the Newton kernel compiled to C (solver.compile = "
                    "auto: first and second process), against scipy's solve_bvp from the "
                    "catenary and from the previous point, in one run; wall-clock and CPU "
                    "times.")
    s.add_argument("--scene", metavar="FILE", help="problem file with layout.psi0_deg "
                                                   "(default problems/dezoysa_sea_buggy.toml)")
    s.add_argument("--intervals", type=int, default=40, metavar="N",
                   help="collocation intervals (default 40)")
    s.add_argument("--repeats", type=int, default=3, metavar="N",
                   help="collocation sweep repeats, the least disturbed kept (default 3)")
    s.add_argument("--no-subprocess", action="store_true",
                   help="skip the second-process run (functions from the disk cache)")
    out.add_json_option(s, "the summary (warm median, iterations, totals, agreement)")
    out.add_csv_option(s, "the timing table")
    out.add_plot_option(s, "the end_a force against psi0, collocation and solve_bvp")
    s.set_defaults(func=cmd_sweep)

    a = which.add_parser(
        "accuracy", parents=[parent],
        help="work-precision: error against run time of every statics method",
        description="For each scene a converged reference, then every method over a range "
                    "of resolutions: error (end forces and profile) against wall time.")
    a.add_argument("--scene", action="append", metavar="FILE",
                   help="problem file (repeatable; default De Zoysa at 90 deg and Berteaux)")
    a.add_argument("--method", action="append", metavar="LABEL",
                   help="restrict to these series (repeatable; labels as in the table)")
    a.add_argument("--repeats", type=int, default=3, metavar="N",
                   help="timing repeats, fastest kept (default 3)")
    a.add_argument("--no-subprocess", action="store_true",
                   help="skip the second-process timings (functions from the disk cache)")
    out.add_json_option(a, "every row")
    out.add_csv_option(a, "every row")
    out.add_plot_option(a, "the work-precision diagram")
    a.set_defaults(func=cmd_accuracy)

    r = which.add_parser(
        "robustness", parents=[parent],
        help="every statics method on every extreme scene",
        description="Each method at its default resolution on each extreme scene: ok "
                    "(converged, within 1 %% of the reference), FAIL (honest failure), n/a "
                    "(cannot represent the scene), WRONG (converged but off). Exit 1 when "
                    "collocation is WRONG anywhere.")
    r.add_argument("--scene", action="append", metavar="FILE",
                   help="problem file (repeatable; default problems/extreme/*.toml and the "
                        "published examples)")
    r.add_argument("--method", action="append", metavar="NAME",
                   help="restrict to these methods (repeatable)")
    out.add_json_option(r, "the matrix and every cell's detail")
    out.add_csv_option(r, "one row per cell")
    r.set_defaults(func=cmd_robustness)

    bb = which.add_parser(
        "batch", parents=[parent],
        help="load-case batch: per-case overhead and parallel speed-up",
        description="De Zoysa's cable over psi0 x current speed (200 cases by default): the "
                    "cases solved bare in this process, then as batches on 1 and 2 local "
                    "workers, in one run: per-case overhead of the batch machinery and the "
                    "parallel speed-up.")
    bb.add_argument("--angles", type=int, default=20, metavar="N", help="psi0 values (20)")
    bb.add_argument("--speeds", type=int, default=10, metavar="N",
                    help="current speeds (10)")
    bb.add_argument("--dask", type=int, default=0, metavar="N",
                    help="also on a dask.distributed LocalCluster of N worker processes "
                         "(needs the cluster extra; default 0: not run)")
    bb.add_argument("--repeats", type=int, default=2, metavar="N",
                    help="timed runs of each loop and batch, the fastest kept (2)")
    out.add_json_option(bb, "the rows and the summary")
    bb.set_defaults(func=cmd_bench_batch)

    y = which.add_parser(
        "systems", parents=[parent],
        help="mooring systems beside MoorPy: pose, tensions, 6x6 and times in one run",
        description="Each system (default: the shipped systems without current) solved by "
                    "cable_ocp and by MoorPy (pip install moorpy) in one run: the largest "
                    "differences of the body pose (m), the line end tensions (relative) and "
                    "laid lengths (m), of cable_ocp's 6x6 from MoorPy's analytic matrix and "
                    "from central differences of full equilibria (relative to the largest "
                    "entry); the median times of the equilibrium (from the file's start, "
                    "solvers built) and of the 6x6 (from the solved lines' stiffnesses, as "
                    "MoorPy's getCoupledStiffnessA); then, without FILEs, the shipped spar and "
                    "9-line spread with a 1 m/s current, ours alone.")
    y.add_argument("files", nargs="*", metavar="FILE",
                   help="system files (default: problems/systems/ without current)")
    y.add_argument("--repeats", type=int, default=5, metavar="N",
                   help="timed runs, the median kept (5)")
    out.add_json_option(y, "the rows")
    y.set_defaults(func=cmd_bench_systems)

    d = which.add_parser(
        "dynamics", parents=[parent],
        help="lumped-mass dynamics: wall time per simulated second beside MoorDyn",
        description="Huang (1992) 5.7 system (300 m cable, 3 t unit, top moved by "
                    "x = y = z = sin(1.256 t) m) at 20, 40, 80 and 160 segments: wall time "
                    "per simulated second of cable_ocp's implicit midpoint scheme at several "
                    "time steps beside MoorDyn (optional: pip install moordyn) at its stable "
                    "steps, each with its top-force error against one converged reference "
                    "(cable_ocp at 160 and 320 segments, Richardson-extrapolated, 4 ms), in "
                    "one run; then the targets (100x real time at 40 segments; no slower "
                    "than MoorDyn at equal accuracy). Several minutes; --quick: seconds.")
    d.add_argument("--segments", type=int, nargs="+", default=None, metavar="N",
                   help="numbers of segments (default 20 40 80 160)")
    d.add_argument("--time-steps", type=float, nargs="+", default=None, metavar="DT",
                   help="cable_ocp time steps, s (default 0.1 0.075 0.05 0.025)")
    d.add_argument("--tolerance", type=float, default=None, metavar="TOL",
                   help="Newton tolerance of cable_ocp's timed runs (scaled residual; "
                        "default 1e-8; the reference uses the scene's 1e-10)")
    d.add_argument("--duration", type=float, default=None, metavar="S",
                   help="simulated time, s (default 60; errors over the last 10 s)")
    d.add_argument("--repeats", type=int, default=None, metavar="N",
                   help="timed runs per row, fastest kept (default 2)")
    d.add_argument("--no-moordyn", action="store_true", help="skip MoorDyn even if installed")
    d.add_argument("--quick", action="store_true",
                   help="a seconds-long smoke run (6 segments, one step, 20 s; its numbers "
                        "mean little)")
    out.add_json_option(d, "the rows and the targets")
    out.add_plot_option(d, "error against wall time per simulated second")
    d.set_defaults(func=cmd_bench_dynamics)

    dp = which.add_parser(
        "deploy", parents=[parent],
        help="deployment schedule: the optimum beside the constant speed and today's "
             "deployment, its cost, a 600 s run",
        description="Issue 25's benchmark of the deployment OCP (docs/deployment.md), in "
                    "one run: compare (on Huang (1992) 3.3.5 and the 6.3.6 line: the optimal "
                    "schedule, re-simulated on the forward simulator, beside the fastest "
                    "constant speed found by bisection on the forward simulator and "
                    "the scheduled-gain deployment of cable-ocp heave), cost (build and "
                    "solve time, iterations and variables against the duration and the "
                    "elements) and long (a ~600 s deployment on 40 elements). Tens of "
                    "minutes on a shared 2-core machine; choose parts with --part.")
    dp.add_argument("--part", action="append", choices=["compare", "cost", "long"],
                    metavar="PART", help="compare, cost or long (repeatable; default all)")
    dp.add_argument("--case", action="append", metavar="FILE",
                    help="compare: a dynamic scene with [deployment] (repeatable; default "
                         "problems/dynamics/deploy_3_3_5.toml and deploy_6_3_6.toml)")
    dp.add_argument("--rel-tol", type=float, default=1e-3, metavar="R",
                    help="compare: the constant speed's bisection width, relative (0.001: "
                         "narrower than the savings it is compared with)")
    dp.add_argument("--motion-step", type=float, default=None, metavar="S",
                    help="compare: the forward simulator's sampling of a sea's heave, s "
                         "(default the case's [simulation] time_step; the linear "
                         "interpolation's error is about S^2 max|z''| / 8)")
    dp.add_argument("--max-iter", type=int, default=None, metavar="N",
                    help="compare: IPOPT's iteration limit for the OCP (default the OCP's "
                         "500)")
    dp.add_argument("--floor-fraction", type=float, default=None, metavar="F",
                    help="compare: the slowest constant speed tried on the forward "
                         "simulator, as a fraction of speed_max (default 1/32)")
    dp.add_argument("--durations", type=float, nargs="+", default=None, metavar="S",
                    help="cost: the warm start's durations, s (default 60 120 240 480)")
    dp.add_argument("--segments", type=int, nargs="+", default=None, metavar="N",
                    help="cost: the OCP line's elements (default 5 10 20 40)")
    dp.add_argument("--cost-file", metavar="FILE", default=None,
                    help="cost: the scene (default problems/dynamics/deploy_small.toml)")
    dp.add_argument("--budget", type=float, default=600.0, metavar="S",
                    help="cost: a cell taking longer (build + solve) skips the row's larger "
                         "cells (600 s)")
    dp.add_argument("--long-duration", type=float, default=600.0, metavar="S",
                    help="long: the deployment's duration, s (600)")
    dp.add_argument("--long-segments", type=int, default=40, metavar="N",
                    help="long: the OCP line's elements (40)")
    dp.add_argument("--long-time-step", type=float, default=None, metavar="S",
                    help="long: the OCP's step, s (default the scene's deployment.time_step)")
    out.add_json_option(dp, "every part's rows")
    dp.set_defaults(func=cmd_bench_deploy)

    h = sub.add_parser(
        "bench-heave", parents=[parent],
        help="MPC solve time per closed-loop step, every solver and do-mpc",
        description="Median and p99 time per closed-loop MPC step on "
                    "problems/heave/ex_6_3_6.toml (0.2 s delay, hard limits, soft tension "
                    "limit) for every QP/NLP solver and, when installed, do-mpc, at each "
                    "horizon, in one run.")
    h.add_argument("--horizons", type=int, nargs="+", default=[20, 50, 100], metavar="N",
                   help="MPC horizons in samples (default 20 50 100)")
    h.add_argument("--steps", type=int, default=300, metavar="N",
                   help="closed-loop steps per case (default 300; IPOPT and do-mpc: N/5)")
    h.add_argument("--solvers", nargs="+", default=["daqp", "qpoases", "osqp", "qrqp", "ipopt"],
                   metavar="NAME",
                   help="solvers to time (default daqp qpoases osqp qrqp ipopt)")
    h.add_argument("--no-do-mpc", action="store_true", help="skip do-mpc even if installed")
    out.add_json_option(h, "the timing rows")
    h.set_defaults(func=cmd_bench_heave)


def cmd_sweep(args: argparse.Namespace) -> int:
    """``cable-ocp bench sweep``."""
    from cable_ocp import report
    from cable_ocp.bench import statics_sweep

    out.check_outputs(args)
    if not 2 <= args.intervals <= 2560:
        raise out_error(f"--intervals {args.intervals}: give 2..2560")
    if not 1 <= getattr(args, "repeats", 3) <= 100:
        raise out_error(f"--repeats {args.repeats}: give 1..100")
    kw: dict[str, Any] = {"intervals": args.intervals, "repeats": getattr(args, "repeats", 3),
                          "subprocess_run": not getattr(args, "no_subprocess", False)}
    if args.scene:
        kw["scene_path"] = args.scene
    out.note(args, "bench sweep: timing the collocation and solve_bvp sweeps (~10 s) ...")
    res = statics_sweep.run(**kw)
    m, t, sm = res["measured"], res["targets"], res["summary"]
    out.say(args, f"De Zoysa psi0 sweep, {len(res['angles'])} angles, {args.intervals} "
                  f"intervals (least disturbed of {kw['repeats']} repeats for the collocation "
                  f"sweeps; load average {sm['load_average_1min']:.1f})")
    out.say(args, report.table(res["headers"], res["rows"]))
    out.say(args, f"\nwarm solve median {m['warm_median_ms']:.2f} ms wall, "
                  f"{sm['warm_median_cpu_ms']:.2f} ms CPU, {sm['warm_iterations_median']:g} "
                  f"steps (chord and Newton) and {sm['warm_factorizations_mean']:.1f} "
                  f"factorisations per point (mean) (target <= {t['warm_median_ms']:g} ms); "
                  f"each point all in "
                  f"{sm['warm_point_all_in_ms']:.2f} ms; solve_bvp/collocation per point "
                  f"{sm['warm_ratio_solve_bvp_over_collocation']:.1f}x")
    second = ("" if sm["sweep_total_second_process_ms"] is None else
              f"; 2nd process {sm['sweep_total_second_process_ms']:.0f} ms wall, "
              f"{sm['sweep_total_second_process_cpu_ms']:.0f} ms CPU")
    out.say(args, f"sweep incl. build: 1st process {m['sweep_total_ms']:.0f} ms wall, "
                  f"{sm['sweep_total_cpu_ms']:.0f} ms CPU{second} "
                  f"(target <= {t['sweep_total_ms']:.0f} ms)")
    if sm["compiled"]:
        second = ("" if sm["compiled_sweep_total_second_process_ms"] is None else
                  f"; sweep incl. build, 2nd process "
                  f"{sm['compiled_sweep_total_second_process_ms']:.0f} ms wall, "
                  f"{sm['compiled_sweep_total_second_process_cpu_ms']:.0f} ms CPU")
        out.say(args, f"compiled (solver.compile = auto): warm median "
                      f"{sm['compiled_warm_median_ms']:.2f} ms wall, "
                      f"{sm['compiled_warm_median_cpu_ms']:.2f} ms CPU, "
                      f"{sm['compiled_warm_iterations_median']:g} steps (chord and Newton) "
                      f"and {sm['compiled_warm_factorizations_mean']:.1f} Jacobian "
                      f"factorisations per point (mean); 1st process "
                      f"with the C compilation {sm['compiled_sweep_total_first_process_ms']:.0f}"
                      f" ms{second}")
    else:
        out.say(args, "compiled (solver.compile = auto): no C compiler, ran interpreted")
    out.say(args, "collocation vs solve_bvp end_a force: max relative difference "
                  f"{res['agreement']:.1e}")
    out.emit_json(args, out.envelope("ok", "benchmark completed", {
        **res["summary"], "headers": res["headers"], "rows": res["rows"]}))
    out.emit_csv(args, res["headers"], res["rows"])
    if args.plot:
        from cable_ocp.plots.statics_series import plot_sweep

        out.emit_plot(args, lambda path: plot_sweep(
            res["angles"], res["forces"], path, "psi0 (deg)", "De Zoysa: force at the buggy",
            overlays={"solve_bvp": res["forces_bvp"]}, name="collocation"))
    return out.EXIT_OK


def out_error(msg: str) -> Exception:
    """The user-input error (exit 2)."""
    from cable_ocp.errors import CableOCPError

    return CableOCPError(msg)


ACCURACY_KEYS = ["scene", "method", "resolution", "time_s", "cpu_s", "status", "force_error",
                 "profile_error", "estimate_ratio"]
ACCURACY_HEADER = ["scene", "method", "resolution", "time [s]", "CPU [s]", "status",
                   "force error [-]", "profile error [-]", "estimate/true [-]"]


def cmd_accuracy(args: argparse.Namespace) -> int:
    """``cable-ocp bench accuracy``."""
    from cable_ocp import report
    from cable_ocp.bench import accuracy
    from cable_ocp.bench.common import fmt_sci

    out.check_outputs(args)
    if not 1 <= args.repeats <= 100:
        raise out_error(f"--repeats {args.repeats}: give 1..100 (the fastest is kept)")
    labels = [*accuracy.PLAN, accuracy.REUSED]
    for m in args.method or []:
        if m not in labels:
            raise out_error(f"--method {m!r}: valid are " + ", ".join(f'"{x}"' for x in labels))
    scenes = [(Path(f).stem, Path(f), {}) for f in args.scene] if args.scene else None
    if scenes:
        from cable_ocp.scene import load_scene

        for _, path, _ in scenes:
            load_scene(path)  # input errors before any solve
    n_scenes = len(scenes) if scenes else len(accuracy.default_scenes())
    total = n_scenes * accuracy.planned_rows(args.method, args.repeats)
    rows: list[dict[str, Any]] = []
    calls = [0]
    try:
        with out.progress(args, total, "bench accuracy", "timing") as bar:
            def step(row: dict[str, Any]) -> None:
                # a row comes once per repeat (interleaved passes): kept once
                if not any(r is row for r in rows):
                    rows.append(row)
                calls[0] += 1
                bar(calls[0], postfix=f"{row['scene']}: {row['method']}")

            results = accuracy.run(scenes, args.method, repeats=args.repeats, progress=step,
                                   second_process=not args.no_subprocess)
    except (KeyboardInterrupt, Exception) as exc:  # a CasADi error may stand for a Ctrl-C
        if not interrupt.is_interruption(exc):
            raise
        _write_partial(args, rows, ACCURACY_KEYS, ACCURACY_HEADER)
        raise
    for res in results:
        out.say(args, f"\n{res['scene']}: reference = {res['reference']} "
                      f"(agreement {res['reference_check']:.1e})")
        table = [[r["method"], r["resolution"], f"{r['time_s'] * 1e3:.2f}",
                  f"{r.get('cpu_s', float('nan')) * 1e3:.2f}", r["status"],
                  fmt_sci(r["force_error"]), fmt_sci(r["profile_error"]),
                  fmt_sci(r["estimate_ratio"])] for r in res["rows"]]
        out.say(args, report.table(["method", "resolution", "time [ms]", "CPU [ms]", "status",
                                    "force error [-]", "profile error [-]", "est/true [-]"],
                                   table))
        for name, note in res["notes"].items():
            out.say(args, f"  {name}: {note}")
        for name, d in sorted(res["dominance"].items()):
            out.say(args, f"  {name}: {d}")
        vs = res.get("versus_solve_bvp") or []
        if any(e["solve_bvp_s"] is not None for e in vs):
            def ms(x: float | None) -> str:
                return "-" if x is None else f"{x * 1e3:.2f}"

            out.say(args, "\n  least time to reach each error, cold collocation (any scheme) "
                          "vs solve_bvp [ms], wall / CPU:")
            out.say(args, report.table(
                ["error <=", "solve_bvp", "collocation 1st process", "ahead",
                 "collocation 2nd process", "ahead"],
                [[f"{e['error']:.0e}", f"{ms(e['solve_bvp_s'])} / {ms(e['solve_bvp_cpu_s'])}",
                  f"{ms(e['first_s'])} / {ms(e['first_cpu_s'])}",
                  f"{e['first_ahead_s']} / {e['first_ahead_cpu_s']}",
                  f"{ms(e['second_s'])} / {ms(e['second_cpu_s'])}",
                  f"{e['second_ahead_s']} / {e['second_ahead_cpu_s']}"] for e in vs]))
    low = [(res["scene"], r["method"], r["resolution"], r["estimate_ratio"])
           for res in results for r in res["rows"]
           if r["estimate_ratio"] is not None and r["estimate_ratio"] < 0.1]
    out.say(args, "\nerror estimates under-estimating by more than 10x: "
            + (", ".join(f"{a} {b} {c} ({d:.2f})" for a, b, c, d in low) if low else "none"))
    out.emit_json(args, out.envelope("ok", "benchmark completed", {"scenes": results}))
    out.emit_csv(args, ACCURACY_HEADER, [[r.get(k) for k in ACCURACY_KEYS]
                                         for res in results for r in res["rows"]])
    if args.plot:
        from cable_ocp.plots.bench import plot_work_precision

        out.emit_plot(args, lambda path: plot_work_precision(results, path))
    return out.EXIT_OK


def _write_partial(args: argparse.Namespace, rows: list[dict[str, Any]], keys: list[str],
                   header: list[str]) -> None:
    """On Ctrl-C: write the rows finished so far (JSON status "interrupted")."""
    out.emit_json(args, out.envelope("interrupted", f"interrupted after {len(rows)} rows",
                                     {"rows": rows}))
    out.emit_csv(args, header, [[r.get(k) for k in keys] for r in rows], partial=True)
    if out.stdout_free(args) and rows:
        from cable_ocp import report

        print(report.table(header, [[r.get(k) for k in keys] for r in rows]))


ROBUST_KEYS = ["scene", "method", "category", "error", "time_s", "message"]
ROBUST_HEADER = ["scene", "method", "category", "error [-]", "time [s]", "message"]


def cmd_robustness(args: argparse.Namespace) -> int:
    """``cable-ocp bench robustness``."""
    from cable_ocp import report
    from cable_ocp.bench import robustness
    from cable_ocp.scene import METHODS, load_scene

    out.check_outputs(args)
    scenes = [Path(f) for f in args.scene] if args.scene else None
    for path in scenes or []:
        load_scene(path)
    for m in args.method or []:
        if m not in METHODS:
            raise out_error(f"--method {m}: valid are {', '.join(METHODS)}")
    details: list[dict[str, Any]] = []
    n = len(scenes or robustness.default_scenes()) * len(args.method or METHODS)
    try:
        with out.progress(args, n, "bench robustness", "cell") as bar:
            res = robustness.run(scenes, args.method, details=details, progress=lambda d, t, c:
                                 bar(d, postfix=f"{c['scene']}: {c['method']}"))
    except (KeyboardInterrupt, Exception) as exc:  # a CasADi error may stand for a Ctrl-C
        if not interrupt.is_interruption(exc):
            raise
        _write_partial(args, details, ROBUST_KEYS, ROBUST_HEADER)
        raise
    out.say(args, "Robustness matrix (ok: converged and within 1 % of the reference; FAIL: "
                  "honest failure; n/a: method cannot represent the scene; WRONG: converged "
                  "but off by more than 1 %)")
    out.say(args, report.table(res["headers"], res["rows"]))
    out.say(args, "\nnot ok:")
    for d in res["details"]:
        if d["category"] != "ok":
            out.say(args, f"  {d['scene']:<26} {d['method']:<28} {d['category']:<6} "
                          f"{d['message'][:110]}")
    wrong = [d["scene"] for d in res["wrong_ours"]]
    out.say(args, "\ncollocation reported as success but wrong: " + (", ".join(wrong) or "none"))
    status = "ok" if not wrong else "wrong"
    out.emit_json(args, out.envelope(status, "collocation wrong on: " + ", ".join(wrong)
                                     if wrong else "benchmark completed", res))
    out.emit_csv(args, ROBUST_HEADER, [[d[k] for k in ROBUST_KEYS] for d in res["details"]])
    return out.EXIT_NOT_SUCCESS if wrong else out.EXIT_OK


def cmd_bench_heave(args: argparse.Namespace) -> int:
    """``cable-ocp bench-heave``."""
    from cable_ocp.bench.heave_mpc import format_table, json_data, run

    out.check_outputs(args)
    for n in args.horizons:
        if not 1 <= n <= 400:
            raise out_error(f"--horizons {n}: give 1..400 samples (the condensed QP grows "
                            "as N^2 in memory and N^3 in time)")
    if not 1 <= args.steps <= 100000:
        raise out_error(f"--steps {args.steps}: give 1..100000")
    from cable_ocp.heave.mpc import SOLVERS

    for s in args.solvers:
        if s not in SOLVERS:
            raise out_error(f"--solvers {s}: valid are {', '.join(SOLVERS)}")
    total = len(args.horizons) * (len(args.solvers) + (0 if args.no_do_mpc else 1))
    with out.progress(args, total, "bench-heave", "case") as bar:
        rows = run(horizons=args.horizons, steps=args.steps, solvers=args.solvers,
                   with_do_mpc=not args.no_do_mpc,
                   progress=lambda done, tot, row: bar(done, tot, postfix=f"{row.solver} "
                                                                           f"N={row.horizon}"))
    out.say(args, format_table(rows))
    out.emit_json(args, out.envelope("ok", "benchmark completed", json_data(rows)))
    return out.EXIT_OK


def cmd_bench_batch(args: argparse.Namespace) -> int:
    """``cable-ocp bench batch``."""
    from cable_ocp import report
    from cable_ocp.bench import batch

    out.check_outputs(args)
    if not (1 <= args.angles <= 1000 and 1 <= args.speeds <= 1000):
        raise out_error("--angles and --speeds: give 1..1000")
    if not 0 <= args.dask <= 64:
        raise out_error("--dask: give 0..64 worker processes")
    if not 1 <= args.repeats <= 100:
        raise out_error(f"--repeats {args.repeats}: give 1..100")
    if args.dask:
        try:
            import distributed  # noqa: F401
        except ImportError:
            raise out_error("--dask needs dask.distributed: pip install -e '.[cluster]'"
                            ) from None
    res = batch.run(args.angles, args.speeds, progress=lambda what: out.note(args, what),
                    repeats=args.repeats, dask_workers=args.dask)
    keys = ["run", "wall_s", "per_case_ms", "solve_ms", "overhead_ms", "speedup", "solved"]
    out.say(args, report.table(["run", "wall [s]", "per case [ms]", "solve/case [ms]",
                                "machinery/case [ms]", "speed-up [-]", "solved"],
                               [["-" if r[k] is None else r[k] for k in keys]
                                for r in res["rows"]]))
    sm = res["summary"]
    out.say(args, f"\n{sm['cases']} cases on one worker: the batch machinery adds "
                  f"{sm['overhead_per_case_ms']:.2f} ms per case "
                  f"({100 * sm['overhead_fraction']:.1f} % of a bare warm solve of "
                  f"{sm['bare_per_case_ms']:.2f} ms, target < 10 %); the cases themselves "
                  f"took {sm['solve_in_batch_per_case_ms']:.2f} ms each (the whole batch "
                  f"{sm['difference_to_bare_per_case_ms']:+.2f} ms per case against the bare "
                  f"loop); speed-up on 2 workers {sm['speedup_2_workers']:.2f}x "
                  f"(target >= 1.8x)")
    if sm.get("ceiling_2_processes"):
        out.say(args, f"this machine's ceiling: two processes of the bare loop at once run "
                      f"{sm['ceiling_2_processes']:.2f}x the work of one (2.00 on free, "
                      "independent cores); the 2-worker batch reaches "
                      f"{100 * sm['efficiency_vs_ceiling']:.0f} % of it")
    if sm.get("load_average"):
        out.say(args, "load average " + ", ".join(f"{x:.2f}" for x in sm["load_average"])
                + f" on {sm['cpu_count']} cores (the speed-up needs them free)")
    out.emit_json(args, out.envelope("ok", "benchmark completed", res))
    return out.EXIT_OK


DYNAMICS_KEYS = ["model", "segments", "time_step", "wall_per_simulated_s", "realtime_factor",
                 "top_tension_amplitude_N", "error", "amplitude_vs_reference",
                 "amplitude_vs_other", "status"]


def cmd_bench_systems(args: argparse.Namespace) -> int:
    """``cable-ocp bench systems``."""
    from cable_ocp.bench import systems as bs
    from cable_ocp.numerics.text_table import table

    out.check_outputs(args)
    if not 1 <= args.repeats <= 100:
        raise out_error(f"--repeats {args.repeats}: give 1..100")
    files = args.files or list(bs.DEFAULT_FILES)
    currents = [] if args.files else list(bs.CURRENT_CASES)
    results = []
    with out.progress(args, len(files) + len(currents), "bench systems", "system") as bar:
        for i, f in enumerate(files):
            bar(i, postfix=Path(f).stem)
            results.append(bs.compare_with_moorpy(f, repeats=args.repeats))
        for j, (f, speed, heading) in enumerate(currents):
            bar(len(files) + j, postfix=Path(f).stem + " + current")
            results.append(bs.ours_with_current(f, speed, heading, repeats=args.repeats))
        bar(len(files) + len(currents))
    head, rows = bs.rows(results)
    out.say(args, "cable_ocp beside MoorPy (no current; differences are the largest over "
                  "the system; times are medians of " + f"{args.repeats} runs; the rows "
                  "'+ current' (1 m/s at 30 deg) are ours alone: MoorPy smears a current)")
    out.say(args, table(head, rows, left=1))
    out.emit_json(args, out.envelope("ok", f"{len(results)} systems", {"rows": results}, []))
    return out.EXIT_OK


def cmd_bench_dynamics(args: argparse.Namespace) -> int:
    """``cable-ocp bench dynamics``."""
    import os

    from cable_ocp.bench import dynamics as bd

    out.check_outputs(args)
    kw: dict[str, Any] = dict(bd.QUICK) if args.quick else {
        "segments": bd.SEGMENTS, "time_steps": bd.TIME_STEPS, "duration": bd.DURATION,
        "repeats": 2, "compile_mode": "step", "moordyn_steps": None,
        "reference_segments": bd.REFERENCE_SEGMENTS, "reference_step": bd.REFERENCE_STEP}
    if args.segments is not None:
        for n in args.segments:
            if not 2 <= n <= 400:
                raise out_error(f"--segments {n}: give 2..400")
        kw["segments"] = tuple(args.segments)
        if kw.get("moordyn_steps") is not None:
            kw["moordyn_steps"] = {n: (4e-3,) if n <= 40 else (2e-3,) if n <= 80 else (2.5e-4,)
                                   for n in args.segments}
    if args.time_steps is not None:
        for dt in args.time_steps:
            if not 1e-4 <= dt <= 1.0:
                raise out_error(f"--time-steps {dt}: give 1e-4..1 s")
        kw["time_steps"] = tuple(args.time_steps)
    if args.duration is not None:
        if not bd.WINDOW + bd.RAMP <= args.duration <= 3600.0:
            raise out_error(f"--duration {args.duration}: give {bd.WINDOW + bd.RAMP:g}..3600 s "
                            f"(the {bd.RAMP:g} s ramp, then the {bd.WINDOW:g} s window the "
                            "errors are taken over)")
        kw["duration"] = args.duration
    tolerance = bd.TOLERANCE
    if args.tolerance is not None:
        if not 1e-14 <= args.tolerance <= 1e-4:
            raise out_error(f"--tolerance {args.tolerance}: give 1e-14..1e-4 (a scaled "
                            "residual)")
        tolerance = args.tolerance
    if args.repeats is not None:
        if not 1 <= args.repeats <= 20:
            raise out_error(f"--repeats {args.repeats}: give 1..20 (the fastest is kept)")
        kw["repeats"] = args.repeats
    with_md = not args.no_moordyn
    if with_md and not bd.moordyn_available():
        out.note(args, "MoorDyn is not installed (pip install moordyn): its rows say so")
    total = bd.planned_rows(kw["segments"], kw["time_steps"], kw.get("moordyn_steps"), with_md)
    done = [0]
    with out.progress(args, total, "bench dynamics", "run") as bar:
        def step(label: str) -> None:
            bar(done[0], postfix=label)
            done[0] += 1

        rows, ref = bd.run(kw["segments"], kw["time_steps"], kw.get("moordyn_steps"),
                           with_moordyn=with_md, compile_mode=kw["compile_mode"],
                           repeats=kw["repeats"], duration=kw["duration"],
                           tolerance=tolerance, reference_segments=kw["reference_segments"],
                           reference_step=kw["reference_step"], progress=step)
        bar(total)
    sm = bd.summary(rows)
    load = os.getloadavg() if hasattr(os, "getloadavg") else None
    out.say(args, f"Huang (1992) 5.7 system at {bd.FREQUENCY} rad/s, {kw['duration']:g} s "
                  "simulated; the top force (the attachment's force on the cable, the top "
                  "node's inertia included, MoorDyn's too); errors over the last "
                  f"{bd.WINDOW:g} s against one converged reference for both models, over "
                  f"its amplitude; cable_ocp's Newton tolerance {tolerance:g} (reference "
                  "1e-10); wall time of the stepping, fastest of "
                  f"{kw['repeats']} (noisy on a shared machine: compare ratios)")
    out.say(args, bd.format_reference(ref))
    if load is not None:
        out.say(args, "load average (1, 5, 15 min): " + ", ".join(f"{v:.2f}" for v in load))
    out.say(args, bd.format_table(rows))
    out.say(args, "\n" + bd.format_summary(sm))
    rows_d = bd.as_dicts(rows)
    # a MoorDyn step beyond its explicit limit failing is a result of the benchmark (its
    # row says so); a cable_ocp run failing is a failure of the command
    failed = [r for r in rows if r.model.startswith("cable_ocp") and r.status != "ok"]
    status = "failed" if failed else "ok"
    message = ("benchmark completed" if not failed else
               f"{len(failed)} cable_ocp run(s) failed: " + "; ".join(
                   f"{r.segments} segments, dt {r.time_step:g} s: {r.status}" for r in failed))
    out.emit_json(args, out.envelope(status, message, {
        "rows": rows_d, "summary": sm, "reference": ref.info,
        "reference_amplitude_N": ref.amplitude, "load_average": list(load) if load else None,
        "duration_s": kw["duration"], "frequency_rad_s": bd.FREQUENCY,
        "newton_tolerance": tolerance}))
    if args.plot:
        from cable_ocp.plots.bench import plot_dynamics_work_precision

        out.emit_plot(args, lambda path: plot_dynamics_work_precision(rows, path))
    return out.EXIT_OK if status == "ok" else out.EXIT_NOT_SUCCESS


def cmd_bench_deploy(args: argparse.Namespace) -> int:
    """``cable-ocp bench deploy``."""
    import math
    import os
    import sys

    from cable_ocp.bench import deployment as bd
    from cable_ocp.cli.bench_deploy import format_compare, format_cost, format_long
    from cable_ocp.numerics.atomic import write_text_file

    out.check_outputs(args)
    parts = list(dict.fromkeys(args.part or bd.PARTS))
    if not 0.0 < args.rel_tol < 1.0:
        raise out_error(f"--rel-tol {args.rel_tol}: give a width in (0, 1)")
    if args.motion_step is not None and not 1e-3 <= args.motion_step <= 10.0:
        raise out_error(f"--motion-step {args.motion_step}: give 0.001..10 s")
    if args.max_iter is not None and not 1 <= args.max_iter <= 100000:
        raise out_error(f"--max-iter {args.max_iter}: give 1..100000 iterations")
    if args.floor_fraction is not None and not 0.0 < args.floor_fraction < 1.0:
        raise out_error(f"--floor-fraction {args.floor_fraction}: give a fraction in (0, 1)")
    segs = args.segments or list(bd.COST_SEGMENTS)
    for n in segs + [args.long_segments]:
        if not 1 <= n <= 400:
            raise out_error(f"--segments/--long-segments {n}: give 1..400 elements")
    durs = args.durations or list(bd.COST_DURATIONS)
    for t in durs + [args.long_duration]:
        if not (math.isfinite(t) and 0.0 < t <= 7200.0):
            raise out_error(f"--durations/--long-duration {t}: give 0..7200 s")
    if args.long_time_step is not None and not 1e-3 <= args.long_time_step <= 10.0:
        raise out_error(f"--long-time-step {args.long_time_step}: give 0.001..10 s")
    if not args.budget > 0.0:
        raise out_error(f"--budget {args.budget}: give a time > 0 s")
    load = os.getloadavg() if hasattr(os, "getloadavg") else None
    data: dict[str, Any] = {"parts": parts, "cpu_count": os.cpu_count(),
                            "load_average_start": list(load) if load else None}

    def note(what: str) -> None:
        out.note(args, f"bench deploy: {what} ...")

    def save(what: str) -> None:
        # the JSON so far, rewritten whole after each finished step (a file, not stdout:
        # one document there), so that a stopped run keeps what it finished
        if args.json and args.json != out.STDOUT:
            out.write_output("--json", args.json, lambda tmp: write_text_file(
                tmp, out.json_text(out.envelope("partial", f"bench deploy: running; "
                                                f"done: {what}", data)) + "\n"))

    if "compare" in parts:
        cases = args.case or [str(p) for p in bd.COMPARE_CASES]
        data["compare"] = []

        def keep(case: dict[str, Any]) -> None:
            if not data["compare"] or data["compare"][-1] is not case:
                data["compare"].append(case)  # a new case: its slot, filled row by row
            save(f"{case['case']}: {case['rows'][-1]['method']}")

        for c in cases:
            res = bd.compare_case(c, rel_tol=args.rel_tol, motion_step=args.motion_step,
                                  floor_fraction=args.floor_fraction,
                                  ipopt={"ipopt.max_iter": args.max_iter}
                                  if args.max_iter else None, progress=note,
                                  on_row=keep)
            if not data["compare"] or data["compare"][-1] is not res:
                data["compare"].append(res)
            out.say(args, format_compare([res]))  # the case's table at once
            sys.stdout.flush()
        save("compare")
    if "cost" in parts:
        kw: dict[str, Any] = {"budget_s": args.budget, "progress": note}
        if args.cost_file:
            kw["path"] = args.cost_file
        rows = bd.cost_grid(durs, segs, **kw)
        data["cost"] = {"rows": rows, "fits": bd.cost_fits(rows),
                        "file": str(args.cost_file or bd.COST_FILE),
                        "speed_m_s": bd.COST_SPEED}
        out.say(args, format_cost(data["cost"]))
        save("cost")
    if "long" in parts:
        data["long"] = bd.long_run(duration=args.long_duration, segments=args.long_segments,
                                   time_step=args.long_time_step, progress=note)
        out.say(args, format_long(data["long"]))
    load = os.getloadavg() if hasattr(os, "getloadavg") else None
    data["load_average_end"] = list(load) if load else None
    if load is not None:
        out.say(args, "\nload average (1, 5, 15 min) at the end: "
                      + ", ".join(f"{v:.2f}" for v in load) + f" on {os.cpu_count()} cores")
    out.emit_json(args, out.envelope("ok", "benchmark completed", data))
    return out.EXIT_OK
