"""A sparse QR factorisation kept between solves (compiled C, called through ctypes).

CasADi's linear solvers factorise the matrix at every call; a simplified (chord) Newton
iteration needs one factorisation reused for several right-hand sides. This module
compiles, once per machine, a small C library with the Householder QR of CasADi's "qr"
linear solver (``casadi_qr``, ``casadi_qr_mv``, ``casadi_qr_trs``, ``casadi_qr_solve``
of CasADi's runtime, MIT No Attribution, after T. Davis (2006), *Direct Methods for
Sparse Linear Systems*, ch. 5), specialised to double precision, and keeps the factors
(V, R, beta) in numpy arrays: :meth:`SparseQR.factor` fills them from the nonzeros of a
matrix of fixed sparsity, :meth:`SparseQR.solve` back-substitutes.

The symbolic analysis (column ordering, the patterns of V and R) is CasADi's own
(``Sparsity.qr_sparse``). Without a C compiler (:mod:`cable_ocp.compile`) the helper is
unavailable: :func:`available` is False and callers keep CasADi's linear solvers.
"""

from __future__ import annotations

import ctypes
import functools
import hashlib
import os
import tempfile

import casadi as ca
import numpy as np

from cable_ocp.compile import c_compiler, cache_dir, compile_shared

_SOURCE = r"""
#include <math.h>
typedef long long cint;

static double house(double* v, double* beta, cint nv) {
  cint i; double v0, sigma, s;
  v0 = v[0]; sigma = 0;
  for (i = 1; i < nv; ++i) sigma += v[i]*v[i];
  s = sqrt(v0*v0 + sigma);
  if (sigma == 0) { v[0] = 1; *beta = (v0 <= 0) ? 2 : 0; }
  else { v[0] = (v0 <= 0) ? v0 - s : -sigma/(v0 + s); *beta = -1/(s*v[0]); }
  return s;
}

void cqr_factor(const cint* sp_a, const double* nz_a, double* x,
                const cint* sp_v, double* nz_v, const cint* sp_r, double* nz_r,
                double* beta, const cint* prinv, const cint* pc) {
  cint ncol, nrow, r, c, k, k1; double alpha;
  const cint *a_colind, *a_row, *v_colind, *v_row, *r_colind, *r_row;
  ncol = sp_a[1]; a_colind = sp_a + 2; a_row = sp_a + 2 + ncol + 1;
  nrow = sp_v[0]; v_colind = sp_v + 2; v_row = sp_v + 2 + ncol + 1;
  r_colind = sp_r + 2; r_row = sp_r + 2 + ncol + 1;
  for (r = 0; r < nrow; ++r) x[r] = 0;
  for (c = 0; c < ncol; ++c) {
    for (k = a_colind[pc[c]]; k < a_colind[pc[c]+1]; ++k) x[prinv[a_row[k]]] = nz_a[k];
    for (k = r_colind[c]; k < r_colind[c+1] && (r = r_row[k]) < c; ++k) {
      alpha = 0;
      for (k1 = v_colind[r]; k1 < v_colind[r+1]; ++k1) alpha += nz_v[k1]*x[v_row[k1]];
      alpha *= beta[r];
      for (k1 = v_colind[r]; k1 < v_colind[r+1]; ++k1) x[v_row[k1]] -= alpha*nz_v[k1];
      *nz_r++ = x[r];
      x[r] = 0;
    }
    for (k = v_colind[c]; k < v_colind[c+1]; ++k) { nz_v[k] = x[v_row[k]]; x[v_row[k]] = 0; }
    *nz_r++ = house(nz_v + v_colind[c], beta + c, v_colind[c+1] - v_colind[c]);
  }
}

/* x <- -A^-1 x (the Newton step of a residual x), w: work of length nrow_ext */
void cqr_solve(double* x, const cint* sp_v, const double* v, const cint* sp_r,
               const double* r, const double* beta, const cint* prinv, const cint* pc,
               double* w) {
  cint nrow_ext = sp_v[0], ncol = sp_v[1], c, c1, k, rr;
  const cint *vc = sp_v + 2, *vr = sp_v + 2 + ncol + 1;
  const cint *rc = sp_r + 2, *rw = sp_r + 2 + ncol + 1;
  double alpha;
  for (c = 0; c < nrow_ext; ++c) w[c] = 0;
  for (c = 0; c < ncol; ++c) w[prinv[c]] = x[c];
  for (c1 = 0; c1 < ncol; ++c1) {  /* w <- Q' w */
    c = c1;
    alpha = 0;
    for (k = vc[c]; k < vc[c+1]; ++k) alpha += v[k]*w[vr[k]];
    alpha *= beta[c];
    for (k = vc[c]; k < vc[c+1]; ++k) w[vr[k]] -= alpha*v[k];
  }
  for (c = ncol - 1; c >= 0; --c) {  /* w <- R \ w */
    for (k = rc[c+1] - 1; k >= rc[c]; --k) {
      rr = rw[k];
      if (rr == c) w[rr] /= r[k]; else w[rr] -= r[k]*w[c];
    }
  }
  for (c = 0; c < ncol; ++c) x[pc[c]] = -w[c];
}
"""


