"""The elastic catenary: a uniform line between two ends, with point loads, in closed form.

One uniform line (unstretched length L, weight in water w per unstretched length, axial
stiffness EA, possibly infinite) between two ends, each end's components either fixed in
position or loaded by a given force, with point loads F^i at unstretched arc lengths s_i
and no drag. Huang (1992) (seed /work/shared/seeds/004_7da4a1ee8042db40.txt), ch. 2:

**Tension** (Huang 1992, (2.1)-(2.3), (2.24)), in Huang's frame with z **downwards**
(inside this module only: every input and output is in the project frame, z up, except
V, which is Huang's unknown)::

    T_vec(s) = -(V + sum_{s_i <= s} F^i + w s e_z),   T = |T_vec|

with V = (V_x, V_y, V_z) the force the support at s = 0 exerts on the cable.

**One piece** between consecutive loads (:func:`piece_increments`): Hooke's law (2.5) with
(2.18)-(2.23) integrates exactly over [s_n, s_{n+1}]. With a = V + sum F^i (constant on
the piece), h = sqrt(a_x^2 + a_y^2), A = a_z + w s_n, B = a_z + w s_{n+1},
T_A = sqrt(h^2 + A^2), T_B = sqrt(h^2 + B^2)::

    Delta x = -a_x [ (s_{n+1} - s_n)/EA + I ],  I = (1/w)[asinh(B/h) - asinh(A/h)]   (2.31)
    Delta y = -a_y [ (s_{n+1} - s_n)/EA + I ]                                        (2.32)
    Delta z = (A^2 - B^2)/(2 w EA) + (T_A - T_B)/w                                    (2.33)

(2.33) is garbled in the OCR of the thesis (docs/conventions.md): the relation above is
*derived here* by integrating (2.23) with (2.24), dz/ds = -X (1/EA + 1/T), X = a_z + w s,
and agrees with the legible parts of (2.33) (its first bracket is the 1/EA term; the
second is (L/W) times T(s_n) - T(s_{n+1})). Since T_A - T_B = -w (s_{n+1} - s_n)(A + B)/
(T_A + T_B), both terms are evaluated without dividing by w (so w = 0, a neutrally
buoyant cable, is regular), and I is evaluated through log1p in a cancellation-free
form that is also regular on a vertical piece (h = 0) and at w -> 0. EA = inf makes the
1/EA terms vanish (inextensible cable).

**The line** (:func:`solve_line`, Huang 1992, (2.34)-(2.45)): per component, an end
position fixed at both ends gives the equation sum Delta r_i = r_i(L) - r_i(0) (type 1,
(2.34)-(2.36)); a force given at end_b gives V_i directly from (2.40)-(2.42) (type 2; the
mooring case, type 3, is (2.43)-(2.44) for V_x, V_y and (2.45) for V_z); a force given at
end_a is V_i itself. The remaining components of V are found by Newton-Raphson (section
2.5) with the analytic Jacobian. The sum sum Delta r is minus the gradient of the convex
complementary energy Phi(V) = int (T + T^2 / (2 EA)) ds, so each Newton step is also
checked against the merit Phi + V . target (Armijo) and halved until it decreases it: a
safeguard the thesis does not have (it notes that Newton "only guarantees local
convergence", 2.7); a full step is always tried first. The result
(:class:`CatenaryShape`) is exact everywhere along the line, to the Newton tolerance.

**The inextensible catenary without loads** in its parametric closed form, for the cold
guesses of the collocation (:mod:`cable_ocp.statics.initial_guess`): the catenary
parameter a = H / w through two points at a given arc length
(:func:`catenary_parameter`, :func:`catenary_parameter_bracketed`), its vertex
(:func:`catenary_vertex`) and its nodes (:func:`catenary_nodes`), and the catenary with
touchdown on a horizontal seabed (:func:`touchdown_catenary`, :func:`vertex_nodes`)
(Irvine 1981, ch. 1; Huang 1992, (2.31)-(2.33) with EA = inf and no point loads).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from cable_ocp.scene import End

__all__ = ["FLIP", "CatenaryShape", "catenary_nodes", "catenary_parameter",
           "catenary_parameter_bracketed", "catenary_vertex", "piece_increments",
           "solve_line", "start_force", "touchdown_catenary", "vertex_nodes"]

#: project frame (z up) <-> Huang's frame (z down, Huang (1992) (2.3), (2.42)): flip z
FLIP = np.array([1.0, 1.0, -1.0])

#: most Newton steps on V
MAX_NEWTON = 50


# --------------------------------------------------------------------------------------
# One piece between point loads: (2.31)-(2.33), their Jacobian and the energy
# --------------------------------------------------------------------------------------

def _phi(e: np.ndarray) -> np.ndarray:
    """log1p(e) / e, with its limit 1 at e = 0 (e > -1)."""
    small = np.abs(e) < 1e-8
    es = np.where(small, 1.0, e)
    return np.where(small, 1.0 - 0.5 * e, np.log1p(es) / es)


def _plus(x: np.ndarray, t: np.ndarray, h2: np.ndarray) -> np.ndarray:
    """T + X without cancellation (= h^2 / (T - X) for X < 0)."""
    neg = x < 0
    return np.where(neg, h2 / np.where(neg, t - x, 1.0), t + x)


def _minus(x: np.ndarray, t: np.ndarray, h2: np.ndarray) -> np.ndarray:
    """T - X without cancellation (= h^2 / (T + X) for X > 0)."""
    pos = x > 0
    return np.where(pos, h2 / np.where(pos, t + x, 1.0), t - x)


def piece_increments(v: np.ndarray, s0: np.ndarray, ds: np.ndarray, cum: np.ndarray,
                     w: float, inv_ea: float, derivatives: bool = True
                     ) -> tuple[np.ndarray, np.ndarray | None, float]:
    """Exact increments of all pieces, Huang's frame (z down): (2.31)-(2.33).

    Parameters
    ----------
    v : ndarray, shape (3,)
        End force V on the cable at s = 0, N (Huang 1992, (2.1)-(2.3)).
    s0, ds : ndarray, shape (M,)
        Start and unstretched length of each piece, m.
    cum : ndarray, shape (M, 3)
        Sum of the point loads acting on the cable at or before each piece's start, N.
    w : float
        Weight in water per unstretched length, N/m (W/L of the thesis).
    inv_ea : float
        1/EA, 1/N (0 for an inextensible cable).
    derivatives : bool
        Also return the Jacobian d(sum Delta r)/dV.

    Returns
    -------
    dr : ndarray, shape (M, 3)
        (Delta x, Delta y, Delta z) of each piece, m: (2.31), (2.32) and the derived (2.33).
    jac : ndarray, shape (3, 3) or None
        d(sum_pieces Delta r)/dV, m/N (symmetric negative definite unless degenerate).
    energy : float
        Phi(V) = int (T + T^2/(2 EA)) ds, N m; grad Phi = -sum Delta r.
    """
    a = v[None, :] + cum
    ax, ay = a[:, 0], a[:, 1]
    h2 = ax * ax + ay * ay
    xa = a[:, 2] + w * s0
    xb = xa + w * ds
    ta = np.sqrt(h2 + xa * xa)
    tb = np.sqrt(h2 + xb * xb)
    ssum = ta + tb
    pa, pb = _plus(xa, ta, h2), _plus(xb, tb, h2)
    ma, mb = _minus(xa, ta, h2), _minus(xb, tb, h2)
    # I = int ds / T = (1/w)[asinh(B/h) - asinh(A/h)] = (1/w) ln((T_B + B)/(T_A + A))
    branch = xa + xb >= 0
    ep = w * ds * (pa + pb) / ssum / pa
    em = -w * ds * (ma + mb) / ssum / np.where(branch, 1.0, ma)
    integral = np.where(branch, ds * (pa + pb) / ssum / pa * _phi(np.where(branch, ep, 0.0)),
                        ds * (ma + mb) / ssum / np.where(branch, 1.0, ma)
                        * _phi(np.where(branch, 0.0, em)))
    # int X / T ds = (T_B - T_A)/w
    xt = ds * (xa + xb) / ssum
    lin = ds * inv_ea
    dr = np.empty_like(a)
    dr[:, 0] = -ax * (lin + integral)
    dr[:, 1] = -ay * (lin + integral)
    dr[:, 2] = -0.5 * (xa + xb) * lin - xt
    # energy: int T ds = 1/2 [ds M + h^2 I], M = (B T_B - A T_A)/(B - A)
    mean = 0.5 * (ssum + (xa + xb) ** 2 / ssum)
    energy = float(np.sum(0.5 * (ds * mean + h2 * integral)
                          + 0.5 * inv_ea * (h2 * ds + ds * (xa * xa + xa * xb + xb * xb) / 3.0)))
    if not derivatives:
        return dr, None, energy
    # int ds/T^3 and int X/T^3 ds
    k3 = 2.0 * ssum * ds / ((pa + mb) * (ma + pb) * ta * tb)
    n3 = ds * (xa + xb) / (ssum * ta * tb)
    jac = np.empty((3, 3))
    base = -(lin + integral)
    jac[0, 0] = np.sum(base + ax * ax * k3)
    jac[1, 1] = np.sum(base + ay * ay * k3)
    jac[0, 1] = jac[1, 0] = np.sum(ax * ay * k3)
    jac[0, 2] = jac[2, 0] = np.sum(ax * n3)
    jac[1, 2] = jac[2, 1] = np.sum(ay * n3)
    jac[2, 2] = np.sum(-lin - h2 * k3)
    return dr, jac, energy


# --------------------------------------------------------------------------------------
# The line under point loads: Newton on V (2.34)-(2.45)
# --------------------------------------------------------------------------------------

@dataclass
class CatenaryShape:
    """The exact shape of a line under point loads (:func:`solve_line`).

    Attributes
    ----------
    v : ndarray, shape (3,)
        V, the force the support at s = 0 exerts on the cable, N, in Huang's frame (z
        down): the unknown of (2.34)-(2.45).
    length : float
        Unstretched length, m.
    breaks : ndarray, shape (M + 1,)
        Piece boundaries (unstretched arc length from end_a, m): 0, the loads, the
        requested nodes, L.
    cum : ndarray, shape (M, 3)
        Loads acting on the cable before each piece, N, Huang's frame.
    jump_start, jump_end : ndarray, shape (3,)
        Loads applied at s = 0 and s = L, N, Huang's frame.
    start : ndarray, shape (3,)
        Position of end_a, m (given where fixed, else from end_b and the increments).
    dr : ndarray, shape (M, 3)
        Increments of each piece, m, Huang's frame.
    iterations : int
        Newton steps taken.
    residual : float
        Largest end-position mismatch of the Newton equations, relative to L.
    converged : bool
        Newton converged to the tolerance (or V was given directly by the forces).
    message : str
        How it ended.
    weight : float
        Weight in water per unstretched length, N/m.
    inv_ea : float
        1/EA, 1/N (0 for an inextensible line).
    end_a, end_b : End
        The end conditions solved for.
    """

    v: np.ndarray
    length: float
    breaks: np.ndarray
    cum: np.ndarray
    jump_start: np.ndarray
    jump_end: np.ndarray
    start: np.ndarray
    dr: np.ndarray
    iterations: int
    residual: float
    converged: bool
    message: str
    weight: float
    inv_ea: float
    end_a: End
    end_b: End

    def nodes(self) -> np.ndarray:
        """Positions of the piece boundaries, project frame, (M + 1, 3), m."""
        steps = self.dr * FLIP
        return self.start[None, :] + np.vstack([np.zeros(3), np.cumsum(steps, axis=0)])

    def tension_at_end(self, at_b: bool) -> np.ndarray:
        """Tension vector (N, project frame) at s = L (after any load there) or at s = 0
        (before any load there)."""
        if at_b:
            return -FLIP * (self.v + self.cum[-1] + self.jump_end
                            + self.weight * self.length * np.array([0.0, 0.0, 1.0]))
        return -FLIP * self.v

    @property
    def force_a(self) -> np.ndarray:
        """Force the cable exerts on the end_a attachment, N, project frame (+T(0))."""
        return self.tension_at_end(False)

    @property
    def force_b(self) -> np.ndarray:
        """Force the cable exerts on the end_b attachment, N, project frame (-T(L))."""
        return -self.tension_at_end(True)

    def profile(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Arc lengths s (m), positions (m) and tension vectors (N), project frame, at
        every piece's start and end: at a loaded point s appears twice, with the tension
        just before and just after the load (T jumps by -F there)."""
        br = self.breaks
        nodes = self.nodes()
        m = br.size - 1
        ez = np.array([0.0, 0.0, 1.0])
        w = self.weight
        s_list, r_list, t_list = [], [], []
        if np.any(self.jump_start):
            s_list.append(0.0)
            r_list.append(nodes[0])
            t_list.append(-FLIP * self.v)
        for j in range(m):
            a = self.v + self.cum[j]
            for k in (j, j + 1):
                s_list.append(br[k])
                r_list.append(nodes[k])
                t_list.append(-FLIP * (a + w * br[k] * ez))
        if np.any(self.jump_end):
            s_list.append(br[-1])
            r_list.append(nodes[-1])
            t_list.append(self.tension_at_end(True))
        s = np.asarray(s_list)
        r = np.asarray(r_list)
        t = np.asarray(t_list)
        # drop duplicates where nothing jumps
        keep = np.ones(s.size, dtype=bool)
        for i in range(1, s.size):
            if s[i] == s[i - 1] and np.array_equal(t[i], t[i - 1]):
                keep[i] = False
        return s[keep], r[keep], t[keep]

    def lowest_z(self) -> float:
        """Exact lowest height of the line, m (project frame).

        Inside a piece the cable is lowest where the vertical tension component changes
        sign (Huang's X = a_z + w s goes from < 0 to > 0); there the piece is cut and its
        exact increment evaluated.
        """
        w = self.weight
        nodes = self.nodes()
        low = float(np.min(nodes[:, 2]))
        if w <= 0:
            return low
        s0, ds = self.breaks[:-1], np.diff(self.breaks)
        xa = self.v[2] + self.cum[:, 2] + w * s0
        xb = xa + w * ds
        cut = (xa < 0) & (xb > 0)
        if np.any(cut):
            dr, _, _ = piece_increments(self.v, s0[cut], -xa[cut] / w, self.cum[cut], w,
                                        self.inv_ea, derivatives=False)
            low = min(low, float(np.min(nodes[:-1][cut, 2] - dr[:, 2])))
        return low

    def end_mismatch(self) -> float:
        """Largest relative mismatch of the end conditions (positions / L, forces / |T|max,
        a prescribed tension / itself)."""
        nodes = self.nodes()
        ta = self.tension_at_end(False)
        tb = self.tension_at_end(True)
        fscale = max(float(np.linalg.norm(ta)), float(np.linalg.norm(tb)), 1e-300)
        out = 0.0
        for end, pos, t, sign in ((self.end_a, nodes[0], ta, -1.0),
                                  (self.end_b, nodes[-1], tb, 1.0)):
            for i in range(3):
                if end.position[i] is not None:
                    out = max(out, abs(pos[i] - end.position[i]) / self.length)
                else:
                    out = max(out, abs(t[i] - sign * end.force[i]) / fscale)
            if end.tension is not None:
                out = max(out, abs(float(np.linalg.norm(t)) - end.tension) / end.tension)
        return out


