"""Smooth replacement of the modulus in the quadratic drag terms |u| u.

We use ``|u| ~ sqrt(u^2 + delta^2)`` with a velocity scale ``delta`` (m/s). Then

    |u sqrt(u^2 + delta^2) - u |u||  =  |u| delta^2 / (sqrt(u^2 + delta^2) + |u|)
                                     <=  delta^2 / 2      for every u,

so the error in any drag term 0.5 rho C D |u| u is at most 0.25 rho C D delta^2 per
unit length, uniformly, whatever the flow. Unlike ``|u|`` itself (whose derivative is
undefined at 0) the replacement is infinitely differentiable, and since ``u |u|`` is C^1
with bounded second derivative, the Hessian of the smoothed term stays bounded (by 3)
however small delta is: delta can be tiny without making the NLP stiff.
"""

from __future__ import annotations

from typing import Any

import casadi as ca


def smooth_abs(u: Any, delta: float) -> Any:
    """Return sqrt(u^2 + delta^2), a smooth upper approximation of |u|.

    Parameters
    ----------
    u : casadi.SX or casadi.MX or float
        Velocity component, m/s.
    delta : float
        Smoothing velocity, m/s (> 0).
    """
    return ca.sqrt(u * u + delta * delta)


def smooth_abs_error_bound(delta: float) -> float:
    """Uniform bound on |u*smooth_abs(u) - u*|u||, in (m/s)^2: delta^2 / 2."""
    return 0.5 * delta * delta
