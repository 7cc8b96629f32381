"""The one status vocabulary (cable_ocp.status.Status): its members are their strings (JSON
and comparisons unchanged), a status outside it fails where it is made, IPOPT's return
statuses map onto it, every status the command docs list is a member, and the result of
every kind carries one."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

from cable_ocp.status import SUCCESS, Status, from_ipopt

ROOT = Path(__file__).resolve().parents[1]


def test_members_are_their_strings() -> None:
    assert Status.SOLVED == "solved" and f"{Status.BELOW_SEABED}" == "below_seabed"
    assert json.dumps({"status": Status.WORKER_LOST}) == '{"status": "worker_lost"}'
    assert Status("inaccurate") is Status.INACCURATE
    assert SUCCESS == {"solved", "ok"}
    with pytest.raises(ValueError):
        Status("solvd")


def test_a_statics_solution_refuses_a_status_outside_the_vocabulary() -> None:
    from cable_ocp.statics.solution import StaticsSolution

    sol = StaticsSolution("solved", "", np.zeros(2), np.zeros((2, 3)), np.zeros((2, 3)), 1.0)
    assert type(sol.status) is Status
    sol.status = "inaccurate"
    assert sol.status is Status.INACCURATE
    with pytest.raises(ValueError):
        sol.status = "Infeasible_Problem_Detected"


@pytest.mark.parametrize("ipopt,success,status", [
    ("Solve_Succeeded", True, "solved"), ("Infeasible_Problem_Detected", False, "infeasible"),
    ("Maximum_Iterations_Exceeded", False, "max_iterations"),
    ("User_Requested_Stop", False, "interrupted"), ("Restoration_Failed", False, "failed"),
    (None, False, "failed"), ("Maximum_Iterations_Exceeded", True, "solved"),
])
def test_ipopt_statuses_map_onto_the_vocabulary(ipopt: str | None, success: bool,
                                                 status: str) -> None:
    assert from_ipopt(ipopt, success) == status


def test_every_status_the_command_docs_list_is_a_member() -> None:
    """docs/cli.md's tables name each command's statuses: each is a member (the docs and
    the vocabulary cannot drift apart)."""
    text = (ROOT / "docs" / "cli.md").read_text(encoding="utf-8")
    section = text[text.index("## Statuses"):text.index("## Input checks")]
    named = set(re.findall(r"^\| `([a-z_]+)` \|", section, re.M))
    named |= set(re.findall(r"`([a-z_]+)`", section.split("| other methods |")[1].split("\n")[0]))
    assert {"solved", "inaccurate", "failed", "partial", "unstable", "non_finite"} <= named
    assert named <= {s.value for s in Status}, named - {s.value for s in Status}


def test_results_of_every_kind_carry_a_status() -> None:
    import cable_ocp as co
    from cable_ocp.heave.design_loop import compare
    from cable_ocp.scene.heave import load_scene as load_heave

    sol = co.solve(ROOT / "problems" / "berteaux_mooring.toml")
    assert type(sol.status) is Status and sol.status == "solved"
    res = compare(load_heave(ROOT / "problems" / "heave" / "ex_6_3_6.toml",
                             {"simulation.duration": 20.0, "simulation.warmup": 5.0}),
                  ("passive", "lqr"))
    assert all(type(s) is Status for s in res.statuses.values()) and res.status == "solved"
    from cable_ocp.dynamics import modes, simulate

    dyn = ROOT / "problems" / "dynamics" / "huang_3_3_5.toml"
    run = simulate(dyn, overrides={"simulation.duration": 2.0})
    assert type(run.status) is Status and run.status == "solved"
    assert type(modes(dyn, 2).status) is Status


def test_a_baselines_own_failure_code_is_a_status() -> None:
    """Huang's drag iteration whose inner Newton fails (the neutrally buoyant extreme scene:
    no weight to hang the catenaries from) ends "newton_failed", a member: a failed solve
    with its status, exit 1, not a crash (the robustness benchmark met it as a ValueError
    once the vocabulary was enforced without this member)."""
    from cable_ocp.scene import load_scene
    from cable_ocp.statics.solver import solve

    sol = solve(load_scene(ROOT / "problems" / "extreme" / "neutrally_buoyant.toml",
                           {"solver.method": "huang_semianalytic"}))
    assert sol.status is Status.NEWTON_FAILED and not sol.success
    assert sol.to_dict()["status"] == "newton_failed" and "inner Newton failed" in sol.message
