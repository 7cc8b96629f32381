"""Bending stiffness of a discretised cable: the hinge law between adjacent elements, once.

Huang (1992), 12.4.6, eqs (12.29)-(12.31), adds the bending moment M = EI kappa to the
cable equations (a beam-cable: the shear dM/ds = tau (1 + e) turns the internal force out
of the tangent; for a taut, nearly straight line mu y_tt - T y_ss + EI y_ssss = F_y,
(12.31), whence the dispersion omega = k sqrt(T / mu + EI k^2 / mu)); Bielański (003,
eqs (4)-(7)) treats the towed object as such a beam. In a lumped-mass chain the curvature
lives at the hinges, the interior nodes: with the element vectors d_j = r_{j+1} - r_j
(m), unstretched lengths h_j (m) and the stretched tangents u_j = d_j / h_j (-), the
hinge at node j + 1 between elements j and j + 1 carries the bending energy

    E_j = EI / (2 hbar_j) |u_{j+1} - u_j|^2,      hbar_j = (h_j + h_{j+1}) / 2     (J)

Its link to the turning angle phi_j between the elements (the angle between d_j and
d_{j+1}): at equal strains e, |u_{j+1} - u_j| = 2 (1 + e) sin(phi_j / 2), so
E_j = EI (1 + e)^2 (1 - cos phi_j) / hbar_j ~ EI phi_j^2 / (2 hbar_j) = (EI kappa^2 / 2)
hbar_j with the curvature kappa = phi_j / hbar_j: the discrete form of the beam energy
integral of EI kappa^2 / 2 ds, and the moment is M_j = EI |u_{j+1} - u_j| / hbar_j ~
EI phi_j / hbar_j (N m). Against Huang's M = EI kappa (kappa the curvature of the
stretched line, his EI (x_s y_ss - y_s x_ss) / (1 + e)^3) this is EI kappa (1 + e)^3: the
same to O(e), the strain of a cable (1e-5 .. 1e-2). The energy is quadratic in the node
positions: the forces are linear in them, the implicit midpoint rule conserves it exactly,
and the Jacobian is constant. Its coupling to the stretch (it also sees
(e_{j+1} - e_j)^2) is of relative order EI / (EA h^2), negligible for a cable. On a
straight line the linearised hinge forces are EI / h^4 times the fourth difference of the
transverse displacements: the beam term EI d^4w/ds^4 to O(h^2).

Ends: a pinned or free end carries no hinge (M = 0 there). A clamped end (the end tangent
held along t_c) is a hinge of half an element between the clamp and the end element:

    E_c = EI / h |(I - t_c t_c^T) u|^2     (u the end element's tangent d / h)

the mirror-image (ghost node) condition of a centred finite difference, second order
(a one-sided hinge EI / (2h) |u - t_c|^2 would be first order).

These functions take numbers (numpy arrays) or CasADi expressions; columns are elements or
hinges (rows x, z in 2D or x, y, z in 3D) and carry no model object.
"""

from __future__ import annotations

from typing import Any

import casadi as ca
import numpy as np

__all__ = [
    "clamp_energy",
    "clamp_force",
    "hinge_energy",
    "hinge_forces",
    "hinge_moment",
    "turning_angle",
]


def _is_ca(*xs: Any) -> bool:
    return any(isinstance(x, (ca.SX, ca.MX, ca.DM)) for x in xs)


def _sum_rows(x: Any) -> Any:
    return ca.sum1(x) if _is_ca(x) else np.sum(x, axis=0, keepdims=True)


def _row(x: Any, like: Any) -> Any:
    """A number or row (1 x K) as CasADi when ``like`` is CasADi, else numpy."""
    if _is_ca(like):
        return x if _is_ca(x) else ca.DM(np.asarray(x, dtype=float).reshape(1, -1))
    return np.asarray(x, dtype=float).reshape(1, -1) if np.ndim(x) else x


def _spread(x: Any, like: Any) -> Any:
    """A row broadcast to the rows of ``like`` (CasADi needs it explicitly)."""
    x = _row(x, like)
    if _is_ca(like) and x.shape[0] == 1 and like.shape[0] > 1:
        return ca.repmat(x, like.shape[0], 1)
    return x


def _hinge_jump(d_prev: Any, d_next: Any, h_prev: Any, h_next: Any) -> Any:
    """u_{j+1} - u_j of the hinges (columns), -."""
    return d_next / _spread(h_next, d_next) - d_prev / _spread(h_prev, d_prev)


