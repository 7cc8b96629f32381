"""Multi-segment lines and point bodies (issue 6, item 2).

Checks, each against an independent result:

* a cable split into two identical segments is the single cable (same equations on the
  same mesh when the split falls on a mesh point);
* Huang's hanging cable under a point load (Huang 1992, Fig. 2.5 is a caption only;
docs/conventions.md
  "Reading the sources": a constructed case) against
  :func:`cable_ocp.baselines.huang.solve_point_loads`, exact for point loads on a uniform
  elastic cable with no drag: a clump and a buoy;
* a 3-segment line with different weights and EA, and a subsea unit with drag and thrust
  in a current, against shooting with scipy ``solve_ivp`` over the segments with the
  joint jumps (written here from the equations, not from the package);
* bad scenes give errors naming the key, or an explicit failure;
* the shipped problem file problems/mooring_clump_buoy.toml solves from the CLI.
"""

from __future__ import annotations

import copy
import json
import math
import tomllib

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import fsolve

from cable_ocp.baselines.huang import solve_point_loads
from cable_ocp.cli import main
from cable_ocp.errors import CableOCPError
from cable_ocp.scene import scene_from_dict
from cable_ocp.statics.solver import solve

ENV = {"water_depth": 100.0, "water_density": 1025.0}
A, B = [0.0, 0.0, 20.0], [80.0, 10.0, 60.0]


def _rel(a: np.ndarray, b: np.ndarray) -> float:
    """Largest component difference over the reference's magnitude."""
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b))) / np.linalg.norm(b))


def _multi(segments: list[dict], bodies: list[dict] | None = None, env: dict | None = None,
           a: list | None = None, b: list | None = None, **cable) -> dict:
    data = {"environment": copy.deepcopy(env or ENV),
            "cable": {"segments": copy.deepcopy(segments), **cable},
            "end_a": {"position": a or A}, "end_b": {"position": b or B},
            "solver": {"intervals": 40}}
    if bodies is not None:
        data["bodies"] = copy.deepcopy(bodies)
    return data


# -- 1. two identical segments = one cable ----------------------------------------------

def test_split_cable_equals_single_cable(problems):
    """De Zoysa at psi0 = 90 deg (3D, componentwise drag, current): the cable cut into two
    150.5 m halves. 20 + 20 uniform intervals are the single cable's 40 with a joint at a
    mesh point, so the discrete equations are the same and only round-off differs: 1e-9.
    With mesh points on the drag's kink (the default) the two meshes differ, and the end
    forces agree to 1e-10 relative (both within ~1e-11 of the converged solution)."""
    with (problems / "dezoysa_sea_buggy.toml").open("rb") as fh:
        data = tomllib.load(fh)
    data["layout"]["psi0_deg"] = 90.0
    fitted = solve(scene_from_dict(data))
    data.setdefault("solver", {})["mesh"] = "uniform"
    ref = solve(scene_from_dict(data))
    cab = data["cable"]
    law, length = cab.pop("drag_law"), cab.pop("length")
    data["cable"] = {"drag_law": law, "segments": [dict(cab, length=length / 2),
                                                   dict(cab, length=length / 2)]}
    sol = solve(scene_from_dict(data))
    assert ref.success and sol.success, sol.message
    assert _rel(sol.force_a, ref.force_a) < 1e-9
    assert _rel(sol.force_b, ref.force_b) < 1e-9
    np.testing.assert_allclose(sol.force_a, [1579.9, 3388.9, 1140.1], atol=0.06)
    assert np.all(np.diff(sol.s) >= 0)
    mid = np.interp(length / 2, ref.s, ref.position[:, 0])
    joint = sol.diagnostics["joints"][0]
    assert abs(joint[0] - mid) < 1e-6 * length  # np.interp is linear between nodes
    data["solver"]["mesh"] = "kinks"
    split = solve(scene_from_dict(data))
    assert fitted.diagnostics["mesh"]["kind"] == split.diagnostics["mesh"]["kind"] == "kinks"
    assert _rel(split.force_a, fitted.force_a) < 1e-10
    assert _rel(split.force_b, fitted.force_b) < 1e-10


# -- 2. point loads on a hanging elastic cable: Huang's exact method -------------------

