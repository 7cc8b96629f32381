"""The closed loop on the cable plant (or on the design model as the plant): the boom-tip
wave, the loop plants, the run and its status.

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

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy import linalg

from cable_ocp.heave import plant as pl
from cable_ocp.heave.axial_plant import AxialCablePlant
from cable_ocp.heave.controllers import _Ctrl
from cable_ocp.heave.simulate import Trace
from cable_ocp.scene.heave import HeaveScene

__all__ = ["CableTrace", "LoopRun", "Wave", "make_wave", "run_loop", "run_status"]


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

