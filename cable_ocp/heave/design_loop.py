"""Closed-loop simulation and comparison on one seeded wave realisation (Huang 1992, 6.3.6).

The sea and vessel states (the shaping filter (6.23) and boom-tip filter (6.26)) are sampled
exactly on the fine grid ``h_sim = h / substeps`` (ZOH transition, Van Loan noise covariance with
intensity ``pi``, stationary initial state), once per seed: every controller sees the same boom
tip. The plant (:class:`cable_ocp.heave.loop_plants.UnitWinchPlant`) integrates the unit and
winch with RK4 on that grid, with the boom-tip motion linear between grid points, the unit's
damping linear (6.2) or quadratic (6.3), and the winch command delayed by exactly ``tau``
(:class:`cable_ocp.heave.delay.DelayLine`); the loop is :func:`cable_ocp.heave.closed_loop.
run_loop`. Controllers (:mod:`cable_ocp.heave.controllers`) act every ``h`` seconds (ZOH):

* ``passive``: the winch held still (``u0 = 0``; not the thesis' passive compensator).
* ``lqr``: exact discrete-delay LQR on the full plant (sea and vessel states known).
* ``lqg``: the same gain on a discrete Kalman filter (current estimator) that measures the
  unit's heave with white noise of standard deviation ``measurement_noise``.
* ``mpc``: :class:`cable_ocp.heave.mpc.LinearMPC` with full state (and wave preview if asked).
* ``phc``: the passive compensator of ``[passive_compensator]`` (an in-line gas-spring
  cylinder, Huang (1992) 6.1.4) with the winch held still; ``phc+lqr``, ``phc+lqg``,
  ``phc+mpc``: the compensator and the active controller, designed on the plant with the
  compensator linearised (:func:`cable_ocp.heave.plant.compensator_block`), simulated with
  the gas spring exact and its end stops (:class:`cable_ocp.heave.loop_plants.
  UnitWinchPlant`).
* ``printed-g3``, ``printed-g5``: the thesis' printed gains G3, G5 of 6.2.6, each on the
  scene's winch with the delay it was designed for (none, 0.2 s), the scene's ``[winch]
  delay`` being the other controllers' (:mod:`cable_ocp.heave.printed`).

The unit and winch start at rest in a sea that starts in its stationary state; that start is
artificial, so **every** metric is taken over the same window ``t >= [simulation] warmup``
(see :func:`cable_ocp.heave.metrics.run_metrics`).

Per-controller status (:data:`cable_ocp.heave.closed_loop.STATUSES`), never a NaN reported as a
number:

* ``"solved"``: the run finished with finite, bounded states; every metric is a number.
* ``"unstable"``: the closed loop is unstable. Detected two ways: for the linear controllers
  (``lqr``, ``lqg``) by the design's closed-loop eigenvalues on the exact sampled model
  (spectral radius of ``Ad - Bd G``, and for ``lqg`` also of the estimator error dynamics
  ``Ad (I - M C)``, >= 1); for every controller by the simulated unit heave or winch output
  leaving :data:`cable_ocp.heave.closed_loop.UNSTABLE_FACTOR` times the largest boom-tip heave
  of the realisation (a stable loop moves them by at most its resonance amplification times
  the boom tip, ~1/(2 zeta) = 14 for the shipped units). The run stops there.
* ``"non_finite"``: a state or command became NaN or infinite (the run stops there).
* ``"failed"``: the controller could not be designed or built (a Riccati equation without a
  stabilising solution, a QP that cannot be set up); the message gives the solver's error.
* ``"interrupted"``: a Ctrl-C (:class:`KeyboardInterrupt`) stopped the comparison before this
  controller's run finished. The comparison returns what finished (the controllers run
  before, their metrics as in an uninterrupted run) and its status is ``"interrupted"``;
  without the passive baseline the reductions are None.

For every status but ``"solved"`` the metrics of the run are None (JSON null), except
``energy_index`` (a property of the design) and the MPC solve times. ``reduction_pct`` is
always relative to a passive run on the same realisation, run as a baseline when ``passive``
is not among the controllers.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy import linalg

from cable_ocp.errors import CableOCPError
from cable_ocp.heave import mpc as mpc_mod
from cable_ocp.heave import plant as pl
from cable_ocp.heave import sea as sea_mod
from cable_ocp.heave.closed_loop import INTERRUPTED, run_loop, unstable_bound
from cable_ocp.heave.controllers import Controller, MPCController, Passive, StateFeedback
from cable_ocp.heave.discrete import DelayedDiscreteModel, discretize_delayed, discretize_noise
from cable_ocp.heave.estimators import FullState, KalmanFilter, kalman_gain, process_noise
from cable_ocp.heave.loop_plants import UnitWinchPlant
from cable_ocp.heave.metrics import (
    Comparison,
    Metrics,
    limit_excess,
    limit_warning,
    run_metrics,
    with_reduction,
)
from cable_ocp.heave.printed import printed_run
from cable_ocp.heave.stochastic import (
    WHITE_NOISE_INTENSITY,
    discrete_delay_lqr,
    output_variance_lyapunov,
)
from cable_ocp.numerics import interrupt
from cable_ocp.physics.gas_spring import gas_stiffness
from cable_ocp.scene.heave import PRINTED_CONTROLLERS, HeaveScene, compensator_pressure

__all__ = ["Models", "base_controller", "build_models", "compare", "wave_realisation"]


@dataclass(frozen=True)
class Models:
    """Everything built from a scene: spectrum, filter, plant."""

    spectrum: sea_mod.SeaSpectrum
    filter_fit: sea_mod.FilterFit
    plant: pl.HeavePlant
    sigma_uncontrolled: float
    #: the plant with the passive compensator (block ``"comp"``), None without one
    plant_phc: pl.HeavePlant | None = None


#: exceptions of the numerical libraries that mean "this design cannot be computed"
_DESIGN_ERRORS = (ArithmeticError, ValueError, TypeError, RuntimeError, np.linalg.LinAlgError)


def build_models(scene: HeaveScene) -> Models:
    """Spectrum, shaping filter and the full plant (6.28) of a scene.

    ``sigma_uncontrolled`` is None when the Lyapunov equation gives no valid variance (a
    negative or non-finite value, from an ill-conditioned filter)."""
    s = scene.sea
    if s.modal_frequency is not None:
        wm = s.modal_frequency
    elif s.zero_crossing_period is not None:
        wm = sea_mod.modal_frequency_from_zero_crossing(s.zero_crossing_period)
    else:
        wm = 2 * np.pi / s.peak_period
    spec = sea_mod.SeaSpectrum(s.spectrum, s.significant_wave_height, wm, s.peak_enhancement)
    fit = sea_mod.make_shaping_filter(spec, s.shaping_filter, s.filter_order)
    v = scene.vessel
    vessel = (pl.direct_vessel() if v.model == "none"
              else pl.vessel_block(v.natural_frequency, v.damping_ratio, v.gain))
    w = scene.winch
    winch = (pl.winch_first(w.gain) if w.model == "first_order"
             else pl.winch_second(w.natural_frequency, w.damping_ratio))
    plant = pl.assemble_plant(scene.unit.a, scene.unit.b, winch, vessel=vessel, sea=fit.filter)
    with np.errstate(all="ignore"):
        var = output_variance_lyapunov(plant.A, plant.B2, plant.e("x"))
    sig = float(np.sqrt(var)) if np.isfinite(var) and var >= 0 else None
    plant_phc = None
    pc = scene.passive_compensator
    if pc is not None:
        k_p = gas_stiffness(0.0, compensator_pressure(scene), pc.gas_volume, pc.area,
                            pc.polytropic_exponent)
        comp = pl.compensator_block(k_p, pc.damping, scene.unit.mass / scene.unit.a)
        plant_phc = pl.assemble_plant(scene.unit.a, scene.unit.b, winch, vessel=vessel,
                                      sea=fit.filter, compensator=comp)
    return Models(spec, fit, plant, sig, plant_phc)


def base_controller(name: str) -> tuple[str, bool]:
    """``(active controller, with the passive compensator)`` of a controller's name:
    ``"phc"`` is ``("passive", True)``, ``"phc+lqr"`` ``("lqr", True)``, ``"lqr"``
    ``("lqr", False)``."""
    if name == "phc":
        return "passive", True
    if name.startswith("phc+"):
        return name[4:], True
    return name, False


def wave_realisation(plant: pl.HeavePlant, t_end: float, h_sim: float, seed: int
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Exactly sampled sea + vessel states and the boom-tip heave on ``[0, t_end]``.

    The shaping filter (6.21)-(6.23) and the vessel filter (6.25)-(6.26) are sampled exactly
    (ZOH transition, Van Loan noise covariance with intensity ``pi``); stationary start (initial
    state drawn from the Lyapunov covariance (6.31)).

    Parameters
    ----------
    plant : HeavePlant
        The plant (6.28) (its vessel and sea blocks).
    t_end : float
        Length of the record, s.
    h_sim : float
        Step of the record, s.
    seed : int
        Seed of the noise.

    Returns
    -------
    t : numpy.ndarray
        Time, s (step ``h_sim``).
    x0 : numpy.ndarray
        Boom-tip heave, m.
    states : numpy.ndarray, shape (len(t), n_vessel + n_sea)
        Vessel and sea states (the plant's states from the vessel block on).
    """
    lo = plant.blocks["vessel"].start
    A = plant.A[lo:, lo:]
    G = plant.B2[lo:]
    n = A.shape[0]
    Phi = linalg.expm(A * h_sim)
    Qd = discretize_noise(A, G, WHITE_NOISE_INTENSITY, h_sim)
    lam, V = np.linalg.eigh(Qd)
    Lq = V * np.sqrt(np.clip(lam, 0, None))
    P = WHITE_NOISE_INTENSITY * linalg.solve_continuous_lyapunov(A, -G @ G.T)
    lam, V = np.linalg.eigh(0.5 * (P + P.T))
    Lp = V * np.sqrt(np.clip(lam, 0, None))
    rng = np.random.default_rng(seed)
    nt = int(round(t_end / h_sim)) + 1
    xs = np.empty((nt, n))
    xs[0] = Lp @ rng.standard_normal(n)
    noise = rng.standard_normal((nt - 1, n)) @ Lq.T
    for k in range(nt - 1):
        xs[k + 1] = Phi @ xs[k] + noise[k]
    cx0, _ = plant.output_row("x0")
    x0 = xs @ cx0[lo:]
    return np.arange(nt) * h_sim, x0, xs


