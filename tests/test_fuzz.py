"""Property-based fuzz of the command line: every shipped problem file, mutated.

Each case takes one shipped problem file (a glob per scene kind, with the command and the
cheap arguments of that kind, see :data:`TARGETS`), applies one or two mutations to its
keys (deleted keys, wrong types, sign flips, zero, NaN, +-inf, +-1e300, unicode strings,
tables replaced by scalars, arrays of the wrong length) or to its text (truncation, stray
bytes, unicode), and runs ``cable_ocp.cli.main([...])`` in-process with ``--json PATH
--quiet``. Three things are asserted on every case:

1. No traceback: no exception escapes ``main`` and the exit code is never 3.
2. The exit code matches the JSON: 0 <-> a success status, 1 <-> a non-success status with
   a message, 2 <-> no JSON written and exactly one stderr line that names a mutated key
   (or the file, for a mutation of its text).
3. Every ``"solved"`` statics result passes physics checks written here, independent of
   the solver (:func:`check_statics_physics`): the profile in the water column, the
   prescribed end coordinates, forces and tensions, and the force balance of the whole
   line (of the part off the seabed where contact is modelled) with this file's own drag
   law. ``"solved"`` heave and footprint results are checked for finite metrics and for
   their bounds.

CI replays the corpus of this fuzz (:func:`test_fuzz_corpus`, ``tests/fuzz_corpus.py``: the
fewest drawn cases that reach every line the whole draw reaches); the drawn run itself is
``CABLE_OCP_FUZZ=full python -m pytest tests/test_fuzz.py``.

The run is derandomised (Hypothesis ``derandomize=True``): the same code and command give
the same cases every time. (Hypothesis also draws, now and then, constants it finds in the
loaded project modules, so a change of the code, or running this file alone rather than in
the whole suite, gives another, equally fixed, set of cases.) The counts (cases, exit 0/1/2,
tracebacks) are printed (``pytest -s``) and written with every case and its outcome to
``fuzz_counts.json`` and ``cases.txt`` in pytest's temporary directory.
"""

from __future__ import annotations

import contextlib
import copy
import csv
import io
import json
import math
import os
import shutil
import tomllib
from collections import Counter
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cable_ocp.cli import main
from cable_ocp.physics.current import profile_velocity_np
from cable_ocp.scene import load_scene

ROOT = Path(__file__).resolve().parents[1]

#: (command, file globs, extra arguments). The extra arguments only lower the cost and
#: hide no check: ``solver.refine=false`` keeps the error estimate (so "inaccurate" is still
#: reported when it exceeds solver.accuracy) but skips the mesh doublings; the heave and
#: dynamics runs are 2 s long (every controller or model is still built and run; the status
#: rules do not depend on the duration); the footprint takes 3 directions. The heave scenes
#: on a cable also shorten the identification experiment to 30 s (its multi-sine needs
#: harmonics of 2 pi / 10 s inside the band) and lower the unit at 10 m/s.
#: A new scene kind adds one line here; a file matched by two lines of one command takes the
#: first.
TARGETS: list[tuple[str, tuple[str, ...], tuple[str, ...]]] = [
    ("solve", ("problems/*.toml", "problems/extreme/*.toml"),
     ("--set", "solver.refine=false")),
    ("footprint", ("problems/footprint_*.toml",), ("--directions", "3")),
    ("heave", ("problems/heave/*_cable.toml",),
     ("--duration", "2", "--set", "simulation.warmup=0.5", "--set",
      "identification.duration=30")),
    ("heave", ("problems/heave/deployment_*.toml",),
     ("--set", "simulation.warmup=0.5", "--set", "identification.duration=30", "--set",
      "deployment.payout_speed=10")),
    ("heave", ("problems/heave/*.toml",),
     ("--duration", "2", "--set", "simulation.warmup=0.5")),
    ("simulate", ("problems/dynamics/*.toml",), ("--set", "simulation.duration=2")),
    ("modes", ("problems/dynamics/*.toml",), ()),
]