def _direct_components(end_a: End, end_b: End, total_load: np.ndarray, w: float,
                       length: float) -> tuple[np.ndarray, np.ndarray]:
    """V components fixed by a prescribed force (Huang frame) and the Newton mask.

    end_a force: the support passes F_a to the cable, V_i = F_a,i. end_b force: (2.40)-(2.42)
    (and (2.43)-(2.44)) with the tension T(L) = F_b (Huang 1992, (2.9)-(2.11)).
    """
    v = np.zeros(3)
    unknown = np.zeros(3, dtype=bool)
    weight = np.array([0.0, 0.0, w * length])
    for i in range(3):
        fa, fb = end_a.force[i], end_b.force[i]
        if fa is not None:
            v[i] = FLIP[i] * fa
        elif fb is not None:
            v[i] = -FLIP[i] * fb - total_load[i] - weight[i]
        else:
            unknown[i] = True
    return v, unknown


def start_force(end_a: End, end_b: End, length: float, weight: float,
                axial_stiffness: float) -> np.ndarray:
    """Drag-free starting V (Huang frame, N) from a catenary/parabola estimate (Huang
    1992, 2.5): Newton's start in :func:`solve_line`.

    Parameters
    ----------
    end_a, end_b : End
        The end conditions (only the components fixed at both ends enter the chord).
    length : float
        Unstretched length, m.
    weight : float
        Weight in water per unstretched length, N/m.
    axial_stiffness : float
        EA, N (``math.inf``: inextensible).
    """
    w = weight
    pa, pb = end_a.position, end_b.position
    # chord over the components fixed at both ends (the others are not Newton unknowns)
    d = np.array([b - a if a is not None and b is not None else 0.0
                  for a, b in zip(pa, pb, strict=True)])
    chord = float(np.linalg.norm(d))
    dh = math.hypot(d[0], d[1])
    eh = d[:2] / dh if dh > 0 else np.array([1.0, 0.0])
    ea = axial_stiffness
    if chord > 0 and length <= chord and math.isfinite(ea):
        t0 = (ea * (chord / length - 1.0) + abs(w) * length) * d / chord
        t0[2] -= 0.5 * w * length
    elif dh > 1e-9 * max(chord, 1.0):
        ratio = (length * length - d[2] ** 2) / (dh * dh) - 1.0
        lam = math.sqrt(3.0 * ratio) if ratio > 0 else 0.2
        hor = max(abs(w) * dh / (2.0 * max(lam, 1e-3)), 1e-6 * max(abs(w) * length, 1.0))
        t0 = np.array([hor * eh[0], hor * eh[1], hor * d[2] / dh - 0.5 * w * length])
    else:
        t0 = np.array([0.0, 0.0, 0.5 * abs(w) * length * (1.0 if d[2] >= 0 else -1.0)
                       + (w * length * 0.5)])
        if t0[2] == 0.0:
            t0[2] = max(abs(w) * length, 1.0)
    return -FLIP * t0


