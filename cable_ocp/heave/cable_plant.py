"""The cable as the heave plant: the axial cable model stepped one control sample at a time.

Huang (1992) designs the compensator on the second-order unit model (6.2), identified from
the cable model of his ch. 3 (section 6.2.3), and never closes the loop on the cable itself.
Here the controllers (designed on (6.2), identified or given) run against the axial cable
model (:class:`cable_ocp.dynamics.axial.AxialModel`, Huang's (3.1)-(3.3)) of a dynamic scene:

* the boom-tip heave ``x0(t)`` moves end_b (the sheave) vertically;
* the winch output ``u(t)`` (m, ``u > 0`` hauls the unit up, as in (6.4)) pays cable in at
  end_b: the unstretched length is ``L(t) = L_dep(t) - u(t)``, with ``L_dep`` the deployment
  length (constant, or the pay-out of a lowering);
* the winch itself is the scene's winch model ((6.1) or the second-order winch) with the
  command delayed by exactly ``tau``, integrated exactly (zero-order hold) on the plant's
  sub-steps; it is a position source, as in (6.4).

:class:`AxialCablePlant` builds, once, a CasADi function that advances the cable over one
control sample: the cable scene's ``[simulation] time_step`` divides the sample into ``m``
implicit-midpoint steps (a Newton ``rootfinder`` each, the axial model's own scheme), with
``L`` and the sheave height linear in time over each step. One call per sample, no Python per
sub-step.

The controllers do not see the plant's state. They see what a real system measures, once per
sample, each with its own white noise: the unit's depth (``[controller] measurement_noise``),
the winch position (``winch_noise``) and the boom-tip heave from the vessel's motion sensor
(``boom_tip_noise``). The state of the design model (unit, winch, vessel and sea filters, the
delay buffer) is estimated by the LQG's discrete Kalman filter (current estimator) on the
design model, extended to the three measurements; LQR and MPC both use that estimate
(certainty equivalence). ``lqg`` keeps its own sensor set: the unit's depth only, as on the
design model. The delay buffer (the controller's own past commands) is known exactly.

Every controller also runs, with the same estimator, sensors, noise and sea, against the
design model as the plant: the reduction that model predicts sits beside the one the cable
achieves (:class:`CableMetrics`). The comparison itself, with the identification and the
deployment, is :mod:`cable_ocp.heave.cable_compare`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import casadi as ca
import numpy as np
from scipy import linalg

from cable_ocp.dynamics.axial import AxialModel, static_profile
from cable_ocp.errors import CableOCPError
from cable_ocp.heave import mpc as mpc_mod
from cable_ocp.heave import plant as pl
from cable_ocp.heave.discrete import DelayedDiscreteModel, discretize_delayed, discretize_noise
from cable_ocp.heave.simulate import Comparison, Trace
from cable_ocp.heave.stochastic import WHITE_NOISE_INTENSITY, discrete_delay_lqr
from cable_ocp.numerics.compile import compile_functions
from cable_ocp.scene.dynamics import DynamicScene
from cable_ocp.scene.heave import HeaveScene

__all__ = [
    "AxialCablePlant",
    "CableComparison",
    "CableMetrics",
    "CableTrace",
    "DesignTable",
    "KalmanEstimator",
    "design_scene",
    "run_loop",
]


# ------------------------------------------------------------------------------------------
# The step-able cable
# ------------------------------------------------------------------------------------------

def sampled_motion(top: Any, p: ca.SX, dt: Any) -> Callable[[Any], tuple]:
    """The motion of a plant step as the models' ``motion(t)``: over the step (0, dt) the
    unstretched length goes linearly from ``p[0]`` to ``p[1]`` and the top's height from
    ``p[2]`` to ``p[3]`` (x and y stay at ``top``'s); returns (length, its rate, its second
    derivative, top position, velocity, acceleration)."""

    def motion(t: Any) -> tuple:
        s = t / dt
        length = p[0] + s * (p[1] - p[0])
        z = p[2] + s * (p[3] - p[2])
        return (length, (p[1] - p[0]) / dt, ca.SX(0.0),
                ca.vertcat(top[0], top[1], z), ca.vertcat(0.0, 0.0, (p[3] - p[2]) / dt),
                ca.SX.zeros(3))

    return motion


class _SteppedAxial(AxialModel):
    """The axial model with the sheave height and the unstretched length as parameters.

    Over one step of ``dt`` both are linear in time between their values at the start and
    the end of the step, ``p = [L_a, L_b, z_a, z_b]`` (m): the motion that the model's
    ``_fields`` reads from ``self.motion`` is this interpolation instead of a function of
    time (its acceleration is zero inside a step: the top tension leaves out the inertia of
    half an element, ``mu h a_top / 2``).
    """

    def __init__(self, scene: DynamicScene, dt: float) -> None:
        super().__init__(scene)
        self.dt = dt
        self.p = ca.SX.sym("p", 4)
        self.motion = sampled_motion(scene.top_position, self.p, dt)


class SampledCablePlant:
    """What the heave loop needs of a cable plant stepped one control sample per call:
    :meth:`advance` (one sample from the state) and :meth:`run_open_loop` (a prescribed
    top and length, for the identification), on top of a subclass's ``_flat`` (one sample,
    flat outputs), ``_sample`` (one sample, for ``mapaccum``), ``substeps``, ``length0``,
    ``z_top0``, :meth:`initial_state`, :meth:`static_unit_height` and
    :meth:`static_tensions`."""

    substeps: int
    length0: float
    z_top0: float
    _chunk_name = "cable_chunk"

    def _setup(self, scene: DynamicScene, sample_time: float, wrong_model: str | None = None,
               need_unit: bool = True) -> None:
        """Check the cable scene (its ``simulation.model`` is this plant's, else
        ``wrong_model`` is the error, by default "<class>: simulation.model = ...;
        expected ..."; a ``[unit]`` where ``need_unit``; its time step divides the control
        sample) and set the sampling attributes: ``scene``, ``h``, ``substeps``, ``dt``,
        ``length0``, ``z_top0``, ``tolerance``."""
        sim = scene.simulation
        if sim.model != self.model_name:
            raise CableOCPError(wrong_model or (
                f"{type(self).__name__}: simulation.model = {sim.model!r}; "
                f'expected "{self.model_name}"'))
        if need_unit and scene.unit is None:
            raise CableOCPError(f'simulation.model = "{self.model_name}" as the heave plant: '
                                "the cable scene needs a [unit] at end_a (the unit the winch "
                                "lifts)")
        ratio = sample_time / sim.time_step
        m = int(round(ratio))
        if m < 1 or abs(ratio - m) > 1e-9 * max(1.0, ratio):
            raise CableOCPError(f"cable scene: [simulation] time_step = {sim.time_step} s must "
                                f"divide the control sample time {sample_time} s")
        self.scene = scene
        self.h = float(sample_time)
        self.substeps = m
        self.dt = self.h / m
        self.length0 = scene.length
        self.z_top0 = float(scene.top_position[2])
        self.tolerance = sim.tolerance

    def advance(self, x: np.ndarray, lengths: np.ndarray, tops: np.ndarray
                ) -> tuple[np.ndarray, dict[str, Any]]:
        """Advance one sample.

        Parameters
        ----------
        x : numpy.ndarray
            State (``2 N``).
        lengths, tops : numpy.ndarray, shape (substeps + 1,)
            Unstretched length (m) and sheave height (m) at the sub-step points of the
            sample, start included.

        Returns
        -------
        x_next : numpy.ndarray
        out : dict
            ``z_unit``, ``v_unit``, ``t_unit``, ``t_top`` (m, m/s, N, N at the ends of the
            sub-steps, shape (substeps,)), ``t_min`` (smallest element tension, N) and
            ``residual`` (largest scaled Newton residual).
        """
        m = self.substeps
        P = np.empty(4 * m)
        P[0::4] = lengths[:-1]
        P[1::4] = lengths[1:]
        P[2::4] = tops[:-1]
        P[3::4] = tops[1:]
        r = self._flat(x, P).full().ravel()
        n2 = x.size
        out = {"z_unit": r[n2: n2 + m], "v_unit": r[n2 + m: n2 + 2 * m],
               "t_unit": r[n2 + 2 * m: n2 + 3 * m], "t_top": r[n2 + 3 * m: n2 + 4 * m],
               "t_min": float(r[n2 + 4 * m]), "residual": float(r[n2 + 4 * m + 1])}
        return r[:n2], out

    def run_open_loop(self, lengths: np.ndarray, tops: np.ndarray,
                      chunk: int = 200) -> dict[str, np.ndarray]:
        """Run a prescribed top motion and length from the static state (identification).

        ``lengths``, ``tops``: on the sub-step grid, ``K * substeps + 1`` points (K samples).
        Returns ``z_unit``, ``t_unit``, ``t_top`` on that grid (the first point static) and
        ``t_min``, ``residual`` (over the run). Chunks of samples are stepped by ``mapaccum``.
        """
        m = self.substeps
        nk = (len(lengths) - 1) // m
        if nk * m + 1 != len(lengths) or len(tops) != len(lengths):
            raise CableOCPError("run_open_loop: lengths and tops need K * substeps + 1 points")
        x = self.initial_state()
        t_u0, t_t0 = self.static_tensions(float(lengths[0]))
        z = [np.array([float(self.static_unit_height(self.length0)) + tops[0] - self.z_top0])]
        tu, tt = [np.array([t_u0])], [np.array([t_t0])]
        t_min, rmax = min(t_u0, t_t0), 0.0
        done = 0
        while done < nk:
            k = min(chunk, nk - done)
            if k not in self._chunks:
                self._chunks[k] = self._sample.mapaccum(self._chunk_name, k)
            i0 = done * m
            L = lengths[i0: i0 + k * m + 1]
            T = tops[i0: i0 + k * m + 1]
            P = np.vstack([L[:-1], L[1:], T[:-1], T[1:]])
            r = self._chunks[k](x, P)
            x = np.asarray(r[0])[:, -1]
            z.append(np.asarray(r[1]).ravel())
            tu.append(np.asarray(r[3]).ravel())
            tt.append(np.asarray(r[4]).ravel())
            t_min = min(t_min, float(np.min(np.asarray(r[5]))))
            rmax = max(rmax, float(np.max(np.asarray(r[6]))))
            done += k
        return {"z_unit": np.concatenate(z), "t_unit": np.concatenate(tu),
                "t_top": np.concatenate(tt), "t_min": t_min, "residual": rmax}




class AxialCablePlant(SampledCablePlant):
    """The axial cable model advanced one control sample per call (module docstring).

    Parameters
    ----------
    scene : DynamicScene
        An axial scene (``[simulation] model = "axial"``): the line, the unit, the static
        top position, ``segments``, and ``time_step`` (the sub-step, s, which must divide
        ``sample_time``); ``tolerance`` and ``max_iterations`` of the Newton steps. Its
        ``[top_motion]`` is not used: the heave scene moves the top.
    sample_time : float
        Control sample ``h``, s.

    Attributes
    ----------
    substeps : int
        Midpoint steps per sample.
    model : AxialModel
        The discretised line.
    """

    #: the cable scene's ``simulation.model`` of this plant
    model_name = "axial"

    def __init__(self, scene: DynamicScene, sample_time: float) -> None:
        sim = scene.simulation
        self._setup(scene, sample_time, f"cable plant: [simulation] model = {sim.model!r}; "
                    "the heave plant uses the axial model (model = \"axial\")",
                    need_unit=False)
        self.model = _SteppedAxial(scene, self.dt)
        self._sample = self._build(sim.tolerance, sim.max_iterations)
        self._chunks: dict[int, ca.Function] = {}

    def _build(self, tol: float, max_iter: int) -> ca.Function:
        """The sample function ``(x, P) -> (x_next, z_unit, v_unit, t_unit, t_top, t_min,
        residual)`` (see :meth:`advance`).

        Each midpoint step ``x1 - x0 - dt f(dt/2, (x0 + x1)/2) = 0`` takes two Newton
        iterations from ``x1 = x0``. The Jacobian is block tridiagonal in the node order
        (zeta_i, V_i) (each node couples to its neighbours only: checked when built), so an
        iteration is a block Thomas elimination of 2 x 2 blocks written in SX, about 140
        operations per node: no sparse LU, no Python. The line is nearly linear (the drag
        and the pay-out terms are the only nonlinearities), so one iteration is already
        exact up to them and the second squares that error; the scaled residual of the
        result (as :meth:`AxialModel.step_function` scales it) is returned, and a value above
        ``1e3 tolerance`` marks the run as failed. The functions are compiled to C when a
        compiler is found (:func:`_compile`).
        """
        md = self.model
        n = md.n
        n2 = 2 * n
        dt = self.dt
        p = md.p
        t = ca.SX.sym("t")
        x = ca.SX.sym("x", n2)
        rhs = md.rhs(t, x)
        f = ca.Function("f", [t, x, p], [rhs])
        scale = ca.DM([1.0 / md.elongation] * n + [1.0 / (dt * md.gravity)] * n)
        x0 = ca.SX.sym("x0", n2)
        x1 = ca.SX.sym("x1", n2)
        res = x1 - x0 - dt * f(0.5 * dt, 0.5 * (x0 + x1), p)
        perm = [int(i) for i in np.ravel(np.column_stack([np.arange(n), n + np.arange(n)]))]
        back = [int(i) for i in np.argsort(perm)]
        jac = ca.jacobian(res, x1)[perm, perm]
        rows, cols = np.nonzero(np.array(ca.DM(jac.sparsity(), 1)))
        if rows.size and np.max(np.abs(rows // 2 - cols // 2)) > 1:
            raise CableOCPError("cable plant: the axial model's Jacobian is not block "
                                "tridiagonal (internal error)")
        step = _block_tridiagonal_solve(jac, res[perm], n)
        newton = ca.Function("axial_newton", [x1, x0, p], [x1 - step[back]])
        resid = ca.Function("axial_resid", [x1, x0, p], [ca.norm_inf(res * scale)])
        heights, tens, top, length, vel = md.outputs(t, x)
        # tension at the unit's attachment (s = 0): element 0's tension less the half
        # element that node 0 carries (its weight in water, drag and inertia)
        h_el = length / n
        eps0 = tens[0] / md.ea  # (the drag's factor 1 + e; internal damping left out there)
        drag0 = md.k_drag * (1.0 + eps0) * ca.fabs(vel[0]) * vel[0]
        t_unit = tens[0] - 0.5 * h_el * (md.w + drag0 + md.mu * rhs[n])
        out = ca.Function("axial_out", [x, p], [ca.substitute(
            ca.vertcat(heights[0], vel[0], t_unit, top, ca.mmin(tens)), t, ca.SX(dt))])
        newton, resid, out = _compile([newton, resid, out])

        # one sub-step: two iterations, then more (up to max_iterations, evaluated only
        # while the scaled residual exceeds the tolerance: a short-circuit switch)
        xa = ca.MX.sym("xa", n2)
        pm = ca.MX.sym("p", 4)
        x2 = newton(newton(xa, xa, pm), xa, pm)
        y = ca.vertcat(x2, resid(x2, xa, pm))
        yb = ca.MX.sym("y", n2 + 1)
        xb = newton(yb[:n2], xa, pm)
        more = ca.Function("more", [yb, xa, pm], [ca.vertcat(xb, resid(xb, xa, pm))])
        keep = ca.Function("keep", [yb, xa, pm], [yb])
        switch = ca.Function.conditional("newton_more", [keep], more)
        for _ in range(max(0, max_iter - 2)):
            y = switch(y[n2] > tol, y, xa, pm)
        sub = ca.Function("axial_substep", [xa, pm], [y[:n2], y[n2]])

        m = self.substeps
        X = ca.MX.sym("X", n2)
        P = ca.MX.sym("P", 4, m)
        xx = X
        cols_out, rs = [], []
        for j in range(m):
            pj = P[:, j]
            xn, r = sub(xx, pj)
            rs.append(r)
            cols_out.append(out(xn, pj))
            xx = xn
        rmax = rs[0]
        for r in rs[1:]:
            rmax = ca.fmax(rmax, r)
        o = ca.horzcat(*cols_out)
        tmin = o[4, 0]
        for j in range(1, m):
            tmin = ca.fmin(tmin, o[4, j])
        sample = ca.Function("cable_sample", [X, P],
                             [xx, o[0, :], o[1, :], o[2, :], o[3, :], tmin, rmax],
                             ["x", "P"], ["x_next", "z_unit", "v_unit", "t_unit", "t_top",
                                          "t_min", "residual"])
        # the same as one column (one conversion per call in the closed loop)
        Pf = ca.MX.sym("Pf", 4 * m)
        r = sample(X, ca.reshape(Pf, 4, m))
        self._flat = ca.Function("cable_sample_flat", [X, Pf], [ca.vertcat(
            r[0], r[1].T, r[2].T, r[3].T, r[4].T, r[5], r[6])])
        return sample

    # ------------------------------------------------------------------------------------
    def initial_state(self) -> np.ndarray:
        """The static state at the scene's length, at rest (relative to the top, so a top
        that starts displaced carries the static line with it)."""
        md = self.model
        n = md.n
        s = np.arange(n) * self.length0 / n
        z, _ = static_profile(self.scene, s)
        zeta = z - (self.z_top0 - (self.length0 - s))
        return np.concatenate([zeta, np.zeros(n)])

    def static_unit_height(self, length: float | np.ndarray) -> np.ndarray:
        """Static height of the unit (m) hanging on ``length`` (m) from the top's static
        position: ``z_b - L - (W L + w L^2 / 2) / EA``."""
        md = self.model
        length = np.asarray(length, dtype=float)
        return (self.z_top0 - length
                - (md.unit_weight * length + 0.5 * md.w * length**2) / md.ea)

    def static_tensions(self, length: float | None = None) -> tuple[float, float]:
        """(tension at the unit, at the top) of the static line of ``length`` (m), N."""
        md = self.model
        length = self.length0 if length is None else length
        return md.unit_weight, md.unit_weight + md.w * length

def _inv2(m: ca.SX) -> ca.SX:
    a, b, c, d = m[0, 0], m[0, 1], m[1, 0], m[1, 1]
    return ca.vertcat(ca.horzcat(d, -b), ca.horzcat(-c, a)) / (a * d - b * c)


def _block_tridiagonal_solve(jac: ca.SX, r: ca.SX, n: int) -> ca.SX:
    """``jac^-1 r`` for a block-tridiagonal ``jac`` of ``n`` 2 x 2 blocks (block Thomas
    elimination without pivoting: here ``jac = I - dt/2 df/dx`` of the midpoint rule, whose
    Schur complements stay close to ``I + dt^2/4 M^-1 K``, well conditioned)."""
    def blk(i: int, j: int) -> ca.SX:
        return jac[2 * i: 2 * i + 2, 2 * j: 2 * j + 2]

    piv = [blk(0, 0)]
    rhs = [r[0:2]]
    for i in range(1, n):
        w = ca.mtimes(blk(i, i - 1), _inv2(piv[i - 1]))
        piv.append(blk(i, i) - ca.mtimes(w, blk(i - 1, i)))
        rhs.append(r[2 * i: 2 * i + 2] - ca.mtimes(w, rhs[i - 1]))
    sol: list[ca.SX] = [ca.SX()] * n
    sol[n - 1] = ca.mtimes(_inv2(piv[n - 1]), rhs[n - 1])
    for i in range(n - 2, -1, -1):
        sol[i] = ca.mtimes(_inv2(piv[i]), rhs[i] - ca.mtimes(blk(i, i + 1), sol[i + 1]))
    return ca.vertcat(*sol)


def _compile(fns: list[ca.Function], flags: str = "-O1") -> list[ca.Function]:
    """Compile the plant's functions to one shared library (``cc -O1``: on the generated
    straight-line code ``-O2`` is no faster and compiles as slowly), cached
    (:func:`cable_ocp.numerics.compile.compile_functions`). Returns them unchanged when compiling is
    off (``CABLE_OCP_CACHE=0``), no compiler is found or anything fails (the interpreted
    functions compute the same numbers, about 5x slower)."""
    return compile_functions(fns, flags, prefix="heave_")


# ------------------------------------------------------------------------------------------
# Plants seen by the closed loop
# ------------------------------------------------------------------------------------------

class _CableLoopPlant:
    """The cable plant in the loop: heave relative to the static depth at ``L_dep``."""

    def __init__(self, plant: AxialCablePlant) -> None:
        self.p = plant
        self.substeps = plant.substeps
        self.x = plant.initial_state()
        self.heave = 0.0
        self.failed_at: int | None = None
        self.max_residual = 0.0
        #: (status, message) where the plant refused a sample (its ``out["stop"]``)
        self.stop: tuple[str, str] | None = None

    def start(self, x0_start: float, ldep0: float) -> tuple[float, float]:
        self.x = self.p.initial_state()
        self.heave = x0_start  # the static line hangs from the displaced top, at rest
        self.stop = None
        return self.p.static_tensions(ldep0)

    def advance(self, k: int, u: np.ndarray, x0: np.ndarray, ldep: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        x, out = self.p.advance(self.x, ldep - u, self.p.z_top0 + x0)
        if "stop" in out and self.stop is None:
            self.stop = ("failed", f"at t = {k * self.p.h:.2f} s {out['stop']}; the run "
                         "stops there")
        if "stop" not in out:
            self.max_residual = max(self.max_residual, out["residual"])
        if not (out["residual"] <= max(1e3 * self.p.tolerance, 1e-6)) and self.failed_at is None:
            self.failed_at = k
        self.x = x
        heave = out["z_unit"] - self.p.static_unit_height(ldep[1:])
        self.heave = float(heave[-1])
        return heave, out["t_unit"], out["t_top"], out["t_min"]


class _ModelLoopPlant:
    """The design model (6.2) or (6.3) as the plant, RK4 with ``x0 + u`` linear per step.

    Tension at the unit ``T0 + (m/a)(x0 + u - x)`` (the model's own, :mod:`.mpc`); the
    model has no top tension (reported as the same dynamic part on the static top tension).
    """

    def __init__(self, a: float, b: float, b_quadratic: float, quadratic: bool,
                 substeps: int, dt: float, mass: float, t_unit0: float, t_top0: float) -> None:
        self.a, self.b, self.bq, self.quad = a, b, b_quadratic, quadratic
        self.substeps, self.dt = substeps, dt
        self.k = mass / a
        self.t0, self.tt0 = t_unit0, t_top0
        self.s = [0.0, 0.0]
        self.heave = 0.0
        self.failed_at: int | None = None
        self.max_residual = 0.0

    def start(self, x0_start: float, ldep0: float) -> tuple[float, float]:  # noqa: ARG002
        self.s = [x0_start, 0.0]
        self.heave = x0_start
        return self.t0, self.tt0

    def _f(self, x: float, v: float, inp: float) -> tuple[float, float]:
        damp = self.bq * v * abs(v) if self.quad else self.b * v
        return v, (inp - x - damp) / self.a

    def advance(self, k: int, u: np.ndarray, x0: np.ndarray, ldep: np.ndarray  # noqa: ARG002
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        m, dt = self.substeps, self.dt
        x, v = self.s
        inp = (x0 + u).tolist()
        xs = np.empty(m)
        for j in range(m):
            ia, ib = inp[j], inp[j + 1]
            im = 0.5 * (ia + ib)
            k1 = self._f(x, v, ia)
            k2 = self._f(x + 0.5 * dt * k1[0], v + 0.5 * dt * k1[1], im)
            k3 = self._f(x + 0.5 * dt * k2[0], v + 0.5 * dt * k2[1], im)
            k4 = self._f(x + dt * k3[0], v + dt * k3[1], ib)
            x += dt / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            v += dt / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
            xs[j] = x
        self.s = [x, v]
        self.heave = x
        dyn = self.k * (x0[1:] + u[1:] - xs)
        return xs, self.t0 + dyn, self.tt0 + dyn, float(np.min(self.t0 + dyn))


# ------------------------------------------------------------------------------------------
# Estimator and controllers
# ------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class DesignTable:
    """A design (or a table of designs over lengths) the controllers interpolate.

    Attributes
    ----------
    lengths : numpy.ndarray, shape (K,)
        Deployment lengths of the designs, m (one entry: a fixed design).
    a, b : numpy.ndarray, shape (K,)
        Design-model coefficients of (6.2), s^2 and s.
    Ad, Bd : numpy.ndarray, shapes (K, nz + 1, nz + 1), (K, nz + 1, 1)
        The estimator's models: the sampled delayed design models
        (:func:`cable_ocp.heave.discrete.discretize_delayed`) and the depth offset.
    G : numpy.ndarray, shape (K, 1, nz + 1)
        Exact discrete-delay LQR gains, ``u0 = -G z`` (0 on the offset).
    M3, M1 : numpy.ndarray, shapes (K, nz + 1, 3), (K, nz + 1, 1)
        Kalman gains of the current estimator with the three sensors (depth, winch,
        boom tip) and with the depth alone.
    C3 : numpy.ndarray, shape (3, nz + 1)
        Measurement rows (depth, winch, boom tip); the first row is the depth's.
    n : int
        Plant states (the delay buffer follows).
    nz : int
        Plant states and delay buffer: the design model's state (the depth offset follows,
        the estimator's last state; :func:`_design`).
    """

    lengths: np.ndarray
    a: np.ndarray
    b: np.ndarray
    Ad: np.ndarray
    Bd: np.ndarray
    G: np.ndarray
    M3: np.ndarray
    M1: np.ndarray
    C3: np.ndarray
    n: int
    nz: int

    def at(self, length: float) -> tuple[np.ndarray, ...]:
        """``(Ad, Bd, G, M3, M1)`` linearly interpolated in the length (held outside)."""
        L = self.lengths
        if L.size == 1 or length <= L[0]:
            i, w = 0, 0.0
        elif length >= L[-1]:
            i, w = L.size - 2, 1.0
        else:
            i = int(np.searchsorted(L, length) - 1)
            w = (length - L[i]) / (L[i + 1] - L[i])
        if L.size == 1:
            return self.Ad[0], self.Bd[0], self.G[0], self.M3[0], self.M1[0]
        return tuple((1 - w) * arr[i] + w * arr[i + 1]
                     for arr in (self.Ad, self.Bd, self.G, self.M3, self.M1))


def kalman_gain(Ad: np.ndarray, C: np.ndarray, Qw: np.ndarray, R: np.ndarray  # noqa: N803
                ) -> np.ndarray:
    """Steady-state gain ``M = P C^T (C P C^T + R)^-1`` of the current estimator
    (``x_hat = x_pred + M (y - C x_pred)``), ``P`` the a-priori covariance from the DARE."""
    P = linalg.solve_discrete_are(Ad.T, C.T, Qw, R)
    return P @ C.T @ np.linalg.inv(C @ P @ C.T + R)


def _design(sc: HeaveScene, a: float, b: float) -> tuple[pl.HeavePlant, np.ndarray,
                                                           np.ndarray, np.ndarray, np.ndarray,
                                                           np.ndarray, np.ndarray, int]:
    """Plant (6.28) with ``a, b``; the estimator's sampled model (delayed design model plus
    a depth offset); LQR gain; Kalman gains; measurement rows; ``nz``.

    The estimator's state is ``[plant (n); past commands (d); depth offset]``. The offset is
    a random walk seen only by the depth sensor: the static depth of the unit is never known
    exactly (a pressure sensor's offset, the tide, the drag of a pay-out, which shifts the
    unit by centimetres, the design model's own static error). Its intensity gives the
    filter a time constant ``[controller] depth_bias_time`` for it (per-sample variance
    ``(sigma_depth h / tau_b)^2``: the bandwidth ``1 / tau_b`` of a random walk seen in white
    noise), far below the waves, so that a slow offset is not taken for heave and not
    compensated; without it the filter forces the design model's states to explain it.
    """
    from cable_ocp.heave.simulate import build_models

    s2 = replace(sc, unit=replace(sc.unit, a=a, b=b))
    p = build_models(s2).plant
    c = sc.controller
    h, tau = c.sample_time, sc.winch.delay
    G = np.atleast_2d(discrete_delay_lqr(p.A, p.B1, p.e("x"), c.q, c.r, h, tau))
    mdl: DelayedDiscreteModel = discretize_delayed(p.A, p.B1, h, tau)
    nz, n = mdl.Ad.shape[0], p.n
    ne = nz + 1
    Ad = np.eye(ne)
    Ad[:nz, :nz] = mdl.Ad
    Bd = np.zeros((ne, 1))
    Bd[:nz] = mdl.Bd
    Qw = np.zeros((ne, ne))
    Qw[:n, :n] = discretize_noise(p.A, p.B2, WHITE_NOISE_INTENSITY, h)
    Qw += 1e-14 * np.eye(ne) * np.max(np.abs(Qw))
    tb = c.depth_bias_time
    Qw[nz, nz] = (c.measurement_noise * h / tb) ** 2 if tb > 0 else 0.0
    C3 = np.zeros((3, ne))
    C3[0, :n] = p.e("x")
    C3[0, nz] = 1.0 if tb > 0 else 0.0
    C3[1, :n] = p.e("u")
    C3[2, :n] = p.e("x0")
    R3 = np.diag([c.measurement_noise**2, c.winch_noise**2, c.boom_tip_noise**2])
    if tb > 0:
        M3 = kalman_gain(Ad, C3, Qw, R3)
        M1 = kalman_gain(Ad, C3[:1], Qw, R3[:1, :1])
    else:  # no offset state: the filter on the design model alone
        M3 = np.zeros((ne, 3))
        M1 = np.zeros((ne, 1))
        M3[:nz] = kalman_gain(mdl.Ad, C3[:, :nz], Qw[:nz, :nz], R3)
        M1[:nz] = kalman_gain(mdl.Ad, C3[:1, :nz], Qw[:nz, :nz], R3[:1, :1])
    Ge = np.zeros((1, ne))
    Ge[:, :nz] = G
    return p, Ad, Bd, Ge, M3, M1, C3, nz


def design_table(sc: HeaveScene, lengths: np.ndarray, a: np.ndarray, b: np.ndarray
                 ) -> tuple[DesignTable, pl.HeavePlant]:
    """Designs (LQR gain, Kalman gains, sampled model) at each ``(length, a, b)``."""
    rows = [_design(sc, float(ai), float(bi)) for ai, bi in zip(a, b, strict=True)]
    p = rows[0][0]
    return DesignTable(lengths=np.asarray(lengths, dtype=float), a=np.asarray(a, dtype=float),
                       b=np.asarray(b, dtype=float),
                       Ad=np.stack([r[1] for r in rows]), Bd=np.stack([r[2] for r in rows]),
                       G=np.stack([r[3] for r in rows]), M3=np.stack([r[4] for r in rows]),
                       M1=np.stack([r[5] for r in rows]), C3=rows[0][6], n=p.n,
                       nz=rows[0][7]), p


class KalmanEstimator:
    """The LQG's discrete Kalman filter (current estimator) on the design model.

    ``sensors = 3``: the unit's depth, the winch position and the boom-tip heave;
    ``sensors = 1``: the depth alone. The delay buffer is set to the known past commands.
    With a :class:`DesignTable` of several lengths the model and gains are interpolated at
    the current deployment length (a scheduled filter).
    """

    def __init__(self, table: DesignTable, sensors: int) -> None:
        self.table = table
        self.sensors = sensors
        self.C = table.C3[:sensors]
        self.xp = np.zeros(table.Ad.shape[1])

    def estimate(self, y: np.ndarray, buffer: np.ndarray, length: float
                 ) -> tuple[np.ndarray, tuple[np.ndarray, ...]]:
        """Measurement update; returns the estimate and the interpolated design."""
        des = self.table.at(length)
        M = des[3] if self.sensors == 3 else des[4]
        xh = self.xp + M @ (y[: self.sensors] - self.C @ self.xp)
        n, nz = self.table.n, self.table.nz
        xh[n:nz] = buffer
        return xh, des

    def predict(self, xh: np.ndarray, u0: float, des: tuple[np.ndarray, ...]) -> None:
        """Time update with the command just issued."""
        self.xp = des[0] @ xh + des[1][:, 0] * u0


class _Ctrl:
    """A controller on estimated states: ``__call__(y, u_prev, buffer, length, fore)``."""

    def __init__(self, name: str, table: DesignTable | None, mpc: mpc_mod.LinearMPC | None
                 ) -> None:
        self.name = name
        self.est = None if table is None else KalmanEstimator(table, 1 if name == "lqg" else 3)
        self.mpc = mpc
        self.times: list[float] = []
        self.failures = 0

    def __call__(self, y: np.ndarray, u_prev: float, buffer: np.ndarray, length: float,
                 fore: np.ndarray | None) -> float:
        if self.est is None:
            return 0.0
        xh, des = self.est.estimate(y, buffer, length)
        if self.mpc is not None:
            z = xh[: self.est.table.nz]
            D = self.mpc.preview_correction(z, fore) if fore is not None else None
            r = self.mpc.step(z, u_prev, D)
            self.times.append(r.solve_time)
            if not r.success:
                self.failures += 1
            u0 = r.u0
        else:
            u0 = float(-(des[2] @ xh)[0])
        self.est.predict(xh, u0, des)
        return u0


# ------------------------------------------------------------------------------------------
# The closed loop
# ------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class CableTrace(Trace):
    """Time histories of one closed-loop run on the plant's sub-step grid.

    Attributes
    ----------
    t, x, x0, u, u_dot, u0 : numpy.ndarray
        As :class:`cable_ocp.heave.simulate.Trace`: time (s), unit heave relative to the
        static depth at the deployment length (m), boom-tip heave (m), winch output (m),
        winch speed (m/s), applied (delayed) command (m).
    tension_unit, tension_top : numpy.ndarray
        Tension at the unit and at the top, N.
    length : numpy.ndarray
        Deployment length ``L_dep`` (m; the unstretched length is ``L_dep - u``).
    min_element_tension : numpy.ndarray
        Smallest element tension over each sample, N (per control sample).
    """

    tension_unit: np.ndarray
    tension_top: np.ndarray
    length: np.ndarray
    min_element_tension: np.ndarray


@dataclass
class LoopRun:
    """One closed-loop run: trace, commands, solver statistics and the plant's health."""

    trace: CableTrace
    commands: np.ndarray
    times: np.ndarray
    failures: int
    plant_failed_at: float | None
    max_residual: float
    stop: tuple[str, str] | None = None


def run_status(run: LoopRun, plant: str = "cable") -> tuple[str, str]:
    """``(status, message)`` of a run, in the statuses of :mod:`cable_ocp.heave.simulate`:
    ``"unstable"`` / ``"non_finite"`` where the run left its bound or turned non-finite,
    ``"failed"`` where a step of the cable plant did not converge (the axial model cannot
    follow the line from there: a diverging loop or a slack line), else ``"solved"``."""
    if run.stop is not None:
        return run.stop
    if run.plant_failed_at is not None:
        return ("failed", f"the {plant} plant's Newton step did not converge at t = "
                f"{run.plant_failed_at:.2f} s (scaled residual {run.max_residual:.3g}); the "
                "run stops there (a diverging loop or a slack line, which the cable model "
                "cannot follow)")
    return "solved", "ran to the end with finite, bounded states"


@dataclass(frozen=True)
class Wave:
    """The boom-tip heave on the plant's sub-step grid and at the samples.

    ``t`` (s) and ``x0`` (m) on the sub-step grid ``h / substeps``; ``ldep`` the deployment
    length there (m).
    """

    t: np.ndarray
    x0: np.ndarray
    ldep: np.ndarray
    substeps: int


def make_wave(t_fine: np.ndarray, x0_fine: np.ndarray, h: float, substeps: int, n_ctrl: int,
              ldep: Callable[[np.ndarray], np.ndarray], fade_in: float) -> Wave:
    """Boom tip interpolated (linearly) from the sea's fine grid onto the plant's grid and
    faded in over ``fade_in`` s (the quintic ramp ``10 x^3 - 15 x^4 + 6 x^5``).

    The fade-in: the line starts at rest in its static state and the estimators know
    nothing of the sea at t = 0. Started in the sea's stationary state, the boom tip would
    begin metres away from the static top with a finite speed (a tension step down the
    line), and an estimator that first sees a displaced unit answers with commands of tens
    of metres (no limits on LQR and LQG). Faded in, both plants start smoothly; the fade-in
    ends inside the warm-up, before any metric is taken.
    """
    t = np.arange(n_ctrl * substeps + 1) * (h / substeps)
    x = np.clip(t / fade_in, 0.0, 1.0) if fade_in > 0 else np.ones_like(t)
    ramp = x**3 * (10.0 - 15.0 * x + 6.0 * x**2)
    return Wave(t=t, x0=ramp * np.interp(t, t_fine, x0_fine),
                ldep=np.asarray(ldep(t), dtype=float), substeps=substeps)


def _winch_maps(sc: HeaveScene, dt: float) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                     np.ndarray]:
    """Exact ZOH map of the winch over ``dt``: ``w+ = Phi w + Gam v``; rows for u and u'."""
    w = sc.winch
    blk = pl.winch_first(w.gain) if w.model == "first_order" else pl.winch_second(
        w.natural_frequency, w.damping_ratio)
    A, B = np.asarray(blk.A), np.asarray(blk.B)
    C, D = np.asarray(blk.C), np.asarray(blk.D)
    nw = A.shape[0]
    Mx = np.zeros((nw + 1, nw + 1))
    Mx[:nw, :nw] = A
    Mx[:nw, nw:] = B
    E = linalg.expm(Mx * dt)
    # outputs: row 0 u, row 1 u_dot (C, D of the block)
    return E[:nw, :nw], E[:nw, nw], np.vstack([C[0], C[1]]), np.array([D[0, 0], D[1, 0]])


