"""Figures of a mooring system: the solved lines in plan and in 3D, coloured by tension, and
the offset curve (restoring force and line tensions against the body's offset).

:func:`system_figure` draws every line of a
:class:`~cable_ocp.mooring.result.SystemResult` along its solved profile
(``result.solutions[name].position``), each as one collection of segments coloured by the
tension (kN, the mean of the segment's two node tensions) on one colour scale shared by all
lines: its limits are the smallest and largest node tension of the system. Anchors are
triangles, fairleads (body points) dots, free points (clumps, buoys, connections) labelled
squares; a body is its reference point with an arrow along its yaw (the heading of its
body-frame x axis, R = Rz(yaw) Ry(pitch) Rx(roll), docs/systems.md). The 3D view is drawn
at true scale unless the water column would be flatter than :data:`MIN_HEIGHT_RATIO` of the
plan's extent; then the vertical scale is exaggerated by a round factor named in its title.

:func:`offset_curve_figure` takes plain arrays (the design checks compute them): offsets
(m), the restoring force (N) and optionally each line's largest tension (N), drawn in kN.

Nothing is shown on screen (Agg canvas); save with :func:`cable_ocp.plots.common.save`.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.cm import ScalarMappable
from matplotlib.collections import LineCollection
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator
from mpl_toolkits.mplot3d.art3d import Line3DCollection

from cable_ocp.mooring.result import SystemResult
from cable_ocp.plots.common import legend_below, new_figure, nice_factor, save, wrap
from cable_ocp.scene.system import SystemScene

__all__ = ["draw_plan", "offset_curve_figure", "system_figure", "tension_norm"]

#: colour map of the tension (perceptually uniform, readable in grey)
TENSION_CMAP = "viridis"
#: the 3D view's vertical scale is exaggerated until the shown water column is at least
#: this fraction as tall as the plan is wide
MIN_HEIGHT_RATIO = 0.3
#: length of a body's heading arrow, as a fraction of the plan's largest extent
HEADING_FRACTION = 0.12

ANCHOR_STYLE = {"marker": "^", "color": "#8c6d4f", "ms": 10, "mec": "k", "mew": 0.8}
FAIRLEAD_STYLE = {"marker": "o", "color": "k", "ms": 4}
FREE_STYLE = {"marker": "s", "color": "#f28e2b", "ms": 8, "mec": "k", "mew": 0.8}
BODY_STYLE = {"marker": "o", "mfc": "none", "mec": "#c0504d", "mew": 2.0, "ms": 13}
HEADING_COLOR = "#c0504d"
SEABED_COLOR, SURFACE_COLOR = "#8c6d4f", "#2f6fb0"
POINT_STYLE = {"fixed": ANCHOR_STYLE, "body": FAIRLEAD_STYLE, "free": FREE_STYLE}
POINT_LABEL = {"fixed": "anchor (fixed point)", "body": "fairlead (body point)",
               "free": "free point (clump, buoy, connection)"}


def _drawn_lines(result: SystemResult) -> list[tuple[str, Any]]:
    """(name, solution) of each line with a finite solved profile, in the result's order."""
    out = []
    for ln in result.lines:
        sol = result.solutions.get(ln["name"])
        if sol is None:
            continue
        r, t = np.asarray(sol.position, float), np.asarray(sol.tension, float)
        if len(r) >= 2 and np.isfinite(r).all() and np.isfinite(t).all():
            out.append((ln["name"], sol))
    return out


def tension_norm(result: SystemResult) -> Normalize:
    """The colour scale of the tension, kN: from the smallest to the largest node tension
    of all drawn lines (one scale for the whole system).

    Parameters
    ----------
    result : SystemResult
        The solved system; lines without a finite profile are left out.
    """
    tens = [np.asarray(sol.tension, float) / 1e3 for _, sol in _drawn_lines(result)]
    if not tens:
        return Normalize(0.0, 1.0)
    lo, hi = float(min(t.min() for t in tens)), float(max(t.max() for t in tens))
    if hi <= lo:  # every node at one tension: a scale of nonzero width around it
        lo, hi = lo - 0.5, hi + 0.5
    return Normalize(lo, hi)


def _segments(r: np.ndarray, dims: int) -> np.ndarray:
    """Segments (n - 1, 2, dims) between consecutive nodes of ``r`` (n, 3)."""
    return np.stack([r[:-1, :dims], r[1:, :dims]], axis=1)


