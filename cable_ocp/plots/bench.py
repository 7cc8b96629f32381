"""Figures of the benchmarks: the work-precision diagram of the statics methods."""

from __future__ import annotations

import csv
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.plots.common import legend_below, new_figure, save

#: methods built on this package's collocation or multiple shooting (drawn solid)
OURS_PREFIX = ("collocation", "multiple shooting")


def plot_work_precision(results: list[dict[str, Any]], path: str | Path,
                        title: str = "Work-precision of the statics methods") -> Any:
    """Log-log error against wall time, one panel per scene, one legend below them.

    Parameters
    ----------
    results : list of dict
        One dict per scene with ``"scene"`` (its label) and ``"rows"``: dicts with
        ``method``, ``time_s`` (s), ``force_error`` and ``profile_error`` (relative, -;
        None when the solve failed), as :func:`cable_ocp.bench.accuracy.run` returns.
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
    fig = new_figure(6.2 * n + 0.6, 6.4)
    methods = list(dict.fromkeys(r["method"] for res in results for r in res["rows"]))
    handles = []
    for k, res in enumerate(results):
        ax = fig.add_subplot(1, n, k + 1, label=res["scene"])
        for j, m in enumerate(methods):
            pts = [(r["time_s"], max(r["force_error"], r["profile_error"]))
                   for r in res["rows"] if r["method"] == m and r["force_error"] is not None
                   and r["profile_error"] is not None]
            if not pts:
                continue
            t, e = np.array(pts, float).T
            warm = "built once" in m
            ours = m.startswith(OURS_PREFIX)
            style = ({"ls": "-", "marker": "D", "color": "k"} if warm else
                     {"ls": "-", "marker": "o", "color": f"C{j % 10}"} if ours else
                     {"ls": "--", "marker": "s", "color": f"C{j % 10}"})
            (h,) = ax.loglog(t * 1e3, np.maximum(e, 1e-16), ms=4.5, lw=1.4, label=m, **style)
            handles.append(h)
        ax.set_xlabel("wall time per solve (ms); cold calls include the CasADi build")
        ax.set_ylabel("relative error, larger of end forces and profile (-)")
        ax.set_title(res["scene"], fontsize=10.5)
        ax.grid(True, which="major", alpha=0.35)
        ax.grid(True, which="minor", alpha=0.12)
    fig.suptitle(title + "\nsolid: this package's transcriptions; dashed: the published "
                 "methods (baselines); black: one solver reused, warm-started", fontsize=11)
    legend_below(fig, handles, ncols=3)
    save(fig, path)
    return fig


def read_work_precision_csv(path: str | Path) -> list[dict[str, Any]]:
    """Read the CSV of ``cable-ocp bench accuracy --csv`` back into ``results`` form (to
    redraw the figure without re-running the benchmark)."""
    scenes: dict[str, list[dict[str, Any]]] = {}
    with Path(path).open(newline="") as fh:
        for row in csv.DictReader(fh):
            def num(key: str, row: dict[str, str] = row) -> float | None:
                v = row.get(key, "")
                return float(v) if v not in ("", "None", "nan", "-") else None

            scenes.setdefault(row["scene"], []).append({
                "method": row["method"], "time_s": num("time_s"),
                "force_error": num("force_error"), "profile_error": num("profile_error")})
    return [{"scene": k, "rows": v} for k, v in scenes.items()]
