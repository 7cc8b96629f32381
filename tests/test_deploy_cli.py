"""``cable-ocp deploy``: the optimal pay-out schedule's text, JSON, CSV and figure, the exit
codes of an infeasible problem and a bad key, the interruption, the resonant lengths.

One solve of problems/dynamics/deploy_small.toml (a few s) is shared by the module's tests.
"""

from __future__ import annotations

import contextlib
import csv
import dataclasses
import io
import json
import math
import re
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from cable_ocp.cli import main
from cable_ocp.cli.output import EXIT_INPUT, EXIT_INTERRUPTED, EXIT_NOT_SUCCESS, EXIT_OK

SMALL = Path(__file__).resolve().parents[1] / "problems" / "dynamics" / "deploy_small.toml"
#: the unit's weight in water and the cable's (deploy_small.toml), N and N/m
W_UNIT, W_CABLE = 42645.0, 53.19


@pytest.fixture(scope="module")
def run(tmp_path_factory: pytest.TempPathFactory) -> SimpleNamespace:
    """``cable-ocp deploy deploy_small.toml --json --csv --plot``, once; the library's result
    recorded (for the interruption test)."""
    import cable_ocp.schedule.planning as planning

    tmp = tmp_path_factory.mktemp("deploy")
    paths = SimpleNamespace(json=tmp / "d.json", csv=tmp / "d.csv", plot=tmp / "d.png")
    seen: list = []
    real = planning.verified_schedule

    def recording(*a, **k):
        seen.append(real(*a, **k))
        return seen[-1]

    buf, err = io.StringIO(), io.StringIO()
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(planning, "verified_schedule", recording)
        with contextlib.redirect_stdout(buf), contextlib.redirect_stderr(err):
            rc = main(["deploy", str(SMALL), "--json", str(paths.json), "--csv",
                       str(paths.csv), "--plot", str(paths.plot)])
    with paths.csv.open() as f:
        rows = list(csv.reader(f))
    return SimpleNamespace(rc=rc, text=buf.getvalue(), err=err.getvalue(), paths=paths,
                           data=json.loads(paths.json.read_text()), header=rows[0],
                           table=np.array([[float(v) if v else math.nan for v in r]
                                           for r in rows[1:]]),
                           result=seen[0])


def test_deploy_models_the_checks_hold_by_default(run):
    # the OCP keeps the limits through the forward check's hold after the arrival: 40 more
    # steps of 0.5 s (deploy_small's time_step), reported on the size row
    from cable_ocp.schedule.forward import CHECK_HOLD

    d = run.result.diagnostics
    assert d["hold_steps"] == math.ceil(CHECK_HOLD / 0.5) == 40
    assert d["hold_s"] == pytest.approx(CHECK_HOLD, rel=1e-9)
    assert f"(the last 40: the {CHECK_HOLD:g} s hold after the arrival)" in run.text


def test_deploy_text_reports_status_times_and_binding_limits(run):
    assert run.rc == EXIT_OK
    for word in ("solved", "time to depth", "constant speed", "saving", "binding limits",
                 "tension_min", "steps", "elements", "variables", "build", "solve"):
        assert word in run.text, word
    assert "wrote" in run.err
    # the saving against the warm start: 100 (T_0 - T) / T_0, as printed (3 digits)
    ws, dur = run.data["warm_start"]["duration_s"], run.data["duration_s"]
    shown = re.search(r"constant speed .*saving ([0-9.]+) %", run.text)
    assert float(shown.group(1)) == pytest.approx(100.0 * (ws - dur) / ws, rel=5e-3)
    assert re.search(rf"time to depth\s+{dur:.4g} s", run.text)


