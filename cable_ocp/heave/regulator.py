"""The thesis' printed regulator gains in the closed loop (Huang 1992, sections 6.2.4-6.2.6).

Huang prints two gains for the 6.2.6 unit (a = 7.339769 s^2, b = 0.1906759 s, (6.2)) and no
weights (:mod:`cable_ocp.heave.thesis`):

* **G3** = [93.944, 41.41, 5.166] on ``[x, x', u]`` of (6.6), no delay (Figs. 6.15-6.16);
* **G5** = [296.97, 132.73, 15.95, 2.306, 0.164] on ``[x, x', u, u0(t - tau), u0'(t - tau)]``
  of (6.14), the Taylor model (6.13) of a 0.2 s delay (Fig. 6.17).

Both use ``u0 = -G z`` (the printed gains are positive: :mod:`cable_ocp.heave.lqr`) and the
first-order winch (6.5) with K = 1 1/s: 6.2.6 never states K (docs/conventions.md). The
controller of G5 cannot measure the two Taylor states; it computes them by running the filter
(6.13) on its own commands, sampled exactly with its command held over the sample
(:class:`TaylorFilterEstimator`), while the plant gets the command delayed by exactly ``tau``.
The gains and their controllers live in :mod:`cable_ocp.heave.printed` (a heave scene runs
them as the controllers ``"printed-g3"``, ``"printed-g5"``: ``problems/heave/ex_6_2_6.toml``).

Each gain runs on its plant through the one closed loop,
:func:`cable_ocp.heave.closed_loop.run_loop`, on the design-model plant
:class:`cable_ocp.heave.loop_plants.UnitWinchPlant` (RK4 on the sub-steps), in the sea of
Fig. 6.10 (two-parameter Pierson-Moskowitz, Hs = 6 m, Tz = 14 s, through the thesis' shaping
filter, sampled exactly: :func:`cable_ocp.heave.design_loop.wave_realisation`): the responses of
Figs. 6.14-6.17 (:func:`simulate_printed`), and from a displaced start without a sea, whose
decay rate is that of the loop's slowest pole (:func:`free_response`, :func:`decay_rate`).

Figs. 6.14-6.17 are lost from the OCR'd thesis (only the captions survive: 6.14 "boom tip
motion", 6.15 and 6.16 the G3 caption, 6.17 the G5 caption). What the text states about them
(004, 6.2.6): "a large reduction in the response of the subsea unit when the active control
is introduced"; "the output of the winch acts to oppose the boom tip motion"; with the 0.2 s
delay "the controlled response can still be kept small", with "a significant increase in the
control energy required which is manifested through the increase in magnitude of the gain"
(J_c (6.18)). :func:`stated_numbers` gives those quantities.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.heave import lqr
from cable_ocp.heave import plant as pl
from cable_ocp.heave.closed_loop import Trace, run_loop, run_status, unstable_bound
from cable_ocp.heave.controllers import Passive
from cable_ocp.heave.design_loop import build_models, wave_realisation
from cable_ocp.heave.loop_plants import UnitWinchPlant
from cable_ocp.heave.printed import (
    PRINTED,
    PrintedGain,
    TaylorFilterEstimator,
    printed_controller,
)
from cable_ocp.heave.printed import printed_gain as _gain
from cable_ocp.heave.thesis import A_626, B_626, HS_626, TZ_626
from cable_ocp.scene.heave import HeaveScene, scene_from_dict

__all__ = ["PRINTED", "PrintedGain", "PrintedRun", "TaylorFilterEstimator", "decay_rate",
           "design_matrices", "design_poles", "free_response", "printed_controller",
           "regulator_scene", "simulate_printed", "stated_numbers", "true_loop_poles"]


def design_matrices(gain: PrintedGain | str, a: float = A_626, b: float = B_626,
                    K: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """``(A, B)`` of the plant the gain was designed for: (6.6), or (6.14) with the Taylor
    delay model (:func:`cable_ocp.heave.lqr.regulator_plant`).

    Parameters
    ----------
    gain : PrintedGain or str
        The gain (``"G3"``, ``"G5"``).
    a, b : float
        Unit coefficients (6.2), s^2 and s.
    K : float
        Winch gain (6.5), 1/s.
    """
    g = _gain(gain)
    dblk = pl.delay_block(g.delay_model, g.tau) if g.delay_model != "none" else None
    p = lqr.regulator_plant(a, b, K, delay=dblk)
    if p.n != g.G.shape[1]:
        raise CableOCPError(f"gain {g.name} has {g.G.shape[1]} entries; its plant has {p.n} "
                            "states")
    return p.A, p.B1


def design_poles(gain: PrintedGain | str, a: float = A_626, b: float = B_626,
                 K: float = 1.0) -> np.ndarray:
    """Eigenvalues of ``A - B G`` on the gain's design plant (1/s), sorted by real part
    (slowest last).

    Parameters
    ----------
    gain : PrintedGain or str
        The gain.
    a, b : float
        Unit coefficients (6.2), s^2 and s.
    K : float
        Winch gain (6.5), 1/s.
    """
    g = _gain(gain)
    A, B = design_matrices(g, a, b, K)
    ev = np.linalg.eigvals(A - B @ g.G)
    return ev[np.argsort(ev.real)]


def true_loop_poles(gain: PrintedGain | str, h: float, a: float = A_626, b: float = B_626,
                    K: float = 1.0) -> np.ndarray:
    """Poles (1/s, ``log(z) / h``) of the loop sampled at ``h`` with the true delay ``tau``
    (:func:`cable_ocp.heave.lqr.true_discrete_loop`: the command held over the sample, the
    Taylor states computed by the controller), sorted by real part (slowest last); the
    poles at ``z = 0`` of the delay's shift register are left out.

    Parameters
    ----------
    gain : PrintedGain or str
        The gain.
    h : float
        Sample time, s.
    a, b : float
        Unit coefficients (6.2), s^2 and s.
    K : float
        Winch gain (6.5), 1/s.
    """
    g = _gain(gain)
    des = lqr.design_from_gains(a, b, g.G, tau=g.tau, method=g.delay_model, K=K)
    z = np.linalg.eigvals(lqr.true_discrete_loop(des, g.tau, h).A)
    z = z[np.abs(z) > 1e-12]
    s = np.log(z.astype(complex)) / h
    return s[np.argsort(s.real)]


def regulator_scene(tau: float = 0.0, *, a: float = A_626, b: float = B_626, K: float = 1.0,
                    sample_time: float = 0.01, substeps: int = 1, duration: float = 300.0,
                    seed: int = 2, warmup: float = 30.0) -> HeaveScene:
    """The 6.2.6 regulator as a heave scene: the sea of Fig. 6.10 at the boom tip (no vessel
    filter), the unit (6.2), the first-order winch with the delay ``tau``.

    Parameters
    ----------
    tau : float
        Winch delay, s (a multiple of ``sample_time``).
    a, b : float
        Unit coefficients (6.2), s^2 and s.
    K : float
        Winch gain, 1/s.
    sample_time : float
        Control sample, s (the thesis' loop is continuous: keep it small).
    substeps : int
        RK4 sub-steps per sample.
    duration : float
        Simulated time, s.
    seed : int
        Seed of the sea.
    warmup : float
        Start-up left out of the RMS, s.
    """
    return scene_from_dict({
        "sea": {"spectrum": "pierson_moskowitz", "significant_wave_height": HS_626,
                "zero_crossing_period": TZ_626, "shaping_filter": "thesis"},
        "vessel": {"model": "none"},
        "winch": {"model": "first_order", "gain": K, "delay": tau},
        "unit": {"a": a, "b": b, "model": "linear"},
        "controller": {"sample_time": sample_time},
        "simulation": {"duration": duration, "seed": seed, "substeps": substeps,
                       "warmup": warmup},
    })


class _StartedPlant(UnitWinchPlant):
    """:class:`UnitWinchPlant` started from a given unit and winch state."""

    def __init__(self, *args: object, s0: np.ndarray) -> None:
        super().__init__(*args)
        self.s0 = np.asarray(s0, dtype=float)

    def start(self) -> dict[str, float]:
        self.s = self.s0.copy()
        return {"x": float(self.s[0])}


@dataclass(frozen=True)
class PrintedRun:
    """The responses of Figs. 6.14-6.17 on one boom-tip record.

    Attributes
    ----------
    t, x0 : numpy.ndarray
        Time (s) and boom-tip heave (m) on the plant's grid.
    traces : dict
        ``"uncontrolled"`` (the winch held still) and each gain's name -> its
        :class:`cable_ocp.heave.closed_loop.Trace`.
    statuses : dict
        Name -> ``(status, message)`` of the run (:func:`cable_ocp.heave.closed_loop.
        run_status` statuses).
    warmup : float
        Start-up left out of the numbers, s.
    gains : dict
        Each gain's name -> its :class:`PrintedGain`.
    """

    t: np.ndarray
    x0: np.ndarray
    traces: dict
    statuses: dict
    warmup: float
    gains: dict = field(default_factory=dict)


def _run(sc: HeaveScene, ctrl: object, t: np.ndarray, x0: np.ndarray, xs: np.ndarray,
         s0: np.ndarray | None = None) -> tuple[Trace, tuple[str, str]]:
    p = build_models(sc).plant
    h = sc.controller.sample_time
    n_ctrl = int(round(sc.simulation.duration / h))
    noise = np.zeros(n_ctrl + 1)  # full-state feedback: the depth sensor is not used
    args = (sc, p, t, x0, xs, noise, n_ctrl)
    plant = UnitWinchPlant(*args) if s0 is None else _StartedPlant(*args, s0=s0)
    bound = unstable_bound(x0[: n_ctrl * sc.simulation.substeps + 1]) if s0 is None else (
        1e3 * max(float(np.max(np.abs(s0))), 1e-3))
    run = run_loop(plant, ctrl, n_ctrl, bound)
    return run.trace, run_status(run, "design-model")


def simulate_printed(gains: tuple = ("G3", "G5"), *, duration: float = 300.0,
                     sample_time: float = 0.01, substeps: int = 1, seed: int = 2,
                     warmup: float = 30.0, a: float = A_626, b: float = B_626,
                     K: float = 1.0) -> PrintedRun:
    """Each printed gain on its plant (its delay) and the uncontrolled unit, on one boom-tip
    record of the Fig. 6.10 sea (module docstring).

    Parameters
    ----------
    gains : tuple of str
        The gains to run.
    duration : float
        Simulated time, s.
    sample_time : float
        Control sample, s (the delay must be a multiple of it).
    substeps : int
        RK4 sub-steps per sample.
    seed : int
        Seed of the sea.
    warmup : float
        Start-up left out of :func:`stated_numbers`, s.
    a, b : float
        Unit coefficients (6.2), s^2 and s.
    K : float
        Winch gain, 1/s.
    """
    base = regulator_scene(0.0, a=a, b=b, K=K, sample_time=sample_time, substeps=substeps,
                           duration=duration, seed=seed, warmup=warmup)
    p = build_models(base).plant
    t, x0, xs = wave_realisation(p, duration + sample_time, sample_time / substeps, seed)
    traces, statuses, used = {}, {}, {}
    traces["uncontrolled"], statuses["uncontrolled"] = _run(base, Passive(), t, x0, xs)
    for name in gains:
        g = _gain(name)
        used[g.name] = g
        sc = regulator_scene(g.tau, a=a, b=b, K=K, sample_time=sample_time,
                             substeps=substeps, duration=duration, seed=seed, warmup=warmup)
        traces[g.name], statuses[g.name] = _run(sc, printed_controller(g, sample_time), t,
                                                x0, xs)
    tr = traces["uncontrolled"]
    return PrintedRun(tr.t, tr.x0, traces, statuses, warmup, used)


def free_response(gain: PrintedGain | str, x_start: float = 1.0, *, duration: float = 30.0,
                  sample_time: float = 0.01, substeps: int = 1, a: float = A_626,
                  b: float = B_626, K: float = 1.0) -> Trace:
    """The loop of a printed gain from the unit displaced by ``x_start`` (m) at rest, no
    sea: its decay is that of the loop's slowest pole.

    Parameters
    ----------
    gain : PrintedGain or str
        The gain.
    x_start : float
        Initial unit heave, m.
    duration : float
        Simulated time, s.
    sample_time : float
        Control sample, s.
    substeps : int
        RK4 sub-steps per sample.
    a, b : float
        Unit coefficients (6.2), s^2 and s.
    K : float
        Winch gain, 1/s.
    """
    g = _gain(gain)
    sc = regulator_scene(g.tau, a=a, b=b, K=K, sample_time=sample_time, substeps=substeps,
                         duration=duration, warmup=0.0)
    p = build_models(sc).plant
    n = int(round(duration / sample_time)) * substeps + 2
    t = np.arange(n) * (sample_time / substeps)
    lo = p.blocks["vessel"].start
    tr, status = _run(sc, printed_controller(g, sample_time), t, np.zeros(n),
                      np.zeros((n, p.n - lo)), s0=np.array([x_start, 0.0, 0.0]))
    if status[0] != "solved":
        raise CableOCPError(f"the free response of {g.name} stopped: {status[1]}")
    return tr


def decay_rate(t: np.ndarray, x: np.ndarray, t_from: float = 0.0) -> float:
    """Decay rate (1/s, negative for a decaying response) of an oscillation: the slope of
    ``log |x|`` at its successive extremes after ``t_from`` (least squares). For one damped
    mode ``C exp(sigma t) cos(omega t + phi)`` the extremes are ``pi / omega`` apart and the
    slope is ``sigma`` exactly.

    Parameters
    ----------
    t : numpy.ndarray
        Time, s.
    x : numpy.ndarray
        The response.
    t_from : float
        Start of the fit, s.
    """
    sel = t >= t_from
    tt, xx = t[sel], np.abs(x[sel])
    i = np.flatnonzero((xx[1:-1] > xx[:-2]) & (xx[1:-1] >= xx[2:])) + 1
    if i.size < 3:
        raise CableOCPError(f"decay_rate: {i.size} extremes after t = {t_from} s; at least 3 "
                            "are needed (a longer record)")
    return float(np.polyfit(tt[i], np.log(xx[i]), 1)[0])


def stated_numbers(run: PrintedRun) -> dict:
    """What the 6.2.6 text states about Figs. 6.14-6.17, as numbers (after the warm-up).

    Per run: ``heave_rms`` (m); per gain: ``reduction_pct`` against the uncontrolled unit,
    ``opposition`` the correlation of the winch output ``u`` with the boom tip ``x0`` (-1: the
    winch opposes the boom tip exactly), ``residual_ratio`` ``rms(x0 + u) / rms(x0)``, ``J_c``
    (6.18) ``sum G_i^2`` and ``J_w`` the winch-speed energy ``int u'^2 dt`` (m^2/s).

    Parameters
    ----------
    run : PrintedRun
        The responses.
    """
    sel = run.t >= run.warmup
    dt = float(run.t[1] - run.t[0])
    out: dict = {}
    x0 = run.x0[sel]
    for name, tr in run.traces.items():
        x = tr.x[sel]
        row: dict = {"heave_rms": float(np.sqrt(np.mean(x**2)))}
        if name != "uncontrolled":
            u = tr.u[sel]
            row["reduction_pct"] = 100.0 * (1.0 - row["heave_rms"]
                                            / out["uncontrolled"]["heave_rms"])
            row["opposition"] = float(np.corrcoef(u, x0)[0, 1])
            row["residual_ratio"] = float(np.sqrt(np.mean((x0 + u) ** 2) / np.mean(x0**2)))
            row["J_c"] = float(np.sum(run.gains[name].G ** 2))
            row["J_w"] = float(np.sum(tr.u_dot[sel] ** 2) * dt)
        out[name] = row
    return out
