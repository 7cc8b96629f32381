"""A uniform elastic line in still water between two fixed ends, in closed form.

The line model of a mooring line where the catenary is exact (no current, one line type,
no bending stiffness, a flat seabed z = 0 or none): unstretched length L, weight in water
w per unstretched length (> 0), axial stiffness EA (finite or infinite), end_a the lower
end, end_b the upper one. In the vertical plane through the ends (horizontal span X > 0
along e_h, the unit horizontal vector from end_a to end_b, height Z = z_b - z_a) the
unknowns are H, the horizontal tension, and V_b, the vertical component of the tension at
end_b. Irvine (1981), ch. 1; Huang (1992), (2.31)-(2.33) (:mod:`cable_ocp.statics.catenary`);
the same cases as MoorPy's ``Catenary.py`` (profile types 1, 2, 3):

**Fully suspended** (V_a = V_b - w L, T_a = sqrt(H^2 + V_a^2), T_b = sqrt(H^2 + V_b^2))::

    X = (H/w) [asinh(V_b/H) - asinh(V_a/H)] + H L / EA
    Z = (T_b - T_a)/w + L (V_a + V_b) / (2 EA)

**Grounded at end_a** (end_a on the seabed and V_b < w L): a suspended length
L_s = V_b / w leaves the seabed horizontally at the touchdown; the grounded length
L_g = L - L_s is straight along e_h, its tension falling by k = mu w per metre from H at
the touchdown towards the anchor, T(s') = max(H - k (L_g - s'), 0)
(:func:`cable_ocp.physics.seabed.friction_gradient`; zero from s' = L_g - H/k on when the
friction exhausts it, MoorPy's profile type 3: the anchor force is then zero)::

    X = L_g + (H/w) asinh(V_b/H) + H V_b/(w EA) + (1/EA) int_0^L_g T ds'
    Z = (T_b - H)/w + V_b^2 / (2 w EA)

with the integral :func:`cable_ocp.physics.seabed.grounded_tension_integral`. The two
branches meet with their Jacobians at V_b = w L (C^1), so one Newton iteration on (H, V_b)
with the analytic 2x2 Jacobian J = d(X, Z)/d(H, V_b) crosses the lift-off.

**End forces and their 6x6 Jacobian.** The force on end_b's attachment is
F_b = -(H e_h + V_b e_z), on end_a's F_a = H_a e_h + V_a e_z (H_a = H, V_a = V_b - w L
suspended; H_a = max(H - k L_g, 0), V_a = 0 grounded). By the implicit-function theorem
d(H, V_b)/d(X, Z) = J^-1, with dX/dx_b = e_h, dZ/dz_b = 1 (minus for end_a); the
horizontal direction normal to the plane turns e_h: de_h/dx_b = (I - e_h e_h^T - e_z e_z^T)
/ X, which gives the out-of-plane terms H_a / X (on F_a) and -H / X (on F_b). Where the
line lies on the seabed at end_a the z_a column is NaN (one-sided contact), as in the
collocation's :meth:`~cable_ocp.statics.solution.StaticsSolution.end_jacobian`.

:func:`solve_catenary_line` returns a :class:`~cable_ocp.statics.solution.StaticsSolution`
(``diagnostics["method"] = "catenary"``, the solved ``horizontal_tension`` and
``vertical_force``, which :func:`solve_catenary_line` accepts back as ``guess``: the warm
start). :func:`catenary_exact` says whether a single-line scene is one it solves exactly.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from typing import Any

import numpy as np

from cable_ocp.physics import seabed as seabed_law
from cable_ocp.scene import Scene
from cable_ocp.statics.checks import check_physical
from cable_ocp.statics.solution import StaticsSolution

__all__ = ["catenary_exact", "line_equations", "solve_catenary_line", "solve_catenary_scene"]

#: most Newton steps on (H, V_b)
MAX_NEWTON = 100

_EZ = np.array([0.0, 0.0, 1.0])


def line_equations(h: float, vb: float, length: float, weight: float, axial_stiffness: float,
                   friction: float, contact: bool) -> tuple[float, float, np.ndarray, bool]:
    """The span X (m), height Z (m) of the line for a given (H, V_b) and their Jacobian.

    Parameters
    ----------
    h : float
        Horizontal tension H, N (> 0).
    vb : float
        Vertical tension component at end_b V_b, N.
    length : float
        Unstretched length L, m.
    weight : float
        Weight in water per unstretched length w, N/m (> 0).
    axial_stiffness : float
        EA, N (``math.inf``: inextensible).
    friction : float
        Axial friction coefficient mu of the grounded part (-).
    contact : bool
        end_a lies on the seabed: the grounded branch applies where V_b < w L.

    Returns
    -------
    x, z : float
        Span and height, m.
    jac : ndarray, shape (2, 2)
        d(X, Z)/d(H, V_b), m/N.
    grounded : bool
        The grounded branch was used.
    """
    w, big_l = weight, length
    inv_ea = 0.0 if math.isinf(axial_stiffness) else 1.0 / axial_stiffness
    tb = math.hypot(h, vb)
    if not (contact and vb < w * big_l):
        va = vb - w * big_l
        ta = math.hypot(h, va)
        ash = math.asinh(vb / h) - math.asinh(va / h)
        x = h / w * ash + h * big_l * inv_ea
        z = big_l * (va + vb) / (ta + tb) + 0.5 * big_l * (va + vb) * inv_ea
        dx_dh = ash / w - (vb / tb - va / ta) / w + big_l * inv_ea
        dx_dv = h / w * (1.0 / tb - 1.0 / ta)
        dz_dv = (vb / tb - va / ta) / w + big_l * inv_ea
        return x, z, np.array([[dx_dh, dx_dv], [dx_dv, dz_dv]]), False
    ls = vb / w
    lg = big_l - ls
    k = seabed_law.friction_gradient(w, _EZ * 0.0, friction, 1.0)  # mu w on a flat seabed
    integral = seabed_law.grounded_tension_integral(h, k, lg)
    slack = k > 0 and k * lg > h  # the friction exhausts the tension before the anchor
    ash = math.asinh(vb / h)
    x = lg + h / w * ash + h * vb / w * inv_ea + integral * inv_ea
    rise = vb * vb / (tb + h)  # T_b - H without cancellation
    z = rise / w + 0.5 * vb * vb / w * inv_ea
    # d(integral)/dH and d/dV_b (dL_g/dV_b = -1/w)
    di_dh = h / k if slack else lg
    di_dv = 0.0 if slack else -(h - k * lg) / w
    dx_dh = ash / w - vb / (w * tb) + vb / w * inv_ea + di_dh * inv_ea
    dx_dv = -1.0 / w + h / (w * tb) + h / w * inv_ea + di_dv * inv_ea
    dz_dh = -vb * vb / (tb * (tb + h)) / w  # (H/T_b - 1)/w without cancellation
    dz_dv = vb / (w * tb) + vb / w * inv_ea
    return x, z, np.array([[dx_dh, dx_dv], [dz_dh, dz_dv]]), True


def _cold_guess(span: float, rise: float, length: float, weight: float,
                axial_stiffness: float) -> tuple[float, float]:
    """(H, V_b) to start Newton from without a warm start (MoorPy's ``Catenary.py`` start,
    after Peyrot and Goulois (1979); a taut elastic line from its chord's stretch)."""
    chord = math.hypot(span, rise)
    w = weight
    if length >= chord:
        lam = math.sqrt(3.0 * max((length * length - rise * rise) / (span * span) - 1.0,
                                  0.0)) or 0.2
        h = max(abs(w * span / (2.0 * lam)), 1e-6 * w * length)
        vb = 0.5 * w * (rise / math.tanh(lam) + length)
        return h, vb
    tension = axial_stiffness * (chord / length - 1.0) + w * length
    return tension * span / chord, tension * rise / chord + 0.5 * w * length


def _newton(span: float, rise: float, length: float, weight: float, ea: float,
            friction: float, contact: bool, start: tuple[float, float], tolerance: float
            ) -> tuple[float, float, int, bool, str]:
    """Newton's method with backtracking on (H, V_b): (H, V_b, steps, converged, how)."""
    h, vb = start
    scale = max(length, span, rise)
    target = np.array([span, rise])

    def resid(h_: float, v_: float) -> tuple[np.ndarray, np.ndarray]:
        x, z, jac, _ = line_equations(h_, v_, length, weight, ea, friction, contact)
        return np.array([x, z]) - target, jac

    r, jac = resid(h, vb)
    for it in range(MAX_NEWTON + 1):
        norm = float(np.max(np.abs(r)))
        if not math.isfinite(norm):
            return h, vb, it, False, "non-finite Newton iterate"
        if norm <= tolerance * scale:
            return h, vb, it, True, f"Newton converged in {it} steps"
        if it == MAX_NEWTON:
            break
        try:
            step = -np.linalg.solve(jac, r)
        except np.linalg.LinAlgError:
            return h, vb, it, False, "singular Newton matrix"
        alpha = 1.0
        # keep H > 0 (at most a tenfold drop per step) and, grounded, V_b > 0
        if step[0] < -0.9 * h:
            alpha = -0.9 * h / step[0]
        if contact and vb + alpha * step[1] <= 0.0:
            alpha = min(alpha, -0.9 * vb / step[1]) if vb > 0 else alpha
        accepted = False
        while alpha > 1e-12:
            ht, vt = h + alpha * step[0], vb + alpha * step[1]
            rt, jt = resid(ht, vt)
            nt = float(np.linalg.norm(rt))
            if math.isfinite(nt) and nt < (1.0 - 1e-4 * alpha) * float(np.linalg.norm(r)):
                accepted = True
                break
            alpha *= 0.5
        if not accepted:
            if norm <= 1e3 * tolerance * scale:  # rounding floor just above the tolerance
                return h, vb, it, True, f"Newton converged in {it} steps (rounding floor)"
            return h, vb, it, False, "Newton line search failed"
        h, vb, r, jac = ht, vt, rt, jt
    return h, vb, MAX_NEWTON, False, f"Newton: no convergence in {MAX_NEWTON} steps"


def solve_catenary_line(length: float, weight: float, axial_stiffness: float,
                        end_a: Sequence[float], end_b: Sequence[float], *,
                        friction: float = 0.0, contact: bool = False,
                        guess: tuple[float, float] | None = None, tolerance: float = 1e-13,
                        nodes: int = 41, grounded_nodes: int = 11) -> StaticsSolution:
    """The uniform elastic line between two fixed ends in still water, in closed form.

    Parameters
    ----------
    length : float
        Unstretched length L, m.
    weight : float
        Weight in water per unstretched length w, N/m (> 0).
    axial_stiffness : float
        EA, N (``math.inf``: inextensible).
    end_a, end_b : sequence of 3 float
        Positions of the lower end (on the seabed z = 0 when ``contact``) and of the upper
        end, m.
    friction : float
        Axial friction coefficient mu of the grounded part (-).
    contact : bool
        end_a lies on a flat seabed z = 0 with contact (a grounded part from end_a).
    guess : (float, float), optional
        (H, V_b), N, to start Newton from (a previous solution's
        ``diagnostics["horizontal_tension"]``, ``["vertical_force"]``); else a cold start.
    tolerance : float
        Newton's tolerance on the span and height, relative to the largest of L, X, Z.
    nodes : int
        Nodes of the profile on the suspended part (>= 2).
    grounded_nodes : int
        Nodes of the profile on the grounded part, the touchdown included (>= 2).

    Returns
    -------
    StaticsSolution
        ``status`` "solved" when Newton converged, else "failed" with the reason;
        ``end_jacobian()`` the exact 6x6 dF/dx; ``grounded_length`` the laid length, m.
    """
    t0 = time.perf_counter()
    xa, xb = np.asarray(end_a, float), np.asarray(end_b, float)
    d = xb - xa
    span, rise = math.hypot(d[0], d[1]), float(d[2])
    ea, w, big_l = float(axial_stiffness), float(weight), float(length)
    diag: dict[str, Any] = {"method": "catenary", "span": span, "height": rise,
                            "weight": w, "axial_stiffness": ea, "friction": friction}

    def failed(msg: str) -> StaticsSolution:
        return StaticsSolution(status="failed", message=msg, s=np.array([0.0, big_l]),
                               position=np.vstack([xa, xb]), tension_vector=np.full((2, 3),
                                                                                    np.nan),
                               length=big_l, wall_time_s=time.perf_counter() - t0,
                               diagnostics=diag)

    if not (w > 0 and math.isfinite(w)):
        return failed(f"the catenary line model needs a weight in water w > 0 (got {w:g} N/m)")
    if span <= 1e-9 * big_l:
        return failed("the ends are vertically above one another (X = 0): a vertical line is "
                      "not handled by the catenary line model")
    if math.isinf(ea) and math.hypot(span, rise) >= big_l * (1.0 - 1e-12):
        return failed(f"an inextensible line of length {big_l:g} m is too short for the span "
                      f"{math.hypot(span, rise):g} m between its ends")
    if contact and rise <= 0.0:
        return failed("end_b is not above the seabed end end_a (Z <= 0)")
    starts = [guess] if guess is not None and guess[0] > 0 and math.isfinite(guess[1]) else []
    starts.append(_cold_guess(span, rise, big_l, w, ea))
    for start in starts:
        h, vb, its, ok, how = _newton(span, rise, big_l, w, ea, friction, contact,
                                      (float(start[0]), float(start[1])), tolerance)
        if ok:
            break
    diag.update({"horizontal_tension": h, "vertical_force": vb, "newton": how})
    if not ok:
        return failed(f"the catenary's Newton iteration did not converge: {how}")
    _, _, jac, grounded = line_equations(h, vb, big_l, w, ea, friction, contact)
    e_h = np.array([d[0] / span, d[1] / span, 0.0])
    k = friction * w
    lg = big_l - vb / w if grounded else 0.0
    h_a = max(h - k * lg, 0.0) if grounded else h
    v_a = 0.0 if grounded else vb - w * big_l
    # the profile: grounded nodes (anchor to touchdown), then the suspended part
    inv_ea = 0.0 if math.isinf(ea) else 1.0 / ea
    s_list, r_list, t_list = [], [], []
    if grounded:
        sg, rg, tg = seabed_law.grounded_nodes(xa, e_h, h, k, lg, ea, max(grounded_nodes, 2))
        s_list.append(sg[:-1])
        r_list.append(rg[:-1])
        t_list.append(tg[:-1])
        r0 = rg[-1]
        v0 = 0.0
    else:
        r0, v0 = xa, v_a
    s_sus = np.linspace(lg, big_l, max(nodes, 2))
    vs = v0 + w * (s_sus - lg)
    ts, t0s = np.hypot(h, vs), math.hypot(h, v0)
    along = h / w * (np.arcsinh(vs / h) - math.asinh(v0 / h)) + h * (s_sus - lg) * inv_ea
    up = (vs - v0) * (vs + v0) / (w * (ts + t0s)) + 0.5 * (vs * vs - v0 * v0) / w * inv_ea
    r_sus = r0[None, :] + np.outer(along, e_h) + np.outer(up, _EZ)
    r_sus[-1] = xb  # the end where it is held (the profile closes to the Newton tolerance)
    s_list.append(s_sus)
    r_list.append(r_sus)
    t_list.append(np.outer(np.full_like(s_sus, h), e_h) + np.outer(vs, _EZ))
    s = np.concatenate(s_list)
    tension = np.vstack(t_list)
    tension[0] = h_a * e_h + v_a * _EZ
    offset = len(s_list[0]) if grounded else 0
    diag.update({"grounded": grounded, "anchor_slack": bool(grounded and k * lg >= h),
                 "touchdown": r0.tolist() if grounded else None})
    sens = _sensitivities(jac, h, vb, big_l, w, ea, friction, span, e_h, grounded)
    sol = StaticsSolution(status="solved", message=f"catenary: {how}", s=s,
                          position=np.vstack(r_list), tension_vector=tension, length=big_l,
                          iterations=its, wall_time_s=time.perf_counter() - t0,
                          constraint_violation=0.0, error_estimate=0.0, diagnostics=diag,
                          node_offset=offset)
    sol._jacobian_source = lambda: sens["end_jacobian"].copy()
    sol._length_source = lambda: {key: (val.copy() if isinstance(val, np.ndarray) else val)
                                  for key, val in sens.items()}
    return sol


def _sensitivities(jac: np.ndarray, h: float, vb: float, length: float, weight: float,
                   axial_stiffness: float, friction: float, span: float, e_h: np.ndarray,
                   grounded: bool) -> dict[str, Any]:
    """The end forces' and the grounded length's sensitivities (module docstring): the
    6x6 dF/dx, F = (F_a, F_b), x = (x_a, x_b), N/m; dF/dL (6,), N/m; dg/dL (-), dg/dx (6,)
    (-), g the grounded length; the z_a entries NaN where the line lies on the seabed at
    end_a."""
    w, big_l = weight, length
    inv_ea = 0.0 if math.isinf(axial_stiffness) else 1.0 / axial_stiffness
    k = friction * w
    lg = big_l - vb / w if grounded else 0.0
    slack = grounded and k * lg >= h
    h_a = max(h - k * lg, 0.0) if grounded else h
    inv = np.linalg.inv(jac)  # d(H, V_b)/d(X, Z)
    # d(H_a, V_a)/d(H, V_b) and the explicit d(H_a, V_a)/dL; d(X, Z)/dL at fixed (H, V_b)
    if grounded:
        da = np.zeros((2, 2)) if slack else np.array([[1.0, friction], [0.0, 0.0]])
        da_l = np.array([0.0 if slack else -k, 0.0])
        xz_l = np.array([1.0 + h_a * inv_ea, 0.0])
    else:
        va = vb - w * big_l
        ta = math.hypot(h, va)
        da, da_l = np.eye(2), np.array([0.0, -w])
        xz_l = np.array([h / ta + h * inv_ea, va / ta + va * inv_ea])
    hv_l = -inv @ xz_l  # d(H, V_b)/dL
    basis = np.column_stack([e_h, _EZ])  # (3, 2): the in-plane directions
    perp = np.eye(3) - np.outer(e_h, e_h) - np.outer(_EZ, _EZ)
    # d/dx_b of F_b = -(H e_h + V_b e_z) and of F_a = H_a e_h + V_a e_z (e_h turns by
    # perp / X); everything depends on x_b - x_a
    kbb = -(basis @ inv @ basis.T) - h / span * perp
    kab = basis @ (da @ inv) @ basis.T + h_a / span * perp
    jacobian = np.empty((6, 6))
    jacobian[:3, 3:], jacobian[:3, :3] = kab, -kab
    jacobian[3:, 3:], jacobian[3:, :3] = kbb, -kbb
    force_l = np.concatenate([basis @ (da @ hv_l + da_l), -(basis @ hv_l)])
    if grounded:  # g = L - V_b / w
        g_xb = -(basis @ inv[1]) / w
        g_x = np.concatenate([-g_xb, g_xb])
        g_l = 1.0 - hv_l[1] / w
        jacobian[:, 2] = np.nan
        g_x[2] = np.nan
    else:
        g_x, g_l = np.zeros(6), 0.0
    return {"force": force_l, "end_jacobian": jacobian, "grounded_length": float(g_l),
            "grounded_length_ends": g_x}


def catenary_exact(scene: Scene) -> str:
    """Why the catenary line model is not exact for ``scene``, "" when it is: no current,
    one uniform part without bending stiffness and without bodies, a weight in water > 0,
    both ends fixed, a flat seabed z = 0 (or none).

    Parameters
    ----------
    scene : Scene
        A single-line statics scene (end_a the lower end).
    """
    env = scene.environment
    if env.current is not None:
        return "a current acts on the line"
    if len(scene.segments) > 1:
        return "the line has several parts"
    if scene.bodies:
        return "the line carries bodies"
    if scene.cable.bending_stiffness:
        return "the line has bending stiffness"
    if scene.cable.length is None:
        return "the length is an unknown"
    if not scene.cable.weight_in_water > 0:
        return "the line is not heavier than water"
    if not (all(scene.end_a.fixed_mask) and all(scene.end_b.fixed_mask)):
        return "an end is not fixed"
    sb = env.seabed
    if sb is not None and (sb.slope_deg != 0.0 or sb.depth_offset != 0.0):
        return "the seabed is not the flat plane z = 0"
    return ""


def solve_catenary_scene(scene: Scene, guess: tuple[float, float] | None = None
                         ) -> StaticsSolution:
    """:func:`solve_catenary_line` on a single-line scene :func:`catenary_exact` accepts,
    with contact where end_a lies on the seabed, and the method-free checks
    (:func:`cable_ocp.statics.checks.check_physical`; with a seabed table and end_a off
    the seabed, a profile through the seabed is ``"below_seabed"``).

    Parameters
    ----------
    scene : Scene
        The scene.
    guess : (float, float), optional
        (H, V_b), N: Newton's start (a previous solution's diagnostics).
    """
    why = catenary_exact(scene)
    if why:
        return StaticsSolution(status="failed", message=f"not a catenary line: {why}",
                               s=np.zeros(0), position=np.zeros((0, 3)),
                               tension_vector=np.zeros((0, 3)),
                               length=float(scene.cable.length or math.nan),
                               diagnostics={"method": "catenary"})
    cab, sb = scene.cable, scene.environment.seabed
    xa = np.asarray(scene.end_a.position, float)
    xb = np.asarray(scene.end_b.position, float)
    tol_z = 1e-6 * float(cab.length)  # as the collocation's can_ground
    contact = sb is not None and abs(xa[2]) <= tol_z
    sol = solve_catenary_line(float(cab.length), cab.weight_in_water, cab.axial_stiffness,
                              xa, xb, friction=sb.friction if sb is not None else 0.0,
                              contact=contact, guess=guess)
    if sol.status == "solved" and sb is not None and not contact:
        low = _lowest(sol)
        if low < -tol_z:
            sol.status = "below_seabed"
            sol.message = (f"the cable passes {-low:.3g} m below the seabed; end_a is not "
                           "anchored on the seabed, and contact elsewhere is not modelled yet")
    return check_physical(scene, sol)


def _lowest(sol: StaticsSolution) -> float:
    """Lowest height of a suspended line, m: at the vertex (V = 0) when it lies between
    the ends (Z of the piece from V_a to 0, as in :func:`line_equations`), else end_a's."""
    d = sol.diagnostics
    h, w, ea = d["horizontal_tension"], d["weight"], d["axial_stiffness"]
    va = d["vertical_force"] - w * sol.length
    za = float(sol.position[0, 2])
    if va >= 0.0 or sol.node_offset:
        return za
    inv_ea = 0.0 if math.isinf(ea) else 1.0 / ea
    return za - va * va / (w * (h + math.hypot(h, va))) - 0.5 * va * va / w * inv_ea
