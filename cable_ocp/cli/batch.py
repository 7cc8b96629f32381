"""``cable-ocp batch``: a load-case study over a matrix of cases (parse, call, format)."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

from cable_ocp.cli import output as out
from cable_ocp.errors import CableOCPError


def register(sub: argparse._SubParsersAction, parent: argparse.ArgumentParser) -> None:
    """Add ``batch``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The ``cable-ocp`` parser's subparsers, to which the command is added.
    parent : argparse.ArgumentParser
        The common options (``--quiet``, ``--debug``: :func:`cable_ocp.cli.output.common_parent`),
        a parent of every parser added.
    """
    p = sub.add_parser(
        "batch", parents=[parent],
        help="load-case study: a grid, ranges or random samples of any key, on all cores "
             "or a dask cluster",
        description="Run one problem file over a matrix of cases: the full grid of every "
                    "--grid and --range, times --samples seeded random draws of the --random "
                    "keys. Cases run on every local core by default (--workers) or on a "
                    "dask.distributed cluster (--scheduler); each worker builds its solver "
                    "once and warm-starts each case from its neighbour. Every case ends as a "
                    "row in OUT.csv and OUT.jsonl, written as it arrives; an interrupted batch "
                    "continues with --resume. Exit 0 when every case succeeded, 1 when some "
                    "did not (see the status column), 2 invalid input, 130 interrupted.")
    p.add_argument("file", help="problem file (statics, footprint or heave scene)")
    p.add_argument("--grid", action="append", default=[], metavar="KEY=V1,V2,...",
                   help="sweep a dotted key over these values (TOML values; repeatable)")
    p.add_argument("--range", dest="ranges", action="append", default=[],
                   metavar="KEY=START:STOP:N",
                   help="sweep a dotted key over N evenly spaced values (repeatable)")
    p.add_argument("--samples", type=int, default=0, metavar="N",
                   help="seeded random draws of the --random keys")
    p.add_argument("--random", action="append", default=[], metavar="KEY=DIST(a,b)",
                   help="draw a key from uniform(low,high), normal(mean,std) or "
                        "lognormal(mu,sigma) (repeatable; needs --samples)")
    p.add_argument("--seed", type=int, default=0, metavar="S",
                   help="batch seed: random draws and every case's own seed (default 0)")
    p.add_argument("--command", choices=["statics", "footprint"],
                   help="for a statics scene: solve (default) or footprint; heave and "
                        "dynamic (simulate) scenes need none")
    p.add_argument("--directions", type=int, default=36, metavar="N",
                   help="footprint directions per case (default 36)")
    p.add_argument("--out", metavar="PATH",
                   help="results: PATH.csv, PATH.jsonl and PATH.meta.json (inputs, units); "
                        "default: the problem file's name with _batch, in the current "
                        "directory (x.toml -> x_batch.csv, ...). One batch at a time writes "
                        "there (PATH.lock)")
    p.add_argument("--resume", action="store_true",
                   help="continue the batch stored at --out with the same inputs (problem "
                        "file, --set, sweeps, seed), skipping finished cases and running "
                        "worker_lost ones again")
    p.add_argument("--overwrite", action="store_true",
                   help="replace the results stored at --out")
    p.add_argument("--workers", type=int, metavar="N",
                   help="local worker processes (default: every core; 0 = in this process)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="run on a dask.distributed scheduler, e.g. tcp://10.0.0.5:8786 "
                        "(needs pip install -e '.[cluster]')")
    p.add_argument("--chunk-size", type=int, metavar="N",
                   help="consecutive cases per task (default: shrinking chunks, each 1/(2 x "
                        "workers) of the cases left, so that the workers finish together)")
    out.add_set_option(p)
    out.add_json_option(p, "the summary (statuses, extremes, files)")
    out.add_plot_option(p, "an output over one swept key (line) or two (heat map)")
    p.add_argument("--plot-output", metavar="COLUMN",
                   help="output column to plot, e.g. 'max_tension [N]' (default: the kind's "
                        "main output)")
    p.set_defaults(func=cmd_batch)


MAIN_OUTPUT = {"statics": "max_tension [N]", "footprint": "max_reach [m]",
               "dynamics": "max_top_tension [N]"}


def cmd_batch(args: argparse.Namespace) -> int:
    """``cable-ocp batch FILE ...``."""
    from cable_ocp import report
    from cable_ocp.batch import parse_grid, parse_random, parse_range, run_batch
    from cable_ocp.batch.store import default_out, paths

    if args.out is None:
        args.out = str(default_out(args.file))
    store = paths(args.out)
    for p in store:
        out.check_output_path(str(p), "--out", allow_stdout=False)
    out.check_outputs(args, [("--out", p) for p in store])
    if args.workers is not None and not 0 <= args.workers <= 1024:
        raise CableOCPError(f"--workers {args.workers}: give 0..1024")
    if args.chunk_size is not None and args.chunk_size < 1:
        raise CableOCPError(f"--chunk-size {args.chunk_size}: give >= 1")
    if not 3 <= args.directions <= 3600:
        raise CableOCPError(f"--directions {args.directions}: give 3..3600")
    if args.resume and args.overwrite:
        raise CableOCPError("--resume and --overwrite: choose one")
    grids = [parse_grid(g) for g in args.grid]
    ranges = [parse_range(r) for r in args.ranges]
    randoms = [parse_random(r) for r in args.random]
    if not (grids or ranges or randoms):
        raise CableOCPError("give at least one --grid, --range or --random (with --samples)")
    failures = 0
    with out.progress(args, 1, "batch", "case") as bar:
        def step(done: int, total: int, row: dict[str, Any]) -> None:
            nonlocal failures
            failures += row["status"] not in ("solved",)
            bar(done, total, postfix=f"{failures} not solved")

        # the file's path (its digest goes into the meta file; a heave scene's relative
        # [unit] cable_scene is read from its folder) and the --set overrides apart
        res = run_batch(args.file, grids, ranges, args.samples, randoms, args.seed,
                        overrides=out.overrides(args),
                        command=args.command, options={"directions": args.directions},
                        out=args.out, resume=args.resume, overwrite=args.overwrite,
                        workers=args.workers, scheduler=args.scheduler,
                        chunk_size=args.chunk_size, progress=step)
    if res.rows and all(r["status"] == "invalid_input" for r in res.rows):
        raise CableOCPError(f"every case is invalid; the first: {res.rows[0]['message']}")
    for remark in res.notes:
        out.note(args, f"note: {remark}")
    dups = res.duplicates()
    for group in dups:
        out.note(args, f"note: cases {', '.join(map(str, group))} have identical parameters "
                       "(separate rows, each with its own seed)")
    counts = res.statuses()
    summary = _extremes(res)
    out.say(args, f"{Path(args.file).stem}: {len(res.rows)} cases ({res.kind}), "
                  f"{res.skipped} already done, {res.wall_time_s:.1f} s")
    out.say(args, report.table(["status", "cases"], sorted(counts.items())))
    if summary:
        out.say(args, report.table(["output", "min", "at case", "max", "at case"],
                                   [[k, v["min"], v["min_case"], v["max"], v["max_case"]]
                                    for k, v in summary.items()]))
    for p in res.paths or ():
        out.confirm(args, str(p))
    status = "solved" if res.failures == 0 else "partial"
    out.emit_json(args, out.envelope(
        status, f"{len(res.rows) - res.failures} of {len(res.rows)} cases solved",
        {"kind": res.kind, "cases": len(res.rows), "statuses": counts, "extremes": summary,
         "duplicates": dups, "notes": res.notes,
         "files": [str(p) for p in res.paths or ()], "wall_time_s": res.wall_time_s}))
    if args.plot:
        column = args.plot_output or MAIN_OUTPUT.get(res.kind) or res.outputs[1]
        if column not in res.outputs:
            raise CableOCPError(f"--plot-output {column!r}: valid are "
                                + ", ".join(repr(c) for c in res.outputs))
        from cable_ocp.plots.batch import plot_batch

        out.emit_plot(args, lambda path: plot_batch(res, column, path,
                                                    title=Path(args.file).stem))
    return out.EXIT_OK if res.failures == 0 else out.EXIT_NOT_SUCCESS


def _extremes(res: Any) -> dict[str, dict[str, Any]]:
    """Min and max of each output over the successful cases, with the case index."""
    out_: dict[str, dict[str, Any]] = {}
    ok = [r for r in res.rows if r["status"] == "solved"]
    for col in res.outputs:
        vals = [(r[col], r["case"]) for r in ok if r.get(col) is not None
                and math.isfinite(r[col])]
        if vals:
            lo, hi = min(vals), max(vals)
            out_[col] = {"min": lo[0], "min_case": lo[1], "max": hi[0], "max_case": hi[1]}
    return out_
