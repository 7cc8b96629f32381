"""MoorDyn v2 input files <-> the system problem dict (cable_ocp.scene.moordyn).

The handwritten file tests/data/moordyn/spread_clump.dat is read into exact values (MoorDyn's
z = 0 at the surface shifted to ours: z_ours = z_moordyn + depth); files read, written and
read again give the same dict; the TOML text comes back through tomllib equal; bad inputs
name their file line; MoorPy's own test inputs and a MoorPy-written file are read.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.scene.moordyn import read_moordyn, system_dict_to_toml, write_moordyn

DATA = Path(__file__).parent / "data" / "moordyn"
SPREAD = DATA / "spread_clump.dat"
MOORPY_CASES = sorted(DATA.glob("moorpy_case*.dat"))

EXPECTED = {
    "meta": {"title": "MoorDyn v2 input file: a 3-line spread on a free buoy, one line with "
                      "a clump\n(handwritten for cable_ocp's tests; depth 200 m)"},
    "environment": {"water_depth": 200.0, "water_density": 1027.5, "gravity": 9.81,
                    "seabed": {"friction": 0.0}},  # MoorDyn always has its seabed
    "line_types": {
        # CdAx is copied: MoorDyn's and ours are both on pi d (source/Line.cpp, Dq)
        "chain": {"diameter": 0.1674, "mass_per_length": 146.0, "axial_stiffness": 1.5e9,
                  "normal_drag": 2.4, "added_mass": 1.0, "tangential_drag": 1.15,
                  "tangential_added_mass": 0.5},
        "wire": {"diameter": 0.08, "mass_per_length": 25.5, "axial_stiffness": 4.2e8,
                 "normal_drag": 1.2, "added_mass": 1.0, "tangential_drag": 0.008,
                 "tangential_added_mass": 0.0},
    },
    "points": [
        {"name": "point1", "kind": "fixed", "position": [800.0, 0.0, 0.0]},
        {"name": "point2", "kind": "fixed", "position": [-400.0, 692.82, 0.0]},
        {"name": "point3", "kind": "fixed", "position": [-400.0, -692.82, 0.0]},
        # body points: in the body frame, not shifted
        {"name": "point4", "kind": "body", "body": "body1", "position": [20.0, 0.0, -8.0]},
        {"name": "point5", "kind": "body", "body": "body1", "position": [-10.0, 17.32, -8.0]},
        {"name": "point6", "kind": "body", "body": "body1", "position": [-10.0, -17.32, -8.0]},
        {"name": "point7", "kind": "free", "position": [-250.0, -433.0, 20.0],
         "mass": 15000.0, "volume": 1.9},
    ],
    "bodies": [
        {"name": "body1", "kind": "free", "position": [5.0, -2.0, 187.5],
         "rotation_deg": [0.0, 1.5, 30.0], "mass": 2.0e6,
         "center_of_gravity": [0.0, 0.0, -4.25], "volume": 2500.0,
         # MoorDyn applies the buoyancy at the CG (source/Body.cpp doRHS)
         "center_of_buoyancy": [0.0, 0.0, -4.25]},
    ],
    "lines": [
        {"name": "line1", "point_a": "point1", "point_b": "point4", "type": "chain",
         "length": 850.0},
        {"name": "line2", "point_a": "point2", "point_b": "point5", "type": "chain",
         "length": 850.5},
        {"name": "line3", "point_a": "point3", "point_b": "point7", "type": "chain",
         "length": 520.25},
        {"name": "line4", "point_a": "point7", "point_b": "point6", "type": "wire",
         "length": 345.0},
    ],
    "moordyn": {
        "options": {"dtM": 0.0005, "kBot": 3.0e6, "tScheme": "RK4", "myOwnFlag": 1},
        "line_types": {"chain": {"BA": -0.8},
                       "wire": {"EA_dynamic": [6.3e8], "BA": "-1|0.3", "EI": 1250.0}},
        "bodies": {"body1": {"inertia": [1e9, 1e9, 2.5e9], "CdA": [120.0], "Ca": [0.8]}},
        "points": {"point7": {"CdA": 2.5, "Ca": 1.0}},
        "lines": {"line1": {"NumSegs": 40, "outputs": "pt"},
                  "line2": {"NumSegs": 42, "outputs": "-"},
                  "line3": {"NumSegs": 26, "outputs": "p"},
                  "line4": {"NumSegs": 18, "outputs": "t"}},
        "outputs": ["FairTen1", "FairTen2", "FairTen3", "Body1PX"],
    },
}


def test_handwritten_file_exact_values() -> None:
    assert read_moordyn(SPREAD) == EXPECTED


def test_z_shift_is_depth() -> None:
    # the free clump at z = -180 in MoorDyn is 20 m above a 200 m deep seabed
    data = read_moordyn(SPREAD)
    assert data["points"][6]["position"][2] == -180.0 + 200.0
    assert data["bodies"][0]["position"][2] == -12.5 + 200.0


@pytest.mark.parametrize("path", [SPREAD, *MOORPY_CASES], ids=lambda p: p.name)
def test_read_write_read_round_trip(path: Path, tmp_path: Path) -> None:
    data = read_moordyn(path)
    out = tmp_path / "out.dat"
    write_moordyn(data, out)
    assert read_moordyn(out) == data          # repr precision: every number exact
    assert tomllib.loads(system_dict_to_toml(data)) == data


def test_written_z_is_moordyn_z(tmp_path: Path) -> None:
    out = tmp_path / "out.dat"
    write_moordyn(read_moordyn(SPREAD), out)
    rows = [ln.split() for ln in out.read_text().splitlines()]
    clump = next(r for r in rows if r[:2] == ["7", "Free"])
    assert float(clump[4]) == -180.0          # back to MoorDyn's z
    fair = next(r for r in rows if r[:2] == ["4", "Body1"])
    assert float(fair[4]) == -8.0             # body frame: unchanged


def test_multi_part_line_becomes_moordyn_lines_joined_by_free_points(tmp_path: Path) -> None:
    data = read_moordyn(SPREAD)
    del data["moordyn"]
    data["points"] = [p for p in data["points"] if p["name"] != "point7"]
    data["lines"] = data["lines"][:2] + [
        {"name": "leg3", "point_a": "point3", "point_b": "point6",
         "parts": [{"type": "chain", "length": 500.0}, {"type": "wire", "length": 300.0}]}]
    out = tmp_path / "out.dat"
    write_moordyn(data, out)
    back = read_moordyn(out)
    joint = back["points"][-1]
    assert joint["name"] == "leg3.joint1" and joint["kind"] == "free"
    assert joint["mass"] == 0.0 and joint["volume"] == 0.0
    assert [ln["name"] for ln in back["lines"][2:]] == ["leg3.part1", "leg3.part2"]
    assert [(ln["type"], ln["length"]) for ln in back["lines"][2:]] == [
        ("chain", 500.0), ("wire", 300.0)]
    assert tomllib.loads(system_dict_to_toml(back)) == back    # quoted keys "leg3.part1"
    assert back["lines"][2]["point_a"] == "point3"
    assert back["lines"][3]["point_b"] == "point6"
    # the joint starts on the chord, 5/8 of the way from the anchor to the fairlead
    body = data["bodies"][0]
    r, p, y = (math.radians(a) for a in body["rotation_deg"])
    fx, fy, fz = -10.0, -17.32, -8.0
    # R = Rz(y) Ry(p) Rx(r), written out for r = 0 (the file's roll)
    assert r == 0.0
    gx = body["position"][0] + math.cos(y) * (math.cos(p) * fx + math.sin(p) * fz) \
        - math.sin(y) * fy
    gz = body["position"][2] - math.sin(p) * fx + math.cos(p) * fz
    a = data["points"][2]["position"]
    s = 500.0 / 800.0
    # 1e-9 m: rounding of the rotation only
    assert joint["position"][0] == pytest.approx(a[0] + s * (gx - a[0]), abs=1e-9)
    assert joint["position"][2] == pytest.approx(a[2] + s * (gz - a[2]), abs=1e-9)


def test_custom_names_survive_a_write(tmp_path: Path) -> None:
    data = read_moordyn(SPREAD)
    data["points"][0]["name"] = "anchor east"
    data["lines"][0]["point_a"] = "anchor east"
    out = tmp_path / "out.dat"
    write_moordyn(data, out)
    assert read_moordyn(out) == data
    assert tomllib.loads(system_dict_to_toml(data)) == data


@pytest.mark.parametrize("key,value,word", [
    ("waterplane_area", 80.0, "waterplane_area"),
    ("center_of_buoyancy", [0.0, 0.0, -6.0], "centre of gravity"),
    ("held", ["z"], "held")])
def test_write_refuses_what_moordyn_cannot_carry(key: str, value: object, word: str,
                                                 tmp_path: Path) -> None:
    data = read_moordyn(SPREAD)
    data["bodies"][0][key] = value
    out = tmp_path / "out.dat"
    with pytest.raises(CableOCPError, match=word):
        write_moordyn(data, out)
    assert not out.exists()


def _bad(tmp_path: Path, old: str, new: str) -> str:
    text = SPREAD.read_text()
    assert text.count(old) == 1
    path = tmp_path / "bad.dat"
    path.write_text(text.replace(old, new))
    with pytest.raises(CableOCPError) as err:
        read_moordyn(path)
    return str(err.value)


RODS = """---------------------- RODS ----------------------
ID RodType Attachment Xa Ya Za Xb Yb Zb NumSegs Outputs
(#) (name) (#/key) (m) (m) (m) (m) (m) (m) (-) (-)
1 spar Body1 0 0 0 0 0 -10 5 -
---------------------- POINTS"""


def test_rods_refused_with_line_number(tmp_path: Path) -> None:
    msg = _bad(tmp_path, "---------------------- POINTS", RODS)
    # the RODS header is line 12, its row line 15
    assert msg == ("bad.dat line 15: section RODS is not modelled (cable_ocp reads line "
                   "types, points, bodies, lines, options)")


def test_empty_rod_sections_accepted(tmp_path: Path) -> None:
    # MoorPy's unload writes ROD TYPES and RODS headers with no rows
    text = SPREAD.read_text().replace("---------------------- POINTS", "\n".join(
        RODS.splitlines()[:3] + ["---------------------- POINTS"]))
    path = tmp_path / "ok.dat"
    path.write_text(text)
    assert read_moordyn(path) == EXPECTED


def test_unknown_point_refused(tmp_path: Path) -> None:
    msg = _bad(tmp_path, "4   wire      7        6", "4   wire      7        9")
    assert msg.startswith("bad.dat line 28: line 4 AttachB = '9': no such point")


def test_unknown_line_type_refused(tmp_path: Path) -> None:
    msg = _bad(tmp_path, "4   wire      7", "4   rope      7")
    assert msg.startswith("bad.dat line 28: line 4 has line type 'rope': no such type")


def test_missing_depth_refused(tmp_path: Path) -> None:
    msg = _bad(tmp_path, "200      WtrDpth   - water depth (m)\n", "")
    assert "WtrDpth" in msg and msg.startswith("bad.dat: no water depth")


def test_malformed_number_refused(tmp_path: Path) -> None:
    msg = _bad(tmp_path, "850.5 ", "85O.5 ")
    assert msg.startswith("bad.dat line 26: line 2 UnstrLen = '85O.5' is not a number")


def test_table_ea_refused(tmp_path: Path) -> None:
    msg = _bad(tmp_path, "1.5e9 ", "chain_ea.txt ")
    assert msg.startswith("bad.dat line 6: line type 'chain' EA = 'chain_ea.txt' is a "
                          "tension-strain table")


def test_depth_from_moorpy_option_name() -> None:
    # MoorPy's unload writes the depth as option "depth" (system.py, unload, MDversion 2)
    assert read_moordyn(DATA / "moorpy_case8.dat")["environment"]["water_depth"] == 100.0


@pytest.mark.parametrize("path", MOORPY_CASES, ids=lambda p: p.name)
def test_moorpy_test_inputs_read(path: Path) -> None:
    data = read_moordyn(path)
    depth = data["environment"]["water_depth"]
    ids = {p["name"] for p in data["points"]}
    for ln in data["lines"]:
        assert {ln["point_a"], ln["point_b"]} <= ids
    for p in data["points"]:
        if p["kind"] != "body":
            assert -1e-9 <= p["position"][2] <= depth   # between seabed and surface


def test_moorpy_written_file(tmp_path: Path) -> None:
    mp = pytest.importorskip("moorpy")
    np = pytest.importorskip("numpy")
    ms = mp.System(depth=200.0)
    ms.setLineType(dnommm=120, material="chain", name="chain")
    ms.setLineType(dnommm=90, material="polyester", name="poly")
    ms.addBody(0, np.array([0.0, 0.0, -10.0, 0.0, 0.0, 0.0]), m=1e6, v=1200.0,
               rCG=np.array([0.0, 0.0, -3.0]))
    for ang in (0.0, 120.0, 240.0):
        c, s = math.cos(math.radians(ang)), math.sin(math.radians(ang))
        ms.addPoint(1, [700 * c, 700 * s, -200.0])
        ms.addPoint(1, [20 * c, 20 * s, -8.0])
        ms.bodyList[0].attachPoint(len(ms.pointList), [20 * c, 20 * s, -8.0])
    ms.addPoint(0, [400.0, 0.0, -150.0], m=8000.0, v=0.5)
    ends = [(1, 7, 350.0, "chain"), (7, 2, 380.0, "poly"), (3, 4, 720.0, "chain"),
            (5, 6, 720.0, "chain")]
    for k, (a, b, length, kind) in enumerate(ends, start=1):
        ms.addLine(length, kind)
        ms.pointList[a - 1].attachLine(k, 0)
        ms.pointList[b - 1].attachLine(k, 1)
    ms.initialize()
    path = tmp_path / "moorpy.dat"
    ms.unload(str(path))
    data = read_moordyn(path)
    assert data["environment"]["water_depth"] == 200.0
    # tolerances: unload's print formats ({:8.3f} lengths, {:8.2f} positions, {:7.3e} EA,
    # {:7.4f} diameters, {:8.2f} masses, {:<7.3f} Cd, {:<7.2f} CdAx): half a last digit
    for ln, mline in zip(data["lines"], ms.lineList, strict=True):
        assert ln["type"] == mline.type["name"]
        assert ln["length"] == pytest.approx(mline.L, abs=5e-4)
    for name, t in data["line_types"].items():
        mt = ms.lineTypes[name]
        assert t["diameter"] == pytest.approx(mt["d_vol"], abs=5e-5)
        assert t["mass_per_length"] == pytest.approx(mt["m"], abs=5e-3)
        assert t["axial_stiffness"] == pytest.approx(mt["EA"], rel=5e-4)
        assert t["normal_drag"] == pytest.approx(mt["Cd"], abs=5e-4)
        assert t["tangential_drag"] == pytest.approx(mt["CdAx"], abs=5e-3)
    body = ms.bodyList[0]
    for p, mpt in zip(data["points"], ms.pointList, strict=True):
        if p["kind"] == "body":
            rel = body.rPointRel[body.attachedP.index(mpt.number)]
            assert p["position"] == pytest.approx(list(rel), abs=5e-3)
        else:
            want = [mpt.r[0], mpt.r[1], mpt.r[2] + 200.0]    # z shifted by the depth
            assert p["position"] == pytest.approx(want, abs=5e-3)
    clump = data["points"][6]
    assert clump["kind"] == "free" and clump["mass"] == 8000.0 and clump["volume"] == 0.5
    b = data["bodies"][0]
    assert b["kind"] == "free" and b["position"] == [0.0, 0.0, 190.0]
    assert b["mass"] == 1e6 and b["center_of_gravity"] == [0.0, 0.0, -3.0]
