"""Bielański's towed system slowing from 12 kn to 8 kn: a transitional state of a towed
flexible object while manoeuvring (Bielański 003, section 1's stated goal).

Source: J. Bielański, "The analysis of the system towing rope with long underwater object"
(003, section 3 and Table 1: a 1500 m steel rope towing a 300 m, 90 mm, nearly neutrally
buoyant flexible object at 12 kn); the bending term of Huang (1992) 12.4.6. The problem file
problems/dynamics/bielanski_tow_speed_change.toml states every reading (masses, EA, EI).
The run starts from the EI statics at 12 kn and ends near the statics at 8 kn; both are
solved here and drawn for comparison. The object's bending moment comes from the hinge
law (cable_ocp/physics/bending.py) on the computed node positions.

Run:  python examples/bielanski_tow_speed_change.py [--out bielanski_tow_speed_change.png]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.dynamics import load_dynamic_scene, simulate
from cable_ocp.dynamics.static import static_state
from cable_ocp.physics.bending import hinge_moment

PROBLEM = (Path(__file__).resolve().parents[1] / "problems" / "dynamics"
           / "bielanski_tow_speed_change.toml")
KNOT = 1852.0 / 3600.0  # m/s


def compute(overrides: dict[str, Any] | None = None) -> dict[str, Any]:
    """The run and the statics at the final speed: node positions (m), times (s), the top
    tension N(A) (N), the object's largest bending moment (N m) and the depths of B and C
    below the tow point (m)."""
    scene = load_dynamic_scene(PROBLEM, overrides or {})
    res = simulate(scene)
    if res.status != "solved":
        raise RuntimeError(f"the run failed: {res.message}")
    st = scene.statics
    v0 = st.environment.current.max_speed  # type: ignore[union-attr]
    dv = scene.top_motion.tow.speed  # type: ignore[union-attr]
    final = static_state(load_dynamic_scene(
        PROBLEM, {**(overrides or {}), "environment.current.speed": v0 - dv}))
    if not final.success:
        raise RuntimeError(f"the final statics failed: {final.message}")
    pos = res.node_positions
    n = pos.shape[1] - 1
    lengths = np.array([float(c.length) for c in st.lines])  # type: ignore[arg-type]
    n_obj = int(round(n * lengths[0] / lengths.sum()))  # nodes 0..n_obj: the object
    h = lengths[0] / n_obj
    ei = st.lines[0].bending_stiffness
    moment = []
    for p in pos:
        d = np.diff(p[:n_obj + 1], axis=0).T  # the object's element vectors (3 x n_obj)
        moment.append(float(np.max(hinge_moment(d[:, :-1], d[:, 1:], ei, h, h))))
    top_z = scene.top_position[2]
    return {"t": res.t, "pos": pos, "top_tension": res.top_tension,
            "moment": np.array(moment), "depth_c": top_z - pos[:, 0, 2],
            "depth_b": top_z - pos[:, n_obj, 2], "n_obj": n_obj,
            "final_depth_c": top_z - float(final.position[0, 2]),
            "final_top_tension": float(np.linalg.norm(final.force_b)),
            "speeds": (v0 / KNOT, (v0 - dv) / KNOT), "ramp": scene.top_motion.ramp_time,
            "x_top": pos[:, -1, 0]}


def plot(data: dict[str, Any], path: str | Path) -> Path:
    """Draw the figure to ``path`` (the format follows the suffix)."""
    from cable_ocp.plots.common import new_figure, save

    fig = new_figure(11.0, 8.0)
    axs = fig.subplot_mosaic([["shape", "shape"], ["depth", "force"]])
    ax1, ax2, ax3 = axs["shape"], axs["depth"], axs["force"]
    t, pos, k = data["t"], data["pos"], data["n_obj"]
    v0, v1 = data["speeds"]
    for j, tt in enumerate((0.0, 30.0, 60.0, 120.0, 300.0, 600.0, t[-1])):
        i = int(np.argmin(np.abs(t - tt)))
        p = pos[i] - pos[i, -1]  # relative to the tow point A
        col = f"C{j}"
        ax1.plot(p[k:, 0], p[k:, 2], "-", color=col, lw=1.0, label=f"t = {t[i]:.0f} s")
        ax1.plot(p[:k + 1, 0], p[:k + 1, 2], "-", color=col, lw=3.0)
    ax1.set_xlabel("x behind the tow point A (m)")
    ax1.set_ylabel("z relative to A (m)")
    ax1.set_title(f"Bielański's towed system slowing from {v0:.0f} to {v1:.0f} kn over "
                  f"{data['ramp']:.0f} s: rope (thin) and 300 m object (thick, EI = 100 N m^2)",
                  fontsize=10)
    ax1.grid(True, alpha=0.3)
    ax1.legend(fontsize=8, ncols=3)
    ax2.plot(t, data["depth_c"], label="tail C")
    ax2.plot(t, data["depth_b"], label="joint B")
    ax2.axhline(data["final_depth_c"], color="C0", ls="--", lw=0.9,
                label=f"C in the {v1:.0f} kn statics")
    ax2.invert_yaxis()
    ax2.set_xlabel("t (s)")
    ax2.set_ylabel("depth below A (m)")
    ax2.grid(True, alpha=0.3)
    ax2.legend(fontsize=8)
    ax3.plot(t, data["top_tension"] / 1e3, color="C3", label="N(A), top tension")
    ax3.axhline(data["final_top_tension"] / 1e3, color="C3", ls="--", lw=0.9,
                label=f"N(A) in the {v1:.0f} kn statics")
    ax3.set_xlabel("t (s)")
    ax3.set_ylabel("tension (kN)")
    ax3.grid(True, alpha=0.3)
    ax4 = ax3.twinx()
    ax4.plot(t, data["moment"], color="C4", lw=0.9, label="largest moment in the object")
    ax4.set_ylabel("bending moment (N m)", color="C4")
    h1, l1 = ax3.get_legend_handles_labels()
    h2, l2 = ax4.get_legend_handles_labels()
    ax3.legend(h1 + h2, l1 + l2, fontsize=8, loc="center right")
    path = Path(path)
    save(fig, path)
    return path


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    ap = argparse.ArgumentParser(
        description="Simulate Bielański's towed system (1500 m rope, 300 m flexible object "
                    "with bending stiffness) while the ship slows from 12 to 8 kn, from the "
                    "EI statics at 12 kn; print the depths and tensions at the start and the "
                    "end beside the 8 kn statics, and write the figure.")
    ap.add_argument("--out", default="bielanski_tow_speed_change.png", metavar="PATH",
                    help="figure file; PNG, PDF or SVG by its suffix (default %(default)s)")
    ap.add_argument("--duration", type=float, default=None, metavar="S",
                    help="simulated time, s (default: the problem file's)")
    args = ap.parse_args(argv)
    ov = {} if args.duration is None else {"simulation.duration": args.duration}
    data = compute(ov)
    v0, v1 = data["speeds"]
    print(f"t = 0 s ({v0:.0f} kn): tail C {data['depth_c'][0]:.1f} m below A, N(A) = "
          f"{data['top_tension'][0] / 1e3:.2f} kN")
    print(f"t = {data['t'][-1]:.0f} s ({v1:.0f} kn): tail C {data['depth_c'][-1]:.1f} m, "
          f"N(A) = {data['top_tension'][-1] / 1e3:.2f} kN; the {v1:.0f} kn statics: "
          f"{data['final_depth_c']:.1f} m, {data['final_top_tension'] / 1e3:.2f} kN")
    print(f"largest bending moment in the object: {data['moment'].max():.3g} N m")
    plot(data, args.out)
    print(f"wrote {args.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
