"""The forms of each law in cable_ocp.physics against closed forms and against each other.

Tolerances: forms of one law that differ only in the order of floating-point operations agree
to rtol 1e-12 (a few ulps of ~10 operations; we allow 1e-12 against cancellation in U - U_t t
for flows nearly along the cable); a Jacobian written by hand against CasADi's AD of the value:
rtol 1e-10 (both exact; the AD graph sums terms in another order, cancellation in the
derivative of sqrt near u_n = 0 is bounded by delta = 1e-3 here).
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest

from cable_ocp.physics import added_mass as am
from cable_ocp.physics import elasticity as el
from cable_ocp.physics import seabed as sb
from cable_ocp.physics.current import (
    current_velocity,
    is_uniform,
    profile_knots,
    profile_velocity,
    profile_velocity_np,
)
from cable_ocp.physics.drag import (
    body_drag_factor,
    drag_in_local_basis,
    drag_per_length,
    drag_per_length_np,
    line_drag_factors,
    line_drag_kernel,
    point_drag,
    point_drag_error_bound,
    point_drag_jacobian,
    point_drag_np,
    quadratic_drag,
    vector_drag_columns,
)
from cable_ocp.scene import Current

RHO, D, CN, CT = 1025.0, 0.03, 1.2, 0.015
ROUND = 1e-12  # reordered floating-point sums (module docstring)
AD = 1e-10  # hand-built Jacobian against AD (module docstring)


def _unit(v) -> np.ndarray:
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def _samples(n: int = 40, seed: int = 5) -> tuple[np.ndarray, np.ndarray]:
    """Flows and unit tangents, including a vertical and two near-vertical tangents (inside
    and across the blend of the componentwise law)."""
    rng = np.random.default_rng(seed)
    t = np.array([_unit(v) for v in rng.normal(size=(n, 3))])
    t[0] = [0.0, 0.0, 1.0]
    t[1] = _unit([0.003, 0.001, 1.0])
    t[2] = _unit([0.008, -0.004, -1.0])
    u = rng.normal(size=(n, 3)) * 0.7
    return u, t


def _casadi(law: str, u, t, delta: float) -> np.ndarray:
    return np.array([np.asarray(drag_per_length(
        law, ca.DM(uu), ca.DM(tt), rho=RHO, diameter=D, normal_drag=CN, tangential_drag=CT,
        delta=delta)).ravel() for uu, tt in zip(u, t, strict=True)])


@pytest.mark.parametrize("law", ["vector", "componentwise"])
def test_numpy_form_equals_casadi_form(law):
    """The numpy form is the CasADi form: with the same smoothing, to rounding; with the exact
    modulus (delta = 0), within the smoothing bound of the CasADi form."""
    u, t = _samples()
    delta = 0.05
    np.testing.assert_allclose(
        drag_per_length_np(law, u, t, rho=RHO, diameter=D, normal_drag=CN,
                           tangential_drag=CT, delta=delta),
        _casadi(law, u, t, delta), rtol=ROUND, atol=ROUND * RHO * D)
    exact = drag_per_length_np(law, u, t, rho=RHO, diameter=D, normal_drag=CN,
                               tangential_drag=CT)
    np.testing.assert_allclose(exact, _casadi(law, u, t, 1e-9), rtol=ROUND,
                               atol=ROUND * RHO * D)
    # one tangent alone (no leading axis) works as well
    np.testing.assert_allclose(
        drag_per_length_np(law, u[5], t[5], rho=RHO, diameter=D, normal_drag=CN,
                           tangential_drag=CT), exact[5], rtol=0, atol=0)


def test_line_drag_factors_closed_form():
    kn, kt = line_drag_factors(RHO, D, CN, CT)
    assert kn == pytest.approx(0.5 * RHO * CN * D, rel=1e-15)
    assert kt == pytest.approx(0.5 * RHO * CT * math.pi * D, rel=1e-15)
    assert body_drag_factor(RHO, 1.5, 2.0) == pytest.approx(0.5 * RHO * 3.0, rel=1e-15)


def test_column_form_equals_vector_law_in_3d_and_2d():
    """vector_drag_columns on 3 x K matrices is the vector law; on the x-z rows of an in-plane
    case it is the x-z part of the 3D law (the planar model)."""
    u, t = _samples()
    kn, kt = line_drag_factors(RHO, D, CN, CT)
    delta = 0.02
    us, ts = ca.SX.sym("u", 3, len(u)), ca.SX.sym("t", 3, len(u))
    f = ca.Function("f", [us, ts], [vector_drag_columns(us, ts, kn, kt, delta)])
    np.testing.assert_allclose(np.asarray(f(u.T, t.T)).T, _casadi("vector", u, t, delta),
                               rtol=ROUND, atol=ROUND * RHO * D)
    u2, t2 = u.copy(), t.copy()
    u2[:, 1], t2[:, 1] = 0.0, 0.0
    t2 = t2 / np.linalg.norm(t2, axis=1)[:, None]
    u2s, t2s = ca.SX.sym("u", 2, len(u)), ca.SX.sym("t", 2, len(u))
    g = ca.Function("g", [u2s, t2s], [vector_drag_columns(u2s, t2s, kn, kt, delta)])
    full = _casadi("vector", u2, t2, delta)
    np.testing.assert_allclose(np.asarray(g(u2[:, [0, 2]].T, t2[:, [0, 2]].T)).T,
                               full[:, [0, 2]], rtol=ROUND, atol=ROUND * RHO * D)
    assert np.max(np.abs(full[:, 1])) == 0.0


@pytest.mark.parametrize("law", ["vector", "componentwise"])
def test_kernel_value_and_jacobian(law):
    """line_drag_kernel: its value is length x drag_per_length, with symbolic coefficients;
    its Jacobian is CasADi's AD Jacobian of the vector law with respect to the flow (for the
    componentwise law: equal to it where the two laws coincide, a 2D flow)."""
    uu, tt, ll = ca.SX.sym("u", 3), ca.SX.sym("t", 3), ca.SX.sym("l")
    par = ca.SX.sym("p", 6)  # rho, d, cn, ct, delta, blend
    f, jac = line_drag_kernel(law, uu, tt, ll, rho=par[0], diameter=par[1],
                              normal_drag=par[2], tangential_drag=par[3], delta=par[4],
                              blend=par[5])
    fvec, _ = line_drag_kernel("vector", uu, tt, ll, rho=par[0], diameter=par[1],
                               normal_drag=par[2], tangential_drag=par[3], delta=par[4],
                               blend=par[5])
    fn = ca.Function("k", [uu, tt, ll, par], [f, jac, ca.jacobian(fvec, uu) / ll])
    delta, length = 1e-3, 2.5
    p = [RHO, D, CN, CT, delta, 1e-2]
    u, t = _samples()
    for k in range(len(u)):
        val, j, j_ad = (np.asarray(x) for x in fn(u[k], t[k], length, p))
        np.testing.assert_allclose(val.ravel(), length * _casadi(law, u[k:k + 1], t[k:k + 1],
                                                                 delta)[0],
                                   rtol=ROUND, atol=ROUND * RHO * D)
        np.testing.assert_allclose(j, j_ad, rtol=AD, atol=AD * RHO * D)
    # in 2D (flow and tangent in the x-z plane) the componentwise law is the vector law: the
    # in-plane block of its AD Jacobian is the kernel's (across the plane the componentwise
    # law's derivative is 2 k_n |u_b| ~ 0, the vector law's k_n |u_n|)
    t2, u2 = _unit([0.6, 0.0, 0.8]), np.array([0.9, 0.0, -0.2])
    fc, _ = line_drag_kernel("componentwise", uu, tt, ll, rho=RHO, diameter=D, normal_drag=CN,
                             tangential_drag=CT, delta=delta, blend=1e-2)
    jc = ca.Function("jc", [uu, tt, ll], [ca.jacobian(fc, uu) / ll])
    xz = np.ix_([0, 2], [0, 2])
    np.testing.assert_allclose(np.asarray(jc(u2, t2, length))[xz],
                               np.asarray(fn(u2, t2, length, p)[1])[xz], rtol=AD,
                               atol=AD * RHO * D)


def test_local_basis_form_equals_vector_and_componentwise_laws():
    """drag_in_local_basis (Wang et al. (1993) eqs (4)-(6) on e_t, e_b, e_n) against the 3D
    laws with the exact modulus, away from vertical (where e_b = e_z x t / |e_z x t|)."""
    kn, kt = line_drag_factors(RHO, D, CN, CT)
    rng = np.random.default_rng(8)
    for _ in range(30):
        t = _unit(rng.normal(size=3))
        if math.hypot(t[0], t[1]) < 0.05:
            continue
        eb = _unit(np.cross([0.0, 0.0, 1.0], t))
        en = np.cross(t, eb)
        u = rng.normal(size=3)
        for law in ("vector", "componentwise"):
            pt, pb, pn = drag_in_local_basis(law, u @ t, u @ eb, u @ en, kn, kt)
            np.testing.assert_allclose(
                pt * t + pb * eb + pn * en,
                drag_per_length_np(law, u, t, rho=RHO, diameter=D, normal_drag=CN,
                                   tangential_drag=CT), rtol=ROUND, atol=ROUND * RHO * D)


def test_quadratic_drag_is_odd_and_exact():
    assert quadratic_drag(2.0, -3.0) == -18.0
    assert quadratic_drag(2.0, 3.0) == 18.0
    v = ca.SX.sym("v")
    f = ca.Function("q", [v], [quadratic_drag(2.0, v, 0.1)])
    # smooth modulus: 2 sqrt(9 + 0.01) 3, within k delta^2 / 2 of the exact 18
    assert float(f(3.0)) == pytest.approx(2.0 * math.sqrt(9.01) * 3.0, rel=1e-15)
    assert abs(float(f(3.0)) - 18.0) <= 2.0 * 0.5 * 0.01


@pytest.mark.parametrize("per_axis", [False, True])
def test_point_drag_closed_form_forms_and_jacobian(per_axis):
    """Vector law 1/2 rho C_D S |u| u (isotropic) and per axis 1/2 rho (C_D S)_k |u_k| u_k
    (Huang (1992) 5.2.2); numpy = CasADi; Jacobian = AD; smoothing error within its bound."""
    cs = (0.8, 1.1, 2.3) if per_axis else (1.7, 1.7, 1.7)
    delta = 0.01
    us = ca.SX.sym("u", 3)
    f = point_drag(us, cs, rho=RHO, delta=delta, per_axis=per_axis)
    fn = ca.Function("p", [us], [f, point_drag_jacobian(us, cs, rho=RHO, delta=delta,
                                                        per_axis=per_axis),
                                 ca.jacobian(f, us)])
    bound = point_drag_error_bound(cs, rho=RHO, delta=delta, per_axis=per_axis)
    rng = np.random.default_rng(3)
    for u in rng.normal(size=(20, 3)):
        val, j, j_ad = (np.asarray(x) for x in fn(u))
        if per_axis:
            exact = 0.5 * RHO * np.asarray(cs) * np.abs(u) * u
        else:
            exact = 0.5 * RHO * cs[0] * np.linalg.norm(u) * u
        np.testing.assert_allclose(point_drag_np(u, cs, rho=RHO, per_axis=per_axis), exact,
                                   rtol=ROUND)
        np.testing.assert_allclose(point_drag_np(u, cs, rho=RHO, delta=delta,
                                                 per_axis=per_axis), val.ravel(), rtol=ROUND)
        assert np.linalg.norm(val.ravel() - exact) <= bound * (1 + 1e-12)
        np.testing.assert_allclose(j, j_ad, rtol=AD, atol=AD * RHO)


def test_current_profile_forms_at_and_beyond_knots():
    """docs/conventions.md: linear in the components between knots, constant beyond the
    first and last knot, also for a profile whose first knot lies above the seabed (z = 0):
    below it the current is the first knot's. CasADi form = numpy form (rounding)."""
    knots, ux, uy = (20.0, 60.0, 150.0), (0.3, 1.0, 1.0), (0.0, -0.5, 0.4)
    z = ca.SX.sym("z")
    f = ca.Function("u", [z], [profile_velocity(z, knots, ux, uy)])
    zs = np.array([-5.0, 0.0, 19.999, 20.0, 40.0, 60.0, 100.0, 150.0, 151.0, 1e4])
    num = profile_velocity_np(zs, knots, ux, uy)
    cas = np.array([np.asarray(f(zz)).ravel() for zz in zs])
    np.testing.assert_allclose(cas, num, rtol=ROUND, atol=1e-15)
    np.testing.assert_allclose(num[0], [0.3, 0.0, 0.0], atol=0)  # below the first knot
    np.testing.assert_allclose(num[1], [0.3, 0.0, 0.0], atol=0)  # at the seabed
    np.testing.assert_allclose(num[3], [0.3, 0.0, 0.0], atol=0)  # at the knot
    np.testing.assert_allclose(num[4], [0.65, -0.25, 0.0], rtol=1e-15)  # mid-segment
    np.testing.assert_allclose(num[5], [1.0, -0.5, 0.0], rtol=1e-15)
    np.testing.assert_allclose(num[-1], [1.0, 0.4, 0.0], atol=0)  # beyond the last knot
    scaled = ca.Function("s", [z], [profile_velocity(z, knots, ux, uy, 0.5)])
    np.testing.assert_allclose(np.asarray(scaled(100.0)).ravel(), 0.5 * num[6], rtol=ROUND)
    # the scene's Current through the convenience: the same law
    cur = Current(z=knots, ux=ux, uy=uy)
    g = ca.Function("c", [z], [current_velocity(cur, z)])
    assert np.array_equal(np.asarray(g(100.0)).ravel(), np.asarray(f(100.0)).ravel())
    assert profile_knots(knots, ux, uy) == [20.0, 60.0, 150.0]
    assert profile_knots((0.0, 50.0, 100.0), (1.0, 1.0, 2.0), (0.0, 0.0, 0.0)) == [50.0, 100.0]
    assert is_uniform((0.0, 10.0), (1.0, 1.0), (0.5, 0.5))
    assert profile_knots((0.0, 10.0), (1.0, 1.0), (0.5, 0.5)) == []
    np.testing.assert_array_equal(profile_velocity_np(np.array([3.0, 30.0]), (5.0,), (0.7,),
                                                      (-0.2,)), [[0.7, -0.2, 0], [0.7, -0.2, 0]])


