"""The passive heave compensator (issue 24 item 7; Huang (1992), 004_7da4a1ee8042db40.txt,
6.1.4 and 7.3 (4)): the gas spring's law, the isolation it gives against closed forms, its end
stops, its scene table and its rows in the comparison."""

from __future__ import annotations

import dataclasses
import tomllib
from pathlib import Path

import control as ct
import numpy as np
import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.heave import design_loop as sm
from cable_ocp.heave import plant as pl
from cable_ocp.heave.closed_loop import run_loop
from cable_ocp.heave.controllers import Passive
from cable_ocp.heave.loop_plants import UnitWinchPlant
from cable_ocp.physics.gas_spring import gas_force, gas_pressure, gas_stiffness
from cable_ocp.scene.heave import load_scene, scene_from_dict

ROOT = Path(__file__).resolve().parents[2]
PHC = ROOT / "problems" / "heave" / "ex_6_3_6_phc.toml"


def test_small_stroke_stiffness_is_n_p0_a2_over_v0() -> None:
    p0, v0, area, n = 1.0e6, 0.5, 0.05, 1.4
    closed = n * p0 * area**2 / v0  # 7000 N/m
    assert gas_stiffness(0.0, p0, v0, area, n) == pytest.approx(closed, rel=1e-14)
    # central difference of the force: O(ds^2) truncation (~1e-12) and ~1e-16 F / ds rounding
    ds = 1e-4
    fd = (gas_force(ds, p0, v0, area, n) - gas_force(-ds, p0, v0, area, n)) / (2 * ds)
    assert fd == pytest.approx(closed, rel=1e-7)
    # the polytropic law itself: p V^n is constant along the stroke (to rounding)
    for s in (-1.0, 0.5, 2.0):
        assert gas_pressure(s, p0, v0, area, n) * (v0 - area * s) ** n == pytest.approx(
            p0 * v0**n, rel=1e-13)
    # isothermal (n = 1): F s-curve is p0 V0 A / (V0 - A s), stiffening as the gas shrinks
    assert gas_force(2.0, p0, v0, area, 1.0) == pytest.approx(p0 * v0 * area / (v0 - 0.1))


def _closed_form(w: float, a: float, b: float, kp: float, c: float, kc: float) -> float:
    """|x / x0| of the unit under the compensator in series with the line (docs/heave.md):
    Z_p / ((a s^2 + b s)(Z_p + k_c) + Z_p), Z_p = k_p + c s, s = i w."""
    s = 1j * w
    zp = kp + c * s
    return abs(zp / ((a * s * s + b * s) * (zp + kc) + zp))


def _scene() -> object:
    return load_scene(PHC, {"winch.delay": 0.0, "controller.controllers": ["passive", "phc"]})


