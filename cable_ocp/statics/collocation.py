"""Direct collocation of the static cable BVP on sigma = s/L in [0, 1].

The mesh has N uniform intervals; in each, the state is a Lagrange polynomial of degree d
through the interval start and d collocation points (Gauss-Legendre or Gauss-Radau,
``casadi.collocation_points``). Unknowns, in order::

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
smooth solutions (the |u|u drag kink where a flow component changes sign lowers it;
CONVENTIONS "Reading the seeds").
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import casadi as ca
import numpy as np

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


def segment_intervals(scene: Scene, intervals: int) -> tuple[int, ...]:
    """Intervals per segment of a multi-segment line on a mesh of ``intervals`` in all.

    On ``scene.solver.intervals`` (the base mesh) each segment gets its own
    ``intervals`` key, else a share of ``solver.intervals`` proportional to its length,
    at least 2. Other meshes scale the base mesh by ``intervals / solver.intervals``
    (halving and doubling give nested meshes), at least 1 per segment.
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


def _lagrange_matrices(tau: list[float]) -> tuple[np.ndarray, np.ndarray]:
    """Derivative matrix C (C[j, r] = dl_j/dtau at tau_r) and end weights D."""
    pts = [0.0, *tau]
    d = len(tau)
    cmat = np.zeros((d + 1, d + 1))
    dvec = np.zeros(d + 1)
    for j in range(d + 1):
        coeff = np.poly1d([1.0])
        for r in range(d + 1):
            if r != j:
                coeff *= np.poly1d([1.0, -pts[r]]) / (pts[j] - pts[r])
        dvec[j] = coeff(1.0)
        der = np.polyder(coeff)
        for r in range(d + 1):
            cmat[j, r] = der(pts[r])
    return cmat, dvec


@dataclass(frozen=True)
class Mesh:
    """Node locations of a collocation mesh on sigma in [0, 1]."""

    intervals: int
    degree: int
    scheme: str
    tau: tuple[float, ...]
    #: per-segment numbers of intervals of a multi-segment line (empty: one cable)
    segments: tuple[int, ...] = ()
    #: sigma at the segment ends, 0 = b_0 < b_1 < ... < b_n = 1 (empty: one cable)
    bounds: tuple[float, ...] = ()

    @property
    def n_nodes(self) -> int:
        """Number of state nodes (interval starts, collocation points, final point)."""
        if self.segments:
            return sum(n * (self.degree + 1) + 1 for n in self.segments)
        return self.intervals * (self.degree + 1) + 1

    def segment_offsets(self) -> list[int]:
        """Index of the first node of every segment, and the total number of nodes."""
        out = [0]
        for n in self.segments or (self.intervals,):
            out.append(out[-1] + n * (self.degree + 1) + 1)
        return out

    def sigma(self) -> np.ndarray:
        """sigma of every state node, in unknown order (not sorted for Radau: the last
        collocation point of an interval coincides with the next interval start; a joint
        between segments appears twice)."""
        if self.segments:
            parts = []
            for k, n in enumerate(self.segments):
                lo, hi = self.bounds[k], self.bounds[k + 1]
                local = replace(self, intervals=n, segments=(), bounds=()).sigma()
                parts.append(lo + (hi - lo) * local)
            return np.concatenate(parts)
        h = 1.0 / self.intervals
        out = []
        for k in range(self.intervals):
            out.append(k * h)
            out.extend(k * h + h * t for t in self.tau)
        out.append(1.0)
        return np.asarray(out)

    def mesh_index(self) -> np.ndarray:
        """Indices of the mesh points (interval ends) among the state nodes."""
        if self.segments:
            offs = self.segment_offsets()
            return np.concatenate([offs[k] + np.arange(n + 1) * (self.degree + 1)
                                   for k, n in enumerate(self.segments)])
        return np.arange(self.intervals + 1) * (self.degree + 1)

    @property
    def order(self) -> int:
        """Nominal convergence order at the mesh points."""
        return 2 * self.degree if self.scheme == "legendre" else 2 * self.degree - 1


