"""Figures for statics results: the cable profile and tension.

Sweeps and footprints (many solutions in one figure) are in :mod:`cable_ocp.plots.statics_series`.

:func:`plot_statics` draws a planar line (every node in one vertical plane, to a tolerance)
as a side elevation in that plane; a three-dimensional line as a 3D view, a plan (x-y) and
an elevation (the projection on the vertical plane through the two ends). Both show the
tension along the cable. Elevations keep the sag visible: when the water column is much
wider than deep, the vertical scale is exaggerated by a round factor, and the z-axis label
says so. The seabed, the free surface, the touchdown point, the bodies at the joints, the
ends and the current are drawn; all legends sit below the panels, outside every axes.

Every function returns the :class:`matplotlib.figure.Figure` it saved (built without
pyplot: nothing is shown on screen and nothing needs closing).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

from cable_ocp.physics import seabed as seabed_mod
from cable_ocp.physics.current import profile_components_np
from cable_ocp.plots.common import (
    force_scale,
    legend_below,
    new_figure,
    nice_factor,
    save,
    wrap,
)
from cable_ocp.scene import Scene
from cable_ocp.statics.solution import StaticsSolution

#: a line is drawn as planar when every node lies within this fraction of its largest
#: extent of one vertical plane (1e-3: less than a pixel on a 1000-pixel panel)
PLANAR_TOL = 1e-3
#: elevations are exaggerated vertically until the shown water column is at least this
#: fraction as tall as it is wide
MIN_VIEW_RATIO = 0.3

SEABED_COLOR, SEABED_FILL = "#8c6d4f", "#efe6d8"
SURFACE_COLOR, WATER_FILL = "#2f6fb0", "#eef5fb"
CURRENT_COLOR = "#1f77b4"
TDP_STYLE = {"marker": "v", "color": "#d62728", "ms": 10, "mec": "k", "mew": 0.8}
BODY_STYLE = {
    "clump": {"marker": "h", "color": "0.3", "ms": 12, "mec": "k", "mew": 0.8},
    "buoy": {"marker": "o", "color": "#f28e2b", "ms": 12, "mec": "k", "mew": 0.8},
    "unit": {"marker": "D", "color": "#59a14f", "ms": 10, "mec": "k", "mew": 0.8},
}
END_MARKER = {"a": "s", "b": "^"}
SEGMENT_COLORS = ["#1f4e79", "#c0504d", "#4f8f3a", "#8064a2", "#d4a017", "#2aa198"]


# --------------------------------------------------------------------------------------
# Geometry: the vertical plane of an elevation
# --------------------------------------------------------------------------------------

@dataclass(frozen=True)
class ElevationPlane:
    """A vertical plane to draw an elevation in.

    Attributes
    ----------
    e : ndarray, shape (2,)
        Horizontal unit vector along which the elevation's horizontal coordinate runs.
    origin : ndarray, shape (2,)
        Horizontal point of the plane where that coordinate is 0, m.
    axis : str or None
        ``"x"`` or ``"y"`` when the plane is parallel to that axis (the coordinate is then
        the x or y coordinate itself).
    planar : bool
        True when every node lies within :data:`PLANAR_TOL` of the line's extent of a
        vertical plane (the elevation is then the line itself, not a projection).
    deviation : float
        Largest horizontal distance of the nodes from this plane, m.
    """

    e: np.ndarray
    origin: np.ndarray
    axis: str | None
    planar: bool
    deviation: float

    @property
    def normal(self) -> np.ndarray:
        """Horizontal unit normal (e rotated by +90 deg), shape (2,)."""
        return np.array([-self.e[1], self.e[0]])

    @property
    def heading_deg(self) -> float:
        """Direction of ``e``, deg from +x towards +y."""
        return math.degrees(math.atan2(self.e[1], self.e[0]))

    def coord(self, xy: np.ndarray) -> np.ndarray:
        """Horizontal coordinate in the plane of points ``xy`` (..., 2), m."""
        return (np.asarray(xy, float)[..., :2] - self.origin) @ self.e

    def across(self, xy: np.ndarray) -> np.ndarray:
        """Signed horizontal distance of points from the plane, m."""
        return (np.asarray(xy, float)[..., :2] - self.origin) @ self.normal

    def point(self, h: np.ndarray) -> np.ndarray:
        """Horizontal points (n, 2) of the plane at coordinates ``h``."""
        return self.origin + np.outer(np.atleast_1d(h), self.e)

    @property
    def label(self) -> str:
        """Axis label of the horizontal coordinate."""
        if self.axis:
            return f"{self.axis} (m)"
        return f"horizontal distance along {self.heading_deg:.1f}° (m)"

    @property
    def name(self) -> str:
        """The plane in words (for titles)."""
        if self.axis == "x":
            return f"the plane y = {_clean(self.origin[1]):.4g} m"
        if self.axis == "y":
            return f"the plane x = {_clean(self.origin[0]):.4g} m"
        return f"the vertical plane through end_a at {self.heading_deg:.1f}° from +x"


def _clean(v: float, scale: float = 1.0) -> float:
    """``v`` with round-off below 1e-9 of ``scale`` (m) shown as 0."""
    return 0.0 if abs(v) < 1e-9 * max(scale, 1.0) else float(v)


def elevation_plane(r: np.ndarray, tol: float = PLANAR_TOL) -> ElevationPlane:
    """The vertical plane in which to draw the line ``r`` (n, 3) in elevation.

    The line is planar when the best-fitting vertical plane (principal direction of the
    horizontal node positions) holds every node to ``tol`` times the line's largest
    extent. A planar line is drawn in that plane; a 3D line is projected on the vertical
    plane through its ends. A plane within ``tol`` of an axis direction is snapped to it.

    Parameters
    ----------
    r : numpy.ndarray
        Node positions, m, shape (n, 3), from end_a to end_b.
    tol : float
        Relative tolerance (-), default :data:`PLANAR_TOL`: the line is planar when every
        node lies within ``tol`` times the line's largest extent of the fitted plane, and
        a plane whose horizontal direction has an x or y component of at most ``tol`` (an
        angle of about ``tol`` rad to an axis) is snapped to that axis.
    """
    r = np.asarray(r, float)
    xy = r[:, :2]
    extent = float(np.ptp(r, axis=0).max()) or 1.0
    chord = xy[-1] - xy[0]
    centred = xy - xy.mean(axis=0)
    if float(np.ptp(xy, axis=0).max()) <= 1e-9 * extent:  # a vertical line
        pca, dev_fit = np.array([1.0, 0.0]), 0.0
    else:
        pca = np.linalg.svd(centred, full_matrices=False)[2][0]
        dev_fit = float(np.abs(centred @ np.array([-pca[1], pca[0]])).max())
    planar = dev_fit <= tol * extent
    if not planar and np.hypot(*chord) > tol * extent:
        e = chord / np.hypot(*chord)
    else:
        e = pca
    if e @ chord < 0 or (abs(e @ chord) <= 1e-12 * extent and (e[0] < 0 or (e[0] == 0
                                                                             and e[1] < 0))):
        e = -e
    axis = None
    if abs(e[1]) <= tol:
        e, axis = np.array([1.0, 0.0]), "x"
    elif abs(e[0]) <= tol:
        e, axis = np.array([0.0, 1.0]), "y"
    origin = xy[0].copy()
    if axis == "x":
        origin = np.array([0.0, xy[0, 1]])
    elif axis == "y":
        origin = np.array([xy[0, 0], 0.0])
    normal = np.array([-e[1], e[0]])
    dev = float(np.abs((xy - origin) @ normal).max())
    return ElevationPlane(e=e, origin=origin, axis=axis, planar=planar, deviation=dev)


# --------------------------------------------------------------------------------------
# What there is to draw (from the solution and, when given, the scene)
# --------------------------------------------------------------------------------------

@dataclass
class _Item:
    """A marker: position (3,), matplotlib style, legend label, arc length s (m)."""

    position: np.ndarray
    style: dict[str, Any]
    label: str
    s: float | None = None
    tick: str = ""


def _fmt_force(f: float) -> str:
    return f"{f / 1e3:.4g} kN" if abs(f) >= 1e3 else f"{f:.4g} N"


def _end_item(which: str, sol: StaticsSolution, scene: Scene | None) -> _Item:
    pos = sol.position[0 if which == "a" else -1]
    s = 0.0 if which == "a" else float(sol.s[-1])
    name = f"end_{which}, s = {'0' if which == 'a' else 'L'}"
    filled = True
    if scene is not None:
        end = scene.end_a if which == "a" else scene.end_b
        mask = end.fixed_mask
        if all(mask):
            name += ", fixed"
        elif not any(mask):
            name += ", load prescribed"
            filled = False
        else:
            free = "".join(c for c, m in zip("xyz", mask, strict=True) if not m)
            name += f", free in {free}"
            filled = False
    style = {"marker": END_MARKER[which], "color": "k" if filled else "w", "mec": "k",
             "mew": 1.2, "ms": 9 if which == "b" else 8}
    return _Item(np.asarray(pos, float), style, name, s)


def _body_items(sol: StaticsSolution, scene: Scene | None) -> list[_Item]:
    items = []
    starts = None
    if scene is not None and scene.segments:
        starts = np.concatenate([[0.0], np.cumsum([c.length for c in scene.segments])])
    for i, b in enumerate(sol.diagnostics.get("bodies") or []):
        kind = b.get("kind", "body")
        pos = np.asarray(b["position"], float)
        desc = kind
        if scene is not None and i < len(scene.bodies):
            body = scene.bodies[i]
            if kind == "buoy":
                desc += f", {_fmt_force(body.net_buoyancy)} net buoyancy"
            else:
                desc += f", {_fmt_force(body.weight_in_water)} in water"
            if kind == "unit" and any(body.thrust):
                desc += f", thrust {_fmt_force(float(np.linalg.norm(body.thrust)))}"
        desc += f" (joint {b['joint']})"
        if starts is not None and b["joint"] < len(starts):
            s = float(starts[b["joint"]])
        else:
            s = float(sol.s[int(np.argmin(np.linalg.norm(sol.position - pos, axis=1)))])
        style = dict(BODY_STYLE.get(kind, {"marker": "P", "color": "m", "ms": 10}))
        items.append(_Item(pos, style, desc, s, kind))
    return items


def _touchdown_item(sol: StaticsSolution) -> _Item | None:
    td = sol.diagnostics.get("touchdown")
    if not td:
        return None
    g = float(td.get("grounded_length", sol.grounded_length))
    return _Item(np.asarray(td["position"], float), dict(TDP_STYLE),
                 f"touchdown point, {g:.1f} m grounded", g, "TDP")


def _segments(sol: StaticsSolution, scene: Scene | None) -> list[tuple[float, float, str, str]]:
    """(s0, s1, colour, label) of each segment."""
    if scene is None or len(scene.segments) <= 1:
        return [(0.0, float(sol.s[-1]), SEGMENT_COLORS[0], f"cable, L = {sol.length:.1f} m")]
    out, s0 = [], 0.0
    for k, c in enumerate(scene.segments):
        lab = f"segment {k + 1}: {c.length:g} m, {c.weight_in_water:g} N/m in water"
        if c.bending_stiffness > 0:
            lab += f", EI {c.bending_stiffness:g} N m²"
        out.append((s0, s0 + c.length, SEGMENT_COLORS[k % len(SEGMENT_COLORS)], lab))
        s0 += c.length
    return out


def _segment_slices(sol: StaticsSolution, segs: list[tuple[float, float, str, str]]
                    ) -> list[np.ndarray]:
    """Node indices of each segment (overlapping by one node so the curve is continuous)."""
    out = []
    n = len(sol.s)
    for k, (s0, s1, _, _) in enumerate(segs):
        lo = int(np.searchsorted(sol.s, s0, side="left")) if k else 0
        hi = int(np.searchsorted(sol.s, s1, side="right")) if k < len(segs) - 1 else n
        out.append(np.arange(max(lo - 1, 0), min(hi + 1, n) if k < len(segs) - 1 else n))
    return out


def heading_words(ux: float, uy: float) -> str:
    """Where a current of components (ux, uy) (m/s) flows to, in words ("towards +x", or
    the angle from +x towards +y in degrees).

    Parameters
    ----------
    ux, uy : float
        The current's horizontal velocity components along +x and +y, m/s (only the
        direction matters; within 0.05 deg of an axis, the axis is named).
    """
    ang = math.degrees(math.atan2(uy, ux)) % 360.0
    for a, name in ((0.0, "+x"), (90.0, "+y"), (180.0, "-x"), (270.0, "-y"), (360.0, "+x")):
        if abs(ang - a) < 0.05:
            return f"towards {name}"
    return f"towards {ang:.0f}° from +x"


@dataclass
class _CurrentInfo:
    z: np.ndarray
    ux: np.ndarray
    uy: np.ndarray
    uniform: bool

    def at(self, z: float) -> tuple[float, float]:
        ux, uy = profile_components_np(z, self.z, self.ux, self.uy)
        return float(ux), float(uy)


def _current(scene: Scene | None) -> _CurrentInfo | None:
    cur = scene.environment.current if scene is not None else None
    if cur is None or cur.max_speed == 0.0:
        return None
    return _CurrentInfo(np.asarray(cur.z, float), np.asarray(cur.ux, float),
                        np.asarray(cur.uy, float), cur.uniform)


# --------------------------------------------------------------------------------------
# The statics figure
# --------------------------------------------------------------------------------------

@dataclass
class _View:
    """The elevation's data window and vertical exaggeration."""

    h_lim: tuple[float, float]
    z_lim: tuple[float, float]
    exaggeration: float
    sky: tuple[float, float] | None  # z band above everything, for the current arrow
    seabed_shown: bool
    surface_shown: bool
    note: str

    @property
    def box_ratio(self) -> float:
        """Displayed height / width of the data window."""
        return (self.exaggeration * (self.z_lim[1] - self.z_lim[0])
                / (self.h_lim[1] - self.h_lim[0]))