def _pieces(length: float, load_s: np.ndarray, nodes_s: np.ndarray) -> np.ndarray:
    """Sorted piece boundaries: 0, L, the nodes and the interior load positions."""
    pts = np.concatenate([[0.0, length], nodes_s, load_s])
    pts = pts[(pts >= 0.0) & (pts <= length)]
    pts = np.unique(pts)
    keep = np.concatenate([[True], np.diff(pts) > 1e-12 * length])
    return pts[keep]


def solve_line(length: float, weight: float, axial_stiffness: float, end_a: End, end_b: End,
               loads_s: Sequence[float] | np.ndarray = (),
               loads_f: Sequence[Sequence[float]] | np.ndarray = (), *,
               tolerance: float = 1e-10, nodes_s: np.ndarray | None = None,
               v_guess: np.ndarray | None = None) -> CatenaryShape:
    """The line under point loads, exactly (Huang 1992, (2.24)-(2.45)).

    Parameters
    ----------
    length : float
        Unstretched length L, m.
    weight : float
        Weight in water per unstretched length w, N/m (negative: buoyant; 0 allowed).
    axial_stiffness : float
        EA, N; ``math.inf`` for an inextensible line.
    end_a, end_b : End
        End conditions at s = 0 and s = L (project frame): per component a position (m)
        or the external load on the attachment (N, which it passes to the cable: at
        equilibrium the force the cable exerts there is its negative). ``tension`` is
        not used here (only by :meth:`CatenaryShape.end_mismatch`).
    loads_s : sequence of float
        Unstretched arc lengths of the point loads from end_a, m (0 <= s <= L). A load at
        s = 0 or s = L acts on the end point, so the end's force includes it.
    loads_f : sequence of (Fx, Fy, Fz)
        The point loads, the external force on the cable, N, project frame (z up).
    tolerance : float
        Newton's tolerance on the end positions, relative to L.
    nodes_s : ndarray, optional
        Extra piece boundaries (arc lengths, m) where the shape is listed (no load).
    v_guess : ndarray, optional
        Newton's start for V (Huang frame, N); default :func:`start_force`.

    Returns
    -------
    CatenaryShape
        Check ``converged`` before use.
    """
    w = weight
    inv_ea = 1.0 / axial_stiffness if math.isfinite(axial_stiffness) else 0.0
    tol = tolerance
    load_s = np.asarray(loads_s, dtype=float).reshape(-1)
    load_f = FLIP * np.asarray(loads_f, dtype=float).reshape(-1, 3)  # Huang's frame
    nodes_s = np.zeros(0) if nodes_s is None else nodes_s
    breaks = _pieces(length, load_s, nodes_s)
    s0, ds = breaks[:-1], np.diff(breaks)
    eps = 1e-12 * length
    at_start = load_s <= eps
    at_end = load_s >= length - eps
    # cumulative loads: a load at s_k acts on every piece starting at or after s_k
    # (loads at s = 0 act from the first piece on, as F^0 in (2.1)-(2.3))
    cum = np.zeros((s0.size, 3))
    for k in np.nonzero(~at_end)[0]:
        # loads are piece boundaries by construction: the piece that starts there
        j = 0 if at_start[k] else int(np.argmin(np.abs(s0 - load_s[k])))
        cum[j:] += load_f[k]
    jump_start = load_f[at_start].sum(axis=0) if np.any(at_start) else np.zeros(3)
    jump_end = load_f[at_end].sum(axis=0) if np.any(at_end) else np.zeros(3)
    total = load_f.sum(axis=0) if load_f.size else np.zeros(3)
    v_known, unknown = _direct_components(end_a, end_b, total, w, length)

    # targets of the Newton equations (2.34)-(2.36)/(2.45), Huang frame
    pa, pb = end_a.position, end_b.position
    target = np.array([FLIP[i] * (pb[i] - pa[i]) for i in range(3) if unknown[i]])
    scale = max(length, float(np.linalg.norm(target)) if target.size else 0.0, 1e-300)

    def evaluate(v: np.ndarray, deriv: bool = True
                 ) -> tuple[np.ndarray, np.ndarray | None, float, np.ndarray]:
        dr, jac, energy = piece_increments(v, s0, ds, cum, w, inv_ea, deriv)
        tot = dr.sum(axis=0)
        return dr, jac, energy, tot[unknown] - target

    v = v_known.copy()
    if np.any(unknown):
        g = start_force(end_a, end_b, length, weight, axial_stiffness) if v_guess is None \
            else np.asarray(v_guess, float)
        v[unknown] = g[unknown]
    it, converged, msg = 0, False, ""
    dr, jac, energy, res = evaluate(v)
    if not np.any(unknown):
        converged = bool(np.all(np.isfinite(dr)))
        msg = "direct (2.40)-(2.42)" if converged else "non-finite profile (zero tension?)"
    else:
        for it in range(MAX_NEWTON + 1):  # noqa: B007 - it is reported
            if not (np.all(np.isfinite(res)) and np.isfinite(energy)):
                msg = "non-finite Newton iterate (zero tension in a piece?)"
                break
            if np.max(np.abs(res)) <= tol * scale:
                converged, msg = True, f"Newton-Raphson converged in {it} steps"
                break
            if it == MAX_NEWTON:
                msg = f"Newton-Raphson: no convergence in {MAX_NEWTON} steps"
                break
            juu = jac[np.ix_(unknown, unknown)]
            try:
                step = -np.linalg.solve(juu, res)
            except np.linalg.LinAlgError:
                msg = "singular Newton matrix"
                break
            merit0 = energy + target @ v[unknown]
            slope = -res @ step  # grad(merit) . step
            alpha, accepted = 1.0, False
            while alpha >= 1e-12:
                vt = v.copy()
                vt[unknown] += alpha * step
                drt, jact, energyt, rest = evaluate(vt)
                merit = energyt + target @ vt[unknown]
                # Armijo on the convex merit; near the solution, where the merit changes
                # by rounding only, a smaller residual is accepted instead
                if np.all(np.isfinite(rest)) and np.isfinite(energyt) and (
                        merit <= merit0 + 1e-4 * alpha * slope
                        or (merit <= merit0 + 1e-12 * abs(merit0)
                            and np.linalg.norm(rest) < np.linalg.norm(res))):
                    accepted = True
                    break
                alpha *= 0.5
            if not accepted:
                msg = "Newton-Raphson line search failed"
                break
            v, dr, jac, energy, res = vt, drt, jact, energyt, rest
    # position of end_a: given where fixed; else from end_b and the increments
    tot = dr.sum(axis=0) * FLIP
    start = np.array([pa[i] if pa[i] is not None else pb[i] - tot[i] for i in range(3)])
    resid = float(np.max(np.abs(res)) / scale) if res.size else 0.0
    if not np.all(np.isfinite(start)):
        converged = False
    return CatenaryShape(v=v, length=length, breaks=breaks, cum=cum, jump_start=jump_start,
                         jump_end=jump_end, start=start, dr=dr, iterations=it,
                         residual=resid, converged=converged, message=msg, weight=weight,
                         inv_ea=inv_ea, end_a=end_a, end_b=end_b)


