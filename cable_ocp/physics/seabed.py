"""Seabed plane and the grounded part of a cable lying on it (touchdown formulation).

The cable leaves an anchor on the seabed (end_a), lies on the plane for a grounded length
g, and lifts off at the touchdown point (TDP), where it is tangent to the seabed:
T(TDP) . n = 0 with n the plane's unit normal. On the seabed the cable carries no current
load (it lies in the boundary layer; docs/conventions.md "Seabed") and no lateral load resists
it, so the grounded part is straight, from the anchor towards the TDP along e = T/|T|.

Axial tension along the grounded part, with s' measured from the anchor (0 <= s' <= g):

    T(s') = max(T_td - k (g - s'), 0),    k = w e_z + mu w n_z,

where w e_z is the weight component along a sloping line and mu w n_z the axial friction
(mu times the normal reaction w n_z per length). Friction convention (quasi-static, as in
MoorPy's catenary and most mooring codes): the cable is taken to have been pulled taut from
the suspended side, so friction reduces the tension from the TDP towards the anchor; where
it would go negative the cable lies slack with zero tension. The lateral component of the
weight on a slope is assumed carried by the seabed (embedment), not modelled.

The TDP lies at r_a + e (g + (1/EA) integral of T ds') (stretch of the grounded part).

Every law here takes numbers: the plane is its slope (deg), the heading in which it rises
(deg from +x towards +y) and its height at x = y = 0 (m); the friction coefficient is a
number. :func:`normal`, :func:`height`, :func:`gap` and :func:`axial_gradient` are the same
laws for an object that carries those numbers as attributes (:class:`SeabedPlane`, e.g. the
scene's ``Seabed``).
"""

from __future__ import annotations

import math
from typing import Any, Protocol

import casadi as ca
import numpy as np


class SeabedPlane(Protocol):
    """What the conveniences read: the plane's numbers and the friction coefficient."""

    depth_offset: float
    friction: float
    slope_deg: float
    slope_heading_deg: float


def plane_normal(slope_deg: float, heading_deg: float) -> np.ndarray:
    """Unit normal of the seabed plane, pointing up into the water (-).

    Parameters
    ----------
    slope_deg : float
        Slope of the plane, deg.
    heading_deg : float
        Direction in which the plane rises, deg from +x towards +y.
    """
    a, h = math.radians(slope_deg), math.radians(heading_deg)
    return np.array([-math.sin(a) * math.cos(h), -math.sin(a) * math.sin(h), math.cos(a)])


def plane_height(x: Any, y: Any, slope_deg: float, heading_deg: float,
                 offset: float) -> Any:
    """Seabed height z at (x, y), m (floats, arrays or CasADi expressions).

    Parameters
    ----------
    x, y : float or array
        Horizontal position, m.
    slope_deg : float
        Slope of the plane, deg.
    heading_deg : float
        Direction in which the plane rises, deg.
    offset : float
        Height of the plane at x = y = 0, m.
    """
    t = math.tan(math.radians(slope_deg))
    h = math.radians(heading_deg)
    return offset + t * (x * math.cos(h) + y * math.sin(h))


def plane_gap(r: np.ndarray, slope_deg: float, heading_deg: float,
              offset: float) -> np.ndarray:
    """Signed distance of points (n, 3) above the seabed plane, m (negative = below).

    Parameters
    ----------
    r : ndarray, shape (n, 3) or (3,)
        Points, m.
    slope_deg : float
        Slope of the plane, deg.
    heading_deg : float
        Direction in which the plane rises, deg.
    offset : float
        Height of the plane at x = y = 0, m.
    """
    r = np.atleast_2d(r)
    z0 = plane_height(r[:, 0], r[:, 1], slope_deg, heading_deg, offset)
    return (r[:, 2] - z0) * plane_normal(slope_deg, heading_deg)[2]


def friction_gradient(w: float, e: Any, friction: float, normal_z: float) -> Any:
    """k = w e_z + mu w n_z: tension drop per metre from the TDP towards the anchor, N/m.

    Parameters
    ----------
    w : float
        Weight in water per length, N/m.
    e : array or casadi expression, shape (3,)
        Unit direction of the grounded line, anchor to TDP (-).
    friction : float
        Axial friction coefficient mu (-).
    normal_z : float
        Vertical component of the plane's unit normal (:func:`plane_normal`) (-).
    """
    return w * e[2] + friction * w * normal_z


