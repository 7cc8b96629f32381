"""The lumped-mass line stepped with the top's height and the top segment's unstretched
length as inputs (the heave plant's step: the winch pays cable through the top).

:class:`DrivenLumpedStep` builds, from a :class:`~cable_ocp.dynamics.lumped.LumpedMassModel`
on the line at its length ``L0`` with the top at rest, the implicit-midpoint step of the
same equations of motion (:mod:`cable_ocp.dynamics.lumped_equations`: the segments' pull,
drag and added mass, the nodes' masses, loads and drag) where, over a step ``(0, dt)``, the
unstretched length ``L`` and the top's height are linear between ``p = [L_a, L_b, z_a,
z_b]`` (m) and the top keeps its static x and y. The top segment (node N-1 to the top,
node N) has the unstretched length ``l_top = l_top0 + (L - L0)``; the other segments keep
theirs. The coordinates are relative to the top (small numbers: the residual carries no
round-off from the absolute positions).
"""

from __future__ import annotations

from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.dynamics.lumped import LumpedMassModel
from cable_ocp.errors import CableOCPError

__all__ = ["DrivenLumpedStep"]


class DrivenLumpedStep:
    """The step of a lumped-mass line driven by its top (module docstring).

    Parameters
    ----------
    model : LumpedMassModel
        The line at its length ``length0`` with a unit at end_a (the unit the winch
        lifts); it gives the static equilibrium, the force scale and every term of the
        equations.
    length0 : float
        The line's unstretched length, m.

    Attributes
    ----------
    l_top0 : float
        The top segment's unstretched length at ``length0``, m.
    top0 : ndarray (3,)
        The top's static position, m.
    """

    def __init__(self, model: LumpedMassModel, length0: float) -> None:
        params = model.params
        if params.fixed_a:
            raise CableOCPError("the lumped-mass heave plant needs a [unit] at end_a (the "
                                "unit the winch lifts), not an anchor")
        self.model = model
        self.length0 = float(length0)
        self.l_top0 = float(params.segment_length[-1])
        self.top0 = np.asarray(params.top_position(0.0), dtype=float).ravel()

    @property
    def n(self) -> int:
        """Number of lumped segments N."""
        return self.model.params.segments

    def expressions(self, fscale: float) -> dict[str, Any]:
        """The midpoint step as SX expressions.

        Unknown ``y``: the free nodes' displacement over the step relative to the top
        (``q1 - q0``, ``3 N``: small numbers, so the residual has no round-off from the
        positions). State: ``q`` the free nodes' positions relative to the top (m) and
        ``v`` their velocities (m/s). Equations at node i::

            M_i(r_m, l_m) (v1 - v0) / dt = F_T + W_i(l_m) + D(r_m, (r1 - r0) / dt) + ...
            r1 - r0 = dt (v0 + v1) / 2

        with the discrete-gradient tension of each segment: the mean of T over
        ``[eps0, eps1]`` (exact for EA e) along ``(d0 + d1) / (|d0| + |d1|)``, where the
        strain of each level is taken with that level's unstretched length
        (``eps_k = |d_k| / l_k - 1``), and the material damping at the strain rate
        ``(eps1 - eps0) / dt`` (:func:`~cable_ocp.dynamics.lumped_equations.segment_tension`).
        For the fixed segments this is the model's own scheme
        (:meth:`~cable_ocp.dynamics.lumped.LumpedMassModel.step_function`, ``"midpoint"``,
        the same terms of :mod:`cable_ocp.dynamics.lumped_equations`). For the top segment it
        is the same form, second order (``eps`` and the direction are midpoint values up
        to ``O(dt^2)``); it does not balance the strain energy exactly while ``l``
        changes, which is not required: cable paid out carries energy in and out with
        it, and with the winch still (``l_a = l_b``) the step is the model's own,
        energy-conserving one.

        The node below the top carries half of the top segment's mass, added mass and
        weight in water at its length in the middle of the step, ``l_m``: the mass
        changes as cable is paid out and joins the node at the node's own velocity, for
        which ``M(l_m) (v1 - v0) = m1 v1 - m0 v0 - (m1 - m0) (v0 + v1) / 2`` is exactly
        the discrete momentum balance ``d(m v)/dt = F + m' v`` (no thrust). The
        momentum that the paid-out cable brings in at the sheave's velocity is left
        out: ``mu L' (v_sheave - v) / 2``, a few newtons against the tensions.

        Returns a dict: symbols ``y``, ``q0``, ``v0``, ``p`` (4), ``dt``; ``res``
        (scaled by ``fscale``, N), ``x1`` (the state at the end), ``guess`` (the
        explicit predictor ``r1 = r0 + dt v0``) and ``out``: ``[z_unit, v_unit, t_unit,
        t_top, t_min]`` at the end of the step.
        """
        p = self.model.params
        eq = self.model.eq
        n = p.segments
        nf3 = 3 * n
        y = ca.SX.sym("y", nf3)
        q0 = ca.SX.sym("q0", nf3)
        v0 = ca.SX.sym("v0", nf3)
        par = ca.SX.sym("p", 4)
        dt = ca.SX.sym("dt")
        la = self.l_top0 + (par[0] - self.length0)
        lb = self.l_top0 + (par[1] - self.length0)
        lm = 0.5 * (la + lb)
        drt = ca.vertcat(0.0, 0.0, par[3] - par[2])  # the top's displacement over the step
        ztm = 0.5 * (par[2] + par[3])
        top_xy = ca.DM(self.top0[:2])

        def node(v: Any, i: int) -> Any:
            return v[3 * i:3 * i + 3] if i < n else ca.SX.zeros(3)

        q1 = q0 + y
        dq = [node(y, i) + drt for i in range(n)] + [drt]  # r1 - r0 of every node
        vel = [d / dt for d in dq]  # the step's mean velocities
        v1 = 2.0 * (y + ca.repmat(drt, n, 1)) / dt - v0
        ell0 = [float(v) for v in p.segment_length[:-1]] + [la]
        ell1 = [float(v) for v in p.segment_length[:-1]] + [lb]

        def absolute(q: Any, i: int, zt: Any) -> Any:  # a node's position, m
            return ca.vertcat(top_xy, zt) + node(q, i)

        force = [ca.SX.zeros(3) for _ in range(n + 1)]
        madd = []
        for j in range(n):
            d0 = node(q0, j + 1) - node(q0, j)
            d1 = node(q1, j + 1) - node(q1, j)
            st = eq.tension(j, d1, ell1=ell1[j], d0=d0, ell0=ell0[j], dt=dt)
            fe = st["tension"] * st["num"] / st["den"]
            dm = 0.5 * (d0 + d1)
            zm = 0.25 * (node(q0, j)[2] + node(q1, j)[2] + node(q0, j + 1)[2]
                         + node(q1, j + 1)[2]) + ztm
            fd = eq.segment_drag(j, dm, eq.current(zm) - 0.5 * (vel[j] + vel[j + 1]))
            force[j] = force[j] + fe + 0.5 * fd
            force[j + 1] = force[j + 1] - fe + 0.5 * fd
            madd.append(eq.added_mass_share(j, dm, lm if j == n - 1 else None))
        loads = eq.static_loads()
        # the top segment's share of mass and weight at its length in the middle of the step
        extra_l = lm - self.l_top0
        loads[n - 1] = loads[n - 1] - ca.vertcat(0.0, 0.0, 0.5 * float(p.weight_in_water[-1])
                                                 * extra_l)
        mu_top = float(p.mass_per_length[-1])
        rows = []
        for i in range(n):
            mass = ca.SX(ca.diag(ca.DM(eq.node_mass[i]))) + madd[i]
            if i > 0:
                mass = mass + madd[i - 1]
            if i == n - 1:
                mass = mass + 0.5 * mu_top * extra_l * ca.SX.eye(3)
            fi = force[i] + loads[i]
            rm = 0.5 * (absolute(q0, i, par[2]) + absolute(q1, i, par[3]))
            fi = fi + eq.point_drag(i, rm, vel[i])
            rows.append(ca.mtimes(mass, node(v1, i) - node(v0, i)) / dt - fi)
        res = ca.vertcat(*rows) / fscale

        # outputs at the end of the step (the top's velocity: its mean over the step)
        vend = [node(v1, i) for i in range(n)] + [drt / dt]
        ldot = (lb - la) / dt
        tens, hooke, chords = [], [], []
        for j in range(n):
            d1 = node(q1, j + 1) - node(q1, j)
            # the top segment's strain rate with its unstretched length changing
            st = eq.tension(j, d1, ell1=ell1[j], dv=vend[j + 1] - vend[j],
                            length_rate=ldot if j == n - 1 else None)
            tens.append(st["tension"])
            # the Hooke tension EA eps with the damping: <= 0 exactly where slack
            hooke.append(float(p.axial_stiffness[j]) * st["strain"] + st["damping"])
            chords.append(d1)

        def end_drag(j: int) -> Any:
            zm = 0.5 * (node(q1, j)[2] + node(q1, j + 1)[2]) + par[3]
            return eq.segment_drag(j, chords[j],
                                   eq.current(zm) - 0.5 * (vend[j] + vend[j + 1]))

        ez = ca.DM([0.0, 0.0, 1.0])
        # the pull of the cable on the unit: segment 0's tension less the half segment
        # that node 0 carries (weight in water, drag, inertia at the step's mean
        # acceleration)
        e_0 = chords[0] / ca.norm_2(chords[0])
        half = (0.5 * float(p.mass_per_length[0]) * ell1[0] * ca.SX.eye(3)
                + eq.added_mass_share(0, chords[0], ell1[0]))
        acc0 = (node(v1, 0) - node(v0, 0)) / dt
        pull = (tens[0] * e_0 + 0.5 * end_drag(0)
                - 0.5 * float(p.weight_in_water[0]) * ell1[0] * ez - ca.mtimes(half, acc0))
        # the top: the force of the attachment on the cable, node N's balance without its
        # acceleration (the top is linear within a step)
        e_t = chords[n - 1] / ca.norm_2(chords[n - 1])
        top = (tens[n - 1] * e_t - 0.5 * end_drag(n - 1)
               + 0.5 * float(p.weight_in_water[-1]) * lb * ez)
        out = ca.vertcat(node(q1, 0)[2] + par[3], node(v1, 0)[2], ca.norm_2(pull),
                         ca.norm_2(top), ca.mmin(ca.vertcat(*hooke)))
        guess = dt * v0 - ca.repmat(drt, n, 1)
        return {"y": y, "q0": q0, "v0": v0, "p": par, "dt": dt, "res": res,
                "x1": ca.vertcat(q1, v1), "guess": guess, "out": out}
