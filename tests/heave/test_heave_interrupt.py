"""``cable-ocp heave`` interrupted: the controllers whose runs finished are written (--json,
--csv) with status ``interrupted`` for the others and the whole, then exit 130 and one line.

The Ctrl-C is a :class:`KeyboardInterrupt` raised by the closed loop of the n-th run (what the
command line's signal handler raises, in-process: no real signal needed)."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest

from cable_ocp.cli import main
from cable_ocp.heave import design_loop

ROOT = Path(__file__).resolve().parents[2]
SCENE = str(ROOT / "problems" / "heave" / "ex_6_3_6.toml")
# 40 s: 10 s of metrics after the 30 s warm-up, a fraction of a second per run
ARGS = ["heave", SCENE, "--duration", "40", "--quiet"]


def _run(tmp: Path, name: str, controllers: list[str]) -> tuple[int, dict, list[dict]]:
    js, cs = tmp / f"{name}.json", tmp / f"{name}.csv"
    rc = main([*ARGS, "--controllers", *controllers, "--json", str(js), "--csv", str(cs)])
    data = json.loads(js.read_text(), parse_constant=pytest.fail) if js.exists() else {}
    rows = list(csv.DictReader(cs.open())) if cs.exists() else []
    return rc, data, rows


def _interrupt_at(monkeypatch: pytest.MonkeyPatch, nth: int) -> None:
    """The ``nth`` closed-loop run (1-based) raises KeyboardInterrupt at its start."""
    calls = []
    real = design_loop.run_loop

    def run_loop(*a, **k):  # noqa: ANN002, ANN003, ANN202 - the wrapped run_loop's
        calls.append(1)
        if len(calls) == nth:
            raise KeyboardInterrupt
        return real(*a, **k)

    monkeypatch.setattr(design_loop, "run_loop", run_loop)


def test_heave_interrupted_writes_the_controllers_finished(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture) -> None:
    rc, ref, ref_rows = _run(tmp_path, "ref", ["passive", "lqr", "lqg"])
    assert rc == 0 and ref["status"] == "solved"
    capsys.readouterr()

    # runs passive, lqr, lqg: the third is stopped -> passive and lqr finished
    _interrupt_at(monkeypatch, 3)
    rc, data, rows = _run(tmp_path, "int", ["passive", "lqr", "lqg"])
    assert rc == 130
    assert capsys.readouterr().err == "cable-ocp: interrupted\n"
    assert data["status"] == "interrupted"
    assert data["message"] == "interrupted after 2 of 3 controllers (passive, lqr)"
    ctrl = data["controllers"]
    assert list(ctrl) == ["passive", "lqr", "lqg"]
    for name in ("passive", "lqr"):
        assert ctrl[name]["status"] == "solved"
        for key, v in ref["controllers"][name].items():
            # the same runs on the same seeded sea: equal up to round-off (1e-12 relative)
            if isinstance(v, float):
                assert ctrl[name][key] == pytest.approx(v, rel=1e-12, abs=1e-15), (name, key)
            else:
                assert ctrl[name][key] == v, (name, key)
    assert ctrl["lqr"]["reduction_pct"] is not None  # the passive baseline finished
    assert ctrl["lqg"]["status"] == "interrupted"
    assert ctrl["lqg"]["message"] == "interrupted before its run finished"
    assert all(ctrl["lqg"][k] is None for k in ("heave_rms", "reduction_pct", "max_stroke"))
    # the CSV: the finished controllers' columns, as in the uninterrupted run
    assert list(rows[0]) == [k for k in ref_rows[0] if not k.startswith("lqg_")]
    assert len(rows) == len(ref_rows)
    for key in rows[0]:
        assert [float(r[key]) for r in rows] == pytest.approx(
            [float(r[key]) for r in ref_rows], rel=1e-12, abs=1e-15), key

    # without passive among the controllers it is the baseline, run last: interrupted
    # there, the reductions do not exist
    _interrupt_at(monkeypatch, 2)
    rc, data, _ = _run(tmp_path, "nobase", ["lqr"])
    assert rc == 130 and data["status"] == "interrupted"
    assert data["passive_heave_rms"] is None
    lqr = data["controllers"]["lqr"]
    assert lqr["status"] == "solved" and lqr["reduction_pct"] is None
    assert lqr["heave_rms"] == pytest.approx(ref["controllers"]["lqr"]["heave_rms"], rel=1e-12)


def test_heave_on_the_cable_interrupted_keeps_the_passive_run(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture) -> None:
    """The loop on the cable plant: passive's two runs (design model, cable) finish, the
    third (lqr's on the design model) is stopped."""
    from cable_ocp.heave import cable_compare

    calls = []
    real = cable_compare.run_loop

    def run_loop(*a, **k):  # noqa: ANN002, ANN003, ANN202 - the wrapped run_loop's
        calls.append(1)
        if len(calls) == 3:
            raise KeyboardInterrupt
        return real(*a, **k)

    monkeypatch.setattr(cable_compare, "run_loop", run_loop)
    js = tmp_path / "c.json"
    rc = main(["heave", str(ROOT / "problems" / "heave" / "ex_6_3_6_cable.toml"), "--quiet",
               "--duration", "40", "--set", "identification.duration=40",
               "--controllers", "passive", "lqr", "--json", str(js)])
    assert rc == 130 and capsys.readouterr().err == "cable-ocp: interrupted\n"
    data = json.loads(js.read_text(), parse_constant=pytest.fail)
    assert data["status"] == "interrupted"
    ctrl = data["controllers"]
    assert ctrl["passive"]["status"] == "solved" and ctrl["passive"]["reduction_pct"] == 0.0
    assert data["passive_heave_rms"] == ctrl["passive"]["heave_rms"] > 0
    assert ctrl["lqr"]["status"] == "interrupted"
    assert all(v is None for k, v in ctrl["lqr"].items() if k not in ("status", "message"))
