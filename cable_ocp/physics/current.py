"""Current velocity as a function of height z (CasADi expression).

A profile is interpolated linearly in the horizontal velocity components between its
knots and held constant beyond the first and last knot (docs/conventions.md, "Frame and scene
files"): a current that reverses with depth passes through zero, not through a cross-flow.
"""

from __future__ import annotations

from typing import Any

import casadi as ca

from cable_ocp.scene import Current


def _piecewise_linear(z: Any, knots: tuple[float, ...], values: tuple[float, ...]) -> Any:
    """Continuous piecewise-linear interpolant, constant outside [knots[0], knots[-1]]."""
    out = values[0]
    for k in range(len(knots) - 1):
        slope = (values[k + 1] - values[k]) / (knots[k + 1] - knots[k])
        if slope != 0.0:
            seg = ca.fmin(ca.fmax(z - knots[k], 0.0), knots[k + 1] - knots[k])
            out = out + slope * seg
    return out


def current_velocity(current: Current, z: Any, scale: Any = 1.0) -> Any:
    """Current velocity vector at height ``z``, m/s.

    Parameters
    ----------
    current : Current
        The scene's current.
    z : casadi expression
        Height above the seabed, m.
    scale : casadi expression or float
        Multiplier on the whole current (a homotopy parameter; 1 = as specified).

    Returns
    -------
    casadi expression, shape (3, 1)
        (u_x, u_y, 0) in m/s.
    """
    if current.uniform:
        ux, uy = current.ux[0], current.uy[0]
    else:
        ux = _piecewise_linear(z, current.z, current.ux)
        uy = _piecewise_linear(z, current.z, current.uy)
    return scale * ca.vertcat(ux, uy, 0)
