"""Smoke tests of the figures: each function runs, writes a file of the requested format,
and makes the choices that keep it readable (inspected on the returned Figure).

What is checked is the figure's geometry, not its pixels: which panels exist, that the
seabed and the surface are drawn where the scene puts them, that no legend covers a curve
(every legend is outside every axes), that the sag is visible on the screen, that every axis
label carries a unit in parentheses, and that the heave panels show the limits and the
warm-up.
"""

from __future__ import annotations

import math
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from matplotlib.figure import Figure

from cable_ocp.plots.statics import elevation_plane, plot_statics

ROOT = Path(__file__).resolve().parents[1]
UNIT = re.compile(r"\([^()]*[A-Za-z°%\-][^()]*\)")


# --------------------------------------------------------------------------------------
# helpers: geometry of a drawn figure, in display pixels
# --------------------------------------------------------------------------------------

def _axes(fig: Figure) -> dict[str, object]:
    return {a.get_label(): a for a in fig.axes}


def _draw(fig: Figure):  # noqa: ANN202
    """The renderer of a figure already laid out and drawn by its ``savefig``."""
    return fig.canvas.get_renderer()


def _legends_outside_axes(fig: Figure, r) -> None:  # noqa: ANN001
    """Every figure legend lies outside every axes' box, so it cannot cover a curve."""
    assert fig.legends, "the figure has a legend"
    for leg in fig.legends:
        lb = leg.get_window_extent(r)
        for ax in fig.axes:
            assert not lb.overlaps(ax.get_window_extent(r)), (ax.get_label(), lb)
    for ax in fig.axes:
        assert ax.get_legend() is None, f"no legend inside {ax.get_label()}"


def _no_point_in_legend(fig: Figure, r, ax, x: np.ndarray, y: np.ndarray  # noqa: ANN001
                        ) -> None:
    """No point of a curve drawn in ``ax`` falls inside a legend's box."""
    pts = ax.transData.transform(np.column_stack([x, y]))
    for leg in fig.legends:
        b = leg.get_window_extent(r)
        inside = ((pts[:, 0] >= b.x0) & (pts[:, 0] <= b.x1) & (pts[:, 1] >= b.y0)
                  & (pts[:, 1] <= b.y1))
        assert not inside.any()


def _units_on_labels(fig: Figure) -> None:
    for ax in fig.axes:
        for lab in (ax.get_xlabel(), ax.get_ylabel()):
            if lab:
                assert UNIT.search(lab), f"{ax.get_label()}: label {lab!r} has no unit"


def _magic(path: Path) -> bytes:
    return path.read_bytes()[:8]


# --------------------------------------------------------------------------------------
# statics: real solves of small scenes (well under a second each)
# --------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def mooring():  # noqa: ANN201
    """Planar chain-wire-chain line: seabed contact (touchdown), a clump and a buoy, a
    current 20 deg across the line (which moves it about 0.5 m out of its plane)."""
    from cable_ocp.scene import load_scene
    from cable_ocp.statics.solver import solve

    sc = load_scene(ROOT / "problems" / "mooring_clump_buoy.toml",
                    {"solver.intervals": 24, "solver.error_estimate": False})
    sol = solve(sc)
    assert sol.success
    return sc, sol


@pytest.fixture(scope="module")
def buggy():  # noqa: ANN201
    """De Zoysa's buggy at psi0 = 90 deg: the current bends the line ~28 m out of the
    vertical plane through its ends (a 3D line)."""
    from cable_ocp.scene import load_scene
    from cable_ocp.statics.solver import solve

    sc = load_scene(ROOT / "problems" / "dezoysa_sea_buggy.toml",
                    {"solver.intervals": 16, "solver.error_estimate": False,
                     "layout.psi0_deg": 90.0})
    sol = solve(sc)
    assert sol.success
    return sc, sol


