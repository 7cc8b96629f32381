"""Figures of the cable dynamics: a simulation (the unit's heave or trajectory from its static
position, tension envelope along the cable, top against unit heave, top tension in time;
for the lumped-mass model also a plan and a 3D view), mode shapes (axial modes as axial
displacement against depth), and the deployment resonance chart (natural frequencies
against paid-out length, the wave band shaded)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

from cable_ocp.plots.common import force_scale, legend_below, new_figure, save, series, wrap


def _reference(scene: Any) -> tuple[str, str]:
    """(what the t = 0 state is, its subscript): ``("static", "static")`` for a static start
    (the default, and when the scene is not given), ``("t = 0", "0")`` for an unstrained one."""
    start = getattr(getattr(scene, "simulation", None), "start", "static")
    return ("static", "static") if start == "static" else ("t = 0", "0")


def simulation_figure(res: Any, title: str = "", scene: Any = None) -> Figure:
    """The panels of a :class:`cable_ocp.dynamics.result.SimulationResult`.

    Four panels: the unit's heave z - z_static (or its trajectory in its vertical plane of
    largest motion, both relative to its static position), the tension envelope along the
    cable, top against unit heave, and the top tension. A lumped-mass (3D) run adds a plan
    view (x-y) and a 3D view of the line at t = 0 and at the end with the paths of the unit
    and the top. Time series of many samples are drawn as envelopes
    (:func:`cable_ocp.plots.common.series`). Axes labels: ``"unit"``, ``"tension"``,
    ``"heave"``, ``"top tension"``, ``"plan"``, ``"3d"``.

    Parameters
    ----------
    res : SimulationResult
        The simulation: unit and top positions (m), segment and top tensions (N), length
        (m), slack record, status; a failed run is drawn too, its status in red.
    title : str
        First line of the figure's title (the model and simulated time follow); empty
        (default): an empty first line.
    scene : DynamicScene, optional
        The scene: its ``simulation.start`` says whether the t = 0 state is the static one
        (default None: it is taken to be).
    """
    three_d = res.model == "lumped3d"
    fig = new_figure(12.0, 12.0 if three_d else 8.0)
    gs = fig.add_gridspec(3 if three_d else 2, 2)
    t = res.t
    what, sub = _reference(scene)
    handles: list[Any] = []
    # the unit's motion relative to its static position: trajectory or heave
    up = res.unit_position
    rel = up - up[0]
    span = np.ptp(rel[:, :2], axis=0)
    k = int(np.argmax(span))
    axis = "xy"[k]
    a = fig.add_subplot(gs[0, 0], label="unit")
    heave_label = f"unit heave z - z_{sub} (m)"
    if span[k] > 1e-9 * max(1.0, abs(up[0, 2])):
        a.plot(rel[:, k], rel[:, 2], lw=1.0, color="C0", gid="unit-trajectory")
        a.plot(0.0, 0.0, "o", color="k", ms=5, label=f"unit at t = 0 ({what})")
        a.set_xlabel(f"unit {axis} - {axis}_{sub} (m)")
        a.set_title(f"Unit trajectory from its {what} position (side view)")
    else:
        series(a, t, rel[:, 2], label="", color="C0", lw=1.2)
        a.set_xlabel("time t (s)")
        a.set_title(f"Unit heave from its {what} position (the unit moves vertically only)")
    a.set_ylabel(heave_label)
    a.grid(True, alpha=0.3)
    # tension envelope along the cable
    a = fig.add_subplot(gs[0, 1], label="tension")
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
    a = fig.add_subplot(gs[1, 0], label="heave")
    in_time = [a]
    zt = res.top_position[:, 2] - res.top_position[0, 2]
    zu = rel[:, 2]
    paid = np.asarray(res.length, dtype=float) - float(res.length[0])
    handles.append(series(a, t, zt, color="C2",
                          label=f"top (end_b) heave z - z_{sub}").handle)
    if np.ptp(paid) > 0:
        # a deployment: the unit's descent by the paid-out length would hide its heave
        handles.append(series(a, t, zu + paid, color="C0",
                              label=f"unit (end_a) heave about its lowering path "
                                    f"(z - z_{sub} + paid-out length)").handle)
        a.set_title("Top against unit heave (pay-out taken out)")
    else:
        handles.append(series(a, t, zu, color="C0",
                              label=f"unit (end_a) heave z - z_{sub}").handle)
        a.set_title("Top against unit heave")
    a.set_xlabel("time t (s)")
    a.set_ylabel(f"heave from the {what} position (m)")
    a.grid(True, alpha=0.3)
    # top tension and length in time
    a = fig.add_subplot(gs[1, 1], label="top tension")
    in_time.append(a)
    sc2, unit2 = force_scale(float(np.nanmax(np.abs(res.top_tension))))
    handles.append(series(a, t, res.top_tension / sc2, color="C3", label="top tension").handle)
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
        for axx in in_time:
            axx.axvline(slack["first_time"], color="r", lw=0.8, ls="--", label="first slack")
    if three_d:
        _plan_view(fig.add_subplot(gs[2, 0], label="plan"), res)
        _view_3d(fig.add_subplot(gs[2, 1], projection="3d", label="3d"), res)
    for axx in fig.axes:
        handles += axx.get_legend_handles_labels()[0]
    legend_below(fig, handles)
    status = "" if res.status == "solved" else f" - {res.status}: {res.message}"
    fig.suptitle(f"{title}\n{res.model} model, {t[-1] - t[0]:.4g} s simulated{status}",
                 fontsize=11, color="k" if res.status == "solved" else "firebrick")
    return fig


def _snapshots(res: Any, count: int = 4) -> np.ndarray:
    """Indices of ``count`` samples evenly spread over the run, without the first and last."""
    n = len(res.t)
    return np.unique(np.linspace(0, n - 1, count + 2).round().astype(int))[1:-1]


def _plan_view(a: Any, res: Any) -> None:
    """The line seen from above (x-y): at t = 0, a few times between and at the end, and the
    paths of the unit and the top."""
    r = res.node_positions
    for i in _snapshots(res):
        a.plot(r[i, :, 0], r[i, :, 1], color="0.75", lw=0.8, gid="snapshot",
               label="line between (evenly spaced times)")
    a.plot(r[0, :, 0], r[0, :, 1], color="k", lw=1.6, gid="line-start",
           label="line at t = 0")
    a.plot(r[-1, :, 0], r[-1, :, 1], color="C4", lw=1.4, ls="--", gid="line-end",
           label=f"line at t = {res.t[-1]:.4g} s")
    a.plot(res.unit_position[:, 0], res.unit_position[:, 1], color="C0", lw=0.8,
           gid="unit-path", label="path of the unit (end_a)")
    a.plot(res.top_position[:, 0], res.top_position[:, 1], color="C2", lw=0.8,
           gid="top-path", label="path of the top (end_b)")
    a.plot(r[0, 0, 0], r[0, 0, 1], "o", color="C0", ms=5)
    a.plot(r[0, -1, 0], r[0, -1, 1], "s", color="C2", ms=5)
    a.set_aspect("equal", adjustable="datalim")
    a.set_xlabel("x (m)")
    a.set_ylabel("y (m)")
    a.set_title("Plan view (seen from above, to scale)")
    a.grid(True, alpha=0.3)


def _view_3d(a: Any, res: Any) -> None:
    """The line in 3D at t = 0, a few times between and at the end, with the paths of the
    unit and the top; an extent below half the largest is stretched to it (the title says
    which axes are not to scale)."""
    r = res.node_positions
    for i in _snapshots(res):
        a.plot(r[i, :, 0], r[i, :, 1], r[i, :, 2], color="0.75", lw=0.8)
    a.plot(r[0, :, 0], r[0, :, 1], r[0, :, 2], color="k", lw=1.6)
    a.plot(r[-1, :, 0], r[-1, :, 1], r[-1, :, 2], color="C4", lw=1.4, ls="--")
    for p, c in ((res.unit_position, "C0"), (res.top_position, "C2")):
        a.plot(p[:, 0], p[:, 1], p[:, 2], color=c, lw=0.8)
    pts = r.reshape(-1, 3)
    pts = pts[np.all(np.isfinite(pts), axis=1)]
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    ext = hi - lo
    big = max(float(ext.max()), 1e-9)
    shown = np.maximum(ext, 0.5 * big)
    mid = 0.5 * (lo + hi)
    a.set_xlim(mid[0] - shown[0] / 2, mid[0] + shown[0] / 2)
    a.set_ylim(mid[1] - shown[1] / 2, mid[1] + shown[1] / 2)
    a.set_zlim(mid[2] - shown[2] / 2, mid[2] + shown[2] / 2)
    a.set_box_aspect(tuple(shown), zoom=0.95)
    for ax_ in (a.xaxis, a.yaxis, a.zaxis):
        ax_.set_major_locator(MaxNLocator(4))
    a.tick_params(labelsize=7)
    a.set_xlabel("x (m)", fontsize=8)
    a.set_ylabel("y (m)", fontsize=8)
    a.set_zlabel("z (m)", fontsize=8)
    stretched = [c for c, e in zip("xyz", ext, strict=True) if e < 0.5 * big]
    a.set_title("3D view" + (" (to scale)" if not stretched else
                             f" ({', '.join(stretched)} stretched: not to scale)"))


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
        Passed on to :func:`simulation_figure` (its static or unstrained start); default
        None.
    """
    fig = simulation_figure(res, title, scene)
    save(fig, path)
    return fig


