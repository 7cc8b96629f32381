"""``cable-ocp solve`` on a mooring system (a system TOML or a MoorDyn v2 input file), and
``cable-ocp convert``: parse, call the library, format."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from cable_ocp.cli import output as out
from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import interrupt

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
    """Add ``convert`` and ``mooring-checks``.

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
    register_checks(sub, parent)


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


def register_checks(sub: argparse._SubParsersAction, parent: argparse.ArgumentParser) -> None:
    """Add ``mooring-checks``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The ``cable-ocp`` parser's subparsers.
    parent : argparse.ArgumentParser
        The common options.
    """
    c = sub.add_parser(
        "mooring-checks", parents=[parent],
        help="design checks of a moored body: restoring curve, heading loads, line failure",
        description="The checks the mooring standards ask for (docs/systems.md, 'Design "
                    "checks'): the restoring curve along --heading over --offsets about the "
                    "position without environmental load; the equilibrium under the body's "
                    "steady load (its magnitude) from every --headings; each line removed in "
                    "turn under the file's loads. Exit 0 when every case is solved, 1 when "
                    "some is not (its status says why).")
    c.add_argument("file", help="a system, e.g. problems/systems/spread_9line.toml")
    c.add_argument("--body", default=None, help="the body (default: the only free one)")
    c.add_argument("--heading", type=float, default=0.0, metavar="DEG",
                   help="heading of the restoring curve, deg from +x towards +y (default 0)")
    c.add_argument("--offsets", default="-20:40:13", metavar="START:STOP:N",
                   help="offsets of the restoring curve, m (default -20:40:13)")
    c.add_argument("--headings", default="0:330:12", metavar="START:STOP:N",
                   help="headings of the steady load, deg (default 0:330:12)")
    out.add_set_option(c)
    out.add_json_option(c, "the three checks")
    out.add_plot_option(c, "the restoring curve and the lines' tensions along it")
    c.set_defaults(func=cmd_checks)


def _span(text: str, option: str) -> list[float]:
    import numpy as np

    try:
        a, b, n = text.split(":")
        vals = np.linspace(float(a), float(b), int(n))
    except ValueError:
        raise CableOCPError(f"{option} {text!r}: expected START:STOP:N, e.g. -20:40:13") from None
    if not 1 <= len(vals) <= 1000:
        raise CableOCPError(f"{option} {text!r}: N must be in 1..1000")
    return [float(v) for v in vals]


def cmd_checks(args: argparse.Namespace) -> int:
    """``cable-ocp mooring-checks FILE``."""
    import numpy as np

    from cable_ocp.mooring.checks import heading_loads, line_failure, offset_curve
    from cable_ocp.numerics.text_table import table
    from cable_ocp.scene.system import load_system

    offsets = _span(args.offsets, "--offsets")
    headings = _span(args.headings, "--headings")
    out.check_outputs(args)
    scene = load_system(args.file, out.overrides(args))
    free = [b for b in scene.bodies if b.free]
    body = args.body or (free[0].name if len(free) == 1 else None)
    if body is None:
        raise CableOCPError("--body: name the body (the system has "
                            f"{len(free)} free bodies: {', '.join(b.name for b in free)})")
    b = scene.body(body)
    load = float(np.hypot(b.force[0], b.force[1]))
    runs = [("offset_curve", lambda: offset_curve(scene, body, args.heading, offsets)),
            ("headings", (lambda: heading_loads(scene, body, load, b.moment, headings))
             if load > 0 else None),
            ("line_failure", lambda: line_failure(scene, body))]
    done: dict[str, Any] = {}
    interrupted = False
    with out.progress(args, len(runs), "mooring checks", "check") as bar:
        for i, (name, run_check) in enumerate(runs):
            bar(i, postfix=name)
            try:
                done[name] = run_check() if run_check is not None else None
            except (KeyboardInterrupt, Exception) as exc:  # a CasADi error may be a Ctrl-C
                if not interrupt.is_interruption(exc):
                    raise
                interrupted = True
                break
        if not interrupted:
            bar(len(runs))
    curve, heads, fail = (done.get(k) for k in ("offset_curve", "headings", "line_failure"))
    kn = 1e-3
    text = []
    if curve is not None:
        text += [f"restoring curve of {body} along {args.heading:g} deg (about its position "
                 "without environmental load):",
                 table(["offset", "restoring", "T_max", "SF", "status"],
                       [[o, f * kn, t * kn, s, st] for o, f, t, s, st in zip(
                           curve.offsets, curve.restoring_force, curve.max_tension,
                           curve.min_safety_factor, curve.status, strict=True)],
                       units=["[m]", "[kN]", "[kN]", "[-]", ""])]
    if heads is not None:
        text += ["", f"steady load of {load * kn:.6g} kN from each heading:",
                 table(["heading", "offset", "T_max", "line", "SF", "status"],
                       [[h, o, t * kn, ln, s, st] for h, o, t, ln, s, st in zip(
                           heads.headings_deg, heads.offset, heads.max_tension,
                           heads.max_tension_line, heads.min_safety_factor, heads.status,
                           strict=True)], units=["[deg]", "[m]", "[kN]", "", "[-]", ""])]
    if fail is not None:
        text += ["", "line failure (each line removed in turn, the file's loads):",
                 table(["removed", "T_max", "line", "SF", "offset", "status"],
                       [[r, t * kn, ln, s, o, st] for r, t, ln, s, o, st in zip(
                           fail.removed, fail.max_tension, fail.max_tension_line,
                           fail.min_safety_factor, fail.offset, fail.status, strict=True)],
                       units=["", "[kN]", "", "[-]", "[m]", ""])]
    if text:
        out.say(args, "\n".join(text))
    statuses = [s for c in (curve, heads, fail) if c is not None for s in c.status]
    ok = all(s == "solved" for s in statuses)
    data = {k: (done[k].to_dict() if done.get(k) is not None else None)
            for k in ("offset_curve", "headings", "line_failure")}
    if interrupted:
        status, message = "interrupted", (
            f"interrupted; finished: {', '.join(done) or 'none'}")
    else:
        status = "solved" if ok else "partial"
        message = "every case solved" if ok else "some cases were not solved"
    out.emit_json(args, out.envelope(status, message, data, []))
    if interrupted:
        raise KeyboardInterrupt
    if args.plot and curve is not None:
        from cable_ocp.plots.common import save
        from cable_ocp.plots.system import offset_curve_figure

        def draw(path: str) -> None:
            tens = {n: curve.line_tension[:, i] for i, n in enumerate(curve.line_names)}
            save(offset_curve_figure(curve.offsets, curve.restoring_force, tens,
                                     title=f"{body}: restoring curve along "
                                           f"{args.heading:g} deg"), path)

        out.emit_plot(args, draw)
    return out.EXIT_OK if ok else out.EXIT_NOT_SUCCESS
