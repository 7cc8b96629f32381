"""Direct collocation of the static cable BVP on sigma = s/L in [0, 1].

The mesh has N intervals (uniform, or with points on the drag's kinks); in each, the state
is a Lagrange polynomial of degree d through the interval start and d collocation points
(Gauss-Legendre or Gauss-Radau, :func:`cable_ocp.numerics.quadrature.collocation_points`).
Unknowns, in order::

    w = [x_0, x_0^1 .. x_0^d, x_1, x_1^1 .. x_{N-1}^d, x_N, (lam if the length is free)]

Equations: the ODE at every collocation point, continuity of the polynomial at every
interval end, 6 end conditions and, when the length is free, the end tension. The system
is square, so a warm start converges in a few Newton steps.

Multi-segment lines: each segment k is collocated on its own share of sigma (the
fraction L_k / L of the unstretched length) with its own N_k intervals and right-hand
side; the unknowns are the segments' node blocks in order (a joint appears twice, as the
end of one block and the start of the next), and the joint conditions (continuous
position, tension jump by the body load) replace the continuity across the joint.

Accuracy at the mesh points: order 2d for Gauss-Legendre and 2d - 1 for Radau, for
smooth solutions (the |u|u drag kink where a flow component changes sign lowers it,
unless a mesh point sits on it: :mod:`cable_ocp.statics.kinks`). The intervals need not
be uniform: each interval's width is a parameter of the residual (:meth:`Collocation.params`).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable

import casadi as ca
import numpy as np

from cable_ocp.numerics.quadrature import collocation_points
from cable_ocp.scene import Scene
from cable_ocp.statics.formulation import (
    NX,
    P_CURRENT,
    P_END_A,
    P_END_B,
    P_LENGTH,
    P_TENSION,
    Formulation,
)
from cable_ocp.statics.mesh import Mesh
from cable_ocp.statics.newton import Block, residual_function


def segment_intervals(scene: Scene, intervals: int) -> tuple[int, ...]:
    """Intervals per segment of a multi-segment line on a mesh of ``intervals`` in all.

    On ``scene.solver.intervals`` (the base mesh) each segment gets its own
    ``intervals`` key, else a share of ``solver.intervals`` proportional to its length,
    at least 2. Other meshes scale the base mesh by ``intervals / solver.intervals``
    (halving and doubling give nested meshes), at least 1 per segment.

    Parameters
    ----------
    scene : Scene
        A multi-segment scene: its ``segments`` (lengths, m), ``segment_intervals`` (the
        segments' own ``intervals`` keys, None where not given) and ``solver.intervals``.
    intervals : int
        Number of intervals of the whole mesh; equal to ``scene.solver.intervals`` for
        the base mesh.
    """
    lines = scene.segments
    total = sum(c.length for c in lines)  # type: ignore[misc]
    base_n = scene.solver.intervals
    base = [iv if iv is not None else max(2, round(base_n * c.length / total))
            for c, iv in zip(lines, scene.segment_intervals, strict=True)]
    if intervals == base_n:
        return tuple(base)
    factor = intervals / base_n
    return tuple(max(1, math.floor(b * factor + 0.5)) for b in base)


@functools.lru_cache(maxsize=32)
def _lagrange_matrices(tau: tuple[float, ...]) -> tuple[np.ndarray, np.ndarray]:
    """Derivative matrix C (C[j, r] = dl_j/dtau at tau_r) and end weights D of the Lagrange
    basis l_0 .. l_d through tau_0 = 0 and the d collocation points.

    Closed forms, no polynomial arithmetic: l_j(x) = prod_{m != j} (x - t_m) / (t_j - t_m),
    l_j'(t_r) = (1 / (t_j - t_r)) prod_{m != j, r} (t_r - t_m) / (t_j - t_m) for r != j,
    and l_j'(t_j) = sum_{m != j} 1 / (t_j - t_m). Cached: constants of the scheme."""
    pts = np.array([0.0, *tau])
    d = len(tau)
    cmat = np.zeros((d + 1, d + 1))
    dvec = np.zeros(d + 1)
    for j in range(d + 1):
        others = [m for m in range(d + 1) if m != j]
        dvec[j] = np.prod([(1.0 - pts[m]) / (pts[j] - pts[m]) for m in others])
        for r in range(d + 1):
            if r == j:
                cmat[j, r] = sum(1.0 / (pts[j] - pts[m]) for m in others)
            else:
                cmat[j, r] = np.prod([(pts[r] - pts[m]) / (pts[j] - pts[m])
                                      for m in others if m != r]) / (pts[j] - pts[r])
    cmat.setflags(write=False)
    dvec.setflags(write=False)
    return cmat, dvec


@functools.lru_cache(maxsize=32)
def _lagrange_denominators(tau: tuple[float, ...]) -> np.ndarray:
    """prod_{r != j} (t_j - t_r) of the Lagrange basis through 0 and the collocation
    points, j = 0 .. d (read-only)."""
    pts = [0.0, *tau]
    out = np.array([math.prod(pts[j] - pts[r] for r in range(len(pts)) if r != j)
                    for j in range(len(pts))])
    out.setflags(write=False)
    return out


class Collocation:
    """Residual function G(w, p) of the collocated BVP for one formulation and mesh.

    Parameters
    ----------
    form : Formulation
        The scene's scaled equations (right-hand sides, end conditions, parameters).
    intervals : int
        Number of intervals in all; a multi-segment line shares them out by
        :func:`segment_intervals`.
    degree : int
        Degree d of the collocation polynomial, 1..9 (d collocation points per interval).
    scheme : {"legendre", "radau"}
        Gauss-Legendre or right Gauss-Radau collocation points
        (:func:`cable_ocp.numerics.quadrature.collocation_points`).
    grounded : bool, default False
        Seabed contact at end_a: the unknowns end with the scaled grounded length g, the
        collocated part starts at the touchdown point, and end_a's conditions are those
        of :meth:`Formulation.touchdown_residual`.

    Attributes
    ----------
    residual : casadi.Function
        ``G(w, p) -> g``; the solution satisfies g = 0 (scaled units).
    n_w : int
        Number of unknowns (= number of equations).
    """

    def __init__(self, form: Formulation, intervals: int, degree: int, scheme: str,
                 grounded: bool = False):
        self.form = form
        tau = collocation_points(degree, scheme)
        segs: tuple[int, ...] = ()
        bounds: tuple[float, ...] = ()
        if form.segmented:
            segs = segment_intervals(form.scene, intervals)
            bounds = tuple(float(b) for b in np.concatenate([[0.0], np.cumsum(form.fractions)]))
            bounds = (*bounds[:-1], 1.0)
        self.mesh = Mesh(intervals, degree, scheme, tuple(float(t) for t in tau), segs, bounds)
        self._setup(grounded)

    # the residual and its block description are built on first use: a solver whose
    # functions come from the on-disk cache never builds them
    @property
    def residual(self) -> ca.Function:
        """``G(w, p) -> g``, the collocated equations (scaled)."""
        if self._residual is None:
            self._residual = self._build()
        return self._residual

    @residual.setter
    def residual(self, fn: ca.Function) -> None:
        self._residual = fn

    @property
    def blocks(self) -> list[Block]:
        """The residual as blocks (:mod:`cable_ocp.statics.newton`)."""
        if self._blocks is None:
            self._blocks = self._make_blocks()
        return self._blocks

    def _setup(self, grounded: bool) -> None:
        """Unknown layout: node states, then lam (free length), then g (grounded)."""
        self.free_length = self.form.scene.free_length
        self.grounded = grounded
        self.nx = self.form.nx
        self.n_x = self.mesh.n_nodes * self.nx
        self.i_lam = self.n_x if self.free_length else None
        self.i_g = self.n_x + (1 if self.free_length else 0) if grounded else None
        self.n_w = self.n_x + (1 if self.free_length else 0) + (1 if grounded else 0)
        #: size of the residual's parameter vector: the formulation's parameters, then
        #: the width of every interval (:meth:`params`)
        self.n_p = len(self.form.params()) + len(self.mesh_params())
        self._residual: ca.Function | None = None
        self._blocks: list[Block] | None = None
        self._block_fns: list[ca.Function] | None = None

    def mesh_params(self, mesh: Mesh | None = None) -> np.ndarray:
        """The mesh's part of the residual's parameters: the width of every interval in
        its segment's own coordinate (``mesh``: another mesh with the same numbers of
        intervals; default the current one)."""
        return (self.mesh if mesh is None else mesh).local_widths()

    def params(self, p_form: np.ndarray, mesh: Mesh | None = None) -> np.ndarray:
        """The residual's parameter vector: the formulation's parameters ``p_form``
        (:meth:`Formulation.params`) and the interval widths of ``mesh`` (default: the
        current mesh).

        Parameters
        ----------
        p_form : numpy.ndarray, shape (NP,)
            The formulation's scaled parameters (:meth:`Formulation.params`).
        mesh : Mesh, optional
            A mesh with the same numbers of intervals as the current one, whose interval
            widths (in each segment's own coordinate, -) to append; default the current
            mesh.
        """
        return np.concatenate([p_form, self.mesh_params(mesh)])

    def set_mesh(self, mesh: Mesh) -> None:
        """Use ``mesh`` (the same numbers of intervals, other interval ends) from now on:
        nothing is rebuilt, the widths are parameters (:meth:`params`)."""
        if mesh.uniform != self.mesh.uniform:
            raise ValueError("set_mesh: the mesh must keep the numbers of intervals")
        self.mesh = mesh

    def _lengths(self, w: ca.MX, p: ca.MX) -> tuple[ca.MX, ca.MX | float]:
        """Scaled length of the collocated (suspended) part and scaled grounded length."""
        g = w[self.i_g] if self.grounded else 0.0
        lam = w[self.i_lam] if self.free_length else p[P_LENGTH] - g
        return lam, g

    def _boundary(self, x0: ca.MX, xn: ca.MX, g: ca.MX | float, p: ca.MX) -> list[ca.MX]:
        """End conditions (both ends, the tension, the touchdown), scaled."""
        sc = self.form.scene
        if self.grounded:
            bc = self.form.touchdown_residual(x0, g, p[P_END_A])
        else:
            bc = self.form.end_residual(sc.end_a, x0, p[P_END_A], at_a=True)
        bc += self.form.end_residual(sc.end_b, xn, p[P_END_B], at_a=False)
        if self.free_length:
            x_t = x0 if sc.end_a.tension is not None else xn
            bc.append(self.form.tension_residual(x_t, p[P_TENSION]))
        return bc

    def _build(self) -> ca.Function:
        return residual_function(self.blocks, self.n_w, self.n_p)

    def _interval_block(self, rhs: ca.Function, fraction: float | None,
                        with_g: bool) -> tuple[ca.Function, ca.Function]:
        """One interval: ``(z, q) -> [collocation residuals; x_end - x_next]`` with
        z = [x_k, x_k^1 .. x_k^d, x_next, (lam | g)] and q = [p; h], h the interval's width
        in its segment's own coordinate (a parameter: one function serves every mesh),
        and ``(z, q) -> (r, dr/dz)``.

        The collocation residuals are in derivative units (divided by h), so that one
        residual tolerance means the same accuracy on every mesh. The scaled length of the
        interval's segment is lam = z[-1] (free length), else p[P_LENGTH] (times
        ``fraction`` on a multi-segment line) less the grounded length g = z[-1] when
        ``with_g``.

        The Jacobian by the chain rule: r is linear in the node states and in the
        right-hand side values f_j = f(x_k^j, lam), so dr/dz = (the constant part) +
        sum_j dr/df_j (df/d(x, lam) at x_k^j) d(x_k^j, lam)/dz, with df/d(x, lam) the
        right-hand side's own small Jacobian (cheaper to build than differentiating the
        whole interval)."""
        d, nx = self.mesh.degree, self.nx
        cmat, dvec = _lagrange_matrices(self.mesh.tau)
        has_tail = self.free_length or with_g
        n_z = nx * (d + 2) + (1 if has_tail else 0)
        n_p = len(self.form.params())
        z = ca.SX.sym("z", n_z)
        q = ca.SX.sym("q", n_p + 1)
        p, h = q[:n_p], q[n_p]
        xk = z[: nx * (d + 1)]
        x_next = z[nx * (d + 1): nx * (d + 2)]
        if self.free_length:
            lam, dlam = z[-1], 1.0
        else:
            lam = p[P_LENGTH] if fraction is None else p[P_LENGTH] * fraction
            dlam = 0.0
            if with_g:
                lam, dlam = lam - z[-1], -1.0
        xcols = ca.reshape(xk, nx, d + 1)
        # the right-hand side, and it with its Jacobian in (x, lam), at the collocation
        # points (inlined: called as SX call nodes instead, with never_inline, the
        # functions serialise in half the size but evaluate 5-20 % slower, which warm
        # solves pay at every step)
        xs_, lam_s, cs_s = ca.SX.sym("x", nx), ca.SX.sym("lam"), ca.SX.sym("cs")
        f_s = rhs(xs_, lam_s, cs_s)
        rhs_jac = ca.Function("rhs_jac", [xs_, lam_s, cs_s],
                              [f_s, ca.jacobian(f_s, ca.vertcat(xs_, lam_s))])
        inv_h = 1.0 / h
        # X C_j / h for j = 1 .. d as the columns of one (nx, d) matrix, and the end state
        lin = ca.mtimes(xcols, ca.DM(cmat[:, 1:].tolist())) * inv_h
        x_end = ca.mtimes(xcols, ca.DM(dvec.tolist()))
        fx, jx = [], []
        for j in range(1, d + 1):
            fj, jj = rhs_jac(xcols[:, j], lam, p[P_CURRENT])
            fx.append(fj)
            jx.append(jj)
        r = ca.vertcat(ca.vec(ca.horzcat(*fx) - lin), x_end - x_next)
        # the residual alone from the same expressions (a function keeps only the nodes
        # its outputs need: the Jacobians' are left out)
        fn = ca.Function("interval", [z, q], [r])
        # dr/dz: the constant part, -C[i, j]/h on the collocation rows (A/h), D_i and -1 on
        # the last rows (B), plus the right-hand side's Jacobians: block-diagonal in the
        # collocation points x_k^1 .. x_k^d (columns nx .. nx (d + 1) of z), and the tail
        nr, ncoll = nx * (d + 1), nx * d
        eye = np.arange(nx)
        a_rows = np.concatenate([(j - 1) * nx + eye for j in range(1, d + 1)
                                 for i in range(d + 1)])
        a_cols = np.concatenate([i * nx + eye for j in range(1, d + 1) for i in range(d + 1)])
        a_vals = np.concatenate([np.full(nx, -float(cmat[i, j])) for j in range(1, d + 1)
                                 for i in range(d + 1)])
        b_rows = np.concatenate([ncoll + eye] * (d + 2))
        b_cols = np.concatenate([i * nx + eye for i in range(d + 2)])
        b_vals = np.concatenate([np.full(nx, float(dvec[i])) for i in range(d + 1)]
                                + [np.full(nx, -1.0)])

        def sparse(rows: np.ndarray, cols: np.ndarray, vals: np.ndarray) -> ca.DM:
            order = np.lexsort((rows, cols))  # compressed-column order
            return ca.DM(ca.Sparsity.triplet(nr, n_z, rows.tolist(), cols.tolist()),
                         vals[order].tolist())

        blocks = ca.diagcat(*[jj[:, :nx] for jj in jx])
        tail = [ca.vertcat(*[jj[:, nx] for jj in jx]) * dlam] \
            if has_tail and dlam != 0.0 else [ca.SX(ncoll, 1)] if has_tail else []
        varying = ca.vertcat(ca.horzcat(ca.SX(ncoll, nx), blocks, ca.SX(ncoll, nx), *tail),
                             ca.SX(nx, n_z))
        jac = sparse(a_rows, a_cols, a_vals) * inv_h + sparse(b_rows, b_cols, b_vals) + varying
        jac_fn = ca.Function("interval_jac", [z, q], [r, jac])
        return fn, jac_fn

    def _interval_rows(self, n: int, coll0: int, cont0: int) -> np.ndarray:
        """Rows of G of the n intervals of one segment: collocation rows from ``coll0``,
        continuity rows from ``cont0`` (rows in the order of the unscaled build)."""
        d, nx = self.mesh.degree, self.nx
        k = np.arange(n)
        coll = coll0 + k[None, :] * nx * d + np.arange(nx * d)[:, None]
        cont = cont0 + k[None, :] * nx + np.arange(nx)[:, None]
        return np.vstack([coll, cont])

    def _interval_index(self, n: int, node0: int, tail: int | None) -> np.ndarray:
        """w indices of z of the n intervals of a segment whose first node is ``node0``."""
        d, nx = self.mesh.degree, self.nx
        k = np.arange(n)
        first = (node0 + k * (d + 1)) * nx  # first unknown of each interval block
        idx = first[None, :] + np.arange(nx * (d + 2))[:, None]
        if tail is not None:
            idx = np.vstack([idx, np.full((1, n), tail)])
        return idx

    def block_functions(self) -> list[ca.Function]:
        """The blocks' SX functions, ``[f_0, jac_0, f_1, jac_1, ...]`` in block order
        (what the on-disk cache stores: their size does not grow with the mesh)."""
        if self._block_fns is None:
            self._block_fns = [f for b in self.blocks for f in (b.fn, b.jac)]
        return self._block_fns

    def set_block_functions(self, fns: list[ca.Function]) -> bool:
        """Use stored block functions (from :meth:`block_functions` of a collocation of
        the same structure and mesh) instead of building them; False (and nothing
        changed) when they do not fit this layout."""
        try:
            blocks = self._make_blocks(fns)
        except (ValueError, IndexError, RuntimeError):
            return False
        self._blocks, self._block_fns = blocks, list(fns)
        return True

    def _make_blocks(self, fns: list[ca.Function] | None = None) -> list[Block]:
        """The residual as blocks: one mapped interval block per segment, the joints and
        the end conditions; rows in the order collocation, continuity (per segment),
        joints, end conditions. With ``fns`` (from :meth:`block_functions`), no function
        is built: the layout is checked against them."""
        d, nx, form = self.mesh.degree, self.nx, self.form
        n_p = len(form.params())
        tail = self.i_lam if self.free_length else self.i_g
        given = iter(fns) if fns is not None else None
        blocks: list[Block] = []

        # the parameters of each block: the formulation's (p[:n_p]); an interval also its
        # own width (p[n_p + its index], :meth:`params`)
        p_form = np.arange(n_p)[:, None]

        def add(make: Callable[[], tuple[ca.Function, ca.Function]], idx: np.ndarray,
                rows: Callable[[int], np.ndarray], p_idx: np.ndarray = p_form) -> int:
            if given is None:
                fn, jac = make()
            else:
                fn, jac = next(given), next(given)
                if fn.size1_in(0) != idx.shape[0] or fn.size1_in(1) != p_idx.shape[0] \
                        or jac.size1_out(0) != fn.size1_out(0) \
                        or jac.size_out(1) != (fn.size1_out(0), idx.shape[0]):
                    raise ValueError("stored block functions do not fit this layout")
            nr = fn.size1_out(0)
            blocks.append(Block(fn, idx, rows(nr), jac, p_idx))
            return nr

        segs = self.mesh.segments or (self.mesh.intervals,)
        offs = self.mesh.segment_offsets()
        row = 0
        first = 0  # index of the segment's first interval among all intervals
        for k, n in enumerate(segs):
            with_g = self.grounded and k == 0 and not self.free_length
            use_tail = tail if (self.free_length or with_g) else None

            def interval(k: int = k, with_g: bool = with_g
                         ) -> tuple[ca.Function, ca.Function]:
                rhs = form.rhs_list[k] if self.mesh.segments else form.rhs
                return self._interval_block(rhs, form.fractions[k]
                                            if self.mesh.segments else None, with_g)

            p_idx = np.vstack([np.repeat(p_form, n, axis=1),
                               n_p + first + np.arange(n)[None, :]])
            add(interval, self._interval_index(n, offs[k], use_tail),
                lambda nr, n=n, row=row: self._interval_rows(n, row, row + nx * d * n), p_idx)
            row += nx * (d + 1) * n
            first += n
        if self.mesh.segments:
            for k in range(len(segs)):
                if k == 0 and nx == NX:
                    continue  # no joint before the first segment, no bending conditions
                row += add(lambda k=k: self._joint_block(k, n_p), self._joint_index(k, offs),
                           lambda nr, row=row: (row + np.arange(nr))[:, None])
        idx = np.concatenate([np.arange(nx), self.n_x - nx + np.arange(nx)]
                             + ([[self.i_g]] if self.grounded else []))
        add(lambda: self._ends_block(n_p), idx[:, None],
            lambda nr, row=row: (row + np.arange(nr))[:, None])
        if given is not None and next(given, None) is not None:
            raise ValueError("more stored block functions than blocks")
        return blocks

    @staticmethod
    def _with_jacobian(name: str, zs: list[ca.SX], p: ca.SX, res: list[ca.SX]
                       ) -> tuple[ca.Function, ca.Function]:
        """``(z, p) -> r`` and ``(z, p) -> (r, dr/dz)`` for the residuals ``res`` of the
        symbols ``zs`` (stacked into z) and ``p`` (a small block: SX Jacobian)."""
        z, r = ca.vertcat(*zs), ca.vertcat(*res)
        return (ca.Function(name, [z, p], [r]),
                ca.Function(name + "_jac", [z, p], [r, ca.jacobian(r, z)]))

    def _ends_block(self, n_p: int) -> tuple[ca.Function, ca.Function]:
        """End conditions: ``(z, p) -> r`` with z = [x_0, x_N, (g)]."""
        nx = self.nx
        x0 = ca.SX.sym("x0", nx)
        xn = ca.SX.sym("xn", nx)
        gs = ca.SX.sym("g") if self.grounded else None
        p = ca.SX.sym("p", n_p)
        bc = self._boundary(x0, xn, gs if gs is not None else 0.0, p)
        zs = [x0, xn] + ([gs] if gs is not None else [])
        return self._with_jacobian("ends", zs, p, bc)

    def _joint_index(self, k: int, offs: list[int]) -> np.ndarray:
        """w indices of z of the joint block of segment k (see :meth:`_joint_block`)."""
        nx = self.nx
        idx = np.concatenate(([(offs[k] - 1) * nx + np.arange(nx)] if k > 0 else [])
                             + [offs[k] * nx + np.arange(nx), (offs[k + 1] - 1) * nx
                                + np.arange(nx)])
        return idx[:, None]

    def _joint_block(self, k: int, n_p: int) -> tuple[ca.Function, ca.Function]:
        """Joint conditions at the start of segment k (continuous position, tension jump by
        the body loads) and the bending conditions of segment k: ``(z, p) -> r`` with
        z = [last node of segment k-1 (k > 0), first and last node of segment k]."""
        nx, form = self.nx, self.form
        x_prev = ca.SX.sym("x_prev", nx) if k > 0 else None
        x_start = ca.SX.sym("x_start", nx)
        x_last = ca.SX.sym("x_last", nx)
        p = ca.SX.sym("p", n_p)
        res = []
        if k > 0:
            load = form.joint_loads[k - 1](x_prev[0:NX], p[P_CURRENT])
            res += [x_start[0:3] - x_prev[0:3], x_start[3:6] - (x_prev[3:6] - load)]
        res += form.bending_joint_residual(k, x_prev, x_start, x_last)
        zs = ([x_prev] if k > 0 else []) + [x_start, x_last]
        return self._with_jacobian(f"joint_{k}", zs, p, res)

    # -- arc length -----------------------------------------------------------------------
    def segment_s(self, length: float, g: float) -> list[tuple[float, float]]:
        """Unstretched arc length (m) at the start and end of every collocated segment.

        Parameters
        ----------
        length : float
            Total unstretched length, m.
        g : float
            Grounded length at end_a, m (the first segment starts there).
        """
        if not self.mesh.segments:
            return [(g, length)]
        lens = [c.length for c in self.form.lines]
        cum = np.concatenate([[0.0], np.cumsum(lens)])
        return [(g if k == 0 else float(cum[k]), float(cum[k + 1])) for k in range(len(lens))]

    def node_s(self, length: float, g: float = 0.0) -> np.ndarray:
        """Unstretched arc length of every state node, m (total length L, grounded g).

        Parameters
        ----------
        length : float
            Total unstretched length L, m.
        g : float, default 0.0
            Grounded length at end_a, m: the nodes cover the suspended part from s = g
            to s = L (on a multi-segment line the first segment starts there).

        Returns
        -------
        numpy.ndarray, shape (n_nodes,)
            s of every node in unknown order, m.
        """
        sig = self.mesh.sigma()
        if not self.mesh.segments:
            return g + sig * (length - g)
        offs = self.mesh.segment_offsets()
        out = np.empty_like(sig)
        for k, (s0, s1) in enumerate(self.segment_s(length, g)):
            b0, b1 = self.mesh.bounds[k], self.mesh.bounds[k + 1]
            out[offs[k]: offs[k + 1]] = s0 + (sig[offs[k]: offs[k + 1]] - b0) / (b1 - b0) \
                * (s1 - s0)
        return out

    def sigma_of_s(self, s: np.ndarray, length: float, g: float = 0.0) -> np.ndarray:
        """sigma (mesh coordinate) of arc lengths s (m), the inverse of :meth:`node_s`.

        Parameters
        ----------
        s : array_like
            Unstretched arc lengths from end_a, m (any shape; g <= s <= L).
        length : float
            Total unstretched length L, m.
        g : float, default 0.0
            Grounded length at end_a, m (sigma = 0 at s = g). On a multi-segment line a
            point at a joint maps to the end of the segment before it.
        """
        s = np.asarray(s, dtype=float)
        if not self.mesh.segments:
            return (s - g) / (length - g)
        ss = self.segment_s(length, g)
        ends = np.array([e for _, e in ss])
        k = np.clip(np.searchsorted(ends, s, side="left"), 0, len(ss) - 1)
        s0 = np.array([a for a, _ in ss])[k]
        s1 = ends[k]
        b = np.asarray(self.mesh.bounds)
        return b[k] + (s - s0) / (s1 - s0) * (b[k + 1] - b[k])

    def resample(self, s_src: np.ndarray, r_src: np.ndarray, t_src: np.ndarray,
                 length: float, g: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
        """Node arrays r (m), T (N) of a multi-segment line at this mesh's nodes from
        another solution's nodes (arc length s_src, m), segment by segment: the tension
        jumps at a joint, so each segment takes only its own nodes (at a joint listed
        twice: the end of the segment before, the start of the segment after).

        Parameters
        ----------
        s_src : numpy.ndarray, shape (n,)
            Unstretched arc length of the source nodes from end_a, m, increasing (a joint
            may appear twice).
        r_src : numpy.ndarray, shape (n, 3)
            Positions at the source nodes, m.
        t_src : numpy.ndarray, shape (n, 3)
            Tension vectors at the source nodes, N (any three-column node quantity is
            interpolated the same way, e.g. the bending angle and moment).
        length : float
            Total unstretched length L, m.
        g : float, default 0.0
            Grounded length at end_a, m (the target nodes start there).

        Returns
        -------
        r, t : numpy.ndarray, shape (n_nodes, 3)
            ``r_src`` and ``t_src`` linearly interpolated in s at this mesh's nodes.
        """
        tol = 1e-9 * max(length, 1.0)
        s_tgt = self.node_s(length, g)
        offs = self.mesh.segment_offsets()
        lens = [c.length for c in self.form.lines]
        cum = np.concatenate([[0.0], np.cumsum(lens)])
        r = np.empty((len(s_tgt), 3))
        t = np.empty((len(s_tgt), 3))
        for k in range(len(lens)):
            lo, hi = cum[k], cum[k + 1]
            idx = np.flatnonzero((s_src >= lo - tol) & (s_src <= hi + tol))
            at_lo = idx[np.abs(s_src[idx] - lo) <= tol]
            at_hi = idx[np.abs(s_src[idx] - hi) <= tol]
            drop = set(at_lo[:-1].tolist()) if k > 0 else set()
            if k < len(lens) - 1:
                drop |= set(at_hi[1:].tolist())
            idx = np.array([i for i in idx if i not in drop], dtype=int)
            tgt = s_tgt[offs[k]: offs[k + 1]]
            for arr, src in ((r, r_src), (t, t_src)):
                arr[offs[k]: offs[k + 1]] = np.stack(
                    [np.interp(tgt, s_src[idx], src[idx, c]) for c in range(3)], axis=1)
        return r, t

    # -- evaluation ---------------------------------------------------------------------
    def interpolate(self, values: np.ndarray, sigma: np.ndarray, mesh: Mesh | None = None,
                    segment: np.ndarray | None = None) -> np.ndarray:
        """Evaluate the collocation polynomials of node values (n_nodes, k) at ``sigma``.

        Each interval's polynomial passes through its start and its d collocation points
        (the polynomial the collocation equations define), so this is the solution itself
        between the nodes, not a re-interpolation. ``mesh``: the mesh of ``values``
        (default the current one); ``segment``: the segment of each point (a joint belongs
        to the segment after it unless given).

        Parameters
        ----------
        values : numpy.ndarray, shape (n_nodes, k)
            Values at the state nodes of ``mesh``, in unknown order (e.g. the scaled
            states).
        sigma : array_like, shape (m,)
            Points in the mesh coordinate sigma in [0, 1] (-).
        mesh : Mesh, optional
            The mesh of ``values``; default the current one.
        segment : array_like of int, shape (m,), optional
            The segment of each point (0 at end_a); default: found from ``sigma``.

        Returns
        -------
        numpy.ndarray, shape (m, k)
            The polynomials' values at ``sigma``.
        """
        mesh = self.mesh if mesh is None else mesh
        n, d = mesh.intervals, mesh.degree
        pts = np.array([0.0, *mesh.tau])
        sigma = np.asarray(sigma, dtype=float)
        if mesh.edges:
            edges = mesh.interval_edges()
            counts = np.asarray(mesh.segments or (n,))
            first = np.concatenate([[0], np.cumsum(counts)])
            i = np.searchsorted(edges, sigma, side="right") - 1
            if segment is not None:
                i = np.clip(i, first[segment], first[np.asarray(segment) + 1] - 1)
            i = np.clip(i, 0, first[-1] - 1)
            seg = np.searchsorted(first, i, side="right") - 1
            tau = (sigma - edges[i]) / (edges[i + 1] - edges[i])
            base = np.asarray(mesh.segment_offsets())[seg] + (i - first[seg]) * (d + 1)
        elif mesh.segments:
            b = np.asarray(mesh.bounds)
            seg = np.clip(np.searchsorted(b, sigma, side="right") - 1, 0, len(b) - 2)
            if segment is not None:
                seg = np.asarray(segment)
            nk = np.asarray(mesh.segments)[seg]
            local = (sigma - b[seg]) / (b[seg + 1] - b[seg])
            k = np.clip(np.floor(local * nk).astype(int), 0, nk - 1)
            tau = local * nk - k
            base = np.asarray(mesh.segment_offsets())[seg] + k * (d + 1)
        else:
            k = np.clip(np.floor(sigma * n).astype(int), 0, n - 1)
            tau = sigma * n - k
            base = k * (d + 1)
        # Lagrange basis through the interval start and tau_1..tau_d: l_j = prod_{r != j}
        # (tau - t_r) / (t_j - t_r), the products left and right of j by cumulative products
        diff = tau[:, None] - pts[None, :]
        ones = np.ones((tau.size, 1))
        left = np.hstack([ones, np.cumprod(diff[:, :-1], axis=1)])
        right = np.hstack([np.cumprod(diff[:, :0:-1], axis=1)[:, ::-1], ones])
        basis = left * right / _lagrange_denominators(mesh.tau)
        idx = base[:, None] + np.arange(d + 1)[None, :]
        return np.einsum("nj,njk->nk", basis, values[idx])

    def transfer(self, w: np.ndarray, source: Mesh, target: Mesh) -> np.ndarray:
        """Unknowns ``w`` on mesh ``source`` moved to mesh ``target`` (the same numbers of
        intervals): every node state from the source's collocation polynomials, segment by
        segment (a joint keeps the value of its own side); the length and the grounded
        length as they are.

        Parameters
        ----------
        w : numpy.ndarray, shape (n_w,)
            Scaled unknowns on ``source``.
        source : Mesh
            The mesh of ``w``.
        target : Mesh
            The mesh to move to, with the same numbers of intervals (other interval ends).
        """
        w = np.asarray(w, dtype=float)
        xs = w[: self.n_x].reshape(source.n_nodes, self.nx)
        offs = target.segment_offsets()
        seg = np.repeat(np.arange(len(offs) - 1), np.diff(offs))
        out = w.copy()
        out[: self.n_x] = self.interpolate(xs, target.sigma(), mesh=source,
                                           segment=seg).reshape(-1)
        return out

    # -- packing ------------------------------------------------------------------------
    def pack(self, r: np.ndarray, tension: np.ndarray, length: float,
             grounded_length: float = 0.0, bending: np.ndarray | None = None) -> np.ndarray:
        """Scaled unknowns from the suspended part's node arrays r (n, 3) [m], T (n, 3) [N],
        the total unstretched length L [m] and the grounded length g [m]; with bending
        stiffness also (theta [rad], M [N m]) per node in ``bending`` (n, 2), by default
        theta along the chord of each stiff segment, M = 0 (dummies 0 elsewhere).

        Parameters
        ----------
        r : numpy.ndarray, shape (n_nodes, 3)
            Positions of the suspended part's nodes, m, in unknown order.
        tension : numpy.ndarray, shape (n_nodes, 3)
            Tension vectors at those nodes, N.
        length : float
            Total unstretched length L, m (stored as the unknown lam = (L - g) / ell when
            the length is free; otherwise not used).
        grounded_length : float, default 0.0
            Grounded length g at end_a, m (stored as g / ell when ``grounded``).
        bending : numpy.ndarray, shape (n_nodes, 2), optional
            Per node the tangent angle theta (rad, from +x towards +z) and the bending
            moment M (N m); only read with bending stiffness. Default: theta along the
            chord of each stiff segment, M = 0.

        Returns
        -------
        numpy.ndarray, shape (n_w,)
            The scaled unknowns w.
        """
        sc = self.form.scales
        cols = [r / sc.length, tension / sc.force]
        if self.nx > NX:
            if bending is None:
                bending = np.zeros((len(r), 2))
                offs = self.mesh.segment_offsets()
                for k, st in enumerate(self.form.stiff):
                    if st:
                        chord = r[offs[k + 1] - 1] - r[offs[k]]
                        bending[offs[k]: offs[k + 1], 0] = np.arctan2(chord[2], chord[0])
            else:
                bending = np.array(bending, dtype=float)
            bending[:, 1] /= self.form.moment_scale
            cols.append(bending)
        x = np.hstack(cols).reshape(-1)
        if self.free_length:
            x = np.append(x, (length - grounded_length) / sc.length)
        if self.grounded:
            x = np.append(x, grounded_length / sc.length)
        return x

    def unpack(self, w: np.ndarray, p: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray, float, float]:
        """Suspended-part node arrays r (n, 3) [m], T (n, 3) [N], the total length L [m]
        and the grounded length g [m] from the unknowns.

        Parameters
        ----------
        w : numpy.ndarray, shape (n_w,)
            Scaled unknowns.
        p : numpy.ndarray
            The residual's scaled parameters (:meth:`params`, or the formulation's alone):
            the fixed length is read from ``p[P_LENGTH]`` (L / ell) when the length is not
            an unknown.
        """
        sc = self.form.scales
        w = np.asarray(w, dtype=float).reshape(-1)
        xs = w[: self.n_x].reshape(self.mesh.n_nodes, self.nx)
        g = float(w[self.i_g]) if self.grounded else 0.0
        length = w[self.i_lam] + g if self.free_length else p[P_LENGTH]
        return (xs[:, :3] * sc.length, xs[:, 3:6] * sc.force, float(length * sc.length),
                g * sc.length)

    def unpack_bending(self, w: np.ndarray) -> np.ndarray | None:
        """Per node (theta [rad], M [N m]) with bending stiffness (dummies on flexible
        segments), else None."""
        if self.nx == NX:
            return None
        xs = np.asarray(w, dtype=float).reshape(-1)[: self.n_x].reshape(self.mesh.n_nodes,
                                                                        self.nx)
        return np.stack([xs[:, 6], xs[:, 7] * self.form.moment_scale], axis=1)