def axial_shapes(res: Any) -> np.ndarray | None:
    """The axial displacement of each mode shape along the static line, normalised to a
    largest magnitude of 1 (positive towards end_b), shape (n_modes, n_nodes); None when a
    shape moves the nodes across the line (the modes are not all axial).

    Parameters
    ----------
    res : ModesResult
        The modal analysis: mode shapes (n_modes, n_nodes, 3) and static node positions (m).
    """
    r = np.asarray(res.node_positions, dtype=float)
    shapes = np.asarray(res.shapes, dtype=float)
    if shapes.size == 0 or len(r) < 2:
        return None
    tangent = np.gradient(r, axis=0)
    tangent /= np.linalg.norm(tangent, axis=1, keepdims=True)
    u = np.einsum("mnk,nk->mn", shapes, tangent)
    across = shapes - u[:, :, None] * tangent[None]
    peak = np.max(np.abs(u), axis=1)
    if not np.all(peak > 0) or np.max(np.abs(across)) > 1e-6 * np.max(np.abs(shapes)):
        return None
    return u / peak[:, None]


def modes_figure(res: Any, title: str = "", max_modes: int = 6) -> Figure:
    """The figure of :func:`plot_modes`, built and not saved (``ModesResult.plot``): the
    first mode shapes: for axial modes (every shape along the line, e.g. the axial
    model) one panel of the axial displacement u against the depth below end_b, one curve
    per mode; otherwise one panel per mode in the vertical plane of the line (the shape's
    components along the line's horizontal direction and vertically, on the static
    profile).

    Parameters
    ----------
    res : ModesResult
        The modal analysis: frequencies (rad/s), mode shapes and static node positions
        (m). Axial shapes are normalised to a largest |u| of 1; the others are drawn scaled
        to 12 % of the line's extent.
    title : str
        Start of the title (``"{title}: natural modes of ..."``); default empty.
    max_modes : int
        Largest number of modes drawn, lowest first (default 6).
    """
    n = min(max_modes, len(res.frequencies))
    axial = axial_shapes(res) if n else None
    if axial is not None:
        fig = _axial_modes_figure(res, axial[:n])
    else:
        fig = _modes_panels(res, n)
    fig.suptitle(f"{title}: natural modes of the {res.model} model about the static state",
                 fontsize=11)
    return fig