class Collocation:
    """Residual function G(w, p) of the collocated BVP for one formulation and mesh.

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
        tau = ca.collocation_points(degree, scheme)
        segs: tuple[int, ...] = ()
        bounds: tuple[float, ...] = ()
        if form.segmented:
            segs = segment_intervals(form.scene, intervals)
            bounds = tuple(float(b) for b in np.concatenate([[0.0], np.cumsum(form.fractions)]))
            bounds = (*bounds[:-1], 1.0)
        self.mesh = Mesh(intervals, degree, scheme, tuple(float(t) for t in tau), segs, bounds)
        self._setup(grounded)
        self.residual = self._build()

    def _setup(self, grounded: bool) -> None:
        """Unknown layout: node states, then lam (free length), then g (grounded)."""
        self.free_length = self.form.scene.free_length
        self.grounded = grounded
        self.nx = self.form.nx
        self.n_x = self.mesh.n_nodes * self.nx
        self.i_lam = self.n_x if self.free_length else None
        self.i_g = self.n_x + (1 if self.free_length else 0) if grounded else None
        self.n_w = self.n_x + (1 if self.free_length else 0) + (1 if grounded else 0)

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
        if self.mesh.segments:
            return self._build_segmented()
        n, d = self.mesh.intervals, self.mesh.degree
        w = ca.MX.sym("w", self.n_w)
        p = ca.MX.sym("p", len(self.form.params()))
        lam, g_len = self._lengths(w, p)
        xs = ca.reshape(w[: self.n_x], self.nx, self.mesh.n_nodes)
        # interval blocks: columns k*(d+1) .. k*(d+1)+d, one column per interval
        blocks = ca.reshape(xs[:, : n * (d + 1)], self.nx * (d + 1), n)
        interval = self._interval_function(self.form.rhs, 1.0 / n)
        coll_all, xend_all = interval.map(n)(blocks, lam, p[P_CURRENT])
        starts = ca.horzcat(*[xs[:, (k + 1) * (d + 1)] for k in range(n)])
        cont = ca.vec(xend_all - starts)
        bc = self._boundary(xs[:, 0], xs[:, -1], g_len, p)
        gexpr = ca.vertcat(ca.vec(coll_all), cont, *bc)
        return ca.Function("G", [w, p], [gexpr], ["w", "p"], ["g"])

    def _interval_function(self, rhs: ca.Function, h: float) -> ca.Function:
        """Collocation residuals and end state of one interval of width h (sigma).

        The residuals are in derivative units (divided by h), so that one residual
        tolerance means the same accuracy on every mesh."""
        d, nx = self.mesh.degree, self.nx
        cmat, dvec = _lagrange_matrices(list(self.mesh.tau))
        xk = ca.MX.sym("xk", nx * (d + 1))
        lam_s = ca.MX.sym("lam")
        cs_s = ca.MX.sym("cs")
        xcols = ca.reshape(xk, nx, d + 1)
        fx = rhs.map(d)(xcols[:, 1:], lam_s, cs_s)
        coll = [fx[:, j - 1] - ca.mtimes(xcols, ca.DM(cmat[:, j])) / h for j in range(1, d + 1)]
        x_end = ca.mtimes(xcols, ca.DM(dvec))
        return ca.Function("interval", [xk, lam_s, cs_s], [ca.vertcat(*coll), x_end]).expand()

    def _build_segmented(self) -> ca.Function:
        """Residual of a multi-segment line: per segment, collocation on its own share of
        sigma (local variable in [0, 1], scaled length lam_k = L_k / ell, minus the
        grounded length on the first); joint conditions between segments."""
        d, form, nx = self.mesh.degree, self.form, self.nx
        w = ca.MX.sym("w", self.n_w)
        p = ca.MX.sym("p", len(form.params()))
        g_len = w[self.i_g] if self.grounded else 0.0
        xs = ca.reshape(w[: self.n_x], nx, self.mesh.n_nodes)
        offs = self.mesh.segment_offsets()
        res, joints = [], []
        for k, n in enumerate(self.mesh.segments):
            lam = p[P_LENGTH] * form.fractions[k] - (g_len if k == 0 else 0.0)
            seg = xs[:, offs[k]: offs[k + 1]]
            blocks = ca.reshape(seg[:, : n * (d + 1)], nx * (d + 1), n)
            interval = self._interval_function(form.rhs_list[k], 1.0 / n)
            coll_all, xend_all = interval.map(n)(blocks, lam, p[P_CURRENT])
            starts = ca.horzcat(*[seg[:, (i + 1) * (d + 1)] for i in range(n)])
            res += [ca.vec(coll_all), ca.vec(xend_all - starts)]
            x_prev = xs[:, offs[k] - 1] if k > 0 else None
            if k > 0:
                x_end, x_start = x_prev, xs[:, offs[k]]
                load = form.joint_loads[k - 1](x_end[0:NX], p[P_CURRENT])
                joints += [x_start[0:3] - x_end[0:3], x_start[3:6] - (x_end[3:6] - load)]
            joints += form.bending_joint_residual(k, x_prev, xs[:, offs[k]],
                                                  xs[:, offs[k + 1] - 1])
        bc = self._boundary(xs[:, 0], xs[:, -1], g_len, p)
        gexpr = ca.vertcat(*res, *joints, *bc)
        return ca.Function("G", [w, p], [gexpr], ["w", "p"], ["g"])

    # -- arc length -----------------------------------------------------------------------
    def _segment_s(self, length: float, g: float) -> list[tuple[float, float]]:
        """Unstretched arc length (m) at the start and end of every collocated segment."""
        if not self.mesh.segments:
            return [(g, length)]
        lens = [c.length for c in self.form.lines]
        cum = np.concatenate([[0.0], np.cumsum(lens)])
        return [(g if k == 0 else float(cum[k]), float(cum[k + 1])) for k in range(len(lens))]

    def node_s(self, length: float, g: float = 0.0) -> np.ndarray:
        """Unstretched arc length of every state node, m (total length L, grounded g)."""
        sig = self.mesh.sigma()
        if not self.mesh.segments:
            return g + sig * (length - g)
        offs = self.mesh.segment_offsets()
        out = np.empty_like(sig)
        for k, (s0, s1) in enumerate(self._segment_s(length, g)):
            b0, b1 = self.mesh.bounds[k], self.mesh.bounds[k + 1]
            out[offs[k]: offs[k + 1]] = s0 + (sig[offs[k]: offs[k + 1]] - b0) / (b1 - b0) \
                * (s1 - s0)
        return out

    def sigma_of_s(self, s: np.ndarray, length: float, g: float = 0.0) -> np.ndarray:
        """sigma (mesh coordinate) of arc lengths s (m), the inverse of :meth:`node_s`."""
        s = np.asarray(s, dtype=float)
        if not self.mesh.segments:
            return (s - g) / (length - g)
        ss = self._segment_s(length, g)
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
        twice: the end of the segment before, the start of the segment after)."""
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
    def interpolate(self, values: np.ndarray, sigma: np.ndarray) -> np.ndarray:
        """Evaluate the collocation polynomials of node values (n_nodes, k) at ``sigma``.

        Each interval's polynomial passes through its start and its d collocation points
        (the polynomial the collocation equations define), so this is the solution itself
        between the nodes, not a re-interpolation.
        """
        n, d = self.mesh.intervals, self.mesh.degree
        pts = np.array([0.0, *self.mesh.tau])
        sigma = np.asarray(sigma, dtype=float)
        if self.mesh.segments:
            b = np.asarray(self.mesh.bounds)
            seg = np.clip(np.searchsorted(b, sigma, side="right") - 1, 0, len(b) - 2)
            nk = np.asarray(self.mesh.segments)[seg]
            local = (sigma - b[seg]) / (b[seg + 1] - b[seg])
            k = np.clip(np.floor(local * nk).astype(int), 0, nk - 1)
            tau = local * nk - k
            base = np.asarray(self.mesh.segment_offsets())[seg] + k * (d + 1)
        else:
            k = np.clip(np.floor(sigma * n).astype(int), 0, n - 1)
            tau = sigma * n - k
            base = k * (d + 1)
        out = np.zeros((sigma.size, values.shape[1]))
        for j in range(d + 1):  # Lagrange basis through the interval start and tau_1..tau_d
            basis = np.ones_like(tau)
            for r in range(d + 1):
                if r != j:
                    basis *= (tau - pts[r]) / (pts[j] - pts[r])
            out += basis[:, None] * values[base + j]
        return out

    # -- packing ------------------------------------------------------------------------
    def pack(self, r: np.ndarray, tension: np.ndarray, length: float,
             grounded_length: float = 0.0, bending: np.ndarray | None = None) -> np.ndarray:
        """Scaled unknowns from the suspended part's node arrays r (n, 3) [m], T (n, 3) [N],
        the total unstretched length L [m] and the grounded length g [m]; with bending
        stiffness also (theta [rad], M [N m]) per node in ``bending`` (n, 2), by default
        theta along the chord of each stiff segment, M = 0 (dummies 0 elsewhere)."""
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
        and the grounded length g [m] from the unknowns."""
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
