"""The quintic smooth step, the one home of every fade-in and ramp of the package (the
scene's ``ramp_time``, :mod:`cable_ocp.scene.motion`; the seeded seas' ``fade_in``,
:mod:`cable_ocp.schedule.sea`; the identification's excitations,
:mod:`cable_ocp.heave.identify_cable`).

    s(x) = 10 x^3 - 15 x^4 + 6 x^5 = x^3 (10 - 15 x + 6 x^2),   x in [0, 1]

rises from 0 to 1 with zero first and second derivatives at both ends (so a motion faded
by it starts from rest without a jump in acceleration); s'(x) = 30 x^2 (1 - x)^2 and
its integral S(x) = x^4 (5/2 - 3 x + x^2) from 0 (S(1) = 1/2).

The functions take an x already clipped to [0, 1] and work on floats, numpy arrays and
CasADi expressions alike.
"""

from __future__ import annotations

from typing import Any

__all__ = ["smoothstep", "smoothstep_integral", "smoothstep_rate"]


def smoothstep(x: Any) -> Any:
    """s(x) = x^3 (10 - 15 x + 6 x^2) (-).

    Parameters
    ----------
    x : float, numpy.ndarray or casadi expression
        In [0, 1] (-).
    """
    return x**3 * (10.0 - 15.0 * x + 6.0 * x**2)


def smoothstep_rate(x: Any) -> Any:
    """ds/dx = 30 x^2 (1 - x)^2 (-).

    Parameters
    ----------
    x : float, numpy.ndarray or casadi expression
        In [0, 1] (-).
    """
    return 30.0 * x**2 * (1.0 - x) ** 2


def smoothstep_integral(x: Any) -> Any:
    """The integral of s from 0 to x, x^4 (5/2 - 3 x + x^2) (-).

    Parameters
    ----------
    x : float, numpy.ndarray or casadi expression
        In [0, 1] (-).
    """
    return x**4 * (2.5 - 3.0 * x + x**2)
