"""The command line, ``cable-ocp SUBCOMMAND ...``: the face of the package, apart from it.

Commands parse arguments, call the library and format its results; no physics lives here,
and no library module imports this package. One module per command group registers its
subcommands through ``register(subparsers, parent)``; :mod:`cable_ocp.cli.output` holds the
contract they share (exit codes, JSON/CSV/plot writing, confirmations, progress).

Modules
-------
app       :func:`main` and :func:`build_parser`: the parser, the exit codes of exceptions
output    the shared contract of the commands
statics, heave, dynamics, batch, bench, cost   the command groups, and the cost estimates
inverse   heave-inverse: the parameters that give an identified a, b (Huang 6.4 (2))
system    mooring systems: solve on a system or a MoorDyn file, convert, mooring-checks
response  frequency-response curves of a dynamic scene
deploy    the optimal pay-out schedule of a dynamic scene's [deployment] (docs/deployment.md)
bench_deploy  the tables of ``cable-ocp bench deploy`` (:mod:`cable_ocp.bench.deployment`)
"""

from cable_ocp.cli.app import build_parser, main

__all__ = ["build_parser", "main"]