def test_no_saving_is_claimed_against_a_constant_speed_that_breaks_the_limits(run, capsys):
    """The constant-speed row of a case where no constant speed keeps the limits (the 6.3.6
    line: the warm start's slowest, 5355 s, was called a saving of 89.9 %) names the
    speed and claims no saving; a feasible one gives the saving, 100 (T_0 - T) / T_0."""
    import argparse

    import cable_ocp.cli.deploy as dep
    from cable_ocp.scene.dynamics import load_dynamic_scene
    from cable_ocp.schedule.sea import vessel_motions

    res = run.result
    scene = load_dynamic_scene(SMALL)
    args = argparse.Namespace(json=None, csv=None, quiet=True)
    bad = dataclasses.replace(res, warm_start=dataclasses.replace(res.warm_start,
                                                                  feasible=False))
    dep._text(args, scene, bad, vessel_motions(scene), {}, "t")
    (row,) = [x for x in capsys.readouterr().out.splitlines()
              if x.startswith("constant speed")]
    assert "none keeps the limits" in row and "no saving" in row and "%" not in row
    assert f"{res.warm_start.speed:.4g} m/s" in row
    dep._text(args, scene, res, vessel_motions(scene), {}, "t")
    (row,) = [x for x in capsys.readouterr().out.splitlines()
              if x.startswith("constant speed")]
    ws = res.warm_start.duration
    assert f"saving {100.0 * (ws - res.duration) / ws:.3g} %" in row


def test_the_readme_deploy_sample_is_this_run(run):
    """The README's ``cable-ocp deploy problems/dynamics/deploy_small.toml`` sample is this
    run's standard output (the same command, output files added), by the rules of
    tests/test_readme_outputs.py (which leaves this sample to this test: one solve)."""
    from test_readme_outputs import CHECKED_ELSEWHERE, ROOT, samples, shown_lines_missing

    cmd = "cable-ocp deploy problems/dynamics/deploy_small.toml"
    assert CHECKED_ELSEWHERE[cmd].endswith(
        "test_deploy_cli.py::test_the_readme_deploy_sample_is_this_run")
    shown = dict(samples((ROOT / "README.md").read_text(encoding="utf-8")))[cmd]
    assert len([line for line in shown if line.strip()]) >= 5
    assert shown_lines_missing(shown, run.text) == []


def test_deploy_json_duration_is_the_csv_last_time_and_beats_the_warm_start(run):
    d = run.data
    assert d["status"] == "solved"
    assert set(d) >= {"status", "message", "version", "binding", "duration_s", "warm_start",
                      "schedule", "realisations", "diagnostics"}
    t = run.table[:, 0]
    # the JSON and the CSV carry the same float (repr): equal but for JSON's round trip
    assert d["duration_s"] == pytest.approx(t[-1], rel=1e-14)
    assert d["duration_s"] == pytest.approx(run.result.duration, rel=1e-14)
    ws = d["warm_start"]
    assert ws["feasible"]
    # the warm start is a feasible point of the OCP: the optimum is no longer (IPOPT's
    # tolerance on the duration, 1e-6 relative)
    assert d["duration_s"] <= ws["duration_s"] * (1.0 + 1e-6)
    # the warm start's trapezoid, closed form: T = dist / v + v / a (the cruise reached)
    assert ws["duration_s"] == pytest.approx(100.0 / ws["speed_m_s"] + ws["speed_m_s"] / 0.2,
                                             rel=1e-12)


