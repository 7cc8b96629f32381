"""Drag laws, the smooth modulus and current profiles (cable_ocp.physics)."""

from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cable_ocp.physics.current import current_velocity
from cable_ocp.physics.drag import drag_error_bound, drag_per_length
from cable_ocp.physics.smooth import smooth_abs, smooth_abs_error_bound
from cable_ocp.scene import Current

RHO, D, CN, CT = 1021.0, 0.023, 1.0, 0.005
DELTA = 1e-9  # effectively exact: error <= delta^2/2 ~ 5e-19


def drag(law: str, u, t, blend: float = 1e-2) -> np.ndarray:
    return np.asarray(drag_per_length(law, ca.DM(u), ca.DM(t), rho=RHO, diameter=D,
                                      normal_drag=CN, tangential_drag=CT, delta=DELTA,
                                      blend=blend)).ravel()


def unit(v) -> np.ndarray:
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def test_vector_law_formula():
    """Huang (1992) (2.46)-(2.47): normal 1/2 rho Cn D |Un| Un, tangential pi/2 rho Ct D |Ut| Ut."""
    rng = np.random.default_rng(1)
    for _ in range(20):
        t, u = unit(rng.normal(size=3)), rng.normal(size=3)
        ut = (u @ t) * t
        un = u - ut
        expect = 0.5 * RHO * D * (CN * np.linalg.norm(un) * un
                                  + CT * math.pi * np.linalg.norm(ut) * ut)
        np.testing.assert_allclose(drag("vector", u, t), expect, rtol=1e-12, atol=1e-15)


def test_vector_law_rotation_invariant():
    rng = np.random.default_rng(2)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    t, u = unit(rng.normal(size=3)), rng.normal(size=3)
    np.testing.assert_allclose(drag("vector", q @ u, q @ t), q @ drag("vector", u, t),
                               rtol=1e-12, atol=1e-14)


@pytest.mark.parametrize("theta_deg", [0.0, 30.0, 100.0, 200.0, 300.0])
@pytest.mark.parametrize("phi_deg", [10.0, 45.0, 80.0, 135.0])
def test_componentwise_matches_wang(theta_deg, phi_deg):
    """Wang et al. (1993) eqs (4)-(6) with the current V along +x: the load is P_t e_t + P_b e_b +
    P_n e_n (Wang et al. 1993, eqs (1)-(3): dT/ds = W sin(phi) - P_t, ...), e_n = e_t x e_b. phi >
    90 deg (the cable leaning back, as at Berteaux's buoy) flips e_z x e_t against Wang et al.
    (1993)'s e_b; the
    componentwise terms |U.e|(U.e)e do not depend on the sign of e, so both agree."""
    th, ph, v = math.radians(theta_deg), math.radians(phi_deg), 1.0277
    t = np.array([math.cos(ph) * math.cos(th), math.cos(ph) * math.sin(th), math.sin(ph)])
    # Wang et al. (1993) Fig. 1; = e_z x t/|.| if phi < 90
    eb = np.array([-math.sin(th), math.cos(th), 0.0])
    en = np.cross(t, eb)
    cpt = math.cos(ph) * math.cos(th)
    pt = 0.5 * RHO * CT * math.pi * D * v**2 * cpt * abs(cpt)
    pb = -0.5 * RHO * CN * D * v**2 * math.sin(th) * abs(math.sin(th))
    spc = math.sin(ph) * math.cos(th)
    pn = -0.5 * RHO * CN * D * v**2 * spc * abs(spc)
    expect = pt * t + pb * eb + pn * en
    np.testing.assert_allclose(drag("componentwise", [v, 0, 0], t), expect, rtol=1e-10,
                               atol=1e-12)


def test_laws_coincide_in_2d_and_differ_in_3d():
    """docs/conventions.md "Drag": equal when the flow lies in the vertical plane of the cable."""
    t = unit([1.0, 0.0, 0.7])
    np.testing.assert_allclose(drag("componentwise", [0.8, 0, 0], t),
                               drag("vector", [0.8, 0, 0], t), rtol=1e-12)
    t3 = unit([0.3, 0.8, 0.5])
    a, b = drag("componentwise", [1.0, 0, 0], t3), drag("vector", [1.0, 0, 0], t3)
    assert np.linalg.norm(a - b) > 0.05 * np.linalg.norm(b)


