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


@pytest.mark.parametrize("case", ["json-csv", "json-problem", "plot-json", "batch-out"])
def test_colliding_outputs_are_refused_before_the_solve(problems, tmp_path, capsys,
                                                        case: str) -> None:
    """Two outputs onto one file, or an output onto the problem file, is an input error
    (exit 2, one line naming both), found before anything runs or is written (issue 22,
    item 6): `--json X --csv X`, `--json` onto the problem, a `--plot` that is the
    `--json` through another spelling, `batch --out bb --json bb.jsonl`."""
    import shutil

    problem = tmp_path / "p.toml"
    shutil.copy(problems / "dezoysa_sea_buggy.toml", problem)
    before = problem.read_bytes()
    x = tmp_path / "x.png"
    argv = {"json-csv": ["solve", str(problem), "--json", str(x), "--csv", str(x)],
            "json-problem": ["solve", str(problem), "--json", str(problem)],
            "plot-json": ["solve", str(problem), "--json", str(x),
                          "--plot", str(tmp_path / "." / "x.png")],
            "batch-out": ["batch", str(problem), "--grid", "layout.psi0_deg=0,90",
                          "--out", str(tmp_path / "bb"), "--json",
                          str(tmp_path / "bb.jsonl"), "--workers", "1"]}[case]
    rc = main(argv)
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1, err
    assert "the same file as" in err[0] and "give each output its own file" in err[0]
    first = {"json-csv": "--csv", "json-problem": "--json", "plot-json": "--plot",
             "batch-out": "--out"}[case]
    assert err[0].startswith(f"cable-ocp: error: {first} ")
    assert problem.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["p.toml"]


def test_a_problem_that_is_not_a_regular_file_or_too_large_is_refused(problems, tmp_path,
                                                                      capsys):
    """A FIFO (directly, and as a heave scene's ``[unit] cable_scene``) would block the
    open forever, /dev/zero read until memory runs out, an oversized file (17 MiB, sparse)
    be read whole: each is exit 2 with one line (issue 22, item 6). An alarm of 30 s turns a
    regression into a failure instead of a hang."""
    import os
    import signal

    fifo = tmp_path / "fifo.toml"
    os.mkfifo(fifo)
    heave = tmp_path / "h.toml"
    text = (problems / "heave" / "ex_6_3_6_cable.toml").read_text()
    heave.write_text(text.replace('cable_scene = "../dynamics/line_6_3_6.toml"',
                                  f'cable_scene = "{fifo}"'))
    big = tmp_path / "big.toml"
    with big.open("wb") as fh:
        fh.truncate(17 * 2**20)
    cases = [(["solve", str(fifo)], "is not a regular file"),
             (["heave", str(heave)], "is not a regular file"),
             (["solve", "/dev/zero"], "is not a regular file"),
             (["solve", str(big)], "a problem file is at most 16 MiB")]

    def hung(signum, frame):
        raise TimeoutError("the read blocked")

    old = signal.signal(signal.SIGALRM, hung)
    try:
        for argv, words in cases:
            signal.alarm(30)
            rc = main([*argv, "--quiet"])
            signal.alarm(0)
            lines = capsys.readouterr().err.strip().splitlines()
            assert rc == 2 and len(lines) == 1, (argv, lines)
            assert words in lines[0], lines
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


@pytest.mark.parametrize("option", ["--json", "--csv"])
def test_an_output_onto_a_pipe_is_refused_and_the_pipe_kept(problems, tmp_path, capsys,
                                                            option: str) -> None:
    """An output path that is not a regular file (a FIFO here; a device such as /dev/full
    alike) is exit 2 with one line, before the solve: the whole-or-nothing write renames a
    temporary file over its path, which would replace the pipe (or, for root, the device)
    by a regular file."""
    import os
    import stat

    fifo = tmp_path / "out.fifo"
    os.mkfifo(fifo)
    rc = main(["solve", str(problems / "dezoysa_sea_buggy.toml"), option, str(fifo)])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1, err
    assert err[0].startswith(f"cable-ocp: error: {option} {fifo}: is not a regular file")
    assert stat.S_ISFIFO(fifo.stat().st_mode)


@pytest.mark.parametrize("command", ["heave", "batch"])
def test_an_output_onto_the_cable_scene_is_refused(problems, tmp_path, capsys,
                                                   command: str) -> None:
    """An output onto the dynamic scene that the problem file's `[unit] cable_scene` names
    (an input too) is refused, exit 2 with one line naming it, and the scene is untouched."""
    import re
    import shutil

    src = problems / "heave" / "ex_6_3_6_cable.toml"
    text = src.read_text()
    name = re.search(r'cable_scene\s*=\s*"([^"]+)"', text).group(1)
    shutil.copy((src.parent / name).resolve(), tmp_path / "cable.toml")
    problem = tmp_path / "h.toml"
    problem.write_text(text.replace(f'"{name}"', '"cable.toml"'))
    scene = tmp_path / "cable.toml"
    before = scene.read_bytes()
    argv = {"heave": ["heave", str(problem), "--json", str(scene)],
            "batch": ["batch", str(problem), "--grid", "simulation.duration=1,2",
                      "--out", str(tmp_path / "bb"), "--json", str(scene), "--workers", "0"]}
    rc = main(argv[command])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1, err
    assert err[0].startswith(f"cable-ocp: error: --json {scene}: the same file as the input "
                             "[unit] cable_scene"), err[0]
    assert scene.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cable.toml", "h.toml"]
