"""The mooring design checks (cable_ocp.mooring.checks): the restoring curve against the
body's condensed 6x6, the loads per heading and the line failures against the spreads'
symmetries, a force balance and the bundles' neighbours."""

from __future__ import annotations

import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from cable_ocp.mooring.checks import heading_loads, line_failure, offset_curve
from cable_ocp.mooring.model import condensed
from cable_ocp.numerics.rotation import rotation_matrix
from cable_ocp.physics.hydrostatics import body_load
from cable_ocp.scene.system import system_from_dict

ROOT = Path(__file__).resolve().parents[2]


def _scene(name: str):  # noqa: ANN202
    with open(ROOT / "problems" / "systems" / name, "rb") as fh:
        return system_from_dict(tomllib.load(fh))


@pytest.fixture(scope="module")
def spar():  # noqa: ANN201
    return _scene("spar_3line.toml")


@pytest.fixture(scope="module")
def spread9():  # noqa: ANN201
    return _scene("spread_9line.toml")


def _schur_xy(k: np.ndarray) -> np.ndarray:
    """The 2x2 on (x, y) of a 6x6 with z, roll, pitch, yaw in equilibrium."""
    return condensed(-k, np.array([0, 1]), np.array([2, 3, 4, 5])) * -1.0


@pytest.mark.parametrize("heading", [0.0, 37.0])
def test_the_slope_at_zero_offset_is_the_condensed_total_stiffness(spar, heading) -> None:
    h = 0.1
    curve = offset_curve(spar, "spar", heading, [-h, 0.0, h, 10.0])
    assert curve.status == ["solved"] * 4
    slope = (curve.restoring_force[2] - curve.restoring_force[0]) / (2 * h)
    e = np.array([math.cos(math.radians(heading)), math.sin(math.radians(heading))])
    expected = e @ _schur_xy(curve.neutral_stiffness) @ e
    # central difference of the curve's own points: truncation h^2 R'''/(6 R') measured
    # 1.4e-4 at h = 1 m and 1.4e-6 at h = 0.1 m (h^2 convergence); the equilibria's force
    # tolerance (1e-9 of ~2 MN over 2h) adds ~1e-7: 1e-5 leaves a margin of 7
    assert slope == pytest.approx(expected, rel=1e-5)
    # positive restoring (pointing back) for a positive offset; at zero offset no force
    assert curve.restoring_force[3] > 0 and curve.restoring_force[2] > 0
    assert abs(curve.restoring_force[1]) < 1e-6 * curve.restoring_force[3]
    # the heading's transverse force vanishes at 0 deg (the x-z plane is a mirror plane)
    if heading == 0.0:
        assert np.all(np.abs(curve.transverse_force) < 1e-6 * curve.restoring_force[3])
    json.dumps(curve.to_dict(), allow_nan=False)


def test_heading_loads_follow_the_threefold_symmetry(spar) -> None:
    res = heading_loads(spar, "spar", force=1.0e6, headings_deg=[0.0, 120.0, 60.0, 180.0])
    assert res.status == ["solved"] * 4
    t0, t120, t60, t180 = res.max_tension
    # 120 deg turns the spread onto itself, and 60 deg is 180 deg mirrored in the line at
    # 120 deg: equal to the file's rounding of the anchors and fairleads (1e-3 m, 1e-4 m),
    # which breaks the symmetry at ~1e-7
    assert t120 == pytest.approx(t0, rel=1e-6)
    assert t60 == pytest.approx(t180, rel=1e-6)
    assert res.offset[1] == pytest.approx(res.offset[0], rel=1e-6)
    # at 60 deg the load points straight away from anchor a3: L3 alone holds it, a larger
    # tension and a smaller offset than at 0 deg (towards an anchor, two lines share it)
    assert res.max_tension_line[2] == "L3" and t60 > 1.05 * t0
    assert res.offset[2] < 0.9 * res.offset[0]
    # the load's direction: the body moves along the heading at 0 deg
    assert res.offsets[0, 0] > 0 and abs(res.offsets[0, 1]) < 1e-6 * res.offsets[0, 0]
    json.dumps(res.to_dict(), allow_nan=False)