def test_smooth_tension_bound_switch_and_material():
    """No compression: 0 < T(e) - max(EA e, 0) <= delta_T / 2, equality at e = 0; dT/de =
    EA s(e) (against AD); T -> EA e taut; damping c de/dt s(e)."""
    ea, dt_ = 2.0e8, 0.01
    eps = np.concatenate([np.linspace(-1e-9, 1e-9, 201), [-0.1, -1e-3, 0.0, 1e-3, 0.1]])
    excess = el.smooth_tension(eps, ea, dt_) - np.maximum(ea * eps, 0.0)
    bound = el.no_compression_bound(dt_)
    assert bound == 0.005
    # > 0 in exact arithmetic; in floats the excess rounds to 0 (never below) once |EA e|
    # dwarfs delta_T (e = +-0.1 here)
    assert np.all(excess >= 0.0) and np.all(excess[:201] > 0.0)
    assert np.all(excess <= bound * (1 + 1e-15))
    assert el.smooth_tension(0.0, ea, dt_) == bound
    assert el.smooth_tension(0.1, ea, dt_) == pytest.approx(ea * 0.1, rel=1e-15)
    e = ca.SX.sym("e")
    fn = ca.Function("t", [e], [ca.jacobian(el.smooth_tension(e, ea, dt_), e),
                                ea * el.taut_switch(e, ea, dt_)])
    for x in (-1e-10, -1e-11, 0.0, 3e-11, 1e-3):
        d_ad, d_law = (float(v) for v in fn(x))
        assert d_law == pytest.approx(d_ad, rel=1e-12)
    mat = el.LinearElastic(ea, damping=3.0e5, slack_smoothing=dt_)
    assert mat.bound == bound
    assert mat.tension(1e-3, 0.2) == pytest.approx(ea * 1e-3 + 3.0e5 * 0.2, rel=1e-12)
    assert mat.tension(-1e-3, 0.2) < 1e-6  # slack: tension and damping off
    assert mat.tension(1e-3) == el.smooth_tension(1e-3, ea, dt_)
    assert float(mat.stiffness(1e-3)) == pytest.approx(ea, rel=1e-12)
    assert el.hooke_tension(-1e-3, ea) == -ea * 1e-3
    # the stored energy: 0 unstrained, its derivative the tension (AD)
    en = ca.Function("en", [e], [ca.jacobian(mat.energy(e), e), mat.tension(e)])
    assert el.smooth_strain_energy(0.0, ea, dt_) == 0.0
    for x in (-1e-3, -1e-11, 0.0, 2e-11, 1e-3):
        d_ad, t_law = (float(v) for v in en(x))
        # slack, the derivative is EA e / 2 + ~(-EA e / 2): cancellation of terms of size
        # EA |e| / 2, rounding 4 eps of that
        assert d_ad == pytest.approx(t_law, rel=1e-9, abs=4e-16 * ea * abs(x) + 1e-15)
    # CasADi expressions, the same numbers
    g = ca.Function("g", [e], [mat.tension(e, 0.2)])
    assert float(g(1e-3)) == pytest.approx(mat.tension(1e-3, 0.2), rel=1e-15)


