"""Closed-loop comparison on one seeded sea (issue 4 item 5) and the CLI JSON contract."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import pytest

from cable_ocp.heave import simulate as sm
from cable_ocp.heave.scene import load_scene

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
    import argparse

    from cable_ocp.heave import cli

    parser = argparse.ArgumentParser()
    cli.register(parser.add_subparsers(dest="command"))
    out = tmp_path / "r.json"
    args = parser.parse_args(["heave", str(ROOT / "problems" / "heave" / "ex_6_3_6.toml"),
                              "--json", str(out), "--duration", "40",
                              "--controllers", "passive", "lqr", "mpc"])
    assert args.func(args) == 0
    data = json.loads(out.read_text())
    assert set(data) == {"sigma_uncontrolled", "controllers"}
    fields = {"heave_rms", "reduction_pct", "peak_winch_speed", "max_stroke", "energy_index",
              "max_constraint_violation", "solve_time_median_s", "winch_speed_rms"}
    for name in ("passive", "lqr", "mpc"):
        assert set(data["controllers"][name]) == fields
    assert data["controllers"]["passive"]["solve_time_median_s"] is None
    assert data["controllers"]["mpc"]["energy_index"] is None
    assert data["controllers"]["lqr"]["energy_index"] > 0