class _Drawing:
    """Everything the panels share: geometry, items, environment, legend handles."""

    def __init__(self, sol: StaticsSolution, scene: Scene | None) -> None:
        self.sol, self.scene = sol, scene
        self.r = np.asarray(sol.position, float)
        self.plane = elevation_plane(self.r)
        self.ends = [_end_item("a", sol, scene), _end_item("b", sol, scene)]
        self.bodies = _body_items(sol, scene)
        self.tdp = _touchdown_item(sol)
        self.segs = _segments(sol, scene)
        self.slices = _segment_slices(sol, self.segs)
        env = scene.environment if scene is not None else None
        self.seabed = env.seabed if env is not None else None
        self.surface = float(env.water_depth) if env is not None else None
        self.current = _current(scene)
        self.handles: list[Any] = []

    @property
    def markers(self) -> list[_Item]:
        return ([self.tdp] if self.tdp else []) + self.bodies + self.ends

    def item_points(self) -> np.ndarray:
        return np.vstack([self.r] + [m.position[None, :] for m in self.markers])

    def seabed_z(self, xy: np.ndarray) -> np.ndarray:
        xy = np.atleast_2d(xy)
        if self.seabed is None:
            return np.zeros(len(xy))
        return np.asarray(seabed_mod.height(self.seabed, xy[:, 0], xy[:, 1]), float)

    def seabed_label(self) -> str:
        sb = self.seabed
        if sb is None:
            return "seabed z = 0 m (no contact modelled: checked only)"
        lab = "seabed (contact"
        if sb.friction:
            lab += f", friction {sb.friction:g}"
        if sb.slope_deg:
            lab += f", slope {sb.slope_deg:g}° rising towards {sb.slope_heading_deg:g}°"
        return lab + ")"

    def view(self, coord: np.ndarray, seabed_line: np.ndarray) -> _View:
        """Elevation window: the items, plus seabed and surface when they are near."""
        pts = self.item_points()
        z_lo_i, z_hi_i = float(pts[:, 2].min()), float(pts[:, 2].max())
        h_lo, h_hi = float(coord.min()), float(coord.max())
        z_span = max(z_hi_i - z_lo_i, 0.05 * (h_hi - h_lo), 1e-6)
        notes = []
        sb_hi = float(seabed_line.max())
        seabed_shown = self.seabed is not None or z_lo_i - sb_hi <= 0.5 * z_span
        if not seabed_shown:
            notes.append(f"seabed {z_lo_i - sb_hi:.4g} m below the lowest point, not shown")
        surface_shown = False
        if self.surface is not None:
            surface_shown = self.surface - z_hi_i <= 0.5 * z_span
            if not surface_shown:
                notes.append(f"surface {self.surface - z_hi_i:.4g} m above the highest point, "
                             "not shown")
        z_lo = min(z_lo_i, float(seabed_line.min())) if seabed_shown else z_lo_i
        z_hi = max(z_hi_i, self.surface) if surface_shown else z_hi_i  # type: ignore[type-var]
        zs = max(z_hi - z_lo, 1e-6)
        hs = h_hi - h_lo
        if hs < 0.5 * zs:  # a (nearly) vertical line: show some water around it
            mid = 0.5 * (h_lo + h_hi)
            h_lo, h_hi, hs = mid - 0.25 * zs, mid + 0.25 * zs, 0.5 * zs
        k = nice_factor(MIN_VIEW_RATIO * hs / zs)
        z_top = z_hi + (0.05 + (0.14 if self.current else 0.0)) * zs
        sky = (z_hi + 0.03 * zs, z_top) if self.current else None
        return _View((h_lo - 0.04 * hs, h_hi + 0.04 * hs), (z_lo - 0.07 * zs, z_top), k, sky,
                     seabed_shown, surface_shown, "; ".join(notes))

    def add(self, handle: Any, order: int = 5) -> None:
        """A legend entry; entries are listed by ``order`` (environment, cable, markers,
        references, current, tension), then in the order they were added."""
        self.handles.append((order, len(self.handles), handle))

    def legend(self) -> list[Any]:
        return [h for _, _, h in sorted(self.handles, key=lambda t: t[:2])]


