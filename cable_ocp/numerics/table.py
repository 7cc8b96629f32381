"""Tables of time as CasADi expressions whose cost does not grow with their rows: the one
home of the piecewise-linear lookups of the package (a ``[top_motion] series``, a pay-out
length or speed table, :mod:`cable_ocp.scene.motion`; a vessel motion's series,
:mod:`cable_ocp.schedule.sea`).

A chain of ``if_else`` over the rows (what a table of at most :data:`CHAIN_ROWS` rows
still is) costs every row at every evaluation: a simulation of
n steps on a table of m rows then costs n m (a 600 s schedule at 0.5 s and a heave sampled
at 0.25 s: m ~ 3600 operations per right-hand side). Here the segment is found by a
linear ``casadi.interpolant`` of the row index over the times (a binary search, a call
node in SX), j = floor(index), and the segment's data are read at the integer j from
interpolants on the index grid (exact there). The expressions are those of the chain:

* :func:`piecewise_linear`: v_j + (v_j+1 - v_j) (t - t_j) / (t_j+1 - t_j) on
  [t_j, t_j+1), v_last from the last row on, before the first row the first segment
  extended (or its first value held);
* :func:`speed_table_length`: the exact integral of a speed linear between rows (a time
  given twice is a jump in speed), L_j + v_j tau + (v'_j - v_j) tau^2 / (2 w_j), tau =
  t - t_j, w_j the segment's width, v'_j the speed at its end; held at the last row's
  speed after it.

Their derivatives in t (CasADi's AD: ``floor`` has derivative 0) are those of the
segment's own polynomial, so the rates and accelerations of a motion are those of the
chain too (the right-hand segment at a row).
"""

from __future__ import annotations

from collections.abc import Sequence

import casadi as ca
import numpy as np

__all__ = ["CHAIN_ROWS", "piecewise_linear", "speed_table_length"]

#: up to this many rows a table is the chain of ``if_else`` itself: inline SX is cheaper
#: than the interpolants' call nodes for short tables (the pay-out and forward-check tests'
#: 2-30-row tables ran 1.5x slower through call nodes, 2026-12-03); above it, the lookup
CHAIN_ROWS = 64


def _on_index(name: str, values: np.ndarray) -> ca.Function:
    """Linear interpolant of ``values`` over the index grid 0, 1, ..., read at integers."""
    if values.size == 1:  # one segment: j is 0
        j = ca.SX.sym("j")
        return ca.Function(name, [j], [ca.SX(float(values[0]))])
    grid = np.arange(values.size, dtype=float)
    return ca.interpolant(name, "linear", [grid], np.asarray(values, dtype=float))


def _segment(ts: np.ndarray, t: ca.SX) -> ca.SX:
    """j = the segment of t (0 .. len(ts) - 2) of strictly increasing times ``ts``, as an
    SX (piecewise constant in t): the first segment before ts[0], the last from ts[-1]."""
    n = ts.size
    if n == 2:
        return ca.SX(0.0)
    index = ca.interpolant("index", "linear", [ts], np.arange(n, dtype=float))
    s = index(ca.fmin(ca.fmax(t, float(ts[0])), float(ts[-1])))
    return ca.fmin(ca.floor(s), float(n - 2))


def piecewise_linear(times: Sequence[float] | np.ndarray, values: Sequence[float] | np.ndarray,
                     t: ca.SX, *, hold_before: bool = False) -> ca.SX:
    """The linear interpolation of ``values`` over ``times`` at t, held at the last value
    from the last time on (module docstring).

    Parameters
    ----------
    times : sequence of float
        s, strictly increasing, at least two.
    values : sequence of float
        The table's values (any unit), one per time.
    t : casadi.SX
        Scalar symbolic time, s.
    hold_before : bool
        Before the first time: the first value held (True) or the first segment extended
        (False).
    """
    ts = np.asarray(times, dtype=float)
    vs = np.asarray(values, dtype=float)
    if ts.size <= CHAIN_ROWS:
        expr = ca.SX(float(vs[-1]))
        for k in range(ts.size - 2, -1, -1):
            seg = vs[k] + (vs[k + 1] - vs[k]) * (t - ts[k]) / (ts[k + 1] - ts[k])
            expr = ca.if_else(t < float(ts[k + 1]), seg, expr)
        if hold_before:
            expr = ca.if_else(t < float(ts[0]), float(vs[0]), expr)
        return expr
    j = _segment(ts, t)
    at_t, at_v = _on_index("t", ts), _on_index("v", vs)
    t0, t1 = at_t(j), at_t(j + 1)
    v0, v1 = at_v(j), at_v(j + 1)
    seg = v0 + (v1 - v0) * (t - t0) / (t1 - t0)
    expr = ca.if_else(t < float(ts[-1]), seg, float(vs[-1]))
    if hold_before:
        expr = ca.if_else(t < float(ts[0]), float(vs[0]), expr)
    return expr


def speed_table_length(times: Sequence[float] | np.ndarray,
                       speeds: Sequence[float] | np.ndarray, length0: float,
                       t: ca.SX) -> ca.SX:
    """L(t), m: ``length0`` plus the integral from times[0] of a speed linear between
    rows, held at the last speed after the last row (module docstring).

    Parameters
    ----------
    times : sequence of float
        s, non-decreasing (a time given twice: a jump in speed), at least two.
    speeds : sequence of float
        m/s, one per time.
    length0 : float
        L at times[0], m.
    t : casadi.SX
        Scalar symbolic time, s.
    """
    ts = np.asarray(times, dtype=float)
    vs = np.asarray(speeds, dtype=float)
    width = np.diff(ts)
    # L at every row: trapezoidal sums of the linear speed (zero over a jump)
    ls = np.concatenate(([float(length0)], float(length0) + np.cumsum(
        0.5 * (vs[:-1] + vs[1:]) * width)))
    keep = np.flatnonzero(width > 0.0)  # the segments with time in them
    after = float(ls[-1]) + float(vs[-1]) * (t - float(ts[-1]))
    if ts.size <= CHAIN_ROWS:
        expr = after
        for k in keep[::-1]:
            tau = t - float(ts[k])
            seg = float(ls[k]) + float(vs[k]) * tau + float(vs[k + 1] - vs[k]) * tau * tau / (
                2.0 * float(width[k]))
            expr = ca.if_else(t < float(ts[k + 1]), seg, expr)
        return expr
    starts = np.append(ts[keep], ts[-1])
    j = _segment(starts, t)
    t0, w = _on_index("t", ts[keep])(j), _on_index("w", width[keep])(j)
    l0 = _on_index("L", ls[keep])(j)
    v0, v1 = _on_index("v", vs[keep])(j), _on_index("v1", vs[keep + 1])(j)
    tau = t - t0
    seg = l0 + v0 * tau + (v1 - v0) * tau * tau / (2.0 * w)
    return ca.if_else(t < float(ts[-1]), seg, after)
