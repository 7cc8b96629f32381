"""The current profile: velocity at height z from its knots (CasADi and numpy forms).

A profile is given by knot heights z_0 < ... < z_{m-1} (m) and the horizontal velocity
components ux, uy (m/s) at the knots. It is interpolated linearly in the components between
the knots and held constant beyond the first and last knot (docs/conventions.md, "Frame and
scene files"): a current that reverses with depth passes through zero, not through a
cross-flow. One knot (or equal components at every knot) is a uniform current.

Forms (every model, plant and baseline calls one of them):

* :func:`profile_velocity`: CasADi, (u_x, u_y, 0) with a homotopy scale (statics, planar
  and lumped models);
* :func:`profile_velocity_np`: numpy (``np.interp``), any shape of z (baselines, the switch
  functions of the statics mesh, the dynamic scene's unit load), and its bare interpolation
  :func:`profile_components_np` (an inner loop);
* :func:`profile_knots`: the heights where the velocity has a kink (a knot where the slope
  of a component changes), which a mesh should place a node on.

The two forms agree to rounding (the CasADi form sums clamped segments, ``np.interp``
evaluates the bracketing segment). :func:`current_velocity` is a convenience for an
object with the attributes ``z``, ``ux``, ``uy`` (the scene's ``Current``).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol

import casadi as ca
import numpy as np


class Profile(Protocol):
    """What :func:`current_velocity` reads: knot heights and components at the knots."""

    z: tuple[float, ...]
    ux: tuple[float, ...]
    uy: tuple[float, ...]


def is_uniform(knots: Sequence[float], ux: Sequence[float], uy: Sequence[float]) -> bool:
    """True when the velocity does not depend on z (one knot or equal components).

    Parameters
    ----------
    knots : sequence of float
        Knot heights, m.
    ux, uy : sequence of float
        Components at the knots, m/s.
    """
    return len(knots) == 1 or (len(set(ux)) == 1 and len(set(uy)) == 1)


def _piecewise_linear(z: Any, knots: Sequence[float], values: Sequence[float]) -> Any:
    """Continuous piecewise-linear interpolant, constant outside [knots[0], knots[-1]]."""
    out = values[0]
    for k in range(len(knots) - 1):
        slope = (values[k + 1] - values[k]) / (knots[k + 1] - knots[k])
        if slope != 0.0:
            seg = ca.fmin(ca.fmax(z - knots[k], 0.0), knots[k + 1] - knots[k])
            out = out + slope * seg
    return out


def profile_velocity(z: Any, knots: Sequence[float], ux: Sequence[float],
                     uy: Sequence[float], scale: Any = 1.0) -> Any:
    """Current velocity vector at height ``z``, m/s (CasADi).

    Parameters
    ----------
    z : casadi expression
        Height, m (the scene's frame: seabed at z = 0 unless offset).
    knots : sequence of float
        Knot heights, m, increasing.
    ux, uy : sequence of float
        Velocity components at the knots, m/s.
    scale : casadi expression or float
        Multiplier on the whole current (a homotopy parameter; 1 = as specified).

    Returns
    -------
    casadi expression, shape (3, 1)
        (u_x, u_y, 0) in m/s.
    """
    if is_uniform(knots, ux, uy):
        vx, vy = ux[0], uy[0]
    else:
        vx = _piecewise_linear(z, knots, ux)
        vy = _piecewise_linear(z, knots, uy)
    return scale * ca.vertcat(vx, vy, 0)


def profile_velocity_np(z: Any, knots: Sequence[float], ux: Sequence[float],
                        uy: Sequence[float]) -> np.ndarray:
    """Current velocity at heights ``z`` (numpy), m/s, shape ``z.shape + (3,)``.

    Parameters
    ----------
    z : float or array
        Heights, m.
    knots : sequence of float
        Knot heights, m, increasing.
    ux, uy : sequence of float
        Velocity components at the knots, m/s.
    """
    zz = np.asarray(z, dtype=float)
    out = np.zeros((*zz.shape, 3))
    if is_uniform(knots, ux, uy):
        out[..., 0], out[..., 1] = ux[0], uy[0]
    else:
        out[..., 0], out[..., 1] = profile_components_np(zz, knots, ux, uy)
    return out


def profile_components_np(z: Any, knots: Sequence[float], ux: Sequence[float],
                          uy: Sequence[float]) -> tuple[Any, Any]:
    """(u_x, u_y) at heights ``z``: the interpolation of :func:`profile_velocity_np` alone.

    No uniform-current shortcut and no output array: for a caller that evaluates one
    height at a time in an inner loop (a shooting ODE) and has checked the profile once.

    Parameters
    ----------
    z : float or array
        Heights, m.
    knots : sequence of float
        Knot heights, m, increasing.
    ux, uy : sequence of float
        Components at the knots (m/s, or the same scaled).
    """
    return np.interp(z, knots, ux), np.interp(z, knots, uy)


def profile_knots(knots: Sequence[float], ux: Sequence[float],
                  uy: Sequence[float]) -> list[float]:
    """Heights (m) of the knots where the velocity has a kink, sorted.

    A knot is a kink where the slope of either component changes (the slope is 0 beyond
    the end knots, so an end knot with a sloping neighbour segment is one). A uniform
    current has none.

    Parameters
    ----------
    knots : sequence of float
        Knot heights, m, increasing.
    ux, uy : sequence of float
        Velocity components at the knots, m/s.
    """
    if is_uniform(knots, ux, uy):
        return []
    z = np.asarray(knots)
    out = []
    for comp in (np.asarray(ux), np.asarray(uy)):
        slope = np.concatenate([[0.0], np.diff(comp) / np.diff(z), [0.0]])
        out += [float(z[j]) for j in range(len(z)) if slope[j] != slope[j + 1]]
    return sorted(set(out))


def current_velocity(current: Profile, z: Any, scale: Any = 1.0) -> Any:
    """:func:`profile_velocity` of a profile object (``z``, ``ux``, ``uy``), m/s.

    Parameters
    ----------
    current : Profile
        Knots and components (e.g. the scene's ``Current``).
    z : casadi expression
        Height, m.
    scale : casadi expression or float
        Multiplier on the whole current (-).
    """
    return profile_velocity(z, current.z, current.ux, current.uy, scale)
