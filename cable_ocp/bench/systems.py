"""Mooring systems beside MoorPy in one run (docs/systems.md, "Against MoorPy").

For each system without current: the body pose, every line's end tensions and laid length
of cable_ocp's equilibrium against MoorPy's ``solveEquilibrium``
(:mod:`cable_ocp.bench.moorpy_systems`), cable_ocp's exact 6x6 against central
differences of full equilibria about the fixed axes and against MoorPy's analytic
``getCoupledStiffnessA``, and the times: the equilibrium (the first, its solvers built,
and a repeat from the file's start with the solvers built), the 6x6 alone at the
equilibrium, MoorPy's equilibrium and analytic 6x6.
"""

from __future__ import annotations

import statistics
import time
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.mooring import SystemModel, body_stiffness, solve_system
from cable_ocp.scene import read_problem
from cable_ocp.scene.system import system_from_dict

__all__ = ["CURRENT_CASES", "DEFAULT_FILES", "compare_with_moorpy", "ours_with_current",
           "rows"]

#: the systems of ``cable-ocp bench systems`` (none has a current: MoorPy's is smeared)
SYSTEMS = Path(__file__).resolve().parents[2] / "problems" / "systems"
DEFAULT_FILES = tuple(str(SYSTEMS / f) for f in (
    "spar_3line.toml", "moorpy_3line_spread.toml", "spread_9line_bundled.toml",
    "spread_two_part_clump.toml"))


def _timed_solve(scene: Any, repeats: int) -> tuple[Any, Any, Any, dict[str, Any]]:
    """(model, result, evaluation at the result, ours' times): the first equilibrium (the
    model built), a repeat from the file's start (the solvers built), the 6x6 from the
    lines' end Jacobians of the solve (as MoorPy's analytic matrix uses the line
    stiffnesses of its last solve) and with the lines' sensitivities anew."""
    t0 = time.perf_counter()
    model = SystemModel(scene)
    res = solve_system(scene, model=model)
    first = time.perf_counter() - t0
    repeat = _median_time(lambda: solve_system(scene, model=model, stiffness=False), repeats)
    body = scene.bodies[0].name if scene.bodies else None
    ev = model.evaluate(res.state)
    times: dict[str, Any] = {"ours_first": first, "ours_repeat": repeat,
                             "ours_6x6_assembly": None, "ours_6x6_fresh": None}
    if body:
        times["ours_6x6_assembly"] = _median_time(lambda: body_stiffness(model, ev, body),
                                                  max(repeats, 20))
        times["ours_6x6_fresh"] = _median_time(
            lambda: body_stiffness(model, model.evaluate(res.state), body), repeats)
    return model, res, ev, times


#: (file, current speed m/s, heading deg) timed with a current (MoorPy has no exact one)
CURRENT_CASES = ((str(SYSTEMS / "spar_3line.toml"), 1.0, 30.0),
                 (str(SYSTEMS / "spread_9line.toml"), 1.0, 30.0))


def ours_with_current(path: str | Path, speed: float, heading_deg: float,
                      repeats: int = 5) -> dict[str, Any]:
    """The times of a system's equilibrium and 6x6 with a uniform current, ours alone.

    Parameters
    ----------
    path : str or Path
        A system TOML.
    speed : float
        Current speed, m/s.
    heading_deg : float
        Direction the water flows towards, deg from +x towards +y.
    repeats : int
        Timed repeats (medians).

    Returns
    -------
    dict
        As :func:`compare_with_moorpy`, without MoorPy's numbers: ``status``, ``times_s``
        (ours_first, ours_repeat, ours_6x6_assembly, ours_6x6_fresh), and ``asymmetry``
        (max |K - K^T| / max |K| of the mooring 6x6: the drag's follower loads).
    """
    from cable_ocp.mooring.stiffness import relative_asymmetry
    from cable_ocp.scene import apply_overrides

    data = apply_overrides(read_problem(path), {"environment.current": {
        "speed": speed, "heading_deg": heading_deg}})
    scene = system_from_dict(data)
    model, res, ev, times = _timed_solve(scene, repeats)
    k = body_stiffness(model, ev, scene.bodies[0].name)["mooring"]
    return {"file": f"{path} + {speed:g} m/s at {heading_deg:g} deg", "status": str(res.status),
            "asymmetry": relative_asymmetry(k), "lines": [], "times_s": {
                **times, "moorpy_equilibrium": None, "moorpy_analytic_6x6": None}}