def _library() -> ctypes.CDLL | None:
    """The compiled helper (built once per machine into the cache folder), or None."""
    folder, cc = cache_dir(), c_compiler()
    if folder is None or cc is None:
        return None
    return _load(folder, tuple(cc))


@functools.lru_cache(maxsize=8)
def _load(folder: str, cc: tuple[str, ...]) -> ctypes.CDLL | None:
    """The helper compiled by ``cc`` into ``folder`` (once per process and setting)."""
    digest = hashlib.sha256(_SOURCE.encode()).hexdigest()[:16]
    lib = os.path.join(folder, f"cable_ocp_sparse_qr_{digest}.so")
    try:
        if not os.path.exists(lib):
            os.makedirs(folder, exist_ok=True)
            with tempfile.TemporaryDirectory(prefix="cable_ocp_") as tmp:
                src = os.path.join(tmp, "sparse_qr.c")
                with open(src, "w", encoding="utf-8") as fh:
                    fh.write(_SOURCE)
                compile_shared(list(cc), "-O2", src, lib, timeout=120)
        dll = ctypes.CDLL(lib)
        dll.cqr_factor.restype = None
        dll.cqr_solve.restype = None
        return dll
    except Exception:  # noqa: BLE001 - no helper: callers keep CasADi's linear solvers
        return None


def available() -> bool:
    """True when the compiled helper can be used (a C compiler, compiling not off)."""
    return _library() is not None


def _ptr(a: np.ndarray) -> ctypes.c_void_p:
    return ctypes.c_void_p(a.ctypes.data)


class SparseQR:
    """QR factors of square matrices of one sparsity, kept between solves.

    Parameters
    ----------
    sparsity : casadi.Sparsity
        The pattern (n x n) of the matrices; their nonzeros are given in its
        compressed-column order.
    """

    def __init__(self, sparsity: ca.Sparsity):
        dll = _library()
        if dll is None:
            raise RuntimeError("the sparse QR helper needs a C compiler")
        sp_v, sp_r, prinv, pc = sparsity.qr_sparse(True)
        self.n = sparsity.size2()
        self._sp_a = np.asarray(sparsity.compress(), dtype=np.int64)
        self._sp_v = np.asarray(sp_v.compress(), dtype=np.int64)
        self._sp_r = np.asarray(sp_r.compress(), dtype=np.int64)
        self._prinv = np.asarray(prinv, dtype=np.int64)
        self._pc = np.asarray(pc, dtype=np.int64)
        self._v = np.zeros(sp_v.nnz())
        self._r = np.zeros(sp_r.nnz())
        self._beta = np.zeros(self.n)
        self._w = np.zeros(sp_v.size1())
        self.nz = np.zeros(sparsity.nnz())  #: the matrix's nonzeros (filled by the caller)
        self.x = np.zeros(self.n)  #: right-hand side in, solution out
        p = _ptr
        self._factor = functools.partial(
            dll.cqr_factor, p(self._sp_a), p(self.nz), p(self._w), p(self._sp_v), p(self._v),
            p(self._sp_r), p(self._r), p(self._beta), p(self._prinv), p(self._pc))
        self._solve = functools.partial(
            dll.cqr_solve, p(self.x), p(self._sp_v), p(self._v), p(self._sp_r), p(self._r),
            p(self._beta), p(self._prinv), p(self._pc), p(self._w))

    def factor(self) -> None:
        """Factorise the matrix whose nonzeros are in :attr:`nz`."""
        self._factor()

    def newton_step(self, g: np.ndarray) -> np.ndarray:
        """``-A^-1 g`` with the last factors (a new array; non-finite entries when the
        factorised matrix was singular)."""
        self.x[:] = g
        self._solve()
        return self.x.copy()
