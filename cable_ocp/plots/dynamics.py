"""Figures of the cable dynamics: a simulation (unit trajectory, tension envelope along the
cable, top against unit heave, top tension in time), mode shapes, and the deployment
resonance chart (natural frequencies against paid-out length, the wave band shaded)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from cable_ocp.plots.common import force_scale, legend_below, new_figure, save, wrap


def simulation_figure(res: Any, title: str = "", scene: Any = None) -> Figure:
    """The four panels of a :class:`cable_ocp.dynamics.result.SimulationResult`.

    Parameters
    ----------
    res : SimulationResult
        The simulation: unit and top positions (m), segment and top tensions (N), length
        (m), slack record, status; a failed run is drawn too, its status in red.
    title : str
        First line of the figure's title (the model and simulated time follow); empty
        (default): an empty first line.
    scene : DynamicScene, optional
        Not used by the figure (accepted so that callers can pass the scene); default None.
    """
    fig = new_figure(12.0, 8.0)
    ax = fig.subplots(2, 2)
    t = res.t
    handles: list[Any] = []
    # unit trajectory in its vertical plane of largest motion
    up = res.unit_position
    horiz = up[:, :2] - up[0, :2]
    span = np.ptp(horiz, axis=0)
    k = int(np.argmax(span))
    axis = "xy"[k]
    a = ax[0, 0]
    if span[k] > 1e-9 * max(1.0, abs(up[0, 2])):
        a.plot(up[:, k], up[:, 2], lw=1.2, color="C0")
        a.plot(up[0, k], up[0, 2], "o", color="k", ms=5, label="unit at t = 0 (static)")
        a.set_xlabel(f"{axis} (m)")
        a.set_title("Unit trajectory (side view)")
    else:
        a.plot(t, up[:, 2], lw=1.2, color="C0")
        a.set_xlabel("time t (s)")
        a.set_title("Unit heave (the unit moves vertically only)")
    a.set_ylabel("unit z (m)")
    a.grid(True, alpha=0.3)
    # tension envelope along the cable
    a = ax[0, 1]
    ten = res.segment_tensions
    n_el = ten.shape[1]
    s_mid = (np.arange(n_el) + 0.5) / n_el  # element centres, fraction of the length
    scale, unit = force_scale(float(np.nanmax(np.abs(ten))) if ten.size else 1.0)
    lo, hi = np.nanmin(ten, axis=0) / scale, np.nanmax(ten, axis=0) / scale
    a.fill_between(s_mid, lo, hi, color="C1", alpha=0.3, label="tension envelope (min..max)")
    a.plot(s_mid, ten[0] / scale, color="k", lw=1.0, label="static tension (t = 0)")
    a.axhline(0.0, color="r", lw=0.8, ls="--", label="slack (zero tension)")
    a.set_xlabel("position along the cable, s/L from end_a (unit) to end_b (ship) (-)")
    a.set_ylabel(f"tension ({unit})")
    a.set_title("Tension envelope along the cable")
    a.grid(True, alpha=0.3)
    # top against unit heave
    a = ax[1, 0]
    zt = res.top_position[:, 2] - res.top_position[0, 2]
    zu = up[:, 2] - up[0, 2]
    paid = np.asarray(res.length, dtype=float) - float(res.length[0])
    a.plot(t, zt, color="C2", lw=1.0, label="top (end_b) heave from its static position")
    if np.ptp(paid) > 0:
        # a deployment: the unit's descent by the paid-out length would hide its heave
        a.plot(t, zu + paid, color="C0", lw=1.0,
               label="unit (end_a) heave about its lowering path (z + paid-out length)")
        a.set_title("Top against unit heave (pay-out taken out)")
    else:
        a.plot(t, zu, color="C0", lw=1.0, label="unit (end_a) heave from its static position")
        a.set_title("Top against unit heave")
    a.set_xlabel("time t (s)")
    a.set_ylabel("heave (m)")
    a.grid(True, alpha=0.3)
    # top tension and length in time
    a = ax[1, 1]
    sc2, unit2 = force_scale(float(np.nanmax(np.abs(res.top_tension))))
    a.plot(t, res.top_tension / sc2, color="C3", lw=1.0, label="top tension")
    a.set_xlabel("time t (s)")
    a.set_ylabel(f"top tension ({unit2})")
    a.grid(True, alpha=0.3)
    if np.ptp(res.length) > 0:
        b = a.twinx()
        b.plot(t, res.length, color="0.4", lw=1.0, ls=":", label="paid-out length")
        b.set_ylabel("unstretched length (m)")
    a.set_title("Top tension" + (" and paid-out length" if np.ptp(res.length) > 0 else ""))
    slack = res.slack or {}
    if slack.get("occurred") and slack.get("first_time") is not None:
        for axx in (ax[1, 0], ax[1, 1]):
            axx.axvline(slack["first_time"], color="r", lw=0.8, ls="--", label="first slack")
    for axx in fig.axes:
        handles += axx.get_legend_handles_labels()[0]
    legend_below(fig, handles)
    status = "" if res.status == "solved" else f" - {res.status}: {res.message}"
    fig.suptitle(f"{title}\n{res.model} model, {t[-1] - t[0]:.4g} s simulated{status}",
                 fontsize=11, color="k" if res.status == "solved" else "firebrick")
    return fig


def plot_simulation(res: Any, path: str | Path, title: str = "", scene: Any = None) -> Figure:
    """Save :func:`simulation_figure` to ``path``.

    Parameters
    ----------
    res : SimulationResult
        The simulation to draw.
    path : str or Path
        Where to save the figure (format from the suffix).
    title : str
        First line of the figure's title; empty (default): none.
    scene : DynamicScene, optional
        Passed on to :func:`simulation_figure` (which does not use it); default None.
    """
    fig = simulation_figure(res, title, scene)
    save(fig, path)
    return fig


def modes_figure(res: Any, title: str = "", max_modes: int = 6) -> Figure:
    """Build (without saving) the figure of :func:`plot_modes`: the first mode shapes
    in the vertical plane of the line (shape components along the line's horizontal
    direction and vertically, against the static profile).

    Parameters
    ----------
    res : ModesResult
        The modal analysis: frequencies (rad/s), mode shapes and static node positions
        (m). Each shape is drawn scaled to 12 % of the line's extent.
    title : str
        Start of the title (``"{title}: natural modes of ..."``); default empty.
    max_modes : int
        Largest number of modes drawn, one panel each, lowest first (default 6).
    """
    n = min(max_modes, len(res.frequencies))
    fig = new_figure(3.0 * max(n, 1), 4.6)
    axes = np.atleast_1d(fig.subplots(1, max(n, 1), sharey=True))
    r = res.node_positions
    d = r[-1, :2] - r[0, :2]
    e = d / np.linalg.norm(d) if np.linalg.norm(d) > 1e-9 else np.array([1.0, 0.0])
    h = (r[:, :2] - r[0, :2]) @ e
    extent = max(np.ptp(h), np.ptp(r[:, 2]), 1.0)
    for k in range(n):
        a = axes[k]
        shape = res.shapes[k]
        sh = shape[:, :2] @ e
        amp = 0.12 * extent
        a.plot(h, r[:, 2], color="0.6", lw=1.0, label="static profile")
        a.plot(h + amp * sh, r[:, 2] + amp * shape[:, 2], color="C0", lw=1.4,
               label="mode shape (scaled)")
        a.set_title(f"mode {k + 1}: {res.frequencies[k]:.4g} rad/s\n"
                    f"period {res.periods[k]:.4g} s", fontsize=9)
        a.set_xlabel("horizontal (m)")
        a.set_aspect("equal", adjustable="datalim")
        a.grid(True, alpha=0.3)
    axes[0].set_ylabel("z (m)")
    legend_below(fig, [*axes[0].get_lines()])
    fig.suptitle(f"{title}: natural modes of the {res.model} model about the static state",
                 fontsize=11)
    return fig


def plot_modes(res: Any, path: str | Path, title: str = "", max_modes: int = 6) -> Figure:
    """Save :func:`modes_figure` (the first mode shapes, one panel each) to ``path``.

    Parameters
    ----------
    res : ModesResult
        The modal analysis.
    path : str or Path
        Where to save the figure (format from the suffix).
    title : str
        Start of the title; default empty.
    max_modes : int
        Largest number of modes drawn (default 6).
    """
    fig = modes_figure(res, title, max_modes)
    save(fig, path)
    return fig


def deployment_figure(chart: Any, title: str = "") -> Figure:
    """Build (without saving) the figure of :func:`plot_deployment`: natural
    frequencies against paid-out length, the wave band shaded, crossings marked (the
    lengths at which lowering the unit passes through a resonance).

    Parameters
    ----------
    chart : DeploymentChart
        Natural frequencies (rad/s) against unstretched paid-out length (m), and the wave
        band (rad/s).
    title : str
        Start of the title (``"{title}: deployment resonance chart ..."``); default empty.
    """
    fig = new_figure(9.0, 5.6)
    a = fig.subplots()
    lo, hi = chart.wave_band
    band = a.axhspan(lo, hi, color="C0", alpha=0.15,
                     label=f"wave band {lo:.3g}-{hi:.3g} rad/s")
    for k in range(chart.frequencies.shape[1]):
        a.plot(chart.lengths, chart.frequencies[:, k], "-o", ms=3, lw=1.5, label=f"mode {k + 1}")
    for c in chart.crossings():
        a.plot(c["length_m"], c["edge"], "x", color="firebrick", ms=8)
    a.plot([], [], "x", color="firebrick", label="mode enters/leaves the band")
    a.set_xlabel("paid-out length (unstretched) (m)")
    a.set_ylabel("natural frequency omega (rad/s)")
    # the band is what matters: show up to 3x its upper edge (higher modes run off the top)
    f = chart.frequencies[np.isfinite(chart.frequencies)]
    top = min(float(f.max()) * 1.05 if f.size else hi, 3.0 * hi)
    a.set_ylim(0.0, max(top, 1.2 * hi))
    a.grid(True, alpha=0.3)
    handles = [band, *a.get_lines()]
    legend_below(fig, handles)
    hidden = int(np.sum(np.nanmin(chart.frequencies, axis=0) > a.get_ylim()[1]))
    note = f"; {hidden} higher modes above the axis" if hidden else ""
    a.set_title(wrap(f"{title}: deployment resonance chart ({chart.model} model{note})", 9.0,
                     11), fontsize=11)
    return fig


def plot_deployment(chart: Any, path: str | Path, title: str = "") -> Figure:
    """Save :func:`deployment_figure` (the deployment resonance chart) to ``path``.

    Parameters
    ----------
    chart : DeploymentChart
        Natural frequencies against paid-out length and the wave band.
    path : str or Path
        Where to save the figure (format from the suffix).
    title : str
        Start of the title; default empty.
    """
    fig = deployment_figure(chart, title)
    save(fig, path)
    return fig
