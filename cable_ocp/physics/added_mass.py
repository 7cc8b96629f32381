"""Inertia and weight in water: added mass of a line element and of a body, weight, buoyancy.

Line element (Huang (1992) eq. (5.2), the matrix A of the lumped-mass model with
e = rho k l sigma): accelerating across the element entrains C_a rho pi d^2 / 4 per length,
along it C_at rho pi d^2 / 4 (0 for a smooth cable), so its added mass per length is the
direction-dependent

    A = m_an (I - t t^T) + m_at t t^T,   m_an = C_a rho pi d^2 / 4,  m_at = C_at rho pi d^2/4,

with t the unit tangent (:func:`line_added_mass`, the planar rows
:func:`line_added_mass_2d`); each end node of a lumped element carries half of it. A body
(the subsea unit, Huang (1992) (4.11)-(4.12), (5.6)) has added mass per axis:
:func:`virtual_mass`. Weight in water: (m - rho V) g (:func:`weight_in_water`), the
buoyancy rho V g (:func:`buoyancy`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import casadi as ca
import numpy as np


def added_mass_per_length(coefficient: float, rho: float, diameter: float) -> float:
    """C rho pi d^2 / 4, kg/m: a line's added mass per unstretched length.

    Parameters
    ----------
    coefficient : float
        Added-mass coefficient C_a (normal) or C_at (tangential) (-).
    rho : float
        Water density, kg/m^3.
    diameter : float
        Hydrodynamic diameter, m.
    """
    return coefficient * rho * math.pi * diameter**2 / 4.0


def line_added_mass(d: Any, normal: Any, tangential: Any) -> Any:
    """m_an (I - t t^T) + m_at t t^T with t = d / |d| (CasADi, 3 x 3), as ``normal``.

    Parameters
    ----------
    d : casadi expression, shape (3, 1)
        Element chord (any length; only its direction is used), m.
    normal : float or casadi expression
        Normal added mass (per length, kg/m, or of the element, kg).
    tangential : float or casadi expression
        Tangential added mass, same unit.
    """
    return projected_added_mass(ca.mtimes(d, d.T) / ca.dot(d, d), normal, tangential)


def projected_added_mass(tt: Any, normal: Any, tangential: Any) -> Any:
    """The added-mass law (004 eq. (5.2)) on a given projector ``tt = t t^T``:
    m_an (I - t t^T) + m_at t t^T (CasADi, 3 x 3).

    :func:`line_added_mass` builds ``tt`` from a chord; a stepping kernel that has ``t t^T``
    from its unit tangent already (for the drag's Jacobian) passes it here (the two
    projectors differ by rounding).

    Parameters
    ----------
    tt : casadi expression, shape (3, 3)
        t t^T of the element's unit tangent t (-).
    normal : float or casadi expression
        Normal added mass (per length, kg/m, or of the element, kg).
    tangential : float or casadi expression
        Tangential added mass, same unit.
    """
    return normal * (ca.SX.eye(3) - tt) + tangential * tt


def line_added_mass_np(t: np.ndarray, normal: float, tangential: float) -> np.ndarray:
    """:func:`line_added_mass` in numpy for unit tangents ``t`` (..., 3): (..., 3, 3).

    Parameters
    ----------
    t : ndarray, shape (..., 3)
        Unit tangents (-).
    normal : float
        Normal added mass, kg/m or kg.
    tangential : float
        Tangential added mass, same unit.
    """
    t = np.asarray(t, dtype=float)
    tt = t[..., :, None] * t[..., None, :]
    return normal * (np.eye(3) - tt) + tangential * tt


def line_added_mass_2d(dd: Any, normal: Any, tangential: Any, scale: Any = 1.0
                       ) -> tuple[Any, Any, Any]:
    """(A_xx, A_xz, A_zz) of :func:`line_added_mass` in the x-z plane, per element column.

    For the chords of K elements as the columns of a 2 x K matrix (the planar model): with
    t_ij = d_i d_j / |d|^2, A_xx = m_an (1 - t_xx) + m_at t_xx, A_xz = (m_at - m_an) t_xz,
    A_zz likewise; each 1 x K, times ``scale``.

    Parameters
    ----------
    dd : casadi SX, shape (2, K)
        Chords (x, z rows), m (any common length).
    normal : float
        Normal added mass per length, kg/m.
    tangential : float
        Tangential added mass per length, kg/m.
    scale : float or casadi expression
        Multiplier, e.g. the share of an element length at a node, m (then kg).
    """
    l2 = ca.sum1(dd * dd)
    txx, txz, tzz = dd[0, :] ** 2 / l2, dd[0, :] * dd[1, :] / l2, dd[1, :] ** 2 / l2
    return (scale * (normal * (1.0 - txx) + tangential * txx),
            scale * (tangential - normal) * txz,
            scale * (normal * (1.0 - tzz) + tangential * tzz))


def virtual_mass(mass: float, added_mass: Sequence[float]) -> tuple[float, ...]:
    """Mass plus added mass per axis, kg.

    Parameters
    ----------
    mass : float
        Mass in air, kg.
    added_mass : sequence of float
        Added mass per axis, kg.
    """
    return tuple(mass + a for a in added_mass)


def buoyancy(volume: float, rho: float, gravity: float) -> float:
    """rho V g, N.

    Parameters
    ----------
    volume : float
        Displaced volume, m^3.
    rho : float
        Water density, kg/m^3.
    gravity : float
        g, m/s^2.
    """
    return rho * volume * gravity


def weight_in_water(mass: float, volume: float, rho: float, gravity: float) -> float:
    """(m - rho V) g, N (negative = buoyant).

    Parameters
    ----------
    mass : float
        Mass in air, kg.
    volume : float
        Displaced volume, m^3.
    rho : float
        Water density, kg/m^3.
    gravity : float
        g, m/s^2.
    """
    return (mass - rho * volume) * gravity