def _z_label(k: float) -> str:
    return "z (m)" if k == 1.0 else f"z (m), vertical exaggeration {k:g}x"


def _elevation_view(dr: _Drawing) -> _View:
    plane = dr.plane
    h_all = np.concatenate([plane.coord(dr.r), [plane.coord(m.position) for m in dr.markers]])
    grid = np.linspace(h_all.min(), h_all.max(), 50)
    return dr.view(h_all, dr.seabed_z(plane.point(grid)))


def _draw_elevation(ax: Axes, dr: _Drawing, view: _View, width_in: float) -> None:
    plane = dr.plane
    coord = plane.coord(dr.r)
    hgrid = np.linspace(*view.h_lim, 200)
    zb = dr.seabed_z(plane.point(hgrid))
    bottom = view.z_lim[0]
    if view.surface_shown:
        ax.fill_between(hgrid, np.maximum(zb, bottom) if view.seabed_shown else bottom,
                        dr.surface, color=WATER_FILL, lw=0, zorder=0)
        (h,) = ax.plot(view.h_lim, [dr.surface] * 2, color=SURFACE_COLOR, lw=1.6,
                       label=f"free surface, z = {dr.surface:.4g} m", zorder=1, gid="surface")
        dr.add(h, 0)
    if view.seabed_shown:
        ax.fill_between(hgrid, bottom, zb, facecolor=SEABED_FILL, edgecolor=SEABED_COLOR,
                        hatch="///", lw=0, zorder=1)
        (h,) = ax.plot(hgrid, zb, color=SEABED_COLOR, lw=1.6, label=dr.seabed_label(),
                       zorder=2, gid="seabed")
        dr.add(h, 0)
    for (_, _, color, lab), idx in zip(dr.segs, dr.slices, strict=True):
        (h,) = ax.plot(coord[idx], dr.r[idx, 2], "-", color=color, lw=2.0, label=lab,
                       zorder=4, solid_capstyle="round", gid="cable")
        dr.add(h, 1)
    for m in dr.markers:
        (h,) = ax.plot([plane.coord(m.position)], [m.position[2]], ls="none", label=m.label,
                       zorder=6, **m.style)
        dr.add(h, 2)
    if dr.current is not None and view.sky is not None:
        _elevation_current_arrow(ax, dr, view)
    ax.set_xlim(*view.h_lim)
    ax.set_ylim(*view.z_lim)
    ax.set_aspect(view.exaggeration, adjustable="box")
    ax.set_xlabel(plane.label)
    ax.set_ylabel(_z_label(view.exaggeration))
    ax.grid(True, alpha=0.25, lw=0.6)
    if plane.planar:
        title = f"Side elevation in {plane.name}"
        if plane.deviation > 1e-9 * max(1.0, float(np.ptp(dr.r, axis=0).max())):
            title += f" (nodes within {plane.deviation:.2g} m of it)"
    else:
        title = ("Elevation, projected on the vertical plane through the ends"
                 + (f" (the {plane.axis}-z plane)" if plane.axis else
                    f" ({plane.heading_deg:.1f}° from +x, origin at end_a)"))
    lines = [title]
    if dr.current is not None:
        z_ref = min(dr.surface or np.inf, float(dr.r[:, 2].max()))
        ux, uy = dr.current.at(z_ref)
        speed = math.hypot(ux, uy)
        u_e, u_n = float(np.dot([ux, uy], plane.e)), float(np.dot([ux, uy], plane.normal))
        words = (f"current {speed:.3g} m/s {heading_words(ux, uy)}" if dr.current.uniform
                 else f"current at z = {z_ref:.4g} m: {speed:.3g} m/s "
                      f"{heading_words(ux, uy)} (varies: profile panel)")
        if abs(u_n) >= 0.01 * speed and abs(u_e) >= 0.1 * speed:
            words += f"; arrow: {abs(u_e):.3g} m/s along this plane"
        lines.append(words)
    if view.note:
        lines.append(view.note)
    ax.set_title(wrap("\n".join(lines), width_in), fontsize=9.5)