def compare(scene: HeaveScene, controllers: tuple | None = None,
            progress: Callable[[int, int, Any], None] | None = None) -> Comparison:
    """Simulate the scene's controllers on one wave realisation and compute the metrics.

    Each controller gets a status (:data:`cable_ocp.heave.closed_loop.STATUSES`, see the module
    docstring); a controller that cannot be designed, or whose loop is unstable or non-finite,
    never stops the others. ``progress``, if given, is called as ``progress(done, total,
    None)`` every 100 control samples (``total`` = samples x runs, the passive baseline
    included).

    A scene with ``[unit] cable_scene`` is compared by :func:`cable_ocp.heave.compare`
    (:mod:`cable_ocp.heave.cable_compare`: identification from the cable, the cable as the
    plant); here it raises.

    Parameters
    ----------
    scene : HeaveScene
        A heave scene without a cable scene.
    controllers : tuple of str, optional
        The controllers (default the scene's).
    progress : callable, optional
        ``progress(done, total, None)`` every 100 samples.
    """
    if scene.unit.cable_scene is not None:
        raise CableOCPError(
            f"unit.cable_scene = {scene.unit.cable_scene!r}: a scene on a cable is compared by "
            "cable_ocp.heave.compare (cable_ocp.heave.cable_compare), which identifies the "
            "design model from the cable; simulate.compare runs the design model alone")
    models = build_models(scene)
    p = models.plant
    c = scene.controller
    h = c.sample_time
    m = scene.simulation.substeps
    if m < 1:
        raise CableOCPError(f"simulation.substeps = {m}: must be >= 1")
    hs = h / m
    tau = scene.winch.delay
    T = scene.simulation.duration
    n_ctrl = int(round(T / h))
    preview = c.preview_time
    t, x0, xs_sea = wave_realisation(p, T + preview + h, hs, scene.simulation.seed)
    controllers = tuple(controllers or c.controllers)
    runs = controllers if "passive" in controllers else controllers + ("passive",)
    bound = unstable_bound(x0[: n_ctrl * m + 1])

    # Designs on the linear plants (with the compensator for the phc* controllers); a
    # failure is the status of the controllers that need it.
    designs = {False: _lqr_design(p, c, h, tau)}
    phc_names = [nm for nm in runs if base_controller(nm)[1]]
    if phc_names and models.plant_phc is None:
        raise CableOCPError(f"controllers {', '.join(phc_names)}: need a [passive_compensator] "
                            "table in the scene (area, gas_volume, damping, stroke_max, ...)")
    if phc_names:
        designs[True] = _lqr_design(models.plant_phc, c, h, tau)
    settings = mpc_mod.settings_from_scene(scene)

    traces, metrics, statuses, messages = {}, {}, {}, {}
    solve_times = None
    failures = 0
    warnings: list[str] = []
    rng_meas = np.random.default_rng(scene.simulation.seed + 1000)
    meas_noise = rng_meas.standard_normal(n_ctrl + 1) * c.measurement_noise
    total = n_ctrl * len(runs)
    passive_rms = None
    stopped = None  # the index in runs where a Ctrl-C stopped the comparison
    for n_done, name in enumerate(runs):
        report = None if progress is None else (
            lambda k, n_done=n_done: progress(n_done * n_ctrl + k, total, None))
        try:
            base, phc = base_controller(name)
            sc_run = scene
            if name in PRINTED_CONTROLLERS:  # the thesis' gain on the plant of its design
                pn = p
                sc_run, ctrl, status, message = printed_run(scene, name)
            else:
                pn, mdl, G, design_error = designs[phc]
                status, message, ctrl = _design(base, pn, mdl, G, design_error, settings, tau,
                                                c, h)
            if ctrl is not None:
                ctrl.name = name
            if status == "failed":
                if name in controllers:
                    statuses[name], messages[name] = status, message
                    metrics[name] = Metrics(None, None, None, None, None, None, None, None)
                continue
            plant = UnitWinchPlant(sc_run, pn, t, x0, xs_sea, meas_noise, n_ctrl, phc=phc)
            run = run_loop(plant, ctrl, n_ctrl, bound, report)
        except (KeyboardInterrupt, Exception) as exc:  # a CasADi error may be a Ctrl-C
            # an interruption: keep the runs finished; this one and the rest: interrupted
            if not interrupt.is_interruption(exc):
                raise
            stopped = n_done
            break
        tr, cmds, stop = run.trace, run.commands, run.stop
        if stop is not None and status == "solved":
            status, message = stop
        elif stop is not None:  # the design said so already; the run confirms it
            message += f"; in the run, {stop[1]}"
        if name == "mpc":
            solve_times = run.times
            failures = run.failures
            if failures:
                warnings.append(f"mpc: the QP failed at {failures} of {run.times.size} "
                                "samples; the shifted previous plan was applied there")
        energy = ctrl.energy_index
        times = run.times if base == "mpc" else None
        if status == "solved":
            mt = run_metrics(scene, tr, cmds, energy, times, h)
            lim = limit_warning(name, limit_excess(scene, tr, cmds, h))
            if lim and name in controllers:
                warnings.append(lim)
        else:
            mt = Metrics(None, None, None, None, energy, None,
                         float(np.median(times)) if times is not None and times.size else None,
                         None)
        if name == "passive":
            passive_rms = mt.heave_rms
        if name in controllers:
            traces[name], metrics[name] = tr, mt
            statuses[name], messages[name] = status, message
    if stopped is not None:
        for name in runs[stopped:]:
            if name in controllers:
                statuses[name], messages[name] = INTERRUPTED
                metrics[name] = Metrics(None, None, None, None, None, None, None, None)
        metrics = {k: metrics[k] for k in controllers}  # the scene's order
    elif progress is not None:  # (after a Ctrl-C the progress would raise it again)
        progress(total, total, None)
    metrics = {k: with_reduction(v, passive_rms) for k, v in metrics.items()}
    if models.sigma_uncontrolled is None:
        warnings.append("sigma_uncontrolled: the Lyapunov equation of the sea and vessel "
                        "filters gives no valid variance (ill-conditioned); reported as null")
    return Comparison(models.sigma_uncontrolled, metrics, traces, models, solve_times,
                      failures, statuses, messages, passive_rms, warnings,
                      interrupted=stopped is not None)