def normal(seabed: SeabedPlane) -> np.ndarray:
    """:func:`plane_normal` of a seabed object."""
    return plane_normal(seabed.slope_deg, seabed.slope_heading_deg)


def height(seabed: SeabedPlane, x: Any, y: Any) -> Any:
    """:func:`plane_height` of a seabed object, m.

    Parameters
    ----------
    seabed : SeabedPlane
        The plane's numbers.
    x, y : float or array
        Horizontal position, m.
    """
    return plane_height(x, y, seabed.slope_deg, seabed.slope_heading_deg, seabed.depth_offset)


def gap(seabed: SeabedPlane, r: np.ndarray) -> np.ndarray:
    """:func:`plane_gap` of a seabed object, m.

    Parameters
    ----------
    seabed : SeabedPlane
        The plane's numbers.
    r : ndarray, shape (n, 3) or (3,)
        Points, m.
    """
    return plane_gap(r, seabed.slope_deg, seabed.slope_heading_deg, seabed.depth_offset)


def axial_gradient(seabed: SeabedPlane, w: float, e: Any) -> Any:
    """:func:`friction_gradient` of a seabed object, N/m.

    Parameters
    ----------
    seabed : SeabedPlane
        The plane's numbers and friction coefficient.
    w : float
        Weight in water per length, N/m.
    e : array or casadi expression, shape (3,)
        Unit direction of the grounded line, anchor to TDP (-).
    """
    return friction_gradient(w, e, seabed.friction, float(normal(seabed)[2]))


def grounded_tension_integral(t_td: Any, k: Any, g: Any) -> Any:
    """Integral of T over the grounded length (N m), with the slack floor at T = 0.

    Works on CasADi expressions and floats; k may be 0 (no friction, flat seabed).

    Parameters
    ----------
    t_td : float or casadi expression
        Tension at the touchdown point, N.
    k : float or casadi expression
        Tension drop per metre towards the anchor (:func:`friction_gradient`), N/m.
    g : float or casadi expression
        Grounded length, m.
    """
    if isinstance(k, (int, float)) and k <= 0:
        return t_td * g - 0.5 * k * g * g
    g_eff = ca.fmin(g, t_td / ca.fmax(k, 1e-300)) if not isinstance(k, (int, float)) else (
        min(g, t_td / k))
    if isinstance(k, (int, float)):
        return t_td * g_eff - 0.5 * k * g_eff * g_eff
    return ca.if_else(k > 0, t_td * g_eff - 0.5 * k * g_eff * g_eff, t_td * g - 0.5 * k * g * g)


def grounded_nodes(anchor: np.ndarray, e: np.ndarray, t_td: float, k: float, g: float,
                   ea: float, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Arc length (from the anchor), positions and tension vectors of n grounded nodes.

    Parameters
    ----------
    anchor : ndarray, shape (3,)
        Anchor position, m.
    e : ndarray, shape (3,)
        Unit direction of the grounded line, anchor to TDP (-).
    t_td : float
        Tension at the touchdown point, N.
    k : float
        Tension drop per metre towards the anchor, N/m.
    g : float
        Grounded (unstretched) length, m.
    ea : float
        EA, N (``inf``: inextensible).
    n : int
        Number of nodes.

    Returns
    -------
    tuple of ndarray
        s' (n,) in m, positions (n, 3) in m, tension vectors (n, 3) in N.
    """
    sp = np.linspace(0.0, g, n)
    tens = np.maximum(t_td - k * (g - sp), 0.0)
    if math.isfinite(ea):
        # stretched distance from the anchor: integral of (1 + T/EA) ds'
        seg = np.concatenate([[0.0], np.cumsum(0.5 * (tens[1:] + tens[:-1]) * np.diff(sp))])
        dist = sp + seg / ea
    else:
        dist = sp
    return sp, anchor + np.outer(dist, e), np.outer(tens, e)
