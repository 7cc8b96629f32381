"""The piecewise-linear tables of time (cable_ocp/numerics/table.py): the values and
derivatives against numpy's own interpolation and the speed's exact integral, and a cost
that does not grow with the rows (the reason for the module: the forward simulator's heave
series and pay-out tables were chains of if_else over every row)."""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

from cable_ocp.numerics import table
from cable_ocp.numerics.table import CHAIN_ROWS, piecewise_linear, speed_table_length

T = ca.SX.sym("t")


def _eval(expr: ca.SX, times: np.ndarray) -> np.ndarray:
    f = ca.Function("f", [T], [expr]).map(times.size)
    return np.asarray(f(times[None, :])).ravel()


def _table(rows: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    ts = np.concatenate(([0.0], np.cumsum(rng.uniform(0.1, 2.0, rows - 1))))
    return ts, rng.normal(size=rows)


@pytest.fixture(params=["chain", "lookup"])
def form(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch) -> str:
    """Both writings of a table: the if_else chain (short tables) and the lookup (long
    ones), by moving the threshold between them."""
    if request.param == "lookup":
        monkeypatch.setattr(table, "CHAIN_ROWS", 0)
    return request.param


@pytest.mark.parametrize("rows", [2, 3, 17])
def test_piecewise_linear_is_numpys_interpolation_and_its_slope(rows: int, form: str) -> None:
    ts, vs = _table(rows, rows)
    grid = np.linspace(0.0, ts[-1] + 3.0, 801)
    # inside and after the table (held): np.interp holds the last value; round-off only
    assert np.allclose(_eval(piecewise_linear(ts, vs, T), grid), np.interp(grid, ts, vs),
                       rtol=0.0, atol=1e-12)
    # the slope: the segment's own, 0 after the last row
    mid = 0.5 * (ts[:-1] + ts[1:])
    slope = _eval(ca.jacobian(piecewise_linear(ts, vs, T), T), np.append(mid, ts[-1] + 1.0))
    assert np.allclose(slope, np.append(np.diff(vs) / np.diff(ts), 0.0), atol=1e-12)
    # before the first row: the first segment extended, or the first value held
    before = np.array([-1.5])
    ext = vs[0] - 1.5 * (vs[1] - vs[0]) / (ts[1] - ts[0])
    assert _eval(piecewise_linear(ts, vs, T), before)[0] == pytest.approx(ext, abs=1e-12)
    held = _eval(piecewise_linear(ts, vs, T, hold_before=True), before)[0]
    assert held == pytest.approx(vs[0], abs=1e-15)


def test_speed_table_length_is_the_exact_integral_of_the_speed_with_a_jump(form: str) -> None:
    # a speed linear between rows, a jump at t = 3 (a time given twice), held after 7 s
    ts = np.array([0.0, 1.0, 3.0, 3.0, 4.5, 7.0])
    vs = np.array([0.0, 2.0, 1.0, -0.5, 0.25, 0.75])
    grid = np.linspace(0.0, 9.0, 1801)
    # the reference: each side of the jump sampled finely (the rows among the samples)
    # and integrated by the trapezoidal rule, exact for a speed linear between samples
    left = np.linspace(0.0, 3.0, 30001)
    right = np.linspace(3.0, 9.0, 60001)
    l_left = 10.0 + np.concatenate(([0.0], np.cumsum(
        0.5 * np.diff(left) * (np.interp(left[1:], ts[:3], vs[:3])
                               + np.interp(left[:-1], ts[:3], vs[:3])))))
    v_right = np.interp(right, ts[3:], vs[3:])
    l_right = l_left[-1] + np.concatenate(([0.0], np.cumsum(
        0.5 * np.diff(right) * (v_right[1:] + v_right[:-1]))))
    fine = np.concatenate((left[:-1], right))
    ref = np.concatenate((l_left[:-1], l_right))
    got = _eval(speed_table_length(ts, vs, 10.0, T), fine)
    assert np.allclose(got, ref, rtol=0.0, atol=1e-9)  # round-off of 9e4 sums
    # closed forms: L(3) = 10 + 1 + 3 = 14 (the areas of 0->2 over 1 s and 2->1 over 2 s);
    # the speed (dL/dt) is the table's, the jump's right side at t = 3, held after 7 s
    rate = _eval(ca.jacobian(speed_table_length(ts, vs, 10.0, T), T), grid)
    assert _eval(speed_table_length(ts, vs, 10.0, T), np.array([3.0]))[0] == pytest.approx(
        14.0, abs=1e-12)
    expect = np.where(grid < 3.0, np.interp(grid, ts[:3], vs[:3]),
                      np.interp(grid, ts[3:], vs[3:]))
    assert np.allclose(rate, expect, atol=1e-12)
    acc = _eval(ca.jacobian(ca.jacobian(speed_table_length(ts, vs, 10.0, T), T), T),
                np.array([0.5, 2.0, 4.0, 6.0, 8.0]))
    assert np.allclose(acc, [2.0, -0.5, 0.5, 0.2, 0.0], atol=1e-12)


def test_the_cost_does_not_grow_with_the_rows() -> None:
    # the instructions of one evaluation: a binary search inside a call node, not a row
    # chain (a chain of 2000 rows is ~24 000 instructions)
    sizes = []
    for rows in (CHAIN_ROWS + 1, 2000):
        ts, vs = _table(rows, 1)
        f = ca.Function("f", [T], [piecewise_linear(ts, vs, T),
                                   speed_table_length(ts, vs, 0.0, T)])
        sizes.append(f.n_instructions())
    assert sizes[0] == sizes[1] < 100
