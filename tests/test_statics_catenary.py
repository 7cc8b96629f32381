"""The elastic catenary between point loads on its own (cable_ocp.statics.catenary).

What is checked, and why each tolerance:

* The piece formulas (2.31)-(2.33) of Huang (1992) (with the derived Delta z) against
  adaptive quadrature of (2.21)-(2.23), and their Jacobian against central differences
  (moved here from tests/test_baseline_huang.py with its assertions): the formulas are
  exact, so agreement is to rounding (1e-12 relative; FD Jacobian to 1e-7: its truncation
  and rounding).
* Irvine's elastic catenary (both ends fixed, no load): the end force found by an
  independent root find on Irvine's closed-form end equations, and the profile from his
  closed form, against solve_line: 1e-9 relative (both exact; the margin covers the
  conditioning of the end equations, ~1e3, times the root finder's 1e-13).
* A taut vertical line (h = 0 on every piece, the regularised branch of the formulas):
  T(s) = T_0 + w s, z(s) = s + (T_0 s + w s^2 / 2)/EA in closed form, with both ends fixed
  (Newton on V) and with the lower end loaded by a given force (V direct, (2.40)-(2.42)):
  1e-9 relative.
* One point load, solved independently: two Irvine pieces joined at the load (the
  tension jumps by -F there), their end equations solved by scipy root: end forces,
  the load point and the jump to 1e-9 relative.
* The catenary with touchdown: tangent to the seabed at its vertex, through the top end
  (1e-9 of L: the parameter is found to 1e-12 in log a).
* The two forms of the inextensible catenary in the module agree: the closed form
  through two points (catenary_parameter, catenary_nodes) and solve_line with EA = inf
  (1e-9 relative: both exact, the parameter found to 1e-14).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import root

from cable_ocp.scene import End
from cable_ocp.statics.catenary import (
    catenary_nodes,
    catenary_parameter,
    catenary_parameter_bracketed,
    piece_increments,
    solve_line,
    touchdown_catenary,
    vertex_nodes,
)

L, W, EA = 100.0, 10.0, 1e5


def _fixed(x: float, y: float, z: float) -> End:
    return End(position=(x, y, z), force=(None, None, None))


def _irvine(h: float, v0: float, s: np.ndarray, w: float, ea: float
            ) -> tuple[np.ndarray, np.ndarray]:
    """Irvine's elastic catenary (z up, s from the lower end, T(0) = (H, V0) in the
    vertical plane): horizontal distance and height at arc lengths s, m."""
    inv = 0.0 if math.isinf(ea) else 1.0 / ea
    x = h * s * inv + h / w * (np.arcsinh((v0 + w * s) / h) - np.arcsinh(v0 / h))
    z = (v0 * s + w * s**2 / 2) * inv + h / w * (np.sqrt(1 + ((v0 + w * s) / h) ** 2)
                                                  - np.sqrt(1 + (v0 / h) ** 2))
    return x, z


# --------------------------------------------------------------------------------------
# the exact piece (2.31)-(2.33)
# --------------------------------------------------------------------------------------

@pytest.mark.parametrize("w, inv_ea, vertical", [(12.3, 0.0, False), (12.3, 1e-5, False),
                                                 (-3.0, 1e-5, False), (0.0, 1e-5, False),
                                                 (12.3, 1e-5, True)])
def test_piece_increments_exact(w: float, inv_ea: float, vertical: bool) -> None:
    """(2.31), (2.32) and the derived (2.33) equal the quadrature of (2.21)-(2.23), also
    for a buoyant (w < 0), a weightless (w = 0) and a vertical (h = 0) piece; the
    Jacobian equals central differences (to 1e-7: FD truncation/rounding)."""
    rng = np.random.default_rng(3)
    v = rng.normal(size=3) * 100.0
    if vertical:
        v[:2] = 0.0
        v[2] = 50.0
    s0, ds = np.array([0.0, 3.0]), np.array([3.0, 7.0])
    cum = np.array([[0.0, 0.0, 0.0], [5.0, -2.0, 8.0]])
    dr, jac, _ = piece_increments(v, s0, ds, cum, w, inv_ea)
    for j in range(2):
        def tau(s: float, j: int = j) -> np.ndarray:
            return v + cum[j] + np.array([0.0, 0.0, w * s])
        for k in range(3):
            ref = quad(lambda s, k=k, tau=tau: -tau(s)[k] * (inv_ea + 1 / np.linalg.norm(tau(s))),
                       s0[j], s0[j] + ds[j], epsabs=1e-14, epsrel=1e-13)[0]
            assert dr[j, k] == pytest.approx(ref, rel=1e-12, abs=1e-12)
    h = 1e-4
    fd = np.zeros((3, 3))
    for k in range(3):
        e = np.zeros(3)
        e[k] = h
        fd[:, k] = (piece_increments(v + e, s0, ds, cum, w, inv_ea)[0].sum(0)
                    - piece_increments(v - e, s0, ds, cum, w, inv_ea)[0].sum(0)) / (2 * h)
    np.testing.assert_allclose(jac, fd, rtol=1e-7, atol=1e-7 * np.abs(jac).max())


@pytest.mark.parametrize("ea", [EA, math.inf])
def test_irvine_elastic_catenary(ea: float) -> None:
    """Both ends fixed, no load: the end force and the profile equal Irvine's closed form,
    the end force found independently by a root find on his end equations."""
    span, rise = 60.0, 30.0
    e_h = np.array([0.8, 0.6])  # the ends' horizontal direction (48, 36) / 60

    def ends(x: np.ndarray) -> np.ndarray:
        xl, zl = _irvine(x[0], x[1], np.array([L]), W, ea)
        return np.array([xl[0] - span, zl[0] - rise])

    ref = root(ends, [200.0, -100.0], method="hybr", options={"xtol": 1e-14})
    assert ref.success and np.abs(ends(ref.x)).max() < 1e-10
    h, v0 = ref.x
    shape = solve_line(L, W, ea, _fixed(0.0, 0.0, 0.0), _fixed(48.0, 36.0, rise),
                       tolerance=1e-13, nodes_s=np.linspace(0.0, L, 9))
    assert shape.converged, shape.message
    np.testing.assert_allclose(shape.force_a, [h * e_h[0], h * e_h[1], v0], rtol=1e-9)
    s, r, t = shape.profile()
    x, z = _irvine(h, v0, s, W, ea)
    np.testing.assert_allclose(r, np.column_stack([x * e_h[0], x * e_h[1], z]), rtol=0,
                               atol=1e-9 * L)
    # the tension: T(s) = T(0) + w s e_z, and the force on end_b is -T(L)
    np.testing.assert_allclose(t, shape.force_a + np.outer(s, [0.0, 0.0, W]), rtol=0,
                               atol=1e-9 * np.abs(t).max())
    np.testing.assert_allclose(shape.force_b, -t[-1], rtol=0, atol=1e-9 * np.abs(t).max())
    assert shape.end_mismatch() < 1e-12


@pytest.mark.parametrize("ends", ["fixed", "lower_loaded", "upper_loaded"])
def test_taut_vertical_line(ends: str) -> None:
    """A vertical line (h = 0) stretched between its ends (Newton on V), hanging with a
    given load at its lower end, or held up by a given load at its upper end (V direct):
    T(s) = T_0 + w s e_z and z(s) = z_a + s + (T_0 s + w s^2 / 2)/EA."""
    top = 101.0  # m: 1 m of stretch over L = 100 m
    t0 = (top - L) * EA / L - W * L / 2  # N at the lower end (500 N: taut everywhere)
    end_a, end_b = _fixed(0.0, 0.0, 0.0), _fixed(0.0, 0.0, top)
    if ends == "lower_loaded":  # the external load on end_a's attachment: t0 down
        end_a = End(position=(None, None, None), force=(0.0, 0.0, -t0))
    elif ends == "upper_loaded":  # a buoy pulling end_b up with T(L) = t0 + w L
        end_b = End(position=(None, None, None), force=(0.0, 0.0, t0 + W * L))
    nodes = np.linspace(0.0, L, 11)
    shape = solve_line(L, W, EA, end_a, end_b, tolerance=1e-13, nodes_s=nodes)
    assert shape.converged, shape.message
    np.testing.assert_allclose(shape.force_b, [0.0, 0.0, -(t0 + W * L)], rtol=0,
                               atol=1e-9 * t0)
    s, r, t = shape.profile()
    np.testing.assert_allclose(shape.force_a, [0.0, 0.0, t0], rtol=0, atol=1e-9 * t0)
    np.testing.assert_allclose(t[:, 2], t0 + W * s, rtol=1e-9)
    np.testing.assert_allclose(t[:, :2], 0.0, atol=1e-9 * t0)
    np.testing.assert_allclose(r[:, 2], s + (t0 * s + W * s**2 / 2) / EA, rtol=0,
                               atol=1e-9 * L)
    np.testing.assert_allclose(r[:, :2], 0.0, atol=1e-9 * L)
    assert shape.lowest_z() == pytest.approx(0.0, abs=1e-9 * L)


def test_single_point_load_solved_independently() -> None:
    """A clump of 400 N at s = 35 m on a line fixed at both ends (2D): two Irvine pieces,
    the second starting with T(s1) - F, their end equations solved by scipy root."""
    s1, f = 35.0, np.array([0.0, 0.0, -400.0])
    span, rise = 70.0, 40.0

    def profile(x: np.ndarray) -> tuple[float, float, float, float]:
        h, v0 = x
        x1, z1 = _irvine(h, v0, np.array([s1]), W, EA)
        v1 = v0 + W * s1 - f[2]  # the tension's vertical component after the load
        x2, z2 = _irvine(h, v1, np.array([L - s1]), W, EA)
        return float(x1[0]), float(z1[0]), float(x1[0] + x2[0]), float(z1[0] + z2[0])

    def ends(x: np.ndarray) -> np.ndarray:
        _, _, xl, zl = profile(x)
        return np.array([xl - span, zl - rise])

    ref = root(ends, [300.0, -200.0], method="hybr", options={"xtol": 1e-14})
    assert ref.success and np.abs(ends(ref.x)).max() < 1e-10
    h, v0 = ref.x
    x1, z1, _, _ = profile(ref.x)
    shape = solve_line(L, W, EA, _fixed(0.0, 0.0, 0.0), _fixed(span, 0.0, rise), [s1], [f],
                       tolerance=1e-13)
    assert shape.converged, shape.message
    np.testing.assert_allclose(shape.force_a, [h, 0.0, v0], rtol=1e-9, atol=1e-9 * h)
    v_l = v0 + W * L - f[2]
    np.testing.assert_allclose(shape.force_b, [-h, 0.0, -v_l], rtol=1e-9, atol=1e-9 * h)
    s, r, t = shape.profile()
    at = np.nonzero(s == s1)[0]
    assert at.size == 2  # the load point is listed before and after the jump
    np.testing.assert_allclose(r[at[0]], [x1, 0.0, z1], rtol=0, atol=1e-9 * L)
    np.testing.assert_allclose(t[at[1]] - t[at[0]], -f, rtol=0, atol=1e-9 * abs(f[2]))


def test_the_closed_form_catenary_is_the_inextensible_line() -> None:
    """The parametric catenary through two points (both parameter searches) and
    solve_line with EA = inf and no load are the one law: same nodes and tensions."""
    span, rise, length = 80.0, 25.0, 110.0
    a = catenary_parameter(span, rise, length)
    assert a == pytest.approx(catenary_parameter_bracketed(span, rise, length), rel=1e-9)
    s = np.linspace(0.0, length, 12)
    xs, zs, ht = catenary_nodes(a, span, rise, s, W)
    shape = solve_line(length, W, math.inf, _fixed(0.0, 0.0, 0.0), _fixed(span, 0.0, rise),
                       tolerance=1e-13, nodes_s=s)
    assert shape.converged, shape.message
    s_l, r, t = shape.profile()
    np.testing.assert_allclose(np.interp(s, s_l, r[:, 0]), xs, rtol=0, atol=1e-9 * length)
    np.testing.assert_allclose(np.interp(s, s_l, r[:, 2]), zs, rtol=0, atol=1e-9 * length)
    np.testing.assert_allclose(np.interp(s, s_l, t[:, 0]), ht[:, 0], rtol=1e-9)
    np.testing.assert_allclose(np.interp(s, s_l, t[:, 2]), ht[:, 1], rtol=0,
                               atol=1e-9 * W * length)


def test_touchdown_catenary_leaves_the_seabed_tangentially_and_reaches_the_top() -> None:
    """The catenary with touchdown: from its vertex on the seabed (tension horizontal) its
    suspended length ls reaches the top end, rise and distance away from the anchor with
    the grounded part L - ls straight before it (to 1e-9 of L: Brent to 1e-12 in log a);
    a line too short to touch has none."""
    rise, distance, length = 50.0, 150.0, 180.0
    found = touchdown_catenary(rise, distance, length)
    assert found is not None
    a, ls = found
    assert 0.0 < ls < length
    xs, zs, ht = vertex_nodes(a, np.array([0.0, ls]), W)
    assert (length - ls) + xs[-1] == pytest.approx(distance, abs=1e-9 * length)
    assert zs[-1] == pytest.approx(rise, abs=1e-9 * length)
    assert zs[0] == 0.0 and ht[0, 1] == 0.0 and ht[0, 0] == pytest.approx(W * a)
    # the suspended part is a catenary: T = w (a + z) along it
    assert math.hypot(*ht[-1]) == pytest.approx(W * (a + rise), rel=1e-12)
    # 178 m over a chord of 177.2 m: the suspended catenary alone is longer than the line
    assert touchdown_catenary(rise, 170.0, 178.0) is None
