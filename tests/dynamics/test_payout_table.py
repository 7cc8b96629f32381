"""``payout_law = "table"``: a pay-out given as a table of times and speeds (or lengths),
including a sudden stop (Huang (1992) Fig. 3.24, 004_7da4a1ee8042db40.txt line ~1041).

The speed table is linear in speed between rows, so the length is its exact integral
(:func:`cable_ocp.scene.motion.table_length_expr`); the sudden stop of a unit on a light
elastic line is checked against the massless-spring closed form in every model that varies
the length (axial, planar, lumped3d)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from cable_ocp.dynamics import dynamic_scene_from_dict, load_dynamic_scene, simulate
from cable_ocp.errors import CableOCPError
from cable_ocp.scene.motion import length_numeric

G = 9.80665
#: the speed ramp lasts two periods 2 pi sqrt(M / k) of the unit on the line (k = EA / L
#: at 100 m), so that it leaves the unit (nearly) without swing; then the sudden stop
RAMP = 4.0 * math.pi * math.sqrt(1000.0 * 100.0 / 1.0e7)
ROWS = [[0.0, 0.0], [RAMP, 0.5], [3.0, 0.5], [3.0, 0.0]]  # ramp, run, sudden stop


def _scene(model: str = "axial", top: dict | None = None, mu: float = 1e-2,
           duration: float = 3.8) -> dict:
    """A 100 m line (EA = 1e7 N) with a 1000 kg unit in air; mu kg/m."""
    return {"environment": {"water_depth": 5000.0, "water_density": 1.225},
            "cable": {"length": 100.0, "diameter": 0.02, "weight_in_water": mu * G,
                      "axial_stiffness": 1.0e7, "mass_per_length": mu,
                      "added_mass_coefficient": 0.0},
            "unit": {"mass": 1000.0, "weight_in_water": 1000.0 * G},
            "end_b": {"position": [0.0, 0.0, 4000.0]},
            "top_motion": top or {"payout_law": "table", "payout_speed_table": ROWS},
            "simulation": {"model": model, "duration": duration, "time_step": 1e-3,
                           "output_step": 1e-3, "segments": 10}}


def test_the_length_is_the_exact_integral_of_the_speed_table() -> None:
    """L(t) - L0 against an independent quadrature of the piecewise linear speed
    (np.interp, with the jump as two rows): to 1e-9 m (the quadrature's tolerance; the
    table integral is exact), and the speed L_t is the table's speed."""
    rows = [[0.0, 0.0], [2.0, 1.5], [5.0, -0.5], [5.0, 1.0], [7.0, 1.0]]
    sc = dynamic_scene_from_dict(_scene(top={"payout_law": "table",
                                             "payout_speed_table": rows}))
    ts = np.linspace(0.0, 9.0, 181)
    length, speed = length_numeric(sc.top_motion, 100.0, ts)
    tt, vv = np.array(rows).T

    def v(t: float) -> float:  # the jump at 5 s: the left rows before it, the right after
        return float(np.interp(t, tt[:3], vv[:3])) if t < 5.0 else (
            float(np.interp(t, tt[3:], vv[3:])))

    ref = [quad(v, 0.0, t, points=[2.0, 5.0], limit=200, epsabs=1e-12)[0] for t in ts]
    assert np.abs(length - 100.0 - np.array(ref)).max() < 1e-9
    assert np.abs(speed - np.array([v(t) for t in ts])).max() < 1e-12  # round-off only
    # held after the last row: 1 m/s
    assert speed[-1] == pytest.approx(1.0, abs=1e-15)


def test_a_length_table_is_linear_between_rows_and_held_after() -> None:
    sc = dynamic_scene_from_dict(_scene(top={
        "payout_law": "table", "payout_length_table": [[0.0, 100.0], [2.0, 104.0],
                                                       [4.0, 103.0]]}))
    length, speed = length_numeric(sc.top_motion, 100.0, [1.0, 3.0, 5.0])
    assert length.tolist() == pytest.approx([102.0, 103.5, 103.0], abs=1e-12)
    assert speed.tolist() == pytest.approx([2.0, -0.5, 0.0], abs=1e-12)


