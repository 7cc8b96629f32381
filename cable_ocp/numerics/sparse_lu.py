"""A sparse LU factorisation kept between solves (compiled C, called through ctypes).

CasADi's linear solvers factorise the matrix at every call; a simplified (chord) Newton
iteration needs one factorisation reused for several right-hand sides, and a sweep
factorises matrices of one sparsity hundreds of times. This module keeps both the
factors and the *pivot order*:

* **Analysis** (first use, and whenever a refactorisation is refused, below): SciPy's SuperLU
  (``scipy.sparse.linalg.splu``) with columns in their natural order (the collocation
  unknowns are already in interval order: fill-reducing orderings gave no less fill
  here) and threshold partial pivoting (``diag_pivot_thresh`` :data:`ANALYSE_THRESHOLD`)
  gives the row and column permutations; the patterns of L and U for them are the fill
  of Gaussian elimination in that order, computed from the structure in C (SciPy's own
  L and U leave out entries that happen to be zero for the analysed values).
* **Refactorisation** (every Newton step): a left-looking LU without pivoting search on
  those fixed patterns and permutations (Gilbert & Peierls (1988), *SIAM J. Sci. Stat.
  Comput.* 9(5); the refactorisation of KLU, Davis & Palamadai Natarajan (2010), *ACM
  TOMS* 37(3)), in C: about 60 000 flops for De Zoysa's cable on 40 intervals
  (n = 966), ~0.08 ms against ~0.33 ms for the sparse Householder QR used before.
  Each pivot is checked against the entries below it in its column, as threshold
  partial pivoting does (Duff, Erisman & Reid (2017), *Direct Methods for Sparse
  Matrices*, 2nd ed., sec. 7.8): a pivot smaller than :data:`REFACTOR_THRESHOLD` times
  the largest of them, zero, or a non-finite entry stops the refactorisation. As that
  test alone lets the entries grow by up to 1 + 1/threshold per column, the largest entry
  of U is checked too (:data:`GROWTH_LIMIT` times the largest of the matrix). A refused
  refactorisation means a new analysis with SuperLU's pivoting (:attr:`SparseLU.analyses`
  counts them).

A singular matrix (SuperLU: "exactly singular") gives non-finite steps, not an exception.
Without a C compiler (:mod:`cable_ocp.numerics.compile`) the helper is unavailable:
:func:`available` is False and callers keep CasADi's linear solvers.
"""

from __future__ import annotations

import ctypes
import functools
import hashlib
import os
import shutil
import tempfile

import casadi as ca
import numpy as np
import scipy.sparse as sps
import scipy.sparse.linalg as spl

from cable_ocp.numerics import interrupt
from cable_ocp.numerics.compile import (
    c_compiler,
    cache_dir,
    compile_shared,
    forget_library,
    install_library,
    library_ok,
)

#: SuperLU's threshold for keeping the diagonal as pivot in the analysis: a diagonal entry
#: at least this fraction of the largest in its column is kept (1.0: partial pivoting);
#: below 1, the pivot order depends less on the values, so it survives more Newton steps
ANALYSE_THRESHOLD = 0.1
#: a refactorisation pivot below this fraction of the largest entry under it in its
#: column (after the updates) is refused, and the matrix analysed again
REFACTOR_THRESHOLD = 0.01
#: a refactorisation on a kept pivot order whose largest entry of U exceeds this times the
#: largest entry of the matrix is refused, and the matrix analysed again: the threshold
#: alone allows a growth of 101 per column (a banded matrix with a border column reached
#: 1e16 in 8 columns); the collocated Jacobians of the shipped and extreme scenes grow by
#: 3-23
GROWTH_LIMIT = 1e6

