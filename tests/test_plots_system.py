"""The mooring-system figures, checked on the numbers their artists hold (not pixels).

The 3-line spar (problems/systems/spar_3line.toml) is solved once (about 0.1 s):

- each line in the plan and in the 3D view is one LineCollection whose segments are the
  solution's consecutive node positions and whose values are the segment tensions (kN);
- one colour scale for all lines: its limits are the smallest and largest node tension of
  the system, kN;
- the heading arrow of a body points along its yaw (a copy of the result turned to 35 deg);
- free points are drawn as labelled squares; the summary names the largest tension and
  the smallest safety factor of the result;
- the offset curve draws the arrays it is given, in kN;
- ``SystemResult.plot`` returns (fig, axes) or draws the plan on a given axes;
- a saved figure is a PNG.
"""

from __future__ import annotations

import copy
import dataclasses
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure

from cable_ocp.mooring import solve_system
from cable_ocp.scene.system import system_from_dict

ROOT = Path(__file__).resolve().parents[1]
SPAR = ROOT / "problems" / "systems" / "spar_3line.toml"


@pytest.fixture(scope="module")
def spar():  # noqa: ANN201
    scene = system_from_dict(tomllib.loads(SPAR.read_text()))
    res = solve_system(scene)
    assert res.status == "solved"
    return scene, res


def _axes(fig: Figure) -> dict[str, object]:
    return {a.get_label(): a for a in fig.axes}


def _lines(ax) -> dict[str, LineCollection]:  # noqa: ANN001
    return {c.get_gid()[5:]: c for c in ax.collections
            if (c.get_gid() or "").startswith("line:")}


def test_lines_are_the_solved_profiles_coloured_by_tension(spar, tmp_path: Path) -> None:  # noqa: ANN001
    """Plan and 3D: the segments are the node positions (exact: the arrays themselves), the
    values the mean node tension of each segment in kN, the shared scale from the least to
    the largest node tension; the colorbar says kN; the summary names L2's 2432 kN."""
    from cable_ocp.plots.common import save
    from cable_ocp.plots.system import system_figure

    scene, res = spar
    fig = system_figure(res, scene)
    ax = _axes(fig)
    assert ax["3d"].name == "3d"
    t_all = np.concatenate([res.solutions[n].tension for n in res.solutions])
    for view, dims in (("plan", 2), ("3d", 3)):
        lines = _lines(ax[view])
        assert set(lines) == {"L1", "L2", "L3"}
        for name, lc in lines.items():
            r = res.solutions[name].position
            t = res.solutions[name].tension
            if dims == 2:
                segs = np.asarray(lc.get_segments())
            else:  # Line3DCollection keeps the 3D segments it was given
                segs = np.asarray(lc._segments3d)
            np.testing.assert_array_equal(segs[:, 0, :], r[:-1, :dims])
            np.testing.assert_array_equal(segs[:, 1, :], r[1:, :dims])
            # exact up to the rounding of (a + b) / 2 / 1e3
            np.testing.assert_allclose(lc.get_array(), 0.5 * (t[:-1] + t[1:]) / 1e3,
                                       rtol=1e-15)
            assert lc.norm.vmin == pytest.approx(t_all.min() / 1e3, rel=1e-15)
            assert lc.norm.vmax == pytest.approx(t_all.max() / 1e3, rel=1e-15)
    # the lines differ in tension: the scale spans more than 1 MN
    assert lc.norm.vmax - lc.norm.vmin > 1e3
    assert "kN" in ax["tension"].get_ylabel()
    # the largest node tension is the result's largest line tension (the fairlead's)
    assert t_all.max() == pytest.approx(res.max_tension, rel=1e-12)
    (box,) = [t for t in ax["3d"].texts if t.get_gid() == "summary"]
    assert f"{res.max_tension / 1e3:.4g} kN (L2)" in box.get_text()
    assert f"{res.min_safety_factor:.3g} (L2)" in box.get_text()
    # the seabed and the free surface are drawn in the 3D view with the scene
    assert len(ax["3d"].collections) - 3 == 2
    png = save(fig, tmp_path / "system.png")
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000


