"""Newton's method on the collocated system G(w, p) = 0, with few Python round trips.

The residual of a transcription is described as *blocks*: each block is a small SX
function r = f(z, p) of a few unknowns z = w[index] (one collocation interval, the end
conditions, a joint), mapped over its instances. From the blocks this module builds

* ``G(w, p) -> g`` (MX over the mapped block functions),
* ``GJ(w, p) -> (g, J)`` with the sparse Jacobian J = dG/dw assembled from the blocks'
  own small SX Jacobians (no colouring of the global graph: building it costs about as
  much as building G, and the number of operations per evaluation is the same as that
  of the Jacobian of the fully expanded residual),
* ``step(w, p) -> (g, dw)``, the Newton step dw = -J^-1 g, with the sparse linear solve
  (CSparse's LU) inside the same call.

With the sparse-LU helper (:mod:`cable_ocp.numerics.sparse_lu`), J is factorised by a sparse
LU whose factors and pivot order are kept (:meth:`Kernel.attach_lu`; the compiled kernel,
``solver.compile = "auto"``, uses it for every step, the interpreted one from its first
warm solve on), and warm solves run :func:`chord_newton`: one factorisation serves several
steps, each a residual evaluation and a back-substitution.

:class:`Kernel` evaluates them through CasADi's ``FunctionBuffer`` on preallocated numpy
arrays (converting a 1000-entry numpy vector to a CasADi matrix costs about as much as
evaluating the residual), and :func:`newton` runs the iteration: Newton steps with a
backtracking line search within bounds, as CasADi's ``rootfinder`` does, but the full
step's residual comes from the next step's call, so an undamped step costs no extra
evaluation.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import casadi as ca
import numpy as np

from cable_ocp.numerics import interrupt

#: sparse linear solver of the Newton step (CasADi plugin): CSparse's LU, as the CasADi
#: ``rootfinder`` used before; its set-up costs a tenth of the sparse QR's ("qr") and its
#: solves about as much on the collocated systems
LINEAR_SOLVER = "csparse"


@dataclass(frozen=True)
class Block:
    """Rows of G computed by one SX function ``fn(z, p) -> r`` on ``count`` instances.

    Attributes
    ----------
    fn : casadi.Function
        ``(z[nz], p[np]) -> r[nr]``, built from SX.
    z_index : ndarray of int, shape (nz, count)
        Indices into w of each instance's z.
    rows : ndarray of int, shape (nr, count)
        Rows of G of each instance's r.
    jac : casadi.Function, optional
        ``(z, p) -> (r, dr/dz)`` when the block knows its Jacobian's structure (cheaper
        to build than differentiating ``fn``); else ``fn`` is differentiated.
    p_index : ndarray of int, shape (np, count), optional
        Indices into the global parameter vector of each instance's ``p`` (per-instance
        parameters, e.g. the width of each collocation interval); None: every instance
        gets the whole parameter vector.
    """

    fn: ca.Function
    z_index: np.ndarray
    rows: np.ndarray
    jac: ca.Function | None = None
    p_index: np.ndarray | None = None

    @property
    def count(self) -> int:
        """Number of instances."""
        return int(self.z_index.shape[1])


def _gather(w: ca.MX, block: Block) -> ca.MX:
    """z of every instance as the columns of one (nz, count) matrix."""
    nz, count = block.z_index.shape
    return ca.reshape(w[block.z_index.ravel(order="F").tolist()], nz, count)


def _scatter_order(blocks: list[Block], n: int) -> list[int]:
    """Permutation taking the concatenated block outputs to the rows of G."""
    rows = np.concatenate([b.rows.ravel(order="F") for b in blocks])
    if rows.size != n or not np.array_equal(np.sort(rows), np.arange(n)):
        raise ValueError("the blocks do not cover every row of G exactly once")
    order = np.empty(n, dtype=int)
    order[rows] = np.arange(n)
    return order.tolist()


def _block_params(block: Block, p: ca.MX) -> ca.MX:
    """The block's parameters: p itself, or one column per instance (its entries of p)."""
    if block.p_index is None:
        return p
    m, count = block.p_index.shape
    return ca.reshape(p[block.p_index.ravel(order="F").tolist()], m, count)