def run_loop(sc: HeaveScene, plant: Any, ctrl: _Ctrl, wave: Wave, noise: np.ndarray,
             n_ctrl: int, progress: Callable[[int], None] | None = None,
             bound: float | None = None) -> LoopRun:
    """Simulate one controller on one plant (``_CableLoopPlant`` or ``_ModelLoopPlant``).

    ``noise``: shape (n_ctrl + 1, 3), the measurement noise of depth, winch and boom tip
    (m) per sample (the same for every controller and plant). The run stops (the rest of
    the trace NaN) where the plant's step fails (or the plant refuses the sample, with its
    reason as the run's status), a state or command turns non-finite, or
    the unit heave or winch output leaves ``bound`` (m; default
    :data:`cable_ocp.heave.simulate.UNSTABLE_FACTOR` times the largest boom-tip heave, as
    :func:`cable_ocp.heave.simulate.compare`).
    """
    if bound is None:
        from cable_ocp.heave.simulate import UNSTABLE_FACTOR

        bound = UNSTABLE_FACTOR * max(float(np.max(np.abs(wave.x0))), 1e-3)
    stop = None
    c = sc.controller
    h = c.sample_time
    d = int(round(sc.winch.delay / h))
    m = wave.substeps
    dt = h / m
    Phi, Gam, Cw, Dw = _winch_maps(sc, dt)
    nw = Phi.shape[0]
    nfine = n_ctrl * m
    # NaN where a run that failed (a cable step that did not converge) stops
    xs, us, uds, vs, tu, tt = (np.full(nfine + 1, np.nan) for _ in range(6))
    tmin = np.full(n_ctrl, np.nan)
    cmds = np.zeros(n_ctrl)
    w = np.zeros(nw)
    t_u0, t_t0 = plant.start(float(wave.x0[0]), float(wave.ldep[0]))
    xs[0], tu[0], tt[0] = plant.heave, t_u0, t_t0
    buf = np.zeros(d)
    u_prev = 0.0
    npv = int(round(c.preview_time / h))
    x0_samples = wave.x0[::m]
    for k in range(n_ctrl):
        if progress is not None and k % 100 == 0:
            progress(k)
        i = k * m
        u_now = float(Cw[0] @ w)
        y = np.array([plant.heave, u_now, wave.x0[i]]) + noise[k]
        fore = x0_samples[k: k + npv + 1] if npv > 0 else None
        u0 = ctrl(y, u_prev, buf.copy(), float(wave.ldep[i]), fore)
        cmds[k] = u0
        u_prev = u0
        if d:
            v = buf[0]
            buf = np.concatenate([buf[1:], [u0]])
        else:
            v = u0
        upts = np.empty(m + 1)
        upts[0] = u_now
        for j in range(m):
            uds[i + j] = float(Cw[1] @ w + Dw[1] * v)
            us[i + j] = upts[j]
            vs[i + j] = v
            w = Phi @ w + Gam * v
            upts[j + 1] = float(Cw[0] @ w)
        heave, t_unit, t_top, t_mn = plant.advance(k, upts, wave.x0[i: i + m + 1],
                                                    wave.ldep[i: i + m + 1])
        xs[i + 1: i + m + 1] = heave
        tu[i + 1: i + m + 1] = t_unit
        tt[i + 1: i + m + 1] = t_top
        tmin[k] = t_mn
        if plant.failed_at is not None:
            stop = getattr(plant, "stop", None)  # a reason the plant gave, if any
            break
        last = np.concatenate([heave, upts, [u0]])
        if not np.all(np.isfinite(last)):
            stop = ("non_finite", f"a state or command became non-finite at t = "
                    f"{(k + 1) * h:.2f} s; the run stops there")
        elif float(np.max(np.abs(last[:-1]))) > bound:
            stop = ("unstable", f"the unit heave or winch output left {bound:.4g} m "
                    f"(1000 times the largest boom-tip heave) at t = {(k + 1) * h:.2f} s: "
                    "the closed loop is unstable; the run stops there")
        if stop is not None:
            xs[i + 1: i + m + 1] = np.nan
            break
    if plant.failed_at is None and stop is None:
        # the last point: the command applied over the last step (as simulate.compare)
        us[nfine] = float(Cw[0] @ w)
        uds[nfine] = float(Cw[1] @ w + Dw[1] * vs[nfine - 1])
        vs[nfine] = vs[nfine - 1]
    tr = CableTrace(t=wave.t, x=xs, x0=wave.x0, u=us, u_dot=uds, u0=vs, tension_unit=tu,
                    tension_top=tt, length=wave.ldep, min_element_tension=tmin)
    failed = None if plant.failed_at is None else float(plant.failed_at * h)
    return LoopRun(trace=tr, commands=cmds, times=np.array(ctrl.times), failures=ctrl.failures,
                   plant_failed_at=failed, max_residual=plant.max_residual, stop=stop)