def test_deploy_csv_schedule_keeps_its_kinematics_and_limits(run):
    h = run.header
    assert h[:4] == ["t [s]", "L [m]", "v [m/s]", "a [m/s^2]"]
    assert h[4:] == ["r0_tension_min [N]", "r0_tension_max [N]", "r0_unit_tension [N]",
                     "r0_top_tension [N]"]
    t, length, v, a = run.table[:, 0], run.table[:, 1], run.table[:, 2], run.table[:, 3]
    # rest to rest, 50 -> 150 m; the constraints hold to IPOPT's tolerance (1e-8 absolute
    # on the scaled rows; 1e-6 relative allowed here)
    assert length[0] == 50.0 and length[-1] == pytest.approx(150.0, abs=1e-6)
    assert v[0] == pytest.approx(0.0, abs=1e-6) and v[-1] == pytest.approx(0.0, abs=1e-6)
    assert math.isnan(a[-1])
    assert np.all(np.abs(a[:-1]) <= 0.2 * (1 + 1e-6))
    assert np.all(v <= 3.0 * (1 + 1e-6))
    # the OCP's kinematics, recomputed: v by the step's acceleration, L by the trapezoid
    dt = np.diff(t)
    np.testing.assert_allclose(np.diff(v), a[:-1] * dt, atol=1e-7)
    np.testing.assert_allclose(np.diff(length), 0.5 * dt * (v[1:] + v[:-1]), atol=1e-7)
    tmin, tmax = run.table[:, 4], run.table[:, 5]
    assert np.all(tmin >= 1e4 * (1 - 1e-6)) and np.all(tmax <= 1.2e5 * (1 + 1e-6))
    assert np.all(tmin <= tmax)
    # at rest at the start: the pull on the unit is its weight in water, the top tension
    # W + w L (the static line; 1e-9 relative: the static solve's round-off)
    assert run.table[0, 6] == pytest.approx(W_UNIT, rel=1e-9)
    assert run.table[0, 7] == pytest.approx(W_UNIT + W_CABLE * 50.0, rel=1e-9)
    # along the line at rest, each of the 5 elements' tension at its middle: the smallest
    # W + w L / 10 (element 0), the largest W + w L 9 / 10 (element 4)
    assert tmin[0] == pytest.approx(W_UNIT + W_CABLE * 5.0, rel=1e-9)
    assert tmax[0] == pytest.approx(W_UNIT + W_CABLE * 45.0, rel=1e-9)


def test_deploy_schedule_keeps_its_limits_on_a_finer_forward_simulation(run):
    """The 1 % check of docs/deployment.md, "Checks": the OCP alone (0.5 s midpoint steps
    on 5 elements) breaks tension_min on the forward simulator (20 elements, 0.05 s) by far
    more than 1 %; re-solved with the margins the check finds, the schedule keeps every
    limit to 1 % there, and on a forward simulation finer than the check's own."""
    from cable_ocp.scene.dynamics import load_dynamic_scene
    from cable_ocp.schedule.forward import Schedule, resimulate
    from cable_ocp.schedule.sea import vessel_motions

    res = run.result
    checks = res.checks
    assert res.status == "solved" and len(checks) >= 2
    # 21 % seen: the transcription's error at 0.5 s, which the check exists to catch
    assert checks[0].margins == {} and checks[0].violations["tension_min"] > 0.1
    assert all(v <= 0.01 for v in checks[-1].violations.values())
    assert checks[-1].failed_runs == 0
    # each round moves the limit by the excess seen plus half the tolerance (0.5 %), of
    # tension_min = 10 kN; the sums are exact but for round-off
    for a, b in zip(checks, checks[1:], strict=False):
        assert a.violations["tension_min"] > 0.01
        assert b.margins["tension_min"] == pytest.approx(
            a.margins.get("tension_min", 0.0) + (a.violations["tension_min"] + 0.005) * 1e4,
            rel=1e-12)
    margin = checks[-1].margins["tension_min"]
    # the final OCP keeps the line's tensions (its elements and both ends: tension_at =
    # "line") the margin above the limit: the CSV's smallest of them is tension_min +
    # margin (IPOPT's tolerance, 1e-6 relative)
    assert np.min(run.table[1:, 4:8]) == pytest.approx(1e4 + margin, rel=1e-6)
    assert np.min(run.table[1:, 4]) >= (1e4 + margin) * (1 - 1e-6)
    # the round count in the JSON and the diagnostics
    assert len(run.data["checks"]) == len(checks)
    assert run.data["diagnostics"]["check_rounds"] == len(checks) - 1
    assert run.data["checks"][0]["violations"]["tension_min"] == pytest.approx(
        checks[0].violations["tension_min"], rel=1e-14)
    assert f"{len(checks) - 1} re-solve(s)" in run.text and "re-simulated" in run.text
    # independent of the check: 40 elements at 0.01 s (5 and 2 times finer than it)
    scene = load_dynamic_scene(SMALL)
    sol = res.solution
    sched = Schedule.from_speed(sol.time, sol.speed, scene.length)
    fine = resimulate(scene, sched, vessel_motions(scene)[0], time_step=0.01, segments=40)
    assert fine.keeps_limits(0.01), fine.violations


