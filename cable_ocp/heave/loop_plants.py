"""The plants of the closed loop (:class:`cable_ocp.heave.closed_loop.LoopPlant`).

* :class:`UnitWinchPlant`: the design model (6.2) or (6.3) and its winch ((6.1) or the
  second-order winch) integrated together by RK4 on the sub-steps ``h / substeps``, with
  the boom-tip heave linear between grid points, in the sea and vessel states sampled
  exactly (:func:`cable_ocp.heave.design_loop.wave_realisation`). Its state (unit, winch, sea,
  vessel) is measurable for full-state feedback, and the unit's depth with white noise
  (the plant of :func:`cable_ocp.heave.design_loop.compare`).
* :class:`WinchedLine`: a line under the winch. The winch is integrated exactly (ZOH) on
  the sub-steps and is a position source, as in (6.4); the line is :class:`CableLine` (the
  cable plant: :class:`cable_ocp.heave.axial_plant.AxialCablePlant` or a plant of
  :mod:`cable_ocp.heave.cable_models`, heave measured from the static depth at the
  deployment length) or :class:`ModelLine` (the design model (6.2)/(6.3) by RK4 with
  ``x0 + u`` linear per sub-step: the prediction beside the cable). The controllers see what
  a real system measures, once per sample, each with its own white noise: the unit's depth
  (``[controller] measurement_noise``), the winch position (``winch_noise``) and the
  boom-tip heave from the vessel's motion sensor (``boom_tip_noise``).

Both integrate the unit model with :func:`cable_ocp.heave.plant.unit_acceleration` (its one
home); they differ in the winch (inside the RK4 step, or exact) because each is the plant of
its own comparison. The passive compensator's piston (:class:`Piston`, the one home of its
law in the loop) goes with either: RK4 with the design model (:class:`UnitWinchPlant`,
:class:`ModelLine`), an implicit-midpoint step with each of the cable's time steps
(:class:`CableLine`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from scipy import linalg

from cable_ocp.heave import plant as pl
from cable_ocp.heave.closed_loop import CableTrace, LoopPlant, Sample, Trace, Wave
from cable_ocp.heave.discrete import delay_steps
from cable_ocp.heave.drive import design_tension, drive_series
from cable_ocp.heave.estimators import Observation
from cable_ocp.heave.plant import unit_acceleration
from cable_ocp.physics.gas_spring import gas_force, gas_stiffness
from cable_ocp.scene.heave import HeaveScene, compensator_pressure

__all__ = ["CableLine", "ModelLine", "Piston", "UnitWinchPlant", "WinchedLine", "winch_maps"]


class Piston:
    """The massless piston of the in-line passive compensator: its one law in the loop.

    ``c delta' = T - F_gas(delta)`` (``T`` the line tension the cylinder carries, N;
    :func:`cable_ocp.physics.gas_spring.gas_force`), the stroke ``delta`` (m, positive into
    the gas: it lowers the line's top by ``delta``) held at the end stops ``|delta| <=
    stroke_max`` while the force pushes into them. The design model's plants integrate
    :meth:`rate` by RK4 and :meth:`clip` after each step (:class:`UnitWinchPlant`,
    :class:`ModelLine`); the cable plant, whose top tension answers the stroke through the
    stiff top element, takes :meth:`implicit_step` (:class:`CableLine`).

    Parameters
    ----------
    sc : HeaveScene
        A scene with ``[passive_compensator]`` (its static pressure from
        :func:`cable_ocp.scene.heave.compensator_pressure`).
    """

    #: force residual of :meth:`implicit_step`, relative to the static gas force
    TOLERANCE = 1e-10
    #: Newton iterations of :meth:`implicit_step` before it gives up
    MAX_ITERATIONS = 8

    def __init__(self, sc: HeaveScene) -> None:
        pc = sc.passive_compensator
        self.gas = (compensator_pressure(sc), pc.gas_volume, pc.area, pc.polytropic_exponent)
        self.c, self.smax = pc.damping, pc.stroke_max
        self.f0 = self.gas[0] * pc.area
        #: the line's tangent stiffness at the top seen by the stroke (N/m), learnt by
        #: :meth:`implicit_step` (a secant)
        self.k_line: float | None = None

    def rate(self, d: float, tension: float) -> float:
        """``delta'`` (m/s) at the stroke ``d`` (m) under the tension ``tension`` (N); 0 at an
        end stop the force pushes into.

        Parameters
        ----------
        d : float
            The stroke, m.
        tension : float
            The tension the cylinder carries, N.
        """
        rate = (tension - gas_force(d, *self.gas)) / self.c
        if (d >= self.smax and rate > 0) or (d <= -self.smax and rate < 0):
            return 0.0
        return rate

    def clip(self, d: float) -> float:
        """The stroke ``d`` (m) held inside the end stops."""
        return min(max(d, -self.smax), self.smax)

    def implicit_step(self, d0: float, dt: float, t_start: float,
                      tension_of: Callable[[float], Any]) -> tuple[float, Any, float]:
        """One implicit-midpoint step of the stroke, then the stops:
        ``c (d1 - d0) / dt = (T0 + T1) / 2 - F_gas((d0 + d1) / 2)``.

        Implicit because the stroke is stiff against the line: ``T`` answers ``d1``
        through the top element (its stiffness and its internal damping, ``dT/dd ~ -EA / l
        - c_a / (l dt)``), so ``k dt / c`` is far above the stability limit of an explicit
        step. The midpoint form is the cable's own step (the cable plants are implicit
        midpoint, the top linear over the step), second order like it; the tension at the
        step's end alone (backward Euler) goes unstable against the top element's damping
        on a fine mesh. Solved by Newton's method with the line's stiffness from a secant
        (exact for a linear line after one correction).

        Parameters
        ----------
        d0 : float
            The stroke at the step's start, m.
        dt : float
            The step, s.
        t_start : float
            ``T0``: the top tension at the step's start, N.
        tension_of : callable
            ``tension_of(d1) -> (T1, result)``: the line stepped with the stroke ``d1`` at
            the step's end (its top at ``x0 + u - d1``), its top tension there ``T1`` (N) and
            what the step returns (kept for the accepted ``d1``).

        Returns
        -------
        d1 : float
            The stroke at the step's end, m.
        result
            ``tension_of(d1)[1]``.
        residual : float
            The force residual, relative to the static gas force (0 at a stop).
        """
        def resid(d: float, tension: float) -> float:
            return (self.c * (d - d0) / dt - 0.5 * (t_start + tension)
                    + gas_force(0.5 * (d0 + d), *self.gas))

        d = d0
        tension, res = tension_of(d)
        f = resid(d, tension)
        tol = self.TOLERANCE * self.f0
        for _ in range(self.MAX_ITERATIONS):
            if abs(f) <= tol:
                break
            k = self.k_line
            if k is None:  # the first step: the line's stiffness by a difference
                eps = 1e-6 * max(self.smax, 1e-3)
                t_eps = tension_of(d + eps)[0]
                k = self.k_line = max((tension - t_eps) / eps, 0.0)
            slope = self.c / dt + 0.5 * (k + gas_stiffness(0.5 * (d0 + d), *self.gas))
            d_new = self.clip(d - f / slope)
            if d_new == d:  # held at a stop
                break
            t_new, res_new = tension_of(d_new)
            k_sec = -(t_new - tension) / (d_new - d)
            if np.isfinite(k_sec) and k_sec > 0:
                self.k_line = float(k_sec)
            d, tension, res = d_new, t_new, res_new
            f = resid(d, tension)
        if abs(d) >= self.smax:  # at a stop: the force holds it there
            return d, res, 0.0
        return d, res, abs(f) / self.f0


class UnitWinchPlant(LoopPlant):
    """The design model with its winch, RK4 on the sub-steps, in the exactly sampled sea.

    Parameters
    ----------
    sc : HeaveScene
        The scene: unit (``a``, ``b``, ``model``, ``b_quadratic``), winch, controller
        (sample time, preview), ``[simulation] substeps``.
    p : HeavePlant
        Its plant (6.28) (the states' order: unit, winch, vessel, sea).
    t, x0 : numpy.ndarray
        The sea's grid (s, step ``h / substeps``) and the boom-tip heave there (m), long
        enough for the preview.
    sea_states : numpy.ndarray
        The vessel and sea states on that grid (the plant's states from the vessel block on).
    noise : numpy.ndarray, shape (n_ctrl + 1,)
        The depth sensor's noise per sample, m.
    n_ctrl : int
        Control samples (the trace's length).
    phc : bool
        With the passive compensator of ``[passive_compensator]`` (``p`` then has its block
        ``"comp"``): the gas spring exact (:func:`cable_ocp.physics.gas_spring.
        compensator_force`), the massless piston's stroke ``c delta' = T - F_gas(delta)``
        with ``T = T0 + (m/a)(x0 + u - delta - x)``, held at the end stops
        ``|delta| <= stroke_max`` while the force pushes into them (:class:`Piston`).
    """

    def __init__(self, sc: HeaveScene, p: pl.HeavePlant, t: np.ndarray, x0: np.ndarray,
                 sea_states: np.ndarray, noise: np.ndarray, n_ctrl: int,
                 phc: bool = False) -> None:
        c, u, w = sc.controller, sc.unit, sc.winch
        self.sample_time = h = c.sample_time
        self.substeps = m = sc.simulation.substeps
        self.hs = h / m
        self.delay = delay_steps(w.delay, h)
        self.a, self.b = u.a, u.b
        self.bq = u.b_quadratic if u.model == "quadratic" else 0.0
        self.quad = u.model == "quadratic"
        self.first = w.model == "first_order"
        self.K, self.wn, self.zeta = w.gain, w.natural_frequency, w.damping_ratio
        self.nuw = 3 if self.first else 4
        self.n = p.n
        self.lo = p.blocks["vessel"].start
        self.t, self.x0, self.sea, self.noise = t, x0, sea_states, noise
        self.n_fore = int(round(c.preview_time / self.hs)) if c.preview_time > 0 else None
        self.nfine = n_ctrl * m
        self.scene = sc
        self.phc = phc
        self.ns = self.nuw + (1 if phc else 0)
        if phc:
            self.ic = p.blocks["comp"].start
            self.piston = Piston(sc)
            self.kc, self.t0 = sc.unit.mass / u.a, sc.unit.static_tension
        self.s = np.zeros(self.ns)
        self.deltas: list[float] = [0.0]

    def _f(self, s: np.ndarray, x0: float, v: float) -> np.ndarray:
        top = x0 + s[2] - (s[self.nuw] if self.phc else 0.0)
        acc = unit_acceleration(s[0], s[1], top, self.a, self.b, self.bq, self.quad)
        if self.first:
            out = [s[1], acc, self.K * (v - s[2])]
        else:
            wn = self.wn
            out = [s[1], acc, s[3], wn**2 * (v - s[2]) - 2 * self.zeta * wn * s[3]]
        if self.phc:
            out.append(self.piston.rate(s[self.nuw], self.t0 + self.kc * (top - s[0])))
        return np.array(out)

    def start(self) -> dict[str, float]:
        self.s = np.zeros(self.ns)  # the unit and winch at rest; the sea stationary
        self.deltas = [0.0]
        return {"x": float(self.s[0])}

    def observe(self, k: int) -> Observation:
        i = k * self.substeps
        z = np.empty(self.n)
        z[: self.nuw] = self.s[: self.nuw]
        if self.phc:
            z[self.ic] = self.s[self.nuw]
        z[self.lo:] = self.sea[i]
        fore = (self.x0[i: i + self.n_fore + 1: self.substeps] if self.n_fore is not None
                else None)
        return Observation(y=np.array([self.s[0] + self.noise[k]]), state=z, forecast=fore)

    def advance(self, k: int, v: float) -> Sample:
        """As :meth:`cable_ocp.heave.closed_loop.LoopPlant.advance`.

        Parameters
        ----------
        k : int
            The sample.
        v : float
            The applied (delayed) command, m.
        """
        m, hs, f, x0 = self.substeps, self.hs, self._f, self.x0
        i = k * m
        s = self.s
        xs, us, uds = np.empty(m), np.empty(m + 1), np.empty(m)
        for j in range(m):
            ii = i + j
            us[j] = s[2]
            uds[j] = self.K * (v - s[2]) if self.first else s[3]
            xa, xb = x0[ii], x0[ii + 1]
            xm = 0.5 * (xa + xb)
            k1 = f(s, xa, v)
            k2 = f(s + hs / 2 * k1, xm, v)
            k3 = f(s + hs / 2 * k2, xm, v)
            k4 = f(s + hs * k3, xb, v)
            s = s + hs / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            if self.phc:  # the end stops
                s[self.nuw] = self.piston.clip(s[self.nuw])
                self.deltas.append(float(s[self.nuw]))
            xs[j] = s[0]
        us[m] = s[2]
        self.s = s
        return Sample(x=xs, u=us, u_dot=uds)

    def end_speed(self, v: float) -> float:
        # the left limit K (v - u(T)) of the first-order winch
        return self.K * (v - self.s[2]) if self.first else self.s[3]

    def trace(self, x: np.ndarray, u: np.ndarray, u_dot: np.ndarray, u0: np.ndarray,
              channels: dict[str, np.ndarray], per_sample: np.ndarray) -> Trace:  # noqa: ARG002
        """As :meth:`cable_ocp.heave.closed_loop.LoopPlant.trace`.

        Parameters
        ----------
        x, u, u_dot, u0 : numpy.ndarray
            The loop's histories (:meth:`cable_ocp.heave.closed_loop.LoopPlant.trace`).
        channels : dict
            Empty: this plant has no channels.
        per_sample : numpy.ndarray
            Not used.
        """
        n = self.nfine + 1
        x0 = self.x0[:n]
        delta = None
        if self.phc:
            delta = np.full(n, np.nan)
            delta[: len(self.deltas)] = self.deltas[:n]
        tension = design_tension(self.scene, x, x0, u, delta)
        torque, power = drive_series(self.scene, tension, u, u_dot, u0)
        return Trace(self.t[:n], x, x0, u, u_dot, u0, tension=tension, torque=torque,
                     power=power, stroke_phc=delta)


def winch_maps(scene: HeaveScene, dt: float) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                   np.ndarray]:
    """Exact ZOH map of the winch over ``dt``: ``w+ = Phi w + Gam v``; its output rows for
    ``u`` and ``u'`` (``C``, ``D``).

    Parameters
    ----------
    scene : HeaveScene
        The scene's ``[winch]`` (first-order (6.1) or second-order).
    dt : float
        The sub-step, s.
    """
    w = scene.winch
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


class WinchedLine(LoopPlant):
    """A line under the winch (module docstring): the winch exact on the sub-steps.

    Parameters
    ----------
    sc : HeaveScene
        The scene: winch, controller (sample time, preview).
    line : CableLine or ModelLine
        The line the winch output pays in and out.
    wave : Wave
        The boom tip and the deployment length on the sub-step grid.
    noise : numpy.ndarray, shape (n_ctrl + 1, 3)
        The noise of the depth, winch and boom-tip sensors per sample, m.
    """

    channels = ("tension_unit", "tension_top")

    def __init__(self, sc: HeaveScene, line: Any, wave: Wave, noise: np.ndarray) -> None:
        c = sc.controller
        self.sample_time = h = c.sample_time
        self.substeps = m = wave.substeps
        self.delay = delay_steps(sc.winch.delay, h)
        self.Phi, self.Gam, self.Cw, self.Dw = winch_maps(sc, h / m)
        self.line, self.wave, self.noise = line, wave, noise
        self.scene = sc
        self.n_preview = int(round(c.preview_time / h))
        self.x0_samples = wave.x0[::m]
        self.w = np.zeros(self.Phi.shape[0])

    @property
    def failed_at(self) -> int | None:  # type: ignore[override]
        return self.line.failed_at

    @property
    def stop(self) -> tuple[str, str] | None:  # type: ignore[override]
        return getattr(self.line, "stop", None)

    @property
    def max_residual(self) -> float:  # type: ignore[override]
        return self.line.max_residual

    def start(self) -> dict[str, float]:
        self.w = np.zeros(self.Phi.shape[0])
        t_u0, t_t0 = self.line.start(float(self.wave.x0[0]), float(self.wave.ldep[0]))
        return {"x": self.line.heave, "tension_unit": t_u0, "tension_top": t_t0}

    def observe(self, k: int) -> Observation:
        i = k * self.substeps
        u_now = float(self.Cw[0] @ self.w)
        y = np.array([self.line.heave, u_now, self.wave.x0[i]]) + self.noise[k]
        npv = self.n_preview
        fore = self.x0_samples[k: k + npv + 1] if npv > 0 else None
        return Observation(y=y, length=float(self.wave.ldep[i]), forecast=fore)

    def advance(self, k: int, v: float) -> Sample:
        """As :meth:`cable_ocp.heave.closed_loop.LoopPlant.advance`.

        Parameters
        ----------
        k : int
            The sample.
        v : float
            The applied (delayed) command, m.
        """
        m = self.substeps
        i = k * m
        Phi, Gam, Cw, Dw = self.Phi, self.Gam, self.Cw, self.Dw
        w = self.w
        upts, uds = np.empty(m + 1), np.empty(m)
        upts[0] = float(Cw[0] @ w)
        for j in range(m):
            uds[j] = float(Cw[1] @ w + Dw[1] * v)
            w = Phi @ w + Gam * v
            upts[j + 1] = float(Cw[0] @ w)
        self.w = w
        wave = self.wave
        heave, t_unit, t_top, t_mn = self.line.advance(k, upts, wave.x0[i: i + m + 1],
                                                       wave.ldep[i: i + m + 1])
        return Sample(x=heave, u=upts, u_dot=uds,
                      channels={"tension_unit": t_unit, "tension_top": t_top}, per_sample=t_mn)

    def end_speed(self, v: float) -> float:
        return float(self.Cw[1] @ self.w + self.Dw[1] * v)

    def trace(self, x: np.ndarray, u: np.ndarray, u_dot: np.ndarray, u0: np.ndarray,
              channels: dict[str, np.ndarray], per_sample: np.ndarray) -> CableTrace:
        """As :meth:`cable_ocp.heave.closed_loop.LoopPlant.trace`.

        Parameters
        ----------
        x, u, u_dot, u0 : numpy.ndarray
            The loop's histories (:meth:`cable_ocp.heave.closed_loop.LoopPlant.trace`).
        channels : dict
            The tensions at the unit and the top, N.
        per_sample : numpy.ndarray
            The smallest element tension per sample, N.
        """
        wave = self.wave
        top = channels["tension_top"]
        torque, power = drive_series(self.scene, top, u, u_dot, u0)
        strokes = getattr(self.line, "strokes", None)
        stroke = None
        if strokes is not None:  # the compensator's stroke (NaN after a stopped run's end)
            stroke = np.full(wave.t.size, np.nan)
            stroke[: len(strokes)] = strokes[: wave.t.size]
        return CableTrace(t=wave.t, x=x, x0=wave.x0, u=u, u_dot=u_dot, u0=u0,
                          tension_unit=channels["tension_unit"],
                          tension_top=top, length=wave.ldep,
                          min_element_tension=per_sample, tension=top, torque=torque,
                          power=power, stroke_phc=stroke)


class CableLine:
    """The cable plant as the line: heave relative to the static depth at ``L_dep``.

    With a ``piston`` (:class:`Piston`) the passive compensator sits between the boom tip
    and the line's top: the top follows ``x0 + u - delta`` (the winch pays in ``u``, the
    cylinder lowers the top by its stroke ``delta``), and the stroke is stepped with the
    cable, one of the cable's time steps at a time (:meth:`Piston.implicit_step` on the
    top tension the cable's step returns).

    Parameters
    ----------
    plant : SampledCablePlant
        The cable stepped one sample per call (:func:`cable_ocp.heave.cable_models.
        cable_plant`), shared by the runs; with a ``piston``, one of the cable's time steps
        per call (the plant built with the cable scene's ``time_step`` as its sample).
    piston : Piston, optional
        The passive compensator at the top (None: the line hangs from the boom tip).
    """

    def __init__(self, plant: Any, piston: Piston | None = None) -> None:
        if piston is not None and plant.substeps != 1:
            raise ValueError("CableLine with a piston: the plant must take one time step "
                             "per call (internal error)")
        self.p = plant
        self.piston = piston
        self.substeps = plant.substeps
        self.x = plant.initial_state()
        self.heave = 0.0
        self.delta = 0.0
        self.t_top = 0.0
        #: the stroke at the sub-step points, m (None without a piston)
        self.strokes: list[float] | None = None if piston is None else [0.0]
        self.failed_at: int | None = None
        self.max_residual = 0.0
        #: (status, message) where the plant refused a sample (its ``out["stop"]``)
        self.stop: tuple[str, str] | None = None

    def start(self, x0_start: float, ldep0: float) -> tuple[float, float]:
        """The static state, at rest; returns the static tensions (at the unit, at the top,
        N).

        Parameters
        ----------
        x0_start : float
            The top's displacement at the start (the boom tip), m: the static line hangs
            from it.
        ldep0 : float
            The deployment length at the start, m.
        """
        self.x = self.p.initial_state()
        self.heave = x0_start  # the static line hangs from the displaced top, at rest
        self.delta = 0.0
        if self.piston is not None:
            self.strokes = [0.0]
        self.stop = None
        self.failed_at = None
        self.max_residual = 0.0
        tensions = self.p.static_tensions(ldep0)
        self.t_top = tensions[1]  # the piston's tension at the step's start, N
        return tensions

    def advance(self, k: int, u: np.ndarray, x0: np.ndarray, ldep: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        """Advance one sample; returns the heave, the tensions at the unit and the top at
        the sub-step ends (m, N, N) and the smallest element tension (N).

        Parameters
        ----------
        k : int
            The sample.
        u, x0, ldep : numpy.ndarray, shape (m + 1,)
            Winch output, boom-tip heave and deployment length at the sub-step points, m.
        """
        if self.piston is not None:
            x, out = self._advance_piston(ldep - u, x0)
        else:
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

    def _advance_piston(self, lengths: np.ndarray, x0: np.ndarray
                        ) -> tuple[np.ndarray, dict[str, Any]]:
        """The sample's time steps one by one, each with the piston's implicit step; the
        outputs as :meth:`SampledCablePlant.advance` returns them for the whole sample."""
        p, piston = self.p, self.piston
        m = lengths.size - 1
        x = self.x
        cols: dict[str, Any] = {k: np.empty(m) for k in ("z_unit", "v_unit", "t_unit",
                                                        "t_top")}
        t_min, rmax, worst = np.inf, 0.0, 0.0
        stop = None
        for j in range(m):
            d0 = self.delta
            lj = lengths[j: j + 2]
            za = p.z_top0 + x0[j] - d0

            def tension_of(d1: float, x: np.ndarray = x, lj: np.ndarray = lj,
                           za: float = za, j: int = j) -> tuple[float, Any]:
                r = p.advance(x, lj, np.array([za, p.z_top0 + x0[j + 1] - d1]))
                return float(r[1]["t_top"][0]), r

            d1, (x, out), res = piston.implicit_step(d0, p.dt, self.t_top, tension_of)
            self.t_top = float(out["t_top"][0])
            self.delta = d1
            self.strokes.append(d1)
            for k in cols:
                cols[k][j] = out[k][0]
            t_min = min(t_min, out["t_min"])
            rmax = max(rmax, out["residual"])
            worst = max(worst, res)
            if "stop" in out and stop is None:
                stop = out["stop"]
        out = {**cols, "t_min": t_min, "residual": rmax}
        if not worst <= 1e3 * piston.TOLERANCE:  # the piston's Newton did not converge
            out["residual"] = np.inf
        if stop is not None:
            out["stop"] = stop
        return x, out


class ModelLine:
    """The design model (6.2) or (6.3) as the line, RK4 with ``x0 + u`` linear per step.

    Tension at the unit ``T0 + (m/a)(x0 + u - x)`` (the model's own, :mod:`.mpc`); the
    model has no top tension (reported as the same dynamic part on the static top tension).

    Parameters
    ----------
    a, b, b_quadratic : float
        The model's coefficients: s^2, s, s^2/m.
    quadratic : bool
        (6.3) instead of (6.2).
    substeps : int
        Sub-steps per sample.
    dt : float
        Sub-step, s.
    mass : float
        Unit mass with its added mass, kg.
    t_unit0, t_top0 : float
        Static tensions at the unit and the top, N.
    piston : Piston, optional
        The passive compensator at the top (as :class:`CableLine`): the input is ``x0 + u
        - delta``, the stroke integrated with the unit by the same RK4 under the top
        tension ``t_top0 + (m/a)(x0 + u - delta - x)``, as :class:`UnitWinchPlant` does.
    """

    def __init__(self, a: float, b: float, b_quadratic: float, quadratic: bool,
                 substeps: int, dt: float, mass: float, t_unit0: float, t_top0: float,
                 piston: Piston | None = None) -> None:
        self.a, self.b, self.bq, self.quad = a, b, b_quadratic, quadratic
        self.substeps, self.dt = substeps, dt
        self.k = mass / a
        self.t0, self.tt0 = t_unit0, t_top0
        self.piston = piston
        self.s = [0.0, 0.0, 0.0]
        self.heave = 0.0
        self.failed_at: int | None = None
        self.max_residual = 0.0
        #: the stroke at the sub-step points, m (None without a piston)
        self.strokes: list[float] | None = None if piston is None else [0.0]

    def start(self, x0_start: float, ldep0: float) -> tuple[float, float]:  # noqa: ARG002
        """At rest; returns the static tensions (N).

        Parameters
        ----------
        x0_start : float
            The boom tip at the start, m: the unit starts there.
        ldep0 : float
            The deployment length at the start, m (not used by the model).
        """
        self.s = [x0_start, 0.0, 0.0]
        self.heave = x0_start
        if self.piston is not None:
            self.strokes = [0.0]
        return self.t0, self.tt0

    def _f(self, x: float, v: float, d: float, inp: float) -> tuple[float, float, float]:
        top = inp - d
        rate = (0.0 if self.piston is None
                else self.piston.rate(d, self.tt0 + self.k * (top - x)))
        return v, unit_acceleration(x, v, top, self.a, self.b, self.bq, self.quad), rate

    def advance(self, k: int, u: np.ndarray, x0: np.ndarray, ldep: np.ndarray  # noqa: ARG002
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        """As :meth:`CableLine.advance`.

        Parameters
        ----------
        k : int
            The sample (not used).
        u, x0 : numpy.ndarray, shape (m + 1,)
            Winch output and boom-tip heave at the sub-step points, m.
        ldep : numpy.ndarray
            Deployment length there, m (not used).
        """
        m, dt, f = self.substeps, self.dt, self._f
        x, v, d = self.s
        inp = (x0 + u).tolist()
        xs, ds = np.empty(m), np.empty(m)
        for j in range(m):
            ia, ib = inp[j], inp[j + 1]
            im = 0.5 * (ia + ib)
            k1 = f(x, v, d, ia)
            k2 = f(x + 0.5 * dt * k1[0], v + 0.5 * dt * k1[1], d + 0.5 * dt * k1[2], im)
            k3 = f(x + 0.5 * dt * k2[0], v + 0.5 * dt * k2[1], d + 0.5 * dt * k2[2], im)
            k4 = f(x + dt * k3[0], v + dt * k3[1], d + dt * k3[2], ib)
            x += dt / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            v += dt / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
            if self.piston is not None:  # the end stops
                d = self.piston.clip(d + dt / 6 * (k1[2] + 2 * k2[2] + 2 * k3[2] + k4[2]))
                self.strokes.append(d)
            xs[j], ds[j] = x, d
        self.s = [x, v, d]
        self.heave = x
        dyn = self.k * (x0[1:] + u[1:] - ds - xs)
        return xs, self.t0 + dyn, self.tt0 + dyn, float(np.min(self.t0 + dyn))
