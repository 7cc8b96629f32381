"""The face of a load-case study: summaries that name the parameter values of the extreme
cases, axes with the keys' units, random samples drawn as points, a heave batch drawn by
its controllers, the per-case arrays in one netCDF file and the range graph over the cases.

One small statics batch (De Zoysa's cable, 3 headings x 2 current speeds, in this process)
is run once through the CLI for the module; the other checks reuse it."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from cable_ocp.batch import BatchResult, parse_random, run_batch
from cable_ocp.batch.arrays import case_arrays, read_arrays
from cable_ocp.batch.kinds import HeaveRunner
from cable_ocp.cli import main
from cable_ocp.plots.batch import default_columns, plot_batch, plot_range_graph
from cable_ocp.scene.units import key_label, key_unit
from cable_ocp.statics.solver import solve

ROOT = Path(__file__).resolve().parents[1]
DEZOYSA = ROOT / "problems" / "dezoysa_sea_buggy.toml"
SPEED, PSI = "environment.current.speed", "layout.psi0_deg"
TOL_NODES = 1e-6  # of the largest tension (why: test_array_store_holds_...)

pytest.importorskip("xarray")


@pytest.fixture(scope="module")
def study(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    """``cable-ocp batch`` over psi0 = 30, 75, 120 deg x U = 0.6, 1.0 m/s with --arrays,
    --range-graph, --plot and --json; the rows read back from the JSON lines."""
    d = tmp_path_factory.mktemp("face")
    rc = main(["batch", str(DEZOYSA), "--range", f"{PSI}=30:120:3", "--grid",
               f"{SPEED}=0.6,1.0", "--out", str(d / "r"), "--workers", "0", "--quiet",
               "--arrays", str(d / "a.nc"), "--range-graph", str(d / "rg.png"),
               "--plot", str(d / "p.png"), "--json", str(d / "s.json")])
    rows = [json.loads(line) for line in (d / "r.jsonl").read_text().splitlines()]
    return {"dir": d, "rc": rc, "rows": rows,
            "summary": json.loads((d / "s.json").read_text())}


def test_extremes_name_the_parameter_values_of_the_extreme_case(study, capsys) -> None:
    """For every output, the summary's largest and smallest values and the swept keys'
    values it names are those of the row that really has the extreme (found here from the
    stored rows, independently); the text says them with units."""
    assert study["rc"] == 0
    rows = [r for r in study["rows"] if r["status"] == "solved"]
    assert len(rows) == 6
    ext = study["summary"]["extremes"]
    for col in ("max_tension [N]", "end_a_tension [N]", "end_b_angle [deg]",
                "end_a_force_x [N]"):
        for which, pick in (("max", max), ("min", min)):
            best = pick(rows, key=lambda r, col=col: r[col])
            assert ext[col][which] == best[col]  # the same stored number
            assert ext[col][f"{which}_at"] == {SPEED: best[SPEED], PSI: best[PSI]}
            assert ext[col][f"{which}_case"] == best["case"]
    # the printed sentence of the main output (a second run of the same command prints it)
    d = study["dir"]
    main(["batch", str(DEZOYSA), "--range", f"{PSI}=30:120:3", "--grid", f"{SPEED}=0.6,1.0",
          "--out", str(d / "r"), "--resume", "--workers", "0"])
    text = capsys.readouterr().out
    top = max(rows, key=lambda r: r["max_tension [N]"])
    want = (f"largest max_tension {top['max_tension [N]'] / 1e3:.4g} kN at "
            f"{SPEED} = {top[SPEED]:.4g} m/s, {PSI} = {top[PSI]:.4g} deg (case {top['case']})")
    assert want in text, text


def test_keys_have_units_and_the_axes_carry_them(study) -> None:
    """The key->unit table (scene/units.py) gives the problem-file units (docs tables), an
    array index is ignored; the batch figures' axes read the keys with their units."""
    assert key_unit(SPEED) == "m/s" and key_unit(PSI) == "deg"
    assert key_unit("cable.segments.1.length") == "m"
    assert key_unit("sea.significant_wave_height") == "m"
    assert key_unit("winch.gain") == "1/s" and key_unit("vessel.gain") == "-"
    assert key_label("cable.weight_in_water") == "cable.weight_in_water (N/m)"
    res = _result(study["rows"], [PSI, SPEED])
    fig = plot_batch(res, "max_tension [N]")
    ax = fig.axes[0]
    assert (ax.get_xlabel(), ax.get_ylabel()) == (f"{PSI} (deg)", f"{SPEED} (m/s)")
    one = _result([r for r in study["rows"] if r[SPEED] == 0.6], [PSI, SPEED])
    ax = plot_batch(one, "max_tension [N]").axes[0]
    assert ax.get_xlabel() == f"{PSI} (deg)" and ax.get_ylabel() == "max_tension (N)"
    line = ax.get_lines()[0]
    assert line.get_linestyle() == "-"  # a grid keeps its lines
    np.testing.assert_array_equal(line.get_xdata(), [30.0, 75.0, 120.0])