def test_heading_arrow_free_points_and_labels(spar) -> None:  # noqa: ANN001
    """A copy of the result with the spar turned to yaw 35 deg and a free point: the arrow
    runs from the reference point along (cos 35, sin 35); the free point is a square with
    its name beside it; every line name sits near its line's middle."""
    from cable_ocp.plots.system import system_figure

    _, res = spar
    bodies = copy.deepcopy(res.bodies)
    bodies[0]["rotation_deg"] = [0.0, 2.0, 35.0]
    points = res.points + [{"name": "clump1", "kind": "free", "position": [400.0, 200.0, 30.0]}]
    turned = dataclasses.replace(res, bodies=bodies, points=points)
    plan = _axes(system_figure(turned))["plan"]
    (arrow,) = [t for t in plan.texts if t.get_gid() == "heading:spar"]
    d = np.subtract(arrow.xy, arrow.xyann)
    np.testing.assert_array_equal(arrow.xyann, bodies[0]["position"][:2])
    assert math.degrees(math.atan2(d[1], d[0])) == pytest.approx(35.0, abs=1e-12)
    (free,) = [ln for ln in plan.get_lines() if ln.get_gid() == "points:free"]
    assert free.get_marker() == "s"
    np.testing.assert_array_equal(free.get_xydata(), [[400.0, 200.0]])
    (lab,) = [t for t in plan.texts if t.get_gid() == "label:clump1"]
    assert lab.get_text() == "clump1"
    assert 0 < np.hypot(*(np.array(lab.get_position()) - [400.0, 200.0])) < 150.0
    for name in ("L1", "L2", "L3"):
        (txt,) = [t for t in plan.texts if t.get_gid() == f"name:{name}"]
        r = res.solutions[name].position[:, :2]
        # within a tenth of the plan's extent (about 1700 m) of the line's nodes
        assert np.min(np.hypot(*(r - txt.get_position()).T)) < 170.0


def test_offset_curve_draws_its_arrays_in_kn(tmp_path: Path) -> None:
    """The restoring force and the tensions are the given arrays over 1e3; one panel
    without tensions; a force array of the wrong length is refused."""
    from cable_ocp.plots.system import offset_curve_figure

    x = np.linspace(-30.0, 30.0, 13)
    f = -5e4 * x - 200.0 * x**3
    tens = {"L1": 1.4e6 + 3e4 * x, "L2": 2e6 - 2e4 * x}
    fig = offset_curve_figure(x, f, tens, title="offset")
    ax = _axes(fig)
    (rest,) = [ln for ln in ax["restoring"].get_lines() if ln.get_gid() == "restoring"]
    np.testing.assert_array_equal(rest.get_xdata(), x)
    np.testing.assert_array_equal(rest.get_ydata(), f / 1e3)
    assert ax["restoring"].get_ylabel() == "restoring force (kN)"
    assert ax["restoring"].get_xlabel() == "offset (m)"
    for name, t in tens.items():
        (ln,) = [ln for ln in ax["tensions"].get_lines() if ln.get_gid() == f"tension:{name}"]
        np.testing.assert_array_equal(ln.get_ydata(), t / 1e3)
    assert len(offset_curve_figure(x, f).axes) == 1
    with pytest.raises(ValueError, match="one force per offset"):
        offset_curve_figure(x, f[:-1])


def test_result_plot_accessor(spar) -> None:  # noqa: ANN001
    """``plot()``: the figure and its panels; ``plot(ax=...)``: the plan on that axes."""
    from cable_ocp.plots.common import new_figure

    scene, res = spar
    fig, axes = res.plot(scene=scene)
    assert {a.get_label() for a in axes} >= {"plan", "3d", "tension"}
    own = new_figure(5.0, 5.0)
    ax = own.subplots()
    fig2, ax2 = res.plot(ax=ax)
    assert fig2 is own and ax2 is ax
    lines = _lines(ax)
    np.testing.assert_array_equal(np.asarray(lines["L1"].get_segments())[:, 0, :],
                                  res.solutions["L1"].position[:-1, :2])
