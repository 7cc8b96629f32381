"""The axial and planar models' steps with the top motion and the top length as inputs.

:meth:`cable_ocp.dynamics.axial.AxialModel.driven_step` and
:meth:`cable_ocp.dynamics.planar.PlanarModel.driven_step` (the interface's
:meth:`~cable_ocp.dynamics.model.CableModel.driven_step`; the lumped-mass model's is
:mod:`cable_ocp.dynamics.lumped_driven`): the model's own implicit-midpoint step where the
motion it reads (``motion(t)``: the unstretched length, its rates, the top's position,
velocity and acceleration) is :func:`sampled_motion`, linear in time over the step between
the inputs ``p = [L_a, L_b, z_a, z_b]``. The heave plants step the models through these
(the winch pays cable through the top), with the outputs the plant reports: the unit's
height and vertical velocity, the tension at the unit (the cable's pull on it: element 0's
tension less the half element that the unit's node carries, its weight in water, drag and
inertia), the top tension and the smallest element tension.
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import casadi as ca
import numpy as np

from cable_ocp.dynamics.model import DrivenStep
from cable_ocp.errors import CableOCPError
from cable_ocp.physics.added_mass import line_added_mass_2d
from cable_ocp.physics.drag import quadratic_drag

if TYPE_CHECKING:
    from cable_ocp.dynamics.axial import AxialModel
    from cable_ocp.dynamics.planar import PlanarModel

__all__ = ["axial_driven_step", "axial_unit_pull", "planar_driven_step", "sampled_motion"]


def sampled_motion(top: Any, p: ca.SX, dt: Any) -> Callable[[Any], tuple]:
    """The motion of a driven step as the models' ``motion(t)``: over the step (0, dt) the
    unstretched length goes linearly from ``p[0]`` to ``p[1]`` and the top's height from
    ``p[2]`` to ``p[3]`` (x and y stay at ``top``'s); returns (length, its rate, its second
    derivative, top position, velocity, acceleration) (m, m/s, m/s^2).

    Parameters
    ----------
    top : sequence of 3 float
        The top's static position, m.
    p : casadi.SX (4,)
        ``[L_a, L_b, z_a, z_b]``, m.
    dt : float or casadi.SX
        The step, s.
    """

    def motion(t: Any) -> tuple:
        s = t / dt
        length = p[0] + s * (p[1] - p[0])
        z = p[2] + s * (p[3] - p[2])
        return (length, (p[1] - p[0]) / dt, ca.SX(0.0),
                ca.vertcat(top[0], top[1], z), ca.vertcat(0.0, 0.0, (p[3] - p[2]) / dt),
                ca.SX.zeros(3))

    return motion


def axial_unit_pull(model: AxialModel, tension0: Any, element_length: Any, velocity: Any,
                    acceleration: Any) -> Any:
    """The axial line's pull on the unit (N): element 0's tension less the half element that
    node 0 carries, P = T_0 - (h / 2) (w + D + mu a), D = k (1 + T_0 / EA) |V| V its
    tangential drag (the model's own factor k, the strain taken from T_0, the internal
    damping left out there) -- the balance of the unit's half element, (mu h / 2) a = T_0 -
    P - (h / 2) (w + D). The one home of that pull: the driven step's output (the OCP's
    ``tension_at = "unit"``) and the forward check's (:func:`cable_ocp.schedule.forward.
    resimulate`), so that both bound the same point, s = 0, whatever their elements
    (element 0's own tension is at its middle, w h / 2 higher: 1350 N apart between 10
    and 20 elements on 1000 m of the 6.3.6 line).

    Parameters
    ----------
    model : AxialModel
        The line (w, mu, EA, k).
    tension0 : float, numpy.ndarray or casadi expression
        Element 0's tension, N.
    element_length : same
        h = L / n, m.
    velocity : same
        Node 0's (the unit's) vertical velocity, m/s (positive up).
    acceleration : same
        Its acceleration, m/s^2 (positive up).
    """
    k = model.k_drag * (1.0 + tension0 / model.ea)
    if isinstance(velocity, (ca.SX, ca.MX, ca.DM)):
        drag = quadratic_drag(k, velocity)
    else:
        drag = k * np.abs(velocity) * velocity
    return tension0 - 0.5 * element_length * (model.w + drag + model.mu * acceleration)


def axial_driven_step(model: AxialModel, dt: float) -> DrivenStep:
    """The axial model's midpoint step ``x1 - x0 - dt f(dt/2, (x0 + x1)/2) = 0`` with the
    top motion and the length as inputs (module docstring), over a step of ``dt`` (s).

    The unknown is the new state ``x1`` (the residual unscaled, its convergence measure
    scaled by :attr:`DrivenStep.residual_scale`: positions in units of the static
    elongation, velocities in units of g dt, as :meth:`AxialModel.step_function` scales
    them); the guess is ``x0``; the start is the closed-form static profile at rest (the
    motion's acceleration is zero inside a step: the top tension leaves out the inertia of
    half an element, ``mu h a_top / 2``).

    Parameters
    ----------
    model : AxialModel
        The axial model of the scene.
    dt : float or casadi.SX
        The step, s; a symbol where one built step serves every step size (the deployment
        schedule's free duration; the convergence scale then at ``simulation.time_step``).
    """
    sc = model.scene
    md = copy.copy(model)
    p = ca.SX.sym("p", 4)
    md.motion = sampled_motion(sc.top_position, p, dt)
    md._rhs_fn = None
    n = md.n
    n2 = 2 * n
    t = ca.SX.sym("t")
    x = ca.SX.sym("x", n2)
    rhs = md.rhs(t, x)
    symbolic = isinstance(dt, ca.SX)
    f = ca.Function("f", [t, x, p] + ([dt] if symbolic else []), [rhs])
    dt_scale = sc.simulation.time_step if symbolic else dt
    scale = ca.DM([1.0 / md.elongation] * n + [1.0 / (dt_scale * md.gravity)] * n)
    x0 = ca.SX.sym("x0", n2)
    x1 = ca.SX.sym("x1", n2)
    res = x1 - x0 - dt * f(0.5 * dt, 0.5 * (x0 + x1), p, *([dt] if symbolic else []))
    heights, tens, top, length, vel = md.outputs(t, x)
    # tension at the unit's attachment (s = 0): element 0's tension less the half
    # element that node 0 carries (its weight in water, drag and inertia)
    t_unit = axial_unit_pull(md, tens[0], length / n, vel[0], rhs[n])
    out, tens_end = ca.substitute([ca.vertcat(heights[0], vel[0], t_unit, top, ca.mmin(tens)),
                                   tens], [t], [dt if symbolic else ca.SX(dt)])
    out, tens_end = ca.substitute([out, tens_end], [x], [x1])
    return DrivenStep(unknown=x1, state=x0, inputs=p, dt=dt, residual=res,
                      next_state=x1, guess=x0, outputs=out,
                      start=model.rest_state(), residual_scale=scale, tensions=tens_end)


def planar_driven_step(model: PlanarModel, dt: float | None = None) -> DrivenStep:
    """The planar model's midpoint step (its own :meth:`PlanarModel._step_expressions`)
    with the top motion and the length as inputs (module docstring); ``dt`` a symbol
    unless given (s), so that one built step serves every step size (the halving of a
    step whose Newton iteration does not converge).

    The unknown is the new offsets ``q1``; the guess the model's explicit predictor; the
    start the static state (:meth:`PlanarModel.initial_state` with ``start = "static"``,
    which also raises the model's force scale to the static tension).

    Parameters
    ----------
    model : PlanarModel
        The planar model of the scene.
    dt : float, optional
        The step, s (None: a symbol).

    Raises
    ------
    CableOCPError
        When the static state fails.
    """
    sc = model.scene
    if model.solid is not None:
        raise CableOCPError("cable.viscoelastic: the driven planar step (the heave plant) has "
                            "the elastic laws only; give axial_stiffness alone")
    base = model if sc.simulation.start == "static" else type(model)(
        sc.with_overrides({"simulation.start": "static"}), model.n)
    x_start, info = base.initial_state()
    if x_start is None:
        raise CableOCPError(f"the planar line's static state failed: "
                            f"{info.get('message', '')}")
    md = copy.copy(model)
    md.force_scale = base.force_scale
    dts = ca.SX.sym("dt") if dt is None else dt
    p = ca.SX.sym("p", 4)
    md.motion_params = ca.vertcat(p, dts) if dt is None else p
    md.motion = sampled_motion(sc.top_position, p, dts)
    q1, q0, v0, t0, res, v1, _, pred = md._step_expressions(dts)[:8]
    res, v1, pred = ca.substitute([res, v1, pred], [t0], [ca.SX(0.0)])
    # outputs at the end of the step (t = dt)
    rs, tens, top, _, vel, _ = md.output_function()(dts, q1, v1, md.motion_params)
    # the pull on the unit: element 0's tension along its chord, less the half element
    # that node 0 carries (weight in water, drag, inertia at the step's mean acceleration),
    # as the axial model's
    h_el = p[1] / md.n
    d0 = rs[:, 1] - rs[:, 0]
    urel = md._current(0.5 * (rs[1, 0] + rs[1, 1])) - 0.5 * (vel[:, 0] + vel[:, 1])
    drag_half = 0.5 * md._element_drag(d0, urel)
    axx, axz, azz = line_added_mass_2d(d0, md.man, md.mat)
    half = 0.5 * h_el
    mxx, mxz, mzz = half * (md.mu + axx), half * axz, half * (md.mu + azz)
    acc = (v1[0:2] - v0[0:2]) / dts
    pull = (tens[0] * d0 / ca.norm_2(d0) + drag_half
            - ca.vertcat(mxx * acc[0] + mxz * acc[1],
                         mxz * acc[0] + mzz * acc[1] + 0.5 * md.w * h_el))
    out = ca.vertcat(rs[1, 0], vel[1, 0], ca.norm_2(pull), top, ca.mmin(tens))
    return DrivenStep(unknown=q1, state=ca.vertcat(q0, v0), inputs=p, dt=dts,
                      residual=res, next_state=ca.vertcat(q1, v1), guess=pred,
                      outputs=out, start=np.asarray(x_start, dtype=float), tensions=ca.vec(tens))
