"""Footprint (Huang 1992, section 2.2.4): an NLP per direction over thrust and cable length."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from cable_ocp.cli import main
from cable_ocp.errors import CableOCPError
from cable_ocp.scene import load_scene
from cable_ocp.statics.footprint_nlp import footprint

W, H_SHIP, T_MAX, L_MAX, L_MIN = 12.3, 183.0, 2000.0, 305.0, 190.0


def _catenary_length(h: float, v0: float) -> float:
    """Length of an inextensible catenary with horizontal tension h and vertical force v0
    at its lower end that rises H_SHIP (from h/W (sqrt(1+((v0+WL)/h)^2) - sqrt(1+(v0/h)^2))
    = H_SHIP solved for L)."""
    c = W * H_SHIP / h + math.sqrt(1.0 + (v0 / h) ** 2)
    return (h * math.sqrt(c * c - 1.0) - v0) / W


def _span(h: float, v0: float) -> float:
    length = _catenary_length(h, v0)
    return h / W * (math.asinh((v0 + W * length) / h) - math.asinh(v0 / h))


def still_water_radius() -> float:
    """Independent answer in still water: the largest span of an inextensible catenary
    from the unit (horizontal tension H <= T_max = the thrust, vertical force V0 >= 0 at
    the unit) to the ship H_SHIP above, with L in [L_min, L_max].

    Closed form: the span grows with H and falls with V0, so the optimum is H = T_max,
    V0 = 0 (the catenary's vertex at the unit), span = (H/W) acosh(1 + W H_SHIP / H),
    provided that catenary's length lies in [L_min, L_max] (asserted). The monotonicity
    is checked numerically by a bounded scalar search over V0 at H = T_max and over H at
    V0 = 0 (scipy's bounded Brent; SLSQP on the joint problem stops early on newer scipy).
    """
    radius = T_MAX / W * math.acosh(1.0 + W * H_SHIP / T_MAX)
    assert L_MIN <= _catenary_length(T_MAX, 0.0) <= L_MAX
    by_v0 = minimize_scalar(lambda v: -_span(T_MAX, v), bounds=(0.0, 5000.0),
                            method="bounded", options={"xatol": 1e-10})
    by_h = minimize_scalar(lambda h: -_span(h, 0.0), bounds=(1.0, T_MAX),
                           method="bounded", options={"xatol": 1e-10})
    assert -by_v0.fun <= radius * (1 + 1e-12) and -by_h.fun <= radius * (1 + 1e-12)
    # bounded Brent approaches the bound H = T_max to ~1e-5 N, not exactly: 1e-7 relative
    assert -by_h.fun == pytest.approx(radius, rel=1e-7)
    return radius


def test_still_water_footprint_is_the_catenary_circle(problems):
    """No current: the footprint is a circle, every direction reaches the radius of the
    independent catenary optimisation (to 1e-6 relative: both are converged optimisers on
    the same physics, the collocation error at 40 intervals of degree 3 is ~1e-10)."""
    sc = load_scene(problems / "footprint_tethered_unit.toml")
    sc = sc.with_overrides({"environment": {"water_depth": 183.0, "water_density": 1021.0}})
    res = footprint(sc, directions=8)
    assert all(s == "solved" for s in res.status)
    np.testing.assert_allclose(res.reach, still_water_radius(), rtol=1e-6)
    np.testing.assert_allclose(np.hypot(*res.thrust.T), T_MAX, rtol=1e-6)


def test_current_footprint_shape(problems):
    """In the current along +x the footprint is symmetric about the x axis and reaches
    further downstream than upstream; the thrust bound is active everywhere."""
    res = footprint(load_scene(problems / "footprint_tethered_unit.toml"), directions=12)
    assert all(s == "solved" for s in res.status)
    r = dict(zip(res.theta_deg, res.reach, strict=True))
    for a in (30.0, 60.0, 90.0, 120.0, 150.0):
        assert r[a] == pytest.approx(r[360.0 - a], rel=1e-6)
    assert r[0.0] > r[90.0] > r[180.0]
    np.testing.assert_allclose(np.hypot(*res.thrust.T), T_MAX, rtol=1e-6)
    assert np.all(res.length <= L_MAX + 1e-6)


def test_unreachable_directions_are_reported(problems):
    """With 50 N of thrust and 200 m of cable the unit cannot leave the downstream wake
    line: every cross-stream direction reports a failure of the NLP (NaN reach, never a
    number), and even pushing upstream at full thrust it stays downstream of the ship
    (reach along 180 deg negative, as Huang's c1 allows). IPOPT's iteration cap is 60 here
    (300 by default): the two reachable directions converge within it (in 22-40 iterations),
    and an unreachable one ends at the cap instead of proving its infeasibility (68-231
    iterations at the default; the cap bounds the time, not the check). Four directions
    (0, 90, 180, 270 deg): both reachable ones and both cross-stream ones (8 directions
    took 14 s in CI, the 45 deg ones failing as the 90 deg ones do)."""
    sc = load_scene(problems / "footprint_tethered_unit.toml", {"footprint.thrust_max": 50.0,
                                                                "footprint.max_length": 200.0})
    res = footprint(sc, directions=4, max_iterations=60)
    assert list(res.theta_deg) == [0.0, 90.0, 180.0, 270.0]
    assert res.status[0] == res.status[2] == "solved"
    for k in (1, 3):
        assert res.status[k] != "solved" and math.isnan(res.reach[k])
    assert res.reach[0] > 0 > res.reach[2]


def test_footprint_cli(problems, tmp_path, capsys):
    png = tmp_path / "fp.png"
    assert main(["footprint", str(problems / "footprint_tethered_unit.toml"),
                 "--directions", "8", "--plot", str(png)]) == 0
    out = capsys.readouterr().out
    assert "reach" in out and png.stat().st_size > 10_000
    with pytest.raises(CableOCPError, match="footprint"):
        footprint(load_scene(problems / "dezoysa_sea_buggy.toml"))
