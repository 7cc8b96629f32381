"""Mesh points on the kinks of the drag (cable_ocp.statics.kinks, ``solver.mesh``).

The references are independent: single shooting with scipy (tests/shooting_reference.py:
its own loads in numpy, no smoothing, DOP853 at rtol 1e-11, so it agrees with a converged
collocation solution to ~2e-11 of the largest tension, the smoothing's own bound), and
synthetic switching functions with known roots.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest
import shooting_reference as sref
from scipy.optimize import brentq, minimize_scalar

from cable_ocp.errors import CableOCPError
from cable_ocp.scene import load_scene, scene_from_dict
from cable_ocp.statics import kinks
from cable_ocp.statics.solver import StaticsSolver, solve, sweep

ROOT = Path(__file__).resolve().parents[1] / "problems"
DEZOYSA = ROOT / "dezoysa_sea_buggy.toml"
CHUCHEEPSAKUL = ROOT / "chucheepsakul_top_tension.toml"
OFF = {"solver.error_estimate": False, "solver.refine": False}


@pytest.fixture(scope="module")
def dezoysa_shot() -> sref.Reference:
    """De Zoysa's cable at psi0 = 90 deg by independent shooting."""
    shot = sref.shoot(sref.read_problem(DEZOYSA, {"layout.psi0_deg": 90.0}),
                      np.array([1500.0, 3400.0, 1100.0]))
    assert shot.residual < 1e-10
    return shot


def _errors(sol, shot: sref.Reference, degree: int) -> tuple[float, float]:
    """End-force error over the largest tension, and the position error at the mesh
    points (where the scheme has its full order) over the length."""
    tmax = float(np.max(np.linalg.norm(shot.t, axis=1)))
    force = max(np.max(np.abs(sol.force_a - shot.tension_a)),
                np.max(np.abs(sol.force_b + shot.tension_b))) / tmax
    r, _ = shot.at(sol.s[:: degree + 1])
    return float(force), float(np.max(np.abs(sol.position[:: degree + 1] - r)) / sol.length)


def test_fitted_mesh_beats_a_four_times_finer_uniform_mesh(dezoysa_shot) -> None:
    """De Zoysa at psi0 = 90 deg, Gauss-Legendre degree 4: the flow along the tangent and
    along e_n change sign at s* ~ 140.3 m, and uniform meshes lose their order 8 there
    (16 intervals: 7.7e-8 in the end forces; 64: 1.0e-9). With a mesh point on s*,
    16 intervals reach the shooting reference's own floor (2e-11, the smoothing's bound):
    fewer intervals than the uniform mesh needs by far. Tolerances: 1e-10 for the fitted
    mesh (5x its measured error), 5e-10 from below for the uniform ones (half theirs)."""
    fitted = solve(load_scene(DEZOYSA, {"layout.psi0_deg": 90.0, "solver.degree": 4,
                                        "solver.intervals": 16, **OFF}))
    assert fitted.success and fitted.diagnostics["mesh"]["kind"] == "kinks"
    assert max(_errors(fitted, dezoysa_shot, 4)) < 1e-10
    for n in (16, 64):
        uniform = solve(load_scene(DEZOYSA, {"layout.psi0_deg": 90.0, "solver.degree": 4,
                                             "solver.intervals": n, "solver.mesh": "uniform",
                                             **OFF}))
        assert uniform.success and "kind" not in uniform.diagnostics["mesh"]
        assert _errors(uniform, dezoysa_shot, 4)[0] > 5e-10


