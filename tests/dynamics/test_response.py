"""Frequency-response curves (``cable-ocp response``, :mod:`cable_ocp.dynamics.response`,
:mod:`cable_ocp.batch.response`): the thesis' Figs 3.3-3.7 and 4.2-4.6 plot steady-state
amplitudes against the excitation frequency (Huang (1992), 004 sections 3.3, 4.5).

The closed-form case: a 100 kg mass on a 100 m steel wire in air (vertical_in_air.toml)
with the wire's mass made negligible (1e-4 kg/m: 0.01 kg against 100 kg) and internal
damping c = 20000 N s: a spring k = EA / L = 7e4 N/m with a dashpot c / L = 200 N s/m and
a mass M = 100 kg, whose top moves as A sin(w t). Then

    X / A = (k + i w c/L) / (k + i w c/L - M w^2),   T_unit / A = M w^2 X / A,

the natural frequency is sqrt(k / M) = 26.458 rad/s, and the free vibration decays as
exp(-c/(2 L M) t) = exp(-t / 1 s), so the time runs reach their steady state.
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest

from cable_ocp.batch.response import (
    ResponseSettings,
    frequency_response,
    parse_amplitudes,
    parse_frequencies,
    steady_run,
)
from cable_ocp.cli import main
from cable_ocp.dynamics.response import linear_response, parse_outputs, period_change
from cable_ocp.errors import CableOCPError
from cable_ocp.scene.dynamics import dynamic_scene_from_dict, load_dynamic_scene
from cable_ocp.scene.files import apply_overrides, read_problem

ROOT = Path(__file__).resolve().parents[2]
AIR = ROOT / "problems" / "dynamics" / "vertical_in_air.toml"
SPRING = {"simulation.segments": 4, "cable.axial_damping": 20000.0,
          "cable.mass_per_length": 1e-4, "cable.weight_in_water": 9.81e-4}
K, C, M = 7.0e6 / 100.0, 20000.0 / 100.0, 100.0  # N/m, N s/m, kg
OUTS = ["top_tension", "unit_tension", "unit_z"]


def closed_form(w: np.ndarray, c: float = C) -> np.ndarray:
    """X / A of the damped spring-mass (module docstring)."""
    return (K + 1j * w * c) / (K + 1j * w * c - M * w**2)


def spring_data(**extra: float) -> dict:
    return apply_overrides(read_problem(AIR), {**SPRING, **extra})


def test_linear_transfer_function_is_the_spring_mass_closed_form() -> None:
    """The modal transfer function of the axial model equals the closed form: the unit's
    motion and the unit's tension M w^2 X; the top element carries the same tension."""
    scene = dynamic_scene_from_dict(spring_data())
    w = np.array([5.0, 15.0, 26.0, 40.0, 80.0])
    lin = linear_response(scene, w, OUTS)
    assert lin.status == "solved"
    h = closed_form(w)
    # 1e-3: the wire's 0.01 kg against the 100 kg unit (1e-4), spread over 4 elements
    assert np.abs(lin.transfer[:, 2]) == pytest.approx(np.abs(h), rel=1e-3)
    assert np.abs(lin.transfer[:, 1]) == pytest.approx(M * w**2 * np.abs(h), rel=1e-3)
    assert np.abs(lin.transfer[:, 0]) == pytest.approx(np.abs(lin.transfer[:, 1]), rel=1e-3)
    # the phase of the motion too (same 1e-3 reason, absolute in rad)
    assert np.angle(lin.transfer[:, 2] / (-1j)) == pytest.approx(np.angle(h), abs=1e-3)


def test_linear_curve_peaks_at_the_first_natural_frequency() -> None:
    """Undamped, on a dense grid: the unit's ratio peaks within one grid step of omega_1,
    and omega_1 is the closed form beta L tan(beta L) = m L / M of vertical_in_air.toml
    (the wire's own mass, 7.85 kg, kept: 26.106 rad/s on 20 elements)."""
    scene = load_dynamic_scene(AIR)
    grid = np.linspace(10.0, 40.0, 601)
    lin = linear_response(scene, grid, ["unit_z", "top_tension"])
    w1 = lin.natural_frequencies[0]
    # closed form of the continuous rod with a tip mass: 0.0785 * 100 / 100 = 0.0785
    from scipy.optimize import brentq

    bl = brentq(lambda x: x * math.tan(x) - 0.0785, 1e-6, 1.0)
    w_rod = bl / 100.0 * math.sqrt(7.0e6 / 0.0785)
    assert w1 == pytest.approx(w_rod, rel=2e-3)  # 20 lumped elements: O(1/N^2) ~ 1e-3
    step = grid[1] - grid[0]
    for k in range(2):
        assert abs(grid[int(np.argmax(lin.rao[:, k]))] - w1) <= step
    # a modal damping ratio bounds the peak: 1 / (2 zeta) for a base-excited spring-mass
    damped = linear_response(scene, [w1], ["unit_z"], damping_ratio=0.05)
    # 2 %: the wire's mass (8 % of the unit's) and the base-excitation numerator
    # sqrt(1 + (2 zeta)^2) = 1.005
    assert damped.rao[0, 0] == pytest.approx(1.0 / 0.1, rel=0.02)