def test_elevation_plane_choice() -> None:
    """Planarity to 1e-3 of the extent; an x-z line snaps to y; a vertical line is planar;
    a helix is not (its nodes lie up to its radius, 10 m, off any vertical plane)."""
    s = np.linspace(0.0, 1.0, 50)
    line = np.column_stack([100 * s, 2.0 + 1e-5 * s, 50 * s ** 2])
    p = elevation_plane(line)
    assert p.planar and p.axis == "x" and p.label == "x (m)"
    assert p.deviation == pytest.approx(1e-5, rel=1e-6)
    vertical = np.column_stack([0 * s, 0 * s, 100 * s])
    assert elevation_plane(vertical).planar
    a = np.radians(45.0)  # a planar line along 45 deg: a distance coordinate, no axis
    diag = np.column_stack([80 * s * math.cos(a), 80 * s * math.sin(a), 30 * s ** 2])
    pd = elevation_plane(diag)
    assert pd.planar and pd.axis is None and pd.heading_deg == pytest.approx(45.0)
    np.testing.assert_allclose(pd.coord(diag[:, :2]), 80 * s, atol=1e-9)
    th = 4 * np.pi * s
    helix = np.column_stack([10 * np.cos(th), 10 * np.sin(th), 100 * s])
    assert not elevation_plane(helix).planar


def test_statics_planar_mooring(mooring, tmp_path: Path) -> None:
    sc, sol = mooring
    fig = plot_statics(sol, tmp_path / "m.png", scene=sc)
    assert _magic(tmp_path / "m.png").startswith(b"\x89PNG")
    axes = _axes(fig)
    assert set(axes) == {"elevation", "tension"}  # planar: side elevation + tension
    el = axes["elevation"]
    assert el.get_xlabel() == "x (m)"
    # the water column (150 m deep, 680 m wide) is exaggerated vertically, and says so
    assert "vertical exaggeration 2x" in el.get_ylabel()
    assert el.get_aspect() == pytest.approx(2.0)
    lines = {ln.get_gid(): ln for ln in el.get_lines() if ln.get_gid()}
    np.testing.assert_allclose(lines["surface"].get_ydata(), 150.0)  # water_depth
    np.testing.assert_allclose(lines["seabed"].get_ydata(), 0.0)     # flat seabed at z = 0
    labels = [ln.get_label() for ln in el.get_lines()]
    for word in ("touchdown", "clump", "buoy", "end_a", "end_b"):
        assert any(word in lab for lab in labels), word
    # the touchdown marker sits at the solution's touchdown point
    tdp = next(ln for ln in el.get_lines() if ln.get_label().startswith("touchdown"))
    assert tdp.get_xdata()[0] == pytest.approx(sol.diagnostics["touchdown"]["position"][0])
    # the sag is visible: on screen the profile leaves its chord by > 10 % of the panel
    r = _draw(fig)
    xy = el.transData.transform(sol.position[:, [0, 2]])
    chord = xy[-1] - xy[0]
    d = xy - xy[0]
    off = np.abs(chord[0] * d[:, 1] - chord[1] * d[:, 0]) / np.linalg.norm(chord)
    assert off.max() > 0.1 * el.get_window_extent(r).height
    # the current arrow lies above every node (in the band over the water)
    arrow = next(t for t in el.texts if t.get_gid() == "current")
    assert arrow.xy[1] > sol.position[:, 2].max()
    _legends_outside_axes(fig, r)
    _no_point_in_legend(fig, r, el, sol.position[:, 0], sol.position[:, 2])
    _no_point_in_legend(fig, r, axes["tension"], sol.s, sol.tension / 1e3)
    _units_on_labels(fig)


