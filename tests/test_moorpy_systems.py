"""The MoorPy side of the system benchmark (cable_ocp.bench.moorpy_systems): our system
dictionary converted to a MoorPy System reproduces independent answers (a closed-form
elastic catenary, MoorPy's own builds of the same systems, MoorPy's own line-type table).
Skipped without moorpy (a benchmark peer, not a dependency)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

mp = pytest.importorskip("moorpy")

from cable_ocp.bench.moorpy_systems import (  # noqa: E402
    euler_from_matrix,
    moorpy_stiffness,
    moorpy_system_from_dict,
    rotation_matrix,
)
from cable_ocp.scene import End, read_problem  # noqa: E402
from cable_ocp.statics.catenary import solve_line  # noqa: E402

SYSTEMS = Path(__file__).resolve().parents[1] / "problems" / "systems"
CHAIN = {"diameter": 0.216, "mass_per_length": 288.0, "axial_stiffness": 1232572089.6,
         "mbl": 13639789.32, "normal_drag": 1.333, "tangential_drag": 0.639 / math.pi,
         "added_mass": 1.0, "tangential_added_mass": 0.5}
POLY = {"diameter": 0.12663984955177424, "mass_per_length": 17.3824,
        "axial_stiffness": 110387200.0, "normal_drag": 2.021}
TOL = 1e-9   # MoorPy's solveEquilibrium position tolerance, m (its catenaries to 1e-11)


def _line_system(parts: list[dict], fairlead: list[float], depth: float = 100.0) -> dict:
    return {"environment": {"water_depth": depth, "water_density": 1025.0, "gravity": 9.81},
            "line_types": {"chain": CHAIN, "polyester": POLY},
            "points": [{"name": "anchor", "kind": "fixed", "position": [0.0, 0.0, 0.0]},
                       {"name": "fair", "kind": "fixed", "position": fairlead}],
            "lines": [{"name": "l", "point_a": "anchor", "point_b": "fair", "parts": parts}]}


def test_single_suspended_line_matches_the_elastic_catenary_and_z_is_shifted():
    """Anchor on our seabed (z = 0) to a fixed fairlead 90 m up, fully suspended: MoorPy's
    end forces equal the elastic catenary of cable_ocp.statics.catenary.solve_line (Huang
    1992 (2.31)-(2.33)), which knows nothing of MoorPy."""
    data = _line_system([{"type": "chain", "length": 125.0}], [80.0, 0.0, 90.0])
    ms = moorpy_system_from_dict(data)
    # the z convention: our z = 0 (seabed) is MoorPy's -depth, our 90 m is MoorPy's -10 m
    assert ms.pointList[0].r[2] == -100.0 and ms.pointList[1].r[2] == -10.0
    ms.solveEquilibrium(tol=TOL)
    line = ms.lineList[0]
    w = (288.0 - 1025.0 * math.pi * 0.216**2 / 4.0) * 9.81
    shape = solve_line(125.0, w, 1232572089.6, End((0.0, 0.0, 0.0), (None, None, None)),
                       End((80.0, 0.0, 90.0), (None, None, None)), tolerance=1e-13)
    assert shape.converged and shape.force_a[2] > 0.0   # the anchor is pulled up: no contact
    assert line.LBot == 0.0
    # 1e-6: MoorPy's catenary solve tolerance (0.01 tol, relative) and ours 1e-13
    np.testing.assert_allclose(line.fB, shape.force_b, rtol=1e-6, atol=1e-6 * line.TB)
    np.testing.assert_allclose(line.fA, shape.force_a, rtol=1e-6, atol=1e-6 * line.TB)


def test_two_part_line_equals_moorpys_own_two_lines_with_a_free_point():
    """A chain + polyester line from our dict equals MoorPy's build of two Lines joined by
    a free zero-mass Point (tests/test_system.py::test_multiseg's way)."""
    parts = [{"type": "chain", "length": 400.0}, {"type": "polyester", "length": 450.0}]
    ours = moorpy_system_from_dict(_line_system(parts, [800.0, 0.0, 185.0], depth=200.0))
    assert ours.cable_ocp_lines == {"l": [1, 2]}
    ours.solveEquilibrium(tol=TOL)
    ref = mp.System(depth=200.0)
    ref.setLineType(120, "chain", name="chain")
    ref.setLineType(160, "polyester", name="polyester")
    ref.addPoint(1, [0.0, 0.0, -200.0])
    ref.addPoint(0, [400.0, 0.0, -150.0])
    ref.addPoint(1, [800.0, 0.0, -15.0])
    ref.addLine(400.0, "chain", pointA=1, pointB=2)
    ref.addLine(450.0, "polyester", pointA=2, pointB=3)
    ref.initialize()
    ref.solveEquilibrium(tol=TOL)
    # 1e-6: two equilibria of the same system to 1e-9 m, line types from two routes
    # (ours written out to 16 digits; the wire's EA and d are MoorPy's numbers)
    for a, b in ((ours.lineList[0], ref.lineList[0]), (ours.lineList[1], ref.lineList[1])):
        np.testing.assert_allclose(a.fA, b.fA, rtol=1e-6, atol=1e-6 * b.TA)
        np.testing.assert_allclose(a.fB, b.fB, rtol=1e-6, atol=1e-6 * b.TB)
    np.testing.assert_allclose(ours.pointList[2].r, ref.pointList[1].r, atol=1e-5)
    assert ours.lineList[0].LBot > 0.0   # the chain lies on the seabed over part of it


def test_line_type_is_moorpys_own_table():
    """Our written-out chain (C_dt = CdAx, both on pi d; mass in air) becomes exactly MoorPy's
    getLineProps(120, 'chain'), including the weight in water it computes itself."""
    ms = moorpy_system_from_dict(read_problem(SYSTEMS / "moorpy_3line_spread.toml"))
    ref = mp.System(depth=600.0).setLineType(120, "chain", name="chain")
    ours = ms.lineTypes["chain"]
    for key in ("d_vol", "m", "EA", "w", "MBL", "Cd", "CdAx", "Ca", "CaAx"):
        # 1e-9: the file's values are MoorPy's, written to 14+ digits
        assert ours[key] == pytest.approx(ref[key], rel=1e-9, abs=1e-12), key


def test_free_body_spread_equals_moorpys_test_basic():
    """problems/systems/moorpy_3line_spread.toml through our converter equals MoorPy's
    tests/test_system.py::test_basic built by MoorPy's own calls: same pose and tensions."""
    ms = moorpy_system_from_dict(read_problem(SYSTEMS / "moorpy_3line_spread.toml"))
    ref = mp.System(depth=600.0)
    ref.setLineType(120, "chain", name="chain")
    ref.addBody(0, np.zeros(6), m=1e6, v=1e3, rM=100, AWP=1e6)
    ang = np.arange(3) * 2.0 * np.pi / 3.0
    for a in ang:
        ref.addPoint(1, [1600.0 * np.cos(a), 1600.0 * np.sin(a), -600.0])
    for a in ang:
        p = ref.addPoint(1, [20.0 * np.cos(a), 20.0 * np.sin(a), -21.0])
        ref.bodyList[0].attachPoint(p.number, p.r)
    for i in range(3):
        ref.addLine(1800.0, "chain", pointA=i + 1, pointB=i + 4)
    ref.initialize()
    for s in (ms, ref):
        s.bodyList[0].setPosition([10.0, 10.0, 1.0, 0.0, 0.0, 0.0])
        s.solveEquilibrium(tol=TOL)
    # 1e-6 m: both equilibria to 1e-9 m; the headings differ in the last digits
    np.testing.assert_allclose(ms.bodyList[0].r6, ref.bodyList[0].r6, atol=1e-6)
    np.testing.assert_allclose([ln.TB for ln in ms.lineList], [ln.TB for ln in ref.lineList],
                               rtol=1e-8)


def test_metacenter_from_waterplane_moments_and_the_free_clump():
    ms = moorpy_system_from_dict(read_problem(SYSTEMS / "spread_two_part_clump.toml"))
    body = ms.bodyList[0]
    # rM = CB + (Ixx / V) e_z = -10 + 2.02e5 / 10100 = +10 m
    np.testing.assert_allclose(body.rM, [0.0, 0.0, 10.0], rtol=1e-14)
    np.testing.assert_allclose(body.f6Ext, [-1e6, 0, 0, 0, 0, 0])
    clump = ms.pointList[ms.cable_ocp_points["clump1"] - 1]
    # the clump at the file's first guess, MoorPy's z
    assert clump.type == 0 and clump.m == 10000.0 and clump.r[2] == 40.0 - 200.0


def test_rotation_matrix_is_moorpys_and_euler_inverts_it():
    from moorpy.helpers import rotationMatrix

    angles = np.array([0.1, -0.3, 2.0])
    r = rotation_matrix(*angles)
    np.testing.assert_allclose(r, rotationMatrix(*angles), atol=1e-15)
    np.testing.assert_allclose(euler_from_matrix(r), angles, atol=1e-14)


def test_stiffness_three_ways_agree_at_zero_rotation():
    """On MoorPy's test_basic spread at its pose (no rotation) MoorPy's analytic 6x6 and
    central differences of full equilibria agree: the differencing is right."""
    ms = moorpy_system_from_dict(read_problem(SYSTEMS / "moorpy_3line_spread.toml"))
    ms.solveEquilibrium(tol=TOL)
    k = moorpy_stiffness(ms)
    ka, kf = np.array(k["analytic"]), np.array(k["fd_fixed_axes"])
    assert ka[0, 0] > 0.0 and kf[0, 0] > 0.0   # MoorPy's sign: positive in surge
    # 1e-4 of the diagonal: central differences with steps 1e-3 m / 1e-5 rad (truncation
    # ~1e-7, catenary tolerance 1e-9 m over the step ~1e-6)
    assert k["analytic_vs_fd"]["all_over_diagonal"] < 1e-4


def test_at_a_yawed_pose_moorpys_differences_are_in_euler_angles():
    """At 5 deg of yaw MoorPy's own central differences (getCoupledStiffness) are the
    fixed-axes stiffness times the Euler-rate matrix: taken back, they equal central
    differences about the fixed axes and the analytic matrix, which in Euler angles they
    do not (their roll column mixes in sin 5 deg of the pitch column)."""
    ms = moorpy_system_from_dict(read_problem(SYSTEMS / "moorpy_3line_spread.toml"))
    ms.solveEquilibrium(tol=TOL)
    ms.bodyList[0].setPosition([0.0, 0.0, ms.bodyList[0].r6[2], 0.0, 0.0, math.radians(5.0)])
    k = moorpy_stiffness(ms)
    # 1e-4: the differencing (MoorPy's own steps and its loose 5e-5 m inner tolerance)
    assert k["moorpy_fd_in_fixed_axes_vs_fd"]["all_over_diagonal"] < 1e-4
    assert k["analytic_vs_fd"]["all_over_diagonal"] < 1e-4
    # in Euler angles: K[:, roll] picks up sin(5 deg) K[:, pitch], ~9 % of the diagonal
    assert k["moorpy_fd_vs_fd"]["all_over_diagonal"] > 0.05
