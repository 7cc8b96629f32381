"""The equilibrium of a mooring system and its exact 6x6 (docs/systems.md).

Checks against independent computations: the 6x6 against central differences of full
equilibria (the body held at perturbed poses, the free points re-found), the body's own
hydrostatic Jacobian against central differences of its load, the textbook hydrostatic
matrix at a level pose, the asymmetry of the 6x6 against the mooring's moment, the
invariance under swapping a line's ends, the force balance of every free point from the
line solutions themselves.
"""

from __future__ import annotations

import copy
import math
import tomllib
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.mooring import SystemModel, solve_system
from cable_ocp.numerics.rotation import euler_angles, rotate_small, rotation_matrix
from cable_ocp.physics.hydrostatics import body_load, load_jacobian
from cable_ocp.scene.system import system_from_dict

ROOT = Path(__file__).resolve().parents[2]
SPAR = ROOT / "problems" / "systems" / "spar_3line.toml"


def spar_dict() -> dict:
    with open(SPAR, "rb") as f:
        return tomllib.load(f)


def clump_dict() -> dict:
    """The spar with line L1 split at a free clump (20 t, 2.5 m^3) 400 m from its anchor."""
    d = spar_dict()
    d["points"].append({"name": "c1", "kind": "free", "position": [520.0, 0.0, 60.0],
                        "mass": 2.0e4, "volume": 2.5})
    d["lines"][0] = {"name": "L1a", "point_a": "a1", "point_b": "c1", "type": "chain",
                     "length": 400.0}
    d["lines"].append({"name": "L1b", "point_a": "c1", "point_b": "f1", "type": "chain",
                       "length": 502.2})
    return d


def held(d: dict, rotation_deg: list[float], shift: list[float]) -> dict:
    """``d`` with its body held at the file pose moved by ``shift`` (m) and turned to
    ``rotation_deg``."""
    d = copy.deepcopy(d)
    b = d["bodies"][0]
    b["kind"] = "fixed"
    b["position"] = [p + s for p, s in zip(b["position"], shift, strict=True)]
    b["rotation_deg"] = rotation_deg
    return d


@pytest.fixture(scope="module")
def spar():
    sc = system_from_dict(spar_dict())
    return sc, solve_system(sc)


def central_difference_6x6(d: dict) -> tuple[np.ndarray, np.ndarray]:
    """(exact K, central differences of full equilibria): the body held at its pose and
    at +-h in each of x, y, z and in small rotations about the fixed axes, the free points
    found anew each time; K = -d[F; M]/d[x; theta] of the mooring's load."""
    sc = system_from_dict(d)
    res = solve_system(sc)
    assert res.status == "solved", res.message
    k = res.stiffness(which="mooring")
    model = SystemModel(sc)
    name = sc.bodies[0].name
    pose0 = res.state.bodies[name]
    kfd = np.zeros((6, 6))
    for j in range(6):
        # h: 1 mm and 1e-5 rad: the truncation error h^2 |F'''| is ~1e-8 of K here, the
        # solve noise (line tolerance 1e-10 on forces of ~1e6 N) / h is ~1e-7 of K
        h = 1e-3 if j < 3 else 1e-5
        loads = []
        for sgn in (1.0, -1.0):
            pose = pose0.copy()
            if j < 3:
                pose[j] += sgn * h
            else:
                th = np.zeros(3)
                th[j - 3] = sgn * h
                pose[3:] = euler_angles(rotate_small(th, rotation_matrix(*pose0[3:])))
            st = res.state.copy()
            st.bodies[name] = pose
            r = solve_system(sc, model=model, start=st, stiffness=False)
            assert r.status == "solved", r.message
            loads.append(np.r_[r.body()["mooring_force"], r.body()["mooring_moment"]])
        kfd[:, j] = -(loads[0] - loads[1]) / (2.0 * h)
    return k, kfd