def test_deploy_plot_written(run):
    assert run.paths.plot.stat().st_size > 20_000


def test_deploy_infeasible_tension_max_exits_1_and_writes_no_schedule(tmp_path, capsys):
    """tension_max below the static tension W + w L = 50.6 kN at the target (150 m): no
    schedule; the message names tension_max; the JSON carries the status, no schedule."""
    js, cs, png = tmp_path / "f.json", tmp_path / "f.csv", tmp_path / "f.png"
    rc = main(["deploy", str(SMALL), "--set", "deployment.tension_max=48000", "--json",
               str(js), "--csv", str(cs), "--plot", str(png)])
    assert rc == EXIT_NOT_SUCCESS
    cap = capsys.readouterr()
    assert "infeasible" in cap.out and "tension_max" in cap.out
    assert "no CSV or figure" in cap.err
    d = json.loads(js.read_text())
    assert d["status"] == "infeasible" and "tension_max" in d["message"]
    assert d["binding"] == ["tension_max"]
    assert d["schedule"] is None and d["duration_s"] is None
    assert not cs.exists() and not png.exists()


def test_deploy_schedule_the_check_rejects_is_not_a_schedule(tmp_path, capsys, monkeypatch):
    """A re-simulation that breaks a limit no margin moves (speed_max: the schedule's own)
    ends "failed" at once (no re-solve), exit 1, the limit named, no schedule written."""
    import cable_ocp.schedule.planning as planning

    real = planning.resimulate
    calls = []

    def broken(*a, **k):
        chk = real(*a, **k)
        calls.append(chk)
        return dataclasses.replace(chk, violations={**chk.violations, "speed_max": 0.02})

    monkeypatch.setattr(planning, "resimulate", broken)
    js, cs = tmp_path / "c.json", tmp_path / "c.csv"
    rc = main(["deploy", str(SMALL), "--json", str(js), "--csv", str(cs)])
    assert rc == EXIT_NOT_SUCCESS and len(calls) == 1
    d = json.loads(js.read_text())
    assert d["status"] == "failed" and "speed_max by 2 %" in d["message"]
    assert "speed_max" in d["binding"] and d["schedule"] is None
    assert len(d["checks"]) == 1 and d["diagnostics"]["check_rounds"] == 0
    assert not cs.exists()


def test_deploy_ctrl_c_in_the_forward_check_writes_nothing_and_exits_130(tmp_path, capsys,
                                                                         monkeypatch):
    """A Ctrl-C while the schedule is re-simulated (the simulator returns "interrupted"):
    the result is "interrupted", nothing is written, exit 130."""
    import cable_ocp.schedule.planning as planning

    real = planning.resimulate

    def stopped(*a, **k):
        return dataclasses.replace(real(*a, **k), status="interrupted")

    monkeypatch.setattr(planning, "resimulate", stopped)
    js = tmp_path / "i.json"
    assert main(["deploy", str(SMALL), "--json", str(js)]) == EXIT_INTERRUPTED
    assert "interrupted" in capsys.readouterr().err
    assert not js.exists()


#: a sea on deploy_small, 2 unseen realisations, re-simulated coarsely (0.2 s, 5 elements:
#: the counts' bookkeeping, not their accuracy, is tested here)
SEA = ["--set", "deployment.sea.significant_height=0.5", "--set",
       "deployment.sea.peak_frequency=0.6", "--set", "deployment.sea.unseen=2",
       "--set", "deployment.check_time_step=0.2", "--set", "deployment.check_segments=5"]