def _call(block: Block, fn: ca.Function, w: ca.MX, p: ca.MX) -> list[ca.MX]:
    z = _gather(w, block)
    p = _block_params(block, p)
    if block.count == 1:
        return fn(z, p) if fn.n_out() > 1 else [fn(z, p)]
    out = fn.map(block.count)(z, p)
    return out if fn.n_out() > 1 else [out]


def residual_function(blocks: list[Block], n_w: int, n_p: int, name: str = "G"
                      ) -> ca.Function:
    """``G(w, p) -> g`` from the blocks (rows in the blocks' declared order).

    Parameters
    ----------
    blocks : list of Block
        The residual's blocks; together their ``rows`` cover every row 0 .. n_w - 1 of G
        exactly once (else ValueError).
    n_w : int
        Number of unknowns, and of equations (the system is square).
    n_p : int
        Length of the parameter vector p.
    name : str, default "G"
        Name of the CasADi function.
    """
    w, p = ca.MX.sym("w", n_w), ca.MX.sym("p", n_p)
    parts = [ca.vec(_call(b, b.fn, w, p)[0]) for b in blocks]
    g = ca.vertcat(*parts)[_scatter_order(blocks, n_w)]
    return ca.Function(name, [w, p], [g], ["w", "p"], ["g"])


def jacobian_functions(blocks: list[Block], n_w: int, n_p: int,
                       linear_solver: str = LINEAR_SOLVER) -> tuple[ca.Function, ca.Function]:
    """``GJ(w, p) -> (g, J)`` and ``step(w, p) -> (g, dw)`` from the blocks.

    J is assembled from each block's SX Jacobian dr/dz (its structural nonzeros, in
    compressed-column order of the global pattern); dw = -J^-1 g by ``linear_solver``.

    Parameters
    ----------
    blocks : list of Block
        The residual's blocks, as for :func:`residual_function`; a block without ``jac``
        is differentiated here. Two blocks writing the same entry of J raise ValueError.
    n_w : int
        Number of unknowns, and of equations.
    n_p : int
        Length of the parameter vector p.
    linear_solver : str, default LINEAR_SOLVER
        CasADi linear-solver plugin of the Newton step (``casadi.solve``), e.g.
        ``"csparse"`` or ``"qr"``.
    """
    w, p = ca.MX.sym("w", n_w), ca.MX.sym("p", n_p)
    g_parts, values, rows, cols = [], [], [], []
    for b in blocks:
        if b.jac is not None:
            fj = b.jac
        else:
            z = ca.SX.sym("z", b.fn.size1_in(0))
            ps = ca.SX.sym("p", b.fn.size1_in(1))
            r = b.fn(z, ps)
            fj = ca.Function(b.fn.name() + "_jac", [z, ps], [r, ca.jacobian(r, z)])
        r_all, j_all = _call(b, fj, w, p)
        g_parts.append(ca.vec(r_all))
        values.append(j_all.nz[:] if j_all.nnz() else ca.MX(0, 1))
        jr, jc = (np.asarray(v) for v in fj.sparsity_out(1).get_triplet())
        # the per-instance nonzeros in compressed-column order of (nr, nz)
        order = np.lexsort((jr, jc))
        jr, jc = jr[order], jc[order]
        rows.append(b.rows[jr, :].ravel(order="F"))  # instance by instance
        cols.append(b.z_index[jc, :].ravel(order="F"))
    g = ca.vertcat(*g_parts)[_scatter_order(blocks, n_w)]
    rows_a, cols_a = np.concatenate(rows), np.concatenate(cols)
    key = np.sort(cols_a.astype(np.int64) * n_w + rows_a)
    if key.size > 1 and np.any(key[1:] == key[:-1]):
        raise ValueError("two blocks write the same Jacobian entry")
    ccs = np.lexsort((rows_a, cols_a))
    colind = np.searchsorted(cols_a[ccs], np.arange(n_w + 1))
    sp = ca.Sparsity(n_w, n_w, colind.tolist(), rows_a[ccs].tolist())
    jac_mx = ca.sparsity_cast(ca.vertcat(*values)[ccs.tolist()], sp)
    gj = ca.Function("GJ", [w, p], [g, jac_mx], ["w", "p"], ["g", "J"])
    dw = -ca.solve(jac_mx, g, linear_solver)
    step = ca.Function("newton_step", [w, p], [g, dw], ["w", "p"], ["g", "dw"])
    return gj, step


