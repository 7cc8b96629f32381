"""Figures of a load-case batch: outputs over one swept key (lines for a grid, points for
random samples) or over two swept keys (a heat map, or coloured points for random
samples), and the range graph of a statics batch (the envelope of the tension along the
line over the cases)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from cable_ocp.plots.common import force_scale, legend_below, new_figure, save, wrap
from cable_ocp.scene.units import key_label


def default_columns(res: Any) -> list[str]:
    """The outputs a batch's figure draws when none is asked for: statics the largest
    tension, footprint the largest reach, dynamics the largest top tension, heave the
    controlled heave RMS of every controller but the passive one (the passive run alone
    when it is the only one).

    Parameters
    ----------
    res : BatchResult
        The batch (its ``kind`` and ``outputs``).
    """
    if res.kind == "heave":
        rms = [c for c in res.outputs if c.endswith("_heave_rms [m]")]
        controlled = [c for c in rms if not c.startswith("passive_")]
        return controlled or rms or list(res.outputs[:1])
    main = MAIN_OUTPUT.get(res.kind)
    return [main] if main in res.outputs else list(res.outputs[:1])


#: the main output of each kind (the default of ``--plot-output``)
MAIN_OUTPUT = {"statics": "max_tension [N]", "footprint": "max_reach [m]",
               "dynamics": "max_top_tension [N]"}


def batch_figure(res: Any, column: str | Sequence[str] | None = None, title: str = ""
                 ) -> Figure:
    """The figure of :func:`plot_batch` built and not saved (``BatchResult.plot``).

    Parameters
    ----------
    res : BatchResult
        The batch.
    column : str, sequence of str or None
        The output(s); None: :func:`default_columns`.
    title : str
        Start of the title.
    """
    return plot_batch(res, column, None, title)


def plot_batch(res: Any, column: str | Sequence[str] | None, path: str | Path | None = None,
               title: str = "") -> Figure:
    """Plot output columns of a :class:`cable_ocp.batch.BatchResult` against its swept keys.

    One swept key: each output against it (one series per output), the cases that are
    not a success marked by their status; grid values joined by lines, random samples
    (:attr:`BatchResult.random_inputs`) drawn as points. Two: a heat map over the grid per
    output (cases that are not a success grey), or, when a key is drawn at random, the
    cases as points coloured by the output. More: the first two keys, the others' values
    ignored (the title says so). Axes carry the keys' units
    (:func:`cable_ocp.scene.units.key_label`).

    Parameters
    ----------
    res : BatchResult
        The batch's rows and swept input keys; only keys that take more than one value
        count as swept.
    column : str, sequence of str or None
        The output(s) to plot, column names with their unit, e.g. ``"max_tension [N]"``;
        None: :func:`default_columns` (a heave batch: the controllers, not the passive run).
    path : str or Path, optional
        Where to save the figure (format from the suffix); None (default): not saved.
    title : str
        Start of the title (``"{title}: {column}"``); empty (default): the columns alone.
    """
    columns = default_columns(res) if column is None else (
        [column] if isinstance(column, str) else list(column))
    keys = res.swept()
    random = set(getattr(res, "random_inputs", ()) or ())
    ok = np.array([r["status"] == "solved" for r in res.rows])
    two = len(keys) >= 2
    panels = len(columns) if two else 1
    fig = new_figure(7.5 if panels == 1 else min(4.2 * panels, 13.0), 5.0)
    axes = np.atleast_1d(fig.subplots(1, panels, squeeze=False)[0])
    if not two:
        ax = axes[0]
        x = res.column(keys[0])
        order = np.argsort(x, kind="stable")
        style = {"linestyle": "None"} if keys[0] in random else {"linestyle": "-"}
        multi = len(columns) > 1
        for i, col in enumerate(columns):  # later series hollow: coinciding ones show
            y = res.column(col)
            m = ok[order]
            ax.plot(x[order][m], y[order][m], marker="osD^v"[i % 5], ms=4 + 2 * (i > 0),
                    mfc=None if i == 0 else "none", **style,
                    label=_series(col, res.kind) if multi else "solved")
        for st in sorted({r["status"] for r in res.rows} - {"solved"}):
            m = np.array([r["status"] == st for r in res.rows])
            for col in columns:
                ax.plot(x[m], res.column(col)[m], "x", ms=7, label=st)
        ax.set_xlabel(key_label(keys[0]))
        ax.set_ylabel(_common_label(columns))
        legend_below(fig, ax.get_lines())
    else:
        kx, ky = keys[0], keys[1]
        for ax, col in zip(axes, columns, strict=True):
            y = res.column(col)
            if kx in random or ky in random:
                pts = ax.scatter(res.column(kx)[ok], res.column(ky)[ok], c=y[ok], s=22)
                fig.colorbar(pts, ax=ax, label=_label(col))
                bad = ~ok
                if bad.any():
                    ax.plot(res.column(kx)[bad], res.column(ky)[bad], "x", color="0.4",
                            linestyle="None", label="not solved")
                    legend_below(fig, ax.get_lines())
            else:
                _heat_map(fig, ax, res, kx, ky, y, ok, col)
            ax.set_xlabel(key_label(kx))
            ax.set_ylabel(key_label(ky))
            if panels > 1:
                ax.set_title(_series(col, res.kind), fontsize=9)
    extra = f" (only the first two of {len(keys)} swept keys)" if len(keys) > 2 else ""
    heave = res.kind == "heave" and all(c.endswith("_heave_rms [m]") for c in columns)
    what = (f"controlled heave RMS ({', '.join(_series(c, res.kind) for c in columns)})"
            if heave else ", ".join(columns))
    fig.suptitle(wrap(f"{title}: {what}{extra}" if title else what + extra,
                      fig.get_figwidth() - 0.3, 10), fontsize=10)
    for ax in axes:
        ax.grid(True, alpha=0.3)
    if path is not None:
        save(fig, path)
    return fig


def _heat_map(fig: Figure, ax: Any, res: Any, kx: str, ky: str, y: np.ndarray,
              ok: np.ndarray, col: str) -> None:
    """One output over a two-key grid (cases that are not a success grey)."""
    xs = sorted({r[kx] for r in res.rows})
    ys = sorted({r[ky] for r in res.rows})
    grid = np.full((len(ys), len(xs)), np.nan)
    for r, v, good in zip(res.rows, y, ok, strict=True):
        if good:
            grid[ys.index(r[ky]), xs.index(r[kx])] = v
    mesh = ax.pcolormesh(_edges(np.asarray(xs, float)), _edges(np.asarray(ys, float)),
                         np.ma.masked_invalid(grid), shading="flat")
    fig.colorbar(mesh, ax=ax, label=_label(col))
    if (~ok).any():
        ax.set_facecolor("0.85")
        ax.text(1.0, -0.16, "grey: not solved", transform=ax.transAxes, ha="right",
                fontsize=8)


def _series(column: str, kind: str) -> str:
    """A series' legend entry: a heave controller's name, else the column."""
    if kind == "heave" and column.endswith("_heave_rms [m]"):
        return column[: -len("_heave_rms [m]")]
    return column


def _common_label(columns: Sequence[str]) -> str:
    """The y label of several outputs: their shared quantity and unit when they share one
    (``heave RMS (m)``), else the first's."""
    if len(columns) > 1 and all(c.endswith("_heave_rms [m]") for c in columns):
        return "unit heave RMS, controlled (m)"
    return _label(columns[0])