def test_tensions_carry_the_wire_inertia() -> None:
    """With the wire's own mass (vertical_in_air.toml: 7.85 kg on the 100 kg unit), the top
    element's tension exceeds the unit's by the wire's inertia: the continuous rod with a
    tip mass under base motion, u = a cos(b y) + c sin(b y) (y up from the unit,
    b = w sqrt(mu / EA)), EA u'(0) = -M w^2 u(0) at the unit, u(L) = 1 at the top,
    T(y) = EA u'(y), at the elements' middles (y = h / 2 and L - h / 2)."""
    scene = load_dynamic_scene(AIR)
    ea, mu, length, n = 7.0e6, 0.0785, 100.0, 20
    h = length / n
    w = np.array([10.0, 20.0, 40.0])
    lin = linear_response(scene, w, ["top_tension", "unit_tension", "unit_z"])
    b = w * math.sqrt(mu / ea)
    # a (1) + c (0) with EA b c = -M w^2 a and a cos(b L) + c sin(b L) = 1
    ratio = -M * w**2 / (ea * b)
    a = 1.0 / (np.cos(b * length) + ratio * np.sin(b * length))
    c = ratio * a

    def tension(y: float) -> np.ndarray:
        return ea * b * (-a * np.sin(b * y) + c * np.cos(b * y))

    # 1e-3: 20 lumped masses against the continuous rod, (b h)^2 / 12 < 1e-5, and the
    # rod's own mass split half and half at the unit's node
    assert np.abs(lin.transfer[:, 0]) == pytest.approx(np.abs(tension(length - h / 2)),
                                                       rel=1e-3)
    assert np.abs(lin.transfer[:, 1]) == pytest.approx(np.abs(tension(h / 2)), rel=1e-3)
    assert np.abs(lin.transfer[:, 2]) == pytest.approx(np.abs(a), rel=1e-3)
    # the wire's inertia is visible: the two tensions differ by more than 1 %
    assert np.all(np.abs(np.abs(lin.transfer[:, 0] / lin.transfer[:, 1]) - 1.0) > 0.01)


def test_time_runs_equal_the_linear_curve_off_resonance() -> None:
    """Fourier amplitude, half range and the linear transfer function agree off
    resonance; every run is periodic."""
    w = [5.0, 15.0, 40.0]
    res = frequency_response(spring_data(), w, [0.002], OUTS, workers=0)
    assert res.status == "solved", res.message
    assert res.linear.status == "solved"
    # 1 %: the midpoint rule's dispersion at 64 samples per period ((w dt)^2 / 12 ~ 1e-3
    # at the natural frequency) and the transient left below the 1 % periodicity test
    assert res.rao[0, :, 2] == pytest.approx(np.abs(closed_form(np.array(w))), rel=0.01)
    assert res.rao[0] == pytest.approx(res.linear.rao, rel=0.01)
    # a linear response is a sine: (max - min) / 2 is the Fourier amplitude (1 %, as above)
    assert res.half_range[0] == pytest.approx(res.amplitude[0], rel=0.01)
    # the static tension is the unit's weight, 981 N (0.1 %: the wire's 1e-3 N/m)
    assert res.mean[0, :, 1] == pytest.approx(981.0, rel=1e-3)
    head, rows = res.table()
    assert len(rows) == 3 and head[:3] == ["amplitude [m]", "frequency [rad/s]", "status"]


def test_worker_processes_give_the_serial_numbers() -> None:
    """The sweep on two local worker processes (the batch executor) gives the numbers of
    the run in this process, case by case."""
    w = [5.0, 40.0]
    serial = frequency_response(spring_data(), w, [0.002], ["unit_z"], workers=0)
    pool = frequency_response(spring_data(), w, [0.002], ["unit_z"], workers=2)
    assert pool.diagnostics["workers"] == 2
    # the same computation on another process: identical to rounding
    assert pool.amplitude == pytest.approx(serial.amplitude, rel=1e-12)
    assert list(pool.run_status.ravel()) == ["solved", "solved"]


def test_periodicity_detection_on_signals() -> None:
    """period_change: zero for a sine, the decay of a transient over one period."""
    w = 2.0
    t = np.arange(0, 20 * 64) * (2 * math.pi / w / 64)
    assert period_change(t, 3.0 + 0.5 * np.sin(w * t + 0.3), w)[2] < 1e-12
    # a steady sine plus a decaying one at another frequency: the change shrinks with time
    y = np.sin(w * t) + np.exp(-t / 5.0) * np.sin(3.3 * w * t)
    early = period_change(t[t < 8.0], y[t < 8.0], w)[2]
    late = period_change(t, y, w)[2]
    assert late < early
    # an output that does not move at all is periodic
    assert period_change(t, np.full(t.size, 7.0), w)[2] < 1e-12
    # fewer than two periods: no verdict
    assert math.isnan(period_change(t[:100], y[:100], w)[2])