def hinge_energy(d_prev: Any, d_next: Any, ei: Any, h_prev: Any, h_next: Any) -> Any:
    """Bending energy of each hinge, J (a row: one column per hinge).

    Parameters
    ----------
    d_prev, d_next : array or casadi expression (dim x K)
        The element vectors before and after each hinge, m.
    ei : float or row (1 x K)
        Bending stiffness EI at the hinge, N m^2.
    h_prev, h_next : float or row (1 x K)
        The two elements' unstretched lengths, m.
    """
    jump = _hinge_jump(d_prev, d_next, h_prev, h_next)
    coef = _row(ei, jump) / (_row(h_prev, jump) + _row(h_next, jump))
    return coef * _sum_rows(jump * jump)


def hinge_forces(d_prev: Any, d_next: Any, ei: Any, h_prev: Any, h_next: Any
                 ) -> tuple[Any, Any, Any]:
    """Forces of each hinge on its three nodes, N: ``(f_a, f_b, f_c)`` (dim x K each) on
    the node before, at and after the hinge (-dE/dr of :func:`hinge_energy`; they sum to
    zero and exert no net moment).

    Parameters
    ----------
    d_prev, d_next : array or casadi expression (dim x K)
        The element vectors before and after each hinge, m.
    ei : float or row (1 x K)
        Bending stiffness EI at the hinge, N m^2.
    h_prev, h_next : float or row (1 x K)
        The two elements' unstretched lengths, m.
    """
    jump = _hinge_jump(d_prev, d_next, h_prev, h_next)
    b = _spread(2.0 * _row(ei, jump) / (_row(h_prev, jump) + _row(h_next, jump)), jump) * jump
    f_a = -b / _spread(h_prev, jump)
    f_c = -b / _spread(h_next, jump)
    return f_a, -(f_a + f_c), f_c


def hinge_moment(d_prev: Any, d_next: Any, ei: Any, h_prev: Any, h_next: Any) -> Any:
    """Bending moment at each hinge, M = EI |u_{j+1} - u_j| / hbar ~ EI phi / hbar, N m
    (a row, >= 0).

    Parameters
    ----------
    d_prev, d_next : array or casadi expression (dim x K)
        The element vectors before and after each hinge, m.
    ei : float or row (1 x K)
        Bending stiffness EI, N m^2.
    h_prev, h_next : float or row (1 x K)
        Unstretched element lengths, m.
    """
    jump = _hinge_jump(d_prev, d_next, h_prev, h_next)
    norm = ca.sqrt(_sum_rows(jump * jump)) if _is_ca(jump) else np.sqrt(_sum_rows(jump * jump))
    return 2.0 * _row(ei, jump) / (_row(h_prev, jump) + _row(h_next, jump)) * norm


def turning_angle(d_prev: Any, d_next: Any) -> Any:
    """Turning angle phi between adjacent elements, rad (a row, in [0, pi]).

    Parameters
    ----------
    d_prev, d_next : array or casadi expression (dim x K)
        The element vectors before and after each hinge, m.
    """
    if _is_ca(d_prev, d_next):
        c = ca.sum1(d_prev * d_next)
        s = ca.sqrt(ca.sum1(d_prev * d_prev) * ca.sum1(d_next * d_next) - c * c + 0.0)
        return ca.atan2(s, c)
    c = _sum_rows(d_prev * d_next)
    s2 = _sum_rows(d_prev * d_prev) * _sum_rows(d_next * d_next) - c * c
    return np.arctan2(np.sqrt(np.maximum(s2, 0.0)), c)


def _normal_part(d: Any, t_c: Any) -> Any:
    t_c = ca.DM(np.asarray(t_c, dtype=float).reshape(-1, 1)) if _is_ca(d) and not _is_ca(
        t_c) else (t_c if _is_ca(d) else np.asarray(t_c, dtype=float).reshape(-1, 1))
    along = _sum_rows(d * t_c)
    return d - along * t_c


def clamp_energy(d: Any, t_c: Any, ei: Any, h: Any) -> Any:
    """Bending energy of a clamped end, EI / h |(I - t_c t_c^T) d / h|^2, J.

    Parameters
    ----------
    d : array or casadi expression (dim x 1)
        The end element's vector, m (any sign: the energy is even in it).
    t_c : array (dim x 1)
        The clamp's unit direction, -.
    ei : float
        Bending stiffness EI, N m^2.
    h : float or casadi expression
        The end element's unstretched length, m.
    """
    dn = _normal_part(d, t_c)
    return ei / h**3 * _sum_rows(dn * dn)


def clamp_force(d: Any, t_c: Any, ei: Any, h: Any) -> Any:
    """-dE_c/dd of :func:`clamp_energy`, N (dim x 1): the force on the element's far node
    (the end element's vector d = r_far - r_end; the clamped end node carries its
    negative).

    Parameters
    ----------
    d : array or casadi expression (dim x 1)
        The end element's vector, m.
    t_c : array (dim x 1)
        The clamp's unit direction, -.
    ei : float
        Bending stiffness EI, N m^2.
    h : float or casadi expression
        The end element's unstretched length, m.
    """
    return -2.0 * ei / h**3 * _normal_part(d, t_c)
