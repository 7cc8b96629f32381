"""Multiple shooting of the static cable BVP with a CasADi integrator.

The same equations as the collocation (:class:`~cable_ocp.statics.formulation.Formulation`),
another transcription: sigma = s/L in [0, 1] is cut into N uniform intervals; the state at
each interval start is an unknown, and a fixed-step RK4 integrator (CasADi ``integrator``
plugin ``"rk"``, one step per interval, mapped over all intervals) carries it to the next
start. Unknowns::

    w = [x_0, x_1, ..., x_N, (lam if the length is free)]

Equations: continuity F(x_k) - x_{k+1} = 0 (divided by the step, like the collocation
residuals), 6 end conditions and, when the length is free, the end tension. The system is
square and is solved by the same :class:`~cable_ocp.statics.line_solver.StaticsSolver` (Newton,
IPOPT as the fallback; the residual and its Jacobian assembled per interval as for the
collocation). Convergence: order 4 at the nodes.
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from cable_ocp.statics.collocation import Collocation
from cable_ocp.statics.formulation import (
    NX,
    P_CURRENT,
    P_LENGTH,
    Formulation,
)
from cable_ocp.statics.newton import Block


@dataclass(frozen=True)
class ShootingMesh:
    """Nodes of a multiple-shooting grid on sigma in [0, 1] (same API as ``Mesh``)."""

    intervals: int
    degree: int = 0
    scheme: str = "rk4"
    segments: tuple[int, ...] = ()  # one cable only (see ``Mesh``)

    @property
    def n_nodes(self) -> int:
        """Number of state nodes (interval starts and the final point)."""
        return self.intervals + 1

    def sigma(self) -> np.ndarray:
        """sigma of every node."""
        return np.linspace(0.0, 1.0, self.intervals + 1)

    def mesh_index(self) -> np.ndarray:
        """Every node is a mesh point."""
        return np.arange(self.intervals + 1)

    @property
    def order(self) -> int:
        """Convergence order of RK4."""
        return 4


class MultipleShooting(Collocation):
    """Residual G(w, p) of the multiple-shooting transcription (RK4, one step/interval).

    Shares packing and unpacking with :class:`Collocation` (node arrays in sigma order).
    """

    def __init__(self, form: Formulation, intervals: int, degree: int = 0,
                 scheme: str = "rk4", grounded: bool = False):
        self.form = form
        self.mesh = ShootingMesh(intervals)  # type: ignore[assignment]
        self._setup(grounded)

    def mesh_params(self, mesh: object = None) -> np.ndarray:
        """No mesh parameters: the uniform step is part of the built RK4 step."""
        return np.zeros(0)

    def interpolate(self, values: np.ndarray, sigma: np.ndarray, mesh: object = None,
                    segment: np.ndarray | None = None) -> np.ndarray:
        """Piecewise-linear between the nodes (RK4 has no dense output here); exact at the
        nodes, which is where the error estimate compares shooting solutions."""
        grid = self.mesh.sigma()
        return np.stack([np.interp(sigma, grid, values[:, k]) for k in range(values.shape[1])],
                        axis=1)

    def _rk4_step(self) -> ca.Function:
        """One RK4 step of width h = 1/N (CasADi ``integrator`` plugin ``"rk"``, one finite
        element), expanded to SX: ``(x0, p=[lam, cscale]) -> xf``."""
        h = 1.0 / self.mesh.intervals
        x = ca.MX.sym("x", NX)
        q = ca.MX.sym("q", 2)  # lam, current scale
        dae = {"x": x, "p": q, "ode": self.form.rhs(x, q[0], q[1])}
        step = ca.integrator("rk4_step", "rk", dae, 0.0, h, {
            "number_of_finite_elements": 1, "simplify": True})
        return step.expand()

    def _make_blocks(self, fns: list[ca.Function] | None = None) -> list[Block]:
        """The residual as blocks: the mapped interval ``(z, p) -> (F(x_k) - x_{k+1}) / h``
        with z = [x_k, x_{k+1}, (lam | g)], then the end conditions; rows in the order
        continuity, end conditions. With ``fns`` (from :meth:`block_functions`), nothing
        is built: the layout is checked against them."""
        n, nx = self.mesh.intervals, NX
        n_p = len(self.form.params())
        with_g = self.grounded and not self.free_length
        has_tail = self.free_length or with_g
        tail = self.i_lam if self.free_length else self.i_g
        k = np.arange(n)
        idx = (k[None, :] * nx) + np.arange(2 * nx)[:, None]
        if has_tail:
            idx = np.vstack([idx, np.full((1, n), tail)])
        rows = k[None, :] * nx + np.arange(nx)[:, None]
        ends_idx = np.concatenate([np.arange(nx), self.n_x - nx + np.arange(nx)]
                                  + ([[self.i_g]] if self.grounded else []))[:, None]
        if fns is None:
            h = 1.0 / n
            z = ca.SX.sym("z", 2 * nx + (1 if has_tail else 0))
            p = ca.SX.sym("p", n_p)
            if self.free_length:
                lam = z[-1]
            else:
                lam = p[P_LENGTH] - z[-1] if with_g else p[P_LENGTH]
            xf = self._rk4_step()(x0=z[:nx], p=ca.vertcat(lam, p[P_CURRENT]))["xf"]
            fns = [*self._with_jacobian("shooting_interval", [z], p,
                                        [(xf - z[nx: 2 * nx]) / h]),
                   *self._ends_block(n_p)]
        if len(fns) != 4 or fns[0].size1_in(0) != idx.shape[0] \
                or fns[0].size1_out(0) != nx or fns[2].size1_in(0) != ends_idx.shape[0]:
            raise ValueError("stored block functions do not fit this layout")
        nbc = fns[2].size1_out(0)
        return [Block(fns[0], idx, rows, fns[1]),
                Block(fns[2], ends_idx, (n * nx + np.arange(nbc))[:, None], fns[3])]
