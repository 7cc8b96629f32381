"""Prescribed top motion and pay-out law as CasADi expressions of time.

The same expressions serve every model: they are built once on a symbolic time and
differentiated by CasADi, so velocities and accelerations are exact derivatives of the
positions (no finite differences), and a time-stepper written as a CasADi function can
evaluate them inside ``mapaccum`` without Python per step.

Formulas (t in s; offsets in m from ``end_b.position``; ``r(t)`` the ramp, 1 without
``ramp_time``, else 10x^3 - 15x^4 + 6x^5 with x = min(t / ramp_time, 1), twice
continuously differentiable, so the ramp adds no force step; ``R(t)`` its integral,
t - ramp_time/2 after the ramp):

* heave: dz = r A sin(w t)
* horizontal: (dx, dy) = r A sin(w t) (cos psi, sin psi)
* circular: dz = r a sin(w t), (dx, dy) = r a (1 - cos(w t)) (cos psi, sin psi)
* tow: the path point at distance d = v R(t) along straight - arc - straight
* series: linear interpolation of the rows, held after the last one
* pay-out (Huang (1992) 3.1): L = L0 + v R(t) (linear), L0 + v R(t) + a t^2 / 2
  (quadratic), L0 + r p sin(w t) (periodic)
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import casadi as ca
import numpy as np

from cable_ocp.numerics.ramp import smoothstep, smoothstep_integral
from cable_ocp.numerics.table import piecewise_linear, speed_table_length

if TYPE_CHECKING:  # types only: the scene module uses this one at run time
    from cable_ocp.scene.dynamic_parts import TopMotion, Tow
    from cable_ocp.scene.dynamics import DynamicScene


__all__ = ["length_expr", "length_numeric", "motion_function", "top_offset_expr"]


def _ramp(tm: TopMotion, t: ca.SX) -> tuple[ca.SX, ca.SX]:
    """(r(t), R(t) = integral of r from 0 to t)."""
    tau = tm.ramp_time
    if tau <= 0.0:
        return ca.SX(1.0), t
    x = ca.fmin(ca.fmax(t / tau, 0.0), 1.0)
    r = smoothstep(x)
    big_r = ca.if_else(t < tau, tau * smoothstep_integral(x), t - 0.5 * tau)
    return r, big_r


def _tow_offset(tow: Tow, d: ca.SX) -> tuple[ca.SX, ca.SX]:
    """Horizontal offset (x, y) at distance d (m) along the towing path."""
    psi = math.radians(tow.heading_deg)
    e = (math.cos(psi), math.sin(psi))
    if not math.isfinite(tow.straight_length) or tow.turn_angle_deg == 0.0:
        return d * e[0], d * e[1]
    s0 = tow.straight_length
    rad = 0.5 * tow.turn_diameter
    sign = 1.0 if tow.turn_direction == "left" else -1.0
    n = (-sign * e[1], sign * e[0])  # towards the centre of the turn
    theta = math.radians(tow.turn_angle_deg)
    c = (s0 * e[0] + rad * n[0], s0 * e[1] + rad * n[1])
    phi = ca.fmin(ca.fmax((d - s0) / rad, 0.0), theta)
    arc = (c[0] - rad * n[0] * ca.cos(phi) + rad * e[0] * ca.sin(phi),
           c[1] - rad * n[1] * ca.cos(phi) + rad * e[1] * ca.sin(phi))
    end = (c[0] - rad * n[0] * math.cos(theta) + rad * e[0] * math.sin(theta),
           c[1] - rad * n[1] * math.cos(theta) + rad * e[1] * math.sin(theta))
    psi_end = psi + sign * theta
    e_end = (math.cos(psi_end), math.sin(psi_end))
    s1 = s0 + rad * theta
    after = (end[0] + (d - s1) * e_end[0], end[1] + (d - s1) * e_end[1])
    out = []
    for k in range(2):
        out.append(ca.if_else(d <= s0, d * e[k], ca.if_else(d <= s1, arc[k], after[k])))
    return out[0], out[1]


def top_offset_expr(tm: TopMotion, t: ca.SX) -> ca.SX:
    """Offset of end_b from its static position, m, as a 3-vector expression of t (s).

    Parameters
    ----------
    tm : TopMotion
        The scene's ``[top_motion]``: the heave, horizontal, circular, tow and series
        components are summed (see the module docstring for the formulas).
    t : casadi.SX
        Scalar symbolic time, s (t = 0 the start of the motion).
    """
    r, big_r = _ramp(tm, t)
    dx = ca.SX(0.0)
    dy = ca.SX(0.0)
    dz = ca.SX(0.0)
    if tm.heave_amplitude != 0.0:
        dz = dz + r * tm.heave_amplitude * ca.sin(tm.heave_frequency * t)
    if tm.horizontal_amplitude != 0.0:
        psi = math.radians(tm.horizontal_heading_deg)
        h = r * tm.horizontal_amplitude * ca.sin(tm.horizontal_frequency * t)
        dx = dx + h * math.cos(psi)
        dy = dy + h * math.sin(psi)
    if tm.circular_radius != 0.0:
        psi = math.radians(tm.circular_heading_deg)
        w = tm.circular_frequency
        h = r * tm.circular_radius * (1.0 - ca.cos(w * t))
        dx = dx + h * math.cos(psi)
        dy = dy + h * math.sin(psi)
        dz = dz + r * tm.circular_radius * ca.sin(w * t)
    if tm.tow is not None:
        tx, ty = _tow_offset(tm.tow, tm.tow.speed * big_r)
        dx = dx + tx
        dy = dy + ty
    if tm.series:
        rows = np.asarray(tm.series, dtype=float)
        ts = rows[:, 0]
        for k, comp in enumerate((0, 1, 2)):
            vals = rows[:, 1 + comp]
            if not np.any(vals):
                continue
            # piecewise linear, held after the last row (its cost independent of the rows)
            expr = piecewise_linear(ts, vals, t)
            if k == 0:
                dx = dx + expr
            elif k == 1:
                dy = dy + expr
            else:
                dz = dz + expr
    return ca.vertcat(dx, dy, dz)


def length_expr(tm: TopMotion, length0: float, t: ca.SX) -> ca.SX:
    """Unstretched length L(t), m, of the pay-out law (Huang (1992) 3.1).

    Parameters
    ----------
    tm : TopMotion
        The scene's ``[top_motion]``: its ``payout_law`` (``"linear"``, ``"quadratic"``
        or ``"periodic"``), speed (m/s), acceleration (m/s^2), amplitude (m), frequency
        (rad/s) and ``ramp_time`` (s).
    length0 : float
        Unstretched length at t = 0, m.
    t : casadi.SX
        Scalar symbolic time, s.
    """
    if tm.payout_law == "table":
        return table_length_expr(tm.payout_table, tm.payout_table_kind, length0, t)
    r, big_r = _ramp(tm, t)
    if tm.payout_law == "periodic":
        return length0 + r * tm.payout_amplitude * ca.sin(tm.payout_frequency * t)
    out = length0 + tm.payout_speed * big_r
    if tm.payout_law == "quadratic":
        out = out + 0.5 * tm.payout_acceleration * t**2
    return out


def table_length_expr(rows: Sequence[tuple[float, float]], kind: str, length0: float,
                      t: ca.SX) -> ca.SX:
    """Unstretched length L(t), m, of ``payout_law = "table"``.

    ``kind = "speed"`` (rows (t_j, v_j), s and m/s): the speed is linear in t between rows
    and held after the last, and L is its exact integral from ``length0``: on
    [t_j, t_j+1], L = L_j + v_j (t - t_j) + (v_j+1 - v_j) (t - t_j)^2 / (2 (t_j+1 - t_j)),
    L_j the trapezoidal sums (exact for a linear speed); a time given twice is a jump in
    speed (a sudden stop), L continuous through it. ``kind = "length"`` (rows (t_j, L_j),
    s and m): L linear in t between rows (the speed piecewise constant, jumping at the
    rows), held after the last row. ``top_motion.ramp_time`` does not act on a table.

    Parameters
    ----------
    rows : sequence of (float, float)
        The table (validated by :mod:`cable_ocp.scene.dynamic_parts`).
    kind : str
        ``"speed"`` or ``"length"``.
    length0 : float
        Unstretched length at t = 0, m (a length table's first length).
    t : casadi.SX
        Scalar symbolic time, s.
    """
    ts = [float(r[0]) for r in rows]
    vs = [float(r[1]) for r in rows]
    if kind == "length":
        return piecewise_linear(ts, vs, t)
    return speed_table_length(ts, vs, length0, t)


def motion_function(scene: DynamicScene) -> ca.Function:
    """CasADi function ``t -> (L, L_t, L_tt, x_b, v_b, a_b)``.

    L (m), L_t (m/s), L_tt (m/s^2): the unstretched length and its derivatives;
    x_b (m), v_b (m/s), a_b (m/s^2): end_b's position (3-vectors) and derivatives.
    """
    t = ca.SX.sym("t")
    tm = scene.top_motion
    length = length_expr(tm, scene.length, t)
    dl = ca.jacobian(length, t)
    ddl = ca.jacobian(dl, t)
    pos = ca.DM(scene.top_position) + top_offset_expr(tm, t)
    vel = ca.jacobian(pos, t)
    acc = ca.jacobian(vel, t)
    return ca.Function("motion", [t], [length, dl, ddl, pos, vel, acc],
                       ["t"], ["L", "L_t", "L_tt", "x_b", "v_b", "a_b"])


def length_numeric(tm: TopMotion, length0: float, times: Sequence[float] | np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray]:
    """(L(t), L_t(t)) on a grid of times (s), as numpy arrays (m, m/s).

    Parameters
    ----------
    tm : TopMotion
        The scene's ``[top_motion]`` (its pay-out law, as in :func:`length_expr`).
    length0 : float
        Unstretched length at t = 0, m.
    times : sequence of float or numpy.ndarray
        Times, s, any shape (flattened); the outputs have one entry per time, in order.
    """
    t = ca.SX.sym("t")
    length = length_expr(tm, length0, t)
    f = ca.Function("L", [t], [length, ca.jacobian(length, t)])
    ts = np.asarray(times, dtype=float).reshape(1, -1)
    fm = f.map(ts.shape[1])
    a, b = fm(ts)
    return np.asarray(a).ravel(), np.asarray(b).ravel()