def test_added_mass_of_vertical_and_horizontal_elements():
    """Huang (1992) eq. (5.2): m_an across the element, m_at along it."""
    man = am.added_mass_per_length(1.0, RHO, D)
    mat = am.added_mass_per_length(0.1, RHO, D)
    assert man == pytest.approx(RHO * math.pi * D * D / 4.0, rel=1e-15)
    d = ca.SX.sym("d", 3)
    fn = ca.Function("a", [d], [am.line_added_mass(d, man, mat)])
    np.testing.assert_allclose(np.asarray(fn([0.0, 0.0, 3.0])), np.diag([man, man, mat]),
                               rtol=1e-15, atol=1e-15)
    np.testing.assert_allclose(np.asarray(fn([-2.0, 0.0, 0.0])), np.diag([mat, man, man]),
                               rtol=1e-15, atol=1e-15)
    t = _unit([0.3, -0.5, 0.8])
    a = am.line_added_mass_np(t, man, mat)
    np.testing.assert_allclose(np.asarray(fn(2.0 * t)), a, rtol=ROUND, atol=ROUND * man)
    np.testing.assert_allclose(a @ t, mat * t, rtol=ROUND)  # along: tangential
    n = _unit(np.cross(t, [1.0, 0.0, 0.0]))
    np.testing.assert_allclose(a @ n, man * n, rtol=ROUND, atol=ROUND * man)  # across
    # the law on a given projector (the stepping kernel's t t^T) is the same law
    tt = ca.SX.sym("tt", 3, 3)
    proj = ca.Function("p", [tt], [am.projected_added_mass(tt, man, mat)])
    np.testing.assert_allclose(np.asarray(proj(np.outer(t, t))), a, rtol=ROUND,
                               atol=ROUND * man)
    # the planar rows are the x-z entries of the 3D matrix of an in-plane element
    t2 = _unit([0.6, 0.0, -0.8])
    dd = ca.SX.sym("dd", 2, 1)
    rows = ca.Function("r", [dd], list(am.line_added_mass_2d(dd, man, mat, 2.0)))
    axx, axz, azz = (float(v) for v in rows([t2[0] * 5.0, t2[2] * 5.0]))
    full = 2.0 * am.line_added_mass_np(t2, man, mat)
    np.testing.assert_allclose([axx, axz, azz], [full[0, 0], full[0, 2], full[2, 2]],
                               rtol=ROUND)
    assert am.virtual_mass(100.0, (5.0, 6.0, 7.0)) == (105.0, 106.0, 107.0)


