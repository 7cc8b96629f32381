"""A current on one line: ours against the closed form and against MoorPy's smeared load
(cable_ocp/bench/moorpy_current.py; moorpy only where importorskip'd)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from cable_ocp.bench import moorpy_current as mc


@pytest.mark.parametrize("direction", [1.0, -1.0])
def test_straight_line_in_a_current_along_it_equals_the_closed_form(direction: float) -> None:
    case = mc.exact_case(direction)
    lt = case["line_types"]["line"]
    u = case["environment"]["current"]["speed"]
    # the load written out here, not through the physics module: 1/2 rho C_dt (pi d) U^2
    load = 0.5 * mc.RHO * lt["tangential_drag"] * math.pi * lt["diameter"] * u * u
    t_up, t_down = mc.straight_closed_form(case["lines"][0]["length"], 200.0,
                                           lt["axial_stiffness"], load)
    # the upstream end holds the line: it carries the larger tension, by the whole drag
    assert t_up - t_down == pytest.approx(load * 200.0, rel=1e-12)
    o = mc.ours(case)
    ta = float(np.linalg.norm(o["force_anchor"]))
    tb = float(np.linalg.norm(o["force_fairlead"]))
    want_a, want_b = (t_up, t_down) if direction > 0 else (t_down, t_up)
    # straight line, tension linear in the stretched arc: the collocation is exact up to the
    # Newton tolerance (1e-9 relative); 3e-10 seen
    assert ta == pytest.approx(want_a, rel=1e-6)
    assert tb == pytest.approx(want_b, rel=1e-6)
    # the forces lie along the chord (x): the drag has no normal part
    assert abs(o["force_anchor"][2]) < 1e-6 * ta and abs(o["force_anchor"][1]) < 1e-6 * ta


def test_moorpy_equals_ours_where_its_smeared_load_is_exact() -> None:
    pytest.importorskip("moorpy")
    rows = mc.exact_rows()
    for row in rows:
        # MoorPy smears the stretched-length total over the unstretched length: off by the
        # spread of T/EA along the line (3.6e-6 here) times its share, 1.3e-7 seen
        assert row["moorpy_rel"] < 1e-6
        assert row["ours_vs_moorpy"] < 1e-6


def test_moorpy_differs_by_its_smear_and_its_tilted_seabed() -> None:
    pytest.importorskip("moorpy")
    rows = mc.realistic_rows(("suspended",), ("along, towards fairlead",))
    rows += mc.realistic_rows(("touchdown",), ("along, towards fairlead",))
    susp, td = rows
    # suspended: a real difference (0.2-0.3 % seen), within the L1 norm of the load MoorPy
    # moves (4.2 kN; 1.6 kN seen)
    assert susp["rel_fairlead"] > 1e-4
    assert susp["diff_anchor_N"] < susp["bound_N"]
    assert susp["diff_fairlead_N"] < susp["bound_N"]
    # touchdown: MoorPy's answer is the current-free catenary in its rotated frame (our
    # solver on that problem gives MoorPy's tensions to the Newton tolerances; 1e-12 seen)
    assert td["mimic_vs_moorpy"] < 1e-6
    # and that frame's seabed rises towards the fairlead by tan(tilt) per metre of span
    assert td["moorpy_rise_change_m"] == pytest.approx(
        -780.0 * math.tan(math.radians(td["moorpy_tilt_deg"])), rel=0.05)
    # so the difference is far beyond the smear (34 % at the anchor seen)
    assert td["diff_anchor_N"] > 5.0 * td["bound_N"]
    assert td["moorpy_laid_m"] > td["ours_laid_m"]