_SOURCE = r"""
#include <math.h>
typedef long long cint;

/* The patterns of L and U in L U = P A Q without further pivoting (the fill of Gaussian
   elimination in this order): lp/li with the diagonal first in each column, up/ui in
   ascending rows with the diagonal last. mark: work of length n. Column j's reach: the
   rows of column q[j] of A, then for k < j in ascending order, when row k is reached, the
   rows of L(:, k). Returns 0, or -1 when li or ui would need more than cap entries. */
int clu_symbolic(cint n, const cint* ap, const cint* ai, const cint* pinv, const cint* q,
                 cint* lp, cint* li, cint* up, cint* ui, cint cap, cint* mark) {
  cint j, p, k, r, i, nl = 0, nu = 0, kmin;
  for (i = 0; i < n; ++i) mark[i] = -1;
  lp[0] = up[0] = 0;
  for (j = 0; j < n; ++j) {
    kmin = j;
    if (nl + 1 > cap) return -1;
    li[nl++] = j;
    mark[j] = j;
    for (p = ap[q[j]]; p < ap[q[j] + 1]; ++p) {
      i = pinv[ai[p]];
      if (mark[i] == j) continue;
      mark[i] = j;
      if (i < kmin) kmin = i;
      else if (i > j) { if (nl + 1 > cap) return -1; li[nl++] = i; }
    }
    for (k = kmin; k < j; ++k) {
      if (mark[k] != j) continue;
      if (nu + 1 > cap) return -1;
      ui[nu++] = k;
      for (r = lp[k] + 1; r < lp[k + 1]; ++r) {
        i = li[r];
        if (mark[i] == j) continue;
        mark[i] = j;
        if (i > j) { if (nl + 1 > cap) return -1; li[nl++] = i; }
      }
    }
    if (nu + 1 > cap) return -1;
    ui[nu++] = j;
    up[j + 1] = nu; lp[j + 1] = nl;
  }
  return 0;
}

/* L U = P A Q on fixed patterns (CSC): L unit lower with its diagonal stored first in
   each column (the rows below it in any order), U upper with its rows ascending and its
   diagonal last. pinv[i]: the row of P A holding row i of A; q[j]: the column of A that is
   column j of A Q. x: work of length n, zero on return (on entry, only the rows this
   elimination reads before writing them must be zero: the entries of A are assigned).
   Refused (the return value): a pivot of column j below tau times the largest entry
   under it, zero or not finite, or a non-finite entry (j + 1); with gmax > 0, a largest
   entry of U above gmax times the largest of A (growth: n + 1). 0: factorised. */
int clu_refactor(cint n, const cint* ap, const cint* ai, const double* ax,
                 const cint* pinv, const cint* q, const cint* lp, const cint* li,
                 double* lx, const cint* up, const cint* ui, double* ux, double* x,
                 double tau, double gmax) {
  cint j, k, p, pe, r; double xk, piv, big, a, amax = 0, umax = 0, chk = 0;
  if (gmax > 0) for (p = 0; p < ap[n]; ++p) { a = fabs(ax[p]); if (a > amax) amax = a; }
  for (j = 0; j < n; ++j) {
    for (p = ap[q[j]]; p < ap[q[j] + 1]; ++p) x[pinv[ai[p]]] = ax[p];
    for (p = up[j], pe = up[j + 1] - 1; p < pe; ++p) {
      k = ui[p]; xk = x[k]; ux[p] = xk; x[k] = 0;
      chk += 0.0 * xk;  /* NaN when an entry is not finite */
      a = fabs(xk); if (a > umax) umax = a;
      if (xk != 0) for (r = lp[k] + 1; r < lp[k + 1]; ++r) x[li[r]] -= lx[r] * xk;
    }
    piv = x[j]; x[j] = 0; ux[up[j + 1] - 1] = piv;
    big = 0;
    for (r = lp[j] + 1; r < lp[j + 1]; ++r) {
      a = fabs(x[li[r]]); chk += 0.0 * a; if (a > big) big = a;
    }
    chk += 0.0 * piv;
    if (chk != 0 || !(fabs(piv) >= tau * big) || !(fabs(piv) > 0)) {
      for (r = 0; r < n; ++r) x[r] = 0;
      return (int)(j + 1);
    }
    if (fabs(piv) > umax) umax = fabs(piv);
    for (r = lp[j] + 1; r < lp[j + 1]; ++r) { lx[r] = x[li[r]] / piv; x[li[r]] = 0; }
  }
  if (gmax > 0 && umax > gmax * amax) return (int)(n + 1);
  return 0;
}

/* b <- -A^-1 b (the Newton step of a residual b) with the factors; w: work of length n */
void clu_solve(cint n, const cint* pinv, const cint* q, const cint* lp, const cint* li,
               const double* lx, const cint* up, const cint* ui, const double* ux,
               double* b, double* w) {
  cint j, p, pe; double wj;
  for (j = 0; j < n; ++j) w[pinv[j]] = b[j];
  for (j = 0; j < n; ++j) {
    wj = w[j];
    if (wj != 0) for (p = lp[j] + 1; p < lp[j + 1]; ++p) w[li[p]] -= lx[p] * wj;
  }
  for (j = n - 1; j >= 0; --j) {
    pe = up[j + 1] - 1;
    wj = w[j] /= ux[pe];
    if (wj != 0) for (p = up[j]; p < pe; ++p) w[ui[p]] -= ux[p] * wj;
  }
  for (j = 0; j < n; ++j) b[q[j]] = -w[j];
}
"""