# ------------------------------------------------------------------------------------------
# compare() on the cable
# ------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class CableComparison(Comparison):
    """Result of :func:`compare_cable` (the fields of
    :class:`cable_ocp.heave.simulate.Comparison` plus the cable's).

    Attributes
    ----------
    statuses, messages : dict
        Controller name -> status (:data:`cable_ocp.heave.simulate.STATUSES`) of its run on
        the plant, and its explanation.
    passive_heave_rms : float or None
        Heave RMS of the passive run on the same plant and sea (the baseline of
        ``reduction_pct``), m.
    warnings : list of str
        Remarks that do not change a status.
    json_extra : dict
        Top-level JSON fields: ``plant``, ``design_model`` (a, b used and where from),
        ``identified`` (see :func:`cable_ocp.heave.identify_cable.identified_json`).
    predicted_traces : dict
        The runs on the design model (same estimator, sensors, noise, sea).
    """

    json_extra: dict = field(default_factory=dict)
    predicted_traces: dict = field(default_factory=dict)


#: the smallest damping b (s) a design takes: an identified b below it (a line without drag
#: gives b ~ -1e-4 s, the fit's RK4 dissipating a little where the plant's midpoint rule
#: dissipates nothing) is raised to it, with a warning
B_MIN = 1e-6


