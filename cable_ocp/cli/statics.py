"""``cable-ocp solve`` and ``cable-ocp footprint``: parse, call the library, format."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from cable_ocp.cli import output as out
from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import interrupt

PROFILE_HEADER = ["s [m]", "x [m]", "y [m]", "z [m]", "Tx [N]", "Ty [N]", "Tz [N]",
                  "tension [N]"]


def register(sub: argparse._SubParsersAction, parent: argparse.ArgumentParser) -> None:
    """Add ``solve`` and ``footprint``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The ``cable-ocp`` parser's subparsers, to which the commands are added.
    parent : argparse.ArgumentParser
        The common options (``--quiet``, ``--debug``: :func:`cable_ocp.cli.output.common_parent`),
        a parent of every parser added.
    """
    p = sub.add_parser(
        "solve", parents=[parent], help="solve a static cable problem (TOML file)",
        description="Solve a static cable problem: print a summary (length, end angles, "
                    "forces and tensions, line stiffness, solver status, error estimate), and "
                    "optionally write JSON, the profile as CSV and a figure. Exit 0 solved, "
                    "1 not solved (the JSON status says why), 2 invalid input.")
    p.add_argument("file", help="problem file (UTF-8 TOML, SI units), e.g. "
                                "problems/dezoysa_sea_buggy.toml")
    out.add_set_option(p)
    out.add_json_option(p, "the solution (status, ends, profile, solver diagnostics)")
    out.add_csv_option(p, "the profile, one row per node")
    out.add_plot_option(p, "the profile and the tension along the cable")
    out.add_force_option(p)
    p.set_defaults(func=cmd_solve)

    f = sub.add_parser(
        "footprint", parents=[parent],
        help="footprint of a thrust-limited, tethered seabed unit (Huang 1992, 2.2.4)",
        description="Reach of a tethered seabed unit in N directions: one NLP per direction "
                    "over the thrust and the cable length, built once and warm-started from "
                    "the neighbouring direction. Exit 0 when every direction is solved, 1 "
                    "when some is not (unreachable directions report the optimiser's status, "
                    "e.g. infeasible).")
    f.add_argument("file", help="problem file with a [footprint] table, e.g. "
                                "problems/footprint_tethered_unit.toml")
    f.add_argument("--directions", type=int, default=72, metavar="N",
                   help="number of equally spaced directions from +x (default 72)")
    out.add_set_option(f)
    out.add_json_option(f, "the polygon and the per-direction results")
    out.add_csv_option(f, "one row per direction")
    out.add_plot_option(f, "the footprint polygon around the ship")
    out.add_force_option(f)
    f.set_defaults(func=cmd_footprint)


def _title(scene: Any, file: str) -> str:
    return scene.meta.get("title", Path(file).stem)


def solution_json(sol: Any) -> dict[str, Any]:
    """The JSON document of a statics solution (the output-contract envelope)."""
    data = sol.to_dict()
    return out.envelope(data["status"], data["message"], data, data.get("warnings", []))


def profile_rows(sol: Any) -> list[list[float]]:
    """One CSV row per distinct node (s, x, y, z, Tx, Ty, Tz, |T|)."""
    import numpy as np

    keep = np.concatenate([[True], np.diff(sol.s) > 0])
    t = sol.tension_vector[keep]
    return np.column_stack([sol.s[keep], sol.position[keep], t,
                            np.linalg.norm(t, axis=1)]).tolist()


def cmd_solve(args: argparse.Namespace) -> int:
    """``cable-ocp solve FILE``."""
    from cable_ocp import report
    from cable_ocp.cli.cost import statics_cost
    from cable_ocp.cli.system import cmd_solve_system, is_system_file
    from cable_ocp.scene import load_scene
    from cable_ocp.statics.solver import solve

    if is_system_file(args.file):
        return cmd_solve_system(args)
    out.check_outputs(args)
    scene = load_scene(args.file, out.overrides(args))
    out.check_cost(args, statics_cost(scene))
    sol = solve(scene)
    out.say(args, report.statics_summary(sol, title=_title(scene, args.file)))
    out.emit_json(args, solution_json(sol))
    out.emit_csv(args, PROFILE_HEADER, profile_rows(sol))
    if args.plot:
        from cable_ocp.plots.statics import plot_statics

        out.emit_plot(args, lambda path: plot_statics(sol, path, title=_title(scene, args.file),
                                                      scene=scene))
    if not sol.success:
        out.note(args, f"cable-ocp: not solved ({sol.status}): {sol.message}")
        return out.EXIT_NOT_SUCCESS
    return out.EXIT_OK


FOOTPRINT_HEADER = ["theta [deg]", "reach [m]", "x [m]", "y [m]", "thrust_x [N]",
                    "thrust_y [N]", "length [m]", "status"]
_FP_KEYS = ["theta_deg", "reach", "x", "y", "thrust_x", "thrust_y", "length", "status"]


def cmd_footprint(args: argparse.Namespace) -> int:
    """``cable-ocp footprint FILE``."""
    from cable_ocp import report
    from cable_ocp.cli.cost import statics_cost
    from cable_ocp.scene import load_scene
    from cable_ocp.statics.footprint_nlp import footprint

    out.check_outputs(args)
    if args.directions < 3 or args.directions > 3600:
        raise CableOCPError(f"--directions {args.directions}: give 3..3600")
    scene = load_scene(args.file, out.overrides(args))
    out.check_cost(args, statics_cost(scene, directions=args.directions))
    rows: list[dict[str, Any]] = []
    interrupted = False
    with out.progress(args, args.directions, "footprint", "dir") as bar:
        def step(done: int, total: int, row: dict[str, Any]) -> None:
            rows.append(row)
            bar(done, postfix=f"{sum(r['status'] != 'solved' for r in rows)} unreachable")

        try:
            res = footprint(scene, args.directions, progress=step)
            wall = res.wall_time_s
        except (KeyboardInterrupt, Exception) as exc:  # a CasADi error may stand for a Ctrl-C
            if not interrupt.is_interruption(exc):
                raise
            interrupted, wall = True, None
    n_bad = sum(r["status"] != "solved" for r in rows)
    status = ("interrupted" if interrupted else "solved" if n_bad == 0 else "partial")
    message = (f"interrupted after {len(rows)} of {args.directions} directions" if interrupted
               else f"{len(rows) - n_bad} of {len(rows)} directions solved")
    table = [[r[k] if k == "status" else ("-" if r[k] != r[k] else f"{r[k]:.3f}")
              for k in _FP_KEYS] for r in rows]
    out.say(args, f"{_title(scene, args.file)}: {message}"
            + (f", {wall:.2f} s" if wall is not None else ""))
    out.say(args, report.table(FOOTPRINT_HEADER, table))
    out.emit_json(args, out.envelope(status, message, {
        "directions": rows, "wall_time_s": wall,
        "ship": list(scene.end_b.position[:2])}))
    out.emit_csv(args, FOOTPRINT_HEADER, [[r[k] for k in _FP_KEYS] for r in rows],
                 partial=interrupted)
    if args.plot and not interrupted:
        from cable_ocp.plots.statics_series import plot_footprint

        out.emit_plot(args, lambda path: plot_footprint(res, path, _title(scene, args.file),
                                                        scene=scene))
    if interrupted:
        raise KeyboardInterrupt
    return out.EXIT_OK if n_bad == 0 else out.EXIT_NOT_SUCCESS