def test_componentwise_on_vertical_cable():
    """The basis e_b, e_n is undefined on a vertical cable: the regularised law is finite,
    NaN-free (value and Jacobian), equals the vector law there, and is continuous: the load
    approaches it from every azimuth as the tangent approaches the vertical."""
    u = np.array([0.9, -0.4, 0.0])
    ez = np.array([0.0, 0.0, 1.0])
    at_vertical = drag("componentwise", u, ez)
    assert np.all(np.isfinite(at_vertical))
    np.testing.assert_allclose(at_vertical, drag("vector", u, ez), rtol=1e-12)
    tt = ca.SX.sym("t", 3)
    jac = ca.Function("j", [tt], [ca.jacobian(drag_per_length(
        "componentwise", ca.DM(u), tt, rho=RHO, diameter=D, normal_drag=CN,
        tangential_drag=CT, delta=1e-5), tt)])
    assert np.all(np.isfinite(np.asarray(jac(ez))))
    for az in np.linspace(0, 2 * np.pi, 7):
        gaps = []
        for eps in (1e-2, 5e-3, 1e-3, 0.0):
            t = unit([eps * math.cos(az), eps * math.sin(az), 1.0])
            f = drag("componentwise", u, t)
            assert np.all(np.isfinite(f))
            gaps.append(np.linalg.norm(f - at_vertical))
        assert gaps[-1] == 0.0 and gaps[2] < 1e-2 * np.linalg.norm(at_vertical)
    # away from vertical (sigma >= blend) the law is exactly Wang's, not blended
    t = unit([0.02, 0.0, 1.0])  # sigma ~ 0.02 > 0.01
    eb = unit(np.cross(ez, t))
    en = np.cross(t, eb)
    normal = 0.5 * RHO * CN * D * ((u @ eb) * abs(u @ eb) * eb + (u @ en) * abs(u @ en) * en)
    tang = 0.5 * RHO * CT * math.pi * D * (u @ t) * abs(u @ t) * t
    np.testing.assert_allclose(drag("componentwise", u, t), normal + tang, rtol=1e-9)


@settings(max_examples=200, deadline=None)
@given(u=st.floats(-50, 50), delta=st.floats(1e-8, 1.0))
def test_smooth_abs_error_bound(u, delta):
    """|u sqrt(u^2 + delta^2) - u|u|| <= delta^2 / 2 for every u."""
    approx = float(u * smooth_abs(u, delta))
    roundoff = 4 * np.finfo(float).eps * (u * u + delta * delta)  # cancellation in u^2 terms
    assert abs(approx - u * abs(u)) <= smooth_abs_error_bound(delta) + roundoff


def test_drag_error_bound_holds():
    rng = np.random.default_rng(3)
    delta = 0.05
    bound = drag_error_bound("componentwise", rho=RHO, diameter=D, normal_drag=CN,
                             tangential_drag=CT, delta=delta)
    for _ in range(200):
        t, u = unit(rng.normal(size=3)), rng.normal(size=3) * 0.3
        exact = drag("componentwise", u, t)
        smooth = np.asarray(drag_per_length("componentwise", ca.DM(u), ca.DM(t), rho=RHO,
                                            diameter=D, normal_drag=CN, tangential_drag=CT,
                                            delta=delta)).ravel()
        assert np.linalg.norm(smooth - exact) <= bound


def test_current_profile_interpolates_components():
    """docs/conventions.md: linear in the velocity components between knots, constant outside; a
    current that reverses with depth passes through zero at mid-depth."""
    cur = Current(z=(0.0, 100.0), ux=(-1.0, 1.0), uy=(0.0, 0.0))
    z = ca.SX.sym("z")
    f = ca.Function("u", [z], [current_velocity(cur, z)])
    np.testing.assert_allclose(np.asarray(f(50.0)).ravel(), [0, 0, 0], atol=1e-15)
    np.testing.assert_allclose(np.asarray(f(25.0)).ravel(), [-0.5, 0, 0], atol=1e-15)
    np.testing.assert_allclose(np.asarray(f(-10.0)).ravel(), [-1, 0, 0], atol=1e-15)
    np.testing.assert_allclose(np.asarray(f(250.0)).ravel(), [1, 0, 0], atol=1e-15)
    three = Current(z=(0.0, 50.0, 200.0), ux=(0.0, 1.0, 1.0), uy=(0.0, 0.0, 2.0))
    g = ca.Function("u", [z], [current_velocity(three, z, 0.5)])
    np.testing.assert_allclose(np.asarray(g(125.0)).ravel(), [0.5, 0.5, 0], atol=1e-15)