#: how often each command is drawn (per 24 cases): heave and footprint have a file or two
#: each but as many keys as the statics files together
WEIGHTS = {"solve": 12, "heave": 5, "footprint": 1, "simulate": 4, "modes": 2}

#: exit-0 statuses of each command (everything else exits 1)
SUCCESS = {"solve": {"solved"}, "footprint": {"solved"}, "heave": {"solved"},
           "simulate": {"solved"}, "modes": {"solved"}}

N_CASES = 330


def _files() -> list[tuple[str, Path, tuple[str, ...]]]:
    out, seen = [], set()
    for command, globs, extra in TARGETS:
        for pattern in globs:
            for path in sorted(ROOT.glob(pattern)):
                if (command, path) not in seen:
                    seen.add((command, path))
                    out.append((command, path, extra))
    return out


FILES = _files()


# --------------------------------------------------------------------------------------
# A small TOML writer (inline tables), enough for every mutated document
# --------------------------------------------------------------------------------------

def _toml_string(s: str) -> str:
    # json escapes quotes, backslashes and control characters the way TOML basic strings
    # accept them; DEL must be escaped too in TOML
    return json.dumps(s, ensure_ascii=False).replace("\x7f", "\\u007f")


def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return _toml_string(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{_toml_string(k)} = {_toml_value(x)}"
                               for k, x in v.items()) + "}"
    raise TypeError(type(v))


def toml_text(doc: dict[str, Any]) -> str:
    """``doc`` as TOML (one line per top-level key, inline tables below)."""
    return "".join(f"{_toml_string(k)} = {_toml_value(v)}\n" for k, v in doc.items())


# --------------------------------------------------------------------------------------
# Mutations
# --------------------------------------------------------------------------------------

