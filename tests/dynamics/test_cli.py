"""``cable-ocp simulate`` and ``cable-ocp modes``: the output contract on dynamic scenes."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import pytest

from cable_ocp.cli import main

ROOT = Path(__file__).resolve().parents[2]
AIR = ROOT / "problems" / "dynamics" / "vertical_in_air.toml"


def test_simulate_json_fields_and_csv(tmp_path: Path) -> None:
    """The JSON has the issue's fields (strict JSON, envelope), the CSV one row per sample
    with node positions and element tensions; a clean run exits 0."""
    js, cs = tmp_path / "s.json", tmp_path / "s.csv"
    rc = main(["simulate", str(AIR), "--set", "simulation.duration=1.0", "--json", str(js),
               "--csv", str(cs), "--quiet"])
    assert rc == 0
    d = json.loads(js.read_text())
    for key in ("status", "message", "warnings", "version", "t", "length", "top_position",
                "unit_position", "top_tension", "min_tension", "slack", "wall_time_s"):
        assert key in d, key
    assert d["status"] == "solved" and d["slack"]["occurred"] is False
    n = len(d["t"])
    assert len(d["top_position"]) == n and len(d["top_position"][0]) == 3
    rows = list(csv.reader(cs.open()))
    assert len(rows) == n + 1
    assert rows[0][:2] == ["t [s]", "length [m]"] and "element0_tension [N]" in rows[0]
    assert math.isclose(float(rows[-1][0]), d["t"][-1])


def test_simulate_slack_exits_1(tmp_path: Path) -> None:
    """Huang's 3.3.1 rope started impulsively at 2 Hz goes slack: status "slack", where and
    when, exit 1."""
    js = tmp_path / "s.json"
    rc = main(["simulate", str(ROOT / "problems" / "dynamics" / "huang_3_3_1_impulsive.toml"),
               "--set", "simulation.duration=1.0", "--json", str(js), "--quiet"])
    d = json.loads(js.read_text())
    assert rc == 1 and d["status"] == "slack"
    assert d["slack"]["occurred"] and d["slack"]["first_time"] > 0


def test_modes_json_and_deployment_chart(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    """modes --json: ascending frequencies, one shape row per node; --lengths: a chart whose
    first frequency falls with length."""
    assert main(["modes", str(AIR), "--count", "3", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    w = [m["frequency_rad_s"] for m in d["modes"]]
    assert w == sorted(w) and len(w) == 3
    assert all(len(row) == 3 for row in d["modes"][0]["shape"])
    assert d["modes"][0]["period_s"] == pytest.approx(2 * math.pi / w[0])
    assert main(["modes", str(AIR), "--count", "2", "--lengths", "50:150:3", "--json",
                 "-", "--quiet"]) == 0
    chart = json.loads(capsys.readouterr().out)
    first = [row[0] for row in chart["frequencies_rad_s"]]
    assert first[0] > first[1] > first[2]


@pytest.mark.parametrize("args,needle", [
    (["simulate", "problems/dezoysa_sea_buggy.toml"], "cable-ocp solve"),
    (["solve", "problems/dynamics/vertical_in_air.toml"], "cable-ocp simulate"),
    (["modes", "problems/dynamics/vertical_in_air.toml", "--lengths", "1:2"], "START:STOP:N"),
    (["simulate", "problems/dynamics/vertical_in_air.toml", "--set",
      "simulation.time_step=-1"], "simulation.time_step"),
])
def test_input_errors_exit_2(args: list[str], needle: str, capsys: pytest.CaptureFixture,
                             monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(ROOT)
    assert main(args) == 2
    assert needle in capsys.readouterr().err


@pytest.mark.parametrize("command", ["simulate", "modes"])
def test_a_run_that_would_take_hours_is_refused_before_any_work(
        command: str, capsys: pytest.CaptureFixture) -> None:
    """100 000 lumped-mass segments: exit 2 at once with the estimate and the key (the run
    itself would build for hours and need tens of GB); every shipped dynamic scene is far
    below the limits (checked by the same estimate)."""
    from cable_ocp.cli.cost import dynamics_cost
    from cable_ocp.dynamics import load_dynamic_scene

    src = ROOT / "problems" / "dynamics" / "huang_5_7.toml"
    rc = main([command, str(src), "--set", "simulation.segments=100000", "--quiet"])
    err = capsys.readouterr().err
    assert rc == 2
    assert "simulation.segments = 100000" in err and "--force" in err
    for path in sorted((ROOT / "problems" / "dynamics").glob("*.toml")):
        cost = dynamics_cost(load_dynamic_scene(path))
        assert not cost.too_much, (path.name, cost.describe())


def test_modes_lengths_out_of_bounds_is_one_line_before_the_plan(problems, capsys) -> None:
    """``modes --lengths`` whose longest length is outside ``cable.length``'s bounds is an
    input error found before the plan line: exactly one line on stderr, exit 2 (issue 22,
    item 6: the plan line came first, two lines)."""
    from cable_ocp.cli import main

    rc = main(["modes", str(problems / "dynamics" / "huang_3_3_5.toml"), "--lengths",
               "100:1e9:15"])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1, err
    assert err[0].startswith("cable-ocp: error: cable.length = 1000000000.0")


def test_interrupted_modes_lengths_keeps_the_lengths_it_finished(
        tmp_path: Path, capsys: pytest.CaptureFixture, monkeypatch: pytest.MonkeyPatch) -> None:
    """A Ctrl-C during `modes --lengths` (here while the fourth of five lengths is solved)
    ends with exit 130 and one stderr line, after writing the chart of the lengths that
    finished: JSON with status `interrupted`, the CSV's rows, each frequency equal to the
    uninterrupted run's (the same solves)."""
    from cable_ocp.dynamics import modal

    argv = ["modes", str(AIR), "--count", "2", "--lengths", "50:150:5", "--quiet"]
    assert main([*argv, "--json", str(tmp_path / "full.json")]) == 0
    full = json.loads((tmp_path / "full.json").read_text())
    calls = []
    real = modal.model_for

    def stopping(scene):  # the fourth length's model: as if Ctrl-C landed in its solve
        calls.append(scene)
        if len(calls) == 4:
            raise KeyboardInterrupt
        return real(scene)

    monkeypatch.setattr(modal, "model_for", stopping)
    capsys.readouterr()
    rc = main([*argv, "--json", str(tmp_path / "cut.json"), "--csv", str(tmp_path / "cut.csv")])
    assert rc == 130
    assert capsys.readouterr().err.strip().splitlines() == ["cable-ocp: interrupted"]
    cut = json.loads((tmp_path / "cut.json").read_text())
    assert cut["status"] == "interrupted" and "3 of 5 lengths" in cut["message"]
    assert cut["lengths"] == full["lengths"][:3]
    assert cut["frequencies_rad_s"] == full["frequencies_rad_s"][:3]
    with open(tmp_path / "cut.csv") as fh:
        rows = list(csv.reader(fh))
    assert len(rows) == 1 + 3 and float(rows[3][1]) == pytest.approx(
        full["frequencies_rad_s"][2][0], rel=1e-12)