# --------------------------------------------------------------------------------------
# The inextensible catenary without loads, parametric closed form
# --------------------------------------------------------------------------------------

def catenary_parameter_bracketed(span: float, rise: float, length: float) -> float:
    """Catenary parameter a = H / w (m) through two points ``span`` apart horizontally and
    ``rise`` vertically, at arc length ``length`` (> chord): 2 a sinh(span / (2 a)) =
    sqrt(L^2 - rise^2), by a bracketing search (Brent) on log a.

    Parameters
    ----------
    span : float
        Horizontal distance between the ends, m (> 0).
    rise : float
        Height of the second end above the first, m.
    length : float
        Arc length between them, m.
    """
    target = math.sqrt(max(length * length - rise * rise, 1e-300))

    def fun(log_a: float) -> float:
        a = math.exp(log_a)
        arg = span / (2 * a)
        if arg > 700:
            return math.inf
        return math.log(2 * a * math.sinh(arg)) - math.log(target)

    lo, hi = math.log(span * 1e-4 + 1e-12), math.log(span * 1e6 + 1e-12)
    return math.exp(brentq(fun, lo, hi, xtol=1e-14))


def _log_sinhc(u: float) -> float:
    """log(sinh(u)/u) for u > 0: for u < 1 as log1p of the series of (sinh(u) - u)/u,
    which keeps full relative accuracy near a taut cable; else u + log1p(-exp(-2u)) -
    log(2u), which does not overflow."""
    if u >= 1.0:
        return u + math.log1p(-math.exp(-2.0 * u)) - math.log(2.0 * u)
    term, series = u, 0.0
    for k in range(1, 12):
        term *= u * u / ((2 * k) * (2 * k + 1))
        series += term
    return math.log1p(series / u)