def test_random_samples_are_drawn_as_points() -> None:
    """Four seeded random current speeds: drawn as markers without a line, at the drawn
    values (sorted), with the key's unit on the axis."""
    res = run_batch(DEZOYSA, samples=4, randoms=[parse_random(f"{SPEED}=uniform(0.5,1)")],
                    seed=3, workers=0)
    assert res.random_inputs == [SPEED]
    ax = plot_batch(res, None).axes[0]
    line = ax.get_lines()[0]
    assert line.get_linestyle() == "None" and line.get_marker() == "o"
    np.testing.assert_array_equal(line.get_xdata(), np.sort(res.column(SPEED)))
    assert ax.get_xlabel() == f"{SPEED} (m/s)"


def test_heave_batch_draws_the_controllers_not_the_passive_run() -> None:
    """A heave batch's default figure draws each controller's heave RMS (the compensated
    result), not the passive one (which is 1000x larger); rows made up here, no run."""
    cols = HeaveRunner({}, {"controllers": ["passive", "lqr", "mpc"]}).columns()
    key = "sea.significant_wave_height"
    rows = [{"case": i, "case_id": str(i), "status": "solved", key: h,
             "passive_heave_rms [m]": 0.1 * h, "lqr_heave_rms [m]": 1e-4 * h,
             "mpc_heave_rms [m]": 2e-4 * h, "sigma_uncontrolled [m]": 0.09 * h}
            for i, h in enumerate([2.0, 3.0, 4.0])]
    res = BatchResult("heave", [key], cols, rows)
    assert default_columns(res) == ["lqr_heave_rms [m]", "mpc_heave_rms [m]"]
    ax = plot_batch(res, None).axes[0]
    got = {ln.get_label(): ln.get_ydata() for ln in ax.get_lines()}
    assert set(got) == {"lqr", "mpc"}
    np.testing.assert_allclose(got["lqr"], [2e-4, 3e-4, 4e-4], rtol=1e-15)
    assert ax.get_xlabel() == f"{key} (m)"


def test_array_store_holds_each_cases_tension_along_the_line(study) -> None:
    """The netCDF store has one entry per case; each case's arc length and tension equal a
    separate cold `solve` of that case (to 1e-7 of the largest tension: the batch warm-starts
    and both converge to the 1e-10 residual tolerance, as in test_batch), its swept inputs and
    status equal the row's, and the units are recorded."""
    ds = read_arrays(study["dir"] / "a.nc")
    assert ds.attrs["kind"] == "statics" and ds["tension"].attrs["units"] == "N"
    assert ds[SPEED].attrs["units"] == "m/s"
    arrays = case_arrays(ds)
    by_case = {r["case"]: r for r in study["rows"]}
    assert sorted(arrays) == sorted(by_case)
    for c, a in arrays.items():
        row = by_case[c]
        assert float(ds[PSI].sel(case=c)) == row[PSI]
        assert str(ds["status"].sel(case=c).values) == row["status"]
        assert a["arc_length"][0] == 0.0 and a["arc_length"][-1] == pytest.approx(
            row["length [m]"], rel=1e-14)
        assert a["tension"].max() == pytest.approx(row["max_tension [N]"], rel=1e-12)
        assert a["tension"][0] == pytest.approx(row["end_a_tension [N]"], rel=1e-12)
        assert a["tension"][-1] == pytest.approx(row["end_b_tension [N]"], rel=1e-12)
        # a cold solve places its mesh on the drag's kinks itself (a warm one keeps its
        # start's): compare at the stored nodes, the cold solution interpolated linearly
        # between its own nodes (spacing <= 3.1 m; seen: up to 4.3e-8 of the largest
        # tension, where the two meshes differ; 0 where they are the same)
        sol = solve(DEZOYSA, {SPEED: row[SPEED], PSI: row[PSI]})
        np.testing.assert_allclose(a["tension"], np.interp(a["arc_length"], sol.s,
                                                           sol.tension),
                                   rtol=0, atol=TOL_NODES * sol.max_tension)
        assert np.ptp(a["x"] ** 2 + a["y"] ** 2) > 0  # positions, not zeros
    try:
        import netCDF4
    except ImportError:
        return
    with netCDF4.Dataset(study["dir"] / "a.nc") as nc:  # chunked by case
        assert nc["tension"].chunking()[0] == 1