class Kernel:
    """Buffered evaluation of ``G`` and the Newton step (not thread-safe: one set of
    buffers per kernel).

    Parameters
    ----------
    g_fn : casadi.Function
        ``(w, p) -> g``.
    step_fn : casadi.Function, optional
        ``(w, p) -> (g, dw)``; :meth:`step` calls it when given (the interpreted kernel:
        CasADi's CSparse LU inside the call, which a cold solve's few steps prefer to an
        LU analysis), else factorises with ``lu``.
    gj_fn : casadi.Function, optional
        ``(w, p) -> (g, J)``, with ``lu``: the Jacobian is factorised by ``lu`` and the
        factors are kept (:meth:`factor`, :meth:`chord_step`: the simplified Newton
        iteration of :func:`chord_newton`).
    lu : cable_ocp.numerics.sparse_lu.SparseLU, optional
        Factors of matrices of J's sparsity.
    """

    def __init__(self, g_fn: ca.Function, step_fn: ca.Function | None = None,
                 gj_fn: ca.Function | None = None, lu: object | None = None):
        n_w, n_p = g_fn.size1_in(0), g_fn.size1_in(1)
        self.n_w, self.n_p = n_w, n_p
        self._w = np.zeros(n_w)
        self._p = np.zeros(n_p)
        self._g = np.zeros(n_w)
        self._g2 = np.zeros(n_w)
        self._dw = np.zeros(n_w)
        self._gbuf, self._geval = g_fn.buffer()
        self._gbuf.set_arg(0, memoryview(self._w))
        self._gbuf.set_arg(1, memoryview(self._p))
        self._gbuf.set_res(0, memoryview(self._g))
        self._lu = None
        if gj_fn is not None and lu is not None:
            self.attach_lu(gj_fn, lu)
        self._seval = None
        if step_fn is not None:
            self._sbuf, self._seval = step_fn.buffer()
            self._sbuf.set_arg(0, memoryview(self._w))
            self._sbuf.set_arg(1, memoryview(self._p))
            self._sbuf.set_res(0, memoryview(self._g2))
            self._sbuf.set_res(1, memoryview(self._dw))
        elif self._lu is None:
            raise ValueError("a kernel needs step_fn, or gj_fn with lu")
        #: evaluations since construction: residuals, Newton steps (Jacobian + solve),
        #: factorisations kept for chord steps and the chord steps
        self.counts = {"g": 0, "step": 0, "factor": 0, "chord": 0}

    def attach_lu(self, gj_fn: ca.Function, lu: object) -> None:
        """Keep factorisations from now on: ``gj_fn`` ``(w, p) -> (g, J)`` and ``lu``
        (a :class:`cable_ocp.numerics.sparse_lu.SparseLU` of J's sparsity).

        Parameters
        ----------
        gj_fn : casadi.Function
            ``(w, p) -> (g, J)``, the residual and its sparse Jacobian (``GJ`` of
            :func:`jacobian_functions`); J's nonzeros are written straight into ``lu.nz``.
        lu : cable_ocp.numerics.sparse_lu.SparseLU
            The sparse LU of matrices of J's sparsity whose factors are kept.
        """
        self._lu = lu
        self._jbuf, self._jeval = gj_fn.buffer()
        self._jbuf.set_arg(0, memoryview(self._w))
        self._jbuf.set_arg(1, memoryview(self._p))
        self._jbuf.set_res(0, memoryview(self._g2))
        self._jbuf.set_res(1, memoryview(lu.nz))

    @property
    def can_chord(self) -> bool:
        """True when the kernel keeps its factorisation (:func:`chord_newton` applies)."""
        return self._lu is not None

    def g(self, w: np.ndarray, p: np.ndarray) -> np.ndarray:
        """G(w, p) (a new array).

        Parameters
        ----------
        w : numpy.ndarray, shape (n_w,)
            Scaled unknowns.
        p : numpy.ndarray, shape (n_p,)
            Scaled parameters.
        """
        self._w[:] = w
        self._p[:] = p
        self._geval()
        self.counts["g"] += 1
        return self._g.copy()

    def factor(self, w: np.ndarray, p: np.ndarray) -> np.ndarray:
        """Evaluate G and J at (w, p), factorise J and keep the factors; return G (a new
        array). Only when :attr:`can_chord`.

        Parameters
        ----------
        w : numpy.ndarray, shape (n_w,)
            Scaled unknowns, the point of the factorisation.
        p : numpy.ndarray, shape (n_p,)
            Scaled parameters.
        """
        self._factorise(w, p)
        self.counts["factor"] += 1
        return self._g2.copy()

    def _factorise(self, w: np.ndarray, p: np.ndarray) -> None:
        """G and J at (w, p) into their buffers (``_g2``, the LU's nonzeros), then J
        factorised in place (the factors kept)."""
        self._w[:] = w
        self._p[:] = p
        self._jeval()
        self._lu.factor()

    def chord_step(self, g: np.ndarray) -> np.ndarray:
        """``-J^-1 g`` with the kept factors (a new array; non-finite where J was
        singular)."""
        self.counts["chord"] += 1
        return self._lu.newton_step(g)

    def step(self, w: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(G(w, p), -J(w, p)^-1 G(w, p)) (new arrays; the step is NaN where the sparse
        factorisation fails: a singular Jacobian).

        Parameters
        ----------
        w : numpy.ndarray, shape (n_w,)
            Scaled unknowns.
        p : numpy.ndarray, shape (n_p,)
            Scaled parameters.
        """
        if self._seval is None:
            self._factorise(w, p)
            self.counts["step"] += 1
            dw = self._lu.newton_step(self._g2)
            return self._g2.copy(), dw if np.all(np.isfinite(dw)) else np.full(self.n_w, np.nan)
        self._w[:] = w
        self._p[:] = p
        self.counts["step"] += 1
        try:
            self._seval()
        except RuntimeError as exc:  # CSparse: "factorization failed, ... singular"
            interrupt.reraise_interruption(exc)
            return self.g(w, p), np.full(self.n_w, np.nan)
        return self._g2.copy(), self._dw.copy()


@dataclass
class NewtonResult:
    """Outcome of :func:`newton`."""

    w: np.ndarray
    g: np.ndarray | None  # G at w when evaluated there (None otherwise)
    iterations: int  # Newton steps taken (linear solves)
    success: bool
    message: str
    factorizations: int = -1  # Jacobians evaluated and factorised (-1: not counted)
    kappa: float = math.nan  # |G| after a full step over |step|^2 (nan: not measured)
    p: np.ndarray | None = None  # the parameters at w, when a remesh changed them
    remeshes: int = 0  # moves onto another mesh during the iteration
    chord: bool = False  # chord steps were taken first (:func:`chord_newton`)


def _max_step(w: np.ndarray, dw: np.ndarray, lb: np.ndarray | None, ub: np.ndarray | None
              ) -> float:
    """Largest alpha <= 1 keeping w + alpha dw within 99 % of the way to the bounds."""
    alpha = 1.0
    for bound, sign in ((lb, -1.0), (ub, 1.0)):
        if bound is None:
            continue
        gap = sign * (bound - w)  # >= 0 inside
        move = sign * dw
        hit = np.isfinite(bound) & (move > 0)
        if np.any(hit):
            alpha = min(alpha, float(np.min(0.99 * np.maximum(gap[hit], 0.0) / move[hit])))
    return alpha


def _decrease(g_new: np.ndarray, g_max: float, alpha: float) -> bool:
    """Sufficient decrease for a step of length alpha: max|G| falls to (1 - alpha/2) of
    its value (the test of CasADi's ``rootfinder`` "newton")."""
    new = float(np.max(np.abs(g_new))) if g_new.size else 0.0
    return math.isfinite(new) and new <= (1.0 - 0.5 * alpha) * g_max


#: a remesh is tried before evaluating a full step whose residual, predicted from the
#: quadratic convergence, is at most this (scaled): the iterate is then close enough for
#: its kinks to be where the solution's are (a kink found 1e-4 of the cable's length away
#: from the solution's leaves ~2e-13 of error on De Zoysa's cable, :mod:`kinks`)
REMESH_RESIDUAL = 1e-4
#: a point moved onto another mesh is accepted while max|G| there is at most this (scaled)
#: or the residual before the move: the residuals of two meshes do not compare (moving a
#: converged 8-interval solution of De Zoysa's cable onto the fitted mesh leaves ~1e-4,
#: from which Newton converges in two steps)
REMESH_ACCEPT = 1e-3


def newton(kernel: Kernel, w0: np.ndarray, p: np.ndarray, tol: float, max_iter: int = 30,
           lb: np.ndarray | None = None, ub: np.ndarray | None = None,
           step_tol: float = 1e-14, kappa: float = math.nan,
           remesh: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray] | None] | None = None,
           unmesh: Callable[[], None] | None = None) -> NewtonResult:
    """Solve G(w, p) = 0 from ``w0`` to max|G| <= ``tol`` by Newton's method with a
    backtracking line search within [lb, ub]: the step length is halved until max|G| falls
    to (1 - alpha/2) of its value, as in CasADi's ``rootfinder`` "newton" (its default).

    The full step is tried first, and its residual comes from the next Newton-step call
    (the Jacobian there is used if the step is accepted), so a step that needs no damping
    costs no extra evaluation; only a rejected full step costs residual evaluations (and
    the Jacobian computed at the rejected point). When quadratic convergence predicts
    that the full step lands within the tolerance, its residual is checked first, without
    a Jacobian.

    Parameters
    ----------
    kernel : Kernel
        The residual and its Newton step.
    w0, p : ndarray
        Start and parameters (scaled).
    tol : float
        Tolerance on the largest absolute residual (scaled).
    max_iter : int
        Most Newton steps.
    lb, ub : ndarray, optional
        Bounds kept by every step (99 % of the way to a bound at most).
    step_tol : float
        A step shorter than this (max norm) ends the iteration as converged (CasADi
        ``rootfinder``'s ``abstolStep``); the caller checks the residual.
    kappa : float
        The quadratic-convergence constant (max|G| after a full step over the step's max
        norm squared) of a previous solve of a nearby system (:attr:`NewtonResult.kappa`),
        so that the first step too can end with a residual check alone; nan: unknown.
    remesh, unmesh : callable, optional
        A moving mesh (:mod:`cable_ocp.statics.kinks`): before a full step whose predicted
        residual is at most :data:`REMESH_RESIDUAL`, ``remesh(trial)`` may move the trial
        point onto another mesh and return it with that mesh's parameters (None: keep
        the mesh). The moved point is accepted while its residual is at most
        :data:`REMESH_ACCEPT` or the residual before the step (its Jacobian is the one
        evaluated there anyway); else ``unmesh()`` restores the mesh and the step is taken
        on the old one. Tried once per call; the result's ``p`` holds the parameters of
        the mesh it ends on.

    Returns
    -------
    NewtonResult
        ``iterations`` counts the accepted Newton steps (one Jacobian and one sparse
        factorisation each).
    """
    w = np.array(w0, dtype=float)
    if lb is not None or ub is not None:
        w = np.clip(w, lb if lb is not None else -np.inf, ub if ub is not None else np.inf)
    g, dw = kernel.step(w, p)
    steps, moves, accepted = 0, 0, 0
    p0 = p
    # kappa = |g_{k+1}| / |dw_k|^2: the quadratic-convergence constant

    def result(ok: bool, message: str) -> NewtonResult:
        return NewtonResult(w, g, steps, ok, message, kappa=kappa,
                            p=p if p is not p0 else None, remeshes=accepted)

    while True:
        gmax = float(np.max(np.abs(g))) if g.size else 0.0
        if not math.isfinite(gmax):
            return result(False, "non-finite residual")
        if gmax <= tol:
            return result(True, "converged")
        if steps >= max_iter:
            return result(False, f"no convergence in {max_iter} steps")
        if dw is None:
            g, dw = kernel.step(w, p)
            continue
        if not np.all(np.isfinite(dw)):
            return result(False, "singular Jacobian (non-finite step)")
        alpha = _max_step(w, dw, lb, ub)
        dnorm = float(np.max(np.abs(dw))) if dw.size else 0.0
        trial = w + alpha * dw
        predicted = kappa * dnorm**2 if alpha == 1.0 and math.isfinite(kappa) else math.inf
        moved = None
        if remesh is not None and moves == 0 and predicted <= REMESH_RESIDUAL:
            moves += 1
            moved = remesh(trial)
        if moved is not None:
            g_new, dw_new = kernel.step(moved[0], moved[1])
            new_max = float(np.max(np.abs(g_new))) if g_new.size else 0.0
            if math.isfinite(new_max) and new_max <= max(REMESH_ACCEPT, gmax) \
                    and np.all(np.isfinite(dw_new)):
                trial, p = moved
                accepted += 1
                w, g, dw = trial, g_new, dw_new
                steps += 1
                continue
            if unmesh is not None:  # back to the old mesh, and the step taken there
                unmesh()
            g_new, dw_new = kernel.step(trial, p)
        elif predicted <= 10.0 * tol:
            g_new, dw_new = kernel.g(trial, p), None  # probably converged: no Jacobian
        else:
            g_new, dw_new = kernel.step(trial, p)
        while not _decrease(g_new, gmax, alpha):
            alpha *= 0.5
            if alpha * dnorm <= step_tol or alpha < 2.0**-60:
                return result(False, "line search failed (no decrease of the residual)")
            trial = w + alpha * dw
            g_new, dw_new = kernel.g(trial, p), None
        new_max = float(np.max(np.abs(g_new))) if g_new.size else 0.0
        if alpha == 1.0 and dnorm > 0.0 and moved is None:
            kappa = new_max / dnorm**2
        w, g, dw = trial, g_new, dw_new
        steps += 1
        if alpha * dnorm <= step_tol and new_max > tol:
            return result(True, "step below tolerance")


