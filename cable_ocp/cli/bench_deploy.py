"""The text tables of ``cable-ocp bench deploy`` (:mod:`cable_ocp.bench.deployment` returns
the rows; this formats them)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from cable_ocp.numerics.text_table import table

__all__ = ["format_compare", "format_cost", "format_long"]


def _pct(x: Any) -> str:
    return "-" if x is None or not math.isfinite(x) else f"{x:.3g} %"


def _excess(row: dict[str, Any]) -> str:
    x = row.get("worst_excess")
    if x is None or not math.isfinite(x):
        return "-"
    slack = ", slack" if row.get("slack") else ""
    if x <= 0.0:
        return "0" + slack
    return f"{100.0 * x:.3g} % {row.get('worst_limit') or ''}{slack}".strip()


def format_compare(cases: Sequence[dict[str, Any]]) -> str:
    """One table per case: the methods' time to depth, the optimum's saving against each,
    the forward check's worst limit excess, then the OCP's sizes and times.

    Parameters
    ----------
    cases : sequence of dict
        :func:`cable_ocp.bench.deployment.compare_case`'s results.
    """
    blocks = []
    for c in cases:
        o = c["ocp"]
        head = (f"{c['case']}: {c['start_length_m']:g} -> {c['target_length_m']:g} m, motion "
                + ", ".join(c["motions"]) + " (saving: of the optimum against the row; "
                "excess: the worst limit excess on the forward simulator, relative)")
        rows = [[r["method"], r["status"], r["duration_s"], _pct(r["saving_pct"]),
                 r["speed_m_s"], r["binding"], _excess(r), r.get("note", "")]
                for r in c["rows"]]
        tab = table(["method", "status", "time to depth", "saving", "speed", "binding",
                     "forward excess", "note"], rows,
                    units=["", "", "[s]", "", "[m/s]", "", "", ""], left=1)
        it = o.get("iterations")
        tail = (f"OCP: {o['status']} ({o['message']}); {o.get('steps')} steps, "
                f"{o.get('elements')} elements, {o.get('variables')} variables, "
                f"{o.get('constraints')} constraints; warm start "
                f"{_s(o.get('warm_start_s'))}, build {_s(o.get('build_s'))}, solve "
                f"{_s(o.get('solve_s'))} ({it} iterations)")
        starts = o.get("starts") or []
        if len(starts) > 1:
            tail += f"; kept the start from the {o.get('start')}, of " + "; ".join(
                f"the {st['start']} ({st['speed_m_s']:.4g} m/s): {st['status']}, "
                f"{st['duration_s']:.6g} s, {st['iterations']} iterations, "
                f"{_s(st['solve_time_s'])}" for st in starts)
        for i, rd in enumerate(o.get("rounds") or []):
            worst = max(rd["violations"].items(), key=lambda kv: kv[1], default=("", 0.0))
            tail += (f"\ncheck round {i}: {rd['status']} at {rd['duration_s']:.6g} s"
                     + (f" (re-solved in {_s(rd['resolve_s'])})" if rd.get("resolve_s")
                        else "")
                     + ", margins " + (", ".join(f"{k} {v:.4g}" for k, v in
                                                 rd["margins"].items()) or "none")
                     + f"; re-simulated, worst excess {100 * worst[1]:.3g} % {worst[0]}")
        hv = c.get("heave")
        if hv is not None:
            lim = hv["limits"]
            tail += (f"\ntoday's deployment ({hv['file']}): {hv['payout_speed_m_s']:g} m/s, "
                     f"{hv['ramp_time_s']:g} s ramps, {hv['duration_s']:.4g} s of pay-out; "
                     f"its limits: tension_min {lim['tension_min_N']} N (the MPC's soft "
                     f"limit), no tension_max; the compensator's speed "
                     f"{lim['compensator_speed_max_m_s']} m/s and stroke "
                     f"{lim['compensator_stroke_max_m']} m")
        blocks.append(head + "\n" + tab + "\n" + tail)
    return "\n\n".join(blocks)


def _s(x: Any) -> str:
    return "-" if x is None or not math.isfinite(x) else f"{x:.3g} s"


def format_cost(cost: dict[str, Any]) -> str:
    """The cost grid and its fitted exponents.

    Parameters
    ----------
    cost : dict
        ``{"rows": cost_grid(...), "fits": cost_fits(rows), "file", "speed_m_s"}``.
    """
    rows = [[r["duration_target_s"], r["distance_m"], r["segments"], r["status"],
             r.get("duration_s"), _pct(r.get("saving_pct")), r.get("steps"),
             r.get("variables"), r.get("iterations"), r.get("build_s"), r.get("solve_s")]
            for r in cost["rows"]]
    tab = table(["duration", "distance", "elements", "status", "optimum", "saving", "steps",
                 "variables", "iterations", "build", "solve"], rows,
                units=["[s]", "[m]", "", "", "[s]", "", "", "", "", "[s]", "[s]"], width=140)
    lines = [f"cost on {cost['file']} (speed_max {cost['speed_m_s']:g} m/s; the distance "
             "makes the warm start last the duration)", tab]
    for key, what in (("duration", "the duration"), ("segments", "the elements")):
        f = cost["fits"].get(key)
        if not f:
            continue
        at = (f"at {int(f['at_segments'])} elements" if key == "duration"
              else f"at {f['at_duration_s']:g} s")
        lines.append(f"growth with {what} ({at}), exponent p of c x^p: build "
                     f"{_p(f['build_s'])}, solve {_p(f['solve_s'])}, iterations "
                     f"{_p(f['iterations'])}, variables {_p(f['variables'])}")
    return "\n".join(lines)


def _p(x: float) -> str:
    return "-" if not math.isfinite(x) else f"{x:.2f}"


def format_long(row: dict[str, Any]) -> str:
    """The long run's line.

    Parameters
    ----------
    row : dict
        :func:`cable_ocp.bench.deployment.long_run`'s result.
    """
    return (f"long: {row['file']}, {row['distance_m']:g} m at speed_max "
            f"{row['speed_max_m_s']:.4g} m/s, {row['segments']} elements, step "
            f"{row['time_step_s']:g} s: {row['status']} ({row['message']}); optimum "
            f"{row['duration_s']:.4g} s against the constant speed's "
            f"{row['warm_duration_s']:.4g} s (saving {_pct(row['saving_pct'])}); "
            f"{row['steps']} steps, {row['variables']} variables, {row['constraints']} "
            f"constraints; warm start {_s(row['warm_start_s'])}, build "
            f"{_s(row['build_s'])}, solve {_s(row['solve_s'])} ({row['iterations']} "
            f"iterations), wall {_s(row['wall_s'])}, peak memory "
            f"{row.get('peak_rss_bytes', math.nan) / 1e9:.2f} GB; nlpsol options "
            f"{row.get('ipopt') or 'the defaults'}; binding "
            + (", ".join(row["binding"]) or "none"))
