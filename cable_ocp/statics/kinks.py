"""Mesh points on the kinks of the drag: where the load along the cable is not smooth.

The quadratic drag |u| u (:mod:`cable_ocp.physics.drag`) is continuously differentiable
in the flow component u but its second derivative jumps where u changes sign (the smooth
modulus of :mod:`cable_ocp.physics.smooth` spreads the jump over a velocity of the order
of ``solver.smoothing``, a few millimetres of cable). Where a flow component relative to
the cable changes sign at an arc length s*, the tension's third derivative jumps there.
Collocation of degree d converges at order 2d at the mesh points only for smooth
solutions; with s* inside an interval, the error of that interval falls like h^4 whatever
d, and mesh points belong where the data lose smoothness (Ascher, Mattheij & Russell
(1995), *Numerical Solution of Boundary Value Problems for Ordinary Differential
Equations*, ch. 9, mesh selection). Measured on De Zoysa's cable at psi0 = 90 deg (Wang,
Cheong & Chucheepsakul (1993), eq. (28)), where the flow along the tangent and along e_n
both change sign at s* ~ 140.3 m: the end forces of Gauss-Legendre degree 4 on 16 uniform
intervals are off by 7.7e-8 of the largest tension, by 1e-13 with a mesh point on s*. A
mesh point at a distance e from s* leaves about (2/3) J e^3 / T_max, J = sum over the
components vanishing there of K_c (du_c/ds)^2 (K_c the component's drag coefficient,
1/2 rho C D): the quadrature misses the 2 x^2 part of |x| x over the stretch e; on De
Zoysa's cable 0.2 (e / L)^3.

Sources of kinks, each the zero of a *switching function* evaluated at the nodes of a
profile (positions r, unit tangents t, the current u(z)):

* the tangential drag |u.t| (u.t): u.t (when the tangential drag coefficient is not 0);
* the componentwise normal drag (Wang et al. (1993), eqs (4)-(6)): u.e_b and
  u.e_n = -t_z (u.t) / |e_z x t| (so u.t and t_z: the tangent normal to the current,
  or horizontal), and the two ends of the vertical blend (sigma^2 = beta^2 / 4 and
  beta^2, where its smoothstep is clipped) where the cable comes that near vertical;
* the vector law's normal drag |u_n| u_n: where u_n = u - (u.t) t passes through zero,
  i.e. u x t changes sign along a fixed direction (planar lines; in 3D u_n rarely
  vanishes, and a sign change of one component of u x t alone is not a kink);
* a current profile: the heights of its knots (its velocity has a kink there).

A mesh *fitted* to kinks s*_1 < ... < s*_m of a segment splits the segment at them and
gives each part a uniform share of the segment's intervals (at least one each, the widest
interval as narrow as possible); kinks closer than :data:`GAP` (as a fraction of the
collocated length) to a segment end or to each other are not separated, and a segment
whose widest interval would widen by more than :data:`WIDEN` stays uniform.

Fitting pays only where the scheme's order at the mesh points exceeds the kink's 4
(degree 3 and up): with Gauss-Legendre of degree 2 (order 4) the errors on De Zoysa's
cable stayed within 0.86-1.1x of the uniform mesh's, so the solver fits from degree 3.
"""

from __future__ import annotations

import numpy as np

from cable_ocp.physics.current import profile_knots as current_knots
from cable_ocp.physics.current import profile_velocity_np
from cable_ocp.scene import Scene

#: kinks closer than this to a segment end or to another kink (as a fraction of the
#: collocated length, sigma) get no mesh point of their own; a mesh whose interval ends
#: differ from the fitted one by less than this is kept (a kink at a distance e from its
#: mesh point leaves an error of about 0.2 (e / L)^3 on De Zoysa's cable: 2e-13 at 1e-4)
GAP = 1e-4
#: a segment keeps its uniform intervals when fitting its kinks would widen its widest
#: interval by more than this fraction: the rest of the segment then loses more accuracy
#: than the kink costs (Berteaux's mooring, whose kink of the weak tangential drag lies
#: 16 m below the buoy, 0.5 % of the line: fitted on 8 intervals, the other seven widen
#: by 14 % and the profile error of degree 4 grows 1.8x; on 16, by 6 %, and the error
#: falls 4.8x)
WIDEN = 0.1


def _current(scene: Scene, z: np.ndarray) -> np.ndarray:
    """Current velocity at heights z (m), (n, 3) m/s
    (:func:`cable_ocp.physics.current.profile_velocity_np`)."""
    cur = scene.environment.current
    if cur is None:
        return np.zeros((len(z), 3))
    return profile_velocity_np(z, cur.z, cur.ux, cur.uy)


def profile_knots(scene: Scene) -> list[float]:
    """Heights (m) of the knots of the current profile where its velocity has a kink
    (:func:`cable_ocp.physics.current.profile_knots`)."""
    cur = scene.environment.current
    if cur is None:
        return []
    return current_knots(cur.z, cur.ux, cur.uy)


