"""The dynamics figures read at a glance, checked on the numbers the figure objects hold.

- a long time series is an envelope whose band is the min and max of the data over each
  window (the windows read back from the band's own edges), short ones a line of the data;
- the unit's heave is drawn as z - z_static (the static start is the t = 0 sample);
- the lumped-mass figure has a plan view whose lines are the node x, y and a 3D view;
- a scene without excitation carries a warning (and the CLI one stderr line), one with
  excitation none, and the status stays "solved";
- axial mode shapes are drawn as axial displacement against depth, one curve per mode,
  each the mode's own (normalised) axial component;
- every title lies inside its figure.

Runs are short (0.5 s of the 6.3.6 line, 200 s of 3.3.5's axial lowering in 4000 steps):
about 3 s in all.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from matplotlib.figure import Figure

from cable_ocp.dynamics import simulate

ROOT = Path(__file__).resolve().parents[1]
DYN = ROOT / "problems" / "dynamics"
LUMPED = DYN / "line_6_3_6_lumped3d.toml"
HEAVE = {"top_motion.heave_amplitude": 1.0, "top_motion.heave_frequency": 0.6}


def _axes(fig: Figure) -> dict[str, object]:
    return {a.get_label(): a for a in fig.axes}


def _band(ax) -> tuple[np.ndarray, np.ndarray, np.ndarray]:  # noqa: ANN001
    """(edges, lo, hi) of the envelope drawn by plots.common.series in ``ax``: the window
    edges (start, end, start, end, ...) and each edge's lower and upper value, read back
    from the filled polygon (lower boundary forwards, then the upper one backwards)."""
    (band,) = [c for c in ax.collections if c.get_gid() == "envelope"]
    v = band.get_paths()[0].vertices
    m = (len(v) - 3) // 2
    x, lo = v[1:m + 1, 0], v[1:m + 1, 1]
    hi = v[m + 2:2 * m + 2, 1][::-1]
    np.testing.assert_array_equal(v[m + 2:2 * m + 2, 0][::-1], x)
    return x, lo, hi


def _check_envelope(ax, t: np.ndarray, y: np.ndarray) -> None:  # noqa: ANN001
    """The band of ``ax`` is, window by window, the min and max of ``y`` over the samples
    of that window (both edges included)."""
    x, lo, hi = _band(ax)
    i0 = np.searchsorted(t, x[0::2])
    i1 = np.searchsorted(t, x[1::2])
    np.testing.assert_array_equal(t[i0], x[0::2])  # the edges are sample times
    assert i0[0] == 0 and i1[-1] == len(t) - 1 and np.all(i0[1:] == i1[:-1])
    want_lo = [np.nanmin(y[a:b + 1]) for a, b in zip(i0, i1, strict=True)]
    want_hi = [np.nanmax(y[a:b + 1]) for a, b in zip(i0, i1, strict=True)]
    # exact: the band holds the data's own values
    np.testing.assert_array_equal(lo[0::2], want_lo)
    np.testing.assert_array_equal(lo[1::2], want_lo)
    np.testing.assert_array_equal(hi[0::2], want_hi)
    np.testing.assert_array_equal(hi[1::2], want_hi)


def _titles_inside(fig: Figure) -> None:
    """Every title (the figure's and each axes') lies within the figure's width."""
    r = fig.canvas.get_renderer()
    width = fig.get_figwidth() * fig.dpi
    texts = [fig.get_suptitle() and fig._suptitle] + [a.title for a in fig.axes]
    for txt in filter(None, texts):
        if txt.get_text():
            e = txt.get_window_extent(r)
            assert 0.0 <= e.x0 and e.x1 <= width, (txt.get_text(), e, width)


def test_series_line_or_envelope_of_window_extremes() -> None:
    """Few samples for the axes' width: the line is the data. Many: the band is each
    window's min and max (NaN samples left out), the mean line each window's mean."""
    from cable_ocp.plots.common import new_figure, series

    fig = new_figure(6.0, 3.0)
    ax = fig.subplots()
    t = np.arange(0.0, 2000.0, 0.05)
    y = np.sin(1.26 * t) * (1.0 + t / 500.0) + 0.01 * t
    y[[7, 5000, 5001]] = np.nan
    s = series(ax, t, y, label="y")
    assert s.window is not None and s.handle.get_gid() == "envelope"
    _check_envelope(ax, t, y)
    # the mean line: each window's mean of the finite samples, at the window's middle
    x, _, _ = _band(ax)
    i0, i1 = np.searchsorted(t, x[0::2]), np.searchsorted(t, x[1::2])
    np.testing.assert_allclose(s.line.get_ydata(),
                               [np.nanmean(y[a:b + 1]) for a, b in zip(i0, i1, strict=True)],
                               rtol=1e-12, atol=1e-12)  # a sum in another order
    # windows of a few pixels: at least 100 over a 6 in figure, each several samples
    assert 100 <= len(i0) <= 400 and np.all(i1 - i0 >= 2)
    ax2 = fig.add_subplot(2, 1, 2)
    s2 = series(ax2, t[:300], y[:300])
    assert s2.window is None
    np.testing.assert_array_equal(s2.line.get_ydata(), y[:300])


