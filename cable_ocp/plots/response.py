"""Frequency-response curves as Huang (1992) plots them (004 Figs 3.3-3.7, 4.2-4.6): per
output, the amplitude ratio (the response amplitude operator, amplitude / A) against the
excitation frequency; the linear transfer function of the modes as a line, the time runs
as points (filled: the Fourier amplitude at the excitation frequency; open: the half range
(max - min) / 2; crosses: runs that were not periodic or went slack; triangles on the
frequency axis: runs that failed and have no amplitude), the natural
frequencies as dashed vertical lines. The ratio axis is logarithmic when the ratios span
more than two decades (an undamped resonance). With ``tension_scale`` K (N/m) a tension's
ratio is plotted divided by K, and with ``frequency_scale`` w_ref (rad/s) the frequency
axis is w / w_ref: Fig. 3.5's (T_max - T_static) / (K x0) against w / w_nc (3.3.3:
K = 380 N/m, w_nc = 1.1 Hz).
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


def response_figure(res: Any, title: str = "", tension_scale: float | None = None,
                    frequency_scale: float | None = None) -> Figure:
    """The figure of :func:`plot_response`, not saved.

    Parameters
    ----------
    res : ResponseResult
        The sweep (:func:`cable_ocp.batch.response.frequency_response`).
    title : str
        The figure's title.
    tension_scale : float, optional
        K, N/m: the tensions' ratios are plotted divided by it (dimensionless).
    frequency_scale : float, optional
        w_ref, rad/s: the frequency axis is w / w_ref.
    """
    n = len(res.outputs)
    fig = new_figure(6.4, 2.5 * n + 0.9)
    axes = fig.subplots(n, 1, sharex=True, squeeze=False)[:, 0]
    handles: list[Any] = []
    colors = [f"C{i}" for i in range(max(1, res.amplitudes.size))]
    curve = res.linear_curve
    nat = np.asarray(res.linear.natural_frequencies, dtype=float)
    fs = float(frequency_scale) if frequency_scale else 1.0
    freqs = np.asarray(res.frequencies, dtype=float) / fs
    lo, hi = float(np.min(freqs)), float(np.max(freqs))
    for k, (ax, name, unit) in enumerate(zip(axes, res.outputs, res.units, strict=True)):
        scale = float(tension_scale) if (tension_scale and unit == "N") else 1.0
        ratio_unit = ("-" if scale != 1.0 else "N/m") if unit == "N" else "m/m"
        half = res.half_range[:, :, k] / res.amplitudes[:, None] / scale
        fourier = res.rao[:, :, k] / scale
        # the axis follows the time runs and the linear values at the swept frequencies
        # (an undamped linear peak runs off the top; a Fourier amplitude far below the half
        # range, an output at 2 w, off the bottom)
        values = [half, np.where(fourier >= 1e-3 * half, fourier, np.nan),
                  res.linear.rao[:, k] / scale]
        if curve.status == "solved":
            rao = curve.rao[:, k] / scale
            h, = ax.plot(curve.frequencies / fs, rao, "-", color="0.25", lw=1.3,
                         label="linear transfer function of the modes")
            handles.append(h)
        for a, amp in enumerate(res.amplitudes):
            ok = res.run_status[a] == "solved"
            c = colors[a % len(colors)]
            h1, = ax.plot(freqs[ok], res.rao[a, ok, k] / scale, "o", color=c, ms=5,
                          label=f"time runs, A = {amp:g} m: Fourier amplitude")
            h2, = ax.plot(freqs, res.half_range[a, :, k] / amp / scale, "o", mfc="none",
                          color=c, ms=8, lw=0, label=f"A = {amp:g} m: (max - min) / 2")
            bad = ~ok
            if bad.any():
                h3, = ax.plot(freqs[bad], res.rao[a, bad, k] / scale, "x", color="C3",
                              ms=7, label="not periodic, slack or failed")
                handles.append(h3)
            lost = ~np.isfinite(res.rao[a, :, k])
            if lost.any():  # no number (a failed step): marked on the frequency axis
                h4, = ax.plot(freqs[lost], np.full(int(lost.sum()), 0.03 + 0.05 * a), "v",
                              color=c, ms=7, transform=ax.get_xaxis_transform(),
                              clip_on=False, label=f"A = {amp:g} m: run failed (no amplitude)")
                handles.append(h4)
            handles += [h1, h2]
        for w in nat[(nat >= lo * fs) & (nat <= hi * fs)]:
            hn = ax.axvline(w / fs, ls="--", color="C7", lw=1.0, label="natural frequencies")
            handles.append(hn)
        what = f"{_label(name)} / A" + (f" / {scale:g} N/m" if scale != 1.0 else "")
        ax.set_ylabel(f"{what} ({ratio_unit})")
        pos = np.concatenate([np.ravel(v) for v in values])
        pos = pos[np.isfinite(pos) & (pos > 0)]
        if pos.size and pos.max() > 100.0 * pos.min():
            ax.set_yscale("log")
            ax.set_ylim(max(pos.min(), pos.max() * 1e-6) / 2.0, pos.max() * 3.0)
        elif pos.size:
            ax.set_ylim(0.0, 1.3 * pos.max())
        else:
            ax.set_ylim(bottom=0.0)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("excitation frequency (rad/s)" if fs == 1.0 else
                        f"excitation frequency / {fs:.4g} rad/s (-)")
    axes[-1].set_xlim(lo - 0.02 * (hi - lo), hi + 0.02 * (hi - lo))
    if title:
        fig.suptitle(title)
    legend_below(fig, handles)
    return fig


def plot_response(res: Any, path: str | Path, title: str = "",
                  tension_scale: float | None = None,
                  frequency_scale: float | None = None) -> Figure:
    """Save the frequency-response figure (module docstring) to ``path``.

    Parameters
    ----------
    res : ResponseResult
        The sweep.
    path : str or Path
        The file; its suffix picks the format.
    title : str
        The figure's title.
    tension_scale : float, optional
        K, N/m: the tensions' ratios divided by it.
    frequency_scale : float, optional
        w_ref, rad/s: the frequency axis as w / w_ref.
    """
    fig = response_figure(res, title, tension_scale, frequency_scale)
    save(fig, path)
    return fig