def _sine_run(sc: object, w: float, amp: float, duration: float
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The nonlinear plant with the compensator, the winch still, under x0 = amp sin(w t)."""
    models = sm.build_models(sc)
    p = models.plant_phc
    h, m = sc.controller.sample_time, sc.simulation.substeps
    n_ctrl = int(round(duration / h))
    t = np.arange(n_ctrl * m + 2) * (h / m)
    x0 = amp * np.sin(w * t)
    sea = np.zeros((t.size, p.n - p.blocks["vessel"].start))
    plant = UnitWinchPlant(sc, p, t, x0, sea, np.zeros(n_ctrl + 1), n_ctrl, phc=True)
    run = run_loop(plant, Passive(), n_ctrl, bound=1e3)
    return run.trace.t, run.trace.x, run.trace.stroke_phc


def _amplitude(t: np.ndarray, y: np.ndarray, w: float, t_from: float) -> float:
    """The amplitude at w of y over t >= t_from (least squares on sin, cos and a constant)."""
    k = t >= t_from
    M = np.column_stack([np.sin(w * t[k]), np.cos(w * t[k]), np.ones(k.sum())])
    coef = np.linalg.lstsq(M, y[k], rcond=None)[0]
    return float(np.hypot(coef[0], coef[1]))


@pytest.mark.parametrize("w", [0.3, 0.785, 1.5])
def test_simulated_isolation_matches_the_closed_form(w: float) -> None:
    sc = _scene()
    pc, un = sc.passive_compensator, sc.unit
    kp = gas_stiffness(0.0, un.static_tension / pc.area, pc.gas_volume, pc.area,
                       pc.polytropic_exponent)
    amp = 0.01  # 1 cm: A delta / V0 ~ 1e-3, the gas is linear to ~0.1 % in its stiffness
    t, x, _ = _sine_run(sc, w, amp, 200.0)
    # the slowest mode decays in 1 / (zeta w_n) ~ 12 s: after 130 s its trace is ~3e-5 of it
    ratio = _amplitude(t, x, w, 130.0) / amp
    expect = _closed_form(w, un.a, un.b, kp, pc.damping, un.mass / un.a)
    # RK4 at 0.01 s and the gas' nonlinearity at 1 cm both give < 1e-4; 1e-3 covers them
    assert ratio == pytest.approx(expect, rel=1e-3)
    assert expect < 1.0 or w < 0.35  # it isolates above its natural frequency (0.24 rad/s)


def test_linear_block_is_second_order_isolation_on_a_stiff_line() -> None:
    # a line much stiffer than the gas spring: the unit of mass m hangs on k_p and c from the
    # boom tip, with its own damping m b / a: the textbook base isolation
    m, kp, c = 125000.0, 7000.0, 2.0e4
    a = 1e-5
    b = a * 0.1658 / 0.8959  # the 6.3.6 unit's damping rate b / a, 1/s
    kc = m / a
    plant = pl.assemble_plant(a, b, pl.winch_first(1.0),
                              compensator=pl.compensator_block(kp, c, kc))
    sys = ct.ss(plant.A, plant.B2, plant.e("x"), 0)
    for w in (0.1, 0.237, 0.785, 2.0):
        iso = abs(kp + 1j * c * w) / abs(kp - m * w**2 + 1j * (c + m * b / a) * w)
        # the exact series system (rounding with k_c = 1.25e10 N/m: ~1e-12), and the
        # isolation to O(|Z_p| / k_c) times the resonance's amplification, ~3e-7 here
        assert abs(complex(ct.evalfr(sys, 1j * w))) == pytest.approx(
            _closed_form(w, a, b, kp, c, kc), rel=1e-8)
        assert abs(complex(ct.evalfr(sys, 1j * w))) == pytest.approx(iso, rel=1e-5)


def test_end_stops_hold_the_stroke() -> None:
    sc = _scene()
    pc = dataclasses.replace(sc.passive_compensator, stroke_max=0.3)
    sc = dataclasses.replace(sc, passive_compensator=pc)
    # 1 m at the compensator's natural frequency: the free stroke would be ~1.6 m
    t, x, delta = _sine_run(sc, 0.237, 1.0, 120.0)
    assert np.all(np.isfinite(x))
    assert np.max(np.abs(delta)) <= 0.3 + 1e-12  # clipped exactly at the stops
    assert np.max(delta) == pytest.approx(0.3) and np.min(delta) == pytest.approx(-0.3)
    assert np.count_nonzero(np.abs(delta) >= 0.3 - 1e-12) > 100  # it rests on them a while


def test_comparison_rows_and_reductions() -> None:
    sc = load_scene(PHC, {"simulation.duration": 60.0,
                          "controller.controllers": ["passive", "lqr", "phc", "phc+lqr"]})
    res = sm.compare(sc)
    assert all(res.statuses[k] == "solved" for k in res.metrics)
    m = res.metrics
    # the soft spring isolates the wave band: a large part of the heave, not all of it
    assert 30.0 < m["phc"].reduction_pct < 95.0
    assert m["phc+lqr"].reduction_pct > 99.0  # the winch removes the residual (6.1.4)
    assert m["phc"].max_stroke == 0.0 and m["phc"].max_stroke_phc > 0.05
    assert m["lqr"].max_stroke_phc is None
    # the LQR on the plant with the compensator is its own design (more states, other gain)
    assert m["phc+lqr"].energy_index != pytest.approx(m["lqr"].energy_index, rel=1e-3)


def test_scene_errors_name_the_keys() -> None:
    with pytest.raises(CableOCPError, match="passive_compensator.pressure"):
        load_scene(PHC, {"passive_compensator.pressure": 2.0e6})
    with pytest.raises(CableOCPError, match=r"need a \[passive_compensator\]"):
        load_scene(ROOT / "problems" / "heave" / "ex_6_3_6.toml",
                   {"controller.controllers": ["passive", "phc"]})
    with pytest.raises(CableOCPError, match="passive_compensator.stroke_max"):
        load_scene(PHC, {"passive_compensator.stroke_max": 9.5})
    with pytest.raises(CableOCPError, match="unknown|valid"):
        load_scene(PHC, {"passive_compensator.volume": 1.0})
    data = tomllib.loads(PHC.read_text())
    for key in ("tension_min", "drum_radius", "drum_inertia"):
        del data["winch"][key]
    data["unit"]["mass"] = 0.0
    with pytest.raises(CableOCPError, match=r"\[passive_compensator\]: needs unit.mass"):
        scene_from_dict(data)
