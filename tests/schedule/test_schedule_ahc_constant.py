"""The constant-speed baseline with heave compensation (cable_ocp/schedule/forward.py
``fastest_constant_speed(ahc_gain=...)``, the forward check's compensation limits) and the
compared gain of ``cable-ocp bench deploy`` (cable_ocp/bench/deployment.py
``comparison_gain``), issue 25.

The runs are huang_3_3_5.toml (a 50 m line, a 13 t virtual unit mass, its own harmonic
heave of 0.5 m at 1.26 rad/s faded in over 30 s) paid out to 80 m on 5 elements at 0.05 s
(a fraction of a second each)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from cable_ocp.bench.deployment import comparison_gain
from cable_ocp.errors import CableOCPError
from cable_ocp.scene.dynamics import load_dynamic_scene
from cable_ocp.schedule.forward import fastest_constant_speed, resimulate, trapezoid_schedule
from cable_ocp.schedule.sea import vessel_motions

ROOT = Path(__file__).resolve().parents[2]
HUANG = ROOT / "problems" / "dynamics" / "huang_3_3_5.toml"
COARSE = {"deployment.target_length": 80.0, "simulation.segments": 5,
          "simulation.time_step": 0.05}
#: m and m/s: the scene's heave amplitude and frequency (huang_3_3_5.toml [top_motion])
AMP, FREQ = 0.5, 1.26


def _scene(**deploy):
    ov = dict(COARSE)
    ov.update({f"deployment.{k}": v for k, v in deploy.items()})
    return load_dynamic_scene(HUANG, ov)


def test_constant_speed_with_gain_is_the_compensated_trapezoid_resimulated():
    g = 0.6
    # tension_min binds near 1.52 m/s: the bracket 1.2-1.6 m/s keeps the runs to a few
    scene = _scene(tension_min=25000.0, accel_max=0.5, speed_max=1.6, ahc_stroke=2.0,
                   ahc_speed=1.5)
    motions = vessel_motions(scene)
    res = fastest_constant_speed(scene, motions, rel_tol=0.05, floor=1.2, ahc_gain=g)
    assert res.status == "solved" and res.schedule is not None
    assert res.binding == "tension_min" and res.simulations <= 4
    assert res.schedule.ahc_gain == g
    # the accepted run is the trapezoid of that speed with the gain, re-simulated: the same
    # simulation, so the same tensions to round-off
    again = resimulate(scene, trapezoid_schedule(50.0, 80.0, res.speed, 0.5, ahc_gain=g),
                       motions[0])
    chk = res.checks[-1]
    assert np.allclose(chk.tension_min_line, again.tension_min_line, rtol=1e-12, atol=1e-9)
    assert again.keeps_limits(0.0)
    # and not the uncompensated one: the winch's table carries g dz/dt (its speeds differ
    # by g times the heave's rate, up to g A omega = 0.378 m/s once faded in)
    plain = resimulate(scene, trapezoid_schedule(50.0, 80.0, res.speed, 0.5), motions[0])
    gap = np.max(np.abs(chk.speed - plain.speed))
    assert gap == pytest.approx(g * AMP * FREQ, rel=0.02)  # 2 %: the rate's peak sampled
    assert not np.allclose(chk.tension_min_line, plain.tension_min_line, rtol=1e-3)


def test_gain_outside_zero_one_is_refused():
    scene = _scene(tension_min=25000.0, accel_max=0.5)
    motions = vessel_motions(scene)
    for g in (-0.1, 1.5):
        with pytest.raises(CableOCPError, match="ahc_gain"):
            fastest_constant_speed(scene, motions, ahc_gain=g)
        with pytest.raises(CableOCPError, match="ahc_gain"):
            trapezoid_schedule(50.0, 80.0, 1.0, 0.5, ahc_gain=g)


def test_forward_check_bounds_the_payout_and_the_compensation_apart():
    g = 0.8
    stroke, rate = 0.3, 0.4
    scene = _scene(speed_max=1.0, accel_max=0.5, ahc_stroke=stroke, ahc_speed=rate)
    motion = vessel_motions(scene)[0]
    chk = resimulate(scene, trapezoid_schedule(50.0, 80.0, 1.0, 0.5, ahc_gain=g), motion)
    # the pay-out itself keeps speed_max and accel_max (as in the OCP, whose v and a they
    # bound), although the winch's table adds g dz/dt to it
    assert np.max(np.abs(chk.speed)) > 1.1
    assert chk.violations["speed_max"] == 0.0 and chk.violations["accel_max"] == 0.0
    # the compensation: |g z| and |g dz/dt| at the samples against ahc_stroke / ahc_speed
    zs = np.max(np.abs(g * motion.heave(chk.t)))
    zr = np.max(np.abs(g * motion.heave_rate(chk.t)))
    assert chk.violations["ahc_stroke"] == pytest.approx((zs - stroke) / stroke, rel=1e-12)
    assert chk.violations["ahc_speed"] == pytest.approx((zr - rate) / rate, rel=1e-12)
    # (the faded-in heave reaches g A = 0.4 m and g A omega = 0.504 m/s; 2 %: sampling)
    assert zs == pytest.approx(g * AMP, rel=0.02)
    assert not chk.keeps_limits()
    # no gain: no compensation limits measured
    plain = resimulate(scene, trapezoid_schedule(50.0, 80.0, 1.0, 0.5), motion)
    assert "ahc_stroke" not in plain.violations and "ahc_speed" not in plain.violations


@dataclasses.dataclass
class _Failed:
    success: bool = False
    solution: object = None


def test_comparison_gain_is_the_largest_the_compensator_allows():
    motions = vessel_motions(_scene())
    # a harmonic heave of amplitude A at omega, faded in: max |h| = A, max |dh/dt| = A omega
    scene = _scene(ahc_stroke=0.25, ahc_speed=10.0)
    g, _ = comparison_gain(scene, motions, _Failed(), 120.0)
    assert g == pytest.approx(0.25 / AMP, rel=1e-3)  # 1e-3: the 0.01 s sampling of the peak
    scene = _scene(ahc_stroke=10.0, ahc_speed=0.4 * AMP * FREQ)
    g, _ = comparison_gain(scene, motions, _Failed(), 120.0)
    assert g == pytest.approx(0.4, rel=1e-3)  # 1e-3: as above
    g, _ = comparison_gain(_scene(ahc_stroke=10.0), motions, _Failed(), 120.0)
    assert g == 1.0
    g, why = comparison_gain(_scene(), motions, _Failed(), 120.0)
    assert g == 0.0 and why == "no compensation"


def test_the_ocps_gain_is_put_back_into_its_bounds():
    """IPOPT's relaxed bounds may return g = 1 + 1e-8 (the 6.3.6 line: 1.0000000098, which
    the bisection then refused as a gain): the solution's gain is g clipped to [0, 1],
    any g inside unchanged."""
    from cable_ocp.schedule.ocp import ScheduleOCP, line_step

    scene = _scene(ahc_stroke=2.0, ahc_speed=1.5, segments=2)
    still = [ca.Function("still", [ca.SX.sym("t")], [ca.SX(0.0)])]
    ocp = ScheduleOCP(scene, line_step(scene), still, 10)
    w = np.zeros(ocp.variables)
    k = sum(ocp._sizes[:4])  # the gain's place: after T, the accelerations, v and L
    for g, want in ((1.0 + 1e-8, 1.0), (-1e-8, 0.0), (0.695, 0.695)):
        w[k] = g
        assert ocp._split(w)[4][0] == g
        assert ocp.gain_of(w) == want