@pytest.mark.parametrize("rotation_deg, shift", [
    ([0.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
    ([0.0, 3.0, 5.0], [-12.0, -4.0, 1.5]),
    ([2.0, -3.0, 10.0], [-6.0, 8.0, 0.0]),
])
def test_six_by_six_equals_central_differences_with_a_clump(rotation_deg, shift):
    """The issue's bar: 1e-5 of the largest entry, at poses with rotations of a few
    degrees, a free clump in equilibrium (the Schur complement)."""
    k, kfd = central_difference_6x6(held(clump_dict(), rotation_deg, shift))
    err = np.max(np.abs(k - kfd)) / np.max(np.abs(k))
    assert err < 1e-5, (err, k, kfd)
    # the rotational block is where MoorPy's analytic matrix is off (CONVENTIONS): check it
    # on its own, relative to its own largest entry
    rot = np.max(np.abs(k[3:, 3:] - kfd[3:, 3:])) / np.max(np.abs(k[3:, 3:]))
    assert rot < 1e-5, rot


def test_six_by_six_with_a_current_equals_central_differences():
    """With a current (1 m/s towards 30 deg) the drag is a follower load: the 6x6 is no
    longer symmetric in its elastic part, and still the exact derivative (the lines' end
    Jacobians carry the drag's derivatives): 1e-5 of the largest entry, as without."""
    d = held(clump_dict(), [0.0, 0.0, 0.0], [0.0, 0.0, 0.0])
    d["environment"]["current"] = {"speed": 1.0, "heading_deg": 30.0}
    k, kfd = central_difference_6x6(d)
    assert np.max(np.abs(k - kfd)) / np.max(np.abs(k)) < 1e-5
    # the elastic part's asymmetry (1e-9 without current) is now far above the noise
    el = solve_system(system_from_dict(d)).stiffness(which="elastic")
    assert np.max(np.abs(el - el.T)) > 1e-3 * np.max(np.abs(el))


def test_asymmetry_is_the_mooring_moment(spar):
    """K - K^T = [M]x in the rotational block (lines without current are conservative:
    their elastic part is symmetric; the geometric part's antisymmetric part is
    (1/2)[M]x, so the difference is [M]x): K45 - K54 = -M_z, K46 - K64 = M_y,
    K56 - K65 = -M_x."""
    _, res = spar
    k = res.stiffness(which="mooring")
    m = np.array(res.body()["mooring_moment"])
    assert abs(m[1]) > 1e7  # the 1 MN surge load at 70 m: a real asymmetry to test
    big = np.max(np.abs(k))
    a = k[3:, 3:] - k[3:, 3:].T
    # 1e-9 of the largest entry: both sides are computed from the same solution exactly
    assert abs(a[0, 1] + m[2]) < 1e-9 * big
    assert abs(a[0, 2] - m[1]) < 1e-9 * big
    assert abs(a[1, 2] + m[0]) < 1e-9 * big
    elastic = res.stiffness(which="elastic")
    assert np.max(np.abs(elastic - elastic.T)) < 1e-9 * big  # conservative lines
    assert np.max(np.abs(k[:3] - k[:, :3].T)) < 1e-9 * big  # translational rows symmetric


def test_symmetric_without_a_net_moment():
    """No external load and the body level: the mooring's moment about the reference point
    is zero by symmetry of the spread, so K is symmetric."""
    d = spar_dict()
    d["bodies"][0]["force"] = [0.0, 0.0, 0.0]
    res = solve_system(system_from_dict(d))
    k = res.stiffness(which="mooring")
    m = np.array(res.body()["mooring_moment"])
    assert np.max(np.abs(m)) < 1e-3  # N m, against ~1e8 N m of the loaded case
    assert np.max(np.abs(k - k.T)) < 1e-8 * np.max(np.abs(k))


def test_swapping_a_lines_ends_changes_nothing(spar):
    """MoorPy's own test (tests/test_system.py, lines with swapped ends): the same pose,
    tensions and stiffness when every line runs from the fairlead to the anchor."""
    _, res = spar
    d = spar_dict()
    for ln in d["lines"]:
        ln["point_a"], ln["point_b"] = ln["point_b"], ln["point_a"]
    swapped = solve_system(system_from_dict(d))
    assert swapped.status == "solved"
    # 1e-9 relative: the same line scenes are solved (end_a at the lower end), so only the
    # Newton path of the system differs
    assert np.allclose(swapped.body()["position"], res.body()["position"], rtol=0, atol=1e-7)
    for a, b in zip(res.lines, swapped.lines, strict=True):
        assert math.isclose(a["tension_a"], b["tension_b"], rel_tol=1e-9)
        assert math.isclose(a["tension_b"], b["tension_a"], rel_tol=1e-9)
        assert math.isclose(a["laid_length"], b["laid_length"], rel_tol=1e-7, abs_tol=1e-6)
    k1, k2 = res.stiffness(), swapped.stiffness()
    assert np.max(np.abs(k1 - k2)) < 1e-7 * np.max(np.abs(k1))


def test_free_points_and_body_in_balance_from_the_line_solutions():
    """At the equilibrium, the forces the line solutions themselves report balance every
    free point's weight in water, and the body's load (external, weight, buoyancy,
    waterplane): an independent sum, not the solver's residual vector."""
    d = clump_dict()
    sc = system_from_dict(d)
    res = solve_system(sc)
    assert res.status == "solved"
    g, rho = 9.81, 1025.0
    total = np.zeros(3)
    for ln in res.lines:
        if ln["point_b"] == "c1":
            total += ln["force_b"]
        if ln["point_a"] == "c1":
            total += ln["force_a"]
    total[2] += (rho * 2.5 - 2.0e4) * g
    # 1e-6 of the clump's weight: the system tolerance (1e-8 of ~2.4e6 N) is 0.02 N
    assert np.max(np.abs(total)) < 1e-6 * 2.0e4 * g
    body = res.body()
    b = sc.bodies[0]
    pose = np.r_[body["position"], np.radians(body["rotation_deg"])]
    own = body_load(b, pose[:3], rotation_matrix(*pose[3:]), rho, g, 320.0)
    net = np.r_[body["mooring_force"], body["mooring_moment"]] + own
    assert np.max(np.abs(net[:3])) < 1e-7 * 7.466e6 * g
    assert np.max(np.abs(net[3:])) < 1e-7 * 7.466e6 * g * 100.0


def test_hydrostatic_jacobian_equals_central_differences():
    """load_jacobian is the exact derivative of body_load in (dx, small rotations), at a
    tilted, yawed pose; and at a level pose its negative is the textbook matrix
    C33 = rho g A, C44 = rho g (Ixx + V z_B) - m g z_G (same for C55 with Iyy)."""
    sc = system_from_dict(spar_dict())
    b = replace(sc.bodies[0], waterplane_moments=(87.6, 120.0))
    rho, g = 1025.0, 9.81
    x = np.array([3.0, -2.0, 318.0])
    r = rotation_matrix(*np.radians([4.0, -3.0, 25.0]))
    jac = load_jacobian(b, x, r, rho, g)
    fd = np.zeros((6, 6))
    for j in range(6):
        h = 1e-4 if j < 3 else 1e-6
        dx, th = np.zeros(3), np.zeros(3)
        (dx if j < 3 else th)[j % 3] = h
        fp = body_load(b, x + dx, rotate_small(th, r), rho, g, 320.0)
        fm = body_load(b, x - dx, rotate_small(-th, r), rho, g, 320.0)
        fd[:, j] = (fp - fm) / (2 * h)
    # 1e-7 of the largest entry: central differences of smooth functions at h = 1e-6 rad
    assert np.max(np.abs(jac - fd)) < 1e-7 * np.max(np.abs(jac))
    c = -load_jacobian(b, x, np.eye(3), rho, g)
    assert math.isclose(c[2, 2], rho * g * 33.18, rel_tol=1e-14)
    assert math.isclose(c[3, 3], rho * g * (87.6 + 8029.0 * -62.06) - 7.466e6 * g * -89.9,
                        rel_tol=1e-12)
    assert math.isclose(c[4, 4], rho * g * (120.0 + 8029.0 * -62.06) - 7.466e6 * g * -89.9,
                        rel_tol=1e-12)


def test_no_restoring_is_one_clear_error():
    """A free body held by nothing in yaw (lines through its reference point, no
    waterplane moment about z): the message names the body and the degree of freedom."""
    d = spar_dict()
    for p in d["points"]:
        if p["kind"] == "body":
            p["position"] = [0.0, 0.0, -70.0]
    with pytest.raises(CableOCPError, match=r"body 'spar' yaw has no restoring"):
        solve_system(system_from_dict(d))


@pytest.mark.parametrize("edit, match", [
    (lambda d: d["lines"][0].update(point_b="a1"), r"point_a and point_b are both 'a1'"),
    (lambda d: d["lines"][0].update(type="chian"), r"lines\[0\]\.type = 'chian': no such "
                                                   r"line type; defined: chain"),
    (lambda d: d["lines"][0].update(point_b="f9"), r"lines\[0\]\.point_b = 'f9': no such"),
    (lambda d: (d["environment"].pop("seabed"), d["lines"][0].update(length=1200.0)),
     r"longer than the way from its ends"),
    (lambda d: (d["line_types"]["chain"].pop("axial_stiffness"),
                d["lines"][0].update(length=800.0)), r"not longer than the span"),
    (lambda d: d["bodies"][0].update(held=["surge"]), r"bodies\[0\]\.held"),
    (lambda d: d["points"][3].update(body="hull"), r"points\[3\]\.body = 'hull': no such"),
])
def test_bad_input_is_one_clear_error(edit, match):
    d = spar_dict()
    edit(d)
    with pytest.raises(CableOCPError, match=match):
        system_from_dict(d)


def test_a_standard_line_type_fills_the_table_and_keys_override_it():
    """``standard = "chain"`` at 90 mm gives the spar's chain table (written out from
    MoorPy's getLineProps(90, 'chain')) key for key, the weight in water from the mass and
    the volume-equivalent diameter in this water; a key given beside it wins."""
    d = spar_dict()
    d["line_types"]["std"] = {"standard": "chain", "nominal_diameter": 0.09,
                              "mbl": 7.0e6}
    sc = system_from_dict(d)
    std, chain = sc.line_types["std"], sc.line_types["chain"]
    for key in ("diameter", "mass_per_length", "weight_in_water", "normal_drag",
                "tangential_drag"):
        assert getattr(std, key) == pytest.approx(getattr(chain, key), rel=1e-12), key
    # the file's EA is MoorPy's rounded to 9 digits
    assert std.axial_stiffness == pytest.approx(chain.axial_stiffness, rel=1e-9)
    assert std.mbl == 7.0e6
    assert std.weight_in_water == pytest.approx(
        (162.0 - 1025.0 * math.pi * 0.162**2 / 4) * 9.81, rel=1e-12)


def test_a_system_tolerance_below_the_lines_accuracy_is_refused():
    """The net forces stall at ~25 x the lines' own tolerance (2.3e-9 at 1e-10 on the spar:
    the residual history of its solve); a system tolerance below 50 x it is refused before
    any solve, naming both keys, and accepted once solver.tolerance is lowered with it."""
    d = spar_dict()
    d["system"] = {"tolerance": 1e-9}
    with pytest.raises(CableOCPError, match=r"system.tolerance = 1e-09: must be >= 5e-09 "
                                             r"\(50 x solver.tolerance = 1e-10\)"):
        system_from_dict(d)
    d["solver"] = {"tolerance": 1e-11}
    assert system_from_dict(d).tolerance == 1e-9


def test_an_equilibrium_with_a_line_below_the_seabed_is_not_a_solution():
    """The two-part spread with lines 2 and 3 of 400 m chain + 450 m polyester: pushed
    towards them, they would lay more than their 400 m of chain on the seabed, and contact
    is modelled on a line's first part only. Whatever the iteration ends on, it is not
    reported as solved, and the message names the lines and says why."""
    path = ROOT / "problems" / "systems" / "spread_two_part_clump.toml"
    over = {f"lines.{i}.parts": [{"type": "chain", "length": 400.0},
                                 {"type": "polyester", "length": 450.0}] for i in (2, 3)}
    from cable_ocp.scene.system import load_system

    res = solve_system(load_system(path, over), stiffness=False)
    assert res.status == "failed"
    assert "line 'line2'" in res.message and "first segment" in res.message
