"""Seabed contact at an anchored end (touchdown formulation, cable_ocp.physics.seabed).

Closed forms: the catenary with touchdown (Irvine 1981; the standard mooring-line
catenary): with horizontal tension H and a = H/w, a suspended part of unstretched length
L_s from the touchdown point (TDP), where the cable is horizontal, rises by
h = a (sqrt(1 + (w L_s/H)^2) - 1) + w L_s^2 / (2 EA) over a span
x_s = a asinh(w L_s / H) + H L_s / EA; the grounded part L_g = L - L_s lies straight with
tension H (frictionless) or H - mu w (L_g - s') (friction), stretched by 1 + T/EA.
Tolerance 1e-6 relative, as the issue asks (the solution is smooth on both parts).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from cable_ocp.scene import load_scene, scene_from_dict
from cable_ocp.statics.solver import solve, sweep

W, L, H = 400.0, 800.0, 150_000.0  # N/m, m, N


def catenary_with_touchdown(ls: float, ea: float, mu: float = 0.0):
    """Fairlead position (x, z) and forces for a suspended length ls."""
    inv = 0.0 if math.isinf(ea) else 1.0 / ea
    a = H / W
    h = a * (math.sqrt(1 + (W * ls / H) ** 2) - 1) + W * ls**2 / 2 * inv
    xs = a * math.asinh(W * ls / H) + H * ls * inv
    lg = L - ls
    t_anchor = max(H - mu * W * lg, 0.0)
    g_eff = min(lg, H / (mu * W)) if mu > 0 else lg
    integral = H * g_eff - 0.5 * mu * W * g_eff**2
    x_fair = lg + integral * inv + xs
    return x_fair, h, lg, t_anchor, np.array([H, 0.0, W * ls])


def scene(x_fair: float, h: float, ea: float, mu: float = 0.0, **extra):
    cable = {"length": L, "weight_in_water": W}
    if not math.isinf(ea):
        cable["axial_stiffness"] = ea
    data = {"environment": {"water_depth": h, "water_density": 1025.0,
                            "seabed": {"friction": mu}},
            "cable": cable, "end_a": {"position": [0.0, 0.0, 0.0]},
            "end_b": {"position": [x_fair, 0.0, h]}}
    data.update(extra)
    return scene_from_dict(data)


@pytest.mark.parametrize("ea", [math.inf, 5.0e8])
@pytest.mark.parametrize("mu", [0.0, 0.5])
def test_catenary_with_touchdown(ea, mu):
    x_fair, h, lg, t_anchor, t_fair = catenary_with_touchdown(600.0, ea, mu)
    sol = solve(scene(x_fair, h, ea, mu))
    assert sol.success, sol.message
    assert sol.grounded_length == pytest.approx(lg, rel=1e-6)
    td = sol.diagnostics["touchdown"]
    assert td["grounded_length"] == pytest.approx(lg, rel=1e-6)
    assert td["position"][2] == pytest.approx(0.0, abs=1e-6 * L)
    np.testing.assert_allclose(sol.force_a, [t_anchor, 0, 0], rtol=0, atol=1e-6 * H)
    np.testing.assert_allclose(sol.force_b, -t_fair, rtol=0, atol=1e-6 * H)
    assert np.min(sol.position[:, 2]) >= -1e-6 * L  # nowhere below the seabed
    assert sol.to_dict()["touchdown"]["grounded_length"] == pytest.approx(lg, rel=1e-6)


def test_no_contact_when_taut():
    """A cable that does not reach the seabed keeps touchdown = null."""
    x_fair, h, *_ = catenary_with_touchdown(600.0, math.inf)
    sol = solve(scene(x_fair + 150.0, h, 5.0e8))
    assert sol.success and sol.diagnostics["touchdown"] is None
    assert sol.to_dict()["touchdown"] is None
    assert sol.force_a[2] > 0


def test_slope_across_the_cable_changes_nothing():
    """A seabed rising across the cable's vertical plane (heading 90 deg) meets that plane
    along the flat line: the answer equals the flat one (the lateral weight component on
    the slope is carried by the seabed, as documented)."""
    x_fair, h, lg, *_ = catenary_with_touchdown(600.0, math.inf)
    flat = solve(scene(x_fair, h, math.inf))
    sloped = solve(scene_from_dict({
        "environment": {"water_depth": h, "water_density": 1025.0,
                        "seabed": {"slope_deg": 10.0, "slope_heading_deg": 90.0}},
        "cable": {"length": L, "weight_in_water": W},
        "end_a": {"position": [0.0, 0.0, 0.0]}, "end_b": {"position": [x_fair, 0.0, h]}}))
    assert sloped.success, sloped.message
    assert sloped.grounded_length == pytest.approx(flat.grounded_length, rel=1e-9)


@pytest.mark.parametrize("heading", [0.0, 180.0])
def test_slope_along_the_cable_against_independent_shooting(heading):
    """A seabed rising (heading 0) or falling (180) 3 deg along the cable, friction 0.5,
    EA 5e8 N:
    the grounded part lies on the slope, its tension dropping by w sin(alpha) + mu w
    cos(alpha) per metre towards the anchor, and the cable lifts off tangent to the slope.
    Against the independent shooting (tests/shooting_reference.py, grounded part written
    separately): grounded length, end forces and length to 1e-6 relative (the solution is
    smooth on both parts, as above)."""
    import shooting_reference as sref

    x_fair, h, *_ = catenary_with_touchdown(600.0, 5.0e8, 0.5)
    data = {"environment": {"water_depth": h + 60.0, "water_density": 1025.0,
                            "seabed": {"friction": 0.5, "slope_deg": 3.0,
                                       "slope_heading_deg": heading}},
            "cable": {"length": L, "weight_in_water": W, "axial_stiffness": 5.0e8},
            "end_a": {"position": [0.0, 0.0, 0.0]}, "end_b": {"position": [x_fair, 0.0, h]}}
    sol = solve(scene_from_dict(data))
    assert sol.success, sol.message
    g = sol.grounded_length
    assert g > 50.0
    ref = sref.shoot(sref.problem_from_dict(data), 1.05 * sol.tension_vector[sol.node_offset],
                     grounded_guess=1.05 * g)
    assert ref.residual < 1e-10
    assert g == pytest.approx(ref.grounded_length, rel=1e-6)
    np.testing.assert_allclose(sol.force_a, ref.tension_a, rtol=0, atol=1e-6 * H)
    np.testing.assert_allclose(sol.force_b, -ref.tension_b, rtol=0, atol=1e-6 * H)
    e = sol.tension_vector[sol.node_offset] / np.linalg.norm(sol.tension_vector[sol.node_offset])
    slope = 3.0 if heading == 0.0 else -3.0
    assert math.degrees(math.atan2(e[2], e[0])) == pytest.approx(slope, abs=1e-6)


def test_dezoysa_with_seabed_stays_above(problems):
    """The issue: De Zoysa at psi0 = 150..180 deg with a seabed nowhere goes below it;
    below 147.9 deg (componentwise) nothing touches, so the answer is unchanged."""
    sc = load_scene(problems / "dezoysa_sea_buggy.toml", {"environment.seabed": {}})
    sols = sweep(sc, "layout.psi0_deg", [140, 150, 160, 170, 180])
    free = sweep(load_scene(problems / "dezoysa_sea_buggy.toml"), "layout.psi0_deg", [140])
    for s in sols:
        assert s.success, s.message
        assert np.min(s.position[:, 2]) >= -1e-6 * 305.0
    assert sols[0].diagnostics["touchdown"] is None
    np.testing.assert_allclose(sols[0].force_a, free[0].force_a, rtol=1e-9)
    g = [s.grounded_length for s in sols[1:]]
    assert all(x > 0 for x in g) and np.all(np.diff(g) > 0)
    for s in sols[1:]:
        assert abs(s.force_a[2]) < 1e-6 * s.max_tension  # tangent to the seabed at the buggy


def test_contact_away_from_anchor_is_a_failure():
    """A slack cable between two buoys sagging onto the seabed needs mid-span contact,
    which is not modelled: the result is a failure, not a profile through the seabed."""
    sol = solve(scene_from_dict({
        "environment": {"water_depth": 100.0, "water_density": 1025.0, "seabed": {}},
        "cable": {"length": 600.0, "weight_in_water": 50.0},
        "end_a": {"position": [0.0, 0.0, 50.0]}, "end_b": {"position": [300.0, 0.0, 50.0]}}))
    assert sol.status == "below_seabed"
    assert "below the seabed" in sol.message
