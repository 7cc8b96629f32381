"""Figures for heave-compensation results (Huang 1992, ch. 6).

:func:`plot_comparison` draws one closed-loop comparison: the sea spectrum and its shaping
filter, the boom-tip and passive unit heave, the controlled unit heave (one strip per
controller, each on its own scale: the controlled heave is three orders of magnitude below
the passive one), the running RMS of the unit heave on a log scale, the winch stroke and
speed against their limits, and the trade-off curves. The simulation's warm-up, which the
metrics leave out, is shaded. Long time series are drawn as envelopes (min..max per window,
:func:`cable_ocp.plots.common.series`). Panel titles say what is drawn in words and cite the thesis
figure it corresponds to, when the scene is one of the thesis' examples.
"""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from cable_ocp.heave.metrics import Comparison
from cable_ocp.heave.sea import filter_spectrum
from cable_ocp.plots.common import (
    legend_below,
    new_figure,
    plain_log_ticks,
    save,
    series,
    shade,
    wrap,
)

#: thesis figures that correspond to the panels, by section of Huang (1992), ch. 6
THESIS_FIGURES: dict[str, dict[str, str]] = {
    "6.2.6": {
        "spectrum": "cf. Huang 1992, Fig. 6.10",
        "passive": "cf. Huang 1992, Figs. 6.14 and 6.17",
        "controlled": "cf. Huang 1992, Figs. 6.15-6.17",
        "tradeoff_d": "cf. Huang 1992, Fig. 6.18",
        "tradeoff_v": "cf. Huang 1992, Fig. 6.19",
    },
    "6.3.6": {
        "spectrum": "cf. Huang 1992, Fig. 6.21",
        "passive": "cf. Huang 1992, Figs. 6.22-6.23",
        "controlled": "cf. Huang 1992, Fig. 6.24",
        "tradeoff_d": "method of Huang 1992, Fig. 6.18",
        "tradeoff_v": "method of Huang 1992, Fig. 6.19",
    },
}

CONTROLLER_STYLE: dict[str, dict[str, Any]] = {
    "passive": {"color": "0.35", "ls": "-"},
    "lqr": {"color": "#1f77b4", "ls": "-"},
    "lqg": {"color": "#ff7f0e", "ls": "-"},
    "mpc": {"color": "#2ca02c", "ls": "--"},
    "phc": {"color": "#9467bd", "ls": "-"},
    "phc+lqr": {"color": "#8c564b", "ls": "-"},
    "phc+lqg": {"color": "#e377c2", "ls": "-"},
    "phc+mpc": {"color": "#17becf", "ls": "--"},
    "printed-g3": {"color": "#4d004b", "ls": "-"},
    "printed-g5": {"color": "#bcbd22", "ls": "--"},
}
BOOM_STYLE = {"color": "#9ecae1", "ls": "-"}
LIMIT_STYLE = {"color": "#d62728", "ls": "--", "lw": 1.2, "gid": "limit"}


def references_for(scene: Any) -> dict[str, str]:
    """The thesis figures of :data:`THESIS_FIGURES` for a heave scene whose ``[meta]``
    (title or source) names section 6.2.6 or 6.3.6; empty otherwise."""
    meta = getattr(scene, "meta", None) or {}
    text = " ".join(str(meta.get(k, "")) for k in ("title", "source"))
    text += " " + str(getattr(scene, "title", "") or "")
    for section, refs in THESIS_FIGURES.items():
        if re.search(re.escape(section) + r"(?!\d)", text):
            return dict(refs)
    return {}


def _title(words: str, refs: dict[str, str], key: str) -> str:
    """A panel title in words, with the thesis figure when there is one (wrapped)."""
    return wrap(f"{words} ({refs[key]})" if key in refs else words, 6.6, 10)


def _rms(m: Any, prefix: str = "rms ") -> str:
    """``rms 0.0123 m``, or ``not solved`` for a run without a heave RMS (JSON null)."""
    return "not solved" if m.heave_rms is None else f"{prefix}{m.heave_rms:.3g} m"


def _name(name: str) -> str:
    return "passive" if name == "passive" else name.upper()