def test_statics_3d_buggy(buggy, tmp_path: Path) -> None:
    sc, sol = buggy
    fig = plot_statics(sol, tmp_path / "b.pdf", "De Zoysa", scene=sc)
    assert _magic(tmp_path / "b.pdf").startswith(b"%PDF")
    axes = _axes(fig)
    assert set(axes) == {"3d", "plan", "elevation", "tension"}
    assert axes["3d"].name == "3d"
    plan = axes["plan"]
    assert plan.get_aspect() == 1.0  # plan at true scale
    assert (plan.get_xlabel(), plan.get_ylabel()) == ("x (m)", "y (m)")
    # the line runs from (0, 0) to (0, 229): its elevation is the y-z plane, at true scale
    assert axes["elevation"].get_xlabel() == "y (m)"
    assert axes["elevation"].get_ylabel() == "z (m)"
    # the current is across the elevation: drawn as a symbol, arrow in the plan view
    assert any(t.get_gid() == "current" for t in axes["elevation"].texts)
    assert any(t.get_gid() == "current" for t in plan.texts)
    assert [t.get_text() for t in fig.legends[0].get_texts()].count("T_x") == 1
    r = _draw(fig)
    _legends_outside_axes(fig, r)
    _no_point_in_legend(fig, r, plan, sol.position[:, 0], sol.position[:, 1])
    _units_on_labels(fig)


def test_statics_profile_current_and_no_scene(buggy, tmp_path: Path) -> None:
    """A current varying with depth adds a profile panel; without a scene the figure is
    still drawn (no surface, seabed at z = 0)."""
    from cable_ocp.scene import Current

    sc, sol = buggy
    cur = Current(z=(0.0, 183.0), ux=(0.2, 1.0), uy=(0.0, 0.3))
    sc2 = replace(sc, environment=replace(sc.environment, current=cur))
    fig = plot_statics(sol, tmp_path / "p.svg", scene=sc2)
    assert b"<svg" in (tmp_path / "p.svg").read_bytes()[:400]
    prof = _axes(fig)["current profile"]
    speed = next(ln for ln in prof.get_lines() if ln.get_label() == "current speed")
    z = speed.get_ydata()
    np.testing.assert_allclose(speed.get_xdata(), np.hypot(np.interp(z, cur.z, cur.ux),
                                                           np.interp(z, cur.z, cur.uy)))
    _legends_outside_axes(fig, _draw(fig))
    fig = plot_statics(sol, tmp_path / "n.png")
    assert set(_axes(fig)) == {"3d", "plan", "elevation", "tension"}
    gids = {ln.get_gid() for ln in _axes(fig)["elevation"].get_lines()}
    assert "seabed" in gids and "surface" not in gids


def test_statics_non_finite_iterate(buggy, tmp_path: Path) -> None:
    """A failed solve with a non-finite iterate still gives a figure, which says so."""
    sc, sol = buggy
    pos = sol.position.copy()
    pos[3, 2] = np.nan
    bad = replace(sol, status="failed", message="non-finite iterate", position=pos)
    fig = plot_statics(bad, tmp_path / "bad.png", scene=sc)
    assert (tmp_path / "bad.png").stat().st_size > 1000
    (text,) = _axes(fig)["message"].texts
    assert "not finite" in text.get_text() and "failed" in text.get_text()


# --------------------------------------------------------------------------------------
# footprint, sweep, work-precision: synthetic data (the drawing, not the numbers)
# --------------------------------------------------------------------------------------

def test_footprint_marks_unreachable(tmp_path: Path) -> None:
    from cable_ocp.plots.statics_series import plot_footprint
    from cable_ocp.scene import load_scene
    from cable_ocp.statics.footprint_nlp import FootprintResult

    sc = load_scene(ROOT / "problems" / "footprint_tethered_unit.toml")
    th = np.arange(0.0, 360.0, 15.0)
    reach = 200.0 + 40.0 * np.cos(np.radians(th))
    reach[(th > 150) & (th < 210)] = np.nan  # three unreachable directions
    pts = np.column_stack([reach * np.cos(np.radians(th)), reach * np.sin(np.radians(th))])
    status = ["solved" if np.isfinite(v) else "Infeasible_Problem_Detected" for v in reach]
    res = FootprintResult(th, reach, pts, np.zeros((len(th), 2)), np.full(len(th), 300.0),
                          status, 1.0, np.zeros(2))
    fig = plot_footprint(res, tmp_path / "f.png", "test", scene=sc)
    assert _magic(tmp_path / "f.png").startswith(b"\x89PNG")
    plan = _axes(fig)["plan"]
    crosses = [ln for ln in plan.get_lines() if ln.get_marker() == "x" and len(ln.get_xdata())]
    assert len(crosses) == 3
    assert any(t.get_gid() == "current" for t in plan.texts)
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert "unreachable direction (3)" in labels and any("ship" in lab for lab in labels)
    _legends_outside_axes(fig, _draw(fig))
    _units_on_labels(fig)


