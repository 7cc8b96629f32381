"""Figures over many statics solutions: a parameter sweep of the end forces, and the
footprint of a tethered seabed unit (its reach in every direction).

Every function returns the :class:`matplotlib.figure.Figure` it saved (built without
pyplot: nothing is shown on screen and nothing needs closing).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np
from matplotlib.collections import PolyCollection
from matplotlib.figure import Figure

from cable_ocp.plots.common import force_scale, legend_below, new_figure, save
from cable_ocp.plots.statics import CURRENT_COLOR, heading_words
from cable_ocp.scene import Scene
from cable_ocp.statics.footprint_nlp import FootprintResult


def plot_sweep(values: Sequence[float], forces: np.ndarray, path: str | Path, xlabel: str,
               title: str = "", labels: Sequence[str] = ("F_x", "F_y", "F_z"),
               overlays: dict[str, np.ndarray] | None = None,
               ylabel: str = "force at end_a", name: str = "") -> Figure:
    """Force components (N, shape (n, 3)) against a swept parameter.

    ``xlabel`` names the parameter with its unit, e.g. ``"psi0 (deg)"``; ``name`` names
    the method of ``forces``; ``overlays`` maps other methods' names to their forces,
    drawn as markers in the same colours (so that agreement shows). Returns the saved figure.

    Parameters
    ----------
    values : sequence of float
        The swept parameter's values, shape (n,), in the unit ``xlabel`` names.
    forces : numpy.ndarray
        Force components, N, shape (n, 3), one row per value; drawn in N, kN or MN,
        whichever suits the largest magnitude.
    path : str or Path
        Where to save the figure (format from the suffix).
    xlabel : str
        The x axis' label: the parameter with its unit, e.g. ``"psi0 (deg)"``.
    title : str
        The axes' title; empty (default): none.
    labels : sequence of str
        Names of the components, one per column of ``forces`` that is drawn (default
        ``("F_x", "F_y", "F_z")``).
    overlays : dict, optional
        Other methods' name -> forces, N, shape (n, 3), drawn as markers (at most three
        marker shapes, then repeated). None (default): none.
    ylabel : str
        The y axis' label without its unit (the unit is appended); default
        ``"force at end_a"``.
    name : str
        Name of the method of ``forces``, added to its legend entries; empty (default):
        the component names alone.
    """
    forces = np.asarray(forces, float)
    div, unit = force_scale(float(np.abs(forces).max()))
    fig = new_figure(8.0, 5.2)
    ax = fig.add_subplot(label="sweep")
    handles = []
    for k, lab in enumerate(labels):  # legend: one column per component
        (h,) = ax.plot(values, forces[:, k] / div, "o-", ms=3.5, color=f"C{k}",
                       label=f"{lab}, {name}" if name else lab)
        handles.append(h)
        for j, (other, arr) in enumerate((overlays or {}).items()):
            (h,) = ax.plot(values, np.asarray(arr)[:, k] / div, ls="none",
                           marker="xs+"[j % 3], ms=7, mew=1.3, color=f"C{k}",
                           label=f"{lab}, {other}")
            handles.append(h)
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(f"{ylabel} ({unit})")
    ax.grid(True, alpha=0.3)
    if title:
        ax.set_title(title, fontsize=10.5)
    legend_below(fig, handles, ncols=len(labels))
    save(fig, path)
    return fig


def footprint_figure(res: FootprintResult, title: str = "", scene: Scene | None = None
                     ) -> Figure:
    """Build (without saving) the figure of :func:`plot_footprint`: the footprint of a
    tethered unit, a plan view of the reachable unit positions around the ship with the
    unreachable directions marked, and the reach and cable length per direction.

    Parameters
    ----------
    res : FootprintResult
        The footprint to draw.
    title : str
        Figure title.
    scene : Scene, optional
        The footprint scene (for the current arrow and the limits in the titles).

    Returns
    -------
    matplotlib.figure.Figure
        The figure; its axes are labelled ``"plan"`` and ``"reach"``.
    """
    ok = np.isfinite(res.reach)
    ship = np.asarray(res.ship, float)
    theta = np.asarray(res.theta_deg, float)
    fig = new_figure(12.5, 6.4)
    gs = fig.add_gridspec(1, 2, width_ratios=[1.15, 1.0])
    ax = fig.add_subplot(gs[0, 0], label="plan")
    ax2 = fig.add_subplot(gs[0, 1], label="reach")
    handles = []
    allpts = np.asarray(res.points, float)
    pts = allpts[ok]
    reach_max = float(np.nanmax(res.reach)) if ok.any() else 1.0
    n = len(theta)
    if len(pts):
        # reachable sectors: triangles (ship, p_i, p_i+1) between neighbouring reachable
        # directions; the boundary breaks where a direction is unreachable
        tris = [[ship, allpts[i], allpts[(i + 1) % n]] for i in range(n)
                if ok[i] and ok[(i + 1) % n]]
        if tris:
            ax.add_collection(PolyCollection(tris, facecolors="#d9e8f5", edgecolors="#d9e8f5",
                                             linewidths=0.6,
                                             zorder=1))
        ring = np.where(ok[:, None], allpts, np.nan)
        ring = np.vstack([ring, ring[:1]])
        (h,) = ax.plot(ring[:, 0], ring[:, 1], "-", color="#1f4e79", lw=1.6, zorder=3,
                       label="footprint boundary (reachable area shaded)")
        handles.append(h)
        (h,) = ax.plot(pts[:, 0], pts[:, 1], "o", color="#1f4e79", ms=3.5, zorder=4,
                       label=f"unit position at the largest reach ({int(ok.sum())} of {n} "
                             "directions)")
        handles.append(h)
    if (~ok).any():
        for th in np.radians(theta[~ok]):
            d = np.array([math.cos(th), math.sin(th)])
            ax.plot(*np.column_stack([ship + 0.15 * reach_max * d,
                                      ship + 1.05 * reach_max * d]), "--", color="#d62728",
                    lw=1.0, zorder=2)
            ax.plot(*(ship + 1.05 * reach_max * d), "x", color="#d62728", ms=7, mew=1.8,
                    zorder=5)
        (h,) = ax.plot([], [], "--x", color="#d62728", lw=1.0, ms=7, mew=1.8,
                       label=f"unreachable direction ({int((~ok).sum())})")
        handles.append(h)
    (h,) = ax.plot(*ship, "^", color="k", ms=11, zorder=6, label="ship (end_b, plan position)")
    handles.append(h)
    lim = 1.2 * reach_max
    arrow = 0.25 * reach_max
    top = lim + (1.1 * arrow if scene is not None and scene.environment.current else 0.0)
    ptitle = "Plan view (true scale)"
    cur = scene.environment.current if scene is not None else None
    if cur is not None:
        ux, uy = cur.ux[-1], cur.uy[-1]
        speed = math.hypot(ux, uy)
        c = ship + np.array([-lim + 0.7 * arrow, lim + 0.55 * arrow])
        d = np.array([ux, uy]) / speed * arrow
        ax.annotate("", xy=tuple(c + 0.5 * d), xytext=tuple(c - 0.5 * d),
                    arrowprops={"arrowstyle": "-|>", "lw": 2.2, "color": CURRENT_COLOR,
                                "mutation_scale": 16}, zorder=7, gid="current")
        ptitle += (f"\ncurrent (arrow): {speed:.3g} m/s {heading_words(ux, uy)}"
                   + ("" if cur.uniform else " at the surface"))
    ax.set_xlim(ship[0] - lim, ship[0] + lim)
    ax.set_ylim(ship[1] - lim, ship[1] + top)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.grid(True, alpha=0.3)
    ax.set_title(ptitle, fontsize=9.5)

    (h,) = ax2.plot(theta, np.where(ok, res.reach, np.nan), "o-", ms=3, color="#1f4e79",
                    label="reach from the ship (m)")
    handles.append(h)
    (h,) = ax2.plot(theta, np.where(ok, res.length, np.nan), "s--", ms=3, color="#4f8f3a",
                    label="cable length at the optimum (m)")
    handles.append(h)
    for th in theta[~ok]:
        ax2.axvline(th, color="#d62728", lw=1.0, ls="--")
    ax2.set_xlim(theta.min() - 5, theta.max() + 5)
    ax2.set_xticks(np.arange(0, 361, 45))
    ax2.set_xlabel("direction theta from +x towards +y (deg)")
    ax2.set_ylabel("distance, length (m)")
    ax2.grid(True, alpha=0.3)
    sub = "Reach and cable length per direction"
    if scene is not None and scene.footprint is not None:
        fp = scene.footprint
        if fp.bound == "magnitude":
            sub += f"\nthrust |T_h| <= {fp.thrust_max:g} N"
        else:
            sub += f"\n|T_x| <= {fp.thrust_x_max:g} N, |T_y| <= {fp.thrust_y_max:g} N"
        sub += f", cable {fp.min_length:g} to {fp.max_length:g} m"
    ax2.set_title(sub, fontsize=9.5)
    fig.suptitle(title or "Footprint of the tethered unit", fontsize=11)
    legend_below(fig, handles, ncols=3)
    return fig


def plot_footprint(res: FootprintResult, path: str | Path, title: str = "",
                   scene: Scene | None = None) -> Figure:
    """Save :func:`footprint_figure` to ``path``.

    Parameters
    ----------
    res : FootprintResult
        The footprint to draw.
    path : str or Path
        Output file; the format follows the suffix.
    title : str
        Figure title.
    scene : Scene, optional
        The footprint scene (current arrow, limits in the titles).

    Returns
    -------
    matplotlib.figure.Figure
        The saved figure; its axes are labelled ``"plan"`` and ``"reach"``.
    """
    fig = footprint_figure(res, title, scene)
    save(fig, path)
    return fig

