"""The closed loop: any plant with any controller, and the run's trace and status.

:func:`run_loop` runs one :class:`Controller <cable_ocp.heave.controllers.Controller>` on one
:class:`LoopPlant` for ``n_ctrl`` control samples of ``h`` seconds. Per sample: the plant's
observation (:meth:`LoopPlant.observe`), the controller's command (held over the sample,
ZOH), the command the winch applies, delayed by exactly ``tau = d h``
(:class:`cable_ocp.heave.delay.DelayLine`), and the plant advanced over the sample on its
``m`` sub-steps (:meth:`LoopPlant.advance`). The plants (:mod:`cable_ocp.heave.loop_plants`):
the design model (6.2)/(6.3) with its winch, integrated by RK4 on the sub-steps in the sea
sampled exactly (:func:`cable_ocp.heave.design_loop.compare`); and a line under the winch: the
cable (axial, planar or lumped3d) or the design model, with the winch integrated exactly
(:func:`cable_ocp.heave.cable_compare.compare_cable`, the deployment).

The run stops (the rest of the trace NaN) where

* the command is not finite (``"non_finite"``; before it is applied);
* the plant's step fails or the plant refuses the sample (``"failed"``, with the plant's
  reason: :func:`run_status`);
* the unit heave or winch output at a sub-step is not finite (``"non_finite"``) or leaves
  ``bound`` (``"unstable"``; by default :data:`UNSTABLE_FACTOR` times the largest boom-tip
  heave: a stable loop moves them by at most its resonance amplification times the boom tip,
  ~1/(2 zeta) = 14 for the shipped units).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from cable_ocp.heave.controllers import Controller
from cable_ocp.heave.delay import DelayLine
from cable_ocp.heave.estimators import Observation
from cable_ocp.numerics.ramp import smoothstep
from cable_ocp.status import Status

__all__ = ["INTERRUPTED", "STATUSES", "UNSTABLE_FACTOR", "CableTrace", "LoopPlant", "LoopRun",
           "Sample", "Trace", "Wave", "make_wave", "run_loop", "run_status", "unstable_bound"]

#: per-controller statuses (:mod:`cable_ocp.heave.design_loop`)
#: the statuses of a run (members of :class:`cable_ocp.status.Status`)
STATUSES = (Status.SOLVED, Status.UNSTABLE, Status.NON_FINITE, Status.FAILED,
            Status.INTERRUPTED)

#: ``(status, message)`` of a controller whose run a Ctrl-C stopped, or that had not run yet:
#: a comparison catches the interruption, keeps the runs finished and returns with it
INTERRUPTED = (Status.INTERRUPTED, "interrupted before its run finished")

#: bound on the simulated unit heave and winch output, times the largest boom-tip heave of
#: the realisation (at least 1 mm): beyond it the loop is declared unstable
UNSTABLE_FACTOR = 1000.0


def unstable_bound(x0: np.ndarray) -> float:
    """The bound of a stable run (m): :data:`UNSTABLE_FACTOR` times the largest boom-tip heave
    ``x0`` (m) of the run, at least 1 mm."""
    return UNSTABLE_FACTOR * max(float(np.max(np.abs(x0))), 1e-3)


@dataclass(frozen=True)
class Trace:
    """Time histories of one closed-loop run (the plant's sub-step grid).

    Attributes
    ----------
    t : numpy.ndarray
        Time, s.
    x, x0, u, u_dot, u0 : numpy.ndarray
        Unit heave (m), boom-tip heave (m), winch output (m), winch speed (m/s), applied
        (delayed) command (m).
    tension : numpy.ndarray or None
        Line tension at the drum, N (the design model's ``T0 + (m/a) stretch``; None without
        ``[unit] mass`` and ``static_tension``).
    torque, power : numpy.ndarray or None
        The winch motor's torque (N m) and power (W) (:mod:`cable_ocp.heave.drive`; None
        without ``[winch] drum_radius``).
    stroke_phc : numpy.ndarray or None
        The passive compensator's compression, m (None without one).
    """

    t: np.ndarray
    x: np.ndarray
    x0: np.ndarray
    u: np.ndarray
    u_dot: np.ndarray
    u0: np.ndarray
    tension: np.ndarray | None = field(default=None, kw_only=True)
    torque: np.ndarray | None = field(default=None, kw_only=True)
    power: np.ndarray | None = field(default=None, kw_only=True)
    stroke_phc: np.ndarray | None = field(default=None, kw_only=True)


@dataclass(frozen=True)
class CableTrace(Trace):
    """Time histories of one closed-loop run of a line under the winch (sub-step grid).

    Attributes
    ----------
    t, x, x0, u, u_dot, u0 : numpy.ndarray
        As :class:`Trace`: time (s), unit heave relative to the static depth at the
        deployment length (m), boom-tip heave (m), winch output (m), winch speed (m/s),
        applied (delayed) command (m).
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
    """One closed-loop run: trace, commands, solver statistics and the plant's health.

    ``times`` are the controller's solve times (s; the MPC's), ``failures`` its solver
    failures, ``plant_failed_at`` the time (s) where the plant's step failed (or None),
    ``max_residual`` the plant's largest scaled Newton residual, ``stop`` the ``(status,
    message)`` where the run stopped for another reason (or None).
    """

    trace: Trace
    commands: np.ndarray
    times: np.ndarray
    failures: int
    plant_failed_at: float | None
    max_residual: float
    stop: tuple[str, str] | None = None