def _lqr_design(p: pl.HeavePlant, c: Any, h: float, tau: float
                ) -> tuple[pl.HeavePlant, DelayedDiscreteModel, np.ndarray | None, str | None]:
    """``(plant, sampled model, LQR gain or None, the design's error or None)``."""
    mdl = discretize_delayed(p.A, p.B1, h, tau)
    try:
        with np.errstate(all="ignore"):
            G = discrete_delay_lqr(p.A, p.B1, p.e("x"), c.q, c.r, h, tau)
        if not np.all(np.isfinite(G)):
            raise ArithmeticError("the LQR gain is not finite")
        return p, mdl, G, None
    except CableOCPError:
        raise
    except _DESIGN_ERRORS as exc:
        return p, mdl, None, f"{type(exc).__name__}: {exc}"


def _spectral_radius(A: np.ndarray) -> float:  # noqa: N803
    return float(np.max(np.abs(np.linalg.eigvals(A)))) if A.size else 0.0


def _design(name: str, p: pl.HeavePlant, mdl: DelayedDiscreteModel, G: np.ndarray | None,
            design_error: str | None, settings: mpc_mod.MPCSettings, tau: float, c: Any,
            h: float) -> tuple[str, str, Controller | None]:
    """(status, message, controller) before the run: "failed" when the controller cannot be
    built, "unstable" when its linear design's closed loop is (see the module docstring)."""
    if name in ("lqr", "lqg") and G is None:
        return "failed", f"the LQR design failed: {design_error}", None
    try:
        with np.errstate(all="ignore"):
            ctrl = _make_controller(name, p, mdl, G, settings, tau, c, h)
    except CableOCPError:
        raise
    except _DESIGN_ERRORS as exc:
        return "failed", f"the {name} design failed: {type(exc).__name__}: {exc}", None
    if name in ("lqr", "lqg"):
        with np.errstate(all="ignore"):
            rho = _spectral_radius(mdl.Ad - mdl.Bd @ G)
            if name == "lqg":
                Ad, _, M = ctrl.estimator.model_at()
                C = ctrl.estimator.C
                rho_e = _spectral_radius(Ad @ (np.eye(Ad.shape[0]) - M @ C))
                if not rho_e < 1.0:
                    return ("unstable", f"the Kalman filter's error dynamics are unstable "
                            f"(spectral radius {rho_e:.6g} >= 1)", ctrl)
        if not rho < 1.0:
            return ("unstable", f"the closed loop of the design is unstable (spectral radius "
                    f"{rho:.6g} >= 1 on the exact sampled model)", ctrl)
    return "solved", "ran to the end with finite, bounded states", ctrl


