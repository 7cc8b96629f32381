"""Rotations of rigid bodies: the pose convention of the mooring systems.

R = Rz(yaw) Ry(pitch) Rx(roll) (MoorPy's ``rotationMatrix`` and MoorDyn's order;
CONVENTIONS "Mooring systems"). Small rotations theta are about the fixed axes at a pose:
R' = exp([theta]x) R. The map from Euler-angle rates to the rotation vector is
:func:`euler_rate_matrix`.
"""

from __future__ import annotations

import numpy as np

__all__ = ["euler_angles", "euler_rate_derivatives", "euler_rate_matrix", "rotate_small",
           "rotation_matrix", "skew"]


def skew(v: np.ndarray) -> np.ndarray:
    """The cross-product matrix [v]x, with [v]x u = v x u."""
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def rotation_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """R = Rz(yaw) Ry(pitch) Rx(roll), angles in rad.

    Parameters
    ----------
    roll, pitch, yaw : float
        rad.
    """
    cr, sr, cp, sp, cy, sy = (np.cos(roll), np.sin(roll), np.cos(pitch), np.sin(pitch),
                              np.cos(yaw), np.sin(yaw))
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def euler_angles(r: np.ndarray) -> tuple[float, float, float]:
    """(roll, pitch, yaw), rad, of R = Rz(yaw) Ry(pitch) Rx(roll) (pitch in [-90, 90] deg)."""
    pitch = float(np.arcsin(np.clip(-r[2, 0], -1.0, 1.0)))
    return float(np.arctan2(r[2, 1], r[2, 2])), pitch, float(np.arctan2(r[1, 0], r[0, 0]))


def rotate_small(theta: np.ndarray, r: np.ndarray) -> np.ndarray:
    """exp([theta]x) R (Rodrigues' formula): R turned by the rotation vector theta (rad)
    about the fixed axes.

    Parameters
    ----------
    theta : ndarray
        Rotation vector, rad.
    r : ndarray
        Rotation matrix.
    """
    a = float(np.linalg.norm(theta))
    if a < 1e-300:
        return r.copy()
    k = skew(np.asarray(theta) / a)
    return (np.eye(3) + np.sin(a) * k + (1.0 - np.cos(a)) * (k @ k)) @ r


def euler_rate_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """E with d(theta) = E d(roll, pitch, yaw): the columns are the fixed-frame axes of the
    three rotations, (Rz Ry e_x, Rz e_y, e_z). ``roll`` enters only through the argument
    list (E does not depend on it).

    Parameters
    ----------
    roll, pitch, yaw : float
        rad.
    """
    cp, sp, cy, sy = np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    return np.array([[cy * cp, -sy, 0.0], [sy * cp, cy, 0.0], [-sp, 0.0, 1.0]])


def euler_rate_derivatives(pitch: float, yaw: float) -> np.ndarray:
    """dE/d(roll, pitch, yaw): an array D[k] = dE/d(angle k), (3, 3, 3).

    Parameters
    ----------
    pitch, yaw : float
        rad.
    """
    cp, sp, cy, sy = np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    d = np.zeros((3, 3, 3))
    d[1] = [[-cy * sp, 0.0, 0.0], [-sy * sp, 0.0, 0.0], [-cp, 0.0, 0.0]]
    d[2] = [[-sy * cp, -cy, 0.0], [cy * cp, -sy, 0.0], [0.0, 0.0, 0.0]]
    return d