def _segment_tension(t: np.ndarray) -> np.ndarray:
    """Tension of each segment, kN: the mean of its two node tensions (N)."""
    return 0.5 * (t[:-1] + t[1:]) / 1e3


def _midpoint(sol: Any) -> np.ndarray:
    """The node position (3,) at half the line's unstretched length, m."""
    s = np.asarray(sol.s, float)
    r = np.asarray(sol.position, float)
    return np.array([np.interp(0.5 * s[-1], s, r[:, k]) for k in range(3)])


def _yaw_rad(body: dict[str, Any]) -> float:
    return math.radians(float(body["rotation_deg"][2]))


def _plan_extent(result: SystemResult) -> tuple[np.ndarray, np.ndarray]:
    """(lo, hi) of x, y over every node, point and body reference point, m."""
    pts = [np.asarray(sol.position, float)[:, :2] for _, sol in _drawn_lines(result)]
    pts += [np.asarray([p["position"][:2] for p in result.points], float).reshape(-1, 2)]
    pts += [np.asarray([b["position"][:2] for b in result.bodies], float).reshape(-1, 2)]
    allp = np.vstack(pts)
    allp = allp[np.isfinite(allp).all(axis=1)]
    if not len(allp):
        return np.zeros(2), np.ones(2)
    return allp.min(axis=0), allp.max(axis=0)



class _Spots:
    """Label positions clear of what is drawn: of the candidate directions around a point,
    the one whose label lies farthest from every node, point and earlier label."""

    def __init__(self, taken: np.ndarray, span: float) -> None:
        self.taken = np.asarray(taken, float).reshape(-1, 2)
        self.taken = self.taken[np.isfinite(self.taken).all(axis=1)]
        self.span = span

    def place(self, at: np.ndarray, dist: float,
              directions: list[np.ndarray] | None = None) -> np.ndarray:
        """A label spot ``dist`` (fraction of the plan's extent) from ``at`` (2,), m."""
        if directions is None:
            directions = [np.array([math.cos(a), math.sin(a)])
                          for a in np.radians(np.arange(0.0, 360.0, 30.0))]
        cands = [np.asarray(at, float) + dist * self.span * d for d in directions]
        clear = [float(np.min(np.hypot(*(self.taken - c).T))) if len(self.taken) else 0.0
                 for c in cands]
        best = cands[int(np.argmax(clear))]
        self.taken = np.vstack([self.taken, best])
        return best