def test_the_mesh_point_lies_where_the_flow_along_the_cable_changes_sign(dezoysa_shot) -> None:
    """The kink found, and the mesh point put on it, is where T_x of the shooting
    reference vanishes (the tangent normal to the current): within 1e-5 of the length
    (it is located on a Newton iterate near the solution; an offset e from the true kink
    leaves about 0.2 (e/L)^3 of error, 2e-16 here). The other mesh points split the two
    parts uniformly."""
    exact = brentq(lambda s: dezoysa_shot.at(np.array([s]))[1][0, 0], 100.0, 200.0,
                   xtol=1e-12)
    sol = solve(load_scene(DEZOYSA, {"layout.psi0_deg": 90.0, "solver.degree": 4,
                                     "solver.intervals": 8, **OFF}))
    mesh = sol.diagnostics["mesh"]
    assert len(mesh["kinks_s"]) == 1
    assert abs(mesh["kinks_s"][0] - exact) < 1e-5 * sol.length
    points = np.asarray(mesh["points_s"])
    assert len(points) == 9 and points[0] == 0.0 and points[-1] == pytest.approx(305.0)
    k = int(np.argmin(np.abs(points - mesh["kinks_s"][0])))
    assert points[k] == pytest.approx(mesh["kinks_s"][0], abs=1e-9)
    for part in (points[: k + 1], points[k:]):
        assert np.allclose(np.diff(part), np.diff(part)[0], rtol=1e-9)
    # and the JSON says the same
    assert sol.to_dict()["solver"]["mesh"] == {"kind": "kinks", "points_s": mesh["points_s"],
                                               "kinks_s": mesh["kinks_s"]}


def test_lowest_point_of_a_cable_leaving_its_anchor_downwards() -> None:
    """Chucheepsakul & Subwonglee's free-length cable (5000 N at the top, psi0 = 0) leaves
    its anchor 0.1 deg below horizontal: the componentwise load's e_n component changes
    sign where the cable turns horizontal, 0.39 m from the anchor, its lowest point. The
    mesh point on that kink resolves the 0.335 mm dip below the anchor that the uniform
    40-interval mesh (7.9 m intervals) steps over: its depth against the shooting
    reference to 1e-9 m (measured 7e-11 m; the offset of the mesh point, ~0.6 mm, costs
    only (0.6 mm)^2 times the curvature, ~1e-10 m)."""
    shot = sref.shoot(sref.read_problem(CHUCHEEPSAKUL), np.array([4000.0, 0.0, 0.0]),
                      length_guess=310.0)
    low = minimize_scalar(lambda s: shot.at(np.array([s]))[0][0, 2], bounds=(0.0, 5.0),
                          method="bounded", options={"xatol": 1e-10})
    assert -4e-4 < low.fun < -3e-4
    fitted = solve(load_scene(CHUCHEEPSAKUL, OFF))
    uniform = solve(load_scene(CHUCHEEPSAKUL, {**OFF, "solver.mesh": "uniform"}))
    assert fitted.converged and uniform.success
    # no seabed table: the dip, within the cable's 11.5 mm radius, is a warning (the
    # cable touches the seabed plane), not a failure
    assert fitted.success
    assert any("dips 0.335 mm" in w for w in fitted.diagnostics["warnings"])
    assert abs(fitted.position[:, 2].min() - low.fun) < 1e-9
    assert abs(fitted.diagnostics["mesh"]["kinks_s"][0] - low.x) < 1e-3
    # the anchor (z = 0 to rounding) is the uniform mesh's lowest node: the dip falls
    # between its nodes
    assert abs(uniform.position[:, 2].min()) < 1e-12


def test_no_kink_no_change() -> None:
    """Where no flow component changes sign (De Zoysa at psi0 = 0 deg, a plane cable rising
    into the current) and where there is no current (the drag-free catenary), the default
    mesh gives the uniform mesh's solution bit for bit."""
    for over in ({"layout.psi0_deg": 0.0}, {"layout.psi0_deg": 90.0}):
        data = tomllib.loads(DEZOYSA.read_text())
        if over["layout.psi0_deg"] == 90.0:
            del data["environment"]["current"]  # still water: a catenary
        data["layout"]["psi0_deg"] = over["layout.psi0_deg"]
        data["solver"] = {"degree": 4, "intervals": 16, "error_estimate": False}
        default = solve(scene_from_dict(data))
        data["solver"]["mesh"] = "uniform"
        uniform = solve(scene_from_dict(data))
        assert default.success and uniform.success
        assert default.diagnostics["mesh"].get("kind", "uniform") == "uniform"
        assert default.diagnostics["mesh"].get("kinks_s", []) == []
        assert np.array_equal(default.position, uniform.position)
        assert np.array_equal(default.tension_vector, uniform.tension_vector)


