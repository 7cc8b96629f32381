"""The cable-ocp command line: solve, JSON, plots, overrides, exit codes."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from cable_ocp.cli import main


def test_solve_json_and_plot(problems, tmp_path, capsys):
    out, png = tmp_path / "s.json", tmp_path / "s.png"
    rc = main(["solve", str(problems / "dezoysa_sea_buggy.toml"), "--json", str(out),
               "--plot", str(png), "--set", "layout.psi0_deg=90"])
    assert rc == 0
    text = capsys.readouterr().out
    for word in ("length", "end_a force", "max tension", "iterations", "wall time",
                 "error estimate", "solved"):
        assert word in text
    data = json.loads(out.read_text())
    assert data["status"] == "solved"
    assert set(data) >= {"status", "length", "end_a", "end_b", "max_tension", "profile",
                         "solver"}
    assert set(data["solver"]) >= {"iterations", "wall_time_s", "constraint_violation",
                                   "error_estimate"}
    np.testing.assert_allclose(data["end_a"]["force"], [1579.9, 3388.9, 1140.1], atol=0.06)
    assert data["end_b"]["force"][2] < 0
    assert len(data["profile"]["s"]) == len(data["profile"]["tension"])
    assert png.stat().st_size > 10_000


def test_json_to_stdout_and_set_position(problems, capsys):
    rc = main(["solve", str(problems / "dezoysa_sea_buggy.toml"), "--json", "-",
               "--set", "end_b.position=[0,229,183]", "--set", "layout.psi0_deg=90"])
    assert rc == 0
    data = json.loads(capsys.readouterr().out)
    assert data["end_b"]["position"] == pytest.approx([0.0, 229.0, 183.0], abs=1e-9)


def test_bad_input_exit_2(problems, capsys):
    rc = main(["solve", str(problems / "dezoysa_sea_buggy.toml"), "--set", "cable.length=-1"])
    assert rc == 2
    assert "cable.length" in capsys.readouterr().err


def test_failed_solve_exit_1_with_diagnostics(problems, tmp_path, capsys):
    """Berteaux's buoy with 1 kN top tension: the cable alone weighs 3.8 kN in water, so no
    equilibrium exists. IPOPT reports infeasibility, the current ramp fails too, and the
    result is a failure with diagnostics, never a profile reported as a solution."""
    out = tmp_path / "f.json"
    rc = main(["solve", str(problems / "berteaux_mooring.toml"), "--set",
               "end_b.tension=1000", "--json", str(out)])
    assert rc == 1
    cap = capsys.readouterr()
    assert "not solved (failed)" in cap.err
    data = json.loads(out.read_text())
    assert data["status"] == "failed"
    assert data["solver"]["constraint_violation"] > 1e-3
    assert data["solver"]["error_estimate"] is None
    assert "continuation" in data["solver"]["continuation"]


def test_python_m_entry_point(problems):
    res = subprocess.run([sys.executable, "-m", "cable_ocp", "solve",
                          str(problems / "berteaux_mooring.toml")],
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    assert "3013" in res.stdout


def test_json_dash_is_stdout_for_every_command(problems, tmp_path, capsys, monkeypatch):
    """'--json -' writes the JSON alone to stdout (no file named '-')."""
    monkeypatch.chdir(tmp_path)
    assert main(["footprint", str(problems / "footprint_tethered_unit.toml"),
                 "--directions", "4", "--json", "-"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["directions"]) == 4 and data["status"] in ("solved", "partial")
    assert not (tmp_path / "-").exists()
