"""Plain-text tables and JSON for statics solutions (the CLI prints what these return)."""

from __future__ import annotations

import json
from collections.abc import Sequence
from typing import Any

import numpy as np

from cable_ocp.statics.solution import StaticsSolution


def _vec(v: np.ndarray, unit: str) -> str:
    return "(" + ", ".join(f"{x:12.4f}" for x in v) + f") {unit}"


def _mesh(m: dict | None) -> str:
    if not m:
        return ""
    return (f" ({m['scheme']} degree {m['degree']}, {m['intervals']} intervals, "
            f"order {m['order']})")


def statics_summary(sol: StaticsSolution, title: str = "") -> str:
    """Summary table of one solve: length, end forces, max tension, solver diagnostics."""
    d = sol.diagnostics
    est = d.get("error_estimate_detail", {})
    rows = [
        ("status", f"{sol.status}: {sol.message}"),
        ("length L", f"{sol.length:.6f} m"),
        ("end_a position", _vec(sol.position[0], "m")),
        ("end_a force (cable on attachment)", _vec(sol.force_a, "N")),
        ("end_b position", _vec(sol.position[-1], "m")),
        ("end_b force (cable on attachment)", _vec(sol.force_b, "N")),
        ("max tension", f"{sol.max_tension:.4f} N"),
        ("solver", f"{d.get('method')}{_mesh(d.get('mesh'))} via {d.get('solver')}"),
        ("start", str(d.get("start"))),
        ("iterations", str(sol.iterations)),
        ("wall time (solve)", f"{sol.wall_time_s * 1e3:.2f} ms"),
        ("build time", f"{d.get('build_time_s', float('nan')) * 1e3:.1f} ms"),
        ("max scaled residual", f"{sol.constraint_violation:.2e}"),
        ("error estimate (relative)", "n/a" if sol.error_estimate is None
         else f"{sol.error_estimate:.2e}  ({est.get('force_N', 0):.2e} N, "
              f"{est.get('position_m', 0):.2e} m; {est.get('method', '')})"),
        ("smoothing bound on drag", f"{d.get('smoothing_force_bound_N', 0):.2e} N over the cable"),
    ]
    td = d.get("touchdown")
    if td:
        rows.insert(6, ("touchdown (on the seabed)", _vec(np.asarray(td["position"]), "m")
                        + f", grounded length {td['grounded_length']:.4f} m"))
    for b in d.get("bodies") or []:
        rows.append((f"body at joint {b['joint']} ({b['kind']})",
                     _vec(np.asarray(b["position"]), "m") + "; load "
                     + _vec(np.asarray(b["force"]), "N")))
    if d.get("continuation"):
        rows.append(("continuation", str(d["continuation"])))
    for w in d.get("warnings", []):
        rows.append(("WARNING", w))
    width = max(len(k) for k, _ in rows)
    lines = [title] if title else []
    lines += [f"{k:<{width}}  {v}" for k, v in rows]
    return "\n".join(lines)


def table(headers: Sequence[str], rows: Sequence[Sequence[Any]]) -> str:
    """Fixed-width text table; floats are printed with 4 significant digits."""
    def fmt(v: Any) -> str:
        if isinstance(v, float):
            return f"{v:.4g}"
        return str(v)

    cells = [[fmt(v) for v in r] for r in rows]
    widths = [max(len(h), *(len(r[i]) for r in cells)) for i, h in enumerate(headers)]
    out = ["  ".join(h.rjust(w) for h, w in zip(headers, widths, strict=True))]
    out.append("  ".join("-" * w for w in widths))
    out += ["  ".join(c.rjust(w) for c, w in zip(r, widths, strict=True)) for r in cells]
    return "\n".join(out)


def to_json(obj: Any) -> str:
    """JSON text with NaN/inf written as null."""
    def clean(o: Any) -> Any:
        if isinstance(o, dict):
            return {k: clean(v) for k, v in o.items()}
        if isinstance(o, (list, tuple)):
            return [clean(v) for v in o]
        if isinstance(o, (float, np.floating)):
            return float(o) if np.isfinite(o) else None
        if isinstance(o, np.integer):
            return int(o)
        return o

    return json.dumps(clean(obj), indent=2)