def _elevation_current_arrow(ax: Axes, dr: _Drawing, view: _View) -> None:
    """The current's component along the plane as an arrow in the band above the water."""
    assert dr.current is not None and view.sky is not None
    z_ref = min(dr.surface if dr.surface is not None else np.inf, float(dr.r[:, 2].max()))
    ux, uy = dr.current.at(z_ref)
    u_e = ux * dr.plane.e[0] + uy * dr.plane.e[1]
    u_n = ux * dr.plane.normal[0] + uy * dr.plane.normal[1]
    z = 0.5 * (view.sky[0] + view.sky[1])
    h0, h1 = view.h_lim
    width = h1 - h0
    speed = math.hypot(ux, uy)
    if abs(u_e) >= 0.1 * speed:
        length = 0.14 * width * (1.0 if u_e > 0 else -1.0)
        start = h0 + 0.04 * width + (0.0 if u_e > 0 else -length)
        ax.annotate("", xy=(start + length, z), xytext=(start, z),
                    arrowprops={"arrowstyle": "-|>", "lw": 2.2, "color": CURRENT_COLOR,
                                "mutation_scale": 16}, zorder=7, gid="current")
        tip = max(start, start + length)
        txt = f"{abs(u_e):.3g} m/s"
        ax.text(tip + 0.02 * width, z, txt, va="center", ha="left", fontsize=8,
                color=CURRENT_COLOR, zorder=7, clip_on=True)
    else:
        # viewer looks along d x z = (e_y, -e_x): flow along -normal comes out of the page
        sym = "\u2299" if u_n < 0 else "\u2297"
        ax.text(h0 + 0.05 * width, z, sym, va="center", ha="center", fontsize=15,
                color=CURRENT_COLOR, zorder=7, gid="current")
        ax.text(h0 + 0.09 * width, z, "out of the page" if u_n < 0 else "into the page",
                va="center", ha="left", fontsize=8, color=CURRENT_COLOR, clip_on=True)