SEG = {"weight_in_water": 10.0, "axial_stiffness": 1.0e6}  # N/m, N


@pytest.mark.parametrize("kind, key, fz", [("clump", "weight_in_water", -200.0),
                                           ("buoy", "net_buoyancy", 300.0)])
def test_point_body_against_huang(kind, key, fz):
    """A still-water elastic cable (100 m, 10 N/m, EA = 1 MN) between fixed ends with a
    clump (200 N down) or a buoy (300 N up) 40 m from end_a. Huang's method (Huang (1992)
    (2.31)-(2.33) with the segment relation derived from (2.31)-(2.32), exact for point
    loads) gives end forces and the joint position to its Newton tolerance; the
    collocation's discretisation error at 40 + 60 intervals is below 1e-9 (the profile is
    smooth on each segment): 1e-8 relative."""
    data = _multi([dict(SEG, length=40.0), dict(SEG, length=60.0)],
                  [{"joint": 1, "kind": kind, key: abs(fz)}])
    data["solver"]["intervals"] = 100
    sol = solve(scene_from_dict(data))
    single = scene_from_dict({"environment": ENV, "cable": dict(SEG, length=100.0),
                              "end_a": {"position": A}, "end_b": {"position": B},
                              "solver": {"tolerance": 1e-12}})
    ref = solve_point_loads(single, [(40.0, (0.0, 0.0, fz))])
    assert sol.success and ref.success, sol.message
    assert _rel(sol.force_a, ref.force_a) < 1e-8
    assert _rel(sol.force_b, ref.force_b) < 1e-8
    j = int(np.flatnonzero(np.isclose(ref.s, 40.0))[0])
    body = sol.to_dict()["bodies"][0]
    assert body["kind"] == kind and body["joint"] == 1
    assert np.max(np.abs(np.array(body["position"]) - ref.position[j])) < 1e-8 * 100.0
    np.testing.assert_allclose(body["force"], [0.0, 0.0, fz], rtol=1e-12)
    # the tension jumps by the body's load at the joint: T(s+) = T(s-) - P
    k = int(np.flatnonzero(np.isclose(sol.s, 40.0))[0])
    np.testing.assert_allclose(sol.tension_vector[k + 1] - sol.tension_vector[k],
                               [0.0, 0.0, -fz], atol=1e-9 * abs(fz))


# -- 3. independent shooting over the segments ------------------------------------------

def _shoot(segments: list[dict], loads: dict[int, callable], ra, rb, current,
           rho: float, t0_guess) -> tuple[np.ndarray, np.ndarray, list[np.ndarray]]:
    """Shoot from end_a with unknown T(0) (N) to end_b's position: dr/ds = (1 + T/EA) t,
    dT/ds = -f, f = (0, 0, -w) + (1 + T/EA) f_drag, vector law
    f_drag = 1/2 rho D (C_n |U_n| U_n + C_t pi |U_t| U_t); T(s+) = T(s-) - P at joints.
    Returns T(0), T(L) and the joint positions."""
    u = np.asarray(current, dtype=float)

    def rhs(seg):
        ea = seg.get("axial_stiffness", math.inf)

        def f(_s, y):
            tvec = y[3:]
            tm = np.linalg.norm(tvec)
            t = tvec / tm
            st = 1.0 + tm / ea
            ut = np.dot(u, t) * t
            un = u - ut
            drag = 0.5 * rho * seg.get("diameter", 0.0) * (
                seg.get("normal_drag", 0.0) * np.linalg.norm(un) * un
                + seg.get("tangential_drag", 0.0) * math.pi * np.linalg.norm(ut) * ut)
            load = np.array([0.0, 0.0, -seg["weight_in_water"]]) + st * drag
            return np.concatenate([st * t, -load])
        return f

    def run(t0):
        y = np.concatenate([ra, t0])
        joints = []
        for k, seg in enumerate(segments):
            if k:
                joints.append(y[:3].copy())
                y = np.concatenate([y[:3], y[3:] - loads.get(k, lambda r: np.zeros(3))(y[:3])])
            y = solve_ivp(rhs(seg), (0.0, seg["length"]), y, method="DOP853", rtol=1e-13,
                          atol=1e-11).y[:, -1]
        return y, joints

    t0 = fsolve(lambda t0: run(t0)[0][:3] - rb, t0_guess, xtol=1e-12)
    y, joints = run(t0)
    assert np.max(np.abs(y[:3] - rb)) < 1e-9
    return t0, y[3:], joints