def test_long_simulation_is_drawn_as_envelopes(tmp_path: Path) -> None:
    """200 s of 3.3.5's lowering sampled every 0.05 s (4001 samples, about 160 wave
    periods): the top tension and the heave panel are envelopes of the result's data; the
    unit panel is its heave from the static position."""
    from cable_ocp.plots.dynamics import plot_simulation

    res = simulate(DYN / "huang_3_3_5.toml",
                   overrides={"simulation.duration": 200.0, "simulation.output_step": 0.05})
    assert res.status == "solved" and len(res.t) == 4001
    fig = plot_simulation(res, tmp_path / "s.png")
    ax = _axes(fig)
    _check_envelope(ax["top tension"], res.t, res.top_tension / 1e3)  # kN on the axis
    zu = res.unit_position[:, 2] - res.unit_position[0, 2]
    paid = res.length - res.length[0]
    bands = [c for c in ax["heave"].collections if c.get_gid() == "envelope"]
    assert len(bands) == 2  # top, then unit about its lowering path
    for c in bands[:1]:
        c.remove()
    _check_envelope(ax["heave"], res.t, zu + paid)
    _check_envelope(ax["unit"], res.t, zu)
    assert "z - z_static" in ax["unit"].get_ylabel()
    _titles_inside(fig)


def test_lumped_figure_heave_plan_3d_and_excitation_warning(tmp_path: Path,
                                                            capsys: pytest.CaptureFixture
                                                            ) -> None:
    """0.5 s of the 6.3.6 lumped line. With top heave: no warning; the heave panel's unit
    line is z - z_static; the plan view's lines are the nodes' x, y at t = 0 and at the end;
    a 3D view. The shipped file (no top motion): solved, with the warning, which the CLI
    prints as one stderr line."""
    from cable_ocp.cli import main
    from cable_ocp.dynamics.simulation import NO_EXCITATION
    from cable_ocp.plots.dynamics import plot_simulation

    res = simulate(LUMPED, overrides={"simulation.duration": 0.5, **HEAVE})
    assert res.status == "solved" and res.diagnostics["excitation"] == ["top motion"]
    assert not any("nothing excites" in w for w in res.warnings)
    fig = plot_simulation(res, tmp_path / "l.png", title="6.3.6 lumped")
    ax = _axes(fig)
    (unit,) = [ln for ln in ax["heave"].get_lines() if ln.get_label().startswith("unit")]
    z = res.unit_position[:, 2]
    np.testing.assert_array_equal(unit.get_ydata(), z - z[0])
    assert np.ptp(z) > 0.0 and abs(z[0]) > 2000.0  # the absolute z would be far off
    lines = {ln.get_gid(): ln for ln in ax["plan"].get_lines()}
    r = res.node_positions
    np.testing.assert_array_equal(lines["line-start"].get_xydata(), r[0, :, :2])
    np.testing.assert_array_equal(lines["line-end"].get_xydata(), r[-1, :, :2])
    np.testing.assert_array_equal(lines["unit-path"].get_xydata(), res.unit_position[:, :2])
    assert ax["3d"].name == "3d"
    _titles_inside(fig)

    still = simulate(LUMPED, overrides={"simulation.duration": 0.5})
    assert still.status == "solved" and still.diagnostics["excitation"] == []
    assert NO_EXCITATION.format(duration=0.5) in still.warnings
    capsys.readouterr()
    rc = main(["simulate", str(LUMPED), "--set", "simulation.duration=0.5", "--quiet"])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 0 and len(err) == 1 and err[0].startswith("warning: nothing excites")


def test_axial_modes_are_displacement_against_depth(tmp_path: Path) -> None:
    """The 6.3.6 axial line: one curve per mode, u against depth below end_b, equal to the
    mode's axial (z) component over its largest magnitude, the curves different."""
    from cable_ocp.dynamics.modal import modes
    from cable_ocp.plots.dynamics import plot_modes
    from cable_ocp.scene.dynamics import load_dynamic_scene

    res = modes(load_dynamic_scene(DYN / "line_6_3_6.toml"), 3)
    assert res.model == "axial" and len(res.frequencies) == 3
    title = load_dynamic_scene(DYN / "line_6_3_6.toml").statics.meta["title"]
    fig = plot_modes(res, tmp_path / "m.png", title=title)
    (ax,) = fig.axes
    curves = [ln for ln in ax.get_lines() if (ln.get_gid() or "").startswith("mode")]
    assert len(curves) == 3
    r = res.node_positions
    for k, ln in enumerate(curves):
        w = res.shapes[k, :, 2]  # a vertical line: the axial component is dz
        np.testing.assert_allclose(ln.get_xdata(), w / np.max(np.abs(w)), atol=1e-12)
        np.testing.assert_allclose(ln.get_ydata(), r[-1, 2] - r[:, 2], atol=1e-12)
        assert f"{res.frequencies[k]:.4g} rad/s" in ln.get_label()
    for i in range(3):
        for j in range(i):
            assert np.max(np.abs(curves[i].get_xdata() - curves[j].get_xdata())) > 0.3
    _titles_inside(fig)


def test_titles_are_fitted_to_the_figure(tmp_path: Path) -> None:
    """A suptitle twice the figure's width is wrapped, a long axes title and an unbreakable
    one shrunk or wrapped, until each lies inside the figure."""
    from cable_ocp.plots.common import fit_titles, new_figure, save

    fig = new_figure(4.0, 3.0)
    ax = fig.subplots()
    ax.set_title("a panel title that is much too long for a figure four inches wide, "
                 "surely", fontsize=12)
    fig.suptitle("word " * 40, fontsize=12)
    save(fig, tmp_path / "t.png")
    _titles_inside(fig)
    assert "\n" in fig.get_suptitle()
    fig = new_figure(3.0, 2.0)
    fig.subplots().set_title("x" * 80)
    fit_titles(fig)
    _titles_inside(fig)