def _draw_tension(ax: Axes, dr: _Drawing, width_in: float) -> None:
    sol, plane = dr.sol, dr.plane
    t = np.asarray(sol.tension_vector, float)
    mag = np.linalg.norm(t, axis=1)
    div, unit = force_scale(float(np.abs(t).max()))
    for (_, _, color, _), idx in zip(dr.segs, dr.slices, strict=True):
        ax.plot(sol.s[idx], mag[idx] / div, "-", color=color, lw=2.2, zorder=4)
    (h,) = ax.plot([], [], "-", color="k", lw=2.2, label="tension magnitude |T|")
    dr.add(h, 6)
    if plane.planar:
        comps = [(t[:, :2] @ plane.e, "#9467bd", "T horizontal (in the plane)"),
                 (t[:, 2], "#17becf", "T vertical, T_z")]
    else:
        comps = [(t[:, 0], "#9467bd", "T_x"), (t[:, 1], "#bcbd22", "T_y"),
                 (t[:, 2], "#17becf", "T_z")]
    for vals, color, lab in comps:
        (h,) = ax.plot(sol.s, vals / div, "--", color=color, lw=1.2, label=lab, zorder=5)
        dr.add(h, 6)
    ax.axhline(0.0, color="k", lw=0.6, zorder=2)
    ticks, names = [], []
    for m in ([dr.tdp] if dr.tdp else []) + dr.bodies:
        if m.s is not None:
            ax.axvline(m.s, color="0.45", lw=0.9, ls=":", zorder=1)
            ticks.append(m.s)
            names.append(m.tick)
    if ticks:
        top = ax.secondary_xaxis("top")
        top.set_xticks(ticks, names, fontsize=8)
        top.tick_params(length=3)
    ax.set_xlim(float(sol.s[0]), float(sol.s[-1]))
    ax.set_xlabel("unstretched arc length from end_a, s (m)")
    ax.set_ylabel(f"tension ({unit})")
    ax.grid(True, alpha=0.25, lw=0.6)
    end_b = mag[-1] if mag[-1] > 1e-9 * mag.max() else 0.0
    ax.set_title(wrap(f"Tension along the cable: max {sol.max_tension / div:.4g} {unit}, "
                       f"at end_a {mag[0] / div:.4g} {unit}, at end_b {end_b / div:.4g} {unit}",
                       width_in), fontsize=9.5)


