"""IPOPT on the square collocated system: the statics solver's fallback when Newton fails.

The function built here is kept in the on-disk cache (:mod:`cable_ocp.statics.cache`, whose
key hashes this file): its options are part of what the cached function is.
"""

from __future__ import annotations

import casadi as ca

__all__ = ["build_ipopt"]


def build_ipopt(residual: ca.Function, n_w: int, n_p: int, tolerance: float,
                max_iterations: int) -> ca.Function:
    """``nlpsol`` for G(w, p) = 0 with a zero objective (a square system).

    Parameters
    ----------
    residual : casadi.Function
        ``G(w, p) -> g``, the collocated equations (scaled).
    n_w : int
        Number of unknowns (= number of equations).
    n_p : int
        Size of the parameter vector.
    tolerance : float
        IPOPT's ``tol`` and ``constr_viol_tol`` (scaled residual).
    max_iterations : int
        IPOPT's ``max_iter``.

    Returns
    -------
    casadi.Function
        The solver, called with ``x0, p, lbx, ubx, lbg=0, ubg=0``; it does not raise on a
        failed solve (``error_on_fail`` off: read its ``stats()``).
    """
    w = ca.MX.sym("w", n_w)
    p = ca.MX.sym("p", n_p)
    g = residual(w, p)
    return ca.nlpsol("statics_ipopt", "ipopt", {
        "x": w, "p": p, "f": 0, "g": g}, {
        "print_time": False,
        "error_on_fail": False,
        "ipopt.print_level": 0,
        "ipopt.sb": "yes",
        "ipopt.tol": tolerance,
        "ipopt.constr_viol_tol": tolerance,
        "ipopt.max_iter": max_iterations,
        "ipopt.nlp_scaling_method": "none",
        # square system: the primal step is fixed by the constraint Jacobian
        # alone, so the Lagrangian Hessian buys nothing here and costs build
        # and evaluation time
        "ipopt.hessian_approximation": "limited-memory",
        # the unknowns are already O(1); MUMPS' own scaling of this
        # zero-Hessian KKT system made its fill-in explode at N = 320, d = 5
        # (>1 GB, no progress)
        "ipopt.mumps_scaling": 0,
    })
