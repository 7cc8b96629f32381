"""Still-water statics against the closed-form elastic catenary (Irvine 1981; Huang (1992) eqs
(2.31)-(2.33) with no point loads), for every kind of end condition (Huang 1992, (2.6)-(2.15)).

With T(0) = (H e_h, V) at end_a, weight w per unstretched length and axial stiffness EA:

    x_h(s) = H s / EA + (H / w) [asinh((V + w s) / H) - asinh(V / H)]
    z(s)   = (V s + w s^2 / 2) / EA + (H / w) [sqrt(1 + ((V + w s)/H)^2) - sqrt(1 + (V/H)^2)]

The issue asks for 1e-6 relative; a smooth solution with 40 intervals of degree 3
(order 6) is far more accurate than that, so 1e-6 is a real bound, not a loose one.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from cable_ocp.scene import scene_from_dict
from cable_ocp.statics.solver import solve

H, V, W, L = 20000.0, -3000.0, 50.0, 400.0  # N, N, N/m, m (moderate sag)
ALPHA = math.radians(35.0)  # the plane of the cable, to make the test 3D
EH = np.array([math.cos(ALPHA), math.sin(ALPHA), 0.0])


def closed_form(s: np.ndarray, ea: float) -> tuple[np.ndarray, np.ndarray]:
    """Positions (n, 3) and tension vectors (n, 3) of the elastic catenary."""
    inv = 0.0 if math.isinf(ea) else 1.0 / ea
    xh = H * s * inv + (H / W) * (np.arcsinh((V + W * s) / H) - math.asinh(V / H))
    z = (V * s + 0.5 * W * s**2) * inv + (H / W) * (
        np.sqrt(1 + ((V + W * s) / H) ** 2) - math.sqrt(1 + (V / H) ** 2))
    r = np.outer(xh, EH) + np.outer(z, [0, 0, 1.0]) + np.array([10.0, -5.0, 20.0])
    t = np.outer(np.full_like(s, H), EH) + np.outer(V + W * s, [0, 0, 1.0])
    return r, t


def scene(end_a: dict, end_b: dict, ea: float = 2.0e7, length: float | str = L, **solver):
    cable = {"length": length, "weight_in_water": W}
    if not math.isinf(ea):
        cable["axial_stiffness"] = ea
    return scene_from_dict({
        "environment": {"water_depth": 1000.0, "water_density": 1025.0},
        "cable": cable, "end_a": end_a, "end_b": end_b, "solver": solver})


def ends(ea: float):
    r, t = closed_form(np.array([0.0, L]), ea)
    return r, t


@pytest.mark.parametrize("ea", [2.0e7, 2.0e5, math.inf])  # 0.1 %, 10 % strain, none
@pytest.mark.parametrize("scheme", ["legendre", "radau"])
def test_fixed_ends(ea, scheme):
    """Type 1 (both ends fixed): end forces and the whole profile, 1e-6 relative."""
    r, t = ends(ea)
    sol = solve(scene({"position": list(r[0])}, {"position": list(r[1])}, ea, scheme=scheme))
    assert sol.success, sol.message
    tmax = np.linalg.norm(t, axis=1).max()
    np.testing.assert_allclose(sol.force_a, t[0], rtol=0, atol=1e-6 * tmax)
    np.testing.assert_allclose(sol.force_b, -t[1], rtol=0, atol=1e-6 * tmax)
    rs, ts = closed_form(sol.s, ea)
    # mesh points carry the superconvergent order 2d (2d - 1 for Radau): 1e-6 as asked;
    # interior collocation points only the stage order d + 1: 1e-5 there.
    m = np.zeros(len(sol.s), bool)
    m[np.arange(0, len(sol.s), 4)] = True  # degree 3: every 4th node is a mesh point
    np.testing.assert_allclose(sol.position[m], rs[m], rtol=0, atol=1e-6 * L)
    np.testing.assert_allclose(sol.tension_vector[m], ts[m], rtol=0, atol=1e-6 * tmax)
    np.testing.assert_allclose(sol.position, rs, rtol=0, atol=1e-5 * L)
    np.testing.assert_allclose(sol.tension_vector, ts, rtol=0, atol=1e-5 * tmax)
    # the solver's own error estimate is honest here: the true error is below it x 10
    # (both are compared above the solve tolerance, 1e-10, below which neither number
    # measures discretisation error)
    true = np.max(np.abs(sol.force_a - t[0])) / tmax
    assert true <= 10 * sol.error_estimate + 1e-10


def test_stretch_is_built_only_when_elastic():
    r, _ = ends(math.inf)
    from cable_ocp.statics.formulation import Formulation

    assert Formulation(scene({"position": list(r[0])}, {"position": list(r[1])},
                             math.inf)).terms == ("weight",)
    assert Formulation(scene({"position": list(r[0])}, {"position": list(r[1])},
                             1e6)).terms == ("weight", "stretch")


def test_inextensible_limit():
    """As EA grows the elastic solution approaches the inextensible one, and the gap
    shrinks like 1/EA (first-order strain effect): x10 stiffer, gap /10 within 5 %."""
    r, _ = ends(math.inf)
    a, b = {"position": list(r[0])}, {"position": list(r[1])}
    ref = solve(scene(a, b, math.inf))
    gaps = []
    for ea in (1e8, 1e9, 1e10, 1e11):
        sol = solve(scene(a, b, ea))
        assert sol.success
        gaps.append(np.max(np.abs(sol.force_a - ref.force_a)))
    ratios = np.array(gaps[:-1]) / np.array(gaps[1:])
    np.testing.assert_allclose(ratios, 10.0, rtol=0.05)
    assert gaps[-1] < 1e-5 * H  # strain 2e-7 at EA = 1e11


def test_towing_force_end():
    """Type 2 (Huang 1992, (2.8)-(2.11)): end_a fixed, a known external load on end_b. With the
    load equal to the closed form's T(L), end_b lands where the closed form puts it."""
    r, t = ends(2e7)
    sol = solve(scene({"position": list(r[0])}, {"force": list(t[1])}))
    assert sol.success, sol.message
    np.testing.assert_allclose(sol.position[-1], r[1], rtol=0, atol=1e-6 * L)
    np.testing.assert_allclose(sol.force_b, -t[1], rtol=1e-12)  # JSON force = -external load