@dataclass
class _PlanView:
    x_lim: tuple[float, float]
    y_lim: tuple[float, float]
    arrow_centre: np.ndarray
    arrow_length: float

    @property
    def box_ratio(self) -> float:
        return (self.y_lim[1] - self.y_lim[0]) / (self.x_lim[1] - self.x_lim[0])


def _plan_view(dr: _Drawing) -> _PlanView:
    """Plan window: the items (neither side under half the other), and a band above them
    for the current arrow."""
    pts = dr.item_points()
    lo, hi = pts[:, :2].min(axis=0), pts[:, :2].max(axis=0)
    span = max(float((hi - lo).max()), 1e-6)
    for i in range(2):
        if hi[i] - lo[i] < 0.5 * span:
            mid = 0.5 * (lo[i] + hi[i])
            lo[i], hi[i] = mid - 0.25 * span, mid + 0.25 * span
    pad, arrow = 0.06 * span, 0.12 * span
    top = hi[1] + pad + (2.6 * arrow if dr.current is not None else 0.0)
    centre = np.array([0.5 * (lo[0] + hi[0]), hi[1] + pad + 1.3 * arrow])
    return _PlanView((lo[0] - pad, hi[0] + pad), (lo[1] - pad, top), centre, arrow)


def _draw_plan(ax: Axes, dr: _Drawing, pv: _PlanView, width_in: float) -> None:
    r = dr.r
    ax.plot(r[[0, -1], 0], r[[0, -1], 1], ":", color="0.5", lw=1.0, zorder=2,
            label="_chord")
    for (_, _, color, _), idx in zip(dr.segs, dr.slices, strict=True):
        ax.plot(r[idx, 0], r[idx, 1], "-", color=color, lw=2.0, zorder=4, gid="cable")
    for m in dr.markers:
        ax.plot([m.position[0]], [m.position[1]], ls="none", zorder=6, **m.style)
    (h,) = ax.plot([], [], ":", color="0.5", lw=1.0, label="straight line end_a to end_b")
    dr.add(h, 3)
    title = "Plan view (x-y, true scale)"
    if dr.current is not None:
        z_ref = min(dr.surface if dr.surface is not None else np.inf, float(r[:, 2].max()))
        ux, uy = dr.current.at(z_ref)
        speed = math.hypot(ux, uy)
        d = np.array([ux, uy]) / speed * pv.arrow_length
        ax.annotate("", xy=tuple(pv.arrow_centre + 0.5 * d),
                    xytext=tuple(pv.arrow_centre - 0.5 * d),
                    arrowprops={"arrowstyle": "-|>", "lw": 2.2, "color": CURRENT_COLOR,
                                "mutation_scale": 16}, zorder=7, gid="current")
        title += (f"\ncurrent (arrow): {speed:.3g} m/s {heading_words(ux, uy)}"
                  + ("" if dr.current.uniform else f" at z = {z_ref:.4g} m"))
    ax.set_xlim(*pv.x_lim)
    ax.set_ylim(*pv.y_lim)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.grid(True, alpha=0.25, lw=0.6)
    title += f"\nnodes up to {dr.plane.deviation:.3g} m off the straight line"
    ax.set_title(wrap(title, width_in), fontsize=9.5)