def catenary_parameter(span: float, rise: float, length: float) -> float:
    """:func:`catenary_parameter_bracketed` by Newton's method on phi(u) = log(sinh(u)/u)
    - log(sqrt(L^2 - v^2)/h), u = h / (2a): phi is increasing and convex for u > 0, and
    the start lies above the root, so the iterates fall monotonically onto it (to
    roundoff, about 20 times faster than the bracketing search).

    Parameters
    ----------
    span : float
        Horizontal distance between the ends h, m (> 0).
    rise : float
        Height of the second end above the first v, m.
    length : float
        Arc length between them, m (> chord).
    """
    log_r = math.log(max(math.sqrt(max(length * length - rise * rise, 1e-300)) / span,
                         1.0 + 1e-15))
    # above the root: sinh(u)/u >= 1 + u^2/6, and sinh(u)/u >= r at u = 2 log(r) + 10
    u = min(math.sqrt(6.0 * math.expm1(min(log_r, 700.0))), 2.0 * log_r + 10.0)
    done = False
    for _ in range(200):
        step = (_log_sinhc(u) - log_r) / (1.0 / math.tanh(u) - 1.0 / u)
        u -= step
        if done:  # one more step after 1e-12: quadratic convergence reaches roundoff
            break
        done = abs(step) <= 1e-12 * u
    return span / (2.0 * u)


