"""Multiple shooting of the static cable BVP with a CasADi integrator.

The same equations as the collocation (:class:`~cable_ocp.statics.formulation.Formulation`),
another transcription: sigma = s/L in [0, 1] is cut into N uniform intervals; the state at
each interval start is an unknown, and a fixed-step RK4 integrator (CasADi ``integrator``
plugin ``"rk"``, one step per interval, mapped over all intervals) carries it to the next
start. Unknowns::

    w = [x_0, x_1, ..., x_N, (lam if the length is free)]

Equations: continuity F(x_k) - x_{k+1} = 0 (divided by the step, like the collocation
residuals), 6 end conditions and, when the length is free, the end tension. The system is
square and is solved by the same :class:`~cable_ocp.statics.solver.StaticsSolver` (IPOPT
cold, Newton warm). Convergence: order 4 at the nodes.
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from cable_ocp.statics.collocation import Collocation
from cable_ocp.statics.formulation import (
    NX,
    P_CURRENT,
    Formulation,
)


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
        self.residual = self._build()

    def interpolate(self, values: np.ndarray, sigma: np.ndarray) -> np.ndarray:
        """Piecewise-linear between the nodes (RK4 has no dense output here); exact at the
        nodes, which is where the error estimate compares shooting solutions."""
        grid = self.mesh.sigma()
        return np.stack([np.interp(sigma, grid, values[:, k]) for k in range(values.shape[1])],
                        axis=1)

    def _build(self) -> ca.Function:
        n = self.mesh.intervals
        h = 1.0 / n
        x = ca.MX.sym("x", NX)
        q = ca.MX.sym("q", 2)  # lam, current scale
        dae = {"x": x, "p": q, "ode": self.form.rhs(x, q[0], q[1])}
        step = ca.integrator("rk4_step", "rk", dae, 0.0, h, {
            "number_of_finite_elements": 1, "simplify": True})
        w = ca.MX.sym("w", self.n_w)
        p = ca.MX.sym("p", len(self.form.params()))
        lam, g_len = self._lengths(w, p)
        xs = ca.reshape(w[: self.n_x], NX, self.mesh.n_nodes)
        qq = ca.repmat(ca.vertcat(lam, p[P_CURRENT]), 1, n)
        xf = step.map(n)(x0=xs[:, :n], p=qq)["xf"]
        cont = ca.vec(xf - xs[:, 1:]) / h
        bc = self._boundary(xs[:, 0], xs[:, -1], g_len, p)
        return ca.Function("G", [w, p], [ca.vertcat(cont, *bc)], ["w", "p"], ["g"])

    def _make_blocks(self, fns: list[ca.Function] | None = None) -> None:
        """No block description (the RK4 step is an integrator): the solver expands the
        residual instead (:func:`cable_ocp.statics.newton.expanded_functions`)."""
        return None

    @property
    def has_blocks(self) -> bool:
        """False: see :meth:`_make_blocks`."""
        return False
