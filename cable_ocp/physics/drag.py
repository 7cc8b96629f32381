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

The one law in the forms its callers need (every model, plant and baseline calls these):

* :func:`drag_per_length`: CasADi, one 3-vector (statics, lumped mass, heave plants);
* :func:`drag_per_length_np`: numpy, vectorised over nodes, exact modulus by default
  (the baselines: Huang's piecewise catenary, Chucheepsakul's FEM);
* :func:`vector_drag_columns`: CasADi on matrices whose columns are elements, in any
  dimension (the planar model's 2 x N expressions);
* :func:`drag_in_local_basis`: the law on the flow's components in (e_t, e_b, e_n), floats
  (Wang's shooting ODE in its own basis);
* :func:`line_drag_kernel`: value on an element and Jacobian with respect to the relative
  flow, as a stepping kernel needs them (its Newton matrix);
* :func:`quadratic_drag`: the scalar law k |u| u (the axial models' tangential drag and
  unit drag along the line; the heave unit model's quadratic damping b_q |x'| x' of Huang
  (1992) (6.3) in its plant, its identification and the nonlinear MPC's model);
* point-body drag, the vector law -1/2 rho C_D S |u| u or per axis (Huang (1992) 5.2.2,
  the unit's drag (5.6)): :func:`point_drag` (CasADi), :func:`point_drag_jacobian`,
  :func:`point_drag_np` (numpy), with :func:`point_drag_error_bound`.

The factors 1/2 rho C_n D and 1/2 rho C_t pi D are :func:`line_drag_factors`, the body's
1/2 rho C_D S :func:`body_drag_factor`.
"""

from __future__ import annotations

import math
from typing import Any

import casadi as ca
import numpy as np

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
    cn, ct = line_drag_factors(rho, diameter, normal_drag, tangential_drag)
    out = cn * normal
    if tangential_drag != 0.0:
        ut = ca.dot(u, t)
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

    Parameters
    ----------
    law : {"vector", "componentwise"}
        Drag law.
    rho : float
        Water density, kg/m^3.
    diameter : float
        Hydrodynamic diameter, m.
    normal_drag, tangential_drag : float
        C_n, C_t (-).
    delta : float
        Smoothing velocity, m/s.
    """
    e = smooth_abs_error_bound(delta)
    k = math.sqrt(2.0) if law == "componentwise" else 1.0
    return 0.5 * rho * diameter * e * (k * normal_drag + math.pi * tangential_drag)


# --------------------------------------------------------------------------------------
# factors
# --------------------------------------------------------------------------------------

def line_drag_factors(rho: float, diameter: float, normal_drag: float,
                      tangential_drag: float) -> tuple[float, float]:
    """(k_n, k_t) = (1/2 rho C_n D, 1/2 rho C_t pi D), N s^2/m^3 (Huang (1992) (2.46)-(2.47)).

    Parameters
    ----------
    rho : float
        Water density, kg/m^3.
    diameter : float
        Hydrodynamic diameter D, m.
    normal_drag, tangential_drag : float
        C_n and C_t (-); the tangential term acts on the perimeter pi D.
    """
    return (0.5 * rho * normal_drag * diameter,
            0.5 * rho * tangential_drag * math.pi * diameter)


def body_drag_factor(rho: float, drag_coefficient: float, drag_area: float) -> float:
    """1/2 rho C_D S, kg/m: the factor of a point body's quadratic drag.

    Parameters
    ----------
    rho : float
        Water density, kg/m^3.
    drag_coefficient : float
        C_D (-).
    drag_area : float
        Projected area S, m^2.
    """
    return 0.5 * rho * drag_coefficient * drag_area


def quadratic_drag(k: Any, u: Any, delta: float = 0.0) -> Any:
    """The scalar law k |u| u (N or N/m, as k), CasADi or float.

    ``delta`` = 0 keeps the exact modulus (``fabs``, as the axial models do); > 0 the smooth
    one sqrt(u^2 + delta^2) (error <= k delta^2 / 2). The law is odd: a body moving at v
    through still water feels ``-quadratic_drag(k, v)``.

    Parameters
    ----------
    k : float or casadi expression
        Factor, e.g. 1/2 rho C_t pi D (1 + e) per length (N s^2/m^3) or 1/2 rho C_D S (kg/m).
    u : float or casadi expression
        Flow velocity relative to the body or line, m/s.
    delta : float
        Smoothing velocity, m/s (0 = exact).
    """
    if delta != 0.0:
        mod = smooth_abs(u, delta)
    else:
        # a float keeps Python's abs (a plant's inner loop), an expression CasADi's fabs
        mod = abs(u) if isinstance(u, float) else ca.fabs(u)
    return k * mod * u


# --------------------------------------------------------------------------------------
# other forms of the line law
# --------------------------------------------------------------------------------------

def vector_drag_columns(u: Any, t: Any, kn: float, kt: float, delta: float) -> Any:
    """Vector-law drag per stretched length (N/m) on the columns of ``u`` and ``t``.

    The same law as :func:`drag_per_length` (``vector``), written on whole matrices whose
    K columns are elements (a few operations whatever K; any dimension, e.g. the planar
    model's (x, z) rows)::

        f = k_n sqrt(|U_n|^2 + delta^2) U_n + k_t sqrt(U_t^2 + delta^2) U_t t.

    Parameters
    ----------
    u : casadi SX, shape (dim, K)
        Flow relative to the elements, m/s.
    t : casadi SX, shape (dim, K)
        Unit tangents (-).
    kn, kt : float
        :func:`line_drag_factors`, N s^2/m^3; ``kt`` = 0 builds no tangential term.
    delta : float
        Smoothing velocity, m/s.
    """
    dim = u.shape[0]
    ut = ca.sum1(u * t)
    un = u - ca.repmat(ut, dim, 1) * t
    f = kn * ca.repmat(ca.sqrt(ca.sum1(un * un) + delta * delta), dim, 1) * un
    if kt != 0.0:
        f = f + kt * ca.repmat(ca.sqrt(ut * ut + delta * delta) * ut, dim, 1) * t
    return f


def drag_in_local_basis(law: str, ut: float, ub: float, un: float, kn: float,
                        kt: float) -> tuple[float, float, float]:
    """The load per length (N/m) on the basis (e_t, e_b, e_n) from the flow's components.

    Wang et al. (1993) eqs (4)-(6) (``componentwise``: P_b = k_n |U_b| U_b, P_n = k_n |U_n|
    U_n) or the vector law (P = k_n |U_n| U_n in the normal plane); P_t = k_t |U_t| U_t.
    Exact modulus, floats (a shooting ODE in its own basis calls it per evaluation).

    Parameters
    ----------
    law : {"vector", "componentwise"}
        Drag law.
    ut, ub, un : float
        Flow components on e_t, e_b, e_n, any consistent velocity unit.
    kn, kt : float
        Normal and tangential factors (:func:`line_drag_factors`, or the same scaled).
    """
    pt = kt * abs(ut) * ut
    if law == "vector":
        mag = math.sqrt(ub * ub + un * un)
        return pt, kn * mag * ub, kn * mag * un
    return pt, kn * abs(ub) * ub, kn * abs(un) * un


def drag_per_length_np(
    law: str,
    u: np.ndarray,
    t: np.ndarray,
    *,
    rho: float,
    diameter: float,
    normal_drag: float,
    tangential_drag: float,
    delta: float = 0.0,
    blend: float = 1e-2,
    signed: bool = True,
) -> np.ndarray:
    """:func:`drag_per_length` in numpy, vectorised over the leading axes, N/m.

    The same law and vertical blend; ``delta`` = 0 (the default) keeps the exact modulus
    (the baselines), > 0 the smooth one of the CasADi form (they then agree to rounding).
    ``signed = False`` gives the componentwise law as Chucheepsakul & Subwonglee (1991)
    print it, eqs (5)-(7): each flow component squared without its sign (u_b^2 e_b +
    u_n^2 e_n normal, u_t^2 t tangential), so the load never changes direction with the
    flow and a reversed current gives the same load. Wang et al. (1993), eqs (4)-(6), show
    that the modulus signs are needed; the sign-free form is kept only to show what it gives
    (``docs/baselines.md``, "Chucheepsakul & Subwonglee's Table 2").

    Parameters
    ----------
    law : {"vector", "componentwise"}
        Drag law.
    u : ndarray, shape (..., 3)
        Flow relative to the cable, m/s.
    t : ndarray, shape (..., 3)
        Unit tangents (-).
    rho : float
        Water density, kg/m^3.
    diameter : float
        Hydrodynamic diameter D, m.
    normal_drag, tangential_drag : float
        C_n and C_t (-).
    delta : float
        Smoothing velocity, m/s (0 = exact modulus).
    blend : float
        Vertical blend beta of the componentwise law (-).
    signed : bool
        False: the sign-free componentwise law of Chucheepsakul & Subwonglee (1991), eqs
        (5)-(7) (``law`` must be ``"componentwise"``).

    Returns
    -------
    ndarray, shape (..., 3)
        Force per unit stretched length, N/m.
    """
    u, t = np.asarray(u, dtype=float), np.asarray(t, dtype=float)
    kn, kt = line_drag_factors(rho, diameter, normal_drag, tangential_drag)
    if not signed and law != "componentwise":
        raise ValueError(f"the sign-free law is componentwise only, not {law!r}")

    def mod(x: np.ndarray) -> np.ndarray:
        if not signed:
            return x
        return np.abs(x) if delta == 0.0 else np.sqrt(x * x + delta * delta)

    ut = np.sum(u * t, axis=-1)
    u_n = u - ut[..., None] * t
    if delta == 0.0:
        vec = np.linalg.norm(u_n, axis=-1)[..., None] * u_n
    else:
        vec = np.sqrt(np.sum(u_n * u_n, axis=-1) + delta * delta)[..., None] * u_n
    if law == "componentwise":
        b = np.stack([-t[..., 1], t[..., 0], np.zeros(t.shape[:-1])], axis=-1)  # e_z x t
        n = np.cross(t, b)
        sig2 = b[..., 0] ** 2 + b[..., 1] ** 2
        floor = 1e-6 * blend
        sig = np.sqrt(sig2 + floor * floor)[..., None]
        eb, en = b / sig, n / sig
        ub = np.sum(u * eb, axis=-1)[..., None]
        un = np.sum(u * en, axis=-1)[..., None]
        comp = mod(ub) * ub * eb + mod(un) * un * en
        lo2 = 0.25 * blend * blend
        x = np.clip((sig2 - lo2) / (blend * blend - lo2), 0.0, 1.0)[..., None]
        wgt = x * x * (3.0 - 2.0 * x)
        normal = wgt * comp + (1.0 - wgt) * vec
    elif law == "vector":
        normal = vec
    else:
        raise ValueError(f"unknown drag law {law!r}; valid: {DRAG_LAWS}")
    return kn * normal + kt * (mod(ut) * ut)[..., None] * t


def line_drag_kernel(
    law: str,
    u: Any,
    t: Any,
    length: Any,
    *,
    rho: Any,
    diameter: Any,
    normal_drag: Any,
    tangential_drag: Any,
    delta: Any,
    blend: Any,
) -> tuple[Any, Any]:
    """Drag on one element and its Jacobian, as a stepping kernel needs them (CasADi SX).

    Every coefficient may be symbolic (a kernel compiled once and fed the element's
    parameters). Returns

    * ``f`` (3,), N: ``length`` times :func:`drag_per_length` of ``law``, the normal part
      evaluated with unit factors and scaled by rho C_n D, the tangential part added with
      its own factor 1/2 rho C_t pi D (so a symbolic C_t = 0 costs nothing at run time);
    * ``jac`` (3, 3), N s/m^2 (per stretched length): the exact Jacobian of the
      **vector** law with respect to the relative flow ``u`` at fixed ``t``::

          d f / d u = 1/2 rho C_n D (s_n (I - t t^T) + U_n U_n^T / s_n)
                      + 1/2 rho C_t pi D (s_t + U_t^2 / s_t) t t^T,

      s_n = sqrt(|U_n|^2 + delta^2), s_t = sqrt(U_t^2 + delta^2). For the componentwise law
      it is the Newton matrix of a nearby law (the values coincide in 2D, and so does the
      Jacobian's in-plane block; in 3D they differ by up to 19 %, docs/conventions.md
      "Drag"): a Newton iteration converges on the residual built from ``f``, only its
      rate depends on ``jac``.

    Parameters
    ----------
    law : {"vector", "componentwise"}
        Drag law of the value.
    u : casadi SX, shape (3, 1)
        Flow relative to the element, m/s.
    t : casadi SX, shape (3, 1)
        Unit tangent (-).
    length : casadi SX
        Stretched element length, m.
    rho : float or SX
        Water density, kg/m^3.
    diameter : float or SX
        Hydrodynamic diameter, m.
    normal_drag, tangential_drag : float or SX
        C_n, C_t (-).
    delta : float or SX
        Smoothing velocity, m/s.
    blend : float or SX
        Vertical blend of the componentwise law (-).
    """
    unit = drag_per_length(law, u, t, rho=1.0, diameter=1.0, normal_drag=1.0,
                           tangential_drag=0.0, delta=delta, blend=blend)
    f = length * unit * (rho * normal_drag * diameter)
    ut = ca.dot(u, t)
    f = f + length * 0.5 * rho * tangential_drag * math.pi * diameter * ca.sqrt(
        ut * ut + delta * delta) * ut * t
    eye = ca.SX.eye(3)
    ttt = ca.mtimes(t, t.T)
    un = u - ut * t
    sn = ca.sqrt(ca.dot(un, un) + delta * delta)
    st = ca.sqrt(ut * ut + delta * delta)
    jac = 0.5 * rho * normal_drag * diameter * (sn * (eye - ttt) + ca.mtimes(un, un.T) / sn)
    jac = jac + 0.5 * rho * tangential_drag * math.pi * diameter * (st + ut * ut / st) * ttt
    return f, jac


# --------------------------------------------------------------------------------------
# point bodies (a unit, a clump, a towed body)
# --------------------------------------------------------------------------------------

def point_drag(u: Any, drag_areas: Any, *, rho: float, delta: float,
               per_axis: bool = False) -> Any:
    """Drag on a point body, N (CasADi), for the flow ``u`` relative to it.

    Vector law (``per_axis`` False): 1/2 rho |u| (C_D S)_k u_k (isotropic for equal
    entries: 1/2 rho C_D S |u| u, the unit's drag of Huang (1992) (4.11), (5.6)); per axis
    (Huang (1992) 5.2.2, a body with different areas along its axes): 1/2 rho (C_D S)_k
    |u_k| u_k. The modulus is smooth: sqrt(.^2 + delta^2); error bound
    :func:`point_drag_error_bound`.

    Parameters
    ----------
    u : casadi expression, shape (dim, 1)
        Flow relative to the body (current minus body velocity), m/s.
    drag_areas : sequence of float
        C_D S per axis, m^2 (dim entries).
    rho : float
        Water density, kg/m^3.
    delta : float
        Smoothing velocity, m/s.
    per_axis : bool
        Per-axis law instead of the vector law.
    """
    cs = list(drag_areas)
    half_rho = 0.5 * rho
    if not per_axis:
        speed = ca.sqrt(ca.dot(u, u) + delta * delta)
        return half_rho * speed * ca.vertcat(*[cs[k] * u[k] for k in range(len(cs))])
    return half_rho * ca.vertcat(*[cs[k] * smooth_abs(u[k], delta) * u[k]
                                   for k in range(len(cs))])


def point_drag_jacobian(u: Any, drag_areas: Any, *, rho: float, delta: float,
                        per_axis: bool = False) -> Any:
    """d :func:`point_drag` / d u, kg/s (CasADi, dim x dim), exact.

    Vector law: 1/2 rho diag(C_D S) (s I + u u^T / s), s = sqrt(|u|^2 + delta^2) (symmetric
    when the entries are equal); per axis: diag(1/2 rho (C_D S)_k (s_k + u_k^2 / s_k)).

    Parameters
    ----------
    u : casadi expression, shape (dim, 1)
        Flow relative to the body, m/s.
    drag_areas : sequence of float
        C_D S per axis, m^2.
    rho : float
        Water density, kg/m^3.
    delta : float
        Smoothing velocity, m/s.
    per_axis : bool
        Per-axis law.
    """
    cs = list(drag_areas)
    dim = len(cs)
    half_rho = 0.5 * rho
    if not per_axis:
        sp = ca.sqrt(ca.dot(u, u) + delta * delta)
        return half_rho * ca.mtimes(ca.diag(ca.DM(cs)),
                                    sp * ca.SX.eye(dim) + ca.mtimes(u, u.T) / sp)
    return half_rho * ca.diag(ca.vertcat(*[
        cs[k] * (smooth_abs(u[k], delta) + u[k] ** 2 / smooth_abs(u[k], delta))
        for k in range(dim)]))


def point_drag_np(u: Any, drag_areas: Any, *, rho: float, delta: float = 0.0,
                  per_axis: bool = False) -> np.ndarray:
    """:func:`point_drag` in numpy, N (exact modulus for ``delta`` = 0).

    Parameters
    ----------
    u : array, shape (..., dim)
        Flow relative to the body, m/s.
    drag_areas : sequence of float
        C_D S per axis, m^2.
    rho : float
        Water density, kg/m^3.
    delta : float
        Smoothing velocity, m/s (0 = exact).
    per_axis : bool
        Per-axis law.
    """
    u = np.asarray(u, dtype=float)
    cs = np.asarray(drag_areas, dtype=float)
    half_rho = 0.5 * rho
    if not per_axis:
        mod = np.sqrt(np.sum(u * u, axis=-1) + delta * delta)[..., None]
    else:
        mod = np.abs(u) if delta == 0.0 else np.sqrt(u * u + delta * delta)
    return half_rho * cs * mod * u


def point_drag_error_bound(drag_areas: Any, *, rho: float, delta: float,
                           per_axis: bool = False) -> float:
    """Uniform bound on |point_drag(delta) - point_drag(0)|, N.

    Each smoothed product differs by at most delta^2 / 2 (:mod:`cable_ocp.physics.smooth`):
    1/2 rho max(C_D S) delta^2 / 2 for the vector law, sqrt(sum (C_D S)_k^2) times that
    for the per-axis law.

    Parameters
    ----------
    drag_areas : sequence of float
        C_D S per axis, m^2.
    rho : float
        Water density, kg/m^3.
    delta : float
        Smoothing velocity, m/s.
    per_axis : bool
        Per-axis law.
    """
    cs = np.abs(np.asarray(drag_areas, dtype=float))
    k = float(np.sqrt(np.sum(cs * cs))) if per_axis else float(np.max(cs))
    return 0.5 * rho * k * smooth_abs_error_bound(delta)