#: a chord step is accepted when it cuts max|G| to this fraction or less; else the
#: Jacobian is evaluated and factorised again. On the De Zoysa sweep (40 intervals, the
#: kept sparse LU: a factorisation with its Jacobian costs about three chord steps)
#: 0.01-0.5 took the same time within the noise of a shared machine (0.1: on average 1.4
#: factorisations and 5.8 steps per warm point; 0.01: 2.3 and 4.0; 0.5: 1.1 and 7.6)
CHORD_CONTRACTION = 0.1


def chord_newton(kernel: Kernel, w0: np.ndarray, p: np.ndarray, tol: float,
                 max_iter: int = 30, lb: np.ndarray | None = None,
                 ub: np.ndarray | None = None, contraction: float | None = None
                 ) -> NewtonResult:
    """Simplified (chord) Newton from a warm start: the Jacobian is factorised at ``w0``
    and the factors are reused, each further step costing one residual and one
    back-substitution: ``w <- w - J(w_f)^-1 G(w)``, with w_f the point of the last
    factorisation (Kelley (2003), *Solving Nonlinear Equations with Newton's Method*,
    section 1.8; Shamanskii's method).

    A step that cuts max|G| to ``contraction`` of its value or less is accepted. A step
    that decreases it less is accepted and the Jacobian is factorised again at the new
    point; a step that does not decrease it is rejected and the Jacobian is factorised
    again at the current point. A step from a fresh factorisation (a Newton step) that
    does not decrease max|G| is shortened as in :func:`newton`'s line search (halved until
    max|G| falls to (1 - alpha/2) of its value; residual evaluations only). A failed line
    search, a step that would cross a bound, a non-finite residual or step, or
    ``max_iter`` steps end the iteration unsuccessfully at the best point reached (the
    caller then runs :func:`newton` from there). The answer is
    accepted on the same test as :func:`newton`'s: max|G| <= ``tol``.

    Parameters
    ----------
    kernel : Kernel
        A kernel that keeps its factorisation (:attr:`Kernel.can_chord`; else ValueError).
    w0 : numpy.ndarray, shape (n_w,)
        Warm start (scaled), clipped to [lb, ub]; the first factorisation is made there.
    p : numpy.ndarray, shape (n_p,)
        Parameters (scaled).
    tol : float
        Tolerance on the largest absolute residual (scaled).
    max_iter : int, default 30
        Most steps (linear solves, chord or Newton).
    lb, ub : numpy.ndarray, optional
        Bounds on w: a full step that would go more than 99 % of the way to a finite
        bound (:func:`newton`'s step limit) ends the iteration; None or all infinite: no
        bound.
    contraction : float, optional
        Fraction (-) to which a chord step must cut max|G| to be accepted without a new
        factorisation; default :data:`CHORD_CONTRACTION`.

    Returns
    -------
    NewtonResult
        ``iterations`` counts the steps (linear solves), ``factorizations`` the
        Jacobians evaluated and factorised.
    """
    if not kernel.can_chord:
        raise ValueError("chord_newton needs a kernel that keeps its factorisation")
    contraction = CHORD_CONTRACTION if contraction is None else contraction
    w = np.array(w0, dtype=float)
    if lb is not None or ub is not None:
        w = np.clip(w, lb if lb is not None else -np.inf, ub if ub is not None else np.inf)
    # bounds that can be crossed (the others cost nothing per step)
    lb = lb if lb is not None and np.any(np.isfinite(lb)) else None
    ub = ub if ub is not None and np.any(np.isfinite(ub)) else None
    bounded = lb is not None or ub is not None
    g = kernel.factor(w, p)
    factors, steps, fresh = 1, 0, True
    gmax = float(np.max(np.abs(g))) if g.size else 0.0
    while True:
        if not math.isfinite(gmax):
            return NewtonResult(w, g, steps, False, "non-finite residual", factors)
        if gmax <= tol:
            return NewtonResult(w, g, steps, True, "converged", factors)
        if steps >= max_iter:
            return NewtonResult(w, g, steps, False, f"no convergence in {max_iter} steps",
                                factors)
        dw = kernel.chord_step(g)
        steps += 1
        if not math.isfinite(float(np.max(np.abs(dw))) if dw.size else 0.0):
            return NewtonResult(w, g, steps, False, "singular Jacobian (non-finite step)",
                                factors)
        if bounded and _max_step(w, dw, lb, ub) < 1.0:
            return NewtonResult(w, g, steps, False, "chord step crosses a bound", factors)
        trial = w + dw
        g_new = kernel.g(trial, p)
        new_max = float(np.max(np.abs(g_new))) if g_new.size else 0.0
        if math.isfinite(new_max) and new_max <= contraction * gmax:
            w, g, gmax, fresh = trial, g_new, new_max, False
            continue
        if math.isfinite(new_max) and new_max < gmax:
            w = trial  # a decrease, too slow: a new Jacobian at the new point
        elif fresh:
            # a Newton step that does not decrease max|G|: backtrack along it (the line
            # search of :func:`newton`, each trial a residual only)
            alpha = 0.5
            while True:
                trial = w + alpha * dw
                if _decrease(kernel.g(trial, p), gmax, alpha):
                    w = trial
                    break
                alpha *= 0.5
                if alpha < 2.0**-20:
                    return NewtonResult(w, g, steps, False,
                                        "line search failed from a fresh Jacobian", factors)
        g = kernel.factor(w, p)
        gmax = float(np.max(np.abs(g))) if g.size else 0.0
        factors += 1
        fresh = True
