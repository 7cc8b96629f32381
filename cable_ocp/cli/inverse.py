"""``cable-ocp heave-inverse``: the inverse problem of Huang (1992), 6.4 (2) (parse, call,
format): the line and unit parameters that give an identified ``a``, ``b``
(:mod:`cable_ocp.heave.inverse`)."""

from __future__ import annotations

import argparse

from cable_ocp.cli import output as out
from cable_ocp.cli.output import EXIT_NOT_SUCCESS


def register(sub: argparse._SubParsersAction, parent: argparse.ArgumentParser) -> None:
    """Add ``heave-inverse``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The ``cable-ocp`` parser's subparsers, to which the command is added.
    parent : argparse.ArgumentParser
        The common options (:func:`cable_ocp.cli.output.common_parent`).
    """
    from cable_ocp.scene.heave import INVERSE_UNKNOWNS as PARAMETERS

    p = sub.add_parser(
        "heave-inverse", parents=[parent],
        help="the cable and unit parameters that give an identified a, b (Huang 1992, 6.4 (2))",
        description="Solve for the named unknown parameters of a cable scene's line and unit "
                    "(the others as in the file) so that the first axial mode gives the "
                    "design model's a (s^2) and b (6.3's b_quadratic, s^2/m, or 6.2's b, s, "
                    "with --velocity-std). Exit 0 when the data are reached, 1 when no "
                    "parameters reach them, 2 invalid input or not identifiable (more "
                    "unknowns than data, or unknowns the data cannot separate).")
    p.add_argument("file", help="dynamics cable scene (UTF-8 TOML), e.g. "
                                "problems/dynamics/huang_6_2_6.toml")
    p.add_argument("--a", type=float, metavar="S2", help="identified a of (6.2)/(6.3), s^2")
    p.add_argument("--b-quadratic", type=float, metavar="S2_PER_M",
                   help="identified b of (6.3), s^2/m")
    p.add_argument("--b", type=float, metavar="S", help="identified b of (6.2), s (needs "
                                                        "--velocity-std)")
    p.add_argument("--velocity-std", type=float, metavar="M_PER_S",
                   help="the unit's velocity standard deviation of the identification, m/s")
    p.add_argument("--unknowns", nargs="+", required=True, choices=PARAMETERS, metavar="NAME",
                   help="parameters to solve for, any of: " + ", ".join(PARAMETERS)
                        + " (their values in the file are the guess)")
    out.add_json_option(p, "the parameters found")
    p.set_defaults(func=cmd_inverse)


def cmd_inverse(args: argparse.Namespace) -> int:
    """``cable-ocp heave-inverse FILE``."""
    from cable_ocp.errors import CableOCPError
    from cable_ocp.heave.inverse import design_coefficients, from_dynamic_scene, solve_parameters
    from cable_ocp.scene.dynamics import load_dynamic_scene

    out.check_outputs(args)
    data = {k: v for k, v in (("a", args.a), ("b_quadratic", args.b_quadratic),
                              ("b", args.b)) if v is not None}
    if not data:
        raise CableOCPError("give at least one of --a, --b-quadratic, --b")
    known = from_dynamic_scene(load_dynamic_scene(args.file))
    res = solve_parameters(data, args.unknowns, known, velocity_std=args.velocity_std)
    before = design_coefficients(known, args.velocity_std)
    out.emit_json(args, out.envelope(res.status, res.message, {
        **res.as_json(), "file_values": {k: getattr(known, k) for k in args.unknowns},
        "file_coefficients": before}))
    lines = [f"{res.status}: {res.message}"]
    for k in args.unknowns:
        lines.append(f"  {k:16s} {res.unknowns[k]:.6g}   (file: {getattr(known, k):.6g})")
    for k in data:
        lines.append(f"  {k:16s} given {data[k]:.6g}, achieved {res.achieved[k]:.6g} "
                     f"(file's parameters: {before[k]:.6g})")
    out.say(args, "\n".join(lines))
    return 0 if res.status == "solved" else EXIT_NOT_SUCCESS
