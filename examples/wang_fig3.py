"""Reproduce Wang, Cheong & Chucheepsakul (1993), Fig. 3: the force at De Zoysa's buggy.

Source: Wang, Cheong & Chucheepsakul (1993), "Static analysis of marine cables via
shooting-optimization technique", section "De Zoysa's Three-Dimensional Cable Problem" and
Fig. 3 (bottom tension components Tx, Ty, Tz against the angle psi0 between the current and
the ship-to-buggy line; Tx ~ 1.580 kN at psi0 = 90 deg). This script draws the figure from
our solutions with Wang et al.'s componentwise drag law (their eqs (4)-(6)), with the vector
law for comparison.

Beyond psi0 ~ 147.9 deg (componentwise) the free-hanging cable would pass below the seabed
near the buggy; Wang et al.'s z-formulation cannot represent that, and neither can this
contact-free scene: that range is shaded and flagged.

Run:  python examples/wang_fig3.py [--out wang_fig3.png] [--step 5]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from cable_ocp.scene import load_scene
from cable_ocp.statics.solver import sweep

PROBLEM = Path(__file__).resolve().parents[1] / "problems" / "dezoysa_sea_buggy.toml"


def compute(step: float = 5.0) -> dict[str, np.ndarray]:
    """Buggy forces (N) for both drag laws over psi0 = 0..180 deg, and the seabed flags."""
    angles = np.arange(0.0, 180.0 + 1e-9, step)
    out: dict[str, np.ndarray] = {"psi0": angles}
    for law in ("componentwise", "vector"):
        scene = load_scene(PROBLEM, {"cable.drag_law": law, "solver.error_estimate": False})
        sols = sweep(scene, "layout.psi0_deg", angles)
        # beyond the touchdown angle the cable passes below the seabed (no contact in
        # Wang's formulation): computed, flagged "below_seabed", drawn as such
        if not all(s.success or s.status == "below_seabed" for s in sols):
            bad = [a for a, s in zip(angles, sols, strict=True)
                   if not (s.success or s.status == "below_seabed")]
            raise RuntimeError(f"{law}: solves failed at psi0 = {bad}")
        out[law] = np.array([s.force_a for s in sols])
        out[law + "_below_seabed"] = np.array([s.force_a[2] < 0 for s in sols])
    return out


def plot(data: dict[str, np.ndarray], path: str | Path) -> Path:
    """Draw the figure to ``path`` (the format follows the suffix)."""
    from cable_ocp.plots.common import legend_below, new_figure, save

    fig = new_figure(8.5, 6.2)
    ax = fig.add_subplot()
    psi = data["psi0"]
    handles = []
    for k, lab in enumerate(("T_x", "T_y", "T_z")):
        handles += ax.plot(psi, data["componentwise"][:, k] / 1e3, "o-", ms=3, color=f"C{k}",
                           label=f"{lab}, componentwise law (Wang et al.)")
        handles += ax.plot(psi, data["vector"][:, k] / 1e3, "--", lw=1.2, color=f"C{k}",
                           label=f"{lab}, vector law")
    below = psi[data["componentwise_below_seabed"]]
    if below.size:
        handles.append(ax.axvspan(below.min() - 0.5 * (psi[1] - psi[0]), psi.max(),
                                  color="0.9", zorder=0,
                                  label="componentwise cable below the seabed (no contact "
                                        "modelled)"))
    ax.axhline(0.0, color="k", lw=0.6)
    handles += ax.plot([90.0], [1.58], "*", color="k", ms=12, ls="none",
                       label="Wang et al. (1993): T_x ~ 1.580 kN at psi0 = 90 deg")
    ax.set_xlim(psi.min() - 3, psi.max() + 3)
    ax.set_xticks(np.arange(0, 181, 30))
    ax.set_xlabel("angle between the current and the ship-to-buggy line, psi0 (deg)")
    ax.set_ylabel("force of the cable on the buggy (kN)")
    ax.set_title("De Zoysa's sea buggy: force at the buggy against the current's angle\n"
                 "(cf. Wang, Cheong & Chucheepsakul 1993, Fig. 3)", fontsize=10.5)
    ax.grid(True, alpha=0.3)
    legend_below(fig, handles, ncols=2)
    path = Path(path)
    save(fig, path)
    return path


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    ap = argparse.ArgumentParser(
        description="Reproduce Wang, Cheong & Chucheepsakul (1993), Fig. 3: the force of the "
                    "cable on De Zoysa's sea buggy against the current's angle psi0, with "
                    "the componentwise and the vector drag laws. Prints the force at "
                    "psi0 = 90 deg and writes the figure.")
    ap.add_argument("--out", default="wang_fig3.png", metavar="PATH",
                    help="figure file; PNG, PDF or SVG by its suffix (default %(default)s)")
    ap.add_argument("--step", type=float, default=5.0, metavar="DEG",
                    help="psi0 step, deg, from 0 to 180 (default %(default)s)")
    args = ap.parse_args(argv)
    data = compute(args.step)
    i90 = int(np.argmin(np.abs(data["psi0"] - 90.0)))
    print(f"psi0 = {data['psi0'][i90]:g} deg: force at buggy = "
          f"{np.round(data['componentwise'][i90], 1)} N (Wang et al. 1993: Tx ~ 1580 N)")
    plot(data, args.out)
    print(f"wrote {args.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
