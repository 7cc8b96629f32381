"""The steady loads of a rigid body and their derivatives: weight, buoyancy, the
waterplane's restoring and an external load (docs/systems.md, "Bodies").

At a pose (reference point x, rotation R; :mod:`cable_ocp.numerics.rotation`) the load
(force F, N; moment M about x, N m) is

* weight -m g e_z at the centre of gravity x + R r_G;
* buoyancy rho g V e_z at the centre of buoyancy x + R r_B (or at the metacentre
  x + R r_M where one is given: MoorPy's ``rM``, whose height carries the waterplane's
  second moments, z_M = z_B + I / V);
* the waterplane: -rho g A_wp (z - z_s) e_z, z_s the free surface (``volume`` is the
  displaced volume with the reference point on the surface, as in MoorPy's Body), and,
  with ``waterplane_moments`` (Ixx, Iyy), the moment rho g (Ixx n_y, -Iyy n_x, 0) of the
  tilt n = R e_z (the linear restoring of the waterplane, about the fixed x and y axes);
* or, with a ``hydrostatic_matrix`` C, the net vertical force (rho g V - m g) e_z at x and
  -C (x - x0, phi), phi the rotation vector of R R0^T (R0, x0: the file's pose);
* the external force at x and moment.

:func:`load_jacobian` gives d[F; M]/d[dx; dtheta], dtheta small rotations about the fixed
axes at the pose, exactly. At a level pose its negative is the textbook matrix:
C33 = rho g A_wp, C44 = rho g (Ixx + V z_B) - m g z_G, C55 = rho g (Iyy + V z_B) - m g z_G.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from cable_ocp.numerics.rotation import rotation_matrix, skew

__all__ = ["body_load", "load_jacobian", "moment_jacobian_of_point_force"]

_EZ = np.array([0.0, 0.0, 1.0])


def _point_loads(body: Any, r: np.ndarray, rho: float, g: float
                 ) -> list[tuple[np.ndarray, np.ndarray]]:
    """(force, arm) of the loads at points of the body: weight and buoyancy."""
    if body.hydrostatic_matrix is not None:
        return []
    at = body.metacenter if body.metacenter is not None else body.center_of_buoyancy
    return [(-body.mass * g * _EZ, r @ np.asarray(body.center_of_gravity, float)),
            (rho * g * body.volume * _EZ, r @ np.asarray(at, float))]


def _log_rotation(r: np.ndarray) -> np.ndarray:
    """The rotation vector phi of R (exp([phi]x) = R), |phi| < pi."""
    c = np.clip((np.trace(r) - 1.0) / 2.0, -1.0, 1.0)
    a = float(np.arccos(c))
    w = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]]) / 2.0
    return w if a < 1e-8 else w * a / np.sin(a)


def _inverse_left_jacobian(phi: np.ndarray) -> np.ndarray:
    """d phi / d theta for R' = exp([theta]x) R: the inverse left Jacobian of SO(3)."""
    a = float(np.linalg.norm(phi))
    k = skew(phi)
    if a < 1e-6:
        return np.eye(3) - 0.5 * k + k @ k / 12.0
    return np.eye(3) - 0.5 * k + (1.0 / a**2 - (1.0 + np.cos(a)) / (2.0 * a * np.sin(a))) * k @ k


def body_load(body: Any, x: np.ndarray, r: np.ndarray, rho: float, g: float,
              surface: float) -> np.ndarray:
    """The body's own steady load [F; M] (N, N m about x) at a pose.

    Parameters
    ----------
    body : SystemBody
        The body (:class:`cable_ocp.scene.system.SystemBody`).
    x : ndarray
        Reference point, m.
    r : ndarray
        Rotation matrix.
    rho, g : float
        Water density (kg/m^3) and gravity (m/s^2).
    surface : float
        z of the free surface, m.
    """
    f = np.asarray(body.force, float).copy()
    m = np.asarray(body.moment, float).copy()
    for force, arm in _point_loads(body, r, rho, g):
        f += force
        m += np.cross(arm, force)
    if body.hydrostatic_matrix is not None:
        f[2] += (rho * body.volume - body.mass) * g
        x0 = np.asarray(body.position, float)
        r0 = rotation_matrix(*body.rotation)
        dq = np.concatenate([np.asarray(x, float) - x0, _log_rotation(r @ r0.T)])
        out = np.concatenate([f, m]) - np.asarray(body.hydrostatic_matrix, float) @ dq
        return out
    f[2] -= rho * g * body.waterplane_area * (x[2] - surface)
    ixx, iyy = body.waterplane_moments
    n = r @ _EZ
    m += rho * g * np.array([ixx * n[1], -iyy * n[0], 0.0])
    return np.concatenate([f, m])


def moment_jacobian_of_point_force(force: np.ndarray, arm: np.ndarray) -> np.ndarray:
    """d(arm x F)/d(theta) for a constant force F at a point turning with the body
    (arm = R r): [F]x [arm]x (N m per rad).

    Parameters
    ----------
    force : ndarray
        The force, N.
    arm : ndarray
        From the reference point to the point, m.
    """
    return skew(force) @ skew(arm)


def load_jacobian(body: Any, x: np.ndarray, r: np.ndarray, rho: float, g: float) -> np.ndarray:
    """d[F; M]/d[dx; dtheta] of :func:`body_load` (6x6; dtheta small rotations about the
    fixed axes at the pose; the negative is the hydrostatic stiffness).

    Parameters
    ----------
    body : SystemBody
        The body.
    x : ndarray
        Reference point, m.
    r : ndarray
        Rotation matrix.
    rho, g : float
        Water density (kg/m^3) and gravity (m/s^2).
    """
    jac = np.zeros((6, 6))
    if body.hydrostatic_matrix is not None:
        r0 = rotation_matrix(*body.rotation)
        c = np.asarray(body.hydrostatic_matrix, float)
        jac[:, :3] = -c[:, :3]
        jac[:, 3:] = -c[:, 3:] @ _inverse_left_jacobian(_log_rotation(r @ r0.T))
        return jac
    for force, arm in _point_loads(body, r, rho, g):
        jac[3:, 3:] += moment_jacobian_of_point_force(force, arm)
    jac[2, 2] -= rho * g * body.waterplane_area
    ixx, iyy = body.waterplane_moments
    dn = -skew(r @ _EZ)  # dn/dtheta
    jac[3, 3:] += rho * g * ixx * dn[1]
    jac[4, 3:] -= rho * g * iyy * dn[0]
    return jac