def _make_controller(name: str, p: pl.HeavePlant, mdl: DelayedDiscreteModel,
                     G: np.ndarray | None, settings: mpc_mod.MPCSettings, tau: float, c: Any,
                     h: float) -> Controller:
    """The controller ``name`` on the full plant ``p`` (module docstring): passive; the LQR
    gain ``G`` on the full state or (``lqg``) on the Kalman filter of the unit's depth with
    the noise ``c.measurement_noise`` (m); the MPC on the full state."""
    n, d = p.n, mdl.d
    if name == "passive":
        return Passive()
    if name == "lqr":
        return StateFeedback("lqr", G, FullState(n, d))
    if name == "lqg":
        std = c.measurement_noise
        if std <= 0:
            raise CableOCPError(f"controller.measurement_noise = {std!r}: must be > 0 (m)")
        nz = mdl.Ad.shape[0]
        C = np.zeros((1, nz))
        C[0, :n] = p.e("x")
        M = kalman_gain(mdl.Ad, C, process_noise(p, h, nz), np.array([[std**2]]))
        return StateFeedback("lqg", G, KalmanFilter((mdl.Ad, mdl.Bd, M), C, n, d))
    if name == "mpc":
        return MPCController(mpc_mod.LinearMPC(p, tau, settings), FullState(n, d))
    raise CableOCPError(f"controller {name!r} is unknown; valid: passive, lqr, lqg, mpc, "
                        "phc, phc+lqr, phc+lqg, phc+mpc, printed-g3, printed-g5")