def test_deploy_unseen_counts_are_the_runs_on_the_unseen_seas(run, tmp_path, monkeypatch,
                                                               capsys):
    """--unseen: the schedule and the constant speed of its duration re-simulated on the
    sea's unseen realisations; the counts against resimulate's own runs, the constant
    speed against the smaller root of v^2 - a T v + a D = 0 (deploy_small's schedule,
    solved in its own heave, stands in for one solved on the sea)."""
    import cable_ocp.schedule.planning as planning
    from cable_ocp.scene.dynamics import load_dynamic_scene
    from cable_ocp.schedule.forward import Schedule, resimulate
    from cable_ocp.schedule.sea import vessel_motions

    monkeypatch.setattr(planning, "verified_schedule", lambda *a, **k: run.result)
    js = tmp_path / "u.json"
    assert main(["deploy", str(SMALL), *SEA, "--unseen", "--json", str(js)]) == EXIT_OK
    text = capsys.readouterr().out
    u = json.loads(js.read_text())["unseen"]
    scene = load_dynamic_scene(SMALL, {"deployment.sea.significant_height": 0.5,
                                       "deployment.sea.peak_frequency": 0.6,
                                       "deployment.sea.unseen": 2})
    assert u["time_step_s"] == 0.2 and u["segments"] == 5
    seas = vessel_motions(scene, "unseen")
    assert u["motions"] == [m.name for m in seas] and len(seas) == 2
    sol = run.result.solution
    mine = [resimulate(scene, Schedule.from_speed(sol.time, sol.speed, 50.0), m,
                       time_step=0.2, segments=5) for m in seas]
    opt = u["schedules"]["optimal"]
    assert opt["runs"] == 2 and opt["duration_s"] == pytest.approx(sol.duration, rel=1e-14)
    assert opt["slack"] == sum(c.slack for c in mine)
    assert opt["under_tension_min"] == sum(c.violations["tension_min"] > 0.01 for c in mine)
    assert opt["keeps_limits"] == sum(c.keeps_limits(0.01) for c in mine)
    # T = D / v + v / a: a = 0.2 m/s^2, D = 100 m
    a, d, t = 0.2, 100.0, sol.duration
    v = (a * t - math.sqrt((a * t) ** 2 - 4 * a * d)) / 2
    assert u["constant_speed_m_s"] == pytest.approx(v, rel=1e-9)
    assert u["schedules"]["constant"]["duration_s"] == pytest.approx(t, rel=1e-12)
    assert "unseen seas" in text and "2 realisations" in text


def test_deploy_receding_keeps_the_checks_margins(run, tmp_path, monkeypatch):
    """--receding: the horizon gets the limits moved in by the forward check's margins,
    the open-loop schedule and the unseen seas; its counts go to the JSON."""
    import cable_ocp.schedule.planning as planning
    import cable_ocp.schedule.receding as receding

    seen = {}

    def fake(scene, motions, open_loop, **kw):
        seen.update(kw, motions=[m.name for m in motions], open_loop=open_loop)
        c = {"runs": 2, "slack": 0, "over_tension_max": 0, "under_tension_min": 1,
             "keeps_limits": 1, "failed": 0}
        return receding.RecedingComparison("solved", (), open_loop.duration,
                                           {"open_loop": c, "receding": c}, 0.01)

    monkeypatch.setattr(planning, "verified_schedule", lambda *a, **k: run.result)
    monkeypatch.setattr(receding, "compare_receding", fake)
    js = tmp_path / "r.json"
    assert main(["deploy", str(SMALL), *SEA, "--receding", "--json", str(js)]) == EXIT_OK
    margin = run.result.margins["tension_min"]
    assert seen["problem"].tension_min == pytest.approx(1e4 + margin, rel=1e-15)
    assert seen["problem"].tension_max == 1.2e5 and len(seen["motions"]) == 2
    assert seen["open_loop"].duration == pytest.approx(run.result.duration, rel=1e-14)
    r = json.loads(js.read_text())["receding"]
    assert r["counts"]["receding"]["under_tension_min"] == 1
    assert r["margins"]["tension_min"] == pytest.approx(margin, rel=1e-15)