def _paths(node: Any, prefix: tuple = ()) -> list[tuple]:
    """Every key path of a TOML document (tables, arrays and their elements)."""
    out = []
    if isinstance(node, dict):
        for k, v in node.items():
            out.append(prefix + (k,))
            out += _paths(v, prefix + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out.append(prefix + (i,))
            out += _paths(v, prefix + (i,))
    return out


def _get(doc: Any, path: tuple) -> Any:
    for p in path:
        doc = doc[p]
    return doc


#: replacement values: zero, signs, non-finite, huge and tiny (overflow), legal but extreme
#: (cost and conditioning), wrong types
BAD_VALUES = [0, 0.0, -1.0, math.nan, math.inf, -math.inf, 1e300, -1e300, 1e-300, 1e6, -1e6,
              1e-6, 20000, 5000, True, "x", "free", "inf", [], [1.0, 2.0], {}, {"x": 1.0},
              2**70]

mutation = st.one_of(
    st.tuples(st.just("delete")),
    st.tuples(st.just("value"), st.sampled_from(BAD_VALUES)),
    st.tuples(st.just("negate")),
    st.tuples(st.just("unicode"), st.text(min_size=0, max_size=8)),
    st.tuples(st.just("scalar"), st.sampled_from([1.5, "table", True, 7])),
    st.tuples(st.just("length"), st.sampled_from(["drop", "append", "empty"])),
)
text_mutation = st.one_of(
    st.tuples(st.just("truncate"), st.floats(0.0, 1.0)),
    st.tuples(st.just("bytes"), st.floats(0.0, 1.0), st.binary(min_size=1, max_size=4)),
    st.tuples(st.just("insert"), st.floats(0.0, 1.0), st.text(min_size=1, max_size=6)),
)


def mutate(doc: dict, path: tuple, mut: tuple) -> None:
    """Apply one key mutation in place."""
    parent, key = _get(doc, path[:-1]), path[-1]
    old = parent[key]
    kind = mut[0]
    if kind == "delete":
        del parent[key]
    elif kind == "value":
        parent[key] = copy.deepcopy(mut[1])
    elif kind == "negate":
        if isinstance(old, bool) or not isinstance(old, (int, float)):
            parent[key] = -1.0
        else:
            parent[key] = -old if old != 0 else -1.0
    elif kind == "unicode":
        parent[key] = mut[1]
    elif kind == "scalar":
        parent[key] = mut[1]
    elif kind == "length":
        if not isinstance(old, list):
            parent[key] = [old]
        elif mut[1] == "drop":
            parent[key] = old[:-1]
        elif mut[1] == "append":
            parent[key] = old + [old[-1] if old else 1.0]
        else:
            parent[key] = []


@st.composite
def cases(draw: Any) -> dict[str, Any]:
    command = draw(st.sampled_from([c for c, n in WEIGHTS.items() for _ in range(n)]))
    command, path, extra = draw(st.sampled_from([f for f in FILES if f[0] == command]))
    text = path.read_text(encoding="utf-8")
    if draw(st.integers(0, 4)) == 0:  # one case in five mutates the text
        tm = draw(text_mutation)
        raw = text.encode("utf-8")
        cut = int(tm[1] * len(raw))
        if tm[0] == "truncate":
            data = raw[:cut]
        elif tm[0] == "bytes":
            data = raw[:cut] + tm[2] + raw[cut:]
        else:
            data = raw[:cut] + tm[2].encode("utf-8") + raw[cut:]
        return {"command": command, "file": path, "extra": extra, "bytes": data,
                "mutated": [], "what": f"text {tm[0]} at byte {cut}"}
    doc = tomllib.loads(text)
    mutated = []
    for _ in range(draw(st.integers(1, 2))):
        paths = _paths(doc)
        if not paths:
            break
        # numbers are most of what can go wrong: half of the picks are numeric leaves
        numeric = [q for q in paths if isinstance(_get(doc, q), (int, float))]
        p = draw(st.sampled_from(numeric if numeric and draw(st.booleans()) else paths))
        m = draw(mutation)
        mutate(doc, p, m)
        mutated.append((p, m))
    return {"command": command, "file": path, "extra": extra,
            "bytes": toml_text(doc).encode("utf-8"), "mutated": mutated,
            "what": "; ".join(f"{'.'.join(map(str, p))}: {m!r}" for p, m in mutated)}


# --------------------------------------------------------------------------------------
# Independent physics of a statics answer
# --------------------------------------------------------------------------------------

def current_at(scene: Any, z: np.ndarray) -> np.ndarray:
    """Current velocity (m/s) at heights z: components linear between knots, constant
    beyond (docs/conventions.md, "Frame and scene files"; the one profile law,
    cable_ocp.physics.current, is tested on its own in tests/test_physics_laws.py)."""
    cur = scene.environment.current
    if cur is None:
        return np.zeros((len(z), 3))
    return profile_velocity_np(z, cur.z, cur.ux, cur.uy)


def drag(law: str, rho: float, d: float, cn: float, ct: float, u: np.ndarray,
         t: np.ndarray, blend: float) -> tuple[np.ndarray, np.ndarray]:
    """Drag per unit stretched length (N/m) by the laws of docs/conventions.md "Drag", and a bound
    (N/m) on how far the solver's vertical blend of the componentwise law may lie from it.

    vector:        1/2 rho (C_n D |U_n| U_n + C_t pi D |U_t| U_t)
    componentwise: normal flow split on e_b = e_z x t/|e_z x t|, e_n = t x e_b, each
                   component squared with its sign.
    """
    ut = np.sum(u * t, axis=1)
    un = u - ut[:, None] * t
    unorm = np.linalg.norm(un, axis=1)
    f_t = 0.5 * rho * ct * math.pi * d * (np.abs(ut) * ut)[:, None] * t
    f_vec = 0.5 * rho * cn * d * unorm[:, None] * un
    blend_bound = np.zeros(len(t))
    if law == "vector":
        return f_vec + f_t, blend_bound
    b = np.stack([-t[:, 1], t[:, 0], np.zeros(len(t))], axis=1)
    sig = np.linalg.norm(b, axis=1)
    safe = np.where(sig > 0, sig, 1.0)
    eb = b / safe[:, None]
    en = np.cross(t, eb)
    ub = np.sum(u * eb, axis=1)
    unn = np.sum(u * en, axis=1)
    f_comp = 0.5 * rho * cn * d * ((np.abs(ub) * ub)[:, None] * eb
                                   + (np.abs(unn) * unn)[:, None] * en)
    near = sig < blend  # the solver blends into the vector law here
    f_n = np.where(near[:, None], f_vec, f_comp)
    # both normal laws have magnitude <= 1/2 rho C_n D |U_n|^2
    blend_bound[near] = 2 * 0.5 * rho * cn * d * unorm[near] ** 2
    return f_n + f_t, blend_bound


def trapezoid(y: np.ndarray, x: np.ndarray) -> np.ndarray:
    return np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(x)[:, None], axis=0)