def plot_modes(res: Any, path: str | Path, title: str = "", max_modes: int = 6) -> Figure:
    """Save :func:`modes_figure` (the first mode shapes) to ``path``.

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


def _axial_modes_figure(res: Any, u: np.ndarray) -> Figure:
    """Axial displacement against depth below end_b, one curve per mode."""
    fig = new_figure(7.0, 6.0)
    a = fig.add_subplot(label="axial modes")
    r = np.asarray(res.node_positions, dtype=float)
    depth = r[-1, 2] - r[:, 2]
    styles = ["-", "--", "-.", ":"]
    for k, uk in enumerate(u):
        a.plot(uk, depth, color=f"C{k}", ls=styles[(k // 10) % 4], lw=1.5, gid=f"mode {k + 1}",
               label=f"mode {k + 1}: {res.frequencies[k]:.4g} rad/s "
                     f"(period {res.periods[k]:.4g} s)")
    a.axvline(0.0, color="0.6", lw=0.8)
    a.set_ylim(float(depth.max()), float(depth.min()))  # end_b at the top
    a.set_xlim(-1.08, 1.08)
    a.set_xlabel("axial displacement u, normalised, + towards end_b (-)")
    a.set_ylabel("depth below end_b (m)")
    a.set_title("Axial mode shapes along the line (end_b at the top, the unit at the bottom)",
                fontsize=10)
    a.grid(True, alpha=0.3)
    legend_below(fig, a.get_lines(), ncols=2)
    return fig


def _modes_panels(res: Any, n: int) -> Figure:
    """One panel per mode: the shape on the static profile in the line's vertical plane."""
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
    return fig


def deployment_figure(chart: Any, title: str = "") -> Figure:
    """The figure of :func:`plot_deployment`, built and not saved: natural frequencies
    against paid-out length, the wave band shaded, crossings marked (the lengths at which
    lowering the unit passes through a resonance).

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
