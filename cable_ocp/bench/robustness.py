"""Robustness matrix: every statics method on every extreme scene.

Each cell is one of

* ``ok``     converged, and the end forces and length agree with the reference to 1 %;
* ``FAIL``   not a success, with the method's own status message (an honest failure). A
             result that converged but whose error estimate misses ``solver.accuracy``
             (status ``"inaccurate"``, every method) shows its error against the
             reference, e.g. ``FAIL 7e-03``;
* ``n/a``    the method cannot represent the scene and says so (CableOCPError);
* ``WRONG``  reported as converged but more than 1 % off the reference: a defect. This
             column must stay empty for the collocation solver.
* ``CRASH``  an unexpected exception (a defect too).

The 1 % threshold is what an engineer would call a wrong answer. Each method runs with the
scene's own settings: ``solver.intervals`` = 40 to start, refined up to its limit towards
``solver.accuracy`` (1e-6), so a ``"solved"`` cell also promises that accuracy (to 3x, the
estimates' contract, tested in tests/test_baseline_accuracy.py) and the first-order
Huang method is ``FAIL`` (inaccurate) with its 1e-3-1e-2 error shown. The reference is
:func:`cable_ocp.bench.common.reference_solution`.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from cable_ocp.bench.common import force_error, reference_solution, timed_solve
from cable_ocp.scene import METHODS, load_scene

ROOT = Path(__file__).resolve().parents[2] / "problems"
WRONG_THRESHOLD = 1e-2


def default_scenes() -> list[Path]:
    """The extreme scenes plus the shipped published examples."""
    return sorted((ROOT / "extreme").glob("*.toml")) + [
        ROOT / "berteaux_mooring.toml", ROOT / "dezoysa_sea_buggy.toml"]


def classify(sol: Any, note: str, ref: Any) -> tuple[str, float | None, str]:
    """Cell category, error against the reference, and the detail message.

    Parameters
    ----------
    sol : StaticsSolution or None
        The method's solution; None when it raised (see ``note``).
    note : str
        :func:`~cable_ocp.bench.common.timed_solve`'s note: ``"unsupported: ..."`` (the
        method cannot represent the scene: ``n/a``) or ``"crashed: ..."`` (``CRASH``).
    ref : StaticsSolution or None
        The scene's reference; None or a failed one gives ``"ok?"`` for a success. The
        error is the larger of the end-force error over its largest tension and the
        length error over its length (-).
    """
    if sol is None:
        return ("n/a" if note.startswith("unsupported") else "CRASH"), None, note
    if not sol.success:
        err = None
        if sol.status == "inaccurate" and ref is not None and ref.success:
            err = max(force_error(sol, ref), abs(sol.length - ref.length) / ref.length)
        return "FAIL", err, f"{sol.status}: {sol.message}"
    if ref is None or not ref.success:
        return "ok?", None, "no reference to compare with"
    err = max(force_error(sol, ref), abs(sol.length - ref.length) / ref.length)
    return ("WRONG" if err > WRONG_THRESHOLD else "ok"), err, sol.message


def run(scenes: list[Path] | None = None, methods: list[str] | None = None,
        progress: Callable[[int, int, dict[str, Any]], None] | None = None,
        details: list[dict[str, Any]] | None = None) -> dict[str, Any]:
    """Run the matrix; returns rows of cells and the details of every cell.

    ``progress(done, total, detail)`` is called after each cell; ``details``, if given, is
    the list the cell details are appended to (so that a caller keeps the finished cells
    when the run is interrupted).

    Parameters
    ----------
    scenes : list of Path, optional
        Problem files, one row each; None (default): :func:`default_scenes`.
    methods : list of str, optional
        Statics methods, one column each (names of :data:`cable_ocp.scene.METHODS`); None
        (default): all of them.
    progress : callable, optional
        ``progress(done, total, detail)``, called after each cell, ``done`` the length of
        ``details``; None (default): none.
    details : list of dict, optional
        The list the cell details are appended to (scene, method, category, error, time_s
        in s, message); None (default): a new one.
    """
    scenes = scenes or default_scenes()
    methods = methods or list(METHODS)
    rows: list[list[Any]] = []
    details = [] if details is None else details
    total = len(scenes) * len(methods)
    for path in scenes:
        scene = load_scene(path)
        ref = reference_solution(scene)
        row: list[Any] = [path.stem, f"{ref.agreement:.0e}"]
        for m in methods:
            sol, dt, note = timed_solve(scene.with_overrides({"solver.method": m}))
            cat, err, msg = classify(sol, note, ref.solution)
            row.append(cat if err is None else f"{cat} {err:.0e}")
            details.append({"scene": path.stem, "method": m, "category": cat, "error": err,
                            "time_s": dt, "message": msg})
            if progress is not None:
                progress(len(details), total, details[-1])
        rows.append(row)
    headers = ["scene", "ref check", *methods]
    wrong_ours = [d for d in details if d["method"] == "collocation"
                  and d["category"] in ("WRONG", "CRASH")]
    return {"headers": headers, "rows": rows, "details": details, "wrong_ours": wrong_ours}
