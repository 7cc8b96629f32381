"""The entry point of ``cable-ocp``: the parser with every command group's subcommands, and
:func:`main`, which maps what a command raises to the exit codes of the contract
(:mod:`cable_ocp.cli.output`)."""


from __future__ import annotations

import argparse
import importlib
import signal
import sys
import threading
import traceback

from cable_ocp.cli.output import (
    EXIT_INPUT,
    EXIT_INTERNAL,
    EXIT_INTERRUPTED,
    EXIT_NOT_SUCCESS,
    common_parent,
    version,
)
from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import interrupt

_COMMAND_MODULES = [
    "cable_ocp.cli.statics",
    "cable_ocp.cli.system",
    "cable_ocp.cli.heave",
    "cable_ocp.cli.inverse",
    "cable_ocp.cli.dynamics",
    "cable_ocp.cli.deploy",
    "cable_ocp.cli.response",
    "cable_ocp.cli.batch",
    "cable_ocp.cli.bench",
]


def build_parser() -> argparse.ArgumentParser:
    """The top-level argument parser with every registered subcommand."""
    parser = argparse.ArgumentParser(
        prog="cable-ocp",
        description="Marine-cable statics, dynamics and heave compensation as CasADi "
                    "optimal-control and boundary-value problems. Exit codes: 0 success, "
                    "1 computed but not a success (see the JSON status), 2 invalid input, "
                    "3 internal error, 130 interrupted.",
    )
    parser.add_argument("--version", action="version", version=f"cable-ocp {version()}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    parent = common_parent()
    for name in _COMMAND_MODULES:
        importlib.import_module(name).register(sub, parent)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the CLI and return the process exit status (see :mod:`cable_ocp.cli.output`).

    SIGINT (Ctrl-C) and SIGTERM interrupt every command the same way
    (:mod:`cable_ocp.numerics.interrupt`): what finished is written, one line says so,
    exit 130; an interruption that native code turned into a failed solve or a CasADi
    error is recognised as one, never retried or reported as an internal error.
    """
    args: argparse.Namespace | None = None
    main_thread = threading.current_thread() is threading.main_thread()
    before = {sig: signal.getsignal(sig) for sig in interrupt.SIGNALS} if main_thread else {}
    try:
        if main_thread:
            interrupt.install()
        interrupt.check()  # a Ctrl-C during start-up (the imports)
        parser = build_parser()
        try:
            args = parser.parse_args(argv)
        except SystemExit as exc:  # argparse: --help/--version (0) or a usage error (2)
            return int(exc.code or 0) if isinstance(exc.code, int) else EXIT_INPUT
        rc = int(args.func(args) or 0)
        interrupt.check()  # a Ctrl-C that CasADi swallowed after the last checkpoint
        return rc
    except CableOCPError as exc:
        if interrupt.requested():
            return _interrupted()
        print(f"cable-ocp: error: {exc}", file=sys.stderr)
        return EXIT_INPUT
    except KeyboardInterrupt:
        return _interrupted()
    except BrokenPipeError:  # e.g. `cable-ocp solve ... --json - | head`
        sys.stdout = open(__import__("os").devnull, "w")  # noqa: SIM115 - silence the flush
        return EXIT_NOT_SUCCESS
    except Exception as exc:  # noqa: BLE001 - the contract: one line, exit 3
        if interrupt.is_interruption(exc):  # CasADi's RuntimeError around a Ctrl-C
            return _interrupted()
        if getattr(args, "debug", False):
            traceback.print_exc()
        msg = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
        print(f"cable-ocp: internal error: {type(exc).__name__}: {msg[:300]} (rerun with "
              "--debug for the traceback)", file=sys.stderr)
        return EXIT_INTERNAL
    finally:  # called in-process (tests, scripts): leave the process as it was
        for sig, handler in before.items():
            signal.signal(sig, handler)
        interrupt.clear()


def _interrupted() -> int:
    """The one line of an interruption."""
    print("cable-ocp: interrupted", file=sys.stderr)
    return EXIT_INTERRUPTED


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
