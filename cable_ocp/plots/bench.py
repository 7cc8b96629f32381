"""Figures of the benchmarks: the work-precision diagrams of the statics methods and of
the dynamics beside MoorDyn."""

from __future__ import annotations

import csv
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.bench.dynamics import EQUAL_ACCURACY, TARGET_REALTIME, BenchRow, row_ok
from cable_ocp.plots.common import legend_below, new_figure, save

#: methods built on this package's collocation or multiple shooting (drawn solid)
OURS_PREFIX = ("collocation", "multiple shooting")


def plot_work_precision(results: list[dict[str, Any]], path: str | Path,
                        title: str = "Work-precision of the statics methods") -> Any:
    """Log-log error against run time, one panel per scene, one legend below them.

    The time axis is the process's CPU time per solve when every row has it (``cpu_s``:
    other jobs on a shared machine disturb it much less than the wall clock), else the
    wall time (``time_s``); the axis label says which. A series timed in a second process
    (label ending in " (2nd process)", functions from the disk cache) has the colour of
    its first-process series, dotted with open markers; scipy's ``solve_bvp``, the
    reference the cold solves are compared with, is drawn thicker.

    Parameters
    ----------
    results : list of dict
        One dict per scene with ``"scene"`` (its label) and ``"rows"``: dicts with
        ``method``, ``time_s`` (s), optionally ``cpu_s`` (s), ``force_error`` and
        ``profile_error`` (relative, -; None when the solve failed), as
        :func:`cable_ocp.bench.accuracy.run` returns.
    path : str or Path
        Output file; the format follows the suffix.
    title : str
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
        The saved figure; its axes are labelled with the scenes' names.
    """
    n = len(results)
    fig = new_figure(6.2 * n + 0.6, 6.6)
    second = " (2nd process)"

    def usable(r: dict[str, Any]) -> bool:
        return r["force_error"] is not None and r["profile_error"] is not None

    rows = [r for res in results for r in res["rows"] if usable(r)]
    key = "cpu_s" if rows and all(r.get("cpu_s") is not None for r in rows) else "time_s"
    methods = list(dict.fromkeys(r["method"] for res in results for r in res["rows"]))
    bases = list(dict.fromkeys(m.removesuffix(second) for m in methods))
    handles = []
    for k, res in enumerate(results):
        ax = fig.add_subplot(1, n, k + 1, label=res["scene"])
        for m in methods:
            pts = [(r[key], max(r["force_error"], r["profile_error"]))
                   for r in res["rows"] if r["method"] == m and usable(r)]
            if not pts:
                continue
            t, e = np.array(pts, float).T
            color = f"C{bases.index(m.removesuffix(second)) % 10}"
            if "built once" in m:
                style = {"ls": "-", "marker": "D", "color": "k", "lw": 1.4}
            elif m.endswith(second):
                style = {"ls": ":", "marker": "o", "mfc": "none", "color": color, "lw": 1.4}
            elif m.startswith(OURS_PREFIX):
                style = {"ls": "-", "marker": "o", "color": color, "lw": 1.4}
            else:
                style = {"ls": "--", "marker": "s", "color": color,
                         "lw": 2.6 if "solve_bvp" in m else 1.4}
            (h,) = ax.loglog(t * 1e3, np.maximum(e, 1e-16), ms=4.5, label=m, **style)
            handles.append(h)
        what = "CPU time" if key == "cpu_s" else "wall time"
        ax.set_xlabel(f"{what} per solve (ms); cold calls include the CasADi build")
        ax.set_ylabel("relative error, larger of end forces and profile (-)")
        ax.set_title(res["scene"], fontsize=10.5)
        ax.grid(True, which="major", alpha=0.35)
        ax.grid(True, which="minor", alpha=0.12)
    fig.suptitle(title + "\nsolid: this package's transcriptions, first process (functions "
                 "built); dotted: second process (functions from the disk cache);\n"
                 "dashed: scipy's solve_bvp (thick) and the published methods; black: one "
                 "solver reused, warm-started", fontsize=10.5)
    legend_below(fig, handles, ncols=3)
    save(fig, path)
    return fig


def read_work_precision_csv(path: str | Path) -> list[dict[str, Any]]:
    """Read the CSV of ``cable-ocp bench accuracy --csv`` back into ``results`` form (to
    redraw the figure without re-running the benchmark)."""
    scenes: dict[str, list[dict[str, Any]]] = {}
    with Path(path).open(newline="") as fh:
        for row in csv.DictReader(fh):
            def num(key: str, header: str, row: dict[str, str] = row) -> float | None:
                # the command writes the headers with units ("time [s]"); keys also read
                v = row.get(key, row.get(header, ""))
                return float(v) if v not in ("", "None", "nan", "-") else None

            scenes.setdefault(row["scene"], []).append({
                "method": row["method"], "time_s": num("time_s", "time [s]"),
                "cpu_s": num("cpu_s", "CPU [s]"),
                "force_error": num("force_error", "force error [-]"),
                "profile_error": num("profile_error", "profile error [-]")})
    return [{"scene": k, "rows": v} for k, v in scenes.items()]


def plot_dynamics_work_precision(rows: Sequence[BenchRow], path: str | Path) -> Path:
    """Work-precision figure: top-tension error against wall time per simulated second,
    one colour per number of segments, solid cable_ocp, dashed MoorDyn
    (:func:`cable_ocp.bench.dynamics.run`'s rows).

    Parameters
    ----------
    rows : sequence of BenchRow
        The benchmark's rows (failed rows are left out).
    path : str or Path
        Output file; the format follows the suffix.
    """
    fig = new_figure(7.5, 5.2)
    ax = fig.add_subplot(1, 1, 1)
    for j, n in enumerate(dict.fromkeys(r.segments for r in rows)):
        for model, style in (("cable_ocp", {"ls": "-", "marker": "o"}),
                             ("MoorDyn", {"ls": "--", "marker": "s"})):
            # joined in the order of the time step (largest first), not of the timings
            pts = sorted((-r.time_step, r.wall_per_simulated_s, r.error) for r in rows
                         if r.segments == n and r.model.startswith(model) and row_ok(r))
            if pts:
                _, w, e = np.array(pts).T
                ax.loglog(w * 1e3, np.maximum(e, 1e-16), color=f"C{j % 10}",
                          label=f"{model}, {n} segments", **style)
    ax.axhline(EQUAL_ACCURACY, color="0.5", lw=0.8, ls=":")  # the equal-accuracy level
    ax.axvline(1e3 / TARGET_REALTIME, color="0.5", lw=0.8, ls=":")  # 100x real time
    ax.set_xlabel("wall time per simulated second (ms)")
    ax.set_ylabel("top-force error against the reference / amplitude (-)")
    ax.set_title("Huang (1992) 5.7 system at 1.256 rad/s: work-precision", fontsize=10.5)
    ax.grid(True, which="major", alpha=0.35)
    ax.legend(fontsize=8)
    save(fig, path)
    return Path(path)