def test_towed_body_at_end_a():
    """A towed body at end_a (s = 0) with a known external load F: the cable pulls on it
    with -F (docs/conventions.md "Forces at the ends"), and the body lands where the closed form
    says relative to the fixed ship at end_b."""
    r, t = ends(2e7)
    load = -t[0]  # the body's own drag and weight, passed to the cable
    sol = solve(scene({"force": list(load)}, {"position": list(r[1])}))
    assert sol.success, sol.message
    np.testing.assert_allclose(sol.force_a, -load, rtol=1e-12)
    np.testing.assert_allclose(sol.position[0], r[0], rtol=0, atol=1e-6 * L)


def test_mooring_mixed_end():
    """Type 3 (Huang 1992, (2.12)-(2.15)): end_b has its horizontal load known and its height fixed;
    its horizontal position comes out of the solve."""
    r, t = ends(2e7)
    sol = solve(scene({"position": list(r[0])},
                      {"position": ["free", "free", r[1][2]],
                       "force": [t[1][0], t[1][1], "free"]}))
    assert sol.success, sol.message
    np.testing.assert_allclose(sol.position[-1], r[1], rtol=0, atol=1e-6 * L)
    np.testing.assert_allclose(sol.force_b, -t[1], rtol=0, atol=1e-6 * H)


@pytest.mark.parametrize("at", ["end_a", "end_b"])
def test_free_length_with_tension(at):
    """Given tension, unknown length (Wang et al. 1993, eq. (15); Chucheepsakul (1991)): prescribing
    |T| of the closed form
    at either end recovers L."""
    r, t = ends(2e7)
    a, b = {"position": list(r[0])}, {"position": list(r[1])}
    k = 0 if at == "end_a" else 1
    (a if at == "end_a" else b)["tension"] = float(np.linalg.norm(t[k]))
    sol = solve(scene(a, b, length="free"))
    assert sol.success, sol.message
    assert sol.length == pytest.approx(L, rel=1e-8)


def test_free_length_when_the_tension_is_not_the_force_scale():
    """The equations are solved in scaled units, forces divided by the largest of w x chord,
    the end loads and the prescribed tension. Above, that scale is the prescribed tension
    itself, and in scaled units |T|^2 = T0^2 and |T| = T0 coincide at 1. Here the tension
    (10 kN at the anchor) is below w x chord (17.5 kN): the length against the independent
    shooting (tests/shooting_reference.py; both converged to ~1e-10), 1e-8 relative."""
    import shooting_reference as sref

    data = {"environment": {"water_depth": 200.0, "water_density": 1025.0},
            "cable": {"length": "free", "weight_in_water": 150.0, "axial_stiffness": 1e8},
            "end_a": {"position": [0.0, 0.0, 50.0], "tension": 10000.0},
            "end_b": {"position": [100.0, 0.0, 110.0]}}
    # the cable leaves the anchor downwards: the anchor sits 50 m above the seabed plane so
    # that the profile stays in the water (else it is status below_seabed)
    sol = solve(scene_from_dict(data))
    assert sol.success, sol.message
    ref = sref.shoot(sref.problem_from_dict(data), np.array([9000.0, 0.0, -2000.0]),
                     length_guess=130.0)
    assert ref.residual < 1e-10
    assert sol.length == pytest.approx(ref.length, rel=1e-8)
    np.testing.assert_allclose(sol.force_a, ref.tension_a, rtol=0, atol=1e-8 * 1e4)


def test_vertical_hanging_cable_exact():
    """A cable hanging straight down under a clump weight (no current): tension grows
    linearly with height, the profile is a vertical line. Exact for any mesh."""
    clump = 1000.0
    sol = solve(scene({"force": [0.0, 0.0, -clump]}, {"position": [0.0, 0.0, 500.0]},
                      ea=1e7))
    assert sol.success, sol.message
    tz = clump + W * sol.s
    np.testing.assert_allclose(sol.tension_vector[:, 2], tz, rtol=1e-10)
    np.testing.assert_allclose(sol.position[:, :2], 0.0, atol=1e-9)
    stretch = (clump * L + 0.5 * W * L**2) / 1e7
    assert sol.position[0, 2] == pytest.approx(500.0 - L - stretch, abs=1e-8)