def draw_plan(ax: Axes, result: SystemResult, norm: Normalize | None = None,
              cmap: str = TENSION_CMAP) -> ScalarMappable:
    """Draw the plan view (x-y, true scale) of a system on ``ax``; return the mappable of
    its colour scale (for a colorbar).

    Each line is a :class:`~matplotlib.collections.LineCollection` (gid ``"line:NAME"``)
    whose segments are the solved node positions and whose values are the segment
    tensions in kN; each body's heading arrow is an annotation with gid ``"heading:NAME"``
    from the reference point along (cos yaw, sin yaw).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        A 2D axes.
    result : SystemResult
        The solved system.
    norm : matplotlib.colors.Normalize, optional
        The tension scale, kN (default :func:`tension_norm`).
    cmap : str
        The colour map (default :data:`TENSION_CMAP`).
    """
    norm = norm or tension_norm(result)
    lo, hi = _plan_extent(result)
    span = max(float((hi - lo).max()), 1e-6)
    drawn = _drawn_lines(result)
    # what a label must keep clear of: the lines, the points, the heading arrows
    taken = [np.asarray(sol.position, float)[:, :2] for _, sol in drawn]
    taken += [np.asarray([p["position"][:2] for p in result.points], float).reshape(-1, 2)]
    heads = []
    for b in result.bodies:
        ref = np.asarray(b["position"][:2], float)
        yaw = _yaw_rad(b)
        tip = ref + HEADING_FRACTION * span * np.array([math.cos(yaw), math.sin(yaw)])
        heads.append((b, ref, tip))
        taken.append(ref + np.outer(np.linspace(0.0, 1.0, 12), tip - ref))
    spots = _Spots(np.vstack(taken), span)
    for name, sol in drawn:
        r = np.asarray(sol.position, float)
        lc = LineCollection(_segments(r, 2), cmap=cmap, norm=norm, lw=2.4, zorder=3,
                            gid=f"line:{name}", capstyle="round")
        lc.set_array(_segment_tension(np.asarray(sol.tension, float)))
        ax.add_collection(lc)
        # the name beside the line at its middle, on the clearer side
        d = r[-1, :2] - r[0, :2]
        nrm = np.array([-d[1], d[0]]) / max(float(np.hypot(*d)), 1e-12)
        at = spots.place(_midpoint(sol)[:2], 0.06, [nrm, -nrm])
        ax.text(at[0], at[1], name, fontsize=9, ha="center", va="center", zorder=6,
                gid=f"name:{name}",
                bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none",
                      "alpha": 0.8})
    for kind in ("fixed", "body", "free"):
        pts = [p for p in result.points if p["kind"] == kind]
        if not pts:
            continue
        xy = np.asarray([p["position"][:2] for p in pts], float)
        ax.plot(xy[:, 0], xy[:, 1], ls="none", zorder=5, label=POINT_LABEL[kind],
                gid=f"points:{kind}", **POINT_STYLE[kind])
        if kind == "body":
            continue  # fairleads sit metres apart at the body: their names would overlap
        for p, q in zip(pts, xy, strict=True):
            at = spots.place(q, 0.05)
            ax.text(at[0], at[1], p["name"], fontsize=8, ha="center", va="center",
                    zorder=6, color="0.25" if kind == "fixed" else "k",
                    gid=f"label:{p['name']}")
    for b, ref, tip in heads:
        ax.plot([ref[0]], [ref[1]], ls="none", zorder=4, label="body reference point",
                **BODY_STYLE)
        ax.annotate("", xy=(float(tip[0]), float(tip[1])),
                    xytext=(float(ref[0]), float(ref[1])), zorder=6, gid=f"heading:{b['name']}",
                    arrowprops={"arrowstyle": "-|>", "lw": 2.0, "color": HEADING_COLOR,
                                "mutation_scale": 14, "shrinkA": 0, "shrinkB": 0})
        ax.plot([], [], color=HEADING_COLOR, lw=2.0,
                label="body heading (its x axis, at its yaw)")
        yaw_deg = float(b["rotation_deg"][2])
        yaw_deg = 0.0 if abs(yaw_deg) < 1e-9 else yaw_deg  # round-off of a zero yaw
        at = spots.place(ref, 0.075)
        ax.text(at[0], at[1], f"{b['name']}\nyaw {yaw_deg:.3g}°", fontsize=8, ha="center",
                va="center", color=HEADING_COLOR, zorder=6, gid=f"label:{b['name']}")
    pad = 0.09 * span
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.grid(True, alpha=0.25, lw=0.6)
    sm = ScalarMappable(norm=norm, cmap=cmap)
    sm.set_array([])
    return sm


def _water(scene: SystemScene | None) -> float | None:
    return float(scene.environment.water_depth) if scene is not None else None


