"""Design through the statics: the cable length that minimises the ship's top tension while
the whole cable stays off the seabed (De Zoysa's sea buggy at psi0 = 150 deg, 000).

A longer cable hangs slacker, so the top tension falls with the length, until the cable
touches the seabed next to the buggy (the vertical force at the buggy reaches zero). The
optimum is that touchdown length; one NLP (cable_ocp.statics.optimize) finds it directly,
where a user of MoorPy/OrcaFlex would scan. The scan is done here too, as the check.

Run:  python examples/design_min_top_tension.py [--scan 40]
"""

from __future__ import annotations

import argparse
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


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scan", type=int, default=40, help="number of lengths in the check scan")
    args = ap.parse_args(argv)
    sc = scene()
    res = optimise(sc)
    print(f"NLP: {res.status}, L* = {res.variables['cable.length']:.4f} m, top tension "
          f"{np.linalg.norm(res.solution.force_b):.2f} N ({res.iterations} iterations, "
          f"{res.wall_time_s * 1e3:.0f} ms)")
    rows = scan(sc, np.linspace(295.0, 320.0, args.scan))
    best = min((t, length) for length, t, f in rows if f)
    print(f"scan: best feasible L = {best[1]:.3f} m with {best[0]:.2f} N "
          f"({sum(f for *_, f in rows)} of {len(rows)} lengths feasible)")
    return 0 if res.success else 1


if __name__ == "__main__":
    raise SystemExit(main())
