"""The winch drive: the torque and power of the drum that pays the line in and out.

A drum of radius ``R`` (m) and inertia ``J`` (kg m^2, drum, gear and motor referred to the drum
shaft) hauls the line in at the speed ``u'`` (m/s, ``u > 0`` hauls in, as the heave model's
winch output ``u``). Its angular speed is ``omega = u' / R`` (rad/s) and its angular
acceleration ``u'' / R``; the line pulls on it with the tension ``T`` (N), so the torque the
motor must deliver and its mechanical power are

    tau = R T + J u'' / R,        P = tau omega = tau u' / R.

``P > 0``: the motor drives (hauls in against the tension); ``P < 0``: the line drives the
motor (paying out, regenerative braking). Huang (1992), 004_7da4a1ee8042db40.txt, section 6.5,
asks for "feasibility studies ... in terms of the magnitudes of the speed, acceleration and
torque of the winch"; the thesis' winch (6.1) is a kinematic model and gives no drive
equations: these are the rigid drum's. Every function works on numbers, numpy arrays and
CasADi symbols.
"""

from __future__ import annotations

from typing import Any

__all__ = ["drum_power", "drum_speed", "drum_torque", "linearised_power"]


def drum_speed(line_speed: Any, drum_radius: float) -> Any:
    """The drum's angular speed ``u' / R``, rad/s.

    Parameters
    ----------
    line_speed : float or array or casadi symbol
        ``u'``: the line's haul-in speed, m/s.
    drum_radius : float
        ``R``, m.
    """
    return line_speed / drum_radius


def drum_torque(tension: Any, line_accel: Any, drum_radius: float,
                drum_inertia: float) -> Any:
    """The motor torque ``R T + J u'' / R``, N m.

    Parameters
    ----------
    tension : float or array or casadi symbol
        ``T``: the line tension at the drum, N.
    line_accel : float or array or casadi symbol
        ``u''``: the line's haul-in acceleration, m/s^2.
    drum_radius : float
        ``R``, m.
    drum_inertia : float
        ``J``: the inertia referred to the drum shaft, kg m^2.
    """
    return drum_radius * tension + drum_inertia * line_accel / drum_radius


def drum_power(torque: Any, line_speed: Any, drum_radius: float) -> Any:
    """The motor's mechanical power ``tau u' / R``, W (> 0 driving, < 0 regenerating).

    Parameters
    ----------
    torque : float or array or casadi symbol
        ``tau``: the motor torque (:func:`drum_torque`), N m.
    line_speed : float or array or casadi symbol
        ``u'``, m/s.
    drum_radius : float
        ``R``, m.
    """
    return torque * drum_speed(line_speed, drum_radius)


def linearised_power(static_tension: float, line_speed: Any) -> Any:
    """The power linearised about the static state (tension ``T0``, drum at rest): ``T0 u'``, W.

    ``P = tau omega`` is bilinear; about ``tau0 = R T0``, ``omega0 = 0`` its first-order part is
    ``tau0 omega = T0 u'`` (the dropped term, ``(tau - tau0) omega``, is of second order in the
    motion), so ``|P| <= P_max`` becomes the speed limit ``|u'| <= P_max / T0``.

    Parameters
    ----------
    static_tension : float
        ``T0``: the static line tension at the drum, N.
    line_speed : float or array or casadi symbol
        ``u'``, m/s.
    """
    return static_tension * line_speed