def catenary_vertex(a: float, span: float, rise: float) -> float:
    """Horizontal position x0 (m) of the catenary's vertex, from the first end, for the
    catenary z = a cosh((x - x0)/a) + c through (0, 0) and (span, rise).

    Parameters
    ----------
    a : float
        Catenary parameter H / w, m.
    span : float
        Horizontal distance between the ends, m.
    rise : float
        Height of the second end above the first, m.
    """
    return span / 2 - a * math.asinh(rise / (2 * a * math.sinh(span / (2 * a))))


def catenary_nodes(a: float, span: float, rise: float, s: np.ndarray, w: float
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Horizontal coordinate X(s), height Z(s) (m, relative to the first end) and tension
    (H, V) (N) at arc lengths ``s`` from the first end of the catenary through both ends.

    Parameters
    ----------
    a : float
        Catenary parameter H / w, m (:func:`catenary_parameter_bracketed`).
    span : float
        Horizontal distance between the ends, m.
    rise : float
        Height of the second end above the first, m.
    s : ndarray
        Arc lengths from the first end, m.
    w : float
        Weight per length, N/m (> 0).

    Returns
    -------
    xs, zs : ndarray
        Coordinates of the nodes, m.
    tension : ndarray, shape (n, 2)
        Horizontal and vertical tension components, N.
    """
    x0 = catenary_vertex(a, span, rise)
    s_a = a * math.sinh(-x0 / a)  # arc-length coordinate of end a from the vertex
    xs = x0 + a * np.arcsinh((s + s_a) / a)
    zs = a * np.cosh((xs - x0) / a) - a * math.cosh(-x0 / a)
    th = np.full_like(s, w * a)
    tv = w * (s + s_a)
    return xs, zs, np.stack([th, tv], axis=1)


def touchdown_catenary(rise: float, distance: float, length: float
                       ) -> tuple[float, float] | None:
    """The inextensible catenary with touchdown on a horizontal seabed: a grounded
    straight part from the anchor, then a catenary that leaves the seabed horizontally
    and reaches the top end ``rise`` above and ``distance`` away from the anchor. With
    a = H/w, suspended length L_s = sqrt(h^2 + 2 h a) and span x_s = a acosh(1 + h/a)
    for the rise h, H solves L - L_s + x_s = X (the horizontal distance).

    Parameters
    ----------
    rise : float
        Height of the top end above the anchor, m (> 0).
    distance : float
        Horizontal distance from the anchor to the top end, m.
    length : float
        Unstretched length of the line, m.

    Returns
    -------
    (a, ls) or None
        The catenary parameter (m) and the suspended length (m; the grounded length is
        L - ls); None when no such catenary exists (the line is too short to touch).
    """
    h, x_tot = rise, distance

    def excess(log_a: float) -> float:
        a = math.exp(log_a)
        ls = math.sqrt(h * h + 2 * h * a)
        return (length - ls + a * math.acosh(1 + h / a)) - x_tot

    lo, hi = math.log(1e-6 * h), math.log(1e6 * max(x_tot, h))
    if excess(lo) * excess(hi) > 0:
        return None
    a = math.exp(brentq(excess, lo, hi, xtol=1e-12))
    ls = math.sqrt(h * h + 2 * h * a)
    if ls >= length:
        return None
    return a, ls


def vertex_nodes(a: float, s: np.ndarray, w: float
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Horizontal coordinate (m), height (m) and tension (H, V) (N) at arc lengths ``s``
    from the vertex of a catenary: x = a asinh(s/a), z = a (sqrt(1 + (s/a)^2) - 1),
    T = (w a, w s).

    Parameters
    ----------
    a : float
        Catenary parameter H / w, m.
    s : ndarray
        Arc lengths from the vertex, m.
    w : float
        Weight per length, N/m.
    """
    xs = a * np.arcsinh(s / a)
    zs = a * (np.sqrt(1 + (s / a) ** 2) - 1)
    return xs, zs, np.stack([np.full_like(s, w * a), w * s], axis=1)
