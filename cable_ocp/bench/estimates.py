"""Honesty of the baselines' error estimates: estimate against true error on the benchmark
scenes (the accuracy contract of ``solver.accuracy``, docs/baselines.md).

For each baseline method, scene and resolution (refinement off, so that the resolution is
the one asked for), the method's ``error_estimate`` is compared with its true error: the
larger of the end-force error over the largest tension and the position error at the
method's own nodes (and the length error) over the length, against a converged reference
(:func:`cable_ocp.bench.common.reference_solution`). The contract: true error <= 3 x
estimate. True errors below ``floor`` (the reference's own uncertainty, times 10) are
reported but not judged.

Run ``python -m cable_ocp.bench.estimates`` (several minutes: Wang's Nelder-Mead and the
references dominate) to print the table of docs/baselines.md.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from cable_ocp.bench.common import force_error, profile_error, reference_solution
from cable_ocp.errors import CableOCPError
from cable_ocp.scene import Scene, load_scene
from cable_ocp.statics.registry import get_method
from cable_ocp.statics.solution import StaticsSolution

ROOT = Path(__file__).resolve().parents[2] / "problems"

#: method -> (key set per row, resolutions, fixed overrides)
PLAN: dict[str, tuple[str, list[Any], dict[str, Any]]] = {
    "huang_semianalytic": ("solver.intervals", [10, 40, 160], {}),
    "chucheepsakul_fem": ("solver.intervals", [10, 40, 160], {}),
    "wang_shooting_optimization": ("solver.intervals", [10, 20, 40], {}),
    "solve_bvp": ("solver.tolerance", [1e-3, 1e-5, 1e-7], {"solver.intervals": 10}),
}

RATIO_LIMIT = 3.0


def default_scenes() -> list[tuple[str, Path, dict[str, Any]]]:
    """De Zoysa at 45, 90, 135 deg with both drag laws, Berteaux, and the extreme scenes
    the baselines can represent at least partly (the others fail honestly for all four)."""
    out = []
    dz = ROOT / "dezoysa_sea_buggy.toml"
    for psi in (45.0, 90.0, 135.0):
        for law in ("componentwise", "vector"):
            out.append((f"De Zoysa {psi:.0f} {law[:4]}.", dz,
                        {"layout.psi0_deg": psi, "cable.drag_law": law}))
    out.append(("Berteaux", ROOT / "berteaux_mooring.toml", {}))
    for name in ("deep_water", "drag_dominated", "very_soft", "neutrally_buoyant",
                 "hanging_vertical", "nearly_taut_stiff"):
        out.append((name, ROOT / "extreme" / f"{name}.toml", {}))
    return out


def true_error(sol: StaticsSolution, ref: StaticsSolution) -> float:
    """Larger of the end-force error over the largest tension and the position (at the
    method's nodes) and length error over the length (-).

    Parameters
    ----------
    sol : StaticsSolution
        The baseline's solution.
    ref : StaticsSolution
        The converged reference of the same scene (:func:`reference_solution`'s).
    """
    return max(force_error(sol, ref), profile_error(sol, ref))


def run_scene(label: str, scene: Scene, ref: StaticsSolution, floor: float,
              methods: list[str] | None = None,
              progress: Callable[[dict[str, Any]], None] | None = None
              ) -> list[dict[str, Any]]:
    """Rows (scene, method, resolution, status, estimate, true error, ratio, time).

    Parameters
    ----------
    label : str
        The scene's name in the rows.
    scene : Scene
        The statics scene; each row overrides its method, resolution and
        ``solver.refine = false``.
    ref : StaticsSolution
        The scene's converged reference (the true errors are measured against it).
    floor : float
        True errors (-) at or below it are reported but not judged (the reference's own
        uncertainty).
    methods : list of str, optional
        Baseline methods to check, keys of :data:`PLAN` (another name raises
        ``KeyError``); None (default): all four.
    progress : callable, optional
        ``progress(row)``, called after each row; None (default): none.
    """
    rows = []
    for method in methods or list(PLAN):
        key, resolutions, fixed = PLAN[method]
        for res in resolutions:
            sc = scene.with_overrides({**fixed, "solver.method": method, key: res,
                                       "solver.refine": False})
            t0 = time.perf_counter()
            try:
                sol = get_method(method)(sc)
            except CableOCPError:
                break  # the method cannot represent the scene
            row: dict[str, Any] = {"scene": label, "method": method, "resolution": res,
                                   "status": sol.status, "estimate": sol.error_estimate,
                                   "true_error": None, "ratio": None, "judged": False,
                                   "time_s": time.perf_counter() - t0}
            if sol.converged and ref.success:
                true = true_error(sol, ref)
                row["true_error"] = true
                est = sol.error_estimate
                if est is not None and est > 0 and math.isfinite(est):
                    row["ratio"] = true / est
                row["judged"] = true > floor
            rows.append(row)
            if progress is not None:
                progress(row)
    return rows


def run(scenes: list[tuple[str, Path, dict[str, Any]]] | None = None,
        methods: list[str] | None = None,
        progress: Callable[[dict[str, Any]], None] | None = None) -> list[dict[str, Any]]:
    """All scenes; each row also carries the reference's agreement with its check.

    Parameters
    ----------
    scenes : list of (str, Path, dict), optional
        ``(label, problem file, overrides)`` per scene; None (default):
        :func:`default_scenes`.
    methods : list of str, optional
        Baseline methods to check, keys of :data:`PLAN` (another name raises
        ``KeyError``); None (default): all four.
    progress : callable, optional
        ``progress(row)``, called after each row; None (default): none.
    """
    rows = []
    for label, path, over in scenes or default_scenes():
        scene = load_scene(path, over)
        ref = reference_solution(scene)
        floor = 10.0 * ref.agreement if math.isfinite(ref.agreement) else math.inf
        for row in run_scene(label, scene, ref.solution, max(floor, 1e-9), methods, progress):
            row["reference_check"] = ref.agreement
            rows.append(row)
    return rows


def summary(rows: list[dict[str, Any]]) -> dict[str, dict[str, Any]]:
    """Per method: judged rows, min/median/max of true/estimate, rows over RATIO_LIMIT."""
    out = {}
    for m in dict.fromkeys(r["method"] for r in rows):
        ratios = sorted(r["ratio"] for r in rows if r["method"] == m and r["judged"]
                        and r["ratio"] is not None)
        unjudged = [r for r in rows if r["method"] == m and r["judged"] and r["ratio"] is None]
        out[m] = {"judged": len(ratios) + len(unjudged),
                  "min": ratios[0] if ratios else None,
                  "median": ratios[len(ratios) // 2] if ratios else None,
                  "max": ratios[-1] if ratios else None,
                  "over_limit": sum(r > RATIO_LIMIT for r in ratios),
                  "no_estimate": len(unjudged)}
    return out


def main() -> None:  # pragma: no cover - a benchmark, run by hand
    """Print the rows and the summary (a benchmark: prints)."""
    def show(r: dict[str, Any]) -> None:
        def f(x: Any) -> str:
            return "-" if x is None else f"{x:.1e}" if isinstance(x, float) else str(x)
        print(f"{r['scene']:22s} {r['method']:28s} {f(r['resolution']):>8s} "
              f"{r['status']:12s} est {f(r['estimate']):>8s} true {f(r['true_error']):>8s} "
              f"true/est {f(r['ratio']):>8s}{'' if r['judged'] else ' (below floor)'} "
              f"{r['time_s']:.2f} s", flush=True)

    rows = run(progress=show)
    for m, s in summary(rows).items():
        print(m, s)


if __name__ == "__main__":  # pragma: no cover
    main()
