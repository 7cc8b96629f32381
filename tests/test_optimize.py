"""Design optimisation through the statics, checked by brute force (issue 6)."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.statics.optimize import StaticsNLP

EX = Path(__file__).resolve().parents[1] / "examples" / "design_min_top_tension.py"


def _example():
    spec = importlib.util.spec_from_file_location("design_min_top_tension", EX)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_min_top_tension_matches_brute_force(tmp_path):
    """The NLP optimum is no worse than any feasible length of a scan, and sits at the
    feasibility boundary (touchdown at the buggy), which bisection on ordinary statics
    solves locates to 1e-4 m; agreement to 1e-3 m (the NLP tolerance is far tighter)."""
    mod = _example()
    sc = mod.scene()
    res = mod.optimise(sc)
    assert res.success, res.status
    l_opt = res.variables["cable.length"]
    t_opt = float(np.linalg.norm(res.solution.force_b))
    rows = mod.scan(sc, np.linspace(295.0, 320.0, 26))
    feasible = [(t, length) for length, t, f in rows if f]
    assert feasible and t_opt <= min(feasible)[0] + 1e-6
    lo, hi = max(length for _, length in feasible), min(
        length for length, _, f in rows if not f)
    while hi - lo > 1e-4:
        mid = 0.5 * (lo + hi)
        (_, _, ok), = mod.scan(sc, np.array([mid]))
        lo, hi = (mid, hi) if ok else (lo, mid)
    assert l_opt == pytest.approx(0.5 * (lo + hi), abs=1e-3)
    assert res.solution.force_a[2] == pytest.approx(0.0, abs=1e-6 * t_opt)
    text = repr(res)  # a short summary: the optimum's variables to 6 digits, not arrays
    assert len(text) < 1000 and f"cable.length = {l_opt:.6g}" in text
    assert mod.main(["--scan", "5", "--out", str(tmp_path / "d.png")]) == 0


def test_bad_variable_names(problems):
    from cable_ocp.scene import load_scene

    sc = load_scene(problems / "dezoysa_sea_buggy.toml")
    with pytest.raises(CableOCPError, match="unknown decision variable"):
        StaticsNLP(sc, {"cable.diameter": (0.01, 0.03)})
    with pytest.raises(CableOCPError, match="not prescribed"):
        StaticsNLP(sc, {"end_a.force.x": (-1.0, 1.0)})


def test_a_method_the_optimisation_cannot_transcribe_is_refused() -> None:
    """The optimisation NLP collocates the statics whatever the scene's method: a scene
    asking for multiple shooting is refused by name (it was optimised by collocation
    without a word)."""
    from cable_ocp.scene import load_scene

    sc = load_scene(Path(__file__).resolve().parents[1] / "problems" / "berteaux_mooring.toml",
                    {"solver.method": "multiple_shooting"})
    with pytest.raises(CableOCPError, match="solver.method = 'multiple_shooting'"):
        StaticsNLP(sc, {"cable.length": (2000.0, 4000.0)})
