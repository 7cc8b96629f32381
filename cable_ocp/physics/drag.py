"""Hydrodynamic drag per unit length of a cable in a steady current.

Two laws, selected per problem by ``cable.drag_law``:

``vector`` (independence principle; Huang (1992) eqs (2.46)-(2.47))
    The relative flow U is split into its tangential part U_t = (U . t) t and its normal
    part U_n = U - U_t; the load per unit length is

        f = 1/2 rho C_n D |U_n| U_n  +  1/2 rho C_t pi D |U_t| U_t.

    Rotation invariant.

``componentwise`` (Wang, Cheong & Chucheepsakul 1993; Wang et al. (1993) eqs (4)-(6), Wilson's
model)
    With e_b = e_z x t / |e_z x t| and e_n = t x e_b (docs/conventions.md, "Drag"), the normal
    flow is split along e_b and e_n and each component is squared with its own sign:

        f = 1/2 rho C_n D (|U.e_b| (U.e_b) e_b + |U.e_n| (U.e_n) e_n) + tangential as above.

    In 2D (current in the plane of the cable) it equals the vector law; in 3D the two
    differ (about 2 % on Wang's Tx at psi0 = 90 deg).

The basis (e_b, e_n) is undefined on a vertical cable, and there the componentwise load
has no limit (it depends on the direction from which the tangent approaches e_z). We
regularise it: with sigma^2 = |e_z x t|^2 (the squared sine of the angle to the
vertical) and the blend parameter beta (``solver.vertical_blend``, default 0.01),

    f_n = w f_n,componentwise + (1 - w) f_n,vector,
    w = smoothstep((sigma^2 - beta^2/4) / (3 beta^2 / 4)) clipped to [0, 1],

so the law is exactly Wang's wherever the cable is more than asin(beta) (0.57 deg) from
vertical, exactly the vector law within asin(beta/2) of vertical, C^1 in between, and
finite and NaN-free everywhere (the basis vectors are divided by a floored norm).

Every modulus is replaced by :func:`cable_ocp.physics.smooth.smooth_abs`; see
:func:`drag_error_bound` for the resulting uniform error bound.
"""

from __future__ import annotations

import math
from typing import Any

import casadi as ca

from cable_ocp.physics.smooth import smooth_abs, smooth_abs_error_bound

DRAG_LAWS = ("vector", "componentwise")


def _normal_vector_law(u: Any, t: Any, delta: float) -> Any:
    """|U_n| U_n (m^2/s^2) for unit tangent t."""
    un = u - ca.dot(u, t) * t
    return ca.sqrt(ca.dot(un, un) + delta * delta) * un


def _normal_componentwise(u: Any, t: Any, delta: float, blend: float) -> Any:
    """Wang's componentwise normal term with the vertical blend (m^2/s^2)."""
    b = ca.vertcat(-t[1], t[0], 0)  # e_z x t, |b| = sigma
    n = ca.cross(t, b)  # t x (e_z x t), |n| = sigma
    sigma2 = b[0] * b[0] + b[1] * b[1]
    floor = 1e-6 * blend
    sig = ca.sqrt(sigma2 + floor * floor)
    eb = b / sig
    en = n / sig
    ub = ca.dot(u, eb)
    un = ca.dot(u, en)
    comp = smooth_abs(ub, delta) * ub * eb + smooth_abs(un, delta) * un * en
    lo2 = 0.25 * blend * blend
    x = ca.fmin(ca.fmax((sigma2 - lo2) / (blend * blend - lo2), 0.0), 1.0)
    w = x * x * (3.0 - 2.0 * x)
    return w * comp + (1.0 - w) * _normal_vector_law(u, t, delta)


def drag_per_length(
    law: str,
    u: Any,
    t: Any,
    *,
    rho: float,
    diameter: float,
    normal_drag: float,
    tangential_drag: float,
    delta: float,
    blend: float = 1e-2,
) -> Any:
    """Drag force on the cable per unit (stretched) length, N/m.

    Parameters
    ----------
    law : {"vector", "componentwise"}
        Drag law (see module docstring).
    u : casadi expression, shape (3, 1)
        Flow velocity relative to the cable, m/s.
    t : casadi expression, shape (3, 1)
        Unit tangent of the cable (-).
    rho : float
        Water density, kg/m^3.
    diameter : float
        Hydrodynamic diameter D, m.
    normal_drag, tangential_drag : float
        C_n and C_t (-); the tangential term acts on the perimeter pi*D.
    delta : float
        Smoothing velocity of the modulus, m/s.
    blend : float
        Vertical blend beta of the componentwise law (-).

    Returns
    -------
    casadi expression, shape (3, 1)
        Force per unit stretched length, N/m, in the direction the water pushes.
    """
    if law == "vector":
        normal = _normal_vector_law(u, t, delta)
    elif law == "componentwise":
        normal = _normal_componentwise(u, t, delta, blend)
    else:  # validated in scene.py; guard for API users
        raise ValueError(f"unknown drag law {law!r}; valid: {DRAG_LAWS}")
    out = 0.5 * rho * normal_drag * diameter * normal
    if tangential_drag != 0.0:
        ut = ca.dot(u, t)
        ct = 0.5 * rho * tangential_drag * math.pi * diameter
        out = out + ct * smooth_abs(ut, delta) * ut * t
    return out


def drag_error_bound(
    law: str, *, rho: float, diameter: float, normal_drag: float, tangential_drag: float,
    delta: float,
) -> float:
    """Uniform bound on the smoothing error of :func:`drag_per_length`, N/m.

    Each smoothed product u*sqrt(u^2 + delta^2) differs from u|u| by at most delta^2/2
    (:mod:`cable_ocp.physics.smooth`); the componentwise law has two orthogonal normal
    terms (factor sqrt(2)), the vector law one.
    """
    e = smooth_abs_error_bound(delta)
    k = math.sqrt(2.0) if law == "componentwise" else 1.0
    return 0.5 * rho * diameter * e * (k * normal_drag + math.pi * tangential_drag)