class Switches:
    """The switching functions of a scene (see the module docstring), set up once.

    Calling it with node positions (n, 3), m, unit tangents (n, 3) and optionally the
    segment of each node gives their values (n, m): a kink lies where a column changes
    sign between neighbouring nodes (NaN: not a kink source at that node)."""

    def __init__(self, scene: Scene):
        self.scene = scene
        cur = scene.environment.current
        lines = scene.lines
        self.active = cur is not None
        comp = [c.drag_law == "componentwise" and c.normal_drag != 0.0 for c in lines]
        # per column kind, the segments it applies to (None: every one, False: none):
        # u.t for the tangential drag and, through u.e_n = -t_z (u.t) / |e_z x t|, for the
        # componentwise law, whose other sources are t_z, u.e_b and the blend's two ends
        self.along = self._mask([c.tangential_drag != 0.0 or k
                                 for c, k in zip(lines, comp, strict=True)])
        self.componentwise = self._mask(comp)
        self.vector = self._mask([c.drag_law == "vector" and c.normal_drag != 0.0
                                  for c in lines])
        self.knots = profile_knots(scene)
        self.blend = scene.solver.vertical_blend
        if cur is not None and cur.uniform:
            self.u0 = np.array([cur.ux[0], cur.uy[0], 0.0])
        else:
            self.u0 = None

    @staticmethod
    def _mask(flags: list[bool]) -> np.ndarray | None | bool:
        """False: no segment; None: every segment; else the flags per segment."""
        if not any(flags):
            return False
        return None if all(flags) else np.asarray(flags)

    def __call__(self, position: np.ndarray, tangent: np.ndarray,
                 segment: np.ndarray | None = None) -> np.ndarray:
        n = len(position)
        if not self.active or n == 0:
            return np.zeros((n, 0))
        if self.u0 is not None:
            ux, uy = self.u0[0], self.u0[1]
        else:
            u = _current(self.scene, position[:, 2])
            ux, uy = u[:, 0], u[:, 1]
        tx, ty, tz = tangent[:, 0], tangent[:, 1], tangent[:, 2]
        cols: list[np.ndarray] = []

        def on(mask: np.ndarray | None, values: np.ndarray) -> None:
            if mask is not None:
                seg = np.zeros(n, dtype=int) if segment is None else segment
                values = np.where(mask[seg], values, np.nan)
            cols.append(values)

        if self.along is not False:
            on(self.along, ux * tx + uy * ty)  # u.t (u has no vertical part)
        if self.componentwise is not False:
            on(self.componentwise, tz)
            on(self.componentwise, uy * tx - ux * ty)  # u.e_b |e_z x t|
            sigma2 = tx * tx + ty * ty
            blend2 = self.blend * self.blend
            if float(np.min(sigma2)) < blend2:  # near vertical somewhere: the blend's ends
                on(self.componentwise, sigma2 - 0.25 * blend2)
                on(self.componentwise, sigma2 - blend2)
        if self.vector is not False:
            # u x t = (u_y t_z, -u_x t_z, u_x t_y - u_y t_x)
            c = np.stack([uy * tz + 0.0 * tx, -ux * tz + 0.0 * tx, ux * ty - uy * tx], axis=1)
            size = np.sqrt(np.einsum("ij,ij->i", c, c))
            big = float(size.max())
            if big > 0.0:
                along = c @ (c[int(np.argmax(size))] / big)
                # a sign change of u x t along e is a kink only where u x t stays along e
                on(self.vector, np.where(np.abs(along) >= 0.5 * size, along, np.nan))
        for zk in self.knots:
            cols.append(position[:, 2] - zk)
        return np.stack(cols, axis=1) if cols else np.zeros((n, 0))


def switching_values(scene: Scene, position: np.ndarray, tangent: np.ndarray,
                     segment: np.ndarray | None = None) -> np.ndarray:
    """The switching functions at each node, (n, m) (:class:`Switches`).

    Parameters
    ----------
    scene : Scene
        The scene (current, drag laws and coefficients of each segment).
    position : ndarray, shape (n, 3)
        Node positions, m.
    tangent : ndarray, shape (n, 3)
        Unit tangents, -.
    segment : ndarray of int, shape (n,), optional
        Segment of each node (multi-segment lines; default all 0).
    """
    return Switches(scene)(position, tangent, segment)


