"""Block-tridiagonal linear systems, solved symbolically (CasADi SX) by block elimination.

The Newton matrices of the lumped-mass time step (3 x 3 blocks, one per free node) and of
the heave plant's axial step (2 x 2 blocks, one per node: the height and the velocity)
couple each node to its neighbours only. :func:`block_tridiagonal_solve` writes the block
Thomas elimination into the expression graph: no sparse factorisation at run time, no
Python per solve, about ``2 b^3`` operations per block row. There is no pivoting between
block rows: the callers' matrices are close to symmetric positive definite (a mass over
dt^2 plus a stiffness, or the identity minus dt/2 times a Jacobian), whose Schur
complements stay well conditioned. A 2 x 2 block is inverted in closed form; a larger one
by CasADi's ``inv`` and ``solve``.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import casadi as ca

__all__ = ["block_tridiagonal_solve", "inverse_2x2"]


def inverse_2x2(m: Any) -> Any:
    """The inverse of a 2 x 2 matrix in closed form, ``[[d, -b], [-c, a]] / (a d - b c)``.

    Parameters
    ----------
    m : casadi SX, shape (2, 2)
        The matrix (any unit; the inverse has the reciprocal one).
    """
    a, b, c, d = m[0, 0], m[0, 1], m[1, 0], m[1, 1]
    return ca.vertcat(ca.horzcat(d, -b), ca.horzcat(-c, a)) / (a * d - b * c)


def _inv(m: Any) -> Any:
    return inverse_2x2(m) if m.shape == (2, 2) else ca.inv(m)


def _solve(m: Any, v: Any) -> Any:
    return ca.mtimes(inverse_2x2(m), v) if m.shape == (2, 2) else ca.solve(m, v)


def block_tridiagonal_solve(diag: Sequence[Any], lower: Sequence[Any], upper: Sequence[Any],
                            rhs: Sequence[Any]) -> list[Any]:
    """Solve a block-tridiagonal system by block elimination without pivoting (SX).

    Block row ``i`` reads ``lower[i-1] x[i-1] + diag[i] x[i] + upper[i] x[i+1] = rhs[i]``.

    Parameters
    ----------
    diag : sequence of casadi SX, each (b, b)
        The ``n`` diagonal blocks.
    lower : sequence of casadi SX, each (b, b)
        The ``n - 1`` blocks below the diagonal (``lower[i]`` in block row ``i + 1``).
    upper : sequence of casadi SX, each (b, b)
        The ``n - 1`` blocks above the diagonal (``upper[i]`` in block row ``i``).
    rhs : sequence of casadi SX, each (b, 1) or (b, k)
        The right-hand side per block row.

    Returns
    -------
    list of casadi SX
        The solution per block row.
    """
    n = len(diag)
    piv = [diag[0]]
    y = [rhs[0]]
    for i in range(1, n):
        w = ca.mtimes(lower[i - 1], _inv(piv[i - 1]))
        piv.append(diag[i] - ca.mtimes(w, upper[i - 1]))
        y.append(rhs[i] - ca.mtimes(w, y[i - 1]))
    x: list[Any] = [None] * n
    x[n - 1] = _solve(piv[n - 1], y[n - 1])
    for i in range(n - 2, -1, -1):
        x[i] = _solve(piv[i], y[i] - ca.mtimes(upper[i], x[i + 1]))
    return x