def _draw_3d(ax: Any, result: SystemResult, norm: Normalize, cmap: str,
             depth: float | None) -> float:
    """The 3D view; returns its vertical exaggeration (-)."""
    lo2, hi2 = _plan_extent(result)
    zs = [np.asarray(sol.position, float)[:, 2] for _, sol in _drawn_lines(result)]
    zs += [np.asarray([p["position"][2] for p in result.points], float)]
    zs += [np.asarray([b["position"][2] for b in result.bodies], float)]
    zall = np.concatenate(zs)
    zall = zall[np.isfinite(zall)]
    z_lo, z_hi = (float(zall.min()), float(zall.max())) if len(zall) else (0.0, 1.0)
    if depth is not None:
        z_lo, z_hi = min(z_lo, 0.0), max(z_hi, depth)
    span = max(float((hi2 - lo2).max()), 1e-6)
    pad = 0.04 * span
    lo = np.array([lo2[0] - pad, lo2[1] - pad, z_lo])
    hi = np.array([hi2[0] + pad, hi2[1] + pad, max(z_hi, z_lo + 1e-6)])
    if depth is not None:
        xx, yy = np.meshgrid([lo[0], hi[0]], [lo[1], hi[1]])
        ax.plot_surface(xx, yy, np.zeros_like(xx), color=SEABED_COLOR, alpha=0.12, lw=0,
                        shade=False, zorder=0)
        ax.plot_surface(xx, yy, np.full_like(xx, depth), color=SURFACE_COLOR, alpha=0.08,
                        lw=0, shade=False, zorder=0)
        ax.plot([], [], color=SEABED_COLOR, alpha=0.5, lw=6, label="seabed, z = 0 m")
        ax.plot([], [], color=SURFACE_COLOR, alpha=0.4, lw=6,
                label=f"free surface, z = {depth:.4g} m")
    for name, sol in _drawn_lines(result):
        r = np.asarray(sol.position, float)
        lc = Line3DCollection(_segments(r, 3), cmap=cmap, norm=norm, lw=2.2, gid=f"line:{name}")
        lc.set_array(_segment_tension(np.asarray(sol.tension, float)))
        ax.add_collection3d(lc)
    for kind in ("fixed", "body", "free"):
        pts = np.asarray([p["position"] for p in result.points if p["kind"] == kind], float)
        if len(pts):
            st = dict(POINT_STYLE[kind])
            st["ms"] = st["ms"] * 0.8
            ax.plot(pts[:, 0], pts[:, 1], pts[:, 2], ls="none", zorder=5, **st)
    for b in result.bodies:
        p = np.asarray(b["position"], float)
        ax.plot([p[0]], [p[1]], [p[2]], ls="none", zorder=4, **{**BODY_STYLE, "ms": 9})
    ext = np.maximum(hi - lo, 1e-9)
    k = nice_factor(MIN_HEIGHT_RATIO * max(ext[0], ext[1]) / ext[2])
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect((ext[0], ext[1], ext[2] * k), zoom=1.05)
    ax.view_init(elev=24, azim=-40)
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(4))
    ax.tick_params(labelsize=7, pad=0)
    ax.set_xlabel("x (m)", fontsize=8, labelpad=2)
    ax.set_ylabel("y (m)", fontsize=8, labelpad=2)
    ax.set_zlabel("z (m)", fontsize=8, labelpad=6)
    return k


def _summary(result: SystemResult) -> str:
    """The largest tension and the smallest safety factor, with their lines."""
    rows = [ln for ln in result.lines if ln.get("max_tension") is not None
            and math.isfinite(ln["max_tension"])]
    if not rows:
        return "no line tension"
    top = max(rows, key=lambda ln: ln["max_tension"])
    text = f"largest tension {top['max_tension'] / 1e3:.4g} kN ({top['name']})"
    sf = [ln for ln in rows if ln.get("safety_factor") is not None]
    if sf:
        low = min(sf, key=lambda ln: ln["safety_factor"])
        text += f"\nsmallest safety factor {low['safety_factor']:.3g} ({low['name']})"
    else:
        text += "\nno safety factor (no MBL given)"
    return text


def system_figure(result: SystemResult, scene: SystemScene | None = None,
                  title: str | None = None) -> Figure:
    """A solved mooring system in plan (x-y, true scale) and in 3D, the lines coloured by
    tension (kN, one colour scale: :func:`tension_norm`), with the largest tension and the
    smallest safety factor in a box.

    The axes are labelled ``"plan"`` and ``"3d"`` (and the colorbar's ``"tension"``).

    Parameters
    ----------
    result : SystemResult
        The system to draw (a failed one too: its status is written in red).
    scene : SystemScene, optional
        The solved scene: with it the seabed (z = 0) and the free surface
        (z = water_depth, m) are drawn in the 3D view, and the default title is its
        ``[meta] title``.
    title : str, optional
        The figure's title (default: the scene's title, if any).
    """
    head = title if title is not None else (scene.meta.get("title", "") if scene else "")
    norm = tension_norm(result)
    fig = new_figure(12.0, 6.4)
    gs = fig.add_gridspec(1, 2, width_ratios=[1.0, 1.3])
    ax_plan = fig.add_subplot(gs[0, 0], label="plan")
    ax_3d = fig.add_subplot(gs[0, 1], projection="3d", label="3d")
    sm = draw_plan(ax_plan, result, norm)
    ax_plan.set_title("Plan view (x-y, true scale)", fontsize=9.5)
    k = _draw_3d(ax_3d, result, norm, TENSION_CMAP, _water(scene))
    ax_3d.set_title("3D view" + (f" (vertical exaggeration {k:g}x)" if k != 1.0
                                 else " (true scale)"), fontsize=9.5)
    cb = fig.colorbar(sm, ax=[ax_plan, ax_3d], location="right", shrink=0.8, aspect=30,
                      pad=0.06)
    cb.set_label("line tension (kN)")
    cb.ax.set_label("tension")
    ax_3d.text2D(0.02, 0.98, _summary(result), transform=ax_3d.transAxes, fontsize=8.5,
                 va="top", ha="left", gid="summary",
                 bbox={"boxstyle": "round,pad=0.35", "fc": "white", "ec": "0.6"})
    ok = result.status == "solved"
    nb = len(result.bodies)
    info = (f"{len(result.lines)} lines, {nb} {'body' if nb == 1 else 'bodies'}: "
            + ("solved" if ok else f"not a success: status {result.status} ({result.message})"))
    fig.suptitle(wrap((head + "\n" if head else "") + info, fig.get_figwidth(), 11),
                 fontsize=11, color="k" if ok else "#b00000")
    handles = ax_plan.get_lines() + ax_3d.get_lines()
    legend_below(fig, handles)
    return fig


