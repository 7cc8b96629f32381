"""``cable-ocp solve`` on a mooring system (a system TOML or a MoorDyn v2 input file), and
``cable-ocp convert``: parse, call the library, format."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from cable_ocp.cli import output as out
from cable_ocp.errors import CableOCPError

LINE_HEADER = ["line", "point_a", "point_b", "length [m]", "tension_a [N]", "tension_b [N]",
               "max_tension [N]", "safety_factor [-]", "laid_length [m]",
               "anchor_horizontal [N]", "anchor_vertical [N]", "status"]


def is_system_file(path: str) -> bool:
    """True when ``path`` is a MoorDyn file or a TOML problem with ``[[lines]]``.

    Parameters
    ----------
    path : str
        The problem file named on the command line.
    """
    from cable_ocp.scene.system import is_moordyn_path, is_system

    if is_moordyn_path(path):
        return True
    from cable_ocp.scene import read_problem

    try:
        return is_system(read_problem(path))
    except CableOCPError:
        return False  # the statics loader reports the file's problem


def line_rows(res: Any) -> list[list[Any]]:
    """One CSV row per line."""
    rows = []
    for ln in res.lines:
        anchor = ln.get("anchor_a") or ln.get("anchor_b")
        rows.append([ln["name"], ln["point_a"], ln["point_b"], ln["length"], ln["tension_a"],
                     ln["tension_b"], ln["max_tension"], ln["safety_factor"],
                     ln["laid_length"], anchor["horizontal"] if anchor else None,
                     anchor["vertical"] if anchor else None, ln["status"]])
    return rows


def cmd_solve_system(args: argparse.Namespace) -> int:
    """``cable-ocp solve FILE`` for a system."""
    from cable_ocp import report
    from cable_ocp.mooring import solve_system
    from cable_ocp.scene.system import load_system

    out.check_outputs(args)
    scene = load_system(args.file, out.overrides(args))
    res = solve_system(scene)
    title = scene.meta.get("title", Path(args.file).stem)
    out.say(args, report.system_summary(res, title=title))
    data = res.to_dict()
    out.emit_json(args, out.envelope(data["status"], data["message"], data, []))
    out.emit_csv(args, LINE_HEADER, line_rows(res))
    if args.plot:
        from cable_ocp.plots.system import plot_system

        out.emit_plot(args, lambda path: plot_system(res, path, title=title, scene=scene))
    if not res.converged:
        out.note(args, f"cable-ocp: not solved ({res.status}): {res.message}")
        return out.EXIT_NOT_SUCCESS
    return out.EXIT_OK


def register(sub: argparse._SubParsersAction, parent: argparse.ArgumentParser) -> None:
    """Add ``convert``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The ``cable-ocp`` parser's subparsers.
    parent : argparse.ArgumentParser
        The common options.
    """
    c = sub.add_parser(
        "convert", parents=[parent],
        help="convert a mooring system between a MoorDyn v2 input file and our TOML",
        description="Read a system (a MoorDyn v2 input file: .dat, .txt; or a system TOML) "
                    "and write it in the other format: MoorDyn's z = 0 is the free surface, "
                    "ours the seabed (z_ours = z_moordyn + water depth). Exit 0 written, 2 "
                    "invalid input or an output that cannot be written.")
    c.add_argument("file", help="the system to read, e.g. problems/systems/spar_3line.toml")
    c.add_argument("output", help="the file to write: .toml for ours, .dat or .txt for "
                                  "MoorDyn")
    c.set_defaults(func=cmd_convert)


def cmd_convert(args: argparse.Namespace) -> int:
    """``cable-ocp convert IN OUT``."""
    from cable_ocp.scene import read_problem
    from cable_ocp.scene.moordyn import read_moordyn, system_dict_to_toml, write_moordyn
    from cable_ocp.scene.system import is_moordyn_path, is_system, system_from_dict

    out.check_output_path(args.output, "output", allow_stdout=False)
    data = read_moordyn(args.file) if is_moordyn_path(args.file) else read_problem(args.file)
    if not is_system(data):
        raise CableOCPError(f"{args.file!r} is not a mooring system (no [[lines]])")
    system_from_dict(data)  # validated before anything is written
    if is_moordyn_path(args.output):
        out.write_output("output", args.output, lambda path: write_moordyn(data, path))
    elif args.output.endswith(".toml"):
        text = system_dict_to_toml(data)
        out.write_output("output", args.output,
                         lambda path: Path(path).write_text(text, encoding="utf-8"))
    else:
        raise CableOCPError(f"output {args.output!r}: give a .toml (ours) or a .dat or .txt "
                            "(MoorDyn) file")
    out.confirm(args, args.output, "MoorDyn" if is_moordyn_path(args.output) else "TOML")
    return out.EXIT_OK