def _root(x: np.ndarray, v: np.ndarray, a: float, b: float, va: float, vb: float) -> float:
    """Root in [a, b] (va, vb of opposite signs) of the polynomial through (x, v), by
    the Illinois variant of regula falsi (superlinear; a few steps)."""
    xs = [float(e) for e in x]
    c = [float(e) for e in v]  # Newton's divided differences, in place
    for j in range(1, len(xs)):
        for i in range(len(xs) - 1, j - 1, -1):
            c[i] = (c[i] - c[i - 1]) / (xs[i] - xs[i - j])

    def poly(s: float) -> float:
        total = c[-1]
        for i in range(len(xs) - 2, -1, -1):
            total = total * (s - xs[i]) + c[i]
        return total

    m = a
    for _ in range(60):
        m = (a * vb - b * va) / (vb - va)
        vm = poly(m)
        if vm == 0.0:
            break
        if vm * vb < 0.0:  # the root lies between b and m
            a, va = b, vb
        else:  # between a and m: halve the retained end's value (Illinois)
            va *= 0.5
        b, vb = m, vm
        if abs(b - a) <= 1e-13 * max(1.0, abs(m)):
            break
    return float(m)


def find(sigma: np.ndarray, values: np.ndarray, offsets: list[int] | None = None
         ) -> np.ndarray:
    """Kinks (sigma, sorted): sign changes of each column of ``values`` between
    neighbouring nodes of one segment, located on the cubic through the four nodes
    around each (the two nodes themselves on a straight line where fewer are usable).

    Parameters
    ----------
    sigma : ndarray, shape (n,)
        Node coordinates, increasing within each segment (repeated points allowed).
    values : ndarray, shape (n, m)
        Switching functions at the nodes (:func:`switching_values`).
    offsets : list of int, optional
        Index of each segment's first node and the number of nodes (default one
        segment).
    """
    if values.shape[1] == 0:
        return np.zeros(0)
    offsets = [0, len(sigma)] if offsets is None else offsets
    # neighbouring nodes of one segment, at distinct points (a Radau interval's last
    # point is the next one's first; a joint appears twice)
    pair = np.diff(sigma) > 1e-14
    pair[np.asarray(offsets[1:-1], dtype=int) - 1] = False
    rows, cols = np.nonzero((values[:-1] * values[1:] < 0.0) & pair[:, None])  # NaN: False
    out: list[float] = []
    for i, col in zip(rows.tolist(), cols.tolist(), strict=True):
        k = int(np.searchsorted(offsets, i, side="right")) - 1
        lo, hi = offsets[k], offsets[k + 1]
        j0 = min(max(i - 1, lo), hi - 4)
        win = slice(j0, j0 + 4)
        if j0 < lo or not (np.all(pair[j0: j0 + 3]) and np.all(np.isfinite(values[win, col]))):
            win = slice(i, i + 2)
        out.append(_root(sigma[win], values[win, col], float(sigma[i]), float(sigma[i + 1]),
                         float(values[i, col]), float(values[i + 1, col])))
    if not out:
        return np.zeros(0)
    found = np.sort(np.asarray(out))
    # one kink where several switching functions change sign together
    return found[np.concatenate([[True], np.diff(found) > 1e-9])]


def _counts(lengths: np.ndarray, n: int) -> np.ndarray:
    """Intervals per part: at least one each, n in all, the widest interval (length over
    count) as narrow as possible."""
    c = np.maximum(1, np.floor(n * lengths / lengths.sum()).astype(int))
    while c.sum() < n:
        c[int(np.argmax(lengths / c))] += 1
    while c.sum() > n:
        cand = np.where(c > 1, lengths / np.maximum(c - 1, 1), np.inf)
        c[int(np.argmin(cand))] -= 1
    return c


def fitted_edges(counts: tuple[int, ...], bounds: tuple[float, ...], kinks: np.ndarray,
                 gap: float = GAP, widen: float = WIDEN) -> np.ndarray | None:
    """Interval ends (sigma) of the mesh fitted to ``kinks``: each segment (``counts``
    intervals between ``bounds``) split at its kinks, each part uniform, unless that
    widens the segment's widest interval by more than ``widen``; None when no kink gets a
    mesh point (the uniform mesh)."""
    if len(kinks) == 0:
        return None
    edges = [np.zeros(1)]
    fitted = False
    for k, n in enumerate(counts):
        lo, hi = bounds[k], bounds[k + 1]
        pts = [lo]
        for x in kinks:
            if lo + gap < x < hi - gap and x - pts[-1] > gap and len(pts) < n:
                pts.append(float(x))
        pts.append(hi)
        part = None
        if len(pts) > 2:
            pts_a = np.asarray(pts)
            lengths = np.diff(pts_a)
            c = _counts(lengths, n)
            if float(np.max(lengths / c)) <= (1.0 + widen) * (hi - lo) / n:
                fitted = True
                part = np.concatenate([pts_a[i] + lengths[i] * np.arange(1, c[i] + 1) / c[i]
                                       for i in range(len(c))])
        if part is None:
            part = lo + (hi - lo) * np.arange(1, n + 1) / n
        part[-1] = hi
        edges.append(part)
    return np.concatenate(edges) if fitted else None
