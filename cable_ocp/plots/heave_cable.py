"""Figure of a controlled deployment through resonance (the heave scene's ``[deployment]``).

:func:`plot_deployment` draws, against the paid-out length: the first axial natural
frequency (modal analysis and the identified ``1 / sqrt(a)`` of the schedule) beside the band
where the boom-tip heave has its power; the unit's heave per length window for the passive,
fixed-gain and scheduled compensators (standard deviation about the window's mean, log
scale); the tension extremes at the unit against the static tension and zero; and the
samples with slack.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.plots.common import legend_below, new_figure, save, wrap

STYLE = {
    "passive": {"color": "0.35", "ls": "-", "label": "passive (winch held)"},
    "lqr_fixed": {"color": "#ff7f0e", "ls": "--", "label": "LQR, fixed (designed at the start)"},
    "lqr_scheduled": {"color": "#1f77b4", "ls": "-", "label": "LQR scheduled on a(L), b(L)"},
}


def boom_tip_band(res: Any, fraction: float = 0.5, count: int = 4000
                  ) -> tuple[float, float, float]:
    """(low, peak, high) rad/s: where the boom-tip heave spectrum of the result's sea and
    vessel is above ``fraction`` of its peak.

    Parameters
    ----------
    res : Comparison
        A heave result whose ``models.plant`` has the sea and vessel blocks and the
        boom-tip output ``x0`` (e.g. a :func:`cable_ocp.heave.deployment.deploy` result).
    fraction : float
        Level of the band's edges as a fraction of the spectrum's peak (-), in (0, 1];
        default 0.5: the half-power band.
    count : int
        Number of frequencies on the evaluation grid, evenly spaced over 0.05-3.0 rad/s
        (default 4000); the band's edges and peak are grid points.
    """
    p = res.models.plant
    lo = p.blocks["vessel"].start
    A, B = p.A[lo:, lo:], p.B2[lo:, 0]
    c, _ = p.output_row("x0")
    c = c[lo:]
    w = np.linspace(0.05, 3.0, count)
    eye = np.eye(A.shape[0])
    s = np.array([abs(c @ np.linalg.solve(1j * wi * eye - A, B)) ** 2 for wi in w])
    k = s >= fraction * s.max()
    return float(w[k][0]), float(w[int(np.argmax(s))]), float(w[k][-1])


def plot_deployment(res: Any, path: str | Path, title: str = "") -> Path:
    """Write the deployment figure of a :func:`cable_ocp.heave.deployment.deploy` result.

    Parameters
    ----------
    res : CableComparison
        The deployment result; its ``json_extra["deployment"]`` holds the schedule and the
        per-length windows (lengths in m, heave in m, tensions in N, slack in samples).
    path : str or Path
        Where to save the figure (format from the suffix).
    title : str
        The figure's title; empty (default): "Controlled deployment through resonance".
    """
    dep = res.json_extra["deployment"]
    sch = dep["schedule"]
    tab = dep["per_length"]
    L = np.asarray(tab["length"], dtype=float)
    fig = new_figure(7.5, 9.0)
    axs = fig.subplots(4, 1, sharex=True, height_ratios=[1.0, 1.4, 1.4, 0.7])
    handles = []

    ax = axs[0]
    lo, pk, hi = boom_tip_band(res)
    ax.axhspan(lo, hi, color="#c6dbef", lw=0, label="boom-tip heave: half-power band")
    ax.axhline(pk, color="#6baed6", lw=1.0, label=f"boom-tip heave: peak {pk:.3g} rad/s")
    Ls = np.asarray(sch["lengths"], dtype=float)
    handles += ax.plot(Ls, sch["omega_1"], "k-", lw=1.2, label="omega_1, modal analysis")
    handles += ax.plot(Ls, 1.0 / np.sqrt(np.asarray(sch["a"])), "o", color="#d62728", ms=4,
                       label="1/sqrt(a), identified (6.2.3)")
    handles += ax.get_legend_handles_labels()[0][:2]
    ax.set_ylabel("rad/s")
    ax.set_title(wrap("First axial natural frequency against length, and the band of the "
                      "boom-tip heave", 7.0), fontsize=9.5)

    ax = axs[1]
    for name, st in STYLE.items():
        y = np.array([np.nan if v is None else v for v in tab[name]["heave_std"]])
        handles += ax.plot(L, y, color=st["color"], ls=st["ls"], lw=1.3, label=st["label"])
    ax.set_yscale("log")
    ax.set_ylabel("m")
    ax.set_title(wrap(f"Unit heave per {dep['window']:g} m of length (standard deviation "
                      "about the window's mean)", 7.0), fontsize=9.5)

    ax = axs[2]
    for name, st in STYLE.items():
        lo_t = np.array([np.nan if v is None else v for v in tab[name]["tension_unit_min"]])
        hi_t = np.array([np.nan if v is None else v for v in tab[name]["tension_unit_max"]])
        ax.plot(L, lo_t / 1e3, color=st["color"], ls=st["ls"], lw=1.1)
        ax.plot(L, hi_t / 1e3, color=st["color"], ls=st["ls"], lw=1.1)
    t0 = res.json_extra.get("design_model", {}).get("static_tension")
    if t0:
        handles.append(ax.axhline(t0 / 1e3, color="0.6", lw=0.8, ls=":",
                                  label="static tension at the unit"))
    handles.append(ax.axhline(0.0, color="#d62728", lw=1.0, ls="--",
                              label="zero tension (slack)"))
    ax.set_ylabel("kN")
    ax.set_title("Tension at the unit: lowest and highest per window", fontsize=9.5)

    ax = axs[3]
    width = float(dep["window"])
    names = list(STYLE)
    for j, name in enumerate(names):
        y = np.array([0 if v is None else v for v in tab[name]["slack_samples"]], dtype=float)
        ax.bar(L + (j - 1) * width / 3.5, y * float(dep["sample_time"]), width=width / 3.5,
               color=STYLE[name]["color"])
    ax.set_ylim(bottom=0.0)
    ax.set_ylabel("s")
    ax.set_xlabel("paid-out length L [m]")
    ax.set_title("Time with slack (an element's tension <= 0) per window", fontsize=9.5)
    ax.set_xlim(min(Ls[0], L[0] - width / 2), max(Ls[-1], L[-1] + width / 2))

    fig.suptitle(wrap(title or "Controlled deployment through resonance", 7.2),
                 fontsize=10.5)
    legend_below(fig, handles, ncols=2)
    return save(fig, path)
