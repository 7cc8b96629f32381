"""Sparse linear solves that never warn: a singular matrix is a failed solve (None), for
the caller to turn into a status with a message (the library is silent)."""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

__all__ = ["solve_sparse"]


def solve_sparse(mat: Any, rhs: np.ndarray) -> np.ndarray | None:
    """Solve ``mat x = rhs`` (a scipy sparse matrix) with ``spsolve``.

    Parameters
    ----------
    mat : scipy.sparse matrix
        Square matrix, shape (n, n) (CSC or CSR is best; other formats are converted).
    rhs : numpy.ndarray
        Right-hand side, shape (n,) (or (n, k) for k right-hand sides).

    Returns
    -------
    ndarray or None
        The solution, or None when the matrix is (numerically) singular: scipy's
        ``MatrixRankWarning``, any other warning of the solve, an exception, or a
        non-finite result. Nothing is printed or warned.
    """
    from scipy.sparse.linalg import spsolve

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            x = np.asarray(spsolve(mat, rhs))
        except Exception:  # noqa: BLE001 - MatrixRankWarning raised as error, or a failure
            return None
    if not np.all(np.isfinite(x)):
        return None
    return x