def running_rms(t: np.ndarray, x: np.ndarray, window: float) -> tuple[np.ndarray, np.ndarray]:
    """RMS of ``x`` over the trailing ``window`` seconds, from ``t[0] + window`` on.

    Parameters
    ----------
    t : numpy.ndarray
        Sample times, s, shape (n,), evenly spaced (the median step is used).
    x : numpy.ndarray
        The signal, shape (n,), in its own unit (the RMS has the same unit, e.g. m).
    window : float
        Length of the trailing window, s; a window as long as the record gives one value,
        the RMS of all of ``x`` at ``t[-1]``.
    """
    t, x = np.asarray(t, float), np.asarray(x, float)
    dt = float(np.median(np.diff(t)))
    n = max(1, int(round(window / dt)))
    if n >= len(x):
        return t[-1:], np.array([math.sqrt(float(np.mean(x * x)))])
    c = np.concatenate([[0.0], np.cumsum(x * x)])
    ms = (c[n:] - c[:-n]) / n
    return t[n - 1:], np.sqrt(np.maximum(ms, 0.0))


def _time_axes(ax: Axes, t: np.ndarray, warmup: float, handles: list[Any]) -> None:
    if warmup > 0:
        handles.append(shade(ax, float(t[0]), min(warmup, float(t[-1])),
                             f"warm-up, first {warmup:g} s (left out of the metrics)"))
    ax.set_xlim(float(t[0]), float(t[-1]))
    ax.grid(True, alpha=0.3)


def _limit_lines(ax: Axes, value: float | None, label: str, handles: list[Any]) -> None:
    if value is None or not math.isfinite(value):
        return
    h = ax.axhline(value, label=label, **LIMIT_STYLE)
    ax.axhline(-value, **LIMIT_STYLE)
    handles.append(h)


