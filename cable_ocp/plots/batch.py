"""Figures of a load-case batch: one output over one swept key (lines, one per status
group) or over two swept keys (a heat map)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from cable_ocp.plots.common import legend_below, new_figure, save


def batch_figure(res: Any, column: str, title: str = "") -> Figure:
    """Build (without saving) the figure of :func:`plot_batch`: ``column`` of a
    :class:`cable_ocp.batch.BatchResult` against its swept keys.

    One swept key: the output against it, with the cases that are not a success marked by
    their status. Two: a heat map over the grid (cases that are not a success hatched
    out). More: the first two keys, the others' values ignored (say so in the title).

    Parameters
    ----------
    res : BatchResult
        The batch's rows and swept input keys; only keys that take more than one value
        count as swept.
    column : str
        The output to plot, a column name with its unit, e.g. ``"max_tension [N]"``.
    title : str
        Start of the title (``"{title}: {column}"``); empty (default): the column alone.
    """
    keys = [k for k in res.inputs if len({r.get(k) for r in res.rows}) > 1] or res.inputs
    ok = np.array([r["status"] == "solved" for r in res.rows])
    y = res.column(column)
    fig = new_figure(7.5, 5.0)
    ax = fig.subplots()
    if len(keys) == 1:
        x = res.column(keys[0])
        order = np.argsort(x)
        ax.plot(x[order][ok[order]], y[order][ok[order]], "o-", ms=4, label="solved")
        for st in sorted({r["status"] for r in res.rows} - {"solved"}):
            m = np.array([r["status"] == st for r in res.rows])
            ax.plot(x[m], y[m], "x", ms=7, label=st)
        ax.set_xlabel(keys[0])
        ax.set_ylabel(_label(column))
        legend_below(fig, ax.get_lines())
    else:
        kx, ky = keys[0], keys[1]
        xs = sorted({r[kx] for r in res.rows})
        ys = sorted({r[ky] for r in res.rows})
        grid = np.full((len(ys), len(xs)), np.nan)
        for r, v, good in zip(res.rows, y, ok, strict=True):
            if good:
                grid[ys.index(r[ky]), xs.index(r[kx])] = v
        mesh = ax.pcolormesh(_edges(np.asarray(xs, float)), _edges(np.asarray(ys, float)),
                             np.ma.masked_invalid(grid), shading="flat")
        fig.colorbar(mesh, ax=ax, label=_label(column))
        ax.set_xlabel(kx)
        ax.set_ylabel(ky)
        if (~ok).any():
            ax.set_facecolor("0.85")
            ax.text(1.0, -0.16, "grey: not solved", transform=ax.transAxes, ha="right",
                    fontsize=8)
    extra = f" (only the first two of {len(keys)} swept keys)" if len(keys) > 2 else ""
    ax.set_title(f"{title}: {column}{extra}" if title else column + extra, fontsize=10)
    ax.grid(True, alpha=0.3)
    return fig


def plot_batch(res: Any, column: str, path: str | Path, title: str = "") -> Figure:
    """Save :func:`batch_figure` (``column`` against the swept keys) to ``path``.

    Parameters
    ----------
    res : BatchResult
        The batch's rows and swept input keys.
    column : str
        The output to plot, e.g. ``"max_tension [N]"``.
    path : str or Path
        Where to save the figure (format from the suffix).
    title : str
        Start of the title; empty (default): the column alone.
    """
    fig = batch_figure(res, column, title)
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
