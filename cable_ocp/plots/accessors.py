"""The results' ``.plot(ax=None)`` methods (MoorPy's habit, pandas' and xarray's accessor
pattern): each result type imports this module when its ``plot`` is called, never when it
is imported, so the library still works without its face (tests/test_layout.py checks
both).

With ``ax=None`` a result gets the figure of its command's ``--plot`` (the ``*_figure``
builders of this package) and the pair ``(fig, axes)``, ``axes`` an array of its panels;
with an ``ax`` it draws its main view on that Axes and returns ``(ax.figure, ax)``.
Nothing is saved and nothing is shown: in a notebook the returned figure displays itself.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

from cable_ocp.plots.batch import batch_figure, default_columns
from cable_ocp.plots.dynamics import deployment_figure, modes_figure, simulation_figure
from cable_ocp.plots.heave import comparison_figure
from cable_ocp.plots.response import response_figure
from cable_ocp.plots.statics import elevation_plane, statics_figure
from cable_ocp.plots.statics_series import footprint_figure
from cable_ocp.plots.system import draw_plan, system_figure
from cable_ocp.scene.units import key_label

__all__ = ["plot_batch_result", "plot_deployment_chart", "plot_footprint_result",
           "plot_heave_result", "plot_modes_result", "plot_response_result",
           "plot_simulation_result", "plot_statics_result", "plot_system_result"]


def _panels(fig: Figure) -> tuple[Figure, np.ndarray]:
    """``(fig, its axes as an array)``: what ``ax=None`` returns."""
    axes = np.empty(len(fig.axes), dtype=object)
    axes[:] = fig.axes
    return fig, axes


def plot_statics_result(sol: Any, ax: Any = None, title: str = "", scene: Any = None
                        ) -> tuple[Figure, Any]:
    """``StaticsSolution.plot``: the figure of ``cable-ocp solve --plot``, or the elevation
    (horizontal distance in the line's vertical plane, z) drawn on ``ax``.

    Parameters
    ----------
    sol : StaticsSolution
        The solution: node positions, m.
    ax : matplotlib Axes, optional
        Where to draw the elevation; None: a new figure (:func:`statics_figure`).
    title : str
        The title (default: the scene's).
    scene : Scene, optional
        The solved scene (seabed, surface, current, bodies) for the full figure.
    """
    if ax is None:
        return _panels(statics_figure(sol, title, scene))
    plane = elevation_plane(sol.position)
    ax.plot(plane.coord(sol.position), sol.position[:, 2], lw=1.6,
            label=f"{sol.status}, max tension {sol.max_tension:.4g} N")
    ax.set_xlabel(plane.label)
    ax.set_ylabel("z (m)")
    ax.set_aspect("equal", adjustable="datalim")
    if title:
        ax.set_title(title)
    ax.legend(fontsize=8)
    return ax.figure, ax


def plot_simulation_result(res: Any, ax: Any = None, title: str = "", scene: Any = None
                           ) -> tuple[Figure, Any]:
    """``SimulationResult.plot``: the four panels of ``cable-ocp simulate --plot``, or the
    top tension against time drawn on ``ax``.

    Parameters
    ----------
    res : SimulationResult
        The simulation: times (s), top tension (N).
    ax : matplotlib Axes, optional
        Where to draw the top tension; None: a new figure (:func:`simulation_figure`).
    title : str
        The title.
    scene : DynamicScene, optional
        Passed to :func:`simulation_figure`.
    """
    if ax is None:
        return _panels(simulation_figure(res, title, scene))
    ax.plot(res.t, res.top_tension, lw=1.2, label=f"{res.model}: top tension")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("tension at end_b (N)")
    if title:
        ax.set_title(title)
    ax.legend(fontsize=8)
    return ax.figure, ax


def plot_modes_result(res: Any, ax: Any = None, title: str = "", max_modes: int = 6
                      ) -> tuple[Figure, Any]:
    """``ModesResult.plot``: one panel per mode (``cable-ocp modes --plot``), or the static
    profile with the lowest three shapes (scaled to 12 % of the line's extent) on ``ax``.

    Parameters
    ----------
    res : ModesResult
        Frequencies (rad/s), shapes, static node positions (m).
    ax : matplotlib Axes, optional
        Where to draw; None: a new figure (:func:`modes_figure`).
    title : str
        Start of the title.
    max_modes : int
        Panels of the full figure (default 6).
    """
    if ax is None:
        return _panels(modes_figure(res, title, max_modes))
    r = res.node_positions
    plane = elevation_plane(r)
    h = plane.coord(r)
    amp = 0.12 * max(float(np.ptp(h)), float(np.ptp(r[:, 2])), 1.0)
    ax.plot(h, r[:, 2], color="0.6", lw=1.0, label="static profile")
    for k in range(min(3, len(res.frequencies))):
        sh = res.shapes[k]
        ax.plot(h + amp * (sh[:, :2] @ plane.e), r[:, 2] + amp * sh[:, 2], lw=1.3,
                label=f"mode {k + 1}: {res.frequencies[k]:.4g} rad/s")
    ax.set_xlabel(plane.label)
    ax.set_ylabel("z (m)")
    if title:
        ax.set_title(title)
    ax.legend(fontsize=8)
    return ax.figure, ax


def plot_deployment_chart(chart: Any, ax: Any = None, title: str = "") -> tuple[Figure, Any]:
    """``DeploymentChart.plot``: the chart of ``cable-ocp modes --lengths --plot``, or the
    frequencies against the length (the wave band shaded) on ``ax``.

    Parameters
    ----------
    chart : DeploymentChart
        Frequencies (rad/s) against unstretched length (m), the wave band.
    ax : matplotlib Axes, optional
        Where to draw; None: a new figure (:func:`deployment_figure`).
    title : str
        Start of the title.
    """
    if ax is None:
        return _panels(deployment_figure(chart, title))
    lo, hi = chart.wave_band
    ax.axhspan(lo, hi, color="C0", alpha=0.15, label="wave band")
    for k in range(chart.frequencies.shape[1]):
        ax.plot(chart.lengths, chart.frequencies[:, k], "-o", ms=3, label=f"mode {k + 1}")
    ax.set_xlabel("paid-out length (unstretched) (m)")
    ax.set_ylabel("natural frequency omega (rad/s)")
    if title:
        ax.set_title(title)
    ax.legend(fontsize=8)
    return ax.figure, ax


def plot_heave_result(res: Any, ax: Any = None, tradeoff: dict | None = None,
                      scene: Any = None, references: dict[str, str] | None = None
                      ) -> tuple[Figure, Any]:
    """``Comparison.plot``: the panels of ``cable-ocp heave --plot``, or the unit's heave
    against time, one line per controller, on ``ax``.

    Parameters
    ----------
    res : Comparison
        The traces (t in s, heave in m) and metrics.
    ax : matplotlib Axes, optional
        Where to draw; None: a new figure (:func:`comparison_figure`).
    tradeoff : dict, optional
        Trade-off data (two more panels of the full figure).
    scene : HeaveScene, optional
        Title, warm-up and winch limits of the full figure.
    references : dict, optional
        Thesis figure per panel of the full figure.
    """
    if ax is None:
        return _panels(comparison_figure(res, tradeoff, scene, references))
    for name, tr in res.traces.items():
        m = res.metrics.get(name)
        rms = f", rms {m.heave_rms:.3g} m" if m is not None and m.heave_rms is not None else ""
        ax.plot(tr.t, tr.x, lw=1.0, label=f"{name}{rms}")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("unit heave (m)")
    ax.legend(fontsize=8)
    return ax.figure, ax


def plot_batch_result(res: Any, ax: Any = None, column: str | None = None, title: str = ""
                      ) -> tuple[Figure, Any]:
    """``BatchResult.plot``: ``column`` against the swept keys, as ``cable-ocp batch
    --plot`` draws it (:func:`batch_figure`), on a new figure or on ``ax``.

    Parameters
    ----------
    res : BatchResult
        The rows and the swept keys.
    ax : matplotlib Axes, optional
        Where to draw: against the first swept key; None: a new figure.
    column : str, optional
        The output (default: the first output column).
    title : str
        Start of the title.
    """
    if not res.outputs:
        raise ValueError("the batch has no output column to plot")
    if ax is None:
        return _panels(batch_figure(res, column, title))
    column = column or default_columns(res)[0]
    keys = res.swept()
    x = res.column(keys[0]) if keys else np.arange(len(res.rows), dtype=float)
    ok = np.array([r["status"] == "solved" for r in res.rows], dtype=bool)
    y = res.column(column)
    ax.plot(x[ok], y[ok], "o", ms=4, label="solved")
    if (~ok).any():
        ax.plot(x[~ok], y[~ok], "x", ms=7, label="not solved")
    ax.set_xlabel(key_label(keys[0]) if keys else "case")
    ax.set_ylabel(column)
    if title:
        ax.set_title(title)
    ax.legend(fontsize=8)
    return ax.figure, ax


def plot_footprint_result(res: Any, ax: Any = None, title: str = "", scene: Any = None
                          ) -> tuple[Figure, Any]:
    """``FootprintResult.plot``: the plan and the reach of ``cable-ocp footprint --plot``,
    or the plan (the unit's positions at the largest reach around the ship) on ``ax``.

    Parameters
    ----------
    res : FootprintResult
        Unit positions (m), the ship's position (m).
    ax : matplotlib Axes, optional
        Where to draw the plan; None: a new figure (:func:`footprint_figure`).
    title : str
        The title.
    scene : Scene, optional
        The footprint scene (current arrow, limits) for the full figure.
    """
    if ax is None:
        return _panels(footprint_figure(res, title, scene))
    p = np.asarray(res.points, dtype=float)
    ring = np.vstack([p, p[:1]])
    ax.plot(ring[:, 0], ring[:, 1], "-o", ms=3, lw=1.4, label="unit at the largest reach")
    ax.plot(*np.asarray(res.ship, dtype=float), "^", color="k", ms=10, label="ship")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    if title:
        ax.set_title(title)
    ax.legend(fontsize=8)
    return ax.figure, ax


def plot_system_result(result: Any, ax: Any = None, **kwargs: Any) -> tuple[Figure, Any]:
    """``SystemResult.plot``: the plan and 3D views of :func:`system_figure`, or the plan
    view (lines coloured by tension, kN, with its colorbar) drawn on ``ax``.

    Parameters
    ----------
    result : SystemResult
        The solved system: line profiles and tensions (N), points and bodies (m, deg).
    ax : matplotlib Axes, optional
        Where to draw the plan; None: a new figure (:func:`system_figure`).
    **kwargs
        ``scene`` (SystemScene) and ``title`` (str), passed to :func:`system_figure`;
        with ``ax``, ``title`` is the axes' title.
    """
    if ax is None:
        return _panels(system_figure(result, **kwargs))
    sm = draw_plan(ax, result)
    ax.figure.colorbar(sm, ax=ax, label="line tension (kN)")
    title = kwargs.get("title")
    if title:
        ax.set_title(title)
    ax.legend(fontsize=8)
    return ax.figure, ax


def plot_response_result(res: Any, ax: Any = None, title: str = "") -> tuple[Figure, Any]:
    """``ResponseResult.plot``: the panels of :func:`response_figure`, or the first
    output's amplitude ratio against the excitation frequency (rad/s) drawn on ``ax``.

    Parameters
    ----------
    res : ResponseResult
        The sweep (amplitudes in N or m, frequencies in rad/s).
    ax : matplotlib Axes, optional
        Where to draw; None: a new figure.
    title : str
        The title.
    """
    if ax is None:
        return _panels(response_figure(res, title))
    if res.linear_curve.status == "solved":
        ax.plot(res.linear_curve.frequencies, res.linear_curve.rao[:, 0], "-", color="0.25",
                label="linear")
    for a, amp in enumerate(res.amplitudes):
        ax.plot(res.frequencies, res.rao[a, :, 0], "o", label=f"time runs, A = {amp:g} m")
    ax.set_xlabel("excitation frequency (rad/s)")
    ax.set_ylabel(f"{res.outputs[0]} / A ({res.units[0]}/m)")
    if title:
        ax.set_title(title)
    ax.legend(fontsize=8)
    return ax.figure, ax