def plot_range_graph(arrays: Any, path: str | Path | None = None, title: str = "",
                     mean: bool = True, name: str = "tension",
                     cases: Sequence[int] | None = None) -> Figure:
    """The range graph of a statics batch: the envelope (min and max over all cases, and
    the mean) of the tension along the line against arc length
    (:func:`cable_ocp.batch.arrays.envelope`), as OrcaFlex draws a range graph, with every
    case's own curve in light grey beneath.

    Parameters
    ----------
    arrays : dict or xarray.Dataset
        Case index -> {name: 1-D array} (:attr:`cable_ocp.batch.BatchResult.arrays`), or a
        file's dataset (:func:`cable_ocp.batch.arrays.read_arrays`).
    path : str or Path, optional
        Where to save the figure; None (default): not saved.
    title : str
        Start of the title; empty (default): none.
    mean : bool
        Also draw the mean over the cases (default True).
    name : str
        The quantity along the line (default ``"tension"``).
    cases : sequence of int, optional
        The cases to draw; None (default): every case of a dict, the cases with status
        ``solved`` of a dataset.
    """
    from cable_ocp.batch.arrays import array_unit, case_arrays, envelope

    if hasattr(arrays, "data_vars"):
        if cases is None:
            cases = [int(c) for c, st in zip(arrays["case"].values, arrays["status"].values,
                                             strict=True) if str(st) == "solved"]
        arrays = case_arrays(arrays)
    if cases is not None:
        arrays = {c: arrays[c] for c in cases if c in arrays}
    s, lo, hi, avg = envelope(arrays, name)
    unit = array_unit(name)
    div, shown = force_scale(float(np.nanmax(np.abs(hi)))) if unit == "N" else (1.0, unit)
    fig = new_figure(7.5, 4.8)
    ax = fig.subplots()
    for c in sorted(arrays):
        a = arrays[c]
        if name in a and "arc_length" in a:
            ax.plot(a["arc_length"], np.asarray(a[name]) / div, "-", color="0.8", lw=0.7,
                    label="each case", gid="case")
    band = ax.fill_between(s, lo / div, hi / div, color="C0", alpha=0.15, lw=0,
                           label="range over cases")
    ax.plot(s, hi / div, "-", color="C3", lw=1.6, label="max over cases", gid="max")
    ax.plot(s, lo / div, "-", color="C0", lw=1.6, label="min over cases", gid="min")
    if mean:
        ax.plot(s, avg / div, "--", color="k", lw=1.1, label="mean over cases", gid="mean")
    ax.set_xlabel("arc length s from end_a, unstretched (m)")
    ax.set_ylabel(f"{name} ({shown})")
    n = sum(name in a for a in arrays.values())
    head = f"{title}: " if title else ""
    ax.set_title(wrap(f"{head}range graph of {name} over {n} cases: max "
                      f"{np.nanmax(hi) / div:.4g} {shown}", 7.2, 10), fontsize=10)
    ax.grid(True, alpha=0.3)
    legend_below(fig, [*ax.get_lines(), band])
    if path is not None:
        save(fig, path)
    return fig


def _label(column: str) -> str:
    """``name [unit]`` -> ``name (unit)``, the figures' way of writing units."""
    return column.replace(" [", " (").replace("]", ")") if column.endswith("]") else column


def _edges(v: np.ndarray) -> np.ndarray:
    """Cell edges around sorted centres (for pcolormesh)."""
    if len(v) == 1:
        return np.array([v[0] - 0.5, v[0] + 0.5])
    mid = 0.5 * (v[1:] + v[:-1])
    return np.concatenate([[2 * v[0] - mid[0]], mid, [2 * v[-1] - mid[-1]]])
