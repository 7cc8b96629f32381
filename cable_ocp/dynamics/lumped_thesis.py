"""Huang's finite-difference scheme (5.21) for the lumped-mass model, as written.

A reference implementation of Huang (1992), section 5.4, kept as a baseline: at each step
the positions x^{j+1} of the free nodes solve the linear system

    A^j (x^{j+1} - 2 x^j + x^{j-1}) / dt^2 + B^j C^j X^{j+1} = f^j + B^j [sigma E, sigma E]^T

per node i, with

* A^j the node's mass matrix with the added mass of (5.2), at the directions of time j;
* B^j = [e_{i-1/2}, -e_{i+1/2}] the unit vectors of the two segments at time j;
* C^j X^{j+1} = sigma E d^j . d^{j+1} / q, q = l^2 (T^j / (sigma E) + 1) = l |d^j|: the
  linearised tension T^{j+1} = sigma E (d^j . d^{j+1} / (l |d^j|) - 1) plus sigma E (the
  linearisation of (5.3)-(5.4) printed after the difference quotients of 5.4);
* f^j the drag with the backward-difference velocities (x^j - x^{j-1}) / dt, the weight
  and buoyancy, and the loads of the unit and bodies, at time j.

So the tension *magnitude* is implicit and its *direction* explicit. Huang's stability
analysis (5.5) sets delta B = delta C = 0, which drops the product of the tension and the
perturbed direction, i.e. the transverse restoring force; for transverse waves the scheme
is the explicit central difference m (y^{j+1} - 2 y^j + y^{j-1}) / dt^2 = (T / |d|)
(y_{i+1} - 2 y_i + y_{i-1})^j, stable only while omega dt <= 2 with omega up to
2 sqrt(T / (m |d|)): dt <= sqrt(m |d| / T). The axial waves have Huang's own amplification
|lambda|^2 = 1 / (1 + a), a = 4 sin^2(beta/2) sigma E dt^2 / (l m) (damped, unconditionally
stable). See docs/dynamics.md, "Lumped-mass model (Huang ch. 5)".

The tension follows Hooke's law (5.3) with compression allowed, as printed (no slack
switch). The start is x^{-1} = x^0 - dt v^0. Python runs once per step (a baseline, not
a fast path).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import numpy as np
from scipy.sparse import coo_matrix

from cable_ocp.dynamics.lumped import LumpedMassModel
from cable_ocp.dynamics.lumped_run import LumpedRun, step_grid
from cable_ocp.numerics.linalg import solve_sparse
from cable_ocp.physics.elasticity import hooke_tension

__all__ = ["run_thesis", "thesis_step"]


class _Thesis:
    """Numeric pieces of (5.21) for one model."""

    def __init__(self, model: LumpedMassModel) -> None:
        self.model = model
        p = model.params
        self.n = p.segments
        self.ell = p.segment_length
        self.ea = p.axial_stiffness
        self.mass_blocks = model.mass_blocks
        self.ends = model.ends
        self.first = 1 if p.fixed_a else 0
        # sparsity pattern of the block-tridiagonal system (free nodes)
        nf = model.n_free
        rows, cols = [], []
        for a in range(nf):
            for b in (a - 1, a, a + 1):
                if 0 <= b < nf:
                    for i in range(3):
                        for k in range(3):
                            rows.append(3 * a + i)
                            cols.append(3 * b + k)
        self.rows = np.asarray(rows)
        self.cols = np.asarray(cols)

    def all_nodes(self, xf: np.ndarray, t: float) -> np.ndarray:
        ra, _, rb, _ = (np.asarray(v).reshape(-1) for v in self.ends(t))
        pts = [xf.reshape(-1, 3)]
        if self.first:
            pts = [ra[None, :]] + pts
        return np.vstack(pts + [rb[None, :]])

    def step(self, x_prev: np.ndarray, x_now: np.ndarray, t: float, dt: float
             ) -> np.ndarray | None:
        """x^{j+1} of the free nodes from x^{j-1}, x^j at t = t_j (s); None when the
        step's matrix is singular."""
        m = self.model
        n, nf, first = self.n, m.n_free, self.first
        r = self.all_nodes(x_now, t)
        r1 = self.all_nodes(x_now, t + dt)  # only the prescribed ends are used from r1
        d = r[1:] - r[:-1]
        big_l = np.linalg.norm(d, axis=1)
        e = d / big_l[:, None]
        k_s = self.ea / (self.ell * big_l)  # sigma E / q
        v = (x_now - x_prev) / dt
        f = np.asarray(m.external_forces(x_now, v, t)).reshape(-1)
        mb = np.asarray(self.mass_blocks(x_now, t)).reshape(-1, 3, 3).transpose(0, 2, 1)
        rhs = f.reshape(-1, 3).copy()
        blocks: dict[tuple[int, int], np.ndarray] = {}

        def add(a: int, b: int, blk: np.ndarray) -> None:
            blocks[(a, b)] = blocks.get((a, b), 0.0) + blk

        for i in range(nf):
            node = i + first
            add(i, i, mb[node] / dt**2)
            rhs[i] += mb[node] @ (2.0 * x_now[3 * i:3 * i + 3] - x_prev[3 * i:3 * i + 3]) / dt**2
        for j in range(n):
            a, b = j, j + 1  # node indices
            kmat = k_s[j] * np.outer(e[j], d[j])  # force on a: kmat (x_b - x_a) - EA e
            const = -self.ea[j] * e[j]
            ia, ib = a - first, b - first
            fa = 0 <= ia < nf
            fb = 0 <= ib < nf
            if fa:
                rhs[ia] += const
                add(ia, ia, kmat)
                if fb:
                    add(ia, ib, -kmat)
                else:
                    rhs[ia] += kmat @ r1[b]
            if fb:
                rhs[ib] -= const
                add(ib, ib, kmat)
                if fa:
                    add(ib, ia, -kmat)
                else:
                    rhs[ib] += kmat @ r1[a]
        vals = []
        for a in range(nf):
            for b in (a - 1, a, a + 1):
                if 0 <= b < nf:
                    vals.append(np.asarray(blocks.get((a, b), np.zeros((3, 3)))).reshape(-1))
        mat = coo_matrix((np.concatenate(vals), (self.rows, self.cols)),
                         shape=(3 * nf, 3 * nf)).tocsc()
        return solve_sparse(mat, rhs.reshape(-1))


