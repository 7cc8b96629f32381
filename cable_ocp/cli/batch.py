"""``cable-ocp batch``: a load-case study over a matrix of cases (parse, call, format)."""

from __future__ import annotations

import argparse
import contextlib
from collections.abc import Sequence
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
                        "main output; heave: every controller's heave RMS but the passive)")
    p.add_argument("--arrays", metavar="FILE.nc",
                   help="keep every case's arrays (statics: tension and position along the "
                        "line; dynamics, heave: time series) in one netCDF file, chunked by "
                        "case (needs pip install -e '.[io]')")
    p.add_argument("--range-graph", metavar="PATH",
                   help="statics: draw the envelope (min, max, mean over the cases) of the "
                        "tension along the line against arc length (PNG, PDF, SVG)")
    p.set_defaults(func=cmd_batch)


def cmd_batch(args: argparse.Namespace) -> int:
    """``cable-ocp batch FILE ...``."""
    from cable_ocp import report
    from cable_ocp.batch import parse_grid, parse_random, parse_range, run_batch
    from cable_ocp.batch.store import default_out, paths
    from cable_ocp.batch.summary import extremes
    from cable_ocp.scene import apply_overrides, read_problem
    from cable_ocp.scene.heave import resolve_cable_scene

    if args.out is None:
        args.out = str(default_out(args.file))
    store = paths(args.out)
    for p in store:
        out.check_output_path(str(p), "--out", allow_stdout=False)
    out.check_outputs(args, [("--out", p) for p in store] + _array_outputs(args))
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
    # read here for the checks before any case runs (run_batch reads the file again: its
    # digest goes into the meta file)
    data = apply_overrides(read_problem(args.file), out.overrides(args))
    data = resolve_cable_scene(data, Path(args.file).parent)
    unit = data.get("unit")
    scene_file = unit.get("cable_scene") if isinstance(unit, dict) else None
    out.check_outputs(args, [("--out", p) for p in store] + _array_outputs(args),
                      inputs=[("[unit] cable_scene", scene_file)] if isinstance(scene_file, str)
                      else [])
    _check_arrays(args, data)
    failures = 0
    with out.progress(args, 1, "batch", "case") as bar:
        def step(done: int, total: int, row: dict[str, Any]) -> None:
            nonlocal failures
            failures += row["status"] not in ("solved",)
            bar(done, total, postfix=f"{failures} not solved")

        # the file's path (its digest goes into the meta file; a heave scene's relative
        # [unit] cable_scene is read from its folder) and the --set overrides apart
        try:
            res = run_batch(args.file, grids, ranges, args.samples, randoms, args.seed,
                            overrides=out.overrides(args),
                            command=args.command, options={"directions": args.directions},
                            out=args.out, resume=args.resume, overwrite=args.overwrite,
                            workers=args.workers, scheduler=args.scheduler,
                            chunk_size=args.chunk_size, progress=step, arrays=args.arrays,
                            keep_arrays=bool(args.range_graph))
        except KeyboardInterrupt:
            _interrupted_summary(args, store)
            raise
    if res.rows and all(r["status"] == "invalid_input" for r in res.rows):
        raise CableOCPError(f"every case is invalid; the first: {res.rows[0]['message']}")
    for remark in res.notes:
        out.note(args, f"note: {remark}")
    dups = res.duplicates()
    for group in dups:
        out.note(args, f"note: cases {', '.join(map(str, group))} have identical parameters "
                       "(separate rows, each with its own seed)")
    counts = res.statuses()
    summary = extremes(res)
    out.say(args, f"{Path(args.file).stem}: {len(res.rows)} cases ({res.kind}), "
                  f"{res.skipped} already done, {res.wall_time_s:.1f} s")
    out.say(args, report.table(["status", "cases"], sorted(counts.items())))
    if summary:
        from cable_ocp.plots.batch import default_columns

        out.say(args, report.batch_extremes(summary, [args.plot_output] if args.plot_output
                                            else default_columns(res)))
    for p in res.paths or ():
        out.confirm(args, str(p))
    if args.arrays and res.arrays:
        out.confirm(args, args.arrays, "netCDF")
    status = "solved" if res.failures == 0 else "partial"
    out.emit_json(args, out.envelope(
        status, f"{len(res.rows) - res.failures} of {len(res.rows)} cases solved",
        {"kind": res.kind, "cases": len(res.rows), "statuses": counts, "extremes": summary,
         "duplicates": dups, "notes": res.notes,
         "files": [str(p) for p in res.paths or ()] + ([args.arrays] if args.arrays else []),
         "wall_time_s": res.wall_time_s}))
    if args.plot:
        column = args.plot_output
        if column is not None and column not in res.outputs:
            raise CableOCPError(f"--plot-output {column!r}: valid are "
                                + ", ".join(repr(c) for c in res.outputs))
        from cable_ocp.plots.batch import plot_batch

        out.emit_plot(args, lambda path: plot_batch(res, column, path,
                                                    title=Path(args.file).stem))
    if args.range_graph and res.arrays:
        from cable_ocp.plots.batch import plot_range_graph

        solved = [r["case"] for r in res.rows if r["status"] == "solved"]
        out.emit_plot(args, lambda path: plot_range_graph(
            res.arrays, path, title=Path(args.file).stem, cases=solved), args.range_graph)
    return out.EXIT_OK if res.failures == 0 else out.EXIT_NOT_SUCCESS


def _array_outputs(args: argparse.Namespace) -> list[tuple[str, str]]:
    """``--arrays`` and ``--range-graph``, checked like the other outputs."""
    out.check_output_path(args.arrays, "--arrays", allow_stdout=False, formats=("nc",))
    out.check_output_path(args.range_graph, "--range-graph", allow_stdout=False,
                          formats=out.plot_formats())
    return [(o, p) for o, p in (("--arrays", args.arrays), ("--range-graph", args.range_graph))
            if p is not None]


def _interrupted_summary(args: argparse.Namespace, store: Sequence[Path]) -> None:
    """``--json`` of an interrupted batch: status ``interrupted`` and the cases stored (the
    store's JSON lines, every row whole), per status; then the interruption goes on."""
    import json

    if not args.json:
        return
    rows = []
    with contextlib.suppress(OSError):
        for line in store[1].read_text(encoding="utf-8").splitlines():
            with contextlib.suppress(ValueError):
                row = json.loads(line)
                if isinstance(row, dict) and "status" in row:
                    rows.append(row)
    counts: dict[str, int] = {}
    for r in rows:
        counts[str(r["status"])] = counts.get(str(r["status"]), 0) + 1
    out.emit_json(args, out.envelope(
        "interrupted", f"interrupted: {len(rows)} cases stored in {store[1]}; --resume "
        "continues", {"cases_stored": len(rows), "statuses": counts,
                      "files": [str(p) for p in store]}))


def _check_arrays(args: argparse.Namespace, data: dict[str, Any]) -> None:
    """Before any case runs: xarray for ``--arrays``, a statics batch for a range graph."""
    from cable_ocp.batch.arrays import require_xarray
    from cable_ocp.batch.kinds import runner_kind

    if args.arrays:
        require_xarray()
    if args.range_graph and runner_kind(data, args.command) != "statics":
        raise CableOCPError(f"--range-graph: draws the tension along the line of a statics "
                            f"batch, not of a {runner_kind(data, args.command)} batch")