def design_damping(b: float, where: str) -> tuple[float, str | None]:
    """``(b used by the design, warning or None)``: an identified ``b`` below :data:`B_MIN`
    is raised to it (the unit model (6.2) needs b >= 0)."""
    if b >= B_MIN:
        return float(b), None
    return B_MIN, (f"{where}: the identified b = {b:.3g} s is below {B_MIN:g} s (a line with "
                   "almost no damping, or an experiment too short for its resonance); the "
                   f"design uses b = {B_MIN:g} s")


def design_scene(sc: HeaveScene, identification: Any | None, dyn: DynamicScene
                 ) -> tuple[HeaveScene, str]:
    """The heave scene with its design model: identified ``a, b`` (and ``b_quadratic``)
    unless ``[unit] a`` and ``b`` are given in the file; the unit's mass and static tension
    from the cable scene when not given. Returns ``(scene, source)``."""
    given = isinstance(sc.raw.get("unit"), dict) and {"a", "b"} <= set(sc.raw["unit"])
    unit = sc.unit
    kw: dict[str, Any] = {"cable_scene": None}
    source = "given"
    if not given:
        if identification is None:
            raise CableOCPError("[unit] a and b are not given and nothing was identified")
        kw.update(a=identification.linear.a,
                  b=design_damping(identification.linear.b, "design model")[0])
        if identification.quadratic is not None and "b_quadratic" not in sc.raw["unit"]:
            kw["b_quadratic"] = identification.quadratic.b
        source = "identified"
    if not unit.mass > 0 and dyn.unit is not None:
        kw["mass"] = dyn.unit.mass + dyn.unit.added_mass[2]
        kw["static_tension"] = dyn.unit.weight_in_water
    return replace(sc, unit=replace(unit, **kw),
                   simulation=replace(sc.simulation, plant="model")), source


