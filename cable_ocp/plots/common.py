"""Shared style of the figures: one way to write units, legends outside the data, saving.

Every figure is a :class:`matplotlib.figure.Figure` built without pyplot (no global state,
nothing shown on screen, nothing to close), laid out by matplotlib's constrained layout.
Axis labels read ``name (unit)``, e.g. ``x (m)``; legends sit outside the axes (below the
panels), never on a curve. Time series go through :func:`series`, which draws a line while
the samples are few for the axes' width and, beyond that, the signal's envelope (min and
max per time window, filled, with the window means as a thin line), which reads where a
line would be a solid block of oscillation. Every title is fitted to its figure
(:func:`fit_titles`, called by :func:`save`): wrapped, then shrunk, until it lies inside.
"""

from __future__ import annotations

import textwrap
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter

from cable_ocp.numerics.atomic import replace_atomically

#: resolution of saved raster figures, dots per inch
DPI = 110
#: a time series with more samples than this per pixel of its axes' width is drawn as an
#: envelope (min..max per window) instead of a line
SAMPLES_PER_PIXEL = 2.0
#: width of one envelope window on the screen, pixels (a window spans several samples)
PIXELS_PER_WINDOW = 3.0


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
    fit_titles(fig)
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



@dataclass(frozen=True)
class Series:
    """What :func:`series` drew: a line, or an envelope and its mean line.

    Attributes
    ----------
    handle : matplotlib.artist.Artist
        The artist for the legend (the line, or the envelope's filled band).
    line : matplotlib.lines.Line2D
        The line drawn: the samples themselves, or the window means of an envelope.
    window : float or None
        Length of an envelope window in the x axis' unit (s for time); None for a line.
    """

    handle: Artist
    line: Any
    window: float | None


def envelope_windows(n: int, windows: int) -> np.ndarray:
    """Start indices of ``windows`` windows of nearly equal length over ``n`` samples.

    Window k holds samples ``starts[k]`` to ``starts[k + 1]`` inclusive (neighbours share
    their boundary sample, so the band covers the whole record); the last ends at ``n - 1``.

    Parameters
    ----------
    n : int
        Number of samples (>= 2).
    windows : int
        Number of windows wanted, at most ``n - 1``.
    """
    windows = max(1, min(int(windows), n - 1))
    return np.unique(np.linspace(0, n - 1, windows + 1).round().astype(int))


def series(ax: Axes, t: np.ndarray, y: np.ndarray, label: str = "", color: Any = None,
           lw: float = 1.0, ls: str = "-", max_samples: int | None = None) -> Series:
    """Draw a time series: a line while there are at most :data:`SAMPLES_PER_PIXEL` samples
    per pixel of the axes' width, otherwise its envelope (gid ``"envelope"``): the min and
    max of each window of about :data:`PIXELS_PER_WINDOW` pixels, filled between, with the
    window means as a thin line (gid ``"envelope-mean"``). Non-finite samples are left out
    of the windows' statistics.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes whose x axis is ``t``.
    t : numpy.ndarray
        Sample times (or any increasing abscissa), shape (n,).
    y : numpy.ndarray
        Values, shape (n,), in the unit of the y axis.
    label : str
        Legend label; an envelope's label adds the window length.
    color : color, optional
        Colour of the line and the band (default: the axes' next colour).
    lw : float
        Line width of a line, points (the means of an envelope get ``0.6 lw``).
    ls : str
        Line style of the line or the means (default solid).
    max_samples : int, optional
        Largest number of samples drawn as a line; None (default): from the axes' width
        on the figure, :data:`SAMPLES_PER_PIXEL` per pixel.
    """
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    fig = ax.get_figure()
    width_px = ax.get_position().width * fig.get_figwidth() * fig.dpi
    limit = max_samples if max_samples is not None else int(SAMPLES_PER_PIXEL * width_px)
    if color is None:
        color = ax._get_lines.get_next_color()  # noqa: SLF001 (matplotlib's colour cycle)
    if len(t) <= max(limit, 2):
        (line,) = ax.plot(t, y, color=color, lw=lw, ls=ls, label=label, gid="series")
        return Series(line, line, None)
    starts = envelope_windows(len(t), max(1, int(width_px / PIXELS_PER_WINDOW)))
    # window k: samples starts[k] .. starts[k + 1] - 1 (reduceat over y[:-1]), and its end
    # sample starts[k + 1], shared with the next window
    lo = np.fmin.reduceat(y[:-1], starts[:-1])  # fmin/fmax skip NaN (unless all are NaN)
    hi = np.fmax.reduceat(y[:-1], starts[:-1])
    lo = np.fmin(lo, y[starts[1:]])
    hi = np.fmax(hi, y[starts[1:]])
    ok = np.isfinite(y)
    yz = np.where(ok, y, 0.0)
    total = np.add.reduceat(yz[:-1], starts[:-1]) + yz[starts[1:]]
    count = np.add.reduceat(ok[:-1].astype(float), starts[:-1]) + ok[starts[1:]]
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = np.where(count > 0, total / count, np.nan)
    edges = np.column_stack([t[starts[:-1]], t[starts[1:]]]).ravel()
    window = float((t[-1] - t[0]) / (len(starts) - 1))
    band = ax.fill_between(edges, np.repeat(lo, 2), np.repeat(hi, 2), color=color,
                           alpha=0.35, lw=0, gid="envelope",
                           label=f"{label} (min..max per {window:.2g} s, line: mean)"
                           if label else "")
    (line,) = ax.plot(0.5 * (t[starts[:-1]] + t[starts[1:]]), mean, color=color,
                      lw=0.6 * lw, ls=ls, gid="envelope-mean", label="_mean")
    return Series(band, line, window)


def _titles(fig: Figure) -> list[tuple[Any, float]]:
    """Every visible, non-empty title of ``fig`` with the width it may take, pixels."""
    width = fig.get_figwidth() * fig.dpi
    out: list[tuple[Any, float]] = []
    sup = getattr(fig, "_suptitle", None)
    if sup is not None and sup.get_text():
        out.append((sup, width))
    for ax in fig.axes:
        for text in (ax.title, getattr(ax, "_left_title", None),
                     getattr(ax, "_right_title", None)):
            if text is not None and text.get_visible() and text.get_text():
                out.append((text, width))
    return out


def fit_titles(fig: Figure, margin: float = 4.0) -> None:
    """Wrap, then shrink, every title (the figure's and the axes') that would reach past an
    edge of the figure, until each lies inside it with ``margin`` pixels to spare.

    The figure is laid out once first (titles are placed by the layout); a title that
    already fits is left as it is.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure, with its titles set.
    margin : float
        Room kept between a title and the figure's left and right edges, pixels.
    """
    width = fig.get_figwidth() * fig.dpi
    for _ in range(4):
        fig.draw_without_rendering()
        renderer = fig.canvas.get_renderer()
        wide = [(txt, room) for txt, room in _titles(fig)
                if (e := txt.get_window_extent(renderer)).x0 < margin
                or e.x1 > width - margin]
        if not wide:
            return
        for txt, room in wide:
            e = txt.get_window_extent(renderer)
            lines = txt.get_text().split("\n")
            longest = max(len(line) for line in lines)
            chars = int(longest * (room - 2.0 * margin) / max(e.width, 1.0) * 0.95)
            if chars >= 20 and chars < longest:
                txt.set_text("\n".join(textwrap.fill(line, chars) for line in lines))
            else:
                txt.set_fontsize(txt.get_fontsize() * 0.9)
