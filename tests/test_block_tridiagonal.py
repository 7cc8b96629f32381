"""The block-tridiagonal elimination (numerics/block_tridiagonal.py) against a dense solve.

Random diagonally dominant systems with 2 x 2 blocks (closed-form inverse) and 3 x 3 blocks
(CasADi's inv and solve), non-symmetric off-diagonal blocks: the SX elimination equals
numpy's dense LU solve to 1e-12 relative (both are backward stable on these well
conditioned matrices, condition number below 100; the bound leaves four digits to rounding).
"""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

from cable_ocp.numerics.block_tridiagonal import block_tridiagonal_solve, inverse_2x2


@pytest.mark.parametrize("b", [2, 3])
@pytest.mark.parametrize("n", [1, 2, 7])
def test_block_tridiagonal_solve_equals_dense_solve(b: int, n: int) -> None:
    rng = np.random.default_rng(10 * b + n)
    diag = [rng.standard_normal((b, b)) + 6.0 * np.eye(b) for _ in range(n)]
    lower = [rng.standard_normal((b, b)) for _ in range(n - 1)]
    upper = [rng.standard_normal((b, b)) for _ in range(n - 1)]
    rhs = rng.standard_normal(n * b)
    dense = np.zeros((n * b, n * b))
    for i in range(n):
        dense[b * i:b * i + b, b * i:b * i + b] = diag[i]
        if i:
            dense[b * i:b * i + b, b * (i - 1):b * i] = lower[i - 1]
            dense[b * (i - 1):b * i, b * i:b * i + b] = upper[i - 1]
    x = ca.SX.sym("x", n * b * b * 3)  # symbolic blocks: the elimination is written in SX
    syms = [ca.reshape(x[k * b * b:(k + 1) * b * b], b, b) for k in range(3 * n - 2)]
    r = ca.SX.sym("r", n * b)
    sol = ca.vertcat(*block_tridiagonal_solve(
        syms[:n], syms[n:2 * n - 1], syms[2 * n - 1:3 * n - 2],
        [r[b * i:b * i + b] for i in range(n)]))
    fn = ca.Function("solve", [x, r], [sol])
    vals = np.concatenate([m.T.ravel() for m in diag + lower + upper]
                          + [np.zeros(n * b * b * 3 - (3 * n - 2) * b * b)])
    got = np.asarray(fn(vals, rhs)).ravel()
    want = np.linalg.solve(dense, rhs)
    assert np.max(np.abs(got - want)) <= 1e-12 * np.max(np.abs(want))


def test_inverse_2x2_closed_form() -> None:
    """[[a, b], [c, d]]^-1 = [[d, -b], [-c, a]] / (a d - b c): exact for these integers."""
    m = ca.DM([[4.0, 1.0], [2.0, 3.0]])
    inv = np.asarray(ca.evalf(inverse_2x2(ca.SX(m))))
    assert np.array_equal(inv * 10.0, np.array([[3.0, -1.0], [-2.0, 4.0]]))
