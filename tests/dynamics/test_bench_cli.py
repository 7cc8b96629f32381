"""``cable-ocp bench dynamics``: the output contract (a quick run; timing is never asserted).

MoorDyn is optional: these tests run without it (its availability is patched off), and its
rows must then say "not installed".
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from cable_ocp.bench import dynamics as bd
from cable_ocp.cli import main


@pytest.fixture
def no_moordyn(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(bd, "moordyn_available", lambda: False)


def test_quick_run_table_json_and_plot(no_moordyn: None, tmp_path: Path,
                                       capsys: pytest.CaptureFixture[str]) -> None:
    """``--quick``: a table on stdout with the load average and the targets, the JSON
    envelope with one cable_ocp row and a "not installed" MoorDyn row, a figure.

    The numbers checked are consistency checks, not timings: the real-time factor is the
    inverse of the wall time per simulated second; the error against the reference (the
    same model at an 8x smaller step) is finite and below 0.5 (a 0.1 s step resolves the
    5 s period to a few per cent: a broken reference or a sign slip gives O(1)); the
    top-tension amplitude is between the 1 m heave's inertial estimate of the unit alone,
    (M + M_a) w^2 = 9.5 kN, and 5x that (drag and the cable add to it).
    """
    js, fig = tmp_path / "b.json", tmp_path / "b.png"
    rc = main(["bench", "dynamics", "--quick", "--json", str(js), "--plot", str(fig),
               "--quiet"])
    assert rc == 0
    text = capsys.readouterr().out
    assert "load average" in text and "cable_ocp midpoint" in text
    assert "not installed" in text and "100x real time" in text
    d = json.loads(js.read_text())
    for key in ("status", "message", "warnings", "version", "rows", "summary",
                "load_average"):
        assert key in d, key
    assert d["status"] == "ok"
    ours = [r for r in d["rows"] if r["model"] == "cable_ocp midpoint"]
    md = [r for r in d["rows"] if r["model"].startswith("MoorDyn")]
    assert len(ours) == 1 and ours[0]["status"] == "ok" and ours[0]["segments"] == 6
    assert md and all(r["status"].startswith("not installed") for r in md)
    r = ours[0]
    assert math.isclose(r["realtime_factor"] * r["wall_per_simulated_s"], 1.0, rel_tol=1e-9)
    assert 0.0 <= r["error"] < 0.5
    inertial = 6000.0 * bd.FREQUENCY**2
    assert inertial < r["top_tension_amplitude_N"] < 5.0 * inertial
    assert fig.stat().st_size > 1000


def test_json_to_stdout_alone_and_strict(no_moordyn: None, monkeypatch: pytest.MonkeyPatch,
                                         capsys: pytest.CaptureFixture[str]) -> None:
    """``--json -``: stdout is the JSON alone, strict (NaN as null); the run is patched
    (the CLI's plumbing is under test here, not the numbers)."""
    row = bd.BenchRow(model="cable_ocp midpoint", segments=40, time_step=0.05,
                      wall_per_simulated_s=0.005, realtime_factor=200.0,
                      top_tension_amplitude_N=2e4, error=0.004, amplitude_vs_other=None,
                      status="ok")
    nan_row = bd.BenchRow(model="MoorDyn RK2", segments=40, time_step=4e-3,
                          wall_per_simulated_s=math.nan, realtime_factor=math.nan,
                          top_tension_amplitude_N=math.nan, error=math.nan,
                          amplitude_vs_other=None, status="not installed (pip install moordyn)")
    monkeypatch.setattr(bd, "run", lambda *a, **k: [row, nan_row])
    rc = main(["bench", "dynamics", "--segments", "40", "--json", "-"])
    assert rc == 0
    out = capsys.readouterr().out
    d = json.loads(out)  # the whole of stdout parses: nothing else was printed
    assert "NaN" not in out
    assert d["rows"][1]["wall_per_simulated_s"] is None
    rt = d["summary"]["realtime"]
    assert rt["met"] is True and rt["time_step"] == 0.05


@pytest.mark.parametrize("argv", [["--segments", "1"], ["--time-steps", "0"],
                                  ["--duration", "5"], ["--repeats", "0"],
                                  ["--tolerance", "0.1"],
                                  ["--json", "/nonexistent-dir/b.json"],
                                  ["--plot", "b.unknownformat"]])
def test_bad_input_exits_2_before_work(argv: list[str], monkeypatch: pytest.MonkeyPatch
                                       ) -> None:
    """Every bad option is refused (exit 2) before any run."""
    def boom(*a: object, **k: object) -> None:
        raise AssertionError("the benchmark ran")

    monkeypatch.setattr(bd, "run", boom)
    assert main(["bench", "dynamics", "--quiet", *argv]) == 2


def _row(model: str, dt: float, wall: float, error: float) -> bd.BenchRow:
    return bd.BenchRow(model=model, segments=20, time_step=dt, wall_per_simulated_s=wall,
                       realtime_factor=1.0 / wall, top_tension_amplitude_N=1.5e4,
                       error=error, amplitude_vs_other=None, status="ok")


def test_summary_compares_at_moordyns_own_accuracy_when_it_misses_one_percent() -> None:
    """Where no MoorDyn row is within 1 %, its fastest row is compared with cable_ocp's
    fastest row that is at least as accurate (not with a faster, less accurate one)."""
    rows = [_row("cable_ocp midpoint", 0.1, 0.002, 0.02),
            _row("cable_ocp midpoint", 0.075, 0.0025, 0.0076),
            _row("MoorDyn RK2", 0.004, 0.003, 0.0156),
            _row("MoorDyn RK2", 0.002, 0.005, 0.0155)]
    e = bd.summary(rows)["versus_moordyn"][0]
    assert e["cable_ocp"]["time_step"] == 0.075  # 0.1 s is faster but less accurate
    assert e["moordyn"]["time_step"] == 0.004
    assert e["speed_ratio"] == pytest.approx(0.003 / 0.0025) and e["met"] is True
    assert "own accuracy" in e["basis"]
    # within 1 %, the plain comparison
    rows[2] = _row("MoorDyn RK2", 0.004, 0.003, 0.009)
    e = bd.summary(rows)["versus_moordyn"][0]
    assert e["basis"] == "error <= 1%" and e["cable_ocp"]["time_step"] == 0.075