def test_range_graph_is_the_envelope_of_the_stored_cases(study) -> None:
    """The range graph drawn from the stored file: its max, min and mean lines are, at
    every point of the union of the cases' nodes, the max, min and mean over the cases of
    their tension (read back from the netCDF file, interpolated linearly between each case's
    own nodes, here independently); at end_a and end_b they are the extremes of the rows'
    end tensions (1e-9: the norm of the same stored force vector). The CLI wrote the PNG."""
    assert (study["dir"] / "rg.png").stat().st_size > 10_000
    ds = read_arrays(study["dir"] / "a.nc")
    arrays = case_arrays(ds)
    fig = plot_range_graph(ds)
    lines = {ln.get_gid(): ln for ln in fig.axes[0].get_lines() if ln.get_gid()}
    div = 1e3  # drawn in kN (tensions of 1.9-6 kN)
    assert fig.axes[0].get_ylabel() == "tension (kN)"
    s = lines["max"].get_xdata()
    grid = np.unique(np.concatenate([a["arc_length"] for a in arrays.values()]))
    np.testing.assert_array_equal(s, grid)
    table = np.array([[np.interp(x, a["arc_length"], a["tension"])
                       if a["arc_length"][0] <= x <= a["arc_length"][-1] else np.nan
                       for x in grid] for a in arrays.values()])
    for gid, f in (("max", np.nanmax), ("min", np.nanmin), ("mean", np.nanmean)):
        np.testing.assert_allclose(lines[gid].get_ydata() * div, f(table, axis=0),
                                   rtol=1e-14)
    rows = study["rows"]
    for end, i in (("a", 0), ("b", -1)):
        ends = [r[f"end_{end}_tension [N]"] for r in rows]
        assert lines["max"].get_ydata()[i] * div == pytest.approx(max(ends), rel=1e-9)
        assert lines["min"].get_ydata()[i] * div == pytest.approx(min(ends), rel=1e-9)


def test_arrays_without_xarray_is_an_input_error(tmp_path: Path, monkeypatch,
                                                 capsys) -> None:
    """Without xarray, --arrays exits 2 before any case runs, naming the extra to install;
    nothing is written."""
    monkeypatch.setitem(sys.modules, "xarray", None)
    rc = main(["batch", str(DEZOYSA), "--grid", f"{SPEED}=0.6", "--out",
               str(tmp_path / "r"), "--workers", "0", "--arrays", str(tmp_path / "a.nc")])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and "pip install -e '.[io]'" in err[0]
    assert not (tmp_path / "r.jsonl").exists() and not (tmp_path / "a.nc").exists()


def _result(rows: list[dict[str, Any]], inputs: list[str]) -> BatchResult:
    from cable_ocp.batch.kinds import OUTPUTS

    return BatchResult("statics", inputs, OUTPUTS["statics"], rows)


def test_resume_keeps_the_stored_arrays_of_the_cases_it_skips(tmp_path: Path) -> None:
    """A batch stopped after its first case (the store cut to that row) and resumed: the
    arrays file ends with both cases, the skipped one's arrays as first stored (bit for
    bit) and the other's as the resumed run computed them; an existing file without
    --resume or --overwrite is refused."""
    from cable_ocp.errors import CableOCPError

    grid = [(SPEED, [0.6, 1.0])]
    out, nc = tmp_path / "r", tmp_path / "a.nc"
    run_batch(DEZOYSA, grid, workers=0, out=out, arrays=nc)
    first = case_arrays(read_arrays(nc))
    jsonl = tmp_path / "r.jsonl"
    jsonl.write_text(jsonl.read_text().splitlines(keepends=True)[0])
    res = run_batch(DEZOYSA, grid, workers=0, out=out, arrays=nc, resume=True)
    assert res.skipped == 1
    again = case_arrays(read_arrays(nc))
    assert sorted(again) == [0, 1]
    for name in ("arc_length", "tension", "z"):
        np.testing.assert_array_equal(again[0][name], first[0][name])
        np.testing.assert_array_equal(again[1][name], res.arrays[1][name])
    with pytest.raises(CableOCPError, match="--resume"):
        run_batch(DEZOYSA, grid, workers=0, arrays=nc)


def test_quantity_writes_values_with_their_prefix_and_no_negative_zero() -> None:
    """The summary's numbers: 4 significant digits, forces with an SI prefix, a value that
    is zero without a sign (the y-force of a plane scene, -0.0, is "0 N", not "-0 N")."""
    from cable_ocp.report import quantity

    assert quantity(4347.1, "N") == "4.347 kN"
    assert quantity(-2.4911e3, "N") == "-2.491 kN"
    assert quantity(-1.0e-13, "N") == "-1e-13 N"  # not zero at 4 digits: kept as it is
    assert quantity(-0.0, "N") == "0 N"
    assert quantity(-0.00001, "m/s") == "-1e-05 m/s"
    assert quantity(None, "m") == "-"
