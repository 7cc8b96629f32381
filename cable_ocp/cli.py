"""Command-line interface: ``cable-ocp SUBCOMMAND ...``.

Subcommands only parse arguments, call the library and format its results; no physics
lives here. Each subsystem registers its subcommands through a module that exposes
``register(subparsers)``; the modules are listed in ``_SUBCOMMAND_MODULES``.
"""

from __future__ import annotations

import argparse
import importlib
import sys

from cable_ocp.errors import CableOCPError

_SUBCOMMAND_MODULES = [
    "cable_ocp.statics.cli",
    "cable_ocp.heave.cli",
]


def build_parser() -> argparse.ArgumentParser:
    """Return the top-level argument parser with every registered subcommand."""
    parser = argparse.ArgumentParser(
        prog="cable-ocp",
        description="Marine-cable statics and heave compensation as CasADi OCPs/BVPs.",
    )
    sub = parser.add_subparsers(dest="command", required=True)
    for name in _SUBCOMMAND_MODULES:
        importlib.import_module(name).register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the CLI; return the process exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except CableOCPError as exc:
        print(f"cable-ocp: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
