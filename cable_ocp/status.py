"""The one status vocabulary of every result: statics, footprint, optimisation, dynamics,
modes, heave, batch and benchmarks.

:class:`Status` is a :class:`enum.StrEnum`: each member *is* its string (``Status.SOLVED ==
"solved"``, ``json.dumps`` writes ``"solved"``, an f-string shows ``solved``), so a result's
``status`` compares with plain strings and its JSON is unchanged, while a typo is caught
where the status is made (``Status("solvd")`` raises ``ValueError``). The statuses, by what
they say (docs/cli.md has each command's table and exit code):

success (exit 0)
    ``solved``: the computation finished and meets its accuracy or bounds; ``ok``: a
    benchmark completed (a benchmark measures, it does not solve).
computed, not a success (exit 1)
    ``inaccurate`` (converged, error estimate above ``solver.accuracy``), ``below_seabed``,
    ``above_surface`` (the profile leaves the water column), ``failed`` (did not converge,
    could not be built, a plant step failed), ``partial`` (some cases or directions
    failed), ``slack`` (a dynamic line went slack: its tensions past that are not
    physical), ``unstable`` and ``non_finite`` (a closed loop), ``wrong`` (a benchmark found
    an answer off by more than its tolerance); the baselines' own: ``not_converged``,
    ``infeasible``, ``max_iterations``, ``diverged``, ``not_equilibrium``, ``seabed_contact``,
    ``unresolved``, ``max_nodes``, ``singular``.
interrupted (exit 130)
    ``interrupted``: Ctrl-C; what finished is written.
rows of a batch
    ``error`` (a case raised), ``worker_lost`` (a worker process died on the case).
internal
    ``predicted``: a sweep's extrapolated start, never a result.
"""

from __future__ import annotations

from enum import StrEnum

__all__ = ["SUCCESS", "Status"]


class Status(StrEnum):
    """A result's status; see the module docstring for what each says and its exit code."""

    SOLVED = "solved"
    OK = "ok"
    INACCURATE = "inaccurate"
    BELOW_SEABED = "below_seabed"
    ABOVE_SURFACE = "above_surface"
    FAILED = "failed"
    PARTIAL = "partial"
    SLACK = "slack"
    UNSTABLE = "unstable"
    NON_FINITE = "non_finite"
    WRONG = "wrong"
    NOT_CONVERGED = "not_converged"
    INFEASIBLE = "infeasible"
    MAX_ITERATIONS = "max_iterations"
    DIVERGED = "diverged"
    NOT_EQUILIBRIUM = "not_equilibrium"
    SEABED_CONTACT = "seabed_contact"
    UNRESOLVED = "unresolved"
    MAX_NODES = "max_nodes"
    SINGULAR = "singular"
    INTERRUPTED = "interrupted"
    ERROR = "error"
    WORKER_LOST = "worker_lost"
    PREDICTED = "predicted"


#: the statuses a command exits 0 with
SUCCESS = frozenset({Status.SOLVED, Status.OK})
