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

__all__ = ["compare_with_moorpy"]


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
        ``times_s``.
    """
    from cable_ocp.bench.moorpy_systems import moorpy_reference

    data = read_problem(path)
    scene = system_from_dict(data)
    t0 = time.perf_counter()
    model = SystemModel(scene)
    res = solve_system(scene, model=model)
    first = time.perf_counter() - t0
    repeat = _median_time(lambda: solve_system(scene, model=model, stiffness=False), repeats)
    body = scene.bodies[0].name if scene.bodies else None
    ev = model.evaluate(res.state)
    k_time = _median_time(lambda: body_stiffness(model, model.evaluate(res.state), body),
                          repeats) if body else None
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
    out["times_s"] = {"ours_first": first, "ours_repeat": repeat, "ours_6x6": k_time,
                      "moorpy_equilibrium": ref.get("time_s"),
                      "moorpy_analytic_6x6": (ref.get("stiffness") or {}).get("times_s", {})
                      .get("analytic")}
    return out