def test_weight_in_water_and_buoyancy():
    m, v, g = 4500.0, 0.354, 9.81
    assert am.weight_in_water(m, v, RHO, g) == pytest.approx(m * g - am.buoyancy(v, RHO, g),
                                                            rel=1e-15)
    assert am.buoyancy(v, RHO, g) == pytest.approx(RHO * v * g, rel=1e-15)
    assert am.weight_in_water(100.0, 1.0, RHO, g) < 0.0  # buoyant


def test_seabed_plane_on_numbers():
    """A point on the plane has zero gap; the normal is a unit vector orthogonal to the
    plane's rising direction; the conveniences on a seabed object are the same laws."""
    slope, head, off = 10.0, 30.0, -5.0
    nrm = sb.plane_normal(slope, head)
    assert np.linalg.norm(nrm) == pytest.approx(1.0, rel=1e-15)
    h = math.radians(head)
    rise = np.array([math.cos(h), math.sin(h), math.tan(math.radians(slope))])
    assert abs(nrm @ rise) < 1e-15
    x, y = 40.0, -12.0
    z = sb.plane_height(x, y, slope, head, off)
    assert abs(sb.plane_gap(np.array([x, y, z]), slope, head, off)[0]) < 1e-13
    # a point 2 m above the plane along the normal
    p = np.array([x, y, z]) + 2.0 * nrm
    assert sb.plane_gap(p, slope, head, off)[0] == pytest.approx(2.0, rel=1e-13)

    class Bed:
        depth_offset, friction, slope_deg, slope_heading_deg = off, 0.4, slope, head

    e = _unit([1.0, 0.0, 0.1])
    assert sb.axial_gradient(Bed, 80.0, e) == sb.friction_gradient(80.0, e, 0.4, nrm[2])
    assert sb.friction_gradient(80.0, e, 0.4, nrm[2]) == pytest.approx(
        80.0 * e[2] + 0.4 * 80.0 * math.cos(math.radians(slope)), rel=1e-15)
    assert np.array_equal(sb.gap(Bed, p), sb.plane_gap(p, slope, head, off))
    assert sb.height(Bed, x, y) == z
