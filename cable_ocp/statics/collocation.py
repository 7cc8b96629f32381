"""Direct collocation of the static cable BVP on sigma = s/L in [0, 1].

The mesh has N uniform intervals; in each, the state is a Lagrange polynomial of degree d
through the interval start and d collocation points (Gauss-Legendre or Gauss-Radau,
``casadi.collocation_points``). Unknowns, in order::

    w = [x_0, x_0^1 .. x_0^d, x_1, x_1^1 .. x_{N-1}^d, x_N, (lam if the length is free)]

Equations: the ODE at every collocation point, continuity of the polynomial at every
interval end, 6 end conditions and, when the length is free, the end tension. The system
is square, so a warm start converges in a few Newton steps.

Accuracy at the mesh points: order 2d for Gauss-Legendre and 2d - 1 for Radau, for
smooth solutions (the |u|u drag kink where a flow component changes sign lowers it;
CONVENTIONS "Reading the seeds").
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from cable_ocp.statics.formulation import (
    NX,
    P_CURRENT,
    P_END_A,
    P_END_B,
    P_LENGTH,
    P_TENSION,
    Formulation,
)


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

    @property
    def n_nodes(self) -> int:
        """Number of state nodes (interval starts, collocation points, final point)."""
        return self.intervals * (self.degree + 1) + 1

    def sigma(self) -> np.ndarray:
        """sigma of every state node, in unknown order (not sorted for Radau: the last
        collocation point of an interval coincides with the next interval start)."""
        h = 1.0 / self.intervals
        out = []
        for k in range(self.intervals):
            out.append(k * h)
            out.extend(k * h + h * t for t in self.tau)
        out.append(1.0)
        return np.asarray(out)

    def mesh_index(self) -> np.ndarray:
        """Indices of the mesh points (interval ends) among the state nodes."""
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
        self.mesh = Mesh(intervals, degree, scheme, tuple(float(t) for t in tau))
        self._setup(grounded)
        self.residual = self._build()

    def _setup(self, grounded: bool) -> None:
        """Unknown layout: node states, then lam (free length), then g (grounded)."""
        self.free_length = self.form.scene.free_length
        self.grounded = grounded
        self.n_x = self.mesh.n_nodes * NX
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
        n, d = self.mesh.intervals, self.mesh.degree
        cmat, dvec = _lagrange_matrices(list(self.mesh.tau))
        h = 1.0 / n
        w = ca.MX.sym("w", self.n_w)
        p = ca.MX.sym("p", len(self.form.params()))
        lam, g_len = self._lengths(w, p)
        xs = ca.reshape(w[: self.n_x], NX, self.mesh.n_nodes)
        # interval blocks: columns k*(d+1) .. k*(d+1)+d
        blocks = ca.reshape(xs[:, : n * (d + 1)], NX * (d + 1), n)  # one column per interval
        xk = ca.MX.sym("xk", NX * (d + 1))
        lam_s = ca.MX.sym("lam")
        cs_s = ca.MX.sym("cs")
        xcols = ca.reshape(xk, NX, d + 1)
        fx = self.form.rhs.map(d)(xcols[:, 1:], lam_s, cs_s)  # 6 x d
        coll = []
        for j in range(1, d + 1):
            xp = ca.mtimes(xcols, ca.DM(cmat[:, j]))
            # in derivative units (divided by h), so that one residual tolerance means the
            # same accuracy on every mesh
            coll.append(fx[:, j - 1] - xp / h)
        x_end = ca.mtimes(xcols, ca.DM(dvec))
        interval = ca.Function("interval", [xk, lam_s, cs_s], [ca.vertcat(*coll), x_end]).expand()
        coll_all, xend_all = interval.map(n)(blocks, lam, p[P_CURRENT])
        starts = ca.horzcat(*[xs[:, (k + 1) * (d + 1)] for k in range(n)])
        cont = ca.vec(xend_all - starts)
        bc = self._boundary(xs[:, 0], xs[:, -1], g_len, p)
        gexpr = ca.vertcat(ca.vec(coll_all), cont, *bc)
        return ca.Function("G", [w, p], [gexpr], ["w", "p"], ["g"])

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
        k = np.clip(np.floor(sigma * n).astype(int), 0, n - 1)
        tau = sigma * n - k
        out = np.zeros((sigma.size, values.shape[1]))
        for j in range(d + 1):
            basis = np.ones_like(tau)
            for r in range(d + 1):
                if r != j:
                    basis *= (tau - pts[r]) / (pts[j] - pts[r])
            out += basis[:, None] * values[k * (d + 1) + j]
        return out

    # -- packing ------------------------------------------------------------------------
    def pack(self, r: np.ndarray, tension: np.ndarray, length: float,
             grounded_length: float = 0.0) -> np.ndarray:
        """Scaled unknowns from the suspended part's node arrays r (n, 3) [m], T (n, 3) [N],
        the total unstretched length L [m] and the grounded length g [m]."""
        sc = self.form.scales
        x = np.hstack([r / sc.length, tension / sc.force]).reshape(-1)
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
        xs = w[: self.n_x].reshape(self.mesh.n_nodes, NX)
        g = float(w[self.i_g]) if self.grounded else 0.0
        length = w[self.i_lam] + g if self.free_length else p[P_LENGTH]
        return (xs[:, :3] * sc.length, xs[:, 3:] * sc.force, float(length * sc.length),
                g * sc.length)
