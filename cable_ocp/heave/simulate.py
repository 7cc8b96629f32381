"""Closed-loop simulation and comparison on one seeded wave realisation (Huang 1992, 6.3.6).

The sea and vessel states (the shaping filter (6.23) and boom-tip filter (6.26)) are sampled
exactly on the fine grid ``h_sim = h / substeps`` (ZOH transition, Van Loan noise covariance with
intensity ``pi``, stationary initial state), once per seed: every controller sees the same boom
tip. The unit and winch are integrated with RK4 on that grid, with the boom-tip motion linear
between grid points, the unit's damping linear (6.2) or quadratic (6.3), and the winch command
delayed by exactly ``tau`` (a buffer of fine steps). Controllers act every ``h`` seconds (ZOH):

* ``passive``: the winch held still (``u0 = 0``; not the thesis' passive compensator).
* ``lqr``: exact discrete-delay LQR on the full plant (sea and vessel states known).
* ``lqg``: the same gain on a discrete Kalman filter (current estimator) that measures the
  unit's heave with white noise of standard deviation ``measurement_noise``.
* ``mpc``: :class:`cable_ocp.heave.mpc.LinearMPC` with full state (and wave preview if asked).

The unit and winch start at rest in a sea that starts in its stationary state; that start is
artificial, so **every** metric is taken over the same window ``t >= [simulation] warmup``
(see :func:`_metrics`).

Per-controller status (:data:`STATUSES`), never a NaN reported as a number:

* ``"solved"``: the run finished with finite, bounded states; every metric is a number.
* ``"unstable"``: the closed loop is unstable. Detected two ways: for the linear controllers
  (``lqr``, ``lqg``) by the design's closed-loop eigenvalues on the exact sampled model
  (spectral radius of ``Ad - Bd G``, and for ``lqg`` also of the estimator error dynamics
  ``Ad (I - M C)``, >= 1); for every controller by the simulated unit heave or winch output
  leaving :data:`UNSTABLE_FACTOR` times the largest boom-tip heave of the realisation (a stable
  loop moves them by at most its resonance amplification times the boom tip, ~1/(2 zeta) = 14
  for the shipped units). The run stops there.
* ``"non_finite"``: a state or command became NaN or infinite (the run stops there).
* ``"failed"``: the controller could not be designed or built (a Riccati equation without a
  stabilising solution, a QP that cannot be set up); the message gives the solver's error.

For every status but ``"solved"`` the metrics of the run are None (JSON null), except
``energy_index`` (a property of the design) and the MPC solve times. ``reduction_pct`` is
always relative to a passive run on the same realisation, run as a baseline when ``passive``
is not among the controllers.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import linalg

from cable_ocp.errors import CableOCPError
from cable_ocp.heave import mpc as mpc_mod
from cable_ocp.heave import plant as pl
from cable_ocp.heave import sea as sea_mod
from cable_ocp.heave.discrete import delay_steps, discretize_delayed, discretize_noise
from cable_ocp.heave.stochastic import (
    WHITE_NOISE_INTENSITY,
    discrete_delay_lqr,
    output_variance_lyapunov,
)
from cable_ocp.scene.heave import HeaveScene


@dataclass(frozen=True)
class Models:
    """Everything built from a scene: spectrum, filter, plant."""

    spectrum: sea_mod.SeaSpectrum
    filter_fit: sea_mod.FilterFit
    plant: pl.HeavePlant
    sigma_uncontrolled: float


#: per-controller statuses (see the module docstring)
STATUSES = ("solved", "unstable", "non_finite", "failed")

#: bound on the simulated unit heave and winch output, times the largest boom-tip heave of
#: the realisation (at least 1 mm): beyond it the loop is declared unstable
UNSTABLE_FACTOR = 1000.0

#: exceptions of the numerical libraries that mean "this design cannot be computed"
_DESIGN_ERRORS = (ArithmeticError, ValueError, TypeError, RuntimeError, np.linalg.LinAlgError)


def build_models(sc: HeaveScene) -> Models:
    """Spectrum, shaping filter and the full plant (6.28) of a scene.

    ``sigma_uncontrolled`` is None when the Lyapunov equation gives no valid variance (a
    negative or non-finite value, from an ill-conditioned filter)."""
    s = sc.sea
    if s.modal_frequency is not None:
        wm = s.modal_frequency
    elif s.zero_crossing_period is not None:
        wm = sea_mod.modal_frequency_from_zero_crossing(s.zero_crossing_period)
    else:
        wm = 2 * np.pi / s.peak_period
    spec = sea_mod.SeaSpectrum(s.spectrum, s.significant_wave_height, wm, s.peak_enhancement)
    fit = sea_mod.make_shaping_filter(spec, s.shaping_filter, s.filter_order)
    v = sc.vessel
    vessel = (pl.direct_vessel() if v.model == "none"
              else pl.vessel_block(v.natural_frequency, v.damping_ratio, v.gain))
    w = sc.winch
    winch = (pl.winch_first(w.gain) if w.model == "first_order"
             else pl.winch_second(w.natural_frequency, w.damping_ratio))
    plant = pl.assemble_plant(sc.unit.a, sc.unit.b, winch, vessel=vessel, sea=fit.filter)
    with np.errstate(all="ignore"):
        var = output_variance_lyapunov(plant.A, plant.B2, plant.e("x"))
    sig = float(np.sqrt(var)) if np.isfinite(var) and var >= 0 else None
    return Models(spec, fit, plant, sig)


@dataclass(frozen=True)
class Trace:
    """Time histories of one closed-loop run (fine grid).

    Attributes
    ----------
    t : numpy.ndarray
        Time, s.
    x, x0, u, u_dot, u0 : numpy.ndarray
        Unit heave (m), boom-tip heave (m), winch output (m), winch speed (m/s), applied
        (delayed) command (m).
    """

    t: np.ndarray
    x: np.ndarray
    x0: np.ndarray
    u: np.ndarray
    u_dot: np.ndarray
    u0: np.ndarray


@dataclass(frozen=True)
class Metrics:
    """JSON metrics of one controller (field names as in docs/conventions.md, "Heave compensation").

    Every field is None (JSON null) where the number does not exist: all but
    ``energy_index`` and ``solve_time_median_s`` for a controller whose status is not
    ``"solved"``; ``reduction_pct`` when the passive baseline has no heave.
    """

    heave_rms: float | None
    reduction_pct: float | None
    peak_winch_speed: float | None
    max_stroke: float | None
    energy_index: float | None
    max_constraint_violation: float | None
    solve_time_median_s: float | None
    winch_speed_rms: float | None

    def as_dict(self) -> dict:
        """Plain dict for JSON."""
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


@dataclass(frozen=True)
class Comparison:
    """Result of :func:`compare`.

    Attributes
    ----------
    sigma_uncontrolled : float or None
        Lyapunov standard deviation of the uncontrolled unit heave, m (None if it does not
        exist).
    metrics : dict
        Controller name -> :class:`Metrics`.
    traces : dict
        Controller name -> :class:`Trace` (NaN after the sample where a run was stopped).
    statuses, messages : dict
        Controller name -> status (:data:`STATUSES`) and its explanation.
    passive_heave_rms : float
        Heave RMS of the passive run on the same realisation (the baseline of
        ``reduction_pct``), m.
    mpc_failures : int
        MPC samples at which the QP failed and the shifted previous plan was applied.
    warnings : list of str
        Remarks that do not change a status (MPC fallbacks, a missing sigma_uncontrolled).
    """

    sigma_uncontrolled: float | None
    metrics: dict
    traces: dict
    models: Models
    mpc_solve_times: np.ndarray | None
    mpc_failures: int
    statuses: dict = field(default_factory=dict)
    messages: dict = field(default_factory=dict)
    passive_heave_rms: float | None = None
    warnings: list = field(default_factory=list)

    @property
    def status(self) -> str:
        """``"solved"`` when every controller is, else the first other status."""
        bad = [s for s in self.statuses.values() if s != "solved"]
        return bad[0] if bad else "solved"


def wave_realisation(plant: pl.HeavePlant, t_end: float, h_sim: float, seed: int
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Exactly sampled sea + vessel states and the boom-tip heave on ``[0, t_end]``.

    The shaping filter (6.21)-(6.23) and the vessel filter (6.25)-(6.26) are sampled exactly
    (ZOH transition, Van Loan noise covariance with intensity ``pi``); stationary start (initial
    state drawn from the Lyapunov covariance (6.31)).

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


def _unit_winch_rhs(sc: HeaveScene):  # noqa: ANN202
    a, b = sc.unit.a, sc.unit.b
    bq = sc.unit.b_quadratic if sc.unit.model == "quadratic" else 0.0
    quad = sc.unit.model == "quadratic"
    w = sc.winch
    first = w.model == "first_order"
    K = w.gain
    wn, z = w.natural_frequency, w.damping_ratio

    def f(s: np.ndarray, x0: float, v: float) -> np.ndarray:
        damp = bq * s[1] * abs(s[1]) if quad else b * s[1]
        acc = (x0 + s[2] - s[0] - damp) / a
        if first:
            return np.array([s[1], acc, K * (v - s[2])])
        return np.array([s[1], acc, s[3], wn**2 * (v - s[2]) - 2 * z * wn * s[3]])

    return f


def compare(sc: HeaveScene, controllers: tuple | None = None,
            progress: Callable[[int, int, Any], None] | None = None) -> Comparison:
    """Simulate the scene's controllers on one wave realisation and compute the metrics.

    Each controller gets a status (:data:`STATUSES`, see the module docstring); a controller
    that cannot be designed, or whose loop is unstable or non-finite, never stops the others.
    ``progress``, if given, is called as ``progress(done, total, None)`` every 100 control
    samples (``total`` = samples x runs, the passive baseline included).

    A scene with ``[unit] cable_scene`` is compared by :func:`cable_ocp.heave.compare`
    (:mod:`cable_ocp.heave.cable_compare`: identification from the cable, the cable as the
    plant); here it raises.
    """
    if sc.unit.cable_scene is not None:
        raise CableOCPError(
            f"unit.cable_scene = {sc.unit.cable_scene!r}: a scene on a cable is compared by "
            "cable_ocp.heave.compare (cable_ocp.heave.cable_compare), which identifies the "
            "design model from the cable; simulate.compare runs the design model alone")
    models = build_models(sc)
    p = models.plant
    c = sc.controller
    h = c.sample_time
    m = sc.simulation.substeps
    if m < 1:
        raise CableOCPError(f"simulation.substeps = {m}: must be >= 1")
    hs = h / m
    tau = sc.winch.delay
    T = sc.simulation.duration
    n_ctrl = int(round(T / h))
    preview = c.preview_time
    t, x0, xs_sea = wave_realisation(p, T + preview + h, hs, sc.simulation.seed)
    controllers = tuple(controllers or c.controllers)
    runs = controllers if "passive" in controllers else controllers + ("passive",)
    bound = UNSTABLE_FACTOR * max(float(np.max(np.abs(x0[: n_ctrl * m + 1]))), 1e-3)

    # Designs on the linear plant; a failure is the status of the controllers that need it.
    mdl = discretize_delayed(p.A, p.B1, h, tau)
    try:
        with np.errstate(all="ignore"):
            G = discrete_delay_lqr(p.A, p.B1, p.e("x"), c.q, c.r, h, tau)
        if not np.all(np.isfinite(G)):
            raise ArithmeticError("the LQR gain is not finite")
        design_error = None
    except CableOCPError:
        raise
    except _DESIGN_ERRORS as exc:
        G, design_error = None, f"{type(exc).__name__}: {exc}"
    settings = mpc_mod.MPCSettings(
        horizon=c.horizon, sample_time=h, q=c.q, r=c.r, solver=c.solver,
        stroke_max=sc.winch.stroke_max, speed_max=sc.winch.speed_max,
        command_rate_max=sc.winch.command_rate_max, accel_max=sc.winch.accel_max,
        tension_min=sc.winch.tension_min, unit_mass=sc.unit.mass,
        static_tension=sc.unit.static_tension, tension_penalty=c.tension_penalty,
        preview_time=preview, terminal=c.terminal,
        nonlinear_b=sc.unit.b_quadratic if sc.unit.model == "quadratic" else 0.0)

    traces, metrics, statuses, messages = {}, {}, {}, {}
    solve_times = None
    failures = 0
    warnings: list[str] = []
    rng_meas = np.random.default_rng(sc.simulation.seed + 1000)
    meas_noise = rng_meas.standard_normal(n_ctrl + 1) * c.measurement_noise
    total = n_ctrl * len(runs)
    passive_rms = None
    for n_done, name in enumerate(runs):
        report = None if progress is None else (
            lambda k, n_done=n_done: progress(n_done * n_ctrl + k, total, None))
        status, message, ctrl = _design(name, p, mdl, G, design_error, settings, tau, c, h)
        if status == "failed":
            if name in controllers:
                statuses[name], messages[name] = status, message
                metrics[name] = Metrics(None, None, None, None, None, None, None, None)
            continue
        tr, cmds, stop = _run(sc, ctrl, p, t, x0, xs_sea, meas_noise, n_ctrl, bound, report)
        if stop is not None and status == "solved":
            status, message = stop
        elif stop is not None:  # the design said so already; the run confirms it
            message += f"; in the run, {stop[1]}"
        if name == "mpc":
            solve_times = np.array(ctrl.times)
            failures = ctrl.failures
            if failures:
                warnings.append(f"mpc: the QP failed at {failures} of {len(ctrl.times)} "
                                "samples; the shifted previous plan was applied there")
        energy = float(np.sqrt(np.sum(G**2))) if name in ("lqr", "lqg") else None
        times = np.array(ctrl.times) if name == "mpc" else None
        if status == "solved":
            mt = _metrics(sc, tr, cmds, energy, times, h)
        else:
            mt = Metrics(None, None, None, None, energy, None,
                         float(np.median(times)) if times is not None and times.size else None,
                         None)
        if name == "passive":
            passive_rms = mt.heave_rms
        if name in controllers:
            traces[name], metrics[name] = tr, mt
            statuses[name], messages[name] = status, message
    if progress is not None:
        progress(total, total, None)
    metrics = {k: _with_reduction(v, passive_rms) for k, v in metrics.items()}
    if models.sigma_uncontrolled is None:
        warnings.append("sigma_uncontrolled: the Lyapunov equation of the sea and vessel "
                        "filters gives no valid variance (ill-conditioned); reported as null")
    return Comparison(models.sigma_uncontrolled, metrics, traces, models, solve_times,
                      failures, statuses, messages, passive_rms, warnings)


def _spectral_radius(A: np.ndarray) -> float:  # noqa: N803
    return float(np.max(np.abs(np.linalg.eigvals(A)))) if A.size else 0.0


def _design(name: str, p: pl.HeavePlant, mdl, G: np.ndarray | None,  # noqa: ANN001
            design_error: str | None, settings: mpc_mod.MPCSettings, tau: float, c,  # noqa: ANN001
            h: float) -> tuple[str, str, Any]:
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
                rho_e = _spectral_radius(ctrl.A @ (np.eye(ctrl.A.shape[0]) - ctrl.M @ ctrl.C))
                if not rho_e < 1.0:
                    return ("unstable", f"the Kalman filter's error dynamics are unstable "
                            f"(spectral radius {rho_e:.6g} >= 1)", ctrl)
        if not rho < 1.0:
            return ("unstable", f"the closed loop of the design is unstable (spectral radius "
                    f"{rho:.6g} >= 1 on the exact sampled model)", ctrl)
    return "solved", "ran to the end with finite, bounded states", ctrl


def _run(sc: HeaveScene, ctrl: Any, p: pl.HeavePlant, t: np.ndarray, x0: np.ndarray,
         xs_sea: np.ndarray, meas_noise: np.ndarray, n_ctrl: int, bound: float,
         report: Callable[[int], None] | None
         ) -> tuple[Trace, np.ndarray, tuple[str, str] | None]:
    """One closed-loop run; stops (rest of the trace NaN) when it leaves ``bound`` or turns
    non-finite, and says so as ``(status, message)``."""
    c = sc.controller
    h = c.sample_time
    m = sc.simulation.substeps
    hs = h / m
    nd_fine = int(round(sc.winch.delay / hs))
    preview = c.preview_time
    nfine = n_ctrl * m
    f = _unit_winch_rhs(sc)
    first = sc.winch.model == "first_order"
    nuw = 3 if first else 4
    n = p.n
    lo = p.blocks["vessel"].start
    d = delay_steps(sc.winch.delay, h)
    s = np.zeros(nuw)
    ring = np.zeros(nd_fine + 1)  # fine-step command history for the exact delay (a ring)
    nring = nd_fine + 1
    xs_out = np.full(nfine + 1, np.nan)
    u_out = np.full(nfine + 1, np.nan)
    ud_out = np.full(nfine + 1, np.nan)
    v_out = np.full(nfine + 1, np.nan)
    cmds = np.zeros(n_ctrl)
    u_prev = 0.0
    cmd_hist = np.zeros(d)
    stop = None
    v = 0.0
    with np.errstate(all="ignore"):
        for k in range(n_ctrl):
            if report is not None and k % 100 == 0:
                report(k)
            i = k * m
            z = np.empty(n)
            z[:nuw] = s
            z[lo:] = xs_sea[i]
            zaug = np.concatenate([z, cmd_hist])
            x0_fore = x0[i: i + int(round(preview / hs)) + 1: m] if preview > 0 else None
            u0 = ctrl(zaug, u_prev, s[0] + meas_noise[k], x0_fore)
            if not np.isfinite(u0):
                stop = ("non_finite", f"the command became {u0} at t = {i * hs:.6g} s")
                break
            cmds[k] = u0
            u_prev = u0
            if d:
                cmd_hist = np.concatenate([cmd_hist[1:], [u0]])
            for j in range(m):
                ii = i + j
                ring[ii % nring] = u0
                v = ring[(ii + 1) % nring]  # the command issued nd_fine steps ago
                xs_out[ii], u_out[ii], v_out[ii] = s[0], s[2], v
                ud_out[ii] = sc.winch.gain * (v - s[2]) if first else s[3]
                xa, xb = x0[ii], x0[ii + 1]
                xm = 0.5 * (xa + xb)
                k1 = f(s, xa, v)
                k2 = f(s + hs / 2 * k1, xm, v)
                k3 = f(s + hs / 2 * k2, xm, v)
                k4 = f(s + hs * k3, xb, v)
                s = s + hs / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            if not np.all(np.isfinite(s)):
                stop = ("non_finite", f"the unit or winch state became non-finite by "
                        f"t = {(i + m) * hs:.6g} s")
                break
            if abs(s[0]) > bound or abs(s[2]) > bound:
                stop = ("unstable", f"the unit heave or winch output reached "
                        f"{max(abs(s[0]), abs(s[2])):.4g} m by t = {(i + m) * hs:.6g} s, "
                        f"{UNSTABLE_FACTOR:g} times the largest boom-tip heave: the closed "
                        "loop is unstable")
                break
    if stop is None:
        # t = T: the command applied over the last fine step is the delayed one (the newest
        # command is still inside the delay line), so u'(T) is the left limit K (v - u(T)).
        xs_out[nfine], u_out[nfine], v_out[nfine] = s[0], s[2], v
        ud_out[nfine] = sc.winch.gain * (v - s[2]) if first else s[3]
    tr = Trace(t[: nfine + 1], xs_out, x0[: nfine + 1], u_out, ud_out, v_out)
    return tr, cmds, stop


def _with_reduction(mt: Metrics, base: float | None) -> Metrics:
    """``reduction_pct`` = 100 (1 - rms / passive rms); None where either does not exist."""
    d = mt.as_dict()
    ok = mt.heave_rms is not None and base is not None and base > 0
    d["reduction_pct"] = float(100.0 * (1.0 - mt.heave_rms / base)) if ok else None
    return Metrics(**d)


def _metrics(sc: HeaveScene, tr: Trace, cmds: np.ndarray, energy: float | None,
             times: np.ndarray | None, h: float) -> Metrics:
    """Metrics of one run, all over the same window ``t >= [simulation] warmup``.

    The run starts with the unit and winch at rest while the sea starts in a stationary random
    state, so the first seconds are an artificial start-up transient. Every metric (RMS values,
    peaks, stroke, constraint violations, including the command change per sample and the
    second-order winch's acceleration) is taken after the warm-up only, so that they describe
    the same stationary operation.
    """
    warm = sc.simulation.warmup
    keep = tr.t >= warm - 1e-12
    u, ud = tr.u[keep], tr.u_dot[keep]
    w = sc.winch
    viol = 0.0
    for val, lim in [(np.max(np.abs(u)), w.stroke_max), (np.max(np.abs(ud)), w.speed_max)]:
        if lim is not None:
            viol = max(viol, max(0.0, val - lim) / lim)
    if w.command_rate_max is not None and cmds.size > 1:
        # Command k is issued at t = k h (command -1 is the initial 0); its change from
        # command k - 1 counts if k h >= warm-up.
        k0 = max(0, int(np.ceil(warm / h - 1e-9)))
        dcmd = np.diff(np.concatenate([[0.0], cmds]))[k0:]
        if dcmd.size:
            dr = float(np.max(np.abs(dcmd)))
            viol = max(viol, max(0.0, dr - w.command_rate_max) / w.command_rate_max)
    if w.accel_max is not None and w.model == "second_order":
        acc = np.gradient(tr.u_dot, tr.t)[keep]
        viol = max(viol, max(0.0, float(np.max(np.abs(acc))) - w.accel_max) / w.accel_max)
    return Metrics(
        heave_rms=float(np.sqrt(np.mean(tr.x[keep] ** 2))),
        reduction_pct=None,
        peak_winch_speed=float(np.max(np.abs(ud))),
        max_stroke=float(np.max(np.abs(u))),
        energy_index=energy,
        max_constraint_violation=float(viol),
        solve_time_median_s=float(np.median(times)) if times is not None and times.size
        else None,
        winch_speed_rms=float(np.sqrt(np.mean(ud**2))),
    )


class _Controller:
    times: list
    failures: int

    def __init__(self) -> None:
        self.times = []
        self.failures = 0


def _make_controller(name: str, p: pl.HeavePlant, mdl, G: np.ndarray,  # noqa: ANN001
                     settings: mpc_mod.MPCSettings, tau: float, c, h: float):  # noqa: ANN001
    if name == "passive":
        class Passive(_Controller):
            def __call__(self, z, up, y, fore):  # noqa: ANN001, ANN204
                return 0.0

        return Passive()
    if name == "lqr":
        class LQR(_Controller):
            def __call__(self, z, up, y, fore):  # noqa: ANN001, ANN204
                return float(-(G @ z)[0])

        return LQR()
    if name == "lqg":
        return _LQG(p, mdl, G, c.measurement_noise, h)
    if name == "mpc":
        return _MPCController(p, tau, settings)
    raise CableOCPError(f"controller {name!r} is unknown; valid: passive, lqr, lqg, mpc")


class _LQG(_Controller):
    """Discrete Kalman filter (current estimator) on the delayed sampled model + LQR gain."""

    def __init__(self, p: pl.HeavePlant, mdl, G: np.ndarray, std: float, h: float) -> None:  # noqa: ANN001
        super().__init__()
        if std <= 0:
            raise CableOCPError(f"controller.measurement_noise = {std!r}: must be > 0 (m)")
        self.A, self.B, self.G = mdl.Ad, mdl.Bd, G
        nz = mdl.Ad.shape[0]
        n = p.n
        Qw = np.zeros((nz, nz))
        Qw[:n, :n] = discretize_noise(p.A, p.B2, WHITE_NOISE_INTENSITY, h)
        Qw += 1e-14 * np.eye(nz) * np.max(np.abs(Qw))
        C = np.zeros((1, nz))
        C[0, :n] = p.e("x")
        R = np.array([[std**2]])
        P = linalg.solve_discrete_are(self.A.T, C.T, Qw, R)
        self.M = P @ C.T @ np.linalg.inv(C @ P @ C.T + R)
        self.C = C
        self.xp = np.zeros(nz)  # a priori estimate
        self.n = n

    def __call__(self, z, up, y, fore):  # noqa: ANN001, ANN204
        xh = self.xp + (self.M @ (np.array([y]) - self.C @ self.xp)).ravel()
        xh[self.n :] = z[self.n :]  # own past commands are known exactly
        u0 = float(-(self.G @ xh)[0])
        self.xp = self.A @ xh + self.B[:, 0] * u0
        return u0


class _MPCController(_Controller):
    def __init__(self, p: pl.HeavePlant, tau: float, settings: mpc_mod.MPCSettings) -> None:
        super().__init__()
        self.m = mpc_mod.LinearMPC(p, tau, settings)

    def __call__(self, z, up, y, fore):  # noqa: ANN001, ANN204
        D = self.m.preview_correction(z, fore) if fore is not None else None
        r = self.m.step(z, up, D)
        self.times.append(r.solve_time)
        if not r.success:
            self.failures += 1
        return r.u0