def offset_curve_figure(offsets: np.ndarray, restoring: np.ndarray,
                        tensions: dict[str, np.ndarray] | None = None,
                        title: str | None = None) -> Figure:
    """The restoring force against the offset, and optionally each line's largest tension
    against the offset on a second panel (axes labelled ``"restoring"``, ``"tensions"``).

    Parameters
    ----------
    offsets : numpy.ndarray
        The body's offsets, m, shape (n,).
    restoring : numpy.ndarray
        The mooring's restoring force at each offset, N, shape (n,) (drawn in kN).
    tensions : dict, optional
        Line name -> its largest tension at each offset, N, shape (n,) (drawn in kN).
    title : str, optional
        The figure's title.
    """
    x = np.asarray(offsets, float).ravel()
    f = np.asarray(restoring, float).ravel()
    if f.shape != x.shape:
        raise ValueError(f"restoring has shape {f.shape}, offsets {x.shape}: give one "
                         "force per offset")
    tensions = dict(tensions or {})
    for name, t in tensions.items():
        if np.asarray(t).ravel().shape != x.shape:
            raise ValueError(f"tensions[{name!r}] has shape {np.asarray(t).shape}, offsets "
                             f"{x.shape}: give one tension per offset")
    panels = 2 if tensions else 1
    fig = new_figure(5.2 * panels + 0.6, 4.4)
    axes = fig.subplots(1, panels, squeeze=False)[0]
    ax = axes[0]
    ax.set_label("restoring")
    ax.plot(x, f / 1e3, "-o", ms=3.5, lw=1.6, color="#1f4e79", label="restoring force",
            gid="restoring")
    ax.axhline(0.0, color="k", lw=0.6)
    ax.axvline(0.0, color="k", lw=0.6)
    ax.set_xlabel("offset (m)")
    ax.set_ylabel("restoring force (kN)")
    ax.set_title("Restoring force of the mooring", fontsize=9.5)
    ax.grid(True, alpha=0.25, lw=0.6)
    handles = list(ax.get_lines()[:1])
    if tensions:
        ax_t = axes[1]
        ax_t.set_label("tensions")
        for name, t in tensions.items():
            (h,) = ax_t.plot(x, np.asarray(t, float).ravel() / 1e3, "-o", ms=3, lw=1.4,
                             label=f"line {name}: largest tension", gid=f"tension:{name}")
            handles.append(h)
        ax_t.axvline(0.0, color="k", lw=0.6)
        ax_t.set_xlabel("offset (m)")
        ax_t.set_ylabel("largest line tension (kN)")
        ax_t.set_title("Largest tension of each line", fontsize=9.5)
        ax_t.grid(True, alpha=0.25, lw=0.6)
    if title:
        fig.suptitle(wrap(title, fig.get_figwidth(), 11), fontsize=11)
    legend_below(fig, handles)
    return fig


def plot_system(result: SystemResult, path: str | Path, title: str = "",
                scene: SystemScene | None = None) -> Figure:
    """Save the plan and 3D views of a system (:func:`system_figure`) to ``path``.

    Parameters
    ----------
    result : SystemResult
        The result (a failed one too: its status is written in red).
    path : str or Path
        Output file; the format follows the suffix.
    title : str
        Figure title (default: the figure's own).
    scene : SystemScene, optional
        The scene solved (the seabed and the free surface).
    """
    fig = system_figure(result, scene=scene, title=title or None)
    save(fig, path)
    return fig
