"""Bending stiffness in the dynamic models: the hinge terms of the planar and lumped lines.

The law is :mod:`cable_ocp.physics.bending` (Huang (1992) 12.4.6; Bielański 003 eqs
(4)-(7)): a hinge at every interior node with the energy EI / (2 hbar) |u_{j+1} - u_j|^2
(u_j = d_j / h_j the stretched tangent of element j), quadratic in the node positions. This
module places the hinges on a model's nodes and adds their forces to the model's nodal
forces; the models call it in one line each (:mod:`cable_ocp.dynamics.planar`,
:mod:`cable_ocp.dynamics.lumped_equations`, :mod:`cable_ocp.dynamics.lumped_kernel`).

* **Where EI comes from**: ``bending_stiffness`` (EI, N m^2) of each ``[[cable.segments]]``
  entry, the key of the statics (:mod:`cable_ocp.statics.formulation`), so that a line with
  EI starts from its EI statics. An element takes the EI of the segment holding its
  midpoint; a hinge between elements of EI_1 and EI_2 takes 2 EI_1 EI_2 / (EI_1 + EI_2)
  (two half elements in series: EI where both are equal, 0 where a flexible part meets a
  stiff one, the pin M = 0 of the statics).
* **Ends** (``[simulation] top_end``): end_a (a unit, a free tail or an anchor) and a
  ``"pinned"`` end_b carry no moment. ``"clamped"`` holds the top tangent along the top
  element's direction at t = 0 (the static state, or vertical for ``start =
  "unstrained"``) with the half-element clamp hinge of :func:`cable_ocp.physics.bending.
  clamp_energy` (second order).
* **Time**: the forces are linear in the positions, so the midpoint rule's force at the
  mean positions is the exact discrete gradient of the bending energy: an undamped run
  in air conserves kinetic + strain + weight + bending energy to the Newton tolerance
  (tests/dynamics/test_bending.py). Their Jacobian is a constant matrix (:meth:`stiffness`).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.physics.bending import (
    clamp_energy,
    clamp_force,
    hinge_energy,
    hinge_forces,
    hinge_moment,
)
from cable_ocp.scene import Scene
from cable_ocp.scene.dynamics import DynamicScene
from cable_ocp.statics.solution import StaticsSolution

__all__ = ["LineBending", "element_bending_stiffness", "flexible_warm_start",
           "hinge_stiffness"]


def flexible_warm_start(statics: Scene) -> StaticsSolution | None:
    """The EI statics of a line warm-started from the same line without bending stiffness
    (its solution starts the EI solve's Newton: a towed line with a free tail at end_a,
    whose flexible statics converge from the default guess where the EI statics' own
    continuation does not). None when the line has no EI or the flexible solve fails.

    Parameters
    ----------
    statics : Scene
        The statics scene of the initial state.
    """
    from cable_ocp.statics.solver import solve  # heavy import, only when needed

    if not any(c.bending_stiffness > 0.0 for c in statics.lines) or not statics.segments:
        return None
    flex = replace(statics, cable=replace(statics.cable, bending_stiffness=0.0),
                   segments=tuple(replace(c, bending_stiffness=0.0)
                                  for c in statics.segments))
    start = solve(flex)
    if not start.success:
        return None
    sol = solve(statics, warm_start=start)
    sol.diagnostics["warm_start"] = "the same line without bending stiffness"
    return sol


def element_bending_stiffness(scene: DynamicScene, lengths: np.ndarray) -> np.ndarray:
    """EI of each element (N m^2): the segment holding the element's midpoint.

    Parameters
    ----------
    scene : DynamicScene
        The scene (``bending_stiffness`` of its statics segments).
    lengths : numpy.ndarray
        Unstretched element lengths from end_a, m.
    """
    lines = scene.statics.lines
    ends = np.cumsum([float(c.length) for c in lines])  # type: ignore[arg-type]
    mids = np.cumsum(lengths) - 0.5 * np.asarray(lengths)
    k = np.minimum(np.searchsorted(ends, mids), len(lines) - 1)
    return np.array([float(lines[i].bending_stiffness) for i in k])


def hinge_stiffness(ei_elements: np.ndarray) -> np.ndarray:
    """EI of each hinge (interior node) between elements, 2 EI_1 EI_2 / (EI_1 + EI_2),
    N m^2 (0 where either element is flexible).

    Parameters
    ----------
    ei_elements : numpy.ndarray
        EI of each element, N m^2.
    """
    a, b = ei_elements[:-1], ei_elements[1:]
    s = a + b
    return np.where(s > 0.0, 2.0 * a * b / np.where(s > 0.0, s, 1.0), 0.0)


class LineBending:
    """The hinges of one line of ``n`` elements (see the module docstring).

    Parameters
    ----------
    ei_elements : numpy.ndarray
        EI of each element from end_a, N m^2 (:func:`element_bending_stiffness`).
    lengths : numpy.ndarray
        Unstretched element lengths from end_a at t = 0, m (they scale with the length
        when it varies: :meth:`node_forces` takes the current ones).
    dim : int
        2 (the planar model's x, z rows) or 3.
    clamped : bool
        True for ``simulation.top_end = "clamped"``.

    Attributes
    ----------
    active : bool
        True when any hinge has EI > 0 (else every method returns zeros and the models
        build nothing).
    clamp_direction : numpy.ndarray
        The clamp's unit direction (dim), -; set by :meth:`set_clamp`.
    """

    def __init__(self, ei_elements: np.ndarray, lengths: np.ndarray, dim: int = 2,
                 clamped: bool = False) -> None:
        self.dim = dim
        self.lengths0 = np.asarray(lengths, dtype=float).reshape(-1)
        self.ei_elements = np.broadcast_to(np.asarray(ei_elements, dtype=float),
                                           self.lengths0.shape).copy()
        self.ei = hinge_stiffness(self.ei_elements)
        self.clamped = bool(clamped)
        self.ei_top = float(self.ei_elements[-1])
        self.active = bool(np.any(self.ei > 0.0) or (self.clamped and self.ei_top > 0.0))
        self.clamp_direction = np.eye(dim)[-1]

    @classmethod
    def from_scene(cls, scene: DynamicScene, lengths: np.ndarray, dim: int = 2
                   ) -> LineBending:
        """The hinges of a scene's line cut into elements of ``lengths`` (m).

        Parameters
        ----------
        scene : DynamicScene
            The scene: segments' ``bending_stiffness`` and ``simulation.top_end``.
        lengths : numpy.ndarray
            Unstretched element lengths from end_a, m.
        dim : int
            2 or 3.
        """
        return cls(element_bending_stiffness(scene, np.asarray(lengths, dtype=float)),
                   lengths, dim, scene.simulation.top_end == "clamped")

    def node_list_forces(self, r: list[Any]) -> list[Any]:
        """:meth:`node_forces` on a list of node positions (3-vectors, m): a list of
        node forces (N), at a fixed length (the lumped-mass model).

        Parameters
        ----------
        r : list of casadi expression
            Node positions from end_a, m.
        """
        if not self.active:
            return [0.0 * ri for ri in r]
        dd = ca.horzcat(*[r[j + 1] - r[j] for j in range(len(r) - 1)])
        f = self.node_forces(dd)
        return [f[:, i] for i in range(len(r))]

    def node_list_energy(self, r: list[Any]) -> Any:
        """:meth:`energy` on a list of node positions (m), J.

        Parameters
        ----------
        r : list of casadi expression
            Node positions from end_a, m.
        """
        if not self.active:
            return 0.0
        return self.energy(ca.horzcat(*[r[j + 1] - r[j] for j in range(len(r) - 1)]))

    def set_clamp(self, top_element: np.ndarray) -> None:
        """Hold the clamp along ``top_element`` (the top element's vector at t = 0, m).

        Parameters
        ----------
        top_element : numpy.ndarray
            Vector from node N-1 to node N (dim), m; a zero vector keeps the vertical.
        """
        v = np.asarray(top_element, dtype=float).reshape(-1)
        norm = float(np.linalg.norm(v))
        if norm > 0.0:
            self.clamp_direction = v / norm

    def _scaled(self, scale: Any) -> tuple[Any, Any, Any]:
        h = ca.DM(self.lengths0).T * scale
        return h[:, :-1], h[:, 1:], h[:, -1]

    def node_forces(self, dd: Any, scale: Any = 1.0) -> Any:
        """Hinge forces on every node (dim x (N+1), N) for the element vectors ``dd``
        (dim x N, m) and the element lengths ``lengths * scale``.

        Parameters
        ----------
        dd : casadi SX, MX or DM (dim x N)
            Element vectors r_{j+1} - r_j, m.
        scale : float or casadi expression
            L(t) / L(0), - (1 at a fixed length).
        """
        n = dd.shape[1]
        dim = self.dim
        kind = ca.SX if isinstance(dd, ca.SX) else ca.MX if isinstance(dd, ca.MX) else ca.DM
        out = kind.zeros(dim, n + 1)
        if not self.active:
            return out
        hp, hn, htop = self._scaled(scale)
        if n >= 2:
            fa, fb, fc = hinge_forces(dd[:, :-1], dd[:, 1:], ca.DM(self.ei).T, hp, hn)
            z1 = ca.DM.zeros(dim, 1)
            z2 = ca.DM.zeros(dim, 2)
            out = (out + ca.horzcat(fa, z2) + ca.horzcat(z1, fb, z1) + ca.horzcat(z2, fc))
        if self.clamped and self.ei_top > 0.0:
            # the far node of the clamp hinge is N-1: the element vector from N to N-1
            f = clamp_force(-dd[:, n - 1], ca.DM(self.clamp_direction), self.ei_top, htop)
            out = out + ca.horzcat(ca.DM.zeros(dim, n - 1), f, -f)
        return out

    def energy(self, dd: Any, scale: Any = 1.0) -> Any:
        """Bending energy of the line (J) for element vectors ``dd`` (dim x N, m).

        Parameters
        ----------
        dd : casadi expression or numpy.ndarray (dim x N)
            Element vectors, m.
        scale : float
            L(t) / L(0), -.
        """
        is_ca = isinstance(dd, (ca.SX, ca.MX))
        dd = dd if is_ca else np.asarray(dd, dtype=float)
        h = self.lengths0 * scale
        e: Any = 0.0
        if dd.shape[1] >= 2:
            eh = hinge_energy(dd[:, :-1], dd[:, 1:], self.ei, h[:-1], h[1:])
            e = ca.sum2(eh) if is_ca else float(np.sum(eh))
        if self.clamped and self.ei_top > 0.0:
            top = dd[:, dd.shape[1] - 1] if is_ca else dd[:, -1:]
            ec = clamp_energy(top, self.clamp_direction, self.ei_top, h[-1])
            e = e + (ec if is_ca else float(np.sum(ec)))
        return e

    def moments(self, dd: Any, scale: Any = 1.0) -> Any:
        """Bending moment at the interior nodes 1..N-1 (1 x (N-1), N m).

        Parameters
        ----------
        dd : casadi expression (dim x N)
            Element vectors, m.
        scale : float or casadi expression
            L(t) / L(0), -.
        """
        hp, hn, _ = self._scaled(scale)
        return hinge_moment(dd[:, :-1], dd[:, 1:], ca.DM(self.ei).T, hp, hn)

    def free_blocks(self, first: int, count: int) -> tuple[np.ndarray, np.ndarray, Any]:
        """:meth:`stiffness` on the free nodes ``first .. first + count - 1`` split for a
        block-tridiagonal Newton matrix: the diagonal 3x3 blocks and the blocks (a, a + 1)
        as row-major columns (9 x count, 9 x (count - 1)), and the rest (the blocks two
        nodes apart) as a sparse matrix (dim count square), N/m.

        Parameters
        ----------
        first : int
            The first free node.
        count : int
            Number of free nodes.
        """
        d = self.dim
        k = self.stiffness()[d * first:d * (first + count), d * first:d * (first + count)]
        diag = np.stack([k[d * a:d * a + d, d * a:d * a + d].reshape(-1)
                         for a in range(count)], axis=1)
        off = np.zeros((d * d, max(count - 1, 0)))
        for a in range(count - 1):
            off[:, a] = k[d * a:d * a + d, d * (a + 1):d * (a + 1) + d].reshape(-1)
        rest = k.copy()
        for a in range(count):
            for b in range(max(0, a - 1), min(count, a + 2)):
                rest[d * a:d * a + d, d * b:d * b + d] = 0.0
        return diag, off, ca.sparsify(ca.DM(rest))

    def stiffness(self) -> np.ndarray:
        """-d(forces)/d(positions) at a fixed length: the constant bending stiffness matrix
        of all nodes (dim (N+1) square, node-major, N/m)."""
        n = self.lengths0.size
        r = ca.SX.sym("r", self.dim * (n + 1))
        rr = ca.reshape(r, self.dim, n + 1)
        f = ca.vec(self.node_forces(rr[:, 1:] - rr[:, :-1]))
        return -np.asarray(ca.evalf(ca.jacobian(f, r)))
