"""Shared style of the figures: one way to write units, legends outside the data, saving.

Every figure is a :class:`matplotlib.figure.Figure` built without pyplot (no global state,
nothing shown on screen, nothing to close), laid out by matplotlib's constrained layout.
Axis labels read ``name (unit)``, e.g. ``x (m)``; legends sit outside the axes (below the
panels), never on a curve.
"""

from __future__ import annotations

import textwrap
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter

from cable_ocp.numerics.atomic import replace_atomically

#: resolution of saved raster figures, dots per inch
DPI = 110


def new_figure(width: float, height: float) -> Figure:
    """A figure of ``width`` x ``height`` inches with constrained layout.

    Parameters
    ----------
    width, height : float
        Size of the figure, inches (at :data:`DPI` dots per inch).
    """
    fig = Figure(figsize=(width, height), dpi=DPI, layout="constrained")
    FigureCanvasAgg(fig)  # a renderer to measure text with (any format can still be saved)
    fig.get_layout_engine().set(h_pad=0.06, w_pad=0.06, hspace=0.04, wspace=0.04)
    return fig


def save(fig: Figure, path: str | Path, dpi: int = DPI) -> Path:
    """Write ``fig`` to ``path``; the format follows the suffix (PNG, PDF, SVG, ...).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure to write.
    path : str or Path
        The file, overwritten if it exists; its suffix picks the format.
    dpi : int
        Resolution of raster formats, dots per inch (default :data:`DPI`).
    """
    path = Path(path)
    # whole or not at all: a full disk keeps the earlier figure
    replace_atomically(path, lambda tmp: fig.savefig(tmp, dpi=dpi))
    return path


def legend_below(fig: Figure, handles: Sequence[Artist], labels: Sequence[str] | None = None,
                 ncols: int | None = None, fontsize: float = 8.5) -> Any:
    """One figure legend below all panels (outside every axes), duplicates removed.

    The number of columns is reduced until the legend fits the figure's width.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure; the legend goes below all its panels.
    handles : sequence of matplotlib.artist.Artist
        The artists to list (lines, patches, ...).
    labels : sequence of str, optional
        One label per handle; None (default): each handle's own label. Empty labels,
        labels starting with ``_`` and repeated labels are left out.
    ncols : int, optional
        Largest number of columns (default 5, never more than the entries).
    fontsize : float
        Font size of the entries, points (default 8.5).
    """
    if labels is None:
        labels = [h.get_label() for h in handles]
    seen: dict[str, Artist] = {}
    for h, lab in zip(handles, labels, strict=True):
        if lab and not lab.startswith("_") and lab not in seen:
            seen[lab] = h
    if not seen:
        return None
    n = len(seen)
    ncols = min(n, ncols or 5)
    width = fig.get_figwidth() * fig.dpi
    renderer = fig.canvas.get_renderer()
    while True:
        leg = fig.legend(list(seen.values()), list(seen), loc="outside lower center",
                         ncols=ncols, fontsize=fontsize, frameon=False)
        if ncols == 1 or leg.get_window_extent(renderer).width <= 0.97 * width:
            return leg
        leg.remove()
        ncols -= 1


def wrap(text: str, width_in: float, fontsize: float = 9.5) -> str:
    """Wrap each line of a title to fit ``width_in`` inches at ``fontsize`` points.

    Parameters
    ----------
    text : str
        The title; its own line breaks are kept, each line wrapped on its own.
    width_in : float
        Width available, inches (at least 20 characters are allowed per line).
    fontsize : float
        Font size of the title, points (default 9.5).
    """
    chars = max(20, int(width_in * 125.0 / fontsize))
    return "\n".join(textwrap.fill(line, chars) for line in text.split("\n"))


def force_scale(max_abs: float) -> tuple[float, str]:
    """(divisor, unit) to show forces up to ``max_abs`` N in N, kN or MN."""
    if max_abs >= 1e7:
        return 1e6, "MN"
    if max_abs >= 1e3:
        return 1e3, "kN"
    return 1.0, "N"


def nice_factor(needed: float, choices: Iterable[float] = (2, 3, 5, 10, 20, 50, 100, 200, 500,
                                                          1000)) -> float:
    """The smallest of ``choices`` that is at least ``needed`` (1 when ``needed`` <= 1).

    Parameters
    ----------
    needed : float
        The least factor wanted (-), e.g. the magnification that makes a small deflection
        visible.
    choices : iterable of float
        The round factors (-) to pick from, in increasing order; above the last, the
        largest is returned.
    """
    if needed <= 1.0:
        return 1.0
    for c in choices:
        if c >= needed:
            return float(c)
    return float(max(choices))


def shade(ax: Axes, t0: float, t1: float, label: str = "warm-up (not in the metrics)") -> Artist:
    """Grey band over ``t0 <= t <= t1`` (e.g. a simulation's warm-up).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes whose x axis is time.
    t0, t1 : float
        Start and end of the band, in the x axis' unit (s for a time axis).
    label : str
        The band's legend label (default: a warm-up not counted in the metrics).
    """
    return ax.axvspan(t0, t1, color="0.88", zorder=0, lw=0, label=label, gid="warmup")


def plain_log_ticks(ax: Axes, which: str = "x") -> None:
    """Label a log axis with plain numbers (40, 60, 0.002) rather than 4x10^1, including the
    minor ticks when the axis spans less than a decade.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes with a log axis; call it after the limits are set (they decide the minor
        ticks).
    which : str
        ``"x"`` (default) or ``"y"``: the axis to label (anything but ``"x"`` means y).
    """
    fmt = FuncFormatter(lambda v, _pos: f"{v:g}")
    axis = ax.xaxis if which == "x" else ax.yaxis
    lo, hi = ax.get_xlim() if which == "x" else ax.get_ylim()
    axis.set_major_formatter(fmt)
    if hi / max(lo, 1e-300) < 10.0:
        axis.set_minor_formatter(fmt)