def _library() -> ctypes.CDLL | None:
    """The compiled helper (built once per machine into the cache folder), or None."""
    folder, cc = cache_dir(), c_compiler()
    if folder is None or cc is None:
        return None
    return _load(folder, tuple(cc))


#: the helper libraries this process compiled or loaded (the newest last): a new cache
#: folder gets a copy instead of a second compilation
_BUILT: list[str] = []


def _open(lib: str) -> ctypes.CDLL:
    """The compiled helper at ``lib`` with its functions' signatures."""
    dll = ctypes.CDLL(lib)
    dll.clu_refactor.restype = ctypes.c_int
    dll.clu_refactor.argtypes = [ctypes.c_longlong] + [ctypes.c_void_p] * 12 \
        + [ctypes.c_double, ctypes.c_double]
    dll.clu_solve.restype = None
    dll.clu_solve.argtypes = [ctypes.c_longlong] + [ctypes.c_void_p] * 10
    dll.clu_symbolic.restype = ctypes.c_int
    dll.clu_symbolic.argtypes = [ctypes.c_longlong] + [ctypes.c_void_p] * 8 \
        + [ctypes.c_longlong, ctypes.c_void_p]
    return dll


@functools.lru_cache(maxsize=8)
def _load(folder: str, cc: tuple[str, ...]) -> ctypes.CDLL | None:
    """The helper compiled by ``cc`` into ``folder`` (once per process and setting; once
    per machine for one cache folder: a later folder gets a copy). A library that does not
    load (a truncated or foreign file) is removed and built again, never trusted."""
    digest = hashlib.sha256(_SOURCE.encode()).hexdigest()[:16]
    lib = os.path.join(folder, f"cable_ocp_sparse_lu_{digest}.so")
    try:
        if library_ok(lib):  # only a library that matches its record is ever opened
            try:
                dll = _open(lib)
                _BUILT.append(lib)
                return dll
            except (OSError, AttributeError):  # broken: built again below
                forget_library(lib)
        else:
            forget_library(lib)
        os.makedirs(folder, exist_ok=True)
        made = [x for x in _BUILT if library_ok(x)]  # all of this one source
        if made:  # already compiled in this process: a copy
            part = lib + f".{os.getpid()}.tmp"
            try:
                shutil.copyfile(made[-1], part)
                install_library(part, lib)
            finally:
                if os.path.exists(part):
                    os.remove(part)
        else:
            with tempfile.TemporaryDirectory(prefix="cable_ocp_") as tmp:
                src = os.path.join(tmp, "sparse_lu.c")
                with open(src, "w", encoding="utf-8") as fh:
                    fh.write(_SOURCE)
                compile_shared(list(cc), "-O2", src, lib, timeout=120)
        dll = _open(lib)
        _BUILT.append(lib)
        return dll
    except Exception as exc:  # noqa: BLE001 - no helper: callers keep CasADi's linear solvers
        interrupt.reraise_interruption(exc)
        return None


def available() -> bool:
    """True when the compiled helper can be used (a C compiler, compiling not off)."""
    return _library() is not None


def _ptr(a: np.ndarray) -> ctypes.c_void_p:
    return ctypes.c_void_p(a.ctypes.data)


def _index(a: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=np.int64)