def _draw_3d(ax: Any, dr: _Drawing, k: float) -> None:
    r = dr.r
    pts = dr.item_points()
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    if dr.surface is not None and dr.surface - hi[2] <= 0.5 * max(np.ptp(pts[:, 2]), 1e-6):
        hi[2] = max(hi[2], dr.surface)
    span = hi - lo
    big = max(span[:2].max(), span[2], 1e-6)
    for i in range(2):
        if span[i] < 0.2 * big:
            mid = 0.5 * (lo[i] + hi[i])
            lo[i], hi[i] = mid - 0.1 * big, mid + 0.1 * big
    xx, yy = np.meshgrid([lo[0], hi[0]], [lo[1], hi[1]])
    zb = dr.seabed_z(np.column_stack([xx.ravel(), yy.ravel()])).reshape(xx.shape)
    if zb.max() >= lo[2] - 0.5 * max(span[2], 1e-6):
        ax.plot_surface(xx, yy, zb, color=SEABED_FILL, alpha=0.6, edgecolor=SEABED_COLOR,
                        lw=0.6, shade=False, zorder=0)
        lo[2] = min(lo[2], zb.min())
    for (_, _, color, _), idx in zip(dr.segs, dr.slices, strict=True):
        ax.plot(r[idx, 0], r[idx, 1], r[idx, 2], "-", color=color, lw=2.0, zorder=4)
    for m in dr.markers:
        st = dict(m.style)
        ax.plot([m.position[0]], [m.position[1]], [m.position[2]], ls="none", zorder=6,
                **{**st, "ms": st.get("ms", 8) * 0.8})
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ext = np.maximum(hi - lo, 1e-9)
    ax.set_box_aspect((ext[0], ext[1], ext[2] * k), zoom=0.95)
    ax.view_init(elev=25, azim=-60)  # matplotlib's default view: x and y both to the right
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(4))
    ax.tick_params(labelsize=7, pad=0)
    ax.set_xlabel("x (m)", fontsize=8, labelpad=2)
    ax.set_ylabel("y (m)", fontsize=8, labelpad=2)
    ax.set_zlabel("z (m)", fontsize=8, labelpad=2)
    ax.set_title("3D view" + (f" (vertical exaggeration {k:g}x)" if k != 1 else
                              " (true scale)"), fontsize=9.5)


def _draw_profile(ax: Axes, dr: _Drawing, z_lim: tuple[float, float]) -> None:
    cur = dr.current
    assert cur is not None
    z_lo = max(z_lim[0], 0.0 if dr.seabed is None else z_lim[0])
    z_hi = min(z_lim[1], dr.surface) if dr.surface is not None else z_lim[1]
    z = np.linspace(z_lo, z_hi, 200)
    ux, uy = profile_components_np(z, cur.z, cur.ux, cur.uy)
    if dr.plane.planar:
        e, n = dr.plane.e, dr.plane.normal
        comps = [(ux * e[0] + uy * e[1], "in the plane"), (ux * n[0] + uy * n[1], "across")]
    else:
        comps = [(ux, "u_x"), (uy, "u_y")]
    comps.append((np.hypot(ux, uy), "speed"))
    styles = [("-", "#1f77b4"), ("-", "#ff7f0e"), ("--", "0.3")]
    for (vals, lab), (ls, color) in zip(comps, styles, strict=True):
        (h,) = ax.plot(vals, z, ls, color=color, lw=1.6, label=f"current {lab}")
        dr.add(h, 4)
    knots = (cur.z >= z_lo) & (cur.z <= z_hi)
    (h,) = ax.plot(np.hypot(cur.ux, cur.uy)[knots], cur.z[knots], "o", color="0.3", ms=4,
                   label="current profile knots")
    dr.add(h, 4)
    ax.axvline(0.0, color="k", lw=0.6)
    ax.set_ylim(*z_lim)
    ax.set_xlabel("current velocity (m/s)")
    ax.set_ylabel("z (m)")
    ax.grid(True, alpha=0.25, lw=0.6)
    ax.set_title("Current profile\n(linear between knots)", fontsize=9.5)


