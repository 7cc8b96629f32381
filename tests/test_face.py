"""The results' face for notebooks: a short summary as ``repr``, ``plot(ax=None)`` returning
``(fig, ax)``, ``to_xarray()`` with named dimensions and units, ``to_pandas()`` tables, and
the netCDF writer (:mod:`cable_ocp.numerics.export`), on one small result of every kind."""

from __future__ import annotations

import re
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from matplotlib.figure import Figure

import cable_ocp as co
from cable_ocp.numerics.export import IO_EXTRA, summary_repr, write_netcdf

ROOT = Path(__file__).resolve().parents[1]
DYN = ROOT / "problems" / "dynamics" / "huang_3_3_5.toml"


@pytest.fixture(scope="module")
def results() -> dict[str, Any]:
    """One cheap result of every kind (about 2.5 s together, most of it the footprint's NLP
    build): Berteaux's mooring, 2 s of Huang's 3.3.5 axial line and its modes, 20 s of the
    6.3.6 heave loop (passive, LQR), a two-case batch, a four-direction footprint."""
    import cable_ocp.heave as hv
    from cable_ocp.batch import parse_grid, run_batch
    from cable_ocp.dynamics import modes, simulate

    dyn = DYN
    return {
        "statics": co.solve(ROOT / "problems" / "berteaux_mooring.toml"),
        "simulation": simulate(dyn, overrides={"simulation.duration": 2.0}),
        "modes": modes(dyn, 3),
        "heave": hv.compare(hv.load_scene(ROOT / "problems" / "heave" / "ex_6_3_6.toml",
                                          {"simulation.duration": 20.0,
                                           "simulation.warmup": 5.0}), ("passive", "lqr")),
        "batch": run_batch(ROOT / "problems" / "berteaux_mooring.toml",
                           [parse_grid("end_b.tension=11000,12000")], workers=0),
        "footprint": co.footprint(co.load_scene(ROOT / "problems" /
                                                "footprint_tethered_unit.toml"), directions=4),
    }


def _key_numbers(res: dict[str, Any]) -> dict[str, tuple[str, float, str]]:
    """Per kind: the status the summary's first line names, one key number's name in the
    summary, its value from the result's own attributes."""
    lqr = res["heave"].metrics["lqr"]
    fp = res["footprint"]
    return {
        "statics": ("solved", "max_tension", res["statics"].max_tension),
        "simulation": ("solved", "max_top_tension", float(np.max(res["simulation"].top_tension))),
        "modes": ("solved", "omega_1", float(res["modes"].frequencies[0])),
        "heave": ("solved", "lqr.heave_rms", lqr.heave_rms),
        "batch": ("2 solved", "cases", float(len(res["batch"].rows))),
        "footprint": ("solved", "max_reach", float(np.nanmax(fp.reach))),
    }


def test_repr_is_a_short_summary_with_the_status_and_key_numbers(results: dict) -> None:
    """Each result's repr is a few lines (< 1000 characters; a statics solution's dataclass
    repr was 24 kB), its first line names the status, and a key number written in it
    equals the result's attribute to 1e-5 (it is written with 6 significant digits, a
    rounding of at most 5e-6 relative)."""
    for kind, (status, name, value) in _key_numbers(results).items():
        text = repr(results[kind])
        assert len(text) < 1000 and len(text.splitlines()) <= 8, (kind, len(text), text)
        assert status in text.splitlines()[0], (kind, text)
        m = re.search(rf"(?<![\w.]){re.escape(name)} = ([-+0-9.e]+)", text)
        assert m, (kind, name, text)
        assert float(m.group(1)) == pytest.approx(value, rel=1e-5), (kind, text)
    assert "arrays: s (" in repr(results["statics"])  # the shapes, not the values


def test_summary_of_missing_numbers_and_long_messages() -> None:
    """A number that does not exist is '-', a long message is cut, arrays are shapes."""
    text = summary_repr("X", "failed", "m" * 500, [("a", None, "N"), ("b", float("nan"), "m")],
                        {"r": np.zeros((4, 3)), "none": None})
    assert text.splitlines()[0].startswith("<X failed: mmm") and len(text) < 300
    assert "a = - N" in text and "b = - m" in text and "r (4, 3)" in text


