"""The extreme scenes (problems/extreme): our solver converges on every one, within its
error estimate, and agrees with an independent reference; never a wrong answer reported as
success.

Two comparisons, of different strength:

* against :mod:`shooting_reference` (tests/shooting_reference.py): single shooting with
  scipy ``solve_ivp`` (DOP853) and ``root`` on a right-hand side written separately from the
  package (numpy loads from the raw TOML tables, exact moduli, the stretch factor, the
  current profile, the seabed's friction-grounded part). This is the independent check of
  the physics: end forces, length and grounded length to 1e-5 relative (the collocation's
  estimated error is <= 1e-6 = ``solver.accuracy``, the shooting's ~1e-10; the smooth
  modulus, delta = 1e-5 m/s, changes the loads by ~1e-10 relative; measured worst 3.7e-7,
  on reversing_current), and positions and tensions at every node to 1e-4 (interior
  collocation points converge only at the stage order d + 1; measured worst 1.3e-5, the
  tension on drag_dominated). Dropping the drag's stretch factor (1 + T/EA) moves
  deep_water's end force by 2.6e-4 relative.
* against the package's own multiple shooting (RK4, refined by its own error estimate):
  the **same** ``Formulation.rhs``, so only a cross-check of the discretisation (mesh,
  collocation, refinement), blind to an error in the equations themselves.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import numpy as np
import pytest
import shooting_reference as ref_mod

from cable_ocp.scene import load_scene
from cable_ocp.statics.solver import solve

EXTREME = sorted((Path(__file__).resolve().parents[1] / "problems" / "extreme").glob("*.toml"))
IDS = [p.stem for p in EXTREME]


@cache
def _solved(path: Path):  # noqa: ANN202
    scene = load_scene(path)
    return scene, solve(scene)


@pytest.mark.parametrize("path", EXTREME, ids=IDS)
def test_extreme_scene_against_independent_shooting(path):
    scene, sol = _solved(path)
    assert scene.meta.get("why"), "each extreme scene says why it is hard"
    assert sol.success, sol.message
    assert sol.error_estimate is not None and sol.error_estimate <= scene.solver.accuracy
    prob = ref_mod.read_problem(path)
    g = sol.grounded_length
    # Newton starts 5 % (and 1 m) away from the solution under test; the reference converges
    # to the root of its own equations (residual checked below).
    ref = ref_mod.shoot(prob, 1.05 * (sol.tension_vector[sol.node_offset] if g > 0
                                      else sol.force_a),
                        r0_guess=sol.position[0] + 1.0, length_guess=1.01 * sol.length,
                        grounded_guess=1.05 * g if g > 0 else None)
    assert ref.residual < 1e-9
    assert (g > 0) == (path.stem == "slack_touchdown")  # the only scene with contact
    scale = sol.max_tension
    assert np.max(np.abs(sol.force_a - ref.tension_a)) < 1e-5 * scale
    assert np.max(np.abs(sol.force_b + ref.tension_b)) < 1e-5 * scale
    assert abs(sol.length - ref.length) < 1e-5 * sol.length
    assert abs(g - ref.grounded_length) < 1e-5 * sol.length
    susp = sol.s >= g
    r_ref, t_ref = ref.at(sol.s[susp])
    assert np.max(np.abs(sol.position[susp] - r_ref)) < 1e-4 * sol.length
    assert np.max(np.abs(sol.tension_vector[susp] - t_ref)) < 1e-4 * scale


@pytest.mark.parametrize("path", EXTREME, ids=IDS)
def test_extreme_scene_discretisation_cross_check(path):
    """Collocation vs the package's multiple shooting (RK4, 80 intervals, refined to its own
    error estimate) on the same ``Formulation.rhs``: a discretisation cross-check only (both
    estimates are <= 1e-6, so 1e-5 leaves a factor 5 for the estimates' own error)."""
    scene, sol = _solved(path)
    assert sol.success, sol.message
    ms = solve(scene.with_overrides({"solver.method": "multiple_shooting",
                                     "solver.intervals": 80}), warm_start=sol)
    assert ms.success, ms.message
    scale = sol.max_tension
    assert np.max(np.abs(sol.force_a - ms.force_a)) < 1e-5 * scale
    assert np.max(np.abs(sol.force_b - ms.force_b)) < 1e-5 * scale
    assert abs(sol.length - ms.length) < 1e-5 * sol.length
    assert abs(sol.grounded_length - ms.grounded_length) < 1e-5 * sol.length


def test_hanging_vertical_exact():
    """Exact answer: T_z(s) = 5000 + 30 s, a vertical line."""
    sol = solve(load_scene(EXTREME[0].parent / "hanging_vertical.toml"))
    np.testing.assert_allclose(sol.tension_vector[:, 2], 5000.0 + 30.0 * sol.s, rtol=1e-10)
    np.testing.assert_allclose(sol.position[:, :2], 0.0, atol=1e-9)


def test_continuation_is_automatic_and_reported():
    """Huang (1992), section 2.5: when the cold solve at full current fails (here on the high-speed
    tow: Newton's line search stalls from the drag-free hanging guess, and the IPOPT
    fallback is held to 20 iterations, fewer than it needs), the solver ramps the current
    from 0 in steps, says so in the diagnostics, and lands on the same answer as an
    unrestricted solve (to 1e-9 of the force; the out-of-plane component is zero, a few
    1e-12 N of roundoff in both)."""
    path = EXTREME[0].parent / "high_speed_tow.toml"
    over = {"solver.refine": False, "solver.error_estimate": False}
    ramped = solve(load_scene(path, {**over, "solver.max_iterations": 20}))
    assert ramped.success, ramped.message
    assert "current ramped" in (ramped.diagnostics.get("continuation") or "")
    direct = solve(load_scene(path, over))
    assert direct.success and "continuation" not in direct.diagnostics
    np.testing.assert_allclose(ramped.force_b, direct.force_b, rtol=1e-9,
                               atol=1e-9 * np.max(np.abs(direct.force_b)))