def trapezoid_error_bound(f: np.ndarray, x: np.ndarray) -> float:
    """Bound on the trapezoid's error, sum of h_i^3 / 12 max|f''| over the intervals, with
    |f''| on each interval taken as the largest second divided difference of the nodes
    around it (a kink of the |u| u drag contributes its jump of f' times h^2 / 12)."""
    h = np.diff(x)
    if len(x) < 3:
        return 0.0
    slope = np.diff(f, axis=0) / np.maximum(h, 1e-300)[:, None]
    f2 = np.linalg.norm(2 * np.diff(slope, axis=0)
                        / np.maximum(h[1:] + h[:-1], 1e-300)[:, None], axis=1)
    # interval i has the nodes i, i + 1; second differences live at nodes 1..n-2
    at_node = np.concatenate([[f2[0]], f2, [f2[-1]]])
    per_interval = np.maximum(at_node[:-1], at_node[1:])
    wide = np.maximum(per_interval, np.concatenate([per_interval[1:], [0.0]]))
    wide = np.maximum(wide, np.concatenate([[0.0], per_interval[:-1]]))
    return float(np.sum(h**3 / 12.0 * wide))


def read_csv(path: Path) -> np.ndarray:
    with path.open(encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    return np.array([[float(v) for v in r] for r in rows[1:]])


#: largest |T/|T| - t| seen (t by second-order finite differences of the returned nodes)
TANGENT_DEV: list[float] = []
#: the tension of a flexible segment is tangent to it: 1e-2 (0.6 deg) is 10x the largest
#: finite-difference error of the tangent on the shipped scenes (1e-3, drag_dominated on 40
#: intervals), and far below a wrong direction
TANGENT_TOL = 1e-2


def check_statics_physics(scene: Any, data: dict, table: np.ndarray) -> dict[str, float]:
    """Assert the solver-independent physics of a "solved" statics answer.

    Returns the force-balance residual and its tolerance (N) for the record.

    Tolerances and why:

    * water column: 1e-6 L (the same relative tolerance the solver states for its own
      check) plus the reported position error estimate;
    * fixed end coordinates: 1e-7 L + 1e-9 m plus the position error estimate (a boundary
      condition is an equation of the discrete system, solved to ~1e-10 scaled);
    * prescribed end forces and tensions: 1e-7 of the largest tension (same reason);
    * the tension of a flexible segment tangent to its profile: :data:`TANGENT_TOL`;
    * force balance (end forces + integral of weight, drag and point loads = 0), with the
      drag from this file's own laws at the returned nodes (tangent T/|T| on flexible
      segments, finite differences elsewhere), within
        - the reported end-force error estimate (the error of the discrete solution),
        - plus the trapezoid's own quadrature error on the returned nodes, bounded by the
          classical sum of h^3/12 max|f''| with |f''| from the neighbouring second divided
          differences (a |u| u kink contributes its jump of f' times h^2/12), times 2: the
          divided differences give f'' to first order only, and where f'' hardly changes
          the bound is tight (the shipped scenes use up to 0.8 of it without the 2);
        - plus the solver's modulus smoothing, |sqrt(u^2 + delta^2) u - |u| u| <= delta^2/2
          per squared component, over the stretched length,
        - plus the componentwise law's vertical blend, at most 2 x 1/2 rho C_n D |U_n|^2
          per metre where the cable is within asin(vertical_blend) of vertical,
        - plus 1e-9 of the forces involved (rounding).
    """
    env = scene.environment
    prof = data["profile"]
    s = np.asarray(prof["s"])
    pos = np.column_stack([prof["x"], prof["y"], prof["z"]])
    length = float(data["length"])
    scale = max(float(data["max_tension"]), 1e-9)
    solver = data["solver"]
    est = solver.get("error_estimate") or 0.0
    est_pos = solver.get("error_estimate_position_m") or est * length
    est_force = solver.get("error_estimate_force_N") or est * scale
    assert np.all(np.isfinite(pos)) and np.all(np.isfinite(s))
    assert abs(s[-1] - length) <= 1e-9 * max(length, 1.0)

    # 1. in the water column
    tol_z = 1e-6 * max(length, 1.0) + est_pos
    assert pos[:, 2].max() <= env.water_depth + tol_z, "above the surface"
    sb = env.seabed
    if sb is None:
        floor = np.zeros(len(pos))
    else:
        slope = math.tan(math.radians(sb.slope_deg))
        h = math.radians(sb.slope_heading_deg)
        floor = sb.depth_offset + slope * (pos[:, 0] * math.cos(h) + pos[:, 1] * math.sin(h))
    assert np.all(pos[:, 2] >= floor - tol_z), "below the seabed"

    # 2. ends as prescribed
    tol_p = 1e-7 * max(length, 1.0) + 1e-9 + est_pos
    tol_f = 1e-7 * scale + 1e-9
    for name, end in (("end_a", scene.end_a), ("end_b", scene.end_b)):
        got_p = np.asarray(data[name]["position"])
        got_f = np.asarray(data[name]["force"])
        for i in range(3):
            if end.position[i] is not None:
                assert abs(got_p[i] - end.position[i]) <= tol_p, (name, "position", i)
            else:  # the JSON force is the cable's pull on the attachment: minus the load
                assert abs(got_f[i] + end.force[i]) <= tol_f + est_force, (name, "force", i)
        if end.tension is not None:
            assert abs(np.linalg.norm(got_f) - end.tension) <= tol_f, (name, "tension")

    # 3. force balance on the line off the seabed
    start = 0
    td = data.get("touchdown")
    if sb is not None and td and td.get("grounded_length"):
        # contact is modelled: the grounded part (which must lie on the seabed) carries
        # no current load (docs/conventions.md "Seabed") and its horizontal tension changes by at
        # most the friction, mu w per metre; the balance starts at the touchdown node
        start = int(np.argmin(np.abs(s - td["grounded_length"])))
        assert np.all(pos[:start + 1, 2] - floor[:start + 1] <= tol_z), "grounded part"
        assert table.shape[0] == len(s)
        t_start = table[start, 4:7]
        w0 = scene.lines[0].weight_in_water
        dh = np.linalg.norm(t_start[:2] - np.asarray(data["end_a"]["force"])[:2])
        assert dh <= sb.friction * abs(w0) * s[start] * (1 + 1e-6) + 1e-7 * scale, "friction"
    else:
        t_start = np.asarray(data["end_a"]["force"])  # T(0) = force on the end_a attachment
    s_, p_ = s[start:], pos[start:]
    bounds = np.concatenate([[0.0], np.cumsum([c.length if c.length is not None else length
                                               for c in scene.lines])])
    weight = np.zeros(3)
    fd, quad, extra = np.zeros(3), 0.0, 0.0
    for c, a, b in zip(scene.lines, bounds[:-1], bounds[1:], strict=True):
        a, b = max(a, s_[0]), min(b, s_[-1])
        if b <= a:
            continue
        # weight in water: per unstretched length, piecewise constant: exact
        weight[2] -= c.weight_in_water * (b - a)
        if env.current is None or not (c.normal_drag or c.tangential_drag):
            continue
        eps = 1e-9 * max(length, 1.0)
        sel = (s_ >= a - eps) & (s_ <= b + eps)
        uniq = np.concatenate([[True], np.diff(s_[sel]) > 0])
        pts = p_[sel][uniq]
        if len(pts) < 3:
            continue
        # drag: per stretched length (docs/conventions.md "Drag"): integrated over |dr| of the
        # returned geometry, so no EA enters. Tangent: T/|T| where the segment is flexible
        # (its internal force is tangent), finite differences of the nodes elsewhere
        ell = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
        tan = np.gradient(pts, ell, axis=0, edge_order=2)
        tvec = table[start:][sel][uniq, 4:7] if table.size else np.zeros((len(pts), 3))
        tmag = np.linalg.norm(tvec, axis=1)
        flex = (c.bending_stiffness == 0.0) & (tmag > 1e-6 * scale)
        if len(scene.lines) > 1:  # at a joint the listed T is one side's (a body's load
            flex[[0, -1]] = False  # makes it jump): finite differences there
        tan /= np.maximum(np.linalg.norm(tan, axis=1), 1e-300)[:, None]
        if np.any(flex):  # the returned tension is tangent to the returned geometry
            t_dir = tvec[flex] / tmag[flex][:, None]
            TANGENT_DEV.append(float(np.max(np.linalg.norm(t_dir - tan[flex], axis=1))))
            assert TANGENT_DEV[-1] <= TANGENT_TOL, f"tension not tangent: {TANGENT_DEV[-1]:.2e}"
            tan[flex] = t_dir
        f, bb = drag(c.drag_law, env.water_density, c.diameter, c.normal_drag,
                     c.tangential_drag, current_at(scene, pts[:, 2]), tan,
                     scene.solver.vertical_blend)
        fd += trapezoid(f, ell)
        quad += 2.0 * trapezoid_error_bound(f, ell)
        # smoothing of |u| (delta^2 / 2 per squared component) and the vertical blend
        smooth = 0.5 * env.water_density * c.diameter * (
            c.normal_drag + math.pi * c.tangential_drag) * scene.solver.smoothing**2
        extra += smooth * ell[-1] + float(trapezoid(bb[:, None], ell)[0])
    point = np.zeros(3)
    for b in data.get("bodies", []) or []:
        body = scene.bodies[[x.joint for x in scene.bodies].index(b["joint"])]
        load = np.array(body.static_load, dtype=float)
        if body.has_drag:
            ub = current_at(scene, np.array([b["position"][2]]))[0]
            load += 0.5 * env.water_density * body.drag_coefficient * body.drag_area * \
                np.linalg.norm(ub) * ub
        point += load
    t_end = -np.asarray(data["end_b"]["force"])  # T(L)
    residual = t_end - t_start + weight + fd + point
    tol = (est_force + quad + extra
           + 1e-9 * (scale + abs(weight[2]) + float(np.linalg.norm(fd))) + 1e-9)
    res = float(np.linalg.norm(residual))
    assert res <= tol, f"force balance residual {res:.3e} N > tolerance {tol:.3e} N"
    return {"residual_N": res, "tolerance_N": tol, "quadrature_N": quad,
            "estimate_N": est_force}


# --------------------------------------------------------------------------------------
# The property
# --------------------------------------------------------------------------------------

def _strict_json(text: str) -> dict:
    def bad(token: str) -> Any:
        raise AssertionError(f"non-strict JSON token {token}")

    return json.loads(text, parse_constant=bad)


def _names_a_key(line: str, case: dict) -> bool:
    """The one error line names a mutated key (any part of its dotted path) or, for a
    mutation of the text, the file or one of the keys of the original file."""
    if case["mutated"]:
        words = {str(p) for path, _ in case["mutated"] for p in path if isinstance(p, str)}
    else:
        words = {str(case["src"])} | {str(p) for path in _paths(tomllib.loads(
            case["file"].read_text(encoding="utf-8"))) for p in path if isinstance(p, str)}
    return any(w in line for w in words)


def run_case(case: dict, work: Path, counts: Counter, balance: list) -> tuple[int, list[str]]:
    counts["cases"] += 1
    n = counts["cases"]
    src = work / f"case{n}.toml"
    src.write_bytes(case["bytes"])
    case["src"] = src
    jpath, cpath = work / f"case{n}.json", work / f"case{n}.csv"
    argv = [case["command"], str(src), *case["extra"], "--json", str(jpath), "--quiet"]
    if case["command"] == "solve":
        argv += ["--csv", str(cpath)]
    err, sink = io.StringIO(), io.StringIO()
    try:
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(sink):
            rc = main(argv)
    except BaseException as exc:  # noqa: BLE001 - the property: nothing escapes main
        counts["tracebacks"] += 1
        raise AssertionError(f"{type(exc).__name__} escaped main on {case['what']}") from exc
    lines = [ln for ln in err.getvalue().splitlines() if ln.strip()]
    what = f"{case['command']} {case['file'].name} [{case['what']}] -> rc {rc}: {lines}"
    if rc == 3:
        counts["tracebacks"] += 1
    assert rc in (0, 1, 2), what
    counts[f"exit_{rc}"] += 1
    if rc == 2:
        assert not jpath.exists(), what
        assert len(lines) == 1 and lines[0].startswith("cable-ocp: error: "), what
        assert _names_a_key(lines[0], case), what
        return rc, lines
    data = _strict_json(jpath.read_text(encoding="utf-8"))
    assert {"status", "message", "warnings", "version"} <= set(data), what
    assert isinstance(data["warnings"], list)
    ok = data["status"] in SUCCESS[case["command"]]
    assert ok == (rc == 0), what + f" status {data['status']}"
    if rc == 1:
        assert data["message"], what
        counts[f"status_{data['status']}"] += 1
        return rc, lines
    if case["command"] == "solve":
        scene = load_scene(src, {"solver.refine": False})
        balance.append(check_statics_physics(scene, data, read_csv(cpath)))
    elif case["command"] == "heave":
        for name, ctrl in data["controllers"].items():
            assert ctrl["status"] == "solved", (what, name)
            for key in ("heave_rms", "reduction_pct", "peak_winch_speed", "max_stroke",
                        "max_constraint_violation", "winch_speed_rms"):
                assert isinstance(ctrl[key], (int, float)) and math.isfinite(ctrl[key]), \
                    (what, name, key)
    elif case["command"] == "simulate":
        # a solved run: every sample of the time series is a number
        for key in ("t", "length", "top_tension"):
            assert all(isinstance(v, (int, float)) for v in data[key]), (what, key)
    elif case["command"] == "footprint":
        scene = load_scene(src)
        fp = scene.footprint
        for row in data["directions"]:
            assert row["status"] == "solved"
            assert fp.min_length * (1 - 1e-6) <= row["length"] <= fp.max_length * (1 + 1e-6)
            if fp.bound == "magnitude":
                assert math.hypot(row["thrust_x"], row["thrust_y"]) <= fp.thrust_max * (
                    1 + 1e-6) + 1e-6
    return rc, lines


def test_fuzz_corpus(tmp_path_factory: Any) -> None:
    """The corpus of the long fuzz (``tests/fuzz_corpus.py``: the drawn cases that together
    reach every line of cable_ocp the 330 drawn cases reach), replayed with the same
    checks: no traceback, exit code and JSON status agree, the error line names the key,
    every solved statics answer passes the independent physics."""
    from fuzz_corpus import load

    base = tmp_path_factory.mktemp("fuzz_corpus")
    work = base / "cases"
    work.mkdir()
    shutil.copytree(ROOT / "problems" / "dynamics", base / "dynamics")
    counts: Counter = Counter()
    balance: list[dict[str, float]] = []
    corpus = load()
    for case in corpus:
        run_case(case, work, counts, balance)
    assert counts["cases"] == len(corpus) > 0 and counts["tracebacks"] == 0
    # the corpus holds every outcome: clean errors, honest failures and checked solutions
    assert counts["exit_0"] and counts["exit_1"] and counts["exit_2"] and balance


@pytest.mark.slow
@pytest.mark.skipif(os.environ.get("CABLE_OCP_FUZZ") != "full",
                    reason="the long drawn fuzz (330 cases, ~2.5 min): CABLE_OCP_FUZZ=full; CI "
                           "replays its corpus (test_fuzz_corpus)")
def test_fuzz_every_shipped_problem(tmp_path_factory: Any) -> None:
    """At least 300 mutated problem files through the CLI: no traceback, exit code and
    JSON status agree, every solved statics answer passes the independent physics."""
    base = tmp_path_factory.mktemp("fuzz")
    work = base / "cases"
    work.mkdir()
    # the heave scenes on a cable name their line relative to the file: ../dynamics/...
    shutil.copytree(ROOT / "problems" / "dynamics", base / "dynamics")
    counts: Counter = Counter()
    balance: list[dict[str, float]] = []

    log = (work / "cases.txt").open("w", encoding="utf-8")

    @settings(max_examples=N_CASES, derandomize=True, deadline=None, database=None,
              suppress_health_check=list(HealthCheck), print_blob=True)
    @given(case=cases())
    def run(case: dict) -> None:
        rc, lines = run_case(case, work, counts, balance)
        log.write(f"{case['command']} {case['file'].name} [{case['what']}] -> {rc} "
                  f"{lines[:1]}\n")

    run()
    log.close()
    worst = max((b["residual_N"] / b["tolerance_N"] for b in balance), default=0.0)
    summary = {"cases": counts["cases"], "exit_0_solved": counts["exit_0"],
               "exit_1_honest_failure": counts["exit_1"], "exit_2_clean_error": counts["exit_2"],
               "tracebacks": counts["tracebacks"],
               "statuses_exit_1": {k[7:]: v for k, v in counts.items()
                                   if k.startswith("status_")},
               "force_balance_checked": len(balance),
               "worst_residual_over_tolerance": worst,
               "worst_tangent_deviation": max(TANGENT_DEV, default=0.0)}
    (work / "fuzz_counts.json").write_text(json.dumps(summary, indent=2))
    print("\nfuzz counts:", json.dumps(summary))
    assert counts["tracebacks"] == 0
    assert counts["cases"] >= 300


def test_physics_checks_catch_wrong_answers(tmp_path: Path) -> None:
    """The checks above pass on a solved answer and fail on slightly wrong ones: an end force
    off by 1e-4 of the largest tension, the vector drag law where the scene says
    componentwise (2 % apart in 3D), a node below the seabed, an end moved by 1 mm."""
    src = ROOT / "problems" / "dezoysa_sea_buggy.toml"
    jpath, cpath = tmp_path / "d.json", tmp_path / "d.csv"
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["solve", str(src), "--json", str(jpath), "--csv", str(cpath),
                     "--quiet"]) == 0
    scene = load_scene(src)
    data, table = json.loads(jpath.read_text()), read_csv(cpath)
    check_statics_physics(scene, data, table)

    def fails(d: dict, sc: Any = scene) -> None:
        try:
            check_statics_physics(sc, d, table)
        except AssertionError:
            return
        raise AssertionError("a wrong answer passed the physics checks")

    bad = copy.deepcopy(data)
    bad["end_a"]["force"][0] += 1e-4 * data["max_tension"]
    fails(bad)
    fails(data, load_scene(src, {"cable.drag_law": "vector"}))
    bad = copy.deepcopy(data)
    bad["profile"]["z"][len(bad["profile"]["z"]) // 2] = -0.01
    fails(bad)
    bad = copy.deepcopy(data)
    bad["end_b"]["position"][1] += 1e-3
    fails(bad)