def comparison_figure(res: Comparison, tradeoff: dict | None = None, scene: Any = None,
                      references: dict[str, str] | None = None) -> Figure:
    """Build (without saving) the figure of :func:`plot_comparison`.

    Its axes are labelled ``"spectrum"``, ``"passive"``, ``"controlled <name>"`` (one per
    controller), ``"rms"``, ``"stroke"``, ``"speed"`` and, with ``tradeoff``,
    ``"tradeoff_d"`` and ``"tradeoff_v"``.

    Parameters
    ----------
    res : Comparison
        The result of :func:`cable_ocp.heave.design_loop.compare`: traces (t in s, heave in
        m, winch output in m and speed in m/s), metrics, sea models.
    tradeoff : dict, optional
        ``{label: array of rows [J_w, J_d, J_v, ...]}`` from
        :func:`cable_ocp.heave.lqr.tradeoff_data` (m^2/s, m^2 s, m^2/s): two more
        panels. None (default): none.
    scene : HeaveScene, optional
        The scene: its title, warm-up (s, shaded) and winch stroke (m) and speed (m/s)
        limits (drawn as lines). None (default): no title, warm-up or limits.
    references : dict, optional
        Thesis figure per panel (keys as in :data:`THESIS_FIGURES`); None (default): those
        of the thesis section the scene's ``[meta]`` names, if any.
    """
    refs = references_for(scene) if references is None else references
    warmup = float(scene.simulation.warmup) if scene is not None else 0.0
    winch = scene.winch if scene is not None else None
    traces = res.traces
    controlled = [k for k in traces if k != "passive"]
    first = next(iter(traces.values()))
    t = first.t
    rows = 4 if tradeoff else 3
    fig = new_figure(13.5, 4.0 * rows + 1.6)
    gs = fig.add_gridspec(rows, 2)
    handles: list[Any] = []

    # sea spectrum and its shaping filter
    ax = fig.add_subplot(gs[0, 0], label="spectrum")
    spec = res.models.spectrum
    w = np.linspace(0.02, 5 * spec.omega_m, 600)
    kind = spec.kind.replace("_", "-").title()
    handles += ax.plot(w, spec(w), color="k", lw=1.8,
                       label=f"sea spectrum: {kind}, Hs = {spec.hs:g} m, "
                             f"omega_m = {spec.omega_m:.3g} rad/s")
    fit = res.models.filter_fit
    handles += ax.plot(w, filter_spectrum(fit.filter, w), color="#9467bd", lw=1.5, ls="--",
                       label=f"shaping filter (spectral error {fit.spectral_error:.2f}, "
                             f"variance error {100 * fit.variance_error:+.1f} %)")
    ax.set_xlim(0.0, float(w[-1]))
    ax.set_ylim(bottom=0.0)
    ax.set(xlabel="wave frequency omega (rad/s)", ylabel="spectral density S (m² s/rad)")
    ax.grid(True, alpha=0.3)
    ax.set_title(_title("Sea spectrum and its shaping filter", refs, "spectrum"), fontsize=10)

    # boom tip and passive unit heave
    ax = fig.add_subplot(gs[0, 1], label="passive")
    _time_axes(ax, t, warmup, handles)
    handles.append(series(ax, t, first.x0, lw=0.9, label="boom-tip heave x0",
                          **BOOM_STYLE).handle)
    if "passive" in traces:
        m = res.metrics["passive"]
        handles.append(series(ax, t, traces["passive"].x, lw=0.9,
                              label=f"unit heave, passive ({_rms(m)})",
                              **CONTROLLER_STYLE["passive"]).handle)
    ax.set(xlabel="time t (s)", ylabel="heave (m)")
    ax.set_title(_title("Boom-tip heave and unit heave without control", refs, "passive"),
                 fontsize=10)

    # controlled unit heave: one strip per controller, each on its own scale (mm)
    if not controlled:
        ax = fig.add_subplot(gs[1, 0], label="controlled")
        ax.axis("off")
        ax.text(0.5, 0.5, "no controller ran (passive only)", ha="center", va="center",
                fontsize=11, transform=ax.transAxes)
    strips = gs[1, 0].subgridspec(max(len(controlled), 1), 1, hspace=0.0)
    for i, name in enumerate(controlled):
        ax = fig.add_subplot(strips[i, 0], label=f"controlled {name}")
        _time_axes(ax, t, warmup, handles)
        m = res.metrics[name]
        handles.append(series(ax, t, traces[name].x * 1e3, lw=0.8,
                              label=f"unit heave, {_name(name)} ({_rms(m)})",
                              **CONTROLLER_STYLE.get(name, {})).handle)
        after = t >= warmup
        if warmup > 0 and after.sum() > 1:  # fit the scale to the measured part
            peak = float(np.max(np.abs(traces[name].x[after]))) * 1e3
            if math.isfinite(peak) and peak > 0:
                ax.set_ylim(-1.15 * peak, 1.15 * peak)
        ax.set_ylabel(f"{_name(name)} (mm)", fontsize=9)
        ax.tick_params(labelsize=8)
        if i == 0:
            ax.set_title(_title("Unit heave with control, each on its own scale (fitted "
                                "after the warm-up)", refs, "controlled"), fontsize=10)
        if i < len(controlled) - 1:
            ax.tick_params(labelbottom=False)
        else:
            ax.set_xlabel("time t (s)")

    # running RMS, log scale: every controller on one axis
    ax = fig.add_subplot(gs[1, 1], label="rms")
    _time_axes(ax, t, warmup, handles)
    window = min(30.0, 0.2 * float(t[-1] - t[0]))
    for name, tr in traces.items():
        tt, rms = running_rms(tr.t, tr.x, window)
        ax.semilogy(tt, rms, lw=1.4, **CONTROLLER_STYLE.get(name, {}))
    tt, rms = running_rms(t, first.x0, window)
    ax.semilogy(tt, rms, lw=1.2, **BOOM_STYLE)
    sig = float(res.sigma_uncontrolled)
    if math.isfinite(sig) and sig > 0:
        handles.append(ax.axhline(sig, color="k", ls=":", lw=1.2,
                                  label=f"unit heave std without control, Lyapunov "
                                        f"({sig:.3g} m)"))
    ax.set(xlabel="time t (s)", ylabel=f"running RMS over {window:g} s (m)")
    ax.grid(True, which="both", alpha=0.25)
    ax.set_title("Running RMS of the unit heave (log scale)", fontsize=10)

    # winch stroke and speed against their limits
    ax_u = fig.add_subplot(gs[2, 0], label="stroke")
    ax_v = fig.add_subplot(gs[2, 1], label="speed")
    for a in (ax_u, ax_v):
        _time_axes(a, t, warmup, handles)
    for name in controlled:
        tr = traces[name]
        style = CONTROLLER_STYLE.get(name, {})
        series(ax_u, t, tr.u, lw=0.8, **style)
        series(ax_v, t, tr.u_dot, lw=0.8, **style)
    _limit_lines(ax_u, getattr(winch, "stroke_max", None), "winch limits (stroke, speed)",
                 handles)
    _limit_lines(ax_v, getattr(winch, "speed_max", None), "winch limits (stroke, speed)",
                 handles)
    ax_u.set(xlabel="time t (s)", ylabel="winch output u (m)")
    ax_v.set(xlabel="time t (s)", ylabel="winch speed u' (m/s)")
    su = getattr(winch, "stroke_max", None)
    sv = getattr(winch, "speed_max", None)
    ax_u.set_title("Winch stroke" + (f" (limit ±{su:g} m)" if su else ""), fontsize=10)
    ax_v.set_title("Winch speed" + (f" (limit ±{sv:g} m/s)" if sv else ""), fontsize=10)

    # trade-off curves
    if tradeoff:
        ax_d = fig.add_subplot(gs[3, 0], label="tradeoff_d")
        ax_j = fig.add_subplot(gs[3, 1], label="tradeoff_v")
        markers = ["o", "s", "^", "D", "v"]
        for k, (label, arr) in enumerate(tradeoff.items()):
            arr = np.asarray(arr)
            if arr.size:
                style = {"marker": markers[k % len(markers)], "ms": 5, "color": f"C{k + 3}"}
                handles += ax_d.loglog(arr[:, 0], arr[:, 1], "-", label=f"LQR design, {label}",
                                       **style)
                ax_j.loglog(arr[:, 0], arr[:, 2], "-", **style)
        xl = "winch-speed energy J_w = ∫ u'² dt (m²/s)"
        ax_d.set(xlabel=xl, ylabel="displacement index J_d = ∫ x² dt (m² s)")
        ax_j.set(xlabel=xl, ylabel="velocity index J_v = ∫ x'² dt (m²/s)")
        for a in (ax_d, ax_j):
            a.grid(True, which="both", alpha=0.25)
            plain_log_ticks(a, "x")
        ax_d.set_title(_title("Trade-off: unit displacement against winch effort", refs,
                              "tradeoff_d"), fontsize=10)
        ax_j.set_title(_title("Trade-off: unit velocity against winch effort", refs,
                              "tradeoff_v"), fontsize=10)

    title = getattr(scene, "title", "") if scene is not None else ""
    if scene is not None and not title:
        title = (getattr(scene, "meta", None) or {}).get("title", "")
    sub = ("unit heave rms: " + ", ".join(f"{_name(k)} {_rms(m, '')}"
                                          for k, m in res.metrics.items()))
    fig.suptitle((f"{title}\n" if title else "") + sub, fontsize=11)
    legend_below(fig, handles, ncols=3)
    return fig


def plot_comparison(res: Comparison, path: str | Path, tradeoff: dict | None = None,
                    scene: Any = None, references: dict[str, str] | None = None) -> Figure:
    """Save the comparison figure of one heave simulation to ``path``.

    Parameters
    ----------
    res : Comparison
        The result of :func:`cable_ocp.heave.design_loop.compare`.
    path : str or Path
        Output file; the format follows the suffix.
    tradeoff : dict, optional
        Trade-off data from :func:`cable_ocp.heave.lqr.tradeoff_data` (two more panels).
    scene : HeaveScene, optional
        The scene: its title, warm-up (shaded) and winch limits (drawn as lines).
    references : dict, optional
        Thesis figure per panel (keys as in :data:`THESIS_FIGURES`); by default those of
        the thesis section the scene's ``[meta]`` names, if any.

    Returns
    -------
    matplotlib.figure.Figure
        The saved figure (see :func:`comparison_figure` for its axes' labels).
    """
    fig = comparison_figure(res, tradeoff, scene, references)
    save(fig, path)
    return fig