def statics_figure(sol: StaticsSolution, title: str = "", scene: Scene | None = None
                   ) -> Figure:
    """Build (without saving) the figure of :func:`plot_statics`.

    The figure's axes carry labels that tests and callers may inspect:
    ``"elevation"``, ``"tension"``, and for a 3D line also ``"3d"`` and ``"plan"``, and
    ``"current profile"`` when the current varies with depth.

    Parameters
    ----------
    sol : StaticsSolution
        The solution to draw; one with a non-finite iterate gives a figure with only its
        status and message (an axes labelled ``"message"``).
    title : str
        Figure title; empty (default): the scene's ``[meta] title``, if any.
    scene : Scene, optional
        The scene that was solved: with it the seabed, the free surface, the current, the
        segments and the bodies' loads are drawn too. None (default): the line alone.
    """
    head = title or (scene.meta.get("title", "") if scene is not None else "")
    if not (np.isfinite(sol.position).all() and np.isfinite(sol.tension_vector).all()):
        # a failed solve may leave a non-finite iterate: say so rather than draw it
        fig = new_figure(8.0, 3.0)
        ax = fig.add_subplot(label="message")
        ax.axis("off")
        ax.text(0.5, 0.5, wrap(f"{head}\nNo profile to draw: the iterate is not finite.\n"
                               f"status {sol.status}: {sol.message}", 7.5, 11),
                ha="center", va="center", color="#b00000", fontsize=11)
        return fig
    dr = _Drawing(sol, scene)
    varying = dr.current is not None and not dr.current.uniform
    view = _elevation_view(dr)
    ratio = view.box_ratio
    w_prof = 2.3 if varying else 0.0
    if dr.plane.planar:
        # one row; the elevation's cell is shaped like its data window
        h_row = float(np.clip(7.0 * ratio, 2.6, 6.2))
        w_el = float(np.clip(h_row / ratio, 2.8, 8.2))
        w_t = 4.6
        fig = new_figure(w_el + w_t + w_prof + 0.9, h_row + 2.6)
        widths = ([w_prof] if varying else []) + [w_el, w_t]
        gs = fig.add_gridspec(1, len(widths), width_ratios=widths)
        col = 1 if varying else 0
        ax_el = fig.add_subplot(gs[0, col], label="elevation")
        ax_t = fig.add_subplot(gs[0, col + 1], label="tension")
        if varying:
            _draw_profile(fig.add_subplot(gs[0, 0], label="current profile"), dr, view.z_lim)
    else:
        # 3D view and plan above, elevation and tension below (each row shaped by its
        # panels), the current profile at the right when the current varies with depth
        pv = _plan_view(dr)
        h_top = 4.4
        w_plan = float(np.clip(h_top / pv.box_ratio, 2.6, 6.0))
        w_3d = 4.8
        h_bot = float(np.clip(6.0 * ratio, 2.6, 4.6))
        w_el = float(np.clip(h_bot / ratio, 2.6, 7.5))
        w_t = 5.0
        width = max(w_3d + w_plan, w_el + w_t) + w_prof + 0.9
        fig = new_figure(width, h_top + h_bot + 3.4)
        outer = fig.add_gridspec(2, 2 if varying else 1, height_ratios=[h_top, h_bot],
                                 width_ratios=[width - w_prof, w_prof] if varying else [1])
        # the plan's cell is shaped like the plan; the 3D view takes the rest of the row
        top = outer[0, 0].subgridspec(1, 2, width_ratios=[width - w_prof - 0.9 - w_plan,
                                                          w_plan])
        bot = outer[1, 0].subgridspec(1, 2, width_ratios=[w_el, w_t])
        ax_3d = fig.add_subplot(top[0, 0], projection="3d", label="3d")
        ax_plan = fig.add_subplot(top[0, 1], label="plan")
        ax_el = fig.add_subplot(bot[0, 0], label="elevation")
        ax_t = fig.add_subplot(bot[0, 1], label="tension")
        _draw_plan(ax_plan, dr, pv, w_plan)
        _draw_3d(ax_3d, dr, view.exaggeration)
        if varying:
            _draw_profile(fig.add_subplot(outer[:, 1], label="current profile"), dr,
                          view.z_lim)
    _draw_elevation(ax_el, dr, view, w_el)
    _draw_tension(ax_t, dr, w_t)
    info = f"L = {sol.length:.2f} m, max tension {sol.max_tension / 1e3:.4g} kN"
    if sol.grounded_length > 0:
        info += f", grounded {sol.grounded_length:.1f} m"
    if sol.status == "solved":
        info += ", solved"
        color = "k"
    else:
        info += f", not a success: status {sol.status} ({sol.message})"
        color = "#b00000"
    fig.suptitle(wrap((head + "\n" if head else "") + info, fig.get_figwidth(), 11),
                 fontsize=11, color=color)
    legend_below(fig, dr.legend())
    return fig


def plot_statics(sol: StaticsSolution, path: str | Path, title: str = "",
                 scene: Scene | None = None) -> Figure:
    """Save the profile and the tension along the cable to ``path`` (PNG, PDF, SVG, ...).

    A planar line gets a side elevation in its plane, a 3D line a 3D view, a plan and an
    elevation; both get the tension along the cable (magnitude and components). With
    ``scene`` the seabed, the free surface, the current (an arrow, and a profile panel when
    it varies with depth), the segments and the bodies' loads are drawn too.

    Parameters
    ----------
    sol : StaticsSolution
        The solution to draw (a failed one too: its status is written in red).
    path : str or Path
        Output file; the format follows the suffix.
    title : str
        Figure title (default: the scene's ``[meta] title``).
    scene : Scene, optional
        The scene that was solved.

    Returns
    -------
    matplotlib.figure.Figure
        The saved figure (see :func:`statics_figure` for its axes' labels).
    """
    fig = statics_figure(sol, title, scene)
    save(fig, path)
    return fig


# --------------------------------------------------------------------------------------
# Sweeps and footprints
# --------------------------------------------------------------------------------------
