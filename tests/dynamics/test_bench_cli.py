"""``cable-ocp bench dynamics``: the output contract (a quick run; timing is never asserted).

MoorDyn is optional: these tests run without it (its availability is patched off), and its
rows must then say "not installed".
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
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
    quick run's: 6 and 12 segments extrapolated, 0.01 s) is finite and below 0.5 (a broken
    reference or a sign slip gives O(1)); the
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
                      top_tension_amplitude_N=2e4, error=0.004, amplitude_vs_reference=0.0,
                      amplitude_vs_other=None, status="ok")
    nan_row = bd.BenchRow(model="MoorDyn RK2", segments=40, time_step=4e-3,
                          wall_per_simulated_s=math.nan, realtime_factor=math.nan,
                          top_tension_amplitude_N=math.nan, error=math.nan,
                          amplitude_vs_reference=math.nan, amplitude_vs_other=None,
                          status="not installed (pip install moordyn)")
    ref = bd.Reference(np.zeros(2), np.zeros(2), 1.0, {
        "segments": [160, 320], "time_step": 0.002, "output_step": 0.01, "status": "ok",
        "richardson_correction": None, "halving_ratio": None})
    monkeypatch.setattr(bd, "run", lambda *a, **k: ([row, nan_row], ref))
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
                       error=error, amplitude_vs_reference=0.0, amplitude_vs_other=None,
                       status="ok")


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


# -- the comparison's bookkeeping ---------------------------------------------------------

def _synthetic(n: int, dt: float) -> tuple[np.ndarray, np.ndarray, float, str]:
    """A made-up top force Y(t) + 2e5 / N^2 + 1e5 dt^2 N (a spatial and a time error)."""
    t = np.arange(0.0, 20.0 + 1e-9, 0.01)
    return t, 3e4 + 1.5e4 * np.sin(bd.FREQUENCY * t) + 2e5 / n**2 + 1e5 * dt**2, 1.0, "ok"


def test_reference_extrapolates_and_every_row_is_compared_with_it(
        no_moordyn: None, monkeypatch: pytest.MonkeyPatch) -> None:
    """With model runs of a known spatial error C / N^2 (and time error D dt^2), the
    reference is Y + D dt_ref^2 (Richardson removes C / N^2 exactly: 1e-9 relative, round-
    off), the O(1/N^2) check gives 4, and each row's error is its own spatial plus time
    error against that one reference, (C / N^2 + D (dt^2 - dt_ref^2)) / amplitude: a row
    compared with its own model at the same N (the old bookkeeping) would show the time
    error alone."""
    monkeypatch.setattr(bd, "_cable_ocp", lambda n, dt, *a, **k: _synthetic(n, dt))
    ref = bd.reference(20.0, (10, 20, 40), 0.002)
    amp = 1.5e4
    t = ref.t
    np.testing.assert_allclose(ref.y, 3e4 + amp * np.sin(bd.FREQUENCY * t) + 0.4, rtol=1e-9)
    assert ref.info["halving_ratio"] == pytest.approx(4.0, rel=1e-6)
    rows, _ = bd.run((20,), (0.05,), with_moordyn=False, duration=20.0, repeats=1,
                     reference_segments=(10, 20, 40), reference_step=0.002)
    r = rows[0]
    time_error = 1e5 * (0.05**2 - 0.002**2)
    assert r.error == pytest.approx((2e5 / 20**2 + time_error) / ref.amplitude, rel=1e-6)
    assert r.error > 2.0 * time_error / ref.amplitude  # the spatial error counts


def test_moordyn_is_driven_consistently_and_compared_on_cable_ocps_force(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """MoorDyn's bookkeeping on a 6-segment line, 8 s (after the 5 s ramp):

    * the input file starts the unit at cable_ocp's static position, z_b - L - (L / EA)
      (W + w L / 2) (the lumped chain's stretch is exact: tension linear in s), and names
      its IC generator (``ICgenDynamic``); the first sample is then the static top force,
      W + w L = 36 529.3 N, to 2e-4 (MoorDyn's own equilibrium of the same chain; from the
      unstretched start at dtM = 1 ms its stationary solver stops early and the line rings
      between about 9 and 61 kN);
    * each ``Step`` gets the prescribed position x_k and the velocity that carries it to
      x_k+1 over the coupling step, (x_k+1 - x_k) / dt_c (1e-9 m: round-off);
    * the compared force is cable_ocp's top force, M a - F (MoorDyn's F has no inertia),
      with a the analytic acceleration at the RK2 stage the force comes from,
      t_k+1 - dtM / 2; here M a reaches more than 1 % of F's swing, so the two
      definitions differ.
    """
    moordyn = pytest.importorskip("moordyn")
    sc = bd.scene(6, 0.05, 8.0)
    z_unit = bd.static_unit_height(6)
    cab = sc.statics.cable
    big_w = sc.unit.weight_in_water
    stretch = cab.length / cab.axial_stiffness * (big_w + 0.5 * cab.weight_in_water * cab.length)
    assert z_unit == pytest.approx(sc.top_position[2] - cab.length - stretch, abs=1e-9)
    text = bd._moordyn_input(sc, 6, 1e-3, z_unit)
    point = next(ln.split() for ln in text.splitlines() if ln.startswith("1 Free"))
    assert float(point[4]) == pytest.approx(z_unit - sc.statics.environment.water_depth,
                                            abs=1e-9)
    assert any(ln.split()[1:] == ["ICgenDynamic"] for ln in text.splitlines()
               if len(ln.split()) == 2)

    steps: list[tuple[list[float], list[float], float, float]] = []
    real_step = moordyn.Step

    def step(system, x, v, t, dt):  # noqa: ANN001, ANN202 - MoorDyn's signature
        steps.append((list(x), list(v), t, dt))
        return real_step(system, x, v, t, dt)

    seen: dict[str, np.ndarray] = {}
    real_force = bd.top_force_as_cable_ocp

    def force(f, m, a):  # noqa: ANN001, ANN202
        seen.update(f=np.array(f), m=np.array(m), a=np.array(a))
        return real_force(f, m, a)

    monkeypatch.setattr(moordyn, "Step", step)
    monkeypatch.setattr(bd, "top_force_as_cable_ocp", force)
    t, y, _, status = bd._moordyn(6, 1e-3, 8.0)
    assert status == "ok"
    static = big_w + cab.weight_in_water * cab.length
    assert y[0] == pytest.approx(static, rel=2e-4)
    x = np.array([s[0] for s in steps])
    v = np.array([s[1] for s in steps])
    dtc = steps[0][3]
    np.testing.assert_allclose(v[:-1] * dtc, np.diff(x, axis=0), atol=1e-9)
    # stage times; after the ramp the top moves as sin(w t) on each axis: a = -w^2 sin(w t)
    np.testing.assert_allclose(t, dtc * np.arange(1, len(steps) + 1) - 0.5e-3, atol=1e-12)
    late = t > bd.RAMP + 0.01
    w = bd.FREQUENCY
    np.testing.assert_allclose(seen["a"][late],
                               np.outer(-w * w * np.sin(w * t[late]), [1.0, 1.0, 1.0]),
                               atol=1e-9)
    inertia = np.einsum("nij,nj->ni", seen["m"], seen["a"])
    np.testing.assert_allclose(y, np.linalg.norm(inertia - seen["f"], axis=1), rtol=1e-12)
    raw = np.linalg.norm(seen["f"], axis=1)
    assert np.max(np.abs(y - raw)[late]) > 0.01 * np.ptp(raw[late])
