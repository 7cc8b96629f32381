"""The winch drive along a run: line tension at the drum, torque and power.

The law is :mod:`cable_ocp.physics.winch_drive` (``tau = R T + J u'' / R``, ``P = tau u' / R``);
here it is evaluated on a run's sub-step grid from the winch output's speed and acceleration and
the line tension at the top:

* the tension: on the design model ``T = T0 + (m / a) (x0 + u - delta - x)`` (``delta`` the
  passive compensator's compression, 0 without one; ``[unit] mass`` and ``static_tension``),
  on the cable plant the cable's top tension;
* the acceleration ``u''``: the second-order winch's ``w^2 (v - u) - 2 zeta w u'``; the
  first-order winch (6.1) ``u' = K (v - u)`` has ``u'' = -K u'`` between the samples and a
  jump of its speed, ``K dv``, at each change ``dv`` of the applied command (an impulse of
  torque ``J K dv / R`` that no finite torque delivers: it is not in the torque reported, and
  ``[winch] command_rate_max`` bounds it).

``[winch] drum_radius`` not given: no drive (None).
"""

from __future__ import annotations

import numpy as np

from cable_ocp.physics.winch_drive import drum_power, drum_torque
from cable_ocp.scene.heave import HeaveScene

__all__ = ["design_tension", "drive_series", "line_acceleration"]


def line_acceleration(scene: HeaveScene, u: np.ndarray, u_dot: np.ndarray, v: np.ndarray
                      ) -> np.ndarray:
    """The winch output's acceleration ``u''`` (m/s^2) on a run's grid (module docstring).

    Parameters
    ----------
    scene : HeaveScene
        Its ``[winch]`` model.
    u, u_dot : numpy.ndarray
        Winch output (m) and speed (m/s, the right limit after a command change).
    v : numpy.ndarray
        The applied (delayed) command, m.
    """
    w = scene.winch
    if w.model == "first_order":
        return -w.gain * np.asarray(u_dot, dtype=float)
    wn, z = w.natural_frequency, w.damping_ratio
    return wn**2 * (np.asarray(v) - np.asarray(u)) - 2.0 * z * wn * np.asarray(u_dot)


def design_tension(scene: HeaveScene, x: np.ndarray, x0: np.ndarray, u: np.ndarray,
                   delta: np.ndarray | None = None) -> np.ndarray | None:
    """The line tension of the design model, ``T0 + (m / a) (x0 + u - delta - x)`` (N), or
    None when ``[unit] mass`` or ``static_tension`` is not given.

    Parameters
    ----------
    scene : HeaveScene
        ``[unit] a, mass, static_tension``.
    x, x0, u : numpy.ndarray
        Unit heave, boom-tip heave and winch output, m.
    delta : numpy.ndarray, optional
        The passive compensator's compression, m (None: no compensator).
    """
    un = scene.unit
    if not (un.mass > 0 and un.static_tension > 0):
        return None
    top = np.asarray(x0) + np.asarray(u) - (0.0 if delta is None else np.asarray(delta))
    return un.static_tension + un.mass / un.a * (top - np.asarray(x))


def drive_series(scene: HeaveScene, tension: np.ndarray | None, u: np.ndarray,
                 u_dot: np.ndarray, v: np.ndarray) -> tuple[np.ndarray | None, np.ndarray | None]:
    """``(torque, power)`` on a run's grid (N m, W), or ``(None, None)`` without
    ``[winch] drum_radius`` or a tension.

    Parameters
    ----------
    scene : HeaveScene
        ``[winch] drum_radius, drum_inertia`` and the winch model.
    tension : numpy.ndarray or None
        The line tension at the drum, N.
    u, u_dot, v : numpy.ndarray
        Winch output (m), speed (m/s) and the applied command (m).
    """
    w = scene.winch
    if w.drum_radius is None or tension is None:
        return None, None
    acc = line_acceleration(scene, u, u_dot, v)
    torque = drum_torque(np.asarray(tension, dtype=float), acc, w.drum_radius, w.drum_inertia)
    return torque, drum_power(torque, np.asarray(u_dot, dtype=float), w.drum_radius)