@pytest.mark.parametrize("model", ["axial", "planar", "lumped3d"])
def test_sudden_stop_peak_tension(model: str) -> None:
    """A unit lowered at v = 0.5 m/s is stopped at once at L = 101.19 m: on a massless
    line it swings on the spring k = EA / L with the peak tension W + v sqrt(k M) a
    quarter period pi/2 sqrt(M/k) after the stop. The line's mass (1 kg here against
    1000 kg) adds the stop's wave front v sqrt(EA mu) = 158 N and its reflection: the peak
    lies within 2 v sqrt(EA mu) of the closed form; its time within 10 % of the quarter
    period (the wave arrivals shift it). The length follows the table's integral exactly
    in the run too."""
    mu, v, ea, m = 1e-2, 0.5, 1.0e7, 1000.0
    res = simulate(dynamic_scene_from_dict(_scene(model)))
    assert res.status == "solved", res.message
    l_stop = 100.0 + 0.5 * v * RAMP + v * (3.0 - RAMP)
    assert res.length[-1] == pytest.approx(l_stop, abs=1e-9)  # round-off of the sums
    k = ea / l_stop
    w = m * G + mu * G * l_stop
    after = res.t > 3.0
    peak = float(res.top_tension[after].max())
    closed = w + v * math.sqrt(k * m)
    assert abs(peak - closed) <= 2.0 * v * math.sqrt(ea * mu), (peak, closed)
    # the first swing's peak (the later ones repeat it: no damping)
    quarter = 0.5 * math.pi * math.sqrt(m / k)
    first = after & (res.t < 3.0 + 2.0 * quarter)
    t_peak = float(res.t[first][np.argmax(res.top_tension[first])])
    assert abs(t_peak - 3.0 - quarter) <= 0.1 * quarter, (t_peak, quarter)
    assert res.top_tension[first].max() == pytest.approx(peak, rel=0.02)  # wave ripple
    # before the stop the line is quasi-static: W within the same wave bound
    before = (res.t > 2.5) & (res.t < 3.0)
    assert np.abs(res.top_tension[before] - w).max() <= 2.0 * v * math.sqrt(ea * mu)


def test_the_shipped_sudden_stop_runs_and_peaks_after_the_stop() -> None:
    """problems/dynamics/payout_sudden_stop.toml (3.3.5 system): the length ends at
    50 + 2.5 + 45 = 97.5 m, the top tension after the stop exceeds its range while
    lowering (the unit is caught), and the line stays taut."""
    res = simulate(load_dynamic_scene("problems/dynamics/payout_sudden_stop.toml"))
    assert res.status == "solved", res.message
    assert res.length[-1] == pytest.approx(97.5, abs=1e-9)
    lowering = (res.t > 80.0) & (res.t < 100.0)
    after = (res.t > 100.0) & (res.t < 110.0)
    assert res.top_tension[after].max() > 1.2 * res.top_tension[lowering].max()


@pytest.mark.parametrize("top, words", [
    ({"payout_law": "table"}, "exactly one of"),
    ({"payout_law": "table", "payout_speed_table": ROWS,
      "payout_length_table": [[0.0, 100.0], [1.0, 101.0]]}, "exactly one of"),
    ({"payout_law": "table", "payout_speed_table": [[0.0, 1.0]]}, "at least two rows"),
    ({"payout_law": "table", "payout_speed_table": [[0.5, 1.0], [1.0, 1.0]]},
     "starts at t = 0"),
    ({"payout_law": "table", "payout_speed_table": [[0.0, 1.0], [2.0, 1.0], [1.0, 0.0]]},
     "must not decrease"),
    ({"payout_law": "table", "payout_speed_table": [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0],
                                                    [1.0, 2.0]]}, "at most twice"),
    ({"payout_law": "table", "payout_speed_table": [[0.0, 1.0, 2.0], [1.0, 1.0]]},
     "expected [t, v]"),
    ({"payout_law": "table", "payout_length_table": [[0.0, 100.0], [1.0, 101.0],
                                                     [1.0, 102.0]]}, "increase strictly"),
    ({"payout_law": "table", "payout_length_table": [[0.0, 90.0], [1.0, 101.0]]},
     "cable.length = 100.0"),
    ({"payout_law": "linear", "payout_speed_table": ROWS}, "does not belong"),
    ({"payout_law": "tabel"}, "table"),
])
def test_bad_tables_raise_named_errors(top: dict, words: str) -> None:
    with pytest.raises(CableOCPError, match="top_motion") as err:
        dynamic_scene_from_dict(_scene(top=top))
    assert words in str(err.value)


def test_hauling_in_past_the_line_names_the_table_key() -> None:
    """Hauling in past the whole line is refused with the table's key."""
    with pytest.raises(CableOCPError, match="payout_speed_table"):
        dynamic_scene_from_dict(_scene(top={"payout_law": "table", "payout_speed_table":
                                            [[0.0, -10.0], [20.0, -10.0]]}, duration=20.0))