class SparseLU:
    """LU factors of square matrices of one sparsity, and their pivot order, kept between
    solves.

    Parameters
    ----------
    sparsity : casadi.Sparsity
        The pattern (n x n) of the matrices; their nonzeros are given in its
        compressed-column order (in :attr:`nz`).
    """

    def __init__(self, sparsity: ca.Sparsity):
        dll = _library()
        if dll is None:
            raise RuntimeError("the sparse LU helper needs a C compiler")
        self._dll = dll
        self.n = n = sparsity.size2()
        self._ap = _index(sparsity.colind())
        self._ai = _index(sparsity.row())
        self.nz = np.zeros(sparsity.nnz())  #: the matrix's nonzeros (filled by the caller)
        self.x = np.zeros(n)  #: right-hand side in, solution out
        self._work = np.zeros(n)  # the refactorisation's (zero between calls)
        self._wsolve = np.zeros(n)  # the back-substitution's
        self._factor: functools.partial | None = None
        self._fresh: functools.partial | None = None
        self._solve: functools.partial | None = None
        self._singular = True
        #: pivot orders computed (SuperLU analyses): the first, and one per refused pivot
        self.analyses = 0

    def _analyse(self) -> None:
        """SuperLU with threshold pivoting on the present matrix gives the permutations;
        the patterns of L and U for them are computed here (symbolically: SciPy leaves
        out of its L and U the entries that happen to be zero for these values)."""
        self.analyses += 1
        n = self.n
        a = sps.csc_matrix((self.nz, self._ai, self._ap), shape=(n, n))
        try:
            lu = spl.splu(a, permc_spec="NATURAL", diag_pivot_thresh=ANALYSE_THRESHOLD)
        except RuntimeError:  # "Factor is exactly singular"
            self._factor = self._fresh = self._solve = None
            return
        # column j of A Q is column q[j] of A (SciPy: P_r A P_c = L U, P_c[i, perm_c[i]] = 1)
        q = np.empty(n, dtype=np.int64)
        q[lu.perm_c] = np.arange(n)
        pinv = _index(lu.perm_r)
        lp, up, mark = (np.zeros(n + 1, dtype=np.int64), np.zeros(n + 1, dtype=np.int64),
                        np.zeros(n, dtype=np.int64))
        cap = 4 * (lu.L.nnz + lu.U.nnz) + n
        while True:
            li, ui = np.zeros(cap, dtype=np.int64), np.zeros(cap, dtype=np.int64)
            p = _ptr
            if self._dll.clu_symbolic(n, p(self._ap), p(self._ai), p(pinv), p(q), p(lp),
                                      p(li), p(up), p(ui), cap, p(mark)) == 0:
                break
            cap *= 2
        self._pinv, self._q, self._lp, self._up = pinv, q, lp, up
        self._li, self._ui = li[:lp[n]].copy(), ui[:up[n]].copy()
        self._lx, self._ux = np.zeros(lp[n]), np.zeros(up[n])
        args = (n, p(self._ap), p(self._ai), p(self.nz), p(pinv), p(q), p(lp), p(self._li),
                p(self._lx), p(up), p(self._ui), p(self._ux), p(self._work), REFACTOR_THRESHOLD)
        # on the kept order with the growth check; right after the analysis without (its
        # pivots are SuperLU's own choice for this matrix)
        self._factor = functools.partial(self._dll.clu_refactor, *args, GROWTH_LIMIT)
        self._fresh = functools.partial(self._dll.clu_refactor, *args, 0.0)
        self._solve = functools.partial(
            self._dll.clu_solve, n, p(pinv), p(q), p(lp), p(self._li), p(self._lx), p(up),
            p(self._ui), p(self._ux), p(self.x), p(self._wsolve))

    def factor(self) -> None:
        """Factorise the matrix whose nonzeros are in :attr:`nz`: on the kept pivot order,
        or, when that is refused (a small pivot, growth, a non-finite entry) or on first
        use, on a new one."""
        if self._factor is not None and self._factor() == 0:
            self._singular = False
            return
        self._analyse()
        # SuperLU's own pivots pass the check (its threshold is larger), unless the matrix
        # is singular to working precision or has non-finite entries
        self._singular = self._fresh is None or self._fresh() != 0

    def newton_step(self, g: np.ndarray) -> np.ndarray:
        """``-A^-1 g`` with the last factors (a new array; non-finite entries when the
        factorised matrix was singular)."""
        if self._singular:
            return np.full(self.n, np.nan)
        self.x[:] = g
        self._solve()
        return self.x.copy()
