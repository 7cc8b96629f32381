"""Figures for statics solutions (matplotlib, Agg backend; nothing is shown on screen)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from cable_ocp.scene import Scene  # noqa: E402
from cable_ocp.statics.footprint import FootprintResult  # noqa: E402
from cable_ocp.statics.solution import StaticsSolution  # noqa: E402


def _save(fig: plt.Figure, path: str | Path) -> Path:
    """Lay out, write and close a figure."""
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def plot_statics(sol: StaticsSolution, path: str | Path, title: str = "",
                 scene: Scene | None = None) -> Path:
    """Save a 3D profile and the tension along the cable to ``path`` (PNG, PDF, ...)."""
    fig = plt.figure(figsize=(11, 4.8))
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    r = sol.position
    ax.plot(r[:, 0], r[:, 1], r[:, 2], "-", lw=1.5)
    ax.scatter(*r[0], color="k", marker="s", label="end_a")
    ax.scatter(*r[-1], color="r", marker="^", label="end_b")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    span = np.ptp(r, axis=0).max() / 2 or 1.0
    mid = r.min(axis=0) + np.ptp(r, axis=0) / 2
    ax.set_xlim(mid[0] - span, mid[0] + span)
    ax.set_ylim(mid[1] - span, mid[1] + span)
    ax.set_zlim(min(0.0, r[:, 2].min()), max(r[:, 2].max(), mid[2] + span))
    ax.legend(loc="upper left")
    ax.set_title("profile")
    ax2 = fig.add_subplot(1, 2, 2)
    ax2.plot(sol.s, sol.tension / 1e3, "-")
    ax2.set_xlabel("unstretched arc length s [m]")
    ax2.set_ylabel("tension |T| [kN]")
    ax2.grid(True, alpha=0.3)
    ax2.set_title(f"L = {sol.length:.2f} m, max |T| = {sol.max_tension / 1e3:.3f} kN")
    if title:
        fig.suptitle(title)
    return _save(fig, path)


def plot_sweep(values: Sequence[float], forces: np.ndarray, path: str | Path, xlabel: str,
               title: str = "", labels: Sequence[str] = ("Tx", "Ty", "Tz"),
               overlays: dict[str, np.ndarray] | None = None) -> Path:
    """Plot force components (N, shape (n, 3)) against a swept parameter, in kN."""
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for k, lab in enumerate(labels):
        ax.plot(values, forces[:, k] / 1e3, "o-", ms=3, label=lab)
    for name, arr in (overlays or {}).items():
        for k, lab in enumerate(labels):
            ax.plot(values, arr[:, k] / 1e3, "--", lw=1, color=f"C{k}", label=f"{lab} {name}")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("force at end_a [kN]")
    ax.grid(True, alpha=0.3)
    ax.legend()
    if title:
        ax.set_title(title)
    return _save(fig, path)


def plot_footprint(res: FootprintResult, path: str, title: str = "") -> None:
    """Draw the footprint polygon (unit positions) around the ship."""
    fig, ax = plt.subplots(figsize=(6, 6))
    ok = np.isfinite(res.reach)
    pts = res.points[ok]
    if len(pts):
        closed = np.vstack([pts, pts[:1]])
        ax.plot(closed[:, 0], closed[:, 1], "-o", ms=3, label="footprint (unit on seabed)")
    if (~ok).any():
        ax.plot([], [], "x", color="r", label=f"{int((~ok).sum())} unreachable directions")
    ax.plot(*res.ship, "r^", ms=10, label="ship")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    ax.set_title(title or "footprint")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