def thesis_step(model: LumpedMassModel) -> Callable[[np.ndarray, np.ndarray, float, float],
                                                    np.ndarray | None]:
    """``step(x_prev, x_now, t, dt) -> x_next``: one step of (5.21) for ``model`` (free-node
    positions, m; t the time of x_now, s; None when the step's matrix is singular)."""
    return _Thesis(model).step


def run_thesis(model: LumpedMassModel, x0: np.ndarray, v0: np.ndarray | None,
               duration: float, time_step: float, *, record_every: int = 1,
               t0: float = 0.0, progress: Callable[[float, float], Any] | None = None
               ) -> LumpedRun:
    """Integrate with Huang's scheme (5.21) (Python once per step; see the module
    docstring). Same arguments and result type as :func:`cable_ocp.dynamics.lumped_run.run`;
    a step that produces non-finite positions stops the run with status ``"failed"``
    (the scheme is unstable for dt above about sqrt(m l / T): see the module docstring).

    Parameters
    ----------
    model : LumpedMassModel
        The model.
    x0, v0 : ndarray (3 n_free,)
        Initial positions (m) and velocities (m/s; None: at rest).
    duration, time_step : float
        Simulated time and step, s.
    record_every : int
        Keep every k-th step.
    t0 : float
        Start time, s.
    progress : callable, optional
        ``progress(t_done, duration)`` (s, s).
    """
    k, n_steps, dt = step_grid(duration, time_step, record_every)
    tb = time.perf_counter()
    th = _Thesis(model)
    build = time.perf_counter() - tb
    x_now = np.asarray(x0, float).reshape(-1)
    v = np.zeros_like(x_now) if v0 is None else np.asarray(v0, float).reshape(-1)
    x_prev = x_now - dt * v
    xs, vs, ts = [x_now.copy()], [v.copy()], [t0]
    status, message = "solved", f"{n_steps} steps of {dt:.6g} s (Huang (5.21))"
    tw = time.perf_counter()
    every_progress = max(1, n_steps // 200)
    scale = 10.0 * (model.params.length + float(np.max(np.abs(x_now))) + 1.0)
    for j in range(n_steps):
        t = t0 + j * dt
        x_next = th.step(x_prev, x_now, t, dt)
        if x_next is None:
            status = "failed"
            message = (f"Huang's scheme (5.21): the step matrix is singular at t = {t:.6g} s "
                       "(a node with no mass and no stiffness, e.g. a slack or massless "
                       "segment at a free end)")
            break
        if not np.all(np.isfinite(x_next)) or np.max(np.abs(x_next)) > scale:
            status = "failed"
            message = (f"Huang's scheme (5.21) diverged at t = {t + dt:.6g} s (positions "
                       "non-finite or beyond 10 line lengths): the explicit transverse "
                       "direction limits dt to about sqrt(m l / T)")
            break
        x_prev, x_now = x_now, x_next
        if (j + 1) % k == 0:
            xs.append(x_now.copy())
            vs.append((x_now - x_prev) / dt)
            ts.append(t + dt)
        if progress is not None and ((j + 1) % every_progress == 0 or j + 1 == n_steps):
            progress((j + 1) * dt, duration)
    wall = time.perf_counter() - tw
    xa = np.asarray(xs)
    va = np.asarray(vs)
    ta = np.asarray(ts)
    n = ta.size
    pos = np.asarray(model.nodes.map(n)(xa.T, ta[None, :]))
    positions = pos.reshape(3, n, model.params.segments + 1).transpose(1, 2, 0)
    vel = np.asarray(model.node_velocities.map(n)(va.T, ta[None, :]))
    velocities = vel.reshape(3, n, model.params.segments + 1).transpose(1, 2, 0)
    d = positions[:, 1:] - positions[:, :-1]
    strain = np.linalg.norm(d, axis=2) / model.params.segment_length - 1.0
    tension = hooke_tension(strain, model.params.axial_stiffness)  # (5.3): compression allowed
    ftop = np.asarray(model.top_force.map(n)(xa.T, va.T, ta[None, :])).T
    slack = None
    bad = np.argwhere(strain <= 0.0)
    if bad.size:
        slack = (float(ta[bad[0, 0]]), int(bad[0, 1]))
    return LumpedRun(status=status, message=message, t=ta, x=xa, v=va, positions=positions,
                     velocities=velocities,
                     tension=tension, strain=strain, top_force=ftop,
                     residual=np.zeros(n), scheme="thesis", time_step=dt,
                     steps=(n - 1) * k, wall_time_s=wall, build_time_s=build,
                     mean_iterations=1.0, compiled="none",
                     min_strain=float(np.min(strain)), slack=slack)
