"""Frequency-response curves as Huang (1992) plots them (004 Figs 3.3-3.7, 4.2-4.6): per
output, the amplitude ratio (the response amplitude operator, amplitude / A) against the
excitation frequency; the linear transfer function of the modes as a line, the time runs
as points (filled: the Fourier amplitude at the excitation frequency; open: the half range
(max - min) / 2; crosses: runs that were not periodic or went slack), the natural
frequencies as dashed vertical lines.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from cable_ocp.plots.common import legend_below, new_figure, save

__all__ = ["plot_response", "response_figure"]

_LABEL = {"top_tension": "top tension", "unit_tension": "tension at the unit",
          "unit_x": "unit x", "unit_y": "unit y", "unit_z": "unit z"}


def _label(name: str) -> str:
    if name in _LABEL:
        return _LABEL[name]
    axis, node = name.split(":")
    return f"node {node} {axis[-1]}"


def response_figure(res: Any, title: str = "") -> Figure:
    """The figure of :func:`plot_response`, not saved.

    Parameters
    ----------
    res : ResponseResult
        The sweep (:func:`cable_ocp.batch.response.frequency_response`).
    title : str
        The figure's title.
    """
    n = len(res.outputs)
    fig = new_figure(6.4, 2.5 * n + 0.9)
    axes = fig.subplots(n, 1, sharex=True, squeeze=False)[:, 0]
    handles: list[Any] = []
    colors = [f"C{i}" for i in range(max(1, res.amplitudes.size))]
    curve = res.linear_curve
    nat = np.asarray(res.linear.natural_frequencies, dtype=float)
    lo, hi = float(np.min(res.frequencies)), float(np.max(res.frequencies))
    for k, (ax, name, unit) in enumerate(zip(axes, res.outputs, res.units, strict=True)):
        ratio_unit = "N/m" if unit == "N" else "m/m"
        if curve.status == "solved":
            rao = curve.rao[:, k]
            top = np.nanmax(res.rao[:, :, k]) if np.isfinite(res.rao[:, :, k]).any() else 0.0
            cap = 3.0 * max(float(top), float(np.nanmedian(rao)) if rao.size else 0.0)
            shown = np.where(rao <= cap, rao, np.nan) if cap > 0 else rao
            h, = ax.plot(curve.frequencies, shown, "-", color="0.25", lw=1.3,
                         label="linear transfer function of the modes")
            handles.append(h)
        for a, amp in enumerate(res.amplitudes):
            ok = res.run_status[a] == "solved"
            c = colors[a % len(colors)]
            h1, = ax.plot(res.frequencies[ok], res.rao[a, ok, k], "o", color=c, ms=5,
                          label=f"time runs, A = {amp:g} m: Fourier amplitude")
            h2, = ax.plot(res.frequencies, res.half_range[a, :, k] / amp, "o", mfc="none",
                          color=c, ms=8, lw=0, label=f"A = {amp:g} m: (max - min) / 2")
            bad = ~ok
            if bad.any():
                h3, = ax.plot(res.frequencies[bad], res.rao[a, bad, k], "x", color="C3",
                              ms=7, label="not periodic, slack or failed")
                handles.append(h3)
            handles += [h1, h2]
        for w in nat[(nat >= lo) & (nat <= hi)]:
            hn = ax.axvline(w, ls="--", color="C7", lw=1.0, label="natural frequencies")
            handles.append(hn)
        ax.set_ylabel(f"{_label(name)} / A ({ratio_unit})")
        ax.set_ylim(bottom=0.0)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("excitation frequency (rad/s)")
    axes[-1].set_xlim(lo - 0.02 * (hi - lo), hi + 0.02 * (hi - lo))
    if title:
        fig.suptitle(title)
    legend_below(fig, handles)
    return fig


def plot_response(res: Any, path: str | Path, title: str = "") -> Figure:
    """Save the frequency-response figure (module docstring) to ``path``.

    Parameters
    ----------
    res : ResponseResult
        The sweep.
    path : str or Path
        The file; its suffix picks the format.
    title : str
        The figure's title.
    """
    fig = response_figure(res, title)
    save(fig, path)
    return fig
