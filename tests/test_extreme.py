"""The extreme scenes (problems/extreme): our solver converges on every one and agrees with
an independent transcription of the same equations (multiple shooting, RK4, refined by
its own error estimate to 1e-6) to 1e-5 relative in the end forces and length (both
estimates are <= 1e-6, so 1e-5 leaves a factor 5 for the estimates' own error); never a
wrong answer reported as success (issue 5)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from cable_ocp.scene import load_scene
from cable_ocp.statics.solver import solve

EXTREME = sorted((Path(__file__).resolve().parents[1] / "problems" / "extreme").glob("*.toml"))


@pytest.mark.parametrize("path", EXTREME, ids=[p.stem for p in EXTREME])
def test_extreme_scene(path):
    scene = load_scene(path)
    assert scene.meta.get("why"), "each extreme scene says why it is hard"
    sol = solve(scene)
    assert sol.success, sol.message
    assert sol.error_estimate is not None and sol.error_estimate <= scene.solver.accuracy
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
    """004 section 2.5: when the cold solve at full current fails (here on the high-speed
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
