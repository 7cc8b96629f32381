"""A steady current on one mooring line: our drag along the solved shape against MoorPy's.

What MoorPy 1.3.0 does (``moorpy/line.py``, ``Line.staticSolve``):

* lines 915-943: after each catenary solve it sums, over the ``nNodes - 1`` straight
  segments of the profile just solved, the independence-principle drag
  ``1/2 rho Cd d_vol ds |U_p| U_p + 1/2 rho CdAx pi d_vol ds |U_q| U_q`` (U_q the flow along
  the segment, U_p the rest; ``CdAx`` acts on pi d_vol, as our ``tangential_drag``) into one
  vector ``fCurrent``, *grounded segments included*;
* lines 785-805: the next solve spreads that total uniformly over the unstretched length,
  ``w_vec = fCurrent / L + (0, 0, -w)``, and solves the ordinary elastic catenary in a frame
  whose "down" is ``w_vec`` (``RotFrm2Vect``);
* lines 838-843: with a current and neither end on the seabed the seabed is put out of reach;
  with an end on it (lines 826-837) the seabed of the catenary is the plane normal to
  ``w_vec`` in the rotated frame, not the true one (its tilt changes the fairlead's height
  above it by the span times the tilt's tangent).

The current load is thus evaluated on the real shape (per segment), but smeared: MoorPy's
line carries the right total current force, but spread as if uniform. Ours
(:func:`cable_ocp.physics.drag.drag_per_length`, vector law) integrates the drag on the
solved shape with no smearing and no current load on the seabed (docs/conventions.md,
"Seabed"). Both agree exactly where the drag per length is uniform along the line: a
straight line whose load is along it (:func:`exact_rows`; a quadratic law with
``normal_drag == pi * tangential_drag`` is *not* isotropic, |U_n| U_n + |U_t| U_t differs
from |U| U, so a curved line never has a uniform load). Elsewhere the difference is the
smearing, bounded by :func:`smearing_bound`.

Functions return rows (dicts); ``moorpy`` is imported inside the functions that need it.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from cable_ocp.mooring import solve_system
from cable_ocp.physics.drag import line_drag_factors
from cable_ocp.scene.system import system_from_dict

#: water density (kg/m^3) and gravity (m/s^2) of every case (MoorPy's defaults' g)
RHO = 1025.0
G = 9.80665


def line_case(*, length: float, anchor: tuple[float, float, float],
              fairlead: tuple[float, float, float], depth: float, diameter: float,
              mass: float, axial_stiffness: float, normal_drag: float,
              tangential_drag: float, speed: float, heading_deg: float,
              intervals: int = 40) -> dict[str, Any]:
    """A one-line system (anchor and fairlead both fixed points) as a system dict.

    Parameters
    ----------
    length : float
        Unstretched length, m.
    anchor, fairlead : tuple of 3 float
        End positions, m (seabed z = 0).
    depth : float
        Water depth, m.
    diameter : float
        Volume-equivalent diameter, m.
    mass : float
        Mass per length in air, kg/m.
    axial_stiffness : float
        EA, N.
    normal_drag, tangential_drag : float
        C_dn on d and C_dt on pi d (-) (MoorPy's ``Cd`` and ``CdAx``, line.py:938-939).
    speed : float
        Uniform current speed, m/s.
    heading_deg : float
        Direction the current flows towards, deg from +x.
    intervals : int
        Collocation intervals.

    Returns
    -------
    dict
        The system dict (:func:`cable_ocp.scene.system.system_from_dict`).
    """
    return {
        "environment": {"water_depth": depth, "water_density": RHO, "gravity": G,
                        "current": {"speed": speed, "heading_deg": heading_deg},
                        "seabed": {"friction": 0.0}},
        "line_types": {"line": {"diameter": diameter, "mass_per_length": mass,
                                "axial_stiffness": axial_stiffness,
                                "normal_drag": normal_drag,
                                "tangential_drag": tangential_drag}},
        "points": [{"name": "anchor", "kind": "fixed", "position": list(anchor)},
                   {"name": "fairlead", "kind": "fixed", "position": list(fairlead)}],
        "lines": [{"name": "L", "point_a": "anchor", "point_b": "fairlead", "type": "line",
                   "length": length}],
        "solver": {"intervals": intervals},
    }


def ours(case: dict[str, Any]) -> dict[str, Any]:
    """Our end forces (collocation through :func:`cable_ocp.mooring.solve_system`).

    Parameters
    ----------
    case : dict
        A system dict from :func:`line_case`.

    Returns
    -------
    dict
        ``force_anchor``, ``force_fairlead`` (N, the force the line exerts on each point),
        ``laid_length`` (m), ``status``.
    """
    res = solve_system(system_from_dict(case))
    ln = res.line("L")
    return {"force_anchor": np.asarray(ln["force_a"], float),
            "force_fairlead": np.asarray(ln["force_b"], float),
            "laid_length": float(ln["laid_length"] or 0.0), "status": res.status}


def moorpy_forces(case: dict[str, Any], n_nodes: int = 400, sweeps: int = 200
                  ) -> dict[str, Any]:
    """MoorPy's end forces for the same case, its current fixed point iterated out.

    ``Line.staticSolve`` uses the ``fCurrent`` of its previous call (line.py:785-789,
    915-943); with both ends fixed there is no outer equilibrium to iterate it, so the
    solve is repeated until ``fCurrent`` stops changing (relative 1e-12).

    Parameters
    ----------
    case : dict
        A system dict from :func:`line_case`.
    n_nodes : int
        MoorPy's profile nodes (its current sum runs over n_nodes - 1 segments).
    sweeps : int
        Most repeated solves.

    Returns
    -------
    dict
        ``force_anchor``, ``force_fairlead`` (N, force of the line on each point),
        ``laid_length`` (m), ``f_current`` (N, MoorPy's total current force), ``sweeps``.
    """
    import moorpy as mp  # benchmark only

    env = case["environment"]
    depth = env["water_depth"]
    cur = env["current"]
    h = math.radians(cur["heading_deg"])
    lt_in = case["line_types"]["line"]
    d, m = lt_in["diameter"], lt_in["mass_per_length"]
    lt = {"name": "line", "d_vol": d, "d_nom": d, "m": m, "material": "chain",
          "w": (m - RHO * math.pi / 4.0 * d * d) * G, "EA": lt_in["axial_stiffness"],
          "Cd": lt_in["normal_drag"], "CdAx": lt_in["tangential_drag"], "MBL": 1e9}
    ms = mp.System(depth=depth, rho=RHO, g=G,
                   current=[cur["speed"] * math.cos(h), cur["speed"] * math.sin(h), 0.0])
    pts = {p["name"]: p for p in case["points"]}
    for name in ("anchor", "fairlead"):  # MoorPy: z = 0 at the surface
        ms.addPoint(1, np.asarray(pts[name]["position"], float) - [0.0, 0.0, depth])
    ms.addLine(case["lines"][0]["length"], lt, nSegs=n_nodes - 1)
    ms.pointList[0].attachLine(1, 0)
    ms.pointList[1].attachLine(1, 1)
    ms.initialize()
    line = ms.lineList[0]
    k = 0
    for k in range(1, sweeps + 1):  # noqa: B007 - reported
        before = line.fCurrent.copy()
        line.staticSolve(tol=1e-10)
        if np.max(np.abs(line.fCurrent - before)) <= 1e-12 * max(
                1.0, float(np.max(np.abs(line.fCurrent)))):
            break
    # the frame MoorPy solves in (line.py:786-802): "down" along w_vec
    w_vec = line.fCurrent / line.L + np.array([0.0, 0.0, -line.w])
    w_hat = w_vec / np.linalg.norm(w_vec)
    dr = np.asarray(pts["fairlead"]["position"], float) - pts["anchor"]["position"]
    rise = float(-dr @ w_hat)
    return {"force_anchor": np.asarray(line.fA, float).copy(),
            "force_fairlead": np.asarray(line.fB, float).copy(),
            "laid_length": float(line.LBot), "f_current": line.fCurrent.copy(), "sweeps": k,
            "tilt_deg": math.degrees(math.acos(min(1.0, -float(w_hat[2])))),
            "rise_rotated": rise, "span_rotated": float(np.linalg.norm(dr + rise * w_hat)),
            "w_total": float(np.linalg.norm(w_vec))}


def straight_closed_form(length: float, chord: float, axial_stiffness: float,
                         load: float) -> tuple[float, float]:
    """Tensions at the two ends of a straight taut line under a uniform load along it, N.

    The load f (N per *stretched* metre, docs/conventions.md "Drag") acts along the line
    from end a towards end b, so the upstream end a holds it: T(p) = T_a - f p along the
    stretched arc p, T_b = T_a - f c (c the chord). Hooke's law ds = dp / (1 + T/EA)
    integrated over the chord gives L = (EA/f) ln((EA + T_a)/(EA + T_a - f c)), so
    T_a = f c / (1 - exp(-f L / EA)) - EA (derived here).

    Parameters
    ----------
    length : float
        Unstretched length L, m.
    chord : float
        Distance between the ends c > L, m.
    axial_stiffness : float
        EA, N.
    load : float
        Tangential load per stretched length f > 0, N/m, towards end b.

    Returns
    -------
    tuple of float
        (T_a, T_b), N.
    """
    x = load * length / axial_stiffness
    t_a = load * chord / -math.expm1(-x) - axial_stiffness
    return t_a, t_a - load * chord


def _rel(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.linalg.norm(a - b) / max(np.linalg.norm(b), 1e-300))


def exact_case(direction: float = 1.0) -> dict[str, Any]:
    """The exact case: a neutrally buoyant taut line, horizontal, current along it.

    Weight in water 0 (mass = rho pi d^2 / 4), ends at the same height 200 m apart, the
    current along +x (``direction`` = +1, towards the fairlead) or -x: the line stays
    straight, the drag is tangential and uniform, 1/2 rho C_dt pi d U^2 per stretched metre,
    so MoorPy's uniform smearing is exact and both equal :func:`straight_closed_form`.

    Parameters
    ----------
    direction : float
        +1: current towards the fairlead (+x); -1: towards the anchor.

    Returns
    -------
    dict
        A system dict.
    """
    d = 0.1
    return line_case(length=200.0 * (1.0 - 1e-5), anchor=(0.0, 0.0, 50.0),
                     fairlead=(200.0, 0.0, 50.0),
                     depth=100.0, diameter=d, mass=RHO * math.pi / 4.0 * d * d,
                     axial_stiffness=1.0e10, normal_drag=1.2, tangential_drag=0.5,
                     speed=1.5, heading_deg=0.0 if direction > 0 else 180.0)


def exact_rows(with_moorpy: bool = True) -> list[dict[str, Any]]:
    """Ours, MoorPy and the closed form on :func:`exact_case`, both current directions.

    Parameters
    ----------
    with_moorpy : bool
        Also run MoorPy (needs it installed).

    Returns
    -------
    list of dict
        Per direction the end tensions (N) and the relative differences (-).
    """
    rows = []
    for direction in (1.0, -1.0):
        case = exact_case(direction)
        lt = case["line_types"]["line"]
        _, ct = line_drag_factors(RHO, lt["diameter"], lt["normal_drag"],
                                  lt["tangential_drag"])
        u = case["environment"]["current"]["speed"]
        ta, tb = straight_closed_form(case["lines"][0]["length"], 200.0,
                                      lt["axial_stiffness"], ct * u * u)
        # the upstream end holds the line against the flow
        t_anchor, t_fair = (ta, tb) if direction > 0 else (tb, ta)
        o = ours(case)
        row: dict[str, Any] = {
            "current": "along, towards fairlead" if direction > 0 else "along, towards anchor",
            "closed_anchor_N": t_anchor, "closed_fairlead_N": t_fair,
            "ours_anchor_N": float(np.linalg.norm(o["force_anchor"])),
            "ours_fairlead_N": float(np.linalg.norm(o["force_fairlead"])),
        }
        row["ours_rel"] = max(abs(row["ours_anchor_N"] / t_anchor - 1.0),
                              abs(row["ours_fairlead_N"] / t_fair - 1.0))
        if with_moorpy:
            m = moorpy_forces(case)
            row["moorpy_anchor_N"] = float(np.linalg.norm(m["force_anchor"]))
            row["moorpy_fairlead_N"] = float(np.linalg.norm(m["force_fairlead"]))
            row["moorpy_rel"] = max(abs(row["moorpy_anchor_N"] / t_anchor - 1.0),
                                    abs(row["moorpy_fairlead_N"] / t_fair - 1.0))
            row["ours_vs_moorpy"] = max(_rel(o["force_anchor"], m["force_anchor"]),
                                        _rel(o["force_fairlead"], m["force_fairlead"]))
        rows.append(row)
    return rows


#: the realistic chain: MoorPy's 90 mm studless chain (getLineProps: d_vol 0.162 m, 162 kg/m,
#: Cd 1.333); CdAx = 0.639 / pi = 0.2034 on pi d (the spar example's tangential_drag)
CHAIN = {"diameter": 0.162, "mass": 162.0, "axial_stiffness": 6.93331350e8,
         "normal_drag": 1.333, "tangential_drag": 0.2034}

#: the realistic currents: name -> heading (deg) with the fairlead at +x from the anchor
HEADINGS = {"along, towards fairlead": 0.0, "along, towards anchor": 180.0,
            "across (plan)": 90.0}

#: the geometries: name -> (length m, anchor m, fairlead m); depth 200 m
GEOMETRIES = {
    "touchdown": (850.0, (0.0, 0.0, 0.0), (780.0, 0.0, 190.0)),
    "suspended": (560.0, (0.0, 0.0, 60.0), (500.0, 0.0, 190.0)),
}


def realistic_case(geometry: str, heading_deg: float, speed: float = 1.0) -> dict[str, Any]:
    """A chain line of :data:`GEOMETRIES` in a uniform current of 1 m/s.

    Parameters
    ----------
    geometry : str
        Key of :data:`GEOMETRIES`.
    heading_deg : float
        Direction the current flows towards, deg (0: towards the fairlead).
    speed : float
        Current speed, m/s.

    Returns
    -------
    dict
        A system dict.
    """
    length, anchor, fair = GEOMETRIES[geometry]
    return line_case(length=length, anchor=anchor, fairlead=fair, depth=200.0,
                     speed=speed, heading_deg=heading_deg, intervals=80, **CHAIN)


def moorpy_frame_case(case: dict[str, Any], m: dict[str, Any]) -> dict[str, Any]:
    """The current-free line MoorPy actually solves: its rotated frame as our scene.

    MoorPy solves the catenary with the weight ``w_total = |w_vec|`` on a seabed normal to
    ``w_vec`` with the fairlead at (``span_rotated``, 0, ``rise_rotated``) from the anchor
    (line.py:786-843). Solving that with ours (no current, the mass raised so the weight in
    water is w_total) reproduces MoorPy's tensions: the difference from ours in the current
    is then the physics, not the solvers.

    Parameters
    ----------
    case : dict
        The system dict (:func:`line_case`) with the anchor on the seabed.
    m : dict
        :func:`moorpy_forces` of the case.

    Returns
    -------
    dict
        A system dict.
    """
    lt = case["line_types"]["line"]
    d = lt["diameter"]
    pts = {p["name"]: p for p in case["points"]}
    a = pts["anchor"]["position"]
    return line_case(length=case["lines"][0]["length"], anchor=tuple(a),
                     fairlead=(a[0] + m["span_rotated"], a[1], a[2] + m["rise_rotated"]),
                     depth=10.0 * case["environment"]["water_depth"], diameter=d,
                     mass=m["w_total"] / G + RHO * math.pi / 4.0 * d * d,
                     axial_stiffness=lt["axial_stiffness"], normal_drag=lt["normal_drag"],
                     tangential_drag=lt["tangential_drag"], speed=0.0, heading_deg=0.0,
                     intervals=case["solver"]["intervals"])


def smearing_bound(case: dict[str, Any]) -> dict[str, float]:
    """The load MoorPy moves, from our solved shape: L1 norm of (our drag - its smear), N.

    On our solution (tangents by finite differences of the nodes) the drag per unstretched
    length is f(s) = (1 + T/EA) f_vector(U, t(s)) off the seabed and 0 on it; MoorPy's load is
    the uniform f_bar = F_M / L with F_M the same law summed over every segment, grounded ones
    included (line.py:925-941). B = int |f - f_bar| ds is the largest force either end can
    gain or lose by the redistribution for a slack line whose shape barely changes (each end
    carries a share of every load, between 0 and 1): an estimate, not a proof (a taut line
    amplifies a lateral load).

    Parameters
    ----------
    case : dict
        A system dict from :func:`line_case`.

    Returns
    -------
    dict
        ``bound_N`` (B), ``grounded_N`` (MoorPy's current force on our laid part, N),
        ``normal_spread`` (max - min over the suspended part of |U_n|/|U|, -),
        ``touchdown_offset_m`` (our touchdown point's distance from the anchor-fairlead
        vertical plane, m: our laid part swings with the suspended part, MoorPy's stays in
        its rotated seabed plane).
    """
    from cable_ocp.physics.drag import drag_per_length_np

    res = solve_system(system_from_dict(case))
    sol = res.solutions["L"]
    lt = case["line_types"]["line"]
    cur = case["environment"]["current"]
    h = math.radians(cur["heading_deg"])
    u = cur["speed"] * np.array([math.cos(h), math.sin(h), 0.0])
    r = np.asarray(sol.position, float)
    s = np.asarray(sol.s, float)
    seg = np.diff(r, axis=0)
    ds_stretched = np.linalg.norm(seg, axis=1)
    t = seg / np.maximum(ds_stretched, 1e-300)[:, None]
    f = drag_per_length_np("vector", np.broadcast_to(u, t.shape), t, rho=RHO,
                           diameter=lt["diameter"], normal_drag=lt["normal_drag"],
                           tangential_drag=lt["tangential_drag"])
    ds = np.diff(s)
    stretch = ds_stretched / np.maximum(ds, 1e-300)
    grounded = 0.5 * (r[1:, 2] + r[:-1, 2]) < 1e-6 * max(float(s[-1]), 1.0)
    f_total_moorpy = (f * ds_stretched[:, None]).sum(axis=0)
    f_bar = f_total_moorpy / s[-1]
    # on the seabed both loads go into the seabed's reaction: only the suspended part counts
    diff = np.linalg.norm(f * stretch[:, None] - f_bar, axis=1)[~grounded]
    bound = float((diff * ds[~grounded]).sum())
    ground = float(np.linalg.norm((f * ds_stretched[:, None])[grounded].sum(axis=0)))
    un = u[None, :] - (t @ u)[:, None] * t
    ratio = np.linalg.norm(un, axis=1)[~grounded] / max(float(np.linalg.norm(u)), 1e-300)
    tdp = r[1:][grounded][-1] if np.any(grounded) else r[0]
    plan = (r[-1] - r[0])[:2] / max(float(np.linalg.norm((r[-1] - r[0])[:2])), 1e-300)
    rel = (tdp - r[0])[:2]
    return {"bound_N": bound, "grounded_N": ground,
            "normal_spread": float(ratio.max() - ratio.min()) if ratio.size else 0.0,
            "touchdown_offset_m": float(plan[0] * rel[1] - plan[1] * rel[0])}


def realistic_rows(geometries: tuple[str, ...] = ("touchdown", "suspended"),
                   headings: tuple[str, ...] = tuple(HEADINGS)) -> list[dict[str, Any]]:
    """Ours against MoorPy on the realistic chain, per geometry and current direction.

    Parameters
    ----------
    geometries : tuple of str
        Keys of :data:`GEOMETRIES`.
    headings : tuple of str
        Keys of :data:`HEADINGS`.

    Returns
    -------
    list of dict
        Per case: the end forces' magnitudes (N), the differences |F_ours - F_MoorPy| at each
        end (N) and relative to |F_ours|, the laid lengths (m) and :func:`smearing_bound`.
    """
    rows = []
    for geo in geometries:
        for name in headings:
            case = realistic_case(geo, HEADINGS[name])
            o = ours(case)
            m = moorpy_forces(case)
            est = smearing_bound(case)
            row: dict[str, Any] = {"geometry": geo, "current": name, "status": o["status"]}
            for end in ("anchor", "fairlead"):
                fo, fm = o[f"force_{end}"], m[f"force_{end}"]
                row[f"ours_{end}_N"] = float(np.linalg.norm(fo))
                row[f"moorpy_{end}_N"] = float(np.linalg.norm(fm))
                row[f"diff_{end}_N"] = float(np.linalg.norm(fo - fm))
                row[f"rel_{end}"] = row[f"diff_{end}_N"] / row[f"ours_{end}_N"]
            row["ours_laid_m"] = o["laid_length"]
            row["moorpy_laid_m"] = m["laid_length"]
            row["moorpy_current_N"] = float(np.linalg.norm(m["f_current"]))
            row["moorpy_tilt_deg"] = m["tilt_deg"]
            row["moorpy_rise_change_m"] = m["rise_rotated"] - (
                case["points"][1]["position"][2] - case["points"][0]["position"][2])
            mimic = ours(moorpy_frame_case(case, m))
            row["mimic_vs_moorpy"] = max(
                abs(float(np.linalg.norm(mimic[f"force_{e}"])) / row[f"moorpy_{e}_N"] - 1.0)
                for e in ("anchor", "fairlead"))
            row.update(est)
            rows.append(row)
    return rows
