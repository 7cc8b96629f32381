"""`bench-heave` data: the JSON rows (schema only; timing belongs to the benchmark itself)."""

from __future__ import annotations

import json
import math

from cable_ocp.bench import heave_mpc

KEYS = {"solver", "horizon", "median_ms", "p99_ms", "steps", "failures"}


def test_json_data_has_one_row_per_solver_and_horizon() -> None:
    data = heave_mpc.bench_json(horizons=(5, 8), steps=4, solvers=("daqp", "qpoases"),
                                with_do_mpc=False)
    assert set(data) == {"rows"}
    rows = data["rows"]
    assert [(r["solver"], r["horizon"]) for r in rows] == [
        ("daqp", 5), ("qpoases", 5), ("daqp", 8), ("qpoases", 8)]
    for r in rows:
        assert set(r) == KEYS
        assert r["steps"] == 4 and r["failures"] == 0
        assert math.isfinite(r["median_ms"]) and r["p99_ms"] >= r["median_ms"] > 0
    json.dumps(data)  # plain JSON types


def test_do_mpc_placeholder_row_is_left_out() -> None:
    # When do-mpc is not installed, run() adds a row without steps for the table; the JSON
    # carries only measured rows.
    rows = [heave_mpc.BenchRow("daqp", 5, 1e-4, 2e-4, 4, 0),
            heave_mpc.BenchRow("do-mpc", 5, float("nan"), float("nan"), 0, 0, "not installed")]
    assert [r["solver"] for r in heave_mpc.json_data(rows)["rows"]] == ["daqp"]


def test_cli_json_dash_prints_the_json_alone(capsys, tmp_path, monkeypatch) -> None:  # noqa: ANN001
    from cable_ocp.cli import main

    monkeypatch.chdir(tmp_path)
    assert main(["bench-heave", "--horizons", "5", "--steps", "4", "--solvers", "daqp",
                 "--no-do-mpc", "--json", "-"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [r["solver"] for r in data["rows"]] == ["daqp"]
    assert not (tmp_path / "-").exists()
