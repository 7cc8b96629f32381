"""Figures for heave results: spectra (Fig. 6.21), time series (Figs. 6.22-6.24), trade-off
curves (Figs. 6.18-6.19). Returns/saves matplotlib figures; no computation beyond plotting."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from cable_ocp.heave.sea import filter_spectrum  # noqa: E402
from cable_ocp.heave.simulate import Comparison  # noqa: E402


def plot_comparison(res: Comparison, path: str | Path, tradeoff: dict | None = None) -> None:
    """Save a 2x3 figure: spectrum and fit (Fig. 6.21), boom tip and unit heave, winch output
    and winch speed (Figs. 6.22-6.24), and, if ``tradeoff`` (from :func:`tradeoff_data`), J_d
    and J_v against the winch-speed energy J_w (Figs. 6.18 and 6.19)."""
    fig, ax = plt.subplots(2, 3, figsize=(16, 8))
    spec = res.models.spectrum
    w = np.linspace(0.02, 5 * spec.omega_m, 600)
    ax[0, 0].plot(w, spec(w), label=f"{spec.kind} (Hs = {spec.hs:g} m)")
    ax[0, 0].plot(w, filter_spectrum(res.models.filter_fit.filter, w),
                  label=f"shaping filter (L2 err {res.models.filter_fit.spectral_error:.2f})")
    ax[0, 0].set(xlabel="omega (rad/s)", ylabel="S (m^2 s/rad)", title="Sea spectrum (6.20)-(6.21)")
    ax[0, 0].legend()
    for name, tr in res.traces.items():
        if name == "passive":
            ax[0, 1].plot(tr.t, tr.x0, color="0.6", lw=0.8, label="boom tip x0")
        ax[0, 1].plot(tr.t, tr.x, lw=0.8, label=f"unit x, {name}")
        if name != "passive":
            ax[1, 0].plot(tr.t, tr.u, lw=0.8, label=f"winch u, {name}")
            ax[0, 2].plot(tr.t, tr.u_dot, lw=0.8, label=f"winch u', {name}")
    ax[0, 1].set(xlabel="t (s)", ylabel="heave (m)", title="Time series")
    ax[0, 1].legend(fontsize=7)
    ax[1, 0].set(xlabel="t (s)", ylabel="u (m)", title="Winch output")
    ax[1, 0].legend(fontsize=7)
    ax[0, 2].set(xlabel="t (s)", ylabel="u' (m/s)", title="Winch speed")
    ax[0, 2].legend(fontsize=7)
    if tradeoff:
        for label, arr in tradeoff.items():
            if arr.size:
                ax[1, 1].loglog(arr[:, 0], arr[:, 1], "o-", label=label)
                ax[1, 2].loglog(arr[:, 0], arr[:, 2], "o-", label=label)
        ax[1, 1].set(xlabel="J_w = int u'^2 dt (m^2/s)", ylabel="J_d (m^2 s) (6.16)",
                     title="Trade-off (Fig. 6.18)")
        ax[1, 2].set(xlabel="J_w = int u'^2 dt (m^2/s)", ylabel="J_v (m^2/s) (6.17)",
                     title="Trade-off (Fig. 6.19)")
        ax[1, 1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