def test_sweep_and_work_precision(tmp_path: Path) -> None:
    from cable_ocp.plots.bench import plot_work_precision, read_work_precision_csv
    from cable_ocp.plots.statics_series import plot_sweep

    psi = np.arange(0.0, 181.0, 30.0)
    f = np.column_stack([np.cos(np.radians(psi)), np.sin(np.radians(psi)), 0.3 + 0 * psi])
    fig = plot_sweep(psi, 3e3 * f, tmp_path / "s.png", "psi0 (deg)", "sweep",
                     overlays={"solve_bvp": 3e3 * f}, name="collocation")
    ax = _axes(fig)["sweep"]
    assert ax.get_ylabel() == "force at end_a (kN)"
    assert len(fig.legends[0].get_texts()) == 6
    _legends_outside_axes(fig, _draw(fig))
    _units_on_labels(fig)
    csv = tmp_path / "wp.csv"
    csv.write_text("scene,method,resolution,time_s,status,force_error,profile_error,"
                   "estimate_ratio\n"
                   "A,collocation legendre d=3,4,0.02,solved,1e-4,2e-4,0.5\n"
                   "A,collocation legendre d=3,8,0.03,solved,1e-6,2e-6,0.5\n"
                   "A,scipy solve_bvp,0.001,0.01,solved,1e-3,1e-3,\n"
                   "A,scipy solve_bvp,1e-05,0.05,failed,,,\n"
                   "B,collocation legendre d=3,4,0.02,solved,3e-5,1e-5,0.5\n")
    results = read_work_precision_csv(csv)
    assert [r["scene"] for r in results] == ["A", "B"]
    fig = plot_work_precision(results, tmp_path / "wp.png")
    a = _axes(fig)["A"]
    assert a.get_xscale() == "log" and a.get_yscale() == "log"
    (coll,) = [ln for ln in a.get_lines() if ln.get_label().startswith("collocation")]
    np.testing.assert_allclose(coll.get_xdata(), [20.0, 30.0])   # ms
    np.testing.assert_allclose(coll.get_ydata(), [2e-4, 2e-6])   # larger of the two errors
    _legends_outside_axes(fig, _draw(fig))
    _units_on_labels(fig)
    # the CSV as `bench accuracy --csv` writes it (headers with units, CPU times): the
    # time axis is then the CPU time, and a 2nd-process series takes its series' colour
    from cable_ocp.cli.bench import ACCURACY_HEADER

    csv.write_text(",".join(ACCURACY_HEADER) + "\n"
                   "A,collocation legendre d=3,4,0.02,0.01,solved,1e-4,2e-4,0.5\n"
                   "A,collocation legendre d=3 (2nd process),4,0.008,0.004,solved,1e-4,2e-4,\n"
                   "A,scipy solve_bvp,0.001,0.03,0.02,solved,1e-3,1e-3,\n")
    fig = plot_work_precision(read_work_precision_csv(csv), tmp_path / "wp2.png")
    a = _axes(fig)["A"]
    assert a.get_xlabel().startswith("CPU time")
    lines = {ln.get_label(): ln for ln in a.get_lines()}
    np.testing.assert_allclose(lines["collocation legendre d=3"].get_xdata(), [10.0])  # ms
    np.testing.assert_allclose(lines["scipy solve_bvp"].get_xdata(), [20.0])
    assert (lines["collocation legendre d=3 (2nd process)"].get_color()
            == lines["collocation legendre d=3"].get_color())


# --------------------------------------------------------------------------------------
# heave: a synthetic comparison on the 6.3.6 scene (no simulation)
# --------------------------------------------------------------------------------------

