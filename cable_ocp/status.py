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
    an answer off by more than its tolerance); the baselines' and optimisers' own:
    ``not_converged``, ``infeasible``, ``max_iterations``, ``diverged``, ``not_equilibrium``,
    ``seabed_contact``, ``length_root_failed``, ``newton_failed``, ``max_nodes``, ``singular``
    (IPOPT's return statuses map onto these: :func:`from_ipopt`).
interrupted (exit 130)
    ``interrupted``: Ctrl-C; what finished is written.
rows of a batch
    ``error`` (a case raised), ``worker_lost`` (a worker process died on the case).
internal
    ``predicted``: a sweep's extrapolated start, never a result.
"""

from __future__ import annotations

from enum import StrEnum

__all__ = ["SUCCESS", "Status", "from_ipopt"]


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
    LENGTH_ROOT_FAILED = "length_root_failed"
    NEWTON_FAILED = "newton_failed"
    MAX_NODES = "max_nodes"
    SINGULAR = "singular"
    INTERRUPTED = "interrupted"
    ERROR = "error"
    WORKER_LOST = "worker_lost"
    PREDICTED = "predicted"


#: the statuses a command exits 0 with
SUCCESS = frozenset({Status.SOLVED, Status.OK})

#: IPOPT's return statuses (``nlpsol(...).stats()["return_status"]``) that have a status of
#: their own; every other failure is ``failed`` (the IPOPT string goes into the message)
_IPOPT = {"Solve_Succeeded": Status.SOLVED, "Solved_To_Acceptable_Level": Status.SOLVED,
          "Infeasible_Problem_Detected": Status.INFEASIBLE,
          "Maximum_Iterations_Exceeded": Status.MAX_ITERATIONS,
          "Maximum_CpuTime_Exceeded": Status.MAX_ITERATIONS,
          "User_Requested_Stop": Status.INTERRUPTED}


def from_ipopt(return_status: str | None, success: bool) -> Status:
    """The status of an IPOPT solve.

    Parameters
    ----------
    return_status : str or None
        IPOPT's ``return_status`` (e.g. ``"Infeasible_Problem_Detected"``).
    success : bool
        CasADi's ``stats()["success"]``: a success is ``solved`` whatever the string.

    Returns
    -------
    Status
        ``solved``, ``infeasible``, ``max_iterations``, ``interrupted`` (Ctrl-C inside
        IPOPT) or ``failed``.
    """
    if success:
        return Status.SOLVED
    return _IPOPT.get(str(return_status), Status.FAILED) if return_status else Status.FAILED