def test_three_segments_different_weights_against_shooting():
    """Chain - wire - chain in still water (different w and EA) with a clump and a buoy;
    the shooting (DOP853, rtol 1e-13) is an independent solution of the same ODEs with the
    joint jumps. Collocation error below 1e-9 at 90 intervals: 1e-8 relative."""
    segs = [{"length": 40.0, "weight_in_water": 80.0, "axial_stiffness": 2e7},
            {"length": 70.0, "weight_in_water": 15.0, "axial_stiffness": 5e6},
            {"length": 30.0, "weight_in_water": 60.0, "axial_stiffness": 2e7}]
    bodies = [{"joint": 1, "kind": "clump", "weight_in_water": 500.0},
              {"joint": 2, "kind": "buoy", "net_buoyancy": 800.0}]
    data = _multi(segs, bodies, a=[0.0, 0.0, 5.0], b=[110.0, 20.0, 90.0])
    data["solver"]["intervals"] = 90
    sol = solve(scene_from_dict(data))
    assert sol.success, sol.message
    loads = {1: lambda r: np.array([0.0, 0.0, -500.0]), 2: lambda r: np.array([0.0, 0.0, 800.0])}
    t0, tl, joints = _shoot(segs, loads, np.array([0.0, 0.0, 5.0]), np.array([110.0, 20.0, 90.0]),
                            [0.0, 0.0, 0.0], 1025.0, 1.05 * sol.force_a)
    assert _rel(sol.force_a, t0) < 1e-8
    assert _rel(sol.force_b, -tl) < 1e-8
    for got, ref in zip(sol.diagnostics["joints"], joints, strict=True):
        assert np.max(np.abs(np.array(got) - ref)) < 1e-8 * 140.0


def test_subsea_unit_with_drag_in_current_against_shooting():
    """A subsea unit (2 kN in water, drag area 2 m^2, C_d 1.0, thrust (300, -150, 0) N)
    between two segments of a line in a 0.8 m/s current at 30 deg (3D), vector drag law on
    the cable. Against the shooting solution: 1e-6 relative (the issue's tolerance; the
    smooth modulus, delta = 1e-5 m/s, changes the loads by ~1e-10 relative)."""
    segs = [{"length": 120.0, "diameter": 0.05, "weight_in_water": 50.0,
             "axial_stiffness": 5e7, "normal_drag": 1.2, "tangential_drag": 0.01},
            {"length": 150.0, "diameter": 0.04, "weight_in_water": 20.0,
             "axial_stiffness": 2e7, "normal_drag": 1.2, "tangential_drag": 0.01}]
    unit = {"joint": 1, "kind": "unit", "weight_in_water": 2000.0, "drag_area": 2.0,
            "drag_coefficient": 1.0, "thrust": [300.0, -150.0, 0.0]}
    env = {"water_depth": 200.0, "water_density": 1025.0,
           "current": {"speed": 0.8, "heading_deg": 30.0}}
    ra, rb = [0.0, 0.0, 10.0], [150.0, 0.0, 200.0]
    sol = solve(scene_from_dict(_multi(segs, [unit], env=env, a=ra, b=rb,
                                       drag_law="vector")))
    assert sol.success, sol.message
    u = 0.8 * np.array([math.cos(math.radians(30)), math.sin(math.radians(30)), 0.0])
    p_unit = (np.array([300.0, -150.0, -2000.0])
              + 0.5 * 1025.0 * 1.0 * 2.0 * np.linalg.norm(u) * u)
    t0, tl, joints = _shoot(segs, {1: lambda r: p_unit}, np.array(ra), np.array(rb), u,
                            1025.0, 1.05 * sol.force_a)
    assert _rel(sol.force_a, t0) < 1e-6
    assert _rel(sol.force_b, -tl) < 1e-6
    body = sol.to_dict()["bodies"][0]
    assert np.max(np.abs(np.array(body["position"]) - joints[0])) < 1e-6 * 270.0
    np.testing.assert_allclose(body["force"], p_unit, rtol=1e-9)