def test_heave_comparison(tmp_path: Path) -> None:
    from cable_ocp.heave import sea
    from cable_ocp.heave.closed_loop import Trace
    from cable_ocp.heave.design_loop import Models
    from cable_ocp.heave.metrics import Comparison, Metrics
    from cable_ocp.plots.heave import plot_comparison, running_rms
    from cable_ocp.scene.heave import load_scene

    sc = load_scene(ROOT / "problems" / "heave" / "ex_6_3_6.toml")
    spec = sea.SeaSpectrum("bretschneider", 3.048, 0.785)
    fit = sea.make_shaping_filter(spec, "thesis", 3)
    t = np.arange(0.0, 60.0, 0.01)
    x0 = 0.3 * np.sin(0.8 * t)
    amp = {"passive": 0.25, "lqr": 3e-4, "mpc": 3e-4, "lqg": 2e-2}
    traces, metrics = {}, {}
    for k, a in amp.items():
        x = a * np.sin(0.8 * t + 0.3)
        if k != "passive":
            x = x + 50 * a * np.exp(-t)  # a start-up transient inside the 30 s warm-up
        u = 0.0 * t if k == "passive" else 0.3 * np.sin(0.8 * t)
        traces[k] = Trace(t, x, x0, u, np.gradient(u, t), u)
        metrics[k] = Metrics(a / math.sqrt(2), 0.0, 0.2, 0.3, None, 0.0, None, 0.1)
    res = Comparison(0.255, metrics, traces, Models(spec, fit, None, 0.255), None, 0)
    td = {"tau = 0": np.array([[1.0, 2.0, 3.0, 4.0], [2.0, 1.0, 1.5, 5.0]])}
    fig = plot_comparison(res, tmp_path / "h.png", td, scene=sc)
    assert _magic(tmp_path / "h.png").startswith(b"\x89PNG")
    axes = _axes(fig)
    assert {"spectrum", "passive", "rms", "stroke", "speed", "tradeoff_d", "tradeoff_v",
            "controlled lqr", "controlled lqg", "controlled mpc"} <= set(axes)
    # the controlled heave has its own scale, fitted after the warm-up (mm): the
    # transient does not set it, and the 0.3 mm response fills it
    lo, hi = axes["controlled lqr"].get_ylim()
    assert hi == pytest.approx(1.15 * 0.3, rel=0.02) and lo == pytest.approx(-hi)
    assert axes["rms"].get_yscale() == "log"
    # limits as lines at +-stroke_max and +-speed_max; the warm-up shaded
    for name, lim in (("stroke", sc.winch.stroke_max), ("speed", sc.winch.speed_max)):
        ys = sorted(ln.get_ydata()[0] for ln in axes[name].get_lines()
                    if ln.get_gid() == "limit")
        assert ys == [-lim, lim]
        spans = [p for p in axes[name].patches if p.get_gid() == "warmup"]
        assert len(spans) == 1
    # titles in words, with the thesis figure of section 6.3.6
    assert "Fig. 6.24" in axes["controlled lqr"].get_title()
    assert "Fig. 6.21" in axes["spectrum"].get_title()
    _legends_outside_axes(fig, _draw(fig))
    _units_on_labels(fig)
    # passive only, no trade-off: three rows, and the controlled cell says why it is empty
    only = Comparison(0.255, {"passive": metrics["passive"]}, {"passive": traces["passive"]},
                      res.models, None, 0)
    fig = plot_comparison(only, tmp_path / "p.svg", scene=sc)
    assert "tradeoff_d" not in _axes(fig)
    assert "no controller" in _axes(fig)["controlled"].texts[0].get_text()
    # running RMS of a sine of amplitude A over whole periods is A / sqrt(2)
    tt, rms = running_rms(t, np.sin(2 * np.pi * t), 10.0)
    np.testing.assert_allclose(rms, 1 / math.sqrt(2), rtol=2e-3)
    assert tt[0] == pytest.approx(9.99)