def run_status(run: LoopRun, plant: str = "cable") -> tuple[str, str]:
    """``(status, message)`` of a run, in :data:`STATUSES`: where it stopped, why
    (``"unstable"``, ``"non_finite"``, or ``"failed"`` with the plant's reason); ``"failed"``
    where a Newton step of the plant did not converge (the cable model cannot follow the line
    from there: a diverging loop or a slack line); else ``"solved"``.

    Parameters
    ----------
    run : LoopRun
        The run.
    plant : str
        The plant's name in the message (``"cable"``, ``"design-model"``).
    """
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

    Parameters
    ----------
    t_fine, x0_fine : numpy.ndarray
        The sea's grid (s) and boom-tip heave there (m).
    h : float
        Control sample, s.
    substeps : int
        The plant's sub-steps per sample.
    n_ctrl : int
        Control samples.
    ldep : callable
        Deployment length (m) at given times (s).
    fade_in : float
        Length of the ramp, s (0: none).
    """
    t = np.arange(n_ctrl * substeps + 1) * (h / substeps)
    x = np.clip(t / fade_in, 0.0, 1.0) if fade_in > 0 else np.ones_like(t)
    ramp = smoothstep(x)
    return Wave(t=t, x0=ramp * np.interp(t, t_fine, x0_fine),
                ldep=np.asarray(ldep(t), dtype=float), substeps=substeps)


@dataclass(frozen=True)
class Sample:
    """What a plant's :meth:`LoopPlant.advance` returns for one control sample of ``m``
    sub-steps.

    Attributes
    ----------
    x : numpy.ndarray, shape (m,)
        Unit heave at the ends of the sub-steps, m.
    u : numpy.ndarray, shape (m + 1,)
        Winch output at the sub-step points, the sample's start included, m.
    u_dot : numpy.ndarray, shape (m,)
        Winch speed at the starts of the sub-steps (with the new applied command), m/s.
    channels : dict
        The plant's further histories at the ends of the sub-steps (name -> shape (m,)).
    per_sample : float or None
        The plant's value per sample (the smallest element tension, N), or None.
    """

    x: np.ndarray
    u: np.ndarray
    u_dot: np.ndarray
    channels: dict = field(default_factory=dict)
    per_sample: float | None = None


class LoopPlant(ABC):
    """The interface of a plant in the closed loop (:func:`run_loop`).

    Attributes
    ----------
    sample_time : float
        Control sample ``h``, s.
    substeps : int
        Sub-steps ``m`` per sample (the trace's grid).
    delay : int
        The winch command's delay in samples, ``d = tau / h``.
    channels : tuple of str
        Names of the further histories of :attr:`Sample.channels`.
    failed_at : int or None
        The sample where the plant's step failed (or it refused the sample), else None.
    stop : tuple or None
        ``(status, message)`` where the plant refused a sample, else None.
    max_residual : float
        Largest scaled Newton residual of the plant's steps (0 for an explicit one).
    """

    sample_time: float
    substeps: int
    delay: int
    channels: tuple[str, ...] = ()
    failed_at: int | None = None
    stop: tuple[str, str] | None = None
    max_residual: float = 0.0

    @abstractmethod
    def start(self) -> dict[str, float]:
        """Back to the initial state; returns the unit heave ``"x"`` (m) and the channels at
        ``t = 0``."""

    @abstractmethod
    def observe(self, k: int) -> Observation:
        """What the controller gets at sample ``k`` (sensors with their noise, ...)."""

    @abstractmethod
    def advance(self, k: int, v: float) -> Sample:
        """Advance over one sample.

        Parameters
        ----------
        k : int
            The sample (from ``t = k h`` to ``(k + 1) h``).
        v : float
            The applied (delayed) command, m, held over the sample.
        """

    @abstractmethod
    def end_speed(self, v: float) -> float:
        """Winch speed (m/s) at the end of the run, the command ``v`` (m) still applied."""

    @abstractmethod
    def trace(self, x: np.ndarray, u: np.ndarray, u_dot: np.ndarray, u0: np.ndarray,
              channels: dict[str, np.ndarray], per_sample: np.ndarray) -> Trace:
        """The run's trace from the histories the loop recorded.

        Parameters
        ----------
        x, u, u_dot, u0 : numpy.ndarray, shape (n_ctrl m + 1,)
            Unit heave (m), winch output (m), winch speed (m/s) and applied command (m) on
            the sub-step grid (NaN where the run stopped).
        channels : dict
            The plant's :attr:`channels` on that grid.
        per_sample : numpy.ndarray, shape (n_ctrl,)
            The plant's value per sample (:attr:`Sample.per_sample`).
        """


def run_loop(plant: LoopPlant, ctrl: Controller, n_ctrl: int, bound: float,
             progress: Callable[[int], None] | None = None) -> LoopRun:
    """Simulate one controller on one plant (module docstring).

    Parameters
    ----------
    plant : LoopPlant
        The plant, started here.
    ctrl : Controller
        The controller, reset here.
    n_ctrl : int
        Control samples.
    bound : float
        Largest unit heave and winch output (m) of a stable run (:func:`unstable_bound`).
    progress : callable, optional
        Called as ``progress(k)`` every 100 samples.
    """
    h = plant.sample_time
    m = plant.substeps
    nfine = n_ctrl * m
    ctrl.reset()
    line = DelayLine(plant.delay)  # the plant side of the delay
    # NaN where a run that stopped has no value
    xs, us, uds, vs = (np.full(nfine + 1, np.nan) for _ in range(4))
    chans = {c: np.full(nfine + 1, np.nan) for c in plant.channels}
    per_sample = np.full(n_ctrl, np.nan)
    cmds = np.zeros(n_ctrl)
    first = plant.start()
    xs[0] = first["x"]
    for c in plant.channels:
        chans[c][0] = first[c]
    stop = None
    smp = None
    v = 0.0
    with np.errstate(all="ignore"):
        for k in range(n_ctrl):
            if progress is not None and k % 100 == 0:
                progress(k)
            i = k * m
            u0 = ctrl.step(plant.observe(k))
            if not np.isfinite(u0):
                stop = ("non_finite", f"the command became {u0} at t = {k * h:.2f} s; the "
                        "run stops there")
                break
            cmds[k] = u0
            v = line.push(u0)
            smp = plant.advance(k, v)
            xs[i + 1: i + m + 1] = smp.x
            us[i: i + m] = smp.u[:m]
            uds[i: i + m] = smp.u_dot
            vs[i: i + m] = v
            for c in plant.channels:
                chans[c][i + 1: i + m + 1] = smp.channels[c]
            if smp.per_sample is not None:
                per_sample[k] = smp.per_sample
            if plant.failed_at is not None:
                stop = plant.stop  # a reason the plant gave, if any
                break
            last = np.concatenate([smp.x, smp.u])
            if not np.all(np.isfinite(last)):
                stop = ("non_finite", f"a state or command became non-finite at t = "
                        f"{(k + 1) * h:.2f} s; the run stops there")
            elif float(np.max(np.abs(last))) > bound:
                stop = ("unstable", f"the unit heave or winch output left {bound:.4g} m "
                        f"({UNSTABLE_FACTOR:g} times the largest boom-tip heave) at t = "
                        f"{(k + 1) * h:.2f} s: the closed loop is unstable; the run stops "
                        "there")
            if stop is not None:
                xs[i + 1: i + m + 1] = np.nan
                break
    if plant.failed_at is None and stop is None and smp is not None:
        # the last point: the command applied over the last step is still applied (the
        # newest command is inside the delay line), so u'(T) is the left limit
        us[nfine] = smp.u[m]
        uds[nfine] = plant.end_speed(v)
        vs[nfine] = v
    tr = plant.trace(xs, us, uds, vs, chans, per_sample)
    failed = None if plant.failed_at is None else float(plant.failed_at * h)
    return LoopRun(trace=tr, commands=cmds, times=np.array(ctrl.solve_times),
                   failures=ctrl.failures, plant_failed_at=failed,
                   max_residual=plant.max_residual, stop=stop)