#: the cable-plant fields of a controller's metrics (None where the run is not solved)
CABLE_FIELDS = ("tension_unit_min", "tension_unit_max", "tension_top_min", "tension_top_max",
                "slack_samples", "slack_first_time_s", "plant_failed_at_s")


def _metrics_cable(sc: HeaveScene, run: LoopRun, name: str, G: np.ndarray | None) -> dict:
    """The metrics of :func:`cable_ocp.heave.simulate.compare` and the cable's; every value
    None (JSON null) but ``energy_index``, the solve time and ``plant_failed_at_s`` when
    the run is not solved."""
    from cable_ocp.heave.simulate import _metrics

    energy = (float(np.sqrt(np.sum(G**2))) if name in ("lqr", "lqg") and G is not None
              else None)
    times = run.times if name == "mpc" else None
    if run_status(run)[0] != "solved":
        d = dict.fromkeys(("heave_rms", "reduction_pct", "peak_winch_speed", "max_stroke",
                           "max_constraint_violation", "winch_speed_rms") + CABLE_FIELDS)
        d["energy_index"] = energy
        d["solve_time_median_s"] = (float(np.median(times)) if times is not None
                                    and times.size else None)
        d["plant_failed_at_s"] = run.plant_failed_at
        return d
    base = _metrics(sc, run.trace, run.commands, energy, times, sc.controller.sample_time)
    tr = run.trace
    keep = tr.t >= sc.simulation.warmup - 1e-12
    h = sc.controller.sample_time
    kk = np.arange(tr.min_element_tension.size) * h >= sc.simulation.warmup - 1e-12
    slack = tr.min_element_tension <= 0.0
    first = np.flatnonzero(slack & kk)
    return {**base.as_dict(),
            "tension_unit_min": float(np.min(tr.tension_unit[keep])),
            "tension_unit_max": float(np.max(tr.tension_unit[keep])),
            "tension_top_min": float(np.min(tr.tension_top[keep])),
            "tension_top_max": float(np.max(tr.tension_top[keep])),
            "slack_samples": int(np.count_nonzero(slack[kk])),
            "slack_first_time_s": float(first[0] * h) if first.size else None,
            "plant_failed_at_s": run.plant_failed_at}


