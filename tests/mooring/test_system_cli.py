"""``cable-ocp solve`` and ``cable-ocp batch`` on a mooring system: exit codes, the JSON, the
CSV, one line on bad input with nothing written (CONVENTIONS "Exit codes")."""

from __future__ import annotations

import csv
import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SPAR = ROOT / "problems" / "systems" / "spar_3line.toml"


def run(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "cable_ocp", *args], cwd=cwd,
                          capture_output=True, text=True, timeout=300)


def test_solve_writes_json_and_csv_that_agree(tmp_path):
    r = run("solve", str(SPAR), "--json", "s.json", "--csv", "s.csv", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    doc = json.loads((tmp_path / "s.json").read_text())
    assert doc["status"] == "solved" and doc["kind"] == "system"
    body = doc["bodies"][0]
    # the external 1 MN surge load is carried by the mooring: its x force is -1 MN to the
    # system tolerance (1e-8 of ~2.4 MN) -- the body's own load has no x component
    assert abs(body["mooring_force"][0] + 1.0e6) < 0.1
    k = body["stiffness"]["mooring"]
    assert len(k) == 6 and all(len(row) == 6 for row in k) and k[0][0] > 0
    with open(tmp_path / "s.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert [r["line"] for r in rows] == ["L1", "L2", "L3"]
    for row, line in zip(rows, doc["lines"], strict=True):
        assert float(row["max_tension [N]"]) == pytest.approx(line["max_tension"], rel=1e-12)
        assert float(row["laid_length [m]"]) == pytest.approx(line["laid_length"], abs=1e-9)
    assert "L1" in r.stdout and "mooring stiffness of spar" in r.stdout
    for line in doc["lines"]:
        anchor = line["anchor_a"]
        # the anchor's loads are the line's force on it: the horizontal part, and the
        # vertical part as uplift (the line pulls up); a line lying on the seabed at the
        # anchor (laid length > 0) lifts nothing off it
        assert anchor["horizontal"] == pytest.approx(math.hypot(*line["force_a"][:2]))
        assert anchor["vertical"] == line["force_a"][2]
        if line["laid_length"] > 0:
            assert abs(anchor["vertical"]) < 1e-6 * line["tension_a"]
        else:
            assert anchor["vertical"] > 0.01 * line["tension_a"]


@pytest.mark.parametrize("edits, words", [
    (["lines.1.point_b=a2"], "point_a and point_b are both 'a2'"),
    (["lines.1.type=rope"], "lines[1].type = 'rope': no such line type"),
    # every fairlead on the spar's axis: nothing resists a yaw (found in the solve)
    ([f"points.{i}.position=[0.0,0.0,-70.0]" for i in (3, 4, 5)],
     "body 'spar' yaw has no restoring"),
])
def test_bad_system_is_one_line_exit_2_and_nothing_written(tmp_path, edits, words):
    sets = [a for e in edits for a in ("--set", e)]
    r = run("solve", str(SPAR), *sets, "--json", "o.json", "--csv", "o.csv", cwd=tmp_path)
    assert r.returncode == 2
    assert r.stderr.strip().count("\n") == 0 and words in r.stderr
    assert not (tmp_path / "o.json").exists() and not (tmp_path / "o.csv").exists()


def test_batch_over_a_systems_key(tmp_path):
    """Two cases of the line length: the longer L1 carries less tension and lies longer
    on the seabed; each case's columns equal a solve of that case."""
    r = run("batch", str(SPAR), "--grid", "lines.0.length=895.0,910.0", "--out", "b",
            "--workers", "1", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    with open(tmp_path / "b.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 2
    t = [float(row["L1_max_tension [N]"]) for row in rows]
    laid = [float(row["L1_laid_length [m]"]) for row in rows]
    assert t[1] < t[0] and laid[1] > laid[0]
    from cable_ocp.mooring import solve_system
    from cable_ocp.scene.system import load_system

    ref = solve_system(load_system(SPAR, {"lines.0.length": 910.0}), stiffness=False)
    # 1e-7: the batch case is warm-started from the other case, the reference is cold;
    # both stop at the system tolerance
    assert t[1] == pytest.approx(ref.line("L1")["max_tension"], rel=1e-7)


def test_mooring_checks_command(tmp_path):
    """The three checks in one command: the restoring curve through zero at the neutral
    position and rising; the headings 120 deg apart equal (the spread's symmetry); the
    failures of L2 and L3 mirror images; the JSON holds what the table shows."""
    r = run("mooring-checks", str(SPAR), "--offsets=-10:10:3", "--headings", "0:240:3",
            "--json", "c.json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    doc = json.loads((tmp_path / "c.json").read_text())
    f = doc["offset_curve"]["restoring_force"]
    # 1e-6 of the 10 m value: the neutral position is an equilibrium to the tolerance
    assert abs(f[1]) < 1e-6 * abs(f[2]) and f[0] < 0 < f[2]
    t = doc["headings"]["max_tension"]
    assert t[0] == pytest.approx(t[1], rel=1e-6) and t[1] == pytest.approx(t[2], rel=1e-6)
    fail = doc["line_failure"]
    assert fail["removed"] == ["L1", "L2", "L3"]
    assert fail["max_tension"][1] == pytest.approx(fail["max_tension"][2], rel=1e-6)
    assert "line failure" in r.stdout


def test_a_moordyn_deck_with_rods_is_one_line_exit_2(tmp_path):
    """A section we do not model, with rows: refused with the file's line, nothing written."""
    deck = (ROOT / "tests" / "data" / "moordyn" / "moorpy_case1.dat").read_text()
    rods = ("---------------------- ROD TYPES ----------------------\n"
            "Name  Diam  Mass/m  Cd  Ca  CdEnd  CaEnd\n(-) (m) (kg/m) (-) (-) (-) (-)\n"
            "pile  2.0  500.0  1.0  1.0  0.0  0.0\n")
    lines = deck.splitlines(keepends=True)
    at = next(k for k, ln in enumerate(lines) if ln.startswith("-") and "OPTIONS" in ln)
    (tmp_path / "rods.dat").write_text("".join(lines[:at]) + rods + "".join(lines[at:]))
    r = run("solve", "rods.dat", "--json", "o.json", cwd=tmp_path)
    assert r.returncode == 2 and "ROD TYPES" in r.stderr and "not modelled" in r.stderr
    assert r.stderr.strip().count("\n") == 0 and not (tmp_path / "o.json").exists()