def test_degree_two_keeps_the_uniform_mesh() -> None:
    """Gauss-Legendre of degree 2 has order 4 at the mesh points, the kink's own: fitting
    would not pay (measured 0.86-1.1x the uniform errors), so the solver does not look."""
    sol = solve(load_scene(DEZOYSA, {"layout.psi0_deg": 90.0, "solver.degree": 2, **OFF}))
    assert "kind" not in sol.diagnostics["mesh"]


def test_tracking_sweep_moves_the_mesh_points_with_the_kink() -> None:
    """A psi0 sweep with ``solver.mesh = "tracking"``: every point's mesh sits on its own
    kink (1e-4 of the length, :data:`kinks.GAP`), and the end forces equal cold solves of
    each angle to 1e-10 relative (both fitted; the kink offsets cost ~1e-13). With the
    default ``"kinks"`` a warm point keeps its start's mesh."""
    base = load_scene(DEZOYSA, {"solver.degree": 4, "solver.intervals": 16,
                                "solver.mesh": "tracking", **OFF})
    angles = [80.0, 90.0, 100.0]
    sols = sweep(base, "layout.psi0_deg", angles)
    for angle, sol in zip(angles, sols, strict=True):
        cold = solve(base.with_overrides({"layout.psi0_deg": angle}))
        (k_cold,), (k_warm,) = cold.diagnostics["mesh"]["kinks_s"], \
            sol.diagnostics["mesh"]["kinks_s"]
        assert abs(k_warm - k_cold) < kinks.GAP * sol.length
        assert min(abs(np.asarray(sol.diagnostics["mesh"]["points_s"]) - k_warm)) < 1e-9
        scale = cold.max_tension
        assert np.max(np.abs(sol.force_a - cold.force_a)) < 1e-10 * scale
    kept = sweep(base.with_overrides({"solver.mesh": "kinks"}), "layout.psi0_deg", angles)
    assert kept[0].diagnostics["mesh"]["points_s"] == kept[2].diagnostics["mesh"]["points_s"]
    assert "kinks_s" not in kept[2].diagnostics["mesh"]


def test_error_estimate_on_a_fitted_mesh(dezoysa_shot) -> None:
    """The Richardson estimate (N, N/2, N/4, each fitted to the kink) against the true
    error from the shooting reference: within a factor 10 either way (degree 3, 16
    intervals, where the stage-order profile error, 3.5e-8, dominates)."""
    sol = solve(load_scene(DEZOYSA, {"layout.psi0_deg": 90.0, "solver.intervals": 16,
                                     "solver.error_estimate": True, "solver.refine": False,
                                     "solver.accuracy": 1.0}))
    tmax = float(np.max(np.linalg.norm(dezoysa_shot.t, axis=1)))
    force = max(np.max(np.abs(sol.force_a - dezoysa_shot.tension_a)),
                np.max(np.abs(sol.force_b + dezoysa_shot.tension_b))) / tmax
    r, _ = dezoysa_shot.at(sol.s)
    true = max(force, float(np.max(np.abs(sol.position - r))) / sol.length)
    assert 0.1 < sol.error_estimate / true < 10.0