def rows(results: list[dict[str, Any]]) -> tuple[list[str], list[list[Any]]]:
    """(headers, rows) of the bench table, one row per system.

    Parameters
    ----------
    results : list of dict
        :func:`compare_with_moorpy` results.
    """
    head = ["system", "status", "pose [m]", "T rel", "laid [m]", "K vs MP", "K vs FD",
            "ours eq [ms]", "MP eq [ms]", "ours K [ms]", "MP K [ms]"]
    out = []
    for r in results:
        t = r["times_s"]

        def ms(v: Any) -> Any:
            return None if v is None else 1e3 * v

        name = Path(r["file"].split(" + ")[0]).stem + (
            " + current" if " + " in r["file"] else "")
        out.append([name, r["status"], (r.get("pose") or {}).get("max_difference"),
            max((max(ln["tension_a"], ln["tension_b"]) for ln in r["lines"]), default=None),
            max((ln["laid_length_m"] for ln in r["lines"]), default=None),
            (r.get("stiffness") or {}).get("analytic"),
            (r.get("stiffness") or {}).get("fd_fixed_axes"), ms(t["ours_repeat"]),
            ms(t["moorpy_equilibrium"]), ms(t["ours_6x6_assembly"]),
            ms(t["moorpy_analytic_6x6"])])
    return head, out


def _median_time(fn: Any, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def compare_with_moorpy(path: str | Path, repeats: int = 5) -> dict[str, Any]:
    """One system beside MoorPy.

    Parameters
    ----------
    path : str or Path
        A system TOML without current (MoorPy's catenary is exact there).
    repeats : int
        Timed repeats (medians).

    Returns
    -------
    dict
        ``pose`` (ours, MoorPy's, the largest difference in m and deg), ``lines`` (per line
        the relative differences of the end tensions and the laid-length difference, m),
        ``stiffness`` (the largest difference of ours from MoorPy's analytic and from
        the central differences about the fixed axes, relative to the largest entry), and
        ``times_s`` (s, medians): ours_first (the model built, the lines' solvers from the
        disk cache or built), ours_repeat (from the file's start, the solvers built),
        ours_6x6_assembly (from the lines' end Jacobians of the solve, as MoorPy's analytic
        matrix uses its last solve's line stiffnesses), ours_6x6_fresh (the lines' end
        Jacobians computed anew), moorpy_equilibrium, moorpy_analytic_6x6.
    """
    from cable_ocp.bench.moorpy_systems import moorpy_reference

    data = read_problem(path)
    scene = system_from_dict(data)
    model, res, ev, times = _timed_solve(scene, repeats)
    body = scene.bodies[0].name if scene.bodies else None
    ref = moorpy_reference(data, repeats=repeats)
    out: dict[str, Any] = {"file": str(path), "status": str(res.status)}
    if body:
        ours = np.r_[res.body()["position"], res.body()["rotation_deg"]]
        mp_body = (ref.get("bodies") or {}).get(body) or {}
        theirs = (np.r_[mp_body["position_m"], mp_body["rotation_deg"]]
                  if "position_m" in mp_body else None)
        out["pose"] = {"ours": ours.tolist(), "moorpy": None if theirs is None else
                       theirs.tolist(),
                       "max_difference": None if theirs is None else
                       float(np.max(np.abs(ours - theirs)))}
        k = body_stiffness(model, ev, body)["mooring"]
        st = ref.get("stiffness") or {}
        big = float(np.max(np.abs(k)))
        out["stiffness"] = {
            key: float(np.max(np.abs(k - np.asarray(st[key])))) / big
            for key in ("analytic", "fd_fixed_axes") if key in st}
    rows = []
    for ln in res.lines:
        mp = ref["lines"][ln["name"]]
        rows.append({"line": ln["name"],
                     "tension_a": abs(ln["tension_a"] - mp["tension_a_N"]) / mp["tension_a_N"],
                     "tension_b": abs(ln["tension_b"] - mp["tension_b_N"]) / mp["tension_b_N"],
                     "laid_length_m": abs(ln["laid_length"] - mp["laid_length_m"])})
    out["lines"] = rows
    out["times_s"] = {**times,
                      "moorpy_equilibrium": (ref.get("time_s") or {}).get("solve_equilibrium"),
                      "moorpy_analytic_6x6": ((ref.get("stiffness") or {}).get("time_s") or {})
                      .get("analytic")}
    out["line_models"] = res.diagnostics.get("line_models")
    return out
