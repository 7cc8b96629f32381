"""Reproduce Wang, Cheong & Chucheepsakul (1993), Fig. 3: the force at De Zoysa's buggy.

Source: ../shared/seeds/000_2b3c74cf924aa082.txt, "De Zoysa's Three-Dimensional Cable
Problem" and Fig. 3 (bottom tension components Tx, Ty, Tz versus the angle psi0 between the
current and the ship-to-buggy line; "Tx ~ 1.580" kN at psi0 = 90 deg). The figure itself is
lost in the OCR; this script draws it from our solution with Wang's componentwise drag law
(000 eqs (4)-(6)), with the vector law dashed for comparison.

Beyond psi0 ~ 147.9 deg (componentwise) the free-hanging cable would pass below the seabed
near the buggy (seeds README, CONVENTIONS "Seabed"); Wang's z-formulation cannot represent
that, and neither can this contact-free scene: that range is shaded and flagged.

Run:  python examples/wang_fig3.py [--out wang_fig3.png] [--step 5]
"""

from __future__ import annotations

import argparse
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
    """Draw the figure to ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.5, 5))
    psi = data["psi0"]
    for k, lab in enumerate(("Tx", "Ty", "Tz")):
        ax.plot(psi, data["componentwise"][:, k] / 1e3, "o-", ms=3, color=f"C{k}",
                label=f"{lab} (componentwise, 000)")
        ax.plot(psi, data["vector"][:, k] / 1e3, "--", lw=1, color=f"C{k}",
                label=f"{lab} (vector law)")
    below = psi[data["componentwise_below_seabed"]]
    if below.size:
        ax.axvspan(below.min() - 0.5 * (psi[1] - psi[0]), psi.max(), color="0.9", zorder=0,
                   label="cable below seabed (no contact model)")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.annotate("Tx ~ 1.580 kN (000)", xy=(90, 1.58), xytext=(100, 2.6),
                arrowprops={"arrowstyle": "->"})
    ax.set_xlabel("psi0 [deg]")
    ax.set_ylabel("force at the buggy [kN]")
    ax.set_title("De Zoysa's sea buggy (000 Fig. 3)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path, dpi=130)
    plt.close(fig)
    return path


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="wang_fig3.png")
    ap.add_argument("--step", type=float, default=5.0, help="psi0 step, deg")
    args = ap.parse_args(argv)
    data = compute(args.step)
    plot(data, args.out)
    i90 = int(np.argmin(np.abs(data["psi0"] - 90.0)))
    print(f"psi0 = 90 deg: force at buggy = {np.round(data['componentwise'][i90], 1)} N "
          f"(000: Tx ~ 1580 N); figure: {args.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