def test_find_locates_roots_between_nodes() -> None:
    """kinks.find on known functions sampled every 0.05: the root of a cubic exactly (the
    local cubic through four nodes is the function), both roots of sin(3x) - 0.3 to 5e-6
    (the cubic's interpolation error, 81/24 * 9/16 * 0.05^4 = 1.2e-5, over the slope,
    3 cos(0.3)); a zero only touched (x^2) is no kink, NaN values are skipped, and two
    columns vanishing together give one kink."""
    x = np.linspace(0.0, 1.0, 21)
    cubic = (x - 0.4137) * (x + 0.5) * (x - 2.0)
    sine = np.sin(3.0 * x) - 0.3
    touch = (x - 0.5) ** 2
    nan = np.where(x > 0.7, np.nan, x - 0.9)
    found = kinks.find(x, np.stack([cubic, touch, nan, cubic], axis=1))
    assert found == pytest.approx([0.4137], abs=1e-12)
    found = kinks.find(x, sine[:, None])
    roots = [np.arcsin(0.3) / 3.0, (np.pi - np.arcsin(0.3)) / 3.0]
    assert found == pytest.approx(roots, abs=5e-6)
    # two segments: a sign change across their joint (the node repeated) is not a kink
    xs = np.concatenate([x[:11], x[10:]])
    vals = np.concatenate([np.full(11, 1.0), np.full(11, -1.0)])[:, None]
    assert kinks.find(xs, vals, [0, 11, 22]).size == 0


def test_fitted_edges() -> None:
    """The fitted mesh: a point on each kink, each part uniform with at least one
    interval and the widest interval as narrow as possible; kinks within GAP of a segment
    end or of each other share a point; a segment whose widest interval would widen by
    more than WIDEN stays uniform (None: nothing fitted)."""
    edges = kinks.fitted_edges((8,), (0.0, 1.0), np.array([0.46]))
    assert len(edges) == 9 and 0.46 in edges
    assert np.allclose(np.diff(edges), [0.115] * 4 + [0.135] * 4)
    assert kinks.fitted_edges((8,), (0.0, 1.0), np.array([0.5 * kinks.GAP])) is None
    two = kinks.fitted_edges((10,), (0.0, 1.0), np.array([0.3, 0.3 + 0.5 * kinks.GAP, 0.6]))
    assert len(two) == 11 and 0.3 in two and 0.6 in two
    assert np.allclose(np.diff(two), 0.1)
    # Berteaux's kink 16 m below the buoy (0.5 % of the line): 8 intervals would widen
    # the others by 14 %, 16 intervals by 6 %
    assert kinks.fitted_edges((8,), (0.0, 1.0), np.array([0.9947])) is None
    assert kinks.fitted_edges((16,), (0.0, 1.0), np.array([0.9947])) is not None
    # two segments: only the second has a kink
    edges = kinks.fitted_edges((4, 4), (0.0, 0.5, 1.0), np.array([0.75]))
    assert np.allclose(edges[:5], np.linspace(0.0, 0.5, 5)) and 0.75 in edges
    assert edges[4] == 0.5 and edges[-1] == 1.0


def test_mesh_option_is_validated() -> None:
    """A wrong value names the key and the valid ones."""
    with pytest.raises(CableOCPError, match=r'solver.mesh = .*"kinks", "tracking", '
                                            r'"uniform"'):
        load_scene(DEZOYSA, {"solver.mesh": "adaptive"})


def test_widths_are_parameters_not_a_rebuild() -> None:
    """Moving the mesh points builds nothing: one solver solves on the uniform and on the
    fitted mesh (the interval widths are parameters of the same functions), and its
    residual on the fitted mesh vanishes at the fitted solution."""
    solver = StaticsSolver(load_scene(DEZOYSA, {"layout.psi0_deg": 90.0, **OFF}))
    fitted = solver.solve()
    w, mesh = fitted._unknowns[1], fitted._unknowns[2]
    assert mesh.edges and mesh.uniform is not mesh
    g = np.asarray(solver.coll.residual(w, solver.params(mesh=mesh))).ravel()
    assert np.max(np.abs(g)) <= 10 * solver.tol
    g_uniform = np.asarray(solver.coll.residual(w, solver.params(mesh=mesh.uniform))).ravel()
    assert np.max(np.abs(g_uniform)) > 1e3 * solver.tol