def test_deploy_unseen_without_a_sea_exits_2(capsys):
    assert main(["deploy", str(SMALL), "--receding"]) == EXIT_INPUT
    assert "[deployment.sea]" in capsys.readouterr().err


def test_deploy_bad_key_names_the_key(capsys):
    rc = main(["deploy", str(SMALL), "--set", "deployment.speed_mx=1"])
    assert rc == EXIT_INPUT
    assert "deployment.speed_mx" in capsys.readouterr().err


@pytest.mark.parametrize("argv, word", [(["--segments", "0"], "--segments"),
                                        (["--time-step", "-1"], "--time-step"),
                                        (["--check-rounds", "11"], "--check-rounds"),
                                        (["--hold", "-1"], "--hold -1.0: give 0..600 s"),
                                        (["--hold", "nan"], "--hold nan: give 0..600 s"),
                                        (["--set", "deployment.hold=601"],
                                         "deployment.hold = 601: must be in [0, 600] (s)"),
                                        (["--set", "deployment.check_tolerance=0.5"],
                                         "deployment.check_tolerance"),
                                        (["--set", "deployment.check_rounds=-1"],
                                         "deployment.check_rounds")])
def test_deploy_bad_options_exit_2(argv, word, capsys):
    assert main(["deploy", str(SMALL), *argv]) == EXIT_INPUT
    assert word in capsys.readouterr().err


def test_deploy_without_a_deployment_table_exits_2(problems, capsys):
    rc = main(["deploy", str(problems / "dynamics" / "huang_3_3_5.toml")])
    assert rc == EXIT_INPUT
    assert "[deployment]" in capsys.readouterr().err


def test_deploy_interrupted_comparison_writes_the_schedule_then_130(run, tmp_path, capsys,
                                                                    monkeypatch):
    """A Ctrl-C in --compare's bisection: the finished schedule is written (the comparison
    marked interrupted), then the one line and exit 130."""
    import cable_ocp.schedule.forward as forward
    import cable_ocp.schedule.planning as planning

    def stop(*a, **k):
        raise KeyboardInterrupt

    monkeypatch.setattr(planning, "verified_schedule", lambda *a, **k: run.result)
    monkeypatch.setattr(forward, "fastest_constant_speed", stop)
    js, cs = tmp_path / "i.json", tmp_path / "i.csv"
    rc = main(["deploy", str(SMALL), "--compare", "--json", str(js), "--csv", str(cs)])
    assert rc == EXIT_INTERRUPTED
    assert "interrupted" in capsys.readouterr().err
    d = json.loads(js.read_text())
    assert d["status"] == "solved" and d["compare"]["status"] == "interrupted"
    assert d["duration_s"] == pytest.approx(run.data["duration_s"], rel=1e-14)
    assert cs.exists()


def test_resonant_lengths_meet_the_rod_with_a_tip_mass():
    """omega_1(L) = sqrt(EA / (L M)) (a massless rod with the tip mass M, the estimate of
    Huang 3.3.5 (5)) meets w at L = EA / (w^2 M); on 201 lengths the chord's error is
    below 1e-3 relative (the curve's convexity over one interval)."""
    from cable_ocp.plots.deploy import resonant_lengths

    ea, mass = 1.57012e7, 13000.0
    lengths = np.linspace(500.0, 1000.0, 201)
    chart = SimpleNamespace(lengths=lengths, frequencies=np.sqrt(ea / (lengths * mass))[:, None],
                            wave_band=(0.314, 1.4))
    found = resonant_lengths(chart, [1.26])
    # sorted by length: the band's high edge (616 m) before the heave (760 m)
    assert [w for _, w, _ in found] == [1.4, 1.26]
    assert [what for _, _, what in found] == ["band high edge", "heave"]
    for length, w, _ in found:
        assert length == pytest.approx(ea / (w**2 * mass), rel=1e-3)
    assert resonant_lengths(chart, [5.0]) == sorted(
        [f for f in found if f[2] != "heave"])
