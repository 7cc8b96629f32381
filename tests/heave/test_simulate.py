"""Closed-loop comparison on one seeded sea (issue 4 item 5) and the CLI JSON contract."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

from cable_ocp.heave import simulate as sm
from cable_ocp.scene.heave import load_scene

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def short_636() -> sm.Comparison:
    sc = load_scene(ROOT / "problems" / "heave" / "ex_6_3_6.toml")
    sc = dataclasses.replace(sc, simulation=dataclasses.replace(sc.simulation, duration=120.0,
                                                                warmup=20.0))
    return sm.compare(sc)


def test_sigma_uncontrolled_in_comparison(short_636: sm.Comparison) -> None:
    # Same convention and number as test_stochastic (0.255 m, 3 digits).
    assert short_636.sigma_uncontrolled == pytest.approx(0.255, abs=5e-4)


def test_passive_rms_consistent_with_lyapunov(short_636: sm.Comparison) -> None:
    # A 100 s record of a narrow-band process (correlation time ~10 s) estimates sigma with a
    # sampling error of ~20 %; the simulated passive RMS must be within 35 % of 0.255 m.
    assert short_636.metrics["passive"].heave_rms == pytest.approx(0.255, rel=0.35)


def test_lqr_and_mpc_reduce_heave_over_99pct_and_mpc_keeps_limits(short_636: sm.Comparison
                                                                  ) -> None:
    m = short_636.metrics
    assert m["lqr"].reduction_pct > 99.0
    assert m["mpc"].reduction_pct > 99.0
    assert m["mpc"].max_constraint_violation <= 1e-9
    assert short_636.mpc_failures == 0
    # LQG with 1 cm sensor noise is worse than full-state LQR but still reduces the heave.
    assert m["lqr"].heave_rms < m["lqg"].heave_rms < m["passive"].heave_rms


def test_all_metrics_share_the_warmup_window(short_636: sm.Comparison) -> None:
    # Every metric is over t >= warmup (20 s here): recompute each from the trace (exact, same
    # arithmetic). The LQR's start-up transient (unit at rest in a stationary sea) reaches a
    # winch speed several times the stationary peak; it must not leak into the metrics.
    warm = 20.0
    for name in ("lqr", "lqg", "mpc"):
        tr, mt = short_636.traces[name], short_636.metrics[name]
        keep = tr.t >= warm - 1e-12
        assert mt.peak_winch_speed == np.max(np.abs(tr.u_dot[keep]))
        assert mt.max_stroke == np.max(np.abs(tr.u[keep]))
        assert mt.winch_speed_rms == pytest.approx(np.sqrt(np.mean(tr.u_dot[keep] ** 2)),
                                                   rel=1e-12)
        assert mt.heave_rms == pytest.approx(np.sqrt(np.mean(tr.x[keep] ** 2)), rel=1e-12)
    lqr = short_636.traces["lqr"]
    assert np.max(np.abs(lqr.u_dot)) > 2 * short_636.metrics["lqr"].peak_winch_speed
    # After the start-up the full-state LQR keeps the 6.3.6 limits (stroke 2 m, speed
    # 1.5 m/s, 0.1 m per sample): no violation is reported.
    assert short_636.metrics["lqr"].max_constraint_violation == 0.0


def test_last_sample_uses_the_applied_command(short_636: sm.Comparison) -> None:
    # At t = T the winch still sees the command applied over the last step (the newest command
    # is inside the 0.2 s delay line): u0(T) = u0(T - h_sim) and u'(T) = K (u0(T) - u(T)),
    # K = 1 1/s (ex_6_3_6.toml); exact equality, same arithmetic.
    for name in ("lqr", "mpc"):
        tr = short_636.traces[name]
        assert tr.u0[-1] == tr.u0[-2]
        assert tr.u_dot[-1] == 1.0 * (tr.u0[-1] - tr.u[-1])


def test_nonlinear_plant_runs_and_mpc_keeps_limits() -> None:
    # (6.3) plant: controllers designed on (6.2) still reduce the heave; hard limits hold.
    sc = load_scene(ROOT / "problems" / "heave" / "ex_6_2_6.toml")
    sc = dataclasses.replace(
        sc, unit=dataclasses.replace(sc.unit, model="quadratic"),
        simulation=dataclasses.replace(sc.simulation, duration=60.0, warmup=10.0))
    r = sm.compare(sc, ("passive", "mpc"))
    assert r.metrics["mpc"].max_constraint_violation <= 1e-9
    assert r.metrics["mpc"].reduction_pct > 90.0


def test_cli_json_fields(tmp_path: Path) -> None:
    from cable_ocp.cli import main

    out = tmp_path / "r.json"
    rc = main(["heave", str(ROOT / "problems" / "heave" / "ex_6_3_6.toml"), "--json", str(out),
               "--duration", "40", "--controllers", "passive", "lqr", "mpc", "--quiet"])
    assert rc == 0
    data = json.loads(out.read_text())
    assert {"status", "message", "warnings", "version", "sigma_uncontrolled",
            "controllers"} <= set(data)
    assert data["status"] == "solved"
    fields = {"status", "heave_rms", "reduction_pct", "peak_winch_speed", "max_stroke",
              "energy_index", "max_constraint_violation", "solve_time_median_s",
              "winch_speed_rms"}
    for name in ("passive", "lqr", "mpc"):
        assert fields <= set(data["controllers"][name])
    assert data["controllers"]["passive"]["solve_time_median_s"] is None
    assert data["controllers"]["mpc"]["energy_index"] is None
    assert data["controllers"]["lqr"]["energy_index"] > 0
    assert data["controllers"]["mpc"]["solver_failures"] == 0
