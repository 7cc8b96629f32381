"""Plain-text tables and JSON for statics solutions (the CLI prints what these return).

:func:`table` is :func:`cable_ocp.numerics.text_table.table`, the one table formatter.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from typing import Any

import numpy as np

from cable_ocp.numerics.text_table import MISSING, table
from cable_ocp.statics.solution import StaticsSolution

__all__ = ["statics_summary", "table", "to_json"]

#: decimals of each unit in the summary (one way for every row: value, space, unit)
_DECIMALS = {"m": 4, "N": 2, "deg": 3, "ms": 2}


def _fmt(v: Any, decimals: int) -> str:
    """Fixed-point number, ``-`` when missing (None, NaN, inf); no negative zero."""
    if v is None or not np.isfinite(v):
        return MISSING
    text = f"{float(v):.{decimals}f}"
    return text.lstrip("-") if float(text) == 0.0 else text


def _qty(v: Any, unit: str, decimals: int | None = None) -> str:
    """A scalar with its unit (``36.289 deg``, ``1579.90 N``), ``-`` when missing."""
    text = _fmt(v, _DECIMALS[unit] if decimals is None else decimals)
    return text if text == MISSING else f"{text} {unit}"


def _sci(v: Any, unit: str = "") -> str:
    """A small number in scientific notation, with its unit if any; ``-`` when missing."""
    if v is None or not np.isfinite(v):
        return MISSING
    return f"{float(v):.2e}" + (f" {unit}" if unit else "")


def _vec(v: Any, unit: str, decimals: int | None = None, width: int = 12) -> str:
    """A vector ``(x, y, z) unit``; missing components as ``-``."""
    d = _DECIMALS.get(unit, 4) if decimals is None else decimals
    return "(" + ", ".join(f"{_fmt(x, d):>{width}}" for x in v) + f") {unit}"


def _mesh(m: dict | None) -> str:
    if not m:
        return ""
    if "scheme" not in m:  # the baselines: intervals (and solve_bvp's tolerance) only
        parts = [f"tol {m['tolerance']:.0e}"] if "tolerance" in m else []
        if "intervals" in m:
            parts.append(f"{m['intervals']} intervals")
        return f" ({', '.join(parts)})" if parts else ""
    return (f" ({m['scheme']} degree {m['degree']}, {m['intervals']} intervals, "
            f"order {m['order']})")


def _stiffness_rows(sol: StaticsSolution, end: str) -> list[tuple[str, str]]:
    """The 3x3 stiffness at one end, one row per force component, decimals chosen for
    four significant digits in the largest entry; or ``-`` and the reason."""
    k = sol.stiffness(end)
    if k is None:
        return [(f"end_{end} stiffness", f"{MISSING} ({sol.stiffness_note(end)})")]
    big = float(np.nanmax(np.abs(k))) if np.any(np.isfinite(k)) else 0.0
    # round-off level (e.g. a line that moves with a free end): zeros, not 15 decimals
    tiny = 1e-9 * sol.max_tension / max(sol.length, 1e-300)
    decimals = max(0, 3 - int(np.floor(np.log10(big)))) if big > tiny else 2
    width = max(len(_fmt(v, decimals)) for v in k.ravel())
    rows = [(f"end_{end} stiffness dF{c}/d(x, y, z)", _vec(k[i], "N/m", decimals, width))
            for i, c in enumerate("xyz")]
    rows.append((f"end_{end} stiffness holds", sol.stiffness_note(end)))
    return rows


def statics_summary(sol: StaticsSolution, title: str = "") -> str:
    """Summary table of one solve: length, grounded length, the ends (position, force,
    tension, angle, stiffness), max tension, solver diagnostics. Every value carries its
    unit; a missing value is ``-``.

    Parameters
    ----------
    sol : StaticsSolution
        The solve to summarise (a failed one too: its missing values print as ``-``).
    title : str
        First line of the text; empty (default): no title line.
    """
    d = sol.diagnostics
    est = d.get("error_estimate_detail", {})
    rows = [
        ("status", f"{sol.status}: {sol.message}"),
        ("length L", _qty(sol.length, "m")),
        ("grounded length", _qty(sol.grounded_length, "m")),
    ]
    for end in ("a", "b"):
        pos = sol.position[0 if end == "a" else -1]
        force = sol.force_a if end == "a" else sol.force_b
        rows += [
            (f"end_{end} position", _vec(pos, "m")),
            (f"end_{end} force (cable on attachment)", _vec(force, "N")),
            (f"end_{end} tension", _qty(sol.end_tension(end), "N")),
            (f"end_{end} angle to horizontal", _qty(sol.angle_to_horizontal_deg(end), "deg")),
        ]
        rows += _stiffness_rows(sol, end)
    if sol.stiffness("a") is not None or sol.stiffness("b") is not None:
        rows.append(("stiffness convention",
                     "K[i][j] = dF_i/dx_j, F the force on the attachment, x its position: "
                     "a restoring line has a negative diagonal (MoorPy's matrices are -K)"))
    td = d.get("touchdown")
    if td:
        rows.append(("touchdown (on the seabed)", _vec(np.asarray(td["position"]), "m")))
    build = d.get("build_time_s")
    rows += [
        ("max tension", _qty(sol.max_tension, "N")),
        ("solver", f"{d.get('method', MISSING)}{_mesh(d.get('mesh'))}"
                   + (f" via {d['solver']}" if d.get("solver") else "")),
        ("start", str(d.get("start", MISSING))),
        ("iterations", str(sol.iterations)),
        ("wall time (solve)", _qty(sol.wall_time_s * 1e3, "ms")),
        ("build time", _qty(None if build is None else build * 1e3, "ms")),
        ("max scaled residual", _sci(sol.constraint_violation, "(scaled, -)")),
        ("error estimate (relative)", _sci(sol.error_estimate, "(-)") + (
            f"  ({_sci(est.get('force_N'), 'N')}, {_sci(est.get('position_m'), 'm')}; "
            f"{est['method']})" if sol.error_estimate is not None and "method" in est
            else "")),
        ("smoothing bound on drag", _sci(d.get("smoothing_force_bound_N"), "N")
         + (" over the cable" if d.get("smoothing_force_bound_N") is not None else "")),
    ]
    mesh = d.get("mesh") or {}
    if mesh.get("kind") == "kinks":
        # mesh points on the drag's kinks (where a relative-flow component changes sign)
        found = mesh.get("kinks_s")
        rows.append(("mesh points on the drag's kinks", "at s = " + ", ".join(
            _fmt(v, 3) for v in found) + " m" if found else "kept from the warm start"))
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


#: SI prefixes for engineering notation of forces (N -> kN, MN, GN)
_PREFIXED = {"N": ((1e9, "G"), (1e6, "M"), (1e3, "k"))}


def quantity(value: Any, unit: str) -> str:
    """A value with its unit, 4 significant digits, forces with an SI prefix
    (``4347.1, "N"`` -> ``4.347 kN``); a dimensionless ``-`` unit is left out; ``-`` when
    missing.

    Parameters
    ----------
    value : float or other
        The number (a string or bool is printed as is).
    unit : str
        Its unit, e.g. ``"N"``, ``"m/s"``, ``"-"``.
    """
    if isinstance(value, (bool, str)) or value is None:
        return MISSING if value is None else str(value)
    v = float(value)
    if not np.isfinite(v):
        return MISSING
    for scale, prefix in _PREFIXED.get(unit, ()):
        if abs(v) >= scale:
            v, unit = v / scale, prefix + unit
            break
    text = f"{v:.4g}"
    if text.startswith("-") and float(text) == 0.0:  # a rounded -1e-13: no "-0"
        text = text[1:]
    return text if unit in ("", "-") else f"{text} {unit}"


def _split(col: str) -> tuple[str, str]:
    """``name [unit]`` -> (name, unit)."""
    if col.endswith("]") and " [" in col:
        name, unit = col[:-1].split(" [", 1)
        return name, unit
    return col, ""


def extreme_sentence(col: str, e: dict[str, Any], which: str = "max") -> str:
    """One extreme as a sentence: ``largest max_tension 6.021 kN at
    environment.current.speed = 1 m/s, layout.psi0_deg = 90 deg (case 7)``.

    Parameters
    ----------
    col : str
        The output column, ``name [unit]``.
    e : dict
        Its extremes (:func:`cable_ocp.batch.summary.extremes`).
    which : str
        ``"max"`` (default) or ``"min"``.
    """
    name, unit = _split(col)
    at = ", ".join(f"{k} = {quantity(v, e['units'].get(k, ''))}"
                   for k, v in e[f"{which}_at"].items())
    word = "largest" if which == "max" else "smallest"
    return (f"{word} {name} {quantity(e[which], unit)}" + (f" at {at}" if at else "")
            + f" (case {e[f'{which}_case']})")


def batch_extremes(summary: dict[str, dict[str, Any]], headline: Sequence[str] = (),
                   width: int = 100) -> str:
    """The extremes of a batch (:func:`cable_ocp.batch.summary.extremes`) as text: the
    ``headline`` outputs as sentences naming the parameter values of the extreme cases
    (:func:`extreme_sentence`), then a table of every output's largest and smallest value
    with the swept keys' values of the case that gave each (headed by the keys' last parts
    when those are distinct, their units in a line above). A table wider than ``width``
    is split in two (largest, smallest); if those are still too wide, every output gets two
    sentences.

    Parameters
    ----------
    summary : dict
        Output column -> its extremes, as :func:`cable_ocp.batch.summary.extremes` gives.
    headline : sequence of str
        Outputs stated first as sentences (e.g. the kind's main output); default none.
    width : int
        Largest line width of the table (default 100).
    """
    import textwrap

    lines = []
    for col in headline:
        if col in summary:
            for which in ("max", "min"):
                lines += textwrap.wrap(extreme_sentence(col, summary[col], which), width,
                                       subsequent_indent="    ", break_on_hyphens=False)
    if not summary:
        return "\n".join(lines)
    units = next(iter(summary.values()))["units"]
    keys = list(units)
    short = [k.split(".")[-1] for k in keys]
    heads = short if len(set(short)) == len(short) else keys
    def build(parts: Sequence[tuple[str, str]]) -> str:
        headers = ["output"]
        for word, _ in parts:
            headers += [word, *heads, "case"]
        rows = []
        for col, e in summary.items():
            name, unit = _split(col)
            row = [name]
            for _, w in parts:
                row += [quantity(e[w], unit), *[quantity(e[f"{w}_at"][k], "") for k in keys],
                        str(e[f"{w}_case"])]
            rows.append(row)
        return table(headers, rows)

    at = ("at: " + ", ".join(f"{h} = {k} ({units[k] or '-'})"
                             for h, k in zip(heads, keys, strict=True))) if keys else ""
    both = build((("largest", "max"), ("smallest", "min")))
    tables = [both] if _fits(both, width) else [build((("largest", "max"),)),
                                                build((("smallest", "min"),))]
    if all(_fits(t, width) for t in tables):
        return "\n".join([*lines, *([at] if at else []), *tables])
    for col, e in summary.items():
        for which in ("max", "min"):
            lines += textwrap.wrap(extreme_sentence(col, e, which), width,
                                   subsequent_indent="    ", break_on_hyphens=False)
    return "\n".join(lines)


def _fits(text: str, width: int) -> bool:
    return max(len(line) for line in text.splitlines()) <= width


def system_summary(res: Any, title: str = "") -> str:
    """The text summary of a mooring system (:class:`cable_ocp.mooring.SystemResult`): the
    status, each body's pose and mooring load, the line table and each body's 6x6.

    Parameters
    ----------
    res : SystemResult
        The result.
    title : str
        Printed first when given.
    """
    lines = [title] if title else []
    lines.append(f"status: {res.status} ({res.message}); {len(res.lines)} lines, "
                 f"{res.wall_time_s:.3g} s")
    for b in res.bodies:
        held = f"; held: {', '.join(b['held'])}" if b["held"] else ""
        lines.append(f"body {b['name']}: position {_vec(b['position'], 'm', 3)}, rotation "
                     f"{_vec(b['rotation_deg'], 'deg', 4)}{held}")
        if "mooring_force" in b:
            lines.append(f"  mooring force {_vec(np.asarray(b['mooring_force']) / 1e3, 'kN', 2)}"
                         f", moment {_vec(np.asarray(b['mooring_moment']) / 1e3, 'kN m', 1)}")
    rows = []
    for ln in res.lines:
        anchor = ln.get("anchor_a") or ln.get("anchor_b")
        rows.append([ln["name"], ln["tension_a"] / 1e3, ln["tension_b"] / 1e3,
                     ln["max_tension"] / 1e3, ln["safety_factor"], ln["laid_length"],
                     anchor["horizontal"] / 1e3 if anchor else None,
                     anchor["vertical"] / 1e3 if anchor else None])
    if rows:
        lines.append("")
        lines.append(table(["line", "T_a", "T_b", "T_max", "SF", "laid", "anchor H",
                            "anchor V"], rows,
                           units=["", "[kN]", "[kN]", "[kN]", "[-]", "[m]", "[kN]", "[kN]"],
                           left=1))
    for b in res.bodies:
        st = b.get("stiffness")
        if st is None:
            continue
        k = np.asarray(st["mooring"])
        lines.append("")
        lines.append(f"mooring stiffness of {b['name']}, K = -d[F; M]/d[x; theta] (rows F, M "
                     "in N, N m;")
        lines.append("columns x in m, theta in rad: small rotations about the fixed axes):")
        names = ["x", "y", "z", "rx", "ry", "rz"]
        lines.append(table(["", *names], [[names[i], *[float(v) + 0.0 for v in k[i]]]
                                          for i in range(6)], left=1))
    return "\n".join(lines)