def test_line_failure_on_the_three_line_spar(spar) -> None:
    res = line_failure(spar)
    assert res.removed == ["L1", "L2", "L3"] and res.status == ["solved"] * 3
    # removing L2 or L3 under the +x load are mirror images in the x-z plane
    assert res.max_tension[1] == pytest.approx(res.max_tension[2], rel=1e-6)
    assert res.offsets[1, 1] == pytest.approx(-res.offsets[2, 1], rel=1e-6)
    # L1 is the leeward line (its anchor downwind): its pull adds to the load on L2 and
    # L3, so losing it lowers their tension; the removed line carries none
    assert res.max_tension[0] < res.intact_max_tension
    assert math.isnan(res.line_tension[0, 0])
    json.dumps(res.to_dict(), allow_nan=False)


def test_the_body_balances_after_a_line_failure(spar) -> None:
    res = line_failure(spar, lines=["L1"]).results[0]
    assert res.converged
    b = spar.bodies[0]
    pose = res.state.bodies["spar"]
    r = rotation_matrix(*pose[3:])
    # the lines' forces on the fairleads and their moments, from the line table
    f, m = np.zeros(3), np.zeros(3)
    for row in res.lines:
        fb = np.asarray(row["force_b"])
        arm = np.asarray(res.points[[p["name"] for p in res.points].index(row["point_b"])][
            "position"]) - pose[:3]
        f, m = f + fb, m + np.cross(arm, fb)
    own = body_load(b, pose[:3], r, spar.environment.water_density,
                    spar.environment.gravity, spar.environment.water_depth)
    total = np.concatenate([f, m]) + own
    # the equilibrium's tolerance: 1e-9 of the largest tension in force, times the
    # system's length in moment (cable_ocp.mooring.equilibrium._scales); 1e-8 for margin
    assert np.all(np.abs(total[:3]) < 1e-8 * res.max_tension)
    assert np.all(np.abs(total[3:]) < 1e-8 * res.max_tension * 902.2)
    # horizontally no hydrostatics: the lines alone hold the 1 MN
    assert f[0] == pytest.approx(-1.0e6, rel=1e-8) and abs(f[1]) < 1e-2


def test_the_neighbour_in_the_bundle_takes_the_load_of_a_failed_line(spread9) -> None:
    res = line_failure(spread9, lines=["B1a", "B1b", "B2c"])
    assert res.status == ["solved"] * 3
    # B1 is the weather bundle of the +x load: losing its outer line B1a loads its
    # neighbour B1b most; losing the middle B1b loads B1a and B1c alike (mirror images)
    assert res.max_tension_line[0] == "B1b"
    assert res.max_tension_line[1] in ("B1a", "B1c")
    i_a, i_c = res.line_names.index("B1a"), res.line_names.index("B1c")
    assert res.line_tension[1, i_a] == pytest.approx(res.line_tension[1, i_c], rel=1e-6)
    # each weather line carries a third of the bundle's load: a lost one adds about half
    # of its share to each neighbour, more than 20 % (35 % seen)
    assert res.max_tension[0] > 1.2 * res.intact_max_tension
    # a leeward line (B2c, at 305 deg) lost: the weather lines' tensions drop
    assert res.max_tension[2] < res.intact_max_tension


def test_a_body_left_without_restoring_is_a_failed_case_not_an_error(spar) -> None:
    # x, y, roll and pitch held, L1 and L2, L2's fairlead moved onto the spar's axis:
    # L1's pull on its fairlead's arm restores yaw, L2's (no arm) cannot; without L1
    # nothing does (hydrostatics has no yaw stiffness): a failed case with the solver's
    # message, and the other case still solved
    raw = json.loads(json.dumps(spar.raw))
    raw["bodies"][0]["held"] = ["x", "y", "roll", "pitch"]
    raw["bodies"][0].pop("force")
    raw["points"].append({"name": "f0", "kind": "body", "body": "spar",
                          "position": [0.0, 0.0, -70.0]})
    raw["lines"] = raw["lines"][:2]
    raw["points"] = [p for p in raw["points"] if p["name"] not in ("a3", "f2", "f3")]
    raw["lines"][1]["point_b"] = "f0"
    res = line_failure(system_from_dict(raw))
    assert res.status == ["failed", "solved"]
    assert "yaw has no restoring" in res.messages[0]
    assert math.isnan(res.max_tension[0]) and res.max_tension_line[1] == "L1"
    json.dumps(res.to_dict(), allow_nan=False)
