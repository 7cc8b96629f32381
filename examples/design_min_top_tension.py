"""Design through the statics: the cable length that minimises the ship's top tension while
the whole cable stays off the seabed (De Zoysa's sea buggy at psi0 = 150 deg, in the frame
of Wang, Cheong & Chucheepsakul 1993).

A longer cable hangs slacker, so the top tension falls with the length, until the cable
touches the seabed next to the buggy (the vertical force at the buggy reaches zero). The
optimum is that touchdown length; one NLP (cable_ocp.statics.optimize) finds it directly,
where a user of MoorPy/OrcaFlex would scan. The scan is done here too, as the check.

Run:  python examples/design_min_top_tension.py [--scan 40] [--out design_min_top_tension.png]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import casadi as ca
import numpy as np

from cable_ocp.scene import Scene, load_scene
from cable_ocp.statics.optimize import OptimizationResult, StaticsNLP
from cable_ocp.statics.solver import StaticsSolver

PROBLEM = Path(__file__).resolve().parents[1] / "problems" / "dezoysa_sea_buggy.toml"


def scene() -> Scene:
    """De Zoysa at psi0 = 150 deg (componentwise law), no error estimate (speed)."""
    return load_scene(PROBLEM, {"layout.psi0_deg": 150.0, "cable.length": 300.0,
                                "solver.error_estimate": False})


def optimise(sc: Scene, lower: float = 294.0, upper: float = 400.0) -> OptimizationResult:
    """min |T(L)|^2 over L in [lower, upper], with z >= 0 at every node and the cable
    leaving the buggy upwards (vertical force at the buggy >= 0)."""
    nlp = StaticsNLP(sc, {"cable.length": (lower, upper)})
    return nlp.solve(lambda v: ca.sumsqr(v.force_b) / 1e7,
                     lambda v: [(v.position[:, 2], 0.0, np.inf), (v.force_a[2], 0.0, np.inf)])


def scan(sc: Scene, lengths: np.ndarray) -> list[tuple[float, float, bool]]:
    """(length, top tension, feasible) by ordinary statics solves, one solver reused."""
    solver = StaticsSolver(sc)
    out, prev = [], None
    for length in lengths:
        s = solver.solve(sc.with_overrides({"cable.length": float(length)}), warm_start=prev)
        feasible = s.success and s.force_a[2] >= 0 and s.position[:, 2].min() >= -1e-9
        out.append((float(length), float(np.linalg.norm(s.force_b)), bool(feasible)))
        prev = s if s.success else prev
    return out


def plot(res: OptimizationResult, rows: list[tuple[float, float, bool]],
         path: str | Path) -> Path:
    """Top tension against cable length (the scan) with the NLP optimum, to ``path``."""
    from cable_ocp.plots.common import legend_below, new_figure, save

    fig = new_figure(8.0, 5.6)
    ax = fig.add_subplot()
    arr = np.array([(length, t) for length, t, _ in rows])
    ok = np.array([f for *_, f in rows])
    handles = ax.plot(arr[:, 0], arr[:, 1] / 1e3, "-", color="0.6", lw=1.0,
                      label="top tension of ordinary statics solves (scan)")
    handles += ax.plot(arr[ok, 0], arr[ok, 1] / 1e3, "o", color="#1f4e79", ms=5,
                       label="feasible: the cable stays off the seabed")
    handles += ax.plot(arr[~ok, 0], arr[~ok, 1] / 1e3, "o", mfc="w", color="#d62728", ms=5,
                       label="infeasible: the cable would touch the seabed at the buggy")
    l_opt = res.variables["cable.length"]
    t_opt = float(np.linalg.norm(res.solution.force_b))
    handles += ax.plot([l_opt], [t_opt / 1e3], "*", color="k", ms=15, ls="none",
                       label=f"NLP optimum: L* = {l_opt:.3f} m, {t_opt / 1e3:.4g} kN "
                             f"({res.status})")
    ax.axvline(l_opt, color="k", lw=0.8, ls=":")
    ax.set_xlabel("unstretched cable length L (m)")
    ax.set_ylabel("top tension at the ship |T(L)| (kN)")
    ax.set_title("De Zoysa's sea buggy at psi0 = 150 deg: least top tension with the cable "
                 "off the seabed", fontsize=10)
    ax.grid(True, alpha=0.3)
    legend_below(fig, handles, ncols=1)
    path = Path(path)
    save(fig, path)
    return path


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    ap = argparse.ArgumentParser(
        description="The cable length that minimises the ship's top tension on De Zoysa's "
                    "sea buggy (psi0 = 150 deg) with the cable off the seabed: one NLP "
                    "through the statics, checked by a scan of ordinary solves (printed "
                    "and drawn).")
    ap.add_argument("--scan", type=int, default=40, metavar="N",
                    help="number of lengths in the check scan, 295-320 m (default %(default)s)")
    ap.add_argument("--out", default="design_min_top_tension.png", metavar="PATH",
                    help="figure file; PNG, PDF or SVG by its suffix (default %(default)s)")
    args = ap.parse_args(argv)
    if args.scan < 2:
        ap.error(f"--scan {args.scan}: give at least 2 lengths")
    sc = scene()
    res = optimise(sc)
    print(f"NLP: {res.status}, L* = {res.variables['cable.length']:.4f} m, top tension "
          f"{np.linalg.norm(res.solution.force_b):.2f} N ({res.iterations} iterations, "
          f"{res.wall_time_s * 1e3:.0f} ms)")
    rows = scan(sc, np.linspace(295.0, 320.0, args.scan))
    feasible = [(t, length) for length, t, f in rows if f]
    if feasible:
        best = min(feasible)
        print(f"scan: best feasible L = {best[1]:.3f} m with {best[0]:.2f} N "
              f"({len(feasible)} of {len(rows)} lengths feasible)")
    else:
        print(f"scan: none of the {len(rows)} lengths is feasible")
    plot(res, rows, args.out)
    print(f"wrote {args.out}", file=sys.stderr)
    return 0 if res.success else 1


if __name__ == "__main__":
    raise SystemExit(main())