# -- 4. bad scenes ----------------------------------------------------------------------

@pytest.mark.parametrize("edit, key", [
    (lambda d: d["cable"]["segments"][1].update(length=0.0), "cable.segments[1].length"),
    (lambda d: d["cable"]["segments"][0].update(length=-5.0), "cable.segments[0].length"),
    (lambda d: d["bodies"][0].update(weight_in_water=-100.0), "bodies[0].weight_in_water"),
    (lambda d: d["bodies"][0].update(joint=2), "bodies[0].joint"),
    (lambda d: d["bodies"][0].update(joint=0), "bodies[0].joint"),
    (lambda d: d["cable"].update(length=100.0), "cable.length"),
    (lambda d: d["cable"].update(weight_in_water=10.0), "cable.weight_in_water"),
    (lambda d: d["cable"]["segments"][0].update(length="free"), "cable.segments[0].length"),
    (lambda d: d["bodies"][0].update(kind="anchor"), "bodies[0].kind"),
    (lambda d: d["solver"].update(method="multiple_shooting"), "solver.method"),
])
def test_bad_scenes_name_the_key(edit, key):
    """User errors raise CableOCPError naming the offending key."""
    data = _multi([dict(SEG, length=40.0), dict(SEG, length=60.0)],
                  [{"joint": 1, "kind": "clump", "weight_in_water": 200.0}])
    edit(data)
    with pytest.raises(CableOCPError, match=key.replace("[", r"\[").replace("]", r"\]")):
        scene_from_dict(data)


def test_free_length_with_segments_rejected():
    """A prescribed end tension (free length) is not supported with segments."""
    data = _multi([dict(SEG, length=40.0), dict(SEG, length=60.0)])
    data["end_b"]["tension"] = 1000.0
    with pytest.raises(CableOCPError, match="end_b.tension"):
        scene_from_dict(data)


def test_buoy_lifting_line_out_of_water_fails():
    """A 20 kN buoy on a 10 N/m line in 60 m of water would float above the surface: the
    solve must say so (status "above_surface"), never report a profile above z =
    water_depth."""
    env = {"water_depth": 60.0, "water_density": 1025.0}
    data = _multi([dict(SEG, length=80.0), dict(SEG, length=80.0)],
                  [{"joint": 1, "kind": "buoy", "net_buoyancy": 20000.0}], env=env,
                  a=[0.0, 0.0, 0.0], b=[100.0, 0.0, 60.0])
    sol = solve(scene_from_dict(data))
    depth = env["water_depth"]
    assert sol.status == "above_surface" or np.all(sol.position[:, 2] <= depth + 1e-9)
    assert sol.status == "above_surface"
    assert "surface" in sol.message and "water_depth" in sol.message


# -- 5. the shipped mooring ---------------------------------------------------------------

def test_mooring_problem_file_from_cli(problems, tmp_path, capsys):
    """problems/mooring_clump_buoy.toml (chain - wire - chain, clump, buoy, current,
    seabed) solves from ``cable-ocp solve``; the JSON lists both bodies with their loads,
    the bottom chain touches down on its first segment, nothing goes below the seabed or
    above the surface, and the error estimate meets solver.accuracy."""
    out = tmp_path / "m.json"
    rc = main(["solve", str(problems / "mooring_clump_buoy.toml"), "--json", str(out)])
    assert rc == 0, capsys.readouterr().err
    data = json.loads(out.read_text())
    assert data["status"] == "solved"
    kinds = [(b["joint"], b["kind"]) for b in data["bodies"]]
    assert kinds == [(1, "clump"), (2, "buoy")]
    np.testing.assert_allclose(data["bodies"][0]["force"], [0.0, 0.0, -50e3], rtol=1e-12)
    np.testing.assert_allclose(data["bodies"][1]["force"], [0.0, 0.0, 60e3], rtol=1e-12)
    assert 0.0 < data["touchdown"]["grounded_length"] < 300.0
    z = np.array(data["profile"]["z"])
    assert z.min() >= -1e-6 and z.max() <= 150.0
    assert np.all(np.diff(data["profile"]["s"]) > 0)
    assert data["solver"]["error_estimate"] < 1e-6
    assert data["bodies"][0]["position"][2] > 0.0  # the clump hangs above the seabed