def test_to_xarray_names_dimensions_with_units(results: dict) -> None:
    """Dimensions and units as docs/api.md says, and the values are the result's own
    (exact: the same arrays)."""
    sol = results["statics"]
    ds = sol.to_xarray()
    assert ds["position"].dims == ("s", "xyz") and ds["s"].attrs["units"] == "m"
    assert ds["tension"].attrs["units"] == "N" and np.all(np.diff(ds["s"].values) > 0)
    keep = np.concatenate([[True], np.diff(sol.s) > 0])
    assert np.array_equal(ds["tension"].values, sol.tension[keep])
    run = results["simulation"]
    ds = run.to_xarray()
    assert ds["element_tension"].dims == ("time", "element")
    assert ds["element_tension"].attrs["units"] == "N" and ds["time"].attrs["units"] == "s"
    assert ds["node_position"].dims == ("time", "node", "xyz")
    assert np.array_equal(ds["element_tension"].values, run.segment_tensions)
    md = results["modes"].to_xarray()
    assert md["shape"].dims == ("mode", "node", "xyz") and list(md["mode"].values) == [1, 2, 3]
    assert md["frequency"].attrs["units"] == "rad/s"
    hv = results["heave"]
    ds = hv.to_xarray()
    assert ds["unit_heave"].dims == ("controller", "time") and ds["time"].attrs["units"] == "s"
    assert np.array_equal(ds["unit_heave"].sel(controller="lqr").values, hv.traces["lqr"].x)
    ds = results["batch"].to_xarray()
    assert ds["max_tension"].dims == ("case",) and ds["max_tension"].attrs["units"] == "N"
    assert np.array_equal(ds["max_tension"].values, results["batch"].column("max_tension [N]"))
    ds = results["footprint"].to_xarray()
    assert ds["reach"].dims == ("theta",) and ds["theta"].attrs["units"] == "deg"


def test_to_pandas_tables(results: dict) -> None:
    """One row per node, mode, controller, case and direction."""
    assert len(results["statics"].to_pandas()) == len(results["statics"].to_xarray()["s"])
    modes = results["modes"].to_pandas()
    assert list(modes.index) == [1, 2, 3]
    assert modes["period [s]"].iloc[0] == pytest.approx(2 * np.pi / modes.iloc[0, 0], rel=1e-12)
    heave = results["heave"].to_pandas()
    assert list(heave.index) == ["passive", "lqr"]
    assert heave.loc["lqr", "heave_rms"] == results["heave"].metrics["lqr"].heave_rms
    batch = results["batch"].to_pandas()
    assert list(batch.index) == [0, 1] and list(batch["end_b.tension"]) == [11000, 12000]
    fp = results["footprint"].to_pandas()
    assert list(fp.index) == [0.0, 90.0, 180.0, 270.0] and "reach [m]" in fp


@pytest.mark.parametrize("module", ["xarray", "pandas"])
def test_a_missing_extra_names_the_install(results: dict, module: str,
                                           monkeypatch: pytest.MonkeyPatch) -> None:
    """Without xarray or pandas the conversions raise CableOCPError naming the extra."""
    monkeypatch.setitem(sys.modules, module, None)  # `import module` raises ImportError
    call = "to_xarray" if module == "xarray" else "to_pandas"
    tried = [res for res in results.values() if hasattr(res, call)]
    assert len(tried) >= 5  # every kind; to_pandas: all but the simulation (no one table)
    for res in tried:
        with pytest.raises(co.CableOCPError, match=re.escape(IO_EXTRA)):
            getattr(res, call)()


def test_plot_returns_the_figure_and_the_axes(results: dict) -> None:
    """``plot()`` builds the command's figure, ``(fig, panels)``; ``plot(ax=ax)`` draws on
    that Axes and returns ``(ax.figure, ax)``: the simulation's line is its top tension."""
    for kind, res in results.items():
        fig, axes = res.plot()
        assert isinstance(fig, Figure) and len(axes) >= 1 and axes[0] in fig.axes, kind
        own = Figure()
        ax = own.subplots()
        got = res.plot(ax=ax)
        assert got[0] is own and got[1] is ax and ax.lines, kind
    line = results["simulation"].plot(ax=Figure().subplots())[1].lines[0]
    assert np.array_equal(line.get_ydata(), results["simulation"].top_tension)


def test_write_netcdf_round_trip_and_keeps_the_old_file(results: dict, tmp_path: Path) -> None:
    """The written file reads back equal (exact: float64 stored); a writer that fails part
    way leaves the earlier file as it was and no temporary file."""
    xr = pytest.importorskip("xarray")
    path = tmp_path / "run.nc"
    write_netcdf(results["simulation"], path)
    with xr.open_dataset(path) as back:
        assert np.array_equal(back["element_tension"].values,
                              results["simulation"].segment_tensions)
        assert back["element_tension"].attrs["units"] == "N"

    class Broken:
        def to_netcdf(self, tmp: str, engine: str) -> None:
            Path(tmp).write_bytes(b"half")
            raise OSError(28, "No space left on device")

    class Result:
        def to_xarray(self) -> Broken:
            return Broken()

    before = path.read_bytes()
    with pytest.raises(OSError):
        write_netcdf(Result(), path)
    assert path.read_bytes() == before and sorted(p.name for p in tmp_path.iterdir()) == [
        "run.nc"]


def test_cli_netcdf_is_the_library_writer(tmp_path: Path, results: dict) -> None:
    """``cable-ocp simulate --netcdf`` writes what ``write_netcdf`` writes (same run, same
    numbers: exact)."""
    xr = pytest.importorskip("xarray")
    from cable_ocp.cli import main

    path = tmp_path / "cli.nc"
    rc = main(["simulate", str(DYN), "--set", "simulation.duration=2", "--netcdf", str(path),
               "--quiet"])
    assert rc == 0
    with xr.open_dataset(path) as back:
        ref = results["simulation"].to_xarray()
        assert np.array_equal(back["top_tension"].values, ref["top_tension"].values)
        assert back.attrs["status"] == "solved"