@dataclass(frozen=True)
class CableMetrics:
    """Per-controller metrics on the cable plant (JSON fields).

    The fields of :class:`cable_ocp.heave.simulate.Metrics` for the run on the cable, and:
    ``heave_rms_predicted`` (m) and ``reduction_predicted_pct`` (%) of the same controller
    (estimator, sensors, noise, sea) on the design model; ``tension_unit_min/max``,
    ``tension_top_min/max`` (N, after the warm-up); ``slack_samples`` (samples after the
    warm-up with an element tension <= 0), ``slack_first_time_s`` (s or None);
    ``plant_failed_at_s`` (a Newton step of the cable did not converge there, or None).
    """

    values: dict

    def as_dict(self) -> dict:
        """Plain dict for JSON."""
        return dict(self.values)

    def __getattr__(self, key: str) -> Any:
        try:
            return self.__dict__["values"][key]
        except KeyError as exc:
            raise AttributeError(key) from exc


def _mpc_settings(sd: HeaveScene) -> mpc_mod.MPCSettings:
    c = sd.controller
    return mpc_mod.MPCSettings(
        horizon=c.horizon, sample_time=c.sample_time, q=c.q, r=c.r, solver=c.solver,
        stroke_max=sd.winch.stroke_max, speed_max=sd.winch.speed_max,
        command_rate_max=sd.winch.command_rate_max, accel_max=sd.winch.accel_max,
        tension_min=sd.winch.tension_min, unit_mass=sd.unit.mass,
        static_tension=sd.unit.static_tension, tension_penalty=c.tension_penalty,
        preview_time=c.preview_time, terminal=c.terminal,
        nonlinear_b=sd.unit.b_quadratic if sd.unit.model == "quadratic" else 0.0)


def heave_rms(t: np.ndarray, x: np.ndarray, warmup: float) -> float:
    """RMS of ``x`` over ``t >= warmup``, m."""
    keep = t >= warmup - 1e-12
    return float(math.sqrt(np.mean(x[keep] ** 2)))