def test_a_run_extends_until_periodic_and_reports_the_cap() -> None:
    """Started without a ramp, a damped run doubles its periods until periodic; an
    undamped line beats for ever and ends "not_converged" at the cap, amplitudes kept."""
    # no ramp: the impulsive start's free vibration decays as exp(-t / 1 s)
    st = ResponseSettings(min_periods=6, max_periods=96, ramp_periods=0.0)
    status, msg, vals = steady_run(spring_data(), "heave", ["unit_z"], 40.0, 0.002, st)
    assert status == "solved" and vals["periods"] > st.min_periods, msg
    assert vals["change"] <= st.tolerance
    undamped = spring_data(**{"cable.axial_damping": 0.0})
    st = ResponseSettings(min_periods=6, max_periods=24, ramp_periods=0.0)
    status, msg, vals = steady_run(undamped, "heave", ["unit_z"], 22.0, 0.002, st)
    assert status == "not_converged" and vals["periods"] == 24
    assert "cap" in msg and vals["change"] > st.tolerance
    assert math.isfinite(vals["unit_z_amplitude"])


def test_parsers_name_the_bad_value() -> None:
    """--frequencies, --amplitudes and --outputs: errors that name option and value."""
    assert parse_frequencies("1:3:3").tolist() == [1.0, 2.0, 3.0]
    for bad in ("5:40", "a:b:3", "0:4:3", "1:4:0", "1:4:2.5"):
        with pytest.raises(CableOCPError, match="--frequencies"):
            parse_frequencies(bad)
    assert parse_amplitudes("0.1,0.2").tolist() == [0.1, 0.2]
    for bad in ("0.1,x", "-1", "0"):
        with pytest.raises(CableOCPError, match="--amplitudes"):
            parse_amplitudes(bad)
    assert parse_outputs("unit_z,node_x:3", 5) == ["unit_z", "node_x:3"]
    for bad in ("unit_w", "node_z:5", "tension"):
        with pytest.raises(CableOCPError, match="--outputs"):
            parse_outputs(bad, 5)


def _spring_args() -> list[str]:
    return [a for k, v in SPRING.items() for a in ("--set", f"{k}={v}")]


def test_cli_outputs_and_exit_codes(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    """Exit 0 when every run is periodic (JSON envelope, CSV rows), 1 when a run goes
    slack, 2 for a bad --frequencies (named) or a scene with a pay-out."""
    js, cs = tmp_path / "r.json", tmp_path / "r.csv"
    rc = main(["response", str(AIR), "--frequencies", "5:15:2", "--amplitudes", "0.002",
               "--outputs", "unit_z", "--workers", "0", "--json", str(js), "--csv", str(cs),
               "--plot", str(tmp_path / "r.png"), "--quiet", *_spring_args()])
    assert rc == 0 and (tmp_path / "r.png").stat().st_size > 0
    d = json.loads(js.read_text())
    assert d["status"] == "solved" and d["excitation"] == "heave"
    assert d["linear"]["natural_frequencies_rad_s"][0] == pytest.approx(math.sqrt(K / M),
                                                                       rel=1e-3)
    assert len(d["time_runs"]["rao"][0]) == 2
    rows = list(csv.reader(cs.open()))
    assert len(rows) == 3 and "unit_z_rao [m/m]" in rows[0]
    # 0.1 m at 15 rad/s: a tension swing M w^2 |X| = 100 * 225 * 1.47 * 0.1 = 3300 N, more
    # than the 981 N static tension: slack
    rc = main(["response", str(AIR), "--frequencies", "15:15:1", "--amplitudes", "0.1",
               "--workers", "0", "--json", str(js), "--quiet", *_spring_args()])
    assert rc == 1 and json.loads(js.read_text())["time_runs"]["status"] == [["slack"]]
    capsys.readouterr()
    assert main(["response", str(AIR), "--frequencies", "5:40", "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "--frequencies '5:40'" in err and "START:STOP:N" in err
    assert main(["response", str(AIR), "--frequencies", "5:40:3", "--quiet",
                 "--set", "top_motion.payout_speed=0.1"]) == 2
    assert "pay-out" in capsys.readouterr().err


def test_response_table_in_the_scene() -> None:
    """[response] is validated (unknown keys name the valid ones) and gives the defaults."""
    data = spring_data()
    data["response"] = {"frequencies": [5.0, 15.0, 2], "amplitudes": [0.002],
                        "outputs": ["unit_z"]}
    scene = dynamic_scene_from_dict(data)
    assert scene.response.frequencies == (5.0, 15.0, 2)
    assert scene.response.amplitudes == (0.002,)
    data["response"] = {"frequency": [1, 2, 3]}
    with pytest.raises(CableOCPError, match="amplitudes"):
        dynamic_scene_from_dict(data)
    data["response"] = {"frequencies": [1, 2]}
    with pytest.raises(CableOCPError, match=r"response\.frequencies"):
        dynamic_scene_from_dict(data)
